"""Provenance of an output: what made it, so a figure or a table can be traced back and rerun.

One record (a JSON-safe dict) says which frictionsim (version, and the git revision when it runs from a source
tree), which rigs and friction laws (their ``repr``, which rebuilds them, and their parameters with units from the
engine's parameter tables), which solver options, what the solver counted, when (UTC) and on which platform. The
same record is :attr:`frictionsim.Result.metadata`, the ``metadata`` attribute of a netCDF file
(:mod:`frictionsim.io`) and ``metadata.json`` beside the CLI's outputs::

    >>> from frictionsim import provenance
    >>> record = provenance.collect(command=["frictionsim", "run", "fig7.toml"], rigs=[rig])
    >>> provenance.write_metadata("out/fig7", record)
    PosixPath('out/fig7/metadata.json')
"""

from __future__ import annotations

import datetime
import functools
import json
import math
import os
import platform
import subprocess
import sys
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, Dict, Optional, Tuple, Union

import numpy as np

from .atomic import write_text

__all__ = ["SCHEMA", "collect", "rig_record", "solver_options_record", "to_json_safe", "write_metadata"]

#: Names the layout of the record, so a reader can tell which fields to expect.
SCHEMA = "frictionsim.provenance/1"

#: Arrays longer than this are summarised (count, first, last, min, max) instead of listed: a 40,001-sample output
#: grid or a string's 300 wall forces would otherwise swamp the record (the rig's repr still rebuilds it).
_LIST_LIMIT = 64

def _option_fields(options: Any) -> Tuple[str, ...]:
    """The fields of a SolverOptions as its class binds them (every settable attribute, in the binding's order): an
    option added in C++ is recorded without an entry here (the class's limits and methods are not options)."""
    return tuple(name for name, member in vars(type(options)).items()
                 if not name.startswith("_") and isinstance(member, property) and member.fset is not None)


def collect(*, command: Union[str, Iterable[str], None] = None, rigs: Any = (), solver_options: Any = None,
            stats: Optional[Mapping[str, Any]] = None, extra: Optional[Mapping[str, Any]] = None) -> Dict[str, Any]:
    """The provenance record of an output, JSON-safe.

    Parameters
    ----------
    command : str or sequence of str, optional
        The command line that made the output (e.g. ``sys.argv``); its words may also be paths.
    rigs : rig, sequence of rigs, or mapping name -> rig
        The rigs run (each: type, ``repr``, friction law ``repr``, parameters with units); a mapping names them
        (e.g. by scenario case); a single rig is one rig. Records already made by :func:`rig_record` are kept as
        they are.
    solver_options : frictionsim._core.SolverOptions or mapping, optional
        The options of the run (see :func:`solver_options_record`).
    stats : mapping, optional
        The solver's counters (``Result.stats``).
    extra : mapping, optional
        Anything else worth keeping (made JSON-safe), under ``"extra"``.

    Returns
    -------
    dict
        ``schema``, ``frictionsim`` (``version``, and ``git_revision`` / ``git_dirty`` only when run from a git
        source tree), ``created_utc`` (ISO 8601), ``platform`` (system, machine, python, numpy, scipy), then
        ``command``, ``rigs``, ``solver_options``, ``solver_stats``, ``extra`` where given.

    Raises
    ------
    InvalidParameterError (a ValueError)
        ``command`` neither a string nor a sequence of strings (or paths).
    """
    record: Dict[str, Any] = {"schema": SCHEMA, "frictionsim": dict(_package()), "created_utc": _utc_now(),
                              "platform": dict(_platform())}
    if command is not None:
        record["command"] = _command(command)
    if _is_rig_record(rigs) or not isinstance(rigs, (Mapping, Iterable)):
        rigs = [rigs]  # one rig (or one record of one)
    if isinstance(rigs, Mapping):
        record["rigs"] = [dict(_as_rig_record(rig), name=str(name)) for name, rig in rigs.items()]
    else:
        rigs = list(rigs) if rigs is not None else []
        if rigs:
            record["rigs"] = [_as_rig_record(rig) for rig in rigs]
    if solver_options is not None:
        record["solver_options"] = solver_options_record(solver_options)
    if stats is not None:
        record["solver_stats"] = to_json_safe(dict(stats))
    if extra is not None:
        record["extra"] = to_json_safe(dict(extra))
    return record


def _command(command: Any) -> Union[str, list]:
    """The command line as a string or a list of strings; anything else is refused naming ``command``."""
    if isinstance(command, str):
        return command
    words = list(command) if isinstance(command, Iterable) and not isinstance(command, (bytes, Mapping)) else None
    if words is None or not all(isinstance(word, (str, os.PathLike)) for word in words):
        from .errors import InvalidParameterError

        raise InvalidParameterError(f"command must be a string or a sequence of strings, such as sys.argv (got "
                                    f"{command!r})", "command")
    return [os.fspath(word) for word in words]


def _is_rig_record(value: Any) -> bool:
    """A record made by :func:`rig_record` (a mapping with a type and a repr), not a mapping of named rigs."""
    return isinstance(value, Mapping) and isinstance(value.get("type"), str) and isinstance(value.get("repr"), str)


