// The survey's minimum-curvature trajectory against closed forms: circular arcs (a build in a vertical plane and a
// circle in a tilted plane) are placed exactly, at the stations and between them; a straight inclined hole; the
// dogleg against the classic spherical formula; the small-angle limit of the ratio factor; bad surveys named by
// station and field.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <frictionsim/survey.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::contains;
using frictionsim::test::deg;

namespace {

/// A vertical hole to `kickoff`, then a build of radius R at azimuth A: the closed form of the arc.
struct Build {
    double kickoff = 500.0, radius = 30.0 / (3.0 * deg), azimuth = 40.0 * deg;  // 3 degrees per 30 m
    double inclination(double md) const { return md <= kickoff ? 0.0 : (md - kickoff) / radius; }
    double horizontal(double md) const { return radius * (1.0 - std::cos(inclination(md))); }
    double tvd(double md) const { return md <= kickoff ? md : kickoff + radius * std::sin(inclination(md)); }
};

}  // namespace

TEST_CASE("minimum curvature: a build of known radius is placed exactly, at and between the stations", "[survey]") {
    const Build build;
    // irregular station spacing; the build ends at 90 degrees
    std::vector<double> depths{0.0, 250.0, 500.0, 517.3, 560.0, 600.0, 690.0, 750.0, 812.5, 900.0, 1000.0};
    const double end = build.kickoff + build.radius * pi / 2.0;
    depths.push_back(end);
    std::vector<SurveyStation> stations;
    for (double md : depths) stations.push_back({md, build.inclination(md), build.azimuth});
    const Survey survey(stations);
    for (std::size_t i = 0; i < survey.size(); ++i) {
        const double md = depths[i];
        INFO("station " << i << " at " << md << " m");
        CHECK(survey.north(i) == Approx(build.horizontal(md) * std::cos(build.azimuth)).margin(1e-9));
        CHECK(survey.east(i) == Approx(build.horizontal(md) * std::sin(build.azimuth)).margin(1e-9));
        CHECK(survey.tvd(i) == Approx(build.tvd(md)).margin(1e-9));
    }
    CHECK(survey.dogleg_severity(3) == Approx(1.0 / build.radius).epsilon(1e-12));
    CHECK(degrees_per_30m(survey.dogleg_severity(5)) == Approx(3.0).epsilon(1e-12));
    CHECK(survey.dogleg(1) == 0.0);
    for (double md = 0.0; md <= end; md += 7.3) {  // between the stations: the same arc
        const WellPoint p = survey.at(md);
        INFO("md " << md);
        CHECK(p.inclination == Approx(build.inclination(md)).margin(1e-12));
        CHECK(p.north == Approx(build.horizontal(md) * std::cos(build.azimuth)).margin(1e-9));
        CHECK(p.east == Approx(build.horizontal(md) * std::sin(build.azimuth)).margin(1e-9));
        CHECK(p.tvd == Approx(build.tvd(md)).margin(1e-9));
        CHECK(p.curvature == Approx(md < build.kickoff ? 0.0 : 1.0 / build.radius).margin(1e-15));
        if (md > build.kickoff) CHECK(p.azimuth == Approx(build.azimuth).epsilon(1e-12));
    }
}

