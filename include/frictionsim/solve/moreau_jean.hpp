// Event-capturing time-stepping for a linear mechanical system with many frictional point contacts (issue 13,
// item 1): Moreau's velocity-impulse theta-method (Moreau 1988; Jean 1999, CMAME 177, eqs 2.8-2.10; Acary and
// Brogliato 2008, "Numerical Methods for Nonsmooth Dynamical Systems", sec. 10.1, the MoreauJeanOSI of Siconos).
//
//   M v' = f(t) - C v - K q + r,    r_i in -kinetic_i Sgn(v_i) while slipping, |r_i| <= static_i while v_i = 0
//
// One step of size h, with q_{k+theta} = q_k + theta h v_{k+theta}:
//   W v_{k+1} = W v_k - h C v_k - h K (q_k + theta h v_k) + h (theta f_{k+1} + (1 - theta) f_k) + h r_{k+1},
//   W = M + theta h C + theta^2 h^2 K,          q_{k+1} = q_k + h ((1 - theta) v_k + theta v_{k+1}),
// and r_{k+1} solves the set-valued contact law at v_{k+1} for all contacts at once. No regularisation: a stuck
// contact has v = 0 exactly. The one-step problem is solved by an active-set (primal-dual, semi-smooth Newton)
// iteration over {stick, slip+, slip-} per contact, warm-started from the previous step: each iteration solves
// W v = b with the stuck degrees of freedom eliminated (their rows and columns replaced by the identity, so the
// band stays a band), one banded LDL^T factorisation when the stuck set changed and none when it did not (on a
// chain, W tridiagonal, only the pieces between stuck dofs that hold a switched one are refactored). On a
// string W is a Stieltjes matrix, for which this iteration converges monotonically in the monotone case
// (Hintermueller, Ito and Kunisch 2002, SIAM J. Optim. 13, Thm 3.1); static > kinetic (a non-monotone law) keeps
// Leine's switch model: a contact at rest, or reaching rest within the step, sticks while |r| <= static.
//
// ContactTreatment::projection is the explicit special case used by field codes (e.g. Aarsnes and Shor 2018,
// torsionalWaveStep.m): symplectic Euler, W = M (lumped, diagonal), so the inclusion decouples per contact and its
// solution is the predicted force (the one that stops the contact in this step) clipped to the static bound; field
// codes apply it inside a stick band |v| < band and the kinetic force outside.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "../detail/validate.hpp"
#include "../error.hpp"

namespace frictionsim {

/// A frictional point contact on one degree of freedom (forces in the dof's unit: N, or N m for a rotation).
/// Optionally velocity-weakening in one step: while |v| < slow_speed (at the step's start: the level is explicit,
/// the direction and stick implicit) a slipping contact takes slow_bound instead, e.g. Aarsnes and Shor's eq 4
/// (the static level below omega_c, the kinetic above).
struct PointContact {
    std::size_t dof = 0;
    double static_bound = 0.0;   ///< |r| <= static_bound while stuck (breakaway)
    double kinetic_bound = 0.0;  ///< |r| = kinetic_bound while slipping, <= static_bound
    double slow_bound = 0.0;     ///< |r| while slipping slower than slow_speed, <= static_bound
    double slow_speed = 0.0;     ///< 0: no slow level
};

/// M v' = f(t) - C v - K q + r over n degrees of freedom. M symmetric positive definite, C and K symmetric
/// positive semi-definite (a top drive's PI adds its gains to one diagonal entry of each). Their union pattern sets
/// the band of W: a string is tridiagonal.
struct LinearMechanicalSystem {
    Eigen::SparseMatrix<double> mass, damping, stiffness;
    /// f(t) into `out` (sized n); empty: no external force.
    std::function<void(double t, Eigen::VectorXd& out)> force;
    std::vector<PointContact> contacts;  ///< at most one per dof

