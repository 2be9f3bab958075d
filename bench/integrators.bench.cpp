// Integrator choice, measured: each rig on each integrator at the same tolerance, with the solver's work as
// counters beside the time. README "Choosing an integrator" quotes a run of this binary.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include <frictionsim/analysis/cycle_mean.hpp>
#include <frictionsim/analysis/limit_cycle.hpp>
#include <frictionsim/rigs/rigs.hpp>
#include <frictionsim/simulate.hpp>

using namespace frictionsim;

namespace {

void report(benchmark::State& state, const Result& r, double value) {
    state.counters["steps"] = static_cast<double>(r.stats.steps);
    state.counters["rhs"] = static_cast<double>(r.stats.rhs_evaluations);
    state.counters["jac"] = static_cast<double>(r.stats.jacobian_evaluations);
    state.counters["events"] = static_cast<double>(r.events.size());
    state.counters["value"] = value;  // the physical answer, so speed is never bought with a wrong one
}

/// Paper 000 axial rig with Dahl friction: m = 0.2 kg, k_d = 2e4 N/m, mu = 0.41, F_N = 90 N, k_t = 4e4 N/m,
/// u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, 2 s from rest, mean friction over the last 10 whole cycles.
void axial_dahl(benchmark::State& state, Method method, double rtol) {
    AxialRig<Dahl> rig(AxialRigParams{}, Dahl(0.41, 4e4));
    SolverOptions o;
    o.method = method;
    o.rtol = rtol;
    o.atol = rtol * 1e-4;
    const double t_end = 2.0, window = 10 * rig.period();
    o.output_times = {t_end - window, t_end};
    Result r;
    for (auto _ : state) {
        r = simulate(rig, t_end, o);
        benchmark::DoNotOptimize(r.states.data());
    }
    report(state, r, mean_friction_over_cycles(r, rig.period(), 0.0, 10));
}

/// The axial-Dahl scenario at rtol = 10^(-state.range(0) / 10) (atol = 1e-4 rtol): what bench/compare.py
/// searches for the loosest tolerance that meets its accuracy target, e.g. axial_dahl_tolerance/dormand_prince/80.
void axial_dahl_tolerance(benchmark::State& state, Method method) {
    axial_dahl(state, method, std::pow(10.0, -static_cast<double>(state.range(0)) / 10.0));
}

/// A 20-s stick-slip run of `rig` at rtol (atol = 1e-4 rtol), timed per simulation.
template <class Rig>
Result run_stick_slip(benchmark::State& state, const Rig& rig, Method method, double rtol = 1e-8) {
    SolverOptions o;
    o.method = method;
    o.rtol = rtol;
    o.atol = 1e-4 * rtol;
    o.output_times = {20.0};
    Result r;
    for (auto _ : state) {
        r = simulate(rig, 20.0, o);
        benchmark::DoNotOptimize(r.states.data());
    }
    return r;
}

/// Spring-block stick-slip with Coulomb static > kinetic friction: 20 s, ~8 stick-slip cycles. `value` is the
/// position x(20 s); `mean_friction` the mean friction force over the 20 s.
void coulomb_stick_slip(benchmark::State& state, Method method, double rtol = 1e-8) {
    const Result r = run_stick_slip(
        state, AxialRig<Coulomb>(spring_block_params(0.5, 200.0, 0.05), Coulomb(0.4, 0.6)), method, rtol);
    report(state, r, r.state(0, 0));
    state.counters["mean_friction"] = r.state(0, r.column("friction_impulse")) / 20.0;
    state.counters["time_per_event"] =
        benchmark::Counter(static_cast<double>(r.events.size()), benchmark::Counter::kIsIterationInvariantRate |
                                                                     benchmark::Counter::kInvert);
}

/// The spring block at rtol = 10^(-state.range(0) / 10), for bench/compare.py's tolerance search.
void coulomb_stick_slip_tolerance(benchmark::State& state, Method method) {
    coulomb_stick_slip(state, method, std::pow(10.0, -static_cast<double>(state.range(0)) / 10.0));
}

/// LuGre stick-slip example of Canudas de Wit et al. 1995 (m = 1 kg, k = 2 N/m, 0.1 m/s), 20 s.
void lugre_stick_slip(benchmark::State& state, Method method) {
    const Result r =
        run_stick_slip(state, AxialRig<LuGre>(canudas_de_wit_1995_params(), LuGre(canudas_de_wit_1995_lugre())), method);
    report(state, r, r.state(0, 1));
}

/// Paper 001's torsional rig at Fig. 7's operating point (w_ref = 5.76 rad/s, N2 = 35 N), 30 s from rest: about
/// 22 stick-slip cycles. `value` is the limit-cycle frequency over the last 15 s (0.835 Hz with eq 6).
template <class Law>
void torsional_stick_slip(benchmark::State& state, Law law, Method method) {
    const TorsionalRig<Law> rig(TorsionalRigParams{}, std::move(law));
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    for (int i = 0; i <= 3000; ++i) o.output_times.push_back(0.01 * i);
    Result r;
    for (auto _ : state) {
        r = simulate(rig, 30.0, o);
        benchmark::DoNotOptimize(r.states.data());
    }
    const std::vector<double> w = r.column_values("disc_speed");
    report(state, r, limit_cycle(r.t.data(), w.data(), r.rows(), 15.0).frequency);
}

/// Every lab rig of EngineRigs at its table's defaults, 1 s from its initial state on `method` (rtol 1e-8): the law
/// rigs with Coulomb static > kinetic friction (mu 0.3, mu_s 0.4), the kinematic rig under the paper-000 harmonic
/// sliding velocity (v_d 1 mm/s, v_a 0.1 m/s, 17 Hz) and 90 N. Registered from the list, so a rig added there is
/// timed too: rigs/<rig's Python name>/<method> (the string models skipped, by kind: see below). `value` is the last
/// friction force.
template <class Rig>
void rig_at_defaults(benchmark::State& state, const Rig& rig, Method method) {
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-8;
    o.atol = 1e-12;
    o.output_times = {1.0};
    Result r;
    for (auto _ : state) {
        r = simulate(rig, 1.0, o);
        benchmark::DoNotOptimize(r.states.data());
    }
    report(state, r, r.friction_force.back());
}

template <class Entry>
void register_rig_benchmarks(Method method) {
    const std::string name = std::string("rigs/") + Entry::name + "/" + method_name(method);
    if constexpr (Entry::construction == RigConstruction::string ||
                  Entry::construction == RigConstruction::time_stepping) {
        // Skipped here: a string model has no defaults to run at (it is sized at run time from a DrillString), and
        // the time-stepping ones do not run on these ODE methods. They are timed on their own strings by
        // drillstring.bench.cpp (StringRig per element count and method; the Aarsnes-Shor Well B), mixed.bench.cpp
        // and wellb_side_by_side.cpp.
        return;
    } else if constexpr (Entry::construction == RigConstruction::law) {
        using Rig = typename Entry::template of<Coulomb>;
        benchmark::RegisterBenchmark(name.c_str(), [method](benchmark::State& s) {
            rig_at_defaults(s, Rig(typename Entry::Params{}, Coulomb(0.3, 0.4)), method);
        })->Unit(benchmark::kMillisecond);
    } else if constexpr (Entry::construction == RigConstruction::table) {
        benchmark::RegisterBenchmark(name.c_str(), [method](benchmark::State& s) {
            rig_at_defaults(s, typename Entry::type(typename Entry::Params{}), method);
        })->Unit(benchmark::kMillisecond);
    } else {
        using Rig = typename Entry::template of<Coulomb, HarmonicSlidingVelocity>;
        benchmark::RegisterBenchmark(name.c_str(), [method](benchmark::State& s) {
            const HarmonicSlidingVelocity v(1e-3, 0.1, 2.0 * pi * 17.0);
            rig_at_defaults(s, Rig(Coulomb(0.3, 0.4), v, ConstantSignal(90.0)), method);
        })->Unit(benchmark::kMillisecond);
    }
}

[[maybe_unused]] const bool every_rig_registered = [] {
    for (const Method method : {Method::dormand_prince, Method::cvode_bdf})
        for_each_type(EngineRigs{}, [&](auto tag) { register_rig_benchmarks<typename decltype(tag)::type>(method); });
    return true;
}();

}  // namespace

