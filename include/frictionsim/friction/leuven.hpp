// Leuven friction (Swevers, Al-Bender, Ganseman & Prajogo 2000, "An integrated friction model structure with
// improved presliding behavior for accurate friction compensation", IEEE TAC 45(4), sec. III), with the state
// equation of its modification (Lampaert, Swevers & Al-Bender 2002, "Modification of the Leuven integrated friction
// model structure", IEEE TAC 47(4)):
//   F = F_h(z) + sigma_1 dz/dt + sigma_2 v,
//   dz/dt = v (1 - sgn(r) |r|^n),   r = F_d(z) / (S(v) - F_b),   S(v) = sgn(v) s(|v|),
//   s(v) = F_N (mu + (mu_s - mu) exp(-|v/v_s|^delta))                       (the Stribeck curve),
//   F_h(z) = F_b + F_d(z)                                                   (the hysteresis force).
// F_h is a hysteresis function of z with non-local memory (Maxwell's rules, as the 2000 paper builds it): F_b is its
// value at the last turning point (z_b, where v last changed sign), F_d the transition curve from there,
//   F_d(z) = 2 F_vc((z - z_b) / 2)   (Masing's doubling of the virgin curve),   F_d(z) = F_vc(z) on the virgin curve,
// and a stack of turning points: a reversal pushes (z, F_h); when z comes back to the turning point before the last
// (the inner loop closes: F_h reaches that turning point's force) the loop is wiped out of the memory and F_h
// continues on the outer curve as if the loop had never been; the first turning point's loop closes on the virgin
// curve (at -z_1). In steady sliding r -> 1: F_h -> S(v), F -> S(v) + sigma_2 v (the Stribeck curve).
// The 2002 paper replaced F_h / S(v) (the 2000 equation) by F_d / (S - F_b) so that every transition starts with r = 0
// (full presliding stiffness at each reversal) and removed the stack's unbounded growth; here the stack is bounded.
//
// What the papers leave open, and what is done here:
//  * Virgin curve (the papers allow any): F_vc(x) = k x / (1 + h k |x| / F_s), F_s = mu_s F_N: initial slope k (the
//    presliding stiffness), asymptote F_s / h; it reaches F_s at x = F_s / (k (1 - h)). h = 0 makes F_h linear
//    (k z) whatever the memory: with memory_depth = 0 (F_b = 0, the 2000 form) and n = 1 the law is LuGre with
//    sigma_0 = k exactly, the reduction the 2000 paper states.
//  * Memory carried with the law's states: z[0] = z, then the turning-point count, a truncation flag, the force at
//    the bottom turning point once older ones were forgotten, and the turning points' displacements (capacity 8;
//    `memory_depth` <= 8 of them kept, the oldest forgotten first). Their rates are 0; they change only at the
//    reversal the rig locates (v = 0, the kink event), through `on_reversal` (law.hpp): the rig hands the law its
//    states there. Forces at the turning points are replayed from the displacements (F_1 = F_vc(z_1),
//    F_{j+1} = F_j + 2 F_vc((z_{j+1} - z_j) / 2)), so every loop closes exactly at its turning point's force, at any
//    normal force.
//  * The wiping-out is read off the state between reversals (a loop counts as closed once z has passed its turning
//    point along the motion), and committed at the next reversal: no extra event, and F_h is a continuous function of
//    z (its slope and dz/dt change at a closing point, which the step control resolves). The one difference from
//    popping at the closing itself: if the Stribeck level then falls below the closed turning point's force within
//    the same motion (z drawn back past it, r > 1), the loop counts as open again until then.
//  * The 2002 denominator S(v) - F_b reaches zero when the Stribeck level falls to a turning point's force (a
//    reversal above the Coulomb level, then acceleration): the attraction to S would then turn into a repulsion. The
//    transition is kept at least a fraction eps = min_transition_span of |S| long: r = 1 - (S - F_h) / D with
//    sgn(v) D = max(sgn(v) (S - F_b), eps |S|), the paper's r wherever sgn(v)(S - F_b) >= eps |S|, continuous, and
//    attracting F_h to S everywhere.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "../parameters.hpp"
#include "law.hpp"

