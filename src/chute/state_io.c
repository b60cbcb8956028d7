/* state_io.c: the whole state of an instance as plain bytes, out and back in.
 *
 * Layout (native byte order, doubles and 64-bit integers):
 *   magic "TRIBOST1", version, total size,
 *   every scene parameter (in the order of the parameter table),
 *   the external force, the output time, the work counters, how the run has ended (not,
 *   at the chute's exit, at the first lift-off, or at rest: tribo_end_reason),
 *   the committed point (with the charge models' quadratures and global states), for each
 *   selected charge model its committed per-segment charges, their running sum and the
 *   charge its breakdown limit took (each value and compensation) and, where the grain keeps
 *   bands (model.md §8c), its band densities with their charge and loss the same way; then
 *   the bands' widths and hulls with the charged area, then their limits and the gas's state
 *   (model.md §8e: the contact episode, its region's radius and limit, its run of bands, the
 *   grain's charge per model); the integrator's own bytes.
 * The output point is not stored: it is recomputed from the committed point exactly as
 * the advance that made it did, so a loaded instance continues bit-identically.
 *
 * A load checks everything before it changes the instance, and puts the instance back as it
 * was if the integrator refuses its part (which it can only check by replaying it).
 */
#include "model.h"

#include "byte_cursor.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char MAGIC[8] = {'T', 'R', 'I', 'B', 'O', 'S', 'T', '1'};
enum { STATE_VERSION = 9 };

/* Fields of a point, in order; the contact evaluation is stored with it because some
   integrators (phases of the force law) cannot recompute it from y alone. */
#define CONTACT_DOUBLES 10
#define POINT_INTS 6

static size_t point_size(const tribo_model *m)
{
    const size_t doubles = 1 + (size_t)m->n_state + 1 + (size_t)m->charging.n_globals +
                           CONTACT_DOUBLES + 2 + TRIBO_MOTION_CLASSES;
    return doubles * sizeof(double) + POINT_INTS * sizeof(int64_t);
}

static void put_point(tribo_writer *w, const tribo_model *m, const tribo_point *p)
{
    tribo_write_double(w, p->t);
    for (int i = 0; i < m->n_state; i++)
        tribo_write_double(w, p->y[i]);
    tribo_write_double(w, p->contact_time);
    for (int i = 0; i < m->charging.n_globals; i++)
        tribo_write_double(w, p->charge_globals[i]);
    const tribo_contact_eval *c = &p->contact;
    const double cd[CONTACT_DOUBLES] = {c->pose.sin_phi, c->pose.cos_phi, c->pose.h, c->pose.cx,
                                        c->delta_y, c->vs, c->sign_v, c->psi_n, c->psi_t, c->limit};
    for (int i = 0; i < CONTACT_DOUBLES; i++)
        tribo_write_double(w, cd[i]);
    tribo_write_int(w, c->in_contact);
    tribo_write_int(w, p->slipping);
    const tribo_motion *mo = &p->motion;
    tribo_write_double(w, mo->contact);
    tribo_write_double(w, mo->spin);
    for (int i = 0; i < TRIBO_MOTION_CLASSES; i++)
        tribo_write_double(w, mo->class_time[i]);
    tribo_write_int(w, mo->current);
    tribo_write_int(w, mo->outside_assumptions);
    tribo_write_int(w, mo->impacts);
    tribo_write_int(w, mo->touchdowns);
}

/* A flag or a small index saved in 64 bits; one that an int cannot hold reads as -1 (which
   the checks refuse). */
static int read_small(tribo_reader *r)
{
    const int64_t v = tribo_read_int(r);
    return v >= -1 && v <= 1000 ? (int)v : -1;
}

