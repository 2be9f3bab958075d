// The hysteretic velocity-acceleration friction torque of paper 001 (eq 6): a linear stick band and two
// quadratic polynomials of disc speed w and acceleration al, one for accelerating and one for decelerating
// motion (the "double loop" of its Fig. 5a):
//   T = a w                                                     |w| <= w_s
//   T = p00 + p10 w + p01 al + p20 w^2 + p11 w al + p02 al^2      |w| >  w_s, al > 0   (accelerating)
//   T = n00 + n10 w + n01 al + n20 w^2 + n11 w al + n02 al^2      |w| >  w_s, al < 0   (decelerating)
// The paper fitted w > 0 only. For w < -w_s the law is extended oddly, T(w, al) = -T(-w, -al), so that
// "accelerating" means |w| increasing and the torque always opposes the motion it was fitted for.
// The coefficients hold at a reference normal force (35 N in the paper); a normal force N scales the torque
// by N / N_ref. The torque depends on the acceleration, so the disc equation J al = S - T(w, al) is implicit:
// the rig solves it per branch (the quadratic in `branch_acceleration`). Units: N m, rad/s, rad/s^2.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>

#include "../detail/validate.hpp"
#include "../parameters.hpp"

namespace frictionsim {

/// What the rig does where neither slip branch is consistent with the sign of the acceleration (al = 0 with
/// the decelerating level N0(w) below the accelerating level P0(w): eq 6 has no case for it).
enum class BranchGap {
    hold,   ///< Filippov: the set-valued torque in [N0, P0] holds al = 0 until the shaft torque leaves the gap
    error,  ///< stop the run with a SimulationError that names the time, speed and torques
};

/// The six coefficients of one branch in the paper's (MATLAB poly22) order: 1, w, al, w^2, w al, al^2.
struct BranchPolynomial {
    double c00 = 0.0;  ///< N m
    double c10 = 0.0;  ///< N m s/rad
    double c01 = 0.0;  ///< N m s^2/rad (kg m^2: an added inertia)
    double c20 = 0.0;  ///< N m s^2/rad^2
    double c11 = 0.0;  ///< N m s^3/rad^2
    double c02 = 0.0;  ///< N m s^4/rad^2

    /// The torque at al = 0, P0(w) or N0(w).
    double level(double w) const { return c00 + (c10 + c20 * w) * w; }
    double torque(double w, double al) const { return level(w) + (c01 + c11 * w + c02 * al) * al; }
};

class HystereticFriction {
public:
    static constexpr const char* name = "Hysteretic";
    static constexpr std::size_t state_count = 0;

    struct Params {
        double stick_slope = 1000.0;          ///< a, N m s/rad: the stick band T = a w (break-away a w_s)
        double stick_speed = 1e-3;            ///< w_s, rad/s (eq 6)
        BranchPolynomial accelerating;        ///< p00 ... p02
        BranchPolynomial decelerating;        ///< n00 ... n02
        double reference_normal_force = 35.0; ///< N_ref, N: the normal force the coefficients were fitted at
        BranchGap branch_gap = BranchGap::hold;
    };
    /// The scalar parameters; the two branch polynomials (six coefficients each, every one finite, the level at
    /// w_s positive) and branch_gap are checked in the constructor.
    static constexpr std::array<Field<Params>, 3> fields{{
        {"stick_slope", "a", "N m s/rad", Rule::positive(), &Params::stick_slope,
         "Stick band T = a w (break-away torque a w_s).", nullptr, true},
        {"stick_speed", "w_s", "rad/s", Rule::positive(), &Params::stick_speed, "Half-width of the stick band (eq 6)."},
        {"reference_normal_force", "N_ref", "N", Rule::positive(), &Params::reference_normal_force,
         "The normal force the coefficients were fitted at (the torque scales with N / N_ref)."},
    }};

