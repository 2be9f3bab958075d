"""Which friction law does a record support? :func:`compare_laws` fits several laws to one kinematic record and ranks
them by the Akaike information criterion, with delta-AIC and Akaike weights (Burnham & Anderson 2002, sec 2.9):

    Delta_i = AIC_i - min AIC,    w_i = exp(-Delta_i / 2) / sum_j exp(-Delta_j / 2).

A law with Delta < 2 is about as well supported as the best; Delta > 10 has essentially none (ibid., sec 2.6).
Every law is fitted by :func:`frictionsim.fit.identify` with the same record, weights and options, so the
likelihood's constant cancels in the differences (see :class:`IdentificationResult`).
"""

from __future__ import annotations

import math
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ..errors import InvalidParameterError
from ..validation import reject
from .kinematic import identify
from .parameters import law_def
from .result import IdentificationResult
from .solver import FitWorkError

__all__ = ["compare_laws"]

#: The laws compared by default: the kinematic fits of paper 000's Dahl, LuGre, its elasto-plastic refinement and the
#: static Stribeck curve.
DEFAULT_LAWS = ("dahl", "lugre", "elasto_plastic", "stribeck")

_COLUMNS = {"t": ("t", "time"), "relative_velocity": ("relative_velocity", "v_r"),
            "friction_force": ("friction_force", "F"), "normal_force": ("normal_force", "N")}


def _column(data: Any, name: str, required: bool = True) -> Any:
    for key in _COLUMNS[name]:
        if key in data:
            return np.asarray(data[key], dtype=float)
    if required:
        reject(f"data must have a column {name} (or {' / '.join(_COLUMNS[name][1:])}); it has "
               f"{', '.join(map(str, data.keys()))}", "data")
    return None


def _record(data: Any, normal_force: Any) -> Tuple[Any, Any, Any, Any]:
    """-> (t, v_r, F, N) from a table (DataFrame or mapping of columns) or a (t, v_r, F[, N]) tuple."""
    if isinstance(data, (tuple, list)):
        if len(data) not in (3, 4):
            reject(f"data as a sequence must be (t, relative_velocity, friction_force[, normal_force]) (got "
                   f"{len(data)} items)", "data")
        t, v, force = data[:3]
        n = data[3] if len(data) == 4 else None
    elif hasattr(data, "keys") and hasattr(data, "__getitem__"):
        t, v, force = (_column(data, name) for name in ("t", "relative_velocity", "friction_force"))
        n = _column(data, "normal_force", required=False)
    else:
        reject(f"data must be a DataFrame or mapping with columns t, relative_velocity, friction_force[, "
               f"normal_force], or a (t, v_r, F[, N]) tuple (got {type(data).__name__})", "data")
    if normal_force is not None:
        if n is not None:
            reject("normal_force is given both in data and as the normal_force argument", "normal_force")
        n = normal_force
    if n is None:
        reject("normal_force is required: a column of data or the normal_force argument [N]", "normal_force")
    return t, v, force, n


