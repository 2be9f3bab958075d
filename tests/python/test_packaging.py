"""Packaging: the installed package's files, one version source, license metadata, optional extras, and the
extension with or without SUNDIALS.

The version is written once, in CMakeLists.txt's ``project(frictionsim VERSION x.y.z)``: the installed
distribution (scikit-build-core reads it with a regex), ``frictionsim.__version__`` (the extension reports the
CMake project version), the CMake package's version file and CITATION.cff must all say the same.

The extension may be built without SUNDIALS (Dormand-Prince only): each build is tested for what it has, so the
same file runs against the wheel (scripts/test's main suite) and against the no-SUNDIALS build (scripts/test
runs this file again with that extension first on the path).
"""

from __future__ import annotations

import glob
import importlib.metadata
import math
import os
import platform
import re
import shutil
import subprocess
import sys
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import _core
from frictionsim.errors import InvalidParameterError

ROOT = Path(__file__).resolve().parents[2]
CMAKELISTS = ROOT / "CMakeLists.txt"

needs_source = pytest.mark.skipif(not CMAKELISTS.is_file(), reason="needs the source tree (CMakeLists.txt)")


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


def _source_version() -> str:
    """The one version source: project(frictionsim VERSION x.y.z) in CMakeLists.txt."""
    match = re.search(r"project\(\s*frictionsim\s+VERSION\s+([0-9]+\.[0-9]+\.[0-9]+)", CMAKELISTS.read_text())
    assert match, "CMakeLists.txt has no project(frictionsim VERSION x.y.z)"
    return match.group(1)


@needs_source
def test_one_version_source():
    version = _source_version()
    assert _core.__version__ == version  # compiled in from the CMake project version
    assert fs.__version__ == version
    assert importlib.metadata.version("frictionsim") == version  # the installed distribution's metadata
    citation = re.search(r"^version:\s*\"?([^\"\s]+)", (ROOT / "CITATION.cff").read_text(), re.MULTILINE)
    assert citation and citation.group(1) == version


@needs_source
@pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake")
def test_cmake_package_version_file(tmp_path):
    """The CMake package's version file carries the same version, and while 0.x a consumer must ask for the same
    minor version (SameMinorVersion): 0.1 finds 0.1.z, 0.2 and 1.0 do not."""
    version = _source_version()
    major, minor, _ = (int(p) for p in version.split("."))
    build = tmp_path / "build"
    # Only the package files: no tests, examples, extension, SUNDIALS or Eigen (a configure of a second or two).
    subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DFRICTIONSIM_BUILD_TESTS=OFF",
                    "-DFRICTIONSIM_BUILD_BENCHMARKS=OFF", "-DFRICTIONSIM_BUILD_EXAMPLES=OFF",
                    "-DFRICTIONSIM_BUILD_PYTHON=OFF", "-DFRICTIONSIM_SUNDIALS=OFF", "-DFRICTIONSIM_EIGEN=OFF",
                    "-DFRICTIONSIM_INSTALL=ON"], check=True, capture_output=True, text=True)
    version_file = build / "frictionsimConfigVersion.cmake"
    assert version_file.is_file()

    def ask(requested: str) -> tuple:
        # What find_package(frictionsim <requested>) sets before reading the version file.
        parts = requested.split(".") + ["0", "0"]
        script = tmp_path / "ask.cmake"
        script.write_text(
            f'set(PACKAGE_FIND_NAME frictionsim)\nset(PACKAGE_FIND_VERSION "{requested}")\n'
            f"set(PACKAGE_FIND_VERSION_MAJOR {parts[0]})\nset(PACKAGE_FIND_VERSION_MINOR {parts[1]})\n"
            f"set(PACKAGE_FIND_VERSION_PATCH {parts[2]})\n"
            f'include("{version_file.as_posix()}")\n'
            'message("${PACKAGE_VERSION};${PACKAGE_VERSION_COMPATIBLE}")\n')
        out = subprocess.run(["cmake", "-P", str(script)], check=True, capture_output=True, text=True).stderr
        found, compatible = out.strip().splitlines()[-1].split(";")
        return found, compatible.upper() in ("TRUE", "ON", "1")

    assert ask(f"{major}.{minor}") == (version, True)
    assert ask(version) == (version, True)
    assert ask(f"{major}.{minor + 1}") == (version, False)  # a newer minor: refused
    assert ask(f"{major + 1}.0") == (version, False)
    if major == 0 and minor > 0:
        assert ask(f"0.{minor - 1}") == (version, False)  # while 0.x an older minor is refused too


