"""Field units at the boundary: the engine's constructors and scenario files take ``"55 rpm"``, ``"25 klbf"``,
``"5 in"``, ``"8.5 ppg"`` or :mod:`pint` quantities as well as plain SI numbers; the engine itself stays SI.

Every parameter table of the engine names its SI unit (``X.parameters[i].unit``, the C++ ``Field::unit``). A value
given with a unit is converted to that unit and the plain number passed on; a bare number is SI and passes
through untouched (no conversion, no pint import). One mechanism serves every class: :func:`install` (run by
``import frictionsim``) wraps each engine routine that takes a table's keywords, reading the units from the
table (``SoftString.run``'s conditions too: ``run("rotating_off_bottom", rotary_speed="120 rpm",
mud_density="10 ppg")``)::

    >>> import frictionsim as fs
    >>> fs.TorsionalRig(fs.Coulomb(0.3), reference_speed="55 rpm").reference_speed   # rad/s
    5.759586531581287
    >>> fs.units.to_si("25 klbf", "N")
    111205.54038151252
    >>> fs.units.convert(1198.2642731689666, "kg/m^3", "ppg")   # results back in field units
    10.0

A unit of the wrong kind is a :class:`UnitError` (an :class:`~frictionsim.errors.InvalidParameterError`, and a
TypeError) naming the parameter and the dimension it expects (``rotary_speed: expected an angular speed (rad/s),
got 25 klbf [force]``). Strings need pint
(``pip install 'frictionsim[units]'``); without it a string raises :class:`UnitsUnavailableError`, an ImportError
naming the extra.

Angles are a dimension here (pint's own registry counts the radian as a pure number, so it would turn 1 Hz into
1 rad/s and 1 rpm into 0.105 Hz): rpm converts to rad/s, a frequency in Hz does not. The drilling units pint lacks
or defines otherwise are in :data:`DRILLING_UNITS` (ppg, pcf, sg, klbf, oil barrel bbl) and the string rules of
:func:`quantity` (``ft-lbf``, ``deg/30m``, ``deg/100ft``, ``lbf/100ft^2``, pipe sizes ``5 1/2 in``).

Text is read with bounds, since pint evaluates its arithmetic: at most :data:`MAX_TEXT_LENGTH` characters, and
exponents in floating point (``10**10**10`` overflows at once instead of computing a ten-billion-digit integer),
each refused as a :class:`UnitError` naming the parameter, as is a value beyond the range of a double.
"""

from __future__ import annotations

import functools
import math
import re
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple

import numpy as np

from .errors import InvalidParameterError

__all__ = ["DRILLING_UNITS", "MAX_TEXT_LENGTH", "TABLE_UNITS", "UnitError", "UnitsUnavailableError", "convert",
           "describe", "install", "quantity", "registry", "table_unit", "to_si", "units_of"]

#: Words for the unit strings of the engine's parameter tables (C++ ``Field::unit``, include/frictionsim) and of the
#: few arguments no table describes (``deg``, ``rad/m``): (its pint expression, what it measures, the dimension's
#: name), for the messages. A table's unit string needs no entry: :func:`table_unit` reads it as written (units
#: separated by spaces multiply, ``^`` is a power), and a message then names its dimension as pint states it.
TABLE_UNITS: Dict[str, Tuple[str, str, str]] = {
    "-": ("dimensionless", "a dimensionless number", "dimensionless"),
    "Hz": ("Hz", "a frequency", "frequency"),
    "1/s": ("1/s", "a rate", "rate"),
    "H": ("henry", "an inductance", "inductance"),
    "N": ("N", "a force", "force"),
    "N m": ("N*m", "a torque", "torque"),
    "N m s/rad": ("N*m*s/rad", "a torque per angular speed", "torque per angular speed"),
    "N m/A": ("N*m/A", "a torque per current", "torque per current"),
    "N m/rad": ("N*m/rad", "a torque per angle", "torque per angle"),
    "N s/m": ("N*s/m", "a force per speed", "force per speed"),
    "N/m": ("N/m", "a force per length", "force per length"),
    "N/s": ("N/s", "a force rate", "force rate"),
    "Ohm": ("ohm", "a resistance", "resistance"),
    "Pa": ("Pa", "a pressure", "pressure"),
    "V s/rad": ("V*s/rad", "a voltage per angular speed", "voltage per angular speed"),
    "V/rad": ("V/rad", "a voltage per angle", "voltage per angle"),
    "kg": ("kg", "a mass", "mass"),
    "kg m^2": ("kg*m**2", "a moment of inertia", "moment of inertia"),
    "kg/m^3": ("kg/m**3", "a density", "density"),
    "m": ("m", "a length", "length"),
    "m/s": ("m/s", "a speed", "speed"),
    "m/s^2": ("m/s**2", "an acceleration", "acceleration"),
    "rad": ("rad", "an angle", "angle"),
    "rad/s": ("rad/s", "an angular speed", "angular speed"),
    "s": ("s", "a time", "time"),
    # not in a table: Survey.from_degrees's angles, a dogleg severity
    "deg": ("degree", "an angle", "angle"),
    "rad/m": ("rad/m", "a dogleg severity (angle per length)", "angle per length"),
}

