/*
 * aarsnes_shor.c - the published explicit scheme of Aarsnes and Shor (2018), Well B, in plain C99: the yardstick
 * that frictionsim's Moreau-Jean string (include/frictionsim/string/torsional_string.hpp) is timed against.
 *
 * Aarsnes, U. J. F. and Shor, R. J. (2018), "Torsional vibrations with bit off bottom: modeling, characterization
 * and field data validation", J. Pet. Sci. Eng. 163, 712-721. Their MATLAB code (Open Drilling Project,
 * "Aarsnes-and-Shor-Torsional-Model", MIT licence; MAIN.m, parameters_WellB.m, torsionalWaveStep.m) is the
 * algorithm written here from its description; no line of it is copied. What is reproduced, as published:
 *
 *   grid       Pt cells of 2.5 m at 2500 m (908 pipe, 92 collar for Pt = 1000), the pipe and the 230 m BHA each
 *              carrying the Riemann invariants alpha = omega + c f, beta = omega - c f (f the strain, c =
 *              sqrt(G_p / rho) in both: the code advects the collar's invariants with the pipe's wave speed);
 *   step       the PI's sample dt = 0.01 s split into n = ceil(dt / (0.99 min(dx) / c)) sub-steps (CFL; n = 12
 *              at 1000 cells), first-order upwind for each family;
 *   friction   per cell the Coulomb torque per metre F_c = mu sin(inc) g rho A r_o (inc interpolated on the
 *              survey 0 / 0 / 60 / 60 deg at 0 / 500 / 1600 / 4000 m at linspace(0, L, P) as the code does):
 *              inside the stick band |omega| < 1.5 rad/s the source that stops the cell within the sub-step,
 *              clipped to +-F_c; outside, f_rat F_c against the motion (mu = 0.3, f_rat = 0.65);
 *   damping    the code's source dt k_t (alpha + beta), applied as dt times it (k_t = 50): a rate 2 k_t dt_sub;
 *   BHA        the collar polar moment with the code's extra factor pi (as published);
 *   boundaries top: alpha_0 = 2 omega_TD - beta_1; pipe-collar: impedance ratio Z = J_c G_c / (J_p G_p);
 *              bit off bottom (no torque);
 *   top drive  I_TD omega_TD' = tau_m - J_p G_p f(0), explicit per sub-step; tau_m = 38e3 (omega_SP - omega_TD)
 *              + 100e3 int e, sampled every 0.01 s with the set-point filter omega_SP += (40 rpm - omega_SP) dt
 *              / 1 s, as MAIN.m orders them (filter, torque, integral).
 *
 * Usage: aarsnes_shor [--t-end S] [--cells N] [--repeat R] [--trace FILE]
 * prints one line of JSON:
 *   {"cells":..., "pipe_cells":..., "collar_cells":..., "substeps":..., "t_end":..., "cpu_seconds":...,
 *    "bit_peak":..., "period":..., "cycles":..., "max_motor_torque":..., "min_motor_torque":...,
 *    "stuck_fraction":...}
 * cpu_seconds: the best CPU time (CLOCK_PROCESS_CPUTIME_ID) of R runs from rest (default 1). bit_peak [rad/s] and
 * period [s]: the limit cycle's means over the cycles starting after 15 s (a cycle starts when the bit passes
 * 5 rad/s after resting below 0.5 rad/s; samples every 0.01 s), as tests/aarsnes_shor.test.cpp and
 * bench/wellb_side_by_side.cpp count them; the motor torque's extremes [N m] and the mean fraction of cells in the
 * stick band over the same window. --trace writes time_s, bit_speed_rad_s, top_drive_speed_rad_s,
 * motor_torque_N_m, stuck_fraction every 0.01 s (the columns of tests/data/aarsnes_shor_2018/).
 */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846

/* One uniform segment (pipe or collar) of the characteristic scheme. */
typedef struct {
    int cells;
    double length, dx, polar, shear, density_inertia; /* J, G, rho J */
    double *alpha, *beta, *threshold;                  /* threshold: F_c per cell [N m/m] */
} Segment;

