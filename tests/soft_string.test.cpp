// Soft-string torque and drag against closed forms: a straight inclined pipe, the capstan relation around a
// weightless arc, pure rotation, the friction vector's split of axial and circumferential friction, a weighted build
// with tension-dominated contact (the exponential closed form of the continuous equation, approached at first
// order in the element length) and with the contact switching to the low side (the continuous equation with the
// absolute value, integrated independently), the buckling loads against their formulas worked in field units, the
// node side forces given a tension profile, and bad input named. Aadnoy's curvature form (TorqueDragMethod::aadnoy,
// tag [aadnoy]): the build's closed form and the capstan to rounding at any element length, the contact switch
// against RK4, straight pipe / friction vector / multipliers / buckling as Johancsik's, and on a 3D well both methods
// against an independent RK4 of the continuous 3D equation (orders measured: 1 and 2); a locked-up string named.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <frictionsim/wells/buckling.hpp>
#include <frictionsim/wells/soft_string.hpp>

#include "catch.hpp"
#include "drill_pipe.hpp"
#include "rejection.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::buoyed;
using frictionsim::test::pipe;
using frictionsim::test::contains;
using frictionsim::test::deg;

namespace {

constexpr double g = standard_gravity;

SoftStringParams open_hole(double mu) {
    SoftStringParams p;
    p.open_hole_friction = mu;
    p.cased_hole_friction = mu;
    return p;
}

/// A 6 km 3D well: vertical to 500 m, build and turn to 60 degrees by 1500 m, tangent, drop to 45 degrees.
Survey field_well() {
    return Survey::from_degrees({{0.0, 0.0, 0.0},
                                 {500.0, 0.0, 30.0},
                                 {1000.0, 30.0, 50.0},
                                 {1500.0, 60.0, 80.0},
                                 {3000.0, 60.0, 80.0},
                                 {3600.0, 45.0, 95.0},
                                 {6000.0, 45.0, 95.0}});
}

/// The constant-curvature build of the continuous soft string, tension-dominated contact (F/R > w sin theta):
/// dF/dtheta = -R (w cos theta + sigma (F / R - w sin theta)), sigma = +mu pulling out, -mu running in. Linear in F:
/// F = a cos theta + b sin theta + C exp(-sigma theta), a = -2 sigma R w / (1 + sigma^2),
/// b = R w (sigma^2 - 1) / (1 + sigma^2), C from F(theta_bottom) = F_bottom.
double build_tension(double theta, double theta_bottom, double force_bottom, double radius, double w, double sigma) {
    const double a = -2.0 * sigma * radius * w / (1.0 + sigma * sigma);
    const double b = radius * w * (sigma * sigma - 1.0) / (1.0 + sigma * sigma);
    auto particular = [&](double t) { return a * std::cos(t) + b * std::sin(t); };
    return particular(theta) + (force_bottom - particular(theta_bottom)) * std::exp(-sigma * (theta - theta_bottom));
}

/// The continuous equation with the absolute value (the contact on the high or the low side), classical RK4 from
/// the bottom of the build up: the independent reference where the contact switches sides.
double build_tension_rk4(double theta_bottom, double force_bottom, double radius, double w, double sigma,
                         int steps) {
    auto rate = [&](double t, double f) {
        return -radius * (w * std::cos(t) + sigma * std::abs(f / radius - w * std::sin(t)));
    };
    const double h = -theta_bottom / steps;
    double f = force_bottom, t = theta_bottom;
    for (int i = 0; i < steps; ++i) {
        const double k1 = rate(t, f), k2 = rate(t + h / 2, f + h / 2 * k1), k3 = rate(t + h / 2, f + h / 2 * k2),
                     k4 = rate(t + h, f + h * k3);
        f += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        t += h;
    }
    return f;
}

/// The continuous soft string along a survey's minimum-curvature path, classical RK4 from the bit up, independent
/// of SoftString's elements: dF/ds = -w t_z - sigma |F dt/ds + w (z - t_z t)|, dM/ds = -mu_c r |...| (s measured
/// depth, t the unit tangent, z down). Returns {hook load, surface torque}; steps per course.
struct Continuous {
    double hook_load, surface_torque;
};
Continuous continuous_soft_string(const Survey& survey, double length, double w, double sigma, double torque_per_force,
                                  double bit_force, int steps) {
    const std::vector<SurveyStation>& st = survey.stations();
    auto rate = [&](std::size_t c, double md, double f, double& torque_rate) {
        const std::array<double, 3> t1 = well_tangent(st[c].inclination, st[c].azimuth),
                                    t2 = well_tangent(st[c + 1].inclination, st[c + 1].azimuth);
        const double beta = survey.dogleg(c + 1), course = st[c + 1].measured_depth - st[c].measured_depth;
        const double x = (md - st[c].measured_depth) / course;
        std::array<double, 3> t = t1, turn{{0.0, 0.0, 0.0}};  // the tangent and dt/ds on the arc
        if (beta > 0.0)
            for (int k = 0; k < 3; ++k) {
                t[k] = (std::sin((1 - x) * beta) * t1[k] + std::sin(x * beta) * t2[k]) / std::sin(beta);
                turn[k] = beta / course * (-std::cos((1 - x) * beta) * t1[k] + std::cos(x * beta) * t2[k]) /
                          std::sin(beta);
            }
        double squared = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double n = f * turn[k] + w * ((k == 2 ? 1.0 : 0.0) - t[2] * t[k]);
            squared += n * n;
        }
        torque_rate = -torque_per_force * std::sqrt(squared);
        return -w * t[2] - sigma * std::sqrt(squared);
    };
    double f = bit_force, m = 0.0;
    std::size_t last = 0;
    while (st[last + 1].measured_depth < length) ++last;
    for (std::size_t c = last + 1; c-- > 0;) {
        const double bottom = std::min(st[c + 1].measured_depth, length);
        const double h = -(bottom - st[c].measured_depth) / steps;
        double md = bottom;
        for (int i = 0; i < steps; ++i) {
            double m1, m2, m3, m4;
            const double k1 = rate(c, md, f, m1), k2 = rate(c, md + h / 2, f + h / 2 * k1, m2),
                         k3 = rate(c, md + h / 2, f + h / 2 * k2, m3), k4 = rate(c, md + h, f + h * k3, m4);
            f += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
            m += h / 6 * (m1 + 2 * m2 + 2 * m3 + m4);
            md += h;
        }
    }
    return {f, m};
}

}  // namespace

