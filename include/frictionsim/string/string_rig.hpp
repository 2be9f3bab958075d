// A drill string on the event-driven engine (issue 13, item 3): the lumped string of sections.hpp (N elements,
// node 0 at the top, node N at the bit), in torsion and optionally axially, sized at run time.
//   J_i dw_i/dt = tau_i - tau_{i-1} - k_t J_s,i w_i [+ T_m at node 0] - T_wall,i [- T_bit at node N]
//   m_i dv_i/dt = F_i - F_{i-1} + w_b,i cos I_i [- H at node 0] [+ F_x sin(2 pi f_x t) at node k] - F_wall,i [- W]
//   tau_e = k_e (th_{e+1} - th_e) + beta k_e (w_{e+1} - w_e), and the same for the axial force F_e with E A / dx
// (structural damping proportional to stiffness: modal damping ratio beta w / 2 at frequency w; k_t, damping_rate,
// Aarsnes & Shor's viscous damping against absolute rotation, k_t rho J w per unit length, i.e. k_t times node i's
// string inertia J_s,i (without the drive's and the BHA's: TorsionalString's C(i, i)); positions and axial speeds
// positive down the hole).
//  * the top drive (top_drive.hpp, the Drive parameter): a motor whose torque T_m acts on node 0 and whose inertia
//    adds to it (PiTopDrive: paper 001's PI speed control with a torque limit), or a prescribed surface speed
//    (w_0 = w_set held, the torque it takes recorded as work), or a user's own type of the drive concept. The
//    default, TopDriveChoice, picks PiTopDrive or PrescribedSpeed from StringRigSetup::top_drive; both ramp the
//    set speed as w_set (1 - exp(-t / T_SP)) (setpoint_time_constant; 0: a step). With control_period T_c > 0 the
//    PI is SampledPiTopDrive: sampled at t = k T_c (events "top_drive.sample", where the drive's jump map updates
//    its held torque, integral and filtered set-point), the torque held between samples.
//  * hoisting (Hoisting): the top node moves at the hook speed, or the hook load H holds it up.
//  * the hole's inclination I_i at each node: the straight hole's, or given per node (a surveyed well:
//    string_geometry.hpp builds the set-up from a Survey).
//  * wall contacts at chosen nodes with a normal force each (given, e.g. the soft-string side forces of a curved
//    well, or the node's buoyed weight w_b sin I_i; w_b from the string's density minus the mud's). Torsion-only
//    runs: any law of the library at the pipe's outer radius through DiscContact (contact/disc_contact.hpp: exact
//    per-contact stick and slip, state laws' kinks); with axial motion the friction acts against the resultant
//    sliding velocity (wall_contact.hpp, paper 000's friction vector: stick caught at stick_speed, slow slip below
//    it). The string's contacts couple only through its springs and dampers, never rigidly, so the force that
//    holds a stuck node is known from the state and each contact's stick condition is its own (no joint
//    complementarity problem is needed at a switch).
//  * the bit (bit.hpp) at node N, any bit law in (bit speed, weight on bit) -> torque, through DiscContact.
// States, node by node so that the Jacobian is banded: the drive's (speed_error_integral; a sampled PI's also
// held_motor_torque, sampled_setpoint, next_sample), then per node theta_i, omega_i,
// [u_i, v_i], [the wall law's states], [slip_axis_i: the planar contact's reference axis, axial runs with a wall law
// that remembers reversals (wall_contact.hpp)], then the bit law's states and six work integrals that close the balance
//   drive_work + hoist_work + excitation_work = change of (kinetic + elastic + gravity potential energy)
//                                               + wall_friction_work + damping_work + bit_work
// (damping_work: the elements' dampers' and k_t's).
// The work integrals do not feed back, and their rows (which read every node) are left out of the analytic
// Jacobian: they are the system's quadrature rows (quadrature_offset(), solve/jacobian.hpp), which enter CVODE's
// Newton iteration linearly and which RODAS4 applies by a directional difference.
// Modes (ContactModes): one per wall contact, then the bit's, then the top drive's when it has switching
// functions (PiTopDrive: -2 .. 2, see top_drive.hpp). The Result's mode column counts the stuck wall contacts; events name the node.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../contact/disc_contact.hpp"
#include "../detail/validate.hpp"
#include "../parameters.hpp"
#include "../solve/jacobian.hpp"
#include "../solve/root_location.hpp"
#include "../solve/system_size.hpp"
#include "../bits/bit.hpp"
#include "scale.hpp"
#include "sections.hpp"
#include "string_rig_params.hpp"
#include "top_drive.hpp"
#include "../contact/wall_contact.hpp"

namespace frictionsim {

template <class WallLaw, class Bit = OffBottom, class Drive = TopDriveChoice>
class StringRig {
    static_assert(check_friction_law<WallLaw>(), "StringRig<WallLaw, Bit>: WallLaw must meet the FrictionLaw concept");
    static_assert(check_bit<Bit>(), "StringRig<WallLaw, Bit>: Bit must meet the bit interface (bits/bit.hpp)");
    static_assert(check_top_drive<Drive>(),
                  "StringRig<WallLaw, Bit, Drive>: Drive must meet the drive concept (string/top_drive.hpp)");
    using Wall1 = DiscContact<WallLaw>;
    using Wall2 = PlanarWallContact<WallLaw>;
    using BitContact = DiscContact<Bit>;
    static constexpr std::size_t Z = WallLaw::state_count, ZB = Bit::state_count;
    static constexpr std::size_t A = Wall2::axis_states;  ///< per node in axial runs: the reference axis phi
    static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();
    static constexpr double gravity = 9.80665;

public:
    using mode_type = ContactModes;
    using Params = StringRigParams;
    static constexpr bool on_bottom = bit_touches_rock<Bit>();
    static constexpr bool stiff = declares_stiff<WallLaw>::value;
    /// Offsets of the work integrals after work_offset().
    enum Work : std::size_t { drive_work, hoist_work, excitation_work, wall_friction_work, damping_work, bit_work };
    static constexpr std::size_t work_count = 6;

    using drive_type = Drive;

