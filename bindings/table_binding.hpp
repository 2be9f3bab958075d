// What the bindings do with any parameter table (include/frictionsim/parameters.hpp), for laws and rigs alike:
// fs.Parameter records, rule texts and errors in Python's names, table-driven properties, keywords, repr and pickling.
#pragma once

#include <pybind11/pybind11.h>

#include <cmath>
#include <deque>
#include <optional>
#include <string>
#include <utility>

#include "common.hpp"

namespace frictionsim::python {

/// A parameter's description as Python sees it (fs.Parameter): from a Field of a parameter table.
struct ParameterInfo {
    std::string name, field, symbol, unit, rule, doc;
    double lower, upper;
    bool lower_open, upper_open, unset_allowed, required;
    std::optional<std::string> at_least;  ///< public name of the field bounding this one from below
    std::optional<double> default_value;   ///< None when required or unset by default
    double example;                        ///< the C++ Params default: a typical value, also for required ones
};

std::string format_double(double v);

/// Text that pybind11 keeps a pointer to (docstrings, default descriptions) lives as long as the module.
inline const char* kept(std::string text) {
    static std::deque<std::string> store;
    return store.emplace_back(std::move(text)).c_str();
}

/// The field that bounds `f` from below (its rule's at_least), or nullptr.
template <class P, std::size_t N>
const Field<P>* bound_field(const Field<P>& f, const std::array<Field<P>, N>& fields) {
    if (f.rule.at_least)
        for (const Field<P>& other : fields)
            if (std::string(other.name) == f.rule.at_least) return &other;
    return nullptr;
}

/// The rule in words with Python's names (">= mu", not ">= coulomb_coefficient").
template <class P, std::size_t N>
std::string public_rule(const Field<P>& f, const std::array<Field<P>, N>& fields) {
    const Field<P>* bound = bound_field(f, fields);
    return f.rule.text(bound ? bound->public_name() : nullptr);
}

template <class P, std::size_t N>
py::tuple parameter_infos(const std::array<Field<P>, N>& fields) {
    const P defaults{};
    py::tuple out(N);
    for (std::size_t i = 0; i < N; ++i) {
        const Field<P>& f = fields[i];
        ParameterInfo info{f.public_name(), f.name, f.symbol, f.unit, public_rule(f, fields), f.doc,
                           f.rule.lower, f.rule.upper, f.rule.lower_open, f.rule.upper_open,
                           f.rule.unset_allowed, f.required, std::nullopt, std::nullopt, defaults.*(f.member)};
        if (f.rule.at_least) info.at_least = bound_field(f, fields)->public_name();
        const double d = defaults.*(f.member);
        if (!f.required && !std::isnan(d)) info.default_value = d;
        out[i] = py::cast(std::move(info));
    }
    return out;
}

/// Rethrows an InvalidParameter of `fields` under the field's public name: "LuGre: mu (coulomb_coefficient) must ...".
template <class P, std::size_t N>
[[noreturn]] void rethrow_with_public_name(const InvalidParameter& e, const std::array<Field<P>, N>& fields) {
    for (const Field<P>& f : fields) {
        if (e.parameter() != f.name || f.key == nullptr) continue;
        std::string message = e.what();
        const std::string needle = std::string(": ") + f.name + " must";
        if (const auto at = message.find(needle); at != std::string::npos)
            message.replace(at, needle.size(), std::string(": ") + f.key + " (" + f.name + ") must");
        throw InvalidParameter(f.key, message);
    }
    throw e;
}

/// One read-only property per field; `params` maps the bound object to its Params struct.
template <class Class, class P, std::size_t N, class GetParams>
void def_field_properties(Class& cls, const std::array<Field<P>, N>& fields, GetParams params) {
    for (const Field<P>& f : fields) {
        const auto member = f.member;
        cls.def_property_readonly(f.public_name(),
                                  [member, params](const typename Class::type& self) { return params(self).*member; },
                                  kept(std::string(f.symbol) + " [" + f.unit + "]: " + f.doc));
    }
    cls.attr("parameters") = parameter_infos(fields);
}

/// Keyword arguments -> the table's fields of `p` (the others keep their defaults); TypeError for a value that is
/// not a number; returns how many keywords it used.
template <class P, std::size_t N>
std::size_t read_field_keywords(P& p, const py::kwargs& kwargs, const std::array<Field<P>, N>& fields,
                                const char* owner) {
    std::size_t used = 0;
    for (const Field<P>& f : fields) {
        if (!kwargs.contains(f.public_name())) continue;
        const py::handle value = kwargs[f.public_name()];
        if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) || !py::hasattr(value, "__float__"))
            throw py::type_error(std::string(owner) + ": " + f.public_name() + " must be a number (got " +
                                 std::string(py::str(py::type::of(value).attr("__name__"))) + ")");
        p.*(f.member) = value.attr("__float__")().template cast<double>();
        ++used;
    }
    return used;
}

/// The fields as keyword arguments (for __reduce__).
template <class P, std::size_t N>
py::dict field_keywords(const P& p, const std::array<Field<P>, N>& fields) {
    py::dict out;
    for (const Field<P>& f : fields) out[f.public_name()] = p.*(f.member);
    return out;
}

/// ", key=value" for each field that differs from its default (for __repr__).
template <class P, std::size_t N>
std::string changed_fields_repr(const P& p, const std::array<Field<P>, N>& fields) {
    const P defaults{};
    std::string out;
    for (const Field<P>& f : fields)
        if (p.*(f.member) != defaults.*(f.member))
            out += ", " + std::string(f.public_name()) + "=" + format_double(p.*(f.member));
    return out;
}

/// The "Keywords" section of a rig's docstring: "name : float = default" and the field's doc.
template <class P, std::size_t N>
std::string keywords_doc(const std::array<Field<P>, N>& fields) {
    const P defaults{};
    std::string doc;
    for (const Field<P>& f : fields)
        doc += std::string(f.public_name()) + " : float = " + format_double(defaults.*(f.member)) + "\n    " +
               f.symbol + " [" + f.unit + "], " + f.rule.text() + ": " + f.doc + "\n";
    return doc;
}

}  // namespace frictionsim::python
