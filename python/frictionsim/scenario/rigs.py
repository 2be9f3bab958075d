"""The rig kinds of the scenario schema: one :class:`RigKind` per ``rig.type``, registered in :data:`RIG_KINDS`.

A rig kind owns what differs between rigs: its [rig] keys (read from the engine class), how the rig object is
built from a :class:`~frictionsim.scenario.RigSpec`, its analysis (:mod:`frictionsim.scenario.analyses`: the mean
friction over vibration cycles, or the limit cycle), its time-series columns, its plots, and the friction types
only it runs. The parser and the runner ask the registry; nothing else branches on the rig type.

Friction types (:func:`friction_types`): the engine's laws of :func:`frictionsim.laws.law_classes` ("coulomb",
"stribeck", "dahl", "lugre", "elasto_plastic"), whose keys are their constructors' parameters, then the types of
the rig kinds (the torsional rig's "hysteretic" and "fig7").
"""

from __future__ import annotations

import functools
import inspect
import math
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Mapping, Optional, Tuple

import numpy as np

from .. import _core, drillstring, laws, units
from ..errors import InvalidParameterError
from ..torsional import fig7_friction
from .analyses import CYCLE_MEAN, LIMIT_CYCLE, STICK_SLIP, Analysis
from .text import article, join

__all__ = ["DrillStringKind", "LawKind", "PLOTS", "RIG_KINDS", "RigKind", "STRING_PLOTS", "TORSIONAL_PLOTS",
           "friction_type", "friction_types", "plots_of", "rig_kind"]


@dataclass(frozen=True)
class LawKind:
    """A scenario ``friction.type``: the callable that makes the law from the keys given, and its parameters."""

    key: str
    label: str  #: the class name, e.g. "Dahl"
    make: Callable[..., Any]
    rig: Optional[str] = None  #: the only rig kind that runs it (None: every kind)
    origin: str = ""  #: where the law comes from, in the error that refuses it on another rig
    #: array parameter -> its elements and their units (in the error for a wrong length)
    arrays: Mapping[str, str] = field(default_factory=dict)
    #: a name the engine's errors give -> the key it was written under
    aliases: Mapping[str, str] = field(default_factory=dict)

    @property
    def parameters(self) -> Tuple[laws.Parameter, ...]:
        """The keyword parameters of :attr:`make` (name, default, required, value kind)."""
        return laws.parameters(self.make)


class RigKind:
    """One rig type of the schema. The defaults here serve a rig that has no vibration period of its own."""

    name: str  #: the rig.type string
    engine: type  #: the frictionsim class
    analysis: Analysis
    plots: Tuple[str, ...] = ()  #: the plots its cases can draw
    own_laws: Tuple[LawKind, ...] = ()  #: friction types only this kind runs
    lubricant = False  #: whether a case may name a lubricant (paper 000's Table 5 power law in the summary)
    torsional = False  #: paper 001's torsional rig (Case.torsional)

    @functools.cached_property
    def keys(self) -> Dict[str, type]:
        """[rig] key -> value type, in the engine's order: its constructor's keyword parameters."""
        return {p.name: p.kind for p in laws.parameters(self.engine)}

    @functools.cached_property
    def units(self) -> Dict[str, str]:
        """[rig] key -> its SI unit, from the engine's parameter table (a value may be written with a unit)."""
        return units.units_of(self.engine)

    @functools.cached_property
    def defaults(self) -> Dict[str, Any]:
        """[rig] key -> the engine's default."""
        return {p.name: p.default for p in laws.parameters(self.engine)}

    def describe(self, spec) -> str:
        """The rig in words, e.g. "an axial rig"."""
        return f"{article(self.name)} {self.name} rig"

    def check(self, parser, params: Dict[str, Any], paths: Dict[str, str], path: str) -> Optional[Tuple]:
        """Rules across the keys of a [rig] table (raise ``parser.error``); returns the recorded samples the rig
        is driven by, if any."""
        return None

    def build(self, spec, friction):
        """The rig object of ``spec`` (a RigSpec) with the law object ``friction``."""
        return self.engine(friction, **spec.params)

    def time_stepping(self, spec) -> bool:
        """Whether the rig is a time-stepping model (fixed ``step``, methods moreau_jean / explicit_projection)."""
        return False

    def harmonic(self, spec) -> bool:
        """Whether the rig vibrates harmonically, with period :meth:`vibration_period`."""
        return False

    def vibration_period(self, spec) -> Optional[float]:
        """1/f [s] of a harmonic rig, else None."""
        return None

    def velocity_ratio(self, run) -> float:
        """v_a / v_d [-] of a run (eqs 16-17), NaN where it has none."""
        return math.nan

    def columns(self, run) -> Dict[str, np.ndarray]:
        """The time-series columns after the states (and before mode) of a run."""
        return {"friction_force": run.result.friction_force}


