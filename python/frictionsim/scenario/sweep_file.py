"""Sweep files: one scenario run over a grid of its parameters (``frictionsim sweep FILE.toml``).

A sweep file is a scenario file (:mod:`frictionsim.scenario`) with a ``[grid]`` table: each grid key is a dotted
``section.key`` of the scenario (section one of rig, friction, solver, analysis) with the values it takes. Every
combination of the values is one point (the Cartesian product, last key varying fastest); at each point the
scenario's selected cases are run and their summary rows kept. The scenario is either written inline (the
scenario file's own keys: rig, friction, solver, analysis, [[case]]) or named by ``scenario``, a path relative to
the sweep file::

    title = "Fig. 7 dry, Dahl: friction reduction over amplitude and frequency"
    scenario = "fig7_dry_coulomb_vs_dahl.toml"   # or the scenario's own tables here
    cases = ["dahl"]                               # default: every case
    [grid]
    "rig.amplitude" = [1e-3, 3e-3, 5e-3]           # m: a list of values ...
    "rig.frequency" = { start = 10.0, stop = 25.0, num = 4 }                    # ... or evenly spaced
    "friction.tangential_stiffness" = { start = 1e4, stop = 1e5, num = 3, scale = "log" }
    [output]
    directory = "out/fig7_dry_sweep"   # as a scenario's output.directory (relative, confined to the folder)
    value = "F_df_N"                    # the summary column plotted against the first grid key
    columns = ["F_df_N", "reduction_percent"]    # summary columns kept (default: all)

A grid value replaces the key in the scenario's top-level table (when it has one, or has no [[case]]) and in
every [[case]] table of that section, so that the point's value holds in every case. Each point is validated by
the scenario parser before anything runs; a bad value is reported against the grid key and its position
(``grid."rig.amplitude"[2]: ...``). Errors raise :class:`~frictionsim.scenario.ScenarioError` naming the file,
the key and the rule.

A grid value may carry a unit as any scenario value may (``"rig.normal_force" = ["10 klbf", "5 kN"]``): the
point's scenario reads it in SI, and so do the outputs (:attr:`SweepFile.si_points`).

Outputs (:meth:`SweepRun.write`): ``sweep.csv`` (one row per point and case: the grid keys in SI, the text of
a key given with units in a column ``<key> (given)``, then the summary columns), ``sweep.png`` (``output.value``
against the first grid key, one line per case and combination of the other keys; skipped, with a log message,
when that key is not numeric) and ``sweep.toml`` (the sweep file as run).
"""

from __future__ import annotations

import copy
import dataclasses
import itertools
import logging
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ..atomic import write_csv, write_text
from .. import units
from ..errors import InvalidParameterError
from .parser import SCHEMA_UNITS, ScenarioError, loads_toml, parse, read_toml
from .rigs import RIG_KINDS, friction_types
from .specs import Scenario
from .staging import staged_directory

__all__ = ["GRID_SECTIONS", "MAX_POINTS", "SweepFile", "SweepOutput", "SweepRun", "load", "loads", "run",
           "run_point"]

#: The scenario sections a grid key may name.
GRID_SECTIONS = ("rig", "friction", "solver", "analysis")
#: At most this many grid points (each runs every selected case).
MAX_POINTS = 10_000
#: At most this many lines in sweep.png (the rest of the combinations are in sweep.csv only).
MAX_LINES = 12
#: output.value when the file gives none: the first of these the summary has.
DEFAULT_VALUES = ("F_df_N", "peak_ratio", "frequency_Hz")

log = logging.getLogger("frictionsim")

_SWEEP_KEYS = ("scenario", "cases", "grid")
_SCENARIO_KEYS = ("rig", "friction", "solver", "analysis", "case")
_OUTPUT_KEYS = ("directory", "value", "columns")
_RANGE_KEYS = ("start", "stop", "num", "scale")


@dataclass(frozen=True)
class SweepOutput:
    """The ``[output]`` table: directory (as a scenario's), value (the plotted summary column; None: the first
    of :data:`DEFAULT_VALUES` present), columns (the summary columns kept; None: all)."""

    directory: Optional[str] = None
    value: Optional[str] = None
    columns: Optional[Tuple[str, ...]] = None


