/* separator.c: the free-fall separator (separator.h, docs/model.md §10): its table, the
   equation of motion with Schiller-Naumann drag, integrated by CVODE with the run's ends
   located as roots, and its state. */
#include "separator.h"

#include <cvode/cvode.h>
#include <float.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "byte_cursor.h"
#include "param_table.h"

static const tribo_param_info PARAMS[] = {
#define TRIBO_PARAMETER(...) TRIBO_PARAM_INFO(tribo_separator_scene, __VA_ARGS__),
#include "separator_quantities.def"
};
static const tribo_param_table_of TABLE = {PARAMS, sizeof PARAMS / sizeof PARAMS[0], NULL};

/* released is a switch: an integer in [0, 1] for the checks and messages */
static const tribo_param_info INPUTS[TRIBO_SEPARATOR_INPUT_COUNT] = {
#define TRIBO_BOOLEAN_INPUT(id_, name_, vr_, description_)                                        \
    [TRIBO_SEPARATOR_INPUT_##id_] = {.name = name_, .description = description_, .unit = "1",    \
                                     .vr = vr_, .type = TRIBO_TYPE_INTEGER, .min = 0, .max = 1,   \
                                     .min_inclusive = 1, .max_inclusive = 1, .start = 0,          \
                                     .variability = TRIBO_PARAM_TUNABLE},
#define TRIBO_INPUT(id_, ...) [TRIBO_SEPARATOR_INPUT_##id_] = TRIBO_INPUT_INFO(__VA_ARGS__),
#include "separator_quantities.def"
};

static const char *const QUANTITY_NAMES[TRIBO_SEPARATOR_Q_COUNT] = {
#define TRIBO_TIME(id, name, ...) [TRIBO_SEPARATOR_Q_##id] = name,
#define TRIBO_OUTPUT(id, name, ...) [TRIBO_SEPARATOR_Q_##id] = name,
#define TRIBO_CALCULATED(id, name, ...) [TRIBO_SEPARATOR_Q_##id] = name,
#include "separator_quantities.def"
};

enum { IX, IY, IZ, IVX, IVY, IVZ, N_STATE };
enum { ROOT_BINS, ROOT_PLUS_PLATE, ROOT_MINUS_PLATE, N_ROOTS };

struct tribo_separator {
    tribo_separator_scene scene;
    tribo_separator_derived d;
    double t;
    double inputs[TRIBO_SEPARATOR_INPUT_COUNT];
    int released;
    double t_release, q_per_m;
    double accel_x;   /* (q/m) E_x, from the release on */
    double y[N_STATE]; /* x, y, z, vx, vy, vz */
    int end;          /* tribo_separator_end */
    char error[512];

    SUNContext ctx;
    void *mem;
    N_Vector v;
    SUNMatrix jac;
    SUNLinearSolver ls;
};

/* ---- the table ------------------------------------------------------------------------- */

void tribo_separator_scene_defaults(tribo_separator_scene *s) { tribo_table_defaults(TABLE, s, sizeof *s); }

const tribo_param_info *tribo_separator_param_table(size_t *count)
{
    if (count)
        *count = TABLE.n;
    return PARAMS;
}

const tribo_param_info *tribo_separator_param_find(const char *name) { return tribo_table_find(TABLE, name); }

tribo_status tribo_separator_scene_set(tribo_separator_scene *s, const char *name, double value,
                                       char *msg, size_t msg_size)
{
    return tribo_table_set(TABLE, s, name, value, msg, msg_size);
}

tribo_status tribo_separator_scene_apply(tribo_separator_scene *s, const char *settings, char *msg,
                                         size_t msg_size)
{
    return tribo_table_apply(TABLE, s, settings, msg, msg_size);
}

const tribo_param_info *tribo_separator_input_table(size_t *count)
{
    if (count)
        *count = TRIBO_SEPARATOR_INPUT_COUNT;
    return INPUTS;
}

const char *tribo_separator_quantity_name(tribo_separator_quantity q)
{
    return (unsigned)q < TRIBO_SEPARATOR_Q_COUNT ? QUANTITY_NAMES[q] : NULL;
}

