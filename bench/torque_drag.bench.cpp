// Soft-string torque and drag on a 6 km well at 1 m elements (issue 14, item 6: "well under a millisecond per
// operation"): one run() per iteration, reusing its result (no allocation), for each operation and both methods
// (Johancsik's step, Aadnoy's closed form). bench/torque_drag_peers.py runs this binary beside the Python peers.
// Each run reports its answer beside the time:  hook_kN  hook load, kN;  torque_kNm  surface torque, kN m.
// The well (bench/torque_drag_peers.py builds the same one for the peers): vertical to 2000 m, built at 3 deg/30 m to
// horizontal (heel at 2954.9 m), a lateral to 6000 m, azimuth 0; 5" x 4.276" drill pipe (SG 7.85) over the whole
// 6000 m; SG 1.2 mud; friction factor 0.3 everywhere (no casing); 50 kN on the bit while sliding.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include <frictionsim/wells/soft_string.hpp>

using namespace frictionsim;

namespace {

constexpr double well_length = 6000.0;
constexpr std::size_t elements = 6000;

SoftString six_km_well(TorqueDragMethod method) {
    const double radius = 30.0 / (3.0 * pi / 180.0), heel = 2000.0 + radius * pi / 2.0;
    const Survey survey({{0.0, 0.0, 0.0}, {2000.0, 0.0, 0.0}, {heel, pi / 2.0, 0.0}, {well_length, pi / 2.0, 0.0}});
    PipeSection dp;
    dp.outer_diameter = 5.0 * 0.0254;
    dp.inner_diameter = 4.276 * 0.0254;
    dp.density = 7850.0;
    dp.length = well_length;
    return SoftString(survey, DrillString({dp}), elements, method);
}

const SoftString& model(TorqueDragMethod method) {
    static const SoftString johancsik = six_km_well(TorqueDragMethod::johancsik);
    static const SoftString aadnoy = six_km_well(TorqueDragMethod::aadnoy);
    return method == TorqueDragMethod::aadnoy ? aadnoy : johancsik;
}

SoftStringParams conditions() {
    SoftStringParams p;
    p.mud_density = 1200.0;
    p.cased_hole_friction = p.open_hole_friction = 0.3;
    p.weight_on_bit = 50e3;
    return p;
}

/// state.range(0): the Operation, state.range(1): the TorqueDragMethod.
void BM_torque_drag(benchmark::State& state) {
    const auto op = static_cast<Operation>(state.range(0));
    const auto method = static_cast<TorqueDragMethod>(state.range(1));
    const SoftString& string = model(method);
    const SoftStringParams p = conditions();
    TorqueDragResult out;
    string.run(op, p, out);  // size the result once
    for (auto _ : state) {
        string.run(op, p, out);
        benchmark::DoNotOptimize(out.tension.data());
        benchmark::ClobberMemory();
    }
    state.counters["hook_kN"] = out.hook_load() / 1e3;
    state.counters["torque_kNm"] = out.surface_torque() / 1e3;
    state.counters["elements"] = static_cast<double>(string.elements());
    state.SetLabel(std::string(operation_name(op)) + "/" + torque_drag_method_name(method));
}

void operations(benchmark::internal::Benchmark* b) {
    for (const TorqueDragMethod m : {TorqueDragMethod::johancsik, TorqueDragMethod::aadnoy})
        for (const Operation op : {Operation::trip_out, Operation::trip_in, Operation::rotating_off_bottom,
                                   Operation::sliding_drilling, Operation::rotary_drilling})
            b->Args({static_cast<std::int64_t>(op), static_cast<std::int64_t>(m)});
}

}  // namespace

BENCHMARK(BM_torque_drag)->Apply(operations)->Unit(benchmark::kMicrosecond);
