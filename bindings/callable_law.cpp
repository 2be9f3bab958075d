// fs.CallableLaw (see callable_law.hpp): the calls into Python, the errors they can end in, and the Python class.
// No rig is instantiated here: the rigs run CallableLaw from axial.cpp, kinematic.cpp and torsional.cpp through
// the law variant, and call force() / state_derivative() below out of line (a Python call costs far more).
#include "callable_law.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "common.hpp"

namespace frictionsim::python {

namespace {

enum class Role { force, state_derivative };

const char* role_name(Role role) { return role == Role::force ? "force" : "state_derivative"; }
const char* role_unit(Role role) { return role == Role::force ? "N" : "1/s times the state's unit"; }

/// Set on this thread when a callable's Exception was left pending for the caller of simulate (see raise_from):
/// the exception translator below then raises that exception instead of the SimulationError it stopped the run
/// with. Only ever read and cleared with the GIL held, by the thread that ran the simulation.
bool& callable_error_pending() {
    thread_local bool pending = false;
    return pending;
}

/// Thrown (with the Python exception pending) when a callable raised an Exception: the engine turns it into the
/// SimulationError that stops the run and carries the partial result.
class CallableRaised : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

std::string format_number(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

/// A real number: float, int, NumPy scalar (not bool, str, None, a sequence or array), as Signal accepts.
bool is_real_number(PyObject* out) {
    if (PyFloat_Check(out)) return true;
    if (PyBool_Check(out)) return false;
    if (PyLong_Check(out)) return true;
    return PyNumber_Check(out) && !PySequence_Check(out) && PyObject_HasAttrString(out, "__float__");
}

}  // namespace

struct CallableLaw::Callables {
    PyObject* force = nullptr;             // owned references
    PyObject* state_derivative = nullptr;  // null: no state derivative, the state stays constant
    std::string label;
    bool stiff = false;

    Callables(py::object f, py::object dz, std::string name, bool stiff_)
        : force(f.release().ptr()), state_derivative(dz.is_none() ? nullptr : dz.release().ptr()),
          label(std::move(name)), stiff(stiff_) {}
    Callables(const Callables&) = delete;
    Callables& operator=(const Callables&) = delete;
    ~Callables() {
        // The last copy of a law goes with its Python object or rig, with the GIL held; be safe anyway.
        if (!Py_IsInitialized()) return;
        const PyGILState_STATE gil = PyGILState_Ensure();
        Py_XDECREF(force);
        Py_XDECREF(state_derivative);
        PyGILState_Release(gil);
    }

    PyObject* function(Role role) const { return role == Role::force ? force : state_derivative; }

    /// "CallableLaw 'name': force (dahl_force)": the law and the callable, for messages. GIL held.
    std::string who(Role role) const {
        std::string function_name = "?";
        PyObject* f = function(role);
        PyObject* qualname = PyObject_GetAttrString(f, "__qualname__");
        if (qualname == nullptr) {
            PyErr_Clear();
            qualname = PyObject_Repr(f);
        }
        if (qualname != nullptr) {
            if (const char* text = PyUnicode_AsUTF8(qualname)) function_name = text;
            Py_DECREF(qualname);
        }
        PyErr_Clear();
        return std::string(CallableLaw::name) + " '" + label + "': " + role_name(role) + " (" + function_name + ")";
    }

    std::string arguments(double v_r, double normal_force, double z) const {
        return "v_r = " + format_number(v_r) + " m/s, normal_force = " + format_number(normal_force) +
               " N, z = " + format_number(z);
    }

