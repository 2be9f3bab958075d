// The lumped torsional drill strings of Navarro-Lopez & Cortes (2007, J. Sound Vib. 307, 152-171, Sec. 2): a chain of
// inertias from the rotary table (index 0) to the bit (last), joined by torsional springs k_i and dampers d_i, a
// constant motor torque u on the table with its viscous loss c_r, and the velocity-weakening bit friction with
// stick (NavarroLopezBit, with its viscous c_b) under the weight on bit W:
//   J_i dw_i/dt = [i = 0] (u - c_r w_0) + S_{i-1} - S_i - T_i,    S_i = k_i (phi_i - phi_{i+1}) + d_i (w_i - w_{i+1})
// 2-DOF (rotary table, bit): the parameter set of Navarro-Lopez & Suarez (2004, Proc. IEEE Conf. Control
// Applications), reused by Navarro-Lopez & Cortes (2007) (as printed in the papers; no public code of it was found);
// 4-DOF (rotary table, two pipe inertias, bit): Navarro-Lopez & Cortes (2007), the parameter set as published in
// the public code of alwaysuu/active-control-for-drill-string-systems (code/drillstring.m: J1..J4, k1..k3, c1..c3,
// cr, cb, Rb, mu_cb, mu_sb, gamma_b, v_f). Optionally (0 in the papers) each pipe inertia rubs the wellbore with a
// Coulomb torque: more than one frictional contact.
//
// Steady states (sum of all equations, all speeds equal to w): u - (c_r + c_b) w - R_b W mu_b(w) = 0 while the
// bit turns; at rest the bit holds while u <= R_b W mu_sb, i.e. W >= u / (R_b mu_sb) keeps a stuck string stuck.
//
// Switches are resolved algebraically (contact/switching.hpp's guards, one pair per contact):
//  * a stuck contact whose holding torque reaches its static bound (its guard fires: the rate of the reserve, one
//    order above the acceleration, says it breaks away) slips in the guard's direction. This is exact break-away:
//    at the threshold the acceleration-level problem has a tie (zero acceleration, force at the bound) and a scheme
//    that re-solves it there keeps the contact stuck, stalls and trips the chattering bound;
//  * the contacts at rest (stuck, or whose speed just reached zero) get their new stick/slip set jointly, as the
//    LCP of Pfeiffer & Glocker (solve/lcp.hpp: resolve_contacts_at_rest; its one-contact case is Leine's switch
//    model). In this chain the contacts see a diagonal inverse inertia (friction torques enter only their own
//    equation), so the joint solution coincides with the per-contact one; simultaneous switches still go through
//    one LCP.
//
// States: the inertias' speeds w_0..w_{n-1}, the spring twists phi_i - phi_{i+1}, and three running integrals for
// the energy balance: motor_work = int u w_0 dt = kinetic + elastic energy change + damping_work + friction_work,
// damping_work = int [c_r w_0^2 + sum d_i (w_i - w_{i+1})^2] dt, friction_work = int sum T_i w_i dt (the bit's
// torque including its viscous c_b w_b).
// Mode: two bits per contact, the bit's lowest (contact_mode / with_contact_mode): 0 slip forwards, 1 stuck,
// 2 slip backwards; so the recorded mode is 0 while everything turns forwards and 1 while only the bit is stuck.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../detail/validate.hpp"
#include "../bits/bit_rock.hpp"
#include "../friction/law.hpp"
#include "../parameters.hpp"
#include "../contact/lcp.hpp"
#include "../outputs.hpp"

