// Two bit-rock laws for drill-string models (issue 13, item 3).
//
// DetournayBit: the drag-bit model of Detournay & Defourny (1992, Int. J. Rock Mech. Min. Sci. 29(1), 13-23),
// as used in the discrete model of Richard, Germay & Detournay (2007, J. Sound Vib. 305, 432-456, Sec. 2). Weight and
// torque on bit are a cutting part, proportional to the depth of cut per revolution d, plus a frictional contact
// part carried by the wear flats:
//   W = W_c + W_f,  W_c = zeta eps a d,            W_f = a l sigma                  (fully developed contact)
//   T = T_c + T_f,  T_c = c eps a^2 d,             T_f = c gamma mu a W_f,    c = 1/2 (Detournay & Defourny)
// The constant c is exposed (`torque_constant`): open codes differ by that factor 1/2 (c = 1 writes the torque as
// eps a^2 d + gamma mu a W_f). The frictional torque is set-valued at zero angular speed: the bit sticks while the
// torque needed to hold it stays within T_f (no rotation, no cutting: d = 0 there).
// Eliminating d gives the E-S line of Detournay, Richard & Shepherd (2008, Int. J. Rock Mech. Min. Sci. 45,
// 1347-1360), with the specific energy E = 2 T / (a^2 d) and the drilling strength S = W / (a d) (c = 1/2):
//   E = (1 - beta) eps + mu gamma S,   beta = mu gamma zeta.
//
// NavarroLopezBit: the velocity-weakening bit friction of the lumped models of Navarro-Lopez & Suarez (2004) and
// Navarro-Lopez & Cortes (2007, J. Sound Vib. 307, 152-171, Sec. 2): with bit speed w (rad/s) and weight on bit W (N),
//   T_b(w) = c_b w + R_b W mu_b(w) sign(w),   mu_b(w) = mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w| / v_f)   (slip)
//   |T_b| <= R_b W mu_sb                                                                              (stick)
// It meets the FrictionLaw concept (friction/law.hpp) with the weight on bit as its normal force and the bit speed
// as its relative velocity, so ContactSwitching and the rigs accept it; its "force" is a torque (N m). (The
// StringRig's bit, drillstring/bit.hpp's VelocityWeakeningBit, is the same law without c_b, v_f and the band, and
// with the weight on bit inside; NavarroLopezBit keeps W an input because the lumped models sweep it.)
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../friction/law.hpp"
#include "../parameters.hpp"
#include "../string/scale.hpp"

namespace frictionsim {

/// Drag bit of Detournay & Defourny (1992). Defaults: an 8.5" PDC bit in a medium-strength rock (illustrative values
/// of the order of those in the literature; set your own).
class DetournayBit {
public:
    static constexpr const char* name = "DetournayBit";
    /// c of T_c = c eps a^2 d, T_f = c gamma mu a W_f in Detournay & Defourny's convention, and in the convention
    /// of codes that write T = eps a^2 d + gamma mu a W_f.
    static constexpr double detournay_defourny_constant = 0.5;
    static constexpr double unit_constant = 1.0;

