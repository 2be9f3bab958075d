// A torsional drill string with distributed Coulomb stiction along the wellbore, a PI top drive and the bit off
// bottom: the model of Aarsnes and Shor (2018, J. Pet. Sci. Eng. 163, 712-721; "A&S" below), on the lumped string of
// string/sections.hpp and stepped by Moreau-Jean (eigen/moreau_jean.hpp). A time-stepping model: simulate(string,
// t_end, SolverOptions) runs it (Method::moreau_jean or explicit_projection, solve/time_stepping.hpp's loop) and
// returns the same Result as the rigs.
//   string:    node inertias and element springs from DrillString::lump(N); viscous damping k_t rho J omega per
//              unit length (A&S eq 3), i.e. k_t times each node's string inertia, and/or StringRig's element damping
//              beta k_e (w_{e+1} - w_e) (damping_time): the same string physics as the event-driven StringRig;
//   wall:      at each node a Coulomb contact, static torque bound = the integral over the node's half elements of
//              F_c(x) = mu sin(inc(x)) w(x) r_o(x) (A&S eq 6; w the buoyed weight per length, g rho A (1 - rho_mud
//              / rho), r_o the contact radius), kinetic = f_rat times it; A&S eq 4 keeps the static level while
//              |omega| < omega_c (stick_band_speed; their code: 1.5 rad/s), and stick is true stick (omega = 0);
//   top drive: node 0 carries I_TD, driven by tau_m = k_p e + k_i int e, e = omega_SP - omega_TD (A&S eqs 7-10);
//              continuous, that is a damper k_p and a spring k_i to the set-point angle (the top row of C and K),
//              or sampled with a zero-order hold (A&S's MAIN.m: every 0.01 s). With a torque limit T_max > 0 the
//              drive is StringRig's PiTopDrive (string/top_drive.hpp): tau_m = clamp(k_p e + k_i I, -T_max, T_max),
//              I frozen while the torque is limited (anti-windup). The continuous limited PI stays implicit: each
//              step is taken in the drive's mode, linear (the unlimited PI's damper and spring, the spring's set
//              angle behind by what the integral missed while frozen) or at the limit (tau_m = +-T_max, the PI out
//              of the operator), guessed from the last step, checked at the step's end (linear: the law within the
//              limit; at the limit: the frozen law still past it, or the linear law started on it moving outward)
//              and retaken from the step's start in the other mode when inconsistent; a mode change restarts
//              Moreau-Jean on the other operator (both built once). At the limit the integral stays frozen while
//              the frozen law is past the limit (PiTopDrive's modes +-1), else it follows the limit, k_p e + k_i I =
//              +-T_max (the sliding motion, modes +-2); where neither mode is consistent (the limit grazed within
//              the step) the step at the limit is kept. The mode changes at step ends only, so the limit's
//              crossings cost O(h^2) each; no step restriction (both operators are the A-stable theta-method's, the
//              mode choice and the integral are algebraic). Or (set_top_drive) a prescribed speed: node 0 turns at
//              omega_SP(t) whatever it takes (StringRig's PrescribedSpeed); its dof is held out of the inclusion
//              (at rest, decoupled), element 0 pulls node 1 from the prescribed angle, and motor_torque reports
//              what holds node 0 on its path:
//              J_0 d omega_SP/dt + k_t J_0 omega_SP + node 0's wall torque - element 0's torque on it (J_0 the
//              string's node 0 inertia: a prescribed drive's own inertia is not the string's, as in StringRig);
//   bit:       off bottom: node N carries an optional BHA inertia and a constant bit torque (0 off bottom); on
//              bottom (weight_on_bit > 0): the velocity-weakening bit of Navarro-Lopez and Cortes (2007,
//              NavarroLopezBit of bit_rock.hpp) at node N, merged with node N's wall contact into one contact (both
//              act on the same dof: the bounds add), its slip level taken at the speed predicted for each step's
//              middle (LumpedFriction's rule, moreau_jean_events.hpp: second order where the start's is first).
//              Its treatment is the model's (set_bit_treatment): captured by Moreau-Jean with the walls, or exact
//              (its stick <-> slip located and restarted by eigen/moreau_jean_events.hpp, the walls still captured:
//              the mixed treatment); c_b is a linear damper at N.
// The closed forms of A&S sec. 4 come with it: break-off torque (eq 27), minimum torque (eq 30), the twist at the
// top drive (eq 29 at x = 0), build-up time (eq 34) and period estimate (eq 40) with the string's fundamental
// period (the continuous string's lowest mode, top held, by transfer matrices).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "../detail/constants.hpp"
#include "../outputs.hpp"
#include "../parameters.hpp"
#include "../survey.hpp"
#include "../eigen/moreau_jean.hpp"
#include "../eigen/moreau_jean_events.hpp"
#include "../solve/time_stepping.hpp"
#include "../bits/bit_rock.hpp"
#include "sections.hpp"
#include "string_rig_params.hpp"
#include "top_drive.hpp"

namespace frictionsim {

struct TorsionalStringParams {
    double top_drive_inertia = 2900.0;           ///< I_TD, kg m^2 (A&S Well B)
    double proportional_gain = 38e3;             ///< k_p, N m s/rad
    double integral_gain = 100e3;                ///< k_i, N m/rad
    double speed_setpoint = 40.0 * pi / 30.0;    ///< omega_SP, rad/s (40 rpm)
    double setpoint_time_constant = 1.0;         ///< s: omega_SP ramps from rest as 1 - exp(-t / T); 0: a step
    double control_period = 0.0;                 ///< s: 0 continuous PI; > 0 sampled, zero-order hold
    double friction_coefficient = 0.3;           ///< mu, static (A&S: the static friction factor)
    double kinetic_ratio = 0.65;                 ///< f_rat = kinetic / static
    double stick_band_speed = 0.0;               ///< omega_c, rad/s: below it a slipping node keeps the static level
    double inclination = 60.0 * pi / 180.0;      ///< rad, of a straight inclined well (when no survey is given)
    double mud_density = 0.0;                    ///< kg/m^3: buoyancy; 0 the dry weight, as A&S's code
    double damping_rate = 0.0;                   ///< k_t, 1/s: damping torque k_t rho J omega per unit length
    double damping_time = 0.0;                   ///< beta, s: element damping beta k_e (StringRig's structural)
    double bha_inertia = 0.0;                    ///< kg m^2 lumped on the bit node, beyond the sections'
    double bit_torque = 0.0;                     ///< N m against the rotation at the bit; off bottom 0
    double gravity = 9.81;                       ///< m/s^2
    double weight_on_bit = 0.0;                  ///< W, N: > 0 puts the velocity-weakening bit on bottom
    double torque_limit = 0.0;                   ///< T_max, N m: |tau_m| <= T_max, anti-windup; 0: no limit

