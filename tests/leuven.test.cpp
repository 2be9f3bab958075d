// Leuven friction (Swevers et al. 2000; Lampaert et al. 2002) against the properties its papers state: the Stribeck
// curve in steady sliding, presliding hysteresis with non-local memory (Masing transition curves, inner loops that
// close and are wiped out, the first loop closing on the virgin curve), LuGre when the hysteresis force is linear
// without memory and n = 1; and the engine's own: the memory updated at the located reversals on both integrators,
// parameter rules, the energy balance on the axial rig.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "rig_checks.hpp"

using namespace frictionsim;

namespace {

// F_N = 10 N: F_s = 4 N, F_c = 3 N. k = 1e5 N/m, h = 0.5: the virgin curve reaches F_s at F_s / (k (1 - h)) = 80 um.
constexpr double normal = 10.0;
constexpr double um = 1e-6;

Leuven::Params params(double n = 2.0, double micro_damping = 0.0, double viscous_damping = 0.0) {
    Leuven::Params p;
    p.attraction_exponent = n;
    p.micro_damping = micro_damping;
    p.viscous_damping = viscous_damping;
    return p;
}

/// The virgin curve written out (not the law's): k x / (1 + h k |x| / (mu_s F_N)).
double virgin(double x, double k = 1e5, double h = 0.5) { return k * x / (1.0 + h * k * std::abs(x) / (0.4 * normal)); }

SolverOptions tight(Method method, std::vector<double> output_times) {
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-15;
    o.output_times = std::move(output_times);
    return o;
}

/// A displacement through knots x_k at t = k T, half a cosine per segment: v = 0 at every knot.
struct KnotPath {
    std::vector<double> x;
    double T;
    std::size_t segment(double t) const {
        return std::min<std::size_t>(static_cast<std::size_t>(std::max(0.0, t) / T), x.size() - 2);
    }
    double operator()(double t) const {
        const std::size_t k = segment(t);
        return (x[k + 1] - x[k]) * pi / (2 * T) * std::sin(pi * (t - k * T) / T);
    }
};

std::vector<double> grid(double t_end, int n) {
    std::vector<double> t;
    for (int i = 0; i <= n; ++i) t.push_back(t_end * i / n);
    return t;
}

std::array<double, Leuven::state_count> row(const Result& r, std::size_t i) {
    std::array<double, Leuven::state_count> z{};
    for (std::size_t j = 0; j < Leuven::state_count; ++j) z[j] = r.state(i, j);
    return z;
}

/// y(x) by linear interpolation in samples (xs, ys) with xs monotone (either way).
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    for (std::size_t i = 1; i < xs.size(); ++i) {
        const double a = xs[i - 1], b = xs[i];
        if ((x - a) * (x - b) <= 0.0 && a != b) return ys[i - 1] + (ys[i] - ys[i - 1]) * (x - a) / (b - a);
    }
    return NAN;
}

}  // namespace

TEST_CASE("Leuven steady sliding: F = S(v) + sigma_2 v (the Stribeck curve); sigma_1 drops out", "[leuven][kinematic_rig]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    for (double n : {1.0, 2.0, 4.0}) {
        const Leuven law(params(n, 50.0, 2.0));
        for (double v : {-3e-3, -1e-3, 2e-4, 1e-3, 5e-3, 0.1}) {
            // the relaxation length S / (n dF_h/dz) is at most 80 um / n: 60 of them
            const double t_end = 60 * 80 * um / std::abs(v);
            const Result r =
                simulate(KinematicRig(law, ConstantSignal(v), ConstantSignal(normal)), t_end, tight(method, {t_end}));
            const double s = normal * (0.3 + 0.1 * std::exp(-std::pow(v / 1e-3, 2)));
            INFO(method_name(method) << ", n = " << n << ", v = " << v);
            CHECK(r.events.empty());
            CHECK(law.stribeck_level(v, normal) == Approx(s).epsilon(1e-15));
            CHECK(r.friction_force.back() == Approx(std::copysign(s, v) + 2.0 * v).epsilon(1e-8));
            // on the virgin curve, at the force S: z = F_vc^-1(S)
            const double z = r.state(r.rows() - 1, Leuven::presliding);
            CHECK(virgin(z) == Approx(std::copysign(s, v)).epsilon(1e-8));
        }
    }
}