TEST_CASE("soft string: a straight inclined pipe changes tension by w L (cos I +/- mu sin I)", "[soft_string]") {
    const double inclination = 60.0 * deg, length = 3000.0, mu = 0.3;
    const Survey survey({{0.0, inclination, 1.0}, {length, inclination, 1.0}});
    const PipeSection dp = pipe(length);
    const SoftString string(survey, DrillString({dp}), 300);
    const SoftStringParams p = open_hole(mu);
    const double w = buoyed(dp, p.mud_density);
    const TorqueDragResult out = string.run(Operation::trip_out, p);
    const TorqueDragResult in = string.run(Operation::trip_in, p);
    CHECK(out.hook_load() == Approx(w * length * (std::cos(inclination) + mu * std::sin(inclination))).epsilon(1e-12));
    CHECK(in.hook_load() == Approx(w * length * (std::cos(inclination) - mu * std::sin(inclination))).epsilon(1e-12));
    for (std::size_t i = 0; i <= 300; i += 37) {  // linear along the string, zero at the bit
        const double below = length - out.measured_depth[i];
        CHECK(out.tension[i] ==
              Approx(w * below * (std::cos(inclination) + mu * std::sin(inclination))).margin(1e-9 * w * length));
    }
    for (std::size_t e = 0; e < 300; e += 41) CHECK(out.side_force_per_length[e] == Approx(w * std::sin(inclination)));
    CHECK(out.surface_torque() == 0.0);
    CHECK(in.torque[150] == 0.0);

    // cased above 1000 m at mu_c = 0.15: each part drags with its own factor
    SoftStringParams cased = p;
    cased.casing_shoe_depth = 1000.0;
    cased.cased_hole_friction = 0.15;
    CHECK(string.run(Operation::trip_out, cased).hook_load() ==
          Approx(w * length * std::cos(inclination) + w * std::sin(inclination) * (0.15 * 1000.0 + mu * 2000.0))
              .epsilon(1e-12));
}

TEST_CASE("soft string: a weightless string around an arc follows the capstan relation", "[soft_string]") {
    // from horizontal at azimuth 45 degrees, a 3D arc of 600 m down to 30 degrees at azimuth 200; below it 1200 m of
    // straight hole where a heavy section pulls F_in = w H (cos 30 +/- mu sin 30). The arc's pipe has the mud's
    // density: no weight, the side force is F dbeta and the explicit step gives F_in (1 +/- mu theta / n)^n exactly,
    // which tends to F_in exp(+/- mu theta) at first order.
    const double mu = 0.25, mud = 1200.0, arc = 600.0, straight = 1200.0;
    const Survey survey = Survey::from_degrees({{0.0, 90.0, 45.0}, {arc, 30.0, 200.0}, {arc + straight, 30.0, 200.0}});
    const double i1 = 90.0 * deg, a1 = 45.0 * deg, i2 = 30.0 * deg, a2 = 200.0 * deg;
    const double theta = std::acos(std::cos(i2 - i1) - std::sin(i1) * std::sin(i2) * (1.0 - std::cos(a2 - a1)));
    const PipeSection weightless = pipe(arc, mud), heavy = pipe(straight);
    const DrillString drill_string({weightless, heavy});
    SoftStringParams p = open_hole(mu);
    p.mud_density = mud;
    const double w = buoyed(heavy, mud);
    double previous_out = 0.0, previous_in = 0.0;
    for (std::size_t n : {90u, 180u, 360u, 720u}) {  // a node at the arc's end every time
        const SoftString string(survey, drill_string, n);
        const double arc_elements = static_cast<double>(n) * arc / (arc + straight);
        const double pulled = w * straight * (std::cos(i2) + mu * std::sin(i2));
        const double pushed = w * straight * (std::cos(i2) - mu * std::sin(i2));
        const double out = string.run(Operation::trip_out, p).hook_load();
        const double in = string.run(Operation::trip_in, p).hook_load();
        CHECK(out == Approx(pulled * std::pow(1.0 + mu * theta / arc_elements, arc_elements)).epsilon(1e-11));
        CHECK(in == Approx(pushed * std::pow(1.0 - mu * theta / arc_elements, arc_elements)).epsilon(1e-11));
        const double error_out = std::abs(out / (pulled * std::exp(mu * theta)) - 1.0);
        const double error_in = std::abs(in / (pushed * std::exp(-mu * theta)) - 1.0);
        INFO("N = " << n << ": capstan relative error " << error_out << " (out), " << error_in << " (in)");
        CHECK(error_out < 0.6 * mu * mu * theta * theta / arc_elements);  // leading term mu^2 theta^2 / (2 n)
        CHECK(error_in < 0.6 * mu * mu * theta * theta / arc_elements);
        if (previous_out > 0.0) {
            CHECK(previous_out / error_out == Approx(2.0).epsilon(0.02));
            CHECK(previous_in / error_in == Approx(2.0).epsilon(0.02));
        }
        previous_out = error_out;
        previous_in = error_in;
    }
}

TEST_CASE("soft string: a course through the vertical turns the tension by its dogleg, not its azimuth change",
          "[soft_string]") {
    // 20 degrees towards north to 20 degrees towards south over one 400 m course: the arc passes the vertical and
    // turns by 40 degrees while the azimuth jumps by 180 (Johancsik's dA sin I_avg would see 180 degrees there).
    // Weightless pipe on the arc, a heavy section below: F_in (1 + mu theta / n)^n exactly, as on any arc.
    const double mu = 0.3, mud = 1200.0, arc = 400.0, straight = 800.0, theta = 40.0 * deg;
    const Survey survey = Survey::from_degrees({{0.0, 20.0, 0.0}, {arc, 20.0, 180.0}, {arc + straight, 20.0, 180.0}});
    REQUIRE(survey.dogleg(1) == Approx(theta).epsilon(1e-12));
    const PipeSection weightless = pipe(arc, mud), heavy = pipe(straight);
    const SoftString string(survey, DrillString({weightless, heavy}), 300);  // 100 elements on the arc
    SoftStringParams p = open_hole(mu);
    p.mud_density = mud;
    const double pulled = buoyed(heavy, mud) * straight * (std::cos(20.0 * deg) + mu * std::sin(20.0 * deg));
    CHECK(string.run(Operation::trip_out, p).hook_load() ==
          Approx(pulled * std::pow(1.0 + mu * theta / 100.0, 100.0)).epsilon(1e-11));
}

