"""Paper 001's identification of the hysteretic friction law (eq 6) from the torsional rig's encoder angles.

Two steps, as the paper does them (docs/paper001_torsional_rig.md, section 5):

1. :func:`estimate_friction_torque`: the disc friction torque from eq 1a,
   T_f2 = -(J2 al2 + d2 (w2 - w3) + k2 (th2 - th3)), with w and al from a Savitzky-Golay differentiator.
2. :func:`fit_hysteretic_friction`: stick / accelerating / decelerating samples, a linear least-squares
   ``poly22`` fit per slip branch (regressors 1, w, al, w^2, w al, al^2 in MATLAB's order p00 p10 p01 p20 p11
   p02), with the coefficients' standard errors, and the stick slope a = Ts / w_s from the break-away torque
   Ts; returns a ready :class:`frictionsim.HystereticFriction`.

``estimate_friction_torque(...).fit()`` runs both with the fit's ``guard`` matched to the smoothing window.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional, Tuple

import numpy as np
from scipy.signal import savgol_filter

from .._core import HystereticFriction
from ..errors import InvalidParameterError
from ..signal import sampling_rate
from ..validation import require_finite
from .quality import fit_quality
from .validation import finite_vector, sample_times, varying

__all__ = ["FrictionTorqueEstimate", "estimate_friction_torque", "BranchFit", "HystereticFit",
           "fit_hysteretic_friction"]

DEFAULT_WINDOW = 0.03  # s; see estimate_friction_torque
_MIN_STICK_PHASE = 3  # samples; shorter runs below the stick threshold are noise crossings, not stick phases


def reject(function: str, parameter: str, rule: str):
    raise InvalidParameterError(f"{function}: {parameter} {rule}", parameter)


def _number(function: str, name: str, value: Any, allow_zero: bool = False) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        reject(function, name, f"must be a number (got {value!r})")
    if not np.isfinite(value) or value < 0.0 or (value == 0.0 and not allow_zero):
        reject(function, name, f"must be finite and {'>= 0' if allow_zero else '> 0'} (got {value})")
    return value


def _integer(function: str, name: str, value: Any, minimum: int, why: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        reject(function, name, f"must be an integer >= {minimum}{why} (got {value!r})")
    return int(value)


def _frozen(array: np.ndarray) -> np.ndarray:
    array.flags.writeable = False
    return array


@dataclass(frozen=True, eq=False)
class FrictionTorqueEstimate:
    """Eq 1a on a record. Read-only arrays on the time base ``t`` [s]: ``disc_speed`` w2 [rad/s],
    ``drive_speed`` w3 [rad/s], ``disc_acceleration`` al2 [rad/s^2], ``friction_torque`` T_f2 [N m];
    ``window`` [s] is the Savitzky-Golay window used (``window_samples`` samples, degree ``polyorder``)."""

    t: np.ndarray
    disc_speed: np.ndarray
    drive_speed: np.ndarray
    disc_acceleration: np.ndarray
    friction_torque: np.ndarray
    window: float
    window_samples: int
    polyorder: int

    @property
    def guard(self) -> int:
        """window_samples // 2 + 1: the samples on each side of a stick-slip corner that the smoothing mixes."""
        return self.window_samples // 2 + 1

    def fit(self, **options) -> "HystereticFit":
        """:func:`fit_hysteretic_friction` on these samples, with ``guard`` defaulting to :attr:`guard`."""
        options.setdefault("guard", self.guard)
        return fit_hysteretic_friction(self.disc_speed, self.disc_acceleration, self.friction_torque, **options)


