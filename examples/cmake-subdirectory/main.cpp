// frictionsim without SUNDIALS: the header-only core (frictionsim/frictionsim.hpp) runs the library's rigs on
// Dormand-Prince 5(4) through simulate_with<DormandPrince> (frictionsim/simulate.hpp, the method dispatch, also
// brings CVODE). Two checks of physics, not of numbers the engine printed before:
//  1. the spring-block on paper 000's axial rig (no vibration) in stick-slip under Coulomb friction with static
//     > kinetic: the steady cycle's stick and slip times have closed forms (derived below);
//  2. paper 000's Fig. 7(a) rig with Dahl friction: drive work = stored mechanical energy + friction work.
#include <cmath>
#include <cstdio>
#include <vector>

#include <frictionsim/frictionsim.hpp>

#if defined(FRICTIONSIM_SUNDIALS) && FRICTIONSIM_SUNDIALS
#error "this example is built without frictionsim::sundials"
#endif

namespace {

namespace fs = frictionsim;
constexpr double pi = 3.14159265358979323846;

double relative_error(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

/// Block of mass m on a plane (normal force m g), pulled through a spring k whose end moves at v. Stuck, the
/// spring stretches from the kinetic level x_d = mu_k m g / k to the static one x_s = mu_s m g / k: stick lasts
/// 2 (x_s - x_d) / v. Sliding is a harmonic oscillation of lambda = sqrt(k / m) about x_d, entered at relative
/// speed -v and left when the speed is back at v: slip lasts (2 / lambda) (pi - atan(lambda (x_s - x_d) / v)).
bool spring_block_stick_slip() {
    const double m = 0.5, k = 200.0, v = 0.05, g = 9.81, mu_s = 0.6, mu_k = 0.4;
    const fs::AxialRig<fs::Coulomb> rig(fs::spring_block_params(m, k, v, g), fs::Coulomb(mu_k, mu_s));
    const double lambda = std::sqrt(k / m), x_s = mu_s * m * g / k, x_d = mu_k * m * g / k;
    const double stick_time = 2 * (x_s - x_d) / v;
    const double slip_time = 2 / lambda * (pi - std::atan(lambda * (x_s - x_d) / v));

    fs::SolverOptions options;  // method is not read: simulate_with names the integrator
    options.rtol = 1e-10;
    options.atol = 1e-12;
    options.output_times = {0.0};
    const fs::Result run = fs::simulate_with<fs::DormandPrince>(rig, 6 * (stick_time + slip_time), options);

    std::vector<double> slip_starts, stick_starts;  // breakaway at the static limit, stick at zero relative speed
    for (const fs::Event& e : run.events) (e.name == "relative_velocity" ? stick_starts : slip_starts).push_back(e.time);
    if (slip_starts.size() < 4 || stick_starts.size() < 4) {
        std::printf("spring-block: only %zu breakaways and %zu sticks\n", slip_starts.size(), stick_starts.size());
        return false;
    }
    double worst = relative_error(slip_starts[0], x_s / v);  // first breakaway: stretched to x_s from rest
    for (std::size_t i = 1; i + 1 < slip_starts.size() && i < stick_starts.size(); ++i) {
        worst = std::fmax(worst, relative_error(stick_starts[i] - slip_starts[i], slip_time));
        worst = std::fmax(worst, relative_error(slip_starts[i + 1] - stick_starts[i], stick_time));
    }
    std::printf("spring-block stick-slip on Dormand-Prince: stick %.6f s, slip %.6f s (closed forms), %zu switches, "
                "largest relative error %.2e\n",
                stick_time, slip_time, run.events.size(), worst);
    return worst < 1e-6;
}

bool fig7a_energy_balance() {
    const fs::AxialRigParams params;  // Fig. 7(a): dry, u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, F_N = 90 N
    const fs::AxialRig<fs::Dahl> rig(params, fs::Dahl(0.41, 4e4));
    fs::SolverOptions options;
    options.rtol = 1e-10;
    options.atol = 1e-13;
    options.output_times = {0.0, 0.25, 0.5, 1.0};
    const fs::Result run = fs::simulate_with<fs::DormandPrince>(rig, 1.0, options);
    const std::size_t drive = run.column("drive_work"), friction = run.column("friction_work");
    const double e0 = rig.mechanical_energy(0.0, run.states.data());
    double worst = 0.0;
    for (std::size_t i = 1; i < run.rows(); ++i) {
        const double* x = &run.states[i * run.state_count()];
        const double stored = rig.mechanical_energy(run.t[i], x) - e0;
        const double balance = run.state(i, drive) - stored - run.state(i, friction);
        worst = std::fmax(worst, std::abs(balance) / (std::abs(run.state(i, friction)) + std::abs(stored)));
    }
    const double mean = fs::mean_friction_over_cycles(run, rig.period(), 0.5);
    std::printf("Fig. 7(a) rig, Dahl: mean friction %.6f N over the last 0.5 s, friction work %.6f J, "
                "energy balance to %.2e of it\n",
                mean, run.state(run.rows() - 1, friction), worst);
    return worst < 1e-6 && std::isfinite(mean) && mean > 0.0;
}

}  // namespace

int main() {
    const bool stick_slip = spring_block_stick_slip();
    const bool energy = fig7a_energy_balance();
    return stick_slip && energy ? 0 : 1;
}
