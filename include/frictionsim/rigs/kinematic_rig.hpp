// A kinematic rig: a friction law driven by a prescribed relative velocity v_r(t) and normal force N(t), as
// identification from measured signals needs. There is no mass: set-valued laws give their slip force on the
// branch sgn(v_r), and zero crossings of v_r are located as events (the force jumps there). A Karnopp band
// needs the force that would stick, which a kinematic rig does not have: such laws are rejected. States: the
// law's states, friction impulse int F dt and friction work int F v_r dt (energy dissipated plus what the law
// stores).
//
// Rest: where the prescribed v_r stays at exactly zero (a standstill in measured data) the contact sticks. It
// holds the force it carried on arriving, the rate-independent (Coulomb) limit of a bristle law: a set-valued
// law keeps its slip force at v_r = 0 on the branch it arrived on (+mu N after sliding forwards), a state law
// the force its state gives (dz/dt = 0 at v_r = 0). Modes: +-1 slip (the branch sgn v_r), +-2 stick holding
// branch +-1's force, 0 stick from the start of the run (a set-valued law then holds no force). In stick the
// guard fires when |v_r| exceeds the smallest normal double, so no guard sits at zero through a standstill: one
// that did would fire again at every step of it (chattering).
//
// Paper 001's hysteretic torque (eq 6) is no FrictionLaw (it depends on the acceleration dw/dt): it has its own
// partial specialization, KinematicRig<HystereticFriction, V, N> in kinematic_hysteretic.hpp (included at the end
// of this header), which takes dw/dt from the signal's derivative(t).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <limits>
#include <stdexcept>
#include <utility>

#include "../detail/validate.hpp"
#include "../solve/hybrid_system.hpp"
#include "../contact/switching.hpp"
#include "../outputs.hpp"
#include "signals.hpp"

namespace frictionsim {

/// The kinematic rig's Result columns beside t and the law's states (state_names below). It has no parameter
/// table (its inputs are signals), so its outputs stand here, first in the header.
constexpr std::array<RigOutput, 3> kinematic_rig_outputs() {
    return {{
        {"friction_force", "N", "friction force F under the prescribed v_r(t), N(t)"},
        {"friction_impulse", "N s", "int F dt"},
        {"friction_work", "J", "int F v_r dt: dissipated plus stored in the law"},
    }};
}

template <class Law, class RelativeVelocity, class NormalForce = ConstantSignal>
class KinematicRig {
    static_assert(check_friction_law<Law>(), "KinematicRig<Law>: Law must meet the FrictionLaw concept (see above)");

    static constexpr std::size_t Z = Law::state_count;
    static constexpr bool branches = Law::has_stick || ContactSwitching<Law>::guard_count == 1;

public:
    static constexpr std::size_t state_size = Z + 2;
    static constexpr bool stiff = declares_stiff<Law>::value;  ///< picks the integrator under Method::automatic
    static constexpr std::size_t guard_count = branches ? 1 : 0;
    static constexpr std::size_t law_state = 0, friction_impulse = Z, friction_work = Z + 1;
    /// Mode of a standstill that holds slip branch s's force (s = +-1); 0 is a standstill from the run's start.
    static constexpr int rest_holding(int s) { return 2 * s; }

    KinematicRig(Law law, RelativeVelocity relative_velocity, NormalForce normal_force,
                 std::array<double, Z> initial_law_state = {})
        : law_(std::move(law)), v_r_(std::move(relative_velocity)), normal_(std::move(normal_force)),
          z0_(initial_law_state) {
        if constexpr (Law::has_stick)
            if (law_.karnopp_band() > 0.0)
                detail::reject("KinematicRig", "karnopp_band",
                               "zero: a Karnopp band needs the force that would stick, which a kinematic rig lacks",
                               law_.karnopp_band());
        for (double z : z0_) detail::require_finite("KinematicRig", "initial_law_state", z);
    }

    const Law& law() const { return law_; }
    double relative_velocity(double t) const { return v_r_(t); }

    double friction_force(double t, const double* x, int mode) const {
        return force(v_r_(t), normal_force(t), x, mode);
    }

    void rhs(double t, const double* x, int mode, double* dxdt) const { rhs_guards(t, x, mode, dxdt, nullptr); }

    /// The right-hand side and, into g unless null, the switching function: one evaluation of the prescribed
    /// signals for both (they may be Python callables).
    void rhs_guards(double t, const double* x, int mode, double* dxdt, double* g) const {
        const double v = v_r_(t), n = normal_force(t);
        if constexpr (branches) {
            if (g != nullptr) g[0] = guard(v, mode);
        }
        const double f = force(v, n, x, mode);
        if constexpr (Z > 0) law_.state_derivative(v, n, x + law_state, branch_of(mode), dxdt + law_state);
        dxdt[friction_impulse] = f;
        dxdt[friction_work] = f * v;
    }

