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
    // A value of its own always has its holder; one without (owned) was never constructed, even where pybind11 has
    // since allocated its value lazily (a cast of the bare instance does: uninitialised memory behind it)
    if (!v_h.holder_constructed() && (v_h.value_ptr() == nullptr || inst->owned)) {
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

/// Every argument that is an instance of the extension, and the items of a list or tuple argument (a string's
/// sections, a survey's stations), constructed: pybind11 would pass a never-constructed one's uninitialised value.
/// The first `skip` positional arguments are left unchecked (1: __init__'s self, the instance being built).
void require_all_constructed(const py::args& args, const py::kwargs& kwargs, std::size_t skip) {
    const auto check = [](const py::handle& value) {
        require_constructed(value);
        if (PyList_Check(value.ptr()) || PyTuple_Check(value.ptr()))
            for (const py::handle item : value) require_constructed(item);
    };
    for (std::size_t i = skip; i < args.size(); ++i) check(args[i]);
    for (const auto item : kwargs) check(item.second);
}

/// Names a class keeps unwrapped: what constructs (__new__, __setstate__; __init__ checks its arguments only) and the
/// guard itself. (pybind11's cross-module hook _pybind11_conduit_v1_ is guarded too: it hands out self's pointer.)
bool left_unwrapped(const std::string& name) {
    return name == "__new__" || name == "__setstate__" || name == "__getattribute__";
}

/// `function` with every argument's construction checked first (self included), under the same name and with the
/// same docstring (signatures included, as pybind11 wrote them: help() and the stub generator read them); `where`
/// is py::is_method(cls) for a class's member, py::scope(module) for a module-level function.
template <class Where>
py::object guarded(const std::string& name, const py::object& function, const Where& where, std::size_t skip = 0) {
    py::options docs;
    docs.disable_function_signatures();  // the docstring is the original's, signature lines and all
    const py::object doc = py::getattr(function, "__doc__", py::none());
    const char* text = doc.is_none() ? "" : kept(doc.cast<std::string>());
    return py::cpp_function([function, skip](py::args args, py::kwargs kwargs) {
        require_all_constructed(args, kwargs, skip);
        return function(*args, **kwargs);
    }, py::name(kept(name)), where, py::doc(text));
}

/// Every class of the module checks construction wherever Python reaches an instance's C++ value: attribute access
/// on an instance (__getattribute__), and every method, dunder slot and property of the class itself, also when
/// reached through the class (`Cls.method(bare)`, `Cls.prop.fget(bare)`, len(bare), which skip __getattribute__:
/// pybind11 passes `self` to member-function bindings as a pointer, null for an instance never constructed). The
/// functions that take instances as arguments take them by reference (pybind11 then refuses a null value:
/// results.cpp's translator says so) or call require_constructed themselves.
void guard_construction(py::module_& m) {
    std::vector<std::pair<std::string, py::object>> functions;
    for (const auto item : m.attr("__dict__").cast<py::dict>())
        if (PyCFunction_Check(item.second.ptr()) && py::isinstance<py::str>(item.first))
            functions.emplace_back(py::str(item.first), py::reinterpret_borrow<py::object>(item.second));
    for (const auto& [name, function] : functions) m.attr(name.c_str()) = guarded(name, function, py::scope(m));
    for (const auto item : m.attr("__dict__").cast<py::dict>()) {
        const py::handle cls = item.second;
        if (!PyType_Check(cls.ptr()) || !py::hasattr(cls, "__module__") ||
            cls.attr("__module__").cast<std::string>() != "frictionsim._core" ||
            !PyObject_IsInstance(cls.ptr(), reinterpret_cast<PyObject*>(py::detail::get_internals().default_metaclass)))
            continue;
        std::vector<std::pair<std::string, py::object>> replaced;
        for (const auto entry : cls.attr("__dict__").cast<py::dict>()) {
            const std::string name = py::str(entry.first);
            const py::handle value = entry.second;
            if (left_unwrapped(name)) continue;
            if (PyInstanceMethod_Check(value.ptr())) {
                const py::object function = py::reinterpret_borrow<py::object>(PyInstanceMethod_GET_FUNCTION(value.ptr()));
                replaced.emplace_back(name, guarded(name, function, py::is_method(cls), name == "__init__" ? 1 : 0));
            } else if (py::isinstance<py::staticmethod>(value)) {
                replaced.emplace_back(name, py::staticmethod(guarded(name, value.attr("__func__"), py::scope(cls))));
            } else if (Py_TYPE(value.ptr()) == &PyProperty_Type) {
                // a property of getter and setter, both guarded, its docstring kept
                const py::object fget = value.attr("fget"), fset = value.attr("fset");
                const py::object get = fget.is_none() ? py::none() : guarded(name, fget, py::is_method(cls));
                const py::object set = fset.is_none() ? py::none() : guarded(name, fset, py::is_method(cls));
                replaced.emplace_back(name, py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(
                                                &PyProperty_Type))(get, set, py::none(), value.attr("__doc__")));
            }
        }
        for (const auto& [name, value] : replaced) py::setattr(cls, name.c_str(), value);
        // a class without a repr of its own shows the object's: guarded too (it prints nothing of the value, but a
        // bare instance should say what it is wherever it is used)
        if (!cls.attr("__dict__").contains("__repr__"))
            py::setattr(cls, "__repr__", guarded("__repr__", cls.attr("__repr__"), py::is_method(cls)));
        py::setattr(cls, "__getattribute__", py::cpp_function([](py::handle self, py::handle name) {
            if (!constructs(name)) require_constructed(self);
            PyObject* value = PyObject_GenericGetAttr(self.ptr(), name.ptr());
            if (value == nullptr) throw py::error_already_set();
            return py::reinterpret_steal<py::object>(value);
        }, py::is_method(cls), py::name("__getattribute__")));
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

namespace {

[[noreturn]] void refuse_pickle(const char* parameter, const std::string& rule) {
    throw InvalidParameter(parameter, std::string("unpickling (frictionsim._core._rebuild): ") + parameter +
                                          " must be " + rule + " (a tampered or foreign pickle)");
}

/// What a pickle made by reduce_by_construction calls: every argument checked, so a tampered pickle raises the
/// package's InvalidParameterError naming what is wrong, never another kind of error or a half-built object.
py::object rebuild(const py::object& cls, const py::object& args, const py::object& kwargs,
                   const py::object& factory) {
    if (!PyType_Check(cls.ptr()) || !py::hasattr(cls, "__module__") ||
        !py::isinstance<py::str>(cls.attr("__module__")) ||
        cls.attr("__module__").cast<std::string>() != "frictionsim._core")
        refuse_pickle("cls", "a class of frictionsim._core");
    if (!py::isinstance<py::tuple>(args)) refuse_pickle("args", "a tuple");
    if (!py::isinstance<py::dict>(kwargs)) refuse_pickle("kwargs", "a dict");
    for (const auto item : kwargs.cast<py::dict>())
        if (!py::isinstance<py::str>(item.first)) refuse_pickle("kwargs", "a dict with str keys");
    if (!py::isinstance<py::str>(factory)) refuse_pickle("factory", "a str (empty: the constructor)");
    const std::string name = factory.cast<std::string>();
    py::object make = cls;
    if (!name.empty()) {
        // a factory is one of the class's own static constructors, never another attribute or a private one
        const py::dict own = cls.attr("__dict__").cast<py::dict>();
        if (name.front() == '_' || !own.contains(name.c_str()))
            refuse_pickle("factory", "a static constructor of " + cls.attr("__name__").cast<std::string>());
        make = cls.attr(name.c_str());
    }
    try {
        return make(*args.cast<py::tuple>(), **kwargs.cast<py::dict>());
    } catch (py::error_already_set& e) {
        // the constructor's own rule (InvalidParameterError) passes; pybind11's overload mismatch does not
        if (!e.matches(PyExc_TypeError)) throw;
        refuse_pickle("args", "the arguments of " + cls.attr("__name__").cast<std::string>() + "(...): " +
                                  std::string(py::str(e.value())).substr(0, 300));
    }
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
    m.def("_rebuild", &rebuild, py::arg("cls"), py::arg("args"), py::arg("kwargs"), py::arg("factory"),
          "Unpickling: cls(*args, **kwargs), or cls.<factory>(...), through the validating constructor.");
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
