// The parameters of a StringRig: the scalars in a table (StringRigParams::fields, validated by validate_fields),
// the discrete choices (element count, top-drive kind, axial motion, hoisting, contact nodes, normal forces,
// excitation node) in StringRigSetup, checked by the rig's constructor naming the member.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "../outputs.hpp"
#include "../parameters.hpp"

namespace frictionsim {

/// How the top of the string turns: a motor of inertia J_td under PI speed control with a torque limit (paper
/// 001's drive, anti-windup by conditional integration), or a prescribed surface speed (an infinitely stiff drive).
enum class TopDrive { pi_motor, prescribed_speed };
/// The axial top boundary: the hook moves at a prescribed speed, or holds a prescribed hook load.
enum class Hoisting { hook_speed, hook_load };

/// Scalar parameters. Defaults: a 60 rpm top drive on a water-based mud, a vertical hole.
struct StringRigParams {
    double damping_time = 0.0;          ///< beta, s: element damping c_e = beta k_e (torsional and axial)
    double top_drive_inertia = 500.0;   ///< J_td, kg m^2 (rotor and gearbox referred to the quill)
    double surface_speed = 6.283185307179586;  ///< w_set, rad/s (60 rpm)
    double proportional_gain = 5.0e3;   ///< k_p, N m s/rad
    double integral_gain = 2.0e3;       ///< k_i, N m/rad
    double torque_limit = 6.0e4;        ///< T_max, N m
    double mud_density = 1200.0;        ///< rho_mud, kg/m^3 (buoyancy)
    double inclination = 0.0;           ///< hole inclination from vertical, rad
    double hook_speed = 0.0;            ///< m/s along the hole, positive down (running in)
    double hook_load = 0.0;             ///< N, upwards on the top node
    double excitation_amplitude = 0.0;  ///< F_x, N: axial force F_x sin(2 pi f_x t) at the excitation node
    double excitation_frequency = 0.0;  ///< f_x, Hz
    double stick_speed = 1e-4;          ///< m/s: where an axially moving contact is caught to stick (wall_contact.hpp)
    double initial_speed = 0.0;         ///< rad/s: the whole string's rotation at t = 0
    double initial_axial_speed = 0.0;   ///< m/s: the whole string's axial speed at t = 0
    double end_inertia = 0.0;           ///< J_end, kg m^2: a rigid BHA (or bit sub) added to node N
    double end_mass = 0.0;              ///< m_end, kg: its mass (its buoyed weight joins node N's)
    double damping_rate = 0.0;          ///< k_t, 1/s: viscous torque -k_t J_i w_i at node i (J_i its string inertia)
    double setpoint_time_constant = 0.0;  ///< T_SP, s: the set speed ramps as w_set (1 - exp(-t / T_SP)); 0: a step
    double control_period = 0.0;  ///< T_c, s: 0 a continuous PI; > 0 the PI sampled every T_c, zero-order hold

