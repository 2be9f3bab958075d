// The hybrid event loop (solve/hybrid_loop.hpp) driving the HybridSystem concept (solve/hybrid_system.hpp)
// into a Recorder (solve/recorder.hpp) on small systems whose switching behaviour is known exactly, on every integrator:
// a guard that sits at zero right after a switch and heads into its triggering side, simultaneous switches,
// a Zeno-prone bouncing ball that trips the chattering bound, and failures mid-run that keep the results; and
// the one-step integrators' step driver (solve/adaptive_stepper.hpp) carrying a third scheme.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <frictionsim/simulate.hpp>
#include <frictionsim/solve/adaptive_stepper.hpp>

#include "catch.hpp"
#include "support.hpp"

using namespace frictionsim;
using frictionsim::test::options_for;

namespace {

/// Shared boilerplate of the toy systems: names, and a mode that is its own name.
struct ToyBase {
    const char* mode_name(int) const { return "toy"; }
    double friction_force(double, const double*, int) const { return 0.0; }
};

/// x' = +1 in mode 0 until x = 1; then mode 1 (x' = -1) whose guard x - 1 is zero at the switch and falls
/// at once: it must fire immediately (mode 2, x' = 0), not be masked as "starting at zero".
struct ZeroGuardAfterSwitch : ToyBase {
    static constexpr std::size_t state_size = 1, guard_count = 1;
    void rhs(double, const double*, int mode, double* dx) const { dx[0] = mode == 0 ? 1.0 : mode == 1 ? -1.0 : 0.0; }
    void guards(double, const double* x, int mode, double* g) const { g[0] = mode == 0 ? 1.0 - x[0] : mode == 1 ? x[0] - 1.0 : 1.0; }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t, int mode) const { return mode == 0 ? "top" : "turn"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double* x, int mode, const int*) const {
        if (mode == 0) x[0] = 1.0;  // project onto the guard surface exactly
        return mode + 1;
    }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    std::array<double, 1> initial_state() const { return {0.0}; }
};

/// x' = 1, y' = 2: guards 1 - x and 2 - y cross together at t = 1. The mode records which fired (bits).
struct Simultaneous : ToyBase {
    static constexpr std::size_t state_size = 2, guard_count = 2;
    void rhs(double, const double*, int, double* dx) const { dx[0] = 1.0; dx[1] = 2.0; }
    void guards(double, const double* x, int mode, double* g) const {
        g[0] = mode == 0 ? 1.0 - x[0] : 1.0;
        g[1] = mode == 0 ? 2.0 - x[1] : 1.0;
    }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t i, int) const { return i == 0 ? "x_reaches_1" : "y_reaches_2"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int, const int* fired) const { return (fired[0] ? 1 : 0) | (fired[1] ? 2 : 0); }
    std::array<const char*, 2> state_names() const { return {"x", "y"}; }
    std::array<double, 2> initial_state() const { return {0.0, 0.0}; }
};

/// Bouncing ball, restitution e: impacts accumulate at a finite (Zeno) time.
struct BouncingBall : ToyBase {
    static constexpr std::size_t state_size = 2, guard_count = 1;
    double g = 9.81, restitution = 0.5;
    void rhs(double, const double* x, int, double* dx) const { dx[0] = x[1]; dx[1] = -g; }
    void guards(double, const double* x, int, double* gv) const { gv[0] = x[0]; }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t, int) const { return "floor_contact"; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double* x, int mode, const int*) const {
        x[0] = 0.0;
        x[1] = -restitution * x[1];
        return mode;
    }
    std::array<const char*, 2> state_names() const { return {"height", "velocity"}; }
    std::array<double, 2> initial_state() const { return {1.0, 0.0}; }
};

/// x' = 1 until the right-hand side fails at t > 0.5: by throwing, or by returning NaN.
struct FailsMidRun : ToyBase {
    static constexpr std::size_t state_size = 1, guard_count = 0;
    bool nan = false;
    void rhs(double t, const double*, int, double* dx) const {
        if (t > 0.5) {
            if (!nan) throw std::runtime_error("boom: model undefined beyond t = 0.5");
            dx[0] = std::nan("");
            return;
        }
        dx[0] = 1.0;
    }
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return ""; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    std::array<const char*, 1> state_names() const { return {"x"}; }
    std::array<double, 1> initial_state() const { return {0.0}; }
};

