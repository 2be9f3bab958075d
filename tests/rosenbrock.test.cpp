// RODAS4 (solve/rosenbrock.hpp) and its linear algebra (banded_lu.hpp, difference_jacobian.hpp): orders of
// convergence measured on fixed steps, stiff problems against published reference values (Robertson, DETEST D2;
// Van der Pol, Hairer's test set), a run-time sized banded system against its closed-form modal solution with
// analytic and difference Jacobians, and switches located through the hybrid event loop against closed forms.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "catch.hpp"
#include "frictionsim/friction/coulomb.hpp"
#include "frictionsim/friction/lugre.hpp"
#include "frictionsim/rigs/reference_setups.hpp"
#include "frictionsim/eigen/banded_lu.hpp"
#include "frictionsim/eigen/difference_jacobian.hpp"
#include "frictionsim/solve/dormand_prince.hpp"
#include "frictionsim/solve/hybrid_loop.hpp"
#include "frictionsim/eigen/rosenbrock.hpp"
#include "frictionsim/solve/simulate_with.hpp"
#include "frictionsim/sundials/cvode.hpp"

using namespace frictionsim;

namespace {

/// The HybridSystem members a smooth fixed-size test system does not care about (no switching functions).
template <std::size_t N>
struct Smooth {
    static constexpr std::size_t state_size = N;
    static constexpr std::size_t guard_count = 0;
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return ""; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    const char* mode_name(int) const { return "smooth"; }
    std::array<const char*, N> state_names() const {
        std::array<const char*, N> names{};
        names.fill("y");
        return names;
    }
    double friction_force(double, const double*, int) const { return 0.0; }
};

/// y' = y cos t, y(0) = 1: y = exp(sin t). Non-autonomous and with a time-varying Jacobian, so df/dt and J both
/// enter the stages.
struct ExpSin : Smooth<1> {
    void rhs(double t, const double* x, int, double* dxdt) const { dxdt[0] = x[0] * std::cos(t); }
    std::array<double, 1> initial_state() const { return {1.0}; }
    static double exact(double t) { return std::exp(std::sin(t)); }
};

/// A damped oscillator x'' + 2 zeta w x' + w^2 x = 0, x(0) = 1, x'(0) = 0, with its analytic Jacobian.
struct DampedOscillator : Smooth<2> {
    static constexpr bool autonomous = true;
    double w = 3.0, zeta = 0.1;
    void rhs(double, const double* x, int, double* dxdt) const {
        dxdt[0] = x[1];
        dxdt[1] = -w * w * x[0] - 2 * zeta * w * x[1];
    }
    void jacobian(double, const double*, int, double* J) const {  // column-major
        J[1] = -w * w;
        J[2] = 1.0;
        J[3] = -2 * zeta * w;
    }
    std::array<double, 2> initial_state() const { return {1.0, 0.0}; }
    double exact(double t) const {
        const double wd = w * std::sqrt(1 - zeta * zeta);
        return std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
    }
};

/// Robertson's chemical kinetics (Robertson 1966): the classic stiff test, with its analytic Jacobian.
struct Robertson : Smooth<3> {
    static constexpr bool autonomous = true;
    void rhs(double, const double* y, int, double* f) const {
        f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        f[2] = 3e7 * y[1] * y[1];
        f[1] = -f[0] - f[2];
    }
    void jacobian(double, const double* y, int, double* J) const {
        J[0] = -0.04;                               // d f0 / d y0
        J[1] = 0.04;                                // d f1 / d y0
        J[3] = 1e4 * y[2];                          // d f0 / d y1
        J[4] = -1e4 * y[2] - 6e7 * y[1];            // d f1 / d y1
        J[5] = 6e7 * y[1];                          // d f2 / d y1
        J[6] = 1e4 * y[1];                          // d f0 / d y2
        J[7] = -1e4 * y[1];                         // d f1 / d y2
    }
    std::array<double, 3> initial_state() const { return {1.0, 0.0, 0.0}; }
};
/// The same equations without a Jacobian: the integrator differences them.
struct RobertsonNoJacobian : Smooth<3> {
    void rhs(double t, const double* y, int m, double* f) const { Robertson{}.rhs(t, y, m, f); }
    std::array<double, 3> initial_state() const { return {1.0, 0.0, 0.0}; }
};

/// Van der Pol in Hairer's scaled form (Hairer & Wanner II, sec. IV.10 "VDPOL"): y1' = y2,
/// y2' = ((1 - y1^2) y2 - y1) / eps with eps = 1e-6, i.e. mu = 1000 in the time t / mu.
struct VanDerPol : Smooth<2> {
    static constexpr bool autonomous = true;
    double eps = 1e-6;
    void rhs(double, const double* y, int, double* f) const {
        f[0] = y[1];
        f[1] = ((1 - y[0] * y[0]) * y[1] - y[0]) / eps;
    }
    void jacobian(double, const double* y, int, double* J) const {
        J[1] = (-2 * y[0] * y[1] - 1) / eps;
        J[2] = 1.0;
        J[3] = (1 - y[0] * y[0]) / eps;
    }
    std::array<double, 2> initial_state() const { return {2.0, 0.0}; }
};

/// Fixed steps of h: the error estimate never rejects (huge atol) and max_step caps the growth.
SolverOptions fixed_steps(double h) {
    SolverOptions o;
    o.rtol = 0.1;
    o.atol = 1e10;
    o.initial_step = h;
    o.max_step = h;
    return o;
}

double log2_ratio(double coarse, double fine) { return std::log2(coarse / fine); }

/// The largest error of the first state at the ends of the integrator's steps, against a closed form.
template <class Exact>
struct StepErrors {
    Exact exact;
    double largest = 0.0;
    template <class Mode>
    void step(double t, const double* x, const Mode&) {
        largest = std::max(largest, std::abs(x[0] - exact(t)));
    }
    template <class... A>
    void output(A&&...) {}
    template <class... A>
    void event(A&&...) {}
};
template <class Exact>
StepErrors(Exact) -> StepErrors<Exact>;

}  // namespace