namespace frictionsim {

class Leuven {
public:
    static constexpr const char* name = "Leuven";
    static constexpr const char* key = "leuven";
    /// What Python's help() shows above the parameter list (the bindings add that from `fields`).
    static constexpr const char* description =
        R"doc(Leuven friction (Swevers, Al-Bender, Ganseman & Prajogo 2000, IEEE TAC 45(4); state equation of
Lampaert, Swevers & Al-Bender 2002, IEEE TAC 47(4)):

    F = F_h(z) + sigma_1 dz/dt + sigma_2 v_r,
    dz/dt = v_r (1 - sgn(r) |r|^n),   r = F_d(z) / (S(v_r) - F_b),
    S(v) = sgn(v) F_N [mu + (mu_static - mu) exp(-|v/v_s|^delta)],

with the hysteresis force F_h = F_b + F_d (non-local memory, Maxwell's rules): F_b its value at the last
turning point z_b, F_d(z) = 2 F_vc((z - z_b)/2) the transition curve from the virgin curve
F_vc(x) = k x / (1 + h k |x| / (mu_static F_N)). A reversal of v_r pushes a turning point; an inner loop
that closes is wiped out of the memory (up to memory_depth turning points, the oldest forgotten first).
Steady sliding gives the Stribeck curve F = S(v) + sigma_2 v; h = 0, n = 1 and memory_depth = 0 give LuGre.
States: presliding_displacement z [m] and the memory (turning_point_count, memory_truncated,
bottom_turning_force [N], turning_point_1..8 [m]), which changes only at reversals.)doc";
    static constexpr bool has_stick = false;
    static constexpr bool kink_at_zero_velocity = true;  ///< reversals are the memory's events
    static constexpr bool stiff = true;  ///< presliding modes ~ k |v| / (S - F_b), as LuGre's sigma_0 |v| / g
    static constexpr std::size_t memory_capacity = 8;
    static constexpr std::size_t state_count = 4 + memory_capacity;
    static constexpr std::size_t presliding = 0, count = 1, truncated = 2, bottom_force = 3, turning = 4;
    static constexpr std::array<const char*, state_count> state_names{
        "presliding_displacement", "turning_point_count", "memory_truncated", "bottom_turning_force",
        "turning_point_1", "turning_point_2", "turning_point_3", "turning_point_4",
        "turning_point_5", "turning_point_6", "turning_point_7", "turning_point_8"};
    static constexpr std::array<const char*, state_count> state_units{  ///< SI; "1" a count or a flag
        "m", "1", "1", "N", "m", "m", "m", "m", "m", "m", "m", "m"};
    /// eps: the shortest transition, as a fraction of |S(v)|, that the state equation uses (see above).
    static constexpr double min_transition_span = 1e-2;

    struct Params {
        double coulomb_coefficient = 0.3;   ///< mu: s(v) -> mu F_N at high speed
        double static_coefficient = 0.4;    ///< mu_s >= mu: s(0) = mu_s F_N
        double stribeck_velocity = 1e-3;    ///< v_s, m/s
        double shape_exponent = 2.0;        ///< delta
        double presliding_stiffness = 1e5;  ///< k, N/m: the virgin curve's initial slope
        double hysteresis_shape = 0.5;      ///< h: the virgin curve's asymptote is F_s / h (0: linear)
        double attraction_exponent = 2.0;   ///< n
        double memory_depth = 8.0;          ///< turning points kept (integer, 0..8)
        double micro_damping = 0.0;         ///< sigma_1, N s/m
        double viscous_damping = 0.0;       ///< sigma_2, N s/m
    };

