"""Fit quality, and the one rule every fit's result passes before it is returned: NaN or inf is never success.

* :func:`_fit_quality`: rms residual and R^2 = 1 - SS_res / SS_tot, summed in units of the record's largest
  value so that neither sum over- or underflows for any record double precision can hold;
* :func:`_non_finite`: the result's fields holding NaN or inf;
* an iterative fit (identify_*, identify_axial_rig) has a success flag: :func:`_finite_or_failed` turns it off
  and says which fields are not finite, as scipy.optimize reports a failed search;
* a closed-form fit (the power-law line, the eq 6 branches, the eq 1a torque) has none, so
  :func:`_require_finite` raises InvalidParameterError naming the input whose magnitudes did it.

R^2 of a constant record is undefined: the fits refuse one before fitting (``validation._varying``), so a NaN
here always means an overflow or a failed fit, never "no variance".
"""

from __future__ import annotations

import math
from typing import Any, List, Mapping, Tuple

import numpy as np

from ..errors import InvalidParameterError


def _fit_quality(measured: np.ndarray, residual: np.ndarray) -> Tuple[float, float]:
    """-> (rms residual, R^2) of ``residual`` (model - measured) against a varying ``measured``."""
    scale = float(np.max(np.abs(measured)))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        r = residual / scale  # the residual may still be too large for its square: inf, caught by the rule below
        m = measured / scale
        centred = m - m.mean()
        ss_res, ss_tot = float(r @ r), float(centred @ centred)
        return scale * math.sqrt(ss_res / r.size), 1.0 - ss_res / ss_tot


def _non_finite(fields: Mapping[str, Any]) -> List[str]:
    """The names of the fields holding NaN or +-inf: numbers, arrays, sequences, or dicts of numbers (reported
    as ``name[key]``). None means "not computed" and passes."""
    bad: List[str] = []
    for name, value in fields.items():
        if isinstance(value, Mapping):
            bad.extend(_non_finite({f"{name}[{key!r}]": item for key, item in value.items()}))
        elif value is not None and not np.all(np.isfinite(np.asarray(value, dtype=float))):
            bad.append(name)
    return bad


def _finite_or_failed(success: bool, message: str, fields: Mapping[str, Any]) -> Tuple[bool, str]:
    """-> (success, message) of an iterative fit: not a success when a field is not finite, whatever the
    optimiser said, and the message says which."""
    bad = _non_finite(fields)
    if not bad:
        return success, message
    return False, (f"not finite: {', '.join(bad[:6])}{' ...' if len(bad) > 6 else ''} (the record's magnitudes "
                   f"overflow double precision against the model's, or the fit diverged); optimiser: {message}")


def _require_finite(owner: str, fields: Mapping[str, Any], inputs: Mapping[str, Any]) -> None:
    """Raise InvalidParameterError when a field of a closed-form fit is not finite. Its inputs were finite, so
    some magnitude over- or underflowed: the error names the input furthest from 1 in orders of magnitude
    (``inputs``: name -> values)."""
    bad = _non_finite(fields)
    if not bad:
        return
    sizes = {name: float(np.max(np.abs(np.asarray(value, dtype=float)))) for name, value in inputs.items()}
    culprit = max(sizes, key=lambda name: abs(math.log10(sizes[name])) if sizes[name] > 0.0 else 0.0)
    raise InvalidParameterError(
        f"{owner}: {culprit} must have magnitudes that keep the result finite in double precision (largest "
        f"|{culprit}| = {sizes[culprit]:.3g}; not finite: {', '.join(bad[:6])}); rescale the data (other units)",
        culprit)