namespace frictionsim {

// The strings' common description (their help() in Python, through Params::description), one literal for both.
#define FRICTIONSIM_NAVARRO_LOPEZ_DOC \
    "A constant motor torque u drives the rotary table (viscous loss " \
    "c_r); springs k and dampers d join the inertias;\n" \
    "the bit (last inertia) carries the velocity-weakening friction of " \
    "NavarroLopezBit with stick, under weight on bit W:\n" \
    "\n" \
    "    J_i w_i' = [i = 0] (u - c_r w_0) + S_{i-1} - S_i - T_i,   S_i " \
    "= k_i (phi_i - phi_{i+1}) + d_i (w_i - w_{i+1})\n" \
    "    T_b = c_b w_b + R_b W mu_b(w_b) sign(w_b),  mu_b = mu_cb + " \
    "(mu_sb - mu_cb) exp(-gamma_b |w_b| / v_f)   (slip)\n" \
    "    |T_b| <= R_b W mu_sb                                                                           (stick)\n" \
    "\n" \
    "Steady states (closed forms): while the bit turns every inertia runs at the root w of steady_balance(w) = 0,\n" \
    "u - (c_r + c_b) w - R_b W mu_b(w) = 0; at rest the bit holds while " \
    "W >= stuck_weight_threshold = u / (R_b mu_sb).\n" \
    "Switches are located as events (exact stick, or a Karnopp band " \
    "D_v). States: each inertia's speed [rad/s], each\n" \
    "spring's twist [rad], and motor_work = stored energy change + damping_work + friction_work [J]. The Result's\n" \
    "friction_force is the bit's torque T_b [N m]; the mode is 0 while " \
    "everything turns forwards, 1 while the bit sticks.\n"

/// 2-DOF string: rotary table and bit (Navarro-Lopez & Suarez 2004). The operating point u = 6 kN m, W = 30 kN is
/// illustrative (the papers sweep both).
struct NavarroLopez2DofParams {
    static constexpr std::size_t dof = 2;
    double table_inertia = 2122.0;          ///< J_r, kg m^2
    double bit_inertia = 374.0;             ///< J_b, kg m^2
    double string_stiffness = 861.2;        ///< k_t, N m/rad
    double string_damping = 172.3;          ///< c_t, N m s/rad
    double table_damping = 425.0;           ///< c_r, N m s/rad
    double bit_damping = 50.0;              ///< c_b, N m s/rad
    double bit_radius = 0.155575;           ///< R_b, m
    double coulomb_coefficient = 0.5;       ///< mu_cb
    double static_coefficient = 0.8;        ///< mu_sb
    double weakening_rate = 0.9;            ///< gamma_b
    double velocity_scale = 1.0;            ///< v_f, rad/s
    double stick_band = 0.0;                ///< D_v, rad/s (0: exact stick)
    double motor_torque = 6000.0;           ///< u, N m
    double weight_on_bit = 30e3;            ///< W, N
    double initial_speed = 0.0;             ///< every inertia's speed at t = 0, rad/s (springs untwisted)

    static constexpr const char* rig_name = "NavarroLopez2Dof";  ///< as Python and the rig list name it
    static constexpr const char* description =
        "The 2-DOF drill string of Navarro-Lopez & Suarez (2004), reused by Navarro-Lopez & Cortes (2007): rotary "
        "table and bit.\n\n" FRICTIONSIM_NAVARRO_LOPEZ_DOC
        "\nDefaults: the papers' parameter set at u = 6 kN m, W = 30 kN (illustrative).";
    static constexpr std::array<Field<NavarroLopez2DofParams>, 15> fields();
    /// The Result's columns beside t (NavarroLopezRig::state_names; the bit law has no states).
    static constexpr std::array<RigOutput, 7> outputs() {
        return {{
            {"friction_force", "N m", "the bit's torque T_b"},
            {"table_speed", "rad/s", "rotary table speed"},
            {"bit_speed", "rad/s", "bit speed"},
            {"string_twist", "rad", "twist of the string, table - bit"},
            {"motor_work", "J", "int u w_0 dt = stored energy change + damping work + friction work"},
            {"damping_work", "J", "int [c_r w_0^2 + sum d_i (w_i - w_i+1)^2] dt"},
            {"friction_work", "J", "int sum T_i w_i dt: the bit's (and the pipe walls') friction"},
        }};
    }
};

/// 4-DOF string: rotary table, two pipe inertias, bit (Navarro-Lopez & Cortes 2007; public code, see the header).
struct NavarroLopez4DofParams {
    static constexpr std::size_t dof = 4;
    double table_inertia = 930.0;           ///< J_r, kg m^2
    double upper_pipe_inertia = 2782.25;    ///< J_p1, kg m^2
    double lower_pipe_inertia = 750.0;      ///< J_p2, kg m^2
    double bit_inertia = 471.9698;          ///< J_b, kg m^2
    double table_stiffness = 698.063;       ///< k_r, N m/rad: table - upper pipe
    double pipe_stiffness = 1080.0;         ///< k_p, N m/rad: upper - lower pipe
    double bit_stiffness = 907.48;          ///< k_b, N m/rad: lower pipe - bit
    double table_spring_damping = 139.6126; ///< d_r, N m s/rad
    double pipe_damping = 190.0;            ///< d_p, N m s/rad
    double bit_spring_damping = 181.49;     ///< d_b, N m s/rad
    double table_damping = 425.0;           ///< c_r, N m s/rad
    double bit_damping = 50.0;              ///< c_b, N m s/rad
    double bit_radius = 0.155575;           ///< R_b, m
    double coulomb_coefficient = 0.5;       ///< mu_cb
    double static_coefficient = 0.8;        ///< mu_sb
    double weakening_rate = 0.9;            ///< gamma_b
    double velocity_scale = 1.0;            ///< v_f, rad/s
    double stick_band = 0.0;                ///< D_v, rad/s
    double pipe_wall_torque = 0.0;          ///< Coulomb torque of each pipe inertia on the wellbore, N m (0: none)
    double motor_torque = 6000.0;           ///< u, N m
    double weight_on_bit = 30e3;            ///< W, N
    double initial_speed = 0.0;             ///< rad/s

