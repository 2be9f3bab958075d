// Leuven friction (Swevers et al. 2000; Lampaert et al. 2002) against the properties its papers state: the Stribeck
// curve in steady sliding, presliding hysteresis with non-local memory (Masing transition curves, inner loops that
// close and are wiped out, the first loop closing on the virgin curve), LuGre when the hysteresis force is linear
// without memory and n = 1; and the engine's own: the memory updated at the located reversals on both integrators,
// parameter rules, the energy balance on the axial rig; on a planar wall (wall_contact.hpp): the 1D law along an
// axis, the reversal ruled for 2D sliding against its closed form, passivity over closed paths.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <frictionsim/contact/wall_contact.hpp>
#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "rig_checks.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::KnotPath;
using frictionsim::test::tight;
using frictionsim::test::um;

namespace {

// F_N = 10 N: F_s = 4 N, F_c = 3 N. k = 1e5 N/m, h = 0.5: the virgin curve reaches F_s at F_s / (k (1 - h)) = 80 um.
constexpr double normal_load = 10.0;

Leuven::Params leuven_params(double n = 2.0, double micro_damping = 0.0, double viscous_damping = 0.0) {
    Leuven::Params p;
    p.attraction_exponent = n;
    p.micro_damping = micro_damping;
    p.viscous_damping = viscous_damping;
    return p;
}

/// The virgin curve written out (not the law's): k x / (1 + h k |x| / (mu_s F_N)).
double virgin(double x, double k = 1e5, double h = 0.5) { return k * x / (1.0 + h * k * std::abs(x) / (0.4 * normal_load)); }

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

/// A node on a planar wall (PlanarWallContact<Leuven>, r = 0.1 m) whose axial speed v(t) and rotation w(t) are
/// prescribed, motion(t, v, w): the planar counterpart of KinematicRig. States: the law's, the contact's reference
/// axis phi, the friction work int (f_a v + r f_t w) dt. friction_force: F along the axis, f_a cos phi + f_t sin phi.
template <class Motion>
struct PlanarKinematic {
    using Contact = PlanarWallContact<Leuven>;
    static constexpr std::size_t Z = Leuven::state_count, axis = Z, work = Z + 1;
    static constexpr std::size_t state_size = Z + 2, guard_count = Contact::guard_count;
    static constexpr bool stiff = true;
    static constexpr double radius = 0.1;

    PlanarKinematic(const Leuven& law, Motion m, double phi) : contact(law, radius, normal_load, 1e-3), motion(m), phi0(phi) {}

    Contact contact;
    Motion motion;
    double phi0;

    PlanarResponse response(double t, const double* x, int mode, double& v, double& w) const {
        motion(t, v, w);
        return contact.respond(w, v, 0.0, 0.0, x, mode, 1.0, 1.0);
    }
    void rhs(double t, const double* x, int mode, double* dx) const {
        double v = 0.0, w = 0.0;
        const PlanarResponse r = response(t, x, mode, v, w);
        std::fill(dx, dx + state_size, 0.0);
        contact.state_derivative(w, v, x, mode, dx);
        dx[work] = r.axial_force * v + r.torque * w;
    }
    void guards(double t, const double* x, int mode, double* g) const {
        double v = 0.0, w = 0.0;
        motion(t, v, w);
        contact.guards(w, v, PlanarLoads{}, x, mode, 1.0, 1.0, g);
    }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t k, int m) const { return Contact::guard_name(k, m); }
    const char* mode_name(int m) const { return Contact::mode_name(m); }
    int initial_mode(double t, const double* x) const {
        double v = 0.0, w = 0.0;
        motion(t, v, w);
        return contact.initial_mode(w, v, PlanarLoads{}, x);
    }
    int switch_mode(double t, double* x, int mode, const int* fired) const {
        double v = 0.0, w = 0.0, lost = 0.0;
        motion(t, v, w);
        return contact.switch_mode(w, v, PlanarLoads{}, x, mode, fired, 1.0, 1.0, lost);
    }
    double friction_force(double t, const double* x, int mode) const {
        double v = 0.0, w = 0.0;
        const PlanarResponse r = response(t, x, mode, v, w);
        return r.axial_force * std::cos(x[axis]) + r.torque / radius * std::sin(x[axis]);
    }
    std::array<double, state_size> initial_state() const {
        std::array<double, state_size> x{};
        x[axis] = phi0;
        return x;
    }
    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        for (std::size_t i = 0; i < Z; ++i) n[i] = Leuven::state_names[i];
        n[axis] = "slip_axis";
        n[work] = "friction_work";
        return n;
    }
};

