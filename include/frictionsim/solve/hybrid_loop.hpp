// The hybrid event loop shared by every integrator: integrate, report outputs from dense output, stop at
// the roots of the switching functions, resolve the new mode algebraically, restart exactly, and bound the
// number of switches per time window (chattering / Zeno guard).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "../error.hpp"
#include "hybrid_system.hpp"
#include "options.hpp"
#include "result.hpp"
#include "stop_conditions.hpp"
#include "system_size.hpp"

namespace frictionsim {

/// What integrate_hybrid hands back: the final state and mode, and the integrator's counters.
template <class System>
struct HybridOutcome {
    StateArray<System> state{};
    system_mode_t<System> mode{};
    SolverStats stats;
    double time = 0.0;     ///< t_end, or where a terminal stop condition ended the run
    bool stopped = false;  ///< a terminal stop condition ended the run
};

/// Observer that ignores everything: the default when only the final state matters.
struct NullObserver {
    template <class... A>
    void output(A&&...) {}
    template <class... A>
    void step(A&&...) {}
    template <class... A>
    void event(A&&...) {}
};

namespace detail {

/// Ring of the last (bound + 1) switch times: more than `bound` switches within `window` seconds is chattering.
class ChatteringGuard {
public:
    explicit ChatteringGuard(const SolverOptions& o)
        : window_(o.event_window), times_(static_cast<std::size_t>(o.max_events_in_window) + 1) {}

    /// Records a switch at t; true when the bound is exceeded.
    bool record(double t) {
        times_[next_] = t;
        next_ = (next_ + 1) % times_.size();
        if (count_ < times_.size()) ++count_;
        return count_ == times_.size() && t - times_[next_] <= window_;  // times_[next_] is now the oldest
    }

private:
    double window_;
    std::vector<double> times_;
    std::size_t next_ = 0, count_ = 0;
};

/// Guards that are exactly zero right after a restart are masked by the integrators until they move. Probe
/// which way each one moves (explicit Euler over a tiny step) so that one leaving zero towards its triggering
/// side fires at once rather than being masked (SciML OrdinaryDiffEq #3222). Its arrays are made once per run:
/// a string switches a thousand times per simulated second.
template <class System>
class ZeroGuardProbe {
public:
    explicit ZeroGuardProbe(const System& sys)
        : g_(make_guard_array(sys)), g_probe_(make_guard_array(sys)), dxdt_(make_state_array(sys)),
          probe_(make_state_array(sys)) {}

    /// Sets fired[i] to the side a zero guard i leaves towards when that is its triggering side; true if any.
    bool triggering(const System& sys, double t, const double* x, const system_mode_t<System>& mode,
                    GuardArray<System, int>& fired) {
        const std::size_t N = state_size_of(sys), G = guard_count_of(sys);
        sys.guards(t, x, mode, g_.data());
        bool any_zero = false;
        for (double gi : g_) any_zero = any_zero || gi == 0.0;
        if (!any_zero) return false;
        const double dt = 1e-9 * std::max(1.0, std::abs(t));
        sys.rhs(t, x, mode, dxdt_.data());
        for (std::size_t k = 0; k < N; ++k) probe_[k] = x[k] + dt * dxdt_[k];
        sys.guards(t + dt, probe_.data(), mode, g_probe_.data());
        bool any = false;
        for (std::size_t i = 0; i < G; ++i) {
            fired[i] = 0;
            if (g_[i] != 0.0) continue;
            const int dir = sys.guard_direction(i, mode);
            if (dir <= 0 && g_probe_[i] < 0.0) fired[i] = -1;
            if (dir >= 0 && g_probe_[i] > 0.0) fired[i] = +1;
            any = any || fired[i] != 0;
        }
        return any;
    }

private:
    GuardArray<System> g_, g_probe_;
    StateArray<System> dxdt_, probe_;
};

/// The run's wall-clock watch: between steps it polls SolverOptions::interrupt and checks the timeout, at most
/// every kPollInterval (the clock is read every kStepsPerClockRead steps, a few ns each). Inactive, and free,
/// when there is neither an interrupt callback nor a finite timeout.
class RunWatch {
public:
    using Clock = std::chrono::steady_clock;
    static constexpr std::chrono::milliseconds kPollInterval{20};
    static constexpr unsigned kStepsPerClockRead = 16;

    explicit RunWatch(const SolverOptions& o)
        : options_(o), active_(static_cast<bool>(o.interrupt) || std::isfinite(o.timeout)), start_(Clock::now()),
          next_poll_(start_ + kPollInterval) {}

