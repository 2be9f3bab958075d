"""Scenario files: a rig, a friction law, solver settings, analysis and outputs, described in TOML.

One schema serves ``frictionsim run`` and the built-in demo (:mod:`frictionsim.demo`). A file holds defaults at the
top level and any number of ``[[case]]`` tables; each case is one rig with one friction law, so a file can compare
Coulomb and Dahl friction side by side. SI units throughout::

    title = "Paper 000 Fig. 7(a)"
    [rig]                       # default rig of every case
    type = "axial"              # "axial" (AxialVibrationRig), "kinematic" (KinematicRig), "torsional" (TorsionalRig)
    amplitude = 5e-3            # u0 [m]; omitted keys take the engine's defaults
    [solver]
    t_end = 2.0                 # s
    [analysis]
    cycles = 10                 # mean friction over the last 10 whole cycles
    [[case]]
    name = "coulomb"
    friction = { type = "coulomb", mu = 0.41 }
    [[case]]
    name = "dahl"
    friction = { type = "dahl", mu = 0.41, tangential_stiffness = 4e4 }

Sections (each may be given at the top level as a default, and per case; a case's keys override the default's
key by key, unless the case changes ``type``, in which case the default table is not used):

``rig``
    ``type = "axial"``: mass [kg], drive_stiffness [N/m], sliding_velocity v_d [m/s], amplitude u0 [m],
    frequency f [Hz], normal_force F_N [N], gravity (bool), gravitational_acceleration [m/s^2],
    initial_position [m], initial_velocity [m/s]; all optional (defaults of :class:`frictionsim.AxialVibrationRig`).
    ``type = "kinematic"``: normal_force [N] and either a harmonic relative velocity v_r = v_d - v_a cos(2 pi f t)
    (sliding_velocity [m/s], velocity_amplitude [m/s], frequency [Hz]) or ``velocity_file``, a CSV of two
    columns t [s], v_r [m/s] (header row optional, ``#`` comments; relative to the scenario file).
    ``type = "torsional"``: paper 001's drill-string rig (:class:`frictionsim.TorsionalRig`; defaults: Tables 1-2
    at the Fig. 7 operating point): disc_inertia J2 [kg m^2], shaft_stiffness k2 [N m/rad], shaft_damping d2
    [N m s/rad], motor_inertia J_m [kg m^2], gear_ratio eta, inductance L [H], resistance R [Ohm],
    torque_constant K_T [N m/A], back_emf_constant K_E [V s/rad], motor_friction_torque T_f [N m],
    motor_viscous_coefficient C_m [N m s/rad], proportional_gain k_p [V s/rad], integral_gain k_i [V/rad],
    reference_speed w_ref [rad/s], normal_force N2 [N], contact_radius r [m], initial_disc_speed [rad/s],
    initial_drive_speed [rad/s]; all optional. A file's cases are either all torsional or none.
``friction``
    ``type`` = "coulomb" | "stribeck" | "dahl" | "lugre" | "elasto_plastic" and the constructor's parameters by
    name (:class:`frictionsim.Coulomb` ...): mu, mu_static, stribeck_velocity [m/s], shape_exponent,
    viscous_coefficient [N s/m], karnopp_band [m/s], tangential_stiffness [N/m], exponent, bristle_stiffness [N/m],
    bristle_damping [N s/m], viscous_damping [N s/m], breakaway_fraction (elasto_plastic: z_ba / (mu F_N / sigma0)).
    On a torsional rig they act at contact_radius (v_r = r w2).
    Torsional rigs only: ``type = "hysteretic"``, paper 001's eq 6 (:class:`frictionsim.HystereticFriction`):
    stick_slope a [N m s/rad], accelerating = [p00, p10, p01, p20, p11, p02] and decelerating = [n00, ..., n02]
    (6 numbers each: N m, N m s/rad, kg m^2, N m s^2/rad^2, N m s^3/rad^2, N m s^4/rad^2), optional stick_speed
    w_s [rad/s], reference_normal_force [N], branch_gap ("hold" or "error"); ``type = "fig7"``: the eq 6 set
    chosen to reproduce paper 001's Fig. 7 (:func:`frictionsim.torsional.fig7_friction`; optional branch_gap).
``solver``
    t_end [s] (required), method (one of :data:`frictionsim.METHODS`), rtol (in [1e-14, 0.1]), atol (>= 1e-20),
    timeout [s] (wall-clock budget of each run), and output_points (default 2001, evenly spaced over [0, t_end],
    at most 1e6) or output_step [s]. The ends of the averaging window are always
    recorded as well, so the mean friction is exact to solver tolerance.
``analysis``
    transient [s], cycles, period [s] (default: the rig's vibration period 1/f; required for a velocity_file).
    The mean friction force F_df is taken over ``cycles`` whole cycles after ``transient``; without transient it
    is over the last ``cycles`` cycles before t_end; without either, over all whole cycles after t_end / 2.
    Torsional rigs: the limit cycle of the disc speed instead (:func:`frictionsim.torsional.limit_cycle`):
    transient [s] (default t_end / 2; must be < t_end) and stick_speed [rad/s] (default 0.01: |w2| at or below
    it counts as stuck). Summary: frequency [Hz], period [s], peak / trough / mean disc speed [rad/s], peak / w_ref,
    stick fraction, mean friction torque [N m] over the whole cycles measured (see
    :mod:`frictionsim.scenario_torsional`).
``output`` (top level only)
    directory (relative to the scenario file's folder, which it may not leave: no absolute path, no ``..`` or
    symbolic link out of it, unless ``frictionsim run --allow-outside``; ignored when ``--out`` is given; default
    ``out/<file stem>`` in the working directory), tables (subset of
    ["timeseries", "summary"]), plots (subset of ["friction_force", "hysteresis", "drive_force"]; torsional
    rigs: of ["disc_speed", "friction_torque_hysteresis", "phase_portrait"]), plot_window = [t_start, t_end] [s]
    (default: the last 3 vibration cycles; torsional: the last 10 s for disc_speed, [transient, t_end] for the
    others). The time series of a torsional case has t, the rig's states (disc_speed, drive_speed, shaft_twist,
    current, ...), disc_acceleration, friction_torque, shaft_torque, voltage and mode.

A case also takes ``name`` (file-name safe; default the friction type), ``description`` and ``lubricant``
("dry", "water", "wbm", "obm", "sbm": adds the Table 5 power-law F_df to the summary; not for torsional rigs).

Everything is validated by :func:`load` before anything runs: the law and rig objects are built (so the engine's
own rules reject non-physical values), and the averaging window is checked against t_end. Any problem raises
:class:`ScenarioError` naming the file and the key by its dotted path, e.g. ``case[2].friction.tangential_stiffness``
(cases count from 1 in file order).
"""

