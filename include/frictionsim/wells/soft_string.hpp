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
//
// TorqueDragMethod::aadnoy, the curvature form (Aadnoy & Andersen 2001, J. Pet. Sci. Eng. 32, 53-71; Aadnoy,
// Fazaelizadeh & Hareland 2010, JCPT 49(10), 25-36): each element is integrated in closed form instead of stepped.
// The sections of those papers are its special cases (their equations for straight sections, for build-up and
// drop-off sections with weight, and for side bends / combined 3D bends; the equation numbers are not quoted here,
// the forms are derived below):
//     straight:                F_top = F + w L (cos I +/- mu sin I),          M_top = M + mu r w L sin I
//     build/drop with weight:  the linear equation dF/dI = -R (w cos I +/- mu (F / R - w sin I)) solved exactly:
//                              A cos I + B sin I + C exp(-/+ mu I), the curved sections' exponential factor
//     side bend / 3D dogleg:   the capstan F_top = F exp(+/- mu |theta|) on the absolute dogleg theta, and
//                              M_top = M + mu r F |theta| under rotation alone
// Derivation (ours; it unifies the three): on a minimum-curvature element the tangent turns at the rate kappa in a
// fixed plane with unit normal b. Split gravity into its share rho = sqrt(1 - b_z^2) in that plane and b_z across it
// and let psi be the angle from the in-plane gravity to the tangent (psi grows down-hole). The side force per
// length is |(F kappa - rho w sin psi) n + b_z w b|: the in-plane term is Aadnoy's build with the weight rho w (a
// vertical build: rho = 1, psi = I; a horizontal side bend: rho = 0, the capstan), solved exactly and piecewise
// where F kappa - rho w sin psi changes sign (the contact moves to the other side: the root located by Illinois);
// the across term w b_z adds in quadrature and enters as a constant extra side force per length taken at the
// element's middle (second order in the element length; zero in a vertical plane, so exact there). In closed form,
// with u the distance up from the element's bottom, lambda = sigma eps kappa (sigma = +/- mu_axial, eps the
// contact's side), z = lambda + i kappa and phi1(x) = (e^x - 1) / x:
//     N(u) = eps (kappa u F_b phi1(lambda u) + rho w u Re[e^(i psi(u)) (kappa u phi1[z u, i kappa u]
//            + i phi1(z u))]) + e u phi1(lambda u),     F(u) = F_b + rho w u Re[e^(i psi(u)) phi1(i kappa u)] + sigma N
// (phi1[a, b] the divided difference): free of cancellation as kappa -> 0 (the straight element) or sigma -> 0 (pure
// rotation), so one formula serves every element.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../detail/constants.hpp"
#include "../detail/illinois.hpp"
#include "../parameters.hpp"
#include "../string/sections.hpp"
#include "../survey.hpp"

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

/// How each element is integrated: Johancsik's explicit step (first order in the element length, the default) or
/// Aadnoy's curvature form (closed form per element: exact on straight, planar build/drop and weightless curved
/// elements at any length; second order where the weight has a share across a 3D dogleg's plane).
enum class TorqueDragMethod { johancsik, aadnoy };

inline const char* torque_drag_method_name(TorqueDragMethod m) {
    return m == TorqueDragMethod::aadnoy ? "aadnoy" : "johancsik";
}

