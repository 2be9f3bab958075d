"""
Torsional stick-slip: a limit cycle and a stick-slip map (paper 001)
====================================================================

Paper 001's rig is a small drill string: a DC motor turns, through a gear, a flexible shaft whose lower end
carries a disc braked by friction under the normal force N2 (eqs 1-5, Tables 1-2). At the Fig. 7 operating
point (reference speed w_ref = 5.76 rad/s, N2 = 35 N) the disc does not turn smoothly: it sticks while the shaft
winds up, then breaks away and overshoots to more than twice w_ref, the torsional stick-slip of a drill bit.

The paper's friction torque on the disc is eq 6, a hysteretic law with a branch for accelerating and one for
decelerating. :func:`frictionsim.torsional.fig7_friction` is that law with coefficients chosen to reproduce
Fig. 7 (the paper prints none): 0.83-0.84 Hz and a peak of 13.55-14 rad/s.
"""

from concurrent.futures import ThreadPoolExecutor

import matplotlib.pyplot as plt

import frictionsim as fs
from frictionsim import torsional

# %%
# The limit cycle at Fig. 7's operating point
# -------------------------------------------
# 40 s from rest, sampled every millisecond; the limit cycle is measured over the last 20 s.
rig, result = torsional.simulate_fig7(t_end=40.0)
cycle = torsional.limit_cycle(result, transient=20.0)
print(cycle)
print(f"paper 001, Fig. 7: {torsional.FIG7['frequency_measured']} Hz measured, "
      f"{torsional.FIG7['frequency_simulated']} Hz simulated; peak {torsional.FIG7['peak_measured']} / "
      f"{torsional.FIG7['peak_simulated']} rad/s; disc-on-shaft natural frequency "
      f"{rig.natural_frequency:.3f} Hz")

# %%
# :mod:`frictionsim.plots` draws a Result into the Axes it is given: the speeds over the last six seconds, and the
# phase portrait (Fig. 7b), the disc speed against the shaft's twist, one closed curve in the limit cycle.
fig, (ax_t, ax_p) = plt.subplots(1, 2, figsize=(12, 4.5), layout="constrained")
fs.plots.disc_speed_figure(result, window=(34.0, 40.0), reference_speeds=[rig.reference_speed], ax=[ax_t],
                           title=f"stick-slip at {cycle.frequency:.3f} Hz")
fs.plots.phase_portrait_figure(result, window=(20.0, 40.0), ax=ax_p)

# %%
# While it sticks, the disc is held by the friction torque; it breaks away when the shaft's torque exceeds the
# static limit. The share of the cycle spent stuck:
print(f"stick fraction {cycle.stick_fraction:.2f}, trough {cycle.trough:.2g} rad/s over {cycle.cycles} cycles; "
      f"severity (peak - trough) / (2 mean) = {cycle.severity:.2f}")

# %%
# Where does the rig stick-slip?
# ------------------------------
# One simulation per (w_ref, N2) point, run on two threads (the engine releases the GIL while it integrates).
# Faster rotation or a lighter normal force cures the stick-slip, as drillers find on a rig.
speeds = [2.0, 4.0, 5.76, 8.0, 10.0, 13.0, 16.0, 20.0]
forces = [15.0, 25.0, 35.0, 50.0, 70.0]
with ThreadPoolExecutor(max_workers=2) as pool:
    smap = torsional.stick_slip_map(speeds, forces, executor=pool, t_end=30.0, transient=15.0)
print(f"{smap.stick_slip.sum()} of {smap.stick_slip.size} points stick-slip; the sweep took "
      f"{smap.sweep.elapsed:.1f} s")

# %%
# The map's ``plot`` colours one measure per panel: the stick-slip severity index (peak-to-peak disc speed over
# twice its mean: 1 when the disc stops and overshoots to 2 w_ref) and the peak speed over w_ref.
fig, (ax_s, ax_r) = plt.subplots(1, 2, figsize=(13, 5), layout="constrained")
smap.plot("severity", ax=ax_s, point=(5.76, 35.0))
smap.plot("peak_ratio", ax=ax_r, point=(5.76, 35.0))
plt.show()
