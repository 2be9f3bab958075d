"""Figures of friction simulations and of paper 000's data, drawn with matplotlib's Agg renderer.

The functions compose with matplotlib: each takes ``ax=None`` (draw into your Axes; a multi-panel one takes a
sequence of Axes, one per panel), returns the Axes it drew on (or the Figure for multi-panel ones), and passes style
keywords (``color=``, ``linewidth=``, ...) to the artists of its data. Without ``ax`` the figure is a plain
:class:`matplotlib.figure.Figure`, not a pyplot figure: nothing is registered with pyplot and no backend is
switched, so these functions work headless (CI, ``frictionsim`` on a server) and inside notebooks alike.
:func:`save` writes a PNG of a Figure or of an Axes' figure and leaves it as it was (``release=True`` frees the
contents of a figure frictionsim made, for a pipeline done with it; a figure of yours is never cleared).

The single-panel functions are named ``*axes_for`` and return the Axes they drew on; the multi-panel ones
``*_figure`` and return the Figure. Five single-panel functions were once named ``*_figure`` (when every function
made its own figure); those names stay as aliases of the ``*axes_for`` ones and, like them, return the Axes:
``friction_force_figure``, ``drive_force_figure``, ``power_law_figure``, ``reduction_sweep_figure``,
``phase_portrait_figure``.

Time-series inputs are ``traces``: a :class:`frictionsim.Result`, a pandas DataFrame, or a sequence of
``(label, data)`` with either. A frame has the columns of :meth:`frictionsim.scenario.CaseRun.timeseries` (t [s],
friction_force [N], relative_displacement [m], relative_velocity [m/s], drive_force [N]), or for paper 001's
torsional rig those of :meth:`frictionsim.scenario.LimitCycleRun.timeseries` (t [s], disc_speed and drive_speed
[rad/s], disc_acceleration [rad/s^2], friction_torque [N m], shaft_twist [rad], ...); a Result gives t, its states,
friction_force and mode (and friction_torque on the torsional rig). A plot that needs a column the data lack says
which.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from .atomic import atomic_path
from .errors import InvalidParameterError

__all__ = ["broomstick_axes", "broomstick_figure", "disc_speed_figure", "drive_force_axes", "drive_force_figure",
           "friction_force_axes", "friction_force_figure", "friction_torque_hysteresis_figure", "hysteresis_figure",
           "identification_figure", "law_comparison_figure", "oscillator_broomstick_figure", "phase_portrait_axes",
           "phase_portrait_figure", "placement_axes", "placements_figure", "power_law_axes", "power_law_figure",
           "reduction_sweep_axes", "reduction_sweep_figure", "save", "stick_slip_map_axes", "stick_slip_map_figure",
           "sweep_axes", "time_series_axes", "well_path_axes", "well_path_figure"]

Window = Optional[Tuple[float, float]]


#: Marks the figures frictionsim made (the only ones :func:`save` may clear).
_MADE_HERE = "_frictionsim_made"


def _new_figure(width: float, height: float):
    """A new (non-pyplot) figure, marked as frictionsim's own."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(width, height), layout="constrained")
    setattr(figure, _MADE_HERE, True)
    return figure


def axes_for(ax, width: float = 8.0, height: float = 4.5):
    """``ax``, or the Axes of a new (non-pyplot) figure."""
    if ax is not None:
        if not hasattr(ax, "plot") or not hasattr(ax, "figure"):
            raise InvalidParameterError(f"ax must be a matplotlib Axes (got {type(ax).__name__})", "ax")
        return ax
    return _new_figure(width, height).subplots()


def panels_for(ax, n: int, width: float, height: float, rows: bool = False):
    """(figure, list of n Axes): the given sequence ``ax`` (one Axes per panel), or a new figure's n panels side by
    side (``rows``: stacked, sharing t)."""
    if ax is None:
        figure = _new_figure(width, height)
        grid = figure.subplots(n, 1, sharex=True, squeeze=False) if rows else figure.subplots(1, n, squeeze=False)
        return figure, list(np.ravel(grid))
    axes = list(np.ravel(np.asarray(ax, dtype=object)))
    if len(axes) != n or not all(hasattr(a, "plot") and hasattr(a, "figure") for a in axes):
        raise InvalidParameterError(f"ax must be a sequence of {n} matplotlib Axes, one per panel (got "
                                    f"{len(axes)} {'Axes' if all(hasattr(a, 'plot') for a in axes) else 'objects'})",
                                    "ax")
    return axes[0].figure, axes


