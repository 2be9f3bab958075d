// simulate_time_stepping(model, t_end, options): the one run loop of the time-stepping (event-capturing) models,
// returning the same Result as the hybrid event loop (simulate() in simulate.hpp dispatches here at compile time for
// a model that declares `time_stepping = true`). Header-only, no SUNDIALS, no Eigen: the model brings its stepper.
//
// A TimeSteppingModel M provides
//   static constexpr bool time_stepping = true;
//   state_names() const;                 // the Result's columns (std::vector<std::string> or of const char*)
//   const char* mode_name(int mode) const;   // the names of the Result's mode codes (events, mode stop conditions)
//   Stepper make_stepper(const TimeStepping& setup) const;   // from the model's initial state at setup.t_start
// and its Stepper
//   double time() const;                          // the end of the last step
//   bool finished(double t_end) const;            // no step is left before t_end
//   void step(double t_end, bool keep_start);     // one step (shortened to end at t_end, or cut at a switch it
//                                                 // locates); keep_start: row() will be asked inside this step
//   int row(double t, double* out) const;         // the columns at t in the last step, and the mode code there
//                                                 // (Result::mode): at its end, or (keep_start) from the state
//                                                 // linear between its ends
//   double friction_force() const;                // Result::friction_force now
//   const std::vector<Event>& events() const;     // the switches of the last step (name, modes, time)
//   void add_stats(SolverStats& stats) const;     // its counters
//
// The loop: outputs at options.output_times from row() (an output within 1e-9 h of a step end takes that end's
// state), or every step end when there are none; state stop conditions located between step ends by linear
// interpolation of the columns, mode stop conditions on the stepper's events; timeout and interrupt polled between
// steps (hybrid_loop.hpp's RunWatch: at most every 20 ms); max_output_rows and max_steps; a failed run throws
// SimulationError carrying the result up to the time reached; non-finite columns stop the run.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../detail/traits.hpp"
#include "../error.hpp"
#include "hybrid_loop.hpp"
#include "options.hpp"
#include "recorder.hpp"
#include "result.hpp"
#include "stop_conditions.hpp"