from __future__ import annotations

import dataclasses
import math
import stat
import re
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from . import scenario_torsional as _torsional
from .errors import InvalidParameterError
from .simulation import METHODS, simulate

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = [
    "AnalysisSpec", "Case", "CaseRun", "FrictionSpec", "OutputSpec", "RigSpec", "Scenario", "ScenarioError",
    "ScenarioRun", "SolverSpec", "load", "loads", "parse", "run", "run_case",
]

#: friction type -> (constructor name in frictionsim, required keys, optional keys); all values are numbers.
FRICTION_TYPES: Dict[str, Tuple[str, Tuple[str, ...], Tuple[str, ...]]] = {
    "coulomb": ("Coulomb", ("mu",), ("mu_static",)),
    "stribeck": ("Stribeck", ("mu", "mu_static", "stribeck_velocity"),
                 ("shape_exponent", "viscous_coefficient", "karnopp_band")),
    "dahl": ("Dahl", ("mu", "tangential_stiffness"), ("exponent",)),
    "lugre": ("LuGre", ("mu", "mu_static", "stribeck_velocity", "bristle_stiffness", "bristle_damping"),
              ("viscous_damping",)),
    "elasto_plastic": ("ElastoPlastic", ("mu", "mu_static", "stribeck_velocity", "bristle_stiffness",
                                         "bristle_damping"), ("viscous_damping", "breakaway_fraction")),
    **_torsional.FRICTION_TYPES,  # "hysteretic", "fig7": torsional rigs only
}
RIG_TYPES = ("axial", "kinematic", "torsional")
_AXIAL_KEYS = {"mass": float, "drive_stiffness": float, "sliding_velocity": float, "amplitude": float,
               "frequency": float, "normal_force": float, "gravity": bool, "gravitational_acceleration": float,
               "initial_position": float, "initial_velocity": float}
_KINEMATIC_KEYS = {"normal_force": float, "sliding_velocity": float, "velocity_amplitude": float,
                   "frequency": float, "velocity_file": str}
_HARMONIC = ("sliding_velocity", "velocity_amplitude", "frequency")
#: Output rows a scenario may ask for: 1e7 rows of a few states are ~0.5 GB of CSV already.
MAX_OUTPUT_POINTS = 1_000_000  # 1e7 took 4 minutes and 4.6 GB; 1e6 rows are ~100 MB of CSV per case
#: Free text is printed and drawn in every plot: a 100,000-character title took 65 s to render.
MAX_TITLE_CHARACTERS = 200
MAX_DESCRIPTION_CHARACTERS = 4000
#: A velocity_file is read whole: larger ones (or /dev/zero) are refused before reading.
MAX_DATA_FILE_BYTES = 256 * 2**20

_SOLVER_KEYS = {"t_end": float, "method": str, "rtol": float, "atol": float, "timeout": float, "output_points": int,
                "output_step": float}
_ANALYSIS_KEYS = {"transient": float, "cycles": int, "period": float}
_OUTPUT_KEYS = {"directory": str, "tables": list, "plots": list, "plot_window": list}
_CASE_KEYS = ("name", "description", "lubricant", "rig", "friction", "solver", "analysis")
_TOP_KEYS = ("title", "description", "rig", "friction", "solver", "analysis", "output", "case")
TABLES = ("timeseries", "summary")
PLOTS = ("friction_force", "hysteresis", "drive_force")
TORSIONAL_PLOTS = _torsional.PLOTS
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")
_RESERVED_NAMES = {"summary", "scenario"}


class ScenarioError(ValueError):
    """A scenario file breaks the schema: ``file``, ``key`` (dotted path, or None) and ``rule`` say where and why."""

    def __init__(self, file: Optional[Union[str, Path]], key: Optional[str], rule: str) -> None:
        self.file = str(file) if file is not None else "<scenario>"
        self.key = key
        self.rule = rule
        super().__init__(f"{self.file}: {key}: {rule}" if key else f"{self.file}: {rule}")


# ----------------------------------------------------------------------------------------------------------- specs
@dataclass(frozen=True)
class FrictionSpec:
    """A friction law: ``type`` and the constructor's keyword arguments (SI units; numbers, and for "hysteretic"
    two tuples of 6 numbers and the branch_gap string)."""

    type: str
    params: Dict[str, Any]

    @property
    def label(self) -> str:
        """The class name, e.g. "Dahl"."""
        return FRICTION_TYPES[self.type][0]

    @property
    def mu(self) -> float:
        """The (kinetic) friction coefficient mu [-] (NaN for the torque laws "hysteretic" and "fig7")."""
        return float(self.params["mu"]) if "mu" in self.params else math.nan

    def build(self):
        """The law object, e.g. ``frictionsim.Dahl(mu=0.41, tangential_stiffness=4e4)``."""
        if self.type in _torsional.TORSIONAL_ONLY:
            return _torsional.build_friction(self.type, self.params)
        return getattr(_core, self.label)(**self.params)


