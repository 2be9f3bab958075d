// Field-scale drill strings, measured (issue 13, item 5): the cost per simulated second against the element count
// N = 10 .. 1000 for each integrator on the event-driven StringRig (a 3 km string's first 10 s) and for
// Moreau-Jean time-stepping on the torsional string (Well B, 60 s), the Aarsnes-Shor (2018) Well B case at 1000
// cells and on a coarser grid, and the 3 km / 300-element / 60 s on-bottom stick-slip case. Every run reports the
// solver's work and the physical answer beside the time, so that speed is never bought with a wrong answer:
//   sim_per_cpu_s  simulated seconds per CPU second (a rate counter: t_end over the CPU time of one run)
//   steps, rhs, jac, events, bit_sticks (events where the bit comes to rest)
//   bit_angle      the bit's angle at t_end, rad (the run's answer: integrators at equal tolerance agree on it)
//   top_angle      the top drive's angle at t_end, rad
//   bit_peak, period  (time-stepping) the limit cycle's mean bit peak speed, rad/s, and period, s
// bench/drillstring_compare.py runs this binary, fits the exponents of cost against N, runs the 300-element case in
// SciPy and writes the ratios to out/bench/.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <frictionsim/string/string_rig.hpp>
#include <frictionsim/string/torsional_string.hpp>
#include <frictionsim/friction/coulomb.hpp>
#include <frictionsim/simulate.hpp>

#include "three_km_string.hpp"

// The Eigen Rosenbrock integrator (RODAS4, Method::rosenbrock) joins the comparison where frictionsim::eigen
// provides it (FRICTIONSIM_EIGEN) and its header is in the tree.
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN && __has_include(<frictionsim/eigen/rosenbrock.hpp>)
#define FRICTIONSIM_BENCH_RODAS4 1
#endif

using namespace frictionsim;

