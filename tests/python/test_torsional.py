"""The torsional rig of paper 001 (eqs 1-5) through Python: against an independent SciPy implementation of eq 5 with
Stribeck friction on the disc, Fig. 7's limit cycle, the natural-frequency bound of speed-only friction laws, the
energy integrals, limit_cycle on signals with known answers, the stick-slip map on threads, pickling, and the
errors of a friction law with no consistent branch."""

import math
import pickle
import re
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import frictionsim as fs

# Paper 001, Tables 1-2 in SI (docs/paper001_torsional_rig.md, section 2), written out again here rather than read
# from the rig: J_m = J3 / eta^2 (reading B), k_i = 3.5 (Table 2's misprinted label).
J2, K2, D2 = 0.0149, 0.3659, 0.0167
ETA, J_M = 8.0, 0.0237 / 64.0
L, R, K_T, K_E, T_F, C_M = 8.437e-4, 0.33, 0.126, 0.0602, 0.1196, 1.784e-4
K_P, K_I, W_REF, N2, RADIUS = 2.8, 3.5, 5.76, 35.0, 0.1
F_N = math.sqrt(K2 / J2) / (2 * math.pi)  # disc on a rigidly held shaft end, 0.7887 Hz

T_END, WINDOW = 30.0, 10.0  # SciPy comparison: run length and the final window measured [s]


# --------------------------------------------------------------------------------- independent SciPy model
class ScipyStribeckRig:
    """Eq 5 in load-side form with Stribeck friction at radius r on the disc, stick (w2 = 0 held) while
    |S| <= r mu_s N2, integrated phase by phase with solve_ivp's terminal events. States
    (th2, w2, phi = th3 - th2, w3, i, z). The motor turns forwards throughout (checked by a terminal event)."""

    def __init__(self, mu, mu_static, stribeck_velocity, shape_exponent, viscous_coefficient):
        self.mu, self.mu_s, self.v_s = mu, mu_static, stribeck_velocity
        self.delta, self.sigma_v = shape_exponent, viscous_coefficient
        self.limit = RADIUS * mu_static * N2  # static torque limit [N m]

    @staticmethod
    def shaft(y):
        return K2 * y[2] + D2 * (y[3] - y[1])

    def friction_torque(self, w2, direction):
        v = RADIUS * w2
        level = self.mu * N2 + (self.mu_s - self.mu) * N2 * math.exp(-(abs(v) / self.v_s) ** self.delta)
        return RADIUS * (direction * level + self.sigma_v * v)

    def rhs(self, mode, y):
        _, w2, phi, w3, i, z = y
        if mode == 0:  # disc stuck: w2 = 0 held
            w2, dw2 = 0.0, 0.0
        else:
            dw2 = (K2 * phi + D2 * (w3 - w2) - self.friction_torque(w2, mode)) / J2
        s = K2 * phi + D2 * (w3 - w2)
        voltage = K_P * (W_REF - w3) + K_I * z
        dw3 = (ETA * K_T * i - ETA ** 2 * C_M * w3 - ETA * T_F * math.copysign(1.0, w3) - s) / (ETA ** 2 * J_M)
        di = (voltage - R * i - ETA * K_E * w3) / L
        return [w2, dw2, w3 - w2, dw3, di, W_REF - w3]

    def run(self, t_end, w2_0=0.0, w3_0=W_REF, method="LSODA", rtol=1e-9, atol=1e-12):
        """Returns (segments [(t0, t1, mode, dense)], switches [(t, 'slip' | 'stick')])."""

        def event(function, direction):
            function.terminal, function.direction = True, direction
            return function

        motor_stops = event(lambda t, y: y[3], -1)
        t, y = 0.0, np.array([0.0, w2_0, 0.0, w3_0, 0.0, 0.0])
        mode = int(np.sign(w2_0)) if w2_0 != 0.0 else (0 if abs(self.shaft(y)) <= self.limit else int(np.sign(self.shaft(y))))
        departing = False
        segments, switches = [], []
        while t < t_end:
            if mode == 0:
                events = [event(lambda t, y: self.limit - self.shaft(y), -1),
                          event(lambda t, y: self.limit + self.shaft(y), -1), motor_stops]
            elif departing:
                # just broke away at w2 = 0 with S at the static limit: let the disc get under way before the
                # w2 = 0 guard is armed (otherwise the root just found is found again)
                s = mode
                events = [event(lambda t, y: s * y[1] - 1e-7, 1), motor_stops,
                          event(lambda t, y: s * y[1] + 1e-9, -1)]
            else:
                s = mode
                events = [event(lambda t, y: s * y[1], -1), motor_stops]
            sol = solve_ivp(lambda t, y: self.rhs(mode, y), (t, t_end), y, method=method, rtol=rtol, atol=atol,
                            events=events, dense_output=True)
            assert sol.success, sol.message
            segments.append((t, sol.t[-1], mode, sol.sol))
            t, y = sol.t[-1], sol.y[:, -1].copy()
            if sol.status != 1:
                break
            fired = [k for k, times in enumerate(sol.t_events) if len(times)]
            assert fired == [0] or (mode == 0 and fired == [1]), f"motor stopped or disc reversed at t = {t}"
            if mode == 0:  # breaks away in the direction of S
                mode, departing = (1 if fired == [0] else -1), True
                switches.append((t, "slip"))
            elif departing:
                departing = False
            else:  # w2 reached zero: stick if the static limit holds the disc, else reverse
                y[1] = 0.0
                mode = 0 if abs(self.shaft(y)) <= self.limit else int(np.sign(self.shaft(y)))
                assert mode == 0, f"disc reversed at t = {t}"
                switches.append((t, "stick"))
        return segments, switches

    @staticmethod
    def sample(segments, times):
        out = np.full((len(times), 6), np.nan)
        for t0, t1, _, dense in segments:
            inside = (times >= t0) & (times <= t1)
            if inside.any():
                out[inside] = dense(times[inside]).T
        assert not np.isnan(out).any()
        return out


