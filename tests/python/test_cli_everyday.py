"""The command line's everyday jobs (issue 15 item 7, item 3's CLI side): -q / -v, progress bars, --jobs, Ctrl-C,
``scenarios list|copy``, ``sweep``, ``fit`` and metadata.json beside every command's outputs."""

import argparse
import hashlib
import io
import json
import logging
import math
import os
import signal
import subprocess
import sys
import time
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import frictionsim as fs
from frictionsim import scenario
from frictionsim.cli import main
from frictionsim.scenario import sweep_file

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "scenarios"
PACKAGED = resources.files("frictionsim").joinpath("scenarios")


def _files(directory: Path):
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*"))


def _metadata(directory: Path) -> dict:
    return json.loads((directory / "metadata.json").read_text(encoding="utf-8"))


# A kinematic Coulomb rig: the mean friction over whole cycles has the closed form F_df = mu F_N (2/pi) asin(v_d/v_a)
# for v_a > v_d (1 - F_df / (mu F_N) = 1 - (2/pi) asin(v_d/v_a)), and mu F_N without reversals
KINEMATIC = """
title = "kinematic Coulomb"
[rig]
type = "kinematic"
sliding_velocity = 1e-3
velocity_amplitude = 0.01
frequency = 20.0
normal_force = 50.0
[solver]
t_end = 0.3
rtol = 1e-10
atol = 1e-12
output_points = 301
[analysis]
transient = 0.05
cycles = 4
[[case]]
name = "coulomb"
friction = { type = "coulomb", mu = 0.3 }
[[case]]
name = "dahl"
friction = { type = "dahl", mu = 0.3, tangential_stiffness = 4e4 }
"""
#: KINEMATIC for `run` where no test looks at the plots: drawing them is ~95 % of such a run's time
RUN = KINEMATIC + "[output]\nplots = []\n"


# --------------------------------------------------------------------------------------------- -q, -v, progress
def test_verbose_logs_the_cases_and_quiet_silences_stderr(tmp_path, capsys):
    source = tmp_path / "k.toml"
    source.write_text(RUN)
    logger = logging.getLogger("frictionsim")
    level, handlers = logger.level, list(logger.handlers)
    assert main(["-v", "run", str(source), "--out", str(tmp_path / "a")]) == 0
    err = capsys.readouterr().err
    assert "INFO: frictionsim.cli: " in err and "case[1] 'coulomb'" in err and "case[2] 'dahl'" in err
    assert main(["run", str(source), "--out", str(tmp_path / "c")]) == 0
    assert capsys.readouterr().err == ""  # not a terminal: no progress bar, and no INFO without -v
    assert logger.level == level and logger.handlers == handlers  # main() leaves the library's logger as it was


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_bar_only_on_a_terminal_and_not_with_quiet(tmp_path, monkeypatch):
    source = tmp_path / "k.toml"
    source.write_text(RUN)
    for quiet, shown in (([], True), (["-q"], False)):
        terminal = _Terminal()
        monkeypatch.setattr(sys, "stderr", terminal)
        assert main(["run", *quiet, str(source), "--out", str(tmp_path / str(shown))]) == 0
        text = terminal.getvalue()
        assert ("k: " in text and "/2 [" in text) == shown, text


# --------------------------------------------------------------------------------------------------------- --jobs
def test_jobs_gives_the_same_files_as_one_process(tmp_path):
    source = tmp_path / "k.toml"
    source.write_text(RUN)
    assert main(["run", str(source), "--out", str(tmp_path / "one")]) == 0
    assert main(["run", str(source), "--jobs", "2", "--out", str(tmp_path / "two")]) == 0
    files = [f for f in _files(tmp_path / "one") if f.endswith(".csv")]
    assert files == ["coulomb.csv", "dahl.csv", "summary.csv"]
    for name in files:  # bit for bit: the same simulations, in the same order
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()
    summary = pd.read_csv(tmp_path / "two" / "summary.csv").set_index("case")
    closed_form = 100 * (1 - 2 / math.pi * math.asin(1e-3 / 0.01))
    assert summary.loc["coulomb", "reduction_percent"] == pytest.approx(closed_form, rel=1e-6)
    assert _metadata(tmp_path / "two")["command"].endswith("--jobs 2 --out " + str(tmp_path / "two"))


