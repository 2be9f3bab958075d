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
//   state law that remembers reversals (Leuven, law_remembers_reversals_v): the turning points only mean something
//     against an axis, so the contact carries one: the reference direction d = b a, a = (cos phi, sin phi) in the
//     (axial, circumferential) plane, phi a state after the law's, b = +-1 the mode (slip_positive / negative).
//     The law is the 1D law of the motion projected on a: it sees u = q . a on branch b, and its force F acts
//     along a (f_a = F cos phi, r f_t = r F sin phi), so the friction power is F u, the 1D law's.
//     The reversal (the ruling): q . d falling through zero (guard b u, "sliding_reversal"), i.e. the sliding
//     direction turned by more than 90 degrees from the reference direction; there on_reversal(z, b, -b) and
//     b -> -b, so d flips and a, u and the force are continuous through the event (as the 1D law's at v = 0).
//     Between reversals d follows the sliding direction over the law's presliding length l = presliding_length(N)
//     (Leuven: F_s / k): d phi/dt = (d x q) / l, i.e. |q| sin(angle from d to q) / l.
//     Why: the memory is the asperity junctions' elastic (presliding) deflection, which lies along the direction
//     they were loaded in. Gross sliding that turns slowly (a path much longer than l per radian) renews the
//     junctions along the new direction, so d keeps up, nothing unloads and no turning point is pushed; a turn past
//     90 degrees within a presliding length unloads the junctions as a 1D reversal does. A direction frozen at the
//     last reversal instead counts spurious reversals in steady sliding on a curve and loses the friction on the
//     component of motion across its axis.
//     It is exactly the 1D law when q stays on one axis: phi = 0 (axial; pi / 2 torsional, to cos(pi / 2) ~ 6e-17)
//     gives d x q = 0, u = v (r w), guard b v, the 1D kink at v = 0. A rotating string under axial vibration
//     (paper 000's case, r w > max |v|, a path per cycle >> l): q . d ~ |q| > 0, so no reversal is counted and d
//     lags q by ~ l times the rate q turns per unit path: u ~ |q|, F ~ S(|q|) against q, paper 000's friction
//     vector. The junctions are in gross sliding throughout, never back in presliding: no turning point to
//     remember, which is the right physics. At F_N = 0 (l = 0) phi is frozen (the law's force is zero anyway).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "../friction/law.hpp"

namespace frictionsim {

namespace detail {
template <class L> using presliding_length_t = decltype(double{std::declval<const L&>().presliding_length(0.0)});
}  // namespace detail

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
    static constexpr std::size_t state_count = Law::state_count;  ///< the law's; z[state_count] is the axis phi
    static constexpr bool set_valued = Law::has_stick;
    /// A law with a memory of reversals: the contact adds its reference axis phi [rad] after the law's states.
    static constexpr bool remembers = law_remembers_reversals_v<Law>;
    static constexpr std::size_t axis_states = remembers ? 1 : 0;
    static constexpr std::size_t guard_count = set_valued ? 2 : remembers ? 1 : 0;
    /// Planar modes: stick (0), slow slip (1: below the stick speed) and slip (2; 2D slip has no sign). A law that
    /// remembers reversals: the branch b along the reference axis, slip_negative (-1) or slip_positive (+1).
    static constexpr int stick_mode = 0, slow_slip_mode = 1, slip_mode = 2;

    PlanarWallContact(Law law, double radius, double normal_force, double stick_speed)
        : law_(std::move(law)), radius_(radius), normal_force_(normal_force), stick_speed_(stick_speed) {
        if constexpr (remembers) {
            static_assert(detail::detected<Law, detail::presliding_length_t>::value,
                          "PlanarWallContact: a law with on_reversal needs `double presliding_length(double "
                          "normal_force) const` (the length over which the reference axis follows the sliding)");
            length_ = law_.presliding_length(normal_force_);
        }
    }

    const Law& law() const { return law_; }
    double radius() const { return radius_; }
    double normal_force() const { return normal_force_; }

