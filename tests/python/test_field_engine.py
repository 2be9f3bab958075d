"""The field engine from Python (issue 22 item 2): the Moreau-Jean string fs.TorsionalString and its Well B preset,
the Navarro-Lopez rigs, method="rosenbrock", the Detournay bit's depth of cut and torque conventions.

Every figure is checked against a closed form written out here, an independent SciPy computation, or the C++
suite's own reference (tests/aarsnes_shor.test.cpp and the published code's runs in tests/data/aarsnes_shor_2018/).
"""

from __future__ import annotations

import math
import pickle
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

import frictionsim as fs
from strategies import FIELD_TABLES, table_kwargs, valid

needs_eigen = pytest.mark.skipif(not fs.HAS_EIGEN, reason="the extension was built without Eigen")
DATA = Path(__file__).resolve().parents[1] / "data" / "aarsnes_shor_2018"


# ------------------------------------------------------------------------------------------------ Navarro-Lopez
def balance_root(p: dict, walls: float = 0.0) -> float:
    """Root of u - (c_r + c_b) w - R_b W mu_b(w) - walls = 0 (the sum of all equations at a common speed w), mu_b
    written out here, by SciPy's brentq."""
    def f(w):
        mu = p["coulomb_coefficient"] + (p["static_coefficient"] - p["coulomb_coefficient"]) * math.exp(
            -p["weakening_rate"] * w / p["velocity_scale"])
        return (p["motor_torque"] - (p["table_damping"] + p["bit_damping"]) * w
                - p["bit_radius"] * p["weight_on_bit"] * mu - walls)
    return brentq(f, 0.0, (p["motor_torque"] - walls) / (p["table_damping"] + p["bit_damping"]) + 1.0, xtol=1e-14)


def table(rig) -> dict:
    return {q.name: getattr(rig, q.name) for q in type(rig).parameters}


@pytest.mark.parametrize("weight", [10e3, 20e3, 30e3])
def test_navarro_lopez_2dof_steady_speed_is_the_closed_form_balance(weight):
    rig = fs.NavarroLopez2Dof(weight_on_bit=weight, initial_speed=5.0)
    w = balance_root(table(rig))
    result = fs.simulate(rig, 150.0, rtol=1e-9, atol=1e-9, output_times=[150.0])
    assert result["bit_speed"][-1] == pytest.approx(w, rel=1e-6)
    assert result["table_speed"][-1] == pytest.approx(w, rel=1e-6)
    assert rig.steady_balance(w) == pytest.approx(0.0, abs=1e-9 * rig.motor_torque)
    # the string carries the bit's torque: k_t twist = c_b w + R_b W mu_b(w)
    assert rig.string_stiffness * result["string_twist"][-1] == pytest.approx(
        rig.bit.torque(w, weight), rel=1e-6)


@pytest.mark.parametrize("pipe_wall_torque", [0.0, 300.0])
def test_navarro_lopez_4dof_steady_speed_with_pipe_walls(pipe_wall_torque):
    rig = fs.NavarroLopez4Dof(weight_on_bit=20e3, initial_speed=5.0, pipe_wall_torque=pipe_wall_torque)
    w = balance_root(table(rig), walls=2.0 * pipe_wall_torque)
    result = fs.simulate(rig, 200.0, rtol=1e-9, atol=1e-9, output_times=[200.0])
    for name in ("table_speed", "upper_pipe_speed", "lower_pipe_speed", "bit_speed"):
        assert result[name][-1] == pytest.approx(w, rel=1e-6), name