    static constexpr std::array<Field<TorsionalStringParams>, 18> fields();
    static constexpr const char* rig_name = "TorsionalString";  ///< as Python and the rig list name it
    /// The Result's columns beside t (TorsionalString::state_names). The mode column counts the wall contacts at
    /// rest, as StringRig's does; the bit's own stick and slip are in the events.
    static constexpr std::array<RigOutput, 6> outputs() {
        return {{
            {"friction_force", "N m", "node N's contact torque (the bit's with its wall's) over the step"},
            {"bit_speed", "rad/s", "speed of node N, the bit"},
            {"top_drive_speed", "rad/s", "speed of node 0, the top drive"},
            {"motor_torque", "N m", "the top drive's torque: the PI motor's tau_m, or what holds a prescribed speed"},
            {"stuck_fraction", "1", "share of the nodes at rest (|omega| < slow_speed where set)"},
            {"mode", "1", "wall contacts at rest (a count out of contact_count())"},
        }};
    }
};

inline constexpr std::array<Field<TorsionalStringParams>, 18> TorsionalStringParams::fields() {
    using P = TorsionalStringParams;
    return {{
        {"top_drive_inertia", "I_TD", "kg m^2", Rule::positive(), &P::top_drive_inertia, "Top drive inertia."},
        {"proportional_gain", "k_p", "N m s/rad", Rule::non_negative(), &P::proportional_gain, "PI proportional gain."},
        {"integral_gain", "k_i", "N m/rad", Rule::non_negative(), &P::integral_gain, "PI integral gain."},
        {"speed_setpoint", "omega_SP", "rad/s", Rule::finite(), &P::speed_setpoint, "Top drive speed set-point."},
        {"setpoint_time_constant", "T_SP", "s", Rule::non_negative(), &P::setpoint_time_constant,
         "Time constant of the set-point's ramp from rest; 0: a step."},
        {"control_period", "T_c", "s", Rule::non_negative(), &P::control_period,
         "Sampling period of the PI (zero-order hold); 0: continuous."},
        {"friction_coefficient", "mu", "-", Rule::non_negative(), &P::friction_coefficient,
         "Static wall friction coefficient."},
        {"kinetic_ratio", "f_rat", "-", Rule::interval(0.0, 1.0).because("kinetic friction <= static"),
         &P::kinetic_ratio, "Kinetic over static friction."},
        {"stick_band_speed", "omega_c", "rad/s", Rule::non_negative(), &P::stick_band_speed,
         "A&S eq 4: below it the friction keeps the static level; 0: kinetic as soon as it slips."},
        {"inclination", "INC", "rad", Rule::interval(0.0, pi), &P::inclination,
         "Inclination of a straight well (ignored when a survey is given)."},
        {"mud_density", "rho_mud", "kg/m^3", Rule::non_negative(), &P::mud_density, "Mud density (buoyancy)."},
        {"damping_rate", "k_t", "1/s", Rule::non_negative(), &P::damping_rate,
         "Viscous damping: torque k_t rho J omega per unit length."},
        {"damping_time", "beta", "s", Rule::non_negative(), &P::damping_time,
         "Structural damping: each element's damper is beta times its stiffness (StringRig's damping_time)."},
        {"bha_inertia", "J_BHA", "kg m^2", Rule::non_negative(), &P::bha_inertia, "Inertia lumped on the bit."},
        {"bit_torque", "T_b", "N m", Rule::non_negative(), &P::bit_torque, "Torque on bit; off bottom 0."},
        {"gravity", "g", "m/s^2", Rule::positive(), &P::gravity, "Acceleration of gravity."},
        {"weight_on_bit", "W", "N", Rule::non_negative(), &P::weight_on_bit,
         "Weight on bit of the velocity-weakening bit at node N; 0: off bottom."},
        {"torque_limit", "T_max", "N m", Rule::non_negative(), &P::torque_limit,
         "Top-drive torque limit: the PI's torque clamped to +-T_max, its integral frozen while limited "
         "(anti-windup); 0: no limit."},
    }};
}

/// What a run records every output interval.
struct TorsionalStringRun {
    std::vector<double> time;             ///< s
    std::vector<double> bit_speed;        ///< rad/s, node N
    std::vector<double> top_drive_speed;  ///< rad/s, node 0
    std::vector<double> motor_torque;     ///< N m, tau_m
    std::vector<double> stuck_fraction;   ///< nodes at rest (v == 0 exactly; or |v| < slow_speed if set)
    std::vector<double> bit_stick_times;    ///< s: the on-bottom bit comes to rest (captured: the step's end)
    std::vector<double> bit_release_times;  ///< s: the on-bottom bit breaks loose
    MoreauJean::Statistics statistics;
    long bit_location_trials = 0;  ///< exact bit: trial steps that located its switches
};

/// How the on-bottom bit's stick and slip are treated: a contact of the Moreau-Jean inclusion like the walls, or a
/// lumped element whose switches are located exactly (solve/moreau_jean_events.hpp).
enum class BitTreatment { captured, exact };

/// The earlier run interface (TorsionalString::simulate(run)), kept as a thin wrapper over simulate(): its settings
/// map to SolverOptions (method, step, theta, projection_band, interrupt) and to the model's (bit treatment,
/// switch tolerance, slow speed).
struct TorsionalStringRunOptions {
    double t_end = 60.0;
    double step = 1e-3;            ///< h, s; the output interval and a sampled PI's period are multiples of it
    double theta = 0.5;
    double output_interval = 0.01;
    double slow_speed = 0.0;       ///< > 0: count |omega| < slow_speed as stuck (A&S's stick band, 1.5 rad/s)
    ContactTreatment treatment = ContactTreatment::inclusion;
    double projection_band = 0.0;
    BitTreatment bit_treatment = BitTreatment::captured;
    double switch_tolerance = 1e-10;  ///< s: exact bit, its switches located within it
    std::function<bool()> interrupt;
};

class TorsionalString {
public:
    /// `contact_radius`: one per section (m), empty: each section's OD / 2. `survey`: the well's (its inclination at
    /// each measured depth, Survey::inclination_at); none: the straight well of params.inclination.
    /// `bit`: the law of the on-bottom bit (used when params.weight_on_bit > 0).
    TorsionalString(DrillString string, TorsionalStringParams params, std::size_t elements,
                    std::optional<Survey> survey = std::nullopt, std::vector<double> contact_radius = {},
                    NavarroLopezBit bit = NavarroLopezBit{})
        : string_(std::move(string)), p_(params), survey_(std::move(survey)), radius_(std::move(contact_radius)),
          bit_(std::move(bit)) {
        validate_fields("TorsionalString", p_, TorsionalStringParams::fields());
        const auto& sections = string_.sections();
        if (radius_.empty())
            for (const PipeSection& s : sections) radius_.push_back(s.outer_diameter / 2.0);
        if (radius_.size() != sections.size())
            detail::reject("TorsionalString", "contact_radius", "one per section (count given)",
                           static_cast<double>(radius_.size()));
        for (double r : radius_) detail::require_positive("TorsionalString", "contact_radius", r);
        for (const PipeSection& s : sections)  // a buoyed weight <= 0 would make a wall's bound negative
            if (!(p_.mud_density < s.density))
                detail::reject("TorsionalString", "mud_density",
                               "below every section's density (the string would float: no wall friction)",
                               p_.mud_density);
        lumped_ = string_.lump(elements);
        const std::size_t n = elements;
        const double dx = lumped_.element_length;
        static_torque_.assign(n + 1, 0.0);
        for (std::size_t e = 0; e < n; ++e) {  // each element's friction, half to each of its nodes
            const double half = 0.5 * friction_integral(static_cast<double>(e) * dx, static_cast<double>(e + 1) * dx);
            static_torque_[e] += half;
            static_torque_[e + 1] += half;
        }
        for (std::size_t i = 0; i <= n; ++i)  // the wall contacts: nodes with friction (on bottom node N is the bit's)
            if (static_torque_[i] > 0.0 && !(bit_on_bottom() && i == n)) wall_nodes_.push_back(i);
    }

