// The friction contact on a rotating disc: modes, switching functions and the disc's acceleration for any law.
// The rig supplies the disc speed w, the shaft torque S on the disc (everything but friction, so that
// J dw/dt = S - T) and the disc inertia J; the contact returns the acceleration and the friction torque T.
//
//  * Laws of the engine (Coulomb, Stribeck, Karnopp, Dahl, LuGre) act at a contact radius r: the sliding
//    velocity is v_r = r w, the torque T = r F(v_r, N), and the force that holds the disc is S / r. Modes,
//    guards and mode resolution are ContactSwitching's.
//  * The hysteretic law of paper 001 (eq 6) acts on w and dw/dt directly. Its torque depends on dw/dt, so
//    every slip branch solves J al = S - T(w, al) exactly (one quadratic per right-hand-side call, the root
//    continuous with the linear case). Modes, with s = sgn(w) on the slip side:
//      stick (|w| <= w_s, T = a w) -> leaves through |w| = w_s onto the accelerating branch if it is
//        consistent there, else slides along the band edge (the branch gap);
//      accelerating s (s al > 0):  guards  S' - P0(|w|) (al reaches 0), D, B;
//      decelerating s (s al < 0):  guards  N0(|w|) - S' (al reaches 0), |w| - w_s (enters stick), D, B;
//      hold s (al = 0, BranchGap::hold): guards P0 - S' (to accelerating), S' - N0 (to decelerating; held on the
//        band edge |w| = w_s: S' - a w_s, back into stick), the branch it enters checked as on any switch;
//    with S' = s S, D the discriminant and B the effective inertia of the branch quadratic: D or B reaching
//    zero means the branch has no real root left, and the run stops with a SimulationError saying where.
//    A branch is consistent when its root has the branch's sign: accelerating iff S' > P0, decelerating iff
//    S' < N0. Where both are (N0 > P0) the current branch is kept until its own al reaches zero (hysteresis);
//    where neither is (N0 <= S' <= P0), BranchGap decides.
#pragma once

#include <algorithm>

#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "../error.hpp"
#include "../friction/hysteretic.hpp"
#include "../solve/hybrid_system.hpp"
#include "switching.hpp"

namespace frictionsim {

/// The disc's response in one mode: dw/dt and the friction torque T (N m) with J dw/dt = S - T.
struct DiscResponse {
    double acceleration;
    double torque;
};

/// First derivatives of the disc's response in one mode (analytic Jacobians): of the friction torque T and of
/// the law's state rates, with respect to the disc speed w, the shaft torque S and the law's states z. The
/// acceleration follows from J dw/dt = S - T.
template <std::size_t Z>
struct DiscPartials {
    double torque_speed = 0.0, torque_shaft = 0.0;  ///< dT/dw, dT/dS
    std::array<double, Z> torque_state{};           ///< dT/dz_j
    std::array<double, Z> rate_speed{};             ///< d(dz_i/dt)/dw
    std::array<std::array<double, Z>, Z> rate_state{};
};

template <class Law>
class DiscContact {
    static_assert(check_friction_law<Law>(), "DiscContact<Law>: Law must meet the FrictionLaw concept (see above)");
    using Switching = ContactSwitching<Law>;

public:
    static constexpr std::size_t state_count = Law::state_count;
    static constexpr std::size_t guard_count = Switching::guard_count;
    static constexpr bool stiff = declares_stiff<Law>::value;
    static constexpr std::array<int, 3> modes{slip_negative, stick, slip_positive};

    DiscContact(Law law, double contact_radius, double normal_force)
        : law_(std::move(law)), radius_(contact_radius), normal_force_(normal_force) {
        if constexpr (Switching::set_valued)  // no normal force, no jump: nothing to stick or switch
            inert_ = law_.static_limit(normal_force_) == 0.0 &&
                     law_.slip_force(0.0, normal_force_, +1) == law_.slip_force(0.0, normal_force_, -1);
    }

