// Torque and drag with axial vibration tools (issue 14, items 3 and 4): the soft string (soft_string.hpp) whose
// friction is reduced, element by element, where the tools' vibration reverses the sliding.
//  1. the soft string without the tools gives each element's side force q_n and so the wall's Coulomb friction
//     mu q_n per metre; the operation gives the sliding speed V and the surface speed omega r;
//  2. each tool's travelling wave (axial_wave.hpp) gives the vibration velocity amplitude along the string, or, with
//     source = VibrationSource::dynamic, the dynamic axial string model run to a periodic steady state
//     (oscillator_response.hpp: resonances, partial sticking; seconds instead of microseconds, so it is taken once,
//     under the plain run's side forces, and held while step 4 iterates); several tools add as independent
//     (unsynchronised) vibrations, a^2 = sum a_i^2 (their mean squares add);
//  3. each element's friction is scaled by its cycle mean (vibration_friction.hpp), user's choice of model:
//       friction_vector  axial: < v / |q| > / (V / |q_0|), circumferential: < w / |q| > / (w / |q_0|)
//                        ((2 / pi) asin(V / a) without rotation), or
//       table5           paper 000's measured cycle-mean coefficient for one lubricant, on both components;
//  4. the soft string is run again with those factors; its side forces (they change with the tension in curves)
//     feed step 1 again until the factors change by less than coupling_tolerance.
// The zone of influence is where the friction against the operation's motion (axial when the string moves along the
// hole, else circumferential) is reduced by more than zone_threshold. Sliding at a given hook load, the weight on bit
// follows from the hook load by a bracketed secant (Illinois) search: the placement objective (item 4).
// Buckling lock-up is not modelled: the weight on bit is what the soft string transfers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "../detail/illinois.hpp"
#include "../detail/validate.hpp"
#include "../error.hpp"
#include "../friction/power_law.hpp"
#include "../parameters.hpp"
#include "axial_wave.hpp"
#include "oscillator_response.hpp"
#include "../string/sections.hpp"
#include "soft_string.hpp"
#include "../survey.hpp"
#include "vibration_friction.hpp"

namespace frictionsim {

/// How the vibration reduces the friction: the friction vector's cycle mean (Coulomb friction against the sliding
/// velocity), or paper 000's Table 5 power law for one lubricant.
enum class VibrationFrictionModel { friction_vector, table5 };

inline const char* vibration_friction_model_name(VibrationFrictionModel m) {
    return m == VibrationFrictionModel::friction_vector ? "friction_vector" : "table5";
}

/// The estimate's settings: the scalars in a table, the model and lubricant beside it.
struct OscillatorDragParams {
    double bit_reflection = 0.0;       ///< R: +1 a free bit, -1 a held one, 0 no reflection
    double zone_threshold = 0.05;      ///< reduction of the friction that marks the zone of influence
    double coupling_tolerance = 1e-9;  ///< largest change of a friction factor between passes at convergence
    VibrationFrictionModel model = VibrationFrictionModel::friction_vector;
    Lubricant lubricant = Lubricant::wbm;  ///< Table 5's row (model table5)
    VibrationSource source = VibrationSource::wave;  ///< the travelling-wave estimate or the dynamic model
    OscillatorResponseParams dynamic;                 ///< the dynamic model's settings (source dynamic)

    static constexpr std::size_t max_coupling_passes = 50;
    static constexpr std::array<Field<OscillatorDragParams>, 3> fields();
};

inline constexpr std::array<Field<OscillatorDragParams>, 3> OscillatorDragParams::fields() {
    using P = OscillatorDragParams;
    return {{
        {"bit_reflection", "R", "-", Rule::interval(-1.0, 1.0).because("+1 a free bit, -1 a held one"),
         &P::bit_reflection, "Velocity reflection coefficient of the bit for the tools' waves."},
        {"zone_threshold", "r_zone", "-", Rule::interval(0.0, 1.0, true, true), &P::zone_threshold,
         "Friction reduction above which an element is in the zone of influence."},
        {"coupling_tolerance", "tol", "-", Rule::positive(), &P::coupling_tolerance,
         "Largest change of a friction factor between two passes at convergence."},
    }};
}

/// One operation with and without the tools.
struct OscillatorDragResult {
    TorqueDragResult plain;     ///< without the tools
    TorqueDragResult vibrated;  ///< with them
    /// per element, m/s: all tools together (source dynamic: the amplitude the friction sees, see
    /// OscillatorResponse::amplitude; the first harmonics are in `responses`)
    std::vector<double> vibration_amplitude;
    FrictionMultipliers multipliers;          ///< per element, what the vibrated run used
    std::vector<double> reduction;            ///< per element: 1 - factor of the friction against the motion
    double zone_top = 0.0, zone_bottom = 0.0;  ///< m MD: the first and last element reduced past the threshold
    double zone_length = 0.0;                  ///< m: the length of the elements reduced past it (0: no zone)
    std::size_t coupling_passes = 0;
    bool converged = true;  ///< false: the factors still moved by more than the tolerance after the last pass
    VibrationSource source = VibrationSource::wave;
    std::vector<OscillatorResponse> responses;  ///< source dynamic: each active tool's run, in the tools' order