#: Arguments that no parameter table describes (yet), with their SI units as the bindings document them:
#: class -> routine -> argument -> unit. Everything else is read off the tables.
_UNTABLED: Dict[str, Dict[str, Dict[str, str]]] = {
    # Survey's table (SI: m, rad) describes __init__; from_degrees takes its angles in degrees
    "Survey": {"from_degrees": {"inclination": "deg", "azimuth": "deg"}},
    "StringRig": {"__init__": {"weight_on_bit": "N", "normal_forces": "N", "node_inclinations": "rad"}},
    "AxialVibrationRig": {"__init__": {"initial_position": "m"}},
    "KinematicRig": {"harmonic": {"sliding_velocity": "m/s", "velocity_amplitude": "m/s", "frequency": "Hz",
                                  "normal_force": "N"}},
    "SoftString": {"sliding_weight_on_bit": {"hook_load": "N"}},
}

#: The drilling units pint lacks, in pint's definition syntax (the oil barrel is made pint's ``bbl`` too: pint's
#: own ``bbl`` is the 31.5-gallon barrel, never the drilling one).
DRILLING_UNITS: Tuple[str, ...] = (
    "pound_per_gallon = pound / gallon = ppg",  # mud weight: 1 ppg = 119.826427 kg/m^3 (US gallon)
    "pound_per_cubic_foot = pound / foot ** 3 = pcf",  # mud weight: 1 pcf = 16.018463 kg/m^3
    "specific_gravity = 1000 * kilogram / meter ** 3 = sg",  # mud weight in SG (water as 1000 kg/m^3)
    "kilopound_force = 1000 * force_pound = klbf",  # hook load, weight on bit: 1 klbf = 4448.2216 N
)

#: "5 1/2 in", "13-3/8 in": a pipe size as a mixed number (pint would read 5 * 1/2 in = 2.5 in)
_MIXED = re.compile(r"(?<![\d.])(\d+)(?:\s+|\s*-\s*)(\d+)\s*/\s*(\d+)(?=\s*[A-Za-z])")
#: "ft-lbf", "ft·lbf": a product of units (pint would read the hyphen as a minus sign)
_PRODUCT = re.compile(r"(?<=[A-Za-z])\s*[-\u00b7\u22c5]\s*(?=[A-Za-z])")
#: "deg/30m", "deg/100 ft", "lbf/100ft^2": per a course (an area) of that size (pint would read deg/30*m); the
#: unit keeps its exponent: lbf/(100 ft^2), the yield point's unit, not lbf/(100 ft)^2
_PER_COURSE = re.compile(r"(?<=[A-Za-z])\s*/\s*(\d+(?:\.\d*)?)\s*([A-Za-z]+(?:\s*(?:\^|\*\*)\s*\d+)?)")
#: the first number of an exponent ("**10", "^(2", "**-3"): made a float, so that "10**10**10" overflows at once
#: (OverflowError, a string that cannot be read) instead of pint computing a ten-billion-digit integer; the rest of
#: an exponent follows the float through the arithmetic
_INTEGER_EXPONENT = re.compile(r"(\*\*|\^)([\s(+-]*)(\d+)(?![\d.eE])")
#: the longest unit string read: pint's parser and its integers grow with the text (a 400-digit magnitude)
MAX_TEXT_LENGTH = 200


class UnitsUnavailableError(ImportError):
    """A value with a unit arrived but pint is not installed: ``pip install 'frictionsim[units]'``."""


