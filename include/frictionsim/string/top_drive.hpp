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
// check_top_drive<Drive>() says whether a type meets it (a static_assert in StringRig names the concept). A
// user's drive is any such type (tests/string_rig.test.cpp builds a DC motor's torque-speed line).
//
// The two built-in drives:
//  * PiTopDrive: paper 001's drive, a motor of inertia J_td under PI speed control with a torque limit,
//      T_m = clamp(k_p (w_set(t) - w_0) + k_i I, -T_max, T_max),  dI/dt = w_set(t) - w_0 (linear),
//    the set speed ramped from rest as Aarsnes & Shor's, w_set(t) = w_SP (1 - exp(-t / T_SP)) (T_SP = 0: a step),
//    the integral frozen while the torque is limited (anti-windup; modes +-1), the limit located as events; where
//    the linear law would push the torque straight back past the limit and the frozen one back inside (a Filippov
//    sliding motion along T_m = T_max), the drive holds the limit with the integral following it (modes +-2),
//    k_i dI/dt = k_p (dw_0/dt - dw_set/dt).
//  * PrescribedSpeed: w_0 = w_set(t) held (the same ramp; node 0's acceleration dw_set/dt prescribed with it).
// TopDriveChoice, StringRig's default, picks one of them at run time from StringRigSetup::top_drive and the
// StringRigParams drive fields, and keeps the historical layout (the integral state present either way).
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

/// PiTopDrive or PrescribedSpeed as StringRigSetup::top_drive says, with StringRigParams' drive fields. The PI
/// integral is a state either way (zero and still under a prescribed speed), as it always was.
class TopDriveChoice {
public:
    TopDriveChoice(const StringRigParams& p, const StringRigSetup& s)
        : pi_(s.top_drive == TopDrive::pi_motor), motor_(PiTopDriveParams::from(checked(p))),
          held_(p.surface_speed, p.setpoint_time_constant) {}
    TopDrive kind() const { return pi_ ? TopDrive::pi_motor : TopDrive::prescribed_speed; }

    bool holds_speed() const { return !pi_; }
    double held_speed() const { return held_.held_speed(); }
    double held_speed_at(double t) const { return held_.held_speed_at(t); }
    double held_acceleration(double t) const { return held_.held_acceleration(t); }
    double inertia() const { return pi_ ? motor_.inertia() : 0.0; }
    std::size_t state_count() const { return 1; }
    const char* state_name(std::size_t j) const { return motor_.state_name(j); }
    double torque(const DriveInput& in, int mode) const { return pi_ ? motor_.torque(in, mode) : 0.0; }
    void rates(const DriveInput& in, double dw0, int mode, double* dz) const {
        if (pi_) motor_.rates(in, dw0, mode, dz);
        else dz[0] = 0.0;
    }
    bool rates_follow_acceleration() const { return pi_ && motor_.rates_follow_acceleration(); }
    std::size_t guard_count() const { return pi_ ? motor_.guard_count() : 0; }
    int initial_mode(const DriveInput& in) const { return pi_ ? motor_.initial_mode(in) : 0; }
    void guards(const DriveInput& in, double dw0, int mode, double* g) const {
        if (pi_) motor_.guards(in, dw0, mode, g);
    }
    int switch_mode(const DriveInput& in, int mode, const int* fired) const {
        return pi_ ? motor_.switch_mode(in, mode, fired) : mode;
    }
    const char* guard_name(std::size_t k, int mode) const { return motor_.guard_name(k, mode); }
    const char* mode_name(int mode) const { return pi_ ? motor_.mode_name(mode) : held_.mode_name(mode); }
    void torque_partials(const DriveInput& in, int mode, double& d_speed, double* d_state) const {
        if (pi_) return motor_.torque_partials(in, mode, d_speed, d_state);
        d_speed = d_state[0] = 0.0;
    }
    void rate_partials(const DriveInput& in, int mode, std::size_t j, double& d_speed, double* d_state,
                       double& d_acceleration) const {
        if (pi_) return motor_.rate_partials(in, mode, j, d_speed, d_state, d_acceleration);
        d_speed = d_state[0] = d_acceleration = 0.0;
    }

private:
    /// The rig's table first, so that a bad drive field is named as the rig's (as it always was).
    static const StringRigParams& checked(const StringRigParams& p) {
        validate_fields("StringRig", p, StringRigParams::fields());
        return p;
    }
    bool pi_;
    PiTopDrive motor_;
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
}  // namespace detail
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
