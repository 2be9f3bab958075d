// Elasto-plastic friction (Dupont, Hayward, Armstrong & Altpeter 2002, "Single state elastoplastic friction
// models", IEEE TAC 47(5)): LuGre with a purely elastic presliding regime, so that small oscillations of the
// load below break-away do not drift (LuGre creeps under them).
//   dz/dt = v (1 - alpha(z, v) z / z_ss(v)),   z_ss(v) = sgn(v) g(v) / sigma0,
//   g(v)  = Fc + (Fs - Fc) exp(-(v/vs)^2),   Fc = mu_c N, Fs = mu_s N,
//   F     = sigma0 z + sigma1 dz/dt + sigma2 v,
//   alpha = 0 while |z| <= z_ba or sgn(z) != sgn(v) (elastic: below break-away, or unloading),
//           1/2 + 1/2 sin(pi (|z| - (z_max + z_ba)/2) / (z_max - z_ba)) for z_ba < |z| < z_max,
//           1 for |z| >= z_max (LuGre),
// with the paper's constants 0 <= z_ba < z_max <= |z_ss(v)| for every v: here z_max = Fc / sigma0, the largest
// value that rule allows (g >= Fc), and z_ba = breakaway_fraction z_max. alpha is C1 in z (the sine's slope
// vanishes at both ends) and jumps with sgn(v) only where dz/dt = v (...) vanishes: the right-hand side is
// continuous with a kink at v = 0, which the rig locates as an event. Between events `branch` = sgn v, and each
// branch uses branch * v for |v|, so it stays smooth when a stage steps past v = 0 (as Dahl's does).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "../detail/constants.hpp"
#include "../parameters.hpp"
#include "law.hpp"
#include "lugre.hpp"

namespace frictionsim {

class ElastoPlastic {
public:
    static constexpr const char* name = "ElastoPlastic";
    static constexpr const char* key = "elasto_plastic";
    /// What Python's help() shows above the parameter list (the bindings add that from `fields`).
    static constexpr const char* description = R"doc(Elasto-plastic friction (Dupont, Hayward, Armstrong & Altpeter 2002): LuGre with a purely elastic presliding
regime, so that small oscillations below break-away do not drift (LuGre creeps under them):

    dz/dt = v_r (1 - alpha(z, v_r) z / z_ss(v_r)),   z_ss(v) = sgn(v) g(v) / sigma0,
    g(v)  = F_N [mu + (mu_static - mu) exp(-(v/v_s)^2)],
    F     = sigma0 z + sigma1 dz/dt + sigma2 v_r,

    alpha = 0                                            |z| <= z_ba, or sgn(z) != sgn(v_r) (elastic)
          = 1/2 + 1/2 sin(pi (|z| - z_m) / (z_max - z_ba))   z_ba < |z| < z_max,  z_m = (z_max + z_ba) / 2
          = 1                                            |z| >= z_max (LuGre)

with the paper's constants 0 <= z_ba < z_max <= |z_ss(v)|: z_max = mu F_N / sigma0 (the largest that rule allows)
and z_ba = breakaway_fraction z_max. The kink of dz/dt at v_r = 0 is located as an event. Stiff (bristle
dynamics): simulate() picks CVODE BDF for it.)doc";
    static constexpr bool has_stick = false;
    static constexpr bool kink_at_zero_velocity = true;
    static constexpr bool stiff = true;  ///< bristle modes as LuGre's
    static constexpr std::size_t state_count = 1;
    static constexpr std::array<const char*, 1> state_names{"bristle_deflection"};  ///< z, m
    static constexpr std::array<const char*, 1> state_units{"m"};  ///< SI, the Results' and files' units

    /// LuGre's parameters (and defaults), and where the plastic ramp starts.
    struct Params : LuGre::Params {
        /// z_ba / z_max in [0, 1). 0 starts the plastic ramp at z = 0: LuGre-like on loading, still elastic when
        /// unloading.
        double breakaway_fraction = 0.5;
    };