TEST_CASE("RODAS4 on fixed steps converges at order 4, its dense output at order 3",
          "[rosenbrock]") {
    SECTION("largest global error over [0, 2] of y' = y cos t (non-autonomous): ratio 2^4 per halving") {
        const ExpSin sys;
        std::vector<double> errors;
        for (double h : {0.1, 0.05, 0.025, 0.0125}) {
            SolverOptions o = fixed_steps(h);
            o.record_steps = true;
            StepErrors worst{[](double t) { return ExpSin::exact(t); }};
            const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 2.0, o, worst);
            CHECK(out.stats.steps == std::lround(2.0 / h));
            errors.push_back(worst.largest);
        }
        for (std::size_t i = 1; i < errors.size(); ++i) {
            INFO("error " << errors[i] << ", previous " << errors[i - 1]);
            CHECK(log2_ratio(errors[i - 1], errors[i]) == Approx(4.0).margin(0.3));
        }
    }
    SECTION("global error of a damped oscillator (analytic Jacobian, autonomous): ratio 2^4 per halving") {
        const DampedOscillator sys;
        std::vector<double> errors;
        for (double h : {0.1, 0.05, 0.025, 0.0125}) {
            const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 3.0, fixed_steps(h));
            errors.push_back(std::abs(out.state[0] - sys.exact(3.0)));
        }
        for (std::size_t i = 1; i < errors.size(); ++i) {
            INFO("error " << errors[i] << ", previous " << errors[i - 1]);
            CHECK(log2_ratio(errors[i - 1], errors[i]) == Approx(4.0).margin(0.3));
        }
    }
    SECTION("one step from the exact value: local error h^5 at the end, h^4 inside (dense output of order 3)") {
        const ExpSin sys;
        const double t0 = 0.4;
        std::vector<double> end_errors, mid_errors;
        for (double h : {0.1, 0.05, 0.025, 0.0125}) {
            const SolverOptions o = fixed_steps(h);
            Rodas4<ExpSin> integrator(sys, o);
            const double x0 = ExpSin::exact(t0);
            integrator.restart(t0, &x0, 0);
            const StepResult s = integrator.step(t0 + h);
            REQUIRE(s.t == t0 + h);
            end_errors.push_back(std::abs(integrator.state()[0] - ExpSin::exact(t0 + h)));
            double mid = 0.0;
            integrator.interpolate(t0 + 0.5 * h, &mid);
            mid_errors.push_back(std::abs(mid - ExpSin::exact(t0 + 0.5 * h)));
            double at_ends[2];
            integrator.interpolate(t0, &at_ends[0]);
            integrator.interpolate(t0 + h, &at_ends[1]);
            CHECK(at_ends[0] == x0);  // the interpolant passes through both ends of the step
            CHECK(at_ends[1] == Approx(integrator.state()[0]).epsilon(1e-15));
        }
        for (std::size_t i = 1; i < end_errors.size(); ++i) {
            INFO("end " << end_errors[i] << " (previous " << end_errors[i - 1] << "), middle " << mid_errors[i]
                        << " (previous " << mid_errors[i - 1] << ")");
            CHECK(log2_ratio(end_errors[i - 1], end_errors[i]) == Approx(5.0).margin(0.35));
            CHECK(log2_ratio(mid_errors[i - 1], mid_errors[i]) == Approx(4.0).margin(0.35));
        }
    }
}

