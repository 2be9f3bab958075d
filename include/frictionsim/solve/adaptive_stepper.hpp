// The step driver of the one-step integrators with error control (Dormand-Prince, RODAS4), written once: the
// trial step towards t_stop within max_steps, the error test with accept / reject, the exact restart at a switch,
// the last few ulps to t_stop, and the root location of the guards on the accepted step's dense output
// (root_location.hpp). A scheme is its tableau, its dense output and its step-size rule; it derives from
// AdaptiveStepper<Scheme, System> (CRTP: the hooks inline into the loop, and fixed-size schemes keep their
// compile-time state counts) and supplies, as members the base may call (befriend it):
//
//   static constexpr const char* kName, *kUnderflow       the error's method name, the step-underflow text
//   double* y() / const double* y() const                 the state at time()
//   double* scratch()                                     a state-sized buffer for the dense output
//   void load(const double* x)                            y <- x (restart)
//   void reset_controller()                               forget the step-size controller's history (restart)
//   void slope()                                          the first stage at (t_, y): FSAL stage or f0
//   double initial_step(double t_stop)                    Hairer's starting step, from y and the slope
//   double attempt(double h)                              one trial step from (t_, y): the scaled error norm
//   double rejected_step(double h, double err)            the next trial after a failed error test
//   void fit_dense_output(double h)                       coefficients of the accepted step's dense output
//   double next_step(double h, double err)                the step-size controller after an accepted step
//   void advance()                                        y <- the accepted solution (FSAL, stale Jacobian...)
//   void euler_step(double h)                             the last few ulps: y + h f, linear dense output
//   void interpolate(double t, double* x) const           the dense output on [previous_time(), time()]
//   void interpolate_states(t, first, last, x)            the same for states [first, last) only
// and may hide the defaults below: begin_step() (before the first trial of a step), prepare(h) (before each
// trial; false refuses h, which is then halved, at most kMaxRefused times in a row, else the run fails with
// kRefused: RODAS's singular matrix),
// end_guards(g) (the guards at the step's end), may_cross(g) (false: no guard can have crossed in this step, the
// scan is skipped), cut_to_root() (after the step was cut back to a root).
#pragma once

#include <algorithm>
#include <cstddef>

#include "hybrid_system.hpp"
#include "options.hpp"
#include "result.hpp"
#include "root_location.hpp"
#include "step_control.hpp"
#include "system_size.hpp"

namespace frictionsim::detail {

template <class Scheme, class System>
class AdaptiveStepper {
public:
    using Mode = system_mode_t<System>;
    using Guards = GuardArray<System>;

    /// Exact restart at a switch: a one-step method has no history, so only the step size carries over. It
    /// starts from the last accepted step: a switch rarely changes the time scales much (Hairer's starting guess
    /// from one Euler step would ramp up from far below them), and a step too long for the new mode fails the
    /// error test once and shrinks.
    void restart(double t, const double* x, const Mode& mode) {
        t_ = t_prev_ = t;
        mode_ = mode;
        scheme().load(x);
        scheme().slope();
        h_ = std::min(h_accepted_, opt_.max_step);
        scheme().reset_controller();
        last_rejected_ = false;
        guards(t_, scheme().y(), roots_.values());
        roots_.restarted();
        ++stats_.restarts;
    }

    /// One accepted step towards t_stop (landing on it exactly when it is near), cut back to the earliest root.
    StepResult step(double t_stop) {
        if (t_stop - t_ <= underflow_step()) return cross_tiny_span(t_stop);
        scheme().begin_step();
        if (h_ == 0.0) h_ = opt_.initial_step > 0.0 ? opt_.initial_step : scheme().initial_step(t_stop);
        int refused = 0;
        for (;;) {
            if (stats_.steps >= opt_.max_steps) fail("max_steps exceeded (raise SolverOptions::max_steps)");
            bool last = false;
            const double h = trial_step(h_, opt_, t_, t_stop, last);
            if (h <= underflow_step()) fail(Scheme::kUnderflow);
            const bool ready = scheme().prepare(h);
            ++stats_.steps;
            if (!ready) {
                if (++refused > Scheme::kMaxRefused) fail(Scheme::kRefused);
                h_ = 0.5 * h;
                last_rejected_ = true;
                continue;
            }
            const double err = scheme().attempt(h);
            if (err <= 1.0) {
                accept(h, err, last ? t_stop : t_ + h);
                return locate_roots();
            }
            ++stats_.error_test_failures;
            last_rejected_ = true;
            h_ = scheme().rejected_step(h, err);
        }
    }

