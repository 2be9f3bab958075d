"""Friction-law identification from measured signals: Dahl, LuGre and Stribeck fitted through the C++ engine.

Paper 000 (sec 4.2) stresses that the Dahl tangential contact stiffness k_t "is one of the most complicated
parameters that need to be determined" and that genetic / particle-swarm searches are commonly used for it.
This module does that identification by output-error least squares on simulations of the C++ kinematic rig:

* every residual evaluation is one simulation ``fs.simulate(fs.KinematicRig(law, relative_velocity=(t, v_r),
  normal_force=N), t[-1], output_times=t, t_start=t[0])`` whose ``friction_force`` is compared with the
  measured friction force F(t) [N];
* local search: :func:`scipy.optimize.least_squares` (trust-region reflective, box bounds); global search
  (what the paper's genetic / PSO methods are for): :func:`scipy.optimize.differential_evolution` over the same
  bounds, deterministic for a given ``seed``, polished by least_squares;
* positive parameters are searched in log space (x = ln(q / q_ref)), the others linearly scaled by their
  starting magnitude, so the search variables are all O(1);
* mu_static >= mu is kept by fitting mu_static_excess = mu_static - mu >= 0;
* the uncertainty comes from the Jacobian J (central differences) at the solution: Cov_x = s^2 (J^T J)^-1,
  s^2 = SSR / (m - n), mapped to the physical parameters with the chain rule (dq/dx = q for log-space
  variables); identifiability is flagged per parameter with a reason (at a bound, in a near-null direction of
  the scaled Jacobian, or a relative standard error above a threshold).

The friction force follows the engine's sign convention: positive opposing positive relative velocity v_r.
A kinematic rig has no mass, so set-valued laws (Stribeck) give their slip force on the branch sgn(v_r) (no
stick); the fitted Stribeck curve is the sliding branch.

Rig-level identification (fitting k_t from the drive force of the axial vibrating-sliding rig, eq 7) is in
:mod:`frictionsim.fit.rig` and shares the fitting core (:func:`_fit`) and the result class.
"""

from __future__ import annotations

import inspect
import math
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
from scipy import optimize

from .._core import Dahl, KinematicRig, LuGre, Stribeck
from ..errors import InvalidParameterError, SimulationError
from ..simulation import simulate

__all__ = [
    "IdentificationResult",
    "identify",
    "identify_dahl",
    "identify_lugre",
    "identify_stribeck",
    "LAW_PARAMETERS",
]

Bounds = Mapping[str, Tuple[float, float]]

#: Search methods accepted by ``method=``.
METHODS = ("least_squares", "differential_evolution")


# ============================================================================================ parameter catalogue
@dataclass(frozen=True)
class _Param:
    """A fit variable: a law keyword (mu, tangential_stiffness, ...) or a derived one (mu_static_excess)."""

    name: str
    symbol: str
    unit: str
    bounds: Tuple[float, float]  # default search bounds; upper NaN: from the data (see _default_bounds)
    minimum: float = 0.0  # validity: > minimum (strict) or >= minimum
    strict: bool = True
    aliases: Tuple[str, ...] = ()
    scan: bool = False  # coarse grid scan for a starting value when no initial guess is given
    default: Optional[float] = None  # value when held fixed and not given


@dataclass(frozen=True)
class _LawDef:
    key: str
    name: str
    params: Tuple[_Param, ...]
    physical_names: Tuple[str, ...]  # keywords of the law's constructor, in order
    state_count: int

    def param(self, name: str) -> _Param:
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError(name)

    def physical(self, q: Mapping[str, float]) -> Dict[str, float]:
        """Fit variables -> the law constructor's keywords."""
        out = {}
        for name in self.physical_names:
            if name == "mu_static":
                out[name] = q["mu"] + q["mu_static_excess"]
            else:
                out[name] = q[name]
        return out

    def build(self, physical: Mapping[str, float]):
        cls = {"dahl": Dahl, "lugre": LuGre, "stribeck": Stribeck}[self.key]
        return cls(**{k: float(physical[k]) for k in self.physical_names})

    def state_stiffness(self, physical: Mapping[str, float]) -> float:
        """dF/dz of the law state [N/m] (k_t or sigma_0), to scale its absolute tolerance; 0 if no state."""
        return {"dahl": physical.get("tangential_stiffness", 0.0),
                "lugre": physical.get("bristle_stiffness", 0.0)}.get(self.key, 0.0)

    def state_from_force(self, physical: Mapping[str, float], force: float, velocity: float,
                         normal_force: float) -> Optional[List[float]]:
        """Law state that gives friction force ``force`` [N] at v_r = ``velocity``, N = ``normal_force``."""
        if self.key == "dahl":  # F = k_t z
            return [force / physical["tangential_stiffness"]]
        if self.key == "lugre":  # F = sigma0 z (1 - sigma1 |v| / g) + (sigma1 + sigma2) v
            s0, s1, s2 = (physical["bristle_stiffness"], physical["bristle_damping"], physical["viscous_damping"])
            r = velocity / physical["stribeck_velocity"]
            g = normal_force * (physical["mu"] + (physical["mu_static"] - physical["mu"]) * math.exp(-r * r))
            factor = 1.0 - s1 * abs(velocity) / g
            if abs(factor) < 1e-6:
                return [force / s0]
            return [(force - (s1 + s2) * velocity) / (s0 * factor)]
        return None


_MU = _Param("mu", "mu", "-", (1e-4, 10.0), aliases=("friction_coefficient", "coulomb_coefficient", "mu_c"))
_EXCESS = _Param("mu_static_excess", "mu_s - mu", "-", (0.0, 10.0), strict=False)
_VS = _Param("stribeck_velocity", "v_s", "m/s", (1e-7, 10.0), aliases=("v_s",), scan=True)