TEST_CASE("soft string: pure rotation carries no axial friction - torque = mu r times the sum of side forces",
          "[soft_string]") {
    PipeSection collar = pipe(200.0);
    collar.outer_diameter = 0.1651;
    collar.inner_diameter = 0.0714;
    const DrillString drill_string({pipe(5300.0), pipe(300.0), collar});  // 5.8 km, the collars deepest
    const SoftString string(field_well(), drill_string, 1450);           // elements across section boundaries
    SoftStringParams p;
    p.casing_shoe_depth = 2000.0;
    p.cased_hole_friction = 0.2;
    p.open_hole_friction = 0.35;
    const TorqueDragResult rotating = string.run(Operation::rotating_off_bottom, p);
    SoftStringParams frictionless = p;
    frictionless.cased_hole_friction = frictionless.open_hole_friction = 0.0;
    const TorqueDragResult hanging = string.run(Operation::trip_out, frictionless);
    double torque = 0.0;
    for (std::size_t e = 0; e < string.elements(); ++e) {
        const double mid = 0.5 * (rotating.measured_depth[e] + rotating.measured_depth[e + 1]);
        const double mu = mid < 2000.0 ? 0.2 : 0.35;
        // the element's contact radius: its pieces' OD / 2 weighted by length
        const double top = rotating.measured_depth[e], bottom = rotating.measured_depth[e + 1];
        const double in_collar = std::max(0.0, bottom - std::max(top, 5600.0));
        const double radius = ((bottom - top - in_collar) * 0.127 / 2 + in_collar * 0.1651 / 2) / (bottom - top);
        torque += mu * radius * rotating.side_force[e];
    }
    CHECK(rotating.surface_torque() == Approx(torque).epsilon(1e-12));
    for (std::size_t i = 0; i <= string.elements(); i += 97) CHECK(rotating.tension[i] == Approx(hanging.tension[i]));
    CHECK(rotating.hook_load() == Approx(hanging.hook_load()).epsilon(1e-12));
    // and the drag of the trips brackets it
    CHECK(string.run(Operation::trip_out, p).hook_load() > rotating.hook_load());
    CHECK(string.run(Operation::trip_in, p).hook_load() < rotating.hook_load());
    CHECK(rotating.surface_torque() > 10e3);  // a 5.8 km string in a 60 degree well: over 10 kN m off bottom
}

TEST_CASE("soft string: the side force is Johancsik's as elements shrink, also where the well turns", "[soft_string]") {
    // F_n = sqrt((F dA sin I_avg)^2 + (F dI + W sin I_avg)^2) (Johancsik et al. 1984) on the 1 m elements of a build
    // and turn, against the dogleg form used here
    const Survey survey = field_well();
    const DrillString drill_string({pipe(6000.0)});
    const SoftString string(survey, drill_string, 6000);
    const double mud = 1200.0, tension = 400e3;
    for (std::size_t e : {600u, 900u, 1200u, 1499u, 3100u, 3500u}) {
        const WellPoint top = survey.at(static_cast<double>(e)), bottom = survey.at(static_cast<double>(e + 1));
        const double weight = string.element_weight(e, mud);
        const double sin_avg = std::sin(0.5 * (top.inclination + bottom.inclination));
        const double johancsik =
            std::hypot(tension * (top.azimuth - bottom.azimuth) * sin_avg,
                       tension * (top.inclination - bottom.inclination) + weight * sin_avg);
        INFO("element " << e);
        CHECK(string.element_side_force(e, tension, mud) == Approx(johancsik).epsilon(1e-6));
    }
}

TEST_CASE("soft string: the friction vector splits axial and circumferential friction", "[soft_string]") {
    // a straight pipe reaming at v with surface speed omega r: axial drag mu W sin I v / sqrt(v^2 + (omega r)^2),
    // torque mu r W sin I omega r / sqrt(...) (paper 000's friction vector)
    const double inclination = 75.0 * deg, length = 2000.0, mu = 0.3, v = 0.3, r = 0.127 / 2;
    const Survey survey({{0.0, inclination, 0.0}, {length, inclination, 0.0}});
    const PipeSection dp = pipe(length);
    const SoftString string(survey, DrillString({dp}), 200);
    SoftStringParams p = open_hole(mu);
    p.trip_speed = v;
    const double weight = buoyed(dp, p.mud_density) * length;
    const double drag = mu * weight * std::sin(inclination);
    for (double ratio : {0.25, 1.0, 4.0}) {  // (omega r) / v
        p.rotary_speed = ratio * v / r;
        const double axial = 1.0 / std::sqrt(1.0 + ratio * ratio), circumferential = ratio * axial;
        const TorqueDragResult down = string.run(Operation::reaming, p), up = string.run(Operation::backreaming, p);
        INFO("omega r / v = " << ratio);
        CHECK(weight * std::cos(inclination) - down.hook_load() == Approx(drag * axial).epsilon(1e-12));
        CHECK(up.hook_load() - weight * std::cos(inclination) == Approx(drag * axial).epsilon(1e-12));
        CHECK(down.surface_torque() == Approx(drag * circumferential * r).epsilon(1e-12));
        CHECK(up.surface_torque() == Approx(drag * circumferential * r).epsilon(1e-12));
    }
    // rotary drilling: the bit's loads carried up, the ROP against the surface speed
    p.rotary_speed = 120.0 * pi / 30.0;
    p.rate_of_penetration = 20.0 / 3600.0;
    p.weight_on_bit = 80e3;
    p.bit_torque = 6e3;
    const double ratio = p.rate_of_penetration / std::hypot(p.rate_of_penetration, p.rotary_speed * r);
    const TorqueDragResult drilling = string.run(Operation::rotary_drilling, p);
    CHECK(drilling.tension.back() == -80e3);
    CHECK(drilling.hook_load() == Approx(weight * std::cos(inclination) - 80e3 - drag * ratio).epsilon(1e-12));
    CHECK(drilling.surface_torque() ==
          Approx(6e3 + drag * r * std::sqrt(1.0 - ratio * ratio)).epsilon(1e-12));
    const TorqueDragResult sliding = string.run(Operation::sliding_drilling, p);  // no rotation: all axial
    CHECK(sliding.hook_load() == Approx(weight * std::cos(inclination) - 80e3 - drag).epsilon(1e-12));
    CHECK(sliding.surface_torque() == 0.0);
}

TEST_CASE("soft string: a weighted build with tension-dominated contact approaches the continuous closed form at "
          "first order", "[soft_string]") {
    // kick off at the surface, build to 60 degrees over 600 m (R = 573 m, 3 degrees per 30 m), then 2400 m of
    // straight hole whose weight keeps the pipe on the high side of the build (F / R > w sin theta)
    const double mu = 0.3, build = 600.0, tangent = 2400.0, theta1 = 60.0 * deg, radius = build / theta1;
    const Survey survey = Survey::from_degrees({{0.0, 0.0, 0.0}, {build, 60.0, 0.0}, {build + tangent, 60.0, 0.0}});
    const PipeSection dp = pipe(build + tangent);
    const SoftStringParams p = open_hole(mu);
    const double w = buoyed(dp, p.mud_density);
    for (double sigma : {mu, -mu}) {  // trip out, trip in
        const double bottom = w * tangent * (std::cos(theta1) + sigma * std::sin(theta1));
        for (double t = 0.0; t <= theta1; t += theta1 / 50)  // the closed form's premise
            REQUIRE(build_tension(t, theta1, bottom, radius, w, sigma) / radius > w * std::sin(t));
        const double exact = build_tension(0.0, theta1, bottom, radius, w, sigma);
        double previous = 0.0;
        for (std::size_t n : {300u, 600u, 1200u, 2400u}) {  // elements of 10, 5, 2.5, 1.25 m
            const SoftString string(survey, DrillString({dp}), n);
            const TorqueDragResult r = string.run(sigma > 0 ? Operation::trip_out : Operation::trip_in, p);
            const std::size_t end_of_build = n / 5;
            REQUIRE(r.measured_depth[end_of_build] == build);
            CHECK(r.tension[end_of_build] == Approx(bottom).epsilon(1e-12));  // the straight part is exact
            const double error = std::abs(r.hook_load() / exact - 1.0);
            INFO((sigma > 0 ? "trip out" : "trip in") << ", N = " << n << ": hook load " << r.hook_load()
                                                      << " N, closed form " << exact << " N, relative error " << error);
            CHECK(error < 1.5e-4 * (3000.0 / static_cast<double>(n)));  // measured: 1.2e-4 per metre of element
            if (previous > 0.0) CHECK(previous / error == Approx(2.0).epsilon(0.05));  // first order
            previous = error;
        }
    }
}