    bool has_zone() const { return zone_length > 0.0; }
    double hook_load_change() const { return vibrated.hook_load() - plain.hook_load(); }            ///< N
    double surface_torque_change() const { return vibrated.surface_torque() - plain.surface_torque(); }  ///< N m
};

/// Sliding drilling at a given hook load: the weight the string puts on the bit without and with the tools.
struct SlidingTransfer {
    double hook_load = 0.0;
    double weight_on_bit_plain = 0.0;     ///< N
    double weight_on_bit_vibrated = 0.0;  ///< N
    double gain() const { return weight_on_bit_vibrated - weight_on_bit_plain; }  ///< N
};

class OscillatorDrag {
public:
    OscillatorDrag(const Survey& survey, const DrillString& string, std::size_t elements,
                   TorqueDragMethod method = TorqueDragMethod::johancsik)
        : soft_(survey, string, elements, method), wave_(string, elements), response_(survey, string) {}

    const SoftString& soft_string() const { return soft_; }
    const AxialWave& axial_wave() const { return wave_; }
    const OscillatorResponseModel& response_model() const { return response_; }

    /// Source dynamic: each active tool's steady-state run under operation `op` into `responses`, and all tools'
    /// amplitude at each element's middle into `amplitude` (a^2 = sum a_i^2).
    void dynamic_amplitude(Operation op, const SoftStringParams& p, const std::vector<HydraulicOscillator>& tools,
                           const OscillatorDragParams& o, std::vector<OscillatorResponse>& responses,
                           std::vector<double>& amplitude) const {
        const std::size_t n = soft_.elements();
        amplitude.assign(n, 0.0);
        responses.clear();
        for (const HydraulicOscillator& tool : tools) {
            if (!(tool.force_amplitude > 0.0)) continue;
            responses.push_back(response_.response(op, p, tool, o.dynamic));
            for (std::size_t e = 0; e < n; ++e) {
                const double a = responses.back().amplitude_at(soft_.element_mid_depth(e));
                amplitude[e] += a * a;
            }
        }
        for (double& a : amplitude) a = std::sqrt(a);
    }

    /// The operation without and with the tools (any number; none or zero force: the plain run, exactly).
    OscillatorDragResult run(Operation op, const SoftStringParams& p, const std::vector<HydraulicOscillator>& tools,
                             const OscillatorDragParams& o = {}) const {
        check(op, p, tools, o);
        OscillatorDragResult out;
        out.source = o.source;
        soft_.run(op, p, out.plain);
        Coupled state;
        if (o.source == VibrationSource::dynamic && any_active(tools))
            dynamic_amplitude(op, p, tools, o, out.responses, state.fixed);
        couple(op, p, tools, o, state);
        out.vibrated = std::move(state.result);
        out.vibration_amplitude = std::move(state.amplitude);
        out.multipliers = std::move(state.multipliers);
        out.coupling_passes = state.passes;
        out.converged = state.converged;
        const std::size_t n = soft_.elements();
        if (out.multipliers.axial.empty()) out.multipliers.axial.assign(n, 1.0);
        if (out.multipliers.circumferential.empty()) out.multipliers.circumferential.assign(n, 1.0);
        const bool axial_motion = operation_kinematics(op, p).direction != 0.0;
        out.reduction.resize(n);
        const std::vector<double>& depth = soft_.node_depths();
        bool first = true;
        for (std::size_t e = 0; e < n; ++e) {
            out.reduction[e] = 1.0 - (axial_motion ? out.multipliers.axial[e] : out.multipliers.circumferential[e]);
            if (!(out.reduction[e] > o.zone_threshold)) continue;
            if (first) out.zone_top = depth[e];
            first = false;
            out.zone_bottom = depth[e + 1];
            out.zone_length += depth[e + 1] - depth[e];
        }
        return out;
    }

    /// Sliding drilling at hook load H [N] (p's weight_on_bit is ignored): the weight on bit without and with the
    /// tools. A hook load at or above the string's sliding hook load with no weight on bit leaves the bit off
    /// bottom: 0.
    SlidingTransfer sliding_transfer(double hook_load, const SoftStringParams& p,
                                     const std::vector<HydraulicOscillator>& tools,
                                     const OscillatorDragParams& o = {}) const {
        SlidingTransfer out;
        out.hook_load = hook_load;
        out.weight_on_bit_plain = weight_on_bit_at(hook_load, p, {}, o);
        out.weight_on_bit_vibrated = weight_on_bit_at(hook_load, p, tools, o);
        return out;
    }

