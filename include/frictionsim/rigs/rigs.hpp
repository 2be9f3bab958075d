// The engine's rigs, one list: what code that enumerates rigs reads (the Python bindings register each, the fuzz
// target draws from them, bench/integrators runs each). An entry names the rig and how it is built:
//   law_rig<Rig, Params>    Rig<Law>(Params, law): a parameter table and any friction law
//   table_rig<Rig, Params>  Rig(Params): the table alone (a law of its own inside, e.g. the Navarro-Lopez bit)
//   signal_rig              the kinematic rig: a law driven by prescribed signals, no table
//   event_string_rig        the event-driven drill string, sized at run time: StringRig<WallLaw, Bit>(DrillString,
//                           its table, its set-up, a wall law, a bit)
//   time_stepping_rig<M, P> a time-stepping string model sized at run time: M(DrillString, P, elements), run by
//                           the time-stepping methods (the Aarsnes-Shor TorsionalString; needs Eigen)
// Each entry gives its outputs (name, SI unit, meaning of each Result column beside t and the law's states). Code
// that enumerates rigs handles each kind or skips it by kind (for_each_rig<kind>); the string kinds need a
// DrillString and are not built from a table alone. This header is the registry: it reads string/ as well as rigs/.
// Adding a rig: its header, then one line in EngineRigs (docs/architecture.md, "Adding a rig").
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "../friction/laws.hpp"
#include "../outputs.hpp"
#include "../string/string_rig.hpp"
#include "axial_rig.hpp"
#include "kinematic_rig.hpp"
#include "navarro_lopez.hpp"
#include "torsional_rig.hpp"
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
#include "../string/torsional_string.hpp"
#endif

namespace frictionsim {

enum class RigConstruction { law, table, signal, string, time_stepping };

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

/// The event-driven drill string (string/string_rig.hpp), sized at run time: `of<WallLaw, Bit>(string, params,
/// setup, law, bit)` from a DrillString, its table (StringRigParams), its set-up (StringRigSetup: elements, drive,
/// axial motion, contacts), a wall law and a bit (OffBottom, BitOnRock, DetournayBitOnRock).
struct event_string_rig {
    static constexpr RigConstruction construction = RigConstruction::string;
    template <class WallLaw, class Bit = OffBottom>
    using of = StringRig<WallLaw, Bit>;
    using Params = StringRigParams;
    static constexpr const char* name = StringRigParams::rig_name;  ///< its Python class's name
    static constexpr auto outputs() { return StringRigParams::outputs(); }
};

/// A time-stepping string model (solve/time_stepping.hpp: run by Method::moreau_jean / explicit_projection, not
/// the ODE methods), sized at run time: `type(string, params, elements)` from a DrillString and its table.
template <class Model, class P>
struct time_stepping_rig {
    static constexpr RigConstruction construction = RigConstruction::time_stepping;
    using type = Model;
    using Params = P;
    static constexpr const char* name = P::rig_name;  ///< its Python class's name
    static constexpr auto outputs() { return P::outputs(); }
};

/// Every rig of the engine, in the order Python binds them (fs.RIGS): the lab rigs, the string models (the
/// event-driven StringRig before the Navarro-Lopez strings, whose bit law its bindings file binds; the Moreau-Jean
/// TorsionalString last, where Eigen is: FRICTIONSIM_EIGEN).
using EngineRigs = TypeList<law_rig<AxialRig, AxialRigParams>,      //
                            signal_rig,                              //
                            law_rig<TorsionalRig, TorsionalRigParams>,  //
                            event_string_rig,                        //
                            table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>,
                            table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>
#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
                            ,
                            time_stepping_rig<TorsionalString, TorsionalStringParams>
#endif
                            >;

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
