// The bit-rock laws (drillstring/bit_rock.hpp) against their closed forms: Detournay & Defourny's steady weight and
// torque on bit in both conventions of the torque constant, the E-S line of Detournay, Richard & Shepherd (2008)
// that follows from them, the set-valued stuck bit; the velocity-weakening bit of Navarro-Lopez & Cortes (2007).
#include <cmath>
#include <limits>

#include <frictionsim/contact/switching.hpp>
#include <frictionsim/bits/bit_rock.hpp>

#include "catch.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
}

TEST_CASE("DetournayBit: steady weight and torque on bit are the Detournay-Defourny closed form", "[bit_rock]") {
    const DetournayBit bit;  // c = 1/2
    const auto& p = bit.params();
    const double a = p.bit_radius, eps = p.intrinsic_specific_energy, zeta = p.cutting_force_ratio,
                 sigma = p.contact_strength, l = p.wearflat_length, mu = p.friction_coefficient,
                 gamma = p.contact_orientation;
    REQUIRE(p.torque_constant == 0.5);
    for (double d : {0.0, 1e-4, 5e-4, 1e-3, 2.5e-3, 5e-3}) {  // depth of cut per revolution, m
        // W = zeta eps a d + a l sigma, T = eps a^2 d / 2 + gamma mu a (a l sigma) / 2 (issue 13's statement)
        CHECK(bit.weight_on_bit(d) == Approx(zeta * eps * a * d + a * l * sigma).epsilon(1e-14));
        CHECK(bit.torque_on_bit(d) == Approx(eps * a * a * d / 2.0 + gamma * mu * a * (a * l * sigma) / 2.0).epsilon(1e-14));
        CHECK(bit.depth_at_weight(bit.weight_on_bit(d)) == Approx(d).margin(1e-15));
    }
    // the wear flats alone carry a weight below a l sigma: no cutting
    CHECK(bit.depth_at_weight(0.5 * bit.contact_force()) == 0.0);
}

TEST_CASE("DetournayBit: the torque constant's two conventions differ by exactly the factor 2", "[bit_rock]") {
    DetournayBit::Params unit = DetournayBit::Params{};
    unit.torque_constant = DetournayBit::unit_constant;
    const DetournayBit half, one(unit);
    for (double d : {0.0, 3e-4, 2e-3}) {
        CHECK(one.torque_on_bit(d) == Approx(2.0 * half.torque_on_bit(d)).epsilon(1e-15));
        CHECK(one.weight_on_bit(d) == half.weight_on_bit(d));  // the weight has no such constant
    }
    CHECK(one.contact_torque() == Approx(2.0 * half.contact_torque()).epsilon(1e-15));
}

TEST_CASE("DetournayBit: specific energy and drilling strength lie on the E-S line", "[bit_rock]") {
    // Detournay, Richard & Shepherd (2008): E = 2T / (a^2 d), S = W / (a d) satisfy E = (1 - beta) eps + mu gamma S,
    // beta = mu gamma zeta, for every depth of cut; a sharp bit (l = 0) sits at the cutting point (S, E) = (zeta eps, eps).
    const DetournayBit bit;
    const auto& p = bit.params();
    const double beta = p.friction_coefficient * p.contact_orientation * p.cutting_force_ratio;
    for (double d : {2e-4, 7e-4, 1.5e-3, 4e-3}) {
        const double E = 2.0 * bit.torque_on_bit(d) / (p.bit_radius * p.bit_radius * d);
        const double S = bit.weight_on_bit(d) / (p.bit_radius * d);
        CHECK(E == Approx((1.0 - beta) * p.intrinsic_specific_energy +
                          p.friction_coefficient * p.contact_orientation * S).epsilon(1e-12));
    }
    DetournayBit::Params sharp_params;
    sharp_params.wearflat_length = 0.0;
    const DetournayBit sharp(sharp_params);
    const double d = 1e-3, a = sharp_params.bit_radius;
    CHECK(2.0 * sharp.torque_on_bit(d) / (a * a * d) == Approx(sharp_params.intrinsic_specific_energy).epsilon(1e-14));
    CHECK(sharp.weight_on_bit(d) / (a * d) ==
          Approx(sharp_params.cutting_force_ratio * sharp_params.intrinsic_specific_energy).epsilon(1e-14));
}

TEST_CASE("DetournayBit: depth of cut per revolution from rate of penetration and angular speed", "[bit_rock]") {
    // 10 m/h at 120 rpm: d = V / (revolutions per second)
    const double V = 10.0 / 3600.0, rpm = 120.0;
    CHECK(DetournayBit::depth_of_cut(V, rpm * 2.0 * 3.141592653589793 / 60.0) == Approx(V / (rpm / 60.0)).epsilon(1e-14));
    CHECK(rejected_parameter([] { DetournayBit::depth_of_cut(1e-3, 0.0); }) == "angular_speed");
    CHECK(rejected_parameter([] { DetournayBit::depth_of_cut(-1e-3, 1.0); }) == "rate_of_penetration");
}

TEST_CASE("DetournayBit: the stuck bit's torque is set-valued within the wear flats' friction", "[bit_rock]") {
    const DetournayBit bit;
    const double Tf = bit.contact_torque(), d = 1e-3;
    REQUIRE(Tf > 0.0);
    CHECK(bit.torque(0.0, d, 0.3 * Tf) == 0.3 * Tf);   // held: the torque needed
    CHECK(bit.torque(0.0, d, -0.9 * Tf) == -0.9 * Tf);
    CHECK(bit.torque(0.0, d, 2.0 * Tf) == Tf);         // beyond the bound: it cannot hold (it breaks away)
    CHECK(bit.holds(Tf));
    CHECK_FALSE(bit.holds(1.0001 * Tf));
    CHECK(bit.torque(1.0, d) == bit.torque_on_bit(d));  // turning: cutting + friction
    CHECK(bit.torque(-1.0, d) == -Tf);                  // backwards: the wear flats rub, nothing is cut
}

