// The drill string's sections and lumped model (issue 13's first layer) against closed forms: pipe properties, the
// series stiffness of a stepped string, and the natural frequencies of a fixed-top string with a BHA end inertia,
// which converge to the continuous string's kL tan(kL) = (string inertia) / (end inertia) at second order in 1/N.
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include <frictionsim/string/sections.hpp>

#include "catch.hpp"
#include "rejection.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::first_root;

namespace {

/// Lowest natural frequency [rad/s] of the lumped string, top node held, `end` added to the bottom node's inertia:
/// the generalized eigenproblem K x = w^2 M x over the free nodes (Eigen's symmetric-definite solver).
double lowest_frequency(const std::vector<double>& stiffness, std::vector<double> inertia, double end) {
    inertia.back() += end;
    const Eigen::Index n = static_cast<Eigen::Index>(stiffness.size());  // free nodes 1..N
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index e = 0; e < n; ++e) {  // spring e joins node e (held when e = 0) and node e + 1
        const double k = stiffness[static_cast<std::size_t>(e)];
        K(e, e) += k;
        if (e > 0) {
            K(e - 1, e - 1) += k;
            K(e - 1, e) -= k;
            K(e, e - 1) -= k;
        }
        M(e, e) = inertia[static_cast<std::size_t>(e + 1)];
    }
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M);
    return std::sqrt(solver.eigenvalues()(0));
}

}  // namespace

TEST_CASE("pipe section: area, polar moment and rigidities of a tube", "[drillstring]") {
    const PipeSection dp{};  // 5" drill pipe
    const double od = 0.127, id = 0.1086;
    CHECK(dp.area() == Approx(pi / 4 * (od * od - id * id)).epsilon(1e-14));
    CHECK(dp.polar_moment() == Approx(pi / 32 * (std::pow(od, 4) - std::pow(id, 4))).epsilon(1e-14));
    CHECK(dp.torsional_rigidity() == Approx(80.8e9 * dp.polar_moment()).epsilon(1e-14));
    CHECK(dp.mass_per_length() == Approx(7850.0 * dp.area()).epsilon(1e-14));
    CHECK(dp.mass_per_length() == Approx(26.68).margin(0.05));  // 5" 19.50 ppf pipe: plain-end 17.93 lb/ft
}

TEST_CASE("drill string: bad sections are refused naming the section and the parameter", "[drillstring][validation]") {
    PipeSection bad{};
    bad.inner_diameter = bad.outer_diameter;
    CHECK(rejection_message([&] { (void)DrillString({PipeSection{}, bad}); }).find("section 1: inner_diameter") !=
          std::string::npos);
    bad = PipeSection{};
    bad.length = -5.0;
    CHECK(rejection_message([&] { (void)DrillString({bad}); }).find("section 0: length must be positive") !=
          std::string::npos);
    CHECK_THROWS_AS(DrillString({}), InvalidParameter);
    CHECK_THROWS_AS(DrillString({PipeSection{}}).lump(0), InvalidParameter);
}