static void get_point(tribo_reader *r, const tribo_model *m, tribo_point *p)
{
    memset(p, 0, sizeof *p);
    p->t = tribo_read_double(r);
    for (int i = 0; i < m->n_state; i++)
        p->y[i] = tribo_read_double(r);
    p->contact_time = tribo_read_double(r);
    for (int i = 0; i < m->charging.n_globals; i++)
        p->charge_globals[i] = tribo_read_double(r);
    tribo_contact_eval *c = &p->contact;
    double *cd[CONTACT_DOUBLES] = {&c->pose.sin_phi, &c->pose.cos_phi, &c->pose.h, &c->pose.cx,
                                   &c->delta_y, &c->vs, &c->sign_v, &c->psi_n, &c->psi_t, &c->limit};
    for (int i = 0; i < CONTACT_DOUBLES; i++)
        *cd[i] = tribo_read_double(r);
    c->in_contact = read_small(r);
    p->slipping = read_small(r);
    tribo_motion *mo = &p->motion;
    mo->contact = tribo_read_double(r);
    mo->spin = tribo_read_double(r);
    for (int i = 0; i < TRIBO_MOTION_CLASSES; i++)
        mo->class_time[i] = tribo_read_double(r);
    mo->current = read_small(r);
    mo->outside_assumptions = read_small(r);
    mo->impacts = tribo_read_int(r);
    mo->touchdowns = tribo_read_int(r);
}

static size_t header_size(void) { return sizeof MAGIC + 2 * sizeof(int64_t); }

/* The values of the committed per-segment charges, bands and their totals, over every
   selected model, and the bands' geometry. */
static size_t charge_count(const tribo_model *m)
{
    const tribo_charging *c = &m->charging;
    size_t n = 0;
    for (int i = 0; i < c->n_models; i++)
        if (c->slot[i].segments)
            n += ((size_t)c->n + 4) * (c->keep_bands ? 2 : 1);
    if (c->any_selected && c->keep_bands)
        n += 4 * (size_t)c->n + 2 + 5 + (size_t)c->n_models;
    return n;
}

static void write_compensated(tribo_writer *w, const tribo_compensated *x)
{
    tribo_write_double(w, x->sum);
    tribo_write_double(w, x->c);
}

static tribo_compensated read_compensated(tribo_reader *r)
{
    tribo_compensated x;
    x.sum = tribo_read_double(r);
    x.c = tribo_read_double(r);
    return x;
}

size_t tribo_state_size(const tribo_model *m)
{
    if (!m)
        return 0;
    size_t n_params;
    tribo_param_table(&n_params);
    return header_size() + n_params * sizeof(double) + 3 * sizeof(double) /* F_T, F_N, t_out */
           + 7 * sizeof(int64_t)                                            /* stats, ended */
           + point_size(m) + charge_count(m) * sizeof(double) +
           m->integrator->state_size(m->integrator_data);
}

