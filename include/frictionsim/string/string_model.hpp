// The one drill-string model (issue 22 item 1): a TorsionalString (the description: sections, lumping, drive,
// damping, the walls' bounds from the buoyed weight and the well's inclination, the bit) and the treatment of its
// contacts, run through simulate() like every other model:
//   captured  every contact captured by Moreau-Jean (TorsionalString's time-stepping);
//   mixed     the walls captured, the on-bottom bit's stick and slip located exactly (TorsionalString with
//             BitTreatment::exact);
//   exact     every stick and slip located as an event: the StringRig of the same string (exact_string.hpp), run
//             by an event-driven method, its rows given back as the TorsionalString's columns.
// Whatever the treatment, the Result has the TorsionalString's columns (bit_speed, top_drive_speed, motor_torque,
// stuck_fraction; friction_force node N's contact torque; mode the wall contacts at rest), so a caller reads the
// same names. Differences, stated: under exact the events are StringRig's (every located wall, bit and drive
// switch, named by their guards) where the time-stepping logs the bit's switches only; the rows are the integrator's
// output points, and a row's modes (for motor_torque and friction_force) are the ones StringRig would start from at
// that state (a stuck contact at its static bound reads as sticking).
// StringModel::automatic picks the treatment by the measured rule of treatment.hpp. Python: fs.TorsionalString(...,
// treatment="captured" | "mixed" | "exact" | "auto") binds this type.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "../error.hpp"
#include "../solve/options.hpp"
#include "../solve/result.hpp"
#include "../solve/stop_conditions.hpp"
#include "../solve/time_stepping.hpp"
#include "exact_string.hpp"
#include "torsional_string.hpp"
#include "treatment.hpp"

namespace frictionsim {

class StringModel {
public:
    /// A model that chooses its engine: simulate() hands it an event-driven runner (simulate.hpp).
    static constexpr bool chooses_engine = true;

    /// `string` as described, its contacts treated as `treatment` says (`switch_tolerance`: the mixed treatment's
    /// bit switches located within it, s). What a treatment cannot carry is refused here, naming the parameter:
    /// mixed needs the bit on bottom and no torque limit; exact what exact_string refuses (a stick band, a bit torque
    /// off bottom, a wall at the top drive's node).
    StringModel(TorsionalString string, StringTreatment treatment, double switch_tolerance = 1e-10)
        : string_(std::move(string)), treatment_(treatment) {
        if (treatment == StringTreatment::mixed && !string_.bit_on_bottom())
            detail::reject("StringModel", "treatment",
                           "captured or exact off bottom (mixed locates the bit's stick and slip; weight_on_bit 0)",
                           string_.params().weight_on_bit);
        string_.set_bit_treatment(treatment == StringTreatment::mixed ? BitTreatment::exact : BitTreatment::captured,
                                  switch_tolerance);
        if (treatment == StringTreatment::exact) {
            if (string_.bit_on_bottom()) exact_ = exact_string_on_bottom(string_);
            else exact_ = exact_string(string_);
        }
    }
    /// The treatment of the measured rule (automatic_treatment) for this string's wall contacts and bit.
    static StringModel automatic(TorsionalString string, double switch_tolerance = 1e-10) {
        const StringTreatment t = automatic_treatment(string.contact_count(), string.bit_on_bottom());
        return StringModel(std::move(string), t, switch_tolerance);
    }

    const TorsionalString& string() const { return string_; }
    StringTreatment treatment() const { return treatment_; }
    std::vector<std::string> state_names() const { return string_.state_names(); }