    static constexpr const char* rig_name = "NavarroLopez4Dof";  ///< as Python and the rig list name it
    static constexpr const char* description =
        "The 4-DOF drill string of Navarro-Lopez & Cortes (2007): rotary table, two pipe inertias, bit. With "
        "pipe_wall_torque > 0 each pipe inertia also rubs the wellbore (Coulomb, with stick): the balance subtracts "
        "2 T_p.\n\n" FRICTIONSIM_NAVARRO_LOPEZ_DOC
        "\nDefaults: the parameter set of the public code of Navarro-Lopez & Cortes' model.";
    static constexpr std::array<Field<NavarroLopez4DofParams>, 22> fields();
    /// The Result's columns beside t (NavarroLopezRig::state_names; the bit law has no states).
    static constexpr std::array<RigOutput, 11> outputs() {
        return {{
            {"friction_force", "N m", "the bit's torque T_b"},
            {"table_speed", "rad/s", "rotary table speed"},
            {"upper_pipe_speed", "rad/s", "upper pipe inertia's speed"},
            {"lower_pipe_speed", "rad/s", "lower pipe inertia's speed"},
            {"bit_speed", "rad/s", "bit speed"},
            {"table_twist", "rad", "twist of the spring table - upper pipe"},
            {"pipe_twist", "rad", "twist of the spring upper - lower pipe"},
            {"bit_twist", "rad", "twist of the spring lower pipe - bit"},
            {"motor_work", "J", "int u w_0 dt = stored energy change + damping work + friction work"},
            {"damping_work", "J", "int [c_r w_0^2 + sum d_i (w_i - w_i+1)^2] dt"},
            {"friction_work", "J", "int sum T_i w_i dt: the bit's (and the pipe walls') friction"},
        }};
    }
};

#undef FRICTIONSIM_NAVARRO_LOPEZ_DOC

namespace detail {
/// Fields shared by both strings' tables (after each string's own): the bit law's, the operating point's, the initial speed.
template <class P>
constexpr std::array<Field<P>, 10> navarro_lopez_common_fields() {
    return {{
        {"bit_damping", "c_b", "N m s/rad", Rule::non_negative(), &P::bit_damping, "Viscous torque coefficient at the bit."},
        {"bit_radius", "R_b", "m", Rule::positive(), &P::bit_radius, "Bit radius."},
        {"coulomb_coefficient", "mu_cb", "-", Rule::positive(), &P::coulomb_coefficient, "Bit friction at high speed."},
        {"static_coefficient", "mu_sb", "-", Rule::at_least_field("coulomb_coefficient"), &P::static_coefficient,
         "Static bit friction, >= mu_cb."},
        {"weakening_rate", "gamma_b", "-", Rule::non_negative(), &P::weakening_rate, "Rate of the velocity weakening."},
        {"velocity_scale", "v_f", "rad/s", Rule::positive(), &P::velocity_scale, "Bit speed scale of the weakening."},
        {"stick_band", "D_v", "rad/s", Rule::non_negative(), &P::stick_band, "Karnopp band (0: exact stick)."},
        {"motor_torque", "u", "N m", Rule::finite(), &P::motor_torque, "Constant motor torque on the rotary table."},
        {"weight_on_bit", "W", "N", Rule::non_negative(), &P::weight_on_bit, "Weight on bit."},
        {"initial_speed", "w(0)", "rad/s", Rule::finite(), &P::initial_speed,
         "Speed of every inertia at t = 0 (springs untwisted)."},
    }};
}
}  // namespace detail

inline constexpr std::array<Field<NavarroLopez2DofParams>, 15> NavarroLopez2DofParams::fields() {
    using P = NavarroLopez2DofParams;
    return extend_fields<P, P>(
        std::array<Field<P>, 5>{{
            {"table_inertia", "J_r", "kg m^2", Rule::positive(), &P::table_inertia, "Rotary table inertia."},
            {"bit_inertia", "J_b", "kg m^2", Rule::positive(), &P::bit_inertia, "Bit (and BHA) inertia."},
            {"string_stiffness", "k_t", "N m/rad", Rule::positive(), &P::string_stiffness, "Torsional stiffness of the string."},
            {"string_damping", "c_t", "N m s/rad", Rule::non_negative(), &P::string_damping, "Structural damping of the string."},
            {"table_damping", "c_r", "N m s/rad", Rule::non_negative(), &P::table_damping, "Viscous loss at the rotary table."},
        }},
        detail::navarro_lopez_common_fields<P>());
}

inline constexpr std::array<Field<NavarroLopez4DofParams>, 22> NavarroLopez4DofParams::fields() {
    using P = NavarroLopez4DofParams;
    return extend_fields<P, P>(
        std::array<Field<P>, 12>{{
            {"table_inertia", "J_r", "kg m^2", Rule::positive(), &P::table_inertia, "Rotary table inertia."},
            {"upper_pipe_inertia", "J_p1", "kg m^2", Rule::positive(), &P::upper_pipe_inertia, "Upper pipe inertia."},
            {"lower_pipe_inertia", "J_p2", "kg m^2", Rule::positive(), &P::lower_pipe_inertia, "Lower pipe inertia."},
            {"bit_inertia", "J_b", "kg m^2", Rule::positive(), &P::bit_inertia, "Bit (and BHA) inertia."},
            {"table_stiffness", "k_r", "N m/rad", Rule::positive(), &P::table_stiffness, "Spring table - upper pipe."},
            {"pipe_stiffness", "k_p", "N m/rad", Rule::positive(), &P::pipe_stiffness, "Spring upper - lower pipe."},
            {"bit_stiffness", "k_b", "N m/rad", Rule::positive(), &P::bit_stiffness, "Spring lower pipe - bit."},
            {"table_spring_damping", "d_r", "N m s/rad", Rule::non_negative(), &P::table_spring_damping, "Damper table - upper pipe."},
            {"pipe_damping", "d_p", "N m s/rad", Rule::non_negative(), &P::pipe_damping, "Damper upper - lower pipe."},
            {"bit_spring_damping", "d_b", "N m s/rad", Rule::non_negative(), &P::bit_spring_damping, "Damper lower pipe - bit."},
            {"table_damping", "c_r", "N m s/rad", Rule::non_negative(), &P::table_damping, "Viscous loss at the rotary table."},
            {"pipe_wall_torque", "T_p", "N m", Rule::non_negative(), &P::pipe_wall_torque,
             "Coulomb torque of each pipe inertia on the wellbore (0 in the paper: no contact)."},
        }},
        detail::navarro_lopez_common_fields<P>());
}

/// A Navarro-Lopez & Cortes string as a HybridSystem; Params is NavarroLopez2DofParams or NavarroLopez4DofParams.
template <class Params>
class NavarroLopezRig {
public:
    static constexpr std::size_t dof = Params::dof;
    static constexpr std::size_t state_size = 2 * dof - 1 + 3;
    static constexpr std::size_t guard_count = 2 * dof;  // a pair per inertia (constant 1 where there is no contact)
    static constexpr std::size_t bit = dof - 1;
    static constexpr std::size_t speed = 0, twist = dof, motor_work = 2 * dof - 1, damping_work = 2 * dof,
                                 friction_work = 2 * dof + 1;
    /// Two-bit code of one contact's mode: slip forwards 0, stuck 1, slip backwards 2.
    static int contact_mode(int mode, std::size_t inertia) {
        const int code = (mode >> (2 * digit(inertia))) & 3;
        return code == 0 ? int{slip_positive} : code == 1 ? int{stick} : int{slip_negative};
    }
    static int with_contact_mode(int mode, std::size_t inertia, int contact) {
        const int shift = 2 * digit(inertia);
        const int code = contact == slip_positive ? 0 : contact == stick ? 1 : 2;
        return (mode & ~(3 << shift)) | (code << shift);
    }

