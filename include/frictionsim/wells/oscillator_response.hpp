// The dynamic route to a tool's vibration along the string (issue 14, item 3): the event-driven axial StringRig
// (string_rig.hpp) in the surveyed well, run to a periodic steady state, instead of the travelling-wave estimate
// (axial_wave.hpp). What it resolves that the estimate does not: the string's axial resonances between its ends, the
// partial sticking of nodes near the zone's edge, and so a frequency optimum.
//  * The model: the string lumped on its own grid (DrillString::lump(M), M from the tool's wavelength: at least
//    elements_per_wavelength elements per c / f, so the lumped chain's phase speed is within ~1 % of c), every node
//    inclined as the survey says, and a Coulomb wall contact at each node 1..M-1 whose normal force is the soft
//    string's side force of the operation (SoftString::node_side_forces under the plain run's tension; the bit
//    node's is carried by node M-1), scaled by its friction factor (cased or open hole): friction mu_i N_i.
//  * Boundary conditions: the hook moves at the operation's axial speed (a fixed end for the vibration), the bit
//    holds the weight on bit as a constant force (a free end: velocity reflection +1) and takes no torque; the
//    string does not turn (operations with rotation are refused: the torsional steady state is not built here).
//  * Start: every node sliding at the operation's speed with the springs stretched to the steady balance of the
//    rig's own nodes (T_{i-1} = T_i + w_i cos I_i - d k_i mu_i N_i, d the direction of motion), k_i the friction
//    vector's factor of the travelling-wave estimate there (1 without the tool: the run then stays where it is,
//    up to the integrator's error); the tool's force F sin(2 pi f t) at the node nearest to it starts at t = 0.
//    The vibration lowers the mean friction, so the string's mean tension has to creep to a new balance (the
//    slowest part of the transient, ~1-3 s for a kilometre of zone): the estimate's factors start it close.
//  * Transient (default): two round trips of the wave over the length it reaches, 4 l / c (l the distance from the
//    tool to the farthest element the travelling-wave estimate reaches with a free bit, c the string's mean wave
//    speed), plus three decay times 2 / (beta omega^2) of the structural damping at the tool's frequency (modal
//    damping ratio beta omega / 2), at least 10 cycles; then windows of `cycles` cycles until two successive ones
//    agree within steady_tolerance of the largest amplitude (or max_time runs out: settled = false). Coulomb
//    friction damps only where the vibration reverses the sliding; where it does not, only beta does. A caller's
//    transient is run as given, then one window.
//  * Measure: the first harmonic of each node's axial speed at the tool's frequency over `cycles` whole cycles after
//    the transient (samples_per_cycle equally spaced samples per cycle: the sliding speed's mean drops out exactly),
//    v_i(t) ~ V + a_i sin(omega t + phi_i); an element's amplitude is the magnitude of the phasor interpolated
//    linearly between the nodes (right across the nodes and antinodes of a standing wave).
//  * The friction it produces: over whole cycles each node's momentum is periodic, so the wall's mean friction is
//    the mean of the other forces on it, d (<T_i> - <T_{i-1}> + w_i cos I_i), from the sampled element tensions:
//    friction_factor = that / (mu_i N_i). It differs from the friction vector of the first harmonic where nodes
//    stick for part of the cycle: at the zone's edges (the factor is higher) and, away from the zone, where a
//    sliding string driven this way sticks and slips forward at the tool's frequency (a first harmonic of order
//    V that would read as a 40-60 % reduction, where the sliding never reverses; the measured factor there is
//    0.8-0.95: a stuck node holds less than mu N).
//  * The amplitude the friction sees (`amplitude`): the first harmonic h, at most the amplitude of the sinusoid
//    V + a sin(omega t) whose cycle-mean friction is the measured one, (2 / pi) asin(V / a) = factor; with V = 0
//    (no sliding: the mean friction is statically indeterminate), h.
// Several tools: one run per tool, their amplitudes added as independent vibrations, a^2 = sum a_i^2 (as the wave
// route does; the rig has one excitation). Cost: one run integrates M nodes over transient + cycles / f seconds
// with Dormand-Prince, each node near the tool switching stick/slip about twice per cycle.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../error.hpp"
#include "../friction/coulomb.hpp"
#include "../parameters.hpp"
#include "../solve/dormand_prince.hpp"
#include "../solve/hybrid_loop.hpp"
#include "axial_wave.hpp"
#include "../string/sections.hpp"
#include "soft_string.hpp"
#include "../string/string_rig.hpp"
#include "../survey.hpp"

