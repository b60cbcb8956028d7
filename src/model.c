/* model.c: life cycle of an instance, its parameters and inputs, and what can be read. */
#include "model.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

tribo_status tribo_fail(tribo_model *m, tribo_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m->error, sizeof m->error, fmt, ap);
    va_end(ap);
    return status;
}

static const tribo_integrator_ops *integrator_for(int kind)
{
    return kind == TRIBO_INTEGRATOR_FIXED_STEP ? &tribo_fixed_step_ops : &tribo_cvode_ops;
}

void tribo_derive_params(tribo_model *m)
{
    const tribo_scene *s = &m->scene;
    tribo_dyn_params *d = &m->dyn;
    const double beta = s->beta * (M_PI / 180.0);
    d->eps = s->epsilon;
    d->eps2 = s->epsilon * s->epsilon;
    d->mu = s->mu;
    d->nu = s->nu;
    d->Gamma = s->Gamma;
    d->g_t = s->Gamma * sin(beta);
    d->g_n = s->Gamma * cos(beta);
    d->inv_inertia = 4.0 / (1.0 + d->eps2); /* MODEL §4 */
    d->v_reg = s->v_reg;
    /* the fixed step integrates omega with the motion; CVODE integrates it along its
       charging sweep, so that it does not steer the steps */
    d->work_per_area = (s->charge_model & TRIBO_CHARGE_SLIDING) != 0 &&
                       s->integrator == TRIBO_INTEGRATOR_FIXED_STEP;
    m->charge.tau0 = s->tau0;
    m->charge.tau_r = s->tau_r;
    m->charge.Sigma0 = s->Sigma0;
    m->charge.eta = s->eta;
}

void tribo_initial_point(const tribo_model *m, tribo_point *p)
{
    const tribo_scene *s = &m->scene;
    const double beta = s->beta * (M_PI / 180.0);
    tribo_pose pose;
    tribo_pose_at(m->dyn.eps2, s->phi0, &pose);
    memset(p, 0, sizeof *p);
    /* MODEL §7: centre at the height of first contact (plus the gap), dropped straight
       down in the external frame */
    p->y[TRIBO_IX] = s->X0;
    p->y[TRIBO_IY] = pose.h + s->gap0;
    p->y[TRIBO_IPHI] = s->phi0;
    p->y[TRIBO_IU] = s->drop_speed * sin(beta);
    p->y[TRIBO_IV] = -s->drop_speed * cos(beta);
    p->y[TRIBO_IOMEGA] = s->Omega0;
    p->Sigma_s = s->Sigma0;
    static const tribo_force_law law = {TRIBO_CONTACT_BY_GEOMETRY, TRIBO_NORMAL_REGULARISED, 0, TRIBO_TANGENT_CLAMP, 0};
    tribo_contact_at(&m->dyn, &law, p->y, &p->contact);
    p->motion.mode = TRIBO_MODE_FLIGHT;
}

/* Warnings past this many are counted but not logged one by one. */
#define LOGGED_VIOLATIONS 10

void tribo_account_interval(tribo_model *m, const tribo_point *from, tribo_point *to, int commit)
{
    const double h = to->t - from->t;
    const int in_contact = to->contact.in_contact;
    to->contact_time = from->contact_time + (in_contact ? h : 0.0);
    to->motion = from->motion;
    if (!(h > 0.0))
        return;
    if (m->motion_decay_h != h) {
        m->motion_decay_h = h;
        m->motion_decay = exp(-h / TRIBO_MOTION_WINDOW);
    }
    tribo_motion_update(&to->motion, h, m->motion_decay, in_contact,
                        to->y[TRIBO_IPHI] - from->y[TRIBO_IPHI]);

    /* rho_c only where there is a contact: this runs on every step */
    const double rho_c =
        in_contact ? tribo_contact_curvature_radius(m->dyn.eps2, to->contact.pose.h) : 0.0;
    const int deep = in_contact && tribo_indentation_too_deep(to->contact.delta_y, m->dyn.eps, rho_c);
    if (deep && !from->motion.outside_assumptions && commit) {
        const long long n = ++m->stats.assumption_warnings;
        if (m->log && n <= LOGGED_VIOLATIONS) {
            char msg[512];
            snprintf(msg, sizeof msg,
                     "t = %.9g: the contact is outside the model's assumptions: delta_y = %.4g "
                     "exceeds %.2g x min(epsilon = %g, rho_c = %.4g); the linear contact law "
                     "and the contact width are not meaningful there (counted in "
                     "assumption_warnings%s)",
                     to->t, to->contact.delta_y, TRIBO_INDENTATION_LIMIT, m->dyn.eps, rho_c,
                     n == LOGGED_VIOLATIONS ? "; further ones are counted, not logged" : "");
            m->log(m->log_user, 1, msg);
        }
    }
    to->motion.outside_assumptions = deep;
}