    /// A set-valued law under a normal force that leaves it no static limit and no jump at zero speed (N = 0 on a
    /// vertical stretch of a string): the contact slides through zero speed without switching (its guards stay
    /// positive), instead of an event at every reversal of an unloaded node.
    bool inert() const { return inert_; }

    const Law& law() const { return law_; }

    DiscResponse respond(double w, double shaft_torque, const double* z, int mode, double inertia) const {
        const double holding = shaft_torque / radius_;
        const double f = Switching::force(law_, radius_ * w, normal_force_, z, mode, holding);
        if constexpr (Switching::set_valued)
            if (mode == stick && f == holding) return {0.0, shaft_torque};  // held: exactly, not S - r (S / r)
        const double torque = radius_ * f;
        return {(shaft_torque - torque) / inertia, torque};
    }
    void state_derivative(double w, const double* z, int mode, double* dz) const {
        if constexpr (state_count > 0) law_.state_derivative(radius_ * w, normal_force_, z, mode, dz);
        else (void)w, (void)z, (void)mode, (void)dz;
    }
    /// T = r F(r w, N, z, S / r): chain rule through the contact radius.
    DiscPartials<state_count> partials(double w, double shaft_torque, const double* z, int mode, double) const {
        double force_stick_slope = 0.0;
        const StatePartials<state_count> f = Switching::partials(law_, radius_ * w, normal_force_, z, mode,
                                                                 shaft_torque / radius_, force_stick_slope);
        DiscPartials<state_count> d;
        d.torque_speed = radius_ * radius_ * f.force_velocity;
        d.torque_shaft = force_stick_slope;
        for (std::size_t j = 0; j < state_count; ++j) {
            d.torque_state[j] = radius_ * f.force_state[j];
            d.rate_speed[j] = radius_ * f.rate_velocity[j];
            d.rate_state[j] = f.rate_state[j];
        }
        return d;
    }
    void guards(double w, double shaft_torque, const double*, int mode, double, double* g) const {
        if (inert_) {
            std::fill(g, g + guard_count, 1.0);
            return;
        }
        Switching::guards(law_, radius_ * w, normal_force_, mode, shaft_torque / radius_, g);
    }
    int guard_direction(std::size_t i, int mode) const { return Switching::guard_direction(i, mode); }
    const char* guard_name(std::size_t i, int mode) const { return Switching::guard_name(law_, i, mode); }
    const char* mode_name(int mode) const { return Switching::mode_name(law_, mode); }
    int initial_mode(double w, double shaft_torque, const double* z, double) const {
        if (inert_) return w < 0.0 ? int{slip_negative} : int{slip_positive};  // the force is the same either way
        return Switching::initial_mode(law_, radius_ * w, normal_force_, z, shaft_torque / radius_);
    }
    /// New mode at a root; projects w to exactly zero on entering stick.
    int switch_mode(double, double& w, double shaft_torque, double* z, int mode, const int* fired,
                    double) const {
        bool stop = false;
        const int next = Switching::switch_mode(law_, normal_force_, mode, fired, shaft_torque / radius_, stop);
        if (!inert_) note_reversal(law_, normal_force_, z, mode, next);  // a memory of turning points (Leuven)
        if (stop) w = 0.0;
        return next;
    }

private:
    Law law_;
    double radius_, normal_force_;
    bool inert_ = false;
};

template <>
class DiscContact<HystereticFriction> {
public:
    static constexpr std::size_t state_count = 0;
    static constexpr std::size_t guard_count = 4;
    /// The band's time constant J / (a N/N_ref) is ~1e-5 s against a ~1 s cycle: BDF.
    static constexpr bool stiff = true;
    enum Mode : int { hold_negative = -3, decelerating_negative = -2, accelerating_negative = -1, stick_band = 0,
                      accelerating_positive = 1, decelerating_positive = 2, hold_positive = 3 };
    static constexpr std::array<int, 7> modes{hold_negative, decelerating_negative, accelerating_negative,
                                              stick_band,    accelerating_positive, decelerating_positive,
                                              hold_positive};

