"""Labelled outputs with provenance (issue 15, item 3): a Result, a sweep and the torsional stick-slip map as xarray
Datasets and netCDF files whose attributes carry the provenance record, opened back equal to the bit; the record
rebuilds the rig and reruns it to the same bits; ScenarioRun.write in csv / netcdf / parquet with metadata.json; the
git revision of a source tree; errors that name the parameter or the extra."""

from __future__ import annotations

import datetime
import json
import math
import pathlib
import platform
import subprocess
import sys

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import io, provenance, scenario
from frictionsim.errors import InvalidParameterError


def torsional_rig():
    return fs.TorsionalRig(fs.torsional.fig7_laws()["Stribeck"], initial_drive_speed=5.76, initial_disc_speed=0.0)


@pytest.fixture(scope="module")
def run():
    """4 s of stick-slip: switches with the state before and after each, and a stop condition that crosses."""
    return fs.simulate(torsional_rig(), 4.0, rtol=1e-9, atol=1e-11,
                       events=[fs.StopCondition(state="disc_speed", level=2.0, direction=1, terminal=False)])


def installed_engines():
    return [e for e in io.ENGINES if io._installed(e)]


def same_bits(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


# ------------------------------------------------------------------------------------------------ provenance
def test_result_metadata_records_the_run(run):
    m = run.metadata
    assert m["schema"] == provenance.SCHEMA
    assert m["frictionsim"]["version"] == fs.__version__
    rig = m["rigs"][0]
    assert rig["type"] == "TorsionalRig" and rig["repr"] == repr(torsional_rig())
    assert rig["friction"]["repr"] == repr(fs.torsional.fig7_laws()["Stribeck"])
    assert rig["parameters"]["normal_force"] == {"value": 35.0, "unit": "N"}  # Table 2, from the rig's table
    assert rig["friction"]["parameters"]["stribeck_velocity"]["unit"] == "m/s"
    assert m["solver_options"]["rtol"] == 1e-9 and m["solver_options"]["atol"] == 1e-11
    assert m["solver_options"]["method"] == "automatic" and m["solver_options"]["max_step"] == "Infinity"
    assert m["solver_options"]["stop_conditions"] == [repr(fs.StopCondition(state="disc_speed", level=2.0,
                                                                            direction=1, terminal=False))]
    assert m["solver_stats"] == run.stats
    assert m["platform"]["python"] == platform.python_version() and m["platform"]["numpy"] == np.__version__
    started = datetime.datetime.fromisoformat(m["created_utc"])
    assert started.utcoffset() == datetime.timedelta(0)
    assert abs((datetime.datetime.now(datetime.timezone.utc) - started).total_seconds()) < 3600
    assert json.loads(json.dumps(m, allow_nan=False)) == m  # JSON-safe as it is


def test_the_record_rebuilds_the_rig_and_reruns_it_to_the_bit(run):
    """Provenance that is enough to rerun: the rig from its repr, the options from the record."""
    m = run.metadata
    namespace = {name: getattr(fs, name) for name in fs.__all__}
    rig = eval(m["rigs"][0]["repr"], namespace)  # noqa: S307 - our own repr
    options = m["solver_options"]
    again = fs.simulate(rig, 4.0, rtol=options["rtol"], atol=options["atol"], method=options["method"],
                        events=[eval(c, namespace) for c in options["stop_conditions"]])  # noqa: S307
    assert same_bits(again.t, run.t) and same_bits(again.states, run.states)
    assert again.stats == m["solver_stats"]


def test_a_time_stepped_run_records_its_step_and_reruns_from_the_record_to_the_bit():
    """The record reads SolverOptions' fields from the binding, so an option added in C++ is recorded: the
    time-stepping methods' step, theta, projection_band and contact_solver were left out while a list named them,
    and a captured string's run could not be rerun from its record."""
    from frictionsim import drillstring as ds

    model = fs.TorsionalString(ds.field_string(), elements=12)
    run = fs.simulate(model, 0.5, method="moreau_jean", step=2.5e-3, theta=0.75, contact_solver="active_set")
    options = run.metadata["solver_options"]
    assert options["step"] == 2.5e-3 and options["theta"] == 0.75 and options["projection_band"] == 0.0
    assert options["method"] == "moreau_jean" and options["contact_solver"] == "active_set"
    namespace = {name: getattr(fs, name) for name in fs.__all__}
    again = fs.simulate(eval(run.metadata["rigs"][0]["repr"], namespace), 0.5,  # noqa: S307 - our own repr
                        **{key: options[key] for key in ("method", "step", "theta", "projection_band",
                                                         "contact_solver")})
    assert same_bits(again.t, run.t) and same_bits(again.states, run.states)
    changed = fs.simulate(model, 0.5, method="moreau_jean", step=2.5e-3)  # theta 0.5: another trajectory
    assert not same_bits(changed.states, run.states)
    # the explicit projection's stick band (A&S's 1.5 rad/s) is recorded and reruns likewise
    clipped = fs.simulate(model, 0.5, method="explicit_projection", step=1e-4, projection_band=1.5)
    options = clipped.metadata["solver_options"]
    assert options["projection_band"] == 1.5 and options["method"] == "explicit_projection"
    again = fs.simulate(model, 0.5, **{key: options[key] for key in ("method", "step", "projection_band")})
    assert same_bits(again.states, clipped.states)
    with pytest.raises(InvalidParameterError, match="projection_band") as info:
        fs.simulate(model, 0.5, method="explicit_projection", step=1e-4, projection_band=-1.0)
    assert info.value.parameter == "projection_band"
    with pytest.raises(InvalidParameterError, match="projection_band"):  # an option of the time-stepping methods
        fs.simulate(fs.StringRig(ds.field_string(), fs.Coulomb(0.2, 0.3), elements=4), 0.1, projection_band=1.0)


def test_a_failed_run_records_its_provenance_too():
    rig = torsional_rig()
    with pytest.raises(fs.SimulationError) as error:
        fs.simulate(rig, 4.0, max_steps=50)
    record = error.value.partial.metadata
    assert record["rigs"][0]["repr"] == repr(rig) and record["solver_options"]["max_steps"] == 50
    assert record["solver_stats"] == error.value.partial.stats


def test_metadata_survives_pickling(run):
    import pickle

    back = pickle.loads(pickle.dumps(run))
    assert back.metadata == run.metadata


def test_collect_and_write_metadata(tmp_path):
    rig = fs.AxialVibrationRig(friction=fs.Dahl(mu=0.41, tangential_stiffness=4e4))
    record = provenance.collect(command=["frictionsim", "run", "x.toml"], rigs={"dahl": rig},
                                solver_options={"rtol": 1e-8, "max_step": math.inf},
                                stats={"steps": np.int64(12)}, extra={"ratio": float("nan"), "grid": np.arange(100.0)})
    assert record["command"] == ["frictionsim", "run", "x.toml"]
    assert record["rigs"][0]["name"] == "dahl" and record["rigs"][0]["repr"] == repr(rig)
    assert record["solver_options"]["max_step"] == "Infinity" and record["solver_stats"] == {"steps": 12}
    assert record["extra"]["ratio"] == "NaN"
    assert record["extra"]["grid"] == {"count": 100, "shape": [100], "first": 0.0, "last": 99.0, "min": 0.0,
                                       "max": 99.0}  # a long array is summarised, not listed
    path = provenance.write_metadata(tmp_path, record)
    assert path == tmp_path / "metadata.json"

    def strict(constant):
        raise AssertionError(f"non-standard JSON constant {constant}")

    assert json.loads(path.read_text(), parse_constant=strict) == record
    with pytest.raises(InvalidParameterError, match="directory") as error:
        provenance.write_metadata(tmp_path / "missing", record)
    assert error.value.parameter == "directory"


def _committed_repository(root):
    """``root`` made a git work tree with everything in it committed; the git command prefix for it."""
    git = ["git", "-C", str(root), "-c", "user.name=t", "-c", "user.email=t@t"]
    try:
        subprocess.run(git[:3] + ["init", "-q"], check=True)
        subprocess.run(git + ["add", "."], check=True)
        subprocess.run(git + ["commit", "-q", "-m", "one"], check=True)
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("no git program")
    return git


def test_git_revision_of_a_source_tree(tmp_path):
    tree = tmp_path / "src"
    package = tree / "python" / "frictionsim"
    package.mkdir(parents=True)
    (package / "module.py").write_text("x = 1\n")
    git = _committed_repository(tree)
    head = subprocess.run(git[:3] + ["rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    assert provenance.git_revision(package) == (head, False)
    (package / "module.py").write_text("x = 2\n")
    assert provenance.git_revision(package) == (head, True)  # tracked file changed
    assert provenance._read_head(tree / ".git") == head  # without the git program
    assert provenance.git_revision(tmp_path / "elsewhere") is None  # not in a work tree: absent, no error
    installed = tree / "venv" / "lib" / "site-packages" / "frictionsim"
    installed.mkdir(parents=True)
    assert provenance.git_revision(installed) is None  # an installed package is never "the source tree"


def test_git_revision_ignores_an_unrelated_outer_repository(tmp_path):
    """A package copied into another project's repository (vendored, or a scratch copy under a home kept in git)
    records no revision: that repository's commit is not frictionsim's."""
    outer = tmp_path / "outer"
    vendored = outer / "third_party" / "frictionsim"
    vendored.mkdir(parents=True)
    (vendored / "module.py").write_text("x = 1\n")
    (outer / "python" / "frictionsim").mkdir(parents=True)  # even beside a python/frictionsim of its own
    (outer / "python" / "frictionsim" / "other.py").write_text("y = 1\n")
    _committed_repository(outer)
    assert provenance.git_revision(vendored) is None
    assert provenance.git_revision(outer / "python") is None  # not the package directory either
    assert provenance.git_revision(outer / "python" / "frictionsim") is not None  # frictionsim's layout: recorded
    link = tmp_path / "linked"
    link.symlink_to(outer / "python" / "frictionsim")  # the same directory by another path is the same tree
    assert provenance.git_revision(link) == provenance.git_revision(outer / "python" / "frictionsim")


def test_collect_takes_a_single_rig_and_refuses_a_bad_command():
    rig = fs.AxialVibrationRig(friction=fs.Coulomb(0.41))
    record = provenance.collect(rigs=rig, command=("frictionsim", "run", pathlib.Path("x.toml")))
    assert [r["repr"] for r in record["rigs"]] == [repr(rig)] and record["command"] == ["frictionsim", "run", "x.toml"]
    assert provenance.collect(rigs=provenance.rig_record(rig))["rigs"] == record["rigs"]  # one record: one rig
    assert provenance.collect(rigs=[rig, rig])["rigs"] == record["rigs"] * 2
    for command in (42, [1, 2], b"frictionsim run", {"argv": "x"}):
        with pytest.raises(InvalidParameterError, match="command") as error:
            provenance.collect(command=command)
        assert error.value.parameter == "command"


# ------------------------------------------------------------------------------------------------ netCDF
@pytest.mark.parametrize("engine", io.ENGINES)
def test_result_netcdf_round_trip_to_the_bit(run, tmp_path, engine):
    pytest.importorskip("xarray")
    if engine not in installed_engines():
        pytest.skip(f"{engine} not installed")
    path = run.to_netcdf(tmp_path / "run.nc", engine=engine)
    back = io.open_dataset(path)
    assert io.metadata(back) == run.metadata  # attrs carry the record
    assert back.attrs["source"] == f"frictionsim {fs.__version__}" and back.attrs["rig"] == repr(torsional_rig())
    assert same_bits(back["time"].values, run.t)
    for name in run.state_names:
        assert same_bits(back[name].values, run[name]), name
    assert same_bits(back["friction_force"].values, run.friction_force)
    assert same_bits(back["mode"].values, run.mode)
    assert list(back["state"].values) == run.state_names
    # units from the physics: the disc's friction is a torque
    assert back["time"].attrs["units"] == "s" and back["disc_speed"].attrs["units"] == "rad/s"
    assert back["friction_force"].attrs["units"] == "N m" and back["shaft_twist"].attrs["units"] == "rad"
    # the switches on their own dimension, with the state before and after each
    events = run.events
    assert back.sizes["event"] == len(events) > 3
    assert same_bits(back["event_time"].values, np.array([e.time for e in events]))
    assert list(back["event_mode_after"].values) == [e.mode_after_name for e in events]
    assert same_bits(back["event_state_before"].values, np.array([e.state_before for e in events]))
    assert same_bits(back["event_state_after"].values, np.array([e.state_after for e in events]))
    assert same_bits(back["stop_time"].values, run.t_events[0]) and len(run.t_events[0]) >= 1
    assert same_bits(back["stop_state_after"].values, run.y_events[0])
    assert back.attrs["status"] == 0 and back.attrs["message"] == run.message


def test_units_follow_the_rig():
    """Friction is a force on the axial rig, a torque on a drill string, whose mode counts stuck contacts."""
    xr = pytest.importorskip("xarray")
    from frictionsim import drillstring

    dataset = fs.simulate(fs.AxialVibrationRig(friction=fs.Coulomb(0.41)), 0.1).to_xarray()
    assert isinstance(dataset, xr.Dataset)
    assert dataset["friction_force"].attrs["units"] == "N" and dataset["velocity"].attrs["units"] == "m/s"
    assert dataset["friction_impulse"].attrs["units"] == "N s" and dataset["mode"].attrs["flag_values"].tolist() == [
        -1, 0, 1]
    string = fs.StringRig(drillstring.field_string(), fs.Coulomb(0.2, 0.3), elements=3, inclination=1.0, axial=True)
    dataset = fs.simulate(string, 0.2).to_xarray()
    assert dataset["friction_force"].attrs["units"] == "N m"
    assert dataset["mode"].attrs["long_name"] == "stuck wall contacts"
    assert [dataset[name].attrs["units"] for name in ("theta_3", "omega_3", "u_3", "v_3", "bit_work")] == [
        "rad", "rad/s", "m", "m/s", "J"]


def test_every_rig_and_law_declares_the_units_of_its_outputs():
    """No unit is looked up by a class or state name: each rig of _core.RIGS has its declaration (outputs.RIG_OUTPUTS,
    keyed by the class), each law its states' units beside their names (from C++), and a run's every state gets
    one: a law's (LuGre's bristle deflection on the axial rig; numbered per node on a string) as well as the rig's."""
    from frictionsim import drillstring, outputs

    assert set(fs._core.RIGS) <= set(outputs.RIG_OUTPUTS)
    for law in fs.FRICTION_LAWS:
        assert len(law.state_units) == len(law.state_names) == len(outputs.law_state_units(law)), law
        assert all(unit for unit in law.state_units), law
    assert fs.LuGre.state_units == ("m",) and fs.Coulomb.state_units == ()
    assert not hasattr(io, "STATE_UNITS")  # a new law needs no entry in io.py
    axial = fs.simulate(fs.AxialVibrationRig(friction=fs.LuGre(0.3, 0.4, 1e-3, 1e5, 300.0)), 0.05)
    assert set(axial.units) == {"t", "friction_force", "friction_impulse", *axial.state_names}
    assert axial.units["bristle_deflection"] == "m" and axial.units["drive_work"] == "J"
    string = fs.StringRig(drillstring.field_string(), fs.Dahl(0.2, 1e5), elements=2, inclination=1.0)
    run = fs.simulate(string, 0.05)
    assert set(run.state_names) <= set(run.units) and run.units["dahl_deflection_2"] == "m"
    assert run.units["friction_force"] == "N m" and run.units["mode"] == "1"
    assert io.state_units("omega_1", run) == "rad/s" and io.state_units("omega_1", string) == "rad/s"
    assert io.state_units("t") == "s" and io.state_units("omega_1") is None
    import pickle

    assert pickle.loads(pickle.dumps(run)).units == run.units  # kept without the rig


def point(amplitude, frequency, fail_at=None):
    """A sweep point with a closed form: the velocity amplitude 2 pi f u0 [m/s] and its square."""
    if fail_at is not None and (amplitude, frequency) == fail_at:
        raise ValueError("this point fails")
    v = 2 * math.pi * frequency * amplitude
    return {"velocity_amplitude": v, "square": v * v}


def test_sweep_netcdf_round_trip(tmp_path):
    pytest.importorskip("xarray")
    grid = {"amplitude": [1e-3, 3e-3], "frequency": [10.0, 17.0, 25.0]}
    result = fs.sweep(point, grid, progress=False, fixed={"fail_at": (3e-3, 17.0)}, errors="collect")
    dataset = result.to_xarray(units={"amplitude": "m", "frequency": "Hz", "velocity_amplitude": "m/s"})
    assert dataset["velocity_amplitude"].dims == ("amplitude", "frequency")
    assert dataset["amplitude"].attrs["units"] == "m" and dataset["velocity_amplitude"].attrs["units"] == "m/s"
    path = result.to_netcdf(tmp_path / "sweep.nc")
    back = io.open_dataset(path)
    expected = np.array([[2 * math.pi * f * a for f in grid["frequency"]] for a in grid["amplitude"]])
    expected[1, 1] = np.nan  # the failed point
    np.testing.assert_array_equal(back["velocity_amplitude"].values, expected)
    assert same_bits(back["square"].values, result.as_array("square"))
    assert back["error"].values[1, 1] == "ValueError: this point fails" and back["error"].values[0, 0] == ""
    record = io.metadata(back)
    assert record == result.metadata and record["extra"]["sweep"]["function"].endswith(".point")
    assert record["extra"]["sweep"]["failed"] == 1


def test_sweep_over_explicit_points_has_a_point_dimension():
    pytest.importorskip("xarray")
    result = fs.sweep(point, [{"amplitude": 1e-3, "frequency": 10.0}, {"amplitude": 2e-3, "frequency": 5.0}],
                      progress=False)
    dataset = result.to_xarray()
    assert dataset["square"].dims == ("point",)
    np.testing.assert_array_equal(dataset["frequency"].values, [10.0, 5.0])


SPEEDS, FORCES = [3.0, 12.0], [25.0, 45.0]


@pytest.fixture(scope="module")
def stick_slip_map():
    return fs.torsional.stick_slip_map(SPEEDS, FORCES, t_end=8.0, transient=4.0)


def test_stick_slip_map_severity_against_an_independent_run(stick_slip_map):
    m, speeds, forces = stick_slip_map, SPEEDS, FORCES
    # Where the disc sticks it is on a limit cycle, whose mean speed is w_ref: the PI motor's speed-error integral
    # and the shaft twist are periodic, so the drive and the disc turn on average at w_ref. With trough 0 (stuck),
    # the severity is then (max - min) / (2 w_ref) of the disc speed, taken here from a run of its own with NumPy
    # (measured: within 0.03 % at both stick-slip points, 3 rad/s at 25 and 45 N).
    assert m.stick_slip.sum() == 2
    for i, j in zip(*np.nonzero(m.stick_slip)):
        _, alone = fs.torsional.simulate_fig7(None, 8.0, reference_speed=speeds[i], normal_force=forces[j])
        w = alone["disc_speed"][alone.t >= 4.0]
        assert m.severity[i, j] == pytest.approx((w.max() - w.min()) / (2.0 * speeds[i]), rel=2e-3)
        assert m.sweep.values[i * 2 + j]["mean"] == pytest.approx(speeds[i], rel=1e-3)


def test_stick_slip_map_netcdf(stick_slip_map, tmp_path):
    pytest.importorskip("xarray")
    m = stick_slip_map
    back = io.open_dataset(m.to_netcdf(tmp_path / "map.nc"))
    assert back["severity"].dims == ("reference_speed", "normal_force")
    for name in ("frequency", "peak_ratio", "stick_fraction", "severity"):
        assert same_bits(back[name].values, np.asarray(getattr(m, name), dtype=float)), name
    np.testing.assert_array_equal(back["stick_slip"].values, m.stick_slip)
    assert back["reference_speed"].attrs["units"] == "rad/s" and back["normal_force"].attrs["units"] == "N"
    assert io.metadata(back) == m.metadata and "stick_slip_point" in m.metadata["extra"]["sweep"]["function"]


# ------------------------------------------------------------------------------------------------ scenario outputs
SCENARIO = """
title = "short Fig. 7(a)"
[rig]
type = "axial"
[solver]
t_end = 0.3
output_points = 301
[analysis]
cycles = 2
[[case]]
name = "coulomb"
friction = { type = "coulomb", mu = 0.41 }
[[case]]
name = "dahl"
friction = { type = "dahl", mu = 0.41, tangential_stiffness = 4.0e4 }
[output]
plots = []
"""


@pytest.fixture(scope="module")
def scenario_run():
    return scenario.run(scenario.loads(SCENARIO, name="short"))


def test_scenario_writes_metadata_json_beside_csv(scenario_run, tmp_path):
    written = scenario_run.write(tmp_path, command=["frictionsim", "run", "short.toml"])
    assert tmp_path / "metadata.json" in written
    record = json.loads((tmp_path / "metadata.json").read_text())
    assert record["command"] == ["frictionsim", "run", "short.toml"]
    assert [r["name"] for r in record["rigs"]] == ["coulomb", "dahl"]
    assert [r["repr"] for r in record["rigs"]] == [repr(run.rig) for run in scenario_run.runs]
    for case, run in zip(record["cases"], scenario_run.runs):
        assert case["solver_stats"] == run.result.stats and case["solver_options"]["rtol"] == run.case.solver.rtol
        assert case["solver_options"]["output_times"]["count"] == len(run.result.t)  # summarised grid
    assert (tmp_path / "dahl.csv").exists() and (tmp_path / "summary.csv").exists()


def test_scenario_writes_netcdf(scenario_run, tmp_path):
    pytest.importorskip("xarray")
    written = scenario_run.write(tmp_path, format="netcdf")
    assert {p.name for p in written} >= {"coulomb.nc", "dahl.nc", "summary.nc", "metadata.json"}
    run = scenario_run.runs[1]
    back = io.open_dataset(tmp_path / "dahl.nc")
    frame = run.timeseries()
    for column in ("relative_velocity", "drive_force", "dahl_deflection"):  # derived and state columns
        assert same_bits(back[column].values, frame[column].to_numpy()), column
    assert back["relative_velocity"].attrs["units"] == "m/s" and back["drive_force"].attrs["units"] == "N"
    assert io.metadata(back) == run.result.metadata
    summary = io.open_dataset(tmp_path / "summary.nc")
    assert list(summary["case"].values) == ["coulomb", "dahl"]
    assert same_bits(summary["F_df_N"].values, scenario_run.summary()["F_df_N"].to_numpy())
    assert io.metadata(summary)["cases"][1]["name"] == "dahl"


def test_scenario_writes_parquet(scenario_run, tmp_path):
    pytest.importorskip("pyarrow")
    import pandas as pd
    import pyarrow.parquet as pq

    scenario_run.write(tmp_path, format="parquet")
    run = scenario_run.runs[0]
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "coulomb.parquet"), run.timeseries(), check_exact=True)
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "summary.parquet"), scenario_run.summary(),
                                  check_exact=True)
    assert json.loads(pq.read_schema(tmp_path / "coulomb.parquet").metadata[b"frictionsim"]) == run.result.metadata
    assert (tmp_path / "metadata.json").exists()


