"""Scenario files, plots and demo for paper 001's torsional rig (frictionsim.scenario and its torsional rig kind,
.plots, .demo)."""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import frictionsim as fs
from frictionsim import demo, plots, scenario
from frictionsim.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "scenarios" / "fig7_torsional.toml"
TEXT = EXAMPLE.read_text()
PNG = b"\x89PNG\r\n\x1a\n"
TORSIONAL_PLOTS = {"disc_speed.png", "friction_torque_hysteresis.png", "phase_portrait.png"}


def _short(text: str = TEXT, t_end: float = 8.0, transient: float = 4.0) -> str:
    """The example with a shorter run (the limit cycle settles within ~3 s)."""
    out = text.replace("t_end = 40.0 ", f"t_end = {t_end} ").replace("transient = 20.0 ", f"transient = {transient} ")
    assert out != text
    return out


def _files(directory: Path):
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*"))


def _assert_png(path: Path) -> None:
    data = path.read_bytes()
    assert data[:8] == PNG and len(data) > 10_000, path


# ---------------------------------------------------------------------------------------------- the example file
def test_example_is_package_data_and_matches_fig7_laws():
    assert EXAMPLE.is_symlink()
    assert demo.builtin_scenario("fig7_torsional").cases == scenario.load(EXAMPLE).cases
    cases = {case.name: case for case in scenario.load(EXAMPLE).cases}
    assert list(cases) == ["eq6", "stribeck", "lugre"]
    laws = fs.torsional.fig7_laws()
    # the numbers written out in the file are fig7_laws()'s
    assert repr(cases["eq6"].friction.build()) == repr(laws["hysteretic (eq 6)"]) == repr(fs.torsional.fig7_friction())
    assert repr(cases["stribeck"].friction.build()) == repr(laws["Stribeck"])
    assert repr(cases["lugre"].friction.build()) == repr(laws["LuGre"])
    for case in cases.values():
        rig = case.build()
        assert isinstance(rig, fs.TorsionalRig) and case.torsional
        assert (rig.reference_speed, rig.normal_force, rig.contact_radius) == (5.76, 35.0, 0.1)
        assert case.solver.t_end == 40.0 and case.solver.output_step == 1e-3
        assert (case.analysis.transient, case.analysis.stick_speed) == (20.0, 1e-2)
    assert scenario.load(EXAMPLE).output.plots == scenario.TORSIONAL_PLOTS


def test_fig7_shortcut_and_defaults():
    text = 'rig = { type = "torsional" }\nfriction = { type = "fig7" }\nsolver = { t_end = 6.0 }\n'
    parsed = scenario.loads(text, source="fig7.toml")
    (case,) = parsed.cases
    assert case.name == "fig7" and case.friction.label == "HystereticFriction"
    assert repr(case.friction.build()) == repr(fs.torsional.fig7_friction())
    assert repr(scenario.loads(text.replace('"fig7" }', '"fig7", branch_gap = "error" }')).cases[0].friction.build()) \
        == repr(fs.torsional.fig7_friction("error"))
    rig = case.build()
    assert rig.disc_inertia == fs.TorsionalRig(fs.torsional.fig7_friction()).disc_inertia  # engine defaults
    run = scenario.run_case(case)
    assert run.summary()["transient_s"] == 3.0 and run.summary()["stick_speed_rad_s"] == 1e-2  # t_end / 2, default
    assert parsed.output.plots == scenario.TORSIONAL_PLOTS
    # every rig key is a TorsionalRig keyword and property
    for key in scenario.rig_kind("torsional").keys:
        fs.TorsionalRig(fs.Coulomb(0.3), **{key: getattr(rig, key)})