    /// The run: captured / mixed by the time-stepping loop (options.method moreau_jean, explicit_projection or
    /// automatic), exact by `event_driven(rig, t_end, options, t_start)` on the StringRig (any event-driven method;
    /// a time-stepping one is refused naming `method`). A stop condition on bit_speed or top_drive_speed reads node
    /// N's or node 0's speed under every treatment; motor_torque and stuck_fraction are not states of the exact
    /// engine and are refused there. A failed run's partial result has the same columns.
    template <class EventDriven>
    Result run(double t_end, const SolverOptions& options, double t_start, const EventDriven& event_driven) const {
        if (treatment_ != StringTreatment::exact) return simulate_time_stepping(string_, t_end, options, t_start);
        if (is_time_stepping_method(options.method))
            throw InvalidParameter("method", std::string("StringModel: treatment exact runs event-driven (automatic, "
                                                         "dormand_prince, rosenbrock, cvode_bdf or cvode_adams), "
                                                         "not method = ") + method_name(options.method));
        return std::visit(
            [&](const auto& rig) -> Result {
                if constexpr (std::is_same_v<std::decay_t<decltype(rig)>, std::monostate>) {
                    return Result{};  // unreachable: exact_ holds a rig under the exact treatment
                } else {
                    const SolverOptions translated = exact_options(rig, options);
                    try {
                        return columns(rig, event_driven(rig, t_end, translated, t_start));
                    } catch (SimulationError& e) {
                        if (e.partial()) e.attach_partial(std::make_shared<Result>(columns(rig, *e.partial())));
                        throw;
                    }
                }
            },
            exact_);
    }

private:
    /// The stop conditions on the string's columns as the StringRig's states (bit_speed: omega_N; top_drive_speed:
    /// omega_0).
    template <class Rig>
    SolverOptions exact_options(const Rig& rig, const SolverOptions& options) const {
        SolverOptions out = options;
        for (StopCondition& c : out.stop_conditions) {
            if (c.state.empty()) continue;
            if (c.name.empty()) c.name = c.state + " = " + detail::StopWatch::number(c.level);  // as the user wrote it
            if (c.state == "bit_speed") c.state = "omega_" + std::to_string(rig.elements());
            else if (c.state == "top_drive_speed") c.state = "omega_0";
            else if (c.state == "motor_torque" || c.state == "stuck_fraction")
                throw InvalidParameter("stop_conditions.state",
                                       "StringModel: under treatment exact a stop condition reads bit_speed or "
                                       "top_drive_speed (the event-driven string's states), not " + c.state);
        }
        return out;
    }

    /// The StringRig's rows as the TorsionalString's columns (see the header).
    template <class Rig>
    Result columns(const Rig& rig, const Result& run) const {
        Result out;
        out.state_names = string_.state_names();
        out.t = run.t;
        out.mode = run.mode;
        out.events = run.events;
        out.stop_events = run.stop_events;
        out.stats = run.stats;
        out.completed = run.completed;
        out.status = run.status;
        out.message = run.message;
        out.warnings = run.warnings;
        out.t_reached = run.t_reached;
        const std::size_t n = rig.elements(), width = run.state_count(), columns = out.state_names.size();
        out.states.reserve(run.rows() * columns);
        out.friction_force.reserve(run.rows());
        const double slow = string_.slow_speed();
        for (std::size_t r = 0; r < run.rows(); ++r) {
            const double t = run.t[r];
            const double* x = run.states.data() + r * width;
            const auto modes = rig.initial_mode(t, x);
            const auto speed = [&](std::size_t i) {
                return i == 0 && rig.drive().holds_speed() ? drive_held_speed(rig.drive(), t) : x[rig.omega(i)];
            };
            std::size_t stuck = 0;
            for (std::size_t i = 0; i <= n; ++i) stuck += (slow > 0.0 ? std::abs(speed(i)) < slow : speed(i) == 0.0);
            out.states.push_back(speed(n));
            out.states.push_back(speed(0));
            out.states.push_back(rig.surface_torque(t, x, modes));
            out.states.push_back(static_cast<double>(stuck) / static_cast<double>(n + 1));
            out.friction_force.push_back(bit_node_torque(rig, t, x, modes));
        }
        return out;
    }

    /// Node N's contact torque on node N (the captured string's friction_force): the bit's with its wall's on
    /// bottom (without the bit's viscous c_b w, which is damping); off bottom the wall's, its slip level
    /// -sign(w) f_rat T_s when turning, what holds it at rest when stuck.
    template <class Rig, class Modes>
    double bit_node_torque(const Rig& rig, double t, const double* x, const Modes& modes) const {
        const std::size_t n = rig.elements();
        if constexpr (Rig::on_bottom) {
            // the torque on bit resists the rotation (negative on node N); the captured string carries the bit's
            // viscous c_b w in its damping, not in the contact: so here too
            const double damper = string_.bit_law().params().viscous_damping * x[rig.omega(n)];
            return damper - rig.bit_torque(t, x, modes);
        } else {
            const std::vector<std::size_t>& nodes = rig.contact_nodes();
            if (nodes.empty() || nodes.back() != n) return 0.0;
            const double w = x[rig.omega(n)];
            if (w != 0.0)
                return -std::copysign(string_.params().kinetic_ratio * rig.node_radius()[n] *
                                          rig.wall_static_limit(nodes.size() - 1), w);
            double s = 0.0, a = 0.0;
            rig.loads(t, x, modes, n, s, a);
            return -s;
        }
    }

    TorsionalString string_;
    StringTreatment treatment_;
    std::variant<std::monostate, ExactString, ExactStringOnBottom> exact_;
};

}  // namespace frictionsim
