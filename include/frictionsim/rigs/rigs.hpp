// The engine's rigs, one list: what code that enumerates rigs reads (the Python bindings register each, the fuzz
// target draws from them, bench/integrators runs each). An entry names the rig and how it is built:
//   law_rig<Rig, Params>    Rig<Law>(Params, law): a parameter table and any friction law
//   table_rig<Rig, Params>  Rig(Params): the table alone (a law of its own inside, e.g. the Navarro-Lopez bit)
//   signal_rig              the kinematic rig: a law driven by prescribed signals, no table
// Each entry gives its outputs (name, SI unit, meaning of each Result column beside t and the law's states).
// Adding a rig: its header, then one line in EngineRigs (docs/architecture.md, "Adding a rig").
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "../friction/laws.hpp"
#include "axial_rig.hpp"
#include "kinematic_rig.hpp"
#include "navarro_lopez.hpp"
#include "outputs.hpp"
#include "torsional_rig.hpp"

namespace frictionsim {

enum class RigConstruction { law, table, signal };

/// A rig built from its parameter table and a friction law: `typename Entry::template of<Law>`.
template <template <class> class Rig, class P>
struct law_rig {
    static constexpr RigConstruction construction = RigConstruction::law;
    template <class Law>
    using of = Rig<Law>;
    using Params = P;
    static constexpr const char* name = P::rig_name;  ///< its Python class's name
    static constexpr auto outputs() { return P::outputs(); }
};

/// A rig built from its parameter table alone.
template <class Rig, class P>
struct table_rig {
    static constexpr RigConstruction construction = RigConstruction::table;
    using type = Rig;
    using Params = P;
    static constexpr const char* name = P::rig_name;  ///< its Python class's name
    static constexpr auto outputs() { return P::outputs(); }
};

/// The kinematic rig: a law under a prescribed relative velocity and normal force (`of<Law, V, N>`).
struct signal_rig {
    static constexpr RigConstruction construction = RigConstruction::signal;
    static constexpr const char* name = "KinematicRig";
    template <class Law, class RelativeVelocity, class NormalForce = ConstantSignal>
    using of = KinematicRig<Law, RelativeVelocity, NormalForce>;
    static constexpr auto outputs() { return kinematic_rig_outputs(); }
};

/// Every rig of the engine, in the order Python binds them (fs.RIGS; the string models stand apart, in string/).
using EngineRigs = TypeList<law_rig<AxialRig, AxialRigParams>,      //
                            signal_rig,                              //
                            law_rig<TorsionalRig, TorsionalRigParams>,  //
                            table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>,
                            table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>>;

/// How many entries of `Rigs` are built as `kind`.
template <RigConstruction kind, class... Entry>
constexpr std::size_t count_rigs(TypeList<Entry...>) {
    return ((Entry::construction == kind ? 1 : 0) + ... + 0);
}

/// Calls f(type_tag<Entry>{}) for every entry of `Rigs` built as `kind`, in order.
template <RigConstruction kind, class... Entry, class F>
void for_each_rig(TypeList<Entry...>, F&& f) {
    (
        [&] {
            if constexpr (Entry::construction == kind) f(type_tag<Entry>{});
        }(),
        ...);
}

}  // namespace frictionsim
