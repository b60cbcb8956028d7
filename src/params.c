/* params.c: the scene's parameters, their defaults and valid ranges (MODEL §1, §7). */
#include "tribo.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define REAL(field, desc, unit, lo, hi, lo_in, hi_in, var) \
    { #field, desc, unit, offsetof(tribo_scene, field), 0, lo, hi, lo_in, hi_in, var }
#define INT(field, desc, unit, lo, hi, var) \
    { #field, desc, unit, offsetof(tribo_scene, field), 1, lo, hi, 1, 1, var }

/* The valid ranges are MODEL §1's. Upper bounds that the model leaves open are
   +INFINITY (any finite value); the few finite caps are there to refuse input that
   would only exhaust memory or time, and say so in their description. */
static const tribo_param_info PARAMS[] = {
    REAL(epsilon, "roundness ratio b/a (1 = circle)", "1", 0, 1, 0, 1, TRIBO_PARAM_STRUCTURAL),
    REAL(mu, "Coulomb friction coefficient (static = kinetic)", "1", 0, INFINITY, 1, 0, TRIBO_PARAM_TUNABLE),
    REAL(nu, "normal dissipation coefficient", "1", 0, INFINITY, 1, 0, TRIBO_PARAM_TUNABLE),
    REAL(Gamma, "gravity / stiffness ratio mg/(ka)", "1", 0, INFINITY, 0, 0, TRIBO_PARAM_FIXED),
    REAL(beta, "plate tilt", "deg", 0, 90, 1, 0, TRIBO_PARAM_FIXED),
    REAL(tau0, "charging time constant", "1", 0, INFINITY, 0, 0, TRIBO_PARAM_TUNABLE),
    REAL(Sigma0, "static saturation charge density (sliding model)", "1", 0, INFINITY, 0, 0,
         TRIBO_PARAM_TUNABLE),
    REAL(eta, "fraction of frictional work that raises the saturation density", "1", 0, INFINITY,
         1, 0, TRIBO_PARAM_TUNABLE),
    REAL(tau_r, "relaxation time of the elevated saturation density", "1", 0, INFINITY, 0, 0,
         TRIBO_PARAM_TUNABLE),
    INT(n_segments, "boundary segments of equal arc length (at most 10^7: memory)", "1", 16,
        10000000, TRIBO_PARAM_STRUCTURAL),
    REAL(v_reg, "velocity scale of the regularised sign (fixed-step integrator)", "1", 0,
         INFINITY, 0, 0, TRIBO_PARAM_FIXED),
    REAL(X0, "initial position of the centre along the plate", "1", -INFINITY, INFINITY, 0, 0,
         TRIBO_PARAM_FIXED),
    REAL(gap0, "initial height of the lowest point above the plate", "1", 0, INFINITY, 1, 0,
         TRIBO_PARAM_FIXED),
    REAL(phi0, "initial orientation of the long axis", "rad", -INFINITY, INFINITY, 0, 0,
         TRIBO_PARAM_FIXED),
    REAL(drop_speed, "initial speed, straight down in the external frame", "1", 0, INFINITY, 1,
         0, TRIBO_PARAM_FIXED),
    REAL(Omega0, "initial spin", "rad", -INFINITY, INFINITY, 0, 0, TRIBO_PARAM_FIXED),
    INT(charge_model, "charge models: 0 none, 1 static, 2 sliding, 3 both", "1", 0, 3,
        TRIBO_PARAM_STRUCTURAL),
    INT(integrator, "integrator: 0 fixed-step RK4, 1 CVODE (Adams), 2 CVODE (BDF)", "1", 0, 2,
        TRIBO_PARAM_STRUCTURAL),
    REAL(dt, "step of the fixed-step integrator (at most 0.1: the contact period is 2 pi)", "1",
         0, 0.1, 0, 1, TRIBO_PARAM_FIXED),
    REAL(rtol, "relative tolerance of CVODE", "1", 1e-14, 1, 1, 0, TRIBO_PARAM_FIXED),
    REAL(atol, "absolute tolerance of CVODE", "1", 0, INFINITY, 0, 0, TRIBO_PARAM_FIXED),
};

#define N_PARAMS (sizeof PARAMS / sizeof PARAMS[0])

void tribo_scene_defaults(tribo_scene *s)
{
    memset(s, 0, sizeof *s);
    s->epsilon = 0.5;
    s->mu = 0.1;
    s->nu = 0.1;
    s->Gamma = 0.001;
    s->beta = 45.0;
    s->tau0 = 1.0;
    s->Sigma0 = 0.01;
    s->eta = 0.1;
    s->tau_r = 1.0;
    s->n_segments = 2000;
    s->v_reg = 1e-6; /* MODEL §3 */
    s->X0 = 0.0;
    s->gap0 = 0.0;
    s->phi0 = 0.0;
    s->drop_speed = 0.025;
    s->Omega0 = 0.0;
    s->charge_model = TRIBO_CHARGE_BOTH;
    /* CVODE at a tolerance that reaches the accuracy of the paper's dt = 8e-5 on the
       short-horizon state (docs/work_precision.md), 67x faster or more */
    s->integrator = TRIBO_INTEGRATOR_CVODE;
    s->dt = 8e-5;
    s->rtol = 1e-9;
    s->atol = 1e-11;
}

const tribo_param_info *tribo_param_table(size_t *count)
{
    if (count)
        *count = N_PARAMS;
    return PARAMS;
}

const tribo_param_info *tribo_param_find(const char *name)
{
    for (size_t i = 0; name && i < N_PARAMS; i++)
        if (strcmp(PARAMS[i].name, name) == 0)
            return &PARAMS[i];
    return NULL;
}

double tribo_param_read(const tribo_scene *scene, const tribo_param_info *p)
{
    const char *base = (const char *)scene + p->offset;
    if (p->is_integer) {
        int v;
        memcpy(&v, base, sizeof v);
        return (double)v;
    }
    double v;
    memcpy(&v, base, sizeof v);
    return v;
}

void tribo_param_write(tribo_scene *scene, const tribo_param_info *p, double value)
{
    char *base = (char *)scene + p->offset;
    if (p->is_integer) {
        int v = (int)value;
        memcpy(base, &v, sizeof v);
    } else {
        memcpy(base, &value, sizeof value);
    }
}

void tribo_param_range_text(const tribo_param_info *p, char *buf, size_t n)
{
    if (p->is_integer) {
        snprintf(buf, n, "an integer with %.0f <= %s <= %.0f", p->min, p->name, p->max);
        return;
    }
    const int has_lo = isfinite(p->min), has_hi = isfinite(p->max);
    if (has_lo && has_hi)
        snprintf(buf, n, "%g %s %s %s %g", p->min, p->min_inclusive ? "<=" : "<", p->name,
                 p->max_inclusive ? "<=" : "<", p->max);
    else if (has_lo)
        snprintf(buf, n, "%s %s %g (finite)", p->name, p->min_inclusive ? ">=" : ">", p->min);
    else if (has_hi)
        snprintf(buf, n, "%s %s %g (finite)", p->name, p->max_inclusive ? "<=" : "<", p->max);
    else
        snprintf(buf, n, "any finite number");
}

tribo_status tribo_param_check(const tribo_param_info *p, double v, char *msg, size_t msg_size)
{
    int ok = isfinite(v);
    if (ok && p->is_integer)
        ok = v == floor(v);
    if (ok)
        ok = p->min_inclusive ? v >= p->min : v > p->min;
    if (ok)
        ok = p->max_inclusive ? v <= p->max : v < p->max;
    if (ok)
        return TRIBO_OK;
    if (msg && msg_size) {
        char range[128];
        tribo_param_range_text(p, range, sizeof range);
        snprintf(msg, msg_size, "%s = %.17g is invalid: the valid range is %s", p->name, v,
                 range);
    }
    return TRIBO_ERR_INVALID_ARGUMENT;
}

tribo_status tribo_scene_validate(const tribo_scene *scene, char *msg, size_t msg_size)
{
    if (!scene) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "scene is NULL");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    for (size_t i = 0; i < N_PARAMS; i++) {
        tribo_status st = tribo_param_check(&PARAMS[i], tribo_param_read(scene, &PARAMS[i]), msg,
                                            msg_size);
        if (st != TRIBO_OK)
            return st;
    }
    return TRIBO_OK;
}
