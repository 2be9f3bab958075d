// Root location of the switching functions on an integrator's dense output, shared by the one-step methods
// (Dormand-Prince, RODAS4): after each accepted step the guards are checked at kScanPoints points of the step (the
// end included), so that a guard that crosses and comes back within one step is not missed (cf. SciML's
// interp_points), and the earliest crossing is bracketed by Illinois false position to CVODE's ttol.
// Masking (CVODE's rule): a guard exactly zero at a restart does not count until it has moved off zero.
//
// Local guards (issue 22, item 3): a system sized at run time with many guards, each reading a few states (a
// string's wall contacts), may declare
//   GuardReads guard_reads(std::size_t i) const                     the states guard i reads, [first, last)
//   double guard(std::size_t i, double t, const double* x, mode) const   guard i alone, equal bit for bit to
//                                                                     guards()[i] (x holds at least those states)
// Then the bracketing evaluates only the guard it brackets, on the dense output of only the states it reads:
// a located switch costs what its guard reads, not a sweep over the whole system per iteration (the crossings
// bracketed and the roots found are the same).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include "../detail/illinois.hpp"
#include "hybrid_system.hpp"
#include "system_size.hpp"

namespace frictionsim {

/// The states a guard reads: indices [first, last).
struct GuardReads {
    std::size_t first = 0, last = 0;
};

namespace detail {

/// Does S evaluate one guard alone (guard_reads and guard, above)?
template <class S, class = void>
struct has_local_guards : std::false_type {};
template <class S>
struct has_local_guards<
    S, std::void_t<decltype(GuardReads{std::declval<const S&>().guard_reads(std::size_t{})}),
                   decltype(double{std::declval<const S&>().guard(std::size_t{}, 0.0, std::declval<const double*>(),
                                                                  std::declval<const system_mode_t<S>&>())})>>
    : std::true_type {};
template <class S>
inline constexpr bool has_local_guards_v = has_local_guards<S>::value;

template <class System>
class RootLocator {
public:
    using Guards = GuardArray<System>;
    using Mode = system_mode_t<System>;
    /// Points per step (the end included) at which the guards are checked on the dense output.
    static constexpr int kScanPoints = 4;

    explicit RootLocator(const System& system)
        : sys_(system), count_(guard_count_of(system)), g_(make_guard_array(system)),
          reference_(make_guard_array(system)), g_lo_(make_guard_array(system)), g_k_(make_guard_array(system)),
          g_scratch_(make_guard_array(system)), masked_(make_guard_array<System, bool>(system)), roots_(make_guard_array<System, int>(system)) {}

    /// The guards at the last accepted point; an integrator's restart fills them, then calls restarted().
    Guards& values() { return g_; }
    void restarted() {
        for (std::size_t i = 0; i < count(); ++i) masked_[i] = g_[i] == 0.0;
        std::fill(roots_.begin(), roots_.end(), 0);
    }
    /// After a root: +1 / -1 per guard that crossed, else 0.
    const int* roots() const { return roots_.data(); }

    /// The values the crossings of this step are judged against, from the guards g_end at the step's end.
    void set_references(const Mode& mode, const Guards& g_end) {
        for (std::size_t i = 0; i < count(); ++i) reference_[i] = reference_value(i, g_end[i], mode);
    }
    /// Has any guard crossed from its reference to `g` (set_references first)?
    bool crosses(const Mode& mode, const Guards& g) const {
        for (std::size_t i = 0; i < count(); ++i)
            if (crossed(i, reference_[i], g[i], mode) != 0) return true;
        return false;
    }

