// SUNDIALS CVODE behind the Integrator concept of solve/hybrid_system.hpp: BDF + Newton for stiff contact laws
// (dense, band or KLU sparse linear solver: SolverOptions::linear_solver), Adams + fixed point for smooth rigs.
// This folder is the only place that includes SUNDIALS headers. Builds against SUNDIALS 6.4 (Debian bookworm)
// and 7.x. KLU needs SUNDIALS' sunlinsolklu library: the CMake target frictionsim::sundials links it and defines
// FRICTIONSIM_SUNDIALS_KLU where SUNDIALS has it.
#pragma once

#include <sundials/sundials_config.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#if defined(FRICTIONSIM_SUNDIALS_KLU) && FRICTIONSIM_SUNDIALS_KLU
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#define FRICTIONSIM_DETAIL_KLU 1
#else
#define FRICTIONSIM_DETAIL_KLU 0
#endif
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../error.hpp"
#include "../solve/hybrid_system.hpp"
#include "../solve/jacobian.hpp"
#include "../solve/options.hpp"
#include "../solve/result.hpp"

namespace frictionsim {
namespace detail::cvode {

/// Is KLU (SUNDIALS' sparse direct solver) compiled in?
constexpr bool klu_available = FRICTIONSIM_DETAIL_KLU != 0;

// One deleter per SUNDIALS handle type, so that every handle is owned by a std::unique_ptr.
struct FreeContext { void operator()(SUNContext c) const { SUNContext_Free(&c); } };
struct FreeVector { void operator()(N_Vector v) const { N_VDestroy(v); } };
struct FreeMatrix { void operator()(SUNMatrix a) const { SUNMatDestroy(a); } };
struct FreeLinearSolver { void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); } };
struct FreeNonlinearSolver { void operator()(SUNNonlinearSolver s) const { SUNNonlinSolFree(s); } };
struct FreeMemory { void operator()(void* m) const { CVodeFree(&m); } };

template <class Handle, class Free>
using Owned = std::unique_ptr<std::remove_pointer_t<Handle>, Free>;

inline std::string number(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

/// SUNDIALS reports a failed constructor with a null handle.
template <class P>
P made(P handle, const char* what) {
    if (!handle) throw SimulationError(std::string("CVODE: could not create ") + what, 0.0);
    return handle;
}

}  // namespace detail::cvode

/// CVODE driven one internal step at a time (CV_ONE_STEP with a stop time), restarted exactly at every switch.
/// `system` must outlive the integrator. Movable, not copyable.
template <class System>
class Cvode {
    using Mode = system_mode_t<System>;

public:
    /// Throws InvalidParameter for invalid options or a method that is not a CVODE one.
    Cvode(const System& system, const SolverOptions& options)
        : options_(options), n(state_size_of(system)), m(guard_count_of(system)), x_previous_(n), roots_(m),
          directions_(m) {
        namespace cv = detail::cvode;
        options_.validate(n);
        if (n == 0) detail::reject("Cvode", "state_size", "at least one state", 0.0);
        if (options_.method != Method::cvode_bdf && options_.method != Method::cvode_adams)
            throw InvalidParameter("method", std::string("Cvode: method must be cvode_bdf or cvode_adams (got ") +
                                                 method_name(options_.method) + ")");
        linear_solver_kind_ = resolve_linear_solver<System>(options_.linear_solver);
        if (linear_solver_kind_ == LinearSolver::sparse && !detail::cvode::klu_available)
            throw InvalidParameter("linear_solver",
                                   "SolverOptions: linear_solver = sparse needs SUNDIALS' KLU, which this build does "
                                   "not have (link SUNDIALS::sunlinsolklu and define FRICTIONSIM_SUNDIALS_KLU=1; the "
                                   "CMake target frictionsim::sundials does so when SUNDIALS provides it)");
        SUNContext context = nullptr;
#if SUNDIALS_VERSION_MAJOR >= 7
        if (SUNContext_Create(SUN_COMM_NULL, &context) != 0) throw SimulationError("CVODE: no SUNContext", 0.0);
#else
        if (SUNContext_Create(nullptr, &context) != 0) throw SimulationError("CVODE: no SUNContext", 0.0);
#endif
        context_.reset(context);
        shared_ = std::make_unique<Shared>();
        shared_->system = &system;
        shared_->states = n;
        shared_->guards = m;
#if SUNDIALS_VERSION_MAJOR >= 7
        // Replace the default handler (which prints to stderr) so that the message ends up in our exception.
        SUNContext_ClearErrHandlers(context);
        SUNContext_PushErrHandler(context, &Cvode::on_error, shared_.get());
#endif
        const auto size = static_cast<sunindextype>(n);
        y_.reset(cv::made(N_VNew_Serial(size, context), "the state vector"));
        dky_.reset(cv::made(N_VNewEmpty_Serial(size, context), "the dense-output vector"));
        if (options_.method == Method::cvode_bdf) {
            make_linear_solver(system, context);
        } else {
            nonlinear_solver_.reset(
                cv::made(SUNNonlinSol_FixedPoint(y_.get(), 0, context), "SUNNonlinSol_FixedPoint"));
        }
        memory_.reset(cv::made(CVodeCreate(options_.method == Method::cvode_bdf ? CV_BDF : CV_ADAMS, context),
                               "the CVODE memory"));
#if SUNDIALS_VERSION_MAJOR < 7
        CVodeSetErrHandlerFn(memory_.get(), &Cvode::on_error, shared_.get());
#endif
    }

