// Generalized Maxwell-slip friction (Al-Bender, Lampaert & Swevers 2005) against the behaviour the paper
// publishes: the Stribeck curve in steady sliding, presliding hysteresis with non-local memory (Maxwell-slip
// forces at the reversal points, inner loops that close, wiping-out), frictional lag in unidirectional sliding
// with the time constant s/C; and the engine's own: parameter rules, energy, analytic partials, the reversals as
// events on both integrators.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "rig_checks.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::KnotPath;
using frictionsim::test::tight;
using frictionsim::test::um;
using GMS = GeneralizedMaxwellSlip;

namespace {

// The defaults: mu = 0.3, mu_s = 0.4, v_s = 1 mm/s, delta = 2, C = 4000 N/s, k = 8e4, 4e4, 2e4, 1e4 N/m,
// alpha = 0.1, 0.2, 0.3, 0.4. At F_N = 10 N the shares at rest are 0.4, 0.8, 1.2, 1.6 N and the break-away
// deflections alpha_i F_s / k_i 5, 20, 60 and 160 um; the lag time s/C is ~0.9 ms.
constexpr double normal = 10.0;

GMS::Params gms_params(double block_damping = 0.0, double viscous_damping = 0.0) {
    GMS::Params p;
    p.block_damping = block_damping;
    p.viscous_damping = viscous_damping;
    return p;
}

}  // namespace

TEST_CASE("GMS steady sliding: F = s(v) sgn(v) + sigma_2 v (the Stribeck curve), each block at its share",
          "[gms][kinematic_rig]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    for (double delta : {2.0, 1.0}) {
        GMS::Params p = gms_params(5.0, 2.0);  // sigma_1 must drop out (dz/dt -> 0), sigma_2 v must not
        p.shape_exponent = delta;
        const GMS law(p);
        for (double v : {-3e-3, -1e-3, 2e-4, 1e-3, 5e-3, 0.1}) {
            // the longest presliding range (160 um) three times over, then 40 lag times s/C
            const double t_end = 3 * 160 * um / std::abs(v) + 40 * 0.4 * normal / p.attraction;
            const Result r =
                simulate(KinematicRig(law, ConstantSignal(v), ConstantSignal(normal)), t_end, tight(method, {t_end}));
            const double s = normal * (0.3 + 0.1 * std::exp(-std::pow(std::abs(v) / 1e-3, delta)));
            INFO(method_name(method) << ", delta = " << delta << ", v = " << v);
            CHECK(law.stribeck_level(v, normal) == Approx(s).epsilon(1e-15));
            // measured within 8e-11 relative (Dormand-Prince) and 1.3e-11 (BDF)
            CHECK(r.friction_force.back() == Approx(std::copysign(s, v) + 2.0 * v).epsilon(1e-9));
            for (std::size_t i = 0; i < GMS::block_count; ++i)
                CHECK(law.block_stiffness(i) * r.state(r.rows() - 1, i) ==
                      Approx(std::copysign(law.block_weight(i) * s, v)).epsilon(1e-8));  // measured 1.7e-9
        }
    }
}

