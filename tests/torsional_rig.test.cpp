// The torsional drill-string rig of paper 001 (eqs 1-5, rigs/torsional_rig.hpp) with the disc contact of
// contact/disc_contact.hpp: energy balances through stick-slip, steady sliding under PI control, the disc-on-shaft
// frequency, the motor's break-away from rest, the branch gap of the hysteretic law (eq 6), mirror symmetry,
// normal-force scaling, bad input and the mode encoding.
#include <cmath>
#include <utility>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <frictionsim/analysis/limit_cycle.hpp>
#include <frictionsim/papers.hpp>
#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::contains;
using frictionsim::test::kInf;
using frictionsim::test::kNaN;

namespace {

const double* row(const Result& r, std::size_t i) { return &r.states[i * r.state_count()]; }

std::vector<double> grid(double t0, double t1, int intervals) {
    std::vector<double> t;
    for (int k = 0; k <= intervals; ++k) t.push_back(t0 + (t1 - t0) * k / intervals);
    return t;
}

/// The Tables 1-2 rig at a lower reference speed (2 rad/s): the disc sticks and slips every ~1.5 s with the laws
/// below (at 5.76 rad/s and d2 = 0.0167 the slip oscillation decays before the disc comes back to rest).
TorsionalRigParams slow_drive() {
    TorsionalRigParams p;
    p.reference_speed = 2.0;
    return p;
}

Stribeck stribeck() {
    Stribeck::Params sp;
    sp.coulomb_coefficient = 0.3;  // r mu_c N = 1.05 N m
    sp.static_coefficient = 0.4;   // r mu_s N = 1.40 N m
    sp.stribeck_velocity = 0.05;   // m/s at r = 0.1 m: w = 0.5 rad/s
    return Stribeck(sp);
}

/// Eq 6 with N0 >= P0 (no gap): break-away a w_s = 1.4 N m, a Stribeck-like fall with w, a negative added
/// inertia (p01, n01 < 0, as doc section 3.5 asks), and p02, n02 != 0.
HystereticFriction stick_slip_hysteretic() {
    HystereticFriction::Params hp;
    hp.stick_slope = 1400.0;
    hp.accelerating = {0.9, -0.02, -0.003, 0.001, 1e-4, 1e-5};
    hp.decelerating = {0.95, -0.02, -0.003, 0.001, -1e-4, -1e-5};
    return HystereticFriction(hp);
}

/// Eq 6 with a gap: decelerating level N0 = 0.8 N m below the accelerating level P0 = 1.0 N m, break-away
/// a w_s = 1.2 N m > P0 so that the disc leaves the band cleanly onto the accelerating branch.
HystereticFriction gap_law(BranchGap gap) {
    HystereticFriction::Params hp;
    hp.stick_slope = 1200.0;
    hp.accelerating.c00 = 1.0;
    hp.decelerating.c00 = 0.8;
    hp.branch_gap = gap;
    return HystereticFriction(hp);
}

/// Switches of the disc into and out of stick (the hysteretic law's band included).
template <class Law>
std::pair<int, int> disc_stick_switches(const Result& r) {
    using Rig = TorsionalRig<Law>;
    int into = 0, out_of = 0;
    for (const Event& e : r.events) {
        const int before = Rig::disc_mode_of(e.mode_before), after = Rig::disc_mode_of(e.mode_after);
        if (before != stick && after == stick) ++into;
        if (before == stick && after != stick) ++out_of;
    }
    return {into, out_of};
}

/// motor_work = stored mechanical energy change + friction_work + damping_work (eq 5 times the speeds), and
/// electrical_work = ohmic_work + L (i^2 - i0^2) / 2 + (K_E / K_T) motor_work, at every output time.
template <class Law>
Result check_energy_balance(const TorsionalRig<Law>& rig, Method method, double t_end) {
    using Rig = TorsionalRig<Law>;
    const TorsionalRigParams& p = rig.params();
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = grid(0.0, t_end, 8);
    const Result r = simulate(rig, t_end, o);
    REQUIRE(r.completed);
    REQUIRE(r.rows() == 9);
    const std::size_t motor = r.column("motor_work"), friction = r.column("friction_work"),
                      damping = r.column("damping_work"), electrical = r.column("electrical_work"),
                      ohmic = r.column("ohmic_work"), current = r.column("current");
    CHECK(motor == Rig::motor_work);
    CHECK(current == Rig::current);
    const double e0 = rig.stored_mechanical_energy(row(r, 0)), i0 = r.state(0, current);
    double previous_damping = 0.0, previous_ohmic = 0.0;
    for (std::size_t k = 1; k < r.rows(); ++k) {
        const double* x = row(r, k);
        const double w_motor = r.state(k, motor), w_friction = r.state(k, friction), w_damping = r.state(k, damping);
        const double stored = rig.stored_mechanical_energy(x) - e0;
        const double magnetic = 0.5 * p.inductance * (x[current] * x[current] - i0 * i0);
        const double w_electrical = r.state(k, electrical), w_ohmic = r.state(k, ohmic);
        INFO(method_name(method) << ", t = " << r.t[k] << ": motor " << w_motor << ", stored " << stored
                                 << ", friction " << w_friction << ", damping " << w_damping << ", electrical "
                                 << w_electrical << ", ohmic " << w_ohmic << ", magnetic " << magnetic);
        const double mechanical_scale = std::abs(w_motor) + std::abs(stored) + std::abs(w_friction) + std::abs(w_damping);
        CHECK(std::abs(w_motor - stored - w_friction - w_damping) <= 1e-6 * mechanical_scale);
        const double converted = p.back_emf_constant / p.torque_constant * w_motor;
        const double electrical_scale = std::abs(w_electrical) + std::abs(w_ohmic) + std::abs(magnetic) + std::abs(converted);
        CHECK(std::abs(w_electrical - w_ohmic - magnetic - converted) <= 1e-6 * electrical_scale);
        if (p.back_emf_constant == p.torque_constant)  // a lossless motor: V i = R i^2 + d(L i^2/2)/dt + motor power
            CHECK(w_electrical == Approx(w_ohmic + magnetic + w_motor).epsilon(1e-6));
        // dissipation only grows, and the motor has put work in
        CHECK(w_damping >= previous_damping);
        CHECK(w_ohmic >= previous_ohmic);
        previous_damping = w_damping;
        previous_ohmic = w_ohmic;
    }
    CHECK(r.state(r.rows() - 1, motor) > 1.0);
    CHECK(r.state(r.rows() - 1, friction) > 1.0);
    return r;
}

}  // namespace

