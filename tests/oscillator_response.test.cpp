// The dynamic route to a tool's vibration (drillstring/oscillator_response.hpp): the axial StringRig in the well,
// run to a periodic steady state. A frictionless string's driven response peaks at the rod's closed-form
// resonances; with wall friction the dynamic amplitude agrees with the travelling-wave estimate where that is valid
// and decays away from the tool; both routes give the same zone of influence; no tool force is the plain run; bad
// input is named.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include <frictionsim/wells/oscillator_drag.hpp>
#include <frictionsim/wells/oscillator_response.hpp>

#include "catch.hpp"
#include "drill_pipe.hpp"
#include "rejection.hpp"

using namespace frictionsim;
using frictionsim::test::buoyed;
using frictionsim::test::impedance;
using frictionsim::test::pipe;

namespace {

/// A straight horizontal hole from the surface: the side force is the buoyed weight, the drag mu w per metre.
Survey horizontal(double length) { return Survey({{0.0, pi / 2.0, 0.0}, {length, pi / 2.0, 0.0}}); }

}  // namespace

TEST_CASE("oscillator response: a frictionless string resonates at (2n - 1) c / 4L (held hook, free bit)",
          "[oscillator][dynamic][heavy]") {
    // 1000 m of pipe hanging in a vertical hole without friction, the hook held, the bit free (no weight on bit):
    // the fixed-free rod, f_n = (2n - 1) c / (4 L). A tool at the bit drives it; light structural damping
    // (beta = 3 ms: modal ratios 1.2, 3.6, 6 %) keeps the peaks finite. The driven point's speed amplitude,
    // scanned in 1 % steps over +/- 6 %, peaks at the closed form to within the step, and at the driving point's
    // anti-resonances n c / (2 L) it falls below 15 % of the peaks on either side (measured: 0.6 % and 13 %).
    const double length = 1000.0;
    const PipeSection dp = pipe(length);
    const double c = std::sqrt(dp.youngs_modulus / dp.density);
    const OscillatorResponseModel model(Survey({{0.0, 0.0, 0.0}, {length, 0.0, 0.0}}), DrillString({dp}));
    SoftStringParams p;
    p.cased_hole_friction = p.open_hole_friction = 0.0;
    p.rate_of_penetration = 0.0;
    OscillatorResponseParams o;
    o.damping_time = 3e-3;
    o.elements_per_wavelength = 100.0;
    o.steady_tolerance = 0.005;
    o.max_time = 300.0;
    const auto at_bit = [&](double f) {
        const OscillatorResponse r = model.response(Operation::sliding_drilling, p, {length, 10e3, f}, o);
        REQUIRE(r.settled);
        REQUIRE(r.excitation_node == r.elements());
        return std::abs(r.phasor.back());
    };
    double peak[4] = {0.0, 0.0, 0.0, 0.0};
    for (int n = 1; n <= 3; ++n) {
        const double f_n = (2.0 * n - 1.0) * c / (4.0 * length);
        double best = 0.0, best_f = 0.0;
        for (int k = -6; k <= 6; ++k) {
            const double f = f_n * (1.0 + 0.01 * k), a = at_bit(f);
            if (a > best) {
                best = a;
                best_f = f;
            }
        }
        INFO("mode " << n << ": closed form " << f_n << " Hz, peak of the scan " << best_f << " Hz (" << best
                     << " m/s)");
        CHECK(std::abs(best_f / f_n - 1.0) <= 0.0101);
        peak[n] = best;
    }
    for (int n = 1; n <= 2; ++n) {
        const double anti = n * c / (2.0 * length);
        INFO("anti-resonance " << anti << " Hz");
        CHECK(at_bit(anti) < 0.15 * std::min(peak[n], peak[n + 1]));
    }
}