TEST_CASE("GMS presliding: virgin slope sum k_i, Maxwell-slip forces at the reversals, inner loops close and are "
          "wiped out",
          "[gms][kinematic_rig]") {
    // A: 0 -> +100 -> -100 -> -20 -> -70 -> -20 -> +100 um, one segment per second (|v| <= 0.31 mm/s); the inner
    // loop -20 -> -70 -> -20 flips blocks 1 and 2 twice, block 3 and 4 stick through it.
    // B: the same without the inner loop. Where A passes -20 um again, its memory of the inner loop must be gone:
    // from there on A is B, one loop (2 s) later.
    const KnotPath a{{0, 100 * um, -100 * um, -20 * um, -70 * um, -20 * um, 100 * um}, 1.0};
    const KnotPath b{{0, 100 * um, -100 * um, -20 * um, 100 * um}, 1.0};
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    const GMS law(gms_params());
    std::vector<double> ta, tb;
    for (int i = 0; i <= 600; ++i) ta.push_back(0.01 * i);
    for (int i = 0; i <= 400; ++i) tb.push_back(0.01 * i);
    const Result ra = simulate(KinematicRig(law, a, ConstantSignal(normal)), 6.0, tight(method, ta));
    const Result rb = simulate(KinematicRig(law, b, ConstantSignal(normal)), 4.0, tight(method, tb));
    REQUIRE(ra.rows() == 601);
    REQUIRE(rb.rows() == 401);
    CHECK(ra.events.size() == 4);  // the four reversals; the pass through -20 um at t = 5 s is no reversal
    CHECK(rb.events.size() == 2);

    // the virgin curve: every block sticks, F = sum k_i x (measured within 5e-8 relative)
    for (std::size_t i : {1, 2, 3})
        CHECK(ra.friction_force[i] / a.displacement(ra.t[i]) == Approx(1.5e5).epsilon(1e-6));

    // At the reversal points v = 0 and s = F_s: the rate-independent Maxwell-slip forces. +100 um: blocks 1-3 slid
    // (0.4 + 0.8 + 1.2 N), block 4 at k_4 x = 1 N. -100 um: all at -share but block 4, at -1 N. -20 um: blocks 1, 2
    // slid back (1.2 N), block 3 at -1.2 + k_3 80 um = 0.4 N, block 4 at -0.2 N. -70 um: blocks 1, 2 at -1.2 N,
    // block 3 at 0.4 - k_3 50 um = -0.6 N, block 4 -0.7 N. (Measured within 1.3e-6 N.)
    const std::array<std::pair<std::size_t, double>, 5> reversals{
        {{100, 3.4}, {200, -3.4}, {300, 1.4}, {400, -2.5}, {500, 1.4}}};
    for (const auto& [row, force] : reversals) {
        INFO("t = " << ra.t[row]);
        CHECK(ra.friction_force[row] == Approx(force).margin(5e-6));
    }
    // the inner loop closes: the blocks return to where they were at its start (measured 6.1e-8 N, 6.3e-8 N)
    CHECK(std::abs(ra.friction_force[500] - ra.friction_force[300]) < 3e-7);
    for (std::size_t i = 0; i < GMS::block_count; ++i)
        CHECK(ra.state(500, i) == Approx(ra.state(300, i)).margin(1e-6 * um));
    // wiping-out: past -20 um the force is B's, the outer curve, as if the inner loop never was (measured
    // 5.8e-8 N, 6.0e-8 N); and the big loop closes at +100 um
    double gap = 0.0;
    for (std::size_t i = 0; i <= 100; ++i)
        gap = std::max(gap, std::abs(ra.friction_force[500 + i] - rb.friction_force[300 + i]));
    INFO("max |F_A - F_B| past the inner loop: " << gap << " N");
    CHECK(gap < 3e-7);
    CHECK(ra.friction_force[600] == Approx(ra.friction_force[100]).margin(1e-6));
    // the inner loop is a loop: the descending and ascending branches between -70 and -20 um differ
    const double x_mid = -45 * um;  // half-way: t = 3.5 s descending, 4.5 s ascending
    CHECK(a.displacement(3.5) == Approx(x_mid).margin(1e-15));
    // ascending above descending by the flipped blocks 1 and 2: 2 x 0.4 N + 2 x 0.2 N = 1.2 N at v = 0
    CHECK(ra.friction_force[450] - ra.friction_force[350] == Approx(1.2).margin(0.01));
}

