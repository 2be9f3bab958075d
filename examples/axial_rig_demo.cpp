// The main job on built-in defaults: paper 000's axial vibrating-sliding rig.
//  1. Fig. 7 cases (dry: u = 5 mm, f = 17 Hz; OBM: u = 4 mm, f = 20 Hz; v_d = 60 mm/min) with Coulomb and Dahl
//     friction: mean friction over whole cycles against Table 4's measured F_df and the Table 5 power law.
//  2. Friction reduction against the velocity ratio v_a/v_d: the kinematic Coulomb closed form, the simulated
//     kinematic rig, and the axial rig with Dahl friction.
// Writes fig7_<case>_<law>.csv time series and friction_reduction.csv into the directory given (default out/).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <frictionsim/analysis/cycle_mean.hpp>
#include <frictionsim/friction/power_law.hpp>
#include <frictionsim/simulate.hpp>

using namespace frictionsim;

namespace {

struct Fig7Case {
    const char* name;
    Lubricant lubricant;
    double amplitude, frequency, normal_force, friction_coefficient, measured_mean;  // Table 4 VS3 / VS17
};

constexpr double kTangentialStiffness = 4e4;  // N/m: Fig. 10's k_t = 40 N/mm

void write_csv(const std::filesystem::path& file, const Result& r) {
    std::ofstream out(file);
    out << "t,position,velocity,friction_force,mode\n";
    for (std::size_t i = 0; i < r.rows(); ++i)
        out << r.t[i] << ',' << r.state(i, 0) << ',' << r.state(i, 1) << ',' << r.friction_force[i] << ','
            << r.mode[i] << '\n';
}

template <class Law>
double simulate_case(const AxialRigParams& p, Law law, const std::filesystem::path& csv, long& steps) {
    AxialRig<Law> rig(p, law);
    const double t_end = 2.0, period = rig.period();
    SolverOptions o;
    o.rtol = 1e-8;
    o.atol = 1e-12;
    // The cycle window's start is an output time too: the mean then differences the friction impulse at a
    // solver-accurate point instead of interpolating it between grid points.
    const double window_start = t_end - 10 * period;
    for (int i = 0; i <= 4000; ++i) {
        const double t = t_end * i / 4000;
        if (t > window_start && o.output_times.back() < window_start) o.output_times.push_back(window_start);
        o.output_times.push_back(t);
    }
    const Result r = simulate(rig, t_end, o);
    steps = r.stats.steps;
    write_csv(csv, r);
    return mean_friction_over_cycles(r, period, window_start, 10);  // last 10 whole cycles
}

}  // namespace

int main(int argc, char** argv) try {
    const std::filesystem::path out_dir = argc > 1 ? argv[1] : "out";
    std::filesystem::create_directories(out_dir);

    std::printf("frictionsim demo: axial vibrating-sliding rig of paper 000 (eqs 5-9)\n");
    std::printf("specimen 0.2 kg, drive stiffness 2e4 N/m, v_d = 60 mm/min, Dahl k_t = 40 N/mm, 2 s, last 10 cycles\n\n");
    const Fig7Case cases[] = {{"dry", Lubricant::dry, 5e-3, 17.0, 90.0, 0.41, 9.27},
                              {"obm", Lubricant::obm, 4e-3, 20.0, 30.0, 0.27, 1.02}};
    std::printf("%-5s %-8s %12s %12s %10s %14s %14s %7s\n", "case", "law", "F_df sim [N]", "mu F_N [N]",
                "reduction", "Table 4 F_df", "Table 5 F_df", "steps");
    for (const Fig7Case& c : cases) {
        AxialRigParams p;
        p.amplitude = c.amplitude;
        p.frequency = c.frequency;
        p.normal_force = c.normal_force;
        const double sliding = c.friction_coefficient * c.normal_force;
        const double v_a = vibration_velocity_amplitude(c.amplitude, c.frequency);
        const double power_law =
            PowerLawCoefficient::from_table5(c.lubricant).friction_force(c.normal_force, v_a, p.sliding_velocity);
        long steps = 0;
        const double coulomb = simulate_case(p, Coulomb(c.friction_coefficient),
                                             out_dir / ("fig7_" + std::string(c.name) + "_coulomb.csv"), steps);
        std::printf("%-5s %-8s %12.4f %12.2f %9.1f%% %14.2f %14.2f %7ld\n", c.name, "Coulomb", coulomb, sliding,
                    100 * friction_reduction(coulomb, sliding), c.measured_mean, power_law, steps);
        const double dahl = simulate_case(p, Dahl(c.friction_coefficient, kTangentialStiffness),
                                          out_dir / ("fig7_" + std::string(c.name) + "_dahl.csv"), steps);
        std::printf("%-5s %-8s %12.4f %12.2f %9.1f%% %14.2f %14.2f %7ld\n", c.name, "Dahl", dahl, sliding,
                    100 * friction_reduction(dahl, sliding), c.measured_mean, power_law, steps);
    }

    std::printf("\nfriction reduction vs velocity ratio (dry, mu = 0.41, F_N = 90 N, f = 17 Hz)\n");
    std::printf("%8s %16s %16s %16s\n", "v_d/v_a", "Coulomb exact", "kinematic sim", "axial rig Dahl");
    std::ofstream csv(out_dir / "friction_reduction.csv");
    csv << "velocity_ratio,coulomb_closed_form,kinematic_coulomb,axial_dahl\n";
    const double mu = 0.41, normal = 90.0, frequency = 17.0, omega = 2 * pi * frequency, period = 1 / frequency;
    for (double ratio : {0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.95, 1.5}) {
        const double v_d = 1e-3, v_a = v_d / ratio;
        const double exact = ratio < 1 ? 1 - 2 / pi * std::asin(ratio) : 0.0;
        KinematicRig kin(Coulomb(mu), HarmonicSlidingVelocity(v_d, v_a, omega), ConstantSignal(normal));
        SolverOptions o;
        o.rtol = 1e-10;
        o.atol = 1e-12;
        o.output_times = {0.0, 5 * period};
        const double kinematic = friction_reduction(mean_friction_over_cycles(simulate(kin, 5 * period, o), period, 0.0),
                                                    mu * normal);
        AxialRigParams p;
        p.amplitude = v_a / omega;
        p.frequency = frequency;
        p.normal_force = normal;
        AxialRig<Dahl> rig(p, Dahl(mu, kTangentialStiffness));
        o.rtol = 1e-8;
        // Dahl loads over a relative displacement of a few mu N / k_t ~ 1 mm: at v_d = 1 mm/s, wait 8 s
        o.output_times = {8.0, 8.0 + 10 * period};
        const double dahl =
            friction_reduction(mean_friction_over_cycles(simulate(rig, 8.0 + 10 * period, o), period, 0.0), mu * normal);
        std::printf("%8.2f %15.2f%% %15.2f%% %15.2f%%\n", ratio, 100 * exact, 100 * kinematic, 100 * dahl);
        csv << ratio << ',' << exact << ',' << kinematic << ',' << dahl << '\n';
    }
    std::printf("\nwrote %s\n", out_dir.string().c_str());
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "axial_rig_demo: %s\n", e.what());
    return 1;
}