TEST_CASE("oscillator response: with wall friction, the travelling-wave estimate where it holds - the same zone",
          "[oscillator][dynamic][heavy]") {
    // 1400 m of pipe sliding at 30 m/h in a horizontal hole (mu 0.3), a tool (F = 34 kN, 18 Hz) in the middle,
    // through OscillatorDrag (1 m elements) by both routes. The estimate: a_0 = F / (2 Z) at the tool, b = sqrt(a^2 -
    // V^2) falling linearly to zero 400 m away each way. The dynamic run (80 elements, windows of 8 cycles until
    // two agree within 2 %):
    //  * its first harmonic within 5 % of a_0 of the estimate where that is above a_0 / 4, falling away from the tool;
    //  * near the tool the friction it produces is the sinusoid's, (2 / pi) asin(V / a) (both below 0.1);
    //  * beyond the reach (> 1.4 times it) the string sticks and slips forward at the tool's frequency: a first
    //    harmonic of order V (< 2.5 V) whose sliding hardly reverses, the friction factor above 0.6 (the first
    //    harmonic's sinusoid would say ~0.4);
    //  * the core of the zone (friction at most halved) and the drag saved agree with the estimate's to 20-25 %
    //    (the run saves more: its forward stick-slip beyond the reach and brief reversals at the ends).
    const double length = 1400.0, mu = 0.3, f = 18.0, reach = 400.0;
    const PipeSection dp = pipe(length);
    SoftStringParams p;
    p.cased_hole_friction = p.open_hole_friction = mu;
    p.rate_of_penetration = 30.0 / 3600.0;
    p.weight_on_bit = 20e3;
    const double w = buoyed(dp, p.mud_density), z = impedance(dp), force = 4.0 * mu * w * reach / pi;
    const double a0 = force / (2.0 * z), v = p.rate_of_penetration;
    const HydraulicOscillator tool{length / 2.0, force, f};
    const OscillatorDrag model(horizontal(length), DrillString({dp}), 1400);
    OscillatorDragParams dynamic, wave_core;
    dynamic.source = VibrationSource::dynamic;
    dynamic.zone_threshold = wave_core.zone_threshold = 0.5;
    const OscillatorDragResult by_wave = model.run(Operation::sliding_drilling, p, {tool}, wave_core);
    const OscillatorDragResult by_run = model.run(Operation::sliding_drilling, p, {tool}, dynamic);
    REQUIRE(by_run.responses.size() == 1);
    const OscillatorResponse& r = by_run.responses[0];
    CHECK(r.settled);
    CHECK(by_run.source == VibrationSource::dynamic);
    CHECK(by_run.converged);
    const std::vector<double> estimate =
        model.axial_wave().amplitude(tool, std::vector<double>(1400, mu * w), v, {}, 1.0);
    double worst = 0.0;
    for (std::size_t i = 1; i < r.elements(); ++i) {
        const double x = r.measured_depth[i], from_tool = std::abs(x - length / 2.0), h = std::abs(r.phasor[i]);
        const double e = estimate[std::min<std::size_t>(1399, static_cast<std::size_t>(x))];
        INFO("node " << i << " at " << x << " m: first harmonic " << h << " m/s, estimate " << e
                     << " m/s; friction factor " << r.friction_factor[i] << ", reversed " << r.reversed[i]);
        if (e > 0.25 * a0) worst = std::max(worst, std::abs(h - e));
        if (from_tool < 100.0) {
            CHECK(r.friction_factor[i] < 0.1);
            CHECK(r.friction_factor[i] == Approx(2.0 / pi * std::asin(v / h)).margin(0.03));
        }
        if (from_tool > 1.4 * reach && x > 60.0 && x < length - 60.0) {  // (the held hook and the free bit
                                                                       // reflect: brief reversals next to them)
            CHECK(h < 2.5 * v);
            CHECK(r.friction_factor[i] > 0.6);
        }
        // away from the tool within its reach: no rise beyond 2 % of a_0
        const double next = x > length / 2.0 ? std::abs(r.phasor[i + 1]) : std::abs(r.phasor[i - 1]);
        if (from_tool > 10.0 && from_tool + 20.0 < reach) CHECK(next <= h + 0.02 * a0);
    }
    INFO("largest difference where the estimate is above a_0 / 4: " << worst << " m/s (a_0 = " << a0 << ")");
    CHECK(worst < 0.05 * a0);
    CHECK(std::abs(r.phasor[r.excitation_node]) == Approx(a0).epsilon(0.03));
    INFO("zone (friction at most halved): wave " << by_wave.zone_top << "-" << by_wave.zone_bottom << " m ("
                                                 << by_wave.zone_length << " m), dynamic " << by_run.zone_top << "-"
                                                 << by_run.zone_bottom << " m (" << by_run.zone_length
                                                 << " m); hook load change " << by_wave.hook_load_change() << " N, "
                                                 << by_run.hook_load_change() << " N");
    // measured: wave 328-1072 m (744 m), dynamic 877 m (the core and a few elements next to the hook and the bit);
    // hook load change 44.7 kN by the wave, 53.9 kN by the run
    CHECK(by_run.zone_length == Approx(by_wave.zone_length).epsilon(0.2));
    for (std::size_t e = 0; e < 1400; ++e)
        if (std::abs(model.soft_string().element_mid_depth(e) - length / 2.0) < 0.8 * 0.5 * by_wave.zone_length) {
            REQUIRE(by_wave.reduction[e] > 0.5);
            REQUIRE(by_run.reduction[e] > 0.5);
        }
    CHECK(by_run.hook_load_change() == Approx(by_wave.hook_load_change()).epsilon(0.25));
}

