"""Field-scale drill strings: what a run of a :class:`frictionsim.StringRig` gives.

The model is C++ (``include/frictionsim/string/string_rig.hpp``): :class:`~frictionsim.PipeSection`,
:class:`~frictionsim.DrillString`, the bits :class:`~frictionsim.NavarroLopezBit` (velocity weakening) and
:class:`DetournayBit` (the drag bit's depth of cut under the weight on bit) and :class:`~frictionsim.StringRig`.
A string in a curved well takes the hole's inclination and the wall's normal force per node as arrays
(``node_inclinations``, ``normal_forces``), computed from a survey or anything else; ``start_hanging=True`` starts
an axial run from the string hanging at rest.
This module reads a :class:`~frictionsim.Result` of one by the rig's own state layout (``rig.omega_index``, the
rig's ``surface_torque`` / ``bit_torque``), so no column arithmetic is repeated here, and measures stick-slip
the way a stick-slip map needs it.

    >>> import frictionsim as fs
    >>> from frictionsim import drillstring as ds
    >>> rig = fs.StringRig(ds.field_string(), fs.Coulomb(0.2, 0.3), bit=fs.NavarroLopezBit(), weight_on_bit=1e5,
    ...                    elements=30, inclination=1.047, surface_speed=6.0)
    >>> result = fs.simulate(rig, 60.0)
    >>> ds.stick_slip(rig, result, transient=20.0).sticks
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import threading
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from typing import Any, Dict, Optional, Sequence

import numpy as np

from . import _core
from ._core import DetournayBit, DrillString, NavarroLopezBit, PipeSection, StringRig
from .errors import InvalidParameterError
from .result import Result

__all__ = [
    "DetournayBit",
    "DrillString",
    "NavarroLopezBit",
    "PipeSection",
    "StickSlip",
    "StickSlipMap",
    "StringRig",
    "TREATMENTS",
    "automatic_treatment",
    "bit_speed",
    "bit_torque",
    "field_string",
    "hook_load",
    "replace",
    "set_speed",
    "stick_slip",
    "stick_slip_map",
    "stick_slip_point",
    "string_model",
    "string_treatment",
    "stuck_contacts",
    "surface_speed",
    "surface_torque",
    "wall_contacts",
]

#: 5" drill pipe (19.5 lb/ft: OD 127 mm, ID 108.6 mm) and 6 1/2" x 2 13/16" drill collars, steel.
DRILL_PIPE = dict(outer_diameter=0.127, inner_diameter=0.1086)
DRILL_COLLAR = dict(outer_diameter=0.1651, inner_diameter=0.0714)


def field_string(pipe_length: float = 2800.0, collar_length: float = 200.0) -> DrillString:
    """A field string: ``pipe_length`` [m] of 5" drill pipe above ``collar_length`` [m] of 6 1/2" collars."""
    return DrillString([PipeSection(length=pipe_length, **DRILL_PIPE),
                        PipeSection(length=collar_length, **DRILL_COLLAR)])


#: The treatments of a string's contacts: every switch located (a StringRig), every contact captured by
#: Moreau-Jean (a TorsionalString), the walls captured and the bit's switches located (mixed), or the measured rule.
TREATMENTS = ("exact", "captured", "mixed", "auto")

#: The StringRig keywords a TorsionalString takes for the same physics, and its name for each.
SHARED = {"surface_speed": "speed_setpoint", "end_inertia": "bha_inertia", "elements": "elements",
          "bit": "bit", "weight_on_bit": "weight_on_bit", "inclination": "inclination",
          "mud_density": "mud_density", "top_drive_inertia": "top_drive_inertia",
          "proportional_gain": "proportional_gain", "integral_gain": "integral_gain",
          "damping_time": "damping_time", "damping_rate": "damping_rate",
          "setpoint_time_constant": "setpoint_time_constant", "torque_limit": "torque_limit",
          "control_period": "control_period", "top_drive": "top_drive"}


#: The measured rule (C++ string/treatment.hpp): the treatment a string of so many wall contacts runs cheapest in.
automatic_treatment = _core.automatic_treatment


def _keywords(engine) -> set:
    return {p.name for p in engine.parameters} | set(_EXTRA_KEYWORDS.get(engine.__name__, ()))


#: A StringRig's elements when none are given (StringRigSetup::elements): the string model's default under every
#: treatment.
DEFAULT_ELEMENTS = 20

#: Keywords outside each engine's table.
_EXTRA_KEYWORDS = {
    "StringRig": ("elements", "top_drive", "axial", "hoisting", "wall_contacts", "contact_nodes", "normal_forces",
                  "node_inclinations", "excitation_node", "bit", "weight_on_bit", "start_hanging"),
    "TorsionalString": ("elements", "survey", "contact_radius", "bit", "top_drive", "slow_speed", "switch_tolerance"),
}


def wall_coefficients(friction) -> Dict[str, float]:
    """A captured string's wall friction from a StringRig's wall law: a Coulomb law's static coefficient is the
    TorsionalString's friction_coefficient mu, its kinetic one over that the kinetic_ratio f_rat (A&S eq 4)."""
    if not isinstance(friction, _core.Coulomb):
        raise InvalidParameterError(f"friction: must be coulomb under treatment captured or mixed (A&S eq 4: "
                                    f"static mu, kinetic f_rat mu; got {type(friction).__name__})", "friction")
    mu_s, mu_k = float(friction.mu_static), float(friction.mu)
    return {"friction_coefficient": mu_s, "kinetic_ratio": mu_k / mu_s if mu_s > 0 else 1.0}


