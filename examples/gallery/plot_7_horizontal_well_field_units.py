"""
Torque and drag in a horizontal well, in field units, with a hydraulic oscillator
=================================================================================

The packaged survey ``horizontal_3km.csv`` is a well that goes vertical to 1200 m, builds at 4 deg/30 m to
horizontal and runs a 3 km lateral. A 5" drill string is slid into it on a soft-string model (Johancsik,
Friesen & Dawson 1984: :class:`frictionsim.SoftString`), and a hydraulic oscillator (an axial vibration tool)
is put in the string to get weight to the bit while sliding.

Everything is given as a drilling engineer would give it: pipe sizes in inches, lengths in feet, mud weight in
ppg, forces in klbf, rotary speed in rpm. The engine stays SI: :mod:`frictionsim.units` converts every value that
carries a unit to the unit of the parameter's table at the boundary (pint, ``frictionsim[units]``), and
:func:`frictionsim.units.convert` turns the results back into field units for the plots.
"""

from importlib import resources

import matplotlib.pyplot as plt
import numpy as np

import frictionsim as fs
from frictionsim import wells
from frictionsim.units import convert, to_si

survey = wells.read_survey(resources.files("frictionsim").joinpath("data", "horizontal_3km.csv"))
path = wells.trajectory(survey)


def klbf(newtons):
    """Forces back in field units (the engine's are in N)."""
    return convert(np.asarray(newtons), "N", "klbf")


def ft(metres):
    """Depths back in field units (the engine's are in m)."""
    return convert(np.asarray(metres), "m", "ft")


# %%
# The string and the hole in field units
# --------------------------------------
# 15,420 ft of 5" drill pipe (19.5 lb/ft: 4.276" bore) over 492 ft of 6 1/2" collars; 10 ppg mud in an
# 8 1/2" hole. A bare number would be SI; a string with a unit is converted by the parameter's own table
# (``PipeSection.parameters``: outer_diameter in m, ...), so a wrong kind of unit is an error naming the parameter.
string = fs.DrillString([fs.PipeSection(outer_diameter="5 in", inner_diameter="4.276 in", length="15420 ft"),
                         fs.PipeSection(outer_diameter="6 1/2 in", inner_diameter="2 13/16 in", length="492 ft")])
hole = dict(mud_density="10 ppg", hole_diameter="8 1/2 in")
print(f"string {convert(string.length, 'm', 'ft'):.0f} ft = {string.length:.1f} m; "
      f"mud {hole['mud_density']} = {to_si(hole['mud_density'], 'kg/m^3'):.1f} kg/m^3")
try:
    fs.PipeSection(outer_diameter="5 klbf", length=10.0)
except fs.units.UnitError as error:
    print("a unit of the wrong kind:", error)

FACTORS = (0.15, 0.25, 0.35)  # open- and cased-hole friction factors of the broomstick
ABOVE_BIT = to_si("1000 ft", "m")  # the oscillator's height above the bit
TOOL = dict(force_amplitude="13.5 klbf", frequency="18 Hz")  # about 60 kN at 18 Hz

# %%
# The broomstick, with and without the oscillator
# -----------------------------------------------
# Hook load (less the block weight) against bit depth while the string is run in every 500 ft: pick-up,
# slack-off and rotating off bottom at 120 rpm, per friction factor (:func:`frictionsim.wells.broomstick`). Then
# the same string slid in at the drilling rate with no weight on the bit, with the oscillator 1000 ft above the
# bit (``SoftString.oscillators``): without the tool, sliding in is the slack-off line (Coulomb friction does not
# depend on the speed).
chart = wells.broomstick(survey, string, FACTORS, depth_step=to_si("500 ft", "m"), rotary_speed="120 rpm", **hole)
rows = []
for depth in sorted(set(chart.frame["bit_depth"])):
    if depth <= ABOVE_BIT:
        continue
    model = wells.soft_string(survey, wells.string_to_depth(string, depth))
    tool = fs.HydraulicOscillator(measured_depth=depth - ABOVE_BIT, **TOOL)
    for mu in FACTORS:
        run = model.oscillators("sliding_drilling", tool, weight_on_bit=0.0, open_hole_friction=mu,
                                cased_hole_friction=mu, **hole)
        rows.append((depth, mu, run.vibrated.hook_load))
with_tool = np.array(rows)

fig, (ax_path, ax_broom) = plt.subplots(1, 2, figsize=(13, 5.5), layout="constrained",
                                        gridspec_kw={"width_ratios": [1.0, 1.2]})
ax_path.plot(ft(np.hypot(path["north"], path["east"])), ft(path["tvd"]), "-o", ms=1.5)
ax_path.invert_yaxis()
ax_path.set(xlabel="horizontal departure [ft]", ylabel="true vertical depth [ft]", title="the well (vertical section)")
styles = dict(zip(FACTORS, ["-", "--", ":"]))
for op, color, label in (("trip_out", "C3", "pick-up"), ("trip_in", "C0", "slack-off"),
                         ("rotating_off_bottom", "C2", "rotating, 120 rpm")):
    for mu in FACTORS[:1] if op == "rotating_off_bottom" else FACTORS:
        depth, load = chart.hook_loads(op, mu)
        ax_broom.plot(klbf(load), ft(depth), color=color, ls=styles[mu],
                      label=label if op == "rotating_off_bottom" else f"{label}, mu = {mu:g}")
