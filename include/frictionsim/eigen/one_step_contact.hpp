// The contact problem of one Moreau-Jean step (eigen/moreau_jean.hpp), and the concept of its solver, so that the
// stepper's exact solve can be swapped (issue 22 item 4):
//
//   W v = b + h r,    per contact j on dof d:  v_d = 0 and |r_d| <= static_j (stuck),
//                                              or r_d = -level_j sgn(v_d), v_d != 0 (slipping),
//
// W symmetric positive definite (M + theta h C + theta^2 h^2 K), b the free velocity's right-hand side, level_j the
// step's slip force. A contact solver is any callable `int(const OneStepContactProblem&, OneStepContactSolution&)`
// (a duck-typed concept, as odeint's steppers): it reads the problem and the warm start in the solution (the last
// step's velocities and modes), leaves there v, r and the modes that satisfy the law, and returns the iterations it
// took; it throws SimulationError when it does not settle. An empty MoreauJeanOptions::contact_solver keeps the
// stepper's own exact solve (the active set, with the chain's updated LDL^T on a string).
//
// ProjectedGaussSeidel is the other one here: Gauss-Seidel sweeps over the dofs, each contact's force projected
// onto its law at its dof's row (Jean 1999, CMAME 177, sec. 4; Acary and Brogliato 2008, sec. 13.4, Siconos'
// nonsmooth Gauss-Seidel). For static == kinetic the law is monotone and the step's solution unique: it converges
// to the active set's (W SPD). With static > kinetic (Leine's switch model) both stop at a v and r satisfying the
// same conditions, but these may have more than one solution, and the two can pick different ones.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

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

enum class ContactState : signed char { slip_negative = -1, stick = 0, slip_positive = 1 };

/// One step's contact problem: W v = b + h r with each contact's law (see the file's head).
struct OneStepContactProblem {
    const Eigen::SparseMatrix<double>& w;     ///< W, symmetric positive definite (column-major, compressed)
    const Eigen::VectorXd& b;                 ///< the free velocity's right-hand side
    double h;                                 ///< the step [s]
    const std::vector<PointContact>& contacts;
    const std::vector<double>& level;         ///< per contact: the slip force of this step
};

/// What a contact solver leaves: v_{k+1}, r per dof (0 where there is no contact) and each contact's mode. On entry
/// v and modes hold the warm start (the step's start).
struct OneStepContactSolution {
    Eigen::VectorXd v, r;
    std::vector<ContactState> modes;
};

/// A contact solver: int(const OneStepContactProblem&, OneStepContactSolution&), the iterations it took.
using ContactSolver = std::function<int(const OneStepContactProblem&, OneStepContactSolution&)>;

/// Projected Gauss-Seidel: sweeps until no contact changes mode and no velocity moves by more than
/// `tolerance` (relative to the largest |v|, absolute below 1); max_sweeps bounds it (then SimulationError).
struct ProjectedGaussSeidel {
    double tolerance = 1e-14;
    int max_sweeps = 100000;

    int operator()(const OneStepContactProblem& p, OneStepContactSolution& s) const {
        const Eigen::SparseMatrix<double>& w = p.w;
        const Eigen::Index n = w.rows();
        std::vector<long> contact_at(static_cast<std::size_t>(n), -1);
        for (std::size_t j = 0; j < p.contacts.size(); ++j) contact_at[p.contacts[j].dof] = static_cast<long>(j);
        s.r = Eigen::VectorXd::Zero(n);
        for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
            double moved = 0.0, largest = 0.0;
            bool switched = false;
            for (Eigen::Index i = 0; i < n; ++i) {
                double diagonal = 0.0, rest = p.b(i);  // rest: b_i - sum_{j != i} W_ij v_j (W symmetric: column i)
                for (Eigen::SparseMatrix<double>::InnerIterator it(w, i); it; ++it) {
                    if (it.row() == i) diagonal += it.value();
                    else rest -= it.value() * s.v(it.row());
                }
                const double free = rest / diagonal;  // v_i with no force at its contact
                double v = free;
                const long j = contact_at[static_cast<std::size_t>(i)];
                if (j >= 0) {
                    const PointContact& c = p.contacts[static_cast<std::size_t>(j)];
                    const double level = p.level[static_cast<std::size_t>(j)], hold = -diagonal * free / p.h;
                    ContactState& mode = s.modes[static_cast<std::size_t>(j)];
                    const ContactState before = mode;
                    // the active set's rules at this row: a slip that would reverse comes to rest; a stuck contact
                    // that the static bound cannot hold breaks away in the direction of its free velocity
                    if (mode != ContactState::stick) {
                        const double sigma = static_cast<double>(mode);
                        if (!(sigma * (rest - p.h * level * sigma) > 0.0)) mode = ContactState::stick;
                    }
                    if (mode == ContactState::stick && std::abs(hold) > c.static_bound)
                        mode = free > 0.0 ? ContactState::slip_positive : ContactState::slip_negative;
                    switched = switched || mode != before;
                    const double sigma = static_cast<double>(mode);
                    s.r(i) = mode == ContactState::stick ? hold : -level * sigma;
                    v = mode == ContactState::stick ? 0.0 : (rest - p.h * level * sigma) / diagonal;
                }
                moved = std::max(moved, std::abs(v - s.v(i)));
                largest = std::max(largest, std::abs(v));
                s.v(i) = v;
            }
            if (!(moved == moved)) throw SimulationError("ProjectedGaussSeidel: a non-finite velocity", 0.0);
            if (!switched && moved <= tolerance * std::max(1.0, largest)) return sweep;
        }
        throw SimulationError("ProjectedGaussSeidel: did not settle in max_sweeps", 0.0);
    }
};

}  // namespace frictionsim