    /// Exact restart at (t, x) in `mode`: CVODE forgets its history (CVodeInit the first time, CVodeReInit after).
    void restart(double t, const double* x, const Mode& mode) {
        std::copy(x, x + n, N_VGetArrayPointer(y_.get()));
        std::copy(x, x + n, x_previous_.begin());
        shared_->mode = mode;
        if (!initialized_) {
            initialize(t);
        } else {
            if (stepped_) done_ = stats();  // CVodeReInit zeroes CVODE's counters: bank them first
            check(CVodeReInit(memory_.get(), t, y_.get()), "CVodeReInit", t);
        }
        ++done_.restarts;
        if (m > 0) {
            for (std::size_t i = 0; i < m; ++i) directions_[i] = shared_->system->guard_direction(i, mode);
            check(CVodeSetRootDirection(memory_.get(), directions_.data()), "CVodeSetRootDirection", t);
        }
        std::fill(roots_.begin(), roots_.end(), 0);
        t_ = t_previous_ = t;
        stepped_ = tiny_span_ = false;
    }

    /// One internal CVODE step, cut at t_stop and at the first root of a guard. Throws SimulationError when
    /// CVODE fails (the message names the cause) or when max_steps is used up.
    StepResult step(double t_stop) {
        if (!initialized_) throw std::logic_error("Cvode::step: call restart() first");
        if (!(t_stop > t_))
            throw std::invalid_argument("Cvode::step: t_stop = " + detail::cvode::number(t_stop) +
                                        " must lie after time() = " + detail::cvode::number(t_));
        void* memory = memory_.get();
        // CVODE's own max_steps counts per CVode call, and each call here is a single step: count the run here.
        if (total_steps() >= options_.max_steps)
            throw SimulationError("CVODE: max_steps = " + std::to_string(options_.max_steps) +
                                      " internal steps used up at t = " + detail::cvode::number(t_) +
                                      " (raise SolverOptions::max_steps)",
                                  t_);
        // After a root CVODE stands at the end of the step that found it; a stop time before that is refused.
        sunrealtype t_internal = t_;
        CVodeGetCurrentTime(memory, &t_internal);
        if (stepped_ && t_stop < t_internal)
            throw std::logic_error("Cvode::step: after a root, restart() before stepping to t_stop = " +
                                   detail::cvode::number(t_stop));
        shared_->clear();
        const double* x = N_VGetArrayPointer(y_.get());
        std::copy(x, x + n, x_previous_.begin());
        if (t_stop - t_ <= 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_)))
            return cross_tiny_span(t_stop);
        tiny_span_ = false;
        check(CVodeSetStopTime(memory, t_stop), "CVodeSetStopTime", t_);
        sunrealtype t_returned = t_;
        const int flag = CVode(memory, t_stop, y_.get(), &t_returned, CV_ONE_STEP);
        stepped_ = true;
        if (flag < 0) {
            // CVODE left y at its internal time; go back to time(), the last time returned.
            std::copy(x_previous_.begin(), x_previous_.end(), N_VGetArrayPointer(y_.get()));
            fail(flag, nullptr);
        }
        const bool progress = t_returned > t_;
        t_previous_ = t_;
        t_ = t_returned;
        // Some CVODE paths (6.x's fixed-point solver) retry after our "unrecoverable" -1; a throw is fatal anyway.
        if (shared_->exception) fail(flag, "CVODE retried the step, but a throw is fatal");
        // Steps shrinking onto a point where the system keeps failing end with t + h == t, forever.
        if (!progress) fail(flag, "no progress (the step size underflowed: t + h == t)");
        if (flag == CV_ROOT_RETURN) {
            CVodeGetRootInfo(memory, roots_.data());
            return {t_, true};
        }
        std::fill(roots_.begin(), roots_.end(), 0);
        return {t_, false};
    }

    /// Dense output (CVODE's Nordsieck interpolant) on [previous_time(), time()]; the ends are returned exactly.
    void interpolate(double t, double* x) const {
        if (t == t_) {
            std::copy(state(), state() + n, x);
        } else if (t == t_previous_) {
            std::copy(x_previous_.begin(), x_previous_.end(), x);
        } else if (tiny_span_ && t > t_previous_ && t < t_) {
            const double s = (t - t_previous_) / (t_ - t_previous_);
            for (std::size_t i = 0; i < n; ++i) x[i] = x_previous_[i] + s * (state()[i] - x_previous_[i]);
        } else if (t > t_previous_ && t < t_) {
            // Let CVODE write straight into x: dky_ owns no data, it only borrows x for this call.
            N_VSetArrayPointer(x, dky_.get());
            const int flag = CVodeGetDky(memory_.get(), t, 0, dky_.get());
            if (flag < 0) throw std::logic_error("Cvode::interpolate: CVodeGetDky failed at t = " +
                                                 detail::cvode::number(t));
        } else {
            throw std::out_of_range("Cvode::interpolate: t = " + detail::cvode::number(t) + " outside [" +
                                    detail::cvode::number(t_previous_) + ", " + detail::cvode::number(t_) + "]");
        }
    }

    double time() const { return t_; }
    double previous_time() const { return t_previous_; }
    const double* state() const { return N_VGetArrayPointer(y_.get()); }
    /// After a root: +1 (rising) / -1 (falling) per guard that crossed, else 0.
    const int* roots() const { return roots_.data(); }

    /// Counters over the whole run, summed across restarts. rhs_evaluations include those of the
    /// difference-quotient Jacobian; restarts counts every restart() call (as DormandPrince does); `events`
    /// stays 0 (the event loop counts them).
    SolverStats stats() const {
        SolverStats s = done_;
        if (!stepped_) return s;
        void* memory = memory_.get();
        const auto add = [memory](int (*get)(void*, long*), long& total) {
            long value = 0;
            if (get(memory, &value) >= 0) total += value;
        };
        add(&CVodeGetNumSteps, s.steps);
        add(&CVodeGetNumRhsEvals, s.rhs_evaluations);
        add(&CVodeGetNumGEvals, s.guard_evaluations);
        add(&CVodeGetNumErrTestFails, s.error_test_failures);
        if (options_.method == Method::cvode_bdf) {
            add(&CVodeGetNumLinRhsEvals, s.rhs_evaluations);
            add(&CVodeGetNumJacEvals, s.jacobian_evaluations);
        }
        return s;
    }