    /// One branch's quadratic J_eff-form at speed u = |w| > 0 and shaft torque S' = sgn(w) S:
    ///   A b^2 + B b + C = 0,  b = sgn(w) al,  A = k c02, B = J + k (c01 + c11 u), C = k level(u) - S'.
    struct Quadratic {
        double a, b, c;
        double discriminant() const { return b * b - 4.0 * a * c; }
        /// The root continuous with the linear case A -> 0 (the other one is ~ -B/A, spurious), stable for
        /// small A. Its sign is the sign of -C when B > 0. Clamps D < 0 (only met on trial states past a
        /// located root loss) so that trial evaluations stay finite.
        double root() const {
            const double denominator = b + std::copysign(std::sqrt(std::max(discriminant(), 0.0)), b);
            return denominator != 0.0 ? -2.0 * c / denominator : 0.0;
        }
    };

    explicit HystereticFriction(const Params& p) : p_(p) {
        validate_fields(name, p, fields);
        static constexpr std::array<const char*, 6> p_names{"p00", "p10", "p01", "p20", "p11", "p02"};
        static constexpr std::array<const char*, 6> n_names{"n00", "n10", "n01", "n20", "n11", "n02"};
        const auto check = [](const BranchPolynomial& c, const std::array<const char*, 6>& names) {
            const std::array<double, 6> v{c.c00, c.c10, c.c01, c.c20, c.c11, c.c02};
            for (std::size_t i = 0; i < 6; ++i) detail::require_finite(name, names[i], v[i]);
        };
        check(p.accelerating, p_names);
        check(p.decelerating, n_names);
        // Friction opposes the motion: where slip begins each branch's level must be a positive torque (a
        // negative one drives the disc, and the rig's friction then does negative work).
        for (const bool accelerating : {true, false}) {
            const double level = (accelerating ? p.accelerating : p.decelerating).level(p.stick_speed);
            if (!(level > 0.0))
                detail::reject(name, accelerating ? "accelerating" : "decelerating",
                               "a branch whose level c00 + c10 w_s + c20 w_s^2 at the stick speed is positive "
                               "(friction opposes the motion)",
                               level);
        }
    }

    /// Throws std::domain_error where a branch's level is not a positive torque at |w| = u: a fitted quadratic
    /// taken past its range, where friction would drive the disc.
    void require_opposing(bool accelerating, double u) const {
        const double level = branch(accelerating).level(u);
        if (level > 0.0) return;
        std::ostringstream msg;
        msg.precision(10);
        msg << "hysteretic friction (eq 6): the " << (accelerating ? "accelerating level P0" : "decelerating level N0")
            << "(|w|) = " << level << " N m at |w| = " << u
            << " rad/s is not positive, so friction would drive the disc; the polynomial is used outside the speed "
               "range it was fitted over";
        throw std::domain_error(msg.str());
    }

    const Params& params() const { return p_; }
    const BranchPolynomial& branch(bool accelerating) const {
        return accelerating ? p_.accelerating : p_.decelerating;
    }
    /// N / N_ref: how the normal force scales every torque of eq 6.
    double scale(double normal_force) const { return normal_force / p_.reference_normal_force; }

    /// Stick band torque a w (scaled).
    double stick_torque(double w, double normal_force) const { return scale(normal_force) * p_.stick_slope * w; }

    /// Eq 6 on one slip branch, with the odd extension for w < 0.
    double slip_torque(bool accelerating, double w, double al, double normal_force) const {
        const double s = w < 0.0 ? -1.0 : 1.0;
        return s * scale(normal_force) * branch(accelerating).torque(s * w, s * al);
    }

    /// Eq 6 with the branch picked from the signs of w and al, as in the paper (al = 0 counts as decelerating).
    double torque(double w, double al, double normal_force) const {
        if (std::abs(w) <= p_.stick_speed) return stick_torque(w, normal_force);
        return slip_torque(w * al > 0.0, w, al, normal_force);
    }

    /// J al = S - T(w, al) on one branch, as a quadratic in b = sgn(w) al at u = |w|, S' = sgn(w) S.
    Quadratic branch_equation(bool accelerating, double u, double shaft_torque_signed, double inertia,
                              double normal_force) const {
        const BranchPolynomial& c = branch(accelerating);
        const double k = scale(normal_force);
        return Quadratic{k * c.c02, inertia + k * (c.c01 + c.c11 * u), k * c.level(u) - shaft_torque_signed};
    }

private:
    Params p_;
};

}  // namespace frictionsim
