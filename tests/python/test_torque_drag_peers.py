"""fs.SoftString side by side with the ``torque-drag`` package (PyPI ``torque-drag`` 0.1.1, Pro Well Plan; issue 14,
item 5) on the same surveys, where both compute the same quantity, every difference explained.

torque-drag's ``calc(trajectory, dimensions, densities, case, fric, wob, tbit, torque_calc)`` (torque_drag/main.py)
is Johancsik's explicit step (SPE 11380) over the survey's stations, with these conventions, each shown by a test:

* **A scalar friction factor is replaced by 0.24** (``if type(fric) is not list: point['fric'] = 0.24``): only a
  list (one value per station) is used. Every comparison below therefore passes a list.
* **Units**: pipe and hole diameters in inches converted with 1/39.37 m (0.02540005 m, not 0.0254), densities in
  specific gravity (x 1000 kg/m^3), g = 9.81 m/s^2 (ours 9.80665), forces in kN and torques in kN m; WOB in kN.
* **Buoyancy** ``1 - (rho_f A_a - rho_f A_ds) / (rho_d (A_a - A_ds))`` is 1 - rho_f / rho_d: the same mud inside
  and out, as ours (W = g (m - rho_mud V)).
* **One course off**: the course from station i to i + 1 takes the weight of the course *above* station i
  (``weight = w * delta_md`` of station i) and the inclination average of stations i - 1 and i; the top course
  (i = 0) has no weight (delta_md = 0) and averages station 0 with the *last* station (Python's index -1). So the
  hook load misses one course of pipe weight: w (L - dMD) in a vertical hole.
* **Side force** from the raw azimuth difference, ``F dA sin I_avg``: not wrapped (a course across north, 350 to 10
  degrees, turns by -340 degrees), where ours uses the dogleg, sqrt(beta^2 - dI^2). Axial weight W cos(I_avg) where
  ours takes the arc's exact dTVD.
* **WOB** is added at the bit as *tension* (the force at the bit is +wob), where a weight on bit compresses the bit
  (ours: -WOB).
* **Torque while tripping**: "hoisting" / "lowering" add the full mu F_n to the axial force *and* mu F_n r to the
  torque (no friction vector); only "static" (no axial friction, torque mu r sum F_n) is an operation of ours:
  rotating off bottom.

A replay of the step written here with either set of conventions (``_johancsik_step``) reproduces torque-drag to
round-off with its conventions and fs.SoftString (method johancsik) with ours: the whole difference is the list
above. The remaining difference on a curved well is first order in the station spacing (the one-course shift), and
halves with it. Skipped where torque-drag is not installed (extras ``test`` and ``bench``).
"""

import math

import numpy as np
import pytest

import frictionsim as fs

td = pytest.importorskip("torque_drag")

INCH_THEIRS = 1.0 / 39.37  # m, torque-drag's inch
G_THEIRS = 9.81
G_OURS = 9.80665  # standard gravity, soft_string.hpp
OD_IN, ID_IN, HOLE_IN = 5.0, 4.276, 8.5
STEEL_SG, MUD_SG = 7.85, 1.2


def _trajectory(md, inc_deg, azi_deg):
    """Stations in torque-drag's form (what well_profile's trajectories were): md [m], inc and azi [deg], and the
    change from the previous station. Built here, so the comparison does not depend on well_profile's versions."""
    points = []
    for i, (m, i_deg, a_deg) in enumerate(zip(md, inc_deg, azi_deg)):
        delta = ({"md": 0.0, "inc": 0.0, "azi": 0.0} if i == 0 else
                 {"md": m - md[i - 1], "inc": i_deg - inc_deg[i - 1], "azi": a_deg - azi_deg[i - 1]})
        points.append({"md": float(m), "inc": float(i_deg), "azi": float(a_deg), "delta": delta})
    return points


def _theirs(md, inc_deg, azi_deg, mu, *, wob=0.0):
    """torque-drag on the stations, its string from the surface to the last station; friction as a list."""
    length = float(md[-1])
    dims = {"pipe": {"od": OD_IN, "id": ID_IN, "length": length, "shoe": length}, "odAnn": HOLE_IN}
    fric = [mu] * len(md) if mu is not None else None
    return td.calc(_trajectory(md, inc_deg, azi_deg), dims, densities={"rhof": MUD_SG, "rhod": STEEL_SG},
                   case="all", fric=fric, wob=wob, torque_calc=True)