class UnitError(InvalidParameterError, TypeError):
    """A value of the wrong kind for its parameter: a unit of another dimension, a string that is no quantity, or
    a bare number written as a string where the parameter has a unit. An InvalidParameterError (a ValueError)
    naming the parameter, and a TypeError as well: what the engine raised for a string before it took units."""


def _preprocess(text: str) -> str:
    text = _MIXED.sub(r"(\1 + \2/\3)", text.replace("\u00b0", " deg "))
    text = _PER_COURSE.sub(r"/(\1 \2)", _PRODUCT.sub("*", text))
    return _INTEGER_EXPONENT.sub(r"\1\2\3.0", text)


@functools.lru_cache(maxsize=None)
def registry():
    """The unit registry of frictionsim: pint's default definitions with the radian as a dimension of its own
    ([angle]), the oil barrel as ``bbl`` and :data:`DRILLING_UNITS`. Built on first use (about 0.1 s).

    Quantities of another pint registry are accepted too (converted through their unit's name)."""
    try:
        import pint
    except ImportError as error:
        raise UnitsUnavailableError("values with units need pint: pip install 'frictionsim[units]'") from error
    from importlib import resources

    files = resources.files("pint")
    text = files.joinpath("default_en.txt").read_text(encoding="utf-8")
    changes = (("@import constants_en.txt", files.joinpath("constants_en.txt").read_text(encoding="utf-8")),
               ("radian = [] = rad", "radian = [angle] = rad"),
               ("barrel = 31.5 * gallon = bbl", "barrel = 31.5 * gallon"),
               ("oil_barrel = 42 * gallon = oil_bbl", "oil_barrel = 42 * gallon = oil_bbl = bbl"))
    for old, new in changes:
        if old not in text:  # a pint release that changed its definitions: fail here, not with wrong numbers
            raise RuntimeError(f"pint {pint.__version__}'s default_en.txt has no line {old!r}; "
                               f"frictionsim.units needs updating")
        text = text.replace(old, new, 1)
    ureg = pint.UnitRegistry(None, preprocessors=[_preprocess])
    ureg.load_definitions(text.splitlines() + list(DRILLING_UNITS))
    ureg._build_cache()  # what the constructor does after loading its default file
    return ureg


@functools.lru_cache(maxsize=None)
def _target(unit: str):
    """The pint unit of a table's unit string."""
    return registry().Unit(table_unit(unit))


def table_unit(unit: str) -> str:
    """The pint expression of a table's unit string ("N m s/rad" -> "N*m*s/rad", "kg m^2" -> "kg*m**2",
    "-" -> "dimensionless"): read off the string itself, so a law's new unit needs no entry here."""
    if unit in TABLE_UNITS:
        return TABLE_UNITS[unit][0]
    if unit.strip() in ("-", "1", ""):
        return "dimensionless"
    return re.sub(r"(?<=[\w)])\s+(?=[A-Za-z(])", "*", unit.strip()).replace("^", "**")


def describe(unit: str) -> str:
    """What a table's unit measures, e.g. ``describe("rad/s") == "an angular speed (rad/s)"``."""
    return f"{TABLE_UNITS[unit][1]} ({unit})" if unit in TABLE_UNITS else f"a value in {unit}"


def _dimension_name(dimensionality) -> str:
    for unit, (_, _, name) in TABLE_UNITS.items():
        if _target(unit).dimensionality == dimensionality:
            return name
    return str(dimensionality)


#: types that never carry a unit: the fast path of a call in SI
_PLAIN = frozenset({float, int, bool, type(None), np.float64, np.ndarray})


def _is_quantity(value: Any) -> bool:
    return hasattr(value, "magnitude") and hasattr(value, "units") and hasattr(value, "dimensionality")


def _has_unit(value: Any) -> bool:
    """A value that needs converting: a string, a quantity, or a list / tuple holding one at any depth (a nested
    list of strings is converted element by element, never passed on as text)."""
    if isinstance(value, str) or _is_quantity(value):
        return True
    return isinstance(value, (list, tuple)) and any(
        isinstance(v, str) or _is_quantity(v) or (isinstance(v, (list, tuple)) and _has_unit(v)) for v in value)