    /// The placement objective: the weight on bit [N] sliding at hook load H with the tools as given (move their
    /// measured_depth to scan placements).
    double weight_on_bit_at(double hook_load, const SoftStringParams& p,
                            const std::vector<HydraulicOscillator>& tools, const OscillatorDragParams& o = {}) const {
        detail::require_finite("OscillatorDrag", "hook_load", hook_load);
        SoftStringParams q = p;
        q.weight_on_bit = 0.0;
        check(Operation::sliding_drilling, q, tools, o);
        Coupled state;
        if (o.source == VibrationSource::dynamic && any_active(tools)) {
            // the dynamic amplitude once, at the plain string's weight on bit for this hook load
            OscillatorDragParams plain = o;
            plain.source = VibrationSource::wave;
            q.weight_on_bit = weight_on_bit_at(hook_load, p, {}, plain);
            std::vector<OscillatorResponse> responses;
            dynamic_amplitude(Operation::sliding_drilling, q, tools, o, responses, state.fixed);
        }
        const auto residual = [&](double wob) {
            q.weight_on_bit = wob;
            couple(Operation::sliding_drilling, q, tools, o, state);
            return state.result.hook_load() - hook_load;  // falls as the weight on bit grows
        };
        double lo = 0.0, r_lo = residual(0.0);
        if (!(r_lo > 0.0)) return 0.0;
        // a straight hole's answer when the drag does not change; doubled up to the weight on bit's own limit (a
        // hook load beyond it is the caller's, not the weight on bit's, to be refused)
        const double most = max_weight_on_bit();
        double hi = std::min(r_lo, most), r_hi = residual(hi);
        while (r_hi > 0.0) {
            if (hi >= most) {
                const std::string rule = "reachable while sliding by a weight on bit within the limit of " +
                                         std::to_string(most) + " N (at least the hook load with it, " +
                                         std::to_string(state.result.hook_load()) + " N)";
                detail::reject("OscillatorDrag", "hook_load", rule.c_str(), hook_load);
            }
            lo = hi;
            r_lo = r_hi;
            hi = std::min(2.0 * hi, most);
            r_hi = residual(hi);
        }
        detail::IllinoisBracket b{lo, r_lo, hi, r_hi};
        for (int k = 0; k < 200; ++k) {
            const double wob = b.next();
            const double r = residual(wob);
            if (r == 0.0 || b.b - b.a <= 1e-12 * b.b) return wob;
            b.move(wob, r, !(r > 0.0));
            if (std::abs(r) <= 1e-10 * std::max(std::abs(hook_load), 1.0)) return wob;
        }
        return 0.5 * (b.a + b.b);
    }

private:
    struct Coupled {
        TorqueDragResult result;
        FrictionMultipliers multipliers;  // empty: ones (also the warm start of the next solve)
        std::vector<double> amplitude, wall, surface, one_tool, next_axial, next_circumferential;
        std::vector<double> fixed;  // source dynamic: the amplitude held through the passes
        std::size_t passes = 0;
        bool converged = true;
    };

    /// The upper end of SoftStringParams' weight_on_bit rule.
    static double max_weight_on_bit() {
        for (const Field<SoftStringParams>& f : SoftStringParams::fields())
            if (f.member == &SoftStringParams::weight_on_bit) return f.rule.upper;
        return 0.0;
    }

    static bool any_active(const std::vector<HydraulicOscillator>& tools) {
        for (const HydraulicOscillator& tool : tools)
            if (tool.force_amplitude > 0.0) return true;
        return false;
    }

    void check(Operation op, const SoftStringParams& p, const std::vector<HydraulicOscillator>& tools,
               const OscillatorDragParams& o) const {
        validate_fields("OscillatorDragParams", o, OscillatorDragParams::fields());
        if (o.source == VibrationSource::dynamic) {
            double work = 0.0;  // one dynamic run per active tool: their sum within one run's limit
            for (const HydraulicOscillator& tool : tools) {
                response_.check(op, p, tool, o.dynamic);
                if (tool.force_amplitude > 0.0) work += response_.node_cycles(tool.frequency, o.dynamic);
            }
            if (!(work <= OscillatorResponseParams::max_node_cycles)) {
                std::ostringstream rule;
                rule.precision(3);
                rule << "few enough for the dynamic runs' work together (elements x cycles simulated, " << work
                     << ") to stay within " << OscillatorResponseParams::max_node_cycles << " (hours on one core)";
                detail::reject("OscillatorDrag", "tools", rule.str().c_str(), static_cast<double>(tools.size()));
            }
        }
        validate_fields("SoftStringParams", p, SoftStringParams::fields());
        const std::vector<double> zero(soft_.elements(), 0.0);
        for (const HydraulicOscillator& tool : tools) wave_.check(tool, zero, 0.0, {}, o.bit_reflection);
        if (o.model == VibrationFrictionModel::table5 && operation_kinematics(op, p).axial_speed == 0.0)
            for (const HydraulicOscillator& tool : tools)
                if (tool.force_amplitude > 0.0)
                    throw InvalidParameter("model", std::string("OscillatorDragParams: model must be friction_vector "
                                                                "for ") + operation_name(op) +
                                                        " (no axial sliding: Table 5 reads a / V)");
    }

