// Torque and drag along a well for Python (issue 14, items 1 and 2): fs.Survey (drillstring/survey.hpp: minimum
// curvature, its trajectory as NumPy arrays), fs.SoftString (drillstring/soft_string.hpp: soft-string torque and
// drag on a DrillString of fs.PipeSection, Johancsik's step or Aadnoy's curvature form by `method`) and
// fs.TorqueDragResult (per node and per element arrays).
// The operating conditions of SoftString.run are SoftStringParams' table: keywords, SoftString.parameters and the
// error names come from it. Axial vibration tools (issue 14, items 3-4): fs.HydraulicOscillator (its table) and
// SoftString.oscillators / sliding_weight_on_bit (drillstring/oscillator_drag.hpp: zone of influence, hook load and
// torque change, the weight on bit transferred while sliding, the placement objective). No physics here:
// conversions and names only.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <frictionsim/wells/oscillator_drag.hpp>
#include <frictionsim/wells/oscillator_response.hpp>
#include <frictionsim/wells/soft_string.hpp>

#include "simulation.hpp"
#include "table_binding.hpp"

namespace frictionsim::python {

namespace {

using namespace pybind11::literals;

constexpr auto condition_fields = SoftStringParams::fields();
constexpr auto tool_fields = HydraulicOscillator::fields();
constexpr auto drag_fields = OscillatorDragParams::fields();
/// More elements than any well needs (a 10 km string at 1 cm): a guard against a typo allocating gigabytes.
constexpr long max_elements = 1000000;
/// More tools than any string carries (one to three): a longer sequence, or an endless iterator, is refused.
constexpr std::size_t max_tools = 100;

constexpr Operation operations[] = {Operation::trip_in,           Operation::trip_out,
                                    Operation::reaming,           Operation::backreaming,
                                    Operation::rotating_off_bottom, Operation::sliding_drilling,
                                    Operation::rotary_drilling};

using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

py::array_t<double> to_array(const std::vector<double>& v) {
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::array_t<bool> to_flags(const std::vector<std::uint8_t>& v) {
    py::array_t<bool> out(static_cast<py::ssize_t>(v.size()));
    auto o = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < v.size(); ++i) o(static_cast<py::ssize_t>(i)) = v[i] != 0;
    return out;
}

/// `value` as an array of real numbers for `field`: complex numbers, text and booleans are refused by name, not
/// converted (forcecast would drop an imaginary part; strings reach numbers only through the units layer).
Values real_numbers(py::handle value, const char* owner, const char* field) {
    const py::module_ np = py::module_::import("numpy");
    const std::string where = std::string(owner) + ": " + field;
    py::object a;
    try {
        a = np.attr("asarray")(value);
    } catch (const py::error_already_set& e) {
        throw InvalidParameter(field, where + " must be an array of numbers (" + std::string(py::str(e.value())) + ")");
    }
    const std::string kind = py::str(a.attr("dtype").attr("kind"));
    if (kind == "O") {  // a list of objects: Python or NumPy real numbers only
        const py::object real = np.attr("floating"), integer = np.attr("integer");
        for (const py::handle x : a.attr("ravel")()) {
            const bool ok = !py::isinstance<py::bool_>(x) &&
                            (py::isinstance<py::float_>(x) || py::isinstance<py::int_>(x) ||
                             py::isinstance(x, real) || py::isinstance(x, integer));
            if (!ok) throw py::type_error(where + " must hold real numbers (got " + type_name(x) + ")");
        }
    } else if (kind != "f" && kind != "i" && kind != "u") {
        const char* what = kind == "c" ? "complex numbers" : kind == "b" ? "booleans" :
                           kind == "U" || kind == "S" ? "text" : "values of another kind";
        throw py::type_error(where + " must hold real numbers (got " + what + ", dtype " +
                             std::string(py::str(a.attr("dtype"))) + ")");
    }
    return np.attr("asarray")(a, "dtype"_a = "float64").cast<Values>();
}

/// A keyword given an array (np.array([1.0])) is refused by name: its __float__ raised numpy's own TypeError.
void refuse_arrays(const py::kwargs& kwargs, const char* owner) {
    for (const auto item : kwargs)
        if (py::isinstance<py::array>(item.second) && py::array::ensure(item.second).ndim() > 0)
            throw py::type_error(std::string(owner) + ": " + std::string(py::str(item.first)) +
                                 " must be a number, not an array of shape " +
                                 std::string(py::str(item.second.attr("shape"))));
}

/// Runs `f` with the GIL released and Ctrl-C polled between the dynamic run's steps (o.dynamic.interrupt):
/// KeyboardInterrupt as the signal handler raised it.
template <class F>
auto interruptible(OscillatorDragParams& o, F&& f) {
    o.dynamic.interrupt = &python_signal_raised;
    try {
        py::gil_scoped_release release;
        return f();
    } catch (const Interrupted&) {
        raise_pending_python_error();
    }
}

/// A one-dimensional array of numbers, or an InvalidParameter naming `field`.
std::vector<double> column(const Values& values, const char* owner, const char* field) {
    if (values.ndim() != 1)
        throw InvalidParameter(field, std::string(owner) + ": " + field + " must be one-dimensional (got " +
                                          std::to_string(values.ndim()) + " dimensions)");
    return std::vector<double>(values.data(), values.data() + values.shape(0));
}

/// The keywords of a result's constructor (what its __reduce__ gives): each one required, an unknown one refused.
class Keywords {
public:
    Keywords(const py::kwargs& kwargs, const char* owner) : kwargs_(kwargs), owner_(owner) {}
    py::handle operator[](const char* name) {
        if (!kwargs_.contains(name))
            throw py::type_error(owner_ + "() missing the keyword argument '" + name + "'");
        names_.insert(name);
        return kwargs_[name];
    }
    double number(const char* name) {
        const py::handle v = (*this)[name];
        if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v) || !py::hasattr(v, "__float__"))
            throw py::type_error(owner_ + ": " + name + " must be a number (got " + type_name(v) + ")");
        return v.attr("__float__")().cast<double>();
    }
    long count(const char* name) {
        const py::handle v = (*this)[name];
        if (py::isinstance<py::bool_>(v) || !py::hasattr(v, "__index__"))
            throw py::type_error(owner_ + ": " + name + " must be a whole number (got " + type_name(v) + ")");
        const long n = v.attr("__index__")().cast<long>();
        if (n < 0) throw InvalidParameter(name, owner_ + ": " + name + " must be >= 0 (got " + std::to_string(n) + ")");
        return n;
    }
    bool flag(const char* name) {
        const py::handle v = (*this)[name];
        if (!py::isinstance<py::bool_>(v))
            throw py::type_error(owner_ + ": " + name + " must be a bool (got " + type_name(v) + ")");
        return v.cast<bool>();
    }
    std::vector<double> values(const char* name) {
        return column(real_numbers((*this)[name], owner_.c_str(), name), owner_.c_str(), name);
    }
    std::vector<double> values(const char* name, std::size_t size) {
        std::vector<double> v = values(name);
        check_size(name, v.size(), size);
        return v;
    }
    std::vector<std::uint8_t> flags(const char* name, std::size_t size) {
        const auto a = (*this)[name].cast<py::array_t<bool, py::array::c_style | py::array::forcecast>>();
        check_size(name, static_cast<std::size_t>(a.size()), size);
        return std::vector<std::uint8_t>(a.data(), a.data() + a.size());
    }
    void check_size(const char* name, std::size_t got, std::size_t size) const {
        if (got != size)
            throw InvalidParameter(name, owner_ + ": " + name + " must hold " + std::to_string(size) +
                                             " values (got " + std::to_string(got) + ")");
    }
    /// After every keyword was read: any other is a TypeError.
    void done() const {
        for (const auto item : kwargs_)
            if (!names_.count(py::str(item.first)))
                throw py::type_error(owner_ + "() got an unexpected keyword argument '" +
                                     std::string(py::str(item.first)) + "'");
    }

private:
    const py::kwargs& kwargs_;
    std::string owner_;
    std::set<std::string> names_;
};