@dataclass(frozen=True)
class RigSpec:
    """A rig: ``type`` ("axial" | "kinematic" | "torsional") and its parameters in SI units (only the keys
    given)."""

    type: str
    params: Dict[str, Any]
    #: (t [s], v_r [m/s]) read from a kinematic rig's velocity_file
    samples: Optional[Tuple[np.ndarray, np.ndarray]] = field(default=None, compare=False, repr=False)

    def with_params(self, **changes: Any) -> "RigSpec":
        """A copy with some parameters changed (validated when the case is built)."""
        return dataclasses.replace(self, params={**self.params, **changes})

    @property
    def harmonic(self) -> bool:
        """Whether the rig vibrates harmonically (axial, or kinematic without a velocity_file)."""
        return self.type == "axial" or (self.type == "kinematic" and "velocity_file" not in self.params)

    def build(self, friction):
        """The rig object with the given law object."""
        if self.type == "axial":
            return _core.AxialVibrationRig(friction=friction, **self.params)
        if self.type == "torsional":
            return _core.TorsionalRig(friction, **self.params)
        if self.samples is not None:
            return _core.KinematicRig(friction, relative_velocity=self.samples,
                                      normal_force=float(self.params["normal_force"]))
        return _core.KinematicRig.harmonic(friction, **{k: float(v) for k, v in self.params.items()})


@dataclass(frozen=True)
class SolverSpec:
    """Solver settings: t_end [s], method, rtol, atol, and output_points or output_step [s]."""

    t_end: float
    method: str = "automatic"
    rtol: float = 1e-8
    atol: float = 1e-10
    output_points: Optional[int] = 2001
    output_step: Optional[float] = None
    timeout: Optional[float] = None  #: wall-clock budget of each run [s]

    def grid(self) -> np.ndarray:
        """The requested output times [s] over [0, t_end]."""
        if self.output_step is not None:
            times = np.arange(0.0, self.t_end, self.output_step)
            return np.append(times[times < self.t_end * (1 - 1e-12)], self.t_end)
        return np.linspace(0.0, self.t_end, int(self.output_points or 2))


@dataclass(frozen=True)
class AnalysisSpec:
    """Averaging window: transient [s], cycles, period [s]; torsional rigs: transient [s] and stick_speed
    [rad/s] of the limit cycle (None: see the module docstring)."""

    transient: Optional[float] = None
    cycles: Optional[int] = None
    period: Optional[float] = None
    stick_speed: Optional[float] = None


@dataclass(frozen=True)
class OutputSpec:
    """What ``frictionsim run`` writes, and where (directory relative to the working directory)."""

    directory: Optional[str] = None
    tables: Tuple[str, ...] = TABLES
    plots: Tuple[str, ...] = PLOTS
    plot_window: Optional[Tuple[float, float]] = None


@dataclass(frozen=True)
class Case:
    """One rig with one friction law, its solver settings and averaging window."""

    name: str
    rig: RigSpec
    friction: FrictionSpec
    solver: SolverSpec
    analysis: AnalysisSpec = AnalysisSpec()
    lubricant: Optional[str] = None
    description: str = ""

    def build(self):
        """The rig object (with its law)."""
        return self.rig.build(self.friction.build())

    @property
    def torsional(self) -> bool:
        """A torsional rig: analysed by its limit cycle (:mod:`frictionsim.scenario_torsional`)."""
        return self.rig.type == "torsional"

    @property
    def period(self) -> Optional[float]:
        """Averaging period [s]: analysis.period, else the rig's vibration period 1/f."""
        if self.analysis.period is not None:
            return self.analysis.period
        if self.rig.harmonic:
            return 1.0 / float(self.rig.params.get("frequency", _axial_default("frequency")))
        return None

    def window(self) -> Tuple[float, float, int]:
        """(t_a, t_b, cycles): the whole cycles [s] the mean friction is taken over (not for torsional rigs,
        whose cycles are found in the result: :class:`frictionsim.scenario_torsional.TorsionalCaseRun`)."""
        if self.torsional:
            raise ValueError("a torsional case has no vibration period: its limit cycle is measured after the run")
        period, t_end, a = self.period, self.solver.t_end, self.analysis
        transient = a.transient
        if transient is None:
            transient = t_end - a.cycles * period if a.cycles else 0.5 * t_end
        return tuple(_core.whole_cycle_window(0.0, t_end, period, transient, int(a.cycles or 0)))

    def output_times(self) -> np.ndarray:
        """The solver grid plus the window ends [s], so the cycle mean needs no interpolation (torsional: the
        grid)."""
        if self.torsional:
            return self.solver.grid()
        t_a, t_b, _ = self.window()
        return np.union1d(self.solver.grid(), [t_a, t_b])


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario file: its cases and outputs. ``name`` is the file stem."""

    name: str
    cases: Tuple[Case, ...]
    output: OutputSpec = OutputSpec()
    title: str = ""
    description: str = ""
    source: Optional[Path] = None
    #: the TOML text it was parsed from (copied into the output directory as scenario.toml)
    text: Optional[str] = field(default=None, compare=False, repr=False)


def _axial_default(name: str) -> Any:
    return getattr(_core.AxialVibrationRig(friction=_core.Coulomb(0.5)), name)


# ------------------------------------------------------------------------------------------------------ parsing
def load(path: Union[str, Path]) -> Scenario:
    """Read and validate a scenario file. Raises :class:`ScenarioError` naming the file and key."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise ScenarioError(path, None, f"cannot read the scenario file ({error.strerror or error})") from None
    except UnicodeDecodeError as error:
        raise ScenarioError(path, None, f"must be UTF-8 text (TOML); byte {error.start} is not") from None
    return loads(text, source=path)