TEST_CASE("RODAS4 error control: the global error falls in proportion to rtol", "[rosenbrock]") {
    const DampedOscillator sys;
    double previous = 0.0;
    for (double rtol : {1e-6, 1e-8, 1e-10}) {
        SolverOptions o;
        o.rtol = rtol;
        o.atol = rtol;
        const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 5.0, o);
        const double error = std::abs(out.state[0] - sys.exact(5.0));
        INFO("rtol " << rtol << ": error " << error << ", steps " << out.stats.steps);
        CHECK(error < 20 * rtol);
        if (previous > 0.0) CHECK(error < previous / 20);  // two decades of rtol: well over one of error
        previous = error;
    }
}

TEST_CASE("RODAS4 with the banded LU takes the dense LU's steps", "[rosenbrock][banded_lu]") {
    // the same iteration matrices factored two ways: the same steps, results equal to rounding
    const Robertson sys;
    SolverOptions o;
    o.rtol = 1e-8;
    o.atol = 1e-14;
    const auto dense = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 40.0, o);
    o.linear_solver = LinearSolver::band;
    const auto band = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 40.0, o);
    CHECK(band.stats.steps == dense.stats.steps);
    CHECK(band.stats.error_test_failures == dense.stats.error_test_failures);
    for (std::size_t i = 0; i < 3; ++i) CHECK(band.state[i] == Approx(dense.state[i]).epsilon(1e-11));
}

TEST_CASE("RODAS4 on Robertson's kinetics at t = 40 matches DETEST D2 and conserves mass", "[rosenbrock]") {
    // Enright, Hull & Lindberg (1975), problem D2, reference solution at t = 40 (their y2, y3 scaled back by
    // 1e-4 and 1e-2). RODAS4 keeps the linear invariant y1 + y2 + y3 exactly, up to rounding: every stage is a
    // combination of f and J k, and 1^T f = 0, 1^T J = 0.
    const std::array<double, 3> reference{0.7158270687193941, 9.185534764557338e-06, 0.2841637457458413};
    SolverOptions o;
    o.rtol = 1e-8;
    o.atol_per_state = {1e-14, 1e-18, 1e-14};
    const auto check = [&](const auto& sys, const char* what) {
        const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 40.0, o);
        INFO(what << ": y = " << out.state[0] << ", " << out.state[1] << ", " << out.state[2] << "; steps "
                  << out.stats.steps << ", Jacobians " << out.stats.jacobian_evaluations);
        for (std::size_t i = 0; i < 3; ++i) CHECK(out.state[i] == Approx(reference[i]).epsilon(2e-8));
        CHECK(out.state[0] + out.state[1] + out.state[2] == Approx(1.0).epsilon(1e-14));
        return out.stats;
    };
    const SolverStats analytic = check(Robertson{}, "analytic Jacobian");
    const SolverStats differenced = check(RobertsonNoJacobian{}, "difference Jacobian");
    // the difference Jacobian costs n = 3 right-hand sides (and df/dt one more) per Jacobian, nothing else
    CHECK(differenced.rhs_evaluations <= 6 * differenced.steps + 4 * differenced.jacobian_evaluations + 2);
    CHECK(analytic.rhs_evaluations <= 6 * analytic.steps + 2);
    // stiff: Dormand-Prince's steps are bounded by stability (eigenvalue ~ -1e4 early on), not accuracy
    const auto explicit_run = integrate_hybrid<DormandPrince>(Robertson{}, Robertson{}.initial_state(), 0.0, 40.0, o);
    INFO("Dormand-Prince: " << explicit_run.stats.steps << " steps; RODAS4: " << analytic.steps);
    CHECK(10 * analytic.steps < explicit_run.stats.steps);
}

