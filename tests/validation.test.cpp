// Bad input (issue 2, last bullet): every non-physical parameter (negative, zero where it must be positive, NaN,
// infinite, or breaking a relational rule) throws frictionsim::InvalidParameter whose parameter() is the
// parameter's name and whose what() contains it; valid boundary values are accepted. Also: a run that goes past
// its sampled data or whose normal force turns non-positive fails cleanly.
//
// Table-driven: each ParameterCheck names a parameter, lists the values it must reject, and builds the object with one
// such value (every other parameter valid).
#include <array>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <string>
#include <typeinfo>
#include <vector>

#include <frictionsim/simulate.hpp>
#if __has_include(<frictionsim/friction/power_law.hpp>)
#include <frictionsim/friction/power_law.hpp>
#define FRICTIONSIM_TEST_POWER_LAW 1
#endif
#if __has_include(<frictionsim/contact/hydraulic_oscillator.hpp>)
#include <frictionsim/contact/hydraulic_oscillator.hpp>
#define FRICTIONSIM_TEST_HOT 1
#endif
#if __has_include(<frictionsim/analysis/cycle_mean.hpp>)
#include <frictionsim/analysis/cycle_mean.hpp>
#define FRICTIONSIM_TEST_CYCLE_MEAN 1
#endif

#include "catch.hpp"
#include "rejection.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::contains;
using frictionsim::test::kInf;
using frictionsim::test::kNaN;

namespace {

// The bad values of each kind of rule.
const std::vector<double> not_positive{-1.0, -1e-300, -0.0, 0.0, kNaN, kInf, -kInf};  // must be > 0 and finite
const std::vector<double> negative_or_nonfinite{-1.0, -1e-300, kNaN, kInf, -kInf};    // must be >= 0 and finite
const std::vector<double> non_finite{kNaN, kInf, -kInf};                              // must be finite

/// `call()` must throw InvalidParameter naming `name` (parameter() == name, what() mentions it).
const auto expect_invalid = [](const std::string& name, auto&& call) {
    try {
        call();
    } catch (const InvalidParameter& e) {
        INFO("what(): " << e.what());
        CHECK(e.parameter() == name);
        CHECK(contains(e.what(), name));
        return;
    } catch (const std::exception& e) {
        FAIL_CHECK("expected InvalidParameter naming '" << name << "', got " << typeid(e).name() << ": "
                                                        << e.what());
        return;
    }
    FAIL_CHECK("expected InvalidParameter naming '" << name << "', nothing was thrown");
};

struct ParameterCheck {
    std::string name;
    std::vector<double> bad;
    std::function<void(double)> build;  ///< builds the object with this parameter set to the value
};

void check_rules(const std::vector<ParameterCheck>& rules) {
    for (const ParameterCheck& r : rules) {
        for (const double v : r.bad) {
            INFO(r.name << " = " << v);
            expect_invalid(r.name, [&] { r.build(v); });
        }
    }
}

/// Builder for aggregates of doubles: copy `valid`, set one field, hand it to `make`.
template <class P, class Field, class Make>
std::function<void(double)> with(const P& valid, double Field::*field, Make make) {  // Field: P or a base of it
    return [=](double v) {
        P p = valid;
        p.*field = v;
        make(p);
    };
}

/// A small valid system for the solver-side checks: Coulomb driven at constant v_r.
using SimpleRig = KinematicRig<Coulomb, ConstantSignal>;
SimpleRig simple_rig() { return SimpleRig(Coulomb(0.3), ConstantSignal(1e-3), ConstantSignal(10.0)); }

const std::array<Method, 3> all_methods{Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams};

}  // namespace

// ------------------------------------------------------------------------------------------------- laws

TEST_CASE("Coulomb rejects non-physical coefficients, naming them", "[validation][coulomb]") {
    check_rules({
        {"friction_coefficient", not_positive, [](double v) { (void)Coulomb(v); }},
        {"friction_coefficient", not_positive, [](double v) { (void)Coulomb(v, 0.5); }},
        // static >= kinetic; NaN means "equal to kinetic" (the default), so only infinities and smaller values
        {"static_coefficient", {0.29, 0.0, -0.3, kInf, -kInf}, [](double v) { (void)Coulomb(0.3, v); }},
    });
    CHECK_NOTHROW(Coulomb(0.3, 0.3));  // boundary: static == kinetic
    CHECK(Coulomb(0.3).static_coefficient() == 0.3);
    CHECK(Coulomb(0.3, kNaN).static_coefficient() == 0.3);
}

