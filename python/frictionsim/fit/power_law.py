"""Refit of paper 000's Table 5: the power-law dynamic friction coefficient mu_df = eta' (v_a/v_d)^c (eq 17).

What the paper regresses (found by refitting Table 4 as printed): per lubricant, an ordinary least-squares line
y = slope x + intercept through its five runs, with

    y = log10(mu_df)        mu_df: Table 4's printed "u_df" column (= F_df/F_N to three decimals)
    x = log10(v_a / v_d)    v_a = 2 pi f u (eq 16), v_d in the same unit (eq 17's ratio, not eq 15's u f / v_d)

so c = slope and eta' = 10**intercept. This reproduces every printed slope and intercept of Table 5 to all
printed digits (five decimals; the intercepts 0.0284 and -0.6745 print four). Eq 15's u f / v_d gives the same
slope but intercepts lower by c log10(2 pi) (e.g. dry -0.26304), and natural logarithms give other intercepts
(dry 0.06538): neither matches Table 5.

eta' = 10**intercept reproduces the printed eta' to its four decimals for dry, water, WBM and OBM (1.0676,
0.1951, 0.2116, 0.1332). For SBM it gives 0.123017 -> 0.1230, the printed intercept -0.91003 gives 0.123018 ->
0.1230, but 0.1231 is printed: a slip of one unit in the last digit (0.07 %), not explained by any regression
that also gives the printed intercept (0.1231 needs an intercept in [-0.90991, -0.90956]).

The printed R^2 are NOT reproduced. The fit's R^2 (= r^2 of x and y, the only R^2 of this line) is
dry 0.7939, water 0.7213, WBM 0.9248, OBM 0.8607, SBM 0.9081 against the printed 0.73, 0.63, 0.88, 0.82, 0.87:
every printed value is 0.04-0.09 lower. Since the slopes and intercepts match to five digits, the data are
the same, so the printed R^2 is a different statistic or a slip. The closest standard one is the adjusted R^2,
1 - (1 - R^2)(n - 1)/(n - 2) with n = 5: 0.7253, 0.6284, 0.8998, 0.8142, 0.8775, which rounds to the printed
value for dry and water but is 0.020 above it for WBM, 0.006 below for OBM and 0.0075 above for SBM. No other
variant tried (R^2 of the power law in linear mu_df, of a direct nonlinear power fit, of linear or semi-log
lines, of F_df or mu_df/mu_sf instead of mu_df) matches more than two of the five.

Standard errors (not printed in the paper): the line is fitted by :func:`scipy.stats.linregress`, whose slope and
intercept standard errors are the least-squares ones, sqrt of the diagonal of s^2 (X^T X)^-1 with s^2 = SS_res /
(n - 2); eta' = 10**intercept and eta = eta' (2 pi)^c get theirs by the delta method (first-order propagation,
with the slope-intercept covariance -mean(x) SE(slope)^2). Five runs per line leave them wide: on Table 4,
c = -0.365 +- 0.107 (dry) to -0.092 +- 0.017 (SBM), eta' = 1.07 +- 0.73 (dry) to 0.123 +- 0.013 (SBM), one
standard error.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import NoReturn, Optional, Tuple, Union

import numpy as np
import pandas as pd
from scipy import stats

from ..errors import InvalidParameterError
from ..validation import require_finite
from .quality import fit_quality
from .validation import varying

__all__ = ["PowerLawFit", "fit_power_law"]


@dataclass(frozen=True)
class PowerLawFit:
    """Least-squares line log10(mu_df) = slope log10(v_a/v_d) + intercept for one lubricant.

    Attributes: ``lubricant`` (normalised name, or None for an ungrouped table), ``slope`` (= c),
    ``intercept``, ``r_squared`` (1 - SS_res/SS_tot of the line, in log10 space), ``n_runs``,
    ``velocity_ratio_min`` and ``velocity_ratio_max`` (the v_a/v_d range fitted; outside it the law
    extrapolates), ``slope_stderr`` and ``intercept_stderr`` (least-squares standard errors, s^2 = SS_res /
    (n - 2), from :func:`scipy.stats.linregress`) and ``slope_intercept_covariance`` (-mean(x) slope_stderr^2).
    """

    lubricant: Optional[str]
    slope: float
    intercept: float
    r_squared: float
    n_runs: int
    velocity_ratio_min: float
    velocity_ratio_max: float
    slope_stderr: float = 0.0
    intercept_stderr: float = 0.0
    slope_intercept_covariance: float = 0.0

    @property
    def exponent(self) -> float:
        """c [-] of eq 17, the slope of the log-log line."""
        return self.slope

    @property
    def eta_prime(self) -> float:
        """eta' [-] of eq 17 (Table 5's coefficient), 10**intercept."""
        return 10.0 ** self.intercept

    @property
    def eta_eq15(self) -> float:
        """eta [-] of eq 15, mu_df = eta (u f / v_d)^c: eta = eta' (2 pi)^c."""
        return self.eta_prime * (2.0 * math.pi) ** self.exponent

    @property
    def exponent_stderr(self) -> float:
        """Standard error of c [-] (= slope_stderr)."""
        return self.slope_stderr

    @property
    def eta_prime_stderr(self) -> float:
        """Standard error of eta' = 10**intercept by the delta method: ln(10) eta' SE(intercept)."""
        return math.log(10.0) * self.eta_prime * self.intercept_stderr

    @property
    def eta_eq15_stderr(self) -> float:
        """Standard error of eta = 10**(intercept + c log10(2 pi)) by the delta method, with the slope-intercept
        covariance: ln(10) eta sqrt(Var b + L^2 Var c + 2 L Cov(b, c)), L = log10(2 pi)."""
        lever = math.log10(2.0 * math.pi)
        variance = (self.intercept_stderr ** 2 + lever ** 2 * self.slope_stderr ** 2
                    + 2.0 * lever * self.slope_intercept_covariance)
        return math.log(10.0) * self.eta_eq15 * math.sqrt(max(variance, 0.0))

    @property
    def adjusted_r_squared(self) -> float:
        """1 - (1 - R^2)(n - 1)/(n - 2). Reported because it is the closest to Table 5's R^2. NaN for n <= 2,
        which fit_power_law never returns (it needs 3 runs)."""
        if self.n_runs <= 2:
            return math.nan
        return 1.0 - (1.0 - self.r_squared) * (self.n_runs - 1) / (self.n_runs - 2)

    @property
    def params(self) -> Tuple[float, float]:
        """(eta, exponent) as ``frictionsim.PowerLawCoefficient(eta, exponent)`` takes them: (eta', c)."""
        return (self.eta_prime, self.exponent)

    def coefficient(self, velocity_amplitude, sliding_velocity):
        """mu_df = eta' (v_a / v_d)^c [-]; v_a and v_d > 0 in any common unit (only the ratio matters). A ratio so
        extreme that mu_df overflows is refused, naming the argument, as PowerLawCoefficient does."""
        v_a = _positive_velocities("velocity_amplitude", velocity_amplitude)
        v_d = _positive_velocities("sliding_velocity", sliding_velocity)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            ratio = v_a / v_d
            mu = self.eta_prime * ratio ** self.exponent
        require_finite("PowerLawFit.coefficient", {"v_a / v_d": ratio, "mu_df": mu},
                       {"velocity_amplitude": v_a, "sliding_velocity": v_d})
        return mu

    def to_dict(self) -> dict:
        """The fields plus eta_prime, exponent, eta_eq15, adjusted_r_squared and their standard errors."""
        row = asdict(self)
        row.update(eta_prime=self.eta_prime, exponent=self.exponent, eta_eq15=self.eta_eq15,
                   adjusted_r_squared=self.adjusted_r_squared, eta_prime_stderr=self.eta_prime_stderr,
                   exponent_stderr=self.exponent_stderr, eta_eq15_stderr=self.eta_eq15_stderr)
        return row