def string_treatment(treatment: str = "auto", **keywords: Any) -> str:
    """The treatment a string of these StringRig / TorsionalString ``keywords`` runs under: ``treatment`` itself, or
    for "auto" the measured rule of :func:`automatic_treatment` on its wall contacts (``elements``, 20
    by default as StringRig's, less the bit's node on bottom): exact up to 30 contacts, mixed up to 300 with the bit
    on bottom, captured beyond. A keyword only one engine takes chooses it (``axial=True`` the exact StringRig,
    ``stick_band_speed`` the captured string); without Eigen (no TorsionalString) "auto" is "exact"."""
    if treatment not in TREATMENTS:
        raise InvalidParameterError(f"treatment: must be one of {', '.join(TREATMENTS)} (got {treatment!r})",
                                    "treatment")
    if treatment != "auto":
        return treatment
    captured_engine = getattr(_core, "TorsionalString", None)
    if captured_engine is None:
        return "exact"
    exact, captured = _keywords(StringRig), _keywords(captured_engine)
    if any(k in exact and k not in SHARED for k in keywords):
        return "exact"
    on_bottom = keywords.get("bit") is not None and float(keywords.get("weight_on_bit", 0.0) or 0.0) > 0.0
    elements = int(keywords.get("elements", DEFAULT_ELEMENTS))
    chosen = _core.automatic_treatment(max(elements - (1 if on_bottom else 0), 0), on_bottom)
    if chosen == "exact" and any(k in captured and k not in SHARED.values() for k in keywords):
        return "mixed" if on_bottom else "captured"
    return chosen


