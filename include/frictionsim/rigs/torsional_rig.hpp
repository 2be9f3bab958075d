// The torsional drill-string rig of paper 001 (eqs 1-5): disc D2 (J2) on a shaft (k2, d2) driven by a DC motor
// through a gear eta:1 under PI speed control, with friction on the disc. In load-side (gear output) form:
//   J2 dw2/dt          = S - T_f2(w2, dw2/dt),        S = k2 (th3 - th2) + d2 (w3 - w2)            (eq 1a)
//   eta^2 J_m dw3/dt   = eta K_T i - eta^2 C_m w3 - eta T_f sgn(w3) - S                           (eqs 1b, 2b, 4)
//   L di/dt            = V - R i - eta K_E w3                                                       (eqs 2a, 4)
//   V                  = k_p (w_ref - w3) + k_i int (w_ref - w3) dt                                 (eq 3)
// which is eq 5. The motor's internal friction T_f acts against the motor's rotation, with stick at w3 = 0
// (Leine's switch model, the same contact logic as the disc's Coulomb friction).
//
// Reading of the paper's tables (docs/paper001_torsional_rig.md):
//  * J_m (eq 5) is the rotor inertia at the motor shaft. Table 1's J3 = 0.0237 kg m^2 ("DC-motor moment of
//    inertia", listed with the mechanical parameters of the disc side) is read as referred to the load side,
//    J_m = J3 / eta^2 = 3.70e-4 kg m^2; the literal reading J_m = 0.0237 is one parameter away and changes the
//    disc mode by 0.3 % (the PI loop makes the drive nearly rigid either way).
//  * Table 2's "DC-motor moment of inertia" = 3.5 is a misprint for the integral gain k_i of eq 3 (V/rad);
//    k_p = 2.8 V s/rad. Both gains act on the load-side speed w3.
//  * K_T = 0.126 N m/A and K_E = 0.0602 V s/rad are kept as printed (not equal, so the motor does not convert
//    power losslessly: the energy integrals below keep the mechanical and electrical balances apart).
//  * The normal force N2 on the disc is not in eqs 1-6; it scales the friction: F(v_r, N2) for the laws of
//    the engine, N2 / N_ref for eq 6.
//
// States: disc_angle th2, disc_speed w2, shaft_twist th3 - th2, drive_speed w3 (load side; the motor turns at
// eta w3), current i, speed_error_integral int (w_ref - w3) dt, the law's states, and five running integrals
// that make the energy balance exact to solver tolerance:
//   motor_work      int eta K_T i w3 dt   = stored mechanical energy change + friction_work + damping_work
//   friction_work   int T_f2 w2 dt        (dissipated at the disc)
//   damping_work    int [d2 (w3 - w2)^2 + eta^2 C_m w3^2 + eta T_f |w3|] dt
//   electrical_work int V i dt            = ohmic_work + L i^2 / 2 change + (K_E / K_T) motor_work
//   ohmic_work      int R i^2 dt
// Mode: the disc contact's mode, minus 16 while the motor sticks and minus 32 while it turns backwards
// (encode_mode), so that in normal operation the recorded mode is the disc's.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../parameters.hpp"
#include "../contact/disc_contact.hpp"
#include "../outputs.hpp"

