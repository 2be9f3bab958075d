"""Issue 23's Python-side defects (helper harden), each with the reproducer the issue gives: default output folders
that stay below out/, strings that reach numbers only through the units layer (and '' never does), fits that
refuse a bad option instead of reporting a table of NaN, a timeout that fails the command, outputs written whole
or not at all, and the engine's enums surviving pickle and copy."""

from __future__ import annotations

import copy
import json
import math
import os
import pickle
import shutil
from pathlib import Path

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import _core, atomic, provenance
from frictionsim import units
from frictionsim.cli import folder_name, main
from frictionsim.fit import compare_laws, identify_dahl
from test_cli_everyday import RUN  # a kinematic scenario of two cases, no plots
from test_drillstring_scenario import SMALL  # a 5-element drill string that simulates in milliseconds

pint = pytest.importorskip("pint", reason="frictionsim[units] is not installed")

ROOT = Path(__file__).resolve().parents[2]
S_WELL = ROOT / "examples" / "surveys" / "s_well.csv"
MU, K_T, N = 0.41, 4e4, 90.0


def _tree(directory: Path):
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*"))


# ------------------------------------------------------------------------------------------- 1. output folders
@pytest.mark.parametrize("stem, folder", [("..", "survey"), (".", "survey"), ("", "survey"), ("  ", "survey"),
                                          ("...", "survey"), ("a/b", "a_b"), ("..\\..", ".._.."),
                                          ("a\0b", "a_b"), ("s_well", "s_well"), (".hidden", ".hidden"),
                                          ("v1.2", "v1.2")])
def test_a_default_folder_name_is_one_folder_below_out(stem, folder):
    assert folder_name(stem, "survey") == folder
    assert (Path("out") / folder_name(stem, "survey")).resolve().parent == Path("out").resolve()


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """A working directory inside tmp_path: outputs that escape out/ land in it or in tmp_path, where the test
    looks."""
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    return work


def test_torque_drag_of_a_survey_named_dots_csv_writes_below_out(workdir, tmp_path, capsys):
    shutil.copy(S_WELL, workdir / "...csv")  # Path("...csv").stem == "..": out/.. was the working directory
    assert main(["torque-drag", "...csv", "--mu", "0.3", "--depth-step", "300"]) == 0
    assert _tree(tmp_path) == ["work", *("work/" + f for f in _tree(workdir))]
    assert sorted(os.listdir(workdir)) == ["...csv", "out"]
    assert os.listdir(workdir / "out") == ["survey"]
    assert {"torque_drag.csv", "broomstick.csv", "metadata.json"} <= set(os.listdir(workdir / "out" / "survey"))


def test_run_of_a_scenario_named_dots_toml_writes_below_out(workdir, tmp_path, capsys):
    (workdir / "...toml").write_text(RUN, encoding="utf-8")
    assert main(["run", "...toml"]) == 0
    assert _tree(tmp_path) == ["work", *("work/" + f for f in _tree(workdir))]
    assert sorted(os.listdir(workdir)) == ["...toml", "out"]
    assert os.listdir(workdir / "out") == ["scenario"]
    assert {"coulomb.csv", "summary.csv", "metadata.json"} <= set(os.listdir(workdir / "out" / "scenario"))


# ------------------------------------------------------------------------------------------------- 2. units
@pytest.fixture(scope="module")
def soft_string():
    survey = fs.Survey.from_degrees([0.0, 500.0, 1500.0], [0.0, 0.0, 45.0], [0.0, 0.0, 30.0])
    return fs.SoftString(survey, fs.DrillString([fs.PipeSection(length=1400.0)]), 20)


@pytest.mark.parametrize("blank", ["", " ", "\t", " \n "])
def test_an_empty_string_is_no_dimensionless_one(blank, soft_string):
    with pytest.raises(units.UnitError, match=r"^mu: .* is empty") as info:
        fs.Coulomb(mu=blank)  # pint reads '' as 1: mu = 1 before
    assert info.value.parameter == "mu" and isinstance(info.value, fs.InvalidParameterError)
    with pytest.raises(fs.InvalidParameterError) as info:
        soft_string.run("rotating_off_bottom", open_hole_friction=blank)  # ran with mu = 1 before
    assert info.value.parameter == "open_hole_friction"
    with pytest.raises(units.UnitError) as info:
        units.to_si(blank, "N", "hook_load")
    assert info.value.parameter == "hook_load"
    assert fs.Coulomb(mu="0.3").mu == 0.3  # a number written as text stays a dimensionless number


def test_convert_refuses_a_value_that_overflows_in_the_target_unit():
    with pytest.raises(units.UnitError, match=r"^value: 1e\+308 klbf is not a finite value in N") as info:
        units.convert(1e308, "klbf", "N")  # inf before
    assert info.value.parameter == "value"
    with pytest.raises(units.UnitError) as info:
        units.convert([1.0, 1e308], "klbf", "N")
    assert info.value.parameter == "value"
    assert units.convert(1e300, "klbf", "N") == pytest.approx(4448.2216152605e300, rel=1e-15)
    assert math.isinf(units.convert(math.inf, "klbf", "N"))  # an inf given stays: the engine's rule names it


