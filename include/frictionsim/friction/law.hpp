// What every friction law declares, and the contact modes shared by laws and rigs.
//
// A friction law is a small value type, validated on construction, SI units. Two kinds:
//  * set-valued laws (Coulomb, Stribeck): `has_stick = true`, no internal state;
//      double static_limit(double normal_force) const;            // largest force that sticking can carry
//      double slip_force(double v_r, double normal_force, int direction) const;   // direction = sign of slip
//      double karnopp_band() const;                                // 0: exact stick (switch model)
//  * state laws (Dahl, LuGre, ElastoPlastic): `has_stick = false`, `state_count >= 1` internal states z;
//      double force(double v_r, double normal_force, const double* z, int branch) const;
//      void state_derivative(double v_r, double normal_force, const double* z, int branch, double* dz) const;
//      static constexpr bool kink_at_zero_velocity;   // the rig locates v_r = 0 as an event; branch = sign(v_r)
//      static constexpr std::array<const char*, state_count> state_names;
//      StatePartials<state_count> partials(double v_r, double normal_force, const double* z, int branch) const;
//  set-valued laws also give  double slip_slope(double v_r, double normal_force, int direction) const;
//  (dF/dv_r in slip): the rigs' analytic Jacobians for CVODE are built from these.
// Every law has `static constexpr const char* name`. A law never integrates anything itself.
#pragma once

#include <array>
#include <cstddef>

namespace frictionsim {

/// First derivatives of a state law at (v_r, z): force F and state rate dz/dt with respect to v_r and z.
template <std::size_t Z>
struct StatePartials {
    double force_velocity = 0.0;                     ///< dF / dv_r
    std::array<double, Z> force_state{};             ///< dF / dz_j
    std::array<double, Z> rate_velocity{};           ///< d(dz_i/dt) / dv_r
    std::array<std::array<double, Z>, Z> rate_state{};  ///< d(dz_i/dt) / dz_j
};

/// Contact modes. Slip modes carry the sign of the relative velocity; stick is v_r = 0 held by friction
/// (or, with a Karnopp band, |v_r| < band).
enum ContactMode : int { slip_negative = -1, stick = 0, slip_positive = 1 };

inline const char* contact_mode_name(int mode) {
    return mode < 0 ? "slip_negative" : mode > 0 ? "slip_positive" : "stick";
}

inline int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

}  // namespace frictionsim
