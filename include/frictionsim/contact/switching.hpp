// Modes, switching functions and mode resolution of one friction contact, for any rig. The rig supplies the
// relative velocity v_r, the normal force N and the stick force F_stick: the friction force that would keep
// the relative acceleration at zero, so that the relative acceleration has the sign of F_stick - F_friction.
//
//  set-valued law, exact stick (Leine's switch model):
//    slip s:  guard  s v_r  (falling)                     -> at zero: stick if |F_stick| <= F_s, else slip
//    stick:   guards F_s - F_stick, F_s + F_stick (falling) -> slip in the direction of F_stick
//  set-valued law with a Karnopp band dv (Karnopp 1985): the contact sticks once |v_r| falls to dv, at the
//  relative velocity it had (not projected to zero), and leaves as in exact stick:
//    slip s:  guard  s v_r - dv (falling)                 -> band (a stick mode)
//    band:    guards F_s - F_stick, F_s + F_stick (falling) -> slip in the direction of F_stick
//  state law with a kink at v_r = 0 (Dahl): branch s, guard s v_r (falling) -> branch -s
//  smooth state law (LuGre): one mode, no guard.
// Every guard falls through zero to fire, so each has a direction and no crossing is seen twice.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "../friction/law.hpp"

namespace frictionsim {

template <class Law>
struct ContactSwitching {
    static_assert(check_friction_law<Law>(), "ContactSwitching<Law>: Law must meet the FrictionLaw concept (see above)");
    static constexpr bool set_valued = Law::has_stick;
    static constexpr std::size_t guard_count = [] {
        if constexpr (Law::has_stick) return std::size_t{2};
        else return std::size_t{Law::kink_at_zero_velocity ? 1 : 0};
    }();

    /// Friction force in `mode`; z is the law's internal state (unused for set-valued laws).
    static double force(const Law& law, double v_r, double normal_force, const double* z, int mode,
                        double stick_force) {
        if constexpr (set_valued) {
            if (mode != stick) return law.slip_force(v_r, normal_force, mode);
            const double limit = law.static_limit(normal_force);
            return std::clamp(stick_force, -limit, limit);  // exact stick: |F_stick| <= limit holds in stick
        } else {
            return law.force(v_r, normal_force, z, mode);
        }
    }

    /// The friction force's first derivatives in `mode` (analytic Jacobians): dF/dv_r and, for state laws, the
    /// law's partials; `force_stick_slope` is dF/dF_stick (1 while stick holds inside the static limit, else 0).
    static StatePartials<Law::state_count> partials(const Law& law, double v_r, double normal_force, const double* z,
                                                    int mode, double stick_force, double& force_stick_slope) {
        force_stick_slope = 0.0;
        if constexpr (set_valued) {
            (void)z;
            StatePartials<0> p;
            if (mode != stick) p.force_velocity = law.slip_slope(v_r, normal_force, mode);
            else if (std::abs(stick_force) < law.static_limit(normal_force)) force_stick_slope = 1.0;
            return p;
        } else {
            (void)stick_force;
            return law.partials(v_r, normal_force, z, mode);
        }
    }

    static void guards(const Law& law, double v_r, double normal_force, int mode, double stick_force, double* g) {
        if constexpr (set_valued) {
            if (mode == stick) {
                const double limit = law.static_limit(normal_force);
                g[0] = limit - stick_force;
                g[1] = limit + stick_force;
            } else {
                g[0] = mode * v_r - law.karnopp_band();
                g[1] = 1.0;  // unused in slip
            }
        } else if constexpr (guard_count == 1) {
            g[0] = mode * v_r;
        }
    }

    static int guard_direction(std::size_t, int) { return -1; }

    static const char* guard_name(const Law& law, std::size_t i, int mode) {
        if constexpr (set_valued) {
            if (mode != stick) return law.karnopp_band() > 0.0 ? "karnopp_band_entry" : "relative_velocity";
            return i == 0 ? "static_limit_positive" : "static_limit_negative";
        } else {
            return "relative_velocity";
        }
    }

    static const char* mode_name(const Law& law, int mode) {
        if constexpr (set_valued) {
            if (mode == stick && law.karnopp_band() > 0.0) return "karnopp_band";
            return contact_mode_name(mode);
        } else if constexpr (guard_count == 1) {
            return contact_mode_name(mode);
        } else {
            return "smooth";
        }
    }

    /// Mode consistent with the state: used at the start of a run.
    static int initial_mode(const Law& law, double v_r, double normal_force, const double* z, double stick_force) {
        if constexpr (set_valued) {
            if (std::abs(v_r) > law.karnopp_band()) return sign_of(v_r);
            if (std::abs(stick_force) <= law.static_limit(normal_force)) return stick;
            return v_r != 0.0 ? sign_of(v_r) : sign_of(stick_force);
        } else if constexpr (guard_count == 1) {
            if (v_r != 0.0) return sign_of(v_r);
            const int s = sign_of(stick_force - law.force(0.0, normal_force, z, +1));
            return s != 0 ? s : int{slip_positive};
        } else {
            return 0;
        }
    }

    /// New mode at a root; `stop_relative_motion` is set when the rig must project v_r to exactly zero.
    static int switch_mode(const Law& law, double normal_force, int mode, const int* fired, double stick_force,
                           bool& stop_relative_motion) {
        stop_relative_motion = false;
        if constexpr (set_valued) {
            if (mode == stick) return fired[0] != 0 ? int{slip_positive} : int{slip_negative};
            const bool holds = std::abs(stick_force) <= law.static_limit(normal_force);
            if (law.karnopp_band() > 0.0) return holds ? int{stick} : sign_of(stick_force);  // held at this v_r
            stop_relative_motion = true;  // v_r reached zero: stick, or reverse through zero
            return holds ? int{stick} : sign_of(stick_force);
        } else {
            (void)law, (void)normal_force, (void)fired, (void)stick_force;
            return -mode;
        }
    }
};

}  // namespace frictionsim
