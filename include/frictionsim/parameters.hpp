// A parameter table: how a law or rig describes its parameters once (name, symbol, unit, rule, default, doc).
// Validation, the Python constructor keywords, properties, repr, pickling, docstrings, scenario keys, the fits'
// parameter lists and the property tests' strategies are all read off it.
//
//   struct Params { double mu = 0.3; double k_t = 4e4; };
//   static constexpr std::array<Field<Params>, 2> fields{{
//       {"mu", "mu", "-", Rule::positive(), &Params::mu, "Friction coefficient."},
//       {"k_t", "k_t", "N/m", Rule::positive(), &Params::k_t, "Tangential stiffness."}}};
//   validate_fields("MyLaw", params, fields);   // throws InvalidParameter naming the field and its rule
//
// A field's `key` is its public name (Python keyword, scenario key) when that differs from the C++ member's
// name (LuGre's coulomb_coefficient is `mu` in Python); errors from C++ name the member, the bindings add the key.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>

#include "detail/validate.hpp"

namespace frictionsim {

/// The rule one parameter obeys: an interval (each end open or closed, infinite ends allowed), or a lower bound
/// given by another field of the same table (mu_static >= mu). Always finite, unless `unset_allowed` (NaN then
/// means "not given": Coulomb's mu_static equal to mu).
struct Rule {
    double lower = -std::numeric_limits<double>::infinity();
    double upper = std::numeric_limits<double>::infinity();
    bool lower_open = false, upper_open = false;
    const char* at_least = nullptr;  ///< name of another field this one must be >= (checked after it)
    bool unset_allowed = false;
    const char* reason = nullptr;    ///< why, appended to the error message

    static constexpr Rule finite() { return Rule{}; }
    static constexpr Rule positive() { return Rule{0.0, std::numeric_limits<double>::infinity(), true, false}; }
    static constexpr Rule non_negative() { return Rule{0.0, std::numeric_limits<double>::infinity(), false, false}; }
    /// [lo, hi], with either end made open by the flags.
    static constexpr Rule interval(double lo, double hi, bool lo_open = false, bool hi_open = false) {
        return Rule{lo, hi, lo_open, hi_open};
    }
    static constexpr Rule at_least_field(const char* other) {
        Rule r;
        r.at_least = other;
        return r;
    }
    constexpr Rule or_unset() const {
        Rule r = *this;
        r.unset_allowed = true;
        return r;
    }
    constexpr Rule because(const char* why) const {
        Rule r = *this;
        r.reason = why;
        return r;
    }

    /// Does `value` obey the interval part (the `at_least` bound is checked by validate_fields)?
    bool admits(double value) const {
        if (!std::isfinite(value)) return false;
        if (lower_open ? !(value > lower) : !(value >= lower)) return false;
        if (upper_open ? !(value < upper) : !(value <= upper)) return false;
        return true;
    }

    /// The rule in words, as error messages and docstrings print it: "positive and finite", "in [0.5, 50]";
    /// `bound_name` replaces the at_least field's name (its public name, for Python).
    std::string text(const char* bound_name = nullptr) const {
        const bool has_lower = std::isfinite(lower), has_upper = std::isfinite(upper);
        std::ostringstream s;
        s.precision(12);
        if (at_least) s << ">= " << (bound_name ? bound_name : at_least) << " and finite";
        else if (has_lower && has_upper)
            s << "in " << (lower_open ? "(" : "[") << lower << ", " << upper << (upper_open ? ")" : "]");
        else if (has_lower && lower == 0.0) s << (lower_open ? "positive and finite" : "non-negative and finite");
        else if (has_lower) s << (lower_open ? "> " : ">= ") << lower << " and finite";
        else if (has_upper) s << (upper_open ? "< " : "<= ") << upper << " and finite";
        else s << "finite";
        if (reason) s << " (" << reason << ")";
        return s.str();
    }
};

/// One parameter of a table. `member` points into the Params struct P; its default is P{}.*member.
template <class P>
struct Field {
    const char* name;    ///< C++ member name (and the name errors from C++ use)
    const char* symbol;  ///< the papers' symbol, e.g. "sigma_0"
    const char* unit;    ///< SI unit, "-" when dimensionless
    Rule rule;
    double P::*member;
    const char* doc;            ///< one line
    const char* key = nullptr;  ///< public name (Python keyword, scenario key) when not `name`
    bool required = false;      ///< the Python constructor has no default for it

    constexpr const char* public_name() const { return key ? key : name; }
    double get(const P& p) const { return p.*member; }
};

/// Field<Base> -> Field<Derived> for a Params struct that extends another (ElastoPlastic::Params : LuGre::Params).
template <class Derived, class Base>
constexpr Field<Derived> inherit_field(const Field<Base>& f) {
    return Field<Derived>{f.name, f.symbol, f.unit, f.rule, static_cast<double Derived::*>(f.member),
                          f.doc, f.key, f.required};
}

/// The base table's fields followed by `extra` (the Params struct of a law that extends another's).
template <class Derived, class Base, std::size_t N, std::size_t M>
constexpr std::array<Field<Derived>, N + M> extend_fields(const std::array<Field<Base>, N>& base,
                                                           const std::array<Field<Derived>, M>& extra) {
    std::array<Field<Derived>, N + M> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = inherit_field<Derived>(base[i]);
    for (std::size_t i = 0; i < M; ++i) out[N + i] = extra[i];
    return out;
}

/// Checks every field of `p` against its rule, in table order; throws InvalidParameter naming `owner`, the
/// field and the rule on the first violation.
template <class P, std::size_t N>
void validate_fields(const char* owner, const P& p, const std::array<Field<P>, N>& fields) {
    for (const Field<P>& f : fields) {
        const double value = p.*(f.member);
        if (f.rule.unset_allowed && std::isnan(value)) continue;
        if (f.rule.at_least) {
            double bound = std::numeric_limits<double>::quiet_NaN();
            for (const Field<P>& other : fields)
                if (std::string(other.name) == f.rule.at_least) bound = p.*(other.member);
            if (!(f.rule.admits(value) && value >= bound)) detail::reject(owner, f.name, f.rule.text().c_str(), value);
        } else if (!f.rule.admits(value)) {
            detail::reject(owner, f.name, f.rule.text().c_str(), value);
        }
    }
}

}  // namespace frictionsim
