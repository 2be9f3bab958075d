// Power-law dynamic friction coefficient of paper 000 (eqs 10-17, Table 5): the cycle-averaged friction
// coefficient of a body sliding at v_d on a surface vibrating axially with velocity amplitude v_a,
//   mu_df = eta' (v_a / v_d)^c,   eta' = eta / (2 pi)^c   (eq 17),
// from dimensional analysis (eqs 11-14: F_df = eta F_N (u_0 f / v_d)^c) and v_a = 2 pi f u_0 (eq 16).
//
// This is a cycle-averaged coefficient, not an instantaneous friction law: it knows nothing of the phase
// within a vibration cycle, so it gives the mean force F_df = mu_df F_N over whole cycles and is not meant for a
// rig's right-hand side.
//
// Validity: Table 5 is a fit to Table 4's 25 runs, whose velocity ratios v_a/v_d span about 160-2560
// (u = 3-8 mm, f = 15-20 Hz, v_d = 20-120 mm/min), each lubricant over a part of it (five runs each: dry
// 450-850, water 280-2260, WBM 160-1360, OBM 300-2560, SBM 190-1510); the fits' R^2 are 0.63-0.88. Outside
// that range the law is an extrapolation, and at small ratios a plainly wrong one: with c < 0 it grows without
// bound as v_a/v_d -> 0 instead of tending to the sliding coefficient without vibration (section 2.4.1: dry
// about 0.41, WBM 0.36, SBM 0.32, OBM 0.27); the dry law passes 0.41 near v_a/v_d = 14. And for v_a <= v_d
// there is no friction-vector effect to fit at all.
#pragma once

#include <array>
#include <cctype>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../parameters.hpp"

namespace frictionsim {

/// The five lubricating conditions of paper 000 (Tables 3-5): dry, water, water-, oil- and synthetic-based mud.
enum class Lubricant { dry, water, wbm, obm, sbm };

inline const char* lubricant_name(Lubricant lubricant) {
    switch (lubricant) {
        case Lubricant::dry: return "dry";
        case Lubricant::water: return "water";
        case Lubricant::wbm: return "wbm";
        case Lubricant::obm: return "obm";
        case Lubricant::sbm: return "sbm";
    }
    return "unknown";
}

/// Case-insensitive lookup ("dry", "water", "wbm", "obm", "sbm"); throws InvalidParameter("lubricant", ...)
/// listing the valid names.
inline Lubricant lubricant_from_name(std::string_view name) {
    constexpr std::array<Lubricant, 5> all{Lubricant::dry, Lubricant::water, Lubricant::wbm, Lubricant::obm,
                                           Lubricant::sbm};
    for (const Lubricant candidate : all) {
        const std::string_view valid = lubricant_name(candidate);
        if (valid.size() != name.size()) continue;
        bool same = true;
        for (std::size_t i = 0; i < name.size() && same; ++i)
            same = std::tolower(static_cast<unsigned char>(name[i])) == valid[i];
        if (same) return candidate;
    }
    throw InvalidParameter("lubricant", "lubricant_from_name: lubricant must be one of dry, water, wbm, obm, sbm "
                                        "(case-insensitive; got '" + std::string(name) + "')");
}

/// One row of paper 000's Table 5, as printed. The fitting line is y = slope x + intercept with
/// y = log10(mu_df) and x = log10(v_a / v_d), so slope = c and 10^intercept = eta' (to the printed rounding).
struct Table5Row {
    Lubricant lubricant;
    double eta_prime;      ///< eta' [-], the coefficient column
    double exponent;       ///< c [-]
    double fit_slope;      ///< printed slope of the log-log fitting line
    double fit_intercept;  ///< printed intercept of the log-log fitting line
    double fit_r_squared;  ///< printed R^2 of the fit
};

/// Table 5 of paper 000, rows in the order of enum Lubricant.
inline const std::array<Table5Row, 5>& table5() {
    static const std::array<Table5Row, 5> rows{{
        {Lubricant::dry, 1.0676, -0.36513, -0.36513, 0.0284, 0.73},
        {Lubricant::water, 0.1951, -0.09531, -0.09531, -0.70976, 0.63},
        {Lubricant::wbm, 0.2116, -0.16533, -0.16533, -0.6745, 0.88},
        {Lubricant::obm, 0.1332, -0.20306, -0.20306, -0.87549, 0.82},
        {Lubricant::sbm, 0.1231, -0.09244, -0.09244, -0.91003, 0.87},
    }};
    return rows;
}

inline const Table5Row& table5(Lubricant lubricant) { return table5()[static_cast<std::size_t>(lubricant)]; }

/// v_a [m/s]: velocity amplitude of a harmonic vibration u = u_0 sin(2 pi f t), v_a = 2 pi f u_0 (eq 16).
inline double vibration_velocity_amplitude(double amplitude, double frequency) {
    constexpr const char* who = "vibration_velocity_amplitude";
    detail::require_non_negative(who, "amplitude", amplitude);
    detail::require_non_negative(who, "frequency", frequency);
    const double velocity = 2.0 * pi * frequency * amplitude;
    if (!std::isfinite(velocity)) detail::reject(who, "amplitude", "such that 2 pi f u_0 is finite", amplitude);
    return velocity;
}

/// mu_df = eta' (v_a / v_d)^c (paper 000, eq 17). See the header comment for the range it was fitted over.
struct PowerLawCoefficient {
    static constexpr const char* who = "PowerLawCoefficient";

