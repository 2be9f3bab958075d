// A well survey (stations: measured depth, inclination, azimuth) and its minimum-curvature trajectory (issue 14,
// item 1): between two stations the well is the circular arc tangent to both station directions. With t the unit
// tangent (north, east, down) = (sin I cos A, sin I sin A, cos I), a course of length dMD and dogleg angle beta
// (the angle between t1 and t2) moves the position by
//     dr = dMD / 2 * RF(beta) * (t1 + t2),   RF = (2 / beta) tan(beta / 2)
// (the ratio factor; Sawaryn & Thorogood 2005, SPE 84246, a compendium of minimum-curvature calculations;
// RF -> 1 + beta^2 / 12 as beta -> 0, the balanced-tangential limit).
// Inside a course the tangent turns at a constant rate in the plane of t1 and t2 (spherical interpolation), so any
// measured depth gets its inclination, azimuth, position and curvature from the same arc: the survey places the
// nodes of a lumped string on the well.
// SI inside (m, rad); Survey::from_degrees reads stations whose angles are in degrees.
// One survey type for the whole library (issue 22): the wells' torque and drag reads positions and curvature from it,
// the torsional string (string/torsional_string.hpp) its inclination along the string (inclination_at).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "detail/constants.hpp"
#include "detail/validate.hpp"
#include "parameters.hpp"

namespace frictionsim {

/// One survey station: measured depth along the hole [m], inclination from vertical [rad, 0..pi], azimuth from
/// north towards east [rad].
struct SurveyStation {
    double measured_depth = 0.0;
    double inclination = 0.0;
    double azimuth = 0.0;

    /// Each station's rules (what Survey checks; Python's Survey.parameters). Across stations: measured depth
    /// strictly increasing, no course turning by 180 degrees.
    static constexpr std::array<Field<SurveyStation>, 3> fields();
};

inline constexpr std::array<Field<SurveyStation>, 3> SurveyStation::fields() {
    using P = SurveyStation;
    return {{
        {"measured_depth", "MD", "m", Rule::finite().because("strictly increasing from station to station"),
         &P::measured_depth, "Measured depth along the hole."},
        {"inclination", "I", "rad", Rule::interval(0.0, pi), &P::inclination, "Inclination from vertical."},
        {"azimuth", "A", "rad", Rule::finite(), &P::azimuth, "Azimuth from north towards east."},
    }};
}

/// The well at one measured depth: direction, position relative to the first station (north, east, true vertical
/// depth, all m) and the curvature of the course it lies on (the dogleg severity, rad/m).
struct WellPoint {
    double measured_depth = 0.0;
    double inclination = 0.0;  ///< rad
    double azimuth = 0.0;      ///< rad, in [0, 2 pi)
    double north = 0.0, east = 0.0, tvd = 0.0;
    double curvature = 0.0;    ///< rad/m
    std::array<double, 3> tangent{{0.0, 0.0, 1.0}};  ///< unit tangent (north, east, down), pointing down-hole
};

/// rad/m -> degrees per 30 m, the usual unit of dogleg severity.
inline double degrees_per_30m(double curvature) { return curvature * 180.0 / pi * 30.0; }

/// Unit tangent (north, east, down) of a direction.
inline std::array<double, 3> well_tangent(double inclination, double azimuth) {
    const double s = std::sin(inclination);
    return {{s * std::cos(azimuth), s * std::sin(azimuth), std::cos(inclination)}};
}

/// The angle between two unit vectors, accurate for small and large angles alike: 2 atan2(|a - b|, |a + b|).
inline double angle_between(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double d = 0.0, s = 0.0;
    for (int k = 0; k < 3; ++k) {
        d += (a[k] - b[k]) * (a[k] - b[k]);
        s += (a[k] + b[k]) * (a[k] + b[k]);
    }
    return 2.0 * std::atan2(std::sqrt(d), std::sqrt(s));
}

/// Minimum curvature's ratio factor RF = (2 / beta) tan(beta / 2); its series 1 + beta^2/12 + beta^4/120 below
/// 1e-4 rad, where the closed form loses digits (and is 0/0 at beta = 0).
inline double ratio_factor(double dogleg) {
    if (dogleg < 1e-4) {
        const double b2 = dogleg * dogleg;
        return 1.0 + b2 / 12.0 + b2 * b2 / 120.0;
    }
    return 2.0 / dogleg * std::tan(0.5 * dogleg);
}

class Survey {
public:
    /// Stations in SI (m, rad), measured depth strictly increasing. Throws InvalidParameter naming the station and
    /// the field: fewer than two stations, NaN or infinite values, depth not increasing, inclination outside
    /// [0, pi], a course that turns the well back on itself (dogleg of 180 degrees: its arc has no plane).
    explicit Survey(std::vector<SurveyStation> stations) : Survey(std::move(stations), false) {}

