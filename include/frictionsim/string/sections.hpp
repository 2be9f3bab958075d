// A drill string as its sections (drill pipe, heavy-weight pipe, collars: OD, ID, length, steel), top to bottom,
// and its lumped model: N elements of equal length, each a torsional and an axial spring between two nodes, with
// the inertia of each element split half to each of its nodes (issue 13, item 3: the first layer of the model).
//   torsion: node inertia J_i = sum over the element halves of rho I_p dx, spring G I_p / dx,  I_p = pi (OD^4 - ID^4) / 32
//   axial:   node mass    m_i = sum over the element halves of rho A dx,   spring E A / dx,    A = pi (OD^2 - ID^2) / 4
// An element that straddles a section boundary takes each section's share: its compliance is the sum of the
// pieces' dx / (G I_p) (springs in series), its inertia the sum of the pieces'.
#pragma once

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../detail/constants.hpp"
#include "../parameters.hpp"
#include "scale.hpp"

namespace frictionsim {

/// One section of a drill string: a steel tube. Defaults: 5" drill pipe (OD 127 mm, ID 108.6 mm), 100 m.
struct PipeSection {
    double outer_diameter = 0.127;  ///< OD, m
    double inner_diameter = 0.1086; ///< ID, m (0 for a solid bar)
    double length = 100.0;          ///< m
    double youngs_modulus = 210e9;  ///< E, Pa
    double shear_modulus = 80.8e9;  ///< G, Pa
    double density = 7850.0;        ///< rho, kg/m^3

    static constexpr std::array<Field<PipeSection>, 6> fields();

    double area() const { return pi / 4.0 * (outer_diameter * outer_diameter - inner_diameter * inner_diameter); }
    double polar_moment() const {
        const double od2 = outer_diameter * outer_diameter, id2 = inner_diameter * inner_diameter;
        return pi / 32.0 * (od2 * od2 - id2 * id2);
    }
    double torsional_rigidity() const { return shear_modulus * polar_moment(); }  ///< G I_p, N m^2/rad
    double axial_rigidity() const { return youngs_modulus * area(); }              ///< E A, N
    double inertia_per_length() const { return density * polar_moment(); }         ///< rho I_p, kg m
    double mass_per_length() const { return density * area(); }                    ///< rho A, kg/m
};

inline constexpr std::array<Field<PipeSection>, 6> PipeSection::fields() {
    using P = PipeSection;
    return {{
        {"outer_diameter", "OD", "m", Rule::positive(), &P::outer_diameter, "Outer diameter."},
        {"inner_diameter", "ID", "m", Rule::non_negative(), &P::inner_diameter, "Inner diameter, < OD."},
        {"length", "L", "m", Rule::positive(), &P::length, "Length of the section."},
        {"youngs_modulus", "E", "Pa", Rule::positive(), &P::youngs_modulus, "Young's modulus."},
        {"shear_modulus", "G", "Pa", Rule::positive(), &P::shear_modulus, "Shear modulus."},
        {"density", "rho", "kg/m^3", Rule::positive(), &P::density, "Density of the steel."},
    }};
}

/// What a section's table leaves out (each value within its rule, their products can leave the range of a double: an
/// OD of 1e300 m, a length of DBL_MAX): the section's area, polar moment, rigidities, mass and inertia per length and
/// its weight and inertia over its length are positive finite doubles, else refused naming the parameter that put them
/// out (the one farthest from its default; the wall itself, inner_diameter, when OD^2 - ID^2 rounds to nothing).
/// Without it the run's first infinite quantity, a node's normal force, took the blame.
inline void check_section_scale(const char* who, const PipeSection& s) {
    const auto& f = PipeSection::fields();
    const double od2 = s.outer_diameter * s.outer_diameter;
    if (!(std::isfinite(od2 * od2) && od2 * od2 >= DBL_MIN))
        detail::reject(who, "outer_diameter", "such that OD^4 is a positive finite double (within about 1e-77 .. "
                       "1e77 m)", s.outer_diameter);
    if (!(s.area() >= DBL_MIN && s.polar_moment() >= DBL_MIN))
        detail::reject(who, "inner_diameter", "such that the wall keeps an area: OD^2 - ID^2 a positive double "
                       "(ID rounds to OD)", s.inner_diameter);
    detail::require_representable(who, s, f, {"youngs_modulus", "outer_diameter"}, s.axial_rigidity(),
                                  "the axial rigidity E A [N]");
    detail::require_representable(who, s, f, {"shear_modulus", "outer_diameter"}, s.torsional_rigidity(),
                                  "the torsional rigidity G I_p [N m^2]");
    detail::require_representable(who, s, f, {"density", "outer_diameter"}, s.mass_per_length(),
                                  "the mass per length rho A [kg/m]");
    detail::require_representable(who, s, f, {"density", "outer_diameter"}, s.inertia_per_length(),
                                  "the inertia per length rho I_p [kg m]");
    // the weight and the inertia over the length (with g ~ 10 and a margin of 1e3 for the sums over sections)
    detail::require_representable(who, s, f, {"length", "density", "outer_diameter"},
                                  s.mass_per_length() * s.length * 1e4, "1e4 times its mass rho A L [kg]");
    detail::require_representable(who, s, f, {"length", "density", "outer_diameter"},
                                  s.inertia_per_length() * s.length * 1e3, "1e3 times its inertia rho I_p L [kg m^2]");
    detail::require_representable(who, s, f, {"length", "youngs_modulus", "outer_diameter"},
                                  s.length / s.axial_rigidity(), "its axial compliance L / (E A) [m/N]");
    detail::require_representable(who, s, f, {"length", "shear_modulus", "outer_diameter"},
                                  s.length / s.torsional_rigidity(), "its torsional compliance L / (G I_p) [1/(N m)]");
}

/// The lumped string: node 0 at the top, node N at the bit; spring i joins nodes i and i + 1.
struct LumpedString {
    double element_length = 0.0;                      ///< dx, m
    std::vector<double> node_inertia, node_mass;      ///< J_i [kg m^2], m_i [kg], N + 1 nodes
    std::vector<double> torsional_stiffness;          ///< k_i [N m/rad], N springs
    std::vector<double> axial_stiffness;              ///< k_i [N/m], N springs

