// Hybrid systems sized at run time (issue 13, item 1): the event loop, Dormand-Prince and CVODE (dense, band and
// KLU sparse Newton solvers) on systems whose state and guard counts are known only at run time, and per-contact
// modes (ContactModes) with one event per contact that switches.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "catch.hpp"
#include "frictionsim/simulate.hpp"
#include "frictionsim/solve/root_location.hpp"
#include "frictionsim/solve/system_size.hpp"

using namespace frictionsim;

namespace {

/// N equal masses m in a fixed-free chain of springs k: x_i, v_i interleaved (state 2i, 2i + 1), so the
/// Jacobian is banded with lower and upper bandwidth 3. No switching functions.
struct SpringChain {
    std::size_t masses = 10;
    double mass = 2.0, stiffness = 50.0;
    std::vector<double> start;

    std::size_t state_size() const { return 2 * masses; }
    std::size_t guard_count() const { return 0; }

    double spring_force(const double* x, std::size_t i) const {  // net spring force on mass i
        const double left = i == 0 ? x[0] : x[2 * i] - x[2 * i - 2];
        const double right = i + 1 < masses ? x[2 * i + 2] - x[2 * i] : 0.0;
        return stiffness * (right - left);
    }
    void rhs(double, const double* x, int, double* dxdt) const {
        for (std::size_t i = 0; i < masses; ++i) {
            dxdt[2 * i] = x[2 * i + 1];
            dxdt[2 * i + 1] = spring_force(x, i) / mass;
        }
    }
    Bandwidths jacobian_bandwidths() const { return {3, 3}; }
    template <class Add>
    void jacobian_entries(double, const double*, int, Add&& add) const {
        const double c = stiffness / mass;
        for (std::size_t i = 0; i < masses; ++i) {
            add(2 * i, 2 * i + 1, 1.0);
            add(2 * i + 1, 2 * i, i + 1 < masses ? -2.0 * c : -c);
            if (i > 0) add(2 * i + 1, 2 * i - 2, c);
            if (i + 1 < masses) add(2 * i + 1, 2 * i + 2, c);
        }
    }
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return ""; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    const char* mode_name(int) const { return "free"; }
    std::vector<std::string> state_names() const {
        std::vector<std::string> names;
        for (std::size_t i = 0; i < masses; ++i) {
            names.push_back("x" + std::to_string(i));
            names.push_back("v" + std::to_string(i));
        }
        return names;
    }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::vector<double> initial_state() const { return start; }

    /// Mode r (0-based) of the fixed-free chain: x_i = sin((2r + 1) (i + 1) pi / (2N + 1)),
    /// omega_r = 2 sqrt(k/m) sin((2r + 1) pi / (2 (2N + 1))).
    double mode_shape(std::size_t r, std::size_t i) const {
        return std::sin((2.0 * r + 1.0) * (i + 1.0) * M_PI / (2.0 * masses + 1.0));
    }
    double mode_frequency(std::size_t r) const {
        return 2.0 * std::sqrt(stiffness / mass) * std::sin((2.0 * r + 1.0) * M_PI / (2.0 * (2.0 * masses + 1.0)));
    }
};

SpringChain chain_in_mode(std::size_t masses, std::size_t r) {
    SpringChain c;
    c.masses = masses;
    c.start.assign(2 * masses, 0.0);
    for (std::size_t i = 0; i < masses; ++i) c.start[2 * i] = 1e-3 * c.mode_shape(r, i);
    return c;
}

/// Blocks on a belt moving at v_belt, each tied to the ground by its own spring k_i, with Coulomb friction (static
/// F_s > kinetic F_k): each block sticks to the belt, breaks away when its spring pulls harder than F_s, slips,
/// and sticks again. One contact per block, its mode in ContactModes: 0 stuck to the belt, 1 slipping.
struct BeltBlocks {
    using mode_type = ContactModes;
    std::vector<double> stiffness;
    double mass = 1.0, belt_speed = 0.1, static_force = 1.0, kinetic_force = 0.6;

    std::size_t blocks() const { return stiffness.size(); }
    std::size_t state_size() const { return 2 * blocks(); }
    std::size_t guard_count() const { return blocks(); }

