// The Moreau-Jean time-stepper (solve/moreau_jean.hpp) against closed forms: the driven spring-block's exact
// stick-slip cycle (and the measured first order in h), the one-step inclusion of a coupled chain against an
// enumeration of all mode sets, the rigid-chain limit, the discrete energy balance, true stick, bad input.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <tuple>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <frictionsim/eigen/chain_ldlt.hpp>
#include <frictionsim/eigen/moreau_jean.hpp>
#include <frictionsim/eigen/one_step_contact.hpp>  // ProjectedGaussSeidel, the ContactSolver concept

#include "catch.hpp"
#include "convergence.hpp"
#include "rejection.hpp"

using namespace frictionsim;
using frictionsim::test::fitted_order;

namespace {

Eigen::SparseMatrix<double> sparse(const Eigen::MatrixXd& a) { return a.sparseView(); }

/// Block of mass m on a fixed floor (static force s >= kinetic d), pulled through a spring k whose far end moves at
/// V from t = 0; at rest and unstretched at t = 0. With y = V t - x (the stretch):
///   stick until k y = s; slip: y = d/k + (s-d)/k cos(w u) + (V/w) sin(w u), w = sqrt(k/m), u from breakaway;
///   slip ends when x' = 0 at w u_s = 2 (pi - atan((s-d) w / (k V))), where y = (2d - s)/k (the slip is a half-
///   sinusoid around d/k); stick for 2 (s-d) / (k V); period u_s + 2 (s-d)/(k V).
struct SpringBlock {
    double m = 1.0, k = 100.0, s = 10.0, d = 6.0, V = 0.5;
    double w() const { return std::sqrt(k / m); }
    double first_breakaway() const { return s / (k * V); }
    double slip_time() const { return 2.0 / w() * (std::acos(-1.0) - std::atan((s - d) * w() / (k * V))); }
    double stick_time() const { return 2.0 * (s - d) / (k * V); }
    double period() const { return slip_time() + stick_time(); }
    /// Exact (x, x') at t.
    std::pair<double, double> exact(double t) const {
        const double t0 = first_breakaway();
        if (t < t0) return {0.0, 0.0};
        const double cycle = std::floor((t - t0) / period());
        const double tb = t0 + cycle * period(), u = t - tb;  // breakaway of this cycle
        if (u < slip_time()) {
            const double y = d / k + (s - d) / k * std::cos(w() * u) + V / w() * std::sin(w() * u);
            const double dy = -(s - d) / k * w() * std::sin(w() * u) + V * std::cos(w() * u);
            return {V * t - y, V - dy};
        }
        return {V * (tb + slip_time()) - (2.0 * d - s) / k, 0.0};
    }
    LinearMechanicalSystem system() const {
        LinearMechanicalSystem sys;
        sys.mass = sparse(Eigen::MatrixXd::Constant(1, 1, m));
        sys.stiffness = sparse(Eigen::MatrixXd::Constant(1, 1, k));
        const double kv = k * V;
        sys.force = [kv](double t, Eigen::VectorXd& f) { f(0) = kv * t; };
        sys.contacts = {PointContact{0, s, d}};
        return sys;
    }
};

struct BlockRun {
    double max_error = 0.0;      ///< max |x - x_exact| over the steps
    double max_speed_error = 0.0;  ///< max |v - v_exact| over the steps
    bool stick_exact = true;     ///< v == 0.0 and |r| <= s at every step the contact is stuck
    double stuck_time = 0.0;     ///< time spent stuck after the first breakaway
    std::vector<double> breakaways;
};

BlockRun run_block(const SpringBlock& b, double h, double theta, double t_end,
                   ContactTreatment treatment = ContactTreatment::inclusion, double band = 0.0) {
    MoreauJeanOptions o;
    o.step = h;
    o.theta = theta;
    o.treatment = treatment;
    o.projection_band = band;
    MoreauJean mj(b.system(), o, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
    BlockRun out;
    while (mj.time() < t_end - 0.5 * h) {
        mj.step();
        out.max_error = std::max(out.max_error, std::abs(mj.positions()(0) - b.exact(mj.time()).first));
        out.max_speed_error = std::max(out.max_speed_error, std::abs(mj.velocities()(0) - b.exact(mj.time()).second));
        if (mj.modes()[0] == ContactState::stick) {
            if (!(mj.velocities()(0) == 0.0 && std::abs(mj.contact_forces()(0)) <= b.s)) out.stick_exact = false;
            if (mj.time() > b.first_breakaway() + h) out.stuck_time += h;
        }
    }
    for (const ContactEvent& e : mj.events())
        if (e.kind == ContactEvent::Kind::stick_to_slip) out.breakaways.push_back(e.time);
    return out;
}

}  // namespace

TEST_CASE("Moreau-Jean: the driven spring-block's exact stick-slip cycle, first order in h", "[moreau_jean]") {
    const SpringBlock b;
    REQUIRE(b.period() == Approx(0.6534).margin(1e-3));  // 0.4934 s slip + 0.16 s stick
    const double t_end = 3.0;                            // 4.3 cycles
    const double exact_stuck = 4.0 * b.stick_time() + std::max(0.0, t_end - b.first_breakaway() - 4.0 * b.period() -
                                                                    b.slip_time());
    for (double theta : {0.5, 1.0}) {
        std::vector<double> steps{2e-3, 1e-3, 5e-4, 2.5e-4}, errors, speed_errors;
        for (double h : steps) {
            const BlockRun run = run_block(b, h, theta, t_end);
            INFO("theta = " << theta << ", h = " << h << ": max |x - x_exact| = " << run.max_error);
            errors.push_back(run.max_error);
            speed_errors.push_back(run.max_speed_error);
            CHECK(run.stick_exact);
            // the stick phases' total: theta = 1 damps each slip a little and shortens the stick (24 h measured)
            CHECK(run.stuck_time == Approx(exact_stuck).margin((theta == 0.5 ? 12 : 26) * h));
            // breakaways one period apart (a theta = 1 cycle is shortened by its numerical damping: O(h))
            REQUIRE(run.breakaways.size() >= 4);
            CHECK(std::abs(run.breakaways[0] - b.first_breakaway()) <= 1.01 * h);
            for (std::size_t i = 1; i < run.breakaways.size(); ++i)
                CHECK(std::abs(run.breakaways[i] - run.breakaways[i - 1] - b.period()) <= 4.0 * h);
            // O(h) with the constants measured: 0.2-0.71 h (theta = 1/2), 5.5 h (theta = 1: its damping of the
            // slip's sinusoid, 1 - w^2 h^2 / 2 per step, adds a phase error that grows over the cycles)
            CHECK(run.max_error < (theta == 0.5 ? 0.8 : 6.5) * h);
        }
        const double order = fitted_order(steps, errors), speed_order = fitted_order(steps, speed_errors);
        INFO("theta = " << theta << ": fitted order " << order << " (position), " << speed_order << " (speed)");
        if (theta == 1.0) {  // first order: ratios per halving 1.87, 2.08, 1.87 (x) and 1.81, 2.03, 1.89 (v)
            CHECK(order == Approx(1.0).margin(0.15));
            CHECK(speed_order == Approx(1.0).margin(0.15));
        } else {  // at least first order, erratic: the error of a switch depends on where it falls in its step
            CHECK(order > 0.85);  // ratios 1.7, 2.8, 5.2 (x), 1.7, 2.8, 5.7 (v): fitted 1.55 and 1.6
            CHECK(speed_order > 0.85);
        }
    }
}

TEST_CASE("Moreau-Jean: the field codes' projection is the explicit special case - its stick band costs half an order",
          "[moreau_jean]") {
    // Explicit: W = M, the inclusion decouples and the clipped predicted force is its solution; a slipping contact
    // needs the stick band to be caught (|v| below the speed its friction removes in a step, d h / m). Inside the
    // band the static force acts on a moving block too, so after breakaway it creeps until |v| leaves the band:
    // v = k V u^2 / (2 m) reaches the band b after u = sqrt(2 m b / (k V)), a delay of O(sqrt(h)) per cycle.
    const SpringBlock b;
    std::vector<double> steps{4e-4, 2e-4, 1e-4}, errors;
    for (double h : steps) {
        const double band = 1.5 * b.d * h / b.m;
        const BlockRun run = run_block(b, h, 1.0, 3.0, ContactTreatment::projection, band);
        INFO("h = " << h << ": max |x - x_exact| = " << run.max_error);
        errors.push_back(run.max_error);
        CHECK(run.stick_exact);
        REQUIRE(run.breakaways.size() >= 4);
        const double delay = std::sqrt(2.0 * b.m * band / (b.k * b.V));
        INFO("period " << run.breakaways[3] - run.breakaways[2] << ", creep delay " << delay);
        CHECK(run.breakaways[3] - run.breakaways[2] - b.period() > 0.3 * delay);  // measured 0.7-0.8 delay
        CHECK(run.breakaways[3] - run.breakaways[2] - b.period() < 1.2 * delay + 2 * h);
    }
    const double order = fitted_order(steps, errors);
    INFO("fitted order " << order);
    CHECK(order > 0.35);  // measured 0.47: one half
    CHECK(order < 0.7);
}

TEST_CASE("Moreau-Jean: the coupled one-step inclusion equals the enumeration of all mode sets - contact by contact "
          "would violate it",
          "[moreau_jean]") {
    // Three unit masses, stiff springs and dashpots between neighbours; h so large that W is far from diagonal.
    // All at rest and stuck, a force on mass 1 only. s = d: the law is monotone, the step's solution unique.
    const double k = 1e4, c = 50.0, h = 0.01;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3, 3), C = Eigen::MatrixXd::Zero(3, 3);
    for (int e = 0; e < 2; ++e) {
        K.block<2, 2>(e, e) += k * (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
        C.block<2, 2>(e, e) += c * (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
    }
    const std::vector<double> bound{3.0, 2.0, 2.0};
    LinearMechanicalSystem sys;
    sys.mass = sparse(Eigen::MatrixXd::Identity(3, 3));
    sys.damping = sparse(C);
    sys.stiffness = sparse(K);
    sys.force = [](double, Eigen::VectorXd& f) { f << 6.5, 0.0, 0.0; };
    for (std::size_t i = 0; i < 3; ++i) sys.contacts.push_back(PointContact{i, bound[i], bound[i]});
    MoreauJeanOptions o;
    o.step = h;
    o.theta = 1.0;
    MoreauJean mj(sys, o, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3));
    mj.step();
    const Eigen::VectorXd v = mj.velocities(), r = mj.contact_forces();

    // Enumerate the 27 mode sets: solve W v = b + h r with stuck dofs at rest, keep the consistent ones.
    const Eigen::MatrixXd W = Eigen::MatrixXd::Identity(3, 3) + h * C + h * h * K;
    const Eigen::VectorXd rhs = (Eigen::VectorXd(3) << h * 6.5, 0.0, 0.0).finished();  // from rest: h f
    int solutions = 0;
    Eigen::VectorXd v_ref = Eigen::VectorXd::Zero(3);
    for (int code = 0; code < 27; ++code) {
        int mode[3] = {code % 3 - 1, (code / 3) % 3 - 1, code / 9 - 1};  // -1, 0 (stick), +1
        Eigen::MatrixXd A = W;
        Eigen::VectorXd y = rhs;
        for (int i = 0; i < 3; ++i) {
            if (mode[i] == 0) {
                A.row(i).setZero();
                A(i, i) = 1.0;
                y(i) = 0.0;
            } else {
                y(i) -= h * bound[static_cast<std::size_t>(i)] * mode[i];
            }
        }
        const Eigen::VectorXd x = A.colPivHouseholderQr().solve(y);
        const Eigen::VectorXd reaction = (W * x - rhs) / h;
        bool ok = true;
        for (int i = 0; i < 3; ++i)
            ok = ok && (mode[i] == 0 ? std::abs(reaction(i)) <= bound[static_cast<std::size_t>(i)] + 1e-9
                                     : mode[i] * x(i) > 0.0);
        if (ok) {
            ++solutions;
            v_ref = x;
        }
    }
    REQUIRE(solutions == 1);
    INFO("v = " << v.transpose() << ", reference " << v_ref.transpose() << ", r = " << r.transpose());
    CHECK((v - v_ref).norm() < 1e-12);
    CHECK(v(0) > 0.0);
    CHECK(v(1) > 0.0);  // mass 2 is dragged loose through the step's coupling
    CHECK((W * v - rhs - h * r).norm() < 1e-12);

    // Contact by contact: each decides from the force on its own dof with the others at rest (mass 1: 6.5 > 3, it
    // slips; masses 2, 3: no force, they stick). Solve with that set: the reaction asked of contact 2 exceeds its
    // bound, so the local answer is not a solution of the step.
    Eigen::MatrixXd A = W;
    Eigen::VectorXd y = Eigen::VectorXd::Zero(3);
    y(0) = rhs(0) - h * bound[0];
    for (int i = 1; i < 3; ++i) {
        A.row(i).setZero();
        A(i, i) = 1.0;
    }
    const Eigen::VectorXd local = A.colPivHouseholderQr().solve(y);
    const Eigen::VectorXd local_reaction = (W * local - rhs) / h;
    CHECK(std::abs(local_reaction(1)) > bound[1]);
}

TEST_CASE("Moreau-Jean: a stiff chain acts as one body: at rest below the sum of the bounds, sliding above it",
          "[moreau_jean]") {
    // Spring period 2 pi sqrt(m / k) = 6 ms << h = 20 ms: theta = 1 damps it out and the chain is rigid.
    const double k = 1e3, h = 0.02;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3, 3);
    for (int e = 0; e < 2; ++e) K.block<2, 2>(e, e) += k * (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
    const double s[3] = {3.0, 2.0, 2.0}, d[3] = {2.0, 1.5, 1.5};
    for (double push : {4.5, 9.0}) {  // max s < 4.5 < sum d = 5 < sum s = 7 < 9
        LinearMechanicalSystem sys;
        sys.mass = sparse(Eigen::MatrixXd::Identity(3, 3));
        sys.stiffness = sparse(K);
        sys.force = [push](double, Eigen::VectorXd& f) { f << push, 0.0, 0.0; };
        for (std::size_t i = 0; i < 3; ++i) sys.contacts.push_back(PointContact{i, s[i], d[i]});
        MoreauJeanOptions o;
        o.step = h;
        o.theta = 1.0;
        MoreauJean mj(sys, o, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3));
        mj.run(2.0);
        INFO("push " << push << ": v = " << mj.velocities().transpose() << ", r = " << mj.contact_forces().transpose());
        if (push < 7.0) {
            for (int i = 0; i < 3; ++i) {
                CHECK(mj.velocities()(i) == 0.0);  // true stick, no creep
                CHECK(std::abs(mj.contact_forces()(i)) <= s[i]);
            }
            CHECK(mj.contact_forces().sum() == Approx(-push).epsilon(1e-9));  // static equilibrium of the chain
        } else {  // one body of mass 3 under push - sum d: v = (9 - 5) / 3 t
            for (int i = 0; i < 3; ++i) CHECK(mj.velocities()(i) == Approx(4.0 / 3.0 * 2.0).epsilon(0.02));
        }
    }
}

