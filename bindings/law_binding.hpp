// bind_law<Law>: one Python class per friction law, read off the law's description (its `fields` table, `key`,
// `name`, `state_names`, optional `description`): constructor keywords (in table order, required ones without a
// default, "unset" ones accepting None), properties, repr, pickling, the docstring, errors in Python's names, and
// the class attributes `key`, `parameters` (one fs.Parameter per field), `state_names`, `state_units` (each
// state's SI unit, declared by the law next to its names: io and plots label the outputs from it), `has_stick`,
// `stiff`.
// The model is manif's wrap_lie_group_base: one template, instantiated per type of a type list.
#pragma once

#include <pybind11/pybind11.h>

#include <cmath>
#include <deque>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

#include "table_binding.hpp"

namespace frictionsim::python {

namespace law_binding {

template <class T, class = void>
struct has_description : std::false_type {};
template <class T>
struct has_description<T, std::void_t<decltype(T::description)>> : std::true_type {};
template <class T, class = void>
struct has_state_names : std::false_type {};
template <class T>
struct has_state_names<T, std::void_t<decltype(T::state_names)>> : std::true_type {};
template <class T, class = void>
struct has_state_units : std::false_type {};
template <class T>
struct has_state_units<T, std::void_t<decltype(T::state_units)>> : std::true_type {};

/// Keyword I of Law's constructor: double, or std::optional<double> (None = unset) for fields that may be unset.
template <class Law, std::size_t I>
using keyword_t = std::conditional_t<Law::fields[I].rule.unset_allowed, std::optional<double>, double>;

template <class Law, std::size_t I>
auto keyword_arg() {
    constexpr auto f = Law::fields[I];
    if constexpr (f.required) {
        return py::arg(f.public_name());
    } else if constexpr (f.rule.unset_allowed) {
        return py::arg_v(f.public_name(), py::none(), "None");
    } else {
        const double d = typename Law::Params{}.*(f.member);
        return py::arg_v(f.public_name(), d, kept(format_double(d)));
    }
}

template <class Law, std::size_t... I>
void def_init(py::class_<Law>& cls, std::index_sequence<I...>) {
    cls.def(py::init([](keyword_t<Law, I>... values) {
                typename Law::Params p{};
                const auto set = [&p](auto field, const auto& value) {
                    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::optional<double>>) {
                        if (value && std::isnan(*value))
                            throw InvalidParameter(field.public_name(),
                                                   std::string(Law::name) + ": " + field.public_name() +
                                                       " must be finite or None (got nan)");
                        p.*(field.member) = value ? *value : std::numeric_limits<double>::quiet_NaN();
                    } else {
                        p.*(field.member) = value;
                    }
                };
                (set(Law::fields[I], values), ...);
                try {
                    return Law(p);
                } catch (const InvalidParameter& e) {
                    rethrow_with_public_name(e, Law::fields);
                }
            }),
            keyword_arg<Law, I>()...);
}

template <class Law>
std::string docstring() {
    std::string doc;
    if constexpr (has_description<Law>::value) doc = std::string(Law::description) + "\n";
    doc += "\nParameters\n----------\n";
    const typename Law::Params defaults{};
    for (const auto& f : Law::fields) {
        doc += std::string(f.public_name()) + " : float" + (f.required ? "" : ", optional") + "\n    " + f.doc +
               " " + f.symbol + " [" + f.unit + "], " + public_rule(f, Law::fields) + ".";
        if (!f.required) {
            const double d = defaults.*(f.member);
            doc += std::isnan(d) ? std::string(" Default: unset.") : " Default: " + format_double(d) + ".";
        }
        doc += "\n";
    }
    if constexpr (Law::state_count > 0) {
        doc += "\nStates: ";
        for (std::size_t i = 0; i < Law::state_count; ++i) doc += (i ? ", " : "") + std::string(Law::state_names[i]);
        doc += ".\n";
    }
    return doc;
}

}  // namespace law_binding

template <class Law>
py::class_<Law> bind_law(py::module_& m) {
    static const std::string doc = law_binding::docstring<Law>();
    py::class_<Law> cls(m, Law::name, doc.c_str());
    constexpr std::size_t n = std::tuple_size<std::decay_t<decltype(Law::fields)>>::value;
    law_binding::def_init(cls, std::make_index_sequence<n>{});
    def_field_properties(cls, Law::fields, [](const Law& law) { return law.params(); });
    cls.attr("key") = Law::key;
    cls.attr("has_stick") = Law::has_stick;
    cls.attr("stiff") = declares_stiff<Law>::value;
    static_assert(Law::state_count == 0 || law_binding::has_state_units<Law>::value,
                  "bind_law: a law with states declares their SI units next to their names: `static constexpr "
                  "std::array<const char*, state_count> state_units` (\"m\", \"N\", \"1\" for a count)");
    py::tuple states(Law::state_count), units(Law::state_count);
    if constexpr (law_binding::has_state_names<Law>::value)
        for (std::size_t i = 0; i < Law::state_count; ++i) states[i] = py::str(Law::state_names[i]);
    if constexpr (law_binding::has_state_units<Law>::value)
        for (std::size_t i = 0; i < Law::state_count; ++i) units[i] = py::str(Law::state_units[i]);
    cls.attr("state_names") = states;
    cls.attr("state_units") = units;
    cls.def("__repr__", [](const Law& law) {
        std::string out = std::string(Law::name) + "(";
        const auto p = law.params();
        bool first = true;
        for (const auto& f : Law::fields) {
            out += (first ? "" : ", ") + std::string(f.public_name()) + "=" + format_double(p.*(f.member));
            first = false;
        }
        return out + ")";
    });
    cls.def("__reduce__", [](py::handle self) {
        const auto p = self.cast<const Law&>().params();
        py::tuple args(Law::fields.size());
        for (std::size_t i = 0; i < Law::fields.size(); ++i) args[i] = p.*(Law::fields[i].member);
        return reduce_by_construction(self, std::move(args));
    });
    return cls;
}

}  // namespace frictionsim::python