_LAWS: Dict[str, _LawDef] = {
    "dahl": _LawDef(
        "dahl", "Dahl",
        (_MU,
         _Param("tangential_stiffness", "k_t", "N/m", (10.0, 1e10), aliases=("k_t",), scan=True),
         _Param("exponent", "alpha", "-", (0.5, 4.0), strict=False, aliases=("alpha",), default=1.0)),
        ("mu", "tangential_stiffness", "exponent"), 1),
    "lugre": _LawDef(
        "lugre", "LuGre",
        (_MU, _EXCESS, _VS,
         _Param("bristle_stiffness", "sigma_0", "N/m", (10.0, 1e10), aliases=("sigma0", "sigma_0"), scan=True),
         _Param("bristle_damping", "sigma_1", "N s/m", (0.0, math.nan), strict=False, aliases=("sigma1", "sigma_1"),
                scan=True),
         _Param("viscous_damping", "sigma_2", "N s/m", (0.0, math.nan), strict=False, aliases=("sigma2", "sigma_2"),
                scan=True, default=0.0)),
        ("mu", "mu_static", "stribeck_velocity", "bristle_stiffness", "bristle_damping", "viscous_damping"), 1),
    "stribeck": _LawDef(
        "stribeck", "Stribeck",
        (_MU, _EXCESS, _VS,
         _Param("shape_exponent", "delta", "-", (0.2, 10.0), aliases=("delta",), default=2.0),
         _Param("viscous_coefficient", "sigma_v", "N s/m", (0.0, math.nan), strict=False, aliases=("sigma_v",),
                scan=True, default=0.0)),
        ("mu", "mu_static", "stribeck_velocity", "shape_exponent", "viscous_coefficient"), 0),
}

#: Fit variables per law: {law: {name: (symbol, unit, default bounds)}} (bounds= and initial_guess= keys).
#: An upper bound NaN (damping coefficients, N s/m) is set from the record: 10 max|F| / max|v_r|, a damping
#: force ten times the largest measured force. Coefficients that may be zero are searched linearly from 0.
LAW_PARAMETERS = {k: {p.name: (p.symbol, p.unit, p.bounds) for p in d.params} for k, d in _LAWS.items()}

_PHYSICAL_META = {  # symbol, unit of reported parameters
    "mu": ("mu", "-"), "mu_static": ("mu_s", "-"), "stribeck_velocity": ("v_s", "m/s"),
    "tangential_stiffness": ("k_t", "N/m"), "exponent": ("alpha", "-"), "bristle_stiffness": ("sigma_0", "N/m"),
    "bristle_damping": ("sigma_1", "N s/m"), "viscous_damping": ("sigma_2", "N s/m"),
    "shape_exponent": ("delta", "-"), "viscous_coefficient": ("sigma_v", "N s/m"), "initial_force": ("F_0", "N"),
}

_INITIAL_FORCE = "initial_force"


def _law_def(law: Any) -> _LawDef:
    if isinstance(law, type) and law in (Dahl, LuGre, Stribeck):
        law = law.__name__
    key = str(law).lower().replace("-", "").replace("_", "")
    if key not in _LAWS:
        raise InvalidParameterError(f"law must be one of 'dahl', 'lugre', 'stribeck' (got {law!r})", "law")
    return _LAWS[key]


def _canonical(lawdef: _LawDef, key: str, where: str, extra: Sequence[str] = ()) -> str:
    """Map a user key (name or alias) to a fit-variable name; mu_static passes through for guesses/fixed."""
    for p in lawdef.params:
        if key == p.name or key in p.aliases:
            return p.name
    if key in ("mu_static", "static_coefficient", "mu_s") and lawdef.key != "dahl":
        return "mu_static"
    if key in extra:
        return key
    names = [p.name for p in lawdef.params] + list(extra)
    raise InvalidParameterError(f"{where}: unknown parameter {key!r} for {lawdef.name}; expected one of "
                                f"{', '.join(names)}", f"{where}[{key!r}]")


# ============================================================================================ fit specification
@dataclass
class _Var:
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
        if not (math.isfinite(self.lower) and math.isfinite(self.upper)):
            return np.array([])
        if self.log:
            n = max(5, int(math.ceil(points_per_decade * math.log10(self.upper / self.lower))) + 1)
            return np.geomspace(self.lower, self.upper, n)
        return np.linspace(self.lower, self.upper, 11)


@dataclass
class _Spec:
    """Fitted variables, fixed values, and the map to reported (physical) parameters."""

    variables: List[_Var]
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

    def with_refs(self, q: Mapping[str, float]) -> "_Spec":
        """The same spec re-centred at ``q`` (x = 0 there)."""
        variables = []
        for v in self.variables:
            ref = q[v.name]
            scale = v.scale if v.log else (abs(ref) if ref != 0.0 else v.scale)
            variables.append(_Var(v.name, v.lower, v.upper, ref, v.log, scale, v.magnitude_floor))
        return _Spec(variables, dict(self.fixed), self.physical)


def _make_var(param: _Param, bounds: Tuple[float, float], ref: float, floor: float = 0.0) -> _Var:
    """Log space when the lower bound is positive; else linear, scaled by |ref| (or a tenth of the range)."""
    lower, upper = bounds
    use_log = lower > 0.0
    if use_log:
        scale = 1.0
    else:
        scale = abs(ref) if ref != 0.0 else ((upper - lower) / 10.0 if math.isfinite(upper - lower) else 1.0)
    return _Var(param.name, lower, upper, ref, use_log, scale, floor)


# ============================================================================================ input validation
def _reject(message: str, parameter: str):
    raise InvalidParameterError(message, parameter)


def _vector(name: str, value: Any, n: Optional[int] = None) -> np.ndarray:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        _reject(f"{name} must be a 1-D array of numbers", name)
    if array.ndim != 1:
        _reject(f"{name} must be a 1-D array (got shape {array.shape})", name)
    if n is not None and array.size != n:
        _reject(f"{name} must have as many samples as t ({n}); got {array.size}", name)
    if not np.all(np.isfinite(array)):
        bad = int(np.flatnonzero(~np.isfinite(array))[0])
        _reject(f"{name} must be finite (sample {bad} is {array[bad]})", name)
    return array


def _time(t: Any) -> np.ndarray:
    t = _vector("t", t)
    if t.size < 3:
        _reject(f"t must hold at least 3 samples (got {t.size})", "t")
    steps = np.diff(t)
    if not np.all(steps > 0.0):
        bad = int(np.flatnonzero(~(steps > 0.0))[0]) + 1
        _reject(f"t must be strictly increasing (t[{bad}] = {t[bad]} after {t[bad - 1]})", "t")
    return t


