// The axial vibrating-sliding rig of paper 000 (eqs 5-9): a specimen of mass m pulled through a drive spring
// k_d whose end moves at v_d, sliding on a surface that vibrates as u = u0 sin(w t), with any friction law:
//   m x'' = F_d - F_F - F_g                                   (eq 6)
//   F_d = k_d (v_d t - x)                                      (eq 7)
//   v_r = x' - u0 w cos(w t)                                   (eq 8-9: velocity relative to the surface)
// F_g = m g opposes the sliding when the rig is vertical (the paper's rig is), 0 when horizontal.
// Besides position, velocity and the law's states, three running integrals make cycle means and the energy
// balance exact to solver tolerance: friction impulse int F_F dt, friction work int F_F x' dt and drive work
// int F_d v_d dt, with  drive work = kinetic + spring (+ potential) energy change + friction work.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <optional>
#include <utility>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../parameters.hpp"
#include "../solve/hybrid_system.hpp"
#include "../contact/switching.hpp"
#include "../outputs.hpp"

namespace frictionsim {

/// Defaults: paper 000's Fig. 7(a) dry case (u = 5 mm, f = 17 Hz, v_d = 60 mm/min, F_N = 90 N). The specimen
/// (170 x 30 x 5 mm of 45 steel, sec 2.1) weighs 0.2 kg. The paper does not give the drive stiffness k_d;
/// 2e4 N/m is chosen (stiff next to the shale contact's k_t = 30-40 N/mm of Fig. 10 only by a factor of 2).
/// Figure 7's caption prints v_d = 60 mm/s but the rig allows < 5 mm/s (Table 2) and Fig. 10 uses 0.001 m/s,
/// so it is read as 60 mm/min = 1e-3 m/s.
struct AxialRigParams {
    double mass = 0.2;                  ///< m, kg
    double drive_stiffness = 2e4;       ///< k_d, N/m
    double sliding_velocity = 1e-3;     ///< v_d, m/s
    double amplitude = 5e-3;            ///< u0, m
    double frequency = 17.0;            ///< f, Hz (w = 2 pi f)
    double normal_force = 90.0;         ///< F_N, N
    bool gravity = false;               ///< vertical rig: F_g = m g opposes +x
    double gravitational_acceleration = 9.81;  ///< g, m/s^2
    /// x(0), m. Default: 0 horizontally; vertically -m g / k_d, the spring preloaded to carry the weight.
    std::optional<double> initial_position;
    double initial_velocity = 0.0;      ///< x'(0), m/s

    /// The numeric parameters (gravity and initial_position, a switch and an optional value, are checked apart).
    static constexpr const char* rig_name = "AxialVibrationRig";  ///< as Python and the rig list name it
    static constexpr std::array<Field<AxialRigParams>, 8> fields();
    /// The Result's columns beside t and the law's states (state_names below).
    static constexpr std::array<RigOutput, 6> outputs() {
        return {{
            {"friction_force", "N", "friction force F_F on the specimen"},
            {"position", "m", "specimen position x"},
            {"velocity", "m/s", "specimen velocity x'"},
            {"friction_impulse", "N s", "int F_F dt"},
            {"friction_work", "J", "int F_F v_r dt: dissipated plus stored in the law"},
            {"drive_work", "J", "int F_d v_d dt = energy change + friction work"},
        }};
    }
};

inline constexpr std::array<Field<AxialRigParams>, 8> AxialRigParams::fields() {
    using P = AxialRigParams;
    return {{
        {"mass", "m", "kg", Rule::positive(), &P::mass, "Specimen mass (0.2 kg: 170 x 30 x 5 mm of 45 steel)."},
        {"drive_stiffness", "k_d", "N/m", Rule::positive(), &P::drive_stiffness, "Drive spring stiffness (not given by the paper; 2e4 N/m chosen)."},
        {"sliding_velocity", "v_d", "m/s", Rule::non_negative(), &P::sliding_velocity, "Drive (sliding) velocity."},
        {"amplitude", "u0", "m", Rule::non_negative(), &P::amplitude, "Vibration amplitude of the surface."},
        {"frequency", "f", "Hz", Rule::positive(), &P::frequency, "Vibration frequency (w = 2 pi f)."},
        {"normal_force", "F_N", "N", Rule::positive(), &P::normal_force, "Normal force."},
        {"gravitational_acceleration", "g", "m/s^2", Rule::non_negative(), &P::gravitational_acceleration, "Used when gravity is on (vertical rig)."},
        {"initial_velocity", "x'(0)", "m/s", Rule::finite(), &P::initial_velocity, "Initial velocity."},
    }};
}

template <class Law>
class AxialRig {
    static_assert(check_friction_law<Law>(), "AxialRig<Law>: Law must meet the FrictionLaw concept (see above)");