    DiscContact(HystereticFriction law, double /*contact_radius: eq 6 is a torque law*/, double normal_force)
        : law_(std::move(law)), normal_force_(normal_force) {}

    const HystereticFriction& law() const { return law_; }

    DiscResponse respond(double w, double shaft_torque, const double*, int mode, double inertia) const {
        if (mode == stick_band) {
            const double torque = law_.stick_torque(w, normal_force_);
            return {(shaft_torque - torque) / inertia, torque};
        }
        const double s = side(mode);
        if (is_hold(mode)) return {0.0, shaft_torque};
        law_.require_opposing(is_accelerating(mode), s * w);
        const double b = equation(mode, w, shaft_torque, inertia).root();
        return {s * b, shaft_torque - inertia * s * b};
    }
    void state_derivative(double, const double*, int, double*) const {}

    /// Stick: T = k a w. Hold: T = S. Slip: b = s dw/dt solves A b^2 + B(u) b + C(u, S') = 0 (u = s w, S' = s S),
    /// so by implicit differentiation db/du = -(B'(u) b + dC/du) / (2 A b + B) and db/dS' = 1 / (2 A b + B),
    /// and T = S - J dw/dt.
    DiscPartials<0> partials(double w, double shaft_torque, const double*, int mode, double inertia) const {
        DiscPartials<0> d;
        if (mode == stick_band) {
            d.torque_speed = law_.scale(normal_force_) * law_.params().stick_slope;
        } else if (is_hold(mode)) {
            d.torque_shaft = 1.0;
        } else {
            const HystereticFriction::Quadratic q = equation(mode, w, shaft_torque, inertia);
            const BranchPolynomial& c = law_.branch(is_accelerating(mode));
            const double k = law_.scale(normal_force_), u = side(mode) * w, b = q.root();
            const double slope = 2.0 * q.a * b + q.b;
            const double db_du = -(k * c.c11 * b + k * (c.c10 + 2.0 * c.c20 * u)) / slope;
            d.torque_speed = -inertia * db_du;             // d(s b)/dw = db/du
            d.torque_shaft = 1.0 - inertia / slope;        // d(s b)/dS = db/dS'
        }
        return d;
    }

    void guards(double w, double shaft_torque, const double*, int mode, double inertia, double* g) const {
        g[0] = g[1] = g[2] = g[3] = 1.0;
        const double w_s = law_.params().stick_speed;
        if (mode == stick_band) {
            g[0] = w_s - w;  // leaves the band upwards
            g[1] = w_s + w;  // leaves it downwards
            return;
        }
        const double s = side(mode), u = s * w, signed_torque = s * shaft_torque;
        const double k = law_.scale(normal_force_);
        if (is_hold(mode)) {
            g[0] = k * law_.branch(true).level(u) - signed_torque;  // S' rises above P0: accelerates
            g[1] = signed_torque - lower_hold_level(u);            // S' falls below it: decelerates or sticks
            return;
        }
        const HystereticFriction::Quadratic q = equation(mode, w, shaft_torque, inertia);
        if (is_accelerating(mode)) {
            g[0] = -q.c;  // S' - k P0: al reaches zero
        } else {
            g[0] = q.c;   // k N0 - S': al reaches zero
            g[1] = u - w_s;
        }
        g[2] = q.a != 0.0 ? q.discriminant() : 1.0;
        g[3] = q.b - min_effective_inertia * inertia;
    }
    int guard_direction(std::size_t, int) const { return -1; }

    const char* guard_name(std::size_t i, int mode) const {
        if (mode == stick_band) return i == 0 ? "stick_band_upper_edge" : "stick_band_lower_edge";
        if (is_hold(mode)) return i == 0 ? "accelerating_level" : "decelerating_level";
        static constexpr std::array<const char*, 4> slip{"acceleration_zero", "stick_band_entry",
                                                         "branch_discriminant", "branch_effective_inertia"};
        return slip[i];
    }
    const char* mode_name(int mode) const {
        switch (mode) {
            case hold_negative: return "hold_negative";
            case decelerating_negative: return "decelerating_negative";
            case accelerating_negative: return "accelerating_negative";
            case stick_band: return "stick";
            case accelerating_positive: return "accelerating_positive";
            case decelerating_positive: return "decelerating_positive";
            case hold_positive: return "hold_positive";
        }
        return "unknown";
    }

