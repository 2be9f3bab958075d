// Observer that stores output rows (time, states, friction force, mode) and the event log into a Result. It is the
// last check before a result is returned: a non-finite value stops the run (NaN is never success), and the rows
// and events it keeps are capped (SolverOptions::max_output_rows), so a failing run cannot fill the memory.
#pragma once

#include <cmath>
#include <cstddef>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "../error.hpp"
#include "options.hpp"
#include "result.hpp"
#include "system_size.hpp"

namespace frictionsim {

/// The rows and the event log of a Result, checked and capped: what every run loop records into.
class RowRecorder {
public:
    template <class Names>
    RowRecorder(const Names& state_names, std::size_t expected_rows, std::size_t max_rows)
        : max_rows_(max_rows), result_(std::make_shared<Result>()) {
        for (const auto& n : state_names) result_->state_names.emplace_back(n);
        n_ = result_->state_names.size();
        result_->t.reserve(expected_rows);
        result_->states.reserve(expected_rows * n_);
        result_->friction_force.reserve(expected_rows);
        result_->mode.reserve(expected_rows);
    }

    /// One row: time, states x[state_count], friction force, mode code. Non-finite values stop the run.
    void row(double t, const double* x, double force, int mode) {
        if (result_->t.size() >= max_rows_) over_budget(t, "rows");
        bool finite = std::isfinite(force);
        for (std::size_t i = 0; i < n_; ++i) finite = finite && std::isfinite(x[i]);
        if (!finite) non_finite(t, x, force);
        result_->t.push_back(t);
        result_->states.insert(result_->states.end(), x, x + n_);
        result_->friction_force.push_back(force);
        result_->mode.push_back(mode);
    }
    void event(const Event& e, double t) {
        std::vector<Event>& log = e.stop_condition >= 0 ? result_->stop_events : result_->events;
        if (log.size() >= max_rows_) over_budget(t, "events");
        log.push_back(e);
    }
    const Result& result() const { return *result_; }

    /// Marks how the run ended and hands the result over (shared, so an exception can carry it too).
    std::shared_ptr<Result> finish(bool completed, double t_reached, const SolverStats& stats = {},
                                   bool stopped = false) {
        result_->completed = completed;
        result_->t_reached = t_reached;
        result_->status = !completed ? -1 : stopped ? 1 : 0;
        if (!completed)
            result_->message = "the run stopped early at t = " + std::to_string(t_reached) + " s (see the error)";
        else if (stopped)
            result_->message = "a terminal stop condition (" + result_->stop_events.back().name + ") ended the run";
        else
            result_->message = "the run reached t_end";
        result_->stats = stats;
        result_->stats.events = static_cast<long>(result_->events.size());
        return result_;
    }

private:
    /// Bytes one output row takes: time, states, friction force, mode.
    std::size_t row_bytes() const { return (n_ + 2) * sizeof(double) + sizeof(int); }

    [[noreturn]] void over_budget(double t, const char* what) const {
        std::ostringstream msg;
        msg.precision(17);
        msg << "the result reached max_output_rows = " << max_rows_ << " " << what << " (about "
            << static_cast<double>(max_rows_ * row_bytes()) / (1 << 20) << " MiB of rows) at t = " << t
            << " s; record fewer rows (output_times instead of every step) or raise max_output_rows";
        throw BudgetExceeded(msg.str(), result_->t.empty() ? t : result_->t.back(), "max_output_rows");
    }

    [[noreturn]] void non_finite(double t, const double* x, double force) const {
        std::ostringstream msg;
        msg.precision(17);
        msg << "non-finite result at t = " << t << " s:";
        for (std::size_t i = 0; i < n_; ++i)
            if (!std::isfinite(x[i])) msg << " " << result_->state_names[i] << " = " << x[i];
        if (!std::isfinite(force)) msg << " friction_force = " << force;
        throw SimulationError(msg.str(), result_->t.empty() ? t : result_->t.back());
    }

    std::size_t n_ = 0;
    std::size_t max_rows_;
    std::shared_ptr<Result> result_;
};

/// The hybrid loop's observer: a RowRecorder fed with the system's friction force and mode code.
template <class System>
class Recorder {
public:
    explicit Recorder(const System& system, std::size_t expected_rows = 0,
                      std::size_t max_rows = SolverOptions{}.max_output_rows)
        : sys_(system), rows_(system.state_names(), expected_rows, max_rows) {}

    void output(double t, const double* x, const system_mode_t<System>& mode) {
        rows_.row(t, x, sys_.friction_force(t, x, mode), mode_code(sys_, mode));
    }
    void step(double t, const double* x, const system_mode_t<System>& mode) { output(t, x, mode); }
    void event(const Event& e, double t, const double*) { rows_.event(e, t); }

    std::shared_ptr<Result> finish(bool completed, double t_reached, const SolverStats& stats = {},
                                   bool stopped = false) {
        return rows_.finish(completed, t_reached, stats, stopped);
    }

private:
    const System& sys_;
    RowRecorder rows_;
};

}  // namespace frictionsim