def _normal_force(normal_force: Any, t: np.ndarray) -> Tuple[Union[float, Tuple[np.ndarray, np.ndarray]], float]:
    """-> (what KinematicRig takes, N at t[0]); accepts a number, an array like t, or a (t_N, N) pair."""
    if normal_force is None:
        _reject("normal_force is required: a positive number [N] or an array of N(t) samples", "normal_force")
    if np.ndim(normal_force) == 0 and not isinstance(normal_force, (tuple, list)):
        try:
            value = float(normal_force)
        except (TypeError, ValueError):
            _reject(f"normal_force must be a number or an array (got {type(normal_force).__name__})", "normal_force")
        if not (math.isfinite(value) and value > 0.0):
            _reject(f"normal_force must be positive and finite (got {value})", "normal_force")
        return value, value
    if isinstance(normal_force, tuple) and len(normal_force) == 2:
        t_n = _time(normal_force[0])
        n = _vector("normal_force", normal_force[1], t_n.size)
        if t_n[0] > t[0] or t_n[-1] < t[-1]:
            _reject(f"normal_force samples must cover t = [{t[0]}, {t[-1]}] s (they cover [{t_n[0]}, {t_n[-1]}])",
                    "normal_force")
    else:
        t_n, n = t, _vector("normal_force", normal_force, t.size)
    if not np.all(n > 0.0):
        bad = int(np.flatnonzero(~(n > 0.0))[0])
        _reject(f"normal_force must be positive at every sample (sample {bad} is {n[bad]})", "normal_force")
    return (t_n, n), float(np.interp(t[0], t_n, n))


def _weights(weights: Any, n: int) -> Optional[np.ndarray]:
    if weights is None:
        return None
    w = _vector("weights", weights, n)
    if not np.all(w >= 0.0) or not np.any(w > 0.0):
        _reject("weights must be non-negative with at least one positive (they multiply the residuals, "
                "1/sigma_i)", "weights")
    return w


def _check_method(method: str) -> str:
    if method not in METHODS:
        _reject(f"method must be one of {', '.join(METHODS)} (got {method!r})", "method")
    return method


def _user_bounds(lawdef: _LawDef, bounds: Optional[Bounds], extra: Mapping[str, _Param],
                 force_scale: float = 1.0, speed_scale: float = 1.0) -> Dict[str, Tuple]:
    damping_max = 10.0 * force_scale / speed_scale
    out: Dict[str, Tuple[float, float]] = {
        p.name: (p.bounds[0], damping_max if math.isnan(p.bounds[1]) else p.bounds[1]) for p in lawdef.params}
    out.update({name: p.bounds for name, p in extra.items()})
    for key, pair in (bounds or {}).items():
        name = _canonical(lawdef, key, "bounds", tuple(extra))
        where = f"bounds[{key!r}]"
        if name == "mu_static":
            _reject(f"{where}: mu_static is fitted as mu_static_excess = mu_static - mu >= 0; bound that instead",
                    where)
        try:
            lo, hi = (float(pair[0]), float(pair[1]))
        except (TypeError, ValueError, IndexError):
            _reject(f"{where} must be a (lower, upper) pair of numbers (got {pair!r})", where)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            _reject(f"{where} must satisfy lower < upper (got ({lo}, {hi}))", where)
        param = extra.get(name) or lawdef.param(name)
        if param.minimum is not None and not math.isinf(-param.minimum):
            if lo < param.minimum or (param.strict and lo == param.minimum):
                rule = ">" if param.strict else ">="
                _reject(f"{where}: the lower bound must be {rule} {param.minimum} for {name} (got {lo})", where)
        out[name] = (lo, hi)
    return out


def _user_values(lawdef: _LawDef, values: Optional[Mapping[str, float]], where: str,
                 extra: Sequence[str] = ()) -> Dict[str, float]:
    out: Dict[str, float] = {}
    for key, value in (values or {}).items():
        name = _canonical(lawdef, key, where, extra)
        try:
            value = float(value)
        except (TypeError, ValueError):
            _reject(f"{where}[{key!r}] must be a number (got {value!r})", f"{where}[{key!r}]")
        if not math.isfinite(value):
            _reject(f"{where}[{key!r}] must be finite (got {value})", f"{where}[{key!r}]")
        out[name] = value
    return out


def _resolve_mu_static(values: Dict[str, float], mu: Optional[float], where: str) -> None:
    """Turn a given mu_static into mu_static_excess (needs mu)."""
    if "mu_static" not in values:
        return
    mu_static = values.pop("mu_static")
    if mu is None:
        _reject(f"{where}['mu_static'] needs mu in {where} too (mu_static is fitted as mu_static - mu); "
                f"or give mu_static_excess", f"{where}['mu_static']")
    if mu_static < mu:
        _reject(f"{where}['mu_static'] must be >= mu ({mu}); got {mu_static}", f"{where}['mu_static']")
    values["mu_static_excess"] = mu_static - mu


def _build_spec(lawdef: _LawDef, fitted: Sequence[str], guess: Mapping[str, float], fixed: Mapping[str, float],
                bounds: Mapping[str, Tuple[float, float]], extra: Mapping[str, _Param],
                floors: Mapping[str, float], user_guess: Mapping[str, float]) -> _Spec:
    variables = []
    for name in fitted:
        param = extra.get(name) or lawdef.param(name)
        lo, hi = bounds[name]
        value = guess[name]
        if not lo <= value <= hi:
            if name in user_guess:
                _reject(f"initial_guess[{name!r}] = {value} is outside its bounds [{lo}, {hi}]",
                        f"initial_guess[{name!r}]")
            value = min(max(value, lo), hi)
        if lo > 0.0 and value <= 0.0:
            value = lo
        variables.append(_make_var(param, (lo, hi), value, floors.get(name, 0.0)))
    for name, value in fixed.items():
        param = extra.get(name) or (lawdef.param(name) if name != "mu_static" else None)
        if param is not None and (value < param.minimum or (param.strict and value == param.minimum)):
            _reject(f"fixed[{name!r}] = {value} is not a valid {name}", f"fixed[{name!r}]")

    def physical(q: Mapping[str, float]) -> Dict[str, float]:
        out = lawdef.physical(q)
        for name in extra:
            if name in q:
                out[name] = q[name]
        return out

    return _Spec(variables, dict(fixed), physical)