    /// The callable raised (the exception is pending): stop the run. A KeyboardInterrupt / SystemExit (no
    /// Exception) is the caller's, not the model's: it stays pending and Interrupted makes simulate raise it
    /// unchanged. An Exception stays pending too, marked for the translator that raises it with the report.
    [[noreturn]] void raise_from(Role role) const {
        const bool stop_request = !PyErr_ExceptionMatches(PyExc_Exception);
        std::string what = "an exception";
        {
            PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
            PyErr_Fetch(&type, &value, &traceback);
            PyErr_NormalizeException(&type, &value, &traceback);
            if (type != nullptr) what = reinterpret_cast<PyTypeObject*>(type)->tp_name;
            if (value != nullptr) {
                if (PyObject* text = PyObject_Str(value)) {
                    if (const char* utf8 = PyUnicode_AsUTF8(text); utf8 != nullptr && *utf8 != '\0')
                        what += std::string(": ") + utf8;
                    Py_DECREF(text);
                }
                PyErr_Clear();
            }
            PyErr_Restore(type, value, traceback);  // pending again, unchanged
        }
        // who() calls Python: keep the pending exception out of its way
        PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
        PyErr_Fetch(&type, &value, &traceback);
        const std::string message = who(role) + " raised " + what;
        PyErr_Restore(type, value, traceback);
        if (stop_request) throw Interrupted(message, 0.0);  // the engine puts the time reached in
        callable_error_pending() = true;
        throw CallableRaised(message);
    }

