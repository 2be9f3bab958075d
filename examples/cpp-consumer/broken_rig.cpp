// Must NOT compile: a user's rig that forgot `guard_name`. frictionsim's check_hybrid_system<S>() names the missing
// member ("HybridSystem requires `const char* guard_name(...)`") as the first error, in simulate(). CMakeLists.txt
// try_compiles this file and fails the configure step if it compiles, or if the message is missing.
#include <array>
#include <cstddef>

#include <frictionsim/simulate.hpp>

struct BrokenRig {  // a mass on a spring, with one guard (x = 0)
    static constexpr std::size_t state_size = 2, guard_count = 1;
    void rhs(double, const double* x, int, double* dxdt) const { dxdt[0] = x[1], dxdt[1] = -x[0]; }
    void guards(double, const double* x, int, double* g) const { g[0] = x[0]; }
    int guard_direction(std::size_t, int) const { return 0; }
    // missing: const char* guard_name(std::size_t i, int mode) const;
    int initial_mode(double, const double*) const { return 0; }
    int switch_mode(double, double*, int mode, const int*) const { return mode; }
    const char* mode_name(int) const { return "free"; }
    std::array<const char*, 2> state_names() const { return {{"position", "velocity"}}; }
    double friction_force(double, const double*, int) const { return 0.0; }
    std::array<double, 2> initial_state() const { return {{1.0, 0.0}}; }
};

int main() { return frictionsim::simulate(BrokenRig{}, 1.0).completed ? 0 : 1; }
