// Analytic Jacobians of the rigs (what CVODE's Newton iteration uses instead of difference quotients) against
// central differences of the right-hand side, for every law in every mode, at states off the switching surfaces.
#include <array>
#include <cmath>
#include <random>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"

using namespace frictionsim;

namespace {

template <class Rig>
void check_jacobian(const Rig& rig, double t, std::array<double, Rig::state_size> x, int mode) {
    constexpr std::size_t n = Rig::state_size;
    std::array<double, n * n> analytic{};
    rig.jacobian(t, x.data(), mode, analytic.data());
    for (std::size_t c = 0; c < n; ++c) {
        const double h = 1e-7 * std::max(1e-3, std::abs(x[c]));
        std::array<double, n> up = x, down = x, f_up{}, f_down{};
        up[c] += h;
        down[c] -= h;
        rig.rhs(t, up.data(), mode, f_up.data());
        rig.rhs(t, down.data(), mode, f_down.data());
        for (std::size_t r = 0; r < n; ++r) {
            const double numeric = (f_up[r] - f_down[r]) / (2 * h);
            INFO(rig.mode_name(mode) << ": d rhs[" << rig.state_names()[r] << "] / d " << rig.state_names()[c]);
            // rounding in f(x + h) - f(x - h) is ~1e-16 |f| / h: a derivative that is exactly 0 reads as that
            const double rounding = 1e-14 * (std::abs(f_up[r]) + std::abs(f_down[r])) / h;
            CHECK(analytic[c * n + r] == Approx(numeric).epsilon(1e-5).margin(rounding + 1e-9));
        }
    }
}

/// The axial rig at random states in each mode the law has, with the relative velocity kept off zero.
template <class Law>
void check_axial(Law law, std::initializer_list<int> modes) {
    AxialRigParams p;  // Fig. 7(a): u0 = 5 mm, 17 Hz, 90 N
    const AxialRig<Law> rig(p, std::move(law));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> position(-2e-3, 2e-3), speed(0.05, 0.6), deflection(-5e-4, 5e-4),
        time(0.0, 0.1);
    for (int trial = 0; trial < 20; ++trial) {
        for (int mode : modes) {
            std::array<double, AxialRig<Law>::state_size> x{};
            const double t = time(rng);
            x[0] = position(rng);
            // slip in direction `mode`, or sticking (v_r = 0)
            x[1] = rig.surface_velocity(t) + (mode == 0 ? 0.0 : mode * speed(rng));
            for (std::size_t j = 0; j < Law::state_count; ++j) x[2 + j] = deflection(rng);
            check_jacobian(rig, t, x, mode);
        }
    }
}

}  // namespace

TEST_CASE("axial rig Jacobian: analytic = central differences of the right-hand side", "[jacobian][axial_rig]") {
    SECTION("Coulomb, slip and stick") { check_axial(Coulomb(0.41, 0.45), {slip_negative, stick, slip_positive}); }
    SECTION("Stribeck, delta = 2 and 1, viscous") {
        check_axial(Stribeck(Stribeck::Params{0.3, 0.45, 0.1, 2.0, 5.0, 0.0}), {slip_negative, stick, slip_positive});
        check_axial(Stribeck(Stribeck::Params{0.3, 0.45, 0.1, 1.0, 0.0, 0.0}), {slip_negative, slip_positive});
    }
    SECTION("Dahl, alpha = 1 and 0.5") {
        check_axial(Dahl(0.41, 4e4), {slip_negative, slip_positive});
        check_axial(Dahl(0.41, 4e4, 0.5), {slip_negative, slip_positive});
    }
    SECTION("LuGre") {
        LuGre::Params lp;
        lp.coulomb_coefficient = 0.41;
        lp.static_coefficient = 0.45;
        lp.stribeck_velocity = 0.1;
        check_axial(LuGre(lp), {0});
    }
    SECTION("elasto-plastic: elastic, transition and LuGre regimes (z_ba = 1.8e-4 m, z_max >= 3.7e-4 m)") {
        ElastoPlastic::Params ep;
        ep.coulomb_coefficient = 0.41;
        ep.static_coefficient = 0.45;
        ep.stribeck_velocity = 0.1;
        check_axial(ElastoPlastic(ep), {slip_negative, slip_positive});
    }
}

TEST_CASE("kinematic rig Jacobian: analytic = central differences (the law's states)", "[jacobian][kinematic_rig]") {
    const HarmonicSlidingVelocity v(1e-3, 0.5, 2 * pi * 17.0);  // paper 000: v_r = v_d - v_a cos(w t)
    LuGre::Params lp;
    lp.coulomb_coefficient = 0.41;
    lp.static_coefficient = 0.45;
    lp.stribeck_velocity = 0.1;
    const KinematicRig<LuGre, HarmonicSlidingVelocity> lugre(LuGre(lp), v, ConstantSignal(90.0));
    const KinematicRig<Dahl, HarmonicSlidingVelocity> dahl(Dahl(0.41, 4e4), v, ConstantSignal(90.0));
    ElastoPlastic::Params ep;
    ep.coulomb_coefficient = 0.41;
    ep.static_coefficient = 0.45;
    ep.stribeck_velocity = 0.1;
    const KinematicRig<ElastoPlastic, HarmonicSlidingVelocity> elasto_plastic(ElastoPlastic(ep), v,
                                                                              ConstantSignal(90.0));
    for (double t : {0.003, 0.011, 0.02, 0.041}) {
        for (double z : {-4e-4, 1e-5, 2.5e-4, 6e-4}) {
            check_jacobian(lugre, t, {z, 0.1, 0.01}, 0);
            check_jacobian(dahl, t, {z, 0.1, 0.01}, sign_of(v(t)));
            check_jacobian(elasto_plastic, t, {z, 0.1, 0.01}, sign_of(v(t)));
        }
    }
}

