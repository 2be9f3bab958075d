"""The ``frictionsim`` command line.

    frictionsim run SCENARIO.toml [--out DIR] [--jobs N] [--format csv|netcdf|parquet]
                                                simulate a scenario file (see frictionsim.scenario)
    frictionsim sweep SWEEP.toml [--out DIR] [--jobs N] [--timeout SECONDS]
                                                a scenario over a grid of its parameters (frictionsim.scenario.
                                                sweep_file): sweep.csv and sweep.png
    frictionsim scenarios list | copy NAME [DEST]
                                                the packaged example scenario and sweep files
    frictionsim demo [--out DIR] [--quick]      paper 000's Fig. 7 cases, friction reduction, Table 5 refit;
                                                paper 001's torsional rig: Fig. 7, law comparison, stick-slip map
    frictionsim fit-table5 [--out DIR]          refit Table 5 from Table 4 and plot Fig. 11
    frictionsim fit --law lugre DATA.csv [--out DIR]
                                                identify a friction law from a record (frictionsim.fit.identify):
                                                the fitted table, fit.csv, fit_record.csv, fit.png
    frictionsim torque-drag SURVEY.csv [--string OD:ID:LENGTH,...] [--mu 0.2 0.3] [--out DIR]
                               [--oscillator MD:FORCE:FREQ,...] [--place]
                                                soft-string torque and drag along a survey: per-node CSV,
                                                broomstick and well-path plots (see frictionsim.wells); with
                                                hydraulic oscillators, the vibrated broomstick and the zone of
                                                influence; --place: the tool's placement curve

Every command takes ``-q`` (errors only, no progress bar) and ``-v`` / ``-vv`` (the library's log messages,
``logging.getLogger("frictionsim")``, at INFO / DEBUG on stderr). Progress bars go to stderr and only to a
terminal. ``--jobs N`` runs a scenario's cases or a sweep's points in N processes (at most one per CPU this
process may use, with a warning when fewer than asked); the results are those of ``--jobs 1``, in the same order.

Outputs appear all at once: everything is simulated first, then written into a temporary directory next to the
target and moved into place (files already in the target that the command does not write are left alone). An
output file that exists is never replaced silently: the command refuses (exit 1), naming the file, unless
``--force`` is given (``fit``: ``--overwrite``, its ``--force`` names the force column); a target holding an
earlier command's metadata.json is refused before anything runs.
Ctrl-C or SIGTERM removes that temporary directory: nothing half-written is left behind. Every command that
writes also writes ``metadata.json`` beside its outputs (:mod:`frictionsim.provenance`: version, git revision,
command line, rigs, solver options and statistics, time, platform).

Where ``run`` and ``sweep`` write: ``--out DIR`` when given (the caller's choice); else the file's
``output.directory``, relative to the file's folder and confined to it: an absolute path, a ``..`` or a symbolic
link that leads out of it is refused unless ``--allow-outside`` is given (a file from elsewhere must not write
anywhere it likes); else ``out/<file stem>`` in the working directory (a stem that would name no folder
below ``out/``, such as ``...toml``'s ``..``, is ``scenario`` / ``sweep`` / ``survey`` instead).

``--timeout SECONDS`` (``run``, ``sweep``; else the file's solver.timeout) is the wall-clock budget of each
simulation: of a case, of each point of a stick-slip map and of each case at each point of a sweep. A sweep's point
or a map's point that runs out (or fails otherwise) is recorded as failed with its reason (the ``error`` column)
and the others still run; the outputs are written and the command exits 1, one line per failed point on stderr.

Exit status: 0 on success, 2 for a bad scenario, sweep file, data file or command line (``error: <file>: <key>:
<rule>`` on stderr), 1 when a simulation stops early (with the time reached), a point of a sweep or a map failed,
or the outputs cannot be written (or would replace files without --force), 130 on Ctrl-C (the workers of --jobs
included: they ignore SIGINT and are terminated), 143 on SIGTERM. ``torque-drag`` reports a bad survey with its file, line, station and field
(exit 2); ``fit`` exits 1 when the fit does not converge (its outputs are written all the same, to look at).
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import math
import os
import shlex
import shutil
import sys
import tempfile
from contextlib import contextmanager
from importlib import resources
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, Iterator, List, Optional, Sequence

from . import __version__
from .atomic import atomic_path, write_csv
from .errors import InvalidParameterError, SimulationError
from .scenario.staging import OutputExistsError, staged_directory

__all__ = ["main", "staged_directory"]

#: default output directory of ``demo`` and ``fit-table5`` (scripts/demo sets FRICTIONSIM_OUT_DIR)
DEFAULT_OUT = os.environ.get("FRICTIONSIM_OUT_DIR", "out")
#: ``--format`` of ``run``: the time series' file format (csv needs nothing; netcdf the [io] extra, parquet pyarrow)
FORMATS = ("csv", "netcdf", "parquet")
#: Log levels of -q, (none), -v, -vv.
LEVELS = {-1: logging.ERROR, 0: logging.WARNING, 1: logging.INFO, 2: logging.DEBUG}

log = logging.getLogger("frictionsim.cli")


class CommandError(Exception):
    """A failure reported as ``error: <message>`` with exit ``status``."""

    def __init__(self, message: str, status: int) -> None:
        super().__init__(message)
        self.status = status


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``frictionsim`` console script; returns the exit status."""
    try:  # Ctrl-C while the command line is read and the scenario package imported: 130 too, not death by SIGINT
        from .scenario import ScenarioError

        parser = _parser()
        argv = list(sys.argv[1:] if argv is None else argv)
        args = parser.parse_args(argv)
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    if not getattr(args, "command", None):
        parser.print_help(sys.stderr)
        return 2
    args.command_line = shlex.join(["frictionsim", *argv])
    with _console_logging(args):
        try:
            with _terminate_as_exception():
                return args.command(args)
        except KeyboardInterrupt:
            print("error: interrupted", file=sys.stderr)
            return 130
        except _Terminated:
            print("error: terminated (SIGTERM)", file=sys.stderr)
            return 143
        except ScenarioError as error:
            print(f"error: {error}", file=sys.stderr)
            return 2
        except CommandError as error:
            print(f"error: {error}", file=sys.stderr)
            return error.status


class _Terminated(BaseException):
    """SIGTERM, raised where the command is so that its clean-up (the staging directory) runs."""


@contextmanager
def _terminate_as_exception() -> Iterator[None]:
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():  # signals go to the main thread only
        yield
        return

    def terminate(signum, frame):
        raise _Terminated()

    previous = signal.signal(signal.SIGTERM, terminate)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


# ------------------------------------------------------------------------------------ logging, progress, processes
def _verbosity(args) -> int:
    return -1 if getattr(args, "quiet", False) else min(getattr(args, "verbose", 0) or 0, 2)


