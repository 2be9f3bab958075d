"""Figures of friction simulations and of paper 000's data, drawn with matplotlib's Agg renderer.

The figures are plain :class:`matplotlib.figure.Figure` objects, not pyplot figures: nothing is registered with
pyplot and no backend is switched, so these functions work headless (CI, ``frictionsim`` on a server) and inside
notebooks alike. :func:`save` writes a PNG and clears the figure.

Time-series inputs are ``traces``: a sequence of ``(label, frame)`` where ``frame`` is a pandas DataFrame with the
columns of :meth:`frictionsim.scenario.CaseRun.timeseries` (t [s], friction_force [N], relative_displacement [m],
relative_velocity [m/s], drive_force [N]).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional, Sequence, Tuple, Union

import numpy as np

__all__ = ["drive_force_figure", "friction_force_figure", "hysteresis_figure", "power_law_figure",
           "reduction_sweep_figure", "save"]

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