namespace frictionsim {

/// Where the tools' vibration velocity along the string comes from: the attenuated travelling-wave estimate
/// (axial_wave.hpp, fast) or the dynamic axial string model run to a periodic steady state (this header).
enum class VibrationSource { wave, dynamic };

inline const char* vibration_source_name(VibrationSource s) { return s == VibrationSource::wave ? "wave" : "dynamic"; }

/// The dynamic run's settings (header comment).
struct OscillatorResponseParams {
    double transient = std::numeric_limits<double>::quiet_NaN();  ///< s; unset (NaN): the header's default
    double cycles = 8.0;                    ///< whole cycles measured after the transient
    double elements_per_wavelength = 16.0;  ///< the grid: elements per wavelength c / f, at least
    double damping_time = 0.0;              ///< beta, s: the string's structural damping (mud, tool joints)
    double rtol = 1e-6;                     ///< the integrator's relative tolerance
    double stick_speed = 1e-4;              ///< m/s: where a contact is caught to stick (wall_contact.hpp)
    double steady_tolerance = 0.02;         ///< settled: two windows' amplitudes agree within this share of the largest
    double max_time = 30.0;                 ///< s: the longest run while waiting for it to settle
    /// Polled between integrator steps (SolverOptions::interrupt): true stops the run (Interrupted). Python's Ctrl-C.
    std::function<bool()> interrupt;

