// Limit-cycle measures of a sampled speed signal, e.g. the disc speed of a drill-string rig in stick-slip:
// period and frequency, peak and trough speed, mean speed and stick fraction, over whole cycles after a
// transient. Cycles are delimited by upward crossings of a level (the mean speed unless given), located by
// linear interpolation between samples; a crossing only counts once the signal has been below the level by
// a hysteresis margin since the last one, so measurement noise near the level does not split cycles, and a
// signal whose peak-to-trough range stays below `min_amplitude` counts as no oscillation at all.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "cycle_mean.hpp"

namespace frictionsim {

struct LimitCycle {
    int cycles = 0;               ///< whole cycles found after the transient; 0: no oscillation about the level
    double period = 0.0;          ///< s, mean over the cycles (infinity when cycles == 0)
    double frequency = 0.0;       ///< Hz, 1 / period (0 when cycles == 0)
    double peak = 0.0;            ///< largest sample over the cycles (over the whole window when cycles == 0)
    double trough = 0.0;          ///< smallest sample, likewise
    double mean = 0.0;            ///< time mean, likewise
    double stick_fraction = 0.0;  ///< fraction of the time with |speed| <= stick_speed, likewise
    double level = 0.0;           ///< the crossing level used
    double start = 0.0, end = 0.0;  ///< s: the window measured (first and last crossing, or transient..end)
};

namespace detail {
// Time in [t0, t1] during which |y| <= threshold, y linear between (t0, y0) and (t1, y1).
inline double time_within(double t0, double y0, double t1, double y1, double threshold) {
    const double a = std::max(y0, y1), b = std::min(y0, y1);  // y spans [b, a]
    if (a == b) return std::abs(a) <= threshold ? t1 - t0 : 0.0;
    const double inside = std::max(0.0, std::min(a, threshold) - std::max(b, -threshold));
    return (t1 - t0) * inside / (a - b);
}
}  // namespace detail

/// Limit cycle of speed samples (t, w) after `transient` seconds. `level`: the crossing level (NaN: the mean
/// of w after the transient). `hysteresis`: the margin below the level, as a fraction of the peak-to-trough
/// range, that re-arms the crossing detector. `stick_speed`: |w| at or below it counts as stuck.
/// `min_amplitude`: the smallest peak-to-trough range (in w's units) that counts as an oscillation.
inline LimitCycle limit_cycle(const double* t, const double* w, std::size_t n, double transient,
                              double level = std::numeric_limits<double>::quiet_NaN(), double stick_speed = 1e-2,
                              double hysteresis = 0.05, double min_amplitude = 0.0) {
    constexpr const char* who = "limit_cycle";
    detail::require_samples(who, "w", t, w, n, n);
    detail::require_non_negative(who, "transient", transient);
    detail::require_non_negative(who, "stick_speed", stick_speed);
    if (!(hysteresis >= 0.0 && hysteresis < 1.0)) detail::reject(who, "hysteresis", "in [0, 1)", hysteresis);
    if (!std::isnan(level)) detail::require_finite(who, "level", level);
    detail::require_non_negative(who, "min_amplitude", min_amplitude);
    for (std::size_t i = 0; i < n; ++i) detail::require_finite(who, "w", w[i]);
    const double start = t[0] + transient;
    if (!(start < t[n - 1])) detail::reject(who, "transient", "shorter than the record t_last - t_first", transient);

    const std::size_t first = detail::segment_of(t, n, start);
    double lo = w[first], hi = w[first];
    for (std::size_t i = first; i < n; ++i) lo = std::min(lo, w[i]), hi = std::max(hi, w[i]);
    LimitCycle c;
    c.level = std::isnan(level) ? detail::integrate_interpolant(t, w, n, start, t[n - 1]) / (t[n - 1] - start) : level;
    const double rearm = c.level - hysteresis * (hi - lo);

    std::vector<double> crossings;
    bool armed = w[first] < rearm;
    for (std::size_t i = first; i + 1 < n; ++i) {
        if (w[i + 1] < rearm) armed = true;
        if (armed && w[i] < c.level && w[i + 1] >= c.level) {
            const double tc = t[i] + (c.level - w[i]) / (w[i + 1] - w[i]) * (t[i + 1] - t[i]);
            if (tc >= start) crossings.push_back(tc), armed = false;
        }
    }
    c.cycles = crossings.size() >= 2 && hi - lo > min_amplitude ? static_cast<int>(crossings.size()) - 1 : 0;
    c.start = c.cycles > 0 ? crossings.front() : start;
    c.end = c.cycles > 0 ? crossings.back() : t[n - 1];
    c.period = c.cycles > 0 ? (c.end - c.start) / c.cycles : std::numeric_limits<double>::infinity();
    c.frequency = c.cycles > 0 ? 1.0 / c.period : 0.0;

    // Peak, trough, mean and stick time over [c.start, c.end], window ends interpolated.
    const std::size_t a = detail::segment_of(t, n, c.start), b = detail::segment_of(t, n, c.end);
    const double w_start = detail::interpolate_on(t, w, a, c.start), w_end = detail::interpolate_on(t, w, b, c.end);
    c.peak = std::max(w_start, w_end), c.trough = std::min(w_start, w_end);
    for (std::size_t i = a + 1; i <= b; ++i) c.peak = std::max(c.peak, w[i]), c.trough = std::min(c.trough, w[i]);
    c.mean = detail::integrate_interpolant(t, w, n, c.start, c.end) / (c.end - c.start);
    double stuck = 0.0;
    for (std::size_t i = a; i <= b; ++i) {
        const double t0 = std::max(t[i], c.start), t1 = std::min(t[i + 1], c.end);
        if (t1 <= t0) continue;
        stuck += detail::time_within(t0, detail::interpolate_on(t, w, i, t0), t1, detail::interpolate_on(t, w, i, t1),
                                     stick_speed);
    }
    c.stick_fraction = stuck / (c.end - c.start);
    return c;
}

}  // namespace frictionsim
