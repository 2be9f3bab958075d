"""Paper 001's identification of the hysteretic friction law on the torsional rig (frictionsim.fit.torsional)."""

import dataclasses

import numpy as np
import pytest

import frictionsim as fs
from frictionsim.fit import (BranchFit, FrictionTorqueEstimate, HystereticFit, estimate_friction_torque,
                             fit_hysteretic_friction)

J2, K2, D2 = 0.0149, 0.3659, 0.0167  # Table 1, the estimator's defaults
DT, T_END = 1e-3, 25.0

# A law with every coefficient non-zero and N0 != P0 (exact recovery needs all six terms present).
HYSTERETIC = dict(stick_slope=1300.0, accelerating=(0.95, -0.03, -0.004, 5e-4, 1e-5, -1e-5),
                  decelerating=(0.90, -0.015, -0.003, 2e-4, -1e-5, 1e-5))


def fig7_law():
    """The round-trip law: the eq 6 set that reproduces paper 001's Fig. 7."""
    return fs.torsional.fig7_friction()


def simulate(law):
    return fs.simulate(fs.TorsionalRig(law), T_END, output_times=np.arange(0.0, T_END, DT), method="cvode_bdf")


def limit_cycle(result, last=10.0):
    """(frequency [Hz] from upward zero crossings of w - mean w, peak disc speed [rad/s]) over the last seconds."""
    keep = result.t > result.t[-1] - last
    t, w = result.t[keep], result.disc_speed[keep]
    below = w < w.mean()
    up = np.flatnonzero(below[:-1] & ~below[1:])
    assert up.size >= 4, "no limit cycle"
    return (up.size - 1) / (t[up[-1]] - t[up[0]]), float(w.max())


def angles(result, noise=None, seed=0):
    """(theta2, theta3) from a rig run, with Gaussian noise [rad] or quantisation ("q", counts per turn)."""
    th2, th3 = result.disc_angle, result.disc_angle + result.shaft_twist
    if noise is None:
        return th2, th3
    if isinstance(noise, tuple):
        q = 2.0 * np.pi / noise[1]
        return np.round(th2 / q) * q, np.round(th3 / q) * q
    rng = np.random.default_rng(seed)
    return th2 + rng.normal(0.0, noise, th2.size), th3 + rng.normal(0.0, noise, th3.size)


@pytest.fixture(scope="module")
def original():
    return simulate(fig7_law())


# ---------------------------------------------------------------------------------------------- exact recovery


