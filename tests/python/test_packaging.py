"""The installed package: the extension carries SUNDIALS (static link where static libraries exist), the paper
data, the type stubs and the console script are installed."""

import glob
import os
import shutil
import subprocess
import sys
from importlib import resources

import pytest

import frictionsim as fs


@pytest.mark.skipif(not sys.platform.startswith("linux") or shutil.which("ldd") is None, reason="needs ldd")
def test_extension_links_sundials_statically_where_static_libraries_exist():
    static = glob.glob("/usr/lib/*/libsundials_cvode.a") + glob.glob("/usr/lib/libsundials_cvode.a")
    if not static:
        pytest.skip("no static SUNDIALS here: the extension links the shared libraries")
    linked = subprocess.run(["ldd", fs._core.__file__], capture_output=True, text=True, check=True).stdout
    assert "sundials" not in linked, linked


def test_package_files_are_installed():
    package = resources.files("frictionsim")
    for name in ("py.typed", "_core.pyi", "data/table4.csv", "data/table3.csv", "scenarios/fig7_obm.toml"):
        assert package.joinpath(name).is_file(), name


def test_help_is_useful():
    doc = fs.Dahl.__doc__
    assert "tangential_stiffness" in doc and "N/m" in doc and "eq 9" in doc
    assert "F_N" in fs.AxialVibrationRig.__doc__ and "[kg]" in fs.AxialVibrationRig.__doc__


def test_console_script_runs():
    script = os.path.join(os.path.dirname(sys.executable), "frictionsim")
    completed = subprocess.run([script, "--help"], capture_output=True, text=True)
    assert completed.returncode == 0, completed.stderr
    assert "demo" in completed.stdout and "fit-table5" in completed.stdout
