// The hysteretic velocity-acceleration friction torque of paper 001 (eq 6, friction/hysteretic.hpp): the law
// by hand on each branch and in the stick band, its odd extension to w < 0, the normal-force scaling, the branch
// equation J al + T(w, al) = S solved as a quadratic (root continuous with the linear case, stable for small A),
// and the rejection of bad parameters. Then the law on the kinematic rig (KinematicRig<HystereticFriction, V, N>,
// w(t) prescribed and dw/dt its derivative): the signals' derivatives, the recorded torque against eq 6 by hand,
// the switches as events at their analytic times, the friction work, and Fig. 5a's loop of paper001_fig7_friction.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::kInf;
using frictionsim::test::kNaN;

namespace {

/// Every coefficient non-zero and distinct, so that a swapped or dropped term shows.
HystereticFriction::Params distinct_params() {
    HystereticFriction::Params p;
    p.stick_slope = 1300.0;
    p.stick_speed = 2e-3;
    p.accelerating = {0.9, -0.03, -0.004, 0.002, 3e-4, 5e-5};
    p.decelerating = {1.1, -0.05, -0.002, 0.003, -2e-4, -7e-5};
    p.reference_normal_force = 35.0;
    return p;
}

/// Eq 6 written out for w > w_s (the paper's fitted side), coefficient by coefficient.
double poly22(const BranchPolynomial& c, double w, double al) {
    return c.c00 + c.c10 * w + c.c01 * al + c.c20 * w * w + c.c11 * w * al + c.c02 * al * al;
}

/// |J al + T(w, al) - S| relative to the size of its terms: the branch equation's residual.
double relative_residual(const HystereticFriction& law, bool accelerating, double w, double al, double s,
                         double inertia, double normal) {
    const double t = law.slip_torque(accelerating, w, al, normal);
    return std::abs(inertia * al + t - s) / (std::abs(inertia * al) + std::abs(t) + std::abs(s));
}

}  // namespace

TEST_CASE("hysteretic law: eq 6 by hand on the stick band and both slip branches", "[hysteretic]") {
    const HystereticFriction::Params p = distinct_params();
    const HystereticFriction law(p);
    const double n = p.reference_normal_force;

    SECTION("stick band: T = a w for |w| <= w_s, whatever the acceleration") {
        for (double w : {0.0, 1e-4, -7e-4, 1.5e-3, p.stick_speed, -p.stick_speed})
            for (double al : {-50.0, 0.0, 50.0}) {
                INFO("w = " << w << ", al = " << al);
                CHECK(law.torque(w, al, n) == Approx(p.stick_slope * w).margin(1e-15));
            }
        // the break-away torque a w_s at the band edge
        CHECK(law.torque(p.stick_speed, 0.0, n) == Approx(1300.0 * 2e-3));
    }
    SECTION("accelerating branch (w > w_s, al > 0): the p polynomial") {
        for (double w : {2.5e-3, 0.5, 3.0, 12.0})
            for (double al : {1e-6, 0.7, 25.0}) {
                INFO("w = " << w << ", al = " << al);
                CHECK(law.torque(w, al, n) == Approx(poly22(p.accelerating, w, al)).epsilon(1e-13));
                CHECK(law.slip_torque(true, w, al, n) == Approx(poly22(p.accelerating, w, al)).epsilon(1e-13));
            }
        // one value fully by hand: w = 3, al = 2
        const double by_hand = 0.9 - 0.03 * 3 - 0.004 * 2 + 0.002 * 9 + 3e-4 * 6 + 5e-5 * 4;
        CHECK(law.torque(3.0, 2.0, n) == Approx(by_hand).epsilon(1e-14));
        CHECK(by_hand == Approx(0.8220).epsilon(1e-12));
    }
    SECTION("decelerating branch (w > w_s, al < 0), and al = 0, which eq 6 leaves open, counts as decelerating") {
        for (double w : {2.5e-3, 0.5, 3.0, 12.0})
            for (double al : {-1e-6, -0.7, -25.0, 0.0}) {
                INFO("w = " << w << ", al = " << al);
                CHECK(law.torque(w, al, n) == Approx(poly22(p.decelerating, w, al)).epsilon(1e-13));
                CHECK(law.slip_torque(false, w, al, n) == Approx(poly22(p.decelerating, w, al)).epsilon(1e-13));
            }
        const double by_hand = 1.1 - 0.05 * 3 + 0.002 * 2 + 0.003 * 9 + 2e-4 * 6 - 7e-5 * 4;
        CHECK(law.torque(3.0, -2.0, n) == Approx(by_hand).epsilon(1e-14));
        CHECK(law.torque(3.0, 0.0, n) == Approx(1.1 - 0.15 + 0.027).epsilon(1e-14));
    }
    SECTION("the two branches differ: the hysteresis of Fig. 5a") {
        CHECK(law.torque(3.0, 1e-9, n) != Approx(law.torque(3.0, -1e-9, n)).epsilon(1e-3));
        CHECK(law.branch(true).level(3.0) == Approx(0.9 - 0.09 + 0.018));
        CHECK(law.branch(false).level(3.0) == Approx(1.1 - 0.15 + 0.027));
    }
    SECTION("just outside the band the slip branch takes over") {
        const double w = std::nextafter(p.stick_speed, 1.0);
        CHECK(law.torque(w, 1.0, n) == Approx(poly22(p.accelerating, w, 1.0)));
        CHECK(law.torque(w, -1.0, n) == Approx(poly22(p.decelerating, w, -1.0)));
    }
}

