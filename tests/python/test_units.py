"""Field units at the boundary (frictionsim.units, issue 15 item 6): conversions against SI values worked by hand,
every unit string of the engine's tables mapped, a rig built from field units identical to the SI one, mismatches
named, and for every parameter of every table: a quantity in the table's own unit is exactly the plain number."""

from __future__ import annotations

import math
import pickle
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import frictionsim as fs
from frictionsim import _core
from frictionsim import scenario as sc
from frictionsim import units

pint = pytest.importorskip("pint", reason="frictionsim[units] is not installed")

ROOT = Path(__file__).resolve().parent.parent.parent
U = units.registry()

# SI values of the field units, from their definitions (NIST SP 811; API: oil barrel = 42 US gallons)
LB = 0.45359237  # kg
LBF = LB * 9.80665  # N: 4.4482216152605
FT = 0.3048  # m
INCH = 0.0254  # m
GALLON = 231 * INCH**3  # m^3 (US liquid gallon)


# -- the drilling units and the conversions, against hand-computed SI values

@pytest.mark.parametrize("text, unit, si", [
    ("1 klbf", "N", 4448.2216152605),
    ("25 klbf", "N", 25 * 1000 * LBF),
    ("1 lbf", "N", LBF),
    ("55 rpm", "rad/s", 55 * 2 * math.pi / 60),
    ("120 rpm", "rad/s", 4 * math.pi),
    ("90 deg/s", "rad/s", math.pi / 2),
    ("1 ppg", "kg/m^3", 119.826427),
    ("8.5 ppg", "kg/m^3", 8.5 * LB / GALLON),
    ("1 pcf", "kg/m^3", LB / FT**3),
    ("1.2 sg", "kg/m^3", 1200.0),
    ("5 in", "m", 0.127),
    ("10000 ft", "m", 3048.0),
    ("1 ft.lbf", "N m", FT * LBF),
    ("1 ft-lbf", "N m", FT * LBF),
    ("1 ft\u00b7lbf", "N m", FT * LBF),
    ("20 kft*lbf", "N m", 20e3 * FT * LBF),
    ("1 bbl", "m^3", 42 * GALLON),
    ("1 bbl", "m^3", 0.158987294928),
    ("3 deg/30m", "rad/m", 3 * math.pi / 180 / 30),
    ("3 deg/30 m", "rad/m", 3 * math.pi / 180 / 30),
    ("3\u00b0/30m", "rad/m", 3 * math.pi / 180 / 30),
    ("3 deg/100ft", "rad/m", 3 * math.pi / 180 / (100 * FT)),
    ("45 deg", "rad", math.pi / 4),
    ("1 psi", "Pa", LBF / INCH**2),
    ("30 ksi", "Pa", 30e3 * LBF / INCH**2),
    ("17 Hz", "Hz", 17.0),
    ("1020 1/min", "Hz", 17.0),
    ("30 percent", "-", 0.3),
    ("2 min", "s", 120.0),
    ("3 t", "kg", 3000.0),
    ("149 kg*cm**2", "kg m^2", 0.0149),
    ("0.5 N*m/rpm", "N m s/rad", 0.5 * 60 / (2 * math.pi)),
    ("2 km/h", "m/s", 2 / 3.6),
    ("30 ft/h", "m/s", 30 * FT / 3600),
    ("5 1/2 in", "m", 5.5 * INCH),  # pipe sizes: mixed numbers, not 5 * 1/2
    ("13-3/8 in", "m", 13.375 * INCH),
    ("1/2 in", "m", 0.5 * INCH),
    # a course keeps its unit's exponent: the yield point's lbf/100 ft^2 is lbf/(100 ft^2), not lbf/(100 ft)^2
    ("10 lbf/100ft^2", "Pa", 10 * LBF / (100 * FT**2)),
    ("10 lbf/100 ft**2", "Pa", 10 * LBF / (100 * FT**2)),
    ("2 m/s^2", "m/s^2", 2.0),
    ("4 N*m^-1", "N/m", 4.0),
])
def test_field_units_convert_to_the_si_values_worked_by_hand(text, unit, si):
    published = si == 119.826427  # the ppg factor as tables print it, to 9 digits
    assert units.to_si(text, unit, "x") == pytest.approx(si, rel=3e-9 if published else 2e-15)


