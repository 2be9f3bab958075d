// simulate(system, t_end, options): the hybrid loop on the integrator that options.method names
// (Dormand-Prince, or CVODE BDF / Adams; `automatic` asks the system, see resolve_method).
// Includes SUNDIALS; link frictionsim::sundials.
#pragma once

#include "frictionsim.hpp"
#include "sundials/cvode.hpp"

namespace frictionsim {

template <class System>
Result simulate(const System& system, double t_end, const SolverOptions& options = {}, double t_start = 0.0) {
    const Method method = resolve_method<System>(options.method);
    if (method != options.method) {
        SolverOptions resolved = options;
        resolved.method = method;
        return simulate(system, t_end, resolved, t_start);
    }
    if (method == Method::dormand_prince) return simulate_with<DormandPrince>(system, t_end, options, t_start);
    return simulate_with<Cvode>(system, t_end, options, t_start);
}

}  // namespace frictionsim
