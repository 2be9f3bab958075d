// The hybrid-system and integrator concepts that the event loop drives. Duck-typed (Boost.Odeint style):
// no base classes, no virtual calls in the right-hand side.
//
// A HybridSystem S provides (Mode is `int` unless S declares `using mode_type = ...`, see system_size.hpp)
//   static constexpr std::size_t state_size;     // continuous states         } or, sized at run time,
//   static constexpr std::size_t guard_count;    // switching functions       } std::size_t state_size() const and
//                                                // (the same count in every mode) std::size_t guard_count() const
//   void rhs(double t, const double* x, const Mode& mode, double* dxdt) const;
//   void guards(double t, const double* x, const Mode& mode, double* g) const;   // g[guard_count]
//   int guard_direction(std::size_t i, const Mode& mode) const;  // -1 falling, +1 rising, 0 both
//   const char* guard_name(std::size_t i, const Mode& mode) const;
//   Mode initial_mode(double t, const double* x) const;
//   // Called at a root with the state there; returns the new mode, resolved algebraically, and may project x
//   // (e.g. set the relative velocity to exactly zero on entering stick). fired[i] is +1/-1 for guards that
//   // crossed (rising/falling), 0 otherwise.
//   Mode switch_mode(double t, double* x, const Mode& mode, const int* fired) const;
//   const char* mode_name(int mode) const;      // with a Mode of its own: the name of one contact's mode
//   state_names() const;                        // std::array<const char*, state_size>, or a std::vector of names
//   double friction_force(double t, const double* x, const Mode& mode) const;   // for recording
//   initial_state() const;                      // std::array<double, state_size> or std::vector<double>
// and optionally
//   void rhs_guards(double t, const double* x, const Mode& mode, double* dxdt, double* g) const;  // both from one
//        evaluation: Dormand-Prince then checks the guards at its stages instead of extra dense-output points
//   the Jacobian in one of the forms of solve/jacobian.hpp (dense, banded, sparse entries) for the implicit methods
//   static constexpr bool autonomous = true;    // rhs does not depend on t: Rosenbrock skips its df/dt difference
//
// An Integrator<S> provides
//   Integrator(const S& system, const SolverOptions& options);
//   void restart(double t, const double* x, const Mode& mode);   // exact restart: no history carried over a switch
//   StepResult step(double t_stop);    // one internal step, never past t_stop; stops at the first root
//   void interpolate(double t, double* x) const;         // dense output on [previous_time(), time()]
//   double time() const; double previous_time() const; const double* state() const;
//   const int* roots() const;          // after a root: +1/-1 per guard that crossed, else 0
//   SolverStats stats() const;
// A guard that is exactly zero at a restart is masked until it becomes non-zero; its first non-zero sign is
// its reference (CVODE's rule). The event loop first checks such guards' direction itself, so a guard that
// leaves zero towards its triggering side fires at once instead of being silently masked.
#pragma once

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "../detail/traits.hpp"
#include "system_size.hpp"

