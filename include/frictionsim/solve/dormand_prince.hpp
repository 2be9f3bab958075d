// Header-only Dormand-Prince RK5(4) with FSAL, PI step control and 4th-order dense output
// (Hairer, Norsett & Wanner, Solving ODEs I, sec. II.5-6; coefficients of their DOPRI5 code): the tableau and the
// step-size rule; the step loop and the root location on the dense output are adaptive_stepper.hpp's. For rigs
// that are accuracy-limited, not stiff: at tight tolerance CVODE's per-step overhead (Newton, history,
// interpolation) is wasted on them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <type_traits>
#include <utility>

#include "../error.hpp"
#include "adaptive_stepper.hpp"
#include "hybrid_system.hpp"
#include "options.hpp"
#include "result.hpp"
#include "root_location.hpp"
#include "step_control.hpp"
#include "system_size.hpp"

namespace frictionsim {

namespace detail {
/// Does S provide `void rhs_guards(double t, const double* x, int mode, double* dxdt, double* g) const`, the
/// right-hand side and the switching functions from one evaluation (e.g. one cos of the surface motion)?
template <class S, class = void>
struct has_rhs_guards : std::false_type {};
template <class S>
struct has_rhs_guards<S, std::void_t<decltype(std::declval<const S&>().rhs_guards(
                             0.0, std::declval<const double*>(), std::declval<const system_mode_t<S>&>(),
                             std::declval<double*>(), std::declval<double*>()))>>
    : std::true_type {};
}  // namespace detail

// Unroll the per-state loop that follows (completely for N <= 32; the rigs have N = 2-20). GCC's loop
// vectorizer turns these short loops into pair loads of values the right-hand side has just stored one at a time,
// each stalling on store forwarding; unrolled, they are left to the straight-line vectorizer, which pairs only
// values already in registers. Measured on the axial-Dahl run in a plain -O3 program (GCC 12): 1.31 -> 1.04 ms.
// `GCC unroll` exists from GCC 8 and in Clang; elsewhere the loops stay as they are. #undef'd at the end.
#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 8 && !defined(__INTEL_COMPILER))
#define FRICTIONSIM_DETAIL_UNROLL _Pragma("GCC unroll 32")
#else
#define FRICTIONSIM_DETAIL_UNROLL
#endif
// attempt() runs once per step: inlined into the event loop (GCC's choice for some rigs, and it changes with code
// elsewhere in the unit), its stages came out 15 % longer (callgrind on the torsional eq 6 run: 766M against 713M
// instructions). Kept out of line, as it was for the axial rig anyway.
#if defined(__GNUC__) || defined(__clang__)
#define FRICTIONSIM_DETAIL_NOINLINE __attribute__((noinline))
#else
#define FRICTIONSIM_DETAIL_NOINLINE
#endif

// The per-state loops' bound inside DormandPrince: a constant expression for fixed-size systems (so that `GCC
// unroll` applies), the run's state count otherwise. #undef'd at the end.
#define FRICTIONSIM_DETAIL_STATES (kFixed ? kStates : n_)

template <class System>
class DormandPrince : public detail::AdaptiveStepper<DormandPrince<System>, System> {
    using Base = detail::AdaptiveStepper<DormandPrince<System>, System>;
    friend Base;

public:
    using State = StateArray<System>;
    using Guards = GuardArray<System>;
    using Mode = system_mode_t<System>;

    DormandPrince(const System& system, const SolverOptions& options) : Base(system, options), n_(state_size_of(system)) {
        for (State* v : {&y_, &y1_, &ytmp_, &k1_, &k2_, &k3_, &k4_, &k5_, &k6_, &k7_, &rc1_, &rc2_, &rc3_, &rc4_, &rc5_})
            *v = make_state_array(system);
        for (Guards* v : {&stage_g_[0], &stage_g_[1], &stage_g_[2], &stage_g_[3], &end_g_, &g_gap_})
            *v = make_guard_array(system);
    }

    /// Dense output of the last step (Hairer's contd5), valid on [previous_time(), time()].
    void interpolate(double t, double* x) const {
        const double s = (t - t_prev_) / h_dense_, s1 = 1.0 - s;
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i)
            x[i] = rc1_[i] + s * (rc2_[i] + s1 * (rc3_[i] + s * (rc4_[i] + s1 * rc5_[i])));
    }

private:
    using Base::guards;
    using Base::h_dense_;
    using Base::mode_;
    using Base::opt_;
    using Base::roots_;
    using Base::stats_;
    using Base::sys_;
    using Base::t_;
    using Base::t_prev_;

    static constexpr const char* kName = "DormandPrince";
    static constexpr const char* kUnderflow = "step size underflow (stiff, discontinuous or non-finite right-hand side)";

