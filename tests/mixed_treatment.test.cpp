// Both contact treatments in one model (solve/moreau_jean_events.hpp, issue 13 item 1): the walls captured by
// Moreau-Jean, the bit's stick <-> slip located exactly. Against the event-driven StringRig on the same lumped
// string (its inertias, springs, PI and wall bounds checked equal first) the mixed model and the all-captured one
// converge as h -> 0, at orders measured here, the mixed one with the smaller bit switch-time error; without wall
// friction the mixed model is second order (trapezoidal steps between exact switches) where the captured bit is
// first. A spring-pulled block's stick-slip cycle (closed form) checks the driver alone.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "catch.hpp"
#include "frictionsim/string/string_rig.hpp"
#include "frictionsim/string/torsional_string.hpp"
#include "frictionsim/friction/coulomb.hpp"
#include "frictionsim/simulate.hpp"
#include "frictionsim/eigen/moreau_jean_events.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {

/// The bit of TorsionalString's node N for StringRig: NavarroLopezBit plus node N's Coulomb wall, one contact (both
/// act on the bit's dof, so their bounds add), as bit.hpp lets a drilling code adapt its own bit law.
struct BitAndWall {
    static constexpr const char* name = "BitAndWall";
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;
    static constexpr bool touches_rock = true;
    NavarroLopezBit law;
    double weight = 0.0, wall_static = 0.0, wall_kinetic = 0.0;
    double weight_on_bit() const { return weight; }
    double static_limit(double w) const { return law.static_limit(w) + wall_static; }
    double slip_force(double v, double w, int dir) const { return law.slip_force(v, w, dir) + dir * wall_kinetic; }
    double slip_slope(double v, double w, int dir) const { return law.slip_slope(v, w, dir); }
    double karnopp_band() const { return 0.0; }
};

using Rig = StringRig<Coulomb, BitAndWall>;

/// 1000 m of 5" pipe, vertical to 200 m then building to 60 degrees at 500 m (node 0, the top drive's, has no wall
/// friction: StringRig has none there), Coulomb walls mu_s = `mu`, kinetic 2/3 of it, at every other node, a 300 kg
/// m^2 top drive under PI (3e3, 1e3) at 4 rad/s, a 40 kg m^2 BHA, the velocity-weakening bit (Navarro-Lopez's
/// defaults) under 60 kN, no damping: stick-slip of the bit.
struct Case {
    static constexpr double weight = 6e4;
    PipeSection pipe;
    TorsionalStringParams params;
    InclinationSurvey survey;
    std::size_t elements;

    Case(std::size_t n, double mu) : elements(n) {
        pipe.length = 1000.0;
        params.top_drive_inertia = 300.0;
        params.proportional_gain = 3e3;
        params.integral_gain = 1e3;
        params.speed_setpoint = 4.0;
        params.setpoint_time_constant = 0.0;
        params.friction_coefficient = mu;
        params.kinetic_ratio = 2.0 / 3.0;
        params.bha_inertia = 40.0;
        params.weight_on_bit = weight;
        survey.measured_depth = {0.0, 200.0, 500.0};
        survey.inclination = {0.0, 0.0, pi / 3.0};
    }
    TorsionalString string() const { return TorsionalString(DrillString({pipe}), params, elements, survey); }
    /// The same physics on the event-driven engine: normal forces such that mu_s N_i r_i is the string's bound.
    Rig rig(const TorsionalString& ts) const {
        StringRigParams p;
        p.top_drive_inertia = params.top_drive_inertia;
        p.proportional_gain = params.proportional_gain;
        p.integral_gain = params.integral_gain;
        p.surface_speed = params.speed_setpoint;
        p.torque_limit = 1e12;  // never reached: TorsionalString's PI is unlimited
        p.end_inertia = params.bha_inertia;
        p.damping_time = 0.0;
        StringRigSetup s;
        s.elements = elements;
        const double mu_s = params.friction_coefficient, radius = pipe.outer_diameter / 2.0;
        const std::vector<double>& bound = ts.static_friction_torque();
        s.wall_contacts = mu_s > 0.0;
        for (std::size_t i = 1; i < elements && s.wall_contacts; ++i)
            if (bound[i] > 0.0) {  // as the string: no contact without friction (the vertical top)
                s.contact_nodes.push_back(i);
                s.normal_forces.push_back(bound[i] / (mu_s * radius));
            }
        BitAndWall bit{ts.bit_law(), weight, bound.back(), params.kinetic_ratio * bound.back()};
        return Rig(DrillString({pipe}), p, s,
                   Coulomb(params.kinetic_ratio * std::max(mu_s, 1e-3), std::max(mu_s, 1e-3)), bit);
    }
};

