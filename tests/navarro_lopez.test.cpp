// The lumped drill strings of Navarro-Lopez & Cortes (2007) (rigs/navarro_lopez.hpp): steady bit speeds against the
// closed-form balance u - (c_r + c_b) w - R_b W mu_b(w) = 0 over weight on bit (roots found here by bisection), the
// stuck steady state above W = u / (R_b mu_sb), exact break-away at the threshold where a scheme that re-solves the
// acceleration-level problem stalls (against an independent RK4 of the slip equations), and the energy balance
// through stick-slip.
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include <frictionsim/rigs/navarro_lopez.hpp>
#include <frictionsim/solve/dormand_prince.hpp>
#include <frictionsim/solve/simulate_with.hpp>

#include "catch.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {

/// Root of u - (c_r + c_b) w - R_b W mu_b(w) - extra = 0 on w > 0, mu_b written out here, by bisection.
double balance_speed(double u, double c_r, double c_b, double R_b, double W, double mu_cb, double mu_sb, double gamma_b,
                     double v_f, double extra = 0.0) {
    const auto f = [&](double w) {
        return u - (c_r + c_b) * w - R_b * W * (mu_cb + (mu_sb - mu_cb) * std::exp(-gamma_b * w / v_f)) - extra;
    };
    double lo = 0.0, hi = (u - extra) / (c_r + c_b) + 1.0;
    REQUIRE(f(lo) > 0.0);
    REQUIRE(f(hi) < 0.0);
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) > 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

template <class Rig>
Result run(const Rig& rig, double t_end, double rtol = 1e-9) {
    SolverOptions o;
    o.rtol = rtol;
    o.atol = 1e-9;
    o.output_times = {t_end};
    return simulate_with<DormandPrince>(rig, t_end, o);
}

double last(const Result& r, const std::string& name) { return r.column_values(name).back(); }

/// The same string, but every switch re-solves the acceleration-level problem for all contacts at zero speed,
/// including one whose break-away guard just fired: what an event scheme without the guard's direction does.
struct NaiveNavarroLopez : NavarroLopez2Dof {
    using NavarroLopez2Dof::NavarroLopez2Dof;
    int switch_mode(double, double* x, int mode, const int*) const {
        std::array<bool, dof> at_rest{};
        at_rest[bit] = x[speed + bit] == 0.0;
        return resolve_at_rest(x, mode, at_rest);
    }
};

}  // namespace

TEST_CASE("Navarro-Lopez 2-DOF: steady bit speed is the closed-form balance over weight on bit", "[navarro_lopez]") {
    NavarroLopez2DofParams p;  // u = 6 kN m
    p.initial_speed = 5.0;
    for (double W : {10e3, 15e3, 20e3, 25e3, 30e3, 35e3}) {
        p.weight_on_bit = W;
        const NavarroLopez2Dof rig(p);
        const double w = balance_speed(p.motor_torque, p.table_damping, p.bit_damping, p.bit_radius, W,
                                       p.coulomb_coefficient, p.static_coefficient, p.weakening_rate, p.velocity_scale);
        const Result r = run(rig, 150.0);
        INFO("W = " << W << " N, balance speed " << w << " rad/s");
        CHECK(last(r, "bit_speed") == Approx(w).epsilon(1e-6));
        CHECK(last(r, "table_speed") == Approx(w).epsilon(1e-6));
        // the string carries the bit's torque: k_t twist = c_b w + R_b W mu_b(w)
        CHECK(p.string_stiffness * last(r, "string_twist") ==
              Approx(rig.bit_law().torque(w, W, +1)).epsilon(1e-6));
    }
}

TEST_CASE("Navarro-Lopez 4-DOF: steady bit speed is the same balance, with pipe wall torques added", "[navarro_lopez]") {
    NavarroLopez4DofParams p;
    p.initial_speed = 5.0;
    for (double T_p : {0.0, 300.0}) {
        p.pipe_wall_torque = T_p;
        for (double W : {10e3, 20e3, 30e3}) {
            p.weight_on_bit = W;
            const NavarroLopez4Dof rig(p);
            const double w = balance_speed(p.motor_torque, p.table_damping, p.bit_damping, p.bit_radius, W,
                                           p.coulomb_coefficient, p.static_coefficient, p.weakening_rate,
                                           p.velocity_scale, 2.0 * T_p);
            const Result r = run(rig, 200.0);
            INFO("W = " << W << " N, pipe wall torque " << T_p << " N m, balance speed " << w << " rad/s");
            for (const char* name : {"table_speed", "upper_pipe_speed", "lower_pipe_speed", "bit_speed"})
                CHECK(last(r, name) == Approx(w).epsilon(1e-6));
        }
    }
}

