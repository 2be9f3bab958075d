"""Smoke test of an installed frictionsim wheel, run by scripts/test in a fresh venv (no source tree, no extras).

    python wheel_smoke.py EXPECTED_VERSION

Checks that the wheel's own files import and run: the version it reports, both integrators on paper 000's
Fig. 7(a) rig (they agree on the mean friction force), the closed-form Coulomb reduction of eq 8, the packaged
data and scenarios, and that the optional extras stay optional (frictionsim.signal.emd names its extra).
"""

import importlib.metadata
import math
import sys
from importlib import resources

import frictionsim as fs
from frictionsim import _core

expected = sys.argv[1]
assert fs.__version__ == expected == importlib.metadata.version("frictionsim"), (fs.__version__, expected)
assert importlib.metadata.metadata("frictionsim")["License-Expression"] == "MIT"
assert _core.HAS_SUNDIALS, "the wheel was built without SUNDIALS"
assert "site-packages" in _core.__file__, f"imported {_core.__file__}, not the installed wheel"

rig = fs.AxialVibrationRig(friction=fs.Dahl(mu=0.41, tangential_stiffness=4e4))
window = [1.0 - 8 * rig.period, 1.0]  # the last 8 whole cycles, both ends output times: the mean friction force
means = {method: fs.simulate(rig, 1.0, method=method, rtol=1e-9, atol=1e-12, output_times=window)
         .mean_over_cycles(transient=0.0) for method in ("dormand_prince", "cvode_bdf")}
assert all(math.isfinite(m) and m > 0 for m in means.values()), means
assert math.isclose(means["dormand_prince"], means["cvode_bdf"], rel_tol=1e-5), means

ratio = 0.5  # eq 8: 1 - (2/pi) asin(v_d/v_a)
assert math.isclose(fs.axial.kinematic_coulomb_reduction(ratio), fs.axial.coulomb_reduction(ratio), abs_tol=1e-7)

package = resources.files("frictionsim")
for name in ("py.typed", "_core.pyi", "data/table4.csv", "scenarios/fig7_obm.toml"):
    assert package.joinpath(name).is_file(), name

try:
    import PyEMD  # noqa: F401  (an extra: absent from a plain install)
except ImportError:
    import numpy as np

    t = np.linspace(0.0, 1.0, 101)
    try:
        fs.signal.emd(t, np.sin(2 * np.pi * 5 * t))
    except ImportError as error:
        assert "frictionsim[signal]" in str(error), error
    else:
        raise AssertionError("emd ran without PyEMD")

print(f"frictionsim {fs.__version__} wheel: Dahl mean friction {means['dormand_prince']:.6f} N (Dormand-Prince) "
      f"= {means['cvode_bdf']:.6f} N (CVODE BDF); extras optional")
