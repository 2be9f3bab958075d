// Power-law dynamic friction coefficient (paper 000, eqs 15-17) against the paper's Table 5 and Table 4.
#include "catch.hpp"
#include "rejection.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "frictionsim/friction/power_law.hpp"

using frictionsim::InvalidParameter;
using frictionsim::Lubricant;
using frictionsim::PowerLawCoefficient;

namespace {

using frictionsim::pi;

// Paper 000, Table 4, as printed: lubricant, amplitude u [mm], frequency f [Hz], sliding velocity v_d
// [mm/min], normal force F_N [N], measured mean dynamic friction coefficient u_df = F_df / F_N.
struct Table4Run {
    const char* number;
    Lubricant lubricant;
    double amplitude_mm, frequency_hz, sliding_velocity_mm_per_min, normal_force_n, measured_coefficient;
};

constexpr Table4Run table4[] = {
    {"VS1", Lubricant::dry, 3, 15, 20, 30, 0.094},     {"VS2", Lubricant::dry, 4, 16, 40, 60, 0.098},
    {"VS3", Lubricant::dry, 5, 17, 60, 90, 0.103},     {"VS4", Lubricant::dry, 6, 18, 90, 120, 0.12},
    {"VS5", Lubricant::dry, 8, 20, 120, 150, 0.112},   {"VS6", Lubricant::water, 3, 16, 60, 150, 0.123},
    {"VS7", Lubricant::water, 4, 17, 90, 30, 0.114},   {"VS8", Lubricant::water, 5, 18, 120, 60, 0.106},
    {"VS9", Lubricant::water, 6, 20, 20, 90, 0.095},   {"VS10", Lubricant::water, 8, 15, 40, 120, 0.097},
    {"VS11", Lubricant::wbm, 3, 17, 120, 60, 0.089},   {"VS12", Lubricant::wbm, 4, 18, 20, 90, 0.061},
    {"VS13", Lubricant::wbm, 5, 20, 40, 120, 0.07},    {"VS14", Lubricant::wbm, 6, 15, 60, 150, 0.075},
    {"VS15", Lubricant::wbm, 8, 16, 90, 30, 0.078},    {"VS16", Lubricant::obm, 3, 18, 40, 150, 0.036},
    {"VS17", Lubricant::obm, 4, 20, 60, 30, 0.034},    {"VS18", Lubricant::obm, 5, 15, 90, 60, 0.043},
    {"VS19", Lubricant::obm, 6, 16, 120, 90, 0.045},   {"VS20", Lubricant::obm, 8, 17, 20, 120, 0.028},
    {"VS21", Lubricant::sbm, 3, 20, 90, 90, 0.071},    {"VS22", Lubricant::sbm, 4, 15, 120, 120, 0.078},
    {"VS23", Lubricant::sbm, 5, 16, 20, 150, 0.062},   {"VS24", Lubricant::sbm, 6, 17, 40, 30, 0.065},
    {"VS25", Lubricant::sbm, 8, 18, 60, 60, 0.067},
};

// SI at the edge: mm -> m, mm/min -> m/s.
double amplitude_m(const Table4Run& r) { return r.amplitude_mm * 1e-3; }
double sliding_velocity_m_per_s(const Table4Run& r) { return r.sliding_velocity_mm_per_min * 1e-3 / 60.0; }

}  // namespace

TEST_CASE("power law: Table 5 parameters exactly as printed", "[friction][power_law]") {
    struct Printed {
        Lubricant lubricant;
        double eta_prime, exponent;
    };
    for (const auto& row : {Printed{Lubricant::dry, 1.0676, -0.36513}, Printed{Lubricant::water, 0.1951, -0.09531},
                            Printed{Lubricant::wbm, 0.2116, -0.16533}, Printed{Lubricant::obm, 0.1332, -0.20306},
                            Printed{Lubricant::sbm, 0.1231, -0.09244}}) {
        INFO(frictionsim::lubricant_name(row.lubricant));
        const auto law = PowerLawCoefficient::from_table5(row.lubricant);
        CHECK(law.params().eta == row.eta_prime);
        CHECK(law.params().exponent == row.exponent);
        CHECK(frictionsim::table5(row.lubricant).lubricant == row.lubricant);
    }
}

