"""The fitting core shared by every identification: search the parameters, then quantify their uncertainty.

* local search: :func:`scipy.optimize.least_squares` (trust-region reflective, box bounds), started from a
  coarse coordinate scan of the parameters that have no initial guess;
* global search (what paper 000's genetic / particle-swarm methods are for):
  :func:`scipy.optimize.differential_evolution` over the same bounds, deterministic for a given ``seed``,
  polished by least_squares;
* the uncertainty at the solution: :mod:`frictionsim.fit.uncertainty`;
* progress: ``verbose=`` / ``callback=`` (:mod:`frictionsim.fit.progress`), logged to ``logging.getLogger(
  "frictionsim")``.
"""

from __future__ import annotations

import inspect
import logging
import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional, Sequence, Tuple

import numpy as np
from scipy import optimize

from ..errors import InvalidParameterError
from ..validation import reject
from .parameters import law_def, LawDef
from .progress import Reporter, StopSearch, verbose_logging
from .residuals import Evaluator
from .search_space import SearchSpace
from .uncertainty import parameter_uncertainty, residual_variance

#: Search methods accepted by ``method=``.
METHODS = ("least_squares", "differential_evolution")

# SciPy renamed differential_evolution's ``seed`` to ``rng``
_DE_SEED_KEYWORD = "rng" if "rng" in inspect.signature(optimize.differential_evolution).parameters else "seed"

logger = logging.getLogger("frictionsim")


def _check_method(method: str) -> str:
    if method not in METHODS:
        reject(f"method must be one of {', '.join(METHODS)} (got {method!r})", "method")
    return method


@dataclass
class SearchOptions:
    """Solver knobs shared by every identify_* function (see the docstrings)."""

    seed: Optional[int] = 0
    polish: bool = True
    maxiter: int = 100
    popsize: int = 15
    tol: float = 0.01
    workers: int = 1
    max_nfev: Optional[int] = None
    diff_step: float = 1e-3
    ftol: float = 1e-10
    xtol: float = 1e-10
    gtol: float = 1e-10
    loss: str = "linear"
    max_relative_stderr: float = 0.3
    rcond: float = 1e-4
    jacobian_step: float = 1e-2
    scan: bool = True
    verbose: int = 0
    callback: Optional[Callable[..., Any]] = None


def _options(kwargs: Dict[str, Any]) -> SearchOptions:
    """The ``**solver_options`` of an identify_* call, checked (a misspelt one is a TypeError, as for any
    keyword)."""
    known = SearchOptions.__dataclass_fields__
    unknown = [k for k in kwargs if k not in known]
    if unknown:
        raise TypeError(f"unexpected keyword argument(s): {', '.join(unknown)}; solver options are "
                        f"{', '.join(known)}")
    opts = SearchOptions(**kwargs)
    for name in ("maxiter", "popsize", "workers"):
        value = getattr(opts, name)
        if isinstance(value, bool) or not float(value).is_integer() or value < 1:
            reject(f"{name} must be a positive whole number (got {value!r})", name)
    if not (isinstance(opts.verbose, (bool, int)) and opts.verbose >= 0):
        reject(f"verbose must be True, False or a non-negative whole number (got {opts.verbose!r})", "verbose")
    if opts.callback is not None and not callable(opts.callback):
        reject(f"callback must be callable, callback(progress) -> bool (got {opts.callback!r})", "callback")
    for name in ("tol", "diff_step", "max_relative_stderr", "rcond", "jacobian_step"):
        value = getattr(opts, name)
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            reject(f"{name} must be positive and finite (got {value!r})", name)
    return opts


def fit_setup(law: Any, method: str, solver_options: Dict[str, Any]) -> Tuple[LawDef, str, SearchOptions]:
    """The law, the search method and its options of an identify_* call, checked in that order."""
    return law_def(law), _check_method(method), _options(solver_options)


# ------------------------------------------------------------------------------------------------ the work
#: The most work a fit starts [sample-simulations]: the record's samples x the simulations its search needs at the
#: least (:func:`minimum_simulations`), each of which runs through every sample. Measured on a loaded 2-core
#: machine: 4e5-8e5 sample-simulations per second (a Dahl fit of 1e5 samples: 35 simulations, 14 at the least,
#: 5 s; a LuGre fit of 1e5 samples: 380 simulations, 61 at the least, 46 s), so the limit is 6-12 s of the least
#: work, and a converging search runs 2.5-6 times as many simulations as the least: a minute at most.
MAX_FIT_WORK = 5_000_000
#: What MAX_FIT_WORK costs: printed with a refusal.
WORK_RATE_NOTE = ("about 10 s of the least work at 5e5 sample-simulations per second; a converging search runs "
                  "2.5-6 times as many")
