"""Parameter sweeps: run one function over a grid of parameters on any executor, with a progress bar.

The same call scales from a laptop to a cluster, because the work is handed to a standard
:class:`concurrent.futures.Executor`::

    >>> import frictionsim as fs
    >>> from frictionsim.axial import axial_mean_friction
    >>> grid = {"amplitude": [1e-3, 3e-3, 5e-3], "frequency": [10.0, 17.0, 25.0]}   # m, Hz
    >>> result = fs.sweep(axial_mean_friction, grid, fixed={"friction": fs.Dahl(0.41, 4e4)})
    >>> result.as_array()           # F_df [N] on the 3 x 3 (amplitude, frequency) grid
    >>> result.to_pandas()          # one row per point

* ``executor=None`` runs serially in this process;
* a :class:`~concurrent.futures.ThreadPoolExecutor` runs simulations truly in parallel (the engine releases
  the GIL while integrating);
* a :class:`~concurrent.futures.ProcessPoolExecutor` needs a picklable, top-level ``function`` (rigs, friction
  laws, results and frictionsim's exceptions all pickle);
* a ``dask.distributed.Client`` is accepted directly: the sweep runs on ``client.get_executor(pure=False)``,
  the concurrent.futures interface of the cluster (``pure=False``: every point is computed, never merged with
  another task that dask would hash as equal).

The points are run in a deterministic order and the values are stored in grid order whatever order they
finish in, so a sweep gives bit-for-bit the same values on every executor. Ready-made point functions, e.g. for
the friction-reduction map of paper 000 over vibration amplitude and frequency, are in :mod:`frictionsim.axial`
(:func:`~frictionsim.axial.axial_mean_friction`, :func:`~frictionsim.axial.kinematic_mean_friction`; still
importable from here).
"""

from __future__ import annotations

import concurrent.futures as cf
import itertools
import math
import pickle
import signal
import threading
import time
import traceback
from collections.abc import Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Iterable, Iterator, List, Optional, Tuple, Union

import numpy as np

from .axial import axial_mean_friction, kinematic_mean_friction  # moved to axial.py; the old names stay
from .errors import InvalidParameterError

__all__ = [
    "SweepError",
    "SweepResult",
    "axial_mean_friction",
    "grid_points",
    "kinematic_mean_friction",
    "sweep",
]

Grid = Union[Mapping, Iterable[Mapping]]

_ERROR_MODES = ("raise", "collect")


class SweepError(RuntimeError):
    """A point of a sweep failed (``errors="raise"``), or the sweep could not be sent to a process pool.

    ``point`` is the failing point's parameters (dict), ``index`` its position in grid order, ``error`` the
    original exception (also the ``__cause__``), and ``remote_traceback`` its traceback as text when it was
    raised in another thread, process or machine. ``index`` is -1 and ``point`` {} when the function, ``fixed``
    or the grid does not pickle for a ProcessPoolExecutor (found before anything is submitted).
    """

    def __init__(self, message: str, index: int, point: Dict[str, Any], error: BaseException,
                 remote_traceback: str = "") -> None:
        super().__init__(message)
        self.index = index
        self.point = point
        self.error = error
        self.remote_traceback = remote_traceback

    def __reduce__(self):
        return (type(self), (str(self), self.index, self.point, self.error, self.remote_traceback))


def _reject(parameter: str, rule: str, value: object) -> None:
    raise InvalidParameterError(f"sweep: {parameter} must be {rule} (got {value!r})", parameter)


