"""The objective of output-error least squares: weighted residuals model - measured, one simulation each,
and their finite-difference Jacobian in the search variables.
"""

from __future__ import annotations

import math
import threading
from typing import Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from ..errors import InvalidParameterError, SimulationError
from .search_space import SearchSpace


class Evaluator:
    """Residual of one parameter vector = one simulation; counts runs and failures (thread-safe)."""

    def __init__(self, model: Callable[[Dict[str, float]], np.ndarray], measured: np.ndarray,
                 weights: Optional[np.ndarray], spec: SearchSpace) -> None:
        self.model = model
        self.measured = measured
        self.weights = weights
        self.spec = spec
        scale = float(np.max(np.abs(measured))) + float(np.std(measured)) + 1.0
        # a failed run: large but finite residual at every sample, so the searches step away instead of stopping
        self.penalty = 10.0 * scale
        self.n_evaluations = 0
        self.n_failed = 0
        self.last_error = ""
        self._lock = threading.Lock()
        self._last: Optional[Tuple[bytes, np.ndarray]] = None
        # the best point seen, for progress reports and a search stopped early (no extra simulation needed)
        self.best_rss = math.inf
        self.best_x: Optional[np.ndarray] = None

    def signal(self, q: Dict[str, float]) -> Optional[np.ndarray]:
        """The simulated signal at ``q``, or None if the run failed."""
        with self._lock:
            self.n_evaluations += 1
        try:
            out = np.asarray(self.model(q), dtype=float)
            if out.shape != self.measured.shape or not np.all(np.isfinite(out)):
                raise SimulationError(f"model returned {out.shape} values, not finite {self.measured.shape}",
                                      math.nan)
            return out
        except (SimulationError, InvalidParameterError, IndexError, RuntimeError) as error:
            with self._lock:
                self.n_failed += 1
                self.last_error = f"{type(error).__name__}: {error}"
            return None

    def residual(self, x: Sequence[float]) -> np.ndarray:
        key = np.asarray(x, dtype=float).tobytes()
        cached = self._last
        if cached is not None and cached[0] == key:  # least_squares asks for fun(x) then jac(x)
            return cached[1].copy()
        out = self.signal(self.spec.q(x))
        r = np.full_like(self.measured, self.penalty) if out is None else out - self.measured
        r = r if self.weights is None else r * self.weights
        self._last = (key, r)
        if out is not None:
            rss = float(r @ r)
            with self._lock:
                if rss < self.best_rss:
                    self.best_rss, self.best_x = rss, np.asarray(x, dtype=float).copy()
        return r.copy()

    def jacobian(self, x: Sequence[float], step: float, central: bool = False) -> np.ndarray:
        """Finite-difference Jacobian with an absolute step in the search variables (log space: relative
        change of the parameter); steps away from a bound. Forward differences unless ``central``."""
        x = np.asarray(x, dtype=float)
        lower, upper = self.spec.x_bounds()
        r0 = self.residual(x)
        jac = np.empty((r0.size, x.size))
        for i in range(x.size):
            up, down = x.copy(), x.copy()
            up[i] += step
            down[i] -= step
            fits_up, fits_down = up[i] <= upper[i], down[i] >= lower[i]
            if central and fits_up and fits_down:
                jac[:, i] = (self.residual(up) - self.residual(down)) / (2.0 * step)
            elif fits_up:
                jac[:, i] = (self.residual(up) - r0) / step
            else:
                jac[:, i] = (r0 - self.residual(down)) / step
        return jac

    def cost(self, x: Sequence[float]) -> float:
        r = self.residual(x)
        return 0.5 * float(r @ r)