for mu in FACTORS:
    part = with_tool[with_tool[:, 1] == mu]
    ax_broom.plot(klbf(part[:, 2]), ft(part[:, 0]), color="darkorange", ls=styles[mu], lw=2,
                  label=f"sliding in with the oscillator, mu = {mu:g}")
ax_broom.invert_yaxis()
ax_broom.set(xlabel="hook load [klbf] (less the block weight)", ylabel="bit depth, measured [ft]",
             title="broomstick: 13.5 klbf oscillator 1000 ft above the bit")
ax_broom.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
ax_broom.grid(alpha=0.3)

# %%
# In the lateral, the wall friction of the pipe's own weight eats the weight above it: at mu = 0.35 the
# slack-off hook load falls towards zero, where the string would have to be pushed. The oscillator's vibration
# reverses the sliding over the lower part of the string and cuts its friction there, and that weight comes
# back to the hook.
deepest = with_tool[with_tool[:, 0] == with_tool[:, 0].max()]
for mu, load in deepest[:, 1:]:
    _, slack = chart.hook_loads("trip_in", mu)
    print(f"mu = {mu:.2f} at TD: slack-off {klbf(slack[-1]):6.1f} klbf, sliding in with the tool "
          f"{klbf(load):6.1f} klbf")
    assert load > slack[-1]  # the tool only gives weight back to the hook

# %%
# The zone of influence
# ---------------------
# With the bit at TD and 5 klbf on it, sliding: the tool's wave is damped by the very friction it reduces, so it
# reaches only so far. Along the string, the vibration's velocity amplitude, the axial friction factor as a share
# of the plain one, and the effective tension with and without the tool; the shaded band is the zone of
# influence (where the friction is reduced by more than 5 %).
conditions = dict(hole, open_hole_friction=0.25, cased_hole_friction=0.25)
model = wells.soft_string(survey, string)
tool = fs.HydraulicOscillator(measured_depth=string.length - ABOVE_BIT, **TOOL)
run = model.oscillators("sliding_drilling", tool, weight_on_bit="5 klbf", **conditions)
print(f"zone of influence {ft(run.zone_top):.0f}-{ft(run.zone_bottom):.0f} ft MD ({ft(run.zone_length):.0f} ft); "
      f"hook load {klbf(run.plain.hook_load):.1f} -> {klbf(run.vibrated.hook_load):.1f} klbf")

nodes = ft(model.node_depths)
middle = 0.5 * (nodes[1:] + nodes[:-1])
fig, (ax_a, ax_f, ax_t) = plt.subplots(3, 1, figsize=(10, 7), sharex=True, layout="constrained")
ax_a.plot(middle, run.vibration_amplitude, color="darkorange")
ax_a.set(ylabel="vibration amplitude [m/s]", title="13.5 klbf, 18 Hz oscillator 1000 ft above the bit, sliding")
ax_f.plot(middle, run.axial_factor, color="C0")
ax_f.set(ylabel="axial friction / plain [-]", ylim=(-0.05, 1.1))
ax_t.plot(ft(run.plain.measured_depth), klbf(run.plain.tension), label="without the tool")
ax_t.plot(ft(run.vibrated.measured_depth), klbf(run.vibrated.tension), label="with the tool")
ax_t.set(xlabel="measured depth [ft]", ylabel="effective tension [klbf]")
ax_t.legend(fontsize=8)
for ax in (ax_a, ax_f, ax_t):
    ax.axvspan(ft(run.zone_top), ft(run.zone_bottom), color="darkorange", alpha=0.12)
    ax.axvline(ft(tool.measured_depth), color="k", lw=0.8, ls=":")
    ax.grid(alpha=0.3)

# %%
# Where to put it
# ---------------
# :func:`frictionsim.wells.place_oscillators` scans the tool's depth and refines the best one with
# ``scipy.optimize`` over the C++ objective: the weight on bit transferred while sliding at the hook load that puts
# 5 klbf on the bit without a tool. :func:`~frictionsim.wells.plot_placement` draws the curve in SI into our Axes;
# secondary axes give it field units.
hook_load = model.run("sliding_drilling", weight_on_bit="5 klbf", **conditions).hook_load
placement = wells.place_oscillators(model, hook_load, force_amplitude=to_si(TOOL["force_amplitude"], "N"),
                                    frequency=to_si(TOOL["frequency"], "Hz"), scan_points=40, **conditions)
best = placement.depths[0]
print(f"best tool depth {ft(best):.0f} ft MD ({ft(string.length - best):.0f} ft above the bit): "
      f"{klbf(placement.weight_on_bit):.1f} klbf on the bit instead of "
      f"{klbf(placement.weight_on_bit_without):.1f} ({placement.evaluations} evaluations)")
assert placement.weight_on_bit >= placement.scan_weight_on_bit.max() > placement.weight_on_bit_without

fig, ax = plt.subplots(figsize=(9, 4.5), layout="constrained")
wells.plot_placement(placement, ax=ax, title="hydraulic oscillator placement")
top = ax.secondary_xaxis("top", functions=(ft, lambda feet: convert(np.asarray(feet), "ft", "m")))
top.set_xlabel("tool measured depth [ft]")
right = ax.secondary_yaxis("right", functions=(lambda kn: klbf(1e3 * np.asarray(kn)),
                                               lambda k: 1e-3 * convert(np.asarray(k), "klbf", "N")))
right.set_ylabel("weight on bit [klbf]")
plt.show()