TEST_CASE("minimum curvature: a circle in a tilted plane, tangent and position exact", "[survey]") {
    // t(s) = cos(s/R) u + sin(s/R) v, r(s) = R sin(s/R) u + R (1 - cos(s/R)) v: a turn and a build together
    const double radius = 400.0;
    const std::array<double, 3> u = well_tangent(30.0 * deg, 20.0 * deg);
    std::array<double, 3> v = well_tangent(70.0 * deg, 120.0 * deg);
    double dot = 0.0, norm = 0.0;
    for (int k = 0; k < 3; ++k) dot += u[k] * v[k];
    for (int k = 0; k < 3; ++k) v[k] -= dot * u[k];
    for (int k = 0; k < 3; ++k) norm += v[k] * v[k];
    for (double& x : v) x /= std::sqrt(norm);
    auto tangent = [&](double s) {
        std::array<double, 3> t{};
        for (int k = 0; k < 3; ++k) t[k] = std::cos(s / radius) * u[k] + std::sin(s / radius) * v[k];
        return t;
    };
    auto position = [&](double s) {
        std::array<double, 3> r{};
        for (int k = 0; k < 3; ++k)
            r[k] = radius * std::sin(s / radius) * u[k] + radius * (1.0 - std::cos(s / radius)) * v[k];
        return r;
    };
    auto station = [&](double s) {
        const std::array<double, 3> t = tangent(s);
        return SurveyStation{s, std::acos(t[2]), std::atan2(t[1], t[0])};
    };
    std::vector<SurveyStation> stations;
    for (double s : {0.0, 90.0, 150.0, 300.0, 330.0, 480.0}) stations.push_back(station(s));
    const Survey survey(stations);
    REQUIRE(survey.tvd(5) > 0.0);
    for (std::size_t i = 0; i < survey.size(); ++i) {
        const std::array<double, 3> r = position(stations[i].measured_depth);
        CHECK(survey.north(i) == Approx(r[0]).margin(1e-9));
        CHECK(survey.east(i) == Approx(r[1]).margin(1e-9));
        CHECK(survey.tvd(i) == Approx(r[2]).margin(1e-9));
        if (i > 0)
            CHECK(survey.dogleg(i) ==
                  Approx((stations[i].measured_depth - stations[i - 1].measured_depth) / radius).epsilon(1e-12));
    }
    for (double s = 0.0; s <= 480.0; s += 11.0) {
        const WellPoint p = survey.at(s);
        const std::array<double, 3> r = position(s), t = tangent(s);
        INFO("s " << s);
        CHECK(p.north == Approx(r[0]).margin(1e-9));
        CHECK(p.east == Approx(r[1]).margin(1e-9));
        CHECK(p.tvd == Approx(r[2]).margin(1e-9));
        CHECK(p.inclination == Approx(std::acos(t[2])).margin(1e-12));
        double azimuth = std::atan2(t[1], t[0]);
        if (azimuth < 0.0) azimuth += 2.0 * pi;
        CHECK(p.azimuth == Approx(azimuth).margin(1e-12));
        CHECK(p.curvature == Approx(1.0 / radius).epsilon(1e-12));
        for (int k = 0; k < 3; ++k) CHECK(p.tangent[k] == Approx(t[k]).margin(1e-12));
    }
}

TEST_CASE("minimum curvature: a straight inclined hole, and the ratio factor's small-angle limit", "[survey]") {
    const double inclination = 63.0 * deg, azimuth = 287.0 * deg;
    const Survey straight(
        {{0.0, inclination, azimuth}, {1000.0, inclination, azimuth}, {2500.0, inclination, azimuth}});
    const std::array<double, 3> t = well_tangent(inclination, azimuth);
    for (double md : {0.0, 123.4, 1000.0, 1777.0, 2500.0}) {
        const WellPoint p = straight.at(md);
        CHECK(p.north == Approx(md * t[0]).margin(1e-10));
        CHECK(p.east == Approx(md * t[1]).margin(1e-10));
        CHECK(p.tvd == Approx(md * t[2]).margin(1e-10));
        CHECK(p.curvature == 0.0);
        CHECK(p.azimuth == Approx(azimuth).epsilon(1e-14));
    }
    CHECK(straight.tvd(2) == Approx(2500.0 * std::cos(inclination)).epsilon(1e-14));

    // RF = (2 / beta) tan(beta / 2): the series below 1e-4 rad meets the closed form, and 1 at beta = 0
    CHECK(ratio_factor(0.0) == 1.0);
    CHECK(ratio_factor(1e-4 * (1.0 - 1e-12)) == Approx(2.0 / 1e-4 * std::tan(0.5e-4)).epsilon(1e-15));
    CHECK(ratio_factor(0.5) == Approx(4.0 * std::tan(0.25)).epsilon(1e-15));
    // a course bending by 1e-9 rad: the balanced-tangential displacement, no 0/0
    const Survey nearly({{0.0, 0.5, 1.0}, {100.0, 0.5 + 1e-9, 1.0}});
    const std::array<double, 3> t1 = well_tangent(0.5, 1.0), t2 = well_tangent(0.5 + 1e-9, 1.0);
    CHECK(nearly.tvd(1) == Approx(50.0 * (t1[2] + t2[2])).epsilon(1e-15));
    CHECK(nearly.north(1) == Approx(50.0 * (t1[0] + t2[0])).epsilon(1e-15));
    CHECK(nearly.dogleg(1) == Approx(1e-9).epsilon(1e-6));
    const WellPoint mid = nearly.at(50.0);
    CHECK(mid.inclination == Approx(0.5 + 0.5e-9).epsilon(1e-14));
    CHECK(std::isfinite(mid.azimuth));
}

