// Both contact treatments in one model (issue 13, item 1): the distributed contacts captured by Moreau-Jean time-
// stepping (moreau_jean.hpp), a few lumped switches (a bit's stick <-> slip, a tool's valve, a torque limit) located
// exactly. Each lumped element has a mode and a guard g(t, q, v, r), positive while the mode holds. After a step the
// guards are evaluated at its end; when one has crossed zero, the step is cut: the length h* in (0, h] whose end
// puts the guard at zero is found (Illinois on h*, bisection when the secant leaves the bracket, to a tolerance in
// time), the partial step of h* is taken, the element switches at that state (Leine's switch model for friction:
// stick while the load it must hold is within the static bound) and the time-stepping restarts from it. This is the
// event-driven treatment of the lumped switch (exact location and restart, as hybrid_loop.hpp does for an ODE)
// embedded in the event-capturing scheme: between switches the walls are captured as before.
//
// A MoreauJean instance is built for one step length (W is factored for it), so a trial step of length h* is a
// second instance built from the step's start state: O(n) per trial, and trials happen only at the lumped switches.
// During a trial each element is "held" in its mode through its guard (a slipping bit keeps its direction, so its
// speed crosses zero instead of being caught at rest by the inclusion), which keeps the guard a continuous function
// of h* with a sign change. In the main steps a slipping lumped friction is a Moreau-Jean contact whose level is set
// at each step's start (set_contact_bounds): a force with that level would lag by (1 - theta) step, because
// MoreauJean applies theta f_{k+1} + (1 - theta) f_k with f_k from the step before.
//
// The element interface (duck-typed; LumpedFriction below is the stick/slip one):
//   int initial_mode(const MechanicalView& at) const;
//   void build(int mode, bool held, const MechanicalView& at, LinearMechanicalSystem& sys) const;
//       appends what the element is in this mode (contacts, forces, matrix entries) to the system of a step that
//       starts at `at`; `held`: the mode is kept through its guard (trial steps)
//   void update(int mode, bool held, const MechanicalView& at, const ContactBoundsSetter& set) const;
//       before each step: levels of the contacts build() appended (set(k, static, kinetic), k counts from 0)
//   double guard(int mode, const MechanicalView& at) const;     // > 0 while the mode holds
//   int switch_mode(int mode, const MechanicalView& at, Eigen::VectorXd& v) const;  // at a located zero; may
//       project v (a stuck dof at rest exactly)
//   std::string name() const; const char* mode_name(int mode) const;
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "../detail/illinois.hpp"
#include "../detail/validate.hpp"
#include "../error.hpp"
#include "moreau_jean.hpp"

namespace frictionsim {

/// What a lumped element reads: the time, the state, the last step's contact forces and the system without the
/// lumped elements.
class MechanicalView {
public:
    MechanicalView(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& r,
                   const LinearMechanicalSystem& base, Eigen::VectorXd& scratch, double step = 0.0)
        : t_(t), q_(q), v_(v), r_(r), base_(base), scratch_(scratch), step_(step) {}

    double time() const { return t_; }
    /// The length of the step that starts here (0 at a step's end).
    double step() const { return step_; }
    const Eigen::VectorXd& q() const { return q_; }
    const Eigen::VectorXd& v() const { return v_; }
    const Eigen::VectorXd& r() const { return r_; }
    const LinearMechanicalSystem& system() const { return base_; }

