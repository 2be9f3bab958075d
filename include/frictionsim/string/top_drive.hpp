// Top drives of the event-driven string (StringRig<WallLaw, Bit, Drive>, issue 22 item 4): what turns node 0.
//
// The drive concept. A drive owns D states (at the front of the rig's state vector, before node 0) and at most one
// mode slot (an int in [-2, 2]; present when it has guards), and sees node 0 through a DriveInput: its states z,
// node 0's speed w_0, the string's torque on node 0 S_0 (everything but the motor: element 0's spring and damper,
// node 0's k_t damping), node 0's inertia J_0 (with the drive's own) and the time t. With T_m = torque(...), the
// rig's node 0 obeys J_0 dw_0/dt = S_0 + T_m.
//   bool holds_speed() const            true: node 0 turns at held_speed() whatever it takes (an infinitely stiff
//   double held_speed() const             drive; the torque it takes is recorded as work, T_m is not read)
//   optional, a held speed that varies: double held_speed_at(double t) const, double held_acceleration(double t)
//                                       const (both or neither; without them the held speed is held_speed())
//   double inertia() const              added to node 0 (J_td), kg m^2
//   std::size_t state_count() const     D, at most kMaxDriveStates
//   const char* state_name(j) const
//   double torque(in, mode) const       T_m, N m
//   void rates(in, dw0, mode, dz) const dz/dt given node 0's acceleration dw0
//   bool rates_follow_acceleration() const   can dz/dt read dw0 (widens the Jacobian's band by a node)
//   std::size_t guard_count() const     switching functions (0: no mode slot)
//   int initial_mode(in) const
//   void guards(in, dw0, mode, g) const   g[0 .. guard_count()), triggering when falling through zero
//   int switch_mode(in, mode, fired) const   the new mode when guards fire (the other slots already switched)
//   const char* guard_name(k, mode) const, const char* mode_name(mode) const   (events: "top_drive.<guard>")
//   analytic Jacobian: void torque_partials(in, mode, double& d_speed, double* d_state) const   (dT/dw0, dT/dz)
//                      void rate_partials(in, mode, j, double& d_speed, double* d_state, double& d_acceleration)
//                      (row j of dz/dt: d/dw0, d/dz, d/d(dw0))
//   optional, a jump map: void jump(in, mode, fired, double* z) const   when the drive's guards fire, the rig calls
//                                       it before switch_mode (which then sees the new states): the drive's states
//                                       may jump there (z; in.z holds them before the jump and may alias z). Without
//                                       it the states are continuous at a switch.
// check_top_drive<Drive>() says whether a type meets it (a static_assert in StringRig names the concept). A
// user's drive is any such type (tests/string_rig.test.cpp builds a DC motor's torque-speed line).
//
// The built-in drives:
//  * PiTopDrive: paper 001's drive, a motor of inertia J_td under PI speed control with a torque limit,
//      T_m = clamp(k_p (w_set(t) - w_0) + k_i I, -T_max, T_max),  dI/dt = w_set(t) - w_0 (linear),
//    the set speed ramped from rest as Aarsnes & Shor's, w_set(t) = w_SP (1 - exp(-t / T_SP)) (T_SP = 0: a step),
//    the integral frozen while the torque is limited (anti-windup; modes +-1), the limit located as events; where
//    the linear law would push the torque straight back past the limit and the frozen one back inside (a Filippov
//    sliding motion along T_m = T_max), the drive holds the limit with the integral following it (modes +-2),
//    k_i dI/dt = k_p (dw_0/dt - dw_set/dt).
//  * SampledPiTopDrive: the same PI sampled every T_c (control_period) with a zero-order hold, as Aarsnes & Shor's
//      MAIN.m (TorsionalString's sampled PI): at t = k T_c the set-point sp steps by forward Euler through the
//      first-order filter (sp += (w_SP - sp) T_c / T_SP; T_SP = 0: sp = w_SP), the demand k_p (sp - w_0) + k_i I is
//      held, clamped to +-T_max, and I += T_c (sp - w_0) unless it was clamped (anti-windup). Between samples T_m is
//      constant. The held torque, I, sp and the next sample's index k are states that jump at the sample (its
//      jump map), located as the event g = k T_c - t (t itself against the grid: no drift over long runs).
//  * PrescribedSpeed: w_0 = w_set(t) held (the same ramp; node 0's acceleration dw_set/dt prescribed with it).
// TopDriveChoice, StringRig's default, picks one of them at run time from StringRigSetup::top_drive and the
// StringRigParams drive fields (SampledPiTopDrive where control_period > 0), and keeps the historical layout (the
// integral state present either way, first).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "../detail/validate.hpp"
#include "../parameters.hpp"
#include "string_rig_params.hpp"