    /// Scans the step [t_prev, t_end] (guards g_end at its end) for the earliest crossing; `at(t, g)` evaluates the
    /// guards on the dense output. True with t_root set when a guard crossed (bracketed to CVODE's ttol, 100 ulps of
    /// t + h); false after no_root(g_end) when none did.
    template <class GuardsAt>
    bool scan(const Mode& mode, double t_prev, double t_end, const Guards& g_end, GuardsAt&& at, double& t_root) {
        auto one = [&](std::size_t i, double t) {
            at(t, g_scratch_);
            return g_scratch_[i];
        };
        return scan(mode, t_prev, t_end, g_end, at, one, t_root);
    }
    /// scan() with `one(i, t)`, guard i alone on the dense output, for the bracketing (local guards, above).
    template <class GuardsAt, class GuardAt>
    bool scan(const Mode& mode, double t_prev, double t_end, const Guards& g_end, GuardsAt&& at, GuardAt&& one,
              double& t_root) {
        const double tol = 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(t_end) + (t_end - t_prev));
        t_root = t_end;
        double lo = t_prev;
        g_lo_ = reference_;
        bool any = false;
        for (int k = 1; k <= kScanPoints && !any; ++k) {
            const double t_k = k == kScanPoints ? t_end : t_prev + (t_end - t_prev) * k / kScanPoints;
            if (k == kScanPoints) g_k_ = g_end;
            else at(t_k, g_k_);
            for (std::size_t i = 0; i < count(); ++i) {
                if (crossed(i, reference_[i], g_k_[i], mode) == 0) continue;
                any = true;
                t_root = std::min(t_root, bracket(i, mode, lo, t_k, g_lo_[i], g_k_[i], tol, one));
            }
            lo = t_k;
            g_lo_ = g_k_;
        }
        if (!any) no_root(g_end);
        return any;
    }

    /// The step ended without a root: its end's guards become the reference, and guards that left zero unmask.
    void no_root(const Guards& g_end) {
        for (std::size_t i = 0; i < count(); ++i) {
            if (masked_[i] && g_end[i] != 0.0) masked_[i] = false;
            g_[i] = g_end[i];
        }
    }
    /// The step was cut at a root, where the guards are g_root: record every guard that has crossed.
    void mark(const Mode& mode, const Guards& g_root) {
        for (std::size_t i = 0; i < count(); ++i) roots_[i] = crossed(i, reference_[i], g_root[i], mode);
    }

private:
    /// The guard count: a compile-time constant for fixed-size systems (the loops over guards unroll and fold, as
    /// they did inside Dormand-Prince: measured 8 % of the axial rig's step without it), else the run's.
    std::size_t count() const {
        if constexpr (has_fixed_size_v<System>) return System::guard_count;
        else return count_;
    }

    /// Guard i's crossing (+1 rising, -1 falling, 0 none) from `reference` to `value`; a masked guard that has
    /// not left its surface (reference 0) does not cross.
    int crossed(std::size_t i, double reference, double value, const Mode& mode) const {
        if (masked_[i] && reference == 0.0) return 0;
        return crossing(reference, value, sys_.guard_direction(i, mode));
    }

    // The value a crossing of guard i is judged against. A guard masked since a restart (it sat at zero and the
    // hybrid loop's probe found it leaving towards its non-triggering side) counts as just off zero on that
    // side once it has moved: if a step ends with it on the triggering side, it went out and came back within
    // the step, and that return is a switch to locate. Taking its first non-zero value as the reference
    // instead would miss it. Returns 0 while a masked guard has not moved, or has no non-triggering side.
    double reference_value(std::size_t i, double g_now, const Mode& mode) const {
        if (!masked_[i]) return g_[i];
        if (g_now == 0.0) return 0.0;
        const int dir = sys_.guard_direction(i, mode);
        if (dir == 0) return 0.0;  // both sides trigger: the probe would have fired had it moved
        return dir < 0 ? std::numeric_limits<double>::denorm_min() : -std::numeric_limits<double>::denorm_min();
    }

    // Guard i crossed from its reference (not yet at lo, where it is g_lo) to g_hi at hi: Illinois false position
    // on the dense output. Returns the right end of the final bracket, where the guard has already crossed (as
    // CVODE does).
    template <class GuardAt>
    double bracket(std::size_t i, const Mode& mode, double lo, double hi, double g_lo, double g_hi, double tol,
                   GuardAt& one) {
        const int dir = sys_.guard_direction(i, mode);
        IllinoisBracket r{lo, g_lo, hi, g_hi};
        for (int iter = 0; iter < 200 && r.b - r.a > tol; ++iter) {
            const double tm = r.next(0.5 * tol);
            const double g = one(i, tm);
            r.move(tm, g, crossing(reference_[i], g, dir) != 0);
        }
        return r.b;
    }
    const System& sys_;
    std::size_t count_;
    Guards g_, reference_, g_lo_, g_k_, g_scratch_;
    GuardArray<System, bool> masked_;
    GuardArray<System, int> roots_;
};

}  // namespace detail
}  // namespace frictionsim