TEST_CASE("GMS frictional lag: in unidirectional sliding F is higher accelerating than decelerating - the loop "
          "shrinks with the frequency, as 2 (s/C) |s'(v)| dv/dt",
          "[gms][kinematic_rig]") {
    // v = 1 mm/s - 0.8 mm/s cos(w t): through the Stribeck range, never reversing. At t = T/4 (accelerating) and
    // 3T/4 (decelerating) v = 1 mm/s. The blocks' forces relax to their shares at rate C / s, so the sum lags
    // s(v(t)) by s/C: F - s = -(s/C) ds/dt.
    const GMS law(gms_params());
    const double v_d = 1e-3, v_a = 0.8e-3, s = law.stribeck_level(v_d, normal);
    const double slope = -normal * 0.1 * 2 * (v_d / 1e-3) * std::exp(-1.0) / 1e-3;  // s'(v_d), N s/m
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    double last_width = 1.0;
    for (double f : {10.0, 3.0, 1.0, 0.3}) {
        const double omega = 2 * pi * f, T = 1 / f;
        const Result r = simulate(KinematicRig(law, HarmonicSlidingVelocity(v_d, v_a, omega), ConstantSignal(normal)),
                                  5.75 * T, tight(method, {5.25 * T, 5.75 * T}));
        const double accelerating = r.friction_force[0], decelerating = r.friction_force[1];
        const double width = accelerating - decelerating;
        const double first_order = 2 * (s / law.params().attraction) * std::abs(slope) * v_a * omega;
        INFO("f = " << f << " Hz: accelerating " << accelerating << " N, decelerating " << decelerating
                    << " N, s(v) = " << s << " N, first-order width " << first_order << " N");
        CHECK(r.events.empty());
        CHECK(accelerating > s);  // lags above the falling curve, and below the rising one
        CHECK(decelerating < s);
        CHECK(width < 0.5 * last_width);  // measured 6.77e-2, 1.87e-2, 6.23e-3, 1.87e-3 N
        if (f <= 1.0) CHECK(width == Approx(first_order).epsilon(0.02));
        last_width = width;
    }
}

TEST_CASE("GMS parameter rules: each field rejected naming it, the weights must sum to 1", "[gms][validation]") {
    const auto bad = [](auto change) {
        return rejected_parameter([&] {
            GMS::Params p;
            change(p);
            GMS law(p);
        });
    };
    CHECK(bad([](GMS::Params& p) { p.coulomb_coefficient = 0.0; }) == "coulomb_coefficient");
    CHECK(bad([](GMS::Params& p) { p.static_coefficient = 0.2; }) == "static_coefficient");  // below mu
    CHECK(bad([](GMS::Params& p) { p.stribeck_velocity = -1e-3; }) == "stribeck_velocity");
    CHECK(bad([](GMS::Params& p) { p.shape_exponent = 0.0; }) == "shape_exponent");
    CHECK(bad([](GMS::Params& p) { p.attraction = NAN; }) == "attraction");
    CHECK(bad([](GMS::Params& p) { p.block_stiffness_1 = 0.0; }) == "block_stiffness_1");
    CHECK(bad([](GMS::Params& p) { p.block_stiffness_2 = -1.0; }) == "block_stiffness_2");
    CHECK(bad([](GMS::Params& p) { p.block_stiffness_3 = INFINITY; }) == "block_stiffness_3");
    CHECK(bad([](GMS::Params& p) { p.block_stiffness_4 = NAN; }) == "block_stiffness_4");
    CHECK(bad([](GMS::Params& p) { p.block_weight_1 = 0.0; }) == "block_weight_1");
    CHECK(bad([](GMS::Params& p) { p.block_weight_2 = -0.2; }) == "block_weight_2");
    CHECK(bad([](GMS::Params& p) { p.block_weight_3 = 1.1; }) == "block_weight_3");
    CHECK(bad([](GMS::Params& p) { p.block_weight_4 = NAN; }) == "block_weight_4");
    CHECK(bad([](GMS::Params& p) { p.block_damping = -1.0; }) == "block_damping");
    CHECK(bad([](GMS::Params& p) { p.viscous_damping = -1.0; }) == "viscous_damping");
    // every field of the table is covered above, in table order
    CHECK(GMS::fields.size() == 15);

    CHECK(rejection_message([] {
              GMS::Params p;
              p.block_weight_1 = 0.5;  // sum 1.4
              GMS law(p);
          }) == "GeneralizedMaxwellSlip: block_weight_4 must be such that the block weights sum to 1 "
                "(block_weight_1 + ... + block_weight_4 = 1.3999999999999999, not 1 within 1.0000000000000001e-09) "
                "(got 0.40000000000000002)");
    CHECK(bad([](GMS::Params& p) { p.block_weight_4 = 0.3; }) == "block_weight_4");  // sum 0.9
    CHECK(bad([](GMS::Params& p) { p.block_weight_4 = 0.4 + 2e-9; }) == "block_weight_4");
    CHECK_NOTHROW(GMS([] {  // rounding of decimals is not an error
        GMS::Params p;
        p.block_weight_1 = p.block_weight_2 = p.block_weight_3 = 0.1 + 0.1 / 3;
        p.block_weight_4 = 0.6;
        return p;
    }()));
    CHECK(rejection_message([] {
              GMS::Params p;
              p.static_coefficient = 0.2;
              GMS law(p);
          }).find("static_coefficient must be >= coulomb_coefficient") != std::string::npos);
    CHECK_NOTHROW(GMS(GMS::Params{}));
}

