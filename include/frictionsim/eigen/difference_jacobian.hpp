// Forward-difference Jacobians of a right-hand side, for implicit integrators whose system gives none.
// Dense: one right-hand side per column. Banded: Curtis, Powell & Reid (1974, "On the estimation of sparse
// Jacobian matrices", J. Inst. Maths Applics 13, 117-119): columns j and j' with |j - j'| > lower + upper touch
// no common row, so every (lower + upper + 1)-th column is perturbed at once and the whole band costs
// lower + upper + 1 right-hand sides, whatever n is.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "banded_lu.hpp"
#include "../solve/jacobian.hpp"

namespace frictionsim {

namespace detail {
/// Hairer & Wanner's increment (RADAU5, RODAS): sqrt(eps max(1e-5, |x|)), a balance of truncation (~ delta) and
/// rounding (~ eps / delta) for states of order one, never zero for a state at zero.
inline double difference_increment(double x) {
    return std::sqrt(std::numeric_limits<double>::epsilon() * std::max(1e-5, std::abs(x)));
}
}  // namespace detail

/// Dense forward differences: J (column-major, n x n) = [f(t, x + delta_j e_j) - f0] / delta_j column by column.
/// f(t, x, dxdt) evaluates the right-hand side; f0 = f(t, x); `x` is restored; `work` holds n values. n calls of f.
template <class Rhs>
void difference_jacobian_dense(Rhs&& f, double t, double* x, const double* f0, std::size_t n, double* J,
                               double* work) {
    for (std::size_t j = 0; j < n; ++j) {
        const double saved = x[j];
        const double delta = detail::difference_increment(saved);
        x[j] = saved + delta;
        const double step = x[j] - saved;  // the increment actually represented
        f(t, x, work);
        x[j] = saved;
        for (std::size_t i = 0; i < n; ++i) J[j * n + i] = (work[i] - f0[i]) / step;
    }
}

/// Banded forward differences with Curtis-Powell-Reid column groups: lower + upper + 1 calls of f (or n if fewer).
/// Fills J (its bandwidths are the groups' spacing); `x` is restored; `work` holds n values.
template <class Rhs>
void difference_jacobian_banded(Rhs&& f, double t, double* x, const double* f0, BandMatrix& J, double* work,
                                double* saved) {
    const std::size_t n = J.size();
    const Bandwidths b = J.bandwidths();
    const std::size_t groups = std::min(n, b.lower + b.upper + 1);
    for (std::size_t g = 0; g < groups; ++g) {
        for (std::size_t j = g; j < n; j += groups) {
            saved[j] = x[j];
            x[j] += detail::difference_increment(x[j]);
        }
        f(t, x, work);
        for (std::size_t j = g; j < n; j += groups) {
            const double step = x[j] - saved[j];
            x[j] = saved[j];
            const std::size_t first = j > b.upper ? j - b.upper : 0, last = std::min(n - 1, j + b.lower);
            for (std::size_t i = first; i <= last; ++i) J(i, j) = (work[i] - f0[i]) / step;
        }
    }
}

}  // namespace frictionsim