namespace frictionsim {

/// What a model's make_stepper() is given: the resolved method and its step.
struct TimeStepping {
    Method method = Method::moreau_jean;  ///< moreau_jean or explicit_projection
    double step = 1e-3;
    double theta = 0.5;
    double projection_band = 0.0;
    double t_start = 0.0;
    ContactSolverChoice contact_solver = ContactSolverChoice::active_set;  ///< moreau_jean's one-step solver
};

namespace detail {
template <class M> using ts_names_t = decltype(std::declval<const M&>().state_names()[0]);
template <class M> using ts_mode_name_t = decltype(static_cast<const char*>(std::declval<const M&>().mode_name(0)));
template <class M> using ts_stepper_t = decltype(std::declval<const M&>().make_stepper(std::declval<const TimeStepping&>()));
template <class P> using ts_time_t = decltype(double{std::declval<const P&>().time()});
template <class P> using ts_finished_t = decltype(bool{std::declval<const P&>().finished(0.0)});
template <class P> using ts_step_t = decltype(std::declval<P&>().step(0.0, true));
template <class P> using ts_row_t = decltype(int{std::declval<const P&>().row(0.0, std::declval<double*>())});
template <class P> using ts_force_t = decltype(double{std::declval<const P&>().friction_force()});
template <class P> using ts_events_t =
    std::enable_if_t<std::is_same_v<std::decay_t<decltype(std::declval<const P&>().events())>, std::vector<Event>>>;
template <class P> using ts_stats_t = decltype(std::declval<const P&>().add_stats(std::declval<SolverStats&>()));

template <class M, bool = detected<M, ts_stepper_t>::value>
struct stepper_of { using type = void; };
template <class M>
struct stepper_of<M, true> { using type = ts_stepper_t<M>; };
}  // namespace detail

/// static_asserts naming the first missing member of the TimeSteppingModel concept above; true when M meets it.
template <class M>
constexpr bool check_time_stepping_model() {
    using namespace detail;
    using P = typename stepper_of<M>::type;
    static_assert(detected<M, ts_names_t>::value,
                  "TimeSteppingModel requires `state_names() const` (a std::vector of names)");
    static_assert(detected<M, ts_mode_name_t>::value,
                  "TimeSteppingModel requires `const char* mode_name(int mode) const`");
    static_assert(detected<M, ts_stepper_t>::value,
                  "TimeSteppingModel requires `Stepper make_stepper(const TimeStepping& setup) const`");
    static_assert(detected<P, ts_time_t>::value, "TimeSteppingModel's Stepper requires `double time() const`");
    static_assert(detected<P, ts_finished_t>::value,
                  "TimeSteppingModel's Stepper requires `bool finished(double t_end) const`");
    static_assert(detected<P, ts_step_t>::value,
                  "TimeSteppingModel's Stepper requires `void step(double t_end, bool keep_start)`");
    static_assert(detected<P, ts_row_t>::value,
                  "TimeSteppingModel's Stepper requires `int row(double t, double* out) const` (returns the mode code)");
    static_assert(detected<P, ts_force_t>::value,
                  "TimeSteppingModel's Stepper requires `double friction_force() const`");
    static_assert(detected<P, ts_events_t>::value,
                  "TimeSteppingModel's Stepper requires `const std::vector<Event>& events() const`");
    static_assert(detected<P, ts_stats_t>::value,
                  "TimeSteppingModel's Stepper requires `void add_stats(SolverStats& stats) const`");
    return detected<M, ts_names_t>::value && detected<M, ts_mode_name_t>::value && detected<P, ts_time_t>::value &&
           detected<P, ts_finished_t>::value && detected<P, ts_step_t>::value && detected<P, ts_row_t>::value &&
           detected<P, ts_force_t>::value && detected<P, ts_events_t>::value &&
           detected<P, ts_stats_t>::value;
}

namespace detail {

/// The last step seen through its columns, linear between its ends: what StopWatch locates state conditions on.
class LinearColumns {
public:
    explicit LinearColumns(std::size_t n) : start_(n), end_(n) {}
    double previous_time() const { return t0_; }
    double time() const { return t1_; }
    const double* state() const { return end_.data(); }
    void interpolate(double t, double* out) const {
        const double a = t1_ > t0_ ? std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0) : 1.0;
        for (std::size_t i = 0; i < end_.size(); ++i) out[i] = (1.0 - a) * start_[i] + a * end_[i];
    }
    /// The columns `x` at t become the end; the old end the start.
    void advance(double t, const std::vector<double>& x) {
        std::swap(start_, end_);
        t0_ = t1_;
        end_ = x;
        t1_ = t;
    }
    void reset(double t, const std::vector<double>& x) {
        start_ = end_ = x;
        t0_ = t1_ = t;
    }

private:
    std::vector<double> start_, end_;
    double t0_ = 0.0, t1_ = 0.0;
};

}  // namespace detail

