"""Torque and drag along a real well: surveys, the soft-string model, broomstick plots (issue 14).

The model is C++: :class:`~frictionsim.Survey` (``include/frictionsim/survey.hpp``: minimum curvature,
dogleg severity, TVD) and :class:`~frictionsim.SoftString` (``soft_string.hpp``: Johancsik, Friesen & Dawson 1984,
SPE 11380, with the friction split between axial and circumferential sliding by the sliding-velocity vector),
on a :class:`~frictionsim.DrillString` of :class:`~frictionsim.PipeSection`. This module reads survey files, runs
the standard operations and the hook load while the string is run in to each depth (the broomstick plot), and
draws them. SI units: metres, newtons, radians inside; survey files give their units in the header.

    >>> import frictionsim as fs
    >>> from frictionsim import wells
    >>> survey = wells.read_survey("examples/surveys/j_well.csv")       # md [m], inc [deg], azi [deg]
    >>> string = fs.DrillString([fs.PipeSection(length=2850.0),
    ...                          fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
    >>> wells.torque_drag(survey, string, "trip_out", open_hole_friction=0.3).hook_load    # N
    >>> chart = wells.broomstick(survey, string, friction_factors=(0.1, 0.2, 0.3, 0.4))
    >>> wells.plot_broomstick(chart)                                   # a matplotlib Axes
"""

from __future__ import annotations

import codecs
import csv
import itertools
import logging
import math
import os
import re
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._core import (DrillString, HydraulicOscillator, OscillatorDragResult, OscillatorResponse, PipeSection, SoftString,
                    Survey, TorqueDragResult)
from .errors import InvalidParameterError

__all__ = [
    "BROOMSTICK_OPERATIONS",
    "Broomstick",
    "DrillString",
    "FrequencyScan",
    "HydraulicOscillator",
    "OscillatorDragResult",
    "OscillatorResponse",
    "Placement",
    "PlannedOscillator",
    "OPERATIONS",
    "PipeSection",
    "SoftString",
    "Survey",
    "TorqueDragResult",
    "broomstick",
    "frequency_scan",
    "node_table",
    "operations_table",
    "oscillator_broomstick",
    "oscillators_at",
    "place_oscillators",
    "plot_placement",
    "plot_broomstick",
    "plot_well_path",
    "read_survey",
    "soft_string",
    "string_to_depth",
    "survey_from",
    "sliding_placements",
    "torque_drag",
    "trajectory",
    "wall_friction",
    "zone_of_influence",
]

_log = logging.getLogger(__name__)

#: The operations of :meth:`SoftString.run` (trip_in, trip_out, reaming, backreaming, rotating_off_bottom,
#: sliding_drilling, rotary_drilling).
OPERATIONS: Tuple[str, ...] = tuple(SoftString.operations)
#: What a broomstick plot shows: slack-off (running in), pick-up (pulling out) and rotating off bottom.
BROOMSTICK_OPERATIONS: Tuple[str, ...] = ("trip_in", "trip_out", "rotating_off_bottom")

#: Depth and angle units a survey file or call may use, as factors to metres and radians.
DEPTH_UNITS: Dict[str, float] = {"m": 1.0, "ft": 0.3048}
ANGLE_UNITS: Dict[str, float] = {"deg": math.pi / 180.0, "rad": 1.0}
_UNIT_ALIASES = {"m": "m", "metre": "m", "metres": "m", "meter": "m", "meters": "m", "ft": "ft", "feet": "ft",
                 "foot": "ft", "deg": "deg", "degree": "deg", "degrees": "deg", "°": "deg", "rad": "rad",
                 "radian": "rad", "radians": "rad"}
#: Column names a survey file may use for each field (case-insensitive, the unit in [..] or (..) after it).
_COLUMNS = {"measured_depth": ("md", "measured_depth", "measured depth", "depth", "dmea"),
            "inclination": ("inc", "incl", "inclination"),
            "azimuth": ("azi", "az", "azim", "azimuth")}

#: Default element length of the soft-string model [m]: survey stations are ~30 m apart; 10 m elements keep the
#: explicit step's first-order error well below the friction factor's uncertainty.
ELEMENT_LENGTH = 10.0

PathLike = Union[str, Path]

#: The largest survey file read [bytes]: a survey of 100,000 stations is ~5 MB (a station every 0.1 m of a 10 km
#: well); anything larger is not a survey listing, and /dev/zero or a huge file would fill the memory.
MAX_SURVEY_BYTES = 64 * 2**20
#: The longest line of a survey file [characters]: a station row is tens of characters, a header hundreds.
MAX_SURVEY_LINE = 65536
#: Control characters a text survey never holds (tab, newline, carriage return, form feed and vertical tab are
#: whitespace): their presence means a binary file.
_CONTROL = re.compile("[\x00-\x08\x0e-\x1f\x7f-\x9f]")
#: The most soft-string element evaluations one broomstick takes: sum over its bit depths of the elements there,
#: times friction factors and operations. Measured 1.3e6 evaluations/s at 10 m elements (the Python per depth
#: dominates) to 1.4e7/s at 1 m, so 2e8 is 15 s to 2.5 min; a 10 km well every 5 m with 10 m elements, 4 factors
#: and 3 operations needs 1.2e8. A depth step of 1 mm on 3 km needs 5e9.
MAX_BROOMSTICK_WORK = 2e8
#: The most bit depths of one broomstick (each builds a soft string and runs it: ~1.4 ms per depth measured, so
#: 100,000 depths are ~2.5 min).
MAX_BROOMSTICK_DEPTHS = 100_000
#: The most friction factors, operations or frequencies a loop takes (an endless iterator stops there).
MAX_LIST = 10_000