TEST_CASE("Leuven presliding: Masing transition curves from each turning point, inner loops close and are wiped out, "
          "the first loop closes on the virgin curve",
          "[leuven][kinematic_rig]") {
    // Displacements as fractions of the 80 um presliding range: A: 0 -> 0.75 -> -0.5 -> 0.25 -> -0.5 -> -0.875;
    // B: 0 -> 0.75 -> -1.25, the same without the inner loop -0.5 -> 0.25 -> -0.5. One segment per second
    // (|v| <= 0.19 mm/s, S within 4 % of F_s). n = 4: presliding close to rate-independent.
    const double range = 80 * um;
    const KnotPath a{{0, 0.75 * range, -0.5 * range, 0.25 * range, -0.5 * range, -0.875 * range}, 1.0};
    const KnotPath b{{0, 0.75 * range, -1.25 * range}, 1.0};
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    const Leuven law(params(4.0));
    const Result ra = simulate(KinematicRig(law, a, ConstantSignal(normal)), 5.0, tight(method, grid(5.0, 1000)));
    const Result rb = simulate(KinematicRig(law, b, ConstantSignal(normal)), 2.0, tight(method, grid(2.0, 400)));
    REQUIRE(ra.rows() == 1001);
    REQUIRE(rb.rows() == 401);
    CHECK(ra.events.size() == 3);  // the pass through -0.5 at t = 4 s is a standstill, no reversal
    CHECK(rb.events.size() == 1);
    const auto z = [](const Result& r, std::size_t i) { return r.state(i, Leuven::presliding); };
    const auto count = [](const Result& r, std::size_t i) { return r.state(i, Leuven::count); };

    // the virgin curve, then one Masing curve per turning point: F = F_j + 2 F_vc((z - z_j) / 2)
    for (std::size_t i : {50, 100, 150}) CHECK(ra.friction_force[i] == Approx(virgin(z(ra, i))).epsilon(1e-9));
    const double z1 = ra.state(300, Leuven::turning), f1 = virgin(z1);
    CHECK(count(ra, 300) == 1.0);
    CHECK(ra.friction_force[200] == Approx(f1).epsilon(1e-9));  // t = 1 s: the reversal
    for (std::size_t i : {250, 300, 350})
        CHECK(ra.friction_force[i] == Approx(f1 + 2 * virgin((z(ra, i) - z1) / 2)).epsilon(1e-9));
    const double z2 = ra.state(500, Leuven::turning + 1), f2 = f1 + 2 * virgin((z2 - z1) / 2);
    CHECK(count(ra, 500) == 2.0);
    for (std::size_t i : {450, 500, 550})
        CHECK(ra.friction_force[i] == Approx(f2 + 2 * virgin((z(ra, i) - z2) / 2)).epsilon(1e-9));
    const double z3 = ra.state(700, Leuven::turning + 2), f3 = f2 + 2 * virgin((z3 - z2) / 2);
    CHECK(count(ra, 700) == 3.0);
    CHECK(ra.friction_force[650] == Approx(f3 + 2 * virgin((z(ra, 650) - z3) / 2)).epsilon(1e-9));
    CHECK(ra.friction_force[600] == Approx(f3).epsilon(1e-9));  // t = 3 s: the inner reversal
    CHECK(f3 > f2 + 0.5);                                         // a loop, not a retrace

    // The inner loop closes at z2 (force f2) on the way down; from there A follows the curve from z1, as B does.
    std::size_t closed = 0;
    for (std::size_t i = 600; i <= 1000 && closed == 0; ++i)
        if (z(ra, i) < z2) closed = i;
    REQUIRE(closed > 800);  // after the standstill at -0.5 (t = 4 s): z lags x on the way up and down
    const std::array<double, Leuven::state_count> after = row(ra, closed);
    CHECK(law.turning_points(after.data(), -1) == 1);  // wiped (committed at the next reversal)
    CHECK(count(ra, closed) == 3.0);
    std::vector<double> zb, fb;
    for (std::size_t i = 200; i <= 400; ++i) {  // B's descending branch from the same turning point z1
        zb.push_back(z(rb, i));
        fb.push_back(rb.friction_force[i]);
    }
    CHECK(rb.state(300, Leuven::turning) == Approx(z1).margin(1e-6 * um));
    double gap = 0.0;
    int compared = 0;
    for (std::size_t i = closed; i <= 1000; ++i) {
        const double fb_here = interpolate(zb, fb, z(ra, i));
        if (std::isnan(fb_here)) continue;
        gap = std::max(gap, std::abs(ra.friction_force[i] - fb_here));
        ++compared;
    }
    INFO("max |F_A - F_B(z_A)| past the closing: " << gap << " N over " << compared << " samples");
    CHECK(compared > 100);
    CHECK(gap < 2e-4);  // linear interpolation between B's samples (0.005 s apart) sets it
    // B's loop from z1 closes on the virgin curve at -z1: beyond it F = F_vc(z) again
    for (std::size_t i = 380; i <= 400; i += 10) {
        REQUIRE(z(rb, i) < -z1);
        CHECK(rb.friction_force[i] == Approx(virgin(z(rb, i))).epsilon(1e-9));
    }
}