def test_jobs_are_capped_at_the_cpus_this_process_may_use(monkeypatch, caplog):
    from frictionsim import cli

    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)  # a 2-CPU share
    with caplog.at_level(logging.WARNING, logger="frictionsim"):
        assert cli._workers(2, 10) == 2 and cli._workers(8, 1) == 1 and not caplog.records
        assert cli._workers(1000, 10) == 2  # not a thousand interpreters
    assert [r.getMessage() for r in caplog.records] == ["--jobs 1000: this process may use 2 CPUs; running 2 "
                                                        "processes"]
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {3}, raising=False)
    with cli._imap(64, 10) as imap:  # one CPU: no pool at all
        assert imap is map
    monkeypatch.delattr(os, "sched_getaffinity", raising=False)  # macOS, Windows: the machine's count
    monkeypatch.setattr(os, "cpu_count", lambda: 3)
    assert cli._workers(16, 100) == 3


def test_run_and_sweep_share_their_output_options():
    from frictionsim import cli

    commands = next(a for a in cli._parser()._actions if isinstance(a, argparse._SubParsersAction)).choices
    options = {name: {a.dest: (a.option_strings, a.help) for a in commands[name]._actions
                      if a.dest in ("out", "allow_outside", "jobs")} for name in ("run", "sweep")}
    assert options["run"] == options["sweep"] and len(options["run"]) == 3


def test_jobs_must_be_a_positive_whole_number(capsys):
    for bad in ("0", "two"):
        with pytest.raises(SystemExit) as info:
            main(["run", "x.toml", "--jobs", bad])
        assert info.value.code == 2
    assert "--jobs" in capsys.readouterr().err


# ------------------------------------------------------------------------------------------------------- Ctrl-C
LONG = """
rig = { type = "kinematic", sliding_velocity = 1e-3, velocity_amplitude = 0.5, frequency = 17.0, normal_force = 90.0 }
solver = { t_end = 1.0e5, output_points = 1001 }
analysis = { cycles = 5 }
[[case]]
name = "first"
friction = { type = "dahl", mu = 0.4, tangential_stiffness = 4e4 }
[[case]]
name = "second"
friction = { type = "dahl", mu = 0.3, tangential_stiffness = 4e4 }
"""


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_ctrl_c_exits_130_without_traceback_or_outputs(jobs, tmp_path):
    (tmp_path / "long.toml").write_text(LONG)  # hours of simulated vibration: it never ends by itself here
    out = tmp_path / "out"
    command = [sys.executable, "-m", "frictionsim", "-v", "run", "long.toml", "--out", str(out), "--jobs", jobs]
    process = subprocess.Popen(command, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    workers = []
    try:
        line = process.stderr.readline()  # "INFO: ...: long.toml: 2 cases": the command is about to simulate
        assert "2 cases" in line, line
        time.sleep(0.5)
        if jobs == "2" and len(os.sched_getaffinity(0)) >= 2:  # on one CPU --jobs 2 runs without a pool
            workers = _children(process.pid, at_least=2)
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=60)
    finally:
        process.kill()
    assert process.returncode == 130
    assert err.strip().splitlines()[-1] == "error: interrupted" and "Traceback" not in err
    assert not out.exists() and _files(tmp_path) == ["long.toml"]  # no output, no staging directory
    deadline = time.monotonic() + 10.0
    while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not [pid for pid in workers if _alive(pid)]  # the pool's workers stopped with the command


def _children(pid, at_least):
    """The process ids of ``pid``'s children (Linux /proc), once there are ``at_least`` of them; [] elsewhere."""
    path = Path(f"/proc/{pid}/task/{pid}/children")
    if not path.exists():
        return []
    deadline = time.monotonic() + 20.0
    while time.monotonic() < deadline:
        children = [int(word) for word in path.read_text().split()]
        if len(children) >= at_least:
            return children
        time.sleep(0.05)
    pytest.fail(f"the command started {len(children)} worker processes, not {at_least}")


def _alive(pid):
    try:
        state = Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0]
    except OSError:
        return False
    return state != "Z"  # a zombie has stopped; its parent just has not collected it yet