#: Coordinate scan: a grid is left once this many points past its best cost 25 % more than it.
SCAN_PATIENCE = 4


def minimum_simulations(spec: SearchSpace, method: str, opts: SearchOptions, scan_names: Sequence[str]) -> int:
    """The simulations a fit runs at the least, before it can stop: least squares, the coordinate scan (its
    start and each scanned grid up to SCAN_PATIENCE points past its best, two rounds over several variables) and
    one Jacobian (n + 1 runs); differential evolution, its first generation (popsize x n); both, the run at the
    solution and the covariance's central Jacobian (2 n + 1). A converging search runs several times as many."""
    n = len(spec.variables)
    covariance = 2 * n + 1
    if method == "differential_evolution":
        return int(opts.popsize) * max(n, 1) + covariance
    scan = 0
    if opts.scan and scan_names:
        rounds = 2 if len(scan_names) > 1 else 1
        grids = [len(spec.variables[spec.names.index(name)].grid()) for name in scan_names]
        scan = 1 + rounds * sum(min(size, SCAN_PATIENCE + 1) for size in grids)
    return scan + n + 1 + covariance


class FitWorkError(InvalidParameterError):
    """A fit refused for its work (:func:`check_work`); ``factor`` is the decimation that brings it within."""

    def __init__(self, message: str, parameter: str, factor: int = 0) -> None:
        super().__init__(message, parameter)
        self.factor = int(factor)

    def __reduce__(self):
        return (type(self), (str(self), self.parameter, self.factor))


def check_work(samples: int, spec: SearchSpace, method: str, opts: SearchOptions,
               scan_names: Sequence[str] = ()) -> None:
    """Refuse a fit whose work (samples x :func:`minimum_simulations`) is beyond :data:`MAX_FIT_WORK`, before
    anything runs, naming ``t`` (the record's samples), the limit and the factor that brings it within."""
    least = minimum_simulations(spec, method, opts, scan_names)
    work = samples * least
    if work <= MAX_FIT_WORK:
        return
    factor = math.ceil(work / MAX_FIT_WORK)
    raise FitWorkError(f"t: {samples} samples x at least {least} simulations of the whole record ({method}, {len(spec.variables)} "
           f"fitted parameters) = {work:.3g} sample-simulations, beyond the fits' limit MAX_FIT_WORK = "
           f"{MAX_FIT_WORK:.3g} ({WORK_RATE_NOTE}); shorten the record by a factor of {factor} or more first: "
           f"frictionsim.fit.decimate(t, relative_velocity, friction_force, factor={factor}) averages blocks of "
           f"{factor} samples (keep a block well below the dynamics' shortest time scale), or fit a part of the "
           f"record", "t", factor)


# ------------------------------------------------------------------------------------------------ searches
def _coordinate_scan(evaluator: Evaluator, spec: SearchSpace, names: Sequence[str], rounds: int = 1,
                     patience: int = SCAN_PATIENCE) -> SearchSpace:
    """Coarse grid over each named variable's bounds in turn (others held), to start least_squares nearby.

    Each grid is walked upwards and left once ``patience`` points past the sweep's best cost 25 % more than it
    (the far end of a stiffness grid is the expensive, stiff end)."""
    if not names:
        return spec
    q = spec.q(np.zeros(len(spec.variables)))
    best = evaluator.cost(spec.x(q))
    for _ in range(rounds):
        for name in names:
            var = spec.variables[spec.names.index(name)]
            sweep_best, worse = math.inf, 0
            for value in var.grid():
                trial = dict(q)
                trial[name] = float(value)
                c = evaluator.cost(spec.x(trial))
                if c < best:
                    best, q = c, trial
                if c < sweep_best:
                    sweep_best, worse = c, 0
                elif c > 1.25 * sweep_best:
                    worse += 1
                    if worse >= patience:
                        break
    logger.debug("coordinate scan of %s: best rss %.6g after %d simulations", ", ".join(names), 2.0 * best,
                 evaluator.n_evaluations)
    return spec.with_refs(q)


