"""Signal processing for friction-force records, as paper 000 processes its measured forces.

Paper 000 (axial vibrating-sliding rig, section 2.4.2) decomposes the measured friction force x(t) with
Empirical Mode Decomposition into intrinsic mode functions c_i(t) and a residue r_n(t),
x(t) = sum_i c_i(t) + r_n(t), then applies an FFT to each IMF to find its frequency content; Table 4 reports
F_df, "the average sliding friction force in a vibration cycle". This module provides:

* :func:`emd` - EMD through PyEMD (cubic-spline envelopes, as in the paper), with each IMF's dominant
  frequency and energy share; :meth:`Decomposition.select` rebuilds the signal from IMFs in a frequency band
  (e.g. dropping high-frequency electrical noise).
* :func:`spectrum` and :func:`dominant_frequency` - one-sided spectra (SciPy) and a sub-bin peak frequency.
* :func:`cycle_averages` and :func:`cycle_averaged` - means over whole vibration cycles (F_df).

Pure Python (NumPy, SciPy; PyEMD for :func:`emd` only, from the optional extra ``signal``); it does not need
the compiled engine. Times are in s, frequencies in Hz,
and x in any unit (N for forces). Bad input raises :class:`frictionsim.InvalidParameterError` (a ValueError)
whose ``parameter`` attribute and message name the parameter, and whose message states the rule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np
import scipy.signal

from . import _core
from .errors import InvalidParameterError
from .validation import require_finite

__all__ = [
    "Decomposition",
    "emd",
    "spectrum",
    "dominant_frequency",
    "cycle_averages",
    "cycle_averaged",
]

def _reject(owner: str, parameter: str, rule: str, value: object) -> None:
    # Same error class and message shape as the engine's: "owner: name must be rule (got value)".
    raise InvalidParameterError(f"{owner}: {parameter} must be {rule} (got {value})", parameter)


def _finite(owner: str, x: np.ndarray, **results) -> None:
    """NaN or inf never leaves: x was finite, so its magnitudes overflowed (the fits' rule, named x)."""
    require_finite(owner, results, {"x": x})


def _samples(owner: str, t, x, *, min_samples: int = 2) -> Tuple[np.ndarray, np.ndarray]:
    """Validate a record (t, x): 1-D, same length, finite, t strictly increasing."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    if t.ndim != 1:
        _reject(owner, "t", "a 1-D array", f"shape {t.shape}")
    if x.ndim != 1:
        _reject(owner, "x", "a 1-D array", f"shape {x.shape}")
    if x.size != t.size:
        _reject(owner, "x", f"the same length as t ({t.size} samples)", f"{x.size} samples")
    if t.size < min_samples:
        _reject(owner, "t", f"at least {min_samples} samples long", f"{t.size} samples")
    if not np.all(np.isfinite(t)):
        _reject(owner, "t", "finite (no NaN or inf)", f"non-finite sample {int(np.argmin(np.isfinite(t)))}")
    if not np.all(np.isfinite(x)):
        _reject(owner, "x", "finite (no NaN or inf)", f"non-finite sample {int(np.argmin(np.isfinite(x)))}")
    dt = np.diff(t)
    if not np.all(dt > 0.0):
        i = int(np.argmin(dt > 0.0)) + 1
        _reject(owner, "t", "strictly increasing", f"t[{i}] = {t[i]!r} after t[{i - 1}] = {t[i - 1]!r}")
    return t, x


def sampling_rate(owner: str, t: np.ndarray, rtol: float) -> float:
    """Sampling rate f_s = 1/dt [Hz] of uniformly sampled times.

    EMD (index-based extrema) and the FFT assume equal spacing, so a record from an adaptive-step solver must
    be sampled on a grid first (simulate(..., output_times=np.linspace(...)) or np.interp).
    """
    if not (rtol >= 0.0):
        _reject(owner, "uniform_rtol", ">= 0", rtol)
    dt = np.diff(t)
    # The mean spacing from the end points is immune to rounding in the individual differences.
    mean_dt = (t[-1] - t[0]) / (t.size - 1)
    worst = float(np.max(np.abs(dt - mean_dt)))
    if worst > rtol * mean_dt:
        _reject(owner, "t", f"uniformly sampled (spacing within uniform_rtol = {rtol:g} of the mean "
                "spacing; resample with np.interp or simulate(output_times=...))",
                f"spacing deviates by {worst / mean_dt:.3g} of the mean")
    return 1.0 / mean_dt


def _peak_frequency(x: np.ndarray, fs: float, *, fmin: Optional[float], fmax: Optional[float],
                    zero_pad: int, detrend: str) -> float:
    """Sub-bin frequency [Hz] of the largest spectral peak of x in [fmin, fmax]; NaN if x has no content above
    rounding (an oscillation below ~16 eps of x's size: a constant record's detrended rounding errors).

    Hann window, zero padding to >= zero_pad * len(x) points (a finer grid for the search), then a parabola
    through the log-magnitudes of the peak bin and its neighbours: the Hann main lobe is close to a Gaussian,
    whose log is exactly a parabola, so the vertex lands well inside a bin.
    """
    size = float(np.max(np.abs(x)))
    x = x / size if size > 0.0 else x  # the frequency does not depend on the scale; the FFT overflowed at 1e308
    rounding = 4.0 * np.finfo(float).eps * x.size  # relative to x's size: a sine of amplitude A peaks at ~A n/4
    if detrend != "none":
        x = scipy.signal.detrend(x, type=detrend)
    n = x.size
    nfft = 1 << max(1, math.ceil(math.log2(zero_pad * n)))
    mag = np.abs(np.fft.rfft(x * np.hanning(n), nfft))
    freqs = np.fft.rfftfreq(nfft, 1.0 / fs)
    band = np.ones(freqs.size, dtype=bool)
    band[0] = fmin is not None and fmin <= 0.0  # DC is the mean, not an oscillation, unless asked for
    if fmin is not None:
        band &= freqs >= fmin
    if fmax is not None:
        band &= freqs <= fmax
    if not band.any() or not np.any(mag[band] > rounding):
        return math.nan
    k = int(np.flatnonzero(band)[np.argmax(mag[band])])
    if k == 0 or k == mag.size - 1 or np.any(mag[k - 1:k + 2] <= 0.0):
        return float(freqs[k])  # no neighbour on one side: the bin frequency is the best estimate
    a, b, c = np.log(mag[k - 1:k + 2])
    offset = 0.5 * (a - c) / (a - 2.0 * b + c)  # vertex of the parabola, in bins, within [-0.5, 0.5]
    return float((k + offset) * fs / nfft)


# --------------------------------------------------------------------------------------------------------------
# Empirical Mode Decomposition
# --------------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Decomposition:
    """EMD of a uniformly sampled signal x(t): x = sum_i c_i + r_n (paper 000, section 2.4.2).

    Attributes
    ----------
    t : (N,) sample times [s].
    imfs : (n_imfs, N) intrinsic mode functions c_i, highest frequency first, same unit as x.
    residue : (N,) residue r_n (the slowly varying part left after the last IMF), same unit as x.
    frequencies : (n_imfs,) dominant frequency of each IMF [Hz] (:func:`dominant_frequency`); NaN for an IMF
        without oscillating content.
    energy_share : (n_imfs,) sum(c_i^2) / (sum_j sum(c_j^2) + sum(r_n^2)): each IMF's share of the total
        energy (IMFs are only nearly orthogonal, so shares of x's own energy would not add up to 1).
    residue_energy_share : the residue's share in the same normalisation; energy_share.sum() plus this is 1.
    """

    t: np.ndarray
    imfs: np.ndarray
    residue: np.ndarray
    frequencies: np.ndarray
    energy_share: np.ndarray
    residue_energy_share: float

    @property
    def n_imfs(self) -> int:
        return int(self.imfs.shape[0])

    def reconstruct(self) -> np.ndarray:
        """sum_i c_i + r_n: the original signal up to floating-point rounding."""
        return self.imfs.sum(axis=0) + self.residue

    def select(self, fmin: Optional[float] = None, fmax: Optional[float] = None, *,
               include_residue: bool = True) -> np.ndarray:
        """Partial reconstruction: sum of the IMFs whose dominant frequency lies in [fmin, fmax] Hz.

        E.g. ``select(fmax=100.0)`` drops IMFs above 100 Hz (electrical and ambient noise in paper 000) and
        keeps the vibration-cycle content and the residue (the slow trend). IMFs with NaN frequency are left
        out unless no bound is given.
        """
        lo = -math.inf if fmin is None else fmin
        hi = math.inf if fmax is None else fmax
        if not lo <= hi:
            _reject("Decomposition.select", "fmax", f">= fmin ({fmin})", fmax)
        f = self.frequencies
        keep = (f >= lo) & (f <= hi) if (fmin is not None or fmax is not None) else np.ones(f.size, bool)
        out = self.imfs[keep].sum(axis=0)
        return out + self.residue if include_residue else out


def _pyemd_emd():
    """PyEMD's EMD class, imported on first use (only emd() needs it, and importing it costs time).

    PyEMD comes with the optional extra ``signal`` (the EMD-signal distribution): without it, an ImportError
    that names the extra, not PyEMD's bare ModuleNotFoundError.
    """
    try:
        from PyEMD import EMD
    except ImportError as error:
        raise ImportError(
            "frictionsim.signal.emd needs PyEMD, which comes with the optional extra 'signal': "
            "pip install 'frictionsim[signal]' (or pip install EMD-signal)", name="PyEMD") from error
    return EMD


def emd(t, x, *, max_imfs: Optional[int] = None, sd_threshold: float = 0.3, spline: str = "cubic",
        uniform_rtol: float = 1e-6, **pyemd_options) -> Decomposition:
    """Empirical Mode Decomposition of a uniformly sampled signal x(t) with PyEMD.

    Parameters
    ----------
    t : sample times [s], strictly increasing and uniform to ``uniform_rtol`` (relative spacing deviation).
    x : signal samples, e.g. friction force F_f [N].
    max_imfs : at most this many IMFs (None: until PyEMD's end condition; the rest stays in the residue).
    sd_threshold : the paper's sifting stop SD = sqrt(sum((h_prev - h)^2 / h_prev^2)) < 0.3. It is passed to
        PyEMD as ``std_thr = sd_threshold**2`` (PyEMD's test is the unsquared-root sum, normalised by the new
        rather than the previous proto-IMF). PyEMD also stops sifting on its scaled-variance and energy-ratio
        tests; tune them through ``pyemd_options`` (svar_thr, energy_ratio_thr, FIXE, ...).
    spline : envelope interpolation, "cubic" as in the paper (PyEMD also offers "akima", "pchip", ...).
    pyemd_options : further keyword arguments for ``PyEMD.EMD``.

    Returns
    -------
    Decomposition with IMFs c_i, residue r_n, and each IMF's dominant frequency [Hz] and energy share.

    Raises
    ------
    ImportError
        PyEMD is not installed: it comes with the optional extra ``signal`` (``pip install 'frictionsim[signal]'``).
    """
    EMD = _pyemd_emd()

    owner = "emd"
    t, x = _samples(owner, t, x, min_samples=4)
    fs = sampling_rate(owner, t, uniform_rtol)
    if max_imfs is not None and not (isinstance(max_imfs, (int, np.integer)) and max_imfs >= 1):
        _reject(owner, "max_imfs", "None or an integer >= 1", max_imfs)
    if not (sd_threshold > 0.0 and math.isfinite(sd_threshold)):
        _reject(owner, "sd_threshold", "finite and > 0", sd_threshold)

    options = {"std_thr": sd_threshold ** 2, **pyemd_options}
    decomposer = EMD(spline_kind=spline, **options)
    # PyEMD takes any keyword and ignores the ones it does not know: a misspelt option must not pass silently.
    unknown = sorted(k for k in pyemd_options if not hasattr(decomposer, k))
    if unknown:
        _reject(owner, unknown[0], "an option of PyEMD.EMD", pyemd_options[unknown[0]])
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is named by _finite below
        # Sampling is uniform, so PyEMD's index-based extrema detection equals a time-based one.
        decomposer.emd(x, t, max_imf=-1 if max_imfs is None else int(max_imfs))
        imfs, _ = decomposer.get_imfs_and_residue()
        imfs = np.atleast_2d(np.asarray(imfs, dtype=float)).reshape(-1, x.size)
        residue = x - imfs.sum(axis=0)  # defined this way so that sum(c_i) + r_n = x up to rounding
        energies = np.sum(imfs ** 2, axis=1)
        residue_energy = float(np.sum(residue ** 2))
        total = energies.sum() + residue_energy
        shares = energies / total if total > 0.0 else np.zeros_like(energies)
    _finite(owner, x, imfs=imfs, residue=residue, energy_share=shares)
    freqs = np.array([_peak_frequency(c, fs, fmin=None, fmax=None, zero_pad=8, detrend="constant")
                      for c in imfs])
    return Decomposition(t=t, imfs=imfs, residue=residue, frequencies=freqs, energy_share=shares,
                         residue_energy_share=residue_energy / total if total > 0.0 else 0.0)


# --------------------------------------------------------------------------------------------------------------
# Spectra
# --------------------------------------------------------------------------------------------------------------

def spectrum(t, x, *, method: str = "periodogram", scaling: str = "amplitude", window="hann",
             detrend="constant", nperseg: Optional[int] = None,
             uniform_rtol: float = 1e-6) -> Tuple[np.ndarray, np.ndarray]:
    """One-sided spectrum of a uniformly sampled signal x(t) (the paper's FFT of the IMFs).

    Parameters
    ----------
    method : "periodogram" (one windowed FFT of the whole record, finest resolution) or "welch" (averaged
        over overlapping segments of ``nperseg`` samples: less noisy, coarser).
    scaling : "amplitude" - peak amplitude per frequency, in x's unit (a sine A sin(2 pi f t) on a bin gives
        A; the DC bin gives the mean if ``detrend`` is False); or "psd" - power spectral density [unit^2/Hz].
    window, detrend : passed to SciPy (detrend "constant" removes the mean, False keeps it).

    Returns
    -------
    (frequencies [Hz], amplitude [unit] or PSD [unit^2/Hz]).
    """
    owner = "spectrum"
    t, x = _samples(owner, t, x, min_samples=4)
    fs = sampling_rate(owner, t, uniform_rtol)
    if scaling not in ("amplitude", "psd"):
        _reject(owner, "scaling", '"amplitude" or "psd"', repr(scaling))
    scipy_scaling = "spectrum" if scaling == "amplitude" else "density"
    if method == "welch" and nperseg is not None and not (isinstance(nperseg, (int, np.integer))
                                                          and 4 <= nperseg <= x.size):
        _reject(owner, "nperseg", f"None or an integer in [4, {x.size}]", nperseg)
    if method not in ("periodogram", "welch"):
        _reject(owner, "method", '"periodogram" or "welch"', repr(method))
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is named by _finite below
        if method == "periodogram":
            f, p = scipy.signal.periodogram(x, fs, window=window, detrend=detrend, scaling=scipy_scaling)
        else:
            f, p = scipy.signal.welch(x, fs, window=window, detrend=detrend, scaling=scipy_scaling,
                                      nperseg=nperseg if nperseg is not None else min(256, x.size))
    _finite(owner, x, spectrum=p)
    if scaling == "psd":
        return f, p
    # SciPy's one-sided power spectrum holds A^2/2 for a sine (its negative-frequency half folded in) but the
    # plain mean^2 at DC and at an even-length Nyquist bin, which have no mirror image.
    amp = np.sqrt(2.0 * p)
    amp[0] = math.sqrt(p[0])
    if np.isclose(f[-1], 0.5 * fs, rtol=1e-12, atol=0.0):
        amp[-1] = math.sqrt(p[-1])
    return f, amp


def dominant_frequency(t, x, *, fmin: Optional[float] = None, fmax: Optional[float] = None,
                       zero_pad: int = 8, detrend: str = "constant", uniform_rtol: float = 1e-6) -> float:
    """Frequency [Hz] of the strongest oscillation of x(t) in [fmin, fmax], with sub-bin accuracy.

    The record is detrended ("constant": mean removed, "linear", or "none"), Hann-windowed and zero-padded to
    at least ``zero_pad`` times its length; a parabola through the log-magnitudes around the largest peak
    places it between grid points. Measured on a clean sine with the defaults: error < 2e-4 of the FFT bin
    width fs/N from 8 cycles in the record up, ~2e-3 bin with 3.4 cycles (leakage from the mirror image at
    -f grows as the record shortens). DC is excluded unless ``fmin <= 0`` is given. For the vibration frequency of the
    axial rig (f = 15-20 Hz in paper 000) pass a band around it to ignore noise peaks.

    Raises ValueError if the band holds no spectral content (e.g. a constant signal).
    """
    owner = "dominant_frequency"
    t, x = _samples(owner, t, x, min_samples=4)
    fs = sampling_rate(owner, t, uniform_rtol)
    if not (isinstance(zero_pad, (int, np.integer)) and zero_pad >= 1):
        _reject(owner, "zero_pad", "an integer >= 1", zero_pad)
    if detrend not in ("constant", "linear", "none"):
        _reject(owner, "detrend", '"constant", "linear" or "none"', repr(detrend))
    for name, value in (("fmin", fmin), ("fmax", fmax)):
        if value is not None and not (math.isfinite(value) and 0.0 <= value <= 0.5 * fs):
            _reject(owner, name, f"None or in [0, fs/2 = {0.5 * fs:g}] Hz", value)
    if fmin is not None and fmax is not None and not fmax > fmin:
        _reject(owner, "fmax", f"> fmin ({fmin})", fmax)
    f = _peak_frequency(x, fs, fmin=fmin, fmax=fmax, zero_pad=int(zero_pad), detrend=detrend)
    if math.isnan(f):
        _reject(owner, "x", "oscillating within [fmin, fmax] (its spectrum there is zero to rounding)",
                f"fmin={fmin}, fmax={fmax}")
    return f


# --------------------------------------------------------------------------------------------------------------
# Cycle averages (F_df of paper 000, Table 4)
# --------------------------------------------------------------------------------------------------------------

def _cycle_bounds(owner: str, t: np.ndarray, period: float, transient: float,
                  cycles: Optional[int]) -> np.ndarray:
    """Boundaries t_a, t_a + T, ..., t_b of whole cycles after the transient: the engine's window rule
    (whole_cycle_window, include/frictionsim/analysis/cycle_mean.hpp), so Result.mean_over_cycles agrees."""
    if cycles is not None and not (isinstance(cycles, (int, np.integer)) and cycles >= 1):
        _reject(owner, "cycles", "None or an integer >= 1", cycles)
    start, end, n = _core.whole_cycle_window(float(t[0]), float(t[-1]), period, transient, int(cycles or 0))
    bounds = start + period * np.arange(n + 1)
    bounds[-1] = end  # the engine clamps an end past t_last by rounding only
    return bounds


def _running_integral(t: np.ndarray, x: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """int_{t_0}^{tau} of the piecewise-linear interpolant of (t, x): the trapezoid rule, exact at partial
    segments, so cycle boundaries between samples cost nothing beyond the interpolation itself."""
    cum = np.concatenate(([0.0], np.cumsum(0.5 * np.diff(t) * (x[1:] + x[:-1]))))
    k = np.clip(np.searchsorted(t, tau, side="right") - 1, 0, t.size - 2)
    x_tau = np.interp(tau, t, x)
    return cum[k] + 0.5 * (tau - t[k]) * (x[k] + x_tau)


def cycle_averages(t, x, period: float, *, transient: float = 0.0,
                   cycles: Optional[int] = None) -> Tuple[np.ndarray, np.ndarray]:
    """Mean of x over each whole vibration cycle after a transient.

    Cycle k covers [t_a + k T, t_a + (k+1) T] with t_a = t[0] + transient and T = ``period`` [s] (1/f for
    the vibration frequency f); its mean is the trapezoid integral of x (piecewise-linear between samples)
    divided by T. ``cycles`` None takes every whole cycle that fits; an integer asks for exactly that many.
    Samples need not be uniform. A discontinuous x (Coulomb friction reversing sign) costs at most
    jump * spacing / T per jump.

    Returns
    -------
    (cycle mid-times [s], per-cycle means [unit of x]).
    """
    owner = "cycle_averages"
    t, x = _samples(owner, t, x)
    bounds = _cycle_bounds(owner, t, float(period), float(transient), cycles)
    with np.errstate(over="ignore", invalid="ignore"):
        means = np.diff(_running_integral(t, x, bounds)) / np.diff(bounds)
    _finite(owner, x, means=means)
    return 0.5 * (bounds[1:] + bounds[:-1]), means


def cycle_averaged(t, x, period: float, transient: float = 0.0, cycles: Optional[int] = None) -> float:
    """Mean of x over whole vibration cycles after a transient: F_df of paper 000 (Table 4, "average sliding
    friction force in a vibration cycle") when x is the friction force F_f [N] and period = 1/f [s].

    The window is [t_a, t_a + n T] with t_a = t[0] + transient and n = ``cycles`` (None: as many whole cycles
    as fit), integrated with the trapezoid rule as in :func:`cycle_averages`. Same window rule as the engine's
    Result.mean_over_cycles, which differences the solver-integrated friction impulse instead and so stays
    exact where the sampled force jumps.
    """
    owner = "cycle_averaged"
    t, x = _samples(owner, t, x)
    bounds = _cycle_bounds(owner, t, float(period), float(transient), cycles)
    mean = _core.mean_over_window(t, x, bounds[0], bounds[-1])
    _finite(owner, x, mean=mean)
    return mean