std::vector<SurveyStation> stations_from(const Values& md, const Values& inc, const Values& azi) {
    const std::vector<double> d = column(md, "Survey", "measured_depth"),
                              i = column(inc, "Survey", "inclination"), a = column(azi, "Survey", "azimuth");
    for (const auto& [values, field] : {std::pair{&i, "inclination"}, std::pair{&a, "azimuth"}})
        if (values->size() != d.size())
            throw InvalidParameter(field, std::string("Survey: ") + field + " must hold one value per station (" +
                                              std::to_string(d.size()) + " measured depths, got " +
                                              std::to_string(values->size()) + ")");
    std::vector<SurveyStation> out(d.size());
    for (std::size_t k = 0; k < d.size(); ++k) out[k] = {d[k], i[k], a[k]};
    return out;
}

std::vector<double> station_values(const Survey& s, double SurveyStation::*member) {
    std::vector<double> out;
    out.reserve(s.size());
    for (const SurveyStation& st : s.stations()) out.push_back(st.*member);
    return out;
}

/// Per station, the first 0 (no course ends there): dogleg [rad] or its severity [rad/m] of the course ending at i.
std::vector<double> per_course(const Survey& s, bool severity) {
    std::vector<double> out(s.size(), 0.0);
    for (std::size_t i = 1; i < s.size(); ++i) out[i] = severity ? s.dogleg_severity(i) : s.dogleg(i);
    return out;
}

std::vector<double> positions(const Survey& s, double (Survey::*coordinate)(std::size_t) const) {
    std::vector<double> out(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) out[i] = (s.*coordinate)(i);
    return out;
}

/// The constructor call that rebuilds the survey bit for bit (the stations in SI: m, rad).
std::string survey_repr(const Survey& s) {
    const auto list = [&](double SurveyStation::*member) {
        std::string out = "[";
        for (std::size_t i = 0; i < s.size(); ++i) out += (i ? ", " : "") + format_double(s.stations()[i].*member);
        return out + "]";
    };
    return "Survey(" + list(&SurveyStation::measured_depth) + ", " + list(&SurveyStation::inclination) + ", " +
           list(&SurveyStation::azimuth) + ")";
}

Operation operation_from(py::handle value) {
    if (py::isinstance<py::str>(value)) {
        const std::string name = value.cast<std::string>();
        for (Operation op : operations)
            if (name == operation_name(op)) return op;
    }
    std::string names;
    for (Operation op : operations) names += std::string(names.empty() ? "" : ", ") + "'" + operation_name(op) + "'";
    if (!py::isinstance<py::str>(value))
        throw py::type_error("SoftString.run: operation must be a str, one of " + names + " (got " +
                             type_name(value) + ")");
    throw InvalidParameter("operation", "SoftString.run: operation must be one of " + names + " (got " +
                                            std::string(py::repr(value)) + ")");
}

template <class P, std::size_t N>
bool names_field(const std::string& key, const std::array<Field<P>, N>& fields) {
    for (const Field<P>& f : fields)
        if (key == f.public_name()) return true;
    return false;
}

// ---- the dynamic vibration route (drillstring/oscillator_response.hpp): its keywords, kept apart
constexpr auto response_fields = OscillatorResponseParams::fields();

bool is_vibration_keyword(const std::string& key) {
    if (key == "vibration") return true;
    for (const Field<OscillatorResponseParams>& f : response_fields)
        if (key == f.public_name()) return true;
    return false;
}

/// `vibration` ('wave' or 'dynamic') and the dynamic run's settings (OscillatorResponseParams' table; None leaves
/// `transient` unset: the default) into o; returns how many keywords it used.
std::size_t read_vibration_keywords(const py::kwargs& kwargs, const char* owner, OscillatorDragParams& o) {
    std::size_t used = 0;
    if (kwargs.contains("vibration")) {
        const py::handle v = kwargs["vibration"];
        const std::string name = py::isinstance<py::str>(v) ? v.cast<std::string>() : "";
        if (name == "wave") o.source = VibrationSource::wave;
        else if (name == "dynamic") o.source = VibrationSource::dynamic;
        else throw InvalidParameter("vibration", std::string(owner) + ": vibration must be 'wave' (the travelling-"
                                                                      "wave estimate) or 'dynamic' (the axial string "
                                                                      "model run to a steady state) (got " +
                                                                      std::string(py::repr(v)) + ")");
        ++used;
    }
    for (const Field<OscillatorResponseParams>& f : response_fields) {
        if (!kwargs.contains(f.public_name())) continue;
        const py::handle value = kwargs[f.public_name()];
        ++used;
        if (value.is_none() && f.rule.unset_allowed) {
            o.dynamic.*(f.member) = std::numeric_limits<double>::quiet_NaN();
            continue;
        }
        if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) || !py::hasattr(value, "__float__"))
            throw py::type_error(std::string(owner) + ": " + f.public_name() + " must be a number (got " +
                                 type_name(value) + ")");
        o.dynamic.*(f.member) = value.attr("__float__")().cast<double>();
    }
    validate_fields(owner, o.dynamic, response_fields);
    return used;
}

std::vector<double> magnitudes(const std::vector<std::complex<double>>& z) {
    std::vector<double> out(z.size());
    for (std::size_t i = 0; i < z.size(); ++i) out[i] = std::abs(z[i]);
    return out;
}

std::vector<double> phases(const std::vector<std::complex<double>>& z) {
    std::vector<double> out(z.size());
    for (std::size_t i = 0; i < z.size(); ++i) out[i] = std::arg(z[i]);
    return out;
}