    static constexpr bool kFixed = has_fixed_size_v<System>;
    static constexpr std::size_t kStates = [] {
        if constexpr (has_fixed_size_v<System>) return System::state_size;
        else return std::size_t{0};
    }();
    /// States: a compile-time constant for the lab rigs (the loops below unroll: `GCC unroll` needs the bound as a
    /// constant expression in the loop itself), else the run's size.
    std::size_t n() const { return FRICTIONSIM_DETAIL_STATES; }

    // Dormand-Prince 5(4) tableau.
    /// With rhs_guards, the guards come free with the stages (c = 0.2, 0.3, 0.8, 8/9 and the end, exact there):
    /// those values and one dense-output point in their widest gap (0.3 to 0.8) leave no gap over h/4, as the
    /// uniform scan does, and the full scan runs only when one of them shows a crossing.
    static constexpr bool kStageGuards = !Base::kNoGuards && detail::has_rhs_guards<System>::value;
    static constexpr double kGapPoint = 0.55;
    static constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
    static constexpr double a21 = 1.0 / 5;
    static constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
    static constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
    static constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
    static constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                            a65 = -5103.0 / 18656;
    static constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784,
                            a76 = 11.0 / 84;
    static constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                            e6 = 22.0 / 525, e7 = -1.0 / 40;
    static constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                            d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                            d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
    // PI step-size control (Hairer's defaults: beta 0.04, safety 0.9, factor in [0.2, 10]).
    static constexpr double kBeta = 0.04, kExpo1 = 0.2 - 0.04 * 0.75, kSafety = 0.9;
    static constexpr double kFacMaxInv = 1.0 / 0.2, kFacMinInv = 1.0 / 10.0;
    static constexpr double kLogFacoldMin = -9.210340371976184;  // log(1e-4)

    void rhs(double t, const State& x, State& dxdt) {
        sys_.rhs(t, x.data(), mode_, dxdt.data());
        ++stats_.rhs_evaluations;
    }
    /// A stage: the right-hand side, and with rhs_guards the guards at the stage too (into g).
    void stage(double t, const State& x, State& dxdt, Guards& g) {
        if constexpr (kStageGuards) {
            sys_.rhs_guards(t, x.data(), mode_, dxdt.data(), g.data());
            ++stats_.rhs_evaluations;
        } else {
            (void)g;
            rhs(t, x, dxdt);
        }
    }
    double scale(std::size_t i, double a, double b) const { return detail::error_scale(opt_, i, a, b); }

    // The hooks of the step driver (adaptive_stepper.hpp).
    double* y() { return y_.data(); }
    const double* y() const { return y_.data(); }
    double* scratch() { return ytmp_.data(); }
    void load(const double* x) { std::copy(x, x + n(), y_.begin()); }
    void slope() { rhs(t_, y_, k1_); }  // the first stage (first same as last after an accepted step)
    void reset_controller() { log_facold_ = kLogFacoldMin; }
    void cut_to_root() { slope(); }

    double initial_step(double t_stop) {
        return detail::starting_step(n(), 4, opt_, t_, t_stop, y_.data(), k1_.data(), ytmp_.data(), k2_.data(),
                                     [this](double t, const double* x, double* dxdt) {
                                         sys_.rhs(t, x, mode_, dxdt);
                                         ++stats_.rhs_evaluations;
                                     });
    }