def test_navarro_lopez_above_the_threshold_weight_the_stuck_string_stays_stuck():
    # W >= u / (R_b mu_sb) holds a string at rest in equilibrium (k_t twist = u). Started untwisted under the step
    # of u, the table winds the spring past u first: undamped its torque peaks at 2 u, so 1.2 x the threshold is
    # not enough to hold it (the bit breaks away) and 2.5 x is.
    rig = fs.NavarroLopez2Dof()
    assert rig.stuck_weight_threshold == pytest.approx(rig.motor_torque / (rig.bit_radius * rig.static_coefficient))
    overshoot = fs.simulate(fs.NavarroLopez2Dof(weight_on_bit=1.2 * rig.stuck_weight_threshold), 100.0,
                            rtol=1e-9, atol=1e-9)
    assert np.any(overshoot["bit_speed"] != 0.0)
    stuck = fs.NavarroLopez2Dof(weight_on_bit=2.5 * rig.stuck_weight_threshold)
    result = fs.simulate(stuck, 100.0, rtol=1e-9, atol=1e-9)
    assert np.all(result["bit_speed"] == 0.0)  # exact stick: the bit never moves
    # the table winds the spring until it passes u: k_t twist = u, the table at rest
    assert stuck.string_stiffness * result["string_twist"][-1] == pytest.approx(stuck.motor_torque, rel=1e-4)
    assert abs(result["table_speed"][-1]) < 1e-4


def test_navarro_lopez_energy_balance_through_stick_slip():
    rig = fs.NavarroLopez2Dof(weight_on_bit=38e3, initial_speed=0.0)  # stick-slip below the threshold
    result = fs.simulate(rig, 60.0, rtol=1e-10, atol=1e-10)
    assert result.events  # it does stick and slip
    s = {name: result[name] for name in rig.state_names}
    stored = 0.5 * (rig.table_inertia * s["table_speed"] ** 2 + rig.bit_inertia * s["bit_speed"] ** 2
                    + rig.string_stiffness * s["string_twist"] ** 2)
    balance = s["motor_work"] - (stored - stored[0]) - s["damping_work"] - s["friction_work"]
    assert np.max(np.abs(balance)) < 1e-6 * np.max(np.abs(s["motor_work"]))


# ------------------------------------------------------------------------------------------------- rosenbrock
@needs_eigen
def test_rosenbrock_agrees_with_dormand_prince_on_a_lab_rig():
    rig = fs.AxialVibrationRig(fs.Coulomb(mu=0.41))
    times = np.linspace(0.0, 0.5, 51)
    a = fs.simulate(rig, 0.5, method="rosenbrock", rtol=1e-9, atol=1e-12, output_times=times)
    b = fs.simulate(rig, 0.5, method="dormand_prince", rtol=1e-9, atol=1e-12, output_times=times)
    assert a.completed and b.completed
    for name in ("position", "velocity", "friction_work"):
        scale = np.max(np.abs(b[name]))
        assert np.max(np.abs(a[name] - b[name])) < 1e-5 * scale, name
    # the same stick-slip switches, located by both
    assert len(a.events) == len(b.events)
    assert np.allclose([e.time for e in a.events], [e.time for e in b.events], atol=1e-7)


@needs_eigen
def test_rosenbrock_reaches_the_navarro_lopez_closed_form():
    rig = fs.NavarroLopez2Dof(weight_on_bit=20e3, initial_speed=5.0)
    result = fs.simulate(rig, 150.0, method="rosenbrock", rtol=1e-9, atol=1e-9, output_times=[150.0])
    assert result["bit_speed"][-1] == pytest.approx(balance_root(table(rig)), rel=1e-6)


def test_methods_are_the_engines_enum_and_a_bad_one_is_named():
    assert "rosenbrock" in fs.METHODS and set(fs.METHODS) == set(fs._core.Method.__members__)
    with pytest.raises(fs.InvalidParameterError) as error:
        fs.simulate(fs.NavarroLopez2Dof(), 1.0, method="rodas")
    assert error.value.parameter == "method"


# ------------------------------------------------------------------------------------------------ Detournay bit
def test_depth_of_cut_is_the_rate_of_penetration_per_revolution():
    rop = np.array([5.0, 10.0, 30.0]) / 3600.0  # m/s
    rpm = np.array([60.0, 120.0, 90.0])
    d = fs.DetournayBit.depth_of_cut(rop, rpm * 2.0 * math.pi / 60.0)
    np.testing.assert_allclose(d, rop / (rpm / 60.0), rtol=1e-14)  # metres advanced per revolution
    for args, name in (((1e-3, 0.0), "angular_speed"), ((-1e-3, 1.0), "rate_of_penetration")):
        with pytest.raises(fs.InvalidParameterError) as error:
            fs.DetournayBit.depth_of_cut(*args)
        assert error.value.parameter == name