    explicit NavarroLopezRig(const Params& p) : p_(validated(p)), bit_law_(bit_params(p)) {
        chain_from(p);
        for (std::size_t i = 0; i < dof; ++i) x0_[speed + i] = p.initial_speed;
        names_.resize(std::size_t{1} << (2 * dof));
        for (int m = 0; m < static_cast<int>(names_.size()); ++m) {
            std::string n;
            for (std::size_t i = dof; i-- > 0;) {
                if (!active_[i]) continue;
                if (!n.empty()) n += "+";
                n += (i == bit ? std::string("bit:") : "inertia" + std::to_string(i) + ":") +
                     contact_mode_name(contact_mode(m, i));
            }
            names_[static_cast<std::size_t>(m)] = n;
        }
    }

    const Params& params() const { return p_; }
    const NavarroLopezBit& bit_law() const { return bit_law_; }
    const std::array<double, dof>& inertias() const { return J_; }
    /// Does inertia i carry a frictional contact (the bit always; pipe inertias when pipe_wall_torque > 0)?
    bool has_contact(std::size_t i) const { return active_[i]; }

    /// Static bound of contact i, N m: R_b W mu_sb at the bit, the Coulomb torque elsewhere.
    double static_limit(std::size_t i) const { return i == bit ? bit_law_.static_limit(p_.weight_on_bit) : wall_[i]; }
    /// Friction torque of contact i slipping at speed w in `direction`, N m.
    double slip_torque(std::size_t i, double w, int direction) const {
        return i == bit ? bit_law_.torque(w, p_.weight_on_bit, direction) : direction * wall_[i];
    }
    /// Torque on inertia i from everything but its contact, N m: the friction torque that holds dw_i/dt = 0.
    double holding_torque(const double* x, std::size_t i) const {
        double h = i == 0 ? p_.motor_torque - table_damping_ * x[speed] : 0.0;
        if (i > 0) h += spring_torque(x, i - 1);
        if (i + 1 < dof) h -= spring_torque(x, i);
        return h;
    }
    /// S_i = k_i twist_i + d_i (w_i - w_{i+1}), N m: the torque spring i passes from inertia i to i + 1.
    double spring_torque(const double* x, std::size_t i) const {
        return k_[i] * x[twist + i] + d_[i] * (x[speed + i] - x[speed + i + 1]);
    }
    /// Friction torque of contact i in `mode` (0 without a contact), N m.
    double contact_torque(const double* x, int mode, std::size_t i) const {
        if (!active_[i]) return 0.0;
        const int m = contact_mode(mode, i);
        if (m != stick) return slip_torque(i, x[speed + i], m);
        const double limit = static_limit(i);
        return std::clamp(holding_torque(x, i), -limit, limit);
    }
    /// Kinetic + elastic energy, J.
    double stored_energy(const double* x) const {
        double e = 0.0;
        for (std::size_t i = 0; i < dof; ++i) e += 0.5 * J_[i] * x[speed + i] * x[speed + i];
        for (std::size_t i = 0; i + 1 < dof; ++i) e += 0.5 * k_[i] * x[twist + i] * x[twist + i];
        return e;
    }

