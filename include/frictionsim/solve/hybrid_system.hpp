// The hybrid-system and integrator concepts that the event loop drives. Duck-typed (Boost.Odeint style):
// no base classes, no virtual calls in the right-hand side.
//
// A HybridSystem S provides
//   static constexpr std::size_t state_size;     // continuous states
//   static constexpr std::size_t guard_count;    // switching functions (the same count in every mode)
//   void rhs(double t, const double* x, int mode, double* dxdt) const;
//   void guards(double t, const double* x, int mode, double* g) const;   // g[guard_count]
//   int guard_direction(std::size_t i, int mode) const;  // -1 falling, +1 rising, 0 both (CVodeSetRootDirection)
//   const char* guard_name(std::size_t i, int mode) const;
//   int initial_mode(double t, const double* x) const;
//   // Called at a root with the state there; returns the new mode, resolved algebraically, and may project x
//   // (e.g. set the relative velocity to exactly zero on entering stick). fired[i] is +1/-1 for guards that
//   // crossed (rising/falling), 0 otherwise.
//   int switch_mode(double t, double* x, int mode, const int* fired) const;
//   const char* mode_name(int mode) const;
//   std::array<const char*, state_size> state_names() const;
//   double friction_force(double t, const double* x, int mode) const;   // for recording
//   std::array<double, state_size> initial_state() const;                // used by simulate()
// and optionally
//   void rhs_guards(double t, const double* x, int mode, double* dxdt, double* g) const;  // both from one evaluation:
//        Dormand-Prince then checks the guards at its stages instead of extra dense-output points
//   void jacobian(double t, const double* x, int mode, double* J) const;  // column-major d(rhs)/dx, for CVODE
//
// An Integrator<S> provides
//   Integrator(const S& system, const SolverOptions& options);
//   void restart(double t, const double* x, int mode);   // exact restart: no history carried over a switch
//   StepResult step(double t_stop);    // one internal step, never past t_stop; stops at the first root
//   void interpolate(double t, double* x) const;         // dense output on [previous_time(), time()]
//   double time() const; double previous_time() const; const double* state() const;
//   const int* roots() const;          // after a root: +1/-1 per guard that crossed, else 0
//   SolverStats stats() const;
// A guard that is exactly zero at a restart is masked until it becomes non-zero; its first non-zero sign is
// its reference (CVODE's rule). The event loop first checks such guards' direction itself, so a guard that
// leaves zero towards its triggering side fires at once instead of being silently masked.
#pragma once

#include <cstddef>

namespace frictionsim {

struct StepResult {
    double t = 0.0;
    bool root = false;  ///< the step was cut at a root of a switching function
};

/// Did guard value move from `before` to `after` across zero in the allowed direction?
/// Falling: from > 0 to <= 0; rising: from < 0 to >= 0; both: either.
inline int crossing(double before, double after, int direction) {
    if (direction <= 0 && before > 0.0 && after <= 0.0) return -1;
    if (direction >= 0 && before < 0.0 && after >= 0.0) return +1;
    return 0;
}

}  // namespace frictionsim
