"""The frictionsim command line, scenario files and plots (frictionsim.cli, .scenario, .demo, .plots)."""

import io
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import frictionsim as fs
from frictionsim import demo, scenario
from frictionsim.cli import main
from frictionsim.data import table4
from frictionsim.fit import fit_power_law

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "scenarios"
EXAMPLE_FILES = ["fig7_dry_coulomb_vs_dahl.toml", "fig7_obm.toml", "kinematic_dahl.toml"]

# Table 5 as printed (paper 000), typed in here independently of the package's CSV.
PRINTED_SLOPES = {"dry": -0.36513, "water": -0.09531, "wbm": -0.16533, "obm": -0.20306, "sbm": -0.09244}


def _files(directory: Path):
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*"))


def _mean_directly(rig, t_end, points, period, transient, cycles, **solver):
    """F_df [N] straight from fs.simulate: the grid plus the window ends, mean over whole cycles."""
    t_a = transient
    times = np.union1d(np.linspace(0.0, t_end, points), [t_a, t_a + cycles * period])
    result = fs.simulate(rig, t_end, output_times=times, **solver)
    return result.mean_over_cycles(period=period, transient=t_a, cycles=cycles)


# ------------------------------------------------------------------------------------------------ run: examples
@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_run_example_writes_expected_files(name, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / name), "--out", str(out)]) == 0
    parsed = scenario.load(EXAMPLES / name)
    axial = any(case.rig.type == "axial" for case in parsed.cases)
    expected = {f"{case.name}.csv" for case in parsed.cases} | {"summary.csv", "scenario.toml",
                                                                "friction_force.png", "hysteresis.png",
                                                                "metadata.json"}
    if axial:
        expected.add("drive_force.png")
    assert set(_files(out)) == expected
    assert _files(tmp_path) == ["out"] + [f"out/{f}" for f in sorted(expected)]  # no staging left behind
    assert (out / "scenario.toml").read_text() == (EXAMPLES / name).read_text()
    for png in out.glob("*.png"):
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000

    summary = pd.read_csv(out / "summary.csv")
    assert list(summary["case"]) == [case.name for case in parsed.cases]
    for case in parsed.cases:
        series = pd.read_csv(out / f"{case.name}.csv")
        for column in ("t", "friction_force", "relative_velocity", "relative_displacement", "mode",
                       "friction_impulse"):
            assert column in series
        if case.rig.type == "axial":
            for column in ("position", "velocity", "drive_force"):
                assert column in series
        assert series["t"].iloc[0] == 0.0 and series["t"].iloc[-1] == pytest.approx(case.solver.t_end)

    stdout = capsys.readouterr().out
    assert "F_df [N]" in stdout and all(case.name in stdout for case in parsed.cases)


def test_run_fig7_dry_mean_equals_direct_simulation(tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / "fig7_dry_coulomb_vs_dahl.toml"), "--out", str(out)]) == 0
    summary = pd.read_csv(out / "summary.csv").set_index("case")
    period = 1 / 17.0
    for case, law in (("coulomb", fs.Coulomb(0.41)), ("dahl", fs.Dahl(0.41, 4e4))):
        rig = fs.AxialVibrationRig(friction=law, mass=0.2, drive_stiffness=2e4, sliding_velocity=1e-3,
                                   amplitude=5e-3, frequency=17.0, normal_force=90.0)
        expected = _mean_directly(rig, 2.0, 4001, period, 2.0 - 10 * period, 10, rtol=1e-8, atol=1e-12)
        row = summary.loc[case]
        assert row["F_df_N"] == pytest.approx(expected, rel=1e-9)
        assert row["mu_df"] == pytest.approx(expected / 90.0, rel=1e-9)
        assert row["reduction_percent"] == pytest.approx(100 * (1 - expected / (0.41 * 90.0)), rel=1e-9)
        assert row["cycles"] == 10 and row["events"] > 0 and row["steps"] > 0
        # Table 5 dry power law at v_a/v_d = 2 pi 17 Hz 5 mm / 1 mm/s (Table 4 VS3)
        assert row["F_df_table5_N"] == pytest.approx(
            1.0676 * (2 * math.pi * 17 * 5e-3 / 1e-3) ** -0.36513 * 90.0, rel=1e-9)
    assert summary.loc["dahl", "F_df_N"] == pytest.approx(0.054589, rel=1e-4)


