// Textbook set-ups of the axial rig with no vibration, shared by tests, benchmarks and examples. The papers'
// presets are in ../papers.hpp.
#pragma once

#include "../friction/lugre.hpp"
#include "axial_rig.hpp"

namespace frictionsim {

/// A block of `mass` on a horizontal plane (normal force m g), pulled through a spring of `stiffness` whose
/// end moves at `pull_velocity`: the classic stick-slip oscillator.
inline AxialRigParams spring_block_params(double mass, double stiffness, double pull_velocity,
                                          double gravitational_acceleration = 9.81) {
    AxialRigParams p;
    p.mass = mass;
    p.drive_stiffness = stiffness;
    p.sliding_velocity = pull_velocity;
    p.amplitude = 0.0;
    p.normal_force = mass * gravitational_acceleration;
    return p;
}

/// The stick-slip example of Canudas de Wit, Olsson, Astrom & Lischinsky (1995): m = 1 kg, k = 2 N/m, pulled
/// at 0.1 m/s; normal force 1 N so that friction coefficients read as their forces (Fc = 1 N, Fs = 1.5 N).
/// Their LuGre values: Fc = 1 N, Fs = 1.5 N at N = 1 N, v_s = 1 mm/s, sigma0 = 1e5 N/m, sigma1 = sqrt(1e5) N s/m,
/// sigma2 = 0.4 N s/m (LuGre::Params' defaults, with their viscous friction).
inline LuGre::Params canudas_de_wit_1995_lugre() {
    LuGre::Params p;
    p.viscous_damping = 0.4;
    return p;
}

inline AxialRigParams canudas_de_wit_1995_params() {
    AxialRigParams p = spring_block_params(1.0, 2.0, 0.1);
    p.normal_force = 1.0;
    return p;
}

}  // namespace frictionsim