    void rhs(double, const double* x, const ContactModes& mode, double* dxdt) const {
        for (std::size_t i = 0; i < blocks(); ++i) {
            dxdt[2 * i] = x[2 * i + 1];
            // stuck: the friction force holds the block on the belt; slipping: kinetic friction drags it along
            dxdt[2 * i + 1] = mode[i] == 0 ? 0.0 : (kinetic_force - stiffness[i] * x[2 * i]) / mass;
        }
    }
    // stuck: the friction reserve F_s - k x (falls through zero at break-away); slipping: the belt's speed over
    // the block's (falls through zero when the block catches up)
    void guards(double, const double* x, const ContactModes& mode, double* g) const {
        for (std::size_t i = 0; i < blocks(); ++i)
            g[i] = mode[i] == 0 ? static_force - stiffness[i] * x[2 * i] : belt_speed - x[2 * i + 1];
    }
    int guard_direction(std::size_t, const ContactModes&) const { return -1; }
    const char* guard_name(std::size_t i, const ContactModes& mode) const {
        (void)i;
        return mode[i] == 0 ? "friction_reserve" : "relative_velocity";
    }
    ContactModes initial_mode(double, const double*) const { return ContactModes(blocks(), 0); }
    ContactModes switch_mode(double, double* x, const ContactModes& mode, const int* fired) const {
        ContactModes next = mode;
        for (std::size_t i = 0; i < blocks(); ++i) {
            if (fired[i] == 0) continue;
            next[i] = mode[i] == 0 ? 1 : 0;
            if (next[i] == 0) x[2 * i + 1] = belt_speed;  // exact stick: on the belt's speed
        }
        return next;
    }
    int mode_code(const ContactModes& mode) const { return static_cast<int>(mode.count(0)); }
    int guard_mode(std::size_t i, const ContactModes& mode) const { return mode[i]; }
    const char* mode_name(int contact_mode) const { return contact_mode == 0 ? "stick" : "slip"; }
    std::vector<std::string> state_names() const {
        std::vector<std::string> names;
        for (std::size_t i = 0; i < blocks(); ++i) {
            names.push_back("x" + std::to_string(i));
            names.push_back("v" + std::to_string(i));
        }
        return names;
    }
    double friction_force(double, const double* x, const ContactModes& mode) const {
        double total = 0.0;
        for (std::size_t i = 0; i < blocks(); ++i) total += mode[i] == 0 ? stiffness[i] * x[2 * i] : kinetic_force;
        return total;
    }
    std::vector<double> initial_state() const {
        std::vector<double> x(state_size(), 0.0);
        for (std::size_t i = 0; i < blocks(); ++i) x[2 * i + 1] = belt_speed;
        return x;
    }

    /// The closed form of block i's cycle. Slip starts at x = F_s/k, v = V; with u = x - F_k/k the slip is
    /// u = R cos(w t - phi), R = sqrt(u0^2 + (V/w)^2), u0 = (F_s - F_k)/k, phi = atan2(V/w, u0), and ends when
    /// u' = V again, after (pi + 2 phi)/w, at u = -u0; the stick that follows lasts 2 u0 / V.
    double first_break_away(std::size_t i) const { return static_force / stiffness[i] / belt_speed; }
    double slip_duration(std::size_t i) const {
        const double w = std::sqrt(stiffness[i] / mass), u0 = (static_force - kinetic_force) / stiffness[i];
        return (M_PI + 2.0 * std::atan2(belt_speed / w, u0)) / w;
    }
    double stick_duration(std::size_t i) const {
        return 2.0 * (static_force - kinetic_force) / stiffness[i] / belt_speed;
    }
};

static_assert(has_run_time_size_v<SpringChain> && !has_fixed_size_v<SpringChain>);
static_assert(is_hybrid_system_v<SpringChain> && is_hybrid_system_v<BeltBlocks>);
static_assert(std::is_same_v<system_mode_t<BeltBlocks>, ContactModes> && std::is_same_v<system_mode_t<SpringChain>, int>);
static_assert(has_jacobian_entries_v<SpringChain> && declares_bandwidths_v<SpringChain>);

void check_chain_mode(const SpringChain& chain, std::size_t r, const SolverOptions& o, double tolerance) {
    const double t_end = 3.0;
    SolverOptions opts = o;
    opts.output_times = {0.5, 1.7, t_end};
    const Result result = simulate(chain, t_end, opts);
    REQUIRE(result.completed);
    REQUIRE(result.state_count() == chain.state_size());
    const double w = chain.mode_frequency(r);
    for (std::size_t row = 0; row < result.rows(); ++row) {
        for (std::size_t i = 0; i < chain.masses; ++i) {
            const double exact = 1e-3 * chain.mode_shape(r, i) * std::cos(w * result.t[row]);
            CHECK(result.state(row, 2 * i) == Approx(exact).margin(tolerance));
        }
    }
}

}  // namespace