    Eigen::Index size() const { return mass.rows(); }
};

enum class ContactTreatment {
    inclusion,   ///< the coupled one-step inclusion solved exactly (active set), implicit theta-method
    projection,  ///< explicit (symplectic Euler, W = M): predicted force clipped inside the stick band
};

enum class ContactState : signed char { slip_negative = -1, stick = 0, slip_positive = 1 };

/// A contact changed mode at the end of the step that reached `time`.
struct ContactEvent {
    enum class Kind : unsigned char { stick_to_slip, slip_to_stick, reversal };
    double time;
    std::size_t contact;
    Kind kind;
};

struct MoreauJeanOptions {
    double step = 1e-3;   ///< h [s]
    double theta = 0.5;   ///< in [0.5, 1]: 0.5 keeps the linear part's energy exactly, 1 damps it (both A-stable)
    ContactTreatment treatment = ContactTreatment::inclusion;
    double projection_band = 0.0;  ///< projection only: |v| below which the clipped predicted force acts
    /// Output times (increasing): the observer sees q and v interpolated linearly between steps there.
    std::vector<double> output_times;
    bool record_events = true;
    std::size_t max_events = 10'000'000;  ///< event log bound: past it the run stops (SimulationError)
    int max_active_set_iterations = 200;  ///< per step, before the run stops (SimulationError)
    std::function<bool()> interrupt;      ///< polled every 256 steps: true stops the run (Interrupted)

    void validate() const {
        constexpr const char* who = "MoreauJeanOptions";
        detail::require_positive(who, "step", step);
        if (!(theta >= 0.5 && theta <= 1.0))
            detail::reject(who, "theta", "in [0.5, 1] (below 0.5 the theta-method is not A-stable)", theta);
        detail::require_non_negative(who, "projection_band", projection_band);
        for (std::size_t i = 0; i < output_times.size(); ++i) {
            detail::require_finite(who, "output_times", output_times[i]);
            if (i > 0 && !(output_times[i] > output_times[i - 1]))
                detail::reject(who, "output_times", "strictly increasing", output_times[i]);
        }
        if (max_events == 0) detail::reject(who, "max_events", "positive", 0.0);
        if (max_active_set_iterations < 2)
            detail::reject(who, "max_active_set_iterations", ">= 2", max_active_set_iterations);
    }
};

namespace detail {

/// LDL^T of a symmetric positive definite band matrix (half-bandwidth b), without pivoting: O(n b^2) to factor,
/// O(n b) to solve. W = M + theta h C + theta^2 h^2 K is SPD, and stays so with identity rows for stuck dofs.
class BandLDLT {
public:
    void resize(Eigen::Index n, Eigen::Index b) {
        n_ = n;
        b_ = b;
        low_.assign(static_cast<std::size_t>(n * std::max<Eigen::Index>(b, 1)), 0.0);
        diag_.assign(static_cast<std::size_t>(n), 0.0);
    }
    /// Entry (i, i - j), j = 1..b, of the lower band; set before factor().
    double& lower(Eigen::Index i, Eigen::Index j) { return low_[static_cast<std::size_t>(i * b_ + j - 1)]; }
    double& diagonal(Eigen::Index i) { return diag_[static_cast<std::size_t>(i)]; }
    void clear() {
        std::fill(low_.begin(), low_.end(), 0.0);
        std::fill(diag_.begin(), diag_.end(), 0.0);
    }

    /// In place; false when a pivot is not positive (the matrix is not positive definite).
    bool factor() {
        if (b_ == 1) return factor_tridiagonal();
        for (Eigen::Index i = 0; i < n_; ++i) {
            const Eigen::Index jmin = std::max<Eigen::Index>(0, i - b_);
            for (Eigen::Index j = jmin; j < i; ++j) {  // L(i, j) = (A(i, j) - sum_k L(i,k) L(j,k) D(k)) / D(j)
                double s = lower(i, i - j);
                for (Eigen::Index k = std::max(jmin, j - b_); k < j; ++k)
                    s -= lower(i, i - k) * lower(j, j - k) * diag_[idx(k)];
                lower(i, i - j) = s / diag_[idx(j)];
            }
            double d = diag_[idx(i)];
            for (Eigen::Index k = jmin; k < i; ++k) d -= lower(i, i - k) * lower(i, i - k) * diag_[idx(k)];
            if (!(d > 0.0)) return false;
            diag_[idx(i)] = d;
        }
        return true;
    }