    /// f_d(t) - (C v)_d - (K q)_d: the force on dof d from the applied force, the dampers and the springs. With the
    /// mass lumped at d (row d of M diagonal) it is what a contact at d must hold to keep the dof at rest.
    double load(std::size_t d) const {
        const Eigen::Index i = static_cast<Eigen::Index>(d);
        double s = 0.0;
        if (base_.force) {
            scratch_.setZero(base_.size());
            base_.force(t_, scratch_);
            s = scratch_(i);
        }
        using It = Eigen::SparseMatrix<double>::InnerIterator;  // C and K symmetric: column d is row d
        for (It it(base_.damping, i); it; ++it) s -= it.value() * v_(it.row());
        for (It it(base_.stiffness, i); it; ++it) s -= it.value() * q_(it.row());
        return s;
    }

private:
    double t_;
    const Eigen::VectorXd &q_, &v_, &r_;
    const LinearMechanicalSystem& base_;
    Eigen::VectorXd& scratch_;
    double step_;
};

/// Sets the bounds of an element's own contacts in a MoreauJean instance (k counts the element's contacts).
class ContactBoundsSetter {
public:
    ContactBoundsSetter(MoreauJean& mj, std::size_t first) : mj_(mj), first_(first) {}
    void operator()(std::size_t k, double static_bound, double kinetic_bound) const {
        mj_.set_contact_bounds(first_ + k, static_bound, kinetic_bound);
    }

private:
    MoreauJean& mj_;
    std::size_t first_;
};

/// A frictional contact on one dof with its stick and slip located exactly: modes -1, 0, +1 (slip negative, stick,
/// slip positive). Stuck, the dof is held at rest (a contact no force exceeds) and the guard is static_bound -
/// |load|; slipping, the guard is direction * v_d and the friction has the level kinetic(|v|) (velocity weakening
/// allowed) at the speed predicted for the step's midpoint, v_d + (h/2) (load - direction kinetic(|v_d|)) / m_d
/// (an explicit midpoint rule: the level taken at the step's start would make the slip phases first order, the
/// trapezoidal theta = 1/2 steps around it second). At a zero: v_d = 0 and Leine's switch model (stick while |load|
/// <= static_bound, else slip along the load). The mass at the dof must be lumped (row d of M diagonal).
class LumpedFriction {
public:
    LumpedFriction(std::size_t dof, double static_bound, std::function<double(double speed)> kinetic_level,
                   std::string name = "lumped_friction")
        : dof_(dof), static_(static_bound), kinetic_(std::move(kinetic_level)), name_(std::move(name)) {
        detail::require_non_negative("LumpedFriction", "static_bound", static_bound);
        if (!kinetic_) detail::reject("LumpedFriction", "kinetic_level", "a callable", 0.0);
    }

    std::size_t dof() const { return dof_; }
    double static_bound() const { return static_; }
    /// The slip level at speed |v|, checked: in [0, static_bound].
    double level(double speed) const {
        const double k = kinetic_(std::abs(speed));
        if (!(k >= 0.0 && k <= static_)) detail::reject("LumpedFriction", "kinetic_level", "in [0, static_bound]", k);
        return k;
    }

    std::string name() const { return name_; }
    const char* mode_name(int mode) const {
        return mode == 0 ? "stick" : mode > 0 ? "slip_positive" : "slip_negative";
    }
    int initial_mode(const MechanicalView& at) const {
        const double v = at.v()(index());
        if (v != 0.0) return v > 0.0 ? 1 : -1;
        const double s = at.load(dof_);
        return std::abs(s) <= static_ ? 0 : (s > 0.0 ? 1 : -1);
    }
    void build(int mode, bool held, const MechanicalView& at, LinearMechanicalSystem& sys) const {
        using It = Eigen::SparseMatrix<double>::InnerIterator;
        for (It it(sys.mass, index()); it; ++it)
            if (it.row() != index() && it.value() != 0.0)
                detail::reject("LumpedFriction", "dof", "a dof whose mass is lumped (row of M diagonal)",
                               static_cast<double>(dof_));
        if (mode == 0) {  // held at rest: no load breaks it loose in a step, the guard does
            sys.contacts.push_back(PointContact{dof_, held_bound, 0.0, 0.0, 0.0});
            return;
        }
        const double k = slip_level(mode, at);
        if (!held) {  // a contact at the step's level: the walls' active set sees it
            sys.contacts.push_back(PointContact{dof_, k, k, 0.0, 0.0});
            return;
        }
        const double torque = -static_cast<double>(mode) * k;  // direction kept through v_d = 0
        const Eigen::Index d = index();
        auto base = std::move(sys.force);
        sys.force = [base, d, torque](double t, Eigen::VectorXd& f) {
            if (base) base(t, f);
            f(d) += torque;
        };
    }
    void update(int mode, bool held, const MechanicalView& at, const ContactBoundsSetter& set) const {
        if (mode == 0 || held) return;  // held slip: its force was set by build() for the one trial step
        const double k = slip_level(mode, at);
        set(0, k, k);
    }
    double guard(int mode, const MechanicalView& at) const {
        if (mode == 0) return static_ - std::abs(at.load(dof_));
        return static_cast<double>(mode) * at.v()(index());
    }
    int switch_mode(int mode, const MechanicalView& at, Eigen::VectorXd& v) const {
        (void)mode;
        v(index()) = 0.0;
        const double s = at.load(dof_);
        return std::abs(s) <= static_ ? 0 : (s > 0.0 ? 1 : -1);
    }