TEST_CASE("Stribeck rejects every non-physical parameter, naming it", "[validation][stribeck]") {
    const Stribeck::Params ok{};
    const auto make = [](const Stribeck::Params& p) { (void)Stribeck(p); };
    using P = Stribeck::Params;
    check_rules({
        {"coulomb_coefficient", not_positive, with(ok, &P::coulomb_coefficient, make)},
        {"static_coefficient", {0.29, 0.0, -1.0, kNaN, kInf, -kInf}, with(ok, &P::static_coefficient, make)},
        {"stribeck_velocity", not_positive, with(ok, &P::stribeck_velocity, make)},
        {"shape_exponent", not_positive, with(ok, &P::shape_exponent, make)},
        {"viscous_coefficient", negative_or_nonfinite, with(ok, &P::viscous_coefficient, make)},
        {"karnopp_band", negative_or_nonfinite, with(ok, &P::karnopp_band, make)},
    });
    // boundaries
    Stribeck::Params edge = ok;
    edge.static_coefficient = edge.coulomb_coefficient;
    edge.viscous_coefficient = 0.0;
    edge.karnopp_band = 0.0;
    CHECK_NOTHROW(Stribeck(edge));
    edge.karnopp_band = 1e-6;
    CHECK_NOTHROW(Stribeck(edge));
}

TEST_CASE("Dahl rejects non-physical parameters, naming them - exponent in [0.5, 50]", "[validation][dahl]") {
    std::vector<double> bad_exponent = negative_or_nonfinite;
    for (double v : {0.0, 0.1, 0.3, 0.4999, 50.001, 1e3}) bad_exponent.push_back(v);
    check_rules({
        {"friction_coefficient", not_positive, [](double v) { (void)Dahl(v, 3e4); }},
        {"tangential_stiffness", not_positive, [](double v) { (void)Dahl(0.3, v); }},
        {"exponent", bad_exponent, [](double v) { (void)Dahl(0.3, 3e4, v); }},
    });
    CHECK(rejection_message([] { (void)Dahl(0.3, 3e4, 0.2); }).find("in [0.5, 50]") != std::string::npos);
    CHECK_NOTHROW(Dahl(0.3, 3e4, 0.5));
    CHECK_NOTHROW(Dahl(0.3, 3e4, 50.0));

    // the lowest exponent runs in reasonable time: the ramp towards the limit mu N = 3 N, dz/dt = v_r sqrt(b),
    // b = 1 - F / (mu N), has F = mu N (1 - (1 - k_t v_r t / (2 mu N))^2) until saturation
    SolverOptions o;
    o.output_times = {0.0, 0.1};
    const Result r = simulate(KinematicRig<Dahl, ConstantSignal>(Dahl(0.3, 3e4, 0.5), ConstantSignal(1e-3),
                                                                 ConstantSignal(10.0)),
                              0.1, o);
    CHECK(r.completed);
    CHECK(r.friction_force.back() == Approx(3.0 * (1.0 - std::pow(1.0 - 3e4 * 1e-3 * 0.1 / 6.0, 2))).epsilon(1e-6));
}

namespace {
/// The rules LuGre and ElastoPlastic share: their six bristle parameters (LuGre::Params, a base of the other's).
template <class Law>
std::vector<ParameterCheck> bristle_rules(const typename Law::Params& ok) {
    const auto make = [](const typename Law::Params& p) { (void)Law(p); };
    using P = LuGre::Params;
    return {
        {"coulomb_coefficient", not_positive, with(ok, &P::coulomb_coefficient, make)},
        {"static_coefficient", {0.99, 0.0, -1.0, kNaN, kInf, -kInf}, with(ok, &P::static_coefficient, make)},
        {"stribeck_velocity", not_positive, with(ok, &P::stribeck_velocity, make)},
        {"bristle_stiffness", not_positive, with(ok, &P::bristle_stiffness, make)},
        {"bristle_damping", negative_or_nonfinite, with(ok, &P::bristle_damping, make)},
        {"viscous_damping", negative_or_nonfinite, with(ok, &P::viscous_damping, make)},
    };
}
}  // namespace

TEST_CASE("LuGre rejects every non-physical parameter, naming it", "[validation][lugre]") {
    const LuGre::Params ok{};
    check_rules(bristle_rules<LuGre>(ok));
    LuGre::Params edge = ok;
    edge.static_coefficient = edge.coulomb_coefficient;
    edge.bristle_damping = 0.0;
    edge.viscous_damping = 0.0;
    CHECK_NOTHROW(LuGre(edge));
}

TEST_CASE("ElastoPlastic rejects every non-physical parameter, naming it", "[validation][elasto_plastic]") {
    const ElastoPlastic::Params ok{};
    std::vector<ParameterCheck> rules = bristle_rules<ElastoPlastic>(ok);
    rules.push_back({"breakaway_fraction", {-0.1, 1.0, 1.5, kNaN, kInf, -kInf},
                     with(ok, &ElastoPlastic::Params::breakaway_fraction, [](const ElastoPlastic::Params& p) {
                         (void)ElastoPlastic(p);
                     })});
    check_rules(rules);
    ElastoPlastic::Params edge = ok;
    edge.breakaway_fraction = 0.0;
    CHECK_NOTHROW(ElastoPlastic(edge));
}

