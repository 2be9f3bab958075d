// Exceptions thrown by frictionsim. Bad input throws InvalidParameter naming the parameter and the rule;
// a run that cannot finish throws SimulationError carrying the time reached and the results up to it.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace frictionsim {

struct Result;

/// A parameter violates a physical rule (negative mass, NaN stiffness, ...). `parameter()` names it.
class InvalidParameter : public std::invalid_argument {
public:
    InvalidParameter(std::string parameter, const std::string& message)
        : std::invalid_argument(message), parameter_(std::move(parameter)) {}
    const std::string& parameter() const noexcept { return parameter_; }

private:
    std::string parameter_;
};

/// The integration stopped before the end time. `time_reached()` is the last time the solution is valid;
/// `partial()` holds everything recorded up to it (may be null when no recorder was attached).
class SimulationError : public std::runtime_error {
public:
    SimulationError(const std::string& message, double time_reached)
        : std::runtime_error(message), time_reached_(time_reached) {}
    double time_reached() const noexcept { return time_reached_; }
    const std::shared_ptr<const Result>& partial() const noexcept { return partial_; }
    void attach_partial(std::shared_ptr<const Result> partial) { partial_ = std::move(partial); }

private:
    double time_reached_;
    std::shared_ptr<const Result> partial_;
};

/// A budget of the run ran out: `budget()` names the option (timeout, max_output_rows); the partial result is kept.
class BudgetExceeded : public SimulationError {
public:
    BudgetExceeded(const std::string& message, double time_reached, std::string budget)
        : SimulationError(message, time_reached), budget_(std::move(budget)) {}
    const std::string& budget() const noexcept { return budget_; }

private:
    std::string budget_;
};

/// The run was asked to stop (SolverOptions::interrupt returned true, or a signal callback of the caller's
/// raised): not a failure of the model. Carries the time reached and the partial result like any stop.
class Interrupted : public SimulationError {
public:
    using SimulationError::SimulationError;
};

/// More switches than the chattering bound allows in one time window (Zeno behaviour or chattering).
class ChatteringError : public SimulationError {
public:
    ChatteringError(const std::string& message, double time_reached, std::string switching_function)
        : SimulationError(message, time_reached), switching_function_(std::move(switching_function)) {}
    const std::string& switching_function() const noexcept { return switching_function_; }

private:
    std::string switching_function_;
};

}  // namespace frictionsim
