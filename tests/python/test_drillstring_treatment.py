"""The scenario type "drillstring" under its contact treatments (issue 22 item 2): "captured" and "mixed" build a
fs.TorsionalString (Moreau-Jean, the walls' switches captured) from the scenario's keys and run it with a fixed
step, bit for bit what fs.simulate gives the same string built by hand; a key or setting the chosen treatment
cannot honour is refused at its dotted path, naming the treatment; the packaged Well B example runs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import drillstring as ds
from frictionsim import scenario

pytestmark = pytest.mark.skipif(not fs.HAS_EIGEN, reason="TorsionalString needs the engine built with Eigen")

EXAMPLE = Path(__file__).resolve().parent.parent.parent / "examples" / "scenarios" / "well_b_captured.toml"

CAPTURED = """
[rig]
type = "drillstring"
treatment = "captured"
sections = [{ length = 900.0 }, { length = 100.0, outer_diameter = 0.1651, inner_diameter = 0.0714 }]
elements = 60
inclination = 1.0
mud_density = 1200.0
surface_speed = 4.0
top_drive_inertia = 300.0
proportional_gain = 3e3
integral_gain = 1e3
damping_rate = 0.05
[friction]
type = "coulomb"
mu = 0.2
mu_static = 0.3
[solver]
t_end = 20.0
step = 2e-3
output_step = 0.02
"""

SECTIONS = [fs.PipeSection(length=900.0), fs.PipeSection(length=100.0, outer_diameter=0.1651, inner_diameter=0.0714)]
BY_HAND = dict(elements=60, inclination=1.0, mud_density=1200.0, speed_setpoint=4.0, top_drive_inertia=300.0,
               proportional_gain=3e3, integral_gain=1e3, damping_rate=0.05, friction_coefficient=0.3,
               kinetic_ratio=0.2 / 0.3, setpoint_time_constant=0.0)  # what the scenario leaves out: StringRig's


def _by_hand_limit(treatment: str) -> dict:
    """StringRig's default torque limit (60 kN m) is not given to the time-stepped treatments: none by hand."""
    return {}


def _with(text: str, old: str, new: str) -> str:
    assert old in text
    return text.replace(old, new, 1)


def _bit_speed_by_hand(treatment: str, **extra):
    string = fs.TorsionalString(fs.DrillString(SECTIONS), treatment=treatment,
                                **{**BY_HAND, **_by_hand_limit(treatment), **extra})
    times = np.linspace(0.0, 20.0, 1001)  # output_step = 0.02 s
    return string, fs.simulate(string, 20.0, method="moreau_jean", step=2e-3, output_times=times)


def test_a_captured_case_is_the_torsional_string_built_by_hand():
    run = scenario.run_case(scenario.loads(CAPTURED).cases[0])
    string, result = _bit_speed_by_hand("captured")
    assert isinstance(run.rig, fs.TorsionalString) and run.rig.treatment == "captured"
    assert run.rig.friction_coefficient == 0.3 and run.rig.kinetic_ratio == pytest.approx(2.0 / 3.0)
    np.testing.assert_array_equal(run.result.t, result.t)
    np.testing.assert_array_equal(run.result["bit_speed"], result["bit_speed"])
    np.testing.assert_array_equal(ds.surface_torque(run.rig, run.result), result["motor_torque"])
    # the physics of the run: once the string turns steadily at the set speed, the motor holds every wall contact
    # slipping (f_rat times A&S eq 27's break-off torque) and the viscous damping k_t J omega of every node (eq 3)
    assert np.all(np.abs(result["bit_speed"][-50:] / 4.0 - 1.0) < 0.05)  # the bit rings lightly about w_set
    steady = string.kinetic_ratio * string.breakoff_torque + string.damping_rate * np.sum(string.node_inertia) * 4.0
    assert np.mean(result["motor_torque"][-50:]) == pytest.approx(steady, rel=5e-3)


def test_a_mixed_case_with_the_bit_on_bottom_is_the_torsional_string_built_by_hand():
    text = _with(CAPTURED, 'treatment = "captured"', 'treatment = "mixed"\nweight_on_bit = 2e4\n'
                                                    'bit = { stick_band = 0.1 }')
    run = scenario.run_case(scenario.loads(text).cases[0])
    _, result = _bit_speed_by_hand("mixed", weight_on_bit=2e4, bit=fs.NavarroLopezBit(stick_band=0.1))
    np.testing.assert_array_equal(run.result["bit_speed"], result["bit_speed"])
    summary = run.summary()
    assert summary["treatment"] == "mixed" and summary["weight_on_bit_N"] == 2e4
    measures = ds.stick_slip(run.rig, result, 10.0)  # after the default transient, t_end / 2
    assert summary["peak_ratio"] == measures.peak_ratio and summary["bit_stuck_fraction"] == measures.stuck_fraction


