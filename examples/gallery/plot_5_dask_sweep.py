"""
A parameter sweep on a dask cluster: the friction-reduction map
===============================================================

How much does axial vibration reduce the drag of a sliding contact, over vibration amplitude and frequency?
One simulation of paper 000's axial rig (Dahl friction, Fig. 7(a)'s rig) per grid point, spread over a
cluster with :func:`frictionsim.sweep`. The same call takes a ``concurrent.futures`` executor or a
``dask.distributed.Client``: here a local cluster of two workers (on a real cluster, ``Client("tcp://...")``
with the scheduler's address), used through its concurrent.futures interface. The values come back in grid order
and are bit-for-bit those of a serial run.
"""

import matplotlib.pyplot as plt
import numpy as np
from dask.distributed import Client, LocalCluster

import frictionsim as fs
from frictionsim.axial import FIG7A_MU, axial_mean_friction, fig7a_rig_parameters

law = fs.Dahl(FIG7A_MU, 4e4)  # mu, k_t [N/m] (Fig. 10)
rig = fig7a_rig_parameters()
amplitudes = np.array([0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0]) * 1e-3  # u0 [m]
frequencies = np.array([2.0, 5.0, 10.0, 17.0, 25.0])  # f [Hz]
grid = {"amplitude": list(amplitudes), "frequency": list(frequencies)}

# %%
# Two workers in this process (``processes=False``): the engine releases the GIL while it integrates, so two
# threads run two simulations at once, and nothing has to be pickled or started. ``processes=True`` gives each
# worker its own interpreter, the choice for point functions that spend their time in Python; a script then
# creates the cluster under ``if __name__ == "__main__":``, since worker processes re-import it.
with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
        Client(cluster) as client:
    result = fs.sweep(axial_mean_friction, grid, fixed={"friction": law, "t_end": 3.0, "transient": 2.0},
                      executor=client, progress=False)
print(result)

# %%
# The mean friction force F_df [N] on the (amplitude, frequency) grid, and the reduction against sliding
# friction mu F_N. The dimensionless number of eq 16 is the velocity ratio v_d / v_a = v_d / (2 pi f u0):
# the reduction is large where the vibration's velocity amplitude dwarfs the sliding velocity.
mean_force = result.as_array()
reduction = 1.0 - mean_force / (FIG7A_MU * rig["normal_force"])
print(result.to_pandas().head())

# A serial spot check of one point: the cluster computed exactly this.
i, j = 4, 3
serial = axial_mean_friction(friction=law, t_end=3.0, transient=2.0, amplitude=amplitudes[i],
                             frequency=frequencies[j])
assert serial == mean_force[i, j], (serial, mean_force[i, j])

fig, (ax_map, ax_ratio) = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
mesh = ax_map.pcolormesh(frequencies, 1e3 * amplitudes, reduction, shading="nearest", cmap="magma", vmin=0, vmax=1)
fig.colorbar(mesh, ax=ax_map, label="friction reduction 1 - F_df / (mu F_N)")
ff, aa = np.meshgrid(frequencies, amplitudes)
ratio = rig["sliding_velocity"] / (2 * np.pi * ff * aa)
lines = ax_map.contour(ff, 1e3 * aa, ratio, levels=[0.01, 0.1, 1.0], colors="w", linewidths=0.8)
ax_map.clabel(lines, fmt="v_d/v_a = %g", fontsize=7)
ax_map.set(xlabel="frequency f [Hz]", ylabel="amplitude u0 [mm]", yscale="log", title="Dahl, axial rig")
ax_ratio.semilogx(ratio.ravel(), reduction.ravel(), "o", label="grid points (axial rig, Dahl)")
fine = np.geomspace(ratio.min(), 1.0, 200)
ax_ratio.semilogx(fine, [fs.axial.coulomb_reduction(r) for r in fine], "k-", lw=0.8,
                  label="closed form, prescribed motion, Coulomb")
ax_ratio.set(xlabel="velocity ratio v_d / v_a", ylabel="friction reduction", ylim=(-0.05, 1.05),
             title="the grid against the velocity ratio")
ax_ratio.legend(fontsize=8)
plt.show()