def with_style(defaults: Dict[str, Any], kwargs: Dict[str, Any]) -> Dict[str, Any]:
    """The caller's style keywords over a plot's defaults (``lw`` replaces ``linewidth``, ``c`` ``color``, ...)."""
    aliases = {"lw": "linewidth", "ls": "linestyle", "c": "color", "ms": "markersize", "mec": "markeredgecolor",
               "mfc": "markerfacecolor", "mew": "markeredgewidth"}
    out = {key: value for key, value in defaults.items()
           if key not in kwargs and not any(alias in kwargs for alias, full in aliases.items() if full == key)}
    out.update(kwargs)
    return out


def _result_frame(result):
    """A :class:`frictionsim.Result` as a time-series frame: t, the states, friction_force, mode, and on the
    torsional rig (a disc_speed state) friction_torque, which is its friction_force [N m]."""
    import pandas as pd

    columns: Dict[str, np.ndarray] = {"t": result.t}
    columns.update((name, result.states[:, i]) for i, name in enumerate(result.state_names))
    columns["friction_force"] = result.friction_force
    if "disc_speed" in result.state_names:
        columns["friction_torque"] = result.friction_force
    columns["mode"] = result.mode
    frame = pd.DataFrame(columns)
    frame.attrs["units"] = units = dict(result.units)
    if "friction_torque" in columns and "friction_force" in units:
        units["friction_torque"] = units["friction_force"]
    return frame


def _is_result(data) -> bool:
    return hasattr(data, "state_names") and hasattr(data, "states") and hasattr(data, "t")


def _traces(data) -> List[Tuple[str, Any]]:
    """``traces`` as a list of (label, frame): a Result or a DataFrame alone, or (label, Result or frame) pairs."""
    import pandas as pd

    if _is_result(data):
        return [("", _result_frame(data))]
    if isinstance(data, pd.DataFrame):
        return [("", data)]
    out = []
    for item in data:
        if not (isinstance(item, tuple) and len(item) == 2):
            raise InvalidParameterError(f"traces must be a Result, a DataFrame or a sequence of (label, Result or "
                                        f"DataFrame) pairs (got an item {type(item).__name__})", "traces")
        label, frame = item
        out.append((str(label), _result_frame(frame) if _is_result(frame) else frame))
    return out


def _units(traces) -> Dict[str, str]:
    """Column -> unit as the traces' makers declared them (the first trace's where they differ)."""
    from .io import column_units

    units: Dict[str, str] = {}
    for _, frame in reversed(traces):
        units.update((k, v) for k, v in column_units(frame).items() if v)
    return units


def _require(traces, columns: Sequence[str], plot: str) -> None:
    for label, frame in traces:
        missing = [c for c in columns if c not in frame]
        if missing:
            raise InvalidParameterError(f"{plot}: trace {label or 0!r} has no column {', '.join(missing)} (a Result "
                                        f"gives t, its states, friction_force and mode; pass the scenario's "
                                        f"timeseries() for derived columns)", "traces")


def _window(frame, window: Window):
    if window is None:
        return frame
    t = frame["t"].to_numpy()
    return frame[(t >= window[0]) & (t <= window[1])]