// ------------------------------------------------------------------------------------------------ energy

TEST_CASE("torsional rig energy balance through stick-slip: engine laws at a contact radius",
          "[torsional_rig][energy]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    const bool lossless_motor = GENERATE(false, true);
    TorsionalRigParams p = slow_drive();
    if (lossless_motor) p.back_emf_constant = p.torque_constant;
    INFO(method_name(method) << (lossless_motor ? ", K_E = K_T" : ", K_E, K_T as printed"));
    SECTION("Coulomb with stick (mu_s > mu)") {
        const Result r = check_energy_balance(TorsionalRig<Coulomb>(p, Coulomb(0.3, 0.4)), method, 6.0);
        const auto [into, out_of] = disc_stick_switches<Coulomb>(r);
        CHECK(into >= 2);  // the disc really sticks again, and again breaks away
        CHECK(out_of >= 3);
    }
    SECTION("Stribeck") {
        const Result r = check_energy_balance(TorsionalRig<Stribeck>(p, stribeck()), method, 6.0);
        const auto [into, out_of] = disc_stick_switches<Stribeck>(r);
        CHECK(into >= 2);
        CHECK(out_of >= 3);
    }
}

TEST_CASE("torsional rig energy balance through stick-slip: hysteretic law of eq 6 (BDF)",
          "[torsional_rig][hysteretic][energy]") {
    const bool lossless_motor = GENERATE(false, true);
    TorsionalRigParams p = slow_drive();
    if (lossless_motor) p.back_emf_constant = p.torque_constant;
    SECTION("N0 >= P0: stick band, accelerating, decelerating") {
        const Result r = check_energy_balance(TorsionalRig<HystereticFriction>(p, stick_slip_hysteretic()),
                                              Method::cvode_bdf, 6.0);
        const auto [into, out_of] = disc_stick_switches<HystereticFriction>(r);
        CHECK(into >= 2);
        CHECK(out_of >= 3);
        int band_entries = 0, band_exits = 0;
        for (const Event& e : r.events) {
            band_entries += e.name == "stick_band_entry" && e.mode_after_name == "stick";
            band_exits += e.name == "stick_band_upper_edge" && e.mode_after_name == "accelerating_positive";
        }
        CHECK(band_entries >= 2);
        CHECK(band_exits >= 3);
    }
    SECTION("N0 < P0 with BranchGap::hold: the hold mode's torque S does work too") {
        TorsionalRigParams fast = p;
        fast.reference_speed = 5.76;
        const Result r = check_energy_balance(TorsionalRig<HystereticFriction>(fast, gap_law(BranchGap::hold)),
                                              Method::cvode_bdf, 5.0);
        bool held = false;
        for (const Event& e : r.events) held = held || e.mode_after_name == "hold_positive";
        CHECK(held);
    }
}

TEST_CASE("torsional rig energy balance with a state law (LuGre: the law's state sits between the rig's)",
          "[torsional_rig][energy]") {
    LuGre::Params lp;
    lp.coulomb_coefficient = 0.3;
    lp.static_coefficient = 0.4;
    lp.stribeck_velocity = 0.05;
    lp.bristle_stiffness = 1e4;
    lp.bristle_damping = 100.0;
    const TorsionalRig<LuGre> rig(slow_drive(), LuGre(lp));
    const Result r = check_energy_balance(rig, Method::cvode_bdf, 3.0);
    CHECK(r.column("bristle_deflection") == TorsionalRig<LuGre>::law_state);
    CHECK(r.column("motor_work") == TorsionalRig<LuGre>::law_state + 1);
}

// ------------------------------------------------------------------------------------------ steady state

