/*
 * cvode_reference.c - the yardstick of what SUNDIALS CVODE itself costs.
 *
 * A hand-written C99 program that integrates the same equations as two of frictionsim's rigs directly on
 * CVODE, with no frictionsim code: whatever frictionsim (C++ or Python) spends beyond this program's time is
 * the engine's overhead, and whatever it saves is the engine's method choice. bench/compare.py runs it.
 *
 *   axial_dahl    paper 000's axial vibrating-sliding rig with Dahl friction, as frictionsim's
 *                 AxialRig<Dahl>(AxialRigParams{}, Dahl(0.41, 4e4)) (include/frictionsim/rigs/axial_rig.hpp,
 *                 friction/dahl.hpp). States y = (x, v, z, I):
 *                     x' = v
 *                     v' = (k_d (v_d t - x) - k_t z) / m
 *                     z' = v_r (1 - (k_t / (mu F_N)) s z),   v_r = v - u0 w cos(w t),   s = sgn(v_r)
 *                     I' = k_t z                             (friction impulse)
 *                 from rest at t = 0 to t = 2 s. mean_friction = (I(2) - I(2 - 10/f)) / (10/f), the mean
 *                 friction force over the last 10 whole vibration cycles (F_df of paper 000).
 *                 z' has a kink at v_r = 0. By default s = sgn(v_r) is evaluated inside the right-hand side
 *                 and CVODE steps across the kink. With --events the kink is located as a root of s v_r
 *                 (falling) and CVODE is restarted there with s := -s, the treatment frictionsim gives it.
 *
 *   spring_block  Coulomb stick-slip, as frictionsim's AxialRig<Coulomb>(spring_block_params(0.5, 200.0,
 *                 0.05), Coulomb(0.4, 0.6)) (rigs/reference_setups.hpp, contact/switching.hpp): a block
 *                 of m = 0.5 kg pulled through a spring k = 200 N/m whose end moves at v_p = 0.05 m/s,
 *                 N = m g, mu_k = 0.4, mu_s = 0.6. States y = (x, v, I), spring force F_s = k (v_p t - x):
 *                     slip (mode +1 / -1): F = mu_k N mode        root: mode v falling to 0 -> stick if
 *                                                                   |F_s| <= mu_s N, else slip sgn(F_s);
 *                                                                   v := 0 exactly either way
 *                     stick (mode 0):      F = F_s (v = v' = 0)    roots: mu_s N - F_s, mu_s N + F_s falling
 *                                                                   -> slip in the direction of F_s
 *                     x' = v,  v' = (F_s - F) / m,  I' = F
 *                 from rest in stick to t = 20 s, restarted exactly (CVodeReInit) at every switch (events are
 *                 always on; --events is accepted and changes nothing). mean_friction = I(20) / 20,
 *                 final_position = x(20).
 *
 * Methods: --method adams (default): Adams-Moulton with fixed-point iteration, CVODE's choice for a
 * non-stiff problem; --method bdf: BDF with Newton iteration and the dense direct linear solver, the
 * Jacobian by CVODE's difference quotients (as frictionsim's rigs do) or, with --jacobian analytic, by hand.
 *
 * Usage:
 *   cvode_reference --scenario axial_dahl|spring_block --rtol R --atol A
 *                   [--method adams|bdf] [--jacobian dq|analytic] [--repeat N] [--events]
 * prints one line of JSON:
 *   {"scenario":..., "method":..., "rtol":R, "atol":A, "seconds_per_run":..., "steps":...,
 *    "rhs_evaluations":..., "jacobian_evaluations":..., "events":..., "mean_friction":..., "final_position":...}
 * seconds_per_run is the best wall time (CLOCK_MONOTONIC) of N full simulations (default 20), each one
 * creating and freeing its SUNContext, vectors, solvers and CVODE memory as a frictionsim simulation does.
 * steps, rhs_evaluations (including the difference-quotient Jacobian's), jacobian_evaluations and events
 * (roots handled) are summed over the restarts of one simulation. Bad arguments or a CVODE failure: a
 * message on stderr and exit status 1 (2 for bad arguments).
 *
 * Builds against SUNDIALS 6.4 (Debian bookworm) and 7.x: the one API difference used here is
 * SUNContext_Create's communicator argument. The time measures the SUNDIALS build as much as CVODE's
 * algorithm: Debian bookworm's libsundials 6.4.1+dfsg1-3 is compiled without optimisation (-O0 code), and
 * the same program on an optimised SUNDIALS 7 build takes the same steps in about a quarter of the time.
 */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <sundials/sundials_config.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#define PROGRAM "cvode_reference"
