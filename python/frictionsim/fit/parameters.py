"""The identifiable parameters of each friction law, read from the engine's own parameter table.

Every engine law describes itself (``Law.parameters``, :data:`frictionsim.FRICTION_LAWS`): names, symbols, units,
validity rules, defaults and typical values. The fit takes all of that from there. What only the fit needs (search
bounds, which parameters get a coarse grid scan, data-free starting values, extra aliases) is ONE table of search
hints keyed by parameter name, :data:`_HINTS`; a parameter without a hint gets bounds from its rule and typical
value (:func:`_generic_bounds`), so a new law's parameters are fittable without editing this file.

A parameter bounded below by another (``at_least``: mu_static >= mu) is fitted as ``<name>_excess`` = value - other
>= 0 (a box bound, which the searches handle, instead of a linear constraint, which they do not);
:meth:`LawDef.physical` maps it back.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, FrozenSet, List, Mapping, Optional, Sequence, Tuple

from ..errors import InvalidParameterError
from ..laws import law_classes
from ..validation import reject


@dataclass(frozen=True)
class Param:
    """A fit variable: a law keyword (mu, tangential_stiffness, ...) or a derived one (mu_static_excess)."""

    name: str
    symbol: str
    unit: str
    bounds: Tuple[float, float]  # default search bounds; upper NaN: from the data (see search_space.user_bounds)
    minimum: float = 0.0  # validity: > minimum (strict) or >= minimum
    strict: bool = True
    maximum: float = math.inf  # validity: < maximum (strict_max) or <= maximum
    aliases: Tuple[str, ...] = ()
    scan: bool = False  # coarse grid scan for a starting value when no initial guess is given
    default: Optional[float] = None  # value when held fixed and not given
    start: Optional[float] = None  # data-free starting value (else ``default``): the record may suggest better
    strict_max: bool = True
    tied: bool = False  # the engine rejects it moved alone (see tied_parameters): held unless given in fixed=

    def admits(self, value: float) -> bool:
        """Is ``value`` valid for this parameter (its rule's interval)?"""
        above = value > self.minimum if self.strict else value >= self.minimum
        below = value < self.maximum if self.strict_max else value <= self.maximum
        return above and below


@dataclass(frozen=True)
class _Hint:
    """What the fit needs beyond the engine's table, for one parameter name (in every law that has it)."""

    bounds: Optional[Tuple[float, float]] = None  # default search bounds (else _generic_bounds)
    scan: bool = False
    start: Optional[float] = None  # data-free starting value (else the law's default or example)
    aliases: Tuple[str, ...] = ()  # beyond the derived ones (the C++ field, the symbol, sigma_0 -> sigma0)
    fitted: bool = True  # False: never a fit variable, the constructor's default is used


#: Search hints by parameter name. An upper bound NaN (damping coefficients, N s/m) is set from the record:
#: 10 max|F| / max|v_r|, a damping force ten times the largest measured force. Coefficients that may be zero are
#: searched linearly from 0.
_HINTS: Dict[str, _Hint] = {
    # every law's spelling of mu (its C++ field and symbol) accepted for any law
    "mu": _Hint((1e-4, 10.0), aliases=("friction_coefficient", "coulomb_coefficient", "mu_c")),
    "stribeck_velocity": _Hint((1e-7, 10.0), scan=True),
    "tangential_stiffness": _Hint((10.0, 1e10), scan=True, start=1e5),
    "exponent": _Hint((0.5, 4.0)),
    "bristle_stiffness": _Hint((10.0, 1e10), scan=True),
    "bristle_damping": _Hint((0.0, math.nan), scan=True, start=0.0),
    "viscous_damping": _Hint((0.0, math.nan), scan=True),
    "viscous_coefficient": _Hint((0.0, math.nan), scan=True),
    "shape_exponent": _Hint((0.2, 10.0)),
    # z_ba / (mu N / sigma_0): the law needs < 1 (the ramp to z_max has positive width); 0.95 keeps the ramp at
    # least 5 % of the Coulomb deflection wide by default
    "breakaway_fraction": _Hint((0.0, 0.95)),
    # a simulation device, not a contact property; the kinematic rig refuses a band (it needs the force that
    # would stick)
    "karnopp_band": _Hint(fitted=False),
}

#: Units whose default upper search bound the record sets (NaN in the bounds, see above).
_DATA_SCALED_UNITS = ("N s/m",)
#: Unit of contact stiffnesses: dF/dz of a law state, and scanned first.
_STIFFNESS_UNIT = "N/m"


def _generic_bounds(record: Any) -> Tuple[float, float]:
    """Search bounds of a parameter without a hint, from its rule and typical value (``example``): a bounded
    rule's interval (an open end pulled in by 1 %); six decades around the example for a positive one; from 0 for
    a non-negative one (to the record's scale for a damping, else 1000 examples)."""
    lo, hi = record.lower, record.upper
    if math.isfinite(lo) and math.isfinite(hi):
        width = hi - lo
        return (lo + 0.01 * width if record.lower_open else lo, hi - 0.01 * width if record.upper_open else hi)
    example = record.example if math.isfinite(record.example) and record.example != 0.0 else 1.0
    if lo > 0.0 or (lo == 0.0 and record.lower_open):
        return max(abs(example) * 1e-3, lo), min(abs(example) * 1e3, hi)
    if lo == 0.0:
        return 0.0, math.nan if record.unit in _DATA_SCALED_UNITS else 1e3 * abs(example)
    return max(example - 1e3 * abs(example), lo), min(example + 1e3 * abs(example), hi)


def _aliases(record: Any, hint: _Hint) -> Tuple[str, ...]:
    """The names a user may give besides the keyword: the hint's, the C++ field, the symbol, and the symbol with
    a numeric subscript written without its underscore (sigma_0 -> sigma0)."""
    candidates = list(hint.aliases) + [record.field, record.symbol]
    head, _, subscript = record.symbol.rpartition("_")
    if head and subscript.isdigit():
        candidates.append(head + subscript)
    out: List[str] = []
    for alias in candidates:
        if alias and alias != record.name and alias not in out:
            out.append(alias)
    return tuple(out)


def _fit_param(record: Any, base: Optional[Param], tied: bool) -> Param:
    """The fit variable of one ``Law.parameters`` record; ``base`` is the fit variable of the parameter bounding it
    from below (``at_least``), when there is one: it is then fitted as the non-negative excess over that one."""
    if base is not None:
        default = None if record.default is None or base.default is None else record.default - base.default
        start = record.example - base.start if base.start is not None else math.nan
        return Param(f"{record.name}_excess", f"{record.symbol} - {base.symbol}", record.unit,
                     (0.0, base.bounds[1]), strict=False, default=default,
                     start=start if math.isfinite(start) and start >= 0.0 else None)
    hint = _HINTS.get(record.name, _Hint())
    start = hint.start if hint.start is not None else (record.example if math.isfinite(record.example) else None)
    return Param(record.name, record.symbol, record.unit, hint.bounds or _generic_bounds(record),
                 minimum=record.lower, strict=record.lower_open, maximum=record.upper,
                 strict_max=record.upper_open, aliases=_aliases(record, hint), scan=hint.scan,
                 default=record.default, start=start, tied=tied)


def _nudged(record: Any) -> float:
    """The example moved by 0.1 %, inside the record's interval."""
    rule = Param(record.name, record.symbol, record.unit, (record.lower, record.upper), minimum=record.lower,
                 strict=record.lower_open, maximum=record.upper, strict_max=record.upper_open)
    for value in (record.example * (1.0 - 1e-3), record.example * (1.0 + 1e-3)):
        if rule.admits(value):
            return value
    return record.example


def tied_parameters(law: type) -> FrozenSet[str]:
    """Keywords of ``law`` that the engine does not let move alone from its typical values: a rule across
    parameters that its table does not state (GeneralizedMaxwellSlip's block weights sum to 1). The fit holds them
    (at their defaults unless given in ``fixed``); the property tests draw them at their examples."""
    records = law.parameters
    examples = {r.name: r.example for r in records if math.isfinite(r.example)}
    tied = set()
    for r in records:
        if r.at_least or r.name not in examples or r.example == 0.0:
            continue
        try:
            law(**dict(examples, **{r.name: _nudged(r)}))
        except InvalidParameterError:
            tied.add(r.name)
    return frozenset(tied)


@dataclass(frozen=True)
class LawDef:
    key: str
    name: str
    cls: type
    params: Tuple[Param, ...]
    physical_names: Tuple[str, ...]  # keywords of the law's constructor that the fit sets, in order
    state_count: int
    symbols: Mapping[str, Tuple[str, str]]  # symbol, unit of every reported parameter
    excess: Mapping[str, Tuple[str, str]] = field(default_factory=dict)  # keyword -> (fit variable, lower bound)

    def param(self, name: str) -> Param:
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError(name)

    def physical(self, q: Mapping[str, float]) -> Dict[str, float]:
        """Fit variables -> the law constructor's keywords."""
        out = {}
        for name in self.physical_names:
            if name in self.excess:
                variable, other = self.excess[name]
                out[name] = q[other] + q[variable]
            else:
                out[name] = q[name]
        return out

    def build(self, physical: Mapping[str, float]):
        return self.cls(**{k: float(physical[k]) for k in self.physical_names})

    def state_stiffness(self, physical: Mapping[str, float]) -> float:
        """dF/dz of the law state [N/m], to scale its absolute tolerance: the largest stiffness among the
        parameters (k_t, sigma_0, the stiffest GMS block), 0 if none."""
        return max((physical.get(p.name, 0.0) for p in self.params if p.unit == _STIFFNESS_UNIT), default=0.0)

    def state_from_force(self, physical: Mapping[str, float], force: float, velocity: float,
                         normal_force: float) -> Optional[List[float]]:
        """Law state that gives friction force ``force`` [N] at v_r = ``velocity``, N = ``normal_force``; None
        where the force does not determine it (the engine's initial state, at rest, is used then)."""
        inverse = _STATE_FROM_FORCE.get(self.key)
        return None if inverse is None else inverse(physical, force, velocity, normal_force)

    @property
    def inverts_force(self) -> bool:
        """Whether :meth:`state_from_force` gives a state (the record's first force can set it)."""
        return self.key in _STATE_FROM_FORCE

    def starting_values(self) -> Dict[str, float]:
        """Data-free starting values (a typical contact); the fits replace mu and what the record shows."""
        out = {}
        for p in self.params:
            value = p.start if p.start is not None else p.default
            if value is not None:
                out[p.name] = value
        return out

    def refuse_fitting_tied(self, name: str, where: str) -> None:
        """Reject fitting ``name`` when it is tied (see tied_parameters): every run would fail."""
        if self.param(name).tied:
            reject(f"{where}: {name} is tied to other parameters of {self.name} by a rule across them, so it cannot "
                   f"be fitted alone: it is held at the value given for it, else its default", where)

    def scan_order(self, names: Sequence[str]) -> List[str]:
        """Scan order: the contact stiffnesses first, since the other scans only mean something once the force
        reaches its sliding level (a stable sort: the rest keep their order)."""
        units = {p.name: p.unit for p in self.params}
        return sorted(names, key=lambda name: 0 if units.get(name) == _STIFFNESS_UNIT else 1)


def _bristle_state(physical: Mapping[str, float], force: float, velocity: float, normal_force: float,
                   elasto_plastic: bool = False) -> List[float]:
    """LuGre / ElastoPlastic: F = sigma0 z (1 - sigma1 |v| / g) + (sigma1 + sigma2) v solved for z."""
    s0, s1, s2 = (physical["bristle_stiffness"], physical["bristle_damping"], physical["viscous_damping"])
    r = velocity / physical["stribeck_velocity"]
    g = normal_force * (physical["mu"] + (physical["mu_static"] - physical["mu"]) * math.exp(-r * r))
    factor = 1.0 - s1 * abs(velocity) / g
    z = force / s0 if abs(factor) < 1e-6 else (force - (s1 + s2) * velocity) / (s0 * factor)
    if elasto_plastic:
        # LuGre's z (alpha = 1) is exact in gross sliding, |z| >= z_max = mu N / sigma0 (a constant, Dupont et al.
        # 2002; the steady z_ss = g / sigma0 >= z_max); below break-away and while unloading alpha = 0 and
        # F = sigma0 z + (sigma1 + sigma2) v is. Once sigma1 |v| is a sizeable part of g both can match F, so
        # LuGre's is kept where it lies past the ramp's middle (alpha >= 1/2) on the side of v: a record that
        # starts in motion is sliding. The ramp has no closed-form inverse; LuGre's z is near enough there to
        # start a run.
        z_max = physical["mu"] * normal_force / s0
        z_ba = physical["breakaway_fraction"] * z_max
        elastic = (force - (s1 + s2) * velocity) / s0
        sliding = z * velocity > 0.0 and abs(z) >= 0.5 * (z_ba + z_max)
        if not sliding and (abs(elastic) <= z_ba or elastic * velocity <= 0.0):
            z = elastic
    return [z]


#: The physics that stays per law: the state a measured force implies (the initial state of a run from a record).
_STATE_FROM_FORCE: Dict[str, Callable[..., List[float]]] = {
    "dahl": lambda physical, force, velocity, normal_force: [force / physical["tangential_stiffness"]],  # k_t z
    "lugre": _bristle_state,
    "elasto_plastic": lambda *args: _bristle_state(*args, elasto_plastic=True),
}


def _fitted_records(law: type) -> List[Any]:
    """The ``Law.parameters`` records the fit sets (all but those its hints exclude)."""
    return [r for r in law.parameters if _HINTS.get(r.name, _Hint()).fitted]


def _identifiable(law: type) -> bool:
    """A law has something to identify unless it is memoryless with only a coefficient and the one bounded by it
    (Coulomb: mu N sgn(v_r) on the kinematic rig, whose mu is just the mean |F| / N)."""
    records = _fitted_records(law) if getattr(law, "parameters", None) else []
    if not records:  # no parameter table: nothing the fit knows how to set
        return False
    pair = {r.name for r in records if r.at_least} | {r.at_least for r in records if r.at_least}
    return bool(law.state_names) or any(r.name not in pair for r in records)


#: Fit variable of the kinematic rig's initial friction force F_0 [N] (initial_state="fit").
INITIAL_FORCE = "initial_force"


def _law_def_of(law: type) -> LawDef:
    tied = tied_parameters(law)
    records = _fitted_records(law)
    fit_params: Dict[str, Param] = {}
    excess: Dict[str, Tuple[str, str]] = {}
    for r in records:  # the bounding keyword is listed (and validated) before the one it bounds
        base = fit_params.get(r.at_least) if r.at_least else None
        fit_params[r.name] = _fit_param(r, base, r.name in tied)
        if base is not None:
            excess[r.name] = (fit_params[r.name].name, r.at_least)
    symbols = {r.name: (r.symbol, r.unit) for r in law.parameters}
    symbols.update({p.name: (p.symbol, p.unit) for p in fit_params.values()})
    symbols[INITIAL_FORCE] = ("F_0", "N")
    return LawDef(law.key, law.__name__, law, tuple(fit_params.values()), tuple(r.name for r in records),
                  len(law.state_names), symbols, excess)


#: The laws identification accepts, by key, in the engine's order (every law of FRICTION_LAWS with something to
#: fit).
_LAWS: Dict[str, LawDef] = {key: _law_def_of(law) for key, law in law_classes().items() if _identifiable(law)}

#: Fit variables per law: {law: {name: (symbol, unit, default bounds)}} (bounds= and initial_guess= keys).
#: An upper bound NaN (damping coefficients, N s/m) is set from the record: 10 max|F| / max|v_r|, a damping
#: force ten times the largest measured force. Coefficients that may be zero are searched linearly from 0.
LAW_PARAMETERS = {k: {p.name: (p.symbol, p.unit, p.bounds) for p in d.params} for k, d in _LAWS.items()}

_SPELLINGS = {spelling: lawdef for key, lawdef in _LAWS.items()  # elasto_plastic, ElastoPlastic
              for spelling in (key.replace("_", ""), lawdef.name.lower())}


def law_def(law: Any) -> LawDef:
    key = str(law.key if isinstance(law, type) and law in law_classes().values() else law)
    key = key.lower().replace("-", "").replace("_", "")
    if key not in _SPELLINGS:
        reject(f"law must be one of {', '.join(repr(k) for k in _LAWS)} (got {law!r})", "law")
    return _SPELLINGS[key]


def symbol_unit(law_name: str, name: str) -> Tuple[str, str]:
    """Symbol and unit of a reported parameter of law ``law_name`` (the class name)."""
    return law_def(law_name).symbols.get(name, (name, ""))


def canonical_name(lawdef: LawDef, key: str, where: str, extra: Sequence[str] = ()) -> str:
    """Map a user key (name or alias) to a fit-variable name; mu_static (a keyword fitted as an excess) passes
    through for guesses/fixed."""
    for p in lawdef.params:
        if key == p.name or key in p.aliases:
            return p.name
    for r in lawdef.cls.parameters:
        if r.name in lawdef.excess and key in (r.name, r.field, r.symbol):
            return r.name
    if key in extra:
        return key
    names = [p.name for p in lawdef.params] + list(extra)
    reject(f"{where}: unknown parameter {key!r} for {lawdef.name}; expected one of {', '.join(names)}",
           f"{where}[{key!r}]")