TEST_CASE("torsional rig: steady sliding under PI control, at the disc-on-shaft frequency", "[torsional_rig]") {
    // Constant kinetic torque (Coulomb, mu = mu_s): after break-away the disc slides for good and its oscillation
    // about w_ref decays (zeta ~ 0.11); the PI integral takes the drive exactly to w_ref.
    const TorsionalRigParams p;  // Tables 1-2, w_ref = 5.76 rad/s, N2 = 35 N
    const double mu = 0.3, disc_torque = p.contact_radius * mu * p.normal_force;  // 1.05 N m
    const TorsionalRig<Coulomb> rig(p, Coulomb(mu));
    SolverOptions o;
    o.method = Method::dormand_prince;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = grid(3.0, 13.0, 10000);
    o.output_times.push_back(30.0);
    const Result r = simulate(rig, 30.0, o);
    REQUIRE(r.completed);

    // one break-away of the disc, and it never sticks again
    const auto [into, out_of] = disc_stick_switches<Coulomb>(r);
    CHECK(out_of == 1);
    CHECK(into == 0);

    const double* x = row(r, r.rows() - 1);
    using Rig = TorsionalRig<Coulomb>;
    const double eta = p.gear_ratio;
    const double i0 = (eta * eta * p.motor_viscous_coefficient * p.reference_speed + eta * p.motor_friction_torque +
                       disc_torque) /
                      (eta * p.torque_constant);
    const double v0 = p.resistance * i0 + eta * p.back_emf_constant * p.reference_speed;
    INFO("i0 = " << i0 << " A, V0 = " << v0 << " V");
    CHECK(i0 == Approx(2.0561).epsilon(1e-4));  // doc section 3.3: 1.0145 A + 0.992 A/(N m) * T0
    CHECK(x[Rig::drive_speed] == Approx(p.reference_speed).epsilon(1e-6));
    CHECK(x[Rig::disc_speed] == Approx(p.reference_speed).epsilon(1e-6));
    CHECK(x[Rig::current] == Approx(i0).epsilon(1e-6));
    CHECK(rig.voltage(x) == Approx(v0).epsilon(1e-6));
    CHECK(x[Rig::speed_error_integral] == Approx(v0 / p.integral_gain).epsilon(1e-6));  // V = k_i z at w3 = w_ref
    CHECK(x[Rig::shaft_twist] == Approx(disc_torque / p.shaft_stiffness).epsilon(1e-6));
    CHECK(r.friction_force.back() == Approx(disc_torque).epsilon(1e-12));
    CHECK(r.mode.back() == Rig::encode_mode(slip_positive, slip_positive));

    // the decaying oscillation of w2 about w_ref: upward zero crossings of w2 - w_ref between 3 s and 13 s
    std::vector<double> crossings;
    const std::size_t w2 = r.column("disc_speed");
    for (std::size_t k = 1; k + 1 < r.rows(); ++k) {
        const double a = r.state(k - 1, w2) - p.reference_speed, b = r.state(k, w2) - p.reference_speed;
        if (a < 0.0 && b >= 0.0) crossings.push_back(r.t[k - 1] + (r.t[k] - r.t[k - 1]) * a / (a - b));
    }
    REQUIRE(crossings.size() >= 6);
    const double f = (crossings.size() - 1) / (crossings.back() - crossings.front());
    INFO("oscillation " << f << " Hz, natural frequency " << rig.natural_frequency() << " Hz");
    // the PI loop makes the drive nearly rigid: the disc-on-shaft mode with its own damping,
    // f_d = f_n sqrt(1 - zeta^2), zeta = d2 / (2 sqrt(k2 J2)) = 0.113 (doc 3.2: 0.7836 Hz)
    const double zeta = p.shaft_damping / (2 * std::sqrt(p.shaft_stiffness * p.disc_inertia));
    const double f_d = rig.natural_frequency() * std::sqrt(1 - zeta * zeta);
    CHECK(f_d == Approx(0.7836).margin(1e-4));
    CHECK(f == Approx(f_d).epsilon(0.005));
    CHECK(f < rig.natural_frequency());
}

TEST_CASE("torsional rig: natural frequency sqrt(k2 / J2) / 2 pi", "[torsional_rig]") {
    const TorsionalRigParams p;
    const TorsionalRig<Coulomb> rig(p, Coulomb(0.3));
    CHECK(rig.natural_frequency() == Approx(0.7887).margin(5e-5));
    CHECK(rig.natural_frequency() == Approx(std::sqrt(0.3659 / 0.0149) / (2 * pi)).epsilon(1e-15));
    TorsionalRigParams q;
    q.shaft_stiffness = 1.0;
    q.disc_inertia = 0.25;
    q.motor_inertia = 1.0;  // the motor side does not enter: the shaft end is held
    CHECK(TorsionalRig<Coulomb>(q, Coulomb(0.3)).natural_frequency() == Approx(1.0 / pi).epsilon(1e-15));
}

// ------------------------------------------------------------------------------------------------ motor

TEST_CASE("torsional rig: the motor starts stuck and breaks away when eta K_T i reaches eta T_f",
          "[torsional_rig]") {
    const TorsionalRigParams p;
    using Rig = TorsionalRig<Coulomb>;
    const Rig rig(p, Coulomb(0.3, 0.4));
    SolverOptions o;  // no output times: every step is recorded, the step at the switch included
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(o.method));
    const Result r = simulate(rig, 2e-3, o);
    REQUIRE(r.completed);
    REQUIRE(!r.events.empty());
    CHECK(r.mode.front() == Rig::encode_mode(stick, stick));
    const Event& e = r.events.front();
    CHECK(e.name == "motor_breakaway_positive");
    CHECK(e.mode_before == Rig::encode_mode(stick, stick));
    CHECK(e.mode_after == Rig::encode_mode(stick, slip_positive));
    CHECK(e.mode_before_name == "stick+motor_stick");
    CHECK(e.mode_after_name == "stick");

    // While the motor is held: w3 = 0, z = w_ref t, V = k_p w_ref + k_i w_ref t, L di/dt = V - R i, i(0) = 0:
    //   i(t) = c0 (1 - exp(-t R / L)) + c1 t,  c1 = k_i w_ref / R,  c0 = (k_p w_ref - L c1) / R.
    // The shaft carries nothing (S = 0), so the motor breaks away at i = T_f / K_T.
    const double tau = p.inductance / p.resistance, c1 = p.integral_gain * p.reference_speed / p.resistance;
    const double c0 = (p.proportional_gain * p.reference_speed - p.inductance * c1) / p.resistance;
    const auto current = [&](double t) { return c0 * (1.0 - std::exp(-t / tau)) + c1 * t; };
    const double i_break = p.motor_friction_torque / p.torque_constant;  // 0.949 A
    double lo = 0.0, hi = 1e-3;
    for (int k = 0; k < 200; ++k) (current(0.5 * (lo + hi)) < i_break ? lo : hi) = 0.5 * (lo + hi);
    const double t_break = 0.5 * (lo + hi);
    INFO("analytic break-away at " << t_break << " s");
    CHECK(t_break == Approx(5.014e-5).epsilon(1e-3));
    CHECK(e.time == Approx(t_break).epsilon(1e-8));

    const std::size_t w3 = r.column("drive_speed"), i = r.column("current");
    bool found = false;
    for (std::size_t k = 0; k < r.rows(); ++k) {
        if (r.t[k] < e.time) {
            CHECK(r.state(k, w3) == 0.0);  // held exactly
            CHECK(r.state(k, i) == Approx(current(r.t[k])).epsilon(1e-7).margin(1e-12));
        }
        if (r.t[k] == e.time && !found) {
            found = true;
            CHECK(r.state(k, i) == Approx(i_break).epsilon(1e-9));
        }
    }
    CHECK(found);
    CHECK(r.state(r.rows() - 1, w3) > 0.0);  // and then it turns forwards
    CHECK(Rig::motor_mode_of(r.mode.back()) == slip_positive);
}