namespace frictionsim {

/// Defaults: paper 001, Tables 1-2, at the Fig. 7 operating point (w_ref = 5.76 rad/s = 55 rpm, N2 = 35 N).
struct TorsionalRigParams {
    double disc_inertia = 0.0149;                 ///< J2, kg m^2 (Table 1)
    double shaft_stiffness = 0.3659;              ///< k2, N m/rad (Table 1)
    double shaft_damping = 0.0167;                ///< d2, N m s/rad (Table 1)
    double motor_inertia = 0.0237 / 64.0;         ///< J_m, kg m^2 at the motor shaft (Table 1's J3 / eta^2)
    double gear_ratio = 8.0;                      ///< eta (eq 4): motor speed = eta w3
    double inductance = 8.437e-4;                 ///< L, H (Table 2)
    double resistance = 0.33;                     ///< R, Ohm (Table 2)
    double torque_constant = 0.126;               ///< K_T, N m/A (Table 2)
    double back_emf_constant = 0.0602;            ///< K_E, V s/rad (Table 2)
    double motor_friction_torque = 0.1196;        ///< T_f, N m at the motor shaft (Table 2)
    double motor_viscous_coefficient = 1.784e-4;  ///< C_m, N m s/rad at the motor shaft (Table 2)
    double proportional_gain = 2.8;               ///< k_p, V s/rad (Table 2)
    double integral_gain = 3.5;                   ///< k_i, V/rad (Table 2, printed as "DC-motor moment of inertia")
    double reference_speed = 5.76;                ///< w_ref, rad/s on the load side (55 rpm)
    double normal_force = 35.0;                   ///< N2, N on the disc
    double contact_radius = 0.1;                  ///< r, m: where the engine's laws act (v_r = r w2, T = r F)
    double initial_disc_speed = 0.0;              ///< w2(0), rad/s
    double initial_drive_speed = 0.0;             ///< w3(0), rad/s

    static constexpr const char* rig_name = "TorsionalRig";  ///< as Python and the rig list name it
    static constexpr std::array<Field<TorsionalRigParams>, 18> fields();
    /// The Result's columns beside t and the law's states (state_names below).
    static constexpr std::array<RigOutput, 12> outputs() {
        return {{
            {"friction_force", "N m", "friction torque on the disc"},
            {"disc_angle", "rad", "disc angle"},
            {"disc_speed", "rad/s", "disc speed w2"},
            {"shaft_twist", "rad", "twist of the shaft between drive and disc"},
            {"drive_speed", "rad/s", "drive speed w3 (load side)"},
            {"current", "A", "motor current"},
            {"speed_error_integral", "rad", "int (w_ref - w3) dt of the PI speed loop"},
            {"motor_work", "J", "int eta K_T i w3 dt: stored energy change + friction + damping work"},
            {"friction_work", "J", "int T_f2 w2 dt, dissipated at the disc"},
            {"damping_work", "J", "the shaft's and the motor's viscous and Coulomb losses"},
            {"electrical_work", "J", "int V i dt into the armature"},
            {"ohmic_work", "J", "int R i^2 dt in the armature"},
        }};
    }
};

/// The parameter table of TorsionalRigParams: validation, Python keywords, properties, repr and pickling read it.
inline constexpr std::array<Field<TorsionalRigParams>, 18> TorsionalRigParams::fields() {
    using P = TorsionalRigParams;
    return {{
        {"disc_inertia", "J2", "kg m^2", Rule::positive(), &P::disc_inertia, "Disc inertia (Table 1)."},
        {"shaft_stiffness", "k2", "N m/rad", Rule::positive(), &P::shaft_stiffness, "Shaft stiffness (Table 1)."},
        {"shaft_damping", "d2", "N m s/rad", Rule::non_negative(), &P::shaft_damping, "Shaft damping (Table 1)."},
        {"motor_inertia", "J_m", "kg m^2", Rule::positive(), &P::motor_inertia, "Rotor inertia at the motor shaft (Table 1's J3 / eta^2)."},
        {"gear_ratio", "eta", "-", Rule::positive(), &P::gear_ratio, "Gear ratio (eq 4): motor speed = eta w3."},
        {"inductance", "L", "H", Rule::positive(), &P::inductance, "Armature inductance (Table 2)."},
        {"resistance", "R", "Ohm", Rule::positive(), &P::resistance, "Armature resistance (Table 2)."},
        {"torque_constant", "K_T", "N m/A", Rule::positive(), &P::torque_constant, "Motor torque constant (Table 2)."},
        {"back_emf_constant", "K_E", "V s/rad", Rule::non_negative(), &P::back_emf_constant, "Back-emf constant (Table 2)."},
        {"motor_friction_torque", "T_f", "N m", Rule::non_negative(), &P::motor_friction_torque, "Motor friction torque at the motor shaft (Table 2)."},
        {"motor_viscous_coefficient", "C_m", "N m s/rad", Rule::non_negative(), &P::motor_viscous_coefficient, "Motor viscous friction (Table 2)."},
        {"proportional_gain", "k_p", "V s/rad", Rule::non_negative(), &P::proportional_gain, "PI proportional gain (Table 2)."},
        {"integral_gain", "k_i", "V/rad", Rule::non_negative(), &P::integral_gain, "PI integral gain (Table 2, printed as \"DC-motor moment of inertia\")."},
        {"reference_speed", "w_ref", "rad/s", Rule::finite(), &P::reference_speed, "Reference speed, load side (eq 3)."},
        {"normal_force", "N2", "N", Rule::positive(), &P::normal_force, "Normal force on the disc."},
        {"contact_radius", "r", "m", Rule::positive(), &P::contact_radius, "Where the engine's laws act: v_r = r w2, T = r F."},
        {"initial_disc_speed", "w2(0)", "rad/s", Rule::finite(), &P::initial_disc_speed, "Initial disc speed."},
        {"initial_drive_speed", "w3(0)", "rad/s", Rule::finite(), &P::initial_drive_speed, "Initial drive speed (load side)."},
    }};
}

namespace detail {
/// The motor's internal friction as a set-valued law for ContactSwitching: T_f against the rotation, stick
/// while the torque needed to hold the motor stays within T_f. Torques on the load side (eta T_f).
struct MotorFriction {
    static constexpr const char* name = "MotorFriction";
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;
    double limit;
    double static_limit(double) const { return limit; }
    double slip_force(double, double, int direction) const { return direction * limit; }
    double slip_slope(double, double, int) const { return 0.0; }
    double karnopp_band() const { return 0.0; }
};
}  // namespace detail

template <class Law>
class TorsionalRig {
    using Disc = DiscContact<Law>;
    using Motor = ContactSwitching<detail::MotorFriction>;
    static constexpr std::size_t Z = Disc::state_count;
    static constexpr std::size_t disc_guards = Disc::guard_count;

public:
    using Params = TorsionalRigParams;
    static constexpr std::size_t state_size = 6 + Z + 5;
    static constexpr std::size_t guard_count = disc_guards + Motor::guard_count;
    static constexpr bool stiff = Disc::stiff;
    // state layout
    static constexpr std::size_t disc_angle = 0, disc_speed = 1, shaft_twist = 2, drive_speed = 3, current = 4,
                                 speed_error_integral = 5, law_state = 6, motor_work = 6 + Z,
                                 friction_work = 7 + Z, damping_work = 8 + Z, electrical_work = 9 + Z,
                                 ohmic_work = 10 + Z;