# ============================================================================================ the fitting core
class _Evaluator:
    """Residual of one parameter vector = one simulation; counts runs and failures (thread-safe)."""

    def __init__(self, model: Callable[[Dict[str, float]], np.ndarray], measured: np.ndarray,
                 weights: Optional[np.ndarray], spec: _Spec) -> None:
        self.model = model
        self.measured = measured
        self.weights = weights
        self.spec = spec
        scale = float(np.max(np.abs(measured))) + float(np.std(measured)) + 1.0
        self.penalty = 10.0 * scale  # a failed run: large but finite residual at every sample
        self.n_evaluations = 0
        self.n_failed = 0
        self.last_error = ""
        self._lock = threading.Lock()
        self._last: Optional[Tuple[bytes, np.ndarray]] = None

    def signal(self, q: Dict[str, float]) -> Optional[np.ndarray]:
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


_DE_SEED_KEYWORD = "rng" if "rng" in inspect.signature(optimize.differential_evolution).parameters else "seed"


@dataclass
class _Options:
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


def _coordinate_scan(evaluator: _Evaluator, spec: _Spec, names: Sequence[str], rounds: int = 1,
                     patience: int = 4) -> _Spec:
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
    return spec.with_refs(q)


def _least_squares(evaluator: _Evaluator, spec: _Spec, x0: np.ndarray, opts: _Options):
    lower, upper = spec.x_bounds()
    x0 = np.clip(x0, lower, upper)
    return optimize.least_squares(
        evaluator.residual, x0, jac=lambda x: evaluator.jacobian(x, opts.diff_step), bounds=(lower, upper),
        method="trf", x_scale=1.0,
        loss=opts.loss, ftol=opts.ftol, xtol=opts.xtol, gtol=opts.gtol, max_nfev=opts.max_nfev)


def _differential_evolution(evaluator: _Evaluator, spec: _Spec, x0: Optional[np.ndarray], opts: _Options):
    lower, upper = spec.x_bounds()
    if not (np.all(np.isfinite(lower)) and np.all(np.isfinite(upper))):
        bad = spec.names[int(np.flatnonzero(~(np.isfinite(lower) & np.isfinite(upper)))[0])]
        _reject(f"differential_evolution needs finite bounds; bounds[{bad!r}] is not", f"bounds[{bad!r}]")
    kwargs: Dict[str, Any] = dict(maxiter=int(opts.maxiter), popsize=int(opts.popsize), tol=float(opts.tol),
                                  polish=False, init="latinhypercube")
    kwargs[_DE_SEED_KEYWORD] = opts.seed
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


@dataclass
class _Fit:
    """What the core returns: the solution and its uncertainty, in fit variables and reported parameters."""

    spec: _Spec
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


def _fit(model: Callable[[Dict[str, float]], np.ndarray], measured: np.ndarray, weights: Optional[np.ndarray],
         spec: _Spec, *, method: str, opts: _Options, scan_names: Sequence[str] = (),
         x0_given: bool = False) -> _Fit:
    """The fitting core shared by the kinematic and the rig-level identification.

    ``model(q)`` returns the simulated signal at the measured samples for fit variables ``q`` (raising
    SimulationError on a failed run); ``spec`` gives the searched variables, bounds, fixed values and the map to
    reported parameters.
    """
    evaluator = _Evaluator(model, measured, weights, spec)
    messages = []
    success = True
    if method == "least_squares":
        if opts.scan and scan_names:
            spec = _coordinate_scan(evaluator, spec, scan_names, rounds=2 if len(scan_names) > 1 else 1)
            evaluator.spec = spec
        ls = _least_squares(evaluator, spec, np.zeros(len(spec.variables)), opts)
        x = ls.x
        success = bool(ls.success)
        messages.append(f"least_squares: {ls.message.rstrip('.')}")
    else:
        de = _differential_evolution(evaluator, spec, np.zeros(len(spec.variables)) if x0_given else None, opts)
        x = np.asarray(de.x, dtype=float)
        messages.append(f"differential_evolution ({de.nit} generations): {str(de.message).rstrip('.')}")
        success = bool(de.success)
        if opts.polish:
            ls = _least_squares(evaluator, spec, x, opts)
            if evaluator.cost(ls.x) <= evaluator.cost(x):
                x = ls.x
            success = success or bool(ls.success)
            messages.append(f"least_squares polish: {ls.message.rstrip('.')}")

    q = spec.q(x)
    signal = evaluator.signal(q)
    ran = signal is not None
    if not ran:
        success = False
        messages.append(f"the simulation at the solution failed ({evaluator.last_error})")
        signal = np.full_like(measured, np.nan)
    residual = signal - measured
    weighted = residual if weights is None else residual * weights
    n, m = len(spec.variables), int(np.count_nonzero(weights)) if weights is not None else measured.size
    dof = max(m - n, 1)
    s2 = float(weighted @ weighted) / dof if np.all(np.isfinite(weighted)) else math.nan

    jac = evaluator.jacobian(x, opts.jacobian_step, central=True) if ran and n else np.zeros((m, n))
    uncertainty = _uncertainty(spec, x, jac, s2, opts)
    return _Fit(spec=spec, x=x, q=q, signal=signal, residual=residual, success=success,
                message="; ".join(messages), n_evaluations=evaluator.n_evaluations, n_failed=evaluator.n_failed,
                **uncertainty)


def _at_bound(var: _Var, value: float) -> int:
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