TEST_CASE("soft string: where F / R < w sin theta the contact moves to the low side, as the continuous equation "
          "with the absolute value says", "[soft_string]") {
    // a build from vertical to horizontal with the bit (off bottom) at its end: near the bit the weight wins and
    // the pipe lies on the low side; higher up the tension pulls it to the high side
    const double mu = 0.3, theta1 = 90.0 * deg, radius = 30.0 / (3.0 * deg), build = radius * theta1;
    const Survey survey({{0.0, 0.0, 2.0}, {build, theta1, 2.0}});
    const PipeSection dp = pipe(build);
    const SoftStringParams p = open_hole(mu);
    const double w = buoyed(dp, p.mud_density);
    for (double sigma : {mu, -mu}) {
        const double reference = build_tension_rk4(theta1, 0.0, radius, w, sigma, 200000);
        const double no_switch = build_tension(0.0, theta1, 0.0, radius, w, sigma);  // high side everywhere
        CHECK(std::abs(no_switch / reference - 1.0) > 0.05);                         // the switch matters
        double previous = 0.0;
        for (std::size_t n : {300u, 600u, 1200u, 2400u}) {
            const SoftString string(survey, DrillString({dp}), n);
            const TorqueDragResult r = string.run(sigma > 0 ? Operation::trip_out : Operation::trip_in, p);
            const double error = std::abs(r.hook_load() / reference - 1.0);
            INFO((sigma > 0 ? "trip out" : "trip in") << ", N = " << n << ": relative error " << error);
            CHECK(error < 1e-2 * 300.0 / static_cast<double>(n));
            if (previous > 0.0) CHECK(previous / error == Approx(2.0).epsilon(0.1));
            previous = error;
            // the contact force per length is |F / R - w sin theta|: w at the bit, near zero where the sides switch
            const double last_element = build / static_cast<double>(n);
            CHECK(r.side_force_per_length.back() ==
                  Approx(w * std::sin(theta1 - 0.5 * last_element / radius)).epsilon(1e-3));
            const auto lowest = std::min_element(r.side_force_per_length.begin(), r.side_force_per_length.end());
            const std::size_t k = static_cast<std::size_t>(lowest - r.side_force_per_length.begin());
            const double theta_k = 0.5 * (r.measured_depth[k] + r.measured_depth[k + 1]) / radius;
            CHECK(std::abs(r.tension[k] / radius - w * std::sin(theta_k)) < 0.02 * w);
            CHECK(k > 0);
            CHECK(k + 1 < n);
        }
    }
}

TEST_CASE("buckling: Dawson-Paslay and Chen-Cheatham loads worked in field units, and the flags", "[soft_string]") {
    // 5" 19.5 lb/ft drill pipe (ID 4.276") in an 8 1/2" hole, horizontal, 10 ppg (1.2 SG) mud, worked in lbf and in:
    // I = pi/64 (5^4 - 4.276^4) = 14.27 in^4, E = 30.46e6 psi, w = (0.2836 - 0.04335) lb/in^3 x 5.277 in^2
    // = 1.268 lbf/in, r = 1.75 in: F_s = 2 sqrt(E I w / r) = 35,500 lbf (158 kN), F_h = sqrt(2) F_s = 50,200 lbf
    const double inch = 0.0254, lbf = 0.45359237 * g, psi = lbf / (inch * inch);
    const double od = 0.127 / inch, id = 0.1086 / inch, hole = 0.2159 / inch;
    const double e_psi = 210e9 / psi, steel = 7850.0 * inch * inch * inch / 0.45359237,
                 mud = 1200.0 * inch * inch * inch / 0.45359237;  // lb/in^3
    const double moment = pi / 64 * (std::pow(od, 4) - std::pow(id, 4)), area = pi / 4 * (od * od - id * id);
    const double w_field = (steel - mud) * area;  // lbf/in
    const double sinusoidal_lbf = 2.0 * std::sqrt(e_psi * moment * w_field / ((hole - od) / 2));
    CHECK(moment == Approx(14.27).epsilon(1e-3));
    CHECK(sinusoidal_lbf == Approx(35500.0).epsilon(3e-3));

    const PipeSection dp{};
    const double ei = dp.youngs_modulus * dp.polar_moment() / 2, w = buoyed(dp, 1200.0), r = (0.2159 - 0.127) / 2;
    CHECK(sinusoidal_buckling_load(ei, w, pi / 2, r) == Approx(sinusoidal_lbf * lbf).epsilon(1e-12));
    CHECK(helical_buckling_load(ei, w, pi / 2, r) == Approx(std::sqrt(2.0) * sinusoidal_lbf * lbf).epsilon(1e-12));
    CHECK(helical_buckling_load_wu_juvkam_wold(ei, w, pi / 2, r) ==
          Approx((2.0 * std::sqrt(2.0) - 1.0) * sinusoidal_lbf * lbf).epsilon(1e-12));
    CHECK(sinusoidal_buckling_load(ei, w, pi / 6, r) == Approx(std::sqrt(0.5) * sinusoidal_lbf * lbf).epsilon(1e-12));

    // sliding with 100 kN on the bit at the end of a 2000 m lateral: the compression grows by mu w per metre up
    // the lateral (pushing the string in) and crosses F_s, then F_h, at the closed-form depths
    const double radius = 30.0 / (3.0 * deg), lateral_start = 1000.0 + radius * pi / 2, td = lateral_start + 2000.0;
    const Survey survey({{0.0, 0.0, 0.0}, {1000.0, 0.0, 0.0}, {lateral_start, pi / 2, 0.0}, {td, pi / 2, 0.0}});
    const SoftString string(survey, DrillString({pipe(td)}), 3000);
    SoftStringParams p = open_hole(0.3);
    p.weight_on_bit = 100e3;
    const TorqueDragResult sliding = string.run(Operation::sliding_drilling, p);
    const double f_s = sinusoidal_lbf * lbf, f_h = std::sqrt(2.0) * f_s;
    std::size_t flagged_s = 0, flagged_h = 0;
    for (std::size_t i = 0; i <= string.elements(); ++i) {
        const double md = sliding.measured_depth[i];
        const double expected = 2.0 * std::sqrt(ei * w / r) * std::sqrt(std::sin(string.node_inclinations()[i]));
        INFO("node " << i << " at " << md << " m");
        CHECK(sliding.sinusoidal_buckling_load[i] == Approx(expected).epsilon(1e-12).margin(1e-9));
        CHECK(sliding.helical_buckling_load[i] == Approx(std::sqrt(2.0) * expected).epsilon(1e-12).margin(1e-9));
        CHECK(static_cast<bool>(sliding.sinusoidally_buckled[i]) == (-sliding.tension[i] > expected));
        if (md >= lateral_start) {
            CHECK(-sliding.tension[i] == Approx(100e3 + 0.3 * w * (td - md)).epsilon(1e-9));
            CHECK(static_cast<bool>(sliding.sinusoidally_buckled[i]) == (100e3 + 0.3 * w * (td - md) > f_s));
            flagged_s += sliding.sinusoidally_buckled[i];
            flagged_h += sliding.helically_buckled[i];
        }
    }
    // on the lateral: flagged above td - (F - WOB) / (mu w)
    const double element = td / 3000.0;
    CHECK(static_cast<double>(flagged_s) * element ==
          Approx(2000.0 - (f_s - 100e3) / (0.3 * w)).margin(1.01 * element));
    CHECK(static_cast<double>(flagged_h) * element ==
          Approx(2000.0 - (f_h - 100e3) / (0.3 * w)).margin(1.01 * element));
    CHECK(flagged_h > 0);
    CHECK(flagged_h < flagged_s);
}

