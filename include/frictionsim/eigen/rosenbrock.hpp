// Header-only RODAS4: the stiffly accurate, L-stable Rosenbrock method of order 4 with an embedded order-3 error
// estimate and an order-3 dense output, on Eigen (Hairer & Wanner, Solving ODEs II, 2nd ed. 1996, sec. IV.7 and
// VI.4 "RODAS"; the coefficients are those of the transformed form of their code RODAS, coefficient set METH = 1
// of its routine RODCOE, typed from it). For stiff rigs and field-scale strings where CVODE's BDF is the
// alternative: one LU of 1/(h gamma) I - J per step and no Newton iteration, so the cost of a step is fixed, and
// a one-step method carries no history across the restart at a switch. Measured (GCC 12 -O2, one run each): the
// axial rig with LuGre bristles (Canudas de Wit 1995, 20 s, rtol 1e-8) 0.96 ms against CVODE BDF's 2.9 ms and
// Dormand-Prince's 17 ms; a damped spring chain of 1000-4000 states (band 3/3) on a par with CVODE's band solver.
//
// Linear algebra: fixed-size systems (the lab rigs) use Eigen fixed-size vectors and a dense PartialPivLU, with
// no heap use in a step; systems sized at run time use Eigen dynamic storage, and those that declare
// jacobian_bandwidths() a banded LU (banded_lu.hpp: 4x faster than Eigen::SparseLU on a string's Jacobian).
// SolverOptions::linear_solver picks dense or band explicitly; sparse (KLU) is CVODE's only.
//
// Jacobian: the system's own when it has one (jacobian() or jacobian_entries(), solve/jacobian.hpp), else
// forward differences, within the band with Curtis-Powell-Reid column groups (lower + upper + 1 right-hand sides,
// not n). df/dt by a forward difference, skipped for a system that declares `static constexpr bool autonomous =
// true`. RODAS4 is a Rosenbrock method, not a W-method: its order needs the exact Jacobian at the step's start,
// so J is evaluated once per step and reused only when a rejected step is retried from the same point. A system's
// quadrature rows (quadrature_offset(), solve/jacobian.hpp: work integrals that read every node) are left out of J
// and their block B = df_q/dx is applied to each stage instead: with no column reading them, the stage matrix is
// [[I/(h gamma) - A, 0], [-B, I/(h gamma)]], so k_q = h gamma (b_q + B k_x), B k_x one directional difference of the
// right-hand side per stage. Without it the method lost its order (a torque-limited 4-element string at rtol
// 1e-10: 1.16e6 steps, 4176 with it; Dormand-Prince 1478).
//
// The step loop, the restart and the root location are Dormand-Prince's (solve/adaptive_stepper.hpp): this header
// is the tableau, the linear algebra, the dense output and the step-size rule; a singular iteration matrix
// refuses the step, which is halved (RODAS's rule).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/LU>

#include "../error.hpp"
#include "banded_lu.hpp"
#include "difference_jacobian.hpp"
#include "../solve/adaptive_stepper.hpp"
#include "../solve/hybrid_system.hpp"
#include "../solve/jacobian.hpp"
#include "../solve/options.hpp"
#include "../solve/result.hpp"
#include "../solve/root_location.hpp"
#include "../solve/step_control.hpp"
#include "../solve/system_size.hpp"

namespace frictionsim {

namespace detail {
/// Does S declare `static constexpr bool autonomous = true` (no explicit time dependence: df/dt = 0)?
template <class S, class = void>
struct declares_autonomous : std::false_type {};
template <class S>
struct declares_autonomous<S, std::void_t<decltype(S::autonomous)>> : std::bool_constant<S::autonomous> {};

/// Eigen's dimension for a system's vectors: the state count for fixed-size systems small enough for the stack
/// (Eigen refuses fixed-size objects over 128 kB: a 32 x 32 matrix is 8 kB), else Eigen::Dynamic.
template <class S>
constexpr int eigen_dimension() {
    if constexpr (has_fixed_size_v<S>) {
        return S::state_size > 0 && S::state_size <= 32 ? static_cast<int>(S::state_size) : Eigen::Dynamic;
    } else {
        return Eigen::Dynamic;
    }
}
}  // namespace detail

template <class System>
class Rodas4 : public detail::AdaptiveStepper<Rodas4<System>, System> {
    using Base = detail::AdaptiveStepper<Rodas4<System>, System>;
    friend Base;

public:
    using Mode = system_mode_t<System>;

