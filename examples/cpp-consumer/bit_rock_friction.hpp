// A user's own friction law, written outside frictionsim against its installed headers: the velocity-weakening
// bit-rock friction of the lumped drill-string models (Navarro-Lopez & Cortes 2007, Germay et al. 2009),
//   mu(v) = mu_c + (mu_s - mu_c) exp(-gamma |v|),     F = mu(v) W sgn(v)  in slip,
// set-valued with exact stick: the bit sticks while the force needed stays within mu_s W (W: weight on bit).
// It meets frictionsim's FrictionLaw concept (friction/law.hpp) and validates its parameters from a Field table
// like the library's own laws, so every library rig and ContactSwitching accept it.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <frictionsim/friction/law.hpp>
#include <frictionsim/parameters.hpp>

namespace user {

class BitRockFriction {
public:
    static constexpr const char* name = "BitRockFriction";
    static constexpr bool has_stick = true;  // set-valued, exact stick
    static constexpr std::size_t state_count = 0;

    struct Params {
        double coulomb_coefficient = 0.5;  ///< mu_c, at high slip speed
        double static_coefficient = 0.8;   ///< mu_s >= mu_c, breakaway
        double decay_rate = 9.0;           ///< gamma, s/m: how fast mu falls from mu_s to mu_c with |v|
    };
    static constexpr std::array<frictionsim::Field<Params>, 3> fields{{
        {"coulomb_coefficient", "mu_c", "-", frictionsim::Rule::positive(), &Params::coulomb_coefficient,
         "Kinetic coefficient at high slip speed."},
        {"static_coefficient", "mu_s", "-", frictionsim::Rule::at_least_field("coulomb_coefficient"),
         &Params::static_coefficient, "Static (breakaway) coefficient."},
        {"decay_rate", "gamma", "s/m", frictionsim::Rule::non_negative(), &Params::decay_rate,
         "Rate of the exponential velocity weakening (0: Coulomb with mu_c in slip)."},
    }};

    explicit BitRockFriction(const Params& p) : p_(p) { frictionsim::validate_fields(name, p, fields); }
    const Params& params() const { return p_; }

    /// mu(v) of the exponential decay, dimensionless.
    double coefficient(double v_r) const {
        return p_.coulomb_coefficient +
               (p_.static_coefficient - p_.coulomb_coefficient) * std::exp(-p_.decay_rate * std::abs(v_r));
    }
    double static_limit(double normal_force) const { return p_.static_coefficient * normal_force; }
    double slip_force(double v_r, double normal_force, int direction) const {
        return direction * coefficient(v_r) * normal_force;
    }
    /// dF/dv_r in slip: lets CVODE build the rigs' Jacobians analytically.
    double slip_slope(double v_r, double normal_force, int direction) const {
        const double weakening = (p_.static_coefficient - p_.coulomb_coefficient) * p_.decay_rate *
                                 std::exp(-p_.decay_rate * std::abs(v_r));
        return -direction * frictionsim::sign_of(v_r) * weakening * normal_force;
    }
    double karnopp_band() const { return 0.0; }  // exact stick

private:
    Params p_;
};

}  // namespace user
