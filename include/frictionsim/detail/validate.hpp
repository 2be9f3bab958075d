// Parameter checks shared by every law and rig: each names the owner, the parameter and the rule.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "../error.hpp"

namespace frictionsim::detail {

[[noreturn]] inline void reject(const char* owner, const char* name, const char* rule, double value) {
    std::ostringstream msg;
    msg.precision(17);
    msg << owner << ": " << name << " must be " << rule << " (got " << value << ")";
    throw InvalidParameter(name, msg.str());
}

inline double require_finite(const char* owner, const char* name, double value) {
    if (!std::isfinite(value)) reject(owner, name, "finite", value);
    return value;
}

inline double require_positive(const char* owner, const char* name, double value) {
    if (!(std::isfinite(value) && value > 0.0)) reject(owner, name, "positive and finite", value);
    return value;
}

inline double require_non_negative(const char* owner, const char* name, double value) {
    if (!(std::isfinite(value) && value >= 0.0)) reject(owner, name, "non-negative and finite", value);
    return value;
}

/// value >= lower (lower itself finite); `rule` says it in words, e.g. ">= friction_coefficient".
inline double require_at_least(const char* owner, const char* name, double value, double lower, const char* rule) {
    if (!(std::isfinite(value) && value >= lower)) reject(owner, name, rule, value);
    return value;
}

}  // namespace frictionsim::detail