# ---------------------------------------------------------------------------------------------- the grid
def grid_points(grid: Grid) -> Tuple[List[Dict[str, Any]], List[str], Optional[Tuple[int, ...]]]:
    """Expand ``grid`` into ``(points, parameters, grid_shape)``.

    A mapping ``name -> sequence of values`` gives the full Cartesian product in C order (the last name varies
    fastest), with ``grid_shape`` = the lengths of the sequences. A sequence of mappings gives those points as
    they are, with ``grid_shape`` None. ``parameters`` lists the names in order of first appearance.

    Raises :class:`frictionsim.InvalidParameterError` (a ValueError) naming the bad entry.
    """
    if isinstance(grid, Mapping):
        if not grid:
            _reject("grid", "a non-empty mapping name -> sequence of values, or a non-empty sequence of dicts",
                    grid)
        axes: Dict[str, List[Any]] = {}
        for name, values in grid.items():
            _check_name(name, "grid")
            label = f"grid[{name!r}]"
            if hasattr(values, "tolist") and not isinstance(values, (str, bytes)):  # NumPy array, pandas Series
                array = np.asarray(values)
                if array.ndim != 1:
                    _reject(label, "a 1-D sequence of values", f"array of shape {array.shape}")
                values = array.tolist()  # Python scalars: plain floats in the points and the DataFrame
            elif isinstance(values, (str, bytes)) or not isinstance(values, Sequence):
                _reject(label, "a sequence of values (list, tuple, range or 1-D array)", values)
            if len(values) == 0:
                _reject(label, "a non-empty sequence of values", values)
            axes[name] = list(values)
        names = list(axes)
        points = [dict(zip(names, combination)) for combination in itertools.product(*axes.values())]
        return points, names, tuple(len(v) for v in axes.values())

    if isinstance(grid, (str, bytes)) or not isinstance(grid, Iterable):
        _reject("grid", "a mapping name -> sequence of values, or a sequence of dicts", grid)
    points = []
    names = []
    for i, point in enumerate(grid):
        if not isinstance(point, Mapping):
            _reject(f"grid[{i}]", "a dict of parameters", point)
        for name in point:
            _check_name(name, f"grid[{i}]")
            if name not in names:
                names.append(name)
        points.append(dict(point))
    if not points:
        _reject("grid", "a non-empty mapping name -> sequence of values, or a non-empty sequence of dicts", grid)
    return points, names, None


def _check_name(name: object, where: str) -> None:
    if not isinstance(name, str) or not name:
        _reject(where, "keyed by parameter names (non-empty str)", name)


# ---------------------------------------------------------------------------------------------- running
class _RemoteTraceback(Exception):
    """Carries the text of a traceback raised in another thread, process or machine (as concurrent.futures does)."""

    def __str__(self) -> str:
        return self.args[0]


@dataclass
class _Failure:
    """An exception raised by ``function`` at one point, with its traceback as text (tracebacks don't pickle)."""

    error: BaseException
    traceback: str


def _run_chunk(function: Callable[..., Any], fixed: Dict[str, Any], points: List[Dict[str, Any]],
               stop: Optional[threading.Event] = None, worker: bool = False) -> Optional[List[Any]]:
    """Run ``function(**fixed, **point)`` for each point; an exception becomes a _Failure (the others still run).

    ``stop`` (an in-process pool's): set, it skips the rest (None: the sweep is ending); an interrupt
    (KeyboardInterrupt, SystemExit) sets it on its way out, so no other worker starts a point meanwhile.
    ``worker``: run in a process pool's worker, which from then on ignores SIGINT (a terminal's Ctrl-C reaches
    the whole process group): the interrupt is the parent's, which terminates the workers (see :func:`sweep`)."""
    if worker and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    out: List[Any] = []
    for point in points:
        if stop is not None and stop.is_set():
            return None
        try:
            out.append(function(**fixed, **point))
        except Exception as error:  # noqa: BLE001 - reported per point by sweep()
            out.append(_Failure(error, traceback.format_exc()))
        except BaseException:
            if stop is not None:
                stop.set()
            raise
    return out


def _as_executor(executor: Any) -> Optional[cf.Executor]:
    if executor is None or isinstance(executor, cf.Executor):
        return executor
    if callable(getattr(executor, "get_executor", None)):  # dask.distributed.Client (duck-typed: dask is optional)
        return executor.get_executor(pure=False)
    raise TypeError("executor must be None, a concurrent.futures.Executor or a dask.distributed.Client, "
                    f"got {type(executor).__name__}")