    /// The default drive: Drive(params, setup) where it takes them (TopDriveChoice), else Drive{}.
    StringRig(const DrillString& string, const StringRigParams& p, StringRigSetup setup, WallLaw law, Bit bit = Bit{})
        : StringRig(string, p, setup, std::move(law), std::move(bit), default_drive(p, setup)) {}
    /// A given drive (its own parameters: StringRigParams' drive fields are not read).
    StringRig(const DrillString& string, const StringRigParams& p, StringRigSetup setup, WallLaw law, Bit bit,
              Drive drive)
        : p_(p), setup_(std::move(setup)), law_(std::move(law)), bit_(std::move(bit)), drive_(std::move(drive)) {
        constexpr const char* who = "StringRig";
        validate_fields(who, p_, StringRigParams::fields());
        // the BHA's weight and inertia join node N's sums: finite with a margin, else blamed here (not as the node's
        // normal force)
        detail::require_representable(who, p_, StringRigParams::fields(), {"end_mass"}, 1e3 * gravity * p_.end_mass,
                                      "1e3 times the BHA's weight g m_end [N]", false);
        detail::require_representable(who, p_, StringRigParams::fields(), {"end_inertia"}, 1e3 * p_.end_inertia,
                                      "1e3 times the BHA's inertia J_end [kg m^2]", false);
        drive_states_ = drive_.state_count();
        if (drive_states_ > kMaxDriveStates)
            detail::reject(who, "drive", "with at most kMaxDriveStates states", static_cast<double>(drive_states_));
        if (setup_.elements == 0) detail::reject(who, "elements", "at least 1", 0.0);
        const std::size_t n = setup_.elements;
        lumped_ = string.lump(n);
        for (const PipeSection& s : string.sections())
            if (!(p_.mud_density < s.density))
                detail::reject(who, "mud_density", "below every section's steel density (buoyed weight > 0)",
                               p_.mud_density);
        axial_ = setup_.axial;
        block_ = 2 + (axial_ ? 2 + A : 0) + Z;
        // contact nodes
        std::vector<std::size_t>& nodes = setup_.contact_nodes;
        if (!setup_.wall_contacts) nodes.clear();
        else if (nodes.empty())
            for (std::size_t i = 1; i <= n; ++i)
                if (i < n || !on_bottom) nodes.push_back(i);
        for (std::size_t c = 0; c < nodes.size(); ++c) {
            const double v = static_cast<double>(nodes[c]);
            if (nodes[c] == 0 || nodes[c] > n)
                detail::reject(who, "contact_nodes", "in 1..N (node 0 is the top drive's)", v);
            if (on_bottom && nodes[c] == n)
                detail::reject(who, "contact_nodes", "below N with the bit on bottom (node N carries the bit)", v);
            if (c > 0 && !(nodes[c] > nodes[c - 1])) detail::reject(who, "contact_nodes", "increasing", v);
        }
        if (setup_.excitation_node > n)
            detail::reject(who, "excitation_node", "in 0..N", static_cast<double>(setup_.excitation_node));
        // node data
        const double dx = lumped_.element_length;
        inertia_ = lumped_.node_inertia;
        mass_ = lumped_.node_mass;
        inertia_[0] += drive_.inertia();
        inertia_[n] += p_.end_inertia;
        mass_[n] += p_.end_mass;
        std::vector<PipeSection> buoyed = string.sections();
        for (PipeSection& s : buoyed) s.density -= p_.mud_density;
        std::vector<double> buoyed_mass = DrillString(buoyed).lump(n).node_mass;
        buoyed_mass[n] += p_.end_mass * (1.0 - p_.mud_density / string.sections().back().density);
        std::vector<double>& incline = setup_.node_inclinations;
        if (incline.empty()) incline.assign(n + 1, p_.inclination);
        else if (incline.size() != n + 1)
            detail::reject(who, "node_inclinations", "one per node (N + 1)", static_cast<double>(incline.size()));
        for (double a : incline)
            if (!(a >= 0.0 && a <= pi)) detail::reject(who, "node_inclinations", "in [0, pi] rad", a);
        weight_.resize(n + 1);
        radius_.assign(n + 1, 0.0);
        for (std::size_t i = 0; i <= n; ++i) {
            weight_[i] = buoyed_mass[i] * gravity * std::cos(incline[i]);
            double top = 0.0;
            const double at = dx * static_cast<double>(i);
            for (const PipeSection& s : string.sections()) {  // a node on a boundary touches with the larger OD
                if (at >= top - 1e-9 * dx && at <= top + s.length + 1e-9 * dx)
                    radius_[i] = std::max(radius_[i], 0.5 * s.outer_diameter);
                top += s.length;
            }
        }
        std::vector<double>& normal = setup_.normal_forces;
        if (normal.empty()) {
            for (std::size_t i : nodes) normal.push_back(buoyed_mass[i] * gravity * std::sin(incline[i]));
        } else if (normal.size() != nodes.size()) {
            detail::reject(who, "normal_forces", "one per contact node", static_cast<double>(normal.size()));
        }
        for (double f : normal)
            if (!(std::isfinite(f) && f >= 0.0)) detail::reject(who, "normal_forces", "non-negative and finite", f);
        contact_of_.assign(n + 1, npos);
        for (std::size_t c = 0; c < nodes.size(); ++c) {
            contact_of_[nodes[c]] = c;
            if (axial_) walls2_.emplace_back(law_, radius_[nodes[c]], normal[c], p_.stick_speed);
            else walls1_.emplace_back(law_, radius_[nodes[c]], normal[c]);
        }
        if constexpr (on_bottom) bit_contact_.emplace_back(bit_, 1.0, bit_.weight_on_bit());
        // mode slots and guards
        contacts_ = nodes.size();
        bit_slot_ = contacts_;
        drive_slot_ = bit_slot_ + (on_bottom ? 1 : 0);
        slots_ = drive_slot_ + (drive_has_slot() ? 1 : 0);
        wall_guards_ = axial_ ? Wall2::guard_count : Wall1::guard_count;
        for (std::size_t c = 0; c < contacts_; ++c)
            for (std::size_t k = 0; k < wall_guards_; ++k) add_guard(c, k);
        if constexpr (on_bottom)
            for (std::size_t k = 0; k < BitContact::guard_count; ++k) add_guard(bit_slot_, k);
        for (std::size_t k = 0; k < drive_guard_count(); ++k) add_guard(drive_slot_, k);
        start_ = std::vector<double>(state_size(), 0.0);
        for (std::size_t i = 0; i <= n; ++i) {
            start_[omega(i)] = i == 0 && drive_.holds_speed() ? drive_held_speed(drive_, 0.0) : p_.initial_speed;
            if (axial_)
                start_[speed(i)] = i == 0 && setup_.hoisting == Hoisting::hook_speed ? p_.hook_speed
                                                                                     : p_.initial_axial_speed;
            if (axial_ && A > 0)  // the reference axis along the initial sliding (axial when at rest)
                start_[law_state(i) + Z] = std::atan2(radius_[i] * start_[omega(i)], start_[speed(i)]);
        }
    }

