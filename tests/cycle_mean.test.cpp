// Cycle means: whole-cycle windows, trapezoid means of sampled signals, means from running integrals, and the
// friction reduction; references are closed-form integrals.
#include "catch.hpp"
#include "rejection.hpp"

#include <frictionsim/detail/constants.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "frictionsim/analysis/cycle_mean.hpp"

using frictionsim::InvalidParameter;

namespace {

using frictionsim::pi;

std::vector<double> uniform_times(double t_end, std::size_t intervals) {
    std::vector<double> t(intervals + 1);
    for (std::size_t i = 0; i <= intervals; ++i) t[i] = t_end * static_cast<double>(i) / static_cast<double>(intervals);
    return t;
}

template <class F>
std::vector<double> sample(const std::vector<double>& t, F&& f) {
    std::vector<double> y(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) y[i] = f(t[i]);
    return y;
}

// Coulomb friction on a body sliding at v_d over a surface vibrating with velocity v_a sin(w t), per unit
// mu N: the sign of the relative velocity v_d - v_a sin(w t), a square wave with duty set by asin(v_d / v_a).
// Its cycle mean is (2/pi) asin(v_d / v_a) (the "friction vector" result, DESIGN.md).
struct CoulombFrictionVector {
    double sliding_velocity, velocity_amplitude, angular_frequency;

    double force(double t) const {
        return sliding_velocity - velocity_amplitude * std::sin(angular_frequency * t) >= 0.0 ? 1.0 : -1.0;
    }
    // Closed-form running integral of force from 0 to t: piecewise linear, +1 slope outside the reversed phase
    // band (theta_1, pi - theta_1) of each cycle, -1 inside.
    double impulse(double t) const {
        const double theta = angular_frequency * t;
        const double whole = std::floor(theta / (2.0 * pi));
        const double phase = theta - 2.0 * pi * whole;
        const double theta_1 = std::asin(sliding_velocity / velocity_amplitude);
        const double theta_2 = pi - theta_1;
        double within;
        if (phase <= theta_1) within = phase;
        else if (phase <= theta_2) within = 2.0 * theta_1 - phase;
        else within = phase + 2.0 * theta_1 - 2.0 * theta_2;
        return (whole * 4.0 * theta_1 + within) / angular_frequency;
    }
    double cycle_mean() const { return 2.0 / pi * std::asin(sliding_velocity / velocity_amplitude); }
};

}  // namespace

TEST_CASE("whole_cycle_window: start after the transient, whole periods only", "[analysis][cycle_mean]") {
    auto w = frictionsim::whole_cycle_window(0.0, 1.0, 0.1, 0.25);
    CHECK(w.start == 0.25);
    CHECK(w.cycles == 7);  // 0.75 s leaves 7.5 periods
    CHECK(w.end == Approx(0.95).epsilon(1e-15));

    w = frictionsim::whole_cycle_window(2.0, 3.0, 0.1, 0.25, 3);
    CHECK(w.start == 2.25);
    CHECK(w.end == Approx(2.55).epsilon(1e-15));
    CHECK(w.cycles == 3);

    // A record that ends at 10 periods up to rounding holds 10 whole periods, clamped to the data.
    double t_last = 0.0;
    for (int i = 0; i < 10; ++i) t_last += 0.1;  // 0.9999999999999999
    w = frictionsim::whole_cycle_window(0.0, t_last, 0.1, 0.0);
    CHECK(w.cycles == 10);
    CHECK(w.end == t_last);

    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(0.0, 1.0, 0.1, 0.25, 8); }) == "cycles");
    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(0.0, 1.0, 0.8, 0.25); }) == "period");
    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(0.0, 1.0, 0.0, 0.25); }) == "period");
    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(0.0, 1.0, NAN, 0.25); }) == "period");
    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(0.0, 1.0, 0.1, -0.1); }) == "transient");
    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(0.0, 1.0, 0.1, 1.0); }) == "transient");
    CHECK(rejected_parameter([] { frictionsim::whole_cycle_window(1.0, 1.0, 0.1, 0.0); }) == "t_last");
}