CODE = dict(bit_radius=0.108, intrinsic_specific_energy=110e6, cutting_force_ratio=0.6, contact_strength=60e6,
            wearflat_length=1.2e-3, friction_coefficient=0.6, contact_orientation=0.9)


@pytest.mark.parametrize("convention", sorted(fs.DetournayBit.CONVENTIONS))
def test_a_codes_convention_gives_that_codes_torque(convention):
    cutting, friction, form = fs.DetournayBit.CONVENTIONS[convention]
    bit = fs.DetournayBit.from_convention(convention, **CODE)
    a, eps, zeta = CODE["bit_radius"], CODE["intrinsic_specific_energy"], CODE["cutting_force_ratio"]
    sigma, l, mu, gamma = (CODE["contact_strength"], CODE["wearflat_length"], CODE["friction_coefficient"],
                           CODE["contact_orientation"])
    for d in (0.0, 3e-4, 2e-3):
        # the code's own closed form, written as that code writes it
        assert bit.torque_on_bit(d) == pytest.approx(cutting * eps * a * a * d + friction * gamma * mu * a * (a * l * sigma),
                                                     rel=1e-14)
        assert bit.weight_on_bit(d) == pytest.approx(zeta * eps * a * d + a * l * sigma, rel=1e-14)
    assert bit.torque_constant == cutting
    assert bit.convention == (convention if cutting == friction else "detournay_defourny")
    assert eval(repr(bit), {"DetournayBit": fs.DetournayBit}).torque_on_bit(1e-3) == bit.torque_on_bit(1e-3)


def _simulator4ndof_bit(depth, angular_speed):
    """The open Simulator4nDOF's drag bit (Open-Source-Drilling-Community, Simulator/BitRockModels/Detournay.cs), as
    that code writes it: d = blades x its per-blade depth, the depth per revolution; its cutting torque carries the factor
    w^2 / (w^2 + (0.4 pi)^2) and its wear flats' torque (1 + exp(-mu w / 2 pi)) / 2."""
    a, eps, zeta = CODE["bit_radius"], CODE["intrinsic_specific_energy"], CODE["cutting_force_ratio"]
    sigma, l, mu, gamma = (CODE["contact_strength"], CODE["wearflat_length"], CODE["friction_coefficient"],
                           CODE["contact_orientation"])
    d = max(depth, 0.0)
    reg = angular_speed / math.sqrt(angular_speed**2 + (2.0 * math.pi * 0.2) ** 2)
    w_f = a * l * sigma
    t_f = 0.5 * (1.0 + math.exp(-mu * angular_speed / (2.0 * math.pi))) * gamma * mu * a / 2.0 * w_f
    return d * a * zeta * eps + w_f, d * a * a * eps / 2.0 * reg**2 + t_f


def test_simulator4ndof_writes_the_detournay_defourny_constants():
    # Its constants are 1/2 on both torque terms; its speed factors are regularisations this law does not carry, so
    # the two agree term by term where those factors are 1: the cutting torque fast (w -> inf), the wear flats' at rest.
    bit = fs.DetournayBit.from_convention("detournay_defourny", **CODE)
    for d in (0.0, 3e-4, 2e-3):
        weight, _ = _simulator4ndof_bit(d, 10.0)
        assert bit.weight_on_bit(d) == pytest.approx(weight, rel=1e-14)
        cutting_fast = _simulator4ndof_bit(d, 1e7)[1] - _simulator4ndof_bit(0.0, 1e7)[1]
        assert bit.torque_on_bit(d) - bit.contact_torque == pytest.approx(cutting_fast, rel=1e-12)
    assert bit.contact_torque == pytest.approx(_simulator4ndof_bit(0.0, 0.0)[1], rel=1e-14)
    # at drilling speed its wear flats rub less than this law's: the factor (1 + e^(-mu w / 2 pi)) / 2 < 1
    w = 10.0
    factor = 0.5 * (1.0 + math.exp(-CODE["friction_coefficient"] * w / (2.0 * math.pi)))
    cut = bit.torque_on_bit(1e-3) - bit.contact_torque
    reg2 = w * w / (w * w + (0.4 * math.pi) ** 2)
    assert _simulator4ndof_bit(1e-3, w)[1] == pytest.approx(cut * reg2 + factor * bit.contact_torque, rel=1e-13)
    assert "Simulator4nDOF" in fs.DetournayBit.CONVENTIONS["detournay_defourny"][2]