// ---- the results' fields as keywords and back (pickling: __reduce__ and the constructors)
py::array to_complex_array(const std::vector<std::complex<double>>& v) {
    return py::array_t<std::complex<double>>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::dict torque_drag_keywords(const TorqueDragResult& r) {
    py::dict d;
    d["operation"] = operation_name(r.operation);
    d["measured_depth"] = to_array(r.measured_depth);
    d["tension"] = to_array(r.tension);
    d["torque"] = to_array(r.torque);
    d["side_force"] = to_array(r.side_force);
    d["side_force_per_length"] = to_array(r.side_force_per_length);
    d["sinusoidal_buckling_load"] = to_array(r.sinusoidal_buckling_load);
    d["helical_buckling_load"] = to_array(r.helical_buckling_load);
    d["sinusoidally_buckled"] = to_flags(r.sinusoidally_buckled);
    d["helically_buckled"] = to_flags(r.helically_buckled);
    return d;
}

TorqueDragResult torque_drag_result_from(const py::kwargs& kwargs) {
    Keywords k(kwargs, "TorqueDragResult");
    TorqueDragResult r;
    r.operation = operation_from(k["operation"]);
    r.measured_depth = k.values("measured_depth");
    const std::size_t nodes = r.measured_depth.size();
    if (nodes < 2) k.check_size("measured_depth", nodes, 2);
    r.tension = k.values("tension", nodes);
    r.torque = k.values("torque", nodes);
    r.side_force = k.values("side_force", nodes - 1);
    r.side_force_per_length = k.values("side_force_per_length", nodes - 1);
    r.sinusoidal_buckling_load = k.values("sinusoidal_buckling_load", nodes);
    r.helical_buckling_load = k.values("helical_buckling_load", nodes);
    r.sinusoidally_buckled = k.flags("sinusoidally_buckled", nodes);
    r.helically_buckled = k.flags("helically_buckled", nodes);
    k.done();
    return r;
}

py::dict response_keywords(const OscillatorResponse& r) {
    py::dict d;
    d["measured_depth"] = to_array(r.measured_depth);
    d["phasor"] = to_complex_array(r.phasor);
    d["reversed"] = to_array(r.reversed);
    d["friction_factor"] = to_array(r.friction_factor);
    d["amplitude"] = to_array(r.amplitude);
    d["excitation_node"] = r.excitation_node;
    d["transient"] = r.transient;
    d["measured_time"] = r.measured_time;
    d["reach"] = r.reach;
    d["settled"] = r.settled;
    d["steps"] = r.stats.steps;
    d["events"] = r.stats.events;
    return d;
}

OscillatorResponse oscillator_response_from(const py::kwargs& kwargs) {
    Keywords k(kwargs, "OscillatorResponse");
    OscillatorResponse r;
    r.measured_depth = k.values("measured_depth");
    const std::size_t nodes = r.measured_depth.size();
    if (nodes < 2) k.check_size("measured_depth", nodes, 2);
    const auto phasor = k["phasor"].cast<py::array_t<std::complex<double>, py::array::c_style | py::array::forcecast>>();
    k.check_size("phasor", static_cast<std::size_t>(phasor.size()), nodes);
    r.phasor.assign(phasor.data(), phasor.data() + phasor.size());
    r.reversed = k.values("reversed", nodes);
    r.friction_factor = k.values("friction_factor", nodes);
    r.amplitude = k.values("amplitude", nodes);
    r.excitation_node = static_cast<std::size_t>(k.count("excitation_node"));
    if (r.excitation_node >= nodes)
        throw InvalidParameter("excitation_node", "OscillatorResponse: excitation_node must be a node, < " +
                                                      std::to_string(nodes));
    r.transient = k.number("transient");
    r.measured_time = k.number("measured_time");
    r.reach = k.number("reach");
    r.settled = k.flag("settled");
    r.stats.steps = k.count("steps");
    r.stats.events = k.count("events");
    k.done();
    return r;
}

py::dict drag_keywords(const OscillatorDragResult& r) {
    py::dict d;
    d["plain"] = r.plain;
    d["vibrated"] = r.vibrated;
    d["vibration_amplitude"] = to_array(r.vibration_amplitude);
    d["axial_factor"] = to_array(r.multipliers.axial);
    d["circumferential_factor"] = to_array(r.multipliers.circumferential);
    d["reduction"] = to_array(r.reduction);
    d["zone_top"] = r.zone_top;
    d["zone_bottom"] = r.zone_bottom;
    d["zone_length"] = r.zone_length;
    d["coupling_passes"] = r.coupling_passes;
    d["converged"] = r.converged;
    d["source"] = vibration_source_name(r.source);
    d["responses"] = r.responses;
    return d;
}

OscillatorDragResult drag_result_from(const py::kwargs& kwargs) {
    Keywords k(kwargs, "OscillatorDragResult");
    OscillatorDragResult r;
    for (const auto& [name, into] : {std::pair{"plain", &r.plain}, std::pair{"vibrated", &r.vibrated}}) {
        const py::handle v = k[name];
        require_constructed(v);
        if (!py::isinstance<TorqueDragResult>(v))
            throw py::type_error(std::string("OscillatorDragResult: ") + name + " must be a TorqueDragResult (got " +
                                 type_name(v) + ")");
        *into = v.cast<TorqueDragResult>();
    }
    const std::size_t elements = r.plain.side_force.size();
    k.check_size("vibrated", r.vibrated.side_force.size(), elements);
    r.vibration_amplitude = k.values("vibration_amplitude", elements);
    r.multipliers.axial = k.values("axial_factor", elements);
    r.multipliers.circumferential = k.values("circumferential_factor", elements);
    r.reduction = k.values("reduction", elements);
    r.zone_top = k.number("zone_top");
    r.zone_bottom = k.number("zone_bottom");
    r.zone_length = k.number("zone_length");
    r.coupling_passes = static_cast<std::size_t>(k.count("coupling_passes"));
    r.converged = k.flag("converged");
    const py::handle source = k["source"];
    const std::string name = py::isinstance<py::str>(source) ? source.cast<std::string>() : "";
    if (name != "wave" && name != "dynamic")
        throw InvalidParameter("source", "OscillatorDragResult: source must be 'wave' or 'dynamic' (got " +
                                             std::string(py::repr(source)) + ")");
    r.source = name == "wave" ? VibrationSource::wave : VibrationSource::dynamic;
    const py::handle responses = k["responses"];
    if (!py::isinstance<py::list>(responses) && !py::isinstance<py::tuple>(responses))
        throw py::type_error("OscillatorDragResult: responses must be a list of OscillatorResponse (got " +
                             type_name(responses) + ")");
    for (const py::handle item : responses) {
        require_constructed(item);
        if (!py::isinstance<OscillatorResponse>(item))
            throw py::type_error("OscillatorDragResult: responses must hold OscillatorResponse objects (got " +
                                 type_name(item) + ")");
        r.responses.push_back(item.cast<OscillatorResponse>());
    }
    k.done();
    return r;
}

/// fs.OscillatorResponse: one tool's dynamic run (read-only arrays per node of the dynamic model).
void register_oscillator_response(py::module_& m) {
    py::class_<OscillatorResponse>(m, "OscillatorResponse", R"doc(
One tool's periodic steady-state response from the dynamic axial string model (drillstring/oscillator_response.hpp):
the event-driven StringRig in the well, the hook at the operation's speed, the bit holding the weight on bit (a
free end), Coulomb walls with the soft string's side forces. Per node of the dynamic model (N + 1, node 0 at the
surface): measured_depth [m], first_harmonic [m/s] and phase [rad] of the axial speed at the tool's frequency
(v ~ V + first_harmonic sin(omega t + phase)), reversed (share of the cycle sliding against the operation),
friction_factor (the wall's cycle-mean friction over mu N, from each node's mean balance) and amplitude [m/s]
(what the friction sees: the first harmonic, at most the amplitude of the sinusoid with that mean friction).
Built by SoftString.oscillator_response; OscillatorResponse(**fields) rebuilds one from its fields (pickling).
)doc")
        .def(py::init([](const py::kwargs& kwargs) { return oscillator_response_from(kwargs); }))
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::tuple(), response_keywords(self.cast<const OscillatorResponse&>()));
        })
        .def_property_readonly("phasor", [](const OscillatorResponse& r) { return to_complex_array(r.phasor); },
                               "Per node, the first harmonic as a complex amplitude [m/s]: "
                               "first_harmonic * exp(1j * phase).")
        .def_property_readonly("measured_depth", [](const OscillatorResponse& r) { return to_array(r.measured_depth); },
                               "Measured depth of each node of the dynamic model [m].")
        .def_property_readonly("first_harmonic",
                               [](const OscillatorResponse& r) { return to_array(magnitudes(r.phasor)); },
                               "Per node, the first harmonic of the axial speed at the tool's frequency [m/s].")
        .def_property_readonly("phase", [](const OscillatorResponse& r) { return to_array(phases(r.phasor)); },
                               "Per node, its phase [rad] (v ~ V + a sin(omega t + phase)).")
        .def_property_readonly("reversed", [](const OscillatorResponse& r) { return to_array(r.reversed); },
                               "Per node, the share of the cycle sliding against the operation's motion.")
        .def_property_readonly("friction_factor", [](const OscillatorResponse& r) { return to_array(r.friction_factor); },
                               "Per node, the wall's cycle-mean friction over mu N (1 where no contact).")
        .def_property_readonly("amplitude", [](const OscillatorResponse& r) { return to_array(r.amplitude); },
                               "Per node, the amplitude the friction sees [m/s].")
        .def_readonly("excitation_node", &OscillatorResponse::excitation_node, "The node the tool's force acts on.")
        .def_readonly("transient", &OscillatorResponse::transient, "Time run before the measured window [s].")
        .def_readonly("measured_time", &OscillatorResponse::measured_time, "The whole cycles measured [s].")
        .def_readonly("reach", &OscillatorResponse::reach,
                      "The travelling-wave estimate's reach from the tool [m] (the default transient's length).")
        .def_readonly("settled", &OscillatorResponse::settled,
                      "False when max_time ran out before two windows agreed.")
        .def_property_readonly("steps", [](const OscillatorResponse& r) { return r.stats.steps; },
                               "Integrator steps of the whole run.")
        .def_property_readonly("events", [](const OscillatorResponse& r) { return r.stats.events; },
                               "Stick-slip switches of the whole run.")
        .def("__repr__", [](const OscillatorResponse& r) {
            return "OscillatorResponse(" + std::to_string(r.elements()) + " elements, transient " +
                   format_double(r.transient) + " s, " + std::to_string(r.stats.events) + " events, settled=" +
                   (r.settled ? "True" : "False") + ")";
        });
}

