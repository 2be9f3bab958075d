// Must NOT compile: a user's state law (has_stick = false) that forgot `state_derivative`. frictionsim's
// check_friction_law<Law>() names the missing member ("FrictionLaw requires `void state_derivative(...)`") as the
// first error, where the rig is instantiated. CMakeLists.txt try_compiles this file and fails the configure step
// if it compiles, or if the message is missing.
#include <array>
#include <cstddef>

#include <frictionsim/simulate.hpp>

struct BrokenBristleLaw {
    static constexpr const char* name = "BrokenBristleLaw";
    static constexpr bool has_stick = false;
    static constexpr std::size_t state_count = 1;
    static constexpr bool kink_at_zero_velocity = false;
    static constexpr std::array<const char*, 1> state_names{{"bristle_deflection"}};
    double force(double, double, const double* z, int) const { return 1e4 * z[0]; }
    // missing: void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const;
};

int main() {
    const frictionsim::AxialRig<BrokenBristleLaw> rig(frictionsim::AxialRigParams{}, BrokenBristleLaw{});
    return frictionsim::simulate(rig, 0.1).completed ? 0 : 1;
}
