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
// band stays a band), one banded LDL^T factorisation when the stuck set changed and none when it did not. On a
// chain (W tridiagonal: a string; detail::ChainLDLT) an iteration after the step's first reruns the factorisation
// and the solve's recurrences from the switched dofs only as far as their values change (a switch's influence
// decays along the chain, a stuck dof stops it), with the operations of a whole-chain solve in the same order:
// the same iterates, bit for bit, at a cost that follows the switches. On a string W is a Stieltjes matrix, for
// which this iteration converges monotonically in the monotone case (Hintermueller, Ito and Kunisch 2002, SIAM J.
// Optim. 13, Thm 3.1); static > kinetic (a non-monotone law) keeps Leine's switch model: a contact at rest, or
// reaching rest within the step, sticks while |r| <= static.
//
// The one-step problem's solver is swappable (MoreauJeanOptions::contact_solver, eigen/one_step_contact.hpp: e.g.
// ProjectedGaussSeidel); the exact active set above is the default.
//
// ContactTreatment::projection is the explicit special case used by field codes (e.g. Aarsnes and Shor 2018,
// torsionalWaveStep.m): symplectic Euler, W = M (lumped, diagonal), so the inclusion decouples per contact and its
// solution is the predicted force (the one that stops the contact in this step) clipped to the static bound; field
// codes apply it inside a stick band |v| < band and the kinetic force outside.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <numeric>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "../detail/validate.hpp"
#include "../error.hpp"
#include "chain_ldlt.hpp"
#include "one_step_contact.hpp"