    const TorsionalStringParams& params() const { return p_; }
    const DrillString& string() const { return string_; }
    /// The survey the walls' bounds read (none: the straight well of params().inclination).
    const std::optional<Survey>& survey() const { return survey_; }
    const LumpedString& lumped() const { return lumped_; }
    std::size_t nodes() const { return lumped_.node_inertia.size(); }
    /// Static torque bound of each node's wall contact [N m] (kinetic: kinetic_ratio times it).
    const std::vector<double>& static_friction_torque() const { return static_torque_; }
    /// The nodes with a wall contact (a static bound > 0; on bottom node N's is the bit's, not counted), top down.
    const std::vector<std::size_t>& wall_contact_nodes() const { return wall_nodes_; }
    /// How many wall contacts the string has: the Result's mode column counts those at rest (StringRig's rule).
    std::size_t contact_count() const { return wall_nodes_.size(); }
    const NavarroLopezBit& bit_law() const { return bit_; }
    bool bit_on_bottom() const { return p_.weight_on_bit > 0.0; }
    /// Node N's static bound with the bit on bottom [N m]: its wall's plus R_b W mu_sb.
    double bit_static_torque() const { return static_torque_.back() + bit_.static_limit(p_.weight_on_bit); }
    /// Node N's slip level at bit speed |w| [N m]: its wall's kinetic (static inside the stick band, A&S eq 4) plus
    /// R_b W mu_b(|w|) (c_b w is the damper at N).
    double bit_kinetic_torque(double speed) const {
        const double wall = static_torque_.back() *
                            (std::abs(speed) < p_.stick_band_speed ? 1.0 : p_.kinetic_ratio);
        return wall + bit_.params().bit_radius * p_.weight_on_bit * bit_.coefficient(speed);
    }
    /// The bit (with node N's wall) as a lumped element of the mixed treatment.
    LumpedFriction bit_element() const {
        const TorsionalString self = *this;
        return LumpedFriction(nodes() - 1, bit_static_torque(),
                              [self](double speed) { return self.bit_kinetic_torque(speed); }, "bit");
    }

    /// F_c(x) of A&S eq 6 [N m/m]: mu sin(inc) g rho A (1 - rho_mud / rho) r_o at measured depth x.
    double wall_friction_per_length(double x) const {
        const auto [s, i] = section_at(x);
        const double inc = survey_ ? survey_->inclination_at(x) : p_.inclination;
        const double buoyed = p_.gravity * s->mass_per_length() * (1.0 - p_.mud_density / s->density);
        return p_.friction_coefficient * std::sin(inc) * buoyed * radius_[i];
    }

    /// A&S eq 27: the break-off torque, int_0^L F_c dx (the torque the top drive must reach to free the bit).
    double breakoff_torque() const { return friction_integral(0.0, string_.length()); }
    /// A&S eq 30: the minimum motor torque of a stick-slip cycle, tau_max (1 - 2 (1 - f_rat)).
    double minimum_torque() const { return breakoff_torque() * (1.0 - 2.0 * (1.0 - p_.kinetic_ratio)); }
    /// A&S eq 29 at the top drive: phi(0) = int_0^L tau(x) / (J G)(x) dx, tau(x) = int_x^L F_c (eq 26), the
    /// string's twist when it holds the break-off torque profile (Simpson, 500 pieces per section).
    double top_drive_twist() const {
        const auto& sections = string_.sections();
        double twist = 0.0, bottom = string_.length(), torque = 0.0;  // tau(L) = 0: the bit is off bottom
        for (std::size_t i = sections.size(); i-- > 0;) {  // upwards, tau accumulated piece by piece
            const PipeSection& s = sections[i];
            const int pieces = 500;
            const double dx = s.length / pieces;
            for (int k = pieces; k-- > 0;) {
                const double a = bottom - s.length + k * dx, m = a + 0.5 * dx, b = a + dx;
                const double at_m = torque + friction_integral(m, b), at_a = at_m + friction_integral(a, m);
                twist += dx / 6.0 * (at_a + 4.0 * at_m + torque) / s.torsional_rigidity();
                torque = at_a;
            }
            bottom -= s.length;
        }
        return twist;
    }
    /// A&S eq 34: build-up time 2 (1 - f_rat) phi(0) / omega_TD.
    double build_up_time() const { return 2.0 * (1.0 - p_.kinetic_ratio) * top_drive_twist() / p_.speed_setpoint; }
    /// The continuous string's fundamental torsional period [s], top held (a stiff top drive), bit free with the
    /// BHA inertia: first root of the transfer-matrix frequency equation over the sections.
    double fundamental_period() const {
        const auto residual = [&](double w) {  // state (twist, torque) from the top: (0, 1)
            double angle = 0.0, torque = 1.0;
            for (const PipeSection& s : string_.sections()) {
                const double k = w * std::sqrt(s.density / s.shear_modulus), gj = s.torsional_rigidity();
                const double c = std::cos(k * s.length), sn = std::sin(k * s.length);
                const double a = angle * c + torque * sn / (gj * k);
                torque = -gj * k * angle * sn + torque * c;
                angle = a;
            }
            return torque - w * w * p_.bha_inertia * angle;  // the end inertia's torque balance
        };
        double lo = 1e-6, hi = lo, r_lo = residual(lo);
        for (hi = 2.0 * lo; residual(hi) * r_lo > 0.0; hi *= 1.01) lo = hi;
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (lo + hi);
            (residual(mid) * r_lo > 0.0 ? lo : hi) = mid;
        }
        return 2.0 * pi / (0.5 * (lo + hi));
    }
    /// A&S eq 40: t_p = t_bu + t_fp (A&S: "slightly" above the observed period).
    double period_estimate() const { return build_up_time() + fundamental_period(); }

    /// The set-point omega_SP(t) = omega_SP (1 - exp(-t / T)) (StringRig's SetpointRamp) and its angle
    /// int_0^t omega_SP.
    SetpointRamp setpoint_ramp() const { return {p_.speed_setpoint, p_.setpoint_time_constant}; }
    double setpoint_speed(double t) const { return setpoint_ramp().at(t); }
    double setpoint_angle(double t) const {
        const double T = p_.setpoint_time_constant;
        return T > 0.0 ? p_.speed_setpoint * (t - T * (1.0 - std::exp(-t / T))) : p_.speed_setpoint * t;
    }
    /// d omega_SP / dt (0 for a step, past t = 0).
    double setpoint_acceleration(double t) const { return setpoint_ramp().rate(t); }