def test_quantities_of_any_registry_convert_and_bare_numbers_are_si_untouched():
    other = pint.UnitRegistry()  # the user's own registry: counts the radian as a pure number
    assert units.to_si(other.Quantity(60, "rpm"), "rad/s") == pytest.approx(2 * math.pi, rel=1e-15)
    assert units.to_si(U.Quantity(5, "in"), "m") == pytest.approx(0.127, rel=1e-15)
    depths = U.Quantity(np.array([0.0, 1000.0, 2000.0]), "ft")
    np.testing.assert_allclose(units.to_si(depths, "m"), [0.0, 304.8, 609.6], rtol=1e-15)
    assert units.to_si(["1 kN", 5.0], "N") == [1000.0, 5.0]
    samples = np.array([1.0, 2.0])
    assert units.to_si(samples, "m") is samples and units.to_si(0.3, "-") == 0.3
    assert units.to_si("0.3", "-") == 0.3  # a dimensionless number may be written as a string
    with pytest.raises(units.UnitError, match=r"^w: '12.5' has no unit: give a number \(SI: rad/s\) or the value "
                                              r"with its unit, e.g. '12.5 rad/s'$") as error:
        units.to_si("12.5", "rad/s", "w")  # where the parameter has a unit, a string without one forgot it
    assert isinstance(error.value, TypeError) and error.value.parameter == "w"
    assert units.convert(4448.2216152605, "N", "klbf") == pytest.approx(1.0, rel=1e-15)
    np.testing.assert_allclose(units.convert([2 * math.pi, math.pi], "rad/s", "rpm"), [60.0, 30.0], rtol=1e-15)


def test_every_unit_of_every_table_is_read_as_the_pint_unit_it_names():
    """The C++ tables' unit strings (grepped from include/frictionsim), Python's Parameter.unit of every bound
    class and the laws' state units: each read off the string itself (units.table_unit; a new unit string needs no
    entry in units.TABLE_UNITS) as the same unit (factor exactly 1) as pint reads the string."""
    cpp = set()
    for header in (ROOT / "include" / "frictionsim").rglob("*.hpp"):
        text = header.read_text(encoding="utf-8")
        if "Field<" in text:
            cpp |= set(re.findall(r'\{"\w+",\s*"[^"]*",\s*"([^"]+)",\s*Rule', text))
    python = {p.unit for cls in vars(_core).values() if isinstance(cls, type)
              for p in getattr(cls, "parameters", ()) if hasattr(p, "unit")}
    states = {unit for law in fs.FRICTION_LAWS for unit in law.state_units}
    assert len(cpp) >= 20 and python <= cpp | {"-"} and "m" in states
    for unit in cpp | python | states | {"N s^2/m^2", "kg m^2/s"}:  # and two no table has yet
        written = {"-": "dimensionless", "1": "dimensionless", "Ohm": "ohm"}.get(unit, unit)
        assert U.Quantity(1.0, written).to(units.table_unit(unit)).magnitude == pytest.approx(1.0, rel=1e-15), unit
    assert units.to_si("2 N*s**2/m**2", "N s^2/m^2", "c") == 2.0
    for unit, (expression, what, _) in units.TABLE_UNITS.items():
        written = {"-": "dimensionless", "Ohm": "ohm"}.get(unit, unit)  # pint spells these two otherwise
        assert U.Quantity(1.0, written).to(expression).magnitude == pytest.approx(1.0, rel=1e-15), unit
        assert units.describe(unit) == f"{what} ({unit})"


