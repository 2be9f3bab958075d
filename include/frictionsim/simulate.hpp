// simulate(system, t_end, options): the hybrid loop on the integrator that options.method names
// (Dormand-Prince, CVODE BDF / Adams, or Rosenbrock; `automatic` asks the system, see resolve_method).
// Includes SUNDIALS; link frictionsim::sundials. Rosenbrock (RODAS4) needs Eigen: link frictionsim::eigen too,
// which defines FRICTIONSIM_EIGEN; without it Method::rosenbrock is refused naming `method`.
#pragma once

#include "frictionsim.hpp"
#include "sundials/cvode.hpp"
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
#include "solve/rosenbrock.hpp"
#endif

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

}  // namespace frictionsim
