// SciPy-style results of the hybrid loop (issue 15, item 2): the user's stop conditions evaluated in C++ (a state
// crossing a level with direction and terminal flags, a switch into a named mode), the state before and after
// each switch on its Event, rows at both sides of a switch, status and message; on every integrator.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {

/// x'' = -x from (1, 0): x = cos t, v = -sin t; no switches.
struct CosineOscillator {
    static constexpr std::size_t state_size = 2, guard_count = 0;
    void rhs(double, const double* x, int, double* dx) const {
        dx[0] = x[1];
        dx[1] = -x[0];
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

/// x' = +1 ("up") until x = 1, where the switch projects x onto 1 exactly and turns it back ("down", x' = -1)
/// until x = 0 ("rest", x' = 0).
struct UpDown {
    static constexpr std::size_t state_size = 1, guard_count = 1;
    void rhs(double, const double*, int mode, double* dx) const { dx[0] = mode == 0 ? 1.0 : mode == 1 ? -1.0 : 0.0; }
    void guards(double, const double* x, int mode, double* g) const { g[0] = mode == 0 ? 1.0 - x[0] : mode == 1 ? x[0] : 1.0; }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t, int mode) const { return mode == 0 ? "top" : "bottom"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double* x, int mode, const int*) const {
        x[0] = mode == 0 ? 1.0 : 0.0;
        return mode + 1;
    }
    const char* mode_name(int mode) const { return mode == 0 ? "up" : mode == 1 ? "down" : "rest"; }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::array<double, 1> initial_state() const { return {0.0}; }
};

/// UpDown sized at run time, as a drill string is.
struct UpDownAtRunTime {
    UpDown fixed;
    std::size_t state_size() const { return 1; }
    std::size_t guard_count() const { return 1; }
    void rhs(double t, const double* x, int mode, double* dx) const { fixed.rhs(t, x, mode, dx); }
    void guards(double t, const double* x, int mode, double* g) const { fixed.guards(t, x, mode, g); }
    int guard_direction(std::size_t i, int mode) const { return fixed.guard_direction(i, mode); }
    const char* guard_name(std::size_t i, int mode) const { return fixed.guard_name(i, mode); }
    int initial_mode(double t, const double* x) const { return fixed.initial_mode(t, x); }
    int switch_mode(double t, double* x, int mode, const int* fired) const { return fixed.switch_mode(t, x, mode, fired); }
    const char* mode_name(int mode) const { return fixed.mode_name(mode); }
    std::vector<const char*> state_names() const { return {"x"}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::vector<double> initial_state() const { return {0.0}; }
};

std::vector<Method> methods() {
    std::vector<Method> m{Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams};
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
    m.push_back(Method::rosenbrock);
#endif
    return m;
}

}  // namespace

TEST_CASE("stop conditions: a terminal level crossing ends the run where the state crosses it", "[stop]") {
    for (Method m : methods()) {
        CAPTURE(method_name(m));
        SolverOptions o;
        o.method = m;
        o.rtol = 1e-10;
        o.atol = 1e-12;
        // v = -sin t falls through -0.8 at t = asin(0.8) = 0.927 (non-terminal: logged, the run goes on), then
        // x = cos t falls through 0.5 at t = pi / 3 = 1.047 (terminal)
        o.stop_conditions = {StopCondition{"v", -0.8, -1, "", false, ""}, StopCondition{"x", 0.5, -1, "", true, ""}};
        const Result r = simulate(CosineOscillator{}, 10.0, o);
        CHECK(r.completed);
        CHECK(r.status == 1);
        CHECK(r.message.find("x = 0.5") != std::string::npos);
        REQUIRE(r.stop_events.size() == 2);
        CHECK(r.stop_events[0].time == Approx(std::asin(0.8)).margin(1e-8));
        CHECK(r.stop_events[0].stop_condition == 0);
        CHECK(r.stop_events[0].direction == -1);
        CHECK(r.stop_events[0].state_after[1] == Approx(-0.8).margin(1e-8));
        CHECK(r.stop_events[1].time == Approx(pi / 3).margin(1e-8));
        CHECK(r.stop_events[1].name == "x = 0.5");
        CHECK(r.t_reached == r.stop_events[1].time);
        CHECK(r.t.back() == r.stop_events[1].time);  // the last row is where the condition held
        CHECK(r.state(r.rows() - 1, 0) == Approx(0.5).margin(1e-8));
        CHECK(r.events.empty());  // stop crossings are not switches
    }
}

TEST_CASE("stop conditions: direction picks the crossings, non-terminal ones are all logged", "[stop]") {
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    // x = cos t crosses 0 at pi/2 (falling), 3 pi/2 (rising), 5 pi/2 (falling), ... up to t = 10
    o.stop_conditions = {StopCondition{"x", 0.0, +1, "", false, "rising"},
                         StopCondition{"x", 0.0, 0, "", false, "both"}};
    const Result r = simulate(CosineOscillator{}, 10.0, o);
    CHECK(r.status == 0);
    CHECK(r.t_reached == 10.0);
    std::vector<double> rising, both;
    for (const Event& e : r.stop_events) (e.stop_condition == 0 ? rising : both).push_back(e.time);
    REQUIRE(rising.size() == 1);  // 3 pi / 2 (7 pi / 2 = 11.0 > 10)
    CHECK(rising[0] == Approx(1.5 * pi).margin(1e-8));
    REQUIRE(both.size() == 3);  // pi / 2, 3 pi / 2, 5 pi / 2 (7 pi / 2 = 11.0 > 10)
    for (std::size_t k = 0; k < 3; ++k) CHECK(both[k] == Approx((0.5 + k) * pi).margin(1e-8));
    for (std::size_t k = 1; k < r.stop_events.size(); ++k) CHECK(r.stop_events[k].time >= r.stop_events[k - 1].time);
}

TEST_CASE("stop conditions: a switch into a named mode ends the run with the state after the switch", "[stop]") {
    for (Method m : methods()) {
        CAPTURE(method_name(m));
        SolverOptions o;
        o.method = m;
        o.stop_conditions = {StopCondition{"", 0.0, 0, "down", true, ""}};
        const Result r = simulate(UpDown{}, 5.0, o);
        CHECK(r.status == 1);
        REQUIRE(r.stop_events.size() == 1);
        CHECK(r.stop_events[0].name == "mode down");
        CHECK(r.stop_events[0].time == Approx(1.0).margin(1e-9));
        CHECK(r.t_reached == r.stop_events[0].time);
        CHECK(r.state(r.rows() - 1, 0) == 1.0);  // the projected state after the switch
        CHECK(r.mode.back() == 1);
        REQUIRE(r.events.size() == 1);  // the switch itself is still logged
    }
}

TEST_CASE("events carry the state before and after the switch - record_event_rows puts rows at both sides", "[stop]") {
    SolverOptions o;
    o.output_times = {0.0, 0.5, 1.5, 2.5, 3.0};
    o.record_event_rows = true;
    const Result r = simulate(UpDown{}, 3.0, o);
    CHECK(r.status == 0);
    CHECK(r.message == "the run reached t_end");
    REQUIRE(r.events.size() == 2);
    const Event& top = r.events[0];
    CHECK(top.time == Approx(1.0).margin(1e-9));
    REQUIRE(top.state_before.size() == 1);
    CHECK(top.state_before[0] == Approx(1.0).margin(1e-9));  // where the root was located
    CHECK(top.state_after[0] == 1.0);                        // projected exactly
    CHECK(r.events[1].state_after[0] == 0.0);
    // rows: 0, 0.5, (1, up), (1, down), 1.5, (2, down), (2, rest), 2.5, 3
    REQUIRE(r.rows() == 9);
    CHECK(r.t[2] == top.time);
    CHECK(r.t[3] == top.time);
    CHECK(r.mode[2] == 0);
    CHECK(r.mode[3] == 1);
    CHECK(r.mode[5] == 1);
    CHECK(r.mode[6] == 2);

    o.record_event_rows = false;
    o.record_event_states = false;
    const Result plain = simulate(UpDown{}, 3.0, o);
    CHECK(plain.rows() == 5);
    CHECK(plain.events[0].state_before.empty());

    // a system sized at run time (a string: thousands of switches of its whole state) keeps none unless asked
    o.record_event_states.reset();
    const Result string_like = simulate(UpDownAtRunTime{}, 3.0, o);
    REQUIRE(string_like.events.size() == 2);
    CHECK(string_like.events[0].state_after.empty());
    o.record_event_states = true;
    CHECK(simulate(UpDownAtRunTime{}, 3.0, o).events[0].state_after == std::vector<double>{1.0});
}

TEST_CASE("stop conditions: bad conditions are refused naming the field", "[stop]") {
    SolverOptions o;
    o.stop_conditions = {StopCondition{"nope", 0.0, 0, "", true, ""}};
    CHECK(rejected_parameter([&] { simulate(CosineOscillator{}, 1.0, o); }) == "stop_conditions.state");
    o.stop_conditions = {StopCondition{"x", 0.0, 2, "", true, ""}};
    CHECK(rejected_parameter([&] { simulate(CosineOscillator{}, 1.0, o); }) == "stop_conditions.direction");
    o.stop_conditions = {StopCondition{"x", NAN, 0, "", true, ""}};
    CHECK(rejected_parameter([&] { simulate(CosineOscillator{}, 1.0, o); }) == "stop_conditions.level");
    o.stop_conditions = {StopCondition{"x", 0.0, 0, "stick", true, ""}};
    CHECK(rejected_parameter([&] { simulate(CosineOscillator{}, 1.0, o); }) == "stop_conditions");
    o.stop_conditions = {StopCondition{"", 0.0, 0, "", true, ""}};
    CHECK(rejected_parameter([&] { simulate(CosineOscillator{}, 1.0, o); }) == "stop_conditions");
}