def test_angles_are_a_dimension_so_rpm_and_hz_do_not_mix():
    # pint's own registry would give 1 Hz = 1 rad/s and 60 rpm = 6.28 Hz
    with pytest.raises(fs.InvalidParameterError, match=r"^x: expected an angular speed \(rad/s\), got 1 Hz "
                                                       r"\[frequency\]$"):
        units.to_si("1 Hz", "rad/s", "x")
    with pytest.raises(fs.InvalidParameterError, match=r"expected a frequency \(Hz\), got 60 rpm \[angular speed\]"):
        units.to_si("60 rpm", "Hz", "x")


def test_text_that_would_hang_or_overflow_is_refused_at_once_naming_the_parameter():
    """pint evaluates the text's arithmetic: an integer power such as 10**10**10 ran for ever (a sweep file with it
    hung `frictionsim sweep`), a 400-digit magnitude overflowed the double with an OverflowError traceback. Run
    in a subprocess so that a regression fails on the timeout instead of hanging the suite."""
    script = textwrap.dedent("""
        from frictionsim import units
        for text in ("10**10**10 N", "10^(10)^(10) N", "2 ** +(10)**(10) N", "9" * 190 + "**9**9 N"):
            try:
                units.to_si(text, "N", "normal_force")
            except units.UnitError as error:
                print(error.parameter, "|", error)
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert len(lines) == 4, out.stdout
    for line in lines:
        assert line.startswith("normal_force | normal_force: cannot read '") and "OverflowError" in line, line
    with pytest.raises(units.UnitError, match=r"^normal_force: cannot read a value with a unit from 402 "
                                              r"characters \(at most 200\)$") as error:
        units.to_si("9" * 400 + " N", "N", "normal_force")
    assert error.value.parameter == "normal_force"
    with pytest.raises(units.UnitError, match=r"^hook_load: .* is beyond the range of a double in N$"):
        units.to_si(U.Quantity(10**400, "klbf"), "N", "hook_load")  # an integer no double holds
    with pytest.raises(units.UnitError, match=r"^hook_load: '1e308 klbf' is not a finite value in N$"):
        units.to_si("1e308 klbf", "N", "hook_load")  # a double, but not in newtons


def test_convert_names_the_unit_at_fault_not_pint():
    with pytest.raises(units.UnitError, match=r"^to_unit: cannot convert a force \(N\) \[force\] to a length "
                                              r"\(m\) \[length\]$") as error:
        units.convert(1.0, "N", "m")
    assert error.value.parameter == "to_unit" and not isinstance(error.value, pint.errors.PintError)
    with pytest.raises(units.UnitError, match=r"^from_unit: cannot read 'furlongz' as a unit") as error:
        units.convert(1.0, "furlongz", "m")
    assert error.value.parameter == "from_unit"
    with pytest.raises(units.UnitError, match=r"^to_unit: cannot read 'm\*\*\*' as a unit"):
        units.convert(1.0, "m", "m***")


# -- the engine's classes take field units

@pytest.fixture(scope="module")
def soft_string():
    survey = fs.Survey.from_degrees([0.0, 500.0, 1500.0, 2500.0], [0.0, 0.0, 45.0, 90.0], [0.0, 0.0, 30.0, 30.0])
    string = fs.DrillString([fs.PipeSection(length=2300.0), fs.PipeSection(outer_diameter=0.1651,
                                                                            inner_diameter=0.0714, length=200.0)])
    return fs.SoftString(survey, string, 50)


def test_import_installs_units_on_the_engine_classes_once():
    for routine in (fs.Coulomb.__init__, fs.TorsionalRig.__init__, fs.StringRig.__init__, fs.SoftString.run,
                    fs.PipeSection.__init__, fs.HydraulicOscillator.__init__, fs.Survey.from_degrees):
        assert hasattr(routine, "_frictionsim_units"), routine
    assert fs.SoftString.run._frictionsim_units["rotary_speed"] == "rad/s"  # read off SoftString.parameters
    units.install()  # again: nothing wrapped twice
    assert not hasattr(fs.Coulomb.__init__.__wrapped__, "_frictionsim_units")


def test_a_rig_in_field_units_is_the_si_rig_bit_for_bit():
    field = fs.TorsionalRig(fs.Coulomb("0.3"), reference_speed="60 rpm", contact_radius="10 cm",
                            normal_force="35 N", disc_inertia=U.Quantity(149.0, "kg*cm**2"))
    si = fs.TorsionalRig(fs.Coulomb(0.3), reference_speed=2 * math.pi, contact_radius=0.1, normal_force=35.0,
                         disc_inertia=0.0149)
    assert repr(field) == repr(si)
    assert field.reference_speed == 2 * math.pi and field.disc_inertia == pytest.approx(0.0149, rel=1e-15)
    a, b = fs.simulate(field, 2.0), fs.simulate(fs.TorsionalRig(fs.Coulomb(0.3), reference_speed=2 * math.pi,
                                                                contact_radius=0.1, normal_force=35.0,
                                                                disc_inertia=field.disc_inertia), 2.0)
    assert np.array_equal(a.t, b.t) and np.array_equal(a.states, b.states) and len(a.events) == len(b.events) > 0
    assert repr(pickle.loads(pickle.dumps(field))) == repr(field)


def test_strings_wells_and_tools_in_field_units(soft_string):
    pipe = fs.PipeSection(outer_diameter="5 in", inner_diameter="4.276 in", length="1000 ft", density="7.85 sg")
    assert (pipe.outer_diameter, pipe.length, pipe.density) == (0.127, pytest.approx(304.8, rel=1e-15), 7850.0)
    assert pipe.inner_diameter == pytest.approx(4.276 * INCH, rel=1e-15)
    rig = fs.StringRig(fs.DrillString([pipe]), fs.Coulomb(0.2), bit=fs.NavarroLopezBit(bit_radius="4.25 in"),
                       weight_on_bit="20 klbf", surface_speed="60 rpm", mud_density="10 ppg", elements=4,
                       normal_forces=["1 kN", 2000.0, "0.5 klbf"], inclination="30 deg")
    assert rig.weight_on_bit == pytest.approx(20e3 * LBF, rel=1e-15) and rig.surface_speed == 2 * math.pi
    assert rig.mud_density == pytest.approx(10 * LB / GALLON, rel=1e-15)
    np.testing.assert_allclose(rig.normal_forces, [1000.0, 2000.0, 500 * LBF], rtol=1e-15)
    assert rig.inclination == pytest.approx(math.pi / 6, rel=1e-15)
    tool = fs.HydraulicOscillator(measured_depth="6000 ft", force_amplitude="10 klbf", frequency="17 Hz")
    assert (tool.measured_depth, tool.frequency) == (pytest.approx(6000 * FT, rel=1e-15), 17.0)

    conditions = dict(rotary_speed="120 rpm", mud_density="10 ppg", hole_diameter="8.5 in", bit_torque="5 kft*lbf")
    field = soft_string.run("rotating_off_bottom", **conditions)
    si_values = {k: units.to_si(v, fs.SoftString.parameters[[p.name for p in fs.SoftString.parameters].index(k)]
                                .unit) for k, v in conditions.items()}
    assert si_values["rotary_speed"] == 4 * math.pi and si_values["hole_diameter"] == pytest.approx(0.2159, 1e-15)
    si = soft_string.run("rotating_off_bottom", **si_values)
    assert field.surface_torque == si.surface_torque and np.array_equal(field.tension, si.tension)

    md = U.Quantity(np.array([0.0, 1000.0, 3000.0]), "ft")
    by_degrees = fs.Survey.from_degrees(md, [0.0, 10.0, 40.0], [0.0, 0.0, 90.0])
    in_radians = fs.Survey(md, U.Quantity(np.array([0.0, 10.0, 40.0]), "deg"), ["0 deg", "0 deg", "90 deg"])
    np.testing.assert_allclose(by_degrees.measured_depth, [0.0, 304.8, 914.4], rtol=1e-15)
    np.testing.assert_allclose(in_radians.inclination, by_degrees.inclination, rtol=1e-15)
    np.testing.assert_allclose(in_radians.tvd, by_degrees.tvd, rtol=1e-13)


def test_a_unit_of_the_wrong_kind_names_the_parameter_and_the_dimension(soft_string):
    with pytest.raises(fs.InvalidParameterError) as error:
        soft_string.run("rotating_off_bottom", rotary_speed="25 klbf")
    assert str(error.value) == "rotary_speed: expected an angular speed (rad/s), got 25 klbf [force]"
    assert error.value.parameter == "rotary_speed"
    assert isinstance(error.value, TypeError)  # a value of the wrong kind, as a string was before units
    cases = [(lambda: fs.Coulomb(mu="0.3 m"), "mu", r"expected a dimensionless number \(-\), got 0.3 m \[length\]"),
             (lambda: fs.AxialVibrationRig(fs.Coulomb(0.3), frequency="1020 rpm"), "frequency",
              r"expected a frequency \(Hz\), got 1020 rpm \[angular speed\]"),
             (lambda: fs.StringRig(fs.DrillString([fs.PipeSection()]), fs.Coulomb(0.2), weight_on_bit="5 in",
                                   bit=fs.NavarroLopezBit()), "weight_on_bit", r"expected a force \(N\)"),
             (lambda: fs.PipeSection(length=U.Quantity(3.0, "s")), "length", r"expected a length \(m\), got 3.0 s "
                                                                              r"\[time\]"),
             (lambda: fs.Survey.from_degrees([0, 100], ["0 deg", "1 m"], [0, 0]), "inclination[1]",
              r"expected an angle \(deg\)"),
             (lambda: fs.Coulomb(mu="0.3 furlongz"), "mu", r"cannot read '0.3 furlongz' as a value with a unit")]
    for build, parameter, message in cases:
        with pytest.raises(fs.InvalidParameterError, match=f"^{parameter.replace('[', '.').replace(']', '.')}: "
                                                           f"{message}") as error:
            build()
        assert error.value.parameter == parameter
    # the engine's own rule still speaks for a converted value
    with pytest.raises(fs.InvalidParameterError, match="outer_diameter.*positive"):
        fs.PipeSection(outer_diameter="-5 in")


def test_without_pint_numbers_work_and_a_string_names_the_extra(tmp_path):
    scenario = tmp_path / "units.toml"
    scenario.write_text('[rig]\ntype = "axial"\nfrequency = "17 Hz"\n[solver]\nt_end = 1.0\n'
                        '[friction]\ntype = "coulomb"\nmu = 0.3\n', encoding="utf-8")
    script = textwrap.dedent(f"""
        import sys
        sys.modules["pint"] = None  # as if frictionsim[units] were not installed
        import frictionsim as fs
        from frictionsim import scenario
        print(fs.Coulomb(mu=0.3).mu, fs.Coulomb(mu="0.3").mu)  # numbers, even as text, need no pint
        try:
            fs.TorsionalRig(fs.Coulomb(0.3), reference_speed="55 rpm")
        except ImportError as error:
            print(type(error).__name__, error)
        try:
            scenario.load({str(scenario)!r})
        except ValueError as error:
            print(type(error).__name__, error)
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0] == "0.3 0.3"
    assert lines[1] == ("UnitsUnavailableError reference_speed='55 rpm': values with units need pint: "
                        "pip install 'frictionsim[units]'")
    assert lines[2].startswith(f"ScenarioError {scenario}: rig.frequency: '17 Hz' has a unit")
    assert "frictionsim[units]" in lines[2]