# --------------------------------------------------------------------------------------------------------- surveys
def survey_from(measured_depth, inclination, azimuth, *, depth_unit: str = "m", angle_unit: str = "deg") -> Survey:
    """A :class:`Survey` from station arrays in the given units (depth ``"m"`` or ``"ft"``, angles ``"deg"`` or
    ``"rad"``). Bad stations raise :class:`~frictionsim.InvalidParameterError` naming the station and field."""
    depth = _factor(depth_unit, DEPTH_UNITS, "depth_unit")
    angle = _factor(angle_unit, ANGLE_UNITS, "angle_unit")
    md = np.asarray(measured_depth, dtype=float) * depth
    return Survey(md, np.asarray(inclination, dtype=float) * angle, np.asarray(azimuth, dtype=float) * angle)


def read_survey(path: PathLike, *, depth_unit: Optional[str] = None, angle_unit: Optional[str] = None) -> Survey:
    """Read a survey CSV file: a header row naming the measured depth, inclination and azimuth columns (``md``,
    ``inc``, ``azi`` or the long names; other columns are ignored), then one station per row. Lines starting with
    ``#`` are comments. Units come from the header (``md [m]``, ``md (ft)``, ``inc [deg]``, ``azi [rad]``) or from
    ``depth_unit`` / ``angle_unit`` (default metres and degrees); a header and an argument that disagree are an
    error.

    Errors are :class:`~frictionsim.InvalidParameterError` (a ValueError) naming the file, the station, its line
    and the field: a cell that is not a number, and every rule of :class:`Survey` (at least two stations, finite
    values, measured depth strictly increasing, inclination in 0..180 degrees).
    """
    path = Path(path)
    lines_of_text = _survey_lines(path)
    try:
        rows = [(number, row) for number, row in enumerate(csv.reader(lines_of_text), start=1)
                if row and any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#")]
    except csv.Error as error:
        raise InvalidParameterError(f"{path}: not a survey listing the csv module can read ({error})", "path") from None
    if not rows:
        raise InvalidParameterError(f"{path}: no header row (expected columns md, inc, azi)", "header")
    header_line, header = rows[0]
    where: Dict[str, int] = {}
    units: Dict[str, Optional[str]] = {}
    for index, cell in enumerate(header):
        name, unit = _split_unit(cell, path, header_line)
        for field, aliases in _COLUMNS.items():
            if name in aliases:
                if field in where:
                    raise InvalidParameterError(f"{path}: line {header_line}: two {field} columns", field)
                where[field], units[field] = index, unit
    for field in _COLUMNS:
        if field not in where:
            raise InvalidParameterError(
                f"{path}: line {header_line}: no {field} column (header: {', '.join(header)}; expected one of "
                f"{', '.join(_COLUMNS[field])})", field)
    depth = _unit_of("measured_depth", units["measured_depth"], depth_unit, "m", DEPTH_UNITS, "depth_unit", path)
    angles = {field: _unit_of(field, units[field], angle_unit, "deg", ANGLE_UNITS, "angle_unit", path)
              for field in ("inclination", "azimuth")}
    values: Dict[str, List[float]] = {field: [] for field in _COLUMNS}
    lines: List[int] = []
    for station, (number, row) in enumerate(rows[1:]):
        for field, index in where.items():
            cell = row[index].strip() if index < len(row) else ""
            try:
                value = float(cell)
            except ValueError:
                raise InvalidParameterError(f"{path}: line {number}: station {station}: {field}: "
                                            f"{cell!r} is not a number", field) from None
            values[field].append(value)
        lines.append(number)
    md = np.asarray(values["measured_depth"]) * DEPTH_UNITS[depth]
    inc, azi = np.asarray(values["inclination"]), np.asarray(values["azimuth"])
    if angles["azimuth"] != angles["inclination"]:  # azimuth in the inclination's unit
        azi = azi * ANGLE_UNITS[angles["azimuth"]] / ANGLE_UNITS[angles["inclination"]]
    try:
        if angles["inclination"] == "deg":  # the errors then quote the file's degrees
            return Survey.from_degrees(md, inc, azi)
        return Survey(md, inc, azi)
    except InvalidParameterError as error:
        message = str(error).replace("Survey: ", "", 1)
        found = re.match(r"station (\d+)", message)
        line = f"line {lines[int(found.group(1))]}: " if found and int(found.group(1)) < len(lines) else ""
        feet = " (depths quoted in m, the file's in ft)" if depth == "ft" else ""
        raise InvalidParameterError(f"{path}: {line}{message}{feet}", error.parameter) from None


def _survey_lines(path: Path) -> List[str]:
    """The lines of a survey file: a regular file of at most MAX_SURVEY_BYTES, in UTF-8, UTF-16 or UTF-32 with their
    byte-order mark, else Windows-1252 / Latin-1 (a degree sign written as byte 0xB0); a FIFO, a device, a binary file
    or an over-long line is an InvalidParameterError naming ``path``."""
    try:
        # non-blocking: a FIFO opens without waiting for a writer (then refused as not a regular file)
        descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except ValueError as error:  # a NUL in the name
        raise InvalidParameterError(f"{str(path)!r}: not a file name ({error})", "path") from None
    except OSError as error:
        raise InvalidParameterError(f"{path}: cannot read the survey ({error.strerror or error})", "path") from None
    try:
        mode = os.fstat(descriptor).st_mode
    except BaseException:
        os.close(descriptor)
        raise
    if not stat.S_ISREG(mode):
        os.close(descriptor)
        kind = ("a directory" if stat.S_ISDIR(mode) else "a FIFO" if stat.S_ISFIFO(mode) else
                "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "a socket or other special file")
        raise InvalidParameterError(f"{path}: {kind}, not a regular file: a survey is read from a file", "path")
    with os.fdopen(descriptor, "rb") as file:
        data = file.read(MAX_SURVEY_BYTES + 1)
    if len(data) > MAX_SURVEY_BYTES:
        raise InvalidParameterError(f"{path}: larger than {MAX_SURVEY_BYTES // 2**20} MiB, the most a survey file "
                                    "may hold (100,000 stations take ~5 MB)", "path")
    text = _decode(data, path)
    lines = text.splitlines()
    for number, line in enumerate(lines, start=1):
        if len(line) > MAX_SURVEY_LINE:
            raise InvalidParameterError(f"{path}: line {number}: {len(line)} characters, more than the "
                                        f"{MAX_SURVEY_LINE} a survey line may hold: not a survey listing", "path")
    return lines


def _decode(data: bytes, path: Path) -> str:
    """Survey bytes as text (see _survey_lines); a binary file is refused naming it."""
    marks = ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"), (codecs.BOM_UTF8, "utf-8-sig"),
             (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16"))
    encoding = next((codec for mark, codec in marks if data.startswith(mark)), None)
    try:
        if encoding is not None:
            text = data.decode(encoding)
        else:
            try:
                text = data.decode("utf-8")
            except UnicodeDecodeError:
                text = data.decode("cp1252")  # a Windows program's degree sign (0xB0), as in Latin-1
    except UnicodeDecodeError as error:
        raise InvalidParameterError(f"{path}: not a text survey file (neither {encoding or 'UTF-8 nor Windows-1252'}:"
                                    f" {error.reason} at byte {error.start})", "path") from None
    found = _CONTROL.search(text)
    if found:
        line = text.count("\n", 0, found.start()) + 1
        raise InvalidParameterError(f"{path}: line {line}: control character U+{ord(found.group()):04X}: a binary "
                                    "file, not a text survey listing", "path")
    return text


def _bounded_list(values: Any, name: str, limit: int = MAX_LIST) -> list:
    """``values`` as a list of at most ``limit`` items (an endless iterator is cut there and refused)."""
    if isinstance(values, (str, bytes)):
        raise InvalidParameterError(f"{name} must be a sequence of values, not text (got {values!r})", name)
    try:
        items = list(itertools.islice(iter(values), limit + 1))
    except TypeError:
        raise InvalidParameterError(f"{name} must be a sequence of values (got {type(values).__name__})",
                                    name) from None
    if len(items) > limit:
        raise InvalidParameterError(f"{name} must hold at most {limit} values", name)
    return items


def _numbers(values: Any, name: str, limit: int = MAX_LIST) -> List[float]:
    """``values`` (a sequence, at most ``limit``) as floats; text, booleans and complex numbers are refused by name
    (strings reach numbers only through the units layer)."""
    out = []
    if isinstance(values, (int, float, np.integer, np.floating)) and not isinstance(values, bool):
        values = [values]  # one number: a sequence of one
    for value in _bounded_list(np.ravel(values) if isinstance(values, np.ndarray) else values, name, limit):
        if isinstance(value, (str, bytes, bool, np.bool_, complex, np.complexfloating)) or not hasattr(value, "__float__"):
            raise InvalidParameterError(f"{name} must hold real numbers (got {type(value).__name__} {value!r})", name)
        out.append(float(value))
    return out


def _split_unit(cell: str, path: Path, line: int) -> Tuple[str, Optional[str]]:
    found = re.fullmatch(r"\s*([^\[\(]*?)\s*(?:[\[\(]\s*([^\]\)]*?)\s*[\]\)])?\s*", cell)
    name, unit = (found.group(1), found.group(2)) if found else (cell.strip(), None)
    name = name.lower().replace("_", " ").strip()
    name = {"measured depth": "measured_depth"}.get(name, name)
    if unit is None:
        return name, None
    alias = _UNIT_ALIASES.get(unit.lower())
    if alias is None:
        raise InvalidParameterError(f"{path}: line {line}: column {cell.strip()!r}: unknown unit {unit!r} "
                                    f"(known: {', '.join(sorted(set(_UNIT_ALIASES.values())))})", "unit")
    return name, alias


def _unit_of(field: str, in_header: Optional[str], given: Optional[str], default: str, known: Dict[str, float],
             keyword: str, path: Path) -> str:
    if given is not None:
        _factor(given, known, keyword)
    if in_header is not None and in_header not in known:
        raise InvalidParameterError(f"{path}: {field}: unit {in_header!r} is not a unit of this field "
                                    f"({', '.join(known)})", field)
    if in_header is not None and given is not None and in_header != given:
        raise InvalidParameterError(f"{path}: {field}: the header says {in_header!r}, {keyword} says {given!r}",
                                    keyword)
    return in_header or given or default


def _factor(unit: str, known: Dict[str, float], keyword: str) -> float:
    if unit not in known:
        raise InvalidParameterError(f"{keyword} must be one of {', '.join(map(repr, known))} (got {unit!r})",
                                    keyword)
    return known[unit]


def trajectory(survey: Survey):
    """The survey's stations and minimum-curvature trajectory as a pandas DataFrame: measured_depth [m],
    inclination and azimuth [deg], north, east, tvd [m], dogleg_severity [deg/30 m] (of the course ending at each
    station; 0 at the first)."""
    import pandas as pd

    return pd.DataFrame({"measured_depth": survey.measured_depth,
                         "inclination": np.degrees(survey.inclination),
                         "azimuth": np.degrees(survey.azimuth),
                         "north": survey.north, "east": survey.east, "tvd": survey.tvd,
                         "dogleg_severity": np.degrees(survey.dogleg_severity) * 30.0})


# ------------------------------------------------------------------------------------------------- torque and drag
def string_to_depth(string: DrillString, depth: float) -> DrillString:
    """``string`` with its bit at measured depth ``depth`` while running in: the bottom sections kept, drill pipe
    removed from the top (the string as it is when the bit passes ``depth``)."""
    if not (math.isfinite(depth) and 0.0 < depth <= string.length):
        raise InvalidParameterError(f"string_to_depth: depth must be in (0, {string.length:g}] m, the string's "
                                    f"length (got {depth!r})", "depth")
    kept: List[PipeSection] = []
    remaining = depth
    for section in reversed(string.sections):
        if remaining <= 0.0:
            break
        length = min(section.length, remaining)
        kept.append(_with_length(section, length))
        remaining -= length
    return DrillString(kept[::-1])


def _with_length(section: PipeSection, length: float) -> PipeSection:
    values = {p.name: getattr(section, p.name) for p in PipeSection.parameters}
    values["length"] = length
    return PipeSection(**values)


def soft_string(survey: Survey, string: DrillString, *, elements: Optional[int] = None,
                element_length: float = ELEMENT_LENGTH, method: str = "johancsik") -> SoftString:
    """The soft-string model of ``string`` hung along ``survey``: ``elements`` elements, or as many as make them
    at most ``element_length`` [m] long; ``method`` "johancsik" (the step method) or "aadnoy" (the curvature
    form, exact on builds, drops and side bends)."""
    if elements is None:
        if not (math.isfinite(element_length) and element_length > 0.0):
            raise InvalidParameterError(f"element_length must be positive and finite (got {element_length!r})",
                                        "element_length")
        elements = max(1, math.ceil(string.length / element_length - 1e-9))
    return SoftString(survey, string, elements, method=method)


def torque_drag(survey: Survey, string: DrillString, operation: str = "trip_out", *,
                elements: Optional[int] = None, element_length: float = ELEMENT_LENGTH, method: str = "johancsik",
                **conditions: float) -> TorqueDragResult:
    """Torque and drag of one operation (one of :data:`OPERATIONS`) with the string's bit at its full length;
    ``conditions`` are the keywords of ``SoftString.parameters`` (mud_density [kg/m^3], cased_hole_friction,
    open_hole_friction, casing_shoe_depth [m], weight_on_bit [N], bit_torque [N m], speeds, hole sizes);
    ``method`` as in :func:`soft_string`."""
    model = soft_string(survey, string, elements=elements, element_length=element_length, method=method)
    return model.run(operation, **conditions)


def node_table(result: TorqueDragResult):
    """One row per node of a result (a pandas DataFrame): measured_depth [m], tension [N], torque [N m],
    side_force [N] lumped at the node (half of each adjoining element's: the total is the elements' total),
    side_force_per_length [N/m] (the mean of the adjoining elements'), the buckling loads [N] and flags."""
    import pandas as pd

    element = np.asarray(result.side_force)
    per_length = np.asarray(result.side_force_per_length)
    lumped = np.zeros(len(element) + 1)
    lumped[:-1] += 0.5 * element
    lumped[1:] += 0.5 * element
    mean_per_length = np.concatenate(([per_length[0]], 0.5 * (per_length[:-1] + per_length[1:]), [per_length[-1]]))
    return pd.DataFrame({"measured_depth": result.measured_depth, "tension": result.tension,
                         "torque": result.torque, "side_force": lumped, "side_force_per_length": mean_per_length,
                         "sinusoidal_buckling_load": result.sinusoidal_buckling_load,
                         "helical_buckling_load": result.helical_buckling_load,
                         "sinusoidally_buckled": result.sinusoidally_buckled,
                         "helically_buckled": result.helically_buckled})


# ------------------------------------------------------------------------------------------------------ broomstick
@dataclass(frozen=True)
class Broomstick:
    """Hook load (and surface torque) against bit depth while the string is run in, per friction factor and
    operation. ``frame``: one row per (bit_depth [m], friction_factor, operation) with hook_load [N] and
    surface_torque [N m]. ``conditions``: the other keywords of the runs."""

    frame: Any
    friction_factors: Tuple[float, ...]
    operations: Tuple[str, ...]
    conditions: Dict[str, float]

    def hook_loads(self, operation: str, friction_factor: float) -> Tuple[np.ndarray, np.ndarray]:
        """(bit depths [m], hook loads [N]) of one operation and friction factor."""
        rows = self.frame[(self.frame["operation"] == operation)
                          & (self.frame["friction_factor"] == friction_factor)]
        if rows.empty:
            raise KeyError(f"no {operation!r} at friction factor {friction_factor!r} in this broomstick "
                           f"(operations {self.operations}, friction factors {self.friction_factors})")
        return rows["bit_depth"].to_numpy(), rows["hook_load"].to_numpy()


def broomstick(survey: Survey, string: DrillString, friction_factors: Sequence[float] = (0.1, 0.2, 0.3, 0.4), *,
               depths: Optional[Sequence[float]] = None, depth_step: float = 30.0,
               element_length: float = ELEMENT_LENGTH, operations: Sequence[str] = BROOMSTICK_OPERATIONS,
               method: str = "johancsik", **conditions: float) -> Broomstick:
    """Hook load against bit depth for each operation and friction factor while the string is run in to each depth
    (``string_to_depth``: the bottom-hole assembly kept, pipe added at the top), the usual broomstick plot.

    Each friction factor is the open-hole one and, unless ``cased_hole_friction`` is among the ``conditions``,
    the cased-hole one too (the usual practice: a known casing factor, the open-hole one calibrated against the
    plot). ``depths``: the bit depths [m] (default every ``depth_step`` metres and the string's full length).
    Rotating off bottom carries no axial friction: its hook load is the same for every friction factor.
    ``method`` as in :func:`soft_string`. The work is estimated first and refused beyond
    :data:`MAX_BROOMSTICK_DEPTHS` bit depths or :data:`MAX_BROOMSTICK_WORK` element evaluations (depths x elements
    x friction factors x operations), naming ``depth_step`` or ``depths``.
    """
    factors = tuple(_numbers(friction_factors, "friction_factors"))
    if not factors:
        raise InvalidParameterError("broomstick: friction_factors must hold at least one value", "friction_factors")
    operations = tuple(_bounded_list(operations, "operations"))
    for op in operations:
        if op not in OPERATIONS:
            raise InvalidParameterError(f"broomstick: operation must be one of {', '.join(OPERATIONS)} (got {op!r})",
                                        "operations")
    if not (math.isfinite(element_length) and element_length > 0.0):
        raise InvalidParameterError(f"element_length must be positive and finite (got {element_length!r})",
                                    "element_length")
    runs = len(factors) * len(operations)
    length = string.length
    if depths is None:
        if not (math.isfinite(depth_step) and depth_step > 0.0):
            raise InvalidParameterError(f"broomstick: depth_step must be positive and finite (got {depth_step!r})",
                                        "depth_step")
        # the work before the grid: ~L / step depths of ~L / (2 element_length) elements each
        count = length / depth_step + 1.0
        _check_broomstick_work(count, count * (0.5 * length / element_length + 1.0) * runs, "depth_step", depth_step)
        grid = np.arange(depth_step, length, depth_step)
        depths = np.append(grid[grid < length - 1e-9 * length], length)
    else:
        depths = _numbers(depths, "depths", MAX_BROOMSTICK_DEPTHS)
        work = sum(max(1.0, math.ceil(d / element_length)) for d in depths if math.isfinite(d)) * runs
        _check_broomstick_work(len(depths), work, "depths", f"{len(depths)} bit depths")
    vary_cased = "cased_hole_friction" not in conditions
    rows: Dict[str, list] = {"bit_depth": [], "friction_factor": [], "operation": [], "hook_load": [],
                             "surface_torque": []}
    for depth in depths:
        model = soft_string(survey, string_to_depth(string, float(depth)), element_length=element_length,
                            method=method)
        for mu in factors:
            given = dict(conditions, open_hole_friction=mu)
            if vary_cased:
                given["cased_hole_friction"] = mu
            for op in operations:
                result = model.run(op, **given)
                rows["bit_depth"].append(float(depth))
                rows["friction_factor"].append(mu)
                rows["operation"].append(op)
                rows["hook_load"].append(result.hook_load)
                rows["surface_torque"].append(result.surface_torque)
    import pandas as pd

    return Broomstick(pd.DataFrame(rows), factors, tuple(operations), dict(conditions))


def _check_broomstick_work(depths: float, work: float, parameter: str, given: Any) -> None:
    """Refuses a broomstick beyond MAX_BROOMSTICK_DEPTHS bit depths or MAX_BROOMSTICK_WORK element evaluations,
    naming ``parameter`` (the depth step, or the depths given)."""
    if depths > MAX_BROOMSTICK_DEPTHS or work > MAX_BROOMSTICK_WORK:
        raise InvalidParameterError(
            f"broomstick: {parameter} = {given!r} asks for {depths:.3g} bit depths and {work:.3g} soft-string element "
            f"evaluations (depths x elements x friction factors x operations); the limits are "
            f"{MAX_BROOMSTICK_DEPTHS} depths and {MAX_BROOMSTICK_WORK:.3g} evaluations (a few minutes): take a "
            f"coarser depth_step, longer elements or fewer depths", parameter)


# ----------------------------------------------------------------------------------------------------------- plots
def plot_broomstick(chart: Broomstick, ax=None, *, title: str = ""):
    """Hook load [kN] against bit depth [m] (depth down) per operation and friction factor; returns the Axes (a new
    figure's when ``ax`` is None)."""
    from .plots import broomstick_axes

    return broomstick_axes(chart, ax=ax, title=title)


def plot_well_path(survey: Survey, ax=None, *, view: str = "section", title: str = ""):
    """The well's path: ``view="section"`` true vertical depth against horizontal departure, ``"plan"`` north
    against east; returns the Axes (a new figure's when ``ax`` is None)."""
    from .plots import well_path_axes

    return well_path_axes(survey, ax=ax, view=view, title=title)


# ------------------------------------------------------------------------------------- axial vibration tools
@dataclass(frozen=True)
class Placement:
    """Where to put one or two axial vibration tools: the weight on bit transferred while sliding at a hook load.

    ``depths``: the best tool depths [m MD]; ``weight_on_bit`` there and ``weight_on_bit_without`` with no tool
    [N]; ``scan_depths`` / ``scan_weight_on_bit``: the objective against one tool's depth (for two tools: the
    second tool's depth with the first at its best), the curve of :func:`plot_placement`; ``evaluations``: calls of
    the C++ objective."""

    depths: Tuple[float, ...]
    weight_on_bit: float
    weight_on_bit_without: float
    hook_load: float
    scan_depths: np.ndarray
    scan_weight_on_bit: np.ndarray
    evaluations: int

    @property
    def gain(self) -> float:
        """Weight on bit the tools add [N]."""
        return self.weight_on_bit - self.weight_on_bit_without


def place_oscillators(model: SoftString, hook_load: float, *, tools: int = 1, force_amplitude: float = 50e3,
                      frequency: float = 18.0, bounds: Optional[Tuple[float, float]] = None, scan_points: int = 60,
                      **keywords) -> Placement:
    """The tool depth(s) that maximise the weight on bit transferred while sliding at ``hook_load`` [N]
    (issue 14, item 4): the C++ objective ``SoftString.sliding_weight_on_bit`` scanned over ``scan_points``
    depths within ``bounds`` [m MD] (default: the string's lowest 95 %, above the bit), then refined with
    ``scipy.optimize``: bounded ``minimize_scalar`` for one tool, Nelder-Mead from the best pair of the scan for
    two (the objective has plateaus and kinks near the bit, so a gradient method would stall). ``keywords``: the
    conditions of ``SoftString.parameters`` and the estimate's settings of ``SoftString.oscillators``
    (``bit_reflection``, ``model``, ``lubricant``, ``vibration``, ...). With ``vibration="dynamic"`` every evaluation
    runs the dynamic string model (seconds each, see :func:`frequency_scan`): lower ``scan_points``."""
    from scipy.optimize import minimize, minimize_scalar

    if isinstance(tools, bool) or tools not in (1, 2):
        raise InvalidParameterError(f"tools must be 1 or 2 (got {tools!r})", "tools")
    if isinstance(scan_points, bool) or not isinstance(scan_points, int) or scan_points < 3:
        raise InvalidParameterError(f"scan_points must be an integer >= 3 (got {scan_points!r})", "scan_points")
    length = float(model.node_depths[-1])
    low, high = bounds if bounds is not None else (0.05 * length, length - model.element_length)
    if not (math.isfinite(low) and math.isfinite(high) and 0.0 <= low < high <= length):
        raise InvalidParameterError(f"bounds must satisfy 0 <= low < high <= the string's length {length:g} m "
                                    f"(got {bounds!r})", "bounds")
    calls = 0

    def objective(*depths: float) -> float:
        nonlocal calls
        calls += 1
        placed = [HydraulicOscillator(measured_depth=float(min(max(d, low), high)), force_amplitude=force_amplitude,
                                      frequency=frequency) for d in depths]
        return model.sliding_weight_on_bit(hook_load, placed, **keywords)

    without = model.sliding_weight_on_bit(hook_load, [], **keywords)
    grid = np.linspace(low, high, scan_points)
    single = np.array([objective(d) for d in grid])
    k = int(np.argmax(single))
    if tools == 1:
        a, b = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        refined = minimize_scalar(lambda d: -objective(d), bounds=(a, b), method="bounded",
                                  options={"xatol": 1e-3 * (high - low) / scan_points})
        best = (float(refined.x), -float(refined.fun)) if -refined.fun > single[k] else (float(grid[k]), single[k])
        return Placement((best[0],), float(best[1]), without, hook_load, grid, single, calls)
    # two tools: the best pair on a coarse grid (first above second), then Nelder-Mead within the bounds
    coarse = grid[:: max(1, scan_points // 15)]
    pairs = [(u, v) for i, u in enumerate(coarse) for v in coarse[i + 1:]]
    values = [objective(u, v) for u, v in pairs]
    start = np.array(pairs[int(np.argmax(values))])
    refined = minimize(lambda x: -objective(*x), start, method="Nelder-Mead", bounds=[(low, high), (low, high)],
                       options={"xatol": 1e-3 * (high - low) / scan_points, "fatol": 1e-6 * max(abs(without), 1.0)})
    pair, value = (refined.x, -refined.fun) if -refined.fun > max(values) else (start, max(values))
    depths = tuple(sorted(float(d) for d in pair))
    curve = np.array([objective(depths[0], d) for d in grid])
    return Placement(depths, float(value), without, hook_load, grid, curve, calls)


@dataclass(frozen=True)
class FrequencyScan:
    """A tool's effect against its frequency (:func:`frequency_scan`), one entry per frequency.

    ``frequencies`` [Hz]; ``zone_length`` [m] and ``hook_load_change`` [N] of the operation with the tool;
    ``tool_amplitude`` [m/s]: the vibration's first harmonic at the tool (``vibration="dynamic"``) or the
    estimate's amplitude there; ``weight_on_bit_gain`` [N]: the weight on bit the tool adds sliding at
    ``hook_load`` (None when no hook load was given); ``responses``: the dynamic runs (empty for the wave)."""

    frequencies: np.ndarray
    zone_length: np.ndarray
    hook_load_change: np.ndarray
    tool_amplitude: np.ndarray
    weight_on_bit_gain: Optional[np.ndarray]
    operation: str
    vibration: str
    hook_load: Optional[float]
    responses: Tuple[Any, ...]

    @property
    def best_frequency(self) -> float:
        """The frequency [Hz] with the largest weight-on-bit gain (with a hook load), else the longest zone."""
        values = self.weight_on_bit_gain if self.weight_on_bit_gain is not None else self.zone_length
        return float(self.frequencies[int(np.argmax(values))])


def frequency_scan(model: SoftString, tool: HydraulicOscillator, frequencies: Sequence[float], *,
                   operation: str = "sliding_drilling", hook_load: Optional[float] = None,
                   vibration: str = "dynamic", **keywords) -> FrequencyScan:
    """The zone of influence, hook load change and (sliding at ``hook_load`` [N]) weight-on-bit gain of ``tool``
    at each of ``frequencies`` [Hz], its depth and force kept (issue 14, item 3).

    The travelling-wave estimate has no frequency optimum (its reach, pi F / (4 mu q_n), does not depend on the
    frequency); the dynamic model (``vibration="dynamic"``, the default) has one: the string's axial resonances
    between the held hook and the free bit, and the wall friction's damping of them. Each frequency costs one
    dynamic run (``oscillators``) and, with a hook load, one more (``sliding_weight_on_bit``): measured on one core,
    0.6 s for 700 m of string at 18 Hz, 8-20 s for a 4.85 km string at 8-28 Hz with ``transient=1.5`` (the default
    waits for two windows to agree, which can take tens of simulated seconds), growing with the string's length,
    the frequency (the grid follows the wavelength) and the length the tool sets sticking and slipping.
    ``keywords``: the conditions of ``SoftString.parameters`` and the settings of ``SoftString.oscillators`` (the
    dynamic run's included). The zone of influence of the dynamic route at the default 5 % threshold can span the
    string: beyond the tool's reach a slowly sliding string sticks and slips forward at the tool's frequency, which
    lowers its mean friction 5-20 %; ``zone_threshold=0.5`` gives the zone's core."""
    freqs = np.asarray(_numbers(frequencies, "frequencies"), dtype=float)
    if freqs.size == 0 or not np.all(np.isfinite(freqs)) or not np.all(freqs > 0.0):
        raise InvalidParameterError(f"frequency_scan: frequencies must be positive and finite, at least one (got "
                                    f"{frequencies!r})", "frequencies")
    if vibration not in ("wave", "dynamic"):
        raise InvalidParameterError(f"frequency_scan: vibration must be 'wave' or 'dynamic' (got {vibration!r})",
                                    "vibration")
    if hook_load is not None and not math.isfinite(hook_load):
        raise InvalidParameterError(f"frequency_scan: hook_load must be finite (got {hook_load!r})", "hook_load")
    zone, change, amplitude, gain, responses = [], [], [], [], []
    without = model.sliding_weight_on_bit(hook_load, [], **keywords) if hook_load is not None else None
    nodes = np.asarray(model.node_depths)
    tool_element = min(int(np.searchsorted(nodes, tool.measured_depth, side="right")) - 1, len(nodes) - 2)
    for f in freqs:
        at_f = HydraulicOscillator(measured_depth=tool.measured_depth, force_amplitude=tool.force_amplitude,
                                   frequency=float(f))
        result = model.oscillators(operation, [at_f], vibration=vibration, **keywords)
        zone.append(result.zone_length)
        change.append(result.hook_load_change)
        if vibration == "dynamic" and result.responses:
            response = result.responses[0]
            responses.append(response)
            amplitude.append(float(response.first_harmonic[response.excitation_node]))
        else:
            amplitude.append(float(np.asarray(result.vibration_amplitude)[max(tool_element, 0)]))
        if hook_load is not None:
            gain.append(model.sliding_weight_on_bit(hook_load, [at_f], vibration=vibration, **keywords) - without)
    return FrequencyScan(freqs, np.array(zone), np.array(change), np.array(amplitude),
                         np.array(gain) if hook_load is not None else None, operation, vibration, hook_load,
                         tuple(responses))


def plot_placement(placement: Placement, ax=None, *, title: str = ""):
    """The weight on bit [kN] against the tool's depth [m MD], without any tool as a line, the best depth(s)
    marked; returns the Axes (a new figure's when ``ax`` is None)."""
    from .plots import placement_axes

    return placement_axes(placement, ax=ax, title=title)


# ------------------------------------------------------------------------ a torque-and-drag study (the CLI's)
@dataclass(frozen=True)
class PlannedOscillator:
    """An axial vibration tool of a study: its depth (``depth`` m MD at the full bit depth, or ``above_bit`` metres
    above the bit), force amplitude [N] and frequency [Hz]. It keeps its height above the bit while the string is
    run in."""

    depth: Optional[float]
    above_bit: Optional[float]
    force: float
    frequency: float

    def height(self, bit_depth: float) -> float:
        """Metres above the bit when the bit is at ``bit_depth`` (the full string)."""
        return self.above_bit if self.above_bit is not None else bit_depth - self.depth


def oscillators_at(tools: Sequence[PlannedOscillator], full_depth: float, bit_depth: float) -> List[Any]:
    """The HydraulicOscillators with the bit at ``bit_depth``: each keeps its height above the bit; those that
    would be above the surface are left out (the string is not that long yet)."""
    return [HydraulicOscillator(measured_depth=bit_depth - tool.height(full_depth), force_amplitude=tool.force,
                                frequency=tool.frequency)
            for tool in tools if bit_depth - tool.height(full_depth) >= 0.0]


def wall_friction(friction_factor: float, cased_friction: Optional[float] = None) -> Dict[str, float]:
    """The SoftString keywords of one friction factor: open hole ``friction_factor``, cased hole
    ``cased_friction`` (default the same)."""
    return dict(open_hole_friction=friction_factor,
                cased_hole_friction=friction_factor if cased_friction is None else cased_friction)


def operations_table(model: SoftString, friction_factors: Sequence[float], operations: Sequence[str],
                     conditions: Dict[str, Any], cased_friction: Optional[float] = None):
    """Every operation at every friction factor: ``(nodes, summary)``, DataFrames of :func:`node_table` per run
    (with operation, friction_factor and node in front) and one row per run (hook load [kN], surface torque
    [kN m], buckled nodes)."""
    import pandas as pd

    tables, summary = [], []
    for mu in friction_factors:
        friction = wall_friction(mu, cased_friction)
        for op in operations:
            result = model.run(op, **conditions, **friction)
            table = node_table(result)
            table.insert(0, "node", range(len(table)))
            table.insert(0, "friction_factor", mu)
            table.insert(0, "operation", op)
            tables.append(table)
            summary.append({"operation": op, "friction_factor": mu, "hook_load_kN": result.hook_load / 1e3,
                            "surface_torque_kNm": result.surface_torque / 1e3,
                            "sinusoidally_buckled_nodes": int(result.sinusoidally_buckled.sum()),
                            "helically_buckled_nodes": int(result.helically_buckled.sum())})
    return pd.concat(tables, ignore_index=True), pd.DataFrame(summary)


def oscillator_broomstick(survey: Survey, string: DrillString, chart: Broomstick,
                          tools: Sequence[PlannedOscillator], full_depth: float, friction_factors: Sequence[float], *,
                          conditions: Dict[str, Any], estimate: Dict[str, Any], element_length: float = ELEMENT_LENGTH,
                          cased_friction: Optional[float] = None):
    """Hook load and surface torque against bit depth with and without the tools, at the broomstick's depths and
    operations (plus sliding, where a tool matters most, and rotary drilling with weight on bit): a DataFrame."""
    import pandas as pd

    weight_on_bit = float(conditions.get("weight_on_bit", 0.0))
    operations = list(dict.fromkeys(list(chart.operations) + ["sliding_drilling"]
                                    + (["rotary_drilling"] if weight_on_bit > 0.0 else [])))
    rows = []
    for bit_depth in sorted(set(chart.frame["bit_depth"])):
        placed = oscillators_at(tools, full_depth, bit_depth)
        model = soft_string(survey, string_to_depth(string, bit_depth), element_length=element_length)
        for mu in friction_factors:
            for op in operations:
                r = model.oscillators(op, placed, **conditions, **wall_friction(mu, cased_friction), **estimate)
                rows.append({"bit_depth": bit_depth, "friction_factor": mu, "operation": op, "tools": len(placed),
                             "hook_load_plain": r.plain.hook_load, "hook_load_tool": r.vibrated.hook_load,
                             "surface_torque_plain": r.plain.surface_torque,
                             "surface_torque_tool": r.vibrated.surface_torque,
                             "zone_length": r.zone_length})
    return pd.DataFrame(rows)


def zone_of_influence(model: SoftString, tools: Sequence[PlannedOscillator], depth: float, operation: str,
                      friction_factors: Sequence[float], *, conditions: Dict[str, Any], estimate: Dict[str, Any],
                      cased_friction: Optional[float] = None):
    """Per element at the full depth, for ``operation`` and each friction factor: the tools' vibration amplitude,
    the friction factors and reduction, in the zone or not; and one summary row per friction factor:
    ``(elements, summary)`` DataFrames."""
    import pandas as pd

    placed = oscillators_at(tools, depth, depth)
    nodes = np.asarray(model.node_depths)
    top, bottom = nodes[:-1], nodes[1:]
    frames, summary = [], []
    for mu in friction_factors:
        r = model.oscillators(operation, placed, **conditions, **wall_friction(mu, cased_friction), **estimate)
        reduction = np.asarray(r.reduction)
        in_zone = (top >= r.zone_top - 1e-9) & (bottom <= r.zone_bottom + 1e-9) & (r.zone_length > 0.0)
        frames.append(pd.DataFrame({"friction_factor": mu, "element": np.arange(len(reduction)),
                                    "top_depth": top, "bottom_depth": bottom,
                                    "vibration_amplitude": r.vibration_amplitude, "axial_factor": r.axial_factor,
                                    "circumferential_factor": r.circumferential_factor, "reduction": reduction,
                                    "in_zone": in_zone & (reduction > 0.0)}))
        summary.append({"friction_factor": mu, "zone_top_m": r.zone_top, "zone_bottom_m": r.zone_bottom,
                        "zone_length_m": r.zone_length, "hook_load_kN": r.plain.hook_load / 1e3,
                        "hook_load_tool_kN": r.vibrated.hook_load / 1e3,
                        "hook_load_change_kN": r.hook_load_change / 1e3,
                        "surface_torque_change_kNm": r.surface_torque_change / 1e3,
                        "weight_on_bit_kN": float(conditions.get("weight_on_bit", 0.0)) / 1e3,
                        "converged": bool(r.converged)})
    return pd.concat(frames, ignore_index=True), pd.DataFrame(summary)


def sliding_placements(model: SoftString, tools: Sequence[PlannedOscillator], friction_factors: Sequence[float], *,
                       conditions: Dict[str, Any], estimate: Dict[str, Any],
                       cased_friction: Optional[float] = None) -> Dict[float, Placement]:
    """friction factor -> :class:`Placement` of one tool (the first of ``tools``' force and frequency, else 50 kN
    at 18 Hz) while sliding at the hook load that puts ``conditions["weight_on_bit"]`` on the bit without it."""
    force, frequency = (tools[0].force, tools[0].frequency) if tools else (50e3, 18.0)
    weight_on_bit = float(conditions.get("weight_on_bit", 0.0))
    out = {}
    for mu in friction_factors:
        friction = wall_friction(mu, cased_friction)
        hook_load = model.run("sliding_drilling", **{**conditions, **friction}).hook_load
        if hook_load < 0.0:
            _log.warning("mu = %g: sliding %g kN onto the bit needs a hook load of %.4g kN: the string would have "
                         "to be pushed from the surface", mu, weight_on_bit / 1e3, hook_load / 1e3)
        rest = {k: v for k, v in conditions.items() if k != "weight_on_bit"}
        out[mu] = place_oscillators(_Estimated(model, estimate), hook_load, force_amplitude=force,
                                    frequency=frequency, **rest, **friction)
    return out


class _Estimated:
    """A SoftString whose placement objective takes the estimate's settings: place_oscillators' first parameter is
    called ``model``, so its ``**keywords`` cannot carry the estimate's ``model`` keyword."""

    def __init__(self, soft_string: SoftString, estimate: Dict[str, Any]) -> None:
        self._soft_string, self._estimate = soft_string, estimate

    def __getattr__(self, name: str):
        return getattr(self._soft_string, name)

    def sliding_weight_on_bit(self, hook_load, tools, **keywords):
        return self._soft_string.sliding_weight_on_bit(hook_load, tools, **keywords, **self._estimate)