#ifdef FRICTIONSIM_TEST_POWER_LAW
TEST_CASE("power-law coefficient rejects non-physical parameters, naming them", "[validation][power_law]") {
    const PowerLawCoefficient law({0.2, -0.2});
    std::vector<double> bad_exponent = non_finite;
    for (double v : {2.001, -2.001, 1e300, -1e300}) bad_exponent.push_back(v);  // 1e300 returned inf before
    check_rules({
        {"eta", not_positive, [](double v) { (void)PowerLawCoefficient({v, -0.2}); }},
        {"exponent", bad_exponent, [](double v) { (void)PowerLawCoefficient({0.2, v}); }},
        {"eta", not_positive, [](double v) { (void)PowerLawCoefficient::from_eq15(v, -0.2); }},
        {"exponent", bad_exponent, [](double v) { (void)PowerLawCoefficient::from_eq15(0.2, v); }},
        {"vibration_velocity_amplitude", not_positive, [&](double v) { (void)law.coefficient(v, 1e-3); }},
        {"sliding_velocity", not_positive, [&](double v) { (void)law.coefficient(0.5, v); }},
        {"normal_force", negative_or_nonfinite, [&](double v) { (void)law.friction_force(v, 0.5, 1e-3); }},
        {"amplitude", negative_or_nonfinite, [](double v) { (void)vibration_velocity_amplitude(v, 17.0); }},
        {"frequency", negative_or_nonfinite, [](double v) { (void)vibration_velocity_amplitude(5e-3, v); }},
    });
    expect_invalid("lubricant", [] { (void)lubricant_from_name("mud"); });
    expect_invalid("lubricant", [] { (void)PowerLawCoefficient::from_table5(""); });
    CHECK_NOTHROW(PowerLawCoefficient({0.2, 0.0}));
    CHECK_NOTHROW(PowerLawCoefficient({0.2, -2.0}));
    // the largest exponent with an extreme ratio overflows: named, never inf
    const PowerLawCoefficient steep({1.0, 2.0});
    CHECK(rejected_parameter([&] { (void)steep.coefficient(1e300, 1e-300); }) == "vibration_velocity_amplitude");
    CHECK(law.friction_force(0.0, 0.5, 1e-3) == 0.0);
    CHECK(vibration_velocity_amplitude(0.0, 0.0) == 0.0);
}
#endif

// ------------------------------------------------------------------------------------------------- rigs

TEST_CASE("AxialRig rejects every non-physical parameter, naming it", "[validation][axial_rig]") {
    const AxialRigParams ok{};
    const auto make = [](const AxialRigParams& p) { (void)AxialRig<Coulomb>(p, Coulomb(0.3)); };
    using P = AxialRigParams;
    check_rules({
        {"mass", not_positive, with(ok, &P::mass, make)},
        {"drive_stiffness", not_positive, with(ok, &P::drive_stiffness, make)},
        {"sliding_velocity", negative_or_nonfinite, with(ok, &P::sliding_velocity, make)},
        {"amplitude", negative_or_nonfinite, with(ok, &P::amplitude, make)},
        {"frequency", not_positive, with(ok, &P::frequency, make)},
        {"normal_force", not_positive, with(ok, &P::normal_force, make)},
        {"gravitational_acceleration", negative_or_nonfinite, with(ok, &P::gravitational_acceleration, make)},
        {"initial_velocity", non_finite, with(ok, &P::initial_velocity, make)},
        {"initial_position", non_finite,
         [&](double v) {
             P p = ok;
             p.initial_position = v;
             make(p);
         }},
    });
    // the same rules hold with gravity on and with a state law
    AxialRigParams vertical = ok;
    vertical.gravity = true;
    check_rules({
        {"gravitational_acceleration", negative_or_nonfinite,
         with(vertical, &P::gravitational_acceleration,
              [](const P& p) { (void)AxialRig<Dahl>(p, Dahl(0.3, 3e4)); })},
        {"mass", not_positive, with(vertical, &P::mass, [](const P& p) { (void)AxialRig<LuGre>(p, LuGre({})); })},
    });
}