TEST_CASE("soft string: node side forces for a given tension profile", "[soft_string]") {
    // a weightless arc under constant tension T: each element presses T dbeta, the nodes sum to T theta
    const double mud = 1200.0, theta = 40.0 * deg, radius = 800.0;
    const Survey arc({{0.0, 10.0 * deg, 0.3}, {radius * theta, 50.0 * deg, 0.3}});
    const SoftString weightless(arc, DrillString({pipe(radius * theta, mud)}), 64);
    const std::vector<double> tension(65, 250e3);
    const std::vector<double> nodes = weightless.node_side_forces(tension, mud);
    double total = 0.0;
    for (double f : nodes) total += f;
    CHECK(total == Approx(250e3 * theta).epsilon(1e-12));
    CHECK(nodes[10] == Approx(250e3 * theta / 64).epsilon(1e-10));
    CHECK(nodes[0] == Approx(0.5 * 250e3 * theta / 64).epsilon(1e-10));

    // a straight inclined pipe without tension: w dx sin I at each inner node, half at the ends
    const double inclination = 35.0 * deg;
    const Survey straight({{0.0, inclination, 0.0}, {1000.0, inclination, 0.0}});
    const PipeSection dp = pipe(1000.0);
    const SoftString string(straight, DrillString({dp}), 100);
    const std::vector<double> slack = string.node_side_forces(std::vector<double>(101, 0.0), mud);
    CHECK(slack[50] == Approx(buoyed(dp, mud) * 10.0 * std::sin(inclination)).epsilon(1e-12));
    CHECK(slack[100] == Approx(buoyed(dp, mud) * 5.0 * std::sin(inclination)).epsilon(1e-12));

    // the nodes are DrillString::lump(N)'s: with no tension each node presses its lumped mass's buoyed weight
    // across the pipe, also where an element straddles a section boundary
    PipeSection collar = pipe(130.0);
    collar.outer_diameter = 0.1651;
    collar.inner_diameter = 0.0714;
    const DrillString stepped({pipe(870.0), collar});
    const SoftString placed(straight, stepped, 77);
    const LumpedString lumped = stepped.lump(77);
    REQUIRE(placed.element_length() == lumped.element_length);
    const std::vector<double> pressed = placed.node_side_forces(std::vector<double>(78, 0.0), mud);
    for (std::size_t i = 0; i <= 77; ++i)
        CHECK(pressed[i] ==
              Approx(lumped.node_mass[i] * g * (1.0 - mud / 7850.0) * std::sin(inclination)).epsilon(1e-12));

    CHECK(rejected_parameter([&] { (void)string.node_side_forces(std::vector<double>(100, 0.0), mud); }) == "tension");
    std::vector<double> bad(101, 0.0);
    bad[3] = std::numeric_limits<double>::quiet_NaN();
    CHECK(rejected_parameter([&] { (void)string.node_side_forces(bad, mud); }) == "tension[3]");
    CHECK(rejected_parameter([&] { (void)string.node_side_forces(slack, -1.0); }) == "mud_density");
}

TEST_CASE("soft string: bad parameters and geometry are refused naming them", "[soft_string][validation]") {
    const Survey survey({{0.0, 0.0, 0.0}, {1000.0, 0.5, 0.0}});
    const DrillString drill_string({pipe(900.0)});
    const SoftString string(survey, drill_string, 90);
    auto rejected = [&](auto change) {
        SoftStringParams p;
        change(p);
        return rejected_parameter([&] { (void)string.run(Operation::trip_out, p); });
    };
    CHECK(rejected([](SoftStringParams& p) { p.mud_density = -1.0; }) == "mud_density");
    CHECK(rejected([](SoftStringParams& p) { p.open_hole_friction = std::nan(""); }) == "open_hole_friction");
    CHECK(rejected([](SoftStringParams& p) { p.rotary_speed = 0.0; }) == "rotary_speed");
    CHECK(rejected([](SoftStringParams& p) { p.trip_speed = -0.1; }) == "trip_speed");
    CHECK(rejected([](SoftStringParams& p) { p.weight_on_bit = -5.0; }) == "weight_on_bit");
    CHECK(rejected([](SoftStringParams& p) { p.hole_diameter = 0.12; }) == "hole_diameter");
    CHECK(rejected([](SoftStringParams& p) {
              p.casing_shoe_depth = 500.0;
              p.casing_inner_diameter = 0.127;
          }) == "casing_inner_diameter");
    SoftStringParams small_hole;
    small_hole.hole_diameter = 0.12;
    CHECK(contains(rejection_message([&] { (void)string.run(Operation::trip_in, small_hole); }),
                   "hole_diameter must be > the pipe's outer diameter"));
    CHECK(rejected_parameter([&] { (void)SoftString(survey, DrillString({pipe(1200.0)}), 10); }) ==
          "survey last measured_depth");
    const Survey deep({{100.0, 0.0, 0.0}, {1000.0, 0.5, 0.0}});
    CHECK(rejected_parameter([&] { (void)SoftString(deep, drill_string, 10); }) == "survey first measured_depth");
    CHECK(rejected_parameter([&] { (void)SoftString(survey, drill_string, 0); }) == "elements");
    CHECK_NOTHROW(string.run(Operation::rotary_drilling, SoftStringParams{}));  // the defaults obey the table
}