class Axial(RigKind):
    """Paper 000's vibrating-sliding rig (:class:`frictionsim.AxialVibrationRig`); all keys optional."""

    name, engine, analysis = "axial", _core.AxialVibrationRig, CYCLE_MEAN
    plots = ("friction_force", "hysteresis", "drive_force")
    lubricant = True

    def build(self, spec, friction):
        return self.engine(friction=friction, **spec.params)

    def harmonic(self, spec) -> bool:
        return True

    def vibration_period(self, spec) -> float:
        return 1.0 / float(spec.params.get("frequency", self.defaults["frequency"]))

    def velocity_ratio(self, run) -> float:
        v_a, v_d = float(run.rig.vibration_velocity_amplitude), float(run.rig.sliding_velocity)
        return v_a / v_d if v_d > 0 else math.nan

    def columns(self, run) -> Dict[str, np.ndarray]:
        """surface_position [m], surface_velocity [m/s], relative_displacement [m], relative_velocity [m/s],
        friction_force [N], drive_force [N]."""
        r, rig, t = run.result, run.rig, run.result.t
        surface = float(rig.amplitude) * np.sin(2 * math.pi * float(rig.frequency) * t)
        velocity = np.asarray(rig.surface_velocity(t), dtype=float)
        return {"surface_position": surface, "surface_velocity": velocity,
                "relative_displacement": r["position"] - surface, "relative_velocity": r["velocity"] - velocity,
                "friction_force": r.friction_force,
                "drive_force": np.asarray(rig.drive_force(t, r["position"]), dtype=float)}


class Kinematic(RigKind):
    """A law driven by a prescribed relative velocity (:class:`frictionsim.KinematicRig`): normal_force and either
    the harmonic v_r = v_d - v_a cos(2 pi f t) of :meth:`frictionsim.KinematicRig.harmonic` or a velocity_file."""

    name, engine, analysis = "kinematic", _core.KinematicRig, CYCLE_MEAN
    plots = ("friction_force", "hysteresis")
    lubricant = True

    @functools.cached_property
    def harmonic_keys(self) -> Tuple[str, ...]:
        """The keys of the harmonic velocity: sliding_velocity, velocity_amplitude, frequency."""
        harmonic = inspect.unwrap(self.engine.harmonic)  # the engine's own, under the wrapper taking units
        return tuple(p.name for p in laws.parameters(harmonic, ("friction", "normal_force", "initial_state")))

    @functools.cached_property
    def keys(self) -> Dict[str, type]:
        return {"normal_force": float, **{key: float for key in self.harmonic_keys}, "velocity_file": str}

    @functools.cached_property
    def units(self) -> Dict[str, str]:
        return units.units_of(self.engine, "harmonic")

    def describe(self, spec) -> str:
        return super().describe(spec) + (" with a velocity_file" if "velocity_file" in spec.params else "")

    def check(self, parser, params, paths, path):
        if "normal_force" not in params:
            raise parser.error(join(path, "normal_force"), "missing required value for a kinematic rig")
        given = [k for k in self.harmonic_keys if k in params]
        if "velocity_file" not in params:
            for key in self.harmonic_keys:
                if key not in params:
                    raise parser.error(join(path, key), "missing required value for a kinematic rig (give "
                                                        "sliding_velocity, velocity_amplitude and frequency, "
                                                        "or velocity_file)")
            return None
        if given:
            raise parser.error(paths[given[0]], "give either velocity_file or a harmonic velocity "
                                                "(sliding_velocity, velocity_amplitude, frequency), not both")
        for name in ("time", "relative_velocity", "value", "values"):  # what the engine's errors name
            paths[name] = paths["velocity_file"]
        return parser.samples(params["velocity_file"], paths["velocity_file"])

    def build(self, spec, friction):
        if spec.samples is not None:
            return self.engine(friction, relative_velocity=spec.samples,
                               normal_force=float(spec.params["normal_force"]))
        return self.engine.harmonic(friction, **{k: float(v) for k, v in spec.params.items()})

    def harmonic(self, spec) -> bool:
        return "velocity_file" not in spec.params

    def vibration_period(self, spec) -> Optional[float]:
        return 1.0 / float(spec.params["frequency"]) if self.harmonic(spec) else None

    def velocity_ratio(self, run) -> float:
        if not self.harmonic(run.case.rig):
            return math.nan
        v_a, v_d = (float(run.case.rig.params[k]) for k in ("velocity_amplitude", "sliding_velocity"))
        return v_a / v_d if v_d > 0 else math.nan

    def columns(self, run) -> Dict[str, np.ndarray]:
        """relative_displacement [m], relative_velocity [m/s] (the harmonic one, or the samples interpolated),
        friction_force [N]."""
        spec, t = run.case.rig, run.result.t
        if spec.samples is None:
            v_d, v_a, f = (float(spec.params[k]) for k in self.harmonic_keys)
            omega = 2 * math.pi * f
            displacement, velocity = v_d * t - v_a / omega * np.sin(omega * t), v_d - v_a * np.cos(omega * t)
        else:
            velocity = np.interp(t, *spec.samples)
            displacement = np.concatenate([[0.0], np.cumsum(np.diff(t) * 0.5 * (velocity[1:] + velocity[:-1]))])
        return {"relative_displacement": displacement, "relative_velocity": velocity,
                "friction_force": run.result.friction_force}