def stribeck_law():
    return fs.torsional.fig7_laws()["Stribeck"]


def period_and_peak(slip_onsets, times, disc_speed):
    """Mean period between break-aways and the peak disc speed over the last WINDOW seconds."""
    onsets = np.asarray(slip_onsets)
    onsets = onsets[onsets >= T_END - WINDOW]
    return float(np.mean(np.diff(onsets))), float(disc_speed[times >= T_END - WINDOW].max())


@pytest.fixture(scope="module")
def scipy_run():
    p = dict(mu=0.22, mu_static=0.3566, stribeck_velocity=0.3, shape_exponent=1.0, viscous_coefficient=0.0)
    law = stribeck_law()
    assert "Stribeck(mu=0.22, mu_static=0.3566, stribeck_velocity=0.3, shape_exponent=1," in repr(law)
    assert "viscous_coefficient=0, karnopp_band=0)" in repr(law)
    model = ScipyStribeckRig(**p)
    segments, switches = model.run(T_END)
    times = np.linspace(0.0, T_END, 30001)
    return dict(times=times, states=model.sample(segments, times), segments=segments,
                slips=np.array([t for t, kind in switches if kind == "slip"]),
                sticks=np.array([t for t, kind in switches if kind == "stick"]))


@pytest.fixture(scope="module", params=["cvode_bdf", "dormand_prince"])
def engine_run(request, scipy_run):
    rig = fs.TorsionalRig(stribeck_law(), initial_drive_speed=W_REF, initial_disc_speed=0.0)
    result = fs.simulate(rig, T_END, output_times=scipy_run["times"], method=request.param, rtol=1e-9)
    return request.param, rig, result