    /// After a step that reached t: throws Interrupted or BudgetExceeded("timeout") when it is time to stop.
    void after_step(double t) {
        if (!active_ || ++steps_ % kStepsPerClockRead != 0) return;
        const Clock::time_point now = Clock::now();
        if (now < next_poll_) return;
        next_poll_ = now + kPollInterval;
        if (options_.interrupt && options_.interrupt()) {
            std::ostringstream msg;
            msg.precision(17);
            msg << "interrupted at t = " << t << " s";
            throw Interrupted(msg.str(), t);
        }
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        if (elapsed > options_.timeout) {
            std::ostringstream msg;
            msg << "wall-clock budget exceeded: timeout = " << std::setprecision(6) << options_.timeout
                << " s spent, stopped at t = " << std::setprecision(17) << t
                << " s; raise SolverOptions::timeout (Python: simulate(timeout=...))";
            throw BudgetExceeded(msg.str(), t, "timeout");
        }
    }

private:
    const SolverOptions& options_;
    bool active_;
    Clock::time_point start_, next_poll_;
    unsigned steps_ = 0;
};

/// Runs f; an exception from the model (a sampled signal run out, a law's own check) becomes a
/// SimulationError that says where the run stopped, so the caller keeps the results up to there.
template <class F>
auto reporting_time(double t, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const Interrupted& e) {
        throw Interrupted(e.what(), t);  // raised inside the model (a Python callable's KeyboardInterrupt): stop here
    } catch (const SimulationError&) {
        throw;
    } catch (const std::exception& e) {
        std::ostringstream msg;
        msg.precision(17);
        msg << "model evaluation failed after t = " << t << " s: " << e.what();
        throw SimulationError(msg.str(), t);
    }
}

inline void check_time_span(double t0, double t_end, const std::vector<double>& output_times) {
    detail::require_finite("simulate", "t_start", t0);
    detail::require_finite("simulate", "t_end", t_end);
    if (!(t_end > t0)) detail::reject("simulate", "t_end", "greater than the start time", t_end);
    if (!output_times.empty() && (output_times.front() < t0 || output_times.back() > t_end))
        detail::reject("SolverOptions", "output_times", "within [t_start, t_end]",
                       output_times.front() < t0 ? output_times.front() : output_times.back());
}

}  // namespace detail