tribo_status tribo_state_save(const tribo_model *m, void *buffer, size_t size)
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    const size_t need = tribo_state_size(m);
    if (!buffer || size < need)
        return tribo_fail((tribo_model *)m, TRIBO_ERR_INVALID_ARGUMENT,
                          "state buffer of %zu bytes given, %zu needed", size, need);
    tribo_writer w = {buffer};
    tribo_write_bytes(&w, MAGIC, sizeof MAGIC);
    tribo_write_int(&w, STATE_VERSION);
    tribo_write_int(&w, (int64_t)need);
    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    for (size_t i = 0; i < n_params; i++)
        tribo_write_double(&w, tribo_param_read(&m->scene, &params[i]));
    tribo_write_double(&w, m->dyn.F_T);
    tribo_write_double(&w, m->dyn.F_N);
    tribo_write_double(&w, m->out.t);
    const tribo_stats *s = &m->stats;
    const long long counters[6] = {s->steps,    s->rhs_evals, s->events,
                                   s->restarts, s->substeps,  s->assumption_warnings};
    for (int i = 0; i < 6; i++)
        tribo_write_int(&w, counters[i]);
    tribo_write_int(&w, m->ended);
    put_point(&w, m, &m->committed);
    const tribo_charging *c = &m->charging;
    const size_t bytes = (size_t)c->n * sizeof(double);
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        if (!slot->segments)
            continue;
        tribo_write_bytes(&w, slot->segments, bytes);
        write_compensated(&w, &c->sum[i]);
        write_compensated(&w, &c->lost[i]);
        if (!slot->bands)
            continue;
        tribo_write_bytes(&w, slot->bands, bytes);
        write_compensated(&w, &c->band_charge[i]);
        write_compensated(&w, &c->band_lost[i]);
    }
    if (c->any_selected && c->keep_bands) {
        tribo_write_bytes(&w, c->bands.width, bytes);
        tribo_write_bytes(&w, c->bands.lo, bytes);
        tribo_write_bytes(&w, c->bands.hi, bytes);
        write_compensated(&w, &c->area);
        tribo_write_bytes(&w, c->bands.limit, bytes);
        const tribo_gas_state *g = &c->gas;
        tribo_write_int(&w, g->episode);
        tribo_write_double(&w, g->radius);
        tribo_write_double(&w, g->limit);
        tribo_write_int(&w, g->first);
        tribo_write_int(&w, g->count);
        for (int i = 0; i < c->n_models; i++)
            tribo_write_double(&w, g->grain[i]);
    }
    m->integrator->state_save(m->integrator_data, w.p);
    return TRIBO_OK;
}

tribo_status tribo_state_time(const void *buffer, size_t size, double *t)
{
    size_t n_params;
    tribo_param_table(&n_params);
    tribo_reader r = tribo_reader_of(buffer, buffer ? size : 0);
    char magic[sizeof MAGIC];
    tribo_read_bytes(&r, magic, sizeof magic);
    const int64_t version = tribo_read_int(&r), total = tribo_read_int(&r);
    for (size_t i = 0; i < n_params + 2; i++)
        tribo_read_double(&r);
    *t = tribo_read_double(&r);
    if (r.overrun || memcmp(magic, MAGIC, sizeof MAGIC) != 0 || version != STATE_VERSION ||
        (uint64_t)total != size)
        return TRIBO_ERR_STATE;
    return TRIBO_OK;
}

/* ---- load: read and check, then apply -------------------------------------------------- */

/* A state read from bytes and checked, not yet applied. */
typedef struct loaded {
    tribo_scene scene;
    double F_T, F_N, t_out;
    tribo_stats stats;
    int ended;
    tribo_point committed;
    double *segments[TRIBO_CHARGE_MAX_MODELS]; /* owned; NULL for models not selected */
    double *bands[TRIBO_CHARGE_MAX_MODELS];    /* owned; NULL without bands */
    tribo_compensated sum[TRIBO_CHARGE_MAX_MODELS], lost[TRIBO_CHARGE_MAX_MODELS];
    tribo_compensated band_charge[TRIBO_CHARGE_MAX_MODELS], band_lost[TRIBO_CHARGE_MAX_MODELS];
    tribo_band_geometry geometry;              /* owned; NULLs without bands */
    tribo_compensated area;
    tribo_gas_state gas;
    const unsigned char *integrator;           /* into the bytes */
} loaded;

static void loaded_free(loaded *l)
{
    for (int i = 0; i < TRIBO_CHARGE_MAX_MODELS; i++) {
        free(l->segments[i]);
        free(l->bands[i]);
    }
    free(l->geometry.width);
    free(l->geometry.lo);
    free(l->geometry.hi);
    free(l->geometry.limit);
}

