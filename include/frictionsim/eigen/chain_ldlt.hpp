// The chain's linear algebra for Moreau-Jean time-stepping (solve/moreau_jean.hpp, issue 13): W = M + theta h C +
// theta^2 h^2 K tridiagonal (a string), its stuck dofs' rows and columns replaced by the identity's, factored as
// LDL^T and solved; after contacts switch, the factors and the solution are updated from the switched dofs only, to
// the bits of a solve of the whole chain. With the small helpers its loops use (a finiteness test and a select that
// vectorise). No Eigen: plain arrays.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace frictionsim::detail {

/// Bit 63 set exactly when x is not finite: its 11 exponent bits are then all set, and adding 1 to the exponent
/// field carries into the sign bit. ORed over an array in integers, a finiteness test that vectorises.
inline std::uint64_t exponent_carry(double x) {
    constexpr std::uint64_t exponent = 0x7ff0000000000000u, one = 0x0010000000000000u;
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return (bits & exponent) + one;
}
/// Whether x_0..x_{n-1} are all finite.
inline bool all_finite(const double* x, std::size_t n) {
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < n; ++i) carry |= exponent_carry(x[i]);
    return (carry >> 63) == 0;
}

/// x where `mask` is all ones, +0.0 where it is 0: a select as a bitwise and (it vectorises where a branch on a
/// flag does not).
inline double masked(double x, std::uint64_t mask) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    bits &= mask;
    std::memcpy(&x, &bits, sizeof bits);
    return x;
}

/// A closed range of dofs, lo..hi.
struct DofSpan {
    std::size_t lo, hi;
};

/// LDL^T of a chain's W (tridiagonal, SPD) with the stuck dofs' rows and columns replaced by the identity's, and
/// the solution of W x = r, both updated in place when contacts switch. Each recurrence of the whole chain's solve
/// (d_i, l_i from d_{i-1}; y = L^-1 r from y_{i-1}; x = D^-1 y - L^T x from x_{i+1}) is rerun from the switched
/// dofs only until its value comes out bit for bit as stored: past that point every input of the recurrence is
/// unchanged, so is every value. A switch's influence decays geometrically along the chain (and a stuck dof stops
/// it at once), so an update costs some tens of dofs per switch, not the chain, and yields the bits of a solve of
/// the whole chain.
class ChainLDLT {
public:
    /// W(i, i), W(i, i - 1) and W(i - 1, i) (sub- and superdiagonal: index 0 unused).
    void assign(std::vector<double> diagonal, std::vector<double> subdiagonal, std::vector<double> superdiagonal) {
        wd_ = std::move(diagonal);
        wl_ = std::move(subdiagonal);
        wu_ = std::move(superdiagonal);
        const std::size_t n = wd_.size();
        d_.assign(n, 1.0);
        l_.assign(n, 0.0);
        y_.assign(n, 0.0);
    }
    std::size_t size() const { return wd_.size(); }
    double diagonal(std::size_t i) const { return wd_[i]; }

    /// (W x)_i, summed as the column of a compressed W (rows i - 1, i, i + 1).
    double row_times(std::size_t i, const double* x) const {
        double s = 0.0;
        if (i > 0) s += wu_[i] * x[i - 1];
        s += wd_[i] * x[i];
        if (i + 1 < size()) s += wl_[i + 1] * x[i + 1];
        return s;
    }

    /// The whole chain's factors; false when a pivot is not positive.
    bool factor(const char* stuck) {
        bool definite = true;
        for (std::size_t i = 0; i < size(); ++i) definite = factor_at(i, stuck) && definite;
        return definite;
    }
    /// y = L^-1 r over the whole chain (a stuck dof's r_i is 0).
    void forward(const double* r) {
        double* y = y_.data();
        const double* l = l_.data();
        y[0] = r[0];
        for (std::size_t i = 1; i < size(); ++i) y[i] = r[i] - l[i] * y[i - 1];
    }
    /// x = D^-1 y - L^T x over the whole chain.
    void backward(double* x) const {
        const double* y = y_.data();
        const double* l = l_.data();
        const double* d = d_.data();
        std::size_t i = size() - 1;
        x[i] = y[i] / d[i];
        while (i-- > 0) x[i] = y[i] / d[i] - l[i + 1] * x[i + 1];
    }

