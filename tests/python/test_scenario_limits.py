"""Issue 11's command-line items: bounded outputs and inputs, outputs confined to the scenario's folder, nothing
left behind on SIGTERM, a wall-clock budget, no silent nonsense at loose tolerances."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from frictionsim.cli import main

SCENARIO = """
title = "{title}"
[rig]
type = "kinematic"
normal_force = 90.0
{velocity}
[friction]
type = "coulomb"
mu = 0.4
[solver]
t_end = {t_end}
{solver}
[analysis]
{analysis}
[output]
tables = ["summary"]
plots = []
{output}
"""


def _scenario(folder: Path, *, title="limits", velocity=None, t_end=1.0, solver="", analysis="cycles = 2",
              output="") -> Path:
    if velocity is None:
        velocity = "sliding_velocity = 0.01\nvelocity_amplitude = 0.1\nfrequency = 10.0"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "case.toml"
    path.write_text(SCENARIO.format(title=title, velocity=velocity, t_end=t_end, solver=solver, analysis=analysis,
                                    output=output))
    return path


def _error(capsys) -> str:
    return capsys.readouterr().err


@pytest.mark.parametrize("solver, key", [("output_points = 10000000", "solver.output_points"),
                                         ("output_step = 1e-7", "solver.output_step"),
                                         ("rtol = 0.999", "solver.rtol"), ("rtol = 0.2", "solver.rtol"),
                                         ("atol = 1e-100", "solver.atol"), ("timeout = -1.0", "solver.timeout")])
def test_solver_settings_that_cost_minutes_or_give_nonsense_are_refused(tmp_path, capsys, solver, key):
    path = _scenario(tmp_path, solver=solver)
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2  # rtol 0.999 exited 0 with NaN before
    assert f"{key}:" in _error(capsys)
    assert not (tmp_path / "out").exists()


def test_an_overlong_title_is_refused(tmp_path, capsys):
    path = _scenario(tmp_path, title="x" * 100_000)  # rendered in every plot: 65 s before
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "title: must be at most 200 characters" in _error(capsys)


@pytest.mark.parametrize("target", ["/dev/zero", "."])
def test_a_velocity_file_that_is_no_regular_file_is_refused_before_reading(tmp_path, capsys, target):
    velocity = f'velocity_file = "{target}"'
    path = _scenario(tmp_path, velocity=velocity, analysis="period = 0.1\ncycles = 2")
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2  # read until MemoryError before
    assert "velocity_file" in (err := _error(capsys)) and "regular file" in err


def test_a_standstill_in_a_velocity_file_runs(tmp_path, capsys):
    (tmp_path / "v.csv").write_text("t,v\n0,0.1\n0.3,0\n0.6,0\n1.0,-0.1\n")
    path = _scenario(tmp_path, velocity='velocity_file = "v.csv"', analysis="period = 0.5\ncycles = 1")
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0  # ChatteringError before
    assert (tmp_path / "out" / "summary.csv").exists()


def test_an_overlong_output_path_is_a_clean_error(tmp_path, capsys):
    path = _scenario(tmp_path)
    assert main(["run", str(path), "--out", str(tmp_path / ("d" * 300))]) == 2  # a traceback before
    assert "unusable output path" in _error(capsys)


@pytest.mark.parametrize("directory", ["/tmp/frictionsim-escape", "../escape", "sub/../../escape"])
def test_a_scenario_cannot_write_outside_its_folder(tmp_path, capsys, directory):
    path = _scenario(tmp_path / "scenarios", output=f'directory = "{directory}"')
    assert main(["run", str(path)]) == 2
    assert "output.directory" in _error(capsys)
    assert not Path("/tmp/frictionsim-escape").exists() and not (tmp_path / "escape").exists()


def test_a_symbolic_link_out_of_the_folder_is_not_followed(tmp_path, capsys):
    folder, elsewhere = tmp_path / "scenarios", tmp_path / "elsewhere"
    elsewhere.mkdir()
    path = _scenario(folder, output='directory = "results"')
    (folder / "results").symlink_to(elsewhere)
    assert main(["run", str(path)]) == 2
    assert "leads out of the scenario's folder" in _error(capsys)
    assert list(elsewhere.iterdir()) == []


def test_inside_the_folder_and_with_the_explicit_flag_it_writes(tmp_path, capsys):
    folder = tmp_path / "scenarios"
    path = _scenario(folder, output='directory = "results/run1"')
    assert main(["run", str(path)]) == 0
    assert (folder / "results" / "run1" / "summary.csv").exists()
    path = _scenario(folder, output='directory = "../allowed"')
    assert main(["run", str(path), "--allow-outside"]) == 0
    assert (tmp_path / "allowed" / "summary.csv").exists()


def test_a_symbolic_link_inside_the_target_is_not_written_through(tmp_path, capsys):
    out, elsewhere = tmp_path / "out", tmp_path / "elsewhere"
    elsewhere.mkdir()
    out.mkdir()
    (out / "summary.csv").symlink_to(elsewhere / "victim.csv")
    assert main(["run", str(_scenario(tmp_path)), "--out", str(out)]) == 1
    assert "symbolic link" in _error(capsys) and not (elsewhere / "victim.csv").exists()


def test_the_wall_clock_budget_stops_a_run(tmp_path, capsys):
    path = _scenario(tmp_path, t_end=1e6, solver="output_points = 2")
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--timeout", "0.3"]) == 1
    assert "timeout = 0.3 s" in _error(capsys)


@pytest.mark.parametrize("signum, status", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_a_signal_mid_run_stops_the_command_cleanly(tmp_path, signum, status):
    # a run of a minute or more (2 reversals per 10 s over 1e7 s); signalled once the command is under way
    velocity = "sliding_velocity = 0.01\nvelocity_amplitude = 0.1\nfrequency = 0.1"
    path = _scenario(tmp_path, velocity=velocity, t_end=1e7, solver="output_points = 2")
    process = subprocess.Popen([sys.executable, "-m", "frictionsim", "run", str(path), "--out", str(tmp_path / "out")],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    time.sleep(3.0)
    assert process.poll() is None
    process.send_signal(signum)
    _, err = process.communicate(timeout=60)  # SIGTERM waited for the end of the run before (or killed it)
    assert process.returncode == status, err
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".partial")]
    assert not (tmp_path / "out").exists()


def test_sigterm_during_writing_removes_the_staging_directory(tmp_path, monkeypatch):
    from frictionsim import cli

    staged = []

    def writer(directory):
        staged.append(directory)
        (directory / "half.csv").write_text("1,2\n")
        os.kill(os.getpid(), signal.SIGTERM)  # arrives while the stage holds half the outputs
        time.sleep(5)
        return []

    with pytest.raises(cli._Terminated):
        with cli._terminate_as_exception():
            cli._write(tmp_path / "out", writer)
    assert staged and not staged[0].exists() and not (tmp_path / "out").exists()