def _uncertainty(spec: _Spec, x: np.ndarray, jac: np.ndarray, s2: float, opts: _Options) -> Dict[str, Any]:
    """Covariance s^2 (J^T J)^-1, chain rule to reported parameters, identifiability flags with reasons."""
    n = x.size
    q = spec.q(x)
    params = spec.physical(q)
    names = list(params)

    # reported parameters as functions of the fit variables: G = d params / d x = (d params / d q) diag(dq/dx)
    G = np.zeros((len(names), n))
    for i, var in enumerate(spec.variables):
        h = 1e-6 * max(abs(q[var.name]), var.scale if not var.log else 0.0, 1e-300)
        bumped = dict(q)
        bumped[var.name] = q[var.name] + h
        p1 = spec.physical(bumped)
        dq_dx = var.dq_dx(x[i])
        for j, name in enumerate(names):
            G[j, i] = (p1[name] - params[name]) / h * dq_dx
    G[np.abs(G) < 1e-12 * (np.abs(G).max() if G.size else 1.0)] = 0.0
    fitted = tuple(name for j, name in enumerate(names) if np.any(G[j] != 0.0))

    # SVD of the Jacobian in the (log / scaled) search variables
    if n:
        _, sv, vt = np.linalg.svd(jac, full_matrices=False)
    else:
        sv, vt = np.zeros(0), np.zeros((0, 0))
    s_max = float(sv[0]) if sv.size else 0.0
    null = sv <= max(s_max, 1e-300) * 1e-12  # numerically singular: no covariance along these
    near_null = sv < s_max * opts.rcond
    condition = float(s_max / sv[-1]) if sv.size and sv[-1] > 0 else math.inf
    inv = np.where(null, 0.0, 1.0 / np.where(null, 1.0, sv) ** 2)
    cov_x = s2 * (vt.T * inv) @ vt if n else np.zeros((0, 0))
    in_null = np.zeros(n, bool)
    for k in np.flatnonzero(null):
        in_null |= np.abs(vt[k]) > 1e-8

    cov_p = G @ cov_x @ G.T
    p_in_null = (np.abs(G) > 0) @ in_null > 0 if n else np.zeros(len(names), bool)
    var_p = np.diag(cov_p).copy()
    var_p[p_in_null] = math.inf
    stderr_all = np.sqrt(np.maximum(var_p, 0.0))

    # per fit-variable flags that propagate to the reported parameters built from them
    var_reasons: List[List[str]] = [[] for _ in range(n)]  # "{name}" is replaced when reported
    for i, var in enumerate(spec.variables):
        side = _at_bound(var, q[var.name])
        if side:
            which, value = ("lower", var.lower) if side < 0 else ("upper", var.upper)
            var_reasons[i].append(f"{{name}}at its {which} bound {value:.4g}: the data push it out of the "
                                  f"search range, so its value and standard error are not determined")
    partners: Dict[int, set] = {}
    smallest: Dict[int, float] = {}
    for k in np.flatnonzero(near_null):  # directions the data barely see: which variables make them up
        weights = np.abs(vt[k])
        members = [i for i in range(n) if weights[i] >= 0.3 * weights.max()]
        ratio = sv[k] / s_max if s_max > 0 else 0.0
        for i in members:
            partners.setdefault(i, set()).update(j for j in members if j != i)
            smallest[i] = min(smallest.get(i, math.inf), ratio)
    for i, others in sorted(partners.items()):
        name = spec.variables[i].name
        detail = f"singular value ratio {smallest[i]:.1e} < rcond {opts.rcond:g} of the log-scaled Jacobian"
        if not others:
            var_reasons[i].append(f"the fitted signal is almost insensitive to {name} ({detail})")
        else:
            var_reasons[i].append(f"{name} is nearly interchangeable with "
                                  f"{', '.join(spec.variables[j].name for j in sorted(others))} ({detail})")

    # correlations
    fitted_idx = [names.index(nm) for nm in fitted]
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
        for i in np.flatnonzero(G[j]):
            var_name = spec.variables[i].name
            label = "" if var_name == name else f"{var_name} "
            why.extend(r.replace("{name}", label) for r in var_reasons[i] if r.replace("{name}", label) not in why)
        scale = max(abs(params[name]), floors.get(name, 0.0))
        rel = se / scale if scale > 0 else math.inf
        if p_in_null[j]:
            why.append("the Jacobian is singular along it: the data do not determine it (infinite standard error)")
        elif not math.isfinite(s2):
            why.append("no finite residual at the solution")
        elif rel > opts.max_relative_stderr:
            text = f"relative standard error {100 * rel:.3g}% > {100 * opts.max_relative_stderr:.3g}%"
            a = fitted.index(name)
            partners = [fitted[b] for b in range(len(fitted))
                        if b != a and np.isfinite(corr[a, b]) and abs(corr[a, b]) > 0.95]
            if partners:
                text += f" (correlation > 0.95 with {', '.join(partners)})"
            why.append(text)
        identifiable[name] = not why
        reasons[name] = "; ".join(why) if why else f"identified: relative standard error {100 * rel:.2g}%"
    return dict(params=params, fitted=fitted, stderr=stderr, covariance=cov_f, correlation=corr,
                identifiable=identifiable, reasons=reasons, singular_values=sv, condition_number=condition)


# ============================================================================================ result
@dataclass
class IdentificationResult:
    """Fitted friction law with uncertainty and identifiability.

    Attributes
    ----------
    law_name : str
        "Dahl", "LuGre" or "Stribeck".
    law : fs.Dahl | fs.LuGre | fs.Stribeck
        Ready to use, e.g. ``fs.AxialVibrationRig(friction=result.law)``.
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
            symbol, unit = _PHYSICAL_META.get(name, (name, ""))
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
            symbol, unit = _PHYSICAL_META.get(name, (name, ""))
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
    law_params = {k: fit.params[k] for k in lawdef.physical_names}
    law = lawdef.build(law_params)
    residual = fit.residual
    ss_res = float(residual @ residual)
    centred = measured - measured.mean()
    ss_tot = float(centred @ centred)
    return IdentificationResult(
        law_name=lawdef.name, law=law, params=dict(fit.params), stderr=fit.stderr, fitted=fit.fitted,
        covariance=fit.covariance, correlation=fit.correlation, identifiable=fit.identifiable, reasons=fit.reasons,
        rms_residual=math.sqrt(ss_res / residual.size), r_squared=1.0 - ss_res / ss_tot if ss_tot > 0 else math.nan,
        n_samples=int(measured.size), n_evaluations=fit.n_evaluations, n_failed=fit.n_failed, success=fit.success,
        message=fit.message, method=method, experiment=experiment, signal_name=signal_name, t=t, measured=measured,
        model=fit.signal, rig=rig, initial_state=initial_state,
        bounds={v.name: (v.lower, v.upper) for v in fit.spec.variables}, singular_values=fit.singular_values,
        condition_number=fit.condition_number, elapsed=time.perf_counter() - started)


def _options(kwargs: Dict[str, Any]) -> _Options:
    known = _Options.__dataclass_fields__
    unknown = [k for k in kwargs if k not in known]
    if unknown:
        raise TypeError(f"unexpected keyword argument(s): {', '.join(unknown)}; solver options are "
                        f"{', '.join(known)}")
    opts = _Options(**kwargs)
    for name in ("maxiter", "popsize", "workers"):
        value = getattr(opts, name)
        if isinstance(value, bool) or not float(value).is_integer() or value < 1:
            _reject(f"{name} must be a positive whole number (got {value!r})", name)
    for name in ("tol", "diff_step", "max_relative_stderr", "rcond", "jacobian_step"):
        value = getattr(opts, name)
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            _reject(f"{name} must be positive and finite (got {value!r})", name)
    return opts


# ============================================================================================ simulations
#: Steps allowed per run: max(_STEP_CAP, _STEPS_PER_SAMPLE * samples). A Dormand-Prince run that needs more is
#: stiff (Dahl with a large k_t relaxes at k_t |v_r| / (mu N), far faster than the record) and is redone with
#: CVODE BDF under the same cap; a BDF run that needs more counts as failed (Dahl with alpha < 1 reaches
#: saturation in finite time, where its right-hand side is not Lipschitz, and both integrators crawl there).
_STEP_CAP = 20_000
_STEPS_PER_SAMPLE = 50


def _simulate_kwargs(simulate_options: Optional[Mapping[str, Any]], rtol: float,
                     atol: Optional[float]) -> Dict[str, Any]:
    for name, value in (("rtol", rtol), ("atol", atol)):
        if value is None and name == "atol":
            continue
        if isinstance(value, bool) or not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            _reject(f"{name} must be positive and finite (got {value!r})", name)
    sim_kwargs = dict(simulate_options or {})
    for reserved in ("output_times", "t_start", "t_end", "rtol", "atol"):
        if reserved in sim_kwargs:
            _reject(f"simulate_options[{reserved!r}] is set by the fit (use the rtol= / atol= arguments for "
                    f"the tolerances)", f"simulate_options[{reserved!r}]")
    sim_kwargs.update(rtol=float(rtol))
    return sim_kwargs


def _force_atol(atol: Optional[float], measured: np.ndarray) -> float:
    """Absolute tolerance on the fitted force [N]: given, or 1e-6 of the record's largest force."""
    if atol is not None:
        return float(atol)
    return 1e-6 * (float(np.max(np.abs(measured))) or 1.0)