TEST_CASE("power law: Table 5 fitting lines reproduce eta' and c", "[friction][power_law]") {
    // y = log10(mu_df) = c x + log10(eta') with x = log10(v_a / v_d): slope = c, 10^intercept = eta'.
    for (const auto& row : frictionsim::table5()) {
        INFO(frictionsim::lubricant_name(row.lubricant));
        CHECK(row.fit_slope == row.exponent);
        CHECK(row.fit_r_squared > 0.6);
        CHECK(row.fit_r_squared < 0.9);
        // eta' is printed to 4 decimals, so half a unit (5e-5) is its rounding. SBM misses by 1.6 half-units
        // (10^-0.91003 = 0.12302, printed 0.1231): a slip in the paper's last digit, so the bound is one unit.
        CHECK(std::pow(10.0, row.fit_intercept) == Approx(row.eta_prime).margin(1e-4));
        if (row.lubricant != Lubricant::sbm)
            CHECK(std::pow(10.0, row.fit_intercept) == Approx(row.eta_prime).margin(5e-5));
    }
}

TEST_CASE("power law: eq 17 and vibration velocity amplitude, eq 16", "[friction][power_law]") {
    // u_0 = 5 mm at f = 17 Hz: v_a = 2 pi 17 * 0.005 = 0.17 pi m/s
    CHECK(frictionsim::vibration_velocity_amplitude(0.005, 17.0) == Approx(0.17 * pi).epsilon(1e-15));
    CHECK(frictionsim::vibration_velocity_amplitude(0.0, 17.0) == 0.0);

    const PowerLawCoefficient law({0.2, -0.25});
    // (v_a / v_d)^c with ratio 16 and c = -1/4: 0.2 / 2
    CHECK(law.coefficient(1.6e-2, 1e-3) == Approx(0.1).epsilon(1e-15));
    CHECK(law.friction_force(150.0, 1.6e-2, 1e-3) == Approx(15.0).epsilon(1e-15));
    CHECK(law.friction_force(0.0, 1.6e-2, 1e-3) == 0.0);
    // Only the ratio matters.
    CHECK(law.coefficient(16.0, 1.0) == Approx(law.coefficient(1.6e-2, 1e-3)).epsilon(1e-15));

    // eq 15's eta multiplies (u_0 f / v_d)^c; eq 17's eta' = eta / (2 pi)^c multiplies (v_a / v_d)^c.
    const auto eq15 = PowerLawCoefficient::from_eq15(0.5, -0.2);
    const double u0 = 0.004, f = 18.0, vd = 1e-3;
    CHECK(eq15.coefficient(frictionsim::vibration_velocity_amplitude(u0, f), vd) ==
          Approx(0.5 * std::pow(u0 * f / vd, -0.2)).epsilon(1e-14));
}

TEST_CASE("power law: each Table 4 run within a factor 1.5 of the Table 5 fit", "[friction][power_law]") {
    // Table 5 is a least-squares line through Table 4's scattered measurements (R^2 = 0.63-0.88), not an
    // interpolation: a fitted coefficient only has to land near each measured u_df. A factor of 1.5 is the
    // brief's bound; the worst run (VS17, OBM) is 11% off.
    double worst = 1.0;
    for (const auto& run : table4) {
        INFO(run.number);
        const double v_a = frictionsim::vibration_velocity_amplitude(amplitude_m(run), run.frequency_hz);
        const double v_d = sliding_velocity_m_per_s(run);
        const double ratio = v_a / v_d;
        CHECK(ratio >= PowerLawCoefficient::fitted_velocity_ratio_min);
        CHECK(ratio <= PowerLawCoefficient::fitted_velocity_ratio_max);

        const auto law = PowerLawCoefficient::from_table5(run.lubricant);
        const double predicted = law.coefficient(v_a, v_d);
        const double factor = std::max(predicted / run.measured_coefficient, run.measured_coefficient / predicted);
        CHECK(factor < 1.5);
        // Same as a force: F_df = mu_df F_N.
        CHECK(law.friction_force(run.normal_force_n, v_a, v_d) == Approx(predicted * run.normal_force_n));
        worst = std::max(worst, factor);
    }
    CHECK(worst < 1.12);
}

