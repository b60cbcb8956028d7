/* state_io.c: the whole state of an instance as plain bytes, out and back in.
 *
 * Layout (native byte order, doubles and 64-bit integers):
 *   magic "TRIBOST1", version, total size,
 *   every scene parameter (in the order of the parameter table),
 *   the external force, the output time, the work counters,
 *   the committed point, the committed charges, the integrator's own bytes.
 * The output point is not stored: it is recomputed from the committed point exactly as
 * the advance that made it did, so a loaded instance continues bit-identically.
 */
#include "model.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static const char MAGIC[8] = {'T', 'R', 'I', 'B', 'O', 'S', 'T', '1'};
enum { STATE_VERSION = 1 };

typedef struct writer {
    unsigned char *p;
} writer;

typedef struct reader {
    const unsigned char *p;
} reader;

static void put(writer *w, const void *v, size_t n)
{
    if (w->p)
        memcpy(w->p, v, n);
    w->p = w->p ? w->p + n : NULL;
}
static void put_d(writer *w, double v) { put(w, &v, sizeof v); }
static void put_i(writer *w, int64_t v) { put(w, &v, sizeof v); }

static void get(reader *r, void *v, size_t n)
{
    memcpy(v, r->p, n);
    r->p += n;
}
static double get_d(reader *r)
{
    double v;
    get(r, &v, sizeof v);
    return v;
}
static int64_t get_i(reader *r)
{
    int64_t v;
    get(r, &v, sizeof v);
    return v;
}

/* Fields of a point, in order; the contact evaluation is stored with it because some
   integrators (modes of the force law) cannot recompute it from y alone. */
#define POINT_DOUBLES (1 + TRIBO_NSTATE + 2 + 10 + 2 + TRIBO_MODE_COUNT)
#define POINT_INTS 4

static void put_point(writer *w, const tribo_point *p)
{
    put_d(w, p->t);
    for (int i = 0; i < TRIBO_NSTATE; i++)
        put_d(w, p->y[i]);
    put_d(w, p->contact_time);
    put_d(w, p->Sigma_s);
    const tribo_contact_eval *c = &p->contact;
    const double cd[10] = {c->pose.sin_phi, c->pose.cos_phi, c->pose.h, c->pose.cx, c->delta_y,
                           c->vs, c->sign_v, c->psi_n, c->psi_t, c->limit};
    for (int i = 0; i < 10; i++)
        put_d(w, cd[i]);
    put_i(w, c->in_contact);
    put_i(w, p->slipping);
    const tribo_motion *mo = &p->motion;
    put_d(w, mo->contact);
    put_d(w, mo->spin);
    for (int i = 0; i < TRIBO_MODE_COUNT; i++)
        put_d(w, mo->mode_time[i]);
    put_i(w, mo->mode);
    put_i(w, mo->outside_assumptions);
}

static void get_point(reader *r, tribo_point *p)
{
    memset(p, 0, sizeof *p);
    p->t = get_d(r);
    for (int i = 0; i < TRIBO_NSTATE; i++)
        p->y[i] = get_d(r);
    p->contact_time = get_d(r);
    p->Sigma_s = get_d(r);
    tribo_contact_eval *c = &p->contact;
    double *cd[10] = {&c->pose.sin_phi, &c->pose.cos_phi, &c->pose.h, &c->pose.cx, &c->delta_y,
                      &c->vs, &c->sign_v, &c->psi_n, &c->psi_t, &c->limit};
    for (int i = 0; i < 10; i++)
        *cd[i] = get_d(r);
    c->in_contact = (int)get_i(r);
    p->slipping = (int)get_i(r);
    tribo_motion *mo = &p->motion;
    mo->contact = get_d(r);
    mo->spin = get_d(r);
    for (int i = 0; i < TRIBO_MODE_COUNT; i++)
        mo->mode_time[i] = get_d(r);
    mo->mode = (int)get_i(r);
    mo->outside_assumptions = (int)get_i(r);
}

static size_t header_size(void) { return sizeof MAGIC + 2 * sizeof(int64_t); }

static size_t charge_count(const tribo_model *m)
{
    if (!m->has_charging)
        return 0;
    return (size_t)m->charging.n * ((m->charging.q ? 1u : 0u) + (m->charging.sigma ? 1u : 0u));
}