TEST_CASE("Moreau-Jean: energy balance, exact for theta = 1/2 and O(h) with the continuous accounting",
          "[moreau_jean]") {
    // Two masses, a spring to the wall and one between, a dashpot, Coulomb contacts on both, a sinusoidal force:
    // input work = kinetic + elastic + friction dissipation + damping.
    Eigen::MatrixXd K(2, 2), C(2, 2);
    K << 150, -50, -50, 50;
    C << 0.4, -0.2, -0.2, 0.2;
    const auto residual = [&](double theta, double h, bool continuous) {
        LinearMechanicalSystem sys;
        sys.mass = sparse(Eigen::Vector2d(1.0, 2.0).asDiagonal().toDenseMatrix());
        sys.damping = sparse(C);
        sys.stiffness = sparse(K);
        sys.force = [](double t, Eigen::VectorXd& f) { f << 30.0 * std::sin(5.0 * t), 0.0; };
        sys.contacts = {PointContact{0, 4.0, 3.0}, PointContact{1, 6.0, 5.0}};
        MoreauJeanOptions o;
        o.step = h;
        o.theta = theta;
        MoreauJean mj(sys, o, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2));
        const Eigen::MatrixXd M = sys.mass, Kd = K;
        const auto energy = [&] {
            return 0.5 * mj.velocities().dot(M * mj.velocities()) + 0.5 * mj.positions().dot(Kd * mj.positions());
        };
        double input = 0.0, friction = 0.0, damping = 0.0, sticks = 0.0;
        while (mj.time() < 4.0 - 0.5 * h) {
            const Eigen::VectorXd v0 = mj.velocities();
            mj.step();
            const Eigen::VectorXd v1 = mj.velocities();
            const Eigen::VectorXd vt = continuous ? v1 : Eigen::VectorXd((1 - theta) * v0 + theta * v1);
            input += h * mj.applied_force().dot(vt);
            friction -= h * mj.contact_forces().dot(vt);
            damping += h * vt.dot(C * vt);
            sticks += mj.velocities()(1) == 0.0 ? 1 : 0;
        }
        REQUIRE(sticks > 10);  // the run sticks and slips
        REQUIRE(friction > 0.1 * input);
        return std::abs(input - energy() - friction - damping) / input;
    };
    // theta = 1/2: the midpoint rule keeps the linear part's energy exactly; with the work of r at v_{k+1/2}
    // the balance holds to round-off.
    CHECK(residual(0.5, 1e-3, false) < 1e-11);
    // Friction work counted as the continuous -r v_{k+1} (>= 0) and theta = 1: O(h).
    const double coarse = residual(1.0, 1e-3, true), fine = residual(1.0, 5e-4, true);
    INFO("relative residual " << coarse << " at h = 1e-3, " << fine << " at h = 5e-4");
    CHECK(coarse < 0.05);
    CHECK(coarse / fine == Approx(2.0).margin(0.4));
}

