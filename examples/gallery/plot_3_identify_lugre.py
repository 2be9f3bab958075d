"""
Identifying LuGre friction from a noisy record, and what the record can tell
============================================================================

A contact is driven with a prescribed sliding speed, v_r = 0.1 sin(2 pi t) m/s, under F_N = 90 N, and its
friction force is recorded with 1 % noise. Which LuGre parameters (Canudas de Wit et al. 1995: Coulomb and
static coefficients, Stribeck velocity, bristle stiffness sigma_0 and damping sigma_1, viscous damping sigma_2)
does the record determine?

:func:`frictionsim.fit.identify_lugre` fits the law by output-error least squares: every residual is a
simulation of the C++ kinematic rig. It returns standard errors from the Jacobian, s^2 (J^T J)^-1, the
correlations, and an identifiability verdict per parameter (at a bound, a near-null direction of the scaled
Jacobian, or a relative standard error too large). :ref:`sphx_glr_gallery_plot_6_choose_friction_law.py` goes
on from here: which law a record supports (AIC), and profile-likelihood intervals beside these Wald ones.
"""

import matplotlib.pyplot as plt
import numpy as np

import frictionsim as fs

N = 90.0  # F_N [N]
TRUTH = dict(mu=0.3, mu_static=0.45, stribeck_velocity=0.01, bristle_stiffness=1e5, bristle_damping=300.0,
             viscous_damping=20.0)


def record(t, v, law, noise, seed):
    """The friction force of ``law`` under the prescribed v_r(t), plus Gaussian noise of ``noise`` N."""
    rig = fs.KinematicRig(law, relative_velocity=(t, v), normal_force=N)
    force = fs.simulate(rig, t[-1], output_times=t, rtol=1e-10, atol=1e-12).friction_force
    return force + np.random.default_rng(seed).normal(0.0, noise, t.size)


# %%
# A record that sweeps through the Stribeck region
# ------------------------------------------------
# Two seconds at 1 kHz: four reversals, ``|v_r|`` up to 0.1 m/s, ten times the Stribeck velocity.
t = np.linspace(0.0, 2.0, 2001)
v = 0.1 * np.sin(2 * np.pi * t)
noise = 0.01 * TRUTH["mu"] * N
force = record(t, v, fs.LuGre(**TRUTH), noise, seed=3)

guess = dict(mu=0.25, mu_static=0.5, stribeck_velocity=0.02, bristle_stiffness=5e4, bristle_damping=150.0,
             viscous_damping=10.0)
fit = fs.fit.identify_lugre(t, v, force, N, initial_guess=guess)
print(fit.summary())

# %%
# Every parameter lies within a few standard errors of the truth, and the residual is the noise.
table = fit.to_pandas()[["value", "stderr", "identifiable"]]
table["truth"] = [TRUTH[name] for name in table.index]
table["error / stderr"] = (table["value"] - table["truth"]) / table["stderr"]
print(table.to_string(float_format=lambda x: f"{x:.4g}"))
print(f"rms residual {fit.rms_residual:.3f} N against noise {noise:.3f} N")

fig, axes = plt.subplots(1, 3, figsize=(13, 4), layout="constrained")
axes[0].plot(v, fit.measured, ".", ms=1.5, color="0.6", label="record")
axes[0].plot(v, fit.model, lw=1.0, label="fitted LuGre")
axes[0].set(xlabel="v_r [m/s]", ylabel="friction force [N]", title="force against sliding speed")
axes[0].legend(fontsize=8)
axes[1].plot(fit.t, fit.residuals, lw=0.5)
axes[1].axhline(2 * noise, color="r", ls=":", lw=0.8)
axes[1].axhline(-2 * noise, color="r", ls=":", lw=0.8)
axes[1].set(xlabel="t [s]", ylabel="model - record [N]", title="residuals (dotted: 2 sigma of the noise)")
image = axes[2].imshow(fit.correlation, vmin=-1, vmax=1, cmap="RdBu_r")
labels = [name.replace("_", " ") for name in fit.fitted]
axes[2].set_xticks(range(len(labels)), labels, rotation=60, ha="right", fontsize=7)
axes[2].set_yticks(range(len(labels)), labels, fontsize=7)
axes[2].set_title("correlation of the estimates")
fig.colorbar(image, ax=axes[2])

# %%
# A quasi-static record cannot see the bristle damping
# ----------------------------------------------------
# Now the contact creeps: ``|v_r| <= 2 mm/s`` over ten seconds. The bristle damping force sigma_1 dz/dt only shows
# in fast presliding transients, here far below the noise: the fit flags it as not identifiable instead of
# returning a number that means nothing, while mu and sigma_0 are still determined.
t_slow = np.linspace(0.0, 10.0, 2001)
v_slow = 2e-3 * np.sin(2 * np.pi * 0.1 * t_slow)
slow_truth = fs.LuGre(0.3, 0.45, 5e-4, 1e5, 300.0, 20.0)
slow = fs.fit.identify_lugre(t_slow, v_slow, record(t_slow, v_slow, slow_truth, noise, seed=3), N)
for name in slow.fitted:
    print(f"{name:18s} {slow.params[name]:11.4g} +/- {slow.stderr[name]:<10.3g} {slow.reasons[name]}")

fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
names = list(slow.fitted)
rel = [min(slow.relative_stderr[n], 10.0) for n in names]
colors = ["tab:green" if slow.identifiable[n] else "tab:red" for n in names]
ax.bar(range(len(names)), rel, color=colors)
ax.set_yscale("log")
ax.set_xticks(range(len(names)), [n.replace("_", " ") for n in names], rotation=30, ha="right")
ax.set(ylabel="relative standard error (capped at 10)", title="quasi-static record: green identified, red not")
plt.show()