@dataclass(frozen=True)
class SweepFile:
    """A validated sweep file.

    ``axes``: grid key -> its values, in file order; ``log_axes``: the keys given with ``scale = "log"``;
    ``points``: the grid values of each point (C order), as given; ``si_points``: the same in SI, as the
    point's scenario reads them (a value given with a unit, "10 klbf", is its number there, 44482.2...);
    ``si_units``: grid key -> its SI unit where one was given with a unit; ``scenarios``: the scenario of each
    point, validated, holding only the selected cases; ``text``: the file's text (None when parsed from a mapping).
    """

    name: str
    title: str
    description: str
    source: Optional[Path]
    axes: Dict[str, Tuple[Any, ...]]
    log_axes: Tuple[str, ...]
    points: Tuple[Dict[str, Any], ...]
    scenarios: Tuple[Scenario, ...]
    output: SweepOutput
    text: Optional[str] = None
    si_points: Tuple[Dict[str, Any], ...] = ()
    si_units: Dict[str, str] = dataclasses.field(default_factory=dict)

    @property
    def given_with_units(self) -> Tuple[str, ...]:
        """The grid keys with a value given as text with a unit (their SI numbers differ from the text)."""
        return tuple(key for key in self.axes if key in self.si_units)

    @property
    def grid_shape(self) -> Tuple[int, ...]:
        return tuple(len(values) for values in self.axes.values())

    @property
    def cases(self) -> Tuple[str, ...]:
        """The names of the cases run at each point."""
        return tuple(case.name for case in self.scenarios[0].cases)


def load(path: Union[str, Path]) -> SweepFile:
    """Read and validate a sweep file. Raises :class:`ScenarioError` naming the file and key."""
    text, data = read_toml(path, "sweep file")
    return dataclasses.replace(parse_sweep(data, source=Path(path)), text=text)


def loads(text: str, *, source: Optional[Union[str, Path]] = None, name: Optional[str] = None) -> SweepFile:
    """Parse and validate sweep TOML text; ``source`` names the file in errors and anchors relative paths."""
    return dataclasses.replace(parse_sweep(loads_toml(text, source=source), source=source, name=name), text=text)


def parse_sweep(data: Mapping[str, Any], *, source: Optional[Union[str, Path]] = None,
                name: Optional[str] = None) -> SweepFile:
    """Validate a sweep file already read into dicts and build every point's scenario."""
    source = Path(source) if source is not None else None

    def error(key: Optional[str], rule: str) -> ScenarioError:
        return ScenarioError(source, key, rule)

    allowed = ("title", "description", "output") + _SWEEP_KEYS + _SCENARIO_KEYS
    for key in data:
        if key not in allowed:
            raise error(key, f"unknown key (allowed: {', '.join(allowed)})")
    title = _typed(data.get("title", ""), str, "title", error)
    description = _typed(data.get("description", ""), str, "description", error)
    output = _output(data.get("output", {}), error)

    inline = {key: data[key] for key in _SCENARIO_KEYS if key in data}
    if "scenario" in data:
        if inline:
            raise error("scenario", f"give the scenario either by file or inline, not both (found "
                                    f"{', '.join(inline)} here too)")
        reference = Path(_typed(data["scenario"], str, "scenario", error))
        scenario_file = reference if reference.is_absolute() or source is None else source.parent / reference
        try:
            _, base = read_toml(scenario_file, "scenario file")
        except ScenarioError as unreadable:
            if unreadable.rule.startswith("invalid TOML"):  # the scenario file's own fault: named as such
                raise
            raise error("scenario", unreadable.rule) from None
        base.pop("output", None)  # the sweep writes its own outputs
    else:
        if "rig" not in inline and "case" not in inline:
            raise error(None, "needs a scenario: a 'scenario' file or the scenario's own tables (rig, friction, "
                              "solver, analysis, [[case]])")
        scenario_file, base = source, copy.deepcopy(inline)

    axes, log_axes = _grid(data.get("grid"), error)
    shape = [len(values) for values in axes.values()]
    count = math.prod(shape)
    if count > MAX_POINTS:
        raise error("grid", f"must have at most {MAX_POINTS} points (got {' x '.join(map(str, shape))} = {count})")

    base = _selected(base, data.get("cases"), scenario_file, error)
    keys = list(axes)
    points, scenarios = [], []
    for index, values in enumerate(itertools.product(*axes.values())):
        point = dict(zip(keys, values))
        scenario = _point_scenario(base, point, scenario_file, axes, index, error)
        points.append(point)
        scenarios.append(scenario)
    stem = name or (source.stem if source is not None else "sweep")
    si_points, si_units = _si_points(axes, points, scenarios)
    return SweepFile(stem, title, description, source, axes, log_axes, tuple(points), tuple(scenarios), output,
                     si_points=si_points, si_units=si_units)