    /// After the dofs `switched` (increasing) changed between stuck and free: the factors, and x for the right-hand
    /// side r (changed at the switched dofs only), updated; `changed` receives the spans (increasing) where x may
    /// have changed. False when a pivot is not positive.
    bool update(const std::vector<std::size_t>& switched, const char* stuck, const double* r, double* x,
                std::vector<DofSpan>& changed) {
        const std::size_t n = size();
        // d_i and l_i read stuck_i and stuck_{i-1}
        sources_.clear();
        for (std::size_t s : switched) sources_.push_back(DofSpan{s, std::min(s + 1, n - 1)});
        bool definite = true;
        sweep_down(sources_, [&](std::size_t i) {
            const double d = d_[i], l = l_[i];
            definite = factor_at(i, stuck) && definite;
            return !same_bits(d, d_[i]) || !same_bits(l, l_[i]);
        }, factored_);
        // y_i reads r_i, l_i and y_{i-1}
        spans_.clear();
        for (std::size_t s : switched) spans_.push_back(DofSpan{s, s});
        merge(spans_, factored_, 0, sources_);
        double* y = y_.data();
        const double* l = l_.data();
        sweep_down(sources_, [&](std::size_t i) {
            const double old = y[i];
            y[i] = i == 0 ? r[i] : r[i] - l[i] * y[i - 1];
            return !same_bits(old, y[i]);
        }, eliminated_);
        // x_i reads y_i, d_i, l_{i+1} and x_{i+1}
        merge(eliminated_, factored_, 1, sources_);
        sweep_up(sources_, [&](std::size_t i) {
            const double old = x[i];
            x[i] = backward_at(i, x);
            return !same_bits(old, x[i]);
        }, changed);
        return definite;
    }

private:
    bool factor_at(std::size_t i, const char* stuck) {
        if (stuck[i]) {
            d_[i] = 1.0;
            l_[i] = 0.0;
            return true;
        }
        if (i == 0 || stuck[i - 1]) {
            l_[i] = 0.0;
            d_[i] = wd_[i];
        } else {
            const double li = wl_[i] / d_[i - 1];
            d_[i] = wd_[i] - li * wl_[i];
            l_[i] = li;
        }
        return d_[i] > 0.0;
    }
    double backward_at(std::size_t i, const double* x) const {
        return i + 1 == wd_.size() ? y_[i] / d_[i] : y_[i] / d_[i] - l_[i + 1] * x[i + 1];
    }
    static bool same_bits(double a, double b) {
        std::uint64_t ua, ub;
        std::memcpy(&ua, &a, sizeof a);
        std::memcpy(&ub, &b, sizeof b);
        return ua == ub;
    }

    /// Runs update(i) (true: its value changed) down the chain from each source span until past the span a value
    /// comes out unchanged; spans reached on the way join. `out`: the spans run.
    template <class Update>
    void sweep_down(const std::vector<DofSpan>& sources, Update&& update, std::vector<DofSpan>& out) const {
        out.clear();
        const std::size_t n = size(), count = sources.size();
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t lo = sources[k].lo;
            std::size_t hi = sources[k].hi, i = lo;
            std::size_t next = k + 1 < count ? sources[k + 1].lo : n;  // the next source's start
            for (;;) {
                const bool changed = update(i);
                if ((i >= hi && !changed) || i + 1 == n) break;
                if (++i == next) {  // reached: it joins
                    hi = std::max(hi, sources[++k].hi);
                    next = k + 1 < count ? sources[k + 1].lo : n;
                }
            }
            out.push_back(DofSpan{lo, i});
        }
    }
    /// The same up the chain (x_i from x_{i+1}); `out` increasing.
    template <class Update>
    void sweep_up(const std::vector<DofSpan>& sources, Update&& update, std::vector<DofSpan>& out) const {
        out.clear();
        const std::size_t none = size();
        for (std::size_t k = sources.size(); k-- > 0;) {
            const std::size_t hi = sources[k].hi;
            std::size_t lo = sources[k].lo, i = hi;
            std::size_t next = k > 0 ? sources[k - 1].hi : none;  // the next source's end (upwards)
            for (;;) {
                const bool changed = update(i);
                if ((i <= lo && !changed) || i == 0) break;
                if (--i == next) {  // reached: it joins
                    lo = std::min(lo, sources[--k].lo);
                    next = k > 0 ? sources[k - 1].hi : none;
                }
            }
            out.push_back(DofSpan{i, hi});
        }
        std::reverse(out.begin(), out.end());
    }
    /// The union of a and of b's spans widened `up` dofs towards 0, as increasing disjoint spans.
    static void merge(const std::vector<DofSpan>& a, const std::vector<DofSpan>& b, std::size_t up,
                      std::vector<DofSpan>& out) {
        out.clear();
        std::size_t ia = 0, ib = 0;
        while (ia < a.size() || ib < b.size()) {
            DofSpan next;
            if (ib == b.size() || (ia < a.size() && a[ia].lo + up <= b[ib].lo)) {
                next = a[ia++];
            } else {
                next = b[ib++];
                next.lo = next.lo >= up ? next.lo - up : 0;
            }
            if (!out.empty() && next.lo <= out.back().hi + 1)
                out.back().hi = std::max(out.back().hi, next.hi);
            else
                out.push_back(next);
        }
    }

    std::vector<double> wd_, wl_, wu_, d_, l_, y_;
    std::vector<DofSpan> sources_, spans_, factored_, eliminated_;
};

}  // namespace frictionsim::detail