typedef struct {
    Segment pipe, collar;
    double c, dt, dt_sub, kt, stick_band, kinetic_ratio, top_drive_inertia;
    int substeps;
} Well;

/* inc [rad] on the survey, linear in between (parameters_WellB.m: interp1 on 0 / 500 / 1600 / 4000 m). */
static double inclination(double md) {
    static const double depth[4] = {0.0, 500.0, 1600.0, 4000.0}, deg[4] = {0.0, 0.0, 60.0, 60.0};
    int i;
    if (md <= depth[0]) return deg[0] * PI / 180.0;
    for (i = 1; i < 4; ++i)
        if (md <= depth[i]) return (deg[i - 1] + (md - depth[i - 1]) / (depth[i] - depth[i - 1]) * (deg[i] - deg[i - 1])) * PI / 180.0;
    return deg[3] * PI / 180.0;
}

static void segment_init(Segment* s, int cells, double top, double length, double area, double polar, double shear,
                         double radius, double rho, double mu) {
    int i;
    s->cells = cells;
    s->length = length;
    s->dx = length / cells;
    s->polar = polar;
    s->shear = shear;
    s->density_inertia = rho * polar;
    s->alpha = calloc((size_t)cells, sizeof(double));
    s->beta = calloc((size_t)cells, sizeof(double));
    s->threshold = malloc((size_t)cells * sizeof(double));
    if (!s->alpha || !s->beta || !s->threshold) {
        fprintf(stderr, "aarsnes_shor: out of memory\n");
        exit(1);
    }
    for (i = 0; i < cells; ++i) { /* the code's stations: linspace(0, L, P), not the cell centres */
        const double x = top + (cells > 1 ? length * i / (cells - 1) : 0.0);
        s->threshold[i] = 9.81 * sin(inclination(x)) * rho * area * radius * mu;
    }
}

static void segment_free(Segment* s) {
    free(s->alpha);
    free(s->beta);
    free(s->threshold);
}

static void well_init(Well* w, int total_cells) {
    static const double lc[4] = {48.700, 114.800, 56.700, 38.880};
    static const double od[4] = {0.150473, 0.187322, 0.209550, 0.247280};
    static const double id[4] = {0.096207, 0.098912, 0.071438, 0.123391};
    const double md = 2500.0, collar_length = 230.0, pipe_length = md - collar_length, rho = 7850.0, mu = 0.3;
    const double ro = 0.146529 / 2.0, ri = 0.123024 / 2.0, gp = 61e9, gc = 67e9;
    double sum = 0.0, ac = 0.0, jc = 0.0, rc = 0.0, dt_cfl;
    int i, pipe_cells;
    for (i = 0; i < 4; ++i) {
        sum += lc[i];
        ac += lc[i] * PI * ((od[i] / 2) * (od[i] / 2) - (id[i] / 2) * (id[i] / 2));
        jc += lc[i] * PI * (pow(od[i], 4) - pow(id[i], 4)) / 32.0;
        rc += lc[i] * od[i] / 2.0;
    }
    ac /= sum;
    jc = PI * jc / sum; /* as published: the extra pi */
    rc /= sum;
    pipe_cells = (int)floor(total_cells * pipe_length / md + 0.5);
    segment_init(&w->pipe, pipe_cells, 0.0, pipe_length, PI * (ro * ro - ri * ri), PI / 2.0 * (pow(ro, 4) - pow(ri, 4)),
                 gp, ro, rho, mu);
    segment_init(&w->collar, total_cells - pipe_cells, pipe_length, collar_length, ac, jc, gc, rc, rho, mu);
    w->c = sqrt(gp / rho);
    w->dt = 0.01;
    dt_cfl = 0.99 * fmin(w->pipe.dx, w->collar.dx) / w->c;
    w->substeps = (int)ceil(w->dt / dt_cfl);
    w->dt_sub = w->dt / w->substeps;
    w->kt = 50.0;
    w->stick_band = 1.5;
    w->kinetic_ratio = 0.65;
    w->top_drive_inertia = 2900.0;
}

/* One sub-step of one segment, in place: alpha reads its upwind neighbour (above; `alpha_top` at the first cell),
 * beta its (below; `beta_bottom` at the last), both the values at the sub-step's start. */