    /// The slip level of a step starting at `at` in slip mode `mode` (see the class comment).
    double slip_level(int mode, const MechanicalView& at) const {
        const double v = at.v()(index()), start = level(v);
        if (!(at.step() > 0.0)) return start;
        const double dir = static_cast<double>(mode);
        const double mass = at.system().mass.coeff(index(), index());
        const double mid = v + 0.5 * at.step() * (at.load(dof_) - dir * start) / mass;
        return level(std::max(0.0, dir * mid));  // a predicted reversal: the level at rest
    }

private:
    static constexpr double held_bound = std::numeric_limits<double>::max();
    Eigen::Index index() const { return static_cast<Eigen::Index>(dof_); }
    std::size_t dof_;
    double static_;
    std::function<double(double)> kinetic_;
    std::string name_;
};

/// A lumped element changed mode at `time` (located to the tolerance).
struct LumpedEvent {
    double time;
    std::size_t element;
    int mode_before, mode_after;
};

struct MoreauJeanEventsOptions {
    /// The time-stepping (h, theta, treatment, interrupt); its output_times and record_events are not used.
    MoreauJeanOptions steps;
    double time_tolerance = 1e-10;        ///< s: a lumped switch is located within it
    int max_location_iterations = 200;    ///< trial steps per located switch before the run stops
    std::size_t max_switches = 1'000'000; ///< lumped switches per run: past it the run stops (ChatteringError)
    std::vector<double> output_times;     ///< increasing: the observer sees q, v linear between steps there

    void validate() const {
        constexpr const char* who = "MoreauJeanEventsOptions";
        steps.validate();
        detail::require_positive(who, "time_tolerance", time_tolerance);
        if (max_location_iterations < 2)
            detail::reject(who, "max_location_iterations", ">= 2", max_location_iterations);
        if (max_switches == 0) detail::reject(who, "max_switches", "positive", 0.0);
        for (std::size_t i = 0; i < output_times.size(); ++i) {
            detail::require_finite(who, "output_times", output_times[i]);
            if (i > 0 && !(output_times[i] > output_times[i - 1]))
                detail::reject(who, "output_times", "strictly increasing", output_times[i]);
        }
    }
};

/// The driver: Moreau-Jean steps of h over the base system, the lumped elements' switches located and restarted.
/// A run that stops (SimulationError from a step, a switch not located, the switch bound) leaves the driver at the
/// last accepted step: time(), the state, events() and what the observer saw are the partial result.
template <class Element>
class MoreauJeanEvents {
public:
    using Observer = MoreauJean::Observer;
    struct Statistics {
        MoreauJean::Statistics steps;  ///< summed over the instances, the accepted trial steps included
        long trial_steps = 0;          ///< steps of the trial instances that located the switches
        long restarts = 0;             ///< instances built for the main step (after switches, the last step)
        long lumped_switches = 0;
    };

