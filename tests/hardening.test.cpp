// Issue 11 on the C++ engine: a prescribed relative velocity resting at exactly zero (every law, every
// integrator), the run's budgets (interrupt callback, wall-clock timeout, result rows), non-finite results,
// tolerances outside the range where error estimates mean anything, and runs a few ulps long.
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {

SolverOptions with_method(Method m) {
    SolverOptions o;
    o.method = m;
    return o;
}

/// Forward sliding at 0.1 m/s falling to rest at t = 1, rest until t = 2, then backward sliding.
SampledSignal standstill() { return SampledSignal({0.0, 1.0, 2.0, 3.0}, {0.1, 0.0, 0.0, -0.1}, "relative_velocity"); }

template <class Law>
void check_standstill(const Law& law, Method method) {
    using Rig = KinematicRig<Law, SampledSignal>;
    const Rig rig(law, standstill(), ConstantSignal(90.0));
    SolverOptions o = with_method(method);
    o.output_times = {1.0 - 1e-7, 1.1, 1.5, 1.9, 2.5};  // just before arriving at rest, at rest, sliding back
    const Result r = simulate(rig, 3.0, o);  // ChatteringError at t = 1.9988 before (Stribeck, ElastoPlastic, DP)
    REQUIRE(r.completed);
    const double arriving = r.friction_force[0];
    for (std::size_t k = 1; k <= 3; ++k) {
        INFO("row " << k);
        CHECK(r.friction_force[k] > 0.0);  // Coulomb held -mu N, the wrong sign, before
        CHECK(r.friction_force[k] == Approx(r.friction_force[1]).epsilon(1e-6));
        CHECK(r.friction_force[k] == Approx(arriving).epsilon(1e-4));
        CHECK(r.state(k, Rig::friction_work) == Approx(r.state(1, Rig::friction_work)).epsilon(1e-8));
        if constexpr (Rig::guard_count == 1) CHECK(r.mode[k] == Rig::rest_holding(slip_positive));
    }
    CHECK(r.friction_force[4] < 0.0);
    if constexpr (Rig::guard_count == 1) {
        REQUIRE(r.events.size() == 2);
        // CVODE's root finder stops at any exact zero of v_r on the rest; the force is the same either side
        CHECK(r.events[0].time >= 1.0);
        CHECK(r.events[0].time <= 1.0 + 1e-3);
        CHECK(std::string(r.events[0].mode_after_name) == "stick");
        CHECK(r.events[1].time == Approx(2.0).margin(1e-9));
        CHECK(r.events[1].mode_after == slip_negative);
    }
}

/// x' = 1: a system that runs as long as it is asked to, for the budgets.
struct Ramp {
    static constexpr std::size_t state_size = 1, guard_count = 0;
    double nan_force_after = std::numeric_limits<double>::infinity();  ///< the recorded force turns NaN past it
    void rhs(double, const double*, int, double* dx) const { dx[0] = 1.0; }
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t, int) const { return ""; }
    const char* mode_name(int) const { return "ramp"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    double friction_force(double t, const double* x, int) const {
        return t > nan_force_after ? std::numeric_limits<double>::quiet_NaN() : x[0];
    }
    std::array<double, 1> initial_state() const { return {0.0}; }
};

}  // namespace

TEST_CASE("a prescribed relative velocity at rest holds the force it arrived with, on every law", "[hardening]") {
    const Method method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    SECTION("Coulomb") { check_standstill(Coulomb(0.4), method); }
    SECTION("Stribeck") { check_standstill(Stribeck(Stribeck::Params{0.3, 0.4, 0.01}), method); }
    SECTION("Dahl") { check_standstill(Dahl(0.4, 1e4), method); }
    SECTION("LuGre") { check_standstill(LuGre(LuGre::Params{0.3, 0.4, 0.01, 1e5, 300.0, 0.0}), method); }
    SECTION("ElastoPlastic") {
        check_standstill(ElastoPlastic(ElastoPlastic::Params{{0.3, 0.4, 0.01, 1e5, 300.0, 0.0}, 0.5}), method);
    }
}

