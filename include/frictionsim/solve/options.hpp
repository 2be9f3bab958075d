// Solver options: one aggregate with defaults (deal.II AdditionalData style). SI units throughout.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "../detail/validate.hpp"
#include "../error.hpp"
#include "hybrid_system.hpp"
#include "jacobian.hpp"
#include "memory.hpp"
#include "stop_conditions.hpp"

namespace frictionsim {

/// Which integrator runs the model: the ODE methods drive the hybrid event loop of an event-driven system (the lab
/// rigs, StringRig); the time-stepping methods step a time-stepping model (TorsionalString, solve/time_stepping.hpp).
enum class Method {
    automatic,       ///< the model's choice: moreau_jean for a time-stepping model; for an event-driven system
                     ///< cvode_bdf if it declares `stiff = true`, else dormand_prince
    dormand_prince,  ///< header-only explicit RK5(4) with dense output: accuracy-limited, non-stiff rigs
    cvode_bdf,       ///< SUNDIALS CVODE, BDF + Newton with dense direct solver: stiff contact laws
    cvode_adams,     ///< SUNDIALS CVODE, Adams-Moulton + fixed point: smooth, non-stiff
    rosenbrock,      ///< header-only RODAS4 on Eigen (solve/rosenbrock.hpp): stiff, dense or banded LU; needs
                     ///< FRICTIONSIM_EIGEN (the CMake target frictionsim::eigen defines it)
    moreau_jean,     ///< time-stepping models only: Moreau-Jean's theta-method on the one-step contact inclusion,
                     ///< solved exactly (eigen/moreau_jean.hpp); SolverOptions::step and theta. Contacts captured (a
                     ///< switch lands on a step end); what the model locates exactly (its bit treatment) is located.
    explicit_projection,  ///< time-stepping models only: symplectic Euler with the predicted contact force clipped
                          ///< to its bound inside projection_band (the field codes' scheme); step below the element's
                          ///< wave transit time
};

/// Does `m` step a time-stepping model (rather than integrate an event-driven system)?
constexpr bool is_time_stepping_method(Method m) {
    return m == Method::moreau_jean || m == Method::explicit_projection;
}

inline const char* method_name(Method m) {
    switch (m) {
        case Method::automatic: return "automatic";
        case Method::dormand_prince: return "dormand_prince";
        case Method::cvode_bdf: return "cvode_bdf";
        case Method::cvode_adams: return "cvode_adams";
        case Method::rosenbrock: return "rosenbrock";
        case Method::moreau_jean: return "moreau_jean";
        case Method::explicit_projection: return "explicit_projection";
    }
    return "unknown";
}

/// The linear solver of the implicit methods: CVODE BDF's Newton iteration, Rosenbrock's stage systems.
enum class LinearSolver {
    automatic,  ///< band when the system declares jacobian_bandwidths(), else dense
    dense,      ///< SUNDIALS dense LU: O(n^3) per factorisation, right for the lab rigs' 2-20 states
    band,       ///< SUNDIALS band LU: O(n (lower + upper)^2), a string's nodes couple only their neighbours
    sparse,     ///< KLU (SuiteSparse) on the system's jacobian_pattern(): needs jacobian_entries(); CVODE only
};

inline const char* linear_solver_name(LinearSolver s) {
    switch (s) {
        case LinearSolver::automatic: return "automatic";
        case LinearSolver::dense: return "dense";
        case LinearSolver::band: return "band";
        case LinearSolver::sparse: return "sparse";
    }
    return "unknown";
}

/// The solver of moreau_jean's one-step contact problem (eigen/one_step_contact.hpp; MoreauJeanOptions::
/// contact_solver): the exact active set (on a chain, with its updated LDL^T), or projected Gauss-Seidel sweeps
/// (Jean 1999; the same step where the law is monotone, static == kinetic; slower: a sweep per iteration over the
/// whole string). moreau_jean only: refused with the explicit projection and the ODE methods.
enum class ContactSolverChoice {
    active_set,              ///< the default
    projected_gauss_seidel,  ///< ProjectedGaussSeidel with its defaults (tolerance 1e-14, 100000 sweeps)
};

inline const char* contact_solver_name(ContactSolverChoice c) {
    return c == ContactSolverChoice::active_set ? "active_set" : "projected_gauss_seidel";
}

template <class System>
constexpr LinearSolver resolve_linear_solver(LinearSolver requested) {
    if (requested != LinearSolver::automatic) return requested;
    return declares_bandwidths_v<System> ? LinearSolver::band : LinearSolver::dense;
}

/// Does a model declare `static constexpr bool time_stepping = true`? simulate() then steps it with a time-stepping
/// method (solve/time_stepping.hpp) instead of the hybrid event loop: a compile-time dispatch.
template <class T, class = void>
struct declares_time_stepping : std::false_type {};
template <class T>
struct declares_time_stepping<T, std::void_t<decltype(T::time_stepping)>> : std::bool_constant<T::time_stepping> {};
template <class T>
constexpr bool is_time_stepping_model_v = declares_time_stepping<T>::value;

template <class System>
constexpr Method resolve_method(Method requested) {
    if (requested != Method::automatic) return requested;
    if constexpr (is_time_stepping_model_v<System>) return Method::moreau_jean;
    return declares_stiff<System>::value ? Method::cvode_bdf : Method::dormand_prince;
}

struct SolverOptions {
    Method method = Method::automatic;
    LinearSolver linear_solver = LinearSolver::automatic;  ///< CVODE BDF's and Rosenbrock's linear solver
    double rtol = 1e-8;
    double atol = 1e-10;                 ///< scalar absolute tolerance, used when atol_per_state is empty
    std::vector<double> atol_per_state;  ///< one absolute tolerance per state, overrides atol
    long max_steps = 10'000'000;         ///< internal steps over the whole run
    double max_step = std::numeric_limits<double>::infinity();
    double initial_step = 0.0;           ///< 0: the integrator chooses
    std::vector<double> output_times;    ///< increasing; states are interpolated there (dense output)
    bool record_steps = false;           ///< also record the state after every internal step
    /// Rows at both sides of every switch (time of the switch, state and mode before, then after), so that
    /// jumps are not smeared on an output grid.
    bool record_event_rows = false;
    /// Each Event keeps the state before and after its switch. Unset: yes for fixed-size systems (the lab rigs),
    /// no for systems sized at run time (a string's whole state at each of its thousands of switches would be
    /// gigabytes).
    std::optional<bool> record_event_states;
    /// The user's stop conditions (SciPy's `events`): a state crossing a level, or a switch into a named mode.
    std::vector<StopCondition> stop_conditions;
    /// Chattering / Zeno bound: more than max_events_in_window switches within event_window seconds stops the run.
    int max_events_in_window = 100;
    double event_window = 1e-6;
    /// Wall-clock budget of the run [s]: past it the run stops with BudgetExceeded("timeout"), results kept.
    double timeout = std::numeric_limits<double>::infinity();
    /// Rows (outputs and recorded steps) and events a Recorder keeps: past it the run stops with
    /// BudgetExceeded("max_output_rows"), so a failing run cannot fill the memory (2e6 rows are 50-200 MB).
    std::size_t max_output_rows = 2'000'000;
    /// Bytes the recorded rows and events may take; 0: an eighth of the machine's physical memory
    /// (output_byte_budget()). Past it the run stops with BudgetExceeded("max_output_bytes"), results kept; a run
    /// whose rows are known before it starts (output_times, a fixed step) and would not fit is refused at once.
    std::size_t max_output_bytes = 0;
    /// Polled between steps, at most every kPollInterval of wall-clock time: true stops the run (Interrupted).
    /// The Python bindings check for Ctrl-C here. Empty: never polled.
    std::function<bool()> interrupt;

