// Elasto-plastic friction (Dupont, Hayward, Armstrong & Altpeter 2002, "Single state elastoplastic friction
// models", IEEE TAC 47(5)): LuGre with a purely elastic presliding regime, so that small oscillations of the
// load below break-away do not drift (LuGre creeps under them).
//   dz/dt = v (1 - alpha(z, v) z / z_ss(v)),   z_ss(v) = sgn(v) g(v) / sigma0,
//   g(v)  = Fc + (Fs - Fc) exp(-(v/vs)^2),   Fc = mu_c N, Fs = mu_s N,
//   F     = sigma0 z + sigma1 dz/dt + sigma2 v,
//   alpha = 0 while |z| <= z_ba or sgn(z) != sgn(v) (elastic: loading back, or below break-away),
//           1/2 + 1/2 sin(pi (|z| - (z_max + z_ba)/2) / (z_max - z_ba)) for z_ba < |z| < z_max(v) = g(v)/sigma0,
//           1 for |z| >= z_max(v) (LuGre).
// alpha is C1 in z (the sine's slope vanishes at both ends), and jumps with sgn(v) only where dz/dt = v (...)
// vanishes: the right-hand side is continuous with a kink at v = 0, which the rig locates as an event
// (`branch` = sgn v between events, as for Dahl). The break-away deflection is given as a fraction of the
// smallest steady deflection Fc / sigma0, so 0 <= z_ba < z_max holds at every speed and normal force.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "law.hpp"

namespace frictionsim {

class ElastoPlastic {
public:
    static constexpr const char* name = "ElastoPlastic";
    static constexpr bool has_stick = false;
    static constexpr bool kink_at_zero_velocity = true;
    static constexpr bool stiff = true;  ///< bristle modes as LuGre's
    static constexpr std::size_t state_count = 1;
    static constexpr std::array<const char*, 1> state_names{"bristle_deflection"};  ///< z, m

    struct Params {
        double coulomb_coefficient = 1.0;   ///< mu_c: Fc = mu_c N
        double static_coefficient = 1.5;    ///< mu_s >= mu_c: Fs = mu_s N
        double stribeck_velocity = 1e-3;    ///< v_s, m/s
        double bristle_stiffness = 1e5;     ///< sigma0, N/m
        double bristle_damping = 316.2277660168379;  ///< sigma1, N s/m
        double viscous_damping = 0.4;       ///< sigma2, N s/m
        double breakaway_fraction = 0.5;    ///< z_ba / (Fc / sigma0), in [0, 1): 0 gives LuGre's drift back
    };

    explicit ElastoPlastic(const Params& p) : p_(p) {
        detail::require_positive(name, "coulomb_coefficient", p.coulomb_coefficient);
        detail::require_at_least(name, "static_coefficient", p.static_coefficient, p.coulomb_coefficient,
                                 ">= coulomb_coefficient and finite");
        detail::require_positive(name, "stribeck_velocity", p.stribeck_velocity);
        detail::require_positive(name, "bristle_stiffness", p.bristle_stiffness);
        detail::require_non_negative(name, "bristle_damping", p.bristle_damping);
        detail::require_non_negative(name, "viscous_damping", p.viscous_damping);
        if (!(p.breakaway_fraction >= 0.0 && p.breakaway_fraction < 1.0))
            detail::reject(name, "breakaway_fraction", "in [0, 1)", p.breakaway_fraction);
    }

    const Params& params() const { return p_; }

    /// Steady sliding level g(v) (N) at normal force N, as LuGre's.
    double stribeck_level(double v_r, double normal_force) const {
        const double r = v_r / p_.stribeck_velocity;
        return normal_force *
               (p_.coulomb_coefficient + (p_.static_coefficient - p_.coulomb_coefficient) * std::exp(-r * r));
    }
    /// z_ba, m: below it the contact is purely elastic.
    double breakaway_deflection(double normal_force) const {
        return p_.breakaway_fraction * p_.coulomb_coefficient * normal_force / p_.bristle_stiffness;
    }

    void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const {
        const Plasticity a = plasticity(v_r, normal_force, z[0], branch);
        dz[0] = v_r - a.alpha * p_.bristle_stiffness * std::abs(v_r) * z[0] / a.level;
    }
    double force(double v_r, double normal_force, const double* z, int branch) const {
        double dz = 0.0;
        state_derivative(v_r, normal_force, z, branch, &dz);
        return p_.bristle_stiffness * z[0] + p_.bristle_damping * dz + p_.viscous_damping * v_r;
    }

    StatePartials<1> partials(double v_r, double normal_force, const double* z, int branch) const {
        const Plasticity a = plasticity(v_r, normal_force, z[0], branch);
        const double s0 = p_.bristle_stiffness, g = a.level, speed = std::abs(v_r);
        const double r = v_r / p_.stribeck_velocity;
        const double dg = -normal_force * (p_.static_coefficient - p_.coulomb_coefficient) * std::exp(-r * r) * 2.0 *
                          r / p_.stribeck_velocity;
        // dz/dt = v - alpha q,  q = s0 |v| z / g;  alpha depends on |z| and, through z_max = g / s0, on v
        const double q = s0 * speed * z[0] / g;
        const double dq_dv = s0 * z[0] * (sign_of(v_r) / g - speed * dg / (g * g));
        const double dalpha_dv = a.slope_max * dg / s0;
        StatePartials<1> p;
        p.rate_velocity[0] = 1.0 - (dalpha_dv * q + a.alpha * dq_dv);
        p.rate_state[0][0] = -(a.slope_z * q + a.alpha * s0 * speed / g);
        p.force_velocity = p_.bristle_damping * p.rate_velocity[0] + p_.viscous_damping;
        p.force_state[0] = s0 + p_.bristle_damping * p.rate_state[0][0];
        return p;
    }

    /// alpha(z, v) (documented above), for plots and tests.
    double plasticity_factor(double v_r, double normal_force, double z, int branch) const {
        return plasticity(v_r, normal_force, z, branch).alpha;
    }

private:
    struct Plasticity {
        double alpha = 0.0;      ///< alpha(z, v)
        double slope_z = 0.0;    ///< d alpha / dz
        double slope_max = 0.0;  ///< d alpha / d z_max
        double level = 1.0;      ///< g(v), N
    };

    Plasticity plasticity(double v_r, double normal_force, double z, int branch) const {
        Plasticity a;
        a.level = stribeck_level(v_r, normal_force);
        const double deflection = std::abs(z), z_ba = breakaway_deflection(normal_force);
        if (branch * z <= 0.0 || deflection <= z_ba) return a;  // elastic: unloading, or below break-away
        const double z_max = a.level / p_.bristle_stiffness;
        if (deflection >= z_max) {
            a.alpha = 1.0;
            return a;
        }
        const double width = z_max - z_ba, u = (deflection - 0.5 * (z_max + z_ba)) / width;
        const double slope = 0.5 * pi * std::cos(pi * u) / width;  // d alpha / d|z|
        a.alpha = 0.5 + 0.5 * std::sin(pi * u);
        a.slope_z = slope * (z > 0.0 ? 1.0 : -1.0);
        a.slope_max = -slope * (0.5 + u);  // du/dz_max = -(1/2 + u) / width
        return a;
    }

    Params p_;
};

}  // namespace frictionsim
