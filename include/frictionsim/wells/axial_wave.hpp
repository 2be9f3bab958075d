// The fast estimate of the axial vibration a downhole tool (hydraulic oscillator, agitator) drives along a drill
// string (issue 14, item 3): an attenuated travelling wave.
//  * Source: a force F sin(2 pi f t) at measured depth x_t on a long bar sends a wave each way; the point sees the
//    two impedances in parallel, so its velocity amplitude is a_0 = F / (Z_up + Z_down), F / (2 Z) on a uniform
//    string, with Z = E A / c = A sqrt(E rho) and c = sqrt(E / rho) (each element takes the section at its middle).
//  * Attenuation by the wall: a travelling wave carries the mean power P = Z a^2 / 2; the wall's Coulomb friction
//    f = mu q_n per metre (q_n the side force per length of the soft string) takes f < a sin(phi) v / |q| > from it
//    (vibration_friction.hpp), so dP/dx = -f D(a) and
//        da/dx = -f D(a) / (Z a),      without rotation   d sqrt(a^2 - V^2) / dx = -(2 / pi) f / Z   (a > V):
//    b = sqrt(a^2 - V^2) falls linearly, the energy form of Jacobsen's equivalent viscous damping of Coulomb friction
//    (vibration_friction.hpp). The wave ends where b reaches 0, a distance pi Z b_0 / (2 f) from the source
//    (pi F / (4 f) each way when V -> 0); below the sliding speed Coulomb friction neither damps a wave nor has a
//    cycle-mean effect with it, and the string's other damping (mud, tool joints), left out here, ends it: its
//    amplitude is set to zero there. With rotation D comes from the cycle-mean quadrature and the wave decays
//    without end (the midpoint rule per half element, sub-stepped where it decays fast).
//  * Section changes transmit the velocity amplitude by 2 Z_1 / (Z_1 + Z_2) (the reflected part is dropped).
//  * The bit reflects the downward wave with velocity coefficient R (+1 a free end, -1 a held one, 0 none). Between
//    the tool and the bit the direct wave a_d and the reflected one a_r then form a partly standing wave,
//        A^2 = a_d^2 + a_r^2 + 2 sign(R) a_d a_r cos(psi),   psi = 2 omega tau (tau the travel time to the bit),
//    and the wall takes f D(A) from it. Its share to each wave follows from equivalent linearisation (the friction's
//    first harmonic as a damper c = 2 f D(A) / A^2 on the total velocity; each wave loses the work of that damper on
//    its own velocity):  dP_d/dx = -f D(A) (a_d^2 + sign(R) a_d a_r cos psi) / A^2, and the same for a_r with the
//    roles swapped (the two sum to f D(A); dissipation where the waves cancel is small, so a standing wave carries
//    further than two waves damped each alone). a_d (down from the tool) and a_r (up from the bit, starting at
//    |R| a_d) are solved by alternating passes, explicit midpoint steps of at most a 40th of a wavelength. Above the
//    tool the reflected wave and the direct upward one travel together: one wave of amplitude
//    |F / 2Z + R-phased a_r| at the tool, attenuated as one.
//    The top of the string reflects nothing here: the waves of a tool in the lower string die out long before.
// tests/oscillator_drag.test.cpp compares the estimate with the event-driven StringRig, with and without a free bit.
// Published axial-oscillation-tool models that resolve the same physics numerically: Zhong et al., Sound &
// Vibration 57 (2023) 15-27 (reflection at the bit, best frequency 15-20 Hz); Wang et al., J. Pet. Sci. Eng. 160
// (2018) 60-71 (soft string with oscillators, pulse attenuation, placement).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../detail/constants.hpp"
#include "../detail/validate.hpp"
#include "../parameters.hpp"
#include "../string/sections.hpp"
#include "vibration_friction.hpp"

namespace frictionsim {

/// An axial vibration tool: force amplitude F at frequency f, at measured depth x_t along the string.
struct HydraulicOscillator {
    double measured_depth = 0.0;    ///< x_t, m (0 at the surface, at most the string's length)
    double force_amplitude = 50e3;  ///< F, N
    double frequency = 18.0;        ///< f, Hz