def _si_points(axes: Mapping[str, Sequence[Any]], points: Sequence[Dict[str, Any]],
               scenarios: Sequence[Scenario]) -> Tuple[Tuple[Dict[str, Any], ...], Dict[str, str]]:
    """The points in SI, read back from each point's parsed scenario for the keys given as text with a unit."""
    si_units: Dict[str, str] = {}
    for key, values in axes.items():
        if not any(isinstance(v, str) for v in values):
            continue
        read = [_read_back(scenario, key) for scenario in scenarios]
        if all(isinstance(v, float) for v in read):  # a key with a unit (a method name stays text)
            si_units[key] = _unit_of(scenarios[0], key) or "SI"
    si_points = tuple({key: _read_back(scenario, key) if key in si_units else value for key, value in point.items()}
                      for point, scenario in zip(points, scenarios))
    return si_points, si_units


def _read_back(scenario: Scenario, key: str) -> Any:
    """The value the grid key holds in ``scenario``'s first case (every case holds the point's value)."""
    section, _, name = key.partition(".")
    case = scenario.cases[0]
    if section in ("rig", "friction"):
        return getattr(case, section).params.get(name)
    return getattr(getattr(case, section), name, None)


def _unit_of(scenario: Scenario, key: str) -> Optional[str]:
    """The SI unit of a grid key, as the scenario parser converts it."""
    section, _, name = key.partition(".")
    case = scenario.cases[0]
    if section == "rig":
        return RIG_KINDS[case.rig.type].units.get(name)
    if section == "friction":
        return units.units_of(friction_types()[case.friction.type].make).get(name)
    return SCHEMA_UNITS.get(name)


def _typed(value: Any, kind: type, key: str, error: Callable[..., ScenarioError]) -> Any:
    if not isinstance(value, kind) or isinstance(value, bool) and kind is not bool:
        raise error(key, f"must be {'a string' if kind is str else 'a ' + kind.__name__} "
                         f"(got {type(value).__name__} {value!r})")
    return value


def _output(raw: Any, error: Callable[..., ScenarioError]) -> SweepOutput:
    table = _typed(raw, dict, "output", error)
    for key in table:
        if key not in _OUTPUT_KEYS:
            raise error(f"output.{key}", f"unknown key (allowed: {', '.join(_OUTPUT_KEYS)})")
    directory = _typed(table["directory"], str, "output.directory", error) if "directory" in table else None
    value = _typed(table["value"], str, "output.value", error) if "value" in table else None
    columns = None
    if "columns" in table:
        columns = tuple(_typed(c, str, f"output.columns[{i}]", error)
                        for i, c in enumerate(_typed(table["columns"], list, "output.columns", error)))
        if not columns:
            raise error("output.columns", "must name at least one summary column")
    return SweepOutput(directory, value, columns)


def _grid(raw: Any, error: Callable[..., ScenarioError]) -> Tuple[Dict[str, Tuple[Any, ...]], Tuple[str, ...]]:
    if raw is None:
        raise error("grid", "is required: a table of \"section.key\" = [values] (section one of "
                            f"{', '.join(GRID_SECTIONS)})")
    table = _typed(raw, dict, "grid", error)
    if not table:
        raise error("grid", "must hold at least one key")
    axes, log_axes = {}, []
    for key, values in table.items():
        where = f'grid."{key}"'
        section, _, name = key.partition(".")
        if section not in GRID_SECTIONS or not name or "." in name:
            if isinstance(values, dict) and section in GRID_SECTIONS and not name:  # [grid.rig] sub-table
                raise error(where, f'write the key quoted, "{key}.<key>" = [...], not a [grid.{key}] table')
            raise error(where, f"must be a quoted \"section.key\" with section one of {', '.join(GRID_SECTIONS)} "
                               "(e.g. \"rig.amplitude\")")
        if name == "type":
            raise error(where, "cannot vary a section's type (run one sweep per type, or list them as [[case]])")
        if isinstance(values, dict):
            values, log = _range(values, where, error)
            if log:
                log_axes.append(key)
        elif isinstance(values, list):
            if not values:
                raise error(where, "must hold at least one value")
        else:
            raise error(where, f"must be a list of values or a table {{start, stop, num[, scale]}} "
                               f"(got {type(values).__name__} {values!r})")
        axes[key] = tuple(values)
    return axes, tuple(log_axes)