    void rhs(double, const double* x, int mode, double* dxdt) const {
        double friction_power = 0.0, damping_power = table_damping_ * x[speed] * x[speed];
        for (std::size_t i = 0; i < dof; ++i) {
            const double T = contact_torque(x, mode, i);
            dxdt[speed + i] = (holding_torque(x, i) - T) / J_[i];
            friction_power += T * x[speed + i];
        }
        for (std::size_t i = 0; i + 1 < dof; ++i) {
            const double dw = x[speed + i] - x[speed + i + 1];
            dxdt[twist + i] = dw;
            damping_power += d_[i] * dw * dw;
        }
        dxdt[motor_work] = p_.motor_torque * x[speed];
        dxdt[damping_work] = damping_power;
        dxdt[friction_work] = friction_power;
    }

    void guards(double, const double* x, int mode, double* g) const {
        for (std::size_t i = 0; i < dof; ++i) {
            double* gi = g + 2 * i;
            gi[0] = gi[1] = 1.0;
            if (!active_[i]) continue;
            const int m = contact_mode(mode, i);
            if (m == stick) {
                const double h = holding_torque(x, i), limit = static_limit(i);
                gi[0] = limit - h;  // falls through zero: the holding torque exceeds the bound forwards
                gi[1] = limit + h;
            } else {
                gi[0] = m * x[speed + i] - band(i);
            }
        }
    }
    int guard_direction(std::size_t, int) const { return -1; }
    const char* guard_name(std::size_t g, int mode) const {
        const std::size_t i = g / 2;
        if (!active_[i]) return "none";
        if (contact_mode(mode, i) != stick) return i == bit ? "bit_speed" : "inertia_speed";
        if (i == bit) return g % 2 == 0 ? "bit_breakaway_positive" : "bit_breakaway_negative";
        return g % 2 == 0 ? "inertia_breakaway_positive" : "inertia_breakaway_negative";
    }
    const char* mode_name(int mode) const {
        return mode >= 0 && static_cast<std::size_t>(mode) < names_.size() ? names_[static_cast<std::size_t>(mode)].c_str()
                                                                           : "unknown";
    }