def test_license_and_extras_metadata():
    meta = importlib.metadata.metadata("frictionsim")
    assert meta["License-Expression"] == "MIT"  # PEP 639
    assert "LICENSE" in (meta.get_all("License-File") or [])
    extras = set(meta.get_all("Provides-Extra") or [])
    assert {"signal", "dask", "io", "units", "docs", "test"} <= extras
    requirements = meta.get_all("Requires-Dist") or []
    optional = {"emd-signal", "dask", "xarray", "pint"}  # only through an extra, never a hard dependency
    for requirement in requirements:
        name = re.match(r"[A-Za-z0-9._-]+", requirement).group(0).lower()
        if name in optional:
            assert "extra ==" in requirement, requirement


def _axial_mean(method: str) -> float:
    """Paper 000's Fig. 7(a) rig with Dahl friction: the mean friction force over its last 8 whole cycles, both
    ends output times (so the mean is the friction impulse's difference at solver accuracy)."""
    rig = fs.AxialVibrationRig(friction=fs.Dahl(mu=0.41, tangential_stiffness=4e4))
    result = fs.simulate(rig, 1.0, method=method, rtol=1e-9, atol=1e-12, output_times=[1.0 - 8 * rig.period, 1.0])
    return result.mean_over_cycles(transient=0.0)


def test_dormand_prince_in_every_build():
    """Whatever the build, Dormand-Prince reproduces eq 8's closed-form Coulomb reduction 1 - (2/pi) asin(v_d/v_a)
    on the kinematic rig."""
    assert fs.axial.kinematic_coulomb_reduction(0.5) == pytest.approx(fs.axial.coulomb_reduction(0.5), abs=1e-7)


@pytest.mark.skipif(not _core.HAS_SUNDIALS, reason="the extension was built without SUNDIALS")
def test_cvode_methods_with_sundials():
    # Both integrators agree on paper 000's mean friction force (Fig. 7(a), Dahl).
    dp = _axial_mean("dormand_prince")
    assert math.isfinite(dp) and dp != 0.0
    assert _axial_mean("cvode_bdf") == pytest.approx(dp, rel=1e-5)
    assert _axial_mean("cvode_adams") == pytest.approx(dp, rel=2e-5)


@pytest.mark.skipif(_core.HAS_SUNDIALS, reason="the extension was built with SUNDIALS")
@pytest.mark.parametrize("method", ["cvode_bdf", "cvode_adams"])
def test_cvode_methods_without_sundials(method):
    rig = fs.AxialVibrationRig(friction=fs.Dahl(mu=0.41, tangential_stiffness=4e4))
    with pytest.raises(InvalidParameterError) as caught:
        fs.simulate(rig, 0.1, method=method)
    assert caught.value.parameter == "method"
    message = str(caught.value)
    assert method in message and "without SUNDIALS" in message and "dormand_prince" in message


@pytest.mark.skipif(_core.HAS_SUNDIALS, reason="the extension was built with SUNDIALS")
def test_automatic_is_dormand_prince_without_sundials():
    """A stiff law (LuGre), whose automatic choice is CVODE BDF, runs on Dormand-Prince: the same run exactly."""
    rig = fs.AxialVibrationRig(friction=fs.LuGre(mu=0.3, mu_static=0.4, stribeck_velocity=0.01,
                                                 bristle_stiffness=1e5, bristle_damping=300.0))
    automatic = fs.simulate(rig, 0.2)
    explicit = fs.simulate(rig, 0.2, method="dormand_prince")
    assert automatic.success
    np.testing.assert_array_equal(automatic.t, explicit.t)
    np.testing.assert_array_equal(automatic.friction_force, explicit.friction_force)