def string_model(string: DrillString, friction, *, treatment: str = "auto", **keywords: Any):
    """One drill string, its contacts treated as chosen: "exact" a :class:`~frictionsim.StringRig` (every stick and
    slip located as an event), "captured" or "mixed" a :class:`~frictionsim.TorsionalString` (Moreau-Jean over the
    walls; mixed also locates the bit's switches) of the same physics, "auto" by the measured rule
    (:func:`string_treatment`). ``friction`` is the wall law (captured / mixed: a Coulomb law, its static and
    kinetic coefficients); ``keywords`` are StringRig's (the ones a TorsionalString shares are renamed: surface_speed
    -> speed_setpoint, end_inertia -> bha_inertia) or a TorsionalString's own (survey, stick_band_speed, ...). A
    keyword the chosen engine cannot take is refused naming it. Run either with :func:`frictionsim.simulate`
    (captured / mixed: ``method="moreau_jean", step=``); both Results' mode column counts the wall contacts at rest.
    What the keywords leave out is StringRig's default under every treatment (its table describes the string model:
    drive, gains, torque limit, mud, inclination, a step set-point, 20 elements), not the captured engine's own (A&S
    Well B's drive, a 60 degree hole, a 1 s set-point ramp, 200 elements), so "auto" changes how the contacts are
    solved, not the string. One exception: StringRig's default torque limit (60 kN m) is not given to the captured
    and mixed strings (the mixed one cannot carry a limit at all, and the captured one keeps the mixed one's
    drive), so their motor torque is
    unlimited unless ``torque_limit`` is given: the treatments differ only where the motor would pass 60 kN m. A
    given ``torque_limit`` follows StringRig's rule (positive) under every treatment. One difference of lumping
    stays: a StringRig has no wall at node 0 (the top drive's), the captured
    string has that node's half element's where the well is inclined at the top; they agree as N grows, and exactly
    in a well vertical at the top (the C++ exact_string builds the StringRig of a TorsionalString).

        >>> import frictionsim as fs
        >>> from frictionsim import drillstring as ds
        >>> model = ds.string_model(ds.field_string(), fs.Coulomb(0.2, 0.3), elements=400, treatment="auto")
        >>> type(model).__name__
        'TorsionalString'
    """
    chosen = string_treatment(treatment, **keywords)
    if chosen == "exact":
        return StringRig(string, friction, **keywords)
    engine = _core.TorsionalString
    own = _keywords(engine)
    limit = keywords.get("torque_limit")
    if limit is not None and not float(limit) > 0.0:  # StringRig's rule; the captured string's 0 means "none"
        raise InvalidParameterError(f"torque_limit: must be positive, StringRig's rule under every treatment (got "
                                    f"{limit!r}; leave it out for an unlimited captured or mixed string)",
                                    "torque_limit")
    captured: Dict[str, Any] = {}
    for key, value in keywords.items():
        name = SHARED.get(key, key)
        if name not in own or name in ("friction_coefficient", "kinetic_ratio"):
            raise InvalidParameterError(f"{key}: treatment {chosen!r} cannot take it (a StringRig keyword without a "
                                        f"captured counterpart; the wall friction comes from `friction`)", key)
        captured[name] = value
    exact_defaults = dict({p.name: p.default for p in StringRig.parameters}, elements=DEFAULT_ELEMENTS)
    for key, name in SHARED.items():
        if key in keywords or name in keywords or key not in exact_defaults:
            continue
        if name == "torque_limit":
            continue  # left out unless given (see above)
        captured[name] = exact_defaults[key]
    captured.update(wall_coefficients(friction))
    return engine(string, treatment=chosen, **captured)


def _string_columns(rig) -> bool:
    """A TorsionalString (under any treatment): its Result's columns are the string's outputs (bit_speed,
    top_drive_speed, motor_torque, stuck_fraction), not a StringRig's node states."""
    return not hasattr(rig, "omega_index")


def set_speed(rig) -> float:
    """The set surface speed w_set [rad/s]: a StringRig's surface_speed, a TorsionalString's speed_setpoint."""
    return float(rig.speed_setpoint if _string_columns(rig) else rig.surface_speed)


def wall_contacts(rig) -> int:
    """How many wall contacts the string has (its contact_nodes; a TorsionalString's nodes with wall friction):
    what the Result's mode column counts at rest, under every treatment."""
    return len(rig.contact_nodes)


def _check_result(rig, result) -> None:
    """``result`` must be a run of ``rig``'s layout: the same state names, one column each (a Result of another rig
    gave an IndexError, or a smaller rig's columns read as this one's bit speed)."""
    names = getattr(result, "state_names", None)
    states = getattr(result, "states", None)
    if names is None or states is None:
        raise TypeError(f"result must be a Result of the rig (got {type(result).__name__})")
    expected = list(rig.state_names)
    if list(names) != expected or np.ndim(states) != 2 or np.shape(states)[1] != len(expected):
        raise InvalidParameterError(
            f"result: must be a run of this {type(rig).__name__} (its {len(expected)} states, "
            f"{', '.join(expected[:3])}, ...); got a Result of {len(names)} states ({', '.join(list(names)[:3])}, "
            f"...): another rig's run", "result")


def bit_speed(rig, result: Result) -> np.ndarray:
    """Bit speed [rad/s] (node N's) at each row of ``result`` (of a StringRig or a TorsionalString)."""
    _check_result(rig, result)
    if _string_columns(rig):
        return np.asarray(result["bit_speed"])
    return result.states[:, rig.omega_index(rig.elements)]


def surface_speed(rig, result: Result) -> np.ndarray:
    """Surface (top-drive) speed [rad/s] (node 0's) at each row."""
    _check_result(rig, result)
    if _string_columns(rig):
        return np.asarray(result["top_drive_speed"])
    return result.states[:, rig.omega_index(0)]