TEST_CASE("power law: worked Table 4 rows", "[friction][power_law]") {
    // VS1, dry: u = 3 mm, f = 15 Hz, v_d = 20 mm/min. v_a = 0.09 pi m/s, v_d = 1/3000 m/s, ratio 270 pi = 848.2;
    // mu_df = 1.0676 * 848.23^-0.36513 = 0.0910 (measured 0.094).
    const auto dry = PowerLawCoefficient::from_table5(Lubricant::dry);
    CHECK(dry.coefficient(frictionsim::vibration_velocity_amplitude(3e-3, 15.0), 20e-3 / 60.0) ==
          Approx(1.0676 * std::pow(270.0 * pi, -0.36513)).epsilon(1e-14));
    CHECK(dry.coefficient(frictionsim::vibration_velocity_amplitude(3e-3, 15.0), 20e-3 / 60.0) ==
          Approx(0.0910).margin(5e-5));
    // VS20, OBM: u = 8 mm, f = 17 Hz, v_d = 20 mm/min: ratio 816 pi = 2563.5; 0.1332 * 2563.5^-0.20306 = 0.0271.
    const auto obm = PowerLawCoefficient::from_table5("OBM");
    CHECK(obm.coefficient(frictionsim::vibration_velocity_amplitude(8e-3, 17.0), 20e-3 / 60.0) ==
          Approx(0.0271).margin(5e-5));
    // Friction falls as the vibration grows relative to the sliding (c < 0 for every lubricant).
    for (const auto& row : frictionsim::table5()) {
        const auto law = PowerLawCoefficient::from_table5(row.lubricant);
        CHECK(law.coefficient(2.0, 1e-3) < law.coefficient(1.0, 1e-3));
    }
}

TEST_CASE("power law: lubricant names are case-insensitive", "[friction][power_law]") {
    CHECK(frictionsim::lubricant_from_name("dry") == Lubricant::dry);
    CHECK(frictionsim::lubricant_from_name("Water") == Lubricant::water);
    CHECK(frictionsim::lubricant_from_name("WBM") == Lubricant::wbm);
    CHECK(frictionsim::lubricant_from_name("oBm") == Lubricant::obm);
    CHECK(frictionsim::lubricant_from_name("sbm") == Lubricant::sbm);
    CHECK(PowerLawCoefficient::from_table5("SBM").params().eta == 0.1231);
    for (const auto& row : frictionsim::table5())
        CHECK(frictionsim::lubricant_from_name(frictionsim::lubricant_name(row.lubricant)) == row.lubricant);

    for (const char* bad : {"", "oil", "wbm ", "drys", "OBM\n"}) {
        INFO(bad);
        CHECK(rejected_parameter([&] { PowerLawCoefficient::from_table5(bad); }) == "lubricant");
    }
    try {
        PowerLawCoefficient::from_table5("diesel");
        FAIL("no throw");
    } catch (const InvalidParameter& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find("dry, water, wbm, obm, sbm") != std::string::npos);
        CHECK(message.find("'diesel'") != std::string::npos);
    }
}