def test_rig_defaults_are_tables_1_and_2():
    rig = fs.TorsionalRig(stribeck_law())
    expected = dict(disc_inertia=J2, shaft_stiffness=K2, shaft_damping=D2, motor_inertia=J_M, gear_ratio=ETA,
                    inductance=L, resistance=R, torque_constant=K_T, back_emf_constant=K_E,
                    motor_friction_torque=T_F, motor_viscous_coefficient=C_M, proportional_gain=K_P,
                    integral_gain=K_I, reference_speed=W_REF, normal_force=N2, contact_radius=RADIUS,
                    initial_disc_speed=0.0, initial_drive_speed=0.0)
    for name, value in expected.items():
        assert getattr(rig, name) == pytest.approx(value, rel=1e-15), name
    assert rig.natural_frequency == pytest.approx(F_N, rel=1e-12) and rig.natural_frequency == pytest.approx(0.7887, abs=1e-4)


def test_scipy_reference_is_a_stick_slip_limit_cycle(scipy_run):
    states, times, slips = scipy_run["states"], scipy_run["times"], scipy_run["slips"]
    assert states[:, 3].min() > 4.0  # the motor never stops (the model's sgn(w3) = +1 holds)
    assert states[:, 1].min() >= -1e-9  # the disc never turns backwards
    assert len(slips) >= 20 and len(scipy_run["sticks"]) >= 20
    periods = np.diff(slips[slips >= T_END - WINDOW])
    assert np.ptp(periods) < 1e-6 * periods.mean()  # converged: every cycle the same
    # periodic limit cycle: the PI integral and the twist return, so the mean disc speed is w_ref exactly
    th_a, th_b = (ScipyStribeckRig.sample(scipy_run["segments"], slips[[-8, -1]])[:, 0])
    assert (th_b - th_a) / (slips[-1] - slips[-8]) == pytest.approx(W_REF, rel=1e-7)
    assert 1.0 / periods.mean() < F_N  # speed-only friction: stick-slip slower than the disc-on-shaft mode


def test_stribeck_rig_agrees_with_scipy_on_switch_times_period_and_peak(scipy_run, engine_run):
    method, rig, result = engine_run
    times = scipy_run["times"]
    assert result.completed and result.drive_speed.min() > 4.0
    assert not any("motor" in e.mode_after_name for e in result.events)
    slips = np.array([e.time for e in result.events if e.name == "static_limit_positive"])
    sticks = np.array([e.time for e in result.events if e.mode_after_name == "stick"])
    assert all(e.mode_after_name in ("stick", "slip_positive") for e in result.events)
    # every switch of every cycle, at the same time (measured: 1e-7 s Dormand-Prince, 1.3e-8 s CVODE BDF)
    assert len(slips) == len(scipy_run["slips"]) and len(sticks) == len(scipy_run["sticks"])
    np.testing.assert_allclose(slips, scipy_run["slips"], rtol=0, atol=2e-6, err_msg=method)
    np.testing.assert_allclose(sticks, scipy_run["sticks"], rtol=0, atol=2e-6, err_msg=method)
    # limit cycle of the last 10 s (measured: period and peak agree to <= 3e-9 relative)
    period, peak = period_and_peak(slips, times, result.disc_speed)
    ref_period, ref_peak = period_and_peak(scipy_run["slips"], times, scipy_run["states"][:, 1])
    assert period == pytest.approx(ref_period, rel=1e-6), method
    assert peak == pytest.approx(ref_peak, rel=1e-6), method
    assert ref_period == pytest.approx(1.3582, rel=1e-4) and ref_peak == pytest.approx(13.80, rel=1e-3)
    # and as fs.torsional.limit_cycle sees the two sampled records
    mine = fs.torsional.limit_cycle(result, transient=20.0)
    theirs = fs.torsional.limit_cycle((times, scipy_run["states"][:, 1]), transient=20.0)
    assert mine.cycles == theirs.cycles >= 6  # 10 s at 1.358 s
    for field in ("frequency", "peak", "mean", "stick_fraction"):
        assert getattr(mine, field) == pytest.approx(getattr(theirs, field), rel=1e-5), field
    assert mine.frequency == pytest.approx(1.0 / ref_period, rel=1e-6)