#: Speeds [rad/s] read as "at rest" when a row's contact modes are rebuilt from its state (the Result records how
#: many contacts stick, not which): a row at a located switch carries the crossing a few 1e-11 rad/s past zero,
#: and a bit breaking away dips by ~1e-8 rad/s before its torque turns it forwards; the sign of either would pick
#: the wrong slip branch. Torques read at rest differ from the slip law's there by c_b * AT_REST at most.
AT_REST = 1e-6


def _states_at_rest(rig: StringRig, result: Result) -> np.ndarray:
    _check_result(rig, result)
    states = np.array(result.states)
    columns = [rig.omega_index(node) for node in (*rig.contact_nodes, rig.elements)]
    block = states[:, columns]
    block[np.abs(block) < AT_REST] = 0.0
    states[:, columns] = block
    return states


def surface_torque(rig: StringRig, result: Result) -> np.ndarray:
    """Torque the surface applies [N m] at each row: the motor's under PI control (limit included), what holds
    the prescribed speed otherwise (a TorsionalString: its PI motor's torque)."""
    _check_result(rig, result)
    if _string_columns(rig):
        return np.asarray(result["motor_torque"])
    return rig.surface_torque(result.t, _states_at_rest(rig, result))


def bit_torque(rig: StringRig, result: Result) -> np.ndarray:
    """Torque on bit [N m] at each row (0 off bottom; the holding torque while the bit sticks: the mode of each
    row is rebuilt from its state, speeds below :data:`AT_REST` counting as zero)."""
    return rig.bit_torque(result.t, _states_at_rest(rig, result))


def hook_load(rig: StringRig, result: Result) -> np.ndarray:
    """The hook's force on the string [N], positive up, at each row: the prescribed hook load, or what holds the
    prescribed hook speed (axial runs; 0 in torsion-only runs)."""
    _check_result(rig, result)
    return rig.hook_force(result.t, result.states)


def stuck_contacts(result: Result) -> np.ndarray:
    """How many wall contacts stick at each row (the Result's mode column counts them under every treatment)."""
    return np.asarray(result.mode)


@dataclass(frozen=True)
class StickSlip:
    """Stick-slip measures of one run after its transient, bit speed against the set surface speed w_set.

    peak_ratio, mean_ratio : max and time-mean of the bit speed over w_set
    stuck_fraction : fraction of the time the bit is stuck (bit speed exactly 0: the engine's stick is exact;
    a TorsionalString's bit: below its slow_speed, as A&S's code counts it)
    sticks : the bit stuck at least once (full stick-slip)
    surface_peak_ratio : max surface speed over w_set (the PI drive's overshoot)
    """

    peak_ratio: float
    mean_ratio: float
    stuck_fraction: float
    sticks: bool
    surface_peak_ratio: float

    def as_dict(self) -> dict:
        return asdict(self)


def stick_slip(rig: StringRig, result: Result, transient: float = 0.0) -> StickSlip:
    """The stick-slip measures of ``result`` over t >= ``transient`` [s] (see :class:`StickSlip`)."""
    _check_result(rig, result)
    t = np.asarray(result.t)
    keep = t >= transient
    if np.count_nonzero(keep) < 2:
        raise ValueError(f"stick_slip: fewer than two rows after transient = {transient} s (the run ends at "
                         f"{t[-1] if len(t) else 0.0} s)")
    w_set = set_speed(rig)
    if not w_set > 0.0:
        raise ValueError(f"stick_slip: the rig's surface_speed must be positive (got {w_set})")
    t, bit, top = t[keep], bit_speed(rig, result)[keep], surface_speed(rig, result)[keep]
    dt = np.diff(t)
    span = t[-1] - t[0]
    mean = float(np.sum(0.5 * (bit[1:] + bit[:-1]) * dt) / span)
    at_rest = np.abs(bit) <= (float(rig.slow_speed) if _string_columns(rig) else 0.0)  # A&S count below slow_speed
    stuck = at_rest[1:] & at_rest[:-1]
    stuck_fraction = float(np.sum(dt[stuck]) / span)
    return StickSlip(peak_ratio=float(np.max(bit) / w_set), mean_ratio=mean / w_set, stuck_fraction=stuck_fraction,
                     sticks=bool(np.any(at_rest)), surface_peak_ratio=float(np.max(top) / w_set))