    // ---- layout -------------------------------------------------------------------------------------------
    std::size_t elements() const { return setup_.elements; }
    std::size_t state_size() const { return work_offset() + work_count; }
    std::size_t guard_count() const { return guard_slot_.size(); }
    std::size_t drive_state(std::size_t j) const { return j; }  ///< the drive's states come first
    std::size_t theta(std::size_t node) const { return drive_states_ + node * block_; }
    std::size_t omega(std::size_t node) const { return drive_states_ + 1 + node * block_; }
    std::size_t position(std::size_t node) const { return drive_states_ + 2 + node * block_; }  ///< u_i (axial runs)
    std::size_t speed(std::size_t node) const { return drive_states_ + 3 + node * block_; }     ///< v_i (axial runs)
    std::size_t law_state(std::size_t node) const { return drive_states_ + node * block_ + (axial_ ? 4 : 2); }
    std::size_t bit_state() const { return drive_states_ + (setup_.elements + 1) * block_; }
    std::size_t work_offset() const { return bit_state() + ZB; }
    /// The work integrals are the quadrature rows (solve/jacobian.hpp): no derivative reads them.
    std::size_t quadrature_offset() const { return work_offset(); }
    /// The PI integral's index (PiTopDrive's one state, SampledPiTopDrive's first, the default drive's first).
    static constexpr std::size_t speed_error_integral = 0;

    const StringRigParams& params() const { return p_; }
    const StringRigSetup& setup() const { return setup_; }
    const LumpedString& lumped() const { return lumped_; }
    const std::vector<double>& node_inertia() const { return inertia_; }  ///< with the drive's at node 0
    const std::vector<double>& node_mass() const { return mass_; }
    const std::vector<double>& node_radius() const { return radius_; }
    /// Normal force of each contact, in contact_nodes order.
    const std::vector<double>& normal_forces() const { return setup_.normal_forces; }
    const std::vector<std::size_t>& contact_nodes() const { return setup_.contact_nodes; }
    /// The static limit F_s of contact c, N (its law's at its normal force; 0 for a state law: it never sticks).
    double wall_static_limit(std::size_t c) const {
        if constexpr (WallLaw::has_stick) return law_.static_limit(setup_.normal_forces[c]);
        else return (void)c, 0.0;
    }
    /// Each node's hole inclination, rad (node_inclinations, or the straight hole's at every node).
    const std::vector<double>& node_inclinations() const { return setup_.node_inclinations; }
    /// w_b,i cos I_i, N: each node's buoyed weight along the hole (with m_end's at node N).
    const std::vector<double>& axial_weights() const { return weight_; }
    const Bit& bit() const { return bit_; }
    const Drive& drive() const { return drive_; }

    /// Replaces the state at t = 0 (size state_size()).
    void set_initial_state(std::vector<double> x) {
        if (x.size() != state_size())
            detail::reject("StringRig", "initial_state", "of size state_size()", static_cast<double>(x.size()));
        for (double v : x)
            if (!std::isfinite(v)) detail::reject("StringRig", "initial_state", "finite", v);
        start_ = std::move(x);
    }
    std::vector<double> initial_state() const { return start_; }
    /// initial_state() with the axial positions of the string hanging at rest from node 0 without wall friction:
    /// each element stretched by what it carries, the buoyed weight along the hole below it less the weight on
    /// bit, so that no contact needs friction to hold its node (an axial run then starts without a transient).
    std::vector<double> hanging_state() const {
        std::vector<double> x = start_;
        if (!axial_) return x;
        const std::size_t n = setup_.elements;
        std::vector<double> tension(n, 0.0);
        double below = on_bottom ? -bit_.weight_on_bit() : 0.0;
        for (std::size_t e = n; e-- > 0;) {
            below += weight_[e + 1];
            tension[e] = below;
        }
        x[position(0)] = 0.0;
        for (std::size_t e = 0; e < n; ++e)
            x[position(e + 1)] = x[position(e)] + tension[e] / lumped_.axial_stiffness[e];
        return x;
    }

    // ---- loads and energies ---------------------------------------------------------------------------------
    /// Element e's torque tau_e (spring + damper), N m: what the string below pulls node e forward with.
    double element_torque(const double* x, std::size_t e) const {
        const double k = lumped_.torsional_stiffness[e];
        return k * (x[theta(e + 1)] - x[theta(e)]) + p_.damping_time * k * (x[omega(e + 1)] - x[omega(e)]);
    }
    /// Element e's axial force (tension positive), N.
    double element_tension(const double* x, std::size_t e) const {
        if (!axial_) return 0.0;
        const double k = lumped_.axial_stiffness[e];
        return k * (x[position(e + 1)] - x[position(e)]) + p_.damping_time * k * (x[speed(e + 1)] - x[speed(e)]);
    }
    /// k_t J_s,i w_i, N m: node i's viscous torque against its absolute rotation (damping_rate).
    double rotation_damping(const double* x, std::size_t i) const {
        return p_.damping_rate * lumped_.node_inertia[i] * x[omega(i)];
    }
    /// What the drive sees of node 0 at t (string_torque: everything on node 0 but the motor).
    DriveInput drive_input(double t, const double* x, double string_torque) const {
        return {x + drive_state(0), x[omega(0)], string_torque, inertia_[0], t};
    }
    DriveInput drive_input(double t, const double* x) const {
        double s = element_torque(x, 0);
        if (p_.damping_rate > 0.0) s -= rotation_damping(x, 0);
        return drive_input(t, x, s);
    }
    /// The drive's mode (0 for a drive without switching functions).
    int drive_mode(const ContactModes& mode) const { return drive_has_slot() ? mode[drive_slot_] : 0; }
    /// The motor's torque T_m on node 0, N m (0 for a drive that holds the speed: surface_torque() is what it takes).
    double motor_torque(double t, const double* x, const ContactModes& mode) const {
        return drive_.holds_speed() ? 0.0 : drive_.torque(drive_input(t, x), drive_mode(mode));
    }
    double excitation_force(double t) const {
        return p_.excitation_amplitude * std::sin(2.0 * pi * p_.excitation_frequency * t);
    }
    /// The torque S and axial force P on node i from everything but its own wall contact and the bit's torque.
    void loads(double t, const double* x, const ContactModes& mode, std::size_t i, double& torque, double& axial) const {
        ElementLoads above;
        if (i > 0) above = element_loads(x, i - 1);
        loads_between(t, x, mode, i, above, element_loads(x, i), torque, axial);
    }
    /// The torque the surface applies, N m: the motor's, or what holds the prescribed speed.
    double surface_torque(double t, const double* x, const ContactModes& mode) const {
        if (!drive_.holds_speed()) return motor_torque(t, x, mode);
        double s = 0.0, a = 0.0;
        loads(t, x, mode, 0, s, a);
        return held_torque(t, s);
    }
    /// What holds node 0 at the drive's speed against the loads S_0 on it: J_0 dw_set/dt - S_0, N m.
    double held_torque(double t, double s) const {
        const double a = drive_held_acceleration(drive_, t);
        return a != 0.0 ? inertia_[0] * a - s : -s;
    }
    /// The hook's force on the string, N, positive up: H, or what holds the prescribed hook speed.
    double hook_force(double t, const double* x, const ContactModes& mode) const {
        if (setup_.hoisting == Hoisting::hook_load) return p_.hook_load;
        double s = 0.0, a = 0.0;
        loads(t, x, mode, 0, s, a);
        return a;
    }
    double kinetic_energy(const double* x) const {
        double e = 0.0;
        for (std::size_t i = 0; i <= setup_.elements; ++i) {
            e += 0.5 * inertia_[i] * x[omega(i)] * x[omega(i)];
            if (axial_) e += 0.5 * mass_[i] * x[speed(i)] * x[speed(i)];
        }
        return e;
    }
    double elastic_energy(const double* x) const {
        double e = 0.0;
        for (std::size_t k = 0; k < setup_.elements; ++k) {
            const double twist = x[theta(k + 1)] - x[theta(k)];
            e += 0.5 * lumped_.torsional_stiffness[k] * twist * twist;
            if (axial_) {
                const double stretch = x[position(k + 1)] - x[position(k)];
                e += 0.5 * lumped_.axial_stiffness[k] * stretch * stretch;
            }
        }
        return e;
    }
    /// - sum w_b,i cos I u_i, J: the buoyed weight's potential energy (0 in torsion-only runs).
    double gravity_potential(const double* x) const {
        double e = 0.0;
        if (axial_)
            for (std::size_t i = 0; i <= setup_.elements; ++i) e -= weight_[i] * x[position(i)];
        return e;
    }