    static constexpr std::array<Field<HydraulicOscillator>, 3> fields();
};

inline constexpr std::array<Field<HydraulicOscillator>, 3> HydraulicOscillator::fields() {
    using P = HydraulicOscillator;
    return {{
        {"measured_depth", "x_t", "m", Rule::non_negative(), &P::measured_depth,
         "Measured depth of the tool (at most the string's length).", nullptr, true},
        {"force_amplitude", "F", "N", Rule::non_negative(), &P::force_amplitude,
         "Amplitude of the axial force the tool exerts."},
        {"frequency", "f", "Hz", Rule::positive(), &P::frequency, "Frequency of the tool's force."},
    }};
}

/// The string's axial wave properties on the elements of DrillString::lump(N) / SoftString (equal lengths, node 0
/// at the surface), and the travelling-wave amplitude of a tool along them.
class AxialWave {
public:
    AxialWave(const DrillString& string, std::size_t elements) {
        if (elements == 0) detail::reject("AxialWave", "elements", "at least 1", 0.0);
        length_ = string.length();
        const double n = static_cast<double>(elements);
        node_.resize(elements + 1);
        for (std::size_t i = 0; i <= elements; ++i) node_[i] = i == elements ? length_ : length_ * static_cast<double>(i) / n;
        impedance_.resize(elements);
        speed_.resize(elements);
        for (std::size_t e = 0; e < elements; ++e) {
            const double mid = 0.5 * (node_[e] + node_[e + 1]);
            double top = 0.0;
            const PipeSection* at = &string.sections().back();
            for (const PipeSection& s : string.sections()) {
                if (mid < top + s.length) {
                    at = &s;
                    break;
                }
                top += s.length;
            }
            speed_[e] = std::sqrt(at->youngs_modulus / at->density);
            impedance_[e] = at->area() * std::sqrt(at->youngs_modulus * at->density);
        }
    }

    std::size_t elements() const { return impedance_.size(); }
    double length() const { return length_; }
    double impedance(std::size_t e) const { return impedance_[e]; }  ///< Z = A sqrt(E rho), N s/m
    double wave_speed(std::size_t e) const { return speed_[e]; }     ///< c = sqrt(E / rho), m/s
    double mid_depth(std::size_t e) const { return 0.5 * (node_[e] + node_[e + 1]); }

    /// The tool's velocity amplitude at each element's middle [m/s] (the header comment's estimate).
    ///   wall_friction   per element, the Coulomb wall friction per length mu q_n [N/m]
    ///   sliding_speed   V [m/s], the string's steady axial speed
    ///   surface_speed   per element, the circumferential surface speed omega r [m/s]; empty: no rotation
    ///   bit_reflection  R in [-1, 1]: +1 a free bit, -1 a held one, 0 no reflection
    void amplitude(const HydraulicOscillator& tool, const std::vector<double>& wall_friction, double sliding_speed,
                   const std::vector<double>& surface_speed, double bit_reflection, std::vector<double>& out) const {
        check(tool, wall_friction, sliding_speed, surface_speed, bit_reflection);
        const std::size_t n = elements();
        out.assign(n, 0.0);
        if (tool.force_amplitude == 0.0) return;
        const Medium medium{wall_friction.data(), surface_speed.empty() ? nullptr : surface_speed.data(), sliding_speed};
        const double x_t = tool.measured_depth;
        // the elements just below and just above the tool (the end elements at the string's ends)
        std::size_t below = n - 1, above = 0;
        for (std::size_t e = 0; e < n; ++e)
            if (x_t < node_[e + 1]) {
                below = e;
                break;
            }
        for (std::size_t e = n; e-- > 0;)
            if (x_t > node_[e]) {
                above = e;
                break;
            }
        const double source = tool.force_amplitude / (impedance_[above] + impedance_[below]);

        // downward from the tool to the bit: elements whose middle is at or below x_t
        double a = source, x = x_t;
        if (x_t < length_) {
            for (std::size_t e = below; e < n; ++e) {
                if (e != below) a *= transmission(e - 1, e);
                const double mid = mid_depth(e);
                if (mid >= x) {
                    a = step(a, mid - x, e, medium);
                    out[e] = a;
                    x = mid;
                }
                a = step(a, node_[e + 1] - x, e, medium);
                x = node_[e + 1];
            }
        }
        const double at_bit = a;
        up_from_tool(source, x_t, above, medium, out);  // elements whose middle is above x_t
        if (bit_reflection == 0.0 || at_bit == 0.0) return;
        standing_wave(tool, medium, bit_reflection, below, above, source, out);
    }