size_t tribo_state_size(const tribo_model *m)
{
    size_t n_params;
    tribo_param_table(&n_params);
    return header_size() + n_params * sizeof(double) + 3 * sizeof(double) /* F_T, F_N, t_out */
           + 6 * sizeof(int64_t)                                            /* stats */
           + POINT_DOUBLES * sizeof(double) + POINT_INTS * sizeof(int64_t) +
           charge_count(m) * sizeof(double) + m->integrator->state_size(m);
}

tribo_status tribo_state_save(const tribo_model *m, void *buffer, size_t size)
{
    const size_t need = tribo_state_size(m);
    if (!buffer || size < need)
        return tribo_fail((tribo_model *)m, TRIBO_ERR_INVALID_ARGUMENT,
                          "state buffer of %zu bytes given, %zu needed", size, need);
    writer w = {buffer};
    put(&w, MAGIC, sizeof MAGIC);
    put_i(&w, STATE_VERSION);
    put_i(&w, (int64_t)need);
    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    for (size_t i = 0; i < n_params; i++)
        put_d(&w, tribo_param_read(&m->scene, &params[i]));
    put_d(&w, m->dyn.F_T);
    put_d(&w, m->dyn.F_N);
    put_d(&w, m->out.t);
    const tribo_stats *s = &m->stats;
    put_i(&w, s->steps);
    put_i(&w, s->rhs_evals);
    put_i(&w, s->events);
    put_i(&w, s->restarts);
    put_i(&w, s->substeps);
    put_i(&w, s->assumption_warnings);
    put_point(&w, &m->committed);
    if (m->has_charging && m->charging.q)
        put(&w, m->charging.q, (size_t)m->charging.n * sizeof(double));
    if (m->has_charging && m->charging.sigma)
        put(&w, m->charging.sigma, (size_t)m->charging.n * sizeof(double));
    m->integrator->state_save(m, w.p);
    return TRIBO_OK;
}

tribo_status tribo_state_load(tribo_model *m, const void *buffer, size_t size)
{
    if (!buffer || size < header_size())
        return tribo_fail(m, TRIBO_ERR_STATE, "state of %zu bytes is too short", size);
    reader r = {buffer};
    char magic[sizeof MAGIC];
    get(&r, magic, sizeof magic);
    const int64_t version = get_i(&r), total = get_i(&r);
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
        const double v = get_d(&r);
        if (tribo_param_check(&params[i], v, m->error, sizeof m->error) != TRIBO_OK)
            return TRIBO_ERR_STATE;
        if (params[i].variability == TRIBO_PARAM_STRUCTURAL &&
            v != tribo_param_read(&m->scene, &params[i]))
            return tribo_fail(m, TRIBO_ERR_STATE,
                              "state was saved with %s = %.17g, this instance has %s = %.17g",
                              params[i].name, v, params[i].name,
                              tribo_param_read(&m->scene, &params[i]));
        tribo_param_write(&scene, &params[i], v);
    }
    const double F_T = get_d(&r), F_N = get_d(&r), t_out = get_d(&r);
    tribo_stats stats;
    stats.steps = get_i(&r);
    stats.rhs_evals = get_i(&r);
    stats.events = get_i(&r);
    stats.restarts = get_i(&r);
    stats.substeps = get_i(&r);
    stats.assumption_warnings = get_i(&r);
    tribo_point committed;
    get_point(&r, &committed);
    if (!isfinite(F_T) || !isfinite(F_N) || !isfinite(t_out) || !isfinite(committed.t) ||
        t_out < committed.t)
        return tribo_fail(m, TRIBO_ERR_STATE, "state is corrupt (times or inputs)");

    m->scene = scene;
    tribo_derive_params(m);
    m->dyn.F_T = F_T;
    m->dyn.F_N = F_N;
    m->stats = stats;
    m->committed = committed;
    if (m->has_charging && m->charging.q)
        get(&r, m->charging.q, (size_t)m->charging.n * sizeof(double));
    if (m->has_charging && m->charging.sigma)
        get(&r, m->charging.sigma, (size_t)m->charging.n * sizeof(double));
    tribo_status st = m->integrator->state_load(m, r.p);
    if (st != TRIBO_OK)
        return st;
    /* the output point, exactly as the advance that made it */
    m->out = m->committed;
    tribo_pending_clear(m);
    m->error[0] = '\0';
    return m->integrator->advance(m, t_out);
}