using frictionsim::test::check_energy_balance;

TEST_CASE("GMS energy: axial rig drive work = stored energy + friction work - the blocks never give energy back "
          "beyond what their springs store",
          "[gms][axial_rig][energy]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    SECTION("axial rig, paper 000 Fig. 7(a) (v_r up to 0.53 m/s), with sigma_1 and sigma_2") {
        check_energy_balance(AxialRig<GMS>(AxialRigParams{}, GMS(gms_params(20.0, 5.0))), method, 0.5);
    }
    SECTION("kinematic rig, fast enough for the taper (|v| > C alpha_i / k_i): dissipation never decreases") {
        // sigma_1 = sigma_2 = 0: int F v dt - sum k_i z_i^2 / 2 = int sum_i k_i z_i (v - dz_i/dt) dt, which the
        // |v| / S_i bound keeps from decreasing (without it a block loaded against the motion would slip forwards)
        const GMS law(gms_params());
        const HarmonicSlidingVelocity v(0.0, 0.05, 2 * pi * 20.0);  // +-0.4 mm, |v| up to 50 mm/s
        std::vector<double> times;
        for (int i = 1; i <= 400; ++i) times.push_back(0.25e-3 * i);
        const Result r = simulate(KinematicRig<GMS, HarmonicSlidingVelocity>(law, v, ConstantSignal(normal)), 0.1,
                                  tight(method, times));
        const auto dissipated = [&](std::size_t row) {
            double stored = 0.0;
            for (std::size_t i = 0; i < GMS::block_count; ++i)
                stored += 0.5 * law.block_stiffness(i) * r.state(row, i) * r.state(row, i);
            return r.state(row, r.column("friction_work")) - stored;
        };
        int taper = 0;
        for (std::size_t row = 1; row < r.rows(); ++row) {
            INFO("t = " << r.t[row]);
            CHECK(dissipated(row) >= dissipated(row - 1) - 1e-9 * std::abs(dissipated(row)) - 1e-12);
            const double z[4] = {r.state(row, 0), r.state(row, 1), r.state(row, 2), r.state(row, 3)};
            const int branch = v(r.t[row]) < 0 ? -1 : 1;
            taper += law.regime(0, v(r.t[row]), normal, z, branch) == GMS::Regime::taper;
        }
        CHECK(taper > 20);  // block 1 (C alpha_1 / k_1 = 5 mm/s) went through it
        CHECK(dissipated(r.rows() - 1) > 5e-3);  // two cycles of gross sliding: ~3.4 N over 3.2 mm
    }
}

