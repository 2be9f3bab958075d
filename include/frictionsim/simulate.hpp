// simulate(system, t_end, options): the hybrid loop on the integrator that options.method names
// (Dormand-Prince, or CVODE BDF / Adams). Includes SUNDIALS; link frictionsim::sundials.
#pragma once

#include "frictionsim.hpp"
#include "sundials/cvode.hpp"

namespace frictionsim {

template <class System>
Result simulate(const System& system, double t_end, const SolverOptions& options = {}, double t_start = 0.0) {
    switch (options.method) {
        case Method::dormand_prince: return simulate_with<DormandPrince>(system, t_end, options, t_start);
        case Method::cvode_bdf:
        case Method::cvode_adams: return simulate_with<Cvode>(system, t_end, options, t_start);
    }
    detail::reject("SolverOptions", "method", "one of dormand_prince, cvode_bdf, cvode_adams",
                   static_cast<double>(options.method));
}

}  // namespace frictionsim