tribo_status tribo_pending_push(tribo_model *m, const tribo_contact_sample *sample)
{
    if (m->n_pending == m->cap_pending) {
        const size_t cap = m->cap_pending ? 2 * m->cap_pending : 8;
        tribo_contact_sample *p = realloc(m->pending, cap * sizeof *p);
        if (!p)
            return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
        m->pending = p;
        m->cap_pending = cap;
    }
    m->pending[m->n_pending++] = *sample;
    m->charges_out_valid = 0;
    return TRIBO_OK;
}

void tribo_pending_clear(tribo_model *m)
{
    m->n_pending = 0;
    m->charges_out_valid = 0;
}

/* Apply the pending charge updates to arrays q / sigma (either may be NULL). */
static void apply_pending(tribo_model *m, double *q, double *sigma)
{
    for (size_t i = 0; i < m->n_pending; i++)
        tribo_charging_segments(&m->charging, &m->charge, &m->pending[i], q, sigma);
}

void tribo_commit_output(tribo_model *m)
{
    if (m->has_charging)
        apply_pending(m, m->charging.q, m->charging.sigma);
    m->committed = m->out;
    tribo_pending_clear(m);
}

/* Start the integrator afresh from the committed point, which is also the output now. */
static void restart_here(tribo_model *m)
{
    m->integrator->restart(m);
    m->out = m->committed;
    tribo_pending_clear(m);
}

tribo_model *tribo_create(const tribo_scene *scene, char *err, size_t err_size)
{
    char msg[512];
    if (tribo_scene_validate(scene, msg, sizeof msg) != TRIBO_OK) {
        if (err && err_size)
            snprintf(err, err_size, "%s", msg);
        return NULL;
    }
    tribo_model *m = calloc(1, sizeof *m);
    if (!m)
        goto oom;
    m->scene = *scene;
    tribo_derive_params(m);
    m->has_charging = scene->charge_model != TRIBO_CHARGE_NONE;
    /* Without a charge model no segment table is built, and no segment is touched. */
    if (m->has_charging &&
        tribo_charging_init(&m->charging, scene->epsilon, scene->n_segments,
                            (scene->charge_model & TRIBO_CHARGE_STATIC) != 0,
                            (scene->charge_model & TRIBO_CHARGE_SLIDING) != 0) != 0)
        goto oom;
    m->integrator = integrator_for(scene->integrator);
    if (m->integrator->create(m) != TRIBO_OK) {
        if (err && err_size)
            snprintf(err, err_size, "%s", m->error[0] ? m->error : "out of memory");
        tribo_free(m);
        return NULL;
    }
    tribo_reset(m);
    return m;
oom:
    if (err && err_size)
        snprintf(err, err_size, "out of memory (n_segments = %d)", scene->n_segments);
    tribo_free(m);
    return NULL;
}

void tribo_free(tribo_model *m)
{
    if (!m)
        return;
    if (m->integrator && m->integrator_data)
        m->integrator->destroy(m);
    if (m->has_charging)
        tribo_charging_free(&m->charging);
    free(m->pending);
    free(m->q_out);
    free(m->sigma_out);
    free(m);
}

void tribo_set_logger(tribo_model *m, tribo_log_fn fn, void *user)
{
    m->log = fn;
    m->log_user = user;
}

void tribo_reset(tribo_model *m)
{
    tribo_initial_point(m, &m->committed);
    if (m->has_charging)
        tribo_charging_reset(&m->charging);
    memset(&m->stats, 0, sizeof m->stats);
    m->error[0] = '\0';
    restart_here(m);
}