    void solve(Eigen::VectorXd& x) const {
        if (b_ == 1) return solve_tridiagonal(x);
        for (Eigen::Index i = 1; i < n_; ++i)
            for (Eigen::Index k = std::max<Eigen::Index>(0, i - b_); k < i; ++k) x(i) -= low(i, i - k) * x(k);
        for (Eigen::Index i = 0; i < n_; ++i) x(i) /= diag_[idx(i)];
        for (Eigen::Index i = n_ - 2; i >= 0; --i)
            for (Eigen::Index m = i + 1; m <= std::min(n_ - 1, i + b_); ++m) x(i) -= low(m, m - i) * x(m);
    }

    /// Tridiagonal only (b = 1): refactor after the stuck set changed from `was` to `stuck`, where W has diagonal
    /// `wd` and subdiagonal `wl` (wl[i] = W(i, i-1)) and a stuck dof's row and column are the identity's. A stuck
    /// dof cuts the chain, so d_i depends on the dofs above it only back to the nearest stuck one: only the pieces
    /// of the chain below a dof that switched (down to the next stuck dof) are recomputed.
    bool refactor_tridiagonal(const double* wd, const double* wl, const char* stuck, const char* was) {
        double* l = low_.data();
        double* d = diag_.data();
        bool carry = false;  // d_{i-1} was recomputed: d_i follows it unless a stuck dof cuts the chain
        for (Eigen::Index i = 0; i < n_; ++i) {
            const std::size_t k = idx(i);
            const bool switched = stuck[k] != was[k] || (i > 0 && stuck[k - 1] != was[k - 1]);
            if (!switched && !carry) continue;
            if (stuck[k]) {
                d[k] = 1.0;
                l[k] = 0.0;
                carry = false;
                continue;
            }
            if (i == 0 || stuck[k - 1]) {
                l[k] = 0.0;
                d[k] = wd[k];
            } else {
                const double li = wl[k] / d[k - 1];
                d[k] = wd[k] - li * wl[k];
                l[k] = li;
            }
            if (!(d[k] > 0.0)) return false;
            carry = true;
        }
        return true;
    }

private:
    // A string's W: the same recurrences without the band loops (they dominate a 1000-node step).
    bool factor_tridiagonal() {
        double* l = low_.data();
        double* d = diag_.data();
        if (!(d[0] > 0.0)) return false;
        for (Eigen::Index i = 1; i < n_; ++i) {
            const double li = l[i] / d[i - 1];
            d[i] -= li * l[i];
            l[i] = li;
            if (!(d[i] > 0.0)) return false;
        }
        return true;
    }
    void solve_tridiagonal(Eigen::VectorXd& x) const {
        const double* l = low_.data();
        const double* d = diag_.data();
        double* y = x.data();
        for (Eigen::Index i = 1; i < n_; ++i) y[i] -= l[i] * y[i - 1];
        y[n_ - 1] /= d[n_ - 1];
        for (Eigen::Index i = n_ - 2; i >= 0; --i) y[i] = y[i] / d[i] - l[i + 1] * y[i + 1];
    }

    static std::size_t idx(Eigen::Index i) { return static_cast<std::size_t>(i); }
    double low(Eigen::Index i, Eigen::Index j) const { return low_[static_cast<std::size_t>(i * b_ + j - 1)]; }
    Eigen::Index n_ = 0, b_ = 0;
    std::vector<double> low_, diag_;
};

}  // namespace detail

/// The time-stepper: construct with the system, the options and the initial state, then run(t_end) or step().
/// Contacts whose dof starts at rest start stuck.
class MoreauJean {
public:
    /// observer(t, q, v) at each requested output time (q, v linear between the steps around it).
    using Observer = std::function<void(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v)>;

    struct Statistics {
        long steps = 0;
        long factorisations = 0;    ///< banded LDL^T of W with the stuck set eliminated
        long solves = 0;            ///< one per active-set iteration
        long contact_switches = 0;  ///< contacts that changed mode, summed over steps
    };

