"""frictionsim.axial, paper 000's rig module: closed-form against simulated reduction, bounds on F_df, the presets
read from the engine, Table 4 beside the simulation, and the old names in frictionsim.sweeps."""

from __future__ import annotations

import math

import pytest

import frictionsim as fs
from frictionsim import axial


@pytest.mark.parametrize("ratio", [0.05, 0.3, 0.7, 0.95, 1.5])
def test_closed_form_reduction_matches_the_simulated_kinematic_coulomb_rig(ratio):
    """1 - (2/pi) asin(v_d/v_a) (0 once v_r no longer reverses) is what eq 8 averages to under v_d - v_a cos(w t)."""
    expected = 1.0 - 2.0 / math.pi * math.asin(ratio) if ratio < 1 else 0.0
    assert axial.coulomb_reduction(ratio) == pytest.approx(expected, abs=1e-15)
    assert axial.kinematic_coulomb_reduction(ratio) == pytest.approx(expected, abs=1e-6)


@pytest.mark.parametrize("amplitude", [0.0, 1e-5, 1e-4, 5e-3])
def test_fig7a_coulomb_mean_friction_is_bounded_by_mu_n(amplitude):
    """|F_F| <= mu F_N at every instant, so its mean over whole cycles is too; the drive pulls forward, so F_df > 0.
    Without vibration the rig slides steadily at v_d and F_df = mu F_N (Table 4's F_sf)."""
    rig = axial.fig7a_rig_parameters()
    mu_n = axial.FIG7A_MU * rig["normal_force"]
    mean = axial.axial_mean_friction(friction=fs.Coulomb(axial.FIG7A_MU), amplitude=amplitude, t_end=4.0,
                                     transient=3.0, rtol=1e-9)
    assert 0.0 < mean <= mu_n * (1 + 1e-9)
    if amplitude == 0.0:
        assert mean == pytest.approx(mu_n, rel=1e-6)
    if amplitude == rig["amplitude"]:  # Fig. 7(a): v_a/v_d = 534, friction nearly gone (reduction > 99 %)
        assert mean < 0.01 * mu_n


def test_presets_are_the_engines_defaults():
    params = axial.fig7a_rig_parameters()
    assert params == {p.name: p.default for p in fs.AxialVibrationRig.parameters}
    assert (params["amplitude"], params["frequency"], params["normal_force"]) == (5e-3, 17.0, 90.0)  # Table 4 VS3
    for law in axial.fig7a_laws().values():
        assert repr(fs.AxialVibrationRig(law, **params)) == repr(fs.AxialVibrationRig(law))


def test_table4_comparison_of_fig7a_finds_vs3():
    row = axial.table4_comparison(fs.Coulomb(axial.FIG7A_MU), lubricant="dry")
    assert row["table4_run"] == "VS3"
    assert row["F_sf_sim_N"] == pytest.approx(axial.FIG7A_MU * 90.0, rel=1e-6)
    assert row["F_sf_table4_N"] == 36.87 and row["F_df_table4_N"] == 9.27
    assert row["velocity_ratio"] == pytest.approx(2 * math.pi * 17.0 * 5e-3 / 1e-3)
    assert 0.0 < row["F_df_sim_N"] < row["F_sf_sim_N"]


def test_reduction_sweep_adds_the_rigs_own_ratio_and_its_table4_run():
    frame = axial.reduction_sweep([0.8, 0.4], laws={"coulomb": fs.Coulomb(axial.FIG7A_MU)})
    own = 1e-3 / (2 * math.pi * 17.0 * 5e-3)
    assert list(frame["velocity_ratio"]) == pytest.approx([own, 0.4, 0.8])
    assert list(frame.columns) == ["velocity_ratio", "velocity_amplitude_m_per_s", "amplitude_mm",
                                   "coulomb_closed_form", "kinematic_coulomb", "axial_coulomb", "table5_dry",
                                   "table4_dry"]
    assert frame["table4_dry"].iloc[0] == pytest.approx(1 - 9.27 / 36.87)
    assert frame["table4_dry"].iloc[1:].isna().all() and frame["table5_dry"].iloc[1:].isna().all()
    assert frame["kinematic_coulomb"].to_numpy() == pytest.approx(frame["coulomb_closed_form"].to_numpy(), abs=1e-6)


def test_bad_input_names_the_parameter():
    with pytest.raises(fs.InvalidParameterError) as error:
        axial.coulomb_reduction(0.0)
    assert error.value.parameter == "ratio"
    with pytest.raises(fs.InvalidParameterError) as error:
        axial.axial_reduction(fs.Coulomb(0.4), 0.5, amplitude=1e-3)
    assert error.value.parameter == "amplitude"


def test_old_names_are_the_moved_functions():
    import frictionsim.fit
    import frictionsim.fit.rig
    import frictionsim.sweeps

    assert frictionsim.sweeps.axial_mean_friction is axial.axial_mean_friction
    assert frictionsim.sweeps.kinematic_mean_friction is axial.kinematic_mean_friction
    assert axial.axial_mean_friction.__module__ == "frictionsim.axial"
    assert axial.identify_axial_rig is frictionsim.fit.identify_axial_rig is frictionsim.fit.rig.identify_axial_rig
    assert fs.axial is axial