    // The time-stepping methods (moreau_jean, explicit_projection); the ODE methods ignore these.
    /// h [s], the fixed step: positive, not larger than the gap between output_times, and t_end - t_start a whole
    /// number of steps.
    double step = 1e-3;
    /// moreau_jean's theta in [0.5, 1]: 0.5 keeps the linear part's energy exactly, 1 damps it (both A-stable).
    double theta = 0.5;
    /// explicit_projection: |v| [m/s or rad/s] below which the clipped predicted contact force acts (A&S's stick
    /// band, 1.5 rad/s); 0: only at rest.
    double projection_band = 0.0;
    /// moreau_jean's one-step contact solver (ContactSolverChoice); refused by the other methods when not the default.
    ContactSolverChoice contact_solver = ContactSolverChoice::active_set;

    /// The loosest rtol accepted: past it a 5(4) or BDF error estimate no longer bounds the error (a cycle-mean
    /// friction force of the axial rig came out with the wrong sign at rtol 0.2).
    static constexpr double max_rtol = 0.1;
    /// The tightest rtol accepted: below it the error control asks for less than double precision resolves.
    static constexpr double min_rtol = 1e-14;
    /// Above this rtol a result is flagged (Result::warnings): at rtol 1e-2 the axial rig's mean friction force
    /// was 4x off, completed and plausible-looking.
    static constexpr double reliable_rtol = 1e-3;
    /// Absolute tolerances below this are pure relative control: a state crossing zero then forces the step to
    /// underflow (at 1e-100 every rig failed so), which is no fault of the model.
    static constexpr double min_atol = 1e-20;