static const double pi = 3.14159265358979323846;

/* ------------------------------------------------------------------------------------------------------ */
/* Command line                                                                                            */
/* ------------------------------------------------------------------------------------------------------ */

typedef enum { AXIAL_DAHL, SPRING_BLOCK } Scenario;

typedef struct {
    Scenario scenario;
    int bdf;               /* 0: Adams + fixed point, 1: BDF + Newton + dense LU */
    int analytic_jacobian; /* BDF only: 1 analytic, 0 difference quotients */
    int events;            /* axial_dahl: locate the kink at v_r = 0 and restart there */
    double rtol, atol;
    int repeat;
} Options;

static void usage(FILE* out) {
    fprintf(out,
            "usage: " PROGRAM " --scenario axial_dahl|spring_block --rtol R --atol A\n"
            "                       [--method adams|bdf] [--jacobian dq|analytic] [--repeat N] [--events]\n"
            "Integrates one of frictionsim's rigs directly on SUNDIALS CVODE and prints one line of JSON.\n");
}

static void bad_argument(const char* message, const char* value) {
    fprintf(stderr, PROGRAM ": %s%s%s\n", message, value ? ": " : "", value ? value : "");
    usage(stderr);
    exit(2);
}

/* A positive finite number, the whole string. */
static double parse_positive(const char* name, const char* text) {
    char* end = NULL;
    const double value = strtod(text, &end);
    if (end == text || *end != '\0' || !(value > 0.0) || !isfinite(value)) {
        fprintf(stderr, PROGRAM ": %s must be a positive finite number (got '%s')\n", name, text);
        exit(2);
    }
    return value;
}

static Options parse_options(int argc, char** argv) {
    Options o;
    int have_scenario = 0, have_rtol = 0, have_atol = 0, have_jacobian = 0, i;
    memset(&o, 0, sizeof o);
    o.repeat = 20;
    for (i = 1; i < argc; ++i) {
        const char* arg = argv[i];
        const char* value = NULL;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            exit(0);
        }
        if (strcmp(arg, "--events") == 0) {
            o.events = 1;
            continue;
        }
        if (strcmp(arg, "--scenario") && strcmp(arg, "--rtol") && strcmp(arg, "--atol") &&
            strcmp(arg, "--method") && strcmp(arg, "--jacobian") && strcmp(arg, "--repeat"))
            bad_argument("unknown argument", arg);
        if (i + 1 >= argc) bad_argument("missing value after", arg);
        value = argv[++i];
        if (strcmp(arg, "--scenario") == 0) {
            if (strcmp(value, "axial_dahl") == 0) o.scenario = AXIAL_DAHL;
            else if (strcmp(value, "spring_block") == 0) o.scenario = SPRING_BLOCK;
            else bad_argument("--scenario must be axial_dahl or spring_block", value);
            have_scenario = 1;
        } else if (strcmp(arg, "--method") == 0) {
            if (strcmp(value, "adams") == 0) o.bdf = 0;
            else if (strcmp(value, "bdf") == 0) o.bdf = 1;
            else bad_argument("--method must be adams or bdf", value);
        } else if (strcmp(arg, "--jacobian") == 0) {
            if (strcmp(value, "dq") == 0) o.analytic_jacobian = 0;
            else if (strcmp(value, "analytic") == 0) o.analytic_jacobian = 1;
            else bad_argument("--jacobian must be dq or analytic", value);
            have_jacobian = 1;
        } else if (strcmp(arg, "--rtol") == 0) {
            o.rtol = parse_positive("--rtol", value);
            if (o.rtol >= 1.0) bad_argument("--rtol must be < 1", value);
            have_rtol = 1;
        } else if (strcmp(arg, "--atol") == 0) {
            o.atol = parse_positive("--atol", value);
            have_atol = 1;
        } else { /* --repeat */
            char* end = NULL;
            const long n = strtol(value, &end, 10);
            if (end == value || *end != '\0' || n < 1 || n > 1000000)
                bad_argument("--repeat must be an integer in [1, 1000000]", value);
            o.repeat = (int)n;
        }
    }
    if (!have_scenario) bad_argument("--scenario is required", NULL);
    if (!have_rtol) bad_argument("--rtol is required", NULL);
    if (!have_atol) bad_argument("--atol is required", NULL);
    if (have_jacobian && !o.bdf) bad_argument("--jacobian applies to --method bdf only", NULL);
    return o;
}