TEST_CASE("torsional rig: a disc spinning at the start begins on the slip side of its speed and comes to rest",
          "[torsional_rig][hysteretic]") {
    TorsionalRigParams p = slow_drive();
    p.initial_drive_speed = p.reference_speed;
    const double w0 = GENERATE(3.0, -3.0);
    p.initial_disc_speed = w0;
    const int side = w0 > 0 ? 1 : -1;
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = {0.0, 0.2};
    INFO("w2(0) = " << w0);
    SECTION("hysteretic: the decelerating branch (S' < N0), then the stick band") {
        using Rig = TorsionalRig<HystereticFriction>;
        const Result r = simulate(Rig(p, stick_slip_hysteretic()), 0.2, o);
        CHECK(Rig::disc_mode_of(r.mode.front()) == 2 * side);
        CHECK(Rig::motor_mode_of(r.mode.front()) == slip_positive);
        REQUIRE(!r.events.empty());
        CHECK(r.events.front().name == "stick_band_entry");
        CHECK(Rig::disc_mode_of(r.events.front().mode_after) == stick);
        // J_eff = J2 + n01 + n11 |w| ~ 0.0116 kg m^2 against ~0.9 N m: about 0.04 s
        CHECK(r.events.front().time == Approx(0.04).epsilon(0.15));
        CHECK(std::abs(r.state(1, Rig::disc_speed)) <= 1e-3);
    }
    SECTION("Coulomb: slip, then stick") {
        using Rig = TorsionalRig<Coulomb>;
        const Result r = simulate(Rig(p, Coulomb(0.3, 0.4)), 0.2, o);
        CHECK(Rig::disc_mode_of(r.mode.front()) == side);
        REQUIRE(!r.events.empty());
        CHECK(r.events.front().name == "relative_velocity");
        CHECK(Rig::disc_mode_of(r.events.front().mode_after) == stick);
        // J2 w0 / (r mu N) = 0.0426 s, give or take the shaft's few per cent of the torque
        CHECK(r.events.front().time == Approx(0.0149 * 3.0 / 1.05).epsilon(0.1));
        CHECK(std::abs(r.state(1, Rig::disc_speed)) <= 1e-12);  // held (to the rounding of r (S / r) vs S)
    }
}

// ----------------------------------------------------------------------------------------- branch gap

TEST_CASE("torsional rig, hysteretic law with N0 < P0: BranchGap::error stops, BranchGap::hold holds al = 0",
          "[torsional_rig][hysteretic]") {
    const TorsionalRigParams p;  // w_ref = 5.76 rad/s
    using Rig = TorsionalRig<HystereticFriction>;
    SolverOptions o;  // every step recorded
    o.rtol = 1e-10;
    o.atol = 1e-12;

    const Result held = simulate(Rig(p, gap_law(BranchGap::hold)), 5.0, o);
    REQUIRE(held.completed);
    double first_gap = -1.0;
    int hold_entries = 0, hold_exits = 0;
    for (const Event& e : held.events) {
        if (e.mode_after_name == "hold_positive") {
            ++hold_entries;
            CHECK(e.name == "acceleration_zero");
            if (first_gap < 0.0) first_gap = e.time;
        }
        if (e.mode_before_name == "hold_positive") {
            ++hold_exits;
            CHECK((e.name == "accelerating_level" || e.name == "decelerating_level"));
        }
    }
    CHECK(hold_entries >= 2);
    CHECK(hold_exits >= 2);
    REQUIRE(first_gap > 0.0);

    // In hold, al = 0 and the friction torque is the shaft torque, inside [N0, P0]; w2 stays put.
    const Rig rig(p, gap_law(BranchGap::hold));
    int hold_rows = 0;
    double held_speed = kNaN;
    for (std::size_t k = 0; k < held.rows(); ++k) {
        const double* x = row(held, k);
        if (Rig::disc_mode_of(held.mode[k]) != 3) {
            held_speed = kNaN;
            continue;
        }
        ++hold_rows;
        INFO("t = " << held.t[k]);
        CHECK(rig.disc_acceleration(x, held.mode[k]) == 0.0);
        CHECK(held.friction_force[k] == Approx(rig.shaft_torque(x)).epsilon(1e-14));
        CHECK(held.friction_force[k] >= 0.8 - 1e-9);
        CHECK(held.friction_force[k] <= 1.0 + 1e-9);
        if (std::isnan(held_speed)) held_speed = x[Rig::disc_speed];
        CHECK(x[Rig::disc_speed] == Approx(held_speed).epsilon(1e-12));
    }
    CHECK(hold_rows >= 10);

    try {
        (void)simulate(Rig(p, gap_law(BranchGap::error)), 5.0, o);
        FAIL("expected a SimulationError: no consistent friction branch");
    } catch (const ChatteringError& e) {
        FAIL("expected the branch-gap error, got chattering: " << e.what());
    } catch (const SimulationError& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(contains(what, "no consistent friction branch"));
        CHECK(contains(what, "t = "));
        CHECK(contains(what, "disc speed w = "));
        CHECK(contains(what, "shaft torque S = "));
        CHECK(contains(what, "P0 = 1 N m"));
        CHECK(contains(what, "N0 = 0.8 N m"));
        // the run stops where the hold run first holds: the same trajectory up to the gap
        CHECK(e.time_reached() > 0.0);
        CHECK(e.time_reached() == Approx(first_gap).epsilon(1e-9));
        REQUIRE(e.partial() != nullptr);
        const Result& partial = *e.partial();
        CHECK_FALSE(partial.completed);
        CHECK(partial.t_reached == e.time_reached());
        REQUIRE(partial.rows() > 10);
        CHECK(partial.t.front() == 0.0);
        CHECK(partial.t.back() == Approx(e.time_reached()).epsilon(1e-12));
        // the last row is on the accelerating branch with al -> 0: the friction torque has come down to P0
        CHECK(Rig::disc_mode_of(partial.mode.back()) == 1);
        CHECK(partial.friction_force.back() == Approx(1.0).epsilon(1e-6));
        CHECK(partial.state(partial.rows() - 1, Rig::disc_speed) > 1.0);
    }
}

