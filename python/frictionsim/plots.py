"""Figures of friction simulations and of paper 000's data, drawn with matplotlib's Agg renderer.

The figures are plain :class:`matplotlib.figure.Figure` objects, not pyplot figures: nothing is registered with
pyplot and no backend is switched, so these functions work headless (CI, ``frictionsim`` on a server) and inside
notebooks alike. :func:`save` writes a PNG and clears the figure.

Time-series inputs are ``traces``: a sequence of ``(label, frame)`` where ``frame`` is a pandas DataFrame with the
columns of :meth:`frictionsim.scenario.CaseRun.timeseries` (t [s], friction_force [N], relative_displacement [m],
relative_velocity [m/s], drive_force [N]), or for paper 001's torsional rig those of
:meth:`frictionsim.scenario.LimitCycleRun.timeseries` (t [s], disc_speed and drive_speed [rad/s],
disc_acceleration [rad/s^2], friction_torque [N m], shaft_twist [rad], ...).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional, Sequence, Tuple, Union

import numpy as np

__all__ = ["broomstick_axes", "broomstick_figure", "disc_speed_figure", "drive_force_figure", "friction_force_figure",
           "friction_torque_hysteresis_figure", "hysteresis_figure", "law_comparison_figure", "phase_portrait_figure",
           "power_law_figure", "reduction_sweep_figure", "save", "stick_slip_map_figure", "well_path_axes",
           "well_path_figure"]

Window = Optional[Tuple[float, float]]


def _figure(ncols: int = 1, width: float = 8.0, height: float = 4.5):
    from matplotlib.figure import Figure

    figure = Figure(figsize=(width, height), layout="constrained")
    axes = figure.subplots(1, ncols)
    return figure, axes


def _window(frame, window: Window):
    if window is None:
        return frame
    t = frame["t"].to_numpy()
    return frame[(t >= window[0]) & (t <= window[1])]


def save(figure, path: Union[str, Path], dpi: int = 120) -> Path:
    """Write ``figure`` as PNG to ``path`` and release its contents; returns the path."""
    path = Path(path)
    figure.savefig(path, dpi=dpi)
    figure.clear()  # not a pyplot figure: nothing to close, this frees the artists
    return path


def _titled(title: str, subtitle: str) -> str:
    return f"{title}\n{subtitle}" if title else subtitle


def _time_series_figure(traces: Sequence, column: str, ylabel: str, subtitle: str, *, title: str,
                        window: Window, zero_line: bool = False):
    """``column`` against time t [s], one line per trace that has it."""
    figure, ax = _figure()
    for label, frame in traces:
        if column in frame:
            part = _window(frame, window)
            ax.plot(part["t"], part[column], label=label, linewidth=1.2)
    if zero_line:
        ax.axhline(0.0, color="0.6", linewidth=0.6)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(ylabel)
    ax.set_title(_titled(title, subtitle), fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend()
    return figure


def friction_force_figure(traces: Sequence, *, title: str = "", window: Window = None):
    """Friction force F_F [N] against time t [s], one line per trace (paper 000 Fig. 7 layout)."""
    return _time_series_figure(traces, "friction_force", "friction force $F_F$ [N]",
                               "friction force vs time (cf. paper 000 Fig. 7)", title=title, window=window,
                               zero_line=True)


def hysteresis_figure(traces: Sequence, *, title: str = "", window: Window = None):
    """Friction force [N] against relative displacement x_r [mm] and relative velocity v_r [m/s]."""
    figure, (left, right) = _figure(2, width=11.0)
    for label, frame in traces:
        part = _window(frame, window)
        left.plot(1e3 * part["relative_displacement"], part["friction_force"], label=label, linewidth=1.0)
        right.plot(part["relative_velocity"], part["friction_force"], label=label, linewidth=1.0)
    left.set_xlabel("relative displacement $x - u$ [mm]")
    right.set_xlabel("relative velocity $v_r$ [m/s]")
    for ax in (left, right):
        ax.set_ylabel("friction force $F_F$ [N]")
        ax.grid(True, alpha=0.3)
        ax.legend()
    figure.suptitle(_titled(title, "friction hysteresis loops (paper 000 eqs 8-9)"), fontsize=10)
    return figure


def drive_force_figure(traces: Sequence, *, title: str = "", window: Window = None):
    """Drive force F_d = k_d (v_d t - x) [N] against time [s] (axial rigs only; paper 000 eq 7, Fig. 4-5)."""
    return _time_series_figure(traces, "drive_force", "drive force $F_d$ [N]",
                               "drive force vs time (paper 000 eq 7, cf. Figs. 4-5)", title=title, window=window)


def power_law_figure(table4, fits, printed=None):
    """Paper 000 Fig. 11: mu_df against v_a/v_d on log-log axes per lubricant, with the fitted power laws.

    ``table4``: :func:`frictionsim.data.table4` (columns lubricant, velocity_ratio, mu_df); ``fits``: the
    DataFrame of :func:`frictionsim.fit.fit_power_law` (indexed by lubricant: eta_prime, exponent); ``printed``:
    :func:`frictionsim.data.table5` to draw the printed laws dashed.
    """
    figure, ax = _figure(width=8.0, height=5.5)
    for i, (lubricant, fit) in enumerate(fits.iterrows()):
        color = f"C{i}"
        runs = table4[table4["lubricant"] == lubricant]
        name = runs["lubricant_printed"].iloc[0] if "lubricant_printed" in runs and len(runs) else lubricant
        ax.loglog(runs["velocity_ratio"], runs["mu_df"], "o", color=color, label=f"{name} (Table 4)")
        x = np.geomspace(runs["velocity_ratio"].min(), runs["velocity_ratio"].max(), 50)
        ax.loglog(x, fit["eta_prime"] * x ** fit["exponent"], "-", color=color,
                  label=f"refit $\\mu_{{df}}$ = {fit['eta_prime']:.4f} $(v_a/v_d)^{{{fit['exponent']:.5f}}}$")
        if printed is not None:
            row = printed[printed["lubricant"] == lubricant]
            if len(row):
                ax.loglog(x, row["eta_prime"].iloc[0] * x ** row["exponent"].iloc[0], "--", color=color,
                          linewidth=0.8, alpha=0.8)
    ax.set_xlabel("velocity ratio $v_a/v_d$ [-]")
    ax.set_ylabel("dynamic friction coefficient $\\mu_{df}$ [-]")
    ax.set_title("paper 000 Fig. 11 / Table 5: $\\mu_{df}$ vs $v_a/v_d$\n"
                 "points: Table 4; solid: refit; dashed: Table 5 as printed", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return figure


def reduction_sweep_figure(frame, columns: Sequence[Tuple[str, str]], *, title: str = ""):
    """Friction reduction [%] against v_d/v_a [-]: one line per ``(column, label)`` of ``frame`` (fractions).

    Columns named ``*closed*`` are drawn as a dashed black line (closed forms), ``*table*`` as markers (data).
    """
    figure, ax = _figure()
    x = frame["velocity_ratio"]
    for column, label in columns:
        style = {"closed": dict(linestyle="--", color="k", linewidth=1.0), "table": dict(linestyle="none",
                 marker="s", markersize=8)}
        kind = next((k for k in style if k in column), None)
        ax.plot(x, 100.0 * frame[column], **style.get(kind, dict(marker="o")), label=label)
    ax.set_xscale("log")
    ax.set_xlabel("velocity ratio $v_d/v_a$ [-]")
    ax.set_ylabel("friction reduction $1 - F_{df}/(\\mu F_N)$ [%]")
    ax.set_title(title or "friction reduction vs velocity ratio", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return figure


# ------------------------------------------------------------------------------------- paper 001, torsional rig
def disc_speed_figure(traces: Sequence, *, title: str = "", window: Window = None,
                      reference_speeds: Optional[Sequence[float]] = None):
    """Disc speed w2 and drive speed w3 [rad/s] against time [s], one panel per trace (paper 001 Figs. 4a, 7a);
    ``reference_speeds``: w_ref [rad/s] per trace, drawn dotted."""
    from matplotlib.figure import Figure

    n = max(1, len(traces))
    figure = Figure(figsize=(10.0, 1.2 + 2.1 * n), layout="constrained")
    axes = np.atleast_1d(figure.subplots(n, 1, sharex=True, squeeze=False)[:, 0])
    for i, (ax, (label, frame)) in enumerate(zip(axes, traces)):
        part = _window(frame, window)
        ax.plot(part["t"], part["disc_speed"], color="C0", linewidth=1.2, label="disc $\\omega_2$")
        ax.plot(part["t"], part["drive_speed"], color="C3", linewidth=1.0, linestyle="--",
                label="drive $\\omega_3$ (load side)")
        if reference_speeds is not None and i < len(reference_speeds):
            ax.axhline(reference_speeds[i], color="0.4", linewidth=0.8, linestyle=":",
                       label=f"$\\omega_{{ref}}$ = {reference_speeds[i]:g} rad/s")
        ax.axhline(0.0, color="0.6", linewidth=0.6)
        low, high = ax.get_ylim()
        ax.set_ylim(low, high + 0.3 * (high - low))  # room for the legend above the peaks
        ax.set_ylabel("speed [rad/s]")
        ax.set_title(label, fontsize=9, loc="left")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper right", ncol=3)
    axes[-1].set_xlabel("time t [s]")
    figure.suptitle(_titled(title, "disc and drive speed vs time (cf. paper 001 Figs. 4a, 7a)"), fontsize=10)
    return figure


def _broken_at_switches(part, *columns):
    """The columns as arrays with a NaN between rows of different ``mode`` (if the frame has one), so that lines
    do not join the two sides of a jump (stick <-> slip, eq 6's branch changes: acceleration and torque jump)."""
    values = [part[c].to_numpy(dtype=float) for c in columns]
    if "mode" not in part or len(part) < 2:
        return values
    cuts = np.flatnonzero(np.diff(part["mode"].to_numpy()) != 0) + 1
    return [np.insert(v, cuts, np.nan) for v in values]


def friction_torque_hysteresis_figure(traces: Sequence, *, title: str = "", window: Window = None):
    """Friction torque T_f2 [N m] against disc speed w2 (paper 001 Fig. 5a) and against disc acceleration dw2/dt
    (Fig. 5b), and dw2/dt against w2 (Fig. 5c), one line per trace; lines break where the contact mode changes
    (the jumps of acceleration and torque at stick <-> slip and at eq 6's branch changes are not drawn)."""
    figure, axes = _figure(3, width=15.0, height=4.8)
    for label, frame in traces:
        w, al, torque = _broken_at_switches(_window(frame, window), "disc_speed", "disc_acceleration",
                                            "friction_torque")
        line, = axes[0].plot(w, torque, linewidth=1.0, label=label)
        axes[1].plot(al, torque, linewidth=1.0, color=line.get_color(), label=label)
        axes[2].plot(w, al, linewidth=1.0, color=line.get_color(), label=label)
    labels = [("disc speed $\\omega_2$ [rad/s]", "friction torque $T_{f2}$ [N m]", "(a) torque vs speed (Fig. 5a)"),
              ("disc acceleration $\\dot\\omega_2$ [rad/s$^2$]", "friction torque $T_{f2}$ [N m]",
               "(b) torque vs acceleration (Fig. 5b)"),
              ("disc speed $\\omega_2$ [rad/s]", "disc acceleration $\\dot\\omega_2$ [rad/s$^2$]",
               "(c) acceleration vs speed (Fig. 5c)")]
    for ax, (xlabel, ylabel, panel) in zip(axes, labels):
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(panel, fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    span = f", t = {window[0]:g}-{window[1]:g} s" if window is not None else ""
    figure.suptitle(_titled(title, f"friction torque on the disc over the limit cycle{span} (cf. paper 001 Fig. 5)"),
                    fontsize=10)
    return figure


def phase_portrait_figure(traces: Sequence, *, title: str = "", window: Window = None,
                          equilibria: Optional[Sequence[Optional[Tuple[float, float]]]] = None,
                          natural_frequency: Optional[float] = None):
    """Phase portrait of the disc (paper 001 Fig. 7b): disc speed w2 [rad/s] against the shaft twist th3 - th2
    [rad], one closed curve per trace in a limit cycle. ``equilibria``: per trace the operating point
    (mean twist, w_ref), marked x (None: no marker)."""
    figure, ax = _figure(width=10.0, height=5.5)
    for i, (label, frame) in enumerate(traces):
        part = _window(frame, window)
        line, = ax.plot(part["shaft_twist"], part["disc_speed"], linewidth=1.0, label=label)
        if equilibria is not None and i < len(equilibria) and equilibria[i] is not None:
            ax.plot(*equilibria[i], marker="x", markersize=9, markeredgewidth=2, color=line.get_color(),
                    linestyle="none")
    if equilibria is not None and any(e is not None for e in equilibria):
        ax.plot([], [], marker="x", color="0.3", linestyle="none", label="operating point: mean twist, $\\omega_{ref}$")
    ax.axhline(0.0, color="0.6", linewidth=0.6)
    ax.set_xlabel("shaft twist $\\theta_3 - \\theta_2$ [rad]")
    ax.set_ylabel("disc speed $\\omega_2$ [rad/s]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    span = f", t = {window[0]:g}-{window[1]:g} s" if window is not None else ""
    note = f"; $f_n$ = {natural_frequency:.3f} Hz" if natural_frequency else ""
    ax.set_title(_titled(title, f"phase portrait of the disc{span} (cf. paper 001 Fig. 7b){note}"), fontsize=10)
    return figure


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around grid values (midpoints inside, half a spacing beyond the ends)."""
    values = np.asarray(values, dtype=float)
    if values.size == 1:
        return np.array([values[0] * 0.9, values[0] * 1.1])
    mid = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - (mid[0] - values[0])], mid, [values[-1] + (values[-1] - mid[-1])]])


def stick_slip_map_figure(stick_slip_map, *, title: str = "", point: Optional[Tuple[float, float]] = (5.76, 35.0)):
    """Where the torsional rig stick-slips over (w_ref [rad/s], N2 [N]) (a
    :class:`frictionsim.torsional.StickSlipMap`): cells coloured by peak disc speed / w_ref (left) and by the
    oscillation frequency [Hz] (right); stick-slip cells (the disc sticks in the limit cycle) carry a black dot,
    ``point`` (paper 001's Fig. 7 operating point) a star, failed runs a red cross."""
    m = stick_slip_map
    speeds, forces = np.asarray(m.reference_speeds, float), np.asarray(m.normal_forces, float)
    x_edges, y_edges = _edges(speeds), _edges(forces)
    stick = np.asarray(m.stick_slip, dtype=bool)
    failed = np.asarray(getattr(m, "failed", np.zeros_like(stick)), dtype=bool)
    figure, axes = _figure(2, width=13.0, height=5.2)
    panels = [(np.asarray(m.peak_ratio, float), "peak disc speed / $\\omega_{ref}$ [-]", "viridis", ".2f"),
              (np.where(np.asarray(m.frequency, float) > 0, m.frequency, np.nan), "oscillation frequency [Hz]",
               "cividis", ".2f")]
    xx, yy = np.meshgrid(speeds, forces, indexing="ij")
    for ax, (values, label, cmap, fmt) in zip(axes, panels):
        mesh = ax.pcolormesh(x_edges, y_edges, values.T, cmap=cmap, shading="flat")
        figure.colorbar(mesh, ax=ax, label=label)
        for (i, j), value in np.ndenumerate(values):
            if np.isfinite(value) and values.size <= 120:
                ax.annotate(format(value, fmt), (speeds[i], forces[j]), textcoords="offset points", xytext=(0, -11),
                            ha="center", fontsize=6.5, color="w" if value < np.nanmean(values) else "k")
        ax.plot(xx[stick], yy[stick], "o", color="k", markersize=4, linestyle="none", label="stick-slip")
        ax.plot(xx[~stick & ~failed], yy[~stick & ~failed], "o", markerfacecolor="none", markeredgecolor="0.85",
                markersize=4, linestyle="none", label="no sticking")
        if failed.any():
            ax.plot(xx[failed], yy[failed], "x", color="r", markersize=6, linestyle="none", label="run failed")
        if point is not None:
            ax.plot(*point, marker="*", markersize=15, color="r", markeredgecolor="k", linestyle="none",
                    label=f"Fig. 7: {point[0]:g} rad/s, {point[1]:g} N")
        ax.set_xlabel("reference speed $\\omega_{ref}$ [rad/s]")
        ax.set_ylabel("normal force $N_2$ [N]")
        ax.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    share = f"{stick.sum()} of {stick.size} points stick-slip" + (f", {failed.sum()} failed" if failed.any() else "")
    figure.suptitle(_titled(title, f"stick-slip map of the torsional rig (paper 001): {share}"), fontsize=10)
    return figure


def law_comparison_figure(frame, *, title: str = "", paper: Optional[dict] = None,
                          natural_frequency: Optional[float] = None):
    """Limit cycle per friction law (the DataFrame of :func:`frictionsim.torsional.compare_laws`: law, frequency
    [Hz], peak [rad/s], stick_slip): bars of the stick-slip frequency and the peak disc speed beside paper 001's
    Fig. 7 values (``paper``: :data:`frictionsim.torsional.FIG7`) and the natural frequency f_n [Hz]."""
    if paper is None:
        from .torsional import FIG7 as paper
    if natural_frequency is None and "natural_frequency" in frame:
        natural_frequency = float(frame["natural_frequency"].iloc[0])
    figure, (left, right) = _figure(2, width=12.0, height=4.8)
    laws = list(frame["law"])
    y = np.arange(len(laws))
    sticks = frame["stick_slip"].astype(bool).to_numpy() if "stick_slip" in frame else np.ones(len(laws), bool)
    colors = ["C0" if s else "0.7" for s in sticks]
    for ax, column, unit, lines in (
            (left, "frequency", "Hz", [(paper["frequency_measured"], "measured", "k", "-"),
                                       (paper["frequency_simulated"], "paper's model", "k", "--")]
             + ([(round(natural_frequency, 3), "$f_n = \\sqrt{k_2/J_2}/2\\pi$", "C3", ":")] if natural_frequency
                else [])),
            (right, "peak", "rad/s", [(paper["peak_measured"], "measured", "k", "-"),
                                      (paper["peak_simulated"], "paper's model", "k", "--"),
                                      (paper["reference_speed"], "$\\omega_{ref}$", "C3", ":")])):
        values = frame[column].to_numpy(dtype=float)
        ax.barh(y, values, color=colors)
        for yi, value, stick in zip(y, values, sticks):
            ax.annotate(f"{value:.3g}" + ("" if stick else " (no stick-slip)"), (value, yi), xytext=(3, 0),
                        textcoords="offset points", va="center", fontsize=8,
                        bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=1))
        for value, label, color, style in lines:
            ax.axvline(value, color=color, linestyle=style, linewidth=1.2, label=f"{label}: {value:g} {unit}")
        ax.set_yticks(y, laws)
        ax.invert_yaxis()
        ax.set_xlim(0, 1.25 * max(np.nanmax(values), max(v for v, *_ in lines)))
        ax.grid(True, axis="x", alpha=0.3)
        ax.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    left.set_xlabel("stick-slip frequency [Hz]")
    right.set_xlabel("peak disc speed [rad/s]")
    figure.suptitle(_titled(title, f"friction laws at paper 001's Fig. 7 point (w_ref = {paper['reference_speed']:g}"
                                   f" rad/s, N2 = {paper['normal_force']:g} N) against the paper's values"),
                    fontsize=10)
    return figure


# ------------------------------------------------------------------------------------------ torque and drag (wells)
#: Broomstick colours per operation: pick-up red, slack-off blue, rotating green (the usual convention).
_OPERATION_STYLE = {"trip_out": ("C3", "pick-up (trip out)"), "trip_in": ("C0", "slack-off (trip in)"),
                    "rotating_off_bottom": ("C2", "rotating off bottom"), "reaming": ("C4", "reaming"),
                    "backreaming": ("C1", "backreaming"), "sliding_drilling": ("C5", "sliding"),
                    "rotary_drilling": ("C6", "rotary drilling")}


def _axes(ax, width: float = 7.0, height: float = 6.0):
    """``ax``, or the Axes of a new (non-pyplot) figure."""
    if ax is not None:
        return ax
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained").subplots()


def broomstick_axes(chart, ax=None, *, title: str = ""):
    """Hook load [kN] against bit depth [m], depth increasing downwards, one line per operation and friction factor
    of a :class:`frictionsim.wells.Broomstick` (line style by friction factor, labelled at the deepest point);
    rotating off bottom once (friction does not change it). Returns the Axes."""
    ax = _axes(ax)
    styles = ["-", "--", "-.", ":"]
    for op in chart.operations:
        color, label = _OPERATION_STYLE.get(op, ("k", op))
        factors = chart.friction_factors[:1] if op == "rotating_off_bottom" else chart.friction_factors
        for k, mu in enumerate(factors):
            depth, load = chart.hook_loads(op, mu)
            text = label if op == "rotating_off_bottom" else f"{label}, mu = {mu:g}"
            ax.plot(load / 1e3, depth, color=color, linestyle=styles[k % len(styles)], linewidth=1.3, label=text)
            if op != "rotating_off_bottom":
                ax.annotate(f"{mu:g}", (load[-1] / 1e3, depth[-1]), xytext=(0, -9), textcoords="offset points",
                            ha="center", fontsize=7, color=color)
    ax.set_xlabel("hook load [kN] (less the block weight)")
    ax.set_ylabel("bit depth, measured [m]")
    if not ax.yaxis_inverted():
        ax.invert_yaxis()
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(_titled(title, "broomstick: hook load while running in, per friction factor"), fontsize=10)
    return ax


def broomstick_figure(chart, *, title: str = ""):
    """:func:`broomstick_axes` on a new figure; returns the figure (for :func:`save`)."""
    return broomstick_axes(chart, title=title).figure


def placement_axes(placement, ax=None, *, title: str = ""):
    """A :class:`frictionsim.wells.Placement`: the weight on bit [kN] while sliding against the tool's measured
    depth [m], without any tool as a dashed line, the best depth(s) marked. Returns the Axes."""
    ax = _axes(ax, 7.0, 4.0)
    label = "one tool at this depth" if len(placement.depths) == 1 else "second tool (first at its best)"
    ax.plot(placement.scan_depths, np.asarray(placement.scan_weight_on_bit) / 1e3, label=label)
    ax.axhline(placement.weight_on_bit_without / 1e3, color="grey", linestyle="--", label="no tool")
    for d in placement.depths:
        ax.axvline(d, color="tab:red", linestyle=":")
    ax.plot(placement.depths, [placement.weight_on_bit / 1e3] * len(placement.depths), "o", color="tab:red",
            label=f"best: {placement.weight_on_bit / 1e3:.1f} kN")
    ax.set_xlabel("tool measured depth [m]")
    ax.set_ylabel("weight on bit while sliding [kN]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(_titled(title, f"sliding at a hook load of {placement.hook_load / 1e3:.0f} kN"), fontsize=10)
    return ax


def well_path_axes(survey, ax=None, *, view: str = "section", title: str = ""):
    """A :class:`frictionsim.Survey`'s minimum-curvature path, drawn through interpolated points (arcs between
    stations, not chords) with the stations marked: ``view="section"`` true vertical depth [m] (down) against
    horizontal departure [m], ``"plan"`` north against east [m]. Returns the Axes."""
    if view not in ("section", "plan"):
        raise ValueError(f"well_path_axes: view must be 'section' or 'plan' (got {view!r})")
    ax = _axes(ax, 6.0, 6.0)
    md = np.asarray(survey.measured_depth)
    fine = np.unique(np.concatenate([np.linspace(md[0], md[-1], 400), md]))
    path = survey.interpolate(fine)
    if view == "section":
        departure = np.hypot(path["north"], path["east"])
        ax.plot(departure, path["tvd"], color="C0", linewidth=1.5)
        ax.plot(np.hypot(survey.north, survey.east), survey.tvd, "o", color="C0", markersize=1.5, label="stations")
        ax.set_xlabel("horizontal departure [m]")
        ax.set_ylabel("true vertical depth [m]")
        if not ax.yaxis_inverted():
            ax.invert_yaxis()
    else:
        ax.plot(path["east"], path["north"], color="C0", linewidth=1.5)
        ax.plot(survey.east, survey.north, "o", color="C0", markersize=1.5, label="stations")
        ax.set_xlabel("east [m]")
        ax.set_ylabel("north [m]")
    ax.set_aspect("equal", adjustable="box")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(_titled(title, f"well path ({'vertical section' if view == 'section' else 'plan view'}, "
                                f"MD {md[0]:g} to {md[-1]:g} m)"), fontsize=10)
    return ax


def well_path_figure(survey, *, title: str = ""):
    """Vertical section and plan view of a survey side by side; returns the figure (for :func:`save`)."""
    figure, (left, right) = _figure(2, width=11.0, height=5.5)
    well_path_axes(survey, left, view="section")
    well_path_axes(survey, right, view="plan")
    if title:
        figure.suptitle(title, fontsize=10)
    return figure