def compare_laws(data: Any, laws: Union[str, Sequence[Any]] = DEFAULT_LAWS, *, normal_force: Any = None,
                 law_options: Optional[Mapping[str, Mapping[str, Any]]] = None, return_results: bool = False,
                 **options: Any):
    """Fit each law of ``laws`` to one kinematic record and rank them by AIC.

    Parameters
    ----------
    data : DataFrame, mapping or tuple
        The record: columns ``t`` [s], ``relative_velocity`` [m/s], ``friction_force`` [N] and optionally
        ``normal_force`` [N], or a tuple (t, relative_velocity, friction_force[, normal_force]).
    laws : sequence of str or class
        Laws to compare, as :func:`frictionsim.fit.identify` accepts them (default dahl, lugre, elasto_plastic,
        stribeck).
    normal_force : float or array or (t_N, N) pair, optional
        N when ``data`` does not hold it.
    law_options : dict, optional
        Per-law keywords for :func:`~frictionsim.fit.identify` (e.g. ``{"lugre": {"initial_guess": {...}}}``),
        by the keys of ``laws``.
    return_results : bool
        Also return the :class:`IdentificationResult` of every law.
    **options
        Keywords for every fit (method, weights, rtol, seed, verbose, callback, ...).

    Returns
    -------
    pandas.DataFrame or (DataFrame, dict)
        Indexed by law key, best first (smallest AIC): ``law_name``, ``k`` (fitted parameters + the noise
        variance), ``n`` (samples), ``rss`` [N^2], ``rms_residual`` [N], ``r_squared``, ``log_likelihood``, ``aic``,
        ``delta_aic``, ``akaike_weight`` (sum 1), ``aicc``, ``bic``, ``delta_bic``, ``success``,
        ``all_identifiable``. With ``return_results``, also {law key: IdentificationResult}.

    Raises
    ------
    InvalidParameterError (a ValueError)
        Bad record or option (as :func:`~frictionsim.fit.identify`), no law, a law named twice, or law_options
        for a law not compared.

    Notes
    -----
    The ranking is only as good as each fit: a local search that stops in a local minimum ranks its law too
    low. A law that fits worse than a simpler one it contains shows it (LuGre with mu_s = mu and sigma_1 =
    sigma_2 = 0 is Dahl with alpha = 1: on a Dahl record its default start ends at 230 times Dahl's RSS, from
    that nesting point within 0.1 %); give it such a start in ``law_options`` or ``method="differential_evolution"``.
    """
    if isinstance(laws, (str, type)):
        laws = (laws,)
    laws = list(laws)
    if not laws:
        reject("laws must name at least one law", "laws")
    keys = [law_def(law).key for law in laws]
    duplicated = sorted({k for k in keys if keys.count(k) > 1})
    if duplicated:
        reject(f"laws names {', '.join(duplicated)} more than once", "laws")
    per_law: Dict[str, Mapping[str, Any]] = {}
    for key, value in (law_options or {}).items():
        canonical = law_def(key).key
        if canonical not in keys:
            reject(f"law_options[{key!r}]: {key} is not among the laws compared ({', '.join(keys)})",
                   f"law_options[{key!r}]")
        per_law[canonical] = value
    t, v, force, n = _record(data, normal_force)

    results: Dict[str, IdentificationResult] = {}
    for key in keys:
        try:
            results[key] = identify(key, t, v, force, n, **dict(options, **per_law.get(key, {})))
        except InvalidParameterError as error:
            if error.parameter != "t":
                raise
            # the record's time column is data's: a refusal of its samples (too many for the fit's work limit,
            # not increasing) names data, the argument given
            message = f"data: {error} (fitting {key})"
            if isinstance(error, FitWorkError):
                raise FitWorkError(message, "data", error.factor) from None
            raise InvalidParameterError(message, "data") from None
    return _table(results, return_results)


def _table(results: Mapping[str, IdentificationResult], return_results: bool = False):
    """The ranking of already fitted results (same record): AIC order, delta-AIC, Akaike weights."""
    import pandas as pd

    rows = []
    for key, r in results.items():
        rows.append(dict(law=key, law_name=r.law_name, k=r.k, n=r.n_used, rss=r.rss, rms_residual=r.rms_residual,
                         r_squared=r.r_squared, log_likelihood=r.log_likelihood, aic=r.aic, aicc=r.aicc, bic=r.bic,
                         success=r.success, all_identifiable=r.all_identifiable))
    table = pd.DataFrame(rows).set_index("law").sort_values("aic", kind="stable")
    best_aic, best_bic = float(table["aic"].min()), float(table["bic"].min())
    if math.isfinite(best_aic):
        delta = table["aic"].to_numpy() - best_aic
        weights = np.exp(-0.5 * delta)
    else:  # an exact fit (AIC -inf) takes all the weight; several share it
        delta = np.where(table["aic"].to_numpy() == best_aic, 0.0, math.inf)
        weights = (delta == 0.0).astype(float)
    table["delta_aic"] = delta
    table["akaike_weight"] = weights / weights.sum()
    table["delta_bic"] = (table["bic"].to_numpy() - best_bic if math.isfinite(best_bic)
                          else np.where(table["bic"].to_numpy() == best_bic, 0.0, math.inf))
    table = table[["law_name", "k", "n", "rss", "rms_residual", "r_squared", "log_likelihood", "aic", "delta_aic",
                   "akaike_weight", "aicc", "bic", "delta_bic", "success", "all_identifiable"]]
    return (table, dict(results)) if return_results else table