def synthetic_samples(law, mirrored=True):
    """Time-ordered (w, al, T): stick ramps up to Ts = a w_s, then both branches on a (w, al) grid."""
    w_s = law.stick_speed
    ramp = np.linspace(-w_s, w_s, 41)  # a stick phase: T = a w, reaching a w_s at its last sample
    grid_w, grid_al = np.meshgrid(np.linspace(0.3, 15.0, 25), np.concatenate([np.linspace(1.0, 40.0, 20),
                                                                               -np.linspace(1.0, 40.0, 20)]))
    w, al = grid_w.ravel(), grid_al.ravel()
    if mirrored:  # w < 0: the odd extension maps (-w, -al) onto the same branches
        w, al = np.concatenate([w, -w]), np.concatenate([al, -al])
    speeds = np.concatenate([ramp, w[: w.size // 2], ramp, w[w.size // 2:], ramp])
    accelerations = np.concatenate([np.zeros(41), al[: al.size // 2], np.zeros(41), al[al.size // 2:], np.zeros(41)])
    return speeds, accelerations, law.torque(speeds, accelerations)


def test_exact_recovery_from_the_law():
    law = fs.HystereticFriction(**HYSTERETIC)
    w, al, torque = synthetic_samples(law)
    fit = fit_hysteretic_friction(w, al, torque, guard=0)
    assert isinstance(fit, HystereticFit) and isinstance(fit.accelerating, BranchFit)
    for branch, key in ((fit.accelerating, "accelerating"), (fit.decelerating, "decelerating")):
        true = HYSTERETIC[key]
        np.testing.assert_allclose(branch.coefficients, true, rtol=1e-9, atol=0)
        assert branch.r_squared == pytest.approx(1.0, abs=1e-12)
        assert branch.rmse < 1e-12
        assert branch.samples == 2 * 25 * 20  # both signs of w, no sample lost
        assert 1.0 < branch.condition_number < 1e6
    assert fit.stick_slope == pytest.approx(1300.0, rel=1e-9)
    assert fit.breakaway_torque == pytest.approx(1.3, rel=1e-9)
    assert fit.stick_phases == 3 and fit.stick_samples == 3 * 41
    np.testing.assert_allclose(fit.law.accelerating, HYSTERETIC["accelerating"], rtol=1e-9)
    np.testing.assert_allclose(fit.law.decelerating, HYSTERETIC["decelerating"], rtol=1e-9)
    probe_w, probe_al = np.array([0.5, 3.0, -7.0, 12.0]), np.array([-20.0, 5.0, 15.0, -2.0])
    np.testing.assert_allclose(fit.law.torque(probe_w, probe_al), law.torque(probe_w, probe_al), rtol=1e-9)


def test_negative_speeds_use_the_odd_extension():
    law = fs.HystereticFriction(**HYSTERETIC)
    w, al, torque = synthetic_samples(law, mirrored=False)
    positive = fit_hysteretic_friction(w, al, torque, guard=0)
    negative = fit_hysteretic_friction(-w, -al, -torque, guard=0)
    np.testing.assert_allclose(negative.accelerating.coefficients, positive.accelerating.coefficients, rtol=1e-9)
    np.testing.assert_allclose(negative.decelerating.coefficients, positive.decelerating.coefficients, rtol=1e-9)
    assert negative.breakaway_torque == pytest.approx(positive.breakaway_torque, rel=1e-12)
    assert negative.accelerating.speed_range[0] > 0.0  # fitted in the mapped (w > 0) coordinates


def test_summary_table():
    fit = fit_hysteretic_friction(*synthetic_samples(fs.HystereticFriction(**HYSTERETIC)), guard=0)
    text = fit.summary()
    assert str(fit) == text
    for label in ("p/n00", "p/n02", "R^2", "RMSE", "cond", "accelerating", "decelerating", "Ts"):
        assert label in text
    assert "-0.03" in text and "0.9" in text  # p10 and n00 printed
    with pytest.raises(dataclasses.FrozenInstanceError):
        fit.stick_slope = 1.0


# ---------------------------------------------------------------------------------- eq 1a on analytic signals


def eq1a(al2, twist_rate, twist):
    return -(J2 * al2 + D2 * twist_rate + K2 * twist)


def test_estimate_is_exact_for_cubic_angles():
    t = np.arange(0.0, 2.0, DT)
    th2 = 0.3 + 5.0 * t + 1.5 * t**2 - 0.4 * t**3
    twist = -(0.8 + 0.2 * t - 0.1 * t**2 + 0.05 * t**3)  # th2 - th3
    est = estimate_friction_torque(t, th2, th2 - twist)
    assert isinstance(est, FrictionTorqueEstimate)
    assert est.window_samples == 31 and est.window == pytest.approx(0.030) and est.guard == 16
    w2, al2 = 5.0 + 3.0 * t - 1.2 * t**2, 3.0 - 2.4 * t
    twist_rate = -(0.2 - 0.2 * t + 0.15 * t**2)
    # exact everywhere, ends included (mode="interp" fits the same cubic there)
    np.testing.assert_allclose(est.disc_speed, w2, atol=1e-9)
    np.testing.assert_allclose(est.disc_acceleration, al2, atol=1e-6)
    np.testing.assert_allclose(est.drive_speed, w2 - twist_rate, atol=1e-9)
    np.testing.assert_allclose(est.friction_torque, eq1a(al2, twist_rate, twist), atol=1e-8)
    with pytest.raises(ValueError):
        est.friction_torque[0] = 1.0  # read-only


def test_estimate_on_sinusoids_and_other_rates():
    f, t = 0.84, np.arange(0.0, 3.0, DT)
    phase = 2 * np.pi * f * t
    th2 = 5.76 * t + 0.3 * np.sin(phase)
    twist = -0.8 - 0.1 * np.cos(phase)
    truth = eq1a(-0.3 * (2 * np.pi * f) ** 2 * np.sin(phase), 0.1 * 2 * np.pi * f * np.sin(phase), twist)
    est = estimate_friction_torque(t, th2, th2 - twist)
    inner = (t > 0.02) & (t < t[-1] - 0.02)
    np.testing.assert_allclose(est.friction_torque[inner], truth[inner], atol=1e-4)  # torque ~ 0.3 N m
    assert np.max(np.abs(est.friction_torque - truth)[inner]) > 1e-9  # a smoother, not an oracle: not exact
    # 200 Hz: the default window keeps 30 ms (7 samples); a given window is rounded to an odd sample count
    coarse = estimate_friction_torque(t[::5], th2[::5], (th2 - twist)[::5])
    assert coarse.window_samples == 7 and coarse.window == pytest.approx(0.03)
    assert estimate_friction_torque(t, th2, th2 - twist, window=0.0504).window_samples == 51


# -------------------------------------------------------------------------------------------- noisy encoders

# Documented in estimate_friction_torque: T_f2 error away from the stick-slip corners, on paper 001's cycle.
# (noise, window, rms bound, max bound) [N m]; measured rms / max: 0.8e-3 / 3.2e-3, 2.0e-3 / 7.3e-3, 3.6e-3 / 1.3e-2
NOISE_CASES = [
    (1e-5, None, 2e-3, 8e-3),
    (("q", 65536), None, 4e-3, 1.5e-2),
    (("q", 4096), 0.08, 7e-3, 2.5e-2),
]


@pytest.mark.parametrize("noise, window, rms_bound, max_bound", NOISE_CASES)
def test_estimate_with_encoder_noise(original, noise, window, rms_bound, max_bound):
    est = estimate_friction_torque(original.t, *angles(original, noise), window=window)
    # corners: stick samples, and the branch switches where dw/dt jumps (N0 > P0 in the Fig. 7 set)
    corner = (np.abs(original.disc_speed) <= 1e-3 * (1 + 1e-9)) | np.r_[False, np.diff(original.mode) != 0]
    near_corner = np.convolve(corner.astype(float), np.ones(2 * est.guard + 1), mode="same") > 0.5
    slip = ~near_corner & (original.t > est.window) & (original.t < original.t[-1] - est.window)
    assert slip.sum() > 0.5 * slip.size
    error = (est.friction_torque - original.friction_force)[slip]
    assert np.sqrt(np.mean(error**2)) < rms_bound
    assert np.max(np.abs(error)) < max_bound
    assert np.max(np.abs(est.disc_speed - original.disc_speed)[slip]) < 0.05


def test_coarse_encoder_needs_a_longer_window(original):
    """A 12-bit encoder at the default 30 ms: the second derivative's noise is ~10 x that at 80 ms."""
    short = estimate_friction_torque(original.t, *angles(original, ("q", 4096)))
    long = estimate_friction_torque(original.t, *angles(original, ("q", 4096)), window=0.08)
    slip = np.abs(original.disc_speed) > 1.0
    error = [np.std((e.friction_torque - original.friction_force)[slip]) for e in (short, long)]
    assert error[0] > 3.0 * error[1]


# --------------------------------------------------------------------------------------- round trip on the rig


@pytest.mark.parametrize("case", ["fig7", "hysteretic"])
def test_round_trip_on_the_rig(original, case):
    law = fig7_law() if case == "fig7" else fs.HystereticFriction(**HYSTERETIC)
    first = original if case == "fig7" else simulate(law)
    tail = first.t > T_END - 10.0
    assert first.disc_speed[tail].min() < 1e-3 and np.mean(np.abs(first.disc_speed[tail]) <= 1e-3) > 0.1  # sticks
    est = estimate_friction_torque(first.t, *angles(first, 1e-5, seed=1))
    fit = est.fit()
    assert fit.guard == est.guard and fit.stick_phases >= 15
    assert fit.breakaway_torque == pytest.approx(law.stick_slope * law.stick_speed, rel=0.02)
    for branch, true in ((fit.accelerating, law.accelerating), (fit.decelerating, law.decelerating)):
        assert branch.r_squared > 0.999 and branch.samples > 5000
        # the fitted surface matches the true one over the sampled region (coefficients trade off along the cycle)
        w = np.linspace(*branch.speed_range, 30)
        al = np.linspace(*branch.acceleration_range, 30)
        gap = BranchFit("true", tuple(true), 1, 0, 0, 0, (0, 0), (0, 0)).torque(w, al) - branch.torque(w, al)
        assert np.sqrt(np.mean(gap**2)) < 0.01
        assert branch.coefficients[0] == pytest.approx(true[0], rel=0.01)
    again = simulate(fit.law)
    (f0, peak0), (f1, peak1) = limit_cycle(first), limit_cycle(again)
    assert f1 == pytest.approx(f0, rel=0.03)
    assert peak1 == pytest.approx(peak0, rel=0.05)


def test_fig7_set_gives_paper_like_stick_slip(original):
    frequency, peak = limit_cycle(original)
    assert 0.83 <= frequency <= 0.84 and 13.5 <= peak <= 14.0  # paper 001: 0.83 / 0.84 Hz, 13.55 / 14 rad/s


# -------------------------------------------------------------------------------------------------- errors

T_OK = np.arange(0.0, 1.0, DT)
TH_OK = 5.0 * T_OK


@pytest.mark.parametrize("kwargs, parameter", [
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK[:-1]), "drive_angle"),
    (dict(t=T_OK[::-1], disc_angle=TH_OK, drive_angle=TH_OK), "t"),
    (dict(t=np.r_[T_OK[:500], T_OK[500:] + 3e-4], disc_angle=TH_OK, drive_angle=TH_OK), "t"),
    (dict(t=T_OK, disc_angle=np.r_[TH_OK[:-1], np.nan], drive_angle=TH_OK), "disc_angle"),
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK, window=0.002), "window"),
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK, window=2.0), "window"),
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK, polyorder=1), "polyorder"),
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK, disc_inertia=0.0), "disc_inertia"),
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK, shaft_stiffness=-1.0), "shaft_stiffness"),
    (dict(t=T_OK, disc_angle=TH_OK, drive_angle=TH_OK, shaft_damping=np.nan), "shaft_damping"),
])
def test_estimate_errors_name_the_parameter(kwargs, parameter):
    with pytest.raises(ValueError, match=parameter) as error:
        estimate_friction_torque(**kwargs)
    assert error.value.parameter == parameter


