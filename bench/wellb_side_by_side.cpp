// Aarsnes-Shor Well B on frictionsim's Moreau-Jean string, one run timed, its limit cycle summarised: the C++ side
// of bench/wellb_side_by_side.py, which alternates it with bench/reference/aarsnes_shor.c (the published explicit
// scheme in plain C) and frictionsim from Python. Not a Google Benchmark: one process per round, as the C program.
//
// Usage: wellb_side_by_side [--elements N] [--step H] [--t-end S] [--repeat R] [--trace FILE] [--entry E]
// prints one line of JSON with the same keys as aarsnes_shor.c: cpu_seconds is the best CPU time of R runs (the
// string, its survey lookups and the node bounds built once before, as a user builds a model once) through
// --entry simulate (default: frictionsim::simulate with Method::moreau_jean, outputs every 0.01 s, what Python's
// fs.simulate runs) or run (TorsionalString::simulate, the model's own loop); bit_peak / period the limit cycle's means over the cycles starting after 15 s (a cycle
// starts when the bit passes 5 rad/s after resting below 0.5 rad/s; outputs every 0.01 s), the motor torque's
// extremes and the mean fraction of nodes in A&S's 1.5 rad/s band over the same window.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>

#include <frictionsim/simulate.hpp>
#include <frictionsim/string/torsional_string.hpp>

namespace {

double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

[[noreturn]] void usage() {
    std::fprintf(stderr, "usage: wellb_side_by_side [--elements N] [--step H] [--t-end S] [--repeat R] [--trace FILE] "
                         "[--entry simulate|run]\n");
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace frictionsim;
    std::size_t elements = 1000;
    double step = 2e-3, t_end = 60.0;
    int repeat = 1;
    const char* trace = nullptr;
    bool through_simulate = true;
    for (int a = 1; a < argc; ++a) {
        if (a + 1 >= argc) usage();
        if (!std::strcmp(argv[a], "--elements")) elements = static_cast<std::size_t>(std::atol(argv[++a]));
        else if (!std::strcmp(argv[a], "--step")) step = std::atof(argv[++a]);
        else if (!std::strcmp(argv[a], "--t-end")) t_end = std::atof(argv[++a]);
        else if (!std::strcmp(argv[a], "--repeat")) repeat = std::atoi(argv[++a]);
        else if (!std::strcmp(argv[a], "--trace")) trace = argv[++a];
        else if (!std::strcmp(argv[a], "--entry")) {
            const char* e = argv[++a];
            if (std::strcmp(e, "simulate") && std::strcmp(e, "run")) usage();
            through_simulate = !std::strcmp(e, "simulate");
        }
        else usage();
    }
    if (repeat < 1) usage();
    // as the published code: collar polar moment with its extra pi, collar advected at the pipe's wave speed
    const WellBCase c = aarsnes_shor_well_b(CollarPolarMoment::as_published, CollarWaveSpeed::as_code);
    const TorsionalString string(c.string, c.params, elements, c.survey, c.contact_radius);
    TorsionalStringRunOptions o;
    o.t_end = t_end;
    o.step = step;
    o.slow_speed = 1.5;  // the stuck fraction counted in A&S's band, as the C program counts it
    SolverOptions so;
    so.method = Method::moreau_jean;
    so.step = step;
    for (long k = 0; k <= std::lround(t_end / 0.01); ++k) so.output_times.push_back(0.01 * static_cast<double>(k));
    TorsionalStringRun r;
    long steps = 0, solves = 0, switches = 0;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < repeat; ++k) {
        const double start = cpu_seconds();
        if (through_simulate) {
            const Result res = simulate(string, t_end, so);
            best = std::min(best, cpu_seconds() - start);
            r = TorsionalStringRun{};
            r.time = res.t;
            for (const char* name : {"bit_speed", "top_drive_speed", "motor_torque", "stuck_fraction"}) {
                const std::size_t c = res.column(name);
                std::vector<double>& out = name[0] == 'b'   ? r.bit_speed
                                           : name[0] == 't' ? r.top_drive_speed
                                           : name[0] == 'm' ? r.motor_torque
                                                            : r.stuck_fraction;
                for (std::size_t i = 0; i < res.t.size(); ++i) out.push_back(res.state(i, c));
            }
            steps = res.stats.steps;
            solves = res.stats.linear_solves;
            switches = res.stats.contact_switches;
        } else {
            r = string.simulate(o);
            best = std::min(best, cpu_seconds() - start);
            steps = r.statistics.steps;
            solves = r.statistics.solves;
            switches = r.statistics.contact_switches;
        }
    }

    double peak = 0.0, period = 0.0, tmax = -HUGE_VAL, tmin = HUGE_VAL, stuck = 0.0;
    int cycles = 0, window = 0;
    bool armed = true;
    long last = -1;
    for (std::size_t k = 0; k < r.time.size(); ++k) {
        if (r.bit_speed[k] < 0.5) armed = true;
        if (armed && r.bit_speed[k] > 5.0) {
            armed = false;
            if (last >= 0 && r.time[static_cast<std::size_t>(last)] >= 15.0) {
                peak += *std::max_element(r.bit_speed.begin() + last, r.bit_speed.begin() + static_cast<long>(k));
                period += r.time[k] - r.time[static_cast<std::size_t>(last)];
                ++cycles;
            }
            last = static_cast<long>(k);
        }
        if (r.time[k] >= 15.0) {
            tmax = std::max(tmax, r.motor_torque[k]);
            tmin = std::min(tmin, r.motor_torque[k]);
            stuck += r.stuck_fraction[k];
            ++window;
        }
    }
    if (trace) {
        std::FILE* f = std::fopen(trace, "w");
        if (!f) {
            std::fprintf(stderr, "wellb_side_by_side: cannot write %s\n", trace);
            return 1;
        }
        std::fprintf(f, "time_s,bit_speed_rad_s,top_drive_speed_rad_s,motor_torque_N_m,stuck_fraction\n");
        for (std::size_t k = 0; k < r.time.size(); ++k)
            std::fprintf(f, "%.6f,%.17g,%.17g,%.17g,%.17g\n", r.time[k], r.bit_speed[k], r.top_drive_speed[k],
                         r.motor_torque[k], r.stuck_fraction[k]);
        std::fclose(f);
    }
    std::printf("{\"elements\": %zu, \"step\": %.17g, \"t_end\": %.17g, \"cpu_seconds\": %.9g, \"bit_peak\": %.17g, "
                "\"period\": %.17g, \"cycles\": %d, \"max_motor_torque\": %.17g, \"min_motor_torque\": %.17g, "
                "\"stuck_fraction\": %.17g, \"steps\": %ld, \"solves\": %ld, \"contact_switches\": %ld, \"entry\": \"%s\"}\n",
                elements, step, t_end, best, cycles ? peak / cycles : 0.0, cycles ? period / cycles : 0.0, cycles,
                window ? tmax : 0.0, window ? tmin : 0.0, window ? stuck / window : 0.0, steps, solves, switches,
                through_simulate ? "simulate" : "run");
    return 0;
}