TEST_CASE("RODAS4 on Van der Pol, mu = 1000, matches Hairer's reference values", "[rosenbrock]") {
    // Hairer & Wanner's test set, VDPOL with eps = 1e-6, y(0) = (2, 0): y(2) from their reference solution.
    const VanDerPol sys;
    SolverOptions o;
    o.rtol = 1e-8;
    o.atol = 1e-8;
    const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 2.0, o);
    INFO("y(2) = " << out.state[0] << ", " << out.state[1] << "; steps " << out.stats.steps << ", rejected "
                   << out.stats.error_test_failures);
    CHECK(out.state[0] == Approx(0.1706167732170483e+01).epsilon(2e-8));
    CHECK(out.state[1] == Approx(-0.8928097010247975).epsilon(2e-8));
    // the relaxation phases have eigenvalues ~ -1e6 (1 / eps): an explicit method needs ~1e6 steps
    CHECK(out.stats.steps < 20000);
}

// ---------------------------------------------------------------------------------------------------------------
// Banded linear algebra

TEST_CASE("BandedLU solves banded systems that need pivoting, as a dense LU does", "[rosenbrock][banded_lu]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (Bandwidths b : {Bandwidths{1, 1}, Bandwidths{3, 3}, Bandwidths{2, 0}, Bandwidths{0, 2}, Bandwidths{4, 1}}) {
        const std::size_t n = 40;
        BandMatrix a(n, b);
        Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
        // two-sided bands: a small diagonal, so that rows are interchanged; one-sided: a dominant one (a triangular
        // matrix with a small diagonal has a condition number growing geometrically with n)
        const bool one_sided = b.lower == 0 || b.upper == 0;
        for (std::size_t j = 0; j < n; ++j)
            for (std::size_t i = 0; i < n; ++i)
                if (a.contains(i, j))
                    dense(i, j) = a(i, j) = i != j ? u(rng) : one_sided ? -3.0 + u(rng) : 0.01 * u(rng);
        const double alpha = 0.3, beta = -1.5;
        BandedLU lu(n, b);
        REQUIRE(lu.factorize(alpha, beta, a));
        Eigen::VectorXd rhs = Eigen::VectorXd::Random(n), x = rhs;
        lu.solve(x.data());
        const Eigen::MatrixXd m = alpha * Eigen::MatrixXd::Identity(n, n) + beta * dense;
        const Eigen::PartialPivLU<Eigen::MatrixXd> dense_lu(m);
        const Eigen::VectorXd expected = dense_lu.solve(rhs);
        // backward stable: a residual of rounding size; forward error within the condition number's amplification
        const double condition = 1.0 / dense_lu.rcond();
        INFO("lower " << b.lower << ", upper " << b.upper << ", condition " << condition);
        REQUIRE(condition < 1e8);
        CHECK((m * x - rhs).norm() <= 1e-14 * m.norm() * x.norm());
        CHECK((x - expected).norm() <= 1e-14 * condition * expected.norm());
    }
    SECTION("a singular matrix is reported, not divided by") {
        BandMatrix a(5, {1, 1});
        BandedLU lu;
        CHECK_FALSE(lu.factorize(0.0, 1.0, a));  // the zero matrix
        a(2, 2) = std::numeric_limits<double>::quiet_NaN();
        CHECK_FALSE(lu.factorize(1.0, 1.0, a));
    }
}

namespace {

/// Heat conduction u_t = D u_xx on (0, 1), u = 0 at both ends, on N interior nodes (run-time sized). Its
/// semi-discrete solution is a sum of modes sin(k pi x_i) exp(-lambda_k t) with
/// lambda_k = 4 D / dx^2 sin^2(k pi / (2 (N + 1))) exactly: the closed form the integrator must reproduce.
/// Stiff: lambda_N / lambda_1 ~ 4 (N + 1)^2 / pi^2 = 16500 at N = 200.
struct HeatEquation {
    std::size_t nodes = 200;
    double diffusivity = 1.0;