@pytest.mark.parametrize("old, new, key, words", [
    ('treatment = "captured"', 'treatment = "implicit"', "rig.treatment", "exact, captured, mixed"),
    ("elements = 60", "elements = 60\nend_mass = 1e3", "rig.end_mass", "treatment 'captured' cannot"),
    ("elements = 60", "elements = 60\ninitial_speed = 1.0", "rig.initial_speed", "treatment 'captured' cannot"),
    ('treatment = "captured"', 'treatment = "exact"\nstick_band_speed = 1.5', "rig.stick_band_speed",
     "treatment 'exact' cannot"),
    ('type = "coulomb"\nmu = 0.2\nmu_static = 0.3', 'type = "dahl"\nmu = 0.2\ntangential_stiffness = 1e4',
     "friction.type", "coulomb under treatment captured"),
    ("step = 2e-3", 'step = 2e-3\nmethod = "dormand_prince"', "solver.method", "treatment 'captured'"),
    ("output_step = 0.02", 'output_step = 0.02\n[analysis]\nsurface_speeds = [2.0]\nweights_on_bit = [1e4]',
     "analysis.surface_speeds", "treatment 'captured'"),
])
def test_what_the_treatment_cannot_take_is_refused_at_its_key(old, new, key, words):
    with pytest.raises(scenario.ScenarioError) as error:
        scenario.loads(_with(CAPTURED, old, new), source="s.toml")
    assert error.value.file == "s.toml" and error.value.key == key
    assert words in error.value.rule
    assert str(error.value).startswith(f"s.toml: {key}: ")


def test_a_step_needs_a_time_stepped_treatment():
    text = _with(_with(CAPTURED, 'treatment = "captured"', 'treatment = "exact"'), "damping_rate = 0.05\n", "")
    with pytest.raises(scenario.ScenarioError) as error:
        scenario.loads(text, source="s.toml")
    assert error.value.key == "solver.step" and "treatment exact" in error.value.rule


def test_the_well_b_example_runs_and_sticks_and_slips(tmp_path):
    text = _with(_with(EXAMPLE.read_text(), "t_end = 40.0", "t_end = 20.0"), "transient = 15.0", "transient = 8.0")
    case = scenario.loads(text, source=EXAMPLE).cases[0]
    assert case.rig.params["elements"] == 500 and case.rig.params["treatment"] == "captured"
    run = scenario.run(scenario.loads(text, source=EXAMPLE))
    well_b = fs.aarsnes_shor_well_b(measured_depth=2500.0, elements=500)
    rig = run.runs[0].rig
    # the scenario's keys give the preset's string: the same walls (A&S eq 27) and the same stick-slip estimate
    assert rig.breakoff_torque == pytest.approx(well_b.breakoff_torque, rel=1e-6)
    assert rig.period_estimate == pytest.approx(well_b.period_estimate, rel=1e-6)
    summary = run.summary().iloc[0]
    assert summary["bit_sticks"] and 0.0 < summary["bit_stuck_fraction"] < 1.0 and summary["peak_ratio"] > 1.5
    written = run.write(tmp_path)
    names = {path.name for path in written}
    assert {"summary.csv", "bit_speed.png", "metadata.json"} <= names
    frame = run.runs[0].timeseries()
    assert {"bit_speed", "top_drive_speed", "motor_torque"} <= set(frame.columns)


# ---- one string model, three treatments (issue 22 item 1)

WELL = dict(elements=16, inclination=1.0, surface_speed=4.0, top_drive_inertia=300.0, proportional_gain=3e3,
            integral_gain=1e3, damping_time=2e-3)


@pytest.mark.parametrize("contacts, on_bottom, chosen", [
    (10, True, "exact"), (10, False, "exact"), (30, True, "exact"), (31, True, "mixed"), (100, True, "mixed"),
    (100, False, "captured"), (300, True, "mixed"), (301, True, "captured"), (1000, True, "captured"),
])
def test_the_automatic_treatment_follows_the_measured_rule(contacts, on_bottom, chosen):
    # bench/mixed.bench.cpp: exact cheapest at 10 contacts, mixed at 100 (bit on bottom), captured at 1000
    assert ds.automatic_treatment(contacts, on_bottom) == chosen