def test_the_conventions_differ_as_their_constants_say():
    c = fs.DetournayBit.CONVENTIONS
    assert c["detournay_defourny"][:2] == (0.5, 0.5) and c["unit"][:2] == (1.0, 1.0) and c["half_cutting"][:2] == (0.5, 1.0)
    dd, unit = (fs.DetournayBit.from_convention(n, **CODE) for n in ("detournay_defourny", "unit"))
    assert unit.torque_on_bit(1e-3) == pytest.approx(2.0 * dd.torque_on_bit(1e-3), rel=1e-15)
    half = fs.DetournayBit.from_convention("half_cutting", **CODE)
    # the wear flats' torque of a half-cutting code is the unit convention's, its cutting torque Detournay's
    assert half.contact_torque == pytest.approx(unit.contact_torque, rel=1e-15)
    assert half.torque_on_bit(1e-3) - half.contact_torque == pytest.approx(
        dd.torque_on_bit(1e-3) - dd.contact_torque, rel=1e-14)
    assert half.contact_orientation == pytest.approx(2.0 * CODE["contact_orientation"])
    assert fs.DetournayBit().convention == "detournay_defourny"
    assert fs.DetournayBit(torque_constant=0.7).convention is None
    with pytest.raises(fs.InvalidParameterError) as error:
        fs.DetournayBit.from_convention("aarsnes", **CODE)
    assert error.value.parameter == "convention"
    with pytest.raises(fs.InvalidParameterError) as error:
        fs.DetournayBit.from_convention("unit", torque_constant=0.5)
    assert error.value.parameter == "torque_constant"


# ---------------------------------------------------------------------------------------- TorsionalString, Well B
def well_b_breakoff(density_factor: float) -> float:
    """A&S eq 27 over Well B's survey, written out: vertical to 500 m, 0 -> 60 deg linearly to 1600 m, 60 deg below;
    int sin(inc) dx over the build = (1100 / (pi / 3)) (1 - cos(pi / 3)); F_c = mu g rho A r_o sin(inc)."""
    lengths = np.array([48.700, 114.800, 56.700, 38.880])
    od = np.array([0.150473, 0.187322, 0.209550, 0.247280])
    id_ = np.array([0.096207, 0.098912, 0.071438, 0.123391])
    area = np.sum(lengths * math.pi / 4 * (od ** 2 - id_ ** 2)) / lengths.sum()
    radius = np.sum(lengths * od / 2) / lengths.sum()
    pipe_area = math.pi / 4 * (0.146529 ** 2 - 0.123024 ** 2)
    g, mu, rho, s60 = 9.81, 0.3, 7850.0, math.sin(math.pi / 3)
    pipe = mu * g * rho * pipe_area * 0.146529 / 2
    bha = mu * g * rho * density_factor * area * radius
    return pipe * (1100 / (math.pi / 3) * 0.5 + s60 * (2270 - 1600)) + bha * s60 * 230


