// The 5" drill pipe of the string tests (PipeSection's defaults), a string of it, and two closed-form properties
// of a section, one definition each.
#pragma once

#include <cmath>

#include <frictionsim/string/sections.hpp>
#include <frictionsim/wells/soft_string.hpp>  // standard_gravity

namespace frictionsim::test {

/// A section of 5" drill pipe, `length` long, of steel of `density`.
inline PipeSection pipe(double length, double density = 7850.0) {
    PipeSection s{};
    s.length = length;
    s.density = density;
    return s;
}

/// A string of one section of 5" drill pipe, `length` long.
inline DrillString pipe_string(double length) { return DrillString({pipe(length)}); }

/// Buoyed weight per length of a section in mud of `mud_density` [N/m].
inline double buoyed(const PipeSection& s, double mud_density) {
    return standard_gravity * s.area() * (s.density - mud_density);
}

/// Axial impedance A sqrt(E rho) of a section [N s/m].
inline double impedance(const PipeSection& s) { return s.area() * std::sqrt(s.youngs_modulus * s.density); }

}  // namespace frictionsim::test
