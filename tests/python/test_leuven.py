"""The Leuven law (Swevers, Al-Bender, Ganseman & Prajogo 2000; state equation of Lampaert, Swevers & Al-Bender
2002) through Python: against an independent SciPy implementation of its equations with its own stack of turning
points on the kinematic rig, the Stribeck curve in steady sliding, keywords, repr, pickling and parameter errors.

The equations (include/frictionsim/friction/leuven.hpp):
    F = F_h(z) + sigma_1 dz/dt + sigma_2 v,   dz/dt = v (1 - sgn(r) |r|^n),   r = F_d(z) / (S(v) - F_b),
    S(v) = sgn(v) F_N (mu + (mu_s - mu) exp(-|v/v_s|^delta)),
    F_h = F_b + F_d,  F_d(z) = 2 F_vc((z - z_b) / 2) from the last turning point (z_b, F_b), F_vc(z) on the virgin
    curve,  F_vc(x) = k x / (1 + h k |x| / (mu_s F_N)).
Maxwell's rules: a reversal of v pushes (z, F_h); when z passes the turning point before the last along the motion,
that loop is closed and both are popped (the first loop closes on the virgin curve at -z_1).
"""

import math
import pickle

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import frictionsim as fs

# mu, mu_s, v_s [m/s], delta, k [N/m], h, n, sigma_1 [N s/m], sigma_2 [N s/m], F_N [N]
MU, MU_S, V_S, DELTA, K, H, N_EXP = 0.3, 0.4, 1e-3, 2.0, 1e5, 0.5, 2.0
SIGMA1, SIGMA2 = 3.0, 1.5
N = 10.0
RANGE = MU_S * N / (K * (1 - H))  # the virgin curve reaches F_s here: 80 um


def law(**changes):
    p = dict(mu=MU, mu_static=MU_S, stribeck_velocity=V_S, shape_exponent=DELTA, presliding_stiffness=K,
             hysteresis_shape=H, attraction_exponent=N_EXP, micro_damping=SIGMA1, viscous_damping=SIGMA2)
    p.update(changes)
    return fs.Leuven(**p)


# --------------------------------------------------------------------------- the equations, written out again
def stribeck(v):
    return N * (MU + (MU_S - MU) * math.exp(-abs(v / V_S) ** DELTA))


def virgin(x):
    return K * x / (1 + H * K * abs(x) / (MU_S * N))


class Memory:
    """Turning points (z_j, F_j) as a list, newest last, each with the force it had when pushed (the law replays
    them from the displacements instead). Maxwell's rules: a loop counts as closed while z is past, along the
    branch, the turning point before the last (the first loop closes on the virgin curve at -z_1); a reversal
    commits the closed loops and pushes."""

    def __init__(self):
        self.points = []

    def open_points(self, z, branch):
        m = len(self.points)
        while True:
            if m >= 2 and branch * (z - self.points[m - 2][0]) >= 0:
                m -= 2
            elif m == 1 and branch * (z + self.points[0][0]) >= 0:
                m = 0
            else:
                return m

    def curve(self, z, branch):
        """(F_b, F_d) at z."""
        m = self.open_points(z, branch)
        if m == 0:
            return 0.0, virgin(z)
        zb, fb = self.points[m - 1]
        return fb, 2 * virgin((z - zb) / 2)

    def reverse(self, z, branch):
        """v changed sign from `branch`: commit the closed loops, push (z, F_h)."""
        fb, fd = self.curve(z, branch)
        del self.points[self.open_points(z, branch):]
        self.points.append((z, fb + fd))
        assert len(self.points) <= 8  # the law's capacity is never exceeded here


def rate(z, v, branch, memory):
    fb, fd = memory.curve(z, branch)
    span = branch * stribeck(v) - fb
    assert branch * span >= 0.01 * stribeck(v)  # the law's floor on the span is not reached in these runs
    r = fd / span
    return v * (1 - math.copysign(abs(r) ** N_EXP, r))


def friction(z, v, branch, memory):
    fb, fd = memory.curve(z, branch)
    return fb + fd + SIGMA1 * rate(z, v, branch, memory) + SIGMA2 * v


def velocity(t):
    """Nested presliding loops (the amplitude shrinks, then grows: inner loops close and are wiped), then sliding."""
    return 2.0e-4 * (1.2 - 0.9 * math.sin(math.pi * t / 2.0)) * math.cos(4 * math.pi * t) * (1 + 8 * max(t - 2.0, 0.0))


def reversals(t_end):
    """The zero crossings of velocity(t) (those of the cosine): (k + 1/2) / 4."""
    return [(k + 0.5) / 4.0 for k in range(int(4 * t_end) + 1) if (k + 0.5) / 4.0 < t_end]


