// LuGre friction (Canudas de Wit, Olsson, Astrom & Lischinsky 1995, eqs 1-3):
//   dz/dt = v - sigma0 |v| z / g(v),  g(v) = Fc + (Fs - Fc) exp(-(v/vs)^2),
//   F = sigma0 z + sigma1 dz/dt + sigma2 v,  with Fc = mu_c N and Fs = mu_s N.
// Its right-hand side is Lipschitz in v (|v| z), so no event is needed at v = 0.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "../parameters.hpp"
#include "law.hpp"

namespace frictionsim {

namespace detail {
/// What the bristle laws (LuGre, ElastoPlastic) share besides their parameter table: the steady sliding level
/// g(v) = N (mu_c + (mu_s - mu_c) exp(-(v/v_s)^2)) and its slope dg/dv.
template <class Params>
double stribeck_level(const Params& p, double v_r, double normal_force) {
    const double r = v_r / p.stribeck_velocity;
    return normal_force * (p.coulomb_coefficient + (p.static_coefficient - p.coulomb_coefficient) * std::exp(-r * r));
}
template <class Params>
double stribeck_level_slope(const Params& p, double v_r, double normal_force) {
    const double r = v_r / p.stribeck_velocity;
    return -normal_force * (p.static_coefficient - p.coulomb_coefficient) * std::exp(-r * r) * 2.0 * r /
           p.stribeck_velocity;
}
}  // namespace detail

class LuGre {
public:
    static constexpr const char* name = "LuGre";
    static constexpr const char* key = "lugre";
    /// What Python's help() shows above the parameter list (the bindings add that from `fields`).
    static constexpr const char* description = R"doc(LuGre friction (Canudas de Wit, Olsson, Astrom & Lischinsky 1995):

    dz/dt = v_r - sigma0 |v_r| z / g(v_r),  g(v) = F_N [mu + (mu_static - mu) exp(-(v/v_s)^2)],
    F = sigma0 z + sigma1 dz/dt + sigma2 v_r.

Stiff (bristle dynamics): simulate() picks CVODE BDF for it.)doc";
    static constexpr bool has_stick = false;
    static constexpr bool kink_at_zero_velocity = false;
    static constexpr bool stiff = true;  ///< bristle modes ~ sqrt(sigma0/m), z relaxation sigma0 |v| / g(v)
    static constexpr std::size_t state_count = 1;
    static constexpr std::array<const char*, 1> state_names{"bristle_deflection"};  ///< z, m
    static constexpr std::array<const char*, 1> state_units{"m"};  ///< SI, the Results' and files' units

    struct Params {
        double coulomb_coefficient = 1.0;   ///< mu_c: Fc = mu_c N
        double static_coefficient = 1.5;    ///< mu_s >= mu_c: Fs = mu_s N
        double stribeck_velocity = 1e-3;    ///< v_s, m/s
        double bristle_stiffness = 1e5;     ///< sigma0, N/m
        double bristle_damping = 316.2277660168379;  ///< sigma1, N s/m (sqrt(1e5) in Canudas de Wit 1995)
        double viscous_damping = 0.0;       ///< sigma2, N s/m (0.4 in Canudas de Wit 1995)
    };
    static constexpr std::array<Field<Params>, 6> fields{{
        {"coulomb_coefficient", "mu_c", "-", Rule::positive(), &Params::coulomb_coefficient,
         "Coulomb coefficient (Fc = mu F_N).", "mu", true},
        {"static_coefficient", "mu_s", "-", Rule::at_least_field("coulomb_coefficient"), &Params::static_coefficient,
         "Static coefficient (Fs = mu_static F_N).", "mu_static", true},
        {"stribeck_velocity", "v_s", "m/s", Rule::positive(), &Params::stribeck_velocity, "Stribeck velocity.",
         nullptr, true},
        {"bristle_stiffness", "sigma_0", "N/m", Rule::positive(), &Params::bristle_stiffness, "Bristle stiffness.",
         nullptr, true},
        {"bristle_damping", "sigma_1", "N s/m", Rule::non_negative(), &Params::bristle_damping,
         "Bristle (micro-)damping.", nullptr, true},
        {"viscous_damping", "sigma_2", "N s/m", Rule::non_negative(), &Params::viscous_damping, "Viscous friction.",
         nullptr},
    }};

    explicit LuGre(const Params& p) : p_(p) { validate_fields(name, p, fields); }

    const Params& params() const { return p_; }

    /// Steady-state sliding level g(v) (N) at normal force N.
    double stribeck_level(double v_r, double normal_force) const {
        return detail::stribeck_level(p_, v_r, normal_force);
    }
    void state_derivative(double v_r, double normal_force, const double* z, int /*branch*/, double* dz) const {
        dz[0] = v_r - p_.bristle_stiffness * std::abs(v_r) * z[0] / stribeck_level(v_r, normal_force);
    }
    double force(double v_r, double normal_force, const double* z, int branch) const {
        double dz = 0.0;
        state_derivative(v_r, normal_force, z, branch, &dz);
        return p_.bristle_stiffness * z[0] + p_.bristle_damping * dz + p_.viscous_damping * v_r;
    }

    StatePartials<1> partials(double v_r, double normal_force, const double* z, int /*branch*/) const {
        const double g = stribeck_level(v_r, normal_force);
        const double dg = detail::stribeck_level_slope(p_, v_r, normal_force);
        const double s0 = p_.bristle_stiffness;
        // dz/dt = v - s0 |v| z / g(v):  d/dv (|v| / g) = sgn(v) / g - |v| g' / g^2
        const double d_ratio = sign_of(v_r) / g - std::abs(v_r) * dg / (g * g);
        StatePartials<1> p;
        p.rate_velocity[0] = 1.0 - s0 * z[0] * d_ratio;
        p.rate_state[0][0] = -s0 * std::abs(v_r) / g;
        p.force_velocity = p_.bristle_damping * p.rate_velocity[0] + p_.viscous_damping;
        p.force_state[0] = s0 + p_.bristle_damping * p.rate_state[0][0];
        return p;
    }

private:
    Params p_;
};

}  // namespace frictionsim