TEST_CASE("DetournayBit: bad parameters name the parameter and its rule", "[bit_rock]") {
    const auto with = [](auto set) {
        DetournayBit::Params p;
        set(p);
        return rejected_parameter([&] { DetournayBit{p}; });
    };
    CHECK(with([](auto& p) { p.bit_radius = 0.0; }) == "bit_radius");
    CHECK(with([](auto& p) { p.intrinsic_specific_energy = -1.0; }) == "intrinsic_specific_energy");
    CHECK(with([](auto& p) { p.cutting_force_ratio = nan_value; }) == "cutting_force_ratio");
    CHECK(with([](auto& p) { p.contact_strength = -1.0; }) == "contact_strength");
    CHECK(with([](auto& p) { p.wearflat_length = -1e-3; }) == "wearflat_length");
    CHECK(with([](auto& p) { p.friction_coefficient = std::numeric_limits<double>::infinity(); }) == "friction_coefficient");
    CHECK(with([](auto& p) { p.contact_orientation = 0.0; }) == "contact_orientation");
    CHECK(with([](auto& p) { p.torque_constant = 0.0; }) == "torque_constant");
    CHECK(rejection_message([] { DetournayBit::Params p; p.torque_constant = -1.0; DetournayBit{p}; })
              .find("Detournay & Defourny") != std::string::npos);
    const DetournayBit bit;
    CHECK(rejected_parameter([&] { bit.weight_on_bit(-1e-3); }) == "depth_of_cut");
    CHECK(rejected_parameter([&] { bit.torque(nan_value, 1e-3); }) == "angular_speed");
}

TEST_CASE("NavarroLopezBit: mu_b and the torque of Navarro-Lopez & Cortes", "[bit_rock]") {
    static_assert(check_friction_law<NavarroLopezBit>());
    const NavarroLopezBit bit;  // R_b = 0.155575 m, mu_cb = 0.5, mu_sb = 0.8, gamma_b = 0.9, v_f = 1, c_b = 50
    const auto& p = bit.params();
    const double W = 50e3;
    for (double w : {1e-6, 0.1, 1.0, 3.0, 10.0}) {
        const double mu = p.coulomb_coefficient +
                          (p.static_coefficient - p.coulomb_coefficient) * std::exp(-p.weakening_rate * w / p.velocity_scale);
        CHECK(bit.coefficient(w) == Approx(mu).epsilon(1e-14));
        CHECK(bit.coefficient(-w) == bit.coefficient(w));
        CHECK(bit.torque(w, W, +1) == Approx(p.viscous_damping * w + p.bit_radius * W * mu).epsilon(1e-14));
        CHECK(bit.torque(-w, W, -1) == Approx(-(p.viscous_damping * w + p.bit_radius * W * mu)).epsilon(1e-14));
        // slip slope against a central difference
        const double h = 1e-6 * std::max(1.0, w);
        CHECK(bit.slip_slope(w, W, +1) ==
              Approx((bit.torque(w + h, W, +1) - bit.torque(w - h, W, +1)) / (2.0 * h)).epsilon(1e-6));
    }
    // exact break-away: the slip torque at zero speed is the static bound to the last bit
    CHECK(bit.coefficient(0.0) == p.static_coefficient);
    CHECK(bit.torque(0.0, W, +1) == bit.static_limit(W));
    CHECK(bit.static_limit(W) == p.bit_radius * W * p.static_coefficient);
    CHECK(bit.coefficient(1e3) == Approx(p.coulomb_coefficient).epsilon(1e-15));
}

TEST_CASE("NavarroLopezBit: a set-valued law of the engine (stick within R_b W mu_sb)", "[bit_rock]") {
    using Switching = ContactSwitching<NavarroLopezBit>;
    const NavarroLopezBit bit;
    const double W = 40e3, limit = bit.static_limit(W);
    CHECK(Switching::force(bit, 0.0, W, nullptr, stick, 0.5 * limit) == 0.5 * limit);
    CHECK(Switching::force(bit, 0.0, W, nullptr, stick, 3.0 * limit) == limit);
    bool stop = false;
    const int fired[2] = {-1, 0};
    CHECK(Switching::switch_mode(bit, W, slip_positive, fired, 0.99 * limit, stop) == stick);
    CHECK(stop);
    CHECK(Switching::switch_mode(bit, W, slip_positive, fired, -1.01 * limit, stop) == slip_negative);
}

TEST_CASE("NavarroLopezBit: bad parameters name the parameter", "[bit_rock]") {
    const auto with = [](auto set) {
        NavarroLopezBit::Params p;
        set(p);
        return rejected_parameter([&] { NavarroLopezBit{p}; });
    };
    CHECK(with([](auto& p) { p.bit_radius = -0.1; }) == "bit_radius");
    CHECK(with([](auto& p) { p.coulomb_coefficient = 0.0; }) == "coulomb_coefficient");
    CHECK(with([](auto& p) { p.static_coefficient = 0.4; }) == "static_coefficient");  // < mu_cb
    CHECK(with([](auto& p) { p.weakening_rate = -1.0; }) == "weakening_rate");
    CHECK(with([](auto& p) { p.velocity_scale = 0.0; }) == "velocity_scale");
    CHECK(with([](auto& p) { p.viscous_damping = nan_value; }) == "viscous_damping");
    CHECK(with([](auto& p) { p.stick_band = -1e-6; }) == "stick_band");
}