def quantity(value: Any, parameter: str = "value"):
    """``value`` (a string such as ``"25 klbf"``, ``"3 deg/30m"``, or a pint quantity of any registry) as a
    quantity of :func:`registry`. A string that is a bare number is a dimensionless quantity.

    Strings are read as pint reads them, and as a drilling engineer writes them: ``ft-lbf`` and ``ft·lbf`` are
    products, ``deg/30m`` and ``deg/100ft`` are per a course of 30 m / 100 ft, ``5 1/2 in`` and ``13-3/8 in`` are
    mixed numbers, ``°`` is a degree."""
    ureg = _registry_for(parameter, value)
    if not isinstance(value, str) and not _is_quantity(value):
        raise UnitError(f"{parameter}: expected a value with a unit (a string such as '25 klbf' or a pint quantity), "
                        f"got {_brief(repr(value), 60)} [{type(value).__name__}]", parameter)
    if isinstance(value, str):
        parsed = _parse(value)
        if isinstance(parsed, str):
            raise UnitError(f"{parameter}: {parsed}", parameter)
        return ureg.Quantity(parsed.magnitude, parsed.units)  # a copy: the cached one stays as read
    if getattr(value, "_REGISTRY", None) is ureg:
        return value
    return ureg.Quantity(value.magnitude, str(value.units))  # another registry's quantity: by its unit's name


def to_si(value: Any, unit: str, parameter: str = "value") -> Any:
    """``value`` in the SI unit ``unit`` (a table's unit string, e.g. ``"rad/s"``, or any pint unit): a string or
    a quantity converted (a float, or an array for an array quantity; a list of them element by element); a bare
    number or array returned as it is. A string that is a bare number is taken only for a dimensionless ``unit``
    ("0.3" for a friction coefficient); elsewhere the unit was forgotten.

    Raises :class:`UnitError` (an InvalidParameterError) naming ``parameter`` and the expected dimension on a unit
    of the wrong kind."""
    if not _has_unit(value):
        return value
    if isinstance(value, (list, tuple)):
        return [to_si(v, unit, f"{parameter}[{i}]") for i, v in enumerate(value)]
    # the target unit readable, or refused by name (a bare number as text needs no pint, nor a unit read)
    context = f" (the unit {parameter} is converted to)"
    if isinstance(value, str):
        if not _is_number(value):
            _registry_for(parameter, value)
            _unit(unit, "unit", context)
        number, problem = _text_to_si(value, unit)  # a string: read once, then from the cache
    else:
        given = quantity(value, parameter)
        _unit(unit, "unit", context)
        number, problem = _in_unit(given, unit, f"{given:~}")
    if problem is not None:
        raise UnitError(f"{parameter}: {problem}", parameter)
    return number


def _registry_for(parameter: str, value: Any):
    """The registry, or the error saying that ``value`` of ``parameter`` needs pint."""
    try:
        return registry()
    except UnitsUnavailableError as error:
        raise UnitsUnavailableError(f"{parameter}={value!r}: {error}") from None


@functools.lru_cache(maxsize=4096)
def _parse(text: str):
    """The quantity a string says, or the problem (a str) why it says none."""
    ureg = registry()
    if not text.strip():  # pint reads '' as the number 1: a value left out, never a friction coefficient of 1
        return f"{text!r} is empty: give a number or a value with its unit"
    if len(text) > MAX_TEXT_LENGTH:
        return f"cannot read a value with a unit from {len(text)} characters (at most {MAX_TEXT_LENGTH})"
    try:
        parsed = ureg.parse_expression(text)
    except Exception as error:  # pint's parser raises anything from AssertionError to TokenError on garbage
        return f"cannot read {_shown(text)} as a value with a unit ({type(error).__name__}: {_brief(str(error))})"
    return parsed if _is_quantity(parsed) else ureg.Quantity(parsed)


@functools.lru_cache(maxsize=4096)
def _text_to_si(text: str, unit: str) -> Tuple[Optional[float], Optional[str]]:
    """(the string's value in ``unit``, None) or (None, the problem)."""
    if _is_number(text):
        if unit in ("-", "dimensionless"):
            return float(text), None
        return None, (f"{text!r} has no unit: give a number (SI: {unit}) or the value with its unit, e.g. "
                      f"'{text.strip()} {unit}'")
    parsed = _parse(text)
    if isinstance(parsed, str):
        return None, parsed
    return _in_unit(parsed, unit, text)


