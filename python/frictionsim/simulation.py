"""simulate(): run a rig through the hybrid (event-driven) integrator of the C++ engine."""

from __future__ import annotations

import math
import numbers
import time
import warnings
from typing import List, Optional, Sequence, Union

import numpy as np

from . import _core
from .errors import AccuracyWarning, InvalidParameterError, SimulationError
from .result import Result

__all__ = ["simulate", "METHODS", "LINEAR_SOLVERS", "CONTACT_SOLVERS", "SOLVER_DEFAULTS"]

#: Integrator names accepted by simulate(method=...): the engine's Method enum.
METHODS = tuple(_core.Method.__members__)
#: Linear solvers of CVODE BDF's Newton iteration accepted by simulate(linear_solver=...) (the engine's enum).
LINEAR_SOLVERS = tuple(_core.LinearSolver.__members__)
#: moreau_jean's one-step contact solvers accepted by simulate(contact_solver=...) (the engine's enum).
CONTACT_SOLVERS = tuple(_core.ContactSolver.__members__)

#: The methods that step a time-stepping model (TorsionalString) with a fixed step instead of locating events.
TIME_STEPPING_METHODS = tuple(m for m in ("moreau_jean", "explicit_projection") if m in METHODS)

Rig = Union["_core.AxialVibrationRig", "_core.KinematicRig", "_core.TorsionalRig", "_core.StringRig"]

#: The engine's defaults (C++ SolverOptions{}): every signature that offers solver options takes its defaults
#: from here instead of restating them.
SOLVER_DEFAULTS = _core.SolverOptions()


