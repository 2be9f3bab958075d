// simulate(model, t_end, options): one entry point for every model. An event-driven system (a lab rig, StringRig)
// runs the hybrid loop on the integrator that options.method names (Dormand-Prince, CVODE BDF / Adams, or
// Rosenbrock; `automatic` asks the system, see resolve_method); a time-stepping model (one that declares
// `time_stepping = true`: TorsionalString) runs solve/time_stepping.hpp's loop with Method::moreau_jean or
// explicit_projection. The choice is made at compile time; the same Result, options and errors either way.
// Includes SUNDIALS; link frictionsim::sundials. Rosenbrock (RODAS4) needs Eigen: link frictionsim::eigen too,
// which defines FRICTIONSIM_EIGEN; without it Method::rosenbrock is refused naming `method`.
#pragma once

#include "frictionsim.hpp"
#include "solve/time_stepping.hpp"
#include "sundials/cvode.hpp"
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
#include "eigen/rosenbrock.hpp"
#endif

namespace frictionsim {

template <class System>
Result simulate(const System& system, double t_end, const SolverOptions& options = {}, double t_start = 0.0) {
    if constexpr (is_time_stepping_model_v<System>) {
        return simulate_time_stepping(system, t_end, options, t_start);
    } else {
        const Method method = resolve_method<System>(options.method);
        if (method != options.method) {
            SolverOptions resolved = options;
            resolved.method = method;
            return simulate(system, t_end, resolved, t_start);
        }
        if (is_time_stepping_method(method)) options.validate(0);  // refused there, naming `method`
        if (method == Method::dormand_prince) return simulate_with<DormandPrince>(system, t_end, options, t_start);
        if (method == Method::rosenbrock) {
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
            return simulate_with<Rodas4>(system, t_end, options, t_start);
#else
            throw InvalidParameter("method", "SolverOptions: method = rosenbrock needs Eigen: link frictionsim::eigen "
                                             "(it defines FRICTIONSIM_EIGEN=1)");
#endif
        }
        return simulate_with<Cvode>(system, t_end, options, t_start);
    }
}

}  // namespace frictionsim