def replace(rig: StringRig, **changes: Any) -> StringRig:
    """A copy of ``rig`` with some constructor keywords changed (``surface_speed=...``, ``weight_on_bit=...``),
    built through the constructor as unpickling builds it, so it is checked the same way."""
    rebuild, (cls, args, kwargs, factory) = rig.__reduce__()
    unknown = set(changes) - set(kwargs)
    if unknown:
        raise TypeError(f"replace: StringRig has no keyword {', '.join(sorted(unknown))}")
    return rebuild(cls, args, {**kwargs, **changes}, factory)


@contextmanager
def _polling(stop):
    """This thread's string runs also poll ``stop`` (an object with ``is_set()``, a threading.Event): set, a run
    stops within the engine's poll interval (20 ms) as KeyboardInterrupt. Worker threads see no signal, so a map's
    workers share the flag the main thread sets when it is interrupted."""
    if stop is None:
        yield
        return
    previous = _core._string_run_stop(stop)
    try:
        yield
    finally:
        _core._string_run_stop(previous)


def stick_slip_point(*, rig: StringRig, surface_speed: float, weight_on_bit: float, t_end: float,
                     transient: float, rtol: float = 1e-6, timeout: Optional[float] = None,
                     stop: Any = None) -> Dict[str, float]:
    """One point of :func:`stick_slip_map`: ``rig`` at (w_set [rad/s], W [N]) from rest, its :class:`StickSlip`
    after ``transient`` as a dict of floats (top-level and picklable, for process pools and dask), with
    ``timed_out`` 1.0 where the run passed ``timeout`` [s of wall time] (its measures NaN) and 0.0 otherwise.
    ``stop``: an object with ``is_set()`` the run polls (see :func:`stick_slip_map`)."""
    from .errors import BudgetExceededError
    from .simulation import simulate

    point = replace(rig, surface_speed=surface_speed, weight_on_bit=weight_on_bit)
    try:
        with _polling(stop):
            result = simulate(point, t_end, rtol=rtol, timeout=timeout)
    except BudgetExceededError as error:
        if error.budget != "timeout":
            raise
        values = {name: math.nan for name in StickSlip.__dataclass_fields__}
        values.update(sticks=0.0, timed_out=1.0)
        return values
    values = stick_slip(point, result, transient).as_dict()
    values["sticks"] = float(values["sticks"])
    values["timed_out"] = 0.0
    return values


@dataclass(frozen=True)
class StickSlipMap:
    """A string's stick-slip over a (surface speed, weight on bit) grid: arrays of shape (len(surface_speeds),
    len(weights_on_bit)) of the :class:`StickSlip` measures; sticks True where the bit sticks after the transient;
    failed True where the run failed (NaN in the float arrays, False in sticks); timed_out True where the point's run
    passed the map's ``timeout`` (NaN and False likewise, not a failure)."""

    surface_speeds: np.ndarray
    weights_on_bit: np.ndarray
    sticks: np.ndarray
    peak_ratio: np.ndarray
    mean_ratio: np.ndarray
    stuck_fraction: np.ndarray
    surface_peak_ratio: np.ndarray
    failed: np.ndarray
    sweep: Any
    timed_out: Optional[np.ndarray] = None

    def to_pandas(self):
        return self.sweep.to_pandas()