    /// Recorded mode = disc mode + 16 (motor mode - 1): the disc's mode while the motor turns forwards.
    static int encode_mode(int disc_mode, int motor_mode) { return disc_mode + 16 * (motor_mode - 1); }
    static int disc_mode_of(int mode) { return mode - 16 * (motor_mode_of(mode) - 1); }
    /// 1 + floor((mode + 8) / 16) in integers: recorded modes are >= -40, so mode + 56 is positive.
    static int motor_mode_of(int mode) { return (mode + 56) / 16 - 2; }

    TorsionalRig(const TorsionalRigParams& p, Law law) : p_(validated(p)), disc_(std::move(law), p.contact_radius, p.normal_force) {
        const double eta = p_.gear_ratio;
        motor_inertia_ = eta * eta * p_.motor_inertia;
        motor_viscous_ = eta * eta * p_.motor_viscous_coefficient;
        motor_ = detail::MotorFriction{eta * p_.motor_friction_torque};
        for (int motor : {slip_positive, stick, slip_negative})
            for (int disc : Disc::modes) {
                std::string n = disc_.mode_name(disc);
                if (motor == stick) n += "+motor_stick";
                if (motor == slip_negative) n += "+motor_reversed";
                mode_names_.emplace_back(encode_mode(disc, motor), std::move(n));
            }
    }

    const TorsionalRigParams& params() const { return p_; }
    const Law& law() const { return disc_.law(); }
    /// sqrt(k2 / J2) / 2 pi, Hz: the disc on a rigidly held shaft end.
    double natural_frequency() const { return std::sqrt(p_.shaft_stiffness / p_.disc_inertia) / (2.0 * pi); }