    static constexpr std::size_t samples_per_cycle = 64;
    static constexpr std::size_t min_elements = 10;
    /// The most work one dynamic run may take: elements x cycles simulated (node-cycles). Measured: 350 node-cycles
    /// per second (4.85 km at 18 and 28 Hz, 270 and 420 elements, ~75 integrator steps and 20 stick-slip switches
    /// per node-cycle; the -O1 development build on a loaded 2-core machine), so 1e7 is hours. A 10 km string at
    /// 30 Hz with the defaults (940 elements, at most 30 s) needs 8.5e5, the heaviest case of the tests (300 s at
    /// 100 elements per wavelength) 2.4e5; a tool at 1e4 Hz on 3 km needs ~2e9 (months), at 1e6 Hz its 9e6
    /// elements alone would not fit in memory.
    static constexpr double max_node_cycles = 1e7;
    static constexpr std::array<Field<OscillatorResponseParams>, 8> fields();
};

inline constexpr std::array<Field<OscillatorResponseParams>, 8> OscillatorResponseParams::fields() {
    using P = OscillatorResponseParams;
    return {{
        {"transient", "t_tr", "s", Rule::interval(0.0, 600.0).or_unset(), &P::transient,
         "Time run before the one measured window; unset: 4 l / c + 3 decay times, then windows until settled."},
        {"cycles", "n_cyc", "-", Rule::interval(1.0, 1000.0), &P::cycles,
         "Whole cycles of the tool's frequency over which the first harmonic is measured (rounded down)."},
        {"elements_per_wavelength", "n_lambda", "-", Rule::interval(4.0, 200.0), &P::elements_per_wavelength,
         "Elements of the dynamic model per wavelength c / f, at least."},
        {"damping_time", "beta", "s", Rule::non_negative(), &P::damping_time,
         "Structural damping of the string: element damping beta times stiffness (modal ratio beta omega / 2)."},
        {"rtol", "rtol", "-", Rule::interval(1e-10, 1e-3), &P::rtol, "Relative tolerance of the integrator."},
        {"stick_speed", "s_stick", "m/s", Rule::positive(), &P::stick_speed,
         "Sliding speed at which a wall contact is caught to stick."},
        {"steady_tolerance", "tol_ss", "-", Rule::interval(0.0, 1.0, true, false), &P::steady_tolerance,
         "Settled when two successive windows' amplitudes differ by at most this share of the largest."},
        {"max_time", "t_max", "s", Rule::interval(0.0, 600.0, true, false), &P::max_time,
         "Longest simulated time while waiting for the response to settle (then settled = false)."},
    }};
}

/// One tool's dynamic steady-state response on the dynamic model's nodes.
struct OscillatorResponse {
    std::vector<double> measured_depth;  ///< per node of the dynamic model, m (node 0 at the surface)
    std::vector<std::complex<double>> phasor;  ///< per node, m/s: the first harmonic, v ~ V + Im(phasor e^{i omega t})
    /// Per node, the share of the measured samples sliding against the operation's motion.
    std::vector<double> reversed;
    /// Per node: the wall's cycle-mean friction over mu_i N_i, from the node's mean balance (1 where no contact).
    std::vector<double> friction_factor;
    /// Per node, m/s: the amplitude the friction sees, min(|phasor|, V / sin(pi factor / 2)) (header comment).
    std::vector<double> amplitude;
    std::size_t excitation_node = 0;  ///< the node the tool's force acts on
    double transient = 0.0;           ///< s, what was run before the measured window
    double measured_time = 0.0;       ///< s, the whole cycles measured
    double reach = 0.0;               ///< m, l of the default transient (the wave estimate's reach)
    bool settled = true;              ///< false: max_time ran out before two windows agreed
    SolverStats stats;                ///< steps and events (stick-slip switches) of the whole run

    std::size_t elements() const { return measured_depth.empty() ? 0 : measured_depth.size() - 1; }
    /// The amplitude the friction sees at measured depth x [m]: linear between the nodes (phasors: right across
    /// the nodes of a standing wave; the limit scales it by the same share).
    double amplitude_at(double x) const {
        const auto [j, u] = locate(x);
        const double harmonic = std::abs(phasor_at(x));
        const double h0 = std::abs(phasor[j]), h1 = std::abs(phasor[j + 1]);
        const double limited = (1.0 - u) * amplitude[j] + u * amplitude[j + 1], linear = (1.0 - u) * h0 + u * h1;
        return linear > 0.0 ? harmonic * std::min(1.0, limited / linear) : 0.0;
    }
    /// The first harmonic's magnitude at measured depth x [m] (phasors interpolated linearly).
    double first_harmonic_at(double x) const { return std::abs(phasor_at(x)); }
    /// The measured friction factor at measured depth x [m], linear between the nodes.
    double friction_factor_at(double x) const {
        const auto [j, u] = locate(x);
        return (1.0 - u) * friction_factor[j] + u * friction_factor[j + 1];
    }

private:
    std::pair<std::size_t, double> locate(double x) const {
        const std::size_t m = elements();
        const double s = std::clamp(x / (measured_depth[m] / static_cast<double>(m)), 0.0, static_cast<double>(m));
        const auto j = std::min(static_cast<std::size_t>(s), m - 1);
        return {j, s - static_cast<double>(j)};
    }
    std::complex<double> phasor_at(double x) const {
        const auto [j, u] = locate(x);
        return (1.0 - u) * phasor[j] + u * phasor[j + 1];
    }
};

/// The bit of the dynamic response: on bottom, it holds the weight on bit against the string as a constant force
/// (axially a free end) and takes no torque (inert: no static limit, no jump at zero speed; bit.hpp's interface).
class ImposedWeightOnBit {
public:
    static constexpr const char* name = "ImposedWeightOnBit";
    static constexpr bool touches_rock = true;
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;