def test_stribeck_rig_agrees_with_scipy_pointwise(scipy_run, engine_run):
    # the whole 30 s trajectory, every state: the drive states (w3, i, z) are what a wrong gear factor, motor
    # friction or back-emf term would change (the PI loop hides most of that from the disc's period and peak)
    method, rig, result = engine_run
    reference = scipy_run["states"]
    names = ["disc_angle", "disc_speed", "shaft_twist", "drive_speed", "current", "speed_error_integral"]
    assert result.state_names[:6] == names
    # measured max |difference| (Dormand-Prince; CVODE BDF is ~10x closer): w2 4.4e-6 rad/s, th2 and twist
    # 8e-7 rad, w3 3e-8 rad/s, i 3e-7 A, z 6e-9 rad. A 6 % change of J_m moves th2 by 9e-4 rad.
    limits = [2e-4, 2e-4, 2e-4, 2e-5, 2e-5, 2e-5]
    for k, (name, limit) in enumerate(zip(names, limits)):
        error = np.max(np.abs(result[name] - reference[:, k]))
        assert error < limit, (method, name, error)
    first_cycles = scipy_run["times"] <= 8.0
    assert np.max(np.abs(result.disc_speed[first_cycles] - reference[first_cycles, 1])) < 5e-5


# ------------------------------------------------------------------------------------------------ Fig. 7
@pytest.fixture(scope="module")
def fig7():
    rig, result = fs.torsional.simulate_fig7()
    return rig, result, fs.torsional.limit_cycle(result, transient=20)


def test_fig7_is_reproduced(fig7):
    rig, result, cycle = fig7
    assert result.completed and result.t[-1] == 40.0
    assert cycle.stick_slip and cycle.stick_fraction > 0.1 and cycle.cycles >= 10
    assert cycle.trough >= -1e-9 and result.disc_speed.min() >= -1e-9  # "always positive"
    assert 0.83 <= cycle.frequency <= 0.84  # measured 0.83 Hz, simulated 0.84 Hz
    assert 13.5 <= cycle.peak <= 14.0  # measured 13.55 rad/s, simulated 14
    assert cycle.frequency > rig.natural_frequency
    assert cycle.mean == pytest.approx(W_REF, abs=1e-4)  # periodic PI integral: mean w3 = mean w2 = w_ref
    assert result.drive_speed[result.t > 1.0].min() > 0.0  # the motor turns throughout once started
    assert result.events[0].name == "motor_breakaway_positive" and result.events[0].time < 1e-3


def test_speed_only_laws_stay_below_the_natural_frequency():
    table = fs.torsional.compare_laws().set_index("law")
    assert set(table.index) == {"hysteretic (eq 6)", "Coulomb", "Stribeck", "Karnopp", "LuGre", "Dahl"}
    assert np.allclose(table["natural_frequency"], F_N, rtol=1e-12)
    for law in ("Coulomb", "Stribeck", "Karnopp", "LuGre"):
        row = table.loc[law]
        assert row["stick_slip"], law
        assert 0.6 < row["frequency"] < F_N, law
        assert row["mean"] == pytest.approx(W_REF, abs=1e-3), law
    eq6 = table.loc["hysteretic (eq 6)"]
    assert eq6["stick_slip"] and eq6["frequency"] > F_N * 1.05
    dahl = table.loc["Dahl"]
    assert not dahl["stick_slip"] and dahl["cycles"] == 0 and dahl["frequency"] == 0.0
    assert dahl["trough"] > 5.0  # steady rotation at w_ref, far from sticking


# ------------------------------------------------------------------------------------------------ energy
def mechanical_residual(rig, r):
    stored = rig.stored_mechanical_energy(r.states)
    return (r.motor_work - r.motor_work[0]) - (stored - stored[0]) - (r.friction_work - r.friction_work[0]) \
        - (r.damping_work - r.damping_work[0])


