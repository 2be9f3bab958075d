"""Shortening a long record before a fit: :func:`decimate` averages blocks of consecutive samples.

An output-error fit simulates the whole record at every evaluation and runs tens to thousands of them, so its work
grows as rows x simulations; a record sampled far faster than its dynamics (1e6 rows of a 10 kHz logger for a
few-hertz vibration) holds no more information for the fit than its block means, and costs a thousand times more.
The fits refuse a record whose estimated work is beyond their limit (:data:`frictionsim.fit.solver.MAX_FIT_WORK`)
and say which factor brings it within.
"""

from __future__ import annotations

import numbers
from typing import Any, Tuple

import numpy as np

from ..validation import reject
from .validation import finite_vector

__all__ = ["decimate"]


def decimate(t: Any, *signals: Any, factor: int) -> Tuple[Any, ...]:
    """``(t, *signals)`` averaged over blocks of ``factor`` consecutive samples (the last block may be shorter).

    A boxcar low-pass and one sample per block: the block means of t and of each signal (velocity, force, normal
    force samples) stay consistent with each other, and noise averages down by sqrt(factor). Keep a block well
    below the shortest time scale of the dynamics (a tenth of the vibration period, of a stick phase) so that
    their shape survives. A scalar among ``signals`` (a constant normal force) is passed through unchanged.

    Raises :class:`frictionsim.InvalidParameterError` naming ``factor``, ``t`` or the signal (``signals[i]``).
    """
    if isinstance(factor, bool) or not isinstance(factor, numbers.Integral) or factor < 1:
        reject(f"factor must be a whole number of samples per block >= 1 (got {factor!r})", "factor")
    t = finite_vector("t", t)
    if t.size == 0:
        reject("t must hold at least one sample", "t")
    starts = np.arange(0, t.size, int(factor))
    counts = np.diff(np.append(starts, t.size))

    def means(values: np.ndarray) -> np.ndarray:
        return np.add.reduceat(values, starts) / counts

    out = [means(t)]
    for i, signal in enumerate(signals):
        if np.ndim(signal) == 0:
            out.append(signal)
            continue
        out.append(means(finite_vector(f"signals[{i}]", signal, t.size)))
    return tuple(out)
