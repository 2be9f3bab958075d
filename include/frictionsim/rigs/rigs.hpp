// The list of the engine's rigs that a parameter table and a law build (Rig<Law>(Params, law)): what code that
// enumerates rigs reads (the fuzz target; the Python bindings bind each with bind_rig). The kinematic rig is built
// from signals, not a table, and stands apart.
#pragma once

#include <cstddef>
#include <utility>

#include "axial_rig.hpp"
#include "torsional_rig.hpp"

namespace frictionsim {

template <template <class> class... Rig>
struct RigList {
    static constexpr std::size_t size = sizeof...(Rig);
};

/// A value standing for a rig template: f(rig_tag<AxialRig>{}), then `typename decltype(tag)::template of<Law>`.
template <template <class> class Rig>
struct rig_tag {
    template <class Law>
    using of = Rig<Law>;
};

/// Calls f(rig_tag<Rig>{}) for every rig of the list, in order.
template <template <class> class... Rig, class F>
void for_each_rig(RigList<Rig...>, F&& f) {
    (f(rig_tag<Rig>{}), ...);
}

/// Rigs built from a Params struct with a fields() table and a law.
using TabledRigs = RigList<AxialRig, TorsionalRig>;

}  // namespace frictionsim