@contextmanager
def _console_logging(args) -> Iterator[None]:
    """The library logs to ``logging.getLogger("frictionsim")``; the command line shows it on stderr at the level
    of -q / -v / -vv, for the length of the command only (main() may run many times in one process)."""
    logger = logging.getLogger("frictionsim")
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(levelname)s: %(name)s: %(message)s"))
    previous = logger.level
    logger.setLevel(LEVELS[_verbosity(args)])
    logger.addHandler(handler)
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.setLevel(previous)


def _progress(args, total: int, description: str, unit: str = "case"):
    """A tqdm bar on stderr, shown only on a terminal and without -q."""
    from tqdm import tqdm

    return tqdm(total=total, desc=description, unit=unit, file=sys.stderr, leave=False, dynamic_ncols=True,
                disable=args.quiet or not sys.stderr.isatty())


def _ignore_interrupts() -> None:
    """Pool workers leave Ctrl-C to the command (a terminal sends it to the whole process group): it stops the pool."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


_SIGINT_WRAPPER: List[Optional[str]] = []  # the wrapper made once per process ([None]: none usable here)


def _sigint_ignoring_wrapper() -> Optional[str]:
    """The path of a two-line /bin/sh wrapper, ``trap '' INT`` then exec of this interpreter, made once per process
    and removed when it exits: a worker's shell opens the script some time after its start (long after it under
    load), so the file must outlive the block that starts the pool (removed at its end, a slow worker once found
    nothing to run). None without /bin/sh (Windows) or where it cannot run (a noexec temporary folder)."""
    import atexit
    import multiprocessing.spawn as spawn
    import subprocess

    if _SIGINT_WRAPPER:
        return _SIGINT_WRAPPER[0]
    shell, path = "/bin/sh", None
    if os.name == "posix" and os.access(shell, os.X_OK):
        folder = Path(tempfile.mkdtemp(prefix="frictionsim-worker."))
        atexit.register(shutil.rmtree, folder, ignore_errors=True)
        wrapper = folder / "python"
        wrapper.write_text(f"#!{shell}\ntrap '' INT\nexec {shlex.quote(os.fsdecode(spawn.get_executable()))} \"$@\"\n",
                           encoding="utf-8")
        wrapper.chmod(0o700)
        try:
            if subprocess.run([str(wrapper), "-S", "-c", "pass"], timeout=30, capture_output=True).returncode == 0:
                path = str(wrapper)
        except (OSError, subprocess.SubprocessError):
            pass
    _SIGINT_WRAPPER.append(path)
    return path


@contextmanager
def _workers_ignoring_sigint(context) -> Iterator[None]:
    """Processes ``context`` (spawn) starts within the block begin with SIGINT ignored: they are started through
    _sigint_ignoring_wrapper's script (an ignored signal stays ignored through exec, and Python keeps it
    ignored), so a terminal's Ctrl-C, sent to the whole process group, reaches none of them while they import,
    before any initializer could run; this process keeps its own handler and loses nothing. Left: a signal
    within the millisecond between a worker's start and its wrapper's trap ends that worker (quietly; the pool
    replaces it, and this process, interrupted too, ends the pool). Without the wrapper they start as before."""
    import multiprocessing.spawn as spawn

    wrapper, previous = _sigint_ignoring_wrapper(), spawn.get_executable()
    if wrapper is not None:
        context.set_executable(wrapper)
    try:
        yield
    finally:
        context.set_executable(previous)  # a worker started later (a replacement) starts as before


@contextmanager
def _imap(jobs: int, count: int) -> Iterator[Callable[[Callable, Iterable], Iterable]]:
    """An ordered ``imap(function, items)``: the built-in map for one job, else a pool of ``jobs`` processes
    (spawned: nothing of this process's threads or handlers is inherited). Leaving the block - Ctrl-C, SIGTERM,
    an error - terminates the workers, so nothing keeps running after the command."""
    workers = _workers(jobs, count)
    if workers == 1:
        yield map
        return
    import multiprocessing

    pool = None
    context = multiprocessing.get_context("spawn")
    try:
        # the workers start with SIGINT ignored: a Ctrl-C to the process group while they import, before their
        # initializer runs, kills none of them with a traceback; this process handles it
        with _workers_ignoring_sigint(context):
            pool = context.Pool(workers, initializer=_ignore_interrupts)
        yield pool.imap
        pool.close()
    finally:
        if pool is not None:
            pool.terminate()
            pool.join()


def _cpus() -> int:
    """The CPUs this process may run on (its affinity mask: a container's or taskset's share, not the machine's)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # macOS, Windows
        return max(1, os.cpu_count() or 1)


def _workers(jobs: int, count: int) -> int:
    """Processes for ``count`` items asked to run in ``jobs``: at most one per item and one per CPU (more only
    share the CPUs and cost a process each: --jobs 1000 must not start 1000 interpreters)."""
    cpus, wanted = _cpus(), min(jobs, count)
    if wanted > cpus:
        log.warning("--jobs %d: this process may use %d CPU%s; running %d processes", jobs, cpus,
                    "" if cpus == 1 else "s", cpus)
    return max(1, min(wanted, cpus))


def _jobs(value: str) -> int:
    try:
        jobs = int(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number of processes (got {value!r})") from None
    if jobs < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1 (got {jobs})")
    return jobs


# ----------------------------------------------------------------------------------------------- provenance
def _metadata(args, directory: Path, *, rigs: Any = (), solver_options: Optional[Dict[str, Any]] = None,
              stats: Optional[Dict[str, Any]] = None, extra: Optional[Dict[str, Any]] = None) -> List[Path]:
    """[metadata.json] in ``directory`` (:func:`frictionsim.provenance.collect`, with the command line)."""
    from . import provenance

    record = provenance.collect(command=args.command_line, rigs=rigs, solver_options=solver_options, stats=stats,
                                extra=extra)
    return [provenance.write_metadata(directory, record)]


# --------------------------------------------------------------------------------------------------- parser
def _common(jobs: bool = False) -> argparse.ArgumentParser:
    """-q / -v (and --jobs) for a subcommand: given after the command, they override the ones before it."""
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-q", "--quiet", action="store_true", default=argparse.SUPPRESS,
                        help="errors only: no progress bar, no warnings")
    common.add_argument("-v", "--verbose", action="count", default=argparse.SUPPRESS,
                        help="the library's log messages (-v: INFO, -vv: DEBUG) on stderr")
    if jobs:
        common.add_argument("-j", "--jobs", type=_jobs, default=1, metavar="N",
                            help="run in N processes (default 1; at most one per CPU); the results are the same")
    return common


def _forcing(*names: str) -> argparse.ArgumentParser:
    """--force (also --overwrite) of every command that writes: an output file that exists is replaced only with
    it. ``fit`` takes --overwrite only: its --force names the friction-force column."""
    names = names or ("--force", "--overwrite")
    forcing = argparse.ArgumentParser(add_help=False)
    forcing.add_argument(*names, dest="overwrite", action="store_true",
                         help="replace output files that exist (default: refuse, naming the file)")
    forcing.set_defaults(force_option=names[0])
    return forcing


def _timeout() -> argparse.ArgumentParser:
    """--timeout of run and sweep: the wall-clock budget of each simulation."""
    timeout = argparse.ArgumentParser(add_help=False)
    timeout.add_argument("--timeout", type=float, metavar="SECONDS",
                         help="wall-clock budget of each simulation, a stick-slip map's points and a sweep's "
                              "points too (overrides the file's solver.timeout); one that runs out is a failure "
                              "(exit 1)")
    return timeout


def _placement() -> argparse.ArgumentParser:
    """--out and --allow-outside of the commands that read a file naming its own output.directory (run, sweep)."""
    placement = argparse.ArgumentParser(add_help=False)
    placement.add_argument("--out", type=Path, help="output directory (default: the file's output.directory, "
                                                    "relative to the file's folder and confined to it, else "
                                                    "out/<file stem>)")
    placement.add_argument("--allow-outside", action="store_true",
                           help="let the file's output.directory be absolute or lead out of the file's folder")
    return placement


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="frictionsim",
        description="Friction-driven dynamics in drilling: simulate paper 000's axial vibrating-sliding rig, "
                    "kinematic friction rigs and paper 001's torsional drill-string rig with Coulomb, Stribeck, "
                    "Dahl, LuGre, elasto-plastic and hysteretic (eq 6) friction.",
        epilog="Scenario files are TOML; `frictionsim scenarios list` shows the packaged examples, and "
               "`python -c 'help(\"frictionsim.scenario\")'` the format.")
    parser.add_argument("--version", action="version", version=f"frictionsim {__version__}")
    parser.add_argument("-q", "--quiet", action="store_true", help="errors only: no progress bar, no warnings")
    parser.add_argument("-v", "--verbose", action="count", default=0,
                        help="the library's log messages (-v: INFO, -vv: DEBUG) on stderr")
    commands = parser.add_subparsers(title="commands", metavar="COMMAND")
    common, parallel = [_common()], [_common(jobs=True), _placement(), _forcing(), _timeout()]
    writing = [_common(), _forcing()]

    run = commands.add_parser("run", parents=parallel, help="simulate a scenario file, write tables and PNG plots",
                              description="Simulate every case of a TOML scenario file; write per-case time "
                                          "series, summary.csv, PNG plots and metadata.json; print the summary.")
    run.add_argument("scenario", type=Path, help="scenario file (TOML)")
    run.add_argument("--format", choices=FORMATS, default="csv",
                     help="file format of the time series (default csv; netcdf needs the [io] extra, parquet "
                          "pyarrow)")
    run.set_defaults(command=_run)

    sweep = commands.add_parser("sweep", parents=parallel, help="a scenario over a grid of its parameters",
                                description="Run a sweep file (a scenario with a [grid] of \"section.key\" = "
                                            "[values]; see `python -c 'help(\"frictionsim.scenario.sweep_file\")'`): "
                                            "every case at every grid point; write sweep.csv (one row per point and "
                                            "case), sweep.png, sweep.toml and metadata.json.")
    sweep.add_argument("file", type=Path, help="sweep file (TOML)")
    sweep.set_defaults(command=_sweep)

    scenarios = commands.add_parser("scenarios", parents=common, help="the packaged example scenarios: list, copy",
                                    description="The example scenario and sweep files that come with the package.")
    actions = scenarios.add_subparsers(title="actions", metavar="ACTION")
    listing = actions.add_parser("list", parents=common, help="name and title of each packaged example")
    listing.set_defaults(command=_scenarios_list)
    copying = actions.add_parser("copy", parents=writing, help="copy a packaged example to edit and run it",
                                 description="Copy the packaged example NAME (with or without .toml) to DEST: a "
                                             "directory (default: the working directory), where it becomes "
                                             "DEST/NAME.toml, or a new file. Never overwrites unless --force.")
    copying.add_argument("name", help="the example's name (see `frictionsim scenarios list`)")
    copying.add_argument("dest", nargs="?", default=".", help="directory or new file (default .)")
    copying.set_defaults(command=_scenarios_copy)
    scenarios.set_defaults(command=_scenarios_list)

    demo = commands.add_parser("demo", parents=writing, help="papers 000 and 001: Fig. 7 cases, friction reduction, "
                                                            "Table 5 refit, torsional stick-slip",
                               description="Built-in scenarios of paper 000: Fig. 7 dry and OBM cases with Coulomb "
                                           "and Dahl friction, friction reduction against Tables 4-5, an amplitude "
                                           "sweep, and the Table 5 refit with the Fig. 11 plot. Paper 001 (into "
                                           "OUT/paper001/): the torsional rig at Fig. 7's operating point with eq 6, "
                                           "Stribeck and LuGre friction, the limit cycle of every law against the "
                                           "paper's frequency and peak speed, and a stick-slip map over w_ref and "
                                           "N2.")
    demo.add_argument("--out", type=Path, default=Path(DEFAULT_OUT), help=f"output directory (default: {DEFAULT_OUT})")
    demo.add_argument("--quick", action="store_true", help="a shorter amplitude sweep and a smaller stick-slip map")
    demo.set_defaults(command=_demo)

    fit = commands.add_parser("fit-table5", parents=writing, help="refit Table 5 from Table 4, print both, plot Fig. 11",
                              description="Least-squares refit of paper 000's Table 5 (log10 mu_df against "
                                          "log10 v_a/v_d per lubricant) from Table 4, beside the printed values.")
    fit.add_argument("--out", type=Path, default=Path(DEFAULT_OUT), help=f"output directory (default: {DEFAULT_OUT})")
    fit.set_defaults(command=_fit_table5)

    identify = commands.add_parser(
        "fit", parents=[_common(), _forcing("--overwrite")], help="identify a friction law from a measured record",
        description="Fit a friction law to a CSV record of time, relative velocity, friction force and normal force "
                    "(frictionsim.fit.identify: output-error least squares through the engine); print the fitted "
                    "parameters with standard errors and identifiability; write fit.csv (the table), "
                    "fit_record.csv (measured, model, residual), fit.png and metadata.json.")
    identify.add_argument("data", type=Path, help="the record (CSV with a header row; '#' comments)")
    identify.add_argument("--law", required=True, metavar="LAW",
                          help="the law to fit: dahl, lugre, elasto_plastic, stribeck, ... (frictionsim.fit."
                               "LAW_PARAMETERS)")
    identify.add_argument("--time", default="t", metavar="COLUMN", help="time column [s] (default t)")
    identify.add_argument("--velocity", default="relative_velocity", metavar="COLUMN",
                          help="relative velocity column [m/s] (default relative_velocity)")
    identify.add_argument("--force", default="friction_force", metavar="COLUMN",
                          help="friction force column [N] (default friction_force)")
    identify.add_argument("--normal", default="normal_force", metavar="COLUMN",
                          help="normal force column [N] (default normal_force)")
    identify.add_argument("--normal-force", type=float, metavar="N",
                          help="a constant normal force [N] instead of a column")
    identify.add_argument("--guess", type=_assignments, default={}, metavar="NAME=VALUE,...",
                          help="starting values, e.g. mu=0.25,bristle_stiffness=5e4 (default: estimated from the "
                               "record and a coarse scan)")
    identify.add_argument("--fixed", type=_assignments, default={}, metavar="NAME=VALUE,...",
                          help="parameters held at these values instead of fitted")
    identify.add_argument("--method", choices=("least_squares", "differential_evolution"), default="least_squares",
                          help="local least squares (default) or a global differential-evolution search")
    identify.add_argument("--decimate", type=_jobs, default=1, metavar="K",
                          help="fit the means of blocks of K samples (frictionsim.fit.decimate): a long record "
                               "within the fit's work limit (default 1: every sample)")
    identify.add_argument("--out", type=Path, help="output directory (default out/fit_<data file stem>)")
    identify.set_defaults(command=_fit)

    td = commands.add_parser("torque-drag", parents=writing,
                             help="soft-string torque and drag along a survey: per-node CSV, broomstick and well-path "
                                  "plots; hydraulic oscillators and their placement",
                             description="Johancsik soft-string torque and drag of a drill string along a survey "
                                         "(CSV: md, inc, azi columns, units in the header such as 'md [m]', "
                                         "'inc [deg]'): tension, torque, side force and buckling per node for "
                                         "tripping in and out and rotating off bottom (and sliding and rotary "
                                         "drilling with --wob) at each friction factor, and the broomstick plot of "
                                         "hook load while the string is run in. Writes into --out only: "
                                         "torque_drag.csv, broomstick.csv, trajectory.csv, broomstick.png, "
                                         "well_path.png, metadata.json. With --oscillator: the same broomstick with "
                                         "the tools (oscillator_broomstick.csv, .png: each tool stays at its height "
                                         "above the bit while the string is run in) and the zone of influence at "
                                         "the bit depth (oscillator_zone.csv, oscillator_summary.csv); with --place: "
                                         "the placement curve while sliding (placement.csv, placement.png).")
    td.add_argument("survey", type=Path, help="survey file (CSV)")
    td.add_argument("--string", default=DEFAULT_STRING, metavar="OD:ID:LENGTH,...",
                    help="the string's sections top to bottom, diameters and lengths in metres; one LENGTH may be "
                         "'*': what the others leave of the bit depth (default: 5\" drill pipe over 150 m of "
                         f"6 1/2\" collars, {DEFAULT_STRING})")
    td.add_argument("--mu", type=float, nargs="+", default=[0.1, 0.2, 0.3, 0.4], metavar="MU",
                    help="friction factors: the open hole's, and the casing's too unless --cased-mu is given "
                         "(default: 0.1 0.2 0.3 0.4)")
    td.add_argument("--cased-mu", type=float, metavar="MU", help="friction factor inside the casing")
    td.add_argument("--casing-shoe", type=float, default=0.0, metavar="MD",
                    help="measured depth of the casing shoe [m] (default 0: all open hole)")
    td.add_argument("--mud-density", type=float, default=1200.0, metavar="RHO", help="kg/m^3 (default 1200)")
    td.add_argument("--wob", type=float, default=0.0, metavar="N",
                    help="weight on bit [N]: adds sliding and rotary drilling (default 0: off bottom only)")
    td.add_argument("--bit-torque", type=float, default=0.0, metavar="NM", help="torque on bit [N m], rotary drilling")
    td.add_argument("--depth", type=float, metavar="MD",
                    help="bit depth [m] (default: the string's length when no section is '*', else the survey's "
                         "last depth)")
    td.add_argument("--depth-unit", choices=("m", "ft"), help="the survey's depth unit when its header gives none "
                                                              "(default m)")
    td.add_argument("--angle-unit", choices=("deg", "rad"), help="the survey's angle unit when its header gives "
                                                                 "none (default deg)")
    td.add_argument("--element-length", type=float, default=10.0, metavar="M", help="soft-string elements [m] "
                                                                                     "(default 10)")
    td.add_argument("--depth-step", type=float, default=30.0, metavar="M",
                    help="bit-depth step of the broomstick [m] (default 30)")
    td.add_argument("--oscillator", type=_oscillators, metavar="MD:FORCE:FREQ,...",
                    help="hydraulic oscillators (axial vibration tools): measured depth [m] at the full bit depth "
                         "(or 'bit-H': H metres above the bit), force amplitude [N] and frequency [Hz] of each, "
                         "e.g. bit-300:60e3:18")
    td.add_argument("--operation", default="sliding_drilling", metavar="OP",
                    help="the operation the oscillators' zone of influence is reported for (default "
                         "sliding_drilling; one of frictionsim.wells.OPERATIONS)")
    td.add_argument("--model", choices=("friction_vector", "table5"), default="friction_vector",
                    help="how the vibration reduces friction: the friction vector's cycle mean (default) or paper "
                         "000's Table 5 power law (with --lubricant)")
    td.add_argument("--lubricant", choices=("dry", "water", "wbm", "obm", "sbm"), default=None,
                    help="Table 5's row for --model table5")
    td.add_argument("--place", action="store_true",
                    help="place one tool (--oscillator's force and frequency, else 50 kN at 18 Hz) for the most weight "
                         "on bit while sliding at the hook load that puts --wob on the bit without it")
    td.add_argument("--out", type=Path, help="output directory (default out/<survey file stem>)")
    td.set_defaults(command=_torque_drag)
    return parser


# ------------------------------------------------------------------------------------------------------- commands
def _run(args) -> int:
    from .scenario import ScenarioRun, load
    from .scenario.runner import with_timeout

    scenario = load(args.scenario)
    out = _output_directory(args, args.scenario, scenario.output.directory, scenario.name)
    _check_target(out, args)
    _check_timeout(args.timeout)
    _check_format(args.format)
    cases = [with_timeout(case, args.timeout) for case in scenario.cases]
    runs = []
    log.info("%s: %d cases", args.scenario, len(cases))
    with _imap(args.jobs, len(cases)) as imap, _progress(args, len(cases), scenario.name) as bar:
        outcomes = imap(_run_case_or_error, cases)
        for index, (case, outcome) in enumerate(zip(cases, outcomes), start=1):
            if isinstance(outcome, SimulationError):
                raise CommandError(f"{args.scenario}: case[{index}] {case.name!r}: simulation stopped at t = "
                                   f"{outcome.time_reached:.9g} s of t_end = {case.solver.t_end:g} s: {outcome}", 1)
            if isinstance(outcome, InvalidParameterError):
                raise CommandError(f"{args.scenario}: case[{index}] {case.name!r}: {outcome}", 2)
            _check_budget(args.scenario, index, case, outcome)
            log.info("case[%d] %r: %.3g s", index, case.name, outcome.wall_time)
            runs.append(outcome)
            bar.update()
    result = ScenarioRun(scenario, runs)
    summary = result.summary()
    print(f"{args.scenario}: {scenario.title}" if scenario.title else str(args.scenario))
    print(_table(summary, result.analysis.summary_columns(summary)))
    print(result.analysis.summary_note)

    # ScenarioRun.write writes metadata.json itself (rigs, solver options and counters per case)
    written = _write(out, lambda directory: result.write(directory, format=args.format, command=args.command_line),
                     args)
    print(f"wrote {out}: {', '.join(str(p) for p in written)}")
    # a stick-slip map's points that failed or ran out of their timeout are in its CSV: the command fails
    failures, points = [], 0
    for run in runs:
        if getattr(run, "map", None) is not None:
            points += len(run.map.sweep.values)
            failures += [(i, run.case.name, why) for i, why in run.case.kind.analysis.map_failures(run)]
    return _report_failures(args.scenario, failures, points, "stick-slip map point")


def _check_budget(file: Path, index: int, case, run) -> None:
    """A case that ran past its timeout, or ended short of t_end, is a failure (exit 1) like one the engine
    stopped (:func:`frictionsim.scenario.runner.budget_failure`)."""
    from .scenario.runner import budget_failure

    reason = budget_failure(case, run)
    if reason is not None:
        hint = "; raise --timeout (or the file's solver.timeout)" if reason.startswith("wall-clock") else ""
        raise CommandError(f"{file}: case[{index}] {case.name!r}: {reason}{hint}", 1)


def _si_axis(sweep, key: str) -> List[Any]:
    """The SI values of a grid key, in the file's order."""
    si_of = {point[key]: si_point[key] for point, si_point in zip(sweep.points, sweep.si_points)}
    return [si_of[value] for value in sweep.axes[key]]


def _run_case_or_error(case):
    """run_case in a worker: the errors a case can end with come back as values, in order with the others."""
    from .scenario import run_case

    try:
        return run_case(case)
    except (SimulationError, InvalidParameterError) as error:
        return error


def _check_format(format: str) -> None:
    """--format's optional packages, checked before anything runs (ScenarioRun.write checks them again)."""
    from . import io

    try:
        if format == "netcdf":
            io.require_xarray()
            io.netcdf_engine()
        elif format == "parquet":
            io.parquet_engine()
    except ImportError as error:
        raise CommandError(f"--format {format}: {error}", 2) from None


def _table(frame, columns) -> str:
    """The ``(column, header, format)`` columns of ``frame`` as text; NaN prints as "-"."""
    shown = frame[[column for column, _, _ in columns]].set_axis([header for _, header, _ in columns], axis=1)
    return shown.to_string(index=False, na_rep="-", formatters=[lambda value, spec=spec: format(value, spec)
                                                                for _, _, spec in columns])


def _sweep(args) -> int:
    from .scenario import sweep_file

    sweep = sweep_file.load(args.file)
    out = _output_directory(args, args.file, sweep.output.directory, sweep.name, "sweep file")
    _check_target(out, args)
    _check_timeout(args.timeout)
    count = len(sweep.points)
    log.info("%s: %d points x %d cases", args.file, count, len(sweep.cases))
    with _imap(args.jobs, count) as imap, _progress(args, count, sweep.name, unit="pt") as bar:
        try:  # a case that fails at a point (its timeout ran out, ...) is recorded as such; the rest run
            result = sweep_file.run(sweep, imap=imap, on_point=lambda index: bar.update(), timeout=args.timeout)
        except InvalidParameterError as error:
            raise CommandError(f"{args.file}: {error}", 2) from None
    frame = result.frame()
    print(f"{args.file}: {sweep.title}" if sweep.title else str(args.file))
    shown = list(sweep.axes) + ["case"] + ([result.value] if result.value else [])
    print(frame[shown].to_string(index=False, max_rows=60, float_format=lambda v: f"{v:.6g}"))
    first = sweep.scenarios[0].cases[0]

    def write(directory: Path) -> List[Path]:
        return result.write(directory) + _metadata(
            args, directory, rigs={f"{case.name} at point 0": case.build() for case in sweep.scenarios[0].cases},
            solver_options=dataclasses.asdict(first.solver),
            extra={"sweep": {"file": str(args.file), "grid": {k: list(v) for k, v in sweep.axes.items()},
                             "grid_si": {k: {"unit": sweep.si_units[k], "values": _si_axis(sweep, k)}
                                         for k in sweep.given_with_units},
                             "cases": list(sweep.cases), "points": count, "jobs": args.jobs}})

    written = _write(out, write, args)
    print(f"wrote {out}: {', '.join(str(p) for p in written)}")
    return _report_failures(args.file, result.failures, count * len(sweep.cases), "point")


def _report_failures(file: Path, failures, total: int, what: str) -> int:
    """Exit status 1 with one line per failed point on stderr when any failed (the outputs are written all the
    same: the failed rows say why), else 0."""
    for index, case, reason in failures:
        print(f"error: {file}: {what} {index} case {case!r} failed: {reason}", file=sys.stderr)
    if failures:
        print(f"error: {file}: {len(failures)} of {total} {what}s failed (their rows hold the reason)",
              file=sys.stderr)
    return 1 if failures else 0


def _check_timeout(timeout: Optional[float]) -> None:
    if timeout is not None and not (timeout > 0 and math.isfinite(timeout)):
        raise CommandError(f"--timeout must be a positive number of seconds (got {timeout:g})", 2)


# ----------------------------------------------------------------------------------------------- scenarios
def _packaged():
    """name -> the packaged example files (python/frictionsim/scenarios/*.toml)."""
    folder = resources.files("frictionsim").joinpath("scenarios")
    return {entry.name[:-5]: entry for entry in sorted(folder.iterdir(), key=lambda e: e.name)
            if entry.name.endswith(".toml")}


def _scenarios_list(args) -> int:
    from .scenario.parser import ScenarioError, loads_toml

    for name, entry in _packaged().items():
        try:
            data = loads_toml(entry.read_text(encoding="utf-8"), source=entry.name)
        except ScenarioError:  # pragma: no cover - package data is tested
            data = {}
        kind = "sweep" if "grid" in data else "scenario"
        print(f"{name:34s} {kind:8s} {data.get('title', '')}")
    print("\nfrictionsim scenarios copy NAME [DEST]   copies one here (or to DEST) to edit and run")
    return 0


def _scenarios_copy(args) -> int:
    examples = _packaged()
    name = args.name[:-5] if args.name.endswith(".toml") else args.name
    if name not in examples:
        raise CommandError(f"scenarios copy: no packaged example {args.name!r} (examples: {', '.join(examples)})", 2)
    dest = Path(args.dest)
    if args.dest.endswith(("/", os.sep)) and not dest.is_dir():
        raise CommandError(f"scenarios copy: {args.dest} is not a directory", 2)
    target = dest / f"{name}.toml" if dest.is_dir() else dest
    if not target.parent.is_dir():
        raise CommandError(f"scenarios copy: {target.parent} is not a directory", 2)
    data = examples[name].read_bytes()
    refused = f"scenarios copy: {target} exists; not overwritten: pass --force to replace it, or give another DEST"
    if os.path.lexists(target) and not args.overwrite:  # checked again, atomically, when the copy is linked in
        raise CommandError(refused, 1)
    try:
        # written whole beside it, then linked in only if the name is still free (with --force renamed onto it:
        # a symbolic link of that name is replaced, never followed out of DEST); never a truncated copy
        with atomic_path(target, replace=args.overwrite) as temporary:
            temporary.write_bytes(data)
    except FileExistsError:
        raise CommandError(refused, 1) from None
    except OSError as error:
        raise CommandError(f"scenarios copy: cannot write {target} ({error.strerror or error})", 1) from None
    kind = "sweep" if b"[grid]" in data else "run"
    print(f"wrote {target}; run it with: frictionsim {kind} {shlex.quote(str(target))}")
    return 0


# ------------------------------------------------------------------------------------------------ demo, fits
def _demo(args) -> int:
    from . import demo

    _check_target(args.out, args)
    with _progress(args, len(demo.STAGES), "demo", unit="part") as bar:
        result = demo.compute(quick=args.quick, progress=lambda stage: (bar.set_postfix_str(stage), bar.update()))
    print(result.report())
    written = _write(args.out, lambda directory: result.write(directory) + _metadata(
        args, directory, extra={"quick": args.quick, "elapsed_s": result.elapsed}), args)
    print(f"\nwrote {len(written)} files into {args.out}/: {', '.join(str(p) for p in written)}")
    return 0


def _fit_table5(args) -> int:
    from . import demo

    _check_target(args.out, args)
    refit = demo.table5_refit()
    print(demo.table5_report(refit))

    def write(directory: Path) -> List[Path]:
        path = directory / "table5_refit.csv"
        write_csv(refit, path)
        return [path, demo.write_fig11(directory)] + _metadata(args, directory, extra={"data": "paper 000 Table 4"})

    written = _write(args.out, write, args)
    print(f"wrote {args.out}: {', '.join(str(p) for p in written)}")
    return 0


def _fit(args) -> int:
    import numpy as np

    from . import plots
    from .fit import LAW_PARAMETERS, identify

    out = args.out if args.out is not None else Path("out") / f"fit_{folder_name(args.data.stem, 'data')}"
    _check_target(out, args)
    laws = sorted(LAW_PARAMETERS)
    if args.law.lower().replace("-", "_") not in {k.lower() for k in laws}:
        raise CommandError(f"--law must be one of {', '.join(laws)} (got {args.law!r})", 2)
    if args.normal_force is not None and not (math.isfinite(args.normal_force) and args.normal_force > 0):
        raise CommandError(f"--normal-force must be positive and finite (got {args.normal_force})", 2)
    columns = {"time": args.time, "velocity": args.velocity, "force": args.force}
    if args.normal_force is None:
        columns["normal"] = args.normal
    record = _read_record(args.data, columns)
    data_file = _file_record(args.data)  # what was read, before the fit's minutes in which it could change
    if args.decimate > 1:
        from .fit import decimate

        roles = list(record)
        record = dict(zip(roles, decimate(*(record[role] for role in roles), factor=args.decimate)))
    normal = record["normal"] if args.normal_force is None else args.normal_force
    try:
        result = identify(args.law, record["time"], record["velocity"], record["force"], normal, method=args.method,
                          initial_guess=args.guess or None, fixed=args.fixed or None)
    except InvalidParameterError as error:
        from .fit.solver import FitWorkError

        hint = f"; here: --decimate {args.decimate * error.factor}" if isinstance(error, FitWorkError) else ""
        raise CommandError(f"{args.data}: {error}{hint}", 2) from None
    print(f"{args.data}: {len(record['time'])} samples over {record['time'][-1] - record['time'][0]:g} s")
    print(result.summary())
    table = result.to_pandas()

    def write(directory: Path) -> List[Path]:
        import pandas as pd

        paths = [directory / "fit.csv", directory / "fit_record.csv"]
        write_csv(table, paths[0], index=True)
        write_csv(pd.DataFrame({"t": result.t, "relative_velocity": np.interp(result.t, record["time"],
                                                                             record["velocity"]),
                                "measured": result.measured, "model": result.model, "residual": result.residuals}),
                  paths[1])
        velocity = np.interp(result.t, record["time"], record["velocity"])
        paths.append(plots.save(plots.identification_figure(result, velocity, title=args.data.name),
                                directory / "fit.png"))
        return paths + _metadata(args, directory, rigs=[result.rig] if result.rig is not None else [],
                                 stats={"n_evaluations": result.n_evaluations, "n_failed": result.n_failed,
                                        "elapsed_s": result.elapsed},
                                 extra={"data": str(args.data), "data_file": data_file,
                                        "law": repr(result.law), "method": result.method,
                                        "success": result.success, "message": result.message,
                                        "rms_residual_N": result.rms_residual, "r_squared": result.r_squared})

    written = _write(out, write, args)
    print(f"wrote {out}: {', '.join(str(p) for p in written)}")
    return 0 if result.success else 1


def _file_record(path: Path) -> Dict[str, Any]:
    """What identifies an input file's content: its sha256 and size (a path alone names whatever is there later)."""
    import hashlib

    digest = hashlib.sha256()
    size = 0
    with open(path, "rb") as file:
        for block in iter(lambda: file.read(1 << 20), b""):
            digest.update(block)
            size += len(block)
    return {"path": str(path), "sha256": digest.hexdigest(), "size_bytes": size}


def _assignments(spec: str) -> Dict[str, float]:
    """--guess / --fixed: NAME=VALUE,... as a dict of floats."""
    out = {}
    for part in (p.strip() for p in spec.split(",") if p.strip()):
        name, equals, value = part.partition("=")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{part!r}: expected NAME=VALUE with a number") from None
        if not equals or not name.strip():
            raise argparse.ArgumentTypeError(f"{part!r}: expected NAME=VALUE")
    return out


def _read_record(path: Path, columns: Dict[str, str]) -> Dict[str, Any]:
    """The named columns of a CSV record as float arrays; an error names the file, the column and the line."""
    import numpy as np
    import pandas as pd

    try:
        frame = pd.read_csv(path, comment="#", skipinitialspace=True)
    except FileNotFoundError:
        raise CommandError(f"{path}: no such file", 2) from None
    except (OSError, UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as error:
        raise CommandError(f"{path}: cannot read the record as CSV ({error})", 2) from None
    frame.columns = [str(c).strip() for c in frame.columns]
    options = {"time": "--time", "velocity": "--velocity", "force": "--force", "normal": "--normal"}
    for role, name in columns.items():
        if name not in frame.columns:
            hint = " or give --normal-force" if role == "normal" else ""
            raise CommandError(f"{path}: no column {name!r} (columns: {', '.join(frame.columns)}); name it with "
                               f"{options[role]}{hint}", 2)
    out = {}
    for role, name in columns.items():
        values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            row = int(bad[0])
            raise CommandError(f"{path}: column {name!r}, data row {row + 1}: must be a finite number (got "
                               f"{str(frame[name].iloc[row])!r})", 2)
        out[role] = values
    if len(frame) < 3:
        raise CommandError(f"{path}: needs at least 3 samples (got {len(frame)})", 2)
    return out


#: torque-drag's default string: 5" drill pipe (OD 127 mm, ID 108.6 mm) over 150 m of 6 1/2" x 2 13/16" collars
DEFAULT_STRING = "0.127:0.1086:*,0.1651:0.0714:150"


def _string_sections(spec: str, depth: Optional[float], survey_depth: float):
    """--string -> (PipeSections top to bottom, bit depth): OD:ID:LENGTH per section, one LENGTH may be '*'."""
    from . import PipeSection

    parts = [part.strip() for part in spec.split(",") if part.strip()]
    if not parts:
        raise CommandError("--string: no section given (OD:ID:LENGTH,...)", 2)
    parsed = []
    for index, part in enumerate(parts):
        fields = part.split(":")
        if len(fields) != 3:
            raise CommandError(f"--string: section {index} {part!r}: expected OD:ID:LENGTH (metres)", 2)
        try:
            od, inner = float(fields[0]), float(fields[1])
            length = None if fields[2].strip() == "*" else float(fields[2])
        except ValueError:
            raise CommandError(f"--string: section {index} {part!r}: OD, ID and LENGTH must be numbers "
                               f"(LENGTH may be '*')", 2) from None
        parsed.append((od, inner, length))
    rest = [index for index, (_, _, length) in enumerate(parsed) if length is None]
    if len(rest) > 1:
        raise CommandError("--string: only one section's LENGTH may be '*'", 2)
    fixed = sum(length for _, _, length in parsed if length is not None)
    if depth is None:
        depth = survey_depth if rest else fixed
    if rest:
        if not fixed < depth:
            raise CommandError(f"--string: the sections of given length ({fixed:g} m) leave nothing of the bit depth "
                               f"({depth:g} m) for the '*' section", 2)
        od, inner, _ = parsed[rest[0]]
        parsed[rest[0]] = (od, inner, depth - fixed)
    elif not math.isclose(fixed, depth, rel_tol=1e-12):
        raise CommandError(f"--string: the sections add up to {fixed:g} m, the bit depth is {depth:g} m (give one "
                           f"LENGTH as '*' to fill it)", 2)
    sections = []
    for index, (od, inner, length) in enumerate(parsed):
        try:
            sections.append(PipeSection(outer_diameter=od, inner_diameter=inner, length=length))
        except InvalidParameterError as error:
            raise CommandError(f"--string: section {index}: {error}", 2) from None
    return sections, depth


# ----------------------------------------------------------------------------------------------- torque-drag
def _oscillators(spec: str) -> List[Any]:
    """--oscillator MD:FORCE:FREQ[,...]; MD may be 'bit-H' (H metres above the bit): wells.PlannedOscillator each."""
    from .wells import PlannedOscillator

    tools = []
    for index, part in enumerate(p.strip() for p in spec.split(",")):
        fields = part.split(":")
        if len(fields) != 3:
            raise argparse.ArgumentTypeError(f"tool {index} {part!r}: expected MD:FORCE:FREQ (m or bit-H, N, Hz)")
        where = fields[0].strip()
        try:
            above = float(where[4:]) if where.startswith("bit-") else None
            depth = None if above is not None else float(where)
            force, frequency = float(fields[1]), float(fields[2])
        except ValueError:
            raise argparse.ArgumentTypeError(f"tool {index} {part!r}: MD (or bit-H), FORCE and FREQ must be "
                                             "numbers") from None
        for name, value, ok in (("MD", depth, depth is None or (math.isfinite(depth) and depth >= 0)),
                                ("H", above, above is None or (math.isfinite(above) and above >= 0)),
                                ("FORCE", force, math.isfinite(force) and force >= 0),
                                ("FREQ", frequency, math.isfinite(frequency) and frequency > 0)):
            if not ok:
                rule = "positive" if name == "FREQ" else "non-negative"
                raise argparse.ArgumentTypeError(f"tool {index} {part!r}: {name} must be {rule} and finite "
                                                 f"(got {value:g})")
        tools.append(PlannedOscillator(depth, above, force, frequency))
    return tools


def _torque_drag(args) -> int:
    import pandas as pd

    from . import DrillString
    from . import plots, wells

    out = args.out if args.out is not None else Path("out") / folder_name(args.survey.stem, "survey")
    _check_target(out, args)
    for name in ("mu", "cased_mu", "casing_shoe", "mud_density", "wob", "bit_torque", "depth", "element_length",
                 "depth_step"):
        values = getattr(args, name)
        for value in values if isinstance(values, list) else [values]:
            if value is not None and not math.isfinite(value):
                raise CommandError(f"--{name.replace('_', '-')} must be finite (got {value})", 2)
    if args.operation not in wells.OPERATIONS:
        raise CommandError(f"--operation must be one of {', '.join(wells.OPERATIONS)} (got {args.operation!r})", 2)
    if args.place and not args.wob > 0.0:
        raise CommandError("--place needs --wob > 0: the tool is placed for the most weight on bit while sliding at "
                           "the hook load that puts --wob on the bit without it", 2)
    if args.lubricant is not None and args.model != "table5":
        raise CommandError("--lubricant is Table 5's row: give it with --model table5", 2)
    try:
        survey = wells.read_survey(args.survey, depth_unit=args.depth_unit, angle_unit=args.angle_unit)
    except InvalidParameterError as error:
        raise CommandError(str(error), 2) from None
    sections, depth = _string_sections(args.string, args.depth, float(survey.measured_depth[-1]))
    tools = args.oscillator or []
    for index, tool in enumerate(tools):
        if not 0.0 <= tool.height(depth) <= depth:
            raise CommandError(f"--oscillator: tool {index} at "
                               f"{'bit-%g' % tool.above_bit if tool.above_bit is not None else '%g m' % tool.depth} "
                               f"is outside the string (0 to {depth:g} m MD)", 2)
    conditions = dict(mud_density=args.mud_density, casing_shoe_depth=args.casing_shoe,
                      weight_on_bit=args.wob, bit_torque=args.bit_torque)
    estimate = {"model": args.model} | ({"lubricant": args.lubricant} if args.lubricant else {})
    operations = list(wells.BROOMSTICK_OPERATIONS)
    if args.wob > 0.0:
        operations += ["sliding_drilling", "rotary_drilling"]
    vibrated = zone = zone_summary = placements = None
    study = dict(conditions=conditions, estimate=estimate, cased_friction=args.cased_mu)
    try:
        string = DrillString(sections)
        model = wells.soft_string(survey, string, element_length=args.element_length)
        nodes, summary_frame = wells.operations_table(model, args.mu, operations, conditions, args.cased_mu)
        broom_conditions = dict(conditions)
        if args.cased_mu is not None:
            broom_conditions["cased_hole_friction"] = args.cased_mu
        chart = wells.broomstick(survey, string, args.mu, depth_step=args.depth_step,
                                 element_length=args.element_length, **broom_conditions)
        if tools:
            vibrated = wells.oscillator_broomstick(survey, string, chart, tools, depth, args.mu,
                                                   element_length=args.element_length, **study)
            zone, zone_summary = wells.zone_of_influence(model, tools, depth, args.operation, args.mu, **study)
        if args.place:
            placements = wells.sliding_placements(model, tools, args.mu, **study)
    except InvalidParameterError as error:
        raise CommandError(f"{args.survey}: {error}", 2) from None
    print(f"{args.survey}: {len(survey)} stations to MD {survey.measured_depth[-1]:g} m; bit at {depth:g} m, "
          f"{model.elements} elements of {model.element_length:.4g} m")
    print(summary_frame.to_string(index=False, float_format=lambda v: f"{v:.6g}"))
    if zone_summary is not None:
        print(f"\nhydraulic oscillators, {args.operation} with the bit at {depth:g} m ({args.model}): "
              f"zone of influence and changes at the surface")
        print(zone_summary.to_string(index=False, float_format=lambda v: f"{v:.6g}"))
    if placements is not None:
        print(f"\nplacement of one tool while sliding at the hook load that puts {args.wob / 1e3:g} kN on the bit "
              "without it")
        print(pd.DataFrame([{"friction_factor": mu, "best_depth_m": p.depths[0], "weight_on_bit_kN":
                             p.weight_on_bit / 1e3, "without_kN": p.weight_on_bit_without / 1e3,
                             "gain_kN": p.gain / 1e3} for mu, p in placements.items()]).to_string(
            index=False, float_format=lambda v: f"{v:.6g}"))

    def write(directory: Path) -> List[Path]:
        paths = [directory / "torque_drag.csv", directory / "broomstick.csv", directory / "trajectory.csv"]
        write_csv(nodes, paths[0])
        write_csv(chart.frame, paths[1])
        write_csv(wells.trajectory(survey), paths[2])
        paths.append(plots.save(plots.broomstick_figure(chart, title=str(args.survey.name)),
                                directory / "broomstick.png"))
        paths.append(plots.save(plots.well_path_figure(survey, title=str(args.survey.name)),
                                directory / "well_path.png"))
        if vibrated is not None:
            for name, frame in (("oscillator_broomstick.csv", vibrated), ("oscillator_zone.csv", zone),
                                ("oscillator_summary.csv", zone_summary)):
                paths.append(write_csv(frame, directory / name))
            paths.append(plots.save(plots.oscillator_broomstick_figure(vibrated, zone, title=args.survey.name),
                                    directory / "oscillator_broomstick.png"))
        if placements is not None:
            rows = [pd.DataFrame({"friction_factor": mu, "tool_depth": p.scan_depths,
                                  "weight_on_bit": p.scan_weight_on_bit,
                                  "weight_on_bit_without": p.weight_on_bit_without,
                                  "hook_load": p.hook_load, "best_depth": p.depths[0],
                                  "best_weight_on_bit": p.weight_on_bit}) for mu, p in placements.items()]
            paths.append(write_csv(pd.concat(rows, ignore_index=True), directory / "placement.csv"))
            paths.append(plots.save(plots.placements_figure(placements, title=args.survey.name),
                                    directory / "placement.png"))
        return paths + _metadata(args, directory, extra={
            "survey": str(args.survey), "string": args.string, "bit_depth_m": depth, "friction_factors": args.mu,
            "conditions": conditions, "oscillators": [dataclasses.asdict(t) for t in tools], "estimate": estimate})

    written = _write(out, write, args)
    print(f"wrote {out}: {', '.join(str(p) for p in written)}")
    return 0


def _output_directory(args, file: Path, directory: Optional[str], stem: str, what: str = "scenario") -> Path:
    """--out, else the file's output.directory confined to the file's folder, else out/<stem>."""
    if args.out is not None:
        return args.out
    if directory is None:
        return Path("out") / folder_name(stem, "sweep" if what == "sweep file" else "scenario")
    base = Path(file).absolute().parent
    given = Path(directory)
    target = base / given
    if args.allow_outside:
        return target
    where = f"{file}: output.directory"
    if given.is_absolute():
        raise CommandError(f"{where}: must be relative to the {what}'s folder (got the absolute path {given}); "
                           f"pass --out or --allow-outside to write elsewhere", 2)
    # resolve() follows '..' and symbolic links: what stays inside the folder after both is confined
    try:
        inside = target.resolve().is_relative_to(base.resolve())
    except OSError as error:
        raise CommandError(f"{where}: cannot resolve {given} ({error.strerror or error})", 2) from None
    if not inside:
        raise CommandError(f"{where}: {given} leads out of the {what}'s folder {base} (through '..' or a symbolic "
                           f"link); pass --out or --allow-outside to write elsewhere", 2)
    return target


def folder_name(stem: str, fallback: str) -> str:
    """A file's stem as one folder name below ``out/``: path separators and NULs become ``_``, and a stem that
    is empty, blank or only dots (``...csv``'s stem is ``..``, which would make ``out/..`` the working directory)
    is ``fallback``."""
    name = stem
    for separator in {"/", "\\", "\0", os.sep, os.altsep or "/"}:
        name = name.replace(separator, "_")
    return fallback if not name.strip() or not name.strip(". \t") else name


# ----------------------------------------------------------------------------------------------- atomic outputs
def _check_target(out: Path, args) -> None:
    """Before anything runs: ``out`` is a directory or nothing yet, and, without --force, holds no earlier
    command's outputs (every command writes metadata.json: there, it would be replaced; any other output that
    exists is found when the outputs are moved in, and refused all the same)."""
    try:
        if out.exists() and not out.is_dir():
            raise CommandError(f"{out}: output path exists and is not a directory", 2)
        if not getattr(args, "overwrite", False) and os.path.lexists(out / "metadata.json"):
            raise CommandError(_exists([out / "metadata.json"], args.force_option), 1)
    except OSError as error:  # e.g. a component longer than the file system allows (ENAMETOOLONG)
        raise CommandError(f"{out}: unusable output path ({error.strerror or error})", 2) from None


def _write(out: Path, writer, args=None) -> List[Path]:
    """Run ``writer(stage_directory)`` and move its files into ``out``; returns the paths relative to ``out``. An
    output that exists in ``out`` is replaced only with ``--force`` (``args.overwrite``)."""
    try:
        with staged_directory(out, overwrite=getattr(args, "overwrite", False)) as stage:
            return [Path(p).relative_to(stage) for p in writer(stage)]
    except OutputExistsError as error:
        raise CommandError(_exists(error.paths, getattr(args, "force_option", "--force")), 1) from None
    except OSError as error:
        raise CommandError(f"{out}: cannot write the outputs ({error})", 1) from None


def _exists(paths: Sequence[Path], option: str = "--force") -> str:
    more = f" (and {len(paths) - 1} more of this command's outputs)" if len(paths) > 1 else ""
    return (f"{paths[0]} exists{more}; not overwritten: pass {option} to replace, or --out to write into another "
            f"directory")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
