"""Scenario files for paper 001's torsional drill-string rig (``rig.type = "torsional"``).

The torsional part of the one scenario schema (:mod:`frictionsim.scenario` documents it all and parses it; this
module holds what differs for the torsional rig, :class:`frictionsim.TorsionalRig`):

* rig keys: the :class:`~frictionsim.TorsionalRig` keywords (:data:`RIG_KEYS`, all optional, SI units);
* friction types "hysteretic" (:class:`~frictionsim.HystereticFriction`, paper 001 eq 6) and "fig7" (the eq 6 set
  of :func:`frictionsim.torsional.fig7_friction`), which only a torsional rig runs; the engine's other laws
  (coulomb, stribeck, dahl, lugre, elasto_plastic) act at the rig's contact_radius;
* analysis: the limit cycle of the disc speed (:func:`frictionsim.torsional.limit_cycle`) after ``transient``
  [s] (default t_end / 2), with ``stick_speed`` [rad/s] (default 0.01) the |w2| counted as stuck, instead of the
  mean friction over vibration cycles;
* outputs: the time series of :meth:`TorsionalCaseRun.timeseries`, the summary of :meth:`TorsionalCaseRun.summary`
  and the plots of :data:`PLOTS`.

Plots (``output.plots``; ``output.plot_window`` = [t_start, t_end] overrides every default window):

``disc_speed``
    disc speed w2 and drive (load-side motor) speed w3 against time, one panel per case (paper 001 Figs. 4a, 7a);
    default window: the last 10 s.
``friction_torque_hysteresis``
    the friction torque T_f2 against disc speed w2 (Fig. 5a), against disc acceleration dw2/dt (Fig. 5b), and
    dw2/dt against w2 (Fig. 5c), over the limit cycle (default window: [transient, t_end]).
``phase_portrait``
    the phase portrait of the disc (Fig. 7b): disc speed w2 against the shaft twist th3 - th2, over the limit
    cycle (default window: [transient, t_end]). The twist is the disc's position relative to the drive: in a
    limit cycle both it and w2 are periodic, so the portrait closes (the absolute angle th2 grows without
    bound; th2 - w_ref t is nearly the mirror image of the twist, since the PI loop holds th3 close to w_ref t).
    Sticking shows as the flat stretch along w2 = 0, where the twist grows at w3 ~ w_ref until the
    break-away torque is reached. The operating point (mean twist, w_ref) is marked: over whole cycles the mean
    shaft torque equals the mean friction torque, so the mean twist is mean T_f2 / k2 (for steady rotation, the
    equilibrium itself).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _core

__all__ = ["FRICTION_TYPES", "PLOTS", "RIG_KEYS", "SUMMARY_COLUMNS", "TorsionalCaseRun", "run_case",
           "write_plots"]

#: Keywords of :class:`frictionsim.TorsionalRig` a scenario's [rig] may set (all floats, SI units).
RIG_KEYS: Dict[str, type] = {name: float for name in (
    "disc_inertia", "shaft_stiffness", "shaft_damping", "motor_inertia", "gear_ratio", "inductance", "resistance",
    "torque_constant", "back_emf_constant", "motor_friction_torque", "motor_viscous_coefficient",
    "proportional_gain", "integral_gain", "reference_speed", "normal_force", "contact_radius",
    "initial_disc_speed", "initial_drive_speed")}

#: friction type -> (constructor name, required keys, optional keys), as scenario.FRICTION_TYPES.
FRICTION_TYPES: Dict[str, Tuple[str, Tuple[str, ...], Tuple[str, ...]]] = {
    "hysteretic": ("HystereticFriction", ("stick_slope", "accelerating", "decelerating"),
                   ("stick_speed", "reference_normal_force", "branch_gap")),
    "fig7": ("HystereticFriction", (), ("branch_gap",)),
}
#: Friction types only a torsional rig runs.
TORSIONAL_ONLY = tuple(FRICTION_TYPES)
#: Keys of the torsional friction types that are not single numbers: "coefficients" is an array of 6 numbers.
VALUE_KINDS: Dict[str, Any] = {"accelerating": "coefficients", "decelerating": "coefficients", "branch_gap": str}
#: The engine names eq 6's coefficients p00..p02 / n00..n02 in its errors: the key they were written under.
COEFFICIENT_KEYS = {**{f"p{i}": "accelerating" for i in ("00", "10", "01", "20", "11", "02")},
                    **{f"n{i}": "decelerating" for i in ("00", "10", "01", "20", "11", "02")}}
COEFFICIENT_NAMES = "(c00, c10, c01, c20, c11, c02): N m, N m s/rad, kg m^2, N m s^2/rad^2, N m s^3/rad^2, " \
                    "N m s^4/rad^2"

ANALYSIS_KEYS = {"transient": float, "stick_speed": float}
DEFAULT_STICK_SPEED = 1e-2  #: rad/s, as frictionsim.torsional.limit_cycle
PLOTS = ("disc_speed", "friction_torque_hysteresis", "phase_portrait")
TIME_SERIES_WINDOW = 10.0  #: s: the default window of the disc_speed plot ends at t_end

#: (column, header, format) of the summary table ``frictionsim run`` prints for torsional cases.
SUMMARY_COLUMNS = [("case", "case", "s"), ("law", "law", "s"), ("reference_speed_rad_s", "w_ref [rad/s]", ".4g"),
                   ("normal_force_N", "N2 [N]", ".4g"), ("frequency_Hz", "f [Hz]", ".4f"),
                   ("period_s", "period [s]", ".4f"), ("peak_speed_rad_s", "peak [rad/s]", ".4g"),
                   ("trough_speed_rad_s", "trough [rad/s]", ".3g"), ("stick_fraction", "stick", ".3f"),
                   ("mean_friction_torque_Nm", "mean T_f2 [N m]", ".4f"), ("cycles", "cycles", "d"),
                   ("events", "events", "d"), ("steps", "steps", "d")]
SUMMARY_NOTE = ("limit cycle of the disc speed w2 over whole cycles after the transient: f = stick-slip frequency, "
                "stick = share of the time with |w2| <= stick_speed; mean T_f2 over the same cycles")


def transient(case) -> float:
    """The start [s] of the limit-cycle analysis: analysis.transient, else t_end / 2."""
    a = case.analysis
    return float(a.transient) if a.transient is not None else 0.5 * case.solver.t_end


def stick_speed(case) -> float:
    """|w2| [rad/s] at or below which the disc counts as stuck: analysis.stick_speed, else 0.01 rad/s."""
    a = case.analysis
    return float(a.stick_speed) if a.stick_speed is not None else DEFAULT_STICK_SPEED


def build_friction(kind: str, params: Dict[str, Any]):
    """The law object of a "hysteretic" or "fig7" friction spec."""
    if kind == "fig7":
        from .torsional import fig7_friction

        return fig7_friction(**params)
    return _core.HystereticFriction(**params)


# ------------------------------------------------------------------------------------------------------- running
@dataclass
class TorsionalCaseRun:
    """A simulated torsional case: the :class:`frictionsim.Result`, the rig object and its limit cycle."""

    case: Any  #: frictionsim.scenario.Case
    rig: Any  #: frictionsim.TorsionalRig
    result: Any  #: frictionsim.Result
    cycle: Any  #: frictionsim.torsional.LimitCycle
    wall_time: float  #: s

    @property
    def normal_force(self) -> float:
        """N2 [N]."""
        return float(self.rig.normal_force)

    @property
    def reference_speed(self) -> float:
        """w_ref [rad/s]."""
        return float(self.rig.reference_speed)

    def analysis_window(self) -> Tuple[float, float]:
        """(t_a, t_b) [s]: the whole cycles measured, or [transient, t_end] when no cycle was found."""
        if self.cycle.cycles > 0:
            return float(self.cycle.start), float(self.cycle.end)
        return transient(self.case), float(self.result.t[-1])

    @property
    def mean_friction_torque(self) -> float:
        """Time average of T_f2 [N m] over :meth:`analysis_window` (trapezoid on the output grid)."""
        t, torque = self.result.t, self.result.friction_force
        t_a, t_b = self.analysis_window()
        inside = (t >= t_a) & (t <= t_b)
        if inside.sum() < 2:
            return math.nan
        t, torque = t[inside], torque[inside]
        return float(np.sum(0.5 * (torque[1:] + torque[:-1]) * np.diff(t)) / (t[-1] - t[0]))

    def timeseries(self):
        """pandas DataFrame: t [s], the rig's states (disc_angle [rad], disc_speed [rad/s], shaft_twist [rad],
        drive_speed [rad/s], current [A], speed_error_integral [rad], the law's states, the energy integrals [J]),
        then disc_acceleration [rad/s^2], friction_torque T_f2 [N m], shaft_torque S [N m], voltage V [V] and
        mode (the disc's contact mode; see :class:`frictionsim.TorsionalRig`)."""
        import pandas as pd

        r, rig = self.result, self.rig
        columns: Dict[str, np.ndarray] = {"t": r.t}
        columns.update((name, r[name]) for name in r.state_names)
        columns["disc_acceleration"] = np.asarray(rig.disc_acceleration(r.states, r.mode), dtype=float)
        columns["friction_torque"] = r.friction_force
        columns["shaft_torque"] = np.asarray(rig.shaft_torque(r.states), dtype=float)
        columns["voltage"] = np.asarray(rig.voltage(r.states), dtype=float)
        columns["mode"] = r.mode
        return pd.DataFrame(columns)

    def summary(self) -> Dict[str, Any]:
        """One summary row: the limit cycle (frequency, period, peak / trough / mean disc speed, stick fraction),
        the mean friction torque over the measured cycles, and the run's counters."""
        c, w_ref = self.cycle, self.reference_speed
        t_a, t_b = self.analysis_window()
        return {
            "case": self.case.name, "law": self.case.friction.label, "rig": "torsional",
            "reference_speed_rad_s": w_ref, "normal_force_N": self.normal_force,
            "stick_slip": bool(c.stick_slip), "frequency_Hz": c.frequency, "period_s": c.period,
            "peak_speed_rad_s": c.peak, "trough_speed_rad_s": c.trough, "mean_speed_rad_s": c.mean,
            "peak_ratio": c.peak / w_ref if w_ref != 0 else math.nan, "stick_fraction": c.stick_fraction,
            "mean_friction_torque_Nm": self.mean_friction_torque, "cycles": int(c.cycles),
            "natural_frequency_Hz": float(self.rig.natural_frequency), "stick_speed_rad_s": stick_speed(self.case),
            "transient_s": transient(self.case), "window_start_s": t_a, "window_end_s": t_b,
            "events": len(self.result.events), "steps": int(self.result.stats["steps"]),
            "t_end_s": self.case.solver.t_end,
        }


def run_case(case) -> TorsionalCaseRun:
    """Simulate a torsional case and measure its limit cycle. Raises :class:`frictionsim.SimulationError`."""
    from . import scenario
    from .torsional import limit_cycle

    rig = case.build()
    start = time.perf_counter()
    s = case.solver
    # through the module attribute, so that tests can replace scenario.simulate
    result = scenario.simulate(rig, s.t_end, method=s.method, rtol=s.rtol, atol=s.atol,
                               output_times=case.output_times(), timeout=s.timeout)
    wall = time.perf_counter() - start
    cycle = limit_cycle(result, transient(case), stick_speed=stick_speed(case))
    return TorsionalCaseRun(case, rig, result, cycle, wall)


# --------------------------------------------------------------------------------------------------------- plots
def default_windows(runs: Sequence[TorsionalCaseRun],
                    plot_window: Optional[Tuple[float, float]]) -> Dict[str, Tuple[float, float]]:
    """Plot name -> (t_start, t_end) [s]: output.plot_window for every plot, else the defaults (module doc)."""
    t_end = min(run.case.solver.t_end for run in runs)
    if plot_window is not None:
        return {plot: plot_window for plot in PLOTS}
    cycle = (min(max(transient(run.case) for run in runs), t_end), t_end)
    return {"disc_speed": (max(0.0, t_end - TIME_SERIES_WINDOW), t_end), "friction_torque_hysteresis": cycle,
            "phase_portrait": cycle}


def write_plots(runs: Sequence[TorsionalCaseRun], traces: Sequence, plots_wanted: Sequence[str], directory: Path,
                *, title: str, plot_window: Optional[Tuple[float, float]]) -> List[Path]:
    """Write the torsional PNGs of ``plots_wanted`` into ``directory``; ``traces`` are (label, timeseries)."""
    from . import plots

    windows = default_windows(runs, plot_window)
    first = runs[0].rig
    written = []
    for plot in plots_wanted:
        if plot == "disc_speed":
            figure = plots.disc_speed_figure(traces, title=title, window=windows[plot],
                                             reference_speeds=[run.reference_speed for run in runs])
        elif plot == "friction_torque_hysteresis":
            figure = plots.friction_torque_hysteresis_figure(traces, title=title, window=windows[plot])
        else:
            equilibria = [_operating_point(run) for run in runs]
            figure = plots.phase_portrait_figure(traces, title=title, window=windows[plot], equilibria=equilibria,
                                                 natural_frequency=float(first.natural_frequency))
        written.append(plots.save(figure, directory / f"{plot}.png"))
    return written


def _operating_point(run: TorsionalCaseRun) -> Optional[Tuple[float, float]]:
    """(twist [rad], w_ref [rad/s]) about which the disc moves: mean T_f2 / k2 over the measured window (the
    mean of S = k2 twist + d2 (w3 - w2) is the mean friction torque, and w3 - w2 averages to zero over whole
    cycles). Derived from the run, so it holds for every law; None when the window holds too few samples."""
    torque = run.mean_friction_torque
    if not math.isfinite(torque):
        return None
    return torque / float(run.rig.shaft_stiffness), run.reference_speed
