// How a C++ drilling code uses an installed frictionsim: find_package(frictionsim COMPONENTS sundials),
// link frictionsim::sundials, simulate paper 000's axial rig with Dahl friction and paper 001's drill-string rig
// in stick-slip.
#include <cmath>
#include <cstdio>
#include <vector>

#include <frictionsim/analysis/cycle_mean.hpp>
#include <frictionsim/analysis/limit_cycle.hpp>
#include <frictionsim/simulate.hpp>

int main() {
    namespace fs = frictionsim;
    fs::AxialRigParams rig_params;  // Fig. 7(a): dry, u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, F_N = 90 N
    fs::AxialRig<fs::Dahl> rig(rig_params, fs::Dahl(0.41, 4e4));

    fs::SolverOptions options;
    options.method = fs::Method::cvode_bdf;
    options.rtol = 1e-8;
    options.atol = 1e-12;
    const double window_start = 2.0 - 10 * rig.period();  // the last 10 whole cycles: an output time, so the
    options.output_times = {window_start, 2.0};            // mean differences the impulse at solver accuracy
    const fs::Result result = fs::simulate(rig, 2.0, options);

    const double mean = fs::mean_friction_over_cycles(result, rig.period(), 0.0, 10);
    std::printf("mean friction over the last 10 cycles: %.6f N (mu F_N = %.2f N), %zu velocity reversals, "
                "%ld steps\n",
                mean, 0.41 * rig_params.normal_force, result.events.size(), result.stats.steps);
    if (!(std::isfinite(mean) && mean > 0 && !result.events.empty())) return 1;

    // Paper 001, Fig. 7: w_ref = 5.76 rad/s, N2 = 35 N, the eq 6 friction chosen to reproduce it; 30 s from rest.
    const fs::TorsionalRig<fs::HystereticFriction> drill_string(fs::TorsionalRigParams{},
                                                                fs::paper001_fig7_friction());
    fs::SolverOptions torsional_options;  // Method::automatic: BDF for eq 6's stiff stick band
    for (int i = 0; i <= 30000; ++i) torsional_options.output_times.push_back(1e-3 * i);
    const fs::Result run = fs::simulate(drill_string, 30.0, torsional_options);
    const std::vector<double> speed = run.column_values("disc_speed");
    const fs::LimitCycle cycle = fs::limit_cycle(run.t.data(), speed.data(), run.rows(), 15.0);
    std::printf("drill-string rig: stick-slip at %.3f Hz, peak disc speed %.2f rad/s, stuck %.0f%% of the time\n",
                cycle.frequency, cycle.peak, 100 * cycle.stick_fraction);
    return cycle.cycles > 0 && cycle.stick_fraction > 0 ? 0 : 1;
}
