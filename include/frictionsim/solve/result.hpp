// What a simulation returns: output rows (time, states, friction force, mode), the event log, solver counters.
// Plain vectors, row-major states, so Python can wrap them without more than one copy.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace frictionsim {

/// One switch of the hybrid system (which switching function fired, the modes and states around it), or one
/// crossing of a user's stop condition (solve/stop_conditions.hpp).
struct Event {
    double time = 0.0;
    int switching_function = -1;  ///< index of the guard that fired; for a stop condition, the condition's index
    std::string name;             ///< its name, e.g. "relative_velocity"
    int mode_before = 0;
    int mode_after = 0;
    std::string mode_before_name;
    std::string mode_after_name;
    /// The state just before the switch and just after it (a switch may project it, e.g. a speed set to exactly
    /// zero on entering stick); empty when SolverOptions::record_event_states is off.
    std::vector<double> state_before, state_after;
    int stop_condition = -1;  ///< >= 0: this is a stop condition's crossing (Result::stop_events), not a switch
    int direction = 0;        ///< a stop condition's crossing: -1 falling, +1 rising
};

struct SolverStats {
    long steps = 0;
    long rhs_evaluations = 0;
    long jacobian_evaluations = 0;
    long guard_evaluations = 0;
    long error_test_failures = 0;
    long restarts = 0;  ///< the integrator restarted (after a switch); time-stepping: stepper instances rebuilt
    long events = 0;    ///< entries of Result::events
    // The time-stepping methods (0 for the ODE methods):
    long contact_switches = 0;  ///< captured contacts that changed mode, summed over steps
    long factorisations = 0;    ///< LDL^T factorisations (or updates) of the step's operator with the stuck set
    long linear_solves = 0;     ///< solves with it: one per active-set iteration (the one-step LCP)
    long location_trials = 0;   ///< trial steps that located the exactly treated switches
};

struct Result {
    std::vector<std::string> state_names;
    std::vector<double> t;
    std::vector<double> states;          ///< row-major, t.size() x state_names.size()
    std::vector<double> friction_force;  ///< N (or N m for torsional rigs), one per row
    std::vector<int> mode;               ///< mode at each row
    std::vector<Event> events;
    std::vector<Event> stop_events;      ///< crossings of SolverOptions::stop_conditions, in time order
    SolverStats stats;
    bool completed = false;              ///< false when the run stopped early (see SimulationError)
    /// SciPy's solve_ivp status: 0 reached t_end, 1 a terminal stop condition ended the run, -1 failed.
    int status = 0;
    std::string message;                 ///< what `status` means for this run, in words
    std::vector<std::string> warnings;   ///< why a completed result may be unreliable (e.g. a loose rtol)
    double t_reached = 0.0;

    std::size_t state_count() const { return state_names.size(); }
    std::size_t rows() const { return t.size(); }
    double state(std::size_t row, std::size_t column) const { return states[row * state_count() + column]; }
    /// Column index of a named state; throws std::out_of_range when there is none.
    std::size_t column(const std::string& name) const {
        for (std::size_t i = 0; i < state_names.size(); ++i)
            if (state_names[i] == name) return i;
        throw std::out_of_range("Result: no state named '" + name + "'");
    }
    std::vector<double> column_values(const std::string& name) const {
        const std::size_t c = column(name);
        std::vector<double> out(rows());
        for (std::size_t r = 0; r < rows(); ++r) out[r] = state(r, c);
        return out;
    }
};

}  // namespace frictionsim