    static constexpr std::array<Field<StringRigParams>, 20> fields();
    static constexpr const char* rig_name = "StringRig";  ///< as Python and the rig list name it
    /// The Result's columns beside t, the wall law's states (numbered per node, theta_3 as dahl_deflection_3) and the
    /// bit law's (bit_*): a row name_* is a state per node 0 (top) .. N (bit); u_* and v_* only in axial runs,
    /// speed_error_integral only under the PI drive, held_motor_torque, sampled_setpoint and next_sample only under
    /// the sampled PI (control_period > 0). The mode column counts the stuck wall contacts.
    static constexpr std::array<RigOutput, 17> outputs() {
        return {{
            {"friction_force", "N m", "the total wall friction torque, sum of r_i times the circumferential friction"},
            {"speed_error_integral", "rad", "the PI drive's int (w_set - w_0) dt"},
            {"held_motor_torque", "N m", "the sampled PI's torque, held between samples (control_period > 0)"},
            {"sampled_setpoint", "rad/s", "the sampled PI's filtered set-point at the last sample"},
            {"next_sample", "1", "the index k of the sampled PI's next sample, at k T_c"},
            {"theta_*", "rad", "angle of node i"},
            {"omega_*", "rad/s", "speed of node i"},
            {"u_*", "m", "axial displacement of node i (axial runs)"},
            {"v_*", "m/s", "axial speed of node i (axial runs)"},
            {"slip_axis_*", "rad", "the planar wall contact's reference axis (axial runs, a law with reversal memory)"},
            {"drive_work", "J", "the top drive's work on node 0"},
            {"hoist_work", "J", "the hook's work on the top node (axial runs)"},
            {"excitation_work", "J", "the axial excitation's work"},
            {"wall_friction_work", "J", "the wall contacts' friction work"},
            {"damping_work", "J", "the dampers' work: the elements' beta k_e and k_t's at the nodes"},
            {"bit_work", "J", "the bit's work: drive + hoist + excitation = energy change + friction + damping + bit"},
            {"mode", "1", "stuck wall contacts (a count)"},
        }};
    }
};

inline constexpr std::array<Field<StringRigParams>, 20> StringRigParams::fields() {
    using P = StringRigParams;
    return {{
        {"damping_time", "beta", "s", Rule::non_negative(), &P::damping_time,
         "Structural damping: each element's damping is beta times its stiffness (modal ratio beta w / 2)."},
        {"top_drive_inertia", "J_td", "kg m^2", Rule::positive(), &P::top_drive_inertia,
         "Top-drive inertia at the quill (PI-controlled drive)."},
        {"surface_speed", "w_set", "rad/s", Rule::finite(), &P::surface_speed,
         "Set speed of the PI drive, or the prescribed surface speed."},
        {"proportional_gain", "k_p", "N m s/rad", Rule::non_negative(), &P::proportional_gain, "PI proportional gain."},
        {"integral_gain", "k_i", "N m/rad", Rule::non_negative(), &P::integral_gain, "PI integral gain."},
        {"torque_limit", "T_max", "N m", Rule::positive(), &P::torque_limit, "Top-drive torque limit."},
        {"mud_density", "rho_mud", "kg/m^3", Rule::non_negative(), &P::mud_density,
         "Mud density (buoyancy); below the steel's."},
        {"inclination", "I", "rad", Rule::interval(0.0, 3.141592653589793), &P::inclination,
         "Hole inclination from vertical (straight hole)."},
        {"hook_speed", "v_hook", "m/s", Rule::finite(), &P::hook_speed, "Prescribed hook speed, positive down."},
        {"hook_load", "H", "N", Rule::finite(), &P::hook_load, "Prescribed hook load, upwards."},
        {"excitation_amplitude", "F_x", "N", Rule::non_negative(), &P::excitation_amplitude,
         "Axial excitation amplitude (hydraulic oscillator, agitator)."},
        {"excitation_frequency", "f_x", "Hz", Rule::non_negative(), &P::excitation_frequency,
         "Axial excitation frequency."},
        {"stick_speed", "s_stick", "m/s", Rule::positive(), &P::stick_speed,
         "Sliding speed at which an axially moving set-valued contact is caught to stick."},
        {"initial_speed", "w0", "rad/s", Rule::finite(), &P::initial_speed, "Rotation of the whole string at t = 0."},
        {"initial_axial_speed", "v0", "m/s", Rule::finite(), &P::initial_axial_speed,
         "Axial speed of the whole string at t = 0."},
        {"end_inertia", "J_end", "kg m^2", Rule::non_negative(), &P::end_inertia,
         "Inertia of a rigid BHA added to the bit node."},
        {"end_mass", "m_end", "kg", Rule::non_negative(), &P::end_mass, "Mass of a rigid BHA added to the bit node."},
        {"damping_rate", "k_t", "1/s", Rule::non_negative(), &P::damping_rate,
         "Viscous damping against absolute rotation (Aarsnes & Shor's k_t): torque k_t J_i w_i at each node, J_i the "
         "node's string inertia (k_t rho J w per unit length)."},
        {"setpoint_time_constant", "T_SP", "s", Rule::non_negative(), &P::setpoint_time_constant,
         "Set-point ramp: the set (or prescribed) speed is w_set (1 - exp(-t / T_SP)) from rest; 0: a step."},
        {"control_period", "T_c", "s", Rule::non_negative(), &P::control_period,
         "Sampling period of the PI drive, zero-order hold (Aarsnes & Shor's MAIN.m: the set-point filtered by "
         "forward Euler at each sample); 0: a continuous PI. Not with a prescribed speed."},
    }};
}

/// The discrete choices of a StringRig.
struct StringRigSetup {
    std::size_t elements = 20;                 ///< N: nodes 0 (top) .. N (bit)
    TopDrive top_drive = TopDrive::pi_motor;
    bool axial = false;                        ///< also the axial motion (u, v per node), friction as a vector
    Hoisting hoisting = Hoisting::hook_speed;  ///< with `axial`
    bool wall_contacts = true;                 ///< false: no wall contact at all (contact_nodes ignored)
    /// Nodes with a wall contact, increasing, in 1..N (the bit node only when the bit is off bottom). Empty: all.
    std::vector<std::size_t> contact_nodes;
    /// One normal force per contact node, N. Empty: each node's buoyed weight times the sine of its inclination
    /// (the straight inclined hole's, or node_inclinations'; a curved well's soft-string forces:
    /// string_geometry.hpp).
    std::vector<double> normal_forces;
    /// One inclination per node 0..N, rad in [0, pi]: the hole's direction at each node (axial gravity w_b,i cos I_i;
    /// e.g. from a survey, string_geometry.hpp). Empty: the params' one straight-hole inclination at every node.
    std::vector<double> node_inclinations;
    std::size_t excitation_node = 0;           ///< node of the axial excitation (with `axial`)
};

}  // namespace frictionsim