def test_string_treatment_auto_picks_each_treatment_where_it_should():
    bit = fs.NavarroLopezBit()
    assert ds.string_treatment("auto", elements=20) == "exact"
    assert ds.string_treatment("auto", elements=101, bit=bit, weight_on_bit=5e4) == "mixed"  # 100 walls + the bit
    assert ds.string_treatment("auto", elements=100) == "captured"  # off bottom mixed is captured
    assert ds.string_treatment("auto", elements=1000, bit=bit, weight_on_bit=5e4) == "captured"
    # a keyword only one engine takes chooses it
    assert ds.string_treatment("auto", elements=1000, axial=True) == "exact"
    assert ds.string_treatment("auto", elements=10, stick_band_speed=1.5) == "captured"
    assert ds.string_treatment("auto", elements=10, stick_band_speed=1.5, bit=bit, weight_on_bit=5e4) == "mixed"
    assert ds.string_treatment("captured", elements=10) == "captured"
    with pytest.raises(fs.InvalidParameterError) as error:
        ds.string_treatment("implicit")
    assert error.value.parameter == "treatment"


def test_one_string_model_builds_each_treatment_and_counts_stuck_walls_alike():
    """The same string (StringRig keywords, a Coulomb wall law) built exact and captured: the physics carried over
    (damping_time, the PI, the walls' coefficients), and both Results' mode column counts the wall contacts at rest
    (all stuck at rest, none once the string slides at the set speed). Their agreement as h shrinks is
    tests/mixed_treatment.test.cpp's [treatments] case (a well vertical at the top: StringRig has no wall at node 0,
    the top drive's, where a straight inclined well gives the captured string half an element's)."""
    string, walls = fs.DrillString([fs.PipeSection(length=1000.0)]), fs.Coulomb(0.18, 0.3)
    exact = ds.string_model(string, walls, treatment="exact", **WELL)
    captured = ds.string_model(string, walls, treatment="captured", **WELL)
    assert isinstance(exact, fs.StringRig) and isinstance(captured, fs.TorsionalString)
    assert ds.string_model(string, walls, **WELL).__class__ is fs.StringRig  # auto: 16 contacts -> exact
    assert captured.damping_time == exact.damping_time == 2e-3
    assert captured.speed_setpoint == exact.surface_speed == 4.0
    assert captured.friction_coefficient == 0.3 and captured.kinetic_ratio == pytest.approx(0.6)
    assert list(exact.contact_nodes) == list(range(1, 17))
    assert list(captured.contact_nodes) == list(range(0, 17))  # node 0's half element inclined too
    times = np.linspace(0.0, 10.0, 501)
    for model, options in ((exact, dict(rtol=1e-8, atol=1e-8)), (captured, dict(method="moreau_jean", step=1e-3))):
        run = fs.simulate(model, 10.0, output_times=times, **options)
        stuck = ds.stuck_contacts(run)
        assert stuck[0] == ds.wall_contacts(model) == len(model.contact_nodes)
        assert stuck[-1] == 0 and np.all((stuck >= 0) & (stuck <= ds.wall_contacts(model)))
    # what the keywords leave out is StringRig's default under every treatment, not the captured engine's own (A&S
    # Well B's drive, a 60 degree hole, a 1 s ramp, 200 elements): "auto" changes the solver, never the string
    bare_exact = ds.string_model(string, walls, treatment="exact")
    for treatment in ("captured", "mixed"):
        bare = ds.string_model(string, walls, treatment=treatment, bit=fs.NavarroLopezBit(), weight_on_bit=1e4)
        assert bare.elements == ds.DEFAULT_ELEMENTS and not bare.contact_nodes  # a vertical hole: no wall friction
        for key, name in ds.SHARED.items():
            if key in {p.name for p in fs.StringRig.parameters} and name != "torque_limit":
                assert getattr(bare, name) == getattr(bare_exact, key), key
        assert bare.torque_limit == 0.0  # StringRig's default limit left out: an unlimited motor (see string_model)
    assert bare_exact.torque_limit == 6e4
    # a given limit is StringRig's under every treatment: positive (the captured string's own 0 means "none")
    assert ds.string_model(string, walls, treatment="captured", torque_limit=7e3).torque_limit == 7e3
    for treatment in ("exact", "captured", "mixed"):
        with pytest.raises(fs.InvalidParameterError) as error:
            ds.string_model(string, walls, treatment=treatment, torque_limit=0.0)
        assert error.value.parameter == "torque_limit"
    with pytest.raises(fs.InvalidParameterError) as error:
        ds.string_model(string, walls, treatment="captured", end_mass=1e3, **WELL)  # StringRig's axial BHA mass
    assert error.value.parameter == "end_mass"


