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
#include <string>
#include <vector>

#include "catch.hpp"
#include "convergence.hpp"
#include "frictionsim/string/string_rig.hpp"
#include "frictionsim/string/torsional_string.hpp"
#include "frictionsim/string/treatment.hpp"
#include "frictionsim/string/exact_string.hpp"
#include "frictionsim/friction/coulomb.hpp"
#include "frictionsim/simulate.hpp"
#include "frictionsim/eigen/moreau_jean_events.hpp"
#include "rejection.hpp"

using namespace frictionsim;
using frictionsim::test::fitted_order;
using frictionsim::test::grid;

namespace {

/// The same string on the event-driven engine: string/exact_string.hpp (its bit with node N's wall, one contact).
using Rig = ExactStringOnBottom;

/// 1000 m of 5" pipe, vertical to 200 m then building to 60 degrees at 500 m (node 0, the top drive's, has no wall
/// friction: StringRig has none there), Coulomb walls mu_s = `mu`, kinetic 2/3 of it, at every other node, a 300 kg
/// m^2 top drive under PI (3e3, 1e3) at 4 rad/s, a 40 kg m^2 BHA, the velocity-weakening bit (Navarro-Lopez's
/// defaults) under 60 kN, no damping: stick-slip of the bit.
struct Case {
    static constexpr double weight = 6e4;
    PipeSection pipe;
    TorsionalStringParams params;
    Survey survey{{{0.0, 0.0, 0.0}, {200.0, 0.0, 0.0}, {500.0, pi / 3.0, 0.0}}};
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
    }
    TorsionalString string() const { return TorsionalString(DrillString({pipe}), params, elements, survey); }
    /// The same physics on the event-driven engine (exact_string.hpp: normal forces such that mu_s N_i r_i is the
    /// string's bound).
    Rig rig(const TorsionalString& ts) const { return exact_string_on_bottom(ts); }
};

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
          "[mixed][heavy]") {
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

TEST_CASE("one string, two treatments: StringRig exact and the captured string agree as h -> 0 (same damping, "
          "drive, walls - the same mode column)", "[mixed][treatments]") {
    // 1000 m of 5" pipe in Case's well, off bottom, Coulomb walls mu_s 0.3 (kinetic 0.6 of it) at every node below
    // the vertical top, the PI stepped to 4 rad/s, and StringRig's element damping beta k_e in both models: all walls
    // stuck at first, the string breaks off, overshoots and settles to sliding. The exact model locates every wall's
    // release (Dormand-Prince, 1e-10); the captured one is Moreau-Jean at step h.
    const std::size_t n = 16;
    const double beta = 2e-3, mu = 0.3, f_rat = 0.6;
    Case c(n, mu);
    c.params.weight_on_bit = 0.0;
    c.params.kinetic_ratio = f_rat;
    c.params.damping_time = beta;
    c.params.gravity = 9.80665;  // StringRig's
    c.params.mud_density = 1200.0;
    const TorsionalString ts = c.string();
    const ExactString rig = exact_string(ts);  // the exact treatment of the same string
    const StringRigParams& p = rig.params();
    CHECK(rig.contact_nodes() == ts.wall_contact_nodes());  // node 0 is vertical: no wall there in either model

    CHECK(p.damping_time == beta);
    // the same damping: C's element entries are beta k_e, as the rig's dampers
    const LinearMechanicalSystem sys = ts.system();
    for (std::size_t e = 0; e < n; ++e) {
        const auto a = static_cast<Eigen::Index>(e);
        CHECK(-sys.damping.coeff(a + 1, a) == Approx(beta * rig.lumped().torsional_stiffness[e]).epsilon(1e-14));
    }
    REQUIRE(ts.contact_count() == rig.contact_count());

    const double t_end = 30.0;
    SolverOptions o;
    o.rtol = o.atol = 1e-10;
    o.output_times = grid(t_end, 0.01);
    const Result ref = simulate(rig, t_end, o);
    REQUIRE(ref.completed);
    const auto motor = [&](std::size_t row) {  // PiTopDrive's k_p e + k_i int e, the limit never reached
        return p.proportional_gain * (p.surface_speed - ref.state(row, rig.omega(0))) +
               p.integral_gain * ref.state(row, rig.drive_state(0));
    };
    double ref_peak = 0.0;
    for (std::size_t row = 0; row < ref.rows(); ++row) ref_peak = std::max(ref_peak, ref.state(row, rig.omega(n)));
    CHECK(ref.mode.front() == static_cast<int>(rig.contact_count()));  // all stuck, then all sliding
    CHECK(ref.mode.back() == 0);

    struct Run {
        double peak = 0.0, speed_rms = 0.0, torque_rms = 0.0;
        std::size_t mode_rows_equal = 0;
    };
    const auto captured = [&](const TorsionalString& model, double h) {
        SolverOptions m;
        m.method = Method::moreau_jean;
        m.step = h;
        m.output_times = o.output_times;
        const Result r = simulate(model, t_end, m);
        REQUIRE(r.rows() == ref.rows());
        Run out;
        const std::size_t bit = r.column("bit_speed"), torque = r.column("motor_torque");
        for (std::size_t row = 0; row < r.rows(); ++row) {
            out.peak = std::max(out.peak, r.state(row, bit));
            const double dw = r.state(row, bit) - ref.state(row, rig.omega(n));
            const double dt = r.state(row, torque) - motor(row);
            out.speed_rms += dw * dw;
            out.torque_rms += dt * dt;
            out.mode_rows_equal += r.mode[row] == ref.mode[row] ? 1 : 0;
        }
        out.speed_rms = std::sqrt(out.speed_rms / static_cast<double>(r.rows()));
        out.torque_rms = std::sqrt(out.torque_rms / static_cast<double>(r.rows()));
        return out;
    };
    const std::vector<double> steps{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4};
    std::vector<double> speed_error, torque_error;
    Run last;
    for (double h : steps) {
        last = captured(ts, h);
        speed_error.push_back(last.speed_rms);
        torque_error.push_back(last.torque_rms);
    }
    const double speed_order = fitted_order(steps, speed_error), torque_order = fitted_order(steps, torque_error);
    INFO("bit peak " << ref_peak << " rad/s; captured at h = 0.25 ms " << last.peak << "; RMS bit speed error "
         << speed_error.front() << " -> " << speed_error.back() << " (order " << speed_order << "), motor torque "
         << torque_error.front() << " -> " << torque_error.back() << " N m (order " << torque_order << ")");
    // measured: speed order 1.37, torque order 1.34 (first order at least, as a captured Coulomb contact is);
    // the bit's peak within 1e-5 relative at h = 0.25 ms
    CHECK(speed_order > 1.0);
    CHECK(torque_order > 0.9);
    CHECK(last.peak == Approx(ref_peak).epsilon(1e-5));
    CHECK(speed_error.back() < 2e-5);  // rad/s, against a peak of 6.8
    CHECK(last.mode_rows_equal == ref.rows());  // the same stuck-wall count on every row
    // and the damping is what makes them agree: without beta the captured string's peak is off by far more
    TorsionalStringParams undamped = c.params;
    undamped.damping_time = 0.0;
    const TorsionalString plain(DrillString({c.pipe}), undamped, n, c.survey);
    CHECK(std::abs(captured(plain, 2.5e-4).peak - ref_peak) > 1e3 * std::abs(last.peak - ref_peak));
}

TEST_CASE("one string, two treatments with A&S's k_t and a ramped set-point: StringRig exact and the captured "
          "string agree as h -> 0", "[mixed][treatments][damping_rate]") {
    // The string of the case above with Aarsnes & Shor's viscous damping k_t (damping_rate: k_t times each node's
    // string inertia against absolute rotation) and the set-point ramped from rest, omega_SP (1 - exp(-t / T_SP)),
    // both now carried by StringRig (exact_string maps them): the captured string converges to it as h falls.
    const std::size_t n = 16;
    const double beta = 2e-3, kt = 0.05, T = 1.0;
    Case c(n, 0.3);
    c.params.weight_on_bit = 0.0;
    c.params.kinetic_ratio = 0.6;
    c.params.damping_time = beta;
    c.params.damping_rate = kt;
    c.params.setpoint_time_constant = T;
    c.params.gravity = 9.80665;
    c.params.mud_density = 1200.0;
    const TorsionalString ts = c.string();
    const ExactString rig = exact_string(ts);
    const StringRigParams& p = rig.params();
    CHECK(p.damping_rate == kt);
    CHECK(p.setpoint_time_constant == T);
    // the same damping: C(i, i) is the elements' beta k_e, the PI's k_p at the top and k_t J_s,i
    const LinearMechanicalSystem sys = ts.system();
    const std::vector<double>& k = rig.lumped().torsional_stiffness;
    for (std::size_t i = 0; i <= n; ++i) {
        const auto a = static_cast<Eigen::Index>(i);
        const double elements = beta * ((i > 0 ? k[i - 1] : 0.0) + (i < n ? k[i] : 0.0));
        const double drive = i == 0 ? p.proportional_gain : 0.0;
        CHECK(sys.damping.coeff(a, a) - elements - drive ==
              Approx(kt * rig.lumped().node_inertia[i]).epsilon(1e-9));
    }
    const double t_end = 30.0;
    SolverOptions o;
    o.rtol = o.atol = 1e-10;
    o.output_times = grid(t_end, 0.01);
    const Result ref = simulate(rig, t_end, o);
    REQUIRE(ref.completed);
    const auto motor = [&](std::size_t row) {  // k_p (w_set(t) - w_0) + k_i int e, the set speed the captured one's
        return p.proportional_gain * (ts.setpoint_speed(ref.t[row]) - ref.state(row, rig.omega(0))) +
               p.integral_gain * ref.state(row, rig.drive_state(0));
    };
    double ref_peak = 0.0;
    for (std::size_t row = 0; row < ref.rows(); ++row) ref_peak = std::max(ref_peak, ref.state(row, rig.omega(n)));
    CHECK(ref.mode.front() == static_cast<int>(rig.contact_count()));
    struct Run {
        double peak = 0.0, speed_rms = 0.0, torque_rms = 0.0;
    };
    const auto captured = [&](double h) {
        SolverOptions m;
        m.method = Method::moreau_jean;
        m.step = h;
        m.output_times = o.output_times;
        const Result r = simulate(ts, t_end, m);
        REQUIRE(r.rows() == ref.rows());
        Run out;
        const std::size_t bit = r.column("bit_speed"), torque = r.column("motor_torque");
        for (std::size_t row = 0; row < r.rows(); ++row) {
            out.peak = std::max(out.peak, r.state(row, bit));
            const double dw = r.state(row, bit) - ref.state(row, rig.omega(n));
            const double dt = r.state(row, torque) - motor(row);
            out.speed_rms += dw * dw;
            out.torque_rms += dt * dt;
        }
        out.speed_rms = std::sqrt(out.speed_rms / static_cast<double>(r.rows()));
        out.torque_rms = std::sqrt(out.torque_rms / static_cast<double>(r.rows()));
        return out;
    };
    const std::vector<double> steps{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4};
    std::vector<double> speed_error, torque_error;
    Run last;
    for (double h : steps) {
        last = captured(h);
        speed_error.push_back(last.speed_rms);
        torque_error.push_back(last.torque_rms);
    }
    const double speed_order = fitted_order(steps, speed_error), torque_order = fitted_order(steps, torque_error);
    INFO("bit peak " << ref_peak << " rad/s; captured at h = 0.25 ms " << last.peak << "; RMS bit speed error "
         << speed_error.front() << " -> " << speed_error.back() << " (order " << speed_order << "), motor torque "
         << torque_error.front() << " -> " << torque_error.back() << " N m (order " << torque_order << ")");
    // measured: speed order 1.15, torque order 1.14 (RMS bit speed 1.6e-4 -> 7.2e-6 rad/s, motor torque 0.084 ->
    // 0.0039 N m from h = 4 to 0.25 ms); the bit's peak 4.7866 rad/s within 2e-6 relative at h = 0.25 ms
    CHECK(speed_order > 1.0);
    CHECK(torque_order > 1.0);
    CHECK(last.peak == Approx(ref_peak).epsilon(1e-5));
    CHECK(speed_error.back() < 2e-5);
}

TEST_CASE("one string, two treatments: a prescribed ramped top-drive speed with k_t, StringRig exact and the "
          "captured string agree as h -> 0", "[mixed][treatments][damping_rate]") {
    // The string above held at the top on omega_SP (1 - exp(-t / T_SP)) (StringRig's PrescribedSpeed with its ramp,
    // node 0's acceleration prescribed; the captured string's node 0 held out of the inclusion), k_t and beta k_e in
    // both: the walls break off as the speed comes up; the bit's speed converges as h falls.
    const std::size_t n = 16;
    Case c(n, 0.3);
    c.params.weight_on_bit = 0.0;
    c.params.kinetic_ratio = 0.6;
    c.params.damping_time = 2e-3;
    c.params.damping_rate = 0.05;
    c.params.setpoint_time_constant = 1.0;
    c.params.gravity = 9.80665;
    c.params.mud_density = 1200.0;
    TorsionalString ts = c.string();
    ts.set_top_drive(TopDrive::prescribed_speed);
    const ExactString rig = exact_string(ts);
    REQUIRE(rig.setup().top_drive == TopDrive::prescribed_speed);
    CHECK(rig.params().setpoint_time_constant == 1.0);
    const double t_end = 20.0;
    SolverOptions o;
    o.rtol = o.atol = 1e-10;
    o.output_times = grid(t_end, 0.01);
    const Result ref = simulate(rig, t_end, o);
    REQUIRE(ref.completed);
    CHECK(ref.events.size() >= rig.contact_count());  // every wall breaks off
    for (std::size_t row = 0; row < ref.rows(); ++row)
        CHECK(ref.state(row, rig.omega(0)) == Approx(ts.setpoint_speed(ref.t[row])).margin(1e-8));
    double ref_peak = 0.0;
    for (std::size_t row = 0; row < ref.rows(); ++row) ref_peak = std::max(ref_peak, ref.state(row, rig.omega(n)));
    const std::vector<double> steps{4e-3, 2e-3, 1e-3, 5e-4};
    std::vector<double> speed_error;
    double peak = 0.0;
    for (double h : steps) {
        SolverOptions m;
        m.method = Method::moreau_jean;
        m.step = h;
        m.output_times = o.output_times;
        const Result r = simulate(ts, t_end, m);
        REQUIRE(r.rows() == ref.rows());
        const std::size_t bit = r.column("bit_speed");
        double sum = 0.0;
        peak = 0.0;
        for (std::size_t row = 0; row < r.rows(); ++row) {
            const double dw = r.state(row, bit) - ref.state(row, rig.omega(n));
            sum += dw * dw;
            peak = std::max(peak, r.state(row, bit));
        }
        speed_error.push_back(std::sqrt(sum / static_cast<double>(r.rows())));
    }
    const double order = fitted_order(steps, speed_error);
    INFO("bit peak " << ref_peak << " rad/s, captured at h = 0.5 ms " << peak << "; RMS bit speed error "
         << speed_error.front() << " -> " << speed_error.back() << " (order " << order << ")");
    // measured: RMS bit speed 8.6e-4 -> 1.4e-4 rad/s over h = 4 .. 0.5 ms (order 0.97), the peak 6.0561 rad/s
    // within 4e-5 relative at h = 0.5 ms
    CHECK(order > 0.9);
    CHECK(peak == Approx(ref_peak).epsilon(1e-4));
    CHECK(speed_error.back() < 2e-4);
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

TEST_CASE("mixed treatment: bad input names the parameter - a stopped run keeps its partial result",
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

// ---- One entry point (issue 22 item 1): simulate(TorsionalString, t_end, SolverOptions) ----

namespace {

long whole_steps(double interval, double step) { return std::lround(interval / step); }

/// The run loop TorsionalString::simulate had before simulate() reached the string (frozen here, read from its
/// public interface), so that the one loop of solve/time_stepping.hpp is checked against it bit for bit.
TorsionalStringRun legacy_run(const TorsionalString& ts, const TorsionalStringRunOptions& run) {
    const long per_output = whole_steps(run.output_interval, run.step);
    const TorsionalStringParams& p = ts.params();
    const bool sampled = p.control_period > 0.0;
    const long per_control = sampled ? whole_steps(p.control_period, run.step) : 0;
    const Eigen::Index n = static_cast<Eigen::Index>(ts.nodes());
    const long total = std::lround(run.t_end / run.step);
    TorsionalStringRun out;
    const auto stuck_fraction = [&](const Eigen::VectorXd& v) {
        Eigen::Index stuck = 0;
        for (Eigen::Index i = 0; i < n; ++i)
            stuck += (run.slow_speed > 0.0 ? std::abs(v(i)) < run.slow_speed : v(i) == 0.0) ? 1 : 0;
        return static_cast<double>(stuck) / static_cast<double>(n);
    };
    if (ts.bit_on_bottom() && run.bit_treatment == BitTreatment::exact) {
        MoreauJeanEventsOptions o;
        o.steps.step = run.step;
        o.steps.theta = run.theta;
        o.steps.treatment = run.treatment;
        o.steps.projection_band = run.projection_band;
        o.time_tolerance = run.switch_tolerance;
        for (long k = 0; k <= total; k += per_output) o.output_times.push_back(static_cast<double>(k) * run.step);
        MoreauJeanEvents<LumpedFriction> driver(ts.system(nullptr, false), {ts.bit_element()}, std::move(o),
                                                Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
        driver.run(static_cast<double>(total) * run.step,
                   [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
                       out.time.push_back(t);
                       out.bit_speed.push_back(v(n - 1));
                       out.top_drive_speed.push_back(v(0));
                       out.motor_torque.push_back(p.proportional_gain * (ts.setpoint_speed(t) - v(0)) +
                                                  p.integral_gain * (ts.setpoint_angle(t) - q(0)));
                       out.stuck_fraction.push_back(stuck_fraction(v));
                   });
        for (const LumpedEvent& e : driver.events()) {
            if (e.mode_after == 0) out.bit_stick_times.push_back(e.time);
            if (e.mode_before == 0) out.bit_release_times.push_back(e.time);
        }
        const auto stats = driver.statistics();
        out.statistics = stats.steps;
        out.bit_location_trials = stats.trial_steps;
        return out;
    }
    MoreauJeanOptions o;
    o.step = run.step;
    o.theta = run.theta;
    o.treatment = run.treatment;
    o.projection_band = run.projection_band;
    o.record_events = false;
    double held = 0.0, setpoint = 0.0, integral = 0.0;
    MoreauJean mj(ts.system(sampled ? &held : nullptr), o, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
    const std::size_t bit_contact = mj.system().contacts.size() - 1;
    Eigen::VectorXd scratch;
    for (long k = 0;; ++k) {
        const double t = mj.time();
        const Eigen::VectorXd& v = mj.velocities();
        if (sampled && k % per_control == 0) {
            const double dt = p.control_period, T = p.setpoint_time_constant;
            setpoint = T > 0.0 ? setpoint + (p.speed_setpoint - setpoint) * dt / T : p.speed_setpoint;
            held = p.proportional_gain * (setpoint - v(0)) + p.integral_gain * integral;
            integral += dt * (setpoint - v(0));
        }
        if (k % per_output == 0) {
            out.time.push_back(t);
            out.bit_speed.push_back(v(n - 1));
            out.top_drive_speed.push_back(v(0));
            out.motor_torque.push_back(sampled ? held
                                               : p.proportional_gain * (ts.setpoint_speed(t) - v(0)) +
                                                     p.integral_gain * (ts.setpoint_angle(t) - mj.positions()(0)));
            out.stuck_fraction.push_back(stuck_fraction(v));
        }
        if (k == total) break;
        if (ts.bit_on_bottom()) {
            const double w = v(n - 1);
            double level = ts.bit_kinetic_torque(w);
            if (w != 0.0) {
                const MechanicalView at(t, mj.positions(), v, mj.contact_forces(), mj.system(), scratch);
                const double dir = w > 0.0 ? 1.0 : -1.0;
                const double mid = w + 0.5 * run.step * (at.load(ts.nodes() - 1) - dir * level) /
                                           mj.system().mass.coeff(n - 1, n - 1);
                level = ts.bit_kinetic_torque(std::max(0.0, dir * mid));
            }
            mj.set_contact_bounds(bit_contact, ts.bit_static_torque(), level);
            mj.step();
            const double after = mj.velocities()(n - 1);
            if (w != 0.0 && after == 0.0) out.bit_stick_times.push_back(mj.time());
            if (w == 0.0 && after != 0.0) out.bit_release_times.push_back(mj.time() - run.step);
        } else {
            mj.step();
        }
    }
    out.statistics = mj.statistics();
    return out;
}

/// simulate(model, ...) with the run's settings, its rows at the legacy run's output times.
Result entry_point_run(TorsionalString model, const TorsionalStringRunOptions& run, const std::vector<double>& times) {
    model.set_slow_speed(run.slow_speed).set_bit_treatment(run.bit_treatment, run.switch_tolerance);
    SolverOptions o;
    o.method = run.treatment == ContactTreatment::projection ? Method::explicit_projection : Method::moreau_jean;
    o.step = run.step;
    o.theta = run.theta;
    o.projection_band = run.projection_band;
    o.output_times = times;
    // the legacy captured loop counted its steps: its last row is at the time they add up to (t_end to rounding)
    const double t_end = std::max(static_cast<double>(std::lround(run.t_end / run.step)) * run.step, times.back());
    return simulate(model, t_end, o);
}

std::vector<double> switch_times(const Result& r, bool stick) {
    std::vector<double> t;
    for (const Event& e : r.events)
        if ((stick ? e.mode_after : e.mode_before) == 0) t.push_back(e.time);
    return t;
}

TorsionalString well_b_string(std::size_t elements, double control_period) {
    WellBCase w = aarsnes_shor_well_b(CollarPolarMoment::as_published, CollarWaveSpeed::as_code);
    w.params.control_period = control_period;
    return TorsionalString(w.string, w.params, elements, w.survey, w.contact_radius);
}

}  // namespace

TEST_CASE("one entry point: simulate(TorsionalString) equals the earlier run loop bit for bit", "[mixed][entry]") {
    struct Setting {
        const char* name;
        TorsionalString model;
        TorsionalStringRunOptions run;
    };
    std::vector<Setting> settings;
    TorsionalStringRunOptions off;
    off.t_end = 20.0;
    off.slow_speed = 1.5;
    settings.push_back({"Well B off bottom, sampled PI", well_b_string(60, 0.01), off});
    off.slow_speed = 0.0;
    settings.push_back({"Well B off bottom, continuous PI", well_b_string(60, 0.0), off});
    off.step = 2e-3;
    off.slow_speed = 1.5;
    off.treatment = ContactTreatment::projection;
    off.projection_band = 1.5;
    settings.push_back({"Well B off bottom, explicit projection", well_b_string(60, 0.01), off});
    const Case c(16, 0.1);
    TorsionalStringRunOptions on;
    on.t_end = 10.0;
    on.output_interval = 0.02;
    settings.push_back({"bit on bottom, captured, continuous PI", c.string(), on});
    on.bit_treatment = BitTreatment::exact;
    settings.push_back({"bit on bottom, exact (mixed), continuous PI", c.string(), on});
    on.bit_treatment = BitTreatment::captured;
    on.theta = 0.75;
    Case sampled_case(16, 0.1);
    sampled_case.params.control_period = 0.01;
    settings.push_back({"bit on bottom, captured, sampled PI, theta 0.75", sampled_case.string(), on});

    for (const Setting& s : settings) {
        INFO(s.name);
        const TorsionalStringRun legacy = legacy_run(s.model, s.run);
        REQUIRE(legacy.time.size() > 100);
        const Result r = entry_point_run(s.model, s.run, legacy.time);
        REQUIRE(r.completed);
        CHECK(r.status == 0);
        CHECK(r.t == legacy.time);
        CHECK(r.column_values("bit_speed") == legacy.bit_speed);
        CHECK(r.column_values("top_drive_speed") == legacy.top_drive_speed);
        CHECK(r.column_values("motor_torque") == legacy.motor_torque);
        CHECK(r.column_values("stuck_fraction") == legacy.stuck_fraction);
        CHECK(r.stats.steps == legacy.statistics.steps);
        CHECK(r.stats.factorisations == legacy.statistics.factorisations);
        CHECK(r.stats.linear_solves == legacy.statistics.solves);
        CHECK(r.stats.contact_switches == legacy.statistics.contact_switches);
        CHECK(r.stats.location_trials == legacy.bit_location_trials);
        if (s.model.bit_on_bottom()) {
            REQUIRE(legacy.bit_stick_times.size() >= 3);  // the bit is in stick-slip
            CHECK(switch_times(r, true) == legacy.bit_stick_times);
            CHECK(switch_times(r, false) == legacy.bit_release_times);
        }
        // the mode column is StringRig's: the wall contacts at rest, each also counted in stuck_fraction
        const double nodes = static_cast<double>(s.model.nodes());
        for (std::size_t row = 0; row < r.rows(); ++row) {
            CHECK(r.mode[row] >= 0);
            CHECK(static_cast<std::size_t>(r.mode[row]) <= s.model.contact_count());
            CHECK(r.mode[row] <= std::lround(r.state(row, r.column("stuck_fraction")) * nodes));
        }
        // the earlier interface is a thin wrapper over the same loop: its rows at k * output_interval
        const TorsionalStringRun wrapped = s.model.simulate(s.run);
        REQUIRE(wrapped.time.size() == legacy.time.size());
        for (std::size_t row = 0; row < wrapped.time.size(); ++row) {
            CHECK(wrapped.time[row] == Approx(legacy.time[row]).margin(1e-9));
            CHECK(wrapped.bit_speed[row] == Approx(legacy.bit_speed[row]).margin(1e-9));
        }
        CHECK(wrapped.bit_stick_times == legacy.bit_stick_times);
        CHECK(wrapped.statistics.steps == legacy.statistics.steps);
    }
}

TEST_CASE("one entry point: stop conditions on the string, located between step ends", "[mixed][entry]") {
    const Case c(16, 0.1);
    TorsionalString exact = c.string();
    exact.set_bit_treatment(BitTreatment::exact);
    SolverOptions o;  // automatic: moreau_jean for a time-stepping model
    o.output_times = grid(10.0, 0.02);
    const Result full = simulate(exact, 10.0, o);
    REQUIRE(full.completed);
    const std::vector<double> sticks = switch_times(full, true);
    REQUIRE(sticks.size() >= 3);
    CHECK(full.stats.location_trials > 0);

    // a switch into the bit's stick: the run ends at the exact treatment's located first stick
    SolverOptions stop = o;
    stop.stop_conditions = {StopCondition{"", 0.0, 0, "stick", true, "bit sticks"}};
    const Result by_mode = simulate(exact, 10.0, stop);
    CHECK(by_mode.completed);
    CHECK(by_mode.status == 1);
    REQUIRE(by_mode.stop_events.size() == 1);
    CHECK(by_mode.stop_events[0].time == sticks[0]);
    CHECK(by_mode.t_reached == sticks[0]);
    CHECK(by_mode.t.back() == sticks[0]);
    CHECK(by_mode.states[by_mode.states.size() - 4] == 0.0);  // bit_speed at rest in the last row

    // the bit's speed falling to 0: the crossing is located at the same instant (the speed is 0 exactly there)
    stop.stop_conditions = {StopCondition{"bit_speed", 0.0, -1, "", true, ""}};
    const Result by_state = simulate(exact, 10.0, stop);
    CHECK(by_state.status == 1);
    REQUIRE(by_state.stop_events.size() == 1);
    CHECK(by_state.stop_events[0].time == sticks[0]);
    CHECK(by_state.t_reached == sticks[0]);

    // a level between step ends: linear interpolation of the columns of the two steps around it
    TorsionalString captured = c.string();
    SolverOptions every_step;  // no output_times: a row at every step end
    const Result steps = simulate(captured, 10.0, every_step);
    REQUIRE(steps.rows() == 10001);
    const std::size_t w = steps.column("bit_speed");
    const double level = 2.0;
    std::vector<double> rising;  // the crossings from the rows, by the same interpolation
    for (std::size_t k = 0; k + 1 < steps.rows(); ++k) {
        const double a = steps.state(k, w) - level, b = steps.state(k + 1, w) - level;
        if (a < 0.0 && b >= 0.0) rising.push_back(steps.t[k] + (steps.t[k + 1] - steps.t[k]) * (-a) / (b - a));
    }
    REQUIRE(rising.size() >= 3);
    SolverOptions logged = o;
    logged.stop_conditions = {StopCondition{"bit_speed", level, +1, "", false, ""}};
    const Result logged_run = simulate(captured, 10.0, logged);
    CHECK(logged_run.status == 0);
    REQUIRE(logged_run.stop_events.size() == rising.size());
    for (std::size_t i = 0; i < rising.size(); ++i) {
        CHECK(logged_run.stop_events[i].time == Approx(rising[i]).margin(1e-12));
        CHECK(logged_run.stop_events[i].direction == 1);
        CHECK(logged_run.stop_events[i].name == "bit_speed = 2");
    }
    logged.stop_conditions[0].terminal = true;
    const Result ended = simulate(captured, 10.0, logged);
    CHECK(ended.status == 1);
    CHECK(ended.t_reached == Approx(rising[0]).margin(1e-12));
    CHECK(ended.state(ended.rows() - 1, w) == Approx(level).epsilon(1e-9));  // the row where it holds
    CHECK(ended.t[ended.rows() - 2] < rising[0]);  // the outputs before it, none after
}

TEST_CASE("one entry point: timeout, interrupt and max_output_rows keep a partial result", "[mixed][entry]") {
    const TorsionalString string = well_b_string(1000, 0.01);  // field resolution: ~1e4 steps per wall-clock s here
    SolverOptions o;
    o.output_times = grid(150.0, 0.01);
    // timeout: the budget ends the run, everything up to the time reached kept
    o.timeout = 0.2;
    double reached = -1.0;
    try {
        (void)simulate(string, 150.0, o);
    } catch (const BudgetExceeded& e) {
        CHECK(e.budget() == "timeout");
        reached = e.time_reached();
        REQUIRE(e.partial());
        CHECK(!e.partial()->completed);
        CHECK(e.partial()->status == -1);
        CHECK(e.partial()->t_reached == reached);
        REQUIRE(e.partial()->rows() > 1);
        CHECK(e.partial()->t.back() <= reached + 1e-12);  // an output within 1e-9 h of a step end is taken there
        CHECK(e.partial()->t.back() > reached - 0.01 - 1e-9);
        CHECK(e.partial()->stats.steps == std::lround(reached / o.step));
    }
    CHECK(reached > 0.0);
    CHECK(reached < 150.0);

    // interrupt (the bindings' Ctrl-C): polled between steps; the first true stops the run
    o.timeout = std::numeric_limits<double>::infinity();
    int polls = 0;
    o.interrupt = [&] { return ++polls >= 3; };
    reached = -1.0;
    try {
        (void)simulate(string, 150.0, o);
    } catch (const Interrupted& e) {
        reached = e.time_reached();
        REQUIRE(e.partial());
        CHECK(e.partial()->t_reached == reached);
        CHECK(e.partial()->t.back() <= reached + 1e-12);
        CHECK(e.partial()->message.find("interrupted") != std::string::npos);
    }
    CHECK(polls == 3);
    CHECK(reached > 0.0);
    CHECK(reached < 150.0);

    // max_output_rows: every step recorded, the run stops at the cap with the rows it has
    const Case c(16, 0.1);
    SolverOptions capped;
    capped.max_output_rows = 50;
    try {
        (void)simulate(c.string(), 10.0, capped);
        FAIL("max_output_rows did not stop the run");
    } catch (const BudgetExceeded& e) {
        CHECK(e.budget() == "max_output_rows");
        REQUIRE(e.partial());
        CHECK(e.partial()->rows() == 50);
        CHECK(e.time_reached() == e.partial()->t.back());
    }
}

TEST_CASE("one entry point: options that do not fit the model are refused, naming the option", "[mixed][entry]") {
    const Case c(10, 0.1);
    const TorsionalString string = c.string();
    const auto run = [&](SolverOptions o, double t_end = 1.0) { return [&string, o, t_end] { (void)simulate(string, t_end, o); }; };
    SolverOptions o;
    o.method = Method::dormand_prince;  // an ODE method on the time-stepping model
    CHECK(rejected_parameter(run(o)) == "method");
    o.method = Method::cvode_bdf;
    CHECK(rejection_message(run(o)).find("moreau_jean or explicit_projection") != std::string::npos);
    o = SolverOptions{};
    o.step = 0.0;
    CHECK(rejected_parameter(run(o)) == "step");
    o.step = -1e-3;
    CHECK(rejected_parameter(run(o)) == "step");
    o.step = 1e-3;
    o.output_times = grid(1.0, 5e-4);  // the step larger than the output interval
    CHECK(rejection_message(run(o)).find("not larger than the output interval") != std::string::npos);
    o.output_times.clear();
    o.step = 3e-3;  // 1 s is not a whole number of steps
    CHECK(rejected_parameter(run(o)) == "step");
    o.step = 1e-3;
    o.theta = 0.3;
    CHECK(rejected_parameter(run(o)) == "theta");
    o.theta = 0.5;
    o.stop_conditions = {StopCondition{"bit_angle", 1.0, 0, "", true, ""}};
    CHECK(rejected_parameter(run(o)) == "stop_conditions.state");
    o.stop_conditions.clear();
    o.timeout = 0.0;
    CHECK(rejected_parameter(run(o)) == "timeout");
    o.timeout = std::numeric_limits<double>::infinity();
    CHECK(rejected_parameter(run(o, -1.0)) == "t_end");

    // Method::moreau_jean on an event-driven rig
    SolverOptions mj;
    mj.method = Method::moreau_jean;
    const Rig rig = c.rig(string);
    CHECK(rejected_parameter([&] { (void)simulate(rig, 1.0, mj); }) == "method");
    mj.method = Method::explicit_projection;
    CHECK(rejection_message([&] { (void)simulate(rig, 1.0, mj); }).find("an ODE method") != std::string::npos);

    // the model's own settings
    TorsionalString m = c.string();
    CHECK(rejected_parameter([&] { m.set_bit_treatment(BitTreatment::exact, 0.0); }) == "switch_tolerance");
    CHECK(rejected_parameter([&] { m.set_slow_speed(-1.0); }) == "slow_speed");
    Case sampled(10, 0.1);
    sampled.params.control_period = 0.01;
    TorsionalString sampled_exact = sampled.string();
    sampled_exact.set_bit_treatment(BitTreatment::exact);
    CHECK(rejected_parameter([&] { (void)simulate(sampled_exact, 1.0, SolverOptions{}); }) == "control_period");
    SolverOptions coarse;
    coarse.step = 4e-3;  // 0.01 s is not a whole number of 4 ms steps
    CHECK(rejected_parameter([&] { (void)simulate(sampled.string(), 1.0, coarse); }) == "control_period");
}

namespace {

/// A user's own time-stepping model (the concept of solve/time_stepping.hpp): x' = a x by explicit Euler from
/// x = 1, so the rows are (1 + a h)^k at the step ends and linear in between.
struct EulerGrowth {
    static constexpr bool time_stepping = true;
    double rate = 1.0;
    std::vector<std::string> state_names() const { return {"x"}; }
    const char* mode_name(int) const { return "growing"; }
    struct Stepper {
        double a, h, t, x, t0, x0;
        std::vector<Event> log;
        double time() const { return t; }
        bool finished(double t_end) const { return t + 0.5 * h >= t_end; }
        void step(double, bool) {
            t0 = t;
            x0 = x;
            x += h * a * x;
            t += h;
        }
        int row(double at, double* out) const {
            const double s = t > t0 ? std::clamp((at - t0) / (t - t0), 0.0, 1.0) : 1.0;
            out[0] = (1.0 - s) * x0 + s * x;
            return 1;
        }
        double friction_force() const { return 0.0; }
        const std::vector<Event>& events() const { return log; }
        void add_stats(SolverStats& stats) const { stats.steps = std::lround((t - t0) / h); }
    };
    Stepper make_stepper(const TimeStepping& s) const { return Stepper{rate, s.step, s.t_start, 1.0, s.t_start, 1.0, {}}; }
};

}  // namespace

TEST_CASE("one entry point: a user's own time-stepping model - non-finite states and max_steps stop the run",
          "[mixed][entry]") {
    const EulerGrowth model;
    SolverOptions o;  // automatic: moreau_jean's loop; the model ignores what it does not use
    o.step = 0.1;
    o.output_times = {0.05, 0.5, 0.85, 1.0};
    const Result r = simulate(model, 1.0, o);
    REQUIRE(r.rows() == 4);
    CHECK(r.states[0] == Approx(1.05).epsilon(1e-14));                                          // inside step 1
    CHECK(r.states[1] == Approx(std::pow(1.1, 5)).epsilon(1e-12));                              // a step end
    CHECK(r.states[2] == Approx(0.5 * (std::pow(1.1, 8) + std::pow(1.1, 9))).epsilon(1e-12));  // mid step 9
    CHECK(r.states[3] == Approx(std::pow(1.1, 10)).epsilon(1e-12));
    CHECK(r.mode == std::vector<int>(4, 1));
    CHECK(r.t_reached == 1.0);

    // overflow: the rows up to the last finite one are kept, the run fails at it (NaN / inf never success)
    EulerGrowth huge;
    huge.rate = 1e300;
    SolverOptions every;
    every.step = 1.0;
    try {
        (void)simulate(huge, 10.0, every);
        FAIL("a non-finite state did not stop the run");
    } catch (const SimulationError& e) {
        CHECK(std::string(e.what()).find("non-finite") != std::string::npos);
        REQUIRE(e.partial());
        CHECK(e.partial()->rows() == 2);  // x = 1 at 0 and 1e300 at 1
        CHECK(e.time_reached() == 1.0);
        CHECK(e.partial()->status == -1);
    }
    SolverOptions sparse = every;
    sparse.output_times = {0.0};  // the final state is checked even when no row records it
    CHECK_THROWS_AS(simulate(huge, 10.0, sparse), SimulationError);

    SolverOptions bounded = o;
    bounded.output_times.clear();
    bounded.max_steps = 3;
    try {
        (void)simulate(model, 1.0, bounded);
        FAIL("max_steps did not stop the run");
    } catch (const SimulationError& e) {
        CHECK(std::string(e.what()).find("max_steps") != std::string::npos);
        REQUIRE(e.partial());
        CHECK(e.partial()->rows() == 4);
        CHECK(e.time_reached() == Approx(0.3).epsilon(1e-14));
    }
}

TEST_CASE("one string, three treatments: the automatic choice follows the measured rule", "[mixed][treatments]") {
    // bench/mixed.bench.cpp's points: exact cheapest at 10 contacts, mixed at 100 (bit on bottom), captured at 1000
    CHECK(automatic_treatment(10, true) == StringTreatment::exact);
    CHECK(automatic_treatment(10, false) == StringTreatment::exact);
    CHECK(automatic_treatment(100, true) == StringTreatment::mixed);
    CHECK(automatic_treatment(100, false) == StringTreatment::captured);  // off bottom mixed is captured
    CHECK(automatic_treatment(1000, true) == StringTreatment::captured);
    CHECK(automatic_treatment(1000, false) == StringTreatment::captured);
    // the crossovers between the measured points, at their geometric middles
    CHECK(automatic_treatment(exact_treatment_up_to, true) == StringTreatment::exact);
    CHECK(automatic_treatment(exact_treatment_up_to + 1, true) == StringTreatment::mixed);
    CHECK(automatic_treatment(mixed_treatment_up_to, true) == StringTreatment::mixed);
    CHECK(automatic_treatment(mixed_treatment_up_to + 1, true) == StringTreatment::captured);
    CHECK(std::string(treatment_name(StringTreatment::mixed)) == "mixed");
}
