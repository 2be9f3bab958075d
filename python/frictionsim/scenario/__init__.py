"""Scenario files: a rig, a friction law, solver settings, analysis and outputs, described in TOML.

One schema serves ``frictionsim run`` and the built-in demo (:mod:`frictionsim.demo`). A file holds defaults at the
top level and any number of ``[[case]]`` tables; each case is one rig with one friction law, so a file can compare
Coulomb and Dahl friction side by side. SI units throughout; any number may instead be a string with its unit
(``reference_speed = "55 rpm"``, ``weight_on_bit = "25 klbf"``, ``outer_diameter = "5 in"``, ``t_end = "2 min"``),
converted to the key's SI unit when the file is read (:mod:`frictionsim.units`, needs ``frictionsim[units]``)::

    title = "Paper 000 Fig. 7(a)"
    [rig]                       # default rig of every case
    type = "axial"              # "axial" (AxialVibrationRig), "kinematic" (KinematicRig), "torsional" (TorsionalRig)
    amplitude = 5e-3            # u0 [m]; omitted keys take the engine's defaults
    [solver]
    t_end = 2.0                 # s
    [analysis]
    cycles = 10                 # mean friction over the last 10 whole cycles
    [[case]]
    name = "coulomb"
    friction = { type = "coulomb", mu = 0.41 }
    [[case]]
    name = "dahl"
    friction = { type = "dahl", mu = 0.41, tangential_stiffness = 4e4 }

Sections (each may be given at the top level as a default, and per case; a case's keys override the default's
key by key, unless the case changes ``type``, in which case the default table is not used):

``rig``
    ``type = "axial"``: mass [kg], drive_stiffness [N/m], sliding_velocity v_d [m/s], amplitude u0 [m],
    frequency f [Hz], normal_force F_N [N], gravity (bool), gravitational_acceleration [m/s^2],
    initial_position [m], initial_velocity [m/s]; all optional (defaults of :class:`frictionsim.AxialVibrationRig`).
    ``type = "kinematic"``: normal_force [N] and either a harmonic relative velocity v_r = v_d - v_a cos(2 pi f t)
    (sliding_velocity [m/s], velocity_amplitude [m/s], frequency [Hz]) or ``velocity_file``, a CSV of two
    columns t [s], v_r [m/s] (header row optional, ``#`` comments; relative to the scenario file).
    ``type = "torsional"``: paper 001's drill-string rig (:class:`frictionsim.TorsionalRig`; defaults: Tables 1-2
    at the Fig. 7 operating point): disc_inertia J2 [kg m^2], shaft_stiffness k2 [N m/rad], shaft_damping d2
    [N m s/rad], motor_inertia J_m [kg m^2], gear_ratio eta, inductance L [H], resistance R [Ohm],
    torque_constant K_T [N m/A], back_emf_constant K_E [V s/rad], motor_friction_torque T_f [N m],
    motor_viscous_coefficient C_m [N m s/rad], proportional_gain k_p [V s/rad], integral_gain k_i [V/rad],
    reference_speed w_ref [rad/s], normal_force N2 [N], contact_radius r [m], initial_disc_speed [rad/s],
    initial_drive_speed [rad/s]; all optional. A file's cases are either all torsional or none.
    ``type = "drillstring"``: a field-scale string (:class:`frictionsim.StringRig`): ``sections`` (required), an
    array of tables top to bottom with the :class:`frictionsim.PipeSection` keys (outer_diameter, inner_diameter,
    length [m], youngs_modulus, shear_modulus [Pa], density [kg/m^3]); ``bit``, a table of
    :class:`frictionsim.NavarroLopezBit` keys, with ``weight_on_bit`` [N] (no bit: off bottom); and the StringRig
    keywords (damping_time [s], surface_speed [rad/s], proportional_gain, integral_gain, torque_limit [N m],
    inclination [rad], mud_density [kg/m^3], ..., elements, top_drive ("pi_motor" or "prescribed_speed"), axial,
    hoisting, wall_contacts, contact_nodes, normal_forces [N], excitation_node). The friction law acts at every
    wall contact. ``treatment``: "exact" (default: the StringRig, every contact's stick and slip located as an
    event), "captured" or "mixed" (a :class:`frictionsim.TorsionalString`, Aarsnes & Shor's string stepped by
    Moreau-Jean with a fixed ``solver.step`` [s]: every wall contact's switches captured, the bit's too or, "mixed",
    located exactly). Those two take the keys of the same physics (sections, elements, surface_speed as its
    speed_setpoint, end_inertia as its bha_inertia, bit, weight_on_bit, inclination, mud_density,
    top_drive_inertia, proportional_gain, integral_gain), the rest of the TorsionalString's own keywords (survey as
    a table of measured_depth [m] and inclination [rad] arrays, contact_radius, damping_rate, control_period,
    stick_band_speed, slow_speed, ...), and a coulomb [friction] (mu_static its friction_coefficient, mu /
    mu_static its kinetic_ratio); a key the treatment cannot honour is refused naming it, and defaults are each
    engine's own. A file's cases are either all drill strings or none
    (:class:`frictionsim.scenario.rigs.DrillStringKind`).
``friction``
    ``type`` = "coulomb" | "stribeck" | "dahl" | "lugre" | "elasto_plastic" and the constructor's parameters by
    name (:class:`frictionsim.Coulomb` ...): mu, mu_static, stribeck_velocity [m/s], shape_exponent,
    viscous_coefficient [N s/m], karnopp_band [m/s], tangential_stiffness [N/m], exponent, bristle_stiffness [N/m],
    bristle_damping [N s/m], viscous_damping [N s/m], breakaway_fraction (elasto_plastic: z_ba / (mu F_N / sigma0)).
    On a torsional rig they act at contact_radius (v_r = r w2).
    Torsional rigs only: ``type = "hysteretic"``, paper 001's eq 6 (:class:`frictionsim.HystereticFriction`):
    stick_slope a [N m s/rad], accelerating = [p00, p10, p01, p20, p11, p02] and decelerating = [n00, ..., n02]
    (6 numbers each: N m, N m s/rad, kg m^2, N m s^2/rad^2, N m s^3/rad^2, N m s^4/rad^2), optional stick_speed
    w_s [rad/s], reference_normal_force [N], branch_gap ("hold" or "error"); ``type = "fig7"``: the eq 6 set
    chosen to reproduce paper 001's Fig. 7 (:func:`frictionsim.torsional.fig7_friction`; optional branch_gap).
``solver``
    t_end [s] (required), method (one of :data:`frictionsim.METHODS`), rtol (in [1e-14, 0.1]), atol (>= 1e-20),
    timeout [s] (wall-clock budget of each run), and output_points (default 2001, evenly spaced over [0, t_end],
    at most 1e6) or output_step [s]. The ends of the averaging window are always
    recorded as well, so the mean friction is exact to solver tolerance.
``analysis``
    transient [s], cycles, period [s] (default: the rig's vibration period 1/f; required for a velocity_file).
    The mean friction force F_df is taken over ``cycles`` whole cycles after ``transient``; without transient it
    is over the last ``cycles`` cycles before t_end; without either, over all whole cycles after t_end / 2.
    Torsional rigs: the limit cycle of the disc speed instead (:func:`frictionsim.torsional.limit_cycle`):
    transient [s] (default t_end / 2; must be < t_end) and stick_speed [rad/s] (default 0.01: |w2| at or below
    it counts as stuck). Summary: frequency [Hz], period [s], peak / trough / mean disc speed [rad/s], peak / w_ref,
    stick fraction, mean friction torque [N m] over the whole cycles measured (see
    :class:`frictionsim.scenario.rigs.Torsional`).
    Drill strings: transient [s] (default t_end / 2) after which the bit's stick-slip is measured (peak and mean
    bit speed over w_set, the share of the time the bit is stuck), and optionally surface_speeds [rad/s] and
    weights_on_bit [N], the grid of a stick-slip map (one run of the case's rig from rest per point;
    ``stick_slip_map_<case>.csv``).
``output`` (top level only)
    directory (relative to the scenario file's folder, which it may not leave: no absolute path, no ``..`` or
    symbolic link out of it, unless ``frictionsim run --allow-outside``; ignored when ``--out`` is given; default
    ``out/<file stem>`` in the working directory), tables (subset of
    ["timeseries", "summary"]), plots (subset of ["friction_force", "hysteresis", "drive_force"]; torsional
    rigs: of ["disc_speed", "friction_torque_hysteresis", "phase_portrait"]; drill strings: of ["bit_speed",
    "stick_slip_map"]), plot_window = [t_start, t_end] [s]
    (default: the last 3 vibration cycles; torsional: the last 10 s for disc_speed, [transient, t_end] for the
    others). The time series of a torsional case has t, the rig's states (disc_speed, drive_speed, shaft_twist,
    current, ...), disc_acceleration, friction_torque, shaft_torque, voltage and mode.

A case also takes ``name`` (file-name safe; default the friction type), ``description`` and ``lubricant``
("dry", "water", "wbm", "obm", "sbm": adds the Table 5 power-law F_df to the summary; not for torsional rigs).

Everything is validated by :func:`load` before anything runs: the law and rig objects are built (so the engine's
own rules reject non-physical values), and the averaging window is checked against t_end. Any problem raises
:class:`ScenarioError` naming the file and the key by its dotted path, e.g. ``case[2].friction.tangential_stiffness``
(cases count from 1 in file order).

The package: :mod:`~frictionsim.scenario.parser` (TOML to specs, every rule and error), :mod:`~.specs` (the
dataclasses), :mod:`~.rigs` (the registry :data:`RIG_KINDS`: one :class:`RigKind` per rig type, with its keys,
builder, time series, plots and own friction types), :mod:`~.analyses` (mean friction over cycles, limit cycle,
a drill string's stick-slip)
and :mod:`~.runner` (running cases, writing CSV and PNG files).
"""

