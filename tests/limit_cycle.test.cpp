// Limit-cycle measures (analysis/limit_cycle.hpp): references are closed forms of sampled periodic signals.
#include "catch.hpp"
#include "rejection.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <frictionsim/analysis/limit_cycle.hpp>
#include <frictionsim/detail/constants.hpp>

using namespace frictionsim;

namespace {
struct Samples {
    std::vector<double> t, w;
};

template <class F>
Samples sampled(double t_end, double dt, F&& f) {
    Samples s;
    for (std::size_t i = 0; static_cast<double>(i) * dt <= t_end + 1e-12; ++i) {
        s.t.push_back(static_cast<double>(i) * dt);
        s.w.push_back(f(s.t.back()));
    }
    return s;
}

LimitCycle measure(const Samples& s, double transient, double stick_speed = 1e-2) {
    return limit_cycle(s.t.data(), s.w.data(), s.t.size(), transient, std::numeric_limits<double>::quiet_NaN(),
                       stick_speed);
}
}  // namespace

TEST_CASE("limit cycle of a sinusoid: frequency, peak, trough, mean", "[limit_cycle]") {
    const double f = 0.7;
    const Samples s = sampled(30.0, 1e-3, [&](double t) { return 5.0 + 3.0 * std::sin(2 * pi * f * t); });
    const LimitCycle c = measure(s, 5.0);
    CHECK(c.cycles >= 16);
    CHECK(c.frequency == Approx(f).epsilon(1e-6));
    CHECK(c.period == Approx(1 / f).epsilon(1e-6));
    CHECK(c.peak == Approx(8.0).epsilon(1e-5));
    CHECK(c.trough == Approx(2.0).epsilon(1e-5));
    CHECK(c.mean == Approx(5.0).epsilon(1e-6));  // whole cycles: the mean of the sine's cycles
    // the level is the mean over [5, 30] s, 17.5 cycles: off the sine's centre by at most 3 / (pi f 25 s)
    CHECK(std::abs(c.level - 5.0) <= 3.0 / (pi * f * 25.0));
    CHECK(c.stick_fraction == 0.0);
    CHECK(c.start >= 5.0);
}

TEST_CASE("limit cycle: the stick fraction of a clipped sinusoid", "[limit_cycle]") {
    // w = max(0, 1 + 2 sin(2 pi t)) is zero while sin < -1/2: for 1/3 of each period.
    const Samples s = sampled(20.0, 1e-4, [](double t) { return std::max(0.0, 1.0 + 2.0 * std::sin(2 * pi * t)); });
    const LimitCycle c = measure(s, 2.0, 1e-9);
    CHECK(c.frequency == Approx(1.0).epsilon(1e-6));
    CHECK(c.stick_fraction == Approx(1.0 / 3.0).epsilon(1e-3));  // up to one 1e-4 s sample per edge lost
    CHECK(c.trough == 0.0);
    CHECK(c.peak == Approx(3.0).epsilon(1e-6));
}

TEST_CASE("limit cycle: noise at the crossing level does not split cycles", "[limit_cycle]") {
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 0.02);
    const Samples s = sampled(40.0, 1e-3, [&](double t) { return 5.0 + 3.0 * std::sin(2 * pi * 0.8 * t) + noise(rng); });
    const LimitCycle c = measure(s, 5.0);
    CHECK(c.frequency == Approx(0.8).epsilon(2e-4));
    CHECK(c.cycles == 27);  // 28 upward crossings in [5, 40]: one per period, none split
}

TEST_CASE("limit cycle: no oscillation gives zero cycles and frequency", "[limit_cycle]") {
    const Samples s = sampled(10.0, 1e-2, [](double t) { return 5.0 + 0.1 * t; });
    const LimitCycle c = measure(s, 1.0);
    CHECK(c.cycles == 0);
    CHECK(c.frequency == 0.0);
    CHECK(std::isinf(c.period));
    CHECK(c.peak == Approx(6.0));
    CHECK(c.trough == Approx(5.1));
}

TEST_CASE("limit cycle: bad input names the parameter", "[limit_cycle][validation]") {
    const Samples s = sampled(10.0, 1e-2, [](double t) { return std::sin(t); });
    CHECK(rejected_parameter([&] { measure(s, 10.0); }) == "transient");
    CHECK(rejected_parameter([&] { measure(s, -1.0); }) == "transient");
    CHECK(rejected_parameter([&] { measure(s, 1.0, -1.0); }) == "stick_speed");
    CHECK(rejected_parameter([&] { limit_cycle(s.t.data(), s.w.data(), s.t.size(), 0.0, 0.0, 0.01, 1.0); }) ==
          "hysteresis");
    Samples bad = s;
    bad.w[5] = std::numeric_limits<double>::quiet_NaN();
    CHECK(rejected_parameter([&] { measure(bad, 1.0); }) == "w");
    bad = s;
    bad.t[5] = bad.t[4];
    CHECK(rejected_parameter([&] { measure(bad, 1.0); }) == "t");
}