    static constexpr bool autonomous = true;
    double dx() const { return 1.0 / static_cast<double>(nodes + 1); }
    std::size_t state_size() const { return nodes; }
    std::size_t guard_count() const { return 0; }
    void rhs(double, const double* u, int, double* dudt) const {
        const double c = diffusivity / (dx() * dx());
        for (std::size_t i = 0; i < nodes; ++i) {
            const double left = i > 0 ? u[i - 1] : 0.0, right = i + 1 < nodes ? u[i + 1] : 0.0;
            dudt[i] = c * (left - 2 * u[i] + right);
        }
    }
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return ""; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    const char* mode_name(int) const { return "conducting"; }
    std::vector<std::string> state_names() const { return std::vector<std::string>(nodes, "u"); }
    double friction_force(double, const double*, int) const { return 0.0; }

    double mode_shape(std::size_t k, std::size_t i) const {
        return std::sin(static_cast<double>(k) * M_PI * static_cast<double>(i + 1) * dx());
    }
    double decay_rate(std::size_t k) const {
        const double s = std::sin(static_cast<double>(k) * M_PI / (2.0 * static_cast<double>(nodes + 1)));
        return 4 * diffusivity / (dx() * dx()) * s * s;
    }
    /// Modes 1 and 40: one slow, one decaying 1600 times faster.
    double exact(double t, std::size_t i) const {
        return mode_shape(1, i) * std::exp(-decay_rate(1) * t) +
               0.5 * mode_shape(40, i) * std::exp(-decay_rate(40) * t);
    }
    std::vector<double> initial_state() const {
        std::vector<double> u(nodes);
        for (std::size_t i = 0; i < nodes; ++i) u[i] = exact(0.0, i);
        return u;
    }
};

/// ... with a banded analytic Jacobian.
struct BandedHeat : HeatEquation {
    Bandwidths jacobian_bandwidths() const { return {1, 1}; }
    template <class Add>
    void jacobian_entries(double, const double*, int, Add&& add) const {
        const double c = diffusivity / (dx() * dx());
        for (std::size_t i = 0; i < nodes; ++i) {
            add(i, i, -2 * c);
            if (i > 0) add(i, i - 1, c);
            if (i + 1 < nodes) add(i, i + 1, c);
        }
    }
};

/// ... declaring the band but leaving the Jacobian to differences.
struct DifferencedHeat : HeatEquation {
    Bandwidths jacobian_bandwidths() const { return {1, 1}; }
};

template <class Heat>
SolverStats check_heat(const Heat& sys, LinearSolver solver, const char* what) {
    SolverOptions o;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.linear_solver = solver;
    const double t_end = 0.05;  // mode 1 decays to exp(-0.49), mode 40 to exp(-780)
    const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, t_end, o);
    double worst = 0.0;
    for (std::size_t i = 0; i < sys.nodes; ++i) worst = std::max(worst, std::abs(out.state[i] - sys.exact(t_end, i)));
    INFO(what << ": max error " << worst << ", steps " << out.stats.steps << ", rhs " << out.stats.rhs_evaluations
              << ", Jacobians " << out.stats.jacobian_evaluations);
    CHECK(worst < 1e-7);
    CHECK(out.stats.steps < 200);  // stiffness ratio 1.6e4: an explicit method would need ~ lambda_N t_end = 4e3
    return out.stats;
}

}  // namespace

TEST_CASE("RODAS4 on a run-time sized banded system (heat equation, N = 200) reproduces the modal solution",
          "[rosenbrock]") {
    check_heat(BandedHeat{}, LinearSolver::automatic, "analytic banded Jacobian, banded LU");
    check_heat(BandedHeat{}, LinearSolver::dense, "analytic Jacobian entries, dense LU");
    const SolverStats differenced = check_heat(DifferencedHeat{}, LinearSolver::automatic, "banded differences");
    // Curtis-Powell-Reid: a tridiagonal Jacobian costs 3 right-hand sides, not 200. Per step: the value at the
    // step's start and 5 stages; per Jacobian 3 more.
    CHECK(differenced.rhs_evaluations <= 6 * differenced.steps + 3 * differenced.jacobian_evaluations + 2);
    const SolverStats dense = check_heat(HeatEquation{}, LinearSolver::automatic, "dense differences");
    CHECK(dense.rhs_evaluations >= 200 * dense.jacobian_evaluations);
}