def scipy_reference(t_eval):
    """z(t), F(t) and the number of loops closed: solve_ivp between the reversals, the branch fixed on each piece."""
    memory = Memory()
    edges = [0.0] + reversals(t_eval[-1]) + [t_eval[-1]]
    z, force = np.empty(len(t_eval)), np.empty(len(t_eval))
    z0, branch, closed = 0.0, 1, 0
    for a, b in zip(edges[:-1], edges[1:]):
        sol = solve_ivp(lambda t, y: [rate(y[0], velocity(t), branch, memory)], (a, b), [z0], method="LSODA",
                        rtol=1e-11, atol=1e-11 * RANGE, max_step=(b - a) / 50, dense_output=True)
        assert sol.success, sol.message
        inside = (t_eval >= a) & (t_eval <= b)
        z[inside] = sol.sol(t_eval[inside])[0]
        for j in np.flatnonzero(inside):
            force[j] = friction(z[j], velocity(t_eval[j]), branch, memory)
        z0 = sol.y[0, -1]
        if b < t_eval[-1]:
            before = len(memory.points)
            memory.reverse(z0, branch)
            closed += (before + 1 - len(memory.points)) // 2
            branch = -branch
    return z, force, closed


# --------------------------------------------------------------------------------- independent SciPy model
def test_kinematic_rig_agrees_with_an_independent_scipy_implementation():
    times = np.linspace(0.0, 3.0, 1201)
    z, force, closings = scipy_reference(times)
    assert closings >= 3  # inner loops closed and wiped while the amplitude grew
    assert np.max(np.abs(force)) > 0.9 * MU * N  # and sliding at the end
    rig = fs.KinematicRig(law(), relative_velocity=velocity, normal_force=N)
    for method in ("dormand_prince", "cvode_bdf"):
        result = fs.simulate(rig, times[-1], method=method, rtol=1e-11, atol=1e-17, output_times=times)
        assert len(result.events) == len(reversals(3.0))
        assert np.max(np.abs(result["presliding_displacement"] - z)) < 1e-6 * RANGE, method
        assert np.max(np.abs(result.friction_force - force)) < 1e-6 * MU_S * N, method
        assert np.all(result["turning_point_count"] <= 8)


# --------------------------------------------------------------------------------------------- steady sliding
@pytest.mark.parametrize("v", [2e-3, -5e-4, 1e-2, -3e-2])
def test_steady_sliding_force_is_the_stribeck_curve_plus_viscous(v):
    t_end = 60 * RANGE / abs(v)
    result = fs.simulate(fs.KinematicRig(law(), relative_velocity=v, normal_force=N), t_end,
                         output_times=[0.0, t_end], rtol=1e-10, atol=1e-16)
    assert result.friction_force[-1] == pytest.approx(math.copysign(stribeck(v), v) + SIGMA2 * v, rel=1e-8)


def test_without_memory_and_linear_it_is_lugre():
    leuven = law(hysteresis_shape=0.0, memory_depth=0, attraction_exponent=1.0)
    lugre = fs.LuGre(mu=MU, mu_static=MU_S, stribeck_velocity=V_S, bristle_stiffness=K, bristle_damping=SIGMA1,
                     viscous_damping=SIGMA2)
    times = np.linspace(0.0, 1.0, 401)
    runs = [fs.simulate(fs.KinematicRig.harmonic(f, sliding_velocity=5e-4, velocity_amplitude=2e-3, frequency=5.0,
                                                 normal_force=N), 1.0, method="cvode_bdf", rtol=1e-10, atol=1e-16,
                        output_times=times) for f in (leuven, lugre)]
    peak = np.max(np.abs(runs[1].friction_force))
    assert peak > 3.0
    assert np.max(np.abs(runs[0].friction_force - runs[1].friction_force)) < 1e-6 * peak


# ------------------------------------------------------------------------------------------------- the law
def test_keywords_are_the_fields_keys_with_defaults_repr_and_pickle():
    leuven = law()
    assert (leuven.mu, leuven.mu_static, leuven.stribeck_velocity, leuven.presliding_stiffness,
            leuven.hysteresis_shape, leuven.attraction_exponent, leuven.micro_damping,
            leuven.viscous_damping) == (MU, MU_S, V_S, K, H, N_EXP, SIGMA1, SIGMA2)
    assert [p.name for p in leuven.parameters] == [
        "mu", "mu_static", "stribeck_velocity", "presliding_stiffness", "shape_exponent", "hysteresis_shape",
        "attraction_exponent", "memory_depth", "micro_damping", "viscous_damping"]
    assert leuven.key == "leuven" and not leuven.has_stick and leuven.stiff
    assert leuven.state_names[0] == "presliding_displacement" and len(leuven.state_names) == 12
    assert "Swevers" in fs.Leuven.__doc__ and "hysteresis_shape" in fs.Leuven.__doc__
    assert "leuven" in [c.key for c in fs.FRICTION_LAWS]
    default = fs.Leuven(mu=MU, mu_static=MU_S, stribeck_velocity=V_S, presliding_stiffness=K)
    assert (default.memory_depth, default.micro_damping, default.viscous_damping) == (8.0, 0.0, 0.0)
    assert repr(eval(repr(leuven), {"Leuven": fs.Leuven})) == repr(leuven)
    copy = pickle.loads(pickle.dumps(leuven))
    assert type(copy) is fs.Leuven and repr(copy) == repr(leuven)


