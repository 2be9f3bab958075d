// Prescribed signals of time for kinematic rigs: constants, the paper's harmonic relative velocity, and
// sampled data (piecewise linear). Plain callables `double(double t)`: a rig is templated on them, so the
// right-hand side makes no virtual call.
//
// Each also gives its time derivative, `double derivative(double t) const`: what a law of the acceleration
// (paper 001's eq 6, KinematicRig<HystereticFriction, ...>) needs. A constant's is 0, the harmonic one's is
// analytic, sampled data's is the slope of its piecewise-linear segment (one-sided at the knots: the segment
// ahead in forward time). Any other callable may give one the same way; signal_has_derivative_v tells whether
// it does.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../detail/validate.hpp"

namespace frictionsim {

struct ConstantSignal {
    double value;
    explicit ConstantSignal(double v) : value(detail::require_finite("ConstantSignal", "value", v)) {}
    double operator()(double /*t*/) const { return value; }
    double derivative(double /*t*/) const { return 0.0; }
};

/// v_r(t) = v_d - v_a cos(w t): a body sliding at v_d over a surface vibrating as u0 sin(w t), v_a = u0 w.
struct HarmonicSlidingVelocity {
    double sliding_velocity, velocity_amplitude, angular_frequency;
    HarmonicSlidingVelocity(double v_d, double v_a, double omega)
        : sliding_velocity(detail::require_finite("HarmonicSlidingVelocity", "sliding_velocity", v_d)),
          velocity_amplitude(detail::require_non_negative("HarmonicSlidingVelocity", "velocity_amplitude", v_a)),
          angular_frequency(detail::require_positive("HarmonicSlidingVelocity", "angular_frequency", omega)) {}
    double operator()(double t) const { return sliding_velocity - velocity_amplitude * std::cos(angular_frequency * t); }
    /// dv_r/dt = v_a w sin(w t).
    double derivative(double t) const {
        return velocity_amplitude * angular_frequency * std::sin(angular_frequency * t);
    }
    /// Relative displacement int_0^t v_r dt.
    double displacement(double t) const {
        return sliding_velocity * t - velocity_amplitude / angular_frequency * std::sin(angular_frequency * t);
    }
};

/// Piecewise-linear interpolation of samples (t_i, y_i), t strictly increasing. Evaluating outside
/// [t_0, t_last] throws std::out_of_range: a simulation must not run past its data.
class SampledSignal {
public:
    SampledSignal(std::vector<double> t, std::vector<double> y, std::string name = "signal")
        : t_(std::move(t)), y_(std::move(y)), name_(std::move(name)) {
        const char* name_c = name_.c_str();
        if (t_.size() != y_.size())
            detail::reject("SampledSignal", name_c, "as many values as times (values given)", double(y_.size()));
        if (t_.size() < 2) detail::reject("SampledSignal", name_c, "at least 2 samples (given)", double(t_.size()));
        for (std::size_t i = 0; i < t_.size(); ++i) {
            detail::require_finite("SampledSignal", "time", t_[i]);
            detail::require_finite("SampledSignal", name_c, y_[i]);
            if (i > 0 && !(t_[i] > t_[i - 1])) detail::reject("SampledSignal", "time", "strictly increasing", t_[i]);
        }
    }
    double operator()(double t) const {
        const std::size_t i = segment(t);
        const double w = (t - t_[i]) / (t_[i + 1] - t_[i]);
        return y_[i] + w * (y_[i + 1] - y_[i]);
    }
    /// The slope of the segment t lies on. At a knot t_i that is the segment ahead, [t_i, t_i+1] (the one-sided
    /// derivative in forward time, what a run from t_i on sees); at the last sample, the last segment's.
    double derivative(double t) const {
        const std::size_t i = segment(t);
        return (y_[i + 1] - y_[i]) / (t_[i + 1] - t_[i]);
    }
    double start_time() const { return t_.front(); }
    double end_time() const { return t_.back(); }

private:
    /// The index i of the segment [t_i, t_i+1] holding t (the one starting at t at a knot, the last one at the
    /// last sample); outside the samples, std::out_of_range.
    std::size_t segment(double t) const {
        if (!(t >= t_.front() && t <= t_.back())) {
            std::ostringstream msg;
            msg << "SampledSignal '" << name_ << "': t = " << t << " s is outside the samples [" << t_.front()
                << ", " << t_.back() << "] s";
            throw std::out_of_range(msg.str());
        }
        // binary search, no cached index: one rig may be shared by simulations on several threads
        return std::min<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin(), t_.size() - 1) - 1;
    }

    std::vector<double> t_, y_;
    std::string name_;
};

/// Does signal S give its time derivative, `double derivative(double t) const`? ConstantSignal,
/// HarmonicSlidingVelocity and SampledSignal do; a lambda or other callable only if it has such a member.
template <class S, class = void>
struct signal_has_derivative : std::false_type {};
template <class S>
struct signal_has_derivative<S, std::void_t<decltype(double{std::declval<const S&>().derivative(0.0)})>>
    : std::true_type {};
template <class S>
inline constexpr bool signal_has_derivative_v = signal_has_derivative<S>::value;

}  // namespace frictionsim
