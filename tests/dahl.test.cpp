// Dahl friction (paper 000 eq 9) against closed forms: loading from rest, the periodic solution under the
// vibrating-surface kinematics (between reversals z is an exponential in the relative displacement), and
// convergence to the Coulomb friction-vector mean as k_t grows.
#include <cmath>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::relative_error;

namespace {

/// Composite 5-point Gauss-Legendre quadrature of f over [a, b].
template <class F>
double integrate(F f, double a, double b, int panels = 400) {
    static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                0.9061798459386640};
    static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                0.2369268850561891};
    const double h = (b - a) / panels;
    double sum = 0.0;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (p + 0.5) * h;
        for (int i = 0; i < 5; ++i) sum += w[i] * f(mid + 0.5 * h * x[i]);
    }
    return 0.5 * h * sum;
}

/// Closed-form periodic Dahl (alpha = 1) state under v_r = v_d - v_a cos(w t), v_d < v_a.
struct PeriodicDahl {
    HarmonicSlidingVelocity kin;
    double z_max, period, t_a, t_b, z_a, z_b;

    PeriodicDahl(double v_d, double v_a, double omega, double z_max_)
        : kin(v_d, v_a, omega), z_max(z_max_), period(2 * pi / omega) {
        t_a = std::acos(v_d / v_a) / omega;  // v_r turns positive
        t_b = period - t_a;                  // v_r turns negative
        const double e_plus = std::exp(-(kin.displacement(t_b) - kin.displacement(t_a)) / z_max);
        const double e_minus = std::exp(-(kin.displacement(t_b) - kin.displacement(t_a + period)) / z_max);
        z_a = z_max * (2 * e_minus - 1 - e_plus * e_minus) / (1 - e_plus * e_minus);
        z_b = z_max + (z_a - z_max) * e_plus;
    }
    double z(double t) const {
        t = std::fmod(t, period);
        if (t >= t_a && t <= t_b) return z_max + (z_a - z_max) * std::exp(-(kin.displacement(t) - kin.displacement(t_a)) / z_max);
        const double t_rev = t < t_a ? t_b - period : t_b;  // last reversal to negative slip
        return -z_max + (z_b + z_max) * std::exp(-(kin.displacement(t_rev) - kin.displacement(t)) / z_max);
    }
};

}  // namespace

TEST_CASE("Dahl from rest under monotone displacement: F = mu N (1 - exp(-k_t x / (mu N)))", "[dahl]") {
    const double mu = 0.41, normal = 90.0, k_t = 4e4, v = 2e-3, f_max = mu * normal;
    KinematicRig rig(Dahl(mu, k_t), ConstantSignal(v), ConstantSignal(normal));
    SolverOptions o;
    o.rtol = 1e-11;
    o.atol = 1e-14;
    for (int i = 0; i <= 40; ++i) o.output_times.push_back(i * 0.005);
    const Result r = simulate(rig, 0.2, o);
    for (std::size_t i = 1; i < r.rows(); ++i) {
        const double expected = f_max * (1 - std::exp(-k_t * v * r.t[i] / f_max));
        CHECK(relative_error(r.friction_force[i], expected) < 1e-6);
    }
}

TEST_CASE("Dahl exponent alpha shapes the loading curve as dz/dx = sgn(b)|b|^alpha, b = 1 - z/z_max", "[dahl]") {
    const double mu = 0.3, normal = 10.0, k_t = 1e4, v = 0.1, z_max = mu * normal / k_t;
    SECTION("alpha = 2: z/z_max = x / (z_max + x)") {
        KinematicRig rig(Dahl(mu, k_t, 2.0), ConstantSignal(v), ConstantSignal(normal));
        SolverOptions o;
        o.rtol = 1e-11;
        o.atol = 1e-15;
        o.output_times = {1e-3, 3e-3, 1e-2, 3e-2};
        const Result r = simulate(rig, 3e-2, o);
        for (std::size_t i = 0; i < r.rows(); ++i) {
            const double x = v * r.t[i];
            CHECK(relative_error(r.state(i, 0), z_max * x / (z_max + x)) < 1e-7);
        }
    }
    SECTION("alpha = 0.5: 1 - z/z_max = (1 - x / (2 z_max))^2 until x = 2 z_max") {
        KinematicRig rig(Dahl(mu, k_t, 0.5), ConstantSignal(v), ConstantSignal(normal));
        SolverOptions o;
        o.rtol = 1e-11;
        o.atol = 1e-15;
        o.output_times = {1e-3, 2e-3, 4e-3, 1e-2};  // x = z_max / 3 ... 10 z_max / 3
        const Result r = simulate(rig, 1e-2, o);
        for (std::size_t i = 0; i < r.rows(); ++i) {
            const double x = v * r.t[i], s = std::max(0.0, 1 - x / (2 * z_max));
            CHECK(relative_error(r.state(i, 0), z_max * (1 - s * s)) < 1e-6);
        }
        CHECK(relative_error(r.state(r.rows() - 1, 0), z_max) < 1e-6);
    }
}