    /// S = k2 (th3 - th2) + d2 (w3 - w2), N m: the shaft's torque on the disc.
    double shaft_torque(const double* x) const {
        return p_.shaft_stiffness * x[shaft_twist] + p_.shaft_damping * (x[drive_speed] - x[disc_speed]);
    }
    /// V = k_p (w_ref - w3) + k_i int (w_ref - w3) dt, V (eq 3).
    double voltage(const double* x) const {
        return p_.proportional_gain * (p_.reference_speed - x[drive_speed]) +
               p_.integral_gain * x[speed_error_integral];
    }
    /// Disc friction torque T_f2, N m (eq 6 or r F).
    double friction_force(double, const double* x, int mode) const {
        return disc_.respond(x[disc_speed], shaft_torque(x), x + law_state, disc_mode_of(mode), p_.disc_inertia)
            .torque;
    }
    /// Disc acceleration dw2/dt, rad/s^2, in `mode`.
    double disc_acceleration(const double* x, int mode) const {
        return disc_.respond(x[disc_speed], shaft_torque(x), x + law_state, disc_mode_of(mode), p_.disc_inertia)
            .acceleration;
    }
    /// Kinetic energy of disc and motor + elastic energy of the shaft, J (magnetic energy L i^2 / 2 apart).
    double stored_mechanical_energy(const double* x) const {
        return 0.5 * p_.disc_inertia * x[disc_speed] * x[disc_speed] +
               0.5 * motor_inertia_ * x[drive_speed] * x[drive_speed] +
               0.5 * p_.shaft_stiffness * x[shaft_twist] * x[shaft_twist];
    }

    void rhs(double t, const double* x, int mode, double* dxdt) const { rhs_guards(t, x, mode, dxdt, nullptr); }

    /// The right-hand side and, into g unless null, the switching functions, sharing the shaft and motor torques.
    void rhs_guards(double, const double* x, int mode, double* dxdt, double* g) const {
        const double w2 = x[disc_speed], w3 = x[drive_speed], i = x[current];
        const double s = shaft_torque(x);
        const int disc_mode = disc_mode_of(mode), motor_mode = motor_mode_of(mode);
        const DiscResponse disc = disc_.respond(w2, s, x + law_state, disc_mode, p_.disc_inertia);
        const double held = motor_holding_torque(x, s);
        if (g != nullptr) fill_guards(x, disc_mode, motor_mode, s, held, g);
        const double motor_friction = Motor::force(motor_, w3, 1.0, nullptr, motor_mode, held);
        const double v = voltage(x);
        dxdt[disc_angle] = w2;
        dxdt[disc_speed] = disc.acceleration;
        dxdt[shaft_twist] = w3 - w2;
        dxdt[drive_speed] = (held - motor_friction) / motor_inertia_;
        dxdt[current] = (v - p_.resistance * i - p_.gear_ratio * p_.back_emf_constant * w3) / p_.inductance;
        dxdt[speed_error_integral] = p_.reference_speed - w3;
        if constexpr (Z > 0) disc_.state_derivative(w2, x + law_state, disc_mode, dxdt + law_state);
        dxdt[motor_work] = p_.gear_ratio * p_.torque_constant * i * w3;
        dxdt[friction_work] = disc.torque * w2;
        dxdt[damping_work] = p_.shaft_damping * (w3 - w2) * (w3 - w2) + motor_viscous_ * w3 * w3 + motor_friction * w3;
        dxdt[electrical_work] = v * i;
        dxdt[ohmic_work] = p_.resistance * i * i;
    }

