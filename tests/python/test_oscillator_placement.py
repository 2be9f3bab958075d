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
