"""The generalized Maxwell-slip law (Al-Bender, Lampaert & Swevers 2005) through Python: against an independent
SciPy implementation of its equations on the kinematic rig, the Stribeck curve in steady sliding, keywords, repr,
pickling and parameter errors.

The equations (include/frictionsim/friction/gms.hpp): four blocks, block i with stiffness k_i, weight alpha_i and
deflection z_i; s(v) = F_N (mu + (mu_s - mu) exp(-|v/v_s|^delta)), share S_i = alpha_i s(v), load along the motion
u_i = sgn(v) k_i z_i. The paper's stick (dF_i/dt = k_i v) and slip (dF_i/dt = sgn(v) C (alpha_i - F_i/s)) equations,
switched where their rates along the motion are equal, so the right-hand side is continuous:
    sgn(v) dz_i/dt = min(|v|, lambda_i (S_i - u_i)),
    lambda_i = C / (k_i s) if u_i >= S_i, else max(C / (k_i s), |v| / S_i),
    F = sum_i (k_i z_i + sigma_1 dz_i/dt) + sigma_2 v.
"""

import math
import pickle

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import frictionsim as fs

# mu, mu_s, v_s [m/s], delta, C [N/s], k_i [N/m], alpha_i, sigma_1 [N s/m], sigma_2 [N s/m], F_N [N]
MU, MU_S, V_S, DELTA, C = 0.3, 0.4, 1e-3, 2.0, 4000.0
K = (8e4, 4e4, 2e4, 1e4)
ALPHA = (0.1, 0.2, 0.3, 0.4)
SIGMA1, SIGMA2 = 3.0, 1.5
N = 10.0
Z_S = tuple(a * MU_S * N / k for k, a in zip(K, ALPHA))  # break-away deflections [m]: 5, 20, 60, 160 um
STATES = ["block_deflection_1", "block_deflection_2", "block_deflection_3", "block_deflection_4"]


def law(**changes):
    p = dict(mu=MU, mu_static=MU_S, stribeck_velocity=V_S, shape_exponent=DELTA, attraction=C,
             block_damping=SIGMA1, viscous_damping=SIGMA2)
    for i in range(4):
        p[f"block_stiffness_{i + 1}"] = K[i]
        p[f"block_weight_{i + 1}"] = ALPHA[i]
    p.update(changes)
    return fs.GeneralizedMaxwellSlip(**p)


# --------------------------------------------------------------------------- the equations, written out again
def stribeck(v, normal=N):
    """s(v) [N]."""
    return normal * (MU + (MU_S - MU) * math.exp(-abs(v / V_S) ** DELTA))


def regime_and_rate(z, i, v, branch, normal=N):
    """("stick" | "attraction" | "taper", dz_i/dt) of block i on branch sgn(v)."""
    s = stribeck(v, normal)
    share, load, speed = ALPHA[i] * s, branch * K[i] * z, branch * v
    lam, regime = C / (K[i] * s), "attraction"  # the paper's slip equation: dF_i/dt = sgn(v) C (alpha_i - F_i/s)
    if load < share and speed / share > lam:  # loading faster than C allows: spread over 0 <= u_i <= S_i
        lam, regime = speed / share, "taper"
    pull = lam * (share - load)
    if speed <= pull:
        return "stick", v
    return regime, branch * pull


def rates(z, v, branch):
    return [regime_and_rate(z[i], i, v, branch)[1] for i in range(4)]


def friction(z, v, branch):
    """F = sum_i (k_i z_i + sigma_1 dz_i/dt) + sigma_2 v [N]."""
    return sum(K[i] * z[i] for i in range(4)) + SIGMA1 * sum(rates(z, v, branch)) + SIGMA2 * v