def fit_inputs():
    return list(synthetic_samples(fs.HystereticFriction(**HYSTERETIC)))


def few_decelerating(arrays):
    """Keep only the first 4 decelerating samples (|w| decreasing: w al < 0)."""
    decelerating = arrays[0] * arrays[1] < 0
    keep = ~decelerating | (np.cumsum(decelerating) <= 4)
    arrays[:] = [a[keep] for a in arrays]


@pytest.mark.parametrize("change, parameter, words", [
    (lambda a, k: a.__setitem__(2, a[2][:-1]), "friction_torque", "as many samples"),
    (lambda a, k: a[1].__setitem__(50, np.inf), "disc_acceleration", "finite"),
    (lambda a, k: k.update(stick_speed=0.0), "stick_speed", "> 0"),
    (lambda a, k: k.update(stick_threshold=-0.1), "stick_threshold", "> 0"),
    (lambda a, k: k.update(acceleration_threshold=-1.0), "acceleration_threshold", ">= 0"),
    (lambda a, k: k.update(guard=-1), "guard", "integer >= 0"),
    (lambda a, k: k.update(branch_gap="ignore"), "branch_gap", "'hold' or 'error'"),
    (lambda a, k: k.update(stick_threshold=1e-9), "disc_speed", "no stick phase"),
    (lambda a, k: few_decelerating(a), "disc_acceleration", "decelerating branch 4 samples; at least 6"),
])
def test_fit_errors_name_the_parameter(change, parameter, words):
    arrays, options = fit_inputs(), dict(guard=0)
    change(arrays, options)
    with pytest.raises(ValueError, match=parameter) as error:
        fit_hysteretic_friction(*arrays, **options)
    assert error.value.parameter == parameter
    assert words in str(error.value)


