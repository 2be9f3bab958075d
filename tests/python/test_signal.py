"""frictionsim.signal against analytic signals: EMD of known sinusoids, sub-bin peak frequencies, cycle means of
smooth and Coulomb (sign-reversing) friction forces, and rejection of bad input."""

import math

import numpy as np
import pytest

from frictionsim import signal


def test_emd_separates_two_sinusoids_and_a_trend():
    # Friction-like record: mean force + slow drift + 17 Hz vibration component + 150 Hz noise tone.
    fs = 2000.0
    t = np.arange(0.0, 2.0, 1.0 / fs)
    slow = 5.0 + 2.0 * t
    vib = 3.0 * np.sin(2 * np.pi * 17.0 * t)
    tone = 1.0 * np.sin(2 * np.pi * 150.0 * t)
    x = slow + vib + tone

    d = signal.emd(t, x)

    # sum c_i + r_n = x: the residue is defined as what the IMFs leave, so only rounding remains.
    assert np.max(np.abs(d.reconstruct() - x)) < 1e-10
    assert d.imfs.shape == (d.n_imfs, t.size) and d.residue.shape == t.shape
    assert d.energy_share.sum() + d.residue_energy_share == pytest.approx(1.0, abs=1e-12)

    # The two most energetic IMFs are the two tones, highest frequency first; 0.05 Hz is 1/10 of the
    # 0.5 Hz FFT bin of the 2 s record (measured error: < 1e-4 Hz).
    top = sorted(np.argsort(d.energy_share)[-2:])
    assert d.frequencies[top[0]] == pytest.approx(150.0, abs=0.05)
    assert d.frequencies[top[1]] == pytest.approx(17.0, abs=0.05)
    # Away from the record ends, where the spline envelopes extrapolate (EMD end effect; here ~4 cycles of
    # 17 Hz), each IMF is its component to 3 % of the 17 Hz amplitude (measured: 0.7 %).
    inner = (t >= 0.25) & (t <= 1.75)
    tol = 0.03 * 3.0
    assert np.max(np.abs(d.imfs[top[0]] - tone)[inner]) < tol
    assert np.max(np.abs(d.imfs[top[1]] - vib)[inner]) < tol
    # Dropping the 150 Hz IMF leaves trend + vibration; keeping only IMFs below 5 Hz leaves the trend.
    assert np.max(np.abs(d.select(fmax=100.0) - (slow + vib))[inner]) < tol
    assert np.max(np.abs(d.select(fmax=5.0) - slow)[inner]) < tol


def test_emd_max_imfs_limits_the_decomposition_and_still_reconstructs():
    t = np.linspace(0.0, 1.0, 2001)
    x = np.sin(2 * np.pi * 17.0 * t) + 0.5 * np.sin(2 * np.pi * 200.0 * t) + t
    d = signal.emd(t, x, max_imfs=1)
    assert d.n_imfs == 1
    assert d.frequencies[0] == pytest.approx(200.0, abs=0.1)
    assert np.max(np.abs(d.reconstruct() - x)) < 1e-10


@pytest.mark.parametrize("duration", [0.7531, 1.2345, 2.9999])
@pytest.mark.parametrize("phase", [0.0, 1.1])
def test_dominant_frequency_of_a_sine_record_with_fractional_cycles(duration, phase):
    # 17 Hz (paper 000, Table 3) sampled at 1 kHz for a non-integer number of cycles, on a mean force.
    t = np.arange(0.0, duration, 1e-3)
    x = 9.27 + 4.0 * np.sin(2 * np.pi * 17.0 * t + phase)
    assert signal.dominant_frequency(t, x) == pytest.approx(17.0, abs=1e-3)


def test_dominant_frequency_band_picks_the_vibration_among_noise():
    t = np.arange(0.0, 1.5, 1e-4)
    x = np.sin(2 * np.pi * 17.0 * t) + 3.0 * np.sin(2 * np.pi * 50.0 * t)  # strong mains-like tone
    assert signal.dominant_frequency(t, x) == pytest.approx(50.0, abs=1e-3)
    assert signal.dominant_frequency(t, x, fmin=10.0, fmax=30.0) == pytest.approx(17.0, abs=1e-3)


@pytest.mark.parametrize("method", ["periodogram", "welch"])
def test_spectrum_amplitude_of_a_sine_on_a_bin(method):
    # 20 Hz on the bin grid of both methods: 1 s periodogram (1 Hz bins), Welch 500-sample segments (2 Hz).
    fs = 1000.0
    t = np.arange(0.0, 1.0, 1.0 / fs)
    x = 2.5 * np.sin(2 * np.pi * 20.0 * t)
    f, a = signal.spectrum(t, x, method=method, nperseg=500)
    assert f[np.argmax(a)] == pytest.approx(20.0)
    assert a.max() == pytest.approx(2.5, rel=1e-9)
    f, p = signal.spectrum(t, x, method=method, scaling="psd", nperseg=500)
    # Parseval: the integrated PSD is the variance A^2 / 2.
    assert np.sum(p) * (f[1] - f[0]) == pytest.approx(2.5**2 / 2, rel=1e-9)


