"""Reading and validating scenario files (TOML, or a mapping as :func:`tomllib.loads` returns) into the specs of
:mod:`frictionsim.scenario.specs`. What a rig type allows is asked of its kind (:mod:`frictionsim.scenario.rigs`).
A number may be written as a string with its unit (``reference_speed = "55 rpm"``): it is converted to the key's SI
unit, read off the engine's parameter table (the schema's own keys: ``SCHEMA_UNITS``), by
:func:`frictionsim.units.to_si`; a unit of the wrong kind is a ScenarioError naming the key and the dimension.
"""

from __future__ import annotations

import dataclasses
import math
import re
import stat
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from .. import _core, units
from ..errors import InvalidParameterError
from ..simulation import METHODS, TIME_STEPPING_METHODS
from .rigs import RIG_KINDS, friction_types, plots_of
from .specs import AnalysisSpec, Case, FrictionSpec, OutputSpec, RigSpec, Scenario, SolverSpec, TABLES
from .text import article, join, type_name

try:
    import tomllib
except ImportError:  # Python < 3.11: its backport, a dependency there (pyproject.toml)
    import tomli as tomllib

__all__ = ["MAX_DATA_FILE_BYTES", "MAX_DESCRIPTION_CHARACTERS", "MAX_OUTPUT_POINTS", "MAX_TITLE_CHARACTERS",
           "ScenarioError", "load", "loads", "loads_toml", "parse", "read_toml"]

#: Output rows a scenario may ask for: 1e7 rows of a few states are ~0.5 GB of CSV already.
MAX_OUTPUT_POINTS = 1_000_000  # 1e7 took 4 minutes and 4.6 GB; 1e6 rows are ~100 MB of CSV per case
#: Free text is printed and drawn in every plot: a 100,000-character title took 65 s to render.
MAX_TITLE_CHARACTERS = 200
MAX_DESCRIPTION_CHARACTERS = 4000
#: A velocity_file is read whole: larger ones (or /dev/zero) are refused before reading.
MAX_DATA_FILE_BYTES = 256 * 2**20

#: The SI units of the schema's own keys (the rig and friction keys take theirs from the engine's tables): a value
#: may be written with a unit, e.g. t_end = "2 min".
SCHEMA_UNITS = {"t_end": "s", "timeout": "s", "step": "s", "output_step": "s", "transient": "s", "period": "s",
                "stick_speed": "rad/s", "surface_speeds": "rad/s", "weights_on_bit": "N", "plot_window": "s"}
_SOLVER_KEYS = {"t_end": float, "method": str, "rtol": float, "atol": float, "timeout": float, "output_points": int,
                "output_step": float, "step": float}
_OUTPUT_KEYS = {"directory": str, "tables": list, "plots": list, "plot_window": list}
_CASE_KEYS = ("name", "description", "lubricant", "rig", "friction", "solver", "analysis")
_TOP_KEYS = ("title", "description", "rig", "friction", "solver", "analysis", "output", "case")
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")
_RESERVED_NAMES = {"summary", "scenario"}


class ScenarioError(ValueError):
    """A scenario file breaks the schema: ``file``, ``key`` (dotted path, or None) and ``rule`` say where and why."""

    def __init__(self, file: Optional[Union[str, Path]], key: Optional[str], rule: str) -> None:
        self.file = str(file) if file is not None else "<scenario>"
        self.key = key
        self.rule = rule
        super().__init__(f"{self.file}: {key}: {rule}" if key else f"{self.file}: {rule}")


def read_toml(path: Union[str, Path], what: str = "scenario file") -> Tuple[str, Dict[str, Any]]:
    """(the text, the tables) of the TOML file ``path`` (a scenario or sweep file: ``what`` names it in errors).
    The one reader of the package's TOML files, so that each reads UTF-8 and speaks of a bad file alike (and
    finds tomli on Python < 3.11). Raises :class:`ScenarioError` naming the file: unreadable, not UTF-8, or not
    TOML."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise ScenarioError(path, None, f"cannot read the {what} ({error.strerror or error})") from None
    except UnicodeDecodeError as error:
        raise ScenarioError(path, None, f"must be UTF-8 text (TOML); byte {error.start} is not") from None
    return text, loads_toml(text, source=path)


def loads_toml(text: str, *, source: Optional[Union[str, Path]] = None) -> Dict[str, Any]:
    """The tables of TOML ``text``; a :class:`ScenarioError` naming ``source`` when it is not TOML."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ScenarioError(source, None, f"invalid TOML: {error}") from None


