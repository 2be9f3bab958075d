// The kinematic rig for paper 001's hysteretic friction torque (eq 6, friction/hysteretic.hpp): the law driven by
// a prescribed disc speed w(t) = v_r(t) (rad/s) and normal force N(t), as identification and plotting need.
//
// Eq 6 depends on the acceleration dw/dt, which on a disc is unknown until the branch equation is solved
// (DiscContact<HystereticFriction>). Here the speed is prescribed, so the acceleration is known too: the
// signal's derivative, `double derivative(double t) const` (signals.hpp: ConstantSignal 0, HarmonicSlidingVelocity
// analytic, SampledSignal the slope of the segment ahead). A signal type without it is refused at compile time
// (static_assert: "... the relative-velocity signal needs a member `double derivative(double t) const` ...").
// The torque is then explicit, eq 6's branch value at (w, dw/dt, N) (HystereticFriction::stick_torque or
// slip_torque), in the case HystereticFriction::torque picks, with s = sgn w and k = N / N_ref:
//   stick            |w| <= w_s                    T = k a w
//   accelerating s   |w| >  w_s,  s dw/dt >  0     T = s k p(s w, s dw/dt)    (p00 ... p02)
//   decelerating s   |w| >  w_s,  s dw/dt <= 0     T = s k n(s w, s dw/dt)    (n00 ... n02)
// (dw/dt = 0 counts as decelerating; w < 0 is eq 6's odd extension). Modes are numbered and named as the disc's:
// stick 0, accelerating +-1, decelerating +-2; no hold modes (with dw/dt prescribed, eq 6's gap at dw/dt = 0 does
// not arise). The switches are located events, so the recorded torque has exact jumps; guards, falling through 0:
//   stick:  w_s - w ("stick_band_upper_edge"), w_s + w ("stick_band_lower_edge")
//   slip s: s dw/dt (accelerating) or -s dw/dt (decelerating) ("acceleration_zero"), s w - w_s ("stick_band_entry")
// each offset by the smallest normal double, as the other laws' kinematic rig does in stick, so that none sits at
// exactly zero (see guard_values; a dw/dt below that counts as zero). w = 0 lies inside the band (w_s > 0), where
// T = a w is continuous: a zero of w is no switch of eq 6, and a reversal is two events, into the band on one side
// and out on the other. At a switch the new mode is eq 6's case at the root (the integrators return the side where
// the guard has crossed); where that is still the old mode (a touch) the signal just ahead decides.
// Where a branch's level P0 / N0 is not positive (the quadratic used past its fitted range, friction driving the
// disc) the run stops with the law's message, as on the disc.
// States: friction impulse int T dt and friction work int T w dt, as for the other laws on this rig. The torque
// does not depend on them (the right-hand side is explicit in t): not stiff, and the Jacobian is zero.
// Sampled w(t): dw/dt, and with it T through the acceleration terms, jumps at every knot; only the jumps that
// change eq 6's case are events, the others are crossed by the integrator's error control.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>

#include "../detail/validate.hpp"
#include "../friction/hysteretic.hpp"
#include "kinematic_rig.hpp"  // the primary template (which includes this header at its end)
#include "signals.hpp"

namespace frictionsim {

template <class RelativeVelocity, class NormalForce>
class KinematicRig<HystereticFriction, RelativeVelocity, NormalForce> {
    static_assert(signal_has_derivative_v<RelativeVelocity>,
                  "KinematicRig<HystereticFriction, V, N>: eq 6 depends on the acceleration dw/dt, so the "
                  "relative-velocity signal V needs a member `double derivative(double t) const` (dw/dt in rad/s^2; "
                  "ConstantSignal, HarmonicSlidingVelocity and SampledSignal have one)");

public:
    using Law = HystereticFriction;
    static constexpr std::size_t state_size = 2;
    static constexpr bool stiff = false;  ///< the states are quadratures of an explicit torque
    static constexpr std::size_t guard_count = 2;
    static constexpr std::size_t friction_impulse = 0, friction_work = 1;
    enum Mode : int { decelerating_negative = -2, accelerating_negative = -1, stick_band = 0,
                      accelerating_positive = 1, decelerating_positive = 2 };

    /// initial_law_state: eq 6 has no state; the parameter keeps the constructor the same for every law.
    KinematicRig(HystereticFriction law, RelativeVelocity relative_velocity, NormalForce normal_force,
                 std::array<double, 0> /*initial_law_state*/ = {})
        : law_(std::move(law)), v_r_(std::move(relative_velocity)), normal_(std::move(normal_force)) {}

    const HystereticFriction& law() const { return law_; }
    /// w(t), rad/s.
    double relative_velocity(double t) const { return v_r_(t); }
    /// dw/dt (t), rad/s^2: the signal's derivative.
    double relative_acceleration(double t) const { return v_r_.derivative(t); }

    double friction_force(double t, const double*, int mode) const {
        return torque(v_r_(t), v_r_.derivative(t), normal_force(t), mode);
    }

    void rhs(double t, const double* x, int mode, double* dxdt) const { rhs_guards(t, x, mode, dxdt, nullptr); }

