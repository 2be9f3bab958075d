// Running a rig variant from Python: the GIL is released for the whole integration, so simulations in threads
// run in parallel (a Python callable signal re-acquires it per call).
#pragma once

#include <memory>
#include <variant>

#include <frictionsim/simulate.hpp>

#include "common.hpp"

namespace frictionsim::python {

template <class RigVariant>
std::shared_ptr<Result> simulate_variant(const RigVariant& rig, double t_end, const SolverOptions& options,
                                         double t_start) {
    py::gil_scoped_release release;
    return std::visit(
        [&](const auto& system) { return std::make_shared<Result>(simulate(system, t_end, options, t_start)); },
        rig);
}

/// One rig type per law, built from a FrictionLaw: std::variant<Rig<Coulomb>, Rig<Stribeck>, ...>.
template <template <class> class Rig>
using RigVariant = std::variant<Rig<Coulomb>, Rig<Stribeck>, Rig<Dahl>, Rig<LuGre>, Rig<ElastoPlastic>>;

}  // namespace frictionsim::python