TEST_CASE("Leuven reduces to LuGre: linear hysteresis force (h = 0), no memory, n = 1", "[leuven][lugre][kinematic_rig]") {
    // The 2000 paper: with F_h(z) = sigma_0 z and n = 1, dz/dt = v (1 - sigma_0 z / S(v)) = v - sigma_0 |v| z / s(v).
    Leuven::Params p = params(1.0, 316.0, 0.4);
    p.hysteresis_shape = 0.0;
    p.memory_depth = 0.0;
    LuGre::Params q;
    q.coulomb_coefficient = p.coulomb_coefficient;
    q.static_coefficient = p.static_coefficient;
    q.stribeck_velocity = p.stribeck_velocity;
    q.bristle_stiffness = p.presliding_stiffness;
    q.bristle_damping = p.micro_damping;
    q.viscous_damping = p.viscous_damping;
    // reversing sliding through the Stribeck range and presliding: v = 0.5 mm/s - 2 mm/s cos(w t)
    const HarmonicSlidingVelocity v(0.5e-3, 2e-3, 2 * pi * 5.0);
    const auto times = grid(1.0, 500);
    const Result leuven = simulate(KinematicRig(Leuven(p), v, ConstantSignal(normal)), 1.0,
                                   tight(Method::cvode_bdf, times));
    const Result lugre = simulate(KinematicRig(LuGre(q), v, ConstantSignal(normal)), 1.0,
                                  tight(Method::cvode_bdf, times));
    REQUIRE(leuven.rows() == lugre.rows());
    double gap = 0.0, peak = 0.0;
    for (std::size_t i = 0; i < leuven.rows(); ++i) {
        gap = std::max(gap, std::abs(leuven.friction_force[i] - lugre.friction_force[i]));
        peak = std::max(peak, std::abs(lugre.friction_force[i]));
        CHECK(leuven.state(i, Leuven::count) == 0.0);
    }
    INFO("max |F_Leuven - F_LuGre| = " << gap << " N of " << peak << " N");
    CHECK(peak > 3.0);
    CHECK(gap < 1e-6 * peak);
    CHECK(leuven.events.size() == 10);  // the reversals are located, but nothing is remembered

    // with memory the 2002 state equation differs: each transition starts at r = 0, so F rises faster
    p.memory_depth = 8.0;
    const Result remembering = simulate(KinematicRig(Leuven(p), v, ConstantSignal(normal)), 1.0,
                                        tight(Method::cvode_bdf, times));
    double apart = 0.0;
    for (std::size_t i = 0; i < remembering.rows(); ++i)
        apart = std::max(apart, std::abs(remembering.friction_force[i] - lugre.friction_force[i]));
    CHECK(apart > 0.1);
}

TEST_CASE("Leuven memory is bounded: a long reversing run keeps at most memory_depth turning points, forces stay on "
          "the Stribeck level",
          "[leuven][kinematic_rig]") {
    Leuven::Params p = params(2.0);
    p.memory_depth = 3.0;
    const Leuven law(p);
    const HarmonicSlidingVelocity v(0.0, 2e-2, 2 * pi * 10.0);  // +-320 um sliding back and forth, 20 reversals
    const Result r = simulate(KinematicRig(law, v, ConstantSignal(normal)), 1.0, tight(Method::cvode_bdf, grid(1.0, 2000)));
    CHECK(r.events.size() == 20);
    double top = 0.0;
    for (std::size_t i = 0; i < r.rows(); ++i) {
        CHECK(r.state(i, Leuven::count) <= 3.0);
        top = std::max(top, std::abs(r.friction_force[i]));
    }
    CHECK(r.state(r.rows() - 1, Leuven::truncated) == 1.0);
    CHECK(top <= 4.0 + 1e-9);  // never above F_s
    CHECK(top > 3.0);
}

TEST_CASE("Leuven on the axial rig: drive work = stored energy + friction work across reversals",
          "[leuven][axial_rig][energy]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    frictionsim::test::check_energy_balance(AxialRig<Leuven>(AxialRigParams{}, Leuven(params(2.0, 20.0, 5.0))),
                                            method, 0.5);
}

TEST_CASE("Leuven parameter rules: each field rejected naming it", "[leuven][validation]") {
    const auto bad = [](auto change) {
        return rejected_parameter([&] {
            Leuven::Params p;
            change(p);
            Leuven law(p);
        });
    };
    CHECK(bad([](Leuven::Params& p) { p.coulomb_coefficient = 0.0; }) == "coulomb_coefficient");
    CHECK(bad([](Leuven::Params& p) { p.static_coefficient = 0.2; }) == "static_coefficient");
    CHECK(bad([](Leuven::Params& p) { p.stribeck_velocity = -1e-3; }) == "stribeck_velocity");
    CHECK(bad([](Leuven::Params& p) { p.shape_exponent = 0.0; }) == "shape_exponent");
    CHECK(bad([](Leuven::Params& p) { p.presliding_stiffness = NAN; }) == "presliding_stiffness");
    CHECK(bad([](Leuven::Params& p) { p.hysteresis_shape = 1.0; }) == "hysteresis_shape");
    CHECK(bad([](Leuven::Params& p) { p.attraction_exponent = 0.5; }) == "attraction_exponent");
    CHECK(bad([](Leuven::Params& p) { p.memory_depth = 9.0; }) == "memory_depth");
    CHECK(bad([](Leuven::Params& p) { p.memory_depth = 2.5; }) == "memory_depth");
    CHECK(bad([](Leuven::Params& p) { p.micro_damping = -1.0; }) == "micro_damping");
    CHECK(bad([](Leuven::Params& p) { p.viscous_damping = INFINITY; }) == "viscous_damping");
    CHECK(Leuven::fields.size() == 10);
}