TEST_CASE("banded difference Jacobian: one right-hand side per column group, equal to the analytic band",
          "[rosenbrock][banded_lu]") {
    BandedHeat sys;
    sys.nodes = 50;
    std::vector<double> u = sys.initial_state(), f0(sys.nodes), work(sys.nodes), saved(sys.nodes);
    for (std::size_t i = 0; i < sys.nodes; ++i) u[i] += 0.1 * std::cos(3.0 * static_cast<double>(i));
    sys.rhs(0.0, u.data(), 0, f0.data());
    int calls = 0;
    BandMatrix differenced(sys.nodes, {1, 1}), analytic(sys.nodes, {1, 1});
    const std::vector<double> before = u;
    difference_jacobian_banded(
        [&](double t, const double* x, double* f) {
            ++calls;
            sys.rhs(t, x, 0, f);
        },
        0.0, u.data(), f0.data(), differenced, work.data(), saved.data());
    CHECK(calls == 3);
    CHECK(u == before);  // the state is restored exactly
    sys.jacobian_entries(0.0, u.data(), 0, [&](std::size_t i, std::size_t j, double v) { analytic(i, j) += v; });
    const double c = sys.diffusivity / (sys.dx() * sys.dx());
    for (std::size_t j = 0; j < sys.nodes; ++j)
        for (std::size_t i = j > 0 ? j - 1 : 0; i <= std::min(sys.nodes - 1, j + 1); ++i)
            CHECK(differenced(i, j) == Approx(analytic(i, j)).margin(1e-6 * c));
}

// ---------------------------------------------------------------------------------------------------------------
// Switches through the hybrid event loop

namespace {

/// Mode 0: x' = -x from x = 1, until x falls to 1/2 (t1 = ln 2). Mode 1: x' = 1 - x, until x rises to 3/4
/// (x = 1 - e^-(t - t1) / 2: t2 = 2 ln 2). Mode 2: x' = 0.
struct TwoSwitches {
    static constexpr std::size_t state_size = 1;
    static constexpr std::size_t guard_count = 1;
    void rhs(double, const double* x, int mode, double* dxdt) const {
        dxdt[0] = mode == 0 ? -x[0] : mode == 1 ? 1.0 - x[0] : 0.0;
    }
    void guards(double, const double* x, int mode, double* g) const {
        g[0] = mode == 0 ? x[0] - 0.5 : mode == 1 ? x[0] - 0.75 : 1.0;
    }
    int guard_direction(std::size_t, int mode) const { return mode == 0 ? -1 : +1; }
    const char* guard_name(std::size_t, int) const { return "level"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode + 1; }
    const char* mode_name(int) const { return "phase"; }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::array<double, 1> initial_state() const { return {1.0}; }
};

struct EventTimes {
    std::vector<double> t;
    std::vector<int> guard;
    template <class... A>
    void output(A&&...) {}
    template <class... A>
    void step(A&&...) {}
    template <class X>
    void event(const Event& e, double, const X*) {
        t.push_back(e.time);
        guard.push_back(e.switching_function);
    }
};

/// Run-time sized, one contact per block: block c decays as x_c' = -x_c from 1 and sticks (x_c' = 0) when it
/// falls to its level (c + 1) / (blocks + 1), at t_c = ln((blocks + 1) / (c + 1)). One ContactModes entry each.
struct DecayingBlocks {
    using mode_type = ContactModes;
    std::size_t blocks = 6;
    std::size_t state_size() const { return blocks; }
    std::size_t guard_count() const { return blocks; }
    double level(std::size_t c) const { return (c + 1.0) / (blocks + 1.0); }
    void rhs(double, const double* x, const ContactModes& m, double* dxdt) const {
        for (std::size_t c = 0; c < blocks; ++c) dxdt[c] = m[c] == 0 ? -x[c] : 0.0;
    }
    Bandwidths jacobian_bandwidths() const { return {0, 0}; }
    void guards(double, const double* x, const ContactModes& m, double* g) const {
        for (std::size_t c = 0; c < blocks; ++c) g[c] = m[c] == 0 ? x[c] - level(c) : 1.0;
    }
    int guard_direction(std::size_t, const ContactModes&) const { return -1; }
    const char* guard_name(std::size_t, const ContactModes&) const { return "level"; }
    ContactModes initial_mode(double, const double*) const { return ContactModes(blocks, 0); }
    ContactModes switch_mode(double, double*, const ContactModes& m, const int* fired) const {
        ContactModes next = m;
        for (std::size_t c = 0; c < blocks; ++c)
            if (fired[c] != 0) next[c] = 1;
        return next;
    }
    const char* mode_name(int m) const { return m == 0 ? "decaying" : "stuck"; }
    int mode_code(const ContactModes& m) const { return static_cast<int>(m.count(1)); }
    int guard_mode(std::size_t c, const ContactModes& m) const { return m[c]; }
    std::vector<std::string> state_names() const { return std::vector<std::string>(blocks, "x"); }
    double friction_force(double, const double*, const ContactModes&) const { return 0.0; }
    std::vector<double> initial_state() const { return std::vector<double>(blocks, 1.0); }
};

}  // namespace