    // ---- the HybridSystem -----------------------------------------------------------------------------------
    void rhs(double t, const double* x, const ContactModes& mode, double* dxdt) const {
        rhs_guards(t, x, mode, dxdt, nullptr);
    }
    void guards(double t, const double* x, const ContactModes& mode, double* g) const {
        const std::size_t n = setup_.elements;
        std::size_t k = 0;
        ElementLoads above, below = element_loads(x, 0);
        for (std::size_t i = 0; i <= n; ++i) {
            if (i > 0) {
                above = below;
                below = element_loads(x, i);
            }
            const std::size_t c = contact_of_[i];
            const bool has_bit = on_bottom && i == n;
            if (c == npos && !has_bit) continue;
            double s = 0.0, a = 0.0;
            loads_between(t, x, mode, i, above, below, s, a);
            if (c != npos) {
                if (axial_) {
                    walls2_[c].guards(x[omega(i)], x[speed(i)], planar_loads(x, i, s, a), x + law_state(i), mode[c],
                                      inertia_[i], mass_[i], g + k);
                } else {
                    walls1_[c].guards(x[omega(i)], s, x + law_state(i), mode[c], inertia_[i], g + k);
                }
                k += wall_guards_;
            }
            if constexpr (on_bottom)
                if (has_bit) {
                    bit_contact_[0].guards(x[omega(i)], s, x + bit_state(), mode[bit_slot_], inertia_[i], g + k);
                    k += BitContact::guard_count;
                }
        }
        if (drive_has_slot())
            drive_.guards(drive_input(t, x), top_acceleration(t, x, mode), drive_mode(mode), g + k);
    }

    /// The states guard i reads (root_location.hpp's local guards): its node's and its neighbours' blocks (node
    /// 0's with the drive's states; node N's with the bit's).
    GuardReads guard_reads(std::size_t i) const {
        const std::size_t node = guard_node(guard_slot_[i]), n = setup_.elements;
        return {node >= 1 ? theta(node - 1) : 0, node + 2 <= n ? theta(node + 2) : work_offset()};
    }
    /// Guard i alone, as guards() gives it.
    double guard(std::size_t i, double t, const double* x, const ContactModes& mode) const {
        const std::size_t slot = guard_slot_[i];
        std::array<double, kMaxSlotGuards> g{};
        if (slot == drive_slot_ && drive_has_slot() && !(on_bottom && slot == bit_slot_)) {
            drive_.guards(drive_input(t, x), top_acceleration(t, x, mode), drive_mode(mode), g.data());
            return g[guard_rank_[i]];
        }
        const std::size_t node = guard_node(slot);
        double s = 0.0, a = 0.0;
        loads(t, x, mode, node, s, a);
        if (slot < contacts_) {
            if (axial_)
                walls2_[slot].guards(x[omega(node)], x[speed(node)], planar_loads(x, node, s, a), x + law_state(node),
                                     mode[slot], inertia_[node], mass_[node], g.data());
            else
                walls1_[slot].guards(x[omega(node)], s, x + law_state(node), mode[slot], inertia_[node], g.data());
        } else if constexpr (on_bottom) {
            bit_contact_[0].guards(x[omega(node)], s, x + bit_state(), mode[bit_slot_], inertia_[node], g.data());
        }
        return g[guard_rank_[i]];
    }