tribo_status tribo_advance(tribo_model *m, double t)
{
    if (!isfinite(t) || t < m->out.t)
        return tribo_fail(m, TRIBO_ERR_TIME,
                          "cannot advance to t = %.17g: the instance is at t = %.17g", t,
                          m->out.t);
    return m->integrator->advance(m, t);
}

tribo_status tribo_set_param(tribo_model *m, const char *name, double value)
{
    const tribo_param_info *p = tribo_param_find(name);
    if (!p)
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT, "unknown parameter '%s'",
                          name ? name : "(null)");
    if (tribo_param_check(p, value, m->error, sizeof m->error) != TRIBO_OK)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (tribo_param_read(&m->scene, p) == value)
        return TRIBO_OK;
    if (p->variability != TRIBO_PARAM_TUNABLE)
        return tribo_fail(m, TRIBO_ERR_NOT_TUNABLE,
                          "%s cannot change during a run (it is %s); create a new instance",
                          p->name,
                          p->variability == TRIBO_PARAM_STRUCTURAL ? "structural" : "fixed");
    tribo_commit_output(m);
    tribo_param_write(&m->scene, p, value);
    tribo_derive_params(m);
    restart_here(m);
    return TRIBO_OK;
}

tribo_status tribo_set_external_force(tribo_model *m, double F_T, double F_N)
{
    if (!isfinite(F_T) || !isfinite(F_N))
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT,
                          "external force (F_T_ext = %g, F_N_ext = %g) must be finite", F_T, F_N);
    if (F_T == m->dyn.F_T && F_N == m->dyn.F_N)
        return TRIBO_OK;
    tribo_commit_output(m);
    m->dyn.F_T = F_T;
    m->dyn.F_N = F_N;
    restart_here(m);
    return TRIBO_OK;
}

const tribo_scene *tribo_get_scene(const tribo_model *m) { return &m->scene; }

const char *tribo_last_error(const tribo_model *m) { return m->error; }

void tribo_get_stats(const tribo_model *m, tribo_stats *s) { *s = m->stats; }

/* The committed charges with the pending updates applied: the committed arrays
   themselves when nothing is pending, else scratch copies. */
static tribo_status charges_out(tribo_model *m, const double **q, const double **sigma)
{
    tribo_charging *c = &m->charging;
    if (m->n_pending == 0) {
        *q = c->q;
        *sigma = c->sigma;
        return TRIBO_OK;
    }
    if (!m->charges_out_valid) {
        const size_t bytes = (size_t)c->n * sizeof(double);
        if (c->q && !m->q_out && !(m->q_out = malloc(bytes)))
            return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
        if (c->sigma && !m->sigma_out && !(m->sigma_out = malloc(bytes)))
            return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
        if (c->q)
            memcpy(m->q_out, c->q, bytes);
        if (c->sigma)
            memcpy(m->sigma_out, c->sigma, bytes);
        apply_pending(m, c->q ? m->q_out : NULL, c->sigma ? m->sigma_out : NULL);
        m->charges_out_valid = 1;
    }
    *q = c->q ? m->q_out : NULL;
    *sigma = c->sigma ? m->sigma_out : NULL;
    return TRIBO_OK;
}