def test_nested_sequences_of_strings_convert_element_by_element():
    assert units.to_si([["2 ft"]], "m", "x") == [[pytest.approx(0.6096, rel=1e-15)]]  # passed on as text before
    assert units.to_si([[1.0, "1 ft"], ["2 m"]], "m", "x") == [[1.0, pytest.approx(0.3048, rel=1e-15)], [2.0]]
    with pytest.raises(units.UnitError, match=r"^depths\[0\]\[1\]: expected a length") as info:
        units.to_si([["1 m", "1 N"]], "m", "depths")
    assert info.value.parameter == "depths[0][1]"


@pytest.mark.parametrize("call, parameter", [
    (lambda: units.to_si("1 m", "m" * 300, "depth"), "unit"),  # UndefinedUnitError before
    (lambda: units.to_si("1 m", "furlongz", "depth"), "unit"),
    (lambda: units.to_si("2 " + "a" * 150, "m", "depth"), "depth"),
    (lambda: units.convert("abc", "m", "ft"), "value"),  # numpy's ValueError before
    (lambda: units.convert("2", "m", "ft"), "value"),  # a string is never read as a number here
    (lambda: units.convert(None, "m", "ft"), "value"),  # NaN before
    (lambda: units.convert([1.0, None], "m", "ft"), "value"),
    (lambda: units.convert(1.0, "m" * 300, "ft"), "from_unit"),
    (lambda: units.convert(1.0, "m", 7), "to_unit"),
    (lambda: units.quantity(None, "normal_force"), "normal_force"),  # AttributeError before
    (lambda: units.quantity(3.0, "normal_force"), "normal_force"),
])
def test_bad_units_input_is_an_invalid_parameter_naming_it(call, parameter):
    with pytest.raises(units.UnitError) as info:
        call()
    assert info.value.parameter == parameter and isinstance(info.value, fs.InvalidParameterError)
    assert str(info.value).startswith(f"{parameter}: ") and len(str(info.value)) < 400


# -------------------------------------------------------------------------------------------------- 3. fits
@pytest.fixture(scope="module")
def dahl_record():
    t = np.linspace(0.0, 0.5, 201)
    v = 0.05 * np.sin(2 * np.pi * 4 * t)
    rig = fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=(t, v), normal_force=N)
    return t, v, fs.simulate(rig, t[-1], output_times=t).friction_force


@pytest.mark.parametrize("rtol", [1.0, 0.5, 1e-20, 1e-300])
def test_compare_laws_refuses_an_rtol_the_engine_refuses(rtol, dahl_record, monkeypatch):
    from frictionsim.fit import forward_model

    monkeypatch.setattr(forward_model, "simulate", lambda *a, **k: pytest.fail("simulated with a refused rtol"))
    with pytest.raises(fs.InvalidParameterError, match=r"rtol must be in \[1e-14, 0.1\]") as info:
        compare_laws((*dahl_record, N), ("dahl",), rtol=rtol)  # a table of NaN, success False before
    assert info.value.parameter == "rtol"


@pytest.mark.parametrize("keywords, parameter", [
    (dict(normal_force="90"), "normal_force"),  # converted to 90.0 before
    (dict(normal_force=b"90"), "normal_force"),
    (dict(normal_force=np.str_("90")), "normal_force"),
    (dict(normal_force=["90"] * 201), "normal_force"),
    (dict(initial_guess={"mu": "0.3"}), "initial_guess['mu']"),
    (dict(bounds={"mu": ("0.1", "1")}), "bounds['mu']"),
])
def test_fits_never_read_text_as_numbers(keywords, parameter, dahl_record):
    t, v, force = dahl_record
    keywords = {"normal_force": N, **keywords}
    with pytest.raises(fs.InvalidParameterError) as info:
        identify_dahl(t, v, force, keywords.pop("normal_force"), fit_exponent=False, **keywords)
    assert info.value.parameter == parameter
    with pytest.raises(fs.InvalidParameterError) as info:
        identify_dahl([str(x) for x in t], v, force, N, fit_exponent=False)
    assert info.value.parameter == "t"


def test_a_run_past_its_timeout_fails_the_command(tmp_path, capsys):
    source = tmp_path / "small.toml"
    source.write_text(SMALL, encoding="utf-8")
    # the run takes ~7 ms, less than the engine's 20 ms between clock reads: it completed and exited 0 before
    assert main(["run", str(source), "--timeout", "1e-6", "--out", str(tmp_path / "o")]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"error: {source}: case[1] 'coulomb': wall-clock budget exceeded") and "timeout" in err
    assert _tree(tmp_path) == ["small.toml"]


