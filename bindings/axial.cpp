// The axial vibrating-sliding rig of paper 000 (eqs 5-9) for Python: any friction law, the paper's Fig. 7(a)
// defaults, pickling for process pools, and simulate().
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "simulation.hpp"
#include "table_binding.hpp"

namespace frictionsim::python {

namespace {

template <class Law>
using Axial = AxialRig<Law>;

struct AxialVibrationRig {
    FrictionLaw friction;
    AxialRigParams params;
    RigVariant<Axial> rig;

    AxialVibrationRig(FrictionLaw law, const AxialRigParams& p)
        : friction(law), params(p),
          rig(std::visit([&](auto l) -> RigVariant<Axial> { return AxialRig<decltype(l)>(p, std::move(l)); }, law)) {}

    template <class F>
    decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), rig); }
};

AxialVibrationRig make_rig(py::handle friction, double mass, double drive_stiffness, double sliding_velocity,
                           double amplitude, double frequency, double normal_force, bool gravity,
                           double gravitational_acceleration, std::optional<double> initial_position,
                           double initial_velocity) {
    AxialRigParams p;
    p.mass = mass;
    p.drive_stiffness = drive_stiffness;
    p.sliding_velocity = sliding_velocity;
    p.amplitude = amplitude;
    p.frequency = frequency;
    p.normal_force = normal_force;
    p.gravity = gravity;
    p.gravitational_acceleration = gravitational_acceleration;
    p.initial_position = initial_position;
    p.initial_velocity = initial_velocity;
    return AxialVibrationRig(friction_law_from_python(friction, "friction"), p);
}

}  // namespace

void register_axial(py::module_& m) {
    const AxialRigParams d;
    static const std::string doc = R"doc(
The axial vibrating-sliding rig of paper 000 (eqs 5-9): a specimen of mass m pulled through a drive spring
k_d whose end moves at v_d, on a surface vibrating as u = u0 sin(2 pi f t), with friction under normal force F_N:

    m x'' = F_d - F_F - F_g,   F_d = k_d (v_d t - x),   v_r = x' - u0 w cos(w t).

Defaults are the paper's Fig. 7(a) dry case (u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, F_N = 90 N; m = 0.2 kg,
k_d = 2e4 N/m chosen, the paper gives no drive stiffness). SI units.

States: position x [m], velocity x' [m/s], the law's state (dahl_deflection / bristle_deflection [m]),
friction_impulse [N s], friction_work [J], drive_work [J] (drive work = energy change + friction work).

Parameters
----------
friction : a friction law (any class of fs.FRICTION_LAWS)
gravity : bool = False
    Vertical rig: F_g = m g opposes the sliding.
initial_position : float, optional
    x(0) [m]; default 0, or -m g / k_d with gravity (the spring carries the weight).
)doc" + keywords_doc(AxialRigParams::fields());
    py::class_<AxialVibrationRig> cls(m, "AxialVibrationRig", doc.c_str());
    cls.def(py::init(&make_rig), py::arg("friction"), py::kw_only(), py::arg("mass") = d.mass,
             py::arg("drive_stiffness") = d.drive_stiffness, py::arg("sliding_velocity") = d.sliding_velocity,
             py::arg("amplitude") = d.amplitude, py::arg("frequency") = d.frequency,
             py::arg("normal_force") = d.normal_force, py::arg("gravity") = d.gravity,
             py::arg("gravitational_acceleration") = d.gravitational_acceleration,
             py::arg("initial_position") = py::none(), py::arg("initial_velocity") = d.initial_velocity)
        .def_property_readonly("friction", [](const AxialVibrationRig& r) { return friction_law_to_python(r.friction); })
        .def_property_readonly("gravity", [](const AxialVibrationRig& r) { return r.params.gravity; })
        .def_property_readonly("initial_position", [](const AxialVibrationRig& r) { return r.params.initial_position; })
        .def_property_readonly("period", [](const AxialVibrationRig& r) { return 1.0 / r.params.frequency; },
                               "Vibration period 1/f [s].")
        .def_property_readonly("vibration_velocity_amplitude",
                               [](const AxialVibrationRig& r) { return r.visit([](const auto& s) { return s.vibration_velocity_amplitude(); }); },
                               "v_a = 2 pi f u0 [m/s] (eq 16).")
        .def_property_readonly("state_names", [](const AxialVibrationRig& r) {
            return r.visit([](const auto& s) {
                const auto names = s.state_names();
                return std::vector<std::string>(names.begin(), names.end());
            });
        })
        .def("drive_force", py::vectorize([](AxialVibrationRig& r, double t, double x) {
                 return r.params.drive_stiffness * (r.params.sliding_velocity * t - x);
             }),
             py::arg("t"), py::arg("position"), "F_d = k_d (v_d t - x) [N] (eq 7).")
        .def("surface_velocity", py::vectorize([](AxialVibrationRig& r, double t) {
                 return r.visit([&](const auto& s) { return s.surface_velocity(t); });
             }),
             py::arg("t"), "Velocity of the vibrating surface u0 w cos(w t) [m/s].")
        .def("_simulate", [](const AxialVibrationRig& r, double t_end, const SolverOptions& options, double t_start) {
            return simulate_variant(r.rig, t_end, options, t_start);
        })
        .def("__reduce__", [](py::handle self) {
            const auto& r = self.cast<const AxialVibrationRig&>();
            py::dict kwargs = field_keywords(r.params, AxialRigParams::fields());
            kwargs["gravity"] = r.params.gravity;
            kwargs["initial_position"] = r.params.initial_position;
            return reduce_by_construction(self, py::make_tuple(friction_law_to_python(r.friction)), kwargs);
        })
        .def("__repr__", [](const AxialVibrationRig& r) {
            return "AxialVibrationRig(friction=" + std::string(py::repr(friction_law_to_python(r.friction))) +
                   changed_fields_repr(r.params, AxialRigParams::fields()) + (r.params.gravity ? ", gravity=True" : "") +
                   (r.params.initial_position ? ", initial_position=" + format_double(*r.params.initial_position) : "") +
                   ")";
        });
    def_field_properties(cls, AxialRigParams::fields(), [](const AxialVibrationRig& r) -> const AxialRigParams& { return r.params; });
}

}  // namespace frictionsim::python
