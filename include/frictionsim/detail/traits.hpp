// The C++17 detection idiom the concept checks are built on (friction/law.hpp, solve/hybrid_system.hpp).
#pragma once

#include <type_traits>

namespace frictionsim::detail {

/// Is Op<T> well-formed?
template <class, template <class> class Op, class = void>
struct detected : std::false_type {};
template <class T, template <class> class Op>
struct detected<T, Op, std::void_t<Op<T>>> : std::true_type {};

}  // namespace frictionsim::detail