def _least_squares(evaluator: Evaluator, spec: SearchSpace, x0: np.ndarray, opts: SearchOptions,
                   report: Optional[Reporter] = None, stage: str = "least_squares") -> Tuple[np.ndarray, bool, str]:
    """-> (x, success, message). Each iteration (one Jacobian, at the accepted iterate) is reported; a callback
    that asks to stop ends the search at the best point seen."""
    lower, upper = spec.x_bounds()
    x0 = np.clip(x0, lower, upper)

    def jacobian(x: np.ndarray) -> np.ndarray:
        if report is not None:
            r = evaluator.residual(x)  # cached: least_squares evaluated it just before
            if report(stage, x, float(r @ r), evaluator.n_evaluations):
                raise StopSearch
        return evaluator.jacobian(x, opts.diff_step)

    try:
        ls = optimize.least_squares(
            evaluator.residual, x0, jac=jacobian, bounds=(lower, upper), method="trf", x_scale=1.0,
            loss=opts.loss, ftol=opts.ftol, xtol=opts.xtol, gtol=opts.gtol, max_nfev=opts.max_nfev)
    except StopSearch:
        x = evaluator.best_x if evaluator.best_x is not None else x0
        return np.clip(x, lower, upper), False, "stopped by the callback"
    logger.debug("%s: %s (%d simulations so far)", stage, ls.message, evaluator.n_evaluations)
    return ls.x, bool(ls.success), str(ls.message)


def _differential_evolution(evaluator: Evaluator, spec: SearchSpace, x0: Optional[np.ndarray], opts: SearchOptions,
                            report: Optional[Reporter] = None):
    lower, upper = spec.x_bounds()
    if not (np.all(np.isfinite(lower)) and np.all(np.isfinite(upper))):
        bad = spec.names[int(np.flatnonzero(~(np.isfinite(lower) & np.isfinite(upper)))[0])]
        reject(f"differential_evolution needs finite bounds; bounds[{bad!r}] is not", f"bounds[{bad!r}]")
    kwargs: Dict[str, Any] = dict(maxiter=int(opts.maxiter), popsize=int(opts.popsize), tol=float(opts.tol),
                                  polish=False, init="latinhypercube")
    kwargs[_DE_SEED_KEYWORD] = opts.seed
    if report is not None:
        def generation(xk: np.ndarray, convergence: float = 0.0) -> bool:  # signature of every SciPy >= 1.9
            return report("differential_evolution", xk, evaluator.best_rss, evaluator.n_evaluations,
                          float(convergence))

        kwargs["callback"] = generation
    if x0 is not None:
        kwargs["x0"] = np.clip(x0, lower, upper)
    pool = None
    if opts.workers > 1:  # the engine releases the GIL: threads run simulations in parallel
        pool = ThreadPoolExecutor(max_workers=int(opts.workers))
        kwargs.update(workers=pool.map, updating="deferred")
    try:
        return optimize.differential_evolution(evaluator.cost, list(zip(lower, upper)), **kwargs)
    finally:
        if pool is not None:
            pool.shutdown()


# ------------------------------------------------------------------------------------------------ the core
@dataclass
class FitSolution:
    """What the core returns: the solution and its uncertainty, in fit variables and reported parameters."""

    spec: SearchSpace
    x: np.ndarray
    q: Dict[str, float]
    params: Dict[str, float]
    fitted: Tuple[str, ...]  # reported parameters that depend on the fit variables
    stderr: Dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    identifiable: Dict[str, bool]
    reasons: Dict[str, str]
    singular_values: np.ndarray
    condition_number: float
    signal: np.ndarray
    residual: np.ndarray  # model - measured, unweighted
    success: bool
    message: str
    n_evaluations: int
    n_failed: int
    x_stderr: np.ndarray  # standard errors in the search variables (inf: not determined)
    rss: float  # weighted residual sum of squares at the solution
    n_used: int  # samples with a positive weight: the m of s^2 = rss / (m - n)
    evaluator: Optional[Evaluator] = None  # the objective, kept for profile likelihood
    opts: Optional[SearchOptions] = None


