// The event-driven string's cost per located switch against the element count (issue 22, item 3): a switch of one
// wall contact should cost what that contact touches, not the whole string. One run per (integrator, N), N = 20 ..
// 400, each reporting the solver's work beside the time:
//   events            located switches (every wall contact, the bit and the top drive)
//   steps_per_event   integrator steps per located switch
//   rhs, guards       right-hand-side and full guard evaluations
//   ns_per_event      wall time of the run over its switches (noisy here: use instruction counts, below)
//   bit_angle         the run's answer at t_end, rad
// Wall time on this shared 2-core machine is noise; instruction counts are not. The figures in the report come
// from callgrind, the whole program's count of one benchmark less that of a run of none (LTO inlines the loop, so
// --toggle-collect finds no function to count):
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null build/bench/string_switch (continued:)
//       --benchmark_filter='dormand_prince/200/'      (and --benchmark_filter=none for the baseline)
// divided by the `events` counter; the exponent is the slope of log(instructions per event) against log N.
// Measured (issue 22, Dormand-Prince): 0.60 / 0.94 / 1.79 / 4.01 / 11.2 M instructions per switch at N = 20 ..
// 400 before the local guards of root_location.hpp (exponent 1.48 between 200 and 400: every bracketing iteration
// evaluated every guard on the whole state), 0.56 / 0.66 / 0.96 / 1.44 / 2.40 M after (exponent 0.73; the same
// steps, switches and answer). What is left grows with N because a switch still ends a step of the whole string.
// Each benchmark runs once (Iterations(1)) so that callgrind counts one run.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <string>

#include <frictionsim/simulate.hpp>

#include "three_km_string.hpp"

using namespace frictionsim;

namespace {

/// The benchmarks' 3 km string (bench/three_km_string.hpp), started turning at the set speed (3 rad/s) so that the
/// walls break free and stick again from the first second on: every wall contact switches a few times per second,
/// so the switches grow with N.
using Rig = bench::ThreeKmRig;

Rig switching_string(std::size_t elements) { return bench::three_km_string(elements, 3.0); }

void string_switch(benchmark::State& state, Method method) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const Rig rig = switching_string(n);
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-6;
    o.atol = 1e-8;
    o.linear_solver = LinearSolver::band;
    o.max_events_in_window = 1000000;
    o.event_window = 1e-3;
    const double t_end = 2.0;
    for (double t = 0.0; t <= t_end; t += 0.01) o.output_times.push_back(t);
    Result r;
    for (auto _ : state) {
        r = simulate(rig, t_end, o);
        benchmark::DoNotOptimize(r.states.data());
    }
    const double events = static_cast<double>(r.events.size());
    state.counters["elements"] = static_cast<double>(n);
    state.counters["events"] = events;
    state.counters["steps"] = static_cast<double>(r.stats.steps);
    state.counters["steps_per_event"] = static_cast<double>(r.stats.steps) / events;
    state.counters["rhs"] = static_cast<double>(r.stats.rhs_evaluations);
    state.counters["guards"] = static_cast<double>(r.stats.guard_evaluations);
    state.counters["ns_per_event"] =
        benchmark::Counter(events * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["bit_angle"] = r.state(r.rows() - 1, rig.theta(n));
}

void sizes(benchmark::internal::Benchmark* b) {
    for (long n : {20, 50, 100, 200, 400}) b->Arg(n);
    b->Iterations(1)->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK_CAPTURE(string_switch, dormand_prince, Method::dormand_prince)->Apply(sizes);
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
BENCHMARK_CAPTURE(string_switch, rosenbrock, Method::rosenbrock)->Apply(sizes);
#endif
