// The fuzz target's cases (fuzz_input.hpp): this file is compiled once per part (FRICTIONSIM_FUZZ_PART = 0 ..
// FRICTIONSIM_FUZZ_PARTS - 1) and instantiates only the cases c with c % parts == part.
#include <tuple>
#include <utility>

#include <frictionsim/string/string_model.hpp>
#include <frictionsim/string/torsional_string.hpp>
#include <frictionsim/wells/string_geometry.hpp>

#include "fuzz_input.hpp"

#ifndef FRICTIONSIM_FUZZ_PART
#error "FRICTIONSIM_FUZZ_PART (which of the FRICTIONSIM_FUZZ_PARTS objects this is) is set by the build"
#endif

namespace frictionsim::fuzz {
namespace {

/// A rig of EngineRigs built with `law`: the law rigs in the list's order, then the kinematic rig (the byte layout
/// of the seed corpus: its index comes after the law rigs').
template <class Law>
void run_rigs(const Law& law, Bytes& in) {
    constexpr std::size_t law_rigs = count_rigs<RigConstruction::law>(EngineRigs{});
    const SolverOptions o = options(in);
    const double t_end = in.byte() & 1 ? in.number() : 0.05;
    const std::size_t which = in.byte() % (law_rigs + 1);
    if (which == law_rigs) {  // the kinematic rig, built from signals
        if constexpr (Law::has_stick) {
            if (law.karnopp_band() > 0.0) return;  // rejected by the kinematic rig; checked elsewhere
        }
        const HarmonicSlidingVelocity v(in.number(), in.number(), in.number());
        using Kinematic = signal_rig::of<Law, HarmonicSlidingVelocity>;
        require_finite(simulate(Kinematic(law, v, ConstantSignal(in.number())), t_end, o));
        return;
    }
    std::size_t i = 0;
    for_each_rig<RigConstruction::law>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        using Rig = typename Entry::template of<Law>;
        if (i++ != which) return;
        const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
        require_finite(simulate(Rig(p, law), t_end, o));
    });
}

/// A law of the engine's list from the bytes: each field of its table either keeps its default or takes a number.
template <class Law>
Law law_from(Bytes& in) {
    return Law(params_from<typename Law::Params>(Law::fields, in));
}

/// `setup` in a surveyed well, read last (past the end a byte reads 0: no survey, so the seeds made before keep their
/// meaning): 2-4 stations from measured depth 0, spread evenly to the bit or at drawn depths, each inclination drawn
/// (a raw double or a byte's share of pi); the rig then takes the survey's node inclinations and soft-string wall
/// forces (wells/string_geometry.hpp), as a field string in a curved well does.
template <class Bit>
StringRigSetup surveyed(const DrillString& string, const StringRigParams& p, StringRigSetup setup, const Bit& bit,
                        Bytes& in) {
    const std::uint8_t how = in.byte();
    if (!(how & 1)) return setup;
    const std::size_t count = 2 + (how >> 1) % 3;
    std::vector<SurveyStation> stations(count);
    for (std::size_t k = 0; k < count; ++k) {
        SurveyStation& s = stations[k];
        s.measured_depth = how & 8 ? (k == 0 ? 0.0 : in.number())
                                   : string.length() * static_cast<double>(k) / static_cast<double>(count - 1);
        s.inclination = how & 16 ? in.number() : pi * in.byte() / 255.0;
        s.azimuth = how & 32 ? in.number() : 0.0;
    }
    return surveyed_setup(Survey(std::move(stations)), string, p, std::move(setup), bit);
}

/// The event-driven string of EngineRigs with `law` on its walls: 1-2 sections, its table, a small set-up (1-8
/// elements, PI or prescribed drive, torsion or also axial with either hoisting, wall contacts or none), off bottom
/// or on bottom with the velocity-weakening or the Detournay bit (tables and weight drawn), straight or in a surveyed
/// well (surveyed), on an ODE method.
template <class Law>
void run_string(const Law& law, Bytes& in) {
    static_assert(count_rigs<RigConstruction::string>(EngineRigs{}) == 1,
                  "the byte layout draws one event-driven string: give a second its own byte");
    for_each_rig<RigConstruction::string>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        const DrillString string = string_from(in);
        const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
        StringRigSetup setup;
        setup.elements = 1 + in.byte() % 8;
        const std::uint8_t flags = in.byte();
        setup.top_drive = flags & 1 ? TopDrive::prescribed_speed : TopDrive::pi_motor;
        setup.axial = (flags & 2) != 0;
        setup.hoisting = flags & 4 ? Hoisting::hook_load : Hoisting::hook_speed;
        setup.wall_contacts = (flags & 8) == 0;
        const SolverOptions o = options(in);
        const double t_end = in.byte() & 1 ? in.number() : 0.05;
        const std::uint8_t bit = in.byte() % 3;
        if (bit == 0) {
            const StringRigSetup s = surveyed(string, p, setup, OffBottom{}, in);
            require_finite(simulate(typename Entry::template of<Law>(string, p, s, law), t_end, o));
        } else if (bit == 1) {
            const NavarroLopezBit b(params_from<NavarroLopezBit::Params>(NavarroLopezBit::fields, in));
            const VelocityWeakeningBit on_rock(b, in.number());
            using Rig = typename Entry::template of<Law, VelocityWeakeningBit>;
            require_finite(simulate(Rig(string, p, surveyed(string, p, setup, on_rock, in), law, on_rock), t_end, o));
        } else {
            const DetournayBit b(params_from<DetournayBit::Params>(DetournayBit::fields, in));
            const DetournayBitOnRock on_rock(b, in.number());
            using Rig = typename Entry::template of<Law, DetournayBitOnRock>;
            require_finite(simulate(Rig(string, p, surveyed(string, p, setup, on_rock, in), law, on_rock), t_end, o));
        }
    });
}

