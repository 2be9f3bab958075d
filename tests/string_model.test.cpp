// The one string model (string/string_model.hpp): a TorsionalString and the treatment of its contacts behind
// simulate(), one Result column set whatever the treatment. The exact treatment's columns are checked against the
// StringRig it runs (bit for bit where they are states, the PI law where they are not), the captured and mixed
// ones against the TorsionalString run directly (bit for bit), and the captured columns against the exact ones as
// h -> 0: bit speed, top-drive speed, motor torque, node N's contact torque (friction_force) and the stuck count.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "catch.hpp"
#include "convergence.hpp"
#include "frictionsim/simulate.hpp"
#include "frictionsim/string/string_model.hpp"
#include "rejection.hpp"

using namespace frictionsim;
using frictionsim::test::fitted_order;
using frictionsim::test::grid;

namespace {

/// 1000 m of 5" pipe, vertical to 200 m and building to 60 degrees at 500 m (no wall at the top drive's node),
/// Coulomb walls mu_s 0.3, kinetic 0.6 of it, StringRig's element damping beta k_e, a 300 kg m^2 top drive under
/// PI (3e3, 1e3) stepped to 4 rad/s, a 40 kg m^2 BHA: off bottom the walls break off and the string settles to
/// sliding; on bottom (60 kN) the velocity-weakening bit sticks and slips.
TorsionalString field_case(std::size_t elements, double weight_on_bit) {
    PipeSection pipe;
    pipe.length = 1000.0;
    TorsionalStringParams p;
    p.top_drive_inertia = 300.0;
    p.proportional_gain = 3e3;
    p.integral_gain = 1e3;
    p.speed_setpoint = 4.0;
    p.setpoint_time_constant = 0.0;
    p.friction_coefficient = 0.3;
    p.kinetic_ratio = 0.6;
    p.bha_inertia = 40.0;
    p.damping_time = 2e-3;
    p.gravity = 9.80665;
    p.mud_density = 1200.0;
    p.weight_on_bit = weight_on_bit;
    const Survey survey{{{0.0, 0.0, 0.0}, {200.0, 0.0, 0.0}, {500.0, pi / 3.0, 0.0}}};
    return TorsionalString(DrillString({pipe}), p, elements, survey);
}

SolverOptions exact_options(double t_end) {
    SolverOptions o;
    o.rtol = o.atol = 1e-10;
    o.output_times = grid(t_end, 0.01);
    return o;
}

SolverOptions captured_options(double t_end, double h) {
    SolverOptions o;
    o.method = Method::moreau_jean;
    o.step = h;
    o.output_times = grid(t_end, 0.01);
    return o;
}

double rms_difference(const Result& a, const Result& b, const std::string& column) {
    REQUIRE(a.rows() == b.rows());
    const std::size_t ca = a.column(column), cb = b.column(column);
    double sum = 0.0;
    for (std::size_t r = 0; r < a.rows(); ++r) sum += std::pow(a.state(r, ca) - b.state(r, cb), 2);
    return std::sqrt(sum / static_cast<double>(a.rows()));
}

double rms_friction_difference(const Result& a, const Result& b) {
    REQUIRE(a.rows() == b.rows());
    double sum = 0.0;
    for (std::size_t r = 0; r < a.rows(); ++r) sum += std::pow(a.friction_force[r] - b.friction_force[r], 2);
    return std::sqrt(sum / static_cast<double>(a.rows()));
}

}  // namespace