std::vector<double> grid(double t_end, double dt) {
    std::vector<double> t;
    const long steps = std::lround(t_end / dt);
    for (long k = 0; k <= steps; ++k) t.push_back(dt * static_cast<double>(k));
    return t;
}

std::vector<double> bit_switch_times(const Result& r) {
    std::vector<double> t;
    for (const Event& e : r.events)
        if (e.name.rfind("bit", 0) == 0) t.push_back(e.time);
    return t;
}

std::vector<double> bit_switch_times(const TorsionalStringRun& r) {
    std::vector<double> t = r.bit_stick_times;
    t.insert(t.end(), r.bit_release_times.begin(), r.bit_release_times.end());
    std::sort(t.begin(), t.end());
    return t;
}

/// Largest |a_k - b_k| over the first `count` entries (both must have them).
double switch_error(const std::vector<double>& a, const std::vector<double>& b, std::size_t count) {
    REQUIRE(a.size() >= count);
    REQUIRE(b.size() >= count);
    double e = 0.0;
    for (std::size_t k = 0; k < count; ++k) e = std::max(e, std::abs(a[k] - b[k]));
    return e;
}

/// The least-squares slope of log(error) against log(x): the measured order.
double fitted_order(const std::vector<double>& x, const std::vector<double>& error) {
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double lx = std::log(x[i]), ly = std::log(error[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

struct Convergence {
    std::vector<double> steps, captured_switch, exact_switch, captured_speed, exact_speed;
    long wall_switches = 0;
};

/// The bit's first `count` switch times and its speed (RMS over the outputs) against the reference, both
/// treatments, over a ladder of steps.
Convergence converge(const Case& c, const Result& reference, double t_end, std::size_t count,
                     const std::vector<double>& steps) {
    const TorsionalString ts = c.string();
    const Rig rig = c.rig(ts);
    const std::vector<double> t_ref = bit_switch_times(reference);
    Convergence out;
    out.steps = steps;
    for (double h : steps) {
        for (BitTreatment treatment : {BitTreatment::captured, BitTreatment::exact}) {
            TorsionalStringRunOptions o;
            o.t_end = t_end;
            o.step = h;
            o.output_interval = 0.02;
            o.bit_treatment = treatment;
            const TorsionalStringRun run = ts.simulate(o);
            REQUIRE(run.time.size() == reference.rows());
            double sum = 0.0;
            for (std::size_t row = 0; row < run.time.size(); ++row) {
                const double d = run.bit_speed[row] - reference.state(row, rig.omega(c.elements));
                sum += d * d;
            }
            const double speed = std::sqrt(sum / static_cast<double>(run.time.size()));
            const double at = switch_error(bit_switch_times(run), t_ref, count);
            if (treatment == BitTreatment::captured) {
                out.captured_switch.push_back(at);
                out.captured_speed.push_back(speed);
            } else {
                out.exact_switch.push_back(at);
                out.exact_speed.push_back(speed);
                out.wall_switches = std::max(out.wall_switches, run.statistics.contact_switches);
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("mixed treatment: TorsionalString and StringRig lump the same string (inertias, springs, PI, bounds)",
          "[mixed]") {
    const Case c(16, 0.1);
    const TorsionalString ts = c.string();
    const Rig rig = c.rig(ts);
    const LinearMechanicalSystem sys = ts.system();
    const std::size_t n = c.elements;
    for (std::size_t i = 0; i <= n; ++i)
        CHECK(sys.mass.coeff(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) ==
              Approx(rig.node_inertia()[i]).epsilon(1e-14));
    for (std::size_t e = 0; e < n; ++e) {
        const auto a = static_cast<Eigen::Index>(e);
        CHECK(-sys.stiffness.coeff(a + 1, a) == Approx(rig.lumped().torsional_stiffness[e]).epsilon(1e-14));
    }
    // the PI: a damper k_p and a spring k_i to the set-point angle at node 0, as StringRig's integral state
    CHECK(sys.damping.coeff(0, 0) == c.params.proportional_gain);
    CHECK(sys.stiffness.coeff(0, 0) - rig.lumped().torsional_stiffness[0] ==
          Approx(c.params.integral_gain).epsilon(1e-9));
    CHECK(ts.static_friction_torque()[0] == 0.0);  // StringRig has no wall at the top drive
    // the wall bounds: the string's contact at node i, mu_s N_i r_i and mu N_i r_i of the rig's Coulomb walls
    const std::vector<std::size_t>& nodes = rig.contact_nodes();
    std::size_t walls = 0;
    for (const PointContact& k : sys.contacts) {
        if (k.dof == n) {  // the bit with node N's wall
            CHECK(k.static_bound == Approx(rig.bit().static_limit(Case::weight)).epsilon(1e-14));
            CHECK(k.kinetic_bound == Approx(rig.bit().slip_force(0.0, Case::weight, 1)).epsilon(1e-14));
            continue;
        }
        ++walls;
        const auto at = std::find(nodes.begin(), nodes.end(), k.dof);
        REQUIRE(at != nodes.end());
        const auto slot = static_cast<std::size_t>(at - nodes.begin());
        const double radius = rig.node_radius()[k.dof], normal = rig.normal_forces()[slot];
        CHECK(k.static_bound == Approx(0.1 * normal * radius).epsilon(1e-13));
        CHECK(k.kinetic_bound == Approx(0.1 * 2.0 / 3.0 * normal * radius).epsilon(1e-13));
    }
    CHECK(walls == nodes.size());
    CHECK(walls >= n - 3);  // all nodes below the vertical top
}

TEST_CASE("mixed treatment: all-captured and mixed converge to the event-driven StringRig, the mixed bit closer",
          "[mixed]") {
    // 16 elements, walls at mu_s 0.1 sticking and slipping at every node below the vertical top, the bit in
    // stick-slip: its first six switches (three cycles) and its speed against Dormand-Prince at 1e-12
    const Case c(16, 0.1);
    const TorsionalString ts = c.string();
    const Rig rig = c.rig(ts);
    const double t_end = 10.0;
    SolverOptions o;
    o.rtol = o.atol = 1e-12;
    o.output_times = grid(t_end, 0.02);
    const Result reference = simulate(rig, t_end, o);
    REQUIRE(reference.completed);
    const std::vector<double> t_ref = bit_switch_times(reference);
    REQUIRE(t_ref.size() >= 6);
    long stuck_walls = 0;
    for (const Event& e : reference.events) stuck_walls += e.mode_after_name == "stick" ? 1 : 0;
    CHECK(stuck_walls >= 20);

    // the reference in its tolerance: first order (the error follows the tolerance)
    std::vector<double> tolerances{1e-5, 1e-6, 1e-7, 1e-8}, dp_error;
    for (double tol : tolerances) {
        o.rtol = o.atol = tol;
        dp_error.push_back(switch_error(bit_switch_times(simulate(rig, t_end, o)), t_ref, 6));
    }
    const double dp_order = fitted_order(tolerances, dp_error);
    CHECK(dp_order > 0.7);
    CHECK(dp_order < 1.3);

    const Convergence k = converge(c, reference, t_end, 6, {2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5, 3.125e-5});
    CHECK(k.wall_switches >= 50);  // the walls are captured, and they do switch
    const double captured = fitted_order(k.steps, k.captured_switch), mixed = fitted_order(k.steps, k.exact_switch);
    const double captured_speed = fitted_order(k.steps, k.captured_speed);
    const double mixed_speed = fitted_order(k.steps, k.exact_speed);
    INFO("orders in h, bit switch times: captured " << captured << ", mixed " << mixed << "; bit speed (RMS): captured "
         << captured_speed << ", mixed " << mixed_speed << "; Dormand-Prince in its tolerance " << dp_order);
    CHECK(captured >= 0.8);
    CHECK(mixed >= 0.8);
    CHECK(captured_speed >= 0.8);
    CHECK(mixed_speed >= 0.8);
    for (std::size_t i = 0; i < k.steps.size(); ++i) CHECK(k.exact_switch[i] < k.captured_switch[i]);
    CHECK(k.exact_switch.back() < 2e-5);  // the bit's switches to 20 us at h = 31 us
}

TEST_CASE("mixed treatment: without wall friction the mixed model is second order, the captured bit first",
          "[mixed]") {
    // the bit the only switch: trapezoidal (theta = 1/2) steps between exactly located switches, the slip level at
    // the predicted mid-step speed; captured, each switch lands on the grid
    const Case c(10, 0.0);
    const TorsionalString ts = c.string();
    const Rig rig = c.rig(ts);
    const double t_end = 8.0;
    SolverOptions o;
    o.rtol = o.atol = 1e-12;
    o.output_times = grid(t_end, 0.02);
    const Result reference = simulate(rig, t_end, o);
    REQUIRE(reference.completed);
    const Convergence k = converge(c, reference, t_end, 4, {2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4});
    const double captured = fitted_order(k.steps, k.captured_switch), mixed = fitted_order(k.steps, k.exact_switch);
    INFO("no wall friction, orders in h of the bit switch times: captured " << captured << ", mixed " << mixed);
    CHECK(mixed >= 1.8);
    CHECK(captured >= 0.7);
    CHECK(captured < 1.5);
}

namespace {

/// A block (mass m) pulled through a spring k whose end moves at V, static and kinetic friction F_s > F_k, from
/// rest: stuck until k V t = F_s, then slipping, u = V t - x - F_k / k obeying u'' = -w^2 u with u(0) = (F_s - F_k)
/// / k, u'(0) = V, for (2 pi - 2 phi) / w, tan phi = u(0) w / V, coming to rest with the spring at 2 F_k - F_s
/// (|.| <= F_s: it sticks), stuck again for 2 (F_s - F_k) / (k V): a periodic cycle from the first break-away.
struct PulledBlock {
    double m = 1.0, k = 100.0, speed = 0.1, fs = 10.0, fk = 6.0;
    double w() const { return std::sqrt(k / m); }
    double first_release() const { return fs / (k * speed); }
    double slip_time() const { return (2.0 * pi - 2.0 * std::atan2((fs - fk) / k * w(), speed)) / w(); }
    double stick_time() const { return 2.0 * (fs - fk) / (k * speed); }
    /// Switch k (0: the first break-away, then alternately stick, release).
    double switch_time(std::size_t i) const {
        const double cycles = static_cast<double>(i / 2);
        return first_release() + cycles * (slip_time() + stick_time()) + (i % 2 == 1 ? slip_time() : 0.0);
    }
    LinearMechanicalSystem system() const {
        LinearMechanicalSystem s;
        s.mass.resize(1, 1);
        s.mass.insert(0, 0) = m;
        s.stiffness.resize(1, 1);
        s.stiffness.insert(0, 0) = k;
        const double pull = k * speed;
        s.force = [pull](double t, Eigen::VectorXd& f) { f(0) = pull * t; };
        return s;
    }
    LumpedFriction friction() const {
        const double level = fk;
        return LumpedFriction(0, fs, [level](double) { return level; }, "block");
    }
};

}  // namespace

TEST_CASE("mixed treatment: the driver locates a pulled block's stick-slip to the tolerance (closed form)",
          "[mixed]") {
    const PulledBlock b;
    const double t_end = 4.0;
    std::vector<double> steps{1e-2, 5e-3, 2.5e-3, 1.25e-3}, stick_error, captured_error;
    for (double h : steps) {
        MoreauJeanEventsOptions o;
        o.steps.step = h;
        o.time_tolerance = 1e-11;
        MoreauJeanEvents<LumpedFriction> driver(b.system(), {b.friction()}, o, Eigen::VectorXd::Zero(1),
                                                Eigen::VectorXd::Zero(1));
        driver.run(t_end);
        CHECK(driver.time() == Approx(t_end).margin(1e-12));
        const std::vector<LumpedEvent>& ev = driver.events();
        REQUIRE(ev.size() == 6);  // three cycles of release and stick within 4 s
        // a stuck block's load k (V t - x) is linear in t: the trapezoidal steps hold it exactly, so every
        // break-away after an exact start is located to the tolerance whatever h
        CHECK(ev[0].time == Approx(b.first_release()).margin(2e-11));
        CHECK(ev[0].mode_before == 0);
        CHECK(ev[0].mode_after == 1);
        CHECK(ev[1].mode_after == 0);
        // the slip phase is the trapezoidal rule's: its end converges at second order
        double e = 0.0;
        for (std::size_t i = 1; i < ev.size(); ++i) e = std::max(e, std::abs(ev[i].time - b.switch_time(i)));
        stick_error.push_back(e);
        // captured: the same block as a contact of Moreau-Jean, its switches on the grid
        LinearMechanicalSystem s = b.system();
        s.contacts.push_back(PointContact{0, b.fs, b.fk, 0.0, 0.0});
        MoreauJeanOptions mo;
        mo.step = h;
        MoreauJean mj(s, mo, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
        mj.run(t_end);
        REQUIRE(mj.events().size() == 6);
        double ec = 0.0;
        for (std::size_t i = 0; i < 6; ++i) {
            // a switch lies inside the step that ends at the logged time
            const double logged = mj.events()[i].time;
            ec = std::max(ec, std::min(std::abs(logged - b.switch_time(i)), std::abs(logged - h - b.switch_time(i))));
        }
        captured_error.push_back(ec);
    }
    const double order = fitted_order(steps, stick_error);
    INFO("pulled block: located switches, order in h " << order << " (errors " << stick_error.front() << " .. "
         << stick_error.back() << " s); captured " << fitted_order(steps, captured_error));
    CHECK(order >= 1.8);
    for (std::size_t i = 0; i < steps.size(); ++i) CHECK(stick_error[i] < captured_error[i]);
}

TEST_CASE("mixed treatment: bad input names the parameter; a stopped run keeps its partial result",
          "[mixed][validation]") {
    const PulledBlock b;
    const auto make = [&](MoreauJeanEventsOptions o) {
        return [=] {
            (void)MoreauJeanEvents<LumpedFriction>(b.system(), {b.friction()}, o, Eigen::VectorXd::Zero(1),
                                                   Eigen::VectorXd::Zero(1));
        };
    };
    MoreauJeanEventsOptions o;
    o.time_tolerance = 0.0;
    CHECK(rejected_parameter(make(o)) == "time_tolerance");
    o.time_tolerance = std::nan("");
    CHECK(rejected_parameter(make(o)) == "time_tolerance");
    o = MoreauJeanEventsOptions{};
    o.max_location_iterations = 1;
    CHECK(rejected_parameter(make(o)) == "max_location_iterations");
    o = MoreauJeanEventsOptions{};
    o.max_switches = 0;
    CHECK(rejected_parameter(make(o)) == "max_switches");
    o = MoreauJeanEventsOptions{};
    o.steps.step = -1.0;
    CHECK(rejected_parameter(make(o)) == "step");
    o = MoreauJeanEventsOptions{};
    o.output_times = {1.0, 0.5};
    CHECK(rejected_parameter(make(o)) == "output_times");
    CHECK(rejected_parameter([] { (void)LumpedFriction(0, -1.0, [](double) { return 0.0; }); }) == "static_bound");
    CHECK(rejected_parameter([] { (void)LumpedFriction(0, 1.0, nullptr); }) == "kinetic_level");
    // a slip level above the static bound is caught when the block slips
    CHECK(rejected_parameter([&] {
              MoreauJeanEvents<LumpedFriction> d(b.system(), {LumpedFriction(0, b.fs, [](double) { return 11.0; })},
                                                 MoreauJeanEventsOptions{}, Eigen::VectorXd::Zero(1),
                                                 Eigen::VectorXd::Zero(1));
              d.run(2.0);
          }) == "kinetic_level");
    // the element's dof must carry a lumped mass
    CHECK(rejected_parameter([&] {
              LinearMechanicalSystem s;
              s.mass.resize(2, 2);
              s.mass.insert(0, 0) = 2.0;
              s.mass.insert(1, 1) = 2.0;
              s.mass.insert(0, 1) = 0.5;
              s.mass.insert(1, 0) = 0.5;
              (void)MoreauJeanEvents<LumpedFriction>(s, {b.friction()}, MoreauJeanEventsOptions{},
                                                     Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2));
          }) == "dof");
    CHECK(rejected_parameter(make(MoreauJeanEventsOptions{})) == "<nothing thrown>");

    // TorsionalString: its new field and run options
    const Case c(10, 0.1);
    TorsionalStringParams p = c.params;
    p.weight_on_bit = -1.0;
    CHECK(rejected_parameter([&] { (void)TorsionalString(DrillString({c.pipe}), p, 10, c.survey); }) ==
          "weight_on_bit");
    TorsionalStringRunOptions ro;
    ro.t_end = 1.0;
    ro.bit_treatment = BitTreatment::exact;
    ro.switch_tolerance = 0.0;
    CHECK(rejected_parameter([&] { (void)c.string().simulate(ro); }) == "switch_tolerance");
    ro.switch_tolerance = 1e-10;
    p = c.params;
    p.control_period = 0.01;
    const TorsionalString sampled(DrillString({c.pipe}), p, 10, c.survey);
    CHECK(rejected_parameter([&] { (void)sampled.simulate(ro); }) == "control_period");

    // the switch bound: the run stops at the third switch with everything up to the last accepted step
    MoreauJeanEventsOptions bounded;
    bounded.steps.step = 1e-3;
    bounded.max_switches = 2;
    bounded.output_times = grid(4.0, 0.1);
    MoreauJeanEvents<LumpedFriction> d(b.system(), {b.friction()}, bounded, Eigen::VectorXd::Zero(1),
                                       Eigen::VectorXd::Zero(1));
    std::vector<double> seen;
    double reached = -1.0;
    try {
        d.run(4.0, [&](double t, const Eigen::VectorXd&, const Eigen::VectorXd&) { seen.push_back(t); });
    } catch (const ChatteringError& e) {
        reached = e.time_reached();
        CHECK(e.switching_function() == "block");
    }
    REQUIRE(reached > 0.0);
    CHECK(d.time() == reached);
    REQUIRE(d.events().size() == 2);
    CHECK(d.events()[0].time == Approx(b.first_release()).margin(1e-9));
    CHECK(d.events()[1].time == Approx(b.switch_time(1)).margin(1e-4));
    CHECK(reached == Approx(b.switch_time(2)).margin(1.5e-3));  // the step before the third switch
    REQUIRE(!seen.empty());
    CHECK(seen.back() <= reached);
    CHECK(seen.back() > reached - 0.1 - 1e-9);
    CHECK(d.statistics().lumped_switches == 2);
}
