"""The identifiable parameters of each friction law: names, symbols, units, default bounds and starting values.

mu_static >= mu is kept by fitting mu_static_excess = mu_static - mu >= 0 (a box bound, which the searches
handle, instead of a linear constraint, which they do not); :meth:`_LawDef.physical` maps it back.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from .._core import Dahl, ElastoPlastic, LuGre, Stribeck
from .validation import _reject


@dataclass(frozen=True)
class _Param:
    """A fit variable: a law keyword (mu, tangential_stiffness, ...) or a derived one (mu_static_excess)."""

    name: str
    symbol: str
    unit: str
    bounds: Tuple[float, float]  # default search bounds; upper NaN: from the data (see search_space._user_bounds)
    minimum: float = 0.0  # validity: > minimum (strict) or >= minimum
    strict: bool = True
    maximum: float = math.inf  # validity: < maximum
    aliases: Tuple[str, ...] = ()
    scan: bool = False  # coarse grid scan for a starting value when no initial guess is given
    default: Optional[float] = None  # value when held fixed and not given
    start: Optional[float] = None  # starting value when the record suggests none (else ``default``)


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
        cls = {"dahl": Dahl, "lugre": LuGre, "elasto_plastic": ElastoPlastic, "stribeck": Stribeck}[self.key]
        return cls(**{k: float(physical[k]) for k in self.physical_names})

    def state_stiffness(self, physical: Mapping[str, float]) -> float:
        """dF/dz of the law state [N/m] (k_t or sigma_0), to scale its absolute tolerance; 0 if no state."""
        return {"dahl": physical.get("tangential_stiffness", 0.0),
                "lugre": physical.get("bristle_stiffness", 0.0),
                "elasto_plastic": physical.get("bristle_stiffness", 0.0)}.get(self.key, 0.0)

    def state_from_force(self, physical: Mapping[str, float], force: float, velocity: float,
                         normal_force: float) -> Optional[List[float]]:
        """Law state that gives friction force ``force`` [N] at v_r = ``velocity``, N = ``normal_force``."""
        if self.key == "dahl":  # F = k_t z
            return [force / physical["tangential_stiffness"]]
        if self.key in ("lugre", "elasto_plastic"):  # F = sigma0 z (1 - sigma1 |v| / g) + (sigma1 + sigma2) v
            s0, s1, s2 = (physical["bristle_stiffness"], physical["bristle_damping"], physical["viscous_damping"])
            r = velocity / physical["stribeck_velocity"]
            g = normal_force * (physical["mu"] + (physical["mu_static"] - physical["mu"]) * math.exp(-r * r))
            factor = 1.0 - s1 * abs(velocity) / g
            z = force / s0 if abs(factor) < 1e-6 else (force - (s1 + s2) * velocity) / (s0 * factor)
            if self.key == "elasto_plastic":
                # LuGre's z (alpha = 1) is exact in gross sliding, |z| >= z_max = mu N / sigma0 (a constant,
                # Dupont et al. 2002; the steady z_ss = g / sigma0 >= z_max); below break-away and while unloading
                # alpha = 0 and F = sigma0 z + (sigma1 + sigma2) v is. Once sigma1 |v| is a sizeable part of g
                # both can match F, so LuGre's is kept where it lies past the ramp's middle (alpha >= 1/2) on the
                # side of v: a record that starts in motion is sliding. The ramp has no closed-form inverse;
                # LuGre's z is near enough there to start a run.
                z_max = physical["mu"] * normal_force / s0
                z_ba = physical["breakaway_fraction"] * z_max
                elastic = (force - (s1 + s2) * velocity) / s0
                sliding = z * velocity > 0.0 and abs(z) >= 0.5 * (z_ba + z_max)
                if not sliding and (abs(elastic) <= z_ba or elastic * velocity <= 0.0):
                    z = elastic
            return [z]
        return None

    def starting_values(self) -> Dict[str, float]:
        """Data-free starting values (a typical contact); the fits replace mu and what the record shows."""
        out = {}
        for p in self.params:
            value = p.start if p.start is not None else p.default
            if value is not None:
                out[p.name] = value
        return out


_MU = _Param("mu", "mu", "-", (1e-4, 10.0), aliases=("friction_coefficient", "coulomb_coefficient", "mu_c"))
_EXCESS = _Param("mu_static_excess", "mu_s - mu", "-", (0.0, 10.0), strict=False)
_VS = _Param("stribeck_velocity", "v_s", "m/s", (1e-7, 10.0), aliases=("v_s",), scan=True, start=1e-3)

_LUGRE = (_MU, _EXCESS, _VS,
          _Param("bristle_stiffness", "sigma_0", "N/m", (10.0, 1e10), aliases=("sigma0", "sigma_0"), scan=True,
                 start=1e5),
          _Param("bristle_damping", "sigma_1", "N s/m", (0.0, math.nan), strict=False, aliases=("sigma1", "sigma_1"),
                 scan=True, start=0.0),
          _Param("viscous_damping", "sigma_2", "N s/m", (0.0, math.nan), strict=False, aliases=("sigma2", "sigma_2"),
                 scan=True, default=0.0))
_LUGRE_NAMES = ("mu", "mu_static", "stribeck_velocity", "bristle_stiffness", "bristle_damping", "viscous_damping")
# z_ba / (mu N / sigma_0): the law needs < 1 (the ramp to z_max has positive width); 0.95 keeps the ramp at least
# 5 % of the Coulomb deflection wide by default
_BREAKAWAY = _Param("breakaway_fraction", "beta", "-", (0.0, 0.95), strict=False, maximum=1.0, aliases=("beta",),
                    default=0.5)

_LAWS: Dict[str, _LawDef] = {
    "dahl": _LawDef(
        "dahl", "Dahl",
        (_MU,
         _Param("tangential_stiffness", "k_t", "N/m", (10.0, 1e10), aliases=("k_t",), scan=True, start=1e5),
         _Param("exponent", "alpha", "-", (0.5, 4.0), strict=False, aliases=("alpha",), default=1.0)),
        ("mu", "tangential_stiffness", "exponent"), 1),
    "lugre": _LawDef("lugre", "LuGre", _LUGRE, _LUGRE_NAMES, 1),
    "elasto_plastic": _LawDef("elasto_plastic", "ElastoPlastic", _LUGRE + (_BREAKAWAY,),
                              _LUGRE_NAMES + ("breakaway_fraction",), 1),
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
    "breakaway_fraction": ("beta", "-"),
}

#: Fit variable of the kinematic rig's initial friction force F_0 [N] (initial_state="fit").
_INITIAL_FORCE = "initial_force"

_CONTACT_STIFFNESSES = ("tangential_stiffness", "bristle_stiffness")


def _stiffness_first(names: Sequence[str]) -> List[str]:
    """Scan order: the contact stiffness first, since the other scans only mean something once the force
    reaches its sliding level (a stable sort: the rest keep their order)."""
    return sorted(names, key=lambda name: 0 if name in _CONTACT_STIFFNESSES else 1)


_SPELLINGS = {key.replace("_", ""): lawdef for key, lawdef in _LAWS.items()}  # elasto_plastic, ElastoPlastic


def _law_def(law: Any) -> _LawDef:
    if isinstance(law, type) and law in (Dahl, LuGre, ElastoPlastic, Stribeck):
        law = law.__name__
    key = str(law).lower().replace("-", "").replace("_", "")
    if key not in _SPELLINGS:
        _reject(f"law must be one of 'dahl', 'lugre', 'elasto_plastic', 'stribeck' (got {law!r})", "law")
    return _SPELLINGS[key]


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
    _reject(f"{where}: unknown parameter {key!r} for {lawdef.name}; expected one of {', '.join(names)}",
            f"{where}[{key!r}]")