#: The elements of eq 6's coefficient arrays, in the order given, and their units.
_EQ6_COEFFICIENTS = ("(c00, c10, c01, c20, c11, c02): N m, N m s/rad, kg m^2, N m s^2/rad^2, N m s^3/rad^2, "
                     "N m s^4/rad^2")
_EQ6_SUFFIXES = ("00", "10", "01", "20", "11", "02")


class Torsional(RigKind):
    """Paper 001's drill-string rig (:class:`frictionsim.TorsionalRig`), ``rig.type = "torsional"``.

    * rig keys: the :class:`~frictionsim.TorsionalRig` keywords (:attr:`keys`, all optional, SI units);
    * friction types "hysteretic" (:class:`~frictionsim.HystereticFriction`, paper 001 eq 6) and "fig7" (the eq 6
      set of :func:`frictionsim.torsional.fig7_friction`), which only a torsional rig runs; the engine's other laws
      (coulomb, stribeck, dahl, lugre, elasto_plastic) act at the rig's contact_radius;
    * analysis: the limit cycle of the disc speed (:data:`frictionsim.scenario.analyses.LIMIT_CYCLE`) after
      ``transient`` [s] (default t_end / 2), with ``stick_speed`` [rad/s] (default 0.01) the |w2| counted as
      stuck, instead of the mean friction over vibration cycles;
    * time series: t, the states, disc_acceleration, friction_torque, shaft_torque, voltage, mode.

    Plots (``output.plots``; ``output.plot_window`` = [t_start, t_end] overrides every default window):

    ``disc_speed``
        disc speed w2 and drive (load-side motor) speed w3 against time, one panel per case (paper 001 Figs. 4a,
        7a); default window: the last 10 s.
    ``friction_torque_hysteresis``
        the friction torque T_f2 against disc speed w2 (Fig. 5a), against disc acceleration dw2/dt (Fig. 5b), and
        dw2/dt against w2 (Fig. 5c), over the limit cycle (default window: [transient, t_end]).
    ``phase_portrait``
        the phase portrait of the disc (Fig. 7b): disc speed w2 against the shaft twist th3 - th2, over the limit
        cycle (default window: [transient, t_end]). The twist is the disc's position relative to the drive: in a
        limit cycle both it and w2 are periodic, so the portrait closes (the absolute angle th2 grows without
        bound; th2 - w_ref t is nearly the mirror image of the twist, since the PI loop holds th3 close to w_ref t).
        Sticking shows as the flat stretch along w2 = 0, where the twist grows at w3 ~ w_ref until the
        break-away torque is reached. The operating point (mean twist, w_ref) is marked: over whole cycles the
        mean shaft torque equals the mean friction torque, so the mean twist is mean T_f2 / k2 (for steady
        rotation, the equilibrium itself).
    """

    name, engine, analysis = "torsional", _core.TorsionalRig, LIMIT_CYCLE
    plots = ("disc_speed", "friction_torque_hysteresis", "phase_portrait")
    torsional = True
    own_laws = (
        LawKind("hysteretic", "HystereticFriction", _core.HystereticFriction, "torsional", "paper 001 eq 6",
                arrays={"accelerating": _EQ6_COEFFICIENTS, "decelerating": _EQ6_COEFFICIENTS},
                aliases={**{f"p{i}": "accelerating" for i in _EQ6_SUFFIXES},
                         **{f"n{i}": "decelerating" for i in _EQ6_SUFFIXES}}),
        LawKind("fig7", "HystereticFriction", fig7_friction, "torsional", "paper 001 eq 6"),
    )

    def columns(self, run) -> Dict[str, np.ndarray]:
        """disc_acceleration [rad/s^2], friction_torque T_f2 [N m], shaft_torque S [N m], voltage V [V]."""
        r, rig = run.result, run.rig
        return {"disc_acceleration": np.asarray(rig.disc_acceleration(r.states, r.mode), dtype=float),
                "friction_torque": r.friction_force,
                "shaft_torque": np.asarray(rig.shaft_torque(r.states), dtype=float),
                "voltage": np.asarray(rig.voltage(r.states), dtype=float)}


