"""
Choosing a friction law: AIC, Akaike weights and profile-likelihood intervals
=============================================================================

A sliding contact is driven with a prescribed relative velocity that reverses often, and its friction force is
recorded with noise. Which law describes it: Dahl (paper 000, eq 9: a force that builds up over a pre-sliding
deflection), LuGre (Canudas de Wit et al. 1995: Dahl plus a Stribeck peak and bristle damping), or a static
Stribeck curve (no pre-sliding at all)?

:func:`frictionsim.fit.compare_laws` fits each law to the same record by output-error least squares and ranks
them by the Akaike information criterion, AIC = 2k - 2 ln L (Burnham & Anderson 2002), with delta-AIC and
Akaike weights. Here the record comes from a Dahl contact with paper 000's Fig. 10 stiffness, so we know the
answer; the example shows how the statistics reach it, and what the profile-likelihood intervals of
:meth:`~frictionsim.fit.IdentificationResult.conf_interval` say that the Wald intervals value +- t stderr do not.
"""

import matplotlib.pyplot as plt
import numpy as np

import frictionsim as fs

N = 90.0  # F_N [N], paper 000's normal force
TRUTH = fs.Dahl(mu=0.41, tangential_stiffness=4e4, exponent=1.0)  # k_t = 40 N/mm (Fig. 10)
NOISE = 1.5  # standard deviation of the force noise [N]


def drive(t):
    """Two tones: a slow sweep to 20 mm/s and a faster ripple that reverses the sliding near each turn."""
    return 0.02 * np.sin(2 * np.pi * t) + 0.005 * np.sin(2 * np.pi * 5 * t)


def friction(t, v):
    """The true contact's friction force [N] under v_r(t), from rest."""
    rig = fs.KinematicRig(TRUTH, relative_velocity=(t, v), normal_force=N)
    return fs.simulate(rig, t[-1], output_times=t, rtol=1e-10, atol=1e-12).friction_force


# %%
# The record and the ranking
# --------------------------
# Two seconds at 400 Hz. LuGre contains Dahl (mu_s = mu, sigma_1 = sigma_2 = 0 and sigma_0 = k_t give eq 9 with
# alpha = 1): a local search only finds that nesting point if it starts near it, so LuGre gets a start there
# through ``law_options`` (see the notes of :func:`~frictionsim.fit.compare_laws`).
t = np.linspace(0.0, 2.0, 801)
v = drive(t)
force = friction(t, v) + np.random.default_rng(7).normal(0.0, NOISE, t.size)
record = {"t": t, "relative_velocity": v, "friction_force": force, "normal_force": N}

near_dahl = dict(mu=0.4, mu_static=0.4, stribeck_velocity=0.01, bristle_stiffness=3e4, bristle_damping=0.0,
                 viscous_damping=0.0)
ranking, fits = fs.fit.compare_laws(record, ["dahl", "lugre", "stribeck"],
                                    law_options={"lugre": {"initial_guess": near_dahl}}, return_results=True)
print(ranking[["law_name", "k", "rss", "rms_residual", "aic", "delta_aic", "akaike_weight", "bic"]]
      .to_string(float_format=lambda x: f"{x:.4g}"))
assert ranking.index[0] == "dahl" and ranking.loc["stribeck", "delta_aic"] > 100.0  # the record's law first

# %%
# Dahl ranks first (k counts the fitted parameters and the noise variance). LuGre fits the record about as well
# (its RSS is a hair lower, as it must be for a law that contains Dahl) but pays 2 for each of its three extra
# parameters: delta-AIC about 5, a few per cent of the Akaike weight. The static Stribeck curve has no
# pre-sliding: at every reversal its force jumps from -mu_s N to +mu_s N where the record's force turns over
# k_t's deflection; its residual is more than ten times the noise and its weight zero. Each fit's ``plot(ax=)``
# draws the record and the model into a panel of our figure.
dahl, lugre, stribeck = fits["dahl"], fits["lugre"], fits["stribeck"]
print(f"noise {NOISE} N; rms residual Dahl {dahl.rms_residual:.3f} N, LuGre {lugre.rms_residual:.3f} N, "
      f"Stribeck {stribeck.rms_residual:.2f} N")

fig, (ax_t, ax_v, ax_w) = plt.subplots(1, 3, figsize=(14, 4), layout="constrained",
                                       gridspec_kw={"width_ratios": [1.4, 1.0, 0.7]})