    MoreauJeanEvents(LinearMechanicalSystem base, std::vector<Element> elements, MoreauJeanEventsOptions options,
                     Eigen::VectorXd q0, Eigen::VectorXd v0, double t0 = 0.0)
        : base_(std::move(base)), elements_(std::move(elements)), opt_(std::move(options)), q_(std::move(q0)),
          v_(std::move(v0)), t_(t0) {
        opt_.validate();
        opt_.steps.output_times.clear();
        opt_.steps.record_events = false;  // the wall contacts' switches are counted in statistics()
        const Eigen::Index n = base_.size();
        for (Eigen::SparseMatrix<double>* m : {&base_.damping, &base_.stiffness})  // empty: none (MoreauJean's rule)
            if (m->rows() == 0 && m->cols() == 0) m->resize(n, n);
        constexpr const char* who = "MoreauJeanEvents";
        if (q_.size() != n) detail::reject(who, "q0", "of size mass.rows() (size given)", double(q_.size()));
        if (v_.size() != n) detail::reject(who, "v0", "of size mass.rows() (size given)", double(v_.size()));
        detail::require_finite(who, "t0", t_);
        reaction_ = Eigen::VectorXd::Zero(n);
        q_prev_ = q_;
        v_prev_ = v_;
        t_prev_ = t_;
        modes_.resize(elements_.size());
        const MechanicalView at = view(t_, q_, v_, reaction_);
        for (std::size_t e = 0; e < elements_.size(); ++e) modes_[e] = elements_[e].initial_mode(at);
        main_ = make(opt_.steps.step, false, t_, q_, v_);  // the instance's checks name the system's parameters
    }

    double time() const { return t_; }
    const Eigen::VectorXd& positions() const { return q_; }
    const Eigen::VectorXd& velocities() const { return v_; }
    /// The state before the last accepted step (at the start: the initial state): with time() and the state, what
    /// outputs inside the step are interpolated from.
    double previous_time() const { return t_prev_; }
    const Eigen::VectorXd& previous_positions() const { return q_prev_; }
    const Eigen::VectorXd& previous_velocities() const { return v_prev_; }
    /// Contact forces of the last accepted step, per dof (the lumped elements' contacts included).
    const Eigen::VectorXd& contact_forces() const { return reaction_; }
    const std::vector<int>& modes() const { return modes_; }
    const std::vector<Element>& elements() const { return elements_; }
    const std::vector<LumpedEvent>& events() const { return events_; }
    const LinearMechanicalSystem& system() const { return base_; }
    const MoreauJeanEventsOptions& options() const { return opt_; }
    Statistics statistics() const {
        Statistics s = stats_;
        if (main_.mj) add(s.steps, main_.mj->statistics());
        return s;
    }
    /// The guard of element e at the current state.
    double guard(std::size_t e) const { return elements_.at(e).guard(modes_[e], view(t_, q_, v_, reaction_)); }

    /// Steps until t_end (the last step shortened to end there), the observer called at the output times.
    void run(double t_end, const Observer& observer = nullptr) {
        detail::require_finite("MoreauJeanEvents", "t_end", t_end);
        const double h = opt_.steps.step;
        while (next_output_ < opt_.output_times.size() && opt_.output_times[next_output_] < t_ - 1e-12 * h)
            ++next_output_;  // before the start: never seen
        emit(observer, t_, q_, v_);
        while (t_end - t_ > 1e-9 * h) {
            const double left = t_end - t_;
            step(left < h * (1.0 + 1e-9) ? left : h, observer);
        }
    }

