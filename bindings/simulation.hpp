// Running a rig variant from Python: the GIL is released for the whole integration, so simulations in threads
// run in parallel (a Python callable signal re-acquires it per call). Ctrl-C is polled between steps (the engine's
// SolverOptions::interrupt), so it stops any run within a fraction of a second as KeyboardInterrupt.
// CVODE is compiled in only where the extension links frictionsim::sundials (FRICTIONSIM_SUNDIALS=1), RODAS4
// (Method::rosenbrock) only where it links frictionsim::eigen (FRICTIONSIM_EIGEN=1).
#pragma once

#include <memory>
#include <string>
#include <variant>

#if defined(FRICTIONSIM_SUNDIALS) && FRICTIONSIM_SUNDIALS
#include <frictionsim/simulate.hpp>
#else
#include <frictionsim/error.hpp>
#include <frictionsim/solve/dormand_prince.hpp>
#include <frictionsim/solve/options.hpp>
#include <frictionsim/solve/simulate_with.hpp>
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
#include <frictionsim/eigen/rosenbrock.hpp>
#endif
#endif

#include "common.hpp"

namespace frictionsim::python {

/// Whether this extension was built with SUNDIALS (CVODE BDF / Adams): frictionsim._core.HAS_SUNDIALS.
#if defined(FRICTIONSIM_SUNDIALS) && FRICTIONSIM_SUNDIALS
inline constexpr bool has_sundials = true;
#else
inline constexpr bool has_sundials = false;
#endif
/// Whether this extension was built with Eigen (RODAS4, the Moreau-Jean string): frictionsim._core.HAS_EIGEN.
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
inline constexpr bool has_eigen = true;
#else
inline constexpr bool has_eigen = false;
#endif

/// Method::rosenbrock in an extension without Eigen: refused saying how to get it.
inline void require_eigen_for(Method method) {
    if (method == Method::rosenbrock && !has_eigen)
        throw InvalidParameter("method", "simulate: method = rosenbrock (RODAS4) needs Eigen, and this frictionsim "
                                         "extension was built without it (frictionsim._core.HAS_EIGEN is False): "
                                         "install Eigen 3 (Debian: libeigen3-dev) and reinstall frictionsim from "
                                         "source, or use another method");
}

/// simulate() on the integrators this extension has. Built without SUNDIALS, only Dormand-Prince is compiled
/// in: `automatic` takes it for every law (stiff ones need more, smaller steps but keep their accuracy), and a
/// CVODE method asked for by name is refused saying how to get it.
template <class System>
Result simulate_built_in(const System& system, double t_end, const SolverOptions& options, double t_start) {
    require_eigen_for(options.method);
#if defined(FRICTIONSIM_SUNDIALS) && FRICTIONSIM_SUNDIALS
    return simulate(system, t_end, options, t_start);
#else
    if (is_time_stepping_method(options.method))  // below, every other method becomes dormand_prince
        throw InvalidParameter("method", std::string("simulate: method = ") + method_name(options.method) +
                                             " steps time-stepping models (TorsionalString), not this rig");
    const bool cvode = options.method == Method::cvode_bdf || options.method == Method::cvode_adams;
    if (cvode) {
        throw InvalidParameter("method", std::string("simulate: method = ") + method_name(options.method) +
                                             " needs SUNDIALS CVODE, and this frictionsim extension was built "
                                             "without SUNDIALS (frictionsim._core.HAS_SUNDIALS is False): use "
                                             "method = \"dormand_prince\", or install SUNDIALS (Debian: "
                                             "libsundials-dev) and reinstall frictionsim from source (pip "
                                             "install --no-binary frictionsim frictionsim, or pip install . "
                                             "in a clone; -C cmake.define.FRICTIONSIM_SUNDIALS=ON makes "
                                             "SUNDIALS required)");
    }
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
    if (options.method == Method::rosenbrock) return simulate_with<Rodas4>(system, t_end, options, t_start);
#endif
    SolverOptions resolved = options;
    resolved.method = Method::dormand_prince;
    return simulate_with<DormandPrince>(system, t_end, resolved, t_start);
#endif
}

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
                // CallableLaw(stiff=True): automatic is CVODE BDF where the extension has it
                if (has_sundials) resolve_callable_law_method(system, polled);
                return std::make_shared<Result>(simulate_built_in(system, t_end, polled, t_start));
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