def _in_unit(given, unit: str, shown: str) -> Tuple[Any, Optional[str]]:
    target = _target(unit)
    if given.dimensionality != target.dimensionality:
        return None, f"expected {describe(unit)}, got {shown} [{_dimension_name(given.dimensionality)}]"
    # the same unit: the very number (no factor of 1.0 through base units)
    try:
        magnitude = given.magnitude if str(given.units) == str(target) else given.to(target).magnitude
        number = _number(magnitude)
    except OverflowError:  # an integer beyond a double ('999...9 N', 400 digits)
        return None, f"{_shown(shown)} is beyond the range of a double in {unit}"
    if _overflowed(given.magnitude, number):
        return None, f"{_shown(shown)} is not a finite value in {unit}"
    return number, None


def _overflowed(given: Any, number: Any) -> bool:
    """A value finite as given but not after the conversion (an inf or NaN given stays for the engine's own rule
    to name)."""
    with np.errstate(invalid="ignore"):
        return bool(np.any(~np.isfinite(np.asarray(number, dtype=float)) & np.isfinite(np.asarray(given, dtype=float))))


def _shown(text: str) -> str:
    return repr(text) if len(text) <= 40 else repr(text[:37] + "...")


def _brief(text: str, length: int = 120) -> str:
    """``text`` cut to ``length`` characters, for a message that quotes something of unbounded size."""
    return text if len(text) <= length else text[:length - 3] + "..."


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def _number(magnitude: Any) -> Any:
    array = np.asarray(magnitude, dtype=float)
    return float(array) if array.ndim == 0 else array


def convert(value: Any, from_unit: str, to_unit: str) -> Any:
    """A number (or array) in ``from_unit`` expressed in ``to_unit``, e.g. a result in field units:
    ``convert(result.hook_load, "N", "klbf")``.

    Raises :class:`UnitError` naming ``from_unit`` or ``to_unit`` when it is no unit, or when the two measure
    different things (not pint's own errors); naming ``value`` when it is not a real number or array of them (a
    string or quantity with its unit goes through :func:`to_si`; None is no number) or when its value in
    ``to_unit`` is beyond the range of a double."""
    import pint

    ureg = registry()
    units = {name: _unit(unit, name) for name, unit in (("from_unit", from_unit), ("to_unit", to_unit))}
    numbers = _real_numbers(value, "value")
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            number = _number(ureg.Quantity(numbers, units["from_unit"]).to(units["to_unit"]).magnitude)
    except pint.errors.DimensionalityError:
        raise UnitError(f"to_unit: cannot convert {describe(from_unit)} "
                        f"[{_dimension_name(units['from_unit'].dimensionality)}] to {describe(to_unit)} "
                        f"[{_dimension_name(units['to_unit'].dimensionality)}]", "to_unit") from None
    if _overflowed(numbers, number):
        raise UnitError(f"value: {_brief(repr(value), 60)} {from_unit} is not a finite value in {to_unit} (beyond the "
                        f"range of a double)", "value")
    return number


def _unit(unit: Any, name: str, context: str = ""):
    """The pint unit of a unit string given as ``name``, or the UnitError naming it (never pint's own errors)."""
    try:
        if not isinstance(unit, str):
            raise TypeError(f"a unit is a string, got {type(unit).__name__}")
        if len(unit) > MAX_TEXT_LENGTH:
            raise ValueError(f"{len(unit)} characters (at most {MAX_TEXT_LENGTH})")
        return _target(unit)
    except UnitsUnavailableError:
        raise
    except Exception as error:  # pint raises UndefinedUnitError, DefinitionSyntaxError, ... on garbage
        raise UnitError(f"{name}: cannot read {_brief(repr(unit), 60)} as a unit{context} ({type(error).__name__}: "
                        f"{_brief(str(error))})", name) from None


def _real_numbers(value: Any, name: str) -> np.ndarray:
    """``value`` as a float array, or the UnitError naming ``name``: numpy would read '2' as 2.0 and None as NaN."""
    if isinstance(value, (str, bytes)) or _is_quantity(value) or value is None:
        raise UnitError(f"{name}: expected a number or an array of numbers, got {_brief(repr(value), 60)} "
                        f"[{type(value).__name__}] (a value with its unit goes through to_si)", name)
    try:
        array = np.asarray(value)
        if array.dtype.kind not in "iuf":
            raise TypeError(f"numbers of dtype {array.dtype}")
        return np.asarray(array, dtype=float)
    except (TypeError, ValueError) as error:
        raise UnitError(f"{name}: expected a number or an array of numbers, got {_brief(repr(value), 60)} "
                        f"({error})", name) from None