TEST_CASE("Navarro-Lopez: above W = u / (R_b mu_sb) the stuck steady state holds, below it breaks away",
          "[navarro_lopez]") {
    // The stuck steady state: everything at rest, every spring passing u (k twist = u), the bit holding u.
    // (From an untwisted string the table's overshoot winds the spring past u, so a string started at rest can
    // break away above the threshold too: the threshold is that of the steady state.)
    NavarroLopez2DofParams p;
    const double threshold = p.motor_torque / (p.bit_radius * p.static_coefficient);
    std::array<double, NavarroLopez2Dof::state_size> wound{};
    wound[NavarroLopez2Dof::twist] = p.motor_torque / p.string_stiffness;
    SECTION("2-DOF, 2 % above: it stays") {
        p.weight_on_bit = 1.02 * threshold;
        NavarroLopez2Dof rig(p);
        rig.set_initial_state(wound);
        CHECK(rig.initial_mode(0.0, wound.data()) == 1);
        const Result r = run(rig, 100.0);
        CHECK(r.events.empty());
        for (int m : r.mode) CHECK(m == 1);  // the bit stuck throughout
        CHECK(last(r, "bit_speed") == 0.0);
        CHECK(last(r, "table_speed") == Approx(0.0).margin(1e-9));
    }
    SECTION("2-DOF, 20 % above, wound to 95 %: it settles into the stuck steady state") {
        p.weight_on_bit = 1.2 * threshold;
        NavarroLopez2Dof rig(p);
        wound[NavarroLopez2Dof::twist] *= 0.95;
        rig.set_initial_state(wound);
        const Result r = run(rig, 150.0);
        CHECK(r.events.empty());
        for (double w : r.column_values("bit_speed")) CHECK(w == 0.0);
        CHECK(last(r, "table_speed") == Approx(0.0).margin(1e-6));
        CHECK(p.string_stiffness * last(r, "string_twist") == Approx(p.motor_torque).epsilon(1e-6));
    }
    SECTION("2-DOF, 2 % below: the bit cannot hold, it starts slipping") {
        p.weight_on_bit = 0.98 * threshold;
        NavarroLopez2Dof rig(p);
        rig.set_initial_state(wound);
        CHECK(rig.initial_mode(0.0, wound.data()) == 0);  // resolved at rest: slips forwards
        const Result r = run(rig, 10.0);
        CHECK(last(r, "bit_speed") > 0.0);
    }
    SECTION("4-DOF, 2 % above and 2 % below") {
        NavarroLopez4DofParams q;
        std::array<double, NavarroLopez4Dof::state_size> x{};
        x[NavarroLopez4Dof::twist + 0] = q.motor_torque / q.table_stiffness;
        x[NavarroLopez4Dof::twist + 1] = q.motor_torque / q.pipe_stiffness;
        x[NavarroLopez4Dof::twist + 2] = q.motor_torque / q.bit_stiffness;
        const double threshold4 = q.motor_torque / (q.bit_radius * q.static_coefficient);
        q.weight_on_bit = 1.02 * threshold4;
        NavarroLopez4Dof above(q);
        above.set_initial_state(x);
        CHECK(above.initial_mode(0.0, x.data()) == 1);
        const Result r = run(above, 100.0);
        CHECK(r.events.empty());
        for (const char* name : {"table_speed", "upper_pipe_speed", "lower_pipe_speed", "bit_speed"})
            CHECK(last(r, name) == Approx(0.0).margin(1e-9));
        q.weight_on_bit = 0.98 * threshold4;
        NavarroLopez4Dof below(q);
        below.set_initial_state(x);
        CHECK(below.initial_mode(0.0, x.data()) == 0);
        const Result s = run(below, 10.0);
        CHECK(last(s, "bit_speed") > 0.0);
    }
}

