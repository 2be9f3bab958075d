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
// Optional: set-valued laws' `double slip_slope(double v_r, double normal_force, int direction) const` (dF/dv_r in
// slip) and state laws' `partials`: the rigs' analytic Jacobians for CVODE are built from these; without them
// CVODE builds its Jacobian from difference quotients. `static constexpr bool stiff = true` picks CVODE BDF.
// Optional for a state law with a memory that changes only at reversals (Leuven's turning points):
//      void on_reversal(double normal_force, double* z, int from_branch, int to_branch) const;
// The memory is carried in its states z (rate 0 between events); every rig that locates the kink at v_r = 0 calls
// note_reversal() (below) when it flips the branch, handing the law its states to update: exact, at the event.
// Such a law also gives `double presliding_length(double normal_force) const` for the planar wall contact
// (contact/wall_contact.hpp: the length over which its reference axis follows the sliding direction).
// Every law has `static constexpr const char* name`. A law never integrates anything itself.
// check_friction_law<Law>() (below) static_asserts each requirement with a message naming it; the rigs and
// ContactSwitching call it first, so a law that misses a member fails there, not deep inside a rig.
#pragma once

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "../contact_mode.hpp"
#include "../detail/traits.hpp"

namespace frictionsim {

/// First derivatives of a state law at (v_r, z): force F and state rate dz/dt with respect to v_r and z.
template <std::size_t Z>
struct StatePartials {
    double force_velocity = 0.0;                     ///< dF / dv_r
    std::array<double, Z> force_state{};             ///< dF / dz_j
    std::array<double, Z> rate_velocity{};           ///< d(dz_i/dt) / dv_r
    std::array<std::array<double, Z>, Z> rate_state{};  ///< d(dz_i/dt) / dz_j
};

namespace detail {
template <class L> using law_name_t = decltype(static_cast<const char*>(L::name));
template <class L> using has_stick_t = decltype(bool{L::has_stick});
template <class L> using state_count_t = decltype(std::integral_constant<std::size_t, L::state_count>{});
template <class L> using static_limit_t = decltype(double{std::declval<const L&>().static_limit(0.0)});
template <class L> using slip_force_t = decltype(double{std::declval<const L&>().slip_force(0.0, 0.0, 1)});
template <class L> using karnopp_band_t = decltype(double{std::declval<const L&>().karnopp_band()});
template <class L> using slip_slope_t = decltype(double{std::declval<const L&>().slip_slope(0.0, 0.0, 1)});
template <class L> using force_t =
    decltype(double{std::declval<const L&>().force(0.0, 0.0, std::declval<const double*>(), 1)});
template <class L> using state_derivative_t = decltype(std::declval<const L&>().state_derivative(
    0.0, 0.0, std::declval<const double*>(), 1, std::declval<double*>()));
template <class L> using kink_t = decltype(bool{L::kink_at_zero_velocity});
template <class L> using state_names_of_t =
    std::enable_if_t<std::tuple_size<std::decay_t<decltype(L::state_names)>>::value == L::state_count>;
template <class L> using partials_t =
    decltype(std::declval<const L&>().partials(0.0, 0.0, std::declval<const double*>(), 1).force_velocity);

template <class L> using on_reversal_t = decltype(std::declval<const L&>().on_reversal(
    0.0, std::declval<double*>(), 1, -1));

template <class L, bool = detected<L, has_stick_t>::value>
struct set_valued_law : std::false_type {};
template <class L>
struct set_valued_law<L, true> : std::bool_constant<L::has_stick> {};
}  // namespace detail

/// Does Law give the analytic first derivatives the rigs' Jacobians need (slip_slope or partials)?
template <class Law>
constexpr bool law_has_partials_v = detail::set_valued_law<Law>::value
                                        ? detail::detected<Law, detail::slip_slope_t>::value
                                        : detail::detected<Law, detail::partials_t>::value;

/// Does Law keep a memory in its states that the rigs update at reversals (`on_reversal`)?
template <class Law>
constexpr bool law_remembers_reversals_v = detail::detected<Law, detail::on_reversal_t>::value;

/// What a rig calls when it flips a state law's branch at a located zero of v_r (from -> to; equal: a touch or a
/// standstill, nothing to remember): the law updates the memory it carries in z. A no-op for other laws.
template <class Law>
void note_reversal(const Law& law, double normal_force, double* z, int from_branch, int to_branch) {
    if constexpr (law_remembers_reversals_v<Law>) {
        if (from_branch != to_branch) law.on_reversal(normal_force, z, from_branch, to_branch);
    } else {
        (void)law, (void)normal_force, (void)z, (void)from_branch, (void)to_branch;
    }
}

/// static_asserts naming the first missing member of the FrictionLaw concept above; true when Law meets it.
template <class Law>
constexpr bool check_friction_law() {
    using namespace detail;
    static_assert(detected<Law, law_name_t>::value, "FrictionLaw requires `static constexpr const char* name`");
    static_assert(detected<Law, has_stick_t>::value,
                  "FrictionLaw requires `static constexpr bool has_stick` (true: set-valued with exact stick, "
                  "false: a state law)");
    static_assert(detected<Law, state_count_t>::value,
                  "FrictionLaw requires `static constexpr std::size_t state_count` (0 for a set-valued law)");
    if constexpr (detected<Law, has_stick_t>::value && detected<Law, state_count_t>::value) {
        if constexpr (Law::has_stick) {
            static_assert(Law::state_count == 0, "FrictionLaw: a set-valued law (has_stick = true) has state_count 0");
            static_assert(detected<Law, static_limit_t>::value,
                          "FrictionLaw requires `double static_limit(double normal_force) const` of a set-valued law");
            static_assert(detected<Law, slip_force_t>::value,
                          "FrictionLaw requires `double slip_force(double v_r, double normal_force, int direction) "
                          "const` of a set-valued law");
            static_assert(detected<Law, karnopp_band_t>::value,
                          "FrictionLaw requires `double karnopp_band() const` of a set-valued law (0: exact stick)");
        } else {
            static_assert(detected<Law, force_t>::value,
                          "FrictionLaw requires `double force(double v_r, double normal_force, const double* z, int "
                          "branch) const` of a state law");
            static_assert(detected<Law, state_derivative_t>::value,
                          "FrictionLaw requires `void state_derivative(double v_r, double normal_force, const double* "
                          "z, int branch, double* dz) const` of a state law");
            static_assert(detected<Law, kink_t>::value,
                          "FrictionLaw requires `static constexpr bool kink_at_zero_velocity` of a state law");
            if constexpr (detected<Law, kink_t>::value && detected<Law, on_reversal_t>::value)
                static_assert(Law::kink_at_zero_velocity,
                              "FrictionLaw: a law with `on_reversal` needs `kink_at_zero_velocity = true` (the rigs "
                              "locate the reversals it remembers)");
            static_assert(detected<Law, state_names_of_t>::value,
                          "FrictionLaw requires `static constexpr std::array<const char*, state_count> state_names` "
                          "of a state law");
        }
    }
    return detected<Law, law_name_t>::value && detected<Law, has_stick_t>::value &&
           detected<Law, state_count_t>::value;
}

}  // namespace frictionsim