TEST_CASE("Dahl (alpha = 1) under v_r = v_d - v_a cos(wt) matches the closed-form periodic solution",
          "[dahl][kinematic_rig]") {
    const double mu = 0.41, normal = 90.0, omega = 2 * pi * 17.0, v_a = 5e-3 * omega;
    const double period = 2 * pi / omega;
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    for (double k_t : {4e4, 2e3}) {  // the paper's order (z_max << u0) and a soft contact (z_max ~ u0)
        const double z_max = mu * normal / k_t;
        for (double ratio : {0.05, 0.2, 0.5, 0.8, 0.95, 1.5}) {
            const double v_d = ratio * v_a;
            INFO("k_t = " << k_t << ", v_d/v_a = " << ratio << ", method " << method_name(method));
            double z0 = z_max, mean_expected = mu * normal;  // v_d > v_a: z = z_max is the periodic solution
            std::vector<double> t_check;
            PeriodicDahl ref(std::min(v_d, 0.5 * v_a), v_a, omega, z_max);
            if (ratio < 1) {
                ref = PeriodicDahl(v_d, v_a, omega, z_max);
                z0 = ref.z(0.0);
                mean_expected = k_t * integrate([&](double t) { return ref.z(t); }, ref.t_a, ref.t_b) / period +
                                k_t * integrate([&](double t) { return ref.z(t); }, ref.t_b, ref.t_a + period) / period;
                for (int i = 1; i <= 19; ++i) t_check.push_back(2 * period + i * period / 20);
            }
            KinematicRig rig(Dahl(mu, k_t), HarmonicSlidingVelocity(v_d, v_a, omega), ConstantSignal(normal), {z0});
            SolverOptions o;
            o.method = method;
            o.rtol = 1e-11;
            o.atol = 1e-14;
            o.output_times = {0.0, period, 2 * period, 3 * period};
            o.output_times.insert(o.output_times.end() - 1, t_check.begin(), t_check.end());
            const Result r = simulate(rig, 3 * period, o);
            const std::size_t impulse = r.column("friction_impulse");
            const double mean = (r.state(r.rows() - 1, impulse) - r.state(0, impulse)) / (3 * period);
            CHECK(relative_error(mean, mean_expected) < 1e-6);
            for (std::size_t i = 3; i + 1 < r.rows(); ++i)
                CHECK(std::abs(r.state(i, 0) - ref.z(r.t[i])) < 1e-6 * z_max);
        }
    }
}

TEST_CASE("Dahl converges to the Coulomb friction-vector mean as k_t grows", "[dahl][coulomb]") {
    const double mu = 0.41, normal = 90.0, omega = 2 * pi * 17.0, v_a = 5e-3 * omega, ratio = 0.3;
    const double period = 2 * pi / omega, coulomb = 2 / pi * std::asin(ratio) * mu * normal;
    double last_error = 1.0;
    for (double k_t : {1e5, 1e6, 1e7, 1e8}) {
        KinematicRig rig(Dahl(mu, k_t), HarmonicSlidingVelocity(ratio * v_a, v_a, omega), ConstantSignal(normal));
        SolverOptions o;
        o.method = Method::cvode_bdf;  // stiff for large k_t
        o.rtol = 1e-10;
        o.atol = 1e-14;
        o.output_times = {period, 4 * period};
        const Result r = simulate(rig, 4 * period, o);
        const std::size_t impulse = r.column("friction_impulse");
        const double mean = (r.state(1, impulse) - r.state(0, impulse)) / (3 * period);
        const double error = relative_error(mean, coulomb);
        INFO("k_t = " << k_t << ": relative error " << error);
        CHECK(error < 0.5 * last_error);  // converges (the error scales like z_max / u0 ~ 1/k_t)
        last_error = error;
    }
    CHECK(last_error < 1e-4);
}

TEST_CASE("Dahl's kink at v_r = 0 is located as an event on the axial rig", "[dahl][axial_rig]") {
    // The 0.2 kg specimen is light enough to be dragged along by the contact (F/m = 185 m/s^2 against the
    // surface's 57 m/s^2), so v_r reverses more often than the kinematic twice per cycle. Both integrators
    // must find the same reversals.
    AxialRig<Dahl> rig(AxialRigParams{}, Dahl(0.41, 4e4));
    SolverOptions o;
    o.rtol = 1e-10;
    o.atol = 1e-13;
    o.output_times = {0.0};
    const Result rk = simulate(rig, 0.5, o);
    o.method = Method::cvode_bdf;
    const Result bdf = simulate(rig, 0.5, o);
    CHECK(rk.events.size() >= 17);
    REQUIRE(rk.events.size() == bdf.events.size());
    for (std::size_t i = 0; i < rk.events.size(); ++i) {
        CHECK(rk.events[i].name == "relative_velocity");
        CHECK(rk.events[i].mode_after == -rk.events[i].mode_before);
        CHECK(rk.events[i].time == Approx(bdf.events[i].time).margin(1e-7));
    }
}