namespace {

// ---- the event-driven string -------------------------------------------------------------------------------------

/// The 3 km case (bench/three_km_string.hpp): from rest the string winds up against the stuck bit for 29 s, then the
/// bit slips (peaks ~23 rad/s) and sticks again, three times in 60 s; at N = 300 the walls switch about 2000 times
/// in 60 s.
using Rig = bench::ThreeKmRig;
using bench::three_km_string;

enum class Integrator { dormand_prince, cvode_band, cvode_klu, cvode_dense, rodas4_band };

SolverOptions string_options(Integrator integrator, double t_end, double rtol) {
    SolverOptions o;
    o.rtol = rtol;
    o.atol = 1e-2 * rtol;  // rad and rad/s: 1e-8 at the runs' rtol 1e-6
    o.max_events_in_window = 100000;  // hundreds of contacts may switch within a millisecond at start-up
    o.event_window = 1e-3;
    o.timeout = 3600.0;
    const auto rows = std::lround(t_end / 0.01);  // every 10 ms, as a drilling code would record
    for (long k = 0; k <= rows; ++k) o.output_times.push_back(std::min(t_end, 0.01 * static_cast<double>(k)));
    switch (integrator) {
        case Integrator::dormand_prince: o.method = Method::dormand_prince; break;
        case Integrator::cvode_band: o.method = Method::cvode_bdf; o.linear_solver = LinearSolver::band; break;
        case Integrator::cvode_klu: o.method = Method::cvode_bdf; o.linear_solver = LinearSolver::sparse; break;
        case Integrator::cvode_dense: o.method = Method::cvode_bdf; o.linear_solver = LinearSolver::dense; break;
        case Integrator::rodas4_band:
#ifdef FRICTIONSIM_BENCH_RODAS4
            o.method = Method::rosenbrock;
#endif
            o.linear_solver = LinearSolver::band;
            break;
    }
    return o;
}

Result run_string(const Rig& rig, Integrator integrator, double t_end, double rtol) {
    return simulate(rig, t_end, string_options(integrator, t_end, rtol));
}

/// The string on `integrator` from rest to t_end at rtol (atol 1e-2 rtol); state.range(0) = N.
void string_rig(benchmark::State& state, Integrator integrator, double t_end, double rtol = 1e-6) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const Rig rig = three_km_string(n);
    Result r;
    for (auto _ : state) {
        r = run_string(rig, integrator, t_end, rtol);
        benchmark::DoNotOptimize(r.states.data());
    }
    const std::size_t last = r.rows() - 1;
    std::size_t sticks = 0;
    double peak = 0.0;
    for (const Event& e : r.events)  // the bit's slot reports 20 + its mode: 20 is at rest
        sticks += e.name.rfind("bit.", 0) == 0 && e.mode_after == 20 ? 1 : 0;
    for (std::size_t row = 0; row <= last; ++row) peak = std::max(peak, r.state(row, rig.omega(n)));
    state.counters["elements"] = static_cast<double>(n);
    state.counters["t_end"] = t_end;
    state.counters["rtol"] = rtol;
    state.counters["sim_per_cpu_s"] = benchmark::Counter(t_end, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["steps"] = static_cast<double>(r.stats.steps);
    state.counters["rhs"] = static_cast<double>(r.stats.rhs_evaluations);
    state.counters["jac"] = static_cast<double>(r.stats.jacobian_evaluations);
    state.counters["events"] = static_cast<double>(r.events.size());
    state.counters["bit_sticks"] = static_cast<double>(sticks);
    state.counters["bit_peak"] = peak;
    state.counters["bit_angle"] = r.state(last, rig.theta(n));
    state.counters["top_angle"] = r.state(last, rig.theta(0));
}

// ---- Moreau-Jean time-stepping on the Aarsnes-Shor string -----------------------------------------------------

/// The mean over the limit cycle (cycles starting after 15 s, as tests/aarsnes_shor.test.cpp counts them: a cycle
/// starts when the bit passes 5 rad/s after resting below 0.5 rad/s) of the bit's peak speed and of the period.
struct CycleMeans {
    double peak = 0.0, period = 0.0;
    std::size_t cycles = 0;
};

CycleMeans cycle_means(const TorsionalStringRun& run) {
    std::vector<std::size_t> starts;
    bool armed = true;
    for (std::size_t i = 0; i < run.time.size(); ++i) {
        if (run.bit_speed[i] < 0.5) armed = true;
        if (armed && run.bit_speed[i] > 5.0) {
            starts.push_back(i);
            armed = false;
        }
    }
    CycleMeans m;
    for (std::size_t c = 0; c + 1 < starts.size(); ++c) {
        const std::size_t a = starts[c], b = starts[c + 1];
        if (run.time[a] < 15.0) continue;
        m.period += run.time[b] - run.time[a];
        m.peak += *std::max_element(run.bit_speed.begin() + static_cast<std::ptrdiff_t>(a),
                                    run.bit_speed.begin() + static_cast<std::ptrdiff_t>(b));
        ++m.cycles;
    }
    if (m.cycles > 0) {
        m.peak /= static_cast<double>(m.cycles);
        m.period /= static_cast<double>(m.cycles);
    }
    return m;
}

/// Well B at 2500 m, 40 rpm (collar polar moment and wave speed as published), N = state.range(0) elements, step
/// h = 10 ms / state.range(1) (the output interval and the PI's sampling period are whole steps), 60 s from rest,
/// the implicit inclusion (theta = 1/2) or the field codes' explicit projection inside A&S's 1.5 rad/s band.
void aarsnes_shor(benchmark::State& state, ContactTreatment treatment) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const double h = 0.01 / static_cast<double>(state.range(1)), t_end = 60.0;
    const WellBCase c = aarsnes_shor_well_b(CollarPolarMoment::as_published, CollarWaveSpeed::as_code);
    const TorsionalString string(c.string, c.params, n, c.survey, c.contact_radius);
    TorsionalStringRunOptions o;
    o.t_end = t_end;
    o.step = h;
    o.treatment = treatment;
    o.projection_band = treatment == ContactTreatment::projection ? 1.5 : 0.0;  // A&S's stick band
    o.slow_speed = 1.5;
    TorsionalStringRun r;
    for (auto _ : state) {
        r = string.simulate(o);
        benchmark::DoNotOptimize(r.bit_speed.data());
    }
    const CycleMeans m = cycle_means(r);
    state.counters["elements"] = static_cast<double>(n);
    state.counters["step_ms"] = 1e3 * h;
    state.counters["sim_per_cpu_s"] = benchmark::Counter(t_end, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["steps"] = static_cast<double>(r.statistics.steps);
    state.counters["factorisations"] = static_cast<double>(r.statistics.factorisations);
    state.counters["solves"] = static_cast<double>(r.statistics.solves);
    state.counters["switches"] = static_cast<double>(r.statistics.contact_switches);
    state.counters["bit_peak"] = m.peak;
    state.counters["period"] = m.period;
    state.counters["cycles"] = static_cast<double>(m.cycles);
}

void sweep(benchmark::internal::Benchmark* b, long largest) {
    for (long n : {10L, 30L, 100L, 300L, 1000L})
        if (n <= largest) b->Arg(n);
    b->Unit(benchmark::kMillisecond);
}

}  // namespace