/* ---- what the parameters mean (model.md §10) -------------------------------------------- */

tribo_status tribo_separator_derive(const tribo_separator_scene *sc, tribo_separator_derived *d,
                                    char *msg, size_t msg_size)
{
    const tribo_status st = tribo_table_validate(TABLE, sc, msg, msg_size);
    if (st != TRIBO_OK)
        return st;
    if (!d) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "the derived numbers' struct is NULL");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    tribo_separator_derived r = {0};
    r.field = -sc->voltage / sc->gap;
    /* Choice (model.md §10 leaves it to the implementation): the 2D chute grain, an ellipse
       of semi-axes a and b = epsilon a, stands for the spheroid of semi-axes a, b, b (the
       body of revolution about its long axis whose sections through that axis are the
       ellipse; a sphere of radius a for epsilon = 1); d_e is the sphere of its volume. */
    r.diameter = 2.0 * sc->semi_major_axis * cbrt(sc->epsilon * sc->epsilon);
    r.area = M_PI * r.diameter * r.diameter / 4.0;
    r.mass = sc->density * M_PI * r.diameter * r.diameter * r.diameter / 6.0;
    /* r: the grain's largest half-size, whichever way it tumbles */
    r.half_size = sc->semi_major_axis;
    r.x_limit = sc->gap / 2.0 - r.half_size;
    /* (a viscosity so small that the time overflows, 5e-324 Pa.s, reads as the largest
       number: every value of the declared range gives a finite output) */
    r.relaxation_time = sc->air_viscosity > 0.0
                            ? fmin(r.mass / (3.0 * M_PI * sc->air_viscosity * r.diameter), DBL_MAX)
                            : 0.0;
    if (!(r.x_limit > 0.0)) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "semi_major_axis = %.9g m is invalid with gap = %.9g m: the grain must fit "
                     "between the plates, 2 semi_major_axis < gap", sc->semi_major_axis, sc->gap);
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    if (!(fabs(sc->x_entry) < r.x_limit)) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "x_entry = %.9g m is invalid: with gap = %.9g m and semi_major_axis = %.9g m "
                     "the valid range is -%.9g < x_entry < %.9g (gap/2 - semi_major_axis)",
                     sc->x_entry, sc->gap, sc->semi_major_axis, r.x_limit, r.x_limit);
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    *d = r;
    return TRIBO_OK;
}

/* ---- the equation of motion (model.md §10) ------------------------------------------------ */

void tribo_separator_drag(const tribo_separator_scene *sc, const tribo_separator_derived *d,
                          const double v[3], double out[3])
{
    if (!sc || !d || !v || !out)
        return;
    const double speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double rho = sc->air_density, mu = sc->air_viscosity;
    double k = 0.0; /* F_drag = m k v */
    if (speed > 0.0 && (rho > 0.0 || mu > 0.0)) {
        const double re = mu > 0.0 ? rho * speed * d->diameter / mu : INFINITY;
        if (re < 1000.0)
            /* 1/2 rho C_D A |v| with C_D = 24/Re (1 + 0.15 Re^0.687): Stokes' 3 pi mu d_e
               times the correction, finite as |v| -> 0 */
            k = 3.0 * M_PI * mu * d->diameter * (1.0 + 0.15 * pow(re, 0.687)) / d->mass;
        else
            k = 0.5 * rho * 0.44 * d->area * speed / d->mass;
    }
    for (int i = 0; i < 3; i++)
        out[i] = k * v[i];
}

static int rhs(sunrealtype t, N_Vector yv, N_Vector ydot, void *user)
{
    (void)t;
    const tribo_separator *s = user;
    const double *y = N_VGetArrayPointer(yv);
    double *dy = N_VGetArrayPointer(ydot), drag[3];
    tribo_separator_drag(&s->scene, &s->d, y + IVX, drag);
    dy[IX] = y[IVX];
    dy[IY] = y[IVY];
    dy[IZ] = y[IVZ];
    dy[IVX] = s->accel_x - drag[0];
    dy[IVY] = -drag[1];
    dy[IVZ] = -s->scene.gravity - drag[2];
    return 0;
}