def _positive_velocities(name: str, value) -> np.ndarray:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"{name} must be a number or an array of numbers [m/s] (got {value!r})",
                                    name) from None
    if not np.all(np.isfinite(array) & (array > 0.0)):
        raise InvalidParameterError(f"{name} must be positive and finite (got {value!r})", name)
    return array


def _column(rows: pd.DataFrame, column: str, lubricant: Optional[str]) -> np.ndarray:
    """One column of a lubricant's runs as positive, finite floats (logarithms are taken)."""
    where = "" if lubricant is None else f" (lubricant {lubricant!r})"
    try:
        values = rows[column].to_numpy(dtype=float)
    except (TypeError, ValueError):
        reject(f"column {column} must hold numbers{where}")
    if not np.all(np.isfinite(values) & (values > 0.0)):
        bad = values[~(np.isfinite(values) & (values > 0.0))][0]
        reject(f"column {column} must be positive and finite to take logarithms{where}; got {bad}")
    return values


def fit_model(lubricant: Optional[str], rows: pd.DataFrame) -> PowerLawFit:
    where = "" if lubricant is None else f" of lubricant {lubricant!r}"
    if len(rows) < 3:  # through 2 points the line is exact: R^2 = 1 whatever they are, no residual to judge it
        reject(f"needs at least 3 runs per line, to fit one and judge it by R^2 (the runs{where} are {len(rows)})")
    ratio, mu = _column(rows, "velocity_ratio", lubricant), _column(rows, "mu_df", lubricant)
    varying("fit_power_law: table column velocity_ratio", ratio, "table", where, "so the line has no slope")
    varying("fit_power_law: table column mu_df", mu, "table", where)
    x, y = np.log10(ratio), np.log10(mu)
    line = stats.linregress(x, y)
    slope, intercept = float(line.slope), float(line.intercept)
    slope_se, intercept_se = float(line.stderr), float(line.intercept_stderr)
    covariance = -float(x.mean()) * slope_se ** 2  # Cov(b, c) = -mean(x) s^2 / Sxx
    _, r_squared = fit_quality(y, slope * x + intercept - y)
    with np.errstate(over="ignore", invalid="ignore"):  # the finiteness rule below names what overflowed
        eta_prime = np.power(10.0, intercept)
        eta_eq15 = eta_prime * np.power(2.0 * math.pi, slope)
        eta_prime_se = math.log(10.0) * eta_prime * intercept_se
    require_finite("fit_power_law", {"slope": slope, "intercept": intercept, "r_squared": r_squared,
                                     "eta_prime": eta_prime, "eta_eq15": eta_eq15, "slope_stderr": slope_se,
                                     "intercept_stderr": intercept_se, "eta_prime_stderr": eta_prime_se},
                    {"table": np.concatenate([ratio, mu])})
    return PowerLawFit(lubricant, slope, intercept, r_squared, int(ratio.size), float(ratio.min()),
                       float(ratio.max()), slope_se, intercept_se, covariance)


