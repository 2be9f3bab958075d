// Elasto-plastic friction (Dupont et al. 2002) against what defines it: purely elastic presliding below the
// break-away deflection (the deflection follows the imposed displacement exactly: no drift), LuGre's steady
// sliding level above it, and its alpha(z, v) at the ends of the transition.
#include <cmath>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::tight;

namespace {
/// Canudas de Wit 1995's LuGre values (Fc = 1 N, Fs = 1.5 N at N = 1 N, sigma0 = 1e5 N/m): z_max >= 1e-5 m.
ElastoPlastic::Params reference_params(double breakaway_fraction = 0.5) {
    ElastoPlastic::Params p;
    static_cast<LuGre::Params&>(p) = canudas_de_wit_1995_lugre();
    p.breakaway_fraction = breakaway_fraction;
    return p;
}

}  // namespace

TEST_CASE("elasto-plastic alpha(z): 0 below break-away and when unloading, 1/2 mid-way, 1 from z_max = Fc / sigma0",
          "[elasto_plastic]") {
    const ElastoPlastic law(reference_params());
    const double N = 1.0, z_ba = law.breakaway_deflection(N), z_max = law.plastic_deflection(N);
    CHECK(z_max == Approx(1e-5).epsilon(1e-15));  // Fc / sigma0 = 1 N / 1e5 N/m
    CHECK(z_ba == Approx(0.5e-5).epsilon(1e-15));
    CHECK(law.plasticity_factor(N, 0.99 * z_ba, +1) == 0.0);
    CHECK(law.plasticity_factor(N, 0.5 * (z_ba + z_max), +1) == Approx(0.5).epsilon(1e-12));
    CHECK(law.plasticity_factor(N, z_max, +1) == 1.0);
    CHECK(law.plasticity_factor(N, 3.0 * z_max, +1) == 1.0);
    CHECK(law.plasticity_factor(N, -3.0 * z_max, -1) == 1.0);
    CHECK(law.plasticity_factor(N, 3.0 * z_max, -1) == 0.0);  // moving back: elastic whatever the deflection
    // continuous at both ends of the ramp
    CHECK(law.plasticity_factor(N, z_ba * (1 + 1e-9), +1) == Approx(0.0).margin(1e-12));
    CHECK(law.plasticity_factor(N, z_max * (1 - 1e-9), +1) == Approx(1.0).epsilon(1e-12));
    // z_max scales with the normal force
    CHECK(law.plastic_deflection(3.0) == Approx(3e-5).epsilon(1e-15));
}

TEST_CASE("elasto-plastic presliding is elastic: z follows the imposed displacement exactly, LuGre's does not",
          "[elasto_plastic][kinematic_rig]") {
    // v_r = -v_a cos(w t): displacement -(v_a / w) sin(w t), amplitude 0.8 z_ba, so |z| < z_ba throughout
    const double omega = 2 * pi * 10.0, z_ba = 0.5e-5, v_a = 0.8 * z_ba * omega;
    const HarmonicSlidingVelocity v(0.0, v_a, omega);
    const auto method = GENERATE(Method::cvode_bdf, Method::dormand_prince);
    INFO(method_name(method));
    std::vector<double> times;
    for (int i = 1; i <= 40; ++i) times.push_back(0.0125 * i);  // quarter periods over 5 cycles
    const SolverOptions o = tight(method, times);
    const Result ep = simulate(KinematicRig<ElastoPlastic, HarmonicSlidingVelocity>(ElastoPlastic(reference_params()),
                                                                                   v, ConstantSignal(1.0)),
                               0.5, o);
    LuGre::Params lp = canudas_de_wit_1995_lugre();  // the same bristles without the elastic regime
    const Result lugre =
        simulate(KinematicRig<LuGre, HarmonicSlidingVelocity>(LuGre(lp), v, ConstantSignal(1.0)), 0.5, o);
    const std::size_t z = ep.column("bristle_deflection");
    double lugre_gap = 0.0;
    for (std::size_t i = 0; i < ep.rows(); ++i) {
        const double displacement = -(v_a / omega) * std::sin(omega * ep.t[i]);
        INFO("t = " << ep.t[i]);
        CHECK(ep.state(i, z) == Approx(displacement).epsilon(0.0).margin(1e-6 * z_ba));
        // F = sigma0 z + (sigma1 + sigma2) v in the elastic regime
        CHECK(ep.friction_force[i] ==
              Approx(1e5 * displacement + (lp.bristle_damping + 0.4) * v(ep.t[i])).epsilon(0.0).margin(1e-6));
        lugre_gap = std::max(lugre_gap, std::abs(lugre.state(i, z) - displacement));
    }
    CHECK(lugre_gap > 0.05 * z_ba);  // LuGre's |v| z / g term slips the bristles even this far below break-away
}

TEST_CASE("elasto-plastic steady sliding force equals g(v) + sigma2 v, as LuGre's", "[elasto_plastic][kinematic_rig]") {
    const ElastoPlastic law(reference_params());
    for (double v : {-0.1, -1e-3, 2e-4, 1e-3, 5e-3, 0.1}) {
        const Result r = simulate(KinematicRig(law, ConstantSignal(v), ConstantSignal(1.0)), 3.0,
                                  tight(Method::cvode_bdf, {3.0}));
        const double g = 1.0 + 0.5 * std::exp(-(v / 1e-3) * (v / 1e-3));
        INFO("v = " << v);
        CHECK(r.friction_force.back() == Approx((v > 0 ? g : -g) + 0.4 * v).epsilon(1e-8));
    }
}