@needs_eigen
def test_well_b_breakoff_torque_depends_on_the_wave_speed_variant_not_the_collars_pi():
    torque = {(c, w): fs.aarsnes_shor_well_b(collar=c, wave_speed=w, elements=50).breakoff_torque
              for c in ("as_published", "corrected") for w in ("as_code", "physical")}
    # the collar variants share the collar's area (its weight): the extra pi changes inertia and stiffness only
    assert torque["as_published", "physical"] == pytest.approx(torque["corrected", "physical"], rel=1e-12)
    assert torque["as_published", "as_code"] == pytest.approx(torque["corrected", "as_code"], rel=1e-12)
    # physical: the paper's analytic 19.531 kN m; as_code: the collar 67/61 heavier, 20.536 kN m
    assert torque["corrected", "physical"] == pytest.approx(well_b_breakoff(1.0), rel=1e-9)
    assert torque["corrected", "physical"] == pytest.approx(19531.017405, rel=2e-4)
    assert torque["corrected", "as_code"] == pytest.approx(well_b_breakoff(67.0 / 61.0), rel=1e-9)
    assert torque["corrected", "as_code"] == pytest.approx(20536.3, rel=1e-4)


@needs_eigen
def test_well_b_closed_forms_are_the_papers():
    published = fs.aarsnes_shor_well_b(collar="as_published", wave_speed="physical", elements=100)
    corrected = fs.aarsnes_shor_well_b(collar="corrected", wave_speed="physical", elements=100)
    # the published code's phiMax_TD and eq 30 (tests/aarsnes_shor.test.cpp, from the code's README)
    assert published.top_drive_twist == pytest.approx(27.432806, rel=2e-4)
    assert corrected.top_drive_twist == pytest.approx(27.512625, rel=2e-4)
    assert published.minimum_torque == pytest.approx(5859.305221, rel=2e-4)
    assert published.minimum_torque == pytest.approx(published.breakoff_torque * (1 - 2 * (1 - 0.65)), rel=1e-14)
    assert published.build_up_time == pytest.approx(2 * 0.35 * published.top_drive_twist / (40 * math.pi / 30),
                                                    rel=1e-12)
    assert published.fundamental_period == pytest.approx(7.99, abs=0.01)  # the heavy (pi-fold) collar: slower
    assert corrected.fundamental_period == pytest.approx(5.18, abs=0.01)
    assert published.period_estimate == pytest.approx(published.build_up_time + published.fundamental_period)
    # the nodes' static bounds add up to the break-off torque on any grid
    assert np.sum(published.static_friction_torque) == pytest.approx(published.breakoff_torque, rel=1e-10)


@needs_eigen
def test_fundamental_period_is_the_lumped_strings_lowest_mode():
    """Against SciPy's generalized eigensolver on the lumped string (top node held), independently assembled."""
    from scipy.linalg import eigh

    ts = fs.aarsnes_shor_well_b(collar="corrected", wave_speed="physical", elements=200)
    lumped = ts.string.lump(ts.elements)
    k, j = lumped["torsional_stiffness"], lumped["node_inertia"][1:]
    n = len(k)
    K = np.zeros((n, n))
    for e in range(n):
        K[e, e] += k[e]
        if e > 0:
            K[e - 1, e - 1] += k[e]
            K[e - 1, e] -= k[e]
            K[e, e - 1] -= k[e]
    lowest = eigh(K, np.diag(j), eigvals_only=True, subset_by_index=[0, 0])[0]
    assert 2 * math.pi / math.sqrt(lowest) == pytest.approx(ts.fundamental_period, rel=2e-4)