/// Steps `model` from its initial state at t_start to t_end with options.method (automatic: moreau_jean).
template <class Model>
Result simulate_time_stepping(const Model& model, double t_end, const SolverOptions& options, double t_start = 0.0) {
    if constexpr (!check_time_stepping_model<Model>()) {
        return Result{};  // not reached: the static_asserts have named what Model misses
    } else {
        const Method method = options.method == Method::automatic ? Method::moreau_jean : options.method;
        detail::check_time_span(t_start, t_end, options.output_times);
        options.validate_time_stepping(method, t_start, t_end);
        const auto names = model.state_names();
        const std::size_t n = static_cast<std::size_t>(names.size());
        detail::StopWatch stops(model, options.stop_conditions);
        auto stepper = model.make_stepper(TimeStepping{method, options.step, options.theta, options.projection_band,
                                                       t_start, options.contact_solver});
        const std::vector<double>& outputs = options.output_times;
        const std::size_t expected =
            outputs.empty() ? static_cast<std::size_t>(std::lround((t_end - t_start) / options.step)) + 1
                            : outputs.size();
        RowRecorder recorder(names, expected, options);
        SolverStats stats;
        try {
            const double h = options.step, tol = 1e-9 * h;
            std::vector<double> x(n);
            std::size_t next_output = 0;
            bool stopped = false;
            double t_stop = t_end;
            detail::RunWatch watch(options);
            detail::LinearColumns columns(n);
            std::vector<double> scratch(n);
            const auto record = [&](double t) {  // the row at t
                const int mode = stepper.row(t, x.data());
                recorder.row(t, x.data(), stepper.friction_force(), mode);
            };
            const auto emit_outputs = [&](double t) {  // the requested outputs up to t
                for (; next_output < outputs.size() && outputs[next_output] <= t + tol; ++next_output)
                    record(outputs[next_output]);
            };
            detail::reporting_time(t_start, [&] {
                if (outputs.empty()) record(t_start);
                else emit_outputs(t_start);
                stepper.row(t_start, x.data());
                columns.reset(t_start, x);
                stops.reset(x.data());
            });
            long steps = 0;
            while (!stepper.finished(t_end)) {
                if (++steps > options.max_steps) {
                    std::ostringstream msg;
                    msg.precision(17);
                    msg << "max_steps = " << options.max_steps << " steps taken at t = " << stepper.time()
                        << " s; raise SolverOptions::max_steps";
                    throw SimulationError(msg.str(), stepper.time());
                }
                const double t0 = stepper.time();
                const bool keep_start =
                    stops.any() || (next_output < outputs.size() && outputs[next_output] < t0 + h - tol);
                detail::reporting_time(t0, [&] { stepper.step(t_end, keep_start); });
                const double t = stepper.time();
                detail::reporting_time(t, [&] {
                    // the step's switches, and the stop conditions they meet
                    std::vector<Event> stop_log;
                    double t_mode_stop = t_end;
                    bool mode_stop = false;
                    for (const Event& e : stepper.events()) {
                        recorder.event(e, e.time);
                        for (std::size_t k = stops.mode_condition(e.mode_after_name); k != detail::StopWatch::npos;
                             k = stops.mode_condition(e.mode_after_name, k + 1)) {
                            Event s;
                            s.time = e.time;
                            s.switching_function = s.stop_condition = static_cast<int>(k);
                            s.name = stops.condition(k).name;
                            s.mode_before = e.mode_before;
                            s.mode_after = e.mode_after;
                            s.mode_before_name = e.mode_before_name;
                            s.mode_after_name = e.mode_after_name;
                            stop_log.push_back(s);
                            if (stops.condition(k).terminal && !mode_stop) {
                                mode_stop = true;
                                t_mode_stop = e.time;
                            }
                        }
                    }
                    // the state conditions crossed within the step, linear between its ends
                    double t_state_stop = t_end;
                    bool state_stop = false;
                    if (stops.any()) {
                        stepper.row(t, x.data());
                        columns.advance(t, x);
                        for (const detail::StopWatch::Crossing& c : stops.after_step(columns, scratch)) {
                            if (mode_stop && c.time > t_mode_stop) break;
                            Event s;
                            s.time = c.time;
                            s.switching_function = s.stop_condition = static_cast<int>(c.condition);
                            s.name = stops.condition(c.condition).name;
                            s.mode_before = s.mode_after = stepper.row(c.time, scratch.data());
                            s.direction = c.direction;
                            stop_log.push_back(s);
                            if (stops.condition(c.condition).terminal) {
                                state_stop = true;
                                t_state_stop = c.time;
                                break;
                            }
                        }
                    }
                    std::stable_sort(stop_log.begin(), stop_log.end(),
                                     [](const Event& a, const Event& b) { return a.time < b.time; });
                    // the run ends at the first terminal one: a state crossing where it is located, a switch at
                    // the step's end (the state after the switch)
                    if (state_stop && (!mode_stop || t_state_stop <= t_mode_stop)) {
                        stopped = true;
                        t_stop = t_state_stop;
                    } else if (mode_stop) {
                        stopped = true;
                        t_stop = t;
                    }
                    for (const Event& s : stop_log) {
                        if (stopped && s.time > t_stop) break;
                        recorder.event(s, s.time);
                    }
                    if (stopped) {
                        emit_outputs(t_stop);
                        record(t_stop);
                        return;
                    }
                    if (outputs.empty()) record(t);
                    else emit_outputs(t);
                });
                if (stopped) break;
                watch.after_step(t);  // after the step's outputs: a stop here keeps everything up to t
            }
            if (!stopped) {
                t_stop = stepper.time();
                emit_outputs(t_end);  // the last step ends on t_end (to rounding): outputs there take its state
                if (!outputs.empty() || steps == 0) {
                    // every row is finite by now; the final state too when it was not recorded
                    stepper.row(t_stop, x.data());
                    for (double xi : x)
                        if (!std::isfinite(xi))
                            throw SimulationError("non-finite final state at t = " + std::to_string(t_stop) + " s",
                                                  t_stop);
                }
            }
            stepper.add_stats(stats);
            return std::move(*recorder.finish(true, stopped ? t_stop : t_end, stats, stopped));
        } catch (SimulationError& e) {
            stepper.add_stats(stats);
            const std::shared_ptr<Result> partial = recorder.finish(false, e.time_reached(), stats);
            partial->message = e.what();
            e.attach_partial(partial);
            throw;
        }
    }
}

}  // namespace frictionsim