TEST_CASE("Navarro-Lopez: exact break-away at the threshold, where re-solving at the acceleration level stalls",
          "[navarro_lopez]") {
    // The bit at rest with the string wound so that its torque on the bit is exactly R_b W mu_sb; the table at
    // rest, driven by u > R_b W mu_sb, so the torque on the bit grows (through c_t). There the acceleration-level
    // problem ties: holding the bit needs exactly the bound, and slipping from zero speed gives zero acceleration.
    NavarroLopez2DofParams p;
    p.weight_on_bit = 30e3;
    const NavarroLopez2Dof rig(p);
    const double limit = rig.static_limit(NavarroLopez2Dof::bit);
    double twist = limit / p.string_stiffness;  // the twist whose spring torque is the bound to the last bit
    for (int i = 0; i < 8 && p.string_stiffness * twist != limit; ++i)
        twist = std::nextafter(twist, p.string_stiffness * twist < limit ? 1.0 : 0.0);
    REQUIRE(p.string_stiffness * twist == limit);
    std::array<double, NavarroLopez2Dof::state_size> x0{};
    x0[NavarroLopez2Dof::twist] = twist;

    // the tie, as the LCP sees it: stuck with zero reserve
    const ContactsAtRest tie = resolve_contacts_at_rest({1.0 / p.bit_inertia}, {limit / p.bit_inertia}, {limit});
    CHECK(tie.modes[0] == stick);
    CHECK(tie.acceleration[0] == 0.0);

    SECTION("re-solving the acceleration-level problem at each switch stalls at t = 0") {
        NaiveNavarroLopez naive(p);
        naive.set_initial_state(x0);
        SolverOptions o;
        o.output_times = {1.0};
        double stalled_at = -1.0;
        try {
            simulate_with<DormandPrince>(naive, 1.0, o);
        } catch (const ChatteringError& e) {
            stalled_at = e.time_reached();
            CHECK(e.switching_function() == "bit_breakaway_positive");
        }
        CHECK(stalled_at == 0.0);  // stick -> break-away guard -> stick again, at the same instant
    }
    SECTION("the rig breaks away at once and follows the slip equations (independent RK4)") {
        NavarroLopez2Dof exact(p);
        exact.set_initial_state(x0);
        SolverOptions o;
        o.rtol = 1e-10;
        o.atol = 1e-12;
        const double t1 = 0.5;
        for (int k = 1; k <= 5; ++k) o.output_times.push_back(0.1 * k);
        const Result r = simulate_with<DormandPrince>(exact, t1, o);
        REQUIRE(r.events.size() == 1);
        CHECK(r.events[0].time == 0.0);
        CHECK(r.events[0].name == "bit_breakaway_positive");
        CHECK(r.events[0].mode_after == 0);  // slips forwards
        // slip equations, x = (w_r, twist, w_b), integrated with classical RK4 at dt = 1e-5
        const auto f = [&](const std::array<double, 3>& y) {
            const double S = p.string_stiffness * y[1] + p.string_damping * (y[0] - y[2]);
            const double mu = p.coulomb_coefficient +
                              (p.static_coefficient - p.coulomb_coefficient) * std::exp(-p.weakening_rate * y[2] / p.velocity_scale);
            const double Tb = p.bit_damping * y[2] + p.bit_radius * p.weight_on_bit * mu;
            return std::array<double, 3>{(p.motor_torque - p.table_damping * y[0] - S) / p.table_inertia, y[0] - y[2],
                                         (S - Tb) / p.bit_inertia};
        };
        std::array<double, 3> y{0.0, twist, 0.0};
        const double dt = 1e-5;
        std::size_t row = 0;
        for (int step = 1; step <= static_cast<int>(std::lround(t1 / dt)); ++step) {
            auto add = [](const std::array<double, 3>& a, const std::array<double, 3>& b, double h) {
                return std::array<double, 3>{a[0] + h * b[0], a[1] + h * b[1], a[2] + h * b[2]};
            };
            const auto k1 = f(y), k2 = f(add(y, k1, dt / 2)), k3 = f(add(y, k2, dt / 2)), k4 = f(add(y, k3, dt));
            for (int i = 0; i < 3; ++i) y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            if (step % 10000 == 0) {
                while (row < r.rows() && r.t[row] < step * dt - 1e-12) ++row;
                REQUIRE(row < r.rows());
                INFO("t = " << r.t[row]);
                CHECK(y[2] > 0.0);
                CHECK(r.state(row, r.column("bit_speed")) == Approx(y[2]).epsilon(1e-7));
                CHECK(r.state(row, r.column("table_speed")) == Approx(y[0]).epsilon(1e-7));
            }
        }
    }
}

TEST_CASE("Navarro-Lopez: stick-slip near the threshold keeps the energy balance", "[navarro_lopez]") {
    NavarroLopez2DofParams p;
    p.motor_torque = 2000.0;
    p.weight_on_bit = 0.99 * p.motor_torque / (p.bit_radius * p.static_coefficient);  // stick-slip from rest
    const NavarroLopez2Dof rig(p);
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-10;
    for (int k = 1; k <= 400; ++k) o.output_times.push_back(0.25 * k);
    const Result r = simulate_with<DormandPrince>(rig, 100.0, o);
    int stick_entries = 0;
    for (const Event& e : r.events) stick_entries += e.mode_after == 1;
    CHECK(stick_entries >= 10);
    const std::array<double, NavarroLopez2Dof::state_size> x0 = rig.initial_state();
    double worst = 0.0;
    for (std::size_t row = 0; row < r.rows(); ++row) {
        std::array<double, NavarroLopez2Dof::state_size> x{};
        for (std::size_t c = 0; c < x.size(); ++c) x[c] = r.state(row, c);
        const double stored = rig.stored_energy(x.data()) - rig.stored_energy(x0.data());
        const double residual = x[NavarroLopez2Dof::motor_work] - stored - x[NavarroLopez2Dof::damping_work] -
                                x[NavarroLopez2Dof::friction_work];
        worst = std::max(worst, std::abs(residual) / std::max(1.0, x[NavarroLopez2Dof::motor_work]));
    }
    CHECK(worst < 1e-7);
}