def test_fig7_energy_balance(fig7):
    rig, r, _ = fig7
    scale = r.motor_work[-1] - r.motor_work[0]
    assert scale > 100.0  # J over 40 s
    assert np.max(np.abs(mechanical_residual(rig, r))) < 1e-6 * scale  # measured 1.5e-8
    stored = 0.5 * J2 * r.disc_speed ** 2 + 0.5 * ETA ** 2 * J_M * r.drive_speed ** 2 + 0.5 * K2 * r.shaft_twist ** 2
    np.testing.assert_allclose(rig.stored_mechanical_energy(r.states), stored, rtol=1e-13, atol=1e-15)
    # the integrands are the equations' powers (trapezoid rule on the 1 ms record: ~1e-4)
    powers = {"motor_work": ETA * K_T * r.current * r.drive_speed,
              "friction_work": r.friction_force * r.disc_speed,
              "damping_work": D2 * (r.drive_speed - r.disc_speed) ** 2 + ETA ** 2 * C_M * r.drive_speed ** 2
              + ETA * T_F * np.abs(r.drive_speed),
              "electrical_work": rig.voltage(r.states) * r.current, "ohmic_work": R * r.current ** 2}
    for name, power in powers.items():
        assert r[name][-1] - r[name][0] == pytest.approx(np.trapezoid(power, r.t), rel=2e-3), name
    np.testing.assert_allclose(rig.voltage(r.states), K_P * (W_REF - r.drive_speed) + K_I * r.speed_error_integral,
                               rtol=1e-13, atol=1e-12)
    # as printed, K_E != K_T: the electrical side takes (K_E / K_T) of the mechanical conversion
    electrical = r.ohmic_work + 0.5 * L * (r.current ** 2 - r.current[0] ** 2) + K_E / K_T * r.motor_work
    assert np.max(np.abs(r.electrical_work - electrical)) < 1e-6 * r.electrical_work[-1]


def test_lossless_motor_closes_the_electrical_balance():
    rig, r = fs.torsional.simulate_fig7(t_end=20.0, back_emf_constant=K_T)
    assert rig.back_emf_constant == K_T
    scale = r.electrical_work[-1]
    electrical = r.ohmic_work + 0.5 * L * (r.current ** 2 - r.current[0] ** 2) + r.motor_work
    assert np.max(np.abs(r.electrical_work - electrical)) < 1e-6 * scale
    assert np.max(np.abs(mechanical_residual(rig, r))) < 1e-6 * r.motor_work[-1]
    assert r.ohmic_work[-1] > 0.1 * scale  # a real check: every term is material


def test_energy_balance_holds_through_branch_gap_holds():
    # Filippov holds (dw2/dt = 0, friction torque = S) must book the friction work like any other mode
    law = fs.HystereticFriction(1400.0, (1.0, 0, 0, 0, 0, 0), (0.8, 0, 0, 0, 0, 0), branch_gap="hold")
    rig = fs.TorsionalRig(law)
    r = fs.simulate(rig, 10.0, output_times=np.linspace(0.0, 10.0, 10001))
    assert any(e.mode_after_name == "hold_positive" for e in r.events)
    assert np.max(np.abs(mechanical_residual(rig, r))) < 1e-6 * r.motor_work[-1]
    holding = np.isin(r.mode, [3])
    assert holding.any()
    np.testing.assert_allclose(r.friction_force[holding], rig.shaft_torque(r.states)[holding], rtol=1e-12)


# ------------------------------------------------------------------------------------------ limit_cycle
T_1KHZ = np.arange(0.0, 30.0, 1e-3)
SINE = 5.0 + 3.0 * np.sin(2 * np.pi * 0.7 * T_1KHZ)