TEST_CASE("hysteretic law: odd extension T(-w, -al) = -T(w, al)", "[hysteretic]") {
    const HystereticFriction::Params p = distinct_params();
    const HystereticFriction law(p);
    const double n = p.reference_normal_force;
    for (double w : {0.0, 5e-4, 2e-3, 2.5e-3, 0.4, 3.0, 11.0})
        for (double al : {-30.0, -1.0, -1e-7, 0.0, 1e-7, 1.0, 30.0}) {
            INFO("w = " << w << ", al = " << al);
            CHECK(law.torque(-w, -al, n) == -law.torque(w, al, n));
            if (w == 0.0) continue;  // slip_torque's side is sgn(w): undefined at w = 0 (inside the band anyway)
            CHECK(law.slip_torque(true, -w, -al, n) == -law.slip_torque(true, w, al, n));
            CHECK(law.slip_torque(false, -w, -al, n) == -law.slip_torque(false, w, al, n));
        }
    // |w| increasing on the negative side (w < 0, al < 0) is the accelerating branch, opposing the motion
    CHECK(law.torque(-3.0, -2.0, n) == Approx(-poly22(p.accelerating, 3.0, 2.0)));
    CHECK(law.torque(-3.0, 2.0, n) == Approx(-poly22(p.decelerating, 3.0, -2.0)));
    CHECK(law.torque(-3.0, -2.0, n) < 0.0);
    CHECK(law.torque(-5e-4, 0.0, n) == Approx(-p.stick_slope * 5e-4));
}

TEST_CASE("hysteretic law: the normal force scales every torque by N / N_ref", "[hysteretic]") {
    HystereticFriction::Params p = distinct_params();
    const HystereticFriction at35(p);
    p.reference_normal_force = 10.0;
    const HystereticFriction at10(p);
    CHECK(at35.scale(70.0) == 2.0);
    CHECK(at10.scale(35.0) == 3.5);
    for (double w : {-6.0, -1e-3, 5e-4, 0.3, 6.0})
        for (double al : {-4.0, 0.0, 4.0}) {
            INFO("w = " << w << ", al = " << al);
            const double base = at35.torque(w, al, 35.0);
            CHECK(at35.torque(w, al, 70.0) == Approx(2.0 * base).epsilon(1e-14));
            CHECK(at35.torque(w, al, 8.75) == Approx(0.25 * base).epsilon(1e-14));
            CHECK(at10.torque(w, al, 35.0) == Approx(3.5 * base).epsilon(1e-14));
            CHECK(at10.torque(w, al, 10.0) == Approx(base).epsilon(1e-14));
        }
    // the break-away torque of the band scales too
    CHECK(at35.stick_torque(p.stick_speed, 70.0) == Approx(2.0 * p.stick_slope * p.stick_speed));
}

TEST_CASE("hysteretic law: the branch quadratic's root solves J al + T(w, al) = S", "[hysteretic]") {
    const double inertia = 0.0149;
    HystereticFriction::Params p = distinct_params();
    // strong quadratic terms: p02 al^2 and n02 al^2 reach O(0.1..1) N m at the accelerations below
    const double p02 = GENERATE(0.0, 5e-5, 2e-3, -4e-4);
    const double n02 = -p02;
    p.accelerating.c02 = p02;
    p.decelerating.c02 = n02;
    const HystereticFriction law(p);
    int solved = 0;
    for (double normal : {35.0, 52.5})
        for (double w : {0.5, 3.0, 12.0, -0.5, -3.0, -12.0})
            for (bool accelerating : {true, false})
                for (double excess : {1e-6, 0.01, 0.1, 0.3}) {
                    const double s_sign = w < 0 ? -1.0 : 1.0, u = std::abs(w), k = law.scale(normal);
                    // a shaft torque on the consistent side of the branch's level: S' > P0 or S' < N0
                    const double level = k * law.branch(accelerating).level(u);
                    const double signed_torque = accelerating ? level + excess : level - excess;
                    const HystereticFriction::Quadratic q =
                        law.branch_equation(accelerating, u, signed_torque, inertia, normal);
                    if (q.a != 0.0 && q.discriminant() < 0.0) continue;  // no real root: the rig's guard D
                    const double b = q.root();
                    const double al = s_sign * b, s = s_sign * signed_torque;
                    INFO("p02 = " << p02 << ", N = " << normal << ", w = " << w << ", "
                                  << (accelerating ? "accelerating" : "decelerating") << ", S = " << s
                                  << ", al = " << al);
                    CHECK(std::isfinite(al));
                    CHECK(relative_residual(law, accelerating, w, al, s, inertia, normal) < 1e-12);
                    // the root has the branch's sign: the branch is consistent (al > 0 <=> accelerating)
                    CHECK((accelerating ? b > 0.0 : b < 0.0));
                    // and law.torque picks that same branch back from the signs of w and al
                    CHECK(std::abs(inertia * al + law.torque(w, al, normal) - s) <=
                          1e-12 * (std::abs(s) + std::abs(inertia * al) + 1.0));
                    ++solved;
                }
    CHECK(solved >= 48);  // at least half of the combinations have a real root
}