/* ------------------------------------------------------------------------------------------------------ */
/* CVODE plumbing: every return flag checked, counters banked across restarts                              */
/* ------------------------------------------------------------------------------------------------------ */

static void die(const char* what) {
    fprintf(stderr, PROGRAM ": %s\n", what);
    exit(1);
}

/* CVODE functions return a flag < 0 on failure (CVODE's own error handler has already printed details). */
static void check(int flag, const char* call) {
    if (flag < 0) {
        char* name = CVodeGetReturnFlagName(flag);
        fprintf(stderr, PROGRAM ": %s failed with %s (%d)\n", call, name ? name : "?", flag);
        free(name);
        exit(1);
    }
}

/* SUNDIALS constructors return NULL on failure. */
static void* made(void* handle, const char* what) {
    if (!handle) {
        fprintf(stderr, PROGRAM ": could not create %s\n", what);
        exit(1);
    }
    return handle;
}

typedef struct {
    long steps, rhs_evaluations, jacobian_evaluations, events;
} Counters;

typedef struct {
    SUNContext context;
    N_Vector y;
    SUNMatrix matrix;              /* BDF only */
    SUNLinearSolver linear;        /* BDF only */
    SUNNonlinearSolver fixed_point; /* Adams only */
    void* cvode;
    int bdf;
    Counters banked; /* counts of the segments before the last (Re)Init: CVodeReInit zeroes CVODE's */
} Solver;

/* Creates everything and calls CVodeInit at (t0, y0). The caller adds root functions. */
static void solver_create(Solver* s, const Options* o, int n, const double* y0, double t0, double t_stop,
                          CVRhsFn rhs, CVLsJacFn jacobian, void* user_data) {
    int i;
    memset(s, 0, sizeof *s);
    s->bdf = o->bdf;
#if SUNDIALS_VERSION_MAJOR >= 7
    if (SUNContext_Create(SUN_COMM_NULL, &s->context) != 0) die("SUNContext_Create failed");
#else
    if (SUNContext_Create(NULL, &s->context) != 0) die("SUNContext_Create failed");
#endif
    s->y = (N_Vector)made(N_VNew_Serial((sunindextype)n, s->context), "the state vector");
    for (i = 0; i < n; ++i) NV_Ith_S(s->y, i) = y0[i];
    s->cvode = made(CVodeCreate(o->bdf ? CV_BDF : CV_ADAMS, s->context), "the CVODE memory");
    check(CVodeInit(s->cvode, rhs, t0, s->y), "CVodeInit");
    check(CVodeSetUserData(s->cvode, user_data), "CVodeSetUserData");
    check(CVodeSStolerances(s->cvode, o->rtol, o->atol), "CVodeSStolerances");
    check(CVodeSetMaxNumSteps(s->cvode, 10000000L), "CVodeSetMaxNumSteps"); /* per CVode call; default 500 */
    check(CVodeSetStopTime(s->cvode, t_stop), "CVodeSetStopTime");
    if (o->bdf) {
        s->matrix = (SUNMatrix)made(SUNDenseMatrix((sunindextype)n, (sunindextype)n, s->context), "the matrix");
        s->linear = (SUNLinearSolver)made(SUNLinSol_Dense(s->y, s->matrix, s->context), "SUNLinSol_Dense");
        check(CVodeSetLinearSolver(s->cvode, s->linear, s->matrix), "CVodeSetLinearSolver");
        if (o->analytic_jacobian) check(CVodeSetJacFn(s->cvode, jacobian), "CVodeSetJacFn");
    } else {
        /* CVodeCreate attaches a Newton solver by default, even for Adams: replace it by fixed point. */
        s->fixed_point = (SUNNonlinearSolver)made(SUNNonlinSol_FixedPoint(s->y, 0, s->context),
                                                  "SUNNonlinSol_FixedPoint");
        check(CVodeSetNonlinearSolver(s->cvode, s->fixed_point), "CVodeSetNonlinearSolver");
    }
}