TEST_CASE("lumped string: inertia and mass conserved, springs in series give the sections' twist exactly",
          "[drillstring]") {
    PipeSection pipe{}, collar{};
    pipe.length = 2000.0;
    collar.outer_diameter = 0.1651;  // 6.5" collars, 2.8125" bore
    collar.inner_diameter = 0.0714;
    collar.length = 150.0;
    const DrillString string({pipe, collar});
    for (std::size_t n : {1u, 7u, 43u, 200u}) {  // 7 and 43 put an element across the boundary at 2000 m
        const LumpedString lumped = string.lump(n);
        REQUIRE(lumped.elements() == n);
        double inertia = 0.0, mass = 0.0, torsional = 0.0, axial = 0.0;
        for (double j : lumped.node_inertia) inertia += j;
        for (double m : lumped.node_mass) mass += m;
        for (double k : lumped.torsional_stiffness) torsional += 1.0 / k;
        for (double k : lumped.axial_stiffness) axial += 1.0 / k;
        INFO("N = " << n);
        CHECK(inertia == Approx(pipe.inertia_per_length() * 2000.0 + collar.inertia_per_length() * 150.0).epsilon(1e-12));
        CHECK(mass == Approx(pipe.mass_per_length() * 2000.0 + collar.mass_per_length() * 150.0).epsilon(1e-12));
        // twist per unit torque: L1 / (G I_p1) + L2 / (G I_p2), whatever the grid
        CHECK(torsional == Approx(2000.0 / pipe.torsional_rigidity() + 150.0 / collar.torsional_rigidity())
                               .epsilon(1e-12));
        CHECK(axial == Approx(2000.0 / pipe.axial_rigidity() + 150.0 / collar.axial_rigidity()).epsilon(1e-12));
    }
}

TEST_CASE("lumped string: natural frequencies converge to kL tan(kL) = J_string / J_BHA at second order",
          "[drillstring][modes]") {
    PipeSection pipe{};
    pipe.length = 2500.0;
    const DrillString string({pipe});
    const double c_torsion = std::sqrt(pipe.shear_modulus / pipe.density);  // wave speed, m/s
    const double c_axial = std::sqrt(pipe.youngs_modulus / pipe.density);
    const double bha_inertia = 0.5 * pipe.inertia_per_length() * pipe.length;  // the string twice the BHA's
    const double bha_mass = 0.8 * pipe.mass_per_length() * pipe.length;
    const double w_torsion = first_root(pipe.inertia_per_length() * pipe.length / bha_inertia) * c_torsion / 2500.0;
    const double w_axial = first_root(pipe.mass_per_length() * pipe.length / bha_mass) * c_axial / 2500.0;
    double previous_torsion = 0.0, previous_axial = 0.0;
    for (std::size_t n : {25u, 50u, 100u, 200u}) {
        const LumpedString lumped = string.lump(n);
        const double error_torsion =
            std::abs(lowest_frequency(lumped.torsional_stiffness, lumped.node_inertia, bha_inertia) / w_torsion - 1);
        const double error_axial =
            std::abs(lowest_frequency(lumped.axial_stiffness, lumped.node_mass, bha_mass) / w_axial - 1);
        INFO("N = " << n << ": relative error " << error_torsion << " (torsion), " << error_axial << " (axial)");
        CHECK(error_torsion < 2.0 / static_cast<double>(n * n));
        CHECK(error_axial < 2.0 / static_cast<double>(n * n));
        if (previous_torsion > 0.0) {  // halving dx quarters the error
            CHECK(previous_torsion / error_torsion == Approx(4.0).epsilon(0.05));
            CHECK(previous_axial / error_axial == Approx(4.0).epsilon(0.05));
        }
        previous_torsion = error_torsion;
        previous_axial = error_axial;
    }
    CHECK(w_torsion / (2 * pi) == Approx(0.22).margin(0.005));  // the torsional stick-slip mode of a 2.5 km string

    // A BHA 100x the string's inertia: the string is a spring with a third of its inertia on the end (Rayleigh),
    // sqrt(k / (J_BHA + J_string / 3)), k = G I_p / L; the closed form and the lumped string both agree with it.
    const double heavy = 100.0 * pipe.inertia_per_length() * pipe.length;
    const double rayleigh = std::sqrt(pipe.torsional_rigidity() / pipe.length /
                                      (heavy + pipe.inertia_per_length() * pipe.length / 3.0));
    CHECK(first_root(0.01) * c_torsion / 2500.0 == Approx(rayleigh).epsilon(1e-5));
    const LumpedString lumped = string.lump(100);
    CHECK(lowest_frequency(lumped.torsional_stiffness, lumped.node_inertia, heavy) == Approx(rayleigh).epsilon(1e-5));
}
