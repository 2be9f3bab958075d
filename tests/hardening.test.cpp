// Issue 11 on the C++ engine: a prescribed relative velocity resting at exactly zero (every law, every
// integrator), the run's budgets (interrupt callback, wall-clock timeout, result rows), non-finite results,
// tolerances outside the range where error estimates mean anything, and runs a few ulps long.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <fstream>
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

TEST_CASE("results are capped by bytes: a run stops whole-rowed at max_output_bytes, a run too big is refused at once",
          "[hardening][memory]") {
    constexpr std::size_t row = 3 * sizeof(double) + sizeof(int);  // Ramp's row: t, x, friction force, mode
    SolverOptions o = with_method(Method::dormand_prince);
    o.max_step = 1e-3;
    o.max_output_bytes = 100 * row + row / 2;  // room for 100 whole rows, not 101
    try {
        (void)simulate(Ramp{}, 1.0, o);  // every step recorded: 1000 rows
        FAIL("no BudgetExceeded");
    } catch (const BudgetExceeded& e) {
        CHECK(e.budget() == "max_output_bytes");
        REQUIRE(e.partial());
        const Result& partial = *e.partial();
        CHECK(partial.rows() == 100);
        CHECK(partial.states.size() == 100);  // every column the same length
        CHECK(partial.friction_force.size() == 100);
        CHECK(partial.mode.size() == 100);
        CHECK(e.time_reached() == partial.t.back());
        CHECK(std::string(e.what()).find("max_output_bytes = " + std::to_string(o.max_output_bytes)) !=
              std::string::npos);
    }

    // rows known before the run (output_times): refused before a step is taken, naming the option and the size
    SolverOptions known = with_method(Method::dormand_prince);
    for (int k = 1; k <= 1000; ++k) known.output_times.push_back(1e-3 * k);
    known.max_output_bytes = 999 * row;
    CHECK(rejected_parameter([&] { (void)simulate(Ramp{}, 1.0, known); }) == "max_output_bytes");
    CHECK(rejection_message([&] { (void)simulate(Ramp{}, 1.0, known); }).find("at least 1000 rows") !=
          std::string::npos);
    known.max_output_bytes = 1000 * row;  // exactly enough
    CHECK(simulate(Ramp{}, 1.0, known).rows() == 1000);

    // events count too: a RowRecorder fed directly, its bytes the rows' plus each event's
    Event e;
    e.name = "relative_velocity";
    e.state_before = {1.0, 2.0};
    e.state_after = {1.0, 0.0};
    const std::size_t event = sizeof(Event) + 4 * sizeof(double) + e.name.size();
    SolverOptions budget;
    budget.max_output_bytes = 2 * row + event;
    RowRecorder recorder(std::array<const char*, 1>{"x"}, 0, budget);
    const double x = 0.0;
    recorder.row(0.0, &x, 0.0, 0);
    recorder.event(e, 0.5);
    recorder.row(1.0, &x, 0.0, 0);
    CHECK_THROWS_AS(recorder.row(2.0, &x, 0.0, 0), BudgetExceeded);
    CHECK_THROWS_AS(recorder.event(e, 2.0), BudgetExceeded);
    CHECK(recorder.result().rows() == 2);
    CHECK(recorder.result().events.size() == 1);
}

TEST_CASE("the default byte budget is an eighth of the memory this process may use", "[hardening][memory]") {
    const std::size_t budget = SolverOptions{}.output_byte_budget();
#if defined(__linux__)
    // an independent reading of the machine's memory: /proc/meminfo's MemTotal [kB]
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    double kib = 0.0;
    while (meminfo >> key) {
        if (key == "MemTotal:") {
            meminfo >> kib;
            break;
        }
        meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    REQUIRE(kib > 0.0);
    double usable = kib * 1024.0;
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream cgroup(path);
        double limit = 0.0;
        if (cgroup >> limit && limit > 0.0) {  // a container's limit, where there is one ("max" reads as none)
            usable = std::min(usable, limit);
            break;
        }
    }
    CHECK(static_cast<double>(budget) == Approx(usable / 8.0).epsilon(0.02));
#else
    CHECK(budget > 0);
#endif
    SolverOptions given;
    given.max_output_bytes = 12345;
    CHECK(given.output_byte_budget() == 12345);
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