def units_of(source: Any, routine: str = "__init__") -> Dict[str, str]:
    """Argument -> SI unit of ``routine`` of ``source`` (an engine class, or any callable: then {}): its table's
    keywords (``source.parameters``) and the arguments no table describes yet."""
    records = getattr(source, "parameters", None)
    units: Dict[str, str] = {}
    if isinstance(records, (list, tuple)):
        units = {r.name: r.unit for r in records if hasattr(r, "unit")}
    return {**units, **_UNTABLED.get(getattr(source, "__name__", ""), {}).get(routine, {})}


# -- installing the conversion on the engine's classes

def _signatures(doc: str) -> List[str]:
    """The argument lists of a pybind11 docstring's signature lines (one per overload)."""
    return [m.group(1) for m in re.finditer(r"^\s*(?:\d+\.\s*)?\w+\((.*)\)\s*->", doc or "", re.M)]


def _argument_names(arguments: str) -> List[str]:
    names, depth, start = [], 0, 0
    for i, char in enumerate(arguments + ","):
        if char in "[(":
            depth += 1
        elif char in "])":
            depth -= 1
        elif char == "," and depth == 0:
            names.append(arguments[start:i].partition(":")[0].partition("=")[0].strip())
            start = i + 1
    return [n for n in names if n]


def _positional(arguments: str) -> List[str]:
    """The names an argument list takes by position: those before ``*`` or ``*args``."""
    names = _argument_names(arguments)
    stars = [i for i, n in enumerate(names) if n.startswith("*")]
    return names[:stars[0]] if stars else names


def _with_units(routine: Callable, qualname: str, positional: Optional[List[str]],
                units: Mapping[str, str]) -> Callable:
    """``routine`` taking values with units for the arguments of ``units`` (by keyword, and by position where
    ``positional`` names them); plain numbers go straight through."""
    at = [(i, n) for i, n in enumerate(positional or ()) if n in units]

    def with_units(*args, **kwargs):  # (*args, **kwargs): pybind11-stubgen reads the docstring's signature
        for key, value in kwargs.items():
            if type(value) not in _PLAIN and key in units and _has_unit(value):
                kwargs = {k: to_si(v, units[k], k) if k in units else v for k, v in kwargs.items()}
                break
        if any(i < len(args) and type(args[i]) not in _PLAIN and _has_unit(args[i]) for i, _ in at):
            args = list(args)
            for i, name in at:
                if i < len(args):
                    args[i] = to_si(args[i], units[name], name)
        return routine(*args, **kwargs)

    with_units.__doc__, with_units.__name__ = routine.__doc__, qualname.rpartition(".")[2]
    with_units.__qualname__, with_units.__module__ = qualname, "frictionsim._core"
    with_units.__wrapped__ = routine
    with_units._frictionsim_units = dict(units)
    return with_units


def install(module: Any = None) -> None:
    """Make every routine of the engine (``frictionsim._core``) that takes a parameter table's keywords (the
    constructors, ``SoftString.run`` and the like) accept values with units. Run once by ``import frictionsim``;
    a second call changes nothing."""
    if module is None:
        from . import _core as module
    for class_name, cls in vars(module).items():
        if not isinstance(cls, type):
            continue
        table = units_of(cls, "")  # the table alone
        for name, raw in list(vars(cls).items()):
            if name.startswith("_") and name != "__init__":
                continue
            static = isinstance(raw, staticmethod)
            routine = raw.__func__ if static else raw
            if not callable(routine) or hasattr(routine, "_frictionsim_units") or isinstance(routine, type):
                continue
            signatures = _signatures(getattr(routine, "__doc__", None) or "")
            if not signatures:
                continue
            names = [n for s in signatures for n in _argument_names(s)]
            by_keyword = any(n.startswith("**") for n in names)
            units = {n: u for n, u in table.items() if by_keyword or n in names}
            units.update(_UNTABLED.get(class_name, {}).get(name, {}))
            if not units:
                continue
            positional = _positional(signatures[0]) if len(signatures) == 1 else None
            wrapped = _with_units(routine, f"{class_name}.{name}", positional, units)
            setattr(cls, name, staticmethod(wrapped) if static else wrapped)