def test_rank_deficient_branch_is_rejected():
    w, al, torque = fit_inputs()
    # one |al| only on the decelerating branch: al and al^2 are multiples of the constant column
    al = np.where(w * al < 0, -10.0 * np.sign(w), al)
    with pytest.raises(ValueError, match="decelerating branch a rank-deficient design") as error:
        fit_hysteretic_friction(w, al, torque, guard=0)
    assert error.value.parameter == "disc_acceleration"


def test_guard_longer_than_the_record_is_named():
    w = np.linspace(0.5, 5.0, 400)
    al = np.where(np.arange(400) % 2 == 0, 1.0, -1.0)
    with pytest.raises(ValueError, match="guard") as info:
        fit_hysteretic_friction(w, al, np.ones(400), guard=300)
    assert info.value.parameter == "guard"


# ------------------------------------------------------------------------------ NaN / inf never leave a fit (issue 11)
def test_fit_is_exact_on_records_of_any_representable_magnitude():
    """w and al of 1e100, T of 1e200: squares of the design overflowed (NaN coefficients) before; the fit is now done
    in units of each signal's largest value and scales exactly."""
    law = fs.HystereticFriction(**HYSTERETIC)
    w, al, torque = synthetic_samples(law)
    reference = fit_hysteretic_friction(w, al, torque, guard=0)
    big = fit_hysteretic_friction(1e100 * w, 1e100 * al, 1e200 * torque, guard=0, stick_speed=1e-3 * 1e100)
    scale = np.array([1e200, 1e100, 1e100, 1.0, 1.0, 1.0])  # T / (w^i al^j) for 1, w, al, w^2, w al, al^2
    for ours, ref in ((big.accelerating, reference.accelerating), (big.decelerating, reference.decelerating)):
        np.testing.assert_allclose(ours.coefficients, np.array(ref.coefficients) * scale, rtol=1e-9)
        assert ours.r_squared == pytest.approx(ref.r_squared, abs=1e-12)
        assert ours.rmse == pytest.approx(ref.rmse * 1e200, rel=1e-3, abs=1e188)
    assert big.stick_slope == pytest.approx(reference.stick_slope * 1e100, rel=1e-9)


