// Coulomb friction with separate static and kinetic coefficients (paper 000 eq 8 for slip). The rig holds
// stick while the force needed to keep v_r = 0 stays within mu_s N (Leine's switch model).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "../parameters.hpp"
#include "law.hpp"

namespace frictionsim {

class Coulomb {
public:
    static constexpr const char* name = "Coulomb";
    static constexpr bool has_stick = true;
    static constexpr const char* key = "coulomb";
    /// What Python's help() shows above the parameter list (the bindings add that from `fields`).
    static constexpr const char* description = R"doc(Coulomb friction with static and kinetic coefficients (paper 000, eq 8).

Slip: F = mu F_N sgn(v_r). Stick (in rigs with a mass): the contact holds v_r = 0 while the force needed
stays within mu_static F_N (Leine's switch model), located exactly as events.)doc";
    static constexpr std::size_t state_count = 0;

    struct Params {
        double friction_coefficient = 0.3;                                      ///< mu, kinetic
        double static_coefficient = std::numeric_limits<double>::quiet_NaN();  ///< mu_s >= mu; NaN: equal to mu
    };
    static constexpr std::array<Field<Params>, 2> fields{{
        {"friction_coefficient", "mu", "-", Rule::positive(), &Params::friction_coefficient,
         "Kinetic (sliding) friction coefficient.", "mu", true},
        {"static_coefficient", "mu_s", "-", Rule::at_least_field("friction_coefficient").or_unset(),
         &Params::static_coefficient, "Static (breakaway) coefficient; unset (None, NaN): equal to mu.", "mu_static"},
    }};

    explicit Coulomb(const Params& p) : mu_(p.friction_coefficient), mu_static_(p.static_coefficient) {
        validate_fields(name, p, fields);
        if (std::isnan(mu_static_)) mu_static_ = mu_;
    }
    /// mu (kinetic) and mu_s (static, >= mu; NaN means equal to mu). Dimensionless.
    explicit Coulomb(double friction_coefficient,
                     double static_coefficient = std::numeric_limits<double>::quiet_NaN())
        : Coulomb(Params{friction_coefficient, static_coefficient}) {}

    Params params() const { return Params{mu_, mu_static_}; }
    double friction_coefficient() const { return mu_; }
    double static_coefficient() const { return mu_static_; }

    double static_limit(double normal_force) const { return mu_static_ * normal_force; }
    double slip_force(double /*v_r*/, double normal_force, int direction) const {
        return direction * mu_ * normal_force;  // eq 8: mu F_N sgn(v_r)
    }
    double slip_slope(double, double, int) const { return 0.0; }
    double karnopp_band() const { return 0.0; }

private:
    double mu_, mu_static_;
};

}  // namespace frictionsim