/// The presliding test path of the inner-loop case below (fractions of the 80 um range): 0 -> 0.75 -> -0.5 ->
/// 0.25 -> -0.5 -> -0.875, one segment per second; the loop -0.5 -> 0.25 -> -0.5 closes and is wiped out.
KnotPath inner_loop_path() {
    const double range = 80 * um;
    return {{0, 0.75 * range, -0.5 * range, 0.25 * range, -0.5 * range, -0.875 * range}, 1.0};
}

/// Circular sliding q = V (cos W t, sin W t) at speed V, the axis phi from 0: with psi = W t - phi and K = V / l
/// (l the presliding length), d phi/dt = b K sin psi, so psi' = W - b K sin psi (Adler's equation). For W > K
/// from psi = 0 on branch +1: tan(psi / 2) = (K + w' tan(w' (t - c1) / 2)) / W, w' = sqrt(W^2 - K^2),
/// c1 = (2 / w') atan(K / w'); q . d = V cos psi falls to 0 at psi = pi / 2, at
/// t_r = (2 / w') [atan((W - K) / w') + atan(K / w')]. Then on branch -1: tan(psi / 2) = (-K + w' tan(w' (t - c2) /
/// 2)) / W, c2 = t_r - (2 / w') atan((W + K) / w'), while psi < pi. u = V cos psi is what the 1D law sees.
struct CircleClosedForm {
    double V, W, K;
    double wp() const { return std::sqrt(W * W - K * K); }
    double reversal() const { return 2.0 / wp() * (std::atan((W - K) / wp()) + std::atan(K / wp())); }
    double psi(double t) const {
        const double c1 = 2.0 / wp() * std::atan(K / wp()), c2 = reversal() - 2.0 / wp() * std::atan((W + K) / wp());
        if (t <= reversal()) return 2.0 * std::atan((K + wp() * std::tan(wp() * (t - c1) / 2.0)) / W);
        return 2.0 * std::atan((-K + wp() * std::tan(wp() * (t - c2) / 2.0)) / W);
    }
    double operator()(double t) const { return V * std::cos(psi(t)); }
    double end() const { return reversal() - 2.0 / wp() * std::atan((W + K) / wp()) + pi / wp(); }  ///< psi = pi
};

}  // namespace

