// How a hybrid system hands its Jacobian d(rhs)/dx to an implicit integrator (CVODE, the Rosenbrock method).
// All members are optional; without any, the integrators difference the right-hand side (within the band when
// the system declares one).
//
//   void jacobian(double t, const double* x, const Mode& mode, double* J) const;
//        dense, column-major (J[col * n + row]), J zeroed before the call: the lab rigs' form
//   Bandwidths jacobian_bandwidths() const;
//        J(i, j) == 0 whenever j - i > upper or i - j > lower, in every mode: a string's nodes couple only their
//        neighbours, so its Jacobian is banded and costs O(N) to factor
//   template <class Add> void jacobian_entries(double t, const double* x, const Mode& mode, Add&& add) const;
//        the structurally non-zero entries as add(row, col, value) calls (a repeated (row, col) is summed): the
//        form that fills a band or a sparse (KLU) matrix without an n x n buffer
//   std::vector<std::pair<std::size_t, std::size_t>> jacobian_pattern() const;
//        every (row, col) jacobian_entries may ever write, in any mode: the sparsity KLU analyses once. Without
//        it the sparse pattern is the full band.
//   std::size_t quadrature_offset() const;
//        the rows from this one to the last are quadratures (a string's work integrals): their derivatives read the
//        other states, no derivative reads them, and the Jacobian leaves their rows out (they read every node, far
//        outside a band). CVODE's Newton iteration converges without those rows; RODAS4 adds their product with
//        its stages by a directional difference, which its order needs (eigen/rosenbrock.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "../detail/traits.hpp"
#include "system_size.hpp"

namespace frictionsim {

/// Lower and upper bandwidths of a banded Jacobian (a tridiagonal one has 1 and 1).
struct Bandwidths {
    std::size_t lower = 0;
    std::size_t upper = 0;
};

namespace detail {
/// A sink with the signature jacobian_entries is called with, for detection.
struct JacobianEntrySink {
    void operator()(std::size_t, std::size_t, double) const {}
};
template <class S> using dense_jacobian_t = decltype(std::declval<const S&>().jacobian(
    0.0, std::declval<const double*>(), std::declval<const system_mode_t<S>&>(), std::declval<double*>()));
template <class S> using jacobian_entries_t = decltype(std::declval<const S&>().jacobian_entries(
    0.0, std::declval<const double*>(), std::declval<const system_mode_t<S>&>(), std::declval<JacobianEntrySink&>()));
template <class S> using bandwidths_t = decltype(Bandwidths{std::declval<const S&>().jacobian_bandwidths()});
template <class S> using pattern_t = decltype(std::declval<const S&>().jacobian_pattern().size());
template <class S> using quadrature_offset_t = decltype(std::size_t{std::declval<const S&>().quadrature_offset()});
}  // namespace detail

template <class S> constexpr bool has_dense_jacobian_v = detail::detected<S, detail::dense_jacobian_t>::value;
template <class S> constexpr bool has_jacobian_entries_v = detail::detected<S, detail::jacobian_entries_t>::value;
template <class S> constexpr bool declares_bandwidths_v = detail::detected<S, detail::bandwidths_t>::value;
template <class S> constexpr bool declares_pattern_v = detail::detected<S, detail::pattern_t>::value;
template <class S> constexpr bool has_quadrature_rows_v = detail::detected<S, detail::quadrature_offset_t>::value;

/// The system's declared bandwidths, or the full matrix's (n - 1, n - 1).
template <class S>
Bandwidths bandwidths_of(const S& s) {
    if constexpr (declares_bandwidths_v<S>) {
        return s.jacobian_bandwidths();
    } else {
        const std::size_t n = state_size_of(s);
        return {n > 0 ? n - 1 : 0, n > 0 ? n - 1 : 0};
    }
}

/// The sparsity KLU analyses: the declared pattern, or every entry inside the band, sorted by column then row.
template <class S>
std::vector<std::pair<std::size_t, std::size_t>> jacobian_pattern_of(const S& s) {
    std::vector<std::pair<std::size_t, std::size_t>> entries;
    if constexpr (declares_pattern_v<S>) {
        entries = s.jacobian_pattern();
    } else {
        const std::size_t n = state_size_of(s);
        const Bandwidths b = bandwidths_of(s);
        for (std::size_t col = 0; col < n; ++col) {
            const std::size_t first = col > b.upper ? col - b.upper : 0;
            const std::size_t last = std::min(n - 1, col + b.lower);
            for (std::size_t row = first; row <= last; ++row) entries.emplace_back(row, col);
        }
    }
    return entries;
}

}  // namespace frictionsim