    struct Params {
        double bit_radius = 0.108;                  ///< a, m
        double intrinsic_specific_energy = 110e6;   ///< eps, Pa (J/m^3): energy to cut a unit volume of rock
        double cutting_force_ratio = 0.6;           ///< zeta: ratio of normal to tangential cutting force
        double contact_strength = 60e6;             ///< sigma, Pa: normal stress on the wear flats
        double wearflat_length = 1.2e-3;            ///< l, m: total length of the wear flats along a blade
        double friction_coefficient = 0.6;          ///< mu: friction on the wear flats
        double contact_orientation = 1.0;           ///< gamma: orientation and distribution of the contact forces
        double torque_constant = detournay_defourny_constant;  ///< c: 1/2 (Detournay & Defourny) or 1
    };
    static constexpr std::array<Field<Params>, 8> fields{{
        {"bit_radius", "a", "m", Rule::positive(), &Params::bit_radius, "Bit radius."},
        {"intrinsic_specific_energy", "eps", "Pa", Rule::positive(), &Params::intrinsic_specific_energy,
         "Intrinsic specific energy: energy to cut a unit volume of rock."},
        {"cutting_force_ratio", "zeta", "-", Rule::positive(), &Params::cutting_force_ratio,
         "Ratio of the normal to the tangential cutting force."},
        {"contact_strength", "sigma", "Pa", Rule::non_negative(), &Params::contact_strength,
         "Normal stress transmitted by the wear flats."},
        {"wearflat_length", "l", "m", Rule::non_negative(), &Params::wearflat_length,
         "Total length of the wear flats (0: a sharp bit, no frictional contact)."},
        {"friction_coefficient", "mu", "-", Rule::non_negative(), &Params::friction_coefficient,
         "Friction coefficient on the wear flats."},
        {"contact_orientation", "gamma", "-", Rule::positive(), &Params::contact_orientation,
         "Bit constant: orientation and spatial distribution of the contact forces."},
        {"torque_constant", "c", "-", Rule::positive().because("1/2 in Detournay & Defourny's convention, 1 in others"),
         &Params::torque_constant, "Constant of the torque: T = c (eps a^2 d + gamma mu a W_f)."},
    }};

    explicit DetournayBit(const Params& p) : p_(p) {
        validate_fields(name, p, fields);
        // the law's constants, products of the table's values, stay doubles (5e-324 for zeta made W / (zeta eps a)
        // infinite, blamed on the depth of cut): each refused naming the value farthest from its default
        detail::require_representable(name, p_, fields, {"cutting_force_ratio", "intrinsic_specific_energy", "bit_radius"},
                                      cutting_weight_per_depth(), "the cutting weight per depth zeta eps a [N/m]");
        detail::require_representable(name, p_, fields, {"torque_constant", "intrinsic_specific_energy", "bit_radius"},
                                      cutting_torque_per_depth(), "the cutting torque per depth c eps a^2 [N]");
        detail::require_representable(name, p_, fields, {"bit_radius", "wearflat_length", "contact_strength"},
                                      contact_force(), "the wear flats' force a l sigma [N]", false);
        detail::require_representable(name, p_, fields,
                                      {"torque_constant", "contact_orientation", "friction_coefficient", "bit_radius",
                                       "wearflat_length", "contact_strength"},
                                      contact_torque(), "the wear flats' torque c gamma mu a W_f [N m]", false);
    }
    DetournayBit() : DetournayBit(Params{}) {}
    const Params& params() const { return p_; }

    /// Depth of cut per revolution d = 2 pi V / Omega, m, from the rate of penetration V (m/s) and the angular
    /// speed Omega (rad/s, positive: the bit cuts only while it turns forwards).
    static double depth_of_cut(double rate_of_penetration, double angular_speed) {
        detail::require_non_negative(name, "rate_of_penetration", rate_of_penetration);
        detail::require_positive(name, "angular_speed", angular_speed);
        const double d = 2.0 * pi * rate_of_penetration / angular_speed;
        if (!std::isfinite(d))  // the ratio of two doubles past the largest: the smaller one is the odd one
            detail::reject(name, angular_speed < 1.0 ? "angular_speed" : "rate_of_penetration",
                           "such that 2 pi V / Omega is a finite depth of cut", angular_speed < 1.0 ? angular_speed
                                                                                                  : rate_of_penetration);
        return d;
    }
    /// zeta eps a [N/m] and c eps a^2 [N]: the cutting weight and torque per metre of depth of cut.
    double cutting_weight_per_depth() const {
        return p_.cutting_force_ratio * p_.intrinsic_specific_energy * p_.bit_radius;
    }
    double cutting_torque_per_depth() const {
        return p_.torque_constant * p_.intrinsic_specific_energy * p_.bit_radius * p_.bit_radius;
    }

