"""simulate(): run a rig through the hybrid (event-driven) integrator of the C++ engine."""

from __future__ import annotations

import math
from typing import Optional, Sequence, Union

import numpy as np

from . import _core
from .errors import SimulationError
from .result import Result

__all__ = ["simulate", "METHODS"]

#: Integrator names accepted by simulate(method=...).
METHODS = ("automatic", "dormand_prince", "cvode_bdf", "cvode_adams")

Rig = Union["_core.AxialVibrationRig", "_core.KinematicRig", "_core.TorsionalRig"]


def simulate(rig: Rig, t_end: float, *, method: str = "automatic", rtol: float = 1e-8, atol: float = 1e-10,
             atol_per_state: Optional[Sequence[float]] = None, output_times: Optional[Sequence[float]] = None,
             record_steps: bool = False, max_steps: int = 10_000_000, max_step: float = math.inf,
             initial_step: float = 0.0, max_events_in_window: int = 100, event_window: float = 1e-6,
             t_start: float = 0.0) -> Result:
    """Simulate ``rig`` from ``t_start`` to ``t_end`` [s] and return a :class:`Result`.

    Every stick-slip switch and velocity reversal is located as an event and the integrator restarts exactly
    there. The GIL is released while integrating, so runs in threads proceed in parallel and give results
    identical to serial runs.

    Parameters
    ----------
    rig : AxialVibrationRig, KinematicRig or TorsionalRig
    t_end : float, s
    method : {"automatic", "dormand_prince", "cvode_bdf", "cvode_adams"}
        "automatic" picks CVODE BDF for stiff laws (LuGre, ElastoPlastic) and Dormand-Prince 5(4) otherwise
        (measured faster on these rigs, see the README).
    rtol, atol : float
        Relative and absolute tolerances (atol in the states' SI units).
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

    Raises
    ------
    InvalidParameterError (ValueError)
        A bad option or rig input, naming it.
    SimulationError
        The run stopped early; ``.time_reached`` and ``.partial`` (the Result up to it).
    """
    if not isinstance(rig, (_core.AxialVibrationRig, _core.KinematicRig, _core.TorsionalRig)):
        raise TypeError(f"rig must be an AxialVibrationRig, a KinematicRig or a TorsionalRig, got {type(rig).__name__}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)} (got {method!r})")
    options = _core.SolverOptions()
    options.method = getattr(_core.Method, method)
    options.rtol = float(rtol)
    options.atol = float(atol)
    if atol_per_state is not None:
        options.atol_per_state = [float(a) for a in np.ravel(atol_per_state)]
    if output_times is not None:
        options.output_times = [float(x) for x in np.ravel(output_times)]
    options.record_steps = bool(record_steps)
    options.max_steps = _integer("max_steps", max_steps)
    options.max_step = float(max_step)
    options.initial_step = float(initial_step)
    options.max_events_in_window = _integer("max_events_in_window", max_events_in_window)
    options.event_window = float(event_window)
    try:
        raw = rig._simulate(float(t_end), options, float(t_start))
    except SimulationError as error:
        error._period = rig.period  # so error.partial.mean_over_cycles() knows the rig's period
        raise
    return Result(raw, period=rig.period)


def _integer(name: str, value) -> int:
    if isinstance(value, bool) or not float(value).is_integer():
        raise ValueError(f"{name} must be a whole number (got {value!r})")
    if not -2**62 < float(value) < 2**62:
        raise ValueError(f"{name} must be a whole number of reasonable size (got {value!r})")
    return int(value)
