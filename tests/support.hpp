// Small helpers several test sources use, one definition each (the suite compiles in unity groups, so two files'
// helpers of one name would collide): non-finite values, a relative error, a substring test, tight solver options,
// degrees and micrometres, the first root of the torsional string's frequency equation, and a knot path.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <frictionsim/detail/constants.hpp>
#include <frictionsim/solve/options.hpp>

namespace frictionsim::test {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double deg = pi / 180.0;  ///< one degree [rad]
inline constexpr double um = 1e-6;          ///< one micrometre [m]

inline double relative_error(double value, double reference) {
    return std::abs(value - reference) / std::abs(reference);
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Options of `method` at the given tolerances.
inline SolverOptions options_for(Method method, double rtol = 1e-10, double atol = 1e-12) {
    SolverOptions o;
    o.method = method;
    o.rtol = rtol;
    o.atol = atol;
    return o;
}

/// Options of `method` at rtol 1e-10, atol 1e-15, reporting at output_times.
inline SolverOptions tight(Method method, std::vector<double> output_times) {
    SolverOptions o = options_for(method, 1e-10, 1e-15);
    o.output_times = std::move(output_times);
    return o;
}

/// First root of x tan(x) = ratio in (0, pi/2), by bisection: the fundamental torsional mode of a shaft with an
/// end inertia (ratio = the shaft's inertia over the end's).
inline double first_root(double ratio) {
    double lo = 0.0, hi = pi / 2.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (mid * std::tan(mid) < ratio ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// A displacement through knots x_k at t = k T, half a cosine per segment: v = 0 at every knot (a reversal where
/// the direction changes), and the velocity is smooth in between.
struct KnotPath {
    std::vector<double> x;
    double T;
    std::size_t segment(double t) const {
        return std::min<std::size_t>(static_cast<std::size_t>(std::max(0.0, t) / T), x.size() - 2);
    }
    double operator()(double t) const {
        const std::size_t k = segment(t);
        return (x[k + 1] - x[k]) * pi / (2 * T) * std::sin(pi * (t - k * T) / T);
    }
    double displacement(double t) const {
        const std::size_t k = segment(t);
        return x[k] + (x[k + 1] - x[k]) * 0.5 * (1 - std::cos(pi * (t - k * T) / T));
    }
};

}  // namespace frictionsim::test