    void rhs_guards(double t, const double* x, const ContactModes& mode, double* dx, double* g) const {
        const std::size_t n = setup_.elements;
        double power[work_count] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        std::size_t k = 0;
        DriveInput top;
        ElementLoads above, below = element_loads(x, 0);
        for (std::size_t i = 0; i <= n; ++i) {
            if (i > 0) {  // each element's torque and tension once: the node above's below is this node's above
                above = below;
                below = element_loads(x, i);
            }
            const double w = x[omega(i)], v = axial_ ? x[speed(i)] : 0.0;
            double s = 0.0, a = 0.0;
            loads_between(t, x, mode, i, above, below, s, a);
            dx[theta(i)] = w;
            double dw = s / inertia_[i], dv = a / mass_[i];
            for (std::size_t j = 0; j < Z + (axial_ ? A : 0); ++j) dx[law_state(i) + j] = 0.0;
            const std::size_t c = contact_of_[i];
            if (c != npos) {
                if (axial_) {
                    const PlanarResponse r =
                        walls2_[c].respond(w, v, s, a, x + law_state(i), mode[c], inertia_[i], mass_[i]);
                    dw = r.angular_acceleration;
                    dv = r.axial_acceleration;
                    power[wall_friction_work] += r.torque * w + r.axial_force * v;
                    walls2_[c].state_derivative(w, v, x + law_state(i), mode[c], dx + law_state(i));
                    if (g != nullptr)
                        walls2_[c].guards(w, v, planar_loads(x, i, s, a), x + law_state(i), mode[c], inertia_[i],
                                          mass_[i], g + k);
                } else {
                    const DiscResponse r = walls1_[c].respond(w, s, x + law_state(i), mode[c], inertia_[i]);
                    dw = r.acceleration;
                    power[wall_friction_work] += r.torque * w;
                    walls1_[c].state_derivative(w, x + law_state(i), mode[c], dx + law_state(i));
                    if (g != nullptr) walls1_[c].guards(w, s, x + law_state(i), mode[c], inertia_[i], g + k);
                }
                k += wall_guards_;
            }
            if constexpr (on_bottom) {
                if (i == n) {
                    const DiscResponse r = bit_contact_[0].respond(w, s, x + bit_state(), mode[bit_slot_], inertia_[i]);
                    dw = r.acceleration;
                    power[bit_work] += r.torque * w + (axial_ ? bit_.weight_on_bit() * v : 0.0);
                    if constexpr (ZB > 0) bit_contact_[0].state_derivative(w, x + bit_state(), mode[bit_slot_],
                                                                           dx + bit_state());
                    if (g != nullptr) bit_contact_[0].guards(w, s, x + bit_state(), mode[bit_slot_], inertia_[i], g + k);
                    k += BitContact::guard_count;
                }
            }
            if (i == 0) {
                double string_torque = below.torque - above.torque;
                if (p_.damping_rate > 0.0) string_torque -= rotation_damping(x, 0);
                top = drive_input(t, x, string_torque);
                if (!drive_.holds_speed()) {
                    power[drive_work] = drive_.torque(top, drive_mode(mode)) * w;
                } else {
                    power[drive_work] = held_torque(t, s) * w;  // the torque that holds w_0 at w_set(t)
                    dw = drive_held_acceleration(drive_, t);
                }
                if (axial_) {
                    if (setup_.hoisting == Hoisting::hook_speed) {
                        power[hoist_work] = -a * v;
                        dv = 0.0;
                    } else {
                        power[hoist_work] = -p_.hook_load * v;
                    }
                }
            }
            if (axial_ && i == setup_.excitation_node) power[excitation_work] = excitation_force(t) * v;
            dx[omega(i)] = dw;
            if (axial_) {
                dx[position(i)] = v;
                dx[speed(i)] = dv;
            }
            if (i < n) {
                const double dw_e = x[omega(i + 1)] - w;
                double d = p_.damping_time * lumped_.torsional_stiffness[i] * dw_e * dw_e;
                if (axial_) {
                    const double dv_e = x[speed(i + 1)] - v;
                    d += p_.damping_time * lumped_.axial_stiffness[i] * dv_e * dv_e;
                }
                power[damping_work] += d;
            }
            if (p_.damping_rate > 0.0) power[damping_work] += rotation_damping(x, i) * w;
        }
        drive_.rates(top, dx[omega(0)], drive_mode(mode), dx + drive_state(0));
        if (g != nullptr && drive_has_slot()) drive_.guards(top, dx[omega(0)], drive_mode(mode), g + k);
        for (std::size_t j = 0; j < work_count; ++j) dx[work_offset() + j] = power[j];
    }

    /// Every node's coupling reaches its neighbours' blocks only (node i's accelerations read nodes i - 1 .. i + 1);
    /// node 0's reads the drive's states, theirs omega_0, and where they follow node 0's acceleration (the PI drive
    /// holding its limit) that row, which reaches omega_1.
    Bandwidths jacobian_bandwidths() const {
        const std::size_t d = drive_states_;
        return {std::max(block_ + 1, d + 1), std::max(block_ + 1, d + 1 + (drive_.rates_follow_acceleration() ? block_ : 0))};
    }