TEST_CASE("run-time size: a 40-mass spring chain started in its third mode keeps its closed-form motion",
          "[run_time_size]") {
    const SpringChain chain = chain_in_mode(40, 2);
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-14;
    SECTION("Dormand-Prince") {
        o.method = Method::dormand_prince;
        check_chain_mode(chain, 2, o, 1e-9);
    }
    SECTION("CVODE BDF, dense Newton solver") {
        o.method = Method::cvode_bdf;
        o.linear_solver = LinearSolver::dense;
        check_chain_mode(chain, 2, o, 2e-8);
    }
    SECTION("CVODE BDF, band solver with the analytic banded Jacobian (the automatic choice)") {
        o.method = Method::cvode_bdf;
        REQUIRE(resolve_linear_solver<SpringChain>(o.linear_solver) == LinearSolver::band);
        check_chain_mode(chain, 2, o, 2e-8);
    }
    SECTION("Rosenbrock (RODAS4), banded LU with the analytic Jacobian") {
        o.method = Method::rosenbrock;
        check_chain_mode(chain, 2, o, 2e-8);
    }
    SECTION("CVODE BDF, KLU sparse solver on the band pattern") {
        o.method = Method::cvode_bdf;
        o.linear_solver = LinearSolver::sparse;
        if (!detail::cvode::klu_available) {
            CHECK_THROWS_AS(simulate(chain, 1.0, o), InvalidParameter);
            return;
        }
        check_chain_mode(chain, 2, o, 2e-8);
    }
}

TEST_CASE("run-time size: band and KLU solvers take the same steps as the dense one (same Newton matrices)",
          "[run_time_size]") {
    const SpringChain chain = chain_in_mode(25, 0);
    SolverOptions o;
    o.method = Method::cvode_bdf;
    o.rtol = 1e-9;
    o.atol = 1e-13;
    o.linear_solver = LinearSolver::dense;
    const Result dense = simulate(chain, 2.0, o);
    o.linear_solver = LinearSolver::band;
    const Result band = simulate(chain, 2.0, o);
    CHECK(band.stats.steps == dense.stats.steps);
    CHECK(band.stats.jacobian_evaluations == dense.stats.jacobian_evaluations);
    CHECK(band.states.back() == Approx(dense.states.back()).margin(1e-12));
    if (detail::cvode::klu_available) {
        o.linear_solver = LinearSolver::sparse;
        const Result sparse = simulate(chain, 2.0, o);
        CHECK(sparse.stats.steps == dense.stats.steps);
        CHECK(sparse.states.back() == Approx(dense.states.back()).margin(1e-12));
    }
}

TEST_CASE("run-time size: a wrong initial state size names initial_state", "[run_time_size]") {
    SpringChain chain = chain_in_mode(5, 0);
    chain.start.pop_back();
    try {
        (void)simulate(chain, 1.0, SolverOptions{});
        FAIL("no exception");
    } catch (const InvalidParameter& e) {
        CHECK(std::string(e.what()).find("initial_state") != std::string::npos);
    }
}

TEST_CASE("run-time size: blocks on a belt stick and slip each on its own, at the closed-form times",
          "[run_time_size]") {
    BeltBlocks belt;
    belt.stiffness = {4.0, 9.0, 25.0, 16.0};
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-13;
    o.output_times = {0.0, 5.0};
    for (Method method : {Method::dormand_prince, Method::cvode_bdf, Method::rosenbrock}) {
        o.method = method;
        const double t_end = 6.0;
        o.output_times = {0.0, t_end};
        const Result r = simulate(belt, t_end, o);
        REQUIRE(r.completed);
        CHECK(r.mode.front() == 4);  // every block starts stuck
        for (std::size_t i = 0; i < belt.blocks(); ++i) {
            // the switch times of contact i, alternating break-away (stick -> slip) and sticking again
            std::vector<double> expected;
            double t = belt.first_break_away(i);
            while (t < t_end) {
                expected.push_back(t);
                t += belt.slip_duration(i);
                if (t >= t_end) break;
                expected.push_back(t);
                t += belt.stick_duration(i);
            }
            std::vector<const Event*> mine;
            for (const Event& e : r.events)
                if (e.switching_function == static_cast<int>(i)) mine.push_back(&e);
            REQUIRE(mine.size() == expected.size());
            for (std::size_t k = 0; k < mine.size(); ++k) {
                CHECK(mine[k]->time == Approx(expected[k]).margin(1e-7));
                const bool break_away = k % 2 == 0;
                CHECK(mine[k]->mode_before_name == std::string(break_away ? "stick" : "slip"));
                CHECK(mine[k]->mode_after_name == std::string(break_away ? "slip" : "stick"));
                CHECK(mine[k]->name == std::string(break_away ? "friction_reserve" : "relative_velocity"));
            }
        }
    }
}