TEST_CASE("mean of sin over whole cycles is 0", "[analysis][cycle_mean]") {
    const double period = 0.05;  // 20 Hz
    const double w = 2.0 * pi / period;
    SECTION("window on samples: the trapezoid rule is exact for a sampled harmonic") {
        const auto t = uniform_times(1.0, 4000);  // 200 samples per period
        const auto y = sample(t, [&](double s) { return std::sin(w * s); });
        CHECK(std::abs(frictionsim::mean_over_cycles(t, y, period, 0.1)) < 1e-14);
        CHECK(std::abs(frictionsim::mean_over_cycles(t.data(), y.data(), t.size(), period, 0.0, 5)) < 1e-14);
    }
    SECTION("window between samples: interpolated ends") {
        const auto t = uniform_times(1.0, 3001);  // period not a whole number of samples
        const auto y = sample(t, [&](double s) { return std::sin(w * s + 0.3); });
        // Per-sample trapezoid errors are O((w dt)^2 / 12), about 1e-4, and cancel over whole cycles except at
        // the two ends: about 1e-9 here.
        CHECK(std::abs(frictionsim::mean_over_cycles(t, y, period, 0.0123)) < 1e-7);
    }
}

TEST_CASE("mean of a + b sin over whole cycles is a", "[analysis][cycle_mean]") {
    const double a = 12.29, b = 30.0, period = 1.0 / 17.0;
    const auto t = uniform_times(2.0, 20000);
    const auto y = sample(t, [&](double s) { return a + b * std::sin(2.0 * pi * s / period - 1.1); });
    CHECK(frictionsim::mean_over_cycles(t, y, period, 0.31) == Approx(a).epsilon(1e-8));
    CHECK(frictionsim::mean_over_cycles(t, y, period, 0.31, 10) == Approx(a).epsilon(1e-8));
    // Over a non-whole window the oscillation does not average out: proof that the window matters.
    CHECK(frictionsim::mean_over_window(t, y, 0.31, 0.31 + 0.25 * period) != Approx(a).epsilon(1e-3));
}

TEST_CASE("mean_over_window integrates the linear interpolant exactly", "[analysis][cycle_mean]") {
    // Non-uniform samples of a linear signal: mean over [t_a, t_b] is y((t_a + t_b) / 2), whatever the grid.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> step(0.001, 0.05);
    std::vector<double> t{0.0};
    while (t.back() < 1.0) t.push_back(t.back() + step(rng));
    const auto y = sample(t, [](double s) { return 3.0 - 2.0 * s; });
    for (const auto& [t_a, t_b] : {std::pair{0.0, t.back()}, std::pair{0.1234, 0.8765}, std::pair{0.5, 0.5001},
                                   std::pair{t[3], t[7]}}) {
        CHECK(frictionsim::mean_over_window(t, y, t_a, t_b) ==
              Approx(3.0 - 2.0 * 0.5 * (t_a + t_b)).epsilon(1e-13));
    }
}

TEST_CASE("square wave mean is exact from its running integral", "[analysis][cycle_mean]") {
    // v_d = 1 mm/s sliding on a surface vibrating at 20 Hz with v_a = 2 mm/s: friction reverses for 1/3 cycle.
    const CoulombFrictionVector cfv{1e-3, 2e-3, 2.0 * pi * 20.0};
    const double period = 0.05;
    REQUIRE(cfv.cycle_mean() == Approx(1.0 / 3.0).epsilon(1e-15));  // (2/pi) asin(1/2) = (2/pi)(pi/6)

    // Coarse samples, 40 per period, window ends on samples (as solver output times are).
    const auto t = uniform_times(1.0, 800);
    const auto impulse = sample(t, [&](double s) { return cfv.impulse(s); });
    const auto w = frictionsim::whole_cycle_window(t.front(), t.back(), period, 0.2);
    CHECK(frictionsim::mean_from_integral(t, impulse, w) == Approx(1.0 / 3.0).epsilon(1e-13));
    CHECK(frictionsim::mean_from_integral(t.data(), impulse.data(), t.size(), w.start, w.end) ==
          Approx(1.0 / 3.0).epsilon(1e-13));

    // The trapezoid mean of the same samples smears each jump over one sample interval: error O(dt / period).
    const auto force = sample(t, [&](double s) { return cfv.force(s); });
    const double trapezoid = frictionsim::mean_over_cycles(t, force, period, 0.2);
    CHECK(std::abs(trapezoid - 1.0 / 3.0) > 1e-4);
    CHECK(std::abs(trapezoid - 1.0 / 3.0) < 2.0 / 40.0);

    // Friction reduction of the friction-vector effect: 1 - (2/pi) asin(v_d / v_a) = 2/3.
    CHECK(frictionsim::friction_reduction(frictionsim::mean_from_integral(t, impulse, w), 1.0) ==
          Approx(2.0 / 3.0).epsilon(1e-13));
}