    /// How node 0 turns: the PI motor (TopDrive::pi_motor, the default; with torque_limit > 0 PiTopDrive's limit
    /// and anti-windup) or a prescribed speed omega_SP(t) (TopDrive::prescribed_speed, StringRig's PrescribedSpeed:
    /// whatever torque it takes). A prescribed speed has no controller: a sampled PI (control_period > 0) or a
    /// torque limit with it is refused, naming the parameter.
    TorsionalString& set_top_drive(TopDrive drive) {
        constexpr const char* who = "TorsionalString";
        if (drive == TopDrive::prescribed_speed) {
            if (p_.control_period > 0.0)
                detail::reject(who, "control_period", "0 with top_drive prescribed_speed (no controller to sample)",
                               p_.control_period);
            if (p_.torque_limit > 0.0)
                detail::reject(who, "torque_limit",
                               "0 with top_drive prescribed_speed (the speed is held whatever torque it takes)",
                               p_.torque_limit);
        }
        drive_ = drive;
        return *this;
    }
    TopDrive top_drive() const { return drive_; }
    bool holds_speed() const { return drive_ == TopDrive::prescribed_speed; }
    /// The PI's torque is taken from each step's start (sampled, a zero-order hold): see the header.
    bool explicit_drive() const { return !holds_speed() && p_.control_period > 0.0; }
    /// The continuous PI with a torque limit: implicit, each step taken in the drive's mode (see the header).
    bool limited_drive() const { return !holds_speed() && p_.control_period == 0.0 && p_.torque_limit > 0.0; }
    /// Under a prescribed speed: the torque that holds node 0 on omega_SP(t) [N m], from node 1's angle and speed,
    /// J_0 d omega_SP/dt + k_t J_0 omega_SP + node 0's wall torque - element 0's torque on node 0 (J_0 without
    /// I_TD: a prescribed drive's own inertia is not the string's, as StringRig's PrescribedSpeed); the wall
    /// at its slip level (static inside the stick band, A&S eq 4) while omega_SP != 0, at rest holding what it can.
    double held_torque(double t, double q1, double v1) const {
        const double w = setpoint_speed(t), j0 = lumped_.node_inertia[0], k0 = lumped_.torsional_stiffness[0];
        const double string_torque = k0 * (q1 - setpoint_angle(t)) + p_.damping_time * k0 * (v1 - w);
        double torque = j0 * setpoint_acceleration(t) + p_.damping_rate * j0 * w - string_torque;
        const double bound = static_torque_[0];
        if (bound > 0.0) {
            if (w != 0.0) torque += std::copysign(std::abs(w) < p_.stick_band_speed ? bound : p_.kinetic_ratio * bound, w);
            else torque = std::copysign(std::max(std::abs(torque) - bound, 0.0), torque);
        }
        return torque;
    }

    /// M v' = f(t) - C v - K q + r over the N + 1 node angles, the wall contacts on the nodes with friction. With a
    /// continuous PI the top drive's gains sit in C(0,0), K(0,0) and f_0 (with `integral_offset`, f_0 takes k_i times
    /// it off: the PI's integral is theta_SP - theta_0 - offset, an integral frozen for a while behind it); sampled
    /// (or at its limit), f_0 reads `held_motor_torque`. Under a prescribed speed dof 0 is decoupled and at rest
    /// (no force, no contact), and element 0 pulls node 1 from the prescribed angle: K(1,1), C(1,1) keep its k_0
    /// and beta k_0, f_1 gets k_0 theta_SP(t) + beta k_0 omega_SP(t). On bottom, node N's contact is the bit's with
    /// its wall's (captured) or absent (`with_bit_contact` false: the bit is the lumped element bit_element()); c_b
    /// sits in C(N, N).
    LinearMechanicalSystem system(const double* held_motor_torque = nullptr, bool with_bit_contact = true,
                                  const double* integral_offset = nullptr) const {
        const Eigen::Index n = static_cast<Eigen::Index>(nodes());
        std::vector<Eigen::Triplet<double>> m, c, k;
        for (Eigen::Index i = 0; i < n; ++i) {
            const double j = lumped_.node_inertia[static_cast<std::size_t>(i)];
            m.emplace_back(i, i, j + (i == 0 ? p_.top_drive_inertia : 0.0) + (i == n - 1 ? p_.bha_inertia : 0.0));
            if (p_.damping_rate > 0.0 && !(i == 0 && holds_speed())) c.emplace_back(i, i, p_.damping_rate * j);
        }
        if (bit_on_bottom() && bit_.params().viscous_damping > 0.0)
            c.emplace_back(n - 1, n - 1, bit_.params().viscous_damping);
        for (Eigen::Index e = 0; e + 1 < n; ++e) {
            const double ke = lumped_.torsional_stiffness[static_cast<std::size_t>(e)];
            const bool coupled = !(e == 0 && holds_speed());  // a prescribed node 0 is not a dof of the inclusion
            if (coupled) k.emplace_back(e, e, ke);
            k.emplace_back(e + 1, e + 1, ke);
            if (coupled) {
                k.emplace_back(e, e + 1, -ke);
                k.emplace_back(e + 1, e, -ke);
            }
            if (p_.damping_time > 0.0) {  // the element's damper beta k_e, as StringRig's
                const double ce = p_.damping_time * ke;
                if (coupled) c.emplace_back(e, e, ce);
                c.emplace_back(e + 1, e + 1, ce);
                if (coupled) {
                    c.emplace_back(e, e + 1, -ce);
                    c.emplace_back(e + 1, e, -ce);
                }
            }
        }
        const bool sampled = held_motor_torque != nullptr;
        if (!sampled && !holds_speed()) {
            c.emplace_back(0, 0, p_.proportional_gain);
            k.emplace_back(0, 0, p_.integral_gain);
        }
        LinearMechanicalSystem sys;
        sys.mass.resize(n, n);
        sys.damping.resize(n, n);
        sys.stiffness.resize(n, n);
        sys.mass.setFromTriplets(m.begin(), m.end());
        sys.damping.setFromTriplets(c.begin(), c.end());
        sys.stiffness.setFromTriplets(k.begin(), k.end());
        const TorsionalString self = *this;
        const double bit = p_.bit_torque;
        if (holds_speed())
            sys.force = [self, bit](double t, Eigen::VectorXd& f) {
                f(f.size() - 1) = -bit;
                const double k0 = self.lumped_.torsional_stiffness[0];
                f(1) += k0 * self.setpoint_angle(t) + self.p_.damping_time * k0 * self.setpoint_speed(t);
            };
        else if (sampled)
            sys.force = [held_motor_torque, bit](double, Eigen::VectorXd& f) {
                f(0) = *held_motor_torque;
                f(f.size() - 1) = -bit;
            };
        else if (integral_offset)
            sys.force = [self, bit, integral_offset](double t, Eigen::VectorXd& f) {
                const TorsionalStringParams& p = self.p_;
                f(0) = p.proportional_gain * self.setpoint_speed(t) +
                       p.integral_gain * (self.setpoint_angle(t) - *integral_offset);
                f(f.size() - 1) = -bit;
            };
        else
            sys.force = [self, bit](double t, Eigen::VectorXd& f) {
                const TorsionalStringParams& p = self.p_;
                f(0) = p.proportional_gain * self.setpoint_speed(t) + p.integral_gain * self.setpoint_angle(t);
                f(f.size() - 1) = -bit;
            };
        const std::size_t last = nodes() - 1;
        for (std::size_t i = 0; i < nodes(); ++i) {
            if (i == 0 && holds_speed()) continue;  // node 0's wall torque is part of what holds its speed
            if (bit_on_bottom() && i == last) {
                if (with_bit_contact)  // at rest: the static level; set_contact_bounds moves it each step
                    sys.contacts.push_back(PointContact{i, bit_static_torque(), bit_kinetic_torque(0.0), 0.0, 0.0});
                continue;
            }
            if (static_torque_[i] > 0.0)
                sys.contacts.push_back(PointContact{i, static_torque_[i], p_.kinetic_ratio * static_torque_[i],
                                                    static_torque_[i], p_.stick_band_speed});
        }
        return sys;
    }

