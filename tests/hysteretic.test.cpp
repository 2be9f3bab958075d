// The hysteretic velocity-acceleration friction torque of paper 001 (eq 6, friction/hysteretic.hpp): the law
// by hand on each branch and in the stick band, its odd extension to w < 0, the normal-force scaling, the branch
// equation J al + T(w, al) = S solved as a quadratic (root continuous with the linear case, stable for small A),
// and the rejection of bad parameters.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

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