TEST_CASE("Moreau-Jean: bad options and sizes name the parameter - a non-finite state stops with the time reached",
          "[moreau_jean][validation]") {
    const SpringBlock b;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
    const auto make = [&](MoreauJeanOptions o, LinearMechanicalSystem sys, Eigen::VectorXd q) {
        return [=] { MoreauJean mj(sys, o, q, zero); };
    };
    MoreauJeanOptions o;
    o.step = 0.0;
    CHECK(rejected_parameter(make(o, b.system(), zero)) == "step");
    o.step = std::nan("");
    CHECK(rejected_parameter(make(o, b.system(), zero)) == "step");
    o = MoreauJeanOptions{};
    o.theta = 0.3;
    CHECK(rejection_message(make(o, b.system(), zero)).find("theta must be in [0.5, 1]") != std::string::npos);
    o = MoreauJeanOptions{};
    CHECK(rejected_parameter(make(o, b.system(), Eigen::VectorXd::Zero(2))) == "q0");
    CHECK(rejected_parameter(make(o, b.system(), Eigen::VectorXd::Constant(1, NAN))) == "q0");
    LinearMechanicalSystem sys = b.system();
    sys.stiffness = sparse(Eigen::MatrixXd::Identity(2, 2));
    CHECK(rejected_parameter(make(o, sys, zero)) == "stiffness");
    sys = b.system();
    sys.contacts[0].static_bound = 1.0;  // below the kinetic 6
    CHECK(rejected_parameter(make(o, sys, zero)) == "contacts.static_bound");
    sys = b.system();
    sys.contacts[0].dof = 3;
    CHECK(rejected_parameter(make(o, sys, zero)) == "contacts.dof");
    sys = b.system();
    sys.mass = sparse(Eigen::MatrixXd::Constant(1, 1, -1.0));
    CHECK(rejected_parameter(make(o, sys, zero)) == "mass");

    sys = b.system();
    sys.force = [](double t, Eigen::VectorXd& f) { f(0) = t < 0.0105 ? 1e3 * t : NAN; };
    o.step = 1e-3;
    MoreauJean mj(sys, o, zero, zero);
    try {
        mj.run(1.0);
        FAIL("no SimulationError");
    } catch (const SimulationError& e) {
        CHECK(e.time_reached() == Approx(0.010).margin(1e-12));  // the last step whose end force was finite
        CHECK(std::isfinite(mj.positions()(0)));
    }
    int polls = 0;
    o.interrupt = [&polls] { return ++polls > 2; };
    MoreauJean stopped(b.system(), o, zero, zero);
    CHECK_THROWS_AS(stopped.run(10.0), Interrupted);
    CHECK(stopped.time() < 1.0);
}