# ------------------------------------------------------------------------------------------------- provenance
def test_every_command_writes_metadata_with_its_command_line(tmp_path, capsys):
    # (demo, fit-table5, sweep and fit: their own tests read metadata.json too)
    (tmp_path / "k.toml").write_text(RUN)
    commands = {
        "run": ["run", str(tmp_path / "k.toml"), "--out", str(tmp_path / "run")],
        "torque-drag": ["torque-drag", str(ROOT / "examples" / "surveys" / "s_well.csv"), "--mu", "0.3",
                        "--depth-step", "300", "--out", str(tmp_path / "torque-drag")],
    }
    for name, argv in commands.items():
        assert main(argv) == 0, capsys.readouterr().err
        record = _metadata(tmp_path / name)
        assert record["command"] == "frictionsim " + " ".join(argv)
        assert record["frictionsim"]["version"] == fs.__version__ and record["created_utc"]
    rigs = _metadata(tmp_path / "run")["rigs"]
    assert [r["name"] for r in rigs] == ["coulomb", "dahl"] and "Dahl(" in rigs[1]["repr"]
    assert repr(eval(rigs[1]["repr"], vars(fs))) == rigs[1]["repr"]  # the record rebuilds the rig


def test_run_format_needs_its_extra_before_anything_runs(tmp_path, capsys, monkeypatch):
    from frictionsim import io as fs_io

    def missing():
        raise ImportError("needs xarray (pip install 'frictionsim[io]')")

    monkeypatch.setattr(fs_io, "require_xarray", missing)
    monkeypatch.setattr(scenario.runner, "simulate", lambda *a, **k: pytest.fail("simulated before the check"))
    assert main(["run", str(EXAMPLES / "fig7_obm.toml"), "--format", "netcdf", "--out", str(tmp_path / "o")]) == 2
    assert capsys.readouterr().err == "error: --format netcdf: needs xarray (pip install 'frictionsim[io]')\n"
    assert _files(tmp_path) == []


@pytest.mark.parametrize("format, suffix", [("netcdf", ".nc"), ("parquet", ".parquet")])
def test_run_format_writes_the_time_series_in_it(format, suffix, tmp_path):
    from frictionsim import io as fs_io

    try:
        fs_io.netcdf_engine() if format == "netcdf" and fs_io.require_xarray() else fs_io.parquet_engine()
    except ImportError as missing:  # the optional extra frictionsim[io]
        pytest.skip(str(missing))
    source = tmp_path / "k.toml"
    source.write_text(RUN)
    assert main(["run", str(source), "--out", str(tmp_path / "csv")]) == 0
    assert main(["run", str(source), "--format", format, "--out", str(tmp_path / "o")]) == 0
    assert {"coulomb" + suffix, "dahl" + suffix, "metadata.json"} <= set(_files(tmp_path / "o"))
    assert _metadata(tmp_path / "o")["command"] == f"frictionsim run {source} --format {format} --out {tmp_path / 'o'}"
    csv = pd.read_csv(tmp_path / "csv" / "dahl.csv")
    if format == "netcdf":
        import xarray

        with xarray.open_dataset(tmp_path / "o" / "dahl.nc") as dataset:
            force = dataset["friction_force"].to_numpy()
    else:
        force = pd.read_parquet(tmp_path / "o" / "dahl.parquet")["friction_force"].to_numpy()
    np.testing.assert_allclose(force, csv["friction_force"], rtol=1e-9, atol=1e-15)  # CSV keeps 10 digits


