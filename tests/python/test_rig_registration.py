"""One rig registration (issue 22 item 4): every rig of the engine's C++ list (EngineRigs, rigs/rigs.hpp), the string
models too, is bound from it (register_rig), and declares the units of its outputs in C++ (``Rig.outputs``) next to
its parameter table; frictionsim.outputs reads those declarations, so units in files and on plots come from C++."""

import math
import pickle
import pydoc

import numpy as np
import pytest
from scipy.optimize import brentq

import frictionsim as fs
from frictionsim import outputs

needs_eigen = pytest.mark.skipif(not fs.HAS_EIGEN, reason="the extension was built without Eigen")

#: The lab rigs of EngineRigs, in the list's order (the string models between and after them: see below).
LIST_RIGS = (fs.AxialVibrationRig, fs.KinematicRig, fs.TorsionalRig, fs.NavarroLopez2Dof, fs.NavarroLopez4Dof)
#: Every class of EngineRigs in its order, as _core.RIGS binds them.
ALL_RIGS = (fs.AxialVibrationRig, fs.KinematicRig, fs.TorsionalRig, fs.StringRig, fs.NavarroLopez2Dof,
            fs.NavarroLopez4Dof) + ((fs.TorsionalString,) if fs.HAS_EIGEN else ())


def build(cls):
    if cls is fs.KinematicRig:
        return cls(fs.LuGre(0.3, 0.4, 1e-3, 1e5, 300.0), relative_velocity=0.01, normal_force=10.0)
    if cls in (fs.AxialVibrationRig, fs.TorsionalRig):
        return cls(fs.LuGre(0.3, 0.4, 1e-3, 1e5, 300.0))
    return cls()


def test_the_bound_rigs_are_the_lists_in_its_order():
    assert fs._core.RIGS == ALL_RIGS
    assert fs._core.RIGS.index(fs.StringRig) == 3  # fs.NavarroLopezBit bound before the rigs whose .bit it is
    assert all(outputs.RIG_OUTPUTS[cls] == outputs.declared_outputs(cls) for cls in fs._core.RIGS)


@pytest.mark.parametrize("cls", LIST_RIGS, ids=lambda c: c.__name__)
def test_each_rig_declares_its_outputs_in_cpp_one_row_per_own_state(cls):
    rows = cls.outputs
    assert all(isinstance(r, tuple) and len(r) == 3 and all(isinstance(x, str) and x for x in r) for r in rows)
    names = [name for name, _, _ in rows]
    assert names[0] == "friction_force" and len(set(names)) == len(names)
    rig = build(cls)
    law_states = set(getattr(getattr(rig, "friction", None), "state_names", ()))
    assert set(names) == {"friction_force"} | (set(rig.state_names) - law_states)
    assert outputs.RIG_OUTPUTS[cls] == outputs.declared_outputs(cls)


def test_units_a_user_sees_are_unchanged():
    """The columns' units as frictionsim 0.x wrote them into files before the declaration moved to C++."""
    units = outputs.output_units(fs.NavarroLopez4Dof())
    assert units == {
        "t": "s", "friction_force": "N m", "friction_impulse": "N m s", "table_speed": "rad/s",
        "upper_pipe_speed": "rad/s", "lower_pipe_speed": "rad/s", "bit_speed": "rad/s", "table_twist": "rad",
        "pipe_twist": "rad", "bit_twist": "rad", "motor_work": "J", "damping_work": "J", "friction_work": "J"}
    assert outputs.output_units(fs.NavarroLopez2Dof())["string_twist"] == "rad"
    torsional = outputs.output_units(build(fs.TorsionalRig))
    assert torsional["current"] == "A" and torsional["friction_impulse"] == "N m s"
    assert torsional["bristle_deflection"] == "m" and torsional["speed_error_integral"] == "rad"
    kinematic = outputs.output_units(build(fs.KinematicRig))
    assert kinematic == {"t": "s", "friction_force": "N", "friction_impulse": "N s", "bristle_deflection": "m",
                         "friction_work": "J"}
    assert outputs.output_units(build(fs.AxialVibrationRig))["drive_work"] == "J"