def sweep(function: Callable[..., Any], grid: Grid, *, fixed: Optional[Mapping[str, Any]] = None,
          executor: Any = None, progress: bool = True, errors: str = "raise", chunksize: int = 1,
          description: Optional[str] = None) -> "SweepResult":
    """Evaluate ``function(**fixed, **point)`` at every point of ``grid``.

    Parameters
    ----------
    function : callable
        Called with keyword arguments only; returns anything, typically a float (e.g. a mean friction force
        [N]) or a dict of floats. For a ProcessPoolExecutor it must pickle (a top-level function such as
        :func:`axial_mean_friction`; :func:`functools.partial` of one also works), as must ``fixed`` and the
        grid: checked before anything is submitted. A dask cluster pickles with cloudpickle (lambdas work).
    grid : mapping or sequence of dicts
        ``{"amplitude": [...], "frequency": [...]}``: the full Cartesian product, last name varying fastest
        (C order, so :meth:`SweepResult.as_array` reshapes to ``grid_shape``). Or a sequence of dicts: those
        explicit points, in order.
    fixed : mapping, optional
        Keyword arguments passed unchanged to every call (e.g. ``friction``, ``t_end``); they must not repeat a
        grid name.
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where to run the points; None runs them serially in this process. The executor is used, not shut down.
    progress : bool
        Show a tqdm progress bar, advanced as points complete.
    errors : {"raise", "collect"}
        "raise": the first failing point (in completion order) cancels the outstanding work and raises
        :class:`SweepError` naming the point, from the original exception. "collect": every point runs; a
        failing point's value is its exception (see :attr:`SweepResult.failed`).
    chunksize : int
        Points per submitted task; more than 1 cuts the per-task overhead of process pools and clusters for
        very short runs. Results are the same.
    description : str, optional
        Label of the progress bar.

    Returns
    -------
    SweepResult
        The points and their values, both in grid order.

    Raises
    ------
    InvalidParameterError (ValueError)
        Empty grid, a grid entry that is not a sequence, a ``fixed`` name repeated in the grid, a bad
        ``errors`` or ``chunksize``; ``.parameter`` names it.
    SweepError
        A point failed and ``errors="raise"``; or the function, ``fixed`` or the grid does not pickle for a
        ProcessPoolExecutor (``index`` -1).
    KeyboardInterrupt, SystemExit
        Raised in a point or by Ctrl-C while waiting (with either ``errors``): propagates unchanged. The points
        not started are cancelled; on a thread pool no other point starts after it; a ProcessPoolExecutor's
        workers are terminated at once (its running points would otherwise hold the caller's ``with`` block for
        as long as they take): the pool is broken afterwards (BrokenProcessPool on a further submit). Its
        workers start with SIGINT blocked (forked, as on Linux) and ignore it from their first point on, so
        that Ctrl-C of a terminal, which reaches the whole process group, is left to this process.
    """
    if not callable(function):
        raise TypeError(f"function must be callable, got {type(function).__name__}")
    if errors not in _ERROR_MODES:
        _reject("errors", "'raise' or 'collect'", errors)
    if isinstance(chunksize, bool) or not isinstance(chunksize, (int, np.integer)) or chunksize < 1:
        _reject("chunksize", "a positive integer", chunksize)
    fixed = dict(fixed or {})
    for name in fixed:
        _check_name(name, "fixed")
    points, parameters, grid_shape = grid_points(grid)
    clashes = [name for name in parameters if name in fixed]
    if clashes:
        _reject("fixed", f"free of the grid's parameter names ({', '.join(clashes)})", sorted(fixed))
    pool = _as_executor(executor)

    from tqdm.auto import tqdm

    chunks = [list(range(start, min(start + int(chunksize), len(points))))
              for start in range(0, len(points), int(chunksize))]
    values: List[Any] = [None] * len(points)
    started = time.perf_counter()
    with tqdm(total=len(points), disable=not progress, desc=description or _name(function), unit="pt") as bar:

        def store(indices: List[int], outcome: List[Any]) -> None:
            for i, value in zip(indices, outcome):
                if isinstance(value, _Failure) and errors == "raise":
                    if value.error.__traceback__ is None and value.error.__cause__ is None and value.traceback:
                        value.error.__cause__ = _RemoteTraceback("\n" + value.traceback)  # shown in the chain
                    raise SweepError(
                        f"sweep point {i} {_describe(points[i])} failed: {type(value.error).__name__}: "
                        f"{value.error}", i, points[i], value.error, value.traceback) from value.error
                values[i] = value.error if isinstance(value, _Failure) else value
            bar.update(len(indices))

        if pool is None:
            for indices in chunks:
                store(indices, _run_chunk(function, fixed, [points[i] for i in indices]))
        else:
            _require_picklable(pool, function, fixed, points)
            # threads share a stop flag: an interrupt in one point stops the others starting new ones at once
            stop = threading.Event() if isinstance(pool, cf.ThreadPoolExecutor) else None
            processes = isinstance(pool, cf.ProcessPoolExecutor)
            futures: Dict[cf.Future, List[int]] = {}
            interrupted = False
            try:
                # the workers a process pool forks while submitting keep SIGINT blocked: a terminal's Ctrl-C (sent
                # to the whole group) is this process's, raised here when the mask is restored
                with _sigint_blocked(processes):
                    for indices in chunks:
                        futures[pool.submit(_run_chunk, function, fixed, [points[i] for i in indices], stop,
                                            processes)] = indices
                for future in cf.as_completed(futures):
                    indices = futures[future]
                    try:
                        outcome = future.result()  # an interrupt raised in a point propagates from here
                    except Exception as error:  # the task itself failed: unpicklable function, broken pool...
                        outcome = [_Failure(error, "".join(traceback.format_exception(
                            type(error), error, error.__traceback__)))] * len(indices)
                    if outcome is not None:  # None: skipped after an interrupt, whose future raises it here
                        store(indices, outcome)
            except BaseException as error:
                interrupted = not isinstance(error, Exception)  # Ctrl-C, SystemExit, SIGTERM raised by a handler
                raise
            finally:  # on an error (or Ctrl-C) cancel what has not started; no-op when all are done
                if stop is not None:
                    stop.set()
                for future in futures:
                    future.cancel()
                if interrupted and processes:
                    _terminate_workers(pool)
    result = SweepResult(points=points, values=values, parameters=parameters, grid_shape=grid_shape,
                         elapsed=time.perf_counter() - started)
    result.metadata = _provenance(function, fixed, pool, result)
    return result