static void segment_step(const Well* w, Segment* s, double alpha_top, double beta_bottom) {
    const double dt = w->dt_sub, courant = w->c * dt / s->dx, rate = w->c / s->dx;
    const double to_torque = s->density_inertia, from_torque = 1.0 / s->density_inertia;
    double* a = s->alpha;
    double* b = s->beta;
    const double* thr = s->threshold;
    double above = alpha_top;
    int i;
    for (i = 0; i < s->cells; ++i) {
        const double ai = a[i], bi = b[i], below = i + 1 < s->cells ? b[i + 1] : beta_bottom;
        const double omega = 0.5 * (ai + bi), viscous = dt * w->kt * (ai + bi);
        const double da = ai - above, db = below - bi;
        double friction;
        if (fabs(omega) < w->stick_band) { /* the torque per metre that stops the cell in this sub-step, clipped */
            const double stop = 0.5 * (ai / dt - rate * da + bi / dt + rate * db - 2.0 * viscous) * to_torque;
            friction = stop > thr[i] ? thr[i] : stop < -thr[i] ? -thr[i] : stop;
        } else {
            friction = (omega > 0.0 ? 1.0 : -1.0) * w->kinetic_ratio * thr[i];
        }
        {
            const double source = viscous + friction * from_torque;
            a[i] = ai - courant * da - dt * source;
            b[i] = bi + courant * db - dt * source;
        }
        above = ai;
    }
}

typedef struct {
    double *time, *bit, *top, *torque, *stuck;
    int samples;
} Trace;

/* From rest to t_end; the trace every 0.01 s (its rows 0..samples-1). */
static void run(Well* w, double t_end, Trace* tr) {
    Segment* p = &w->pipe;
    Segment* c = &w->collar;
    const double setpoint_final = 40.0 / 60.0 * 2.0 * PI, z = c->polar * c->shear / (p->polar * p->shear);
    const double top_torque = p->polar * p->shear / (2.0 * w->c);
    const int samples = (int)floor(t_end / w->dt + 0.5);
    double setpoint = 0.0, integral = 0.0, omega_td = 0.0;
    int k, j, i;
    memset(p->alpha, 0, (size_t)p->cells * sizeof(double));
    memset(p->beta, 0, (size_t)p->cells * sizeof(double));
    memset(c->alpha, 0, (size_t)c->cells * sizeof(double));
    memset(c->beta, 0, (size_t)c->cells * sizeof(double));
    for (k = 0; k <= samples; ++k) {
        double tau;
        setpoint += (setpoint_final - setpoint) * w->dt / 1.0;
        tau = (setpoint - omega_td) * 38e3 + integral * 100e3;
        integral += w->dt * (setpoint - omega_td);
        if (tr && k < tr->samples) {
            int stuck = 0;
            for (i = 0; i < p->cells; ++i) stuck += fabs(0.5 * (p->alpha[i] + p->beta[i])) < w->stick_band;
            for (i = 0; i < c->cells; ++i) stuck += fabs(0.5 * (c->alpha[i] + c->beta[i])) < w->stick_band;
            tr->time[k] = k * w->dt;
            tr->bit[k] = 0.5 * (c->alpha[c->cells - 1] + c->beta[c->cells - 1]);
            tr->top[k] = omega_td;
            tr->torque[k] = tau;
            tr->stuck[k] = (double)stuck / (p->cells + c->cells);
        }
        if (k == samples) break;
        for (j = 0; j < w->substeps; ++j) {
            const double pa_end = p->alpha[p->cells - 1], cb_top = c->beta[0];
            const double pipe_alpha_top = 2.0 * omega_td - p->beta[0];
            const double pipe_beta_bottom = ((1.0 - z) * pa_end + 2.0 * z * cb_top) / (1.0 + z);
            const double collar_alpha_top = (2.0 * pa_end - (1.0 - z) * cb_top) / (1.0 + z);
            const double collar_beta_bottom = c->alpha[c->cells - 1]; /* bit off bottom: no torque */
            segment_step(w, p, pipe_alpha_top, pipe_beta_bottom);
            segment_step(w, c, collar_alpha_top, collar_beta_bottom);
            omega_td += w->dt_sub / w->top_drive_inertia * (tau - top_torque * (p->alpha[0] - p->beta[0]));
        }
    }
}