def _pipe(length):
    """The same pipe in SI: 5" x 4.276" steel of 7850 kg/m^3."""
    return fs.PipeSection(length=length, outer_diameter=OD_IN * 0.0254, inner_diameter=ID_IN * 0.0254,
                          density=STEEL_SG * 1000.0)


def _ours(md, inc_deg, azi_deg, method="johancsik"):
    survey = fs.Survey.from_degrees(np.asarray(md), np.asarray(inc_deg), np.asarray(azi_deg))
    kwargs = {} if method == "johancsik" else {"method": method}
    return fs.SoftString(survey, fs.DrillString([_pipe(float(md[-1]))]), len(md) - 1, **kwargs)


def _weight_per_length(theirs):
    """Buoyed weight per length [N/m]: torque-drag's (its inch, g 9.81) or ours."""
    inch, g = (INCH_THEIRS, G_THEIRS) if theirs else (0.0254, G_OURS)
    area = math.pi / 4 * ((OD_IN * inch) ** 2 - (ID_IN * inch) ** 2)
    return g * area * (STEEL_SG - MUD_SG) * 1000.0


def _radius(theirs):
    return OD_IN / 2 * (INCH_THEIRS if theirs else 0.0254)


def _johancsik_step(md, inc, azi, tvd, mu, direction, *, theirs):
    """Johancsik's explicit step from the bit up over the stations [m, rad], with torque-drag's conventions
    (theirs=True) or frictionsim's. Returns (tension [N], torque [N m]) per station, surface first. `direction`:
    +1 hoisting, -1 lowering, 0 static (the torque is mu r F_n in every case)."""
    n = len(md)
    w, r = _weight_per_length(theirs), _radius(theirs)
    force, torque = np.zeros(n), np.zeros(n)
    for top in range(n - 2, -1, -1):
        bottom = top + 1
        d_inc = inc[top] - inc[bottom]
        if theirs:  # the course above's weight and mean inclination; index -1 wraps to the bit
            weight = w * (md[top] - md[top - 1]) if top > 0 else 0.0
            i_avg = 0.5 * (inc[top] + inc[top - 1])
            lateral = (azi[top] - azi[bottom]) * math.sin(i_avg)  # not wrapped
            axial = weight * math.cos(i_avg)
        else:
            weight = w * (md[bottom] - md[top])
            i_avg = 0.5 * (inc[top] + inc[bottom])
            t1 = np.array([math.sin(inc[top]) * math.cos(azi[top]), math.sin(inc[top]) * math.sin(azi[top]),
                           math.cos(inc[top])])
            t2 = np.array([math.sin(inc[bottom]) * math.cos(azi[bottom]),
                           math.sin(inc[bottom]) * math.sin(azi[bottom]), math.cos(inc[bottom])])
            beta = 2.0 * math.atan2(np.linalg.norm(t1 - t2), np.linalg.norm(t1 + t2))
            lateral = math.sqrt(max(beta * beta - d_inc * d_inc, 0.0))
            axial = w * (tvd[bottom] - tvd[top])
        f = force[bottom]
        normal = math.hypot(f * lateral, f * d_inc + weight * math.sin(i_avg))
        force[top] = f + axial + direction * mu * normal
        torque[top] = torque[bottom] + mu * normal * r
    return force, torque


def _three_d_stations(spacing):
    """A build-and-turn well resampled every `spacing` m on its minimum-curvature arcs: vertical to 400 m, build
    and turn to 50 degrees at azimuth 70 by 1200 m, hold, drop and turn to 35 degrees at azimuth 95 by 2400 m, hold
    to 3000 m. Returns md [m], inclination and azimuth [deg], and the tvd [m] of the resampled survey's own
    minimum-curvature path (where a grid misses a coarse station its course is the chord arc, for both codes)."""
    coarse = fs.Survey.from_degrees(np.array([0.0, 400.0, 1200.0, 1800.0, 2400.0, 3000.0]),
                                    np.array([0.0, 0.0, 50.0, 50.0, 35.0, 35.0]),
                                    np.array([20.0, 20.0, 70.0, 70.0, 95.0, 95.0]))
    md = np.arange(0.0, 3000.0 + 0.5 * spacing, spacing)
    at = coarse.interpolate(md)
    inc, azi = np.degrees(at["inclination"]), np.degrees(at["azimuth"])
    return md, inc, azi, fs.Survey.from_degrees(md, inc, azi).tvd


