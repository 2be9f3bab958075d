// Stribeck friction (and the Karnopp band of contact/switching.hpp, set-ups of reference_setups.hpp): the curve itself, exact stick on a rig, and the Karnopp band converging to exact stick.
#include <cmath>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"

using namespace frictionsim;

namespace {
AxialRigParams spring_block() { return spring_block_params(0.5, 200.0, 0.05); }
}  // namespace

TEST_CASE("Stribeck curve: static level at v -> 0, Coulomb level plus viscous at high speed", "[stribeck]") {
    Stribeck::Params sp;
    sp.coulomb_coefficient = 0.3;
    sp.static_coefficient = 0.5;
    sp.stribeck_velocity = 0.01;
    sp.shape_exponent = 1.0;
    sp.viscous_coefficient = 2.0;
    const Stribeck law(sp);
    const double n = 100.0;
    CHECK(law.slip_force(0.0, n, +1) == Approx(50.0));
    CHECK(law.slip_force(0.0, n, -1) == Approx(-50.0));
    CHECK(law.slip_force(0.01, n, +1) == Approx((0.3 + 0.2 * std::exp(-1.0)) * n + 0.02));
    CHECK(law.slip_force(-0.01, n, -1) == Approx(-(0.3 + 0.2 * std::exp(-1.0)) * n - 0.02));
    CHECK(law.slip_force(10.0, n, +1) == Approx(30.0 + 20.0));
    CHECK(law.static_limit(n) == Approx(50.0));
}

TEST_CASE("Stribeck with exact stick: the spring-block breaks away at the static limit", "[stribeck][axial_rig]") {
    Stribeck::Params sp;
    sp.coulomb_coefficient = 0.4;
    sp.static_coefficient = 0.6;
    sp.stribeck_velocity = 0.01;
    const AxialRigParams p = spring_block();
    AxialRig<Stribeck> rig(p, Stribeck(sp));
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = {0.0};
    const Result r = simulate(rig, 10.0, o);
    REQUIRE(r.events.size() >= 4);
    const double x_s = 0.6 * p.normal_force / p.drive_stiffness;
    CHECK(r.events[0].time == Approx(x_s / p.sliding_velocity).epsilon(1e-9));
    CHECK(r.events[0].name == "static_limit_positive");
    CHECK(r.events[1].name == "relative_velocity");
    CHECK(r.events[1].mode_after == stick);
    // every stick phase ends at the same spring force: the static limit
    for (std::size_t i = 2; i + 1 < r.events.size(); i += 2)
        CHECK(r.events[i + 1].time - r.events[i].time == Approx(r.events[3].time - r.events[2].time).epsilon(1e-6));
}

TEST_CASE("a Karnopp band converges to exact stick as the band narrows", "[stribeck][karnopp][axial_rig]") {
    Stribeck::Params sp;
    sp.coulomb_coefficient = 0.4;
    sp.static_coefficient = 0.6;
    sp.stribeck_velocity = 0.01;
    const AxialRigParams p = spring_block();
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = {0.0};
    const Result exact = simulate(AxialRig<Stribeck>(p, Stribeck(sp)), 10.0, o);
    REQUIRE(exact.events.size() >= 4);
    const double exact_period = exact.events[3].time - exact.events[1].time;

    double last_error = 1.0;
    for (double band : {1e-3, 1e-4, 1e-5}) {
        sp.karnopp_band = band;
        const Result r = simulate(AxialRig<Stribeck>(p, Stribeck(sp)), 10.0, o);
        std::vector<double> entries;
        for (const Event& e : r.events)
            if (e.mode_after == stick) {
                CHECK(e.name == "karnopp_band_entry");
                CHECK(e.mode_after_name == "karnopp_band");
                entries.push_back(e.time);
            }
        REQUIRE(entries.size() >= 3);
        const double error = std::abs((entries[2] - entries[1]) - exact_period) / exact_period;
        INFO("band " << band << ": period error " << error);
        CHECK(error < std::max(1e-6, 0.5 * last_error));
        last_error = error;
    }
    CHECK(last_error < 1e-3);
}