def test_the_exact_treatment_takes_k_t_and_the_set_point_ramp():
    """damping_rate (A&S's k_t: k_t J_s,i w_i at each node, J_s,i its string inertia) and setpoint_time_constant
    (w_set (1 - exp(-t / T))) are StringRig keywords too: string_model carries them to either treatment. A
    prescribed ramped speed turns the top as the closed form, and once the ramp is over (and the string's torsional
    oscillation damped by its elements' dampers) it holds the string's whole k_t torque, k_t J_string w_set (no
    walls: every node turns at w_set)."""
    string, walls = fs.DrillString([fs.PipeSection(length=1000.0)]), fs.Coulomb(0.18, 0.3)
    keys = dict(WELL, damping_rate=0.05, setpoint_time_constant=1.0)
    exact = ds.string_model(string, walls, treatment="exact", **keys)
    captured = ds.string_model(string, walls, treatment="captured", **keys)
    assert isinstance(exact, fs.StringRig) and isinstance(captured, fs.TorsionalString)
    assert exact.damping_rate == captured.damping_rate == 0.05
    assert exact.setpoint_time_constant == captured.setpoint_time_constant == 1.0
    w_set, T, kt = 3.0, 1.5, 0.1
    rig = fs.StringRig(string, walls, elements=8, wall_contacts=False, top_drive="prescribed_speed",
                       surface_speed=w_set, setpoint_time_constant=T, damping_rate=kt, damping_time=0.05)
    times = np.linspace(0.0, 30.0, 61)
    result = fs.simulate(rig, 30.0, output_times=times, rtol=1e-10, atol=1e-10)
    assert result.completed
    np.testing.assert_allclose(ds.surface_speed(rig, result), w_set * (1.0 - np.exp(-times / T)), rtol=0, atol=1e-8)
    section = string.sections[0]
    j_string = section.density * np.pi / 32.0 * (section.outer_diameter ** 4 - section.inner_diameter ** 4) * 1000.0
    assert ds.surface_torque(rig, result)[-1] == pytest.approx(kt * j_string * w_set, rel=1e-6)


def test_the_torsional_string_takes_the_one_survey_type():
    """fs.Survey or (measured_depth, inclination): the same well in one vertical plane gives the same bounds bit for
    bit; a survey whose azimuth turns gives the minimum-curvature arc's inclination."""
    md, inc = [0.0, 200.0, 500.0, 1200.0], [0.0, 0.0, 1.0, 1.0]
    string = fs.DrillString([fs.PipeSection(length=1000.0)])
    pair = fs.TorsionalString(string, elements=40, survey=(md, inc))
    survey = fs.TorsionalString(string, elements=40, survey=fs.Survey(md, inc, [0.3] * 4))
    assert np.array_equal(np.asarray(pair.static_friction_torque), np.asarray(survey.static_friction_torque))
    assert isinstance(survey.survey, fs.Survey) and pair.survey == (md, inc)
    turning = fs.TorsionalString(string, elements=40, survey=fs.Survey(md, inc, [0.0, 0.0, 0.0, 1.5]))
    assert not np.array_equal(np.asarray(turning.static_friction_torque), np.asarray(pair.static_friction_torque))
    assert np.asarray(turning.static_friction_torque)[:8].tolist() == np.asarray(pair.static_friction_torque)[:8].tolist()
    with pytest.raises(fs.InvalidParameterError) as error:
        fs.TorsionalString(string, elements=40, survey=([0.0, 300.0, 200.0], [0.0, 0.5, 0.5]))
    assert "survey" in error.value.parameter


def test_a_scenario_with_treatment_auto_resolves_by_the_rule():
    auto = _with(CAPTURED, 'treatment = "captured"', 'treatment = "auto"')
    large = scenario.loads(_with(auto, "elements = 60", "elements = 400"))
    assert large.cases[0].rig.params["treatment"] == "captured"
    small = scenario.loads(_with(_with(_with(auto, "damping_rate = 0.05\n", ""), "step = 2e-3\n", ""),
                                 "elements = 60", "elements = 20"))
    assert small.cases[0].rig.params["treatment"] == "exact"
    run = scenario.run_case(small.cases[0])
    assert isinstance(run.rig, fs.StringRig) and len(run.rig.contact_nodes) == 20
    # stick_band_speed, a key only the captured string takes, chooses it at 20 contacts too (damping_rate, k_t, is
    # the exact StringRig's too)
    keyed = scenario.loads(_with(_with(auto, "elements = 60", "elements = 20"), "damping_rate = 0.05",
                                 "damping_rate = 0.05\nstick_band_speed = 1.5"))
    assert keyed.cases[0].rig.params["treatment"] == "captured"