namespace {
/// The torsional rig at random states in the given disc modes, with the motor turning, stuck and reversed.
template <class Law>
void check_torsional(Law law, std::initializer_list<int> disc_modes) {
    using Rig = TorsionalRig<Law>;
    const Rig rig(TorsionalRigParams{}, std::move(law));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 10; ++trial) {
        for (int disc : disc_modes) {
            for (int motor : {slip_positive, stick, slip_negative}) {
                std::array<double, Rig::state_size> x{};
                x[Rig::disc_angle] = 3.0 * unit(rng);
                // a speed on the mode's side, off the switching surfaces; ~0 in stick
                x[Rig::disc_speed] = disc == 0 ? 2e-4 * unit(rng) : (disc > 0 ? 1 : -1) * (3.0 + 2.0 * unit(rng));
                x[Rig::shaft_twist] = (disc < 0 ? -1 : 1) * (2.5 + 0.5 * unit(rng));  // S on the slip's side
                x[Rig::drive_speed] = motor == stick ? 0.0 : motor * (5.0 + unit(rng));
                x[Rig::current] = 1.5 + unit(rng);
                x[Rig::speed_error_integral] = 0.9 + 0.1 * unit(rng);
                for (std::size_t j = 0; j < Law::state_count; ++j) x[Rig::law_state + j] = 1e-4 * unit(rng);
                check_jacobian(rig, 0.0, x, Rig::encode_mode(disc, motor));
            }
        }
    }
}
}  // namespace

TEST_CASE("torsional rig Jacobian: analytic = central differences, every disc and motor mode",
          "[jacobian][torsional_rig]") {
    SECTION("Coulomb") { check_torsional(Coulomb(0.2714, 0.5), {slip_negative, stick, slip_positive}); }
    SECTION("Stribeck") {
        check_torsional(Stribeck(Stribeck::Params{0.22, 0.3566, 0.3, 1.0, 0.0, 0.0}), {slip_negative, slip_positive});
    }
    SECTION("Dahl") { check_torsional(Dahl(0.2714, 1e4), {slip_negative, slip_positive}); }
    SECTION("LuGre") {
        check_torsional(LuGre(LuGre::Params{0.22, 0.3453, 0.3, 1e5, 300.0, 0.0}), {0});
    }
    SECTION("elasto-plastic") {
        check_torsional(ElastoPlastic(ElastoPlastic::Params{{0.22, 0.3453, 0.3, 1e5, 300.0, 0.0}, 0.5}),
                        {slip_negative, slip_positive});
    }
    SECTION("eq 6: stick band, both branches on both sides, hold") {
        HystereticFriction::Params hp = paper001_fig7_friction().params();
        hp.accelerating.c11 = 2e-4;  // every coefficient in play
        hp.decelerating.c11 = -1e-4;
        hp.decelerating.c02 = -1e-5;
        check_torsional(HystereticFriction(hp), {-3, -2, -1, 0, 1, 2, 3});
    }
}

TEST_CASE("axial rig Jacobian: CVODE BDF reaches the same answer with it as with difference quotients",
          "[jacobian][cvode]") {
    // A wrapper that hides the rig's jacobian() makes CVODE fall back to difference quotients.
    struct WithoutJacobian : AxialRig<Dahl> {
        using AxialRig<Dahl>::AxialRig;
        void jacobian() const = delete;
    };
    static_assert(has_dense_jacobian_v<AxialRig<Dahl>>);
    static_assert(!has_dense_jacobian_v<WithoutJacobian>);
    AxialRigParams p;
    SolverOptions o;
    o.method = Method::cvode_bdf;
    o.rtol = 1e-9;
    o.atol = 1e-13;
    o.output_times = {2.0 - 10 / 17.0, 2.0};
    const AxialRig<Dahl> rig(p, Dahl(0.41, 4e4));
    const Result analytic = simulate(rig, 2.0, o);
    const Result quotients = simulate(WithoutJacobian(p, Dahl(0.41, 4e4)), 2.0, o);
    o.method = Method::dormand_prince;
    o.rtol = 1e-12;
    o.atol = 1e-16;
    const Result reference = simulate(rig, 2.0, o);
    const double expected = mean_friction_over_cycles(reference, rig.period(), 0.0, 10);
    CHECK(mean_friction_over_cycles(analytic, rig.period(), 0.0, 10) == Approx(expected).epsilon(1e-6));
    CHECK(mean_friction_over_cycles(quotients, rig.period(), 0.0, 10) == Approx(expected).epsilon(1e-6));
    CHECK(analytic.stats.jacobian_evaluations > 0);
    // each difference-quotient Jacobian costs state_size right-hand sides; the analytic one none
    CHECK(analytic.stats.rhs_evaluations < quotients.stats.rhs_evaluations);
}