def simulate(rig: Rig, t_end: float, *, method: str = "automatic",
             linear_solver: str = SOLVER_DEFAULTS.linear_solver.name, rtol: float = SOLVER_DEFAULTS.rtol,
             atol: float = SOLVER_DEFAULTS.atol, atol_per_state: Optional[Sequence[float]] = None,
             output_times: Optional[Sequence[float]] = None, record_steps: bool = SOLVER_DEFAULTS.record_steps,
             max_steps: int = SOLVER_DEFAULTS.max_steps, max_step: float = SOLVER_DEFAULTS.max_step,
             initial_step: float = SOLVER_DEFAULTS.initial_step,
             max_events_in_window: int = SOLVER_DEFAULTS.max_events_in_window,
             event_window: float = SOLVER_DEFAULTS.event_window, t_start: float = 0.0,
             timeout: Optional[float] = None, max_output_rows: Optional[int] = None,
             max_output_bytes: Optional[int] = None,
             events: Optional[Sequence["_core.StopCondition"]] = None, record_events: bool = False,
             record_event_states: Optional[bool] = None, step: Optional[float] = None,
             theta: Optional[float] = None, projection_band: Optional[float] = None,
             contact_solver: Optional[str] = None) -> Result:
    """Simulate ``rig`` from ``t_start`` to ``t_end`` [s] and return a :class:`Result`.

    Every stick-slip switch and velocity reversal is located as an event and the integrator restarts exactly
    there. The GIL is released while integrating, so runs in threads proceed in parallel and give results
    identical to serial runs. Ctrl-C stops a run within a fraction of a second as ``KeyboardInterrupt``.

    Parameters
    ----------
    rig : AxialVibrationRig, KinematicRig, TorsionalRig, StringRig, NavarroLopez2Dof, NavarroLopez4Dof or TorsionalString
        A TorsionalString under treatment "captured" or "mixed" is a time-stepping model: it runs by
        "moreau_jean" (its "automatic") or "explicit_projection" with a fixed ``step``; under "exact", and the
        other rigs always, by the ODE methods, every switch located.
    t_end : float, s
    method : {"automatic", "dormand_prince", "cvode_bdf", "cvode_adams", "rosenbrock", "moreau_jean", "explicit_projection"}
        "automatic" picks CVODE BDF for stiff laws (LuGre, ElastoPlastic) and Dormand-Prince 5(4) otherwise
        (measured faster on these rigs, see the README). "rosenbrock" is RODAS4 (linearly implicit, order 4,
        stiff, no Newton iteration; the extension needs Eigen: ``fs.HAS_EIGEN``). An extension built without
        SUNDIALS (``fs.HAS_SUNDIALS`` is False) runs "automatic" as Dormand-Prince for every law, and "cvode_bdf" /
        "cvode_adams" raise InvalidParameterError saying how to get them. "moreau_jean" (Moreau-Jean's theta-method
        on each step's contact inclusion) and "explicit_projection" (the field codes' explicit scheme) step a
        time-stepping model (TorsionalString) and only that.
    step : float, s, optional
        The time-stepping methods' fixed step h (default the engine's, 1 ms): not larger than the gap between
        ``output_times``, and t_end - t_start a whole number of steps. Refused for the ODE methods.
    theta : float, optional
        Moreau-Jean's theta in [0.5, 1] (default 0.5: the linear part's energy kept; 1 damps it).
    projection_band : float, optional
        "explicit_projection": the speed [rad/s] below which the clipped predicted contact force acts (A&S's stick
        band, 1.5 rad/s; default 0: only at rest). Refused for the ODE methods.
    contact_solver : {"active_set", "projected_gauss_seidel"}, optional
        The solver of each Moreau-Jean step's contact problem: the exact active set (the default) or projected
        Gauss-Seidel sweeps (the same steps where the law is monotone, static == kinetic; slower). "moreau_jean"
        only: refused for the other methods, naming it.
    linear_solver : {"automatic", "dense", "band", "sparse"}
        The linear solver of CVODE BDF's Newton iteration: "automatic" is band LU where the rig declares a banded
        Jacobian (a StringRig: its nodes couple only their neighbours), dense LU otherwise; "sparse" (KLU) only
        where the extension was built with it.
    rtol, atol : float
        Relative and absolute tolerances (atol in the states' SI units). rtol must lie in [1e-14, 0.1] and atol
        be at least 1e-20; a result at rtol above 1e-3 carries an :class:`AccuracyWarning` (``Result.warnings``):
        the error estimates no longer vouch for cycle means of stick-slip rigs there.
    atol_per_state : sequence of float, optional
        One absolute tolerance per state (overrides atol).
    output_times : sequence of float, s, optional
        Increasing times within [t_start, t_end] to record (dense output). Default: every internal step.
    record_steps : bool
        With output_times, also record every internal step.
    max_steps, max_step, initial_step
        Step limits (max_step and initial_step in s; 0 lets the integrator choose).
    max_events_in_window, event_window
        Chattering bound: more than max_events_in_window switches within event_window [s] raises ChatteringError.
    timeout : float, s, optional
        Wall-clock budget of the run: past it :class:`BudgetExceededError` (``budget == "timeout"``) with the
        results up to there.
    max_output_rows : int, optional
        Rows (and events) the result may hold; default the engine's (2,000,000). Past it
        :class:`BudgetExceededError` (``budget == "max_output_rows"``), so a failing run cannot fill the memory.
    max_output_bytes : int, bytes, optional
        Bytes the recorded rows and events may take; default an eighth of the machine's physical memory (the
        result is copied once more into NumPy). Past it :class:`BudgetExceededError` (``budget ==
        "max_output_bytes"``) with a consistent partial result; a run whose rows are known before it starts
        (``output_times``, or every fixed ``step``) and would not fit is refused at once (InvalidParameterError
        naming ``max_output_bytes``).
    events : sequence of StopCondition, optional
        Stop conditions evaluated in the engine as the run goes (SciPy's ``events``, without a Python call per
        step): ``StopCondition(state="disc_speed", level=0.0, direction=-1)`` (a state crossing a level, located
        on the dense output) or ``StopCondition(mode="stick")`` (a switch into a mode of that name). Crossings go
        to ``Result.t_events`` / ``y_events`` / ``stop_events``; the first crossing of a terminal one ends the
        run there (``Result.status == 1``).
    record_events : bool
        Also put rows at both sides of every switch (its time, with the state and mode before, then after), so
        that jumps are not smeared on the output grid.
    record_event_states : bool, optional
        Keep the state before and after each switch on its :class:`Event` (``events_frame()``). Default: yes for
        the lab rigs, no for a StringRig (its whole state at each of thousands of switches).

    Raises
    ------
    InvalidParameterError (ValueError)
        A bad option or rig input, naming it.
    SimulationError
        The run stopped early; ``.time_reached`` and ``.partial`` (the Result up to it). Subclasses:
        ChatteringError, BudgetExceededError.
    KeyboardInterrupt
        Ctrl-C, or raised by a Python callable of the rig (propagated unchanged, as is SystemExit).
    """
    if not isinstance(rig, _core.RIGS):
        names = ", ".join(cls.__name__ for cls in _core.RIGS)
        raise TypeError(f"rig must be one of the engine's rigs ({names}), got {type(rig).__name__}")
    if not isinstance(method, str) or method not in METHODS:
        raise InvalidParameterError(f"method must be one of {', '.join(METHODS)} (got {method!r})", "method")
    options = _core.SolverOptions()
    options.method = getattr(_core.Method, method)
    if not isinstance(linear_solver, str) or linear_solver not in LINEAR_SOLVERS:
        raise InvalidParameterError(f"linear_solver must be one of {', '.join(LINEAR_SOLVERS)} "
                                    f"(got {linear_solver!r})", "linear_solver")
    options.linear_solver = getattr(_core.LinearSolver, linear_solver)
    options.rtol = _real("rtol", rtol)
    options.atol = _real("atol", atol)
    if atol_per_state is not None:
        options.atol_per_state = _reals("atol_per_state", atol_per_state)
    if output_times is not None:
        options.output_times = _reals("output_times", output_times)
    options.record_steps = _flag("record_steps", record_steps)
    options.max_steps = _integer("max_steps", max_steps, 1, 2**62)
    options.max_step = _real("max_step", max_step)
    options.initial_step = _real("initial_step", initial_step)
    options.max_events_in_window = _integer("max_events_in_window", max_events_in_window, 1, 1_000_000)
    options.event_window = _real("event_window", event_window)
    if timeout is not None:
        options.timeout = _real("timeout", timeout)
    if max_output_rows is not None:
        options.max_output_rows = _integer("max_output_rows", max_output_rows, 1, 2**62)
    if max_output_bytes is not None:
        options.max_output_bytes = _integer("max_output_bytes", max_output_bytes, 1, 2**62)
    conditions = _stop_conditions(events)
    options.stop_conditions = conditions
    options.record_event_rows = _flag("record_events", record_events)
    if record_event_states is not None:
        options.record_event_states = _flag("record_event_states", record_event_states)
    time_stepping = method in TIME_STEPPING_METHODS or (method == "automatic" and _is_time_stepping(rig))
    for name, value in (("step", step), ("theta", theta), ("projection_band", projection_band)):
        if value is None:
            continue
        if not time_stepping:
            raise InvalidParameterError(f"{name} is an option of the time-stepping methods "
                                        f"({', '.join(TIME_STEPPING_METHODS)}), not of method {method!r} on a "
                                        f"{type(rig).__name__}", name)
        setattr(options, name, _real(name, value))
    if contact_solver is not None:
        if not time_stepping:
            raise InvalidParameterError(f"contact_solver is an option of method 'moreau_jean', not of method "
                                        f"{method!r} on a {type(rig).__name__}", "contact_solver")
        if not isinstance(contact_solver, str) or contact_solver not in CONTACT_SOLVERS:
            raise InvalidParameterError(f"contact_solver must be one of {', '.join(CONTACT_SOLVERS)} "
                                        f"(got {contact_solver!r})", "contact_solver")
        options.contact_solver = contact_solver  # explicit_projection refuses it in the engine, naming it
    started = time.time()
    try:
        raw = rig._simulate(_real("t_end", t_end), options, _real("t_start", t_start))
    except SimulationError as error:
        partial = error.partial
        if partial is not None:  # the partial result records what ran, as a completed one does
            partial.period = rig.period  # so error.partial.mean_over_cycles() knows the rig's period
            partial._run = (rig, options, started, conditions)
            partial.stop_condition_count = len(conditions)
        raise
    result = Result(raw, period=rig.period)
    result.stop_condition_count = len(conditions)
    result._run = (rig, options, started, conditions)  # Result.metadata: its provenance, made when first asked for
    for message in result.warnings:
        warnings.warn(message, AccuracyWarning, stacklevel=2)
    return result


