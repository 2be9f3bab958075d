// Observer that stores output rows (time, states, friction force, mode) and the event log into a Result.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "result.hpp"

namespace frictionsim {

template <class System>
class Recorder {
public:
    explicit Recorder(const System& system, std::size_t expected_rows = 0)
        : sys_(system), result_(std::make_shared<Result>()) {
        for (const char* n : system.state_names()) result_->state_names.emplace_back(n);
        result_->t.reserve(expected_rows);
        result_->states.reserve(expected_rows * System::state_size);
        result_->friction_force.reserve(expected_rows);
        result_->mode.reserve(expected_rows);
    }

    void output(double t, const double* x, int mode) {
        result_->t.push_back(t);
        result_->states.insert(result_->states.end(), x, x + System::state_size);
        result_->friction_force.push_back(sys_.friction_force(t, x, mode));
        result_->mode.push_back(mode);
    }
    void step(double t, const double* x, int mode) { output(t, x, mode); }
    void event(const Event& e, double, const double*) { result_->events.push_back(e); }

    /// Marks how the run ended and hands the result over (shared, so an exception can carry it too).
    std::shared_ptr<Result> finish(bool completed, double t_reached, const SolverStats& stats = {}) {
        result_->completed = completed;
        result_->t_reached = t_reached;
        result_->stats = stats;
        result_->stats.events = static_cast<long>(result_->events.size());
        return result_;
    }

private:
    const System& sys_;
    std::shared_ptr<Result> result_;
};

}  // namespace frictionsim