TEST_CASE("AxialRig accepts and runs the boundary values: no vibration, no drive, no gravity",
          "[validation][axial_rig]") {
    AxialRigParams p;
    p.amplitude = 0.0;
    p.sliding_velocity = 0.0;
    p.gravity = true;
    p.gravitational_acceleration = 0.0;
    p.initial_position = -1e-4;  // any finite start, negative included
    p.initial_velocity = -1e-3;
    SolverOptions o;
    o.output_times = {0.0, 0.02};
    for (const Method m : all_methods) {
        o.method = m;
        INFO(method_name(m));
        const Result coulomb = simulate(AxialRig<Coulomb>(p, Coulomb(0.3)), 0.02, o);
        CHECK(coulomb.completed);
        const Result dahl = simulate(AxialRig<Dahl>(p, Dahl(0.3, 3e4, 0.5)), 0.02, o);
        CHECK(dahl.completed);
    }
}

TEST_CASE("signals reject non-physical parameters, naming them", "[validation][signals]") {
    check_rules({
        {"value", non_finite, [](double v) { (void)ConstantSignal(v); }},
        {"sliding_velocity", non_finite, [](double v) { (void)HarmonicSlidingVelocity(v, 0.1, 100.0); }},
        {"velocity_amplitude", negative_or_nonfinite, [](double v) { (void)HarmonicSlidingVelocity(1e-3, v, 100.0); }},
        {"angular_frequency", not_positive, [](double v) { (void)HarmonicSlidingVelocity(1e-3, 0.1, v); }},
        // samples: times finite and strictly increasing, values finite (named by the signal's name)
        {"time", {kNaN, kInf, -kInf, 0.0, -1.0, 2.0, 3.0},
         [](double v) { (void)SampledSignal({0.0, v, 2.0}, {1.0, 1.0, 1.0}, "relative_velocity"); }},
        {"time", non_finite, [](double v) { (void)SampledSignal({v, 1.0, 2.0}, {1.0, 1.0, 1.0}, "relative_velocity"); }},
        {"relative_velocity", non_finite,
         [](double v) { (void)SampledSignal({0.0, 1.0, 2.0}, {1.0, v, 1.0}, "relative_velocity"); }},
    });
    // sizes: unequal, and fewer than 2 samples
    expect_invalid("normal_force", [] { (void)SampledSignal({0.0, 1.0, 2.0}, {1.0, 1.0}, "normal_force"); });
    expect_invalid("normal_force", [] { (void)SampledSignal({0.0, 1.0}, {1.0, 1.0, 1.0}, "normal_force"); });
    expect_invalid("normal_force", [] { (void)SampledSignal({0.0}, {1.0}, "normal_force"); });
    expect_invalid("normal_force", [] { (void)SampledSignal({}, {}, "normal_force"); });
    expect_invalid("signal", [] { (void)SampledSignal({0.0}, {1.0}); });  // the default name
    // boundaries: negative constants (a relative velocity), zero amplitude, negative drive, 2 samples
    CHECK_NOTHROW(ConstantSignal(-1.0));
    CHECK_NOTHROW(HarmonicSlidingVelocity(-1e-3, 0.0, 1e-9));
    CHECK_NOTHROW(SampledSignal({-1.0, 1e-300}, {0.0, -5.0}));
}

TEST_CASE("KinematicRig rejects a Karnopp band and a non-finite initial law state", "[validation][kinematic_rig]") {
    Stribeck::Params band{};
    band.karnopp_band = 1e-4;
    expect_invalid("karnopp_band",
                   [&] { (void)KinematicRig<Stribeck, ConstantSignal>(Stribeck(band), ConstantSignal(1e-3),
                                                                      ConstantSignal(10.0)); });
    check_rules({
        {"initial_law_state", non_finite,
         [](double v) {
             (void)KinematicRig<Dahl, ConstantSignal>(Dahl(0.3, 3e4), ConstantSignal(1e-3), ConstantSignal(10.0),
                                                      {v});
         }},
        {"initial_law_state", non_finite,
         [](double v) {
             (void)KinematicRig<LuGre, ConstantSignal>(LuGre({}), ConstantSignal(1e-3), ConstantSignal(10.0), {v});
         }},
    });
    CHECK_NOTHROW(KinematicRig<Stribeck, ConstantSignal>(Stribeck({}), ConstantSignal(1e-3), ConstantSignal(10.0)));
}