    // One trial step of size h from (t_, y_): fills k2..k7 and y1_, returns the scaled error norm.
    FRICTIONSIM_DETAIL_NOINLINE double attempt(double h) {
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i) ytmp_[i] = y_[i] + h * a21 * k1_[i];
        stage(t_ + c2 * h, ytmp_, k2_, stage_g_[0]);
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i) ytmp_[i] = y_[i] + h * (a31 * k1_[i] + a32 * k2_[i]);
        stage(t_ + c3 * h, ytmp_, k3_, stage_g_[1]);
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i) ytmp_[i] = y_[i] + h * (a41 * k1_[i] + a42 * k2_[i] + a43 * k3_[i]);
        stage(t_ + c4 * h, ytmp_, k4_, stage_g_[2]);
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i)
            ytmp_[i] = y_[i] + h * (a51 * k1_[i] + a52 * k2_[i] + a53 * k3_[i] + a54 * k4_[i]);
        stage(t_ + c5 * h, ytmp_, k5_, stage_g_[3]);
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i)
            ytmp_[i] = y_[i] + h * (a61 * k1_[i] + a62 * k2_[i] + a63 * k3_[i] + a64 * k4_[i] + a65 * k5_[i]);
        rhs(t_ + h, ytmp_, k6_);
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i)
            y1_[i] = y_[i] + h * (a71 * k1_[i] + a73 * k3_[i] + a74 * k4_[i] + a75 * k5_[i] + a76 * k6_[i]);
        stage(t_ + h, y1_, k7_, end_g_);  // with rhs_guards: the guards at the step's end, exactly
        double err = 0.0;
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i) {
            const double e =
                h * (e1 * k1_[i] + e3 * k3_[i] + e4 * k4_[i] + e5 * k5_[i] + e6 * k6_[i] + e7 * k7_[i]);
            const double r = e / scale(i, y_[i], y1_[i]);
            err += r * r;
        }
        err = std::sqrt(err / static_cast<double>(n()));
        return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
    }

    double rejected_step(double h, double err) const {
        return std::isfinite(err) ? h / std::min(kFacMaxInv, std::pow(err, kExpo1) / kSafety) : 0.1 * h;
    }

    void fit_dense_output(double h) {
        FRICTIONSIM_DETAIL_UNROLL
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i) {  // Hairer's rcont1..5
            const double dy = y1_[i] - y_[i], bspl = h * k1_[i] - dy;
            rc1_[i] = y_[i];
            rc2_[i] = dy;
            rc3_[i] = bspl;
            rc4_[i] = dy - h * k7_[i] - bspl;
            rc5_[i] = h * (d1 * k1_[i] + d3 * k3_[i] + d4 * k4_[i] + d5 * k5_[i] + d6 * k6_[i] + d7 * k7_[i]);
        }
    }

    // PI control: err^expo1 / facold^beta as one exp of logs, facold's log kept from the last step (pow is ~10 %
    // of a step on the axial rig otherwise)
    double next_step(double h, double err) {
        const double log_err = std::log(err);
        double fac = std::exp(kExpo1 * log_err - kBeta * log_facold_);
        fac = std::max(kFacMinInv, std::min(kFacMaxInv, fac / kSafety));
        log_facold_ = std::max(log_err, kLogFacoldMin);
        return h / fac;
    }

    void advance() {
        y_ = y1_;
        k1_ = k7_;  // first same as last
    }

    void euler_step(double h) {
        for (std::size_t i = 0; i < FRICTIONSIM_DETAIL_STATES; ++i) {
            y1_[i] = y_[i] + h * k1_[i];
            rc1_[i] = y_[i];
            rc2_[i] = y1_[i] - y_[i];
            rc3_[i] = rc4_[i] = rc5_[i] = 0.0;
        }
        y_ = y1_;
    }

    void interpolate_states(double t, std::size_t first, std::size_t last, double* x) const {
        const double s = (t - t_prev_) / h_dense_, s1 = 1.0 - s;
        for (std::size_t k = first; k < last; ++k)  // interpolate()'s expression
            x[k] = rc1_[k] + s * (rc2_[k] + s1 * (rc3_[k] + s * (rc4_[k] + s1 * rc5_[k])));
    }

    // The guards at the step's end: with rhs_guards, those of the last stage.
    void end_guards(Guards& g) {
        if constexpr (kStageGuards) g = end_g_;
        else guards(t_, y_.data(), g);
    }

    // Any guard crossed from its reference at the step's end, at a stage of the accepted step, or at the dense
    // output in the stages' widest gap? Only then is the full scan worth its guard evaluations.
    bool may_cross(const Guards& g1) {
        if constexpr (!kStageGuards) {
            (void)g1;
            return true;
        } else {
            if (roots_.crosses(mode_, g1)) return true;
            for (const auto& g : stage_g_)
                if (roots_.crosses(mode_, g)) return true;
            const double t_gap = t_prev_ + (t_ - t_prev_) * kGapPoint;
            interpolate(t_gap, ytmp_.data());
            guards(t_gap, ytmp_.data(), g_gap_);
            return roots_.crosses(mode_, g_gap_);
        }
    }

    std::size_t n_ = 0;
    double log_facold_ = kLogFacoldMin;  ///< log of the PI controller's previous error, at least log 1e-4
    std::array<Guards, 4> stage_g_{};    ///< guards at stages 2-5 (rhs_guards systems only)
    Guards end_g_{};                     ///< guards at (t + h, y1)
    State y_{}, y1_{}, ytmp_{}, k1_{}, k2_{}, k3_{}, k4_{}, k5_{}, k6_{}, k7_{};
    State rc1_{}, rc2_{}, rc3_{}, rc4_{}, rc5_{};
    Guards g_gap_{};  ///< guards in the stages' gap (no heap per step)
};

}  // namespace frictionsim

#undef FRICTIONSIM_DETAIL_UNROLL
#undef FRICTIONSIM_DETAIL_NOINLINE
#undef FRICTIONSIM_DETAIL_STATES