namespace detail {

/// phi1(x) = (e^x - 1) / x, 1 at 0: its series where the quotient would cancel.
inline std::complex<double> phi1(std::complex<double> x) {
    if (std::norm(x) < 0.25) {  // |x| < 0.5 (norm: no square root)
        std::complex<double> term = 1.0, sum = 1.0;
        for (int n = 1; n < 30; ++n) {
            term *= x / static_cast<double>(n + 1);
            sum += term;
            if (std::norm(term) < 1e-34 * std::norm(sum)) break;
        }
        return sum;
    }
    return (std::exp(x) - 1.0) / x;
}

inline double phi1(double x) { return x == 0.0 ? 1.0 : std::expm1(x) / x; }

/// The divided difference (phi1(a) - phi1(b)) / (a - b), phi1'(a) at a = b. Close arguments: the series
/// sum_{n >= 1} h_{n-1}(a, b) / (n + 1)!, h_m = sum_j a^j b^(m - j) (here |a|, |b| < 3.3: it converges).
inline std::complex<double> phi1_divided(std::complex<double> a, std::complex<double> b) {
    if (std::norm(a - b) >= 0.25) return (phi1(a) - phi1(b)) / (a - b);
    std::complex<double> power = 1.0, h = 1.0, sum = 0.5;
    double factorial = 2.0;
    for (int n = 2; n < 80; ++n) {
        power *= a;
        h = power + b * h;
        factorial *= static_cast<double>(n + 1);
        const std::complex<double> term = h / factorial;
        sum += term;
        if (std::norm(term) < 1e-34 * std::norm(sum) && std::norm(power) < 1.0) break;
    }
    return sum;
}

}  // namespace detail

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
        {"mud_density", "rho_m", "kg/m^3",
         Rule::interval(0.0, 1.0e4).because("drilling fluids are 800-2600 kg/m^3; steel is 7850"), &P::mud_density,
         "Mud density (inside and out)."},
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
        // bounded far above any rig (hook capacities ~1e7 N, bit torques ~1e5 N m): a typo of 1e300 would
        // overflow the tension's square in the side force and read as a friction lock-up
        {"weight_on_bit", "WOB", "N", Rule::interval(0.0, 1e9).because("1e9 N is 100 times the largest hook load"),
         &P::weight_on_bit, "Weight on bit while drilling."},
        {"bit_torque", "TOB", "N m", Rule::interval(0.0, 1e9).because("1e9 N m is 10^4 times a bit's torque"),
         &P::bit_torque, "Torque on bit, rotary drilling."},
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
/// without allocation (when given a result to reuse). `method` chooses how each element is integrated
/// (TorqueDragMethod; the side force of a result is then the element's integral of the side force per length).
class SoftString {
public:
    SoftString(const Survey& survey, const DrillString& string, std::size_t elements,
               TorqueDragMethod method = TorqueDragMethod::johancsik)
        : method_(method) {
        if (elements == 0) detail::reject("SoftString", "elements", "at least 1", 0.0);
        if (method != TorqueDragMethod::johancsik && method != TorqueDragMethod::aadnoy)
            detail::reject("SoftString", "method", "johancsik or aadnoy", static_cast<double>(method));
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
            place_in_plane(el, node[e].tangent, node[e + 1].tangent);
        }
    }

    TorqueDragMethod method() const { return method_; }

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

    /// Wall contact force [N] of element e under tension F [N] (Johancsik's expression in the header comment,
    /// whichever the method: what node_side_forces lumps).
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
            double normal = 0.0;
            if (method_ == TorqueDragMethod::johancsik) {
                normal = side_force(el, force, weight);
                const double friction = mu * normal;
                force += weight * el.axial_share + direction * axial * friction;
                torque += circumferential * friction * el.radius;
            } else {
                force = curved_element(el, force, weight / el.length, direction * mu * axial, normal);
                torque += circumferential * mu * normal * el.radius;
            }
            // a friction factor high enough that e^(mu theta) leaves the doubles: the string locks up (no NaN out)
            if (!(std::isfinite(force) && std::isfinite(torque))) reject_lock_up(cased, el, mu);
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
        // Aadnoy's form: the element's arc (header comment)
        double curvature = 0.0;           // kappa = beta / L, rad/m
        double in_plane_share = 1.0;      // rho: gravity's share in the arc's plane
        double across_share = 0.0;        // |b_z|: its share across it
        double psi_bottom = 0.0;          // angle from the in-plane gravity to the tangent at the bottom, rad
    };

    /// The plane of element el's arc (tangents at its top and bottom) and the angle psi of its bottom tangent.
    static void place_in_plane(Element& el, const std::array<double, 3>& top, const std::array<double, 3>& bottom) {
        el.curvature = el.dogleg / el.length;
        std::array<double, 3> b{{0.0, 1.0, 0.0}};  // the plane's normal; a straight vertical element: any
        if (el.dogleg > 1e-12) {  // rotating top onto bottom is positive about b, so psi grows down-hole
            b = {{top[1] * bottom[2] - top[2] * bottom[1], top[2] * bottom[0] - top[0] * bottom[2],
                  top[0] * bottom[1] - top[1] * bottom[0]}};
        } else if (std::hypot(top[0], top[1]) > 1e-14) {  // straight: the vertical plane holding it
            b = {{-top[1], top[0], 0.0}};
        }
        const double norm = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        for (double& x : b) x /= norm;
        el.across_share = std::abs(b[2]);
        el.in_plane_share = std::sqrt(std::max(0.0, 1.0 - b[2] * b[2]));
        std::array<double, 3> e1 = top;  // gravity's direction in the plane (any in-plane one if it has none)
        if (el.in_plane_share > 1e-12)
            e1 = {{-b[2] * b[0] / el.in_plane_share, -b[2] * b[1] / el.in_plane_share,
                   (1.0 - b[2] * b[2]) / el.in_plane_share}};
        const std::array<double, 3> e2{{b[1] * e1[2] - b[2] * e1[1], b[2] * e1[0] - b[0] * e1[2],
                                        b[0] * e1[1] - b[1] * e1[0]}};
        const double psi_top = std::atan2(top[0] * e2[0] + top[1] * e2[1] + top[2] * e2[2],
                                          top[0] * e1[0] + top[1] * e1[1] + top[2] * e1[2]);
        el.psi_bottom = psi_top + el.dogleg;
    }

    struct Piece {
        double force, normal;  // tension at the piece's top, side force over it
    };

    /// Aadnoy's closed form (header comment) over u up from a point of tension f0 and angle psi0, the contact on the
    /// side eps (+1: F kappa > rho w sin psi), with the in-plane weight per length wr, sigma = +/- mu_axial and the
    /// extra side force per length `extra` (the weight across the plane).
    static Piece piece(double kappa, double wr, double sigma, double eps, double extra, double f0, double psi0,
                       double u) {
        using C = std::complex<double>;
        const double turn = kappa * u, growth = detail::phi1(sigma * eps * turn);
        double normal = turn * f0 * growth, axial = 0.0;
        if (wr != 0.0) {
            const C z(sigma * eps * turn, turn), i_turn(0.0, turn), rotation = std::polar(1.0, psi0 - turn);
            const C bracket = turn * detail::phi1_divided(z, i_turn) + C(0.0, 1.0) * detail::phi1(z);
            normal += wr * u * (rotation * bracket).real();
            axial = wr * u * (rotation * detail::phi1(i_turn)).real();
        }
        normal = eps * normal + extra * u * growth;
        return {f0 + axial + sigma * normal, normal};
    }

    /// One element by Aadnoy's form from the bottom tension `force` [N] with the buoyed weight per length w [N/m]
    /// and sigma = +/- mu_axial: the tension at its top, its side force in `normal`.
    static double curved_element(const Element& el, double force, double w, double sigma, double& normal) {
        const double kappa = el.curvature, wr = el.in_plane_share * w, across = el.across_share * w;
        if (kappa == 0.0) {  // straight: the closed form's kappa -> 0 limit, in short
            normal = std::abs(wr * std::sin(el.psi_bottom)) * el.length;
            return force + wr * std::cos(el.psi_bottom) * el.length + sigma * normal;
        }
        auto contact = [&](double f, double psi) { return kappa * f - wr * std::sin(psi); };  // in-plane, per length
        auto side_of = [&](double h, double psi, double extra) {  // at h = 0: the side h moves to (dh/du's sign)
            if (h != 0.0) return h > 0.0 ? 1.0 : -1.0;
            return kappa * (2.0 * wr * std::cos(psi) + sigma * extra) >= 0.0 ? 1.0 : -1.0;
        };
        double extra = 0.0;
        if (across != 0.0) {  // the across-plane weight in quadrature, at the element's middle (a predictor)
            const double half = 0.5 * el.length, psi_mid = el.psi_bottom - kappa * half;
            const double eps = side_of(contact(force, el.psi_bottom), el.psi_bottom, 0.0);
            const double h = contact(piece(kappa, wr, sigma, eps, 0.0, force, el.psi_bottom, half).force, psi_mid);
            // the extra side force is itself a source of friction: the middle's tension grows by sigma extra (L / 2)
            // phi1(lambda L / 2) (the closed form is linear in it); two fixed-point passes make the middle's contact
            // second order, one would leave the trips first order
            const double feedback = kappa * sigma * half * detail::phi1(sigma * eps * kappa * half);
            for (int pass = 0; pass < 3; ++pass) {
                const double hm = h + feedback * extra;
                extra = across * across / (std::hypot(hm, across) + std::abs(hm));  // sqrt(h^2 + q^2) - |h|
            }
        }
        double psi = el.psi_bottom, remaining = el.length, f = force, total = 0.0;
        double eps = side_of(contact(f, psi), psi, extra);
        for (int pieces = 0;; ++pieces) {
            const Piece whole = piece(kappa, wr, sigma, eps, extra, f, psi, remaining);
            const double h_end = contact(whole.force, psi - kappa * remaining);
            if (pieces == 3 || kappa == 0.0 || !(eps * h_end < 0.0)) {
                total += whole.normal;
                f = whole.force;
                break;
            }
            // the contact changes sides inside: locate h = 0 on this piece's closed form, continue on the other side
            detail::IllinoisBracket bracket{0.0, contact(f, psi), remaining, h_end};
            double root = remaining;
            for (int it = 0; it < 100 && bracket.b - bracket.a > 1e-13 * el.length; ++it) {
                root = bracket.next();
                const double h = contact(piece(kappa, wr, sigma, eps, extra, f, psi, root).force, psi - kappa * root);
                if (h == 0.0) break;
                bracket.move(root, h, eps * h < 0.0);
            }
            const Piece part = piece(kappa, wr, sigma, eps, extra, f, psi, root);
            total += part.normal;
            f = part.force;
            psi -= kappa * root;
            remaining -= root;
            eps = -eps;
        }
        normal = total;
        return f;
    }

    [[noreturn]] static void reject_clearance(bool cased, const Element& el, double hole) {
        const std::string rule = "> the pipe's outer diameter, " + std::to_string(el.outer_diameter) +
                                 " m, at measured depth " + std::to_string(el.mid_depth) + " m";
        detail::reject("SoftStringParams", cased ? "casing_inner_diameter" : "hole_diameter", rule.c_str(), hole);
    }

    [[noreturn]] static void reject_lock_up(bool cased, const Element& el, double mu) {
        const std::string rule = "small enough for a finite tension: the string locks up at measured depth " +
                                 std::to_string(el.mid_depth) + " m";
        detail::reject("SoftStringParams", cased ? "cased_hole_friction" : "open_hole_friction", rule.c_str(), mu);
    }

    static double side_force(const Element& el, double tension, double weight) {
        const double vertical = tension * el.inclination_change + weight * el.sin_inclination;
        return std::sqrt(tension * tension * el.lateral_turn_sq + vertical * vertical);
    }

    TorqueDragMethod method_ = TorqueDragMethod::johancsik;
    double element_length_ = 0.0;
    std::vector<double> depth_, inclination_, sqrt_sin_inclination_;
    std::vector<Element> element_;
};

}  // namespace frictionsim