namespace {

/// Runs a kinematic Coulomb rig to t = 2 s whose normal force is `normal(t)`.
template <class Normal>
void run_with_normal_force(Normal normal, Method method) {
    KinematicRig<Coulomb, ConstantSignal, Normal> rig(Coulomb(0.3), ConstantSignal(1e-3), std::move(normal));
    SolverOptions o;
    o.method = method;
    o.output_times = {0.0, 2.0};
    (void)simulate(rig, 2.0, o);
}

const auto ramp_to_negative = [](double t) { return 10.0 - 10.0 * t; };  // 0 at t = 1
const auto nan_after_one = [](double t) { return t < 1.0 ? 10.0 : kNaN; };
const auto inf_after_one = [](double t) { return t < 1.0 ? 10.0 : kInf; };

/// A bad value met during the run: InvalidParameter naming `name`, or a SimulationError that names it in
/// what(), stops no later than `t_bad` and keeps the results up to there.
const auto expect_named_failure = [](const std::string& name, double t_bad, auto&& call) {
    try {
        call();
    } catch (const InvalidParameter& e) {
        INFO("what(): " << e.what());
        CHECK(e.parameter() == name);
        CHECK(contains(e.what(), name));
        return;
    } catch (const SimulationError& e) {
        INFO("what(): " << e.what());
        CHECK(contains(e.what(), name));
        CHECK(e.time_reached() <= t_bad);
        CHECK(e.partial() != nullptr);
        return;
    } catch (const std::exception& e) {
        FAIL_CHECK("expected an error naming '" << name << "', got " << typeid(e).name() << ": " << e.what());
        return;
    }
    FAIL_CHECK("expected an error naming '" << name << "', nothing was thrown");
};

}  // namespace

TEST_CASE("KinematicRig: a normal force that turns non-positive during the run stops it, naming normal_force",
          "[validation][kinematic_rig]") {
    for (const Method m : all_methods) {
        INFO(method_name(m));
        expect_named_failure("normal_force", 1.0, [m] { run_with_normal_force(ramp_to_negative, m); });
        expect_named_failure("normal_force", 1.0, [m] { run_with_normal_force(nan_after_one, m); });
        expect_named_failure("normal_force", 1.5, [m] {
            run_with_normal_force(SampledSignal({0.0, 1.0, 2.0}, {10.0, 5.0, -5.0}, "N"), m);
        });
        expect_named_failure("normal_force", 0.0, [m] { run_with_normal_force(ConstantSignal(0.0), m); });
        expect_named_failure("normal_force", 0.0, [m] { run_with_normal_force(ConstantSignal(-1.0), m); });
    }
}

// A value that turns bad during a run is a run-time failure: SimulationError naming the parameter, with the
// time reached and the partial result (a bad value at the start may also come out as InvalidParameter).
TEST_CASE("KinematicRig: an infinite normal force during the run stops it, naming normal_force",
          "[validation][kinematic_rig]") {
    for (const Method m : all_methods) {
        INFO(method_name(m));
        expect_named_failure("normal_force", 1.0, [m] { run_with_normal_force(inf_after_one, m); });
    }
}

// ------------------------------------------------------------------------------------------------- solver

TEST_CASE("SolverOptions: every non-physical field throws InvalidParameter naming it, for every method",
          "[validation][solver]") {
    const SimpleRig rig = simple_rig();
    for (const Method m : all_methods) {
        INFO(method_name(m));
        SolverOptions ok;
        ok.method = m;
        const auto run = [&rig](const SolverOptions& o) { (void)simulate(rig, 1.0, o); };
        using O = SolverOptions;
        const auto vector_option = [&](std::vector<double> O::*field, std::vector<double> values) {
            return [=](double v) {
                O o = ok;
                o.*field = values;
                for (double& x : o.*field)
                    if (std::isnan(x)) x = v;  // the NaN in `values` marks where the bad value goes
                run(o);
            };
        };
        check_rules({
            {"rtol", not_positive, with(ok, &O::rtol, run)},
            {"rtol", {1e-15, 1e-300}, with(ok, &O::rtol, run)},  // below double precision
            {"rtol", {1.0, 5.0}, with(ok, &O::rtol, run)},  // 100% relative error or more
            {"atol", not_positive, with(ok, &O::atol, run)},
            {"atol_per_state", not_positive, vector_option(&O::atol_per_state, {1e-10, kNaN})},
            {"max_step", {-1.0, -0.0, 0.0, kNaN, -kInf}, with(ok, &O::max_step, run)},
            {"initial_step", negative_or_nonfinite, with(ok, &O::initial_step, run)},
            {"event_window", not_positive, with(ok, &O::event_window, run)},
            // output times: finite, strictly increasing (equal or decreasing neighbours, NaN, infinities)
            {"output_times", {kNaN, kInf, -kInf, 0.5, 0.4}, vector_option(&O::output_times, {0.0, 0.5, kNaN, 1.0})},
        });
        // integer fields
        for (const long bad : {0L, -1L, std::numeric_limits<long>::min()}) {
            O o = ok;
            o.max_steps = bad;
            expect_invalid("max_steps", [&] { run(o); });
        }
        for (const int bad : {0, -1, std::numeric_limits<int>::min()}) {
            O o = ok;
            o.max_events_in_window = bad;
            expect_invalid("max_events_in_window", [&] { run(o); });
        }
        // atol_per_state of the wrong size (the rig has 2 states)
        for (const std::vector<double>& sizes : {std::vector<double>{1e-10}, std::vector<double>(3, 1e-10)}) {
            O o = ok;
            o.atol_per_state = sizes;
            expect_invalid("atol_per_state", [&] { run(o); });
        }
    }
    // a method that is not one of the enumerators
    SolverOptions bogus;
    bogus.method = static_cast<Method>(7);
    expect_invalid("method", [&] { (void)simulate(rig, 1.0, bogus); });
    // Cvode asked to run a non-CVODE method
    SolverOptions dp;
    expect_invalid("method", [&] { (void)simulate_with<Cvode>(rig, 1.0, dp); });
}