// x'' = -x, x(0) = 1: x = cos t. A smooth system with no guard.
struct ToyOscillator : ToyBase {
    static constexpr std::size_t state_size = 2, guard_count = 0;
    void rhs(double, const double* x, int, double* dx) const { dx[0] = x[1]; dx[1] = -x[0]; }
    void guards(double, const double*, int, double*) const {}
    int guard_direction(std::size_t, int) const { return 0; }
    const char* guard_name(std::size_t, int) const { return ""; }
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int m, const int*) const { return m; }
    std::array<const char*, 2> state_names() const { return {"x", "v"}; }
    std::array<double, 2> initial_state() const { return {1.0, 0.0}; }
};

/// Heun-Euler 2(1) on the step driver that Dormand-Prince and RODAS4 share: the step loop, the restart and the
/// root location come from AdaptiveStepper, this is only the tableau (Euler predictor, Heun's trapezoid), the
/// error h/2 (k2 - k1), the controller h (0.9 / err)^(1/2) and the cubic Hermite dense output (FSAL slope at the
/// step's end). Both the scheme and its dense output are exact on a parabola: a falling ball's impacts come out at
/// their closed-form times to the bracketing tolerance.
template <class System>
class HeunEuler : public detail::AdaptiveStepper<HeunEuler<System>, System> {
    using Base = detail::AdaptiveStepper<HeunEuler<System>, System>;
    friend Base;

public:
    using State = StateArray<System>;
    HeunEuler(const System& system, const SolverOptions& options) : Base(system, options) {
        for (State* v : {&y_, &y1_, &ytmp_, &k1_, &k2_, &y0_, &f0_, &yh_, &fh_}) *v = make_state_array(system);
    }
    void interpolate(double t, double* x) const { interpolate_states(t, 0, y_.size(), x); }

private:
    static constexpr const char* kName = "HeunEuler";
    static constexpr const char* kUnderflow = "step size underflow";
    void f(double t, const State& x, State& dxdt) {
        this->sys_.rhs(t, x.data(), this->mode_, dxdt.data());
        ++this->stats_.rhs_evaluations;
    }
    double* y() { return y_.data(); }
    const double* y() const { return y_.data(); }
    double* scratch() { return ytmp_.data(); }
    void load(const double* x) { std::copy(x, x + y_.size(), y_.begin()); }
    void slope() { f(this->t_, y_, k1_); }
    void reset_controller() {}
    void cut_to_root() { slope(); }
    double initial_step(double t_stop) {
        return detail::starting_step(y_.size(), 1, this->opt_, this->t_, t_stop, y_.data(), k1_.data(), ytmp_.data(),
                                     k2_.data(), [this](double t, const double* x, double* dxdt) {
                                         this->sys_.rhs(t, x, this->mode_, dxdt);
                                     });
    }
    double attempt(double h) {
        for (std::size_t i = 0; i < y_.size(); ++i) ytmp_[i] = y_[i] + h * k1_[i];
        f(this->t_ + h, ytmp_, k2_);
        double err = 0.0;
        for (std::size_t i = 0; i < y_.size(); ++i) {
            y1_[i] = y_[i] + 0.5 * h * (k1_[i] + k2_[i]);
            const double r = (y1_[i] - ytmp_[i]) / detail::error_scale(this->opt_, i, y_[i], y1_[i]);
            err += r * r;
        }
        err = std::sqrt(err / static_cast<double>(y_.size()));
        return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
    }
    double rejected_step(double h, double err) const { return h * std::max(0.2, 0.9 / std::sqrt(err)); }
    double next_step(double h, double err) const { return h * std::min(5.0, 0.9 / std::sqrt(std::max(err, 1e-8))); }
    void fit_dense_output(double h) {
        y0_ = y_;
        f0_ = k1_;
        yh_ = y1_;
        f(this->t_ + h, y1_, fh_);
    }
    void advance() {
        y_ = y1_;
        k1_ = fh_;
    }
    void euler_step(double h) {
        y0_ = y_;
        f0_ = fh_ = k1_;
        for (std::size_t i = 0; i < y_.size(); ++i) y_[i] += h * k1_[i];
        yh_ = y_;
    }
    void interpolate_states(double t, std::size_t first, std::size_t last, double* x) const {
        const double h = this->h_dense_, s = (t - this->t_prev_) / h, s2 = s * s, s3 = s2 * s;
        for (std::size_t i = first; i < last; ++i)
            x[i] = (2 * s3 - 3 * s2 + 1) * y0_[i] + (s3 - 2 * s2 + s) * h * f0_[i] + (3 * s2 - 2 * s3) * yh_[i] +
                   (s3 - s2) * h * fh_[i];
    }

