// simulate_with<Integrator>(system, t_end, options): run the hybrid loop and record a Result. When
// options.output_times is empty every internal step is recorded. A failed run throws SimulationError
// carrying the result up to the time reached.
#pragma once

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include "../error.hpp"
#include "hybrid_loop.hpp"
#include "recorder.hpp"

namespace frictionsim {

inline std::string loose_tolerance_warning(double rtol) {
    std::ostringstream msg;
    msg << "rtol = " << rtol << " is looser than " << SolverOptions::reliable_rtol
        << ": the error estimate is not reliable there (cycle means of a stick-slip rig can be off by a factor); "
           "check the result at a tighter rtol";
    return msg.str();
}

template <template <class> class Integrator, class System>
Result simulate_with(const System& system, double t_end, const SolverOptions& options, double t_start = 0.0) {
    if constexpr (!check_hybrid_system<System>()) {
        return Result{};  // not reached: check_hybrid_system's static_assert has named what System misses
    } else {
    const SolverOptions* opts = &options;
    SolverOptions every_step;
    if (options.output_times.empty() && !options.record_steps) {
        every_step = options;
        every_step.record_steps = true;
        opts = &every_step;
    }
    Recorder<System> recorder(system, options.output_times.size(), options);
    try {
        auto outcome = integrate_hybrid<Integrator>(system, system.initial_state(), t_start, t_end, *opts, recorder);
        Result result = std::move(*recorder.finish(true, outcome.time, outcome.stats, outcome.stopped));
        if (options.rtol > SolverOptions::reliable_rtol) result.warnings.push_back(loose_tolerance_warning(options.rtol));
        return result;
    } catch (SimulationError& e) {
        const std::shared_ptr<Result> partial = recorder.finish(false, e.time_reached());
        partial->message = e.what();
        e.attach_partial(partial);
        throw;
    }
    }
}

}  // namespace frictionsim
