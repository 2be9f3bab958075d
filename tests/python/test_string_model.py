"""One string model, one class (issue 22 item 1): fs.TorsionalString takes treatment="captured" | "mixed" | "exact"
| "auto" (C++ string/string_model.hpp's StringModel) and its Result has the same columns under every treatment.
The exact treatment runs the event-driven StringRig of the same string; the captured one converges to it as the
step shrinks, column by column; "auto" follows the measured rule; what a treatment cannot take is refused by name."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import frictionsim as fs

pytestmark = pytest.mark.skipif(not fs.HAS_EIGEN, reason="TorsionalString needs the engine built with Eigen")

#: 1000 m of 5" pipe, vertical to 200 m and building to 60 degrees at 500 m (no wall at the top drive's node, which
#: the exact engine cannot carry), walls mu_s 0.3 with f_rat 0.6, the PI stepped to 4 rad/s.
SURVEY = fs.Survey([0.0, 200.0, 500.0, 1000.0], [0.0, 0.0, np.pi / 3.0, np.pi / 3.0], [0.0, 0.0, 0.0, 0.0])
KEYS = dict(top_drive_inertia=300.0, proportional_gain=3e3, integral_gain=1e3, speed_setpoint=4.0,
            setpoint_time_constant=0.0, friction_coefficient=0.3, kinetic_ratio=0.6, bha_inertia=40.0,
            damping_time=2e-3, gravity=9.80665, mud_density=1200.0)
COLUMNS = ["bit_speed", "top_drive_speed", "motor_torque", "stuck_fraction"]


def _string(treatment: str, elements: int = 12, **extra) -> "fs.TorsionalString":
    return fs.TorsionalString(fs.DrillString([fs.PipeSection(length=1000.0)]), elements=elements,
                              treatment=treatment, **{"survey": SURVEY, **KEYS, **extra})


def _rms(a, b) -> float:
    return float(np.sqrt(np.mean((np.asarray(a) - np.asarray(b)) ** 2)))


def test_every_treatment_gives_the_same_columns_and_captured_converges_to_exact():
    """The break-off transient: the walls start stuck, break off and slide. Exact (every release located,
    Dormand-Prince 1e-10) against captured at h = 2 -> 0.25 ms: every column's RMS difference falls with h."""
    times = np.linspace(0.0, 20.0, 2001)
    exact = _string("exact")
    ref = fs.simulate(exact, 20.0, output_times=times, rtol=1e-10, atol=1e-10)
    assert ref.completed and ref.state_names == COLUMNS
    assert ref.mode[0] == exact.contact_count and ref.mode[-1] == 0  # all stuck, then all sliding
    assert len(ref.events) >= exact.contact_count  # every wall's release located
    errors = {name: [] for name in COLUMNS[:3] + ["friction_force"]}
    for h in (2e-3, 1e-3, 5e-4, 2.5e-4):
        run = fs.simulate(_string("captured"), 20.0, method="moreau_jean", step=h, output_times=times)
        assert run.state_names == ref.state_names
        for name in errors:
            errors[name].append(_rms(run[name], ref[name]))
    for name, e in errors.items():
        assert e[-1] < 0.25 * e[0], (name, e)  # at least first order over an 8x smaller step
    assert errors["bit_speed"][-1] < 1e-2  # rad/s, against a peak near 8


def test_the_exact_treatment_holds_its_physics_in_the_string_columns():
    """Under exact the motor torque is the PI's k_p e + k_i int e and node N's contact torque is its kinetic wall
    level against the speed once sliding; the steady state holds every wall's kinetic level (f_rat eq 27)."""
    string = _string("exact", damping_rate=0.0)
    times = np.linspace(0.0, 60.0, 601)
    run = fs.simulate(string, 60.0, output_times=times, rtol=1e-9, atol=1e-9)
    sliding = run["bit_speed"] > 0.0
    assert sliding[-1]
    np.testing.assert_allclose(run.friction_force[sliding],
                               -string.kinetic_ratio * string.static_friction_torque[-1], rtol=1e-12)
    assert run["motor_torque"][-1] == pytest.approx(string.kinetic_ratio * string.breakoff_torque, rel=1e-3)
    assert np.all(run["stuck_fraction"][-10:] == 0.0)