TEST_CASE("SolverOptions: boundary values are accepted", "[validation][solver]") {
    const SimpleRig rig = simple_rig();
    for (const Method m : all_methods) {
        INFO(method_name(m));
        SolverOptions o;
        o.method = m;
        o.rtol = 1e-14;  // smallest allowed
        o.atol = 1e-12;
        o.max_step = kInf;       // default: unbounded
        o.initial_step = 0.0;   // the integrator chooses
        o.max_events_in_window = 1;
        o.output_times = {0.0, 1.0};  // exactly the ends of the span
        CHECK_NOTHROW(simulate(rig, 1.0, o));
        o.atol_per_state = {1e-12, 1e-12};  // overrides atol, which is then not used
        o.atol = kNaN;
        CHECK_NOTHROW(simulate(rig, 1.0, o));
    }
}

TEST_CASE("simulate: t_start, t_end and output times outside the span throw InvalidParameter naming them",
          "[validation][solver]") {
    const SimpleRig rig = simple_rig();
    for (const Method m : all_methods) {
        INFO(method_name(m));
        SolverOptions o;
        o.method = m;
        check_rules({
            {"t_end", non_finite, [&](double v) { (void)simulate(rig, v, o); }},
            {"t_end", {0.0, -1.0, -1e-300}, [&](double v) { (void)simulate(rig, v, o); }},  // t_end <= t_start
            {"t_end", {1.0, 0.5}, [&](double v) { (void)simulate(rig, v, o, 1.0); }},
            {"t_start", non_finite, [&](double v) { (void)simulate(rig, 1.0, o, v); }},
        });
        SolverOptions outside = o;
        outside.output_times = {-0.1, 0.5};  // before t_start
        expect_invalid("output_times", [&] { (void)simulate(rig, 1.0, outside); });
        outside.output_times = {0.5, 1.0 + 1e-12};  // after t_end
        expect_invalid("output_times", [&] { (void)simulate(rig, 1.0, outside); });
        outside.output_times = {0.5, 1.5};  // before a non-zero t_start
        expect_invalid("output_times", [&] { (void)simulate(rig, 2.0, outside, 1.0); });
        CHECK_NOTHROW(simulate(rig, 2.0, outside, 0.5));  // [t_start, t_end] = [0.5, 2]: both inside
        CHECK_NOTHROW(simulate(rig, 1.0, o, -1.0));       // a negative start time is fine
    }
}

TEST_CASE("integrate_hybrid: a non-finite initial state throws InvalidParameter 'initial_state'",
          "[validation][solver]") {
    const SimpleRig rig = simple_rig();
    for (const double v : non_finite) {
        std::array<double, SimpleRig::state_size> x{};
        x[1] = v;
        expect_invalid("initial_state", [&] { (void)integrate_hybrid<DormandPrince>(rig, x, 0.0, 1.0, SolverOptions{}); });
        expect_invalid("initial_state", [&] {
            SolverOptions o;
            o.method = Method::cvode_bdf;
            (void)integrate_hybrid<Cvode>(rig, x, 0.0, 1.0, o);
        });
    }
}

// ------------------------------------------------------------------------------------------------- sampled data

namespace {

// v_r reverses at t = 0.5 and 1.5 (Coulomb switches there); the data end at t = 2.
SampledSignal sampled_velocity() { return SampledSignal({0.0, 1.0, 2.0}, {1e-3, -1e-3, 1e-3}, "relative_velocity"); }

void expect_stops_within_data(const std::function<Result()>& run, double data_end) {
    try {
        (void)run();
        FAIL_CHECK("the run past the data's end did not fail");
    } catch (const SimulationError& e) {
        INFO(e.what());
        CHECK(e.time_reached() >= 0.0);
        CHECK(e.time_reached() <= data_end);
        REQUIRE(e.partial() != nullptr);
        CHECK_FALSE(e.partial()->completed);
        CHECK(e.partial()->t_reached == e.time_reached());
        CHECK(contains(e.what(), "outside the samples"));
    } catch (const std::exception& e) {
        FAIL_CHECK("expected SimulationError, got " << typeid(e).name() << ": " << e.what());
    }
}

}  // namespace