    explicit ImposedWeightOnBit(double weight_on_bit = 0.0)
        : weight_(detail::require_non_negative(name, "weight_on_bit", weight_on_bit)) {}
    double weight_on_bit() const { return weight_; }  ///< W, N
    double static_limit(double) const { return 0.0; }
    double slip_force(double, double, int) const { return 0.0; }
    double slip_slope(double, double, int) const { return 0.0; }
    double karnopp_band() const { return 0.0; }

private:
    double weight_ = 0.0;
};

/// The dynamic axial model of a string in a surveyed well under one steady operation, and its response to a tool.
class OscillatorResponseModel {
public:
    using Rig = StringRig<Coulomb, ImposedWeightOnBit>;

    OscillatorResponseModel(const Survey& survey, const DrillString& string) : survey_(survey), string_(string) {
        double travel = 0.0;
        for (const PipeSection& s : string_.sections()) travel += s.length / std::sqrt(s.youngs_modulus / s.density);
        mean_speed_ = string_.length() / travel;
        min_speed_ = std::numeric_limits<double>::infinity();
        for (const PipeSection& s : string_.sections())
            min_speed_ = std::min(min_speed_, std::sqrt(s.youngs_modulus / s.density));
        (void)SoftString(survey_, string_, 1);  // the survey must reach the bit (named there)
    }

    const DrillString& string() const { return string_; }
    double mean_wave_speed() const { return mean_speed_; }  ///< c = L / (travel time), m/s

    /// The dynamic model's element count for a tool of frequency f [Hz] (check() has bounded it).
    std::size_t elements_for(double frequency, const OscillatorResponseParams& o) const {
        return static_cast<std::size_t>(elements_count(frequency, o));
    }

    /// Checks the operation and the settings, naming the parameter.
    void check(Operation op, const SoftStringParams& p, const HydraulicOscillator& tool,
               const OscillatorResponseParams& o) const {
        validate_fields("OscillatorResponseParams", o, OscillatorResponseParams::fields());
        validate_fields("SoftStringParams", p, SoftStringParams::fields());
        validate_fields("HydraulicOscillator", tool, HydraulicOscillator::fields());
        if (!(tool.measured_depth <= string_.length())) {
            const std::string rule = "<= the string's length, " + std::to_string(string_.length()) +
                                     " m (the tool cannot be below the bit)";
            detail::reject("HydraulicOscillator", "measured_depth", rule.c_str(), tool.measured_depth);
        }
        if (operation_kinematics(op, p).rotary_speed > 0.0)
            throw InvalidParameter("vibration", std::string("OscillatorResponse: the dynamic vibration needs an "
                                                            "operation without rotation (trip_in, trip_out, "
                                                            "sliding_drilling), not ") + operation_name(op));
        const double cycles_time = std::floor(o.cycles) / tool.frequency;
        if (!(cycles_time <= 600.0))
            detail::reject("OscillatorResponseParams", "cycles", "at most 600 s of cycles at the tool's frequency",
                           o.cycles);
        if (!std::isnan(o.transient) && !(o.transient <= 600.0))
            detail::reject("OscillatorResponseParams", "transient", "at most 600 s", o.transient);
        const double work = node_cycles(tool.frequency, o);
        if (!(work <= OscillatorResponseParams::max_node_cycles)) {
            std::ostringstream rule;
            rule.precision(3);
            rule << "low enough for the dynamic run's work, elements x cycles simulated, to stay within "
                 << OscillatorResponseParams::max_node_cycles << " (hours on one core): here "
                 << work << " (" << elements_count(tool.frequency, o) << " elements over " << longest_time(tool.frequency, o)
                 << " s at " << tool.frequency << " Hz); lower the frequency, elements_per_wavelength, max_time or "
                 << "transient, or use vibration='wave'";
            detail::reject("HydraulicOscillator", "frequency", rule.str().c_str(), tool.frequency);
        }
    }

