// A StringRig standing in a surveyed well (drillstring/string_geometry.hpp): a straight inclined survey reproduces
// the straight-hole rig, a weightless string around an arc presses each node with T dtheta, the normal forces are
// the soft-string side forces lumped to the nodes, and the rig at rest (and turning) in a build well carries the
// soft-string model's hook load (and surface torque).
#include <cmath>
#include <cstddef>
#include <vector>

#include "catch.hpp"
#include "frictionsim/wells/soft_string.hpp"
#include "frictionsim/wells/string_geometry.hpp"
#include "frictionsim/string/string_rig.hpp"
#include "frictionsim/friction/coulomb.hpp"
#include "frictionsim/simulate.hpp"
#include "drill_pipe.hpp"
#include "rejection.hpp"

using namespace frictionsim;
using frictionsim::test::pipe_string;

namespace {

/// Vertical to 300 m, then a build at constant curvature to 60 degrees at 900 m (kappa = (pi / 3) / 600 m).
Survey build_well() {
    return Survey::from_degrees({{0.0, 0.0, 0.0}, {300.0, 0.0, 45.0}, {900.0, 60.0, 45.0}, {1200.0, 60.0, 45.0}});
}

/// A moving state: every node turning and sliding, twisted and stretched.
template <class Rig>
std::vector<double> moving_state(const Rig& rig) {
    std::vector<double> x = rig.initial_state();
    for (std::size_t i = 0; i <= rig.elements(); ++i) {
        const double s = static_cast<double>(i);
        x[rig.theta(i)] = 0.01 * std::sin(s);
        x[rig.omega(i)] = 1.0 + 0.3 * std::cos(1.7 * s);
        x[rig.position(i)] = 1e-3 * std::cos(s);
        x[rig.speed(i)] = 0.05 + 0.02 * std::sin(2.3 * s);
    }
    return x;
}

}  // namespace

TEST_CASE("string geometry: a straight inclined survey reproduces the straight-hole rig",
          "[string_geometry][string_rig]") {
    const double incline = 0.7;
    const DrillString string = pipe_string(600.0);
    const Survey straight({{0.0, incline, 1.0}, {800.0, incline, 1.0}});
    StringRigParams p;
    p.inclination = incline;
    p.damping_time = 0.01;
    p.end_mass = 4e3;
    StringRigSetup s;
    s.elements = 12;
    s.axial = true;
    SECTION("off bottom: a contact at every node, the end mass's weight at the bit node") {
        const StringRig<Coulomb> flat(string, p, s, Coulomb(0.3));
        const StringRig<Coulomb> surveyed(string, p, surveyed_setup(straight, string, p, s), Coulomb(0.3));
        REQUIRE(surveyed.normal_forces().size() == flat.normal_forces().size());
        for (std::size_t c = 0; c < flat.normal_forces().size(); ++c)
            CHECK(surveyed.normal_forces()[c] == Approx(flat.normal_forces()[c]).epsilon(1e-12));
        for (std::size_t i = 0; i <= 12; ++i) {
            CHECK(surveyed.node_inclinations()[i] == Approx(incline).epsilon(1e-14));
            CHECK(surveyed.axial_weights()[i] == Approx(flat.axial_weights()[i]).epsilon(1e-12));
        }
        const std::vector<double> x = moving_state(flat);
        std::vector<double> a(x.size()), b(x.size());
        const ContactModes mode = flat.initial_mode(0.0, x.data());
        flat.rhs(0.0, x.data(), mode, a.data());
        surveyed.rhs(0.0, x.data(), mode, b.data());
        for (std::size_t k = 0; k < x.size(); ++k) CHECK(b[k] == Approx(a[k]).margin(1e-9).epsilon(1e-12));
    }
    SECTION("on bottom: no contact at the bit node") {
        const VelocityWeakeningBit bit(NavarroLopezBit(), 4e4);
        const StringRig<Coulomb, VelocityWeakeningBit> flat(string, p, s, Coulomb(0.3), bit);
        const StringRig<Coulomb, VelocityWeakeningBit> surveyed(string, p, surveyed_setup(straight, string, p, s, bit),
                                                                Coulomb(0.3), bit);
        REQUIRE(surveyed.normal_forces().size() == 11);
        for (std::size_t c = 0; c < 11; ++c)
            CHECK(surveyed.normal_forces()[c] == Approx(flat.normal_forces()[c]).epsilon(1e-12));
    }
}