    std::vector<double> amplitude(const HydraulicOscillator& tool, const std::vector<double>& wall_friction,
                                  double sliding_speed, const std::vector<double>& surface_speed = {},
                                  double bit_reflection = 0.0) const {
        std::vector<double> out;
        amplitude(tool, wall_friction, sliding_speed, surface_speed, bit_reflection, out);
        return out;
    }

    /// Checks what amplitude() takes, naming the parameter (the tool's fields, its depth against the string's length,
    /// one finite non-negative value per element, R in [-1, 1]).
    void check(const HydraulicOscillator& tool, const std::vector<double>& wall_friction, double sliding_speed,
               const std::vector<double>& surface_speed, double bit_reflection) const {
        constexpr const char* who = "AxialWave";
        validate_fields("HydraulicOscillator", tool, HydraulicOscillator::fields());
        if (!(tool.measured_depth <= length_)) {
            const std::string rule =
                "<= the string's length, " + std::to_string(length_) + " m (the tool cannot be below the bit)";
            detail::reject("HydraulicOscillator", "measured_depth", rule.c_str(), tool.measured_depth);
        }
        check_per_element(wall_friction, "wall_friction", false);
        check_per_element(surface_speed, "surface_speed", true);
        detail::require_non_negative(who, "sliding_speed", sliding_speed);
        if (!(bit_reflection >= -1.0 && bit_reflection <= 1.0))
            detail::reject(who, "bit_reflection", "in [-1, 1] (+1 a free bit, -1 a held one)", bit_reflection);
    }

private:
    struct Medium {
        const double* wall_friction;
        const double* surface_speed;  // nullptr: no rotation
        double sliding_speed;
    };

    void check_per_element(const std::vector<double>& values, const char* name, bool may_be_empty) const {
        if (may_be_empty && values.empty()) return;
        if (values.size() != elements())
            detail::reject("AxialWave", name, ("one value per element (" + std::to_string(elements()) + ")").c_str(),
                           static_cast<double>(values.size()));
        for (std::size_t e = 0; e < values.size(); ++e)
            if (!(std::isfinite(values[e]) && values[e] >= 0.0))
                detail::reject("AxialWave", (std::string(name) + "[" + std::to_string(e) + "]").c_str(),
                               "non-negative and finite", values[e]);
    }

    /// Velocity amplitude transmitted from element `from` into element `to`.
    double transmission(std::size_t from, std::size_t to) const {
        return 2.0 * impedance_[from] / (impedance_[from] + impedance_[to]);
    }

    /// The amplitude after a path of length ds in element e (header comment: exact without rotation, RK4 with it).
    double step(double a, double ds, std::size_t e, const Medium& m) const {
        if (!(ds > 0.0) || a == 0.0) return a;
        const double f = m.wall_friction[e], z = impedance_[e], v = m.sliding_speed;
        const double w = m.surface_speed ? m.surface_speed[e] : 0.0;
        if (w == 0.0) {
            if (!(a > v)) return 0.0;  // no reversal: undamped by Coulomb friction, ended by what is left out
            const double b = std::sqrt((a - v) * (a + v)) - 2.0 / pi * f / z * ds;
            return b > 0.0 ? std::sqrt(b * b + v * v) : 0.0;
        }
        const auto rate = [&](double amp) {
            return amp > 0.0 ? -f * cycle_mean_friction(v, amp, w).vibration_power / (z * amp) : 0.0;
        };
        // the explicit midpoint rule, sub-stepped so that each step decays the amplitude by at most 2 %
        const double first = rate(a);
        const double relative = std::abs(first) / a * ds;
        const auto substeps = static_cast<std::size_t>(std::clamp(std::ceil(relative / 0.02), 1.0, 1000.0));
        const double h = ds / static_cast<double>(substeps);
        for (std::size_t k = 0; k < substeps; ++k) {
            const double k1 = k == 0 ? first : rate(a);
            a = std::max(a + h * rate(std::max(a + 0.5 * h * k1, 0.0)), 0.0);
        }
        return a;
    }