    /// The dynamic run's work [node-cycles] for a tool of frequency f: elements x the longest simulated time x f
    /// (a fixed transient and one window; else the longer of max_time and the default transient's cap, and a
    /// window). Estimated before anything is allocated (check()).
    double node_cycles(double frequency, const OscillatorResponseParams& o) const {
        return elements_count(frequency, o) * longest_time(frequency, o) * frequency;
    }

    /// The rig of operation `op` with tool `tool` on `elements` elements (what response() runs). `start`: per
    /// node, an amplitude whose friction-vector factor presets the springs' mean tension (nullptr: the plain one).
    Rig rig(Operation op, const SoftStringParams& p, const HydraulicOscillator& tool, std::size_t elements,
            const OscillatorResponseParams& o, const std::vector<double>* start = nullptr) const {
        const std::size_t m = elements;
        const OperationKinematics kin = operation_kinematics(op, p);
        const SoftString soft(survey_, string_, m);
        const TorqueDragResult plain = soft.run(op, p);
        std::vector<double> node_force;
        soft.node_side_forces(plain.tension, p.mud_density, node_force);
        const std::vector<double>& depth = soft.node_depths();
        // mu_i N_i as a normal force under one law of coefficient mu_ref (Coulomb is linear in N)
        const double mu_ref = std::max(p.cased_hole_friction, p.open_hole_friction);
        StringRigSetup s;
        s.elements = m;
        s.top_drive = TopDrive::prescribed_speed;
        s.axial = true;
        s.hoisting = Hoisting::hook_speed;
        s.node_inclinations = soft.node_inclinations();
        s.excitation_node = std::clamp<std::size_t>(
            static_cast<std::size_t>(std::lround(tool.measured_depth / soft.element_length())), 1, m);
        s.wall_contacts = mu_ref > 0.0 && m >= 2;
        if (s.wall_contacts) {
            for (std::size_t i = 1; i < m; ++i) {
                double n = node_force[i] * SoftString::friction_factor(depth[i], p);
                if (i + 1 == m) n += node_force[m] * SoftString::friction_factor(depth[m], p);
                s.contact_nodes.push_back(i);
                s.normal_forces.push_back(n / mu_ref);
            }
        }
        StringRigParams rp;
        rp.damping_time = o.damping_time;
        rp.surface_speed = 0.0;
        rp.mud_density = p.mud_density;
        rp.hook_speed = -kin.direction * kin.axial_speed;  // positive down the hole
        rp.initial_axial_speed = rp.hook_speed;
        rp.excitation_amplitude = tool.force_amplitude;
        rp.excitation_frequency = tool.frequency;
        rp.stick_speed = o.stick_speed;
        Rig r(string_, rp, s, Coulomb(mu_ref > 0.0 ? mu_ref : 1.0), ImposedWeightOnBit(p.weight_on_bit));
        std::vector<double> factor(m + 1, 1.0);
        if (start)
            for (std::size_t i = 0; i <= m; ++i)
                if ((*start)[i] > 0.0) factor[i] = cycle_mean_friction(kin.axial_speed, (*start)[i]).axial;
        r.set_initial_state(sliding_state(r, kin, mu_ref, factor));
        return r;
    }

    /// The default transient [s] for a tool whose wave reaches `reach` metres (header comment).
    double default_transient(double reach, double frequency, const OscillatorResponseParams& o) const {
        const double omega = 2.0 * pi * frequency;
        double t = 4.0 * reach / mean_speed_;
        if (o.damping_time > 0.0) t += 3.0 * 2.0 / (o.damping_time * omega * omega);
        return std::clamp(t, 10.0 / frequency, 600.0);
    }

