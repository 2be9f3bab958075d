// Axial vibration tools on a 6 km well at 1 m elements (issue 14, items 4 and 6): the cost of one evaluation of the
// placement objective (the weight on bit sliding at a given hook load, with one and with two tools), of one operation
// with a tool (sliding, and rotary drilling where the cycle means need quadrature), and of the plain soft string and
// the travelling-wave estimate alone. Each run reports its answer beside the time:
//   wob_kN    weight on bit at the hook load, kN (placement objective)
//   hook_kN   hook load change with the tool, kN;  zone_m  zone of influence, m;  passes  coupling passes
// The well: vertical to 2000 m, built at 3 deg/30 m to horizontal, a lateral to 6000 m; 5" drill pipe with 300 m of
// heavy-weight (6.5" x 2.81" steel bar stock) at 1500-1800 m; 1.2 SG mud, mu 0.2 cased to 1800 m, 0.3 open hole.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include <frictionsim/wells/oscillator_drag.hpp>

using namespace frictionsim;

namespace {

const OscillatorDrag& six_km_well() {
    static const OscillatorDrag model = [] {
        const double radius = 30.0 / (3.0 * pi / 180.0), heel = 2000.0 + radius * pi / 2.0;
        const Survey survey({{0.0, 0.0, 0.0}, {2000.0, 0.0, 0.0}, {heel, pi / 2.0, 0.0}, {6000.0, pi / 2.0, 0.0}});
        PipeSection dp;
        dp.length = 1500.0;
        PipeSection hw;
        hw.outer_diameter = 0.1651;
        hw.inner_diameter = 0.0714;
        hw.length = 300.0;
        PipeSection lower = dp;
        lower.length = 4200.0;
        return OscillatorDrag(survey, DrillString({dp, hw, lower}), 6000);
    }();
    return model;
}

SoftStringParams sliding() {
    SoftStringParams p;
    p.casing_shoe_depth = 1800.0;
    p.cased_hole_friction = 0.2;
    p.open_hole_friction = 0.3;
    p.rate_of_penetration = 10.0 / 3600.0;
    p.weight_on_bit = 40e3;
    return p;
}

void BM_soft_string_plain(benchmark::State& state) {
    const OscillatorDrag& model = six_km_well();
    const SoftStringParams p = sliding();
    TorqueDragResult out;
    for (auto _ : state) {
        model.soft_string().run(Operation::sliding_drilling, p, out);
        benchmark::DoNotOptimize(out.tension.data());
    }
    state.counters["hook_kN"] = out.hook_load() / 1e3;
}
BENCHMARK(BM_soft_string_plain)->Unit(benchmark::kMicrosecond);

void BM_travelling_wave(benchmark::State& state) {
    const OscillatorDrag& model = six_km_well();
    const std::vector<double> wall(6000, 70.0);
    std::vector<double> out;
    for (auto _ : state) {
        model.axial_wave().amplitude({5500.0, 60e3, 18.0}, wall, 10.0 / 3600.0, {}, 0.0, out);
        benchmark::DoNotOptimize(out.data());
    }
}
BENCHMARK(BM_travelling_wave)->Unit(benchmark::kMicrosecond);

void BM_operation_with_tool(benchmark::State& state) {
    const OscillatorDrag& model = six_km_well();
    SoftStringParams p = sliding();
    const Operation op = state.range(0) == 0 ? Operation::sliding_drilling : Operation::rotary_drilling;
    OscillatorDragResult r;
    for (auto _ : state) {
        r = model.run(op, p, {{5500.0, 60e3, 18.0}});
        benchmark::DoNotOptimize(r.vibrated.tension.data());
    }
    state.SetLabel(operation_name(op));
    state.counters["hook_kN"] = r.hook_load_change() / 1e3;
    state.counters["zone_m"] = r.zone_length;
    state.counters["passes"] = static_cast<double>(r.coupling_passes);
}
BENCHMARK(BM_operation_with_tool)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/// The placement objective at one position (range 0: tools, 1 or 2).
void BM_placement_objective(benchmark::State& state) {
    const OscillatorDrag& model = six_km_well();
    const SoftStringParams p = sliding();
    SoftStringParams at20 = p;
    at20.weight_on_bit = 20e3;
    const double hook = model.soft_string().run(Operation::sliding_drilling, at20).hook_load();
    std::vector<HydraulicOscillator> tools{{5500.0, 60e3, 18.0}};
    if (state.range(0) == 2) tools.push_back({4500.0, 60e3, 18.0});
    double wob = 0.0, depth = 5000.0;
    for (auto _ : state) {
        tools[0].measured_depth = depth;  // a scan: a new position each evaluation
        depth = depth >= 5900.0 ? 5000.0 : depth + 10.0;
        wob = model.weight_on_bit_at(hook, p, tools);
        benchmark::DoNotOptimize(wob);
    }
    state.counters["wob_kN"] = wob / 1e3;
}
BENCHMARK(BM_placement_objective)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