    static constexpr std::array<Field<Params>, 10> fields{{
        {"coulomb_coefficient", "mu", "-", Rule::positive(), &Params::coulomb_coefficient,
         "Coulomb (high-speed) coefficient: s(v) -> mu F_N.", "mu", true},
        {"static_coefficient", "mu_s", "-", Rule::at_least_field("coulomb_coefficient"), &Params::static_coefficient,
         "Static coefficient: s(0) = mu_static F_N.", "mu_static", true},
        {"stribeck_velocity", "v_s", "m/s", Rule::positive(), &Params::stribeck_velocity, "Stribeck velocity.",
         nullptr, true},
        // the required fields first: Python's signature is written in this order
        {"presliding_stiffness", "k", "N/m", Rule::positive(), &Params::presliding_stiffness,
         "Initial slope of the hysteresis force's virgin curve (LuGre's sigma_0 when h = 0).", nullptr, true},
        {"shape_exponent", "delta", "-", Rule::positive(), &Params::shape_exponent,
         "Shape of the Stribeck decay (2: Gaussian, 1: exponential).", nullptr},
        {"hysteresis_shape", "h", "-",
         Rule::interval(0.0, 1.0, false, true)
             .because("the virgin curve's asymptote mu_static F_N / h must lie above the static force"),
         &Params::hysteresis_shape,
         "Curvature of the virgin curve F_vc(x) = k x / (1 + h k |x| / (mu_static F_N)); 0: linear.", nullptr},
        {"attraction_exponent", "n", "-",
         Rule::interval(1.0, 20.0).because("below 1 the rate's slope is unbounded at every turning point"),
         &Params::attraction_exponent,
         "Exponent n of the state equation: how sharply presliding turns into sliding.", nullptr},
        {"memory_depth", "M", "-", Rule::interval(0.0, static_cast<double>(memory_capacity)),
         &Params::memory_depth, "Turning points the hysteresis remembers (an integer; 0: no memory, F_b = 0).",
         nullptr},
        {"micro_damping", "sigma_1", "N s/m", Rule::non_negative(), &Params::micro_damping,
         "Micro-damping (on dz/dt).", nullptr},
        {"viscous_damping", "sigma_2", "N s/m", Rule::non_negative(), &Params::viscous_damping, "Viscous friction.",
         nullptr},
    }};

    explicit Leuven(const Params& p) : p_(p) {
        validate_fields(name, p, fields);
        if (p.memory_depth != std::floor(p.memory_depth))
            detail::reject(name, "memory_depth", "an integer in [0, 8]", p.memory_depth);
        depth_ = static_cast<std::size_t>(p.memory_depth);
    }

    const Params& params() const { return p_; }
    std::size_t memory_depth() const { return depth_; }

    /// The Stribeck curve s(v) (N) at normal force F_N: the steady sliding force without sigma_2 v.
    double stribeck_level(double v_r, double normal_force) const {
        const double r = std::abs(v_r) / p_.stribeck_velocity;
        const double shaped = p_.shape_exponent == 2.0 ? r * r : std::pow(r, p_.shape_exponent);
        return normal_force * (p_.coulomb_coefficient +
                               (p_.static_coefficient - p_.coulomb_coefficient) * std::exp(-shaped));
    }

    /// The virgin curve F_vc(x) (N) at normal force F_N.
    double virgin_curve(double x, double normal_force) const {
        const double k = p_.presliding_stiffness;
        return k * x / (1.0 + p_.hysteresis_shape * k * std::abs(x) / (p_.static_coefficient * normal_force));
    }

    /// F_s / k (m): the presliding displacement scale at F_N (the virgin curve's initial slope reaches F_s there);
    /// a planar wall contact's reference axis follows the sliding direction over this length (wall_contact.hpp).
    double presliding_length(double normal_force) const {
        return p_.static_coefficient * normal_force / p_.presliding_stiffness;
    }

    /// The hysteresis force F_h (N) on branch `branch` (the sign of v_r): the memory's loops closed by z wiped.
    double hysteresis_force(double normal_force, const double* z, int branch) const {
        const Curve c = curve(normal_force, z, branch);
        return c.turning_force + c.transition;
    }
    /// Turning points the memory holds once the loops z has closed are wiped (what the next reversal commits).
    std::size_t turning_points(const double* z, int branch) const { return open_points(z, branch); }

    void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const {
        std::fill(dz, dz + state_count, 0.0);
        dz[presliding] = rate(v_r, normal_force, branch, curve(normal_force, z, branch));
    }

    double force(double v_r, double normal_force, const double* z, int branch) const {
        const Curve c = curve(normal_force, z, branch);
        return c.turning_force + c.transition + p_.micro_damping * rate(v_r, normal_force, branch, c) +
               p_.viscous_damping * v_r;
    }