/* One root function set for the whole run; every guard fires only when falling through zero. */
static void solver_add_roots(Solver* s, int count, CVRootFn guards) {
    int directions[2] = {-1, -1};
    if (count > 2) die("solver_add_roots: at most 2 root functions");
    check(CVodeRootInit(s->cvode, count, guards), "CVodeRootInit");
    check(CVodeSetRootDirection(s->cvode, directions), "CVodeSetRootDirection");
    /* After a restart on a switching surface a guard is exactly zero: expected, not worth a warning. */
    check(CVodeSetNoInactiveRootWarn(s->cvode), "CVodeSetNoInactiveRootWarn");
}

static Counters solver_counters(const Solver* s) {
    Counters c = s->banked;
    long value = 0;
    check(CVodeGetNumSteps(s->cvode, &value), "CVodeGetNumSteps");
    c.steps += value;
    check(CVodeGetNumRhsEvals(s->cvode, &value), "CVodeGetNumRhsEvals");
    c.rhs_evaluations += value;
    if (s->bdf) {
        check(CVodeGetNumLinRhsEvals(s->cvode, &value), "CVodeGetNumLinRhsEvals"); /* DQ Jacobian's */
        c.rhs_evaluations += value;
        check(CVodeGetNumJacEvals(s->cvode, &value), "CVodeGetNumJacEvals");
        c.jacobian_evaluations += value;
    }
    return c;
}

/* Exact restart at (t, y): CVODE forgets its history (and zeroes its counters, so bank them first). */
static void solver_restart(Solver* s, double t, double t_stop) {
    s->banked = solver_counters(s);
    ++s->banked.events;
    check(CVodeReInit(s->cvode, t, s->y), "CVodeReInit");
    check(CVodeSetStopTime(s->cvode, t_stop), "CVodeSetStopTime");
}

static void solver_free(Solver* s) {
    CVodeFree(&s->cvode);
    if (s->fixed_point) SUNNonlinSolFree(s->fixed_point);
    if (s->linear) SUNLinSolFree(s->linear);
    if (s->matrix) SUNMatDestroy(s->matrix);
    N_VDestroy(s->y);
    SUNContext_Free(&s->context);
}

/* Switch handler: given the time and the state at a root (writable) and which guards fired, set the new mode. */
typedef void (*SwitchFn)(double t, double* y, const int* fired, void* user_data);

/* Advances to tout (CV_NORMAL: CVODE steps past tout, up to the stop time, and interpolates y(tout)),
 * stopping at every root to switch the mode and restart. On return s->y holds y(tout). */
static void solver_advance(Solver* s, double tout, double t_stop, SwitchFn on_switch, void* user_data) {
    sunrealtype t = 0.0;
    for (;;) {
        const int flag = CVode(s->cvode, tout, s->y, &t, CV_NORMAL);
        check(flag, "CVode");
        if (flag == CV_ROOT_RETURN) {
            int fired[2] = {0, 0};
            check(CVodeGetRootInfo(s->cvode, fired), "CVodeGetRootInfo");
            on_switch(t, N_VGetArrayPointer(s->y), fired, user_data);
            solver_restart(s, t, t_stop);
            continue;
        }
        if (t < tout) die("CVode returned before tout without a root"); /* cannot happen; be sure */
        return;
    }
}

/* ------------------------------------------------------------------------------------------------------ */
/* Scenario 1: axial rig with Dahl friction (frictionsim's AxialRig<Dahl> with AxialRigParams{} defaults)  */
/* ------------------------------------------------------------------------------------------------------ */

