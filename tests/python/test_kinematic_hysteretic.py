"""Paper 001's eq 6 (fs.HystereticFriction) on the kinematic rig: a prescribed disc speed w(t) and its derivative
give the branch, so the law can be simulated, plotted and identified like the others."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import frictionsim as fs

F = 0.835  # Hz, paper 001's stick-slip frequency
W_S = 1e-3  # rad/s, eq 6's stick band


T0 = 0.1  # s: the ramp through the stick band


def _amplitude(t):
    """Cycles of changing height (4-10 rad/s), so that w and dw/dt are not tied to one ellipse (a fit needs both)."""
    return 7.0 + 3.0 * np.sin(2.0 * np.pi * 0.3 * t), 3.0 * 2.0 * np.pi * 0.3 * np.cos(2.0 * np.pi * 0.3 * t)


def speed(t):
    """Rest, a slow ramp through the stick band (the torque climbs to break-away a w_s), then 0-20 rad/s cycles."""
    t = np.asarray(t, dtype=float)
    a, _ = _amplitude(t - T0)
    return np.where(t < T0, W_S * t / T0, W_S + a * (1.0 - np.cos(2.0 * np.pi * F * (t - T0))))


def acceleration(t):
    t = np.asarray(t, dtype=float)
    a, da = _amplitude(t - T0)
    phase = 2.0 * np.pi * F * (t - T0)
    return np.where(t < T0, W_S / T0, da * (1.0 - np.cos(phase)) + a * 2.0 * np.pi * F * np.sin(phase))


def eq6(law, w, al, normal_force):
    """Paper 001's eq 6 written out from the law's coefficients (not the engine's evaluation): the stick band
    T = a w for |w| <= w_s; else, with s = sgn(w), u = |w|, b = s al, the accelerating branch (b > 0) or the
    decelerating one (b <= 0): T = s (c00 + c10 u + c01 b + c20 u^2 + c11 u b + c02 b^2); all scaled by N / N_ref."""
    w, al = np.asarray(w, dtype=float), np.asarray(al, dtype=float)
    s, u = np.sign(w), np.abs(w)
    b = s * al
    c = np.where((b > 0.0)[..., None], np.asarray(law.accelerating), np.asarray(law.decelerating))
    slip = s * (c[..., 0] + c[..., 1] * u + c[..., 2] * b + c[..., 3] * u * u + c[..., 4] * u * b + c[..., 5] * b * b)
    torque = np.where(u <= law.stick_speed, law.stick_slope * w, slip)
    return normal_force / law.reference_normal_force * torque


@pytest.mark.parametrize("method", ["dormand_prince", "cvode_bdf"])
def test_torque_is_eq6_at_the_prescribed_speed_and_acceleration(method):
    law = fs.torsional.fig7_friction()
    rig = fs.KinematicRig.harmonic(law, sliding_velocity=3.0, velocity_amplitude=8.0, frequency=F,
                                   normal_force=35.0)
    t = np.linspace(0.0, 2.4, 241)
    result = fs.simulate(rig, 2.4, method=method, rtol=1e-10, output_times=t)
    w = 3.0 - 8.0 * np.cos(2.0 * np.pi * F * t)
    al = 8.0 * 2.0 * np.pi * F * np.sin(2.0 * np.pi * F * t)
    assert np.allclose(result.friction_force, eq6(law, w, al, 35.0), rtol=1e-12, atol=1e-12)
    assert set(np.unique(result.mode)) >= {-2, -1, 1, 2}  # both branches on both sides
    # the switches are events: dw/dt = 0 at t = k / (2 f), the stick band crossed where w = 3 - 8 cos = 0
    zero_acceleration = [e.time for e in result.events if e.name == "acceleration_zero"]
    assert np.allclose(zero_acceleration, np.arange(1, len(zero_acceleration) + 1) / (2.0 * F), atol=1e-9)
    band = [e for e in result.events if e.mode_after_name == "stick"]
    assert band and all(abs(3.0 - 8.0 * np.cos(2.0 * np.pi * F * e.time)) == pytest.approx(W_S, rel=1e-6)
                        for e in band)


def test_callable_and_sampled_speeds_agree_with_the_harmonic():
    law = fs.torsional.fig7_friction()
    t = np.linspace(0.0, 2.0, 201)
    harmonic = fs.simulate(fs.KinematicRig.harmonic(law, sliding_velocity=7.0, velocity_amplitude=7.0, frequency=F,
                                                    normal_force=35.0), 2.0, rtol=1e-10, output_times=t)
    callable_rig = fs.KinematicRig(law, relative_velocity=lambda s: 7.0 - 7.0 * np.cos(2.0 * np.pi * F * s),
                                   normal_force=35.0)
    by_callable = fs.simulate(callable_rig, 2.0, rtol=1e-10, output_times=t)
    # the callable's dw/dt is a central difference (error ~ h^2 w''' ~ 1e-9): the branch choice is the same
    assert np.allclose(by_callable.friction_force, harmonic.friction_force, atol=1e-8)
    fine = np.linspace(0.0, 2.0, 20001)
    sampled = fs.simulate(fs.KinematicRig(law, relative_velocity=(fine, 7.0 - 7.0 * np.cos(2.0 * np.pi * F * fine)),
                                          normal_force=35.0), 2.0, rtol=1e-10, output_times=t)
    # piecewise linear: the slope of each 1e-4 s segment stands for dw/dt (error ~ 1e-4 w'' ~ 2e-2 rad/s^2)
    assert np.allclose(sampled.friction_force, harmonic.friction_force, atol=5e-4)


def test_friction_work_is_the_integral_of_torque_times_speed():
    law = fs.torsional.fig7_friction()
    rig = fs.KinematicRig.harmonic(law, sliding_velocity=7.0, velocity_amplitude=7.0, frequency=F, normal_force=35.0)
    result = fs.simulate(rig, 1.2, rtol=1e-11, atol=1e-12, record_steps=True,
                         output_times=np.linspace(0.0, 1.2, 120001))
    t = result.t
    w = 7.0 - 7.0 * np.cos(2.0 * np.pi * F * t)
    power = result.friction_force * w
    trapezoid = np.concatenate(([0.0], np.cumsum(0.5 * np.diff(t) * (power[1:] + power[:-1]))))
    assert result["friction_work"][-1] == pytest.approx(trapezoid[-1], rel=1e-6)


def test_eq6_identified_from_a_kinematic_record():
    """fs.fit.fit_hysteretic_friction recovers the law that generated the record (exact data, no smoothing)."""
    law = fs.torsional.fig7_friction()
    rig = fs.KinematicRig(law, relative_velocity=lambda s: float(speed(s)), normal_force=35.0)
    t = np.linspace(0.0, 6.0, 12001)
    result = fs.simulate(rig, 6.0, method="dormand_prince", rtol=1e-11, output_times=t)
    fit = fs.fit.fit_hysteretic_friction(speed(t), acceleration(t), result.friction_force, stick_speed=W_S,
                                         stick_threshold=W_S, guard=0)
    assert np.allclose(fit.law.accelerating, law.accelerating, rtol=1e-5, atol=1e-7)
    assert np.allclose(fit.law.decelerating, law.decelerating, rtol=1e-5, atol=1e-7)
    assert fit.law.stick_slope == pytest.approx(law.stick_slope, rel=1e-3)


def test_rig_pickles_and_names_the_law():
    rig = fs.KinematicRig.harmonic(fs.torsional.fig7_friction(), sliding_velocity=7.0, velocity_amplitude=7.0,
                                   frequency=F, normal_force=35.0)
    again = pickle.loads(pickle.dumps(rig))
    assert repr(again) == repr(rig) and "HystereticFriction" in repr(rig)
    a = fs.simulate(rig, 0.5, output_times=[0.5])
    b = fs.simulate(again, 0.5, output_times=[0.5])
    assert a.friction_force[-1] == b.friction_force[-1]
    with pytest.raises(TypeError, match="HystereticFriction"):
        fs.KinematicRig("eq 6", relative_velocity=1.0, normal_force=35.0)
