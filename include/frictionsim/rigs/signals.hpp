// Prescribed signals of time for kinematic rigs: constants, the paper's harmonic relative velocity, and
// sampled data (piecewise linear). Plain callables `double(double t)`: a rig is templated on them, so the
// right-hand side makes no virtual call.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../detail/validate.hpp"

namespace frictionsim {

struct ConstantSignal {
    double value;
    explicit ConstantSignal(double v) : value(detail::require_finite("ConstantSignal", "value", v)) {}
    double operator()(double /*t*/) const { return value; }
};

/// v_r(t) = v_d - v_a cos(w t): a body sliding at v_d over a surface vibrating as u0 sin(w t), v_a = u0 w.
struct HarmonicSlidingVelocity {
    double sliding_velocity, velocity_amplitude, angular_frequency;
    HarmonicSlidingVelocity(double v_d, double v_a, double omega)
        : sliding_velocity(detail::require_finite("HarmonicSlidingVelocity", "sliding_velocity", v_d)),
          velocity_amplitude(detail::require_non_negative("HarmonicSlidingVelocity", "velocity_amplitude", v_a)),
          angular_frequency(detail::require_positive("HarmonicSlidingVelocity", "angular_frequency", omega)) {}
    double operator()(double t) const { return sliding_velocity - velocity_amplitude * std::cos(angular_frequency * t); }
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
        if (!(t >= t_.front() && t <= t_.back())) {
            std::ostringstream msg;
            msg << "SampledSignal '" << name_ << "': t = " << t << " s is outside the samples [" << t_.front()
                << ", " << t_.back() << "] s";
            throw std::out_of_range(msg.str());
        }
        // binary search, no cached index: one rig may be shared by simulations on several threads
        const std::size_t i =
            std::min<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin(), t_.size() - 1) - 1;
        const double w = (t - t_[i]) / (t_[i + 1] - t_[i]);
        return y_[i] + w * (y_[i + 1] - y_[i]);
    }
    double start_time() const { return t_.front(); }
    double end_time() const { return t_.back(); }

private:
    std::vector<double> t_, y_;
    std::string name_;
};

}  // namespace frictionsim
