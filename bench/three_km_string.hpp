// The benchmarks' 3 km event-driven string, built in one place (bench/drillstring.bench.cpp measures its cost
// against N; bench/string_switch.bench.cpp its cost per located switch): 2800 m of 5" 19.5 ppf drill pipe over
// 200 m of 6.5" x 2.81" collars in a straight hole inclined 0.5 rad (28.6 deg), 1200 kg/m^3 mud, Coulomb walls
// (mu 0.2 kinetic, 0.3 static) at every node but the bit's, structural damping beta = 2 ms, a 500 kg m^2 top drive
// under PI control (k_p 3e3, k_i 1e3) at 3 rad/s, and the Navarro-Lopez velocity-weakening bit (R_b 0.156 m,
// mu 0.5 .. 0.8, c_b 50 N m s/rad) on bottom at W = 150 kN.
#pragma once

#include <cstddef>

#include <frictionsim/friction/coulomb.hpp>
#include <frictionsim/string/string_rig.hpp>

namespace frictionsim::bench {

using ThreeKmRig = StringRig<Coulomb, VelocityWeakeningBit>;

/// The 3 km string on `elements` elements, the whole string turning at `initial_speed` (rad/s) at t = 0.
inline ThreeKmRig three_km_string(std::size_t elements, double initial_speed = 0.0) {
    PipeSection pipe;
    pipe.length = 2800.0;
    PipeSection collar;
    collar.outer_diameter = 0.1651;
    collar.inner_diameter = 0.0714;
    collar.length = 200.0;
    StringRigParams p;
    p.inclination = 0.5;
    p.damping_time = 2e-3;
    p.surface_speed = 3.0;
    p.initial_speed = initial_speed;
    p.top_drive_inertia = 500.0;
    p.proportional_gain = 3e3;
    p.integral_gain = 1e3;
    StringRigSetup s;
    s.elements = elements;
    return ThreeKmRig(DrillString({pipe, collar}), p, s, Coulomb(0.2, 0.3),
                      VelocityWeakeningBit(NavarroLopezBit(), 1.5e5));
}

}  // namespace frictionsim::bench
