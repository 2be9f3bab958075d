"""
Friction reduction by axial vibration: Coulomb vs Dahl (paper 000, Fig. 7)
==========================================================================

Paper 000 slides a shale specimen on 45 steel at v_d = 60 mm/min under F_N = 90 N while the counterface
vibrates axially, u0 = 5 mm at 17 Hz (Table 4, run VS3). The specimen hangs on the drive spring k_d; its
mass m and the spring are the rig of eqs 5-7. Whenever the vibration reverses the relative velocity
v_r = v - u0 w cos(w t), the friction force changes sign, so its mean over a cycle, the F_df that drags the
string, falls below the sliding friction mu F_N.

Coulomb friction (eq 8) flips the force at every reversal; Dahl friction (eq 9) builds it up over a finite
deflection (k_t = 40 N/mm, Fig. 10). Here are both, side by side, then the reduction 1 - F_df / (mu F_N)
against the velocity ratio v_d / v_a, with the closed form 1 - (2/pi) asin(v_d / v_a) of a prescribed
motion (eq 8 averaged over a cycle).
"""

import matplotlib.pyplot as plt
import numpy as np

import frictionsim as fs
from frictionsim import axial

# %%
# The Fig. 7(a) rig with both laws
# --------------------------------
# ``fig7a_laws()`` gives Coulomb and Dahl with mu = 0.41 (Table 4, dry: F_sf / F_N = 0.4097); the rig's
# defaults are Fig. 7(a)'s operating point. We record the last three vibration cycles of a 2 s run.
params = axial.fig7a_rig_parameters()
period = 1.0 / params["frequency"]
t_end = 2.0
times = np.linspace(t_end - 3 * period, t_end, 1200)

runs = {}
for name, law in axial.fig7a_laws().items():
    rig = fs.AxialVibrationRig(friction=law)
    runs[name] = fs.simulate(rig, t_end, output_times=times)
    print(f"{name:8s} F_df over the last 10 cycles: "
          f"{axial.axial_mean_friction(friction=law, t_end=t_end, transient=t_end - 10 * period):.3f} N "
          f"(mu F_N = {law.mu * params['normal_force']:.1f} N)")

# %%
# ``Result.plot(ax=)`` draws a run's friction force against time into a panel of our figure. The relative
# velocity is the specimen's velocity minus the counterface's, v_r = v - u0 w cos(w t)
# (``rig.surface_velocity(t)``).
fig, (ax_t, ax_v) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
for name, result in runs.items():
    result.plot(ax=ax_t, label=name)
    ax_v.plot(result.velocity - rig.surface_velocity(result.t), result.friction_force, label=name)
ax_t.set(title="three vibration cycles")
ax_t.legend()
ax_v.set(xlabel="relative velocity v_r [m/s]", ylabel="friction force F [N]", title="force against v_r")
ax_v.axvline(0.0, color="0.7", lw=0.8)

# %%
# The friction reduction against v_d / v_a
# ----------------------------------------
# ``reduction_sweep`` runs, for each velocity ratio, the kinematic rig with Coulomb friction (the closed
# form's set-up, simulated) and the axial rig with both laws, and puts Table 4's measured run and Table 5's
# power law beside them where the paper has data. The simulated kinematic rig lies on the closed form; on
# the spring-mass rig the specimen follows a slow vibration, so v_r reverses less and the reduction is
# smaller, much more so for Coulomb (which sticks) than for Dahl (which yields elastically). At the paper's own
# run (VS3, v_d / v_a = 0.002, the leftmost point) both ideal laws predict almost no friction left, while the rig
# measured a 75 % reduction; Table 5's power law (eq 17), fitted to the measured runs, is the paper's description
# of that (see the Table 5 example).
ratios = [0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.95, 1.5]
sweep = axial.reduction_sweep(ratios)
print(sweep[["velocity_ratio", "coulomb_closed_form", "kinematic_coulomb", "axial_coulomb", "axial_dahl",
             "table4_dry", "table5_dry"]].round(3).to_string(index=False))

fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
fine = np.linspace(1e-3, 1.5, 300)
ax.plot(fine, [100 * axial.coulomb_reduction(r) for r in fine], color="0.3",
        label="closed form 1 - (2/pi) asin(v_d/v_a)")
fs.plots.reduction_sweep_figure(sweep, [("kinematic_coulomb", "kinematic rig, Coulomb"),
                                        ("axial_coulomb", "axial rig, Coulomb (eq 8)"),
                                        ("axial_dahl", "axial rig, Dahl (eq 9)"),
                                        ("table4_dry", "Table 4, dry (VS3, measured)"),
                                        ("table5_dry", "Table 5 power law, dry (eq 17)")],
                                title="friction reduction against the velocity ratio", ax=ax)
ax.set_ylim(-5, 105)
ax.legend(fontsize=8)
plt.show()
