// Soft-string torque and drag (issue 14, item 2): the string follows the hole's axis, carries no bending moment,
// and each element's wall contact force comes from its buoyed weight and the change of direction of the tension
// across it. Johancsik, Friesen & Dawson (1984, SPE 11380), element by element from the bit up:
//     F_n = sqrt( (F dA sin I_avg)^2 + (F dI + W sin I_avg)^2 )           side force of the element
//     F_top = F + W cos I  +/- mu_axial F_n,   M_top = M + mu_circ F_n r     (+ pulling out, - running in)
// with F the effective tension at the element's lower end, W its buoyed weight, dI = I_top - I_bottom, dA the
// azimuth change and r the pipe's radius. Here (F dA sin I_avg)^2 is written F^2 (beta^2 - dI^2), beta the
// element's dogleg on the minimum-curvature well: equal to Johancsik's term as the element shrinks, and right where
// the well passes the vertical (azimuth undefined). W cos I is the weight's exact axial share on the arc,
// W dTVD / dL. The side force per length is then the curvature form |F kappa n + w g_perp| (kappa the dogleg
// severity, n the arc's normal, g_perp the weight's share across the pipe): with no weight the capstan relation
// F_out = F_in exp(+/- mu theta) of Aadnoy's curved sections is its limit, and in a build the continuous equation
// dF/ds = -w cos I -/+ mu |F kappa - w sin I| (contact on the high side or, the absolute value, the low side).
// The explicit step (F at the lower end) approaches both at first order in the element length.
// Friction acts against the sliding velocity of the pipe's surface (paper 000's friction vector): with axial
// speed v and surface speed omega r, mu_axial = mu v / sqrt(v^2 + (omega r)^2) and mu_circ = mu omega r / sqrt(...),
// which is why rotation cuts drag.
// Buoyancy: same mud inside and out, W = g (m - rho_mud V) (the buoyancy-factor form): the tension is the effective
// tension, zero at a bit off bottom, -WOB on bottom; at the surface it is the hook load (less the block weight).
// Per-element friction multipliers (FrictionMultipliers) scale each element's axial and circumferential friction:
// what a cycle average under axial vibration gives (oscillator_drag.hpp); all ones reproduce the plain run exactly.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../detail/constants.hpp"
#include "../parameters.hpp"
#include "sections.hpp"
#include "survey.hpp"

namespace frictionsim {

inline constexpr double standard_gravity = 9.80665;  ///< m/s^2

/// The steady operations of torque and drag. Which speeds and bit loads each one uses:
///   trip_in, trip_out          axial at trip_speed, no rotation, bit off bottom
///   reaming, backreaming       axial (in, out) at trip_speed and rotating at rotary_speed, off bottom
///   rotating_off_bottom        rotary_speed only
///   sliding_drilling           in at rate_of_penetration, no rotation, weight_on_bit (the motor's reactive
///                              torque is not carried: torque zero along the string)
///   rotary_drilling            in at rate_of_penetration, rotary_speed, weight_on_bit and bit_torque
/// With no rotation the friction is wholly axial whatever the axial speed (sliding at ROP -> 0 included).
enum class Operation {
    trip_in,
    trip_out,
    reaming,
    backreaming,
    rotating_off_bottom,
    sliding_drilling,
    rotary_drilling
};

inline const char* operation_name(Operation op) {
    switch (op) {
        case Operation::trip_in: return "trip_in";
        case Operation::trip_out: return "trip_out";
        case Operation::reaming: return "reaming";
        case Operation::backreaming: return "backreaming";
        case Operation::rotating_off_bottom: return "rotating_off_bottom";
        case Operation::sliding_drilling: return "sliding_drilling";
        case Operation::rotary_drilling: return "rotary_drilling";
    }
    return "unknown";
}

/// Mud, hole, friction and the operation's speeds and bit loads. Defaults: 1.2 SG mud, 8 1/2" open hole below
/// 9 5/8" 47 lb/ft casing, friction factors 0.25 cased / 0.30 open, 0.3 m/s trips, 30 m/h ROP, 120 rpm.
struct SoftStringParams {
    double mud_density = 1200.0;                    ///< kg/m^3
    double cased_hole_friction = 0.25;              ///< mu above the casing shoe
    double open_hole_friction = 0.30;               ///< mu below it
    double casing_shoe_depth = 0.0;                 ///< m MD; 0: all open hole
    double casing_inner_diameter = 0.2205;          ///< m
    double hole_diameter = 0.2159;                  ///< m, open hole
    double trip_speed = 0.3;                        ///< m/s (trips, reaming)
    double rate_of_penetration = 30.0 / 3600.0;     ///< m/s (drilling)
    double rotary_speed = 4.0 * pi;                 ///< rad/s at the surface (120 rpm)
    double weight_on_bit = 0.0;                     ///< N (drilling)
    double bit_torque = 0.0;                        ///< N m (rotary drilling)