    /// New mode of the contacts flagged `at_rest` (zero speed, or inside the band), resolved jointly as the LCP of
    /// solve/lcp.hpp; their speeds are projected to exactly zero (exact stick). Other contacts keep their mode.
    int resolve_at_rest(double* x, int mode, const std::array<bool, dof>& at_rest) const {
        std::vector<std::size_t> rest;
        for (std::size_t i = 0; i < dof; ++i)
            if (active_[i] && at_rest[i]) rest.push_back(i);
        if (rest.empty()) return mode;
        const std::size_t n = rest.size();
        for (std::size_t i : rest)
            if (band(i) == 0.0) x[speed + i] = 0.0;
        std::vector<double> W(n * n, 0.0), b(n), limit(n);
        for (std::size_t r = 0; r < n; ++r) {
            const std::size_t i = rest[r];
            W[r * n + r] = 1.0 / J_[i];  // friction torques enter only their own inertia's equation
            b[r] = holding_torque(x, i) / J_[i];
            limit[r] = static_limit(i);
        }
        const ContactsAtRest s = resolve_contacts_at_rest(W, b, limit);
        if (!s.solved())
            throw std::runtime_error(std::string("NavarroLopezRig: stick/slip LCP failed (") +
                                     lcp_status_name(s.status) + ")");
        for (std::size_t r = 0; r < n; ++r) mode = with_contact_mode(mode, rest[r], s.modes[r]);
        return mode;
    }

    int initial_mode(double, const double* x) const {
        std::array<double, state_size> y{};
        std::copy(x, x + state_size, y.begin());
        std::array<bool, dof> at_rest{};
        int mode = 0;
        for (std::size_t i = 0; i < dof; ++i) {
            if (!active_[i]) continue;
            at_rest[i] = std::abs(x[speed + i]) <= band(i);
            if (!at_rest[i]) mode = with_contact_mode(mode, i, sign_of(x[speed + i]));
        }
        return resolve_at_rest(y.data(), mode, at_rest);  // y: the projection is the caller's initial state's
    }

