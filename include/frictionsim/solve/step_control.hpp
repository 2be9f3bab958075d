// What the one-step integrators with error control (Dormand-Prince, RODAS4) share: the error weights, the
// shortest step that still carries information, the length of the next trial step, Hairer's starting step, and
// the failure that keeps the time reached.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>

#include "../error.hpp"
#include "options.hpp"

namespace frictionsim::detail {

/// Weight of state i in the error norm: atol_i + rtol max(|a|, |b|) (Hairer's sc_i, a and b the state at both ends).
inline double error_scale(const SolverOptions& o, std::size_t i, double a, double b) {
    return o.absolute_tolerance(i) + o.rtol * std::max(std::abs(a), std::abs(b));
}

/// Steps this short carry no information at t (a few ulps): the error control cannot work there.
inline double underflow_step(double t) { return 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t)); }

/// The length of the next trial step from t towards t_stop: the controller's h within max_step, stretched to land
/// exactly on t_stop when it would stop a hair short (`last`).
inline double trial_step(double h, const SolverOptions& o, double t, double t_stop, bool& last) {
    h = std::min({h, o.max_step, t_stop - t});
    last = t + h >= t_stop || (t_stop - (t + h)) <= 1e-12 * std::abs(t_stop);
    return last ? t_stop - t : h;
}

/// SimulationError "<method>: <why> at t = <t> s", carrying t so that the loop keeps the result up to it.
[[noreturn]] inline void step_failure(const char* method, const char* why, double t) {
    std::ostringstream msg;
    msg.precision(17);
    msg << method << ": " << why << " at t = " << t << " s";
    throw SimulationError(msg.str(), t);
}

/// Hairer's starting step (Solving ODEs I, sec. II.4) for a method whose error estimate has order `order`:
/// a guess from |y| / |f|, refined by one explicit Euler step to h ~ (0.01 / |y''|)^(1 / (order + 1)).
/// y, f0 = f(t, y) of size n; ytmp and f1 are scratch; rhs(t, x, dxdt) evaluates f.
template <class Rhs>
double starting_step(std::size_t n, int order, const SolverOptions& o, double t, double t_stop, const double* y,
                     const double* f0, double* ytmp, double* f1, Rhs&& rhs) {
    double dnf = 0.0, dny = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double sk = error_scale(o, i, y[i], 0.0);
        dnf += (f0[i] / sk) * (f0[i] / sk);
        dny += (y[i] / sk) * (y[i] / sk);
    }
    double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : 0.01 * std::sqrt(dny / dnf);
    h = std::min({h, o.max_step, t_stop - t});
    for (std::size_t i = 0; i < n; ++i) ytmp[i] = y[i] + h * f0[i];
    rhs(t + h, ytmp, f1);
    double der2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double d = (f1[i] - f0[i]) / error_scale(o, i, y[i], 0.0);
        der2 += d * d;
    }
    const double der12 = std::max(std::sqrt(der2) / h, std::sqrt(dnf));
    const double h1 = der12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / der12, 1.0 / (order + 1));
    return std::min({100.0 * h, h1, o.max_step});
}

}  // namespace frictionsim::detail
