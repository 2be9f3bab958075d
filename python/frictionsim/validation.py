"""The ground floor's checks, shared by every part of the package (it imports only :mod:`frictionsim.errors`).

* :func:`reject`: raise :class:`~frictionsim.errors.InvalidParameterError` naming the parameter;
* :func:`non_finite`: the fields of a result holding NaN or inf;
* :func:`require_finite`: the rule every closed-form fit or estimate passes before it is returned: NaN or inf is
  never success; the error names the input whose magnitudes made it.
"""

from __future__ import annotations

import math
from typing import Any, List, Mapping, NoReturn

import numpy as np

from .errors import InvalidParameterError


def reject(message: str, parameter: str) -> NoReturn:
    """Raise InvalidParameterError(message, parameter): ``message`` states the rule, ``parameter`` names it."""
    raise InvalidParameterError(message, parameter)


def non_finite(fields: Mapping[str, Any]) -> List[str]:
    """The names of the fields holding NaN or +-inf: numbers, arrays, sequences, or dicts of numbers (reported
    as ``name[key]``). None means "not computed" and passes."""
    bad: List[str] = []
    for name, value in fields.items():
        if isinstance(value, Mapping):
            bad.extend(non_finite({f"{name}[{key!r}]": item for key, item in value.items()}))
        elif value is not None and not np.all(np.isfinite(np.asarray(value, dtype=float))):
            bad.append(name)
    return bad


def require_finite(owner: str, fields: Mapping[str, Any], inputs: Mapping[str, Any]) -> None:
    """Raise InvalidParameterError when a field of a closed-form fit is not finite. Its inputs were finite, so
    some magnitude over- or underflowed: the error names the input furthest from 1 in orders of magnitude
    (``inputs``: name -> values)."""
    bad = non_finite(fields)
    if not bad:
        return
    sizes = {name: float(np.max(np.abs(np.asarray(value, dtype=float)))) for name, value in inputs.items()}
    culprit = max(sizes, key=lambda name: abs(math.log10(sizes[name])) if sizes[name] > 0.0 else 0.0)
    raise InvalidParameterError(
        f"{owner}: {culprit} must have magnitudes that keep the result finite in double precision (largest "
        f"|{culprit}| = {sizes[culprit]:.3g}; not finite: {', '.join(bad[:6])}); rescale the data (other units)",
        culprit)
