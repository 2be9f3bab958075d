"""Experimental data of paper 000 (axial vibrating-sliding friction between shale and 45 steel), and the values
paper 001 reports at its Fig. 7 operating point (:data:`PAPER001_FIG7`).

Tables 3, 4 and 5 and the sliding friction coefficients of section 2.4.1, transcribed exactly as printed into
CSV files next to this module (each file's header comments quote the printed column headers). The functions
return pandas DataFrames holding the printed columns, named with their printed unit (``u_mm``, ``f_Hz``,
``v_d_mm_per_min``, ``F_N_N`` ...), plus derived columns in SI units, which each docstring lists. Lubricants are
named ``"dry"``, ``"water"``, ``"wbm"``, ``"obm"``, ``"sbm"`` in column ``lubricant`` (the spelling of the C++
``lubricant_name``); ``lubricant_printed`` keeps the printed spelling.

Pure Python: nothing here needs the compiled extension (pandas loads when a table is read).
"""

from __future__ import annotations

import io
import math
from importlib import resources
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["LUBRICANTS", "PAPER001_FIG7", "sliding_friction_coefficients", "table3", "table4", "table5"]

#: The five lubricating conditions, in the order of Tables 3 and 5 (and of the C++ ``Lubricant`` enum).
LUBRICANTS = ("dry", "water", "wbm", "obm", "sbm")

#: Paper 001, Fig. 7 (measured / simulated): stick-slip frequency [Hz] and peak disc speed [rad/s] at the operating
#: point w_ref = 5.76 rad/s, N2 = 35 N (:data:`frictionsim.torsional.FIG7`; the plots' reference lines).
PAPER001_FIG7 = {"reference_speed": 5.76, "normal_force": 35.0, "frequency_measured": 0.83,
                 "frequency_simulated": 0.84, "peak_measured": 13.55, "peak_simulated": 14.0}


def _read(name: str) -> pd.DataFrame:
    # importlib.resources so the CSVs are found inside an installed wheel (or zip), not only in a source tree.
    import pandas as pd

    text = resources.files(__name__).joinpath(name).read_text(encoding="utf-8")
    frame = pd.read_csv(io.StringIO(text), comment="#")
    frame.insert(frame.columns.get_loc("lubricant_printed"), "lubricant", frame["lubricant_printed"].str.lower())
    return frame


def _mm_per_min_to_m_per_s(value):
    return value / 60_000.0


def table3() -> pd.DataFrame:
    """Table 3, the factor levels of the orthogonal experiment (levels 1-5 of each factor, not runs).

    Printed columns: ``level`` (printed "(1)".."(5)"), ``lubricant_printed``, ``u_mm`` (vibration amplitude u,
    mm), ``f_Hz`` (vibration frequency f, Hz), ``v_d_mm_per_min`` (sliding velocity v_d, mm/min), ``F_N_N``
    (normal force F_N, N).

    Derived: ``lubricant`` (normalised name), ``amplitude_m`` (u, m), ``frequency_hz`` (f, Hz),
    ``sliding_velocity_m_per_s`` (v_d, m/s), ``normal_force_n`` (F_N, N).
    """
    frame = _read("table3.csv")
    frame["amplitude_m"] = frame["u_mm"] / 1000.0
    frame["frequency_hz"] = frame["f_Hz"].astype(float)
    frame["sliding_velocity_m_per_s"] = _mm_per_min_to_m_per_s(frame["v_d_mm_per_min"])
    frame["normal_force_n"] = frame["F_N_N"].astype(float)
    return frame