private:
    /// What the C callbacks reach through user_data. On the heap, so that moving a Cvode keeps CVODE's pointer
    /// valid.
    struct Shared {
        const System* system = nullptr;
        Mode mode{};
        std::size_t states = 0, guards = 0;
        LinearSolver linear_solver = LinearSolver::dense;
        std::vector<sunindextype> column_starts, rows;  // the KLU pattern (CSC), rewritten into J at each call
        std::exception_ptr exception;   // thrown by the system inside a callback, rethrown as text in fail()
        const char* problem = nullptr;  // a non-finite value returned by the system
        double problem_time = 0.0;
        std::array<char, 512> message{};  // last message of CVODE's error handler (fixed buffer: no allocation)

        void clear() {
            exception = nullptr;
            problem = nullptr;
            message[0] = '\0';
        }
        void note(const char* what, double t) {
            if (problem) return;  // keep the first one
            problem = what;
            problem_time = t;
        }
        void store(const char* function, const char* text) {
            std::snprintf(message.data(), message.size(), "%s: %s", function ? function : "?", text ? text : "");
        }
    };

    // C trampolines: no exception may cross into CVODE, so each one catches everything and returns -1
    // (unrecoverable); step() then turns the stored exception into a SimulationError.
    static int rhs(sunrealtype t, N_Vector x, N_Vector dxdt, void* data) noexcept {
        auto& shared = *static_cast<Shared*>(data);
        if (shared.exception) return -1;  // stay failed until step() reports it
        try {
            double* f = N_VGetArrayPointer(dxdt);
            shared.system->rhs(t, N_VGetArrayPointer(x), shared.mode, f);
            // NaN/Inf would poison the error test. Reporting it as recoverable makes CVODE retry with a smaller
            // step (stiff laws can overflow on an overshooting trial step) and give up after a bounded number.
            for (std::size_t i = 0; i < shared.states; ++i) {
                if (!std::isfinite(f[i])) {
                    shared.note("the right-hand side returned a non-finite value", t);
                    return 1;
                }
            }
            return 0;
        } catch (...) {
            shared.exception = std::current_exception();
            return -1;
        }
    }

    static int guards(sunrealtype t, N_Vector x, sunrealtype* g, void* data) noexcept {
        auto& shared = *static_cast<Shared*>(data);
        if (shared.exception) return -1;
        try {
            shared.system->guards(t, N_VGetArrayPointer(x), shared.mode, g);
            // A NaN guard would silently never cross zero, i.e. miss a switch.
            for (std::size_t i = 0; i < shared.guards; ++i) {
                if (!std::isfinite(g[i])) {
                    shared.note("a guard returned a non-finite value", t);
                    return -1;
                }
            }
            return 0;
        } catch (...) {
            shared.exception = std::current_exception();
            return -1;
        }
    }

    // CVODE zeroes J before the call. Dense: the SUNMatrix stores its columns contiguously (column-major), the
    // form of a rig's jacobian(). Band: column j holds rows j - upper .. j + lower. Sparse (CSC): the pattern is
    // written back first (SUNMatZero clears the structure of a sparse matrix too), then each entry is found by
    // a binary search in its column.
    static int jacobian(sunrealtype t, N_Vector x, N_Vector, SUNMatrix J, void* data, N_Vector, N_Vector,
                        N_Vector) noexcept {
        auto& shared = *static_cast<Shared*>(data);
        if (shared.exception) return -1;
        try {
            const double* state = N_VGetArrayPointer(x);
            switch (shared.linear_solver) {
                case LinearSolver::dense:
                    if constexpr (has_dense_jacobian_v<System>) {
                        shared.system->jacobian(t, state, shared.mode, SUNDenseMatrix_Data(J));
                    } else if constexpr (has_jacobian_entries_v<System>) {
                        const sunindextype rows = SUNDenseMatrix_Rows(J);
                        double* a = SUNDenseMatrix_Data(J);
                        shared.system->jacobian_entries(t, state, shared.mode,
                                                        [a, rows](std::size_t i, std::size_t j, double v) {
                                                            a[static_cast<sunindextype>(j) * rows +
                                                              static_cast<sunindextype>(i)] += v;
                                                        });
                    }
                    break;
                case LinearSolver::band:
                    if constexpr (has_jacobian_entries_v<System>) {
                        shared.system->jacobian_entries(t, state, shared.mode, [J](std::size_t i, std::size_t j, double v) {
                            SUNBandMatrix_Column(J, static_cast<sunindextype>(j))[static_cast<sunindextype>(i) -
                                                                                  static_cast<sunindextype>(j)] += v;
                        });
                    }
                    break;
                case LinearSolver::sparse:
#if FRICTIONSIM_DETAIL_KLU
                    if constexpr (has_jacobian_entries_v<System>) {
                        sunindextype* starts = SUNSparseMatrix_IndexPointers(J);
                        sunindextype* rows = SUNSparseMatrix_IndexValues(J);
                        double* values = SUNSparseMatrix_Data(J);
                        std::copy(shared.column_starts.begin(), shared.column_starts.end(), starts);
                        std::copy(shared.rows.begin(), shared.rows.end(), rows);
                        std::fill(values, values + shared.rows.size(), 0.0);
                        shared.system->jacobian_entries(t, state, shared.mode, [&](std::size_t i, std::size_t j, double v) {
                            const sunindextype* first = rows + starts[j];
                            const sunindextype* last = rows + starts[j + 1];
                            const sunindextype* at = std::lower_bound(first, last, static_cast<sunindextype>(i));
                            if (at == last || *at != static_cast<sunindextype>(i))
                                throw std::logic_error("jacobian_entries wrote (" + std::to_string(i) + ", " +
                                                       std::to_string(j) + "), outside jacobian_pattern()");
                            values[at - rows] += v;
                        });
                    }
#endif
                    break;
                default: break;
            }
            return 0;
        } catch (...) {
            shared.exception = std::current_exception();
            return -1;
        }
    }

    /// The BDF linear solver: the matrix and solver of the chosen kind, and the pattern KLU needs.
    void make_linear_solver(const System& system, SUNContext context) {
        namespace cv = detail::cvode;
        const auto size = static_cast<sunindextype>(n);
        shared_->linear_solver = linear_solver_kind_;
        switch (linear_solver_kind_) {
            case LinearSolver::band: {
                const Bandwidths b = bandwidths_of(system);
                jacobian_.reset(cv::made(SUNBandMatrix(size, static_cast<sunindextype>(b.upper),
                                                       static_cast<sunindextype>(b.lower), context),
                                         "the band matrix"));
                linear_solver_.reset(cv::made(SUNLinSol_Band(y_.get(), jacobian_.get(), context), "SUNLinSol_Band"));
                break;
            }
            case LinearSolver::sparse: {
#if FRICTIONSIM_DETAIL_KLU
                auto pattern = jacobian_pattern_of(system);
                std::sort(pattern.begin(), pattern.end(), [](const auto& a, const auto& b) {
                    return a.second != b.second ? a.second < b.second : a.first < b.first;
                });
                pattern.erase(std::unique(pattern.begin(), pattern.end()), pattern.end());
                shared_->column_starts.assign(n + 1, 0);
                shared_->rows.clear();
                for (const auto& [row, col] : pattern) {
                    if (row >= n || col >= n)
                        detail::reject("jacobian_pattern", "entry", "inside the n x n Jacobian",
                                       static_cast<double>(std::max(row, col)));
                    shared_->rows.push_back(static_cast<sunindextype>(row));
                    ++shared_->column_starts[col + 1];
                }
                for (std::size_t j = 0; j < n; ++j) shared_->column_starts[j + 1] += shared_->column_starts[j];
                const auto nonzeros = static_cast<sunindextype>(std::max<std::size_t>(shared_->rows.size(), 1));
                jacobian_.reset(cv::made(SUNSparseMatrix(size, size, nonzeros, CSC_MAT, context), "the sparse matrix"));
                linear_solver_.reset(cv::made(SUNLinSol_KLU(y_.get(), jacobian_.get(), context), "SUNLinSol_KLU"));
#endif
                break;
            }
            default:
                jacobian_.reset(cv::made(SUNDenseMatrix(size, size, context), "the dense matrix"));
                linear_solver_.reset(cv::made(SUNLinSol_Dense(y_.get(), jacobian_.get(), context), "SUNLinSol_Dense"));
        }
    }

