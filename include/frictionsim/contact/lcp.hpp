// A small dense linear complementarity problem (LCP) solver, and the joint stick/slip resolution of contacts at
// rest written as an LCP (issue 13, item 1: several contacts that switch at once, or whose stick conditions
// couple, are resolved together, not contact by contact).
//
//   LCP(M, q):  find z with  w = M z + q,  w >= 0,  z >= 0,  w' z = 0.
//
// solve_lcp_lemke: Lemke's complementary pivoting (Lemke 1965; Cottle, Pang & Stone 1992, Sec. 4.4) with the
// covering vector e and a lexicographic ratio test (no cycling on degenerate problems). It processes every
// copositive-plus M (the contact problems below): it ends at a solution, or at a secondary ray, which proves that
// the LCP has no solution (status ray_termination).
// solve_lcp_murty: Murty's least-index principal pivoting (Murty 1974; Cottle, Pang & Stone Sec. 4.2): finite
// for P-matrices (all principal minors positive; the LCP then has exactly one solution), cheap for a few contacts.
// Non-finite input throws InvalidParameter; a failure is a status, never a NaN.
//
// resolve_contacts_at_rest: Pfeiffer & Glocker (1996, Multibody Dynamics with Unilateral Contacts, Ch. 6 / 7.2):
// for contacts with zero relative velocity, with tangential accelerations a = W lambda + b (lambda: the friction
// forces on the contact coordinates, W = G M^-1 G' the coupling through the mechanism, b: the accelerations without
// friction) and static bounds |lambda_i| <= L_i,
//   a_i = a_i+ - a_i-,  a_i+ >= 0 _|_ L_i + lambda_i >= 0,   a_i- >= 0 _|_ L_i - lambda_i >= 0,
// i.e. LCP(M, q) in z = (L + lambda, a-), w = (a+, L - lambda) with M = [W I; -I 0], q = (b - W L, 2 L).
// A contact with a_i > 0 slips forwards (lambda_i = -L_i), a_i < 0 backwards, a_i = 0 sticks. With one contact,
// W = 1/m: stick iff |m b| <= L, Leine's switch model (contact/switching.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "../detail/validate.hpp"
#include "../contact_mode.hpp"

namespace frictionsim {

enum class LcpStatus {
    solved,
    ray_termination,  ///< Lemke: a secondary ray, the LCP has no solution (for copositive-plus M)
    no_convergence,   ///< the pivot budget ran out (Murty's method on a matrix that is not a P-matrix)
    singular_pivot,   ///< Murty: a singular principal submatrix (M is not a P-matrix)
};

inline const char* lcp_status_name(LcpStatus s) {
    switch (s) {
        case LcpStatus::solved: return "solved";
        case LcpStatus::ray_termination: return "ray_termination";
        case LcpStatus::no_convergence: return "no_convergence";
        case LcpStatus::singular_pivot: return "singular_pivot";
    }
    return "unknown";
}

struct LcpSolution {
    LcpStatus status = LcpStatus::solved;
    std::vector<double> z, w;  ///< w = M z + q (recomputed from z)
    int pivots = 0;
    bool solved() const { return status == LcpStatus::solved; }
};

namespace detail {

/// Checks sizes and finiteness; returns n. M is row-major n x n.
inline std::size_t lcp_check(const char* owner, const std::vector<double>& M, const std::vector<double>& q) {
    const std::size_t n = q.size();
    if (M.size() != n * n) reject(owner, "M", "n x n for q of size n (entries given)", static_cast<double>(M.size()));
    for (double v : M) require_finite(owner, "M", v);
    for (double v : q) require_finite(owner, "q", v);
    return n;
}

/// Scale of the problem for the sign tests: 1e-12 of its largest entry (at least 1e-300).
inline double lcp_tolerance(const std::vector<double>& M, const std::vector<double>& q) {
    double scale = 0.0;
    for (double v : M) scale = std::max(scale, std::abs(v));
    for (double v : q) scale = std::max(scale, std::abs(v));
    return std::max(1e-12 * scale, 1e-300);
}

inline void lcp_finish(LcpSolution& s, const std::vector<double>& M, const std::vector<double>& q) {
    const std::size_t n = q.size();
    s.w.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        double wi = q[i];
        for (std::size_t j = 0; j < n; ++j) wi += M[i * n + j] * s.z[j];
        s.w[i] = wi;
    }
}

/// Solves A x = b (A m x m, row-major, copied) by Gaussian elimination with partial pivoting; false if singular.
inline bool lcp_solve_dense(std::vector<double> A, std::vector<double>& b, std::size_t m, double tiny) {
    for (std::size_t k = 0; k < m; ++k) {
        std::size_t p = k;
        for (std::size_t i = k + 1; i < m; ++i)
            if (std::abs(A[i * m + k]) > std::abs(A[p * m + k])) p = i;
        if (!(std::abs(A[p * m + k]) > tiny)) return false;
        if (p != k) {
            for (std::size_t j = 0; j < m; ++j) std::swap(A[k * m + j], A[p * m + j]);
            std::swap(b[k], b[p]);
        }
        for (std::size_t i = k + 1; i < m; ++i) {
            const double f = A[i * m + k] / A[k * m + k];
            if (f == 0.0) continue;
            for (std::size_t j = k; j < m; ++j) A[i * m + j] -= f * A[k * m + j];
            b[i] -= f * b[k];
        }
    }
    for (std::size_t k = m; k-- > 0;) {
        double s = b[k];
        for (std::size_t j = k + 1; j < m; ++j) s -= A[k * m + j] * b[j];
        b[k] = s / A[k * m + k];
    }
    return true;
}

}  // namespace detail