    static constexpr std::array<Field<SoftStringParams>, 11> fields();
};

inline constexpr std::array<Field<SoftStringParams>, 11> SoftStringParams::fields() {
    using P = SoftStringParams;
    return {{
        {"mud_density", "rho_m", "kg/m^3", Rule::non_negative(), &P::mud_density, "Mud density (inside and out)."},
        {"cased_hole_friction", "mu_c", "-", Rule::non_negative(), &P::cased_hole_friction,
         "Friction factor inside the casing."},
        {"open_hole_friction", "mu_o", "-", Rule::non_negative(), &P::open_hole_friction,
         "Friction factor in the open hole."},
        {"casing_shoe_depth", "MD_shoe", "m", Rule::non_negative(), &P::casing_shoe_depth,
         "Measured depth of the casing shoe (0: no casing)."},
        {"casing_inner_diameter", "ID_c", "m", Rule::positive(), &P::casing_inner_diameter,
         "Casing inner diameter (buckling clearance above the shoe)."},
        {"hole_diameter", "D_h", "m", Rule::positive(), &P::hole_diameter,
         "Open-hole diameter (buckling clearance below the shoe)."},
        {"trip_speed", "v_trip", "m/s", Rule::positive(), &P::trip_speed, "Axial speed of trips and reaming."},
        {"rate_of_penetration", "ROP", "m/s", Rule::non_negative(), &P::rate_of_penetration,
         "Axial speed while drilling."},
        {"rotary_speed", "omega", "rad/s", Rule::positive(), &P::rotary_speed,
         "Rotary speed of the rotating operations."},
        {"weight_on_bit", "WOB", "N", Rule::non_negative(), &P::weight_on_bit, "Weight on bit while drilling."},
        {"bit_torque", "TOB", "N m", Rule::non_negative(), &P::bit_torque, "Torque on bit, rotary drilling."},
    }};
}

/// Torque and drag along the string, node 0 at the surface, node N at the bit; element e joins nodes e and e + 1.
struct TorqueDragResult {
    Operation operation = Operation::trip_out;
    std::vector<double> measured_depth;          ///< per node, m
    std::vector<double> tension;                 ///< effective tension per node, N (compression < 0)
    std::vector<double> torque;                  ///< per node, N m
    std::vector<double> side_force;              ///< wall contact force of each element, N
    std::vector<double> side_force_per_length;   ///< per element, N/m
    std::vector<double> sinusoidal_buckling_load;  ///< Dawson-Paslay, per node, N
    std::vector<double> helical_buckling_load;     ///< Chen-Lin-Cheatham, per node, N
    std::vector<std::uint8_t> sinusoidally_buckled, helically_buckled;  ///< compression above the load, per node