# ------------------------------------------------------------------------------------------------ errors
def test_bad_format_is_named_and_nothing_is_written(scenario_run, tmp_path):
    with pytest.raises(InvalidParameterError, match="format must be one of csv, netcdf, parquet") as error:
        scenario_run.write(tmp_path, format="xlsx")
    assert error.value.parameter == "format" and list(tmp_path.iterdir()) == []


def test_missing_extra_is_named(run, scenario_run, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # as if not installed: import raises ImportError
    with pytest.raises(ImportError, match=r"frictionsim\[io\]"):
        run.to_xarray()
    with pytest.raises(ImportError, match=r"frictionsim\[io\]"):
        scenario_run.write(tmp_path, format="netcdf")
    for module in ("pyarrow", "fastparquet"):
        monkeypatch.setitem(sys.modules, module, None)
    with pytest.raises(ImportError, match=r"pyarrow.*frictionsim\[io\]"):
        scenario_run.write(tmp_path, format="parquet")
    assert list(tmp_path.iterdir()) == []  # refused before anything was written
    for module in ("h5netcdf", "netCDF4"):
        monkeypatch.setitem(sys.modules, module, None)
    with pytest.raises(ImportError, match=r"h5netcdf.*netCDF4.*frictionsim\[io\]"):
        io.netcdf_engine()


def test_unknown_engine_is_named():
    with pytest.raises(InvalidParameterError, match="engine must be one of h5netcdf, netcdf4, scipy") as error:
        io.netcdf_engine("hdf4")
    assert error.value.parameter == "engine"


def test_sweep_of_non_numbers_cannot_be_labelled():
    pytest.importorskip("xarray")
    result = fs.sweep(lambda a: {"law": "Coulomb", "mu": a}, {"a": [1.0, 2.0]}, progress=False)
    dataset = result.to_xarray()  # a column of strings is kept as strings
    assert list(dataset["law"].values) == ["Coulomb", "Coulomb"] and list(dataset["mu"].values) == [1.0, 2.0]
    result = fs.sweep(lambda a: [a], {"a": [1.0, 2.0]}, progress=False)
    with pytest.raises(InvalidParameterError, match="numbers or strings, or dicts of them") as error:
        result.to_xarray()
    assert error.value.parameter == "values"


def test_dataset_without_provenance_is_named():
    with pytest.raises(InvalidParameterError, match="no frictionsim provenance"):
        io.metadata({"title": "someone else's file"})
