// Results, solver options and errors for Python. A Result's columns are copied once into NumPy arrays by the
// Python wrapper (frictionsim.result.Result); C++ exceptions become the Python classes of frictionsim.errors,
// SimulationError carrying the time reached and the partial result.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"

namespace frictionsim::python {

namespace {

template <class T>
py::array_t<T> to_array(const std::vector<T>& v) {
    // allocated, then filled: pybind11's array_t(size, data) does not check the copy it makes, and out of memory it
    // returned a null array that reshape dereferenced (a segfault); this raises MemoryError instead
    py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
    if (!v.empty()) std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::object python_error(const char* name) { return py::module_::import("frictionsim.errors").attr(name); }

void raise(const py::object& type, const py::object& instance) { PyErr_SetObject(type.ptr(), instance.ptr()); }

/// A run's events without its columns: frictionsim.Result builds its event list from this only when asked.
struct EventLog {
    std::vector<Event> events;
};

/// The run up to the failure as a frictionsim.Result (so frictionsim.errors needs nothing of the package).
py::object partial_result(const SimulationError& e) {
    if (!e.partial()) return py::none();
    try {
        return py::module_::import("frictionsim.result").attr("Result")(std::const_pointer_cast<Result>(e.partial()));
    } catch (py::error_already_set& copy) {
        // out of memory copying it into NumPy (a run stopped by memory): the error, without its partial result
        if (!copy.matches(PyExc_MemoryError)) throw;
        return py::none();
    }
}

}  // namespace

bool python_signal_raised() {
    py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() != 0;
}

void raise_pending_python_error() {
    if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
}

void register_errors(py::module_&) {
    // Order matters: the most derived C++ class first.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const BudgetExceeded& e) {
            const py::object type = python_error("BudgetExceededError");
            raise(type, type(e.what(), e.time_reached(), partial_result(e), e.budget()));
        } catch (const ChatteringError& e) {
            const py::object type = python_error("ChatteringError");
            raise(type, type(e.what(), e.time_reached(), partial_result(e), e.switching_function()));
        } catch (const SimulationError& e) {
            const py::object type = python_error("SimulationError");
            raise(type, type(e.what(), e.time_reached(), partial_result(e)));
        } catch (const InvalidParameter& e) {
            const py::object type = python_error("InvalidParameterError");
            raise(type, type(e.what(), e.parameter()));
        } catch (const py::reference_cast_error&) {
            // pybind11 found no C++ value behind an instance it was to pass by reference: one made by __new__ (or an
            // incomplete pickle) and never constructed, or None where an object is required
            PyErr_SetString(PyExc_TypeError,
                            "an argument (or self) was never constructed (made by its class's __new__ or an "
                            "incomplete pickle) or is None: build it with its class(...)");
        }
    });
}

