// The axial vibrating-sliding rig of paper 000 (eqs 5-9) for Python: any friction law, the paper's Fig. 7(a)
// defaults, pickling for process pools, and simulate(); what all table-described rigs share is bind_rig's.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "rig_binding.hpp"

namespace frictionsim::python {

namespace {

using AxialVibrationRig = BoundRig<AxialRig, PythonLaws, AxialRigParams>;

/// gravity and initial_position: a switch and an optional value, outside the table of numbers.
constexpr std::array<ExtraKeyword<AxialRigParams>, 2> extra_keywords{{
    {"gravity", "bool = False",
     [](AxialRigParams& p, py::handle v) {
         if (!py::isinstance<py::bool_>(v) && std::string(py::str(py::type::of(v).attr("__name__"))) != "bool_")
             throw py::type_error("AxialVibrationRig: gravity must be True or False (got " +
                                  std::string(py::str(py::type::of(v).attr("__name__"))) + ")");
         p.gravity = py::bool_(py::reinterpret_borrow<py::object>(v));
     }},
    {"initial_position", "float | None = None",
     [](AxialRigParams& p, py::handle v) {
         if (v.is_none()) return;
         if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v) || !py::hasattr(v, "__float__"))
             throw py::type_error("AxialVibrationRig: initial_position must be a number or None (got " +
                                  std::string(py::str(py::type::of(v).attr("__name__"))) + ")");
         p.initial_position = v.attr("__float__")().cast<double>();
     }},
}};

py::dict extras_of(const AxialVibrationRig& r) {
    return py::dict(py::arg("gravity") = r.params.gravity, py::arg("initial_position") = r.params.initial_position);
}

}  // namespace

template <>
py::object register_rig<law_rig<AxialRig, AxialRigParams>>(py::module_& m) {
    const std::string description = R"doc(
The axial vibrating-sliding rig of paper 000 (eqs 5-9): a specimen of mass m pulled through a drive spring
k_d whose end moves at v_d, on a surface vibrating as u = u0 sin(2 pi f t), with friction under normal force F_N:

    m x'' = F_d - F_F - F_g,   F_d = k_d (v_d t - x),   v_r = x' - u0 w cos(w t).

Defaults are the paper's Fig. 7(a) dry case (u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, F_N = 90 N; m = 0.2 kg,
k_d = 2e4 N/m chosen, the paper gives no drive stiffness). SI units.

States: position x [m], velocity x' [m/s], the law's states, friction_impulse [N s], friction_work [J],
drive_work [J] (drive work = energy change + friction work).

Parameters
----------
friction : a friction law (any class of fs.FRICTION_LAWS, or fs.CallableLaw)
gravity : bool = False
    Vertical rig: F_g = m g opposes the sliding.
initial_position : float, optional
    x(0) [m]; default 0, or -m g / k_d with gravity (the spring carries the weight).

Keywords
--------
)doc";
    auto cls = bind_rig<AxialVibrationRig>(m, "AxialVibrationRig", description, AxialRigParams::fields(),
                                           friction_law_to_python, extras_of);
    def_table_init(cls, "AxialVibrationRig", AxialRigParams::fields(), extra_keywords,
                   [](py::handle friction, const AxialRigParams& p) {
                       return AxialVibrationRig(friction_law_from_python(friction, "friction"), p);
                   });
    cls.def_property_readonly("gravity", [](const AxialVibrationRig& r) { return r.params.gravity; })
        .def_property_readonly("initial_position", [](const AxialVibrationRig& r) { return r.params.initial_position; })
        .def_property_readonly("period", [](const AxialVibrationRig& r) { return 1.0 / r.params.frequency; },
                               "Vibration period 1/f [s].")
        .def_property_readonly("vibration_velocity_amplitude",
                               [](const AxialVibrationRig& r) { return r.visit([](const auto& s) { return s.vibration_velocity_amplitude(); }); },
                               "v_a = 2 pi f u0 [m/s] (eq 16).")
        .def("drive_force", py::vectorize([](AxialVibrationRig& r, double t, double x) {
                 return r.params.drive_stiffness * (r.params.sliding_velocity * t - x);
             }),
             py::arg("t"), py::arg("position"), "F_d = k_d (v_d t - x) [N] (eq 7).")
        .def("surface_velocity", py::vectorize([](AxialVibrationRig& r, double t) {
                 return r.visit([&](const auto& s) { return s.surface_velocity(t); });
             }),
             py::arg("t"), "Velocity of the vibrating surface u0 w cos(w t) [m/s].");
    return std::move(cls);
}

}  // namespace frictionsim::python