/// Lemke's method on LCP(M, q), M row-major n x n. `max_pivots` 0: 50 (n + 1)^2.
inline LcpSolution solve_lcp_lemke(const std::vector<double>& M, const std::vector<double>& q, int max_pivots = 0) {
    const std::size_t n = detail::lcp_check("solve_lcp_lemke", M, q);
    const double tol = detail::lcp_tolerance(M, q);
    LcpSolution s;
    s.z.assign(n, 0.0);
    if (std::all_of(q.begin(), q.end(), [](double v) { return v >= 0.0; })) {  // z = 0 solves it
        detail::lcp_finish(s, M, q);
        return s;
    }
    if (max_pivots <= 0) max_pivots = static_cast<int>(50 * (n + 1) * (n + 1));
    // Tableau of w - M z - e z0 = q over the variables w_0..w_n-1, z_0..z_n-1, z0 (column 2n); rhs b.
    const std::size_t cols = 2 * n + 1, artificial = 2 * n;
    std::vector<double> T(n * cols, 0.0), b = q;
    std::vector<std::size_t> basis(n);
    for (std::size_t i = 0; i < n; ++i) {
        T[i * cols + i] = 1.0;
        for (std::size_t j = 0; j < n; ++j) T[i * cols + n + j] = -M[i * n + j];
        T[i * cols + artificial] = -1.0;
        basis[i] = i;
    }
    auto pivot = [&](std::size_t r, std::size_t c) {
        const double p = T[r * cols + c];
        for (std::size_t j = 0; j < cols; ++j) T[r * cols + j] /= p;
        b[r] /= p;
        for (std::size_t i = 0; i < n; ++i) {
            if (i == r) continue;
            const double f = T[i * cols + c];
            if (f == 0.0) continue;
            for (std::size_t j = 0; j < cols; ++j) T[i * cols + j] -= f * T[r * cols + j];
            b[i] -= f * b[r];
        }
        const std::size_t left = basis[r];
        basis[r] = c;
        ++s.pivots;
        return left;
    };
    // z0 enters at the row of the most negative q: every rhs becomes >= 0.
    std::size_t r = 0;
    for (std::size_t i = 1; i < n; ++i)
        if (b[i] < b[r]) r = i;
    std::size_t left = pivot(r, artificial);
    while (true) {
        if (s.pivots > max_pivots) {
            s.status = LcpStatus::no_convergence;
            break;
        }
        const std::size_t entering = left < n ? left + n : left - n;  // the complement of the variable that left
        // Lexicographic ratio test over (b, columns of the original basis w): ties broken without cycling.
        std::size_t best = n;
        for (std::size_t i = 0; i < n; ++i) {
            const double a = T[i * cols + entering];
            if (!(a > tol)) continue;
            if (best == n) {
                best = i;
                continue;
            }
            const double ab = T[best * cols + entering];
            auto compare = [&](double vi, double vb) {  // -1: row i smaller, +1: best smaller, 0: tie
                const double x = vi / a, y = vb / ab;
                const double eps = tol * std::max({1.0, std::abs(x), std::abs(y)});
                return x < y - eps ? -1 : (y < x - eps ? 1 : 0);
            };
            int c = compare(b[i], b[best]);
            for (std::size_t j = 0; c == 0 && j < n; ++j) c = compare(T[i * cols + j], T[best * cols + j]);
            if (c < 0) best = i;
        }
        if (best == n) {
            s.status = LcpStatus::ray_termination;
            break;
        }
        // z0 leaves as soon as it may: prefer its row among ties in the plain ratio.
        for (std::size_t i = 0; i < n; ++i) {
            if (basis[i] != artificial || i == best) continue;
            const double a = T[i * cols + entering];
            if (a > tol && b[i] / a <= b[best] / T[best * cols + entering] + tol) best = i;
        }
        left = pivot(best, entering);
        if (left == artificial) break;
    }
    if (s.status == LcpStatus::solved)
        for (std::size_t i = 0; i < n; ++i)
            if (basis[i] >= n && basis[i] < artificial) s.z[basis[i] - n] = std::max(0.0, b[i]);
    detail::lcp_finish(s, M, q);
    return s;
}