def stick_slip_map(rig: StringRig, surface_speeds: Sequence[float], weights_on_bit: Sequence[float], *,
                   t_end: float = 60.0, transient: float = 30.0, rtol: float = 1e-6, executor: Any = None,
                   progress: bool = False, errors: str = "collect", timeout: Optional[float] = None) -> StickSlipMap:
    """Where does the string stick-slip? ``rig`` (on bottom) run from rest at every (w_set, W) point of the grid
    through :func:`frictionsim.sweep` (threads run in parallel: the engine releases the GIL).

    ``timeout``: the wall time [s] each point's run may take; a point past it is recorded as timed out
    (:attr:`StickSlipMap.timed_out`), not as a failure of the map. Ctrl-C stops the map within a fraction of a
    second, the points running on a thread pool too (they poll a flag the interrupted main thread sets)."""
    from .sweeps import sweep

    if rig.bit is None:
        raise ValueError("stick_slip_map: the rig must have a bit on bottom (bit=NavarroLopezBit(...))")
    speeds = np.asarray(surface_speeds, dtype=float).ravel()
    weights = np.asarray(weights_on_bit, dtype=float).ravel()
    for name, values in (("surface_speeds", speeds), ("weights_on_bit", weights)):
        if values.size == 0 or not np.all(np.isfinite(values)) or np.any(values <= 0):
            raise ValueError(f"{name} must be a non-empty sequence of positive finite values (got {values!r})")
    if not 0.0 <= transient < t_end:
        raise ValueError(f"stick_slip_map: transient must lie in [0, t_end) (got {transient} and {t_end})")
    if timeout is not None and (isinstance(timeout, (bool, str)) or not float(timeout) > 0.0):
        raise InvalidParameterError(f"timeout: must be a positive number of seconds (got {timeout!r})", "timeout")
    fixed = dict(rig=rig, t_end=t_end, transient=transient, rtol=rtol, timeout=timeout)
    # the points on this process's threads poll a flag set when this thread is interrupted (a process pool or a
    # cluster cannot share it; their workers are the executor's to stop)
    stop = threading.Event() if executor is None or isinstance(executor, cf.ThreadPoolExecutor) else None
    if stop is not None:
        fixed["stop"] = stop
    try:
        result = sweep(stick_slip_point, {"surface_speed": list(speeds), "weight_on_bit": list(weights)},
                       fixed=fixed, executor=executor, progress=progress, errors=errors)
    finally:  # interrupted (or failed): the running points stop at their next poll
        if stop is not None:
            stop.set()
    failed = np.zeros(result.grid_shape, dtype=bool)
    failed.flat[result.failed] = True
    timed_out = np.nan_to_num(result.as_array("timed_out"), nan=0.0) > 0.5
    return StickSlipMap(speeds, weights, result.as_array("sticks") > 0.5, result.as_array("peak_ratio"),
                        result.as_array("mean_ratio"), result.as_array("stuck_fraction"),
                        result.as_array("surface_peak_ratio"), failed, result, timed_out)


# ---------------------------------------------------------------------------------------------- plots
# Multi-panel plots: ``ax`` is a sequence of Axes, one per panel (None: a new figure); they return the Figure;
# style keywords reach the lines (or the map's pcolormesh). A figure given through ``ax`` keeps its own title.
def speeds_panels_figure(items: Sequence[tuple], *, title: str = "", window: Optional[tuple] = None, ax=None,
                         **style: Any):
    """One panel per (label, rig, result): bit and surface speed [rad/s] against t [s] within ``window``."""
    from .plots import panels_for, with_style

    for _, rig, result in items:  # before a figure is made
        _check_result(rig, result)
    figure, axes = panels_for(ax, len(items), 10.0, 2.0 + 2.4 * len(items), rows=True)
    for panel, (label, rig, result) in zip(axes, items):
        t = result.t
        inside = (t >= window[0]) & (t <= window[1]) if window is not None else np.ones(len(t), bool)
        panel.plot(t[inside], surface_speed(rig, result)[inside], **with_style({"color": "tab:blue", "lw": 1.0}, style),
                   label="surface")
        panel.plot(t[inside], bit_speed(rig, result)[inside], **with_style({"color": "tab:red", "lw": 1.0}, style),
                   label="bit")
        panel.axhline(set_speed(rig), color="0.5", lw=0.8, ls="--", label="set speed")
        panel.set_ylabel("speed [rad/s]")
        panel.set_title(label, fontsize=9)
        panel.legend(fontsize=8, loc="upper right")
    axes[-1].set_xlabel("t [s]")
    if ax is None:
        figure.suptitle((title + "\n" if title else "") + "bit and surface speed of the drill string", fontsize=10)
    return figure