    Rodas4(const System& system, const SolverOptions& options) : Base(system, options), n_(state_size_of(system)) {
        const auto idx = static_cast<Eigen::Index>(n_);
        for (Vector* v : {&y_, &y1_, &ytmp_, &f0_, &fs_, &dfdt_, &b_, &k1_, &k2_, &k3_, &k4_, &k5_, &k6_, &rc0_, &rc1_,
                          &rc2_, &rc3_, &work_, &saved_})
            v->setZero(idx);
        banded_ = use_band(options.linear_solver);
        if (banded_) {
            const Bandwidths b = bandwidths_of(system);
            jacobian_band_.resize(n_, b);
            band_lu_.resize(n_, b);
            if constexpr (has_dense_jacobian_v<System> && !has_jacobian_entries_v<System>)
                jacobian_dense_.setZero(idx, idx);  // the system's dense form, copied into the band
        } else {
            jacobian_dense_.setZero(idx, idx);
            iteration_.setZero(idx, idx);
            if constexpr (kDim == Eigen::Dynamic) lu_ = Eigen::PartialPivLU<Matrix>(idx);  // n x n only when used
        }
    }

    /// Dense output of the last step (order 3), valid on [previous_time(), time()].
    void interpolate(double t, double* x) const { interpolate_states(t, 0, n_, x); }

private:
    static constexpr int kDim = detail::eigen_dimension<System>();
    using Vector = Eigen::Matrix<double, kDim, 1>;
    using Matrix = Eigen::Matrix<double, kDim, kDim>;
    using Guards = GuardArray<System>;
    using Base::h_accepted_;
    using Base::h_dense_;
    using Base::mode_;
    using Base::opt_;
    using Base::stats_;
    using Base::sys_;
    using Base::t_;
    using Base::t_prev_;

    static constexpr const char* kName = "Rodas4";
    static constexpr const char* kUnderflow = "step size underflow (discontinuous or non-finite right-hand side)";
    static constexpr int kMaxRefused = 5;  // RODAS's rule: give up after 5 singular matrices in a row
    static constexpr const char* kRefused = "the matrix 1/(h gamma) I - J is singular (or not finite) at every step tried";

    // RODAS (Hairer & Wanner II, sec. VI.4, in the transformed variables of their code): stage i solves
    //   (1/(h gamma) I - J) k_i = f(t + c_i h, y + sum_j a_ij k_j) + sum_j (c_ij / h) k_j + h d_i df/dt,
    // stages 5 and 6 sit at t + h (a_6j = a_5j, a_65 = 1: stiffly accurate), y1 = y + sum a_5j k_j + k5 + k6,
    // and k6 itself is the difference to the embedded order-3 solution: the error estimate.
    static constexpr double gamma = 0.25;
    static constexpr double c2 = 0.386, c3 = 0.21, c4 = 0.63;
    static constexpr double d1 = 0.25, d2 = -0.1043, d3 = 0.1035, d4 = -0.3620000000000023e-01;
    static constexpr double a21 = 0.1544e+01;
    static constexpr double a31 = 0.9466785280815826, a32 = 0.2557011698983284;
    static constexpr double a41 = 0.3314825187068521e+01, a42 = 0.2896124015972201e+01, a43 = 0.9986419139977817;
    static constexpr double a51 = 0.1221224509226641e+01, a52 = 0.6019134481288629e+01,
                            a53 = 0.1253708332932087e+02, a54 = -0.6878860361058950;
    static constexpr double c21 = -0.56688e+01;
    static constexpr double c31 = -0.2430093356833875e+01, c32 = -0.2063599157091915;
    static constexpr double c41 = -0.1073529058151375, c42 = -0.9594562251023355e+01, c43 = -0.2047028614809616e+02;
    static constexpr double c51 = 0.7496443313967647e+01, c52 = -0.1024680431464352e+02,
                            c53 = -0.3399990352819905e+02, c54 = 0.1170890893206160e+02;
    static constexpr double c61 = 0.8083246795921522e+01, c62 = -0.7981132988064893e+01,
                            c63 = -0.3152159432874371e+02, c64 = 0.1631930543123136e+02,
                            c65 = -0.6058818238834054e+01;
    // Dense output (Hairer & Wanner II, sec. IV.7, "dense output" of RODAS):
    //   y(t + s h) = (1 - s) y0 + s (y1 + (1 - s) (q1 + s q2)),  q1 = sum d2j k_j,  q2 = sum d3j k_j.
    static constexpr double e21 = 0.1012623508344586e+02, e22 = -0.7487995877610167e+01,
                            e23 = -0.3480091861555747e+02, e24 = -0.7992771707568823e+01,
                            e25 = 0.1025137723295662e+01;
    static constexpr double e31 = -0.6762803392801253, e32 = 0.6087714651680015e+01, e33 = 0.1643084320892478e+02,
                            e34 = 0.2476722511418386e+02, e35 = -0.6594389125716872e+01;
    // Step-size control of RODAS: h_new / h in [0.2, 6], safety 0.9, Gustafsson's predictive controller.
    static constexpr double kSafety = 0.9, kFacMaxInv = 5.0, kFacMinInv = 1.0 / 6.0;