namespace frictionsim {

/// What a drive sees of node 0.
struct DriveInput {
    const double* z = nullptr;   ///< the drive's states
    double speed = 0.0;          ///< w_0, rad/s
    double string_torque = 0.0;  ///< S_0, N m: element 0's torque on node 0 (the motor's not included)
    double inertia = 0.0;        ///< J_0, kg m^2: node 0's inertia with the drive's
    double time = 0.0;           ///< t, s
};

/// The set speed ramped from rest, w_set(t) = w_SP (1 - exp(-t / T)) (Aarsnes & Shor's set-point; T = 0: the step
/// w_SP), and its rate.
struct SetpointRamp {
    double speed = 0.0;          ///< w_SP, rad/s
    double time_constant = 0.0;  ///< T, s
    double at(double t) const { return time_constant > 0.0 ? speed * (1.0 - std::exp(-t / time_constant)) : speed; }
    double rate(double t) const {
        return time_constant > 0.0 ? speed / time_constant * std::exp(-t / time_constant) : 0.0;
    }
    /// The sampled filter's set-point after a sample period dt from `setpoint`: the ramp's first-order filter by
    /// forward Euler, setpoint + (w_SP - setpoint) dt / T (A&S's MAIN.m); T = 0: w_SP.
    double sampled(double setpoint, double dt) const {
        return time_constant > 0.0 ? setpoint + (speed - setpoint) * dt / time_constant : speed;
    }
};

/// The most states a drive may carry (the rig's Jacobian gathers a drive's partials on the stack).
inline constexpr std::size_t kMaxDriveStates = 8;

// ---- PI speed control with a torque limit ---------------------------------------------------------------------

/// PiTopDrive's parameters (the same names, symbols and rules as StringRigParams' drive fields).
struct PiTopDriveParams {
    double top_drive_inertia = 500.0;          ///< J_td, kg m^2
    double surface_speed = 6.283185307179586;  ///< w_set, rad/s
    double proportional_gain = 5.0e3;          ///< k_p, N m s/rad
    double integral_gain = 2.0e3;              ///< k_i, N m/rad
    double torque_limit = 6.0e4;               ///< T_max, N m
    double setpoint_time_constant = 0.0;       ///< T_SP, s: w_set ramps as 1 - exp(-t / T_SP); 0: a step

    static constexpr std::array<Field<PiTopDriveParams>, 6> fields() {
        using P = PiTopDriveParams;
        return {{
            {"top_drive_inertia", "J_td", "kg m^2", Rule::positive(), &P::top_drive_inertia,
             "Top-drive inertia at the quill."},
            {"surface_speed", "w_set", "rad/s", Rule::finite(), &P::surface_speed, "Set speed."},
            {"proportional_gain", "k_p", "N m s/rad", Rule::non_negative(), &P::proportional_gain,
             "PI proportional gain."},
            {"integral_gain", "k_i", "N m/rad", Rule::non_negative(), &P::integral_gain, "PI integral gain."},
            {"torque_limit", "T_max", "N m", Rule::positive(), &P::torque_limit, "Top-drive torque limit."},
            {"setpoint_time_constant", "T_SP", "s", Rule::non_negative(), &P::setpoint_time_constant,
             "Set-point ramp: w_set (1 - exp(-t / T_SP)) from rest; 0: a step."},
        }};
    }
    /// The drive fields of a StringRig's parameters.
    static PiTopDriveParams from(const StringRigParams& p) {
        return {p.top_drive_inertia, p.surface_speed, p.proportional_gain, p.integral_gain, p.torque_limit,
                p.setpoint_time_constant};
    }
};

class PiTopDrive {
public:
    using Params = PiTopDriveParams;
    explicit PiTopDrive(const Params& p = {}) : p_(p) { validate_fields("PiTopDrive", p_, Params::fields()); }
    const Params& params() const { return p_; }