# --------------------------------------------------------------------------------------- 4. whole or nothing
def test_atomic_path_renames_into_place_or_leaves_the_earlier_file(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("earlier\n")
    with pytest.raises(KeyboardInterrupt):
        with atomic.atomic_path(target) as temporary:
            assert temporary.parent == tmp_path and temporary.suffix == ".csv" and temporary.name.startswith(".")
            temporary.write_text("half a ta")
            raise KeyboardInterrupt
    assert target.read_text() == "earlier\n" and os.listdir(tmp_path) == ["table.csv"]
    atomic.write_text(target, "new\n")
    assert target.read_text() == "new\n" and os.listdir(tmp_path) == ["table.csv"]
    probe = tmp_path / "probe"
    probe.write_text("")  # the permissions open() gives under this umask
    assert (target.stat().st_mode & 0o777) == (probe.stat().st_mode & 0o777)
    with pytest.raises(FileExistsError):
        _exclusive(target)  # replace=False: linked in only where the name is free
    assert target.read_text() == "new\n" and sorted(os.listdir(tmp_path)) == ["probe", "table.csv"]
    _exclusive(tmp_path / "free.csv")
    assert (tmp_path / "free.csv").read_text() == "other" and len(os.listdir(tmp_path)) == 3
    atomic.write_bytes(target, b"bytes")
    assert target.read_bytes() == b"bytes" and len(os.listdir(tmp_path)) == 3


def _exclusive(target):
    with atomic.atomic_path(target, replace=False) as temporary:
        temporary.write_text("other")


@pytest.fixture(scope="module")
def small_result():
    t = np.linspace(0.0, 0.2, 51)
    rig = fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=(t, 0.05 * np.sin(2 * np.pi * 4 * t)), normal_force=N)
    return fs.simulate(rig, t[-1], output_times=t)


def test_an_interrupted_netcdf_write_leaves_the_earlier_file(small_result, tmp_path, monkeypatch):
    xr = pytest.importorskip("xarray")
    from frictionsim import io

    path = small_result.to_netcdf(tmp_path / "run.nc")
    before = path.read_bytes()
    real = xr.Dataset.to_netcdf

    def killed(self, target, *args, **kwargs):  # writes part of the file, then the process is "killed"
        real(self, target, *args, **kwargs)
        with open(target, "r+b") as file:
            file.truncate(len(before) // 3)
        raise KeyboardInterrupt

    monkeypatch.setattr(xr.Dataset, "to_netcdf", killed)
    with pytest.raises(KeyboardInterrupt):
        small_result.to_netcdf(path)  # a 4 MB unreadable file under the final name before
    assert path.read_bytes() == before and os.listdir(tmp_path) == ["run.nc"]
    monkeypatch.undo()
    assert io.metadata(io.open_dataset(path)) == small_result.metadata


def test_an_interrupted_metadata_write_leaves_the_earlier_file(tmp_path, monkeypatch):
    record = {"frictionsim": {"version": fs.__version__}, "n": 1}
    path = provenance.write_metadata(tmp_path, record)
    before = path.read_text(encoding="utf-8")
    real = Path.write_text

    def killed(self, text, *args, **kwargs):
        real(self, text[: len(text) // 2], *args, **kwargs)
        raise KeyboardInterrupt

    monkeypatch.setattr(Path, "write_text", killed)
    with pytest.raises(KeyboardInterrupt):
        provenance.write_metadata(tmp_path, dict(record, n=2))  # a 0-byte or truncated metadata.json before
    monkeypatch.undo()
    assert path.read_text(encoding="utf-8") == before and json.loads(before)["n"] == 1
    assert os.listdir(tmp_path) == ["metadata.json"]
    provenance.write_metadata(tmp_path, dict(record, n=3))
    assert json.loads(path.read_text(encoding="utf-8"))["n"] == 3 and os.listdir(tmp_path) == ["metadata.json"]


# ----------------------------------------------------------------------------------------------- 5. enums
ENUMS = [cls for cls in vars(_core).values() if isinstance(cls, type) and hasattr(cls, "__members__")]


def test_every_enum_of_the_engine_is_in_the_walk():
    assert {_core.Method, _core.LinearSolver} <= set(ENUMS)


@pytest.mark.parametrize("enum", ENUMS, ids=lambda cls: cls.__name__)
def test_enum_values_pickle_and_copy(enum):
    for member in enum.__members__.values():  # "never constructed" before: __setstate__ was guarded
        for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
            back = pickle.loads(pickle.dumps(member, protocol))
            assert back == member and type(back) is enum and int(back) == int(member)
        assert copy.deepcopy(member) == member and copy.copy(member) == member
    options = _core.SolverOptions(method=_core.Method.cvode_bdf, linear_solver=_core.LinearSolver.band)
    assert copy.deepcopy([options.method, options.linear_solver]) == [_core.Method.cvode_bdf, _core.LinearSolver.band]


def test_an_unconstructed_object_is_still_refused():
    law = fs.Coulomb.__new__(fs.Coulomb)
    with pytest.raises(TypeError, match="never constructed"):
        law.mu
    with pytest.raises(TypeError, match="never constructed"):
        repr(law)
    with pytest.raises(AttributeError):
        law.__setstate__  # the one name looked up before construction; Coulomb has none
    method = _core.Method.__new__(_core.Method)
    with pytest.raises(TypeError, match="never constructed"):
        method.name