TEST_CASE("torsional rig, hysteretic law with a w_s < P0(w_s): the disc leaves the band into the gap",
          "[torsional_rig][hysteretic]") {
    // The band lets go at S = a w_s = 0.8 N m, but the accelerating branch needs S > P0 = 1 N m: with hold the
    // disc slides along the band edge (w = w_s, al = 0, T = S) until S reaches P0, which is the real break-away.
    using Rig = TorsionalRig<HystereticFriction>;
    HystereticFriction::Params hp;
    hp.stick_slope = 800.0;
    hp.accelerating.c00 = 1.0;
    hp.decelerating.c00 = 1.0;
    const TorsionalRigParams p = slow_drive();
    SolverOptions o;  // every step recorded
    o.rtol = 1e-10;
    o.atol = 1e-12;
    hp.branch_gap = BranchGap::hold;
    const Rig rig(p, HystereticFriction(hp));
    const Result r = simulate(rig, 3.0, o);
    REQUIRE(r.events.size() >= 3);
    const Event &exit = r.events[1], &breakaway = r.events[2];
    CHECK(exit.name == "stick_band_upper_edge");
    CHECK(exit.mode_after_name == "hold_positive");
    CHECK(breakaway.name == "accelerating_level");
    CHECK(breakaway.mode_after_name == "accelerating_positive");
    int hold_rows = 0;
    for (std::size_t k = 0; k < r.rows(); ++k) {
        const double* x = row(r, k);
        // the band lags S / a by (J / a) dS/dt / a: S = a w_s + J (dS/dt) / a ~ 0.8 + 1.4e-5 N m
        if (r.t[k] == exit.time) CHECK(rig.shaft_torque(x) == Approx(0.8 + 1.3e-5).margin(3e-6));
        if (r.t[k] == breakaway.time) CHECK(rig.shaft_torque(x) == Approx(1.0).epsilon(1e-6));
        if (r.t[k] <= exit.time || r.t[k] >= breakaway.time) continue;
        ++hold_rows;
        INFO("t = " << r.t[k]);
        CHECK(Rig::disc_mode_of(r.mode[k]) == 3);
        CHECK(x[Rig::disc_speed] == Approx(hp.stick_speed).epsilon(1e-12));
        CHECK(r.friction_force[k] == Approx(rig.shaft_torque(x)).epsilon(1e-14));
        CHECK(r.friction_force[k] >= 0.8 - 1e-6);
        CHECK(r.friction_force[k] <= 1.0 + 1e-6);
    }
    CHECK(hold_rows >= 5);

    hp.branch_gap = BranchGap::error;
    try {
        (void)simulate(Rig(p, HystereticFriction(hp)), 3.0, o);
        FAIL("expected a SimulationError");
    } catch (const SimulationError& e) {
        INFO(e.what());
        CHECK(contains(e.what(), "no consistent friction branch"));
        CHECK(e.time_reached() == Approx(exit.time).epsilon(1e-9));
        // S = 0.8 N m is below N0 = P0 = 1 N m here: the message must not say it lies between them (the gap at
        // the band edge is between a w_s and P0(w_s))
        CHECK_FALSE(contains(e.what(), "lies between the decelerating level N0 and the accelerating level P0"));
    }
}

TEST_CASE("torsional rig, hysteretic law: a hold on the band edge ends when the shaft torque falls below a w_s",
          "[torsional_rig][hysteretic][regression]") {
    // a w_s = 0.1 N m below both levels (P0 = 1, N0 = 0.8): the disc leaves the band into a hold on its edge.
    // The drive then reverses (w_ref = -3 rad/s): S falls below a w_s, and the band must take the disc back
    // (it was trapped in the hold at w = +w_s with T = S = -10.5 N m, friction doing positive work).
    HystereticFriction::Params hp;
    hp.stick_slope = 100.0;
    hp.accelerating.c00 = 1.0;
    hp.decelerating.c00 = 0.8;
    TorsionalRigParams p;
    p.reference_speed = -3.0;
    p.initial_drive_speed = 8.0;
    const TorsionalRig<HystereticFriction> rig(p, HystereticFriction(hp));
    SolverOptions o;
    o.rtol = 1e-9;
    o.atol = 1e-12;
    o.output_times = grid(0.0, 10.0, 2000);
    const Result r = simulate(rig, 10.0, o);
    bool held = false, back_to_stick = false;
    for (const Event& e : r.events) {
        held = held || e.mode_after_name == "hold_positive";
        back_to_stick = back_to_stick || (e.mode_before_name == "hold_positive" && e.mode_after_name == "stick");
    }
    CHECK(held);
    CHECK(back_to_stick);
    const std::size_t friction_work = r.column("friction_work");
    for (std::size_t i = 1; i < r.rows(); ++i) CHECK(r.state(i, friction_work) >= r.state(i - 1, friction_work) - 1e-9);
    CHECK(r.state(r.rows() - 1, r.column("disc_speed")) < 0.0);  // dragged backwards with the drive
}

