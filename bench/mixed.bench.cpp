// The two contact treatments and their mix on one stick-slip string (issue 13, item 1): 1000 m of 5" pipe, vertical
// to 200 m then building to 60 degrees, Coulomb walls (mu_s 0.1, mu 0.067) at every node, a PI top drive at 4 rad/s,
// the velocity-weakening bit on bottom under 60 kN; 6 simulated seconds (the bit's first release, stick and
// release). Each case runs at the setting that reaches the bit's first three switch times to 1e-4 s (measured
// against Dormand-Prince at 1e-11, 1e-10, 1e-8 for N = 10, 100, 1000): the event-driven StringRig
// (Dormand-Prince, every wall switch located), the mixed model (walls captured by Moreau-Jean, the bit's switches
// located) and the all-captured one. The counters give the bit's first switch times, to compare with the others.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <frictionsim/string/exact_string.hpp>
#include <frictionsim/friction/coulomb.hpp>
#include <frictionsim/simulate.hpp>

namespace fs = frictionsim;

namespace {

constexpr double t_end = 6.0, mu = 0.1, weight = 6e4;

fs::PipeSection pipe() {
    fs::PipeSection p;
    p.length = 1000.0;
    return p;
}

fs::TorsionalString torsional_string(std::size_t n) {
    fs::TorsionalStringParams p;
    p.top_drive_inertia = 300.0;
    p.proportional_gain = 3e3;
    p.integral_gain = 1e3;
    p.speed_setpoint = 4.0;
    p.setpoint_time_constant = 0.0;
    p.friction_coefficient = mu;
    p.kinetic_ratio = 2.0 / 3.0;
    p.bha_inertia = 40.0;
    p.weight_on_bit = weight;
    const fs::Survey survey({{0.0, 0.0, 0.0}, {200.0, 0.0, 0.0}, {500.0, fs::pi / 3.0, 0.0}});
    return fs::TorsionalString(fs::DrillString({pipe()}), p, n, survey);
}

/// The same string with every switch located: string/exact_string.hpp's StringRig of it (its bit and node N's wall one
/// contact, the PI unlimited).
fs::ExactStringOnBottom string_rig(const fs::TorsionalString& ts) { return fs::exact_string_on_bottom(ts); }

void bit_counters(benchmark::State& state, std::vector<double> t) {
    std::sort(t.begin(), t.end());
    for (std::size_t k = 0; k < std::min<std::size_t>(3, t.size()); ++k)
        state.counters["bit_switch_" + std::to_string(k)] = t[k];
}

/// args: N, tolerance exponent (rtol = atol = 10^-e).
void event_driven(benchmark::State& state) {
    const auto ts = torsional_string(static_cast<std::size_t>(state.range(0)));
    const auto rig = string_rig(ts);
    fs::SolverOptions o;
    o.rtol = o.atol = std::pow(10.0, -static_cast<double>(state.range(1)));
    o.max_events_in_window = 1'000'000;  // a thousand walls switch within any window
    o.record_event_states = false;        // 10^5 events of 2N states each would fill the memory
    o.output_times = {t_end};
    fs::Result r;
    for (auto _ : state) r = fs::simulate(rig, t_end, o);
    std::vector<double> t;
    for (const fs::Event& e : r.events)
        if (e.name.rfind("bit", 0) == 0) t.push_back(e.time);
    bit_counters(state, t);
    state.counters["events"] = static_cast<double>(r.events.size());
}

/// args: N, step in nanoseconds, 1 for the exact bit (mixed) or 0 (all captured).
void time_stepping(benchmark::State& state) {
    const auto ts = torsional_string(static_cast<std::size_t>(state.range(0)));
    fs::TorsionalStringRunOptions o;
    o.t_end = t_end;
    o.step = static_cast<double>(state.range(1)) * 1e-9;
    o.output_interval = 0.5;
    o.bit_treatment = state.range(2) != 0 ? fs::BitTreatment::exact : fs::BitTreatment::captured;
    fs::TorsionalStringRun r;
    for (auto _ : state) r = ts.simulate(o);
    std::vector<double> t = r.bit_stick_times;
    t.insert(t.end(), r.bit_release_times.begin(), r.bit_release_times.end());
    bit_counters(state, t);
    state.counters["wall_switches"] = static_cast<double>(r.statistics.contact_switches);
}

}  // namespace

// The cheapest setting of each that puts the first three bit switches within 1e-4 s of the reference (measured
// errors: N = 10: DP 1e-5 1.3e-5 s, mixed h 500 us 7.1e-5, captured 125 us 3.6e-5; N = 100: DP 1e-6 7.6e-6, mixed
// 250 us 9.7e-5, captured 125 us 6.0e-5; N = 1000: DP 1e-6 3.0e-5, mixed 31.25 us 3.3e-5, captured 31.25 us 2.4e-5),
// and at N = 1000 the 1 ms step (5e-4 s: mixed 5.1e-4, captured 5.5e-4).
BENCHMARK(event_driven)->Args({10, 5})->Args({100, 6})->Args({1000, 6})->Unit(benchmark::kMillisecond);
BENCHMARK(time_stepping)
    ->Args({10, 500'000, 1})
    ->Args({10, 125'000, 0})
    ->Args({100, 250'000, 1})
    ->Args({100, 125'000, 0})
    ->Args({1000, 31'250, 1})
    ->Args({1000, 31'250, 0})
    ->Args({1000, 1'000'000, 1})
    ->Args({1000, 1'000'000, 0})
    ->Unit(benchmark::kMillisecond);
