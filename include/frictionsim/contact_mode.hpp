// The modes of one frictional contact, shared by laws, rigs and the contact solvers (no law needed to name them).
#pragma once

namespace frictionsim {

/// Contact modes. Slip modes carry the sign of the relative velocity; stick is v_r = 0 held by friction
/// (or, with a Karnopp band, |v_r| < band).
enum ContactMode : int { slip_negative = -1, stick = 0, slip_positive = 1 };

inline const char* contact_mode_name(int mode) {
    return mode < 0 ? "slip_negative" : mode > 0 ? "slip_positive" : "stick";
}

inline int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

}  // namespace frictionsim