    bool holds_speed() const { return false; }
    double held_speed() const { return p_.surface_speed; }
    double inertia() const { return p_.top_drive_inertia; }
    std::size_t state_count() const { return 1; }
    const char* state_name(std::size_t) const { return "speed_error_integral"; }

    /// w_set(t), rad/s: the ramped set speed.
    double set_speed(double t) const { return ramp().at(t); }
    /// k_p (w_set(t) - w_0) + k_i I, N m: the PI law before the limit.
    double controller_torque(const DriveInput& in) const {
        return p_.proportional_gain * (set_speed(in.time) - in.speed) + p_.integral_gain * in.z[0];
    }
    /// Modes: 0 linear; +-1 at the limit with the integral frozen; +-2 holding the limit, the integral following.
    double torque(const DriveInput& in, int mode) const {
        return mode == 0 ? controller_torque(in) : limit_torque(mode);
    }
    void rates(const DriveInput& in, double dw0, int mode, double* dz) const {
        if (mode == 0) {
            dz[0] = set_speed(in.time) - in.speed;
        } else if (mode == 2 || mode == -2) {  // T_m stays put: k_i dI/dt = k_p (dw_0/dt - dw_set/dt)
            dz[0] = p_.proportional_gain / p_.integral_gain * dw0;
            if (ramped()) dz[0] -= p_.proportional_gain / p_.integral_gain * ramp().rate(in.time);
        } else {
            dz[0] = 0.0;
        }
    }
    bool rates_follow_acceleration() const { return can_hold_limit(); }

    std::size_t guard_count() const { return 2; }
    int initial_mode(const DriveInput& in) const {
        const double u = controller_torque(in);
        return u > p_.torque_limit ? 1 : u < -p_.torque_limit ? -1 : 0;
    }
    void guards(const DriveInput& in, double dw0, int mode, double* g) const {
        const double u = controller_torque(in), limit = p_.torque_limit;
        if (mode == 0) {
            g[0] = limit - u;  // reaches +T_max
            g[1] = limit + u;  // reaches -T_max
        } else if (mode == 1 || mode == -1) {
            g[0] = mode * (u - mode * limit);  // the PI torque comes back inside the limit
            g[1] = 1.0;
        } else {
            const int side = mode > 0 ? 1 : -1;
            g[0] = linear_push(in, dw0, side);  // the linear law turns inward: release
            g[1] = side * frozen_rate(in, dw0);  // the frozen law turns outward: freeze
        }
    }
    int switch_mode(const DriveInput& in, int mode, const int* fired) const {
        if (mode == 2 || mode == -2) return fired[0] != 0 ? 0 : mode / 2;
        const int side = mode != 0 ? mode : (fired[0] != 0 ? 1 : -1);
        const double dw0 = (in.string_torque + limit_torque(side)) / in.inertia;  // at the limit
        const bool linear_out = can_hold_limit() && linear_push(in, dw0, side) > 0.0;
        if (mode == 0) {                                         // reaching the limit from inside
            if (side * frozen_rate(in, dw0) <= 0.0) return side;  // the frozen law stays outside
            return linear_out ? 2 * side : 0;    // sliding, or grazing the limit
        }
        return linear_out ? 2 * side : 0;  // back inside: unless the linear law would leave again at once
    }
    const char* guard_name(std::size_t k, int mode) const {
        if (mode == 0) return k == 0 ? "positive_torque_limit" : "negative_torque_limit";
        if (mode == 1 || mode == -1) return "back_inside_limit";
        return k == 0 ? "released_from_limit" : "integral_frozen_at_limit";
    }
    const char* mode_name(int mode) const {
        static constexpr std::array<const char*, 5> names{"drive_holding_negative_limit", "drive_at_negative_limit",
                                                          "drive_linear", "drive_at_positive_limit",
                                                          "drive_holding_positive_limit"};
        return names[static_cast<std::size_t>(mode + 2)];
    }