# -- scenario files

_SCENARIO = """
title = "Paper 001's rig, in field units"
[rig]
type = "torsional"
reference_speed = "{speed}"
contact_radius = "10 cm"
normal_force = "35 N"
[solver]
t_end = "{t_end}"
output_step = "10 ms"
[analysis]
transient = "15 s"
[[case]]
name = "dry"
friction = {{ type = "coulomb", mu = "0.3" }}
"""


def test_a_scenario_in_field_units_is_the_si_scenario(tmp_path):
    path = tmp_path / "field.toml"
    path.write_text(_SCENARIO.format(speed="60 rpm", t_end="0.5 min"), encoding="utf-8")
    field = sc.load(path)
    si = sc.loads(textwrap.dedent("""
        [rig]
        type = "torsional"
        reference_speed = 6.283185307179586
        contact_radius = 0.1
        normal_force = 35
        [solver]
        t_end = 30.0
        output_step = 0.01
        [analysis]
        transient = 15.0
        [[case]]
        name = "dry"
        friction = { type = "coulomb", mu = 0.3 }
    """), source=path)
    assert field.cases == si.cases and repr(field.cases[0].build()) == repr(si.cases[0].build())

    string = tmp_path / "string.toml"
    string.write_text(textwrap.dedent("""
        [rig]
        type = "drillstring"
        sections = [{ outer_diameter = "5 in", length = "1000 ft" }, { outer_diameter = "6.5 in", length = 60 }]
        bit = { bit_radius = "4.25 in" }
        weight_on_bit = "20 klbf"
        surface_speed = "60 rpm"
        mud_density = "1.2 sg"
        normal_forces = ["1 kN", 500]
        contact_nodes = [1, 2]
        elements = 4
        [solver]
        t_end = 5
        [analysis]
        surface_speeds = ["40 rpm", 5]
        weights_on_bit = ["10 klbf"]
        [friction]
        type = "coulomb"
        mu = 0.2
    """), encoding="utf-8")
    case = sc.load(string).cases[0]
    params = case.rig.params
    assert params["sections"][0] == {"outer_diameter": 0.127, "length": pytest.approx(304.8, rel=1e-15)}
    assert params["bit"]["bit_radius"] == pytest.approx(4.25 * INCH, rel=1e-15)
    assert params["weight_on_bit"] == pytest.approx(20e3 * LBF, rel=1e-15)
    assert (params["surface_speed"], params["mud_density"], params["normal_forces"]) == (2 * math.pi, 1200.0,
                                                                                          (1000.0, 500.0))
    assert case.analysis.surface_speeds == (pytest.approx(4 * math.pi / 3, rel=1e-15), 5.0)
    assert case.analysis.weights_on_bit == (pytest.approx(10e3 * LBF, rel=1e-15),)


