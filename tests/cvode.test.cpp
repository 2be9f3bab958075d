// Cvode integrator (sundials/cvode.hpp) on toy hybrid systems: accuracy of the dense output, root finding with
// directions, exceptions and NaN from the right-hand side, max_steps, counters across restarts.
#include "frictionsim/sundials/cvode.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "catch.hpp"
#include "support.hpp"

using frictionsim::Cvode;
using frictionsim::Method;
using frictionsim::SimulationError;
using frictionsim::SolverOptions;
using frictionsim::test::options_for;

namespace {

/// x'' = -x as x0' = x1, x1' = -x0; no guards.
struct Oscillator {
    static constexpr std::size_t state_size = 2;
    static constexpr std::size_t guard_count = 0;
    void rhs(double, const double* x, int, double* dxdt) const {
        dxdt[0] = x[1];
        dxdt[1] = -x[0];
    }
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return ""; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    const char* mode_name(int) const { return "free"; }
    std::array<const char*, 2> state_names() const { return {"x", "v"}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::array<double, 2> initial_state() const { return {1.0, 0.0}; }
};

/// The same with its analytic Jacobian, counting the calls.
struct OscillatorWithJacobian : Oscillator {
    mutable long jacobian_calls = 0;
    void jacobian(double, const double*, int, double* J) const {  // column-major
        ++jacobian_calls;
        J[1] = -1.0;  // column 0 (d/dx0) row 1; CVODE zeroes J before the call
        J[2] = 1.0;   // column 1 (d/dx1) row 0
    }
};

static_assert(!frictionsim::has_dense_jacobian_v<Oscillator>);
static_assert(frictionsim::has_dense_jacobian_v<OscillatorWithJacobian>);

/// x' = +1 in mode 0, -1 in mode 1. Guard 0: x - 0.5 (rising only); guard 1: x - 0.25 (falling only).
struct TwoGuardRamp {
    static constexpr std::size_t state_size = 1;
    static constexpr std::size_t guard_count = 2;
    void rhs(double, const double*, int mode, double* dxdt) const { dxdt[0] = mode == 0 ? 1.0 : -1.0; }
    void guards(double, const double* x, int, double* g) const {
        g[0] = x[0] - 0.5;
        g[1] = x[0] - 0.25;
    }
    int guard_direction(std::size_t i, int) const { return i == 0 ? +1 : -1; }
    const char* guard_name(std::size_t i, int) const { return i == 0 ? "half" : "quarter"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int, const int*) const { return 1; }
    const char* mode_name(int mode) const { return mode == 0 ? "up" : "down"; }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::array<double, 1> initial_state() const { return {0.0}; }
};

/// x' = -x, but the right-hand side (or a guard) misbehaves after `t_bad`.
enum class Fault { rhs_throws, rhs_nan, guard_throws };
struct Faulty {
    static constexpr std::size_t state_size = 1;
    static constexpr std::size_t guard_count = 1;
    Fault fault;
    double t_bad;
    void rhs(double t, const double* x, int, double* dxdt) const {
        if (t > t_bad && fault == Fault::rhs_throws) throw std::runtime_error("boom");
        dxdt[0] = (t > t_bad && fault == Fault::rhs_nan) ? std::nan("") : -x[0];
    }
    void guards(double t, const double* x, int, double* g) const {
        if (t > t_bad && fault == Fault::guard_throws) throw std::runtime_error("guard boom");
        g[0] = x[0] + 1.0;  // never crosses
    }
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return "never"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    const char* mode_name(int) const { return "only"; }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::array<double, 1> initial_state() const { return {1.0}; }
};

/// Integrates to t_end; returns the largest |x0 - cos t| over output times every 0.05, via interpolate().
template <class Integrator>
double oscillator_error(Integrator& integrator, double t_end) {
    double worst = 0.0;
    double t_out = 0.05;
    std::array<double, 2> x{};
    while (integrator.time() < t_end) {
        const frictionsim::StepResult r = integrator.step(t_end);
        REQUIRE(r.t <= t_end);
        REQUIRE_FALSE(r.root);
        REQUIRE(integrator.previous_time() < integrator.time());
        for (; t_out <= integrator.time() + 1e-15 && t_out <= t_end; t_out += 0.05) {
            integrator.interpolate(t_out, x.data());
            worst = std::max(worst, std::abs(x[0] - std::cos(t_out)));
        }
    }
    return worst;
}

/// What step() threw: a copy to inspect, and the exception itself (its dynamic type carries the nesting).
struct Failure {
    SimulationError error;
    std::exception_ptr thrown;
};

/// Steps until a SimulationError escapes; fails the test (instead of hanging) after a million steps.
template <class Integrator>
Failure run_until_failure(Integrator& integrator, double t_end) {
    for (long i = 0; i < 1'000'000 && integrator.time() < t_end; ++i) {
        try {
            integrator.step(t_end);
        } catch (const SimulationError& e) {
            return {e, std::current_exception()};
        }
    }
    FAIL("no SimulationError before t = " << integrator.time());
    throw std::logic_error("unreachable");
}

/// what() of the exception nested in `thrown` (std::throw_with_nested), or "" when there is none.
std::string nested_what(const std::exception_ptr& thrown) {
    try {
        std::rethrow_exception(thrown);
    } catch (const std::nested_exception& nested) {
        try {
            nested.rethrow_nested();
        } catch (const std::exception& original) {
            return original.what();
        }
    } catch (...) {
    }
    return "";
}

}  // namespace

TEST_CASE("Cvode integrates the harmonic oscillator to 1e-7 with dense output", "[cvode]") {
    for (Method method : {Method::cvode_bdf, Method::cvode_adams}) {
        INFO(frictionsim::method_name(method));
        const Oscillator system;
        Cvode<Oscillator> integrator(system, options_for(method));
        const auto x0 = system.initial_state();
        integrator.restart(0.0, x0.data(), 0);
        CHECK(oscillator_error(integrator, 10.0) < 1e-7);
        CHECK(integrator.time() == 10.0);  // the last step stops exactly at t_stop
        CHECK(std::abs(integrator.state()[0] - std::cos(10.0)) < 1e-7);

        const frictionsim::SolverStats s = integrator.stats();
        CHECK(s.steps > 10);
        CHECK(s.rhs_evaluations > s.steps);
        CHECK(s.restarts == 1);  // every restart() counts, the first included
        CHECK(s.guard_evaluations == 0);
        if (method == Method::cvode_bdf) CHECK(s.jacobian_evaluations > 0);
        if (method == Method::cvode_adams) CHECK(s.jacobian_evaluations == 0);
    }
}

TEST_CASE("Cvode uses an analytic Jacobian when the system has one", "[cvode]") {
    const OscillatorWithJacobian system;
    Cvode<OscillatorWithJacobian> integrator(system, options_for(Method::cvode_bdf));
    const auto x0 = system.initial_state();
    integrator.restart(0.0, x0.data(), 0);
    CHECK(oscillator_error(integrator, 6.0) < 1e-7);
    CHECK(system.jacobian_calls > 0);
    CHECK(integrator.stats().jacobian_evaluations == system.jacobian_calls);
}

TEST_CASE("Cvode honours atol_per_state, max_step and initial_step", "[cvode]") {
    SolverOptions o = options_for(Method::cvode_bdf);
    o.atol_per_state = {1e-12, 1e-12};
    o.max_step = 0.01;
    o.initial_step = 1e-4;
    const Oscillator system;
    Cvode<Oscillator> integrator(system, o);
    const auto x0 = system.initial_state();
    integrator.restart(0.0, x0.data(), 0);
    integrator.step(1.0);
    CHECK(integrator.time() <= 1e-4 * (1 + 1e-12));  // the first step is at most initial_step
    while (integrator.time() < 1.0) {
        integrator.step(1.0);
        CHECK(integrator.time() - integrator.previous_time() <= 0.01 * (1 + 1e-12));
    }
    CHECK(integrator.stats().steps >= 100);
}

TEST_CASE("Cvode restarts exactly and keeps counting across restarts", "[cvode]") {
    const Oscillator system;
    Cvode<Oscillator> integrator(system, options_for(Method::cvode_bdf));
    const auto x0 = system.initial_state();
    integrator.restart(0.0, x0.data(), 0);
    CHECK(oscillator_error(integrator, 3.0) < 1e-7);
    const frictionsim::SolverStats before = integrator.stats();

    const std::array<double, 2> x{integrator.state()[0], integrator.state()[1]};
    integrator.restart(3.0, x.data(), 0);
    integrator.restart(3.0, x.data(), 0);  // twice in a row: counters must not be banked twice
    CHECK(integrator.time() == 3.0);
    CHECK(integrator.previous_time() == 3.0);
    CHECK(integrator.stats().steps == before.steps);
    CHECK(integrator.stats().rhs_evaluations == before.rhs_evaluations);
    CHECK(integrator.stats().jacobian_evaluations == before.jacobian_evaluations);

    double worst = 0.0;
    std::array<double, 2> y{};
    while (integrator.time() < 6.0) {
        integrator.step(6.0);
        integrator.interpolate(integrator.time(), y.data());
        worst = std::max(worst, std::abs(y[0] - std::cos(integrator.time())));
    }
    CHECK(worst < 1e-7);
    const frictionsim::SolverStats after = integrator.stats();
    CHECK(after.restarts == 3);
    CHECK(after.steps > before.steps);
    CHECK(after.rhs_evaluations > before.rhs_evaluations);
    CHECK(after.jacobian_evaluations > before.jacobian_evaluations);
}

TEST_CASE("Cvode is movable: CVODE keeps reaching the callbacks", "[cvode]") {
    const Oscillator system;
    Cvode<Oscillator> first(system, options_for(Method::cvode_adams));
    const auto x0 = system.initial_state();
    first.restart(0.0, x0.data(), 0);
    first.step(1.0);
    Cvode<Oscillator> second(std::move(first));
    CHECK(oscillator_error(second, 2.0) < 1e-7);
}

TEST_CASE("Cvode finds a guard root in its direction and never steps past t_stop", "[cvode]") {
    for (Method method : {Method::cvode_bdf, Method::cvode_adams}) {
        INFO(frictionsim::method_name(method));
        const TwoGuardRamp system;
        Cvode<TwoGuardRamp> integrator(system, options_for(method, 1e-8, 1e-10));
        const double x0 = 0.0;
        integrator.restart(0.0, &x0, 0);

        // Guard 1 rises through zero at t = 0.25 but only falling crossings count: not reported.
        while (integrator.time() < 0.3) {
            const frictionsim::StepResult r = integrator.step(0.3);
            REQUIRE_FALSE(r.root);
            REQUIRE(r.t <= 0.3);
        }
        CHECK(integrator.time() == 0.3);

        frictionsim::StepResult r;
        do {
            r = integrator.step(1.0);
        } while (!r.root && integrator.time() < 1.0);
        REQUIRE(r.root);
        CHECK(r.t == Approx(0.5).margin(1e-10));
        CHECK(std::abs(integrator.state()[0] - 0.5) < 1e-10);
        CHECK(integrator.roots()[0] == +1);
        CHECK(integrator.roots()[1] == 0);
        double x = 0.0;
        integrator.interpolate(0.5 * (integrator.previous_time() + integrator.time()), &x);
        CHECK(x == Approx(0.5 * (integrator.previous_time() + integrator.time())).margin(1e-10));
        CHECK(integrator.stats().guard_evaluations > 0);

        // Switch to x' = -1 on the surface: guard 0 starts at zero (masked), guard 1 falls through zero at 0.75.
        const double x_root = integrator.state()[0];
        integrator.restart(r.t, &x_root, system.switch_mode(r.t, nullptr, 0, integrator.roots()));
        CHECK(integrator.roots()[0] == 0);
        do {
            r = integrator.step(2.0);
        } while (!r.root && integrator.time() < 2.0);
        REQUIRE(r.root);
        CHECK(r.t == Approx(0.75).margin(1e-10));
        CHECK(integrator.roots()[0] == 0);
        CHECK(integrator.roots()[1] == -1);
        CHECK(integrator.stats().restarts == 2);
    }
}

TEST_CASE("Cvode turns an exception in the right-hand side into a SimulationError", "[cvode]") {
    for (Method method : {Method::cvode_bdf, Method::cvode_adams}) {
        INFO(frictionsim::method_name(method));
        const Faulty system{Fault::rhs_throws, 0.5};
        SolverOptions o = options_for(method, 1e-8, 1e-10);
        o.max_step = 0.05;
        Cvode<Faulty> integrator(system, o);
        const double x0 = 1.0;
        integrator.restart(0.0, &x0, 0);
        const Failure failure = run_until_failure(integrator, 2.0);
        const SimulationError& e = failure.error;
        const std::string what = e.what();
        INFO(what);
        CHECK(e.time_reached() >= 0.4);
        CHECK(e.time_reached() <= 0.5 + 1e-9);
        CHECK(what.find("boom") != std::string::npos);
        CHECK(what.find("CV_") != std::string::npos);  // CVODE's flag name
        CHECK(nested_what(failure.thrown) == "boom");  // the system's own exception stays reachable
        // The integrator stands at the last valid step and can be restarted.
        CHECK(integrator.time() == e.time_reached());
        CHECK(integrator.state()[0] == Approx(std::exp(-e.time_reached())).epsilon(1e-6));
        integrator.restart(0.0, &x0, 0);
        while (integrator.time() < 0.4) integrator.step(0.4);
        CHECK(integrator.state()[0] == Approx(std::exp(-0.4)).epsilon(1e-6));
    }
}

TEST_CASE("Cvode stops with a SimulationError, not a hang, when the right-hand side returns NaN", "[cvode]") {
    for (Method method : {Method::cvode_bdf, Method::cvode_adams}) {
        INFO(frictionsim::method_name(method));
        const Faulty system{Fault::rhs_nan, 0.3};
        Cvode<Faulty> integrator(system, options_for(method, 1e-8, 1e-10));
        const double x0 = 1.0;
        integrator.restart(0.0, &x0, 0);
        const SimulationError e = run_until_failure(integrator, 2.0).error;
        const std::string what = e.what();
        INFO(what);
        CHECK(e.time_reached() <= 0.3 + 1e-12);
        CHECK(what.find("non-finite") != std::string::npos);
    }
}

TEST_CASE("Cvode reports an exception thrown by a guard", "[cvode]") {
    const Faulty system{Fault::guard_throws, 0.2};
    Cvode<Faulty> integrator(system, options_for(Method::cvode_bdf, 1e-8, 1e-10));
    const double x0 = 1.0;
    integrator.restart(0.0, &x0, 0);
    const SimulationError e = run_until_failure(integrator, 2.0).error;
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("guard boom") != std::string::npos);
    CHECK(what.find("CV_RTFUNC_FAIL") != std::string::npos);
    CHECK(e.time_reached() <= 0.2 + 1e-12);
}