class DrillStringKind(RigKind):
    """A field-scale drill string (:class:`frictionsim.StringRig`), ``rig.type = "drillstring"``.

    * rig keys: ``sections``, an array of tables top to bottom, each with the :class:`~frictionsim.PipeSection`
      keys (outer_diameter, inner_diameter, length [m], youngs_modulus, shear_modulus [Pa], density [kg/m^3]);
      ``bit``, a table of :class:`~frictionsim.NavarroLopezBit` keys (bit_radius [m], coulomb_coefficient,
      static_coefficient, weakening_rate, velocity_scale [rad/s], viscous_damping [N m s/rad], stick_band [rad/s])
      with ``weight_on_bit`` [N] (without ``bit`` the bit hangs off bottom); and the StringRig keywords: the
      table's (damping_time, surface_speed, proportional_gain, inclination, ...) and elements, top_drive,
      axial, hoisting, wall_contacts, contact_nodes, normal_forces, excitation_node;
    * ``treatment``: "exact" (the StringRig) or "captured" / "mixed": a :class:`~frictionsim.TorsionalString`
      run by Moreau-Jean with ``solver.step``, built from :data:`SHARED` (StringRig name -> its name), its own
      table's other keywords (:attr:`captured_keys`) and the walls of a coulomb law (:meth:`wall_coefficients`);
      the other treatment's keys are refused, and so is a stick-slip map (it reruns the exact rig); or "auto":
      the measured rule of :func:`frictionsim.drillstring.automatic_treatment` on the string's wall contacts (``elements``,
      less the bit's node on bottom): exact up to 30, mixed up to 300 with the bit on bottom, captured beyond;
      keys that only one treatment takes choose it;
    * friction: the wall contacts' law, any engine law (coulomb, stribeck, dahl, lugre, ...);
    * analysis: the bit's stick-slip after ``transient`` [s] (default t_end / 2) and, with ``surface_speeds``
      [rad/s] and ``weights_on_bit`` [N], the stick-slip map over that grid
      (:data:`frictionsim.scenario.analyses.STICK_SLIP`);
    * time series: t, the states (theta_i, omega_i per node, the work integrals), wall_friction_torque,
      surface_torque, bit_torque [N m], stuck_contacts, mode.

    Plots: ``bit_speed`` (bit and surface speed against time, one panel per case; default window: the last 30 s)
    and ``stick_slip_map`` (one per case with a map: peak bit speed / w_set and the bit's stuck fraction).
    """

    name, engine, analysis = "drillstring", _core.StringRig, STICK_SLIP
    plots = ("bit_speed", "stick_slip_map")
    #: ``treatment``: "exact" (every contact located as an event: StringRig) or a time-stepping TorsionalString's
    TREATMENTS = ("exact", "captured", "mixed", "auto")
    #: The StringRig keys a TorsionalString takes for the same physics under another name (its table's)
    SHARED = drillstring.SHARED
    #: TorsionalString keys the scenario gives elsewhere: [friction] (a coulomb law's mu_static, mu / mu_static)
    #: and the shared keys' StringRig names
    _FROM_FRICTION = ("friction_coefficient", "kinetic_ratio")

    @staticmethod
    def _keywords(engine, skip) -> Dict[str, Any]:
        return {p.name: p for p in laws.parameters(engine, skip)}

    @functools.cached_property
    def exact_keys(self) -> Dict[str, Any]:
        """StringRig's keywords (after the string and the law)."""
        return self._keywords(self.engine, ("self", "string", "friction"))

    @functools.cached_property
    def captured_keys(self) -> Dict[str, Any]:
        """TorsionalString's own keywords: those not under a shared StringRig name nor read from [friction]
        (empty without Eigen, where there is no TorsionalString)."""
        engine = getattr(_core, "TorsionalString", None)
        if engine is None:
            return {}
        taken = set(self.SHARED.values()) | set(self._FROM_FRICTION) | {"treatment"}
        return {name: p for name, p in self._keywords(engine, ("self", "string")).items() if name not in taken}

    @functools.cached_property
    def keys(self) -> Dict[str, type]:
        keys: Dict[str, type] = {"sections": list, "treatment": str}
        for name, p in {**self.exact_keys, **self.captured_keys}.items():
            keys[name] = dict if name in ("bit", "survey") else list if p.kind is tuple else p.kind
        return keys

    @functools.cached_property
    def units(self) -> Dict[str, str]:
        engine = getattr(_core, "TorsionalString", None)
        return {**(units.units_of(engine) if engine is not None else {}), **units.units_of(self.engine)}

    @functools.cached_property
    def defaults(self) -> Dict[str, Any]:
        return {name: p.default for name, p in self.exact_keys.items()}

    @staticmethod
    def treatment(spec) -> str:
        """The spec's contact treatment: "exact" (default), "captured" or "mixed" ("auto" resolved when checked)."""
        return spec.params.get("treatment", "exact")

    def time_stepping(self, spec) -> bool:
        return self.treatment(spec) != "exact"

    def _check_treatment(self, parser, params, paths, path) -> None:
        """The treatment's name, and the keys it cannot honour refused naming it."""
        treatment = params.get("treatment", "exact")
        if treatment not in self.TREATMENTS:
            raise parser.error(paths["treatment"], f"must be one of {', '.join(self.TREATMENTS)} (got {treatment!r})")
        if treatment == "auto":
            treatment = params["treatment"] = self._automatic(params)
        if treatment != "exact" and getattr(_core, "TorsionalString", None) is None:
            raise parser.error(paths["treatment"], f"treatment {treatment!r} needs the engine built with Eigen "
                                                   f"(frictionsim.HAS_EIGEN is False)")
        allowed = (set(self.exact_keys) if treatment == "exact" else set(self.SHARED) | set(self.captured_keys))
        allowed |= {"sections", "treatment"}
        for key in params:
            if key not in allowed:
                other = "exact" if treatment != "exact" else "captured / mixed"
                raise parser.error(paths[key], f"treatment {treatment!r} cannot take it (a key of the {other} "
                                               f"treatment; the {treatment} treatment takes: "
                                               f"{', '.join(k for k in self.keys if k in allowed)})")

    def _automatic(self, params) -> str:
        """treatment = "auto": :func:`frictionsim.drillstring.string_treatment` on the rig keys (the measured rule
        on the wall contacts; a key only one treatment takes chooses it)."""
        keys = {k: v for k, v in params.items() if k not in ("sections", "treatment")}
        if "bit" in keys and "weight_on_bit" not in keys:
            keys["weight_on_bit"] = 1.0  # a bit given is on bottom (its weight is checked below)
        return drillstring.string_treatment("auto", **keys)

    def _table(self, parser, value, cls, path: str, paths: Dict[str, str]):
        """A table of ``cls``'s keys (a PipeSection or the bit), checked by building it."""
        table = parser.table(value, path)
        names = [p.name for p in cls.parameters]
        parser.unknown(table, names, path)
        table_units = units.units_of(cls)
        numbers = {key: parser.measure(v, table_units[key], join(path, key)) for key, v in table.items()}
        try:
            cls(**numbers)
        except InvalidParameterError as error:
            raise parser.engine(error, {key: join(path, key) for key in numbers}, path) from None
        return numbers

    def check(self, parser, params, paths, path):
        self._check_treatment(parser, params, paths, path)
        if "sections" not in params:
            raise parser.error(join(path, "sections"), "missing required value: the string's sections, top to "
                                                       "bottom (an array of tables of PipeSection keys)")
        sections = params["sections"]
        if not sections:
            raise parser.error(paths["sections"], "must hold at least one section")
        params["sections"] = tuple(self._table(parser, section, _core.PipeSection, f"{paths['sections']}[{i + 1}]",
                                               paths) for i, section in enumerate(sections))
        if "bit" in params:
            params["bit"] = self._table(parser, params["bit"], _core.NavarroLopezBit, paths["bit"], paths)
            if "weight_on_bit" not in params:
                raise parser.error(join(path, "weight_on_bit"), "missing required value with a bit on bottom (N)")
        elif "weight_on_bit" in params:
            raise parser.error(paths["weight_on_bit"], "needs a bit (give rig.bit; without it the bit is off "
                                                       "bottom)")
        if "survey" in params:
            table = parser.table(params["survey"], paths["survey"])
            parser.unknown(table, ("measured_depth", "inclination"), paths["survey"])
            for key in ("measured_depth", "inclination"):
                if key not in table:
                    raise parser.error(join(paths["survey"], key), "missing required value (an array of numbers)")
            params["survey"] = tuple(parser.numbers(table[key], None, "", join(paths["survey"], key),
                                                    {"measured_depth": "m", "inclination": "rad"}[key])
                                     for key in ("measured_depth", "inclination"))
        if "contact_radius" in params:
            params["contact_radius"] = parser.numbers(params["contact_radius"], None, "", paths["contact_radius"], "m")
        if "contact_nodes" in params:
            params["contact_nodes"] = tuple(parser.value(v, int, f"{paths['contact_nodes']}[{i + 1}]")
                                            for i, v in enumerate(params["contact_nodes"]))
        if "normal_forces" in params:
            params["normal_forces"] = tuple(parser.measure(v, self.units["normal_forces"],
                                                           f"{paths['normal_forces']}[{i + 1}]")
                                            for i, v in enumerate(params["normal_forces"]))
        return None

    def build(self, spec, friction):
        params = dict(spec.params)
        string = _core.DrillString([_core.PipeSection(**section) for section in params.pop("sections")])
        if "bit" in params:
            params["bit"] = _core.NavarroLopezBit(**params["bit"])
        return drillstring.string_model(string, friction, treatment=params.pop("treatment", "exact"), **params)

    @staticmethod
    def wall_coefficients(friction) -> Dict[str, float]:
        """A TorsionalString's wall friction from the [friction] law (:func:`frictionsim.drillstring.
        wall_coefficients`)."""
        return drillstring.wall_coefficients(friction)

    def describe(self, spec) -> str:
        treatment = self.treatment(spec)
        return "a drillstring rig" + ("" if treatment == "exact" else f" ({treatment} contacts, time-stepped)")

    def columns(self, run) -> Dict[str, np.ndarray]:
        """wall_friction_torque (the Result's friction_force: the sum over the wall contacts), surface_torque,
        bit_torque [N m] (:mod:`frictionsim.drillstring`), stuck_contacts."""
        from .. import drillstring as ds

        r, rig = run.result, run.rig
        if self.time_stepping(run.case.rig):
            return {}  # a TorsionalString's Result holds its outputs (bit_speed, motor_torque, ...) as its states
        return {"wall_friction_torque": r.friction_force, "surface_torque": ds.surface_torque(rig, r),
                "bit_torque": ds.bit_torque(rig, r), "stuck_contacts": ds.stuck_contacts(r)}


