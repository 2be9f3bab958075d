// Dahl friction, paper 000 eq 9 in Dahl's original sign-preserving form (Dahl 1968):
//   dz/dt = v_r * sgn(b) |b|^alpha,  b = 1 - (k_t / (mu N)) sgn(v_r) z,   F = k_t z.
// For alpha = 1 (the paper's choice) this is eq 9 exactly. The right-hand side has a kink at v_r = 0: the rig
// locates it as an event and `branch` (= sgn v_r between events) selects the side.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "../parameters.hpp"
#include "law.hpp"

namespace frictionsim {

class Dahl {
public:
    static constexpr const char* name = "Dahl";
    static constexpr const char* key = "dahl";
    /// What Python's help() shows above the parameter list (the bindings add that from `fields`).
    static constexpr const char* description = R"doc(Dahl friction (paper 000, eq 9; Dahl 1968): a bristle deflection z with

    dz/dt = v_r sgn(b) |b|^alpha,   b = 1 - k_t z sgn(v_r) / (mu F_N),   F = k_t z.

The force rises with slope k_t from a reversal and saturates at mu F_N. The kink of dz/dt at v_r = 0 is
located as an event.)doc";
    static constexpr bool has_stick = false;
    static constexpr bool kink_at_zero_velocity = true;
    static constexpr std::size_t state_count = 1;
    static constexpr std::array<const char*, 1> state_names{"dahl_deflection"};  ///< z, m
    static constexpr std::array<const char*, 1> state_units{"m"};  ///< SI, the Results' and files' units

    /// Range of alpha. Below 1 the saturation b = 0 is reached at a finite sliding distance with an unbounded
    /// slope d(dz/dt)/dz ~ |b|^(alpha - 1), which step-size control resolves ever more slowly (measured on the
    /// axial rig, 0.5 s: 2.1e3 steps at alpha = 1, 2.9e4 at 0.5, 4.9e5 at 0.3, 2.1e6 at 0.2, over 1e7 at 0.1).
    /// Above the maximum, |b|^alpha after a reversal (b up to 2) spans more than 15 decades.
    static constexpr double min_exponent = 0.5, max_exponent = 50.0;

    struct Params {
        double friction_coefficient = 0.41;  ///< mu: saturation force mu N
        double tangential_stiffness = 4e4;   ///< k_t, N/m
        double exponent = 1.0;               ///< alpha (1 in paper 000)
    };
    static constexpr std::array<Field<Params>, 3> fields{{
        {"friction_coefficient", "mu", "-", Rule::positive(), &Params::friction_coefficient,
         "Friction coefficient (saturation force mu F_N).", "mu", true},
        {"tangential_stiffness", "k_t", "N/m", Rule::positive(), &Params::tangential_stiffness,
         "Tangential contact stiffness (paper 000 fits 30-40 N/mm for shale on 45 steel, Fig. 10).", nullptr, true},
        {"exponent", "alpha", "-",
         Rule::interval(min_exponent, max_exponent)
             .because("below 0.5 the saturation is reached with an unbounded slope that no step-size control "
                      "resolves in reasonable time: 0.2 took 2.1 million steps for 0.5 s"),
         &Params::exponent, "Shape exponent (1 in the paper).", nullptr},
    }};

    explicit Dahl(const Params& p) : mu_(p.friction_coefficient), k_t_(p.tangential_stiffness), alpha_(p.exponent) {
        validate_fields(name, p, fields);
    }
    /// mu (dimensionless), k_t (N/m), alpha in [0.5, 50] (dimensionless).
    Dahl(double friction_coefficient, double tangential_stiffness, double exponent = 1.0)
        : Dahl(Params{friction_coefficient, tangential_stiffness, exponent}) {}

    Params params() const { return Params{mu_, k_t_, alpha_}; }
    double friction_coefficient() const { return mu_; }
    double tangential_stiffness() const { return k_t_; }
    double exponent() const { return alpha_; }

    double force(double /*v_r*/, double /*normal_force*/, const double* z, int /*branch*/) const {
        return k_t_ * z[0];
    }
    void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const {
        const double b = 1.0 - k_t_ / (mu_ * normal_force) * branch * z[0];
        const double shaped = alpha_ == 1.0 ? b : std::copysign(std::pow(std::abs(b), alpha_), b);
        dz[0] = v_r * shaped;
    }

    StatePartials<1> partials(double v_r, double normal_force, const double* z, int branch) const {
        const double c = k_t_ / (mu_ * normal_force) * branch;
        const double b = 1.0 - c * z[0];
        const double shaped = alpha_ == 1.0 ? b : std::copysign(std::pow(std::abs(b), alpha_), b);
        const double slope = alpha_ == 1.0 ? 1.0 : (b == 0.0 ? 0.0 : alpha_ * std::pow(std::abs(b), alpha_ - 1.0));
        StatePartials<1> p;
        p.force_state[0] = k_t_;
        p.rate_velocity[0] = shaped;
        p.rate_state[0][0] = -v_r * slope * c;
        return p;
    }

private:
    double mu_, k_t_, alpha_;
};

}  // namespace frictionsim