TEST_CASE("string geometry: around an arc a weightless string presses each node with T dtheta",
          "[string_geometry]") {
    // steel-dense mud: no buoyed weight, the tension T = 2e5 N all along; the build's curvature kappa turns it by
    // kappa dL per element, so each node of the arc carries T kappa dL (half at the arc's ends), none above it
    const DrillString string = pipe_string(900.0);
    const double tension = 2e5, kappa = (pi / 3.0) / 600.0;
    const std::size_t n = 90;  // 10 m elements: node 30 at the kick-off point
    const StringGeometry g = string_geometry(build_well(), string, n, string.sections()[0].density, tension);
    const double dl = 10.0;
    for (std::size_t i = 0; i <= n; ++i) {
        CAPTURE(i);
        CHECK(g.tension[i] == Approx(tension).epsilon(1e-12));
        CHECK(g.measured_depth[i] == Approx(dl * static_cast<double>(i)).epsilon(1e-12));
        const double expected = i < 30 ? 0.0 : (i == 30 || i == n) ? 0.5 * tension * kappa * dl : tension * kappa * dl;
        CHECK(g.normal_force[i] == Approx(expected).margin(1e-9 * tension * kappa * dl).epsilon(1e-9));
        const double incline = i <= 30 ? 0.0 : kappa * dl * static_cast<double>(i - 30);
        CHECK(g.inclination[i] == Approx(incline).margin(1e-12));
    }
}

TEST_CASE("string geometry: with weight, the normal forces are the soft-string side forces lumped to the nodes",
          "[string_geometry]") {
    const DrillString string = pipe_string(900.0);
    const Survey well = build_well();
    const double mud = 1300.0;
    const std::size_t n = 45;
    const StringGeometry g = string_geometry(well, string, n, mud, -3e4);  // on bottom under 30 kN
    // the tension at rest is the soft-string model's while rotating off bottom (no axial friction) or sliding with
    // the weight on bit at the bit: its hook load, independently computed element by element from the bit up
    const SoftString soft(well, string, n);
    SoftStringParams sp;
    sp.mud_density = mud;
    sp.weight_on_bit = 3e4;
    sp.rate_of_penetration = 0.0;
    const TorqueDragResult rotating = soft.run(Operation::rotary_drilling, sp);
    for (std::size_t i = 0; i <= n; ++i) CHECK(g.tension[i] == Approx(rotating.tension[i]).epsilon(1e-12));
    const std::vector<double> side = soft.node_side_forces(rotating.tension, mud);
    for (std::size_t i = 0; i <= n; ++i) CHECK(g.normal_force[i] == Approx(side[i]).epsilon(1e-12));
    // each node's force: half the neighbouring elements' Johancsik side forces; in the vertical part none
    double total = 0.0;
    for (std::size_t e = 0; e < n; ++e) total += rotating.side_force[e];
    double lumped = 0.0;
    for (double f : g.normal_force) lumped += f;
    CHECK(lumped == Approx(total).epsilon(0.02));  // mean tension against the lower end's: first order in dL
    CHECK(g.normal_force[5] == 0.0);
    CHECK(rejected_parameter([&] { (void)string_geometry(well, pipe_string(1300.0), n, mud); }) ==
          "survey last measured_depth");
}

namespace {

/// The string of build_well() hung from a held hook (axial), Coulomb walls with the soft-string normal forces,
/// turned at `speed` by a prescribed surface speed, started hanging (hanging_state) and turning as a whole.
StringRig<Coulomb> rig_in_the_build(std::size_t n, double speed) {
    const DrillString string = pipe_string(900.0);
    StringRigParams p;
    p.mud_density = 1300.0;
    p.surface_speed = speed;
    p.initial_speed = speed;
    p.damping_time = 0.05;
    StringRigSetup s;
    s.elements = n;
    s.axial = true;
    s.top_drive = TopDrive::prescribed_speed;
    return StringRig<Coulomb>(string, p, surveyed_setup(build_well(), string, p, s), Coulomb(0.25, 0.3));
}

}  // namespace