/* The run's ends (model.md §10), each falling through zero: the bins, the plate at +w/2,
   the plate at -w/2. */
static int roots(sunrealtype t, N_Vector yv, sunrealtype *g, void *user)
{
    (void)t;
    const tribo_separator *s = user;
    const double *y = N_VGetArrayPointer(yv);
    g[ROOT_BINS] = y[IZ] + s->scene.height;
    g[ROOT_PLUS_PLATE] = s->d.x_limit - y[IX];
    g[ROOT_MINUS_PLATE] = y[IX] + s->d.x_limit;
    return 0;
}

static void error_handler(int code, const char *module, const char *function, char *msg, void *user)
{
    tribo_separator *s = user;
    snprintf(s->error, sizeof s->error, "%s %s (%d): %s", module, function, code, msg);
}

static void release_cvode(tribo_separator *s)
{
    if (s->mem)
        CVodeFree(&s->mem);
    if (s->ls)
        SUNLinSolFree(s->ls);
    if (s->jac)
        SUNMatDestroy(s->jac);
    if (s->v)
        N_VDestroy(s->v);
    if (s->ctx)
        SUNContext_Free(&s->ctx);
}

/* BDF with Newton on a dense difference-quotient Jacobian: small grains relax to their
   terminal velocity in far less than a flight (relaxation_time), a stiff problem. */
static int setup_cvode(tribo_separator *s)
{
    if (SUNContext_Create(NULL, &s->ctx) != 0)
        return 0;
    s->v = N_VNew_Serial(N_STATE, s->ctx);
    s->mem = CVodeCreate(CV_BDF, s->ctx);
    if (!s->v || !s->mem)
        return 0;
    N_VConst(0.0, s->v);
    const int rdir[N_ROOTS] = {-1, -1, -1};
    s->jac = SUNDenseMatrix(N_STATE, N_STATE, s->ctx);
    s->ls = s->jac ? SUNLinSol_Dense(s->v, s->jac, s->ctx) : NULL;
    return s->ls && CVodeSetErrHandlerFn(s->mem, error_handler, s) == CV_SUCCESS &&
           CVodeInit(s->mem, rhs, 0.0, s->v) == CV_SUCCESS &&
           CVodeSStolerances(s->mem, s->scene.rtol, s->scene.atol) == CV_SUCCESS &&
           CVodeSetUserData(s->mem, s) == CV_SUCCESS &&
           CVodeRootInit(s->mem, N_ROOTS, roots) == CV_SUCCESS &&
           CVodeSetRootDirection(s->mem, (int *)rdir) == CV_SUCCESS &&
           CVodeSetNoInactiveRootWarn(s->mem) == CV_SUCCESS &&
           CVodeSetMaxHnilWarns(s->mem, -1) == CV_SUCCESS &&
           CVodeSetLinearSolver(s->mem, s->ls, s->jac) == CV_SUCCESS;
}

/* The grain held at the entry. */
static void hold_at_entry(tribo_separator *s)
{
    memset(s->y, 0, sizeof s->y);
    s->y[IX] = s->scene.x_entry;
}

tribo_separator *tribo_separator_create(const tribo_separator_scene *scene, char *err, size_t err_size)
{
    tribo_separator_derived d;
    if (!scene) {
        if (err && err_size)
            snprintf(err, err_size, "scene is NULL");
        return NULL;
    }
    if (tribo_separator_derive(scene, &d, err, err_size) != TRIBO_OK)
        return NULL;
    tribo_separator *s = calloc(1, sizeof *s);
    if (!s) {
        if (err && err_size)
            snprintf(err, err_size, "out of memory");
        return NULL;
    }
    s->scene = *scene;
    s->d = d;
    hold_at_entry(s);
    if (!setup_cvode(s)) {
        if (err && err_size)
            snprintf(err, err_size, "CVODE could not be set up%s%s", s->error[0] ? ": " : "",
                     s->error);
        tribo_separator_free(s);
        return NULL;
    }
    return s;
}

