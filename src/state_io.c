/* state_io.c: the whole state of an instance as plain bytes, out and back in.
 *
 * Layout (native byte order, doubles and 64-bit integers):
 *   magic "TRIBOST1", version, total size,
 *   every scene parameter (in the order of the parameter table),
 *   the external force, the output time, the work counters,
 *   the committed point (with the charge models' quadratures and global states), the
 *   committed per-segment charges of each selected charge model, the integrator's own bytes.
 * The output point is not stored: it is recomputed from the committed point exactly as
 * the advance that made it did, so a loaded instance continues bit-identically.
 */
#include "model.h"

#include "byte_cursor.h"

#include <math.h>
#include <string.h>

static const char MAGIC[8] = {'T', 'R', 'I', 'B', 'O', 'S', 'T', '1'};
enum { STATE_VERSION = 2 };

/* Fields of a point, in order; the contact evaluation is stored with it because some
   integrators (phases of the force law) cannot recompute it from y alone. */
#define CONTACT_DOUBLES 10
#define POINT_INTS 4

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
    c->in_contact = (int)tribo_read_int(r);
    p->slipping = (int)tribo_read_int(r);
    tribo_motion *mo = &p->motion;
    mo->contact = tribo_read_double(r);
    mo->spin = tribo_read_double(r);
    for (int i = 0; i < TRIBO_MOTION_CLASSES; i++)
        mo->class_time[i] = tribo_read_double(r);
    mo->current = (int)tribo_read_int(r);
    mo->outside_assumptions = (int)tribo_read_int(r);
}

static size_t header_size(void) { return sizeof MAGIC + 2 * sizeof(int64_t); }

/* The values of the committed per-segment charges, over every selected model. */
static size_t charge_count(const tribo_model *m)
{
    size_t n = 0;
    for (int i = 0; i < m->charging.n_models; i++)
        if (m->charging.slot[i].segments)
            n += (size_t)m->charging.n;
    return n;
}

size_t tribo_state_size(const tribo_model *m)
{
    size_t n_params;
    tribo_param_table(&n_params);
    return header_size() + n_params * sizeof(double) + 3 * sizeof(double) /* F_T, F_N, t_out */
           + 6 * sizeof(int64_t)                                            /* stats */
           + point_size(m) + charge_count(m) * sizeof(double) +
           m->integrator->state_size(m->integrator_data);
}

tribo_status tribo_state_save(const tribo_model *m, void *buffer, size_t size)
{
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
    tribo_write_int(&w, s->steps);
    tribo_write_int(&w, s->rhs_evals);
    tribo_write_int(&w, s->events);
    tribo_write_int(&w, s->restarts);
    tribo_write_int(&w, s->substeps);
    tribo_write_int(&w, s->assumption_warnings);
    put_point(&w, m, &m->committed);
    for (int i = 0; i < m->charging.n_models; i++)
        if (m->charging.slot[i].segments)
            tribo_write_bytes(&w, m->charging.slot[i].segments, (size_t)m->charging.n * sizeof(double));
    m->integrator->state_save(m->integrator_data, w.p);
    return TRIBO_OK;
}

tribo_status tribo_state_load(tribo_model *m, const void *buffer, size_t size)
{
    if (!buffer || size < header_size())
        return tribo_fail(m, TRIBO_ERR_STATE, "state of %zu bytes is too short", size);
    tribo_reader r = tribo_reader_of(buffer, size);
    char magic[sizeof MAGIC];
    tribo_read_bytes(&r, magic, sizeof magic);
    const int64_t version = tribo_read_int(&r), total = tribo_read_int(&r);
    if (memcmp(magic, MAGIC, sizeof MAGIC) != 0 || version != STATE_VERSION)
        return tribo_fail(m, TRIBO_ERR_STATE, "not a tribo state (or of another version)");
    if ((size_t)total != size || size != tribo_state_size(m))
        return tribo_fail(m, TRIBO_ERR_STATE,
                          "state of %zu bytes does not fit this instance (%zu bytes expected)",
                          size, tribo_state_size(m));

    tribo_scene scene = m->scene;
    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    for (size_t i = 0; i < n_params; i++) {
        const tribo_param_info *p = &params[i];
        const double v = tribo_read_double(&r);
        /* a structural parameter must be the instance's own (valid for its parts); the
           others must be valid */
        if (p->variability == TRIBO_PARAM_STRUCTURAL && v != tribo_param_read(&m->scene, p))
            return tribo_fail(m, TRIBO_ERR_STATE,
                              "state was saved with %s = %.17g, this instance has %s = %.17g",
                              p->name, v, p->name, tribo_param_read(&m->scene, p));
        if (p->variability != TRIBO_PARAM_STRUCTURAL &&
            tribo_param_check(p, v, m->error, sizeof m->error) != TRIBO_OK)
            return TRIBO_ERR_STATE;
        tribo_param_write(&scene, p, v);
    }
    const double F_T = tribo_read_double(&r), F_N = tribo_read_double(&r),
                 t_out = tribo_read_double(&r);
    tribo_stats stats;
    stats.steps = tribo_read_int(&r);
    stats.rhs_evals = tribo_read_int(&r);
    stats.events = tribo_read_int(&r);
    stats.restarts = tribo_read_int(&r);
    stats.substeps = tribo_read_int(&r);
    stats.assumption_warnings = tribo_read_int(&r);
    tribo_point committed;
    get_point(&r, m, &committed);
    if (!isfinite(F_T) || !isfinite(F_N) || !isfinite(t_out) || !isfinite(committed.t) ||
        t_out < committed.t)
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt (times or inputs)");

    m->scene = scene;
    tribo_derive_params(m);
    m->dyn.F_T = F_T;
    m->dyn.F_N = F_N;
    m->stats = stats;
    m->committed = committed;
    for (int i = 0; i < m->charging.n_models; i++)
        if (m->charging.slot[i].segments)
            tribo_read_bytes(&r, m->charging.slot[i].segments, (size_t)m->charging.n * sizeof(double));
    tribo_status st = m->integrator->state_load(m, m->integrator_data, r.p);
    if (st != TRIBO_OK)
        return st;
    /* the output point, exactly as the advance that made it */
    m->out = m->committed;
    m->n_pending = 0;
    m->charges_out_valid = 0;
    m->error[0] = '\0';
    return m->integrator->advance(m, m->integrator_data, t_out);
}