    double hook_load() const { return tension.front(); }     ///< N
    double surface_torque() const { return torque.front(); }  ///< N m
};

/// What an operation imposes: the direction of axial motion (+1 out of the hole, -1 in, 0 none), the axial and
/// rotary speeds, and the bit's loads (the table in Operation's comment).
struct OperationKinematics {
    double direction = 0.0;     ///< -1, 0 or +1
    double axial_speed = 0.0;   ///< m/s, >= 0
    double rotary_speed = 0.0;  ///< rad/s, >= 0
    double bit_force = 0.0;     ///< effective tension at the bit, N (-WOB on bottom)
    double bit_torque = 0.0;    ///< N m
};

inline OperationKinematics operation_kinematics(Operation op, const SoftStringParams& p) {
    OperationKinematics k;
    switch (op) {
        case Operation::trip_in:
        case Operation::trip_out:
        case Operation::reaming:
        case Operation::backreaming:
            k.direction = op == Operation::trip_out || op == Operation::backreaming ? 1.0 : -1.0;
            k.axial_speed = p.trip_speed;
            if (op == Operation::reaming || op == Operation::backreaming) k.rotary_speed = p.rotary_speed;
            break;
        case Operation::rotating_off_bottom: k.rotary_speed = p.rotary_speed; break;
        case Operation::sliding_drilling:
            k.direction = -1.0;
            k.axial_speed = p.rate_of_penetration;
            k.bit_force = -p.weight_on_bit;
            break;
        case Operation::rotary_drilling:
            k.direction = -1.0;
            k.axial_speed = p.rate_of_penetration;
            k.rotary_speed = p.rotary_speed;
            k.bit_force = -p.weight_on_bit;
            k.bit_torque = p.bit_torque;
            break;
    }
    return k;
}

/// Per-element factors on the friction of the soft string (1: unchanged): `axial` scales the axial share
/// mu v / |q|, `circumferential` the share mu omega r / |q|. An empty vector means 1 everywhere; otherwise one
/// finite, non-negative value per element.
struct FrictionMultipliers {
    std::vector<double> axial, circumferential;
};

/// A drill string hung from measured depth 0 along a survey, cut into N elements of equal length (the nodes of
/// DrillString::lump(N)), with the properties and geometry each element needs precomputed: each run() is one pass
/// without allocation (when given a result to reuse).
class SoftString {
public:
    SoftString(const Survey& survey, const DrillString& string, std::size_t elements) {
        if (elements == 0) detail::reject("SoftString", "elements", "at least 1", 0.0);
        const double length = string.length();
        if (!(survey.first_depth() <= 0.0))
            detail::reject("SoftString", "survey first measured_depth",
                           "<= 0 (the string hangs from measured depth 0)", survey.first_depth());
        if (!(survey.last_depth() >= length)) {
            const std::string rule =
                ">= the string's length, " + std::to_string(length) + " m (the survey must reach the bit)";
            detail::reject("SoftString", "survey last measured_depth", rule.c_str(), survey.last_depth());
        }
        const double n = static_cast<double>(elements);
        element_length_ = length / n;
        depth_.resize(elements + 1);
        inclination_.resize(elements + 1);
        sqrt_sin_inclination_.resize(elements + 1);
        std::vector<WellPoint> node(elements + 1);
        for (std::size_t i = 0; i <= elements; ++i) {
            depth_[i] = i == elements ? length : length * static_cast<double>(i) / n;
            node[i] = survey.at(depth_[i]);
            inclination_[i] = node[i].inclination;
            sqrt_sin_inclination_[i] = std::sqrt(std::sin(inclination_[i]));
        }
        element_.resize(elements);
        for (std::size_t e = 0; e < elements; ++e) {
            Element& el = element_[e];
            const double a = depth_[e], b = depth_[e + 1];
            el.length = b - a;
            el.mid_depth = 0.5 * (a + b);
            double top = 0.0, radius_length = 0.0;
            el.bending_stiffness = 0.0;
            for (const PipeSection& s : string.sections()) {  // the pieces of [a, b] in each section
                const double lo = std::max(a, top), hi = std::min(b, top + s.length);
                top += s.length;
                if (!(hi > lo)) continue;
                const double dx = hi - lo;
                el.mass += dx * s.mass_per_length();
                el.volume += dx * s.area();
                radius_length += dx * 0.5 * s.outer_diameter;
                el.outer_diameter = std::max(el.outer_diameter, s.outer_diameter);
                const double ei = s.youngs_modulus * 0.5 * s.polar_moment();  // E I, I = I_p / 2
                el.bending_stiffness = el.bending_stiffness > 0.0 ? std::min(el.bending_stiffness, ei) : ei;
            }
            el.radius = radius_length / el.length;
            el.dogleg = angle_between(node[e].tangent, node[e + 1].tangent);
            el.inclination_change = node[e].inclination - node[e + 1].inclination;
            el.sin_inclination = std::sin(0.5 * (node[e].inclination + node[e + 1].inclination));
            el.axial_share = (node[e + 1].tvd - node[e].tvd) / el.length;
            el.lateral_turn_sq = std::max(el.dogleg * el.dogleg - el.inclination_change * el.inclination_change, 0.0);
        }
    }

    std::size_t elements() const { return element_.size(); }
    double element_length() const { return element_length_; }
    const std::vector<double>& node_depths() const { return depth_; }
    const std::vector<double>& node_inclinations() const { return inclination_; }

    /// Buoyed weight of element e [N] in mud of the given density.
    double element_weight(std::size_t e, double mud_density) const {
        return standard_gravity * (element_[e].mass - mud_density * element_[e].volume);
    }

    /// Measured depth of element e's middle [m] and its contact radius (length-weighted OD / 2) [m].
    double element_mid_depth(std::size_t e) const { return element_[e].mid_depth; }
    double element_radius(std::size_t e) const { return element_[e].radius; }
    /// The friction factor of element e: cased above the shoe (by its middle), open hole below.
    static double friction_factor(double mid_depth, const SoftStringParams& p) {
        return mid_depth < p.casing_shoe_depth ? p.cased_hole_friction : p.open_hole_friction;
    }