    /// function(v_r, normal_force, z) as a finite double. GIL released on entry.
    double call(Role role, double v_r, double normal_force, double z) const {
        py::gil_scoped_acquire gil;
        PyObject* args[3] = {PyFloat_FromDouble(v_r), PyFloat_FromDouble(normal_force), PyFloat_FromDouble(z)};
        PyObject* out = nullptr;
        if (args[0] != nullptr && args[1] != nullptr && args[2] != nullptr) {
#if PY_VERSION_HEX >= 0x03090000
            out = PyObject_Vectorcall(function(role), args, 3, nullptr);
#else
            out = PyObject_CallFunctionObjArgs(function(role), args[0], args[1], args[2], nullptr);
#endif
        }
        for (PyObject* a : args) Py_XDECREF(a);
        if (out == nullptr) raise_from(role);
        double value;
        if (PyFloat_CheckExact(out)) {
            value = PyFloat_AS_DOUBLE(out);
        } else if (is_real_number(out)) {
            value = PyFloat_AsDouble(out);
            if (value == -1.0 && PyErr_Occurred()) {  // a __float__ that raised
                Py_DECREF(out);
                raise_from(role);
            }
        } else {
            const std::string type = Py_TYPE(out)->tp_name;
            std::string shown;
            if (PyObject* r = PyObject_Repr(out)) {
                if (const char* utf8 = PyUnicode_AsUTF8(r)) shown = utf8;
                Py_DECREF(r);
            }
            PyErr_Clear();
            Py_DECREF(out);
            if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
            throw InvalidParameter(role_name(role), who(role) + " must return a real number [" + role_unit(role) +
                                                        "], got " + type + " " + shown + " at " +
                                                        arguments(v_r, normal_force, z));
        }
        Py_DECREF(out);
        if (!std::isfinite(value))
            throw InvalidParameter(role_name(role), who(role) + " must return a finite number [" + role_unit(role) +
                                                        "], got " + format_number(value) + " at " +
                                                        arguments(v_r, normal_force, z));
        return value;
    }
};

CallableLaw::CallableLaw(py::object force, py::object state_derivative, std::string label, bool stiff)
    : callables_(std::make_shared<const Callables>(std::move(force), std::move(state_derivative), std::move(label),
                                                   stiff)) {}

double CallableLaw::force(double v_r, double normal_force, const double* z, int) const {
    return callables_->call(Role::force, v_r, normal_force, z[0]);
}

void CallableLaw::state_derivative(double v_r, double normal_force, const double* z, int, double* dz) const {
    dz[0] = callables_->state_derivative != nullptr ? callables_->call(Role::state_derivative, v_r, normal_force, z[0])
                                                    : 0.0;
}

const std::string& CallableLaw::label() const { return callables_->label; }
bool CallableLaw::is_stiff() const { return callables_->stiff; }
int CallableLaw::declared_state_count() const { return callables_->state_derivative != nullptr ? 1 : 0; }
py::object CallableLaw::force_function() const { return py::reinterpret_borrow<py::object>(callables_->force); }
py::object CallableLaw::state_derivative_function() const {
    if (callables_->state_derivative == nullptr) return py::none();
    return py::reinterpret_borrow<py::object>(callables_->state_derivative);
}

namespace {

/// Hangs the run's report on the callable's exception, as fs.SimulationError carries it: time_reached [s],
/// partial (a frictionsim.Result up to there) and, from Python 3.11, a note saying so. Never raises.
void attach_report(py::handle exception, const SimulationError& stop) {
    const auto set = [&](const char* attribute, const py::object& value) {
        if (PyObject_SetAttrString(exception.ptr(), attribute, value.ptr()) != 0) PyErr_Clear();
    };
    try {
        set("time_reached", py::float_(stop.time_reached()));
        py::object partial = py::none();
        if (stop.partial())
            partial = py::module_::import("frictionsim.result")
                          .attr("Result")(py::cast(std::const_pointer_cast<Result>(stop.partial())));
        set("partial", partial);
        if (py::hasattr(exception, "add_note"))
            exception.attr("add_note")("frictionsim.simulate stopped at t = " + format_number(stop.time_reached()) +
                                       " s (" + stop.what() + "); the results up to there are in .partial");
    } catch (py::error_already_set&) {
        // the report is a courtesy: the user's exception goes out as it is
    }
}

}  // namespace

void register_callable_law(py::module_& m) {
    // Tried before register_errors' translator (pybind11 tries the last registered first): a SimulationError
    // that a callable's Exception caused is raised as that Exception. Anything else passes on.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Interrupted&) {
            throw;  // simulate_variant raises the pending KeyboardInterrupt / SystemExit itself
        } catch (const SimulationError& e) {
            const bool ours = std::exchange(callable_error_pending(), false);
            if (!ours || !PyErr_Occurred()) throw;
            py::error_already_set raised;  // takes the pending exception: the callable's own object
            attach_report(raised.value(), e);
            raised.restore();
        }
    });

    py::class_<CallableLaw>(m, "CallableLaw", R"doc(
A friction law written in Python: the friction force and the state rate are Python callables,

    F = force(v_r, normal_force, z)                   [N]
    dz/dt = state_derivative(v_r, normal_force, z)    [unit of z per s]

with v_r the relative velocity [m/s], normal_force N [N] and z the law's one state (``law_state`` in the
results; 0 unless the rig's initial state says otherwise). Without a state_derivative (state_count = 0) z never
changes. Every rig runs it (AxialVibrationRig, KinematicRig, TorsionalRig), with every method.

The slow path: the GIL is re-acquired for every call, one call of each callable per right-hand-side
evaluation (bench/callable_law.py measured ~0.1 microseconds per call for Dahl's one-line functions: the axial
rig ran 10x slower than with fs.Dahl under Dormand-Prince, 1.5x under CVODE), and threads running CallableLaw
rigs take turns. There is no kink event at v_r = 0 (the callables see v_r and may use its sign) and no analytic
Jacobian: CVODE builds one from difference quotients.

Errors: an exception raised by a callable stops the run and propagates from simulate() unchanged (its type,
message and traceback), carrying the run's report as fs.SimulationError does: ``time_reached`` [s] and
``partial`` (the Result up to there). KeyboardInterrupt and SystemExit propagate unchanged. A callable
returning anything but a finite real number stops the run with fs.SimulationError naming it.

Pickling stores the callables by reference (module-level functions pickle; lambdas and closures do not).

Parameters
----------
force : callable (v_r, normal_force, z) -> float
    Friction force F [N], opposing the sliding (positive for v_r > 0 in the engine's sign convention).
state_derivative : callable (v_r, normal_force, z) -> float, optional
    dz/dt of the law's state. None: a stateless law (state_count 0).
state_count : {0, 1}, optional
    0 without state_derivative, 1 with it (the default follows state_derivative; a contradiction is an error).
name : str
    The law's name in errors and repr.
stiff : bool
    simulate(method="automatic") picks CVODE BDF for it, as for the engine's stiff laws (LuGre, ElastoPlastic).
)doc")
        .def(py::init([](py::object force, py::object state_derivative, py::object state_count, py::object name,
                         py::object stiff) {
                 if (!PyCallable_Check(force.ptr()))
                     throw py::type_error("CallableLaw: force must be a callable (v_r, normal_force, z) -> F [N], got " +
                                          std::string(py::str(py::type::of(force).attr("__name__"))));
                 if (!state_derivative.is_none() && !PyCallable_Check(state_derivative.ptr()))
                     throw py::type_error(
                         "CallableLaw: state_derivative must be a callable (v_r, normal_force, z) -> dz/dt or None, "
                         "got " + std::string(py::str(py::type::of(state_derivative).attr("__name__"))));
                 const int states = state_derivative.is_none() ? 0 : 1;
                 if (!state_count.is_none()) {
                     // an integer (NumPy's too), not a bool or a float
                     const bool integer = !PyBool_Check(state_count.ptr()) && PyIndex_Check(state_count.ptr());
                     const int given = !integer                                   ? -1
                                       : state_count.equal(py::int_(0))         ? 0
                                       : state_count.equal(py::int_(1))         ? 1
                                                                                 : -1;
                     if (given < 0)
                         throw InvalidParameter("state_count", "CallableLaw: state_count must be 0 or 1 (got " +
                                                                   std::string(py::repr(state_count)) + ")");
                     if (given == 1 && states == 0)
                         throw InvalidParameter("state_derivative",
                                                "CallableLaw: state_count = 1 needs a state_derivative callable");
                     if (given == 0 && states == 1)
                         throw InvalidParameter("state_count",
                                                "CallableLaw: state_count must be 1 with a state_derivative (got 0)");
                 }
                 if (!py::isinstance<py::str>(name))
                     throw py::type_error("CallableLaw: name must be a str, got " +
                                          std::string(py::str(py::type::of(name).attr("__name__"))));
                 if (!PyBool_Check(stiff.ptr()))
                     throw InvalidParameter("stiff", "CallableLaw: stiff must be True or False (got " +
                                                         std::string(py::repr(stiff)) + ")");
                 return CallableLaw(std::move(force), std::move(state_derivative), name.cast<std::string>(),
                                    stiff.ptr() == Py_True);
             }),
             py::arg("force"), py::arg("state_derivative") = py::none(), py::kw_only(),
             py::arg("state_count") = py::none(), py::arg("name") = CallableLaw::name, py::arg("stiff") = false)
        .def_property_readonly("force", &CallableLaw::force_function, "The friction-force callable.")
        .def_property_readonly("state_derivative", &CallableLaw::state_derivative_function,
                               "The state-rate callable, or None.")
        .def_property_readonly("state_count", &CallableLaw::declared_state_count,
                               "1 with a state_derivative, else 0 (the rigs still carry the constant state).")
        .def_property_readonly("name", &CallableLaw::label, "The law's name in errors and repr.")
        .def_property_readonly("stiff", &CallableLaw::is_stiff, "simulate(method='automatic') picks CVODE BDF.")
        .def("__repr__", [](const CallableLaw& law) {
            std::string out = "CallableLaw(force=" + std::string(py::repr(law.force_function()));
            if (law.declared_state_count() == 1)
                out += ", state_derivative=" + std::string(py::repr(law.state_derivative_function()));
            out += ", name=" + std::string(py::repr(py::str(law.label())));
            if (law.is_stiff()) out += ", stiff=True";
            return out + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& law = self.cast<const CallableLaw&>();
            return reduce_by_construction(
                self, py::make_tuple(law.force_function(), law.state_derivative_function()),
                py::dict(py::arg("state_count") = law.declared_state_count(), py::arg("name") = law.label(),
                         py::arg("stiff") = law.is_stiff()));
        });
    py::object cls = m.attr("CallableLaw");
    cls.attr("has_stick") = CallableLaw::has_stick;
    cls.attr("state_names") = py::make_tuple(CallableLaw::state_names[0]);
}

}  // namespace frictionsim::python
