"""Fit quality, and the one rule every fit's result passes before it is returned: NaN or inf is never success.

* :func:`fit_quality`: rms residual and R^2 = 1 - SS_res / SS_tot, summed in units of the record's largest
  value so that neither sum over- or underflows for any record double precision can hold;
* an iterative fit (identify_*, identify_axial_rig) has a success flag: :func:`finite_or_failed` turns it off
  and says which fields are not finite (:func:`frictionsim.validation.non_finite`), as scipy.optimize reports a
  failed search;
* a closed-form fit (the power-law line, the eq 6 branches, the eq 1a torque) has none, so
  :func:`frictionsim.validation.require_finite` raises InvalidParameterError naming the input whose magnitudes
  did it.

R^2 of a constant record is undefined: the fits refuse one before fitting (``validation.varying``), so a NaN
here always means an overflow or a failed fit, never "no variance".
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Tuple

import numpy as np

from ..validation import non_finite


def fit_quality(measured: np.ndarray, residual: np.ndarray) -> Tuple[float, float]:
    """-> (rms residual, R^2) of ``residual`` (model - measured) against a varying ``measured``."""
    scale = float(np.max(np.abs(measured)))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        r = residual / scale  # the residual may still be too large for its square: inf, caught by the rule below
        m = measured / scale
        centred = m - m.mean()
        ss_res, ss_tot = float(r @ r), float(centred @ centred)
        return scale * math.sqrt(ss_res / r.size), 1.0 - ss_res / ss_tot


def finite_or_failed(success: bool, message: str, fields: Mapping[str, Any]) -> Tuple[bool, str]:
    """-> (success, message) of an iterative fit: not a success when a field is not finite, whatever the
    optimiser said, and the message says which."""
    bad = non_finite(fields)
    if not bad:
        return success, message
    return False, (f"not finite: {', '.join(bad[:6])}{' ...' if len(bad) > 6 else ''} (the record's magnitudes "
                   f"overflow double precision against the model's, or the fit diverged); optimiser: {message}")