double tribo_get(tribo_model *m, tribo_quantity which)
{
    const tribo_point *p = &m->out;
    const double *q = NULL, *sigma = NULL;
    switch (which) {
    case TRIBO_Q_TIME: return p->t;
    case TRIBO_Q_X: return p->y[TRIBO_IX];
    case TRIBO_Q_Y: return p->y[TRIBO_IY];
    case TRIBO_Q_PHI: return p->y[TRIBO_IPHI];
    case TRIBO_Q_U: return p->y[TRIBO_IU];
    case TRIBO_Q_V: return p->y[TRIBO_IV];
    case TRIBO_Q_OMEGA: return p->y[TRIBO_IOMEGA];
    case TRIBO_Q_DELTA_Y: return p->contact.delta_y;
    case TRIBO_Q_DELTA_X: return p->y[TRIBO_IDX];
    case TRIBO_Q_IN_CONTACT: return p->contact.in_contact ? 1.0 : 0.0;
    case TRIBO_Q_SLIPPING: return p->slipping ? 1.0 : 0.0;
    case TRIBO_Q_PSI_N: return p->contact.psi_n;
    case TRIBO_Q_PSI_T: return p->contact.psi_t;
    case TRIBO_Q_STATIC:
        if (!m->has_charging || !m->charging.q || charges_out(m, &q, &sigma) != TRIBO_OK)
            return 0.0;
        return tribo_charging_mean(q, m->charging.n); /* MODEL §5a */
    case TRIBO_Q_SLIDING:
        if (!m->has_charging || !m->charging.sigma || charges_out(m, &q, &sigma) != TRIBO_OK)
            return 0.0;
        return tribo_charging_mean(sigma, m->charging.n) / m->scene.Sigma0; /* MODEL §5b */
    case TRIBO_Q_SIGMA_S: return p->Sigma_s;
    case TRIBO_Q_OMEGA_WORK: return p->y[TRIBO_IWORK];
    case TRIBO_Q_ENERGY: return tribo_energy(&m->dyn, p->y);
    case TRIBO_Q_WORK_DISSIPATED: return p->y[TRIBO_IWDISS];
    case TRIBO_Q_WORK_EXTERNAL: return p->y[TRIBO_IWEXT];
    case TRIBO_Q_CONTACT_TIME: return p->contact_time;
    case TRIBO_Q_CONTACT_FRACTION: return p->t > 0.0 ? p->contact_time / p->t : 0.0;
    case TRIBO_Q_TURNS: return fabs(p->y[TRIBO_IPHI] - m->scene.phi0) / (2.0 * M_PI);
    case TRIBO_Q_CONTACT_MODE: return (double)p->motion.mode;
    case TRIBO_Q_FRACTION_FLIGHT:
    case TRIBO_Q_FRACTION_SLIDING:
    case TRIBO_Q_FRACTION_ROLLING:
    case TRIBO_Q_FRACTION_TUMBLING:
    case TRIBO_Q_FRACTION_BOUNCING:
        return p->t > 0.0 ? p->motion.mode_time[which - TRIBO_Q_FRACTION_FLIGHT] / p->t : 0.0;
    case TRIBO_Q_ASSUMPTION_WARNINGS: return (double)m->stats.assumption_warnings;
    case TRIBO_Q_COUNT: break;
    }
    return NAN;
}

const char *tribo_quantity_name(tribo_quantity q)
{
    static const char *const names[TRIBO_Q_COUNT] = {
        "time", "X", "Y", "phi", "U", "V", "Omega", "delta_y", "delta_x", "in_contact",
        "slipping", "Psi_N", "Psi_T", "Q_static", "Q_sliding", "Sigma_s", "omega_work",
        "energy", "work_dissipated", "work_external", "contact_time", "contact_fraction",
        "turns", "contact_mode", "fraction_flight", "fraction_sliding", "fraction_rolling",
        "fraction_tumbling", "fraction_bouncing", "assumption_warnings",
    };
    return (unsigned)q < TRIBO_Q_COUNT ? names[q] : NULL;
}

tribo_status tribo_get_segment_charges(tribo_model *m, tribo_segment_charge which, double *out,
                                       size_t n)
{
    const int want_static = which == TRIBO_SEGMENTS_STATIC;
    if (!m->has_charging || (want_static ? !m->charging.q : !m->charging.sigma))
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT,
                          "the scene does not include the %s charge model (charge_model = %d)",
                          want_static ? "static" : "sliding", m->scene.charge_model);
    if (n != (size_t)m->charging.n)
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT,
                          "segment array of %zu values given, n_segments = %d", n,
                          m->charging.n);
    const double *q, *sigma;
    tribo_status st = charges_out(m, &q, &sigma);
    if (st != TRIBO_OK)
        return st;
    if (want_static) {
        memcpy(out, q, n * sizeof *out);
    } else {
        for (size_t i = 0; i < n; i++)
            out[i] = sigma[i] / m->scene.Sigma0;
    }
    return TRIBO_OK;
}