    /// Analytic Jacobian d(rhs)/dx, column-major (J[column * state_size + row]); CVODE zeroes J first.
    /// Only for laws with analytic partials (law_has_partials_v); CVODE builds the rest from difference quotients.
    template <class L = Law, std::enable_if_t<std::is_same_v<L, HystereticFriction> || law_has_partials_v<L>, int> = 0>
    void jacobian(double, const double* x, int mode, double* J) const {
        constexpr std::size_t n = state_size;
        const auto at = [&](std::size_t row, std::size_t column) -> double& { return J[column * n + row]; };
        const double w2 = x[disc_speed], w3 = x[drive_speed], i = x[current];
        const double s = shaft_torque(x), k2 = p_.shaft_stiffness, d2 = p_.shaft_damping;
        const double eta = p_.gear_ratio, kt = p_.torque_constant, J2 = p_.disc_inertia;
        const int disc_mode = disc_mode_of(mode);
        const DiscResponse disc = disc_.respond(w2, s, x + law_state, disc_mode, J2);
        const DiscPartials<Z> d = disc_.partials(w2, s, x + law_state, disc_mode, J2);
        // S = k2 twist + d2 (w3 - w2); T = T(w2, S, z)
        const double dT_dw2 = d.torque_speed - d2 * d.torque_shaft, dT_dtwist = k2 * d.torque_shaft,
                     dT_dw3 = d2 * d.torque_shaft;
        at(disc_angle, disc_speed) = 1.0;
        at(disc_speed, disc_speed) = (-d2 - dT_dw2) / J2;
        at(disc_speed, shaft_twist) = (k2 - dT_dtwist) / J2;
        at(disc_speed, drive_speed) = (d2 - dT_dw3) / J2;
        at(shaft_twist, drive_speed) = 1.0;
        at(shaft_twist, disc_speed) = -1.0;
        // motor: (held - T_m) / (eta^2 J_m); a holding motor friction (stick inside the limit) cancels `held`
        const double held = motor_holding_torque(x, s);
        double motor_slope = 0.0;
        (void)Motor::partials(motor_, w3, 1.0, nullptr, motor_mode_of(mode), held, motor_slope);
        const double free = 1.0 - motor_slope;  // d(held - T_m) = free * d(held)
        const double motor_friction = Motor::force(motor_, w3, 1.0, nullptr, motor_mode_of(mode), held);
        const double dheld_di = eta * kt, dheld_dw3 = -motor_viscous_ - d2, dheld_dtwist = -k2, dheld_dw2 = d2;
        at(drive_speed, current) = free * dheld_di / motor_inertia_;
        at(drive_speed, drive_speed) = free * dheld_dw3 / motor_inertia_;
        at(drive_speed, shaft_twist) = free * dheld_dtwist / motor_inertia_;
        at(drive_speed, disc_speed) = free * dheld_dw2 / motor_inertia_;
        at(current, drive_speed) = (-p_.proportional_gain - eta * p_.back_emf_constant) / p_.inductance;
        at(current, current) = -p_.resistance / p_.inductance;
        at(current, speed_error_integral) = p_.integral_gain / p_.inductance;
        at(speed_error_integral, drive_speed) = -1.0;
        for (std::size_t j = 0; j < Z; ++j) {
            at(disc_speed, law_state + j) = -d.torque_state[j] / J2;
            at(friction_work, law_state + j) = w2 * d.torque_state[j];
            at(law_state + j, disc_speed) = d.rate_speed[j];
            for (std::size_t k = 0; k < Z; ++k) at(law_state + k, law_state + j) = d.rate_state[k][j];
        }
        at(motor_work, current) = eta * kt * w3;
        at(motor_work, drive_speed) = eta * kt * i;
        at(friction_work, disc_speed) = disc.torque + w2 * dT_dw2;
        at(friction_work, shaft_twist) = w2 * dT_dtwist;
        at(friction_work, drive_speed) = w2 * dT_dw3;
        // damping: d2 (w3 - w2)^2 + eta^2 C_m w3^2 + T_m w3, with dT_m = motor_slope * d(held)
        at(damping_work, disc_speed) = -2.0 * d2 * (w3 - w2) + w3 * motor_slope * dheld_dw2;
        at(damping_work, drive_speed) =
            2.0 * d2 * (w3 - w2) + 2.0 * motor_viscous_ * w3 + motor_friction + w3 * motor_slope * dheld_dw3;
        at(damping_work, shaft_twist) = w3 * motor_slope * dheld_dtwist;
        at(damping_work, current) = w3 * motor_slope * dheld_di;
        at(electrical_work, current) = voltage(x);
        at(electrical_work, drive_speed) = -p_.proportional_gain * i;
        at(electrical_work, speed_error_integral) = p_.integral_gain * i;
        at(ohmic_work, current) = 2.0 * p_.resistance * i;
    }