    using Switching = ContactSwitching<Law>;
    static constexpr std::size_t Z = Law::state_count;

public:
    using Params = AxialRigParams;
    static constexpr std::size_t state_size = 2 + Z + 3;
    static constexpr bool stiff = declares_stiff<Law>::value;  ///< picks the integrator under Method::automatic
    static constexpr std::size_t guard_count = Switching::guard_count;
    // state layout
    static constexpr std::size_t position = 0, velocity = 1, law_state = 2, friction_impulse = 2 + Z,
                                 friction_work = 3 + Z, drive_work = 4 + Z;

    AxialRig(const AxialRigParams& p, Law law) : p_(p), law_(std::move(law)) {
        constexpr const char* who = "AxialRig";
        validate_fields(who, p, AxialRigParams::fields());
        if (p.initial_position) detail::require_finite(who, "initial_position", *p.initial_position);
        omega_ = 2.0 * pi * p.frequency;
        weight_ = p.gravity ? p.mass * p.gravitational_acceleration : 0.0;
    }

    const AxialRigParams& params() const { return p_; }
    const Law& law() const { return law_; }
    double angular_frequency() const { return omega_; }
    double period() const { return 1.0 / p_.frequency; }
    /// v_a = u0 w (eq 16), m/s.
    double vibration_velocity_amplitude() const { return p_.amplitude * omega_; }

    double surface_velocity(double t) const { return p_.amplitude * omega_ * std::cos(omega_ * t); }
    double surface_acceleration(double t) const { return -p_.amplitude * omega_ * omega_ * std::sin(omega_ * t); }
    double drive_force(double t, const double* x) const {
        return p_.drive_stiffness * (p_.sliding_velocity * t - x[position]);  // eq 7
    }
    /// Friction force that keeps the specimen moving with the surface (relative acceleration zero).
    double stick_force(double t, const double* x) const {
        return drive_force(t, x) - weight_ - p_.mass * surface_acceleration(t);
    }
    double friction_force(double t, const double* x, int mode) const {
        return Switching::force(law_, x[velocity] - surface_velocity(t), p_.normal_force, x + law_state, mode,
                                stick_force(t, x));
    }
    /// Kinetic + spring + potential energy, J: what the drive work pays for beside friction.
    double mechanical_energy(double t, const double* x) const {
        const double stretch = p_.sliding_velocity * t - x[position];
        return 0.5 * p_.mass * x[velocity] * x[velocity] + 0.5 * p_.drive_stiffness * stretch * stretch +
               weight_ * x[position];
    }

    void rhs(double t, const double* x, int mode, double* dxdt) const { rhs_guards(t, x, mode, dxdt, nullptr); }

    /// The right-hand side and, into g unless null, the switching functions: one evaluation of the surface
    /// motion for both (Dormand-Prince reads the guards at its stages from this).
    void rhs_guards(double t, const double* x, int mode, double* dxdt, double* g) const {
        const double v_r = x[velocity] - surface_velocity(t);
        const double f_drive = drive_force(t, x);
        const double f_stick = f_drive - weight_ - p_.mass * surface_acceleration(t);
        if (g != nullptr) Switching::guards(law_, v_r, p_.normal_force, mode, f_stick, g);
        const double f_friction = Switching::force(law_, v_r, p_.normal_force, x + law_state, mode, f_stick);
        dxdt[position] = x[velocity];
        dxdt[velocity] = (f_drive - f_friction - weight_) / p_.mass;  // eq 6
        if constexpr (Z > 0) law_.state_derivative(v_r, p_.normal_force, x + law_state, mode, dxdt + law_state);
        dxdt[friction_impulse] = f_friction;
        dxdt[friction_work] = f_friction * x[velocity];
        dxdt[drive_work] = f_drive * p_.sliding_velocity;
    }

