"""Labelled outputs: results as xarray Datasets and netCDF files that carry their provenance.

Needs the optional extra ``frictionsim[io]`` (xarray, and h5netcdf + h5py to write netCDF-4). netCDF-4 rather than
xarray's built-in netCDF-3 writer (scipy): netCDF-3 has no 64-bit integers (the solver's counters), no Unicode
strings (event and mode names) and no compression. Both h5netcdf and netCDF4 install as wheels; h5netcdf is tried
first (pure Python on h5py), then netCDF4.

A :class:`frictionsim.Result` becomes a Dataset over the dimension ``time`` [s]: one variable per state, the friction
force (a torque [N m] on the torsional rig, the total wall friction torque of a drill string) and the contact mode (a
string's count of stuck wall contacts), each with its ``units`` as the rig and its law declare them
(:attr:`frictionsim.Result.units`, :mod:`frictionsim.outputs`); the switches are their own dimension
``event`` (time, switching function, modes, and the state before and after each over the dimension ``state``), and
the stop conditions' crossings ``stop_event``. The Dataset's ``attrs`` hold the
provenance record (:mod:`frictionsim.provenance`) as JSON under ``metadata``, plus its headline fields flat::

    >>> result.to_netcdf("run.nc")
    >>> dataset = frictionsim.io.open_dataset("run.nc")
    >>> frictionsim.io.metadata(dataset) == result.metadata
    True
"""

from __future__ import annotations

import importlib
import json
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Union

import numpy as np

from .atomic import atomic_path
from .errors import InvalidParameterError
from .outputs import output_units

__all__ = ["ENGINES", "PARQUET_ENGINES", "column_units", "metadata", "netcdf_engine", "open_dataset",
           "parquet_engine", "require_xarray", "result_dataset", "state_units", "write_netcdf"]

#: netCDF writers accepted by ``to_netcdf(engine=...)``, the netCDF-4 ones first: the default is the first installed.
ENGINES = ("h5netcdf", "netcdf4", "scipy")
#: The module each engine needs.
_ENGINE_MODULES = {"h5netcdf": ("h5netcdf", "h5py"), "netcdf4": ("netCDF4",), "scipy": ("scipy.io",)}
#: pandas' parquet writers, in the order tried.
PARQUET_ENGINES = ("pyarrow", "fastparquet")

_EXTRA = "pip install 'frictionsim[io]'"

def require_xarray():
    """The xarray module, imported on first use (it is an optional dependency).

    Returns
    -------
    module
        ``xarray``.

    Raises
    ------
    ImportError
        Without xarray, saying how to get it (``pip install 'frictionsim[io]'``).
    """
    try:
        return importlib.import_module("xarray")
    except ImportError as error:
        raise ImportError(f"labelled outputs (to_xarray, to_netcdf) need xarray, from the optional extra "
                          f"frictionsim[io]: {_EXTRA}") from error


def netcdf_engine(engine: Optional[str] = None) -> str:
    """The netCDF writer to use.

    Parameters
    ----------
    engine : {"h5netcdf", "netcdf4", "scipy"}, optional
        The writer wanted; default the first installed of ``ENGINES``' netCDF-4 writers.

    Returns
    -------
    str
        The engine's name, as xarray's ``to_netcdf(engine=...)`` takes it.

    Raises
    ------
    InvalidParameterError (a ValueError)
        An unknown name.
    ImportError
        The writer (or every netCDF-4 writer) is not installed; names the extra.
    """
    if engine is not None:
        if engine not in ENGINES:
            raise InvalidParameterError(f"engine must be one of {', '.join(ENGINES)} (got {engine!r})", "engine")
        if not _installed(engine):
            raise ImportError(f"the netCDF engine {engine!r} needs {' and '.join(_ENGINE_MODULES[engine])}: "
                              f"{_EXTRA}")
        return engine
    for name in ENGINES[:2]:
        if _installed(name):
            return name
    raise ImportError(f"writing netCDF-4 needs h5netcdf (with h5py) or netCDF4, from the optional extra "
                      f"frictionsim[io]: {_EXTRA}")


def _installed(engine: str) -> bool:
    try:
        for module in _ENGINE_MODULES[engine]:
            importlib.import_module(module)
    except ImportError:
        return False
    return True