    struct Params {
        double eta;       ///< eta' [-]: the prefactor of eq 17 and Table 5 (eq 15's eta is eta' (2 pi)^c)
        double exponent;  ///< c [-]: negative when vibration reduces friction more as v_a/v_d grows
    };

    /// Smallest and largest v_a/v_d of Table 4 (runs VS11 and VS20), the range Table 5 was fitted over.
    static constexpr double fitted_velocity_ratio_min = 160.0;
    static constexpr double fitted_velocity_ratio_max = 2564.0;

    /// eta' is mu_df at v_a = v_d, a friction coefficient: at most 10, the identification's upper bound on any mu
    /// (Table 5: 0.12 to 1.07). |c| at most 2: the friction-vector effect alone gives a cycle mean falling as
    /// (v_a/v_d)^-1 at large ratios, Table 5's exponents are -0.09 to -0.37, and c = 1e300 returned inf before.
    static constexpr double max_eta = 10.0;
    static constexpr double max_exponent_magnitude = 2.0;
    static constexpr std::array<Field<Params>, 2> fields{{
        {"eta", "eta'", "-",
         Rule::interval(0.0, max_eta, true, false).because("it is mu_df at v_a = v_d; Table 5: 0.12 to 1.07"),
         &Params::eta, "Prefactor of eq 17 (eq 15's eta is eta' (2 pi)^c).", nullptr, true},
        {"exponent", "c", "-",
         Rule::interval(-max_exponent_magnitude, max_exponent_magnitude).because("Table 5: -0.09 to -0.37"),
         &Params::exponent, "Exponent of v_a / v_d: negative when vibration reduces friction.", nullptr, true},
    }};

    explicit PowerLawCoefficient(Params params) : params_(params) { validate_fields(who, params_, fields); }

    /// From eq 15's form mu_df = eta (u_0 f / v_d)^c: eta' = eta / (2 pi)^c (eq 17), in the constructor's range.
    static PowerLawCoefficient from_eq15(double eta, double exponent) {
        detail::require_positive(who, "eta", eta);
        validate_fields(who, Params{1.0, exponent}, fields);
        const double eta_prime = eta / std::pow(2.0 * pi, exponent);
        if (!(eta_prime <= max_eta))
            detail::reject(who, "eta", "such that eta' = eta / (2 pi)^c is at most 10", eta);
        return PowerLawCoefficient(Params{eta_prime, exponent});
    }

    /// Table 5's fit for one lubricant, eta' and c exactly as printed.
    static PowerLawCoefficient from_table5(Lubricant lubricant) {
        const Table5Row& row = table5(lubricant);
        return PowerLawCoefficient(Params{row.eta_prime, row.exponent});
    }

    /// Same, by name: "dry", "water", "wbm", "obm", "sbm", case-insensitive.
    static PowerLawCoefficient from_table5(std::string_view name) { return from_table5(lubricant_from_name(name)); }

    const Params& params() const noexcept { return params_; }

    /// mu_df [-] for vibration velocity amplitude v_a [m/s] and sliding velocity v_d [m/s], both > 0. Only the
    /// ratio matters, so any common unit works. A ratio so extreme that mu_df over- or underflows is rejected,
    /// naming v_a: never an inf, NaN or 0 returned.
    double coefficient(double vibration_velocity_amplitude, double sliding_velocity) const {
        detail::require_positive(who, "vibration_velocity_amplitude", vibration_velocity_amplitude);
        detail::require_positive(who, "sliding_velocity", sliding_velocity);
        const double ratio = vibration_velocity_amplitude / sliding_velocity;
        const double mu = params_.eta * std::pow(ratio, params_.exponent);
        if (!(std::isfinite(mu) && mu > 0.0)) {
            std::ostringstream rule;
            rule.precision(17);
            rule << "such that v_a / v_d (v_d = " << sliding_velocity << ") gives a finite, positive mu_df = eta' "
                 << "(v_a / v_d)^c (c = " << params_.exponent << ")";
            detail::reject(who, "vibration_velocity_amplitude", rule.str().c_str(), vibration_velocity_amplitude);
        }
        return mu;
    }

    /// F_df = mu_df F_N [N]: magnitude of the mean friction force over whole vibration cycles, opposing the
    /// sliding (eq 14). normal_force F_N [N] >= 0; v_a and v_d [m/s] > 0.
    double friction_force(double normal_force, double vibration_velocity_amplitude,
                          double sliding_velocity) const {
        detail::require_non_negative(who, "normal_force", normal_force);
        const double force = normal_force * coefficient(vibration_velocity_amplitude, sliding_velocity);
        if (!std::isfinite(force))
            detail::reject(who, "normal_force", "such that F_df = mu_df F_N is finite", normal_force);
        return force;
    }

private:
    Params params_;
};

}  // namespace frictionsim