TEST_CASE("run-time size: the chattering bound and partial results work with per-contact modes",
          "[run_time_size]") {
    BeltBlocks belt;
    belt.stiffness = {4.0, 9.0, 25.0};
    // every block's switches from the closed form, in time order: (time, block)
    std::vector<std::pair<double, int>> switches;
    for (std::size_t i = 0; i < belt.blocks(); ++i) {
        double t = belt.first_break_away(i);
        for (int k = 0; t < 10.0; ++k) {
            switches.emplace_back(t, static_cast<int>(i));
            t += k % 2 == 0 ? belt.slip_duration(i) : belt.stick_duration(i);
        }
    }
    std::sort(switches.begin(), switches.end());
    // the bound: more than 2 switches within 0.3 s stops the run at the first switch that makes it 3
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-13;
    o.max_events_in_window = 2;
    o.event_window = 0.3;
    std::size_t stop = 2;
    while (stop < switches.size() && switches[stop].first - switches[stop - 2].first > o.event_window) ++stop;
    REQUIRE(stop < switches.size());
    const double t_stop = switches[stop].first;
    for (double t = 0.0; t < 10.0; t += 0.25) o.output_times.push_back(t);
    const auto rows_before = static_cast<std::size_t>(std::count_if(
        o.output_times.begin(), o.output_times.end(), [&](double t) { return t <= t_stop; }));
    for (Method method : {Method::dormand_prince, Method::cvode_bdf}) {
        o.method = method;
        try {
            (void)simulate(belt, 10.0, o);
            FAIL("no ChatteringError");
        } catch (const ChatteringError& e) {
            REQUIRE(e.partial());
            const Result& partial = *e.partial();
            CHECK_FALSE(partial.completed);
            CHECK(partial.state_count() == belt.state_size());
            CHECK(partial.rows() == rows_before);  // the output rows up to the stop, none after
            REQUIRE(partial.events.size() == stop + 1);
            for (std::size_t k = 0; k <= stop; ++k) {
                CHECK(partial.events[k].time == Approx(switches[k].first).margin(1e-7));
                CHECK(partial.events[k].switching_function == switches[k].second);
            }
            CHECK(e.time_reached() == Approx(t_stop).margin(1e-7));
            CHECK(std::string(e.what()).find(partial.events.back().name) != std::string::npos);
        }
    }
}

namespace {
/// Two switching functions given as functions of time on one step's "dense output": what RootLocator sees.
struct TwoGuards {
    static constexpr std::size_t state_size = 1, guard_count = 2;
    int guard_direction(std::size_t i, int) const { return i == 0 ? -1 : +1; }
    static void at(double t, std::array<double, 2>& g) {
        g[0] = (t - 0.5) * (t - 0.5) - 0.01;  // falls through zero at 0.4 and rises back at 0.6: same sign at both ends
        g[1] = t - 0.7;                       // rises through zero at 0.7
    }
};
}  // namespace

TEST_CASE("root location: a guard that crosses and comes back within one step is found, the earliest crossing first",
          "[run_time_size]") {
    const TwoGuards sys;
    detail::RootLocator<TwoGuards> roots(sys);
    TwoGuards::at(0.0, roots.values());
    roots.restarted();
    std::array<double, 2> end{};
    TwoGuards::at(1.0, end);
    roots.set_references(0, end);
    CHECK(end[0] == Approx(roots.values()[0]));  // guard 0 has the same value at both ends of the step
    double t_root = 0.0;
    REQUIRE(roots.scan(0, 0.0, 1.0, end, [](double t, std::array<double, 2>& g) { TwoGuards::at(t, g); }, t_root));
    CHECK(t_root == Approx(0.4).margin(1e-12));  // guard 0's dip, before guard 1's crossing at 0.7
    std::array<double, 2> at_root{};
    TwoGuards::at(t_root, at_root);
    roots.mark(0, at_root);
    CHECK(roots.roots()[0] == -1);
    CHECK(roots.roots()[1] == 0);
}

TEST_CASE("root location: a guard that sits at zero after a restart is masked until it moves", "[run_time_size]") {
    const TwoGuards sys;
    detail::RootLocator<TwoGuards> roots(sys);
    roots.values() = {0.0, -0.5};  // guard 0 on its surface at the restart
    roots.restarted();
    const std::array<double, 2> still{0.0, -0.4};
    roots.set_references(0, still);
    double t_root = 0.0;
    CHECK_FALSE(roots.scan(0, 0.0, 1.0, still, [&](double, std::array<double, 2>& g) { g = still; }, t_root));
    // it then leaves zero upwards (its non-triggering side) and comes back below within the next step: a switch
    const std::array<double, 2> below{-0.1, -0.3};
    roots.set_references(0, below);
    CHECK(roots.crosses(0, below));
}