def test_run_short_example_writes_expected_files(tmp_path, capsys):
    source = tmp_path / "fig7_torsional.toml"
    source.write_text(_short())
    out = tmp_path / "out"
    assert main(["run", str(source), "--out", str(out)]) == 0
    expected = {"eq6.csv", "stribeck.csv", "lugre.csv", "summary.csv", "scenario.toml", "metadata.json"} | TORSIONAL_PLOTS
    assert set(_files(out)) == expected
    assert _files(tmp_path) == ["fig7_torsional.toml", "out"] + [f"out/{f}" for f in sorted(expected)]
    for name in TORSIONAL_PLOTS:
        _assert_png(out / name)

    summary = pd.read_csv(out / "summary.csv").set_index("case")
    assert list(summary.index) == ["eq6", "stribeck", "lugre"]
    for column in ("frequency_Hz", "period_s", "peak_speed_rad_s", "trough_speed_rad_s", "stick_fraction",
                   "mean_friction_torque_Nm", "stick_slip", "cycles", "natural_frequency_Hz"):
        assert column in summary
    assert summary["stick_slip"].all()
    eq6 = summary.loc["eq6"]
    # Fig. 7: 0.83 Hz measured, 0.84 Hz the paper's model; the chosen eq 6 set gives 0.835 Hz and 13.8 rad/s
    assert eq6["frequency_Hz"] == pytest.approx(0.835, abs=0.01)
    assert eq6["peak_speed_rad_s"] == pytest.approx(13.8, abs=0.2)
    assert eq6["period_s"] == pytest.approx(1 / eq6["frequency_Hz"], rel=1e-9)  # CSV: 10 digits
    assert 0.1 < eq6["stick_fraction"] < 0.5 and eq6["trough_speed_rad_s"] >= 0.0
    assert summary["frequency_Hz"]["stribeck"] < summary["natural_frequency_Hz"]["stribeck"] < eq6["frequency_Hz"]
    assert 0.7 < eq6["mean_friction_torque_Nm"] < 1.4

    series = pd.read_csv(out / "eq6.csv")
    for column in ("t", "disc_speed", "drive_speed", "disc_acceleration", "friction_torque", "shaft_twist",
                   "current", "voltage", "shaft_torque", "disc_angle", "mode", "friction_work"):
        assert column in series
    assert series["t"].iloc[-1] == pytest.approx(8.0) and np.diff(series["t"]).max() == pytest.approx(1e-3)
    # the columns are consistent: J2 dw2/dt = S - T_f2 (eq 1a) on every row
    j2 = fs.TorsionalRig(fs.torsional.fig7_friction()).disc_inertia
    assert np.abs(j2 * series["disc_acceleration"] - (series["shaft_torque"] - series["friction_torque"])).max() < 1e-6

    stdout = capsys.readouterr().out
    assert "f [Hz]" in stdout and "stick" in stdout and "eq6" in stdout and "F_df" not in stdout


def test_limit_cycle_equals_direct_simulation():
    (case, *_) = scenario.loads(_short()).cases
    run = scenario.run_case(case)
    rig = fs.TorsionalRig(fs.torsional.fig7_friction(), reference_speed=5.76, normal_force=35.0, contact_radius=0.1)
    result = fs.simulate(rig, 8.0, rtol=1e-8, output_times=np.linspace(0.0, 8.0, 8001))
    cycle = fs.torsional.limit_cycle(result, 4.0, stick_speed=1e-2)
    row = run.summary()
    assert row["frequency_Hz"] == pytest.approx(cycle.frequency, rel=1e-6)
    assert row["peak_speed_rad_s"] == pytest.approx(cycle.peak, rel=1e-6)
    assert row["stick_fraction"] == pytest.approx(cycle.stick_fraction, abs=2e-4)
    assert row["cycles"] == cycle.cycles


def test_plot_subset_and_window(tmp_path):
    text = _short().replace('directory = "out/fig7_torsional"',
                            'plots = ["phase_portrait"]\nplot_window = [5.0, 8.0]\ntables = ["summary"]')
    source = tmp_path / "s.toml"
    source.write_text(text)
    assert scenario.load(source).output.plot_window == (5.0, 8.0)
    assert main(["run", str(source), "--out", str(tmp_path / "out")]) == 0
    assert set(_files(tmp_path / "out")) == {"summary.csv", "scenario.toml", "metadata.json", "phase_portrait.png"}
    _assert_png(tmp_path / "out" / "phase_portrait.png")


