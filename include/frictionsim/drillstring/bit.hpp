// The bit of a StringRig: what the rock does to the last node. A bit is a friction law in the bit's own units
// (the FrictionLaw concept of friction/law.hpp, checked by check_friction_law): its "relative velocity" is the
// bit's angular speed w [rad/s], its "normal force" the weight on bit W [N] and its "force" the torque on bit
// T [N m] against the rotation, so the rig runs it through DiscContact at radius 1 (stick at w = 0 with Leine's
// switch model when `has_stick`). On top of the law it gives
//   double weight_on_bit() const;              // W, N: the rock pushes the bit back with W (imposed-WOB model)
//   static constexpr bool touches_rock;        // false: the bit is off bottom and the rig skips it
// A bit-rock model of another header (e.g. a depth-of-cut law) needs only an adapter with these members.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "../detail/traits.hpp"
#include "../friction/law.hpp"
#include "../parameters.hpp"

namespace frictionsim {

/// No bit contact: the bit hangs off bottom.
struct OffBottom {
    static constexpr const char* name = "OffBottom";
    static constexpr bool touches_rock = false;
    static constexpr bool has_stick = true;  // never used: a placeholder meeting the law concept's shape
    static constexpr std::size_t state_count = 0;
    double static_limit(double) const { return 0.0; }
    double slip_force(double, double, int) const { return 0.0; }
    double slip_slope(double, double, int) const { return 0.0; }
    double karnopp_band() const { return 0.0; }
    double weight_on_bit() const { return 0.0; }
};

/// Velocity-weakening bit friction of the lumped stick-slip literature (Navarro-Lopez and Cortes 2007, eq 9):
///   T_b = R_b W mu_b(w) sgn(w),  mu_b(w) = mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w|),
/// and a stuck bit (w = 0) holds any torque up to R_b W mu_sb. Defaults: their parameter set.
class VelocityWeakeningBit {
public:
    static constexpr const char* name = "VelocityWeakeningBit";
    static constexpr bool touches_rock = true;
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;

    struct Params {
        double bit_radius = 0.155575;     ///< R_b, m
        double weight_on_bit = 97347.0;   ///< W, N
        double static_coefficient = 0.8;  ///< mu_sb
        double kinetic_coefficient = 0.5; ///< mu_cb <= mu_sb
        double decay = 0.9;               ///< gamma_b, s/rad
    };
    static constexpr std::array<Field<Params>, 5> fields{{
        {"bit_radius", "R_b", "m", Rule::positive(), &Params::bit_radius, "Bit radius."},
        {"weight_on_bit", "W", "N", Rule::non_negative(), &Params::weight_on_bit, "Weight on bit."},
        {"static_coefficient", "mu_sb", "-", Rule::at_least_field("kinetic_coefficient"), &Params::static_coefficient,
         "Static bit friction coefficient (>= mu_cb)."},
        {"kinetic_coefficient", "mu_cb", "-", Rule::positive(), &Params::kinetic_coefficient,
         "Kinetic bit friction coefficient (the level at high speed)."},
        {"decay", "gamma_b", "s/rad", Rule::non_negative(), &Params::decay,
         "Rate of the velocity weakening, per rad/s of bit speed."},
    }};

    explicit VelocityWeakeningBit(const Params& p) : p_(p) { validate_fields(name, p, fields); }
    VelocityWeakeningBit() : VelocityWeakeningBit(Params{}) {}
    const Params& params() const { return p_; }

    double weight_on_bit() const { return p_.weight_on_bit; }
    double static_limit(double weight) const { return p_.bit_radius * weight * p_.static_coefficient; }
    double slip_force(double w, double weight, int direction) const {
        return direction * p_.bit_radius * weight * coefficient(w);
    }
    /// dT_b/dw in slip.
    double slip_slope(double w, double weight, int direction) const {
        return -direction * p_.bit_radius * weight * (p_.static_coefficient - p_.kinetic_coefficient) * p_.decay *
               std::exp(-p_.decay * std::abs(w)) * sign_of(w);
    }
    double karnopp_band() const { return 0.0; }
    /// mu_b(w).
    double coefficient(double w) const {
        return p_.kinetic_coefficient + (p_.static_coefficient - p_.kinetic_coefficient) * std::exp(-p_.decay * std::abs(w));
    }

private:
    Params p_;
};

namespace detail {
template <class B> using touches_rock_t = decltype(bool{B::touches_rock});
template <class B> using weight_on_bit_t = decltype(double{std::declval<const B&>().weight_on_bit()});
}  // namespace detail

/// Does the bit act on the string (a `touches_rock` member that is true, or none: a bit touches by default)?
template <class Bit>
constexpr bool bit_touches_rock() {
    if constexpr (detail::detected<Bit, detail::touches_rock_t>::value) return Bit::touches_rock;
    else return true;
}

/// static_asserts naming what a Bit misses; true when it meets the interface above.
template <class Bit>
constexpr bool check_bit() {
    static_assert(check_friction_law<Bit>(),
                  "Bit: a bit is a FrictionLaw in (bit speed rad/s, weight on bit N) -> torque on bit N m");
    static_assert(detail::detected<Bit, detail::weight_on_bit_t>::value,
                  "Bit requires `double weight_on_bit() const` (N)");
    return true;
}

}  // namespace frictionsim
