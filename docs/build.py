"""Build the documentation site: ``python docs/build.py OUT_DIR`` (what scripts/docs and tests/python/test_docs.py
run).

Sphinx writes generated sources (autosummary's API pages, sphinx-gallery's example pages) into its source
directory, so the site is built from a staged copy of docs/, README.md (the quick start is included from it) and
examples/gallery/: the repository is never written to. Every build starts from a fresh stage (``--stage``,
default OUT_DIR/../.docs-stage) and a fresh environment, because Sphinx and sphinx-gallery track their sources,
not the package: a changed docstring or engine would otherwise leave stale API pages and example outputs.
``--keep`` reuses the stage (incremental: only edited pages and examples are redone) for work on the docs alone.

Warnings are errors (``-W --keep-going``: every warning is reported, then the build fails). The frictionsim that
is documented, and that the gallery runs, is the one this Python imports.
"""

from __future__ import annotations

import argparse
import filecmp
import shutil
import subprocess
import sys
from pathlib import Path
from typing import List, Optional

REPO = Path(__file__).resolve().parent.parent
#: What the site is built from, relative to the repository.
SOURCES = ("docs", "README.md", "examples/gallery")
#: Written by the build inside the staged docs/: kept between builds, never mirrored from the repository.
GENERATED = ("generated", "gallery", "sg_execution_times.rst")


def _mirror(source: Path, target: Path, keep: tuple = ()) -> None:
    """Make ``target`` a copy of ``source``; files whose bytes did not change keep their time stamps, so Sphinx
    and sphinx-gallery rebuild only what changed. Top-level names in ``keep`` are left alone."""
    if source.is_file():
        if not (target.is_file() and filecmp.cmp(source, target, shallow=False)):
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target)
        return
    target.mkdir(parents=True, exist_ok=True)
    wanted = {p.name for p in source.iterdir() if p.name != "__pycache__"}
    for stale in target.iterdir():
        if stale.name not in wanted and stale.name not in keep:
            shutil.rmtree(stale) if stale.is_dir() else stale.unlink()
    for name in wanted:
        _mirror(source / name, target / name)


def stage(stage_dir: Path) -> Path:
    """Copy the site's sources into ``stage_dir`` (same layout as the repository); returns the staged docs/."""
    for name in SOURCES:
        _mirror(REPO / name, stage_dir / name, keep=GENERATED if name == "docs" else ())
    return stage_dir / "docs"


def sphinx_command(source: Path, out_dir: Path, doctrees: Path, *, warnings_as_errors: bool = True,
                   nitpicky: bool = False, extra: Optional[List[str]] = None) -> List[str]:
    command = [sys.executable, "-m", "sphinx", "-b", "html", "-d", str(doctrees), "--quiet"]
    if warnings_as_errors:
        command += ["-W", "--keep-going"]
    if nitpicky:
        command.append("-n")
    return command + list(extra or []) + [str(source), str(out_dir)]


def build(out_dir: Path, *, stage_dir: Optional[Path] = None, keep: bool = False, warnings_as_errors: bool = True,
          nitpicky: bool = False, extra: Optional[List[str]] = None) -> subprocess.CompletedProcess:
    """Stage the sources and run sphinx-build into ``out_dir``; returns the finished process (output captured,
    ``returncode`` non-zero on any warning when ``warnings_as_errors``). ``keep``: reuse the stage's generated
    pages, example outputs and environment (incremental)."""
    out_dir = Path(out_dir).resolve()
    stage_dir = Path(stage_dir).resolve() if stage_dir else out_dir.parent / ".docs-stage"
    if not keep:
        if stage_dir.exists():
            shutil.rmtree(stage_dir)
        if (out_dir / ".buildinfo").is_file():  # a site Sphinx built: no stale pages of removed sources stay
            shutil.rmtree(out_dir)
    source = stage(stage_dir)
    extra = list(extra or []) + ([] if keep else ["-E"])  # -E: re-read every page (the API pages' docstrings)
    command = sphinx_command(source, out_dir, stage_dir / "doctrees", warnings_as_errors=warnings_as_errors,
                             nitpicky=nitpicky, extra=extra)
    return subprocess.run(command, cwd=stage_dir, capture_output=True, text=True, check=False)


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", type=Path, help="where the HTML site goes (e.g. out/docs)")
    parser.add_argument("--stage", type=Path, default=None, help="staged sources and doctrees "
                        "(default: OUT_DIR/../.docs-stage)")
    parser.add_argument("--keep", action="store_true", help="reuse the staged sources, example outputs and "
                        "environment: an incremental build for work on the docs alone")
    parser.add_argument("--allow-warnings", action="store_true", help="do not turn warnings into errors")
    parser.add_argument("-n", "--nitpicky", action="store_true", help="warn about every unresolved reference")
    args, extra = parser.parse_known_args(argv)
    done = build(args.out_dir, stage_dir=args.stage, keep=args.keep, warnings_as_errors=not args.allow_warnings,
                 nitpicky=args.nitpicky, extra=extra)
    sys.stdout.write(done.stdout)
    sys.stderr.write(done.stderr)
    return done.returncode


if __name__ == "__main__":
    sys.exit(main())