/// Murty's least-index principal pivoting on LCP(M, q): finite for P-matrices. `max_pivots` 0: 2^min(n, 20) + 10.
inline LcpSolution solve_lcp_murty(const std::vector<double>& M, const std::vector<double>& q, int max_pivots = 0) {
    const std::size_t n = detail::lcp_check("solve_lcp_murty", M, q);
    const double tol = detail::lcp_tolerance(M, q);
    if (max_pivots <= 0) max_pivots = (1 << std::min<std::size_t>(n, 20)) + 10;
    LcpSolution s;
    std::vector<char> basic(n, 0);  // z_i basic (w_i = 0) or not (z_i = 0)
    while (true) {
        std::vector<std::size_t> B;
        for (std::size_t i = 0; i < n; ++i)
            if (basic[i]) B.push_back(i);
        const std::size_t m = B.size();
        std::vector<double> A(m * m), rhs(m);
        for (std::size_t i = 0; i < m; ++i) {
            rhs[i] = -q[B[i]];
            for (std::size_t j = 0; j < m; ++j) A[i * m + j] = M[B[i] * n + B[j]];
        }
        s.z.assign(n, 0.0);
        if (!detail::lcp_solve_dense(A, rhs, m, tol)) {
            s.status = LcpStatus::singular_pivot;
            break;
        }
        for (std::size_t i = 0; i < m; ++i) s.z[B[i]] = rhs[i];
        detail::lcp_finish(s, M, q);
        std::size_t bad = n;  // least index with a negative basic z or a negative non-basic w
        for (std::size_t i = 0; i < n && bad == n; ++i)
            if (basic[i] ? s.z[i] < -tol : s.w[i] < -tol) bad = i;
        if (bad == n) {
            for (double& v : s.z) v = std::max(0.0, v);
            break;
        }
        if (++s.pivots > max_pivots) {
            s.status = LcpStatus::no_convergence;
            break;
        }
        basic[bad] = !basic[bad];
    }
    detail::lcp_finish(s, M, q);
    return s;
}

/// The default solver: Lemke's method (any copositive-plus M, including the contact problems).
inline LcpSolution solve_lcp(const std::vector<double>& M, const std::vector<double>& q) {
    return solve_lcp_lemke(M, q);
}