# ---------------------------------------------------------------------------------------------------- scenarios
def test_scenarios_list_and_every_packaged_example_is_valid(capsys):
    assert main(["scenarios", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    names = sorted(p.name[:-5] for p in PACKAGED.iterdir() if p.name.endswith(".toml"))
    assert [line.split()[0] for line in lines[:len(names)]] == names
    for name in names:
        path = Path(str(PACKAGED.joinpath(f"{name}.toml")))
        kind = "sweep" if "[grid]" in path.read_text() else "scenario"
        assert next(line for line in lines if line.startswith(name + " ")).split()[1] == kind
        loaded = sweep_file.load(path) if kind == "sweep" else scenario.load(path)
        assert loaded.title
    assert "velocity_ratio_sweep" in names


def test_scenarios_copy_never_overwrites_and_stays_in_dest(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    packaged = PACKAGED.joinpath("fig7_obm.toml").read_bytes()
    assert main(["scenarios", "copy", "fig7_obm"]) == 0
    assert (tmp_path / "fig7_obm.toml").read_bytes() == packaged
    (tmp_path / "fig7_obm.toml").write_text("mine")
    assert main(["scenarios", "copy", "fig7_obm.toml", "."]) == 1
    assert "exists; not overwritten" in capsys.readouterr().err
    assert (tmp_path / "fig7_obm.toml").read_text() == "mine"
    # DEST a new file name; then a symbolic link pointing out of DEST is never written through
    assert main(["scenarios", "copy", "fig7_obm", "renamed.toml"]) == 0
    assert (tmp_path / "renamed.toml").read_bytes() == packaged
    (tmp_path / "sub").mkdir()
    outside = tmp_path / "outside.toml"
    (tmp_path / "sub" / "fig7_torsional.toml").symlink_to(outside)
    assert main(["scenarios", "copy", "fig7_torsional", "sub"]) == 1
    assert not outside.exists()
    assert main(["scenarios", "copy", "../fig7_obm", "sub"]) == 2
    assert "no packaged example '../fig7_obm'" in capsys.readouterr().err
    assert _files(tmp_path) == ["fig7_obm.toml", "renamed.toml", "sub", "sub/fig7_torsional.toml"]


# -------------------------------------------------------------------------------------------------------- sweep
SWEEP = KINEMATIC.replace('title = "kinematic Coulomb"', 'title = "kinematic sweep"') + """
[grid]
"rig.velocity_amplitude" = [0.5e-3, 2e-3, 0.01]
"friction.mu" = { start = 0.2, stop = 0.4, num = 3 }
[output]
value = "F_df_N"
"""


def test_sweep_matches_the_closed_form_and_one_run_per_point(tmp_path, capsys):
    source = tmp_path / "s.toml"
    source.write_text(SWEEP)
    out = tmp_path / "out"
    assert main(["sweep", str(source), "--out", str(out)]) == 0
    assert set(_files(out)) == {"sweep.csv", "sweep.png", "sweep.toml", "metadata.json"}
    frame = pd.read_csv(out / "sweep.csv")
    assert len(frame) == 3 * 3 * 2 and list(frame.columns[:3]) == ["rig.velocity_amplitude", "friction.mu", "case"]
    coulomb = frame[frame["case"] == "coulomb"]
    for _, row in coulomb.iterrows():
        v_a, mu = row["rig.velocity_amplitude"], row["friction.mu"]
        share = 2 / math.pi * math.asin(1e-3 / v_a) if v_a > 1e-3 else 1.0  # no reversal: F_df = mu F_N
        assert row["F_df_N"] == pytest.approx(mu * 50.0 * share, rel=1e-6), (v_a, mu)
    # the Dahl rows: each point equals a run of the scenario with the value written into it
    row = frame[(frame["case"] == "dahl") & (frame["rig.velocity_amplitude"] == 2e-3)
                & (frame["friction.mu"] == 0.4)].iloc[0]
    text = KINEMATIC.replace("velocity_amplitude = 0.01", "velocity_amplitude = 2e-3").replace(
        "mu = 0.3, tangential", "mu = 0.4, tangential")
    direct = scenario.run_case(scenario.loads(text).cases[1]).summary()
    assert row["F_df_N"] == pytest.approx(direct["F_df_N"], rel=1e-9)
    assert (out / "sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (out / "sweep.toml").read_text() == SWEEP
    record = _metadata(out)
    assert record["extra"]["sweep"]["points"] == 9
    assert record["extra"]["sweep"]["grid"]["friction.mu"] == [0.2, 0.3, 0.4]  # 15 digits: not 0.30000000000000004
    assert "F_df_N" in capsys.readouterr().out
    # --jobs 2: the same table
    assert main(["sweep", str(source), "--jobs", "2", "--out", str(tmp_path / "two")]) == 0
    assert (tmp_path / "two" / "sweep.csv").read_bytes() == (out / "sweep.csv").read_bytes()


def test_packaged_sweep_coulomb_is_the_closed_form_and_dahl_reduces_less(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["scenarios", "copy", "velocity_ratio_sweep"]) == 0
    assert main(["sweep", "velocity_ratio_sweep.toml", "-q"]) == 0
    frame = pd.read_csv(tmp_path / "out" / "velocity_ratio_sweep" / "sweep.csv")  # the file's output.directory
    assert len(frame) == 8 * 2 * 2
    coulomb = frame[frame["case"] == "coulomb"].set_index(["rig.velocity_amplitude", "rig.normal_force"])
    dahl = frame[frame["case"] == "dahl"].set_index(["rig.velocity_amplitude", "rig.normal_force"])
    for (v_a, _), reduction in coulomb["reduction_percent"].items():
        expected = 100 * (1 - 2 / math.pi * math.asin(1e-3 / v_a)) if v_a > 1e-3 else 0.0
        assert reduction == pytest.approx(expected, abs=1e-6)
    reversing = coulomb.index.get_level_values(0) > 1e-3
    # the Dahl contact flexes instead of reversing the sliding: less reduction than Coulomb wherever v_a > v_d
    assert np.all(dahl["reduction_percent"][reversing] < coulomb["reduction_percent"][reversing])


def test_sweep_of_a_scenario_file_and_selected_cases(tmp_path):
    (tmp_path / "scenarios").mkdir()
    (tmp_path / "scenarios" / "obm.toml").write_bytes((EXAMPLES / "fig7_obm.toml").read_bytes())
    (tmp_path / "s.toml").write_text('scenario = "scenarios/obm.toml"\ncases = ["dahl"]\n'  # relative to s.toml
                                     '[grid]\n"rig.frequency" = [15.0, 20.0]\n[output]\ncolumns = ["F_df_N"]\n')
    assert main(["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "o")]) == 0
    frame = pd.read_csv(tmp_path / "o" / "sweep.csv")
    assert list(frame.columns) == ["rig.frequency", "case", "F_df_N"] and list(frame["case"]) == ["dahl", "dahl"]
    obm = scenario.load(EXAMPLES / "fig7_obm.toml")
    assert frame["F_df_N"].iloc[1] == pytest.approx(scenario.run_case(obm.cases[1]).mean_friction, rel=1e-9)


def test_sweep_of_a_parameter_only_the_selected_case_takes(tmp_path, capsys):
    # Dahl's tangential stiffness: the Coulomb case has no such key, so the sweep must leave it out
    grid = '[grid]\n"friction.tangential_stiffness" = [2e4, 8e4]\n'
    (tmp_path / "all.toml").write_text(KINEMATIC + grid)
    assert main(["sweep", str(tmp_path / "all.toml"), "--out", str(tmp_path / "no")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f'error: {tmp_path / "all.toml"}: grid."friction.tangential_stiffness"[0]: ') and \
        "unknown key" in err
    (tmp_path / "dahl.toml").write_text('cases = ["dahl"]\n' + KINEMATIC + grid)
    assert main(["sweep", str(tmp_path / "dahl.toml"), "--out", str(tmp_path / "o")]) == 0
    frame = pd.read_csv(tmp_path / "o" / "sweep.csv")
    assert list(frame["case"]) == ["dahl", "dahl"]
    for k_t, value in zip((2e4, 8e4), frame["F_df_N"]):
        text = KINEMATIC.replace("tangential_stiffness = 4e4", f"tangential_stiffness = {k_t:g}")
        assert value == pytest.approx(scenario.run_case(scenario.loads(text).cases[1]).mean_friction, rel=1e-9)


def test_sweep_grid_in_field_units_is_tabled_and_plotted_in_si(tmp_path, caplog):
    """A grid value with a unit ("10 klbf") runs in SI; sweep.csv's axis column holds the SI number (the text
    beside it) and sweep.png is drawn over it, where before the column held the text and the plot was dropped."""
    source = tmp_path / "u.toml"
    steady = KINEMATIC.replace("velocity_amplitude = 0.01", "velocity_amplitude = 0.0")
    source.write_text(f'cases = ["coulomb"]\n{steady}[grid]\n"rig.normal_force" = ["10 klbf", "5 kN", 50.0]\n'
                      '[output]\ncolumns = ["F_df_N"]\n')
    assert main(["sweep", str(source), "--out", str(tmp_path / "o")]) == 0
    assert set(_files(tmp_path / "o")) == {"sweep.csv", "sweep.png", "sweep.toml", "metadata.json"}
    frame = pd.read_csv(tmp_path / "o" / "sweep.csv")
    assert list(frame.columns) == ["rig.normal_force", "rig.normal_force (given)", "case", "F_df_N"]
    newtons = [10e3 * 0.45359237 * 9.80665, 5000.0, 50.0]  # klbf from the pound and g (NIST SP 811)
    np.testing.assert_allclose(frame["rig.normal_force"], newtons, rtol=1e-10)  # CSV: 10 digits
    assert list(frame["rig.normal_force (given)"]) == ["10 klbf", "5 kN", "50.0"]
    # no velocity reversal: Coulomb slides at mu F_N throughout
    np.testing.assert_allclose(frame["F_df_N"], 0.3 * frame["rig.normal_force"], rtol=1e-8)
    grid = _metadata(tmp_path / "o")["extra"]["sweep"]
    assert grid["grid"]["rig.normal_force"] == ["10 klbf", "5 kN", 50.0]
    assert grid["grid_si"]["rig.normal_force"]["unit"] == "N"
    np.testing.assert_allclose(grid["grid_si"]["rig.normal_force"]["values"], newtons, rtol=1e-15)
    # a first key that is no number: the table still, the plot skipped with a message saying why
    other = tmp_path / "m.toml"
    other.write_text(KINEMATIC + '[grid]\n"solver.method" = ["dormand_prince", "cvode_bdf"]\n')
    with caplog.at_level(logging.WARNING, logger="frictionsim"):
        assert main(["sweep", str(other), "--out", str(tmp_path / "m")]) == 0
    assert "sweep.png" not in _files(tmp_path / "m")
    assert "m: no sweep.png: the first grid key 'solver.method' is not numeric" in caplog.text


def test_sweep_value_that_would_hang_pint_is_refused_at_once(tmp_path, capsys):
    """10**10**10 as a grid value: pint computed a ten-billion-digit integer and `frictionsim sweep` hung."""
    source = tmp_path / "h.toml"
    source.write_text(KINEMATIC + '[grid]\n"rig.normal_force" = ["50 N", "10**10**10 N"]\n')
    assert main(["sweep", str(source), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {source}: grid.\"rig.normal_force\"[1]: cannot read '10**10**10 N' as a value "
                          "with a unit (OverflowError"), err
    assert _files(tmp_path) == ["h.toml"]


BAD_SWEEPS = [
    ("no grid", KINEMATIC, "grid", "is required"),
    ("unknown section", SWEEP.replace('"friction.mu"', '"solvr.mu"'), 'grid."solvr.mu"', "section one of"),
    ("type", SWEEP.replace('"friction.mu"', '"friction.type"'), 'grid."friction.type"', "cannot vary"),
    ("negative value", SWEEP.replace("[0.5e-3, 2e-3, 0.01]", "[0.5e-3, -2e-3, 0.01]"),
     'grid."rig.velocity_amplitude"[1]', "at point 3"),
    ("bad range", SWEEP.replace("num = 3", "num = 0"), 'grid."friction.mu".num', "must be an integer in [1,"),
    ("log range", SWEEP.replace("num = 3", 'num = 3, scale = "log"').replace("start = 0.2", "start = 0.0"),
     'grid."friction.mu"', "needs start > 0"),
    ("unknown case", SWEEP + 'cases = ["lugre"]\n', "cases[0]", "no case 'lugre'"),
    ("both", 'scenario = "x.toml"\n' + SWEEP, "scenario", "not both"),
    ("unknown value", SWEEP.replace('value = "F_df_N"', 'value = "F_dff"'), "output.value", "no summary column"),
    ("unknown key", SWEEP.replace("[output]", "[outputs]"), "outputs", "unknown key"),
]


@pytest.mark.parametrize("label, text, key, rule", BAD_SWEEPS, ids=[b[0] for b in BAD_SWEEPS])
def test_bad_sweep_file_names_file_key_and_rule_and_writes_nothing(label, text, key, rule, tmp_path, capsys):
    if label == "unknown case":  # cases is a top-level key: before the first table
        text = 'cases = ["lugre"]\n' + SWEEP
    source = tmp_path / "bad.toml"
    source.write_text(text)
    assert main(["sweep", str(source), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {source}: {key}: "), err
    assert rule in err and "Traceback" not in err
    assert _files(tmp_path) == ["bad.toml"]


# ---------------------------------------------------------------------------------------------------------- fit
LUGRE = dict(mu=0.3, mu_static=0.45, stribeck_velocity=0.01, bristle_stiffness=1e5, bristle_damping=300.0,
             viscous_damping=20.0)


@pytest.fixture(scope="module")
def lugre_record():
    """2 s of v_r = 0.1 sin(2 pi t) m/s at 1 kHz through a LuGre contact under 90 N, 1 % noise (0.27 N): four
    reversals, |v_r| sweeping through the Stribeck region (test_identify's record)."""
    t = np.linspace(0.0, 2.0, 2001)
    v = 0.1 * np.sin(2 * np.pi * t)
    rig = fs.KinematicRig(fs.LuGre(**LUGRE), relative_velocity=(t, v), normal_force=90.0)
    force = fs.simulate(rig, t[-1], output_times=t, rtol=1e-10, atol=1e-12).friction_force
    return t, v, force + np.random.default_rng(3).normal(0.0, 0.27, t.size)


def test_fit_lugre_from_csv_with_named_columns(lugre_record, tmp_path, capsys):
    from frictionsim.fit import identify

    t, v, force = lugre_record
    data = tmp_path / "record.csv"
    data.write_text("# a rig's record\n" + pd.DataFrame({"time [s]": t, "v_r": v, "F": force, "N": 90.0}).to_csv(
        index=False))
    out = tmp_path / "fit"
    guess = dict(mu=0.25, mu_static=0.5, stribeck_velocity=0.02, bristle_stiffness=5e4, bristle_damping=150.0,
                 viscous_damping=10.0)  # test_identify's perturbed start
    assert main(["fit", "--law", "lugre", str(data), "--time", "time [s]", "--velocity", "v_r", "--force", "F",
                 "--normal", "N", "--guess", ",".join(f"{k}={v:g}" for k, v in guess.items()),
                 "--out", str(out)]) == 0
    assert set(_files(out)) == {"fit.csv", "fit_record.csv", "fit.png", "metadata.json"}
    table = pd.read_csv(out / "fit.csv").set_index("parameter")
    direct = identify("lugre", t, v, force, 90.0, initial_guess=guess)  # the same fit through the Python API
    for name, value in direct.params.items():
        assert table.loc[name, "value"] == pytest.approx(value, rel=1e-9)
        assert table.loc[name, "stderr"] == pytest.approx(direct.stderr[name], rel=1e-9)
        assert abs(value - LUGRE[name]) <= 3 * direct.stderr[name], name  # the truth within 3 s.e.
    record = pd.read_csv(out / "fit_record.csv")
    assert np.sqrt(np.mean(record["residual"] ** 2)) == pytest.approx(0.27, rel=0.1)  # the residual is the noise
    assert "bristle_stiffness" in capsys.readouterr().out
    extra = _metadata(out)["extra"]
    assert extra["law"].startswith("LuGre(")
    # the data by content, not only by path: what was fitted can be checked against a file found later
    content = data.read_bytes()
    assert extra["data_file"] == {"path": str(data), "sha256": hashlib.sha256(content).hexdigest(),
                                  "size_bytes": len(content)}


def test_fit_bad_record_names_file_column_and_row(tmp_path, capsys):
    data = tmp_path / "r.csv"
    data.write_text("t,relative_velocity,friction_force\n0,0.1,1\n0.1,0.2,nan\n0.2,0.1,1\n")
    assert main(["fit", "--law", "dahl", str(data), "--out", str(tmp_path / "o")]) == 2
    assert "no column 'normal_force'" in capsys.readouterr().err
    assert main(["fit", "--law", "dahl", str(data), "--normal-force", "90", "--out", str(tmp_path / "o")]) == 2
    assert f"error: {data}: column 'friction_force', data row 2: must be a finite number" in capsys.readouterr().err
    assert main(["fit", "--law", "magic", str(data), "--out", str(tmp_path / "o")]) == 2
    assert "--law must be one of" in capsys.readouterr().err
    assert _files(tmp_path) == ["r.csv"]