    MoreauJean(LinearMechanicalSystem system, MoreauJeanOptions options, Eigen::VectorXd q0, Eigen::VectorXd v0,
               double t0 = 0.0)
        : sys_(std::move(system)), opt_(std::move(options)), q_(std::move(q0)), v_(std::move(v0)), t_(t0) {
        opt_.validate();
        constexpr const char* who = "MoreauJean";
        const Eigen::Index n = sys_.mass.rows();
        if (n == 0 || sys_.mass.cols() != n)
            detail::reject(who, "mass", "square and non-empty (rows given)", static_cast<double>(n));
        const auto check_matrix = [&](const char* name, Eigen::SparseMatrix<double>& a) {
            if (a.rows() == 0 && a.cols() == 0) a.resize(n, n);
            if (a.rows() != n || a.cols() != n)
                detail::reject(who, name, "n x n, n = mass.rows() (rows given)", static_cast<double>(a.rows()));
            a.makeCompressed();
            for (int i = 0; i < a.nonZeros(); ++i) detail::require_finite(who, name, a.valuePtr()[i]);
            const Eigen::SparseMatrix<double> at = a.transpose();
            if ((a - at).norm() > 1e-12 * (a.norm() + 1e-300)) detail::reject(who, name, "symmetric", (a - at).norm());
        };
        check_matrix("mass", sys_.mass);
        check_matrix("damping", sys_.damping);
        check_matrix("stiffness", sys_.stiffness);
        if (q_.size() != n) detail::reject(who, "q0", "of size mass.rows() (size given)", double(q_.size()));
        if (v_.size() != n) detail::reject(who, "v0", "of size mass.rows() (size given)", double(v_.size()));
        for (Eigen::Index i = 0; i < n; ++i) {
            detail::require_finite(who, "q0", q_(i));
            detail::require_finite(who, "v0", v_(i));
        }
        detail::require_finite(who, "t0", t_);
        std::vector<char> taken(static_cast<std::size_t>(n), 0);
        for (const PointContact& c : sys_.contacts) {
            if (c.dof >= static_cast<std::size_t>(n))
                detail::reject(who, "contacts.dof", "< mass.rows()", static_cast<double>(c.dof));
            if (taken[c.dof]) detail::reject(who, "contacts.dof", "one contact per dof", static_cast<double>(c.dof));
            taken[c.dof] = 1;
            detail::require_non_negative(who, "contacts.kinetic_bound", c.kinetic_bound);
            detail::require_at_least(who, "contacts.static_bound", c.static_bound, c.kinetic_bound,
                                     ">= kinetic_bound and finite");
            detail::require_non_negative(who, "contacts.slow_speed", c.slow_speed);
            if (c.slow_speed > 0.0 && !(c.slow_bound >= 0.0 && c.slow_bound <= c.static_bound))
                detail::reject(who, "contacts.slow_bound", "in [0, static_bound]", c.slow_bound);
        }
        if (opt_.treatment == ContactTreatment::projection) {
            for (int k = 0; k < sys_.mass.outerSize(); ++k)
                for (Eigen::SparseMatrix<double>::InnerIterator it(sys_.mass, k); it; ++it)
                    if (it.row() != it.col() && it.value() != 0.0)
                        detail::reject(who, "mass", "diagonal (lumped) for the explicit projection", it.value());
        }

        const double h = opt_.step, th = opt_.theta;
        if (opt_.treatment == ContactTreatment::inclusion)
            w_ = sys_.mass + (th * h) * sys_.damping + (th * th * h * h) * sys_.stiffness;
        else
            w_ = sys_.mass;
        w_.makeCompressed();
        w_diag_ = w_.diagonal();
        w_sub_.assign(static_cast<std::size_t>(n), 0.0);
        for (int k = 0; k < w_.outerSize(); ++k)
            for (Sparse::InnerIterator it(w_, k); it; ++it)
                if (it.row() == it.col() + 1) w_sub_[static_cast<std::size_t>(it.row())] = it.value();
        free_operator_ = sys_.mass - ((1.0 - th) * h) * sys_.damping - (th * (1.0 - th) * h * h) * sys_.stiffness;
        free_operator_.makeCompressed();
        step_stiffness_ = h * sys_.stiffness;
        step_stiffness_.makeCompressed();
        chain_.assign(static_cast<std::size_t>(n), Chain{});
        const auto to_chain = [&](const Sparse& a, double Chain::*diag, double Chain::*sub) {
            for (int k = 0; k < a.outerSize(); ++k)
                for (Sparse::InnerIterator it(a, k); it; ++it) {
                    const Eigen::Index i = it.row(), j = it.col();
                    if (i == j) chain_[static_cast<std::size_t>(i)].*diag += it.value();
                    else if (i == j + 1) chain_[static_cast<std::size_t>(i)].*sub += it.value();
                    else if (i + 1 != j) return false;  // (i, i + 1) is (i + 1, i): A and K are symmetric
                }
            return true;
        };
        if (!(to_chain(free_operator_, &Chain::a_diag, &Chain::a_sub) &&
              to_chain(step_stiffness_, &Chain::k_diag, &Chain::k_sub)))
            chain_.clear();  // wider than a chain: the sparse products
        band_ = 0;
        for (int k = 0; k < w_.outerSize(); ++k)
            for (Eigen::SparseMatrix<double>::InnerIterator it(w_, k); it; ++it)
                band_ = std::max<Eigen::Index>(band_, std::abs(it.row() - it.col()));
        ldlt_.resize(n, band_);

        f_now_ = Eigen::VectorXd::Zero(n);
        f_next_ = Eigen::VectorXd::Zero(n);
        if (sys_.force) sys_.force(t_, f_now_);
        modes_.resize(sys_.contacts.size());
        reaction_ = Eigen::VectorXd::Zero(n);
        for (std::size_t j = 0; j < sys_.contacts.size(); ++j) {
            const double vj = v_(static_cast<Eigen::Index>(sys_.contacts[j].dof));
            modes_[j] = mode_of(vj);
        }
        stuck_.assign(static_cast<std::size_t>(n), 0);
        factored_stuck_.assign(static_cast<std::size_t>(n), 2);  // nothing factored yet
        if (!factor_with(stuck_))
            detail::reject(who, "mass", "positive definite (W = M + theta h C + theta^2 h^2 K is not)", 0.0);
        q_prev_ = q_;
        v_prev_ = v_;
        b_.resize(n);
        x_.resize(n);
    }