def scipy_harmonic(v_d, v_a, f, t_eval):
    """z(t) (4 x len(t_eval)) and F(t) under v = v_d - v_a cos(2 pi f t), integrated between the zero crossings of
    v (where the branch flips) with the branch fixed on each piece."""
    w, t_end = 2 * math.pi * f, t_eval[-1]
    c = math.acos(v_d / v_a)
    crossings = sorted(t for k in range(int(t_end * f) + 2) for t in ((c + 2 * math.pi * k) / w,
                                                                     (2 * math.pi * (k + 1) - c) / w)
                       if 0.0 < t < t_end)
    edges = [0.0] + crossings + [t_end]
    z = np.empty((4, len(t_eval)))
    z0 = [0.0, 0.0, 0.0, 0.0]
    for a, b in zip(edges[:-1], edges[1:]):
        branch = 1 if v_d - v_a * math.cos(w * 0.5 * (a + b)) > 0 else -1
        sol = solve_ivp(lambda t, y: rates(y, v_d - v_a * math.cos(w * t), branch), (a, b), z0, method="LSODA",
                        rtol=1e-11, atol=[1e-11 * zs for zs in Z_S], max_step=(b - a) / 50, dense_output=True)
        assert sol.success, sol.message
        inside = (t_eval >= a) & (t_eval <= b)
        z[:, inside] = sol.sol(t_eval[inside])
        z0 = list(sol.y[:, -1])  # at b itself: the next piece starts at the crossing
    v = v_d - v_a * np.cos(w * t_eval)
    force = np.array([friction(z[:, j], v[j], 1 if v[j] > 0 else -1) for j in range(len(t_eval))])
    return z, force


# --------------------------------------------------------------------------------- independent SciPy model
def test_kinematic_rig_agrees_with_an_independent_scipy_implementation():
    # v_r = 2 mm/s - 10 mm/s cos(2 pi 5 Hz t) over two cycles: presliding after each reversal (every block
    # sticks, then slips from the stiffest to the softest), the paper's slip equation through the Stribeck range,
    # and above C alpha_i / k_i (5 mm/s for block 1, 20 mm/s for block 2) the taper of fast loading.
    v_d, v_a, f = 2e-3, 1e-2, 5.0
    times = np.linspace(0.0, 2 / f, 401)
    z, force = scipy_harmonic(v_d, v_a, f, times)
    v = v_d - v_a * np.cos(2 * math.pi * f * times)
    regimes = [regime_and_rate(z[i, j], i, v[j], 1 if v[j] > 0 else -1)[0] for i in range(4)
               for j in range(len(times))]
    assert min(regimes.count(r) for r in ("stick", "attraction", "taper")) > 20  # measured 427, 1099, 78
    for i in range(4):  # every block slides in both directions: |z_i| reaches its share
        assert np.max(np.abs(z[i])) > 0.7 * Z_S[i]
    rig = fs.KinematicRig.harmonic(law(), sliding_velocity=v_d, velocity_amplitude=v_a, frequency=f, normal_force=N)
    for method in ("dormand_prince", "cvode_bdf"):
        result = fs.simulate(rig, times[-1], method=method, rtol=1e-12, atol=1e-17, output_times=times)
        assert result.state_names == STATES + ["friction_impulse", "friction_work"]
        assert len(result.events) == 4  # the reversals
        # measured (the engine's C++ core, same equations and outputs): z within 1.0e-9 Z_S (dormand_prince) and
        # 1.8e-10 Z_S (cvode_bdf), F within 2.5e-10 and 4.7e-11 of F_s
        for i, name in enumerate(STATES):
            assert np.max(np.abs(result[name] - z[i])) < 1e-8 * Z_S[i], (method, name)
        assert np.max(np.abs(result.friction_force - force)) < 1e-8 * MU_S * N, method


# --------------------------------------------------------------------------------------------- steady sliding
@pytest.mark.parametrize("v", [2e-3, -5e-4, 1e-2, -3e-2])
def test_steady_sliding_force_is_the_stribeck_curve_plus_viscous(v):
    # every block ends at its share alpha_i s(v): F = s(v) sgn(v) + sigma_2 v (sigma_1 drops out with dz/dt)
    t_end = 3 * max(Z_S) / abs(v) + 40 * MU_S * N / C
    result = fs.simulate(fs.KinematicRig(law(), relative_velocity=v, normal_force=N), t_end,
                         output_times=[0.0, t_end], rtol=1e-10, atol=1e-16)
    assert result.friction_force[-1] == pytest.approx(math.copysign(stribeck(v), v) + SIGMA2 * v, rel=1e-9)
    for i, name in enumerate(STATES):
        assert K[i] * result[name][-1] == pytest.approx(math.copysign(ALPHA[i] * stribeck(v), v), rel=1e-8)