def table4() -> pd.DataFrame:
    """Table 4, the 25 runs VS1-VS25 of the orthogonal experiment (an L25 array over Table 3's levels).

    Printed columns: ``number`` ("VS1".."VS25"), ``lubricant_printed`` (VS10 prints "water" in lower case),
    ``u_mm`` (u, mm), ``f_Hz`` (f, Hz), ``v_d_mm_per_min`` (v_d, mm/min), ``F_N_N`` (F_N, N), ``null`` (the
    array's blank column, printed "Null"), ``F_sf_N`` (F_sf, sliding friction force without vibration, N; the
    printed header has no unit), ``F_df_N`` (F_df, mean friction force over a vibration cycle, N), ``mu_df``
    (mu_df, printed "u_df", the dynamic friction coefficient F_df/F_N as printed to three decimals).

    Derived (SI):

    - ``amplitude_m`` = u [m]; ``frequency_hz`` = f [Hz]; ``sliding_velocity_m_per_s`` = v_d [m/s];
      ``normal_force_n`` = F_N [N].
    - ``velocity_amplitude_m_per_s`` = v_a = 2 pi f u [m/s] (eq 16); ``velocity_ratio`` = v_a / v_d [-], the
      abscissa of Figure 11 and Table 5 (about 160 for VS11 to 2564 for VS20).
    - ``mu_df_from_forces`` = F_df / F_N [-] (agrees with the printed ``mu_df`` to its three decimals in every
      run); ``mu_sf_from_forces`` = F_sf / F_N [-], the sliding friction coefficient without vibration behind
      F_sf (the same within 1e-4 in all five runs of a lubricant: dry 0.4097, water 0.4053, WBM 0.3600,
      OBM 0.2700, SBM 0.3237).

    Kept as printed although not a strict L25 orthogonal array: the lubricant, u, f, v_d and Null columns are
    pairwise orthogonal (every pair of levels once), but in the water runs VS6-VS10 F_N repeats the Null
    column's levels (150, 30, 60, 90, 120 N) where the array would give 120, 150, 30, 60, 90 N, so F_N meets
    each level of u, f, v_d and Null in only 20 of 25 combinations. The printed F_sf and F_df of those runs
    are consistent with the printed F_N (F_sf/F_N = 0.4053 in all five, mu_df = F_df/F_N), so the runs were
    evidently made at these loads; Table 5 does not involve F_N beyond mu_df.
    """
    frame = _read("table4.csv")
    frame["amplitude_m"] = frame["u_mm"] / 1000.0
    frame["frequency_hz"] = frame["f_Hz"].astype(float)
    frame["sliding_velocity_m_per_s"] = _mm_per_min_to_m_per_s(frame["v_d_mm_per_min"])
    frame["normal_force_n"] = frame["F_N_N"].astype(float)
    frame["velocity_amplitude_m_per_s"] = 2.0 * math.pi * frame["frequency_hz"] * frame["amplitude_m"]
    frame["velocity_ratio"] = frame["velocity_amplitude_m_per_s"] / frame["sliding_velocity_m_per_s"]
    frame["mu_df_from_forces"] = frame["F_df_N"] / frame["F_N_N"]
    frame["mu_sf_from_forces"] = frame["F_sf_N"] / frame["F_N_N"]
    return frame


def table5() -> pd.DataFrame:
    """Table 5, the power-law dynamic friction coefficient fitted per lubricant, as printed.

    Columns: ``lubricant``, ``lubricant_printed``, ``slope`` and ``intercept`` of the printed fitting line
    y = slope x + intercept, ``r_squared`` (its printed R^2), ``eta_prime`` and ``exponent`` of
    mu_df = eta' (v_a/v_d)^c (eq 17). All columns are printed; none is derived.

    The line is y = log10(mu_df) against x = log10(v_a/v_d) over Table 4's runs: slope = c and
    10**intercept = eta' (see :mod:`frictionsim.fit.power_law`, which refits it). The printed slopes and
    intercepts are reproduced from Table 4 to every printed digit. Two printed numbers are not:

    - SBM's eta' = 0.1231: 10**-0.91003 = 0.123018 rounds to 0.1230 (so does 10**intercept of the refit), an
      apparent slip of one unit in the last digit (0.07 % in mu_df). Kept as printed, as the C++
      ``PowerLawCoefficient::from_table5`` also uses it. The other four eta' equal 10**intercept rounded.
    - Every R^2: the fits' R^2 are 0.79, 0.72, 0.92, 0.86, 0.91, the printed ones 0.04-0.09 lower; see
      ``frictionsim.fit.power_law``.
    """
    return _read("table5.csv")


def sliding_friction_coefficients() -> pd.DataFrame:
    """Sliding friction coefficients without vibration, section 2.4.1 (Figure 3), one row per lubricant.

    Printed (text of section 2.4.1): ``mu_sf`` (WBM 0.36, SBM 0.32, OBM 0.27) and ``reduction_vs_dry_percent``
    (12.2, 21.9, 34.1), the decrease relative to dry friction. The text prints no value for dry or water: NaN.

    Derived: ``mu_sf_dry_implied`` = mu_sf / (1 - reduction/100), the dry coefficient each printed pair implies
    (0.4100, 0.4097, 0.4097 for WBM, OBM, SBM: all three printed pairs fit one dry coefficient between 0.4098
    and 0.4100, the text's "dry" of about 0.41); ``mu_sf_table4`` = mean F_sf/F_N over the
    lubricant's five runs of Table 4 (dry 0.4097, water 0.4053, WBM 0.3600, OBM 0.2700, SBM 0.3237), the only
    source of a water value. (Against Table 4's dry 0.4097, WBM's 0.36 is a 12.1 % reduction, not the printed
    12.2 %; OBM's and SBM's printed reductions agree.)
    """
    frame = _read("sliding_friction.csv")
    frame["mu_sf_dry_implied"] = frame["mu_sf"] / (1.0 - frame["reduction_vs_dry_percent"] / 100.0)
    runs = table4().groupby("lubricant")["mu_sf_from_forces"].mean()
    frame["mu_sf_table4"] = frame["lubricant"].map(runs)
    return frame