TEST_CASE("elasto-plastic stick-slip on Canudas de Wit's block: the LuGre cycle, without creep in stick",
          "[elasto_plastic][axial_rig][stick_slip]") {
    const AxialRigParams p = canudas_de_wit_1995_params();
    const auto method = GENERATE(Method::cvode_bdf, Method::dormand_prince);
    INFO(method_name(method));
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-8;
    o.atol = 1e-12;
    for (int i = 0; i <= 30000; ++i) o.output_times.push_back(i * 1e-3);
    const Result ep = simulate(AxialRig<ElastoPlastic>(p, ElastoPlastic(reference_params())), 30.0, o);
    const Result lugre = simulate(AxialRig<LuGre>(p, LuGre(canudas_de_wit_1995_lugre())), 30.0, o);
    // slip starts (v > 1 cm/s after v < 1 mm/s) and the creep speed during the first loading, t in (1, 6) s
    const auto slip_starts = [](const Result& r) {
        std::vector<double> starts;
        const std::vector<double> v = r.column_values("velocity");
        bool sticking = true;
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (sticking && v[i] > 1e-2) starts.push_back(r.t[i]);
            if (v[i] > 1e-2) sticking = false;
            if (std::abs(v[i]) < 1e-3) sticking = true;
        }
        return starts;
    };
    const std::vector<double> a = slip_starts(ep), b = slip_starts(lugre);
    REQUIRE(a.size() >= 3);
    REQUIRE(b.size() >= 3);
    // the cycle is set by Fs, Fc and the spring: periods agree to a few per cent
    CHECK((a[2] - a[1]) == Approx(b[2] - b[1]).epsilon(0.05));
    // While the spring loads from rest to sigma0 z_ba = 0.5 N (2.5 s), the contact is elastic: the block moves
    // only by the bristles' deflection, x - z stays at its start (0). LuGre's bristles slip: the block creeps.
    const std::size_t row = 1000;  // t = 1 s, spring force ~0.2 N
    const double creep_ep = ep.state(row, 0) - ep.state(row, ep.column("bristle_deflection"));
    const double creep_lugre = lugre.state(row, 0) - lugre.state(row, lugre.column("bristle_deflection"));
    INFO("x - z at 1 s: elasto-plastic " << creep_ep << " m, LuGre " << creep_lugre << " m");
    CHECK(std::abs(creep_ep) < 1e-12);
    CHECK(creep_lugre > 1e-9);
}

TEST_CASE("elasto-plastic dissipation: none while elastic, never negative (friction work - stored energy)",
          "[elasto_plastic][kinematic_rig][energy]") {
    // sigma1 = sigma2 = 0: F = sigma0 z, so int F v dt - sigma0 z^2 / 2 = int sigma0^2 alpha |v| z^2 / g dt, which
    // is 0 while alpha = 0 and grows with alpha > 0. LuGre (alpha = 1 throughout) dissipates even in presliding.
    ElastoPlastic::Params p = reference_params();
    p.bristle_damping = 0.0;
    p.viscous_damping = 0.0;
    const ElastoPlastic law(p);
    const double omega = 2 * pi * 10.0, z_max = law.plastic_deflection(1.0);
    std::vector<double> times;
    for (int i = 1; i <= 200; ++i) times.push_back(0.0025 * i);
    const SolverOptions o = tight(Method::cvode_bdf, times);
    const auto dissipated = [](const Result& r, std::size_t i) {
        const double z = r.state(i, r.column("bristle_deflection"));
        return r.state(i, r.column("friction_work")) - 0.5 * 1e5 * z * z;
    };
    SECTION("below break-away (amplitude 0.8 z_ba): nothing dissipated, LuGre dissipates") {
        const HarmonicSlidingVelocity v(0.0, 0.4 * z_max * omega, omega);
        const Result r = simulate(KinematicRig<ElastoPlastic, HarmonicSlidingVelocity>(law, v, ConstantSignal(1.0)),
                                  0.5, o);
        LuGre::Params lp;
        lp.bristle_damping = 0.0;
        lp.viscous_damping = 0.0;
        const Result lugre =
            simulate(KinematicRig<LuGre, HarmonicSlidingVelocity>(LuGre(lp), v, ConstantSignal(1.0)), 0.5, o);
        for (std::size_t i = 0; i < r.rows(); ++i) CHECK(std::abs(dissipated(r, i)) < 1e-8 * 1e5 * z_max * z_max);
        CHECK(dissipated(lugre, lugre.rows() - 1) > 1e-3 * 1e5 * z_max * z_max);
    }
    SECTION("through break-away into sliding (amplitude 3 z_max): dissipation never decreases") {
        const HarmonicSlidingVelocity v(0.0, 3.0 * z_max * omega, omega);
        const Result r = simulate(KinematicRig<ElastoPlastic, HarmonicSlidingVelocity>(law, v, ConstantSignal(1.0)),
                                  0.5, o);
        for (std::size_t i = 1; i < r.rows(); ++i)  // flat while unloading: to solver accuracy, 1e-8 of it
            CHECK(dissipated(r, i) >= dissipated(r, i - 1) * (1 - 1e-8) - 1e-8 * 1e5 * z_max * z_max);
        CHECK(dissipated(r, r.rows() - 1) > 0.5 * 1e5 * z_max * z_max);  // several cycles of sliding
    }
}