// The N sweep: the 3 km string's first 10 s (the torsional wave runs down, the wall contacts break free, the string
// winds up against the stuck bit) on N = 10 .. 1000; dense CVODE up to N = 100 (its cost grows as N^2 - N^3).
BENCHMARK_CAPTURE(string_rig, dormand_prince, Integrator::dormand_prince, 10.0)->Apply([](auto* b) { sweep(b, 1000); });
BENCHMARK_CAPTURE(string_rig, cvode_band, Integrator::cvode_band, 10.0)->Apply([](auto* b) { sweep(b, 1000); });
#if defined(FRICTIONSIM_SUNDIALS_KLU) && FRICTIONSIM_SUNDIALS_KLU
BENCHMARK_CAPTURE(string_rig, cvode_klu, Integrator::cvode_klu, 10.0)->Apply([](auto* b) { sweep(b, 1000); });
#endif
BENCHMARK_CAPTURE(string_rig, cvode_dense, Integrator::cvode_dense, 10.0)->Apply([](auto* b) { sweep(b, 100); });
#ifdef FRICTIONSIM_BENCH_RODAS4
BENCHMARK_CAPTURE(string_rig, rodas4_band, Integrator::rodas4_band, 10.0)->Apply([](auto* b) { sweep(b, 1000); });
#else
// RODAS4 (solve/rosenbrock.hpp) is not in this tree: its runs are registered here when the header is.
#endif

// The 3 km / 300-element / 60 s case: three bit stick-slip cycles. Its accuracy reference: Dormand-Prince at
// rtol 1e-10.
BENCHMARK_CAPTURE(string_rig, full60s_dormand_prince, Integrator::dormand_prince, 60.0)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(string_rig, full60s_cvode_band, Integrator::cvode_band, 60.0)->Arg(300)->Unit(benchmark::kMillisecond);
#if defined(FRICTIONSIM_SUNDIALS_KLU) && FRICTIONSIM_SUNDIALS_KLU
BENCHMARK_CAPTURE(string_rig, full60s_cvode_klu, Integrator::cvode_klu, 60.0)->Arg(300)->Unit(benchmark::kMillisecond);
#endif
#ifdef FRICTIONSIM_BENCH_RODAS4
BENCHMARK_CAPTURE(string_rig, full60s_rodas4_band, Integrator::rodas4_band, 60.0)->Arg(300)->Unit(benchmark::kMillisecond);
#endif
BENCHMARK_CAPTURE(string_rig, full60s_reference, Integrator::dormand_prince, 60.0, 1e-10)->Arg(300)->Unit(benchmark::kMillisecond);

// The 300-element string side by side over its first 4 s (~340 events), where dense CVODE takes a minute: the
// dense-CVODE and SciPy ratios. Its accuracy reference: Dormand-Prince at rtol 1e-10.
BENCHMARK_CAPTURE(string_rig, window4s_dormand_prince, Integrator::dormand_prince, 4.0)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(string_rig, window4s_cvode_band, Integrator::cvode_band, 4.0)->Arg(300)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(string_rig, window4s_cvode_dense, Integrator::cvode_dense, 4.0)->Arg(300)->Unit(benchmark::kMillisecond);
#ifdef FRICTIONSIM_BENCH_RODAS4
BENCHMARK_CAPTURE(string_rig, window4s_rodas4_band, Integrator::rodas4_band, 4.0)->Arg(300)->Unit(benchmark::kMillisecond);
#endif
BENCHMARK_CAPTURE(string_rig, window4s_reference, Integrator::dormand_prince, 4.0, 1e-10)->Arg(300)->Unit(benchmark::kMillisecond);

// Moreau-Jean on the same N (Well B, h = 2 ms, 60 s).
BENCHMARK_CAPTURE(aarsnes_shor, sweep_inclusion, ContactTreatment::inclusion)
    ->ArgsProduct({{10, 30, 100, 300, 1000}, {5}})->Unit(benchmark::kMillisecond);
// The published grid (1000 cells) at h = 2 and 5 ms; the coarse grid (250 cells) at h = 5 and 2 ms, whose bit
// peak the fine reference (4000 cells, h = 0.5 ms) judges; the field codes' explicit projection at the published
// code's sub-step (h = 1/1200 s, inside its CFL bound dx / c = 0.9 ms) on 1000 cells: that scheme's cost here.
BENCHMARK_CAPTURE(aarsnes_shor, inclusion, ContactTreatment::inclusion)
    ->Args({1000, 5})->Args({1000, 2})->Args({250, 2})->Args({250, 5})->Args({4000, 20})->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(aarsnes_shor, projection, ContactTreatment::projection)->Args({1000, 12})->Unit(benchmark::kMillisecond);