    void guards(double, const double* x, int mode, double* g) const {
        const double s = shaft_torque(x);
        fill_guards(x, disc_mode_of(mode), motor_mode_of(mode), s, motor_holding_torque(x, s), g);
    }
    int guard_direction(std::size_t i, int mode) const {
        return i < disc_guards ? disc_.guard_direction(i, disc_mode_of(mode)) : -1;
    }
    const char* guard_name(std::size_t i, int mode) const {
        if (i < disc_guards) return disc_.guard_name(i, disc_mode_of(mode));
        return motor_mode_of(mode) == stick ? (i == disc_guards ? "motor_breakaway_positive" : "motor_breakaway_negative")
                                            : "motor_speed";
    }
    const char* mode_name(int mode) const {
        for (const auto& [m, n] : mode_names_)
            if (m == mode) return n.c_str();
        return "unknown";
    }

    int initial_mode(double, const double* x) const {
        const double s = shaft_torque(x);
        const int disc = disc_.initial_mode(x[disc_speed], s, x + law_state, p_.disc_inertia);
        const int motor = Motor::initial_mode(motor_, x[drive_speed], 1.0, nullptr, motor_holding_torque(x, s));
        return encode_mode(disc, motor);
    }
    int switch_mode(double t, double* x, int mode, const int* fired) const {
        int disc = disc_mode_of(mode), motor = motor_mode_of(mode);
        bool disc_fired = false, motor_fired = false;
        for (std::size_t i = 0; i < guard_count; ++i)
            (i < disc_guards ? disc_fired : motor_fired) |= fired[i] != 0;
        const double s = shaft_torque(x);
        if (disc_fired)
            disc = disc_.switch_mode(t, x[disc_speed], s, x + law_state, disc, fired, p_.disc_inertia);
        if (motor_fired) {
            bool stop = false;
            motor = Motor::switch_mode(motor_, 1.0, motor, fired + disc_guards, motor_holding_torque(x, s), stop);
            if (stop) x[drive_speed] = 0.0;
        }
        return encode_mode(disc, motor);
    }

    std::array<double, state_size> initial_state() const {
        std::array<double, state_size> x{};
        x[disc_speed] = p_.initial_disc_speed;
        x[drive_speed] = p_.initial_drive_speed;
        return x;
    }
    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        n[disc_angle] = "disc_angle";
        n[disc_speed] = "disc_speed";
        n[shaft_twist] = "shaft_twist";
        n[drive_speed] = "drive_speed";
        n[current] = "current";
        n[speed_error_integral] = "speed_error_integral";
        if constexpr (Z > 0)
            for (std::size_t k = 0; k < Z; ++k) n[law_state + k] = Law::state_names[k];
        n[motor_work] = "motor_work";
        n[friction_work] = "friction_work";
        n[damping_work] = "damping_work";
        n[electrical_work] = "electrical_work";
        n[ohmic_work] = "ohmic_work";
        return n;
    }

private:
    static const TorsionalRigParams& validated(const TorsionalRigParams& p) {
        validate_fields("TorsionalRig", p, TorsionalRigParams::fields());
        return p;
    }

    /// The disc's guards, then the motor's, at shaft torque s and motor holding torque `held`.
    void fill_guards(const double* x, int disc_mode, int motor_mode, double s, double held, double* g) const {
        disc_.guards(x[disc_speed], s, x + law_state, disc_mode, p_.disc_inertia, g);
        Motor::guards(motor_, x[drive_speed], 1.0, motor_mode, held, g + disc_guards);
    }

    /// Torque (load side) that the motor's friction must supply to hold dw3/dt = 0.
    double motor_holding_torque(const double* x, double shaft) const {
        return p_.gear_ratio * p_.torque_constant * x[current] - motor_viscous_ * x[drive_speed] - shaft;
    }

    TorsionalRigParams p_;
    Disc disc_;
    detail::MotorFriction motor_{0.0};
    double motor_inertia_ = 0.0, motor_viscous_ = 0.0;
    std::vector<std::pair<int, std::string>> mode_names_;
};

}  // namespace frictionsim