    /// The ODE methods' checks. Throws InvalidParameter naming the offending option. `state_size` sizes
    /// atol_per_state.
    void validate(std::size_t state_size) const {
        constexpr const char* who = "SolverOptions";
        if (is_time_stepping_method(method))
            throw InvalidParameter("method", std::string(who) + ": method must be an ODE method for an event-driven "
                                             "system (got " + method_name(method) + ", which steps time-stepping "
                                             "models such as TorsionalString)");
        if (contact_solver != ContactSolverChoice::active_set)
            throw InvalidParameter("contact_solver", std::string(who) + ": contact_solver must be active_set (the "
                                                     "default) for an ODE method: it solves moreau_jean's contact "
                                                     "problem (got " + contact_solver_name(contact_solver) + ")");
        validate_budgets();
        if (!(rtol >= min_rtol && rtol <= max_rtol))
            detail::reject(who, "rtol",
                           "in [1e-14, 0.1] (below, under double precision; looser, the integrators' error estimates "
                           "bound nothing)",
                           rtol);
        const auto check_atol = [&](const char* name, double a) {
            detail::require_positive(who, name, a);
            if (a < min_atol)
                detail::reject(who, name, ">= 1e-20 (below it, states crossing zero make the step underflow)", a);
        };
        if (atol_per_state.empty()) {
            check_atol("atol", atol);
        } else {
            if (atol_per_state.size() != state_size)
                detail::reject(who, "atol_per_state", "one entry per state (size given)",
                               static_cast<double>(atol_per_state.size()));
            for (double a : atol_per_state) check_atol("atol_per_state", a);
        }
        if (!(max_step > 0.0)) detail::reject(who, "max_step", "positive", max_step);
        detail::require_non_negative(who, "initial_step", initial_step);
        if (max_events_in_window <= 0 || max_events_in_window > 1'000'000)
            detail::reject(who, "max_events_in_window", "in [1, 1e6]", max_events_in_window);
        detail::require_positive(who, "event_window", event_window);
    }

    /// The time-stepping methods' checks (`resolved`: the method after `automatic`), for a run over
    /// [t_start, t_end]. Throws InvalidParameter naming the offending option.
    void validate_time_stepping(Method resolved, double t_start, double t_end) const {
        constexpr const char* who = "SolverOptions";
        if (!is_time_stepping_method(resolved))
            throw InvalidParameter("method", std::string(who) + ": method must be moreau_jean or "
                                             "explicit_projection for a time-stepping model (got " +
                                             method_name(resolved) + ", which integrates event-driven systems)");
        validate_budgets();
        detail::require_positive(who, "step", step);
        if (!(theta >= 0.5 && theta <= 1.0)) detail::reject(who, "theta", "in [0.5, 1]", theta);
        detail::require_non_negative(who, "projection_band", projection_band);
        if (resolved == Method::moreau_jean && projection_band != 0.0)  // not silently ignored
            detail::reject(who, "projection_band", "0 with moreau_jean (the explicit projection's stick band)",
                           projection_band);
        if (resolved == Method::explicit_projection && contact_solver != ContactSolverChoice::active_set)
            throw InvalidParameter("contact_solver", std::string(who) + ": contact_solver must be active_set (the "
                                                     "default) with explicit_projection: its contact force is "
                                                     "explicit, there is no one-step problem to solve (got " +
                                                     contact_solver_name(contact_solver) + ")");
        for (std::size_t i = 1; i < output_times.size(); ++i)  // a row per step at most: no output is skipped over
            if (step > (output_times[i] - output_times[i - 1]) * (1.0 + 1e-9))
                detail::reject(who, "step", "not larger than the output interval (the gap between output_times)",
                               step);
        const double steps = (t_end - t_start) / step;  // a captured step cannot be shortened to end at t_end
        if (std::isfinite(steps) && std::abs(steps - std::round(steps)) > 1e-6)
            detail::reject(who, "step", "a whole fraction of t_end - t_start (the run ends on the step grid)", step);
    }

    /// The budgets and outputs every method reads.
    void validate_budgets() const {
        constexpr const char* who = "SolverOptions";
        if (max_steps <= 0) detail::reject(who, "max_steps", "positive", static_cast<double>(max_steps));
        if (!(timeout > 0.0)) detail::reject(who, "timeout", "positive (seconds of wall-clock time; inf: none)", timeout);
        if (max_output_rows == 0) detail::reject(who, "max_output_rows", "positive", 0.0);
        for (std::size_t i = 0; i < output_times.size(); ++i) {
            detail::require_finite(who, "output_times", output_times[i]);
            if (i > 0 && !(output_times[i] > output_times[i - 1]))
                detail::reject(who, "output_times", "strictly increasing", output_times[i]);
        }
    }

    /// The byte budget in force: max_output_bytes, or the machine's default when it is 0.
    std::size_t output_byte_budget() const {
        return max_output_bytes > 0 ? max_output_bytes : detail::default_output_bytes();
    }

    double absolute_tolerance(std::size_t i) const { return atol_per_state.empty() ? atol : atol_per_state[i]; }
};

}  // namespace frictionsim