typedef struct {
    double m, k_d, v_d, u0, w, F_N, mu, k_t;
    double c;   /* k_t / (mu F_N), 1/m */
    int branch; /* with --events: s = sgn(v_r) held between roots; 0: s = sgn(v_r) evaluated in the rhs */
} AxialDahl;

enum { AD_X, AD_V, AD_Z, AD_I, AD_STATES };

static AxialDahl axial_dahl_params(void) {
    AxialDahl p;
    p.m = 0.2;      /* kg */
    p.k_d = 2e4;    /* N/m */
    p.v_d = 1e-3;   /* m/s */
    p.u0 = 5e-3;    /* m */
    p.w = 2.0 * pi * 17.0; /* rad/s, f = 17 Hz */
    p.F_N = 90.0;   /* N */
    p.mu = 0.41;
    p.k_t = 4e4;    /* N/m */
    p.c = p.k_t / (p.mu * p.F_N);
    p.branch = 0;
    return p;
}

static double sign_of(double v) { return (double)((v > 0.0) - (v < 0.0)); }

static int axial_dahl_rhs(sunrealtype t, N_Vector y_vector, N_Vector dy_vector, void* data) {
    const AxialDahl* p = (const AxialDahl*)data;
    const double* y = N_VGetArrayPointer(y_vector);
    double* dy = N_VGetArrayPointer(dy_vector);
    const double v_r = y[AD_V] - p->u0 * p->w * cos(p->w * t);
    const double s = p->branch != 0 ? (double)p->branch : sign_of(v_r);
    const double friction = p->k_t * y[AD_Z];
    dy[AD_X] = y[AD_V];
    dy[AD_V] = (p->k_d * (p->v_d * t - y[AD_X]) - friction) / p->m;
    dy[AD_Z] = v_r * (1.0 - p->c * s * y[AD_Z]);
    dy[AD_I] = friction;
    return 0;
}

/* CVODE zeroes J before the call. s is piecewise constant, so d(z')/dv = 1 - c s z, d(z')/dz = -c s v_r. */
static int axial_dahl_jacobian(sunrealtype t, N_Vector y_vector, N_Vector f, SUNMatrix J, void* data,
                               N_Vector tmp1, N_Vector tmp2, N_Vector tmp3) {
    const AxialDahl* p = (const AxialDahl*)data;
    const double* y = N_VGetArrayPointer(y_vector);
    const double v_r = y[AD_V] - p->u0 * p->w * cos(p->w * t);
    const double s = p->branch != 0 ? (double)p->branch : sign_of(v_r);
    (void)f, (void)tmp1, (void)tmp2, (void)tmp3;
    SM_ELEMENT_D(J, AD_X, AD_V) = 1.0;
    SM_ELEMENT_D(J, AD_V, AD_X) = -p->k_d / p->m;
    SM_ELEMENT_D(J, AD_V, AD_Z) = -p->k_t / p->m;
    SM_ELEMENT_D(J, AD_Z, AD_V) = 1.0 - p->c * s * y[AD_Z];
    SM_ELEMENT_D(J, AD_Z, AD_Z) = -p->c * s * v_r;
    SM_ELEMENT_D(J, AD_I, AD_Z) = p->k_t;
    return 0;
}

/* s v_r falls through zero when the relative velocity reverses. */
static int axial_dahl_guard(sunrealtype t, N_Vector y_vector, sunrealtype* g, void* data) {
    const AxialDahl* p = (const AxialDahl*)data;
    const double* y = N_VGetArrayPointer(y_vector);
    g[0] = p->branch * (y[AD_V] - p->u0 * p->w * cos(p->w * t));
    return 0;
}

static void axial_dahl_switch(double t, double* y, const int* fired, void* data) {
    AxialDahl* p = (AxialDahl*)data;
    (void)t, (void)y, (void)fired;
    p->branch = -p->branch; /* z is continuous: nothing else changes */
}