    /// At a located reversal (the branch flips from `from` to `to`): commit the loops closed on `from`, push the
    /// turning point z (the oldest forgotten beyond memory_depth), and wipe what is already closed on `to` (a
    /// reversal back onto the last turning point).
    void on_reversal(double normal_force, double* z, int from, int to) const {
        std::size_t m = open_points(z, from);
        if (depth_ > 0 && from != to) {
            const double x = z[presliding];
            if (m == depth_) {  // forget the oldest: the next one keeps its force as the bottom of the chain
                const double kept = m > 1 ? point_force(normal_force, z, 1) : hysteresis_force(normal_force, z, from);
                for (std::size_t j = 0; j + 1 < m; ++j) z[turning + j] = z[turning + j + 1];
                z[bottom_force] = kept;
                z[truncated] = 1.0;
                --m;
                if (m == 0) {  // memory_depth 1: the new point is the bottom, with the force it has now
                    z[turning] = x;
                    z[count] = 1.0;
                    return;
                }
            }
            z[turning + m] = x;
            ++m;
        }
        z[count] = static_cast<double>(m);
        z[count] = static_cast<double>(open_points(z, to));
        if (z[count] == 0.0) z[truncated] = z[bottom_force] = 0.0;
    }

private:
    struct Curve {
        double turning_force = 0.0;  ///< F_b
        double transition = 0.0;     ///< F_d(z)
    };

    std::size_t stored(const double* z) const {
        const double m = std::round(z[count]);
        return m <= 0.0 ? 0 : std::min<std::size_t>(static_cast<std::size_t>(m), depth_);
    }

    /// Maxwell's wiping-out on branch b: a loop is closed once z has passed, along b, the turning point before the
    /// last (the first turning point's loop closes on the virgin curve, at -z_1, unless older ones were forgotten).
    std::size_t open_points(const double* z, int branch) const {
        const double b = branch < 0 ? -1.0 : 1.0, x = z[presliding];
        const std::size_t floor = z[truncated] > 0.5 ? 1 : 0;  // a kept bottom has lost what it would rejoin
        std::size_t m = stored(z);
        for (;;) {
            if (m >= 2 + floor && b * (x - z[turning + m - 2]) >= 0.0) m -= 2;
            else if (m == 1 && floor == 0 && b * (x + z[turning]) >= 0.0) m = 0;
            else return m;
        }
    }

    /// F_h at turning point j (0-based), replayed along the chain from the virgin curve or the kept bottom force.
    double point_force(double normal_force, const double* z, std::size_t j) const {
        double f = z[truncated] > 0.5 ? z[bottom_force] : virgin_curve(z[turning], normal_force);
        for (std::size_t i = 1; i <= j; ++i)
            f += 2.0 * virgin_curve(0.5 * (z[turning + i] - z[turning + i - 1]), normal_force);
        return f;
    }

    Curve curve(double normal_force, const double* z, int branch) const {
        const std::size_t m = open_points(z, branch);
        Curve c;
        if (m == 0) {
            c.transition = virgin_curve(z[presliding], normal_force);
        } else {
            c.turning_force = point_force(normal_force, z, m - 1);
            c.transition = 2.0 * virgin_curve(0.5 * (z[presliding] - z[turning + m - 1]), normal_force);
        }
        return c;
    }

    /// dz/dt = v (1 - sgn(r) |r|^n), r = 1 - (S - F_h) / D: the 2002 paper's F_d / (S - F_b) while the transition
    /// spans at least eps |S| (see the header).
    double rate(double v_r, double normal_force, int branch, const Curve& c) const {
        const double b = branch < 0 ? -1.0 : 1.0;
        const double s = stribeck_level(v_r, normal_force), target = b * s;
        const double span = b * std::max(b * (target - c.turning_force), min_transition_span * s);
        const double r = 1.0 - (target - c.turning_force - c.transition) / span;
        const double n = p_.attraction_exponent;
        const double shaped = n == 1.0 ? r : std::copysign(std::pow(std::abs(r), n), r);
        return v_r * (1.0 - shaped);
    }

    Params p_;
    std::size_t depth_ = 0;
};

}  // namespace frictionsim