def speeds_figure(rig: StringRig, result: Result, *, title: str = "", ax=None, **style: Any):
    """Bit and surface speed [rad/s] over time (top), surface and bit torque [kN m] (bottom); ``ax``: two Axes."""
    from .plots import panels_for, with_style

    _check_result(rig, result)  # before a figure is made
    figure, (top, bottom) = panels_for(ax, 2, 10.0, 6.5, rows=True)
    t = result.t
    surface = with_style({"color": "tab:blue", "lw": 1.0}, style)
    bit = with_style({"color": "tab:red", "lw": 1.0}, style)
    top.plot(t, surface_speed(rig, result), **surface, label="surface (top drive)")
    top.plot(t, bit_speed(rig, result), **bit, label="bit")
    top.axhline(rig.surface_speed, color="0.5", lw=0.8, ls="--", label=f"set speed {rig.surface_speed:g} rad/s")
    top.set_ylabel("speed [rad/s]")
    top.legend(fontsize=8, loc="upper right")
    bottom.plot(t, surface_torque(rig, result) / 1e3, **surface, label="surface torque")
    bottom.plot(t, bit_torque(rig, result) / 1e3, **bit, label="torque on bit")
    bottom.set_xlabel("t [s]")
    bottom.set_ylabel("torque [kN m]")
    bottom.legend(fontsize=8, loc="upper right")
    if ax is None:
        figure.suptitle(title or "drill string: bit and surface speed", fontsize=10)
    return figure


def string_stick_slip_map_figure(m: StickSlipMap, *, title: str = "", point: Optional[tuple] = None, ax=None,
                                 **style: Any):
    """Peak bit speed / w_set (left) and the bit's stuck fraction (right) over (w_set, W [kN]); a black dot where
    the bit sticks, a red cross where the run failed (a grey one where it timed out), a star at ``point`` (w_set, W [N]); ``ax``: two Axes; style
    keywords go to the maps (pcolormesh: ``cmap`` replaces both colour maps)."""
    from .plots import panels_for

    speeds, weights = m.surface_speeds, m.weights_on_bit / 1e3

    def edges(v):
        if v.size == 1:
            return np.array([v[0] * 0.9, v[0] * 1.1])
        mid = 0.5 * (v[1:] + v[:-1])
        return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])

    figure, axes = panels_for(ax, 2, 13.0, 5.2)
    xx, yy = np.meshgrid(speeds, weights, indexing="ij")
    for panel, (values, label, cmap) in zip(axes, [(m.peak_ratio, "peak bit speed / $\\omega_{set}$ [-]", "viridis"),
                                                    (m.stuck_fraction, "fraction of time the bit is stuck", "magma")]):
        mesh = panel.pcolormesh(edges(speeds), edges(weights), np.asarray(values, float).T,
                                **dict({"cmap": cmap, "shading": "flat"}, **style))
        figure.colorbar(mesh, ax=panel, label=label)
        for (i, j), value in np.ndenumerate(values):
            if np.isfinite(value):
                panel.annotate(f"{value:.2f}", (speeds[i], weights[j]), textcoords="offset points", xytext=(0, -11),
                               ha="center", fontsize=7, color="w" if value < np.nanmean(values) else "k")
        panel.plot(xx[m.sticks], yy[m.sticks], "o", color="k", markersize=4, linestyle="none", label="bit sticks")
        if m.failed.any():
            panel.plot(xx[m.failed], yy[m.failed], "x", color="r", markersize=6, linestyle="none", label="run failed")
        if m.timed_out is not None and m.timed_out.any():
            panel.plot(xx[m.timed_out], yy[m.timed_out], "x", color="0.4", markersize=6, linestyle="none",
                       label="timed out")
        if point is not None:
            panel.plot(point[0], point[1] / 1e3, marker="*", markersize=15, color="r", markeredgecolor="k",
                       linestyle="none", label="time series")
        panel.set_xlabel("surface speed $\\omega_{set}$ [rad/s]")
        panel.set_ylabel("weight on bit W [kN]")
        panel.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    if ax is None:
        share = f"{int(m.sticks.sum())} of {m.sticks.size} points stick-slip"
        figure.suptitle((title + "\n" if title else "") + f"stick-slip map of the string: {share}", fontsize=10)
    return figure


def stick_slip_map_figure(m: StickSlipMap, **kwargs: Any):
    """Deprecated name of :func:`string_stick_slip_map_figure` (:func:`frictionsim.plots.stick_slip_map_figure` is
    the torsional rig's map); warns and draws the same figure."""
    import warnings

    warnings.warn("frictionsim.drillstring.stick_slip_map_figure is renamed string_stick_slip_map_figure "
                  "(frictionsim.plots.stick_slip_map_figure draws the torsional rig's map)", DeprecationWarning,
                  stacklevel=2)
    return string_stick_slip_map_figure(m, **kwargs)