TEST_CASE("square wave mean from an integral sampled on an irregular grid", "[analysis][cycle_mean]") {
    // Solver-like output: irregular steps, with the window ends among the output times.
    const CoulombFrictionVector cfv{0.7e-3, 3e-3, 2.0 * pi * 16.0};
    const double period = 1.0 / 16.0;
    const double t_a = 0.3, t_b = t_a + 9 * period;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> step(1e-4, 4e-3);
    std::vector<double> t{0.0};
    while (t.back() < 1.0) {
        const double next = t.back() + step(rng);
        for (double end : {t_a, t_b})
            if (t.back() < end && next > end) t.push_back(end);
        t.push_back(next);
    }
    const auto impulse = sample(t, [&](double s) { return cfv.impulse(s); });
    CHECK(frictionsim::mean_from_integral(t, impulse, t_a, t_b) == Approx(cfv.cycle_mean()).epsilon(1e-12));
}

TEST_CASE("friction_reduction is 1 - F_df / F_sf", "[analysis][cycle_mean]") {
    // Paper 000, Table 4, run VS1 (dry): F_sf = 12.29 N without vibration, F_df = 2.82 N with it.
    CHECK(frictionsim::friction_reduction(2.82, 12.29) == Approx(1.0 - 2.82 / 12.29).epsilon(1e-15));
    CHECK(frictionsim::friction_reduction(2.82, 12.29) == Approx(0.7705).margin(1e-4));
    CHECK(frictionsim::friction_reduction(5.0, 5.0) == 0.0);
    CHECK(frictionsim::friction_reduction(6.0, 5.0) == Approx(-0.2));  // vibration that adds friction
    CHECK(rejected_parameter([] { frictionsim::friction_reduction(1.0, 0.0); }) == "mean_without");
    CHECK(rejected_parameter([] { frictionsim::friction_reduction(NAN, 1.0); }) == "mean_with_vibration");
}

TEST_CASE("cycle means reject bad samples and windows, naming the parameter", "[analysis][cycle_mean]") {
    const auto t = uniform_times(1.0, 100);
    const auto y = sample(t, [](double s) { return s; });
    const std::vector<double> short_y(y.begin(), y.end() - 1);

    CHECK(rejected_parameter([&] { frictionsim::mean_over_cycles(t, short_y, 0.1, 0.0); }) == "y");
    CHECK(rejected_parameter([&] { frictionsim::mean_over_window(t, short_y, 0.1, 0.2); }) == "y");
    CHECK(rejected_parameter([&] { frictionsim::mean_from_integral(t, short_y, 0.1, 0.2); }) == "running_integral");
    const std::vector<double> one{0.0};
    CHECK(rejected_parameter([&] { frictionsim::mean_over_cycles(one, one, 0.1, 0.0); }) == "t");

    auto bad_t = t;
    bad_t[50] = bad_t[49];  // repeated time
    CHECK(rejected_parameter([&] { frictionsim::mean_over_cycles(bad_t, y, 0.1, 0.0); }) == "t");
    bad_t[50] = NAN;
    CHECK(rejected_parameter([&] { frictionsim::mean_from_integral(bad_t, y, 0.1, 0.2); }) == "t");
    auto reversed = t;
    std::swap(reversed[10], reversed[11]);
    CHECK(rejected_parameter([&] { frictionsim::mean_over_window(reversed, y, 0.1, 0.2); }) == "t");

    CHECK(rejected_parameter([&] { frictionsim::mean_over_cycles(t, y, -0.1, 0.0); }) == "period");
    CHECK(rejected_parameter([&] { frictionsim::mean_over_cycles(t, y, 0.1, -1.0); }) == "transient");
    CHECK(rejected_parameter([&] { frictionsim::mean_over_cycles(t, y, 0.1, 0.0, 11); }) == "cycles");
    CHECK(rejected_parameter([&] { frictionsim::mean_from_integral(t, y, -0.1, 0.5); }) == "t_a");
    CHECK(rejected_parameter([&] { frictionsim::mean_from_integral(t, y, 0.1, 1.5); }) == "t_b");
    CHECK(rejected_parameter([&] { frictionsim::mean_from_integral(t, y, 0.5, 0.5); }) == "t_b");
    CHECK(rejected_parameter([&] { frictionsim::mean_over_window(t, y, 0.6, 0.5); }) == "t_b");

    // Messages name the owner and the rule.
    try {
        frictionsim::mean_over_cycles(t, y, 0.1, 0.0, 11);
        FAIL("no throw");
    } catch (const InvalidParameter& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find("mean_over_cycles: cycles must be at most the 10 whole cycles") != std::string::npos);
    }
}