TEST_CASE("Moreau-Jean: outputs at requested times and the event log", "[moreau_jean]") {
    const SpringBlock b;
    MoreauJeanOptions o;
    o.step = 1e-3;
    o.theta = 1.0;
    for (int i = 0; i <= 20; ++i) o.output_times.push_back(0.1 * i + 0.00025);  // between steps: interpolated
    MoreauJean mj(b.system(), o, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
    std::vector<double> seen;
    mj.run(2.0, [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
        seen.push_back(t);
        CHECK(q(0) == Approx(b.exact(t).first).margin(6.5e-3));  // theta = 1's O(h) error, as above
    });
    CHECK(seen.size() == 20);  // 2.00025 is past the end
    // breakaway then stick, alternating, one contact
    REQUIRE(mj.events().size() >= 5);
    for (std::size_t i = 0; i < mj.events().size(); ++i)
        CHECK(mj.events()[i].kind ==
              (i % 2 == 0 ? ContactEvent::Kind::stick_to_slip : ContactEvent::Kind::slip_to_stick));
    // a switch costs what the switching contacts cost: a step without a switch factors nothing
    CHECK(mj.statistics().factorisations <= 1 + 2 * mj.statistics().contact_switches);
}

TEST_CASE("MoreauJean: contact bounds changed between steps take effect from the next step", "[moreau_jean]") {
    // A free block (m = 1) sliding at 1 m/s against kinetic 1 N decelerates at 1 m/s^2; from t = 0.2 s at 2 N it
    // decelerates at 2: v(0.4) = 1 - 0.2 - 0.4 = 0.4 exactly (piecewise-constant force: the theta-method is exact).
    LinearMechanicalSystem sys;
    sys.mass = sparse(Eigen::MatrixXd::Constant(1, 1, 1.0));
    sys.contacts = {PointContact{0, 1.5, 1.0}};
    MoreauJeanOptions o;
    o.step = 0.01;
    MoreauJean mj(sys, o, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 1.0));
    mj.run(0.2);
    CHECK(mj.velocities()(0) == Approx(0.8).margin(1e-12));
    mj.set_contact_bounds(0, 3.0, 2.0);
    mj.run(0.4);
    CHECK(mj.velocities()(0) == Approx(0.4).margin(1e-12));
    mj.run(0.7);  // comes to rest at 0.6 and stays (static 3 N, nothing pulls)
    CHECK(mj.velocities()(0) == 0.0);
    CHECK(rejected_parameter([&] { mj.set_contact_bounds(1, 3.0, 2.0); }) == "contact");
    CHECK(rejected_parameter([&] { mj.set_contact_bounds(0, 1.0, 2.0); }) == "static_bound");
    CHECK(rejected_parameter([&] { mj.set_contact_bounds(0, 3.0, -1.0); }) == "kinetic_bound");
}