static void run_axial_dahl(const Options* o, Counters* counters, double* mean_friction, double* position) {
    const double t_end = 2.0, window = 10.0 / 17.0; /* the last 10 whole cycles */
    double y0[AD_STATES] = {0.0, 0.0, 0.0, 0.0};    /* from rest, spring relaxed, no deflection */
    double impulse_at_window_start;
    AxialDahl p = axial_dahl_params();
    Solver s;
    if (o->events) {
        const double v_r0 = y0[AD_V] - p.u0 * p.w; /* -u0 w < 0: the surface moves forward at t = 0 */
        p.branch = v_r0 > 0.0 ? 1 : -1;
    }
    solver_create(&s, o, AD_STATES, y0, 0.0, t_end, axial_dahl_rhs, axial_dahl_jacobian, &p);
    if (o->events) solver_add_roots(&s, 1, axial_dahl_guard);
    solver_advance(&s, t_end - window, t_end, axial_dahl_switch, &p);
    impulse_at_window_start = NV_Ith_S(s.y, AD_I);
    solver_advance(&s, t_end, t_end, axial_dahl_switch, &p);
    *mean_friction = (NV_Ith_S(s.y, AD_I) - impulse_at_window_start) / window;
    *position = NV_Ith_S(s.y, AD_X);
    *counters = solver_counters(&s);
    solver_free(&s);
}

/* ------------------------------------------------------------------------------------------------------ */
/* Scenario 2: Coulomb spring-block stick-slip (frictionsim's AxialRig<Coulomb>, spring_block_params)      */
/* ------------------------------------------------------------------------------------------------------ */

typedef struct {
    double m, k, v_p, N, mu_k, mu_s;
    int mode; /* +1 slip forward, -1 slip backward, 0 stick */
} SpringBlock;

enum { SB_X, SB_V, SB_I, SB_STATES };

static SpringBlock spring_block_params(void) {
    SpringBlock p;
    p.m = 0.5;         /* kg */
    p.k = 200.0;       /* N/m */
    p.v_p = 0.05;      /* m/s */
    p.N = p.m * 9.81;  /* N */
    p.mu_k = 0.4;
    p.mu_s = 0.6;
    p.mode = 0;
    return p;
}

static double spring_force(const SpringBlock* p, double t, const double* y) { return p->k * (p->v_p * t - y[SB_X]); }

/* In stick the friction carries the spring force, clamped to the static limit as frictionsim does: the guards
 * end stick at |F_s| = mu_s N, but CVODE's trial states before the root is located can lie beyond it. */
static double spring_block_friction(const SpringBlock* p, double spring) {
    const double limit = p->mu_s * p->N;
    if (p->mode != 0) return p->mode * p->mu_k * p->N;
    return spring < -limit ? -limit : spring > limit ? limit : spring;
}

static int spring_block_rhs(sunrealtype t, N_Vector y_vector, N_Vector dy_vector, void* data) {
    const SpringBlock* p = (const SpringBlock*)data;
    const double* y = N_VGetArrayPointer(y_vector);
    double* dy = N_VGetArrayPointer(dy_vector);
    const double spring = spring_force(p, t, y);
    const double friction = spring_block_friction(p, spring);
    dy[SB_X] = y[SB_V];
    dy[SB_V] = (spring - friction) / p->m;
    dy[SB_I] = friction;
    return 0;
}

/* The derivative of the rhs as written. In stick the clamp matters: CVODE's trial states past the break-away
 * (before the root is located) have |F_s| > mu_s N, where the friction is constant and the block accelerates. */
static int spring_block_jacobian(sunrealtype t, N_Vector y_vector, N_Vector f, SUNMatrix J, void* data,
                                 N_Vector tmp1, N_Vector tmp2, N_Vector tmp3) {
    const SpringBlock* p = (const SpringBlock*)data;
    const double* y = N_VGetArrayPointer(y_vector);
    (void)f, (void)tmp1, (void)tmp2, (void)tmp3;
    SM_ELEMENT_D(J, SB_X, SB_V) = 1.0;
    if (p->mode == 0 && fabs(spring_force(p, t, y)) <= p->mu_s * p->N)
        SM_ELEMENT_D(J, SB_I, SB_X) = -p->k;     /* stick: friction = spring force, v' = 0 */
    else
        SM_ELEMENT_D(J, SB_V, SB_X) = -p->k / p->m; /* slip (or clamped): constant friction */
    return 0;
}