def _simulate(rig: Any, t: np.ndarray, sim_kwargs: Mapping[str, Any],
              relative_velocity: Optional[Callable[[Any], np.ndarray]] = None):
    """One run recorded at the samples ``t``.

    Unless the caller chose the integrator or the step limit, a run that needs more than the step cap (see
    _STEP_CAP) is redone with CVODE BDF under the same cap. With ``relative_velocity(result)`` (v_r at the
    recorded rows), the recorded branch is checked against sgn(v_r): a switch the integrator stepped over (a
    short excursion of v_r through zero inside one step) leaves the law on the wrong branch, and such a run is
    redone (rtol / 100, then CVODE BDF, then a step limit of one sample spacing) before it counts as failed.
    """
    kwargs = dict(sim_kwargs, output_times=t, t_start=float(t[0]))

    cap = max(_STEP_CAP, _STEPS_PER_SAMPLE * t.size)

    def run(options: Dict[str, Any]):
        if "method" in options or "max_steps" in options:
            return simulate(rig, float(t[-1]), **options)
        try:
            return simulate(rig, float(t[-1]), max_steps=cap, **options)
        except SimulationError:
            return simulate(rig, float(t[-1]), method="cvode_bdf", max_steps=cap, **options)

    result = run(kwargs)
    if relative_velocity is None:
        return result
    tight = max(kwargs.get("rtol", 1e-8) * 1e-2, 1e-12)
    retries = [dict(kwargs, rtol=tight), dict(kwargs, rtol=tight, max_step=float(np.min(np.diff(t))))]
    if "method" not in kwargs:
        retries.insert(1, dict(kwargs, method="cvode_bdf"))
    for retry in retries + [None]:
        v = np.asarray(relative_velocity(result))
        tol = 1e-6 * (float(np.max(np.abs(v))) or 1.0)
        wrong = (result.mode != 0) & (result.mode * v < -tol)
        if not np.any(wrong):
            return result
        if retry is not None:
            result = run(retry)
    first = float(result.t[np.flatnonzero(wrong)[0]])
    raise SimulationError(f"the contact branch disagrees with sgn(v_r) from t = {first:g} s (a missed switch)",
                          first)


# ============================================================================================ kinematic fits
def _data_guess(lawdef: _LawDef, v: np.ndarray, force: np.ndarray, n_abs: np.ndarray) -> Dict[str, float]:
    """Starting values from the record (refined by a coarse scan and least_squares).

    Dahl: mu from the saturated plateau of |F| / N. Stribeck / LuGre: the sliding branch at the faster half of
    the samples, sgn(v_r) F = mu N + sigma v_r, fitted as a line (mu from the intercept, sigma_2 / sigma_v
    from the slope); mu_static from the top 1 % of |F| / N.
    """
    ratio = np.abs(force) / n_abs
    speed = np.abs(v)
    top = float(np.quantile(ratio, 0.95))
    mu = float(np.median(ratio[ratio >= 0.9 * top]))  # the saturated plateau, unbiased by the noise
    viscous = 0.0
    if lawdef.key != "dahl":
        fast = speed >= np.quantile(speed, 0.5)
        if np.count_nonzero(fast) >= 3 and np.ptp(speed[fast]) > 0:
            slope, intercept = np.polyfit(speed[fast], np.sign(v[fast]) * force[fast] / n_abs[fast], 1)
            if slope > 0 and intercept > 0:
                mu = float(intercept)
                viscous = float(slope * np.median(n_abs))
            else:
                mu = float(np.median(ratio[fast]))
    guess = {"mu": max(mu, 1e-3)}
    peak = float(np.quantile(ratio, 0.99))
    guess["mu_static_excess"] = max(peak - guess["mu"], 0.1 * guess["mu"])
    moving = speed[speed > 0]
    typical_speed = float(np.quantile(moving, 0.9)) if moving.size else 1e-3
    guess["stribeck_velocity"] = max(0.1 * typical_speed, 1e-6)
    guess["tangential_stiffness"] = 1e5
    guess["bristle_stiffness"] = 1e5
    guess["bristle_damping"] = 0.0
    guess["viscous_damping"] = viscous
    guess["viscous_coefficient"] = viscous
    guess["exponent"] = 1.0
    guess["shape_exponent"] = 2.0
    return guess