TEST_CASE("a SampledSignal-driven KinematicRig runs up to exactly the end of its data", "[validation][signals]") {
    for (const Method m : all_methods) {
        INFO(method_name(m));
        SolverOptions o;
        o.method = m;
        o.output_times = {0.0, 1.0, 2.0};
        const KinematicRig<Coulomb, SampledSignal> rig(Coulomb(0.3), sampled_velocity(), ConstantSignal(10.0));
        Result r;
        REQUIRE_NOTHROW(r = simulate(rig, 2.0, o));
        CHECK(r.completed);
        CHECK(r.events.size() == 2);
        const KinematicRig<Coulomb, ConstantSignal, SampledSignal> by_normal(
            Coulomb(0.3), ConstantSignal(1e-3), SampledSignal({0.0, 2.0}, {10.0, 20.0}, "normal_force"));
        CHECK_NOTHROW(simulate(by_normal, 2.0, o));
    }
}

TEST_CASE("a SampledSignal-driven KinematicRig run past its data stops with SimulationError inside the data",
          "[validation][signals]") {
    for (const Method m : all_methods) {
        INFO(method_name(m));
        SolverOptions o;
        o.method = m;
        const KinematicRig<Coulomb, SampledSignal> rig(Coulomb(0.3), sampled_velocity(), ConstantSignal(10.0));
        expect_stops_within_data([&] { return simulate(rig, 3.0, o); }, 2.0);
        o.output_times = {0.0, 1.0, 2.0, 2.5, 3.0};
        expect_stops_within_data([&] { return simulate(rig, 3.0, o); }, 2.0);
        o.output_times.clear();
        const KinematicRig<Coulomb, ConstantSignal, SampledSignal> by_normal(
            Coulomb(0.3), ConstantSignal(1e-3), SampledSignal({0.0, 2.0}, {10.0, 20.0}, "normal_force"));
        expect_stops_within_data([&] { return simulate(by_normal, 3.0, o); }, 2.0);
        const KinematicRig<Dahl, SampledSignal> dahl(Dahl(0.3, 3e4), sampled_velocity(), ConstantSignal(10.0));
        expect_stops_within_data([&] { return simulate(dahl, 3.0, o); }, 2.0);
    }
}

// Starting before the data: the rig's initial mode reads the signal at t_start before any step is taken, so
// the hybrid loop's wrapper does not apply and the signal's std::out_of_range escapes as it is. Report only:
// require that it is an exception and not a crash; which type is a design decision (see the report).
TEST_CASE("a SampledSignal-driven KinematicRig started before its data throws, not crashes",
          "[validation][signals]") {
    for (const Method m : all_methods) {
        INFO(method_name(m));
        SolverOptions o;
        o.method = m;
        const KinematicRig<Coulomb, SampledSignal> rig(Coulomb(0.3), sampled_velocity(), ConstantSignal(10.0));
        CHECK_THROWS_AS(simulate(rig, 1.0, o, -1.0), std::exception);
    }
}

// ------------------------------------------------------------------------------------------------- contact, analysis

