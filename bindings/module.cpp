// frictionsim._core: the C++ engine for the frictionsim Python package. The Python modules in
// python/frictionsim/ re-export these classes and add what NumPy/SciPy do well (fitting, signals, plots).
#include "common.hpp"
#include "rig_binding.hpp"
#include "simulation.hpp"

namespace frictionsim::python {

/// fs.Survey, fs.SoftString, fs.TorqueDragResult: torque and drag along a well (bindings/wells.cpp).
void register_wells(py::module_& m);

void require_constructed(py::handle self) {
    // only pybind11 instances have a holder to check (a law argument may be anything)
    if (!PyObject_IsInstance(self.ptr(), py::detail::get_internals().instance_base)) return;
    auto* inst = reinterpret_cast<py::detail::instance*>(self.ptr());
    // A value of its own (a holder) or a reference into another object's value (an element of a list attribute,
    // returned by reference): either has a value pointer; only __new__ without __init__ leaves it null.
    const auto v_h = inst->get_value_and_holder();
    if (!v_h.holder_constructed() && v_h.value_ptr() == nullptr) {
        const std::string type = py::str(py::type::of(self).attr("__name__"));
        throw py::type_error(type + " object was never constructed (made by " + type +
                             ".__new__ or an incomplete pickle): build it with " + type + "(...)");
    }
}

namespace {

/// `__setstate__` is pybind11's new-style constructor of an instance made by `__new__` (the enums' pickling:
/// copyreg's `__newobj__`, then `obj.__setstate__(value)`, as pickle and copy.deepcopy do): the one attribute looked
/// up before construction, since it is what constructs. A class without one raises AttributeError as before.
bool constructs(py::handle name) {
    return PyUnicode_Check(name.ptr()) && PyUnicode_CompareWithASCIIString(name.ptr(), "__setstate__") == 0;
}

/// Every class of the module checks construction on attribute access (methods, properties, pickling) and in repr,
/// the ways Python reaches an instance's C++ value; the functions that take instances as arguments (the rigs'
/// friction) call require_constructed themselves.
void guard_construction(py::module_& m) {
    for (const auto item : m.attr("__dict__").cast<py::dict>()) {
        const py::handle cls = item.second;
        if (!PyType_Check(cls.ptr()) || !py::hasattr(cls, "__module__") ||
            cls.attr("__module__").cast<std::string>() != "frictionsim._core" ||
            !PyObject_IsInstance(cls.ptr(), reinterpret_cast<PyObject*>(py::detail::get_internals().default_metaclass)))
            continue;
        const py::object repr = cls.attr("__repr__");
        py::setattr(cls, "__getattribute__", py::cpp_function([](py::handle self, py::handle name) {
            if (!constructs(name)) require_constructed(self);
            PyObject* value = PyObject_GenericGetAttr(self.ptr(), name.ptr());
            if (value == nullptr) throw py::error_already_set();
            return py::reinterpret_steal<py::object>(value);
        }, py::is_method(cls), py::name("__getattribute__")));
        py::setattr(cls, "__repr__", py::cpp_function([repr](py::handle self) {
            require_constructed(self);
            return repr(self);
        }, py::is_method(cls), py::name("__repr__")));
    }
}

/// Whether the event_string_rig entry comes before every table-built entry of `Rigs` (see PYBIND11_MODULE).
template <class... Entry>
constexpr bool string_models_bound_before_table_rigs(frictionsim::TypeList<Entry...>) {
    bool strings = false, ok = true;
    ((Entry::construction == frictionsim::RigConstruction::string ? void(strings = true)
      : Entry::construction == frictionsim::RigConstruction::table ? void(ok = ok && strings)
                                                                    : void()),
     ...);
    return ok;
}

}  // namespace

py::tuple reduce_by_construction(py::handle self, py::tuple args, py::dict kwargs, const char* factory) {
    const py::object rebuild = py::module_::import("frictionsim._core").attr("_rebuild");
    return py::make_tuple(rebuild, py::make_tuple(py::type::of(self), std::move(args), std::move(kwargs), factory));
}

}  // namespace frictionsim::python

PYBIND11_MODULE(_core, m) {
    using namespace frictionsim::python;
    m.doc() = "frictionsim C++ engine: friction laws, rigs and the hybrid (stick-slip) integrator.";
    // The project's version, from CMakeLists.txt (the one source; frictionsim.__version__ is this).
#ifdef FRICTIONSIM_VERSION
    m.attr("__version__") = FRICTIONSIM_VERSION;
#else
#error "FRICTIONSIM_VERSION is defined by bindings/CMakeLists.txt from the project's version"
#endif
    // False when built without SUNDIALS: Dormand-Prince only, simulate(method="cvode_*") is refused.
#if defined(FRICTIONSIM_SUNDIALS) && FRICTIONSIM_SUNDIALS
    m.attr("HAS_SUNDIALS") = true;
#else
    m.attr("HAS_SUNDIALS") = false;
#endif
    // False when built without Eigen: no TorsionalString, simulate(method="rosenbrock") is refused.
    m.attr("HAS_EIGEN") = has_eigen;
    m.def("_rebuild", [](const py::type& cls, const py::tuple& args, const py::dict& kwargs, const std::string& factory) {
        if (cls.attr("__module__").cast<std::string>() != "frictionsim._core")
            throw py::type_error("_rebuild: only frictionsim._core classes are rebuilt");
        const py::object make = factory.empty() ? py::object(cls) : py::object(cls.attr(factory.c_str()));
        return make(*args, **kwargs);
    }, "Unpickling: cls(*args, **kwargs), or cls.<factory>(...), through the validating constructor.");
    register_errors(m);
    register_laws(m);
    register_callable_law(m);
    register_results(m);
    register_contact(m);
    // the rigs simulate() runs: every entry of EngineRigs (rigs/rigs.hpp) in its order, by register_rig (the string
    // models' by their files, drillstring.cpp and torsional_string.cpp). fs.StringRig's file also binds
    // fs.NavarroLopezBit, the .bit of the rigs built from their table alone: the list puts it before the first of
    // them, so that their signatures name the Python class, not the C++ type.
    static_assert(string_models_bound_before_table_rigs(frictionsim::EngineRigs{}),
                  "EngineRigs: the event_string_rig entry (its file binds NavarroLopezBit) before table-built rigs");
    py::list rigs;
    for_each_type(frictionsim::EngineRigs{},
                  [&](auto tag) { rigs.append(register_rig<typename decltype(tag)::type>(m)); });
    m.attr("RIGS") = py::tuple(rigs);
    register_wells(m);
    guard_construction(m);
}