    /// The analytic Jacobian inside the band (the work integrals' rows left out, see the header comment).
    template <class Add, class L = WallLaw, class B = Bit, class D = Drive,
              std::enable_if_t<law_has_partials_v<L> && law_has_partials_v<B> && top_drive_has_partials_v<D>, int> = 0>
    void jacobian_entries(double t, const double* x, const ContactModes& mode, Add&& add) const {
        const DriveInput top = drive_input(t, x);
        const int m = drive_mode(mode);
        std::array<double, kMaxDriveStates> follow{}, d_state{};  // d(dz_j/dt)/d(dw_0/dt); a row's d/dz
        bool follows = false;
        for (std::size_t j = 0; j < drive_states_; ++j) {
            double d_speed = 0.0;
            drive_.rate_partials(top, m, j, d_speed, d_state.data(), follow[j]);
            follows = follows || follow[j] != 0.0;
        }
        if (follows) {  // those drive rows take their share of node 0's acceleration row (the PI drive at its limit)
            const std::size_t row = omega(0);
            node_jacobian_entries(t, x, mode, [&](std::size_t i, std::size_t j, double v) {
                add(i, j, v);
                if (i == row)
                    for (std::size_t q = 0; q < drive_states_; ++q)
                        if (follow[q] != 0.0) add(drive_state(q), j, follow[q] * v);
            });
        } else {
            node_jacobian_entries(t, x, mode, add);
        }
        for (std::size_t j = 0; j < drive_states_; ++j) {  // the drive's rows: d/dw_0, d/dz
            double d_speed = 0.0, d_acceleration = 0.0;
            drive_.rate_partials(top, m, j, d_speed, d_state.data(), d_acceleration);
            if (d_speed != 0.0) add(drive_state(j), omega(0), d_speed);
            for (std::size_t q = 0; q < drive_states_; ++q)
                if (d_state[q] != 0.0) add(drive_state(j), drive_state(q), d_state[q]);
        }
    }

private:
    template <class Add>
    void node_jacobian_entries(double t, const double* x, const ContactModes& mode, Add&& add) const {
        const std::size_t n = setup_.elements;
        const double beta = p_.damping_time;
        for (std::size_t i = 0; i <= n; ++i) {
            add(theta(i), omega(i), 1.0);
            if (axial_) add(position(i), speed(i), 1.0);
            const double w = x[omega(i)];
            double s = 0.0, a = 0.0;
            loads(t, x, mode, i, s, a);
            const std::size_t c = contact_of_[i];
            // how the rotation's and the axial motion's accelerations follow S and P (0 while held)
            double torque_share = 1.0, axial_share = 1.0;
            const bool top_rotation_held = i == 0 && drive_.holds_speed();
            const bool top_axial_held = i == 0 && setup_.hoisting == Hoisting::hook_speed;
            if (c != npos) {
                if (axial_) {
                    const int m = mode[c];
                    if (Wall2::set_valued && m == Wall2::stick_mode) torque_share = axial_share = 0.0;
                    const PlanarPartials<Z> d = walls2_[c].partials(w, x[speed(i)], x + law_state(i), m);
                    const double J = inertia_[i], M = mass_[i], r = radius_[i];
                    add(omega(i), omega(i), -r * d.tangential_w / J);
                    add(omega(i), speed(i), -r * d.tangential_v / J);
                    add(speed(i), omega(i), -d.axial_w / M);
                    add(speed(i), speed(i), -d.axial_v / M);
                    for (std::size_t j = 0; j < Z; ++j) {
                        add(omega(i), law_state(i) + j, -r * d.tangential_z[j] / J);
                        add(speed(i), law_state(i) + j, -d.axial_z[j] / M);
                        add(law_state(i) + j, omega(i), d.rate_w[j]);
                        add(law_state(i) + j, speed(i), d.rate_v[j]);
                        for (std::size_t q = 0; q < Z; ++q) add(law_state(i) + j, law_state(i) + q, d.rate_z[j][q]);
                    }
                } else {
                    const DiscPartials<Z> d = walls1_[c].partials(w, s, x + law_state(i), mode[c], inertia_[i]);
                    torque_share = 1.0 - d.torque_shaft;
                    add(omega(i), omega(i), -d.torque_speed / inertia_[i]);
                    for (std::size_t j = 0; j < Z; ++j) {
                        add(omega(i), law_state(i) + j, -d.torque_state[j] / inertia_[i]);
                        add(law_state(i) + j, omega(i), d.rate_speed[j]);
                        for (std::size_t q = 0; q < Z; ++q) add(law_state(i) + j, law_state(i) + q, d.rate_state[j][q]);
                    }
                }
            }
            if constexpr (on_bottom) {
                if (i == n) {
                    const DiscPartials<ZB> d = bit_contact_[0].partials(w, s, x + bit_state(), mode[bit_slot_], inertia_[i]);
                    torque_share = 1.0 - d.torque_shaft;
                    add(omega(i), omega(i), -d.torque_speed / inertia_[i]);
                    for (std::size_t j = 0; j < ZB; ++j) {
                        add(omega(i), bit_state() + j, -d.torque_state[j] / inertia_[i]);
                        add(bit_state() + j, omega(i), d.rate_speed[j]);
                        for (std::size_t q = 0; q < ZB; ++q) add(bit_state() + j, bit_state() + q, d.rate_state[j][q]);
                    }
                }
            }
            if (top_rotation_held) torque_share = 0.0;
            if (top_axial_held) axial_share = 0.0;
            // S = tau_i - tau_{i-1} (+ T_m): d/dth and d/dw of the neighbouring elements
            if (torque_share != 0.0) {
                const double f = torque_share / inertia_[i];
                add_element_partials(add, i, f, beta, lumped_.torsional_stiffness, &StringRig::theta, &StringRig::omega);
                if (p_.damping_rate > 0.0) add(omega(i), omega(i), -f * p_.damping_rate * lumped_.node_inertia[i]);
                if (i == 0 && !drive_.holds_speed()) {  // T_m's partials
                    std::array<double, kMaxDriveStates> d_state{};
                    double d_speed = 0.0;
                    drive_.torque_partials(drive_input(t, x), drive_mode(mode), d_speed, d_state.data());
                    if (d_speed != 0.0) add(omega(0), omega(0), f * d_speed);
                    for (std::size_t j = 0; j < drive_states_; ++j)
                        if (d_state[j] != 0.0) add(omega(0), drive_state(j), f * d_state[j]);
                }
            }
            if (axial_ && axial_share != 0.0)
                add_element_partials(add, i, axial_share / mass_[i], beta, lumped_.axial_stiffness,
                                     &StringRig::position, &StringRig::speed);
        }
    }

    /// The partials of node i's rate row (`rate`: omega or v) through its two elements, k_e (x_{e+1} - x_e) +
    /// beta k_e (r_{e+1} - r_e) with x the position (`position`: theta or u), each scaled by f = share / inertia:
    /// the torsional and the axial rows are the same chain, one stiffness vector each.
    template <class Add>
    void add_element_partials(Add& add, std::size_t i, double f, double beta, const std::vector<double>& stiffness,
                              std::size_t (StringRig::*position)(std::size_t) const,
                              std::size_t (StringRig::*rate)(std::size_t) const) const {
        const std::size_t row = (this->*rate)(i);
        const auto element = [&](std::size_t other, double k) {
            add(row, (this->*position)(other), f * k);
            add(row, (this->*position)(i), -f * k);
            add(row, (this->*rate)(other), f * beta * k);
            add(row, row, -f * beta * k);
        };
        if (i < setup_.elements) element(i + 1, stiffness[i]);
        if (i > 0) element(i - 1, stiffness[i - 1]);
    }

public:
    int guard_direction(std::size_t, const ContactModes&) const { return -1; }
    const char* guard_name(std::size_t i, const ContactModes& mode) const {
        const int m = mode[guard_slot_[i]];
        return guard_names_[i][static_cast<std::size_t>(std::clamp(m, -3, 3) + 3)].c_str();
    }
    /// Names of the codes guard_mode gives: wall contact modes as they are, the bit's + 20, the drive's + 10.
    const char* mode_name(int code) const {
        if (code >= 17 && code <= 23) return bit_mode_names[static_cast<std::size_t>(code - 17)];
        if (code >= 8 && code <= 12) return drive_.mode_name(code - 10);
        if (axial_) return Wall2::mode_name(code);
        if (!walls1_.empty()) return walls1_[0].mode_name(code);
        return contact_mode_name(code);
    }
    int mode_code(const ContactModes& mode) const {
        int stuck = 0;
        for (std::size_t c = 0; c < contacts_; ++c) stuck += mode[c] == stick;
        return stuck;
    }
    int guard_mode(std::size_t i, const ContactModes& mode) const { return slot_code(guard_slot_[i], mode); }
    /// The mode code of a slot (wall contact c < contacts, then the bit, then the drive).
    int slot_code(std::size_t slot, const ContactModes& mode) const {
        const int m = mode[slot];
        if (slot < contacts_) return m;
        if (on_bottom && slot == bit_slot_) return 20 + m;
        return 10 + m;
    }
    std::size_t contact_count() const { return contacts_; }
    std::size_t bit_slot() const { return bit_slot_; }
    std::size_t drive_slot() const { return drive_slot_; }