def test_fit_whose_coefficients_overflow_names_the_input():
    w, al, torque = synthetic_samples(fs.HystereticFriction(**HYSTERETIC))
    # T / w^2 = 1e250 / 1e-200: no double holds the w^2 coefficient
    with pytest.raises(fs.InvalidParameterError, match="finite in double precision") as info:
        fit_hysteretic_friction(1e-100 * w, 1e-100 * al, 1e250 * torque, guard=0)
    assert info.value.parameter == "friction_torque"


def test_fit_of_a_constant_branch_says_r_squared_is_undefined():
    # eq 6 with a constant accelerating level: R^2 = 1 - 0/0 there (reported as 1 before)
    law = fs.HystereticFriction(1300.0, accelerating=(0.95, 0, 0, 0, 0, 0), decelerating=HYSTERETIC["decelerating"])
    with pytest.raises(fs.InvalidParameterError, match="accelerating branch must vary.*R\\^2 is undefined") as info:
        fit_hysteretic_friction(*synthetic_samples(law), guard=0)
    assert info.value.parameter == "friction_torque"


def test_estimate_whose_derivatives_overflow_names_the_angle():
    t = np.arange(0.0, 1.0, DT)
    with pytest.raises(fs.InvalidParameterError, match="finite in double precision") as info:  # inf torque before
        estimate_friction_torque(t, 1e305 * np.sin(20 * t), np.zeros_like(t))
    assert info.value.parameter == "disc_angle"
    with pytest.raises(fs.InvalidParameterError, match="finite in double precision") as info:
        estimate_friction_torque(t, np.sin(20 * t), np.sin(20 * t), disc_inertia=1e306)
    assert info.value.parameter == "disc_inertia"
