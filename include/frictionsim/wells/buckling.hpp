// Critical compressive loads of a pipe lying on the low side of an inclined hole (the soft-string model's buckling
// checks, issue 14 item 2). Both scale with sqrt(E I w sin(I) / r): the pipe's weight across the hole is what holds
// it straight against the compression, its bending stiffness and the radial clearance r what set the wavelength.
//   sinusoidal (lateral) buckling:  F_s = 2 sqrt(E I w sin I / r)              Dawson & Paslay 1984, SPE 11167
//   helical buckling:               F_h = 2 sqrt(2) sqrt(E I w sin I / r)      Chen, Lin & Cheatham 1990, SPE 19176
//                                   F_h = 2 (2 sqrt(2) - 1) sqrt(...)          Wu & Juvkam-Wold 1993 (loaded from one
//                                                                              end, the pipe's own weight resisting)
// w is the buoyed weight per length (its magnitude: a pipe lighter than the mud lies on the high side, held the same
// way). The formulas vanish on the vertical, where a pipe buckles under any compression in this model (the
// vertical-well limit of Lubinski is not included).
#pragma once

#include <cmath>

namespace frictionsim {

/// sqrt(E I |w| sin I / r) [N]: the load scale of both criteria. bending_stiffness E I [N m^2], weight_per_length
/// w [N/m], inclination I [rad], radial_clearance r = (hole diameter - pipe OD) / 2 [m], > 0.
inline double buckling_load_scale(double bending_stiffness, double weight_per_length, double inclination,
                                  double radial_clearance) {
    return std::sqrt(bending_stiffness * std::abs(weight_per_length) * std::abs(std::sin(inclination)) /
                     radial_clearance);
}

/// Dawson-Paslay critical load for sinusoidal buckling [N] (compression above it buckles the pipe laterally).
inline double sinusoidal_buckling_load(double bending_stiffness, double weight_per_length, double inclination,
                                       double radial_clearance) {
    return 2.0 * buckling_load_scale(bending_stiffness, weight_per_length, inclination, radial_clearance);
}

/// Chen-Lin-Cheatham critical load for helical buckling [N]: sqrt(2) times Dawson-Paslay's. The soft-string
/// model's helical flag uses this one.
inline double helical_buckling_load(double bending_stiffness, double weight_per_length, double inclination,
                                    double radial_clearance) {
    return 2.0 * std::sqrt(2.0) *
           buckling_load_scale(bending_stiffness, weight_per_length, inclination, radial_clearance);
}

/// Wu & Juvkam-Wold's helical load [N], 2 (2 sqrt(2) - 1) ~ 3.66 times the scale (Chen-Cheatham: 2.83).
inline double helical_buckling_load_wu_juvkam_wold(double bending_stiffness, double weight_per_length,
                                                   double inclination, double radial_clearance) {
    return 2.0 * (2.0 * std::sqrt(2.0) - 1.0) *
           buckling_load_scale(bending_stiffness, weight_per_length, inclination, radial_clearance);
}

}  // namespace frictionsim