    double time() const { return t_; }
    const Eigen::VectorXd& positions() const { return q_; }
    const Eigen::VectorXd& velocities() const { return v_; }
    /// Contact forces r of the last step, per dof (0 where there is no contact): impulse / h.
    const Eigen::VectorXd& contact_forces() const { return reaction_; }
    const std::vector<ContactState>& modes() const { return modes_; }
    const std::vector<ContactEvent>& events() const { return events_; }
    const Statistics& statistics() const { return stats_; }
    const LinearMechanicalSystem& system() const { return sys_; }
    const MoreauJeanOptions& options() const { return opt_; }
    /// f(t) over the last step: theta f_{k+1} + (1 - theta) f_k (what the step applied; explicit: f_k).
    const Eigen::VectorXd& applied_force() const { return f_applied_; }

    /// Changes contact j's bounds between steps (a law whose levels move with the state, e.g. a velocity-weakening
    /// bit's kinetic torque taken at the step's start). Same rules as at construction.
    void set_contact_bounds(std::size_t j, double static_bound, double kinetic_bound) {
        constexpr const char* who = "MoreauJean::set_contact_bounds";
        if (j >= sys_.contacts.size())
            detail::reject(who, "contact", "< the number of contacts", static_cast<double>(j));
        detail::require_non_negative(who, "kinetic_bound", kinetic_bound);
        detail::require_at_least(who, "static_bound", static_bound, kinetic_bound, ">= kinetic_bound and finite");
        PointContact& c = sys_.contacts[j];
        if (c.slow_speed > 0.0 && !(c.slow_bound <= static_bound))
            detail::reject(who, "static_bound", ">= the contact's slow_bound", static_bound);
        c.static_bound = static_bound;
        c.kinetic_bound = kinetic_bound;
    }

    /// Steps of h until t_end is reached or passed by less than h / 2 (the grid t0 + k h), calling the observer
    /// at the output times on the way. Non-finite states stop with SimulationError at the last finite time.
    void run(double t_end, const Observer& observer = nullptr) {
        detail::require_finite("MoreauJean", "t_end", t_end);
        while (next_output_ < opt_.output_times.size() && opt_.output_times[next_output_] < t_ - 1e-12 * opt_.step)
            ++next_output_;  // before the start: never seen
        emit_outputs(observer, false);
        while (t_ + 0.5 * opt_.step < t_end) {
            step();
            emit_outputs(observer, true);
        }
    }