def test_spectrum_amplitude_keeps_the_mean_without_detrending():
    t = np.arange(0.0, 1.0, 1e-3)
    f, a = signal.spectrum(t, 7.0 + np.sin(2 * np.pi * 10.0 * t), detrend=False, window="boxcar")
    assert f[0] == 0.0 and a[0] == pytest.approx(7.0, rel=1e-12)
    assert a[10] == pytest.approx(1.0, rel=1e-12)


def test_cycle_averages_of_mean_plus_sine():
    # F0 + A sin(2 pi f t): over whole cycles the trapezoid sum of the sine cancels exactly (samples divide the
    # period), so every cycle mean is F0 to rounding.
    F0, A, f = 9.27, 4.0, 17.0
    T = 1.0 / f
    t = np.linspace(0.0, 10 * T, 10 * 400 + 1)
    x = F0 + A * np.sin(2 * np.pi * f * t)
    assert signal.cycle_averaged(t, x, T) == pytest.approx(F0, abs=1e-9)
    mid, means = signal.cycle_averages(t, x, T)
    assert means.shape == (10,)
    np.testing.assert_allclose(means, F0, atol=1e-9)
    np.testing.assert_allclose(mid, (np.arange(10) + 0.5) * T, rtol=0, atol=1e-12)
    # The overall mean is the mean of the per-cycle means (equal-length cycles).
    assert signal.cycle_averaged(t, x, T) == pytest.approx(means.mean(), abs=1e-12)


def test_cycle_averages_with_transient_between_samples():
    # Cycle boundaries fall between samples: the piecewise-linear interpolant's error is the only error,
    # |error| <= h^2 / 8 * max|x''| = h^2 / 8 * A (2 pi f)^2 per unit time.
    F0, A, f, h = 2.0, 1.0, 17.0, 1e-4
    T = 1.0 / f
    t = np.arange(0.0, 1.0, h)
    x = F0 + A * np.sin(2 * np.pi * f * t) + 5.0 * np.exp(-t / 0.01)  # decaying start-up transient
    bound = h**2 / 8 * A * (2 * np.pi * f) ** 2
    mid, means = signal.cycle_averages(t, x, T, transient=0.2)
    assert mid.size == math.floor(0.7999 / T)
    np.testing.assert_allclose(means, F0, atol=bound + 5.0 * math.exp(-20.0))
    # cycles=3: the first three cycles after the transient.
    assert signal.cycle_averaged(t, x, T, transient=0.2, cycles=3) == pytest.approx(means[:3].mean(), abs=1e-12)


def test_cycle_averaged_coulomb_friction_vector_effect():
    # Coulomb friction on a body sliding at v_d over a face vibrating with velocity v_a cos(wt):
    # F = mu N sgn(v_d - v_a cos wt); its cycle mean is (2/pi) asin(v_d/v_a) mu N (friction vector effect).
    mu, N, f = 0.4, 90.0, 17.0
    v_d, v_a = 0.2, 0.534
    T = 1.0 / f
    samples_per_cycle = 20000
    t = np.linspace(0.0, 8 * T, 8 * samples_per_cycle + 1)
    F = mu * N * np.sign(v_d - v_a * np.cos(2 * np.pi * f * t))
    exact = 2 / math.pi * math.asin(v_d / v_a) * mu * N
    # Each of the two sign jumps per cycle (height 2 mu N) smeared over one sample spacing h costs at most
    # h * mu N, so the mean is off by at most 2 h / T * mu N.
    tol = 2 * mu * N / samples_per_cycle
    assert signal.cycle_averaged(t, F, T) == pytest.approx(exact, abs=tol)
    _, means = signal.cycle_averages(t, F, T)
    np.testing.assert_allclose(means, exact, atol=tol)
    assert exact < mu * N / 3  # the vibration cuts the mean friction to well below mu N


def _message(excinfo):
    return str(excinfo.value)