@pytest.mark.parametrize("name", EXAMPLE_FILES)
def test_run_every_example_mean_equals_direct_simulation(name, tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / name), "--out", str(out)]) == 0
    summary = pd.read_csv(out / "summary.csv").set_index("case")
    for case in scenario.load(EXAMPLES / name).cases:
        law = {"coulomb": fs.Coulomb, "dahl": fs.Dahl}[case.friction.type](**case.friction.params)
        if case.rig.type == "axial":
            rig = fs.AxialVibrationRig(friction=law, **case.rig.params)
        else:
            rig = fs.KinematicRig.harmonic(law, **case.rig.params)
        a = case.analysis
        transient = a.transient if a.transient is not None else case.solver.t_end - a.cycles * rig.period
        times = np.union1d(case.solver.grid(), [transient, transient + a.cycles * rig.period])
        result = fs.simulate(rig, case.solver.t_end, rtol=case.solver.rtol, atol=case.solver.atol,
                             output_times=times)
        expected = result.mean_over_cycles(transient=transient, cycles=a.cycles)
        assert summary.loc[case.name, "F_df_N"] == pytest.approx(expected, rel=1e-9)


def test_kinematic_dahl_matches_hand_written_case(tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / "kinematic_dahl.toml"), "--out", str(out)]) == 0
    summary = pd.read_csv(out / "summary.csv").set_index("case")
    rig = fs.KinematicRig.harmonic(fs.Dahl(0.41, 3e4), sliding_velocity=1e-3, velocity_amplitude=0.534,
                                   frequency=17.0, normal_force=90.0)
    times = np.union1d(np.arange(0, 6001) * 1e-4, [0.2, 0.2 + 5 / 17])
    result = fs.simulate(rig, 0.6, rtol=1e-9, atol=1e-12, output_times=times)
    assert summary.loc["dahl_kt30", "F_df_N"] == pytest.approx(result.mean_over_cycles(transient=0.2, cycles=5),
                                                               rel=1e-9)
    # Coulomb in a kinematic rig: 1 - (2/pi) asin(v_d/v_a) reduction (closed form)
    coulomb = summary.loc["coulomb"]
    assert coulomb["reduction_percent"] / 100 == pytest.approx(1 - 2 / math.pi * math.asin(1e-3 / 0.534), rel=1e-6)


def test_velocity_file_case(tmp_path):
    t = np.linspace(0.0, 0.5, 2001)
    v = 1e-3 - 0.2 * np.cos(2 * math.pi * 20 * t)
    np.savetxt(tmp_path / "v.csv", np.column_stack([t, v]), delimiter=",", header="t,v", comments="")
    (tmp_path / "s.toml").write_text(
        'rig = { type = "kinematic", velocity_file = "v.csv", normal_force = 30.0 }\n'
        'friction = { type = "dahl", mu = 0.27, tangential_stiffness = 4e4 }\n'
        'solver = { t_end = 0.5, output_points = 501 }\n'
        'analysis = { period = 0.05, transient = 0.1, cycles = 6 }\n')
    out = tmp_path / "out"
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(out)]) == 0
    assert set(_files(out)) == {"dahl.csv", "summary.csv", "friction_force.png", "hysteresis.png", "metadata.json"}
    rig = fs.KinematicRig(fs.Dahl(0.27, 4e4), relative_velocity=(t, v), normal_force=30.0)
    times = np.union1d(np.linspace(0, 0.5, 501), [0.1, 0.4])
    expected = fs.simulate(rig, 0.5, output_times=times).mean_over_cycles(period=0.05, transient=0.1, cycles=6)
    assert pd.read_csv(out / "summary.csv")["F_df_N"].iloc[0] == pytest.approx(expected, rel=1e-9)


