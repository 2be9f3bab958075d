// The chain's linear algebra for Moreau-Jean time-stepping (solve/moreau_jean.hpp, issue 13): W = M + theta h C +
// theta^2 h^2 K tridiagonal (a string), its stuck dofs' rows and columns replaced by the identity's, factored as
// LDL^T and solved; after contacts switch, the factors and the solution are updated from the switched dofs only, to
// the bits of a solve of the whole chain. Eliminated from both ends towards the middle (a twisted factorisation):
// two independent recurrences of half the length. With the small helpers its loops use (a finiteness test and a
// select that vectorise). No Eigen: plain arrays.
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

/// A twisted LDL^T of a chain's W (tridiagonal, SPD) with the stuck dofs' rows and columns replaced by the
/// identity's, and the solution of W x = r, both updated in place when contacts switch. The chain is eliminated from
/// both ends towards its middle dof k (the twist; Parlett and Dhillon 2000, "twisted factorizations"): above k,
/// L D L^T from dof 0 down; below k, the same from dof n - 1 up; at k the two meet. The two halves' recurrences are
/// independent chains of n / 2 steps run in one loop, so a whole-chain factor or solve waits on half the latency of
/// a one-way elimination (the recurrences are latency-bound: each step waits on the one before).
///
/// Each recurrence (a half's d_i, l_i from its neighbour towards its end; y = L^-1 r likewise; x from its neighbour
/// towards the twist) is rerun from the switched dofs only until its value comes out bit for bit as stored: past that
/// point every input of the recurrence is unchanged, so is every value. A switch's influence decays geometrically
/// along the chain (and a stuck dof stops it at once), so an update costs some tens of dofs per switch, not the
/// chain, and yields the bits of a solve of the whole chain.
class ChainLDLT {
public:
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);

    /// W(i, i), W(i, i - 1) and W(i - 1, i) (sub- and superdiagonal: index 0 unused).
    void assign(std::vector<double> diagonal, std::vector<double> subdiagonal, std::vector<double> superdiagonal) {
        wd_ = std::move(diagonal);
        wl_ = std::move(subdiagonal);
        wu_ = std::move(superdiagonal);
        const std::size_t n = wd_.size();
        k_ = n / 2;
        d_.assign(n, 1.0);
        l_.assign(n, 0.0);
        u_.assign(n, 0.0);
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

    /// The whole chain's factors; false when a pivot is not positive. With `lo` and `hi` (the first and the last
    /// dof whose stuck flag changed since the last factor): from them towards the twist only (above the twist d_i,
    /// l_i read the dofs up to i, below it those from i on: outside lo..hi nothing they read changed).
    bool factor(const char* stuck, std::size_t lo = 0, std::size_t hi = npos) {
        const std::size_t n = size(), k = k_;
        if (n == 0) return true;
        bool definite = true;
        std::size_t a = std::min(lo, k), b = std::max(std::min(hi, n - 1), k);  // a up to the twist, b down to it
        for (; a < k && b > k; ++a, --b) {  // the halves interleaved
            definite = factor_above(a, stuck) && definite;
            definite = factor_below(b, stuck) && definite;
        }
        for (; a < k; ++a) definite = factor_above(a, stuck) && definite;
        for (; b > k; --b) definite = factor_below(b, stuck) && definite;
        return factor_twist(stuck) && definite;
    }
    /// y = L^-1 r over the whole chain (a stuck dof's r_i is 0); with `lo` and `hi` (the first and the last dof
    /// where r or the factors changed since the last forward): from them towards the twist only, as factor().
    void forward(const double* r, std::size_t lo = 0, std::size_t hi = npos) {
        const std::size_t n = size(), k = k_;
        if (n == 0) return;
        double* y = y_.data();
        const double *l = l_.data(), *u = u_.data();
        std::size_t a = std::min(lo, k), b = std::max(std::min(hi, n - 1), k);
        // each half's last value carried in a register (a store to y could alias what the other half reads next)
        double above = 0.0, below = 0.0;
        if (a < k) {
            y[a] = above = a == 0 ? r[0] : r[a] - l[a] * y[a - 1];
            ++a;
        }
        if (b > k) {
            y[b] = below = b == n - 1 ? r[n - 1] : r[b] - u[b] * y[b + 1];
            --b;
        }
        for (; a < k && b > k; ++a, --b) {  // two independent recurrences per pass
            above = r[a] - l[a] * above;
            below = r[b] - u[b] * below;
            y[a] = above;
            y[b] = below;
        }
        for (; a < k; ++a) y[a] = above = r[a] - l[a] * above;  // the longer half's rest
        for (; b > k; --b) y[b] = below = r[b] - u[b] * below;
        y[k] = twist_forward(r);
    }
    /// x = the solution, from the twist outwards.
    void backward(double* x) const {
        const std::size_t n = size(), k = k_;
        if (n == 0) return;
        const double *y = y_.data(), *l = l_.data(), *u = u_.data(), *d = d_.data();
        double above = y[k] / d[k], below = above;
        x[k] = above;
        std::size_t j = 1;
        for (; j <= k && k + j < n; ++j) {  // two independent recurrences per pass
            above = y[k - j] / d[k - j] - l[k - j + 1] * above;
            below = y[k + j] / d[k + j] - u[k + j - 1] * below;
            x[k - j] = above;
            x[k + j] = below;
        }
        for (; j <= k; ++j) x[k - j] = above = y[k - j] / d[k - j] - l[k - j + 1] * above;  // the longer half
    }

    /// After the dofs `switched` (increasing) changed between stuck and free: the factors, and x for the right-hand
    /// side r (changed at the switched dofs only), updated; `changed` receives the spans (increasing) where x may
    /// have changed. False when a pivot is not positive.
    bool update(const std::vector<std::size_t>& switched, const char* stuck, const double* r, double* x,
                std::vector<DofSpan>& changed) {
        const std::size_t n = size(), k = k_;
        if (n == 0) return true;
        bool definite = true;
        const bool twist_switched = std::binary_search(switched.begin(), switched.end(), k);
        // The factors. Above the twist d_i, l_i read stuck_i, stuck_{i-1} and d_{i-1}; below it, stuck_{i+1} and
        // d_{i+1}: a half in its own coordinate j (0 at its end, increasing towards the twist) is the same
        // recurrence. The twist reads both halves' neighbours.
        bool twist_factor = update_factors<true>(switched, stuck, definite);
        twist_factor = update_factors<false>(switched, stuck, definite) || twist_factor || twist_switched;
        bool twist_links = false;  // l_k or u_k changed: x next to the twist reads them
        if (twist_factor) {
            const double dk = d_[k], lk = l_[k], uk = u_[k];
            definite = factor_twist(stuck) && definite;
            twist_links = !same_bits(lk, l_[k]) || !same_bits(uk, u_[k]);
            twist_factor = twist_links || !same_bits(dk, d_[k]);
        }
        // y: a half's y_i reads r_i, its link and its neighbour's y; y_k reads r_k, l_k, u_k, y_{k-1}, y_{k+1}
        bool twist_y = update_eliminated<true>(switched, r);
        twist_y = update_eliminated<false>(switched, r) || twist_y || twist_factor || twist_switched;
        bool twist_x = false;
        if (twist_y) {
            const double old_x = x[k];
            y_[k] = twist_forward(r);
            x[k] = y_[k] / d_[k];
            twist_x = !same_bits(old_x, x[k]);
        }
        // x: a half's x_i reads y_i, d_i, the link of its neighbour towards the twist and that neighbour's x
        changed.clear();
        update_solution<true>(twist_x || twist_links, x, changed);
        if (twist_x) add_span(changed, DofSpan{k, k});
        update_solution<false>(twist_x || twist_links, x, changed);
        return definite;
    }

private:
    /// One side of the twist in its own coordinate j: 0 at the chain's end, length - 1 next to the twist.
    struct Half {
        std::size_t length = 0;
        std::vector<DofSpan> sources, factored, eliminated, solved;
    };
    template <bool Above>
    Half& half() {
        return halves_[Above ? 0 : 1];
    }
    /// Dof of j in the half's coordinate, and back (the same map).
    template <bool Above>
    std::size_t mirror(std::size_t j) const {
        return Above ? j : size() - 1 - j;
    }
    /// The switched dofs of a half (not the twist), in its coordinate, increasing.
    template <bool Above, class Each>
    void each_switched(const std::vector<std::size_t>& switched, Each&& each) const {
        const std::size_t count = switched.size(), k = k_;
        for (std::size_t m = 0; m < count; ++m) {
            const std::size_t s = switched[Above ? m : count - 1 - m];
            if (Above ? s < k : s > k) each(mirror<Above>(s));
        }
    }
    /// The half's factors from its switched dofs; whether the one next to the twist changed or the twist reads a
    /// switched stuck flag.
    template <bool Above>
    bool update_factors(const std::vector<std::size_t>& switched, const char* stuck, bool& definite) {
        Half& h = half<Above>();
        h.length = Above ? k_ : size() - 1 - k_;
        h.sources.clear();
        bool twist = false;
        each_switched<Above>(switched, [&](std::size_t j) {  // d_j, l_j and d_{j+1}, l_{j+1} read stuck_j
            h.sources.push_back(DofSpan{j, std::min(j + 1, h.length - 1)});
            twist = twist || j + 1 == h.length;
        });
        const bool at_end = sweep_down(h, [&](std::size_t j) {
            const std::size_t i = mirror<Above>(j);
            double* link = Above ? l_.data() : u_.data();
            const double d = d_[i], m = link[i];
            definite = (Above ? factor_above(i, stuck) : factor_below(i, stuck)) && definite;
            return !same_bits(d, d_[i]) || !same_bits(m, link[i]);
        }, h.factored);
        return twist || at_end;
    }
    /// The half's y from its switched dofs and changed factors; whether the one next to the twist changed.
    template <bool Above>
    bool update_eliminated(const std::vector<std::size_t>& switched, const double* r) {
        Half& h = half<Above>();
        spans_.clear();
        each_switched<Above>(switched, [&](std::size_t j) { spans_.push_back(DofSpan{j, j}); });
        merge(spans_, h.factored, 0, h.sources);
        double* y = y_.data();
        const double* link = Above ? l_.data() : u_.data();
        return sweep_down(h, [&](std::size_t j) {
            const std::size_t i = mirror<Above>(j);
            const double old = y[i];
            y[i] = j == 0 ? r[i] : r[i] - link[i] * y[Above ? i - 1 : i + 1];
            return !same_bits(old, y[i]);
        }, h.eliminated);
    }
    /// The half's x from its changed y and factors (and from the twist when `from_twist`); appends the spans run
    /// to `changed` (increasing).
    template <bool Above>
    void update_solution(bool from_twist, double* x, std::vector<DofSpan>& changed) {
        Half& h = half<Above>();
        merge(h.eliminated, h.factored, 1, h.sources);
        if (from_twist && h.length > 0) {
            const std::size_t last = h.length - 1;
            if (!h.sources.empty() && h.sources.back().hi + 1 >= last)
                h.sources.back().hi = last;
            else
                h.sources.push_back(DofSpan{last, last});
        }
        const double *y = y_.data(), *d = d_.data(), *link = Above ? l_.data() : u_.data();
        sweep_up(h, [&](std::size_t j) {
            const std::size_t i = mirror<Above>(j), toward = Above ? i + 1 : i - 1;
            const double old = x[i];
            x[i] = y[i] / d[i] - link[toward] * x[toward];
            return !same_bits(old, x[i]);
        }, h.solved);
        if (Above) {
            for (const DofSpan& span : h.solved) add_span(changed, span);
        } else {
            for (std::size_t m = h.solved.size(); m-- > 0;)
                add_span(changed, DofSpan{mirror<Above>(h.solved[m].hi), mirror<Above>(h.solved[m].lo)});
        }
    }

    bool factor_above(std::size_t i, const char* stuck) {
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
    bool factor_below(std::size_t i, const char* stuck) {
        if (stuck[i]) {
            d_[i] = 1.0;
            u_[i] = 0.0;
            return true;
        }
        if (i + 1 == size() || stuck[i + 1]) {
            u_[i] = 0.0;
            d_[i] = wd_[i];
        } else {
            const double ui = wl_[i + 1] / d_[i + 1];
            d_[i] = wd_[i] - ui * wl_[i + 1];
            u_[i] = ui;
        }
        return d_[i] > 0.0;
    }
    /// The twist's pivot: W(k, k) less both halves' eliminations (l_k = W(k, k-1) / d_{k-1}, u_k likewise).
    bool factor_twist(const char* stuck) {
        const std::size_t k = k_;
        if (stuck[k]) {
            d_[k] = 1.0;
            l_[k] = u_[k] = 0.0;
            return true;
        }
        l_[k] = k == 0 || stuck[k - 1] ? 0.0 : wl_[k] / d_[k - 1];
        u_[k] = k + 1 == size() || stuck[k + 1] ? 0.0 : wl_[k + 1] / d_[k + 1];
        d_[k] = (wd_[k] - l_[k] * (k == 0 ? 0.0 : wl_[k])) - u_[k] * (k + 1 == size() ? 0.0 : wl_[k + 1]);
        return d_[k] > 0.0;
    }
    double twist_forward(const double* r) const {
        const std::size_t k = k_;
        return (r[k] - (k == 0 ? 0.0 : l_[k] * y_[k - 1])) - (k + 1 == size() ? 0.0 : u_[k] * y_[k + 1]);
    }
    static bool same_bits(double a, double b) {
        std::uint64_t ua, ub;
        std::memcpy(&ua, &a, sizeof a);
        std::memcpy(&ub, &b, sizeof b);
        return ua == ub;
    }
    /// Appends a span to increasing disjoint spans, joining it to the last where they touch.
    static void add_span(std::vector<DofSpan>& spans, DofSpan s) {
        if (!spans.empty() && s.lo <= spans.back().hi + 1)
            spans.back().hi = std::max(spans.back().hi, s.hi);
        else
            spans.push_back(s);
    }

    /// Runs update(j) (true: its value changed) towards the twist from each of the half's source spans until past
    /// the span a value comes out unchanged; spans reached on the way join. `out`: the spans run. Returns whether
    /// the value next to the twist changed.
    template <class Update>
    static bool sweep_down(const Half& half, Update&& update, std::vector<DofSpan>& out) {
        out.clear();
        const std::vector<DofSpan>& sources = half.sources;
        const std::size_t n = half.length, count = sources.size();
        bool at_end = false;
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t lo = sources[k].lo;
            std::size_t hi = sources[k].hi, i = lo;
            std::size_t next = k + 1 < count ? sources[k + 1].lo : n;  // the next source's start
            for (;;) {
                const bool changed = update(i);
                if (i + 1 == n) at_end = changed;
                if ((i >= hi && !changed) || i + 1 == n) break;
                if (++i == next) {  // reached: it joins
                    hi = std::max(hi, sources[++k].hi);
                    next = k + 1 < count ? sources[k + 1].lo : n;
                }
            }
            out.push_back(DofSpan{lo, i});
        }
        return at_end;
    }
    /// The same away from the twist (x_j from x_{j+1}); `out` increasing.
    template <class Update>
    static void sweep_up(const Half& half, Update&& update, std::vector<DofSpan>& out) {
        out.clear();
        const std::vector<DofSpan>& sources = half.sources;
        const std::size_t none = half.length;
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
            add_span(out, next);
        }
    }

    std::vector<double> wd_, wl_, wu_, d_, l_, u_, y_;
    std::size_t k_ = 0;  // the twist
    Half halves_[2];  // above and below the twist
    std::vector<DofSpan> spans_;
};

}  // namespace frictionsim::detail