    /// Wall contact force [N] of element e under tension F [N] (the expression in the header comment).
    double element_side_force(std::size_t e, double tension, double mud_density) const {
        return side_force(element_[e], tension, element_weight(e, mud_density));
    }

    /// One operation; out's vectors are resized once and reused by later calls.
    void run(Operation op, const SoftStringParams& p, TorqueDragResult& out) const {
        run(op, p, nullptr, nullptr, out);
    }

    /// One operation with each element's friction scaled by `m` (FrictionMultipliers; checked: one finite,
    /// non-negative value per element, or empty).
    void run(Operation op, const SoftStringParams& p, const FrictionMultipliers& m, TorqueDragResult& out) const {
        check_multipliers(m.axial, "axial");
        check_multipliers(m.circumferential, "circumferential");
        run(op, p, m.axial.empty() ? nullptr : m.axial.data(),
            m.circumferential.empty() ? nullptr : m.circumferential.data(), out);
    }

    TorqueDragResult run(Operation op, const SoftStringParams& p, const FrictionMultipliers& m) const {
        TorqueDragResult out;
        run(op, p, m, out);
        return out;
    }

private:
    void run(Operation op, const SoftStringParams& p, const double* axial_multiplier,
             const double* circumferential_multiplier, TorqueDragResult& out) const {
        validate_fields("SoftStringParams", p, SoftStringParams::fields());
        const std::size_t n = element_.size();
        out.operation = op;
        out.measured_depth = depth_;
        out.tension.resize(n + 1);
        out.torque.resize(n + 1);
        out.side_force.resize(n);
        out.side_force_per_length.resize(n);
        out.sinusoidal_buckling_load.resize(n + 1);
        out.helical_buckling_load.resize(n + 1);
        out.sinusoidally_buckled.resize(n + 1);
        out.helically_buckled.resize(n + 1);

        // the operation: direction of axial motion (+1 out of the hole), axial speed, rotation, bit loads
        const OperationKinematics kin = operation_kinematics(op, p);
        const double direction = kin.direction, axial_speed = kin.axial_speed, rotary_speed = kin.rotary_speed;
        double force = kin.bit_force, torque = kin.bit_torque;
        out.tension[n] = force;
        out.torque[n] = torque;
        for (std::size_t k = n; k-- > 0;) {  // from the bit up
            const Element& el = element_[k];
            const double weight = standard_gravity * (el.mass - p.mud_density * el.volume);
            const double normal = side_force(el, force, weight);
            const bool cased = el.mid_depth < p.casing_shoe_depth;
            const double mu = cased ? p.cased_hole_friction : p.open_hole_friction;
            double axial = 1.0, circumferential = 0.0;  // the friction vector's shares
            const double surface_speed = rotary_speed * el.radius;
            // hypot: at a tiny rotary speed (omega r)^2 underflows, and sqrt(v^2 + (omega r)^2) would give 0/0
            const double speed = std::hypot(axial_speed, surface_speed);
            if (rotary_speed > 0.0 && speed > 0.0) {
                axial = axial_speed / speed;
                circumferential = surface_speed / speed;
            }
            if (axial_multiplier) axial *= axial_multiplier[k];  // times 1.0 is exact: no tool, the plain run
            if (circumferential_multiplier) circumferential *= circumferential_multiplier[k];
            const double friction = mu * normal;
            force += weight * el.axial_share + direction * axial * friction;
            torque += circumferential * friction * el.radius;
            out.tension[k] = force;
            out.torque[k] = torque;
            out.side_force[k] = normal;
            out.side_force_per_length[k] = normal / el.length;

            // buckling (the loads of buckling.hpp): 2 sqrt(E I |w| / r) sqrt(sin I) at each end; a node takes its
            // weaker element
            const double hole = cased ? p.casing_inner_diameter : p.hole_diameter;
            const double clearance = 0.5 * (hole - el.outer_diameter);
            if (!(clearance > 0.0)) reject_clearance(cased, el, hole);
            const double scale = 2.0 * std::sqrt(el.bending_stiffness * std::abs(weight) / el.length / clearance);
            const double below = scale * sqrt_sin_inclination_[k + 1];
            out.sinusoidal_buckling_load[k + 1] =
                k + 1 == n ? below : std::min(out.sinusoidal_buckling_load[k + 1], below);
            out.sinusoidal_buckling_load[k] = scale * sqrt_sin_inclination_[k];
        }
        for (std::size_t i = 0; i <= n; ++i) {  // Chen-Lin-Cheatham: sqrt(2) times Dawson-Paslay
            out.helical_buckling_load[i] = std::sqrt(2.0) * out.sinusoidal_buckling_load[i];
            out.sinusoidally_buckled[i] = -out.tension[i] > out.sinusoidal_buckling_load[i];
            out.helically_buckled[i] = -out.tension[i] > out.helical_buckling_load[i];
        }
    }

