"""The ``frictionsim`` command line.

    frictionsim run SCENARIO.toml [--out DIR]   simulate a scenario file (see frictionsim.scenario)
    frictionsim demo [--out DIR] [--quick]      paper 000's Fig. 7 cases, friction reduction, Table 5 refit;
                                                paper 001's torsional rig: Fig. 7, law comparison, stick-slip map
    frictionsim fit-table5 [--out DIR]          refit Table 5 from Table 4 and plot Fig. 11
    frictionsim torque-drag SURVEY.csv [--string OD:ID:LENGTH,...] [--mu 0.2 0.3] [--out DIR]
                                                soft-string torque and drag along a survey: per-node CSV,
                                                broomstick and well-path plots (see frictionsim.wells)

Outputs appear all at once: everything is simulated first, then written into a temporary directory next to the
target and moved into place (files already in the target that the command does not write are left alone).
Ctrl-C or SIGTERM removes that temporary directory: nothing half-written is left behind.

Where ``run`` writes: ``--out DIR`` when given (the caller's choice); else the scenario's ``output.directory``,
relative to the scenario file's folder and confined to it: an absolute path, a ``..`` or a symbolic link that
leads out of it is refused unless ``--allow-outside`` is given (a scenario file from elsewhere must not write
anywhere it likes); else ``out/<file stem>`` in the working directory.

Exit status: 0 on success, 2 for a bad scenario or command line (``error: <file>: <key>: <rule>`` on stderr),
1 when a simulation stops early (with the time reached) or the outputs cannot be written, 130 on Ctrl-C, 143 on
SIGTERM. ``torque-drag`` reports a bad survey with its file, line, station and field (exit 2).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import shutil
import sys
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, List, Optional, Sequence

from . import __version__
from .errors import InvalidParameterError, SimulationError

__all__ = ["main", "staged_directory"]

#: default output directory of ``demo`` and ``fit-table5`` (scripts/demo sets FRICTIONSIM_OUT_DIR)
DEFAULT_OUT = os.environ.get("FRICTIONSIM_OUT_DIR", "out")


class CommandError(Exception):
    """A failure reported as ``error: <message>`` with exit ``status``."""

    def __init__(self, message: str, status: int) -> None:
        super().__init__(message)
        self.status = status


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``frictionsim`` console script; returns the exit status."""
    from .scenario import ScenarioError

    parser = _parser()
    args = parser.parse_args(argv)
    if not getattr(args, "command", None):
        parser.print_help(sys.stderr)
        return 2
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


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="frictionsim",
        description="Friction-driven dynamics in drilling: simulate paper 000's axial vibrating-sliding rig, "
                    "kinematic friction rigs and paper 001's torsional drill-string rig with Coulomb, Stribeck, "
                    "Dahl, LuGre, elasto-plastic and hysteretic (eq 6) friction.",
        epilog="Scenario files are TOML; see examples/scenarios/ and `python -c 'help(\"frictionsim.scenario\")'`.")
    parser.add_argument("--version", action="version", version=f"frictionsim {__version__}")
    commands = parser.add_subparsers(title="commands", metavar="COMMAND")

    run = commands.add_parser("run", help="simulate a scenario file, write CSV tables and PNG plots",
                              description="Simulate every case of a TOML scenario file; write per-case time "
                                          "series, summary.csv and PNG plots; print the summary.")
    run.add_argument("scenario", type=Path, help="scenario file (TOML)")
    run.add_argument("--out", type=Path, help="output directory (default: the file's output.directory, relative to "
                                              "the file's folder and confined to it, else out/<file stem>)")
    run.add_argument("--allow-outside", action="store_true",
                     help="let the file's output.directory be absolute or lead out of the file's folder")
    run.add_argument("--timeout", type=float, metavar="SECONDS",
                     help="wall-clock budget of each simulation (overrides the file's solver.timeout)")
    run.set_defaults(command=_run)

    demo = commands.add_parser("demo", help="papers 000 and 001: Fig. 7 cases, friction reduction, Table 5 "
                                             "refit, torsional stick-slip",
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

    fit = commands.add_parser("fit-table5", help="refit Table 5 from Table 4, print both, plot Fig. 11",
                              description="Least-squares refit of paper 000's Table 5 (log10 mu_df against "
                                          "log10 v_a/v_d per lubricant) from Table 4, beside the printed values.")
    fit.add_argument("--out", type=Path, default=Path(DEFAULT_OUT), help=f"output directory (default: {DEFAULT_OUT})")
    fit.set_defaults(command=_fit_table5)

    td = commands.add_parser("torque-drag", help="soft-string torque and drag along a survey: per-node CSV, "
                                                 "broomstick and well-path plots",
                             description="Johancsik soft-string torque and drag of a drill string along a survey "
                                         "(CSV: md, inc, azi columns, units in the header such as 'md [m]', "
                                         "'inc [deg]'): tension, torque, side force and buckling per node for "
                                         "tripping in and out and rotating off bottom (and sliding and rotary "
                                         "drilling with --wob) at each friction factor, and the broomstick plot of "
                                         "hook load while the string is run in. Writes into --out only: "
                                         "torque_drag.csv, broomstick.csv, trajectory.csv, broomstick.png, "
                                         "well_path.png.")
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
    td.add_argument("--out", type=Path, help="output directory (default out/<survey file stem>)")
    td.set_defaults(command=_torque_drag)
    return parser


# ------------------------------------------------------------------------------------------------------- commands
def _run(args) -> int:
    from .scenario import ScenarioRun, load, run_case

    scenario = load(args.scenario)
    out = _output_directory(args, scenario)
    _check_target(out)
    if args.timeout is not None and not (args.timeout > 0 and math.isfinite(args.timeout)):
        raise CommandError(f"--timeout must be a positive number of seconds (got {args.timeout:g})", 2)
    runs = []
    for index, case in enumerate(scenario.cases, start=1):
        if args.timeout is not None:
            case = dataclasses.replace(case, solver=dataclasses.replace(case.solver, timeout=args.timeout))
        try:
            runs.append(run_case(case))
        except SimulationError as error:
            raise CommandError(f"{args.scenario}: case[{index}] {case.name!r}: simulation stopped at t = "
                               f"{error.time_reached:.9g} s of t_end = {case.solver.t_end:g} s: {error}", 1) from None
        except InvalidParameterError as error:
            raise CommandError(f"{args.scenario}: case[{index}] {case.name!r}: {error}", 2) from None
    result = ScenarioRun(scenario, runs)
    summary = result.summary()
    print(f"{args.scenario}: {scenario.title}" if scenario.title else str(args.scenario))
    print(_table(summary, result.analysis.summary_columns(summary)))
    print(result.analysis.summary_note)
    written = _write(out, result.write)
    print(f"wrote {out}: {', '.join(str(p) for p in written)}")
    return 0


def _table(frame, columns) -> str:
    """The ``(column, header, format)`` columns of ``frame`` as text; NaN prints as "-"."""
    shown = frame[[column for column, _, _ in columns]].set_axis([header for _, header, _ in columns], axis=1)
    return shown.to_string(index=False, na_rep="-", formatters=[lambda value, spec=spec: format(value, spec)
                                                                for _, _, spec in columns])


def _demo(args) -> int:
    from . import demo

    _check_target(args.out)
    result = demo.compute(quick=args.quick)
    print(result.report())
    written = _write(args.out, result.write)
    print(f"\nwrote {len(written)} files into {args.out}/: {', '.join(str(p) for p in written)}")
    return 0


def _fit_table5(args) -> int:
    from . import demo

    _check_target(args.out)
    refit = demo.table5_refit()
    print(demo.table5_report(refit))

    def write(directory: Path) -> List[Path]:
        path = directory / "table5_refit.csv"
        refit.to_csv(path, index=False, float_format="%.10g")
        return [path, demo.write_fig11(directory)]

    written = _write(args.out, write)
    print(f"wrote {args.out}: {', '.join(str(p) for p in written)}")
    return 0


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


def _torque_drag(args) -> int:
    import pandas as pd

    from . import DrillString
    from . import plots, wells

    out = args.out if args.out is not None else Path("out") / args.survey.stem
    _check_target(out)
    for name in ("mu", "cased_mu", "casing_shoe", "mud_density", "wob", "bit_torque", "depth", "element_length",
                 "depth_step"):
        values = getattr(args, name)
        for value in values if isinstance(values, list) else [values]:
            if value is not None and not math.isfinite(value):
                raise CommandError(f"--{name.replace('_', '-')} must be finite (got {value})", 2)
    try:
        survey = wells.read_survey(args.survey, depth_unit=args.depth_unit, angle_unit=args.angle_unit)
    except InvalidParameterError as error:
        raise CommandError(str(error), 2) from None
    sections, depth = _string_sections(args.string, args.depth, float(survey.measured_depth[-1]))
    conditions = dict(mud_density=args.mud_density, casing_shoe_depth=args.casing_shoe,
                      weight_on_bit=args.wob, bit_torque=args.bit_torque)
    operations = list(wells.BROOMSTICK_OPERATIONS)
    if args.wob > 0.0:
        operations += ["sliding_drilling", "rotary_drilling"]
    tables, summary = [], []
    try:
        string = DrillString(sections)
        model = wells.soft_string(survey, string, element_length=args.element_length)
        for mu in args.mu:
            friction = dict(open_hole_friction=mu, cased_hole_friction=mu if args.cased_mu is None else args.cased_mu)
            for op in operations:
                result = model.run(op, **conditions, **friction)
                table = wells.node_table(result)
                table.insert(0, "node", range(len(table)))
                table.insert(0, "friction_factor", mu)
                table.insert(0, "operation", op)
                tables.append(table)
                summary.append({"operation": op, "friction_factor": mu, "hook_load_kN": result.hook_load / 1e3,
                                "surface_torque_kNm": result.surface_torque / 1e3,
                                "sinusoidally_buckled_nodes": int(result.sinusoidally_buckled.sum()),
                                "helically_buckled_nodes": int(result.helically_buckled.sum())})
        broom_conditions = dict(conditions)
        if args.cased_mu is not None:
            broom_conditions["cased_hole_friction"] = args.cased_mu
        chart = wells.broomstick(survey, string, args.mu, depth_step=args.depth_step,
                                 element_length=args.element_length, **broom_conditions)
    except InvalidParameterError as error:
        raise CommandError(f"{args.survey}: {error}", 2) from None
    summary_frame = pd.DataFrame(summary)
    print(f"{args.survey}: {len(survey)} stations to MD {survey.measured_depth[-1]:g} m; bit at {depth:g} m, "
          f"{model.elements} elements of {model.element_length:.4g} m")
    print(summary_frame.to_string(index=False, float_format=lambda v: f"{v:.6g}"))

    def write(directory: Path) -> List[Path]:
        paths = [directory / "torque_drag.csv", directory / "broomstick.csv", directory / "trajectory.csv"]
        pd.concat(tables, ignore_index=True).to_csv(paths[0], index=False, float_format="%.10g")
        chart.frame.to_csv(paths[1], index=False, float_format="%.10g")
        wells.trajectory(survey).to_csv(paths[2], index=False, float_format="%.10g")
        paths.append(plots.save(plots.broomstick_figure(chart, title=str(args.survey.name)),
                                directory / "broomstick.png"))
        paths.append(plots.save(plots.well_path_figure(survey, title=str(args.survey.name)),
                                directory / "well_path.png"))
        return paths

    written = _write(out, write)
    print(f"wrote {out}: {', '.join(str(p) for p in written)}")
    return 0


def _output_directory(args, scenario) -> Path:
    """--out, else the scenario's output.directory confined to the file's folder, else out/<stem>."""
    if args.out is not None:
        return args.out
    if scenario.output.directory is None:
        return Path("out") / scenario.name
    base = Path(args.scenario).absolute().parent
    given = Path(scenario.output.directory)
    target = base / given
    if args.allow_outside:
        return target
    where = f"{args.scenario}: output.directory"
    if given.is_absolute():
        raise CommandError(f"{where}: must be relative to the scenario's folder (got the absolute path {given}); "
                           f"pass --out or --allow-outside to write elsewhere", 2)
    # resolve() follows '..' and symbolic links: what stays inside the folder after both is confined
    try:
        inside = target.resolve().is_relative_to(base.resolve())
    except OSError as error:
        raise CommandError(f"{where}: cannot resolve {given} ({error.strerror or error})", 2) from None
    if not inside:
        raise CommandError(f"{where}: {given} leads out of the scenario's folder {base} (through '..' or a symbolic "
                           f"link); pass --out or --allow-outside to write elsewhere", 2)
    return target


# ----------------------------------------------------------------------------------------------- atomic outputs
def _check_target(out: Path) -> None:
    try:
        if out.exists() and not out.is_dir():
            raise CommandError(f"{out}: output path exists and is not a directory", 2)
    except OSError as error:  # e.g. a component longer than the file system allows (ENAMETOOLONG)
        raise CommandError(f"{out}: unusable output path ({error.strerror or error})", 2) from None


def _write(out: Path, writer) -> List[Path]:
    """Run ``writer(stage_directory)`` and move its files into ``out``; returns the paths relative to ``out``."""
    try:
        with staged_directory(out) as stage:
            return [Path(p).relative_to(stage) for p in writer(stage)]
    except OSError as error:
        raise CommandError(f"{out}: cannot write the outputs ({error})", 1) from None


@contextmanager
def staged_directory(target) -> Iterator[Path]:
    """Yield a new temporary directory next to ``target``; when the block succeeds, move its contents into
    ``target`` (renamed into place if ``target`` does not exist yet), else delete it. Nothing half-written
    appears in ``target``."""
    target = Path(target).absolute()
    target.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".partial", dir=target.parent))
    try:
        yield stage
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(stage, 0o777 & ~mask)  # mkdtemp makes it private; give it the usual permissions
        _commit(stage, target)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def _commit(stage: Path, target: Path) -> None:
    if not target.exists():
        try:
            os.rename(stage, target)
            return
        except OSError:
            pass  # created meanwhile: merge below
    files = [source for source in sorted(stage.rglob("*")) if not source.is_dir()]
    # Check every destination before replacing any, so that a blocked one leaves the target as it was.
    for source in files:
        destination = target / source.relative_to(stage)
        if destination.is_dir() or any(p.exists() and not p.is_dir() for p in destination.parents
                                       if target in p.parents or p == target):
            raise OSError(f"cannot write {destination}: a directory or file is in the way")
        # a symbolic link below the target would carry the write elsewhere: never followed
        if destination.is_symlink() or any(p.is_symlink() for p in destination.parents if target in p.parents):
            raise OSError(f"cannot write {destination}: a symbolic link is in the way (not followed)")
    for source in files:
        destination = target / source.relative_to(stage)
        destination.parent.mkdir(parents=True, exist_ok=True)
        os.replace(source, destination)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