TEST_CASE("torsional rig, hysteretic law: leaving a hold checks the branch it enters",
          "[torsional_rig][hysteretic][regression]") {
    // p01 = -0.02 kg m^2 > J2: the accelerating branch has a negative effective inertia. A hold (N0 < P0)
    // that ends on it must stop the run, not integrate dw/dt = -C/B < 0 "accelerating" to -1e19 rad/s.
    HystereticFriction::Params hp;
    hp.stick_slope = 1000.0;
    hp.accelerating = {0.3, 0.0, -0.02, 0.0, 0.0, 0.0};
    hp.decelerating.c00 = 0.1;
    TorsionalRigParams p;
    p.initial_disc_speed = 5.0;
    p.initial_drive_speed = 5.76;
    SolverOptions o;
    o.output_times = grid(0.0, 5.0, 500);
    try {
        (void)simulate(TorsionalRig<HystereticFriction>(p, HystereticFriction(hp)), 5.0, o);
        FAIL("expected a SimulationError");
    } catch (const SimulationError& e) {
        INFO(e.what());
        CHECK(contains(e.what(), "effective inertia"));
        CHECK(e.time_reached() > 0.0);
        REQUIRE(e.partial());
        double fastest = 0.0;
        for (double w : e.partial()->column_values("disc_speed")) fastest = std::max(fastest, std::abs(w));
        CHECK(fastest < 10.0);
    }
}

TEST_CASE("torsional rig, hysteretic law: a branch whose quadratic loses its root stops the run, saying why",
          "[torsional_rig][hysteretic]") {
    using Rig = TorsionalRig<HystereticFriction>;
    SolverOptions o;
    o.method = Method::cvode_bdf;
    o.rtol = GENERATE(1e-8, 1e-10);
    o.atol = 1e-3 * o.rtol;
    INFO("rtol " << o.rtol);
    SECTION("p02 < 0: the discriminant reaches 0 at S - P0 = B^2 / (4 |p02|)") {
        HystereticFriction::Params hp;
        hp.stick_slope = 1030.0;  // break-away 1.03 N m, just above P0
        hp.accelerating.c00 = 1.0;
        hp.accelerating.c02 = -1e-3;
        hp.decelerating.c00 = 1.0;
        try {
            (void)simulate(Rig(slow_drive(), HystereticFriction(hp)), 4.0, o);
            FAIL("expected a SimulationError");
        } catch (const SimulationError& e) {
            const std::string what = e.what();
            INFO(what);
            CHECK(contains(what, "no consistent friction branch"));
            CHECK(contains(what, "discriminant"));
            CHECK_FALSE(contains(what, "branch_gap = hold"));  // holding al = 0 cannot help a lost root
            const double s_loss = 1.0 + 0.0149 * 0.0149 / (4 * 1e-3);  // 1.0555 N m
            CHECK(contains(what, "shaft torque S = 1.0555"));
            REQUIRE(e.partial() != nullptr);
            const double* x = row(*e.partial(), e.partial()->rows() - 1);
            CHECK(Rig(slow_drive(), HystereticFriction(hp)).shaft_torque(x) == Approx(s_loss).epsilon(1e-6));
        }
    }
    SECTION("p02 = 0, p11 < 0: the effective inertia J2 + p11 w reaches 0 at w = 7.45 rad/s") {
        // al = -C / B grows without bound as B -> 0: the guard on B must stop the run before the solver does
        HystereticFriction::Params hp;
        hp.stick_slope = 1200.0;
        hp.accelerating.c00 = 1.0;
        hp.accelerating.c11 = -2e-3;
        hp.decelerating.c00 = 1.0;
        const TorsionalRigParams p;  // w_ref = 5.76 rad/s: the disc overshoots past 7.45 rad/s
        try {
            (void)simulate(Rig(p, HystereticFriction(hp)), 2.0, o);
            FAIL("expected a SimulationError");
        } catch (const SimulationError& e) {
            const std::string what = e.what();
            INFO(what);
            CHECK(contains(what, "no consistent friction branch"));
            CHECK(contains(what, "effective inertia"));
            CHECK(e.time_reached() == Approx(0.7961).epsilon(1e-3));
        }
    }
}

// -------------------------------------------------------------------------------------------- symmetry