def test_limit_cycle_of_a_sine():
    cycle = fs.torsional.limit_cycle((T_1KHZ, SINE))
    assert cycle.frequency == pytest.approx(0.7, rel=1e-4) and cycle.period == pytest.approx(1 / 0.7, rel=1e-4)
    assert cycle.cycles == 19  # 21 upward crossings of 5 in 30 s at 0.7 Hz: t = 0 is not a crossing
    assert cycle.peak == pytest.approx(8.0, rel=1e-6) and cycle.trough == pytest.approx(2.0, rel=1e-6)
    assert cycle.mean == pytest.approx(5.0, rel=1e-6) and cycle.stick_fraction == 0.0 and not cycle.stick_slip
    later = fs.torsional.limit_cycle((T_1KHZ, SINE), transient=5.0)
    assert later.start >= 5.0 and later.frequency == pytest.approx(0.7, rel=1e-4) and later.cycles == 17


def test_limit_cycle_stick_fraction_of_a_clipped_sine():
    # w = max(0, 1 + 2 sin): |w| <= stick_speed while sin <= (stick_speed - 1) / 2
    w = np.maximum(0.0, 1.0 + 2.0 * np.sin(2 * np.pi * 0.7 * T_1KHZ))
    for stick_speed in (1e-2, 0.5):
        cycle = fs.torsional.limit_cycle((T_1KHZ, w), stick_speed=stick_speed)
        expected = 0.5 + math.asin((stick_speed - 1.0) / 2.0) / math.pi
        assert cycle.stick_fraction == pytest.approx(expected, abs=1e-4), stick_speed
        assert cycle.stick_slip and cycle.frequency == pytest.approx(0.7, rel=1e-4)
        assert cycle.peak == pytest.approx(3.0, rel=1e-6) and cycle.trough == 0.0


def test_limit_cycle_noise_near_the_level_does_not_split_cycles():
    noisy = SINE + np.random.default_rng(7).uniform(-0.1, 0.1, SINE.size)
    cycle = fs.torsional.limit_cycle((T_1KHZ, noisy))
    assert cycle.cycles == 20 and cycle.frequency == pytest.approx(0.7, rel=1e-3)
    assert fs.torsional.limit_cycle((T_1KHZ, noisy), hysteresis=0.0).cycles > 40  # what the re-arm margin prevents


@pytest.mark.parametrize("w", [np.full_like(T_1KHZ, 5.76), 5.0 + T_1KHZ, 5.76 + 1e-4 * np.sin(2 * np.pi * T_1KHZ)],
                         ids=["constant", "ramp", "ripple"])
def test_limit_cycle_without_oscillation(w):
    cycle = fs.torsional.limit_cycle((T_1KHZ, w))
    assert cycle.cycles == 0 and cycle.frequency == 0.0 and math.isinf(cycle.period) and not cycle.stick_slip


@pytest.mark.parametrize("args, kwargs, parameter", [
    ((T_1KHZ, SINE[:-1]), {}, "w"),
    ((T_1KHZ, SINE), dict(transient=40.0), "transient"),
    ((T_1KHZ, SINE), dict(transient=-1.0), "transient"),
    ((T_1KHZ, np.where(T_1KHZ > 3.0, np.nan, SINE)), {}, "w"),
    ((np.where(T_1KHZ > 3.0, np.nan, T_1KHZ), SINE), {}, "t"),
    ((T_1KHZ[::-1], SINE), {}, "t"),
    ((T_1KHZ, SINE), dict(hysteresis=1.0), "hysteresis"),
    ((T_1KHZ, SINE), dict(stick_speed=-1.0), "stick_speed"),
    ((T_1KHZ, SINE), dict(level=float("nan")), "level"),
    ((T_1KHZ, SINE), dict(min_amplitude=-1.0), "min_amplitude"),
])
def test_limit_cycle_bad_inputs_name_the_parameter(args, kwargs, parameter):
    with pytest.raises(ValueError, match=parameter) as info:
        fs.torsional.limit_cycle(args, **kwargs)
    assert isinstance(info.value, fs.InvalidParameterError) and info.value.parameter == parameter