    ContactModes initial_mode(double t, const double* x) const {
        ContactModes mode(slots_, 0);
        if (drive_has_slot()) mode[drive_slot_] = static_cast<std::int8_t>(drive_.initial_mode(drive_input(t, x)));
        const std::size_t n = setup_.elements;
        for (std::size_t i = 0; i <= n; ++i) {
            const std::size_t c = contact_of_[i];
            if (c == npos && !(on_bottom && i == n)) continue;
            double s = 0.0, a = 0.0;
            loads(t, x, mode, i, s, a);
            if (c != npos) {
                mode[c] = static_cast<std::int8_t>(
                    axial_ ? walls2_[c].initial_mode(x[omega(i)], x[speed(i)], planar_loads(x, i, s, a),
                                                     x + law_state(i))
                           : walls1_[c].initial_mode(x[omega(i)], s, x + law_state(i), inertia_[i]));
            }
            if constexpr (on_bottom)
                if (i == n)
                    mode[bit_slot_] = static_cast<std::int8_t>(
                        bit_contact_[0].initial_mode(x[omega(i)], s, x + bit_state(), inertia_[i]));
        }
        return mode;
    }

    ContactModes switch_mode(double t, double* x, const ContactModes& mode, const int* fired) const {
        ContactModes next = mode;
        const std::size_t n = setup_.elements;
        std::size_t k = 0;
        for (std::size_t i = 0; i <= n; ++i) {
            const std::size_t c = contact_of_[i];
            const bool has_bit = on_bottom && i == n;
            if (c == npos && !has_bit) continue;
            if (c != npos) {
                if (any(fired + k, wall_guards_)) {
                    double s = 0.0, a = 0.0;
                    loads(t, x, next, i, s, a);
                    if (axial_) {
                        double lost = 0.0;
                        next[c] = static_cast<std::int8_t>(walls2_[c].switch_mode(x[omega(i)], x[speed(i)],
                                                                                  planar_loads(x, i, s, a),
                                                                                  x + law_state(i), mode[c],
                                                                                  fired + k, inertia_[i], mass_[i],
                                                                                  lost));
                        x[work_offset() + wall_friction_work] += lost;
                    } else {
                        next[c] = static_cast<std::int8_t>(walls1_[c].switch_mode(
                            t, x[omega(i)], s, x + law_state(i), mode[c], fired + k, inertia_[i]));
                    }
                }
                k += wall_guards_;
            }
            if constexpr (on_bottom) {
                if (has_bit) {
                    if (any(fired + k, BitContact::guard_count)) {
                        double s = 0.0, a = 0.0;
                        loads(t, x, next, i, s, a);
                        next[bit_slot_] = static_cast<std::int8_t>(bit_contact_[0].switch_mode(
                            t, x[omega(i)], s, x + bit_state(), mode[bit_slot_], fired + k, inertia_[i]));
                    }
                    k += BitContact::guard_count;
                }
            }
        }
        if (drive_has_slot() && any(fired + k, drive_guard_count())) {
            // the drive's states may jump (a sampled PI's sample), then its mode follows from the new states
            if constexpr (detail::top_drive_has_jump<Drive>::value)
                drive_jump(drive_, drive_input(t, x), next[drive_slot_], fired + k, x + drive_state(0));
            next[drive_slot_] =
                static_cast<std::int8_t>(drive_.switch_mode(drive_input(t, x), next[drive_slot_], fired + k));
        }
        return next;
    }

    std::vector<std::string> state_names() const {
        std::vector<std::string> names(state_size());
        for (std::size_t j = 0; j < drive_states_; ++j) names[drive_state(j)] = drive_.state_name(j);
        for (std::size_t i = 0; i <= setup_.elements; ++i) {
            const std::string tag = "_" + std::to_string(i);
            names[theta(i)] = "theta" + tag;
            names[omega(i)] = "omega" + tag;
            if (axial_) {
                names[position(i)] = "u" + tag;
                names[speed(i)] = "v" + tag;
            }
            if constexpr (Z > 0)
                for (std::size_t j = 0; j < Z; ++j) names[law_state(i) + j] = WallLaw::state_names[j] + tag;
            if (axial_ && A > 0) names[law_state(i) + Z] = "slip_axis" + tag;
        }
        if constexpr (ZB > 0)
            for (std::size_t j = 0; j < ZB; ++j) names[bit_state() + j] = std::string("bit_") + Bit::state_names[j];
        static constexpr std::array<const char*, work_count> work{"drive_work",         "hoist_work",
                                                                  "excitation_work",    "wall_friction_work",
                                                                  "damping_work",       "bit_work"};
        for (std::size_t j = 0; j < work_count; ++j) names[work_offset() + j] = work[j];
        return names;
    }

