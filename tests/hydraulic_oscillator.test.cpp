// HOT normal force (paper 000, eqs 1-4) against hand arithmetic and the textbook Hertz line contact.
#include "catch.hpp"
#include "rejection.hpp"

#include <frictionsim/detail/constants.hpp>

#include <cmath>
#include <string>

#include "frictionsim/contact/hydraulic_oscillator.hpp"

using frictionsim::HydraulicOscillatorParams;
using frictionsim::InvalidParameter;

namespace {

using frictionsim::pi;

// Round numbers whose results can be checked by hand.
HydraulicOscillatorParams hand_params() {
    HydraulicOscillatorParams p{};
    p.tool_outer_radius = 0.1;
    p.tool_inner_radius = 0.05;
    p.wellbore_radius = 0.2;
    p.steel_density = 2000.0;
    p.mud_density = 1000.0;
    p.rock_youngs_modulus = 1e9;
    p.rock_poisson_ratio = 0.0;
    p.steel_youngs_modulus = 1e9;
    p.steel_poisson_ratio = 0.0;
    p.rock_wear_width = 0.01;
    p.specimen_width = 0.02;
    return p;
}

// A 172 mm HOT (38 mm bore) in a 216 mm hole, 45 steel on shale in 1.2 SG mud; the rig specimen of paper 000
// is 30 mm wide (section 2.1). The wear width a = 1.2 mm is our choice, not the paper's.
HydraulicOscillatorParams field_params() {
    HydraulicOscillatorParams p{};
    p.tool_outer_radius = 0.086;
    p.tool_inner_radius = 0.038;
    p.wellbore_radius = 0.108;
    p.steel_density = 7850.0;
    p.mud_density = 1200.0;
    p.rock_youngs_modulus = 20e9;
    p.rock_poisson_ratio = 0.25;
    p.steel_youngs_modulus = 206e9;
    p.steel_poisson_ratio = 0.3;
    p.rock_wear_width = 1.2e-3;
    p.specimen_width = 0.030;
    return p;
}

// Textbook Hertz line contact (Johnson, Contact Mechanics, section 4.2), written independently of eq 2:
// effective modulus E*, effective radius R of a cylinder in a concave cylindrical groove, contact half-width b
// and peak pressure p0.
struct TextbookLineContact {
    double effective_modulus, effective_radius, half_width, peak_pressure;
};

TextbookLineContact textbook(double load_per_length, double r_cylinder, double r_groove, double E1, double nu1,
                             double E2, double nu2) {
    TextbookLineContact c{};
    c.effective_modulus = 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
    c.effective_radius = 1.0 / (1.0 / r_cylinder - 1.0 / r_groove);
    c.half_width = std::sqrt(4.0 * load_per_length * c.effective_radius / (pi * c.effective_modulus));
    c.peak_pressure = std::sqrt(load_per_length * c.effective_modulus / (pi * c.effective_radius));
    return c;
}

}  // namespace

TEST_CASE("HOT weight per length in mud, eq 1, by hand", "[contact][hydraulic_oscillator]") {
    // 9.81 * pi * (0.1^2 - 0.05^2) * (2000 - 1000) = 9.81 * pi * 7.5 = 73.575 pi
    CHECK(frictionsim::hot_weight_per_length_in_mud(hand_params()) == Approx(73.575 * pi).epsilon(1e-14));
    // 9.81 * pi * (0.086^2 - 0.038^2) * 6650 = 9.81 * pi * 39.5808 = 1219.8416224... N/m
    CHECK(frictionsim::hot_weight_per_length_in_mud(field_params()) == Approx(1219.84162243646).epsilon(1e-13));

    auto p = hand_params();
    p.gravity = 9.80665;  // standard gravity instead of the paper's 9.81: q_c scales with it
    CHECK(frictionsim::hot_weight_per_length_in_mud(p) ==
          Approx(73.575 * pi * 9.80665 / 9.81).epsilon(1e-14));
}

TEST_CASE("HOT contact stress and rig force, eqs 2-4, by hand", "[contact][hydraulic_oscillator]") {
    const auto p = hand_params();
    // curvature 1/0.1 - 1/0.2 = 5 1/m; compliance 1e-9 + 1e-9 = 2e-9 1/Pa;
    // sigma_d = sqrt(73.575 pi * 5 / (pi * 2e-9)) = sqrt(1.839375e11) = 428879.35366... Pa
    CHECK(frictionsim::hot_relative_curvature(p) == Approx(5.0).epsilon(1e-15));
    CHECK(frictionsim::rock_steel_contact_compliance(p) == Approx(2e-9).epsilon(1e-15));
    CHECK(frictionsim::hot_contact_stress(p) == Approx(428879.353664874).epsilon(1e-13));
    // F_e = a l sigma_d = 0.01 * 0.02 * 428879.35... = 85.77587... N
    CHECK(frictionsim::equivalent_rig_normal_force(p) == Approx(85.7758707329748).epsilon(1e-13));
    // eq 3 closes the loop: the rig stress of F_e on the a x l flat is sigma_d.
    CHECK(frictionsim::rig_contact_stress(85.7758707329748, 0.01, 0.02) == Approx(428879.353664874).epsilon(1e-13));
}