def estimate_friction_torque(t, disc_angle, drive_angle, *, disc_inertia: float = 0.0149,
                             shaft_stiffness: float = 0.3659, shaft_damping: float = 0.0167,
                             window: Optional[float] = None, polyorder: int = 3) -> FrictionTorqueEstimate:
    """The disc friction torque from the encoder angles by eq 1a (paper 001's indirect measurement):

        T_f2 = -(J2 al2 + d2 (w2 - w3) + k2 (th2 - th3))

    ``t`` [s] uniformly sampled (steps equal to within 1e-4; resample with ``np.interp`` otherwise);
    ``disc_angle`` th2 and ``drive_angle`` th3 [rad]: disc D2 and the shaft's motor end (after the gear).
    J2 [kg m^2], k2 [N m/rad] and d2 [N m s/rad] default to Table 1.

    Differentiation: ``scipy.signal.savgol_filter`` (local least-squares polynomial of degree ``polyorder`` over
    ``window`` seconds, ``mode="interp"`` at the ends) gives w2 and al2 from th2, and the twist th2 - th3 and
    its rate. Every term passes the same linear filter, so the estimate is the true torque seen through that
    smoother, exact for polynomial angles of degree <= polyorder; the first and last half-window are the least
    accurate. Default window 30 ms (31 samples at 1 kHz; never fewer than polyorder + 2 samples). The choice:
    al2 is a second derivative, its noise falls as window^-2.5, while each stick-slip corner (al2 jumps at
    break-away and at the return to stick) is smeared over one window; 30 ms keeps a corner to 2.5 % of the
    1.2 s stick-slip period and passes the cycle's harmonics (al2 keeps 95 % at the 10th, 8.4 Hz; -3 dB: 22 Hz).
    Measured on paper 001's cycle at 1 kHz, away from the corners: 1e-5 rad Gaussian noise on both angles
    gives T_f2 errors of 0.8 mN m rms (3 mN m max), a 16-bit encoder (q = 2 pi / 65536) 2 mN m rms (7 max);
    a 12-bit encoder (q = 1.5e-3 rad) needs window=0.08 for 4 mN m rms (13 max; 30 ms gives 34 rms, 150 max).

    Raises InvalidParameterError (a ValueError) naming the parameter: lengths differ, t not strictly
    increasing or not uniform, a NaN or infinity, window shorter than polyorder + 2 samples or longer than the
    record, polyorder < 2, J2 <= 0, k2 <= 0, d2 < 0.
    """
    fn = "estimate_friction_torque"
    t = sample_times(t)  # finite, strictly increasing
    if t.size < 5:
        reject(fn, "t", f"must hold at least 5 samples (got {t.size})")
    th2 = finite_vector("disc_angle", disc_angle, t.size)
    th3 = finite_vector("drive_angle", drive_angle, t.size)
    sampling_rate(fn, t, 1e-4)  # Savitzky-Golay needs steps equal to within 1e-4
    dt = (t[-1] - t[0]) / (t.size - 1)
    j2 = _number(fn, "disc_inertia", disc_inertia)
    k2 = _number(fn, "shaft_stiffness", shaft_stiffness)
    d2 = _number(fn, "shaft_damping", shaft_damping, allow_zero=True)
    polyorder = _integer(fn, "polyorder", polyorder, 2, " to give a second derivative")
    minimum = polyorder + 2 + (polyorder % 2 == 0)  # the smallest odd window with > polyorder + 1 samples
    if window is None:
        samples = max(2 * int(round(DEFAULT_WINDOW / (2 * dt))) + 1, minimum)
        if samples > t.size:
            reject(fn, "t", f"must hold at least {samples} samples for the default window (got {t.size})")
    else:
        window = _number(fn, "window", window)
        samples = 2 * int(round(window / (2 * dt))) + 1
        if samples < minimum:
            reject(fn, "window", f"must span at least {minimum} samples ({(minimum - 1) * dt:.6g} "
                                  f"s at dt = {dt:.6g} s); got {window} s = {samples} samples")
        if samples > t.size:
            reject(fn, "window", f"must not be longer than the record ({t.size} samples, {t[-1] - t[0]:.6g} s); "
                                  f"got {window} s = {samples} samples")

    def smooth(x, deriv):
        return savgol_filter(x, samples, polyorder, deriv=deriv, delta=dt, mode="interp")

    twist = th2 - th3  # differentiate the small twist, not th3 (no cancellation of two large angles)
    with np.errstate(over="ignore", invalid="ignore"):  # the finiteness rule below names what overflowed
        w2, al2, twist_rate = smooth(th2, 1), smooth(th2, 2), smooth(twist, 1)
        torque = -(j2 * al2 + d2 * twist_rate + k2 * smooth(twist, 0))
    require_finite(fn, {"disc_speed": w2, "disc_acceleration": al2, "drive_speed": w2 - twist_rate,
                        "friction_torque": torque},
                    {"disc_angle": th2, "drive_angle": th3, "disc_inertia": j2, "shaft_stiffness": k2,
                     "shaft_damping": d2})
    return FrictionTorqueEstimate(_frozen(t.copy()), _frozen(w2), _frozen(w2 - twist_rate), _frozen(al2),
                                  _frozen(torque), float((samples - 1) * dt), samples, polyorder)