TEST_CASE("hysteretic law: Quadratic::root is the root continuous with the linear case, stable for small A",
          "[hysteretic]") {
    using Q = HystereticFriction::Quadratic;
    SECTION("A = 0: exactly the linear root -C / B") {
        CHECK(Q{0.0, 0.0149, -0.25}.root() == Approx(0.25 / 0.0149).epsilon(1e-15));
        CHECK(Q{0.0, 0.0149, 0.25}.root() == Approx(-0.25 / 0.0149).epsilon(1e-15));
        CHECK(Q{0.0, 0.0149, 0.0}.root() == 0.0);
    }
    SECTION("tiny A: -C/B - A C^2/B^3 to full precision, where (-B + sqrt(D)) / 2A loses every digit") {
        for (double a : {1e-20, -1e-20, 1e-14, -1e-14, 1e-12}) {
            const double b = 0.01, c = -1.0;
            const Q q{a, b, c};
            const double linear = -c / b, series = linear - a * c * c / (b * b * b);
            INFO("A = " << a);
            CHECK(q.root() == Approx(series).epsilon(1e-14));
            const double textbook = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
            CHECK(std::abs(q.root() * q.root() * a + b * q.root() + c) <= 1e-15 * (std::abs(b * q.root()) + 1.0));
            if (std::abs(a) <= 1e-14) CHECK(std::abs(textbook - series) > 1e-9 * series);  // why the stable form
        }
    }
    SECTION("A of either sign, D > 0: a true root, the (-B + sqrt D) / 2A one that tends to -C/B as A -> 0") {
        int checked = 0;
        for (double a : {2e-3, -2e-3, 0.05, -0.05, 1e-6, -1e-6})
            for (double c : {-0.2, -1e-3, 1e-3, 0.2}) {
                const double b = 0.02;
                const Q q{a, b, c};
                if (q.discriminant() < 0.0) continue;
                const double r = q.root();
                // the continuous root in extended precision; the other one, (-B - sqrt D) / 2A, is ~ -B/A for small A
                const long double al = a, bl = b, cl = c;
                const long double continuous = (-bl + std::sqrt(bl * bl - 4 * al * cl)) / (2 * al);
                const long double other = (-bl - std::sqrt(bl * bl - 4 * al * cl)) / (2 * al);
                INFO("A = " << a << ", C = " << c << ", root " << r << ", other root " << static_cast<double>(other));
                CHECK(std::abs(a * r * r + b * r + c) <= 1e-14 * (std::abs(a * r * r) + std::abs(b * r) + std::abs(c)));
                CHECK(r == Approx(static_cast<double>(continuous)).epsilon(1e-9));
                CHECK(std::abs(r - static_cast<double>(other)) > 1e-3 * std::abs(r));  // not the spurious one
                CHECK((c < 0 ? r > 0.0 : r < 0.0));  // sign of -C for B > 0: the branch's consistency test
                ++checked;
            }
        CHECK(checked >= 16);
    }
    SECTION("D < 0 (a trial state past a located root loss) stays finite") {
        const Q q{-0.05, 0.02, -1.0};
        REQUIRE(q.discriminant() < 0.0);
        CHECK(std::isfinite(q.root()));
    }
}

TEST_CASE("hysteretic law: branch_equation's coefficients are J + k(c01 + c11 u), k c02, k level(u) - S'",
          "[hysteretic]") {
    const HystereticFriction::Params p = distinct_params();
    const HystereticFriction law(p);
    const auto q = law.branch_equation(false, 4.0, 0.6, 0.0149, 70.0);  // k = 2
    CHECK(q.a == Approx(2 * p.decelerating.c02));
    CHECK(q.b == Approx(0.0149 + 2 * (p.decelerating.c01 + p.decelerating.c11 * 4.0)));
    CHECK(q.c == Approx(2 * (1.1 - 0.05 * 4 + 0.003 * 16) - 0.6));
}

