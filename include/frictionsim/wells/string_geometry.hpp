// A StringRig standing in a surveyed well (issue 13, item 3; issue 14, item 1): the nodes of DrillString::lump(N)
// placed along a Survey from measured depth 0 (node 0 at the surface, node N at the bit), each node's hole
// inclination, and each node's wall contact force from the soft-string balance (soft_string.hpp: buoyed weight,
// inclination, curvature times tension; Johancsik, Friesen & Dawson 1984) for the string hanging at rest or
// rotating off bottom, where the wall friction has no axial share and the effective tension is the buoyed weight
// along the hole below the node, W_e dTVD_e / dL_e per element, less the weight on bit:
//     F_N = F_bit,  F_e = F_{e+1} + W_e (TVD_{e+1} - TVD_e) / dL_e.
// SoftString::node_side_forces lumps each element's side force under the mean of its end tensions half to each of
// its nodes: with no weight, around an arc of curvature kappa, every inner node carries F kappa dL (the capstan's
// differential form). The dynamic model keeps these forces fixed (the tension's dynamic part does not feed back).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "../detail/validate.hpp"
#include "../bits/bit.hpp"
#include "../string/sections.hpp"
#include "soft_string.hpp"
#include "../string/string_rig_params.hpp"
#include "../survey.hpp"

namespace frictionsim {

/// Per node 0..N of a lumped string in a surveyed well: measured depth [m], hole inclination [rad], effective
/// tension of the string at rest [N] and the soft-string wall contact force lumped to the node [N].
struct StringGeometry {
    std::vector<double> measured_depth, inclination, tension, normal_force;
};

/// The geometry of `string` in N = `elements` elements along `survey` in mud of density `mud_density` [kg/m^3]
/// (equal to the steel's: a weightless string), with effective tension `bit_tension` [N] at the bit (0 off bottom,
/// -W on bottom, a pull > 0). The survey must start at measured depth <= 0 and reach the bit (InvalidParameter).
inline StringGeometry string_geometry(const Survey& survey, const DrillString& string, std::size_t elements,
                                      double mud_density, double bit_tension = 0.0) {
    detail::require_finite("string_geometry", "bit_tension", bit_tension);
    detail::require_non_negative("string_geometry", "mud_density", mud_density);
    const SoftString soft(survey, string, elements);
    StringGeometry g;
    g.measured_depth = soft.node_depths();
    g.inclination = soft.node_inclinations();
    const std::size_t n = elements;
    std::vector<double> tvd(n + 1);
    for (std::size_t i = 0; i <= n; ++i) tvd[i] = survey.at(g.measured_depth[i]).tvd;
    g.tension.assign(n + 1, bit_tension);
    for (std::size_t e = n; e-- > 0;) {  // from the bit up: each element's weight along its chord
        const double along = (tvd[e + 1] - tvd[e]) / (g.measured_depth[e + 1] - g.measured_depth[e]);
        g.tension[e] = g.tension[e + 1] + soft.element_weight(e, mud_density) * along;
    }
    soft.node_side_forces(g.tension, mud_density, g.normal_force);
    return g;
}

/// `setup` with the survey's geometry for a StringRig of `string` with parameters `p` and bit `bit` (the same
/// objects the rig is built from): node_inclinations from the survey and, when `setup.normal_forces` is empty, the
/// soft-string force of each contact node (setup.contact_nodes, or every node the rig gives a contact: 1..N, below N
/// with the bit on bottom). The bit's weight W and a rigid end mass m_end (buoyed, along the hole) load the bit
/// node: tension -W + m_end g' cos I_N there, and m_end g' sin I_N added to the node's wall force.
template <class Bit = OffBottom>
StringRigSetup surveyed_setup(const Survey& survey, const DrillString& string, const StringRigParams& p,
                              StringRigSetup setup, const Bit& bit = Bit{}) {
    constexpr bool on_bottom = bit_touches_rock<Bit>();
    const std::size_t n = setup.elements;
    if (n == 0) detail::reject("surveyed_setup", "elements", "at least 1", 0.0);
    detail::require_non_negative("surveyed_setup", "mud_density", p.mud_density);
    const double bottom_density = string.sections().back().density;
    const double end_weight = p.end_mass * standard_gravity * (1.0 - p.mud_density / bottom_density);
    const double bit_inclination = survey.at(string.length()).inclination;
    const double weight_on_bit = on_bottom ? bit.weight_on_bit() : 0.0;
    const StringGeometry g = string_geometry(survey, string, n, p.mud_density,
                                             -weight_on_bit + end_weight * std::cos(bit_inclination));
    setup.node_inclinations = g.inclination;
    if (setup.normal_forces.empty()) {
        std::vector<double> node_force = g.normal_force;
        node_force[n] += end_weight * std::sin(bit_inclination);
        std::vector<std::size_t> nodes = setup.contact_nodes;
        if (nodes.empty() && setup.wall_contacts)
            for (std::size_t i = 1; i <= n; ++i)
                if (i < n || !on_bottom) nodes.push_back(i);
        if (!setup.wall_contacts) nodes.clear();
        for (std::size_t i : nodes) {
            if (i > n) detail::reject("surveyed_setup", "contact_nodes", "in 1..N", static_cast<double>(i));
            setup.normal_forces.push_back(node_force[i]);
        }
    }
    return setup;
}

}  // namespace frictionsim