BENCHMARK_CAPTURE(torsional_stick_slip, hysteretic_cvode_bdf, paper001_fig7_friction(), Method::cvode_bdf)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(torsional_stick_slip, hysteretic_dormand_prince, paper001_fig7_friction(), Method::dormand_prince)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(torsional_stick_slip, stribeck_dormand_prince,
                  Stribeck(Stribeck::Params{0.22, 0.3566, 0.3, 1.0, 0.0, 0.0}), Method::dormand_prince)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(torsional_stick_slip, stribeck_cvode_bdf, Stribeck(Stribeck::Params{0.22, 0.3566, 0.3, 1.0, 0.0, 0.0}),
                  Method::cvode_bdf)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(axial_dahl_tolerance, dormand_prince, Method::dormand_prince)
    ->DenseRange(40, 130, 5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(axial_dahl_tolerance, cvode_bdf, Method::cvode_bdf)->DenseRange(40, 120, 5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(axial_dahl_tolerance, cvode_adams, Method::cvode_adams)
    ->DenseRange(40, 120, 5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(axial_dahl, dormand_prince_1e8, Method::dormand_prince, 1e-8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(axial_dahl, cvode_bdf_1e8, Method::cvode_bdf, 1e-8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(axial_dahl, cvode_adams_1e8, Method::cvode_adams, 1e-8)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(coulomb_stick_slip_tolerance, dormand_prince, Method::dormand_prince)
    ->DenseRange(40, 130, 5)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(coulomb_stick_slip_tolerance, cvode_bdf, Method::cvode_bdf)
    ->DenseRange(40, 120, 5)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(coulomb_stick_slip, dormand_prince, Method::dormand_prince)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(coulomb_stick_slip, cvode_bdf, Method::cvode_bdf)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(coulomb_stick_slip, cvode_adams, Method::cvode_adams)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(lugre_stick_slip, dormand_prince, Method::dormand_prince)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lugre_stick_slip, cvode_bdf, Method::cvode_bdf)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lugre_stick_slip, cvode_adams, Method::cvode_adams)->Unit(benchmark::kMillisecond);