    // simulate(model, t_end, options) (simulate.hpp, solve/time_stepping.hpp): a time-stepping model, run from rest,
    // untwisted, all contacts stuck, by Method::moreau_jean (or explicit_projection). Columns: bit_speed,
    // top_drive_speed [rad/s], motor_torque [N m], stuck_fraction [-]; friction_force: node N's contact torque (the
    // bit's with its wall's) of the step; mode: the wall contacts at rest (StringRig's mode column: a count out of
    // contact_count()); events: the bit's switches, named by its modes 0 stick, +1 / -1 slip forward / backward.
    static constexpr bool time_stepping = true;
    class Stepper;

    /// How a run treats the on-bottom bit: captured with the walls (its stick / release seen at step ends), or
    /// exact, the mixed treatment (its switches located within `switch_tolerance` s, the walls still captured).
    /// Off bottom both are the captured string.
    TorsionalString& set_bit_treatment(BitTreatment treatment, double switch_tolerance = 1e-10) {
        detail::require_positive("TorsionalString", "switch_tolerance", switch_tolerance);
        if (treatment == BitTreatment::exact && p_.torque_limit > 0.0)  // said here, not when the run starts
            detail::reject("TorsionalString", "torque_limit",
                           "0 (no limit) with the exact bit (the limited PI's mode changes at step ends would be "
                           "switches of their own)", p_.torque_limit);
        treatment_ = treatment;
        switch_tolerance_ = switch_tolerance;
        return *this;
    }
    BitTreatment bit_treatment() const { return treatment_; }
    double switch_tolerance() const { return switch_tolerance_; }
    /// What the stuck_fraction column counts: nodes with |omega| < slow_speed (A&S's band: 1.5 rad/s), or with
    /// slow_speed 0 the nodes at rest exactly (omega == 0).
    TorsionalString& set_slow_speed(double slow_speed) {
        slow_speed_ = detail::require_non_negative("TorsionalString", "slow_speed", slow_speed);
        return *this;
    }
    double slow_speed() const { return slow_speed_; }

    std::vector<std::string> state_names() const {
        return {"bit_speed", "top_drive_speed", "motor_torque", "stuck_fraction"};
    }
    const char* mode_name(int mode) const { return mode == 0 ? "stick" : mode > 0 ? "slip_positive" : "slip_negative"; }
    /// The stepper of solve/time_stepping.hpp's loop (refuses a sampled PI with the exact bit, naming
    /// control_period, and a control period that is not a whole number of steps).
    Stepper make_stepper(const TimeStepping& setup) const;

    /// The earlier run interface, kept: simulate(*this, t_end, options) on the output grid run.output_interval (the
    /// rows at k * output_interval), its columns as vectors, the bit's stick / release times from the events.
    TorsionalStringRun simulate(const TorsionalStringRunOptions& run) const;

private:
    static long steps_per(const char* who, const char* name, double interval, double step) {
        detail::require_positive(who, name, interval);
        const double ratio = interval / step;
        const long steps = std::lround(ratio);
        if (steps < 1 || std::abs(ratio - static_cast<double>(steps)) > 1e-9 * ratio)
            detail::reject(who, name, "a whole multiple of the step", interval);
        return steps;
    }

    /// The section holding measured depth x (the lower one at a boundary) and its index.
    std::pair<const PipeSection*, std::size_t> section_at(double x) const {
        const auto& sections = string_.sections();
        double top = 0.0;
        for (std::size_t i = 0; i < sections.size(); ++i) {
            top += sections[i].length;
            if (x < top) return {&sections[i], i};
        }
        return {&sections.back(), sections.size() - 1};
    }

    /// int_a^b F_c dx: 3-point Gauss on pieces of at most 10 m (or L / 1e5 on a string longer than 1000 km, so the
    /// work stays bounded whatever the length), split at section and survey stations (F_c is smooth in between), so
    /// the node bounds sum to the break-off torque independently of the grid.
    double friction_integral(double a, double b) const {
        const double piece = std::max(10.0, string_.length() / 1e5);
        std::vector<double> cuts{a, b};
        double top = 0.0;
        for (const PipeSection& s : string_.sections()) {
            top += s.length;
            if (top > a && top < b) cuts.push_back(top);
        }
        if (survey_)
            for (const SurveyStation& st : survey_->stations())
                if (st.measured_depth > a && st.measured_depth < b) cuts.push_back(st.measured_depth);
        std::sort(cuts.begin(), cuts.end());
        const double g = std::sqrt(0.6);
        double sum = 0.0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
            // at most 1e5 + 1 pieces (cuts[i + 1] - cuts[i] <= L): the count fits a size_t
            const auto pieces = std::max<std::size_t>(
                1, static_cast<std::size_t>(std::ceil((cuts[i + 1] - cuts[i]) / piece)));
            const double dx = (cuts[i + 1] - cuts[i]) / static_cast<double>(pieces);
            for (std::size_t k = 0; k < pieces; ++k) {
                const double m = cuts[i] + (static_cast<double>(k) + 0.5) * dx, r = 0.5 * dx;
                sum += r * (5.0 / 9.0 * wall_friction_per_length(m - g * r) + 8.0 / 9.0 * wall_friction_per_length(m) +
                            5.0 / 9.0 * wall_friction_per_length(m + g * r));
            }
        }
        return sum;
    }

    DrillString string_;
    TorsionalStringParams p_;
    std::optional<Survey> survey_;
    std::vector<double> radius_;
    LumpedString lumped_;
    std::vector<double> static_torque_;
    std::vector<std::size_t> wall_nodes_;
    NavarroLopezBit bit_;
    BitTreatment treatment_ = BitTreatment::captured;
    TopDrive drive_ = TopDrive::pi_motor;
    double switch_tolerance_ = 1e-10;
    double slow_speed_ = 0.0;
};