TEST_CASE("power law: rejects bad parameters and velocities, naming them", "[friction][power_law]") {
    CHECK(rejected_parameter([] { PowerLawCoefficient({0.0, -0.2}); }) == "eta");
    CHECK(rejected_parameter([] { PowerLawCoefficient({-0.1, -0.2}); }) == "eta");
    CHECK(rejected_parameter([] { PowerLawCoefficient({NAN, -0.2}); }) == "eta");
    CHECK(rejected_parameter([] { PowerLawCoefficient({0.1, INFINITY}); }) == "exponent");
    CHECK(rejected_parameter([] { PowerLawCoefficient({0.1, NAN}); }) == "exponent");
    CHECK(rejected_parameter([] { PowerLawCoefficient::from_eq15(0.0, -0.2); }) == "eta");

    const auto law = PowerLawCoefficient::from_table5(Lubricant::wbm);
    CHECK(rejected_parameter([&] { law.coefficient(0.0, 1e-3); }) == "vibration_velocity_amplitude");
    CHECK(rejected_parameter([&] { law.coefficient(0.5, 0.0); }) == "sliding_velocity");
    CHECK(rejected_parameter([&] { law.coefficient(0.5, -1e-3); }) == "sliding_velocity");
    CHECK(rejected_parameter([&] { law.coefficient(NAN, 1e-3); }) == "vibration_velocity_amplitude");
    CHECK(rejected_parameter([&] { law.friction_force(-1.0, 0.5, 1e-3); }) == "normal_force");
    CHECK(rejected_parameter([] { frictionsim::vibration_velocity_amplitude(-1e-3, 17.0); }) == "amplitude");
    CHECK(rejected_parameter([] { frictionsim::vibration_velocity_amplitude(1e-3, NAN); }) == "frequency");

    try {
        PowerLawCoefficient({0.0, -0.2});
        FAIL("no throw");
    } catch (const InvalidParameter& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find("PowerLawCoefficient: eta must be in (0, 10]") != std::string::npos);  // its table's rule
    }
}

TEST_CASE("power law: eta' and c in a physical range, and never an inf or NaN result", "[friction][power_law]") {
    // Table 5: eta' 0.12-1.07, c -0.09 to -0.37. c = 1e300 returned inf for any ratio above 1 before.
    for (const double exponent : {2.001, -2.001, 10.0, 1e300, -1e300}) {
        INFO(exponent);
        CHECK(rejected_parameter([&] { PowerLawCoefficient({0.2, exponent}); }) == "exponent");
        CHECK(rejected_parameter([&] { PowerLawCoefficient::from_eq15(0.2, exponent); }) == "exponent");
    }
    for (const double eta : {10.001, 1e300}) {
        INFO(eta);
        CHECK(rejected_parameter([&] { PowerLawCoefficient({eta, -0.2}); }) == "eta");
        CHECK(rejected_parameter([&] { PowerLawCoefficient::from_eq15(eta, -0.2); }) == "eta");
    }
    // eq 15's eta = 0.5 at c = -2 is eta' = 0.5 (2 pi)^2 = 19.7: outside, and named by what the caller typed
    CHECK(rejected_parameter([] { PowerLawCoefficient::from_eq15(0.5, -2.0); }) == "eta");
    CHECK_NOTHROW(PowerLawCoefficient({10.0, -2.0}));
    CHECK_NOTHROW(PowerLawCoefficient({1e-6, 2.0}));
    CHECK(rejection_message([] { PowerLawCoefficient({0.2, 5.0}); }).find("[-2, 2]") != std::string::npos);

    // Within range, an extreme velocity ratio still overflows or underflows: named, never returned.
    const PowerLawCoefficient steep({10.0, 2.0});
    CHECK(rejected_parameter([&] { (void)steep.coefficient(1e300, 1e-300); }) == "vibration_velocity_amplitude");
    CHECK(rejected_parameter([&] { (void)steep.coefficient(1e200, 1.0); }) == "vibration_velocity_amplitude");
    CHECK(rejected_parameter([&] { (void)steep.coefficient(1e-300, 1e300); }) == "vibration_velocity_amplitude");
    const PowerLawCoefficient falling({10.0, -2.0});
    CHECK(rejected_parameter([&] { (void)falling.coefficient(1e-300, 1e300); }) == "vibration_velocity_amplitude");
    CHECK(rejected_parameter([&] { (void)falling.coefficient(1e200, 1.0); }) == "vibration_velocity_amplitude");
    CHECK(rejection_message([&] { (void)steep.coefficient(1e300, 1e-300); }).find("v_a / v_d") != std::string::npos);
    CHECK(std::isfinite(steep.coefficient(1e100, 1.0)));
    // F_df = mu_df F_N and v_a = 2 pi f u_0 overflow too: named
    CHECK(rejected_parameter([&] { (void)steep.friction_force(1e308, 10.0, 1.0); }) == "normal_force");
    CHECK(rejected_parameter([] { (void)frictionsim::vibration_velocity_amplitude(1e300, 1e300); }) == "amplitude");
    CHECK(std::isfinite(frictionsim::vibration_velocity_amplitude(1e150, 1e150)));
}
