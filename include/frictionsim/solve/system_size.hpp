// A hybrid system's size and mode, whether fixed at compile time (the lab rigs) or known at run time (a drill
// string of N elements with a contact at each node). The event loop, the integrators and the recorder read a
// system only through these, so the fixed-size path keeps its std::arrays and unrolled loops while a run-time
// system gets std::vectors sized once.
//
//   fixed size:    static constexpr std::size_t state_size, guard_count;  std::array<...> initial_state(), state_names()
//   run-time size: std::size_t state_size() const, guard_count() const;    std::vector<double> initial_state(),
//                  std::vector<std::string> (or const char*) state_names()
//
// The mode is an `int` unless the system declares `using mode_type = ...` (e.g. ContactModes: one small state per
// contact). A system with its own Mode also provides
//   int mode_code(const Mode&) const;                // the Result's mode column (e.g. how many contacts stick)
//   int guard_mode(std::size_t i, const Mode&) const; // the mode of the contact that guard i belongs to; the
//                                                     // event log names it with mode_name(int)
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "../detail/traits.hpp"

namespace frictionsim {

namespace detail {
template <class S> using static_state_size_t = decltype(std::integral_constant<std::size_t, S::state_size>{});
template <class S> using static_guard_count_t = decltype(std::integral_constant<std::size_t, S::guard_count>{});
template <class S> using dynamic_state_size_t = decltype(std::size_t{std::declval<const S&>().state_size()});
template <class S> using dynamic_guard_count_t = decltype(std::size_t{std::declval<const S&>().guard_count()});
template <class S> using declared_mode_t = typename S::mode_type;
}  // namespace detail

/// Does S fix its size at compile time (static constexpr state_size and guard_count)?
template <class S>
constexpr bool has_fixed_size_v =
    detail::detected<S, detail::static_state_size_t>::value && detail::detected<S, detail::static_guard_count_t>::value;

/// Is S sized at run time (state_size() and guard_count() members)?
template <class S>
constexpr bool has_run_time_size_v = !has_fixed_size_v<S> && detail::detected<S, detail::dynamic_state_size_t>::value &&
                                     detail::detected<S, detail::dynamic_guard_count_t>::value;

namespace detail {
template <class S, bool = detected<S, declared_mode_t>::value>
struct mode_of { using type = int; };
template <class S>
struct mode_of<S, true> { using type = typename S::mode_type; };

template <class S, class T, bool Fixed = has_fixed_size_v<S>>
struct arrays { using states = std::vector<T>; using guards = std::vector<T>; };
template <class S, class T>
struct arrays<S, T, true> { using states = std::array<T, S::state_size>; using guards = std::array<T, S::guard_count>; };
}  // namespace detail

/// The mode a system's rhs, guards and switch_mode take: `int`, or the system's own `mode_type`.
template <class S>
using system_mode_t = typename detail::mode_of<S>::type;

/// One value per state / per guard: std::array for fixed-size systems, std::vector otherwise.
template <class S, class T = double>
using StateArray = typename detail::arrays<S, T>::states;
template <class S, class T = double>
using GuardArray = typename detail::arrays<S, T>::guards;

template <class S>
constexpr std::size_t state_size_of(const S& s) {
    if constexpr (has_fixed_size_v<S>) {
        (void)s;
        return S::state_size;
    } else {
        return s.state_size();
    }
}

template <class S>
constexpr std::size_t guard_count_of(const S& s) {
    if constexpr (has_fixed_size_v<S>) {
        (void)s;
        return S::guard_count;
    } else {
        return s.guard_count();
    }
}

/// A zeroed StateArray / GuardArray of the system's size.
template <class S, class T = double>
StateArray<S, T> make_state_array(const S& s) {
    if constexpr (has_fixed_size_v<S>) {
        (void)s;
        return StateArray<S, T>{};
    } else {
        return StateArray<S, T>(s.state_size(), T{});
    }
}
template <class S, class T = double>
GuardArray<S, T> make_guard_array(const S& s) {
    if constexpr (has_fixed_size_v<S>) {
        (void)s;
        return GuardArray<S, T>{};
    } else {
        return GuardArray<S, T>(s.guard_count(), T{});
    }
}

/// The Result's mode column for a mode: the int itself, or the system's mode_code.
template <class S>
int mode_code(const S& s, const system_mode_t<S>& mode) {
    if constexpr (std::is_same_v<system_mode_t<S>, int>) {
        (void)s;
        return mode;
    } else {
        return s.mode_code(mode);
    }
}

/// The mode an event log names for guard i: the whole mode (int), or the mode of guard i's contact.
template <class S>
int guard_mode(const S& s, std::size_t i, const system_mode_t<S>& mode) {
    if constexpr (std::is_same_v<system_mode_t<S>, int>) {
        (void)s;
        (void)i;
        return mode;
    } else {
        return s.guard_mode(i, mode);
    }
}

/// Per-contact modes of a run-time system: one small integer per contact (e.g. -1 slip backwards, 0 stick,
/// +1 slip forwards). Cheap to copy for the hundreds of contacts of a string; compared whole.
class ContactModes {
public:
    ContactModes() = default;
    explicit ContactModes(std::size_t contacts, std::int8_t value = 0) : of_(contacts, value) {}

    std::size_t size() const { return of_.size(); }
    std::int8_t operator[](std::size_t c) const { return of_[c]; }
    std::int8_t& operator[](std::size_t c) { return of_[c]; }
    /// How many contacts are in mode `value`.
    std::size_t count(std::int8_t value) const {
        std::size_t n = 0;
        for (std::int8_t m : of_) n += m == value;
        return n;
    }
    friend bool operator==(const ContactModes& a, const ContactModes& b) { return a.of_ == b.of_; }
    friend bool operator!=(const ContactModes& a, const ContactModes& b) { return !(a == b); }

private:
    std::vector<std::int8_t> of_;
};

}  // namespace frictionsim
