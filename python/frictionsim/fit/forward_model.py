"""The forward model of output-error identification: one engine run per parameter vector, recorded at the
measured sample times, with tolerances that make the fitted force accurate to a fixed number of newtons.
"""

from __future__ import annotations

import math
import numbers
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from .._core import SolverOptions
from ..errors import SimulationError
from ..simulation import simulate
from ..validation import reject

#: Steps allowed per run: max(_STEP_CAP, _STEPS_PER_SAMPLE * samples). A Dormand-Prince run that needs more is
#: stiff (Dahl with a large k_t relaxes at k_t |v_r| / (mu N), far faster than the record) and is redone with
#: CVODE BDF under the same cap; a BDF run that needs more counts as failed (Dahl with alpha < 1 reaches
#: saturation in finite time, where its right-hand side is not Lipschitz, and both integrators crawl there).
_STEP_CAP = 20_000
_STEPS_PER_SAMPLE = 50


def simulate_kwargs(simulate_options: Optional[Mapping[str, Any]], rtol: float,
                    atol: Optional[float]) -> Dict[str, Any]:
    """The user's simulate options, checked; the output times, time span and tolerances are the fit's."""
    for name, value in (("rtol", rtol), ("atol", atol)):
        if value is None and name == "atol":
            continue
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            reject(f"{name} must be a positive number (got {value!r})", name)
        if not (math.isfinite(value) and value > 0):
            reject(f"{name} must be positive and finite (got {value!r})", name)
    # the engine's own rule for rtol, now: each simulation would refuse it, and the search would count every
    # refusal as a failed run and report a table of NaN instead of the option at fault
    SolverOptions(rtol=float(rtol)).validate()
    sim_kwargs = dict(simulate_options or {})
    for reserved in ("output_times", "t_start", "t_end", "rtol", "atol"):
        if reserved in sim_kwargs:
            reject(f"simulate_options[{reserved!r}] is set by the fit (use the rtol= / atol= arguments for "
                   f"the tolerances)", f"simulate_options[{reserved!r}]")
    sim_kwargs.update(rtol=float(rtol))
    return sim_kwargs


def default_force_atol(atol: Optional[float], measured: np.ndarray) -> float:
    """Absolute tolerance on the fitted force [N]: given, or 1e-6 of the record's largest force."""
    if atol is not None:
        return float(atol)
    return 1e-6 * (float(np.max(np.abs(measured))) or 1.0)


def _atol_per_state(names: Sequence[str], force_atol: float, *, law_stiffness: float, duration: float,
                    speed: float, drive_stiffness: Optional[float] = None, omega: float = 0.0) -> List[float]:
    """Absolute tolerance per state, scaled so each contributes ~force_atol [N] to the fitted force.

    The law's deflection by its stiffness (F = k z: a stiff contact is then resolved as accurately as a soft
    one), the rig's position by the drive spring (F_d = k_d (v_d t - x)) and its velocity by the vibration
    frequency, the impulse and work integrals by the record's duration and speed.
    """
    out = []
    for name in names:
        if name == "position":
            out.append(force_atol / drive_stiffness)
        elif name == "velocity":
            out.append(force_atol / drive_stiffness * omega)
        elif "deflection" in name:  # dahl_, bristle_, block_deflection_1..: the law has a positive stiffness
            out.append(force_atol / law_stiffness)
        elif name == "friction_impulse":
            out.append(force_atol * duration)
        elif name.endswith("work"):
            out.append(force_atol * duration * speed)
        else:
            out.append(force_atol)
    # not below the engine's floor: a record of micro-newtons against a stiff contact would fail every run
    return [max(atol, SolverOptions.min_atol) for atol in out]


def with_state_atol(sim_kwargs: Mapping[str, Any], names: Sequence[str], force_atol: float,
                    **scales: float) -> Dict[str, Any]:
    """``sim_kwargs`` with :func:`_atol_per_state`, unless the user set per-state tolerances."""
    kwargs = dict(sim_kwargs)
    if "atol_per_state" not in kwargs:
        kwargs["atol_per_state"] = _atol_per_state(names, force_atol, **scales)
    return kwargs


def simulate_at_samples(rig: Any, t: np.ndarray, sim_kwargs: Mapping[str, Any]):
    """One run recorded at the samples ``t``.

    Unless the caller chose the integrator or the step limit, a run that needs more than the step cap (see
    _STEP_CAP) is redone with CVODE BDF under the same cap: the stiff fallback.
    """
    kwargs = dict(sim_kwargs, output_times=t, t_start=float(t[0]))
    if "method" in kwargs or "max_steps" in kwargs:
        return simulate(rig, float(t[-1]), **kwargs)
    cap = max(_STEP_CAP, _STEPS_PER_SAMPLE * t.size)
    try:
        return simulate(rig, float(t[-1]), max_steps=cap, **kwargs)
    except SimulationError:
        return simulate(rig, float(t[-1]), method="cvode_bdf", max_steps=cap, **kwargs)