namespace {

/// A chain of n masses (about 1 kg) between springs and dashpots, each tethered by a spring to a support that
/// oscillates with a phase lag along the chain (a travelling wave: the contacts stick and slip at different times),
/// Coulomb contacts of varied levels (every seventh mass free, every fifth with a slow level below 0.05 m/s);
/// `band_two`: the same matrices with explicit zeros at (i, i + 2), which sends it down the general banded path.
LinearMechanicalSystem stick_slip_chain(int n, bool band_two) {
    std::vector<Eigen::Triplet<double>> m, c, k;
    const double spring = 1e4, dashpot = 0.3, tether = 50.0;
    for (int i = 0; i < n; ++i) {
        m.emplace_back(i, i, 1.0 + 0.01 * i);
        k.emplace_back(i, i, tether);
        if (band_two && i + 2 < n) {
            k.emplace_back(i, i + 2, 0.0);
            k.emplace_back(i + 2, i, 0.0);
        }
    }
    for (int e = 0; e + 1 < n; ++e)
        for (auto [a, b, s] : {std::tuple{e, e, 1.0}, {e + 1, e + 1, 1.0}, {e, e + 1, -1.0}, {e + 1, e, -1.0}}) {
            k.emplace_back(a, b, s * spring);
            c.emplace_back(a, b, s * dashpot);
        }
    LinearMechanicalSystem sys;
    sys.mass.resize(n, n);
    sys.damping.resize(n, n);
    sys.stiffness.resize(n, n);
    sys.mass.setFromTriplets(m.begin(), m.end());
    sys.damping.setFromTriplets(c.begin(), c.end());
    sys.stiffness.setFromTriplets(k.begin(), k.end());
    sys.force = [tether](double t, Eigen::VectorXd& f) {  // support i at 0.1 sin(20 t - 0.3 i) m
        for (Eigen::Index i = 0; i < f.size(); ++i) f(i) = tether * 0.1 * std::sin(20.0 * t - 0.3 * static_cast<double>(i));
    };
    for (int i = 0; i < n; ++i) {
        if (i % 7 == 3) continue;
        const double s = 1.0 + 0.5 * std::sin(0.7 * i), d = (0.55 + 0.3 * std::cos(1.3 * i)) * s;
        PointContact contact{static_cast<std::size_t>(i), s, d};
        if (i % 5 == 1) {
            contact.slow_bound = 0.9 * s;
            contact.slow_speed = 0.05;
        }
        sys.contacts.push_back(contact);
    }
    return sys;
}

}  // namespace