TEST_CASE("string model, exact: the StringRig's run as the TorsionalString's columns", "[string_model][treatments]") {
    const std::size_t n = 12;
    const TorsionalString ts = field_case(n, 0.0);
    const StringModel model(ts, StringTreatment::exact);
    const ExactString rig = exact_string(ts);
    const double t_end = 10.0;
    const SolverOptions o = exact_options(t_end);
    const Result r = simulate(model, t_end, o), ref = simulate(rig, t_end, o);
    REQUIRE(r.completed);
    CHECK(r.state_names == ts.state_names());
    REQUIRE(r.rows() == ref.rows());
    CHECK(r.events.size() == ref.events.size());
    CHECK(r.mode == ref.mode);
    const StringRigParams& p = rig.params();
    const std::size_t bit = r.column("bit_speed"), top = r.column("top_drive_speed"), motor = r.column("motor_torque"),
                      stuck = r.column("stuck_fraction");
    std::size_t sticking_rows = 0;
    for (std::size_t row = 0; row < r.rows(); ++row) {
        CHECK(r.state(row, bit) == ref.state(row, rig.omega(n)));  // the same numbers, not a re-run
        CHECK(r.state(row, top) == ref.state(row, rig.omega(0)));
        // the PI law from the rig's states (no limit is reached)
        CHECK(r.state(row, motor) == Approx(p.proportional_gain * (p.surface_speed - ref.state(row, rig.omega(0))) +
                                            p.integral_gain * ref.state(row, rig.drive_state(0)))
                                         .margin(1e-9));
        std::size_t at_rest = 0;
        for (std::size_t i = 0; i <= n; ++i) at_rest += ref.state(row, rig.omega(i)) == 0.0 ? 1 : 0;
        CHECK(r.state(row, stuck) == static_cast<double>(at_rest) / static_cast<double>(n + 1));
        // node N's wall: at rest it holds what the string pulls with, sliding its kinetic level against the speed
        const double w = ref.state(row, rig.omega(n));
        if (w > 0.0) {
            CHECK(r.friction_force[row] == Approx(-ts.params().kinetic_ratio * ts.static_friction_torque()[n])
                                               .epsilon(1e-12));
        } else if (w == 0.0) {
            ++sticking_rows;
            CHECK(std::abs(r.friction_force[row]) <= ts.static_friction_torque()[n] * (1.0 + 1e-12));
        }
    }
    CHECK(sticking_rows > 0);  // the walls start stuck
    CHECK(r.mode.front() == static_cast<int>(ts.contact_count()));
}

TEST_CASE("string model, captured and mixed: the TorsionalString's run bit for bit", "[string_model][treatments]") {
    const double t_end = 5.0;
    const SolverOptions o = captured_options(t_end, 1e-3);
    const TorsionalString off = field_case(40, 0.0);
    const Result a = simulate(StringModel(off, StringTreatment::captured), t_end, o), b = simulate(off, t_end, o);
    CHECK(a.states == b.states);
    CHECK(a.friction_force == b.friction_force);
    CHECK(a.mode == b.mode);

    TorsionalString on = field_case(40, 6e4);
    const Result m = simulate(StringModel(on, StringTreatment::mixed, 1e-9), t_end, o);
    on.set_bit_treatment(BitTreatment::exact, 1e-9);
    const Result direct = simulate(on, t_end, o);
    CHECK(m.states == direct.states);
    CHECK(m.events.size() == direct.events.size());
    CHECK(m.stats.location_trials == direct.stats.location_trials);
    CHECK(m.stats.location_trials > 0);  // the bit's switches were located
}

TEST_CASE("string model: captured converges to exact in every column as h -> 0, on and off bottom",
          "[string_model][treatments]") {
    // Off bottom: the break-off transient (walls stuck, released, sliding). On bottom: the bit's stick-slip with its
    // wall merged, the reaction while stuck and the velocity-weakening level while slipping in friction_force.
    for (const double weight : {0.0, 6e4}) {
        const double t_end = weight > 0.0 ? 12.0 : 20.0;
        const TorsionalString ts = field_case(12, weight);
        const Result ref = simulate(StringModel(ts, StringTreatment::exact), t_end, exact_options(t_end));
        REQUIRE(ref.completed);
        const std::vector<double> steps{2e-3, 1e-3, 5e-4, 2.5e-4};
        std::vector<double> bit, top, motor, force;
        for (double h : steps) {
            const Result r = simulate(StringModel(ts, StringTreatment::captured), t_end, captured_options(t_end, h));
            bit.push_back(rms_difference(r, ref, "bit_speed"));
            top.push_back(rms_difference(r, ref, "top_drive_speed"));
            motor.push_back(rms_difference(r, ref, "motor_torque"));
            force.push_back(rms_friction_difference(r, ref));
        }
        INFO("W = " << weight << " N: RMS differences at h = 2 -> 0.25 ms: bit speed " << bit.front() << " -> "
             << bit.back() << " rad/s (order " << fitted_order(steps, bit) << "), top-drive speed " << top.front()
             << " -> " << top.back() << " (order " << fitted_order(steps, top) << "), motor torque " << motor.front()
             << " -> " << motor.back() << " N m (order " << fitted_order(steps, motor) << "), node N's contact "
             << "torque " << force.front() << " -> " << force.back() << " N m (order " << fitted_order(steps, force)
             << ")");
        CHECK(fitted_order(steps, bit) > 0.7);
        CHECK(fitted_order(steps, top) > 0.7);
        CHECK(fitted_order(steps, motor) > 0.7);
        // measured (h = 2 -> 0.25 ms): off bottom orders 1.11 / 1.10 / 1.10 / 0.96 (bit speed 2.2e-4 -> 2.7e-5 rad/s,
        // node N's torque 0.20 -> 0.031 N m); on bottom 1.21 / 1.19 / 1.19 / 2.25 (7.9e-3 -> 5.2e-4 rad/s, 74.5 ->
        // 1.1 N m)
        CHECK(fitted_order(steps, force) > 0.8);
        CHECK(bit.back() < 1e-2);                   // rad/s, against speeds of 4-10
    }
}

