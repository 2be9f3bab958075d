// simulate(model, t_end, options): one entry point for every model. An event-driven system (a lab rig, StringRig)
// runs the hybrid loop on the integrator that options.method names (Dormand-Prince, CVODE BDF / Adams, or
// Rosenbrock; `automatic` asks the system, see resolve_method); a time-stepping model (one that declares
// `time_stepping = true`: TorsionalString) runs solve/time_stepping.hpp's loop with Method::moreau_jean or
// explicit_projection; a model that chooses its engine (string/string_model.hpp's StringModel: a string and the
// treatment of its contacts) runs the one it chose. The choice of loop is made at compile time; the same Result,
// options and errors either way.
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

namespace detail {
/// Does a model choose its engine (`static constexpr bool chooses_engine = true`, string/string_model.hpp)? It then
/// runs itself, handed simulate() for the event-driven system it may run.
template <class T, class = void>
struct chooses_engine : std::false_type {};
template <class T>
struct chooses_engine<T, std::void_t<decltype(T::chooses_engine)>> : std::bool_constant<T::chooses_engine> {};
}  // namespace detail

template <class System>
Result simulate(const System& system, double t_end, const SolverOptions& options = {}, double t_start = 0.0) {
    if constexpr (detail::chooses_engine<System>::value) {
        return system.run(t_end, options, t_start,
                          [](const auto& engine, double end, const SolverOptions& o, double start) {
                              return simulate(engine, end, o, start);
                          });
    } else if constexpr (is_time_stepping_model_v<System>) {
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