    void torque_partials(const DriveInput&, int mode, double& d_speed, double* d_state) const {
        d_speed = mode == 0 ? -p_.proportional_gain : 0.0;
        d_state[0] = mode == 0 ? p_.integral_gain : 0.0;
    }
    void rate_partials(const DriveInput&, int mode, std::size_t, double& d_speed, double* d_state,
                       double& d_acceleration) const {
        d_speed = mode == 0 ? -1.0 : 0.0;
        d_state[0] = 0.0;
        d_acceleration = mode == 2 || mode == -2 ? p_.proportional_gain / p_.integral_gain : 0.0;
    }

private:
    double limit_torque(int side) const { return (side > 0 ? 1.0 : -1.0) * p_.torque_limit; }
    bool can_hold_limit() const { return p_.integral_gain > 0.0; }
    SetpointRamp ramp() const { return {p_.surface_speed, p_.setpoint_time_constant}; }
    bool ramped() const { return p_.setpoint_time_constant > 0.0; }
    /// -dT/dt / k_p of the frozen law: dw_0/dt - dw_set/dt (the torque falls while it is positive).
    double frozen_rate(const DriveInput& in, double dw0) const {
        return ramped() ? dw0 - ramp().rate(in.time) : dw0;
    }
    /// dT/dt of the linear PI law (k_i e + k_p (dw_set/dt - dw_0/dt)), times the side s of the limit: > 0 pushes
    /// outward.
    double linear_push(const DriveInput& in, double dw0, int side) const {
        double push = p_.integral_gain * (set_speed(in.time) - in.speed) - p_.proportional_gain * dw0;
        if (ramped()) push += p_.proportional_gain * ramp().rate(in.time);
        return side * push;
    }
    Params p_;
};

// ---- the PI sampled with a zero-order hold ----------------------------------------------------------------------

/// SampledPiTopDrive's parameters: PiTopDrive's table and the control period T_c.
struct SampledPiTopDriveParams : PiTopDriveParams {
    double control_period = 0.01;  ///< T_c, s

    static constexpr std::array<Field<SampledPiTopDriveParams>, 7> fields() {
        using P = SampledPiTopDriveParams;
        return extend_fields<P>(PiTopDriveParams::fields(),
                                std::array<Field<P>, 1>{{{"control_period", "T_c", "s", Rule::positive(),
                                                          &P::control_period,
                                                          "Sampling period of the PI (zero-order hold)."}}});
    }
    /// The drive fields of a StringRig's parameters (control_period > 0 for a sampled drive).
    static SampledPiTopDriveParams from(const StringRigParams& p) {
        SampledPiTopDriveParams s;
        static_cast<PiTopDriveParams&>(s) = PiTopDriveParams::from(p);
        s.control_period = p.control_period;
        return s;
    }
};

class SampledPiTopDrive {
public:
    using Params = SampledPiTopDriveParams;
    /// Its states: PiTopDrive's integral first (StringRig::speed_error_integral), then the held torque, the
    /// filtered set-point and the index k of the next sample (at k T_c: 0 in the initial state, the first sample
    /// at t = 0; a run from t_0 sets it to the first k with k T_c >= t_0).
    enum State : std::size_t { integral, held_torque, setpoint, next_sample, states };
    explicit SampledPiTopDrive(const Params& p = {}) : p_(p) {
        validate_fields("SampledPiTopDrive", p_, Params::fields());
    }
    const Params& params() const { return p_; }

