// Running a rig variant from Python: the GIL is released for the whole integration, so simulations in threads
// run in parallel (a Python callable signal re-acquires it per call). Ctrl-C is polled between steps (the engine's
// SolverOptions::interrupt), so it stops any run within a fraction of a second as KeyboardInterrupt.
#pragma once

#include <memory>
#include <variant>

#include <frictionsim/simulate.hpp>

#include "common.hpp"

namespace frictionsim::python {

/// True when a Python signal handler raised (the error is then pending on this thread); checked with the GIL
/// re-acquired. Only the main thread runs signal handlers: elsewhere this is always false.
bool python_signal_raised();

/// Raises the Python error that stopped a run (Ctrl-C's KeyboardInterrupt, a callable's SystemExit), unchanged.
[[noreturn]] void raise_pending_python_error();

template <class RigVariant>
std::shared_ptr<Result> simulate_variant(const RigVariant& rig, double t_end, const SolverOptions& options,
                                         double t_start) {
    SolverOptions polled = options;
    polled.interrupt = &python_signal_raised;
    try {
        py::gil_scoped_release release;
        return std::visit(
            [&](const auto& system) {
                resolve_callable_law_method(system, polled);  // CallableLaw(stiff=True): automatic is CVODE BDF
                return std::make_shared<Result>(simulate(system, t_end, polled, t_start));
            },
            rig);
    } catch (const Interrupted&) {
        raise_pending_python_error();
    }
}

/// One rig type per law of a list: std::variant<Rig<Coulomb>, Rig<Stribeck>, ...> (PythonLaws by default).
template <template <class> class Rig, class Laws>
struct rig_variant;
template <template <class> class Rig, class... Law>
struct rig_variant<Rig, TypeList<Law...>> {
    using type = std::variant<Rig<Law>...>;
};
template <template <class> class Rig, class Laws = PythonLaws>
using RigVariant = typename rig_variant<Rig, Laws>::type;

}  // namespace frictionsim::python