def test_single_case_file_and_defaults(tmp_path):
    text = ('[rig]\ntype = "axial"\namplitude = 4e-3\nfrequency = 20.0\nnormal_force = 30.0\n'
            '[friction]\ntype = "coulomb"\nmu = 0.27\n[solver]\nt_end = 1.0\n')
    parsed = scenario.loads(text, source=tmp_path / "one.toml")
    (case,) = parsed.cases
    assert case.name == "coulomb" and parsed.name == "one"
    assert case.window() == pytest.approx((0.5, 1.0, 10))  # default: whole cycles after t_end / 2
    assert case.build().mass == 0.2  # engine default
    assert parsed.output.plots == ("friction_force", "hysteresis", "drive_force")


# ----------------------------------------------------------------------------------------------- bad scenarios
DRY = (EXAMPLES / "fig7_dry_coulomb_vs_dahl.toml").read_text()

BAD = [
    ("unknown key", DRY.replace("mass = 0.2 ", "mas = 0.2 "), "rig.mas", "unknown key"),
    ("unknown case key", DRY.replace('name = "dahl"', 'name = "dahl"\ncolour = "red"'), "case[2].colour",
     "unknown key"),
    ("unknown law key", DRY.replace("tangential_stiffness = 4.0e4", "tangential_stiffnes = 4.0e4"),
     "case[2].friction.tangential_stiffnes", "unknown key for a dahl law"),
    ("missing value", DRY.replace("mu = 0.41, tangential", "tangential"), "case[2].friction.mu",
     "missing required value"),
    ("missing t_end", DRY.replace("t_end = 2.0 ", "# t_end"), "solver.t_end", "missing required value"),
    ("wrong type", DRY.replace("t_end = 2.0 ", "t_end = [2.0] "), "solver.t_end", "must be a number"),  # "2": 2 s
    ("wrong type bool", DRY.replace("mass = 0.2 ", "mass = true "), "rig.mass", "must be a number"),
    ("negative mass", DRY.replace("mass = 0.2 ", "mass = -0.2 "), "rig.mass", "must be positive"),
    ("negative stiffness", DRY.replace("tangential_stiffness = 4.0e4", "tangential_stiffness = -4.0e4"),
     "case[2].friction.tangential_stiffness", "must be positive"),
    ("mu_static below mu", DRY.replace("mu = 0.41 }", "mu = 0.41, mu_static = 0.3 }"),
     "case[1].friction.mu_static", "must be >="),
    ("unknown law type", DRY.replace('type = "dahl"', 'type = "dhal"'), "case[2].friction.type",
     "must be one of coulomb, stribeck, dahl, lugre"),
    ("unknown rig type", DRY.replace('type = "axial"', 'type = "rotary"'), "rig.type",
     "must be one of axial, kinematic, torsional"),
    ("unknown method", DRY.replace("rtol = 1e-8", 'method = "rk4"'), "solver.method", "must be one of"),
    ("window too long", DRY.replace("cycles = 10 ", "cycles = 100 "), "analysis.cycles", "must fit"),
    ("transient too long", DRY.replace("cycles = 10 ", "transient = 5.0 "), "analysis.transient", "must be"),
    ("unknown lubricant", DRY.replace('lubricant = "dry"', 'lubricant = "mud"', 1), "case[1].lubricant",
     "must be one of dry"),
    ("duplicate name", DRY.replace('name = "dahl"', 'name = "coulomb"'), "case[2].name", "duplicate case name"),
    ("unknown plot", DRY.replace('directory = "out/fig7_dry"', 'plots = ["bode"]'), "output.plots[1]",
     "must be one of"),
    ("kinematic missing", 'rig = {type = "kinematic", normal_force = 90.0, sliding_velocity = 1e-3, '
                          'frequency = 17.0}\nfriction = {type = "dahl", mu = 0.4, tangential_stiffness = 4e4}\n'
                          'solver = {t_end = 1.0}\n', "rig.velocity_amplitude", "missing required value"),
    ("missing velocity file", 'rig = {type = "kinematic", normal_force = 90.0, velocity_file = "nope.csv"}\n'
                              'friction = {type = "dahl", mu = 0.4, tangential_stiffness = 4e4}\n'
                              'solver = {t_end = 1.0}\nanalysis = {period = 0.1}\n', "rig.velocity_file",
     "cannot read"),
    ("no friction", 'rig = {type = "axial"}\nsolver = {t_end = 1.0}\n', "friction", "missing required table"),
    ("rtol of 100%", DRY.replace("rtol = 1e-8", "rtol = 5.0"), "solver.rtol", "must be in [1e-14, 0.1]"),
    ("plot window after the run", DRY.replace('directory = "out/fig7_dry"', "plot_window = [10.0, 20.0]"),
     "output.plot_window", "must start before the shortest run ends"),
    ("too many output points", DRY.replace("output_points = 4001", "output_points = 10000000000"),
     "solver.output_points", "must be in [2, "),
    ("latin-1 velocity file", 'rig = {type = "kinematic", normal_force = 90.0, velocity_file = "v.csv"}\n'
                              'friction = {type = "dahl", mu = 0.4, tangential_stiffness = 4e4}\n'
                              'solver = {t_end = 1.0}\nanalysis = {period = 0.1}\n', "rig.velocity_file",
     "must be UTF-8 text"),
]