def write_metadata(directory: Union[str, Path], record: Mapping[str, Any]) -> Path:
    """Write a provenance record as ``metadata.json``, whole or not at all (:mod:`frictionsim.atomic`: a process
    killed meanwhile leaves the earlier file).

    The file is strict JSON (non-finite numbers as the strings "NaN", "Infinity", "-Infinity"), indented, keys in
    the record's order.

    Parameters
    ----------
    directory : str or pathlib.Path
        An existing directory (the outputs' own).
    record : mapping
        The record (:func:`collect`).

    Returns
    -------
    pathlib.Path
        ``directory / "metadata.json"``.

    Raises
    ------
    InvalidParameterError (a ValueError)
        ``directory`` is not an existing directory.
    """
    directory = Path(directory)
    if not directory.is_dir():
        from .errors import InvalidParameterError

        raise InvalidParameterError(f"write_metadata: directory must be an existing directory (got {str(directory)!r})",
                                    "directory")
    text = json.dumps(to_json_safe(record), indent=2, allow_nan=False) + "\n"  # all of it, before the file opens
    return write_text(directory / "metadata.json", text)  # whole or not at all: never a truncated metadata.json


# ------------------------------------------------------------------------------------------------ records
def rig_record(rig: Any) -> Dict[str, Any]:
    """A rig as JSON.

    Parameters
    ----------
    rig : rig
        Any of the engine's rigs (or an object with ``parameters``, and ``friction`` for its law).

    Returns
    -------
    dict
        ``type``, ``repr`` (which rebuilds the rig), ``friction`` (the law's type, ``repr`` and parameters) and
        ``parameters``: the values of its parameter table with their units, ``{"name": {"value": ..., "unit":
        ...}}``.
    """
    record: Dict[str, Any] = {"type": type(rig).__name__, "repr": repr(rig)}
    law = getattr(rig, "friction", None)
    if law is not None:
        record["friction"] = {"type": type(law).__name__, "repr": repr(law),
                              "parameters": _parameter_values(law)}
    parameters = _parameter_values(rig)
    if parameters:
        record["parameters"] = parameters
    return record


def _as_rig_record(rig: Any) -> Dict[str, Any]:
    return dict(rig) if isinstance(rig, Mapping) else rig_record(rig)


def _parameter_values(obj: Any) -> Dict[str, Any]:
    """The values of ``obj``'s parameter table (the engine's ``parameters``: name, unit, ...), read off ``obj``."""
    out: Dict[str, Any] = {}
    for parameter in getattr(obj, "parameters", None) or ():
        name = getattr(parameter, "name", None)
        if not isinstance(name, str):
            continue
        try:
            value = getattr(obj, name)
        except Exception:  # noqa: BLE001 - a table entry without an attribute of that name: nothing to record
            continue
        if callable(value) and not isinstance(value, (np.ndarray, np.generic)):
            value = repr(value)  # a callable input (KinematicRig's relative_velocity): its repr is all we have
        out[name] = {"value": to_json_safe(value), "unit": str(getattr(parameter, "unit", ""))}
    return out


def solver_options_record(options: Any) -> Dict[str, Any]:
    """The options of a run as JSON.

    Parameters
    ----------
    options : frictionsim._core.SolverOptions or mapping
        The run's options.

    Returns
    -------
    dict
        Each option worth recording: enums by name, long arrays (an output grid) summarised, stop conditions by
        ``repr``.
    """
    if isinstance(options, Mapping):
        return to_json_safe(dict(options))
    record: Dict[str, Any] = {}
    for name in _option_fields(options):
        if not hasattr(options, name):
            continue
        if name == "stop_conditions":
            try:
                value = [repr(condition) for condition in options.stop_conditions]
            except TypeError:  # the engine's copies do not read back (see Result.metadata): left to the caller
                continue
        else:
            value = getattr(options, name)
        if hasattr(value, "name") and not isinstance(value, (str, bytes)):  # pybind11 enum
            value = value.name
        record[name] = to_json_safe(value)
    return record


def to_json_safe(value: Any) -> Any:
    """A value as plain JSON types.

    Parameters
    ----------
    value : object
        Anything: numbers, strings, mappings, sequences, NumPy scalars and arrays, enums, paths, ...

    Returns
    -------
    None, bool, int, float, str, list or dict
        NumPy scalars and arrays as numbers and lists (arrays longer than 64 as a summary: count, shape, first,
        last, min, max), tuples as lists, non-finite floats as "NaN" / "Infinity" / "-Infinity", enums by name,
        paths as text, anything else by ``repr``.
    """
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return _finite_or_name(float(value))
    if isinstance(value, Mapping):
        return {str(key): to_json_safe(item) for key, item in value.items()}
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        array = value if isinstance(value, np.ndarray) else _as_array(value)
        if array.dtype.kind in "biuf" and array.size > _LIST_LIMIT:
            flat = array.astype(float).ravel()
            return {"count": int(flat.size), "shape": list(array.shape), "first": _finite_or_name(flat[0]),
                    "last": _finite_or_name(flat[-1]), "min": _finite_or_name(np.nanmin(flat)),
                    "max": _finite_or_name(np.nanmax(flat))}
        return [to_json_safe(item) for item in (value.tolist() if isinstance(value, np.ndarray) else value)]
    if hasattr(value, "name") and hasattr(type(value), "__members__"):  # pybind11 enum
        return str(value.name)
    return repr(value)


