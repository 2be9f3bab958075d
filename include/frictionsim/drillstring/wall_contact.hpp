// A wall contact of a string node that moves both axially (speed v) and in rotation (speed w, outer radius r):
// the friction force acts against the resultant sliding velocity q = (v, r w) (paper 000's friction vector:
// why rotation cuts axial drag, axial drag = F v / |q|). The law sees the sliding speed s = |q| >= 0 and gives
// the magnitude F; the force is F q / s, and at s = 0 it points along the force needed to hold the node.
//   set-valued law (Coulomb, Stribeck): modes slip and stick. Stick holds both components at zero while the
//     force needed to hold the node, f_hold = (P, S / r) (P, S: the node's axial force and torque from
//     everything else), stays inside the static disc |f_hold| <= F_s:   guard F_s - |f_hold| (falling) -> slip.
//     slip -> stick: |q| touches zero without changing sign (a V, not a crossing), which no root finder sees,
//     so the contact is caught at a small stick speed s_stick:   guard s - s_stick (falling); there, if
//     |f_hold| <= F_s the node sticks and both components are projected to zero (the kinetic energy
//     J w^2 / 2 + m v^2 / 2 <= m s_stick^2 / 2 + ... it had is handed back as dissipated), else it slides on.
//   state law (Dahl, LuGre, GMS): one mode; z evolves with the sliding speed s, the force acts against q. This
//     reading is exact for sliding that keeps its direction; a reversal of q through zero does not unload the
//     bristles as the 1D law would (the 1D law is used in torsion-only runs).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "../friction/law.hpp"

namespace frictionsim {

/// The node's accelerations and the friction on it: torque r f_t [N m] and axial force f_a [N].
struct PlanarResponse {
    double angular_acceleration = 0.0, axial_acceleration = 0.0, torque = 0.0, axial_force = 0.0;
};

/// d(f_a, f_t)/d(v, w, z) and d(dz/dt)/d(v, w, z) in slip (f_t: the circumferential force, torque = r f_t).
template <std::size_t Z>
struct PlanarPartials {
    double axial_v = 0.0, axial_w = 0.0, tangential_v = 0.0, tangential_w = 0.0;
    std::array<double, Z> axial_z{}, tangential_z{}, rate_v{}, rate_w{};
    std::array<std::array<double, Z>, Z> rate_z{};
};

template <class Law>
class PlanarWallContact {
    static_assert(check_friction_law<Law>(), "PlanarWallContact<Law>: Law must meet the FrictionLaw concept");

public:
    static constexpr std::size_t state_count = Law::state_count;
    static constexpr bool set_valued = Law::has_stick;
    static constexpr std::size_t guard_count = set_valued ? 1 : 0;
    /// Planar modes: stick (0) and slip (2; 2D slip has no sign).
    static constexpr int stick_mode = 0, slip_mode = 2;

    PlanarWallContact(Law law, double radius, double normal_force, double stick_speed)
        : law_(std::move(law)), radius_(radius), normal_force_(normal_force), stick_speed_(stick_speed) {}

    const Law& law() const { return law_; }
    double radius() const { return radius_; }
    double normal_force() const { return normal_force_; }

    PlanarResponse respond(double w, double v, double torque, double axial, const double* z, int mode, double inertia,
                           double mass) const {
        PlanarResponse r;
        if (set_valued && mode == stick_mode) {  // held: the friction is what holds, exactly
            r.torque = torque;
            r.axial_force = axial;
            return r;
        }
        double ea = 0.0, et = 0.0;
        const double s = direction(w, v, torque, axial, ea, et);
        const double f = magnitude(s, z);
        r.axial_force = f * ea;
        r.torque = radius_ * f * et;
        r.angular_acceleration = (torque - r.torque) / inertia;
        r.axial_acceleration = (axial - r.axial_force) / mass;
        return r;
    }

    void state_derivative(double w, double v, const double* z, int, double* dz) const {
        if constexpr (state_count > 0) law_.state_derivative(std::hypot(v, radius_ * w), normal_force_, z, +1, dz);
        else (void)w, (void)v, (void)z, (void)dz;
    }

