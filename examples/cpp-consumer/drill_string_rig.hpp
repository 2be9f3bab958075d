// A user's own rig, written outside frictionsim against its installed headers: the lumped torsional drill string
// of the stick-slip literature. The top drive turns at a constant speed Omega; a string of stiffness k and
// damping c twists between it and the bit (inertia J); the rock acts on the bit through any FrictionLaw, at the
// bit radius r under the weight on bit W:
//   J dw/dt = k theta + c (Omega - w) - T_f,     dtheta/dt = Omega - w,     T_f = r F(r w, W)
// (theta: twist phi_top - phi_bit, w: bit speed). The bit's stick/slip is frictionsim::ContactSwitching<Law>,
// as in the library's AxialRig. Three running integrals close the energy balance:
//   drive_work = int (k theta + c (Omega - w)) Omega dt = kinetic + elastic energy change + friction_work
//                + damping_work,  friction_work = int T_f w dt,  damping_work = int c (Omega - w)^2 dt.
// It meets frictionsim's HybridSystem concept (solve/hybrid_system.hpp), so frictionsim::simulate runs it.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include <frictionsim/contact/switching.hpp>
#include <frictionsim/parameters.hpp>
#include <frictionsim/solve/hybrid_system.hpp>

namespace user {

struct DrillStringParams {
    double bit_inertia = 471.97;        ///< J, kg m^2
    double string_stiffness = 861.79;   ///< k, N m/rad
    double string_damping = 0.0;        ///< c, N m s/rad
    double top_drive_speed = 5.0;       ///< Omega, rad/s
    double weight_on_bit = 97347.0;     ///< W, N: the friction law's normal force
    double bit_radius = 0.155575;       ///< r, m: the law sees v_r = r w, the bit feels T_f = r F
};

template <class Law>
class DrillStringRig {
    static_assert(frictionsim::check_friction_law<Law>(), "DrillStringRig<Law>: Law must be a FrictionLaw");
    using Switching = frictionsim::ContactSwitching<Law>;
    static constexpr std::size_t Z = Law::state_count;
    using P = DrillStringParams;

public:
    static constexpr std::array<frictionsim::Field<P>, 6> fields{{
        {"bit_inertia", "J", "kg m^2", frictionsim::Rule::positive(), &P::bit_inertia, "Bit inertia."},
        {"string_stiffness", "k", "N m/rad", frictionsim::Rule::positive(), &P::string_stiffness, "String stiffness."},
        {"string_damping", "c", "N m s/rad", frictionsim::Rule::non_negative(), &P::string_damping, "String damping."},
        {"top_drive_speed", "Omega", "rad/s", frictionsim::Rule::positive(), &P::top_drive_speed, "Top-drive speed."},
        {"weight_on_bit", "W", "N", frictionsim::Rule::positive(), &P::weight_on_bit, "Weight on bit."},
        {"bit_radius", "r", "m", frictionsim::Rule::positive(), &P::bit_radius, "Bit radius."},
    }};
    static constexpr std::size_t state_size = 2 + Z + 3, guard_count = Switching::guard_count;
    static constexpr std::size_t twist = 0, bit_speed = 1, law_state = 2, friction_work = 2 + Z,
                                 damping_work = 3 + Z, drive_work = 4 + Z;

    DrillStringRig(const P& p, Law law) : p_(p), law_(std::move(law)) {
        frictionsim::validate_fields("DrillStringRig", p, fields);
    }
    const P& params() const { return p_; }

    /// k theta + c (Omega - w), N m: the string's torque on the bit, which is also what holds a stuck bit.
    double string_torque(const double* x) const {
        return p_.string_stiffness * x[twist] + p_.string_damping * (p_.top_drive_speed - x[bit_speed]);
    }
    double kinetic_and_elastic_energy(const double* x) const {
        return 0.5 * p_.bit_inertia * x[bit_speed] * x[bit_speed] + 0.5 * p_.string_stiffness * x[twist] * x[twist];
    }
    /// Friction torque at the bit, N m (what the Result records as friction_force). A stuck bit held within the
    /// static limit carries exactly the string torque, so that it stays exactly at rest (r (T / r) would round).
    double friction_force(double, const double* x, int mode) const {
        const double torque = string_torque(x), holding = torque / p_.bit_radius;
        const double force = Switching::force(law_, p_.bit_radius * x[bit_speed], p_.weight_on_bit, x + law_state,
                                              mode, holding);
        if constexpr (Law::has_stick)
            if (mode == frictionsim::stick && force == holding) return torque;
        return p_.bit_radius * force;
    }

    void rhs(double t, const double* x, int mode, double* dxdt) const {
        const double torque = string_torque(x), w = x[bit_speed], slip = p_.top_drive_speed - w;
        const double friction = friction_force(t, x, mode);
        dxdt[twist] = slip;
        dxdt[bit_speed] = (torque - friction) / p_.bit_inertia;
        if constexpr (Z > 0) law_.state_derivative(p_.bit_radius * w, p_.weight_on_bit, x + law_state, mode,
                                                   dxdt + law_state);
        dxdt[friction_work] = friction * w;
        dxdt[damping_work] = p_.string_damping * slip * slip;
        dxdt[drive_work] = torque * p_.top_drive_speed;
    }
    void guards(double, const double* x, int mode, double* g) const {
        Switching::guards(law_, p_.bit_radius * x[bit_speed], p_.weight_on_bit, mode, string_torque(x) / p_.bit_radius,
                          g);
    }
    int guard_direction(std::size_t i, int mode) const { return Switching::guard_direction(i, mode); }
    const char* guard_name(std::size_t i, int mode) const { return Switching::guard_name(law_, i, mode); }
    const char* mode_name(int mode) const { return Switching::mode_name(law_, mode); }
    int initial_mode(double, const double* x) const {
        return Switching::initial_mode(law_, p_.bit_radius * x[bit_speed], p_.weight_on_bit, x + law_state,
                                       string_torque(x) / p_.bit_radius);
    }
    int switch_mode(double, double* x, int mode, const int* fired) const {
        bool stop = false;
        const int next =
            Switching::switch_mode(law_, p_.weight_on_bit, mode, fired, string_torque(x) / p_.bit_radius, stop);
        if (stop) x[bit_speed] = 0.0;  // the bit reached w = 0: exactly at rest, stuck or reversing
        return next;
    }

    /// At rest, string untwisted: the bit starts stuck.
    std::array<double, state_size> initial_state() const { return {}; }
    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        n[twist] = "twist";
        n[bit_speed] = "bit_speed";
        if constexpr (Z > 0)
            for (std::size_t i = 0; i < Z; ++i) n[law_state + i] = Law::state_names[i];
        n[friction_work] = "friction_work";
        n[damping_work] = "damping_work";
        n[drive_work] = "drive_work";
        return n;
    }

private:
    P p_;
    Law law_;
};

}  // namespace user
