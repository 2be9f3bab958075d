"""Axial vibration tools along a real well from Python (issue 14, items 3-4): fs.HydraulicOscillator,
SoftString.oscillators (zone of influence, hook load change) and SoftString.sliding_weight_on_bit (the placement
objective), and frictionsim.wells.place_oscillators (scipy.optimize over the C++ objective). The C++ closed forms
are in tests/oscillator_drag.test.cpp; here: the friction vector's cycle mean at each element, the inverse of the
sliding run, what an optimiser's answer must satisfy, and the errors."""

import math
import pickle

import matplotlib

matplotlib.use("Agg")
import numpy as np
import pytest

import frictionsim as fs
from frictionsim import wells

SURVEYS = __import__("pathlib").Path(__file__).resolve().parents[2] / "examples" / "surveys"
MU = dict(open_hole_friction=0.2, cased_hole_friction=0.2)


@pytest.fixture(scope="module")
def model():
    survey = wells.read_survey(SURVEYS / "horizontal_3km.csv")
    string = fs.DrillString([fs.PipeSection(length=4700.0),
                             fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
    return wells.soft_string(survey, string)


@pytest.fixture(scope="module")
def hook_load(model):
    """The hook load at which the plain string slides with 20 kN on the bit."""
    return model.run("sliding_drilling", weight_on_bit=20e3, **MU).hook_load


def test_without_tools_the_objective_inverts_the_sliding_run(model, hook_load):
    assert model.sliding_weight_on_bit(hook_load, [], **MU) == pytest.approx(20e3, rel=1e-8)


def test_a_tool_without_force_changes_nothing(model):
    silent = fs.HydraulicOscillator(measured_depth=3000.0, force_amplitude=0.0)
    r = model.oscillators("sliding_drilling", silent, weight_on_bit=20e3, **MU)
    assert r.vibrated.hook_load == r.plain.hook_load
    assert r.zone_length == 0.0 and not np.any(r.reduction)


def test_the_friction_factor_is_the_friction_vectors_cycle_mean(model):
    """Sliding without rotation, each element's axial factor is (2/pi) asin(V/a) where the vibration amplitude a
    exceeds the sliding speed V (paper 000's friction vector averaged over a cycle), else 1."""
    rop = 30.0 / 3600.0
    tool = fs.HydraulicOscillator(measured_depth=4000.0, force_amplitude=60e3)
    r = model.oscillators("sliding_drilling", [tool], weight_on_bit=20e3, rate_of_penetration=rop, **MU)
    a = np.asarray(r.vibration_amplitude)
    expected = np.where(a > rop, 2.0 / np.pi * np.arcsin(np.minimum(rop / np.maximum(a, 1e-300), 1.0)), 1.0)
    np.testing.assert_allclose(r.axial_factor, expected, rtol=1e-12, atol=1e-12)
    assert r.zone_top <= tool.measured_depth <= r.zone_bottom  # the zone is around the tool
    assert r.hook_load_change > 0.0  # less drag against running in: the string hangs heavier at the hook
    assert r.surface_torque_change == 0.0  # no rotation while sliding


def test_one_tool_placement_is_the_best_of_its_curve(model, hook_load):
    p = wells.place_oscillators(model, hook_load, force_amplitude=60e3, scan_points=40, **MU)
    assert p.weight_on_bit >= p.scan_weight_on_bit.max() - 1e-9 * p.weight_on_bit
    tool = fs.HydraulicOscillator(measured_depth=p.depths[0], force_amplitude=60e3)
    assert model.sliding_weight_on_bit(hook_load, [tool], **MU) == pytest.approx(p.weight_on_bit, rel=1e-9)
    assert p.weight_on_bit_without == pytest.approx(20e3, rel=1e-8)
    assert p.gain > 0.0
    ax = wells.plot_placement(p)
    assert ax.get_xlabel().startswith("tool measured depth")


def test_two_tools_transfer_at_least_what_one_does(model, hook_load):
    one = wells.place_oscillators(model, hook_load, force_amplitude=60e3, scan_points=30, **MU)
    two = wells.place_oscillators(model, hook_load, tools=2, force_amplitude=60e3, scan_points=30, **MU)
    assert len(two.depths) == 2 and two.depths[0] <= two.depths[1]
    assert two.weight_on_bit >= one.weight_on_bit * (1 - 1e-9)


def test_tools_and_settings_are_checked(model, hook_load):
    tool = fs.HydraulicOscillator(measured_depth=4000.0)
    with pytest.raises(ValueError, match="force_amplitude"):
        fs.HydraulicOscillator(measured_depth=100.0, force_amplitude=-1.0)
    with pytest.raises(ValueError, match="measured_depth"):
        model.oscillators("sliding_drilling", fs.HydraulicOscillator(measured_depth=1e5), **MU)
    with pytest.raises(ValueError, match="model"):
        model.oscillators("sliding_drilling", tool, model="coulomb")
    with pytest.raises(ValueError, match="lubricant"):
        model.oscillators("sliding_drilling", tool, model="table5", lubricant="honey")
    with pytest.raises(ValueError, match="bit_reflection"):
        model.oscillators("sliding_drilling", tool, bit_reflection=2.0)
    with pytest.raises(TypeError, match="frequancy"):
        model.oscillators("sliding_drilling", tool, frequancy=18.0)
    with pytest.raises(TypeError, match="tools"):
        model.oscillators("sliding_drilling", "a tool")
    with pytest.raises(ValueError, match="tools"):
        wells.place_oscillators(model, hook_load, tools=3)
    with pytest.raises(ValueError, match="bounds"):
        wells.place_oscillators(model, hook_load, bounds=(4000.0, 100.0))


def test_a_tool_pickles_and_reprs():
    tool = fs.HydraulicOscillator(measured_depth=2500.0, force_amplitude=40e3, frequency=16.0)
    back = pickle.loads(pickle.dumps(tool))
    assert (back.measured_depth, back.force_amplitude, back.frequency) == (2500.0, 40e3, 16.0)
    again = eval(repr(tool), {"HydraulicOscillator": fs.HydraulicOscillator})
    assert again.frequency == 16.0 and math.isclose(again.force_amplitude, 40e3)


# ---- the dynamic route: the axial string model run to a periodic steady state (oscillator_response.hpp)
SHORT = 700.0  # m: a short horizontal string keeps each dynamic run well under a second


@pytest.fixture(scope="module")
def short():
    survey = fs.Survey([0.0, SHORT], [math.pi / 2, math.pi / 2], [0.0, 0.0])
    return fs.SoftString(survey, fs.DrillString([fs.PipeSection(length=SHORT)]), 700)


def _impedance(section):
    return section.area * math.sqrt(section.youngs_modulus * section.density)


def test_dynamic_vibration_agrees_with_the_wave_near_the_tool(short):
    """Sliding at 30 m/h, mu 0.3, a tool mid-string whose estimate reaches 300 m each way: the dynamic run's first
    harmonic at the tool is F / (2 Z) (the two half-strings' impedances in parallel), within 60 m of the tool it is
    the estimate's to 10 %, the friction it produces there is the friction vector's cycle mean of its own first
    harmonic (to 0.035), and the drag saved is the estimate's to 20 % (measured: +9 %; the run's zone is longer:
    684 m against 594 m, the string beyond the reach sticks and slips forward)."""
    pipe = fs.PipeSection(length=SHORT)
    mu, rop = 0.3, 30.0 / 3600.0
    w = 9.80665 * pipe.area * (pipe.density - 1200.0)
    force = 4.0 * mu * w * 300.0 / math.pi
    tool = fs.HydraulicOscillator(measured_depth=SHORT / 2, force_amplitude=force, frequency=18.0)
    given = dict(open_hole_friction=mu, cased_hole_friction=mu, rate_of_penetration=rop, weight_on_bit=5e3)
    wave = short.oscillators("sliding_drilling", tool, **given)
    dynamic = short.oscillators("sliding_drilling", tool, vibration="dynamic", **given)
    assert wave.source == "wave" and not wave.responses
    assert dynamic.source == "dynamic" and len(dynamic.responses) == 1
    r = dynamic.responses[0]
    assert r.settled and r.events > 0
    a0 = force / (2.0 * _impedance(pipe))
    assert r.first_harmonic[r.excitation_node] == pytest.approx(a0, rel=0.05)
    x = np.asarray(r.measured_depth)
    near = np.abs(x - SHORT / 2) <= 60.0
    h = np.asarray(r.first_harmonic)[near]
    estimate = np.interp(x[near], np.asarray(short.node_depths[:-1]) + 0.5, wave.vibration_amplitude)
    np.testing.assert_allclose(h, estimate, rtol=0.1)
    np.testing.assert_allclose(np.asarray(r.friction_factor)[near], 2 / np.pi * np.arcsin(rop / h), atol=0.035)
    assert dynamic.zone_top < SHORT / 2 - 100.0 and dynamic.zone_bottom > SHORT / 2 + 100.0
    assert dynamic.hook_load_change == pytest.approx(wave.hook_load_change, rel=0.2)
    # the same run on its own
    alone = short.oscillator_response("sliding_drilling", tool, **given)
    np.testing.assert_allclose(alone.first_harmonic, r.first_harmonic, rtol=0, atol=1e-12)


def test_dynamic_vibration_without_force_is_the_plain_run(short):
    silent = fs.HydraulicOscillator(measured_depth=300.0, force_amplitude=0.0)
    r = short.oscillators("sliding_drilling", silent, vibration="dynamic", weight_on_bit=5e3)
    np.testing.assert_array_equal(r.vibrated.tension, r.plain.tension)
    assert r.zone_length == 0.0 and not r.responses


def test_frequency_scan_finds_the_free_bits_first_resonance():
    """A frictionless 500 m string hanging vertically, the hook held and the bit free: a tool at the bit drives the
    fixed-free rod, whose first resonance is c / (4 L). The scan's largest first harmonic at the tool is there (to
    the scan's 2 % step)."""
    length = 500.0
    pipe = fs.PipeSection(length=length)
    model = fs.SoftString(fs.Survey([0.0, length], [0.0, 0.0], [0.0, 0.0]), fs.DrillString([pipe]), 50)
    c = math.sqrt(pipe.youngs_modulus / pipe.density)
    f1 = c / (4.0 * length)
    tool = fs.HydraulicOscillator(measured_depth=length, force_amplitude=5e3, frequency=f1)
    freqs = f1 * (1.0 + 0.02 * np.arange(-4, 5))
    scan = wells.frequency_scan(model, tool, freqs, open_hole_friction=0.0, cased_hole_friction=0.0,
                                rate_of_penetration=0.0, damping_time=3e-3, elements_per_wavelength=100,
                                steady_tolerance=0.005, max_time=120.0)
    assert scan.vibration == "dynamic" and len(scan.responses) == len(freqs)
    assert all(r.settled for r in scan.responses)
    assert freqs[int(np.argmax(scan.tool_amplitude))] == pytest.approx(f1, rel=1e-9)
    assert np.all(scan.hook_load_change == 0.0)  # no friction: no drag to save


def test_dynamic_settings_are_checked(short):
    tool = fs.HydraulicOscillator(measured_depth=300.0, force_amplitude=10e3)
    with pytest.raises(fs.InvalidParameterError, match="vibration") as e:
        short.oscillators("sliding_drilling", tool, vibration="standing")
    assert e.value.parameter == "vibration"
    with pytest.raises(ValueError, match="vibration"):
        short.oscillators("rotary_drilling", tool, vibration="dynamic")
    with pytest.raises(ValueError, match="cycles"):
        short.oscillators("sliding_drilling", tool, vibration="dynamic", cycles=0.0)
    with pytest.raises(ValueError, match="elements_per_wavelength"):
        short.oscillator_response("sliding_drilling", tool, elements_per_wavelength=1.0)
    with pytest.raises(TypeError, match="transient"):
        short.oscillators("sliding_drilling", tool, vibration="dynamic", transient="long")
    with pytest.raises(ValueError, match="frequencies"):
        wells.frequency_scan(short, tool, [])
    with pytest.raises(ValueError, match="vibration"):
        wells.frequency_scan(short, tool, [18.0], vibration="both")
