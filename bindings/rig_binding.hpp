// bind_rig: what every rig described by a parameter table shares in Python, bound once: the rig held as one
// instantiation per law of a list (BoundRig) or, for a rig built from its table alone, as itself (BoundTableRig);
// its docstring's Keywords section, one property per field and Rig.parameters, Rig.outputs (its columns' units,
// from C++), friction (law rigs), state_names, _simulate, pickling and repr. def_table_init writes the constructor
// from the table. register_rig<Entry> binds an entry of EngineRigs (rigs/rigs.hpp): from its table alone (its own
// methods, if any, added by a specialisation of def_rig_methods: bindings/navarro_lopez.cpp), or by the
// specialisation of a rig bound its own way (bindings/axial.cpp, torsional.cpp, kinematic.cpp; the string models:
// drillstring.cpp, torsional_string.cpp). The model is manif's wrap_lie_group_base.
#pragma once

#include <pybind11/stl.h>

#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <frictionsim/rigs/rigs.hpp>

#include "simulation.hpp"
#include "table_binding.hpp"

namespace frictionsim::python {

/// A rig of one Params struct with one friction law of `Laws`: the law, the parameters, and the rig built for that
/// law (RigVariant: one alternative per law, no virtual call in the right-hand side).
template <template <class> class Rig, class Laws, class Params>
struct BoundRig {
    using Law = typename variant_of<Laws>::type;
    using Variant = RigVariant<Rig, Laws>;

    Law friction;
    Params params;
    Variant rig;

    BoundRig(Law law, const Params& p)
        : friction(std::move(law)), params(p),
          rig(std::visit([&](auto l) -> Variant { return Rig<decltype(l)>(p, std::move(l)); }, friction)) {}

    template <class F>
    decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), rig); }
};

/// A rig built from its parameter table alone (a law of its own inside): the parameters and the rig, a
/// one-alternative variant for simulate_variant.
template <class Rig, class Params>
struct BoundTableRig {
    Params params;
    std::variant<Rig> rig;

    explicit BoundTableRig(const Params& p) : params(p), rig(Rig(p)) {}
    const Rig& model() const { return std::get<0>(rig); }

    template <class F>
    decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), rig); }
};

/// What bind_rig and def_table_init are given in place of law_to_python for a rig without a friction argument.
struct NoLaw {};

/// Rig.outputs: ((name, unit, what), ...) for the Result's columns beside t and the law's states, as the rig
/// declares them in C++ (frictionsim.outputs reads them for units in files and on plots).
template <class Class, std::size_t K>
void def_outputs(Class& cls, const std::array<RigOutput, K>& outputs) {
    py::tuple out(K);
    for (std::size_t i = 0; i < K; ++i) out[i] = py::make_tuple(outputs[i].name, outputs[i].unit, outputs[i].what);
    cls.attr("outputs") = out;
}

/// A keyword of a rig's constructor outside its table (a switch, an optional value): its name, its type and default
/// as the signature shows them, and how it is read into the Params.
template <class P>
struct ExtraKeyword {
    const char* name;
    const char* signature;  ///< e.g. "bool = False"
    void (*read)(P& p, py::handle value);
};

