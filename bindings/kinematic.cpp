// The kinematic rig for Python: a friction law driven by a prescribed relative velocity v_r(t) and normal force
// N(t), each a constant, sampled data (t, y), the paper's harmonic sliding velocity, or a Python callable.
// This is what identification from measured signals runs (frictionsim.fit).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rig_binding.hpp"

namespace frictionsim::python {

//------------------------------------------------------------------------------------------------ Signal
Signal Signal::constant(double value, const char* name) {
    Signal s;
    s.kind_ = Kind::constant;
    s.name_ = name;
    s.value_ = detail::require_finite("KinematicRig", name, value);
    return s;
}

Signal Signal::sampled(std::vector<double> t, std::vector<double> y, const char* name) {
    Signal s;
    s.kind_ = Kind::sampled;
    s.name_ = name;
    s.samples_ = std::make_shared<const SampledSignal>(t, y, name);
    s.t_ = std::move(t);
    s.y_ = std::move(y);
    return s;
}

Signal Signal::harmonic(double sliding_velocity, double velocity_amplitude, double angular_frequency) {
    Signal s;
    s.kind_ = Kind::harmonic;
    s.name_ = "relative_velocity";
    s.harmonic_.emplace(sliding_velocity, velocity_amplitude, angular_frequency);
    return s;
}

Signal Signal::callable(py::object function, const char* name) {
    Signal s;
    s.kind_ = Kind::callable;
    s.name_ = name;
    s.function_ = std::make_shared<py::object>(std::move(function));
    return s;
}

Signal Signal::from_python(py::handle value, const char* name) {
    if (PyCallable_Check(value.ptr())) return callable(py::reinterpret_borrow<py::object>(value), name);
    // Any real number, NumPy scalars included (np.float32, np.int64 have __float__ / __index__).
    if (!py::isinstance<py::str>(value) && !py::isinstance<py::sequence>(value) && !py::isinstance<py::array>(value) &&
        (PyFloat_Check(value.ptr()) || PyLong_Check(value.ptr()) || PyObject_HasAttrString(value.ptr(), "__float__")))
        return constant(py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>(), name);
    if ((py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) && py::len(value) == 2) {
        using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
        const auto t = Array::ensure(value[py::int_(0)]);
        const auto y = Array::ensure(value[py::int_(1)]);
        if (!t || !y || t.ndim() != 1 || y.ndim() != 1)
            throw py::type_error(std::string(name) + ": a (t, values) pair must hold two 1-D arrays of numbers");
        return sampled(std::vector<double>(t.data(), t.data() + t.size()),
                       std::vector<double>(y.data(), y.data() + y.size()), name);
    }
    throw py::type_error(std::string(name) + " must be a number, a callable of t, or a (t, values) pair of arrays; got " +
                         std::string(py::str(py::type::of(value).attr("__name__"))));
}

double Signal::operator()(double t) const {
    switch (kind_) {
        case Kind::constant: return value_;
        case Kind::sampled: return (*samples_)(t);
        case Kind::harmonic: return (*harmonic_)(t);
        case Kind::callable: break;
    }
    double v;
    {
        py::gil_scoped_acquire gil;
        py::object out;
        try {
            out = (*function_)(t);
        } catch (py::error_already_set& e) {
            // KeyboardInterrupt, SystemExit: the caller's, not the model's. Put it back as the pending error and
            // stop the run; simulate() raises it unchanged.
            if (!e.matches(PyExc_Exception)) {
                e.restore();
                throw Interrupted(name_ + "(t) raised a BaseException", t);
            }
            throw;
        }
        // a real number: float, int, NumPy scalar (not bool, str, None, a sequence)
        if (PyBool_Check(out.ptr()) || !(PyFloat_Check(out.ptr()) || PyLong_Check(out.ptr()) ||
                                         (PyNumber_Check(out.ptr()) && !py::isinstance<py::sequence>(out) &&
                                          py::hasattr(out, "__float__")))) {
            std::ostringstream msg;
            msg.precision(17);
            msg << "KinematicRig: " << name_ << "(t) must return a real number (got "
                << std::string(py::str(py::type::of(out).attr("__name__"))) << " at t = " << t << " s)";
            throw InvalidParameter(name_, msg.str());
        }
        v = py::float_(out).cast<double>();
    }
    if (!std::isfinite(v)) {
        std::ostringstream msg;
        msg.precision(17);
        msg << "KinematicRig: " << name_ << "(t) must be finite (got " << v << " at t = " << t << " s)";
        throw InvalidParameter(name_, msg.str());
    }
    return v;
}

double Signal::derivative(double t) const {
    switch (kind_) {
        case Kind::constant: return 0.0;
        case Kind::sampled: return samples_->derivative(t);
        case Kind::harmonic: return harmonic_->derivative(t);
        case Kind::callable: break;
    }
    const double h = 6e-6 * std::max(1.0, std::abs(t));  // ~ cbrt(machine epsilon): the central difference's best
    return ((*this)(t + h) - (*this)(t - h)) / (2.0 * h);
}

py::object Signal::to_python() const {
    switch (kind_) {
        case Kind::constant: return py::float_(value_);
        case Kind::sampled:
            return py::make_tuple(py::array_t<double>(static_cast<py::ssize_t>(t_.size()), t_.data()),
                                  py::array_t<double>(static_cast<py::ssize_t>(y_.size()), y_.data()));
        case Kind::harmonic:
            return py::make_tuple(harmonic_->sliding_velocity, harmonic_->velocity_amplitude,
                                  harmonic_->angular_frequency);
        case Kind::callable: break;
    }
    return *function_;
}

//------------------------------------------------------------------------------------------------ rig
namespace {

/// A signal in a repr: the number of a constant; samples and callables, which no literal rebuilds, described.
std::string describe_signal(const Signal& s) {
    switch (s.kind()) {
        case Signal::Kind::constant: return format_double(s.to_python().cast<double>());
        case Signal::Kind::sampled: {
            const py::tuple ty = s.to_python();
            const auto t = ty[0].cast<py::array_t<double>>();
            const py::ssize_t n = t.size();
            return "<" + std::to_string(n) + " samples, t = " + format_double(t.at(0)) + " to " +
                   format_double(t.at(n - 1)) + " s>";
        }
        case Signal::Kind::harmonic: break;
        case Signal::Kind::callable: return "<" + std::string(py::repr(s.to_python())) + ">";
    }
    return "<harmonic>";
}

template <class Law>
using Kinematic = KinematicRig<Law, Signal, Signal>;

template <std::size_t Z>
std::array<double, Z> law_state_from_python(const std::optional<std::vector<double>>& z0, const char* law) {
    std::array<double, Z> out{};
    if (!z0) return out;
    if (z0->size() != Z)
        throw InvalidParameter("initial_state", std::string("KinematicRig: initial_state must hold ") +
                                                    std::to_string(Z) + " value(s) for " + law + " (got " +
                                                    std::to_string(z0->size()) + ")");
    for (std::size_t i = 0; i < Z; ++i) out[i] = (*z0)[i];
    return out;
}

struct KinematicRigPy {
    LawOrHysteretic friction;
    Signal relative_velocity, normal_force;
    std::optional<std::vector<double>> initial_state;
    std::optional<double> frequency;  // of a harmonic relative velocity, Hz
    RigVariant<Kinematic, LawsAndHysteretic> rig;

