"""Plots that compose (issue 15, item 4): every plotting function draws into the Axes it is given and returns it (or
the Figure of the Axes given, for multi-panel ones), takes a Result or SweepResult directly, its lines hold the
Result's data, style keywords reach the artists; the stick-slip severity index against closed forms."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")  # headless, whatever the environment says; the library itself never touches pyplot

import numpy as np
import pandas as pd
import pytest
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure

import frictionsim as fs
from frictionsim import plots, scenario
from frictionsim.errors import InvalidParameterError
from frictionsim.torsional import LimitCycle, StickSlipMap, limit_cycle, severity_index


def new_axes(n=1):
    axes = Figure().subplots(1, n, squeeze=False)[0]
    return list(axes) if n > 1 else axes[0]


@pytest.fixture(scope="module")
def torsional():
    """3 s of the Stribeck rig from rest: stick-slip, every internal step."""
    rig = fs.TorsionalRig(fs.torsional.fig7_laws()["Stribeck"], initial_drive_speed=5.76, initial_disc_speed=0.0)
    return fs.simulate(rig, 3.0)


@pytest.fixture(scope="module")
def axial_run():
    text = """
    [rig]
    type = "axial"
    [solver]
    t_end = 0.2
    output_points = 201
    [analysis]
    cycles = 2
    [[case]]
    name = "coulomb"
    friction = { type = "coulomb", mu = 0.41 }
    """
    return scenario.run(scenario.loads(text, name="short")).runs[0]


def only_line(ax):
    assert len(ax.lines) >= 1
    return ax.lines[0]


# ------------------------------------------------------------------------------------------------ Result, time series
def test_result_plot_draws_its_columns_into_the_given_axes(torsional):
    ax = new_axes()
    returned = torsional.plot(["disc_speed", "drive_speed"], ax=ax, color="tab:green", linewidth=2.5)
    assert returned is ax and len(ax.lines) == 2
    for line, name in zip(ax.lines, ["disc_speed", "drive_speed"]):
        np.testing.assert_array_equal(line.get_xdata(), torsional.t)
        np.testing.assert_array_equal(line.get_ydata(), torsional[name])
        assert line.get_color() == "tab:green" and line.get_linewidth() == 2.5
    assert ax.lines[0].get_label() == "disc_speed [rad/s]"  # the unit of the state


def test_result_plot_defaults_to_the_friction_force_and_makes_its_own_axes(torsional):
    ax = torsional.plot()
    assert isinstance(ax.figure, Figure)
    np.testing.assert_array_equal(only_line(ax).get_ydata(), torsional.friction_force)
    assert ax.get_ylabel() == "friction_force [N m]"  # a torque on the torsional rig


def test_result_plot_names_a_missing_column(torsional):
    with pytest.raises(InvalidParameterError, match="no column velocity") as error:
        torsional.plot("velocity")
    assert error.value.parameter == "traces"


@pytest.mark.parametrize("function, column", [(plots.friction_force_axes, "friction_force"),
                                              (plots.drive_force_axes, "drive_force")])
def test_time_series_figures_take_an_axes_and_style(axial_run, function, column):
    frame = axial_run.timeseries()
    ax = new_axes()
    assert function([("coulomb", frame)], ax=ax, linestyle=":", lw=3.0) is ax
    line = only_line(ax)
    np.testing.assert_array_equal(line.get_xdata(), frame["t"])
    np.testing.assert_array_equal(line.get_ydata(), frame[column])
    assert line.get_linestyle() == ":" and line.get_linewidth() == 3.0 and line.get_label() == "coulomb"


def test_friction_force_axes_takes_a_result(axial_run):
    ax = plots.friction_force_axes(axial_run.result, color="k")
    np.testing.assert_array_equal(only_line(ax).get_ydata(), axial_run.result.friction_force)
    assert only_line(ax).get_color() == "k"


def test_hysteresis_figure_draws_into_two_given_axes(axial_run):
    frame = axial_run.timeseries()
    left, right = new_axes(2)
    figure = plots.hysteresis_figure([("c", frame)], ax=[left, right], color="m")
    assert figure is left.figure and figure.axes[:2] == [left, right]
    np.testing.assert_array_equal(only_line(left).get_xdata(), 1e3 * frame["relative_displacement"])
    np.testing.assert_array_equal(only_line(right).get_xdata(), frame["relative_velocity"])
    np.testing.assert_array_equal(only_line(right).get_ydata(), frame["friction_force"])
    assert only_line(left).get_color() == "m"


def test_multi_panel_figures_want_one_axes_per_panel(axial_run):
    with pytest.raises(InvalidParameterError, match="sequence of 2 matplotlib Axes") as error:
        plots.hysteresis_figure(axial_run.timeseries(), ax=new_axes())
    assert error.value.parameter == "ax"
    with pytest.raises(InvalidParameterError, match="Axes"):
        plots.friction_force_axes(axial_run.result, ax="not an axes")


def test_disc_speed_and_phase_portrait_take_a_result(torsional):
    (panel,) = [new_axes()]
    figure = plots.disc_speed_figure(torsional, ax=[panel], color="tab:orange")
    assert figure is panel.figure
    disc = panel.lines[0]
    np.testing.assert_array_equal(disc.get_ydata(), torsional["disc_speed"])
    assert disc.get_color() == "tab:orange"
    np.testing.assert_array_equal(panel.lines[1].get_ydata(), torsional["drive_speed"])
    ax = new_axes()
    assert plots.phase_portrait_axes([("stribeck", torsional)], ax=ax, linewidth=0.5) is ax
    np.testing.assert_array_equal(only_line(ax).get_xdata(), torsional["shaft_twist"])
    np.testing.assert_array_equal(only_line(ax).get_ydata(), torsional["disc_speed"])
    assert only_line(ax).get_linewidth() == 0.5


def test_friction_torque_hysteresis_into_three_axes():
    t = np.linspace(0.0, 1.0, 11)
    frame = pd.DataFrame({"t": t, "disc_speed": np.sin(t), "disc_acceleration": np.cos(t),
                          "friction_torque": 0.9 + 0.1 * t, "mode": np.zeros(11, dtype=int)})
    axes = new_axes(3)
    figure = plots.friction_torque_hysteresis_figure([("f", frame)], ax=axes, color="c")
    assert figure is axes[0].figure
    np.testing.assert_array_equal(axes[0].lines[0].get_xdata(), frame["disc_speed"])
    np.testing.assert_array_equal(axes[1].lines[0].get_xdata(), frame["disc_acceleration"])
    np.testing.assert_array_equal(axes[2].lines[0].get_ydata(), frame["disc_acceleration"])
    assert all(ax.lines[0].get_color() == "c" for ax in axes)


def test_reduction_and_power_law_figures_take_an_axes():
    frame = pd.DataFrame({"velocity_ratio": [0.1, 0.5, 1.0], "closed": [0.9, 0.6, 0.0], "axial": [0.88, 0.61, 0.02]})
    ax = new_axes()
    assert plots.reduction_sweep_axes(frame, [("closed", "closed form"), ("axial", "rig")], ax=ax,
                                      linewidth=4.0) is ax
    np.testing.assert_array_equal(ax.lines[1].get_ydata(), 100.0 * frame["axial"])
    assert all(line.get_linewidth() == 4.0 for line in ax.lines)
    from frictionsim.data import table4, table5

    ax = new_axes()
    fits = table5().set_index("lubricant")[["eta_prime", "exponent"]]  # the printed laws stand in for a refit
    assert plots.power_law_axes(table4(), fits, ax=ax, linewidth=2.0) is ax
    refits = [line for line in ax.lines if line.get_label().startswith("refit")]
    assert len(refits) == len(fits) and all(line.get_linewidth() == 2.0 for line in refits)


def test_well_path_and_broomstick_take_an_axes_and_style():
    survey = fs.Survey([0.0, 500.0, 1500.0], [0.0, 0.0, math.pi / 3], [0.3, 0.3, 0.3])
    ax = new_axes()
    assert plots.well_path_axes(survey, ax, view="plan", color="tab:red") is ax
    assert only_line(ax).get_color() == "tab:red"
    left, right = new_axes(2)
    assert plots.well_path_figure(survey, ax=[left, right]) is left.figure and right.lines


@pytest.mark.parametrize("name", ["friction_force", "drive_force", "power_law", "reduction_sweep", "phase_portrait"])
def test_single_panel_functions_are_named_axes_and_keep_their_former_figure_names(name):
    """The *_axes name is the function (its own __name__, in __all__); the *_figure name stays as an alias."""
    function = getattr(plots, f"{name}_axes")
    assert function.__name__ == f"{name}_axes" and getattr(plots, f"{name}_figure") is function
    assert {f"{name}_axes", f"{name}_figure"} <= set(plots.__all__)


def test_save_leaves_the_figure_as_it_was(torsional, tmp_path):
    """Writing a PNG does not take the figure away: the Axes of a Result's plot, and a figure of one's own, keep
    their axes and lines after save, and can be drawn on and saved again."""
    ax = torsional.plot()
    figure = ax.figure
    plots.save(ax, tmp_path / "a.png")
    assert figure.axes == [ax] and len(ax.lines) == 1
    ax.set_xlim(0.0, 1.0)
    assert plots.save(ax, tmp_path / "b.png").stat().st_size > 0
    own = Figure()
    own_ax = own.subplots()
    own_ax.plot([0.0, 1.0], [1.0, 2.0])
    plots.save(own, tmp_path / "c.png", release=True)  # release never clears a figure frictionsim did not make
    assert own.axes == [own_ax] and len(own_ax.lines) == 1
    plots.save(ax, tmp_path / "d.png", release=True)  # a figure frictionsim made, released by its last user
    assert figure.axes == []


def test_save_takes_a_figure_or_an_axes(torsional, tmp_path):
    ax = torsional.plot()
    path = plots.save(ax, tmp_path / "a.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    figure = plots.hysteresis_figure(pd.DataFrame({"t": [0.0, 1.0], "relative_displacement": [0.0, 1e-3],
                                                   "relative_velocity": [0.0, 1.0], "friction_force": [1.0, 2.0]}))
    assert plots.save(figure, tmp_path / "b.png").read_bytes()[:4] == b"\x89PNG"


# ------------------------------------------------------------------------------------------------ sweeps
def velocity_amplitude(amplitude, frequency=17.0):
    return 2 * math.pi * frequency * amplitude  # m/s


def test_sweep_plot_over_one_parameter_is_a_line():
    result = fs.sweep(velocity_amplitude, {"amplitude": [3e-3, 1e-3, 2e-3]}, progress=False)
    ax = new_axes()
    assert result.plot(ax=ax, color="r", marker="s") is ax
    line = only_line(ax)
    np.testing.assert_array_equal(line.get_xdata(), [1e-3, 2e-3, 3e-3])  # in order along the parameter
    np.testing.assert_array_equal(line.get_ydata(), [velocity_amplitude(a) for a in (1e-3, 2e-3, 3e-3)])
    assert line.get_color() == "r" and line.get_marker() == "s" and ax.get_xlabel() == "amplitude"


def test_sweep_plot_over_two_parameters_is_a_colour_map():
    grid = {"amplitude": [1e-3, 2e-3], "frequency": [10.0, 17.0, 25.0]}
    result = fs.sweep(velocity_amplitude, grid, progress=False)
    ax = new_axes()
    assert plots.sweep_axes(result, ax=ax, cmap="plasma") is ax
    mesh = ax.collections[0]
    np.testing.assert_array_equal(np.asarray(mesh.get_array()).ravel(), result.as_array().T.ravel())
    assert mesh.get_cmap().name == "plasma"
    with pytest.raises(InvalidParameterError, match="x must be one of amplitude, frequency"):
        result.plot(x="mass")


def test_sweep_of_dicts_needs_a_key():
    result = fs.sweep(lambda a: {"v": a, "w": 2 * a}, {"a": [1.0, 2.0]}, progress=False)
    with pytest.raises(InvalidParameterError, match="pass one of v, w") as error:
        result.plot()
    assert error.value.parameter == "key"
    np.testing.assert_array_equal(only_line(result.plot("w")).get_ydata(), [2.0, 4.0])


# ------------------------------------------------------------------------------------------------ severity index
def test_severity_of_a_sinusoid_is_amplitude_over_mean():
    m, amplitude = 5.76, 2.0  # rad/s
    t = np.linspace(0.0, 10.0, 40001)  # quarter periods of 1 Hz on the grid: the samples hold the peak and trough
    cycle = limit_cycle((t, m + amplitude * np.sin(2 * np.pi * t)))
    assert cycle.cycles >= 8
    assert cycle.severity == pytest.approx(amplitude / m, rel=1e-6)


def test_severity_of_a_stick_slip_cycle_is_peak_over_twice_the_mean():
    """The disc at rest half of each cycle, then a sine arch to the peak P: mean P / pi, severity pi / 2."""
    peak = 13.8
    t = np.linspace(0.0, 10.0, 100001)
    w = peak * np.maximum(0.0, np.sin(2 * np.pi * t))
    cycle = limit_cycle((t, w), stick_speed=1e-9)
    assert cycle.stick_slip and cycle.trough == 0.0 and cycle.peak == peak
    assert cycle.mean == pytest.approx(peak / math.pi, rel=1e-6)
    assert cycle.severity == pytest.approx(math.pi / 2, rel=1e-6)
    assert cycle.severity == peak / (2 * cycle.mean)


def test_severity_edge_cases():
    steady = LimitCycle(cycles=0, period=math.inf, frequency=0.0, peak=5.0, trough=5.0, mean=5.0, stick_fraction=0.0,
                        level=5.0, start=0.0, end=1.0)
    assert steady.severity == 0.0
    assert severity_index(1.0, -1.0, 0.0) == math.inf
    np.testing.assert_array_equal(severity_index([2.0, np.nan], [0.0, 1.0], [1.0, 1.0]), [1.0, np.nan])


def synthetic_map():
    speeds, forces = np.array([3.0, 6.0, 12.0]), np.array([25.0, 45.0])
    stick = np.array([[True, True], [True, False], [False, False]])
    severity = np.array([[1.9, 2.4], [1.2, 0.1], [0.02, 0.01]])
    frequency = np.array([[0.8, 0.7], [0.9, 0.0], [0.0, 0.0]])
    return StickSlipMap(speeds, forces, stick, frequency, 1.0 + severity, stick * 0.3, None,
                        np.zeros_like(stick), severity)


def test_stick_slip_map_axes_colours_the_severity():
    m = synthetic_map()
    ax = new_axes()
    assert m.plot(ax=ax, cmap="inferno", annotate=False) is ax
    mesh = ax.collections[0]
    np.testing.assert_array_equal(np.asarray(mesh.get_array()).ravel(), m.severity.T.ravel())
    assert mesh.get_cmap().name == "inferno"
    dots = ax.lines[0]  # the stick-slip cells
    np.testing.assert_array_equal(dots.get_xdata(), [3.0, 3.0, 6.0])
    with pytest.raises(InvalidParameterError, match="measure must be one of") as error:
        m.plot("amplitude")
    assert error.value.parameter == "measure"


def test_stick_slip_map_figure_with_the_severity_option():
    m = synthetic_map()
    axes = new_axes(2)
    figure = plots.stick_slip_map_figure(m, measures=("severity", "frequency"), ax=axes, point=None)
    assert figure is axes[0].figure
    np.testing.assert_array_equal(np.asarray(axes[0].collections[0].get_array()).ravel(), m.severity.T.ravel())
    frequency = np.asarray(axes[1].collections[0].get_array()).ravel()
    np.testing.assert_array_equal(frequency, np.where(m.frequency > 0, m.frequency, np.nan).T.ravel())
    # the default layout (peak ratio and frequency) still returns a Figure, as the CLI and demo use it
    assert isinstance(plots.stick_slip_map_figure(m), Figure)


def test_law_comparison_bars_take_style():
    frame = pd.DataFrame({"law": ["a", "b"], "frequency": [0.8, 0.0], "peak": [13.0, 5.76],
                          "stick_slip": [True, False], "natural_frequency": [0.789, 0.789]})
    axes = new_axes(2)
    figure = plots.law_comparison_figure(frame, ax=axes, color="g")
    assert figure is axes[0].figure
    bars = [p for p in axes[1].patches if p.get_height() > 0]
    assert [p.get_width() for p in bars] == [13.0, 5.76]
    assert all(p.get_facecolor() == to_rgba("g") for p in bars)
