// Products of a table's parameters that must stay doubles: each parameter within its rule, the product of several can
// still leave the range of a double (an outer diameter of 1e300 m squares to infinity, a bit constant of 5e-324 makes
// the depth of cut at a weight infinite). Such a product is refused naming the parameter that put it there: of the
// parameters it is made of, the one whose value lies farthest (in decades) from its default, the typo in practice.
#pragma once

#include <array>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>

#include "../detail/validate.hpp"
#include "../parameters.hpp"

namespace frictionsim::detail {

/// Decades between `value` and `reference` (infinite for a zero or non-finite value).
inline double decades_off(double value, double reference) {
    const double v = std::abs(value), r = std::abs(reference);
    if (!(v > 0.0) || !std::isfinite(v)) return std::numeric_limits<double>::infinity();
    return std::abs(std::log10(v) - std::log10(r > 0.0 && std::isfinite(r) ? r : 1.0));
}

/// Of the fields of `p` named (C++ names) in `names`, the one farthest from its default in decades; `extra_off`: how
/// far an input outside the table is from its own typical value (e.g. a weight on bit), which wins if larger
/// (nullptr then).
template <class P, std::size_t N>
const Field<P>* farthest_from_default(const P& p, const std::array<Field<P>, N>& fields,
                                      std::initializer_list<const char*> names, double extra_off = -1.0) {
    const P defaults{};
    const Field<P>* worst = nullptr;
    double off = extra_off;
    for (const Field<P>& f : fields)
        for (const char* name : names)
            if (std::string_view(f.name) == name) {
                const double d = decades_off(p.*(f.member), defaults.*(f.member));
                if (d > off) {
                    off = d;
                    worst = &f;
                }
            }
    return worst;
}

/// Rejects `value` (`what`, a product of the fields `names` of `p`) unless it is finite and, when `positive`, at
/// least the smallest normal double; naming the field farthest from its default.
template <class P, std::size_t N>
void require_representable(const char* owner, const P& p, const std::array<Field<P>, N>& fields,
                           std::initializer_list<const char*> names, double value, const char* what,
                           bool positive = true) {
    if (std::isfinite(value) && (!positive || value >= DBL_MIN)) return;
    const Field<P>* f = farthest_from_default(p, fields, names);
    std::ostringstream rule;
    rule.precision(6);
    rule << "such that " << what << " is a " << (positive ? "positive " : "") << "finite double (it is " << value
         << ")";
    reject(owner, f->name, rule.str().c_str(), p.*(f->member));
}

}  // namespace frictionsim::detail