void register_results(py::module_& m) {
    py::enum_<Method>(m, "Method", "Integrator of the hybrid event loop.")
        .value("automatic", Method::automatic,
               "cvode_bdf for stiff laws (LuGre, ElastoPlastic), dormand_prince otherwise")
        .value("dormand_prince", Method::dormand_prince, "explicit RK5(4), dense output, root location")
        .value("cvode_bdf", Method::cvode_bdf, "SUNDIALS CVODE BDF + Newton, dense linear solver")
        .value("cvode_adams", Method::cvode_adams, "SUNDIALS CVODE Adams-Moulton + fixed point")
        .value("rosenbrock", Method::rosenbrock, "RODAS4 (linearly implicit, stiff; needs Eigen: HAS_EIGEN)")
        .value("moreau_jean", Method::moreau_jean,
               "time-stepping models (TorsionalString): Moreau-Jean's theta-method, contacts captured; step, theta")
        .value("explicit_projection", Method::explicit_projection,
               "time-stepping models: the field codes' explicit scheme (step below the element's wave transit)");

    py::enum_<LinearSolver>(m, "LinearSolver", "Linear solver of CVODE BDF's Newton iteration.")
        .value("automatic", LinearSolver::automatic, "band when the system declares a banded Jacobian, else dense")
        .value("dense", LinearSolver::dense, "dense LU: the lab rigs' few states")
        .value("band", LinearSolver::band, "band LU: a drill string's nodes couple only their neighbours")
        .value("sparse", LinearSolver::sparse, "KLU (SuiteSparse) on the system's sparsity pattern");

    py::enum_<ContactSolverChoice>(m, "ContactSolver",
                                   "Solver of moreau_jean's one-step contact problem (SolverOptions.contact_solver).")
        .value("active_set", ContactSolverChoice::active_set,
               "the exact active set (on a string, its chain LDL^T updated from the switched contacts)")
        .value("projected_gauss_seidel", ContactSolverChoice::projected_gauss_seidel,
               "projected Gauss-Seidel sweeps (Jean 1999): the same steps where the law is monotone (static == "
               "kinetic), slower");

    py::class_<StopCondition>(m, "StopCondition",
                              "A stop condition evaluated in the engine as the run goes (SciPy solve_ivp's events): a "
                              "state crossing a level, or a switch into a named mode. Its crossings are logged "
                              "(Result.t_events, y_events); a terminal one ends the run there (Result.status 1).")
        .def(py::init([](const std::string& state, double level, int direction, const std::string& mode,
                         bool terminal, const std::string& name) {
                 return StopCondition{state, level, direction, mode, terminal, name};
             }),
             py::kw_only(), py::arg("state") = "", py::arg("level") = 0.0, py::arg("direction") = 0,
             py::arg("mode") = "", py::arg("terminal") = true, py::arg("name") = "",
             "state: a state's name, whose crossing of `level` counts (direction -1 falling, +1 rising, 0 both); or "
             "mode: a switch into a mode of this name counts (e.g. 'stick'). terminal: the first crossing ends the run.")
        .def_readwrite("state", &StopCondition::state)
        .def_readwrite("level", &StopCondition::level)
        .def_readwrite("direction", &StopCondition::direction)
        .def_readwrite("mode", &StopCondition::mode)
        .def_readwrite("terminal", &StopCondition::terminal)
        .def_readwrite("name", &StopCondition::name)
        .def("__repr__", [](const StopCondition& c) {
            const std::string kind = c.state.empty() ? "mode='" + c.mode + "'"
                                                     : "state='" + c.state + "', level=" +
                                                           std::string(py::str(py::float_(c.level))) +
                                                           ", direction=" + std::to_string(c.direction);
            return "StopCondition(" + kind + ", terminal=" + (c.terminal ? "True" : "False") + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& c = self.cast<const StopCondition&>();
            return reduce_by_construction(self, py::tuple(),
                                          py::dict(py::arg("state") = c.state, py::arg("level") = c.level,
                                                   py::arg("direction") = c.direction, py::arg("mode") = c.mode,
                                                   py::arg("terminal") = c.terminal, py::arg("name") = c.name));
        });

    py::class_<SolverOptions>(m, "SolverOptions", "Options of simulate(); validated when the run starts.")
        .def(py::init([](const py::kwargs& kwargs) {
                 auto o = std::make_unique<SolverOptions>();
                 const py::object view = py::cast(o.get(), py::return_value_policy::reference);
                 const py::object property = py::module_::import("builtins").attr("property");
                 for (auto item : kwargs) {  // any option by its attribute's name, as assigning it would
                     const std::string key = py::str(item.first);
                     const py::object attribute = py::type::of(view).attr("__dict__").attr("get")(key);
                     if (key.rfind('_', 0) == 0 || !py::isinstance(attribute, property) ||
                         attribute.attr("fset").is_none())
                         throw py::type_error("SolverOptions() got an unexpected keyword argument '" + key + "'");
                     py::setattr(view, item.first, item.second);
                 }
                 return o;
             }),
             "SolverOptions(**options): the engine's defaults, any option (an attribute) set by keyword.")
        .def_readwrite("method", &SolverOptions::method)
        .def_readwrite("linear_solver", &SolverOptions::linear_solver)
        .def_readwrite("rtol", &SolverOptions::rtol)
        .def_readwrite("atol", &SolverOptions::atol)
        .def_readwrite("atol_per_state", &SolverOptions::atol_per_state)
        .def_readwrite("max_steps", &SolverOptions::max_steps)
        .def_readwrite("max_step", &SolverOptions::max_step)
        .def_readwrite("initial_step", &SolverOptions::initial_step)
        .def_readwrite("output_times", &SolverOptions::output_times)
        .def_readwrite("record_steps", &SolverOptions::record_steps)
        .def_readwrite("record_event_rows", &SolverOptions::record_event_rows)
        .def_readwrite("record_event_states", &SolverOptions::record_event_states)
        .def_readwrite("stop_conditions", &SolverOptions::stop_conditions)
        .def_readwrite("max_events_in_window", &SolverOptions::max_events_in_window)
        .def_readwrite("event_window", &SolverOptions::event_window)
        .def_readwrite("timeout", &SolverOptions::timeout)
        .def_readwrite("max_output_rows", &SolverOptions::max_output_rows)
        .def_readwrite("max_output_bytes", &SolverOptions::max_output_bytes)
        .def_property_readonly("output_byte_budget", &SolverOptions::output_byte_budget,
                               "The byte budget in force [bytes]: max_output_bytes, or (0) an eighth of the "
                               "machine's physical memory.")
        .def_readwrite("step", &SolverOptions::step)
        .def_readwrite("theta", &SolverOptions::theta)
        .def_readwrite("projection_band", &SolverOptions::projection_band)
        .def_property(
            "contact_solver", [](const SolverOptions& o) { return o.contact_solver; },
            [](SolverOptions& o, const py::object& value) {
                if (py::isinstance<ContactSolverChoice>(value)) {
                    o.contact_solver = value.cast<ContactSolverChoice>();
                    return;
                }
                const std::string s = py::isinstance<py::str>(value) ? value.cast<std::string>() : std::string();
                if (s == "active_set") o.contact_solver = ContactSolverChoice::active_set;
                else if (s == "projected_gauss_seidel") o.contact_solver = ContactSolverChoice::projected_gauss_seidel;
                else
                    throw InvalidParameter("contact_solver", "SolverOptions: contact_solver must be 'active_set' or "
                                                             "'projected_gauss_seidel' (got " +
                                                             std::string(py::repr(value)) + ")");
            },
            "moreau_jean's one-step contact solver: ContactSolver or its name ('active_set', the default, or "
            "'projected_gauss_seidel'); the other methods refuse anything but the default.")
        .def_readonly_static("max_rtol", &SolverOptions::max_rtol)
        .def_readonly_static("min_rtol", &SolverOptions::min_rtol)
        .def("validate", &SolverOptions::validate, py::arg("state_size") = 1,
             "Raises InvalidParameterError naming the first option that breaks its rule (what simulate() checks "
             "when the run starts).")
        .def_readonly_static("reliable_rtol", &SolverOptions::reliable_rtol)
        .def_readonly_static("min_atol", &SolverOptions::min_atol);

    py::class_<Event>(m, "Event", "One switch of the hybrid system (a stick-slip transition, a velocity reversal).")
        .def_readonly("time", &Event::time, "t [s]")
        .def_readonly("switching_function", &Event::switching_function, "index of the guard that fired")
        .def_readonly("name", &Event::name, "name of the guard, e.g. 'relative_velocity'")
        .def_readonly("mode_before", &Event::mode_before)
        .def_readonly("mode_after", &Event::mode_after)
        .def_readonly("mode_before_name", &Event::mode_before_name)
        .def_readonly("mode_after_name", &Event::mode_after_name)
        .def_property_readonly("state_before", [](const Event& e) { return to_array(e.state_before); })
        .def_property_readonly("state_after", [](const Event& e) { return to_array(e.state_after); })
        .def_readonly("stop_condition", &Event::stop_condition, "a stop condition's index, or -1 for a switch")
        .def_readonly("direction", &Event::direction, "a stop condition's crossing: -1 falling, +1 rising, 0 mode")
        .def("__repr__", [](const Event& e) {
            return "Event(time=" + std::string(py::str(py::float_(e.time))) + ", name='" + e.name + "', " +
                   e.mode_before_name + " -> " + e.mode_after_name + ")";
        });

    py::class_<EventLog>(m, "EventLog", "A run's event log, read out of the engine's result on demand.")
        .def("__len__", [](const EventLog& log) { return log.events.size(); })
        .def_property_readonly("rows", [](const EventLog& log) {
            // one tuple per event (time, name, switching_function, mode_before, mode_after, mode names): far
            // cheaper to hand over than Event objects, whose attributes Python would read one by one
            py::list rows(log.events.size());
            for (std::size_t k = 0; k < log.events.size(); ++k) {
                const Event& e = log.events[k];
                const auto state = [](const std::vector<double>& x) -> py::object {
                    if (x.empty()) return py::none();
                    py::array_t<double> a = to_array(x);
                    a.attr("setflags")(py::arg("write") = false);
                    return std::move(a);
                };
                rows[k] = py::make_tuple(e.time, e.name, e.switching_function, e.mode_before, e.mode_after,
                                         e.mode_before_name, e.mode_after_name, state(e.state_before),
                                         state(e.state_after), e.stop_condition, e.direction);
            }
            return rows;
        }, "The events as tuples (time, name, switching_function, mode_before, mode_after, mode_before_name, "
           "mode_after_name, state_before, state_after, stop_condition, direction); the states None when not "
           "recorded.");

    py::class_<Result, std::shared_ptr<Result>>(m, "RawResult", "What the C++ engine recorded (see frictionsim.Result).")
        .def_readonly("state_names", &Result::state_names)
        .def_property_readonly("t", [](const Result& r) { return to_array(r.t); })
        .def_property_readonly("states", [](const Result& r) {
            py::array_t<double> a = to_array(r.states);
            return a.reshape({static_cast<py::ssize_t>(r.rows()), static_cast<py::ssize_t>(r.state_count())});
        })
        .def_property_readonly("friction_force", [](const Result& r) { return to_array(r.friction_force); })
        .def_property_readonly("mode", [](const Result& r) { return to_array(r.mode); })
        .def_readonly("events", &Result::events)
        .def("take_event_log", [](Result& r) { return EventLog{std::exchange(r.events, {})}; },
             "Move the event log out (events is empty afterwards): frictionsim.Result keeps it, not the columns.")
        .def("take_stop_events", [](Result& r) { return EventLog{std::exchange(r.stop_events, {})}; },
             "Move the stop conditions' crossings out, as take_event_log.")
        .def_readonly("status", &Result::status, "0 reached t_end, 1 a terminal stop condition, -1 failed")
        .def_readonly("message", &Result::message)
        .def_property_readonly("stats", [](const Result& r) {
            const SolverStats& s = r.stats;
            return py::dict(py::arg("steps") = s.steps, py::arg("rhs_evaluations") = s.rhs_evaluations,
                            py::arg("jacobian_evaluations") = s.jacobian_evaluations,
                            py::arg("guard_evaluations") = s.guard_evaluations,
                            py::arg("error_test_failures") = s.error_test_failures,
                            py::arg("restarts") = s.restarts, py::arg("events") = s.events);
        })
        .def_readonly("completed", &Result::completed)
        .def_readonly("warnings", &Result::warnings)
        .def_readonly("t_reached", &Result::t_reached);

    // Cycle means (analysis/cycle_mean.hpp): one implementation for C++ and Python.
    m.def("whole_cycle_window", [](double t_first, double t_last, double period, double transient, int cycles) {
        const CycleWindow w = whole_cycle_window(t_first, t_last, period, transient, cycles);
        return py::make_tuple(w.start, w.end, w.cycles);
    }, py::arg("t_first"), py::arg("t_last"), py::arg("period"), py::arg("transient") = 0.0, py::arg("cycles") = 0,
          "(t_a, t_b, cycles): whole cycles of `period` [s] after `transient` [s]; cycles <= 0 takes all that fit.");
    m.def("mean_from_integral", py::overload_cast<const std::vector<double>&, const std::vector<double>&, double, double>(
              &mean_from_integral), py::arg("t"), py::arg("running_integral"), py::arg("t_a"), py::arg("t_b"),
          "(Y(t_b) - Y(t_a)) / (t_b - t_a): the mean of dY/dt from its running integral Y (linear between samples).");
    m.def("mean_over_cycles", py::overload_cast<const std::vector<double>&, const std::vector<double>&, double,
                                                double, int>(&mean_over_cycles),
          py::arg("t"), py::arg("y"), py::arg("period"), py::arg("transient") = 0.0, py::arg("cycles") = 0,
          "Mean of sampled y(t) over whole cycles after a transient (trapezoid rule on the samples).");
    m.def("mean_over_window", py::overload_cast<const std::vector<double>&, const std::vector<double>&, double, double>(
              &mean_over_window), py::arg("t"), py::arg("y"), py::arg("t_a"), py::arg("t_b"),
          "Mean of sampled y(t) over [t_a, t_b] (trapezoid rule, interpolated window ends).");
    m.def("limit_cycle", [](py::array_t<double, py::array::c_style | py::array::forcecast> t,
                            py::array_t<double, py::array::c_style | py::array::forcecast> w, double transient,
                            std::optional<double> level, double stick_speed, double hysteresis, double min_amplitude) {
        if (t.ndim() != 1) throw InvalidParameter("t", "limit_cycle: t must be one-dimensional");
        if (w.ndim() != 1) throw InvalidParameter("w", "limit_cycle: w must be one-dimensional");
        if (level && !std::isfinite(*level))
            throw InvalidParameter("level", "limit_cycle: level must be finite or None (the mean speed), got " +
                                                std::to_string(*level));
        if (w.shape(0) != t.shape(0))
            throw InvalidParameter("w", "limit_cycle: w must have the same length as t (" + std::to_string(t.shape(0)) +
                                            " samples, got " + std::to_string(w.shape(0)) + ")");
        LimitCycle c;
        {
            py::gil_scoped_release release;
            c = limit_cycle(t.data(), w.data(), static_cast<std::size_t>(t.shape(0)), transient,
                            level ? *level : std::numeric_limits<double>::quiet_NaN(), stick_speed, hysteresis,
                            min_amplitude);
        }
        return py::dict(py::arg("cycles") = c.cycles, py::arg("period") = c.period, py::arg("frequency") = c.frequency,
                        py::arg("peak") = c.peak, py::arg("trough") = c.trough, py::arg("mean") = c.mean,
                        py::arg("stick_fraction") = c.stick_fraction, py::arg("level") = c.level,
                        py::arg("start") = c.start, py::arg("end") = c.end);
    }, py::arg("t"), py::arg("w"), py::arg("transient") = 0.0, py::arg("level") = py::none(),
          py::arg("stick_speed") = 1e-2, py::arg("hysteresis") = 0.05, py::arg("min_amplitude") = 0.0,
          "Limit cycle of speed samples w(t) after a transient (analysis/limit_cycle.hpp): a dict of cycles, period, "
          "frequency, peak, trough, mean, stick_fraction, level, start, end.");
}

}  // namespace frictionsim::python