@needs_eigen
def test_torsional_string_keywords_properties_repr_and_pickle():
    ts = fs.aarsnes_shor_well_b(elements=40, speed_setpoint=5.0)
    assert ts.elements == 40 and ts.nodes == 41 and ts.speed_setpoint == 5.0 and ts.treatment == "captured"
    assert ts.friction_coefficient == 0.3 and ts.control_period == 0.01 and ts.stick_band_speed == 1.5
    assert [p.name for p in fs.TorsionalString.parameters] == [p.name for p in type(ts).parameters]
    assert "breakoff_torque" in fs.TorsionalString.__doc__ and "top_drive_inertia" in fs.TorsionalString.__doc__
    assert "elements" in fs.TorsionalString.__init__.__doc__
    for copy in (pickle.loads(pickle.dumps(ts)), eval(repr(ts), vars(fs))):
        assert repr(copy) == repr(ts)
        assert copy.breakoff_torque == ts.breakoff_torque
        np.testing.assert_array_equal(copy.static_friction_torque, ts.static_friction_torque)
    on_bottom = fs.TorsionalString(ts.string, elements=10, weight_on_bit=5e4, bit=fs.NavarroLopezBit(stick_band=0.1),
                                   treatment="mixed")
    copy = pickle.loads(pickle.dumps(on_bottom))
    assert copy.treatment == "mixed" and copy.bit.stick_band == 0.1 and copy.bit_on_bottom
    assert copy.bit_static_torque == on_bottom.bit_static_torque


@pytest.mark.parametrize("cls", [fs.NavarroLopez2Dof, fs.NavarroLopez4Dof], ids=lambda c: c.__name__)
def test_navarro_lopez_keywords_properties_repr_and_pickle(cls):
    rig = cls(weight_on_bit=25e3, stick_band=0.01)
    for copy in (pickle.loads(pickle.dumps(rig)), eval(repr(rig), vars(fs))):
        assert repr(copy) == repr(rig) and table(copy) == table(rig)
    assert repr(cls()) == f"{cls.__name__}()"
    assert "steady_balance" in cls.__doc__ and "weight_on_bit" in cls.__init__.__doc__
    with pytest.raises(TypeError, match="unexpected keyword argument 'weigth_on_bit'"):
        cls(weigth_on_bit=1.0)
    with pytest.raises(fs.InvalidParameterError) as error:
        cls(static_coefficient=0.1)  # below mu_cb
    assert error.value.parameter == "static_coefficient"


@needs_eigen
@pytest.mark.parametrize("make, parameter", [
    (lambda s: fs.TorsionalString(s, elements=0), "elements"),
    (lambda s: fs.TorsionalString(s, survey=([0.0, 1000.0], [0.0, 0.5])), "survey"),  # ends above the bit
    (lambda s: fs.TorsionalString(s, treatment="mixed"), "treatment"),  # the bit is off bottom
    (lambda s: fs.TorsionalString(s, treatment="implicit"), "treatment"),
    # every contact exact: the event-driven string has no wall at the top drive's node (this one is inclined there)
    (lambda s: fs.TorsionalString(s, treatment="exact"), "static_friction_torque[0]"),
    (lambda s: fs.TorsionalString(s, kinetic_ratio=1.5), "kinetic_ratio"),
    (lambda s: fs.TorsionalString(s, mud_density=9000.0), "mud_density"),  # heavier than the steel: it would float
    (lambda s: fs.TorsionalString(s, contact_radius=[0.07]), "contact_radius"),
    (lambda s: fs.aarsnes_shor_well_b(collar="pi"), "collar"),
    (lambda s: fs.aarsnes_shor_well_b(wave_speed="fast"), "wave_speed"),
    (lambda s: fs.aarsnes_shor_well_b(measured_depth=5000.0), "measured_depth"),
])
def test_bad_inputs_to_the_torsional_string_are_named(make, parameter):
    string = fs.aarsnes_shor_well_b(elements=5).string
    with pytest.raises(fs.InvalidParameterError) as error:
        make(string)
    assert error.value.parameter == parameter, error.value


