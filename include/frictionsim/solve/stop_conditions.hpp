// A user's stop conditions, evaluated in C++ as the run goes (SciPy solve_ivp's `events`, with its direction and
// terminal flags): a state crossing a level, located on the integrator's dense output, or a switch into a named
// mode (e.g. the first stick of the disc). Each crossing is logged in Result::stop_events; a terminal one ends
// the run there with Result::status = 1.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../detail/illinois.hpp"
#include "../detail/validate.hpp"
#include "hybrid_system.hpp"
#include "system_size.hpp"

namespace frictionsim {

struct StopCondition {
    std::string state;  ///< a state's name: its crossing of `level` counts; empty when `mode` is given
    double level = 0.0;
    int direction = 0;  ///< -1 falling through the level, +1 rising, 0 both
    std::string mode;   ///< or: a switch into a mode of this name counts (Event::mode_after_name), e.g. "stick"
    bool terminal = true;
    std::string name;   ///< the label in the log; empty: "<state> = <level>" or "mode <mode>"
};

namespace detail {

/// The run's stop conditions resolved against the system (state names to columns), and the crossings of the
/// state conditions located over each step.
class StopWatch {
public:
    struct Crossing {
        double time = 0.0;
        std::size_t condition = 0;
        int direction = 0;
    };

    template <class System>
    StopWatch(const System& sys, const std::vector<StopCondition>& conditions) : conditions_(conditions) {
        constexpr const char* who = "SolverOptions";
        const auto names = sys.state_names();
        for (StopCondition& c : conditions_) {
            if (c.state.empty() == c.mode.empty())
                reject(who, "stop_conditions", "each naming either a state (with a level) or a mode, not both", 0.0);
            if (c.direction < -1 || c.direction > 1)
                reject(who, "stop_conditions.direction", "-1 (falling), +1 (rising) or 0 (both)", c.direction);
            require_finite(who, "stop_conditions.level", c.level);
            std::size_t column = npos;
            if (!c.state.empty()) {
                for (std::size_t i = 0; i < static_cast<std::size_t>(names.size()); ++i)
                    if (c.state == names[i]) column = i;
                if (column == npos)
                    throw InvalidParameter("stop_conditions.state", "SolverOptions: stop_conditions.state must name "
                                                                    "one of the system's states (got '" + c.state + "')");
                if (c.name.empty()) c.name = c.state + " = " + number(c.level);
            } else if (c.name.empty()) {
                c.name = "mode " + c.mode;
            }
            column_.push_back(column);
            if (column != npos) state_conditions_ = true;
        }
        previous_.assign(conditions_.size(), 0.0);
    }

    bool any() const { return !conditions_.empty(); }
    const StopCondition& condition(std::size_t k) const { return conditions_[k]; }

    /// The conditions' values g_k = x[column] - level at a point the run restarts from (start, after a switch).
    void reset(const double* x) {
        for (std::size_t k = 0; k < conditions_.size(); ++k)
            if (column_[k] != npos) previous_[k] = x[column_[k]] - conditions_[k].level;
    }

    /// After a step to `integrator.time()`: the crossings of the state conditions within it, earliest first (each
    /// condition's first crossing in each of four sub-intervals of the step, located by Illinois false position on
    /// the dense output to a few ulps of t), and the values at the step's end as the next reference.
    template <class Integrator>
    const std::vector<Crossing>& after_step(const Integrator& integrator, std::vector<double>& scratch) {
        found_.clear();
        if (!state_conditions_) return found_;
        const double t0 = integrator.previous_time(), t1 = integrator.time();
        constexpr int kPieces = 4;
        for (std::size_t k = 0; k < conditions_.size(); ++k) {
            if (column_[k] == npos) continue;
            const auto value = [&](double t) {
                if (t >= t1) return integrator.state()[column_[k]] - conditions_[k].level;
                integrator.interpolate(t, scratch.data());
                return scratch[column_[k]] - conditions_[k].level;
            };
            double a = t0, ga = previous_[k];
            for (int p = 1; p <= kPieces; ++p) {
                const double b = p == kPieces ? t1 : t0 + (t1 - t0) * p / kPieces, gb = value(b);
                const int dir = crossing(ga, gb, conditions_[k].direction);
                if (dir != 0) found_.push_back({locate(value, a, ga, b, gb), k, dir});
                a = b;
                ga = gb;
            }
            previous_[k] = ga;
        }
        std::sort(found_.begin(), found_.end(), [](const Crossing& l, const Crossing& r) { return l.time < r.time; });
        return found_;
    }

    /// Does a switch into `mode_name` meet a mode condition? Returns its index, or npos.
    std::size_t mode_condition(const std::string& mode_name, std::size_t from = 0) const {
        for (std::size_t k = from; k < conditions_.size(); ++k)
            if (!conditions_[k].mode.empty() && conditions_[k].mode == mode_name) return k;
        return npos;
    }

    static constexpr std::size_t npos = static_cast<std::size_t>(-1);

    /// A level as the log writes it ("5", "0.25"): trailing zeros dropped.
    static std::string number(double v) {
        std::string s = std::to_string(v);
        while (s.size() > 1 && s.back() == '0') s.pop_back();
        if (!s.empty() && s.back() == '.') s.pop_back();
        return s;
    }

private:
    /// The root of g on [a, b] (g(a), g(b) of opposite signs or g(b) = 0) by Illinois false position.
    template <class G>
    static double locate(const G& g, double a, double ga, double b, double gb) {
        if (gb == 0.0) return b;
        IllinoisBracket r{a, ga, b, gb};
        for (int it = 0; it < 100 && r.b - r.a > 4.0 * 2.220446049250313e-16 * std::max(1.0, std::abs(r.b)); ++it) {
            const double c = r.next();
            const double gc = g(c);
            if (gc == 0.0) return c;
            r.move(c, gc, (gc > 0.0) == (r.gb > 0.0));
        }
        return r.b;  // the side past the crossing: the condition holds there
    }

    std::vector<StopCondition> conditions_;
    std::vector<std::size_t> column_;
    std::vector<double> previous_;
    std::vector<Crossing> found_;
    bool state_conditions_ = false;
};

}  // namespace detail
}  // namespace frictionsim