def save(figure, path: Union[str, Path], dpi: int = 120, *, release: bool = False) -> Path:
    """Write a figure as PNG.

    Parameters
    ----------
    figure : matplotlib.figure.Figure or matplotlib.axes.Axes
        The figure, or an Axes (its figure is written). It is left as it was: you may go on drawing on it.
    path : str or pathlib.Path
        The PNG file to write.
    dpi : int, optional
        Resolution [dots per inch].
    release : bool, optional
        Clear the figure after writing it, freeing its artists at once (a pipeline that writes many figures and
        keeps none). Only a figure frictionsim made (without ``ax=``) is cleared; yours, or a pyplot figure, never.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    if not hasattr(figure, "savefig"):
        figure = getattr(figure, "figure", None)
        if figure is None or not hasattr(figure, "savefig"):
            raise InvalidParameterError("save: figure must be a matplotlib Figure or Axes", "figure")
    with atomic_path(path) as temporary:  # whole or not at all: a killed run leaves the earlier PNG
        figure.savefig(temporary, dpi=dpi)
    if release and getattr(figure, _MADE_HERE, False):
        figure.clear()  # not a pyplot figure: nothing to close, this frees the artists
    return path


def _titled(title: str, subtitle: str) -> str:
    return f"{title}\n{subtitle}" if title else subtitle


def _time_series_figure(traces, column: str, ylabel: str, subtitle: str, *, title: str, window: Window,
                        zero_line: bool = False, ax=None, **kwargs):
    """``column`` against time t [s], one line per trace that has it; returns the Axes."""
    traces = _traces(traces)
    if not any(column in frame for _, frame in traces):
        _require(traces[:1], [column], subtitle.split(" vs ")[0])
    ax = axes_for(ax)
    for label, frame in traces:
        if column in frame:
            part = _window(frame, window)
            ax.plot(part["t"], part[column], **with_style(dict(label=label, linewidth=1.2), kwargs))
    if zero_line:
        ax.axhline(0.0, color="0.6", linewidth=0.6)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(ylabel)
    ax.set_title(_titled(title, subtitle), fontsize=10)
    ax.grid(True, alpha=0.3)
    if any(label for label, _ in traces):
        ax.legend()
    return ax


def time_series_axes(data, columns: Union[str, Sequence[str], None] = None, ax=None, *, window: Window = None,
                     title: str = "", **kwargs):
    """``columns`` of a Result (or a time-series frame, or (label, data) traces) against time t [s]: one line per
    column and trace, labelled with its unit where declared (a Result's :attr:`~frictionsim.Result.units`, a
    frame's ``attrs["units"]``); default the friction force. ``window``: (t_start, t_end) [s]; style keywords go to
    every line. Returns the Axes."""
    traces = _traces(data)
    if columns is None:
        columns = ["friction_force"]
    elif isinstance(columns, str):
        columns = [columns]
    columns = list(columns)
    if not columns:
        raise InvalidParameterError("time_series_axes: columns must name at least one column", "columns")
    _require(traces, columns, "time_series_axes")
    units = _units(traces)
    ax = axes_for(ax)
    for label, frame in traces:
        part = _window(frame, window)
        for column in columns:
            unit = units.get(column)
            name = f"{column} [{unit}]" if unit else column
            text = f"{label}: {name}" if label else name
            ax.plot(part["t"], part[column], **with_style(dict(label=text, linewidth=1.2), kwargs))
    ax.set_xlabel("time t [s]")
    if len(columns) == 1:
        unit = units.get(columns[0])
        ax.set_ylabel(f"{columns[0]} [{unit}]" if unit else columns[0])
    ax.grid(True, alpha=0.3)
    if len(columns) > 1 or len(traces) > 1:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def friction_force_axes(traces, *, title: str = "", window: Window = None, ax=None, **kwargs):
    """Friction force F_F [N] against time t [s], one line per trace (paper 000 Fig. 7 layout). Returns the Axes."""
    return _time_series_figure(traces, "friction_force", "friction force $F_F$ [N]",
                               "friction force vs time (cf. paper 000 Fig. 7)", title=title, window=window,
                               zero_line=True, ax=ax, **kwargs)


def hysteresis_figure(traces, *, title: str = "", window: Window = None, ax=None, **kwargs):
    """Friction force [N] against relative displacement x_r [mm] and relative velocity v_r [m/s] (two panels, ``ax``
    two Axes); returns the Figure."""
    traces = _traces(traces)
    _require(traces, ["relative_displacement", "relative_velocity", "friction_force"], "hysteresis_figure")
    figure, (left, right) = panels_for(ax, 2, 11.0, 4.5)
    for label, frame in traces:
        part = _window(frame, window)
        style = with_style(dict(label=label, linewidth=1.0), kwargs)
        left.plot(1e3 * part["relative_displacement"], part["friction_force"], **style)
        right.plot(part["relative_velocity"], part["friction_force"], **style)
    left.set_xlabel("relative displacement $x - u$ [mm]")
    right.set_xlabel("relative velocity $v_r$ [m/s]")
    for panel in (left, right):
        panel.set_ylabel("friction force $F_F$ [N]")
        panel.grid(True, alpha=0.3)
        if any(label for label, _ in traces):
            panel.legend()
    figure.suptitle(_titled(title, "friction hysteresis loops (paper 000 eqs 8-9)"), fontsize=10)
    return figure


def drive_force_axes(traces, *, title: str = "", window: Window = None, ax=None, **kwargs):
    """Drive force F_d = k_d (v_d t - x) [N] against time [s] (axial rigs only; paper 000 eq 7, Fig. 4-5). Returns
    the Axes."""
    return _time_series_figure(traces, "drive_force", "drive force $F_d$ [N]",
                               "drive force vs time (paper 000 eq 7, cf. Figs. 4-5)", title=title, window=window,
                               ax=ax, **kwargs)


def power_law_axes(table4, fits, printed=None, *, ax=None, **kwargs):
    """Paper 000 Fig. 11: mu_df against v_a/v_d on log-log axes per lubricant, with the fitted power laws.

    ``table4``: :func:`frictionsim.data.table4` (columns lubricant, velocity_ratio, mu_df); ``fits``: the
    DataFrame of :func:`frictionsim.fit.fit_power_law` (indexed by lubricant: eta_prime, exponent); ``printed``:
    :func:`frictionsim.data.table5` to draw the printed laws dashed. Style keywords go to the refit lines. Returns
    the Axes.
    """
    ax = axes_for(ax, 8.0, 5.5)
    for i, (lubricant, fit) in enumerate(fits.iterrows()):
        color = f"C{i}"
        runs = table4[table4["lubricant"] == lubricant]
        name = runs["lubricant_printed"].iloc[0] if "lubricant_printed" in runs and len(runs) else lubricant
        ax.loglog(runs["velocity_ratio"], runs["mu_df"], "o", color=color, label=f"{name} (Table 4)")
        x = np.geomspace(runs["velocity_ratio"].min(), runs["velocity_ratio"].max(), 50)
        ax.loglog(x, fit["eta_prime"] * x ** fit["exponent"], **with_style(dict(
            linestyle="-", color=color,
            label=f"refit $\\mu_{{df}}$ = {fit['eta_prime']:.4f} $(v_a/v_d)^{{{fit['exponent']:.5f}}}$"), kwargs))
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
    return ax


def reduction_sweep_axes(frame, columns: Sequence[Tuple[str, str]], *, title: str = "", ax=None, **kwargs):
    """Friction reduction [%] against v_d/v_a [-]: one line per ``(column, label)`` of ``frame`` (fractions).

    Columns named ``*closed*`` are drawn as a dashed black line (closed forms), ``*table*`` as markers (data);
    style keywords go to every line. Returns the Axes.
    """
    ax = axes_for(ax)
    x = frame["velocity_ratio"]
    for column, label in columns:
        style = {"closed": dict(linestyle="--", color="k", linewidth=1.0), "table": dict(linestyle="none",
                 marker="s", markersize=8)}
        kind = next((k for k in style if k in column), None)
        ax.plot(x, 100.0 * frame[column], **with_style(dict(style.get(kind, dict(marker="o")), label=label), kwargs))
    ax.set_xscale("log")
    ax.set_xlabel("velocity ratio $v_d/v_a$ [-]")
    ax.set_ylabel("friction reduction $1 - F_{df}/(\\mu F_N)$ [%]")
    ax.set_title(title or "friction reduction vs velocity ratio", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return ax


# ------------------------------------------------------------------------------------- paper 001, torsional rig
def disc_speed_figure(traces, *, title: str = "", window: Window = None,
                      reference_speeds: Optional[Sequence[float]] = None, ax=None, **kwargs):
    """Disc speed w2 and drive speed w3 [rad/s] against time [s], one panel per trace (paper 001 Figs. 4a, 7a;
    ``ax``: one Axes per trace); ``reference_speeds``: w_ref [rad/s] per trace, drawn dotted. Style keywords go
    to the disc-speed line. Returns the Figure."""
    traces = _traces(traces)
    _require(traces, ["disc_speed", "drive_speed"], "disc_speed_figure")
    n = max(1, len(traces))
    figure, axes = panels_for(ax, n, 10.0, 1.2 + 2.1 * n, rows=True)
    for i, (ax, (label, frame)) in enumerate(zip(axes, traces)):
        part = _window(frame, window)
        ax.plot(part["t"], part["disc_speed"], **with_style(dict(color="C0", linewidth=1.2, label="disc $\\omega_2$"),
                                                            kwargs))
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


def friction_torque_hysteresis_figure(traces, *, title: str = "", window: Window = None, ax=None, **kwargs):
    """Friction torque T_f2 [N m] against disc speed w2 (paper 001 Fig. 5a) and against disc acceleration dw2/dt
    (Fig. 5b), and dw2/dt against w2 (Fig. 5c), one line per trace (``ax``: three Axes); lines break where the
    contact mode changes (the jumps of acceleration and torque at stick <-> slip and at eq 6's branch changes are
    not drawn). Needs the scenario's timeseries (disc_acceleration). Returns the Figure."""
    traces = _traces(traces)
    _require(traces, ["disc_speed", "disc_acceleration", "friction_torque"], "friction_torque_hysteresis_figure")
    figure, axes = panels_for(ax, 3, 15.0, 4.8)
    for label, frame in traces:
        w, al, torque = _broken_at_switches(_window(frame, window), "disc_speed", "disc_acceleration",
                                            "friction_torque")
        line, = axes[0].plot(w, torque, **with_style(dict(linewidth=1.0, label=label), kwargs))
        same = with_style(dict(linewidth=1.0, label=label), dict(kwargs, color=line.get_color()))
        axes[1].plot(al, torque, **same)
        axes[2].plot(w, al, **same)
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
    if any(label for label, _ in traces):
        axes[0].legend(fontsize=8)
    span = f", t = {window[0]:g}-{window[1]:g} s" if window is not None else ""
    figure.suptitle(_titled(title, f"friction torque on the disc over the limit cycle{span} (cf. paper 001 Fig. 5)"),
                    fontsize=10)
    return figure


def phase_portrait_axes(traces, *, title: str = "", window: Window = None,
                          equilibria: Optional[Sequence[Optional[Tuple[float, float]]]] = None,
                          natural_frequency: Optional[float] = None, ax=None, **kwargs):
    """Phase portrait of the disc (paper 001 Fig. 7b): disc speed w2 [rad/s] against the shaft twist th3 - th2
    [rad], one closed curve per trace in a limit cycle. ``equilibria``: per trace the operating point
    (mean twist, w_ref), marked x (None: no marker). Style keywords go to the curves. Returns the Axes."""
    traces = _traces(traces)
    _require(traces, ["shaft_twist", "disc_speed"], "phase_portrait_axes")
    ax = axes_for(ax, 10.0, 5.5)
    for i, (label, frame) in enumerate(traces):
        part = _window(frame, window)
        line, = ax.plot(part["shaft_twist"], part["disc_speed"], **with_style(dict(linewidth=1.0, label=label), kwargs))
        if equilibria is not None and i < len(equilibria) and equilibria[i] is not None:
            ax.plot(*equilibria[i], marker="x", markersize=9, markeredgewidth=2, color=line.get_color(),
                    linestyle="none")
    if equilibria is not None and any(e is not None for e in equilibria):
        ax.plot([], [], marker="x", color="0.3", linestyle="none", label="operating point: mean twist, $\\omega_{ref}$")
    ax.axhline(0.0, color="0.6", linewidth=0.6)
    ax.set_xlabel("shaft twist $\\theta_3 - \\theta_2$ [rad]")
    ax.set_ylabel("disc speed $\\omega_2$ [rad/s]")
    ax.grid(True, alpha=0.3)
    if any(label for label, _ in traces) or (equilibria is not None and any(e is not None for e in equilibria)):
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    span = f", t = {window[0]:g}-{window[1]:g} s" if window is not None else ""
    note = f"; $f_n$ = {natural_frequency:.3f} Hz" if natural_frequency else ""
    ax.set_title(_titled(title, f"phase portrait of the disc{span} (cf. paper 001 Fig. 7b){note}"), fontsize=10)
    return ax


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around grid values (midpoints inside, half a spacing beyond the ends)."""
    values = np.asarray(values, dtype=float)
    if values.size == 1:
        return np.array([values[0] * 0.9, values[0] * 1.1])
    mid = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - (mid[0] - values[0])], mid, [values[-1] + (values[-1] - mid[-1])]])


#: What a stick-slip map's cells can be coloured by: (attribute, colour-bar label, colour map, annotation format).
_MAP_MEASURES = {
    "peak_ratio": ("peak_ratio", "peak disc speed / $\\omega_{ref}$ [-]", "viridis", ".2f"),
    "frequency": ("frequency", "oscillation frequency [Hz]", "cividis", ".2f"),
    "severity": ("severity", "stick-slip severity (peak - trough) / (2 mean) [-]", "magma", ".2f"),
    "stick_fraction": ("stick_fraction", "stick fraction [-]", "Greys", ".2f"),
}


def stick_slip_map_axes(stick_slip_map, measure: str = "severity", ax=None, *,
                        point: Optional[Tuple[float, float]] = None, annotate: bool = True, colorbar: bool = True,
                        **kwargs):
    """One measure of a :class:`frictionsim.torsional.StickSlipMap` over (w_ref [rad/s], N2 [N]) as coloured cells:
    ``measure`` "severity" (the stick-slip severity index), "peak_ratio", "frequency" [Hz] (blank where nothing
    oscillates) or "stick_fraction"; stick-slip cells carry a black dot, failed runs a red cross, ``point`` a star.
    Style keywords go to ``pcolormesh`` (``cmap=``, ``vmin=``, ...). Returns the Axes."""
    if measure not in _MAP_MEASURES:
        raise InvalidParameterError(f"measure must be one of {', '.join(_MAP_MEASURES)} (got {measure!r})",
                                    "measure")
    m = stick_slip_map
    attribute, label, cmap, fmt = _MAP_MEASURES[measure]
    speeds, forces = np.asarray(m.reference_speeds, float), np.asarray(m.normal_forces, float)
    stick = np.asarray(m.stick_slip, dtype=bool)
    failed = np.asarray(getattr(m, "failed", np.zeros_like(stick)), dtype=bool)
    values = np.asarray(getattr(m, attribute), dtype=float)
    if measure == "frequency":
        values = np.where(values > 0, values, np.nan)  # no oscillation: no frequency to colour
    ax = axes_for(ax, 6.5, 5.2)
    mesh = ax.pcolormesh(_edges(speeds), _edges(forces), values.T,
                         **with_style(dict(cmap=cmap, shading="flat"), kwargs))
    if colorbar:
        ax.figure.colorbar(mesh, ax=ax, label=label)
    if annotate and values.size <= 120:
        for (i, j), value in np.ndenumerate(values):
            if np.isfinite(value):
                ax.annotate(format(value, fmt), (speeds[i], forces[j]), textcoords="offset points", xytext=(0, -11),
                            ha="center", fontsize=6.5, color="w" if value < np.nanmean(values) else "k")
    xx, yy = np.meshgrid(speeds, forces, indexing="ij")
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
    return ax


def stick_slip_map_figure(stick_slip_map, *, title: str = "", point: Optional[Tuple[float, float]] = (5.76, 35.0),
                          measures: Sequence[str] = ("peak_ratio", "frequency"), ax=None, **kwargs):
    """Where the torsional rig stick-slips over (w_ref [rad/s], N2 [N]) (a
    :class:`frictionsim.torsional.StickSlipMap`): one panel per measure of :func:`stick_slip_map_axes` (default
    peak disc speed / w_ref left, oscillation frequency [Hz] right; ``measures=("severity", "frequency")`` shows the
    stick-slip severity index); ``ax``: one Axes per measure. Stick-slip cells (the disc sticks in the limit cycle)
    carry a black dot, ``point`` (paper 001's Fig. 7 operating point) a star, failed runs a red cross. Returns the
    Figure."""
    measures = [measures] if isinstance(measures, str) else list(measures)
    figure, axes = panels_for(ax, len(measures), 6.5 * len(measures), 5.2)
    for panel, measure in zip(axes, measures):
        stick_slip_map_axes(stick_slip_map, measure, panel, point=point, **kwargs)
    stick = np.asarray(stick_slip_map.stick_slip, dtype=bool)
    failed = np.asarray(getattr(stick_slip_map, "failed", np.zeros_like(stick)), dtype=bool)
    share = f"{stick.sum()} of {stick.size} points stick-slip" + (f", {failed.sum()} failed" if failed.any() else "")
    figure.suptitle(_titled(title, f"stick-slip map of the torsional rig (paper 001): {share}"), fontsize=10)
    return figure


def law_comparison_figure(frame, *, title: str = "", paper: Optional[dict] = None,
                          natural_frequency: Optional[float] = None, ax=None, **kwargs):
    """Limit cycle per friction law (the DataFrame of :func:`frictionsim.torsional.compare_laws`: law, frequency
    [Hz], peak [rad/s], stick_slip): bars of the stick-slip frequency and the peak disc speed beside paper 001's
    Fig. 7 values (``paper``: :data:`frictionsim.data.PAPER001_FIG7`) and the natural frequency f_n [Hz]. ``ax``: two
    Axes; style keywords go to the bars. Returns the Figure."""
    if paper is None:
        from .data import PAPER001_FIG7 as paper
    if natural_frequency is None and "natural_frequency" in frame:
        natural_frequency = float(frame["natural_frequency"].iloc[0])
    figure, (left, right) = panels_for(ax, 2, 12.0, 4.8)
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
        ax.barh(y, values, **with_style(dict(color=colors), kwargs))
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


def broomstick_axes(chart, ax=None, *, title: str = "", **kwargs):
    """Hook load [kN] against bit depth [m], depth increasing downwards, one line per operation and friction factor
    of a :class:`frictionsim.wells.Broomstick` (line style by friction factor, labelled at the deepest point);
    rotating off bottom once (friction does not change it). Style keywords go to every line. Returns the Axes."""
    ax = axes_for(ax, 7.0, 6.0)
    styles = ["-", "--", "-.", ":"]
    for op in chart.operations:
        color, label = _OPERATION_STYLE.get(op, ("k", op))
        factors = chart.friction_factors[:1] if op == "rotating_off_bottom" else chart.friction_factors
        for k, mu in enumerate(factors):
            depth, load = chart.hook_loads(op, mu)
            text = label if op == "rotating_off_bottom" else f"{label}, mu = {mu:g}"
            ax.plot(load / 1e3, depth, **with_style(dict(color=color, linestyle=styles[k % len(styles)], linewidth=1.3,
                                                         label=text), kwargs))
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


def broomstick_figure(chart, *, title: str = "", ax=None, **kwargs):
    """:func:`broomstick_axes` (on ``ax``, or a new figure); returns its figure (for :func:`save`)."""
    return broomstick_axes(chart, ax, title=title, **kwargs).figure


def placement_axes(placement, ax=None, *, title: str = "", **kwargs):
    """A :class:`frictionsim.wells.Placement`: the weight on bit [kN] while sliding against the tool's measured
    depth [m], without any tool as a dashed line, the best depth(s) marked. Style keywords go to the scan's line.
    Returns the Axes."""
    ax = axes_for(ax, 7.0, 4.0)
    label = "one tool at this depth" if len(placement.depths) == 1 else "second tool (first at its best)"
    ax.plot(placement.scan_depths, np.asarray(placement.scan_weight_on_bit) / 1e3,
            **with_style(dict(label=label), kwargs))
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


def well_path_axes(survey, ax=None, *, view: str = "section", title: str = "", **kwargs):
    """A :class:`frictionsim.Survey`'s minimum-curvature path, drawn through interpolated points (arcs between
    stations, not chords) with the stations marked: ``view="section"`` true vertical depth [m] (down) against
    horizontal departure [m], ``"plan"`` north against east [m]. Style keywords go to the path. Returns the Axes."""
    if view not in ("section", "plan"):
        raise InvalidParameterError(f"well_path_axes: view must be 'section' or 'plan' (got {view!r})", "view")
    ax = axes_for(ax, 6.0, 6.0)
    md = np.asarray(survey.measured_depth)
    fine = np.unique(np.concatenate([np.linspace(md[0], md[-1], 400), md]))
    path = survey.interpolate(fine)
    if view == "section":
        departure = np.hypot(path["north"], path["east"])
        ax.plot(departure, path["tvd"], **with_style(dict(color="C0", linewidth=1.5), kwargs))
        ax.plot(np.hypot(survey.north, survey.east), survey.tvd, "o", color="C0", markersize=1.5, label="stations")
        ax.set_xlabel("horizontal departure [m]")
        ax.set_ylabel("true vertical depth [m]")
        if not ax.yaxis_inverted():
            ax.invert_yaxis()
    else:
        ax.plot(path["east"], path["north"], **with_style(dict(color="C0", linewidth=1.5), kwargs))
        ax.plot(survey.east, survey.north, "o", color="C0", markersize=1.5, label="stations")
        ax.set_xlabel("east [m]")
        ax.set_ylabel("north [m]")
    ax.set_aspect("equal", adjustable="box")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(_titled(title, f"well path ({'vertical section' if view == 'section' else 'plan view'}, "
                                f"MD {md[0]:g} to {md[-1]:g} m)"), fontsize=10)
    return ax


def well_path_figure(survey, *, title: str = "", ax=None, **kwargs):
    """Vertical section and plan view of a survey side by side (``ax``: two Axes); returns the figure (for
    :func:`save`)."""
    figure, (left, right) = panels_for(ax, 2, 11.0, 5.5)
    well_path_axes(survey, left, view="section", **kwargs)
    well_path_axes(survey, right, view="plan", **kwargs)
    if title:
        figure.suptitle(title, fontsize=10)
    return figure


def oscillator_broomstick_figure(frame, zone, *, title: str = ""):
    """Left: hook load against bit depth while sliding, with and without the tools, and the pick-up load for
    reference, per friction factor (``frame``: :func:`frictionsim.wells.oscillator_broomstick`); right: the friction
    reduction along the string at the full depth (``zone``: :func:`frictionsim.wells.zone_of_influence`). Returns
    the Figure."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(12.0, 6.0), layout="constrained")
    left, right = figure.subplots(1, 2)
    styles = ["-", "--", "-.", ":"]
    for k, (mu, part) in enumerate(frame[frame["operation"] == "trip_out"].groupby("friction_factor")):
        left.plot(part["hook_load_plain"] / 1e3, part["bit_depth"], color="tab:red", linestyle=styles[k % 4],
                  linewidth=0.9, label=f"pick-up (trip_out), mu = {mu:g}")
    for k, (mu, part) in enumerate(frame[frame["operation"] == "sliding_drilling"].groupby("friction_factor")):
        left.plot(part["hook_load_plain"] / 1e3, part["bit_depth"], color="grey", linestyle=styles[k % 4],
                  linewidth=0.9, label=f"sliding, mu = {mu:g}, no tool")
        left.plot(part["hook_load_tool"] / 1e3, part["bit_depth"], color="tab:green", linestyle=styles[k % 4],
                  linewidth=1.3, label=f"sliding, mu = {mu:g}, with the tools")
    left.invert_yaxis()
    left.set_xlabel("hook load [kN]")
    left.set_ylabel("bit depth, measured [m]")
    left.legend(fontsize=7)
    left.set_title("broomstick with hydraulic oscillators (each at its height above the bit)", fontsize=9)
    for k, (mu, part) in enumerate(zone.groupby("friction_factor")):
        middle = 0.5 * (part["top_depth"] + part["bottom_depth"])
        right.plot(100.0 * part["reduction"], middle, linestyle=styles[k % 4], label=f"mu = {mu:g}")
    right.invert_yaxis()
    right.set_xlabel("friction reduction [%]")
    right.set_ylabel("measured depth [m]")
    right.legend(fontsize=7)
    right.set_title("zone of influence at the full depth", fontsize=9)
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
    figure.suptitle(str(title), fontsize=10)
    return figure


def placements_figure(placements, *, title: str = ""):
    """The weight on bit against the tool's depth, one panel per friction factor (``placements``: friction factor ->
    :class:`frictionsim.wells.Placement`, as :func:`frictionsim.wells.sliding_placements` gives). Returns the
    Figure."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.0, 4.0 * len(placements)), layout="constrained")
    axes = figure.subplots(len(placements), 1, squeeze=False)[:, 0]
    for ax, (mu, placement) in zip(axes, placements.items()):
        placement_axes(placement, ax=ax, title=f"{title}, mu = {mu:g}")
    return figure


def identification_figure(result, relative_velocity, *, title: str = ""):
    """A fit of a friction law to a record (:class:`frictionsim.fit.IdentificationResult`): measured and fitted
    force over time (left) and against ``relative_velocity`` [m/s] at the fit's samples, the hysteresis loops
    (right). Returns the Figure."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(11.0, 4.5), layout="constrained")
    left, right = figure.subplots(1, 2)
    result.plot(ax=left, color="tab:red", linewidth=1.2)
    right.plot(relative_velocity, result.measured, ".", markersize=2, color="grey", label="measured")
    right.plot(relative_velocity, result.model, color="tab:red", linewidth=1.0, label=f"{result.law_name} fit")
    right.set_xlabel("relative velocity [m/s]")
    right.set_ylabel("friction force [N]")
    right.legend(fontsize=8)
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
    figure.suptitle(f"{title}: {result.law_name}, rms residual {result.rms_residual:.4g} N, "
                    f"R^2 = {result.r_squared:.5f}", fontsize=10)
    return figure


# ------------------------------------------------------------------------------------------------------ sweeps
def sweep_axes(sweep_result, key: Optional[str] = None, ax=None, *, x: Optional[str] = None, title: str = "",
               colorbar: bool = True, **kwargs):
    """The values of a :class:`frictionsim.SweepResult` over its grid (``key``: an entry of dict values): a line
    (with markers) against the parameter of a 1-D grid, or against ``x`` (default the first parameter) for
    explicit points; coloured cells over a 2-D grid (first parameter along x; style keywords go to
    ``pcolormesh``). Failed points are gaps. Returns the Axes."""
    values = {name: column for name, column in sweep_result._value_columns(text=True).items()
              if column.dtype.kind == "f"}  # numbers only: a column of strings (a law's name) has nothing to plot
    names = list(values)
    if key is None:
        if len(names) > 1:
            raise InvalidParameterError(f"key: the values are dicts; pass one of {', '.join(names)}", "key")
        key = names[0]
    if key not in values:
        raise InvalidParameterError(f"key must be one of {', '.join(names)} (got {key!r})", "key")
    column = values[key]
    ax = axes_for(ax, 7.0, 4.5)
    shape, parameters = sweep_result.grid_shape, sweep_result.parameters
    label = key if key != "value" else "value"
    if shape is not None and len(shape) == 2 and x is None:
        axes = sweep_result.axes
        first, second = (np.asarray(axes[name], dtype=float) for name in parameters)
        mesh = ax.pcolormesh(_edges(first), _edges(second), column.reshape(shape).T,
                             **with_style(dict(shading="flat"), kwargs))
        if colorbar:
            ax.figure.colorbar(mesh, ax=ax, label=label)
        ax.set_xlabel(parameters[0])
        ax.set_ylabel(parameters[1])
    else:
        if shape is not None and len(shape) > 2 and x is None:
            raise InvalidParameterError(f"x: a {len(shape)}-D grid needs the parameter to plot against (one of "
                                        f"{', '.join(parameters)})", "x")
        x = parameters[0] if x is None else x
        if x not in parameters:
            raise InvalidParameterError(f"x must be one of {', '.join(parameters)} (got {x!r})", "x")
        along = np.array([point.get(x, np.nan) for point in sweep_result.points], dtype=float)
        order = np.argsort(along, kind="stable")
        ax.plot(along[order], column[order], **with_style(dict(marker="o", linewidth=1.2, label=label), kwargs))
        ax.set_xlabel(x)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


# ------------------------------------------------------------------------------------------------ former names
# Single-panel functions once named *_figure (they made their own figure); kept, returning the Axes like the new
# names (CHANGELOG: Changed).
friction_force_figure = friction_force_axes
drive_force_figure = drive_force_axes
power_law_figure = power_law_axes
reduction_sweep_figure = reduction_sweep_axes
phase_portrait_figure = phase_portrait_axes
