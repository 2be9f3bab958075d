// What several convergence tests measure with: an output grid and the fitted order of an error. One definition each.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace frictionsim::test {

/// Output times 0, dt, 2 dt, ... up to t_end (a whole number of intervals, rounded; none past t_end).
inline std::vector<double> grid(double t_end, double dt) {
    std::vector<double> t;
    const long steps = std::lround(t_end / dt);
    for (long k = 0; k <= steps; ++k) t.push_back(std::min(t_end, dt * static_cast<double>(k)));
    return t;
}

/// The least-squares slope of log(error) against log(x): the measured order.
inline double fitted_order(const std::vector<double>& x, const std::vector<double>& error) {
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double lx = std::log(x[i]), ly = std::log(error[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace frictionsim::test