TEST_CASE("Leuven steady sliding: F = S(v) + sigma_2 v (the Stribeck curve) - sigma_1 drops out", "[leuven][kinematic_rig]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    for (double n : {1.0, 2.0, 4.0}) {
        const Leuven law(leuven_params(n, 50.0, 2.0));
        for (double v : {-3e-3, -1e-3, 2e-4, 1e-3, 5e-3, 0.1}) {
            // the relaxation length S / (n dF_h/dz) is at most 80 um / n: 60 of them
            const double t_end = 60 * 80 * um / std::abs(v);
            const Result r =
                simulate(KinematicRig(law, ConstantSignal(v), ConstantSignal(normal_load)), t_end, tight(method, {t_end}));
            const double s = normal_load * (0.3 + 0.1 * std::exp(-std::pow(v / 1e-3, 2)));
            INFO(method_name(method) << ", n = " << n << ", v = " << v);
            CHECK(r.events.empty());
            CHECK(law.stribeck_level(v, normal_load) == Approx(s).epsilon(1e-15));
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
    const Leuven law(leuven_params(4.0));
    const Result ra = simulate(KinematicRig(law, a, ConstantSignal(normal_load)), 5.0, tight(method, grid(5.0, 1000)));
    const Result rb = simulate(KinematicRig(law, b, ConstantSignal(normal_load)), 2.0, tight(method, grid(2.0, 400)));
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
    Leuven::Params p = leuven_params(1.0, 316.0, 0.4);
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
    const Result leuven = simulate(KinematicRig(Leuven(p), v, ConstantSignal(normal_load)), 1.0,
                                   tight(Method::cvode_bdf, times));
    const Result lugre = simulate(KinematicRig(LuGre(q), v, ConstantSignal(normal_load)), 1.0,
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
    const Result remembering = simulate(KinematicRig(Leuven(p), v, ConstantSignal(normal_load)), 1.0,
                                        tight(Method::cvode_bdf, times));
    double apart = 0.0;
    for (std::size_t i = 0; i < remembering.rows(); ++i)
        apart = std::max(apart, std::abs(remembering.friction_force[i] - lugre.friction_force[i]));
    CHECK(apart > 0.1);
}

TEST_CASE("Leuven memory is bounded: a long reversing run keeps at most memory_depth turning points, forces stay on "
          "the Stribeck level",
          "[leuven][kinematic_rig]") {
    Leuven::Params p = leuven_params(2.0);
    p.memory_depth = 3.0;
    const Leuven law(p);
    const HarmonicSlidingVelocity v(0.0, 2e-2, 2 * pi * 10.0);  // +-320 um sliding back and forth, 20 reversals
    const Result r = simulate(KinematicRig(law, v, ConstantSignal(normal_load)), 1.0, tight(Method::cvode_bdf, grid(1.0, 2000)));
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
    frictionsim::test::check_energy_balance(AxialRig<Leuven>(AxialRigParams{}, Leuven(leuven_params(2.0, 20.0, 5.0))),
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

TEST_CASE("Leuven on a planar wall: purely axial or purely torsional sliding is the 1D law, force for force",
          "[leuven][wall_contact]") {
    // the planar contact's axis along v (phi = 0) or along r w (phi = pi / 2) against KinematicRig under the same
    // path, with sigma_1 and sigma_2: the same reversals at the same roots, the same forces and memory
    const KnotPath a = inner_loop_path();
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    const bool torsional = GENERATE(false, true);
    INFO(method_name(method) << (torsional ? ", torsional" : ", axial"));
    const Leuven law(leuven_params(4.0, 20.0, 3.0));
    SolverOptions o = tight(method, grid(5.0, 1000));
    o.rtol = 1e-12;  // what is left between the runs is the integrators' error on two state vectors
    o.atol = 1e-17;
    const KinematicRig rig(law, a, ConstantSignal(normal_load));
    const Result line = simulate(rig, 5.0, o);
    const auto motion = [a, torsional](double t, double& v, double& w) {
        v = torsional ? 0.0 : a(t);
        w = torsional ? a(t) / 0.1 : 0.0;
    };
    const PlanarKinematic<decltype(motion)> node(law, motion, torsional ? pi / 2 : 0.0);
    const Result plane = simulate(node, 5.0, o);
    // the right-hand sides agree at every state of the 1D run: bit for bit along v, to cos(pi / 2) along r w
    for (std::size_t i = 0; i < line.rows(); ++i) {
        std::array<double, Leuven::state_count + 2> x1{}, d1{}, xp{}, dp{};
        for (std::size_t j = 0; j < x1.size(); ++j) x1[j] = line.state(i, j);
        std::copy(x1.begin(), x1.begin() + Leuven::state_count, xp.begin());
        xp[Leuven::state_count] = node.phi0;
        rig.rhs(line.t[i], x1.data(), line.mode[i], d1.data());
        node.rhs(line.t[i], xp.data(), line.mode[i], dp.data());
        const double f1 = rig.friction_force(line.t[i], x1.data(), line.mode[i]);
        const double fp = node.friction_force(line.t[i], xp.data(), line.mode[i]);
        if (torsional) {
            CHECK(fp == Approx(f1).epsilon(1e-15).margin(1e-15));
            CHECK(dp[Leuven::presliding] == Approx(d1[Leuven::presliding]).epsilon(1e-15).margin(1e-20));
        } else {
            CHECK(fp == f1);
            CHECK(dp[Leuven::presliding] == d1[Leuven::presliding]);
        }
    }
    REQUIRE(line.rows() == 1001);
    REQUIRE(plane.rows() == 1001);
    REQUIRE(line.events.size() == 3);
    REQUIRE(plane.events.size() == 3);
    for (std::size_t k = 0; k < 3; ++k) {
        CHECK(plane.events[k].time == Approx(line.events[k].time).margin(1e-9));
        CHECK(plane.events[k].name == "sliding_reversal");
        CHECK(plane.events[k].mode_after == line.events[k].mode_after);
    }
    double gap = 0.0;
    for (std::size_t i = 0; i <= 1000; ++i) {
        gap = std::max(gap, std::abs(plane.friction_force[i] - line.friction_force[i]));
        for (std::size_t j = 0; j < Leuven::state_count; ++j)
            CHECK(plane.state(i, j) == Approx(line.state(i, j)).margin(1e-9 * um));
    }
    INFO("max |F_planar - F_1D| = " << gap << " N");
    CHECK(gap < 1e-9 * 4.0);  // F_s = 4 N
    // the axis stays put: d x q = 0 along an axis
    CHECK(plane.state(1000, PlanarKinematic<decltype(motion)>::axis) == Approx(torsional ? pi / 2 : 0.0).margin(1e-15));
    // the friction work is the 1D law's int F v dt
    CHECK(plane.state(1000, Leuven::state_count + 1) ==
          Approx(line.state(1000, Leuven::state_count + 1)).epsilon(1e-9).margin(1e-15));
}

TEST_CASE("Leuven on a planar wall: sliding along a tilted line keeps the 1D memory, inner loops wiped out",
          "[leuven][wall_contact]") {
    // q = u(t) (cos 0.6, sin 0.6): both components slide, q reverses through zero (a 180 degree turn) at each knot
    const KnotPath a = inner_loop_path();
    const double alpha = 0.6;
    const Leuven law(leuven_params(4.0));
    const Result line =
        simulate(KinematicRig(law, a, ConstantSignal(normal_load)), 5.0, tight(Method::cvode_bdf, grid(5.0, 1000)));
    const auto motion = [a, alpha](double t, double& v, double& w) {
        v = a(t) * std::cos(alpha);
        w = a(t) * std::sin(alpha) / 0.1;
    };
    const PlanarKinematic<decltype(motion)> node(law, motion, alpha);
    const Result plane = simulate(node, 5.0, tight(Method::cvode_bdf, grid(5.0, 1000)));
    REQUIRE(plane.events.size() == 3);
    for (std::size_t i = 0; i <= 1000; i += 5) {
        CHECK(plane.friction_force[i] == Approx(line.friction_force[i]).margin(1e-8));
        for (std::size_t j = 0; j < Leuven::state_count; ++j)
            CHECK(plane.state(i, j) == Approx(line.state(i, j)).margin(1e-8 * um));
    }
    // three turning points held after the inner reversal (t = 3.5 s); by the end the loop has closed: one left
    CHECK(plane.state(700, Leuven::count) == 3.0);
    CHECK(law.turning_points(row(plane, 1000).data(), -1) == 1);
    // the force vector lies along the line: f_t / f_a = tan(alpha)
    double v = 0.0, w = 0.0;
    const double t = plane.t[300];
    const std::array<double, Leuven::state_count> z = row(plane, 300);
    std::array<double, Leuven::state_count + 1> zs{};
    std::copy(z.begin(), z.end(), zs.begin());
    zs[Leuven::state_count] = plane.state(300, Leuven::state_count);
    motion(t, v, w);
    const PlanarResponse r = node.contact.respond(w, v, 0.0, 0.0, zs.data(), -1, 1.0, 1.0);
    CHECK(r.torque / 0.1 / r.axial_force == Approx(std::tan(alpha)).epsilon(1e-12));
}

TEST_CASE("Leuven on a planar wall: a turn past 90 degrees within a presliding length is a reversal at the closed-"
          "form time, with the 1D memory of the projected motion - a slow turn is none",
          "[leuven][wall_contact]") {
    // V = 0.1 mm/s, l = F_s / k = 40 um: K = V / l = 2.5 rad/s (CircleClosedForm)
    const Leuven law(leuven_params(4.0));
    const double V = 1e-4, K = V / law.presliding_length(normal_load);
    REQUIRE(K == Approx(2.5).epsilon(1e-12));
    SECTION("W = 2 K: q turns faster than the axis follows") {
        const CircleClosedForm circle{V, 2.0 * K, K};
        const auto motion = [circle](double t, double& v, double& w) {
            v = circle.V * std::cos(circle.W * t);
            w = circle.V * std::sin(circle.W * t) / 0.1;
        };
        const double t_end = 0.98 * circle.end();
        const PlanarKinematic<decltype(motion)> node(law, motion, 0.0);
        const Result plane = simulate(node, t_end, tight(Method::cvode_bdf, grid(t_end, 400)));
        // the 1D law driven by the projected motion u = q . a = V cos psi, psi in closed form
        const Result line = simulate(KinematicRig(law, circle, ConstantSignal(normal_load)), t_end,
                                     tight(Method::cvode_bdf, grid(t_end, 400)));
        REQUIRE(plane.events.size() == 1);
        REQUIRE(line.events.size() == 1);
        const Event& e = plane.events[0];
        INFO("t_r = " << circle.reversal() << " s, the node's direction has turned " << circle.W * e.time * 180 / pi
                      << " degrees");
        CHECK(e.name == "sliding_reversal");
        CHECK(e.mode_before == 1);
        CHECK(e.mode_after == -1);
        CHECK(e.time == Approx(circle.reversal()).epsilon(1e-8));
        CHECK(line.events[0].time == Approx(circle.reversal()).epsilon(1e-8));
        CHECK(circle.W * e.time > pi / 2);  // more than 90 degrees from the first direction: 138.6
        // at the reversal the axis lags q by exactly 90 degrees
        REQUIRE(e.state_after.size() == PlanarKinematic<decltype(motion)>::state_size);
        CHECK(circle.W * e.time - e.state_after[Leuven::state_count] == Approx(pi / 2).epsilon(1e-8));
        // the memory pushed there is the 1D law's: one turning point at the same z
        CHECK(e.state_after[Leuven::count] == 1.0);
        CHECK(e.state_after[Leuven::turning] == Approx(line.events[0].state_after[Leuven::turning]).epsilon(1e-8));
        CHECK(e.state_after[Leuven::turning] == Approx(e.state_after[Leuven::presliding]).epsilon(1e-15));
        for (std::size_t i = 0; i < plane.rows(); ++i) {
            CHECK(plane.friction_force[i] == Approx(line.friction_force[i]).margin(1e-7));
            CHECK(plane.state(i, Leuven::presliding) == Approx(line.state(i, Leuven::presliding)).margin(1e-7 * um));
        }
    }
    SECTION("W = K / 2: the axis keeps up (gross sliding on a curve), lagging by asin(W / K) = 30 degrees") {
        const double W = 0.5 * K;
        const auto motion = [V, W](double t, double& v, double& w) {
            v = V * std::cos(W * t);
            w = V * std::sin(W * t) / 0.1;
        };
        const PlanarKinematic<decltype(motion)> node(law, motion, 0.0);
        const Result plane = simulate(node, 12.0, tight(Method::cvode_bdf, grid(12.0, 120)));
        CHECK(plane.events.empty());
        const std::size_t last = plane.rows() - 1;
        const double lag = W * 12.0 - plane.state(last, PlanarKinematic<decltype(motion)>::axis);
        CHECK(lag == Approx(std::asin(0.5)).epsilon(1e-6));
        // steady: F = S(u), u = V cos(lag): the Stribeck curve along the axis
        CHECK(plane.friction_force[last] == Approx(law.stribeck_level(V * std::cos(lag), normal_load)).epsilon(1e-6));
    }
}

TEST_CASE("Leuven on a planar wall: closed sliding paths take work (no energy created), the force stays within "
          "the static bound",
          "[leuven][wall_contact][energy]") {
    // circles in velocity space (closed paths of the node, period 2 pi / W) turning fast (reversals every half
    // turn of psi) and slowly, and the tilted inner-loop path, with and without sigma_1, sigma_2
    const double V = 1e-4;
    for (double n : {1.0, 4.0}) {
        for (double sigma : {0.0, 10.0}) {
            const Leuven law(leuven_params(n, sigma, sigma));
            const double K = V / law.presliding_length(normal_load);
            for (double W : {0.5 * K, 2.0 * K, 8.0 * K}) {
                const auto motion = [V, W](double t, double& v, double& w) {
                    v = V * std::cos(W * t);
                    w = V * std::sin(W * t) / 0.1;
                };
                const PlanarKinematic<decltype(motion)> node(law, motion, 0.0);
                const double period = 2 * pi / W;
                const Result r = simulate(node, 6 * period, tight(Method::cvode_bdf, grid(6 * period, 6 * 50)));
                INFO("n = " << n << ", sigma = " << sigma << ", W / K = " << W / K << ": " << r.events.size()
                            << " reversals");
                REQUIRE(r.rows() == 301);
                if (W > K) CHECK(r.events.size() >= 6);
                const std::size_t work = PlanarKinematic<decltype(motion)>::work;
                for (std::size_t p = 0; p < 6; ++p) CHECK(r.state(50 * (p + 1), work) - r.state(50 * p, work) > 0.0);
                double peak = 0.0;  // the hysteresis force (sigma_1 dz/dt, sigma_2 u ride on it)
                for (std::size_t i = 0; i < r.rows(); ++i) {
                    const std::array<double, Leuven::state_count> z = row(r, i);
                    peak = std::max(peak, std::abs(law.hysteresis_force(normal_load, z.data(), r.mode[i])));
                }
                CHECK(peak <= 0.4 * normal_load * (1 + 1e-9));
            }
        }
    }
}
