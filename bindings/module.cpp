// frictionsim._core: the C++ engine for the frictionsim Python package. The Python modules in
// python/frictionsim/ re-export these classes and add what NumPy/SciPy do well (fitting, signals, plots).
#include "common.hpp"

PYBIND11_MODULE(_core, m) {
    using namespace frictionsim::python;
    m.doc() = "frictionsim C++ engine: friction laws, rigs and the hybrid (stick-slip) integrator.";
    register_errors(m);
    register_laws(m);
    register_results(m);
    register_axial(m);
    register_kinematic(m);
    register_contact(m);
    register_torsional(m);
}