const char* const vibration_keywords_doc =
    "vibration ('wave': the travelling-wave estimate, microseconds; 'dynamic': the axial string model run to a "
    "periodic steady state, seconds, operations without rotation only) and the dynamic run's settings: transient "
    "(s, None: 4 l / c then windows until settled), cycles (8), elements_per_wavelength (16), damping_time (0 s), "
    "rtol (1e-6), stick_speed (1e-4 m/s), steady_tolerance (0.02), max_time (30 s).\n";

/// The conditions of SoftStringParams' table from keywords; with `tools`, also OscillatorDragParams' (the
/// estimate's settings) and `model` / `lubricant`. Any other keyword is a TypeError naming it.
SoftStringParams conditions_from(const py::kwargs& kwargs, const char* owner = "SoftString.run",
                                 OscillatorDragParams* tools = nullptr) {
    SoftStringParams p{};
    refuse_arrays(kwargs, owner);
    std::size_t used = read_field_keywords(p, kwargs, condition_fields, owner);
    if (tools) {
        used += read_field_keywords(*tools, kwargs, drag_fields, owner);
        if (kwargs.contains("model")) {
            const py::handle m = kwargs["model"];
            const std::string name = py::isinstance<py::str>(m) ? m.cast<std::string>() : "";
            if (name == "friction_vector") tools->model = VibrationFrictionModel::friction_vector;
            else if (name == "table5") tools->model = VibrationFrictionModel::table5;
            else throw InvalidParameter("model", std::string(owner) + ": model must be 'friction_vector' or "
                                                                      "'table5' (got " + std::string(py::repr(m)) + ")");
            ++used;
        }
        if (kwargs.contains("lubricant")) {
            const py::handle l = kwargs["lubricant"];
            if (!py::isinstance<py::str>(l))
                throw InvalidParameter("lubricant", std::string(owner) + ": lubricant must be one of dry, water, "
                                                                         "wbm, obm, sbm (got " + type_name(l) + ")");
            tools->lubricant = lubricant_from_name(l.cast<std::string>());
            ++used;
        }
        used += read_vibration_keywords(kwargs, owner, *tools);
    }
    if (used != kwargs.size())
        for (auto item : kwargs) {
            const std::string key = py::str(item.first);
            const bool known = names_field(key, condition_fields) ||
                               (tools && (names_field(key, drag_fields) || key == "model" || key == "lubricant" ||
                                          is_vibration_keyword(key)));
            if (!known) throw py::type_error(std::string(owner) + "() got an unexpected keyword argument '" + key + "'");
        }
    validate_fields(owner, p, condition_fields);
    if (tools) validate_fields(owner, *tools, drag_fields);
    return p;
}