    /// The travelling-wave estimate with a free bit (axial_wave.hpp) at the m + 1 nodes of the dynamic model, into
    /// `at_nodes`; returns its reach from the tool, m: the largest distance of an element it reaches (the
    /// string's length when the wall has no friction).
    double wave_estimate(Operation op, const SoftStringParams& p, const HydraulicOscillator& tool, std::size_t m,
                         std::vector<double>& at_nodes) const {
        const std::size_t n = std::max<std::size_t>(200, static_cast<std::size_t>(std::ceil(string_.length() / 5.0)));
        const SoftString soft(survey_, string_, n);
        const AxialWave wave(string_, n);
        const TorqueDragResult plain = soft.run(op, p);
        std::vector<double> wall(n);
        for (std::size_t e = 0; e < n; ++e)
            wall[e] = SoftString::friction_factor(soft.element_mid_depth(e), p) * plain.side_force_per_length[e];
        const std::vector<double> a = wave.amplitude(tool, wall, operation_kinematics(op, p).axial_speed, {}, 1.0);
        double reach = 0.0;
        for (std::size_t e = 0; e < n; ++e)
            if (a[e] > 0.0) reach = std::max(reach, std::abs(soft.element_mid_depth(e) - tool.measured_depth));
        at_nodes.assign(m + 1, 0.0);
        const double dx = string_.length() / static_cast<double>(m), de = string_.length() / static_cast<double>(n);
        for (std::size_t i = 0; i <= m; ++i) {  // the element whose middle is nearest
            const double e = std::clamp(std::round(dx * static_cast<double>(i) / de - 0.5), 0.0, static_cast<double>(n - 1));
            at_nodes[i] = a[static_cast<std::size_t>(e)];
        }
        return std::max(reach, soft.element_length());
    }

    /// One tool's periodic steady-state response under operation `op` (header comment). A failed run throws
    /// SimulationError naming the tool and the time reached.
    OscillatorResponse response(Operation op, const SoftStringParams& p, const HydraulicOscillator& tool,
                                const OscillatorResponseParams& o = {}) const {
        check(op, p, tool, o);
        const std::size_t m = elements_for(tool.frequency, o);
        const OperationKinematics kin = operation_kinematics(op, p);
        OscillatorResponse out;
        std::vector<double> estimate;
        out.reach = wave_estimate(op, p, tool, m, estimate);
        const Rig r = rig(op, p, tool, m, o, &estimate);
        const bool fixed = !std::isnan(o.transient);
        out.transient = fixed ? o.transient : default_transient(out.reach, tool.frequency, o);
        const double period = 1.0 / tool.frequency;
        const auto cycles = static_cast<std::size_t>(std::floor(o.cycles));
        const std::size_t samples = cycles * OscillatorResponseParams::samples_per_cycle;
        out.measured_time = static_cast<double>(cycles) * period;
        out.excitation_node = r.setup().excitation_node;
        out.measured_depth.resize(m + 1);
        for (std::size_t i = 0; i <= m; ++i)
            out.measured_depth[i] =
                i == m ? string_.length() : string_.length() * static_cast<double>(i) / static_cast<double>(m);
        SolverOptions so;
        so.method = Method::dormand_prince;
        so.rtol = o.rtol;
        so.atol = 1e-9;
        so.max_events_in_window = 1000000;
        so.interrupt = o.interrupt;
        FirstHarmonic harmonic(r, 2.0 * pi * tool.frequency, -kin.direction);
        std::vector<double> wall(m + 1, 0.0);  // mu_i N_i per node: the contacts' kinetic friction
        for (std::size_t c = 0; c < r.contact_nodes().size(); ++c)
            wall[r.contact_nodes()[c]] = r.wall_static_limit(c);  // Coulomb(mu_ref): static = kinetic
        std::vector<double> x = r.initial_state(), previous;
        double t = 0.0;
        // the transient, then window after window until two agree (unless the caller fixed the transient)
        run_span(r, x, t, out.transient, so, harmonic, tool, out.stats);
        for (;;) {
            so.output_times.resize(samples);
            for (std::size_t k = 0; k < samples; ++k)
                so.output_times[k] = t + out.measured_time * static_cast<double>(k) / static_cast<double>(samples);
            harmonic.reset();
            run_span(r, x, t, t + out.measured_time, so, harmonic, tool, out.stats);
            harmonic.finish(kin.axial_speed, wall, out);
            if (fixed) break;
            double largest = 0.0, change = 0.0;
            for (std::size_t i = 0; i <= m; ++i) {
                largest = std::max(largest, out.amplitude[i]);
                if (!previous.empty()) change = std::max(change, std::abs(out.amplitude[i] - previous[i]));
            }
            if (!previous.empty() && change <= o.steady_tolerance * largest) break;
            if (t + out.measured_time > o.max_time) {
                out.settled = false;
                break;
            }
            previous = out.amplitude;
            out.transient = t;
        }
        return out;
    }

private:
    /// elements_for as a double (no cast of a huge count): at least min_elements, n_lambda per wavelength c / f.
    double elements_count(double frequency, const OscillatorResponseParams& o) const {
        const double n = std::ceil(o.elements_per_wavelength * string_.length() * frequency / min_speed_);
        return std::max(static_cast<double>(OscillatorResponseParams::min_elements), n);
    }
    /// The longest time response() simulates [s]: a fixed transient and one window; else the default transient
    /// (its reach at most the string's length) or max_time, whichever is longer, and one window.
    double longest_time(double frequency, const OscillatorResponseParams& o) const {
        const double window = std::floor(o.cycles) / frequency;
        if (!std::isnan(o.transient)) return o.transient + window;
        return std::max(default_transient(string_.length(), frequency, o), o.max_time) + window;
    }

