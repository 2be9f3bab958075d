// LuGre against Canudas de Wit et al. (1995): the stick-slip example of their paper and the steady-state
// sliding force g(v) + sigma2 v.
#include <algorithm>
#include <cmath>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"

using namespace frictionsim;

TEST_CASE("LuGre steady sliding force equals g(v) + sigma2 v", "[lugre][kinematic_rig]") {
    const LuGre law(canudas_de_wit_1995_lugre());  // Canudas de Wit 1995 values: Fc = 1 N, Fs = 1.5 N at N = 1 N
    for (double v : {-0.1, -1e-3, 2e-4, 1e-3, 5e-3, 0.1}) {
        KinematicRig rig(law, ConstantSignal(v), ConstantSignal(1.0));
        SolverOptions o;
        o.method = Method::cvode_bdf;
        o.rtol = 1e-10;
        o.atol = 1e-14;
        o.output_times = {3.0};
        const Result r = simulate(rig, 3.0, o);  // bristle time constant g/(sigma0 |v|) <= 75 ms
        const double g = 1.0 + 0.5 * std::exp(-(v / 1e-3) * (v / 1e-3));
        const double expected = (v > 0 ? g : -g) + 0.4 * v;
        INFO("v = " << v);
        CHECK(r.friction_force.back() == Approx(expected).epsilon(1e-8));
    }
}

TEST_CASE("LuGre stick-slip example of Canudas de Wit et al. 1995", "[lugre][axial_rig][stick_slip]") {
    // m = 1 kg pulled through k = 2 N/m at 0.1 m/s; sigma0 = 1e5 N/m, sigma1 = sqrt(1e5) N s/m,
    // sigma2 = 0.4 N s/m, Fc = 1 N, Fs = 1.5 N, vs = 1 mm/s (their Fig. 6).
    const AxialRigParams p = canudas_de_wit_1995_params();
    AxialRig<LuGre> rig(p, LuGre(canudas_de_wit_1995_lugre()));
    SolverOptions o;
    o.method = GENERATE(Method::cvode_bdf, Method::dormand_prince);
    o.rtol = 1e-8;
    o.atol = 1e-12;
    for (int i = 0; i <= 30000; ++i) o.output_times.push_back(i * 1e-3);
    const Result r = simulate(rig, 30.0, o);
    INFO(method_name(o.method));

    // Stick: the block creeps (|v| < 1 mm/s) while the spring loads; slip: it overshoots the pulling speed.
    const std::vector<double> v = r.column_values("velocity");
    std::vector<double> slip_starts;
    double longest_stick = 0.0, stick_from = 0.0, peak = 0.0;
    bool sticking = true;
    for (std::size_t i = 0; i < v.size(); ++i) {
        peak = std::max(peak, v[i]);
        if (sticking && v[i] > 1e-2) {
            sticking = false;
            slip_starts.push_back(r.t[i]);
            longest_stick = std::max(longest_stick, r.t[i] - stick_from);
        } else if (!sticking && std::abs(v[i]) < 1e-3) {
            sticking = true;
            stick_from = r.t[i];
        }
        CHECK(v[i] > -1e-3);  // never slides backwards
    }
    // Coulomb estimate of the cycle with Fs, Fc: first breakaway at Fs/(k v) = 7.5 s, then stick
    // 2 (Fs - Fc)/(k v) = 2.5 s and slip ~ 2.6 s, peak ~ 0.47 m/s: stick-slip within the paper's 20 s
    REQUIRE(slip_starts.size() >= 3);
    CHECK(slip_starts[1] < 20.0);
    CHECK(longest_stick > 1.5);
    CHECK(peak > 0.3);
    CHECK(peak < 0.6);
    // a limit cycle: equal periods once established
    const double period1 = slip_starts[2] - slip_starts[1];
    if (slip_starts.size() >= 4) CHECK(slip_starts[3] - slip_starts[2] == Approx(period1).epsilon(1e-3));
    CHECK(period1 > 4.0);
    CHECK(period1 < 7.0);
}

TEST_CASE("LuGre with stiff bristles approaches Stribeck friction with exact stick", "[lugre][stribeck][axial_rig]") {
    const AxialRigParams p = canudas_de_wit_1995_params();
    Stribeck::Params sp;
    sp.coulomb_coefficient = 1.0;
    sp.static_coefficient = 1.5;
    sp.stribeck_velocity = 1e-3;
    sp.viscous_coefficient = 0.4;
    AxialRig<Stribeck> exact(p, Stribeck(sp));
    LuGre::Params lp = canudas_de_wit_1995_lugre();
    lp.bristle_stiffness = 1e7;
    lp.bristle_damping = 2 * std::sqrt(1e7);  // critically damped bristles
    AxialRig<LuGre> bristles(p, LuGre(lp));
    SolverOptions o;
    o.method = Method::cvode_bdf;
    o.rtol = 1e-9;
    o.atol = 1e-12;
    o.output_times = {0.0};
    const Result rs = simulate(exact, 30.0, o);
    std::vector<double> breakaways;
    for (const Event& e : rs.events)
        if (e.mode_after == slip_positive) breakaways.push_back(e.time);
    REQUIRE(breakaways.size() >= 3);
    CHECK(breakaways[0] == Approx(1.5 / (2.0 * 0.1)).epsilon(1e-9));  // spring force reaches Fs from rest

    for (int i = 1; i <= 3000; ++i) o.output_times.push_back(i * 1e-2);
    const Result rl = simulate(bristles, 30.0, o);
    const std::vector<double> v = rl.column_values("velocity");
    std::vector<double> lugre_breakaways;
    for (std::size_t i = 1; i < v.size(); ++i)
        if (v[i - 1] < 1e-2 && v[i] >= 1e-2) lugre_breakaways.push_back(rl.t[i]);
    REQUIRE(lugre_breakaways.size() >= 3);
    // the slip period of the two models agrees to a few per cent (bristle creep before breakaway differs)
    CHECK(lugre_breakaways[2] - lugre_breakaways[1] == Approx(breakaways[2] - breakaways[1]).epsilon(0.03));
}
