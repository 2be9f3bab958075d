"""
Labelled output with provenance: a run in netCDF, opened back with xarray, and rerun from its record
====================================================================================================

A result that leaves the process should say what it is and where it came from. :meth:`frictionsim.Result.to_netcdf`
writes a run as netCDF-4 (``frictionsim[io]``: xarray and h5netcdf): every state over ``time`` with its unit, the
stick/slip switches over their own ``event`` dimension, and in the file's attributes the provenance record of
:mod:`frictionsim.provenance`: the frictionsim version (and git revision from a source tree), the rig's and friction
law's ``repr`` and parameters with units, the solver options and counters, the UTC time and the platform.

Here paper 001's torsional rig at the Fig. 7 operating point is run, saved, opened back with plain xarray, and
rebuilt from the ``repr`` its file recorded; the rerun reproduces the file to the last bit.
"""

import json
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

import frictionsim as fs
from frictionsim import io

# %%
# A run with events and a stop condition
# --------------------------------------
# 20 s from rest at w_ref = 5.76 rad/s, N2 = 35 N (Fig. 7), sampled every 5 ms. Besides the stick/slip switches
# that the engine always locates, a non-terminal stop condition records every time the disc overshoots twice
# w_ref, the breakaway of each stick-slip cycle.
rig = fs.TorsionalRig(fs.torsional.fig7_friction(), reference_speed=5.76)
overshoot = fs.StopCondition(state="disc_speed", level=2 * 5.76, direction=1, terminal=False)
times = np.linspace(0.0, 20.0, 4001)
result = fs.simulate(rig, 20.0, output_times=times, rtol=1e-8, atol=1e-10, events=[overshoot])
print(result)

# %%
# Saved and opened back
# ---------------------
# The file is self-describing: any netCDF reader (xarray, ncdump, Panoply, MATLAB's ncread) sees the variables,
# their units, and the global attributes. xarray needs nothing from frictionsim to read it.
with tempfile.TemporaryDirectory() as scratch:
    path = result.to_netcdf(Path(scratch) / "fig7_torsional.nc")
    print(f"{path.name}: {path.stat().st_size / 1e3:.0f} kB")
    with xr.open_dataset(path) as opened:
        dataset = opened.load()  # read everything before the directory goes
print(dataset)

# %%
# The variables carry their units, which xarray's own plots put on the axes; the events are a table of their own
# (time, the contact's mode before and after, the state on both sides of each switch).
fig, (ax_w, ax_e) = plt.subplots(1, 2, figsize=(12, 4), layout="constrained")
dataset["drive_speed"].sel(time=slice(12.0, 20.0)).plot(ax=ax_w, lw=1.0, ls="--", color="C1", label="drive")
dataset["disc_speed"].sel(time=slice(12.0, 20.0)).plot(ax=ax_w, lw=1.0, color="C0", label="disc")
late = dataset["stop_time"].values
ax_w.plot(late[late >= 12.0], np.full(np.sum(late >= 12.0), 2 * 5.76), "rv", label="disc speed crosses 2 w_ref")
ax_w.set_ylim(top=17.0)
ax_w.legend(fontsize=8, loc="upper left", ncol=3)
ax_w.set_title("from the file: speeds, labelled with the file's units")
events = dataset[["event_time", "event_mode_before", "event_mode_after"]].to_dataframe()
print(events.head(6).to_string())
# the stick-slip period: from one stick to the next, after the start-up's first cycle
sticks = events[events["event_mode_after"] == "stick"]["event_time"].to_numpy()[1:]
periods = np.diff(sticks)
print(f"{len(sticks)} sticks; period over the last ten {periods[-10:].mean():.4f} s = "
      f"{1 / periods[-10:].mean():.3f} Hz (paper 001, Fig. 7: {fs.torsional.FIG7['frequency_measured']} Hz measured)")
ax_e.plot(sticks[1:], periods, "o-")
ax_e.set(xlabel="time of the stick [s]", ylabel="time since the previous stick [s]",
         title="the stick-slip period, from the event log")

# %%
# The provenance record
# ---------------------
# The whole record is one JSON attribute, ``metadata`` (:func:`frictionsim.io.metadata` reads it back); the
# headline fields are also flat attributes (``source``, ``created_utc``, ``rig``) for tools that list them. The
# rig's and the law's parameters are in it with their units, read off the engine's parameter tables.
record = io.metadata(dataset)
print(f"{record['schema']}: frictionsim {record['frictionsim']['version']}, run at {record['created_utc']}")
print("platform:", ", ".join(f"{key} {value}" for key, value in record["platform"].items()))
rig_record = record["rigs"][0]
print(f"rig: {rig_record['type']}, friction law: {rig_record['friction']['type']}")
for name, parameter in {**rig_record["parameters"], **rig_record["friction"]["parameters"]}.items():
    print(f"  {name:26s} {parameter['value']:<14.10g} {parameter['unit']}")
options = record["solver_options"]
print("solver options:", json.dumps({key: options[key] for key in ("method", "rtol", "atol", "output_times",
                                                                   "stop_conditions")}))
print("solver stats:", json.dumps(record["solver_stats"]))

# %%
# Rebuilt from the record, rerun to the bit
# -----------------------------------------
# The recorded ``repr`` is Python that rebuilds the rig and its friction law; the solver options and the stop
# condition's ``repr`` are in the record too, and the output grid is the file's ``time``. The rerun gives the
# same states bit for bit, and the same solver counters.
namespace = {name: getattr(fs, name) for name in fs.__all__}
rebuilt = eval(rig_record["repr"], namespace)  # noqa: S307 - the record is frictionsim's own
again = fs.simulate(rebuilt, float(dataset.attrs["t_reached"]), output_times=dataset["time"].values,
                    rtol=options["rtol"], atol=options["atol"], method=options["method"],
                    events=[eval(c, namespace) for c in options["stop_conditions"]])  # noqa: S307
same = all(np.array_equal(again[name], dataset[name].values) for name in again.state_names)
print(f"rebuilt: {rebuilt!r}")
print(f"states bit-identical: {same}; solver counters equal: {again.stats == record['solver_stats']}")
assert same and again.stats == record["solver_stats"]
plt.show()