def parquet_engine() -> str:
    """pandas' parquet writer that is installed.

    Returns
    -------
    str
        "pyarrow", else "fastparquet", as pandas' ``to_parquet(engine=...)`` takes it.

    Raises
    ------
    ImportError
        Neither is installed; names the extra.
    """
    for name in PARQUET_ENGINES:
        try:
            importlib.import_module(name)
            return name
        except ImportError:
            continue
    raise ImportError(f"writing parquet needs pyarrow (or fastparquet), from the optional extra frictionsim[io]: "
                      f"{_EXTRA}")


def state_units(name: str, source: Any = None) -> Optional[str]:
    """The SI unit of a state or output column, as the rig and its law declare it.

    Parameters
    ----------
    name : str
        A state (``disc_speed``, ``theta_3``, ...) or an output column (``friction_force``, ``t``, ...).
    source : Result, rig, mapping or pandas DataFrame, optional
        Where the column comes from: a :class:`frictionsim.Result` (its :attr:`~frictionsim.Result.units`), a rig
        (:func:`frictionsim.outputs.output_units`), a mapping of column -> unit, or a frame carrying one in
        ``attrs["units"]``; without it only ``t`` [s] is known.

    Returns
    -------
    str or None
        The unit ("rad/s", "N m", ...), or None when not declared.
    """
    return column_units(source).get(name, "s" if name == "t" else None)


def column_units(source: Any) -> Dict[str, str]:
    """Column -> SI unit of ``source`` (see :func:`state_units`); {} when it declares none."""
    if source is None:
        return {}
    if isinstance(source, Mapping):
        return dict(source)
    attrs = getattr(source, "attrs", None)
    if isinstance(attrs, Mapping):  # a frame: the units its maker recorded
        return dict(attrs.get("units", {}))
    units = getattr(source, "units", None)
    if isinstance(units, Mapping):  # a Result
        return dict(units)
    return output_units(source)


# ------------------------------------------------------------------------------------------------ attrs
def metadata_attrs(record: Mapping[str, Any], title: str = "") -> Dict[str, Any]:
    """netCDF global attributes of a provenance record.

    Parameters
    ----------
    record : mapping
        A provenance record (:func:`frictionsim.provenance.collect`).
    title : str, optional
        The dataset's ``title`` attribute (none when empty).

    Returns
    -------
    dict
        The whole record as JSON under ``metadata`` (netCDF attributes are flat: numbers, strings), and its
        headline fields flat for tools that list attributes (``source``, ``frictionsim_git_revision``,
        ``created_utc``, ``rig``).
    """
    from .provenance import to_json_safe

    record = to_json_safe(dict(record))
    package = record.get("frictionsim", {})
    attrs: Dict[str, Any] = {}
    if title:
        attrs["title"] = title
    attrs["source"] = f"frictionsim {package.get('version', '')}".strip()
    if "git_revision" in package:
        attrs["frictionsim_git_revision"] = package["git_revision"]
    if "created_utc" in record:
        attrs["created_utc"] = record["created_utc"]
    rigs = record.get("rigs") or []
    if len(rigs) == 1:
        attrs["rig"] = rigs[0].get("repr", "")
    attrs["metadata"] = json.dumps(record, allow_nan=False)
    return attrs


def metadata(dataset_or_attrs: Any) -> Dict[str, Any]:
    """The provenance record of a Dataset written by frictionsim.

    Parameters
    ----------
    dataset_or_attrs : xarray.Dataset or mapping
        The Dataset (e.g. from :func:`open_dataset`), or its ``attrs``.

    Returns
    -------
    dict
        The record, as :attr:`frictionsim.Result.metadata` had it.

    Raises
    ------
    InvalidParameterError (a ValueError)
        The dataset carries no frictionsim provenance.
    """
    attrs = getattr(dataset_or_attrs, "attrs", dataset_or_attrs)
    if "metadata" not in attrs:
        raise InvalidParameterError("metadata: the dataset carries no frictionsim provenance (no 'metadata' "
                                    "attribute)", "dataset")
    return json.loads(attrs["metadata"])