#ifdef FRICTIONSIM_TEST_HOT
TEST_CASE("hydraulic oscillator: every non-physical parameter throws InvalidParameter naming it",
          "[validation][contact]") {
    HydraulicOscillatorParams ok{};
    ok.tool_outer_radius = 0.086;
    ok.tool_inner_radius = 0.035;
    ok.wellbore_radius = 0.108;
    ok.steel_density = 7850.0;
    ok.mud_density = 1200.0;
    ok.rock_youngs_modulus = 20e9;
    ok.rock_poisson_ratio = 0.25;
    ok.steel_youngs_modulus = 210e9;
    ok.steel_poisson_ratio = 0.3;
    ok.rock_wear_width = 5e-3;
    ok.specimen_width = 30e-3;
    REQUIRE_NOTHROW(ok.validate());
    using P = HydraulicOscillatorParams;
    const auto force = [](const P& p) { (void)equivalent_rig_normal_force(p); };
    const std::vector<double> poisson_bad{-0.1, 0.5, 0.7, kNaN, kInf, -kInf};
    check_rules({
        {"tool_outer_radius", not_positive, with(ok, &P::tool_outer_radius, force)},
        {"tool_outer_radius", {0.108, 0.2}, with(ok, &P::tool_outer_radius, force)},   // >= wellbore radius
        {"tool_inner_radius", not_positive, with(ok, &P::tool_inner_radius, force)},
        {"tool_inner_radius", {0.086, 0.09}, with(ok, &P::tool_inner_radius, force)},  // >= outer radius
        {"wellbore_radius", not_positive, with(ok, &P::wellbore_radius, force)},
        {"steel_density", not_positive, with(ok, &P::steel_density, force)},
        {"steel_density", {1200.0, 1000.0}, with(ok, &P::steel_density, force)},  // the tool must sink
        {"mud_density", not_positive, with(ok, &P::mud_density, force)},
        {"rock_youngs_modulus", not_positive, with(ok, &P::rock_youngs_modulus, force)},
        {"steel_youngs_modulus", not_positive, with(ok, &P::steel_youngs_modulus, force)},
        {"rock_poisson_ratio", poisson_bad, with(ok, &P::rock_poisson_ratio, force)},
        {"steel_poisson_ratio", poisson_bad, with(ok, &P::steel_poisson_ratio, force)},
        {"rock_wear_width", not_positive, with(ok, &P::rock_wear_width, force)},
        {"specimen_width", not_positive, with(ok, &P::specimen_width, force)},
        {"gravity", not_positive, with(ok, &P::gravity, force)},
        {"normal_force", negative_or_nonfinite, [](double v) { (void)rig_contact_stress(v, 5e-3, 30e-3); }},
        {"rock_wear_width", not_positive, [](double v) { (void)rig_contact_stress(100.0, v, 30e-3); }},
        {"specimen_width", not_positive, [](double v) { (void)rig_contact_stress(100.0, 5e-3, v); }},
    });
    P poisson_zero = ok;
    poisson_zero.rock_poisson_ratio = poisson_zero.steel_poisson_ratio = 0.0;
    CHECK_NOTHROW(equivalent_rig_normal_force(poisson_zero));
    CHECK(rig_contact_stress(0.0, 5e-3, 30e-3) == 0.0);
}
#endif

#ifdef FRICTIONSIM_TEST_CYCLE_MEAN
TEST_CASE("cycle means: non-physical arguments throw InvalidParameter naming them", "[validation][analysis]") {
    const std::vector<double> t{0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0};
    const std::vector<double> y(t.size(), 1.0);
    check_rules({
        {"period", not_positive, [&](double v) { (void)mean_over_cycles(t, y, v, 0.0); }},
        {"period", {2.5, 100.0}, [&](double v) { (void)mean_over_cycles(t, y, v, 0.0); }},  // no whole cycle fits
        {"transient", negative_or_nonfinite, [&](double v) { (void)mean_over_cycles(t, y, 0.5, v); }},
        {"transient", {2.0, 3.0}, [&](double v) { (void)mean_over_cycles(t, y, 0.5, v); }},  // nothing left
        {"t_a", {-0.1, 2.1, kNaN, kInf, -kInf}, [&](double v) { (void)mean_over_window(t, y, v, 2.0); }},
        {"t_b", {-0.1, 2.1, kNaN, kInf, -kInf}, [&](double v) { (void)mean_over_window(t, y, 0.0, v); }},
        {"t_b", {0.5, 0.4}, [&](double v) { (void)mean_from_integral(t, y, 0.5, v); }},  // t_b <= t_a
        {"t", {kNaN, kInf, -kInf, 0.25, 0.1},
         [&](double v) {
             std::vector<double> bad = t;
             bad[2] = v;
             (void)mean_over_window(bad, y, 0.0, 2.0);
         }},
        {"t_first", non_finite, [](double v) { (void)whole_cycle_window(v, 2.0, 0.5, 0.0); }},
        {"t_last", non_finite, [](double v) { (void)whole_cycle_window(0.0, v, 0.5, 0.0); }},
        {"t_last", {0.0, -1.0}, [](double v) { (void)whole_cycle_window(0.0, v, 0.5, 0.0); }},
        {"mean_with_vibration", non_finite, [](double v) { (void)friction_reduction(v, 1.0); }},
        {"mean_without", {0.0, -0.0, kNaN, kInf, -kInf}, [](double v) { (void)friction_reduction(1.0, v); }},
    });
    expect_invalid("cycles", [&] { (void)mean_over_cycles(t, y, 0.5, 0.0, 5); });
    expect_invalid("y", [&] { (void)mean_over_window(t, std::vector<double>(3, 1.0), 0.0, 1.0); });
    expect_invalid("running_integral", [&] { (void)mean_from_integral(t, std::vector<double>(3, 1.0), 0.0, 1.0); });
    expect_invalid("t", [] { (void)mean_over_window(std::vector<double>{0.0}, std::vector<double>{1.0}, 0.0, 1.0); });
    CHECK(mean_over_cycles(t, y, 0.5, 0.0, 4) == Approx(1.0));  // exactly the 4 cycles that fit
    CHECK(friction_reduction(0.0, -1.0) == 1.0);
}
#endif