TEST_CASE("RODAS4 in the hybrid loop locates switches at their closed-form times", "[rosenbrock]") {
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    SECTION("fixed size: two switches of one guard, falling then rising") {
        EventTimes events;
        const TwoSwitches sys;
        const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 3.0, o, events);
        REQUIRE(events.t.size() == 2);
        CHECK(std::abs(events.t[0] - std::log(2.0)) < 1e-10);
        CHECK(std::abs(events.t[1] - 2 * std::log(2.0)) < 1e-10);
        CHECK(out.mode == 2);
        CHECK(out.state[0] == Approx(0.75).epsilon(1e-9));
    }
    SECTION("run-time size with per-contact modes: one event per block, each at ln((N + 1) / (c + 1))") {
        EventTimes events;
        const DecayingBlocks sys;
        const auto out = integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 2.5, o, events);
        REQUIRE(events.t.size() == sys.blocks);
        for (std::size_t k = 0; k < events.t.size(); ++k) {
            const std::size_t c = static_cast<std::size_t>(events.guard[k]);
            INFO("block " << c);
            CHECK(c == sys.blocks - 1 - k);  // the highest level is reached first
            CHECK(std::abs(events.t[k] - std::log((sys.blocks + 1.0) / (c + 1.0))) < 1e-10);
            CHECK(out.state[c] == Approx(sys.level(c)).epsilon(1e-9));
        }
        CHECK(out.mode.count(1) == sys.blocks);
    }
}

TEST_CASE("RODAS4 on the Coulomb spring-block: stick-slip cycle as the closed form and as Dormand-Prince",
          "[rosenbrock]") {
    // The stick-slip oscillator of coulomb.test.cpp: stick 2 (x_s - x_d) / v, slip (2 / lambda)(pi - atan(...)).
    // Guards sit at zero after every restart (v_r = 0 entering stick): the masking rule is exercised each cycle.
    const double m = 0.5, k = 200.0, v = 0.05, g = 9.81, mu_s = 0.6, mu_k = 0.4;
    const AxialRig<Coulomb> rig(spring_block_params(m, k, v, g), Coulomb(mu_k, mu_s));
    const double lambda = std::sqrt(k / m), x_s = mu_s * m * g / k, x_d = mu_k * m * g / k;
    const double stick_time = 2 * (x_s - x_d) / v;
    const double slip_time = 2 / lambda * (M_PI - std::atan(lambda * (x_s - x_d) / v));
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.output_times = {0.0};
    const Result r = simulate_with<Rodas4>(rig, 6 * (stick_time + slip_time), o);
    const Result reference = simulate_with<DormandPrince>(rig, 6 * (stick_time + slip_time), o);
    std::vector<double> stick_starts, slip_starts;
    for (const Event& e : r.events) (e.mode_after == stick ? stick_starts : slip_starts).push_back(e.time);
    REQUIRE(slip_starts.size() >= 4);
    REQUIRE(stick_starts.size() >= 4);
    CHECK(slip_starts[0] == Approx(x_s / v).epsilon(1e-9));
    for (std::size_t i = 1; i + 1 < slip_starts.size(); ++i) {
        CHECK(stick_starts[i] - slip_starts[i] == Approx(slip_time).epsilon(1e-7));
        CHECK(slip_starts[i + 1] - stick_starts[i] == Approx(stick_time).epsilon(1e-7));
    }
    REQUIRE(r.events.size() == reference.events.size());
    for (std::size_t i = 0; i < r.events.size(); ++i) {
        CHECK(r.events[i].switching_function == reference.events[i].switching_function);
        CHECK(r.events[i].time == Approx(reference.events[i].time).epsilon(1e-8));
    }
}