    /// W_f = a l sigma, N: the contact force on the wear flats (fully developed contact).
    double contact_force() const { return p_.bit_radius * p_.wearflat_length * p_.contact_strength; }
    /// T_f = c gamma mu a W_f, N m: the frictional torque while the bit turns, and the bound of the stuck bit's.
    double contact_torque() const {
        return p_.torque_constant * p_.contact_orientation * p_.friction_coefficient * p_.bit_radius * contact_force();
    }
    /// W_c = zeta eps a d, N.
    double cutting_weight(double depth) const {
        return finite_at_depth(cutting_weight_per_depth() * checked_depth(depth), depth);
    }
    /// T_c = c eps a^2 d, N m.
    double cutting_torque(double depth) const {
        return finite_at_depth(cutting_torque_per_depth() * checked_depth(depth), depth);
    }
    /// Steady weight on bit W = zeta eps a d + a l sigma, N, at depth of cut d (m per revolution).
    double weight_on_bit(double depth) const { return finite_at_depth(cutting_weight(depth) + contact_force(), depth); }
    /// Steady torque on bit T = c eps a^2 d + c gamma mu a (a l sigma), N m, while the bit turns forwards.
    double torque_on_bit(double depth) const { return finite_at_depth(cutting_torque(depth) + contact_torque(), depth); }
    /// Depth of cut at which the steady bit carries weight W: d = (W - a l sigma) / (zeta eps a), m; 0 below the
    /// contact force (the wear flats carry all the weight, nothing is cut).
    double depth_at_weight(double weight) const {
        detail::require_non_negative(name, "weight_on_bit", weight);
        const double d = std::max(0.0, weight - contact_force()) / cutting_weight_per_depth();
        if (!std::isfinite(d)) blame_at_weight(weight, "the depth of cut (W - a l sigma) / (zeta eps a) [m]", d);
        return d;
    }
    /// Rejects a quantity at weight on bit W that left the doubles: naming W, or the bit's value farthest from its
    /// default when that one is farther (in decades) than W from a typical weight on bit, 1e5 N.
    [[noreturn]] void blame_at_weight(double weight, const char* what, double value) const {
        std::ostringstream rule;
        rule.precision(6);
        rule << "such that " << what << " is a finite double (it is " << value << ")";
        const Field<Params>* f = detail::farthest_from_default(
            p_, fields, {"cutting_force_ratio", "intrinsic_specific_energy", "bit_radius", "torque_constant"},
            detail::decades_off(weight, 1e5));
        if (f == nullptr) detail::reject(name, "weight_on_bit", rule.str().c_str(), weight);
        detail::reject(name, f->name, rule.str().c_str(), p_.*(f->member));
    }

    /// Torque on bit, N m, at angular speed w (rad/s) and depth of cut d. Set-valued at w = 0: the stuck bit
    /// returns the torque needed to hold it, `holding_torque`, clamped to the static bound +-T_f (no cutting).
    double torque(double angular_speed, double depth, double holding_torque = 0.0) const {
        detail::require_finite(name, "angular_speed", angular_speed);
        if (angular_speed == 0.0) return std::clamp(holding_torque, -contact_torque(), contact_torque());
        const int direction = sign_of(angular_speed);
        // turning backwards the cutters do not cut: only the wear flats rub
        return direction > 0 ? torque_on_bit(depth) : -contact_torque();
    }
    /// Does the stuck bit hold under `holding_torque` (|T| <= T_f)?
    bool holds(double holding_torque) const { return std::abs(holding_torque) <= contact_torque(); }

private:
    static double checked_depth(double depth) { return detail::require_non_negative(name, "depth_of_cut", depth); }
    static double finite_at_depth(double value, double depth) {
        if (!std::isfinite(value))
            detail::reject(name, "depth_of_cut", "such that the weight and torque on bit at it are finite", depth);
        return value;
    }
    Params p_;
};

/// Velocity-weakening bit friction of Navarro-Lopez & Cortes (2007, Sec. 2). Defaults: their parameter set
/// (R_b = 0.155575 m, mu_cb = 0.5, mu_sb = 0.8, gamma_b = 0.9, v_f = 1 rad/s, c_b = 50 N m s/rad), exact stick.
class NavarroLopezBit {
public:
    static constexpr const char* name = "NavarroLopezBit";
    static constexpr const char* key = "navarro_lopez_bit";
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;

