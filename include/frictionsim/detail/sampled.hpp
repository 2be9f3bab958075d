// Sampled-data helpers shared by the analysis functions: checks on (t, y) samples and the exact integral of
// their piecewise-linear interpolant.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "validate.hpp"

namespace frictionsim::detail {

inline void require_samples(const char* who, const char* values_name, const double* t, const double* values,
                            std::size_t n_t, std::size_t n_values) {
    if (n_values != n_t) {
        const std::string rule = "the same length as t (" + std::to_string(n_t) + " samples)";
        reject(who, values_name, rule.c_str(), static_cast<double>(n_values));
    }
    if (n_t < 2) reject(who, "t", "at least 2 samples long", static_cast<double>(n_t));
    if (t == nullptr) reject(who, "t", "non-null", 0.0);
    if (values == nullptr) reject(who, values_name, "non-null", 0.0);
    if (!std::isfinite(t[0])) reject(who, "t", "finite", t[0]);
    for (std::size_t i = 1; i < n_t; ++i) {
        // Also catches NaN and infinity: the comparison fails for both.
        if (!(t[i] > t[i - 1] && std::isfinite(t[i]))) {
            const std::string rule = "strictly increasing and finite (sample " + std::to_string(i) + " after " +
                                     std::to_string(t[i - 1]) + ")";
            reject(who, "t", rule.c_str(), t[i]);
        }
    }
}

inline void require_window_in_data(const char* who, const double* t, std::size_t n, double t_a, double t_b) {
    if (!(std::isfinite(t_a) && t_a >= t[0] && t_a <= t[n - 1]))
        reject(who, "t_a", "inside the sampled time range [t_first, t_last]", t_a);
    if (!(std::isfinite(t_b) && t_b >= t[0] && t_b <= t[n - 1]))
        reject(who, "t_b", "inside the sampled time range [t_first, t_last]", t_b);
    if (!(t_b > t_a)) reject(who, "t_b", "> t_a", t_b);
}

// Index k of the segment [t[k], t[k+1]] that holds x (t[0] <= x <= t[n-1]); the last segment holds t[n-1].
inline std::size_t segment_of(const double* t, std::size_t n, double x) {
    const std::size_t upper = static_cast<std::size_t>(std::upper_bound(t, t + n, x) - t);
    return std::min(upper == 0 ? 0 : upper - 1, n - 2);
}

inline double interpolate_on(const double* t, const double* y, std::size_t k, double x) {
    const double s = (x - t[k]) / (t[k + 1] - t[k]);
    return y[k] + s * (y[k + 1] - y[k]);
}

// Exact integral of the piecewise-linear interpolant of (t, y) over [a, b], both inside the data, a < b.
inline double integrate_interpolant(const double* t, const double* y, std::size_t n, double a, double b) {
    const std::size_t first = segment_of(t, n, a);
    const std::size_t last = segment_of(t, n, b);
    const double y_a = interpolate_on(t, y, first, a);
    const double y_b = interpolate_on(t, y, last, b);
    if (first == last) return 0.5 * (b - a) * (y_a + y_b);
    double sum = 0.5 * (t[first + 1] - a) * (y_a + y[first + 1]);  // partial first segment
    for (std::size_t k = first + 1; k < last; ++k) sum += 0.5 * (t[k + 1] - t[k]) * (y[k] + y[k + 1]);
    sum += 0.5 * (b - t[last]) * (y[last] + y_b);  // partial last segment
    return sum;
}

}  // namespace frictionsim::detail