@contextmanager
def _sigint_blocked(block: bool = True) -> Iterator[None]:
    """SIGINT blocked in this thread for the block, then the mask restored: processes forked meanwhile (a
    ProcessPoolExecutor's workers start as it submits, forked on Linux) keep it blocked, so a terminal's Ctrl-C,
    sent to the whole process group, never reaches them; this process gets a SIGINT that arrived meanwhile as
    soon as the mask is restored (nothing is lost). Spawned processes start unblocked (multiprocessing's spawn
    resets the mask): they ignore SIGINT from their first point on. A no-op without signal masks (Windows) or
    outside the main thread."""
    if not (block and hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread()):
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


#: How long the terminated workers of a process pool are waited for before they are killed [s].
_TERMINATE_GRACE = 0.5


def _terminate_workers(pool: cf.ProcessPoolExecutor) -> None:
    """Stop a process pool's workers now, running points and all (SIGTERM, then SIGKILL after a grace period),
    and shut the pool down without waiting: an interrupted sweep must not wait for points that take hours.
    concurrent.futures has no public handle on its processes before Python 3.14's terminate_workers()."""
    workers = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    if not workers and callable(getattr(pool, "terminate_workers", None)):
        pool.terminate_workers()
        return
    for process in workers:
        if process.is_alive():
            process.terminate()
    deadline = time.monotonic() + _TERMINATE_GRACE
    for process in workers:
        process.join(max(0.0, deadline - time.monotonic()))
        if process.is_alive():
            process.kill()
            process.join(_TERMINATE_GRACE)