TEST_CASE("hysteretic law rejects bad parameters, naming them", "[hysteretic][validation]") {
    const HystereticFriction::Params ok = distinct_params();
    const auto build = [](const HystereticFriction::Params& p) { (void)HystereticFriction(p); };
    CHECK(rejected_parameter([&] { build(ok); }) == "<nothing thrown>");

    using P = HystereticFriction::Params;
    struct Scalar {
        const char* name;
        double P::*field;
        std::vector<double> bad;
    };
    const std::vector<double> not_positive{0.0, -0.0, -1.0, -1e-300, kNaN, kInf, -kInf};
    for (const Scalar& s : {Scalar{"stick_slope", &P::stick_slope, not_positive},
                            Scalar{"stick_speed", &P::stick_speed, not_positive},
                            Scalar{"reference_normal_force", &P::reference_normal_force, not_positive}})
        for (double v : s.bad) {
            P p = ok;
            p.*(s.field) = v;
            INFO(s.name << " = " << v);
            CHECK(rejected_parameter([&] { build(p); }) == s.name);
            CHECK(rejection_message([&] { build(p); }).find(s.name) != std::string::npos);
        }

    // every coefficient of both branches: NaN and infinities, each named as the paper names it
    using C = BranchPolynomial;
    const std::array<std::pair<const char*, double C::*>, 6> terms{{{"00", &C::c00},
                                                                    {"10", &C::c10},
                                                                    {"01", &C::c01},
                                                                    {"20", &C::c20},
                                                                    {"11", &C::c11},
                                                                    {"02", &C::c02}}};
    for (const auto& [suffix, field] : terms)
        for (bool accelerating : {true, false})
            for (double v : {kNaN, kInf, -kInf}) {
                P p = ok;
                // through a named reference: GCC 12 drops the store in `(c ? p.x : p.y).*field = v`
                BranchPolynomial& branch = accelerating ? p.accelerating : p.decelerating;
                branch.*field = v;
                const std::string name = std::string(accelerating ? "p" : "n") + suffix;
                INFO(name << " = " << v);
                CHECK(rejected_parameter([&] { build(p); }) == name);
            }
    // the case the lead asked for explicitly
    P p11 = ok;
    p11.accelerating.c11 = kNaN;
    CHECK(rejected_parameter([&] { build(p11); }) == "p11");
    // negative or zero coefficients are legitimate (a Stribeck-like decrease, a negative added inertia)...
    P signs = ok;
    signs.accelerating = {1.0, -1.0, -0.01, -1.0, -1.0, -1.0};
    signs.decelerating = {0.5, 0.0, 0.0, -1.0, 0.0, 0.0};
    CHECK(rejected_parameter([&] { build(signs); }) == "<nothing thrown>");
    // ...but not a level p00 + p10 w_s + p20 w_s^2 <= 0 where slip begins: that friction drives the disc
    for (bool accelerating : {true, false}) {
        P p = ok;
        BranchPolynomial& branch = accelerating ? p.accelerating : p.decelerating;
        branch = {-1e-6, -1.0, 0.5, 0.0, 0.0, 0.0};  // the level alone decides, not the acceleration terms
        CHECK(rejected_parameter([&] { build(p); }) == (accelerating ? "accelerating" : "decelerating"));
        branch = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        CHECK(rejected_parameter([&] { build(p); }) == (accelerating ? "accelerating" : "decelerating"));
    }
}

//------------------------------------------------------------------------------------------------ kinematic rig
// Eq 6 on KinematicRig<HystereticFriction, V, N> (rigs/kinematic_hysteretic.hpp): w(t) prescribed, dw/dt its
// derivative, the torque explicit, the switches located events.
//
// (d) A relative-velocity signal without `double derivative(double t) const` does not compile: e.g.
//     KinematicRig rig(law, [](double t) { return std::sin(t); }, ConstantSignal(35.0));
// stops at the specialization's static_assert with
//     "KinematicRig<HystereticFriction, V, N>: eq 6 depends on the acceleration dw/dt, so the relative-velocity
//      signal V needs a member `double derivative(double t) const` (dw/dt in rad/s^2; ConstantSignal,
//      HarmonicSlidingVelocity and SampledSignal have one)"
// (checked by hand with GCC 12; a try_compile test would need its own CMake project). The trait it reads:
namespace {
const auto plain_lambda = [](double t) { return std::sin(t); };
struct SignalWithDerivative {
    double operator()(double t) const { return 2.0 + std::sin(t); }
    double derivative(double t) const { return std::cos(t); }
};
}  // namespace
static_assert(signal_has_derivative_v<ConstantSignal>);
static_assert(signal_has_derivative_v<HarmonicSlidingVelocity>);
static_assert(signal_has_derivative_v<SampledSignal>);
static_assert(signal_has_derivative_v<SignalWithDerivative>);
static_assert(!signal_has_derivative_v<decltype(plain_lambda)>);
static_assert(!signal_has_derivative_v<double (*)(double)>);

