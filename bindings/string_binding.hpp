// What the drill-string bindings (drillstring.cpp, torsional_string.cpp, navarro_lopez.cpp) share beyond common.hpp:
// the readers of their keywords and the stop flag a worker thread's string runs poll. (The construction guard of
// their classes is module.cpp's, as for every class of the extension.)
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include "common.hpp"
#include "simulation.hpp"
#include "table_binding.hpp"

namespace frictionsim::python {

/// NumPy's bool (np.bool_, named "bool" since NumPy 2): a flag like Python's bool.
inline bool is_numpy_bool(py::handle value) {
    const py::handle type = py::type::of(value);
    return py::hasattr(type, "__module__") && py::str(type.attr("__module__")).cast<std::string>() == "numpy" &&
           (py::str(type.attr("__name__")).cast<std::string>() == "bool" ||
            py::str(type.attr("__name__")).cast<std::string>() == "bool_");
}

/// A whole number in [low, high] (a Python int or a NumPy integer, not a bool) as `owner`'s `keyword`: TypeError
/// for another type, InvalidParameter naming it out of range, also beyond a C++ long (2**63 is refused by its value,
/// not by pybind11's "Unable to cast").
inline long long whole_number_from(py::handle value, const char* keyword, const std::string& owner, long long low,
                                   long long high) {
    if (py::isinstance<py::bool_>(value) || is_numpy_bool(value) || !py::hasattr(value, "__index__"))
        throw py::type_error(owner + ": " + keyword + " must be a whole number (got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))) + ")");
    const py::object index = value.attr("__index__")();
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
    if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
    if (overflow != 0 || v < low || v > high)
        throw InvalidParameter(keyword, owner + ": " + keyword + " must be in [" + std::to_string(low) + ", " +
                                            std::to_string(high) + "] (got " + std::string(py::str(index)) + ")");
    return v;
}

/// The stop flag this thread's string runs poll beside Ctrl-C (drillstring.cpp): an object with is_set() (a
/// threading.Event), or null. Worker threads never see a signal (only the main thread runs the handlers), so a
/// map of runs on a thread pool sets a flag they share when the main thread is interrupted.
PyObject*& string_run_stop();

/// SolverOptions::interrupt for a run on this thread: Ctrl-C (the main thread's signal handlers), or this
/// thread's stop flag set. Called with the GIL released; acquires it.
inline std::function<bool()> string_run_interrupt() {
    PyObject* flag = string_run_stop();
    if (flag == nullptr) return &python_signal_raised;
    return [flag] {
        if (python_signal_raised()) return true;
        py::gil_scoped_acquire gil;
        const py::object set = py::reinterpret_borrow<py::object>(flag).attr("is_set")();
        if (!PyObject_IsTrue(set.ptr())) return false;
        PyErr_SetString(PyExc_KeyboardInterrupt, "the run was stopped: its map was interrupted");
        return true;
    };
}

/// The work one string run may ask for, in state-steps (integrator steps times the states each advances): 2e10, about
/// an hour of Dormand-Prince on a StringRig (measured ~200 ns per state-step, 100-300 elements, the -O1 development
/// extension on a loaded 2-core machine; faster optimised) and a few minutes of the Moreau-Jean string (~16 ns per
/// node-state-step, 1000 elements). Legitimate field work stays well inside: 3000 elements over 60 s are ~4e8 (50x
/// below). A request beyond it (1e5 elements over 60 s: ~5e11, a day) is refused before anything is allocated,
/// naming elements when even a minute of simulated time would pass the limit, t_end otherwise.
inline constexpr double max_state_steps = 2e10;

inline void check_run_work(const std::string& owner, double steps, double states, double span, const char* how) {
    const double work = steps * states;
    if (!(work > max_state_steps)) return;
    const bool per_second = steps / span * 60.0 * states > max_state_steps;  // a minute of it: the string's fault
    std::ostringstream msg;
    msg.precision(3);
    msg << owner << ": " << (per_second ? "elements" : "t_end") << " asks for about " << work
        << " state-steps of work (" << steps << " steps x " << states << " states; " << how
        << "), more than the limit of " << max_state_steps
        << " (about an hour on one core): fewer elements or a shorter run";
    throw InvalidParameter(per_second ? "elements" : "t_end", msg.str());
}

/// The fewest steps an explicit method (Dormand-Prince, CVODE Adams) takes on a StringRig over `span` seconds:
/// its stability bound h |lambda_max| <= 4 with |lambda_max| >= omega_max >= max_i sqrt((k_{i-1} + k_i) / J_i)
/// (the Rayleigh quotient of node i alone; axially the same with E A / dx and m_i): a lower bound, so a legitimate
/// run is never refused by it.
template <class Rig>
double explicit_steps_at_least(const Rig& s, double span) {
    const auto& l = s.lumped();
    const std::size_t n = s.elements();
    double w2 = 0.0;
    for (std::size_t i = 0; i <= n; ++i) {
        const double k = (i > 0 ? l.torsional_stiffness[i - 1] : 0.0) + (i < n ? l.torsional_stiffness[i] : 0.0);
        w2 = std::max(w2, k / s.node_inertia()[i]);
        if (s.setup().axial) {
            const double a = (i > 0 ? l.axial_stiffness[i - 1] : 0.0) + (i < n ? l.axial_stiffness[i] : 0.0);
            w2 = std::max(w2, a / s.node_mass()[i]);
        }
    }
    return span * std::sqrt(w2) / 4.0;
}

/// check_run_work for a StringRig's run under `options`: the explicit methods' stability bound (an implicit method,
/// CVODE BDF or RODAS4, has none: its steps are bounded by the rows and the timeout as it runs); also refused when
/// every one of those steps would be recorded past max_output_rows (no output_times: each step is a row).
template <class Rig>
void check_string_rig_work(const std::string& owner, const Rig& s, double t_end, double t_start,
                           const SolverOptions& options) {
    const double span = t_end - t_start;
    if (!(span > 0.0) || !std::isfinite(span)) return;  // the engine refuses these, naming them
    const bool explicit_method = options.method == Method::dormand_prince || options.method == Method::cvode_adams ||
                                 (options.method == Method::automatic && !Rig::stiff);
    if (!explicit_method) return;
    const double steps = explicit_steps_at_least(s, span);
    check_run_work(owner, steps, static_cast<double>(s.state_size()), span,
                   "the explicit method's stability bound on the string's stiffest element");
    if ((options.output_times.empty() || options.record_steps) && steps > static_cast<double>(options.max_output_rows)) {
        std::ostringstream msg;
        msg.precision(3);
        msg << owner << ": t_end asks for at least " << steps << " steps, each a recorded row, more than "
            << "max_output_rows = " << options.max_output_rows << " (the explicit method's stability bound on the "
            << "string's stiffest element): give output_times, fewer elements or a shorter run";
        throw InvalidParameter("t_end", msg.str());
    }
}

}  // namespace frictionsim::python