_PROFILE = settings(max_examples=30, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
_NEW = [fs.NavarroLopez2Dof, fs.NavarroLopez4Dof] + ([fs.TorsionalString] if fs.HAS_EIGEN else [])


def _build(cls, kwargs):
    if cls is fs.TorsionalString:
        return cls(fs.DrillString([fs.PipeSection(length=500.0)]), elements=5, **kwargs)
    return cls(**kwargs)


@pytest.mark.parametrize("cls", _NEW, ids=lambda c: c.__name__)
@_PROFILE
@given(data=st.data())
def test_a_new_table_with_any_parameters_builds_or_is_refused_naming_the_parameter(cls, data):
    kwargs = data.draw(table_kwargs(cls, mutate=True))
    rules = FIELD_TABLES[cls]
    expect = all(valid(rules[k], v) for k, v in kwargs.items())
    expect = expect and all(kwargs[p.name] >= kwargs[p.at_least] for p in cls.parameters if p.at_least)
    if cls is fs.TorsionalString and "mud_density" in kwargs:  # the rule across tables: mud lighter than the steel
        expect = expect and kwargs["mud_density"] < fs.PipeSection(length=500.0).density
    try:
        built = _build(cls, kwargs)
    except fs.InvalidParameterError as error:
        assert error.parameter in rules, error
        assert not expect, f"valid parameters refused: {kwargs}: {error}"
        return
    assert expect, f"invalid parameters accepted: {kwargs} -> {built!r}"
    assert all(getattr(built, k) == v for k, v in kwargs.items())


# ------------------------------------------------------------------------------ Well B through fs.simulate
def cycle_figures(t, bit_speed, motor_torque):
    """tests/aarsnes_shor.test.cpp's cycle statistics: a cycle starts when the bit passes 5 rad/s after resting
    (< 0.5 rad/s); the cycles starting after 15 s that end before the run does; per cycle its bit peak, duration and
    the motor torque's max and min."""
    starts, armed = [], True
    for i, w in enumerate(bit_speed):
        armed = armed or w < 0.5
        if armed and w > 5.0:
            starts.append(i)
            armed = False
    figures = {"peak": [], "period": [], "max_torque": [], "min_torque": []}
    for a, b in zip(starts, starts[1:]):
        if t[a] < 15.0:
            continue
        figures["period"].append(t[b] - t[a])
        figures["peak"].append(np.max(bit_speed[a:b]))
        figures["max_torque"].append(np.max(motor_torque[a:b]))
        figures["min_torque"].append(np.min(motor_torque[a:b]))
    assert len(figures["period"]) >= 3
    return {k: np.array(v) for k, v in figures.items()}


def same_mean(a, b, resolution=0.0) -> bool:
    """Cycle means within three combined standard errors (plus `resolution`), as the C++ test compares them."""
    se = math.hypot(np.std(a, ddof=1) / math.sqrt(len(a)), np.std(b, ddof=1) / math.sqrt(len(b)))
    return abs(np.mean(a) - np.mean(b)) <= 3.0 * se + resolution


@needs_eigen
@pytest.mark.parametrize("collar", ["as_published", "corrected"])
def test_well_b_through_simulate_has_the_published_codes_limit_cycle(collar):
    """Well B at the published grid (1000 cells, h = 2 ms, outputs every 0.01 s) against the published code's run
    (tests/data/aarsnes_shor_2018): bit peak, period and motor torque extremes, cycle by cycle."""
    ts = fs.aarsnes_shor_well_b(collar=collar, wave_speed="as_code", elements=1000)
    times = np.round(np.arange(0.0, 60.0 + 1e-9, 0.01), 10)
    result = fs.simulate(ts, 60.0, method="moreau_jean", step=2e-3, output_times=times)
    assert result.completed and np.all(np.isfinite(result.states))
    ours = cycle_figures(result.t, result["bit_speed"], result["motor_torque"])
    reference = np.genfromtxt(DATA / f"wellb_2500m_40rpm_1000cells_{'published' if collar == 'as_published' else 'corrected'}.csv",
                              delimiter=",", names=True)
    theirs = cycle_figures(reference["time_s"], reference["bit_speed_rad_s"], reference["motor_torque_N_m"])
    assert same_mean(ours["peak"], theirs["peak"])
    assert same_mean(ours["period"], theirs["period"], 0.02)  # the outputs' 0.01 s, at both ends
    assert same_mean(ours["max_torque"], theirs["max_torque"])
    assert same_mean(ours["min_torque"], theirs["min_torque"])
    # the paper's closed forms bracket the cycle: t_fp < period < t_bu + t_fp, the top drive overshoots eq 27
    assert ts.fundamental_period < np.mean(ours["period"]) < ts.period_estimate
    assert np.mean(ours["max_torque"]) > ts.breakoff_torque
    assert np.mean(ours["min_torque"]) == pytest.approx(ts.minimum_torque, rel=0.15)  # eq 30's "approximately"
    # the stuck fraction as the code counts it (|omega| < 1.5 rad/s), after the start-up
    late = reference["time_s"] >= 15.0
    assert abs(np.mean(result["stuck_fraction"][result.t >= 15.0]) - np.mean(reference["stuck_fraction"][late])) < 0.03


@needs_eigen
@pytest.mark.parametrize("make, parameter", [
    (lambda ts: fs.simulate(ts, 1.0, method="moreau_jean", step=0.02, output_times=[0.0, 0.01, 1.0]), "step"),
    (lambda ts: fs.simulate(ts, 1.0, method="moreau_jean", step=0.3), "step"),  # not a whole fraction of t_end
    (lambda ts: fs.simulate(ts, 1.0, method="dormand_prince"), "method"),  # an ODE method on a time-stepping model
    (lambda ts: fs.simulate(fs.NavarroLopez2Dof(), 1.0, step=1e-3), "step"),  # step on an event-driven rig
    (lambda ts: fs.simulate(fs.NavarroLopez2Dof(), 1.0, method="moreau_jean"), "method"),
    (lambda ts: fs.simulate(ts, 1.0, method="moreau_jean", theta=0.2), "theta"),
])
def test_bad_run_options_of_the_torsional_string_are_named(make, parameter):
    ts = fs.aarsnes_shor_well_b(elements=20)
    with pytest.raises(fs.InvalidParameterError) as error:
        make(ts)
    assert error.value.parameter == parameter, error.value


@needs_eigen
def test_a_timeout_keeps_the_partial_result_of_a_1000_element_run():
    ts = fs.aarsnes_shor_well_b(elements=1000)
    with pytest.raises(fs.BudgetExceededError) as info:
        fs.simulate(ts, 3600.0, step=1e-3, timeout=0.3)
    error = info.value
    assert error.budget == "timeout" and 0.0 < error.time_reached < 3600.0
    partial = error.partial
    assert not partial.completed and len(partial.t) > 1 and np.all(np.isfinite(partial.states))
    assert partial.t[-1] <= error.time_reached + 1e-9


@needs_eigen
def test_ctrl_c_stops_a_1000_element_run():
    import _thread
    import threading

    ts = fs.aarsnes_shor_well_b(elements=1000)
    # interrupt_main trips SIGINT's handler as Ctrl-C does; the run would take minutes, the budget (not a timing
    # assertion) would end it as BudgetExceededError if the signal were not polled
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            fs.simulate(ts, 3600.0, step=1e-3, timeout=60.0)
    finally:
        timer.cancel()


@needs_eigen
def test_mixed_treatment_locates_the_bits_switches():
    ts = fs.aarsnes_shor_well_b(elements=100, weight_on_bit=60e3, treatment="mixed", control_period=0.0)
    captured = fs.aarsnes_shor_well_b(elements=100, weight_on_bit=60e3, control_period=0.0)
    times = np.linspace(0.0, 40.0, 401)
    a = fs.simulate(ts, 40.0, step=2e-3, output_times=times)
    b = fs.simulate(captured, 40.0, step=2e-3, output_times=times)
    assert a.completed and b.completed
    # the located switches fall between the step grid's points; the captured ones on it
    located = np.array([e.time for e in a.events])
    assert located.size > 0
    assert np.any(np.abs(located / 2e-3 - np.round(located / 2e-3)) > 1e-3)
    # the same physics: the cycle-mean bit speed agrees within a few per cent
    late = times >= 20.0
    assert np.mean(a["bit_speed"][late]) == pytest.approx(np.mean(b["bit_speed"][late]), rel=0.05)