# ----------------------------------------------------------------------------------------- stick-slip map
def test_stick_slip_map_on_threads_equals_serial():
    speeds, forces = [4.0, 5.76, 16.0], [35.0]
    serial = fs.torsional.stick_slip_map(speeds, forces)
    with ThreadPoolExecutor(max_workers=2) as pool:
        threaded = fs.torsional.stick_slip_map(speeds, forces, executor=pool)
    for name in ("stick_slip", "frequency", "peak_ratio", "stick_fraction"):
        assert getattr(serial, name).shape == (3, 1)
        np.testing.assert_array_equal(getattr(serial, name), getattr(threaded, name), err_msg=name)
    assert serial.stick_slip[:, 0].tolist() == [True, True, False]
    assert 0.83 <= serial.frequency[1, 0] <= 0.84  # the Fig. 7 point
    assert serial.peak_ratio[1, 0] == pytest.approx(13.8 / 5.76, rel=5e-3)
    assert serial.stick_fraction[2, 0] == 0.0 and serial.peak_ratio[2, 0] < 1.1  # fast enough not to stick
    frame = serial.to_pandas()
    assert len(frame) == 3 and list(frame["reference_speed"]) == speeds


@pytest.mark.parametrize("speeds, forces, parameter", [
    ([], [35.0], "reference_speeds"), ([4.0, -1.0], [35.0], "reference_speeds"),
    ([float("nan")], [35.0], "reference_speeds"), ([4.0], [0.0], "normal_forces"), ([4.0], [], "normal_forces"),
])
def test_stick_slip_map_rejects_a_bad_grid(speeds, forces, parameter):
    with pytest.raises(ValueError, match=parameter):
        fs.torsional.stick_slip_map(speeds, forces, t_end=1.0, transient=0.5)


# ------------------------------------------------------------------------------------ pickling and errors
def test_rig_and_hysteretic_law_pickle():
    rig = fs.TorsionalRig(fs.torsional.fig7_friction(), reference_speed=4.0)
    copy = pickle.loads(pickle.dumps(rig))
    assert type(copy) is fs.TorsionalRig and repr(copy) == repr(rig) and copy.reference_speed == 4.0
    law = fs.HystereticFriction(1400.0, (1.0, -0.02, -0.003, 5e-4, 1e-5, 2e-5), (0.8, 0, 0, 0, 0, 0),
                                stick_speed=2e-3, reference_normal_force=40.0, branch_gap="error")
    law_copy = pickle.loads(pickle.dumps(law))
    assert type(law_copy) is fs.HystereticFriction and repr(law_copy) == repr(law)
    assert law_copy.branch_gap == "error" and tuple(law_copy.accelerating) == (1.0, -0.02, -0.003, 5e-4, 1e-5, 2e-5)
    a = fs.simulate(rig, 3.0)
    b = fs.simulate(copy, 3.0)
    np.testing.assert_array_equal(a.states, b.states)


def test_bad_rig_and_law_arguments():
    with pytest.raises(TypeError, match="disc_inertial"):
        fs.TorsionalRig(stribeck_law(), disc_inertial=0.01)
    with pytest.raises(fs.InvalidParameterError, match="disc_inertia") as info:
        fs.TorsionalRig(stribeck_law(), disc_inertia=-1)
    assert info.value.parameter == "disc_inertia" and isinstance(info.value, ValueError)
    with pytest.raises(ValueError, match="branch_gap") as info:
        fs.HystereticFriction(1400.0, (1.0, 0, 0, 0, 0, 0), (0.8, 0, 0, 0, 0, 0), branch_gap="maybe")
    assert getattr(info.value, "parameter", "branch_gap") == "branch_gap"


