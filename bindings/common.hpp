// Shared declarations of the _core extension: the friction-law variant the rigs are built on, the time signals
// of the kinematic rig, and the register_* functions each translation unit defines.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <frictionsim/frictionsim.hpp>

#include "callable_law.hpp"

namespace frictionsim::python {

namespace py = pybind11;

/// Raises TypeError when `self` skipped __init__ (`cls.__new__(cls)`, a pickle without state): pybind11 would hand
/// out uninitialised memory as its C++ value (garbage parameters, then a crash in simulate()).
void require_constructed(py::handle self);

/// `__reduce__` of a class that its constructor rebuilds: unpickling calls `cls(*args, **kwargs)` (or the static
/// factory `cls.<factory>(...)`) through `_core._rebuild`, so a restored object passes exactly the checks, keyword
/// names and errors of construction, and there is no `__setstate__` to skip them or to call on a live object.
py::tuple reduce_by_construction(py::handle self, py::tuple args, py::dict kwargs = py::dict(),
                                 const char* factory = "");

/// Every instantaneous friction law a rig can run with: the engine's laws and the Python-defined CallableLaw. One
/// variant alternative per law: the rigs are instantiated once per law, the right-hand side stays free of virtual
/// calls.
using PythonLaws = append<EngineLaws, CallableLaw>::type;
using FrictionLaw = variant_of<PythonLaws>::type;

/// The names of the string models' top-drive kinds (the keyword top_drive, StringRig's and TorsionalString's alike).
inline const char* top_drive_name(TopDrive d) { return d == TopDrive::pi_motor ? "pi_motor" : "prescribed_speed"; }
/// `value` (a name of top_drive_name's) as a TopDrive; InvalidParameter naming top_drive, said for `owner`, else.
TopDrive top_drive_from(py::handle value, const char* owner);

/// The Python object (a bound law) -> the variant; TypeError naming `parameter` for anything else.
FrictionLaw friction_law_from_python(py::handle law, const char* parameter);
py::object friction_law_to_python(const FrictionLaw& law);
/// Is `law` an instance of one of PythonLaws' classes?
bool is_engine_law(py::handle law);
/// "Coulomb, Stribeck, ... or ElastoPlastic" (with `extra` as the last name when given), for error messages.
std::string engine_law_names(const char* extra = nullptr);

/// The laws and paper 001's eq 6 (acceleration-dependent): what the rigs that can carry eq 6 take (the torsional
/// disc, the kinematic rig with a prescribed speed and its derivative).
using LawsAndHysteretic = append<PythonLaws, HystereticFriction>::type;
using LawOrHysteretic = variant_of<LawsAndHysteretic>::type;
LawOrHysteretic law_or_hysteretic_from_python(py::handle law, const char* parameter);
py::object law_or_hysteretic_to_python(const LawOrHysteretic& law);

/// A prescribed signal of time for the kinematic rig: a constant, samples (piecewise linear), the paper's
/// harmonic sliding velocity, or a Python callable (called with the GIL re-acquired). A switch per call
/// instead of one rig instantiation per signal kind keeps the extension small.
class Signal {
public:
    enum class Kind { constant, sampled, harmonic, callable };

    static Signal constant(double value, const char* name);
    static Signal sampled(std::vector<double> t, std::vector<double> y, const char* name);
    static Signal harmonic(double sliding_velocity, double velocity_amplitude, double angular_frequency);
    static Signal callable(py::object function, const char* name);
    /// float -> constant, (t, y) pair of arrays -> sampled, callable -> callable; TypeError otherwise.
    static Signal from_python(py::handle value, const char* name);

    double operator()(double t) const;
    /// d/dt of the signal: 0, the sampled slope ahead, analytic for the harmonic, a central difference of a
    /// callable (h = 6e-6 max(1, |t|), two more calls: its O(h^2) error shifts located dw/dt = 0 switches slightly).
    double derivative(double t) const;
    Kind kind() const { return kind_; }
    /// What from_python would rebuild this signal from (for pickling and repr).
    py::object to_python() const;

private:
    Kind kind_ = Kind::constant;
    std::string name_;
    double value_ = 0.0;
    std::shared_ptr<const SampledSignal> samples_;
    std::vector<double> t_, y_;  // kept for to_python
    std::optional<HarmonicSlidingVelocity> harmonic_;
    std::shared_ptr<py::object> function_;
};


void register_errors(py::module_& m);
void register_laws(py::module_& m);
void register_callable_law(py::module_& m);
void register_results(py::module_& m);
void register_contact(py::module_& m);
// The rigs of EngineRigs, the string models too: register_rig<Entry> (bindings/rig_binding.hpp), read from the list
// by module.cpp.

}  // namespace frictionsim::python