TEST_CASE("string model: the automatic treatment, stop conditions, partial results and refusals",
          "[string_model][treatments][validation]") {
    // the measured rule of treatment.hpp
    CHECK(StringModel::automatic(field_case(12, 0.0)).treatment() == StringTreatment::exact);
    CHECK(StringModel::automatic(field_case(100, 6e4)).treatment() == StringTreatment::mixed);
    CHECK(StringModel::automatic(field_case(100, 0.0)).treatment() == StringTreatment::captured);
    CHECK(StringModel::automatic(field_case(400, 6e4)).treatment() == StringTreatment::captured);

    // a stop condition on bit_speed reads node N's speed under exact: located where it crosses, the run ends there
    const TorsionalString ts = field_case(12, 0.0);
    const StringModel exact(ts, StringTreatment::exact);
    SolverOptions o = exact_options(20.0);
    StopCondition up;
    up.state = "bit_speed";
    up.level = 2.0;
    up.direction = 1;
    o.stop_conditions = {up};
    const Result stopped = simulate(exact, 20.0, o);
    REQUIRE(stopped.stop_events.size() == 1);
    CHECK(stopped.stop_events[0].name == "bit_speed = 2");
    CHECK(stopped.status == 1);
    CHECK(stopped.t.back() == Approx(stopped.stop_events[0].time).margin(1e-12));
    CHECK(stopped.state(stopped.rows() - 1, stopped.column("bit_speed")) == Approx(2.0).margin(1e-7));

    up.state = "motor_torque";
    o.stop_conditions = {up};
    CHECK(rejected_parameter([&] { (void)simulate(exact, 20.0, o); }) == "stop_conditions.state");

    // a failed exact run keeps its partial result, in the string's columns
    SolverOptions capped = exact_options(20.0);
    capped.max_output_rows = 40;
    try {
        (void)simulate(exact, 20.0, capped);
        FAIL("max_output_rows did not stop the run");
    } catch (const BudgetExceeded& e) {
        REQUIRE(e.partial());
        CHECK(e.partial()->state_names == ts.state_names());
        CHECK(e.partial()->rows() == 40);
        CHECK(e.partial()->friction_force.size() == 40);
    }

    // refusals, naming the parameter
    CHECK(rejected_parameter([&] { (void)simulate(exact, 1.0, captured_options(1.0, 1e-3)); }) == "method");
    CHECK(rejected_parameter([&] { StringModel(ts, StringTreatment::mixed); }) == "treatment");  // off bottom
    TorsionalStringParams banded = ts.params();
    banded.stick_band_speed = 1.5;
    const TorsionalString band(ts.string(), banded, 12, ts.survey());
    CHECK(rejected_parameter([&] { StringModel(band, StringTreatment::exact); }) == "stick_band_speed");
    TorsionalStringParams limited = field_case(40, 6e4).params();
    limited.torque_limit = 2e4;
    const TorsionalString limit(ts.string(), limited, 40, ts.survey());
    CHECK(rejected_parameter([&] { StringModel(limit, StringTreatment::mixed); }) == "torque_limit");
}