    static constexpr auto fields = extend_fields<Params>(
        LuGre::fields, std::array<Field<Params>, 1>{{
                           {"breakaway_fraction", "beta", "-", Rule::interval(0.0, 1.0, false, true),
                            &Params::breakaway_fraction,
                            "z_ba / z_max: 0 starts the plastic ramp at z = 0 (LuGre-like when loading; unloading "
                            "stays elastic)."},
                       }});

    explicit ElastoPlastic(const Params& p) : p_(p) { validate_fields(name, p, fields); }

    const Params& params() const { return p_; }

    /// Steady sliding level g(v) (N) at normal force N, as LuGre's.
    double stribeck_level(double v_r, double normal_force) const {
        return detail::stribeck_level(p_, v_r, normal_force);
    }
    /// z_max = Fc / sigma0, m: from it on the contact slides as LuGre's.
    double plastic_deflection(double normal_force) const {
        return p_.coulomb_coefficient * normal_force / p_.bristle_stiffness;
    }
    /// z_ba, m: below it the contact is purely elastic.
    double breakaway_deflection(double normal_force) const {
        return p_.breakaway_fraction * plastic_deflection(normal_force);
    }

    void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const {
        const Plasticity a = plasticity(normal_force, z[0], branch);
        dz[0] = v_r - a.alpha * p_.bristle_stiffness * branch * v_r * z[0] / stribeck_level(v_r, normal_force);
    }
    double force(double v_r, double normal_force, const double* z, int branch) const {
        double dz = 0.0;
        state_derivative(v_r, normal_force, z, branch, &dz);
        return p_.bristle_stiffness * z[0] + p_.bristle_damping * dz + p_.viscous_damping * v_r;
    }

    StatePartials<1> partials(double v_r, double normal_force, const double* z, int branch) const {
        const Plasticity a = plasticity(normal_force, z[0], branch);
        const double s0 = p_.bristle_stiffness, speed = branch * v_r;
        const double g = stribeck_level(v_r, normal_force), dg = detail::stribeck_level_slope(p_, v_r, normal_force);
        // dz/dt = v - alpha(z) q,  q = s0 (branch v) z / g(v)
        const double q = s0 * speed * z[0] / g;
        StatePartials<1> p;
        p.rate_velocity[0] = 1.0 - a.alpha * s0 * z[0] * (branch / g - speed * dg / (g * g));
        p.rate_state[0][0] = -(a.slope * q + a.alpha * s0 * speed / g);
        p.force_velocity = p_.bristle_damping * p.rate_velocity[0] + p_.viscous_damping;
        p.force_state[0] = s0 + p_.bristle_damping * p.rate_state[0][0];
        return p;
    }

    /// alpha(z) on branch sgn v (documented above), for plots and tests.
    double plasticity_factor(double normal_force, double z, int branch) const {
        return plasticity(normal_force, z, branch).alpha;
    }

private:
    struct Plasticity {
        double alpha = 0.0;  ///< alpha(z)
        double slope = 0.0;  ///< d alpha / dz
    };

    Plasticity plasticity(double normal_force, double z, int branch) const {
        Plasticity a;
        const double deflection = std::abs(z), z_ba = breakaway_deflection(normal_force);
        if (branch * z <= 0.0 || deflection <= z_ba) return a;  // elastic: unloading, or below break-away
        const double z_max = plastic_deflection(normal_force);
        if (deflection >= z_max) {
            a.alpha = 1.0;
            return a;
        }
        const double width = z_max - z_ba, u = (deflection - 0.5 * (z_max + z_ba)) / width;
        a.alpha = 0.5 + 0.5 * std::sin(pi * u);
        a.slope = (z > 0.0 ? 0.5 : -0.5) * pi * std::cos(pi * u) / width;
        return a;
    }

    Params p_;
};

}  // namespace frictionsim
