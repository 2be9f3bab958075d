// Coulomb friction with separate static and kinetic coefficients (paper 000 eq 8 for slip). The rig holds
// stick while the force needed to keep v_r = 0 stays within mu_s N (Leine's switch model).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "../detail/validate.hpp"
#include "law.hpp"

namespace frictionsim {

class Coulomb {
public:
    static constexpr const char* name = "Coulomb";
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;

    /// mu (kinetic) and mu_s (static, >= mu; NaN means equal to mu). Dimensionless.
    explicit Coulomb(double friction_coefficient,
                     double static_coefficient = std::numeric_limits<double>::quiet_NaN())
        : mu_(detail::require_positive(name, "friction_coefficient", friction_coefficient)),
          mu_static_(std::isnan(static_coefficient)
                         ? mu_
                         : detail::require_at_least(name, "static_coefficient", static_coefficient, mu_,
                                                    ">= friction_coefficient and finite")) {}

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