TEST_CASE("soft string: per-element friction multipliers scale each element's axial and circumferential friction",
          "[soft_string]") {
    // a straight inclined pipe: the drag is mu w sin I summed over the elements, each times its axial multiplier;
    // reaming, the torque is mu w sin I r (omega r / |q|) summed, each times its circumferential multiplier
    const double inclination = 70.0 * deg, length = 2000.0, mu = 0.3, r = 0.127 / 2;
    const Survey survey({{0.0, inclination, 0.0}, {length, inclination, 0.0}});
    const PipeSection dp = pipe(length);
    const SoftString string(survey, DrillString({dp}), 200);
    SoftStringParams p = open_hole(mu);
    const double w = buoyed(dp, p.mud_density), dx = 10.0;
    FrictionMultipliers m;
    m.axial.assign(200, 1.0);
    m.circumferential.assign(200, 1.0);
    for (Operation op : {Operation::trip_out, Operation::reaming, Operation::rotary_drilling}) {
        const TorqueDragResult plain = string.run(op, p);
        const TorqueDragResult ones = string.run(op, p, m), empty = string.run(op, p, FrictionMultipliers{});
        CHECK(ones.tension == plain.tension);  // bit for bit
        CHECK(ones.torque == plain.torque);
        CHECK(empty.tension == plain.tension);
    }
    double axial_sum = 0.0, circumferential_sum = 0.0;
    for (std::size_t e = 0; e < 200; ++e) {
        m.axial[e] = e >= 80 && e < 140 ? 0.1 + 0.01 * static_cast<double>(e - 80) : 1.0;
        m.circumferential[e] = e < 50 ? 0.5 : 1.0;
        axial_sum += m.axial[e] * dx;
        circumferential_sum += m.circumferential[e] * dx;
    }
    const double ratio = 1.0 / std::sqrt(1.0 + std::pow(p.rotary_speed * r / p.trip_speed, 2));  // v / |q|
    const TorqueDragResult out = string.run(Operation::trip_out, p, m);
    CHECK(out.hook_load() ==
          Approx(w * length * std::cos(inclination) + mu * w * std::sin(inclination) * axial_sum).epsilon(1e-12));
    const TorqueDragResult down = string.run(Operation::reaming, p, m);
    CHECK(w * length * std::cos(inclination) - down.hook_load() ==
          Approx(mu * w * std::sin(inclination) * ratio * axial_sum).epsilon(1e-11));
    CHECK(down.surface_torque() ==
          Approx(mu * w * std::sin(inclination) * r * std::sqrt(1.0 - ratio * ratio) * circumferential_sum)
              .epsilon(1e-12));

    FrictionMultipliers bad;
    bad.axial.assign(199, 1.0);
    CHECK(rejected_parameter([&] { (void)string.run(Operation::trip_in, p, bad); }) == "friction_multipliers.axial");
    bad.axial.clear();
    bad.circumferential.assign(200, 1.0);
    bad.circumferential[3] = -0.5;
    CHECK(rejected_parameter([&] { (void)string.run(Operation::trip_in, p, bad); }) ==
          "friction_multipliers.circumferential[3]");
    bad.circumferential[3] = std::nan("");
    CHECK(rejected_parameter([&] { (void)string.run(Operation::trip_in, p, bad); }) ==
          "friction_multipliers.circumferential[3]");
}

TEST_CASE("soft string: the operations' kinematics", "[soft_string]") {
    SoftStringParams p;
    p.weight_on_bit = 70e3;
    p.bit_torque = 4e3;
    const OperationKinematics sliding = operation_kinematics(Operation::sliding_drilling, p);
    CHECK(sliding.direction == -1.0);
    CHECK(sliding.axial_speed == p.rate_of_penetration);
    CHECK(sliding.rotary_speed == 0.0);
    CHECK(sliding.bit_force == -70e3);
    CHECK(sliding.bit_torque == 0.0);
    const OperationKinematics back = operation_kinematics(Operation::backreaming, p);
    CHECK(back.direction == 1.0);
    CHECK(back.axial_speed == p.trip_speed);
    CHECK(back.rotary_speed == p.rotary_speed);
    CHECK(back.bit_force == 0.0);
    const OperationKinematics rotating = operation_kinematics(Operation::rotating_off_bottom, p);
    CHECK(rotating.direction == 0.0);
    CHECK(rotating.axial_speed == 0.0);
    CHECK(operation_kinematics(Operation::rotary_drilling, p).bit_torque == 4e3);
}

// ---- Aadnoy's curvature form (TorqueDragMethod::aadnoy): closed form per element

TEST_CASE("soft string, Aadnoy: a weighted build with tension-dominated contact equals the continuous closed form at "
          "any element length", "[soft_string][aadnoy]") {
    // the build of the Johancsik test above (600 m to 60 degrees, 2400 m of tangent below): where Johancsik's step is
    // first order (5 % off at 120 m elements), Aadnoy's closed form is exact at every node of the build, whatever the
    // element length, from one 600 m element on the build to 1.25 m ones
    const double mu = 0.3, build = 600.0, tangent = 2400.0, theta1 = 60.0 * deg, radius = build / theta1;
    const Survey survey = Survey::from_degrees({{0.0, 0.0, 0.0}, {build, 60.0, 0.0}, {build + tangent, 60.0, 0.0}});
    const PipeSection dp = pipe(build + tangent);
    const SoftStringParams p = open_hole(mu);
    const double w = buoyed(dp, p.mud_density);
    for (double sigma : {mu, -mu}) {
        const double bottom = w * tangent * (std::cos(theta1) + sigma * std::sin(theta1));
        for (std::size_t n : {5u, 10u, 35u, 300u, 2400u}) {  // a node at the end of the build each time
            const SoftString string(survey, DrillString({dp}), n, TorqueDragMethod::aadnoy);
            REQUIRE(string.method() == TorqueDragMethod::aadnoy);
            const TorqueDragResult r = string.run(sigma > 0 ? Operation::trip_out : Operation::trip_in, p);
            INFO((sigma > 0 ? "trip out" : "trip in") << ", N = " << n);
            CHECK(r.tension[n / 5] == Approx(bottom).epsilon(1e-13));
            for (std::size_t i = 0; i <= n / 5; ++i)
                CHECK(r.tension[i] == Approx(build_tension(r.measured_depth[i] / radius, theta1, bottom, radius, w,
                                                           sigma)).epsilon(1e-13));
            // the side force integrates to the friction's share of the change of tension
            double side = 0.0;
            for (std::size_t e = 0; e < n / 5; ++e) side += r.side_force[e];
            CHECK(sigma * side == Approx(r.hook_load() - bottom - w * radius * std::sin(theta1)).epsilon(1e-11));
        }
    }
    // rotating off bottom: no axial friction, the tension is the weight's, F = F_b + R w (sin theta1 - sin theta), and
    // the torque mu r times the side force mu r (integral of F - R w sin theta over theta) + mu r w L_t sin theta1
    const double r = 0.127 / 2, below = w * tangent * std::cos(theta1);
    const double torque = mu * r * ((below + radius * w * std::sin(theta1)) * theta1 -
                                    2.0 * radius * w * (1.0 - std::cos(theta1)) + w * tangent * std::sin(theta1));
    for (std::size_t n : {5u, 15u, 600u}) {
        const SoftString string(survey, DrillString({dp}), n, TorqueDragMethod::aadnoy);
        const TorqueDragResult rotating = string.run(Operation::rotating_off_bottom, p);
        CHECK(rotating.surface_torque() == Approx(torque).epsilon(1e-13));
        CHECK(rotating.hook_load() == Approx(below + radius * w * std::sin(theta1)).epsilon(1e-13));
    }
}