/// New stick/slip set of contacts at rest, from resolve_contacts_at_rest.
struct ContactsAtRest {
    LcpStatus status = LcpStatus::solved;
    std::vector<int> modes;            ///< stick, slip_positive or slip_negative (ContactMode) per contact
    std::vector<double> friction;      ///< lambda_i: friction force on each contact coordinate (N or N m)
    std::vector<double> acceleration;  ///< a_i = (W lambda + b)_i
    bool solved() const { return status == LcpStatus::solved; }
};

/// Joint stick/slip resolution of n contacts at rest (Pfeiffer & Glocker, see the header comment): W (row-major
/// n x n, symmetric positive semi-definite with a positive diagonal: the inverse mass seen by the contacts),
/// `free_acceleration` b (accelerations without friction), `static_limit` L (> 0). A contact whose acceleration is
/// zero to round-off sticks; at a tie (zero acceleration with its force at the bound) it is reported stuck with
/// zero reserve: only the rate of the holding force (the guards' direction, one order higher) can tell whether
/// it breaks away.
inline ContactsAtRest resolve_contacts_at_rest(const std::vector<double>& W, const std::vector<double>& free_acceleration,
                                               const std::vector<double>& static_limit) {
    constexpr const char* owner = "resolve_contacts_at_rest";
    const std::size_t n = free_acceleration.size();
    if (W.size() != n * n) detail::reject(owner, "W", "n x n for n contacts (entries given)", static_cast<double>(W.size()));
    if (static_limit.size() != n)
        detail::reject(owner, "static_limit", "one per contact (entries given)", static_cast<double>(static_limit.size()));
    for (double v : W) detail::require_finite(owner, "W", v);
    for (double v : free_acceleration) detail::require_finite(owner, "free_acceleration", v);
    for (std::size_t i = 0; i < n; ++i) {
        detail::require_positive(owner, "W", W[i * n + i]);  // a contact that no force can accelerate
        detail::require_positive(owner, "static_limit", static_limit[i]);
    }
    std::vector<double> M(4 * n * n, 0.0), q(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        double wl = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
            M[i * 2 * n + j] = W[i * n + j];
            wl += W[i * n + j] * static_limit[j];
        }
        M[i * 2 * n + n + i] = 1.0;
        M[(n + i) * 2 * n + i] = -1.0;
        q[i] = free_acceleration[i] - wl;
        q[n + i] = 2.0 * static_limit[i];
    }
    const LcpSolution s = solve_lcp_lemke(M, q);
    ContactsAtRest out;
    out.status = s.status;
    out.modes.assign(n, int{stick});
    out.friction.assign(n, 0.0);
    out.acceleration.assign(n, 0.0);
    if (!s.solved()) return out;
    double scale = 0.0;  // round-off level of the accelerations
    for (std::size_t i = 0; i < n; ++i) {
        out.friction[i] = std::clamp(s.z[i] - static_limit[i], -static_limit[i], static_limit[i]);
        scale = std::max(scale, std::abs(free_acceleration[i]));
        for (std::size_t j = 0; j < n; ++j) scale = std::max(scale, std::abs(W[i * n + j] * static_limit[j]));
    }
    const double tol = 1e-12 * scale;
    for (std::size_t i = 0; i < n; ++i) {
        double a = free_acceleration[i];
        for (std::size_t j = 0; j < n; ++j) a += W[i * n + j] * out.friction[j];
        if (a > tol) out.modes[i] = slip_positive;
        else if (a < -tol) out.modes[i] = slip_negative;
    }
    for (std::size_t i = 0; i < n; ++i)  // a slipping contact carries its bound exactly (no round-off from z - L)
        if (out.modes[i] != stick) out.friction[i] = -out.modes[i] * static_limit[i];
    for (std::size_t i = 0; i < n; ++i) {
        double a = free_acceleration[i];
        for (std::size_t j = 0; j < n; ++j) a += W[i * n + j] * out.friction[j];
        out.acceleration[i] = out.modes[i] == stick ? 0.0 : a;
    }
    return out;
}

}  // namespace frictionsim