    bool use_band(LinearSolver requested) const {
        const Bandwidths b = bandwidths_of(sys_);
        switch (requested) {
            case LinearSolver::dense: return false;
            case LinearSolver::band: return true;
            case LinearSolver::sparse:
                throw InvalidParameter("linear_solver",
                                       "SolverOptions: linear_solver must be dense, band or automatic with the "
                                       "Rosenbrock method (got sparse: KLU is CVODE's)");
            case LinearSolver::automatic: break;
        }
        // a band pays when its LU's working width (2 lower + upper + 1) is well under n
        return declares_bandwidths_v<System> && kDim == Eigen::Dynamic && 2 * (2 * b.lower + b.upper + 1) <= n_;
    }

    void rhs(double t, const Vector& x, Vector& dxdt) {
        sys_.rhs(t, x.data(), mode_, dxdt.data());
        ++stats_.rhs_evaluations;
    }
    double scale(std::size_t i, double a, double b) const { return detail::error_scale(opt_, i, a, b); }
    static double step_factor(double err) {  // h_new = h / step_factor(err)
        return std::max(kFacMinInv, std::min(kFacMaxInv, std::pow(err, 0.25) / kSafety));
    }

    // J = df/dx at (t_, y_), and df/dt unless the system is autonomous.
    void evaluate_jacobian(double h) {
        ++stats_.jacobian_evaluations;
        const auto f = [this](double t, const double* x, double* dxdt) {
            sys_.rhs(t, x, mode_, dxdt);
            ++stats_.rhs_evaluations;
        };
        if (banded_) {
            jacobian_band_.set_zero();
            if constexpr (has_jacobian_entries_v<System>) {
                sys_.jacobian_entries(t_, y_.data(), mode_, [this](std::size_t i, std::size_t j, double v) {
                    if (!jacobian_band_.contains(i, j)) outside_band(i, j);
                    jacobian_band_(i, j) += v;
                });
            } else if constexpr (has_dense_jacobian_v<System>) {
                jacobian_dense_.setZero();
                sys_.jacobian(t_, y_.data(), mode_, jacobian_dense_.data());
                for (std::size_t j = 0; j < n_; ++j)
                    for (std::size_t i = 0; i < n_; ++i) {
                        const double v = jacobian_dense_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
                        if (v == 0.0) continue;
                        if (!jacobian_band_.contains(i, j)) outside_band(i, j);
                        jacobian_band_(i, j) = v;
                    }
            } else {
                ytmp_ = y_;
                difference_jacobian_banded(f, t_, ytmp_.data(), f0_.data(), jacobian_band_, work_.data(),
                                           saved_.data());
            }
        } else {
            jacobian_dense_.setZero();
            if constexpr (has_dense_jacobian_v<System>) {
                sys_.jacobian(t_, y_.data(), mode_, jacobian_dense_.data());
            } else if constexpr (has_jacobian_entries_v<System>) {
                sys_.jacobian_entries(t_, y_.data(), mode_, [this](std::size_t i, std::size_t j, double v) {
                    jacobian_dense_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) += v;
                });
            } else {
                ytmp_ = y_;
                difference_jacobian_dense(f, t_, ytmp_.data(), f0_.data(), n_, jacobian_dense_.data(), work_.data());
            }
        }
        if constexpr (has_quadrature_rows_v<System>) drop_quadrature_rows();
        if constexpr (detail::declares_autonomous<System>::value) {
            (void)h;
            dfdt_.setZero();
        } else {
            // forward difference in t over a step small against both t and the step about to be taken
            const double dt = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(t_), std::abs(h));
            const double t1 = t_ + dt;
            rhs(t1, y_, fs_);
            dfdt_ = (fs_ - f0_) / (t1 - t_);
        }
        jacobian_current_ = true;
    }

    // The quadrature rows of J zeroed (a difference Jacobian fills them: within the band, aliased by the column
    // groups), so that solve() applies their block exactly once.
    void drop_quadrature_rows() {
        const std::size_t q = quadrature_rows_begin();
        if (!banded_) {
            jacobian_dense_.bottomRows(static_cast<Eigen::Index>(n_ - q)).setZero();
            return;
        }
        const Bandwidths b = bandwidths_of(sys_);
        for (std::size_t i = q; i < n_; ++i)
            for (std::size_t j = i > b.lower ? i - b.lower : 0; j < n_ && j <= i + b.upper; ++j)
                jacobian_band_(i, j) = 0.0;
    }
    std::size_t quadrature_rows_begin() const {
        const std::size_t q = sys_.quadrature_offset();
        if (q > n_) throw std::logic_error("quadrature_offset() lies past the last state");
        return q;
    }

    [[noreturn]] void outside_band(std::size_t i, std::size_t j) const {
        const Bandwidths b = bandwidths_of(sys_);
        std::ostringstream msg;
        msg << "the Jacobian has an entry at (" << i << ", " << j << "), outside jacobian_bandwidths() (lower "
            << b.lower << ", upper " << b.upper << ")";
        throw std::logic_error(msg.str());
    }

    // Before each trial: J at the step's start (once: a retry from the same point reuses it), then the LU of
    // 1/(h gamma) I - J; false when it is singular or not finite.
    bool prepare(double h) {
        if (!jacobian_current_) evaluate_jacobian(h);
        return factorize(h);
    }
    bool factorize(double h) {
        const double alpha = 1.0 / (h * gamma);
        h_gamma_ = h * gamma;
        if (banded_) return band_lu_.factorize(alpha, -1.0, jacobian_band_);
        iteration_ = -jacobian_dense_;
        iteration_.diagonal().array() += alpha;
        lu_.compute(iteration_);
        const auto pivots = lu_.matrixLU().diagonal();
        return pivots.allFinite() && (pivots.array() != 0.0).all();
    }
    void solve(Vector& k) {  // k = (1/(h gamma) I - J)^-1 b_
        if (banded_) {
            k = b_;
            band_lu_.solve(k.data());
        } else {
            k = lu_.solve(b_);
        }
        if constexpr (has_quadrature_rows_v<System>) add_quadrature_block(k);
    }
    // k_q += h gamma B k_x (see the header comment), B k_x = (f_q(t, y + e k_x) - f_q(t, y)) / e, with f0_ = f(t, y)
    // and e sized so that e k_x is sqrt(machine epsilon) of y.
    void add_quadrature_block(Vector& k) {
        const std::size_t q = quadrature_rows_begin();
        double k_max = 0.0, y_max = 1.0;
        for (std::size_t i = 0; i < q; ++i) {
            k_max = std::max(k_max, std::abs(k[static_cast<Eigen::Index>(i)]));
            y_max = std::max(y_max, std::abs(y_[static_cast<Eigen::Index>(i)]));
        }
        if (q == n_ || !(k_max > 0.0) || !std::isfinite(k_max)) return;
        const double e = std::sqrt(std::numeric_limits<double>::epsilon()) * y_max / k_max;
        if (!std::isfinite(e)) return;  // k_x below what a difference can resolve: its product is nil
        work_ = y_;
        for (std::size_t i = 0; i < q; ++i) work_[static_cast<Eigen::Index>(i)] += e * k[static_cast<Eigen::Index>(i)];
        rhs(t_, work_, saved_);
        for (std::size_t i = q; i < n_; ++i) {
            const auto r = static_cast<Eigen::Index>(i);
            k[r] += h_gamma_ * (saved_[r] - f0_[r]) / e;
        }
    }

    double initial_step(double t_stop) {
        return detail::starting_step(n_, 3, opt_, t_, t_stop, y_.data(), f0_.data(), ytmp_.data(), fs_.data(),
                                     [this](double t, const double* x, double* dxdt) {
                                         sys_.rhs(t, x, mode_, dxdt);
                                         ++stats_.rhs_evaluations;
                                     });
    }

    // One trial step of size h from (t_, y_) with the factored matrix: fills k1..k6 and y1_, returns the scaled
    // RMS norm of the error estimate k6 (infinity when it is not finite).
    double attempt(double h) {
        const double inv_h = 1.0 / h;
        b_ = f0_ + (h * d1) * dfdt_;
        solve(k1_);
        ytmp_ = y_ + a21 * k1_;
        rhs(t_ + c2 * h, ytmp_, fs_);
        b_ = fs_ + (inv_h * c21) * k1_ + (h * d2) * dfdt_;
        solve(k2_);
        ytmp_ = y_ + a31 * k1_ + a32 * k2_;
        rhs(t_ + c3 * h, ytmp_, fs_);
        b_ = fs_ + inv_h * (c31 * k1_ + c32 * k2_) + (h * d3) * dfdt_;
        solve(k3_);
        ytmp_ = y_ + a41 * k1_ + a42 * k2_ + a43 * k3_;
        rhs(t_ + c4 * h, ytmp_, fs_);
        b_ = fs_ + inv_h * (c41 * k1_ + c42 * k2_ + c43 * k3_) + (h * d4) * dfdt_;
        solve(k4_);
        ytmp_ = y_ + a51 * k1_ + a52 * k2_ + a53 * k3_ + a54 * k4_;
        rhs(t_ + h, ytmp_, fs_);
        b_ = fs_ + inv_h * (c51 * k1_ + c52 * k2_ + c53 * k3_ + c54 * k4_);
        solve(k5_);
        ytmp_ += k5_;  // the embedded order-3 solution
        rhs(t_ + h, ytmp_, fs_);
        b_ = fs_ + inv_h * (c61 * k1_ + c62 * k2_ + c63 * k3_ + c64 * k4_ + c65 * k5_);
        solve(k6_);
        y1_ = ytmp_ + k6_;
        double err = 0.0;
        for (std::size_t i = 0; i < n_; ++i) {
            const auto k = static_cast<Eigen::Index>(i);
            const double r = k6_[k] / scale(i, y_[k], y1_[k]);
            err += r * r;
        }
        err = std::sqrt(err / static_cast<double>(std::max<std::size_t>(n_, 1)));
        return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
    }

    // The hooks of the step driver (adaptive_stepper.hpp).
    double* y() { return y_.data(); }
    const double* y() const { return y_.data(); }
    double* scratch() { return ytmp_.data(); }
    void load(const double* x) { std::copy(x, x + n_, y_.data()); }
    void slope() {  // f0 at (t_, y_); J is due
        rhs(t_, y_, f0_);
        f0_current_ = true;
        jacobian_current_ = false;
    }
    void begin_step() {  // f0 is evaluated lazily: a step cut back to a root is usually followed by a restart
        if (!f0_current_) {
            rhs(t_, y_, f0_);
            f0_current_ = true;
        }
    }
    void reset_controller() { controller_primed_ = false; }
    double rejected_step(double h, double err) const { return h / step_factor(err); }

    void fit_dense_output(double) {
        rc0_ = y_;
        rc1_ = y1_;
        rc2_ = e21 * k1_ + e22 * k2_ + e23 * k3_ + e24 * k4_ + e25 * k5_;
        rc3_ = e31 * k1_ + e32 * k2_ + e33 * k3_ + e34 * k4_ + e35 * k5_;
    }
    double next_step(double h, double err) {
        double fac = step_factor(err);
        if (controller_primed_) {  // Gustafsson: also predict from the last two accepted errors
            const double predicted = (h_accepted_ / h) * std::pow(err * err / err_accepted_, 0.25) / kSafety;
            fac = std::max(fac, std::max(kFacMinInv, std::min(kFacMaxInv, predicted)));
        }
        controller_primed_ = true;
        err_accepted_ = std::max(0.01, err);
        return h / fac;
    }
    void advance() {
        y_ = y1_;
        f0_current_ = false;
        jacobian_current_ = false;
    }

    void euler_step(double h) {
        if (!f0_current_) rhs(t_, y_, f0_);
        rc0_ = y_;
        rc1_ = y_ + h * f0_;
        rc2_.setZero();
        rc3_.setZero();
        y_ = rc1_;
    }

    void interpolate_states(double t, std::size_t first, std::size_t last, double* x) const {
        const double s = (t - t_prev_) / h_dense_, s1 = 1.0 - s;
        for (std::size_t i = first; i < last; ++i) {
            const auto k = static_cast<Eigen::Index>(i);
            x[i] = rc0_[k] * s1 + s * (rc1_[k] + s1 * (rc2_[k] + s * rc3_[k]));
        }
    }

    std::size_t n_ = 0;
    double h_gamma_ = 0.0;  ///< h gamma of the factored matrix
    bool banded_ = false;
    double err_accepted_ = 1.0;  ///< the last accepted step's error, for the predictive controller
    bool controller_primed_ = false, f0_current_ = false, jacobian_current_ = false;
    Vector y_, y1_, ytmp_, f0_, fs_, dfdt_, b_, k1_, k2_, k3_, k4_, k5_, k6_;
    Vector rc0_, rc1_, rc2_, rc3_;  ///< dense output of the last step
    Vector work_, saved_;           ///< difference Jacobian's work space (and the quadrature block's)
    Matrix jacobian_dense_, iteration_;
    Eigen::PartialPivLU<Matrix> lu_;
    BandMatrix jacobian_band_;
    BandedLU band_lu_;
};

}  // namespace frictionsim
