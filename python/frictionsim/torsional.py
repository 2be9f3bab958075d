"""The torsional drill-string rig of paper 001: the Fig. 7 friction sets, limit-cycle measures, the comparison of
friction laws, and the stick-slip map over reference speed and normal force.

Paper 001 prints no friction coefficients (eq 6 is identified from its rig's data and the values are not given),
so the sets here are **chosen**, each documented: the hysteretic law of eq 6 was tuned (Nelder-Mead on two
numbers, the break-away torque a w_s and the acceleration coefficient p01 = n01) so that the rig of Tables 1-2 at
w_ref = 5.76 rad/s, N2 = 35 N reproduces Fig. 7: fully developed stick-slip, disc speed never negative,
0.835 Hz and a peak disc speed of 13.8 rad/s. The laws of speed alone got the same treatment on their static
coefficient (peak 13.8 rad/s where they can reach it). They show the physics the paper's model relies on: with
friction a function of speed alone, the stick-slip frequency stays below the disc-on-shaft natural frequency
sqrt(k2/J2)/2 pi = 0.789 Hz; the negative acceleration coefficient of eq 6 (p01 = -0.00315 kg m^2, 21 % of J2)
lowers the disc's effective inertia during slip, which is how the paper's model reaches 0.84 Hz.

    >>> import frictionsim as fs
    >>> rig = fs.TorsionalRig(fs.torsional.fig7_friction())
    >>> result = fs.simulate(rig, 40.0, output_times=np.arange(0, 40, 1e-3))
    >>> fs.torsional.limit_cycle(result, transient=20.0)
    LimitCycle(frequency=0.835 Hz, peak=13.8 rad/s, ...)
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, Dict, Optional, Sequence

import numpy as np

from . import _core
from .data import PAPER001_FIG7
from .errors import InvalidParameterError
from ._core import Coulomb, Dahl, LuGre, Stribeck, TorsionalRig
from .simulation import SOLVER_DEFAULTS, simulate

__all__ = ["FIG7", "LimitCycle", "StickSlipMap", "compare_laws", "fig7_friction", "fig7_laws", "limit_cycle",
           "severity_index", "simulate_fig7", "stick_slip_map", "stick_slip_point"]

#: Paper 001, Fig. 7 (measured / simulated): stick-slip frequency [Hz] and peak disc speed [rad/s].
FIG7 = PAPER001_FIG7

def fig7_friction(branch_gap: str = "hold") -> "_core.HystereticFriction":
    """The eq 6 friction law chosen to reproduce paper 001's Fig. 7 (C++ ``paper001_fig7_friction``):

    p = (0.95, -0.02, -0.00315, 0.0005, 0, 2e-5), n = (0.98, -0.02, -0.00315, 0.0005, 0, 0) in SI units,
    stick slope 1378 N m s/rad with w_s = 1e-3 rad/s (break-away 1.378 N m), at N_ref = 35 N. A Stribeck-like
    level falling with speed (p10 < 0: velocity weakening; with the shaft damping steady rotation at 5.76 rad/s
    is still barely stable, and stick-slip is the large-amplitude cycle reached from rest), the decelerating
    branch 0.03 N m above the accelerating one (Fig. 5a's loop; both branches consistent at dw/dt = 0, so no gap
    rule is needed here; the jump of dw/dt at each branch change keeps a small oscillation alive where the disc
    does not stick, which is why the map's non-sticking points still oscillate by a few %), and the tuned
    acceleration coefficient. Valid for N2 < 163 N: the coefficients scale with N2 / 35 N, and beyond that p01
    cancels the disc's inertia (the run then stops, saying so).
    """
    return _core.paper001_fig7_friction(branch_gap)


def fig7_laws() -> Dict[str, Any]:
    """Every friction law on the disc, set for the Fig. 7 operating point (contact radius 0.1 m, N2 = 35 N).

    The kinetic levels match eq 6's (about 0.95 N m at low speed: mu = 0.2714 for Coulomb; 0.22 with a
    Stribeck fall over v_s = 0.3 m/s, i.e. 3 rad/s); the static coefficient was tuned for a 13.8 rad/s peak.
    Coulomb cannot sustain stick-slip below mu_static ~ 0.49 (the shaft damping wins), so it gets 0.5; Dahl has
    no static peak and gives none at all: both are reported as what they are.
    """
    return {
        "hysteretic (eq 6)": fig7_friction(),
        "Coulomb": Coulomb(mu=0.2714, mu_static=0.5),
        "Stribeck": Stribeck(mu=0.22, mu_static=0.3566, stribeck_velocity=0.3, shape_exponent=1.0),
        "Karnopp": Stribeck(mu=0.22, mu_static=0.3567, stribeck_velocity=0.3, shape_exponent=1.0,
                            karnopp_band=1e-4),
        "LuGre": LuGre(mu=0.22, mu_static=0.3453, stribeck_velocity=0.3, bristle_stiffness=1e5,
                       bristle_damping=300.0),
        "Dahl": Dahl(mu=0.2714, tangential_stiffness=1e4),
    }


@dataclass(frozen=True)
class LimitCycle:
    """Limit-cycle measures of a speed signal over whole cycles after a transient.

    cycles: whole cycles found (0: no oscillation about the level, the other figures then cover the whole
    window); period [s] (inf when cycles == 0); frequency [Hz] (0 then); peak, trough and mean speed [rad/s];
    stick_fraction: share of the time with |w| <= stick_speed; level: the crossing level [rad/s]; start, end [s]:
    the window measured (first and last upward crossing of the level).
    """

    cycles: int
    period: float
    frequency: float
    peak: float
    trough: float
    mean: float
    stick_fraction: float
    level: float
    start: float
    end: float

    @property
    def stick_slip(self) -> bool:
        """Does the disc stick in the cycle (a limit cycle that touches |w| <= stick_speed)?"""
        return self.cycles > 0 and self.stick_fraction > 0.0

    @property
    def severity(self) -> float:
        """Stick-slip severity index [-]: peak-to-peak speed over twice the mean speed, (peak - trough) / (2 |mean|),
        the measure drilling reports torsional stick-slip by (half the speed's swing against its mean): A/m for a
        sinusoid of mean m and amplitude A, 1 or more once the speed swings down to rest and back (a cycle from
        rest to a peak P has P / (2 mean)). 0 when the speed does not move; inf for a swing about a zero mean."""
        return severity_index(self.peak, self.trough, self.mean)

    def __repr__(self) -> str:
        return (f"LimitCycle(frequency={self.frequency:.4g} Hz, peak={self.peak:.4g} rad/s, "
                f"trough={self.trough:.3g} rad/s, stick_fraction={self.stick_fraction:.3f}, cycles={self.cycles})")


def severity_index(peak, trough, mean):
    """(peak - trough) / (2 |mean|) elementwise (see :attr:`LimitCycle.severity`); NaN stays NaN (a failed run)."""
    peak, trough, mean = (np.asarray(x, dtype=float) for x in (peak, trough, mean))
    swing = peak - trough
    with np.errstate(divide="ignore", invalid="ignore"):
        index = np.where(swing == 0.0, 0.0, swing / (2.0 * np.abs(mean)))
    return float(index) if index.ndim == 0 else index


def limit_cycle(result, transient: float = 0.0, *, speed: str = "disc_speed", level: Optional[float] = None,
                stick_speed: float = 1e-2, hysteresis: float = 0.05, min_amplitude: float = 1e-2) -> LimitCycle:
    """Limit cycle of ``result[speed]`` after ``transient`` seconds (C++ ``analysis/limit_cycle.hpp``).

    ``result`` is a :class:`frictionsim.Result` or a pair ``(t, w)`` of arrays (e.g. measured data). Cycles are
    delimited by upward crossings of ``level`` (default: the mean speed), re-armed only after the signal fell
    ``hysteresis`` x (peak - trough) below it, so noise does not split cycles. ``stick_speed`` [rad/s]: |w| at or
    below it counts as stuck (default 0.01 rad/s, 0.2 % of the paper's 5.76 rad/s: above the creep of eq 6's
    stick band and of LuGre's presliding, far below slip speeds). A speed whose peak-to-trough range stays
    below ``min_amplitude`` [rad/s] (default 0.01) is steady rotation: cycles == 0, frequency 0.
    """
    if isinstance(result, tuple):
        t, w = result
    else:
        t, w = result.t, result[speed]
    values = _core.limit_cycle(np.asarray(t, dtype=float), np.asarray(w, dtype=float), float(transient),
                               None if level is None else float(level), float(stick_speed), float(hysteresis),
                               float(min_amplitude))
    return LimitCycle(**values)


def simulate_fig7(friction=None, t_end: float = 40.0, *, sample_time: float = 1e-3, method: str = "automatic",
                  rtol: float = SOLVER_DEFAULTS.rtol, **rig_params: Any):
    """Simulate the rig (defaults: Fig. 7's operating point and :func:`fig7_friction`) from rest to ``t_end``
    [s], sampled every ``sample_time`` [s]; returns ``(rig, result)``."""
    rig = TorsionalRig(fig7_friction() if friction is None else friction, **rig_params)
    if not (np.isfinite(t_end) and t_end > 0):
        raise InvalidParameterError(f"simulate_fig7: t_end must be positive and finite (got {t_end!r})", "t_end")
    if not (np.isfinite(sample_time) and 0 < sample_time <= t_end):
        raise InvalidParameterError(f"simulate_fig7: sample_time must be in (0, t_end] (got {sample_time!r})",
                                    "sample_time")
    n = int(np.floor(t_end / sample_time * (1 + 1e-12)))  # samples at k dt up to t_end; t_end itself too
    times = np.minimum(np.arange(n + 1) * sample_time, t_end)
    if times[-1] < t_end:
        times = np.append(times, t_end)
    result = simulate(rig, t_end, output_times=np.unique(times), method=method, rtol=rtol)
    return rig, result


def compare_laws(laws: Optional[Dict[str, Any]] = None, *, t_end: float = 40.0, transient: float = 20.0,
                 **rig_params: Any):
    """Limit cycle of the rig with each law (default :func:`fig7_laws`) at Fig. 7's operating point: a pandas
    DataFrame with one row per law (frequency [Hz], peak / trough speed [rad/s], stick fraction, steps)."""
    import pandas as pd

    rows = []
    for name, law in (fig7_laws() if laws is None else laws).items():
        rig, result = simulate_fig7(law, t_end, **rig_params)
        cycle = limit_cycle(result, transient)
        rows.append({"law": name, "stick_slip": cycle.stick_slip, **asdict(cycle), "severity": cycle.severity,
                     "steps": result.stats["steps"], "events": result.stats["events"],
                     "natural_frequency": rig.natural_frequency})
    return pd.DataFrame(rows)


def stick_slip_point(*, reference_speed: float, normal_force: float, friction=None, t_end: float = 40.0,
                     transient: float = 20.0, **rig_params: Any) -> Dict[str, float]:
    """One point of :func:`stick_slip_map`: the limit cycle at (w_ref [rad/s], N2 [N]) as a dict of floats.
    Top-level and picklable, for :func:`frictionsim.sweep` on process pools and dask."""
    _, result = simulate_fig7(friction, t_end, reference_speed=reference_speed, normal_force=normal_force,
                              **rig_params)
    cycle = limit_cycle(result, transient)
    values = asdict(cycle)
    values["stick_slip"] = float(cycle.stick_slip)
    values["peak_ratio"] = cycle.peak / reference_speed
    values["severity"] = cycle.severity
    return values


@dataclass(frozen=True)
class StickSlipMap:
    """Stick-slip over a (reference speed, normal force) grid: arrays of shape (len(reference_speeds),
    len(normal_forces)). stick_slip: True where the disc sticks in a limit cycle; frequency [Hz] (0 without an
    oscillation), peak_ratio = peak disc speed / w_ref, stick_fraction, severity (the stick-slip severity index
    (peak - trough) / (2 mean) of the disc speed, :attr:`LimitCycle.severity`); failed: True where the run failed
    (``errors="collect"``; NaN in the float arrays, False in stick_slip)."""

    reference_speeds: np.ndarray
    normal_forces: np.ndarray
    stick_slip: np.ndarray
    frequency: np.ndarray
    peak_ratio: np.ndarray
    stick_fraction: np.ndarray
    sweep: Any
    failed: np.ndarray
    severity: np.ndarray

    #: Units of the map's coordinates and measures ("1": dimensionless).
    UNITS = {"reference_speed": "rad/s", "normal_force": "N", "frequency": "Hz", "peak_ratio": "1",
             "stick_fraction": "1", "severity": "1"}

    def to_pandas(self):
        return self.sweep.to_pandas()

    @property
    def metadata(self) -> Dict[str, Any]:
        """Provenance of the map (its sweep's, :attr:`frictionsim.SweepResult.metadata`)."""
        return self.sweep.metadata

    def to_xarray(self):
        """The map as an :class:`xarray.Dataset` over (reference_speed [rad/s], normal_force [N]): stick_slip,
        failed, frequency [Hz], peak_ratio, stick_fraction and severity, with units; ``attrs`` the provenance.
        Needs ``frictionsim[io]``."""
        from .io import metadata_attrs, require_xarray

        xr = require_xarray()
        dims = ("reference_speed", "normal_force")
        units = self.UNITS
        data = {"stick_slip": (dims, np.asarray(self.stick_slip, dtype=bool)),
                "failed": (dims, np.asarray(self.failed, dtype=bool))}
        for name in ("frequency", "peak_ratio", "stick_fraction", "severity"):
            data[name] = (dims, np.asarray(getattr(self, name), dtype=float), {"units": units[name]})
        coords = {"reference_speed": ("reference_speed", np.asarray(self.reference_speeds, dtype=float),
                                      {"units": units["reference_speed"], "long_name": "reference speed w_ref"}),
                  "normal_force": ("normal_force", np.asarray(self.normal_forces, dtype=float),
                                   {"units": units["normal_force"], "long_name": "normal force N2 on the disc"})}
        return xr.Dataset(data, coords=coords,
                          attrs=metadata_attrs(self.metadata or {}, title="stick-slip map of the torsional rig"))

    def to_netcdf(self, path, *, engine: Optional[str] = None):
        """Write :meth:`to_xarray` as netCDF to ``path`` (see :meth:`frictionsim.Result.to_netcdf`); returns it."""
        from .io import write_netcdf

        return write_netcdf(self.to_xarray(), path, engine)

    def plot(self, measure: str = "severity", ax=None, **kwargs):
        """One measure of the map as a colour map on ``ax`` (:func:`frictionsim.plots.stick_slip_map_axes`):
        "severity", "peak_ratio", "frequency" or "stick_fraction". Returns the Axes."""
        from .plots import stick_slip_map_axes

        return stick_slip_map_axes(self, measure, ax=ax, **kwargs)


def stick_slip_map(reference_speeds: Sequence[float], normal_forces: Sequence[float], *, friction=None,
                   t_end: float = 40.0, transient: float = 20.0, executor: Any = None, progress: bool = False,
                   errors: str = "raise", **rig_params: Any) -> StickSlipMap:
    """Where does the rig stick-slip? One simulation per (w_ref, N2) point through :func:`frictionsim.sweep`
    (any ``executor``: threads run in parallel, the engine releases the GIL). The question drilling engineers
    ask of such a rig: above which rotary speed, at a given weight (normal force), does the bit stop sticking.
    ``errors="collect"`` keeps going past a point whose run fails (e.g. a friction law with no consistent branch
    there): its entries are NaN and ``.sweep.failed`` lists it."""
    from .sweeps import sweep

    speeds = np.asarray(reference_speeds, dtype=float).ravel()
    forces = np.asarray(normal_forces, dtype=float).ravel()
    for name, values in (("reference_speeds", speeds), ("normal_forces", forces)):
        if values.size == 0 or not np.all(np.isfinite(values)) or np.any(values <= 0):
            raise ValueError(f"{name} must be a non-empty sequence of positive finite values (got {values!r})")
    fixed = dict(friction=friction, t_end=t_end, transient=transient, **rig_params)
    result = sweep(stick_slip_point, {"reference_speed": list(speeds), "normal_force": list(forces)}, fixed=fixed,
                   executor=executor, progress=progress, errors=errors)
    failed = np.zeros(result.grid_shape, dtype=bool)
    failed.flat[result.failed] = True
    return StickSlipMap(speeds, forces, result.as_array("stick_slip") > 0.5, result.as_array("frequency"),
                        result.as_array("peak_ratio"), result.as_array("stick_fraction"), result, failed,
                        result.as_array("severity"))