def test_hysteretic_written_out_with_defaults(tmp_path):
    text = ('rig = { type = "torsional", reference_speed = 8.0 }\n'
            'friction = { type = "hysteretic", stick_slope = 1384, accelerating = [0.95, -0.02, -0.00277, 5e-4, 0, '
            '2e-5], decelerating = [0.98, -0.02, -0.00277, 5e-4, 0, 2e-5] }\nsolver = { t_end = 2.0 }\n')
    (case,) = scenario.loads(text).cases
    law = case.friction.build()
    assert law.stick_speed == 1e-3 and law.reference_normal_force == 35.0 and law.branch_gap == "hold"
    assert law.accelerating == [0.95, -0.02, -0.00277, 5e-4, 0.0, 2e-5]
    assert case.name == "hysteretic" and case.build().reference_speed == 8.0
    assert math.isnan(case.friction.mu)


# ----------------------------------------------------------------------------------------------- bad scenarios
CASE_RIG = TEXT.replace('name = "eq6"\n', 'name = "eq6"\nrig = { disc_inertia = -0.0149 }\n')
BAD = [
    ("negative disc inertia", CASE_RIG, "case[1].rig.disc_inertia", "must be positive"),
    ("five coefficients", TEXT.replace("accelerating = [0.95, -0.02, -0.00315, 0.0005, 0.0, 2.0e-5]",
                                       "accelerating = [0.95, -0.02, -0.00315, 0.0005, 0.0]"),
     "case[1].friction.accelerating", "must be an array of 6 numbers"),
    ("coefficient not a number", TEXT.replace("accelerating = [0.95, -0.02,", 'accelerating = [0.95, "x",'),
     "case[1].friction.accelerating[2]", "must be a number"),
    ("coefficients not an array", TEXT.replace("decelerating = [0.98, -0.02, -0.00315, 0.0005, 0.0, 0.0]",
                                               "decelerating = 0.98"), "case[1].friction.decelerating",
     "must be an array"),
    ("non-finite coefficient", TEXT.replace("decelerating = [0.98,", "decelerating = [nan,"),
     "case[1].friction.decelerating", "must be finite"),
    ("negative stick slope", TEXT.replace("stick_slope = 1378.0 ", "stick_slope = -1378.0 "),
     "case[1].friction.stick_slope", "must be positive"),
    ("missing stick slope", TEXT.replace("stick_slope = 1378.0 ", "# "), "case[1].friction.stick_slope",
     "missing required value for a hysteretic law"),
    ("bad branch gap", TEXT.replace('branch_gap = "hold"', 'branch_gap = "skip"'), "case[1].friction.branch_gap",
     "must be 'hold' or 'error'"),
    ("branch gap not a string", TEXT.replace('branch_gap = "hold"', "branch_gap = 1"), "case[1].friction.branch_gap",
     "must be a string"),
    ("unknown hysteretic key", TEXT.replace("stick_slope = 1378.0 ", "stick_slop = 1378.0 "),
     "case[1].friction.stick_slop", "unknown key for a hysteretic law"),
    ("zero normal force", TEXT.replace("normal_force = 35.0 ", "normal_force = 0.0 ", 1), "rig.normal_force",
     "must be positive"),
    ("axial key on a torsional rig", TEXT.replace("contact_radius = 0.1 ", "mass = 0.2 "), "rig.mass",
     "unknown key for a torsional rig"),
    ("cycles for a torsional rig", TEXT.replace("transient = 20.0 ", "cycles = 10 "), "analysis.cycles",
     "unknown key for a torsional rig"),
    ("transient after the run", TEXT.replace("transient = 20.0 ", "transient = 40.0 "), "analysis.transient",
     "must be >= 0 and < t_end"),
    ("zero stick speed", TEXT.replace("stick_speed = 1.0e-2 ", "stick_speed = 0.0 "), "analysis.stick_speed",
     "must be positive"),
    ("axial plot", TEXT.replace('directory = "out/fig7_torsional"', 'plots = ["hysteresis"]'), "output.plots[1]",
     "must be one of disc_speed, friction_torque_hysteresis, phase_portrait for torsional rigs"),
    ("lubricant", TEXT.replace('name = "stribeck"', 'name = "stribeck"\nlubricant = "dry"'), "case[2].lubricant",
     "not for a torsional rig"),
    ("mixed rigs", TEXT.replace('name = "lugre"', 'name = "lugre"\nrig = { type = "axial" }\n'
                                                  'analysis = { cycles = 10 }'),
     "case[3].rig.type", "must be all torsional or all axial / kinematic"),
    ("eq 6 on an axial rig", 'rig = { type = "axial" }\nfriction = { type = "fig7" }\nsolver = { t_end = 1.0 }\n',
     "friction.type", "runs only on a torsional rig"),
    ("unknown friction type", TEXT.replace('type = "hysteretic"', 'type = "hysteresis"'), "case[1].friction.type",
     "must be one of " + ", ".join([law.key for law in fs.FRICTION_LAWS] + ["hysteretic", "fig7"])),
]