#if SUNDIALS_VERSION_MAJOR >= 7
    static void on_error(int, const char* function, const char*, const char* message, SUNErrCode, void* data,
                         SUNContext) noexcept {
        static_cast<Shared*>(data)->store(function, message);
    }
#else
    static void on_error(int, const char*, const char* function, char* message, void* data) noexcept {
        static_cast<Shared*>(data)->store(function, message);
    }
#endif

    void check(int flag, const char* call, double t) const {
        if (flag < 0) {
            const std::unique_ptr<char, void (*)(void*)> name(CVodeGetReturnFlagName(flag), &std::free);
            throw SimulationError(std::string("CVODE: ") + call + " failed (" + (name ? name.get() : "?") +
                                      "): " + shared_->message.data(),
                                  t);
        }
    }

    // CVodeInit must come before tolerances, solvers and root functions.
    void initialize(double t) {
        void* memory = memory_.get();
        const SolverOptions& o = options_;
        check(CVodeInit(memory, &Cvode::rhs, t, y_.get()), "CVodeInit", t);
        check(CVodeSetUserData(memory, shared_.get()), "CVodeSetUserData", t);
        if (o.atol_per_state.empty()) {
            check(CVodeSStolerances(memory, o.rtol, o.atol), "CVodeSStolerances", t);
        } else {
            // CVODE copies the vector, so it need not outlive this call.
            const detail::cvode::Owned<N_Vector, detail::cvode::FreeVector> atol(detail::cvode::made(
                N_VNew_Serial(static_cast<sunindextype>(n), context_.get()), "the tolerance vector"));
            std::copy(o.atol_per_state.begin(), o.atol_per_state.end(), N_VGetArrayPointer(atol.get()));
            check(CVodeSVtolerances(memory, o.rtol, atol.get()), "CVodeSVtolerances", t);
        }
        check(CVodeSetMaxNumSteps(memory, o.max_steps), "CVodeSetMaxNumSteps", t);
        if (std::isfinite(o.max_step)) check(CVodeSetMaxStep(memory, o.max_step), "CVodeSetMaxStep", t);
        if (o.initial_step > 0.0) check(CVodeSetInitStep(memory, o.initial_step), "CVodeSetInitStep", t);
        if (options_.method == Method::cvode_bdf) {
            check(CVodeSetLinearSolver(memory, linear_solver_.get(), jacobian_.get()), "CVodeSetLinearSolver", t);
            // Without an analytic Jacobian CVODE differences the right-hand side (within the band for a band
            // matrix: upper + lower + 1 evaluations); KLU needs the entries.
            const bool analytic = linear_solver_kind_ == LinearSolver::dense
                                      ? has_dense_jacobian_v<System> || has_jacobian_entries_v<System>
                                      : has_jacobian_entries_v<System>;
            if (analytic) check(CVodeSetJacFn(memory, &Cvode::jacobian), "CVodeSetJacFn", t);
        } else {
            check(CVodeSetNonlinearSolver(memory, nonlinear_solver_.get()), "CVodeSetNonlinearSolver", t);
        }
        if (m > 0) {
            check(CVodeRootInit(memory, static_cast<int>(m), &Cvode::guards), "CVodeRootInit", t);
            // A guard exactly zero at a restart is normal here (we restart on the switching surface).
            check(CVodeSetNoInactiveRootWarn(memory), "CVodeSetNoInactiveRootWarn", t);
        }
        initialized_ = true;
    }

    /// Throws the SimulationError for a failed step: CVode returned `flag` < 0, or `reason` says what else went
    /// wrong. time() and state() are left at the last time returned, the last time the solution (guards
    /// included) is valid; for failures inside a step that equals CVodeGetCurrentTime.
    [[noreturn]] void fail(int flag, const char* reason) {
        namespace cv = detail::cvode;
        t_previous_ = t_;
        std::copy(state(), state() + n, x_previous_.begin());
        std::fill(roots_.begin(), roots_.end(), 0);

        std::string what =
            std::string("CVODE (") + method_name(options_.method) + ") failed at t = " + cv::number(t_);
        if (shared_->exception) {
            try {
                std::rethrow_exception(shared_->exception);
            } catch (const std::exception& e) {
                what += std::string(": the system threw: ") + e.what();
            } catch (...) {
                what += ": the system threw a non-standard exception";
            }
        }
        if (shared_->problem)
            what += std::string(": ") + shared_->problem + " at t = " + cv::number(shared_->problem_time);
        if (flag < 0) {
            const std::unique_ptr<char, void (*)(void*)> name(CVodeGetReturnFlagName(flag), &std::free);
            what += std::string(": ") + (name ? name.get() : "unknown CVODE flag");
        }
        if (reason) what += std::string(": ") + reason;
        if (shared_->message[0] != '\0') what += std::string(" (CVODE: ") + shared_->message.data() + ")";
        const std::exception_ptr original = shared_->exception;
        shared_->clear();
        if (original) {
            // Keep the system's own exception reachable (std::rethrow_if_nested), e.g. an InvalidParameter. A stop
            // the caller asked for (a Python callable's KeyboardInterrupt) is no failure: it passes unchanged.
            try {
                std::rethrow_exception(original);
            } catch (const Interrupted& e) {
                throw Interrupted(e.what(), t_);
            } catch (...) {
                std::throw_with_nested(SimulationError(what, t_));
            }
        }
        throw SimulationError(what, t_);
    }

    /// What is left to t_stop is a few ulps (a run of t_end = 1e-300): CVODE refuses such a span, and no error
    /// control can work there. One Euler step without CVODE, linear dense output, no root search; the hybrid loop
    /// only asks this of the run's last step (t_stop is t_end).
    StepResult cross_tiny_span(double t_stop) {
        double* y = N_VGetArrayPointer(y_.get());
        std::vector<double> dxdt(n);
        shared_->system->rhs(t_, y, shared_->mode, dxdt.data());
        for (std::size_t i = 0; i < n; ++i) y[i] += (t_stop - t_) * dxdt[i];
        t_previous_ = t_;
        t_ = t_stop;
        tiny_span_ = true;
        std::fill(roots_.begin(), roots_.end(), 0);
        return {t_, false};
    }

    long total_steps() const {
        long steps = 0;
        if (stepped_) CVodeGetNumSteps(memory_.get(), &steps);
        return done_.steps + steps;
    }

    // Declaration order is destruction order reversed: the context goes last, the CVODE memory (which refers
    // to the vectors and solvers) first.
    detail::cvode::Owned<SUNContext, detail::cvode::FreeContext> context_;
    std::unique_ptr<Shared> shared_;
    detail::cvode::Owned<N_Vector, detail::cvode::FreeVector> y_;
    detail::cvode::Owned<N_Vector, detail::cvode::FreeVector> dky_;
    detail::cvode::Owned<SUNMatrix, detail::cvode::FreeMatrix> jacobian_;
    detail::cvode::Owned<SUNLinearSolver, detail::cvode::FreeLinearSolver> linear_solver_;
    detail::cvode::Owned<SUNNonlinearSolver, detail::cvode::FreeNonlinearSolver> nonlinear_solver_;
    std::unique_ptr<void, detail::cvode::FreeMemory> memory_;

    SolverOptions options_;
    std::size_t n, m;                  // states, guards
    LinearSolver linear_solver_kind_ = LinearSolver::dense;
    std::vector<double> x_previous_;   // state at previous_time(), for an exact left end of dense output
    std::vector<int> roots_;
    std::vector<int> directions_;      // CVodeSetRootDirection wants a mutable array
    SolverStats done_{};               // counters banked before each CVodeReInit
    double t_ = 0.0;
    double t_previous_ = 0.0;
    bool initialized_ = false;
    bool tiny_span_ = false;  // the last step was cross_tiny_span's (interpolate linearly)
    bool stepped_ = false;  // CVode called since the last restart (CVODE resets its solver counters lazily)
};

}  // namespace frictionsim

#undef FRICTIONSIM_DETAIL_KLU
