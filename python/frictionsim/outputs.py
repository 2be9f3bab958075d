"""The SI units of a run's outputs, as the rigs and laws declare them: what :mod:`frictionsim.io` writes into a
netCDF file's ``units`` and :mod:`frictionsim.plots` onto an axis.

A friction law declares its states' units in C++ next to their names (``Law::state_units``, bound as the class
attribute ``state_units`` beside ``state_names``), so a new law needs no entry here. A rig declares, once per rig
class (the class object the bindings made, never its name), the unit of its friction output (a force [N] or a torque
[N m]), its own states, the states it has per node of a string (``theta_3``), and what its ``mode`` column counts.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional

from ._core import AxialVibrationRig, KinematicRig, NavarroLopez2Dof, NavarroLopez4Dof, StringRig, TorsionalRig

try:
    from ._core import TorsionalString  # needs Eigen (HAS_EIGEN)
except ImportError:  # pragma: no cover - an extension built without Eigen
    TorsionalString = None

__all__ = ["RIG_OUTPUTS", "RigOutputs", "law_state_units", "output_units", "rig_outputs"]


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


_WORK = "J"
_STRING = dict(theta="rad", omega="rad/s", u="m", v="m/s")

#: Every rig the engine binds, by its class (``frictionsim.RIGS``): a new rig adds one entry (tests/python/
#: test_io.py checks that each has one).
RIG_OUTPUTS: Dict[type, RigOutputs] = {
    cls: outputs for cls, outputs in (
        (AxialVibrationRig, RigOutputs("N", {
            "position": "m", "velocity": "m/s", "friction_impulse": "N s", "friction_work": _WORK,
            "drive_work": _WORK})),
        (KinematicRig, RigOutputs("N", {
            "friction_impulse": "N s", "friction_work": _WORK})),
        (TorsionalRig, RigOutputs("N m", {
            "disc_angle": "rad", "disc_speed": "rad/s", "shaft_twist": "rad", "drive_speed": "rad/s", "current": "A",
            "speed_error_integral": "rad", "friction_impulse": "N m s", "motor_work": _WORK,
            "friction_work": _WORK, "damping_work": _WORK, "electrical_work": _WORK, "ohmic_work": _WORK})),
        (StringRig, RigOutputs("N m", {
            "speed_error_integral": "rad", "drive_work": _WORK, "hoist_work": _WORK, "excitation_work": _WORK,
            "wall_friction_work": _WORK, "damping_work": _WORK, "bit_work": _WORK}, _STRING, "stuck contacts")),
        (TorsionalString, RigOutputs("N m", {
            "bit_speed": "rad/s", "top_drive_speed": "rad/s", "motor_torque": "N m", "stuck_fraction": "1"})),
        (NavarroLopez2Dof, RigOutputs("N m", {
            "table_speed": "rad/s", "bit_speed": "rad/s", "string_twist": "rad", "motor_work": _WORK,
            "damping_work": _WORK, "friction_work": _WORK})),
        (NavarroLopez4Dof, RigOutputs("N m", {
            "table_speed": "rad/s", "upper_pipe_speed": "rad/s", "lower_pipe_speed": "rad/s", "bit_speed": "rad/s",
            "table_twist": "rad", "pipe_twist": "rad", "bit_twist": "rad", "motor_work": _WORK,
            "damping_work": _WORK, "friction_work": _WORK})),
    ) if cls is not None
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
