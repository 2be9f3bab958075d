// A user's own friction law and own rig, outside frictionsim, run by the installed package's solvers:
//  1. the user's drill string with the user's bit-rock law, by Dormand-Prince and by CVODE BDF: both stick-slip,
//     with the same period and end state, the bit at rest while stuck and a closed energy balance;
//  2. a library law (Coulomb) on the user's rig: the stick-slip period and peak bit speed of the closed form;
//  3. the user's law on a library rig (AxialRig): identical to the library's Stribeck law with delta = 1,
//     which is the same exponential decay;
//  4. the user's parameter table rejects a bad parameter by name, like the library's laws.
// Exits 1 when a check fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "bit_rock_friction.hpp"
#include "drill_string_rig.hpp"

namespace fs = frictionsim;

namespace {

int failures = 0;

void check(bool ok, const char* what) {
    std::printf("  [%s] %s\n", ok ? "ok" : "FAILED", what);
    if (!ok) ++failures;
}

double relative_difference(double a, double b) { return std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

/// Times at which the bit breaks away (stick -> slip events).
std::vector<double> breakaway_times(const fs::Result& r) {
    std::vector<double> times;
    for (const fs::Event& e : r.events)
        if (e.mode_before == fs::stick && e.mode_after != fs::stick) times.push_back(e.time);
    return times;
}

/// Mean stick-slip period over the breakaways after the first two (the transient from rest).
double stick_slip_period(const std::vector<double>& breakaways) {
    if (breakaways.size() < 4) return NAN;
    return (breakaways.back() - breakaways[2]) / static_cast<double>(breakaways.size() - 3);
}

/// Relative residual of drive_work = energy change + friction_work + damping_work at the end of the run.
template <class Rig>
double energy_residual(const Rig& rig, const fs::Result& r) {
    const std::size_t last = r.rows() - 1, n = r.state_count();
    const double* x0 = &r.states[0];
    const double* x = &r.states[last * n];
    const double drive = x[Rig::drive_work];
    const double balance = rig.kinetic_and_elastic_energy(x) - rig.kinetic_and_elastic_energy(x0) +
                           x[Rig::friction_work] + x[Rig::damping_work];
    return std::abs(drive - balance) / std::abs(drive);
}

/// Largest |w| in any row of stick: 0 but for rows at and just before a breakaway, which are the integrator's
/// interpolation across the root (exact to solver tolerance).
double largest_stuck_speed(const fs::Result& r, std::size_t speed_column) {
    double largest = 0.0;
    for (std::size_t i = 0; i < r.rows(); ++i)
        if (r.mode[i] == fs::stick) largest = std::max(largest, std::abs(r.state(i, speed_column)));
    return largest;
}

}  // namespace

int main() {
    using user::BitRockFriction;
    using user::DrillStringRig;
    // Bit-rock friction mu_c = 0.5, mu_s = 0.8 and the rig's defaults, of the order of Navarro-Lopez & Cortes
    // (2007)'s lumped drill string; gamma = 9 s/m at the bit radius (1.4 s/rad of bit speed).
    const BitRockFriction law(BitRockFriction::Params{0.5, 0.8, 9.0});
    user::DrillStringParams rig_params;
    rig_params.string_damping = 172.3;  // N m s/rad
    const DrillStringRig<BitRockFriction> rig(rig_params, law);
    constexpr double t_end = 100.0;

    std::printf("1. user's law on the user's drill string (Omega = %.1f rad/s, %.0f s)\n", rig_params.top_drive_speed,
                t_end);
    fs::SolverOptions options;
    options.rtol = 1e-10;
    options.atol = 1e-10;
    options.method = fs::Method::dormand_prince;
    const fs::Result dp = fs::simulate(rig, t_end, options);
    options.method = fs::Method::cvode_bdf;
    const fs::Result bdf = fs::simulate(rig, t_end, options);
    using Rig = DrillStringRig<BitRockFriction>;
    const double period_dp = stick_slip_period(breakaway_times(dp));
    const double period_bdf = stick_slip_period(breakaway_times(bdf));
    const double w_dp = dp.state(dp.rows() - 1, Rig::bit_speed);
    const double w_bdf = bdf.state(bdf.rows() - 1, Rig::bit_speed);
    const double twist_dp = dp.state(dp.rows() - 1, Rig::twist), twist_bdf = bdf.state(bdf.rows() - 1, Rig::twist);
    std::printf("   Dormand-Prince: %zu events, period %.9f s, end w = %.9f rad/s, twist %.9f rad, %ld steps\n",
                dp.events.size(), period_dp, w_dp, twist_dp, dp.stats.steps);
    std::printf("   CVODE BDF:      %zu events, period %.9f s, end w = %.9f rad/s, twist %.9f rad, %ld steps\n",
                bdf.events.size(), period_bdf, w_bdf, twist_bdf, bdf.stats.steps);
    std::printf("   energy balance residual: %.2e (DP), %.2e (BDF)\n", energy_residual(rig, dp),
                energy_residual(rig, bdf));
    check(breakaway_times(dp).size() >= 10 && dp.events.size() == bdf.events.size(),
          "stick-slip: >= 10 breakaways, the same event count from both integrators");
    check(relative_difference(period_dp, period_bdf) < 1e-6, "the integrators' periods agree to 1e-6");
    check(std::abs(w_dp - w_bdf) < 1e-4 * rig_params.top_drive_speed &&
              std::abs(twist_dp - twist_bdf) < 1e-5 * twist_dp,
          "the integrators' end states agree (bit speed to 1e-4 Omega, twist to 1e-5)");
    check(energy_residual(rig, dp) < 1e-7 && energy_residual(rig, bdf) < 1e-7, "energy balance closes to 1e-7");
    const double stuck_dp = largest_stuck_speed(dp, Rig::bit_speed);
    const double stuck_bdf = largest_stuck_speed(bdf, Rig::bit_speed);
    std::printf("   largest |w| while stuck: %.1e rad/s (DP), %.1e rad/s (BDF)\n", stuck_dp, stuck_bdf);
    check(std::max(stuck_dp, stuck_bdf) < 1e-6 * rig_params.top_drive_speed,
          "the stuck bit stays at rest (1e-6 Omega)");

    // 2. Coulomb (mu_c, mu_s) on the undamped drill string: stick while the string winds up from T_k - dT to
    // T_s = T_k + dT (2 dT / (k Omega)), then half a free oscillation about T_k in which the bit overshoots:
    //   period = 2 dT / (k Omega) + 2 (pi - atan(dT / (Omega sqrt(k J)))) / w_n,   w_max = Omega + sqrt(Omega^2 +
    //   dT^2 / (k J)),   dT = r W (mu_s - mu_c),   w_n = sqrt(k / J).
    std::printf("2. library law (Coulomb) on the user's drill string, undamped: closed form\n");
    const user::DrillStringParams undamped;
    const DrillStringRig<fs::Coulomb> coulomb_rig(undamped, fs::Coulomb(0.5, 0.8));
    const double k = undamped.string_stiffness, J = undamped.bit_inertia, omega = undamped.top_drive_speed;
    const double dT = undamped.bit_radius * undamped.weight_on_bit * (0.8 - 0.5), wn = std::sqrt(k / J);
    const double period_exact =
        2.0 * dT / (k * omega) + 2.0 * (fs::pi - std::atan(dT / (omega * std::sqrt(k * J)))) / wn;
    const double peak_exact = omega + std::sqrt(omega * omega + dT * dT / (k * J));
    fs::SolverOptions coulomb_options;  // Method::automatic: Dormand-Prince
    coulomb_options.rtol = 1e-10;
    coulomb_options.atol = 1e-12;
    const fs::Result coulomb = fs::simulate(coulomb_rig, 100.0, coulomb_options);
    const double period_coulomb = stick_slip_period(breakaway_times(coulomb));
    const std::vector<double> speed = coulomb.column_values("bit_speed");
    const double peak = *std::max_element(speed.begin(), speed.end());
    std::printf("   period %.9f s (closed form %.9f s), peak bit speed %.6f rad/s (closed form %.6f rad/s)\n",
                period_coulomb, period_exact, peak, peak_exact);
    check(relative_difference(period_coulomb, period_exact) < 1e-7, "stick-slip period = closed form to 1e-7");
    check(relative_difference(peak, peak_exact) < 1e-3, "peak bit speed = closed form to 1e-3 (sampled at steps)");

    // 3. The user's law on the library's axial rig (paper 000 Fig. 7(a)): mu(v) = mu_c + (mu_s - mu_c)
    // exp(-gamma |v|) is Stribeck's law with delta = 1 and v_s = 1 / gamma, so both must give the same forces
    // and the same mean friction over the last 10 vibration cycles (the runs differ by rounding only).
    std::printf("3. user's law on the library's AxialRig, against the library's Stribeck (delta = 1)\n");
    const fs::AxialRigParams axial;
    const fs::AxialRig<BitRockFriction> user_axial(axial, law);
    fs::Stribeck::Params stribeck;
    stribeck.coulomb_coefficient = 0.5;
    stribeck.static_coefficient = 0.8;
    stribeck.stribeck_velocity = 1.0 / 9.0;
    stribeck.shape_exponent = 1.0;
    const fs::Stribeck library_law(stribeck);
    const fs::AxialRig<fs::Stribeck> library_axial(axial, library_law);
    double law_difference = 0.0;
    for (double v = -2.0; v <= 2.0; v += 1e-3)
        for (int direction : {-1, 1})
            law_difference = std::max(law_difference, std::abs(law.slip_force(v, axial.normal_force, direction) -
                                                               library_law.slip_force(v, axial.normal_force,
                                                                                      direction)));
    fs::SolverOptions axial_options;
    axial_options.rtol = 1e-9;
    axial_options.atol = 1e-12;
    const double axial_end = 1.0, window_start = axial_end - 10 * user_axial.period();
    axial_options.output_times = {window_start, axial_end};  // the window's ends: exact cycle means
    const fs::Result mine = fs::simulate(user_axial, axial_end, axial_options);
    const fs::Result theirs = fs::simulate(library_axial, axial_end, axial_options);
    const double mean_mine = fs::mean_friction_over_cycles(mine, user_axial.period(), 0.0, 10);
    const double mean_theirs = fs::mean_friction_over_cycles(theirs, library_axial.period(), 0.0, 10);
    using Axial = fs::AxialRig<BitRockFriction>;
    const double* end = &mine.states[mine.state_count()];
    const auto start = user_axial.initial_state();
    const double force_scale = stribeck.static_coefficient * axial.normal_force;  // mu_s F_N, N
    const double work_scale = force_scale * user_axial.vibration_velocity_amplitude() * axial_end;  // J
    const double axial_residual = std::abs(end[Axial::drive_work] - end[Axial::friction_work] -
                                           (user_axial.mechanical_energy(axial_end, end) -
                                            user_axial.mechanical_energy(0.0, start.data()))) /
                                  work_scale;
    std::printf("   forces differ by at most %.1e N; %zu events (Stribeck: %zu); mean friction over the last 10 cycles "
                "%.9f N (Stribeck: %.9f N); energy residual %.1e of mu_s F_N v_a t\n",
                law_difference, mine.events.size(), theirs.events.size(), mean_mine, mean_theirs, axial_residual);
    check(law_difference < 1e-12 * force_scale, "the user's law gives Stribeck's (delta = 1) forces");
    check(mine.events.size() > 10 && mine.events.size() == theirs.events.size(),
          "the user's law sticks and slips on the axial rig, with Stribeck's event count");
    check(std::abs(mean_mine - mean_theirs) < 1e-6 * force_scale, "mean friction = Stribeck's to 1e-6 mu_s F_N");
    check(axial_residual < 1e-8, "axial rig energy balance closes to 1e-8 of mu_s F_N v_a t");

    // 4. The parameter table validates like the library's: mu_s < mu_c is refused, naming the parameter.
    std::printf("4. parameter validation\n");
    std::string message;
    try {
        BitRockFriction(BitRockFriction::Params{0.5, 0.4, 9.0});
    } catch (const fs::InvalidParameter& e) {
        message = e.what();
        check(e.parameter() == "static_coefficient", "mu_s < mu_c throws InvalidParameter(\"static_coefficient\")");
    }
    std::printf("   %s\n", message.c_str());
    check(!message.empty(), "a bad parameter is refused");

    std::printf(failures == 0 ? "all checks passed\n" : "%d check(s) FAILED\n", failures);
    return failures == 0 ? 0 : 1;
}