@pytest.mark.parametrize("changes, parameter", [
    (dict(mu=0.0), "mu"),
    (dict(mu_static=0.2), "mu_static"),  # below mu
    (dict(stribeck_velocity=-1e-3), "stribeck_velocity"),
    (dict(presliding_stiffness=float("nan")), "presliding_stiffness"),
    (dict(hysteresis_shape=1.0), "hysteresis_shape"),
    (dict(attraction_exponent=0.5), "attraction_exponent"),
    (dict(memory_depth=9), "memory_depth"),
    (dict(memory_depth=2.5), "memory_depth"),
    (dict(micro_damping=-1.0), "micro_damping"),
    (dict(viscous_damping=-1.0), "viscous_damping"),
])
def test_bad_parameters_are_value_errors_naming_the_parameter(changes, parameter):
    with pytest.raises(ValueError, match=parameter) as info:
        law(**changes)
    assert isinstance(info.value, fs.InvalidParameterError) and info.value.parameter == parameter


# --------------------------------------------------------------------------- on a string's planar walls
def test_a_string_rig_with_leuven_walls_runs_axially_the_1d_law_along_an_axis_that_follows_the_sliding():
    # fs.StringRig(axial=True) with fs.Leuven at the walls (contact/wall_contact.hpp: the 1D law along a reference
    # axis, a state slip_axis_i, that follows the sliding over l = F_s / k; a reversal is q . d falling through 0).
    # Pulled at the hook speed v along a horizontal hole while turning at w, in steady sliding: the axis lies along
    # q = (v, r w), F = S(|q|) = mu F_N against it, so the hook holds back mu F_N v / |q| (paper 000's friction
    # vector) and the drive supplies mu F_N r (r w) / |q|; no reversal is counted
    pipe = fs.PipeSection(length=300.0)
    wall = law(mu=0.3, mu_static=0.3, presliding_stiffness=1e7, micro_damping=0.0, viscous_damping=0.0)
    v, w = 0.2, 2.0
    rig = fs.StringRig(fs.DrillString([pipe]), wall, elements=4, axial=True, inclination=math.pi / 2,
                       damping_time=0.02, top_drive="prescribed_speed", surface_speed=w, initial_speed=w,
                       hook_speed=v, initial_axial_speed=v)
    result = fs.simulate(rig, 4.0, rtol=1e-9, atol=1e-12, output_times=[4.0])
    assert result.completed and not result.events
    r = rig.node_radius[1]
    axis = [result.states[-1, list(result.state_names).index(f"slip_axis_{i}")] for i in range(1, 5)]
    assert np.allclose(axis, math.atan2(r * w, v), rtol=0.0, atol=1e-9)
    slide = math.hypot(v, r * w)
    normal = sum(rig.normal_forces)
    assert -rig.hook_force(result.t, result.states)[-1] == pytest.approx(0.3 * normal * v / slide, rel=1e-6)
    assert rig.surface_torque(result.t, result.states)[-1] == pytest.approx(0.3 * normal * r * r * w / slide, rel=1e-6)


def test_a_string_rig_with_leuven_walls_counts_reversals_where_an_axial_vibration_turns_the_sliding_back():
    # barely turning (r w = 1.3 mm/s) and shaken axially at the bottom (5 Hz): each contact's sliding turns back
    # twice a cycle, a "sliding_reversal" that flips the branch and pushes a turning point; turning at 4 rad/s
    # (r w = 0.25 m/s above every axial speed) the sliding never turns back: none
    pipe = fs.PipeSection(length=300.0)
    wall = law(presliding_stiffness=1e7, micro_damping=0.0, viscous_damping=0.0)
    counts = {}
    for w in (0.02, 4.0):
        rig = fs.StringRig(fs.DrillString([pipe]), wall, elements=3, axial=True, inclination=math.pi / 2,
                           damping_time=0.01, top_drive="prescribed_speed", surface_speed=w, initial_speed=w,
                           excitation_amplitude=4e3, excitation_frequency=5.0, excitation_node=3)
        result = fs.simulate(rig, 1.0, rtol=1e-8, atol=1e-10)
        assert result.completed
        for event in result.events:
            assert event.name.endswith("sliding_reversal") and event.mode_after == -event.mode_before
        counts[w] = len(result.events)
        if w < 1.0:
            names = list(result.state_names)
            pushed = result.states[-1, [names.index(f"turning_point_count_{i}") for i in (1, 2, 3)]]
            assert all(pushed >= 1)
    assert counts[0.02] >= 15 and counts[4.0] == 0