@dataclass(frozen=True)
class BranchFit:
    """One slip branch of eq 6 by linear least squares: ``coefficients`` (c00, c10, c01, c20, c11, c02) in SI
    units (``poly22`` order), ``r_squared``, ``rmse`` [N m], ``samples``, ``condition_number`` of the design
    with unit-norm columns (large: w and al too correlated along the cycle to separate the terms), the
    ``speed_range`` [rad/s] and ``acceleration_range`` [rad/s^2] fitted (after the odd extension; outside
    them the polynomial extrapolates), and ``stderr``: the coefficients' least-squares standard errors, the
    square roots of the diagonal of s^2 (X^T X)^-1 with s^2 = SS_res / (m - 6) (inf with m = 6 samples: an exact
    fit leaves no residual to judge them). They assume independent errors; T_f2 from a Savitzky-Golay window is
    correlated over the window, so they understate the spread by up to ~sqrt(window_samples)."""

    name: str
    coefficients: Tuple[float, float, float, float, float, float]
    r_squared: float
    rmse: float
    samples: int
    condition_number: float
    speed_range: Tuple[float, float]
    acceleration_range: Tuple[float, float]
    stderr: Optional[Tuple[float, float, float, float, float, float]] = None

    def torque(self, w, al):
        """The branch polynomial at (w, al) [N m]: no stick band, no branch selection."""
        return _design(np.asarray(w, dtype=float), np.asarray(al, dtype=float)) @ np.asarray(self.coefficients)


@dataclass(frozen=True)
class HystereticFit:
    """Outcome of :func:`fit_hysteretic_friction`: ``law`` (a :class:`frictionsim.HystereticFriction`),
    ``stick_slope`` a [N m s/rad] = ``breakaway_torque`` Ts [N m] / ``stick_speed`` w_s [rad/s], the
    ``accelerating`` and ``decelerating`` :class:`BranchFit`, and the split: ``stick_samples``, ``stick_phases``
    (giving Ts), ``dropped_samples`` (slip samples within ``guard`` of a corner or with |al| below
    ``acceleration_threshold`` [rad/s^2]), ``stick_threshold`` [rad/s]."""

    law: Any
    stick_slope: float
    breakaway_torque: float
    stick_speed: float
    accelerating: BranchFit
    decelerating: BranchFit
    stick_samples: int
    stick_phases: int
    dropped_samples: int
    stick_threshold: float
    acceleration_threshold: float
    guard: int

    def summary(self) -> str:
        """A table of both branches' coefficients with R^2, RMSE, samples and condition numbers."""
        p, n = self.accelerating, self.decelerating
        lines = ["Hysteretic friction (paper 001 eq 6), poly22 least squares per slip branch",
                 f"  stick: a = {self.stick_slope:.6g} N m s/rad = Ts / w_s, Ts = {self.breakaway_torque:.6g} N m "
                 f"(median over {self.stick_phases} stick phases), w_s = {self.stick_speed:.3g} rad/s",
                 f"  samples: {self.stick_samples} stick (|w| <= {self.stick_threshold:.3g} rad/s), "
                 f"{self.dropped_samples} slip dropped (within {self.guard} of a corner or "
                 f"|al| < {self.acceleration_threshold:.3g} rad/s^2)",
                 f"  {'':8}{'accelerating p':>16}{'decelerating n':>16}"]
        lines[-1] += f"{'s.e. p':>12}{'s.e. n':>12}"
        for i, suffix in enumerate(("00", "10", "01", "20", "11", "02")):
            se = "".join(f"{b.stderr[i]:>12.3g}" if b.stderr is not None else f"{'':>12}" for b in (p, n))
            lines.append(f"  {'p/n' + suffix:<8}{p.coefficients[i]:>16.6g}{n.coefficients[i]:>16.6g}{se}")
        for label, attr, fmt in (("R^2", "r_squared", ".6f"), ("RMSE", "rmse", ".4g"), ("samples", "samples", "d"),
                                 ("cond", "condition_number", ".3g")):
            lines.append(f"  {label:<8}{getattr(p, attr):>16{fmt}}{getattr(n, attr):>16{fmt}}")
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.summary()


def _design(w: np.ndarray, al: np.ndarray) -> np.ndarray:
    return np.stack([np.ones_like(w), w, al, w * w, w * al, al * al], axis=-1)