static int all_finite(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* The most a counter can have counted: far beyond any run, far below overflow. */
#define COUNTER_MAX 0x1p53

/* Whether a point holds what an integration can produce, up to time t_out. */
static const char *point_problem(const tribo_model *m, const tribo_point *p, double t_out)
{
    /* sums of the steps' lengths may exceed the time by their rounding */
    const double slack = 1e-9 * fmax(1.0, p->t);
    const tribo_contact_eval *c = &p->contact;
    const double cd[CONTACT_DOUBLES] = {c->pose.sin_phi, c->pose.cos_phi, c->pose.h, c->pose.cx,
                                        c->delta_y, c->vs, c->sign_v, c->psi_n, c->psi_t, c->limit};
    const tribo_motion *mo = &p->motion;
    if (!(p->t >= 0.0 && p->t <= t_out && t_out <= TRIBO_TIME_MAX))
        return "times";
    if (!all_finite(p->y, m->n_state) || !all_finite(p->charge_globals, m->charging.n_globals) ||
        !all_finite(cd, CONTACT_DOUBLES))
        return "motion";
    if (!(p->contact_time >= 0.0 && p->contact_time <= p->t + slack))
        return "contact time";
    if ((c->in_contact != 0 && c->in_contact != 1) || (p->slipping != 0 && p->slipping != 1))
        return "contact flags";
    /* an average of 0 and 1, up to its rounding */
    if (!(mo->contact >= -1e-12 && mo->contact <= 1.0 + 1e-12) || !isfinite(mo->spin) ||
        mo->current < 0 || mo->current >= TRIBO_MOTION_CLASSES ||
        (mo->outside_assumptions != 0 && mo->outside_assumptions != 1))
        return "motion classes";
    for (int i = 0; i < TRIBO_MOTION_CLASSES; i++)
        if (!(mo->class_time[i] >= 0.0 && mo->class_time[i] <= p->t + slack))
            return "motion classes";
    if (!(mo->impacts >= 0 && (double)mo->impacts <= COUNTER_MAX))
        return "impacts";
    if (!(mo->touchdowns >= mo->impacts && (double)mo->touchdowns <= COUNTER_MAX))
        return "touch-downs";
    return NULL;
}

/* Whether the run has ended where the state says (model.md §9, §3c): an ended run's committed
   point is its output point, and the exit, at or past the end of the chute, or a lift-off of
   a scene that ends there, or a rest of a scene that rests (before the end); a run that goes on
   has its committed point before the end. */
static const char *end_problem(const loaded *l)
{
    const double L = l->scene.chute_length, X = l->committed.y[TRIBO_IX];
    if (l->ended != TRIBO_END_RUNNING && l->ended != TRIBO_END_EXIT && l->ended != TRIBO_END_LIFTOFF &&
        l->ended != TRIBO_END_REST)
        return "whether the run has ended";
    if (l->ended == TRIBO_END_LIFTOFF && l->scene.run_end != TRIBO_RUN_END_FIRST_LIFTOFF)
        return "whether the run has ended";
    /* at rest only with the rigid stick (and so CVODE) and rolling resistance (model.md §3c) */
    if (l->ended == TRIBO_END_REST &&
        (l->scene.stick_model != TRIBO_STICK_RIGID || !(l->scene.mu_roll > 0.0)))
        return "whether the run has ended";
    if (l->ended && l->t_out != l->committed.t)
        return "the end of the run";
    if (l->ended == TRIBO_END_EXIT ? !(X >= L) : !(X < L))
        return "the end of the run";
    return NULL;
}

static int finite_sums(const tribo_compensated *a, const tribo_compensated *b)
{
    return isfinite(a->sum) && isfinite(a->c) && isfinite(b->sum) && isfinite(b->c);
}

/* The bound the breakdown limit sets on a model's values (docs/model.md §8b; INF: none). */
static double cap_of(const tribo_charge_slot *slot, const tribo_scene *scene)
{
    return slot->model->density_unit ? scene->Sigma_bd / slot->model->density_unit(scene) : INFINITY;
}

/* The committed charges of one model: finite, ones the model can produce, and their running
   sum that of the values up to its rounding. */
static const char *charges_problem(const tribo_model *m, const tribo_charge_slot *slot,
                                   const tribo_scene *scene, const double *values,
                                   const tribo_compensated *sum, const tribo_compensated *lost,
                                   const double *globals)
{
    const int n = m->charging.n;
    if (!all_finite(values, n) || !finite_sums(sum, lost))
        return "values that are not numbers";
    if (slot->model->valid && !slot->model->valid(scene, globals + slot->globals_at, values, n))
        return "values the model cannot produce";
    /* the breakdown limit holds every value (docs/model.md §8b) */
    const double cap = cap_of(slot, scene);
    for (int i = 0; i < n; i++)
        if (fabs(values[i]) > cap)
            return "values above the breakdown limit";
    double magnitude = 0.0;
    for (int i = 0; i < n; i++)
        magnitude += fabs(values[i]);
    if (!(fabs(tribo_compensated_value(sum) - tribo_sum(values, n)) <= 1e-6 * magnitude + 1e-300))
        return "a sum that is not the sum of its values";
    return NULL;
}

/* The area (a^2) of a band, from its geometry (empty: lo = 1, hi = 0). */
static double band_area(const tribo_band_geometry *g, int i, double segment_length)
{
    return g->hi[i] > g->lo[i] ? g->width[i] * (g->hi[i] - g->lo[i]) * segment_length : 0.0;
}

/* The bands' geometry (docs/model.md §8c): each empty, or a width >= 0 over a hull within
   its segment; the charged area their sum, up to its rounding. */
static const char *geometry_problem(const tribo_model *m, const tribo_band_geometry *g,
                                    const tribo_compensated *area)
{
    const int n = m->charging.n;
    const double seg = m->charging.segment_length;
    if (!all_finite(g->width, n) || !all_finite(g->lo, n) || !all_finite(g->hi, n) ||
        !isfinite(area->sum) || !isfinite(area->c))
        return "values that are not numbers";
    double total = 0.0;
    for (int i = 0; i < n; i++) {
        const int empty = g->lo[i] == 1.0 && g->hi[i] == 0.0 && g->width[i] == 0.0;
        if (!empty && !(g->lo[i] >= 0.0 && g->lo[i] <= g->hi[i] && g->hi[i] <= 1.0 &&
                        g->width[i] >= 0.0))
            return "a band that is not one";
        total += band_area(g, i, seg);
    }
    if (!(fabs(tribo_compensated_value(area) - total) <= 1e-6 * total + 1e-300))
        return "a charged area that is not the sum of its bands";
    return NULL;
}

/* The gas's state (§8e): an episode of the touch-downs so far (0: none yet), its region's
   radius and limit, a run of bands on the ring, each band's limit positive, the grain's
   charges finite. */
static const char *gas_problem(const tribo_model *m, const loaded *l)
{
    const tribo_gas_state *g = &l->gas;
    const long n = m->charging.n;
    if (!(g->episode >= 0 && g->episode <= l->committed.motion.touchdowns + 1) ||
        !(g->radius >= 0.0 && isfinite(g->radius)) || !(g->limit > 0.0) ||
        !(g->first >= 0 && g->first < n && g->count >= 0 && g->count <= n))
        return "a gas's state that is not one";
    for (long i = 0; i < n; i++)
        if (!(l->geometry.limit[i] > 0.0))
            return "a band's limit that is not one";
    for (int i = 0; i < m->charging.n_models; i++)
        if (!isfinite(g->grain[i]))
            return "a grain charge that is not a number";
    return NULL;
}

/* A model's band densities: finite, within the breakdown limit where it holds the initial
   density too, their charge the sum of density times area up to its rounding. */
static const char *bands_problem(const tribo_model *m, const tribo_charge_slot *slot,
                                 const tribo_scene *scene, const double *bands,
                                 const tribo_band_geometry *g, const tribo_compensated *charge,
                                 const tribo_compensated *lost)
{
    const int n = m->charging.n;
    if (!all_finite(bands, n) || !finite_sums(charge, lost))
        return "bands that are not numbers";
    const double cap = cap_of(slot, scene);
    const double init = tribo_charging_initial_value(&m->charging, slot->model, scene);
    /* with the Paschen limit each band has its episode's (§8e) */
    const int paschen = scene->breakdown_model == TRIBO_BREAKDOWN_PASCHEN && slot->model->density_unit;
    const double unit = paschen ? slot->model->density_unit(scene) : 1.0;
    double total = 0.0, magnitude = 0.0;
    for (int i = 0; i < n; i++) {
        if (fabs(bands[i]) > fmax(paschen ? g->limit[i] / unit : cap, fabs(init)))
            return "bands above the breakdown limit";
        const double a = band_area(g, i, m->charging.segment_length);
        total += bands[i] * a;
        magnitude += fabs(bands[i]) * a;
    }
    if (!(fabs(tribo_compensated_value(charge) - total) <= 1e-6 * magnitude + 1e-300))
        return "a band charge that is not the sum of its bands";
    return NULL;
}

/* The saved scene and inputs into l; with check, refuse a structural parameter that is not
   the instance's own and any value out of its range. */
static tribo_status read_scene(tribo_model *m, tribo_reader *r, loaded *l, int check)
{
    l->scene = m->scene;
    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    char msg[300];
    for (size_t i = 0; i < n_params; i++) {
        const tribo_param_info *p = &params[i];
        const double v = tribo_read_double(r);
        /* a structural parameter must be the instance's own (valid for its parts); the
           others must be valid */
        if (check && p->variability == TRIBO_PARAM_STRUCTURAL && v != tribo_param_read(&m->scene, p))
            return tribo_fail(m, TRIBO_ERR_STATE,
                              "state was saved with %s = %.17g, this instance has %s = %.17g",
                              p->name, v, p->name, tribo_param_read(&m->scene, p));
        if (check && p->variability != TRIBO_PARAM_STRUCTURAL &&
            tribo_param_check(p, v, msg, sizeof msg) != TRIBO_OK)
            return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: %s", msg);
        tribo_param_write(&l->scene, p, v);
    }
    if (check && tribo_scene_check_combinations(&l->scene, msg, sizeof msg) != TRIBO_OK)
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: %s", msg);
    const tribo_param_info *inputs = tribo_input_table(NULL);
    l->F_T = tribo_read_double(r);
    l->F_N = tribo_read_double(r);
    if (check && (tribo_param_check(&inputs[TRIBO_INPUT_F_T], l->F_T, msg, sizeof msg) != TRIBO_OK ||
                  tribo_param_check(&inputs[TRIBO_INPUT_F_N], l->F_N, msg, sizeof msg) != TRIBO_OK))
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: %s", msg);
    return TRIBO_OK;
}

/* The output time, the work counters, the end flag and the committed point into l. */
static tribo_status read_point(tribo_model *m, tribo_reader *r, loaded *l, int check)
{
    l->t_out = tribo_read_double(r);
    long long counters[6];
    for (int i = 0; i < 6; i++) {
        counters[i] = tribo_read_int(r);
        if (check && !(counters[i] >= 0 && (double)counters[i] <= COUNTER_MAX))
            return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt (work counters)");
    }
    const tribo_stats stats = {counters[0], counters[1], counters[2],
                               counters[3], counters[4], counters[5]};
    l->stats = stats;
    l->ended = read_small(r);
    get_point(r, m, &l->committed);
    const char *problem = check ? point_problem(m, &l->committed, l->t_out) : NULL;
    if (!problem && check)
        problem = end_problem(l);
    if (problem)
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt (%s of the committed point)", problem);
    return TRIBO_OK;
}

/* Each selected model's segment charges (and its grain's bands) into l. */
static tribo_status read_charges(tribo_model *m, tribo_reader *r, loaded *l, int check)
{
    const tribo_charging *c = &m->charging;
    const size_t bytes = (size_t)c->n * sizeof(double);
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        if (!slot->segments)
            continue;
        if (!(l->segments[i] = malloc(bytes)) || (slot->bands && !(l->bands[i] = malloc(bytes))))
            return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
        tribo_read_bytes(r, l->segments[i], bytes);
        l->sum[i] = read_compensated(r);
        l->lost[i] = read_compensated(r);
        const char *problem = check ? charges_problem(m, slot, &l->scene, l->segments[i], &l->sum[i],
                                                      &l->lost[i], l->committed.charge_globals)
                                    : NULL;
        if (problem)
            return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: the %s charges hold %s",
                              slot->model->name, problem);
        if (!slot->bands)
            continue;
        tribo_read_bytes(r, l->bands[i], bytes);
        l->band_charge[i] = read_compensated(r);
        l->band_lost[i] = read_compensated(r);
    }
    return TRIBO_OK;
}