def load(path: Union[str, Path]) -> Scenario:
    """Read and validate a scenario file. Raises :class:`ScenarioError` naming the file and key."""
    text, data = read_toml(path)
    return dataclasses.replace(parse(data, source=Path(path)), text=text)


def loads(text: str, *, source: Optional[Union[str, Path]] = None, name: Optional[str] = None) -> Scenario:
    """Parse and validate scenario TOML text. ``source`` names the file in errors and anchors relative paths."""
    return dataclasses.replace(parse(loads_toml(text, source=source), source=source, name=name), text=text)


def parse(data: Mapping[str, Any], *, source: Optional[Union[str, Path]] = None,
          name: Optional[str] = None) -> Scenario:
    """Validate a scenario already read into dicts (as :func:`tomllib.loads` returns) and build the specs."""
    return _Parser(source).scenario(data, name)


class _Parser:
    def __init__(self, source: Optional[Union[str, Path]]) -> None:
        self.source = Path(source) if source is not None else None

    def error(self, key: Optional[str], rule: str) -> ScenarioError:
        return ScenarioError(self.source, key, rule)

    # -- generic checks
    def table(self, value: Any, path: str) -> Dict[str, Any]:
        if not isinstance(value, dict):
            raise self.error(path, f"must be a table (got {type_name(value)})")
        return value

    def unknown(self, table: Mapping[str, Any], allowed: Sequence[str], path: str, what: str = "") -> None:
        for key in table:
            if key not in allowed:
                raise self.error(join(path, key), f"unknown key{what} (allowed: {', '.join(allowed)})")

    def value(self, value: Any, kind: type, path: str) -> Any:
        if kind is float:
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise self.error(path, f"must be a number (got {type_name(value)} {value!r})")
            return float(value)
        if kind is int:
            if isinstance(value, bool) or not isinstance(value, int):
                raise self.error(path, f"must be an integer (got {type_name(value)} {value!r})")
            return value
        if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
            wanted = {bool: "a boolean (true or false)", str: "a string", list: "an array", dict: "a table"}[kind]
            raise self.error(path, f"must be {wanted} (got {type_name(value)} {value!r})")
        return value

    def measure(self, value: Any, unit: Optional[str], path: str) -> float:
        """A number (SI), or where the key has a ``unit``, a string with a unit ("55 rpm") converted to it."""
        if unit is not None and isinstance(value, str):
            try:
                value = units.to_si(value, unit, path)
            except InvalidParameterError as error:
                raise self.error(path, str(error)[len(path) + 2:]) from None
            except units.UnitsUnavailableError:
                raise self.error(path, f"{value!r} has a unit, and reading units needs pint: pip install "
                                       f"'frictionsim[units]'") from None
        return self.value(value, float, path)

    def positive(self, value: float, path: str, *, allow_zero: bool = False) -> float:
        if not math.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
            rule = "non-negative and finite" if allow_zero else "positive and finite"
            raise self.error(path, f"must be {rule} (got {value:g})")
        return value

    def section(self, data: Mapping[str, Any], own: Mapping[str, Any], prefix: str,
                name: str) -> Tuple[Optional[Dict[str, Tuple[Any, str]]], str]:
        """(key -> (value, dotted path where written), path where a missing key belongs) of a case's section."""
        own_path = join(prefix, name)
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
        out = {k: (v, join(default_path, k)) for k, v in (default or {}).items()}
        out.update({k: (v, join(own_path, k)) for k, v in (own or {}).items()})
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
            cases.append(self.case(data, own, prefix, index, cases[0] if cases else None))
        names: Dict[str, int] = {}
        for index, case in enumerate(cases, start=1):
            if case.name in names:
                raise self.error(f"case[{index}].name", f"duplicate case name {case.name!r} "
                                                        f"(also case[{names[case.name]}])")
            names[case.name] = index
        output = self.output(data.get("output"), cases)
        stem = name or (self.source.stem if self.source is not None else "scenario")
        return Scenario(stem, tuple(cases), output, title, description, self.source)

    def case(self, data: Mapping[str, Any], own: Dict[str, Any], prefix: str, index: int,
             first: Optional[Case]) -> Case:
        self.unknown(own, _CASE_KEYS, prefix)
        friction, friction_paths = self.friction(*self.section(data, own, prefix, "friction"))
        try:
            law = friction.build()
        except InvalidParameterError as error:
            raise self.engine(error, friction_paths, join(prefix, "friction")) from None

        rig, rig_paths = self.rig(*self.section(data, own, prefix, "rig"))
        kind = rig.kind
        if first is not None and first.kind.analysis is not kind.analysis:
            groups = " or ".join(f"all {' / '.join(self.sharing(k.analysis))}" for k in (first.kind, kind))
            raise self.error(rig_paths["_type"], f"a file's cases must be {groups} (case[1] is {first.rig.type}, "
                                                 f"got {rig.type!r}): their analyses and outputs differ")
        only_on = friction_types()[friction.type].rig
        if only_on is not None and only_on != rig.type:
            raise self.error(friction_paths["friction"], f"a {friction.type} law "
                                                         f"({friction_types()[friction.type].origin}) runs only on "
                                                         f"{article(only_on)} {only_on} rig (got a {rig.type} rig)")
        try:
            rig.build(law)
        except InvalidParameterError as error:
            raise self.engine(error, {**friction_paths, **rig_paths}, join(prefix, "rig")) from None

        solver = self.solver(*self.section(data, own, prefix, "solver"))
        self.time_stepping_rules(rig, solver[0], {**solver[1], **rig_paths}, prefix)
        if rig.samples is not None and solver[0].t_end > rig.samples[0][-1]:
            raise self.error(solver[1]["t_end"], f"must be <= the last time of {rig.params['velocity_file']} "
                                                 f"({rig.samples[0][-1]:g} s) (got {solver[0].t_end:g})")
        analysis, analysis_paths = self.analysis(*self.section(data, own, prefix, "analysis"), kind)

        if "name" in own:
            name = self.value(own["name"], str, join(prefix, "name"))
        else:
            name = friction.type if _unique_type(data, friction.type) else f"case{index}"
        if not _NAME.match(name) or name.lower() in _RESERVED_NAMES:
            raise self.error(join(prefix, "name"), f"must be a file-name-safe word (letters, digits, _ . -; not "
                                                   f"{' or '.join(sorted(_RESERVED_NAMES))}) (got {name!r})")
        lubricant = own.get("lubricant")
        if lubricant is not None:
            if not kind.lubricant:
                kinds = " and ".join(k.name for k in RIG_KINDS.values() if k.lubricant)
                raise self.error(join(prefix, "lubricant"), f"only for {kinds} rigs (paper 000's Table 5 power "
                                                            f"law), not for {kind.describe(rig)}")
            lubricant = self.value(lubricant, str, join(prefix, "lubricant")).lower()
            try:
                _core.PowerLawCoefficient.from_table5(lubricant)
            except InvalidParameterError as error:
                raise self.engine(error, {}, join(prefix, "lubricant")) from None
        case = Case(name, rig, friction, solver[0], analysis, lubricant,
                    self.value(own.get("description", ""), str, join(prefix, "description")))
        kind.analysis.check(self, case, {**analysis_paths, "t_end": solver[1]["t_end"]})
        return case

    @staticmethod
    def sharing(analysis) -> Tuple[str, ...]:
        """The rig types whose cases share ``analysis`` (and so may stand in one file)."""
        return tuple(name for name, kind in RIG_KINDS.items() if kind.analysis is analysis)

    def friction(self, merged, path: str) -> Tuple[FrictionSpec, Dict[str, str]]:
        if merged is None:
            raise self.error(path, "missing required table (give a [friction] default or one per case)")
        kind, type_path = self.type_of(merged, path, tuple(friction_types()))
        law = friction_types()[kind]
        parameters = {p.name: p for p in law.parameters}
        law_units = units.units_of(law.make)
        params, paths = {}, {}
        for key, (value, key_path) in merged.items():
            if key == "type":
                continue
            if key not in parameters:
                raise self.error(key_path, f"unknown key for a {kind} law (allowed: type, "
                                           f"{', '.join(parameters)})")
            parameter = parameters[key]
            if parameter.kind is tuple:
                params[key] = self.numbers(value, parameter.size, law.arrays.get(key, ""), key_path)
            elif parameter.kind is float:
                params[key] = self.measure(value, law_units.get(key), key_path)
            else:
                params[key] = self.value(value, parameter.kind, key_path)
            paths[key] = key_path
        for key, parameter in parameters.items():
            if parameter.required and key not in params:
                raise self.error(join(path, key), f"missing required value for a {kind} law")
        for name, key in law.aliases.items():  # e.g. the engine names eq 6's p00 ... n02
            if key in paths:
                paths[name] = paths[key]
        paths["friction"] = type_path
        return FrictionSpec(kind, params), paths

    def rig(self, merged, path: str) -> Tuple[RigSpec, Dict[str, str]]:
        if merged is None:
            raise self.error(path, "missing required table (give a [rig] default or one per case)")
        name, type_path = self.type_of(merged, path, tuple(RIG_KINDS))
        kind = RIG_KINDS[name]
        params, paths = {}, {"_type": type_path}
        for key, (value, key_path) in merged.items():
            if key == "type":
                continue
            if key not in kind.keys:
                raise self.error(key_path, f"unknown key for {article(name)} {name} rig (allowed: type, "
                                           f"{', '.join(kind.keys)})")
            if kind.keys[key] is float:
                params[key] = self.measure(value, kind.units.get(key), key_path)
            else:
                params[key] = self.value(value, kind.keys[key], key_path)
            paths[key] = key_path
        samples = kind.check(self, params, paths, path)
        return RigSpec(name, params, samples), paths

    def samples(self, name: str, path: str) -> Tuple[np.ndarray, np.ndarray]:
        """The two columns t [s], v [SI] of the CSV file ``name`` (relative to the scenario file)."""
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

    def type_of(self, merged, path: str, allowed: Sequence[str]) -> Tuple[str, str]:
        if "type" not in merged:
            raise self.error(join(path, "type"), f"missing required value (one of {', '.join(allowed)})")
        value, type_path = merged["type"]
        kind = self.value(value, str, type_path)
        if kind not in allowed:
            raise self.error(type_path, f"must be one of {', '.join(allowed)} (got {kind!r})")
        return kind, type_path

    def solver(self, merged, path: str) -> Tuple[SolverSpec, Dict[str, str]]:
        merged = merged or {}
        values, paths = {}, {"t_end": join(path, "t_end")}
        for key, (value, key_path) in merged.items():
            if key not in _SOLVER_KEYS:
                raise self.error(key_path, f"unknown key (allowed: {', '.join(_SOLVER_KEYS)})")
            if _SOLVER_KEYS[key] is float:
                values[key] = self.measure(value, SCHEMA_UNITS.get(key), key_path)
            else:
                values[key] = self.value(value, _SOLVER_KEYS[key], key_path)
            paths[key] = key_path
        if "t_end" not in values:
            raise self.error(join(path, "t_end"), "missing required value (simulated time, s)")
        for key in ("t_end", "rtol", "atol", "output_step", "timeout", "step"):
            if key in values:
                self.positive(values[key], paths[key])
        if values.get("method", "automatic") not in METHODS:
            raise self.error(paths["method"], f"must be one of {', '.join(METHODS)} (got {values['method']!r})")
        if "output_points" in values and "output_step" in values:
            raise self.error(paths["output_step"], "give output_points or output_step, not both")
        self.engine_solver_rules(values, paths)
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

    def time_stepping_rules(self, rig: RigSpec, solver: SolverSpec, paths: Dict[str, str], prefix: str) -> None:
        """A fixed ``step`` and a time-stepping method only for a time-stepping rig (a drillstring's captured or
        mixed treatment), and an ODE method only for the others."""
        stepped = rig.kind.time_stepping(rig)
        if solver.step is not None and not stepped:
            raise self.error(paths["step"], f"only a time-stepped rig takes a fixed step (a drillstring rig with "
                                            f"treatment captured or mixed; got {article(rig.type)} {rig.type} rig"
                                            + (" with treatment exact)" if rig.type == "drillstring" else ")"))
        if solver.method != "automatic" and (solver.method in TIME_STEPPING_METHODS) != stepped:
            rule = (f"must be automatic or one of {', '.join(TIME_STEPPING_METHODS)} for a time-stepped rig"
                    if stepped else f"must not be a time-stepping method ({', '.join(TIME_STEPPING_METHODS)}) on "
                                    f"an event-driven rig")
            raise self.error(paths["method"], f"{rule} (treatment {rig.params.get('treatment', 'exact')!r}; got "
                                              f"{solver.method!r})" if rig.type == "drillstring"
                             else f"{rule} (got {solver.method!r})")

    def engine_solver_rules(self, values: Dict[str, Any], paths: Dict[str, str]) -> None:
        """The engine's own rules on rtol, atol and timeout (SolverOptions.validate), reported at the file's key."""
        options = _core.SolverOptions()
        for key in ("rtol", "atol", "timeout"):
            if key in values:
                setattr(options, key, values[key])
        try:
            options.validate()
        except InvalidParameterError as error:
            raise self.engine(error, paths, "solver") from None

    def analysis(self, merged, path: str, kind) -> Tuple[AnalysisSpec, Dict[str, str]]:
        values, paths = {}, {}
        keys = kind.analysis.keys
        for key, (value, key_path) in (merged or {}).items():
            if key not in keys:
                raise self.error(key_path, f"unknown key{kind.analysis.unknown_note(kind)} "
                                           f"(allowed: {', '.join(keys)})")
            if keys[key] is float:
                values[key] = self.measure(value, SCHEMA_UNITS.get(key), key_path)
            else:
                values[key] = self.value(value, keys[key], key_path)
            paths[key] = key_path
            if keys[key] is list:  # an analysis's arrays are of numbers (a drill string's map grid)
                values[key] = self.numbers(value, None, "", key_path, SCHEMA_UNITS.get(key))
        if "stick_speed" in values:
            self.positive(values["stick_speed"], paths["stick_speed"])
        if "period" in values:
            self.positive(values["period"], paths["period"])
        if "cycles" in values and values["cycles"] < 1:
            raise self.error(paths["cycles"], f"must be at least 1 (got {values['cycles']})")
        paths.setdefault("_section", path)
        return AnalysisSpec(**values), paths

    def numbers(self, value: Any, size: Optional[int], names: str, path: str,
                unit: Optional[str] = None) -> Tuple[float, ...]:
        """An array of ``size`` numbers (``names``: what they are, for the error), each in ``unit`` if given."""
        values = self.value(value, list, path)
        if size is not None and len(values) != size:
            raise self.error(path, f"must be an array of {size} numbers {names} (got {len(values)} values)")
        return tuple(self.measure(x, unit, f"{path}[{i + 1}]") for i, x in enumerate(values))

    def output(self, raw: Any, cases: Sequence[Case]) -> OutputSpec:
        if raw is None:
            raw = {}
        raw = self.table(raw, "output")
        self.unknown(raw, tuple(_OUTPUT_KEYS), "output")
        values: Dict[str, Any] = {}
        for key, kind in _OUTPUT_KEYS.items():
            if key in raw:
                values[key] = self.value(raw[key], kind, f"output.{key}")
        analysis = cases[0].kind.analysis
        plots = plots_of(analysis)
        for key, allowed in (("tables", TABLES), ("plots", plots)):
            if key in values:
                what = analysis.plots_note(self.sharing(analysis)) if key == "plots" else ""
                for i, item in enumerate(values[key]):
                    if item not in allowed:
                        raise self.error(f"output.{key}[{i + 1}]", f"must be one of {', '.join(allowed)}{what} "
                                                                   f"(got {item!r})")
                values[key] = tuple(dict.fromkeys(values[key]))
        drawn = {plot for case in cases for plot in case.kind.plots}  # what the file's rigs can draw
        if "plots" not in values:
            values["plots"] = tuple(plot for plot in plots if plot in drawn)
        for plot in values["plots"]:
            if plot not in drawn:
                kinds = " or ".join(f"{article(k.name)} {k.name}" for k in RIG_KINDS.values() if plot in k.plots)
                raise self.error("output.plots", f"{plot} needs at least one case with {kinds} rig")
        if "plot_window" in values:
            window = values["plot_window"]
            if len(window) != 2:
                raise self.error("output.plot_window", f"must be [t_start, t_end] in s (got {window!r})")
            window = tuple(self.measure(x, SCHEMA_UNITS["plot_window"], f"output.plot_window[{i + 1}]")
                           for i, x in enumerate(window))
            if not (math.isfinite(window[0]) and math.isfinite(window[1]) and 0 <= window[0] < window[1]):
                raise self.error("output.plot_window", f"must satisfy 0 <= t_start < t_end (got {list(window)})")
            shortest = min(case.solver.t_end for case in cases)
            if window[0] >= shortest:
                raise self.error("output.plot_window", f"must start before the shortest run ends "
                                                       f"(t_end = {shortest:g} s; got t_start = {window[0]:g})")
            values["plot_window"] = window
        return OutputSpec(**values)


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