/// `__init__(self, friction, *, <table keywords>, <extras>)` (`__init__(self, *, ...)` for a rig without a law, whose
/// `make` then takes the Params alone): the law positionally, every field of the table and the extras by keyword. The keywords are read by the table (a value that is not a number is a TypeError naming it, an
/// unknown keyword is refused as Python refuses it), and the signature that help() and the generated stub show is
/// written from the table, so it cannot drift from it.
template <class Bound, class P, std::size_t N, std::size_t E, class Make>
void def_table_init(py::class_<Bound>& cls, const char* name, const std::array<Field<P>, N>& fields,
                    const std::array<ExtraKeyword<P>, E>& extras, Make make) {
    constexpr bool with_law = std::is_invocable_v<Make, py::handle, const P&>;
    const P defaults{};
    std::string signature = with_law ? "__init__(self, friction: object, *" : "__init__(self, *";
    for (const Field<P>& f : fields)
        signature += ", " + std::string(f.public_name()) + ": float = " + format_double(defaults.*(f.member));
    for (const ExtraKeyword<P>& x : extras) signature += ", " + std::string(x.name) + ": " + x.signature;
    signature += with_law ? ") -> None\n\nThe friction law, then the rig's parameters by keyword (see the class docstring).\n"
                          : ") -> None\n\nThe rig's parameters by keyword (see the class docstring).\n";
    py::options options;
    options.disable_function_signatures();
    const auto read = [name, fields, extras](const py::kwargs& kwargs) {
                P p{};
                std::size_t used = read_field_keywords(p, kwargs, fields, name);
                for (const ExtraKeyword<P>& x : extras)
                    if (kwargs.contains(x.name)) {
                        x.read(p, kwargs[x.name]);
                        ++used;
                    }
                if (used != kwargs.size())
                    for (auto item : kwargs) {
                        const std::string key = py::str(item.first);
                        bool known = false;
                        for (const Field<P>& f : fields) known = known || key == f.public_name();
                        for (const ExtraKeyword<P>& x : extras) known = known || key == x.name;
                        if (!known)
                            throw py::type_error(std::string(name) + "() got an unexpected keyword argument '" + key +
                                                 "'");
                    }
                return p;
    };
    if constexpr (with_law)
        cls.def(py::init([read, make](py::handle friction, const py::kwargs& kwargs) { return make(friction, read(kwargs)); }),
                py::arg("friction"), kept(std::move(signature)));
    else
        cls.def(py::init([read, make](const py::kwargs& kwargs) { return make(read(kwargs)); }),
                kept(std::move(signature)));
}

/// Binds the shared members of a BoundRig or a BoundTableRig. `law_to_python` turns its law back into the Python
/// object (NoLaw{} for a rig without one: no friction property, nothing positional); `extra(self)` gives the keywords
/// outside the table (a dict, for pickling; repr shows those that are not None or False).
template <class Bound, class P, std::size_t N, class LawToPython, class Extra>
py::class_<Bound> bind_rig(py::module_& m, const char* name, const std::string& description,
                           const std::array<Field<P>, N>& fields, LawToPython law_to_python, Extra extra) {
    constexpr bool with_law = !std::is_same_v<LawToPython, NoLaw>;
    const char* doc = kept(description + keywords_doc(fields));
    py::class_<Bound> cls(m, name, doc);
    def_field_properties(cls, fields, [](const Bound& r) -> const P& { return r.params; });
    def_outputs(cls, P::outputs());
    if constexpr (with_law)
        cls.def_property_readonly("friction", [law_to_python](const Bound& r) { return law_to_python(r.friction); });
    // the law positionally (a rig with one), then the table's keywords and the extras
    const auto positional = [law_to_python](const Bound& r) {
        if constexpr (with_law) return py::make_tuple(law_to_python(r.friction));
        else return py::tuple();
    };
    cls.def_property_readonly("state_names", [](const Bound& r) {
            return r.visit([](const auto& s) {
                const auto names = s.state_names();
                return std::vector<std::string>(names.begin(), names.end());
            });
        })
        .def("_simulate", [](const Bound& r, double t_end, const SolverOptions& options, double t_start) {
            return simulate_variant(r.rig, t_end, options, t_start);
        })
        .def("__reduce__", [fields, positional, extra](py::handle self) {
            const auto& r = self.cast<const Bound&>();
            py::dict kwargs = field_keywords(r.params, fields);
            for (auto item : extra(r)) kwargs[item.first] = item.second;
            return reduce_by_construction(self, positional(r), kwargs);
        })
        .def("__repr__", [name, fields, law_to_python, extra](const Bound& r) {
            std::string args;
            if constexpr (with_law) args = ", friction=" + std::string(py::repr(law_to_python(r.friction)));
            args += changed_fields_repr(r.params, fields);
            for (auto item : extra(r))
                if (!item.second.is_none() && !item.second.is(py::bool_(false)))
                    args += ", " + std::string(py::str(item.first)) + "=" + std::string(py::repr(item.second));
            return std::string(name) + "(" + (args.empty() ? args : args.substr(2)) + ")";
        });
    return cls;
}