    bool holds_speed() const { return false; }
    double held_speed() const { return p_.surface_speed; }
    double inertia() const { return p_.top_drive_inertia; }
    std::size_t state_count() const { return states; }
    const char* state_name(std::size_t j) const {
        static constexpr std::array<const char*, states> names{"speed_error_integral", "held_motor_torque",
                                                               "sampled_setpoint", "next_sample"};
        return names[j];
    }
    /// k T_c, s: the instant of the next sample.
    double sample_time(const double* z) const { return z[next_sample] * p_.control_period; }

    /// The held torque (modes: 0 inside the limit, +-1 held at +-T_max; names only, the torque is the state's).
    double torque(const DriveInput& in, int) const { return in.z[held_torque]; }
    void rates(const DriveInput&, double, int, double* dz) const {
        for (std::size_t j = 0; j < states; ++j) dz[j] = 0.0;
    }
    bool rates_follow_acceleration() const { return false; }

    std::size_t guard_count() const { return 1; }
    int initial_mode(const DriveInput& in) const {
        // a sample overdue at the start would never fire (the guard triggers falling through zero); rows read back
        // at a located sample are late by the location's ulps only
        if (in.time - sample_time(in.z) > 1e-9 * (std::abs(in.time) + p_.control_period))
            detail::reject("SampledPiTopDrive", "next_sample",
                           "a state with next_sample * control_period at or after the run's start (0 from t = 0)",
                           in.z[next_sample]);
        return held_mode(in.z[held_torque]);
    }
    void guards(const DriveInput& in, double, int, double* g) const { g[0] = sample_time(in.z) - in.time; }
    /// The sample at t = k T_c: the set-point filtered, the demand held (clamped), the integral (unless clamped),
    /// the next sample's index.
    void jump(const DriveInput& in, int, const int* fired, double* z) const {
        if (fired[0] == 0) return;
        const double sp = ramp().sampled(in.z[setpoint], p_.control_period), e = sp - in.speed;
        const double integral_before = in.z[integral], k = in.z[next_sample];
        const double demand = p_.proportional_gain * e + p_.integral_gain * integral_before;
        const bool limited = std::abs(demand) > p_.torque_limit;
        z[held_torque] = limited ? std::copysign(p_.torque_limit, demand) : demand;
        z[integral] = limited ? integral_before : integral_before + p_.control_period * e;
        z[setpoint] = sp;
        z[next_sample] = k + 1.0;
    }
    int switch_mode(const DriveInput& in, int, const int*) const { return held_mode(in.z[held_torque]); }
    const char* guard_name(std::size_t, int) const { return "sample"; }
    const char* mode_name(int mode) const {
        return mode > 0 ? "drive_sampled_at_positive_limit" : mode < 0 ? "drive_sampled_at_negative_limit"
                                                                       : "drive_sampled";
    }