TEST_CASE("survey: dogleg against the spherical formula - a vertical station's azimuth does not matter", "[survey]") {
    // the textbook spherical form: cos(beta) = cos(I2 - I1) - sin I1 sin I2 (1 - cos(A2 - A1))
    const std::vector<std::array<double, 4>> courses{
        {10.0, 30.0, 14.0, 42.0}, {45.0, 350.0, 50.0, 10.0}, {88.0, 90.0, 92.0, 96.0}, {5.0, 0.0, 3.0, 180.0},
        {120.0, 200.0, 60.0, 240.0}};
    for (const auto& c : courses) {
        const Survey survey = Survey::from_degrees({{1000.0, c[0], c[1]}, {1030.0, c[2], c[3]}});
        const double i1 = c[0] * deg, a1 = c[1] * deg, i2 = c[2] * deg, a2 = c[3] * deg;
        const double beta =
            std::acos(std::cos(i2 - i1) - std::sin(i1) * std::sin(i2) * (1.0 - std::cos(a2 - a1)));
        INFO("course " << c[0] << "/" << c[1] << " -> " << c[2] << "/" << c[3]);
        CHECK(survey.dogleg(1) == Approx(beta).epsilon(1e-10));
        CHECK(survey.dogleg_severity(1) == Approx(beta / 30.0).epsilon(1e-10));
        // from_degrees is the SI constructor after conversion
        const Survey si({{1000.0, i1, a1}, {1030.0, i2, a2}});
        CHECK(si.north(1) == Approx(survey.north(1)).epsilon(1e-14));
        CHECK(si.tvd(1) == Approx(survey.tvd(1)).epsilon(1e-14));
    }
    // the course from a vertical station lies in the lower station's azimuth, whatever the upper one says
    const Survey kickoff = Survey::from_degrees({{0.0, 0.0, 123.0}, {100.0, 10.0, 45.0}});
    CHECK(kickoff.north(1) == Approx(kickoff.east(1)).epsilon(1e-13));
    CHECK(kickoff.dogleg(1) == Approx(10.0 * deg).epsilon(1e-13));
    CHECK(kickoff.at(30.0).azimuth == Approx(45.0 * deg).epsilon(1e-13));
    CHECK(kickoff.at(0.0).azimuth == Approx(45.0 * deg).epsilon(1e-13));  // the vertical: the course's azimuth
}

TEST_CASE("survey: bad stations are refused naming the station and the field", "[survey][validation]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(rejected_parameter([] { (void)Survey({{0.0, 0.0, 0.0}}); }) == "stations");
    CHECK(rejected_parameter([] { (void)Survey(std::vector<SurveyStation>{}); }) == "stations");
    CHECK(contains(rejection_message([] { (void)Survey({{0.0, 0.0, 0.0}, {100.0, 0.1, 0.0}, {90.0, 0.2, 0.0}}); }),
                   "station 2: measured_depth must be > the measured depth of station 1"));
    CHECK(contains(rejection_message([] { (void)Survey({{0.0, 0.0, 0.0}, {0.0, 0.1, 0.0}}); }),
                   "station 1: measured_depth"));
    CHECK(contains(rejection_message([] { (void)Survey::from_degrees({{0.0, 0.0, 0.0}, {100.0, 181.0, 0.0}}); }),
                   "station 1: inclination must be in [0, 180] degrees (got 181)"));
    CHECK(contains(rejection_message([] { (void)Survey({{0.0, -0.01, 0.0}, {100.0, 0.1, 0.0}}); }),
                   "station 0: inclination must be in [0, pi] rad"));
    CHECK(contains(rejection_message([&] { (void)Survey({{0.0, 0.0, 0.0}, {100.0, 0.1, nan}}); }),
                   "station 1: azimuth must be finite"));
    CHECK(contains(rejection_message([&] { (void)Survey({{nan, 0.0, 0.0}, {100.0, 0.1, 0.0}}); }),
                   "station 0: measured_depth must be finite"));
    CHECK(contains(rejection_message([&] { (void)Survey({{0.0, nan, 0.0}, {100.0, 0.1, 0.0}}); }),
                   "station 0: inclination"));
    CHECK(contains(rejection_message([] {
                       (void)Survey({{0.0, 0.0, 0.0}, {100.0, 0.1, std::numeric_limits<double>::infinity()}});
                   }),
                   "station 1: azimuth"));
    // a course that reverses the direction (vertical down to vertical up) has no arc
    CHECK(contains(rejection_message([] { (void)Survey::from_degrees({{0.0, 0.0, 0.0}, {100.0, 180.0, 0.0}}); }),
                   "station 1: inclination"));
    const Survey survey({{100.0, 0.0, 0.0}, {200.0, 0.1, 0.0}});
    CHECK(rejected_parameter([&] { (void)survey.at(99.0); }) == "measured_depth");
    CHECK(rejected_parameter([&] { (void)survey.at(nan); }) == "measured_depth");
    CHECK(rejected_parameter([&] { (void)survey.at(200.5); }) == "measured_depth");
    CHECK(rejected_parameter([&] { (void)survey.at(150.0, 1); }) == "course");
    const Survey three({{0.0, 0.0, 0.0}, {100.0, 0.1, 0.0}, {200.0, 0.2, 0.0}});
    CHECK(rejected_parameter([&] { (void)three.at(150.0, 0); }) == "measured_depth");
    CHECK(three.at(150.0, 1).inclination == Approx(0.15).epsilon(1e-12));
}