def _fit_branch(name: str, w: np.ndarray, al: np.ndarray, torque: np.ndarray) -> BranchFit:
    fn = "fit_hysteretic_friction"
    if w.size < 6:
        reject(fn, "disc_acceleration", f"leaves the {name} branch {w.size} samples; at least 6 are needed to fit "
                                         f"its 6 coefficients")
    varying("friction_torque", torque, where=f" on the {name} branch")
    # in units of each signal's largest value, so the squares and products below stay in double's range
    units = [float(np.max(np.abs(x))) for x in (w, al, torque)]
    design = _design(w / units[0], al / units[1])
    norms = np.linalg.norm(design, axis=0)
    norms[norms == 0.0] = 1.0
    solution, _, rank, singular = np.linalg.lstsq(design / norms, torque / units[2], rcond=None)
    if rank < 6:
        reject(fn, "disc_acceleration", f"gives the {name} branch a rank-deficient design (rank {rank} of 6): its "
                                         f"{w.size} samples do not vary enough in w and al to separate the 6 terms")
    scaled = design / norms
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # the finiteness rule reports these
        factor = units[2] / norms / _design(np.array(units[0]), np.array(units[1]))  # solution -> SI coefficients
        coefficients = solution * factor
        residual = scaled @ solution - torque / units[2]
        rmse, r_squared = fit_quality(torque / units[2], residual)
        # Cov = s^2 (A^T A)^-1 of the scaled design A = U S V^T: s^2 V S^-2 V^T (no normal equations formed)
        dof = w.size - 6
        _, sv, vt = np.linalg.svd(scaled, full_matrices=False)
        variance = (float(residual @ residual) / dof) * ((vt.T / sv) ** 2).sum(axis=1) if dof else np.full(6, np.inf)
        stderr = np.abs(factor) * np.sqrt(variance)
    return BranchFit(name, tuple(float(c) for c in coefficients), r_squared, rmse * units[2], int(w.size),
                     float(singular[0] / singular[-1]), (float(w.min()), float(w.max())),
                     (float(al.min()), float(al.max())), tuple(float(e) for e in stderr))


def _phase_end_torque(torque: np.ndarray, guard: int) -> float:
    """|T| at the last sample of a stick phase: a line through the end of the phase's interior (clear of the
    smoothed corners) extrapolated over the guard; the largest |T| when the interior is too short."""
    interior = torque[guard:torque.size - guard]
    if interior.size < 3:
        return float(np.max(np.abs(torque)))
    tail = interior[-min(interior.size, max(5, 4 * guard)):]
    slope, intercept = np.polyfit(np.arange(torque.size - guard - tail.size, torque.size - guard), tail, 1)
    return float(abs(slope * (torque.size - 1) + intercept))