    State y_{}, y1_{}, ytmp_{}, k1_{}, k2_{};
    State y0_{}, f0_{}, yh_{}, fh_{};  ///< the cubic Hermite dense output's ends
};

}  // namespace

TEST_CASE("a guard that is zero right after a switch and heads into its triggering side fires at once", "[solver]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams);
    INFO(method_name(method));
    SolverOptions o = options_for(method);
    o.output_times = {0.5, 1.5, 2.0};
    const Result r = simulate(ZeroGuardAfterSwitch{}, 2.0, o);
    REQUIRE(r.events.size() == 2);
    CHECK(r.events[0].time == Approx(1.0).margin(1e-12));
    CHECK(r.events[0].name == "top");
    CHECK(r.events[1].time == r.events[0].time);  // same instant: the cascade is resolved at the switch
    CHECK(r.events[1].name == "turn");
    CHECK(r.events[1].mode_after == 2);
    CHECK(r.state(1, 0) == Approx(1.0).margin(1e-12));  // mode 2 holds x = 1 (x' = 0), never runs back down
    CHECK(r.state(2, 0) == Approx(1.0).margin(1e-12));
}

TEST_CASE("a guard that leaves zero to its quiet side and returns within the first step still fires", "[solver]") {
    // v_r = t (t - 1e-3) starts at zero heading negative (mode slip_negative, guard -v_r > 0), and turns positive
    // at t = 1e-3. A first step of 5e-3 spans the whole excursion: the return crossing must still be located.
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams);
    INFO(method_name(method));
    auto v_r = [](double t) { return t * (t - 1e-3); };
    const KinematicRig<Coulomb, decltype(v_r)> rig(Coulomb(0.5), v_r, ConstantSignal(10.0));
    SolverOptions o = options_for(method);
    o.initial_step = 5e-3;
    const Result r = simulate(rig, 0.02, o);
    REQUIRE(r.events.size() == 1);
    CHECK(r.events[0].time == Approx(1e-3).margin(1e-12));
    CHECK(r.events[0].mode_before == slip_negative);
    CHECK(r.events[0].mode_after == slip_positive);
    CHECK(r.mode.back() == slip_positive);
    // impulse: -5 N over [0, 1e-3], +5 N after
    CHECK(r.state(r.rows() - 1, KinematicRig<Coulomb, decltype(v_r)>::friction_impulse) ==
          Approx(-5.0 * 1e-3 + 5.0 * (0.02 - 1e-3)).margin(1e-10));
}

TEST_CASE("a guard that crosses zero and comes back within one step is located", "[solver]") {
    // v_r = 1 - 1.001 exp(-((t - 0.51)/0.01)^2) dips just below zero for 0.63 ms: two reversals inside steps of
    // about 1 ms, with v_r > 0 at both ends of the step. Dormand-Prince samples its dense output inside every
    // step; CVODE gets no such help (its root finding sees step ends only), so only it is held to this here.
    auto v_r = [](double t) { return 1.0 - 1.001 * std::exp(-std::pow((t - 0.51) / 0.01, 2)); };
    const KinematicRig<Coulomb, decltype(v_r)> rig(Coulomb(0.5), v_r, ConstantSignal(10.0));
    SolverOptions o = options_for(Method::dormand_prince);
    o.max_step = 0.02;
    const Result r = simulate(rig, 1.0, o);
    const double half_width = 0.01 * std::sqrt(std::log(1.001));
    REQUIRE(r.events.size() == 2);
    CHECK(r.events[0].time == Approx(0.51 - half_width).margin(1e-10));
    CHECK(r.events[0].mode_after == slip_negative);
    CHECK(r.events[1].time == Approx(0.51 + half_width).margin(1e-10));
    CHECK(r.events[1].mode_after == slip_positive);
    CHECK(r.state(r.rows() - 1, KinematicRig<Coulomb, decltype(v_r)>::friction_impulse) ==
          Approx(5.0 * (1.0 - 4.0 * half_width)).margin(1e-9));
}