def test_auto_follows_the_measured_rule_and_survives_repr_and_pickle():
    assert _string("auto", elements=12).treatment == "exact"  # 12 wall contacts
    assert _string("auto", elements=100).treatment == "captured"  # off bottom beyond 30
    assert _string("auto", elements=100, weight_on_bit=6e4).treatment == "mixed"
    assert _string("auto", elements=400, weight_on_bit=6e4).treatment == "captured"
    # an fs.Survey's repr is the constructor call that rebuilds it bit for bit, so the string's repr rebuilds it too
    survey = eval(repr(SURVEY), vars(fs))
    for name in ("measured_depth", "inclination", "azimuth"):
        np.testing.assert_array_equal(getattr(survey, name), getattr(SURVEY, name))
    for treatment in ("exact", "captured", "mixed"):
        string = _string(treatment, weight_on_bit=6e4 if treatment == "mixed" else 0.0)
        assert string.treatment == treatment
        for copy in (pickle.loads(pickle.dumps(string)), eval(repr(string), vars(fs))):
            assert copy.treatment == treatment and repr(copy) == repr(string)


def test_a_stop_condition_on_the_bit_speed_reads_node_n_under_exact():
    run = fs.simulate(_string("exact"), 20.0, rtol=1e-10, atol=1e-10,
                      events=[fs.StopCondition(state="bit_speed", level=2.0, direction=1)])
    assert run.status == 1 and len(run.stop_events) == 1
    assert run["bit_speed"][-1] == pytest.approx(2.0, abs=1e-7)


@pytest.mark.parametrize("make, parameter", [
    (lambda: fs.simulate(_string("exact"), 1.0, method="moreau_jean"), "method"),
    (lambda: fs.simulate(_string("exact"), 1.0, step=1e-3), "step"),
    (lambda: _string("exact", stick_band_speed=1.5), "stick_band_speed"),
    (lambda: _string("exact", bit_torque=1e3), "bit_torque"),
    (lambda: fs.TorsionalString(fs.DrillString([fs.PipeSection(length=500.0)]), elements=5, inclination=0.5,
                                treatment="exact"), "static_friction_torque[0]"),  # a wall at the top drive's node
    (lambda: _string("mixed"), "treatment"),  # off bottom
    (lambda: _string("mixed", weight_on_bit=6e4, torque_limit=2e4), "torque_limit"),
    (lambda: _string("implicit"), "treatment"),
    (lambda: fs.simulate(_string("exact"), 5.0, events=[fs.StopCondition(state="motor_torque", level=1.0)]),
     "stop_conditions.state"),
])
def test_what_a_treatment_cannot_take_is_refused_by_name(make, parameter):
    with pytest.raises(fs.InvalidParameterError) as error:
        make()
    assert error.value.parameter == parameter, error.value


@settings(max_examples=25, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(treatment=st.sampled_from(["captured", "mixed", "exact", "auto"]), elements=st.integers(1, 60),
       weight=st.sampled_from([0.0, 3e4]), inclination=st.floats(0.0, 1.5), limit=st.sampled_from([0.0, 2e4]))
def test_any_treatment_builds_or_is_refused_naming_a_parameter(treatment, elements, weight, inclination, limit):
    """Every combination either builds a string whose treatment is one of the three (auto resolved) and whose short
    run has the four columns, finite, or raises InvalidParameterError naming a parameter."""
    try:
        string = fs.TorsionalString(fs.DrillString([fs.PipeSection(length=300.0)]), elements=elements,
                                    inclination=inclination, weight_on_bit=weight, torque_limit=limit,
                                    treatment=treatment)
    except fs.InvalidParameterError as error:
        assert error.parameter in {"treatment", "torque_limit", "static_friction_torque[0]"}, error
        return
    assert string.treatment in {"captured", "mixed", "exact"}
    options = dict(rtol=1e-6, atol=1e-6) if string.treatment == "exact" else dict(step=1e-3)
    run = fs.simulate(string, 0.2, output_times=np.linspace(0.0, 0.2, 11), **options)
    assert run.state_names == COLUMNS and np.all(np.isfinite(run.states))