def _provenance(function: Callable[..., Any], fixed: Mapping[str, Any], pool: Optional[cf.Executor],
                result: "SweepResult") -> Dict[str, Any]:
    """The sweep's provenance record: the function, ``fixed`` (rigs and laws by repr), executor and wall time."""
    from .provenance import collect

    rigs = {name: value for name, value in fixed.items() if hasattr(value, "state_names")}  # the engine's rigs
    return collect(rigs=rigs, extra={
        "sweep": {"function": _qualified_name(function), "fixed": {name: repr(value) for name, value in fixed.items()},
                  "parameters": list(result.parameters), "points": len(result.points),
                  "failed": len(result.failed), "executor": type(pool).__name__ if pool is not None else "serial",
                  "elapsed_s": result.elapsed}})


def _require_picklable(pool: cf.Executor, function: Callable[..., Any], fixed: Mapping[str, Any],
                       points: List[Dict[str, Any]]) -> None:
    """A process pool pickles the function, fixed and the points to send them to its workers: pickle them here
    first, before anything is submitted. Failing inside the pool instead left its shutdown deadlocked now and then.
    Other executors serialise as they like (dask uses cloudpickle, which takes lambdas; a thread pool
    needs nothing), so only a ProcessPoolExecutor is checked."""
    if not isinstance(pool, cf.ProcessPoolExecutor):
        return
    for what, value in (("function", function), ("fixed", fixed), ("grid", points)):
        try:
            pickle.dumps(value)
        except Exception as error:
            label = f"function {_qualified_name(function)!r}" if what == "function" else f"the {what}"
            raise SweepError(f"sweep: {label} must pickle to run on a {type(pool).__name__} "
                             f"({type(error).__name__}: {error}); use a top-level function (not a lambda or a local "
                             f"function) and picklable values, or a ThreadPoolExecutor", -1, {}, error) from error


def _qualified_name(function: Callable[..., Any]) -> str:
    inner = getattr(function, "func", function)  # functools.partial
    return f"{getattr(inner, '__module__', '?')}.{getattr(inner, '__qualname__', _name(function))}"


def _name(function: Callable[..., Any]) -> str:
    inner = getattr(function, "func", function)  # functools.partial
    return getattr(inner, "__name__", type(inner).__name__)


def _describe(point: Dict[str, Any]) -> str:
    return "(" + ", ".join(f"{name}={value!r}" for name, value in point.items()) + ")"