namespace {
/// Reversing w_ref mirrors the whole run: every state but the energy integrals changes sign, the disc and motor
/// modes flip side, the events happen at the same times. Exercises the odd extension of eq 6 and the negative
/// side of every mode. Dormand-Prince is odd itself, so the mirror is exact to rounding (`tolerance` 1e-12);
/// CVODE's difference-quotient Jacobian perturbs y_j by +|inc| on both sides, so BDF runs agree to the
/// integration tolerance only.
template <class Law>
void check_mirror(TorsionalRigParams p, const Law& law, Method method, double t_end, double tolerance) {
    using Rig = TorsionalRig<Law>;
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = grid(0.0, t_end, 12);
    const Result forwards = simulate(Rig(p, law), t_end, o);
    p.reference_speed = -p.reference_speed;
    const Result backwards = simulate(Rig(p, law), t_end, o);
    REQUIRE(forwards.events.size() == backwards.events.size());
    REQUIRE(forwards.events.size() >= 3);
    for (std::size_t k = 0; k < forwards.events.size(); ++k) {
        const Event &a = forwards.events[k], &b = backwards.events[k];
        INFO("event " << k << ": " << a.name << " " << a.mode_before_name << " -> " << a.mode_after_name << " | "
                      << b.name << " " << b.mode_before_name << " -> " << b.mode_after_name);
        CHECK(b.time == Approx(a.time).epsilon(tolerance));
        CHECK(Rig::disc_mode_of(b.mode_after) == -Rig::disc_mode_of(a.mode_after));
        CHECK(Rig::motor_mode_of(b.mode_after) == -Rig::motor_mode_of(a.mode_after));
    }
    const std::size_t first_integral = Rig::motor_work;
    for (std::size_t k = 0; k < forwards.rows(); ++k) {
        INFO("t = " << forwards.t[k]);
        CHECK(backwards.friction_force[k] == Approx(-forwards.friction_force[k]).margin(tolerance));
        CHECK(Rig::disc_mode_of(backwards.mode[k]) == -Rig::disc_mode_of(forwards.mode[k]));
        CHECK(Rig::motor_mode_of(backwards.mode[k]) == -Rig::motor_mode_of(forwards.mode[k]));
        for (std::size_t c = 0; c < forwards.state_count(); ++c) {
            const double sign = c >= first_integral ? 1.0 : -1.0;
            INFO(forwards.state_names[c]);
            CHECK(backwards.state(k, c) == Approx(sign * forwards.state(k, c)).epsilon(tolerance).margin(tolerance));
        }
    }
}
}  // namespace

TEST_CASE("torsional rig: reversing w_ref mirrors the run (odd laws, negative-side modes)", "[torsional_rig]") {
    SECTION("Coulomb with stick") {
        check_mirror(slow_drive(), Coulomb(0.3, 0.4), Method::dormand_prince, 6.0, 1e-12);
    }
    SECTION("hysteretic, N0 >= P0") {
        // Dormand-Prince crawls through the stiff band (~1e5 steps, ~40 ms) but mirrors exactly
        check_mirror(slow_drive(), stick_slip_hysteretic(), Method::dormand_prince, 5.0, 1e-12);
        check_mirror(slow_drive(), stick_slip_hysteretic(), Method::cvode_bdf, 5.0, 1e-6);
    }
    SECTION("hysteretic, N0 < P0, hold") {
        check_mirror(TorsionalRigParams{}, gap_law(BranchGap::hold), Method::cvode_bdf, 5.0, 1e-6);
    }
}

TEST_CASE("torsional rig: the disc torque scales with N2 (eq 6: N2 / N_ref - engine laws: r F(N2))",
          "[torsional_rig][hysteretic]") {
    // Twice the normal force with half the coefficients (hysteretic), or with half the contact radius (Coulomb):
    // the same disc torque, so the same run.
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = grid(0.0, 4.0, 8);
    const auto same_run = [](const Result& a, const Result& b) {
        REQUIRE(a.events.size() == b.events.size());
        REQUIRE(a.events.size() >= 3);
        for (std::size_t k = 0; k < a.events.size(); ++k) CHECK(b.events[k].time == Approx(a.events[k].time).epsilon(1e-8));
        for (std::size_t k = 0; k < a.rows(); ++k) {
            CHECK(b.friction_force[k] == Approx(a.friction_force[k]).margin(1e-7));
            CHECK(b.state(k, 1) == Approx(a.state(k, 1)).margin(1e-7));
        }
    };
    TorsionalRigParams p = slow_drive(), doubled = slow_drive();
    doubled.normal_force = 2 * p.normal_force;
    SECTION("hysteretic") {
        HystereticFriction::Params half = stick_slip_hysteretic().params();
        half.stick_slope /= 2;
        for (BranchPolynomial* c : {&half.accelerating, &half.decelerating})
            *c = {c->c00 / 2, c->c10 / 2, c->c01 / 2, c->c20 / 2, c->c11 / 2, c->c02 / 2};
        o.method = Method::cvode_bdf;
        same_run(simulate(TorsionalRig<HystereticFriction>(p, stick_slip_hysteretic()), 4.0, o),
                 simulate(TorsionalRig<HystereticFriction>(doubled, HystereticFriction(half)), 4.0, o));
    }
    SECTION("Coulomb") {
        doubled.contact_radius = p.contact_radius / 2;
        o.method = Method::dormand_prince;
        same_run(simulate(TorsionalRig<Coulomb>(p, Coulomb(0.3, 0.4)), 4.0, o),
                 simulate(TorsionalRig<Coulomb>(doubled, Coulomb(0.3, 0.4)), 4.0, o));
    }
}

// ------------------------------------------------------------------------------------------- bad input