def test_the_string_models_declare_their_outputs_in_cpp():
    """StringRig's declaration reads as the entry frictionsim.outputs wrote for it in Python before (units in files
    unchanged); TorsionalString's too, but for its mode column, now declared as what it is: a count of the wall
    contacts at rest (as StringRig's), no longer read as a contact flag (-1, 0, +1)."""
    work = dict.fromkeys(("drive_work", "hoist_work", "excitation_work", "wall_friction_work", "damping_work",
                          "bit_work"), "J")
    assert outputs.declared_outputs(fs.StringRig) == outputs.RigOutputs(
        "N m", {"speed_error_integral": "rad", "held_motor_torque": "N m", "sampled_setpoint": "rad/s",
                "next_sample": "1", **work},
        {"theta": "rad", "omega": "rad/s", "u": "m", "v": "m/s", "slip_axis": "rad"}, "stuck contacts")
    if fs.HAS_EIGEN:
        assert outputs.declared_outputs(fs.TorsionalString) == outputs.RigOutputs("N m", {
            "bit_speed": "rad/s", "top_drive_speed": "rad/s", "motor_torque": "N m", "stuck_fraction": "1"},
            {}, "stuck contacts")
    # a Leuven wall law's planar reference axis (axial runs) is an angle: its column says so in files and plots
    leuven = fs.StringRig(fs.DrillString([fs.PipeSection(length=300.0)]), fs.Leuven(0.3, 0.4, 1e-3, 1e7),
                          elements=3, axial=True, top_drive="prescribed_speed")
    axes = [name for name in leuven.state_names if name.startswith("slip_axis_")]
    assert axes and all(outputs.output_units(leuven)[name] == "rad" for name in axes)
    for cls in (fs.StringRig,) + ((fs.TorsionalString,) if fs.HAS_EIGEN else ()):
        assert all(unit and what for _, unit, what in cls.outputs)
        assert cls.outputs[0][:2] == ("friction_force", "N m")


@needs_eigen
def test_a_torsional_strings_mode_counts_its_wall_contacts_at_rest():
    """From rest every wall contact is stuck: the mode column starts at contact_count and never exceeds it; files
    say it is a count."""
    string = fs.aarsnes_shor_well_b(elements=20)
    run = fs.simulate(string, 3.0, method="moreau_jean", step=1e-3, output_times=np.linspace(0.0, 3.0, 31))
    assert run.units["mode"] == "1" and run.units["stuck_fraction"] == "1" and run.units["bit_speed"] == "rad/s"
    assert run.mode[0] == string.contact_count > 0
    assert np.all((0 <= run.mode) & (run.mode <= string.contact_count))
    assert run.units["friction_force"] == "N m" and run.units["motor_torque"] == "N m"
    xr = pytest.importorskip("xarray")
    dataset = run.to_xarray()
    assert isinstance(dataset, xr.Dataset) and dataset["mode"].attrs["long_name"] == "stuck wall contacts"
    assert dataset["top_drive_speed"].attrs["units"] == "rad/s"


def balance_root(rig) -> float:
    """Root of u - (c_r + c_b) w - R_b W mu_b(w) = 0, the Navarro-Lopez strings' steady speed (the sum of all their
    equations at a common speed w), mu_b written out here, by SciPy's brentq."""
    def f(w):
        mu = rig.coulomb_coefficient + (rig.static_coefficient - rig.coulomb_coefficient) * math.exp(
            -rig.weakening_rate * w / rig.velocity_scale)
        return rig.motor_torque - (rig.table_damping + rig.bit_damping) * w - rig.bit_radius * rig.weight_on_bit * mu
    return brentq(f, 0.0, rig.motor_torque / (rig.table_damping + rig.bit_damping) + 1.0, xtol=1e-14)