    struct Params {
        double bit_radius = 0.155575;         ///< R_b, m
        double coulomb_coefficient = 0.5;     ///< mu_cb: at high bit speed
        double static_coefficient = 0.8;      ///< mu_sb >= mu_cb: break-away
        double weakening_rate = 0.9;          ///< gamma_b: 0 < gamma_b < 1 in the paper
        double velocity_scale = 1.0;          ///< v_f, rad/s
        double viscous_damping = 50.0;        ///< c_b, N m s/rad: mud and bit viscous torque
        double stick_band = 0.0;              ///< D_v, rad/s: Karnopp band (0: exact stick, Leine's switch model)
    };
    static constexpr std::array<Field<Params>, 7> fields{{
        {"bit_radius", "R_b", "m", Rule::positive(), &Params::bit_radius, "Bit radius."},
        {"coulomb_coefficient", "mu_cb", "-", Rule::positive(), &Params::coulomb_coefficient,
         "Friction coefficient at high bit speed."},
        {"static_coefficient", "mu_sb", "-", Rule::at_least_field("coulomb_coefficient"), &Params::static_coefficient,
         "Static (break-away) friction coefficient, >= mu_cb."},
        {"weakening_rate", "gamma_b", "-", Rule::non_negative(), &Params::weakening_rate,
         "Rate of the exponential decay from mu_sb to mu_cb."},
        {"velocity_scale", "v_f", "rad/s", Rule::positive(), &Params::velocity_scale,
         "Bit speed scale of the decay."},
        {"viscous_damping", "c_b", "N m s/rad", Rule::non_negative(), &Params::viscous_damping,
         "Viscous torque coefficient at the bit."},
        {"stick_band", "D_v", "rad/s", Rule::non_negative(), &Params::stick_band,
         "Karnopp band: the bit sticks below this speed (0: exact stick)."},
    }};

    explicit NavarroLopezBit(const Params& p) : p_(p) { validate_fields(name, p, fields); }
    NavarroLopezBit() : NavarroLopezBit(Params{}) {}
    const Params& params() const { return p_; }

    /// mu_b(w) = mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w| / v_f), written so that mu_b(0) is mu_sb exactly: the
    /// slip torque at w = 0 then equals the static bound to the last bit (exact break-away).
    double coefficient(double angular_speed) const {
        const double x = p_.weakening_rate * std::abs(angular_speed) / p_.velocity_scale;
        return p_.static_coefficient + (p_.static_coefficient - p_.coulomb_coefficient) * std::expm1(-x);
    }
    /// Slip torque T_b = c_b w + R_b W mu_b(w) direction, N m (direction: the sign of the bit speed).
    double torque(double angular_speed, double weight_on_bit, int direction) const {
        return p_.viscous_damping * angular_speed + p_.bit_radius * weight_on_bit * coefficient(angular_speed) * direction;
    }
    /// Static bound R_b W mu_sb, N m.
    double static_limit(double weight_on_bit) const { return p_.bit_radius * weight_on_bit * p_.static_coefficient; }
    /// FrictionLaw members: the "normal force" is the weight on bit, the "force" the torque.
    double slip_force(double angular_speed, double weight_on_bit, int direction) const {
        return torque(angular_speed, weight_on_bit, direction);
    }
    /// dT_b/dw in slip.
    double slip_slope(double angular_speed, double weight_on_bit, int direction) const {
        const double x = p_.weakening_rate * std::abs(angular_speed) / p_.velocity_scale;
        const double weakening = (p_.static_coefficient - p_.coulomb_coefficient) * p_.weakening_rate /
                                 p_.velocity_scale * std::exp(-x);
        return p_.viscous_damping - direction * sign_of(angular_speed) * p_.bit_radius * weight_on_bit * weakening;
    }
    double karnopp_band() const { return p_.stick_band; }

private:
    Params p_;
};

}  // namespace frictionsim
