"""Progress of the long searches (coordinate scan, differential evolution, least squares, profile likelihood):
``verbose=`` and ``callback=`` on every identify_* call, through ``logging.getLogger("frictionsim")``.

Every stage logs what it did at DEBUG level; ``verbose=True`` raises the per-iteration messages to INFO and, for
the duration of the call, makes them visible: the logger's level is lowered to INFO if it is above, and, when the
application configured no logging handler at all, a temporary one writes to stderr. The library never prints.

``callback(progress)`` is called once per differential-evolution generation and once per least-squares iteration
(each Jacobian), with a :class:`FitProgress`; a true return value (``True``, ``numpy.True_``, a non-zero number:
anything ``bool()`` calls true) stops the search at the best point found so far, and the result's message says so;
``None`` (a callback that returns nothing) and false values let it go on. This is the rule of
``scipy.optimize.differential_evolution``'s callback, which tests ``bool(callback(...))``.
"""

from __future__ import annotations

import contextlib
import logging
import sys
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Iterator, Optional

import numpy as np

logger = logging.getLogger("frictionsim")

__all__ = ["FitProgress"]


@dataclass(frozen=True)
class FitProgress:
    """One report of a running search, passed to ``callback=``.

    Attributes
    ----------
    stage : str
        "differential_evolution", "least_squares" or "polish" (the least-squares refinement after a global search).
    iteration : int
        Generation (differential evolution) or iteration (least squares, one per Jacobian), from 1.
    rss : float
        Smallest weighted residual sum of squares sum((w (model - measured))^2) found so far [N^2].
    params : dict
        The reported parameters at that point (law keywords, physical units).
    n_evaluations : int
        Simulations run so far in this fit.
    convergence : float or None
        Differential evolution's convergence measure (it stops when it reaches 1); None for least squares.
    """

    stage: str
    iteration: int
    rss: float
    params: Dict[str, float] = field(default_factory=dict)
    n_evaluations: int = 0
    convergence: Optional[float] = None


class StopSearch(Exception):
    """Raised inside a least-squares iteration when the callback asks to stop."""


class Reporter:
    """Logs each iteration of a search and calls the user's callback; ``stopped`` once the callback returned True."""

    def __init__(self, verbose: int, callback: Optional[Callable[[FitProgress], Any]],
                 params_of: Callable[[np.ndarray], Dict[str, float]]) -> None:
        self.level = logging.INFO if verbose else logging.DEBUG
        self.callback = callback
        self.params_of = params_of
        self.stopped = False
        self.counts: Dict[str, int] = {}

    def __call__(self, stage: str, x: np.ndarray, rss: float, n_evaluations: int,
                 convergence: Optional[float] = None) -> bool:
        """Report one iteration of ``stage`` at ``x``; -> True if the search should stop."""
        iteration = self.counts[stage] = self.counts.get(stage, 0) + 1
        wants_log = logger.isEnabledFor(self.level)
        if not (wants_log or self.callback):
            return False
        params = self.params_of(x)
        if wants_log:
            tail = "" if convergence is None else f", convergence {convergence:.3g}"
            values = ", ".join(f"{k}={v:.6g}" for k, v in params.items())
            logger.log(self.level, "%s %d: rss %.6g after %d simulations%s; %s", stage, iteration, rss,
                       n_evaluations, tail, values)
        if self.callback is not None and _wants_stop(self.callback(FitProgress(stage, iteration, float(rss), params,
                                                                               int(n_evaluations), convergence))):
            self.stopped = True
            logger.log(self.level, "%s: stopped by the callback at iteration %d", stage, iteration)
        return self.stopped


def _wants_stop(answer: Any) -> bool:
    """The callback's answer as a stop request: None -> go on, else its truth value (``np.True_`` stops like True)."""
    return answer is not None and bool(answer)


@contextlib.contextmanager
def verbose_logging(verbose: int) -> Iterator[None]:
    """While a verbose fit runs: the logger lets INFO through, and a stderr handler shows it when no handler is
    configured anywhere (an application that configured logging keeps its own handlers and format)."""
    if not verbose:
        yield
        return
    old_level = logger.level
    handler = None
    if logger.getEffectiveLevel() > logging.INFO:
        logger.setLevel(logging.INFO)
    if not logger.hasHandlers():
        handler = logging.StreamHandler(sys.stderr)
        handler.setFormatter(logging.Formatter("frictionsim.fit: %(message)s"))
        logger.addHandler(handler)
    try:
        yield
    finally:
        logger.setLevel(old_level)
        if handler is not None:
            logger.removeHandler(handler)