    int switch_mode(double, double* x, int mode, const int* fired) const {
        std::array<bool, dof> at_rest{};
        for (std::size_t i = 0; i < dof; ++i) {
            if (!active_[i]) continue;
            const bool hit = fired[2 * i] != 0 || fired[2 * i + 1] != 0;
            if (contact_mode(mode, i) == stick) {
                if (hit) mode = with_contact_mode(mode, i, fired[2 * i] != 0 ? int{slip_positive} : int{slip_negative});
                else at_rest[i] = true;  // still stuck: re-resolved with the others
            } else if (hit) {
                at_rest[i] = true;  // its speed reached zero (or the band)
            }
        }
        return resolve_at_rest(x, mode, at_rest);
    }

    double friction_force(double, const double* x, int mode) const { return contact_torque(x, mode, bit); }

    std::array<double, state_size> initial_state() const { return x0_; }
    /// Replaces the initial state (e.g. a stuck bit with the string wound to its threshold).
    void set_initial_state(const std::array<double, state_size>& x) {
        for (double v : x) detail::require_finite("NavarroLopezRig", "initial_state", v);
        x0_ = x;
    }
    std::array<const char*, state_size> state_names() const {
        std::array<const char*, state_size> n{};
        static constexpr std::array<const char*, 4> speeds2{"table_speed", "bit_speed", "", ""};
        static constexpr std::array<const char*, 4> speeds4{"table_speed", "upper_pipe_speed", "lower_pipe_speed",
                                                           "bit_speed"};
        static constexpr std::array<const char*, 3> twists2{"string_twist", "", ""};
        static constexpr std::array<const char*, 3> twists4{"table_twist", "pipe_twist", "bit_twist"};
        for (std::size_t i = 0; i < dof; ++i) n[speed + i] = dof == 2 ? speeds2[i] : speeds4[i];
        for (std::size_t i = 0; i + 1 < dof; ++i) n[twist + i] = dof == 2 ? twists2[i] : twists4[i];
        n[motor_work] = "motor_work";
        n[damping_work] = "damping_work";
        n[friction_work] = "friction_work";
        return n;
    }

private:
    static int digit(std::size_t inertia) { return static_cast<int>(bit - inertia); }
    static const Params& validated(const Params& p) {
        validate_fields("NavarroLopezRig", p, Params::fields());
        return p;
    }
    static NavarroLopezBit::Params bit_params(const Params& p) {
        return {p.bit_radius, p.coulomb_coefficient, p.static_coefficient, p.weakening_rate,
                p.velocity_scale, p.bit_damping, p.stick_band};
    }
    double band(std::size_t i) const { return i == bit ? bit_law_.karnopp_band() : 0.0; }

    void chain_from(const NavarroLopez2DofParams& p) {
        J_ = {p.table_inertia, p.bit_inertia};
        k_ = {p.string_stiffness};
        d_ = {p.string_damping};
        table_damping_ = p.table_damping;
        wall_ = {0.0, 0.0};
        active_ = {false, true};
    }
    void chain_from(const NavarroLopez4DofParams& p) {
        J_ = {p.table_inertia, p.upper_pipe_inertia, p.lower_pipe_inertia, p.bit_inertia};
        k_ = {p.table_stiffness, p.pipe_stiffness, p.bit_stiffness};
        d_ = {p.table_spring_damping, p.pipe_damping, p.bit_spring_damping};
        table_damping_ = p.table_damping;
        wall_ = {0.0, p.pipe_wall_torque, p.pipe_wall_torque, 0.0};
        const bool walls = p.pipe_wall_torque > 0.0;
        active_ = {false, walls, walls, true};
    }

    Params p_;
    NavarroLopezBit bit_law_;
    std::array<double, dof> J_{}, wall_{};
    std::array<double, dof - 1> k_{}, d_{};
    std::array<bool, dof> active_{};
    double table_damping_ = 0.0;
    std::array<double, state_size> x0_{};
    std::vector<std::string> names_;
};

using NavarroLopez2Dof = NavarroLopezRig<NavarroLopez2DofParams>;
using NavarroLopez4Dof = NavarroLopezRig<NavarroLopez4DofParams>;

}  // namespace frictionsim