    /// Steps 1-4 of the header comment, from state.multipliers (a warm start) to convergence.
    void couple(Operation op, const SoftStringParams& p, const std::vector<HydraulicOscillator>& tools,
                const OscillatorDragParams& o, Coupled& s) const {
        const std::size_t n = soft_.elements();
        const OperationKinematics kin = operation_kinematics(op, p);
        s.surface.assign(kin.rotary_speed > 0.0 ? n : 0, 0.0);
        for (std::size_t e = 0; e < s.surface.size(); ++e) s.surface[e] = kin.rotary_speed * soft_.element_radius(e);
        bool active = false;
        for (const HydraulicOscillator& tool : tools) active = active || tool.force_amplitude > 0.0;
        s.wall.resize(n);
        s.passes = 0;
        s.converged = true;
        for (;;) {
            soft_.run(op, p, s.multipliers, s.result);
            ++s.passes;
            s.amplitude.assign(n, 0.0);
            if (!active) {  // the plain run: no factor at all
                s.multipliers = {};
                return;
            }
            for (std::size_t e = 0; e < n; ++e)
                s.wall[e] = SoftString::friction_factor(soft_.element_mid_depth(e), p) * s.result.side_force_per_length[e];
            if (!s.fixed.empty()) {
                s.amplitude = s.fixed;
            } else {
                for (const HydraulicOscillator& tool : tools) {
                    wave_.amplitude(tool, s.wall, kin.axial_speed, s.surface, o.bit_reflection, s.one_tool);
                    for (std::size_t e = 0; e < n; ++e) s.amplitude[e] += s.one_tool[e] * s.one_tool[e];
                }
                for (double& a : s.amplitude) a = std::sqrt(a);
            }
            factors(kin, s.amplitude, o, s.next_axial, s.next_circumferential);
            double change = 0.0;
            for (std::size_t e = 0; e < n; ++e) {
                const double ax = s.multipliers.axial.empty() ? 1.0 : s.multipliers.axial[e];
                const double ci = s.multipliers.circumferential.empty() ? 1.0 : s.multipliers.circumferential[e];
                change = std::max({change, std::abs(s.next_axial[e] - ax), std::abs(s.next_circumferential[e] - ci)});
            }
            if (change <= o.coupling_tolerance) return;
            if (s.passes >= OscillatorDragParams::max_coupling_passes) {
                s.converged = false;
                return;
            }
            s.multipliers.axial.swap(s.next_axial);
            s.multipliers.circumferential.swap(s.next_circumferential);
        }
    }

    /// Step 3: each element's factors on its axial and circumferential friction (exactly 1 where a = 0).
    void factors(const OperationKinematics& kin, const std::vector<double>& amplitude, const OscillatorDragParams& o,
                 std::vector<double>& axial, std::vector<double>& circumferential) const {
        const std::size_t n = amplitude.size();
        axial.assign(n, 1.0);
        circumferential.assign(n, 1.0);
        const double v = kin.axial_speed;
        for (std::size_t e = 0; e < n; ++e) {
            const double a = amplitude[e];
            if (a == 0.0) continue;
            if (o.model == VibrationFrictionModel::table5) {
                axial[e] = circumferential[e] = table5_friction_factor(o.lubricant, v, a);
                continue;
            }
            const double w = kin.rotary_speed * soft_.element_radius(e);
            const CycleMeanFriction mean = cycle_mean_friction(v, a, w);
            if (w == 0.0) {
                axial[e] = mean.axial;  // the steady share is 1
                continue;
            }
            const CycleMeanFriction steady = cycle_mean_friction(v, 0.0, w);
            if (steady.axial > 0.0) axial[e] = mean.axial / steady.axial;
            circumferential[e] = mean.circumferential / steady.circumferential;
        }
    }

    SoftString soft_;
    AxialWave wave_;
    OscillatorResponseModel response_;
};

}  // namespace frictionsim