    /// Stations whose inclination and azimuth are in degrees (measured depth in m); errors quote degrees.
    static Survey from_degrees(std::vector<SurveyStation> stations) { return Survey(std::move(stations), true); }

    std::size_t size() const { return stations_.size(); }
    const std::vector<SurveyStation>& stations() const { return stations_; }
    double first_depth() const { return stations_.front().measured_depth; }
    double last_depth() const { return stations_.back().measured_depth; }

    /// Position of station i relative to station 0 [m].
    double north(std::size_t i) const { return position_[i][0]; }
    double east(std::size_t i) const { return position_[i][1]; }
    double tvd(std::size_t i) const { return position_[i][2]; }
    /// Dogleg angle [rad] and severity [rad/m] of the course from station i - 1 to station i (i >= 1).
    double dogleg(std::size_t i) const { return dogleg_[i - 1]; }
    double dogleg_severity(std::size_t i) const {
        return dogleg_[i - 1] / (stations_[i].measured_depth - stations_[i - 1].measured_depth);
    }

    /// The course holding `md`: c such that md lies in [station c, station c + 1] (the upper station's course at
    /// a station). `md` must lie within the survey.
    std::size_t course_of(double md) const {
        check_depth(md);
        const auto after = std::upper_bound(depths_.begin(), depths_.end(), md);
        const auto c = static_cast<std::size_t>(after - depths_.begin());
        return std::min(c == 0 ? 0 : c - 1, stations_.size() - 2);
    }

    /// The well at measured depth `md` on the minimum-curvature arc (InvalidParameter outside the survey).
    WellPoint at(double md) const { return at(md, course_of(md)); }

    /// The inclination [rad] at measured depth `md`, held at the end stations' beyond them (a string that starts
    /// above the first station or reaches below the last continues straight). On a course in a vertical plane
    /// (equal azimuths, or one end vertical) the tangent turns at a constant rate within that plane, so the
    /// inclination is linear in md and is computed so (exactly; a well given by inclinations alone is such a well);
    /// otherwise it is the arc's, from at().
    double inclination_at(double md) const {
        if (md <= depths_.front()) return stations_.front().inclination;
        if (md >= depths_.back()) return stations_.back().inclination;
        const std::size_t i = static_cast<std::size_t>(std::upper_bound(depths_.begin(), depths_.end(), md) -
                                                       depths_.begin());
        const SurveyStation &a = stations_[i - 1], &b = stations_[i];
        if (a.azimuth == b.azimuth || std::sin(a.inclination) == 0.0 || std::sin(b.inclination) == 0.0) {
            const double s = (md - a.measured_depth) / (b.measured_depth - a.measured_depth);
            return a.inclination + s * (b.inclination - a.inclination);
        }
        return at(md, i - 1).inclination;
    }

