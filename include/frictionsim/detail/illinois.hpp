// Illinois false position (Dowell & Jarratt 1971, BIT 11, 168-174): the regula falsi with the value at an end that
// is kept twice in a row halved, so that the bracket shrinks from both sides (superlinear, never slower than
// bisection by much). One bracket type for every root search of the engine: the guards on a step's dense output
// (solve/root_location.hpp), the user's stop conditions, the lumped switches of Moreau-Jean with events, and the
// weight on bit at a hook load. The caller decides which end a new point replaces (a sign, or a crossing test).
#pragma once

namespace frictionsim::detail {

struct IllinoisBracket {
    double a, ga, b, gb;  ///< the bracket [a, b] and the function's values (halved when stale) at its ends
    int last = 0;         ///< the end that moved last: -1 a, +1 b, 0 none yet

    /// The false-position point, or the midpoint where that falls within `margin` of an end (or outside).
    double next(double margin = 0.0) const {
        const double x = b - gb * (b - a) / (gb - ga);
        return x > a + margin && x < b - margin ? x : 0.5 * (a + b);
    }
    /// x (value gx) replaces b when `replaces_b`, else a; the other end's value is halved if it was kept last time.
    void move(double x, double gx, bool replaces_b) {
        if (replaces_b) {
            b = x;
            gb = gx;
            if (last == +1) ga *= 0.5;
            last = +1;
        } else {
            a = x;
            ga = gx;
            if (last == -1) gb *= 0.5;
            last = -1;
        }
    }
};

}  // namespace frictionsim::detail