def loads(text: str, *, source: Optional[Union[str, Path]] = None, name: Optional[str] = None) -> Scenario:
    """Parse and validate scenario TOML text. ``source`` names the file in errors and anchors relative paths."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ScenarioError(source, None, f"invalid TOML: {error}") from None
    return dataclasses.replace(parse(data, source=source, name=name), text=text)


def parse(data: Mapping[str, Any], *, source: Optional[Union[str, Path]] = None,
          name: Optional[str] = None) -> Scenario:
    """Validate a scenario already read into dicts (as :func:`tomllib.loads` returns) and build the specs."""
    return _Parser(source).scenario(data, name)


class _Parser:
    def __init__(self, source: Optional[Union[str, Path]]) -> None:
        self.source = Path(source) if source is not None else None
        self.rig_types: List[str] = []  # per case parsed so far

    def error(self, key: Optional[str], rule: str) -> ScenarioError:
        return ScenarioError(self.source, key, rule)

    # -- generic checks
    def table(self, value: Any, path: str) -> Dict[str, Any]:
        if not isinstance(value, dict):
            raise self.error(path, f"must be a table (got {_type_name(value)})")
        return value

    def unknown(self, table: Mapping[str, Any], allowed: Sequence[str], path: str, what: str = "") -> None:
        for key in table:
            if key not in allowed:
                raise self.error(_join(path, key), f"unknown key{what} (allowed: {', '.join(allowed)})")

    def value(self, value: Any, kind: type, path: str) -> Any:
        if kind is float:
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise self.error(path, f"must be a number (got {_type_name(value)} {value!r})")
            return float(value)
        if kind is int:
            if isinstance(value, bool) or not isinstance(value, int):
                raise self.error(path, f"must be an integer (got {_type_name(value)} {value!r})")
            return value
        if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
            wanted = {bool: "a boolean (true or false)", str: "a string", list: "an array"}[kind]
            raise self.error(path, f"must be {wanted} (got {_type_name(value)} {value!r})")
        return value

    def positive(self, value: float, path: str, *, allow_zero: bool = False) -> float:
        if not math.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
            rule = "non-negative and finite" if allow_zero else "positive and finite"
            raise self.error(path, f"must be {rule} (got {value:g})")
        return value

    def section(self, data: Mapping[str, Any], own: Mapping[str, Any], prefix: str,
                name: str) -> Tuple[Optional[Dict[str, Tuple[Any, str]]], str]:
        """(key -> (value, dotted path where written), path where a missing key belongs) of a case's section."""
        own_path = _join(prefix, name)
        merged = self.merged(data.get(name), name, own.get(name), own_path)
        home = name if name not in own and name in data else own_path
        return merged, home

    def merged(self, default: Any, default_path: str, own: Any, own_path: str) -> Optional[Dict[str, Tuple[Any, str]]]:
        """Key -> (value, dotted path of where it was written); the case's keys override the default's."""
        if own is not None:
            own = self.table(own, own_path)
        if default is not None:
            default = self.table(default, default_path)
            if own is not None and "type" in own and "type" in default and own["type"] != default["type"]:
                default = None  # a different type does not inherit another type's parameters
        if own is None and default is None:
            return None
        out = {k: (v, _join(default_path, k)) for k, v in (default or {}).items()}
        out.update({k: (v, _join(own_path, k)) for k, v in (own or {}).items()})
        return out

    def engine(self, error: InvalidParameterError, paths: Mapping[str, str], fallback: str) -> ScenarioError:
        """Re-raise an engine error at the key its ``parameter`` names."""
        message = str(error)
        rule = message.split(": ", 1)[1] if ": " in message else message
        rule = rule[rule.index("must"):] if "must" in rule else rule
        return self.error(paths.get(error.parameter, fallback), rule)

    # -- sections
    def scenario(self, data: Mapping[str, Any], name: Optional[str]) -> Scenario:
        self.unknown(data, _TOP_KEYS, "")
        title = self.value(data.get("title", ""), str, "title")
        description = self.value(data.get("description", ""), str, "description")
        for key, text, limit in (("title", title, MAX_TITLE_CHARACTERS),
                                 ("description", description, MAX_DESCRIPTION_CHARACTERS)):
            if len(text) > limit:
                raise self.error(key, f"must be at most {limit} characters (got {len(text)})")
        if "case" in data:
            if isinstance(data["case"], dict):
                raise self.error("case", "must be an array of tables: write [[case]], not [case]")
            raw_cases = self.value(data["case"], list, "case")
            if not raw_cases:
                raise self.error("case", "must hold at least one [[case]] table")
        else:
            raw_cases = [None]  # a single case made of the top-level sections
        cases: List[Case] = []
        for index, raw in enumerate(raw_cases, start=1):
            prefix = f"case[{index}]" if "case" in data else ""
            own = self.table(raw, prefix) if raw is not None else {}
            cases.append(self.case(data, own, prefix, index))
        names: Dict[str, int] = {}
        for index, case in enumerate(cases, start=1):
            if case.name in names:
                raise self.error(f"case[{index}].name", f"duplicate case name {case.name!r} "
                                                        f"(also case[{names[case.name]}])")
            names[case.name] = index
        output = self.output(data.get("output"), cases)
        stem = name or (self.source.stem if self.source is not None else "scenario")
        return Scenario(stem, tuple(cases), output, title, description, self.source)

    def case(self, data: Mapping[str, Any], own: Dict[str, Any], prefix: str, index: int) -> Case:
        self.unknown(own, _CASE_KEYS, prefix)
        friction, friction_paths = self.friction(*self.section(data, own, prefix, "friction"))
        try:
            law = friction.build()
        except InvalidParameterError as error:
            raise self.engine(error, friction_paths, _join(prefix, "friction")) from None

        rig, rig_paths = self.rig(*self.section(data, own, prefix, "rig"))
        self.rig_types.append(rig.type)
        if (rig.type == "torsional") != (self.rig_types[0] == "torsional"):
            raise self.error(rig_paths["_type"], f"a file's cases must be all torsional or all axial / kinematic "
                                                 f"(case[1] is {self.rig_types[0]}, got {rig.type!r}): their "
                                                 f"analyses and outputs differ")
        if friction.type in _torsional.TORSIONAL_ONLY and rig.type != "torsional":
            raise self.error(friction_paths["friction"], f"a {friction.type} law (paper 001 eq 6) runs only on a "
                                                         f"torsional rig (got a {rig.type} rig)")
        try:
            rig.build(law)
        except InvalidParameterError as error:
            raise self.engine(error, {**friction_paths, **rig_paths}, _join(prefix, "rig")) from None

        solver = self.solver(*self.section(data, own, prefix, "solver"))
        if rig.samples is not None and solver[0].t_end > rig.samples[0][-1]:
            raise self.error(solver[1]["t_end"], f"must be <= the last time of {rig.params['velocity_file']} "
                                                 f"({rig.samples[0][-1]:g} s) (got {solver[0].t_end:g})")
        analysis, analysis_paths = self.analysis(*self.section(data, own, prefix, "analysis"), rig.type)

        if "name" in own:
            name = self.value(own["name"], str, _join(prefix, "name"))
        else:
            name = friction.type if _unique_type(data, friction.type) else f"case{index}"
        if not _NAME.match(name) or name.lower() in _RESERVED_NAMES:
            raise self.error(_join(prefix, "name"), f"must be a file-name-safe word (letters, digits, _ . -; not "
                                                    f"{' or '.join(sorted(_RESERVED_NAMES))}) (got {name!r})")
        lubricant = own.get("lubricant")
        if lubricant is not None:
            if rig.type == "torsional":
                raise self.error(_join(prefix, "lubricant"), "only for axial and kinematic rigs (paper 000's Table 5 "
                                                             "power law), not for a torsional rig")
            lubricant = self.value(lubricant, str, _join(prefix, "lubricant")).lower()
            try:
                _core.PowerLawCoefficient.from_table5(lubricant)
            except InvalidParameterError as error:
                raise self.engine(error, {}, _join(prefix, "lubricant")) from None
        case = Case(name, rig, friction, solver[0], analysis, lubricant,
                    self.value(own.get("description", ""), str, _join(prefix, "description")))
        if case.torsional:
            self.check_transient(case, analysis_paths)
        else:
            self.check_window(case, {**analysis_paths, "t_end": solver[1]["t_end"]}, analysis_paths["_section"])
        return case

    def friction(self, merged, path: str) -> Tuple[FrictionSpec, Dict[str, str]]:
        if merged is None:
            raise self.error(path, "missing required table (give a [friction] default or one per case)")
        kind, type_path = self.type_of(merged, path, FRICTION_TYPES)
        _, required, optional = FRICTION_TYPES[kind]
        params, paths = {}, {}
        for key, (value, key_path) in merged.items():
            if key == "type":
                continue
            if key not in required + optional:
                raise self.error(key_path, f"unknown key for a {kind} law (allowed: type, "
                                           f"{', '.join(required + optional)})")
            value_kind = _torsional.VALUE_KINDS.get(key, float) if kind in _torsional.TORSIONAL_ONLY else float
            if value_kind == "coefficients":
                params[key] = self.coefficients(value, key_path)
            else:
                params[key] = self.value(value, value_kind, key_path)
            paths[key] = key_path
        for key in required:
            if key not in params:
                raise self.error(_join(path, key), f"missing required value for a {kind} law")
        for coefficient, key in _torsional.COEFFICIENT_KEYS.items():  # the engine names eq 6's p00 ... n02
            if key in paths:
                paths[coefficient] = paths[key]
        paths["friction"] = type_path
        return FrictionSpec(kind, params), paths

    def rig(self, merged, path: str) -> Tuple[RigSpec, Dict[str, str]]:
        if merged is None:
            raise self.error(path, "missing required table (give a [rig] default or one per case)")
        kind, type_path = self.type_of(merged, path, RIG_TYPES)
        keys = {"axial": _AXIAL_KEYS, "kinematic": _KINEMATIC_KEYS, "torsional": _torsional.RIG_KEYS}[kind]
        params, paths = {}, {"_type": type_path}
        for key, (value, key_path) in merged.items():
            if key == "type":
                continue
            if key not in keys:
                raise self.error(key_path, f"unknown key for {_article(kind)} {kind} rig (allowed: type, "
                                           f"{', '.join(keys)})")
            params[key], paths[key] = self.value(value, keys[key], key_path), key_path
        samples = None
        if kind == "kinematic":
            if "normal_force" not in params:
                raise self.error(_join(path, "normal_force"), "missing required value for a kinematic rig")
            given = [k for k in _HARMONIC if k in params]
            if "velocity_file" in params:
                if given:
                    raise self.error(paths[given[0]], "give either velocity_file or a harmonic velocity "
                                                      "(sliding_velocity, velocity_amplitude, frequency), not both")
                samples = self.samples(params["velocity_file"], paths["velocity_file"])
                for name in ("time", "relative_velocity", "value", "values"):
                    paths[name] = paths["velocity_file"]
            else:
                for key in _HARMONIC:
                    if key not in params:
                        raise self.error(_join(path, key), "missing required value for a kinematic rig (give "
                                                           "sliding_velocity, velocity_amplitude and frequency, "
                                                           "or velocity_file)")
        return RigSpec(kind, params, samples), paths

    def samples(self, name: str, path: str) -> Tuple[np.ndarray, np.ndarray]:
        file = Path(name)
        if not file.is_absolute() and self.source is not None:
            file = self.source.parent / file
        try:
            status = file.stat()
        except OSError as error:
            raise self.error(path, f"cannot read {str(file)!r} ({error.strerror or error})") from None
        if not stat.S_ISREG(status.st_mode):  # /dev/zero, a FIFO or a directory would be read forever or fail
            raise self.error(path, f"{str(file)!r} must be a regular file")
        if status.st_size > MAX_DATA_FILE_BYTES:
            raise self.error(path, f"{str(file)!r} must be at most {MAX_DATA_FILE_BYTES // 2**20} MiB "
                                   f"(it has {status.st_size / 2**20:.0f} MiB)")
        try:
            lines = file.read_text(encoding="utf-8").splitlines()
        except OSError as error:
            raise self.error(path, f"cannot read {str(file)!r} ({error.strerror or error})") from None
        except UnicodeDecodeError as error:
            raise self.error(path, f"{str(file)!r} must be UTF-8 text; byte {error.start} is not") from None
        rows = [line.split("#", 1)[0].strip() for line in lines]
        rows = [row for row in rows if row]
        try:
            if rows and not _numeric(rows[0]):
                rows = rows[1:]  # header row
            table = np.array([[float(x) for x in row.split(",")] for row in rows], dtype=float)
        except ValueError:
            table = np.empty((0, 0))
        if table.ndim != 2 or table.shape[0] < 2 or table.shape[1] != 2:
            raise self.error(path, f"{str(file)!r} must hold two numeric CSV columns t [s], v_r [m/s] with at "
                                   f"least two rows")
        if table[0, 0] > 0.0:  # runs start at t = 0
            raise self.error(path, f"{str(file)!r} must start at t <= 0 s, where the run starts "
                                   f"(its first time is {table[0, 0]:g} s)")
        return table[:, 0].copy(), table[:, 1].copy()

    def type_of(self, merged, path: str, allowed) -> Tuple[str, str]:
        if "type" not in merged:
            raise self.error(_join(path, "type"), f"missing required value (one of {', '.join(allowed)})")
        value, type_path = merged["type"]
        kind = self.value(value, str, type_path)
        if kind not in allowed:
            raise self.error(type_path, f"must be one of {', '.join(allowed)} (got {kind!r})")
        return kind, type_path

    def solver(self, merged, path: str) -> Tuple[SolverSpec, Dict[str, str]]:
        merged = merged or {}
        values, paths = {}, {"t_end": _join(path, "t_end")}
        for key, (value, key_path) in merged.items():
            if key not in _SOLVER_KEYS:
                raise self.error(key_path, f"unknown key (allowed: {', '.join(_SOLVER_KEYS)})")
            values[key], paths[key] = self.value(value, _SOLVER_KEYS[key], key_path), key_path
        if "t_end" not in values:
            raise self.error(_join(path, "t_end"), "missing required value (simulated time, s)")
        for key in ("t_end", "rtol", "atol", "output_step", "timeout"):
            if key in values:
                self.positive(values[key], paths[key])
        if values.get("method", "automatic") not in METHODS:
            raise self.error(paths["method"], f"must be one of {', '.join(METHODS)} (got {values['method']!r})")
        if "output_points" in values and "output_step" in values:
            raise self.error(paths["output_step"], "give output_points or output_step, not both")
        if "rtol" in values and not 1e-14 <= values["rtol"] <= _core.SolverOptions.max_rtol:
            raise self.error(paths["rtol"], f"must be in [1e-14, {_core.SolverOptions.max_rtol:g}]: looser, the "
                                            f"error estimates bound nothing (got {values['rtol']:g})")
        if "atol" in values and values["atol"] < _core.SolverOptions.min_atol:
            raise self.error(paths["atol"], f"must be >= {_core.SolverOptions.min_atol:g} (got {values['atol']:g})")
        if "output_points" in values and not 2 <= values["output_points"] <= MAX_OUTPUT_POINTS:
            raise self.error(paths["output_points"],
                             f"must be in [2, {MAX_OUTPUT_POINTS:.0e}] (got {values['output_points']})")
        if "output_step" in values:
            values["output_points"] = None
            if values["output_step"] > values["t_end"]:
                raise self.error(paths["output_step"], f"must be <= t_end (got {values['output_step']:g})")
            if values["t_end"] / values["output_step"] > MAX_OUTPUT_POINTS:
                raise self.error(paths["output_step"], f"must give at most {MAX_OUTPUT_POINTS:.0e} output points "
                                 f"(t_end / output_step = {values['t_end'] / values['output_step']:.3g})")
        return SolverSpec(**values), paths

    def analysis(self, merged, path: str, rig_type: str) -> Tuple[AnalysisSpec, Dict[str, str]]:
        values, paths = {}, {}
        torsional = rig_type == "torsional"
        keys = _torsional.ANALYSIS_KEYS if torsional else _ANALYSIS_KEYS
        for key, (value, key_path) in (merged or {}).items():
            if key not in keys:
                what = " for a torsional rig (its limit cycle)" if torsional else ""
                raise self.error(key_path, f"unknown key{what} (allowed: {', '.join(keys)})")
            values[key], paths[key] = self.value(value, keys[key], key_path), key_path
        if "stick_speed" in values:
            self.positive(values["stick_speed"], paths["stick_speed"])
        if "period" in values:
            self.positive(values["period"], paths["period"])
        if "cycles" in values and values["cycles"] < 1:
            raise self.error(paths["cycles"], f"must be at least 1 (got {values['cycles']})")
        paths.setdefault("_section", path)
        return AnalysisSpec(**values), paths

    def check_transient(self, case: Case, paths: Mapping[str, str]) -> None:
        """A torsional case's limit cycle is measured over [transient, t_end]."""
        transient, t_end = case.analysis.transient, case.solver.t_end
        if transient is not None and not (math.isfinite(transient) and 0.0 <= transient < t_end):
            raise self.error(paths["transient"], f"must be >= 0 and < t_end = {t_end:g} s (got {transient:g})")

    def coefficients(self, value: Any, path: str) -> Tuple[float, ...]:
        """An array of eq 6's 6 coefficients."""
        values = self.value(value, list, path)
        if len(values) != 6:
            raise self.error(path, f"must be an array of 6 numbers {_torsional.COEFFICIENT_NAMES} (got "
                                   f"{len(values)} values)")
        return tuple(self.value(x, float, f"{path}[{i + 1}]") for i, x in enumerate(values))

    def check_window(self, case: Case, paths: Mapping[str, str], fallback: str) -> None:
        if case.period is None:
            raise self.error(_join(fallback, "period"), "missing required value: a kinematic rig with a "
                                                        "velocity_file has no vibration period (s) to average over")
        a = case.analysis
        if a.transient is None and a.cycles and a.cycles * case.period > case.solver.t_end:
            raise self.error(paths["cycles"], f"the last {a.cycles} cycles ({a.cycles * case.period:g} s) must fit "
                                              f"in t_end = {case.solver.t_end:g} s")
        try:
            case.window()
        except InvalidParameterError as error:
            raise self.engine(error, paths, paths.get("transient", paths.get("cycles", fallback))) from None

    def output(self, raw: Any, cases: Sequence[Case]) -> OutputSpec:
        if raw is None:
            raw = {}
        raw = self.table(raw, "output")
        self.unknown(raw, tuple(_OUTPUT_KEYS), "output")
        values: Dict[str, Any] = {}
        for key, kind in _OUTPUT_KEYS.items():
            if key in raw:
                values[key] = self.value(raw[key], kind, f"output.{key}")
        torsional = cases[0].torsional
        for key, allowed in (("tables", TABLES), ("plots", TORSIONAL_PLOTS if torsional else PLOTS)):
            if key in values:
                what = " for torsional rigs" if torsional and key == "plots" else ""
                for i, item in enumerate(values[key]):
                    if item not in allowed:
                        raise self.error(f"output.{key}[{i + 1}]", f"must be one of {', '.join(allowed)}{what} "
                                                                   f"(got {item!r})")
                values[key] = tuple(dict.fromkeys(values[key]))
        has_axial = any(case.rig.type == "axial" for case in cases)
        if torsional:
            values.setdefault("plots", TORSIONAL_PLOTS)
        elif "plots" not in values:
            values["plots"] = tuple(p for p in PLOTS if p != "drive_force" or has_axial)
        elif "drive_force" in values["plots"] and not has_axial:
            raise self.error("output.plots", "drive_force needs at least one case with an axial rig")
        if "plot_window" in values:
            window = values["plot_window"]
            if len(window) != 2:
                raise self.error("output.plot_window", f"must be [t_start, t_end] in s (got {window!r})")
            window = tuple(self.value(x, float, f"output.plot_window[{i + 1}]") for i, x in enumerate(window))
            if not (math.isfinite(window[0]) and math.isfinite(window[1]) and 0 <= window[0] < window[1]):
                raise self.error("output.plot_window", f"must satisfy 0 <= t_start < t_end (got {list(window)})")
            shortest = min(case.solver.t_end for case in cases)
            if window[0] >= shortest:
                raise self.error("output.plot_window", f"must start before the shortest run ends "
                                                       f"(t_end = {shortest:g} s; got t_start = {window[0]:g})")
            values["plot_window"] = window
        return OutputSpec(**values)


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"