TEST_CASE("GMS analytic partials = central differences, in each regime - the axial rig's Jacobian with them",
          "[gms][jacobian]") {
    const GMS law(gms_params(3.0, 1.5));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::array<int, 3> seen{};
    for (int trial = 0; trial < 3000; ++trial) {
        const int branch = unit(rng) < 0.5 ? -1 : 1;
        const double v = branch * std::pow(10.0, -4.5 + 3.5 * unit(rng));  // 30 um/s .. 0.1 m/s
        const double s = law.stribeck_level(v, normal);
        std::array<double, 4> z{};
        for (std::size_t i = 0; i < 4; ++i)  // loads from -1.5 to 1.5 shares
            z[i] = branch * (3 * unit(rng) - 1.5) * law.block_weight(i) * s / law.block_stiffness(i);
        const auto p = law.partials(v, normal, z.data(), branch);
        // central differences; skip samples whose perturbations cross a kink (a regime change)
        const double hv = 1e-6 * std::abs(v);
        bool smooth = true;
        for (std::size_t i = 0; i < 4; ++i) {
            const double hz = 1e-7 * std::max(std::abs(z[i]), 1e-7);
            auto up = z, down = z;
            up[i] += hz;
            down[i] -= hz;
            const auto r0 = law.regime(i, v, normal, z.data(), branch);
            smooth = smooth && law.regime(i, v, normal, up.data(), branch) == r0 &&
                     law.regime(i, v, normal, down.data(), branch) == r0 &&
                     law.regime(i, v + hv, normal, z.data(), branch) == r0 &&
                     law.regime(i, v - hv, normal, z.data(), branch) == r0;
        }
        if (!smooth) continue;
        std::array<double, 4> dz_up{}, dz_down{};
        law.state_derivative(v + hv, normal, z.data(), branch, dz_up.data());
        law.state_derivative(v - hv, normal, z.data(), branch, dz_down.data());
        // rounding in f(x + h) - f(x - h) is ~1e-16 |f| / h: a small derivative reads as that
        const auto rounding = [](double up, double down, double h) {
            return 1e-14 * (std::abs(up) + std::abs(down)) / h;
        };
        const double f_up = law.force(v + hv, normal, z.data(), branch);
        const double f_down = law.force(v - hv, normal, z.data(), branch);
        CHECK(p.force_velocity == Approx((f_up - f_down) / (2 * hv)).epsilon(1e-5).margin(rounding(f_up, f_down, hv)));
        for (std::size_t i = 0; i < 4; ++i) {
            ++seen[static_cast<int>(law.regime(i, v, normal, z.data(), branch))];
            INFO("block " << i + 1 << ", v = " << v << ", load / share = "
                          << branch * law.block_stiffness(i) * z[i] / (law.block_weight(i) * s));
            CHECK(p.rate_velocity[i] ==
                  Approx((dz_up[i] - dz_down[i]) / (2 * hv)).epsilon(1e-5).margin(rounding(dz_up[i], dz_down[i], hv)));
            const double hz = 1e-7 * std::max(std::abs(z[i]), 1e-7);
            auto up = z, down = z;
            up[i] += hz;
            down[i] -= hz;
            std::array<double, 4> a{}, b{};
            law.state_derivative(v, normal, up.data(), branch, a.data());
            law.state_derivative(v, normal, down.data(), branch, b.data());
            for (std::size_t j = 0; j < 4; ++j)  // block i's deflection moves block j's rate only for j = i
                CHECK(p.rate_state[j][i] ==
                      Approx((a[j] - b[j]) / (2 * hz)).epsilon(1e-5).margin(rounding(a[j], b[j], hz)));
            const double fz_up = law.force(v, normal, up.data(), branch);
            const double fz_down = law.force(v, normal, down.data(), branch);
            CHECK(p.force_state[i] ==
                  Approx((fz_up - fz_down) / (2 * hz)).epsilon(1e-5).margin(rounding(fz_up, fz_down, hz)));
        }
    }
    INFO("samples per regime: stick " << seen[0] << ", attraction " << seen[1] << ", taper " << seen[2]);
    CHECK(std::min({seen[0], seen[1], seen[2]}) > 200);

    // the axial rig's analytic Jacobian (what CVODE's Newton iteration uses) against its right-hand side
    const AxialRig<GMS> rig(AxialRigParams{}, law);
    constexpr std::size_t n = AxialRig<GMS>::state_size;
    std::uniform_real_distribution<double> deflection(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 200 && checked < 40; ++trial) {
        const int mode = trial % 2 ? slip_positive : slip_negative;
        std::array<double, n> x{};
        const double t = 0.1 * unit(rng);
        const double v_r = mode * std::pow(10.0, -3.0 + 2.5 * unit(rng));
        x[0] = 1e-3 * deflection(rng);
        x[1] = rig.surface_velocity(t) + v_r;
        for (std::size_t j = 0; j < 4; ++j) x[2 + j] = 40 * um * deflection(rng);
        bool smooth = true;
        for (std::size_t j = 0; j < 4; ++j) {
            const auto r0 = law.regime(j, v_r, 90.0, x.data() + 2, mode);
            for (double h : {-1e-6, 1e-6}) {
                auto y = x;
                y[2 + j] *= 1 + h;
                smooth = smooth && law.regime(j, v_r, 90.0, y.data() + 2, mode) == r0 &&
                         law.regime(j, v_r * (1 + h), 90.0, x.data() + 2, mode) == r0;
            }
        }
        if (!smooth) continue;
        ++checked;
        std::array<double, n * n> analytic{};
        rig.jacobian(t, x.data(), mode, analytic.data());
        for (std::size_t c = 0; c < n; ++c) {
            const double h = 1e-7 * std::max(1e-3, std::abs(x[c]));
            std::array<double, n> up = x, down = x, f_up{}, f_down{};
            up[c] += h;
            down[c] -= h;
            rig.rhs(t, up.data(), mode, f_up.data());
            rig.rhs(t, down.data(), mode, f_down.data());
            for (std::size_t r = 0; r < n; ++r) {
                INFO("d rhs[" << rig.state_names()[r] << "] / d " << rig.state_names()[c]);
                const double rounding = 1e-14 * (std::abs(f_up[r]) + std::abs(f_down[r])) / h;
                CHECK(analytic[c * n + r] ==
                      Approx((f_up[r] - f_down[r]) / (2 * h)).epsilon(1e-5).margin(rounding + 1e-9));
            }
        }
    }
    CHECK(checked == 40);
}

