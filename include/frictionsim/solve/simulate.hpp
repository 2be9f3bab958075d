// simulate_with<Integrator>(system, t_end, options): run the hybrid loop and record a Result. When
// options.output_times is empty every internal step is recorded. A failed run throws SimulationError
// carrying the result up to the time reached.
#pragma once

#include <memory>
#include <utility>

#include "../error.hpp"
#include "hybrid_loop.hpp"
#include "recorder.hpp"

namespace frictionsim {

template <template <class> class Integrator, class System>
Result simulate_with(const System& system, double t_end, const SolverOptions& options, double t_start = 0.0) {
    const SolverOptions* opts = &options;
    SolverOptions every_step;
    if (options.output_times.empty() && !options.record_steps) {
        every_step = options;
        every_step.record_steps = true;
        opts = &every_step;
    }
    Recorder<System> recorder(system, options.output_times.size());
    try {
        auto outcome = integrate_hybrid<Integrator>(system, system.initial_state(), t_start, t_end, *opts, recorder);
        return std::move(*recorder.finish(true, t_end, outcome.stats));
    } catch (SimulationError& e) {
        e.attach_partial(recorder.finish(false, e.time_reached()));
        throw;
    }
}

}  // namespace frictionsim
