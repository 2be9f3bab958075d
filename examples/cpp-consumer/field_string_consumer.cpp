// A drilling code's field-scale run on the installed package (find_package(frictionsim COMPONENTS sundials eigen)):
//  1. the library's StringRig (a 2 km string of sections, a wall contact at every node) with the user's own law
//     (bit_rock_friction.hpp) at the wall AND at the bit (BitOnRock<user law>: the library's bit interface
//     under an imposed weight on bit), by Dormand-Prince and by CVODE BDF with the band solver: the same switches,
//     and the energy balance closed;
//  2. the Aarsnes-Shor distributed model (Eigen, Moreau-Jean time-stepping) on the Well B preset: the node bounds
//     add up to the break-off torque of the paper's closed form, and a short run starts the string.
// Exits 1 when a check fails.
#include <cmath>
#include <cstdio>
#include <vector>

#include <frictionsim/string/string_rig.hpp>
#include <frictionsim/string/torsional_string.hpp>
#include <frictionsim/simulate.hpp>

#include "bit_rock_friction.hpp"

namespace fs = frictionsim;

namespace {

int failures = 0;

void check(bool ok, const char* what) {
    std::printf("  [%s] %s\n", ok ? "ok" : "FAILED", what);
    if (!ok) ++failures;
}

using UserBit = fs::BitOnRock<user::BitRockFriction>;
using Rig = fs::StringRig<user::BitRockFriction, UserBit>;

Rig field_string() {
    fs::PipeSection pipe, collar;
    pipe.length = 1800.0;  // 5" drill pipe
    collar.outer_diameter = 0.1651;
    collar.inner_diameter = 0.0714;
    collar.length = 200.0;  // 6.5" collars
    fs::StringRigParams p;
    p.inclination = 0.6;
    p.damping_time = 2e-3;
    p.surface_speed = 4.0;
    p.top_drive_inertia = 400.0;
    p.proportional_gain = 3e3;
    p.integral_gain = 1e3;
    p.end_inertia = 30.0;
    fs::StringRigSetup setup;
    setup.elements = 40;
    user::BitRockFriction::Params wall;
    wall.coulomb_coefficient = 0.2;
    wall.static_coefficient = 0.3;
    wall.decay_rate = 2.0;
    user::BitRockFriction::Params rock;
    rock.coulomb_coefficient = 0.05;
    rock.static_coefficient = 0.08;
    rock.decay_rate = 0.9;
    return Rig(fs::DrillString({pipe, collar}), p, setup, user::BitRockFriction(wall),
               UserBit(user::BitRockFriction(rock), 8e4));
}

}  // namespace

int main() {
    std::printf("field-scale string with the user's law at the wall and at the bit\n");
    const Rig rig = field_string();
    fs::SolverOptions o;
    o.rtol = 1e-8;
    o.atol = 1e-9;
    for (double t = 0.0; t <= 20.0; t += 0.5) o.output_times.push_back(t);
    o.method = fs::Method::dormand_prince;
    const fs::Result explicit_run = fs::simulate(rig, 20.0, o);
    o.method = fs::Method::cvode_bdf;
    o.linear_solver = fs::LinearSolver::band;
    const fs::Result band_run = fs::simulate(rig, 20.0, o);
    check(explicit_run.completed && band_run.completed, "both runs complete");
    check(explicit_run.state_count() == rig.state_size() && rig.state_size() > 80, "sized at run time (N = 40)");
    check(!explicit_run.events.empty(), "wall contacts and the bit switch");
    check(explicit_run.events.size() == band_run.events.size(), "Dormand-Prince and CVODE band: the same switches");
    const std::size_t n = rig.state_size(), last = explicit_run.rows() - 1, bit = rig.omega(rig.elements());
    check(std::abs(explicit_run.state(last, bit) - band_run.state(last, bit)) < 1e-3,
          "the same bit speed at the end (1e-3 rad/s)");
    const double* x0 = &explicit_run.states[0];
    const double* x = &explicit_run.states[last * n];
    const std::size_t w = rig.work_offset();
    const double stored = rig.kinetic_energy(x) + rig.elastic_energy(x) - rig.kinetic_energy(x0) - rig.elastic_energy(x0);
    const double lost = x[w + Rig::wall_friction_work] + x[w + Rig::damping_work] + x[w + Rig::bit_work];
    check(std::abs(x[w + Rig::drive_work] - stored - lost) < 1e-5 * x[w + Rig::drive_work],
          "top-drive work = stored energy + friction + damping + bit work (1e-5)");

    std::printf("Aarsnes-Shor Well B on Moreau-Jean time-stepping (Eigen)\n");
    const fs::WellBCase well = fs::aarsnes_shor_well_b(fs::CollarPolarMoment::corrected, fs::CollarWaveSpeed::physical);
    const fs::TorsionalString model(well.string, well.params, 100, well.survey, well.contact_radius);
    double bounds = 0.0;
    for (double b : model.static_friction_torque()) bounds += b;
    check(std::abs(bounds - model.breakoff_torque()) < 1e-6 * model.breakoff_torque(),
          "node bounds add up to the break-off torque (eq 27)");
    fs::TorsionalStringRunOptions run;
    run.t_end = 5.0;
    run.step = 5e-3;
    run.output_interval = 0.05;
    const fs::TorsionalStringRun result = model.simulate(run);
    check(!result.time.empty() && std::isfinite(result.bit_speed.back()), "a 5 s run");
    check(result.motor_torque.back() > 0.0, "the top drive winds the string up");
    return failures == 0 ? 0 : 1;
}