    /// One step of h.
    void step() {
        const double h = opt_.step, t_next = t_ + h;
        if (opt_.interrupt && (stats_.steps & 255) == 0 && opt_.interrupt()) {
            std::ostringstream msg;
            msg.precision(17);
            msg << "MoreauJean: interrupted at t = " << t_ << " s";
            throw Interrupted(msg.str(), t_);
        }
        q_prev_ = q_;
        v_prev_ = v_;
        previous_modes_ = modes_;
        if (sys_.force) {
            f_next_.setZero();
            sys_.force(t_next, f_next_);
        }
        if (opt_.treatment == ContactTreatment::inclusion)
            step_inclusion(h);
        else
            step_projection(h);
        ++stats_.steps;
        for (Eigen::Index i = 0; i < v_.size(); ++i)
            if (!std::isfinite(v_(i)) || !std::isfinite(q_(i))) {
                q_ = q_prev_;
                v_ = v_prev_;
                std::ostringstream msg;
                msg.precision(17);
                msg << "MoreauJean: non-finite state at dof " << i << " in the step from t = " << t_ << " s";
                throw SimulationError(msg.str(), t_);
            }
        t_ = t_next;
        std::swap(f_now_, f_next_);
        log_switches();
    }

private:
    using Sparse = Eigen::SparseMatrix<double>;

    static ContactState mode_of(double v) {
        return v > 0.0 ? ContactState::slip_positive : v < 0.0 ? ContactState::slip_negative : ContactState::stick;
    }

    /// b = W v - h C v - h K (q + theta h v) + h f_theta (the free velocity's right-hand side).
    /// Written as b = A v - h K q + h f_theta, A = M - (1 - theta) h C - theta (1 - theta) h^2 K (precomputed).
    void free_rhs(double h) {
        const double th = opt_.theta;
        f_applied_ = th * f_next_ + (1.0 - th) * f_now_;
        if (!chain_.empty()) {  // tridiagonal A and K: one pass instead of two sparse products
            const Eigen::Index n = v_.size();
            const double* v = v_.data();
            const double* q = q_.data();
            const double* f = f_applied_.data();
            const Chain* c = chain_.data();
            double* b = b_.data();
            for (Eigen::Index i = 0; i < n; ++i) {
                double s = c[i].a_diag * v[i] - c[i].k_diag * q[i] + h * f[i];
                if (i > 0) s += c[i].a_sub * v[i - 1] - c[i].k_sub * q[i - 1];
                if (i + 1 < n) s += c[i + 1].a_sub * v[i + 1] - c[i + 1].k_sub * q[i + 1];
                b[i] = s;
            }
            return;
        }
        b_.noalias() = free_operator_ * v_;
        b_.noalias() -= step_stiffness_ * q_;
        b_ += h * f_applied_;
    }

    /// Factor W with the dofs in `stuck` replaced by identity rows/columns; no work if that set is factored.
    bool factor_with(const std::vector<char>& stuck) {
        if (stuck == factored_stuck_) return true;
        if (band_ == 1 && factored_once_) {  // a chain: only the pieces below the switched dofs change
            ++stats_.factorisations;
            const bool ok = ldlt_.refactor_tridiagonal(w_diag_.data(), w_sub_.data(), stuck.data(),
                                                       factored_stuck_.data());
            factored_stuck_ = stuck;
            return ok;
        }
        ldlt_.clear();
        for (int k = 0; k < w_.outerSize(); ++k)
            for (Sparse::InnerIterator it(w_, k); it; ++it) {
                const Eigen::Index i = it.row(), j = it.col();
                if (i < j) continue;
                if (stuck[static_cast<std::size_t>(i)] || stuck[static_cast<std::size_t>(j)]) continue;
                if (i == j) ldlt_.diagonal(i) += it.value();
                else ldlt_.lower(i, i - j) += it.value();
            }
        for (std::size_t i = 0; i < stuck.size(); ++i)
            if (stuck[i]) ldlt_.diagonal(static_cast<Eigen::Index>(i)) = 1.0;
        ++stats_.factorisations;
        factored_stuck_ = stuck;
        factored_once_ = ldlt_.factor();
        return factored_once_;
    }

