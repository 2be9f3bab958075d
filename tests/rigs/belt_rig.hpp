// A toy rig written as a new rig would be (issue 22 item 4: what adding a rig takes): a block of mass m on a belt
// moving at v_b, held by a spring k to a wall, with any friction law between block and belt:
//   m x'' = -k x + F,   F = -F_law(v_r),   v_r = x' - v_b   (the law acts against the block's slip on the belt)
// States: x, x', the law's states, friction_work int F_law v_r dt (dissipated, plus stored in a law) and belt_work
// int F_law v_b dt (what the belt delivers) = mechanical energy change + friction_work.
// Everything a rig of EngineRigs needs: a Params table with rig_name, description and outputs, and the HybridSystem
// members, with ContactSwitching for the contact.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include <frictionsim/contact/switching.hpp>
#include <frictionsim/detail/validate.hpp>
#include <frictionsim/parameters.hpp>
#include <frictionsim/outputs.hpp>

namespace frictionsim::test {

struct BeltRigParams {
    static constexpr const char* rig_name = "BeltRig";
    static constexpr const char* description =
        "A block of mass m on a belt moving at v_b, held to a wall by a spring k: m x'' = -k x - F(x' - v_b).";
    double mass = 1.0;           ///< m, kg
    double stiffness = 100.0;    ///< k, N/m
    double belt_speed = 0.1;     ///< v_b, m/s
    double normal_force = 10.0;  ///< N, N

    static constexpr std::array<Field<BeltRigParams>, 4> fields() {
        using P = BeltRigParams;
        return {{
            {"mass", "m", "kg", Rule::positive(), &P::mass, "Block mass."},
            {"stiffness", "k", "N/m", Rule::positive(), &P::stiffness, "Spring to the wall."},
            {"belt_speed", "v_b", "m/s", Rule::finite(), &P::belt_speed, "Belt speed."},
            {"normal_force", "N", "N", Rule::positive(), &P::normal_force, "Block weight on the belt."},
        }};
    }
    static constexpr std::array<RigOutput, 5> outputs() {
        return {{
            {"friction_force", "N", "friction force of the belt on the block"},
            {"position", "m", "block position x (spring relaxed at 0)"},
            {"velocity", "m/s", "block velocity x'"},
            {"friction_work", "J", "int F v_r dt"},
            {"belt_work", "J", "int F v_b dt = energy change + friction work"},
        }};
    }
};

template <class Law>
class BeltRig {
    using Switching = ContactSwitching<Law>;
    static constexpr std::size_t Z = Law::state_count;

public:
    using Params = BeltRigParams;
    static constexpr std::size_t state_size = 2 + Z + 2;
    static constexpr bool stiff = false;
    static constexpr std::size_t guard_count = Switching::guard_count;
    static constexpr std::size_t position = 0, velocity = 1, law_state = 2, friction_work = 2 + Z, belt_work = 3 + Z;

    BeltRig(const Params& p, Law law) : p_(p), law_(std::move(law)) { validate_fields("BeltRig", p, Params::fields()); }

    /// The law's force that keeps the block on the belt (x'' = 0): it balances the spring.
    double stick_force(const double* x) const { return -p_.stiffness * x[position]; }
    double friction_force(double, const double* x, int mode) const {
        return Switching::force(law_, x[velocity] - p_.belt_speed, p_.normal_force, x + law_state, mode,
                                stick_force(x));
    }
    void rhs(double t, const double* x, int mode, double* dxdt) const {
        const double v_r = x[velocity] - p_.belt_speed;
        const double f = friction_force(t, x, mode);
        dxdt[position] = x[velocity];
        dxdt[velocity] = (-p_.stiffness * x[position] - f) / p_.mass;
        if constexpr (Z > 0) law_.state_derivative(v_r, p_.normal_force, x + law_state, mode, dxdt + law_state);
        dxdt[friction_work] = f * v_r;
        dxdt[belt_work] = -f * p_.belt_speed;
    }
    void guards(double, const double* x, int mode, double* g) const {
        Switching::guards(law_, x[velocity] - p_.belt_speed, p_.normal_force, mode, stick_force(x), g);
    }
    int guard_direction(std::size_t i, int mode) const { return Switching::guard_direction(i, mode); }
    const char* guard_name(std::size_t i, int mode) const { return Switching::guard_name(law_, i, mode); }
    const char* mode_name(int mode) const { return Switching::mode_name(law_, mode); }
    int initial_mode(double, const double* x) const {
        return Switching::initial_mode(law_, x[velocity] - p_.belt_speed, p_.normal_force, x + law_state,
                                       stick_force(x));
    }
    int switch_mode(double, double* x, int mode, const int* fired) const {
        bool stop = false;
        const int next = Switching::switch_mode(law_, p_.normal_force, mode, fired, stick_force(x), stop);
        note_reversal(law_, p_.normal_force, x + law_state, mode, next);
        if (stop) x[velocity] = p_.belt_speed;  // v_r = 0 exactly
        return next;
    }
    std::array<double, state_size> initial_state() const { return {}; }
    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        n[position] = "position";
        n[velocity] = "velocity";
        if constexpr (Z > 0)
            for (std::size_t i = 0; i < Z; ++i) n[law_state + i] = Law::state_names[i];
        n[friction_work] = "friction_work";
        n[belt_work] = "belt_work";
        return n;
    }

private:
    Params p_;
    Law law_;
};

}  // namespace frictionsim::test