@pytest.mark.parametrize("speed, t_end, key, rule", [
    ("25 klbf", "30 s", "rig.reference_speed", "expected an angular speed (rad/s), got 25 klbf [force]"),
    ("5 Hz", "30 s", "rig.reference_speed", "expected an angular speed (rad/s), got 5 Hz [frequency]"),
    ("60 rpm", "3 m", "solver.t_end", "expected a time (s), got 3 m [length]"),
])
def test_a_scenario_unit_mismatch_names_file_key_and_dimension(tmp_path, speed, t_end, key, rule):
    path = tmp_path / "bad.toml"
    path.write_text(_SCENARIO.format(speed=speed, t_end=t_end), encoding="utf-8")
    with pytest.raises(sc.ScenarioError) as error:
        sc.load(path)
    assert (error.value.file, error.value.key, error.value.rule) == (str(path), key, rule)
    assert str(error.value) == f"{path}: {key}: {rule}"


# -- every parameter of every table: a quantity in the table's SI unit is exactly the plain number

def _tabled():
    """(class, parameter record) of every table whose keywords a constructor takes, and SoftString's conditions."""
    out = []
    for cls in vars(_core).values():
        if isinstance(cls, type) and isinstance(getattr(cls, "parameters", None), tuple):
            out += [(cls, record) for record in cls.parameters]
    return out