dahl.plot(ax=ax_t, color="C0", lw=1.2)
ax_t.plot(stribeck.t, stribeck.model, color="C3", lw=1.0, label=f"Stribeck fit (R$^2$ = {stribeck.r_squared:.3f})")
ax_t.set(xlim=(0.6, 1.4), title="record and fits (a window)")
ax_t.legend(fontsize=8, loc="lower left")
ax_v.plot(v, force, ".", ms=2, color="0.6", label="record")
ax_v.plot(v, dahl.model, color="C0", lw=0.8, label="Dahl")
ax_v.plot(v, stribeck.model, color="C3", lw=0.8, label="Stribeck")
ax_v.set(xlabel="relative velocity v_r [m/s]", ylabel="friction force [N]", title="force against v_r")
ax_v.legend(fontsize=8)
ax_w.bar(ranking["law_name"], ranking["akaike_weight"], color=["C0", "C1", "C3"])
for x, (weight, delta) in enumerate(zip(ranking["akaike_weight"], ranking["delta_aic"])):
    ax_w.annotate(f"dAIC {delta:.3g}", (x, weight), xytext=(0, 3), textcoords="offset points", ha="center",
                  fontsize=8)
ax_w.set(ylabel="Akaike weight", ylim=(0, 1.1), title="which law the record supports")

# %%
# Does the chosen law predict a record it was not fitted to?
# ----------------------------------------------------------
# ``eval(t, v, N)`` runs a fit's own forward model (same rig, integrator and tolerances) on new inputs: here a
# faster, larger drive, from rest (``initial_state="zero"``), against the true contact without noise.
t_new = np.linspace(0.0, 1.0, 401)
v_new = 0.03 * np.sin(2 * np.pi * 3 * t_new)
true_new = friction(t_new, v_new)
for name, fit in fits.items():
    error = fit.eval(t_new, v_new, N, initial_state="zero") - true_new
    print(f"{fit.law_name:9s} prediction error on the new drive: rms {np.sqrt(np.mean(error ** 2)):.3f} N")

# %%
# What the record says about each parameter
# -----------------------------------------
# Dahl's three parameters are well determined: the likelihood is close to quadratic around the optimum, and the
# profile-likelihood intervals agree with the Wald ones to a few per cent of their width.
print(dahl.conf_interval().to_string(float_format=lambda x: f"{x:.5g}"))

# %%
# LuGre's extra parameters are another matter. The data put them at zero (the true contact is Dahl), at the edge
# of what is physical: the Wald interval, symmetric about the estimate, runs into negative damping and a static
# coefficient below the Coulomb one; the profile likelihood holds each parameter along a path and refits the
# others, stops at the bound, and says so (``closed`` False: the data do not bound it from below at 95 %).
# Only an upper limit is learned from this record. (mu_static is searched, and profiled, as its excess over mu.)
lugre_ci = lugre.conf_interval(["mu_static", "bristle_damping", "viscous_damping"])
print(lugre_ci.to_string(float_format=lambda x: f"{x:.4g}"))
assert (lugre_ci["wald_lower"] < 0.0).all() and (lugre_ci["lower"] >= 0.0).all() and not lugre_ci["closed"].any()

units = {"mu_static_excess": "mu_s - mu [-]", "bristle_damping": "sigma_1 [N s/m]",
         "viscous_damping": "sigma_2 [N s/m]"}
fig, axes = plt.subplots(1, 3, figsize=(12, 3.2), layout="constrained")
for ax, (name, row) in zip(axes, lugre_ci.iterrows()):
    ax.plot([row["wald_lower"], row["wald_upper"]], [1, 1], "s-", color="C1", lw=3, label="Wald: value +- t stderr")
    ax.plot([row["lower"], row["upper"]], [0, 0], "o-", color="C0", lw=3, label="profile likelihood")
    ax.plot(row["value"], 0.5, "kx", ms=9, label="estimate")
    ax.axvline(0.0, color="C3", ls=":", label="truth (Dahl) and the bound")
    ax.set(yticks=[], ylim=(-0.7, 1.7), xlabel=units[name], title=f"LuGre {name.replace('_', ' ')}, 95 %")
fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncol=4, fontsize=8)
plt.show()