static double cpu_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void usage(void) {
    fprintf(stderr, "usage: aarsnes_shor [--t-end S] [--cells N] [--repeat R] [--trace FILE]\n");
    exit(2);
}

int main(int argc, char** argv) {
    double t_end = 60.0, best = HUGE_VAL, peak = 0.0, period = 0.0, tmax = -HUGE_VAL, tmin = HUGE_VAL, stuck = 0.0;
    int cells = 1000, repeat = 1, a, r, k, cycles = 0, armed = 1, last = -1, window = 0;
    const char* trace_file = NULL;
    Well w;
    Trace tr;
    for (a = 1; a < argc; ++a) {
        if (a + 1 >= argc) usage();
        if (!strcmp(argv[a], "--t-end")) t_end = atof(argv[++a]);
        else if (!strcmp(argv[a], "--cells")) cells = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--repeat")) repeat = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--trace")) trace_file = argv[++a];
        else usage();
    }
    if (!(t_end > 0.0) || cells < 4 || repeat < 1) usage();
    well_init(&w, cells);
    tr.samples = (int)floor(t_end / w.dt + 0.5) + 1;
    tr.time = malloc((size_t)tr.samples * 5 * sizeof(double));
    if (!tr.time) return 1;
    tr.bit = tr.time + tr.samples;
    tr.top = tr.bit + tr.samples;
    tr.torque = tr.top + tr.samples;
    tr.stuck = tr.torque + tr.samples;
    for (r = 0; r < repeat; ++r) {
        const double start = cpu_seconds();
        run(&w, t_end, &tr);
        best = fmin(best, cpu_seconds() - start);
    }
    for (k = 0; k < tr.samples; ++k) { /* the limit cycle after 15 s */
        if (tr.bit[k] < 0.5) armed = 1;
        if (armed && tr.bit[k] > 5.0) {
            armed = 0;
            if (last >= 0 && tr.time[last] >= 15.0) {
                double top = tr.bit[last];
                int i;
                for (i = last; i < k; ++i) top = fmax(top, tr.bit[i]);
                peak += top;
                period += tr.time[k] - tr.time[last];
                ++cycles;
            }
            last = k;
        }
        if (tr.time[k] >= 15.0) {
            tmax = fmax(tmax, tr.torque[k]);
            tmin = fmin(tmin, tr.torque[k]);
            stuck += tr.stuck[k];
            ++window;
        }
    }
    if (trace_file) {
        FILE* f = fopen(trace_file, "w");
        if (!f) {
            fprintf(stderr, "aarsnes_shor: cannot write %s\n", trace_file);
            return 1;
        }
        fprintf(f, "time_s,bit_speed_rad_s,top_drive_speed_rad_s,motor_torque_N_m,stuck_fraction\n");
        for (k = 0; k < tr.samples; ++k)
            fprintf(f, "%.2f,%.17g,%.17g,%.17g,%.17g\n", tr.time[k], tr.bit[k], tr.top[k], tr.torque[k], tr.stuck[k]);
        fclose(f);
    }
    printf("{\"cells\": %d, \"pipe_cells\": %d, \"collar_cells\": %d, \"substeps\": %d, \"t_end\": %.17g, "
           "\"cpu_seconds\": %.9g, \"bit_peak\": %.17g, \"period\": %.17g, \"cycles\": %d, "
           "\"max_motor_torque\": %.17g, \"min_motor_torque\": %.17g, \"stuck_fraction\": %.17g}\n",
           cells, w.pipe.cells, w.collar.cells, w.substeps, t_end, best, cycles ? peak / cycles : 0.0,
           cycles ? period / cycles : 0.0, cycles, window ? tmax : 0.0, window ? tmin : 0.0,
           window ? stuck / window : 0.0);
    free(tr.time);
    segment_free(&w.pipe);
    segment_free(&w.collar);
    return 0;
}