    /// The first harmonic of every node's axial speed over whole cycles: v = V + Im(A e^{i omega t}) gives
    /// A = 2 i <v e^{-i omega t}>; and the slowest speed along the motion (v times the direction, down +1).
    struct FirstHarmonic {
        FirstHarmonic(const Rig& r, double w, double down)
            : rig(&r), omega(w), direction(down), sum(r.elements() + 1), backward(r.elements() + 1),
              tension(r.elements()) {}
        const Rig* rig;
        double omega, direction;
        std::vector<std::complex<double>> sum;
        std::vector<std::size_t> backward;  // samples sliding against the operation's motion
        std::vector<double> tension;        // per element, the sum of its tension
        std::size_t count = 0;
        long events = 0;

        void reset() {
            std::fill(sum.begin(), sum.end(), std::complex<double>(0.0, 0.0));
            std::fill(backward.begin(), backward.end(), 0);
            std::fill(tension.begin(), tension.end(), 0.0);
            count = 0;
        }
        template <class Mode>
        void output(double t, const double* x, const Mode&) {
            const std::complex<double> w = std::complex<double>(0.0, 1.0) * std::exp(std::complex<double>(0.0, -omega * t));
            for (std::size_t i = 0; i < sum.size(); ++i) {
                const double v = x[rig->speed(i)];
                sum[i] += v * w;
                backward[i] += direction * v < 0.0;
            }
            for (std::size_t e = 0; e < tension.size(); ++e) tension[e] += rig->element_tension(x, e);
            ++count;
        }
        template <class... A>
        void step(A&&...) {}
        template <class... A>
        void event(A&&...) {
            ++events;
        }
        /// The window's phasors, reversed shares, measured friction factors and amplitudes into out (header
        /// comment; sliding speed V, `wall` the kinetic friction mu_i N_i per node).
        void finish(double sliding_speed, const std::vector<double>& wall, OscillatorResponse& out) const {
            const std::size_t nodes = sum.size();
            const double n = static_cast<double>(count), scale = 2.0 / n;
            out.phasor.resize(nodes);
            out.reversed.resize(nodes);
            out.amplitude.resize(nodes);
            out.friction_factor.assign(nodes, 1.0);
            const std::vector<double>& weight = rig->axial_weights();
            for (std::size_t i = 0; i < nodes; ++i) {
                out.phasor[i] = scale * sum[i];
                out.reversed[i] = static_cast<double>(backward[i]) / n;
                const double h = std::abs(out.phasor[i]);
                out.amplitude[i] = h;
                if (!(wall[i] > 0.0)) continue;
                // the node's mean balance over whole cycles (its momentum is periodic): the friction's mean
                const double below = i < nodes - 1 ? tension[i] / n : 0.0, above = i > 0 ? tension[i - 1] / n : 0.0;
                const double friction = direction * (below - above + weight[i]);
                const double factor = std::clamp(friction / wall[i], 0.0, 1.0);
                out.friction_factor[i] = factor;
                if (!(sliding_speed > 0.0)) continue;
                // the sinusoid with this cycle-mean friction, (2 / pi) asin(V / a) = factor; at most h
                const double equivalent = factor >= 1.0 ? sliding_speed : sliding_speed / std::sin(0.5 * pi * factor);
                out.amplitude[i] = std::min(h, equivalent);
            }
        }
    };