@pytest.mark.parametrize("label, text, key, rule", BAD, ids=[b[0] for b in BAD])
def test_bad_scenario_names_file_and_key_and_writes_nothing(label, text, key, rule, tmp_path, capsys,
                                                            monkeypatch):
    work = tmp_path / "work"
    work.mkdir()
    bad = work / "bad.toml"
    bad.write_text(text)
    if label == "latin-1 velocity file":  # an instrument's header in Latin-1: t [\xb5s]
        (work / "v.csv").write_bytes("t [\xb5s], v [m/s]\n0, 1\n1, 1\n".encode("latin-1"))
    monkeypatch.chdir(work)  # the file's own output.directory (out/fig7_dry) must not appear either
    assert main(["run", str(bad)]) == 2
    assert main(["run", str(bad), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {bad}: {key}: "), err
    assert rule in err
    assert "Traceback" not in err and err.count("\n") == 2
    assert [f for f in _files(tmp_path) if f != "work/v.csv"] == ["work", "work/bad.toml"]
    with pytest.raises(scenario.ScenarioError) as info:
        scenario.load(bad)
    assert info.value.key == key and info.value.file == str(bad)


def test_bad_toml_syntax_and_missing_file(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(DRY.replace("cycles = 10 ", "cycles = "))
    assert main(["run", str(bad), "--out", str(tmp_path / "out")]) == 2
    assert main(["run", str(tmp_path / "none.toml"), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"error: {bad}: invalid TOML:") and "line" in err[0]
    assert err[1].startswith(f"error: {tmp_path / 'none.toml'}: cannot read")
    assert _files(tmp_path) == ["bad.toml"]


def test_simulation_failure_reports_time_and_writes_nothing(tmp_path, capsys, monkeypatch):
    def failing(*args, **kwargs):
        raise fs.SimulationError("integrator step size underflow", 0.625)

    monkeypatch.setattr(scenario.runner, "simulate", failing)
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / "fig7_obm.toml"), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "case[1] 'coulomb'" in err and "t = 0.625 s" in err and "underflow" in err
    assert "Traceback" not in err
    assert not out.exists() and _files(tmp_path) == []


def test_output_into_existing_directory_and_onto_a_file(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    (out / "summary.csv").write_text("old")
    # an output that exists is replaced only with --force (issue 23): refused, nothing moved in
    assert main(["run", str(EXAMPLES / "fig7_obm.toml"), "--out", str(out)]) == 1
    assert "summary.csv exists" in capsys.readouterr().err and (out / "summary.csv").read_text() == "old"
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt", "summary.csv"]
    assert main(["run", str(EXAMPLES / "fig7_obm.toml"), "--out", str(out), "--force"]) == 0
    assert (out / "keep.txt").read_text() == "mine"
    assert (out / "summary.csv").read_text().startswith("case,law")
    assert _files(tmp_path)[0] == "out" and all(f.startswith("out") for f in _files(tmp_path))
    (tmp_path / "file").write_text("")
    assert main(["run", str(EXAMPLES / "fig7_obm.toml"), "--out", str(tmp_path / "file")]) == 2
    assert "not a directory" in capsys.readouterr().err


# ------------------------------------------------------------------------------------------- fit-table5 and demo
def test_fit_table5_matches_printed_slopes(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["fit-table5", "--out", str(out)]) == 0
    assert set(_files(out)) == {"table5_refit.csv", "fig11_power_law.png", "metadata.json"}
    assert json.loads((out / "metadata.json").read_text())["command"] == f"frictionsim fit-table5 --out {out}"
    refit = pd.read_csv(out / "table5_refit.csv").set_index("lubricant")
    for lubricant, slope in PRINTED_SLOPES.items():
        assert round(refit.loc[lubricant, "slope_refit"], 5) == slope
        assert refit.loc[lubricant, "slope_printed"] == slope
    stdout = capsys.readouterr().out
    assert "-0.36513" in stdout and "slope (printed)" in stdout and "obm" in stdout
    # the refit's standard errors, as fit_power_law gives them (the paper prints none): in the CSV and the report
    fits = fit_power_law(table4())
    columns = ["slope_stderr", "intercept_stderr", "eta_prime_stderr", "eta_eq15_stderr"]
    for frame in (refit, demo.table5_refit().set_index("lubricant")):
        assert set(columns + ["eta_eq15_refit"]) <= set(frame.columns)
        for column in columns:
            np.testing.assert_allclose(frame.loc[fits.index, column], fits[column], rtol=1e-9)  # CSV: 10 digits
        np.testing.assert_allclose(frame.loc[fits.index, "eta_eq15_refit"], fits["eta_eq15"], rtol=1e-9)
    dry = next(line.split() for line in stdout.splitlines() if line.startswith("dry "))
    # dry: slope -0.36513 +- 0.107, intercept +- 0.296, eta' 1.0676 +- 0.729 (fit.power_law's docstring)
    assert dry[3] == f"{fits.loc['dry', 'slope_stderr']:.3f}" == "0.107"
    assert dry[6] == f"{fits.loc['dry', 'intercept_stderr']:.3f}"
    assert dry[9] == f"{fits.loc['dry', 'eta_prime_stderr']:.3f}" == "0.729"
    assert "+- one standard error" in stdout


def test_toml_is_read_without_tomllib_as_on_python_3_10(tmp_path):
    """Python < 3.11 has no tomllib (pyproject allows 3.9): every TOML reader of the package goes through
    scenario.parser.read_toml / loads_toml, which fall back to tomli. Simulated: tomllib hidden, tomli standing in."""
    package = Path(fs.__file__).parent
    importers = sorted(str(path.relative_to(package)) for path in package.rglob("*.py")
                       if re.search(r"^\s*(import tomllib|from tomllib)", path.read_text(encoding="utf-8"), re.M))
    assert importers == ["scenario/parser.py"]
    sweep = tmp_path / "s.toml"
    sweep.write_text('scenario = "obm.toml"\n[grid]\n"rig.frequency" = [15.0, 20.0]\n')
    (tmp_path / "obm.toml").write_bytes((EXAMPLES / "fig7_obm.toml").read_bytes())
    script = f"""
import sys
import tomllib
sys.modules["tomli"], sys.modules["tomllib"] = tomllib, None  # as on Python 3.10 with tomli installed
from frictionsim import cli, scenario
from frictionsim.scenario import parser, sweep_file
assert parser.tomllib.__name__ == "tomllib" and sys.modules["tomllib"] is None
print(len(sweep_file.load({str(sweep)!r}).points), len(scenario.load({str(tmp_path / "obm.toml")!r}).cases))
sys.exit(cli.main(["scenarios", "list"]))
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0] == "2 2" and any(line.startswith("velocity_ratio_sweep ") for line in lines)


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_demo_quick(tmp_path, capsys, monkeypatch):
    out = tmp_path / "out"
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)  # the progress bar shows on a terminal only
    assert main(["demo", "--quick", "--out", str(out)]) == 0
    assert "demo:   0%|" in terminal.getvalue() and f"/{len(demo.STAGES)} [" in terminal.getvalue()
    files = set(_files(out))
    record = json.loads((out / "metadata.json").read_text())
    assert record["command"] == f"frictionsim demo --quick --out {out}" and record["extra"]["quick"] is True
    for name in ("fig7_friction_reduction.csv", "friction_reduction.csv", "friction_reduction.png",
                 "table5_refit.csv", "fig11_power_law.png", "fig7_dry/summary.csv", "fig7_dry/dahl.csv",
                 "fig7_dry/coulomb.csv", "fig7_dry/friction_force.png", "fig7_obm/friction_force.png",
                 "fig7_obm/summary.csv", "paper001/fig7_torsional/summary.csv", "paper001/fig7_torsional/eq6.csv",
                 "paper001/fig7_torsional/disc_speed.png", "paper001/fig7_torsional/friction_torque_hysteresis.png",
                 "paper001/fig7_torsional/phase_portrait.png", "paper001/law_comparison.csv",
                 "paper001/law_comparison.png", "paper001/stick_slip_map.csv", "paper001/stick_slip_map.png"):
        assert name in files

    reduction = pd.read_csv(out / "fig7_friction_reduction.csv")
    assert list(reduction["law"]) == ["Coulomb", "Dahl", "Coulomb", "Dahl"]
    assert list(reduction["table4_run"]) == ["VS3", "VS3", "VS17", "VS17"]
    assert list(reduction["F_df_table4_N"]) == [9.27, 9.27, 1.02, 1.02]
    dry = pd.read_csv(out / "fig7_dry" / "summary.csv").set_index("case")
    assert reduction["F_df_sim_N"].iloc[1] == pytest.approx(dry.loc["dahl", "F_df_N"], rel=1e-9)
    # without vibration the steady sliding force is mu F_N
    assert reduction["F_sf_sim_N"].to_numpy() == pytest.approx([36.9, 36.9, 8.1, 8.1], rel=1e-3)

    sweep = pd.read_csv(out / "friction_reduction.csv")
    assert sweep["kinematic_coulomb"].to_numpy() == pytest.approx(sweep["coulomb_closed_form"].to_numpy(),
                                                                  abs=1e-6)
    # the horizontal well: sliding in without the tool is the slack-off (Coulomb: speed-independent), the tool only
    # adds hook load (it takes drag away), and the placement is the best point of its curve
    well = pd.read_csv(out / "horizontal_well" / "broomstick.csv")
    trip = well[(well["operation"] == "trip_in") & ~well["tool"]].set_index(["bit_depth", "friction_factor"])
    for with_tool in (False, True):
        sliding = well[(well["operation"] == "sliding_drilling") & (well["tool"] == with_tool)]
        reference = trip.loc[list(zip(sliding["bit_depth"], sliding["friction_factor"])), "hook_load"].to_numpy()
        if with_tool:
            assert np.all(sliding["hook_load"].to_numpy() >= reference - 1e-6)
            assert np.any(sliding["hook_load"].to_numpy() > reference + 1e3)
        else:
            assert sliding["hook_load"].to_numpy() == pytest.approx(reference, rel=1e-12, abs=1e-6)
    placement = pd.read_csv(out / "horizontal_well" / "placement.csv")
    assert (out / "horizontal_well" / "placement.png").exists()
    assert (out / "horizontal_well" / "broomstick.png").exists()
    stdout = capsys.readouterr().out
    best = float(re.search(r"the bit\), ([0-9.]+) kN on the bit", stdout).group(1))
    assert best * 1e3 >= placement["weight_on_bit"].max() - 100.0  # printed to 0.1 kN
    for text in ("Fig. 7 cases", "VS3", "VS17", "Table 5 refit", "-0.36513", "Coulomb exact", "paper 001",
                 "Stick-slip map", "horizontal well", "Placement while sliding"):
        assert text in stdout


def test_demo_builtin_scenarios_are_the_example_files():
    # one definition: the demo runs the package's scenario files, which examples/scenarios/ links to
    for name in demo.BUILTIN_SCENARIOS:
        assert demo.builtin_scenario(name).cases == scenario.load(EXAMPLES / f"{name}.toml").cases


# ------------------------------------------------------------------------------------------------- entry points
def test_help_and_version_in_process(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and capsys.readouterr().out.strip() == f"frictionsim {fs.__version__}"
    with pytest.raises(SystemExit) as info:
        main(["run", "--help"])
    assert info.value.code == 0 and "SCENARIO" in capsys.readouterr().out.upper()
    assert main([]) == 2


def test_console_script_subprocess(tmp_path):
    script = Path(sys.executable).parent / "frictionsim"
    command = [str(script)] if script.exists() else [sys.executable, "-m", "frictionsim"]
    done = subprocess.run(command + ["--help"], capture_output=True, text=True, timeout=60, cwd=tmp_path)
    assert done.returncode == 0
    for word in ("run", "demo", "fit-table5", "--version"):
        assert word in done.stdout
    done = subprocess.run([sys.executable, "-m", "frictionsim", "run", "missing.toml"], capture_output=True,
                          text=True, timeout=60, cwd=tmp_path)
    assert done.returncode == 2 and done.stderr.startswith("error: missing.toml: ")
    assert os.listdir(tmp_path) == []


def test_blocked_output_replaces_nothing(tmp_path, capsys):
    # an existing output directory where one file cannot be written: no file of the run is moved in
    out = tmp_path / "out"
    (out / "summary.csv").mkdir(parents=True)
    (out / "coulomb.csv").write_text("old")
    assert main(["run", str(EXAMPLES / "fig7_dry_coulomb_vs_dahl.toml"), "--out", str(out)]) == 1
    assert "cannot write" in capsys.readouterr().err
    assert (out / "coulomb.csv").read_text() == "old" and sorted(p.name for p in out.iterdir()) == [
        "coulomb.csv", "summary.csv"]
    assert _files(tmp_path) == ["out", "out/coulomb.csv", "out/summary.csv"]  # staging removed


def test_velocity_file_must_start_at_the_run_start(tmp_path):
    (tmp_path / "v.csv").write_text("t, v\n1.0, 0.1\n2.0, 0.1\n")
    bad = tmp_path / "late.toml"
    bad.write_text('rig = {type = "kinematic", normal_force = 90.0, velocity_file = "v.csv"}\n'
                   'friction = {type = "coulomb", mu = 0.4}\nsolver = {t_end = 1.5}\nanalysis = {period = 0.1}\n')
    with pytest.raises(scenario.ScenarioError) as info:
        scenario.load(bad)
    assert info.value.key == "rig.velocity_file" and "must start at t <= 0" in str(info.value)


def test_fit_power_law_rejects_unusable_tables():
    from frictionsim.fit import fit_power_law
    import pandas as pd

    with pytest.raises(ValueError, match="DataFrame"):
        fit_power_law({"velocity_ratio": [1.0]})
    with pytest.raises(ValueError, match="mu_df"):
        fit_power_law(pd.DataFrame({"velocity_ratio": [1.0, 2.0]}))
    with pytest.raises(ValueError, match="lubricant"):
        fit_power_law(lubricant=3)


# ------------------------------------------------------------------------------------------------ torque-drag
SURVEYS = ROOT / "examples" / "surveys"


def test_torque_drag_writes_node_table_broomstick_and_plots_into_out(tmp_path, capsys):
    from frictionsim import wells

    out = tmp_path / "td"
    survey_file = SURVEYS / "j_well.csv"
    assert main(["torque-drag", str(survey_file), "--mu", "0.2", "0.3", "--wob", "1e5", "--out", str(out)]) == 0
    expected = {"torque_drag.csv", "broomstick.csv", "trajectory.csv", "broomstick.png", "well_path.png",
                "metadata.json"}
    assert set(_files(out)) == expected
    assert _files(tmp_path) == ["td"] + [f"td/{f}" for f in sorted(expected)]  # nothing outside --out
    for png in out.glob("*.png"):
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    nodes = pd.read_csv(out / "torque_drag.csv")
    assert set(nodes["operation"]) == {"trip_in", "trip_out", "rotating_off_bottom", "sliding_drilling",
                                       "rotary_drilling"}
    assert set(nodes["friction_factor"]) == {0.2, 0.3}
    # the default string (5" pipe over 150 m of collars to the survey's 3000 m) through the Python API
    string = fs.DrillString([fs.PipeSection(length=2850.0),
                             fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
    survey = wells.read_survey(survey_file)
    for op in ("trip_out", "sliding_drilling"):
        direct = wells.torque_drag(survey, string, op, open_hole_friction=0.3, cased_hole_friction=0.3,
                                   weight_on_bit=1e5)
        rows = nodes[(nodes["operation"] == op) & (nodes["friction_factor"] == 0.3)]
        np.testing.assert_allclose(rows["tension"], direct.tension, rtol=1e-9)
        # side forces lumped at nodes keep the elements' total
        assert rows["side_force"].sum() == pytest.approx(np.sum(direct.side_force), rel=1e-9)
    broom = pd.read_csv(out / "broomstick.csv")
    last = broom[(broom["bit_depth"] == 3000.0) & (broom["operation"] == "trip_out")
                 & (broom["friction_factor"] == 0.3)]
    assert float(last["hook_load"].iloc[0]) == pytest.approx(
        wells.torque_drag(survey, string, "trip_out", open_hole_friction=0.3, cased_hole_friction=0.3).hook_load,
        rel=1e-9)
    stdout = capsys.readouterr().out
    assert "hook_load_kN" in stdout and "bit at 3000 m" in stdout


def test_torque_drag_bad_survey_names_file_line_station_and_field(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("md [m],inc [deg],azi [deg]\n0,0,0\n500,10,0\n450,20,0\n")
    out = tmp_path / "out"
    assert main(["torque-drag", str(bad), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"error: {bad}: line 4: station 2: measured_depth must be >" in err
    assert not out.exists()
    bad.write_text("md [m],inc [deg],azi [deg]\n0,0,0\n500,190,0\n")
    assert main(["torque-drag", str(bad), "--out", str(out)]) == 2
    assert "line 3: station 1: inclination must be in [0, 180] degrees (got 190)" in capsys.readouterr().err
    bad.write_text("md [m],inc [deg],azi [deg]\n0,0,0\n")
    assert main(["torque-drag", str(bad), "--out", str(out)]) == 2
    assert "stations must be at least 2" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize("string, message", [
    ("0.127:0.1086", "expected OD:ID:LENGTH"),
    ("0.127:0.1086:*,0.1651:0.0714:*", "only one section's LENGTH may be '*'"),
    ("0.127:0.1086:1000", "the sections add up to 1000 m, the bit depth is 1000 m"),
    ("0.127:0.2:*", "section 0: PipeSection: inner_diameter must be < outer_diameter"),
    ("0.127:0.1086:3300", "survey must reach the bit"),
])
def test_torque_drag_bad_string_is_a_clear_error(string, message, tmp_path, capsys):
    if "add up" in message:  # consistent: no error when the sections fill the given depth
        assert main(["torque-drag", str(SURVEYS / "s_well.csv"), "--string", string, "--depth", "1000",
                     "--out", str(tmp_path / "ok"), "--mu", "0.3"]) == 0
        assert main(["torque-drag", str(SURVEYS / "s_well.csv"), "--string", string, "--depth", "1200",
                     "--out", str(tmp_path / "no")]) == 2
        assert "the sections add up to 1000 m, the bit depth is 1200 m" in capsys.readouterr().err
        return
    assert main(["torque-drag", str(SURVEYS / "s_well.csv"), "--string", string, "--out", str(tmp_path / "o")]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "o").exists()