def fit_hysteretic_friction(disc_speed, disc_acceleration, friction_torque, *, stick_speed: float = 1e-3,
                            stick_threshold: Optional[float] = None, acceleration_threshold: Optional[float] = None,
                            guard: int = 16, reference_normal_force: float = 35.0,
                            branch_gap: str = "hold") -> HystereticFit:
    """Fit eq 6 to time-ordered samples of w2 [rad/s], al2 [rad/s^2] and T_f2 [N m] (paper 001 section 5).

    * Stick: |w| <= ``stick_threshold``. The model's w_s (``stick_speed``, 1e-3 rad/s in the paper) is far below
      the noise of a speed differentiated from encoder angles, so stick is detected with a larger threshold,
      default 1 % of the largest |w|: 0.14 rad/s on paper 001's cycle, against speed errors of 0.5e-3 rad/s rms
      (1e-5 rad noise) to 5e-3 rad/s rms (12-bit encoder, 80 ms window).
    * Break-away: in stick the friction torque equals the shaft torque, which climbs until it reaches
      Ts = a w_s and the disc slips. Per stick phase (a run of >= 3 stick samples), a line through the end of its
      interior is extrapolated to its last sample (the smoothed corner itself reads low); Ts is the median over
      phases (robust to a phase cut by the record's end). It reads ~0.6 % high on paper 001's cycle: the
      smoothed speed crosses the threshold a few ms after break-away. Then a = Ts / w_s: the slope itself is not
      identifiable (in stick w ~ 0 while T ranges up to Ts).
    * Slip: the odd extension T(w, al) = -T(-w, -al) maps w < 0 onto w > 0, so "accelerating" means |w|
      increasing. Dropped: samples within ``guard`` samples of a corner, i.e. of a stick sample or a change of
      sign of al (al jumps there when the decelerating level lies above the accelerating one), where the
      smoothing mixes both sides (default 16 = half of :func:`estimate_friction_torque`'s default 31-sample
      window + 1; ``estimate.fit()`` matches it to any window; 0 for exact data), and |al| < ``acceleration_threshold``
      (the branch is ambiguous near al = 0; default 2 % of the 99th percentile of |al|). The rest are split by
      the sign of al into accelerating (p) and decelerating (n).
    * Per branch, ``numpy.linalg.lstsq`` on [1, w, al, w^2, w al, al^2] (columns scaled to unit norm), with
      R^2, RMSE and the scaled design's condition number.

    ``reference_normal_force`` [N] (the test's N2) and ``branch_gap`` go to the law. Raises
    InvalidParameterError (a ValueError) naming the parameter: lengths differ, a NaN, a threshold or w_s <= 0,
    a negative guard, no stick phase, fewer than 6 samples (or a rank-deficient design) in a branch.
    """
    fn = "fit_hysteretic_friction"
    w = finite_vector("disc_speed", disc_speed)
    if w.size == 0:
        reject(fn, "disc_speed", "must not be empty")
    al = finite_vector("disc_acceleration", disc_acceleration, w.size, like="disc_speed")
    torque = finite_vector("friction_torque", friction_torque, w.size, like="disc_speed")
    w_s = _number(fn, "stick_speed", stick_speed)
    guard = _integer(fn, "guard", guard, 0, " (samples)")
    if 2 * guard + 1 > w.size:
        reject(fn, "guard", f"must leave the record longer than 2 guard + 1 samples (got {guard} for {w.size} "
                             "samples)")
    if branch_gap not in ("hold", "error"):
        reject(fn, "branch_gap", f"must be 'hold' or 'error' (got {branch_gap!r})")
    if stick_threshold is None:
        stick_threshold = 0.01 * float(np.max(np.abs(w)))
        if stick_threshold == 0.0:
            reject(fn, "disc_speed", "must not be 0 throughout (the default stick_threshold is 1 % of max |w|)")
    stick_threshold = _number(fn, "stick_threshold", stick_threshold)
    if acceleration_threshold is None:
        acceleration_threshold = 0.02 * float(np.percentile(np.abs(al), 99))
    acceleration_threshold = _number(fn, "acceleration_threshold", acceleration_threshold, allow_zero=True)

    stick = np.abs(w) <= stick_threshold
    edges = np.flatnonzero(np.diff(np.concatenate(([0], stick.astype(np.int8), [0]))))
    phases = [(a, b) for a, b in zip(edges[::2], edges[1::2]) if b - a >= _MIN_STICK_PHASE]
    if not phases:
        reject(fn, "disc_speed", f"has no stick phase (no run of >= {_MIN_STICK_PHASE} samples with |w| <= "
                                  f"stick_threshold = {stick_threshold:.6g} rad/s) to give the break-away torque")
    breakaway = float(np.median([_phase_end_torque(torque[a:b], guard) for a, b in phases]))
    if breakaway <= 0.0:
        reject(fn, "friction_torque", "must reach a positive break-away torque in the stick phases (got 0)")
    sign = np.where(w < 0.0, -1.0, 1.0)  # odd extension T(w, al) = -T(-w, -al)
    w, al, torque = sign * w, sign * al, sign * torque
    near_corner = stick
    if guard:  # stick samples and branch changes (al may jump there, e.g. from 0 on p to < 0 on n), widened
        corner = stick.copy()
        corner[1:] |= (al[1:] > 0.0) != (al[:-1] > 0.0)
        near_corner = np.convolve(corner.astype(float), np.ones(2 * guard + 1), mode="same") > 0.5
    kept = ~near_corner & (np.abs(al) >= acceleration_threshold)
    branches = [_fit_branch(name, w[m], al[m], torque[m])
                for name, m in (("accelerating", kept & (al > 0.0)), ("decelerating", kept & (al < 0.0)))]
    require_finite(fn, {"stick_slope": breakaway / w_s, **{f"{b.name} {field}": getattr(b, field) for b in branches
                                                               for field in ("coefficients", "r_squared", "rmse")}},
                    {"disc_speed": w, "disc_acceleration": al, "friction_torque": torque, "stick_speed": w_s})
    law = HystereticFriction(breakaway / w_s, accelerating=branches[0].coefficients,
                             decelerating=branches[1].coefficients, stick_speed=w_s,
                             reference_normal_force=reference_normal_force, branch_gap=branch_gap)
    return HystereticFit(law, breakaway / w_s, breakaway, w_s, branches[0], branches[1], int(stick.sum()),
                         len(phases), int((~stick & ~kept).sum()), stick_threshold, acceleration_threshold, guard)