# ------------------------------------------------------------------------------------------------- the law
def test_keywords_are_the_fields_keys_with_defaults_repr_and_pickle():
    gms = law()
    assert (gms.mu, gms.mu_static, gms.stribeck_velocity, gms.shape_exponent, gms.attraction, gms.block_damping,
            gms.viscous_damping) == (MU, MU_S, V_S, DELTA, C, SIGMA1, SIGMA2)
    assert tuple(getattr(gms, f"block_stiffness_{i}") for i in (1, 2, 3, 4)) == K
    assert tuple(getattr(gms, f"block_weight_{i}") for i in (1, 2, 3, 4)) == ALPHA
    assert [p.name for p in gms.parameters] == [
        "mu", "mu_static", "stribeck_velocity", "shape_exponent", "attraction", "block_stiffness_1",
        "block_stiffness_2", "block_stiffness_3", "block_stiffness_4", "block_weight_1", "block_weight_2",
        "block_weight_3", "block_weight_4", "block_damping", "viscous_damping"]
    assert gms.key == "gms" and tuple(gms.state_names) == tuple(STATES) and not gms.has_stick
    default = fs.GeneralizedMaxwellSlip(mu=MU, mu_static=MU_S, stribeck_velocity=V_S)
    assert (default.block_damping, default.viscous_damping, default.attraction) == (0.0, 0.0, C)
    assert repr(eval(repr(gms), {"GeneralizedMaxwellSlip": fs.GeneralizedMaxwellSlip})) == repr(gms)
    copy = pickle.loads(pickle.dumps(gms))
    assert type(copy) is fs.GeneralizedMaxwellSlip and repr(copy) == repr(gms)


@pytest.mark.parametrize("changes, parameter", [
    (dict(mu=0.0), "mu"),
    (dict(mu_static=0.2), "mu_static"),  # below mu
    (dict(stribeck_velocity=-1e-3), "stribeck_velocity"),
    (dict(shape_exponent=0.0), "shape_exponent"),
    (dict(attraction=float("nan")), "attraction"),
    (dict(block_stiffness_3=0.0), "block_stiffness_3"),
    (dict(block_weight_2=0.0), "block_weight_2"),
    (dict(block_weight_4=0.5), "block_weight_4"),  # the weights sum to 1.1
    (dict(block_damping=-1.0), "block_damping"),
    (dict(viscous_damping=-1.0), "viscous_damping"),
])
def test_bad_parameters_are_value_errors_naming_the_parameter(changes, parameter):
    with pytest.raises(ValueError, match=parameter) as info:
        law(**changes)
    assert isinstance(info.value, fs.InvalidParameterError) and info.value.parameter == parameter


def test_weights_must_sum_to_one():
    with pytest.raises(fs.InvalidParameterError, match="sum to 1") as info:
        law(block_weight_1=0.2)
    assert info.value.parameter == "block_weight_4"
    law(block_weight_1=0.1 + 1e-12)  # rounding of decimal inputs is not an error


def test_scenario_files_name_it_by_its_key_on_every_rig():
    """A scenario's friction table takes GMS's table keys (type = its key); no scenario code names the law."""
    keys = ", ".join(f"{p.name} = {getattr(law(), p.name)!r}" for p in fs.GeneralizedMaxwellSlip.parameters)
    text = ('rig = { type = "kinematic", normal_force = 10.0, sliding_velocity = 2e-3, velocity_amplitude = 1e-2, '
            'frequency = 5.0 }\nsolver = { t_end = 1.0, rtol = 1e-9, atol = 1e-15, output_points = 1001 }\n'
            'analysis = { cycles = 3 }\n[[case]]\nname = "gms"\nfriction = { type = "gms", ' + keys + ' }\n')
    parsed = fs.scenario.loads(text, source="gms.toml")
    case = parsed.cases[0]
    assert repr(case.friction.build()) == repr(law())
    run = fs.scenario.run_case(case)
    rig = fs.KinematicRig.harmonic(law(), sliding_velocity=2e-3, velocity_amplitude=1e-2, frequency=5.0,
                                   normal_force=N)
    t_a, _, cycles = case.window()
    result = fs.simulate(rig, 1.0, rtol=1e-9, atol=1e-15, output_times=case.output_times())
    assert run.mean_friction == pytest.approx(result.mean_over_cycles(transient=t_a, cycles=cycles), rel=1e-9)
    for rig_table in ('{ type = "axial" }', '{ type = "torsional" }'):
        other = fs.scenario.loads(f'rig = {rig_table}\nsolver = {{ t_end = 0.5 }}\n'
                                  f'friction = {{ type = "gms", {keys} }}\n')
        assert isinstance(other.cases[0].build().friction, fs.GeneralizedMaxwellSlip)
    with pytest.raises(fs.scenario.ScenarioError) as info:  # the table's rule, at the file's key
        fs.scenario.loads(text.replace("attraction = ", "attraction = -"), source="gms.toml")
    assert info.value.key == "case[1].friction.attraction" and "positive" in str(info.value)