from __future__ import annotations

from .analyses import CaseRun, LimitCycleRun, StringRun
from .parser import (MAX_DATA_FILE_BYTES, MAX_DESCRIPTION_CHARACTERS, MAX_OUTPUT_POINTS, MAX_TITLE_CHARACTERS,
                     ScenarioError, load, loads, parse)
from .rigs import PLOTS, RIG_KINDS, STRING_PLOTS, TORSIONAL_PLOTS, RigKind, friction_types, rig_kind
from .runner import ScenarioRun, run, run_case
from .specs import TABLES, AnalysisSpec, Case, FrictionSpec, OutputSpec, RigSpec, Scenario, SolverSpec

__all__ = [
    "AnalysisSpec", "Case", "CaseRun", "FrictionSpec", "LimitCycleRun", "MAX_DATA_FILE_BYTES",
    "MAX_DESCRIPTION_CHARACTERS", "MAX_OUTPUT_POINTS", "MAX_TITLE_CHARACTERS", "OutputSpec", "PLOTS", "RIG_KINDS",
    "RigKind", "RigSpec", "Scenario", "ScenarioError", "ScenarioRun", "SolverSpec", "STRING_PLOTS", "StringRun",
    "TABLES", "TORSIONAL_PLOTS",
    "friction_types", "load", "loads", "parse", "rig_kind", "run", "run_case",
]