TEST_CASE("Cvode enforces max_steps over the whole run", "[cvode]") {
    SolverOptions o = options_for(Method::cvode_adams);
    o.max_steps = 25;
    const Oscillator system;
    Cvode<Oscillator> integrator(system, o);
    const auto x0 = system.initial_state();
    integrator.restart(0.0, x0.data(), 0);
    for (int i = 0; i < 10; ++i) integrator.step(100.0);
    const std::array<double, 2> x{integrator.state()[0], integrator.state()[1]};
    integrator.restart(integrator.time(), x.data(), 0);  // a restart does not reset the budget
    const SimulationError e = run_until_failure(integrator, 100.0).error;
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("max_steps") != std::string::npos);
    CHECK(integrator.stats().steps == 25);
    CHECK(e.time_reached() == integrator.time());
    CHECK(e.time_reached() > 0.0);
}

TEST_CASE("Cvode rejects bad options and misuse", "[cvode]") {
    const Oscillator system;
    CHECK_THROWS_AS(Cvode<Oscillator>(system, options_for(Method::dormand_prince)),
                    frictionsim::InvalidParameter);
    CHECK_THROWS_AS(Cvode<Oscillator>(system, SolverOptions{}), frictionsim::InvalidParameter);  // not resolved
    SolverOptions o = options_for(Method::cvode_bdf);
    o.atol_per_state = {1e-10};  // two states
    CHECK_THROWS_AS(Cvode<Oscillator>(system, o), frictionsim::InvalidParameter);

    Cvode<Oscillator> integrator(system, options_for(Method::cvode_bdf));
    CHECK_THROWS_AS(integrator.step(1.0), std::logic_error);  // no restart yet
    const auto x0 = system.initial_state();
    integrator.restart(1.0, x0.data(), 0);
    CHECK_THROWS_AS(integrator.step(1.0), std::invalid_argument);
    integrator.step(2.0);
    std::array<double, 2> x{};
    CHECK_THROWS_AS(integrator.interpolate(integrator.time() + 1.0, x.data()), std::out_of_range);
}
