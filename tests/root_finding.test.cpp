// The small numerical pieces the integrators share: the Illinois false-position bracket (detail/illinois.hpp)
// against known roots and plain regula falsi's stall, and the step control of the one-step methods
// (solve/step_control.hpp) against Hairer's starting-step rule worked by hand.
#include <cmath>
#include <cstddef>
#include <limits>

#include <frictionsim/detail/illinois.hpp>
#include <frictionsim/solve/step_control.hpp>

#include "catch.hpp"

using namespace frictionsim;

namespace {

/// Iterations Illinois needs to shrink [a, b] around the root of f below tol (f(a) > 0 > f(b)); the root in `root`.
template <class F>
int illinois_iterations(F f, double a, double b, double tol, double& root) {
    detail::IllinoisBracket r{a, f(a), b, f(b)};
    int n = 0;
    while (r.b - r.a > tol && n < 1000) {
        const double x = r.next();
        const double fx = f(x);
        ++n;
        if (fx == 0.0) {
            root = x;
            return n;
        }
        r.move(x, fx, (fx > 0.0) == (r.gb > 0.0));
    }
    root = 0.5 * (r.a + r.b);
    return n;
}

}  // namespace

TEST_CASE("Illinois: the Dottie number and a flat function, superlinear where regula falsi stalls", "[root]") {
    double root = 0.0;
    // cos x = x at 0.739085133215160641655 (the Dottie number); bisection needs 47 halvings for 1e-14
    const int n = illinois_iterations([](double x) { return std::cos(x) - x; }, 0.0, 1.0, 1e-14, root);
    CHECK(root == Approx(0.739085133215160641655).margin(1e-13));
    CHECK(n <= 12);
    // x^10 = 0.5 on [0, 1]: plain regula falsi keeps the end at 1 and creeps; the halved stale end does not
    const int m = illinois_iterations([](double x) { return 0.5 - std::pow(x, 10); }, 0.0, 1.0, 1e-12, root);
    CHECK(root == Approx(std::pow(0.5, 0.1)).margin(1e-11));
    CHECK(m <= 40);
    int plain = 0;
    for (double a = 0.0, b = 1.0, fa = 0.5, fb = -0.5; b - a > 1e-12 && plain < 1000; ++plain) {
        const double x = b - fb * (b - a) / (fb - fa), fx = 0.5 - std::pow(x, 10);
        (fx > 0.0 ? a : b) = x;
        (fx > 0.0 ? fa : fb) = fx;
    }
    CHECK(plain == 1000);  // regula falsi never closes the bracket: the far end stays put
}

TEST_CASE("Illinois: a point outside the inner bracket falls back to the midpoint", "[root]") {
    const detail::IllinoisBracket r{0.0, 1.0, 1.0, -1e-12};  // the secant lands within 1e-12 of b
    CHECK(r.next() == Approx(1.0 - 1e-12 / (1.0 + 1e-12)));
    CHECK(r.next(0.01) == 0.5);
}

TEST_CASE("step control: error weights, the last step lands on t_stop, Hairer's starting step", "[root]") {
    SolverOptions o;
    o.rtol = 1e-6;
    o.atol = 1e-8;
    CHECK(detail::error_scale(o, 0, -3.0, 2.0) == Approx(1e-8 + 3e-6));
    CHECK(detail::underflow_step(1e6) == 16.0 * std::numeric_limits<double>::epsilon() * 1e6);
    bool last = false;
    CHECK(detail::trial_step(0.3, o, 0.0, 1.0, last) == 0.3);
    CHECK_FALSE(last);
    CHECK(detail::trial_step(0.3, o, 0.8, 1.0, last) == Approx(0.2));
    CHECK(last);  // what is left is shorter than the step: land on t_stop exactly
    CHECK(detail::trial_step(1.0 - 1e-13, o, 0.0, 1.0, last) == 1.0);
    CHECK(last);  // a hair short of t_stop is stretched onto it

    // y' = -y, y(0) = 1, order 4 (Dormand-Prince's estimate), sc = atol + rtol = 1.01e-6:
    //   h0 = 0.01 |y| / |f| = 0.01; f1 = -(1 - h0) = -0.99; |f1 - f0| / sc / h0 = 1e-2 / 1.01e-6 / 1e-2;
    //   der12 = max(that, |f| / sc) = 1 / 1.01e-6; h1 = (0.01 / der12)^(1/5); h = min(100 h0, h1)
    const double y = 1.0, f0 = -1.0;
    double ytmp = 0.0, f1 = 0.0;
    const double h = detail::starting_step(1, 4, o, 0.0, 10.0, &y, &f0, &ytmp, &f1,
                                           [](double, const double* x, double* dx) { dx[0] = -x[0]; });
    const double sc = 1e-8 + 1e-6;
    CHECK(h == Approx(std::pow(0.01 * sc, 0.2)).epsilon(1e-12));
    CHECK(f1 == Approx(-0.99));
}