    KinematicRigPy(LawOrHysteretic law, Signal v, Signal n, std::optional<std::vector<double>> z0,
                   std::optional<double> frequency_)
        : friction(law), relative_velocity(v), normal_force(n), initial_state(std::move(z0)), frequency(frequency_),
          rig(std::visit(
              [&](auto l) -> RigVariant<Kinematic, LawsAndHysteretic> {
                  using Law = decltype(l);
                  auto z = law_state_from_python<Law::state_count>(initial_state, Law::name);
                  return Kinematic<Law>(std::move(l), relative_velocity, normal_force, z);
              },
              law)) {
        if (n.kind() == Signal::Kind::constant) detail::require_positive("KinematicRig", "normal_force", n(0.0));
        if (n.kind() == Signal::Kind::sampled) {  // every sample: a spike between two steps would go unseen
            const auto values = normal_force.to_python().cast<py::tuple>()[1].cast<std::vector<double>>();
            for (double v : values) detail::require_positive("KinematicRig", "normal_force", v);
        }
    }

    /// Sampled signals must cover the run: say so up front rather than stop at the edge of the data.
    void require_covered(double t_start, double t_end) const {
        for (const Signal* s : {&relative_velocity, &normal_force}) {
            if (s->kind() != Signal::Kind::sampled) continue;
            const py::tuple data = s->to_python();  // GIL held: called before the release
            const auto t = data[0].cast<py::array_t<double>>();
            const double first = t.at(0), last = t.at(t.size() - 1);
            const char* name = s == &relative_velocity ? "relative_velocity" : "normal_force";
            if (t_start < first)
                detail::reject("simulate", "t_start", (std::string("within the samples of ") + name).c_str(), t_start);
            if (t_end > last)
                detail::reject("simulate", "t_end",
                               (std::string("<= the last sample time of ") + name + " (" +
                                std::string(py::str(py::float_(last))) + " s)").c_str(),
                               t_end);
        }
    }
};

KinematicRigPy make_rig(py::handle friction, py::handle relative_velocity, py::handle normal_force,
                        std::optional<std::vector<double>> initial_state) {
    return KinematicRigPy(law_or_hysteretic_from_python(friction, "friction"),
                          Signal::from_python(relative_velocity, "relative_velocity"),
                          Signal::from_python(normal_force, "normal_force"), std::move(initial_state), std::nullopt);
}

KinematicRigPy make_harmonic(py::handle friction, double v_d, double v_a, double frequency, py::handle normal_force,
                             std::optional<std::vector<double>> initial_state) {
    detail::require_positive("KinematicRig", "frequency", frequency);
    if (!std::isfinite(2.0 * pi * frequency))
        detail::reject("KinematicRig", "frequency", "small enough that 2 pi f is finite", frequency);
    return KinematicRigPy(law_or_hysteretic_from_python(friction, "friction"), Signal::harmonic(v_d, v_a, 2.0 * pi * frequency),
                          Signal::from_python(normal_force, "normal_force"), std::move(initial_state), frequency);
}

}  // namespace

template <>
py::object register_rig<signal_rig>(py::module_& m) {
    py::class_<KinematicRigPy> cls(m, "KinematicRig", R"doc(
A friction law driven by a prescribed relative velocity v_r(t) [m/s] and normal force N(t) [N]: no mass, so
set-valued laws (Coulomb, Stribeck) give their slip force on the branch sgn(v_r); reversals of v_r are located
as events. This is the model that identification from measured signals fits (frictionsim.fit).

States: the law's state (dahl_deflection / bristle_deflection [m]), friction_impulse int F dt [N s] and
friction_work int F v_r dt [J].

Parameters
----------
friction : a friction law (any class of fs.FRICTION_LAWS, a Stribeck law without Karnopp band, fs.CallableLaw) or
    fs.HystereticFriction (paper 001's eq 6: relative_velocity is then the disc speed w [rad/s], its derivative
    dw/dt picks the branch (a callable's by central difference), friction_force is the torque [N m]; modes 0
    stick band, +-1 accelerating, +-2 decelerating)
relative_velocity : float | callable t -> v_r | (t, v_r) pair of arrays (piecewise linear)
normal_force : float | callable t -> N | (t, N) pair of arrays, > 0 at every time
initial_state : sequence of float, optional
    The law's initial state (z0 [m] for Dahl, LuGre and ElastoPlastic); default zero.
)doc");
    def_outputs(cls, signal_rig::outputs());
    cls.def(py::init(&make_rig), py::arg("friction"), py::kw_only(), py::arg("relative_velocity"),
             py::arg("normal_force"), py::arg("initial_state") = py::none())
        .def_static("harmonic", &make_harmonic, py::arg("friction"), py::kw_only(), py::arg("sliding_velocity"),
                    py::arg("velocity_amplitude"), py::arg("frequency"), py::arg("normal_force"),
                    py::arg("initial_state") = py::none(),
                    "The paper's relative velocity v_r = v_d - v_a cos(2 pi f t) (eqs 8-9, 16), v_a [m/s], f [Hz].")
        .def_property_readonly("friction", [](const KinematicRigPy& r) { return law_or_hysteretic_to_python(r.friction); })
        .def_property_readonly("relative_velocity", [](const KinematicRigPy& r) { return r.relative_velocity.to_python(); })
        .def_property_readonly("normal_force", [](const KinematicRigPy& r) { return r.normal_force.to_python(); })
        .def_readonly("initial_state", &KinematicRigPy::initial_state)
        .def_readonly("frequency", &KinematicRigPy::frequency, "f [Hz] of a harmonic relative velocity, else None.")
        .def_property_readonly("period", [](const KinematicRigPy& r) -> std::optional<double> {
            if (!r.frequency) return std::nullopt;
            return 1.0 / *r.frequency;
        }, "Period 1/f [s] of a harmonic relative velocity, else None.")
        .def_property_readonly("state_names", [](const KinematicRigPy& r) {
            return std::visit([](const auto& s) {
                const auto names = s.state_names();
                return std::vector<std::string>(names.begin(), names.end());
            }, r.rig);
        })
        .def("_simulate", [](const KinematicRigPy& r, double t_end, const SolverOptions& options, double t_start) {
            r.require_covered(t_start, t_end);
            return simulate_variant(r.rig, t_end, options, t_start);
        })
        .def("__reduce__", [](py::handle self) {
            const auto& r = self.cast<const KinematicRigPy&>();
            py::dict kwargs(py::arg("normal_force") = r.normal_force.to_python(),
                            py::arg("initial_state") = r.initial_state);
            if (r.relative_velocity.kind() != Signal::Kind::harmonic) {
                kwargs["relative_velocity"] = r.relative_velocity.to_python();
                return reduce_by_construction(self, py::make_tuple(law_or_hysteretic_to_python(r.friction)), kwargs);
            }
            // f, not w = 2 pi f, so that the rebuilt rig is bit-identical
            const py::tuple h = r.relative_velocity.to_python();
            kwargs["sliding_velocity"] = h[0];
            kwargs["velocity_amplitude"] = h[1];
            kwargs["frequency"] = *r.frequency;
            return reduce_by_construction(self, py::make_tuple(law_or_hysteretic_to_python(r.friction)), kwargs, "harmonic");
        })
        .def("__repr__", [](const KinematicRigPy& r) {
            // Literal where a literal rebuilds the rig (constants, the harmonic velocity: eval(repr) is the same
            // rig to the bit); samples and callables are described.
            const bool harmonic = r.relative_velocity.kind() == Signal::Kind::harmonic;
            std::string out = harmonic ? "KinematicRig.harmonic(" : "KinematicRig(";
            out += std::string(py::repr(law_or_hysteretic_to_python(r.friction)));
            if (harmonic) {
                const py::tuple h = r.relative_velocity.to_python();
                out += ", sliding_velocity=" + format_double(h[0].cast<double>()) +
                       ", velocity_amplitude=" + format_double(h[1].cast<double>()) +
                       ", frequency=" + format_double(*r.frequency);
            } else {
                out += ", relative_velocity=" + describe_signal(r.relative_velocity);
            }
            out += ", normal_force=" + describe_signal(r.normal_force);
            if (r.initial_state) {
                out += ", initial_state=[";
                for (std::size_t i = 0; i < r.initial_state->size(); ++i)
                    out += (i ? ", " : "") + format_double((*r.initial_state)[i]);
                out += "]";
            }
            return out + ")";
        });
    return std::move(cls);
}

}  // namespace frictionsim::python
