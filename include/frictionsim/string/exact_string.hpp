// The exact treatment of a TorsionalString (issue 22: one string model, a choice of wall-contact treatment): the
// same string on the event-driven StringRig, every wall's and the bit's stick and slip located as events. The
// TorsionalString is the description (sections, lumping, drive, damping, the walls' bounds from the buoyed weight
// and the well's inclination); this builds the StringRig that carries the same physics:
//   lumping:  the same N elements (DrillString::lump), I_TD on node 0, the BHA's inertia on node N;
//   drive:    the continuous PI, k_p e + k_i int e on node 0 (StringRig's PiTopDrive, its torque limit the string's
//             torque_limit, or out of reach where that is 0: no limit), or the prescribed speed (top_drive
//             prescribed_speed: StringRig's PrescribedSpeed), the set-point ramped as the captured string's,
//             omega_SP (1 - exp(-t / T_SP)) (setpoint_time_constant; 0 a step); the sampled PI (control_period
//             T_c > 0: StringRig's SampledPiTopDrive, A&S's MAIN.m as the captured string's, sampled at t_0 + k T_c
//             with t_0 = 0, each sample located as an event);
//   damping:  StringRig's element damping beta k_e (damping_time) and A&S's absolute k_t (damping_rate: k_t
//             times each node's string inertia, the captured string's C(i, i));
//   walls:    a Coulomb contact at each node with a bound (static mu_s N r, kinetic f_rat times it), the normal
//             force N_i = bound_i / (mu_s r_i) so that the bounds are the string's to rounding;
//   bit:      off bottom none; on bottom NavarroLopezBit with node N's wall merged into one contact (both act on
//             node N: their bounds add), as the captured string's node N.
// What StringRig cannot carry is refused, naming the parameter: a stick band, a bit torque off bottom, a wall at
// node 0 (the top drive's node has none in StringRig).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "../bits/bit_rock.hpp"
#include "../detail/validate.hpp"
#include "../friction/coulomb.hpp"
#include "string_rig.hpp"
#include "torsional_string.hpp"

namespace frictionsim {

/// The on-bottom bit of a TorsionalString's node N for StringRig: NavarroLopezBit under weight W plus node N's
/// Coulomb wall, one contact (bits/bit.hpp's interface).
struct BitWithWall {
    static constexpr const char* name = "BitWithWall";
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;
    static constexpr bool touches_rock = true;
    NavarroLopezBit law;
    double weight = 0.0, wall_static = 0.0, wall_kinetic = 0.0;
    double weight_on_bit() const { return weight; }
    double static_limit(double w) const { return law.static_limit(w) + wall_static; }
    double slip_force(double v, double w, int dir) const { return law.slip_force(v, w, dir) + dir * wall_kinetic; }
    double slip_slope(double v, double w, int dir) const { return law.slip_slope(v, w, dir); }
    double karnopp_band() const { return 0.0; }
};

using ExactString = StringRig<Coulomb, OffBottom>;
using ExactStringOnBottom = StringRig<Coulomb, BitWithWall>;

namespace detail {

/// StringRig's parameters, set-up and wall law for a TorsionalString (the walls at the nodes with a bound).
struct ExactStringParts {
    StringRigParams params;
    StringRigSetup setup;
    Coulomb walls{1.0};
};

inline ExactStringParts exact_string_parts(const TorsionalString& ts) {
    constexpr const char* who = "exact_string";
    const TorsionalStringParams& p = ts.params();
    if (p.stick_band_speed > 0.0)
        reject(who, "stick_band_speed", "0 (StringRig's Coulomb walls have no stick band)", p.stick_band_speed);
    if (p.bit_torque > 0.0) reject(who, "bit_torque", "0 (StringRig's bit off bottom carries no torque)", p.bit_torque);
    const std::vector<double>& bound = ts.static_friction_torque();
    if (bound.front() > 0.0)
        reject(who, "static_friction_torque[0]", "0: no wall at the top drive's node (a vertical top, or mu 0)",
               bound.front());
    ExactStringParts out;
    StringRigParams& q = out.params;
    q.top_drive_inertia = p.top_drive_inertia;
    q.proportional_gain = p.proportional_gain;
    q.integral_gain = p.integral_gain;
    q.surface_speed = p.speed_setpoint;
    q.torque_limit = p.torque_limit > 0.0 ? p.torque_limit : 1e300;  // 0: no limit, out of reach
    q.end_inertia = p.bha_inertia;
    q.mud_density = p.mud_density;
    q.damping_time = p.damping_time;
    q.damping_rate = p.damping_rate;
    q.setpoint_time_constant = p.setpoint_time_constant;
    q.control_period = p.control_period;
    StringRigSetup& s = out.setup;
    s.elements = ts.nodes() - 1;
    s.top_drive = ts.top_drive();
    const double mu_s = p.friction_coefficient;
    s.wall_contacts = mu_s > 0.0 && ts.contact_count() > 0;
    const std::vector<PipeSection>& sections = ts.string().sections();
    for (std::size_t i : ts.wall_contact_nodes()) {  // N_i from the bound: mu_s N_i r_i = the string's bound
        const double x = static_cast<double>(i) * ts.lumped().element_length;
        double top = 0.0, radius = 0.0;  // StringRig's radius: the larger OD at a section boundary
        for (const PipeSection& sec : sections) {
            if (x >= top - 1e-9 && x <= top + sec.length + 1e-9) radius = std::max(radius, 0.5 * sec.outer_diameter);
            top += sec.length;
        }
        s.contact_nodes.push_back(i);
        s.normal_forces.push_back(bound[i] / (mu_s * radius));
    }
    const double mu = std::max(mu_s, 1e-3);  // a Coulomb law needs mu > 0; without walls it is never read
    out.walls = Coulomb(p.kinetic_ratio * mu, mu);
    return out;
}

}  // namespace detail

/// The exact treatment of an off-bottom TorsionalString (see the header). The string's contact_radius must be its
/// sections' OD / 2 at the wall nodes for the radii to agree; the normal forces are chosen so that the bounds do.
inline ExactString exact_string(const TorsionalString& ts) {
    if (ts.bit_on_bottom())
        detail::reject("exact_string", "weight_on_bit", "0 (on bottom: exact_string_on_bottom)",
                       ts.params().weight_on_bit);
    detail::ExactStringParts parts = detail::exact_string_parts(ts);
    return ExactString(ts.string(), parts.params, std::move(parts.setup), parts.walls);
}

/// The exact treatment of an on-bottom TorsionalString: its bit with node N's wall as one located contact.
inline ExactStringOnBottom exact_string_on_bottom(const TorsionalString& ts) {
    if (!ts.bit_on_bottom())
        detail::reject("exact_string_on_bottom", "weight_on_bit", "> 0 (off bottom: exact_string)",
                       ts.params().weight_on_bit);
    detail::ExactStringParts parts = detail::exact_string_parts(ts);
    const double wall = ts.static_friction_torque().back();
    const BitWithWall bit{ts.bit_law(), ts.params().weight_on_bit, wall, ts.params().kinetic_ratio * wall};
    return ExactStringOnBottom(ts.string(), parts.params, std::move(parts.setup), parts.walls, bit);
}

}  // namespace frictionsim