/* The grain's band geometry into l; with check, the geometry and every model's bands on it. */
static tribo_status read_band_geometry(tribo_model *m, tribo_reader *r, loaded *l, int check)
{
    const tribo_charging *c = &m->charging;
    if (!(c->any_selected && c->keep_bands))
        return TRIBO_OK;
    const size_t bytes = (size_t)c->n * sizeof(double);
    tribo_band_geometry *g = &l->geometry;
    if (!(g->width = malloc(bytes)) || !(g->lo = malloc(bytes)) || !(g->hi = malloc(bytes)) ||
        !(g->limit = malloc(bytes)))
        return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
    tribo_read_bytes(r, g->width, bytes);
    tribo_read_bytes(r, g->lo, bytes);
    tribo_read_bytes(r, g->hi, bytes);
    l->area = read_compensated(r);
    tribo_read_bytes(r, g->limit, bytes);
    tribo_gas_state *gas = &l->gas;
    gas->episode = tribo_read_int(r);
    gas->radius = tribo_read_double(r);
    gas->limit = tribo_read_double(r);
    gas->first = (long)tribo_read_int(r);
    gas->count = (long)tribo_read_int(r);
    for (int i = 0; i < c->n_models; i++)
        gas->grain[i] = tribo_read_double(r);
    const char *problem = check && !r->overrun ? geometry_problem(m, g, &l->area) : NULL;
    if (!problem && check && !r->overrun)
        problem = gas_problem(m, l);
    if (problem)
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: the grain's bands hold %s",
                          problem);
    for (int i = 0; i < c->n_models && check && !r->overrun; i++) {
        if (!l->bands[i])
            continue;
        problem = bands_problem(m, &c->slot[i], &l->scene, l->bands[i], g, &l->band_charge[i],
                                &l->band_lost[i]);
        if (problem)
            return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: the %s charges hold %s",
                              c->slot[i].model->name, problem);
    }
    return TRIBO_OK;
}