namespace {

/// Eq 6 by hand, coefficient by coefficient, in a given case: 0 stick, +-1 accelerating, +-2 decelerating on
/// side sgn(mode) (the odd extension for w < 0: T = s k poly22(s w, s al)).
double eq6_in_mode(const HystereticFriction::Params& p, int mode, double w, double al, double normal) {
    const double k = normal / p.reference_normal_force;
    if (mode == 0) return k * p.stick_slope * w;
    const double s = mode > 0 ? 1.0 : -1.0;
    return s * k * poly22(std::abs(mode) == 1 ? p.accelerating : p.decelerating, s * w, s * al);
}

/// Eq 6's case at (w, dw/dt), as the paper states it: the band, else accelerating iff w and dw/dt have the same
/// sign (dw/dt = 0 decelerating).
int eq6_case(const HystereticFriction::Params& p, double w, double al) {
    if (std::abs(w) <= p.stick_speed) return 0;
    const int s = w > 0.0 ? 1 : -1;
    return w * al > 0.0 ? s : 2 * s;
}

double eq6_by_hand(const HystereticFriction::Params& p, double w, double al, double normal) {
    return eq6_in_mode(p, eq6_case(p, w, al), w, al, normal);
}

double rel_diff(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

/// w(t) = v_d - v_a cos(om t): the analytic switch times in [0, t_end] (|w| = w_s, dw/dt = 0), sorted, with
/// the case before and after each and the guard that fires.
struct AnalyticSwitch {
    double t;
    int before, after;
    const char* guard;
};
std::vector<AnalyticSwitch> harmonic_switches(double v_d, double v_a, double om, double w_s, double t_end) {
    std::vector<AnalyticSwitch> out;
    const double period = 2 * pi / om;
    for (int k = 1; k * pi / om <= t_end; ++k)  // dw/dt = v_a om sin(om t) = 0; t = 0 is the start, no switch
        out.push_back({k * pi / om, k % 2 == 1 ? 1 : -1, k % 2 == 1 ? 2 : -2, "acceleration_zero"});
    for (int n = 0; n * period <= t_end; ++n) {
        const double up = std::acos((v_d - w_s) / v_a) / om, down = std::acos((v_d + w_s) / v_a) / om;
        // w rises through -w_s at t = down (into the band), through +w_s at t = up (out of it); then back down
        const AnalyticSwitch cycle[] = {{n * period + down, -2, 0, "stick_band_entry"},
                                        {n * period + up, 0, 1, "stick_band_upper_edge"},
                                        {(n + 1) * period - up, 2, 0, "stick_band_entry"},
                                        {(n + 1) * period - down, 0, -1, "stick_band_lower_edge"}};
        for (const AnalyticSwitch& s : cycle)
            if (s.t <= t_end) out.push_back(s);
    }
    std::sort(out.begin(), out.end(), [](const AnalyticSwitch& a, const AnalyticSwitch& b) { return a.t < b.t; });
    return out;
}

/// int_a^b f dt by the trapezoid rule on n and 2n intervals, Richardson-extrapolated (f smooth on [a, b]).
template <class F>
double trapezoid(F&& f, double a, double b, int n) {
    const auto rule = [&](int m) {
        const double h = (b - a) / m;
        double sum = 0.5 * (f(a) + f(b));
        for (int i = 1; i < m; ++i) sum += f(a + i * h);
        return sum * h;
    };
    const double coarse = rule(n), fine = rule(2 * n);
    return fine + (fine - coarse) / 3.0;
}

}  // namespace

TEST_CASE("signals' derivatives: constant 0, harmonic analytic, sampled the slope of the segment ahead",
          "[hysteretic][kinematic_rig]") {
    CHECK(ConstantSignal(3.5).derivative(7.0) == 0.0);
    const HarmonicSlidingVelocity h(3.0, 8.0, 2 * pi * 0.835);
    for (double t : {0.0, 0.1, 0.37, 1.2, 5.0}) {
        INFO("t = " << t);
        const double dt = 1e-5, central = (h(t + dt) - h(t - dt)) / (2 * dt);
        CHECK(h.derivative(t) == Approx(central).margin(1e-7));
        CHECK(h.derivative(t) == 8.0 * 2 * pi * 0.835 * std::sin(2 * pi * 0.835 * t));
    }
    const SampledSignal s({0.0, 1.0, 3.0, 3.5}, {-2.0, 4.0, 4.0, 3.0});
    CHECK(s.derivative(0.0) == 6.0);
    CHECK(s.derivative(0.5) == 6.0);
    CHECK(s.derivative(std::nextafter(1.0, 0.0)) == 6.0);
    CHECK(s.derivative(1.0) == 0.0);  // at a knot: the segment ahead
    CHECK(s.derivative(2.0) == 0.0);
    CHECK(s.derivative(3.0) == -2.0);
    CHECK(s.derivative(3.5) == -2.0);  // the last sample: nothing ahead, the last segment
    CHECK_THROWS_AS(s.derivative(3.6), std::out_of_range);
    CHECK_THROWS_AS(s.derivative(-0.1), std::out_of_range);
    CHECK(s(0.25) == -0.5);  // the values are unchanged
    CHECK(SignalWithDerivative{}.derivative(0.0) == 1.0);
}

TEST_CASE("hysteretic law on the kinematic rig: w(t) prescribed, T = eq 6 at (w, dw/dt, N), switches as events",
          "[hysteretic][kinematic_rig]") {
    const HystereticFriction::Params p = distinct_params();  // w_s = 2e-3 rad/s, N_ref = 35 N
    const double v_d = 3.0, v_a = 8.0, om = 2 * pi * 0.835, period = 2 * pi / om;  // w in [-5, 11] rad/s
    const double t_end = 2.4 * period;
    const auto normal = [](double t) { return 35.0 * (1.0 + 0.3 * std::sin(2.1 * t)); };  // N needs no derivative
    const HarmonicSlidingVelocity w_of(v_d, v_a, om);
    const KinematicRig rig(HystereticFriction(p), w_of, normal);
    static_assert(std::is_same_v<std::decay_t<decltype(rig)>,
                                 KinematicRig<HystereticFriction, HarmonicSlidingVelocity, std::decay_t<decltype(normal)>>>);
    const std::vector<AnalyticSwitch> switches = harmonic_switches(v_d, v_a, om, p.stick_speed, t_end);
    REQUIRE(switches.size() == 14);  // 6 per period (2 x dw/dt = 0, 2 band entries, 2 band exits), 2 in the 0.4

    const Method method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO("method " << method_name(method));
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    // a grid off the switches, plus points just either side of each switch (in the band T = a w changes by
    // ~7e4 N m/s: 1e-10 s apart keeps that below 1e-5 N m)
    const double delta = 1e-10;
    for (double t = 0.0123; t < t_end; t += 0.00731) {
        bool near = false;
        for (const AnalyticSwitch& s : switches) near = near || std::abs(t - s.t) < 1e-6;
        if (!near) o.output_times.push_back(t);
    }
    for (const AnalyticSwitch& s : switches) {
        o.output_times.push_back(s.t - delta);
        o.output_times.push_back(s.t + delta);
    }
    o.output_times.push_back(t_end);
    std::sort(o.output_times.begin(), o.output_times.end());
    const Result r = simulate(rig, t_end, o);
    REQUIRE(r.completed);
    REQUIRE(r.rows() == o.output_times.size());
    REQUIRE(r.state_names == std::vector<std::string>{"friction_impulse", "friction_work"});

    SECTION("(a) the recorded torque is eq 6 by hand at each output time, in eq 6's case") {
        double worst = 0.0;
        int cases_seen[5] = {0, 0, 0, 0, 0};
        for (std::size_t i = 0; i < r.rows(); ++i) {
            const double t = r.t[i], w = w_of(t), al = v_a * om * std::sin(om * t);
            const double expected = eq6_by_hand(p, w, al, normal(t));
            INFO("t = " << t << ", w = " << w << ", dw/dt = " << al);
            CHECK(r.mode[i] == eq6_case(p, w, al));
            CHECK(rel_diff(r.friction_force[i], expected) < 1e-12);
            worst = std::max(worst, rel_diff(r.friction_force[i], expected));
            ++cases_seen[r.mode[i] + 2];
        }
        for (int c : cases_seen) CHECK(c > 0);  // every case of eq 6 was visited
        CHECK(worst < 1e-12);  // measured 4.6e-16 on both methods (the same formula in another order)
    }
    SECTION("(b) every switch is an event at its analytic time, with the jump of eq 6 there") {
        REQUIRE(r.events.size() == switches.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < switches.size(); ++i) {
            const Event& e = r.events[i];
            const AnalyticSwitch& s = switches[i];
            INFO("event " << i << " at t = " << e.time << " (analytic " << s.t << "): " << e.mode_before_name << " -> "
                          << e.mode_after_name << " by " << e.name);
            CHECK(std::abs(e.time - s.t) < 1e-10);
            worst = std::max(worst, std::abs(e.time - s.t));
            CHECK(e.mode_before == s.before);
            CHECK(e.mode_after == s.after);
            CHECK(std::string(e.name) == s.guard);
            // the recorded torque jumps there by eq 6's jump: its two cases at the switch point
            const std::size_t before = std::lower_bound(r.t.begin(), r.t.end(), s.t - delta) - r.t.begin();
            REQUIRE(r.t[before + 1] == s.t + delta);
            CHECK(r.mode[before] == s.before);
            CHECK(r.mode[before + 1] == s.after);
            const double t_s = s.t, w = w_of(t_s), al = v_a * om * std::sin(om * t_s), n = normal(t_s);
            const double jump = eq6_in_mode(p, s.after, w, al, n) - eq6_in_mode(p, s.before, w, al, n);
            CHECK(r.friction_force[before + 1] - r.friction_force[before] == Approx(jump).margin(1e-4));
            if (std::string(s.guard) == "acceleration_zero")  // dw/dt = 0: the levels' gap N0 - P0, signed, scaled
                CHECK(std::abs(jump) == Approx(n / 35.0 * std::abs(p.decelerating.level(std::abs(w)) -
                                                                    p.accelerating.level(std::abs(w))))
                                            .epsilon(1e-12));
        }
        CHECK(std::string(r.events[0].mode_before_name) == "decelerating_negative");
        CHECK(std::string(r.events[0].mode_after_name) == "stick");
        CHECK(std::string(rig.mode_name(1)) == "accelerating_positive");
        CHECK(std::string(rig.mode_name(-1)) == "accelerating_negative");
        CHECK(std::string(rig.mode_name(2)) == "decelerating_positive");
        CHECK(worst < 1e-10);  // measured 5.4e-14 s (Dormand-Prince), 5.3e-14 s (CVODE)
    }
    SECTION("(c) friction_work = int T w dt and friction_impulse = int T dt (trapezoid between the switches)") {
        std::vector<double> edges{0.0};
        for (const AnalyticSwitch& s : switches) edges.push_back(s.t);
        edges.push_back(t_end);
        double work = 0.0, impulse = 0.0;
        for (std::size_t j = 0; j + 1 < edges.size(); ++j) {
            const double a = edges[j], b = edges[j + 1], mid = 0.5 * (a + b);
            const int mode = eq6_case(p, w_of(mid), w_of.derivative(mid));  // one case on the whole piece
            const auto torque = [&](double t) { return eq6_in_mode(p, mode, w_of(t), w_of.derivative(t), normal(t)); };
            work += trapezoid([&](double t) { return torque(t) * w_of(t); }, a, b, 4000);
            impulse += trapezoid(torque, a, b, 4000);
        }
        const std::size_t last = r.rows() - 1;
        REQUIRE(r.t[last] == t_end);
        const double work_error = rel_diff(r.state(last, r.column("friction_work")), work);
        const double impulse_error = rel_diff(r.state(last, r.column("friction_impulse")), impulse);
        CHECK(work > 0.0);  // friction dissipates
        // rtol 1e-10: measured 3.0e-10 / 1.4e-10 (Dormand-Prince), 3.5e-9 / 2.2e-9 (CVODE BDF); work 13.31 N m
        INFO("friction_work " << work << " N m, relative error " << work_error << "; friction_impulse " << impulse
                              << " N m s, relative error " << impulse_error);
        CHECK(work_error < 1e-8);
        CHECK(impulse_error < 1e-8);
    }
}

TEST_CASE("hysteretic law on the kinematic rig: sampled w(t), dw/dt the slope ahead, switches at the knots",
          "[hysteretic][kinematic_rig]") {
    const HystereticFriction::Params p = distinct_params();
    const double w_s = p.stick_speed;
    // rises through the band, holds at 4 rad/s (dw/dt = 0: decelerating by eq 6), falls back through it
    const SampledSignal w_of({0.0, 1.0, 2.0, 3.0, 4.0}, {-2.0, 4.0, 4.0, 1.0, -1.0}, "w");
    const KinematicRig rig(HystereticFriction(p), w_of, ConstantSignal(52.5));
    const Method method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO("method " << method_name(method));
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    for (int i = 0; i <= 400; ++i) o.output_times.push_back(0.0013 + i * 0.00996);
    o.output_times.push_back(4.0);
    const Result r = simulate(rig, 4.0, o);
    REQUIRE(r.completed);
    REQUIRE(r.t.back() == 4.0);
    for (std::size_t i = 0; i < r.rows(); ++i) {
        const double t = r.t[i];
        INFO("t = " << t);
        CHECK(r.mode[i] == eq6_case(p, w_of(t), w_of.derivative(t)));
        CHECK(rel_diff(r.friction_force[i], eq6_by_hand(p, w_of(t), w_of.derivative(t), 52.5)) < 1e-12);
    }
    // (2 - w_s) / 6: into the band; (2 + w_s) / 6: out, accelerating; 1: the slope turns 0, decelerating;
    // 3 + (1 - w_s) / 2: into the band; 3 + (1 + w_s) / 2: out, accelerating on the negative side
    const std::vector<std::pair<double, std::string>> expected{{(2 - w_s) / 6, "decelerating_negative->stick"},
                                                               {(2 + w_s) / 6, "stick->accelerating_positive"},
                                                               {1.0, "accelerating_positive->decelerating_positive"},
                                                               {3 + (1 - w_s) / 2, "decelerating_positive->stick"},
                                                               {3 + (1 + w_s) / 2, "stick->accelerating_negative"}};
    REQUIRE(r.events.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const Event& e = r.events[i];
        INFO("event " << i << " at " << e.time);
        CHECK(std::abs(e.time - expected[i].first) < 1e-10);
        CHECK(std::string(e.mode_before_name) + "->" + e.mode_after_name == expected[i].second);
    }
    // the torque at the knot t = 2 jumps through its acceleration terms (dw/dt 0 -> -3) without a branch change:
    // the integrator crosses it by error control; the work is still int T w dt to the tolerance
    std::vector<double> edges{0.0, 2.0, 3.0, 4.0};  // the knots where dw/dt jumps without a switch, and the ends
    for (const auto& e : expected) edges.push_back(e.first);
    std::sort(edges.begin(), edges.end());
    double work = 0.0;
    for (std::size_t j = 0; j + 1 < edges.size(); ++j) {
        const double a = edges[j], b = edges[j + 1], mid = 0.5 * (a + b);
        const int mode = eq6_case(p, w_of(mid), w_of.derivative(mid));
        work += trapezoid([&](double t) { return eq6_in_mode(p, mode, w_of(t), w_of.derivative(mid), 52.5) * w_of(t); },
                          a, b, 2000);
    }
    const double work_error = rel_diff(r.state(r.rows() - 1, r.column("friction_work")), work);
    CHECK(work_error < 1e-8);  // measured 9.9e-10 (Dormand-Prince, 171 steps), 1.8e-9 (CVODE BDF, 385 steps)
}

TEST_CASE("paper001_fig7_friction on the kinematic rig at Fig. 7's speeds: Fig. 5a's loop, accelerating below "
          "decelerating",
          "[hysteretic][kinematic_rig]") {
    const HystereticFriction law = paper001_fig7_friction();
    const HystereticFriction::Params& p = law.params();
    // 0 ... 14 rad/s at 0.835 Hz: Fig. 7's peak disc speed and stick-slip frequency, the disc speed never negative
    const double v_d = 7.0, v_a = 7.0, om = 2 * pi * 0.835, period = 2 * pi / om;
    const KinematicRig rig(law, HarmonicSlidingVelocity(v_d, v_a, om), ConstantSignal(35.0));
    const std::vector<double> speeds{0.25, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 13.5, 13.9};
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    for (double w : speeds) {  // in the second cycle: rising at t_up, falling at period - t_up
        const double t_up = std::acos((v_d - w) / v_a) / om;
        o.output_times.push_back(period + t_up);
        o.output_times.push_back(2 * period - t_up);
    }
    std::sort(o.output_times.begin(), o.output_times.end());
    const Result r = simulate(rig, 2 * period, o);
    REQUIRE(r.completed);
    double smallest_gap = kInf, largest_gap = 0.0;
    for (double w : speeds) {
        const double t_up = std::acos((v_d - w) / v_a) / om;
        const auto row = [&](double t) {
            return static_cast<std::size_t>(std::find(r.t.begin(), r.t.end(), t) - r.t.begin());
        };
        const std::size_t up = row(period + t_up), down = row(2 * period - t_up);
        REQUIRE(up < r.rows());
        REQUIRE(down < r.rows());
        const double gap = r.friction_force[down] - r.friction_force[up];
        // at the same speed, |dw/dt| = a on both: N0 - P0 + (n01 + p01 ... ) terms: 0.03 + 2 (0.00315) a - p02 a^2
        const double a = om * std::sqrt(v_a * v_a - (w - v_d) * (w - v_d));
        INFO("w = " << w << " rad/s, |dw/dt| = " << a << ": accelerating " << r.friction_force[up]
                    << " N m, decelerating " << r.friction_force[down] << " N m");
        CHECK(std::string(rig.mode_name(r.mode[up])) == "accelerating_positive");
        CHECK(std::string(rig.mode_name(r.mode[down])) == "decelerating_positive");
        CHECK(gap > 0.0);  // Fig. 5a: the accelerating branch runs below the decelerating one
        CHECK(gap >= 0.03 - 1e-12);
        CHECK(gap == Approx(0.03 - 2 * p.accelerating.c01 * a - p.accelerating.c02 * a * a).epsilon(1e-10));
        smallest_gap = std::min(smallest_gap, gap);
        largest_gap = std::max(largest_gap, gap);
    }
    CHECK(smallest_gap > 0.068);  // measured 0.0682 N m at 13.9 rad/s ... 0.2344 N m at mid-range speeds
    CHECK(largest_gap < 0.235);
    // the loop closes through the band at w = 0 (T = a w, at most the break-away a w_s = 1.378 N m) and through the
    // jump at the top, 14 rad/s (dw/dt = 0: P0 -> N0, +0.03 N m); per cycle, 4 switches
    int tops = 0, band = 0;
    for (const Event& e : r.events) {
        if (std::string(e.name) == "acceleration_zero") {
            ++tops;
            CHECK(std::abs(rig.relative_velocity(e.time) - 14.0) < 1e-9);
            CHECK(rig.friction_force(e.time, nullptr, e.mode_after) - rig.friction_force(e.time, nullptr, e.mode_before) ==
                  Approx(p.decelerating.level(14.0) - p.accelerating.level(14.0)).epsilon(1e-6));
        } else {
            ++band;
        }
    }
    CHECK(tops == 2);
    CHECK(band == 4);  // the run starts in the band (w(0) = 0): out, in and out at T, in at 2T
}