std::vector<HydraulicOscillator> tools_from(py::handle tools, const char* owner) {
    require_constructed(tools);
    if (py::isinstance<HydraulicOscillator>(tools)) return {tools.cast<HydraulicOscillator>()};
    if (py::isinstance<py::str>(tools) || !py::hasattr(tools, "__iter__"))
        throw py::type_error(std::string(owner) + ": tools must be a HydraulicOscillator or a sequence of them (got " +
                             type_name(tools) + ")");
    std::vector<HydraulicOscillator> out;
    for (py::handle t : tools) {
        if (out.size() == max_tools)  // an endless iterator stops here
            throw InvalidParameter("tools", std::string(owner) + ": tools must hold at most " +
                                                std::to_string(max_tools) + " tools (a string carries one to three)");
        require_constructed(t);
        if (!py::isinstance<HydraulicOscillator>(t))
            throw py::type_error(std::string(owner) + ": tools must hold HydraulicOscillator objects (got " +
                                 type_name(t) + ")");
        out.push_back(t.cast<HydraulicOscillator>());
    }
    return out;
}

/// The Python SoftString: what it was built from (properties, pickling) and the model.
struct BoundSoftString {
    Survey survey;
    DrillString string;
    SoftString model;
    OscillatorDrag tools;  // the same string and method with axial vibration tools

    BoundSoftString(Survey s, DrillString d, std::size_t elements, TorqueDragMethod method)
        : survey(std::move(s)), string(std::move(d)), model(survey, string, elements, method),
          tools(survey, string, elements, method) {}
};

constexpr TorqueDragMethod methods[] = {TorqueDragMethod::johancsik, TorqueDragMethod::aadnoy};

TorqueDragMethod method_from(py::handle value) {
    std::string names;
    for (TorqueDragMethod m : methods)
        names += std::string(names.empty() ? "" : ", ") + "'" + torque_drag_method_name(m) + "'";
    if (!py::isinstance<py::str>(value))
        throw py::type_error("SoftString: method must be a str, one of " + names + " (got " + type_name(value) + ")");
    const std::string name = value.cast<std::string>();
    for (TorqueDragMethod m : methods)
        if (name == torque_drag_method_name(m)) return m;
    throw InvalidParameter("method", "SoftString: method must be one of " + names + " (got " +
                                         std::string(py::repr(value)) + ")");
}

std::size_t elements_from(py::handle value) {
    if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__"))
        throw py::type_error("SoftString: elements must be a whole number (got " + type_name(value) + ")");
    const long n = value.attr("__index__")().cast<long>();
    if (n < 1 || n > max_elements)
        throw InvalidParameter("elements", "SoftString: elements must be in [1, " + std::to_string(max_elements) +
                                               "] (got " + std::to_string(n) + ")");
    return static_cast<std::size_t>(n);
}

/// SoftString.oscillator_response: one tool's dynamic run on its own.
template <class Cls>
void def_oscillator_response(Cls& cls) {
    cls.def("oscillator_response",
            [](const BoundSoftString& s, py::handle operation, const HydraulicOscillator& tool, const py::kwargs& kwargs) {
                const Operation op = operation_from(operation);
                OscillatorDragParams o;
                const SoftStringParams p = conditions_from(kwargs, "SoftString.oscillator_response", &o);
                return interruptible(o, [&] { return s.tools.response_model().response(op, p, tool, o.dynamic); });
            },
            kept("oscillator_response(self, operation: str, tool: HydraulicOscillator, **keywords) -> "
                 "OscillatorResponse\n\nOne tool's periodic steady-state response from the dynamic axial string "
                 "model under the operation (no rotation). Keywords: the conditions of SoftString.parameters and "
                 "the dynamic run's settings: " + std::string(vibration_keywords_doc)),
            py::arg("operation"), py::arg("tool"));
}

const char* const soft_string_doc = R"doc(
Soft-string torque and drag of a DrillString hung from measured depth 0 along a Survey (which must reach the
string's length), cut into `elements` elements of equal length: node 0 at the surface, node N at the bit, element e
between nodes e and e + 1. method='johancsik' (the default; Johancsik, Friesen & Dawson 1984, SPE 11380), from the
bit up, per element:

    F_n = sqrt(F^2 (beta^2 - dI^2) + (F dI + W sin I_avg)^2)        side force (dI = I_top - I_bottom)
    F_top = F + W dTVD/dL +/- mu_axial F_n,   M_top = M + mu_circ F_n r

with W the buoyed weight g (m - rho_mud V), beta the element's dogleg on the minimum-curvature well and the
friction factor split between axial and circumferential sliding by the sliding-velocity vector (trip speed
against rotary speed: paper 000's friction vector). run(operation, **conditions) gives a TorqueDragResult; the
conditions are the keywords of SoftString.parameters (mud density, cased and open-hole friction factors, casing shoe,
hole sizes, speeds, weight and torque on bit), SI units. Operations: SoftString.operations.

method='aadnoy' (Aadnoy & Andersen 2001; Aadnoy, Fazaelizadeh & Hareland 2010, JCPT 49(10)) integrates each element
in closed form instead: exact on straight elements, builds and drops with weight (the contact moving to the low side
included) and weightless 3D doglegs (the capstan exp(mu theta)) at any element length; second order in the element
length where the weight has a share across a 3D dogleg's plane (Johancsik's step is first order). The oscillators and
sliding_weight_on_bit estimates run with the same method.
)doc";

}  // namespace

