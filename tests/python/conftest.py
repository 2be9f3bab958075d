"""With FRICTIONSIM_REQUIRE_EXTRAS=1 (scripts/test sets it), a test skipped because a module of the `test` extra is
missing fails instead: the extras in pyproject.toml must hold everything the suite imports, and a gap there would
otherwise hide as a skip (xarray, pint and pyarrow did, before the `io` and `units` extras existed).
"""

from __future__ import annotations

import os
import re

import pytest

#: Import names of what pyproject.toml's `test` extra installs (with the extras it pulls in). Skips naming any other
#: module (mypy, which the stub test uses only when present) stay skips.
TEST_EXTRA_MODULES = ("xarray", "h5netcdf", "h5py", "pyarrow", "pint", "dask", "distributed", "welleng",
                      "torque_drag", "pybind11_stubgen", "PyEMD", "sphinx", "numpydoc", "sphinx_gallery",
                      "myst_parser", "selenium", "hypothesis")

_MISSING = re.compile(r"\b(" + "|".join(re.escape(m) for m in TEST_EXTRA_MODULES) + r")\b")


def _required() -> bool:
    return os.environ.get("FRICTIONSIM_REQUIRE_EXTRAS", "") not in ("", "0")


def _missing_module(report) -> str:
    """The module of the test extra a skip report names, else ''."""
    longrepr = report.longrepr
    reason = longrepr[2] if isinstance(longrepr, tuple) and len(longrepr) == 3 else str(longrepr)
    found = _MISSING.search(reason)
    return found.group(1) if found else ""


def _fail_if_extra_missing(report) -> None:
    if report.skipped and _required() and not hasattr(report, "wasxfail"):
        module = _missing_module(report)
        if module:
            report.outcome = "failed"
            report.longrepr = (f"skipped for want of {module}, which pyproject.toml's test extra must install "
                               f"(FRICTIONSIM_REQUIRE_EXTRAS=1): {report.longrepr}")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    _fail_if_extra_missing(outcome.get_result())


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector):
    outcome = yield
    _fail_if_extra_missing(outcome.get_result())


def pytest_terminal_summary(terminalreporter):
    """The hardening outcome table of the property tests that ran (tests/python/outcomes.py)."""
    import outcomes

    text = outcomes.table()
    if text:
        terminalreporter.write_sep("-", "hardening outcomes (generated inputs per input class)")
        terminalreporter.write_line(text)
        outcomes.write_table()
