// The wall friction of a pipe that slides while it vibrates axially, averaged over one vibration cycle (issue 14,
// item 3). The pipe's surface moves at v(phi) = V + a sin(phi) along the hole and at w = omega r around it; Coulomb
// friction of magnitude mu N acts against the sliding velocity q = (v, w) (paper 000's friction vector), so over a
// cycle, per unit of mu N,
//     axial mean            < v / |q| >
//     circumferential mean  < w / |q| >
//     power taken from the vibration  < a sin(phi) v / |q| >   (the friction's work on the oscillating motion)
// Without rotation (w = 0) and a > V the velocity reverses during part of each cycle and, with phi_0 = asin(V / a),
//     < sign v > = (2 / pi) asin(V / a),   < a sin(phi) sign v > = (2 / pi) sqrt(a^2 - V^2)
// (the first is DESIGN.md's reference; the second follows from < |V + a sin phi| > = (2 / pi) (sqrt(a^2 - V^2) +
// V asin(V / a)) less V < sign v >; at V = 0 it is the 4 mu N u_0 per cycle of Coulomb damping, whose equivalent
// viscous damping is Jacobsen's 4 mu N / (pi a): L. S. Jacobsen, Trans. ASME 52 (1930), APM-52-15). For a <= V the
// velocity never reverses: the friction stays mu N, with no cycle-mean effect and no power taken from the
// vibration (rigid Coulomb friction does not damp a vibration slower than the sliding).
// With rotation the means are taken numerically: Gauss-Legendre on either side of the phase where v reverses, graded
// towards it (the integrand turns from -1 to +1 there within about w / a radians).
// Paper 000's Table 5 gives instead a measured cycle-mean coefficient mu_df = eta' (a / V)^c per lubricant (eq 17,
// power_law.hpp). As a factor on a friction factor it is divided by the same lubricant's sliding coefficient without
// vibration (Table 4: F_sf / F_N), capped at 1 and applied where a > V only: the fit covers a / V = 160..2560 and
// has no meaning where the velocity does not reverse.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../friction/power_law.hpp"