TEST_CASE("torsional rig rejects every non-physical parameter, naming it", "[torsional_rig][validation]") {
    using P = TorsionalRigParams;
    const std::vector<double> not_positive{0.0, -0.0, -1.0, -1e-300, kNaN, kInf, -kInf};
    const std::vector<double> negative_or_nonfinite{-1.0, -1e-300, kNaN, kInf, -kInf};
    const std::vector<double> non_finite{kNaN, kInf, -kInf};
    struct Rule {
        const char* name;
        double P::*field;
        const std::vector<double>* bad;
    };
    const std::vector<Rule> rules{
        {"disc_inertia", &P::disc_inertia, &not_positive},
        {"shaft_stiffness", &P::shaft_stiffness, &not_positive},
        {"shaft_damping", &P::shaft_damping, &negative_or_nonfinite},
        {"motor_inertia", &P::motor_inertia, &not_positive},
        {"gear_ratio", &P::gear_ratio, &not_positive},
        {"inductance", &P::inductance, &not_positive},
        {"resistance", &P::resistance, &not_positive},
        {"torque_constant", &P::torque_constant, &not_positive},
        {"back_emf_constant", &P::back_emf_constant, &negative_or_nonfinite},
        {"motor_friction_torque", &P::motor_friction_torque, &negative_or_nonfinite},
        {"motor_viscous_coefficient", &P::motor_viscous_coefficient, &negative_or_nonfinite},
        {"proportional_gain", &P::proportional_gain, &negative_or_nonfinite},
        {"integral_gain", &P::integral_gain, &negative_or_nonfinite},
        {"reference_speed", &P::reference_speed, &non_finite},
        {"normal_force", &P::normal_force, &not_positive},
        {"contact_radius", &P::contact_radius, &not_positive},
        {"initial_disc_speed", &P::initial_disc_speed, &non_finite},
        {"initial_drive_speed", &P::initial_drive_speed, &non_finite},
    };
    CHECK(rules.size() == sizeof(P) / sizeof(double));  // every field of TorsionalRigParams has a rule
    for (const Rule& rule : rules)
        for (double v : *rule.bad) {
            P p;
            p.*(rule.field) = v;
            INFO(rule.name << " = " << v);
            CHECK(rejected_parameter([&] { (void)TorsionalRig<Coulomb>(p, Coulomb(0.3)); }) == rule.name);
            CHECK(rejected_parameter([&] { (void)TorsionalRig<HystereticFriction>(p, stick_slip_hysteretic()); }) ==
                  rule.name);
            CHECK(contains(rejection_message([&] { (void)TorsionalRig<Coulomb>(p, Coulomb(0.3)); }), rule.name));
        }
    // valid boundary values: no damping, no back-emf, no motor friction, no control, reverse or zero speeds
    P edge;
    edge.shaft_damping = 0.0;
    edge.back_emf_constant = 0.0;
    edge.motor_friction_torque = 0.0;
    edge.motor_viscous_coefficient = 0.0;
    edge.proportional_gain = 0.0;
    edge.integral_gain = 0.0;
    edge.reference_speed = -3.0;
    edge.initial_disc_speed = -1.0;
    edge.initial_drive_speed = 2.0;
    CHECK(rejected_parameter([&] { (void)TorsionalRig<Coulomb>(edge, Coulomb(0.3)); }) == "<nothing thrown>");
}

// --------------------------------------------------------------------------------------- mode encoding

TEST_CASE("torsional rig: recorded mode = disc mode + 16 (motor mode - 1), round trip", "[torsional_rig]") {
    using Rig = TorsionalRig<HystereticFriction>;
    std::set<int> seen;
    for (int disc = -3; disc <= 3; ++disc)
        for (int motor : {-1, 0, 1}) {
            const int m = Rig::encode_mode(disc, motor);
            INFO("disc " << disc << ", motor " << motor << " -> " << m);
            CHECK(Rig::disc_mode_of(m) == disc);
            CHECK(Rig::motor_mode_of(m) == motor);
            CHECK(seen.insert(m).second);  // one code per pair
        }
    CHECK(seen.size() == 21);
    for (int disc = -3; disc <= 3; ++disc) CHECK(Rig::encode_mode(disc, slip_positive) == disc);  // normal running
    CHECK(Rig::encode_mode(stick, stick) == -16);
    CHECK(Rig::encode_mode(stick, slip_negative) == -32);

    // names: the disc's, with the motor's state appended when it is not turning forwards
    const Rig rig(TorsionalRigParams{}, stick_slip_hysteretic());
    CHECK(std::string(rig.mode_name(Rig::encode_mode(3, 1))) == "hold_positive");
    CHECK(std::string(rig.mode_name(Rig::encode_mode(-3, -1))) == "hold_negative+motor_reversed");
    CHECK(std::string(rig.mode_name(Rig::encode_mode(0, 0))) == "stick+motor_stick");
    CHECK(std::string(rig.mode_name(Rig::encode_mode(-2, 0))) == "decelerating_negative+motor_stick");
    const TorsionalRig<Coulomb> coulomb(TorsionalRigParams{}, Coulomb(0.3));
    CHECK(std::string(coulomb.mode_name(Rig::encode_mode(-1, -1))) == "slip_negative+motor_reversed");
    CHECK(std::string(coulomb.mode_name(Rig::encode_mode(1, 1))) == "slip_positive");
}

TEST_CASE("papers.hpp: paper 001's Fig. 7 set-up stick-slips as the paper reports", "[torsional_rig][papers]") {
    // Tables 1-2 at w_ref = 5.76 rad/s, N2 = 35 N with the eq 6 set chosen for Fig. 7. The paper: 0.83 Hz measured,
    // 0.84 simulated; peak disc speed 13.55 rad/s measured, 14 simulated; the disc sticks every cycle.
    const TorsionalRigParams p = paper001_fig7_params();
    CHECK(p.reference_speed == 5.76);
    CHECK(p.normal_force == 35.0);
    const TorsionalRig<HystereticFriction> rig(p, paper001_fig7_friction());
    SolverOptions o;
    o.method = Method::dormand_prince;
    for (int i = 0; i <= 3000; ++i) o.output_times.push_back(0.01 * i);
    const Result r = simulate(rig, 30.0, o);
    const std::vector<double> w = r.column_values("disc_speed");
    const LimitCycle c = limit_cycle(r.t.data(), w.data(), r.rows(), 15.0);
    CHECK(c.frequency > 0.83);
    CHECK(c.frequency < 0.84);
    CHECK(c.peak > 13.55);
    CHECK(c.peak < 14.0);
    CHECK(c.stick_fraction > 0.0);
}

TEST_CASE("papers.hpp: paper 000's Fig. 7(a) set-up is the dry case of the figure", "[axial_rig][papers]") {
    const AxialRigParams p = paper000_fig7a_params();  // u = 5 mm, f = 17 Hz, v_d = 60 mm/min, F_N = 90 N
    CHECK(p.amplitude == 5e-3);
    CHECK(p.frequency == 17.0);
    CHECK(p.sliding_velocity == Approx(60e-3 / 60.0));
    CHECK(p.normal_force == 90.0);
}