TEST_CASE("Moreau-Jean: on a chain the piecewise-updated solve gives the general banded solve's iterates",
          "[moreau_jean]") {
    // The chain path (W tridiagonal: whole-chain passes, then updates from the switched contacts only as far as
    // values change) against the banded LDL^T path on the same system: the same modes at every step, the same
    // active-set iterations and factorisations, velocities and forces to round-off. With a budget of 4 iterations
    // the third changes the worst contact alone (Murty) and runs whole-chain passes: both paths take those steps
    // alike; the single pivots go on past the 4 (up to 2 per contact more), so neither stops where a budget of 4
    // alone stopped them (a fourth iteration still violated at 1.57 s) and both settle every step.
    const int n = 60;
    for (int budget : {200, 4}) {
        MoreauJeanOptions o;
        o.step = 1e-2;
        o.max_active_set_iterations = budget;
        MoreauJean chain(stick_slip_chain(n, false), o, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
        MoreauJean band(stick_slip_chain(n, true), o, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
        double worst_v = 0.0, worst_r = 0.0;
        bool same_modes = true, chain_stopped = false, band_stopped = false;
        double chain_stop = -1.0, band_stop = -2.0;
        for (int step = 0; step < 300 && !chain_stopped && !band_stopped; ++step) {
            try {
                chain.step();
            } catch (const SimulationError& e) {
                chain_stopped = true;
                chain_stop = e.time_reached();
            }
            try {
                band.step();
            } catch (const SimulationError& e) {
                band_stopped = true;
                band_stop = e.time_reached();
            }
            if (chain_stopped || band_stopped) break;
            same_modes = same_modes && chain.modes() == band.modes();
            worst_v = std::max(worst_v, (chain.velocities() - band.velocities()).lpNorm<Eigen::Infinity>());
            worst_r = std::max(worst_r, (chain.contact_forces() - band.contact_forces()).lpNorm<Eigen::Infinity>());
        }
        INFO("budget " << budget << ": t = " << chain.time() << ", max |dv| " << worst_v << ", max |dr| " << worst_r
                       << ", stopped at " << chain_stop << " / " << band_stop);
        CHECK(!chain_stopped);
        CHECK(!band_stopped);
        CHECK(same_modes);
        CHECK(chain.time() > 2.9);  // all 300 steps
        CHECK(worst_v < 1e-12);  // speeds ~0.5 m/s
        CHECK(worst_r < 1e-10);  // forces ~1 N
        const MoreauJean::Statistics& a = chain.statistics();
        const MoreauJean::Statistics& b = band.statistics();
        CHECK(a.contact_switches == b.contact_switches);
        CHECK(a.solves == b.solves);
        CHECK(a.factorisations == b.factorisations);
        // the run is the kind the chain path is for: many switches, steps that need several iterations
        CHECK(a.contact_switches > 1000);
        CHECK(a.solves > 2 * a.steps);
        CHECK(chain.events().size() == band.events().size());
    }
}

TEST_CASE("Moreau-Jean: the finiteness test and the masked select used on the chain", "[moreau_jean]") {
    const double inf = std::numeric_limits<double>::infinity(), big = std::numeric_limits<double>::max();
    const double tiny = std::numeric_limits<double>::denorm_min();
    std::vector<double> x{0.0, -0.0, 1.0, -big, big, tiny, -tiny, std::numeric_limits<double>::min()};
    CHECK(detail::all_finite(x.data(), x.size()));
    for (double bad : {inf, -inf, std::nan(""), -std::nan("")}) {
        for (std::size_t at : {std::size_t{0}, std::size_t{3}, x.size()}) {
            std::vector<double> y = x;
            y.insert(y.begin() + static_cast<std::ptrdiff_t>(at), bad);
            CHECK_FALSE(detail::all_finite(y.data(), y.size()));
        }
    }
    CHECK(std::signbit(detail::masked(-2.5, 0)) == false);  // +0.0, as the stuck dof's exact zero
    CHECK(detail::masked(-2.5, 0) == 0.0);
    CHECK(detail::masked(-2.5, ~std::uint64_t{0}) == -2.5);
}

TEST_CASE("ChainLDLT: the twisted factors and solve solve W x = r - an update gives a whole-chain solve's bits",
          "[moreau_jean]") {
    // A chain with W = diag + sub/superdiagonal (diagonally dominant: SPD), stuck dofs replaced by identity rows and
    // columns. After each random switch set: the updated x equals, bit for bit, the x of a fresh factor + solve, and
    // that x solves the reduced system (residual at round-off); so does a factor and forward pass rerun from the
    // first and last switched dofs only (the chain's many-switch iterations). Lengths around the twist's edge cases.
    std::uint64_t seed = 12345;
    const auto uniform = [&seed]() {
        seed = seed * 6364136223846793005u + 1442695040888963407u;
        return static_cast<double>(seed >> 11) / 9007199254740992.0;
    };
    for (std::size_t n : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{4}, std::size_t{7},
                          std::size_t{64}, std::size_t{301}}) {
        std::vector<double> wd(n), wl(n, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            wd[i] = 2.0 + uniform();
            if (i > 0) wl[i] = -(0.5 + 0.49 * uniform());  // |W(i, i-1)| < 1: dominant, slow decay
        }
        detail::ChainLDLT updated, fresh, partial;
        updated.assign(wd, wl, wl);
        partial.assign(wd, wl, wl);
        std::vector<char> stuck(n, 0);
        std::vector<double> r(n), x(n, 0.0), x_fresh(n), x_partial(n);
        for (std::size_t i = 0; i < n; ++i) r[i] = uniform() - 0.5;
        REQUIRE(updated.factor(stuck.data()));
        updated.forward(r.data());
        updated.backward(x.data());
        REQUIRE(partial.factor(stuck.data()));
        partial.forward(r.data());
        int mismatches = 0, partial_mismatches = 0;
        double worst_residual = 0.0;
        std::vector<detail::DofSpan> changed;
        for (int round = 0; round < 40; ++round) {
            std::vector<std::size_t> switched;
            for (std::size_t i = 0; i < n; ++i)
                if (uniform() < (round % 3 == 0 ? 0.3 : 0.03)) switched.push_back(i);
            for (std::size_t i : switched) {
                stuck[i] = !stuck[i];
                r[i] = stuck[i] ? 0.0 : uniform() - 0.5;
            }
            const std::vector<double> before = x;
            REQUIRE(updated.update(switched, stuck.data(), r.data(), x.data(), changed));
            fresh.assign(wd, wl, wl);
            REQUIRE(fresh.factor(stuck.data()));
            fresh.forward(r.data());
            fresh.backward(x_fresh.data());
            if (!switched.empty()) {
                REQUIRE(partial.factor(stuck.data(), switched.front(), switched.back()));
                partial.forward(r.data(), switched.front(), switched.back());
            }
            partial.backward(x_partial.data());
            for (std::size_t i = 0; i < n; ++i)
                if (std::memcmp(&x_partial[i], &x_fresh[i], sizeof(double)) != 0) ++partial_mismatches;
            std::size_t next = 0;
            for (std::size_t i = 0; i < n; ++i) {
                if (std::memcmp(&x[i], &x_fresh[i], sizeof(double)) != 0) ++mismatches;
                // outside the reported spans x did not change
                while (next < changed.size() && changed[next].hi < i) ++next;
                const bool inside = next < changed.size() && changed[next].lo <= i;
                if (!inside && std::memcmp(&x[i], &before[i], sizeof(double)) != 0) ++mismatches;
                const double wx = stuck[i] ? x[i]
                                           : (i > 0 && !stuck[i - 1] ? wl[i] * x[i - 1] : 0.0) + wd[i] * x[i] +
                                                 (i + 1 < n && !stuck[i + 1] ? wl[i + 1] * x[i + 1] : 0.0);
                worst_residual = std::max(worst_residual, std::abs(wx - r[i]));
            }
        }
        INFO("n = " << n);
        CHECK(mismatches == 0);
        CHECK(partial_mismatches == 0);
        CHECK(worst_residual < 1e-14);
    }
}

TEST_CASE("Moreau-Jean: the contact solver is swappable - projected Gauss-Seidel gives the active set's step where the "
          "law is monotone",
          "[moreau_jean]") {
    // Each step of the default (exact active set on the chain) is repeated from the same state by a stepper whose
    // contact problem is solved by ProjectedGaussSeidel. Monotone law (static == kinetic, no slow level): the step's
    // solution is unique, so the two agree to PGS's tolerance, modes included. Leine's switch model (static >
    // kinetic, the slow levels): PGS stops at a v, r satisfying the same conditions (stuck: v = 0, |r| <= static;
    // slipping: sigma v > 0, r = -level sigma), but it may be another of the step's solutions: counted, not required
    // (measured: 3 of 300 steps differ).
    const int n = 30, steps = 300;
    for (bool monotone : {true, false}) {
        LinearMechanicalSystem sys = stick_slip_chain(n, false);
        if (monotone)
            for (PointContact& c : sys.contacts) {
                c.static_bound = c.kinetic_bound;
                c.slow_speed = 0.0;
            }
        MoreauJeanOptions exact;
        exact.step = 1e-2;
        MoreauJeanOptions pgs = exact;
        pgs.contact_solver = ProjectedGaussSeidel{};
        MoreauJean reference(sys, exact, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
        double worst_v = 0.0, worst_r = 0.0, worst_stick_excess = -1.0;
        int differing = 0, mixed = 0, law_broken = 0;
        long sweeps = 0;
        for (int k = 0; k < steps; ++k) {
            MoreauJean repeat(sys, pgs, reference.positions(), reference.velocities(), reference.time());
            reference.step();
            repeat.step();
            sweeps += repeat.statistics().solves;
            const double dv = (repeat.velocities() - reference.velocities()).lpNorm<Eigen::Infinity>();
            const double dr = (repeat.contact_forces() - reference.contact_forces()).lpNorm<Eigen::Infinity>();
            worst_v = std::max(worst_v, dv);
            worst_r = std::max(worst_r, dr);
            if (dv > 1e-9 || repeat.modes() != reference.modes()) ++differing;
            const auto& modes = reference.modes();
            if (std::count(modes.begin(), modes.end(), ContactState::stick) > 0 &&
                std::count(modes.begin(), modes.end(), ContactState::stick) < static_cast<long>(modes.size()))
                ++mixed;
            for (std::size_t j = 0; j < sys.contacts.size(); ++j) {  // PGS's answer obeys the law
                const PointContact& c = sys.contacts[j];
                const Eigen::Index d = static_cast<Eigen::Index>(c.dof);
                const double v = repeat.velocities()(d), r = repeat.contact_forces()(d);
                if (repeat.modes()[j] == ContactState::stick) {
                    worst_stick_excess = std::max(worst_stick_excess, std::abs(r) - c.static_bound);
                    if (v != 0.0) ++law_broken;
                } else {
                    const double sigma = static_cast<double>(repeat.modes()[j]);
                    const bool level =
                        std::abs(r) == c.kinetic_bound || (c.slow_speed > 0.0 && std::abs(r) == c.slow_bound);
                    if (!(sigma * v > 0.0) || !level || !(sigma * r <= 0.0)) ++law_broken;
                }
            }
        }
        INFO((monotone ? "monotone" : "static > kinetic") << ": max |dv| " << worst_v << ", max |dr| " << worst_r
                                                           << ", steps differing " << differing << " of " << steps
                                                           << ", PGS sweeps " << sweeps);
        CHECK(law_broken == 0);
        CHECK(worst_stick_excess <= 1e-9);
        CHECK(mixed >= 10);           // steps with contacts stuck and slipping (measured 33 and 41 of 300)
        CHECK(sweeps > 3 * steps);    // PGS iterates (the chain couples the contacts)
        if (monotone) {
            CHECK(differing == 0);
            CHECK(worst_v < 1e-12);   // speeds ~0.5 m/s; PGS's tolerance 1e-14
            CHECK(worst_r < 1e-9);    // a stuck contact's force is W_dd v / h: ~100 x the speed's error
        }
    }
    // a solver is checked for what it leaves, and the explicit projection takes none
    MoreauJeanOptions o;
    o.step = 1e-2;
    o.contact_solver = [](const OneStepContactProblem&, OneStepContactSolution& s) {
        s.v.resize(1);
        return 1;
    };
    MoreauJean bad(stick_slip_chain(5, false), o, Eigen::VectorXd::Zero(5), Eigen::VectorXd::Zero(5));
    CHECK_THROWS_AS(bad.step(), SimulationError);
    o.treatment = ContactTreatment::projection;
    CHECK(rejected_parameter([&] { o.validate(); }) == "contact_solver");
}