    void check_multipliers(const std::vector<double>& m, const char* which) const {
        if (m.empty()) return;
        const std::string name = std::string("friction_multipliers.") + which;
        if (m.size() != element_.size())
            detail::reject("SoftString", name.c_str(),
                           ("empty or one value per element (" + std::to_string(element_.size()) + ")").c_str(),
                           static_cast<double>(m.size()));
        for (std::size_t e = 0; e < m.size(); ++e)
            if (!(std::isfinite(m[e]) && m[e] >= 0.0))
                detail::reject("SoftString", (name + "[" + std::to_string(e) + "]").c_str(),
                               "non-negative and finite", m[e]);
    }

public:
    TorqueDragResult run(Operation op, const SoftStringParams& p) const {
        TorqueDragResult out;
        run(op, p, out);
        return out;
    }

    /// The wall contact force at each node [N] for a given effective tension per node (N + 1 values, surface
    /// first): each element's side force under the mean of its end tensions, half to each of its nodes. What the
    /// dynamic string model takes as the normal force of its wall contacts. `out` holds N + 1 values.
    void node_side_forces(const std::vector<double>& tension, double mud_density, std::vector<double>& out) const {
        const std::size_t n = element_.size();
        if (tension.size() != n + 1)
            detail::reject("SoftString", "tension", ("one value per node (" + std::to_string(n + 1) + ")").c_str(),
                           static_cast<double>(tension.size()));
        detail::require_non_negative("SoftString", "mud_density", mud_density);
        out.assign(n + 1, 0.0);
        for (std::size_t k = 0; k < n; ++k) {
            if (!std::isfinite(tension[k + 1]) || !std::isfinite(tension[k])) {
                const std::string name = "tension[" + std::to_string(std::isfinite(tension[k]) ? k + 1 : k) + "]";
                detail::reject("SoftString", name.c_str(), "finite",
                               std::isfinite(tension[k]) ? tension[k + 1] : tension[k]);
            }
            const double half = 0.5 * element_side_force(k, 0.5 * (tension[k] + tension[k + 1]), mud_density);
            out[k] += half;
            out[k + 1] += half;
        }
    }

    std::vector<double> node_side_forces(const std::vector<double>& tension, double mud_density) const {
        std::vector<double> out;
        node_side_forces(tension, mud_density, out);
        return out;
    }

private:
    struct Element {
        double length = 0.0, mid_depth = 0.0;
        double mass = 0.0, volume = 0.0;  // steel: kg, m^3
        double radius = 0.0;              // contact radius (length-weighted OD / 2), m
        double outer_diameter = 0.0;      // largest OD (buckling clearance), m
        double bending_stiffness = 0.0;   // smallest E I, N m^2
        double dogleg = 0.0;              // beta, rad
        double inclination_change = 0.0;  // I_top - I_bottom, rad
        double lateral_turn_sq = 0.0;     // beta^2 - dI^2: Johancsik's (dA sin I_avg)^2
        double sin_inclination = 0.0;     // sin I_avg
        double axial_share = 0.0;         // dTVD / dL: the weight's axial share
    };

    [[noreturn]] static void reject_clearance(bool cased, const Element& el, double hole) {
        const std::string rule = "> the pipe's outer diameter, " + std::to_string(el.outer_diameter) +
                                 " m, at measured depth " + std::to_string(el.mid_depth) + " m";
        detail::reject("SoftStringParams", cased ? "casing_inner_diameter" : "hole_diameter", rule.c_str(), hole);
    }

    static double side_force(const Element& el, double tension, double weight) {
        const double vertical = tension * el.inclination_change + weight * el.sin_inclination;
        return std::sqrt(tension * tension * el.lateral_turn_sq + vertical * vertical);
    }

    double element_length_ = 0.0;
    std::vector<double> depth_, inclination_, sqrt_sin_inclination_;
    std::vector<Element> element_;
};

}  // namespace frictionsim
