// The one list of the engine's instantaneous friction laws. Everything that enumerates laws reads it: the Python
// bindings (the rigs' law variant, one bound class per law), the benchmarks' registration, and through the bindings
// the Python package (scenario keys, fits, property-test strategies). Adding a law: its header, and one entry here.
#pragma once

#include <cstddef>
#include <variant>

#include "coulomb.hpp"
#include "dahl.hpp"
#include "elasto_plastic.hpp"
#include "gms.hpp"
#include "leuven.hpp"
#include "lugre.hpp"
#include "stribeck.hpp"

namespace frictionsim {

template <class... T>
struct TypeList {
    static constexpr std::size_t size = sizeof...(T);
};

/// A value standing for a type, to pass types to generic lambdas: f(type_tag<Law>{}).
template <class T>
struct type_tag {
    using type = T;
};

/// Calls f(type_tag<T>{}) for every T of the list, in order.
template <class... T, class F>
void for_each_type(TypeList<T...>, F&& f) {
    (f(type_tag<T>{}), ...);
}

/// std::variant<T...> of a list, and the list with more types appended.
template <class List>
struct variant_of;
template <class... T>
struct variant_of<TypeList<T...>> {
    using type = std::variant<T...>;
};
template <class List, class... More>
struct append;
template <class... T, class... More>
struct append<TypeList<T...>, More...> {
    using type = TypeList<T..., More...>;
};

/// The engine's instantaneous friction laws, in the order Python lists them.
using EngineLaws = TypeList<Coulomb, Stribeck, Dahl, LuGre, ElastoPlastic, GeneralizedMaxwellSlip, Leuven>;

}  // namespace frictionsim