/// Integrate `sys` from (t0, x0) to t_end with integrator `Integrator<System>`. The observer receives
///   output(t, x, mode)          at every requested output time (dense output, not by stopping there),
///   step(t, x, mode)            after every internal step when options.record_steps,
///   event(const Event&, t, x)   at every switch, with the state after the switch.
/// Throws SimulationError (time reached) when the integrator fails and ChatteringError when the switching
/// bound trips; everything observed before the throw stays with the observer.
template <template <class> class Integrator, class System, class Observer = NullObserver>
HybridOutcome<System> integrate_hybrid(const System& sys, StateArray<System> x, double t0, double t_end,
                                       const SolverOptions& options, Observer&& observer = {}) {
    const std::size_t N = state_size_of(sys), G = guard_count_of(sys);
    options.validate(N);
    detail::check_time_span(t0, t_end, options.output_times);
    if (x.size() != N) detail::reject("simulate", "initial_state", "one value per state (size given)",
                                      static_cast<double>(x.size()));
    for (double xi : x) detail::require_finite("simulate", "initial_state", xi);

    const std::vector<double>& outputs = options.output_times;
    std::size_t next_output = 0;
    Integrator<System> integrator(sys, options);
    system_mode_t<System> mode = detail::reporting_time(t0, [&] { return sys.initial_mode(t0, x.data()); });
    detail::ChatteringGuard chattering(options);
    detail::RunWatch watch(options);
    GuardArray<System, int> fired = make_guard_array<System, int>(sys);
    StateArray<System> buffer = make_state_array(sys), before_switch = make_state_array(sys);
    detail::ZeroGuardProbe<System> zero_guards(sys);
    detail::StopWatch stops(sys, options.stop_conditions);
    std::vector<double> stop_scratch(stops.any() ? N : 0);
    HybridOutcome<System> out;
    const bool keep_states = options.record_event_states.value_or(has_fixed_size_v<System>);
    // A stop condition's crossing at t (state xs) into the log; a terminal one ends the run there.
    auto stop_event = [&](double t, const double* xs, std::size_t k, int direction) {
        Event e;
        e.time = t;
        e.switching_function = e.stop_condition = static_cast<int>(k);
        e.name = stops.condition(k).name;
        e.mode_before = e.mode_after = mode_code(sys, mode);
        e.direction = direction;
        if (keep_states) e.state_before = e.state_after = std::vector<double>(xs, xs + N);
        observer.event(e, t, xs);
        if (stops.condition(k).terminal) out.stopped = true;
    };

    // Resolve a switch at t (state x, guards `fired`), log it, restart; repeat while guards that sit at zero
    // after the restart head straight into their triggering side (cascading or simultaneous switches).
    auto handle_switch = [&](double t) {
        if (options.record_event_rows && !options.record_steps) observer.step(t, x.data(), mode);
        do {
            const system_mode_t<System> before = mode;
            if (keep_states) std::copy(x.begin(), x.end(), before_switch.begin());
            mode = sys.switch_mode(t, x.data(), before, fired.data());
            if (options.record_event_rows) observer.step(t, x.data(), mode);
            for (std::size_t i = 0; i < G; ++i) {
                if (fired[i] == 0) continue;
                const int from = guard_mode(sys, i, before), to = guard_mode(sys, i, mode);
                Event e;
                e.time = t;
                e.switching_function = static_cast<int>(i);
                e.name = sys.guard_name(i, before);
                e.mode_before = from;
                e.mode_after = to;
                e.mode_before_name = sys.mode_name(from);
                e.mode_after_name = sys.mode_name(to);
                if (keep_states) {
                    e.state_before.assign(before_switch.begin(), before_switch.end());
                    e.state_after.assign(x.begin(), x.end());
                }
                observer.event(e, t, x.data());
                for (std::size_t k = stops.mode_condition(e.mode_after_name); k != detail::StopWatch::npos;
                     k = stops.mode_condition(e.mode_after_name, k + 1))
                    stop_event(t, x.data(), k, 0);
                if (chattering.record(t)) {
                    std::ostringstream msg;
                    msg << "chattering: more than " << options.max_events_in_window << " switches within "
                        << options.event_window << " s, last of switching function '" << e.name << "' ("
                        << e.mode_before_name << " -> " << e.mode_after_name << ") at t = " << t
                        << " s; raise SolverOptions::max_events_in_window or event_window, or regularise the law";
                    throw ChatteringError(msg.str(), t, e.name);
                }
            }
            integrator.restart(t, x.data(), mode);
            stops.reset(x.data());
        } while (!out.stopped && zero_guards.triggering(sys, t, x.data(), mode, fired));
    };

    detail::reporting_time(t0, [&] {
        integrator.restart(t0, x.data(), mode);
        stops.reset(x.data());
        while (next_output < outputs.size() && outputs[next_output] <= t0) {
            observer.output(t0, x.data(), mode);
            ++next_output;
        }
        if (options.record_steps && next_output == 0) observer.step(t0, x.data(), mode);
        if (zero_guards.triggering(sys, t0, x.data(), mode, fired)) handle_switch(t0);
        if (out.stopped) {  // a switch at the start into a mode a terminal condition names
            observer.output(t0, x.data(), mode);
            out.time = t0;
        }
    });

    // The requested outputs up to t, from the dense output.
    auto emit_outputs = [&](double t) {
        while (next_output < outputs.size() && outputs[next_output] <= t) {
            integrator.interpolate(outputs[next_output], buffer.data());
            observer.output(outputs[next_output], buffer.data(), mode);
            ++next_output;
        }
    };
    // The user's state conditions crossed within the last step, up to the first terminal one; true when that
    // ended the run (its last row the state where the condition held).
    auto stopped_within_step = [&](double t_step) {
        return detail::reporting_time(t_step, [&] {
            for (const detail::StopWatch::Crossing& c : stops.after_step(integrator, stop_scratch)) {
                if (c.time < integrator.time()) integrator.interpolate(c.time, x.data());
                else std::copy(integrator.state(), integrator.state() + N, x.begin());
                stop_event(c.time, x.data(), c.condition, c.direction);
                if (!out.stopped) continue;
                emit_outputs(c.time);
                observer.output(c.time, x.data(), mode);
                out.time = c.time;
                return true;
            }
            return false;
        });
    };

    const bool watching = stops.any();
    while (!out.stopped && integrator.time() < t_end) {
        const StepResult s = detail::reporting_time(integrator.time(), [&] { return integrator.step(t_end); });
        if (watching && stopped_within_step(s.t)) break;
        detail::reporting_time(s.t, [&] {  // the observer evaluates the model too (friction force)
            emit_outputs(s.t);
            if (options.record_steps) observer.step(s.t, integrator.state(), mode);
        });
        if (s.root) {
            const double* xs = integrator.state();
            std::copy(xs, xs + N, x.begin());
            const int* roots = integrator.roots();
            for (std::size_t i = 0; i < G; ++i) fired[i] = roots[i];  // (std::copy: GCC 12 warns on a 0-size array)
            detail::reporting_time(s.t, [&] { handle_switch(s.t); });
            if (out.stopped) {  // a switch into a mode a terminal condition names
                observer.output(s.t, x.data(), mode);
                out.time = s.t;
                break;
            }
        }
        watch.after_step(s.t);  // after the step's outputs: a stop here keeps everything up to s.t
    }
    out.state = make_state_array(sys);
    if (out.stopped) {
        std::copy(x.begin(), x.end(), out.state.begin());
    } else {
        out.time = t_end;
        std::copy(integrator.state(), integrator.state() + N, out.state.begin());
    }
    for (double xi : out.state)  // NaN is never success, recorded or not
        if (!std::isfinite(xi)) throw SimulationError("non-finite final state at t = " + std::to_string(t_end) + " s",
                                                      integrator.previous_time());
    out.mode = mode;
    out.stats = integrator.stats();
    return out;
}

}  // namespace frictionsim
