// Checks that several test files run on a rig: one definition each.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <frictionsim/simulate.hpp>

#include "catch.hpp"

namespace frictionsim::test {

/// Axial rig: drive work = kinetic + spring (+ potential) energy change + friction work, at four times of a tight run.
template <class Law>
void check_energy_balance(const AxialRig<Law>& rig, Method method, double t_end) {
    SolverOptions o;
    o.method = method;
    o.rtol = 1e-10;
    o.atol = 1e-13;
    o.output_times = {0.0, 0.25 * t_end, 0.5 * t_end, t_end};
    const Result r = simulate(rig, t_end, o);
    const std::size_t drive = r.column("drive_work"), friction = r.column("friction_work");
    std::vector<double> x0(r.state_count());
    for (std::size_t c = 0; c < r.state_count(); ++c) x0[c] = r.state(0, c);
    const double e0 = rig.mechanical_energy(0.0, x0.data());
    for (std::size_t i = 1; i < r.rows(); ++i) {
        const double* x = &r.states[i * r.state_count()];
        const double stored = rig.mechanical_energy(r.t[i], x) - e0;
        const double balance = r.state(i, drive) - stored - r.state(i, friction);
        INFO("t = " << r.t[i] << ": drive " << r.state(i, drive) << ", stored " << stored << ", friction "
                    << r.state(i, friction));
        // the terms are O(1e-2 J); global error of a rtol = 1e-10 run is well below 1e-6 of them
        CHECK(std::abs(balance) < 1e-6 * (std::abs(r.state(i, friction)) + std::abs(stored) + 1e-3));
    }
}

}  // namespace frictionsim::test
