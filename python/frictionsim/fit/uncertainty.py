"""Uncertainty and identifiability of the fitted parameters, from the Jacobian J at the solution.

* Cov_x = s^2 (J^T J)^-1 with s^2 = SSR / (m - n) (the linearised least-squares covariance, in the search
  variables), computed through the SVD of J so numerically null directions get no variance;
* mapped to the reported parameters with the chain rule, Cov_p = G Cov_x G^T, G = d params / d x (dq/dx = q
  for log-space variables);
* each parameter is flagged not identifiable with a reason: at a bound, in a near-null direction of the
  scaled Jacobian (singular-value ratio below ``rcond``), or a relative standard error above a threshold.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, Sequence, Tuple

import numpy as np

from .search_space import SearchSpace, SearchVariable


def residual_variance(weighted: np.ndarray, m: int, n: int) -> float:
    """s^2 = SSR / (m - n), unbiased for n fitted parameters and m samples; NaN if the residual is not finite."""
    dof = max(m - n, 1)
    return float(weighted @ weighted) / dof if np.all(np.isfinite(weighted)) else math.nan


def _at_bound(var: SearchVariable, value: float) -> int:
    """-1 / +1 if ``value`` sits on the lower / upper bound (log: within 0.1 %; linear: within 1e-6 of the
    range, or of the variable's scale for an open range), else 0."""
    if var.log:
        if math.log(value / var.lower) <= 1e-3:
            return -1
        return 1 if math.isfinite(var.upper) and math.log(var.upper / value) <= 1e-3 else 0
    width = var.upper - var.lower if math.isfinite(var.upper - var.lower) else var.scale
    if math.isfinite(var.lower) and value - var.lower <= 1e-6 * width:
        return -1
    return 1 if math.isfinite(var.upper) and var.upper - value <= 1e-6 * width else 0


def _chain_rule(spec: SearchSpace, x: np.ndarray, q: Mapping[str, float], params: Mapping[str, float]) -> np.ndarray:
    """G = d params / d x = (d params / d q) diag(dq/dx): the reported parameters (mu_static = mu + excess)
    as functions of the search variables; entries at rounding level are zeroed so G's pattern says which
    search variables a parameter depends on."""
    names = list(params)
    G = np.zeros((len(names), x.size))
    for i, var in enumerate(spec.variables):
        h = 1e-6 * max(abs(q[var.name]), var.scale if not var.log else 0.0, 1e-300)
        bumped = dict(q)
        bumped[var.name] = q[var.name] + h
        p1 = spec.physical(bumped)
        dq_dx = var.dq_dx(x[i])
        for j, name in enumerate(names):
            G[j, i] = (p1[name] - params[name]) / h * dq_dx
    G[np.abs(G) < 1e-12 * (np.abs(G).max() if G.size else 1.0)] = 0.0
    return G


def _svd_covariance(jac: np.ndarray, s2: float) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """-> (singular values, V^T, Cov_x, in_null): Cov_x = s^2 V S^-2 V^T without the numerically singular
    directions, and which search variables take part in one of those (their variance is unbounded)."""
    n = jac.shape[1]
    if n:
        _, sv, vt = np.linalg.svd(jac, full_matrices=False)
    else:
        sv, vt = np.zeros(0), np.zeros((0, 0))
    s_max = float(sv[0]) if sv.size else 0.0
    null = sv <= max(s_max, 1e-300) * 1e-12
    inv = np.where(null, 0.0, 1.0 / np.where(null, 1.0, sv) ** 2)
    cov_x = s2 * (vt.T * inv) @ vt if n else np.zeros((0, 0))
    in_null = np.zeros(n, bool)
    for k in np.flatnonzero(null):
        in_null |= np.abs(vt[k]) > 1e-8
    return sv, vt, cov_x, in_null


def _variable_reasons(spec: SearchSpace, q: Mapping[str, float], sv: np.ndarray, vt: np.ndarray,
                      rcond: float) -> List[List[str]]:
    """Per search variable, why the data do not determine it: at a bound, or in a direction of the scaled
    Jacobian the data barely see (with its partners there). "{name}" is replaced when reported."""
    n = len(spec.variables)
    s_max = float(sv[0]) if sv.size else 0.0
    reasons: List[List[str]] = [[] for _ in range(n)]
    for i, var in enumerate(spec.variables):
        side = _at_bound(var, q[var.name])
        if side:
            which, value = ("lower", var.lower) if side < 0 else ("upper", var.upper)
            reasons[i].append(f"{{name}}at its {which} bound {value:.4g}: the data push it out of the "
                              f"search range, so its value and standard error are not determined")
    partners: Dict[int, set] = {}
    smallest: Dict[int, float] = {}
    for k in np.flatnonzero(sv < s_max * rcond):  # near-null directions: which variables make them up
        weights = np.abs(vt[k])
        members = [i for i in range(n) if weights[i] >= 0.3 * weights.max()]
        ratio = sv[k] / s_max if s_max > 0 else 0.0
        for i in members:
            partners.setdefault(i, set()).update(j for j in members if j != i)
            smallest[i] = min(smallest.get(i, math.inf), ratio)
    for i, others in sorted(partners.items()):
        name = spec.variables[i].name
        detail = f"singular value ratio {smallest[i]:.1e} < rcond {rcond:g} of the log-scaled Jacobian"
        if not others:
            reasons[i].append(f"the fitted signal is almost insensitive to {name} ({detail})")
        else:
            reasons[i].append(f"{name} is nearly interchangeable with "
                              f"{', '.join(spec.variables[j].name for j in sorted(others))} ({detail})")
    return reasons


def _correlation(cov_p: np.ndarray, var_p: np.ndarray, fitted_idx: Sequence[int]) -> Tuple[np.ndarray,
                                                                                            np.ndarray]:
    """-> (covariance, correlation) over the fitted parameters; an undetermined parameter (infinite variance)
    gets NaN correlations rather than a number that would look meaningful."""
    cov_f = cov_p[np.ix_(fitted_idx, fitted_idx)]
    sd = np.sqrt(np.maximum(np.diag(cov_f), 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = cov_f / np.outer(sd, sd)
    corr[~np.isfinite(corr)] = np.nan
    for a, j in enumerate(fitted_idx):
        if not np.isfinite(var_p[j]):
            corr[a, :] = np.nan
            corr[:, a] = np.nan
            corr[a, a] = 1.0
            cov_f[a, :] = cov_f[:, a] = np.nan
            cov_f[a, a] = math.inf
    return cov_f, corr


def parameter_uncertainty(spec: SearchSpace, x: np.ndarray, jac: np.ndarray, s2: float, *, rcond: float,
                          max_relative_stderr: float) -> Dict[str, Any]:
    """Covariance s^2 (J^T J)^-1, chain rule to reported parameters, identifiability flags with reasons."""
    n = x.size
    q = spec.q(x)
    params = spec.physical(q)
    names = list(params)
    G = _chain_rule(spec, x, q, params)
    fitted = tuple(name for j, name in enumerate(names) if np.any(G[j] != 0.0))

    sv, vt, cov_x, in_null = _svd_covariance(jac, s2)
    condition = float(sv[0] / sv[-1]) if sv.size and sv[-1] > 0 else math.inf
    cov_p = G @ cov_x @ G.T
    p_in_null = (np.abs(G) > 0) @ in_null > 0 if n else np.zeros(len(names), bool)
    var_p = np.diag(cov_p).copy()
    var_p[p_in_null] = math.inf
    stderr_all = np.sqrt(np.maximum(var_p, 0.0))
    var_reasons = _variable_reasons(spec, q, sv, vt, rcond)
    cov_f, corr = _correlation(cov_p, var_p, [names.index(nm) for nm in fitted])

    stderr: Dict[str, float] = {}
    identifiable: Dict[str, bool] = {}
    reasons: Dict[str, str] = {}
    floors = {v.name: v.magnitude_floor for v in spec.variables}
    for j, name in enumerate(names):
        if name not in fitted:
            stderr[name] = 0.0
            identifiable[name] = True
            reasons[name] = f"held fixed at {params[name]:.6g} (not fitted)"
            continue
        se = float(stderr_all[j])
        stderr[name] = se
        why: List[str] = []
        for i in np.flatnonzero(G[j]):  # a parameter inherits the flags of the search variables it is built from
            var_name = spec.variables[i].name
            label = "" if var_name == name else f"{var_name} "
            why.extend(r.replace("{name}", label) for r in var_reasons[i] if r.replace("{name}", label) not in why)
        scale = max(abs(params[name]), floors.get(name, 0.0))
        rel = se / scale if scale > 0 else math.inf
        if p_in_null[j]:
            why.append("the Jacobian is singular along it: the data do not determine it (infinite standard error)")
        elif not math.isfinite(s2):
            why.append("no finite residual at the solution")
        elif rel > max_relative_stderr:
            text = f"relative standard error {100 * rel:.3g}% > {100 * max_relative_stderr:.3g}%"
            a = fitted.index(name)
            partners = [fitted[b] for b in range(len(fitted))
                        if b != a and np.isfinite(corr[a, b]) and abs(corr[a, b]) > 0.95]
            if partners:
                text += f" (correlation > 0.95 with {', '.join(partners)})"
            why.append(text)
        identifiable[name] = not why
        reasons[name] = "; ".join(why) if why else f"identified: relative standard error {100 * rel:.2g}%"
    x_stderr = np.sqrt(np.maximum(np.diag(cov_x), 0.0)) if n else np.zeros(0)
    x_stderr[in_null] = math.inf
    return dict(params=params, fitted=fitted, stderr=stderr, covariance=cov_f, correlation=corr,
                identifiable=identifiable, reasons=reasons, singular_values=sv, condition_number=condition,
                x_stderr=x_stderr)
