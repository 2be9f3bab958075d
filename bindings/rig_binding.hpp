// bind_rig: what every rig described by a parameter table shares in Python, bound once: the rig held as one
// instantiation per law of a list (BoundRig), its docstring's Keywords section, one property per field and
// Rig.parameters, friction, state_names, _simulate, pickling and repr. Each rig's file adds its constructor and
// the methods only it has (bindings/axial.cpp, bindings/torsional.cpp). The model is manif's wrap_lie_group_base.
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

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

/// A keyword of a rig's constructor outside its table (a switch, an optional value): its name, its type and default
/// as the signature shows them, and how it is read into the Params.
template <class P>
struct ExtraKeyword {
    const char* name;
    const char* signature;  ///< e.g. "bool = False"
    void (*read)(P& p, py::handle value);
};

/// `__init__(self, friction, *, <table keywords>, <extras>)`: the law positionally, every field of the table and the
/// extras by keyword. The keywords are read by the table (a value that is not a number is a TypeError naming it, an
/// unknown keyword is refused as Python refuses it), and the signature that help() and the generated stub show is
/// written from the table, so it cannot drift from it.
template <class Bound, class P, std::size_t N, std::size_t E, class Make>
void def_table_init(py::class_<Bound>& cls, const char* name, const std::array<Field<P>, N>& fields,
                    const std::array<ExtraKeyword<P>, E>& extras, Make make) {
    const P defaults{};
    std::string signature = "__init__(self, friction: object, *";
    for (const Field<P>& f : fields)
        signature += ", " + std::string(f.public_name()) + ": float = " + format_double(defaults.*(f.member));
    for (const ExtraKeyword<P>& x : extras) signature += ", " + std::string(x.name) + ": " + x.signature;
    signature += ") -> None\n\nThe friction law, then the rig's parameters by keyword (see the class docstring).\n";
    py::options options;
    options.disable_function_signatures();
    cls.def(py::init([name, fields, extras, make](py::handle friction, const py::kwargs& kwargs) {
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
                return make(friction, p);
            }),
            py::arg("friction"), kept(std::move(signature)));
}

/// Binds the shared members of a BoundRig. `law_to_python` turns its law back into the Python object; `extra(self)`
/// gives the keywords outside the table (a dict, for pickling; repr shows those that are not None or False).
template <class Bound, class P, std::size_t N, class LawToPython, class Extra>
py::class_<Bound> bind_rig(py::module_& m, const char* name, const std::string& description,
                           const std::array<Field<P>, N>& fields, LawToPython law_to_python, Extra extra) {
    const char* doc = kept(description + keywords_doc(fields));
    py::class_<Bound> cls(m, name, doc);
    def_field_properties(cls, fields, [](const Bound& r) -> const P& { return r.params; });
    cls.def_property_readonly("friction", [law_to_python](const Bound& r) { return law_to_python(r.friction); })
        .def_property_readonly("state_names", [](const Bound& r) {
            return r.visit([](const auto& s) {
                const auto names = s.state_names();
                return std::vector<std::string>(names.begin(), names.end());
            });
        })
        .def("_simulate", [](const Bound& r, double t_end, const SolverOptions& options, double t_start) {
            return simulate_variant(r.rig, t_end, options, t_start);
        })
        .def("__reduce__", [fields, law_to_python, extra](py::handle self) {
            const auto& r = self.cast<const Bound&>();
            py::dict kwargs = field_keywords(r.params, fields);
            for (auto item : extra(r)) kwargs[item.first] = item.second;
            return reduce_by_construction(self, py::make_tuple(law_to_python(r.friction)), kwargs);
        })
        .def("__repr__", [name, fields, law_to_python, extra](const Bound& r) {
            std::string out = std::string(name) + "(friction=" + std::string(py::repr(law_to_python(r.friction))) +
                              changed_fields_repr(r.params, fields);
            for (auto item : extra(r))
                if (!item.second.is_none() && !item.second.is(py::bool_(false)))
                    out += ", " + std::string(py::str(item.first)) + "=" + std::string(py::repr(item.second));
            return out + ")";
        });
    return cls;
}

}  // namespace frictionsim::python