    /// The right-hand side and, into g unless null, the switching functions: one evaluation of the signals.
    void rhs_guards(double t, const double*, int mode, double* dxdt, double* g) const {
        const double w = v_r_(t), al = v_r_.derivative(t);
        if (g != nullptr) guard_values(w, al, mode, g);
        const double f = torque(w, al, normal_force(t), mode);
        dxdt[friction_impulse] = f;
        dxdt[friction_work] = f * w;
    }

    /// Nothing depends on the state: the Jacobian is zero (CVODE zeroes J before the call).
    void jacobian(double, const double*, int, double*) const {}

    void guards(double t, const double*, int mode, double* g) const {
        guard_values(v_r_(t), v_r_.derivative(t), mode, g);
    }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t i, int mode) const {
        if (mode == stick_band) return i == 0 ? "stick_band_upper_edge" : "stick_band_lower_edge";
        return i == 0 ? "acceleration_zero" : "stick_band_entry";
    }
    const char* mode_name(int mode) const {
        switch (mode) {
            case decelerating_negative: return "decelerating_negative";
            case accelerating_negative: return "accelerating_negative";
            case stick_band: return "stick";
            case accelerating_positive: return "accelerating_positive";
            case decelerating_positive: return "decelerating_positive";
        }
        return "unknown";
    }

    /// Eq 6's case at (w, dw/dt): stick, or the slip side and branch.
    int mode_at(double t) const { return classify(v_r_(t), v_r_.derivative(t)); }

    int initial_mode(double t, const double*) const { return mode_at(t); }

    /// Eq 6's case at the root; where that is still `mode` (a guard reached exactly zero), the case just ahead.
    int switch_mode(double t, double*, int mode, const int*) const {
        const int now = mode_at(t);
        if (now != mode) return now;
        const double dt = 1e-9 * std::max(1.0, std::abs(t));
        try {
            return mode_at(t + dt);
        } catch (const std::out_of_range&) {  // sampled data ending within dt: nothing follows
            return mode;
        }
    }

    std::array<double, state_size> initial_state() const { return {}; }
    std::array<const char*, state_size> state_names() const { return {"friction_impulse", "friction_work"}; }

private:
    static int side(int mode) { return mode > 0 ? 1 : -1; }
    static bool is_accelerating(int mode) { return mode == accelerating_positive || mode == accelerating_negative; }

    /// Eq 6's case; dw/dt below the smallest normal double counts as zero (as the guards see it).
    int classify(double w, double al) const {
        if (std::abs(w) <= law_.params().stick_speed) return stick_band;
        const int s = w > 0.0 ? 1 : -1;
        return s * (s * al > tiny ? accelerating_positive : decelerating_positive);
    }

    /// Each guard is offset by the smallest normal double so that it is negative exactly where eq 6 leaves the
    /// mode and never sits at zero: |w| = w_s is in the band, dw/dt = 0 decelerating. A guard at exactly zero
    /// through a stretch of sampled data (dw/dt = 0 on a flat segment) would be masked and then taken for a
    /// crossing at every step (chattering), and CVODE puts a root where a guard reaches exactly zero at the end
    /// of the step that finds it, not where it first does.
    void guard_values(double w, double al, int mode, double* g) const {
        const double w_s = law_.params().stick_speed;
        if (mode == stick_band) {
            g[0] = (w_s - w) + tiny;  // leaves the band upwards: w > w_s
            g[1] = (w_s + w) + tiny;  // leaves it downwards: w < -w_s
            return;
        }
        const double s = side(mode);
        // accelerating: s dw/dt falls to 0; decelerating: s dw/dt turns positive
        g[0] = is_accelerating(mode) ? s * al - tiny : tiny - s * al;
        g[1] = (s * w - w_s) - tiny;  // enters the band: |w| <= w_s
    }

    static constexpr double tiny = std::numeric_limits<double>::min();

    /// Eq 6's value in `mode`: the band's a w, or the mode's branch at (w, dw/dt).
    double torque(double w, double al, double n, int mode) const {
        if (mode == stick_band) return law_.stick_torque(w, n);
        const bool accelerating = is_accelerating(mode);
        law_.require_opposing(accelerating, std::abs(w));
        return law_.slip_torque(accelerating, w, al, n);
    }

    double normal_force(double t) const {
        const double n = normal_(t);
        if (!(std::isfinite(n) && n > 0.0))
            detail::reject("KinematicRig", "normal_force", "positive and finite at every time", n);
        return n;
    }

    HystereticFriction law_;
    RelativeVelocity v_r_;
    NormalForce normal_;
};

/// KinematicRig rig(HystereticFriction(...), w_signal, n_signal) deduces the specialization.
template <class RelativeVelocity, class NormalForce>
KinematicRig(HystereticFriction, RelativeVelocity, NormalForce)
    -> KinematicRig<HystereticFriction, RelativeVelocity, NormalForce>;
template <class RelativeVelocity, class NormalForce>
KinematicRig(HystereticFriction, RelativeVelocity, NormalForce, std::array<double, 0>)
    -> KinematicRig<HystereticFriction, RelativeVelocity, NormalForce>;

}  // namespace frictionsim