def fit_model(model: Callable[[Dict[str, float]], np.ndarray], measured: np.ndarray, weights: Optional[np.ndarray],
              spec: SearchSpace, *, method: str, opts: SearchOptions, scan_names: Sequence[str] = (),
              x0_given: bool = False) -> FitSolution:
    """Fit ``model`` to ``measured``: the core of the kinematic and the rig-level identification.

    ``model(q)`` returns the simulated signal at the measured samples for fit variables ``q`` (raising
    SimulationError on a failed run); ``spec`` gives the searched variables, bounds, fixed values and the map to
    reported parameters. A fit whose work is beyond :data:`MAX_FIT_WORK` is refused before it starts
    (:func:`check_work`); within it, each simulation stops at Ctrl-C (KeyboardInterrupt) and ``verbose=`` /
    ``callback=`` report every iteration.
    """
    check_work(measured.size, spec, method, opts, scan_names if opts.scan else ())
    with verbose_logging(int(opts.verbose)):
        return _fit_logged(model, measured, weights, spec, method=method, opts=opts, scan_names=scan_names,
                           x0_given=x0_given)


def _fit_logged(model: Callable[[Dict[str, float]], np.ndarray], measured: np.ndarray,
                weights: Optional[np.ndarray], spec: SearchSpace, *, method: str, opts: SearchOptions,
                scan_names: Sequence[str], x0_given: bool) -> FitSolution:
    evaluator = Evaluator(model, measured, weights, spec)
    # the reporter reads evaluator.spec: the scan re-centres it
    report = Reporter(int(opts.verbose), opts.callback, lambda x: evaluator.spec.physical(evaluator.spec.q(x)))
    messages = []
    success = True
    logger.debug("fitting %s by %s to %d samples", ", ".join(spec.names), method, measured.size)
    if method == "least_squares":
        if opts.scan and scan_names:
            spec = _coordinate_scan(evaluator, spec, scan_names, rounds=2 if len(scan_names) > 1 else 1)
            evaluator.spec = spec
        x, success, message = _least_squares(evaluator, spec, np.zeros(len(spec.variables)), opts, report)
        messages.append(f"least_squares: {message.rstrip('.')}")
    else:
        de = _differential_evolution(evaluator, spec, np.zeros(len(spec.variables)) if x0_given else None, opts,
                                     report)
        x = np.asarray(de.x, dtype=float)
        de_message = "stopped by the callback" if report.stopped else str(de.message).rstrip('.')
        messages.append(f"differential_evolution ({de.nit} generations): {de_message}")
        # a search the callback stopped has not converged, whatever differential_evolution reports
        success = bool(de.success) and not report.stopped
        if opts.polish and not report.stopped:
            x_ls, ls_success, ls_message = _least_squares(evaluator, spec, x, opts, report, stage="polish")
            if evaluator.cost(x_ls) <= evaluator.cost(x):
                x = x_ls
            # the polish refines DE's answer; it cannot make up for a search that did not converge
            success = success and ls_success
            messages.append(f"least_squares polish: {ls_message.rstrip('.')}")

    q = spec.q(x)
    signal = evaluator.signal(q)
    ran = signal is not None
    if not ran:
        success = False
        messages.append(f"the simulation at the solution failed ({evaluator.last_error})")
        signal = np.full_like(measured, np.nan)
    residual = signal - measured
    n, m = len(spec.variables), int(np.count_nonzero(weights)) if weights is not None else measured.size
    s2 = residual_variance(residual if weights is None else residual * weights, m, n)

    jac = evaluator.jacobian(x, opts.jacobian_step, central=True) if ran and n else np.zeros((m, n))
    uncertainty = parameter_uncertainty(spec, x, jac, s2, rcond=opts.rcond,
                                        max_relative_stderr=opts.max_relative_stderr)
    weighted = residual if weights is None else residual * weights
    logger.debug("fit done: rss %.6g, %d simulations (%d failed)", float(weighted @ weighted),
                 evaluator.n_evaluations, evaluator.n_failed)
    return FitSolution(spec=spec, x=x, q=q, signal=signal, residual=residual, success=success,
                       message="; ".join(messages), n_evaluations=evaluator.n_evaluations, n_failed=evaluator.n_failed,
                       rss=float(weighted @ weighted), n_used=m, evaluator=evaluator, opts=opts, **uncertainty)