def _identify_kinematic(law: Any, t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                        method: str = "least_squares", bounds: Optional[Bounds] = None,
                        initial_guess: Optional[Mapping[str, float]] = None,
                        fixed: Optional[Mapping[str, float]] = None,
                        initial_state: Union[str, float, Sequence[float]] = "measured",
                        weights: Any = None, rtol: float = 1e-7, atol: Optional[float] = None,
                        simulate_options: Optional[Mapping[str, Any]] = None,
                        **solver_options: Any) -> IdentificationResult:
    started = time.perf_counter()
    lawdef = _law_def(law)
    method = _check_method(method)
    opts = _options(solver_options)
    t = _time(t)
    v = _vector("relative_velocity", relative_velocity, t.size)
    force = _vector("friction_force", friction_force, t.size)
    n_arg, n0 = _normal_force(normal_force, t)
    n_samples = np.full(t.size, n_arg) if isinstance(n_arg, float) else np.interp(t, n_arg[0], n_arg[1])
    w = _weights(weights, t.size)
    sim_kwargs = _simulate_kwargs(simulate_options, rtol, atol)

    # the initial law state
    extra: Dict[str, _Param] = {}
    force_scale = float(np.max(np.abs(force))) or 1.0
    fixed_state: Optional[List[float]] = None
    if isinstance(initial_state, str):
        if initial_state not in ("measured", "fit", "zero"):
            _reject(f"initial_state must be 'measured', 'fit', 'zero' or the law state (got {initial_state!r})",
                    "initial_state")
        if lawdef.state_count == 0 and initial_state == "fit":
            _reject(f"initial_state='fit': {lawdef.name} has no internal state", "initial_state")
        if initial_state == "fit":
            extra[_INITIAL_FORCE] = _Param(_INITIAL_FORCE, "F_0", "N", (-2.0 * force_scale, 2.0 * force_scale),
                                           minimum=-math.inf, strict=False)
        elif initial_state == "zero" and lawdef.state_count:
            fixed_state = [0.0] * lawdef.state_count
    else:
        if lawdef.state_count == 0:
            _reject(f"initial_state: {lawdef.name} has no internal state", "initial_state")
        fixed_state = list(_vector("initial_state", np.atleast_1d(initial_state), lawdef.state_count))

    all_bounds = _user_bounds(lawdef, bounds, extra, force_scale, float(np.max(np.abs(v))) or 1.0)
    user_guess = _user_values(lawdef, initial_guess, "initial_guess", tuple(extra))
    user_fixed = _user_values(lawdef, fixed, "fixed")
    _resolve_mu_static(user_guess, user_guess.get("mu", user_fixed.get("mu")), "initial_guess")
    _resolve_mu_static(user_fixed, user_fixed.get("mu"), "fixed")
    for name in user_fixed:
        if name in user_guess:
            _reject(f"{name} is both fixed and given an initial guess", f"fixed[{name!r}]")

    guess = _data_guess(lawdef, v, force, n_samples)
    if _INITIAL_FORCE in extra:
        guess[_INITIAL_FORCE] = float(force[0])
    guess.update(user_guess)
    fitted_names: List[str] = []
    fixed_values: Dict[str, float] = {}
    for p in list(lawdef.params) + list(extra.values()):
        if p.name in user_fixed:
            fixed_values[p.name] = user_fixed[p.name]
        else:
            fitted_names.append(p.name)
    if len(fitted_names) >= t.size:
        _reject(f"t: {t.size} samples cannot determine {len(fitted_names)} parameters", "t")
    floors = {_INITIAL_FORCE: force_scale}
    spec = _build_spec(lawdef, fitted_names, guess, fixed_values, all_bounds, extra, floors, user_guess)
    scan_names = [p.name for p in lawdef.params if p.scan and p.name in fitted_names and p.name not in user_guess]
    # stiffness first: the other scans are only meaningful once the force reaches its sliding level
    scan_names.sort(key=lambda name: 0 if name in ("tangential_stiffness", "bristle_stiffness") else 1)

    def rig_for(q: Mapping[str, float]):
        physical = lawdef.physical(q)
        law_obj = lawdef.build(physical)
        state = None
        if lawdef.state_count:
            if fixed_state is not None:
                state = fixed_state
            else:
                f0 = q[_INITIAL_FORCE] if _INITIAL_FORCE in q else float(force[0])
                state = lawdef.state_from_force(physical, f0, float(v[0]), n0)
        return KinematicRig(law_obj, relative_velocity=(t, v), normal_force=n_arg, initial_state=state), state

    force_atol = _force_atol(atol, force)
    duration, v_max = float(t[-1] - t[0]), float(np.max(np.abs(v))) or 1.0

    def model(q: Mapping[str, float]) -> np.ndarray:
        rig, _ = rig_for(q)
        kwargs = dict(sim_kwargs)
        if "atol_per_state" not in kwargs:  # the force F = k z must be accurate, whatever the stiffness
            state_atol = [force_atol / lawdef.state_stiffness(lawdef.physical(q))] if lawdef.state_count else []
            kwargs["atol_per_state"] = state_atol + [force_atol * duration, force_atol * duration * v_max]
        return _simulate(rig, t, kwargs, relative_velocity=lambda result: v).friction_force

    fit = _fit(model, force, w, spec, method=method, opts=opts, scan_names=scan_names,
               x0_given=bool(user_guess))
    rig, state = rig_for(fit.q)
    return _result(fit, lawdef, method=method, experiment="kinematic rig", signal_name="friction_force", t=t,
                   measured=force, rig=rig, initial_state=state, started=started)