def test_no_consistent_branch_reports_where_and_when():
    # accelerating level 1.0 above decelerating 0.8: at dw/dt = 0 with S in (0.8, 1.0] neither branch applies
    gap = (1400.0, (1.0, 0, 0, 0, 0, 0), (0.8, 0, 0, 0, 0, 0))
    rig = fs.TorsionalRig(fs.HystereticFriction(*gap, branch_gap="error"))
    with pytest.raises(fs.SimulationError) as info:
        fs.simulate(rig, 10.0)
    error = info.value
    message = str(error)
    assert "no consistent friction branch" in message and "t = " in message
    assert error.time_reached > 0.0
    assert float(re.search(r"t = ([0-9.eE+-]+) s", message).group(1)) == pytest.approx(error.time_reached, rel=1e-9)
    partial = error.partial
    assert isinstance(partial, fs.Result) and not partial.completed
    assert partial.t[-1] <= error.time_reached and len(partial.t) > 10
    assert partial.disc_speed[-1] > 1.0  # it failed while slipping, where al reached 0
    held = fs.simulate(fs.TorsionalRig(fs.HystereticFriction(*gap, branch_gap="hold")), 10.0)
    assert held.completed and held.t_reached == 10.0
    assert any(e.mode_after_name == "hold_positive" for e in held.events)
    # up to the first hold the two runs are the same run
    first_hold = next(e.time for e in held.events if e.mode_after_name == "hold_positive")
    assert first_hold == pytest.approx(error.time_reached, rel=1e-9)


# ------------------------------------------------------------------------------- review regressions

def test_hysteretic_torque_defaults_to_the_laws_reference_normal_force():
    law = fs.HystereticFriction(100.0, (1.0, 0, 0, 0, 0, 0), (0.8, 0, 0, 0, 0, 0), reference_normal_force=50.0)
    assert law.torque(5.0, 1.0) == pytest.approx(1.0)          # at N_ref the coefficients hold as given
    assert law.torque(5.0, 1.0, 25.0) == pytest.approx(0.5)    # N / N_ref
    assert law.branch_torque(False, 5.0, -1.0) == pytest.approx(0.8)


def test_rig_keyword_that_is_not_a_number_is_named():
    with pytest.raises(TypeError, match="disc_inertia"):
        fs.TorsionalRig(fs.torsional.fig7_friction(), disc_inertia="a")


def test_disc_acceleration_rejects_unknown_mode_codes():
    rig, result = fs.torsional.simulate_fig7(t_end=1.0)
    with pytest.raises(ValueError, match="mode") as info:
        rig.disc_acceleration(result.states, np.full(len(result.t), 99))
    assert info.value.parameter == "mode"


def test_simulate_fig7_ends_at_t_end_whatever_the_sample_time():
    _, result = fs.torsional.simulate_fig7(t_end=1.0006, sample_time=1e-3)
    assert result.t[-1] == pytest.approx(1.0006) and np.all(np.diff(result.t) > 0)
    with pytest.raises(fs.InvalidParameterError, match="sample_time") as info:
        fs.torsional.simulate_fig7(t_end=1.0, sample_time=0.0)
    assert info.value.parameter == "sample_time"
    with pytest.raises(fs.InvalidParameterError, match="t_end") as info:
        fs.torsional.simulate_fig7(t_end=-1.0)
    assert info.value.parameter == "t_end"


def test_stick_slip_map_marks_failed_points():
    # N2 = 200 N: the Fig. 7 set's p01, scaled by N2 / 35 N, cancels the disc's inertia (valid below 163 N)
    m = fs.torsional.stick_slip_map([5.76], [35.0, 200.0], t_end=25.0, transient=10.0, errors="collect")
    assert m.failed.tolist() == [[False, True]]
    assert m.stick_slip.tolist() == [[True, False]] and np.isnan(m.frequency[0, 1])
    with pytest.raises(Exception, match="effective inertia"):
        fs.torsional.stick_slip_map([5.76], [200.0], t_end=25.0, transient=10.0)
