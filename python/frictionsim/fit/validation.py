"""Checks of the measured record (time base, signals, normal force, weights) before any simulation runs.

Every rejection is an :class:`~frictionsim.errors.InvalidParameterError` naming the offending argument, so a
bad record fails at once with the sample at fault instead of deep inside a fit.
"""

from __future__ import annotations

import math
import sys
from typing import Any, Optional, Tuple, Union

import numpy as np

from ..errors import InvalidParameterError
from ..validation import reject

#: What a kinematic rig takes as N: a constant [N] or a (t_N, N) sample pair.
NormalForce = Union[float, Tuple[np.ndarray, np.ndarray]]


def refuse_text(name: str, value: Any) -> None:
    """Text is never read as a number here: strings become numbers only through :mod:`frictionsim.units` (the
    engine's classes), and a fit takes SI numbers, so ``normal_force='90'`` is refused as ``rtol='1e-6'`` is."""
    if isinstance(value, (str, bytes)):
        reject(f"{name} must be a number [SI], not text (got {value!r})", name)


def real_number(name: str, value: Any, rule: str = "must be a number") -> float:
    """``float(value)`` of a number; text or anything else is refused with ``rule``."""
    refuse_text(name, value)
    try:
        return float(value)
    except (TypeError, ValueError):
        reject(f"{name} {rule} (got {value!r})", name)


def finite_vector(name: str, value: Any, n: Optional[int] = None, like: str = "t") -> np.ndarray:
    """A finite 1-D float array (of ``n`` samples, as many as ``like`` has, when given)."""
    refuse_text(name, value)
    try:
        array = np.asarray(value)
        # numpy would read '90' as 90.0 and drop a complex number's imaginary part
        if array.dtype.kind in "USc" or (array.dtype.kind == "O" and any(isinstance(v, (str, bytes, complex))
                                                                         for v in array.flat)):
            reject(f"{name} must be an array of real numbers [SI], not text or complex (dtype {array.dtype})",
                   name)
        array = np.asarray(array, dtype=float)
    except (TypeError, ValueError) as error:
        if isinstance(error, InvalidParameterError):
            raise
        reject(f"{name} must be a 1-D array of numbers", name)
    if array.ndim != 1:
        reject(f"{name} must be a 1-D array (got shape {array.shape})", name)
    if n is not None and array.size != n:
        reject(f"{name} must have as many samples as {like} ({n}); got {array.size}", name)
    if not np.all(np.isfinite(array)):
        bad = int(np.flatnonzero(~np.isfinite(array))[0])
        reject(f"{name} must be finite (sample {bad} is {array[bad]})", name)
    return array


def sample_times(t: Any) -> np.ndarray:
    """Sample times: at least 3 (a fit needs more samples than the smallest model), strictly increasing."""
    t = finite_vector("t", t)
    if t.size < 3:
        reject(f"t must hold at least 3 samples (got {t.size})", "t")
    steps = np.diff(t)
    if not np.all(steps > 0.0):
        bad = int(np.flatnonzero(~(steps > 0.0))[0]) + 1
        reject(f"t must be strictly increasing (t[{bad}] = {t[bad]} after {t[bad - 1]})", "t")
    return t


def checked_record(t: Any, signal: Any, name: str) -> Tuple[np.ndarray, np.ndarray]:
    """-> (t, signal): the time base, then a signal sampled on it."""
    t = sample_times(t)
    return t, finite_vector(name, signal, t.size)


def checked_normal_force(normal_force: Any, t: np.ndarray) -> Tuple[NormalForce, float]:
    """-> (what KinematicRig takes, N at t[0]); accepts a number, an array like t, or a (t_N, N) pair."""
    if normal_force is None:
        reject("normal_force is required: a positive number [N] or an array of N(t) samples", "normal_force")
    refuse_text("normal_force", normal_force)
    if np.ndim(normal_force) == 0 and not isinstance(normal_force, (tuple, list)):
        try:
            value = float(normal_force)
        except (TypeError, ValueError):
            reject(f"normal_force must be a number or an array (got {type(normal_force).__name__})", "normal_force")
        if not (math.isfinite(value) and value > 0.0):
            reject(f"normal_force must be positive and finite (got {value})", "normal_force")
        return value, value
    if isinstance(normal_force, tuple) and len(normal_force) == 2:
        t_n = sample_times(normal_force[0])
        n = finite_vector("normal_force", normal_force[1], t_n.size)
        if t_n[0] > t[0] or t_n[-1] < t[-1]:
            reject(f"normal_force samples must cover t = [{t[0]}, {t[-1]}] s (they cover [{t_n[0]}, {t_n[-1]}])",
                   "normal_force")
    else:
        t_n, n = t, finite_vector("normal_force", normal_force, t.size)
    if not np.all(n > 0.0):
        bad = int(np.flatnonzero(~(n > 0.0))[0])
        reject(f"normal_force must be positive at every sample (sample {bad} is {n[bad]})", "normal_force")
    return (t_n, n), float(np.interp(t[0], t_n, n))


def residual_weights(weights: Any, n: int) -> Optional[np.ndarray]:
    """Residual weights 1/sigma_i: non-negative (0 drops a sample), not all zero."""
    if weights is None:
        return None
    w = finite_vector("weights", weights, n)
    if not np.all(w >= 0.0) or not np.any(w > 0.0):
        reject("weights must be non-negative with at least one positive (they multiply the residuals, "
               "1/sigma_i)", "weights")
    return w


def varying(name: str, values: np.ndarray, parameter: Optional[str] = None, where: str = "",
            why: str = "so there is nothing to fit and R^2 is undefined") -> np.ndarray:
    """A fitted signal must vary: R^2 = 1 - SS_res / SS_tot is undefined for a constant one, which holds nothing to
    fit. Constant to within rounding counts (a spread of a few ulps, e.g. a value written out and read back)."""
    spread, largest = float(np.ptp(values)), float(np.max(np.abs(values)))
    if spread <= 4.0 * np.finfo(float).eps * largest:
        reject(f"{name}{where} must vary: it is constant, {float(values[0])!r} at all {values.size} samples"
               f"{' (to within rounding)' if spread else ''}, {why}", parameter or name)
    return values


def summable(name: str, values: np.ndarray) -> np.ndarray:
    """A fitted signal whose squared residuals sum finitely: |value| below sqrt(max double / (100 n)) (the
    searches square residuals up to 10x the record's size; 1.3e152 N for 100 samples)."""
    limit = math.sqrt(sys.float_info.max / (100.0 * values.size))
    largest = float(np.max(np.abs(values)))
    if not largest < limit:
        reject(f"{name} must stay below {limit:.3g} in magnitude so that the fit's sums of squares over its "
               f"{values.size} samples are finite in double precision (largest |{name}| = {largest:.3g}); "
               f"rescale it (other units)", name)
    return values
