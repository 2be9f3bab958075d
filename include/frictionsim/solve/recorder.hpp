// Observer that stores output rows (time, states, friction force, mode) and the event log into a Result. It is the
// last check before a result is returned: a non-finite value stops the run (NaN is never success), and the rows
// and events it keeps are capped (SolverOptions::max_output_rows and max_output_bytes), so a failing run cannot fill
// the memory.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "../error.hpp"
#include "options.hpp"
#include "result.hpp"
#include "system_size.hpp"

namespace frictionsim {

/// The rows and the event log of a Result, checked and capped: what every run loop records into. Capped by count
/// (SolverOptions::max_output_rows) and by bytes (SolverOptions::output_byte_budget()); a row or an event is kept
/// whole or not at all, so the result stays consistent (every column the same length) when memory runs out.
class RowRecorder {
public:
    /// `rows_at_least`: the rows the run records if it completes (its output_times, or its fixed steps); a run
    /// whose rows cannot fit the byte budget is refused here, before it starts.
    template <class Names>
    RowRecorder(const Names& state_names, std::size_t rows_at_least, const SolverOptions& options)
        : max_rows_(options.max_output_rows), max_bytes_(options.output_byte_budget()),
          result_(std::make_shared<Result>()) {
        for (const auto& n : state_names) result_->state_names.emplace_back(n);
        n_ = result_->state_names.size();
        const double needed = static_cast<double>(rows_at_least) * static_cast<double>(row_bytes());
        if (needed > static_cast<double>(max_bytes_)) refuse(rows_at_least, needed);
        const std::size_t rows = std::min({rows_at_least, max_rows_, max_bytes_ / row_bytes()});
        try {
            result_->t.reserve(rows);
            result_->states.reserve(rows * n_);
            result_->friction_force.reserve(rows);
            result_->mode.reserve(rows);
        } catch (const std::bad_alloc&) {
            out_of_memory(0.0, "rows");
        }
    }

    /// One row: time, states x[state_count], friction force, mode code. Non-finite values stop the run.
    void row(double t, const double* x, double force, int mode) {
        if (result_->t.size() >= max_rows_) over_budget(t, "rows");
        if (bytes_ + row_bytes() > max_bytes_) over_bytes(t, "rows");
        bool finite = std::isfinite(force);
        for (std::size_t i = 0; i < n_; ++i) finite = finite && std::isfinite(x[i]);
        if (!finite) non_finite(t, x, force);
        try {  // room for the whole row first: the push_backs below cannot throw, the columns stay equal in length
            make_room(result_->t, 1);
            make_room(result_->states, n_);
            make_room(result_->friction_force, 1);
            make_room(result_->mode, 1);
        } catch (const std::bad_alloc&) {
            out_of_memory(t, "rows");
        }
        result_->t.push_back(t);
        result_->states.insert(result_->states.end(), x, x + n_);
        result_->friction_force.push_back(force);
        result_->mode.push_back(mode);
        bytes_ += row_bytes();
    }
    void event(const Event& e, double t) {
        std::vector<Event>& log = e.stop_condition >= 0 ? result_->stop_events : result_->events;
        if (log.size() >= max_rows_) over_budget(t, "events");
        const std::size_t size = event_bytes(e);
        if (bytes_ + size > max_bytes_) over_bytes(t, "events");
        try {
            log.push_back(e);  // strong guarantee: on bad_alloc the log is as it was
        } catch (const std::bad_alloc&) {
            out_of_memory(t, "events");
        }
        bytes_ += size;
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
    static std::size_t event_bytes(const Event& e) {
        return sizeof(Event) + (e.state_before.size() + e.state_after.size()) * sizeof(double) + e.name.size() +
               e.mode_before_name.size() + e.mode_after_name.size();
    }
    static double mib(double bytes) { return bytes / double(1 << 20); }

    /// Capacity for `more` elements past the size, doubling (amortised O(1) like push_back).
    template <class T>
    static void make_room(std::vector<T>& v, std::size_t more) {
        if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
    }

    /// The default budget's origin, for the messages.
    std::string budget_text() const {
        std::ostringstream s;
        s.precision(4);
        s << "max_output_bytes = " << max_bytes_ << " (" << mib(static_cast<double>(max_bytes_)) << " MiB";
        const std::size_t memory = detail::usable_memory_bytes();
        if (memory > 0) s << "; this process may use " << mib(static_cast<double>(memory)) / 1024.0 << " GiB";
        s << ", the default is an eighth of it)";
        return s.str();
    }

    [[noreturn]] void refuse(std::size_t rows, double needed) const {
        std::ostringstream msg;
        msg.precision(4);
        msg << "simulate: max_output_bytes: the run would record at least " << rows << " rows of " << n_
            << " states (" << mib(needed) << " MiB), more than " << budget_text()
            << "; give fewer output_times (or a larger step), or raise max_output_bytes";
        throw InvalidParameter("max_output_bytes", msg.str());
    }

    [[noreturn]] void over_budget(double t, const char* what) const {
        std::ostringstream msg;
        msg.precision(17);
        msg << "the result reached max_output_rows = " << max_rows_ << " " << what << " (about "
            << mib(static_cast<double>(max_rows_ * row_bytes())) << " MiB of rows) at t = " << t
            << " s; record fewer rows (output_times instead of every step) or raise max_output_rows";
        throw BudgetExceeded(msg.str(), result_->t.empty() ? t : result_->t.back(), "max_output_rows");
    }

    [[noreturn]] void over_bytes(double t, const char* what) const {
        std::ostringstream msg;
        msg.precision(17);
        msg << "the recorded " << what << " reached " << budget_text() << " at t = " << t << " s after "
            << result_->t.size() << " rows and " << result_->events.size() + result_->stop_events.size()
            << " events; record fewer rows (output_times instead of every step) or raise max_output_bytes";
        throw BudgetExceeded(msg.str(), result_->t.empty() ? t : result_->t.back(), "max_output_bytes");
    }

    [[noreturn]] void out_of_memory(double t, const char* what) const {
        std::ostringstream msg;
        msg.precision(17);
        msg << "out of memory recording " << what << " at t = " << t << " s after " << result_->t.size()
            << " rows (" << mib(static_cast<double>(bytes_)) << " MiB); lower max_output_bytes (now "
            << budget_text() << ") or record fewer rows";
        throw BudgetExceeded(msg.str(), result_->t.empty() ? t : result_->t.back(), "max_output_bytes");
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
    std::size_t max_bytes_;
    std::size_t bytes_ = 0;  ///< recorded so far: rows and events
    std::shared_ptr<Result> result_;
};

/// The hybrid loop's observer: a RowRecorder fed with the system's friction force and mode code.
template <class System>
class Recorder {
public:
    explicit Recorder(const System& system, std::size_t rows_at_least = 0, const SolverOptions& options = {})
        : sys_(system), rows_(system.state_names(), rows_at_least, options) {}

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