void tribo_separator_free(tribo_separator *s)
{
    if (!s)
        return;
    release_cvode(s);
    free(s);
}

const tribo_separator_scene *tribo_separator_get_scene(const tribo_separator *s)
{
    return s ? &s->scene : NULL;
}

const tribo_separator_derived *tribo_separator_get_derived(const tribo_separator *s)
{
    return s ? &s->d : NULL;
}

const char *tribo_separator_last_error(const tribo_separator *s)
{
    return s ? s->error : "the instance is NULL";
}
tribo_separator_end tribo_separator_end_of(const tribo_separator *s)
{
    return s ? (tribo_separator_end)s->end : TRIBO_SEPARATOR_RUNNING;
}

/* Entry (model.md §10): the chute-frame velocity (u down-slope, v away from the chute) in
   the lab frame. Down-slope is cos(beta) horizontally and -sin(beta) vertically; the
   chute's normal sin(beta) horizontally and cos(beta) vertically. */
static void release(tribo_separator *s)
{
    const double beta = s->scene.tilt, u = s->inputs[TRIBO_SEPARATOR_INPUT_U_ENTRY],
                 v = s->inputs[TRIBO_SEPARATOR_INPUT_V_ENTRY];
    const double horizontal = u * cos(beta) + v * sin(beta), vertical = -u * sin(beta) + v * cos(beta);
    hold_at_entry(s);
    s->y[s->scene.chute_direction == TRIBO_SEPARATOR_ACROSS_GAP ? IVX : IVY] = horizontal;
    s->y[IVZ] = vertical;
    s->released = 1;
    s->t_release = s->t;
    s->q_per_m = s->inputs[TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS];
    s->accel_x = s->q_per_m * s->d.field;
}

