"""One rig registration (issue 22 item 4): every rig of the engine's C++ list (EngineRigs, rigs/rigs.hpp) is bound
from it through bind_rig, and declares the units of its outputs in C++ (``Rig.outputs``) next to its parameter
table; frictionsim.outputs reads those declarations, so units in files and on plots come from C++."""

import pickle

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import outputs

#: The rigs of EngineRigs, in the list's order (the string models are bound apart, after them).
LIST_RIGS = (fs.AxialVibrationRig, fs.KinematicRig, fs.TorsionalRig, fs.NavarroLopez2Dof, fs.NavarroLopez4Dof)


def build(cls):
    if cls is fs.KinematicRig:
        return cls(fs.LuGre(0.3, 0.4, 1e-3, 1e5, 300.0), relative_velocity=0.01, normal_force=10.0)
    if cls in (fs.AxialVibrationRig, fs.TorsionalRig):
        return cls(fs.LuGre(0.3, 0.4, 1e-3, 1e5, 300.0))
    return cls()


def test_the_bound_rigs_are_the_lists_in_its_order():
    assert tuple(cls for cls in fs._core.RIGS if cls in LIST_RIGS) == LIST_RIGS
    assert fs._core.RIGS.index(fs.StringRig) == 3  # fs.NavarroLopezBit bound before the rigs whose .bit it is


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