    int initial_mode(double w, double shaft_torque, const double*, double inertia) const {
        if (std::abs(w) <= law_.params().stick_speed) return stick_band;
        return slip_branch(0.0, w, shaft_torque, w > 0.0 ? 1 : -1, 0, inertia);
    }

    int switch_mode(double t, double& w, double shaft_torque, const double*, int mode, const int* fired,
                    double inertia) const {
        if (mode == stick_band) return leave_band(t, w, shaft_torque, fired[0] != 0 ? 1 : -1, inertia);
        const int s = mode > 0 ? 1 : -1;
        if (fired[2] != 0 || fired[3] != 0)
            no_consistent_branch(t, w, shaft_torque, inertia,
                                 fired[2] != 0 ? "the branch equation lost its real root (discriminant reached 0)"
                                               : "the branch's effective inertia J + k (c01 + c11 |w|) fell to 1 % of J "
                                                 "(dw/dt grows without bound as it reaches 0)",
                                 "; the acceleration coefficients, scaled by N / N_ref, cancel the disc's inertia at "
                                 "this speed: check p01, p11, p02 (n01, n11, n02) against J");
        if (is_hold(mode)) {
            if (fired[0] == 0 && on_band_edge(s * w)) return stick_band;
            return checked_branch(t, w, shaft_torque, s, fired[0] != 0 ? accelerating_positive : decelerating_positive,
                                  inertia);
        }
        if (!is_accelerating(mode) && fired[1] != 0) return stick_band;
        // al reached zero: the other branch if it is consistent, else the gap
        return slip_branch(t, w, shaft_torque, s, is_accelerating(mode) ? decelerating_positive : accelerating_positive,
                           inertia);
    }

    std::array<const char*, 0> state_names() const { return {}; }

private:
    /// A branch whose effective inertia B falls to this fraction of J stops the run: dw/dt = -C/B diverges as
    /// B -> 0, and an integrator fails on the way before a guard at exactly 0 could be located.
    static constexpr double min_effective_inertia = 0.01;

    static int side(int mode) { return mode > 0 ? 1 : -1; }
    static bool is_hold(int mode) { return mode == hold_positive || mode == hold_negative; }
    static bool is_accelerating(int mode) { return mode == accelerating_positive || mode == accelerating_negative; }
    bool on_band_edge(double u) const { return u <= law_.params().stick_speed; }

    /// Where a hold ends as S' falls: the decelerating level N0, or, held at the band edge |w| = w_s, the
    /// band's break-away torque a w_s (below it the band pulls the disc back in; a decelerating branch there
    /// would enter the band at once).
    double lower_hold_level(double u) const {
        const double k = law_.scale(normal_force_);
        return on_band_edge(u) ? k * law_.params().stick_slope * law_.params().stick_speed
                               : k * law_.branch(false).level(u);
    }

    HystereticFriction::Quadratic equation(int mode, double w, double shaft_torque, double inertia) const {
        const double s = side(mode);
        return law_.branch_equation(is_accelerating(mode), s * w, s * shaft_torque, inertia, normal_force_);
    }

    /// Leaving the stick band on side s: the band pushes the disc out (a w_s < S'), so only the accelerating
    /// branch can take it; if S' <= P0(w_s) that branch would push it back, and the disc slides along the band
    /// edge with dw/dt = 0 and T = S (Filippov), which is the branch gap at |w| = w_s.
    int leave_band(double t, double& w, double shaft_torque, int s, double inertia) const {
        const double signed_torque = s * shaft_torque, k = law_.scale(normal_force_);
        if (signed_torque > k * law_.branch(true).level(law_.params().stick_speed))
            return slip_branch(t, w, shaft_torque, s, accelerating_positive, inertia);
        if (law_.params().branch_gap == BranchGap::hold) {
            w = s * law_.params().stick_speed;  // held exactly on the edge, where the hold's exits are judged
            return s * hold_positive;
        }
        no_consistent_branch(t, w, shaft_torque, inertia,
                             "the band's break-away torque a w_s is below the accelerating level P0(w_s), so the "
                             "accelerating branch is not consistent at the band edge",
                             "; raise stick_slope to at least P0(w_s) / w_s, or use branch_gap = hold (the disc then "
                             "slides along the band edge until S reaches P0)");
    }