def _join(prefix: str, key: str) -> str:
    return f"{prefix}.{key}" if prefix else key


def _numeric(row: str) -> bool:
    try:
        [float(x) for x in row.split(",")]
        return True
    except ValueError:
        return False


def _unique_type(data: Mapping[str, Any], kind: str) -> bool:
    """Whether exactly one case uses friction ``kind`` (then the type names the case)."""
    default = data.get("friction") if isinstance(data.get("friction"), dict) else {}
    cases = data.get("case") if isinstance(data.get("case"), list) else [None]
    kinds = []
    for raw in cases:
        own = raw.get("friction") if isinstance(raw, dict) and isinstance(raw.get("friction"), dict) else {}
        kinds.append(own.get("type", default.get("type")))
    return kinds.count(kind) == 1


def _type_name(value: Any) -> str:
    if isinstance(value, bool):
        return "boolean"
    return {int: "integer", float: "float", str: "string", list: "array", dict: "table"}.get(type(value),
                                                                                              type(value).__name__)


# ------------------------------------------------------------------------------------------------------- running
@dataclass
class CaseRun:
    """A simulated case: the :class:`frictionsim.Result`, the rig object and the mean friction F_df [N]."""

    case: Case
    rig: Any
    result: Any
    mean_friction: float  #: F_df [N], mean over whole cycles
    window: Tuple[float, float, int]  #: (t_a [s], t_b [s], cycles)
    wall_time: float  #: s

    @property
    def normal_force(self) -> float:
        """F_N [N]."""
        return float(self.rig.normal_force) if self.case.rig.type == "axial" else \
            float(self.case.rig.params["normal_force"])

    @property
    def velocity_ratio(self) -> float:
        """v_a / v_d [-] (eq 16-17), NaN for a sampled velocity or v_d = 0."""
        if self.case.rig.type == "axial":
            v_a, v_d = float(self.rig.vibration_velocity_amplitude), float(self.rig.sliding_velocity)
        elif self.case.rig.harmonic:
            v_a, v_d = (float(self.case.rig.params[k]) for k in ("velocity_amplitude", "sliding_velocity"))
        else:
            return math.nan
        return v_a / v_d if v_d > 0 else math.nan

    def timeseries(self):
        """pandas DataFrame: t [s], the states (SI), relative_displacement [m], relative_velocity [m/s],
        friction_force [N], drive_force [N] (axial rigs) and mode (-1, 0, +1)."""
        import pandas as pd

        r, rig, spec = self.result, self.rig, self.case.rig
        t = r.t
        columns: Dict[str, np.ndarray] = {"t": t}
        columns.update((name, r[name]) for name in r.state_names)
        if spec.type == "axial":
            omega = 2 * math.pi * float(rig.frequency)
            columns["surface_position"] = float(rig.amplitude) * np.sin(omega * t)
            columns["surface_velocity"] = np.asarray(rig.surface_velocity(t), dtype=float)
            columns["relative_displacement"] = r["position"] - columns["surface_position"]
            columns["relative_velocity"] = r["velocity"] - columns["surface_velocity"]
        elif spec.samples is None:
            v_d, v_a, f = (float(spec.params[k]) for k in _HARMONIC)
            omega = 2 * math.pi * f
            columns["relative_displacement"] = v_d * t - v_a / omega * np.sin(omega * t)
            columns["relative_velocity"] = v_d - v_a * np.cos(omega * t)
        else:
            v = np.interp(t, *spec.samples)
            columns["relative_displacement"] = np.concatenate([[0.0], np.cumsum(np.diff(t) * 0.5 * (v[1:] + v[:-1]))])
            columns["relative_velocity"] = v
        columns["friction_force"] = r.friction_force
        if spec.type == "axial":
            columns["drive_force"] = np.asarray(rig.drive_force(t, r["position"]), dtype=float)
        columns["mode"] = r.mode
        return pd.DataFrame(columns)

    def summary(self) -> Dict[str, Any]:
        """One summary row: F_df [N], mu_df = F_df / F_N, reduction against mu F_N [%], events, steps, ..."""
        normal, mu = self.normal_force, self.case.friction.mu
        ratio = self.velocity_ratio
        table5 = math.nan
        if self.case.lubricant and math.isfinite(ratio):
            table5 = float(_core.PowerLawCoefficient.from_table5(self.case.lubricant).coefficient(ratio, 1.0)) * normal
        return {
            "case": self.case.name, "law": self.case.friction.label, "rig": self.case.rig.type,
            "F_N_N": normal, "mu": mu, "mu_F_N_N": mu * normal, "F_df_N": self.mean_friction,
            "mu_df": self.mean_friction / normal,
            "reduction_percent": 100.0 * (1.0 - self.mean_friction / (mu * normal)),
            "velocity_ratio": ratio, "F_df_table5_N": table5, "window_start_s": self.window[0],
            "window_end_s": self.window[1], "cycles": self.window[2], "events": len(self.result.events),
            "steps": int(self.result.stats["steps"]), "t_end_s": self.case.solver.t_end,
        }