TEST_CASE("HOT contact stress is the textbook Hertz peak pressure", "[contact][hydraulic_oscillator]") {
    for (const auto& p : {hand_params(), field_params()}) {
        const double q = frictionsim::hot_weight_per_length_in_mud(p);
        const auto c = textbook(q, p.tool_outer_radius, p.wellbore_radius, p.rock_youngs_modulus,
                                p.rock_poisson_ratio, p.steel_youngs_modulus, p.steel_poisson_ratio);
        const double sigma = frictionsim::hot_contact_stress(p);
        CHECK(sigma == Approx(c.peak_pressure).epsilon(1e-13));
        // Equilibrium of the elliptical (Hertz) pressure over the half-width b: q = (pi / 2) p0 b.
        CHECK(sigma == Approx(2.0 * q / (pi * c.half_width)).epsilon(1e-13));
        CHECK(frictionsim::equivalent_rig_normal_force(p) ==
              Approx(p.rock_wear_width * p.specimen_width * c.peak_pressure).epsilon(1e-13));
    }
}

TEST_CASE("HOT field case: MPa stress, ~150 N rig force as in paper 000", "[contact][hydraulic_oscillator]") {
    const auto p = field_params();
    // 1219.84 N/m * 2.36865 1/m / (pi * 5.12925e-11 1/Pa) -> sigma_d = 4.2345 MPa
    CHECK(frictionsim::hot_contact_stress(p) == Approx(4.23448105176849e6).epsilon(1e-12));
    // Section 2.3.1 settles on "about 150 N"; with a = 1.2 mm the 30 mm specimen needs 152.4 N.
    CHECK(frictionsim::equivalent_rig_normal_force(p) == Approx(152.441317863665).epsilon(1e-12));
}

TEST_CASE("HOT contact: stress grows as the hole closes on the tool", "[contact][hydraulic_oscillator]") {
    auto p = field_params();
    const double wide = frictionsim::hot_contact_stress(p);
    p.wellbore_radius = 0.09;  // nearly conformal: smaller relative curvature, wider contact, lower peak
    CHECK(frictionsim::hot_contact_stress(p) < wide);
    p.wellbore_radius = 0.5;
    CHECK(frictionsim::hot_contact_stress(p) > wide);
}

TEST_CASE("HOT contact rejects bad parameters, naming them", "[contact][hydraulic_oscillator]") {
    using frictionsim::hot_contact_stress;
    auto with = [](auto change) {
        auto p = field_params();
        change(p);
        return rejected_parameter([&] { hot_contact_stress(p); });
    };
    CHECK(with([](auto& p) { p.tool_outer_radius = -0.086; }) == "tool_outer_radius");
    CHECK(with([](auto& p) { p.tool_inner_radius = 0.0; }) == "tool_inner_radius");
    CHECK(with([](auto& p) { p.tool_inner_radius = 0.09; }) == "tool_inner_radius");     // bore wider than tool
    CHECK(with([](auto& p) { p.tool_outer_radius = 0.108; }) == "tool_outer_radius");    // tool fills the hole
    CHECK(with([](auto& p) { p.wellbore_radius = 0.05; }) == "tool_outer_radius");      // tool bigger than hole
    CHECK(with([](auto& p) { p.wellbore_radius = NAN; }) == "wellbore_radius");
    CHECK(with([](auto& p) { p.mud_density = 8000.0; }) == "steel_density");            // the tool would float
    CHECK(with([](auto& p) { p.mud_density = 0.0; }) == "mud_density");
    CHECK(with([](auto& p) { p.steel_density = INFINITY; }) == "steel_density");
    CHECK(with([](auto& p) { p.rock_youngs_modulus = 0.0; }) == "rock_youngs_modulus");
    CHECK(with([](auto& p) { p.steel_youngs_modulus = -1.0; }) == "steel_youngs_modulus");
    CHECK(with([](auto& p) { p.rock_poisson_ratio = 0.5; }) == "rock_poisson_ratio");
    CHECK(with([](auto& p) { p.steel_poisson_ratio = -0.1; }) == "steel_poisson_ratio");
    CHECK(with([](auto& p) { p.rock_wear_width = 0.0; }) == "rock_wear_width");
    CHECK(with([](auto& p) { p.specimen_width = -0.03; }) == "specimen_width");
    CHECK(with([](auto& p) { p.gravity = 0.0; }) == "gravity");

    CHECK(rejected_parameter([] { frictionsim::rig_contact_stress(-1.0, 0.01, 0.02); }) == "normal_force");
    CHECK(rejected_parameter([] { frictionsim::rig_contact_stress(1.0, 0.0, 0.02); }) == "rock_wear_width");
    CHECK(rejected_parameter([] { frictionsim::rig_contact_stress(1.0, 0.01, NAN); }) == "specimen_width");

    // The message names the owner, the parameter and the rule.
    auto p = field_params();
    p.tool_inner_radius = 0.09;
    const std::string message = rejection_message([&] { hot_contact_stress(p); });
    INFO(message);
    CHECK(message.find("HydraulicOscillatorParams") != std::string::npos);
    CHECK(message.find("tool_inner_radius must be < tool_outer_radius") != std::string::npos);
}
