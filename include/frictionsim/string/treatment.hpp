// How a drill string's contacts are treated (issue 22): every switch located exactly (the event-driven StringRig,
// string_rig.hpp), every contact captured by Moreau-Jean (TorsionalString, torsional_string.hpp), or the walls
// captured and the bit's switches located (mixed: TorsionalString with BitTreatment::exact). One string model, three
// treatments, and the automatic choice from issue 13's measured rule (bench/mixed.bench.cpp: the cost to reach 1e-4 s
// in the bit's switch times, ratios within one run):
//   N = 10 wall contacts:   mixed 3.1x and captured 8.7x the event-driven cost      -> exact
//   N = 100:                event-driven 1.25x and captured 1.7x the mixed cost     -> mixed
//   N = 1000:               mixed 1.07x and event-driven 1.43x the captured cost    -> captured
// The crossovers lie between the measured points; the rule puts them at the geometric middles (about 30 and 300
// contacts). Off bottom the mixed model is the captured one (no lumped switch to locate), so it is not chosen.
#pragma once

#include <cstddef>

namespace frictionsim {

enum class StringTreatment { exact, captured, mixed };

/// Contacts up to which every switch located exactly costs least, and up to which the mixed treatment does.
inline constexpr std::size_t exact_treatment_up_to = 30;
inline constexpr std::size_t mixed_treatment_up_to = 300;

/// The measured rule: exact for at most 30 wall contacts; mixed for at most 300 with the bit on bottom; captured
/// beyond (and for more than 30 off bottom).
inline StringTreatment automatic_treatment(std::size_t wall_contacts, bool bit_on_bottom) {
    if (wall_contacts <= exact_treatment_up_to) return StringTreatment::exact;
    if (bit_on_bottom && wall_contacts <= mixed_treatment_up_to) return StringTreatment::mixed;
    return StringTreatment::captured;
}

inline const char* treatment_name(StringTreatment t) {
    return t == StringTreatment::exact ? "exact" : t == StringTreatment::captured ? "captured" : "mixed";
}

}  // namespace frictionsim