TEST_CASE("the interrupt callback stops a run between steps and keeps its results", "[hardening]") {
    const Method method = GENERATE(Method::dormand_prince, Method::cvode_adams);
    INFO(method_name(method));
    std::atomic<int> polls{0};
    SolverOptions o = with_method(method);
    o.max_step = 1e-3;  // many steps
    o.interrupt = [&] { return ++polls >= 3; };
    try {
        (void)simulate(Ramp{}, 1e9, o);
        FAIL("no Interrupted");
    } catch (const Interrupted& e) {
        CHECK(polls == 3);
        REQUIRE(e.partial());
        CHECK_FALSE(e.partial()->completed);
        CHECK(e.time_reached() > 0.0);
        CHECK(e.partial()->t.back() == e.time_reached());
        CHECK(e.partial()->states.back() == Approx(e.time_reached()));  // x = t: the kept rows are the trajectory
    }
}

TEST_CASE("a run past its wall-clock budget stops with BudgetExceeded naming timeout", "[hardening]") {
    SolverOptions o = with_method(Method::dormand_prince);
    o.max_step = 1e-6;
    o.output_times = {1e9};  // nothing recorded: the budget is time, not rows
    o.timeout = 0.05;
    try {
        (void)simulate(Ramp{}, 1e9, o);
        FAIL("no BudgetExceeded");
    } catch (const BudgetExceeded& e) {
        CHECK(e.budget() == "timeout");
        CHECK(std::string(e.what()).find("timeout = 0.05 s") != std::string::npos);
        CHECK(e.time_reached() > 0.0);
    }
}

TEST_CASE("results are capped at max_output_rows, and non-finite rows are never success", "[hardening]") {
    SolverOptions o = with_method(Method::dormand_prince);
    o.max_step = 1e-3;
    o.max_output_rows = 100;
    try {
        (void)simulate(Ramp{}, 1.0, o);  // every step recorded: 1000 rows
        FAIL("no BudgetExceeded");
    } catch (const BudgetExceeded& e) {
        CHECK(e.budget() == "max_output_rows");
        REQUIRE(e.partial());
        CHECK(e.partial()->rows() == 100);
        CHECK(e.time_reached() == e.partial()->t.back());
    }
    CHECK(SolverOptions{}.max_output_rows == 2'000'000);

    Ramp failing;
    failing.nan_force_after = 2.0;
    SolverOptions finite = with_method(Method::dormand_prince);
    finite.output_times = {1.0, 3.0};
    try {
        (void)simulate(failing, 3.0, finite);
        FAIL("a non-finite result was returned");
    } catch (const SimulationError& e) {
        CHECK(std::string(e.what()).find("non-finite") != std::string::npos);
        CHECK(e.partial()->rows() == 1);  // the finite row at t = 1 is kept
    }
}

TEST_CASE("tolerances outside the range where error estimates bound anything are refused", "[hardening]") {
    const auto run = [](SolverOptions o) { (void)simulate(Ramp{}, 1.0, o); };
    for (double rtol : {0.2, 0.5, 0.999}) {
        SolverOptions o;
        o.rtol = rtol;
        CHECK(rejected_parameter([&] { run(o); }) == "rtol");
    }
    for (double atol : {1e-21, 1e-100, 5e-324}) {
        SolverOptions o;
        o.atol = atol;
        CHECK(rejected_parameter([&] { run(o); }) == "atol");
    }
    SolverOptions o;
    o.atol_per_state = {1e-30};
    CHECK(rejected_parameter([&] { run(o); }) == "atol_per_state");
    o = SolverOptions{};
    o.timeout = 0.0;
    CHECK(rejected_parameter([&] { run(o); }) == "timeout");
    o = SolverOptions{};
    o.max_output_rows = 0;
    CHECK(rejected_parameter([&] { run(o); }) == "max_output_rows");

    o = SolverOptions{};
    o.rtol = 0.1;  // accepted, and flagged
    CHECK(simulate(Ramp{}, 1.0, o).warnings.size() == 1);
    o.rtol = 1e-3;
    CHECK(simulate(Ramp{}, 1.0, o).warnings.empty());
}

TEST_CASE("a run a few ulps long returns the trivial result on every integrator", "[hardening]") {
    const Method method = GENERATE(Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams);
    INFO(method_name(method));
    for (double t_end : {std::numeric_limits<double>::denorm_min(), 1e-300, 1e-17}) {
        INFO("t_end " << t_end);
        const Result r = simulate(Ramp{}, t_end, with_method(method));  // "step size underflow" before
        CHECK(r.completed);
        CHECK(r.t.back() == t_end);
        CHECK(r.states.back() == Approx(t_end).margin(1e-300));
    }
}
