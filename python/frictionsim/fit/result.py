"""The outcome of an identification: the fitted law, its parameters with standard errors, correlations and
identifiability, the fit quality, and the record beside the model for plotting or re-running.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .parameters import _LawDef, _symbol_unit
from .quality import _finite_or_failed, _fit_quality, _non_finite
from .solver import _Fit

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
            symbol, unit = _symbol_unit(self.law_name, name)
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
            "",
            f"  {'parameter':<28} {'value':>12} {'std. error':>11} {'rel.':>9}  identifiable",
        ]
        rel = self.relative_stderr
        for name, value in self.params.items():
            symbol, unit = _symbol_unit(self.law_name, name)
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


def _result(fit: _Fit, lawdef: _LawDef, *, method: str, experiment: str, signal_name: str, t: np.ndarray,
            measured: np.ndarray, rig: Any, initial_state: Optional[List[float]],
            started: float) -> IdentificationResult:
    """Package the core's fit with the law built at the solution and the fit quality (rms, R^2)."""
    law_params = {k: fit.params[k] for k in lawdef.physical_names}
    law = None if _non_finite({"params": law_params}) else lawdef.build(law_params)
    rms_residual, r_squared = _fit_quality(measured, fit.residual)
    success, message = _finite_or_failed(fit.success, fit.message, {
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
        condition_number=fit.condition_number, elapsed=time.perf_counter() - started)