TEST_CASE("string rig in a surveyed build: at rest the hook carries the soft-string hook load, second order in N",
          "[string_geometry][string_rig]") {
    const SoftString reference_string(build_well(), pipe_string(900.0), 900);
    SoftStringParams sp;
    sp.mud_density = 1300.0;
    const double hook_load = reference_string.run(Operation::rotating_off_bottom, sp).hook_load();
    std::vector<double> error;
    for (std::size_t n : {15, 30, 60}) {
        const StringRig<Coulomb> rig = rig_in_the_build(n, 0.0);
        StringRig<Coulomb> run = rig;
        run.set_initial_state(rig.hanging_state());
        SolverOptions o;
        o.rtol = 1e-9;
        o.atol = 1e-12;
        o.output_times = {2.0};
        const Result r = simulate(run, 2.0, o);
        REQUIRE(r.completed);
        const double* x = &r.states[0];
        // hanging without friction needed: every contact with a normal force holds (in the vertical part there is
        // none, and only rounding moves a node), nothing moved
        int pressed = 0;
        for (double f : rig.normal_forces()) pressed += f > 0.0;
        CHECK(r.mode[0] >= pressed);
        for (std::size_t i = 0; i <= n; ++i) CHECK(std::abs(x[rig.speed(i)]) < 1e-9);
        const double hook = run.hook_force(2.0, x, run.initial_mode(2.0, x));
        error.push_back(std::abs(hook - hook_load) / hook_load);
    }
    // the lumped weights integrate w cos I by the trapezoidal rule over the build: halving dL quarters the error
    CHECK(error[2] < 1e-4);
    CHECK(error[0] / error[1] == Approx(4.0).epsilon(0.05));
    CHECK(error[1] / error[2] == Approx(4.0).epsilon(0.05));
}

TEST_CASE("string rig in a surveyed build: turning steadily, the surface torque is the soft-string torque",
          "[string_geometry][string_rig][heavy]") {
    // rotating off bottom: the friction is wholly circumferential, the axial balance stays the hanging one and the
    // steady surface torque is sum mu N_i r. The soft string sums mu F_n r over elements (F_n under each element's
    // lower-end tension, where the rig's forces take the mean): at 1 m and 0.5 m elements it has converged to
    // 1e-6, and the lumped rig approaches it within 0.4 % at 60 m elements, not monotonically: inside the build
    // the contact moves from the low side to the high side (F kappa = w sin I, the kink of |F kappa - w sin I|),
    // where the midpoint rule of the lumped forces loses its order.
    SoftStringParams sp;
    sp.mud_density = 1300.0;
    sp.open_hole_friction = 0.25;
    sp.rotary_speed = 2.0;
    const double fine = SoftString(build_well(), pipe_string(900.0), 1800).run(Operation::rotating_off_bottom, sp)
                            .surface_torque();
    const double coarse = SoftString(build_well(), pipe_string(900.0), 900).run(Operation::rotating_off_bottom, sp)
                              .surface_torque();
    CHECK(fine == Approx(coarse).epsilon(1e-5));
    for (std::size_t n : {15, 30, 60}) {
        CAPTURE(n);
        const StringRig<Coulomb> rig = rig_in_the_build(n, 2.0);
        StringRig<Coulomb> run = rig;
        run.set_initial_state(rig.hanging_state());
        SolverOptions o;
        o.rtol = 1e-9;
        o.atol = 1e-12;
        o.output_times = {20.0};
        const Result r = simulate(run, 20.0, o);
        REQUIRE(r.completed);
        const double* x = &r.states[0];
        for (std::size_t i = 0; i <= n; ++i) {
            CHECK(x[rig.omega(i)] == Approx(2.0).epsilon(1e-6));  // steady: the string turns as a whole
            CHECK(std::abs(x[rig.speed(i)]) < 1e-9);              // no axial motion: no axial friction
        }
        double statics = 0.0;
        for (std::size_t c = 0; c < rig.contact_count(); ++c)
            statics += 0.25 * rig.normal_forces()[c] * rig.node_radius()[rig.contact_nodes()[c]];
        const double surface = run.surface_torque(20.0, x, run.initial_mode(20.0, x));
        CHECK(surface == Approx(statics).epsilon(1e-6));
        CHECK(surface == Approx(fine).epsilon(4e-3));
    }
}
