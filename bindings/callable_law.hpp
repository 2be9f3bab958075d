// fs.CallableLaw: a friction law written in Python. The friction force F(v_r, N, z) and the state rate
// dz/dt(v_r, N, z) are Python callables, called with the GIL re-acquired (the slow path, as the kinematic rig's
// callable signals): every rig runs it, one variant alternative beside the engine's laws (PythonLaws in
// common.hpp). To the engine it is a state law with one state and no kink at v_r = 0 and no analytic partials,
// so the rigs have no Jacobian and CVODE builds one from difference quotients.
//
// Errors: an Exception raised by a callable stops the run and reaches the caller of fs.simulate unchanged (its
// type, message and traceback) with the run's report attached, `.time_reached` [s] and `.partial` (the Result up
// to there), as fs.SimulationError carries them; a KeyboardInterrupt or SystemExit propagates unchanged like
// Ctrl-C. A callable returning anything but a finite real number stops the run with a SimulationError naming it.
#pragma once

#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include <frictionsim/frictionsim.hpp>

namespace frictionsim::python {

namespace py = pybind11;

class CallableLaw {
public:
    static constexpr const char* name = "CallableLaw";
    static constexpr bool has_stick = false;
    static constexpr bool kink_at_zero_velocity = false;  ///< the callables see v_r itself; no branch to switch
    /// Always one state in the rigs; a law made with state_count = 0 keeps it constant (dz/dt = 0).
    static constexpr std::size_t state_count = 1;
    static constexpr std::array<const char*, 1> state_names{"law_state"};

    /// `force` callable, `state_derivative` callable or None (then the state is constant), `label` the name
    /// errors and repr use, `stiff`: simulate(method="automatic") picks CVODE BDF. Call with the GIL held.
    CallableLaw(py::object force, py::object state_derivative, std::string label, bool stiff);

    /// F [N] = force(v_r, normal_force, z). Called with the GIL released: re-acquires it.
    double force(double v_r, double normal_force, const double* z, int branch) const;
    /// dz/dt = state_derivative(v_r, normal_force, z), or 0 without one. Called with the GIL released.
    void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const;

    const std::string& label() const;
    bool is_stiff() const;
    /// 1 with a state_derivative callable, else 0 (the state stays at its initial value).
    int declared_state_count() const;
    /// The callables (None for a missing state_derivative). Call with the GIL held.
    py::object force_function() const;
    py::object state_derivative_function() const;

    struct Callables;  // the Python objects and settings, shared by copies (a law is copied into every rig)

private:
    std::shared_ptr<const Callables> callables_;
};

/// Method::automatic on a rig whose law is a CallableLaw(stiff=True) becomes CVODE BDF, as a law declaring
/// `static constexpr bool stiff = true` gets; any other rig or method is left as it is.
namespace callable_law_detail {
template <class System, class = void>
struct runs_callable_law : std::false_type {};
template <class System>
struct runs_callable_law<System, std::void_t<decltype(std::declval<const System&>().law())>>
    : std::is_same<std::decay_t<decltype(std::declval<const System&>().law())>, CallableLaw> {};
}  // namespace callable_law_detail

template <class System>
void resolve_callable_law_method(const System& system, SolverOptions& options) {
    if constexpr (callable_law_detail::runs_callable_law<System>::value) {
        if (options.method == Method::automatic && system.law().is_stiff()) options.method = Method::cvode_bdf;
    } else {
        (void)system, (void)options;
    }
}


}  // namespace frictionsim::python