def reject(rule: str, parameter: str = "table") -> NoReturn:
    raise InvalidParameterError(f"fit_power_law: {parameter} {rule}", parameter)


def fit_power_law(table: Optional[pd.DataFrame] = None, *,
                  lubricant: Optional[str] = None) -> Union[PowerLawFit, pd.DataFrame]:
    """Fit log10(mu_df) = c log10(v_a/v_d) + log10(eta') by least squares, per lubricant (Table 5's method).

    ``table`` needs columns ``velocity_ratio`` (v_a/v_d [-]) and ``mu_df`` [-], and ``lubricant`` to group
    by; the default is :func:`frictionsim.data.table4` (mu_df as printed), which reproduces Table 5's slopes,
    intercepts and eta' (not its R^2; see the module docstring). Any other data (e.g. simulated cycle means)
    can be fitted the same way.

    Returns a :class:`PowerLawFit` when ``lubricant`` is given (case-insensitive) or the table has no
    ``lubricant`` column, otherwise a DataFrame indexed by lubricant (in order of first appearance) with columns
    slope, intercept, eta_prime, exponent, eta_eq15, r_squared, adjusted_r_squared, n_runs,
    velocity_ratio_min, velocity_ratio_max, slope_stderr, intercept_stderr, eta_prime_stderr, eta_eq15_stderr
    (standard errors: see the module docstring).

    Raises InvalidParameterError (a ValueError) naming ``table`` or ``lubricant``: not a DataFrame, no rows, a
    missing column or lubricant name, an unknown lubricant, fewer than 3 runs in a line, a velocity ratio or
    mu_df that is not a positive number, all velocity ratios equal (no slope) or all mu_df equal (R^2 undefined),
    or a line whose eta' or eta_eq15 overflows.
    """
    if table is None:
        from frictionsim.data import table4  # late import: keeps this module usable on any table alone

        table = table4()
    if not isinstance(table, pd.DataFrame):
        reject(f"must be a pandas DataFrame (got {type(table).__name__})")
    missing = [c for c in ("velocity_ratio", "mu_df") if c not in table.columns]
    if missing:
        reject(f"must have the columns velocity_ratio and mu_df (missing {', '.join(missing)})")
    if table.empty:  # a pandas KeyError before
        reject("has no rows (a line needs at least 3 runs per lubricant)")
    if lubricant is not None and not isinstance(lubricant, str):
        reject(f"must be a name such as 'dry' (got {lubricant!r})", "lubricant")
    if "lubricant" not in table.columns:
        if lubricant is not None:
            reject("given, but the table has no 'lubricant' column", "lubricant")
        return fit_model(None, table)

    unnamed = table["lubricant"].isna()
    if unnamed.any():  # pandas' groupby would drop these runs silently
        reject(f"column lubricant must name every run (row {table.index[unnamed.to_numpy()][0]!r} has none)")
    names = table["lubricant"].astype(str).str.lower()
    if lubricant is not None:
        key = lubricant.lower()
        rows = table[names == key]
        if rows.empty:
            reject(f"must be one of {', '.join(names.unique())} (case-insensitive; got {lubricant!r})", "lubricant")
        return fit_model(key, rows)

    fits = [fit_model(key, rows).to_dict() for key, rows in table.groupby(names, sort=False)]
    columns = ["lubricant", "slope", "intercept", "eta_prime", "exponent", "eta_eq15", "r_squared",
               "adjusted_r_squared", "n_runs", "velocity_ratio_min", "velocity_ratio_max", "slope_stderr",
               "intercept_stderr", "eta_prime_stderr", "eta_eq15_stderr"]
    return pd.DataFrame(fits)[columns].set_index("lubricant")
