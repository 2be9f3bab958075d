"""Property tests (hypothesis) of the drill-string surface (issue 23, item 2): pipe sections and string rigs drawn from
the engine's own parameter tables (strategies.TABLES: PipeSection.parameters, StringRig.parameters; no parameter is
listed here), valid and mutated (one keyword any number, or a value of another kind), each input counted in the
outcome table (tests/python/outcomes.py) under "pipe sections" or "string rigs":

* a refused input is an InvalidParameterError naming a keyword the caller gave (or a TypeError naming it for a value
  of the wrong kind), and only an input outside a rule is refused;
* an accepted one builds what was asked (every property reads back its keyword) and runs: a short run completes
  finite with dissipative wall friction and dampers, or stops as a SimulationError with its time;
* never a crash, a hang (each run has a wall-time limit), NaN as success, another kind of error.

Bounded: 40 examples per test, derandomized, runs of 0.2 s on 2-4 elements (the file takes ~20 s).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import frictionsim as fs
from frictionsim import drillstring as ds
from outcomes import record
from strategies import TABLES, table_kwargs, valid

PROFILE = settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])

SECTIONS, RIGS = "pipe sections", "string rigs"
T_END = 0.2
#: a wall-time limit per run: past it the input counts as a hang
RUN_LIMIT = 20.0
#: values of another kind than a number
OTHER_KINDS = st.one_of(st.text(max_size=6), st.none(), st.booleans(), st.lists(st.floats(), max_size=2),
                        st.just(b"1"), st.just(1j))


def _rule_holds(cls, kwargs) -> bool:
    """Each keyword within its table's rule, and the table's bounds between keywords (at_least)."""
    rules = TABLES[cls]
    return (all(valid(rules[k], v) for k, v in kwargs.items())
            and all(kwargs[p.name] >= kwargs[p.at_least] for p in cls.parameters if p.at_least))


def _outcome_of_refusal(input_class, error, names, rule_holds) -> None:
    """An InvalidParameterError must name a keyword the caller gave; one refusing an input inside every rule must
    be a rule beyond the table's (the doubles' range of a product, ID < OD, mud below steel), said in its words."""
    if error.parameter not in names:
        record(input_class, "wrong kind of error")
        pytest.fail(f"refused naming {error.parameter!r}, not a keyword given ({sorted(names)}): {error}")
    if rule_holds and not any(w in str(error) for w in ("double", "wall", "steel", "below")):
        record(input_class, "wrong kind of error")
        pytest.fail(f"an input inside every rule refused: {error}")
    record(input_class, "clean rejection")


def _run(input_class, rig) -> None:
    """A short run: finite and dissipative, or a SimulationError with its time; anything else is counted and
    fails."""
    try:
        result = fs.simulate(rig, T_END, rtol=1e-6, timeout=RUN_LIMIT)
    except fs.BudgetExceededError as error:
        if error.budget == "timeout":
            record(input_class, "hang")
            pytest.fail(f"{T_END} s of a {rig.elements}-element string took more than {RUN_LIMIT} s")
        record(input_class, "clean rejection")
        return
    except fs.SimulationError as error:
        assert math.isfinite(error.time_reached)
        record(input_class, "clean rejection")
        return
    except fs.InvalidParameterError as error:  # a rule of the run (the work limit): named
        assert error.parameter in ("t_end", "elements"), error
        record(input_class, "clean rejection")
        return
    if not (result.completed and np.all(np.isfinite(result.states)) and np.all(np.isfinite(result.friction_force))):
        record(input_class, "NaN as success")
        pytest.fail("a completed run with non-finite values")
    scale = 1e-8 * max(1.0, float(np.max(np.abs(result["drive_work"]))))
    if result["wall_friction_work"][-1] < -scale or result["damping_work"][-1] < -scale:
        record(input_class, "silent nonsense")
        pytest.fail("the wall friction or the dampers gave energy to the string")
    if not np.all(np.isfinite(ds.surface_torque(rig, result))):
        record(input_class, "NaN as success")
        pytest.fail("non-finite surface torque")
    record(input_class, "finite result")


def _reads_back(input_class, built, kwargs) -> None:
    for key, value in kwargs.items():
        got = getattr(built, key)
        if not (got == value or (math.isnan(value) and math.isnan(got))):
            record(input_class, "silent nonsense")
            pytest.fail(f"{key} = {value!r} given, {got!r} built")


def _mutate_kind(data, kwargs) -> str:
    name = data.draw(st.sampled_from(sorted(kwargs)))
    kwargs[name] = data.draw(OTHER_KINDS)
    return name


def _refused_kind(input_class, build, name) -> bool:
    """A value of another kind: a TypeError (or InvalidParameterError) naming the keyword."""
    try:
        build()
    except TypeError as error:
        if name not in str(error):
            record(input_class, "wrong kind of error")
            pytest.fail(f"TypeError not naming {name}: {error}")
        record(input_class, "clean rejection")
        return True
    except fs.InvalidParameterError as error:
        assert error.parameter == name, error
        record(input_class, "clean rejection")
        return True
    except Exception as error:  # noqa: BLE001 - counted, then failed
        record(input_class, "wrong kind of error")
        pytest.fail(f"{type(error).__name__} for a {name} of another kind: {error}")
    return False


# ---------------------------------------------------------------------------------------------- pipe sections
def _section_kwargs(data, mutate: bool):
    kwargs = data.draw(table_kwargs(fs.PipeSection, mutate=False))
    kwargs["inner_diameter"] = data.draw(st.floats(0.0, 0.95)) * kwargs["outer_diameter"]  # a tube has a wall
    if mutate:
        name = data.draw(st.sampled_from(sorted(kwargs)))
        kwargs[name] = data.draw(st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                                           st.sampled_from([0.0, -0.0, 5e-324, 1e-300, 1e300, -1.0,
                                                            1.7976931348623157e308])))
    return kwargs


@PROFILE
@given(data=st.data(), mutate=st.booleans(), of_kind=st.booleans())
def test_a_pipe_section_builds_what_was_asked_and_runs_or_is_refused_naming_its_keyword(data, mutate, of_kind):
    kwargs = _section_kwargs(data, mutate and not of_kind)
    if mutate and of_kind:
        name = _mutate_kind(data, kwargs)
        assert _refused_kind(SECTIONS, lambda: fs.PipeSection(**kwargs), name)
        return
    rule_holds = _rule_holds(fs.PipeSection, kwargs) and kwargs["inner_diameter"] < kwargs["outer_diameter"]
    try:
        section = fs.PipeSection(**kwargs)
    except fs.InvalidParameterError as error:
        _outcome_of_refusal(SECTIONS, error, set(kwargs), rule_holds)
        return
    if not rule_holds:
        record(SECTIONS, "silent nonsense")
        pytest.fail(f"a section outside its rules built: {kwargs}")
    _reads_back(SECTIONS, section, kwargs)
    # the section in a string on bottom, in an inclined hole (mud lighter than its steel)
    try:
        rig = fs.StringRig(fs.DrillString([section]), fs.Coulomb(0.2, 0.3), bit=fs.NavarroLopezBit(),
                           weight_on_bit=5e4, elements=3, inclination=1.0, surface_speed=4.0,
                           mud_density=0.15 * section.density)
    except fs.InvalidParameterError as error:  # the section's values, not the rig's normal forces, are to blame
        _outcome_of_refusal(SECTIONS, error, set(kwargs), True)
        return
    _run(SECTIONS, rig)


# ---------------------------------------------------------------------------------------------- string rigs
_STRING = fs.DrillString([fs.PipeSection(length=700.0), fs.PipeSection(length=100.0, outer_diameter=0.1651,
                                                                       inner_diameter=0.0714)])


def _bit(data):
    kind = data.draw(st.sampled_from(["off bottom", "velocity weakening", "drag bit"]))
    if kind == "off bottom":
        return {}
    bit = (fs.NavarroLopezBit(**data.draw(table_kwargs(fs.NavarroLopezBit, mutate=False)))
           if kind == "velocity weakening" else fs.DetournayBit(**data.draw(table_kwargs(fs.DetournayBit, mutate=False))))
    return {"bit": bit, "weight_on_bit": data.draw(st.floats(1e3, 2e5))}


@PROFILE
@given(data=st.data(), mutate=st.booleans(), of_kind=st.booleans())
def test_a_string_rig_builds_what_was_asked_and_runs_or_is_refused_naming_its_keyword(data, mutate, of_kind):
    kwargs = data.draw(table_kwargs(fs.StringRig, mutate=mutate and not of_kind))
    if "mud_density" in kwargs and valid(TABLES[fs.StringRig]["mud_density"], kwargs["mud_density"]):
        kwargs["mud_density"] = min(kwargs["mud_density"], 2500.0)  # mud, not steel (a rule across tables)
    extras = dict(_bit(data), elements=data.draw(st.integers(2, 4)), axial=data.draw(st.booleans()))
    if kwargs.get("control_period", 0.0) > 0.0 and data.draw(st.booleans()):
        kwargs["control_period"] = 0.0  # the sampled PI's events are many at a typical T_c: keep half the runs free
    build = lambda: fs.StringRig(_STRING, fs.Coulomb(0.2, 0.3), **kwargs, **extras)  # noqa: E731
    if mutate and of_kind:
        name = _mutate_kind(data, kwargs)
        assert _refused_kind(RIGS, build, name)
        return
    rule_holds = _rule_holds(fs.StringRig, kwargs) and kwargs["mud_density"] < 7850.0
    try:
        rig = build()
    except fs.InvalidParameterError as error:
        _outcome_of_refusal(RIGS, error, set(kwargs) | set(extras), rule_holds)
        return
    if not rule_holds:
        record(RIGS, "silent nonsense")
        pytest.fail(f"a rig outside its rules built: {kwargs}")
    _reads_back(RIGS, rig, kwargs)
    assert rig.elements == extras["elements"] and rig.axial == extras["axial"]
    _run(RIGS, rig)