    PlanarResponse respond(double w, double v, double torque, double axial, const double* z, int mode, double inertia,
                           double mass) const {
        PlanarResponse r;
        if constexpr (remembers) {  // the 1D law along the axis a
            const Axis a = axis(z);
            const double f = law_.force(v * a.c + radius_ * w * a.s, normal_force_, z, branch(mode));
            r.axial_force = f * a.c;
            r.torque = radius_ * f * a.s;
            r.angular_acceleration = (torque - r.torque) / inertia;
            r.axial_acceleration = (axial - r.axial_force) / mass;
            return r;
        }
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

    void state_derivative(double w, double v, const double* z, int mode, double* dz) const {
        if constexpr (remembers) {
            const Axis a = axis(z);
            const double qt = radius_ * w, b = branch(mode);
            law_.state_derivative(v * a.c + qt * a.s, normal_force_, z, branch(mode), dz);
            dz[state_count] = length_ > 0.0 ? b * (a.c * qt - a.s * v) / length_ : 0.0;  // d x q / l
        } else if constexpr (state_count > 0) {
            (void)mode;
            law_.state_derivative(std::hypot(v, radius_ * w), normal_force_, z, +1, dz);
        } else {
            (void)w, (void)v, (void)z, (void)mode, (void)dz;
        }
    }

    /// First derivatives in slip with q != 0 (zero in stick and at q = 0, where the direction is the held force's).
    PlanarPartials<state_count> partials(double w, double v, const double* z, int mode) const {
        static_assert(!remembers, "PlanarWallContact::partials: the reference axis's partials are not written for "
                                  "a law with on_reversal (the rig builds its Jacobian from difference quotients)");
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
    /// the capture max((|f_hold| - F_s) / F_s, q . dq/dt m / (s_stick F_s)). A law that remembers reversals: b q . a.
    void guards(double w, double v, const PlanarLoads& loads, const double* z, int mode, double inertia, double mass,
                double* g) const {
        if constexpr (remembers) {
            (void)loads, (void)inertia, (void)mass;
            const Axis a = axis(z);
            g[0] = branch(mode) * (v * a.c + radius_ * w * a.s);
        } else if constexpr (set_valued) {
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
        if constexpr (remembers) return (void)k, (void)mode, "sliding_reversal";
        if (mode == stick_mode) return "static_limit";
        if (mode == slow_slip_mode) return k == 0 ? "slip_speed" : "held_slowing";
        return "stick_speed";
    }
    static const char* mode_name(int mode) {
        if constexpr (remembers) return contact_mode_name(mode);
        return mode == stick_mode ? "stick" : mode == slow_slip_mode ? "slow_slip" : "slip";
    }

    /// The mode consistent with a state (z: the law's states and the axis; read only by a law remembering reversals:
    /// the sign of q . a, at q . a = 0 the side the held force heads to, as ContactSwitching's).
    int initial_mode(double w, double v, const PlanarLoads& loads, const double* z = nullptr) const {
        if constexpr (remembers) {
            const Axis a = axis(z);
            const double u = v * a.c + radius_ * w * a.s;
            if (u != 0.0) return u > 0.0 ? int{slip_positive} : int{slip_negative};
            const double held = loads.hold_axial * a.c + loads.hold_torque / radius_ * a.s;
            return held - law_.force(0.0, normal_force_, z, +1) < 0.0 ? int{slip_negative} : int{slip_positive};
        } else if constexpr (set_valued) {
            const double s = std::hypot(v, radius_ * w);
            if (s == 0.0 && holds(loads)) return stick_mode;
            if (s < stick_speed_) return slow_slip_mode;
        } else {
            (void)w, (void)v, (void)loads;
        }
        return slip_mode;
    }

    /// New mode at a root (`fired`: this contact's guards). Entering stick projects (w, v) to zero and returns the
    /// kinetic energy removed in `dissipated` (the run's energy balance books it as friction work). A law that
    /// remembers reversals: at its reversal the branch flips and the law updates its memory in z (note_reversal).
    int switch_mode(double& w, double& v, const PlanarLoads& loads, double* z, int mode, const int* fired,
                    double inertia, double mass, double& dissipated) const {
        dissipated = 0.0;
        if constexpr (remembers) {
            (void)fired;
            const int b = branch(mode);
            note_reversal(law_, normal_force_, z, b, -b);
            return -b;
        } else {
            (void)z;
        }
        if (mode == stick_mode) return slow_slip_mode;  // breaks away from rest
        if (mode == slow_slip_mode && fired[1] == 0) return slip_mode;  // sped up past s_stick
        if (!holds(loads)) return slow_slip_mode;  // caught at s_stick, cannot hold: slides on
        dissipated = 0.5 * (inertia * w * w + mass * v * v);
        w = v = 0.0;
        return stick_mode;
    }

private:
    struct Axis {
        double c, s;  ///< cos phi, sin phi
    };
    static Axis axis(const double* z) { return {std::cos(z[state_count]), std::sin(z[state_count])}; }
    static int branch(int mode) { return mode < 0 ? -1 : 1; }

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
    double length_ = 0.0;  ///< the presliding length l (a law remembering reversals)
};

}  // namespace frictionsim