def _range(table: Dict[str, Any], where: str, error: Callable[..., ScenarioError]) -> Tuple[List[float], bool]:
    for key in table:
        if key not in _RANGE_KEYS:
            raise error(f"{where}.{key}", f"unknown key (allowed: {', '.join(_RANGE_KEYS)})")
    for key in ("start", "stop", "num"):
        if key not in table:
            raise error(where, f"a range needs start, stop and num (missing {key})")
    start, stop = (table[k] for k in ("start", "stop"))
    for key, value in (("start", start), ("stop", stop)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise error(f"{where}.{key}", f"must be a finite number (got {value!r})")
    num = table["num"]
    if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_POINTS:
        raise error(f"{where}.num", f"must be an integer in [1, {MAX_POINTS}] (got {num!r})")
    scale = table.get("scale", "linear")
    if scale not in ("linear", "log"):
        raise error(f"{where}.scale", f"must be \"linear\" or \"log\" (got {scale!r})")
    if scale == "log" and not (start > 0 and stop > 0):
        raise error(where, f"a log range needs start > 0 and stop > 0 (got {start!r}, {stop!r})")
    values = np.geomspace(start, stop, num) if scale == "log" else np.linspace(start, stop, num)
    # 15 significant digits: 0.3, not linspace's 0.30000000000000004, in the points, the table and the plot
    return [float(f"{v:.15g}") for v in values], scale == "log"


def _selected(base: Dict[str, Any], raw: Any, scenario_file: Optional[Path],
              error: Callable[..., ScenarioError]) -> Dict[str, Any]:
    """The scenario with only the [[case]] tables named in ``cases`` (so that a grid key may be one only they
    take, such as a Dahl law's tangential_stiffness), each name checked against the scenario's."""
    if raw is None:
        return base
    names = [_typed(n, str, f"cases[{i}]", error) for i, n in enumerate(_typed(raw, list, "cases", error))]
    if not names:
        raise error("cases", "must name at least one case (omit it to run every case)")
    known = [case.name for case in parse(base, source=scenario_file).cases]
    for i, n in enumerate(names):
        if n not in known:
            raise error(f"cases[{i}]", f"no case {n!r} in the scenario (its cases: {', '.join(known)})")
    if not isinstance(base.get("case"), list):  # a single case made of the top-level tables: it is the one named
        return base
    kept = dict(base)
    kept["case"] = [table for table, name in zip(base["case"], known) if name in names]
    for table, name in zip(kept["case"], [n for n in known if n in names]):
        table.setdefault("name", name)  # a default name (the friction type, case<k>) would change with the others
    return kept


def _point_scenario(base: Mapping[str, Any], point: Mapping[str, Any], scenario_file: Optional[Path],
                    axes: Mapping[str, Sequence[Any]], index: int, error: Callable[..., ScenarioError]) -> Scenario:
    data = copy.deepcopy(dict(base))
    cases = data.get("case") if isinstance(data.get("case"), list) else []
    for key, value in point.items():
        section, _, name = key.partition(".")
        targets = [case[section] for case in cases if isinstance(case, dict) and isinstance(case.get(section), dict)]
        if isinstance(data.get(section), dict) or not cases:
            targets.append(data.setdefault(section, {}))
        if not targets:
            raise error(f'grid."{key}"', f"the scenario has no {section} table to set {name} in")
        for table in targets:
            if not isinstance(table, dict):
                raise error(f'grid."{key}"', f"the scenario's {section} is not a table")
            table[name] = copy.deepcopy(value)
    try:
        return parse(data, source=scenario_file)
    except ScenarioError as failure:
        for key in point:
            if failure.key is not None and (failure.key == key or failure.key.endswith("." + key)):
                position = axes[key].index(point[key])
                raise error(f'grid."{key}"[{position}]', f"{failure.rule} (at point {index}: "
                                                         f"{_describe(point)})") from None
        raise ScenarioError(failure.file, failure.key, f"{failure.rule} (at sweep point {index}: "
                                                       f"{_describe(point)})") from None


def _describe(point: Mapping[str, Any]) -> str:
    return ", ".join(f"{key} = {value!r}" for key, value in point.items())


# ------------------------------------------------------------------------------------------------------ running
def run_point(scenario: Scenario) -> List[Dict[str, Any]]:
    """The summary row of each case of one point's scenario (top-level, so that a process pool can run it).

    A case whose run fails (its solver.timeout ran out, the engine stopped it early, or it ran past the timeout:
    :func:`frictionsim.scenario.runner.budget_failure`) gives the row ``{"case": name, "error": reason}``
    instead, and the point's other cases, and the other points, still run."""
    from ..errors import SimulationError
    from .runner import budget_failure, run_case

    rows = []
    for case in scenario.cases:
        try:
            outcome = run_case(case)
        except SimulationError as error:
            rows.append({"case": case.name, "error": f"{type(error).__name__}: stopped at t = "
                                                     f"{error.time_reached:.9g} s of t_end = "
                                                     f"{case.solver.t_end:g} s: {error}"})
            continue
        reason = budget_failure(case, outcome)
        rows.append(outcome.summary() if reason is None else {"case": case.name, "error": reason})
    return rows


def run(sweep: SweepFile, *, imap: Callable[[Callable, Iterable], Iterable] = map,
        on_point: Optional[Callable[[int], None]] = None, timeout: Optional[float] = None) -> "SweepRun":
    """Run every point of ``sweep`` (``imap(run_point, scenarios)``: the built-in map, or a pool's ordered
    ``imap``); ``on_point(index)`` is called as each point's rows arrive. ``timeout`` [s]: the wall-clock budget
    of each case's run at each point, replacing the file's solver.timeout (None: the file's); a case that runs out
    is recorded as failed with its reason (:attr:`SweepRun.failures`) and the rest continue. The output columns
    are checked against the first summary that arrives, before the other points' results are read. Writes
    nothing."""
    from .runner import with_timeout

    if timeout is not None and not (isinstance(timeout, (int, float)) and not isinstance(timeout, bool)
                                    and math.isfinite(timeout) and timeout > 0):
        raise InvalidParameterError(f"timeout must be a positive number of seconds (got {timeout!r})", "timeout")
    scenarios = [dataclasses.replace(scenario, cases=tuple(with_timeout(case, timeout) for case in scenario.cases))
                 for scenario in sweep.scenarios]
    rows: List[List[Dict[str, Any]]] = []
    checked = False
    for index, point_rows in enumerate(imap(run_point, scenarios)):
        if not checked:
            summary = next((row for row in point_rows if "error" not in row), None)
            if summary is not None:
                _check_columns(sweep, summary)
                checked = True
        rows.append(point_rows)
        if on_point is not None:
            on_point(index)
    return SweepRun(sweep, rows)


def _check_columns(sweep: SweepFile, summary: Mapping[str, Any]) -> None:
    numeric = [k for k, v in summary.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    wanted = list(sweep.output.columns or ())
    if sweep.output.value is not None:
        wanted.append(sweep.output.value)
    for i, column in enumerate(wanted):
        if column not in summary:
            key = "output.value" if sweep.output.value == column and i == len(wanted) - 1 else \
                f"output.columns[{i}]"
            raise ScenarioError(sweep.source, key, f"no summary column {column!r} (columns of this rig: "
                                                   f"{', '.join(summary)})")
    if sweep.output.value is not None and sweep.output.value not in numeric:
        raise ScenarioError(sweep.source, "output.value", f"must be a numeric summary column (got "
                                                          f"{sweep.output.value!r}; numeric: {', '.join(numeric)})")


@dataclass
class SweepRun:
    """A sweep, run: ``rows[i]`` holds the summary rows of point ``i``'s cases."""

    sweep: SweepFile
    rows: List[List[Dict[str, Any]]]

    @property
    def failures(self) -> List[Tuple[int, str, str]]:
        """(point index, case, reason) of every case that failed at a point (see :func:`run_point`)."""
        return [(index, row["case"], row["error"]) for index, point_rows in enumerate(self.rows)
                for row in point_rows if "error" in row]

    @property
    def value(self) -> Optional[str]:
        """The plotted summary column: output.value, else the first of :data:`DEFAULT_VALUES` present."""
        if self.sweep.output.value is not None:
            return self.sweep.output.value
        first = next((row for point_rows in self.rows for row in point_rows if "error" not in row), {})
        return next((v for v in DEFAULT_VALUES if v in first), None)

    def frame(self):
        """pandas DataFrame, one row per point and case: the grid keys (in SI), ``<key> (given)`` (the text of
        each key given with units), ``case``, then the summary columns (output.columns and the plotted value,
        else all); with failed cases, a last column ``error`` holds the reason (empty elsewhere) and their
        summary columns are NaN."""
        import pandas as pd

        columns = self.sweep.output.columns
        if columns is not None and self.value is not None and self.value not in columns:
            columns = columns + (self.value,)
        records = []
        given = self.sweep.given_with_units
        si_points = self.sweep.si_points or self.sweep.points
        for point, si_point, point_rows in zip(self.sweep.points, si_points, self.rows):
            texts = {f"{key} (given)": str(point[key]) for key in given}
            for row in point_rows:
                kept = {k: v for k, v in row.items() if k not in ("case", "error")}
                if columns is not None:
                    kept = {k: row.get(k, math.nan) for k in columns}
                records.append({**si_point, **texts, "case": row["case"], **kept})
                if "error" in row:
                    records[-1]["error"] = row["error"]
        frame = pd.DataFrame(records)
        if "error" in frame:  # last, and "" where the case ran
            frame["error"] = frame.pop("error").fillna("")
        return frame

    def write(self, directory: Union[str, Path], *, overwrite: bool = False) -> List[Path]:
        """Write sweep.csv, sweep.png (when the first grid key is numeric) and sweep.toml into ``directory``, all
        at once (as :meth:`frictionsim.scenario.ScenarioRun.write`); ``overwrite``: replace files of those names
        there (default False: :class:`~frictionsim.scenario.staging.OutputExistsError` names the file, nothing
        is written)."""
        directory = Path(directory)
        with staged_directory(directory, overwrite=overwrite) as stage:
            return [directory / path.relative_to(stage) for path in self._write_into(stage)]

    def _write_into(self, directory: Path) -> List[Path]:
        frame = self.frame()
        written = [directory / "sweep.csv"]
        write_csv(frame, written[0])
        figure = self.figure(frame)
        if figure is not None:
            from ..plots import save

            written.append(save(figure, directory / "sweep.png"))
        else:
            log.warning("%s: no sweep.png: %s", self.sweep.name, self.why_no_figure())
        if self.sweep.text is not None:
            written.append(directory / "sweep.toml")
            write_text(written[-1], self.sweep.text)
        return written

    def why_no_figure(self) -> Optional[str]:
        """Why :meth:`figure` draws nothing (None when it draws)."""
        x_key = next(iter(self.sweep.axes))
        if self.value is None:
            return f"no numeric summary column to plot (give output.value; tried {', '.join(DEFAULT_VALUES)})"
        si_points = self.sweep.si_points or self.sweep.points
        if not all(isinstance(p[x_key], (int, float)) and not isinstance(p[x_key], bool) for p in si_points):
            return f"the first grid key {x_key!r} is not numeric (put a numeric key first to plot over it)"
        return None

    def figure(self, frame=None):
        """``value`` against the first grid key, one line per case and combination of the other keys (at most
        :data:`MAX_LINES`); None when that key's values are not numbers."""
        if self.why_no_figure() is not None:
            return None
        frame = self.frame() if frame is None else frame
        keys = list(self.sweep.axes)
        x_key, value = keys[0], self.value
        from matplotlib.figure import Figure

        figure = Figure(figsize=(8.0, 4.5), layout="constrained")
        ax = figure.subplots()
        groups = frame.groupby(["case"] + keys[1:], sort=False)
        for k, (label, part) in enumerate(groups):
            if k == MAX_LINES:
                break
            label = label if isinstance(label, tuple) else (label,)
            text = ", ".join([str(label[0])] + [f"{key} = {v:g}" if isinstance(v, float) else f"{key} = {v}"
                                                for key, v in zip(keys[1:], label[1:])])
            ax.plot(part[x_key], part[value], marker="o", markersize=3, label=text)
        if x_key in self.sweep.log_axes:
            ax.set_xscale("log")
        ax.set_xlabel(f"{x_key} [{self.sweep.si_units[x_key]}]" if x_key in self.sweep.si_units else x_key)
        ax.set_ylabel(value)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        title = self.sweep.title or self.sweep.name
        shown = min(groups.ngroups, MAX_LINES)
        ax.set_title(f"{title}\n{value} over {x_key}" + (f" ({shown} of {groups.ngroups} lines; all in sweep.csv)"
                                                         if groups.ngroups > MAX_LINES else ""), fontsize=10)
        return figure