/// No keywords outside the table.
template <class Bound>
py::dict no_extras(const Bound&) {
    return py::dict();
}

/// A rig's own methods and properties beside what its table gives (closed forms, its parts), added to the class
/// register_rig binds from the table: none, unless the rig's bindings file specialises this for its entry (declared
/// below).
template <class Entry, class Class>
void def_rig_methods(Class&) {}

/// Binds the rig of `Entry` (an entry of EngineRigs) and returns its class: by default from its table alone, its
/// Params giving rig_name and description (a rig that needs nothing more is a header and a line in EngineRigs),
/// then def_rig_methods<Entry>; a rig bound its own way (extra keywords, signals, a DrillString) specialises this in
/// its bindings file, declared below.
template <class Entry>
py::object register_rig(py::module_& m) {
    static_assert(Entry::construction == RigConstruction::law || Entry::construction == RigConstruction::table,
                  "register_rig: a signal-driven rig or a string model needs its own binding (declared below)");
    using P = typename Entry::Params;
    const std::string description = std::string("\n") + P::description + "\n\nKeywords\n--------\n";
    constexpr std::array<ExtraKeyword<P>, 0> extras{};
    if constexpr (Entry::construction == RigConstruction::law) {
        using Bound = BoundRig<Entry::template of, PythonLaws, P>;
        auto cls = bind_rig<Bound>(m, Entry::name, description, P::fields(), friction_law_to_python, no_extras<Bound>);
        def_table_init(cls, Entry::name, P::fields(), extras, [](py::handle friction, const P& p) {
            return Bound(friction_law_from_python(friction, "friction"), p);
        });
        def_rig_methods<Entry>(cls);
        return std::move(cls);
    } else {
        using Bound = BoundTableRig<typename Entry::type, P>;
        auto cls = bind_rig<Bound>(m, Entry::name, description, P::fields(), NoLaw{}, no_extras<Bound>);
        def_table_init(cls, Entry::name, P::fields(), extras, [](const P& p) { return Bound(p); });
        def_rig_methods<Entry>(cls);
        return std::move(cls);
    }
}

/// The class register_rig binds for a table-built entry (what def_rig_methods<Entry> is given).
template <class Entry>
using TableRigClass = py::class_<BoundTableRig<typename Entry::type, typename Entry::Params>>;

template <>
py::object register_rig<law_rig<AxialRig, AxialRigParams>>(py::module_& m);  // bindings/axial.cpp
template <>
py::object register_rig<signal_rig>(py::module_& m);  // bindings/kinematic.cpp
template <>
py::object register_rig<law_rig<TorsionalRig, TorsionalRigParams>>(py::module_& m);  // bindings/torsional.cpp
/// fs.StringRig, with fs.PipeSection, fs.DrillString, fs.NavarroLopezBit, fs.DetournayBit and
/// fs.automatic_treatment (bindings/drillstring.cpp).
template <>
py::object register_rig<event_string_rig>(py::module_& m);
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
/// fs.TorsionalString, with fs.aarsnes_shor_well_b (bindings/torsional_string.cpp).
template <>
py::object register_rig<time_stepping_rig<TorsionalString, TorsionalStringParams>>(py::module_& m);
#endif
// the Navarro-Lopez strings: bound from their tables by register_rig, their own methods in navarro_lopez.cpp
template <>
void def_rig_methods<table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>>(
    TableRigClass<table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>>& cls);
template <>
void def_rig_methods<table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>>(
    TableRigClass<table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>>& cls);

}  // namespace frictionsim::python