@pytest.mark.parametrize(
    "call, parameter",
    [
        (lambda t, x: signal.cycle_averaged(t, x[:-1], 0.1), "x"),
        (lambda t, x: signal.cycle_averaged(t, np.where(t > 0.5, np.nan, x), 0.1), "x"),
        (lambda t, x: signal.cycle_averaged(np.where(t > 0.5, np.nan, t), x, 0.1), "t"),
        (lambda t, x: signal.cycle_averaged(t[::-1], x, 0.1), "t"),
        (lambda t, x: signal.cycle_averaged(t[:1], x[:1], 0.1), "t"),
        (lambda t, x: signal.cycle_averaged(t, x, 0.0), "period"),
        (lambda t, x: signal.cycle_averaged(t, x, -0.1), "period"),
        (lambda t, x: signal.cycle_averaged(t, x, math.nan), "period"),
        (lambda t, x: signal.cycle_averaged(t, x, 2.0), "period"),  # no whole cycle in the 1 s record
        (lambda t, x: signal.cycle_averaged(t, x, 0.1, transient=-1.0), "transient"),
        (lambda t, x: signal.cycle_averaged(t, x, 0.1, transient=1.5), "transient"),
        (lambda t, x: signal.cycle_averaged(t, x, 0.1, cycles=11), "cycles"),
        (lambda t, x: signal.cycle_averaged(t, x, 0.1, cycles=0), "cycles"),
        (lambda t, x: signal.cycle_averages(t, x, 0.1, transient=0.95), "period"),
        (lambda t, x: signal.emd(t ** 2, x), "t"),  # non-uniform sampling
        (lambda t, x: signal.emd(t, x, max_imfs=0), "max_imfs"),
        (lambda t, x: signal.emd(t, x, std_threshold=0.1), "std_threshold"),  # misspelt PyEMD option
        (lambda t, x: signal.emd(t[:3], x[:3]), "t"),
        (lambda t, x: signal.spectrum(t, x, method="fft"), "method"),
        (lambda t, x: signal.spectrum(t, x, scaling="db"), "scaling"),
        (lambda t, x: signal.spectrum(t, x, method="welch", nperseg=10**6), "nperseg"),
        (lambda t, x: signal.dominant_frequency(t, x, fmin=30.0, fmax=20.0), "fmax"),
        (lambda t, x: signal.dominant_frequency(t, x, fmax=1e6), "fmax"),
        (lambda t, x: signal.dominant_frequency(t, np.full_like(t, 3.0)), "x"),
        (lambda t, x: signal.dominant_frequency(np.delete(t, 500), np.delete(x, 500)), "t"),  # a gap
    ],
)
def test_bad_input_names_the_parameter(call, parameter):
    t = np.linspace(0.0, 1.0, 1001)
    x = 1.0 + np.sin(2 * np.pi * 17.0 * t)
    with pytest.raises(ValueError) as excinfo:
        call(t, x)
    assert f" {parameter} must be" in _message(excinfo)
    assert excinfo.value.parameter == parameter  # frictionsim.InvalidParameterError, a ValueError


# ------------------------------------------------------------------------------ NaN / inf never leave (issue 11)
T_UNIFORM = np.linspace(0.0, 1.0, 1001)


@pytest.mark.parametrize("level", [0.3, -7.1])
def test_a_constant_record_has_no_dominant_frequency(level):
    # 0.3: the detrended record is rounding noise, whose peak gave 0.00035 Hz before (3.0 happens to detrend to 0)
    with pytest.raises(ValueError, match="oscillating") as excinfo:
        signal.dominant_frequency(T_UNIFORM, np.full_like(T_UNIFORM, level))
    assert excinfo.value.parameter == "x"


@pytest.mark.parametrize("scale", [1e-300, 1.0, 1e307])
def test_dominant_frequency_does_not_depend_on_the_scale(scale):
    x = scale * np.sin(2 * np.pi * 17.0 * T_UNIFORM)  # 1e307: the FFT overflowed and the record looked empty
    assert signal.dominant_frequency(T_UNIFORM, x) == pytest.approx(17.0, abs=1e-3)


@pytest.mark.parametrize("call, field", [
    (lambda t, x: signal.spectrum(t, x), "spectrum"),
    (lambda t, x: signal.spectrum(t, x, method="welch", scaling="psd"), "spectrum"),
    (lambda t, x: signal.cycle_averages(t, x, 0.1), "means"),
    (lambda t, x: signal.cycle_averaged(t, x, 0.1), "mean"),
    (lambda t, x: signal.emd(t, x, max_imfs=2), "energy_share"),
])
def test_a_result_that_overflows_names_x_instead_of_returning_inf_or_nan(call, field):
    x = 1e308 * np.sin(2 * np.pi * 17.0 * T_UNIFORM)  # finite samples; their sums and squares are not
    with pytest.raises(ValueError, match=f"finite in double precision.*{field}") as excinfo:
        call(T_UNIFORM, x)
    assert excinfo.value.parameter == "x"