TEST_CASE("Navarro-Lopez 4-DOF with wall contacts: three contacts break away from rest, energy closes",
          "[navarro_lopez]") {
    NavarroLopez4DofParams p;
    p.pipe_wall_torque = 400.0;
    p.weight_on_bit = 20e3;
    const NavarroLopez4Dof rig(p);
    REQUIRE(rig.has_contact(1));
    REQUIRE(rig.has_contact(2));
    REQUIRE_FALSE(rig.has_contact(0));
    const std::array<double, NavarroLopez4Dof::state_size> x0 = rig.initial_state();
    const int stuck = rig.initial_mode(0.0, x0.data());  // at rest, nothing loaded: all three contacts hold
    for (std::size_t i = 1; i < 4; ++i) CHECK(NavarroLopez4Dof::contact_mode(stuck, i) == stick);
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-10;
    for (int k = 1; k <= 200; ++k) o.output_times.push_back(1.0 * k);
    const Result r = simulate_with<DormandPrince>(rig, 200.0, o);
    int pipe_breakaways = 0, bit_breakaways = 0;
    for (const Event& e : r.events) {
        pipe_breakaways += e.name == "inertia_breakaway_positive";
        bit_breakaways += e.name == "bit_breakaway_positive";
    }
    CHECK(pipe_breakaways >= 2);
    CHECK(bit_breakaways >= 1);
    const double w = balance_speed(p.motor_torque, p.table_damping, p.bit_damping, p.bit_radius, p.weight_on_bit,
                                   p.coulomb_coefficient, p.static_coefficient, p.weakening_rate, p.velocity_scale,
                                   2.0 * p.pipe_wall_torque);
    CHECK(last(r, "bit_speed") == Approx(w).epsilon(1e-6));
    CHECK(last(r, "upper_pipe_speed") == Approx(w).epsilon(1e-6));
    CHECK(r.mode.back() == 0);  // everything slips forwards
    double worst = 0.0;
    for (std::size_t row = 0; row < r.rows(); ++row) {
        std::array<double, NavarroLopez4Dof::state_size> x{};
        for (std::size_t c = 0; c < x.size(); ++c) x[c] = r.state(row, c);
        const double residual = x[NavarroLopez4Dof::motor_work] - rig.stored_energy(x.data()) -
                                x[NavarroLopez4Dof::damping_work] - x[NavarroLopez4Dof::friction_work];
        worst = std::max(worst, std::abs(residual) / std::max(1.0, x[NavarroLopez4Dof::motor_work]));
    }
    CHECK(worst < 1e-7);
}

TEST_CASE("Navarro-Lopez: parameter tables reject bad values by name", "[navarro_lopez]") {
    const auto two = [](auto set) {
        NavarroLopez2DofParams p;
        set(p);
        return rejected_parameter([&] { NavarroLopez2Dof{p}; });
    };
    CHECK(two([](auto& p) { p.bit_inertia = 0.0; }) == "bit_inertia");
    CHECK(two([](auto& p) { p.string_stiffness = -1.0; }) == "string_stiffness");
    CHECK(two([](auto& p) { p.static_coefficient = 0.3; }) == "static_coefficient");
    CHECK(two([](auto& p) { p.weight_on_bit = -1.0; }) == "weight_on_bit");
    CHECK(two([](auto& p) { p.motor_torque = std::numeric_limits<double>::quiet_NaN(); }) == "motor_torque");
    NavarroLopez4DofParams q;
    q.pipe_wall_torque = -5.0;
    CHECK(rejected_parameter([&] { NavarroLopez4Dof{q}; }) == "pipe_wall_torque");
    NavarroLopez2Dof rig{NavarroLopez2DofParams{}};
    std::array<double, NavarroLopez2Dof::state_size> bad{};
    bad[0] = std::numeric_limits<double>::infinity();
    CHECK(rejected_parameter([&] { rig.set_initial_state(bad); }) == "initial_state");
    CHECK(std::string(rig.mode_name(1)) == "bit:stick");
    CHECK(std::string(NavarroLopez4Dof(NavarroLopez4DofParams{}).mode_name(0)) == "bit:slip_positive");
}