namespace frictionsim {

namespace detail {
template <class S> using mode_arg_t = const system_mode_t<S>&;
template <class S> using rhs_t = decltype(std::declval<const S&>().rhs(
    0.0, std::declval<const double*>(), std::declval<mode_arg_t<S>>(), std::declval<double*>()));
template <class S> using guards_t = decltype(std::declval<const S&>().guards(
    0.0, std::declval<const double*>(), std::declval<mode_arg_t<S>>(), std::declval<double*>()));
template <class S> using guard_direction_t =
    decltype(int{std::declval<const S&>().guard_direction(std::size_t{}, std::declval<mode_arg_t<S>>())});
template <class S> using guard_name_t = decltype(static_cast<const char*>(
    std::declval<const S&>().guard_name(std::size_t{}, std::declval<mode_arg_t<S>>())));
template <class S> using initial_mode_t = decltype(system_mode_t<S>{
    std::declval<const S&>().initial_mode(0.0, std::declval<const double*>())});
template <class S> using switch_mode_t = decltype(system_mode_t<S>{std::declval<const S&>().switch_mode(
    0.0, std::declval<double*>(), std::declval<mode_arg_t<S>>(), std::declval<const int*>())});
template <class S> using mode_name_t = decltype(static_cast<const char*>(std::declval<const S&>().mode_name(0)));
template <class S> using state_names_t = decltype(std::declval<const S&>().state_names()[0]);
template <class S> using friction_force_t = decltype(double{std::declval<const S&>().friction_force(
    0.0, std::declval<const double*>(), std::declval<mode_arg_t<S>>())});
template <class S> using initial_state_t = decltype(double{std::declval<const S&>().initial_state()[0]});
template <class S> using mode_code_t = decltype(int{std::declval<const S&>().mode_code(std::declval<mode_arg_t<S>>())});
template <class S> using guard_mode_t =
    decltype(int{std::declval<const S&>().guard_mode(std::size_t{}, std::declval<mode_arg_t<S>>())});
template <class S> constexpr bool int_mode_v = std::is_same_v<system_mode_t<S>, int>;
}  // namespace detail

/// Does a system (rig) or law declare `static constexpr bool stiff = true`? Picks CVODE BDF under
/// Method::automatic. Measured, see bench/integrators: LuGre's bristle dynamics make BDF 1.8x faster than
/// Dormand-Prince; on the axial rig with Coulomb or Dahl friction Dormand-Prince is ~20x faster than CVODE BDF.
template <class T, class = void>
struct declares_stiff : std::false_type {};
template <class T>
struct declares_stiff<T, std::void_t<decltype(T::stiff)>> : std::bool_constant<T::stiff> {};

/// Does S meet the HybridSystem concept above (its required members)?
template <class S>
constexpr bool is_hybrid_system_v =
    (has_fixed_size_v<S> || has_run_time_size_v<S>) && detail::detected<S, detail::rhs_t>::value &&
    detail::detected<S, detail::guards_t>::value && detail::detected<S, detail::guard_direction_t>::value &&
    detail::detected<S, detail::guard_name_t>::value && detail::detected<S, detail::initial_mode_t>::value &&
    detail::detected<S, detail::switch_mode_t>::value && detail::detected<S, detail::mode_name_t>::value &&
    detail::detected<S, detail::state_names_t>::value && detail::detected<S, detail::friction_force_t>::value &&
    detail::detected<S, detail::initial_state_t>::value &&
    (detail::int_mode_v<S> ||
     (detail::detected<S, detail::mode_code_t>::value && detail::detected<S, detail::guard_mode_t>::value));

/// static_asserts naming the first missing member of the HybridSystem concept; true when S meets it. Called at
/// the top of simulate() / simulate_with(), so a rig that misses a member fails there, readably.
template <class S>
constexpr bool check_hybrid_system() {
    using namespace detail;
    static_assert(has_fixed_size_v<S> || has_run_time_size_v<S>,
                  "HybridSystem requires `static constexpr std::size_t state_size` and `guard_count` (fixed size), or "
                  "`std::size_t state_size() const` and `std::size_t guard_count() const` (sized at run time)");
    static_assert(detected<S, rhs_t>::value,
                  "HybridSystem requires `void rhs(double t, const double* x, const Mode& mode, double* dxdt) const`");
    static_assert(detected<S, guards_t>::value,
                  "HybridSystem requires `void guards(double t, const double* x, const Mode& mode, double* g) const`");
    static_assert(detected<S, guard_direction_t>::value,
                  "HybridSystem requires `int guard_direction(std::size_t i, const Mode& mode) const` (-1, +1 or 0)");
    static_assert(detected<S, guard_name_t>::value,
                  "HybridSystem requires `const char* guard_name(std::size_t i, const Mode& mode) const`");
    static_assert(detected<S, initial_mode_t>::value,
                  "HybridSystem requires `Mode initial_mode(double t, const double* x) const`");
    static_assert(detected<S, switch_mode_t>::value,
                  "HybridSystem requires `Mode switch_mode(double t, double* x, const Mode& mode, const int* fired) const`");
    static_assert(detected<S, mode_name_t>::value, "HybridSystem requires `const char* mode_name(int mode) const`");
    static_assert(detected<S, state_names_t>::value,
                  "HybridSystem requires `state_names() const` (std::array<const char*, state_size> or a std::vector of names)");
    static_assert(detected<S, friction_force_t>::value,
                  "HybridSystem requires `double friction_force(double t, const double* x, const Mode& mode) const`");
    static_assert(detected<S, initial_state_t>::value,
                  "HybridSystem requires `initial_state() const` (std::array<double, state_size> or std::vector<double>)");
    static_assert(int_mode_v<S> || detected<S, mode_code_t>::value,
                  "HybridSystem with its own Mode requires `int mode_code(const Mode&) const` (the Result's mode column)");
    static_assert(int_mode_v<S> || detected<S, guard_mode_t>::value,
                  "HybridSystem with its own Mode requires `int guard_mode(std::size_t i, const Mode&) const`");
    return is_hybrid_system_v<S>;
}

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