TEST_CASE("soft string, Aadnoy: the capstan relation holds exactly around a weightless 3D arc",
          "[soft_string][aadnoy]") {
    // the arcs of the Johancsik capstan tests: F_in exp(+/- mu theta) to rounding, with one element on the arc or many,
    // and through the vertical (azimuth jumping by 180 degrees) the dogleg, not the azimuth change
    const double mu = 0.25, mud = 1200.0, arc = 600.0, straight = 1200.0;
    const Survey survey = Survey::from_degrees({{0.0, 90.0, 45.0}, {arc, 30.0, 200.0}, {arc + straight, 30.0, 200.0}});
    const double i1 = 90.0 * deg, a1 = 45.0 * deg, i2 = 30.0 * deg, a2 = 200.0 * deg;
    const double theta = std::acos(std::cos(i2 - i1) - std::sin(i1) * std::sin(i2) * (1.0 - std::cos(a2 - a1)));
    const PipeSection weightless = pipe(arc, mud), heavy = pipe(straight);
    SoftStringParams p = open_hole(mu);
    p.mud_density = mud;
    const double w = buoyed(heavy, mud);
    const double pulled = w * straight * (std::cos(i2) + mu * std::sin(i2));
    const double pushed = w * straight * (std::cos(i2) - mu * std::sin(i2));
    for (std::size_t n : {3u, 9u, 90u, 720u}) {
        const SoftString string(survey, DrillString({weightless, heavy}), n, TorqueDragMethod::aadnoy);
        INFO("N = " << n);
        CHECK(string.run(Operation::trip_out, p).hook_load() == Approx(pulled * std::exp(mu * theta)).epsilon(1e-13));
        CHECK(string.run(Operation::trip_in, p).hook_load() == Approx(pushed * std::exp(-mu * theta)).epsilon(1e-13));
        // rotating: the tension stays F_in on the arc, the torque is mu r F_in theta (Aadnoy et al. 2010: rotation
        // in a bend)
        const double hanging = w * straight * std::cos(i2);
        const TorqueDragResult rotating = string.run(Operation::rotating_off_bottom, p);
        CHECK(rotating.surface_torque() ==
              Approx(mu * 0.0635 * (hanging * theta + w * straight * std::sin(i2))).epsilon(1e-13));
    }
    const Survey through = Survey::from_degrees({{0.0, 20.0, 0.0}, {400.0, 20.0, 180.0}, {1200.0, 20.0, 180.0}});
    const SoftString vertical(through, DrillString({pipe(400.0, mud), pipe(800.0)}), 3, TorqueDragMethod::aadnoy);
    const double hung = w * 800.0 * (std::cos(20.0 * deg) + mu * std::sin(20.0 * deg));
    CHECK(vertical.run(Operation::trip_out, p).hook_load() == Approx(hung * std::exp(mu * 40.0 * deg)).epsilon(1e-13));
}

TEST_CASE("soft string, Aadnoy: straight pipe, the friction vector, multipliers and buckling as Johancsik's",
          "[soft_string][aadnoy]") {
    // on a straight pipe both methods are exact: w L (cos I +/- mu sin I) with the friction vector's shares
    const double inclination = 70.0 * deg, length = 2000.0, mu = 0.3;
    const Survey survey({{0.0, inclination, 0.0}, {length, inclination, 0.0}});
    const PipeSection dp = pipe(length);
    const SoftString johancsik(survey, DrillString({dp}), 200);
    const SoftString aadnoy(survey, DrillString({dp}), 200, TorqueDragMethod::aadnoy);
    SoftStringParams p = open_hole(mu);
    p.weight_on_bit = 60e3;
    p.bit_torque = 5e3;
    const double w = buoyed(dp, p.mud_density);
    CHECK(aadnoy.run(Operation::trip_out, p).hook_load() ==
          Approx(w * length * (std::cos(inclination) + mu * std::sin(inclination))).epsilon(1e-13));
    FrictionMultipliers m;
    m.axial.assign(200, 1.0);
    m.circumferential.assign(200, 1.0);
    for (std::size_t e = 0; e < 200; ++e) {
        m.axial[e] = e >= 80 && e < 140 ? 0.1 + 0.01 * static_cast<double>(e - 80) : 1.0;
        m.circumferential[e] = e < 50 ? 0.5 : 1.0;
    }
    for (Operation op : {Operation::trip_in, Operation::reaming, Operation::backreaming, Operation::rotating_off_bottom,
                         Operation::sliding_drilling, Operation::rotary_drilling}) {
        INFO(operation_name(op));
        const TorqueDragResult a = aadnoy.run(op, p, m), j = johancsik.run(op, p, m);
        for (std::size_t i = 0; i <= 200; i += 20) {
            CHECK(a.tension[i] == Approx(j.tension[i]).epsilon(1e-12).margin(1e-9));
            CHECK(a.torque[i] == Approx(j.torque[i]).epsilon(1e-12).margin(1e-9));
        }
        for (std::size_t e = 0; e < 200; e += 20)
            CHECK(a.side_force_per_length[e] == Approx(w * std::sin(inclination)));
        CHECK(a.sinusoidal_buckling_load == j.sinusoidal_buckling_load);  // the loads do not depend on the tension
        for (std::size_t i = 0; i <= 200; ++i) {
            CHECK(static_cast<bool>(a.sinusoidally_buckled[i]) == (-a.tension[i] > a.sinusoidal_buckling_load[i]));
            CHECK(static_cast<bool>(a.helically_buckled[i]) == (-a.tension[i] > a.helical_buckling_load[i]));
        }
    }
    // sliding 60 kN at the end of a 2000 m, 70 degree hole pushes the compression past the sinusoidal load: flagged
    const TorqueDragResult sliding = aadnoy.run(Operation::sliding_drilling, p);
    CHECK(sliding.sinusoidally_buckled.back() == (60e3 > sliding.sinusoidal_buckling_load.back()));

    // the default is Johancsik's
    const SoftString plain(survey, DrillString({dp}), 200);
    CHECK(plain.method() == TorqueDragMethod::johancsik);
    CHECK(std::string(torque_drag_method_name(TorqueDragMethod::aadnoy)) == "aadnoy");
    CHECK(rejected_parameter([&] {
              (void)SoftString(survey, DrillString({dp}), 10, static_cast<TorqueDragMethod>(7));
          }) == "method");
}