@pytest.mark.parametrize("label, text, key, rule", BAD, ids=[b[0] for b in BAD])
def test_bad_torsional_scenario_names_key(label, text, key, rule, tmp_path, capsys, monkeypatch):
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    monkeypatch.chdir(tmp_path)
    assert main(["run", str(bad), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {bad}: {key}: "), err
    assert rule in err, err
    assert "Traceback" not in err and err.count("\n") == 1
    assert _files(tmp_path) == ["bad.toml"]
    with pytest.raises(scenario.ScenarioError) as info:
        scenario.load(bad)
    assert info.value.key == key


def test_schema_doc_names_the_torsional_keys():
    doc = scenario.__doc__
    for word in ('type = "torsional"', "disc_inertia", '"hysteretic"', '"fig7"', "accelerating", "stick_speed",
                 "phase_portrait", "friction_torque_hysteresis", "disc_speed"):
        assert word in doc, word
    assert "Fig. 7b" in scenario.rig_kind("torsional").__doc__


# --------------------------------------------------------------------------------------------------------- plots
def test_plot_functions_are_headless(tmp_path):
    m = fs.torsional.stick_slip_map([3.0, 12.0], [25.0, 45.0], t_end=10.0, transient=5.0)
    figure = plots.stick_slip_map_figure(m, title="test")
    assert type(figure).__module__ == "matplotlib.figure"
    _assert_png(plots.save(figure, tmp_path / "map.png"))
    frame = pd.DataFrame({"law": ["a", "b"], "frequency": [0.8, 0.0], "peak": [13.0, 5.76],
                          "stick_slip": [True, False], "natural_frequency": [0.789, 0.789]})
    _assert_png(plots.save(plots.law_comparison_figure(frame), tmp_path / "laws.png"))


# ---------------------------------------------------------------------------------------------------------- demo
def test_demo_paper001_quick(tmp_path):
    part = demo.paper001(quick=True)
    part.write(tmp_path)
    files = set(_files(tmp_path))
    for name in ["law_comparison.csv", "law_comparison.png", "stick_slip_map.csv", "stick_slip_map.png",
                 "fig7_torsional/summary.csv", "fig7_torsional/eq6.csv", "fig7_torsional/lugre.csv"] + \
            [f"fig7_torsional/{p}" for p in TORSIONAL_PLOTS]:
        assert name in files, name
    for png in tmp_path.rglob("*.png"):
        _assert_png(png)

    laws = pd.read_csv(tmp_path / "law_comparison.csv").set_index("law")
    assert list(laws.index) == list(fs.torsional.fig7_laws())
    assert laws.loc["hysteretic (eq 6)", "frequency"] == pytest.approx(0.835, abs=0.01)
    assert laws.loc["hysteretic (eq 6)", "frequency"] > laws["natural_frequency"].iloc[0] > laws.loc["Stribeck",
                                                                                                       "frequency"]
    assert not laws.loc["Dahl", "stick_slip"]

    grid = pd.read_csv(tmp_path / "stick_slip_map.csv")
    assert len(grid) == len(demo.QUICK_MAP_REFERENCE_SPEEDS) * len(demo.QUICK_MAP_NORMAL_FORCES)
    fig7 = grid[(grid["reference_speed"] == 5.76) & (grid["normal_force"] == 35.0)].iloc[0]
    assert fig7["stick_slip"] == 1.0 and fig7["frequency"] == pytest.approx(0.835, abs=0.01)
    fast = grid[grid["reference_speed"] == max(demo.QUICK_MAP_REFERENCE_SPEEDS)]
    assert (fast["stick_slip"] == 0.0).all()  # high rotary speed: no sticking

    report = "\n".join(part.report(quick=True))
    for text in ("paper 001", "0.8300", "13.55", "0.789", "Stick-slip map", "hysteretic (eq 6)", "*"):
        assert text in report, text
