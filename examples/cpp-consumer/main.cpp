// How a C++ drilling code uses an installed frictionsim: find_package(frictionsim COMPONENTS sundials),
// link frictionsim::sundials, simulate paper 000's axial rig with Dahl friction.
#include <cmath>
#include <cstdio>

#include <frictionsim/analysis/cycle_mean.hpp>
#include <frictionsim/simulate.hpp>

int main() {
    namespace fs = frictionsim;
    fs::AxialRigParams rig_params;  // Fig. 7(a): dry, u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, F_N = 90 N
    fs::AxialRig<fs::Dahl> rig(rig_params, fs::Dahl(0.41, 4e4));

    fs::SolverOptions options;
    options.method = fs::Method::cvode_bdf;
    options.rtol = 1e-8;
    options.atol = 1e-12;
    for (int i = 0; i <= 1000; ++i) options.output_times.push_back(2.0 * i / 1000);
    const fs::Result result = fs::simulate(rig, 2.0, options);

    const double mean = fs::mean_friction_over_cycles(result, rig.period(), 2.0 - 10 * rig.period(), 10);
    std::printf("mean friction over the last 10 cycles: %.6f N (mu F_N = %.2f N), %zu velocity reversals, "
                "%ld steps\n",
                mean, 0.41 * rig_params.normal_force, result.events.size(), result.stats.steps);
    return std::isfinite(mean) && mean > 0 && !result.events.empty() ? 0 : 1;
}