static int spring_block_guards(sunrealtype t, N_Vector y_vector, sunrealtype* g, void* data) {
    const SpringBlock* p = (const SpringBlock*)data;
    const double* y = N_VGetArrayPointer(y_vector);
    if (p->mode == 0) {
        const double spring = spring_force(p, t, y);
        g[0] = p->mu_s * p->N - spring; /* breaks away forward */
        g[1] = p->mu_s * p->N + spring; /* breaks away backward */
    } else {
        g[0] = p->mode * y[SB_V]; /* the slip velocity reaches zero */
        g[1] = 1.0;               /* unused in slip */
    }
    return 0;
}

static void spring_block_switch(double t, double* y, const int* fired, void* data) {
    SpringBlock* p = (SpringBlock*)data;
    if (p->mode == 0) {
        p->mode = fired[0] != 0 ? 1 : -1;
    } else {
        const double spring = spring_force(p, t, y);
        y[SB_V] = 0.0; /* exactly at rest: the new mode's guards start from the switching surface */
        p->mode = fabs(spring) <= p->mu_s * p->N ? 0 : (spring > 0.0 ? 1 : -1);
    }
}

static void run_spring_block(const Options* o, Counters* counters, double* mean_friction, double* position) {
    const double t_end = 20.0;
    double y0[SB_STATES] = {0.0, 0.0, 0.0}; /* at rest, spring relaxed: stick */
    SpringBlock p = spring_block_params();
    Solver s;
    solver_create(&s, o, SB_STATES, y0, 0.0, t_end, spring_block_rhs, spring_block_jacobian, &p);
    solver_add_roots(&s, 2, spring_block_guards);
    solver_advance(&s, t_end, t_end, spring_block_switch, &p);
    *mean_friction = NV_Ith_S(s.y, SB_I) / t_end;
    *position = NV_Ith_S(s.y, SB_X);
    *counters = solver_counters(&s);
    solver_free(&s);
}

/* ------------------------------------------------------------------------------------------------------ */
/* Timing and output                                                                                       */
/* ------------------------------------------------------------------------------------------------------ */

static double now_seconds(void) {
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) die("clock_gettime(CLOCK_MONOTONIC) failed");
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Shortest of %.15g / %.16g / %.17g that reads back as the same double: valid JSON for finite values. */
static void print_number(double value) {
    char text[40];
    int digits;
    if (!isfinite(value)) die("non-finite result");
    for (digits = 15; digits <= 17; ++digits) {
        sprintf(text, "%.*g", digits, value);
        if (strtod(text, NULL) == value) break;
    }
    fputs(text, stdout);
}

int main(int argc, char** argv) {
    const Options o = parse_options(argc, argv);
    Counters counters;
    double mean_friction = 0.0, position = 0.0, best = INFINITY;
    int run;
    memset(&counters, 0, sizeof counters);
    for (run = 0; run < o.repeat; ++run) {
        const double start = now_seconds();
        if (o.scenario == AXIAL_DAHL) run_axial_dahl(&o, &counters, &mean_friction, &position);
        else run_spring_block(&o, &counters, &mean_friction, &position);
        {
            const double elapsed = now_seconds() - start;
            if (elapsed < best) best = elapsed;
        }
    }
    printf("{\"scenario\":\"%s\",\"method\":\"%s\",\"rtol\":", o.scenario == AXIAL_DAHL ? "axial_dahl" : "spring_block",
           o.bdf ? "bdf" : "adams");
    print_number(o.rtol);
    fputs(",\"atol\":", stdout);
    print_number(o.atol);
    fputs(",\"seconds_per_run\":", stdout);
    print_number(best);
    printf(",\"steps\":%ld,\"rhs_evaluations\":%ld,\"jacobian_evaluations\":%ld,\"events\":%ld,\"mean_friction\":",
           counters.steps, counters.rhs_evaluations, counters.jacobian_evaluations, counters.events);
    print_number(mean_friction);
    fputs(",\"final_position\":", stdout);
    print_number(position);
    fputs("}\n", stdout);
    return fflush(stdout) == 0 ? 0 : 1;
}