#: rig.type -> its kind, in the order the schema lists them
RIG_KINDS: Dict[str, RigKind] = {kind.name: kind for kind in (Axial(), Kinematic(), Torsional(), DrillStringKind())}


def rig_kind(name: str) -> RigKind:
    """The registered kind of rig type ``name`` (KeyError naming the types there are)."""
    try:
        return RIG_KINDS[name]
    except KeyError:
        raise KeyError(f"unknown rig type {name!r} (known: {', '.join(RIG_KINDS)})") from None


@functools.lru_cache(maxsize=None)
def friction_types() -> Dict[str, LawKind]:
    """friction.type -> :class:`LawKind`: the engine's laws (:func:`frictionsim.laws.law_classes`), then those of
    the rig kinds."""
    types = {key: LawKind(key, cls.__name__, cls) for key, cls in laws.law_classes().items()}
    types.update((law.key, law) for kind in RIG_KINDS.values() for law in kind.own_laws)
    return types


def friction_type(key: str) -> LawKind:
    """The :class:`LawKind` of friction type ``key``."""
    return friction_types()[key]


def plots_of(analysis: Analysis) -> Tuple[str, ...]:
    """The plots a file of rigs with ``analysis`` may ask for: those of every kind that has it, in order."""
    return tuple(dict.fromkeys(plot for kind in RIG_KINDS.values() if kind.analysis is analysis
                               for plot in kind.plots))


#: The plots of axial and kinematic rigs, of torsional ones, and of drill strings.
PLOTS = plots_of(CYCLE_MEAN)
TORSIONAL_PLOTS = plots_of(LIMIT_CYCLE)
STRING_PLOTS = plots_of(STICK_SLIP)