_FRICTION = fs.Coulomb(0.3)


def _admitted_example(record) -> float:
    """The table's example, or a value inside the rule where the example is not (PowerLawCoefficient's eta: 0 in
    (0, 10])."""
    if record.example > record.lower or (record.example == record.lower and not record.lower_open):
        return record.example
    return (record.lower + record.upper) / 2 if math.isfinite(record.upper) else record.lower + 1.0


def _outcome(cls, record, value, soft_string):
    """What the engine makes of ``value`` given for ``record`` (the other required keywords at the table's
    examples): the object's repr and the parameter read back, or the error's type and text."""
    keywords = {r.name: _admitted_example(r) for r in cls.parameters if r.required}
    keywords[record.name] = value
    try:
        if cls is fs.SoftString:
            result = soft_string.run("trip_out", **keywords)
            return ("ok", result.hook_load, result.surface_torque, tuple(result.tension))
        if cls is fs.StringRig:
            made = cls(fs.DrillString([fs.PipeSection()]), _FRICTION, elements=2, **keywords)
        elif cls in (fs.AxialVibrationRig, fs.TorsionalRig):
            made = cls(_FRICTION, **keywords)
        elif cls is fs.HystereticFriction:
            made = cls(**{"stick_slope": 2.0, **keywords}, accelerating=[0.1] * 6, decelerating=[0.1] * 6)
        else:
            made = cls(**keywords)
        return ("ok", repr(made), getattr(made, record.name))
    except (ValueError, TypeError) as error:
        return (type(error).__name__, str(error))


