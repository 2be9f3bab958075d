"""Property tests of the WELLS surface (issue 23, item 2): hypothesis strategies generated from the parameter tables
of the soft string's conditions (SoftString.parameters), the hydraulic oscillator (HydraulicOscillator.parameters)
and the survey stations (Survey.parameters), valid and mutated (any number in one field, or a value of the wrong
kind), each input counted in tests/python/outcomes.py's table under "soft-string conditions", "hydraulic
oscillators" and "survey stations". A valid input gives a finite result that obeys the physics checked here (pulling
out hangs heavier than rotating, which hangs heavier than running in; a vibration never adds drag; an arc is no
shorter than its chord); an invalid one a clean rejection naming the parameter given. Bounded: the "ci" profile of
test_properties.py (40 examples, derandomized)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import frictionsim as fs
import test_properties  # noqa: F401  (registers and loads the "ci" / "long" hypothesis profiles)
from frictionsim import wells
from outcomes import record
from strategies import _law_params, any_number, typical, valid

#: the tables, read as strategies.py reads every law's and rig's
CONDITIONS = _law_params(fs.SoftString, tied_by_construction=False)
TOOL = _law_params(fs.HydraulicOscillator, tied_by_construction=False)
STATION = _law_params(fs.Survey, tied_by_construction=False)

SURVEY = fs.Survey.from_degrees([0.0, 500.0, 1500.0, 2500.0], [0.0, 0.0, 60.0, 90.0], [0.0, 0.0, 30.0, 45.0])
PIPE = fs.PipeSection(length=2000.0)
STRING = fs.DrillString([PIPE, fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=200.0)])
MODEL = fs.SoftString(SURVEY, STRING, 44)
LARGEST_OD = max(s.outer_diameter for s in STRING.sections)
MIDDLES = 0.5 * (np.asarray(MODEL.node_depths)[:-1] + np.asarray(MODEL.node_depths)[1:])
#: the rules across tables: the hole and the casing wider than the pipe (SoftString.run checks them per element)
CLEARANCE = ("hole_diameter", "casing_inner_diameter")


def _clear(kwargs):
    """The rule across tables, as SoftString.run applies it: the open hole (an element below the shoe by its middle)
    and the casing (one above it) wider than the pipe."""
    cased = MIDDLES < kwargs["casing_shoe_depth"]
    return ((not np.any(~cased) or kwargs["hole_diameter"] > LARGEST_OD)
            and (not np.any(cased) or kwargs["casing_inner_diameter"] > LARGEST_OD))

#: values of the wrong kind for a number: an array (numpy's TypeError before), a flag, nothing, complex, a list
WRONG_KINDS = [lambda v: np.array([v]), lambda v: True, lambda v: None, lambda v: complex(v, 1.0), lambda v: [v]]


def _draw_kwargs(draw, table, mutate, held=None):
    """Typical keywords of a table (strategies.typical over each field's decade around the engine's example, held
    ones as given); with `mutate`, one field is any number or a value of the wrong kind. Returns (kwargs, mutated
    field, whether the mutation is of kind)."""
    held = held or {}
    kwargs = {name: held[name] if name in held else draw(typical(p)) for name, p in table.items()}
    if not mutate:
        return kwargs, None, False
    name = draw(st.sampled_from(sorted(table)))
    if draw(st.booleans()):
        kwargs[name] = draw(st.sampled_from(WRONG_KINDS))(kwargs[name])
        return kwargs, name, True
    kwargs[name] = draw(any_number())
    return kwargs, name, False


def _refused(error, name, input_class):
    """A refusal of a mutated input: it names the mutated parameter, else it is the wrong error."""
    if name is not None and name in str(error):
        record(input_class, "clean rejection")
        return
    record(input_class, "wrong kind of error")
    raise AssertionError(f"refused without naming {name!r}: {type(error).__name__}: {error}")


# ------------------------------------------------------------------------------------- soft-string conditions
@given(data=st.data())
def test_soft_string_conditions_run_finite_and_ordered_or_are_refused_by_name(data):
    kwargs, mutated, of_kind = _draw_kwargs(data.draw, CONDITIONS, data.draw(st.booleans()))
    operation = data.draw(st.sampled_from(wells.OPERATIONS))
    by_rule = not of_kind and all(valid(CONDITIONS[k], v) for k, v in kwargs.items())
    wide = by_rule and _clear(kwargs)
    try:
        result = MODEL.run(operation, **kwargs)
    except TypeError as error:
        assert of_kind, f"{kwargs}: {error}"
        _refused(error, mutated, "soft-string conditions")
        return
    except fs.InvalidParameterError as error:
        assert error.parameter in kwargs, error  # named as the caller named it
        if error.parameter in CLEARANCE and not _clear(kwargs):
            record("soft-string conditions", "clean rejection")  # the rule across the tables
            return
        if mutated is not None and error.parameter == mutated:
            # outside its rule, or a friction factor so large that e^(mu theta) leaves the doubles (named so)
            assert not by_rule or "locks up" in str(error), error
            record("soft-string conditions", "clean rejection")
            return
        record("soft-string conditions", "wrong kind of error")
        raise AssertionError(f"{kwargs}: valid conditions refused: {error}")
    if not wide:
        record("soft-string conditions", "silent nonsense")
        raise AssertionError(f"invalid conditions accepted: {kwargs} -> {result!r}")
    arrays = [result.tension, result.torque, result.side_force, result.sinusoidal_buckling_load]
    if not all(np.all(np.isfinite(a)) for a in arrays):
        record("soft-string conditions", "NaN as success")
        raise AssertionError(f"{kwargs}: non-finite result")
    # the physics: the bit's load, and friction against the motion: out >= rotating >= in at the hook
    drilling = operation in ("sliding_drilling", "rotary_drilling")
    hooks = [MODEL.run(op, **kwargs).hook_load for op in ("trip_out", "rotating_off_bottom", "trip_in")]
    scale = 1e-9 * max(abs(h) for h in hooks) + 1e-6
    ordered = hooks[0] >= hooks[1] - scale and hooks[1] >= hooks[2] - scale
    at_bit = result.tension[-1] == (-kwargs["weight_on_bit"] if drilling else 0.0)
    if not (ordered and at_bit and np.all(np.asarray(result.side_force) >= 0.0)):
        record("soft-string conditions", "silent nonsense")
        raise AssertionError(f"{kwargs}: hook loads out/rotating/in {hooks}, bit tension {result.tension[-1]}")
    record("soft-string conditions", "finite result")


# ------------------------------------------------------------------------------------------ hydraulic oscillators
@given(data=st.data())
def test_hydraulic_oscillators_build_and_reduce_drag_or_are_refused_by_name(data):
    depth = data.draw(st.floats(0.0, STRING.length))  # the rule across tables: at most the string's length
    kwargs, mutated, of_kind = _draw_kwargs(data.draw, TOOL, data.draw(st.booleans()), {"measured_depth": depth})
    by_rule = not of_kind and all(valid(TOOL[k], v) for k, v in kwargs.items())
    try:
        tool = fs.HydraulicOscillator(**kwargs)
        result = MODEL.oscillators("sliding_drilling", tool, weight_on_bit=2e4)
    except TypeError as error:
        assert of_kind, f"{kwargs}: {error}"
        _refused(error, mutated, "hydraulic oscillators")
        return
    except fs.InvalidParameterError as error:
        assert not by_rule or (error.parameter == "measured_depth" and kwargs["measured_depth"] > STRING.length), \
            f"{kwargs}: valid tool refused: {error}"
        _refused(error, mutated, "hydraulic oscillators")
        return
    if not by_rule:
        record("hydraulic oscillators", "silent nonsense")
        raise AssertionError(f"invalid tool accepted: {kwargs} -> {tool!r}")
    reduction = np.asarray(result.reduction)
    if not (np.all(np.isfinite(reduction)) and math.isfinite(result.hook_load_change)):
        record("hydraulic oscillators", "NaN as success")
        raise AssertionError(f"{kwargs}: non-finite result")
    # a vibration only lowers the friction (factor in [0, 1]), so sliding in the hook hangs no lighter
    plain = result.plain.hook_load
    if not (np.all((reduction >= 0.0) & (reduction <= 1.0))
            and result.hook_load_change >= -1e-9 * abs(plain)
            and (kwargs["force_amplitude"] > 0.0 or result.vibrated.hook_load == plain)):
        record("hydraulic oscillators", "silent nonsense")
        raise AssertionError(f"{kwargs}: reduction {reduction.min()}..{reduction.max()}, "
                             f"hook load change {result.hook_load_change}")
    assert repr(eval(repr(tool), vars(fs))) == repr(tool)  # the repr rebuilds it
    record("hydraulic oscillators", "finite result")


# ----------------------------------------------------------------------------------------------- survey stations
def _tangent(inclination, azimuth):
    return np.array([math.sin(inclination) * math.cos(azimuth), math.sin(inclination) * math.sin(azimuth),
                     math.cos(inclination)])


@st.composite
def stations(draw, mutate):
    """2-8 stations: measured depth increasing by 1-300 m, inclination from the table's typical values (within its
    rule), azimuth any angle; with `mutate` one field of one station any number or of the wrong kind."""
    n = draw(st.integers(2, 8))
    md = np.cumsum([0.0] + [draw(st.floats(1.0, 300.0)) for _ in range(n - 1)])
    inc = [draw(typical(STATION["inclination"])) for _ in range(n)]
    azi = [draw(st.floats(-2 * math.pi, 2 * math.pi)) for _ in range(n)]
    columns = {"measured_depth": list(md), "inclination": inc, "azimuth": azi}
    if not mutate:
        return columns, None, False
    field = draw(st.sampled_from(sorted(STATION)))
    if draw(st.booleans()):
        kind = draw(st.sampled_from([lambda c: [complex(x, 1.0) for x in c], lambda c: np.array(c) > 0.0,
                                     lambda c: np.array([str(x) for x in c])]))
        columns[field] = kind(columns[field])
        return columns, field, True
    station = draw(st.integers(0, n - 1))
    columns[field][station] = draw(any_number())
    return columns, field, False


def _expected_valid(columns):
    md, inc, azi = (np.asarray(columns[k], dtype=float) for k in ("measured_depth", "inclination", "azimuth"))
    if not all(valid(STATION[k], float(v)) for k in STATION for v in columns[k]):
        return False
    if not np.all(np.diff(md) > 0.0):
        return False
    doglegs = [math.acos(max(-1.0, min(1.0, _tangent(inc[i], azi[i]) @ _tangent(inc[i + 1], azi[i + 1]))))
               for i in range(len(md) - 1)]
    return all(b < math.pi - 1e-6 for b in doglegs)


@given(data=st.data())
def test_survey_stations_give_a_trajectory_no_longer_than_its_arcs_or_are_refused_by_name(data):
    columns, mutated, of_kind = data.draw(stations(mutate=data.draw(st.booleans())))
    try:
        survey = fs.Survey(**columns)
    except TypeError as error:
        assert of_kind, f"{columns}: {error}"
        _refused(error, mutated, "survey stations")
        return
    except fs.InvalidParameterError as error:
        assert error.parameter.split("[")[0] in STATION, error  # the units layer names text as field[i]
        assert of_kind or mutated is not None, f"valid stations refused: {columns}: {error}"
        # a mutated value breaks its own rule or one across stations: depth order (named at measured_depth) or a
        # reversed course (named at inclination); the field named is the mutated one's or that rule's
        if of_kind or not _expected_valid(columns):
            record("survey stations", "clean rejection")
            return
        record("survey stations", "wrong kind of error")
        raise AssertionError(f"valid stations refused: {columns}: {error}")
    if of_kind or not _expected_valid(columns):
        record("survey stations", "silent nonsense")
        raise AssertionError(f"invalid stations accepted: {columns}")
    position = np.stack([survey.north, survey.east, survey.tvd], axis=1)
    if not np.all(np.isfinite(position)):
        record("survey stations", "NaN as success")
        raise AssertionError(f"{columns}: non-finite trajectory")
    course = np.diff(survey.measured_depth)
    chord = np.linalg.norm(np.diff(position, axis=0), axis=1)
    md, inc, azi = (np.asarray(columns[k], dtype=float) for k in ("measured_depth", "inclination", "azimuth"))
    dogleg = [2.0 * math.atan2(np.linalg.norm(_tangent(inc[i], azi[i]) - _tangent(inc[i + 1], azi[i + 1])),
                               np.linalg.norm(_tangent(inc[i], azi[i]) + _tangent(inc[i + 1], azi[i + 1])))
              for i in range(len(md) - 1)]
    # the minimum-curvature arc is no shorter than its chord, its dogleg the angle between the station tangents,
    # the arc's chord 2 R sin(beta / 2) with R = dMD / beta exactly
    expected_chord = np.array([c if b < 1e-8 else 2.0 * c / b * math.sin(0.5 * b) for c, b in zip(course, dogleg)])
    if not (np.all(chord <= course * (1.0 + 1e-12))
            and np.allclose(survey.dogleg[1:], dogleg, rtol=1e-9, atol=1e-12)
            and np.allclose(chord, expected_chord, rtol=1e-9, atol=1e-9 * course.max())):
        record("survey stations", "silent nonsense")
        raise AssertionError(f"{columns}: chords {chord} over courses {course}, doglegs {survey.dogleg[1:]} "
                             f"vs {dogleg}")
    rebuilt = eval(repr(survey), vars(fs))  # the repr rebuilds it bit for bit
    assert all(np.array_equal(getattr(rebuilt, k), getattr(survey, k)) for k in STATION)
    record("survey stations", "finite result")


def test_the_strategies_come_from_the_tables():
    # the keywords drawn are the tables' own: a field added to a table is drawn without editing this file
    assert set(CONDITIONS) == {p.name for p in fs.SoftString.parameters} and len(CONDITIONS) == 11
    assert set(TOOL) == {"measured_depth", "force_amplitude", "frequency"}
    assert set(STATION) == {"measured_depth", "inclination", "azimuth"}
    assert STATION["inclination"].valid == (0.0, math.pi)
    assert CONDITIONS["weight_on_bit"].valid == (0.0, 1e9)