    /// With a reflecting bit: between the tool and the bit the direct wave a_d and the reflected one a_r share the
    /// wall's dissipation by equivalent linearisation (header comment), solved by passes down and up until they
    /// agree; above the tool the two travel up together as one wave, attenuated as one.
    void standing_wave(const HydraulicOscillator& tool, const Medium& m, double reflection, std::size_t below,
                       std::size_t above, double source, std::vector<double>& out) const {
        const std::size_t n = elements();
        const double x_t = tool.measured_depth, omega = 2.0 * pi * tool.frequency;
        const double sign = reflection > 0.0 ? 1.0 : -1.0, v = m.sliding_speed;
        // the grid from the tool to the bit: every element middle and end, pieces of at most a 40th of a wavelength
        Grid g;
        g.x.assign(1, x_t);
        g.element.clear();
        g.down.assign(1, 1.0);
        g.up.assign(1, 1.0);
        g.mid.assign(n, npos);
        const auto add = [&](double y, std::size_t e, double crossing_down, double crossing_up) {
            const double piece = speed_[e] / tool.frequency / 40.0, from = g.x.back();
            const auto pieces = static_cast<std::size_t>(std::max(1.0, std::ceil((y - from) / piece)));
            for (std::size_t k = 1; k <= pieces; ++k) {
                g.x.push_back(k == pieces ? y : from + (y - from) * static_cast<double>(k) / static_cast<double>(pieces));
                g.element.push_back(e);
                g.down.push_back(k == pieces ? crossing_down : 1.0);
                g.up.push_back(k == pieces ? crossing_up : 1.0);
            }
        };
        if (x_t < length_) {
            for (std::size_t e = below; e < n; ++e) {
                const double mid = mid_depth(e);
                if (mid == x_t) g.mid[e] = 0;
                if (mid > g.x.back()) {
                    add(mid, e, 1.0, 1.0);
                    g.mid[e] = g.x.size() - 1;
                }
                const bool inner = e + 1 < n;
                add(node_[e + 1], e, inner ? transmission(e, e + 1) : 1.0, inner ? transmission(e + 1, e) : 1.0);
            }
        }
        const std::size_t last = g.x.size() - 1;
        g.phase.assign(last + 1, 0.0);  // 2 omega tau, tau the travel time to the bit
        for (std::size_t j = last; j-- > 0;)
            g.phase[j] = g.phase[j + 1] + 2.0 * omega * (g.x[j + 1] - g.x[j]) / speed_[g.element[j]];
        // d a / d s along the wave's travel: the share of the dissipation f D(A) that falls on it, (a^2 + a a_o s
        // cos psi) / A^2 of it, s the reflection's sign (sums to f D(A) over both waves)
        const auto rate = [&](double self, double other, double psi, std::size_t e) {
            if (!(self > 0.0)) return 0.0;
            const double cross = sign * self * other * std::cos(psi);
            const double a2 = self * self + other * other + 2.0 * cross;
            if (!(a2 > 0.0)) return 0.0;
            const double a = std::sqrt(a2), w = m.surface_speed ? m.surface_speed[e] : 0.0;
            const double dissipated = w == 0.0 ? (a > v ? 2.0 / pi * std::sqrt((a - v) * (a + v)) : 0.0)
                                               : cycle_mean_friction(v, a, w).vibration_power;
            return -m.wall_friction[e] * dissipated * (self * self + cross) / (a2 * impedance_[e] * self);
        };
        const auto ended = [&](double a, std::size_t e) {  // below the sliding speed without rotation: dropped
            const bool rotating = m.surface_speed && m.surface_speed[e] > 0.0;
            return a < 0.0 || (!rotating && !(a > v)) ? 0.0 : a;
        };
        // one explicit midpoint step of the wave `self` over piece j, the other wave linear across it
        const auto advance = [&](double a, const std::vector<double>& other, std::size_t j, std::size_t from,
                                 std::size_t to) {
            const std::size_t e = g.element[j];
            const double h = g.x[j + 1] - g.x[j];
            const double k1 = rate(a, other[from], g.phase[from], e);
            const double half = std::max(a + 0.5 * h * k1, 0.0);
            return ended(a + h * rate(half, 0.5 * (other[from] + other[to]), 0.5 * (g.phase[from] + g.phase[to]), e),
                         e);
        };
        std::vector<double>&ad = g.direct, &ar = g.reflected;
        ad.assign(last + 1, 0.0);
        ar.assign(last + 1, 0.0);
        for (std::size_t pass = 0; pass < 100; ++pass) {
            double change = 0.0;
            double a = source;  // down from the tool
            change = std::max(change, std::abs(ad[0] - a));
            ad[0] = a;
            for (std::size_t j = 0; j < last; ++j) {
                a = ad[j] == 0.0 && j > 0 ? 0.0 : advance(ad[j] * g.down[j], ar, j, j, j + 1);
                change = std::max(change, std::abs(ad[j + 1] - a));
                ad[j + 1] = a;
            }
            a = std::abs(reflection) * ad[last];  // and back up from the bit
            change = std::max(change, std::abs(ar[last] - a));
            ar[last] = a;
            for (std::size_t j = last; j-- > 0;) {
                a = ar[j + 1] == 0.0 ? 0.0 : advance(ar[j + 1] * g.up[j + 1], ad, j, j + 1, j);
                change = std::max(change, std::abs(ar[j] - a));
                ar[j] = a;
            }
            if (change <= 1e-9 * source) break;
        }
        for (std::size_t e = 0; e < n; ++e) {
            if (g.mid[e] == npos) continue;
            const std::size_t j = g.mid[e];
            const double sum = ad[j] * ad[j] + ar[j] * ar[j] + 2.0 * sign * ad[j] * ar[j] * std::cos(g.phase[j]);
            out[e] = std::sqrt(std::max(sum, 0.0));
        }
        // above the tool: the direct upward wave and the reflected one are one wave from there on
        const double merged =
            std::sqrt(std::max(source * source + ar[0] * ar[0] + 2.0 * sign * source * ar[0] * std::cos(g.phase[0]), 0.0));
        up_from_tool(merged, x_t, above, m, out);
    }

    /// A wave of amplitude a leaving the tool at x_t upwards through element `above` and the ones over it: its
    /// amplitude at each element's middle above x_t into out, attenuated and transmitted on the way.
    void up_from_tool(double a, double x_t, std::size_t above, const Medium& medium, std::vector<double>& out) const {
        if (!(x_t > 0.0)) return;
        double x = x_t;
        for (std::size_t e = above + 1; e-- > 0;) {
            if (e != above) a *= transmission(e + 1, e);
            const double mid = mid_depth(e);
            if (mid < x) {
                a = step(a, x - mid, e, medium);
                out[e] = a;
                x = mid;
            }
            a = step(a, x - node_[e], e, medium);
            x = node_[e];
        }
    }

    struct Grid {
        std::vector<double> x, down, up, phase, direct, reflected;  // down / up: transmission crossing x_j
        std::vector<std::size_t> element, mid;                      // element of piece j; grid index of a middle
    };
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);

    double length_ = 0.0;
    std::vector<double> node_, impedance_, speed_;
};

}  // namespace frictionsim
