// Coulomb friction, and the stick/slip switching of contact/switching.hpp, against analytic references: the friction-vector mean force of a body sliding on a
// vibrating surface, and the stick-slip cycle of a spring-pulled block with static > kinetic friction.
#include <cmath>
#include <vector>

#include <frictionsim/simulate.hpp>
// The paths these headers had before issue 12 still build: they forward to contact/ and solve/ (each with a
// #pragma message naming the new path).
#include <frictionsim/contact/switching.hpp>
#include <frictionsim/contact/disc_contact.hpp>
#include <frictionsim/solve/simulate_with.hpp>

#include "catch.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::relative_error;

namespace {

std::vector<double> multiples(double step, int count) {
    std::vector<double> t;
    for (int k = 0; k <= count; ++k) t.push_back(k * step);
    return t;
}

}  // namespace

TEST_CASE("kinematic Coulomb: mean friction under v_r = v_d - v_a cos(wt) is (2/pi) asin(v_d/v_a) mu N",
          "[coulomb][kinematic_rig]") {
    const double mu = 0.41, normal = 90.0, omega = 2 * pi * 17.0, v_a = 5e-3 * omega;
    const double period = 2 * pi / omega;
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    for (double ratio : {0.02, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.2, 3.0}) {
        KinematicRig rig(Coulomb(mu), HarmonicSlidingVelocity(ratio * v_a, v_a, omega), ConstantSignal(normal));
        SolverOptions o;
        o.method = method;
        o.rtol = 1e-10;
        o.atol = 1e-12;
        o.output_times = multiples(period, 5);
        const Result r = simulate(rig, 5 * period, o);
        const std::size_t impulse = r.column("friction_impulse");
        const double mean = (r.state(5, impulse) - r.state(0, impulse)) / (5 * period);
        const double expected = ratio < 1 ? 2 / pi * std::asin(ratio) * mu * normal : mu * normal;
        INFO("v_d/v_a = " << ratio << ", method " << method_name(method));
        CHECK(relative_error(mean, expected) < 1e-6);
        CHECK(r.events.size() == (ratio < 1 ? 10u : 0u));  // two reversals per cycle
    }
}

TEST_CASE("spring-block stick-slip with static > kinetic Coulomb friction matches the analytic cycle",
          "[coulomb][axial_rig][stick_slip]") {
    // Block on a horizontal plane (no vibration), spring end pulled at v. Analytic steady cycle:
    // stick 2 (x_s - x_d) / v, slip (2 / lambda) (pi - atan(lambda (x_s - x_d) / v)).
    const double m = 0.5, k = 200.0, v = 0.05, g = 9.81, mu_s = 0.6, mu_k = 0.4;
    AxialRig<Coulomb> rig(spring_block_params(m, k, v, g), Coulomb(mu_k, mu_s));

    const double lambda = std::sqrt(k / m), x_s = mu_s * m * g / k, x_d = mu_k * m * g / k;
    const double stick_time = 2 * (x_s - x_d) / v;
    const double slip_time = 2 / lambda * (pi - std::atan(lambda * (x_s - x_d) / v));

    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams);
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = {0.0};
    const Result r = simulate(rig, 6 * (stick_time + slip_time), o);
    INFO("method " << method_name(method));

    // events alternate stick -> slip (static limit) and slip -> stick (v_r = 0)
    std::vector<double> stick_starts, slip_starts;
    for (const Event& e : r.events) (e.mode_after == stick ? stick_starts : slip_starts).push_back(e.time);
    REQUIRE(slip_starts.size() >= 4);
    REQUIRE(stick_starts.size() >= 4);
    CHECK(relative_error(slip_starts[0], x_s / v) < 1e-9);  // first breakaway: spring stretched to x_s from rest
    for (std::size_t i = 1; i + 1 < slip_starts.size(); ++i) {
        CHECK(relative_error(stick_starts[i] - slip_starts[i], slip_time) < 1e-6);
        CHECK(relative_error(slip_starts[i + 1] - stick_starts[i], stick_time) < 1e-6);
    }
    for (const Event& e : r.events) {
        if (e.mode_after == stick) CHECK(e.name == "relative_velocity");
        if (e.mode_after == slip_positive) CHECK(e.name == "static_limit_positive");
        CHECK(e.mode_after != slip_negative);  // the block never slides backwards
    }
}

TEST_CASE("Coulomb on the vibrating axial rig: stick force stays within the static limit while stuck",
          "[coulomb][axial_rig]") {
    AxialRigParams p;  // paper 000 Fig. 7(a) defaults
    p.amplitude = 1e-5;  // v_a = 1.07 mm/s ~ v_d: the specimen sticks to the surface part of each cycle
    AxialRig<Coulomb> rig(p, Coulomb(0.41, 0.5));
    SolverOptions o;
    o.rtol = 1e-9;
    o.atol = 1e-12;
    o.record_steps = true;
    const Result r = simulate(rig, 0.5, o);
    bool saw_stick = false;
    for (std::size_t i = 0; i < r.rows(); ++i) {
        if (r.mode[i] != stick) continue;
        saw_stick = true;
        CHECK(std::abs(r.friction_force[i]) <= 0.5 * p.normal_force * (1 + 1e-12));
        CHECK(r.state(i, 1) - rig.surface_velocity(r.t[i]) == Approx(0.0).margin(1e-9));
    }
    CHECK(saw_stick);
}
