"""fs.StringRig's sampled PI (control_period > 0: string/top_drive.hpp's SampledPiTopDrive, Aarsnes & Shor's MAIN.m
with a zero-order hold) through the parameter table: the samples located at k T_c, the surface torque held between
them, the first sample from rest as MAIN.m's recursion gives it, and bad periods refused naming the keyword."""

import math
import pickle

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import drillstring as ds

PERIOD = 0.01  # s, A&S's
FILTER = 0.5  # s, the set-point's first-order filter (forward Euler at each sample)
GAINS = dict(proportional_gain=3e3, integral_gain=1e3)


def sampled_rig(**keywords):
    """1000 m of pipe at 1 rad inclination, Coulomb walls in stick-slip at 8 nodes, the PI sampled every 10 ms."""
    settings = dict(elements=8, inclination=1.0, damping_time=2e-3, top_drive_inertia=300.0, surface_speed=4.0,
                    setpoint_time_constant=FILTER, control_period=PERIOD, **GAINS)
    settings.update(keywords)
    return fs.StringRig(fs.DrillString([fs.PipeSection(length=1000.0)]), fs.Coulomb(0.2, 0.3), **settings)


def test_the_surface_torque_is_held_between_samples_located_at_k_T_c():
    rig = sampled_rig()
    assert rig.control_period == PERIOD and pickle.loads(pickle.dumps(rig)).control_period == PERIOD
    rows = 0.0005 + 0.001 * np.arange(3000)  # never on a sample instant (a row there is either side of it)
    result = fs.simulate(rig, 3.0, output_times=rows, rtol=1e-9, atol=1e-10)
    assert result.completed
    samples = np.array([e.time for e in result.events if e.name == "top_drive.sample"])
    assert 300 <= len(samples) <= 301  # t = 0, 0.01, ..., 3 s (the one at t_end may fire)
    np.testing.assert_allclose(samples, PERIOD * np.arange(len(samples)), rtol=1e-12, atol=0.0)
    assert any(e.name.startswith("node_") for e in result.events)  # the walls switch between samples too
    torque = ds.surface_torque(rig, result)
    assert np.array_equal(torque, result["held_motor_torque"])
    last = np.searchsorted(samples, result.t, side="right") - 1  # each row's latest sample
    assert np.all(last >= 0)
    for k in np.unique(last):  # piecewise constant: one value per sample interval, bit for bit
        held = torque[last == k]
        assert np.all(held == held[0])
    assert len(np.unique(torque)) > 200  # and it moves from sample to sample as the string spins up
    assert np.array_equal(result["next_sample"], last + 1.0)
    # the first sample from rest, MAIN.m's recursion: the set-point one Euler step of the filter, the demand k_p
    # times it (no integral yet), the integral T_c times the error
    setpoint = 4.0 * PERIOD / FILTER
    assert result["sampled_setpoint"][0] == pytest.approx(setpoint, rel=1e-14)
    assert torque[0] == pytest.approx(GAINS["proportional_gain"] * setpoint, rel=1e-14)
    assert result["speed_error_integral"][0] == pytest.approx(PERIOD * setpoint, rel=1e-14)


def test_a_continuous_pi_has_the_historical_layout():
    continuous = sampled_rig(control_period=0.0)
    assert continuous.control_period == 0.0
    names = list(continuous.state_names)
    assert names[0] == "speed_error_integral" and "held_motor_torque" not in names
    assert list(sampled_rig().state_names)[:4] == ["speed_error_integral", "held_motor_torque", "sampled_setpoint",
                                                   "next_sample"]


@pytest.mark.parametrize("keywords", [dict(control_period=-0.01), dict(control_period=math.nan),
                                      dict(control_period=math.inf), dict(top_drive="prescribed_speed")],
                         ids=["negative", "nan", "inf", "prescribed_speed"])
def test_bad_periods_and_a_sampled_prescribed_speed_are_refused_naming_control_period(keywords):
    with pytest.raises(fs.InvalidParameterError) as error:
        sampled_rig(**keywords)
    assert error.value.parameter == "control_period"
