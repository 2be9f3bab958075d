"""The SI units of a run's outputs, as the rigs and laws declare them: what :mod:`frictionsim.io` writes into a
netCDF file's ``units`` and :mod:`frictionsim.plots` onto an axis.

A friction law declares its states' units in C++ next to their names (``Law::state_units``, bound as the class
attribute ``state_units`` beside ``state_names``), so a new law needs no entry here. A rig of the engine's list
declares its outputs in C++ next to its parameter table (``Params::outputs()``, bound as the class attribute
``outputs``: ``(name, unit, what)`` for ``friction_force``, a force [N] or a torque [N m], and each of its own
states), so a new rig needs no entry here either. The string models (``StringRig``, ``TorsionalString``) declare
theirs so too, with the states they have per node (a row ``theta_*`` for ``theta_0``, ``theta_1``, ...) and what
their ``mode`` column counts (a row ``mode`` of unit "1": the stuck wall contacts).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional

from . import _core

__all__ = ["RIG_OUTPUTS", "RigOutputs", "declared_outputs", "law_state_units", "output_units", "rig_outputs"]


@dataclass(frozen=True)
class RigOutputs:
    """What a rig's Result holds, in SI units."""

    friction: str  #: friction_force's unit: "N" (a force) or "N m" (a torque)
    states: Mapping[str, str]  #: the rig's own states (its law's come from the law's ``state_units``)
    #: states numbered per node of a string: ``theta`` -> ``theta_0``, ``theta_1``, ...; the wall law's states
    #: are numbered so too
    node_states: Mapping[str, str] = field(default_factory=dict)
    #: what ``mode`` holds: "contact" (-1 slip negative, 0 stick or smooth, +1 slip positive) or "stuck contacts"
    #: (a string's count of stuck wall contacts)
    mode: str = "contact"

    @property
    def is_torque(self) -> bool:
        return self.friction == "N m"


def declared_outputs(cls: type) -> Optional[RigOutputs]:
    """What a rig class declares in C++ (its ``outputs``: ``(name, unit, what)`` rows, ``friction_force`` among
    them), or None for a class that declares none. A row ``name_*`` is a state per node (``theta_*``: ``theta_0``,
    ``theta_1``, ...); a row ``mode`` of unit "1" says the mode column counts stuck contacts."""
    rows = getattr(cls, "outputs", None)
    if not rows:
        return None
    units = {name: unit for name, unit, _ in rows}
    friction = units.pop("friction_force")
    mode = "stuck contacts" if units.pop("mode", None) == "1" else "contact"
    nodes = {name[:-2]: units.pop(name) for name in list(units) if name.endswith("_*")}
    return RigOutputs(friction, units, nodes, mode)


#: Every rig the engine binds, by its class (``frictionsim.RIGS``), as each declares its outputs in C++
#: (``outputs``; tests/python/test_io.py checks that each rig has an entry).
RIG_OUTPUTS: Dict[type, RigOutputs] = {
    cls: outputs for cls, outputs in ((cls, declared_outputs(cls)) for cls in _core.RIGS) if outputs is not None
}


def rig_outputs(rig: Any) -> Optional[RigOutputs]:
    """The declaration of ``rig``'s class (or of a class it derives from), or None for an object that is no
    engine rig."""
    for cls in type(rig).__mro__:
        if cls in RIG_OUTPUTS:
            return RIG_OUTPUTS[cls]
    return None


def law_state_units(law: Any) -> Dict[str, str]:
    """A friction law's states -> their units, as the law declares them (``state_units`` beside
    ``state_names``); {} for a law that declares none (a CallableLaw's state is the user's)."""
    names = getattr(law, "state_names", ()) or ()
    units = getattr(law, "state_units", ()) or ()
    return dict(zip(names, units)) if len(units) == len(names) else {}


def output_units(rig: Any) -> Dict[str, str]:
    """Every column of ``rig``'s Result with a declared unit: ``t``, each state (the rig's own, its law's, a
    string's per node and its bit's ``bit_*``), ``friction_force`` and ``friction_impulse``, and ``mode`` ("1")
    where it counts stuck contacts; {} when ``rig`` is no engine rig."""
    outputs = rig_outputs(rig)
    if outputs is None:
        return {}
    laws = law_state_units(getattr(rig, "friction", None))
    bit = {f"bit_{name}": unit for name, unit in law_state_units(getattr(rig, "bit", None)).items()}
    per_node = dict(outputs.node_states, **laws) if outputs.node_states else {}
    units = {"t": "s", "friction_force": outputs.friction,
             "friction_impulse": "N m s" if outputs.is_torque else "N s"}
    if outputs.mode == "stuck contacts":
        units["mode"] = "1"  # a count; contact-mode flags (-1, 0, +1) have no unit
    for name in getattr(rig, "state_names", ()):
        unit = outputs.states.get(name) or laws.get(name) or bit.get(name)
        if unit is None and per_node:
            stem, _, index = name.rpartition("_")
            unit = per_node.get(stem) if index.isdigit() else None
        if unit is not None:
            units[name] = unit
    return units