    int branch_gap(double t, double w, double shaft_torque, int s, double inertia) const {
        if (law_.params().branch_gap == BranchGap::hold) return s * hold_positive;
        no_consistent_branch(t, w, shaft_torque, inertia,
                             "the shaft torque lies between the decelerating level N0 and the accelerating level "
                             "P0 (eq 6 has no case for dw/dt = 0)",
                             "; branch_gap = hold holds dw/dt = 0 there (Filippov), or use coefficients with N0 >= P0");
    }

    /// The consistent slip mode on side s (+1/-1) at speed w; `preferred` (a positive-side branch, or 0 for
    /// none) is taken when both are consistent. Accelerating when S' > P0, decelerating when S' < N0.
    int slip_branch(double t, double w, double shaft_torque, int s, int preferred, double inertia) const {
        const double u = std::max(s * w, law_.params().stick_speed);  // at the band edge, |w| = w_s
        const double signed_torque = s * shaft_torque, k = law_.scale(normal_force_);
        const bool accelerates = signed_torque > k * law_.branch(true).level(u);
        const bool decelerates = signed_torque < k * law_.branch(false).level(u);
        int branch = 0;
        if (accelerates && decelerates) branch = preferred != 0 ? preferred : accelerating_positive;
        else if (accelerates) branch = accelerating_positive;
        else if (decelerates) branch = decelerating_positive;
        if (branch == 0) return branch_gap(t, w, shaft_torque, s, inertia);
        return checked_branch(t, w, shaft_torque, s, branch, inertia);
    }

    /// s * branch, once its equation is known to have the root the run needs (else a SimulationError).
    int checked_branch(double t, double w, double shaft_torque, int s, int branch, double inertia) const {
        const double u = std::max(s * w, law_.params().stick_speed);
        const HystereticFriction::Quadratic q =
            law_.branch_equation(branch == accelerating_positive, u, s * shaft_torque, inertia, normal_force_);
        if (q.b <= min_effective_inertia * inertia)
            no_consistent_branch(t, w, shaft_torque, inertia,
                                 "the branch's effective inertia J + k (c01 + c11 |w|) is below 1 % of J",
                                 "; the acceleration coefficients, scaled by N / N_ref, cancel the disc's inertia: "
                                 "lower the normal force or the magnitude of c01, c11");
        if (q.a != 0.0 && q.discriminant() < 0.0)
            no_consistent_branch(t, w, shaft_torque, inertia, "the branch equation has no real root");
        return s * branch;
    }

    [[noreturn]] void no_consistent_branch(double t, double w, double shaft_torque, double inertia, const char* why,
                                           const char* hint = "; check the branch's coefficients over this speed "
                                                              "range (p02, n02 and the effective inertia)") const {
        const double u = std::max(std::abs(w), law_.params().stick_speed), k = law_.scale(normal_force_);
        std::ostringstream msg;
        msg.precision(10);
        msg << "hysteretic friction (eq 6): no consistent friction branch at t = " << t << " s, disc speed w = " << w
            << " rad/s, shaft torque S = " << shaft_torque << " N m (accelerating level P0 = "
            << k * law_.branch(true).level(u) << " N m, decelerating level N0 = " << k * law_.branch(false).level(u)
            << " N m, disc inertia " << inertia << " kg m^2): " << why << hint;
        throw SimulationError(msg.str(), t);
    }

    HystereticFriction law_;
    double normal_force_;
};

}  // namespace frictionsim