TEST_CASE("RODAS4 on a stiff rig (LuGre bristles) agrees with CVODE BDF", "[rosenbrock]") {
    // Canudas de Wit et al. (1995)'s stick-slip example: sigma0 = 1e5 N/m on a 1 kg block makes the bristle
    // state stiff. The rig's analytic Jacobian drives RODAS4; CVODE's BDF is the independent implementation.
    const AxialRig<LuGre> rig(canudas_de_wit_1995_params(), LuGre(canudas_de_wit_1995_lugre()));
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    const auto rosenbrock = integrate_hybrid<Rodas4>(rig, rig.initial_state(), 0.0, 10.0, o);
    o.method = Method::cvode_bdf;
    const auto bdf = integrate_hybrid<Cvode>(rig, rig.initial_state(), 0.0, 10.0, o);
    const auto names = rig.state_names();
    for (std::size_t i = 0; i < rig.state_size; ++i) {
        INFO(names[i] << ": RODAS4 " << rosenbrock.state[i] << ", BDF " << bdf.state[i]);
        CHECK(rosenbrock.state[i] == Approx(bdf.state[i]).epsilon(1e-6).margin(1e-9));
    }
    o.method = Method::dormand_prince;
    const auto explicit_run = integrate_hybrid<DormandPrince>(rig, rig.initial_state(), 0.0, 10.0, o);
    INFO("steps: RODAS4 " << rosenbrock.stats.steps << ", BDF " << bdf.stats.steps << ", Dormand-Prince "
                          << explicit_run.stats.steps);
    CHECK(4 * rosenbrock.stats.steps < explicit_run.stats.steps);  // stability, not accuracy, limits the explicit one
}

// ---------------------------------------------------------------------------------------------------------------
// Failures

namespace {
/// y' = y^2 from y(0) = 1: y = 1 / (1 - t) blows up at t = 1.
struct BlowUp : Smooth<1> {
    void rhs(double, const double* y, int, double* f) const { f[0] = y[0] * y[0]; }
    std::array<double, 1> initial_state() const { return {1.0}; }
};
/// A Jacobian that is not a number: every iteration matrix is unusable.
struct NanJacobian : Smooth<1> {
    void rhs(double, const double* y, int, double* f) const { f[0] = -y[0]; }
    void jacobian(double, const double*, int, double* J) const { J[0] = std::numeric_limits<double>::quiet_NaN(); }
    std::array<double, 1> initial_state() const { return {1.0}; }
};
}  // namespace

TEST_CASE("RODAS4 failures say why and when", "[rosenbrock]") {
    SolverOptions o;
    SECTION("a solution that blows up at t = 1 stops just before it") {
        const BlowUp sys;
        try {
            integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 2.0, o);
            FAIL("no SimulationError");
        } catch (const SimulationError& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find("Rodas4") != std::string::npos);
            CHECK(std::abs(e.time_reached() - 1.0) < 1e-6);
        }
    }
    SECTION("a singular or non-finite iteration matrix") {
        const NanJacobian sys;
        try {
            integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 1.0, o);
            FAIL("no SimulationError");
        } catch (const SimulationError& e) {
            CHECK(std::string(e.what()).find("singular") != std::string::npos);
            CHECK(e.time_reached() == 0.0);
        }
    }
    SECTION("max_steps") {
        o.max_steps = 10;
        const VanDerPol sys;
        CHECK_THROWS_WITH(integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 2.0, o),
                          Catch::Contains("max_steps exceeded"));
    }
    SECTION("a Jacobian entry outside the declared band names itself") {
        struct WrongBand : BandedHeat {
            Bandwidths jacobian_bandwidths() const { return {0, 0}; }  // the entries are tridiagonal
        };
        const WrongBand sys;
        try {
            integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 0.01, o);
            FAIL("no SimulationError");
        } catch (const SimulationError& e) {
            CHECK_THAT(e.what(), Catch::Contains("outside jacobian_bandwidths()"));
            CHECK(e.time_reached() == 0.0);
        }
    }
    SECTION("a linear solver it does not have") {
        o.linear_solver = LinearSolver::sparse;
        const DampedOscillator sys;
        try {
            integrate_hybrid<Rodas4>(sys, sys.initial_state(), 0.0, 1.0, o);
            FAIL("no InvalidParameter");
        } catch (const InvalidParameter& e) {
            CHECK(e.parameter() == "linear_solver");
        }
    }
}