    /// First derivatives in slip with q != 0 (zero in stick and at q = 0, where the direction is the held force's).
    PlanarPartials<state_count> partials(double w, double v, const double* z, int mode) const {
        PlanarPartials<state_count> d;
        const double s = std::hypot(v, radius_ * w);
        if ((set_valued && mode == stick_mode) || s == 0.0) return d;
        const double ea = v / s, et = radius_ * w / s;
        double f = 0.0, slope = 0.0;
        if constexpr (set_valued) {
            f = law_.slip_force(s, normal_force_, +1);
            if constexpr (law_has_partials_v<Law>) slope = law_.slip_slope(s, normal_force_, +1);
        } else {
            f = law_.force(s, normal_force_, z, +1);
            if constexpr (law_has_partials_v<Law>) {
                const StatePartials<state_count> p = law_.partials(s, normal_force_, z, +1);
                slope = p.force_velocity;
                for (std::size_t j = 0; j < state_count; ++j) {
                    d.axial_z[j] = p.force_state[j] * ea;
                    d.tangential_z[j] = p.force_state[j] * et;
                    d.rate_v[j] = p.rate_velocity[j] * ea;            // ds/dv = ea
                    d.rate_w[j] = p.rate_velocity[j] * et * radius_;  // ds/dw = r et
                    for (std::size_t k = 0; k < state_count; ++k) d.rate_z[j][k] = p.rate_state[j][k];
                }
            }
        }
        // d(f e)/dq = F' e e^T + (F / s)(I - e e^T), q = (v, r w)
        const double over = f / s;
        d.axial_v = slope * ea * ea + over * (1.0 - ea * ea);
        const double cross = (slope - over) * ea * et;
        d.axial_w = radius_ * cross;
        d.tangential_v = cross;
        d.tangential_w = radius_ * (slope * et * et + over * (1.0 - et * et));
        return d;
    }

    void guards(double w, double v, double torque, double axial, int mode, double* g) const {
        if constexpr (set_valued) {
            g[0] = mode == stick_mode ? law_.static_limit(normal_force_) - std::hypot(axial, torque / radius_)
                                      : std::hypot(v, radius_ * w) - stick_speed_;
        } else {
            (void)w, (void)v, (void)torque, (void)axial, (void)mode, (void)g;
        }
    }
    static const char* guard_name(int mode) { return mode == stick_mode ? "static_limit" : "stick_speed"; }
    static const char* mode_name(int mode) { return mode == stick_mode ? "stick" : "slip"; }

    int initial_mode(double w, double v, double torque, double axial) const {
        if constexpr (set_valued) {
            if (v == 0.0 && w == 0.0 && holds(torque, axial)) return stick_mode;
        } else {
            (void)w, (void)v, (void)torque, (void)axial;
        }
        return slip_mode;
    }

    /// New mode at a root. Entering stick projects (w, v) to zero and returns the kinetic energy removed in
    /// `dissipated` (the run's energy balance books it as friction work).
    int switch_mode(double& w, double& v, double torque, double axial, int mode, double inertia, double mass,
                    double& dissipated) const {
        dissipated = 0.0;
        if (mode == stick_mode) return slip_mode;
        if (!holds(torque, axial)) return slip_mode;
        dissipated = 0.5 * (inertia * w * w + mass * v * v);
        w = v = 0.0;
        return stick_mode;
    }

private:
    bool holds(double torque, double axial) const {
        if constexpr (set_valued) return std::hypot(axial, torque / radius_) <= law_.static_limit(normal_force_);
        else return (void)torque, (void)axial, false;  // a state law has no stick mode
    }
    /// Unit vector (ea, et) against which friction acts; returns s = |q|.
    double direction(double w, double v, double torque, double axial, double& ea, double& et) const {
        const double s = std::hypot(v, radius_ * w);
        if (s > 0.0) {
            ea = v / s;
            et = radius_ * w / s;
        } else {  // at rest in slip: the node starts to move along the force that drives it
            const double h = std::hypot(axial, torque / radius_);
            ea = h > 0.0 ? axial / h : 0.0;
            et = h > 0.0 ? torque / radius_ / h : 0.0;
        }
        return s;
    }
    double magnitude(double s, const double* z) const {
        if constexpr (set_valued) return law_.slip_force(s, normal_force_, +1);
        else return law_.force(s, normal_force_, z, +1);
    }

    Law law_;
    double radius_, normal_force_, stick_speed_;
};

}  // namespace frictionsim