_COMMON_DOC = """
    Parameters
    ----------
    t : array, s
        Sample times, strictly increasing.
    relative_velocity : array, m/s
        Measured relative velocity v_r(t) at ``t`` (interpolated linearly between samples).
    friction_force : array, N
        Measured friction force F(t) (positive opposing positive v_r).
    normal_force : float or array or (t_N, N) pair, N
        Constant normal force, samples at ``t``, or its own samples covering ``t``; positive.
    method : {"least_squares", "differential_evolution"}
        Local trust-region least squares (after a coarse scan of the stiffness-like parameters that have no
        initial guess), or a global differential-evolution search over the bounds (the paper's genetic /
        particle-swarm role), deterministic for a given ``seed`` and polished by least_squares.
    bounds : dict, optional
        {name: (lower, upper)} in physical units, overriding the defaults (``LAW_PARAMETERS``). A lower bound
        > 0 makes the search logarithmic. mu_static is bounded through ``mu_static_excess`` = mu_static - mu.
    initial_guess : dict, optional
        Starting values (default: estimated from the record plus a coarse scan); with differential_evolution
        they seed the population. Names as the law's keywords or their symbols (k_t, alpha, v_s, sigma0, ...);
        mu_static needs mu given too.
    fixed : dict, optional
        Parameters held at the given values instead of fitted.
    initial_state : "measured" | "fit" | "zero" | float
        Law state at t[0]: from the first measured force (Dahl z0 = F0 / k_t; LuGre from F0 and v_r(t0)),
        fitted (reported as ``initial_force`` F_0 [N]), zero, or the law state itself (m).
    weights : array, optional
        Residual weights (1/sigma_i).
    rtol : float
        Relative tolerance of each run (a fit needs only moderate accuracy).
    atol : float, N, optional
        Absolute tolerance on the friction force (default 1e-6 of the largest measured force); the law state's
        tolerance is atol / k_t (or / sigma_0), so a stiff contact is resolved as accurately as a soft one.
    simulate_options : dict, optional
        Further keywords for :func:`frictionsim.simulate` (method, max_step, ...).
    **solver_options
        seed (0), polish (True), maxiter (100), popsize (15), tol (0.01), workers (1: threads for
        differential_evolution), max_nfev, diff_step (1e-3: forward-difference step in the search
        variables), ftol/xtol/gtol (1e-10), loss ("linear"; the covariance assumes it), max_relative_stderr (0.3: above it a parameter
        is flagged not identifiable), rcond (1e-4: singular-value ratio of the scaled Jacobian below which a
        direction counts as unidentifiable), jacobian_step (1e-2, central differences for the covariance, in
        the search variables), scan (True).

    Returns
    -------
    IdentificationResult

    Raises
    ------
    InvalidParameterError (a ValueError)
        Bad input; ``.parameter`` names it.
"""


def identify_dahl(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                  fit_exponent: bool = True, method: str = "least_squares", bounds: Optional[Bounds] = None,
                  initial_guess: Optional[Mapping[str, float]] = None, fixed: Optional[Mapping[str, float]] = None,
                  **options: Any) -> IdentificationResult:
    """Fit the Dahl law (paper 000, eq 9): mu [-], tangential_stiffness k_t [N/m], exponent alpha [-].

    ``fit_exponent=False`` holds alpha at ``initial_guess['exponent']`` or 1 (the paper's choice). k_t is
    only identifiable when the record contains force reversals (pre-sliding); with v_r of one sign and the
    force saturated at mu N, k_t and alpha are flagged not identifiable.
    """
    fixed = dict(fixed or {})
    if not fit_exponent and not any(k in fixed for k in ("exponent", "alpha")):
        guess = dict(initial_guess or {})
        fixed["exponent"] = guess.pop("exponent", guess.pop("alpha", 1.0))
        initial_guess = guess
    return _identify_kinematic("dahl", t, relative_velocity, friction_force, normal_force, method=method,
                               bounds=bounds, initial_guess=initial_guess, fixed=fixed, **options)


def identify_lugre(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                   fit_viscous: bool = True, method: str = "least_squares", bounds: Optional[Bounds] = None,
                   initial_guess: Optional[Mapping[str, float]] = None, fixed: Optional[Mapping[str, float]] = None,
                   **options: Any) -> IdentificationResult:
    """Fit the LuGre law: mu, mu_static [-], stribeck_velocity v_s [m/s], bristle_stiffness sigma_0 [N/m],
    bristle_damping sigma_1 [N s/m], viscous_damping sigma_2 [N s/m].

    ``fit_viscous=False`` holds sigma_2 at ``initial_guess['viscous_damping']`` or 0. sigma_1 only shows in
    fast pre-sliding transients: quasi-static data leave it flagged not identifiable.
    """
    fixed = dict(fixed or {})
    if not fit_viscous and not any(k in fixed for k in ("viscous_damping", "sigma2", "sigma_2")):
        guess = dict(initial_guess or {})
        fixed["viscous_damping"] = guess.pop("viscous_damping", 0.0)
        initial_guess = guess
    return _identify_kinematic("lugre", t, relative_velocity, friction_force, normal_force, method=method,
                               bounds=bounds, initial_guess=initial_guess, fixed=fixed, **options)


def identify_stribeck(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                      fit_shape_exponent: bool = True, fit_viscous: bool = True, method: str = "least_squares",
                      bounds: Optional[Bounds] = None, initial_guess: Optional[Mapping[str, float]] = None,
                      fixed: Optional[Mapping[str, float]] = None, **options: Any) -> IdentificationResult:
    """Fit the Stribeck sliding curve: mu, mu_static [-], stribeck_velocity v_s [m/s], shape_exponent delta [-],
    viscous_coefficient sigma_v [N s/m].

    In the kinematic rig the law gives its slip force on the branch sgn(v_r) (no stick, karnopp_band 0), so
    the data should sweep |v_r| through the Stribeck region (|v_r| ~ v_s) to identify v_s and delta.
    ``fit_shape_exponent=False`` / ``fit_viscous=False`` hold delta (default 2) / sigma_v (default 0).
    """
    fixed = dict(fixed or {})
    guess = dict(initial_guess or {})
    if not fit_shape_exponent and not any(k in fixed for k in ("shape_exponent", "delta")):
        fixed["shape_exponent"] = guess.pop("shape_exponent", guess.pop("delta", 2.0))
    if not fit_viscous and not any(k in fixed for k in ("viscous_coefficient", "sigma_v")):
        fixed["viscous_coefficient"] = guess.pop("viscous_coefficient", guess.pop("sigma_v", 0.0))
    return _identify_kinematic("stribeck", t, relative_velocity, friction_force, normal_force, method=method,
                               bounds=bounds, initial_guess=guess, fixed=fixed, **options)


def identify(law: Any, t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any,
             **kwargs: Any) -> IdentificationResult:
    """Dispatch to :func:`identify_dahl`, :func:`identify_lugre` or :func:`identify_stribeck` by ``law``
    ("dahl", "lugre", "stribeck", case-insensitive, or the class fs.Dahl / fs.LuGre / fs.Stribeck)."""
    lawdef = _law_def(law)
    function = {"dahl": identify_dahl, "lugre": identify_lugre, "stribeck": identify_stribeck}[lawdef.key]
    return function(t, relative_velocity, friction_force, normal_force, **kwargs)


for _f in (identify_dahl, identify_lugre, identify_stribeck):
    _f.__doc__ = (_f.__doc__ or "") + _COMMON_DOC
del _f