TEST_CASE("a reversal within one step is located when the guards come with the stages (rhs_guards)", "[solver]") {
    // The same 0.63 ms dip, on a system that hands Dormand-Prince its guards with every stage (as the axial rig
    // does): the stage values and the one dense point between stages 3 and 4 must see what the uniform scan saw.
    auto v_r = [](double t) { return 1.0 - 1.001 * std::exp(-std::pow((t - 0.51) / 0.01, 2)); };
    using Base = KinematicRig<Coulomb, decltype(v_r)>;
    struct WithStageGuards : Base {
        using Base::Base;
        void rhs_guards(double t, const double* x, int mode, double* dxdt, double* g) const {
            rhs(t, x, mode, dxdt);
            if (g != nullptr) guards(t, x, mode, g);
        }
    };
    static_assert(detail::has_rhs_guards<WithStageGuards>::value);
    for (double centre : {0.51, 0.5103, 0.5107, 0.5111, 0.5115}) {  // the dip at different places in its step
        auto shifted = [centre](double t) { return 1.0 - 1.001 * std::exp(-std::pow((t - centre) / 0.01, 2)); };
        using ShiftedBase = KinematicRig<Coulomb, decltype(shifted)>;
        struct Shifted : ShiftedBase {
            using ShiftedBase::ShiftedBase;
            void rhs_guards(double t, const double* x, int mode, double* dxdt, double* g) const {
                this->rhs(t, x, mode, dxdt);
                if (g != nullptr) this->guards(t, x, mode, g);
            }
        };
        INFO("dip centred at t = " << centre);
        const Shifted rig(Coulomb(0.5), shifted, ConstantSignal(10.0));
        SolverOptions o = options_for(Method::dormand_prince);
        o.max_step = 0.02;
        const Result r = simulate(rig, 1.0, o);
        const double half_width = 0.01 * std::sqrt(std::log(1.001));
        REQUIRE(r.events.size() == 2);
        CHECK(r.events[0].time == Approx(centre - half_width).margin(1e-10));
        CHECK(r.events[1].time == Approx(centre + half_width).margin(1e-10));
    }
    (void)sizeof(WithStageGuards);
}

TEST_CASE("simultaneous switches are handled in one resolution", "[solver]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    SolverOptions o = options_for(method);
    o.output_times = {2.0};
    const Result r = simulate(Simultaneous{}, 2.0, o);
    REQUIRE(r.events.size() == 2);  // one log entry per switching function, same time, same resolution
    CHECK(r.events[0].time == Approx(1.0).margin(1e-12));
    CHECK(r.events[1].time == r.events[0].time);
    CHECK(r.events[0].name == "x_reaches_1");
    CHECK(r.events[1].name == "y_reaches_2");
    CHECK(r.events[0].mode_after == 3);  // both guards seen by switch_mode at once
    CHECK(r.events[1].mode_after == 3);
}

TEST_CASE("a Zeno-prone bouncing ball trips the chattering bound with a clear error and kept results",
          "[solver]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf);
    INFO(method_name(method));
    const BouncingBall ball;
    // impacts at t1 = sqrt(2h/g), then intervals shrink by e: Zeno time t1 (1 + 2e/(1-e))
    const double t1 = std::sqrt(2.0 / ball.g), zeno = t1 * (1 + 2 * ball.restitution / (1 - ball.restitution));
    SolverOptions o = options_for(method);
    o.max_events_in_window = 10;
    o.event_window = 1e-3;
    for (int i = 0; i < 100; ++i) o.output_times.push_back(i * 0.02);
    try {
        simulate(ball, 1.99, o);
        FAIL("expected a ChatteringError");
    } catch (const ChatteringError& e) {
        CHECK(e.switching_function() == "floor_contact");
        CHECK(std::string(e.what()).find("floor_contact") != std::string::npos);
        CHECK(e.time_reached() < zeno);
        CHECK(e.time_reached() > zeno - 2e-3);
        REQUIRE(e.partial());
        const Result& partial = *e.partial();
        CHECK_FALSE(partial.completed);
        CHECK(partial.events.size() >= 11);
        CHECK(partial.events[0].time == Approx(t1).epsilon(1e-9));
        REQUIRE(partial.rows() > 0);
        CHECK(partial.t.back() <= e.time_reached());
        CHECK(partial.t.back() > e.time_reached() - 0.02 - 1e-12);  // every output up to the stop is kept
    }
}