    double time() const { return t_; }
    double previous_time() const { return t_prev_; }
    const double* state() const { return scheme().y(); }
    const int* roots() const { return roots_.roots(); }
    SolverStats stats() const { return stats_; }

protected:
    AdaptiveStepper(const System& system, const SolverOptions& options)
        : sys_(system), opt_(options), g_count_(guard_count_of(system)), g1_(make_guard_array(system)),
          roots_(system) {}

    /// Guards: a compile-time count for fixed-size systems (the loops fold away when it is 0), else the run's.
    std::size_t guard_count() const {
        if constexpr (has_fixed_size_v<System>) return System::guard_count;
        else return g_count_;
    }
    static constexpr bool kNoGuards = [] {
        if constexpr (has_fixed_size_v<System>) return System::guard_count == 0;
        else return false;
    }();

    void guards(double t, const double* x, Guards& g) {
        if constexpr (!kNoGuards) {
            if (guard_count() == 0) return;
            sys_.guards(t, x, mode_, g.data());
            ++stats_.guard_evaluations;
        }
    }
    double underflow_step() const { return detail::underflow_step(t_); }
    [[noreturn]] void fail(const char* why) const { step_failure(Scheme::kName, why, t_); }

    // The defaults of the optional hooks.
    static constexpr int kMaxRefused = 0;
    static constexpr const char* kRefused = "";
    void begin_step() {}
    bool prepare(double) { return true; }
    void end_guards(Guards& g) { guards(t_, scheme().y(), g); }
    bool may_cross(const Guards&) { return true; }
    void cut_to_root() {}

    const System& sys_;
    const SolverOptions& opt_;
    std::size_t g_count_ = 0;
    Mode mode_{};
    double t_ = 0.0, t_prev_ = 0.0, h_ = 0.0;
    double h_dense_ = 1.0;     ///< the span of the dense output: the last step, or the last few ulps
    double h_accepted_ = 0.0;  ///< last accepted step, 0 before the first: the step after a restart
    bool last_rejected_ = false;
    Guards g1_{};  ///< guards at the step's end (no heap per step)
    RootLocator<System> roots_;
    SolverStats stats_;

private:
    Scheme& scheme() { return static_cast<Scheme&>(*this); }
    const Scheme& scheme() const { return static_cast<const Scheme&>(*this); }

    void accept(double h, double err, double t_new) {
        scheme().fit_dense_output(h);
        double h_new = scheme().next_step(h, err);
        if (last_rejected_) h_new = std::min(h_new, h);  // no growth right after a rejection
        last_rejected_ = false;
        h_dense_ = h_accepted_ = h;
        t_prev_ = t_;
        t_ = t_new;
        h_ = h_new;
        scheme().advance();
    }

    /// What is left to t_stop is a few ulps (a run of t_end = 1e-300, a switch located just before t_end): one
    /// Euler step, linear dense output, no guard scan (no crossing can be resolved inside it).
    StepResult cross_tiny_span(double t_stop) {
        const double h = t_stop - t_;
        scheme().euler_step(h);
        ++stats_.steps;
        h_dense_ = h > 0.0 ? h : 1.0;
        t_prev_ = t_;
        t_ = t_stop;
        scheme().slope();
        guards(t_, scheme().y(), roots_.values());
        return {t_, false};
    }

    // After an accepted step: did a switching function cross zero in its direction? If so, cut the step at the
    // earliest crossing on the dense output (root_location.hpp) and report every guard that has crossed.
    StepResult locate_roots() {
        if constexpr (kNoGuards) {
            return {t_, false};
        } else {
            if (guard_count() == 0) return {t_, false};
            Guards& g1 = g1_;
            scheme().end_guards(g1);
            roots_.set_references(mode_, g1);
            if (!scheme().may_cross(g1)) {
                roots_.no_root(g1);
                return {t_, false};
            }
            double t_root = t_;
            const auto at = [this](double t, Guards& g) {
                scheme().interpolate(t, scheme().scratch());
                guards(t, scheme().scratch(), g);
            };
            bool any = false;
            if constexpr (has_local_guards_v<System>) {  // bracket a guard on the states it reads alone
                any = roots_.scan(mode_, t_prev_, t_, g1, at, [this](std::size_t i, double t) {
                    const GuardReads r = sys_.guard_reads(i);
                    scheme().interpolate_states(t, r.first, r.last, scheme().scratch());
                    return sys_.guard(i, t, scheme().scratch(), mode_);
                }, t_root);
            } else {
                any = roots_.scan(mode_, t_prev_, t_, g1, at, t_root);
            }
            if (!any) return {t_, false};
            if (t_root < t_) {
                scheme().interpolate(t_root, scheme().y());
                t_ = t_root;
                guards(t_, scheme().y(), g1);
                scheme().cut_to_root();
            }
            roots_.mark(mode_, g1);
            return {t_, true};
        }
    }
};

}  // namespace frictionsim::detail