TEST_CASE("oscillator response: no tool force is the plain run", "[oscillator][dynamic]") {
    // Without force the string slides on at the operation's speed: the start is the rig's steady balance (what is
    // left is the integrator's error on positions that grow as V t: below 1e-5 m/s at rtol 1e-6).
    const double length = 800.0;
    const OscillatorResponseModel model(horizontal(length), DrillString({pipe(length)}));
    SoftStringParams p;
    p.weight_on_bit = 10e3;
    OscillatorResponseParams o;
    o.transient = 0.5;
    for (Operation op : {Operation::sliding_drilling, Operation::trip_out, Operation::trip_in}) {
        const OscillatorResponse r = model.response(op, p, {400.0, 0.0, 18.0}, o);
        INFO(operation_name(op));
        CHECK(r.stats.events == 0);
        double largest = 0.0;
        for (std::size_t i = 0; i <= r.elements(); ++i) largest = std::max(largest, std::abs(r.phasor[i]));
        INFO("largest first harmonic " << largest << " m/s");
        CHECK(largest < 1e-5);
    }
    // and through OscillatorDrag: the plain soft string bit for bit, no run at all
    const OscillatorDrag drag(horizontal(length), DrillString({pipe(length)}), 400);
    OscillatorDragParams dynamic;
    dynamic.source = VibrationSource::dynamic;
    const OscillatorDragResult r = drag.run(Operation::sliding_drilling, p, {{400.0, 0.0, 18.0}}, dynamic);
    CHECK(r.vibrated.tension == drag.soft_string().run(Operation::sliding_drilling, p).tension);
    CHECK(r.responses.empty());
    CHECK_FALSE(r.has_zone());
}

TEST_CASE("oscillator response: bad input is refused naming it", "[oscillator][dynamic][validation]") {
    const double length = 500.0;
    const OscillatorResponseModel model(horizontal(length), DrillString({pipe(length)}));
    const SoftStringParams p;
    const HydraulicOscillator tool{250.0, 20e3, 18.0};
    auto params_rejected = [&](auto change) {
        OscillatorResponseParams o;
        change(o);
        return rejected_parameter([&] { (void)model.response(Operation::sliding_drilling, p, tool, o); });
    };
    CHECK(params_rejected([](OscillatorResponseParams& o) { o.cycles = 0.5; }) == "cycles");
    CHECK(params_rejected([](OscillatorResponseParams& o) { o.elements_per_wavelength = 2.0; }) ==
          "elements_per_wavelength");
    CHECK(params_rejected([](OscillatorResponseParams& o) { o.transient = -1.0; }) == "transient");
    CHECK(params_rejected([](OscillatorResponseParams& o) { o.damping_time = -1e-3; }) == "damping_time");
    CHECK(params_rejected([](OscillatorResponseParams& o) { o.steady_tolerance = 0.0; }) == "steady_tolerance");
    CHECK(rejected_parameter([&] { (void)model.response(Operation::sliding_drilling, p, {600.0, 2e4, 18.0}); }) ==
          "measured_depth");
    CHECK(rejected_parameter([&] { (void)model.response(Operation::rotary_drilling, p, tool); }) == "vibration");
    const OscillatorDrag drag(horizontal(length), DrillString({pipe(length)}), 100);
    OscillatorDragParams dynamic;
    dynamic.source = VibrationSource::dynamic;
    CHECK(rejected_parameter([&] { (void)drag.run(Operation::reaming, p, {tool}, dynamic); }) == "vibration");
}