TEST_CASE("GMS kink at v_r = 0 located as an event on the axial rig: both integrators agree - Dormand-Prince takes "
          "fewer steps (not stiff)",
          "[gms][axial_rig]") {
    static_assert(check_friction_law<GMS>() && law_has_partials_v<GMS> && !declares_stiff<GMS>::value);
    const AxialRig<GMS> rig(AxialRigParams{}, GMS(gms_params()));
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-13;
    o.output_times = {0.0, 0.5};
    const Result rk = simulate(rig, 0.5, o);
    o.method = Method::cvode_bdf;
    const Result bdf = simulate(rig, 0.5, o);
    INFO("steps: Dormand-Prince " << rk.stats.steps << ", BDF " << bdf.stats.steps);
    CHECK(rk.events.size() >= 17);
    REQUIRE(rk.events.size() == bdf.events.size());
    for (std::size_t i = 0; i < rk.events.size(); ++i) {
        CHECK(rk.events[i].name == "relative_velocity");
        CHECK(rk.events[i].mode_after == -rk.events[i].mode_before);
        CHECK(rk.events[i].time == Approx(bdf.events[i].time).margin(1e-7));
    }
    const std::size_t impulse = rk.column("friction_impulse");
    CHECK(rk.state(1, impulse) == Approx(bdf.state(1, impulse)).epsilon(1e-6));
    // 2 s at rtol 1e-8: 17k Dormand-Prince steps (16 ms) against 51k BDF steps (170 ms), measured: the fastest
    // rate, C / s or k |v| / S_i, is not far enough from the motion's time scales for BDF to pay
    CHECK(rk.stats.steps < bdf.stats.steps);
}

TEST_CASE("GMS on the torsional rig: runs on both integrators to the same limit cycle", "[gms][torsional_rig]") {
    GMS::Params p;
    p.coulomb_coefficient = 0.22;  // paper 001's operating point, as fs.torsional.fig7_laws() sets the others
    p.static_coefficient = 0.35;
    p.stribeck_velocity = 0.3;
    const TorsionalRig<GMS> rig(TorsionalRigParams{}, GMS(p));
    SolverOptions o;
    o.rtol = 1e-9;
    o.atol = 1e-12;
    o.output_times = {5.0};
    const Result rk = simulate(rig, 5.0, o);
    o.method = Method::cvode_bdf;
    const Result bdf = simulate(rig, 5.0, o);
    CHECK(rk.events.size() > 0);
    // stick-slip amplifies the integrators' differences: measured 2.5e-5 apart at 5 s
    constexpr std::size_t disc_speed = TorsionalRig<GMS>::disc_speed;
    CHECK(rk.state(0, disc_speed) == Approx(bdf.state(0, disc_speed)).epsilon(1e-3));
}