    void torque_partials(const DriveInput&, int, double& d_speed, double* d_state) const {
        d_speed = 0.0;
        for (std::size_t j = 0; j < states; ++j) d_state[j] = j == held_torque ? 1.0 : 0.0;
    }
    void rate_partials(const DriveInput&, int, std::size_t, double& d_speed, double* d_state,
                       double& d_acceleration) const {
        d_speed = d_acceleration = 0.0;
        for (std::size_t j = 0; j < states; ++j) d_state[j] = 0.0;
    }

private:
    int held_mode(double held) const { return held >= p_.torque_limit ? 1 : held <= -p_.torque_limit ? -1 : 0; }
    SetpointRamp ramp() const { return {p_.surface_speed, p_.setpoint_time_constant}; }
    Params p_;
};

// ---- a prescribed surface speed ------------------------------------------------------------------------------

class PrescribedSpeed {
public:
    /// w_set, rad/s, reached as w_set (1 - exp(-t / T_SP)) from rest (setpoint_time_constant T_SP, s; 0: held
    /// from t = 0).
    explicit PrescribedSpeed(double surface_speed = 6.283185307179586, double setpoint_time_constant = 0.0)
        : ramp_{surface_speed, setpoint_time_constant} {
        detail::require_finite("PrescribedSpeed", "surface_speed", surface_speed);
        if (!(setpoint_time_constant >= 0.0 && std::isfinite(setpoint_time_constant)))
            detail::reject("PrescribedSpeed", "setpoint_time_constant", ">= 0 and finite", setpoint_time_constant);
    }
    bool holds_speed() const { return true; }
    double held_speed() const { return ramp_.speed; }
    double held_speed_at(double t) const { return ramp_.at(t); }
    double held_acceleration(double t) const { return ramp_.rate(t); }
    double inertia() const { return 0.0; }
    std::size_t state_count() const { return 0; }
    const char* state_name(std::size_t) const { return ""; }
    double torque(const DriveInput&, int) const { return 0.0; }  // not read: the rig records what holds w_0
    void rates(const DriveInput&, double, int, double*) const {}
    bool rates_follow_acceleration() const { return false; }
    std::size_t guard_count() const { return 0; }
    int initial_mode(const DriveInput&) const { return 0; }
    void guards(const DriveInput&, double, int, double*) const {}
    int switch_mode(const DriveInput&, int mode, const int*) const { return mode; }
    const char* guard_name(std::size_t, int) const { return ""; }
    const char* mode_name(int) const { return "drive_prescribed_speed"; }
    void torque_partials(const DriveInput&, int, double& d_speed, double*) const { d_speed = 0.0; }
    void rate_partials(const DriveInput&, int, std::size_t, double& d_speed, double*, double& d_acceleration) const {
        d_speed = d_acceleration = 0.0;
    }

private:
    SetpointRamp ramp_;
};

// ---- the run-time choice (StringRig's default) -----------------------------------------------------------------

/// PiTopDrive or PrescribedSpeed as StringRigSetup::top_drive says, with StringRigParams' drive fields; the PI
/// sampled (SampledPiTopDrive) where control_period > 0. The PI integral is the first state either way (zero and
/// still under a prescribed speed), as it always was; the sampled PI's other states follow it.
class TopDriveChoice {
public:
    TopDriveChoice(const StringRigParams& p, const StringRigSetup& s)
        : kind_(kind_of(checked(p), s)), motor_(PiTopDriveParams::from(p)), sampled_(sampled_params(p)),
          held_(p.surface_speed, p.setpoint_time_constant) {}
    TopDrive kind() const { return kind_ == Kind::held ? TopDrive::prescribed_speed : TopDrive::pi_motor; }
    /// Is the PI sampled (control_period > 0)?
    bool sampled() const { return kind_ == Kind::sampled; }