/* Read a state; with check, refuse (with the reason) anything the instance could not have
   saved. Without, only its size is checked: for the instance's own state, put back. */
static tribo_status read_state(tribo_model *m, const void *buffer, size_t size, loaded *l,
                               int check)
{
    memset(l, 0, sizeof *l);
    if (!buffer || size < header_size())
        return tribo_fail(m, TRIBO_ERR_STATE, "state of %zu bytes is too short", size);
    tribo_reader r = tribo_reader_of(buffer, size);
    char magic[sizeof MAGIC];
    tribo_read_bytes(&r, magic, sizeof magic);
    const int64_t version = tribo_read_int(&r), total = tribo_read_int(&r);
    if (memcmp(magic, MAGIC, sizeof MAGIC) != 0 || version != STATE_VERSION)
        return tribo_fail(m, TRIBO_ERR_STATE, "not a tribo state (or of another version)");
    if ((uint64_t)total != size || size != tribo_state_size(m))
        return tribo_fail(m, TRIBO_ERR_STATE,
                          "state of %zu bytes does not fit this instance (%zu bytes expected)",
                          size, tribo_state_size(m));
    tribo_status st;
    if ((st = read_scene(m, &r, l, check)) != TRIBO_OK || (st = read_point(m, &r, l, check)) != TRIBO_OK ||
        (st = read_charges(m, &r, l, check)) != TRIBO_OK ||
        (st = read_band_geometry(m, &r, l, check)) != TRIBO_OK)
        return st;
    l->integrator = r.p;
    return r.overrun ? tribo_fail(m, TRIBO_ERR_STATE, "state is truncated") : TRIBO_OK;
}

