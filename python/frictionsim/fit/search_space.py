"""The search space: physical parameters <-> O(1) search variables, bounds, fixed values, user input.

Positive parameters are searched in log space, x = ln(q / q_ref): k_t may lie anywhere in 10..1e10 N/m, and
a relative step is the natural one for it. The others (coefficients that may be zero) are linear,
x = (q - q_ref) / scale with scale ~ |q_ref|. Either way the search variables are all O(1), which the
trust-region steps, the finite-difference Jacobian and the singular-value test of identifiability rely on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..validation import reject
from .parameters import canonical_name, LawDef, Param
from .validation import real_number

Bounds = Mapping[str, Tuple[float, float]]


@dataclass
class SearchVariable:
    """One searched variable: q = ref exp(x) (log) or q = ref + scale x (linear)."""

    name: str
    lower: float
    upper: float
    ref: float
    log: bool
    scale: float = 1.0
    magnitude_floor: float = 0.0  # relative standard errors are taken against max(|q|, floor)

    def q(self, x: float) -> float:
        value = self.ref * math.exp(x) if self.log else self.ref + self.scale * x
        return min(max(value, self.lower), self.upper)  # clip rounding just past a bound

    def x(self, q: float) -> float:
        return math.log(q / self.ref) if self.log else (q - self.ref) / self.scale

    def dq_dx(self, x: float) -> float:
        return self.q(x) if self.log else self.scale

    @property
    def x_bounds(self) -> Tuple[float, float]:
        if self.log:
            lo = math.log(self.lower / self.ref)
            hi = math.log(self.upper / self.ref) if math.isfinite(self.upper) else math.inf
        else:
            lo = (self.lower - self.ref) / self.scale if math.isfinite(self.lower) else -math.inf
            hi = (self.upper - self.ref) / self.scale if math.isfinite(self.upper) else math.inf
        return lo, hi

    def grid(self, points_per_decade: float = 2.0) -> np.ndarray:
        """Coarse grid over the bounds for the starting-value scan (none for an open range)."""
        if not (math.isfinite(self.lower) and math.isfinite(self.upper)):
            return np.array([])
        if self.log:
            n = max(5, int(math.ceil(points_per_decade * math.log10(self.upper / self.lower))) + 1)
            return np.geomspace(self.lower, self.upper, n)
        return np.linspace(self.lower, self.upper, 11)


@dataclass
class SearchSpace:
    """Fitted variables, fixed values, and the map to reported (physical) parameters."""

    variables: List[SearchVariable]
    fixed: Dict[str, float]
    physical: Callable[[Mapping[str, float]], Dict[str, float]]  # all fit variables -> reported parameters

    @property
    def names(self) -> List[str]:
        return [v.name for v in self.variables]

    def q(self, x: Sequence[float]) -> Dict[str, float]:
        out = dict(self.fixed)
        for v, xi in zip(self.variables, x):
            out[v.name] = v.q(float(xi))
        return out

    def x(self, q: Mapping[str, float]) -> np.ndarray:
        return np.array([v.x(q[v.name]) for v in self.variables])

    def x_bounds(self) -> Tuple[np.ndarray, np.ndarray]:
        pairs = [v.x_bounds for v in self.variables]
        return np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])

    def with_refs(self, q: Mapping[str, float]) -> "SearchSpace":
        """The same spec re-centred at ``q`` (x = 0 there)."""
        variables = []
        for v in self.variables:
            ref = q[v.name]
            scale = v.scale if v.log else (abs(ref) if ref != 0.0 else v.scale)
            variables.append(SearchVariable(v.name, v.lower, v.upper, ref, v.log, scale, v.magnitude_floor))
        return SearchSpace(variables, dict(self.fixed), self.physical)


def _make_var(param: Param, bounds: Tuple[float, float], ref: float, floor: float = 0.0) -> SearchVariable:
    """Log space when the lower bound is positive; else linear, scaled by |ref| (or a tenth of the range)."""
    lower, upper = bounds
    use_log = lower > 0.0
    if use_log:
        scale = 1.0
    else:
        scale = abs(ref) if ref != 0.0 else ((upper - lower) / 10.0 if math.isfinite(upper - lower) else 1.0)
    return SearchVariable(param.name, lower, upper, ref, use_log, scale, floor)


# ------------------------------------------------------------------------------------------ the user's input
def user_bounds(lawdef: LawDef, bounds: Optional[Bounds], extra: Mapping[str, Param],
                force_scale: float = 1.0, speed_scale: float = 1.0) -> Dict[str, Tuple]:
    """Default bounds overridden by ``bounds``; a NaN upper bound (damping) becomes 10 force / speed."""
    damping_max = 10.0 * force_scale / speed_scale
    out: Dict[str, Tuple[float, float]] = {
        p.name: (p.bounds[0], damping_max if math.isnan(p.bounds[1]) else p.bounds[1]) for p in lawdef.params}
    out.update({name: p.bounds for name, p in extra.items()})
    for key, pair in (bounds or {}).items():
        name = canonical_name(lawdef, key, "bounds", tuple(extra))
        where = f"bounds[{key!r}]"
        if name in lawdef.excess:
            variable, other = lawdef.excess[name]
            reject(f"{where}: {name} is fitted as {variable} = {name} - {other} >= 0; bound that instead", where)
        try:
            if isinstance(pair, (str, bytes)) or any(isinstance(v, (str, bytes)) for v in pair[:2]):
                raise TypeError("text")  # never read as numbers (see validation.refuse_text)
            lo, hi = (float(pair[0]), float(pair[1]))
        except (TypeError, ValueError, IndexError):
            reject(f"{where} must be a (lower, upper) pair of numbers [SI], not text (got {pair!r})", where)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            reject(f"{where} must satisfy lower < upper (got ({lo}, {hi}))", where)
        param = extra.get(name) or lawdef.param(name)
        if param.minimum is not None and not math.isinf(-param.minimum):
            if lo < param.minimum or (param.strict and lo == param.minimum):
                rule = ">" if param.strict else ">="
                reject(f"{where}: the lower bound must be {rule} {param.minimum} for {name} (got {lo})", where)
        if math.isfinite(param.maximum) and not param.admits(hi):
            rule = "<" if param.strict_max else "<="
            reject(f"{where}: the upper bound must be {rule} {param.maximum} for {name} (got {hi})", where)
        out[name] = (lo, hi)
    return out


def user_values(lawdef: LawDef, values: Optional[Mapping[str, float]], where: str,
                extra: Sequence[str] = ()) -> Dict[str, float]:
    """{name or alias: number} -> {fit-variable name: finite float}."""
    out: Dict[str, float] = {}
    for key, value in (values or {}).items():
        name = canonical_name(lawdef, key, where, extra)
        value = real_number(f"{where}[{key!r}]", value)
        if not math.isfinite(value):
            reject(f"{where}[{key!r}] must be finite (got {value})", f"{where}[{key!r}]")
        out[name] = value
    return out


def resolve_excess(lawdef: LawDef, values: Dict[str, float], where: str,
                   lower_values: Optional[Mapping[str, float]] = None) -> None:
    """Turn a given mu_static (any keyword bounded below by another) into its fit variable mu_static_excess =
    mu_static - mu; needs mu in ``values`` or ``lower_values``."""
    for name, (variable, other) in lawdef.excess.items():
        if name not in values:
            continue
        value = values.pop(name)
        bound = values.get(other, (lower_values or {}).get(other))
        if bound is None:
            reject(f"{where}[{name!r}] needs {other} in {where} too ({name} is fitted as {name} - {other}); "
                   f"or give {variable}", f"{where}[{name!r}]")
        if value < bound:
            reject(f"{where}[{name!r}] must be >= {other} ({bound}); got {value}", f"{where}[{name!r}]")
        values[variable] = value - bound


def build_search_space(lawdef: LawDef, fitted: Sequence[str], guess: Mapping[str, float], fixed: Mapping[str, float],
                       bounds: Mapping[str, Tuple[float, float]], extra: Mapping[str, Param],
                       floors: Mapping[str, float], user_guess: Mapping[str, float]) -> SearchSpace:
    """The search space centred at ``guess`` (a data-based guess is clipped into the bounds, a user's is not)."""
    variables = []
    for name in fitted:
        param = extra.get(name) or lawdef.param(name)
        lo, hi = bounds[name]
        value = guess[name]
        if not lo <= value <= hi:
            if name in user_guess:
                reject(f"initial_guess[{name!r}] = {value} is outside its bounds [{lo}, {hi}]",
                       f"initial_guess[{name!r}]")
            value = min(max(value, lo), hi)
        if lo > 0.0 and value <= 0.0:
            value = lo
        variables.append(_make_var(param, (lo, hi), value, floors.get(name, 0.0)))
    for name, value in fixed.items():
        param = extra.get(name) or lawdef.param(name)
        if not param.admits(value):
            reject(f"fixed[{name!r}] = {value} is not a valid {name}", f"fixed[{name!r}]")

    def physical(q: Mapping[str, float]) -> Dict[str, float]:
        out = lawdef.physical(q)
        for name in extra:
            if name in q:
                out[name] = q[name]
        return out

    return SearchSpace(variables, dict(fixed), physical)
