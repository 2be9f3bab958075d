"""The outcome of an identification: the fitted law, its parameters with standard errors, correlations and
identifiability, the fit quality and information criteria (AIC, BIC), profile-likelihood confidence intervals, and
the record beside the model for plotting or re-running (``eval`` on new inputs, ``plot``).
"""

from __future__ import annotations

import math
import numbers
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ..validation import non_finite, reject
from .parameters import law_def, LawDef, symbol_unit
from .profile import FitProblem, profile_interval, t_quantile
from .quality import finite_or_failed, fit_quality
from .solver import FitSolution

__all__ = ["IdentificationResult"]


@dataclass
class IdentificationResult:
    """Fitted friction law with uncertainty and identifiability.

    Attributes
    ----------
    law_name : str
        The law's class name: "Dahl", "LuGre", "ElastoPlastic", "Stribeck", ... (see ``fs.fit.LAW_PARAMETERS``).
    law : fs.Dahl | fs.LuGre | fs.ElastoPlastic | fs.Stribeck | ... or None
        Ready to use, e.g. ``fs.AxialVibrationRig(friction=result.law)``; None if a parameter is not finite.
    params : dict
        Fitted and fixed parameters under the law constructor's keywords (mu [-], tangential_stiffness [N/m],
        ...), plus ``initial_force`` [N] when the initial state was fitted.
    stderr : dict
        Standard errors in the same units (0 for fixed, inf where the data do not determine the parameter).
    fitted : tuple of str
        The parameters that were estimated (order of ``covariance`` and ``correlation``).
    covariance, correlation : ndarray
        Over ``fitted``, physical units; covariance = s^2 (J^T J)^-1 mapped by the chain rule.
    identifiable : dict of bool, reasons : dict of str
        Per parameter; the reason says why a parameter is not identifiable (at a bound, near-null direction of
        the scaled Jacobian, relative standard error above ``max_relative_stderr``).
    rms_residual : float
        sqrt(mean((model - measured)^2)), in the signal's unit (N).
    r_squared : float
        1 - SS_res / SS_tot.
    n_evaluations, n_failed : int
        Simulations run (scan, search, Jacobian) and how many failed.
    success : bool, message : str
        Never true with a NaN or inf in ``params``, ``r_squared``, ``rms_residual``, ``model`` or the standard
        error of an identifiable parameter; the message then names them.
    method : str
    experiment : str
        "kinematic rig" or "axial vibration rig".
    signal_name : str
        The fitted signal: "friction_force" or "drive_force".
    t, measured, model : ndarray
        The record and the simulated signal at the solution.
    rig :
        The rig at the solution (``fs.simulate(result.rig, result.t[-1], t_start=result.t[0])`` re-runs it).
    initial_state : list or None
        Law state used at t[0].
    singular_values : ndarray, condition_number : float
        Of the Jacobian in the search variables (log space for positive parameters).
    elapsed : float
        Wall time [s].
    weights : ndarray or None
        The residual weights (1/sigma_i) of the fit at ``t``; None for equal weights.
    n_parameters : int
        Parameters the search estimated (its variables: mu_static is searched as mu_static_excess, and
        ``initial_force`` counts when fitted); the k of :attr:`aic` and :attr:`bic` is this plus one.

    Information criteria (:attr:`log_likelihood`, :attr:`aic`, :attr:`aicc`, :attr:`bic`) take the residuals as
    independent Gaussian errors of standard deviation sigma / w_i with sigma estimated by maximum likelihood,
    sigma^2 = RSS / n (RSS = sum (w_i r_i)^2 over the n samples of positive weight), so

        -2 ln L = n ln(2 pi RSS / n) + n - 2 sum ln w_i,
        AIC = -2 ln L + 2 k,   BIC = -2 ln L + k ln n,   k = n_parameters + 1 (the noise variance counts),

    i.e. n ln(RSS / n) + 2 k plus the constant n (ln 2 pi + 1) - 2 sum ln w_i, kept so that the values are the
    full Gaussian log-likelihood (Burnham & Anderson 2002, sec 2.2). The constant is the same for every law fitted
    to one record with the same weights: differences, and so :func:`frictionsim.fit.compare_laws`' ranking,
    delta-AIC and Akaike weights, do not depend on it.
    """

    law_name: str
    law: Any
    params: Dict[str, float]
    stderr: Dict[str, float]
    fitted: Tuple[str, ...]
    covariance: np.ndarray
    correlation: np.ndarray
    identifiable: Dict[str, bool]
    reasons: Dict[str, str]
    rms_residual: float
    r_squared: float
    n_samples: int
    n_evaluations: int
    n_failed: int
    success: bool
    message: str
    method: str
    experiment: str
    signal_name: str
    t: np.ndarray = field(repr=False)
    measured: np.ndarray = field(repr=False)
    model: np.ndarray = field(repr=False)
    rig: Any = field(repr=False, default=None)
    initial_state: Optional[List[float]] = None
    bounds: Dict[str, Tuple[float, float]] = field(default_factory=dict, repr=False)
    singular_values: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    condition_number: float = math.nan
    elapsed: float = 0.0
    weights: Optional[np.ndarray] = field(default=None, repr=False)
    n_parameters: Optional[int] = None
    _problem: Optional[FitProblem] = field(default=None, repr=False, compare=False)

    def __getstate__(self) -> Dict[str, Any]:
        # the objective (a closure over the engine's rig) does not pickle: a copied result keeps its numbers,
        # while conf_interval and eval need the original
        state = dict(self.__dict__)
        state["_problem"] = None
        return state

    # -------------------------------------------------------------------------------- information criteria
    def _used(self) -> np.ndarray:
        return np.ones(self.measured.size, bool) if self.weights is None else self.weights > 0.0

    @property
    def rss(self) -> float:
        """Weighted residual sum of squares sum((w_i (model_i - measured_i))^2) [N^2] (w = 1 unweighted)."""
        r = self.residuals if self.weights is None else self.residuals * self.weights
        r = r[self._used()]
        with np.errstate(over="ignore", invalid="ignore"):
            value = float(r @ r)
        return value if math.isfinite(value) else math.inf

    @property
    def n_used(self) -> int:
        """Samples that enter the fit: those of positive weight (all without weights)."""
        return int(np.count_nonzero(self._used()))

    @property
    def k(self) -> int:
        """Estimated parameters of the likelihood: :attr:`n_parameters` plus the noise variance."""
        return (len(self.fitted) if self.n_parameters is None else self.n_parameters) + 1

    @property
    def log_likelihood(self) -> float:
        """Maximised Gaussian log-likelihood ln L = -n/2 (ln(2 pi RSS / n) + 1) + sum ln w_i (see the class
        docstring); -inf for a failed fit (RSS infinite), +inf for an exact one (RSS = 0)."""
        n, rss = self.n_used, self.rss
        if not math.isfinite(rss):
            return -math.inf
        if rss == 0.0:
            return math.inf
        log_w = 0.0 if self.weights is None else float(np.sum(np.log(self.weights[self._used()])))
        return -0.5 * n * (math.log(2.0 * math.pi * rss / n) + 1.0) + log_w

    @property
    def aic(self) -> float:
        """Akaike information criterion -2 ln L + 2 k (k = n_parameters + 1; see the class docstring)."""
        return -2.0 * self.log_likelihood + 2.0 * self.k

    @property
    def aicc(self) -> float:
        """AIC with the small-sample correction 2 k (k + 1) / (n - k - 1) (Hurvich & Tsai 1989); inf when
        n <= k + 1."""
        n, k = self.n_used, self.k
        return self.aic + 2.0 * k * (k + 1) / (n - k - 1) if n > k + 1 else math.inf

    @property
    def bic(self) -> float:
        """Bayesian (Schwarz) information criterion -2 ln L + k ln n (see the class docstring)."""
        return -2.0 * self.log_likelihood + self.k * math.log(self.n_used)

    # -------------------------------------------------------------------------------- the fitted law at work
    def eval(self, t: Any, relative_velocity: Any = None, normal_force: Any = None, *,
             initial_state: Any = None) -> np.ndarray:
        """The fitted signal for new inputs, by the fit's own forward model (same rig, law, integrator and
        tolerances): ``eval(result.t, v, N)`` on the record's inputs reproduces ``result.model``.

        Parameters
        ----------
        t : array, s
            Output times, strictly increasing (at least 3).
        relative_velocity : array, m/s
            Kinematic rig: v_r at ``t`` (required). Axial rig: must be None (the rig makes its own motion, and
            ``t`` must start at 0 as the fitted record did).
        normal_force : float or array or (t_N, N) pair, N, optional
            Kinematic rig: as for :func:`frictionsim.fit.identify` (default: the record's). Axial rig: None.
        initial_state : list or "zero", optional
            Kinematic rig: the law state at t[0]; default the fit's (:attr:`initial_state`), "zero" for a law
            at rest.

        Returns
        -------
        ndarray
            Friction force [N] (kinematic rig) or drive force [N] (axial rig) at ``t``.

        Raises
        ------
        InvalidParameterError (a ValueError)
            Bad input, or a result without its model (unpickled, or built by hand).
        """
        if self._problem is None or self._problem.forward is None:
            reject("eval needs the fit's forward model, which a copied or unpickled IdentificationResult does "
                   "not keep: call it on the result identify_* returned", "self")
        return self._problem.forward(t, relative_velocity, normal_force, initial_state)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Measured record (grey dots) and fitted model (line) against time.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Drawn into; default a new Figure (not registered with pyplot).
        **kwargs
            Passed to ``ax.plot`` for the model line (color, lw, label, ...).

        Returns
        -------
        matplotlib.axes.Axes
        """
        from ..plots import axes_for

        ax = axes_for(ax, 7.0, 4.0)
        ax.plot(self.t, self.measured, ".", ms=2.5, color="0.6", label="measured")
        kwargs.setdefault("label", f"{self.law_name} fit (R$^2$ = {self.r_squared:.4f})")
        ax.plot(self.t, self.model, **kwargs)
        ax.set_xlabel("t [s]")
        ax.set_ylabel(f"{self.signal_name.replace('_', ' ')} [N]")
        ax.set_title(f"{self.law_name} on the {self.experiment}")
        ax.legend()
        return ax

    # -------------------------------------------------------------------------------- uncertainty
    def conf_interval(self, names: Optional[Sequence[str]] = None, level: float = 0.95):
        """Profile-likelihood confidence intervals (see :mod:`frictionsim.fit.profile`).

        Each named parameter is held along a path while the others are re-fitted; the interval is where the
        statistic (RSS_p - RSS) / s^2, s^2 = RSS / (m - n), stays below F_{1, m-n}(level) = t_{m-n}((1 + level) /
        2)^2 (the square of Bates & Watts' profile t, 1988, sec 6.1: Student's t, as s^2 is estimated from the m
        samples). It equals the closed-form least-squares interval value +- t_{m-n} stderr for a parameter the model
        is linear in, and follows the likelihood's curvature otherwise.

        Parameters
        ----------
        names : str or sequence of str, optional
            Search variables to profile (default all): the law's keywords or their symbols; mu_static is searched,
            and so profiled, as ``mu_static_excess`` = mu_static - mu; ``initial_force`` when fitted. A name given
            twice (or as keyword and symbol) is profiled once, in the order first given.
        level : float
            Confidence level in (0, 1) (any real number type, e.g. ``numpy.float32``).

        Returns
        -------
        pandas.DataFrame
            Indexed by parameter: ``value``, ``lower``, ``upper`` (physical units), ``level``, ``closed`` (False
            when a side reached the search bound before the threshold: the data do not bound the parameter there
            at this level, and that end is the bound), ``runs`` (profile points fitted), and for comparison the
            Wald interval ``wald_lower``, ``wald_upper`` = value -+ t stderr (t = t_{m-n}((1 + level) / 2), the
            standard error of the search variable mapped to the parameter by the chain rule; +-inf where the data
            do not determine it).

        Raises
        ------
        InvalidParameterError (a ValueError)
            level not in (0, 1), a name that is not a search variable, or a result without its model.
        """
        import pandas as pd

        if isinstance(level, (bool, np.bool_)) or not (isinstance(level, numbers.Real) and 0.0 < level < 1.0):
            reject(f"level must be a number in (0, 1) (got {level!r})", "level")
        level = float(level)
        problem = self._problem
        if problem is None:
            reject("conf_interval needs the fit's objective, which a copied or unpickled IdentificationResult does "
                   "not keep: call it on the result identify_* returned", "self")
        searched = problem.spec.names
        if names is None:
            chosen = list(searched)
        else:
            if isinstance(names, str):
                names = [names]
            lawdef = law_def(self.law_name)
            chosen = []
            for key in names:
                name = self._search_variable(lawdef, key, searched)
                if name not in chosen:
                    chosen.append(name)
        t = t_quantile(problem, level)
        rows = []
        for name in chosen:
            i = searched.index(name)
            var = problem.spec.variables[i]
            x_i = float(problem.x[i])
            row = dict(parameter=name, value=var.q(x_i))
            row.update(profile_interval(problem, i, level))
            se = float(problem.x_stderr[i]) * var.dq_dx(x_i)  # dq/dx: q for a log variable, its scale if linear
            row.update(level=level, wald_lower=row["value"] - t * se, wald_upper=row["value"] + t * se)
            rows.append(row)
        return pd.DataFrame(rows, columns=["parameter", "value", "lower", "upper", "level", "closed", "runs",
                                           "wald_lower", "wald_upper"]).set_index("parameter")

    @staticmethod
    def _search_variable(lawdef: LawDef, key: Any, searched: Sequence[str]) -> str:
        """The search variable ``key`` (a keyword, symbol or search-variable name) stands for, or a rejection that
        lists the search variables once."""
        if isinstance(key, str):
            if key in searched:
                return key
            for p in lawdef.params:
                if key == p.name or key in p.aliases:
                    key = p.name
                    break
            else:
                for r in lawdef.cls.parameters:
                    if r.name in lawdef.excess and key in (r.name, r.field, r.symbol):
                        key = r.name
            name = lawdef.excess[key][0] if key in lawdef.excess else key
            if name in searched:
                return name
        reject(f"names: {key!r} is not a search variable of this fit (the search variables are "
               f"{', '.join(searched)})", "names")

    @property
    def residuals(self) -> np.ndarray:
        """model - measured at every sample [N]."""
        return self.model - self.measured

    @property
    def relative_stderr(self) -> Dict[str, float]:
        """stderr / |value| (inf for a zero value)."""
        return {k: (self.stderr[k] / abs(v) if v != 0 else (0.0 if self.stderr[k] == 0 else math.inf))
                for k, v in self.params.items()}

    @property
    def all_identifiable(self) -> bool:
        return all(self.identifiable[k] for k in self.fitted)

    def correlation_frame(self):
        """The correlation matrix as a pandas DataFrame labelled by parameter."""
        import pandas as pd

        return pd.DataFrame(self.correlation, index=list(self.fitted), columns=list(self.fitted))

    def to_pandas(self):
        """One row per parameter: value, stderr, relative_stderr, symbol, unit, fitted, identifiable, reason."""
        import pandas as pd

        rel = self.relative_stderr
        rows = []
        for name, value in self.params.items():
            symbol, unit = symbol_unit(self.law_name, name)
            rows.append(dict(parameter=name, value=value, stderr=self.stderr[name], relative_stderr=rel[name],
                             symbol=symbol, unit=unit, fitted=name in self.fitted,
                             identifiable=self.identifiable[name], reason=self.reasons[name]))
        return pd.DataFrame(rows).set_index("parameter")

    def summary(self) -> str:
        """A human-readable report: fit quality, parameters with standard errors, identifiability, correlations."""
        status = "converged" if self.success else "NOT converged"
        lines = [
            f"{self.law_name} identification from the {self.experiment} ({self.signal_name}), {self.method}: "
            f"{status}",
            f"  {self.message}",
            f"  {self.n_samples} samples, {len(self.fitted)} fitted parameters, {self.n_evaluations} simulations "
            f"({self.n_failed} failed), {self.elapsed:.2f} s",
            f"  rms residual {self.rms_residual:.4g} N, R^2 = {self.r_squared:.6f}, condition number of the scaled "
            f"Jacobian {self.condition_number:.3g}",
            f"  Gaussian log-likelihood {self.log_likelihood:.6g}, AIC {self.aic:.6g}, BIC {self.bic:.6g} (k = "
            f"{self.k}: {self.k - 1} parameters and the noise variance)",
            "",
            f"  {'parameter':<28} {'value':>12} {'std. error':>11} {'rel.':>9}  identifiable",
        ]
        rel = self.relative_stderr
        for name, value in self.params.items():
            symbol, unit = symbol_unit(self.law_name, name)
            label = f"{name} [{unit}]"
            if name in self.fitted:
                se = f"{self.stderr[name]:.4g}"
                r = f"{100 * rel[name]:.3g}%" if math.isfinite(rel[name]) else "inf"
                flag = "yes" if self.identifiable[name] else "NO: " + self.reasons[name]
            else:
                se, r, flag = "fixed", "", ""
            lines.append(f"  {label:<28} {value:>12.6g} {se:>11} {r:>9}  {flag}")
        if len(self.fitted) > 1:
            lines += ["", "  correlation:"]
            width = max(len(n) for n in self.fitted) + 2
            lines.append(" " * (width + 2) + "".join(f"{n[:9]:>10}" for n in self.fitted))
            for a, name in enumerate(self.fitted):
                lines.append(f"  {name:<{width}}" + "".join(f"{c:>10.3f}" for c in self.correlation[a]))
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.summary()


def identification_result(fit: FitSolution, lawdef: LawDef, *, method: str, experiment: str, signal_name: str,
                          t: np.ndarray, measured: np.ndarray, rig: Any, initial_state: Optional[List[float]],
                          started: float, weights: Optional[np.ndarray] = None,
                          forward: Any = None) -> IdentificationResult:
    """Package the core's fit with the law built at the solution and the fit quality (rms, R^2)."""
    law_params = {k: fit.params[k] for k in lawdef.physical_names}
    law = None if non_finite({"params": law_params}) else lawdef.build(law_params)
    rms_residual, r_squared = fit_quality(measured, fit.residual)
    success, message = finite_or_failed(fit.success, fit.message, {
        "params": fit.params, "r_squared": r_squared, "rms_residual": rms_residual, "model": fit.signal,
        # inf marks a parameter the data do not determine (flagged not identifiable): that is an answer, not NaN
        "stderr": {k: se for k, se in fit.stderr.items() if fit.identifiable[k] or not math.isinf(se)}})
    return IdentificationResult(
        law_name=lawdef.name, law=law, params=dict(fit.params), stderr=fit.stderr, fitted=fit.fitted,
        covariance=fit.covariance, correlation=fit.correlation, identifiable=fit.identifiable, reasons=fit.reasons,
        rms_residual=rms_residual, r_squared=r_squared,
        n_samples=int(measured.size), n_evaluations=fit.n_evaluations, n_failed=fit.n_failed, success=success,
        message=message, method=method, experiment=experiment, signal_name=signal_name, t=t, measured=measured,
        model=fit.signal, rig=rig, initial_state=initial_state,
        bounds={v.name: (v.lower, v.upper) for v in fit.spec.variables}, singular_values=fit.singular_values,
        condition_number=fit.condition_number, elapsed=time.perf_counter() - started, weights=weights,
        n_parameters=len(fit.spec.variables),
        _problem=None if fit.evaluator is None else FitProblem(
            fit.evaluator, fit.spec, fit.x, fit.x_stderr, fit.rss, fit.n_used, fit.opts, forward))