def run_case(case: Case) -> Union[CaseRun, "_torsional.TorsionalCaseRun"]:
    """Simulate one case and take its mean friction over the analysis window (torsional rigs: measure its limit
    cycle, :class:`frictionsim.scenario_torsional.TorsionalCaseRun`).

    Raises :class:`frictionsim.SimulationError` (``time_reached``) when the integration stops early.
    """
    if case.torsional:
        return _torsional.run_case(case)
    rig = case.build()
    t_a, t_b, cycles = case.window()
    start = time.perf_counter()
    result = simulate(rig, case.solver.t_end, method=case.solver.method, rtol=case.solver.rtol,
                      atol=case.solver.atol, output_times=case.output_times(), timeout=case.solver.timeout)
    wall = time.perf_counter() - start
    mean = result.mean_over_cycles(period=case.period, transient=t_a, cycles=cycles)
    return CaseRun(case, rig, result, float(mean), (t_a, t_b, cycles), wall)


@dataclass
class ScenarioRun:
    """All cases of a scenario, simulated."""

    scenario: Scenario
    runs: List[Any]  #: CaseRun, or scenario_torsional.TorsionalCaseRun for torsional rigs

    @property
    def torsional(self) -> bool:
        """Torsional rigs (a file's cases are all torsional or none)."""
        return bool(self.runs) and self.runs[0].case.torsional

    def summary(self):
        """pandas DataFrame, one :meth:`CaseRun.summary` row per case."""
        import pandas as pd

        return pd.DataFrame([run.summary() for run in self.runs])

    def plot_window(self) -> Optional[Tuple[float, float]]:
        """output.plot_window, else the last 3 vibration cycles of the first case [s] (torsional: None, each
        plot has its own default window)."""
        if self.scenario.output.plot_window is not None or self.torsional:
            return self.scenario.output.plot_window
        first = self.runs[0]
        t_end = first.case.solver.t_end
        return (max(0.0, t_end - 3 * first.case.period), t_end)

    def write(self, directory: Union[str, Path]) -> List[Path]:
        """Write the CSV tables and PNG plots chosen in ``output`` into ``directory`` (which must exist)."""
        from . import plots

        directory = Path(directory)
        output, written = self.scenario.output, []
        frames = [(run.case.name, run.case.friction.label, run.timeseries()) for run in self.runs]
        if "timeseries" in output.tables:
            for name, _, frame in frames:
                written.append(directory / f"{name}.csv")
                _write_csv(frame, written[-1])
        if "summary" in output.tables:
            written.append(directory / "summary.csv")
            self.summary().to_csv(written[-1], index=False, float_format="%.10g")
        if self.scenario.text is not None and all(c.rig.samples is None for c in self.scenario.cases):
            # what was run, re-runnable with `frictionsim run` (not with a relative velocity_file: it would move)
            written.append(directory / "scenario.toml")
            written[-1].write_text(self.scenario.text, encoding="utf-8")
        title = self.scenario.title or self.scenario.name
        traces = [(f"{name} ({label})" if name.lower() != label.lower() else label, frame)
                  for name, label, frame in frames]
        if self.torsional:
            return written + _torsional.write_plots(self.runs, traces, output.plots, directory, title=title,
                                                    plot_window=output.plot_window)
        makers = {"friction_force": plots.friction_force_figure, "hysteresis": plots.hysteresis_figure,
                  "drive_force": plots.drive_force_figure}
        for plot in output.plots:
            figure = makers[plot](traces, title=title, window=self.plot_window())
            written.append(plots.save(figure, directory / f"{plot}.png"))
        return written


def _write_csv(frame, path: Path) -> None:
    """``frame.to_csv(path, index=False, float_format="%.10g")``, the same text, through numpy's C-level loop
    for purely numeric frames without NaN (3x faster: a torsional run writes 40001 rows of 17 columns)."""
    kinds = [frame[c].dtype.kind for c in frame.columns]
    values = frame.to_numpy(dtype=float) if all(k in "fiu" for k in kinds) else None
    if values is None or np.isnan(values).any():
        frame.to_csv(path, index=False, float_format="%.10g")
        return
    fmt = ",".join("%.10g" if k == "f" else "%d" for k in kinds)
    np.savetxt(path, values, fmt=fmt, delimiter=",", header=",".join(map(str, frame.columns)), comments="",
               encoding="utf-8")


def run(scenario: Scenario) -> ScenarioRun:
    """Simulate every case (serially; each takes milliseconds). Writes nothing."""
    return ScenarioRun(scenario, [run_case(case) for case in scenario.cases])