def _as_array(values) -> np.ndarray:
    """A list as an array when it holds numbers (summarised when long); else an empty object array (the list is
    then converted item by item)."""
    try:
        array = np.asarray(values)
    except (TypeError, ValueError):  # ragged nesting
        array = None
    return array if array is not None and array.dtype.kind in "biuf" else np.empty(0, dtype=object)


def _finite_or_name(x: float) -> Any:
    x = float(x)
    if math.isfinite(x):
        return x
    return "NaN" if math.isnan(x) else ("Infinity" if x > 0 else "-Infinity")


def _utc_now() -> str:
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="microseconds")


def utc_time(timestamp: float) -> str:
    """A POSIX time as the record's ISO 8601 UTC text.

    Parameters
    ----------
    timestamp : float
        Seconds since the epoch.

    Returns
    -------
    str
        E.g. "2026-11-24T20:48:27.000000+00:00".
    """
    return datetime.datetime.fromtimestamp(timestamp, datetime.timezone.utc).isoformat(timespec="microseconds")


# ------------------------------------------------------------------------------------------------ the installation
@functools.lru_cache(maxsize=None)
def _platform() -> tuple:
    """Platform and versions: they do not change within a process, so found once (a sweep records thousands)."""
    from importlib import metadata

    def version(name: str) -> Optional[str]:
        module = sys.modules.get(name)
        if module is not None and isinstance(getattr(module, "__version__", None), str):
            return module.__version__
        try:
            return metadata.version(name)
        except metadata.PackageNotFoundError:
            return None

    items = [("system", platform.system()), ("release", platform.release()), ("machine", platform.machine()),
             ("python", platform.python_version()), ("implementation", platform.python_implementation()),
             ("numpy", np.__version__), ("scipy", version("scipy"))]
    return tuple((key, value) for key, value in items if value is not None)


@functools.lru_cache(maxsize=None)
def _package() -> tuple:
    from ._core import __version__

    items = [("version", __version__)]
    revision = git_revision(Path(__file__).resolve().parent)
    if revision is not None:
        items += [("git_revision", revision[0])] + ([("git_dirty", revision[1])] if revision[1] is not None else [])
    return tuple(items)


def git_revision(package_dir: Union[str, Path]):
    """The git revision of frictionsim's source tree the package lies in.

    A package under ``site-packages`` is installed, never "from the source tree", even when a virtual environment
    sits inside a repository; and a package copied into some other repository (a project that vendors it, a
    scratch directory under a home kept in git) is not that repository's: the enclosing work tree counts only when
    its ``python/frictionsim`` is this package directory, the layout of frictionsim's own tree.

    Parameters
    ----------
    package_dir : str or pathlib.Path
        The directory of the ``frictionsim`` package (``python/frictionsim`` in a source tree).

    Returns
    -------
    tuple of (str, bool or None), or None
        ``(commit, dirty)``: HEAD's commit and whether tracked files changed (None where the git program is
        missing); None when the package lies in no frictionsim source tree (an installed wheel) or the tree cannot
        be read.
    """
    package_dir = Path(package_dir)
    if any(part in ("site-packages", "dist-packages") for part in package_dir.parts):
        return None
    package_dir = package_dir.resolve()  # the tree it lies in, whatever symbolic link it was reached by
    root = next((p for p in (package_dir, *package_dir.parents) if (p / ".git").exists()), None)
    if root is None or not _same_directory(root / "python" / "frictionsim", package_dir):
        return None
    commit = _git(root, "rev-parse", "HEAD")
    if commit is None:
        commit = _read_head(root / ".git")
        return None if commit is None else (commit, None)
    status = _git(root, "status", "--porcelain", "--untracked-files=no")
    return commit, (None if status is None else bool(status))


def _same_directory(a: Path, b: Path) -> bool:
    try:
        return a.resolve(strict=True) == b.resolve(strict=True)
    except OSError:  # a does not exist: not frictionsim's layout
        return False


def _git(root: Path, *args: str) -> Optional[str]:
    try:
        done = subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True, timeout=10,
                              env={**os.environ, "GIT_OPTIONAL_LOCKS": "0"})  # read-only: no index refresh lock
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def _read_head(git_dir: Path) -> Optional[str]:
    """HEAD's commit read from the files, for a machine without the git program."""
    try:
        head = (git_dir / "HEAD").read_text().strip()
        if not head.startswith("ref: "):
            return head or None
        ref = head[5:]
        loose = git_dir / ref
        if loose.exists():
            return loose.read_text().strip() or None
        for line in (git_dir / "packed-refs").read_text().splitlines():
            if line.endswith(" " + ref):
                return line.split()[0]
    except OSError:
        return None
    return None