TEST_CASE("a failure mid-run reports the time reached and keeps the results up to it", "[solver]") {
    const auto method = GENERATE(Method::dormand_prince, Method::cvode_bdf, Method::cvode_adams);
    const bool nan = GENERATE(false, true);
    INFO(method_name(method) << (nan ? " NaN" : " throw"));
    FailsMidRun sys;
    sys.nan = nan;
    SolverOptions o = options_for(method);
    o.max_step = 0.05;  // the time reached is the last accepted step: keep steps short enough to get close
    for (int i = 0; i <= 10; ++i) o.output_times.push_back(0.1 * i);
    try {
        simulate(sys, 1.0, o);
        FAIL("expected a SimulationError");
    } catch (const SimulationError& e) {
        CHECK(e.time_reached() <= 0.5 + 1e-9);
        CHECK(e.time_reached() > 0.45);
        if (!nan) CHECK(std::string(e.what()).find("boom") != std::string::npos);
        REQUIRE(e.partial());
        const Result& partial = *e.partial();
        CHECK_FALSE(partial.completed);
        CHECK(partial.t_reached == e.time_reached());
        REQUIRE(partial.rows() >= 5);
        for (std::size_t i = 0; i < partial.rows(); ++i) {
            CHECK(partial.t[i] <= e.time_reached());
            CHECK(partial.state(i, 0) == Approx(partial.t[i]).margin(1e-9));
        }
    }
}

TEST_CASE("Dormand-Prince: global error falls like rtol and dense output is as accurate as the steps", "[solver]") {
    double previous = 1.0;
    for (double rtol : {1e-6, 1e-8, 1e-10}) {
        SolverOptions o;
        o.rtol = rtol;
        o.atol = rtol * 1e-2;
        for (int i = 0; i <= 200; ++i) o.output_times.push_back(0.05 * i);  // mostly between steps
        const Result r = simulate(ToyOscillator{}, 10.0, o);
        double worst = 0.0;
        for (std::size_t i = 0; i < r.rows(); ++i) worst = std::max(worst, std::abs(r.state(i, 0) - std::cos(r.t[i])));
        INFO("rtol " << rtol << ": max error " << worst << ", steps " << r.stats.steps);
        CHECK(worst < 100 * rtol);
        CHECK(worst < 0.2 * previous);
        previous = worst;
    }
}

TEST_CASE("the step driver written once carries a third scheme: Heun-Euler's ball bounces at the closed-form times",
          "[solver][adaptive_stepper]") {
    // Dropped from 1 m at rest, restitution e: impact k at sqrt(2/g) (1 + 2 (e + ... + e^(k-1))), Zeno at
    // sqrt(2/g) (1 + 2e / (1 - e)) = 1.35 s; before 1.2 s three impacts.
    const BouncingBall ball;
    SolverOptions o;
    o.rtol = 1e-6;
    o.atol = 1e-9;
    for (int i = 0; i <= 120; ++i) o.output_times.push_back(0.01 * i);
    const Result r = simulate_with<HeunEuler>(ball, 1.2, o);
    const double t1 = std::sqrt(2.0 / ball.g);
    REQUIRE(r.events.size() == 3);
    double t_impact = t1, flight = 2.0 * ball.restitution * t1;
    for (const Event& e : r.events) {
        CHECK(e.time == Approx(t_impact).margin(1e-12));
        t_impact += flight;
        flight *= ball.restitution;
    }
    // between impacts the dense output is the parabola itself: after impact k it leaves at e^k sqrt(2 g)
    for (std::size_t i = 0; i < r.rows(); ++i) {
        const double t = r.t[i];
        std::size_t k = 0;
        while (k < r.events.size() && r.events[k].time <= t) ++k;
        const double t0 = k == 0 ? 0.0 : r.events[k - 1].time, dt = t - t0;
        const double v0 = k == 0 ? 0.0 : std::pow(ball.restitution, static_cast<double>(k)) * std::sqrt(2.0 * ball.g);
        INFO("t = " << t);
        CHECK(r.state(i, 0) == Approx((k == 0 ? 1.0 : 0.0) + v0 * dt - 0.5 * ball.g * dt * dt).margin(1e-9));
    }
    // the driver's bookkeeping: a restart at the start and at each impact
    CHECK(r.stats.restarts == 4);
    CHECK(r.stats.steps > 3);
}