    std::size_t elements() const { return torsional_stiffness.size(); }
};

/// Sections top to bottom, checked: each against its table, and ID < OD, naming the section.
class DrillString {
public:
    explicit DrillString(std::vector<PipeSection> sections) : sections_(std::move(sections)) {
        if (sections_.empty()) detail::reject("DrillString", "sections", "at least one section", 0.0);
        for (std::size_t i = 0; i < sections_.size(); ++i) {
            const std::string who = "DrillString: section " + std::to_string(i);
            validate_fields(who.c_str(), sections_[i], PipeSection::fields());
            if (!(sections_[i].inner_diameter < sections_[i].outer_diameter))
                detail::reject(who.c_str(), "inner_diameter", "< outer_diameter (a tube has a wall)",
                               sections_[i].inner_diameter);
            check_section_scale(who.c_str(), sections_[i]);
        }
        if (!std::isfinite(length()))
            detail::reject("DrillString", "length", "such that the sections' total length is finite", length());
    }

    const std::vector<PipeSection>& sections() const { return sections_; }
    double length() const {
        double total = 0.0;
        for (const PipeSection& s : sections_) total += s.length;
        return total;
    }

    /// N elements of equal length dx = L / N (see the header comment for elements across a section boundary).
    LumpedString lump(std::size_t elements) const {
        if (elements == 0) detail::reject("DrillString", "elements", "at least 1", 0.0);
        LumpedString out;
        const double total = length();
        out.element_length = total / static_cast<double>(elements);
        out.node_inertia.assign(elements + 1, 0.0);
        out.node_mass.assign(elements + 1, 0.0);
        for (std::size_t e = 0; e < elements; ++e) {
            const double a = total * static_cast<double>(e) / static_cast<double>(elements);
            const double b = total * static_cast<double>(e + 1) / static_cast<double>(elements);
            double torsional_compliance = 0.0, axial_compliance = 0.0, inertia = 0.0, mass = 0.0;
            double top = 0.0;
            for (const PipeSection& s : sections_) {  // the pieces of [a, b] in each section
                const double lo = std::max(a, top), hi = std::min(b, top + s.length);
                top += s.length;
                if (!(hi > lo)) continue;
                const double dx = hi - lo;
                torsional_compliance += dx / s.torsional_rigidity();
                axial_compliance += dx / s.axial_rigidity();
                inertia += dx * s.inertia_per_length();
                mass += dx * s.mass_per_length();
            }
            out.torsional_stiffness.push_back(1.0 / torsional_compliance);
            out.axial_stiffness.push_back(1.0 / axial_compliance);
            out.node_inertia[e] += 0.5 * inertia;
            out.node_inertia[e + 1] += 0.5 * inertia;
            out.node_mass[e] += 0.5 * mass;
            out.node_mass[e + 1] += 0.5 * mass;
        }
        // every section is representable (check_section_scale); what is left is dx itself, L / N
        const auto positive = [](double v) { return std::isfinite(v) && v >= DBL_MIN; };
        for (std::size_t e = 0; e < elements; ++e)
            if (!positive(out.torsional_stiffness[e]) || !positive(out.axial_stiffness[e]))
                detail::reject("DrillString", "elements", "few enough that each element's length L / N keeps its "
                               "springs G I_p / dx and E A / dx finite", static_cast<double>(elements));
        for (std::size_t i = 0; i <= elements; ++i)
            if (!positive(out.node_inertia[i]) || !positive(out.node_mass[i]))
                detail::reject("DrillString", "elements", "few enough that each node's share of the string keeps "
                               "a positive inertia and mass", static_cast<double>(elements));
        return out;
    }

private:
    std::vector<PipeSection> sections_;
};

}  // namespace frictionsim