@settings(max_examples=150, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(entry=st.sampled_from(_tabled()), as_text=st.booleans(),
       scale=st.one_of(st.floats(0.1, 10.0), st.sampled_from([0.0, -1.0, 1e300, math.inf, math.nan])))
def test_a_quantity_in_the_table_unit_is_the_plain_number(soft_string, entry, scale, as_text):
    """Valid or not (zero, negative, overflowing to inf, NaN): the same object or the same error."""
    cls, record = entry
    x = record.example * scale if math.isfinite(record.example) and record.example != 0 else scale
    expression = units.table_unit(record.unit)
    as_text = as_text and math.isfinite(x)  # "inf N" is no quantity pint reads
    given_with_unit = f"{x!r} {expression}" if as_text else U.Quantity(x, expression)
    assert _outcome(cls, record, given_with_unit, soft_string) == _outcome(cls, record, x, soft_string)


def test_every_table_is_in_the_property_test():
    classes = {cls.__name__ for cls, _ in _tabled()}
    assert {"AxialVibrationRig", "TorsionalRig", "StringRig", "PipeSection", "SoftString", "HydraulicOscillator",
            "NavarroLopezBit", "DetournayBit", "Coulomb", "LuGre"} <= classes


def test_the_arguments_no_table_describes_are_not_in_a_table():
    """units._UNTABLED lists only what no table has, or a routine's own unit where it differs from the table's
    (Survey.from_degrees' degrees): once a binding's table gains an argument in its unit, its entry must go."""
    for class_name, routines in units._UNTABLED.items():
        cls = getattr(_core, class_name)
        tabled = {p.name: p.unit for p in getattr(cls, "parameters", ())}
        for routine, arguments in routines.items():
            assert hasattr(cls, routine), f"{class_name}.{routine}"
            repeated = sorted(a for a in set(tabled) & set(arguments) if tabled[a] == arguments[a])
            assert not repeated, f"{class_name}.{routine}: {repeated}"
            assert set(arguments.values()) <= set(units.TABLE_UNITS)