    /// Analytic Jacobian, column-major: only the law's states are free (v_r and N are imposed).
    /// Only for laws with analytic partials (law_has_partials_v); CVODE builds the rest from difference quotients.
    template <class L = Law, std::enable_if_t<law_has_partials_v<L>, int> = 0>
    void jacobian(double t, const double* x, int mode, double* J) const {
        if constexpr (Z > 0) {
            constexpr std::size_t n = state_size;
            const double v = v_r_(t);
            const StatePartials<Z> d = law_.partials(v, normal_force(t), x + law_state, branch_of(mode));
            for (std::size_t j = 0; j < Z; ++j) {
                J[(law_state + j) * n + friction_impulse] = d.force_state[j];
                J[(law_state + j) * n + friction_work] = v * d.force_state[j];
                for (std::size_t i = 0; i < Z; ++i) J[(law_state + j) * n + law_state + i] = d.rate_state[i][j];
            }
        } else {
            (void)t, (void)x, (void)mode, (void)J;
        }
    }

    void guards(double t, const double* /*x*/, int mode, double* g) const {
        if constexpr (branches) g[0] = guard(v_r_(t), mode);
    }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t, int) const { return "relative_velocity"; }
    const char* mode_name(int mode) const {
        if constexpr (!branches) return "smooth";
        return is_slip(mode) ? contact_mode_name(mode) : "stick";
    }

    int initial_mode(double t, const double* /*x*/) const {
        if constexpr (!branches) return 0;
        const double v = v_r_(t);
        return v != 0.0 ? sign_of(v) : heading(t, 0);  // starting at rest: the side v_r heads to, or stick
    }

    /// At a zero of v_r in slip s: where v_r heads next decides, reversal (-s), standstill (stick holding s) or
    /// a touch (s again). Leaving stick, |v_r| > 0 at the root: its sign.
    int switch_mode(double t, double* x, int mode, const int*) const {
        const int next = next_mode(t, mode);
        if constexpr (Z > 0) note_reversal(law_, normal_force(t), x + law_state, branch_of(mode), branch_of(next));
        else (void)x;
        return next;
    }

    std::array<double, state_size> initial_state() const {
        std::array<double, state_size> x{};
        for (std::size_t i = 0; i < Z; ++i) x[law_state + i] = z0_[i];
        return x;
    }
    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        if constexpr (Z > 0)
            for (std::size_t i = 0; i < Z; ++i) n[law_state + i] = Law::state_names[i];
        n[friction_impulse] = "friction_impulse";
        n[friction_work] = "friction_work";
        return n;
    }

private:
    double normal_force(double t) const {
        const double n = normal_(t);
        if (!(std::isfinite(n) && n > 0.0))
            detail::reject("KinematicRig", "normal_force", "positive and finite at every time", n);
        return n;
    }
    int next_mode(double t, int mode) const {
        const double v = v_r_(t);
        if (!is_slip(mode)) return sign_of(v);
        if (mode * v < 0.0) return -mode;  // already across: the look-ahead could jump a dip narrower than it
        return heading(t, rest_holding(mode));
    }
    static bool is_slip(int mode) { return mode == slip_positive || mode == slip_negative; }
    /// The law's branch in `mode`: the slip direction, the one a stick holds, +1 for a stick from the start (where
    /// v_r = 0 the branch of a state law changes nothing).
    static int branch_of(int mode) { return mode < 0 ? -1 : 1; }

    /// Slip s: s v_r, falling through zero at a reversal or standstill. Stick: DBL_MIN - |v_r|, falling as
    /// soon as v_r leaves zero and never zero while it stays there.
    static double guard(double v, int mode) {
        return is_slip(mode) ? mode * v : std::numeric_limits<double>::min() - std::abs(v);
    }

    /// The mode v_r heads into just after t (the signal is known ahead): its sign, or `at_rest` if it stays 0.
    int heading(double t, int at_rest) const {
        const double dt = 1e-9 * std::max(1.0, std::abs(t));
        try {
            const int s = sign_of(v_r_(t + dt));
            return s != 0 ? s : at_rest;
        } catch (const std::out_of_range&) {  // sampled data ending within dt: nothing follows to head into
            return at_rest;
        }
    }

    double force(double v, double n, const double* x, int mode) const {
        if constexpr (Law::has_stick) {
            (void)x;
            if (mode == stick) return 0.0;  // at rest from the start: no force held
            return law_.slip_force(v, n, branch_of(mode));
        } else {
            return law_.force(v, n, x + law_state, branch_of(mode));
        }
    }

    Law law_;
    RelativeVelocity v_r_;
    NormalForce normal_;
    std::array<double, Z> z0_;
};

}  // namespace frictionsim

#include "kinematic_hysteretic.hpp"  // KinematicRig<HystereticFriction, V, N>