TEST_CASE("soft string, Aadnoy: where the contact moves to the low side the pieces follow the continuous equation "
          "with the absolute value", "[soft_string][aadnoy]") {
    // the vertical-to-horizontal build with the bit at its end: Aadnoy's element is split where F / R = w sin theta
    // (located on its closed form) and continued on the other side, so the hook load is the continuous equation's
    // (RK4 with 400,000 steps, itself good to 1e-12 across the kink) with one 942 m element as with 2400
    const double mu = 0.3, theta1 = 90.0 * deg, radius = 30.0 / (3.0 * deg), build = radius * theta1;
    const Survey survey({{0.0, 0.0, 2.0}, {build, theta1, 2.0}});
    const PipeSection dp = pipe(build);
    const SoftStringParams p = open_hole(mu);
    const double w = buoyed(dp, p.mud_density);
    for (double sigma : {mu, -mu}) {
        const double reference = build_tension_rk4(theta1, 0.0, radius, w, sigma, 400000);
        for (std::size_t n : {1u, 2u, 7u, 300u, 2400u}) {
            const SoftString string(survey, DrillString({dp}), n, TorqueDragMethod::aadnoy);
            const TorqueDragResult r = string.run(sigma > 0 ? Operation::trip_out : Operation::trip_in, p);
            INFO((sigma > 0 ? "trip out" : "trip in") << ", N = " << n);
            CHECK(r.hook_load() == Approx(reference).epsilon(1e-10));
            for (double f : r.side_force) CHECK(f >= 0.0);
        }
    }
}

TEST_CASE("soft string: on a 3D well both methods converge to the continuous equation, Johancsik at first order and "
          "Aadnoy at second", "[soft_string][aadnoy]") {
    // the 6 km build-and-turn, drop-and-turn well; the reference integrates the continuous 3D equation by RK4 along the
    // minimum-curvature arcs (10,000 steps a course; halving them changes it by < 1e-12). Where the weight has a share
    // across a dogleg's plane Aadnoy's element takes that share's side force at its middle: second order, measured
    // 8e-7 (trip out) at 100 m elements against Johancsik's 8e-3. Stations fall on nodes (N divides 6000 by 100 m).
    const Survey survey = field_well();
    const PipeSection dp = pipe(6000.0);
    const double mu = 0.3, r = 0.127 / 2;
    SoftStringParams p = open_hole(mu);
    p.weight_on_bit = 60e3;
    const double w = buoyed(dp, p.mud_density);
    const double v = p.trip_speed, surface = p.rotary_speed * r, speed = std::hypot(v, surface);
    struct Case {
        Operation op;
        double sigma, torque_per_force, bit_force;
        bool torque;
    };
    for (const Case c : {Case{Operation::trip_out, mu, 0.0, 0.0, false}, Case{Operation::trip_in, -mu, 0.0, 0.0, false},
                         Case{Operation::sliding_drilling, -mu, 0.0, -60e3, false},
                         Case{Operation::rotating_off_bottom, 0.0, mu * r, 0.0, true},
                         Case{Operation::reaming, -mu * v / speed, mu * r * surface / speed, 0.0, true}}) {
        const Continuous reference = continuous_soft_string(survey, 6000.0, w, c.sigma, c.torque_per_force, c.bit_force,
                                                            10000);
        const double exact = c.torque ? reference.surface_torque : reference.hook_load;
        double previous_j = 0.0, previous_a = 0.0;
        for (std::size_t n : {60u, 120u, 240u, 480u}) {
            const TorqueDragResult j = SoftString(survey, DrillString({dp}), n).run(c.op, p);
            const TorqueDragResult a = SoftString(survey, DrillString({dp}), n, TorqueDragMethod::aadnoy).run(c.op, p);
            const double error_j = std::abs((c.torque ? j.surface_torque() : j.hook_load()) / exact - 1.0);
            const double error_a = std::abs((c.torque ? a.surface_torque() : a.hook_load()) / exact - 1.0);
            INFO(operation_name(c.op) << ", N = " << n << ": relative error Johancsik " << error_j << ", Aadnoy "
                                      << error_a);
            CHECK(error_a < 2e-6 * std::pow(60.0 / static_cast<double>(n), 2));
            CHECK(error_a < 1e-3 * error_j);
            if (previous_j > 0.0) {
                CHECK(previous_j / error_j == Approx(2.0).epsilon(0.03));  // first order
                CHECK(previous_a / error_a == Approx(4.0).epsilon(0.03));  // second order
            }
            previous_j = error_j;
            previous_a = error_a;
        }
    }
}

TEST_CASE("soft string: a friction factor that locks the string up is named, never a NaN", "[soft_string][aadnoy]") {
    // running in through 70 degrees of bends at mu = 3104: the compression would grow as e^(mu theta), past any double
    const Survey survey = Survey::from_degrees({{0.0, 0.0, 0.0}, {400.0, 0.0, 0.0}, {1200.0, 60.0, 40.0},
                                                {2500.0, 70.0, 50.0}});
    SoftStringParams p = open_hole(3104.0);  // what hypothesis found (tests/python/test_wells.py)
    p.cased_hole_friction = 1.0;
    p.mud_density = 177.8;
    p.hole_diameter = p.casing_inner_diameter = 1.0;
    PipeSection collar = pipe(200.0);
    collar.outer_diameter = 0.1651;
    collar.inner_diameter = 0.0714;
    for (TorqueDragMethod m : {TorqueDragMethod::johancsik, TorqueDragMethod::aadnoy}) {
        INFO(torque_drag_method_name(m));
        const SoftString string(survey, DrillString({pipe(2300.0), collar}), 125, m);
        CHECK(rejected_parameter([&] { (void)string.run(Operation::trip_in, p); }) == "open_hole_friction");
        CHECK(contains(rejection_message([&] { (void)string.run(Operation::trip_in, p); }), "locks up"));
        CHECK_NOTHROW(string.run(Operation::trip_in, open_hole(0.4)));
    }
}

TEST_CASE("soft string: a bit load beyond any rig is named, not read as a friction lock-up",
          "[soft_string][validation]") {
    // issue 23: weight_on_bit = 1e300 overflowed the tension's square in the side force, and the run blamed
    // open_hole_friction (a lock-up). The table bounds both bit loads at 1e9 (N, N m).
    const Survey survey({{0.0, 0.0, 0.0}, {1000.0, 0.5, 0.0}});
    const SoftString string(survey, DrillString({pipe(900.0)}), 90);
    for (const double load : {1e300, 1.0000001e9, std::numeric_limits<double>::infinity()}) {
        SoftStringParams p;
        p.weight_on_bit = load;
        CHECK(rejected_parameter([&] { (void)string.run(Operation::sliding_drilling, p); }) == "weight_on_bit");
        p.weight_on_bit = 0.0;
        p.bit_torque = load;
        CHECK(rejected_parameter([&] { (void)string.run(Operation::rotary_drilling, p); }) == "bit_torque");
    }
    SoftStringParams most;
    most.weight_on_bit = most.bit_torque = 1e9;  // the limit itself runs: finite, the bit's load at the bit
    const TorqueDragResult r = string.run(Operation::rotary_drilling, most);
    CHECK(r.tension.back() == -1e9);
    CHECK(r.torque.back() == 1e9);
    CHECK(std::isfinite(r.hook_load()));
}
