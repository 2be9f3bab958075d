"""The captured string's drive from Python (issue 22 items 1 and 3): fs.TorsionalString's torque limit with
anti-windup (``torque_limit``) and prescribed top-drive speed (``top_drive="prescribed_speed"``), StringRig's drive
physics, and moreau_jean's contact solver chosen by name (``contact_solver=``).

Each figure is checked against a closed form written out here (the rigid string's uniform acceleration at the limit,
the sliding string's steady torque), or against the default solver's run where the law makes the step unique.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import frictionsim as fs
from frictionsim import drillstring as ds

pytestmark = pytest.mark.skipif(not fs.HAS_EIGEN, reason="TorsionalString needs the engine built with Eigen")

#: tests/captured_drive.test.cpp's field string: 1000 m of 5" pipe, vertical to 200 m, 60 degrees at 500 m.
SURVEY = ([0.0, 200.0, 500.0, 1000.0], [0.0, 0.0, math.pi / 3.0, math.pi / 3.0])
FIELD = dict(top_drive_inertia=300.0, proportional_gain=3e3, integral_gain=1e3, speed_setpoint=4.0,
             setpoint_time_constant=0.0, friction_coefficient=0.3, kinetic_ratio=0.6, bha_inertia=40.0,
             gravity=9.80665, mud_density=1200.0, elements=16, survey=SURVEY)


def field_string(**overrides) -> "fs.TorsionalString":
    return fs.TorsionalString(fs.DrillString([fs.PipeSection(length=1000.0)]), **{**FIELD, **overrides})


def spin_up(torque_limit: float, bit_torque: float = 5e3, t_end: float = 6.0):
    """A 100 m string (4 elements, beta 5 ms) without wall friction under a constant bit torque, the PI's demand
    k_p omega_SP = 3e5 N m far past the limit: the motor holds T_max, the string accelerates as one body."""
    ts = fs.TorsionalString(fs.DrillString([fs.PipeSection(length=100.0)]), elements=4, top_drive_inertia=300.0,
                            proportional_gain=3e3, integral_gain=1e3, speed_setpoint=100.0,
                            setpoint_time_constant=0.0, friction_coefficient=0.0, bit_torque=bit_torque,
                            damping_time=5e-3, torque_limit=torque_limit)
    times = np.round(np.arange(0.0, t_end + 1e-9, 0.01), 10)
    return ts, fs.simulate(ts, t_end, method="moreau_jean", step=1e-3, output_times=times)


def test_at_the_torque_limit_the_rigid_string_accelerates_at_the_closed_form_rate():
    ts, r = spin_up(1e4)
    j_total = ts.top_drive_inertia + float(np.sum(ts.node_inertia))
    slope = (1e4 - 5e3) / j_total
    torque, top = r["motor_torque"], r["top_drive_speed"]
    limited = r.t <= 4.0
    np.testing.assert_array_equal(torque[limited], 1e4)  # exactly T_max while limited
    a, b = np.searchsorted(r.t, [1.0, 4.0])
    assert (top[b] - top[a]) / (r.t[b] - r.t[a]) == pytest.approx(slope, rel=1e-3)
    # anti-windup: still limited at 4 s, and the speed where it leaves the limit is the frozen integral's (0)
    assert np.all(top[limited] < ts.speed_setpoint - 1e4 / ts.proportional_gain)


@settings(max_examples=15, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(limit=st.floats(2e3, 2e4), bit_torque=st.floats(0.0, 1.5e3))
def test_any_torque_limit_bounds_the_motor_torque_and_the_acceleration(limit, bit_torque):
    """Property: for any T_max above the bit torque the motor torque never leaves [-T_max, T_max] and the speed never
    rises faster than (T_max - T_b) / J_total allows (plus the string's own transient, bounded by its twist)."""
    ts, r = spin_up(limit, bit_torque, t_end=1.0)
    assert r.completed and np.all(np.isfinite(r.states))
    assert np.all(np.abs(r["motor_torque"]) <= limit)
    j_total = ts.top_drive_inertia + float(np.sum(ts.node_inertia))
    assert r["bit_speed"][-1] == pytest.approx((limit - bit_torque) / j_total * r.t[-1], rel=2e-2)


def test_a_prescribed_speed_holds_node_0_on_the_set_point_and_costs_the_kinetic_wall_torque():
    ts = field_string(top_drive="prescribed_speed", damping_time=0.1, damping_rate=0.05, setpoint_time_constant=1.0)
    assert ts.top_drive == "prescribed_speed"
    times = np.round(np.arange(0.0, 30.0 + 1e-9, 0.01), 10)
    r = fs.simulate(ts, 30.0, method="moreau_jean", step=1e-3, output_times=times)
    set_point = 4.0 * (1.0 - np.exp(-r.t / 1.0))
    np.testing.assert_allclose(r["top_drive_speed"], set_point, rtol=1e-15, atol=1e-14)
    # A&S eq 27's bound (the sum of the static bounds) at f_rat, plus k_t times the string's inertia at speed
    steady = 0.6 * ts.breakoff_torque + 0.05 * float(np.sum(ts.node_inertia)) * set_point[-1]
    assert r.mode[-1] == 0
    assert r["motor_torque"][-1] == pytest.approx(steady, rel=1e-4)


def test_contact_solver_by_name_gives_the_active_sets_run_on_a_monotone_law():
    ts = field_string(kinetic_ratio=1.0, friction_coefficient=0.2, damping_time=2e-3)
    times = np.round(np.arange(0.0, 5.0 + 1e-9, 0.01), 10)
    default = fs.simulate(ts, 5.0, method="moreau_jean", step=1e-3, output_times=times)
    pgs = fs.simulate(ts, 5.0, method="moreau_jean", step=1e-3, output_times=times,
                      contact_solver="projected_gauss_seidel")
    assert default.mode[0] == ts.contact_count and default.mode[-1] < ts.contact_count  # walls stuck, then released
    np.testing.assert_allclose(pgs["bit_speed"], default["bit_speed"], rtol=0.0, atol=1e-10)
    np.testing.assert_array_equal(pgs.mode, default.mode)
    options = fs._core.SolverOptions(contact_solver="projected_gauss_seidel", step=1e-3)
    assert options.contact_solver == fs._core.ContactSolver.projected_gauss_seidel and options.step == 1e-3
    assert fs._core.SolverOptions().contact_solver == fs._core.ContactSolver.active_set


@pytest.mark.parametrize("make, parameter", [
    (lambda: field_string(torque_limit=-1.0), "torque_limit"),
    (lambda: field_string(top_drive="stiff"), "top_drive"),
    (lambda: field_string(top_drive="prescribed_speed", torque_limit=1e4), "torque_limit"),
    (lambda: field_string(top_drive="prescribed_speed", control_period=0.01), "control_period"),
    (lambda: fs.aarsnes_shor_well_b(elements=10, top_drive="prescribed_speed"), "control_period"),  # its sampled PI
    (lambda: fs.simulate(field_string(torque_limit=1e4), 1.0, method="moreau_jean", step=0.3), "step"),  # not k h
    (lambda: fs.simulate(field_string(), 0.1, method="explicit_projection", step=1e-4,
                         contact_solver="projected_gauss_seidel"), "contact_solver"),
    (lambda: fs.simulate(fs.TorsionalRig(fs.Coulomb(0.3)), 0.1, method="dormand_prince",
                         contact_solver="projected_gauss_seidel"), "contact_solver"),
    (lambda: fs.simulate(field_string(), 0.1, method="moreau_jean", contact_solver="lemke"), "contact_solver"),
    (lambda: fs._core.SolverOptions(contact_solver="lemke"), "contact_solver"),
])
def test_bad_drive_and_solver_inputs_are_named(make, parameter):
    with pytest.raises(fs.InvalidParameterError) as error:
        make()
    assert error.value.parameter == parameter, error.value
    assert parameter in str(error.value)


def test_solver_options_refuse_an_unknown_keyword():
    with pytest.raises(TypeError, match="unexpected keyword argument 'contact'"):
        fs._core.SolverOptions(contact="active_set")
    with pytest.raises(TypeError, match="unexpected keyword argument 'max_rtol'"):
        fs._core.SolverOptions(max_rtol=1.0)  # a limit of the class, not an option


def test_drive_keywords_rebuild_and_pickle_and_map_from_stringrigs():
    ts = field_string(top_drive="prescribed_speed", damping_time=0.01)
    limited = field_string(torque_limit=5e3)
    for model in (ts, limited):
        for copy in (pickle.loads(pickle.dumps(model)), eval(repr(model), vars(fs))):
            assert repr(copy) == repr(model)
            assert copy.top_drive == model.top_drive and copy.torque_limit == model.torque_limit
    assert "top_drive='prescribed_speed'" in repr(ts) and "top_drive=" not in repr(limited)
    # one string, two treatments: StringRig's top_drive and torque_limit reach the captured string
    model = ds.string_model(fs.DrillString([fs.PipeSection(length=1000.0)]), fs.Coulomb(0.18, 0.3),
                            treatment="captured", elements=16, top_drive="prescribed_speed", surface_speed=3.0)
    assert isinstance(model, fs.TorsionalString) and model.top_drive == "prescribed_speed"
    model = ds.string_model(fs.DrillString([fs.PipeSection(length=1000.0)]), fs.Coulomb(0.18, 0.3),
                            treatment="captured", elements=16, torque_limit=7e3)
    assert model.torque_limit == 7e3


def test_the_limited_pi_is_implicit_so_a_step_past_the_old_bound_runs_within_the_limit():
    """The captured string's torque-limited PI is implicit (each step taken linear or at the limit and checked at
    its end): a step of 0.5 s, far past h k_p = I_TD + J_0 where the explicit law of before was refused, runs and
    keeps the motor torque within the limit on every row."""
    string = field_string(torque_limit=1e4)
    run = fs.simulate(string, 10.0, method="moreau_jean", step=0.5)
    assert run.completed
    assert np.all(np.abs(run["motor_torque"]) <= 1e4)