/* Make the instance the loaded state; only the integrator's part can still be refused. */
static tribo_status apply_state(tribo_model *m, const loaded *l)
{
    m->scene = l->scene;
    tribo_derive_params(m);
    m->dyn.F_T = l->F_T;
    m->dyn.F_N = l->F_N;
    m->stats = l->stats;
    m->ended = l->ended;
    m->committed = l->committed;
    tribo_charging *c = &m->charging;
    const size_t bytes = (size_t)c->n * sizeof(double);
    for (int i = 0; i < c->n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        if (!slot->segments)
            continue;
        memcpy(slot->segments, l->segments[i], bytes);
        c->sum[i] = l->sum[i];
        c->lost[i] = l->lost[i];
        if (!slot->bands)
            continue;
        memcpy(slot->bands, l->bands[i], bytes);
        c->band_charge[i] = l->band_charge[i];
        c->band_lost[i] = l->band_lost[i];
    }
    if (c->any_selected && c->keep_bands) {
        memcpy(c->bands.width, l->geometry.width, bytes);
        memcpy(c->bands.lo, l->geometry.lo, bytes);
        memcpy(c->bands.hi, l->geometry.hi, bytes);
        c->area = l->area;
        memcpy(c->bands.limit, l->geometry.limit, bytes);
        tribo_charging_setup_gas(c, &m->scene);
        c->gas = l->gas;
    }
    m->out = m->committed;
    m->n_pending = 0;
    m->charges_out_valid = 0;
    m->pending_sums_valid = 0;
    m->work = 0.0;
    tribo_status st = m->integrator->state_load(m, m->integrator_data, l->integrator, l->t_out);
    if (st != TRIBO_OK)
        return st;
    /* the output point, exactly as the advance that made it (it commits nothing: checked) */
    m->error[0] = '\0';
    if ((st = m->integrator->advance(m, m->integrator_data, l->t_out)) != TRIBO_OK)
        return st;
    m->stats = l->stats; /* recomputing the output point is no new work */
    if (tribo_check_outputs(m) != TRIBO_OK) {
        char why[sizeof m->error];
        memcpy(why, m->error, sizeof why);
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt: at its time %s", why);
    }
    return TRIBO_OK;
}

tribo_status tribo_state_load(tribo_model *m, const void *buffer, size_t size)
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    loaded l;
    tribo_status st = read_state(m, buffer, size, &l, 1);
    size_t backup_size = 0;
    unsigned char *backup = NULL;
    if (st == TRIBO_OK) {
        backup_size = tribo_state_size(m);
        if (!(backup = malloc(backup_size)) || tribo_state_save(m, backup, backup_size) != TRIBO_OK)
            st = tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
    }
    if (st == TRIBO_OK && (st = apply_state(m, &l)) != TRIBO_OK) {
        /* back to the instance as it was: its own state, which loads */
        char why[sizeof m->error];
        memcpy(why, m->error, sizeof why);
        loaded own;
        if (read_state(m, backup, backup_size, &own, 0) == TRIBO_OK)
            apply_state(m, &own);
        loaded_free(&own);
        memcpy(m->error, why, sizeof why);
        if (st != TRIBO_ERR_MEMORY)
            st = TRIBO_ERR_STATE;
    }
    free(backup);
    loaded_free(&l);
    return st;
}