    bool holds_speed() const { return kind_ == Kind::held; }
    double held_speed() const { return held_.held_speed(); }
    double held_speed_at(double t) const { return held_.held_speed_at(t); }
    double held_acceleration(double t) const { return held_.held_acceleration(t); }
    double inertia() const { return kind_ == Kind::held ? 0.0 : motor_.inertia(); }
    std::size_t state_count() const { return sampled() ? sampled_.state_count() : 1; }
    const char* state_name(std::size_t j) const { return sampled() ? sampled_.state_name(j) : motor_.state_name(j); }
    double torque(const DriveInput& in, int mode) const {
        switch (kind_) {
        case Kind::pi: return motor_.torque(in, mode);
        case Kind::sampled: return sampled_.torque(in, mode);
        default: return 0.0;
        }
    }
    void rates(const DriveInput& in, double dw0, int mode, double* dz) const {
        if (kind_ == Kind::pi) motor_.rates(in, dw0, mode, dz);
        else if (kind_ == Kind::sampled) sampled_.rates(in, dw0, mode, dz);
        else dz[0] = 0.0;
    }
    bool rates_follow_acceleration() const { return kind_ == Kind::pi && motor_.rates_follow_acceleration(); }
    std::size_t guard_count() const {
        return kind_ == Kind::pi ? motor_.guard_count() : kind_ == Kind::sampled ? sampled_.guard_count() : 0;
    }
    int initial_mode(const DriveInput& in) const {
        return kind_ == Kind::pi ? motor_.initial_mode(in) : kind_ == Kind::sampled ? sampled_.initial_mode(in) : 0;
    }
    void guards(const DriveInput& in, double dw0, int mode, double* g) const {
        if (kind_ == Kind::pi) motor_.guards(in, dw0, mode, g);
        else if (kind_ == Kind::sampled) sampled_.guards(in, dw0, mode, g);
    }
    void jump(const DriveInput& in, int mode, const int* fired, double* z) const {
        if (kind_ == Kind::sampled) sampled_.jump(in, mode, fired, z);  // the continuous PI's states never jump
    }
    int switch_mode(const DriveInput& in, int mode, const int* fired) const {
        return kind_ == Kind::pi        ? motor_.switch_mode(in, mode, fired)
               : kind_ == Kind::sampled ? sampled_.switch_mode(in, mode, fired)
                                        : mode;
    }
    const char* guard_name(std::size_t k, int mode) const {
        return sampled() ? sampled_.guard_name(k, mode) : motor_.guard_name(k, mode);
    }
    const char* mode_name(int mode) const {
        return kind_ == Kind::pi        ? motor_.mode_name(mode)
               : kind_ == Kind::sampled ? sampled_.mode_name(mode)
                                        : held_.mode_name(mode);
    }
    void torque_partials(const DriveInput& in, int mode, double& d_speed, double* d_state) const {
        if (kind_ == Kind::pi) return motor_.torque_partials(in, mode, d_speed, d_state);
        if (kind_ == Kind::sampled) return sampled_.torque_partials(in, mode, d_speed, d_state);
        d_speed = d_state[0] = 0.0;
    }
    void rate_partials(const DriveInput& in, int mode, std::size_t j, double& d_speed, double* d_state,
                       double& d_acceleration) const {
        if (kind_ == Kind::pi) return motor_.rate_partials(in, mode, j, d_speed, d_state, d_acceleration);
        if (kind_ == Kind::sampled) return sampled_.rate_partials(in, mode, j, d_speed, d_state, d_acceleration);
        d_speed = d_state[0] = d_acceleration = 0.0;
    }

private:
    enum class Kind { pi, sampled, held };
    /// The rig's table first, so that a bad drive field is named as the rig's (as it always was).
    static const StringRigParams& checked(const StringRigParams& p) {
        validate_fields("StringRig", p, StringRigParams::fields());
        return p;
    }
    static Kind kind_of(const StringRigParams& p, const StringRigSetup& s) {
        if (s.top_drive == TopDrive::prescribed_speed) {
            if (p.control_period > 0.0)  // as TorsionalString refuses it
                detail::reject("StringRig", "control_period",
                               "0 with top_drive prescribed_speed (no controller to sample)", p.control_period);
            return Kind::held;
        }
        return p.control_period > 0.0 ? Kind::sampled : Kind::pi;
    }
    /// The sampled drive's parameters; a placeholder period where the PI is continuous (the drive not used).
    static SampledPiTopDriveParams sampled_params(const StringRigParams& p) {
        SampledPiTopDriveParams s = SampledPiTopDriveParams::from(p);
        if (!(s.control_period > 0.0)) s.control_period = SampledPiTopDriveParams{}.control_period;
        return s;
    }
    Kind kind_;
    PiTopDrive motor_;
    SampledPiTopDrive sampled_;
    PrescribedSpeed held_;
};

// ---- the concept check -----------------------------------------------------------------------------------------

namespace detail {
template <class D, class = void>
struct is_top_drive : std::false_type {};
template <class D>
struct is_top_drive<
    D, std::void_t<decltype(bool{std::declval<const D&>().holds_speed()}),
                   decltype(double{std::declval<const D&>().held_speed()}),
                   decltype(double{std::declval<const D&>().inertia()}),
                   decltype(std::size_t{std::declval<const D&>().state_count()}),
                   decltype(static_cast<const char*>(std::declval<const D&>().state_name(std::size_t{}))),
                   decltype(double{std::declval<const D&>().torque(std::declval<const DriveInput&>(), 0)}),
                   decltype(std::declval<const D&>().rates(std::declval<const DriveInput&>(), 0.0, 0,
                                                           std::declval<double*>())),
                   decltype(bool{std::declval<const D&>().rates_follow_acceleration()}),
                   decltype(std::size_t{std::declval<const D&>().guard_count()}),
                   decltype(int{std::declval<const D&>().initial_mode(std::declval<const DriveInput&>())}),
                   decltype(std::declval<const D&>().guards(std::declval<const DriveInput&>(), 0.0, 0,
                                                            std::declval<double*>())),
                   decltype(int{std::declval<const D&>().switch_mode(std::declval<const DriveInput&>(), 0,
                                                                     std::declval<const int*>())}),
                   decltype(static_cast<const char*>(std::declval<const D&>().guard_name(std::size_t{}, 0))),
                   decltype(static_cast<const char*>(std::declval<const D&>().mode_name(0)))>>
    : std::true_type {};
template <class D, class = void>
struct top_drive_has_partials : std::false_type {};
template <class D>
struct top_drive_has_partials<
    D, std::void_t<decltype(std::declval<const D&>().torque_partials(std::declval<const DriveInput&>(), 0,
                                                                     std::declval<double&>(),
                                                                     std::declval<double*>())),
                   decltype(std::declval<const D&>().rate_partials(std::declval<const DriveInput&>(), 0,
                                                                   std::size_t{}, std::declval<double&>(),
                                                                   std::declval<double*>(),
                                                                   std::declval<double&>()))>> : std::true_type {};
}  // namespace detail

/// Does D meet the drive concept (the header comment above)?
template <class D>
constexpr bool check_top_drive() {
    return detail::is_top_drive<D>::value;
}
namespace detail {
/// Does D hold a speed that varies in time (held_speed_at(t), held_acceleration(t))?
template <class D, class = void>
struct top_drive_held_ramp : std::false_type {};
template <class D>
struct top_drive_held_ramp<D, std::void_t<decltype(double{std::declval<const D&>().held_speed_at(0.0)}),
                                          decltype(double{std::declval<const D&>().held_acceleration(0.0)})>>
    : std::true_type {};
/// Does D have a jump map (jump(in, mode, fired, z): its states change where its guards fire)?
template <class D, class = void>
struct top_drive_has_jump : std::false_type {};
template <class D>
struct top_drive_has_jump<D, std::void_t<decltype(std::declval<const D&>().jump(
                                 std::declval<const DriveInput&>(), 0, std::declval<const int*>(),
                                 std::declval<double*>()))>> : std::true_type {};
}  // namespace detail
/// Where the drive's guards fired: its jump map on its states z (nothing for a drive without one).
template <class D>
void drive_jump(const D& d, const DriveInput& in, int mode, const int* fired, double* z) {
    if constexpr (detail::top_drive_has_jump<D>::value) d.jump(in, mode, fired, z);
    else (void)d, (void)in, (void)mode, (void)fired, (void)z;
}
/// Does D give the partials of its torque and rates (StringRig's analytic Jacobian needs them)?
template <class D>
inline constexpr bool top_drive_has_partials_v = detail::top_drive_has_partials<D>::value;

/// The speed a drive holds at t (held_speed() for a drive without held_speed_at), rad/s.
template <class D>
double drive_held_speed(const D& d, double t) {
    if constexpr (detail::top_drive_held_ramp<D>::value) return d.held_speed_at(t);
    else return (void)t, d.held_speed();
}
/// Node 0's prescribed acceleration under a drive that holds its speed, rad/s^2 (0 without held_acceleration).
template <class D>
double drive_held_acceleration(const D& d, double t) {
    if constexpr (detail::top_drive_held_ramp<D>::value) return d.held_acceleration(t);
    else return (void)d, (void)t, 0.0;
}

}  // namespace frictionsim