namespace frictionsim {

namespace detail {

/// The n-point Gauss-Legendre rule on [-1, 1]: {node, weight} pairs, by Newton's method on P_n (computed once).
template <int n>
const std::array<std::array<double, 2>, n>& gauss_legendre() {
    static const std::array<std::array<double, 2>, n> rule = [] {
        std::array<std::array<double, 2>, n> r{};
        for (int i = 0; i < n; ++i) {
            double x = std::cos(pi * (i + 0.75) / (n + 0.5)), derivative = 1.0;
            for (int iteration = 0; iteration < 100; ++iteration) {
                double p0 = 1.0, p1 = x;  // P_0, P_1, then the recurrence up to P_n
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = n * (x * p1 - p0) / (x * x - 1.0);
                const double dx = p1 / derivative;
                x -= dx;
                if (std::abs(dx) < 1e-16) break;
            }
            r[static_cast<std::size_t>(i)] = {x, 2.0 / ((1.0 - x * x) * derivative * derivative)};
        }
        return r;
    }();
    return rule;
}

}  // namespace detail

/// Cycle means of the friction vector per unit of mu N (see the header comment).
struct CycleMeanFriction {
    double axial = 1.0;            ///< < v / |q| >, in [-1, 1]
    double circumferential = 0.0;  ///< < w / |q| >, in [0, 1]
    double vibration_power = 0.0;  ///< < a sin(phi) v / |q| >, m/s: the power taken from the vibration / (mu N)
};

/// The cycle means for sliding speed V >= 0, axial vibration velocity amplitude a >= 0 and circumferential surface
/// speed w >= 0 [m/s]: closed forms without rotation, graded Gauss-Legendre with it.
inline CycleMeanFriction cycle_mean_friction(double sliding_speed, double vibration_amplitude,
                                             double surface_speed = 0.0) {
    constexpr const char* who = "cycle_mean_friction";
    const double v = detail::require_non_negative(who, "sliding_speed", sliding_speed);
    const double a = detail::require_non_negative(who, "vibration_amplitude", vibration_amplitude);
    const double w = detail::require_non_negative(who, "surface_speed", surface_speed);
    CycleMeanFriction out;
    if (w == 0.0) {
        if (a > v) {  // the velocity reverses for part of the cycle
            out.axial = 2.0 / pi * std::asin(v / a);
            out.vibration_power = 2.0 / pi * std::sqrt((a - v) * (a + v));
        }
        return out;
    }
    if (a == 0.0) {  // the steady friction vector
        const double speed = std::hypot(v, w);
        out.axial = v / speed;
        out.circumferential = w / speed;
        return out;
    }
    // mean over phi of F(sin phi) = (1 / pi) int_0^pi F(cos theta) d theta; split where v = V + a cos theta = 0
    // (theta_0, or pi when v keeps its sign) and graded towards it, theta = theta_0 -/+ D t^4 (t in [0, 1]), so
    // that Gauss-Legendre resolves the reversal's layer, w / (a sin theta_0) wide, down to w / a ~ 1e-9
    const double theta0 = a > v ? std::acos(-v / a) : pi;
    double axial = 0.0, circumferential = 0.0, power = 0.0;
    const auto integrate = [&](const auto& rule) {
        for (int side = 0; side < 2; ++side) {
            const double span = side == 0 ? theta0 : pi - theta0, direction = side == 0 ? -1.0 : 1.0;
            if (!(span > 0.0)) continue;
            for (const auto& node : rule) {
                const double t = 0.5 * (node[0] + 1.0), t3 = t * t * t;
                const double weight = 0.5 * node[1] * 4.0 * span * t3;  // d theta = 4 D t^3 dt
                const double c = std::cos(theta0 + direction * span * t3 * t);
                const double along = v + a * c, inverse_speed = 1.0 / std::sqrt(along * along + w * w);
                axial += weight * along * inverse_speed;
                circumferential += weight * w * inverse_speed;
                power += weight * a * c * along * inverse_speed;
            }
        }
    };
    // 16 nodes a side resolve a layer 0.1 a wide to 1e-9; 64 down to w / a ~ 1e-9
    if (w >= 0.1 * a) integrate(detail::gauss_legendre<16>());
    else integrate(detail::gauss_legendre<64>());
    out.axial = axial / pi;
    out.circumferential = circumferential / pi;
    out.vibration_power = std::max(power / pi, 0.0);  // >= 0 exactly; rounding may leave -1e-17
    return out;
}

/// The sliding friction coefficient without vibration of paper 000's Table 4 (F_sf / F_N, the same in every run of
/// a lubricant; section 2.4.1 quotes 0.41 dry, 0.36 WBM, 0.32 SBM, 0.27 OBM).
inline double sliding_coefficient_without_vibration(Lubricant lubricant) {
    switch (lubricant) {
        case Lubricant::dry: return 12.29 / 30.0;
        case Lubricant::water: return 60.80 / 150.0;
        case Lubricant::wbm: return 21.60 / 60.0;
        case Lubricant::obm: return 40.50 / 150.0;
        case Lubricant::sbm: return 29.13 / 90.0;
    }
    return 1.0;
}

/// Table 5's friction factor: mu_df (a / V) / mu_sliding, capped at 1, where a > V > 0; 1 elsewhere (no reversal).
inline double table5_friction_factor(Lubricant lubricant, double sliding_speed, double vibration_amplitude) {
    constexpr const char* who = "table5_friction_factor";
    const double v = detail::require_non_negative(who, "sliding_speed", sliding_speed);
    const double a = detail::require_non_negative(who, "vibration_amplitude", vibration_amplitude);
    if (!(a > v)) return 1.0;
    if (v == 0.0) detail::reject(who, "sliding_speed", "positive where the string vibrates (Table 5 reads a / V)", v);
    const double mu = PowerLawCoefficient::from_table5(lubricant).coefficient(a, v);
    return std::min(1.0, mu / sliding_coefficient_without_vibration(lubricant));
}

}  // namespace frictionsim