TEST_CASE("survey: inclination along the string, linear on a course in a vertical plane, the arc's elsewhere",
          "[survey]") {
    // vertical to 500 m, building to 60 deg at 1600 m, held to 4000 m (A&S's Well B), all at azimuth 0
    const double build = pi / 3.0;
    const Survey well({{0.0, 0.0, 0.0}, {500.0, 0.0, 0.0}, {1600.0, build, 0.0}, {4000.0, build, 0.0}});
    CHECK(well.inclination_at(250.0) == 0.0);
    const double md = 1050.0, s = (md - 500.0) / 1100.0;
    CHECK(well.inclination_at(md) == s * build);  // linear, computed so: exact
    CHECK(well.inclination_at(md) == Approx(well.at(md).inclination).margin(1e-14));  // the arc's, rounding aside
    CHECK(well.inclination_at(3000.0) == build);
    // beyond the ends: held at the end stations' (the string goes on straight)
    CHECK(well.inclination_at(-10.0) == 0.0);
    CHECK(well.inclination_at(5000.0) == build);
    // a course that also turns in azimuth: not linear, the arc's inclination (at(): slerp of the tangent)
    const Survey turn({{0.0, pi / 4.0, 0.0}, {300.0, pi / 2.0, pi / 2.0}});
    for (double d : {30.0, 150.0, 270.0}) {
        const double linear = pi / 4.0 + d / 300.0 * pi / 4.0;
        CHECK(turn.inclination_at(d) == Approx(turn.at(d).inclination).margin(1e-14));
        CHECK(std::abs(turn.inclination_at(d) - linear) > 1e-3);
    }
    // one end vertical: the course lies in the vertical plane of the other's azimuth, linear again
    const Survey kick({{100.0, 0.0, 0.0}, {400.0, pi / 6.0, 1.0}});
    CHECK(kick.inclination_at(250.0) == Approx(kick.at(250.0).inclination).margin(1e-14));
    CHECK(kick.inclination_at(250.0) == 0.5 * pi / 6.0);
}

TEST_CASE("survey: the stations' table holds the rules Survey checks", "[survey][validation]") {
    // SurveyStation::fields() is what Python reads as Survey.parameters (and the property tests draw from); the
    // constructor takes its inclination bounds from it, in degrees exactly [0, 180]
    constexpr auto fields = SurveyStation::fields();
    CHECK(std::string(fields[1].name) == "inclination");
    CHECK(fields[1].rule.lower == 0.0);
    CHECK(fields[1].rule.upper == pi);
    CHECK_NOTHROW(Survey({{0.0, 0.0, 0.0}, {100.0, pi / 2, 0.0}, {200.0, pi, 0.0}}));
    CHECK_NOTHROW(Survey::from_degrees({{0.0, 0.0, 0.0}, {100.0, 90.0, 0.0}, {200.0, 180.0, 0.0}}));
    CHECK(rejected_parameter([] { (void)Survey({{0.0, 0.0, 0.0}, {100.0, std::nextafter(pi, 4.0), 0.0}}); }) ==
          "inclination");
    CHECK(rejected_parameter([] { (void)Survey::from_degrees({{0.0, 0.0, 0.0}, {100.0, 180.00000000000003, 0.0}}); }) ==
          "inclination");
    for (const auto& f : fields) {  // every field refuses a non-finite value
        SurveyStation bad{100.0, 0.1, 0.0};
        bad.*(f.member) = std::numeric_limits<double>::quiet_NaN();
        CHECK(rejected_parameter([&] { (void)Survey({{0.0, 0.0, 0.0}, bad}); }) == f.name);
    }
}
