// What a model's Result holds beside t and its friction law's states (whose units the law gives, Law::state_units):
// each column's name, SI unit and meaning, declared once next to the model's parameter table (the lab rigs of rigs/
// and the string models of string/ alike, so it sits on the floor of parameters.hpp, below both). The Python package
// reads it (Rig.outputs) for units in files and on plot axes; nothing looks a unit up by class or state name.
#pragma once

namespace frictionsim {

/// One output column of a rig: `friction_force` (a force [N] or a torque [N m]) or one of its own states.
struct RigOutput {
    /// As Result::state_names gives it; "friction_force" for the friction column; "theta_*" for a state per node
    /// (theta_0, theta_1, ...); "mode" with unit "1" where the mode column counts stuck contacts.
    const char* name;
    const char* unit;  ///< SI, as the parameter tables write units ("N m", "rad/s", "J")
    const char* what;  ///< one line for help() and file metadata
};

}  // namespace frictionsim