# ---------------------------------------------------------------------------------------------- the result
@dataclass
class SweepResult:
    """Points and values of a :func:`sweep`, both in grid order.

    Attributes
    ----------
    points : list of dict
        The parameters of each point (without ``fixed``).
    values : list
        ``function``'s return value at each point; with ``errors="collect"``, the exception for a failed point.
    parameters : list of str
        The grid's parameter names.
    grid_shape : tuple of int or None
        The lengths of the grid's axes for a Cartesian grid, else None.
    elapsed : float, s
        Wall-clock time of the sweep.
    metadata : dict
        Provenance (:func:`frictionsim.provenance.collect`): version, the function, ``fixed`` by repr (rigs with
        their parameters), executor, time, platform; the ``attrs`` of :meth:`to_netcdf`.
    """

    points: List[Dict[str, Any]]
    values: List[Any]
    parameters: List[str]
    grid_shape: Optional[Tuple[int, ...]] = None
    elapsed: float = field(default=0.0, compare=False)
    metadata: Dict[str, Any] = field(default_factory=dict, compare=False, repr=False)

    def __len__(self) -> int:
        return len(self.points)

    def __iter__(self):
        """Iterate over ``(point, value)`` pairs."""
        return iter(zip(self.points, self.values))

    def __repr__(self) -> str:
        shape = "x".join(map(str, self.grid_shape)) if self.grid_shape else "explicit"
        return (f"SweepResult({len(self)} points over {self.parameters} ({shape}), {len(self.failed)} failed, "
                f"{self.elapsed:.3g} s)")

    @property
    def failed(self) -> List[int]:
        """Indices of the points whose value is an exception (``errors="collect"``)."""
        return [i for i, value in enumerate(self.values) if isinstance(value, BaseException)]

    @property
    def axes(self) -> Optional[Dict[str, List[Any]]]:
        """The values along each axis of a Cartesian grid (name -> list), or None for explicit points."""
        if self.grid_shape is None:
            return None
        strides = np.cumprod((self.grid_shape[1:] + (1,))[::-1])[::-1]  # C-order stride of each axis
        return {name: [self.points[k * int(stride)][name] for k in range(n)]
                for name, n, stride in zip(self.parameters, self.grid_shape, strides)}

    def as_array(self, key: Optional[str] = None) -> np.ndarray:
        """The values as a float array of shape ``grid_shape`` (NaN where a point failed).

        ``key`` picks one entry of dict values (required when the values are dicts).
        """
        if self.grid_shape is None:
            raise ValueError("as_array: the sweep ran over explicit points, not a Cartesian grid; use to_pandas()")
        flat = np.empty(len(self.values))
        for i, value in enumerate(self.values):
            if isinstance(value, BaseException):
                flat[i] = math.nan
                continue
            if isinstance(value, Mapping):
                if key is None:
                    raise ValueError(f"key: the values are dicts; pass one of {sorted(value)}")
                value = value[key]
            elif key is not None:
                raise ValueError(f"key: the values are not dicts (got {type(value).__name__}); omit key")
            flat[i] = float(value)
        return flat.reshape(self.grid_shape)

    def to_pandas(self):
        """A pandas DataFrame, one row per point: the parameters, then the value.

        A scalar (or any non-dict) value goes to column "value"; a dict value expands to one column per key
        (a key equal to a parameter name becomes "value.<key>"). With failed points, an "error" column holds
        ``"Type: message"`` (None elsewhere) and their value columns are NaN.
        """
        import pandas as pd

        rows = []
        for point, value in self:
            row = dict(point)
            if isinstance(value, BaseException):
                row["error"] = f"{type(value).__name__}: {value}"
            elif isinstance(value, Mapping):
                row.update({(f"value.{k}" if k in point else k): v for k, v in value.items()})
            else:
                row["value"] = value
            rows.append(row)
        frame = pd.DataFrame(rows)
        values = [c for c in frame.columns if c not in self.parameters and c != "error"]
        frame = frame[self.parameters + values + (["error"] if "error" in frame else [])]
        if "error" in frame:
            frame["error"] = frame["error"].astype(object).where(frame["error"].notna(), None)
        return frame

    def to_xarray(self, units: Optional[Mapping[str, str]] = None):
        """The sweep as a labelled xarray Dataset.

        Over the grid's axes (one dimension per parameter, its values the coordinate) for a Cartesian grid, else
        over ``point`` with the parameters as coordinates. A scalar value is the variable "value", a dict value one
        variable per key (numbers, or strings); failed points are NaN (or "") with their error in the variable
        "error" ("" elsewhere).

        Parameters
        ----------
        units : mapping of str to str, optional
            Name -> unit of parameters and values, written as their ``units`` attributes.

        Returns
        -------
        xarray.Dataset
            The values over the grid; ``attrs`` hold the provenance (:attr:`metadata`).

        Raises
        ------
        ImportError
            Without xarray (``pip install 'frictionsim[io]'``).
        """
        from .io import metadata_attrs, require_xarray

        xr = require_xarray()
        units = dict(units or {})
        columns = self._value_columns(text=True)
        axes = self.axes
        dims = tuple(self.parameters) if axes is not None else ("point",)
        shape = self.grid_shape if axes is not None else (len(self.points),)

        def attrs(name: str) -> Dict[str, str]:
            return {"units": units[name]} if name in units else {}

        data = {name: (dims, column.reshape(shape), attrs(name)) for name, column in columns.items()}
        if self.failed:
            errors = ["" if not isinstance(v, BaseException) else f"{type(v).__name__}: {v}" for v in self.values]
            data["error"] = (dims, np.array(errors, dtype=str).reshape(shape))
        if axes is not None:
            coords = {name: (name, _coordinate(values, name), attrs(name)) for name, values in axes.items()}
        else:
            coords = {name: ("point", _coordinate([p.get(name, math.nan) for p in self.points], name), attrs(name))
                      for name in self.parameters}
        return xr.Dataset(data, coords=coords, attrs=metadata_attrs(self.metadata or {}, title="frictionsim sweep"))

    def to_netcdf(self, path, *, units: Optional[Mapping[str, str]] = None, engine: Optional[str] = None):
        """Write :meth:`to_xarray` as a netCDF file, its provenance in the global attributes.

        Parameters
        ----------
        path : str or pathlib.Path
            The file to write.
        units : mapping of str to str, optional
            Name -> unit of parameters and values (see :meth:`to_xarray`).
        engine : {"h5netcdf", "netcdf4", "scipy"}, optional
            The writer: the netCDF-4 ones (default the first installed), or "scipy" for netCDF-3.

        Returns
        -------
        pathlib.Path
            ``path``; read it back with :func:`frictionsim.io.open_dataset`.
        """
        from .io import write_netcdf

        return write_netcdf(self.to_xarray(units), path, engine)

    def plot(self, key: Optional[str] = None, ax=None, **kwargs):
        """The values over the grid on ``ax`` (:func:`frictionsim.plots.sweep_axes`): a line over a 1-D grid, a
        colour map over a 2-D one; ``key`` picks an entry of dict values. Returns the Axes."""
        from .plots import sweep_axes

        return sweep_axes(self, key, ax=ax, **kwargs)

    def _value_columns(self, text: bool = False) -> Dict[str, np.ndarray]:
        """The values as float columns by name ("value", or each key of dict values), NaN at failed points; with
        ``text``, a key whose values are all strings is a string column ("" at failed points)."""
        keys: List[str] = []
        for value in self.values:
            if isinstance(value, Mapping):
                keys += [k for k in value if k not in keys]
        names = keys or ["value"]
        ok = [value for value in self.values if not isinstance(value, BaseException)]

        def items(name):
            return [value.get(name, math.nan) if isinstance(value, Mapping) else value for value in ok]

        out: Dict[str, np.ndarray] = {}
        for name in names:
            if text and ok and all(isinstance(item, str) for item in items(name)):
                out[name] = np.array(["" if isinstance(v, BaseException) else
                                      (v.get(name, "") if isinstance(v, Mapping) else v) for v in self.values],
                                     dtype=str)
                continue
            column = np.full(len(self.values), math.nan)
            for i, value in enumerate(self.values):
                if isinstance(value, BaseException):
                    continue
                item = value.get(name, math.nan) if isinstance(value, Mapping) else value
                try:
                    if isinstance(item, (str, bytes)):
                        raise TypeError(item)
                    column[i] = float(item)
                except (TypeError, ValueError):
                    raise InvalidParameterError(f"to_xarray: the values must be numbers or strings, or dicts of them "
                                                f"(point {i} has {name} = {type(item).__name__} {item!r:.60})",
                                                "values") from None
            out[name] = column
        return out


def _coordinate(values: List[Any], name: str) -> np.ndarray:
    """Parameter values as a coordinate array: numbers as floats or ints, anything else (a friction law) by repr."""
    array = np.asarray(values)
    if array.dtype.kind in "biuf":
        return array
    return np.array([v if isinstance(v, str) else repr(v) for v in values], dtype=str)