def _is_time_stepping(rig) -> bool:
    """A TorsionalString under a time-stepping treatment (captured, mixed); under "exact" it runs event-driven."""
    field = getattr(_core, "TorsionalString", None)  # bound only with Eigen (HAS_EIGEN)
    return field is not None and isinstance(rig, field) and rig.treatment != "exact"


def _stop_conditions(events) -> List["_core.StopCondition"]:
    if events is None:
        return []
    if isinstance(events, _core.StopCondition):
        events = [events]
    if isinstance(events, (str, bytes)) or not hasattr(events, "__iter__"):
        raise InvalidParameterError(f"events must be a sequence of StopCondition (got {type(events).__name__})",
                                    "events")
    conditions = list(events)
    for condition in conditions:
        if not isinstance(condition, _core.StopCondition):
            raise InvalidParameterError("events must hold StopCondition objects (got "
                                        f"{type(condition).__name__} {condition!r:.60})", "events")
        repr(condition)  # the construction guard: a StopCondition.__new__ without __init__ raises TypeError here
    return conditions


def _real(name: str, value) -> float:
    """A real number (int, float, NumPy scalar); strings, bools and None are refused, not converted."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating, np.integer)):
        raise InvalidParameterError(f"{name} must be a real number (got {type(value).__name__} {value!r:.60})",
                                    name)
    return float(value)


def _reals(name: str, values) -> List[float]:
    if isinstance(values, (str, bytes)):
        raise InvalidParameterError(f"{name} must be a sequence of real numbers (got {type(values).__name__})", name)
    try:
        array = np.asarray(values)
    except (TypeError, ValueError) as error:
        raise InvalidParameterError(f"{name} must be a sequence of real numbers ({error})", name) from None
    if array.dtype.kind not in "iuf" or array.ndim > 1:
        raise InvalidParameterError(f"{name} must be a one-dimensional sequence of real numbers "
                                    f"(got dtype {array.dtype}, {array.ndim} dimensions)", name)
    return [float(x) for x in np.ravel(array)]


def _flag(name: str, value) -> bool:
    """True or False only: "yes", 1 or "false" are refused rather than guessed at."""
    if not isinstance(value, (bool, np.bool_)):
        raise InvalidParameterError(f"{name} must be True or False (got {type(value).__name__} {value!r:.60})", name)
    return bool(value)


def _integer(name: str, value, low: int, high: int) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.integer, np.floating)):
        raise InvalidParameterError(f"{name} must be a whole number (got {type(value).__name__} {value!r:.60})", name)
    if not (math.isfinite(value) and float(value).is_integer()):
        raise InvalidParameterError(f"{name} must be a whole number (got {value!r})", name)
    if not low <= int(value) <= high:
        raise InvalidParameterError(f"{name} must be in [{low}, {high}] (got {int(value)})", name)
    return int(value)
