"""Hypothesis strategies over every law's, rig's and solver option's parameters, from ONE table of them.

Each entry: the constructor keyword, the range where it is valid (inclusive unless ``open_low`` / ``open_high``) and
a range of physically typical values that the runs draw from. The laws' entries are generated from the engine's own
parameter tables (``Law.parameters`` of every class of ``fs.FRICTION_LAWS``, issue 12): the rule from the interval,
its open ends, the keyword bounding it from below (``at_least``) and NaN as "unset"; the typical values around the
engine's typical value (``example``). The solver options are listed here, their tolerance limits read from
``fs._core.SolverOptions``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

from hypothesis import strategies as st

import frictionsim as fs
from frictionsim.fit.parameters import tied_parameters


@dataclass(frozen=True)
class Param:
    valid: Tuple[float, float]  # the rule: valid in [low, high] (low excluded when open_low, high when open_high)
    typical: Tuple[float, float]  # what physical runs draw from (log-uniform when both > 0); the excess with at_least
    open_low: bool = False
    infinite_ok: bool = False  # inf means "no limit" (max_step, timeout)
    open_high: bool = False
    at_least: Optional[str] = None  # also >= this keyword: drawn as its value plus a typical excess
    unset_ok: bool = False  # NaN means "unset" (Coulomb's mu_static: equal to mu)
    held: Optional[float] = None  # tied to other keywords by a rule the table does not state: always this, not mutated


#: Typical values of terms that the engine's example leaves off (0) but the runs should exercise: viscous terms
#: [N s/m], and a string rig's hole inclination [rad], structural damping [s], BHA [kg m^2, kg], A&S's viscous
#: damping k_t [1/s] and set-point ramp [s]. Every other term that is off by default (a Karnopp band, which the
#: kinematic rig refuses; a string's hoisting and excitation) is drawn off.
_TYPICAL_WHEN_OFF = {"viscous_coefficient": (1e-3, 10.0), "viscous_damping": (1e-3, 10.0),
                     "inclination": (0.05, 1.5), "damping_time": (1e-4, 1e-2), "end_inertia": (1.0, 100.0),
                     "end_mass": (1e3, 3e4), "damping_rate": (1e-3, 0.5), "setpoint_time_constant": (0.05, 2.0)}


def _typical(record: Any, base: Any) -> Tuple[float, float]:
    """A decade either side of the engine's example, inside the rule (an open end stays out); the excess over the
    bounding keyword ``base`` (a decade either side of the examples' difference, or of the base's example)."""
    if base is not None:
        excess = record.example - base.example
        scale = excess if math.isfinite(excess) and excess > 0.0 else base.example
        return scale / 10.0, scale * 10.0
    example = record.example
    if not (math.isfinite(example) and example > 0.0):
        return _TYPICAL_WHEN_OFF.get(record.name, (example, example) if math.isfinite(example) else (0.0, 0.0))
    low, high = max(example / 10.0, record.lower), min(example * 10.0, record.upper)
    if record.upper_open and high == record.upper:
        high -= 1e-3 * (high - low)
    if record.lower_open and low == record.lower:
        low += 1e-3 * (high - low)
    return low, high


def _law_params(law: type, tied_by_construction: bool = True) -> Dict[str, Param]:
    records = {r.name: r for r in law.parameters}
    tied = tied_parameters(law) if tied_by_construction else frozenset()
    return {name: Param((r.lower, r.upper), _typical(r, records.get(r.at_least) if r.at_least else None),
                        open_low=r.lower_open, open_high=r.upper_open, at_least=r.at_least or None,
                        unset_ok=r.unset_allowed, held=r.example if name in tied else None)
            for name, r in records.items()}


LAWS: Dict[type, Dict[str, Param]] = {law: _law_params(law) for law in fs.FRICTION_LAWS}
#: The drill-string tables (issue 13), read the same way: a pipe section's, the bit law's and the string rig's
#: (built from its keywords alone, a section or a rig has no rule across them that a nudge would find; the rules
#: across tables, ID < OD and mud lighter than steel, are the tests' to check).
TABLES: Dict[type, Dict[str, Param]] = {fs.NavarroLopezBit: _law_params(fs.NavarroLopezBit),
                                        fs.DetournayBit: _law_params(fs.DetournayBit),
                                        fs.PipeSection: _law_params(fs.PipeSection, tied_by_construction=False),
                                        fs.StringRig: _law_params(fs.StringRig, tied_by_construction=False)}
#: The field engine's tables (issue 22): the Navarro-Lopez strings and, where the extension has Eigen, the
#: Moreau-Jean string (apart from TABLES, whose tests build a StringRig from each).
FIELD_TABLES: Dict[type, Dict[str, Param]] = {
    cls: _law_params(cls, tied_by_construction=False)
    for cls in (fs.NavarroLopez2Dof, fs.NavarroLopez4Dof) + ((fs.TorsionalString,) if fs.HAS_EIGEN else ())}

_SOLVER = fs._core.SolverOptions
#: simulate() options: rule and typical values
OPTIONS: Dict[str, Param] = {
    "rtol": Param((_SOLVER.min_rtol, _SOLVER.max_rtol), (1e-10, 1e-4)),
    "atol": Param((_SOLVER.min_atol, math.inf), (1e-14, 1e-8)),
    "max_step": Param((0.0, math.inf), (1e-4, 1.0), open_low=True, infinite_ok=True),
    "event_window": Param((0.0, math.inf), (1e-9, 1e-5), open_low=True),
    "timeout": Param((0.0, math.inf), (5.0, 30.0), open_low=True, infinite_ok=True),
}


def valid(param: Param, value: float) -> bool:
    """Does ``value`` obey the keyword's own rule (the at_least bound is the caller's: it needs the other value)?"""
    low, high = param.valid
    if (value == math.inf and param.infinite_ok) or (math.isnan(value) and param.unset_ok):
        return True
    return (math.isfinite(value) and (value > low if param.open_low else value >= low)
            and (value < high if param.open_high else value <= high))


def typical(param: Param) -> st.SearchStrategy:
    low, high = param.typical
    if low > 0:  # log-uniform over the decades, rounding kept inside
        return st.floats(math.log10(low), math.log10(high)).map(lambda e: min(max(10.0 ** e, low), high))
    return st.floats(low, high)


def any_number() -> st.SearchStrategy:
    """Anything a user might pass: extremes, specials, negatives, tiny and huge numbers."""
    return st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                     st.sampled_from([0.0, -0.0, 5e-324, 1e-300, 1e300, -1.0, math.nan, math.inf]))


@st.composite
def law_kwargs(draw, law: type, mutate: bool) -> Dict[str, float]:
    """Typical keywords of ``law`` (a keyword bounded by another drawn as that one plus an excess, so mu_static >=
    mu); with ``mutate``, one of them replaced by any number (not NaN where NaN means "unset": valid by design, but
    not by the properties' mu_static >= mu check). Any class of LAWS or TABLES."""
    params = LAWS[law] if law in LAWS else TABLES[law] if law in TABLES else FIELD_TABLES[law]
    kwargs: Dict[str, float] = {}
    for name, p in params.items():
        if p.held is not None:
            kwargs[name] = p.held
        elif p.at_least is None:
            kwargs[name] = draw(typical(p))
    for name, p in params.items():
        if p.held is None and p.at_least is not None:
            kwargs[name] = kwargs[p.at_least] + draw(typical(p))
    kwargs = {name: kwargs[name] for name in params}
    if mutate:
        name = draw(st.sampled_from(sorted(n for n, p in params.items() if p.held is None)))
        numbers = any_number()
        kwargs[name] = draw(numbers.filter(lambda x: not math.isnan(x)) if params[name].unset_ok else numbers)
    return kwargs


def table_kwargs(cls: type, mutate: bool) -> st.SearchStrategy:
    """law_kwargs for the classes of TABLES (the drill-string tables) and FIELD_TABLES."""
    return law_kwargs(cls, mutate)