void register_wells(py::module_& m) {
    py::options options;

    // ---- Survey
    py::class_<Survey> survey(m, "Survey", R"doc(
A well survey: stations of measured depth [m], inclination from vertical [rad, 0..pi] and azimuth from north
towards east [rad], measured depth strictly increasing; its minimum-curvature trajectory (Sawaryn & Thorogood 2005,
SPE 84246): between two stations the circular arc tangent to both station directions.

Survey(measured_depth, inclination, azimuth) takes radians; Survey.from_degrees(...) takes degrees (as survey
listings give them). Positions are relative to the first station: north, east and true vertical depth [m] per
station; dogleg [rad] and dogleg_severity [rad/m] per station of the course ending there (0 at station 0).
A bad survey (fewer than two stations, NaN, depth not increasing, inclination outside 0..180 degrees, a course that
reverses the direction) raises InvalidParameterError (a ValueError) naming the station and the field.
)doc");
    survey.attr("parameters") = parameter_infos(SurveyStation::fields());
    options.disable_function_signatures();
    survey
        .def(py::init([](py::handle md, py::handle inc, py::handle azi) {
                 return Survey(stations_from(real_numbers(md, "Survey", "measured_depth"),
                                             real_numbers(inc, "Survey", "inclination"),
                                             real_numbers(azi, "Survey", "azimuth")));
             }),
             "__init__(self, measured_depth: numpy.typing.ArrayLike, inclination: numpy.typing.ArrayLike, "
             "azimuth: numpy.typing.ArrayLike) -> None\n\nStations in SI: measured depth [m], inclination and "
             "azimuth [rad].\n",
             py::arg("measured_depth"), py::arg("inclination"), py::arg("azimuth"))
        .def_static("from_degrees",
                    [](py::handle md, py::handle inc, py::handle azi) {
                        const char* owner = "Survey.from_degrees";
                        return Survey::from_degrees(stations_from(real_numbers(md, owner, "measured_depth"),
                                                                  real_numbers(inc, owner, "inclination"),
                                                                  real_numbers(azi, owner, "azimuth")));
                    },
                    "from_degrees(measured_depth: numpy.typing.ArrayLike, inclination: numpy.typing.ArrayLike, "
                    "azimuth: numpy.typing.ArrayLike) -> Survey\n\nStations with measured depth [m], inclination "
                    "and azimuth in degrees (errors quote degrees).\n",
                    py::arg("measured_depth"), py::arg("inclination"), py::arg("azimuth"));
    options.enable_function_signatures();
    survey
        .def_property_readonly("measured_depth",
                               [](const Survey& s) {
                                   return to_array(station_values(s, &SurveyStation::measured_depth));
                               },
                               "Measured depth of each station [m].")
        .def_property_readonly("inclination",
                               [](const Survey& s) { return to_array(station_values(s, &SurveyStation::inclination)); },
                               "Inclination of each station [rad].")
        .def_property_readonly("azimuth",
                               [](const Survey& s) { return to_array(station_values(s, &SurveyStation::azimuth)); },
                               "Azimuth of each station as given [rad].")
        .def_property_readonly("north", [](const Survey& s) { return to_array(positions(s, &Survey::north)); },
                               "North of each station relative to station 0 [m].")
        .def_property_readonly("east", [](const Survey& s) { return to_array(positions(s, &Survey::east)); },
                               "East of each station relative to station 0 [m].")
        .def_property_readonly("tvd", [](const Survey& s) { return to_array(positions(s, &Survey::tvd)); },
                               "True vertical depth of each station relative to station 0 [m].")
        .def_property_readonly("dogleg", [](const Survey& s) { return to_array(per_course(s, false)); },
                               "Dogleg angle of the course ending at each station [rad] (0 at station 0).")
        .def_property_readonly("dogleg_severity", [](const Survey& s) { return to_array(per_course(s, true)); },
                               "Dogleg severity of the course ending at each station [rad/m] (0 at station 0); "
                               "times 180/pi * 30 for degrees per 30 m.");
    options.disable_function_signatures();  // the signature as pybind11 writes it for an array (real_numbers reads it)
    survey.def("interpolate",
             [](const Survey& s, py::handle given) {
                 const char* owner = "Survey.interpolate";
                 const std::vector<double> depths =
                     column(real_numbers(given, owner, "measured_depth"), owner, "measured_depth");
                 std::vector<double> inc, azi, north, east, tvd, curvature;
                 for (double d : depths) {
                     const WellPoint p = s.at(d);
                     inc.push_back(p.inclination);
                     azi.push_back(p.azimuth);
                     north.push_back(p.north);
                     east.push_back(p.east);
                     tvd.push_back(p.tvd);
                     curvature.push_back(p.curvature);
                 }
                 py::dict out;
                 out["measured_depth"] = to_array(depths);
                 out["inclination"] = to_array(inc);
                 out["azimuth"] = to_array(azi);
                 out["north"] = to_array(north);
                 out["east"] = to_array(east);
                 out["tvd"] = to_array(tvd);
                 out["curvature"] = to_array(curvature);
                 return out;
             },
             "interpolate(self: frictionsim._core.Survey, measured_depth: typing.Annotated[numpy.typing.ArrayLike, "
             "numpy.float64]) -> dict\n\n"
             "The well at each measured depth [m] (within the survey) on the minimum-curvature arcs: a dict of "
             "arrays measured_depth, inclination and azimuth [rad] (azimuth in [0, 2 pi)), north, east, tvd [m] "
             "and curvature [rad/m] (the dogleg severity of the course holding it).\n",
             py::arg("measured_depth"));
    options.enable_function_signatures();
    survey.def("__len__", &Survey::size)
        .def("__repr__", &survey_repr)
        .def("__reduce__", [](py::handle self) {
            const auto& s = self.cast<const Survey&>();
            py::tuple stations = py::make_tuple(to_array(station_values(s, &SurveyStation::measured_depth)),
                                                to_array(station_values(s, &SurveyStation::inclination)),
                                                to_array(station_values(s, &SurveyStation::azimuth)));
            return reduce_by_construction(self, std::move(stations));
        });

    // ---- TorqueDragResult
    py::class_<TorqueDragResult>(m, "TorqueDragResult", R"doc(
Torque and drag of one operation along the string: per node (N + 1, node 0 at the surface) measured_depth [m],
tension (effective, compression < 0) [N], torque [N m], the Dawson-Paslay sinusoidal and Chen-Lin-Cheatham helical
buckling loads [N] and the flags where the compression exceeds them; per element (N) side_force [N] and
side_force_per_length [N/m]. hook_load [N] (less the block weight) and surface_torque [N m] are node 0's.
Built by SoftString.run; TorqueDragResult(**fields) rebuilds one from its fields (pickling).
)doc")
        .def(py::init([](const py::kwargs& kwargs) { return torque_drag_result_from(kwargs); }))
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::tuple(), torque_drag_keywords(self.cast<const TorqueDragResult&>()));
        })
        .def_property_readonly("operation", [](const TorqueDragResult& r) { return operation_name(r.operation); })
        .def_property_readonly("measured_depth", [](const TorqueDragResult& r) { return to_array(r.measured_depth); },
                               "Measured depth of each node [m].")
        .def_property_readonly("tension", [](const TorqueDragResult& r) { return to_array(r.tension); },
                               "Effective tension at each node [N] (compression < 0).")
        .def_property_readonly("torque", [](const TorqueDragResult& r) { return to_array(r.torque); },
                               "Torque at each node [N m].")
        .def_property_readonly("side_force", [](const TorqueDragResult& r) { return to_array(r.side_force); },
                               "Wall contact force of each element [N].")
        .def_property_readonly("side_force_per_length",
                               [](const TorqueDragResult& r) { return to_array(r.side_force_per_length); },
                               "Wall contact force per length of each element [N/m].")
        .def_property_readonly("sinusoidal_buckling_load",
                               [](const TorqueDragResult& r) { return to_array(r.sinusoidal_buckling_load); },
                               "Dawson-Paslay critical compression at each node [N].")
        .def_property_readonly("helical_buckling_load",
                               [](const TorqueDragResult& r) { return to_array(r.helical_buckling_load); },
                               "Chen-Lin-Cheatham critical compression at each node [N].")
        .def_property_readonly("sinusoidally_buckled",
                               [](const TorqueDragResult& r) { return to_flags(r.sinusoidally_buckled); },
                               "Compression above the sinusoidal buckling load, per node.")
        .def_property_readonly("helically_buckled",
                               [](const TorqueDragResult& r) { return to_flags(r.helically_buckled); },
                               "Compression above the helical buckling load, per node.")
        .def_property_readonly("hook_load", &TorqueDragResult::hook_load, "Tension at the surface [N].")
        .def_property_readonly("surface_torque", &TorqueDragResult::surface_torque, "Torque at the surface [N m].")
        .def("__repr__", [](const TorqueDragResult& r) {
            return std::string("TorqueDragResult(") + operation_name(r.operation) + ", " +
                   std::to_string(r.measured_depth.size()) + " nodes, hook_load=" + format_double(r.hook_load()) +
                   " N, surface_torque=" + format_double(r.surface_torque()) + " N m)";
        });

    // ---- HydraulicOscillator, OscillatorResponse, OscillatorDragResult
    register_oscillator_response(m);
    py::class_<HydraulicOscillator> tool(m, "HydraulicOscillator", kept(
        "An axial vibration tool (hydraulic oscillator, agitator) in the string: its force amplitude and frequency at "
        "a measured depth (drillstring/axial_wave.hpp).\n\nKeywords\n--------\n" + keywords_doc(tool_fields)));
    tool.def(py::init([](const py::kwargs& kwargs) {
                 HydraulicOscillator t{};
                 refuse_arrays(kwargs, "HydraulicOscillator");
                 const std::size_t used = read_field_keywords(t, kwargs, tool_fields, "HydraulicOscillator");
                 if (used != kwargs.size())
                     for (auto item : kwargs)
                         if (!names_field(py::str(item.first), tool_fields))
                             throw py::type_error("HydraulicOscillator() got an unexpected keyword argument '" +
                                                  std::string(py::str(item.first)) + "'");
                 validate_fields("HydraulicOscillator", t, tool_fields);
                 return t;
             }));
    def_field_properties(tool, tool_fields, [](const HydraulicOscillator& t) -> const HydraulicOscillator& { return t; });
    tool.def("__repr__", [](const HydraulicOscillator& t) {
            std::string fields;
            for (const Field<HydraulicOscillator>& f : tool_fields)
                fields += std::string(fields.empty() ? "" : ", ") + f.public_name() + "=" + format_double(t.*(f.member));
            return "HydraulicOscillator(" + fields + ")";
        })
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::tuple(), field_keywords(self.cast<const HydraulicOscillator&>(),
                                                                            tool_fields));
        });

    py::class_<OscillatorDragResult>(m, "OscillatorDragResult",
                                     "One operation with and without the tools: the plain and vibrated torque and "
                                     "drag, per element the vibration amplitude and friction factors, the zone of "
                                     "influence and the changes at the surface. Built by SoftString.oscillators; "
                                     "OscillatorDragResult(**fields) rebuilds one from its fields (pickling).")
        .def(py::init([](const py::kwargs& kwargs) { return drag_result_from(kwargs); }))
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::tuple(), drag_keywords(self.cast<const OscillatorDragResult&>()));
        })
        .def_property_readonly("plain", [](const OscillatorDragResult& r) { return r.plain; },
                               "TorqueDragResult without the tools (a copy).")
        .def_property_readonly("vibrated", [](const OscillatorDragResult& r) { return r.vibrated; },
                               "TorqueDragResult with them (a copy).")
        .def_property_readonly("vibration_amplitude",
                               [](const OscillatorDragResult& r) { return to_array(r.vibration_amplitude); },
                               "Per element, the tools' axial velocity amplitude [m/s] (vibration='dynamic': the "
                               "amplitude the friction sees; the first harmonics are in responses).")
        .def_property_readonly("axial_factor", [](const OscillatorDragResult& r) { return to_array(r.multipliers.axial); },
                               "Per element, the factor on the axial friction.")
        .def_property_readonly("circumferential_factor",
                               [](const OscillatorDragResult& r) { return to_array(r.multipliers.circumferential); },
                               "Per element, the factor on the circumferential friction.")
        .def_property_readonly("reduction", [](const OscillatorDragResult& r) { return to_array(r.reduction); },
                               "Per element, 1 - the factor of the friction against the operation's motion.")
        .def_readonly("zone_top", &OscillatorDragResult::zone_top, "Top of the zone of influence [m MD].")
        .def_readonly("zone_bottom", &OscillatorDragResult::zone_bottom, "Bottom of the zone of influence [m MD].")
        .def_readonly("zone_length", &OscillatorDragResult::zone_length,
                      "Length of the elements reduced past zone_threshold [m] (0: no zone).")
        .def_property_readonly("source", [](const OscillatorDragResult& r) { return vibration_source_name(r.source); },
                               "Where the vibration came from: 'wave' or 'dynamic'.")
        .def_property_readonly("responses", [](const OscillatorDragResult& r) { return r.responses; },
                               "vibration='dynamic': each active tool's OscillatorResponse (copies), else empty.")
        .def_readonly("coupling_passes", &OscillatorDragResult::coupling_passes)
        .def_readonly("converged", &OscillatorDragResult::converged)
        .def_property_readonly("hook_load_change", &OscillatorDragResult::hook_load_change, "[N]")
        .def_property_readonly("surface_torque_change", &OscillatorDragResult::surface_torque_change, "[N m]")
        .def("__repr__", [](const OscillatorDragResult& r) {
            return "OscillatorDragResult(zone " + format_double(r.zone_top) + " to " + format_double(r.zone_bottom) +
                   " m, hook load change " + format_double(r.hook_load_change()) + " N, surface torque change " +
                   format_double(r.surface_torque_change()) + " N m)";
        });

    // ---- SoftString
    py::class_<BoundSoftString> cls(m, "SoftString", kept(soft_string_doc + std::string("\nConditions\n----------\n") +
                                                          keywords_doc(condition_fields)));
    cls.attr("parameters") = parameter_infos(condition_fields);
    py::tuple names(std::size(operations));
    for (std::size_t i = 0; i < std::size(operations); ++i) names[i] = operation_name(operations[i]);
    cls.attr("operations") = names;
    options.disable_function_signatures();
    cls.attr("methods") = py::make_tuple(torque_drag_method_name(methods[0]), torque_drag_method_name(methods[1]));
    cls.def(py::init([](py::handle s, py::handle d, py::handle elements, py::handle method) {
                for (const auto& [value, name, ok] : {std::tuple{s, "survey", py::isinstance<Survey>(s)},
                                                      std::tuple{d, "string", py::isinstance<DrillString>(d)}}) {
                    require_constructed(value);
                    if (!ok)
                        throw py::type_error(std::string("SoftString: ") + name + " must be a " +
                                             (std::string(name) == "survey" ? "Survey" : "DrillString") + " (got " +
                                             type_name(value) + ")");
                }
                const TorqueDragMethod m = method_from(method);
                return BoundSoftString(s.cast<Survey>(), d.cast<DrillString>(), elements_from(elements), m);
            }),
            "__init__(self, survey: Survey, string: DrillString, elements: int, method: str = 'johancsik') -> None"
            "\n\nThe string hung from measured depth 0 along the survey, in `elements` elements of equal length; "
            "method: 'johancsik' (explicit step per element) or 'aadnoy' (closed form per element).\n",
            py::arg("survey"), py::arg("string"), py::arg("elements"), py::arg("method") = "johancsik");
    std::string run_signature = "run(self, operation: str, *";
    const SoftStringParams defaults{};
    for (const Field<SoftStringParams>& f : condition_fields)
        run_signature += ", " + std::string(f.public_name()) + ": float = " + format_double(defaults.*(f.member));
    cls.def("run",
            [](const BoundSoftString& s, py::handle operation, const py::kwargs& kwargs) {
                const Operation op = operation_from(operation);
                const SoftStringParams p = conditions_from(kwargs);
                TorqueDragResult out;
                {
                    py::gil_scoped_release release;
                    s.model.run(op, p, out);
                }
                return out;
            },
            kept(run_signature + ") -> TorqueDragResult\n\nTorque and drag of one operation (one of "
                                 "SoftString.operations) under the conditions given by keyword (the others keep "
                                 "their defaults; see SoftString.parameters).\n"),
            py::arg("operation"));
    const std::string tool_keywords =
        "Keywords: the conditions of SoftString.parameters, and bit_reflection (R in [-1, 1]: +1 a free bit), "
        "zone_threshold (0.05), coupling_tolerance (1e-9), model ('friction_vector': the friction vector's cycle "
        "mean, or 'table5': paper 000's power law), lubricant (Table 5's row: dry, water, wbm, obm, sbm), " +
        std::string(vibration_keywords_doc);
    cls.def("oscillators",
            [](const BoundSoftString& s, py::handle operation, py::handle tools, const py::kwargs& kwargs) {
                const Operation op = operation_from(operation);
                OscillatorDragParams o;
                const SoftStringParams p = conditions_from(kwargs, "SoftString.oscillators", &o);
                const std::vector<HydraulicOscillator> t = tools_from(tools, "SoftString.oscillators");
                return interruptible(o, [&] { return s.tools.run(op, p, t, o); });
            },
            kept("oscillators(self, operation: str, tools: HydraulicOscillator | list[HydraulicOscillator], **keywords) "
                 "-> OscillatorDragResult\n\nOne operation with and without axial vibration tools: each tool's wave "
                 "attenuated by the wall friction it produces, the friction reduced element by element, coupled with "
                 "the side forces until it settles.\n" + tool_keywords),
            py::arg("operation"), py::arg("tools"));
    cls.def("sliding_weight_on_bit",
            [](const BoundSoftString& s, double hook_load, py::handle tools, const py::kwargs& kwargs) {
                OscillatorDragParams o;
                const SoftStringParams p = conditions_from(kwargs, "SoftString.sliding_weight_on_bit", &o);
                const std::vector<HydraulicOscillator> t = tools_from(tools, "SoftString.sliding_weight_on_bit");
                return interruptible(o, [&] { return s.tools.weight_on_bit_at(hook_load, p, t, o); });
            },
            kept("sliding_weight_on_bit(self, hook_load: float, tools: HydraulicOscillator | list[HydraulicOscillator], "
                 "**keywords) -> float\n\nThe weight on bit [N] transferred while sliding at the hook load [N] with "
                 "the tools (an empty list: without): the placement objective.\n" + tool_keywords),
            py::arg("hook_load"), py::arg("tools"));
    def_oscillator_response(cls);
    options.enable_function_signatures();
    cls.def_property_readonly("survey", [](const BoundSoftString& s) { return s.survey; }, "The Survey (a copy).")
        .def_property_readonly("string", [](const BoundSoftString& s) { return s.string; },
                               "The DrillString (a copy).")
        .def_property_readonly("elements", [](const BoundSoftString& s) { return s.model.elements(); }, "N.")
        .def_property_readonly("method",
                               [](const BoundSoftString& s) { return torque_drag_method_name(s.model.method()); },
                               "How each element is integrated: 'johancsik' or 'aadnoy'.")
        .def_property_readonly("element_length", [](const BoundSoftString& s) { return s.model.element_length(); },
                               "Length of each element [m].")
        .def_property_readonly("node_depths", [](const BoundSoftString& s) { return to_array(s.model.node_depths()); },
                               "Measured depth of each node [m] (N + 1).")
        .def_property_readonly("node_inclinations",
                               [](const BoundSoftString& s) { return to_array(s.model.node_inclinations()); },
                               "Inclination at each node [rad].")
        .def("element_weights",
             [](const BoundSoftString& s, double mud_density) {
                 detail::require_non_negative("SoftString", "mud_density", mud_density);
                 std::vector<double> w(s.model.elements());
                 for (std::size_t e = 0; e < w.size(); ++e) w[e] = s.model.element_weight(e, mud_density);
                 return to_array(w);
             },
             "Buoyed weight of each element [N] in mud of density mud_density [kg/m^3].", py::arg("mud_density"))
        .def("node_side_forces",
             [](const BoundSoftString& s, const Values& tension, double mud_density) {
                 const std::vector<double> t = column(tension, "SoftString.node_side_forces", "tension");
                 return to_array(s.model.node_side_forces(t, mud_density));
             },
             "The wall contact force at each node [N] for an effective tension per node (N + 1 values, surface "
             "first): each element's side force under the mean of its end tensions, half to each of its nodes.",
             py::arg("tension"), py::arg("mud_density"))
        .def("__repr__", [](const BoundSoftString& s) {
            const std::string method = s.model.method() == TorqueDragMethod::johancsik
                                           ? ""
                                           : std::string(", method='") + torque_drag_method_name(s.model.method()) + "'";
            return "SoftString(" + survey_repr(s.survey) + ", " + std::string(py::repr(py::cast(s.string))) +
                   ", elements=" + std::to_string(s.model.elements()) + method + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& s = self.cast<const BoundSoftString&>();
            return reduce_by_construction(self, py::make_tuple(py::cast(s.survey), py::cast(s.string),
                                                               s.model.elements(),
                                                               torque_drag_method_name(s.model.method())));
        });
}

}  // namespace frictionsim::python