tribo_status tribo_separator_set_inputs(tribo_separator *s, const double values[TRIBO_SEPARATOR_INPUT_COUNT])
{
    if (!s)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (!values) {
        snprintf(s->error, sizeof s->error, "the inputs' values are NULL");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    if (tribo_params_check(INPUTS, TRIBO_SEPARATOR_INPUT_COUNT, values, s->error,
                           sizeof s->error) != TRIBO_OK)
        return TRIBO_ERR_INVALID_ARGUMENT;
    memcpy(s->inputs, values, sizeof s->inputs);
    if (!s->released && !s->end && values[TRIBO_SEPARATOR_INPUT_RELEASED] != 0.0)
        release(s);
    return TRIBO_OK;
}

/* Where a run ends, on the end it reached exactly (CVODE locates the root to a rounding). */
static void finish(tribo_separator *s, const int found[N_ROOTS])
{
    if (found[ROOT_BINS]) {
        s->end = TRIBO_SEPARATOR_LANDED;
        s->y[IZ] = -s->scene.height;
    } else {
        s->end = TRIBO_SEPARATOR_CAUGHT;
        s->y[IX] = found[ROOT_PLUS_PLATE] ? s->d.x_limit : -s->d.x_limit;
    }
}

/* An advance over an interval too short for CVODE (model.md §10's motion over it): one
   Taylor step, exact to the rounding there, the ends checked at its end. */
static tribo_status advance_short(tribo_separator *s, double t)
{
    const double dt = t - s->t;
    double drag[3];
    tribo_separator_drag(&s->scene, &s->d, s->y + IVX, drag);
    const double a[3] = {s->accel_x - drag[0], -drag[1], -s->scene.gravity - drag[2]};
    for (int i = 0; i < 3; i++) {
        s->y[IX + i] += dt * (s->y[IVX + i] + 0.5 * dt * a[i]);
        s->y[IVX + i] += dt * a[i];
    }
    s->t = t;
    const int found[N_ROOTS] = {[ROOT_BINS] = s->y[IZ] + s->scene.height <= 0.0,
                                [ROOT_PLUS_PLATE] = s->d.x_limit - s->y[IX] <= 0.0,
                                [ROOT_MINUS_PLATE] = s->y[IX] + s->d.x_limit <= 0.0};
    if (found[ROOT_BINS] || found[ROOT_PLUS_PLATE] || found[ROOT_MINUS_PLATE]) {
        finish(s, found);
        return TRIBO_ENDED;
    }
    return TRIBO_OK;
}

static tribo_status check_outputs(tribo_separator *s);

/* The motion to t (tribo_separator_advance, before the outputs are checked). */
static tribo_status advance_motion(tribo_separator *s, double t)
{
    if (!isfinite(t) || t < s->t || t > TRIBO_TIME_MAX) {
        snprintf(s->error, sizeof s->error,
                 "advance to t = %.17g s is invalid: the valid range is %.17g <= t <= %g (the time "
                 "reached to TRIBO_TIME_MAX)", t, s->t, TRIBO_TIME_MAX);
        return TRIBO_ERR_TIME;
    }
    if (s->end)
        return TRIBO_ENDED;
    if (!s->released || t == s->t) {
        s->t = t;
        return TRIBO_OK;
    }
    /* CVODE refuses an end within 2 u max(|t|, |t_end|) of the time (u the rounding unit),
       and one whose product with its first step underflows: an importer's communication
       step may be either */
    if (t - s->t < 4.0 * DBL_EPSILON * fmax(fabs(s->t), fabs(t)) || t - s->t < 1e-140)
        return advance_short(s, t);
    double *nv = N_VGetArrayPointer(s->v);
    memcpy(nv, s->y, sizeof s->y);
    if (CVodeReInit(s->mem, s->t, s->v) != CV_SUCCESS || CVodeSetStopTime(s->mem, t) != CV_SUCCESS)
        return TRIBO_ERR_INTEGRATOR;
    for (int steps = 0;;) {
        sunrealtype reached = s->t;
        const int flag = CVode(s->mem, t, s->v, &reached, CV_ONE_STEP);
        if (flag < 0) {
            char cvode_says[sizeof s->error / 2], *name = CVodeGetReturnFlagName(flag);
            memcpy(cvode_says, s->error, sizeof cvode_says - 1);
            cvode_says[sizeof cvode_says - 1] = '\0';
            snprintf(s->error, sizeof s->error, "CVODE failed at t = %.17g s: %.40s (%s)",
                     (double)reached, name ? name : "?", cvode_says);
            free(name);
            return TRIBO_ERR_INTEGRATOR;
        }
        for (int i = 0; i < N_STATE; i++)
            if (!isfinite(nv[i])) {
                snprintf(s->error, sizeof s->error, "the motion is not finite at t = %.17g s",
                         (double)reached);
                return TRIBO_ERR_INTEGRATOR;
            }
        memcpy(s->y, nv, sizeof s->y);
        if (flag == CV_ROOT_RETURN) {
            int found[N_ROOTS];
            CVodeGetRootInfo(s->mem, found);
            s->t = reached;
            finish(s, found);
            return TRIBO_ENDED;
        }
        if (flag == CV_TSTOP_RETURN || reached >= t) {
            s->t = t;
            return TRIBO_OK;
        }
        s->t = reached;
        if (++steps >= s->scene.work_limit) {
            snprintf(s->error, sizeof s->error,
                     "the work limit (%d CVODE steps) stopped the advance at t = %.17g s",
                     s->scene.work_limit, s->t);
            return TRIBO_INCOMPLETE;
        }
    }
}

tribo_status tribo_separator_advance(tribo_separator *s, double t)
{
    if (!s)
        return TRIBO_ERR_INVALID_ARGUMENT;
    const tribo_status st = advance_motion(s, t);
    if (st != TRIBO_OK && st != TRIBO_ENDED && st != TRIBO_INCOMPLETE)
        return st;
    const tribo_status checked = check_outputs(s);
    return checked != TRIBO_OK ? checked : st;
}

/* ---- outputs ------------------------------------------------------------------------------ */

/* Every output a number after an advance, or the advance fails and says which is not (no
   value of the declared ranges makes one: a guard for the contract, like the chute's). */
static tribo_status check_outputs(tribo_separator *s)
{
    for (int q = 0; q < TRIBO_SEPARATOR_Q_COUNT; q++) {
        const double v = tribo_separator_get(s, (tribo_separator_quantity)q);
        if (!isfinite(v)) {
            snprintf(s->error, sizeof s->error, "%s = %g at t = %.17g s is not a finite number",
                     QUANTITY_NAMES[q], v, s->t);
            return TRIBO_ERR_INTEGRATOR;
        }
    }
    return TRIBO_OK;
}

double tribo_separator_reynolds(const tribo_separator *s)
{
    if (!s)
        return NAN;
    const double speed = sqrt(s->y[IVX] * s->y[IVX] + s->y[IVY] * s->y[IVY] + s->y[IVZ] * s->y[IVZ]);
    if (!(s->scene.air_viscosity > 0.0))
        return 0.0; /* no viscosity: Re is not a number the model uses */
    /* (beyond the largest number, with a viscosity of ~1e-300 Pa.s, the drag is Newton's
       anyway: Re reads as the largest number) */
    return fmin(s->scene.air_density * speed * s->d.diameter / s->scene.air_viscosity, DBL_MAX);
}

int tribo_separator_bin_of(const tribo_separator_scene *sc, double x)
{
    if (!sc)
        return 0;
    const double k = floor((x + sc->gap / 2.0) / sc->gap * sc->n_bins);
    return k < 0 ? 1 : k >= sc->n_bins ? sc->n_bins : (int)k + 1;
}

int tribo_separator_bin(const tribo_separator *s)
{
    return s && s->end == TRIBO_SEPARATOR_LANDED ? tribo_separator_bin_of(&s->scene, s->y[IX]) : 0;
}

double tribo_separator_calculated(const tribo_separator_derived *d, tribo_separator_quantity q)
{
    if (!d)
        return NAN;
    switch (q) {
#define TRIBO_CALCULATED(id, name, vr, unit, variability, description, value)                     \
    case TRIBO_SEPARATOR_Q_##id:                                                                 \
        return (value);
#include "separator_quantities.def"
    default: return 0.0;
    }
}

double tribo_separator_get(const tribo_separator *s, tribo_separator_quantity q)
{
    if (!s)
        return NAN;
    const tribo_separator_derived *d = &s->d;
    switch (q) {
#define TRIBO_TIME(id, name, vr, unit, description, value)                                       \
    case TRIBO_SEPARATOR_Q_##id:                                                                 \
        return (value);
#define TRIBO_OUTPUT(id, name, type, vr, unit, description, value)                               \
    case TRIBO_SEPARATOR_Q_##id:                                                                 \
        return (double)(value);
#define TRIBO_CALCULATED(id, name, vr, unit, variability, description, value)                     \
    case TRIBO_SEPARATOR_Q_##id:                                                                 \
        return (value);
#include "separator_quantities.def"
    default: return NAN;
    }
}

/* ---- the state ------------------------------------------------------------------------------ */

static const char MAGIC[8] = "TRIBOSEP";
enum { STATE_VERSION = 1 };

size_t tribo_separator_state_size(const tribo_separator *s)
{
    (void)s;
    /* magic, version, the parameters, t, the inputs, released, t_release, q/m, the motion,
       the end */
    return sizeof MAGIC + 8 * (1 + TABLE.n + 1 + TRIBO_SEPARATOR_INPUT_COUNT + 3 + N_STATE + 1);
}

tribo_status tribo_separator_state_save(const tribo_separator *s, void *buffer, size_t size)
{
    if (!s || !buffer || size != tribo_separator_state_size(s))
        return TRIBO_ERR_INVALID_ARGUMENT;
    tribo_writer w = {buffer};
    tribo_write_bytes(&w, MAGIC, sizeof MAGIC);
    tribo_write_int(&w, STATE_VERSION);
    for (size_t i = 0; i < TABLE.n; i++)
        tribo_write_double(&w, tribo_param_read(&s->scene, &PARAMS[i]));
    tribo_write_double(&w, s->t);
    for (int i = 0; i < TRIBO_SEPARATOR_INPUT_COUNT; i++)
        tribo_write_double(&w, s->inputs[i]);
    tribo_write_int(&w, s->released);
    tribo_write_double(&w, s->t_release);
    tribo_write_double(&w, s->q_per_m);
    for (int i = 0; i < N_STATE; i++)
        tribo_write_double(&w, s->y[i]);
    tribo_write_int(&w, s->end);
    return TRIBO_OK;
}

static tribo_status refuse(tribo_separator *s, const char *why)
{
    snprintf(s->error, sizeof s->error, "the state is refused: %s", why);
    return TRIBO_ERR_STATE;
}

tribo_status tribo_separator_state_load(tribo_separator *s, const void *buffer, size_t size)
{
    if (!s)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (!buffer || size != tribo_separator_state_size(s))
        return refuse(s, "its size is not this model's");
    tribo_reader r = tribo_reader_of(buffer, size);
    char magic[sizeof MAGIC];
    tribo_read_bytes(&r, magic, sizeof magic);
    if (memcmp(magic, MAGIC, sizeof MAGIC) != 0 || tribo_read_int(&r) != STATE_VERSION)
        return refuse(s, "not a separator's state of this version");
    for (size_t i = 0; i < TABLE.n; i++)
        if (tribo_read_double(&r) != tribo_param_read(&s->scene, &PARAMS[i]))
            return refuse(s, PARAMS[i].name); /* another scene's */
    tribo_separator n = *s; /* the loaded values, checked before s changes */
    n.t = tribo_read_double(&r);
    for (int i = 0; i < TRIBO_SEPARATOR_INPUT_COUNT; i++)
        n.inputs[i] = tribo_read_double(&r);
    const int64_t released = tribo_read_int(&r);
    n.t_release = tribo_read_double(&r);
    n.q_per_m = tribo_read_double(&r);
    for (int i = 0; i < N_STATE; i++)
        n.y[i] = tribo_read_double(&r);
    const int64_t end = tribo_read_int(&r);
    if (r.overrun)
        return refuse(s, "it is truncated");
    if (!isfinite(n.t) || n.t < 0.0 || n.t > TRIBO_TIME_MAX)
        return refuse(s, "its time is out of range");
    char msg[256];
    if (tribo_params_check(INPUTS, TRIBO_SEPARATOR_INPUT_COUNT, n.inputs, msg, sizeof msg) !=
        TRIBO_OK)
        return refuse(s, msg);
    if ((released != 0 && released != 1) || end < TRIBO_SEPARATOR_RUNNING ||
        end > TRIBO_SEPARATOR_CAUGHT || (end && !released))
        return refuse(s, "its release or end is not one the model has");
    for (int i = 0; i < N_STATE; i++)
        if (!isfinite(n.y[i]))
            return refuse(s, "its motion is not finite");
    n.released = (int)released;
    n.end = (int)end;
    if (n.released) {
        const tribo_param_info *qm = &INPUTS[TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS];
        if (!isfinite(n.t_release) || n.t_release < 0.0 || n.t_release > n.t ||
            tribo_param_check(qm, n.q_per_m, msg, sizeof msg) != TRIBO_OK)
            return refuse(s, "its release time or charge is out of range");
        /* within the separator: the ends are where the run stops */
        if (n.y[IZ] < -n.scene.height || fabs(n.y[IX]) > n.d.x_limit)
            return refuse(s, "the grain lies outside the separator");
        n.accel_x = n.q_per_m * n.d.field;
    } else {
        tribo_separator held = n;
        hold_at_entry(&held);
        if (memcmp(held.y, n.y, sizeof n.y) != 0 || n.t_release != 0.0 || n.q_per_m != 0.0)
            return refuse(s, "a grain not released is not at the entry");
        n.accel_x = 0.0;
    }
    s->t = n.t;
    memcpy(s->inputs, n.inputs, sizeof s->inputs);
    s->released = n.released;
    s->t_release = n.t_release;
    s->q_per_m = n.q_per_m;
    s->accel_x = n.accel_x;
    memcpy(s->y, n.y, sizeof s->y);
    s->end = n.end;
    return TRIBO_OK;
}