def test_a_rig_built_from_its_table_alone_runs_through_the_generic_binding():
    """NavarroLopez2Dof is bound by register_rig's generic code (its table, its C++ description; its own methods
    added by def_rig_methods): what a new rig of a header and a line in EngineRigs gets. By keywords, help(), repr
    and pickling that rebuild it, and a run that reaches the closed-form steady state."""
    cls = fs.NavarroLopez2Dof
    rig = cls(weight_on_bit=15e3, initial_speed=4.0, bit_damping=60.0)
    doc = pydoc.render_doc(cls, renderer=pydoc.plaintext)
    assert "Navarro-Lopez & Suarez (2004)" in cls.__doc__ and "u - (c_r + c_b) w - R_b W mu_b(w) = 0" in cls.__doc__
    keywords = cls.__doc__.split("Keywords\n--------\n", 1)[1]
    assert all(p.name in keywords and p.name in doc for p in cls.parameters)
    assert repr(rig) == "NavarroLopez2Dof(bit_damping=60, weight_on_bit=15000, initial_speed=4)"
    copies = (pickle.loads(pickle.dumps(rig)), eval(repr(rig), vars(fs)))
    assert all(repr(c) == repr(rig) and c.bit_damping == 60.0 for c in copies)
    w = balance_root(rig)
    for r in (rig,) + copies:
        run = fs.simulate(r, 150.0, rtol=1e-9, atol=1e-9, output_times=[150.0])
        assert run["bit_speed"][-1] == pytest.approx(w, rel=1e-6)
        assert run["table_speed"][-1] == pytest.approx(w, rel=1e-6)
        # the string carries the bit's torque at the steady speed: k_t twist = c_b w + R_b W mu_b(w)
        mu = rig.coulomb_coefficient + (rig.static_coefficient - rig.coulomb_coefficient) * math.exp(
            -rig.weakening_rate * w / rig.velocity_scale)
        torque = rig.bit_damping * w + rig.bit_radius * rig.weight_on_bit * mu
        assert rig.string_stiffness * run["string_twist"][-1] == pytest.approx(torque, rel=1e-6)
        assert run.units["string_twist"] == "rad" and run.units["friction_force"] == "N m"


def test_a_declaration_of_per_node_states_and_a_counted_mode_reads_as_the_string_models_need():
    """How a string model declares its outputs in C++ (rows ``theta_*``, ``mode`` of unit "1"), read back."""
    class Declared:
        outputs = (("friction_force", "N m", "bit torque"), ("theta_*", "rad", "node angle"),
                   ("bit_work", "J", "bit work"), ("mode", "1", "stuck wall contacts"))
    declared = outputs.declared_outputs(Declared)
    assert declared == outputs.RigOutputs("N m", {"bit_work": "J"}, {"theta": "rad"}, "stuck contacts")


@pytest.mark.parametrize("cls", [fs.NavarroLopez2Dof, fs.NavarroLopez4Dof], ids=lambda c: c.__name__)
def test_a_rig_without_a_law_goes_through_bind_rig(cls):
    """The table-only rigs have what bind_rig gives every rig: keywords (nothing positional, no friction), a
    signature written from the table, properties and parameters, repr that rebuilds, pickling by construction."""
    assert not hasattr(cls(), "friction")
    assert cls.__init__.__doc__.startswith("__init__(self, *, ")
    with pytest.raises(TypeError):
        cls(1.0)
    with pytest.raises((TypeError, ValueError), match="weight_on_bit"):
        cls(weight_on_bit="heavy")
    rig = cls(weight_on_bit=20e3, initial_speed=5.0)
    assert [p.name for p in cls.parameters][-3:] == ["motor_torque", "weight_on_bit", "initial_speed"]
    assert rig.weight_on_bit == 20e3 and repr(rig) == f"{cls.__name__}(weight_on_bit=20000, initial_speed=5)"
    for copy in (pickle.loads(pickle.dumps(rig)), eval(repr(rig), vars(fs))):
        assert repr(copy) == repr(rig)
        a, b = fs.simulate(rig, 2.0), fs.simulate(copy, 2.0)
        assert np.array_equal(a.y, b.y)  # the same rig, bit for bit
    run = fs.simulate(rig, 2.0)
    assert run.units["friction_force"] == "N m" and run.units["bit_speed"] == "rad/s"
