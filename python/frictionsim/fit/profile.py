"""Profile-likelihood confidence intervals of an identification (IdentificationResult.conf_interval).

For one search variable x_i held at a trial value, the others are re-optimised (least squares from the previous
profile point) to give the profile residual sum of squares RSS_p(x_i). With Gaussian errors of unknown variance,
estimated as s^2 = RSS_min / (m - n) (the same s^2 as the standard errors), the statistic is

    D(x_i) = (RSS_p(x_i) - RSS_min) / s^2 = tau(x_i)^2,

the square of Bates & Watts' profile t (1988, sec 6.1, eq 6.4). tau follows Student's t with m - n degrees of
freedom (not the normal: s^2 is estimated), so the interval at ``level`` is {x_i : D(x_i) <= F_{1, m-n}(level)}
with F_{1, m-n}(level) = t_{m-n}((1 + level) / 2)^2 (lmfit's conf_interval makes the same F test). For a model
linear in x_i it equals the closed-form least-squares interval x_i +- t_{m-n} sqrt(Cov_ii) exactly, since then D is
the quadratic (x_i - x_i*)^2 / Cov_ii; for a nonlinear one it follows the curved likelihood (asymmetric, and
invariant under the log transform of a positive parameter). With m = 8 samples and n = 2 parameters the normal
quantile would make the "95 %" interval 1 / 1.248 of this one (coverage about 90 %).

Each side: steps out from the solution (first by the Wald half-width, then growing) until D passes the threshold,
then regula falsi on sqrt(D) - sqrt(threshold). A side that reaches its search bound first ends there (the data do
not bound the parameter at that level within the search range); ``closed`` is then False.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional, Tuple

import numpy as np
from scipy import optimize, stats

from .residuals import Evaluator
from .search_space import SearchSpace

logger = logging.getLogger("frictionsim")

_MAX_STEPS = 30  # outward steps per side before giving up on a finite end
_SUBFIT_TOL = 1e-8
_ROOT_TOL = 1e-3  # |sqrt(D) - sqrt(threshold)| at an end
_MAX_ROOT_STEPS = 30


@dataclass
class FitProblem:
    """What a result keeps of its fit to profile it and to evaluate the law on new inputs."""

    evaluator: Evaluator
    spec: SearchSpace
    x: np.ndarray
    x_stderr: np.ndarray
    rss: float
    n_used: int
    opts: Any
    forward: Optional[Callable[..., np.ndarray]] = None


class _Profile:
    """RSS_p(x_i): the others re-optimised with x_i held; each solution starts the next (profiles are smooth)."""

    def __init__(self, problem: FitProblem, i: int) -> None:
        self.p = problem
        self.i = i
        self.free = np.array([j for j in range(problem.x.size) if j != i], dtype=int)
        self.lower, self.upper = problem.spec.x_bounds()
        self.start = problem.x.copy()
        self.runs = 0

    def _full(self, z: np.ndarray, xi: float) -> np.ndarray:
        x = self.start.copy()
        x[self.free] = z
        x[self.i] = xi
        return x

    def rss(self, xi: float) -> float:
        evaluator, opts = self.p.evaluator, self.p.opts
        self.runs += 1
        if self.free.size == 0:
            r = evaluator.residual(self._full(np.zeros(0), xi))
            return float(r @ r)

        def residual(z: np.ndarray) -> np.ndarray:
            return evaluator.residual(self._full(z, xi))

        def jacobian(z: np.ndarray) -> np.ndarray:  # forward differences in the free variables, away from a bound
            x = self._full(z, xi)
            r0 = evaluator.residual(x)
            jac = np.empty((r0.size, z.size))
            for k, j in enumerate(self.free):
                h = opts.diff_step if x[j] + opts.diff_step <= self.upper[j] else -opts.diff_step
                bumped = x.copy()
                bumped[j] += h
                jac[:, k] = (evaluator.residual(bumped) - r0) / h
            return jac

        lo, hi = self.lower[self.free], self.upper[self.free]
        z0 = np.clip(self.start[self.free], lo, hi)
        # tolerances no tighter than _SUBFIT_TOL: the simulated RSS is only smooth to ~1e-5 relative (the
        # integrator's step sequence moves with the parameters), and iterating below that is chasing its noise
        fit = optimize.least_squares(residual, z0, jac=jacobian, bounds=(lo, hi), method="trf", x_scale=1.0,
                                     loss=opts.loss, ftol=max(opts.ftol, _SUBFIT_TOL),
                                     xtol=max(opts.xtol, _SUBFIT_TOL), gtol=max(opts.gtol, _SUBFIT_TOL),
                                     max_nfev=opts.max_nfev)
        self.start = self._full(fit.x, xi)
        r = evaluator.residual(self.start)
        return float(r @ r)


def _side(profile: _Profile, direction: float, threshold: float, s2: float) -> Tuple[float, bool]:
    """-> (end of the interval on one side in the search variable, closed): where D crosses the threshold."""
    p, i = profile.p, profile.i
    x_hat = float(p.x[i])
    bound = profile.upper[i] if direction > 0 else profile.lower[i]
    se = float(p.x_stderr[i])
    step = math.sqrt(threshold) * se if math.isfinite(se) and se > 0 else 0.1
    profile.start = p.x.copy()

    def statistic(xi: float) -> float:
        return (profile.rss(xi) - p.rss) / s2

    inner, inner_d = x_hat, 0.0
    for _ in range(_MAX_STEPS):
        trial = x_hat + direction * step
        at_bound = (trial - bound) * direction >= 0.0
        if at_bound:
            trial = float(bound)
        d = statistic(trial)
        if d >= threshold:
            return _end(statistic, threshold, inner, inner_d, trial, d), True
        if at_bound:
            return float(bound), False
        inner, inner_d = trial, d
        # next step: where a quadratic D through the solution and this point reaches the threshold, at least
        # 1.5 and at most 4 times further (a flat profile grows the step geometrically)
        growth = math.sqrt(threshold / d) * 1.2 if d > 0 else 4.0
        step *= min(max(growth, 1.5), 4.0)
    return (math.inf if direction > 0 else -math.inf), False


def _end(statistic: Callable[[float], float], threshold: float, inner: float, inner_d: float, outer: float,
         outer_d: float) -> float:
    """Where D = threshold between ``inner`` (D below) and ``outer`` (D above): regula falsi with the Illinois
    modification on the signed root g = sqrt(D) - sqrt(threshold), nearly linear in x_i (exactly so for a linear
    model: the first step lands on the end; Bates & Watts 1988, sec 6.1, the profile t). Stops when |g| <
    _ROOT_TOL (the end within ~0.05 % of the half-width) or the bracket is 1e-6 of its first width: the simulated
    D is only smooth to ~0.01, so the values at the ends are kept, never re-evaluated."""
    root = math.sqrt(threshold)
    a, ga = inner, math.sqrt(max(inner_d, 0.0)) - root
    b, gb = outer, math.sqrt(max(outer_d, 0.0)) - root
    if abs(gb) < _ROOT_TOL:
        return float(b)
    width = abs(b - a)
    side = 0
    x = b
    for _ in range(_MAX_ROOT_STEPS):
        x = b - gb * (b - a) / (gb - ga)
        gx = math.sqrt(max(statistic(x), 0.0)) - root
        if abs(gx) < _ROOT_TOL or abs(b - a) < 1e-6 * width:
            break
        if (gx < 0.0) == (ga < 0.0):  # x replaces the inner end
            a, ga = x, gx
            if side == -1:
                gb *= 0.5
            side = -1
        else:
            b, gb = x, gx
            if side == 1:
                ga *= 0.5
            side = 1
    return float(x)


def _dof(problem: FitProblem) -> int:
    """m - n: the residual degrees of freedom of s^2 (at least 1, as in the standard errors)."""
    return max(problem.n_used - problem.x.size, 1)


def _threshold(problem: FitProblem, level: float) -> float:
    """F_{1, m-n}(level) = t_{m-n}((1 + level) / 2)^2: the bound on D = tau^2 (Bates & Watts 1988, eq 6.4)."""
    return float(stats.f.ppf(level, 1, _dof(problem)))


def t_quantile(problem: FitProblem, level: float) -> float:
    """t_{m-n}((1 + level) / 2): the half-width of the Wald interval in standard errors."""
    return float(stats.t.ppf(0.5 + 0.5 * level, _dof(problem)))


def profile_interval(problem: FitProblem, i: int, level: float) -> Dict[str, Any]:
    """The profile-likelihood interval of search variable ``i`` at ``level``, in the reported unit."""
    var = problem.spec.variables[i]
    s2 = problem.rss / _dof(problem)
    threshold = _threshold(problem, level)
    profile = _Profile(problem, i)
    if not (math.isfinite(s2) and s2 > 0.0):  # an exact fit: every move is infinitely unlikely
        value = var.q(float(problem.x[i]))
        return dict(lower=value, upper=value, closed=False, runs=0)
    lo, lo_closed = _side(profile, -1.0, threshold, s2)
    hi, hi_closed = _side(profile, +1.0, threshold, s2)
    logger.debug("profile of %s at level %g: [%s, %s] in the search variable, %d sub-fits", var.name, level, lo, hi,
                 profile.runs)
    return dict(lower=_q_extended(var, lo), upper=_q_extended(var, hi), closed=lo_closed and hi_closed,
                runs=profile.runs)


def _q_extended(var: Any, x: float) -> float:
    """The reported value of search value ``x``, including an unbounded end (+-inf)."""
    if math.isinf(x):
        if var.log:
            return var.upper if x > 0 else var.lower
        return min(max(math.copysign(math.inf, x * var.scale), var.lower), var.upper)
    return var.q(x)