    /// Runs the rig from (t, x) to t_end (x, t updated), outputs to `h`; a failure names the tool and the time.
    static void run_span(const Rig& r, std::vector<double>& x, double& t, double t_end, const SolverOptions& so,
                         FirstHarmonic& h, const HydraulicOscillator& tool, SolverStats& stats) {
        if (!(t_end > t)) return;
        try {
            const HybridOutcome<Rig> done = integrate_hybrid<DormandPrince>(r, x, t, t_end, so, h);
            x.assign(done.state.begin(), done.state.end());
            stats.steps += done.stats.steps;
            stats.rhs_evaluations += done.stats.rhs_evaluations;
            stats.restarts += done.stats.restarts;
            stats.events = h.events;
            t = t_end;
        } catch (const Interrupted&) {
            throw;  // the caller's stop (Ctrl-C), not a failure of the run
        } catch (const SimulationError& e) {
            throw SimulationError("OscillatorResponse: the dynamic run of the tool at " +
                                      std::to_string(tool.measured_depth) + " m (" + std::to_string(tool.frequency) +
                                      " Hz) failed at t = " + std::to_string(e.time_reached()) + " s: " + e.what(),
                                  e.time_reached());
        }
    }

    /// Every node sliding at the hook's speed, each element stretched to the steady balance of its nodes with the
    /// wall friction times `factor` per node (header comment).
    static std::vector<double> sliding_state(const Rig& r, const OperationKinematics& kin, double mu_ref,
                                             const std::vector<double>& factor) {
        std::vector<double> x = r.initial_state();
        const std::size_t m = r.elements();
        const std::vector<double>& w = r.axial_weights();
        std::vector<double> wall(m + 1, 0.0);
        for (std::size_t c = 0; c < r.contact_nodes().size(); ++c) {
            const std::size_t i = r.contact_nodes()[c];
            wall[i] = mu_ref * r.normal_forces()[c] * factor[i];
        }
        const double down = -kin.direction;  // +1 moving down the hole: friction acts up
        std::vector<double> tension(m, 0.0);
        double below = -r.bit().weight_on_bit();  // what the bit node carries from below
        for (std::size_t i = m; i-- > 0;) {
            below += w[i + 1] - down * wall[i + 1];
            tension[i] = below;
        }
        x[r.position(0)] = 0.0;
        for (std::size_t e = 0; e < m; ++e) {
            x[r.position(e + 1)] = x[r.position(e)] + tension[e] / r.lumped().axial_stiffness[e];
            x[r.speed(e)] = x[r.speed(e + 1)] = r.params().hook_speed;
        }
        return x;
    }

    Survey survey_;
    DrillString string_;
    double mean_speed_ = 0.0, min_speed_ = 0.0;
};

}  // namespace frictionsim