    /// Analytic Jacobian d(rhs)/dx, column-major (J[column * state_size + row]), entries not set left as given
    /// (CVODE zeroes J first).
    /// Only for laws with analytic partials (law_has_partials_v); CVODE builds the rest from difference quotients.
    template <class L = Law, std::enable_if_t<law_has_partials_v<L>, int> = 0>
    void jacobian(double t, const double* x, int mode, double* J) const {
        constexpr std::size_t n = state_size;
        const auto at = [&](std::size_t row, std::size_t column) -> double& { return J[column * n + row]; };
        const double v_r = x[velocity] - surface_velocity(t);
        const double f_stick = stick_force(t, x);
        const double f = Switching::force(law_, v_r, p_.normal_force, x + law_state, mode, f_stick);
        double df_dstick = 0.0;
        const StatePartials<Z> d =
            Switching::partials(law_, v_r, p_.normal_force, x + law_state, mode, f_stick, df_dstick);
        const double k = p_.drive_stiffness, m = p_.mass, v = x[velocity];
        const double df_dx = -k * df_dstick;  // the stick force falls with x through the drive spring
        at(position, velocity) = 1.0;
        at(velocity, position) = (-k - df_dx) / m;
        at(velocity, velocity) = -d.force_velocity / m;
        at(friction_impulse, position) = df_dx;
        at(friction_impulse, velocity) = d.force_velocity;
        at(friction_work, position) = v * df_dx;
        at(friction_work, velocity) = f + v * d.force_velocity;
        at(drive_work, position) = -k * p_.sliding_velocity;
        for (std::size_t j = 0; j < Z; ++j) {
            at(velocity, law_state + j) = -d.force_state[j] / m;
            at(friction_impulse, law_state + j) = d.force_state[j];
            at(friction_work, law_state + j) = v * d.force_state[j];
            at(law_state + j, velocity) = d.rate_velocity[j];
            for (std::size_t i = 0; i < Z; ++i) at(law_state + i, law_state + j) = d.rate_state[i][j];
        }
    }

    void guards(double t, const double* x, int mode, double* g) const {
        Switching::guards(law_, x[velocity] - surface_velocity(t), p_.normal_force, mode, stick_force(t, x), g);
    }
    int guard_direction(std::size_t i, int mode) const { return Switching::guard_direction(i, mode); }
    const char* guard_name(std::size_t i, int mode) const { return Switching::guard_name(law_, i, mode); }
    const char* mode_name(int mode) const { return Switching::mode_name(law_, mode); }

    int initial_mode(double t, const double* x) const {
        return Switching::initial_mode(law_, x[velocity] - surface_velocity(t), p_.normal_force, x + law_state,
                                       stick_force(t, x));
    }
    int switch_mode(double t, double* x, int mode, const int* fired) const {
        bool stop = false;
        const int next = Switching::switch_mode(law_, p_.normal_force, mode, fired, stick_force(t, x), stop);
        note_reversal(law_, p_.normal_force, x + law_state, mode, next);  // a memory of turning points (Leuven)
        if (stop) x[velocity] = surface_velocity(t);  // v_r = 0 exactly: the new mode's guard starts at zero
        return next;
    }

    std::array<double, state_size> initial_state() const {
        std::array<double, state_size> x{};
        x[position] = p_.initial_position ? *p_.initial_position : -weight_ / p_.drive_stiffness;
        x[velocity] = p_.initial_velocity;
        return x;
    }

    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        n[position] = "position";
        n[velocity] = "velocity";
        if constexpr (Z > 0)
            for (std::size_t i = 0; i < Z; ++i) n[law_state + i] = Law::state_names[i];
        n[friction_impulse] = "friction_impulse";
        n[friction_work] = "friction_work";
        n[drive_work] = "drive_work";
        return n;
    }

private:
    AxialRigParams p_;
    Law law_;
    double omega_ = 0.0, weight_ = 0.0;
};

}  // namespace frictionsim
