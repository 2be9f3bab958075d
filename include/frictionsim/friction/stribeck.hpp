// Stribeck friction: F = sgn(v) [Fc + (Fs - Fc) exp(-|v/vs|^delta)] + sigma_v v with Fc = mu_c N and
// Fs = mu_s N (Olsson et al. 1998, eq 5). Stick is exact (switch model) unless a Karnopp band is given:
// then |v_r| < band counts as stick and the friction force saturates the force needed to stick (Karnopp 1985).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "../parameters.hpp"
#include "law.hpp"

namespace frictionsim {

class Stribeck {
public:
    static constexpr const char* name = "Stribeck";
    static constexpr const char* key = "stribeck";
    /// What Python's help() shows above the parameter list (the bindings add that from `fields`).
    static constexpr const char* description = R"doc(Stribeck friction with exact stick, or a Karnopp band (Karnopp 1985).

Slip: F = [mu + (mu_static - mu) exp(-(|v_r|/v_s)^delta)] F_N sgn(v_r) + sigma_v v_r.
Stick holds while the force needed stays within mu_static F_N. With karnopp_band > 0, |v_r| below the band
counts as stick (the band is a located mode of its own).)doc";
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;

    struct Params {
        double coulomb_coefficient = 0.3;   ///< mu_c, kinetic level at high speed
        double static_coefficient = 0.4;    ///< mu_s >= mu_c, breakaway level
        double stribeck_velocity = 1e-3;    ///< v_s, m/s
        double shape_exponent = 2.0;        ///< delta (2: Gaussian, 1: exponential)
        double viscous_coefficient = 0.0;   ///< sigma_v, N s/m
        double karnopp_band = 0.0;          ///< m/s; 0 = exact stick
    };

    static constexpr std::array<Field<Params>, 6> fields{{
        {"coulomb_coefficient", "mu_c", "-", Rule::positive(), &Params::coulomb_coefficient,
         "Coulomb (high-speed) coefficient.", "mu", true},
        {"static_coefficient", "mu_s", "-", Rule::at_least_field("coulomb_coefficient"), &Params::static_coefficient,
         "Static (breakaway) coefficient.", "mu_static", true},
        {"stribeck_velocity", "v_s", "m/s", Rule::positive(), &Params::stribeck_velocity, "Stribeck velocity.",
         nullptr, true},
        {"shape_exponent", "delta", "-", Rule::positive(), &Params::shape_exponent,
         "Shape of the decay (2: Gaussian, 1: exponential).", nullptr},
        {"viscous_coefficient", "sigma_v", "N s/m", Rule::non_negative(), &Params::viscous_coefficient,
         "Viscous friction.", nullptr},
        {"karnopp_band", "dv", "m/s", Rule::non_negative(), &Params::karnopp_band,
         "Half-width of the Karnopp stick band; 0 means exact stick.", nullptr},
    }};

    explicit Stribeck(const Params& p) : p_(p) { validate_fields(name, p, fields); }

    const Params& params() const { return p_; }

    double static_limit(double normal_force) const { return p_.static_coefficient * normal_force; }
    double slip_force(double v_r, double normal_force, int direction) const {
        const double decay = std::exp(-shaped(std::abs(v_r) / p_.stribeck_velocity));
        const double level = p_.coulomb_coefficient + (p_.static_coefficient - p_.coulomb_coefficient) * decay;
        return direction * level * normal_force + p_.viscous_coefficient * v_r;
    }
    /// dF/dv_r in slip (for analytic Jacobians).
    double slip_slope(double v_r, double normal_force, int direction) const {
        const double r = std::abs(v_r) / p_.stribeck_velocity;
        if (r == 0.0) return p_.viscous_coefficient;  // the decay's slope at rest: 0 for delta > 1, a kink else
        const double decay = std::exp(-shaped(r));
        const double d_level = -(p_.static_coefficient - p_.coulomb_coefficient) * decay * p_.shape_exponent *
                               std::pow(r, p_.shape_exponent - 1.0) / p_.stribeck_velocity * sign_of(v_r);
        return direction * d_level * normal_force + p_.viscous_coefficient;
    }
    double karnopp_band() const { return p_.karnopp_band; }

private:
    /// r^delta, without pow for the common Gaussian (2) and exponential (1) shapes (pow is ~15 ns of ~25).
    double shaped(double r) const {
        if (p_.shape_exponent == 2.0) return r * r;
        if (p_.shape_exponent == 1.0) return r;
        return std::pow(r, p_.shape_exponent);
    }

    Params p_;
};

}  // namespace frictionsim