# ------------------------------------------------------------------------------------------------------- tests
def test_a_scalar_friction_factor_is_replaced_by_0_24():
    """calc(fric=0.3) is calc(fric=[0.24, ...]): torque-drag 0.1.1 ignores a scalar friction factor."""
    md = np.linspace(0.0, 2000.0, 201)
    inc, azi = np.full(201, 60.0), np.full(201, 30.0)
    scalar = _theirs(md, inc, azi, None)  # fric=None, as a scalar: 0.24
    length = 2000.0
    dims = {"pipe": {"od": OD_IN, "id": ID_IN, "length": length, "shoe": length}, "odAnn": HOLE_IN}
    as_scalar = td.calc(_trajectory(md, inc, azi), dims, densities={"rhof": MUD_SG, "rhod": STEEL_SG},
                        fric=0.3, torque_calc=True)
    listed_024, listed_03 = _theirs(md, inc, azi, 0.24), _theirs(md, inc, azi, 0.3)
    for case in ("hoisting", "lowering"):
        assert as_scalar.force[case] == listed_024.force[case] == scalar.force[case]
        assert as_scalar.force[case][0] != pytest.approx(listed_03.force[case][0], rel=1e-3)
    assert as_scalar.torque["static"] == listed_024.torque["static"]


@pytest.mark.parametrize("inclination", [0.0, 35.0, 80.0])
def test_straight_inclined_pipe_closed_forms_and_the_missing_course(inclination):
    """On a straight hole both are closed forms: ours w L (cos I +/- mu sin I) and mu r w L sin I rotating;
    torque-drag's the same with its w, r and L - dMD (the top course's weight missing)."""
    spacing, length, mu = 10.0, 2000.0, 0.3
    md = np.arange(0.0, length + 1.0, spacing)
    inc, azi = np.full(len(md), inclination), np.full(len(md), 40.0)
    i = math.radians(inclination)
    theirs = _theirs(md, inc, azi, mu)
    model = _ours(md, inc, azi)
    conditions = dict(open_hole_friction=mu, cased_hole_friction=mu, mud_density=MUD_SG * 1000.0)
    for case, op, sign in (("hoisting", "trip_out", 1.0), ("lowering", "trip_in", -1.0),
                           ("static", "rotating_off_bottom", 0.0)):
        closed = math.cos(i) + sign * mu * math.sin(i)
        w_theirs, w_ours = _weight_per_length(True), _weight_per_length(False)
        assert theirs.force[case][0] * 1e3 == pytest.approx(w_theirs * (length - spacing) * closed, rel=1e-12)
        assert model.run(op, **conditions).hook_load == pytest.approx(w_ours * length * closed, rel=1e-12)
    rotating = model.run("rotating_off_bottom", **conditions).surface_torque
    assert rotating == pytest.approx(mu * _radius(False) * _weight_per_length(False) * length * math.sin(i),
                                     rel=1e-12, abs=1e-9)
    assert theirs.torque["static"][0] * 1e3 == pytest.approx(
        mu * _radius(True) * _weight_per_length(True) * (length - spacing) * math.sin(i), rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("spacing", [10.0, 30.0])
def test_three_d_well_replayed_with_either_conventions(spacing):
    """A build-and-turn, drop-and-turn well at stations every `spacing` m: the replayed step gives torque-drag's
    tension and torque to round-off with its conventions, and fs.SoftString's with ours."""
    md, inc, azi, tvd = _three_d_stations(spacing)
    mu = 0.25
    theirs = _theirs(md, inc, azi, mu)
    model = _ours(md, inc, azi)
    conditions = dict(open_hole_friction=mu, cased_hole_friction=mu, mud_density=MUD_SG * 1000.0)
    inc_r, azi_r = np.radians(inc), np.radians(azi)
    for case, op, direction in (("hoisting", "trip_out", 1), ("lowering", "trip_in", -1),
                                ("static", "rotating_off_bottom", 0)):
        f_theirs, m_theirs = _johancsik_step(md, inc_r, azi_r, tvd, mu, direction, theirs=True)
        np.testing.assert_allclose(f_theirs / 1e3, theirs.force[case], rtol=1e-11, atol=1e-9)
        np.testing.assert_allclose(m_theirs / 1e3, theirs.torque[case], rtol=1e-11, atol=1e-9)
        f_ours, m_ours = _johancsik_step(md, inc_r, azi_r, tvd, mu, direction, theirs=False)
        result = model.run(op, **conditions)
        np.testing.assert_allclose(f_ours, result.tension, rtol=1e-11, atol=1e-6)
        if direction == 0:
            np.testing.assert_allclose(m_ours, result.torque, rtol=1e-11, atol=1e-6)


def test_three_d_well_difference_is_first_order_in_the_station_spacing():
    """With the same pipe, mud and friction the two hook loads differ by the constants (g, torque-drag's inch) and
    by the one-course shift, which halves as the spacing halves: after the constants, 30 -> 15 -> 7.5 m stations
    leave differences in the ratio 2 : 1."""
    mu = 0.25
    constants = _weight_per_length(True) / _weight_per_length(False)
    differences = []
    for spacing in (30.0, 15.0, 7.5):
        md, inc, azi, _ = _three_d_stations(spacing)
        theirs = _theirs(md, inc, azi, mu).force["hoisting"][0] * 1e3 / constants
        ours = _ours(md, inc, azi).run("trip_out", open_hole_friction=mu, cased_hole_friction=mu,
                                       mud_density=MUD_SG * 1000.0).hook_load
        differences.append(theirs / ours - 1.0)
    assert abs(differences[0]) < 0.02
    assert differences[0] / differences[1] == pytest.approx(2.0, rel=0.1)
    assert differences[1] / differences[2] == pytest.approx(2.0, rel=0.1)


def test_weight_on_bit_is_tension_in_torque_drag():
    """torque-drag puts +wob at the bit: its hook load *rises* by the WOB in a vertical hole; ours falls."""
    md = np.linspace(0.0, 1500.0, 151)
    inc, azi = np.zeros(151), np.zeros(151)
    free, loaded = _theirs(md, inc, azi, 0.3), _theirs(md, inc, azi, 0.3, wob=50.0)
    assert loaded.force["static"][0] - free.force["static"][0] == pytest.approx(50.0, rel=1e-12)
    model = _ours(md, inc, azi)
    drilling = model.run("sliding_drilling", weight_on_bit=50e3, mud_density=MUD_SG * 1000.0)
    hanging = model.run("rotating_off_bottom", mud_density=MUD_SG * 1000.0)
    assert drilling.hook_load - hanging.hook_load == pytest.approx(-50e3, rel=1e-12)


def test_a_course_across_north_turns_by_340_degrees_in_torque_drag():
    """A hold at 60 degrees turning from azimuth 300 through north to 60: torque-drag's unwrapped azimuth
    difference sees one course turn by -354 degrees, and its pick-up load jumps; ours depends only on the well's
    shape, so the same well turned by 60 degrees (azimuth 0 to 120, no crossing) gives the same loads."""
    md = np.linspace(0.0, 2000.0, 201)
    inc = np.full(201, 60.0)
    across = (np.linspace(-60.0, 60.0, 201)) % 360.0
    turned = np.linspace(0.0, 120.0, 201)
    mu = 0.3
    conditions = dict(open_hole_friction=mu, cased_hole_friction=mu, mud_density=MUD_SG * 1000.0)
    ours = [_ours(md, inc, a).run("trip_out", **conditions).hook_load for a in (across, turned)]
    assert ours[0] == pytest.approx(ours[1], rel=1e-12)
    theirs = [_theirs(md, inc, a, mu).force["hoisting"][0] for a in (across, turned)]
    assert theirs[0] / theirs[1] > 1.5
    # without the crossing torque-drag is within its conventions' few per cent of ours
    constants = _weight_per_length(True) / _weight_per_length(False)
    assert theirs[1] * 1e3 / constants / ours[1] == pytest.approx(1.0, abs=0.02)