    /// One step of length `length` (<= h), cut at a lumped switch inside it.
    void step(double length, const Observer& observer = nullptr) {
        detail::require_positive("MoreauJeanEvents", "step", length);
        if (!main_.mj) main_ = make(opt_.steps.step, false, t_, q_, v_);  // after a stop inside a location
        const bool full = std::abs(length - opt_.steps.step) <= 1e-12 * opt_.steps.step;
        Stepper shortened;
        if (!full) shortened = make(length, false, t_, q_, v_);
        Stepper& s = full ? main_ : shortened;
        const std::size_t ne = elements_.size();
        g_start_.resize(ne);
        g_end_.resize(ne);
        {
            const MechanicalView at = view(t_, q_, v_, reaction_, length);
            for (std::size_t e = 0; e < ne; ++e) g_start_[e] = elements_[e].guard(modes_[e], at);
            update_bounds(s, at);
        }
        const MoreauJean::Statistics before = s.mj->statistics();
        s.mj->step();  // a SimulationError leaves this driver at its last accepted step
        bool crossed = false;
        {
            const MechanicalView at = view(t_ + length, s.mj->positions(), s.mj->velocities(), s.mj->contact_forces());
            for (std::size_t e = 0; e < ne; ++e) {
                g_end_[e] = elements_[e].guard(modes_[e], at);
                crossed = crossed || g_end_[e] < 0.0 || (g_end_[e] == 0.0 && g_start_[e] > 0.0);
            }
        }
        if (!crossed) {
            accept(*s.mj, t_ + length, observer);
            if (!full) add(stats_.steps, s.mj->statistics());
            return;
        }
        if (full) {  // the main instance ran past the switch: its steps up to this one count, it is rebuilt there
            add(stats_.steps, before);
            main_.mj.reset();
        }
        locate_and_switch(length, observer);
    }

private:
    struct Stepper {
        std::unique_ptr<MoreauJean> mj;
        std::vector<std::size_t> first_contact;  // per element
        bool held = false;
    };

    static void add(MoreauJean::Statistics& a, const MoreauJean::Statistics& b) {
        a.steps += b.steps;
        a.factorisations += b.factorisations;
        a.solves += b.solves;
        a.contact_switches += b.contact_switches;
    }

    MechanicalView view(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& r,
                        double step = 0.0) const {
        return MechanicalView(t, q, v, r, base_, scratch_, step);
    }

    /// An instance for steps of h from (t, q, v), the elements in their modes (held: through their guards).
    Stepper make(double h, bool held, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
        Stepper s;
        s.held = held;
        LinearMechanicalSystem sys = base_;
        const MechanicalView at = view(t, q, v, reaction_, h);
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            s.first_contact.push_back(sys.contacts.size());
            elements_[e].build(modes_[e], held, at, sys);
        }
        MoreauJeanOptions o = opt_.steps;
        o.step = h;
        s.mj = std::make_unique<MoreauJean>(std::move(sys), std::move(o), q, v, t);
        if (held) ++stats_.trial_steps;
        else ++stats_.restarts;
        return s;
    }

    void update_bounds(Stepper& s, const MechanicalView& at) const {
        for (std::size_t e = 0; e < elements_.size(); ++e)
            elements_[e].update(modes_[e], s.held, at, ContactBoundsSetter(*s.mj, s.first_contact[e]));
    }

    /// A trial step of x from the accepted state, the elements held: min over the elements of their guards at its end.
    double trial(double x, Stepper& out) {
        out = make(x, true, t_, q_, v_);
        update_bounds(out, view(t_, q_, v_, reaction_, x));
        out.mj->step();
        const MechanicalView at = view(t_ + x, out.mj->positions(), out.mj->velocities(), out.mj->contact_forces());
        double g = std::numeric_limits<double>::infinity();
        for (std::size_t e = 0; e < elements_.size(); ++e) g = std::min(g, elements_[e].guard(modes_[e], at));
        return g;
    }