# ------------------------------------------------------------------------------------------------ Result
def result_dataset(result) -> Any:
    """A simulation result as a labelled xarray Dataset (see the module's description).

    Parameters
    ----------
    result : frictionsim.Result
        The run.

    Returns
    -------
    xarray.Dataset
        Its values bit for bit, with units; ``attrs``: the provenance record and the run's status.

    Raises
    ------
    ImportError
        Without xarray (``pip install 'frictionsim[io]'``).
    """
    xr = require_xarray()
    record = result.metadata
    units = result.units
    time = {"units": "s", "long_name": "time"}
    data: Dict[str, Any] = {}
    for i, name in enumerate(result.state_names):
        data[name] = ("time", np.array(result.states[:, i]), _units(name, units))
    torque = units.get("friction_force") == "N m"
    data["friction_force"] = ("time", np.array(result.friction_force),
                              dict(_units("friction_force", units),
                                   long_name="friction torque" if torque else "friction force"))
    if units.get("mode") == "1":  # a string's mode counts its stuck wall contacts
        mode = {"long_name": "stuck wall contacts", "units": "1"}
    else:
        mode = {"long_name": "contact mode", "flag_values": np.array([-1, 0, 1], dtype=result.mode.dtype),
                "flag_meanings": "slip_negative stick_or_smooth slip_positive"}
    data["mode"] = ("time", np.array(result.mode), mode)
    data.update(_event_variables(result.events, "event", result.state_names, stop=False))
    data.update(_event_variables(result.stop_events, "stop_event", result.state_names, stop=True))
    coords = {"time": ("time", np.array(result.t), time), "state": ("state", np.array(result.state_names, dtype=str))}
    attrs = metadata_attrs(record, title="frictionsim simulation")
    attrs.update(completed=int(result.completed), status=int(result.status), message=result.message,
                 t_reached=float(result.t_reached))
    if result.period is not None:
        attrs["period"] = float(result.period)
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _units(name: str, units: Mapping[str, str]) -> Dict[str, str]:
    unit = units.get(name)
    return {} if unit is None else {"units": unit}


def _event_variables(events, dim: str, state_names, *, stop: bool) -> Dict[str, Any]:
    """The event log over its own dimension ``dim``: one variable per field of :class:`frictionsim.Event`."""
    prefix = "stop_" if stop else "event_"
    out: Dict[str, Any] = {
        f"{prefix}time": (dim, np.array([e.time for e in events], dtype=float), {"units": "s"}),
        f"{prefix}name": (dim, np.array([e.name for e in events], dtype=str)),
        f"{prefix}switching_function": (dim, np.array([e.switching_function for e in events], dtype=np.int64)),
        f"{prefix}mode_before": (dim, np.array([e.mode_before_name for e in events], dtype=str)),
        f"{prefix}mode_after": (dim, np.array([e.mode_after_name for e in events], dtype=str)),
    }
    if stop:
        out["stop_condition"] = (dim, np.array([e.stop_condition for e in events], dtype=np.int64))
        out["stop_direction"] = (dim, np.array([e.direction for e in events], dtype=np.int64))
    # the states at the switches, when the run kept them (record_event_states): all events or none do
    if events and all(e.state_before is not None and e.state_after is not None for e in events):
        for side in ("before", "after"):
            rows = np.array([getattr(e, "state_" + side) for e in events], dtype=float)
            out[f"{prefix}state_{side}"] = ((dim, "state"), rows.reshape(len(events), len(state_names)))
    return out


# ------------------------------------------------------------------------------------------------ files
def write_netcdf(dataset, path: Union[str, Path], engine: Optional[str] = None) -> Path:
    """Write a Dataset as a netCDF file, whole or not at all: to a temporary name beside ``path``, renamed into
    place when complete (:mod:`frictionsim.atomic`), so an interrupted write leaves the earlier file intact.

    Parameters
    ----------
    dataset : xarray.Dataset
        What to write (e.g. :meth:`frictionsim.Result.to_xarray`).
    path : str or pathlib.Path
        The file to write.
    engine : {"h5netcdf", "netcdf4", "scipy"}, optional
        The writer (see :func:`netcdf_engine`).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    name = netcdf_engine(engine)
    with atomic_path(path) as temporary:  # a run killed mid-write must not leave a truncated file under path
        dataset.to_netcdf(temporary, engine=name)
    return path


def open_dataset(path: Union[str, Path], engine: Optional[str] = None):
    """Open a netCDF file written by frictionsim, read it into memory and close it (no file handle left open).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    engine : {"h5netcdf", "netcdf4", "scipy"}, optional
        The reader; default xarray's choice.

    Returns
    -------
    xarray.Dataset
        Loaded in memory; :func:`metadata` gives its provenance record.
    """
    xr = require_xarray()
    name = netcdf_engine(engine) if engine is not None else None
    with xr.open_dataset(Path(path), engine=name) as dataset:
        return dataset.load()