    void step_inclusion(double h) {
        free_rhs(h);
        if (!b_.allFinite()) throw_at(t_, "non-finite force or state");  // a NaN would pass any stick test
        const std::size_t nc = sys_.contacts.size();
        const int max_iter = opt_.max_active_set_iterations;
        violation_.assign(nc, 0.0);
        std::vector<double>& violation = violation_;
        level_.resize(nc);
        for (std::size_t j = 0; j < nc; ++j) {  // the slip force of this step, from the speed at its start
            const PointContact& c = sys_.contacts[j];
            const double speed = std::abs(v_prev_(static_cast<Eigen::Index>(c.dof)));
            level_[j] = speed < c.slow_speed ? c.slow_bound : c.kinetic_bound;
        }
        for (std::size_t j = 0; j < nc; ++j)  // kept in step with modes_ below
            stuck_[sys_.contacts[j].dof] = modes_[j] == ContactState::stick ? 1 : 0;
        for (int iter = 0;; ++iter) {
            // the linear solve for the current guess: stuck dofs at rest, slipping ones at -kinetic sgn
            if (!factor_with(stuck_)) throw_at(t_, "W lost positive definiteness");
            x_ = b_;
            for (std::size_t j = 0; j < nc; ++j) {
                const PointContact& c = sys_.contacts[j];
                const Eigen::Index d = static_cast<Eigen::Index>(c.dof);
                if (modes_[j] == ContactState::stick) x_(d) = 0.0;
                else x_(d) -= h * level_[j] * static_cast<double>(modes_[j]);
            }
            ldlt_.solve(x_);
            ++stats_.solves;
            // check each contact against its law; collect the changes
            int changes = 0;
            double worst = 0.0;
            std::size_t worst_j = nc;
            for (std::size_t j = 0; j < nc; ++j) {
                const PointContact& c = sys_.contacts[j];
                const Eigen::Index d = static_cast<Eigen::Index>(c.dof);
                violation[j] = 0.0;
                if (modes_[j] == ContactState::stick) {
                    const double r = (row_dot(d, x_) - b_(d)) / h;  // the force that holds v_d = 0
                    reaction_(d) = r;
                    if (std::abs(r) > c.static_bound) violation[j] = std::abs(r) - c.static_bound;
                } else {
                    const double sigma = static_cast<double>(modes_[j]);
                    reaction_(d) = -level_[j] * sigma;
                    // in force units, comparable with a stick violation: the force that would stop it
                    if (!(sigma * x_(d) > 0.0)) violation[j] = w_diag_(d) * std::abs(x_(d)) / h + 1e-300;
                }
                if (violation[j] > 0.0) {
                    ++changes;
                    if (violation[j] > worst) {
                        worst = violation[j];
                        worst_j = j;
                    }
                }
            }
            if (changes == 0) break;
            if (iter + 1 >= max_iter)
                throw_at(t_, "the contact active set did not settle in max_active_set_iterations");
            // PDAS: change every violated contact; past half the budget one at a time (the worst), which cannot
            // cycle in the monotone case (Murty's scheme for P-matrices).
            for (std::size_t j = 0; j < nc; ++j) {
                if (violation[j] <= 0.0) continue;
                if (iter >= max_iter / 2 && j != worst_j) continue;
                const Eigen::Index d = static_cast<Eigen::Index>(sys_.contacts[j].dof);
                if (modes_[j] == ContactState::stick)  // breaks away against the force that could not hold it
                    modes_[j] = reaction_(d) > 0.0 ? ContactState::slip_negative : ContactState::slip_positive;
                else  // reaches rest within the step: Leine's stick test (against the static bound) next
                    modes_[j] = ContactState::stick;
                stuck_[static_cast<std::size_t>(d)] = modes_[j] == ContactState::stick ? 1 : 0;
            }
        }
        v_.swap(x_);
        q_ += h * ((1.0 - opt_.theta) * v_prev_ + opt_.theta * v_);
        for (std::size_t j = 0; j < nc; ++j)  // exact zero, not a solve's round-off
            if (modes_[j] == ContactState::stick) v_(static_cast<Eigen::Index>(sys_.contacts[j].dof)) = 0.0;
    }