def test_emd_without_pyemd_names_the_extra(monkeypatch):
    from frictionsim import signal

    monkeypatch.setitem(sys.modules, "PyEMD", None)  # import PyEMD now raises ImportError
    t = np.linspace(0.0, 1.0, 101)
    with pytest.raises(ImportError, match=r"frictionsim\[signal\]") as caught:
        signal.emd(t, np.sin(2 * np.pi * 5 * t))
    assert caught.value.name == "PyEMD"
    # the rest of frictionsim.signal needs no PyEMD
    assert signal.dominant_frequency(t, np.sin(2 * np.pi * 5 * t)) == pytest.approx(5.0, rel=1e-3)


def _installed_wheel_tags():
    try:
        wheel = importlib.metadata.distribution("frictionsim").read_text("WHEEL")
    except importlib.metadata.PackageNotFoundError:
        return None
    return [line.split(":", 1)[1].strip() for line in (wheel or "").splitlines() if line.startswith("Tag:")]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="manylinux wheels are Linux wheels")
def test_installed_wheel_is_the_repaired_manylinux_wheel():
    """scripts/test installs the wheel that auditwheel repaired (scripts/wheel's): its tags are this interpreter's
    and manylinux, never the bare linux_* of pip wheel's own output."""
    tags = _installed_wheel_tags()
    if tags is None:
        pytest.skip("frictionsim is not installed from a wheel here (a development checkout on the path)")
    here = f"cp{sys.version_info.major}{sys.version_info.minor}"
    assert tags, "the installed WHEEL file has no Tag lines"
    for tag in tags:
        python_tag, abi_tag, platform_tag = tag.split("-")
        assert (python_tag, abi_tag) == (here, here), tag
        assert re.fullmatch(rf"manylinux(_\d+_\d+|1|2010|2014)_{re.escape(platform.machine())}", platform_tag), tag


def _tarball(path: Path, files: dict) -> Path:
    import io
    import tarfile

    with tarfile.open(path, "w:gz") as archive:
        for name, text in files.items():
            data = text.encode()
            info = tarfile.TarInfo(f"frictionsim-0.1.0/{name}")
            info.size = len(data)
            archive.addfile(info, io.BytesIO(data))
    return path


def _sdist_check(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "lib" / "sdist_check.py"), *map(str, args)],
                          capture_output=True, text=True)


@needs_source
def test_sdist_check_refuses_build_files_and_missing_sources(tmp_path):
    """scripts/lib/sdist_check.py, which scripts/test runs on the sdist it builds the wheel from: the top-level
    files a build reads are required, every tracked file of cmake/ include/ bindings/ python/ too, and nothing of a
    build may be packed (build dirs, out/, .venv, objects, extensions, bytecode)."""
    good = {name: "x" for name in ("pyproject.toml", "CMakeLists.txt", "LICENSE", "README.md", "PKG-INFO",
                                   "bindings/module.cpp", "include/frictionsim/a.hpp")}
    assert _sdist_check(_tarball(tmp_path / "good.tar.gz", good)).returncode == 0
    for extra in ("build/x.o", "build-py/bindings/y.txt", "out/wheel/frictionsim.whl", ".venv/bin/python",
                  "python/frictionsim/__pycache__/a.cpython-311.pyc", "python/frictionsim/_core.so"):
        checked = _sdist_check(_tarball(tmp_path / "bad.tar.gz", {**good, extra: "x"}))
        assert checked.returncode == 1 and f"a build's file: {extra}" in checked.stderr, (extra, checked.stderr)
    missing = dict(good)
    del missing["pyproject.toml"]
    checked = _sdist_check(_tarball(tmp_path / "missing.tar.gz", missing))
    assert checked.returncode == 1 and "missing pyproject.toml" in checked.stderr

    if shutil.which("git") is None:
        return
    # A source tree whose tracked header the sdist lacks.
    tree = tmp_path / "tree"
    (tree / "include" / "frictionsim").mkdir(parents=True)
    (tree / "include" / "frictionsim" / "a.hpp").write_text("x")
    (tree / "include" / "frictionsim" / "b.hpp").write_text("x")
    subprocess.run(["git", "init", "-q", str(tree)], check=True)
    subprocess.run(["git", "-C", str(tree), "add", "include"], check=True)
    checked = _sdist_check(_tarball(tmp_path / "good.tar.gz", good), tree)
    assert checked.returncode == 1, checked.stderr
    assert "missing include/frictionsim/b.hpp (tracked, read by the build)" in checked.stderr
    assert "a.hpp" not in checked.stderr.split("error:", 1)[1]