/// A time-stepping model of EngineRigs: a small TorsionalString (1-16 elements, sections and parameters from their
/// tables), the bit's treatment, Moreau-Jean or the explicit projection with a drawn step, the PI or a prescribed
/// speed, the active set or projected Gauss-Seidel, or the string model's exact treatment; or a rig of EngineRigs
/// built from its table alone (a Navarro-Lopez string) on an ODE method.
void run_field(Bytes& in) {
    static_assert(count_rigs<RigConstruction::time_stepping>(EngineRigs{}) == 1,
                  "the byte layout draws one time-stepping model: give a second its own byte");
    constexpr std::size_t table_rigs = count_rigs<RigConstruction::table>(EngineRigs{});
    const std::size_t which = in.byte() % (table_rigs + 1);
    if (which > 0) {  // a rig of EngineRigs built from its table alone (the Navarro-Lopez strings)
        const SolverOptions o = options(in);
        const double t_end = in.byte() & 1 ? in.number() : 0.5;
        std::size_t i = 0;
        for_each_rig<RigConstruction::table>(EngineRigs{}, [&](auto tag) {
            using Entry = typename decltype(tag)::type;
            if (++i != which) return;
            const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
            require_finite(simulate(typename Entry::type(p), t_end, o));
        });
        return;
    }
    for_each_rig<RigConstruction::time_stepping>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        const DrillString string = string_from(in);
        const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
        const std::size_t elements = 1 + in.byte() % 16;
        typename Entry::type model(string, p, elements);
        model.set_bit_treatment(in.byte() & 1 ? BitTreatment::exact : BitTreatment::captured);
        SolverOptions o;
        o.method = in.byte() & 1 ? Method::explicit_projection : Method::moreau_jean;
        o.step = in.byte() & 1 ? in.number() : 1e-3;
        if (in.byte() & 1) o.theta = in.number();
        o.max_steps = 20000;
        o.max_output_rows = 5000;
        o.timeout = 2.0;
        const double t_end = in.byte() & 1 ? in.number() : 0.05;
        // read last, so the seeds made before keep their meaning (past the end a byte reads 0: the defaults)
        const std::uint8_t drive = in.byte();
        if (drive & 1) model.set_top_drive(TopDrive::prescribed_speed);
        if (drive & 2) o.contact_solver = ContactSolverChoice::projected_gauss_seidel;
        // then the string model's exact treatment (string/string_model.hpp: the StringRig of the same string on an
        // ODE method, its rows in the string's columns)
        if (in.byte() & 1) {
            const StringModel exact(model, StringTreatment::exact);
            SolverOptions e;
            e.max_steps = o.max_steps;
            e.max_output_rows = o.max_output_rows;
            e.timeout = o.timeout;
            return require_finite(simulate(exact, t_end, e));
        }
        require_finite(simulate(model, t_end, o));
    });
}

/// The I-th law of a list.
template <std::size_t I, class List>
struct law_at;
template <std::size_t I, class... T>
struct law_at<I, TypeList<T...>> {
    using type = std::tuple_element_t<I, std::tuple<T...>>;
};

template <std::size_t C>
void run_case_at(Bytes& in) {
    if constexpr (C == field_case) {
        run_field(in);
    } else if constexpr (C < string_case) {
        using Law = typename law_at<C - lab_case, EngineLaws>::type;
        run_rigs(law_from<Law>(in), in);
    } else {
        using Law = typename law_at<C - string_case, EngineLaws>::type;
        run_string(law_from<Law>(in), in);
    }
}

template <std::size_t Part, std::size_t... C>
void run_case_of(std::size_t c, Bytes& in, std::index_sequence<C...>) {
    const bool ran = ((c == Part + C * parts ? (run_case_at<Part + C * parts>(in), true) : false) || ...);
    if (!ran) defect("a case run in the wrong part");
}

}  // namespace

template <std::size_t Part>
void run_case(std::size_t c, Bytes& in) {
    constexpr std::size_t mine = (cases - Part + parts - 1) / parts;  // the cases Part, Part + parts, ...
    run_case_of<Part>(c, in, std::make_index_sequence<mine>{});
}

template void run_case<FRICTIONSIM_FUZZ_PART>(std::size_t, Bytes&);

}  // namespace frictionsim::fuzz