    /// Symplectic Euler with each contact's force from its own predicted velocity (W = M diagonal).
    void step_projection(double h) {
        f_applied_ = f_now_;
        x_ = f_now_ - sys_.damping * v_ - sys_.stiffness * q_;  // forces at the step's start
        if (!x_.allFinite()) throw_at(t_, "non-finite force or state");
        for (Eigen::Index i = 0; i < v_.size(); ++i) v_(i) += h * x_(i) / w_diag_(i);
        for (std::size_t j = 0; j < sys_.contacts.size(); ++j) {
            const PointContact& c = sys_.contacts[j];
            const Eigen::Index d = static_cast<Eigen::Index>(c.dof);
            const double m = w_diag_(d), v_free = v_(d);
            double r;
            if (v_prev_(d) == 0.0 || std::abs(v_prev_(d)) < opt_.projection_band) {
                r = -m * v_free / h;  // the force that stops the contact in this step, clipped to the static bound
                if (std::abs(r) <= c.static_bound) v_(d) = 0.0;
                else r = std::copysign(c.static_bound, r);
            } else {
                r = -std::copysign(c.kinetic_bound, v_prev_(d));
            }
            if (v_(d) != 0.0) v_(d) = v_free + h * r / m;
            reaction_(d) = r;
            modes_[j] = mode_of(v_(d));
        }
        q_ += h * v_;
    }

    double row_dot(Eigen::Index d, const Eigen::VectorXd& x) const {
        double s = 0.0;  // W symmetric: column d is row d
        for (Sparse::InnerIterator it(w_, d); it; ++it) s += it.value() * x(it.row());
        return s;
    }

    void log_switches() {
        for (std::size_t j = 0; j < modes_.size(); ++j) {
            const ContactState a = previous_modes_[j], b = modes_[j];
            if (a == b) continue;
            ++stats_.contact_switches;
            if (!opt_.record_events) continue;
            if (events_.size() >= opt_.max_events) {
                std::ostringstream msg;
                msg << "MoreauJean: more than max_events = " << opt_.max_events << " contact switches";
                throw SimulationError(msg.str(), t_);
            }
            const ContactEvent::Kind kind = a == ContactState::stick   ? ContactEvent::Kind::stick_to_slip
                                            : b == ContactState::stick ? ContactEvent::Kind::slip_to_stick
                                                                      : ContactEvent::Kind::reversal;
            events_.push_back(ContactEvent{t_, j, kind});
        }
    }

    void emit_outputs(const Observer& observer, bool stepped) {
        const double tol = 1e-9 * opt_.step;
        while (next_output_ < opt_.output_times.size() && opt_.output_times[next_output_] <= t_ + tol) {
            const double to = opt_.output_times[next_output_++];
            if (!observer) continue;
            if (!stepped || std::abs(to - t_) <= tol) {
                observer(to, q_, v_);
            } else {
                const double a = std::clamp((to - (t_ - opt_.step)) / opt_.step, 0.0, 1.0);
                observer(to, (1.0 - a) * q_prev_ + a * q_, (1.0 - a) * v_prev_ + a * v_);
            }
        }
    }

    [[noreturn]] void throw_at(double t, const char* what) const {
        std::ostringstream msg;
        msg.precision(17);
        msg << "MoreauJean: " << what << " (step from t = " << t << " s)";
        throw SimulationError(msg.str(), t);
    }

    LinearMechanicalSystem sys_;
    MoreauJeanOptions opt_;
    Eigen::VectorXd q_, v_, q_prev_, v_prev_, f_now_, f_next_, f_applied_, b_, x_, reaction_;
    double t_;
    Sparse w_, free_operator_, step_stiffness_;
    struct Chain {  // row i of tridiagonal A and h K: (i, i) and (i, i - 1)
        double a_diag = 0.0, a_sub = 0.0, k_diag = 0.0, k_sub = 0.0;
    };
    std::vector<Chain> chain_;  // empty unless A and h K are tridiagonal
    Eigen::VectorXd w_diag_;
    std::vector<double> w_sub_;  // W(i, i - 1): the chain's refactorisation reads it
    bool factored_once_ = false;
    Eigen::Index band_ = 0;
    detail::BandLDLT ldlt_;
    std::vector<ContactState> modes_, previous_modes_;
    std::vector<double> level_, violation_;
    std::vector<char> stuck_, factored_stuck_;
    std::vector<ContactEvent> events_;
    std::size_t next_output_ = 0;
    Statistics stats_;
};

}  // namespace frictionsim