    /// The total wall friction torque, N m (sum of r_i times the circumferential friction force).
    double friction_force(double t, const double* x, const ContactModes& mode) const {
        double total = 0.0;
        const std::size_t n = setup_.elements;
        for (std::size_t i = 0; i <= n; ++i) {
            const std::size_t c = contact_of_[i];
            if (c == npos) continue;
            double s = 0.0, a = 0.0;
            loads(t, x, mode, i, s, a);
            total += axial_ ? walls2_[c].respond(x[omega(i)], x[speed(i)], s, a, x + law_state(i), mode[c],
                                                 inertia_[i], mass_[i]).torque
                            : walls1_[c].respond(x[omega(i)], s, x + law_state(i), mode[c], inertia_[i]).torque;
        }
        return total;
    }
    /// The wall contact's axial friction force at contact c, N (axial runs), in the direction of motion resisted.
    double wall_axial_force(double t, const double* x, const ContactModes& mode, std::size_t c) const {
        if (!axial_) return 0.0;
        const std::size_t i = setup_.contact_nodes[c];
        double s = 0.0, a = 0.0;
        loads(t, x, mode, i, s, a);
        return walls2_[c].respond(x[omega(i)], x[speed(i)], s, a, x + law_state(i), mode[c], inertia_[i], mass_[i])
            .axial_force;
    }
    /// The torque on bit, N m (0 off bottom).
    double bit_torque(double t, const double* x, const ContactModes& mode) const {
        if constexpr (on_bottom) {
            const std::size_t n = setup_.elements;
            double s = 0.0, a = 0.0;
            loads(t, x, mode, n, s, a);
            return bit_contact_[0].respond(x[omega(n)], s, x + bit_state(), mode[bit_slot_], inertia_[n]).torque;
        } else {
            (void)t, (void)x, (void)mode;
            return 0.0;
        }
    }

private:
    /// Element e's torque and tension (zero past the bit): what loads_between reads, computed once per element
    /// when a sweep over the nodes carries the one above (rhs_guards, guards).
    struct ElementLoads {
        double torque = 0.0, tension = 0.0;
    };
    ElementLoads element_loads(const double* x, std::size_t e) const {
        if (e >= setup_.elements) return {};
        return {element_torque(x, e), element_tension(x, e)};
    }
    /// loads() of node i from the elements above (i - 1; zero at the top) and below (i) it.
    void loads_between(double t, const double* x, const ContactModes& mode, std::size_t i, const ElementLoads& above,
                       const ElementLoads& below, double& torque, double& axial) const {
        torque = below.torque - above.torque;
        if (p_.damping_rate > 0.0) torque -= rotation_damping(x, i);
        axial = 0.0;
        if (i == 0 && !drive_.holds_speed()) torque += drive_.torque(drive_input(t, x, torque), drive_mode(mode));
        if (!axial_) return;
        axial = below.tension - above.tension + weight_[i];
        if (i == 0 && setup_.hoisting == Hoisting::hook_load) axial -= p_.hook_load;
        if (i == setup_.excitation_node) axial += excitation_force(t);
        if (on_bottom && i == setup_.elements) axial -= bit_.weight_on_bit();
    }

    /// Node i's loads (S, P) as they are and with the node itself at rest: its own velocity's share of the element
    /// dampers removed (d S / d w_i = -beta (k_{i-1} + k_i) - k_t J_s,i, the same axially without k_t). What a
    /// planar contact would have to hold once stuck (wall_contact.hpp).
    PlanarLoads planar_loads(const double* x, std::size_t i, double torque, double axial) const {
        PlanarLoads l{torque, axial, torque, axial};
        if (p_.damping_rate > 0.0) l.hold_torque += rotation_damping(x, i);
        if (p_.damping_time == 0.0) return l;
        double kt = 0.0, ka = 0.0;
        if (i > 0) {
            kt += lumped_.torsional_stiffness[i - 1];
            ka += lumped_.axial_stiffness[i - 1];
        }
        if (i < setup_.elements) {
            kt += lumped_.torsional_stiffness[i];
            ka += lumped_.axial_stiffness[i];
        }
        l.hold_torque += p_.damping_time * kt * x[omega(i)];
        l.hold_axial += p_.damping_time * ka * x[speed(i)];
        return l;
    }

    static constexpr std::array<const char*, 7> bit_mode_names{"bit_mode_-3", "bit_mode_-2", "bit_slip_negative",
                                                               "bit_stick",   "bit_slip_positive", "bit_mode_2",
                                                               "bit_mode_3"};

    static bool any(const int* fired, std::size_t count) {
        for (std::size_t j = 0; j < count; ++j)
            if (fired[j] != 0) return true;
        return false;
    }

    /// Node 0's angular acceleration (no wall contact there): what the drive's switching functions read.
    double top_acceleration(double t, const double* x, const ContactModes& mode) const {
        double torque = 0.0, axial = 0.0;
        loads(t, x, mode, 0, torque, axial);
        return torque / inertia_[0];
    }
    /// The node of a mode slot: a wall contact's, the bit's (N), the drive's (0).
    std::size_t guard_node(std::size_t slot) const {
        if (slot < contacts_) return setup_.contact_nodes[slot];
        if (on_bottom && slot == bit_slot_) return setup_.elements;
        return 0;
    }
    static constexpr std::size_t kMaxSlotGuards = 8;  ///< switching functions per slot (guard()'s scratch)
    std::size_t drive_guard_count() const { return drive_.guard_count(); }
    bool drive_has_slot() const { return drive_guard_count() > 0; }
    static Drive default_drive(const StringRigParams& p, const StringRigSetup& s) {
        if constexpr (std::is_constructible_v<Drive, const StringRigParams&, const StringRigSetup&>) return Drive(p, s);
        else return (void)p, (void)s, Drive{};
    }

    /// Guard k of slot `slot`, with its name for each mode the slot can be in (events name the node).
    void add_guard(std::size_t slot, std::size_t k) {
        if (k >= kMaxSlotGuards)
            detail::reject("StringRig", "guard_count", "at most 8 switching functions per contact or drive",
                           static_cast<double>(k + 1));
        guard_slot_.push_back(slot);
        guard_rank_.push_back(k);
        std::array<std::string, 7> names;
        for (int m = -3; m <= 3; ++m) {
            std::string name;
            if (slot < contacts_) {
                name = "node_" + std::to_string(setup_.contact_nodes[slot]) + ".";
                if (axial_) name += Wall2::guard_name(k, m);
                else name += walls1_[slot].guard_name(k, m);
            } else if (on_bottom && slot == bit_slot_) {
                if constexpr (on_bottom) name = std::string("bit.") + bit_contact_[0].guard_name(k, m);
            } else {
                name = std::string("top_drive.") + drive_.guard_name(k, m);
            }
            names[static_cast<std::size_t>(m + 3)] = std::move(name);
        }
        guard_names_.push_back(std::move(names));
    }

    StringRigParams p_;
    StringRigSetup setup_;
    WallLaw law_;
    Bit bit_;
    Drive drive_;
    std::size_t drive_states_ = 1;
    LumpedString lumped_;
    bool axial_ = false;
    std::size_t block_ = 2;
    std::vector<double> inertia_, mass_, weight_, radius_;
    std::vector<std::size_t> contact_of_;
    std::vector<Wall1> walls1_;
    std::vector<Wall2> walls2_;
    std::vector<BitContact> bit_contact_;  // one element with the bit on bottom
    std::size_t contacts_ = 0, bit_slot_ = 0, drive_slot_ = 0, slots_ = 0, wall_guards_ = 0;
    std::vector<std::size_t> guard_slot_, guard_rank_;  ///< each guard's slot and its index within the slot
    std::vector<std::array<std::string, 7>> guard_names_;
    std::vector<double> start_;
};

}  // namespace frictionsim
