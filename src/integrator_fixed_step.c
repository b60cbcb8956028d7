/* integrator_fixed_step.c: the paper's fixed-step integration (MODEL §7).
 *
 * Classical 4th-order Runge-Kutta on the first-order system of dynamics.h (not the
 * paper's Runge-Kutta-Nystrom: the tangential spring stretch is a first-order state
 * and the forces depend on the velocities, so the Nystrom form gains nothing). The
 * set-valued sign of V is regularised as tanh(V / v_reg) (MODEL §3) and the stretch is
 * clamped to the Coulomb limit after each step.
 *
 * Steps lie on the grid t_base + k dt whatever times are asked for; the state at an
 * asked time between grid points is a partial step from the last one, not committed.
 */
#include "model.h"

#include "contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct fixed_step {
    double t_base;  /* start of the grid: 0, or where a tunable / input last changed */
    long long k;    /* steps taken on the grid */
} fixed_step;

static const tribo_force_law LAW = {TRIBO_CONTACT_BY_GEOMETRY, TRIBO_NORMAL_REGULARISED, 0.0, TRIBO_TANGENT_CLAMP, 0.0};

/* One step of size h from p to next; the contact over the step is returned in sample
   (charged at the end point's contact for the whole step, as the paper does). */
static void step(tribo_model *m, const tribo_point *p, double h, tribo_point *next,
                 tribo_contact_sample *sample)
{
    const tribo_dyn_params *dp = &m->dyn;
    double k1[TRIBO_NSTATE], k2[TRIBO_NSTATE], k3[TRIBO_NSTATE], k4[TRIBO_NSTATE];
    double tmp[TRIBO_NSTATE];
    const double *y = p->y;

    tribo_dynamics_rhs(dp, &LAW, y, k1, NULL);
    for (int i = 0; i < TRIBO_NSTATE; i++)
        tmp[i] = y[i] + 0.5 * h * k1[i];
    tribo_dynamics_rhs(dp, &LAW, tmp, k2, NULL);
    for (int i = 0; i < TRIBO_NSTATE; i++)
        tmp[i] = y[i] + 0.5 * h * k2[i];
    tribo_dynamics_rhs(dp, &LAW, tmp, k3, NULL);
    for (int i = 0; i < TRIBO_NSTATE; i++)
        tmp[i] = y[i] + h * k3[i];
    tribo_dynamics_rhs(dp, &LAW, tmp, k4, NULL);

    next->t = p->t + h;
    for (int i = 0; i < TRIBO_NSTATE; i++)
        next->y[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
    m->stats.rhs_evals += 4;

    /* Hold the stretch within the Coulomb limit (MODEL §3); in flight the limit is 0,
       so the stretch is 0 when contact is regained. The spring energy the clamp
       removes is dissipated by friction. */
    tribo_contact_eval *ev = &next->contact;
    tribo_contact_at(dp, &LAW, next->y, ev);
    const double dx = next->y[TRIBO_IDX];
    const double dx_held = tribo_clamp(dx, ev->limit);
    next->y[TRIBO_IDX] = dx_held;
    next->y[TRIBO_IWDISS] += 0.5 * (dx * dx - dx_held * dx_held);
    ev->psi_t = -dx_held;
    next->slipping = ev->in_contact && fabs(dx) >= ev->limit && (ev->limit > 0.0 || ev->vs != 0.0);

    next->contact_time = p->contact_time + (ev->in_contact ? h : 0.0);
    next->Sigma_s = p->Sigma_s;
    if (m->has_charging) {
        tribo_charging_sample(&m->charging, &ev->pose, ev->delta_y, h, p->y[TRIBO_IWORK],
                              next->y[TRIBO_IWORK], sample);
        if (m->charging.with_sliding)
            tribo_charging_saturation(&m->charging, &m->charge, &next->Sigma_s, sample);
    }
}

static tribo_status create(tribo_model *m)
{
    fixed_step *f = calloc(1, sizeof *f);
    if (!f)
        return TRIBO_ERR_MEMORY;
    m->integrator_data = f;
    return TRIBO_OK;
}

static void destroy(tribo_model *m)
{
    free(m->integrator_data);
    m->integrator_data = NULL;
}

static void restart(tribo_model *m)
{
    fixed_step *f = m->integrator_data;
    f->t_base = m->committed.t;
    f->k = 0;
}

static tribo_status advance(tribo_model *m, double t)
{
    fixed_step *f = m->integrator_data;
    const double dt = m->scene.dt;
    /* a time that is a grid point up to rounding counts as that grid point */
    const double slack = 1e-9;
    const long long target = (long long)floor((t - f->t_base) / dt + slack);
    tribo_contact_sample sample;
    tribo_point next;

    while (f->k < target) {
        step(m, &m->committed, dt, &next, &sample);
        f->k++;
        next.t = f->t_base + (double)f->k * dt; /* no drift over millions of steps */
        m->committed = next;
        if (m->has_charging)
            tribo_charging_segments(&m->charging, &m->charge, &sample, m->charging.q,
                                    m->charging.sigma);
        m->stats.steps++;
    }

    tribo_pending_clear(m);
    const double h = t - m->committed.t;
    if (h <= slack * dt) {
        m->out = m->committed;
        m->out.t = t;
        return TRIBO_OK;
    }
    step(m, &m->committed, h, &m->out, &sample);
    m->out.t = t;
    return m->has_charging ? tribo_pending_push(m, &sample) : TRIBO_OK;
}

static size_t state_size(const tribo_model *m)
{
    (void)m;
    return sizeof(double) + sizeof(long long);
}

static void state_save(const tribo_model *m, unsigned char *b)
{
    const fixed_step *f = m->integrator_data;
    memcpy(b, &f->t_base, sizeof f->t_base);
    memcpy(b + sizeof f->t_base, &f->k, sizeof f->k);
}

static tribo_status state_load(tribo_model *m, const unsigned char *b)
{
    fixed_step *f = m->integrator_data;
    memcpy(&f->t_base, b, sizeof f->t_base);
    memcpy(&f->k, b + sizeof f->t_base, sizeof f->k);
    if (!isfinite(f->t_base) || f->k < 0)
        return tribo_fail(m, TRIBO_ERR_STATE, "fixed-step state is corrupt");
    return TRIBO_OK;
}

const tribo_integrator_ops tribo_fixed_step_ops = {
    "fixed-step RK4", create, destroy, restart, advance, state_size, state_save, state_load,
};
