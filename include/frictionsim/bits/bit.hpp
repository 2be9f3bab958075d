// The bit of a StringRig: what the rock does to the last node. A bit is a friction law in the bit's own units
// (the FrictionLaw concept of friction/law.hpp, checked by check_friction_law): its "relative velocity" is the
// bit's angular speed w [rad/s], its "normal force" the weight on bit W [N] and its "force" the torque on bit
// T [N m] against the rotation, so the rig runs it through DiscContact at radius 1 (stick at w = 0 with Leine's
// switch model when `has_stick`). On top of the law it gives
//   double weight_on_bit() const;              // W, N: the rock pushes the bit back with W (imposed-WOB model)
//   static constexpr bool touches_rock;        // false: the bit is off bottom and the rig skips it
// A bit-rock model of another header needs only an adapter with these members (DetournayBitOnRock below: the
// depth-of-cut law of bit_rock.hpp under an imposed weight on bit).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "../detail/traits.hpp"
#include "../friction/law.hpp"
#include "../detail/validate.hpp"
#include "../parameters.hpp"
#include "bit_rock.hpp"

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

/// A bit law on the rock under an imposed weight on bit: any FrictionLaw in (bit speed, weight on bit) -> torque
/// on bit (NavarroLopezBit of bit_rock.hpp, or a drilling code's own law) and the weight on bit it drills with.
template <class Law>
class BitOnRock : public Law {
public:
    static constexpr bool touches_rock = true;

    BitOnRock() = default;
    BitOnRock(Law law, double weight_on_bit)
        : Law(std::move(law)), weight_(detail::require_non_negative("BitOnRock", "weight_on_bit", weight_on_bit)) {}

    double weight_on_bit() const { return weight_; }  ///< W, N
    const Law& law() const { return *this; }

private:
    double weight_ = 0.0;
};

/// The lumped-model literature's velocity-weakening bit (Navarro-Lopez & Cortes 2007) under a weight on bit.
using VelocityWeakeningBit = BitOnRock<NavarroLopezBit>;

/// The drag bit of Detournay & Defourny (1992; DetournayBit of bit_rock.hpp) on bottom under an imposed weight on
/// bit W: the depth of cut per revolution is the steady one at that weight, d = (W - a l sigma) / (zeta eps a)
/// (depth_at_weight: 0 while the wear flats carry all of W), and the torque on bit turning forwards is
///     T = c eps a^2 d + c gamma mu a (a l sigma)          (cutting + frictional contact; c = torque_constant)
/// whatever the speed (rate-independent). The bit sticks at w = 0 while the torque needed to hold it is within
/// |T| <= T (Leine's switch model through DiscContact: breaking away needs the full cutting torque). Turning
/// backwards the cutters do not cut and only the wear flats rub: T = -c gamma mu a (a l sigma).
/// Not modelled: the axial bit-rock interaction of Richard, Germay & Detournay (2007): there the depth of cut is the
/// axial advance of the bit over the delay t_n(t) it takes to turn one blade sector (a state-dependent delay that
/// couples the axial and torsional motions and causes the self-excited stick-slip); here W is imposed and d
/// follows from it, so the bit neither bounces nor weakens with speed.
class DetournayBitOnRock {
public:
    static constexpr const char* name = "DetournayBitOnRock";
    static constexpr bool touches_rock = true;
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;

    DetournayBitOnRock() : DetournayBitOnRock(DetournayBit(), 0.0) {}
    DetournayBitOnRock(DetournayBit law, double weight_on_bit)
        : law_(std::move(law)),
          weight_(detail::require_non_negative("DetournayBitOnRock", "weight_on_bit", weight_on_bit)),
          depth_(law_.depth_at_weight(weight_)), torque_(law_.cutting_torque_per_depth() * depth_ + law_.contact_torque()) {
        // the torque at that depth: blamed on W or the bit's farthest value, not on the depth the rig computed
        if (!std::isfinite(torque_)) law_.blame_at_weight(weight_, "the torque on bit c eps a^2 d + T_f [N m]", torque_);
    }

    const DetournayBit& law() const { return law_; }
    double weight_on_bit() const { return weight_; }  ///< W, N
    double depth_of_cut() const { return depth_; }    ///< d, m per revolution
    double torque_on_bit() const { return torque_; }  ///< T, N m: turning forwards, and the stuck bit's bound

    /// FrictionLaw members in (bit speed, weight on bit) -> torque; the weight is the adapter's own W.
    double static_limit(double) const { return torque_; }
    double slip_force(double, double, int direction) const {
        return direction > 0 ? torque_ : -law_.contact_torque();
    }
    double slip_slope(double, double, int) const { return 0.0; }  // rate-independent
    double karnopp_band() const { return 0.0; }

private:
    DetournayBit law_;
    double weight_ = 0.0, depth_ = 0.0, torque_ = 0.0;
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