/// One run of a TorsionalString, step by step (the Stepper of solve/time_stepping.hpp): Moreau-Jean over the whole
/// string with the bit captured (its slip level at each step's midpoint speed, LumpedFriction's rule), or
/// MoreauJeanEvents with the bit as its lumped element (exact); a sampled PI updated on its own grid; a limited
/// continuous PI's mode chosen per step (the header).
class TorsionalString::Stepper {
public:
    Stepper(const TorsionalString& model, const TimeStepping& setup)
        : ts_(model), h_(setup.step), n_(static_cast<Eigen::Index>(model.nodes())), control_(new Control{}) {
        const TorsionalStringParams& p = model.params();
        sampled_ = p.control_period > 0.0;
        explicit_drive_ = model.explicit_drive();
        limited_ = model.limited_drive();
        per_control_ = sampled_ ? steps_per("TorsionalString", "control_period", p.control_period, h_) : 0;
        exact_ = model.bit_on_bottom() && model.bit_treatment() == BitTreatment::exact;
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_);
        MoreauJeanOptions o;
        o.step = setup.step;
        o.theta = setup.theta;
        o.treatment = setup.method == Method::explicit_projection ? ContactTreatment::projection
                                                                  : ContactTreatment::inclusion;
        o.projection_band = setup.projection_band;
        if (setup.contact_solver == ContactSolverChoice::projected_gauss_seidel) o.contact_solver = ProjectedGaussSeidel{};
        o.record_events = false;  // hundreds of contacts: the run keeps the count (statistics), not the log
        if (exact_) {
            if (sampled_)  // the hold's sampling instants would be switches of their own
                detail::reject("TorsionalString", "control_period", "0 (a continuous PI) with the exact bit",
                               p.control_period);
            if (limited_)  // its mode changes at step ends would be switches of their own
                detail::reject("TorsionalString", "torque_limit", "0 (no limit) with the exact bit", p.torque_limit);
            MoreauJeanEventsOptions e;
            e.steps = std::move(o);
            e.time_tolerance = model.switch_tolerance();
            events_driver_ = std::make_unique<MoreauJeanEvents<LumpedFriction>>(
                model.system(nullptr, false), std::vector<LumpedFriction>{model.bit_element()}, std::move(e), zero,
                zero, setup.t_start);
        } else if (limited_) {
            // both operators built once; a mode change restarts Moreau-Jean on the other from the step's start
            linear_system_ = model.system(nullptr, true, &control_->offset);
            limited_system_ = model.system(&control_->held);
            options_ = o;
            integral_ = model.setpoint_angle(setup.t_start);  // theta_SP - theta_0, as the unlimited PI's spring
            const double u = demand(setup.t_start, 0.0, integral_);
            side_ = std::abs(u) > p.torque_limit ? sign(u) : 0;
            step_side_ = side_;
            start_ = Start{setup.t_start, zero, zero, 0.0};
            restart(side_);
        } else {
            mj_ = std::make_unique<MoreauJean>(model.system(explicit_drive_ ? &control_->held : nullptr), std::move(o),
                                               zero, zero, setup.t_start);
            if (explicit_drive_) control();
        }
        start_ = Start{setup.t_start, zero, zero, control_->held};
    }

    double time() const { return exact_ ? events_driver_->time() : mj_->time(); }
    /// The captured run steps on the grid t_start + k h to the point nearest t_end; the exact one shortens its last
    /// step to end on t_end.
    bool finished(double t_end) const {
        return exact_ ? t_end - time() <= 1e-9 * h_ : time() + 0.5 * h_ >= t_end;
    }

    void step(double t_end, bool keep_start) {
        events_.clear();
        if (exact_) {
            const double left = t_end - time();
            const std::size_t seen = events_driver_->events().size();
            events_driver_->step(left < h_ * (1.0 + 1e-9) ? left : h_);
            const std::vector<LumpedEvent>& log = events_driver_->events();
            for (std::size_t k = seen; k < log.size(); ++k) add_event(log[k].time, log[k].mode_before, log[k].mode_after);
            return;
        }
        kept_ = keep_start;
        if (keep_start || limited_) start_ = Start{mj_->time(), mj_->positions(), mj_->velocities(), control_->held};
        const Eigen::Index last = n_ - 1;
        const double w = mj_->velocities()(last);
        const bool level_moves = ts_.bit_on_bottom();
        double level = 0.0;
        if (level_moves) {  // the bit's slip level at the step's midpoint speed (LumpedFriction's rule)
            const MoreauJean& mj = *mj_;
            level = ts_.bit_kinetic_torque(w);
            if (w != 0.0) {
                const MechanicalView at(mj.time(), mj.positions(), mj.velocities(), mj.contact_forces(), mj.system(),
                                        scratch_);
                const double dir = w > 0.0 ? 1.0 : -1.0;
                const double mid = w + 0.5 * h_ * (at.load(static_cast<std::size_t>(last)) - dir * level) /
                                           mj.system().mass.coeff(last, last);
                level = ts_.bit_kinetic_torque(std::max(0.0, dir * mid));
            }
        }
        const auto take = [&] {  // one step of the current operator from the step's start
            if (level_moves) mj_->set_contact_bounds(mj_->system().contacts.size() - 1, ts_.bit_static_torque(), level);
            mj_->step();
        };
        if (limited_) step_limited(take);
        else take();
        ++steps_;
        if (explicit_drive_ && steps_ % per_control_ == 0) control();
        const double after = mj_->velocities()(last);
        const int before_mode = sign(w), after_mode = sign(after);
        if (before_mode != after_mode)  // a release counts from the step's start (the bit broke loose within it)
            add_event(before_mode == 0 ? mj_->time() - h_ : mj_->time(), before_mode, after_mode);
    }

    /// Columns and mode at t in the last step: its end, or (when kept) the state linear between its ends.
    int row(double t, double* out) const {
        const Eigen::VectorXd *q = nullptr, *v = nullptr;
        double t0 = 0.0, t1 = time(), held = control_->held;
        if (exact_) {
            q = &events_driver_->positions();
            v = &events_driver_->velocities();
            t0 = events_driver_->previous_time();
        } else {
            q = &mj_->positions();
            v = &mj_->velocities();
            t0 = start_.time;
        }
        const double a = (exact_ || kept_) && t1 > t0 ? std::clamp((t - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
        if (a < 1.0) {  // inside the step
            const Eigen::VectorXd& q0 = exact_ ? events_driver_->previous_positions() : start_.q;
            const Eigen::VectorXd& v0 = exact_ ? events_driver_->previous_velocities() : start_.v;
            interpolated_q_ = (1.0 - a) * q0 + a * *q;
            interpolated_v_ = (1.0 - a) * v0 + a * *v;
            q = &interpolated_q_;
            v = &interpolated_v_;
            held = start_.held;
        }
        const TorsionalStringParams& p = ts_.params();
        const bool held_speed = ts_.holds_speed();
        // node 0's speed: its dof's, or the prescribed one (its dof is held out of the inclusion, at rest)
        const auto speed = [&](Eigen::Index i) { return i == 0 && held_speed ? ts_.setpoint_speed(t) : (*v)(i); };
        out[0] = (*v)(n_ - 1);
        out[1] = speed(0);
        if (held_speed) out[2] = ts_.held_torque(t, (*q)(1), (*v)(1));
        else if (explicit_drive_) out[2] = held;
        else if (limited_)  // the step's mode: +-T_max, or the PI law with its integral (within the limit at the ends)
            out[2] = step_side_ != 0
                         ? step_side_ * p.torque_limit
                         : std::clamp(demand(t, (*v)(0), ts_.setpoint_angle(t) - (*q)(0) - control_->offset),
                                      -p.torque_limit, p.torque_limit);
        else
            out[2] = p.proportional_gain * (ts_.setpoint_speed(t) - (*v)(0)) +
                     p.integral_gain * (ts_.setpoint_angle(t) - (*q)(0));
        Eigen::Index stuck = 0;
        const double slow = ts_.slow_speed();
        for (Eigen::Index i = 0; i < n_; ++i) stuck += (slow > 0.0 ? std::abs(speed(i)) < slow : speed(i) == 0.0) ? 1 : 0;
        out[3] = static_cast<double>(stuck) / static_cast<double>(n_);
        // the mode column as StringRig's: the wall contacts at rest (captured: exactly, v == 0); the bit's own
        // modes are in the events
        int walls_at_rest = 0;
        for (std::size_t i : ts_.wall_contact_nodes()) walls_at_rest += speed(static_cast<Eigen::Index>(i)) == 0.0 ? 1 : 0;
        return walls_at_rest;
    }

    double friction_force() const {
        return (exact_ ? events_driver_->contact_forces() : mj_->contact_forces())(n_ - 1);
    }
    const std::vector<Event>& events() const { return events_; }
    /// The limited PI's integral int e at the last step's end (frozen while limited; the unlimited PI's is
    /// theta_SP - theta_0) and its mode over that step: 0 linear, +-1 at +-T_max.
    double drive_integral() const { return integral_; }
    int drive_side() const { return step_side_; }
    /// The captured string's node angles and speeds at the last step's end.
    const Eigen::VectorXd& positions() const { return exact_ ? events_driver_->positions() : mj_->positions(); }
    const Eigen::VectorXd& velocities() const { return exact_ ? events_driver_->velocities() : mj_->velocities(); }
    /// The contact torques of the last step, per node (0 where there is none).
    const Eigen::VectorXd& contact_forces() const {
        return exact_ ? events_driver_->contact_forces() : mj_->contact_forces();
    }
    /// Steps retaken in the limited PI's other mode (the step's guess was inconsistent at its end).
    long retaken_steps() const { return retaken_; }
    void add_stats(SolverStats& stats) const {
        MoreauJean::Statistics s;
        if (exact_) {
            const auto e = events_driver_->statistics();
            s = e.steps;
            stats.location_trials = e.trial_steps;
            stats.restarts = e.restarts;
        } else {
            s = mj_->statistics();
            if (limited_) {  // the operators replaced at mode changes, and the steps retaken: not counted as steps
                s.factorisations += retired_.factorisations;
                s.solves += retired_.solves;
                s.contact_switches += retired_.contact_switches;
                s.steps = steps_;
                stats.restarts = restarts_;
                stats.location_trials = retaken_;
            }
        }
        stats.steps = s.steps;
        stats.factorisations = s.factorisations;
        stats.linear_solves = s.solves;
        stats.contact_switches = s.contact_switches;
    }

private:
    /// The sampled PI's state: its output is held between samples (the MoreauJean force reads `held`). The limited
    /// continuous PI: `held` the torque at the limit, `offset` what its linear operator takes off the integral.
    struct Control {
        double held = 0.0, setpoint = 0.0, integral = 0.0, offset = 0.0;
    };
    struct Start {
        double time = 0.0;
        Eigen::VectorXd q, v;
        double held = 0.0;
    };

    static int sign(double v) { return v > 0.0 ? 1 : v < 0.0 ? -1 : 0; }

    /// A&S MAIN.m at a sampling instant: the set-point filter, then tau_m, then int e. With a limit (PiTopDrive's
    /// law): tau_m clamped to +-T_max and int e frozen while it is (anti-windup).
    void control() {
        const TorsionalStringParams& p = ts_.params();
        const double T = p.setpoint_time_constant, w = mj_->velocities()(0), limit = p.torque_limit;
        const double dt = p.control_period;
        Control& c = *control_;
        c.setpoint = T > 0.0 ? c.setpoint + (p.speed_setpoint - c.setpoint) * dt / T : p.speed_setpoint;
        const double u = p.proportional_gain * (c.setpoint - w) + p.integral_gain * c.integral;
        const bool limited = limit > 0.0 && std::abs(u) > limit;
        c.held = limited ? std::copysign(limit, u) : u;
        if (!limited) c.integral += dt * (c.setpoint - w);
    }

    /// The continuous PI's law before the limit at time t, top-drive speed w and integral I: k_p e + k_i I.
    double demand(double t, double w, double integral) const {
        const TorsionalStringParams& p = ts_.params();
        return p.proportional_gain * (ts_.setpoint_speed(t) - w) + p.integral_gain * integral;
    }

    /// Moreau-Jean on the operator of `side` (0 linear: the PI as damper and spring with the integral's offset;
    /// +-1: tau_m = +-T_max, the PI out of the operator) from the step's start (start_, integral_).
    void restart(int side) {
        const TorsionalStringParams& p = ts_.params();
        if (mj_) {
            const MoreauJean::Statistics& s = mj_->statistics();
            retired_.factorisations += s.factorisations;
            retired_.solves += s.solves;
            retired_.contact_switches += s.contact_switches;
            ++restarts_;
        }
        control_->held = side * p.torque_limit;
        control_->offset = ts_.setpoint_angle(start_.time) - start_.q(0) - integral_;
        mj_ = std::make_unique<MoreauJean>(side == 0 ? linear_system_ : limited_system_, options_, start_.q, start_.v,
                                           start_.time);
        operator_side_ = side;
    }

    /// One step of the torque-limited continuous PI, implicit: the step taken in the drive's mode guessed from the
    /// last (linear, or at the limit on one side), checked at its end and retaken from its start in the other mode
    /// when inconsistent. Linear is consistent when the PI law ends within the limit; at the limit on side s while
    /// the frozen law (the integral held) ends past it (PiTopDrive's modes +-1, the integral stays frozen) or the
    /// linear law, started on the limit, moves outward over the step: k_p (e_1 - e_0) + k_i int e, times s, >= 0
    /// (the sliding motion, modes +-2: the integral follows the limit, k_p e + k_i I = s T_max at the step's end).
    /// Where neither mode is consistent (the limit grazed within the step) the step at the limit is kept, its
    /// integral as the sliding motion's, and the next step starts linear.
    template <class Take>
    void step_limited(const Take& take) {
        const TorsionalStringParams& p = ts_.params();
        const double limit = p.torque_limit, t0 = start_.time, q0 = start_.q(0), i0 = integral_;
        const double e0 = ts_.setpoint_speed(t0) - start_.v(0);
        // the linear step's end: its integral and law
        const auto linear_end = [&](double& integral) {
            integral = ts_.setpoint_angle(mj_->time()) - mj_->positions()(0) - control_->offset;
            return demand(mj_->time(), mj_->velocities()(0), integral);
        };
        // the step at the limit on side s: consistent, and its integral at the end
        const auto limited_end = [&](int s, double& integral) {
            const double t1 = mj_->time(), e1 = ts_.setpoint_speed(t1) - mj_->velocities()(0);
            const double gathered = ts_.setpoint_angle(t1) - ts_.setpoint_angle(t0) - (mj_->positions()(0) - q0);
            const bool frozen_out = s * demand(t1, mj_->velocities()(0), i0) >= limit;
            const bool pushed_out = p.integral_gain > 0.0 &&
                                    s * (p.proportional_gain * (e1 - e0) + p.integral_gain * gathered) >= 0.0;
            const double follow = p.integral_gain > 0.0 ? (s * limit - p.proportional_gain * e1) / p.integral_gain : i0;
            integral = s * std::max(s * i0, s * follow);
            return frozen_out || pushed_out;
        };
        const auto accept_limited = [&](int s, bool consistent) {
            double integral = 0.0;
            limited_end(s, integral);
            integral_ = integral;
            step_side_ = s;
            side_ = consistent ? s : 0;  // grazed: the next step starts linear
        };
        const auto retake = [&](int side) {
            ++retaken_;
            restart(side);
            take();
        };
        if (operator_side_ != side_) restart(side_);
        take();
        double integral = 0.0;
        if (side_ == 0) {
            const double u = linear_end(integral);
            if (std::abs(u) <= limit) {
                integral_ = integral;
                step_side_ = 0;
                return;
            }
            const int s = sign(u);
            retake(s);
            accept_limited(s, limited_end(s, integral));
            return;
        }
        const int s = side_;
        if (limited_end(s, integral)) {
            accept_limited(s, true);
            return;
        }
        retake(0);  // released from the limit?
        const double u = linear_end(integral);
        if (std::abs(u) <= limit) {
            integral_ = integral;
            step_side_ = 0;
            side_ = 0;
            return;
        }
        const int back = sign(u);  // the limit grazed (or, in one step, the other limit reached): at the limit
        retake(back);
        accept_limited(back, limited_end(back, integral));
    }

    void add_event(double t, int before, int after) {
        Event e;
        e.time = t;
        e.switching_function = 0;
        e.name = "bit";
        e.mode_before = before;
        e.mode_after = after;
        e.mode_before_name = ts_.mode_name(before);
        e.mode_after_name = ts_.mode_name(after);
        events_.push_back(std::move(e));
    }

    const TorsionalString& ts_;
    double h_;
    Eigen::Index n_;
    bool sampled_ = false, explicit_drive_ = false, limited_ = false, exact_ = false, kept_ = false;
    long per_control_ = 0, steps_ = 0;
    std::unique_ptr<Control> control_;  // a stable address for the force closures
    std::unique_ptr<MoreauJean> mj_;
    std::unique_ptr<MoreauJeanEvents<LumpedFriction>> events_driver_;
    // the limited continuous PI: its two operators, its integral, the side guessed for the next step (0 linear),
    // the side of the step taken last and of the operator running
    LinearMechanicalSystem linear_system_, limited_system_;
    MoreauJeanOptions options_;
    double integral_ = 0.0;
    int side_ = 0, step_side_ = 0, operator_side_ = 2;
    long restarts_ = 0, retaken_ = 0;
    MoreauJean::Statistics retired_;
    Start start_;
    std::vector<Event> events_;
    mutable Eigen::VectorXd scratch_, interpolated_q_, interpolated_v_;
};

inline TorsionalString::Stepper TorsionalString::make_stepper(const TimeStepping& setup) const {
    return Stepper(*this, setup);
}

inline TorsionalStringRun TorsionalString::simulate(const TorsionalStringRunOptions& run) const {
    constexpr const char* who = "TorsionalStringRunOptions";
    detail::require_positive(who, "t_end", run.t_end);
    detail::require_positive(who, "step", run.step);
    const long per_output = steps_per(who, "output_interval", run.output_interval, run.step);
    TorsionalString model = *this;
    model.set_slow_speed(run.slow_speed).set_bit_treatment(run.bit_treatment, run.switch_tolerance);
    SolverOptions o;
    o.method = run.treatment == ContactTreatment::projection ? Method::explicit_projection : Method::moreau_jean;
    o.step = run.step;
    o.theta = run.theta;
    o.projection_band = run.projection_band;
    o.interrupt = run.interrupt;
    const long total = std::lround(run.t_end / run.step);
    for (long k = 0; k <= total; k += per_output) o.output_times.push_back(static_cast<double>(k) * run.step);
    const Result r = simulate_time_stepping(model, static_cast<double>(total) * run.step, o);
    TorsionalStringRun out;
    out.time = r.t;
    out.bit_speed = r.column_values("bit_speed");
    out.top_drive_speed = r.column_values("top_drive_speed");
    out.motor_torque = r.column_values("motor_torque");
    out.stuck_fraction = r.column_values("stuck_fraction");
    if (bit_on_bottom())
        for (const Event& e : r.events) {
            if (e.mode_after == 0) out.bit_stick_times.push_back(e.time);
            if (e.mode_before == 0) out.bit_release_times.push_back(e.time);
        }
    out.statistics.steps = r.stats.steps;
    out.statistics.factorisations = r.stats.factorisations;
    out.statistics.solves = r.stats.linear_solves;
    out.statistics.contact_switches = r.stats.contact_switches;
    out.bit_location_trials = r.stats.location_trials;
    return out;
}

/// The collar polar moment of A&S's parameters_WellB.m: its line p.Jc = pi * sum(L pi (OD^4 - ID^4) / 32) / sum(L)
/// carries an extra factor pi.
enum class CollarPolarMoment {
    as_published,  ///< with the extra pi (what the published results were computed with)
    corrected,     ///< the length-averaged pi (OD^4 - ID^4) / 32 of the four collar sections
};

/// The collar's torsional wave speed in A&S's torsionalWaveStep.m: it updates the collar's Riemann invariants with the
/// pipe's c_t = sqrt(G_p / rho), while its torque is J_c G_c times the strain. That is a collar of density
/// rho G_c / G_p (inertia and weight, hence wall friction, 67/61 = 1.098 times the steel's).
enum class CollarWaveSpeed {
    as_code,   ///< sqrt(G_p / rho), what the published results were computed with
    physical,  ///< sqrt(G_c / rho)
};

/// A&S's Well B (parameters_WellB.m, MAIN.m: mu 0.3, f_rat 0.65, 40 rpm) at measured depth `md`: 5.77" pipe and a
/// 230 m BHA averaged over its four sections (the tube with that area and polar moment; contact radius the averaged
/// OD / 2), G 61 / 67 GPa, rho 7850, I_TD 2900, k_p 38e3, k_i 100e3, the survey 0 / 0 / 60 / 60 deg at
/// 0 / 500 / 1600 / 4000 m, omega_c 1.5 rad/s, the code's PI sampled every 0.01 s, and its damping at its 1000-cell
/// grid: torsionalWaveStep.m multiplies k_t (alpha + beta) by its sub-step twice, so A&S eq 3's k_t = 50 acts as
/// 2 k_t dt_sub = 2 * 50 * 0.01 / 12 = 0.0833 1/s there (`damping_rate`). The side-by-side comparison uses
/// (as_published, as_code); a physically consistent Well B is (corrected, physical).
struct WellBCase {
    DrillString string;
    TorsionalStringParams params;
    Survey survey;
    std::vector<double> contact_radius;
};

inline WellBCase aarsnes_shor_well_b(CollarPolarMoment collar, CollarWaveSpeed wave_speed, double md = 2500.0) {
    const double lengths[4] = {48.700, 114.800, 56.700, 38.880};
    const double od[4] = {0.150473, 0.187322, 0.209550, 0.247280};
    const double id[4] = {0.096207, 0.098912, 0.071438, 0.123391};
    double total = 0.0, area = 0.0, polar = 0.0, radius = 0.0;
    for (int i = 0; i < 4; ++i) {
        total += lengths[i];
        area += lengths[i] * pi / 4.0 * (od[i] * od[i] - id[i] * id[i]);
        polar += lengths[i] * pi / 32.0 * (std::pow(od[i], 4) - std::pow(id[i], 4));
        radius += lengths[i] * od[i] / 2.0;
    }
    area /= total;
    polar /= total;
    radius /= total;
    if (collar == CollarPolarMoment::as_published) polar *= pi;
    // the tube with that area and polar moment: OD^2 - ID^2 = 4 A / pi, OD^2 + ID^2 = 8 J / A
    const double diff = 4.0 * area / pi, sum = 8.0 * polar / area;
    PipeSection pipe{}, bha{};
    pipe.outer_diameter = 0.146529;
    pipe.inner_diameter = 0.123024;
    pipe.shear_modulus = 61e9;
    pipe.density = 7850.0;
    pipe.length = md - 230.0;
    bha.outer_diameter = std::sqrt(0.5 * (sum + diff));
    bha.inner_diameter = std::sqrt(std::max(0.0, 0.5 * (sum - diff)));
    bha.shear_modulus = 67e9;
    bha.density = wave_speed == CollarWaveSpeed::as_code ? 7850.0 * 67.0 / 61.0 : 7850.0;
    bha.length = 230.0;
    TorsionalStringParams p;
    p.control_period = 0.01;
    p.stick_band_speed = 1.5;
    p.damping_rate = 2.0 * 50.0 * 0.01 / 12.0;
    const double build = 60.0 * pi / 180.0;
    return WellBCase{DrillString({pipe, bha}), p,
                     Survey({{0.0, 0.0, 0.0}, {500.0, 0.0, 0.0}, {1600.0, build, 0.0}, {4000.0, build, 0.0}}),
                     {pipe.outer_diameter / 2.0, radius}};
}

}  // namespace frictionsim