TEST_CASE("oscillator response: the work is estimated before anything is allocated, and refused past the limit",
          "[oscillator][dynamic][validation]") {
    // issue 23: a tool at 1e4 Hz ran past 60 s, at 1e6 Hz it allocated until std::bad_alloc. The estimate is
    // elements x simulated time x frequency: with a fixed transient, (transient + cycles / f) exactly.
    const double length = 1000.0;
    const PipeSection dp = pipe(length);
    const OscillatorResponseModel model(horizontal(length), DrillString({dp}));
    const double c = std::sqrt(dp.youngs_modulus / dp.density);
    OscillatorResponseParams o;
    o.transient = 2.0;
    const double f = 18.0, m = std::ceil(o.elements_per_wavelength * length * f / c);
    CHECK(static_cast<double>(model.elements_for(f, o)) == m);
    CHECK(model.node_cycles(f, o) == Approx(m * (2.0 + 8.0 / f) * f).epsilon(1e-15));
    // the default transient: at most the longer of max_time and the default's cap, and one window
    o.transient = std::nan("");
    CHECK(model.node_cycles(f, o) ==
          Approx(m * (std::max(o.max_time, model.default_transient(length, f, o)) + 8.0 / f) * f).epsilon(1e-15));
    const SoftStringParams p;
    for (const double frequency : {1e4, 1e6, 1e300}) {
        const HydraulicOscillator tool{500.0, 2e4, frequency};
        CHECK(rejected_parameter([&] { (void)model.response(Operation::sliding_drilling, p, tool, o); }) ==
              "frequency");
        CHECK(model.node_cycles(frequency, o) > OscillatorResponseParams::max_node_cycles);
    }
    CHECK(rejection_message([&] { (void)model.response(Operation::sliding_drilling, p, {500.0, 2e4, 1e4}, o); })
              .find("to stay within 1e+07") != std::string::npos);
    // two tools, each within the limit, together beyond it: the sum is named at tools
    o.max_time = 600.0;
    const double each = std::sqrt(0.6 * OscillatorResponseParams::max_node_cycles / (600.0 * 16.0 * length / c));
    REQUIRE(model.node_cycles(each, o) < OscillatorResponseParams::max_node_cycles);
    REQUIRE(2.0 * model.node_cycles(each, o) > OscillatorResponseParams::max_node_cycles);
    const OscillatorDrag drag(horizontal(length), DrillString({dp}), 100);
    OscillatorDragParams dynamic;
    dynamic.source = VibrationSource::dynamic;
    dynamic.dynamic = o;
    CHECK(rejected_parameter([&] {
              (void)drag.run(Operation::sliding_drilling, p, {{300.0, 2e4, each}, {600.0, 2e4, each}}, dynamic);
          }) == "tools");
}

TEST_CASE("oscillator response: the interrupt callback stops the dynamic run as Interrupted",
          "[oscillator][dynamic]") {
    // issue 23: Ctrl-C did not stop the dynamic vibration; the run polls OscillatorResponseParams::interrupt
    // between steps (at most every 20 ms) and the Interrupted passes unchanged (not rewrapped as a failed run)
    const double length = 500.0;
    const OscillatorResponseModel model(horizontal(length), DrillString({pipe(length)}));
    OscillatorResponseParams o;
    o.transient = 60.0;  // minutes of computing: only the interrupt ends it
    int polls = 0;
    o.interrupt = [&] { return ++polls >= 3; };
    SoftStringParams p;
    p.open_hole_friction = p.cased_hole_friction = 0.2;
    const HydraulicOscillator tool{250.0, 20e3, 18.0};
    CHECK_THROWS_AS(model.response(Operation::sliding_drilling, p, tool, o), Interrupted);
    CHECK(polls == 3);
    OscillatorDragParams dynamic;
    dynamic.source = VibrationSource::dynamic;
    dynamic.dynamic = o;
    polls = 0;
    const OscillatorDrag drag(horizontal(length), DrillString({pipe(length)}), 50);
    CHECK_THROWS_AS(drag.run(Operation::sliding_drilling, p, {tool}, dynamic), Interrupted);
    polls = 0;
    CHECK_THROWS_AS(drag.weight_on_bit_at(1e4, p, {tool}, dynamic), Interrupted);
}
