// Normal force of a hydraulic oscillator tool (HOT) lying on the low side of a horizontal wellbore, and the
// equivalent normal force that reproduces its contact stress on the flat-on-flat friction rig of paper 000
// (eqs 1-4). SI units throughout: the paper prints sigma_d in MPa and the Young's moduli in GPa; here they
// are Pa.
#pragma once

#include <cmath>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"

namespace frictionsim {

/// Geometry and materials of the HOT, the hole and the rig specimen (paper 000, eqs 1-4).
///
/// The paper calls r_co, r_ci and r_w "diameters", but eq 1 is the area pi (r_co^2 - r_ci^2) of an annulus
/// written with radii, so all three are radii here.
struct HydraulicOscillatorParams {
    double tool_outer_radius;         ///< r_co [m]
    double tool_inner_radius;         ///< r_ci [m], the flow bore
    double wellbore_radius;           ///< r_w [m]
    double steel_density;             ///< rho_s [kg/m^3]
    double mud_density;               ///< rho_m [kg/m^3]
    double rock_youngs_modulus;       ///< E_r [Pa]
    double rock_poisson_ratio;        ///< mu_r [-]
    double steel_youngs_modulus;      ///< E_s [Pa]
    double steel_poisson_ratio;       ///< mu_s [-]
    double rock_wear_width;           ///< a [m], width of the flat worn on the rock sample (eq 3)
    double specimen_width;            ///< l [m], width of the steel specimen (eq 3)
    double gravity = 9.81;            ///< g [m/s^2], the constant printed in eq 1

    /// Throws InvalidParameter naming the offending field.
    void validate() const {
        constexpr const char* who = "HydraulicOscillatorParams";
        detail::require_positive(who, "tool_inner_radius", tool_inner_radius);
        detail::require_positive(who, "tool_outer_radius", tool_outer_radius);
        detail::require_positive(who, "wellbore_radius", wellbore_radius);
        if (!(tool_inner_radius < tool_outer_radius))
            detail::reject(who, "tool_inner_radius", "< tool_outer_radius", tool_inner_radius);
        // The tool must fit inside the hole: equal radii would be conformal contact with no Hertz stress peak.
        if (!(tool_outer_radius < wellbore_radius))
            detail::reject(who, "tool_outer_radius", "< wellbore_radius", tool_outer_radius);
        detail::require_positive(who, "mud_density", mud_density);
        detail::require_positive(who, "steel_density", steel_density);
        // A tool lighter than the mud floats to the high side: eq 1 would give a negative weight.
        if (!(steel_density > mud_density))
            detail::reject(who, "steel_density", "> mud_density (the tool must sink in the mud)", steel_density);
        detail::require_positive(who, "rock_youngs_modulus", rock_youngs_modulus);
        detail::require_positive(who, "steel_youngs_modulus", steel_youngs_modulus);
        require_poisson(who, "rock_poisson_ratio", rock_poisson_ratio);
        require_poisson(who, "steel_poisson_ratio", steel_poisson_ratio);
        detail::require_positive(who, "rock_wear_width", rock_wear_width);
        detail::require_positive(who, "specimen_width", specimen_width);
        detail::require_positive(who, "gravity", gravity);
    }

private:
    static void require_poisson(const char* who, const char* name, double value) {
        if (!(std::isfinite(value) && value >= 0.0 && value < 0.5)) detail::reject(who, name, "in [0, 0.5)", value);
    }
};

/// q_c [N/m]: buoyed weight per unit length of the HOT in mud, g pi (r_co^2 - r_ci^2)(rho_s - rho_m) (eq 1).
inline double hot_weight_per_length_in_mud(const HydraulicOscillatorParams& p) {
    p.validate();
    const double steel_area = pi * (p.tool_outer_radius * p.tool_outer_radius -
                                      p.tool_inner_radius * p.tool_inner_radius);
    return p.gravity * steel_area * (p.steel_density - p.mud_density);
}

/// 1/r_co - 1/r_w [1/m]: relative curvature of a cylinder lying in a concave cylindrical seat.
///
/// Eq 2 prints (1/r_w - 1/r_co), which is negative for a tool inside a larger hole and makes sigma_d
/// imaginary; eq 4 prints (1/r_co - 1/r_w). The concave seat subtracts its curvature from the tool's, so the
/// positive difference is the physical one and both eq 2 and eq 4 use it here.
inline double hot_relative_curvature(const HydraulicOscillatorParams& p) {
    p.validate();
    return 1.0 / p.tool_outer_radius - 1.0 / p.wellbore_radius;
}

/// (1 - mu_r^2)/E_r + (1 - mu_s^2)/E_s [1/Pa]: the plane-strain compliance of the rock-steel pair (eqs 2, 4).
inline double rock_steel_contact_compliance(const HydraulicOscillatorParams& p) {
    p.validate();
    return (1.0 - p.rock_poisson_ratio * p.rock_poisson_ratio) / p.rock_youngs_modulus +
           (1.0 - p.steel_poisson_ratio * p.steel_poisson_ratio) / p.steel_youngs_modulus;
}

/// sigma_d [Pa]: peak Hertz line-contact stress between the HOT and the wellbore rock (eq 2),
/// sqrt(q_c (1/r_co - 1/r_w) / (pi [(1 - mu_r^2)/E_r + (1 - mu_s^2)/E_s])).
inline double hot_contact_stress(const HydraulicOscillatorParams& p) {
    const double load_times_curvature = hot_weight_per_length_in_mud(p) * hot_relative_curvature(p);
    return std::sqrt(load_times_curvature / (pi * rock_steel_contact_compliance(p)));
}

/// sigma_e [Pa]: mean contact stress on the rig's worn flat, F_e / (a l) (eq 3). The worn rock flat makes the
/// rig a flat-on-flat contact, so the stress is uniform over the wear width a times the specimen width l.
inline double rig_contact_stress(double normal_force, double rock_wear_width, double specimen_width) {
    constexpr const char* who = "rig_contact_stress";
    detail::require_non_negative(who, "normal_force", normal_force);
    detail::require_positive(who, "rock_wear_width", rock_wear_width);
    detail::require_positive(who, "specimen_width", specimen_width);
    return normal_force / (rock_wear_width * specimen_width);
}

/// F_e [N]: rig normal force whose stress on the worn flat (eq 3) equals the HOT's downhole Hertz stress
/// (eq 2): F_e = a l sigma_d (eq 4, "equivalence principle of contact stress").
inline double equivalent_rig_normal_force(const HydraulicOscillatorParams& p) {
    return p.rock_wear_width * p.specimen_width * hot_contact_stress(p);
}

}  // namespace frictionsim
