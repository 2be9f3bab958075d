// A wall contact of a string node that moves both axially (speed v) and in rotation (speed w, outer radius r):
// the friction force acts against the resultant sliding velocity q = (v, r w) (paper 000's friction vector:
// why rotation cuts axial drag, axial drag = F v / |q|). The law sees the sliding speed s = |q| >= 0 and gives
// the magnitude F; the force is F q / s, and at s = 0 it points along the force needed to hold the node.
//   set-valued law (Coulomb, Stribeck): modes stick, slow slip and slip. The force needed to hold the node is
//     f_hold = (P, S / r), P and S the node's axial force and torque from everything else evaluated with the node
//     itself at rest (the rig removes the node's own damping share): what stick would carry after the projection
//     below, so the test before it and the guard after it read the same quantity.
//     stick: held while |f_hold| <= F_s (guard F_s - |f_hold|, falling -> slow slip, from rest).
//     slip -> stick: |q| touches zero without changing sign (a V, not a crossing), which no root finder sees,
//     so the contact is caught at a small stick speed s_stick (guard s - s_stick, falling). There, if
//     |f_hold| <= F_s the node sticks and both components are projected to zero (the kinetic energy
//     J w^2 / 2 + m v^2 / 2 removed is handed back as dissipated); else it goes on in slow slip.
//     slow slip: below s_stick with the dynamics of slip (the force F(s) against q; the mode only changes the
//     switching functions). It ends when s rises past s_stick (guard s_stick - s -> slip), or is caught to stick
//     (projected as above) once the node both could hold, |f_hold| <= F_s, and is slowing down, q . dq/dt <= 0:
//     guard max((|f_hold| - F_s) / F_s, q . dq/dt m / (s_stick F_s)), falling. A node that cannot hold passes
//     near q = 0 and turns towards f_hold (Leine's switch model in 1D: a contact that cannot hold at v_r = 0
//     slides on), as before it was caught. Without this mode the slip guard, left at zero heading below, fired
//     again at once (ChatteringError). Neither condition alone does: capturing as soon as f_hold re-enters the
//     disc stopped a node just broken away, which its springs loaded past F_s again at once; capturing at the
//     minimum of s alone is decided by rounding in steady creep below s_stick. A contact with F_s = 0 (no normal
//     force) never holds and stays in slow slip or slip.
//   state law (Dahl, LuGre, GMS): one mode; z evolves with the sliding speed s, the force acts against q. This
//     reading is exact for sliding that keeps its direction; a reversal of q through zero does not unload the
//     bristles as the 1D law would (the 1D law is used in torsion-only runs).
#pragma once

#include <algorithm>
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

/// The loads on a node from everything but its wall contact: torque S [N m] and axial force P [N], as they are and
/// with the node itself at rest (what holding it takes).
struct PlanarLoads {
    double torque = 0.0, axial = 0.0, hold_torque = 0.0, hold_axial = 0.0;
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
    static constexpr std::size_t guard_count = set_valued ? 2 : 0;
    /// Planar modes: stick (0), slow slip (1: below the stick speed) and slip (2; 2D slip has no sign).
    static constexpr int stick_mode = 0, slow_slip_mode = 1, slip_mode = 2;

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

    /// Switching functions, each falling through zero to fire (unused slots hold 1); `loads`: the node's loads,
    /// current and at rest (f_hold above). Stick: F_s - |f_hold|. Slip: s - s_stick. Slow slip: s_stick - s and
    /// the capture max((|f_hold| - F_s) / F_s, q . dq/dt m / (s_stick F_s)).
    void guards(double w, double v, const PlanarLoads& loads, const double* z, int mode, double inertia, double mass,
                double* g) const {
        if constexpr (set_valued) {
            const double limit = law_.static_limit(normal_force_), s = std::hypot(v, radius_ * w);
            g[1] = 1.0;
            if (mode == stick_mode) {
                g[0] = limit - hold_force(loads);
            } else if (mode == slip_mode) {
                g[0] = s - stick_speed_;
            } else {
                g[0] = stick_speed_ - s;
                if (limit > 0.0) {
                    const PlanarResponse r = respond(w, v, loads.torque, loads.axial, z, mode, inertia, mass);
                    const double speed_rate = v * r.axial_acceleration + radius_ * w * radius_ * r.angular_acceleration;
                    g[1] = std::max((hold_force(loads) - limit) / limit, speed_rate * mass / (stick_speed_ * limit));
                }
            }
        } else {
            (void)w, (void)v, (void)loads, (void)z, (void)mode, (void)inertia, (void)mass, (void)g;
        }
    }
    static const char* guard_name(std::size_t k, int mode) {
        if (mode == stick_mode) return "static_limit";
        if (mode == slow_slip_mode) return k == 0 ? "slip_speed" : "held_slowing";
        return "stick_speed";
    }
    static const char* mode_name(int mode) {
        return mode == stick_mode ? "stick" : mode == slow_slip_mode ? "slow_slip" : "slip";
    }

    /// The mode consistent with a state.
    int initial_mode(double w, double v, const PlanarLoads& loads) const {
        if constexpr (set_valued) {
            const double s = std::hypot(v, radius_ * w);
            if (s == 0.0 && holds(loads)) return stick_mode;
            if (s < stick_speed_) return slow_slip_mode;
        } else {
            (void)w, (void)v, (void)loads;
        }
        return slip_mode;
    }

    /// New mode at a root (`fired`: this contact's guards). Entering stick projects (w, v) to zero and returns the
    /// kinetic energy removed in `dissipated` (the run's energy balance books it as friction work).
    int switch_mode(double& w, double& v, const PlanarLoads& loads, int mode, const int* fired, double inertia,
                    double mass, double& dissipated) const {
        dissipated = 0.0;
        if (mode == stick_mode) return slow_slip_mode;  // breaks away from rest
        if (mode == slow_slip_mode && fired[1] == 0) return slip_mode;  // sped up past s_stick
        if (!holds(loads)) return slow_slip_mode;  // caught at s_stick, cannot hold: slides on
        dissipated = 0.5 * (inertia * w * w + mass * v * v);
        w = v = 0.0;
        return stick_mode;
    }

private:
    double hold_force(const PlanarLoads& l) const { return std::hypot(l.hold_axial, l.hold_torque / radius_); }
    bool holds(const PlanarLoads& l) const {  // F_s = 0 holds nothing (only an exactly zero force, by rounding)
        if constexpr (set_valued) {
            const double limit = law_.static_limit(normal_force_);
            return limit > 0.0 && hold_force(l) <= limit;
        } else {
            return (void)l, false;  // a state law has no stick mode
        }
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
