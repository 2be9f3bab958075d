// Cycle means of sampled signals: the mean friction force over whole vibration cycles after a transient
// (F_df of paper 000, Table 4: "the average sliding friction force in a vibration cycle"), and the friction
// reduction it brings against the force without vibration (F_sf).
//
// Two routes to the same mean:
//  * mean_over_cycles / mean_over_window integrate the sampled signal with the trapezoid rule, i.e. exactly
//    integrate its piecewise-linear interpolant. Good for smooth signals; a discontinuous force (Coulomb
//    friction reversing sign) costs O(sample spacing) per jump.
//  * mean_from_integral differences a running integral Y(t) = int_0^t y, e.g. a friction-impulse state the
//    solver integrates alongside the rig. The solver's error control and event location then make the mean
//    exact to solver tolerance even when the force jumps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../detail/sampled.hpp"
#include "../detail/validate.hpp"
#include "../solve/result.hpp"

namespace frictionsim {

/// [start, end] of `cycles` whole vibration periods. start = t_first + transient.
struct CycleWindow {
    double start;  ///< t_a [s]
    double end;    ///< t_b = t_a + cycles * period [s]
    int cycles;    ///< number of whole periods in the window
};

namespace detail {

// Relative slack that lets a window end that is "t_last up to rounding" count as inside the data: a run to
// t = 10 * period often records t_last = 9.999999999999998 * period.
constexpr double cycle_window_slack = 1e-9;

inline CycleWindow whole_cycle_window(const char* who, double t_first, double t_last, double period,
                                      double transient, int cycles) {
    require_finite(who, "t_first", t_first);
    require_finite(who, "t_last", t_last);
    if (!(t_last > t_first)) reject(who, "t_last", "> t_first", t_last);
    require_positive(who, "period", period);
    require_non_negative(who, "transient", transient);
    const double start = t_first + transient;
    const double span = t_last - start;
    if (!(span > 0.0)) reject(who, "transient", "shorter than the record t_last - t_first", transient);
    const double fit = span / period * (1.0 + cycle_window_slack);
    if (cycles <= 0) {
        cycles = static_cast<int>(std::min(std::floor(fit), 2147483647.0));
        if (cycles < 1)
            reject(who, "period", "at most t_last - t_first - transient (one whole cycle must fit)", period);
    } else if (static_cast<double>(cycles) > fit) {
        const std::string rule = "at most the " + std::to_string(static_cast<long long>(std::floor(fit))) +
                                 " whole cycles that fit after the transient";
        reject(who, "cycles", rule.c_str(), static_cast<double>(cycles));
    }
    const double end = std::min(start + static_cast<double>(cycles) * period, t_last);
    return CycleWindow{start, end, cycles};
}

}  // namespace detail

/// Whole-cycle window after a transient: t_a = t_first + transient, t_b = t_a + n * period.
/// cycles <= 0 takes as many whole periods as fit in [t_a, t_last]; cycles > 0 asks for exactly that many and
/// throws when they do not fit. A window end that overshoots t_last by rounding only (1e-9 of a period) is
/// clamped to t_last.
inline CycleWindow whole_cycle_window(double t_first, double t_last, double period, double transient,
                                      int cycles = 0) {
    return detail::whole_cycle_window("whole_cycle_window", t_first, t_last, period, transient, cycles);
}

namespace detail {

inline double mean_over_window(const char* who, const double* t, const double* y, std::size_t t_size,
                               std::size_t y_size, double t_a, double t_b) {
    require_samples(who, "y", t, y, t_size, y_size);
    require_window_in_data(who, t, t_size, t_a, t_b);
    return integrate_interpolant(t, y, t_size, t_a, t_b) / (t_b - t_a);
}

inline double mean_over_cycles(const double* t, const double* y, std::size_t t_size, std::size_t y_size,
                               double period, double transient, int cycles) {
    constexpr const char* who = "mean_over_cycles";
    require_samples(who, "y", t, y, t_size, y_size);
    const CycleWindow w = whole_cycle_window(who, t[0], t[t_size - 1], period, transient, cycles);
    return integrate_interpolant(t, y, t_size, w.start, w.end) / (w.end - w.start);
}

inline double mean_from_integral(const double* t, const double* running_integral, std::size_t t_size,
                                 std::size_t integral_size, double t_a, double t_b) {
    constexpr const char* who = "mean_from_integral";
    require_samples(who, "running_integral", t, running_integral, t_size, integral_size);
    require_window_in_data(who, t, t_size, t_a, t_b);
    const double Y_a = interpolate_on(t, running_integral, segment_of(t, t_size, t_a), t_a);
    const double Y_b = interpolate_on(t, running_integral, segment_of(t, t_size, t_b), t_b);
    return (Y_b - Y_a) / (t_b - t_a);
}

}  // namespace detail

/// Mean of the sampled signal y(t) over [t_a, t_b]: exact integral of its piecewise-linear interpolant
/// (trapezoid rule, linear interpolation at window ends that fall between samples) divided by t_b - t_a.
inline double mean_over_window(const double* t, const double* y, std::size_t n, double t_a, double t_b) {
    return detail::mean_over_window("mean_over_window", t, y, n, n, t_a, t_b);
}

inline double mean_over_window(const std::vector<double>& t, const std::vector<double>& y, double t_a,
                               double t_b) {
    return detail::mean_over_window("mean_over_window", t.data(), y.data(), t.size(), y.size(), t_a, t_b);
}

/// Mean of y over whole vibration cycles after a transient: the window is whole_cycle_window(t[0], t[n-1],
/// period, transient, cycles), so cycles <= 0 takes as many whole cycles as fit.
inline double mean_over_cycles(const double* t, const double* y, std::size_t n, double period, double transient,
                               int cycles = 0) {
    return detail::mean_over_cycles(t, y, n, n, period, transient, cycles);
}

inline double mean_over_cycles(const std::vector<double>& t, const std::vector<double>& y, double period,
                               double transient, int cycles = 0) {
    return detail::mean_over_cycles(t.data(), y.data(), t.size(), y.size(), period, transient, cycles);
}

/// (Y(t_b) - Y(t_a)) / (t_b - t_a): the mean of y = dY/dt over [t_a, t_b] from its running integral Y,
/// linearly interpolated between samples. Exact to the accuracy of Y (solver tolerance when Y is a state the
/// solver integrates and the window ends are output times) even where y is discontinuous.
inline double mean_from_integral(const double* t, const double* running_integral, std::size_t n, double t_a,
                                 double t_b) {
    return detail::mean_from_integral(t, running_integral, n, n, t_a, t_b);
}

inline double mean_from_integral(const std::vector<double>& t, const std::vector<double>& running_integral,
                                 double t_a, double t_b) {
    return detail::mean_from_integral(t.data(), running_integral.data(), t.size(), running_integral.size(), t_a,
                                      t_b);
}

/// Mean from a running integral over a window from whole_cycle_window.
inline double mean_from_integral(const std::vector<double>& t, const std::vector<double>& running_integral,
                                 const CycleWindow& window) {
    return mean_from_integral(t, running_integral, window.start, window.end);
}

/// Friction reduction 1 - F_df / F_sf: the fraction of the no-vibration mean friction force (F_sf, paper 000
/// Table 4) that vibration removes (F_df). 0 means no effect, 1 means no mean friction left; negative means
/// vibration increased the mean force.
inline double friction_reduction(double mean_with_vibration, double mean_without) {
    constexpr const char* who = "friction_reduction";
    detail::require_finite(who, "mean_with_vibration", mean_with_vibration);
    detail::require_finite(who, "mean_without", mean_without);
    if (mean_without == 0.0) detail::reject(who, "mean_without", "non-zero", mean_without);
    return 1.0 - mean_with_vibration / mean_without;
}

/// Mean friction force of a simulation over whole cycles after a transient, from its running friction
/// impulse (exact to solver tolerance where output times fall on the window ends, even across stick-slip jumps).
inline double mean_friction_over_cycles(const Result& result, double period, double transient, int cycles = 0) {
    const std::vector<double> impulse = result.column_values("friction_impulse");
    const CycleWindow w = whole_cycle_window(result.t.front(), result.t.back(), period, transient, cycles);
    return mean_from_integral(result.t, impulse, w.start, w.end);
}

}  // namespace frictionsim