namespace frictionsim {

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
    /// per step: half of it primal-dual active-set iterations (every violated contact switched), then the worst
    /// contact alone (Murty), which may take up to 2 pivots per contact beyond it before the run stops
    /// (SimulationError): a budget of 200 alone stopped Well B at 4000 elements (h = 10 ms) with hundreds of
    /// contacts still to switch one at a time. A step that settles within it takes the same iterates as before.
    int max_active_set_iterations = 200;
    std::function<bool()> interrupt;      ///< polled every 256 steps: true stops the run (Interrupted)
    /// inclusion only: the one-step contact problem's solver (eigen/one_step_contact.hpp), e.g.
    /// ProjectedGaussSeidel{}; empty: the exact active set (on a chain, with its updated LDL^T)
    ContactSolver contact_solver;

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
        if (contact_solver && treatment == ContactTreatment::projection)
            detail::reject(who, "contact_solver", "empty with the explicit projection (its force is explicit)", 0.0);
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
        long factorisations = 0;    ///< banded LDL^T of W with the stuck set eliminated (a chain: updated)
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
        free_operator_ = sys_.mass - ((1.0 - th) * h) * sys_.damping - (th * (1.0 - th) * h * h) * sys_.stiffness;
        free_operator_.makeCompressed();
        step_stiffness_ = h * sys_.stiffness;
        step_stiffness_.makeCompressed();
        const auto to_chain = [&](const Sparse& a, std::vector<double>& diag, std::vector<double>& sub) {
            diag.assign(static_cast<std::size_t>(n), 0.0);
            sub.assign(static_cast<std::size_t>(n), 0.0);
            for (int k = 0; k < a.outerSize(); ++k)
                for (Sparse::InnerIterator it(a, k); it; ++it) {
                    const Eigen::Index i = it.row(), j = it.col();
                    if (i == j) diag[static_cast<std::size_t>(i)] += it.value();
                    else if (i == j + 1) sub[static_cast<std::size_t>(i)] += it.value();
                    else if (i + 1 != j) return false;  // (i, i + 1) is (i + 1, i): A and K are symmetric
                }
            return true;
        };
        const bool tridiagonal = to_chain(free_operator_, a_diag_, a_sub_) && to_chain(step_stiffness_, k_diag_, k_sub_);
        band_ = 0;
        for (int k = 0; k < w_.outerSize(); ++k)
            for (Eigen::SparseMatrix<double>::InnerIterator it(w_, k); it; ++it)
                band_ = std::max<Eigen::Index>(band_, std::abs(it.row() - it.col()));
        on_chain_ = opt_.treatment == ContactTreatment::inclusion && !opt_.contact_solver && tridiagonal && band_ <= 1;
        if (on_chain_) {
            const std::size_t m = static_cast<std::size_t>(n);
            std::vector<double> sub(m, 0.0), super(m, 0.0);
            for (int k = 0; k < w_.outerSize(); ++k)
                for (Sparse::InnerIterator it(w_, k); it; ++it) {
                    if (it.row() == it.col() + 1) sub[static_cast<std::size_t>(it.row())] = it.value();
                    if (it.row() + 1 == it.col()) super[static_cast<std::size_t>(it.col())] = it.value();
                }
            chain_ldlt_.assign(std::vector<double>(w_diag_.data(), w_diag_.data() + n), std::move(sub), std::move(super));
            contact_at_.assign(m, -1);
            static_at_.assign(m, 0.0);
            kinetic_at_.assign(m, 0.0);
            slow_at_.assign(m, 0.0);
            slow_speed_at_.assign(m, 0.0);
            for (std::size_t j = 0; j < sys_.contacts.size(); ++j) {
                const PointContact& c = sys_.contacts[j];
                contact_at_[c.dof] = static_cast<long>(j);
                static_at_[c.dof] = c.static_bound;
                kinetic_at_[c.dof] = c.kinetic_bound;
                slow_at_[c.dof] = c.slow_bound;
                slow_speed_at_[c.dof] = c.slow_speed;
            }
            slip_level_.assign(m, 0.0);
            sigma_.assign(m, 0.0);
            rhs_ = Eigen::VectorXd::Zero(n);
            free_mask_.assign(m, ~std::uint64_t{0});
        } else {
            ldlt_.resize(n, band_);
        }

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
        bool definite;
        if (on_chain_) {
            ++stats_.factorisations;
            definite = chain_ldlt_.factor(stuck_.data());
            for (std::size_t j = 0; j < sys_.contacts.size(); ++j) {  // the chain keeps per-dof copies of the modes
                const std::size_t d = sys_.contacts[j].dof;
                stuck_[d] = modes_[j] == ContactState::stick ? 1 : 0;
                free_mask_[d] = stuck_[d] ? 0 : ~std::uint64_t{0};
                sigma_[d] = static_cast<double>(modes_[j]);
                refactor_chain_ = refactor_chain_ || stuck_[d];
            }
        } else {
            definite = factor_with(stuck_);
        }
        if (!definite)
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
        if (on_chain_) {
            static_at_[c.dof] = static_bound;
            kinetic_at_[c.dof] = kinetic_bound;
        }
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
        if (!on_chain_) {  // the chain's step leaves the previous state there by swapping, not copying
            q_prev_ = q_;
            v_prev_ = v_;
        }
        previous_modes_ = modes_;
        if (sys_.force) {
            f_next_.setZero();
            sys_.force(t_next, f_next_);
        }
        bool finite = false;  // known finite (the chain's last pass checks it)
        if (on_chain_)
            finite = step_chain(h);
        else if (opt_.treatment == ContactTreatment::inclusion)
            step_inclusion(h);
        else
            step_projection(h);
        ++stats_.steps;
        for (Eigen::Index i = 0; !finite && i < v_.size(); ++i)
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
        if (on_chain_ && !opt_.record_events) {  // counted only: whose modes differ
            stats_.contact_switches += static_cast<long>(
                std::inner_product(modes_.begin(), modes_.end(), previous_modes_.begin(), std::size_t{0},
                                   std::plus<>(), std::not_equal_to<>()));
        } else if (on_chain_) {  // the contacts that switched at some iteration, in index order
            std::sort(switched_contacts_.begin(), switched_contacts_.end());
            switched_contacts_.erase(std::unique(switched_contacts_.begin(), switched_contacts_.end()),
                                     switched_contacts_.end());
            for (std::size_t j : switched_contacts_) log_switch(j);
            switched_contacts_.clear();
        } else {
            for (std::size_t j = 0; j < modes_.size(); ++j) log_switch(j);
        }
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
        b_.noalias() = free_operator_ * v_;
        b_.noalias() -= step_stiffness_ * q_;
        b_ += h * f_applied_;
    }

    /// Factor W with the dofs in `stuck` replaced by identity rows/columns; no work if that set is factored.
    bool factor_with(const std::vector<char>& stuck) {
        if (stuck == factored_stuck_) return true;
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
        return ldlt_.factor();
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
        if (opt_.contact_solver) return solve_contacts_with(opt_.contact_solver, h);
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
            if (iter + 1 >= max_iter + 2 * static_cast<long>(nc))
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

    /// The step's contact problem handed to a ContactSolver (b_ and level_ set), warm-started from the step's start.
    void solve_contacts_with(const ContactSolver& solver, double h) {
        const Eigen::Index n = v_.size();
        contact_solution_.v = v_prev_;
        contact_solution_.modes = modes_;
        const OneStepContactProblem problem{w_, b_, h, sys_.contacts, level_};
        int iterations = 0;
        try {
            iterations = solver(problem, contact_solution_);
        } catch (const SimulationError& e) {
            throw_at(t_, e.what());
        }
        if (contact_solution_.v.size() != n || contact_solution_.r.size() != n ||
            contact_solution_.modes.size() != modes_.size())
            throw_at(t_, "the contact solver left v, r or the modes of the wrong size");
        stats_.solves += iterations;
        v_ = contact_solution_.v;
        reaction_ = contact_solution_.r;
        modes_ = contact_solution_.modes;
        q_ += h * ((1.0 - opt_.theta) * v_prev_ + opt_.theta * v_);
    }

    /// step_inclusion on a chain (detail::ChainLDLT), on plain arrays. The step's first iteration runs over the
    /// whole chain: b, the slip levels and the right-hand side (loops that vectorise), the solve, every contact's
    /// check. Each later iteration updates the factors and the solution from the contacts it switched, as far as
    /// they change, and checks the contacts there and next to it (the only ones whose test can have changed); one
    /// that switched more than n / 8 contacts reruns whole-chain passes instead (the same bits). Past half the
    /// iteration budget the general rule (the worst contact alone) with whole-chain passes. The same
    /// iterates as step_inclusion, bit for bit; per-dof copies of the modes (stuck_, free_mask_, sigma_) follow
    /// modes_. The previous state is left in q_prev_, v_prev_ by swapping; returns whether the new one is finite.
    bool step_chain(double h) {
        const double th = opt_.theta;
        f_applied_ = th * f_next_ + (1.0 - th) * f_now_;
        const std::size_t n = static_cast<std::size_t>(v_.size());
        const int max_iter = opt_.max_active_set_iterations;
        const char* stuck = stuck_.data();
        switched_contacts_.clear();
        if (refactor_chain_) {  // the first step from a state with stuck contacts
            ++stats_.factorisations;
            if (!chain_ldlt_.factor(stuck)) throw_at(t_, "W lost positive definiteness");
            refactor_chain_ = false;
        }
        double* b = b_.data();
        double* x = x_.data();
        double* r = rhs_.data();
        double* reaction = reaction_.data();
        double* level = slip_level_.data();
        const double* sigma = sigma_.data();
        {  // per dof: b = A v - h K q + h f_theta, the slip force from the speed at the step's start, the solve's
           // right-hand side (plain loops over arrays, each simple enough to vectorise: measured faster than one
           // loop fused with the forward elimination)
            const double* v = v_.data();
            const double* q = q_.data();
            const double* f = f_applied_.data();
            const double *ad = a_diag_.data(), *as = a_sub_.data(), *kd = k_diag_.data(), *ks = k_sub_.data();
            const auto row = [=](std::size_t i) { return ad[i] * v[i] - kd[i] * q[i] + h * f[i]; };
            std::uint64_t carry = 0;  // detail::all_finite's test, in the same loop
            if (n == 1) {
                b[0] = row(0);
            } else {
                b[0] = row(0) + (as[1] * v[1] - ks[1] * q[1]);
                b[n - 1] = row(n - 1) + (as[n - 1] * v[n - 2] - ks[n - 1] * q[n - 2]);
                carry = detail::exponent_carry(b[n - 1]);
            }
            carry |= detail::exponent_carry(b[0]);
            for (std::size_t i = 1; i + 1 < n; ++i) {
                b[i] = (row(i) + (as[i] * v[i - 1] - ks[i] * q[i - 1])) + (as[i + 1] * v[i + 1] - ks[i + 1] * q[i + 1]);
                carry |= detail::exponent_carry(b[i]);
            }
            if (carry >> 63) throw_at(t_, "non-finite force or state");  // a NaN would pass any stick test
            const double *slow_speed = slow_speed_at_.data(), *slow = slow_at_.data(), *kinetic = kinetic_at_.data();
            const std::uint64_t* free = free_mask_.data();
            for (std::size_t i = 0; i < n; ++i) {
                const double low = slow[i], high = kinetic[i];  // both read: a select, not a branch
                level[i] = std::abs(v[i]) < slow_speed[i] ? low : high;
            }
            for (std::size_t i = 0; i < n; ++i) r[i] = detail::masked(b[i] - h * level[i] * sigma[i], free[i]);
            chain_ldlt_.forward(r);
        }
        violated_.clear();
        chain_ldlt_.backward(x);
        // a loop of its own: checks inside the recurrence's loop (a branch on each fresh x_i) measured 15 % slower
        for (std::size_t i = 0; i < n; ++i) check_dof(i, h);
        bool whole = false;
        for (int iter = 0;; ++iter) {
            ++stats_.solves;
            if (violated_.empty()) break;
            if (iter + 1 >= max_iter + 2 * static_cast<long>(sys_.contacts.size()))
                throw_at(t_, "the contact active set did not settle in max_active_set_iterations");
            // PDAS: change every violated contact; past half the budget one at a time (the worst), which cannot
            // cycle in the monotone case (Murty's scheme for P-matrices).
            whole = iter >= max_iter / 2;
            std::size_t worst_j = sys_.contacts.size();
            double worst = 0.0;
            for (const auto& [j, violation] : violated_)
                if (violation > worst || (violation == worst && j < worst_j)) {
                    worst = violation;
                    worst_j = j;
                }
            switched_.clear();
            for (const auto& [j, violation] : violated_) {
                if (whole && j != worst_j) continue;
                const std::size_t d = sys_.contacts[j].dof;
                if (modes_[j] == ContactState::stick)  // breaks away against the force that could not hold it
                    modes_[j] = reaction[d] > 0.0 ? ContactState::slip_negative : ContactState::slip_positive;
                else  // reaches rest within the step: Leine's stick test (against the static bound) next
                    modes_[j] = ContactState::stick;
                stuck_[d] = modes_[j] == ContactState::stick ? 1 : 0;
                free_mask_[d] = stuck_[d] ? 0 : ~std::uint64_t{0};
                sigma_[d] = static_cast<double>(modes_[j]);
                r[d] = stuck[d] ? 0.0 : b[d] - h * level[d] * sigma[d];
                switched_.push_back(d);
                if (opt_.record_events) switched_contacts_.push_back(j);
            }
            ++stats_.factorisations;  // the stuck set changed
            violated_.clear();
            // many switches (past n / 8): plain whole-chain passes, the same bits as the update's and cheaper there
            // (the update's reach, ~100-200 dofs per switch on Well B at h = 10 ms, then covers most of the chain,
            // and its span bookkeeping costs more per dof than the plain loops); the factors and y rerun from the
            // outermost switched dofs towards the twist (nothing outside them changed), x over the whole chain
            if (whole || switched_.size() * 8 > n) {
                const auto [lo, hi] = std::minmax_element(switched_.begin(), switched_.end());
                if (!chain_ldlt_.factor(stuck, *lo, *hi)) throw_at(t_, "W lost positive definiteness");
                chain_ldlt_.forward(r, *lo, *hi);
                chain_ldlt_.backward(x);
                for (std::size_t i = 0; i < n; ++i) check_dof(i, h);
                continue;
            }
            if (!std::is_sorted(switched_.begin(), switched_.end())) std::sort(switched_.begin(), switched_.end());
            if (!chain_ldlt_.update(switched_, stuck, r, x, changed_))
                throw_at(t_, "W lost positive definiteness");
            // checked: where x changed and next to it, and the switched dofs (x may come out the same, 0 -> stuck)
            spans_.clear();
            for (std::size_t d : switched_) spans_.push_back(detail::DofSpan{d, d});
            union_spans(changed_, spans_);
            std::size_t next = 0;
            for (const detail::DofSpan& span : changed_) {
                const std::size_t hi = std::min(n - 1, span.hi + 1);
                for (std::size_t i = std::max(next, span.lo > 0 ? span.lo - 1 : 0); i <= hi; ++i) check_dof(i, h);
                next = hi + 1;
            }
        }
        // q_{k+1} into q_prev_'s storage, v_{k+1} (x) into v_'s, the previous state left in q_prev_, v_prev_.
        // q_{k+1} is finite exactly when q_k (finite) and v_{k+1} are: theta > 0 carries a non-finite v into it.
        const double* v0 = v_.data();
        const double* q0 = q_.data();
        double* q1 = q_prev_.data();
        std::uint64_t carry = 0;
        for (std::size_t i = 0; i < n; ++i) {
            q1[i] = q0[i] + h * ((1.0 - th) * v0[i] + th * x[i]);
            carry |= detail::exponent_carry(q1[i]);
        }
        const bool finite = (carry >> 63) == 0;
        const std::uint64_t* free = free_mask_.data();
        for (std::size_t i = 0; i < n; ++i) x[i] = detail::masked(x[i], free[i]);  // exact zero, not round-off
        // a slipping contact's force, -level sigma (sigma = +-1: the sign flip is exact); a stuck one's is its check's
        for (std::size_t i = 0; i < n; ++i) {
            const double slipping = std::copysign(level[i], -sigma[i]), held = reaction[i];
            reaction[i] = sigma[i] != 0.0 ? slipping : held;
        }
        q_.swap(q_prev_);
        v_prev_.swap(v_);
        v_.swap(x_);
        return finite;
    }

    /// A contact's law at the current solve (stuck: its reaction first); into violated_ when it does not hold.
    void check_stick(std::size_t d, double h) {
        const double r = (chain_ldlt_.row_times(d, x_.data()) - b_(static_cast<Eigen::Index>(d))) / h;
        reaction_(static_cast<Eigen::Index>(d)) = r;  // the force that holds v_d = 0
        if (std::abs(r) > static_at_[d])
            violated_.emplace_back(static_cast<std::size_t>(contact_at_[d]), std::abs(r) - static_at_[d]);
    }
    void check_slip(std::size_t d, double h) {
        // in force units, comparable with a stick violation: the force that would stop it
        const double x = x_(static_cast<Eigen::Index>(d));
        if (!(sigma_[d] * x > 0.0))
            violated_.emplace_back(static_cast<std::size_t>(contact_at_[d]),
                                   chain_ldlt_.diagonal(d) * std::abs(x) / h + 1e-300);
    }
    void check_dof(std::size_t d, double h) {
        if (stuck_[d]) check_stick(d, h);
        else if (sigma_[d] != 0.0) check_slip(d, h);
    }

    /// a = a union b (both increasing), as increasing disjoint spans.
    void union_spans(std::vector<detail::DofSpan>& a, const std::vector<detail::DofSpan>& b) {
        merged_.clear();
        std::size_t ia = 0, ib = 0;
        while (ia < a.size() || ib < b.size()) {
            const detail::DofSpan next = ib == b.size() || (ia < a.size() && a[ia].lo <= b[ib].lo) ? a[ia++] : b[ib++];
            if (!merged_.empty() && next.lo <= merged_.back().hi + 1)
                merged_.back().hi = std::max(merged_.back().hi, next.hi);
            else
                merged_.push_back(next);
        }
        a.swap(merged_);
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

    /// Counts (and logs) contact j's switch over the step, if its mode changed.
    void log_switch(std::size_t j) {
        const ContactState a = previous_modes_[j], b = modes_[j];
        if (a == b) return;
        ++stats_.contact_switches;
        if (!opt_.record_events) return;
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
    std::vector<double> a_diag_, a_sub_, k_diag_, k_sub_;  // a chain's A and h K: (i, i) and (i, i - 1)
    Eigen::VectorXd w_diag_;
    Eigen::Index band_ = 0;
    detail::BandLDLT ldlt_;
    // the chain (W tridiagonal, inclusion): its factors and solution, and per dof the contact's index (-1: none),
    // stuck flag (stuck_), direction (sigma_: -1, 0, 1) and slip force of this step (slip_level_)
    bool on_chain_ = false, refactor_chain_ = false;
    Eigen::VectorXd rhs_;  // the chain's right-hand side of the current iteration: 0 stuck, b - h level sigma
    std::vector<std::uint64_t> free_mask_;  // per dof: all ones unless stuck (stuck_ as a mask for masked())
    detail::ChainLDLT chain_ldlt_;
    std::vector<long> contact_at_;
    std::vector<double> slip_level_, sigma_, static_at_, kinetic_at_, slow_at_, slow_speed_at_;
    std::vector<std::size_t> switched_contacts_;  // contacts switched at some iteration of the step
    std::vector<detail::DofSpan> changed_, spans_, merged_;  // where x changed in an iteration
    std::vector<std::size_t> switched_;                       // dofs whose contact switched in an iteration
    std::vector<std::pair<std::size_t, double>> violated_;    // contact, violation
    std::vector<ContactState> modes_, previous_modes_;
    std::vector<double> level_, violation_;
    std::vector<char> stuck_, factored_stuck_;
    std::vector<ContactEvent> events_;
    OneStepContactSolution contact_solution_;
    std::size_t next_output_ = 0;
    Statistics stats_;
};

}  // namespace frictionsim