    /// As at(md), on a known course (a caller walking down the well keeps its course index: no search); md must
    /// lie on that course.
    WellPoint at(double md, std::size_t course) const {
        if (course + 1 >= stations_.size())
            detail::reject("Survey", "course", ("< " + std::to_string(stations_.size() - 1)).c_str(),
                           static_cast<double>(course));
        if (!(md >= depths_[course] && md <= depths_[course + 1])) {
            const std::string rule = "on course " + std::to_string(course) + ", [" + std::to_string(depths_[course]) +
                                     ", " + std::to_string(depths_[course + 1]) + "] m";
            detail::reject("Survey", "measured_depth", rule.c_str(), md);
        }
        const SurveyStation& a = stations_[course];
        const SurveyStation& b = stations_[course + 1];
        const double length = b.measured_depth - a.measured_depth;
        const double s = std::min(std::max((md - a.measured_depth) / length, 0.0), 1.0);
        const double beta = dogleg_[course];
        const std::array<double, 3>& t1 = tangent_[course];
        const std::array<double, 3>& t2 = tangent_[course + 1];
        std::array<double, 3> t = t1;
        if (beta > 1e-12) {  // slerp: the tangent turns at a constant rate in the plane of t1 and t2
            const double w1 = std::sin((1.0 - s) * beta) / std::sin(beta), w2 = std::sin(s * beta) / std::sin(beta);
            double norm = 0.0;
            for (int k = 0; k < 3; ++k) {
                t[k] = w1 * t1[k] + w2 * t2[k];
                norm += t[k] * t[k];
            }
            norm = std::sqrt(norm);
            for (double& x : t) x /= norm;
        }
        // the part of the arc from station a to md is itself a minimum-curvature course of dogleg s beta
        const double half = 0.5 * s * length * ratio_factor(s * beta);
        WellPoint p;
        p.measured_depth = md;
        p.north = position_[course][0] + half * (t1[0] + t[0]);
        p.east = position_[course][1] + half * (t1[1] + t[1]);
        p.tvd = position_[course][2] + half * (t1[2] + t[2]);
        p.tangent = t;
        const double horizontal = std::hypot(t[0], t[1]);
        p.inclination = std::atan2(horizontal, t[2]);
        // azimuth is undefined on the vertical: keep the stations' (a's unless a is vertical)
        double azimuth = horizontal > 1e-14 ? std::atan2(t[1], t[0])
                                            : (std::sin(a.inclination) > 0.0 ? a.azimuth : b.azimuth);
        azimuth = std::fmod(azimuth, 2.0 * pi);
        p.azimuth = azimuth < 0.0 ? azimuth + 2.0 * pi : azimuth;
        p.curvature = beta / length;
        return p;
    }

private:
    Survey(std::vector<SurveyStation> stations, bool degrees) : stations_(std::move(stations)) {
        const char* owner = "Survey";
        if (stations_.size() < 2)
            detail::reject(owner, "stations", "at least 2 (a survey needs a course)",
                           static_cast<double>(stations_.size()));
        const double to_rad = degrees ? pi / 180.0 : 1.0;
        constexpr Rule inclination = SurveyStation::fields()[1].rule;  // [0, pi]: in degrees [0, 180] exactly
        for (std::size_t i = 0; i < stations_.size(); ++i) {
            SurveyStation& st = stations_[i];
            const std::string who = "Survey: station " + std::to_string(i);
            detail::require_finite(who.c_str(), "measured_depth", st.measured_depth);
            if (i > 0 && !(st.measured_depth > stations_[i - 1].measured_depth))
                detail::reject(who.c_str(), "measured_depth",
                               ("> the measured depth of station " + std::to_string(i - 1) + " (" +
                                std::to_string(stations_[i - 1].measured_depth) + " m): depths strictly increase")
                                   .c_str(),
                               st.measured_depth);
            if (!(std::isfinite(st.inclination) && st.inclination >= inclination.lower / to_rad &&
                  st.inclination <= inclination.upper / to_rad))
                detail::reject(who.c_str(), "inclination", degrees ? "in [0, 180] degrees" : "in [0, pi] rad",
                               st.inclination);
            detail::require_finite(who.c_str(), "azimuth", st.azimuth);
            st.inclination *= to_rad;
            st.azimuth *= to_rad;
        }
        const std::size_t n = stations_.size();
        depths_.resize(n);
        tangent_.resize(n);
        position_.assign(n, {{0.0, 0.0, 0.0}});
        dogleg_.resize(n - 1);
        for (std::size_t i = 0; i < n; ++i) {
            depths_[i] = stations_[i].measured_depth;
            tangent_[i] = well_tangent(stations_[i].inclination, stations_[i].azimuth);
        }
        for (std::size_t i = 1; i < n; ++i) {
            const std::array<double, 3>&t1 = tangent_[i - 1], &t2 = tangent_[i];
            const double beta = angle_between(t1, t2);
            if (!(beta < pi - 1e-9)) {
                const std::string who = "Survey: station " + std::to_string(i);
                detail::reject(who.c_str(), "inclination",
                               "such that the course from the previous station turns by less than 180 degrees "
                               "(a reversed direction has no arc)",
                               stations_[i].inclination / to_rad);
            }
            dogleg_[i - 1] = beta;
            const double half = 0.5 * (depths_[i] - depths_[i - 1]) * ratio_factor(beta);
            for (int k = 0; k < 3; ++k) position_[i][k] = position_[i - 1][k] + half * (t1[k] + t2[k]);
        }
    }

    void check_depth(double md) const {
        if (!(md >= depths_.front() && md <= depths_.back())) {
            const std::string rule = "within the survey, [" + std::to_string(depths_.front()) + ", " +
                                     std::to_string(depths_.back()) + "] m";
            detail::reject("Survey", "measured_depth", rule.c_str(), md);
        }
    }

    std::vector<SurveyStation> stations_;  // SI
    std::vector<double> depths_;
    std::vector<std::array<double, 3>> tangent_, position_;
    std::vector<double> dogleg_;  // per course
};

}  // namespace frictionsim
