"""Hypothesis strategies over every law's, rig's and solver option's parameters, from ONE table of them.

Each entry: the constructor keyword, the range where it is valid (inclusive lower unless ``open_low``) and a
range of physically typical values that the runs draw from. Issue 12 will generate this table from the engine's
own field tables; until then it is the single place the property tests read parameter names and rules from.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Tuple

from hypothesis import strategies as st

import frictionsim as fs


@dataclass(frozen=True)
class Param:
    valid: Tuple[float, float]  # the rule: valid in [low, high] (low excluded when open_low)
    typical: Tuple[float, float]  # what physical runs draw from (log-uniform when both > 0)
    open_low: bool = False
    infinite_ok: bool = False  # inf means "no limit" (max_step, timeout)


LAWS: Dict[type, Dict[str, Param]] = {
    fs.Coulomb: {"mu": Param((0.0, math.inf), (0.05, 1.0), open_low=True)},
    fs.Stribeck: {"mu": Param((0.0, math.inf), (0.05, 0.5), open_low=True),
                  "mu_static": Param((0.0, math.inf), (0.5, 1.0), open_low=True),
                  "stribeck_velocity": Param((0.0, math.inf), (1e-4, 1e-1), open_low=True),
                  "shape_exponent": Param((0.0, math.inf), (0.5, 3.0), open_low=True),
                  "viscous_coefficient": Param((0.0, math.inf), (1e-3, 10.0))},
    fs.Dahl: {"mu": Param((0.0, math.inf), (0.05, 1.0), open_low=True),
              "tangential_stiffness": Param((0.0, math.inf), (1e3, 1e6), open_low=True),
              "exponent": Param((0.5, 50.0), (0.5, 3.0))},
    fs.LuGre: {"mu": Param((0.0, math.inf), (0.05, 0.5), open_low=True),
               "mu_static": Param((0.0, math.inf), (0.5, 1.0), open_low=True),
               "stribeck_velocity": Param((0.0, math.inf), (1e-3, 1e-1), open_low=True),
               "bristle_stiffness": Param((0.0, math.inf), (1e4, 1e6), open_low=True),
               "bristle_damping": Param((0.0, math.inf), (1.0, 300.0)),
               "viscous_damping": Param((0.0, math.inf), (1e-3, 10.0))},
}
LAWS[fs.ElastoPlastic] = dict(LAWS[fs.LuGre], breakaway_fraction=Param((0.0, 1.0), (0.0, 0.9)))

#: simulate() options: rule and typical values
OPTIONS: Dict[str, Param] = {
    "rtol": Param((1e-14, 0.1), (1e-10, 1e-4)),
    "atol": Param((1e-20, math.inf), (1e-14, 1e-8)),
    "max_step": Param((0.0, math.inf), (1e-4, 1.0), open_low=True, infinite_ok=True),
    "event_window": Param((0.0, math.inf), (1e-9, 1e-5), open_low=True),
    "timeout": Param((0.0, math.inf), (5.0, 30.0), open_low=True, infinite_ok=True),
}


def valid(param: Param, value: float) -> bool:
    low, high = param.valid
    if value == math.inf and param.infinite_ok:
        return True
    return math.isfinite(value) and (value > low if param.open_low else value >= low) and value <= high


def typical(param: Param) -> st.SearchStrategy:
    low, high = param.typical
    if low > 0:  # log-uniform over the decades
        return st.floats(math.log10(low), math.log10(high)).map(lambda e: 10.0 ** e)
    return st.floats(low, high)


def any_number() -> st.SearchStrategy:
    """Anything a user might pass: extremes, specials, negatives, tiny and huge numbers."""
    return st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                     st.sampled_from([0.0, -0.0, 5e-324, 1e-300, 1e300, -1.0, math.nan, math.inf]))


@st.composite
def law_kwargs(draw, law: type, mutate: bool) -> Dict[str, float]:
    """Typical keywords of ``law`` (mu_static >= mu kept); with ``mutate``, one of them replaced by any number."""
    kwargs = {name: draw(typical(p)) for name, p in LAWS[law].items()}
    if "mu_static" in kwargs:
        kwargs["mu_static"] = max(kwargs["mu_static"], kwargs["mu"])
    if mutate:
        name = draw(st.sampled_from(sorted(kwargs)))
        kwargs[name] = draw(any_number())
    return kwargs