    /// The step of `length` crossed a guard: Illinois on h* in (0, length] for min_e g_e (positive at 0), the
    /// partial step taken, the elements at zero switched, the main instance rebuilt there.
    void locate_and_switch(double length, const Observer& observer) {
        double a = 0.0, ga = std::numeric_limits<double>::infinity();
        for (double g : g_start_) ga = std::min(ga, g);
        ga = std::max(ga, 0.0);
        Stepper best, probe;
        double b = length, gb = trial(length, best);
        if (gb > 0.0) {  // held in its mode, no element reaches its guard: the main step had caught one at rest
            accept(*best.mj, t_ + length, observer);
            add(stats_.steps, best.mj->statistics());
            main_ = make(opt_.steps.step, false, t_, q_, v_);
            return;
        }
        detail::IllinoisBracket r{a, ga, b, gb};
        for (int iter = 0; r.b - r.a > opt_.time_tolerance; ++iter) {
            if (iter >= opt_.max_location_iterations) {
                std::ostringstream msg;
                msg.precision(17);
                msg << "MoreauJeanEvents: a lumped switch in the step from t = " << t_
                    << " s not located within max_location_iterations";
                throw SimulationError(msg.str(), t_);
            }
            // the secant point; where it leaves the inner 98 % of the bracket (or ga is still infinite), bisect
            const double x = r.ga - r.gb != 0.0 ? r.next(0.01 * (r.b - r.a)) : 0.5 * (r.a + r.b);
            const double gx = trial(x, probe);
            if (gx <= 0.0) std::swap(best, probe);
            r.move(x, gx, gx <= 0.0);
        }
        b = r.b;
        const MoreauJean& mj = *best.mj;
        add(stats_.steps, mj.statistics());
        Eigen::VectorXd v = mj.velocities();
        const MechanicalView at = view(t_ + b, mj.positions(), mj.velocities(), mj.contact_forces());
        std::vector<int> next = modes_;
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            if (elements_[e].guard(modes_[e], at) > 0.0) continue;
            next[e] = elements_[e].switch_mode(modes_[e], at, v);
            if (next[e] == modes_[e]) continue;
            if (static_cast<std::size_t>(stats_.lumped_switches) >= opt_.max_switches) {
                std::ostringstream msg;
                msg.precision(17);
                msg << "MoreauJeanEvents: more than max_switches = " << opt_.max_switches << " lumped switches (at "
                    << elements_[e].name() << ", t = " << t_ + b << " s)";
                throw ChatteringError(msg.str(), t_, elements_[e].name());
            }
            ++stats_.lumped_switches;
            events_.push_back(LumpedEvent{t_ + b, e, modes_[e], next[e]});
        }
        accept_state(mj.positions(), v, mj.contact_forces(), t_ + b, observer);
        modes_ = std::move(next);
        main_ = make(opt_.steps.step, false, t_, q_, v_);
    }

    void accept(const MoreauJean& mj, double t, const Observer& observer) {
        accept_state(mj.positions(), mj.velocities(), mj.contact_forces(), t, observer);
    }

    void accept_state(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& r, double t,
                      const Observer& observer) {
        q_prev_ = q_;
        v_prev_ = v_;
        const double t_prev = t_prev_ = t_;
        q_ = q;
        v_ = v;
        reaction_ = r;
        t_ = t;
        const double tol = 1e-9 * opt_.steps.step;
        while (next_output_ < opt_.output_times.size() && opt_.output_times[next_output_] <= t_ + tol) {
            const double to = opt_.output_times[next_output_++];
            if (!observer) continue;
            const double a = t_ > t_prev ? std::clamp((to - t_prev) / (t_ - t_prev), 0.0, 1.0) : 1.0;
            observer(to, (1.0 - a) * q_prev_ + a * q_, (1.0 - a) * v_prev_ + a * v_);
        }
    }

    void emit(const Observer& observer, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
        const double tol = 1e-9 * opt_.steps.step;
        while (next_output_ < opt_.output_times.size() && opt_.output_times[next_output_] <= t + tol) {
            const double to = opt_.output_times[next_output_++];
            if (observer) observer(to, q, v);
        }
    }

    LinearMechanicalSystem base_;
    std::vector<Element> elements_;
    MoreauJeanEventsOptions opt_;
    Eigen::VectorXd q_, v_, q_prev_, v_prev_, reaction_;
    double t_, t_prev_ = 0.0;
    std::vector<int> modes_;
    std::vector<double> g_start_, g_end_;
    std::vector<LumpedEvent> events_;
    Stepper main_;
    Statistics stats_;
    std::size_t next_output_ = 0;
    mutable Eigen::VectorXd scratch_;
};

}  // namespace frictionsim
