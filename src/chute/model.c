/* model.c: life cycle of an instance, its parameters and inputs, what can be read, and the
   services its integrator works through (integrator.h). */
#include "model.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "charge_registry.h"
#include "param_table.h"

tribo_status tribo_fail(tribo_model *m, tribo_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m->error, sizeof m->error, fmt, ap);
    va_end(ap);
    return status;
}

/* The drop's velocity relative to the plate, in the plate's axes (U, V): model.md §7, §9, at
   drop_angle from the external vertical, towards down-slope when positive; §9b: given in
   the lab (drop_frame), the plate's velocity at the drop's phase, d/dtau of (A/a) sin(vib_omega
   tau + vib_phase) along the stroke, taken off. Returns whether it was taken off: a still
   plate's drop is the same in either frame, to the bit. */
static int drop_velocity(const tribo_scene *s, double *U, double *V)
{
    const double direction = s->beta + s->drop_angle;
    *U = s->drop_speed * sin(direction);
    *V = -s->drop_speed * cos(direction);
    if (s->drop_frame != TRIBO_DROP_FRAME_LAB || s->vib_accel == 0.0)
        return 0;
    const double plate_speed = s->vib_accel / s->vib_omega * cos(s->vib_phase);
    *U -= plate_speed * cos(s->vib_angle);
    *V -= plate_speed * sin(s->vib_angle);
    return 1;
}

void tribo_derive_params(tribo_model *m)
{
    const tribo_scene *s = &m->scene;
    tribo_dyn_params *d = &m->dyn;
    const double beta = s->beta; /* rad */
    d->eps = s->epsilon;
    d->eps2 = s->epsilon * s->epsilon;
    d->mu = s->mu;
    d->nu = s->nu;
    d->Gamma = s->Gamma;
    d->g_t = s->Gamma * sin(beta);
    d->g_n = s->Gamma * cos(beta);
    d->inv_inertia = 4.0 / (1.0 + d->eps2); /* model.md §4 */
    d->v_reg = s->v_reg;
    d->damping_point = s->damping_point;
    /* the tolerances CVODE and the event logic work to: the scene's, at most the loosest
       the event logic takes (model.md §3, "Tolerances") */
    d->rtol = fmin(s->rtol, TRIBO_RTOL_LOOSEST);
    d->atol = fmin(s->atol, TRIBO_ATOL_LOOSEST);
    d->chute_length = s->chute_length;
    d->end_at_liftoff = s->run_end == TRIBO_RUN_END_FIRST_LIFTOFF;
    d->rigid_stick = s->stick_model == TRIBO_STICK_RIGID;
    d->mu_roll = s->mu_roll;
    /* the drop's first impact: its speed and a fall of gap0 / cos(beta) at Gamma (model.md
       §7; gap0 = 0: the drop speed, exactly) */
    const double fall = s->gap0 > 0.0 ? 2.0 * s->Gamma * s->gap0 / cos(beta) : 0.0;
    double U, V;
    const double speed2 = drop_velocity(s, &U, &V) ? U * U + V * V : s->drop_speed * s->drop_speed;
    m->motion_scales = tribo_motion_scales_of(s->Gamma, sqrt(speed2 + fall));
    m->motion_decay_h = NAN; /* (the decay of the window before, if another) */
    /* model.md §9b: the plate's stroke; vib_slot is the instance's (set with its state) */
    d->vib_accel = s->vib_accel;
    d->vib_omega = s->vib_omega;
    d->vib_phase = s->vib_phase;
    d->vib_cos = cos(s->vib_angle);
    d->vib_sin = sin(s->vib_angle);
}

/* The initial point of the scene (model.md §7 by default); its contact is evaluated by the
   integrator's restart, under the integrator's own force law. */
static void initial_point(const tribo_model *m, tribo_point *p)
{
    const tribo_scene *s = &m->scene;
    tribo_pose pose;
    tribo_pose_at(m->dyn.eps2, s->phi0, &pose);
    memset(p, 0, sizeof *p);
    /* model.md §7: centre at the height of first contact (plus the gap), with the drop's
       velocity */
    double U, V;
    drop_velocity(s, &U, &V);
    p->y[TRIBO_IX] = s->X0;
    p->y[TRIBO_IY] = pose.h + s->gap0;
    p->y[TRIBO_IGAP] = s->gap0;
    p->y[TRIBO_IPHI] = s->phi0;
    p->y[TRIBO_IU] = U;
    p->y[TRIBO_IV] = V;
    p->y[TRIBO_IOMEGA] = s->Omega0;
    tribo_charging_start(&m->charging, s, p->charge_globals);
    p->motion.current = TRIBO_MOTION_FLIGHT;
}

/* ---- services for the integrators ------------------------------------------------------ */

const tribo_dyn_params *tribo_dynamics(const tribo_model *m) { return &m->dyn; }
const tribo_point *tribo_committed(const tribo_model *m) { return &m->committed; }
int tribo_state_length(const tribo_model *m) { return m->n_state; }

static void pending_clear(tribo_model *m)
{
    m->n_pending = 0;
    m->charges_out_valid = 0;
    m->pending_sums_valid = 0;
}

void tribo_commit(tribo_model *m, const tribo_point *p) { m->committed = *p; }
void tribo_output_begin(tribo_model *m) { pending_clear(m); }
void tribo_output_set(tribo_model *m, const tribo_point *p) { m->out = *p; }

void tribo_count(tribo_model *m, tribo_counter which, long long n)
{
    switch (which) {
    case TRIBO_COUNT_STEPS: m->stats.steps += n; break;
    case TRIBO_COUNT_RHS_EVALS: m->stats.rhs_evals += n; break;
    case TRIBO_COUNT_EVENTS: m->stats.events += n; break;
    case TRIBO_COUNT_RESTARTS: m->stats.restarts += n; break;
    case TRIBO_COUNT_SUBSTEPS: m->stats.substeps += n; break;
    }
}

/* The run is over: the particle left the chute, or lifted off (model.md §9), or came to rest
   (§3c). */
static tribo_status ended(tribo_model *m)
{
    if (m->ended == TRIBO_END_REST)
        return tribo_fail(m, TRIBO_ENDED,
                          "the grain came to rest on the chute at t = %.17g (%s = %.17g; "
                          "docs/model.md §3c): the run is over there; reset to run again",
                          m->out.t, tribo_quantity_name(TRIBO_QUANTITY_X), m->out.y[TRIBO_IX]);
    if (m->ended == TRIBO_END_LIFTOFF)
        return tribo_fail(m, TRIBO_ENDED,
                          "the particle lifted off the plate at t = %.17g (%s = %s: the run "
                          "ends at the first contact lost): the run is over there; reset to run "
                          "again",
                          m->out.t, TRIBO_PARAM_NAME(run_end),
                          TRIBO_PARAM_ITEM_NAME(run_end, TRIBO_RUN_END_FIRST_LIFTOFF));
    return tribo_fail(m, TRIBO_ENDED,
                      "the particle left the chute at t = %.17g (its centre passed %s = %s = "
                      "%.17g): the run is over there; reset to run again",
                      m->out.t, tribo_quantity_name(TRIBO_QUANTITY_X), TRIBO_PARAM_NAME(chute_length),
                      m->scene.chute_length);
}

/* The charges of a grain at rest are their limits for t -> infinity (model.md §3c): only the
   segments under its contact still charge. Each model's global states go to their limits at
   rest (tribo_charge_model.rest_limits: the sliding model's Sigma_s relaxes to Sigma0, no work
   being done; without it they hold still), and the segments under the contact (and the
   grain's bands there, §8c) take one sample of infinite duration at those limits, whose exact
   update (e^-inf = 0) leaves each at its saturation there. */
static tribo_status charge_at_rest(tribo_model *m)
{
    tribo_point *p = &m->committed;
    for (int i = 0; i < m->charging.n_models; i++) {
        const tribo_charge_slot *slot = &m->charging.slot[i];
        if (slot->selected && slot->model->rest_limits)
            slot->model->rest_limits(&m->scene, p->charge_globals + slot->globals_at);
    }
    if (!m->charging.any_selected)
        return TRIBO_OK;
    tribo_contact_sample sample = {.duration = INFINITY};
    double s_centre, half_width, speed;
    tribo_contact_kinematics k;
    tribo_probe_contact(m, p->y, &s_centre, &half_width, &speed, &k);
    tribo_pose g;
    tribo_pose_at(m->dyn.eps2, p->y[TRIBO_IPHI], &g);
    tribo_charging_patch(&m->charging, s_centre, half_width, g.h, &sample);
    const size_t bytes = (size_t)m->charging.n_globals * sizeof(double);
    memcpy(sample.globals_begin, p->charge_globals, bytes);
    memcpy(sample.globals_mid, p->charge_globals, bytes);
    memcpy(sample.globals_end, p->charge_globals, bytes);
    return tribo_charge_sample(m, &sample, TRIBO_CHARGE_COMMIT);
}

void tribo_work(tribo_model *m, double units) { m->work += units; }

int tribo_work_spent(const tribo_model *m) { return m->work >= (double)m->scene.work_limit; }

tribo_status tribo_stop_early(tribo_model *m, tribo_stop_reason why)
{
    if (why == TRIBO_STOP_REST) {
        m->ended = TRIBO_END_REST;
        const tribo_status st = charge_at_rest(m);
        if (st != TRIBO_OK)
            return st;
    }
    tribo_output_begin(m);
    tribo_output_set(m, &m->committed);
    if (why == TRIBO_STOP_REST)
        return ended(m);
    if (why == TRIBO_STOP_EXIT || why == TRIBO_STOP_LIFTOFF) {
        /* a lift-off found at or past the end of the chute (both within one step, or within
           the root finding's tolerance of each other) is the exit: the particle has left */
        const int past = !(m->committed.y[TRIBO_IX] < m->scene.chute_length);
        m->ended = why == TRIBO_STOP_EXIT || past ? TRIBO_END_EXIT : TRIBO_END_LIFTOFF;
        return ended(m);
    }
    return tribo_fail(m, TRIBO_INCOMPLETE,
                      "stopped early at t = %.17g: the advance spent its work limit (%s = %d "
                      "units of work; take shorter steps, or raise it)",
                      m->committed.t, TRIBO_PARAM_NAME(work_limit), m->scene.work_limit);
}

void tribo_warn(tribo_model *m, const char *message)
{
    if (m->log)
        m->log(m->log_user, 1, message);
}

/* Warnings past this many are counted but not logged one by one. */
#define LOGGED_VIOLATIONS 10

void tribo_book_interval(tribo_model *m, const tribo_point *from, tribo_point *to, int commit)
{
    const double h = to->t - from->t;
    const int in_contact = to->contact.in_contact;
    to->contact_time = from->contact_time + (in_contact ? h : 0.0);
    to->motion = from->motion;
    /* an impact is a contact made while the contact point approaches the plate, vn < 0 beyond
       its rounding (model.md §3b): a particle set down on it makes none */
    const double spin = to->contact.pose.cx * to->y[TRIBO_IOMEGA];
    if (in_contact && !from->contact.in_contact &&
        to->y[TRIBO_IV] + spin < -tribo_velocity_rounding(&m->dyn, to->y[TRIBO_IV], spin))
        to->motion.impacts++;
    if (in_contact && !from->contact.in_contact)
        to->motion.touchdowns++;
    if (!(h > 0.0))
        return;
    if (m->motion_decay_h != h) {
        m->motion_decay_h = h;
        m->motion_decay = exp(-h / m->motion_scales.window);
    }
    tribo_motion_update(&to->motion, &m->motion_scales, h, m->motion_decay, in_contact,
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
                     "t = %.9g: the contact is outside the model's assumptions: %s = %.4g "
                     "exceeds %.2g x min(%s = %g, rho_c = %.4g); the linear contact law and "
                     "the contact width are not meaningful there (counted in %s%s)",
                     to->t, tribo_quantity_name(TRIBO_QUANTITY_DELTA_Y), to->contact.delta_y,
                     TRIBO_INDENTATION_LIMIT, TRIBO_PARAM_NAME(epsilon), m->dyn.eps, rho_c,
                     tribo_quantity_name(TRIBO_QUANTITY_ASSUMPTION_WARNINGS),
                     n == LOGGED_VIOLATIONS ? "; further ones are counted, not logged" : "");
            m->log(m->log_user, 1, msg);
        }
    }
    to->motion.outside_assumptions = deep;
}

/* ---- charging services ------------------------------------------------------------------- */

static tribo_status pending_push(tribo_model *m, const tribo_contact_sample *sample)
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
    m->pending_sums_valid = 0;
    return TRIBO_OK;
}

/* The work of charging one segment value: each is held within the breakdown limit again
   where there is one (every model's limit follows Sigma_bd, model.md §8b). */
static double segment_work(const tribo_model *m)
{
    return TRIBO_WORK_SEGMENT_UPDATE + (isfinite(m->scene.Sigma_bd) ? TRIBO_WORK_SEGMENT_HELD : 0.0);
}

static int selected_models(const tribo_model *m)
{
    int models = 0;
    for (int k = 0; k < m->charging.n_models; k++)
        models += m->charging.slot[k].selected;
    return models;
}

/* The work of charging `values` segment values (each model's value of each segment; models
   of them per segment): each value, its band of the spheroid charged the same way (§8c),
   the band widened once per segment, and in instantaneous transfer whose globals move each
   value's own saturation where its segment left the contact (§5c). */
static double values_work(const tribo_model *m, int leave_by_edges, double values, int models)
{
    const int bands = m->charging.keep_bands;
    const int targets = m->scene.tau0 == 0.0 && leave_by_edges;
    double work = values * segment_work(m) * (bands ? 2.0 : 1.0);
    if (targets)
        work += values * TRIBO_WORK_LEAVE_TARGET;
    if (bands && models > 0)
        work += values / models * TRIBO_WORK_BAND;
    return work;
}

tribo_status tribo_charge_sample(tribo_model *m, const tribo_contact_sample *sample,
                                 tribo_charge_destination where)
{
    if (!m->charging.any_selected)
        return TRIBO_OK;
    tribo_contact_sample stamped;
    if (!sample->episode) {
        /* a rest's: inside the committed point's contact episode (§8e) */
        stamped = *sample;
        stamped.episode = m->committed.motion.touchdowns + 1;
        sample = &stamped;
    }
    if (where == TRIBO_CHARGE_PENDING)
        return pending_push(m, sample);
    const long updates = tribo_charging_apply(&m->charging, &m->scene, sample, TRIBO_CHARGE_COMMIT);
    tribo_work(m, values_work(m, sample->leave_by_edges, (double)updates, selected_models(m)));
    return TRIBO_OK;
}

void tribo_quadrature_rates(const tribo_model *m, const tribo_contact_eval *ev, double *rates)
{
    if (!ev->in_contact) {
        for (int k = 0; k < m->charging.n_quadratures; k++)
            rates[k] = 0.0;
        return;
    }
    const tribo_contact_kinematics k = {m->dyn.mu, ev->delta_y, ev->vs,
                                        tribo_contact_curvature_radius(m->dyn.eps2, ev->pose.h),
                                        ev->pose.h};
    tribo_charging_quadrature_rates(&m->charging, &k, rates);
}

void tribo_charge_step(tribo_model *m, const tribo_point *from, tribo_point *to, double h,
                       tribo_contact_sample *sample)
{
    if (!m->charging.any_selected) {
        memcpy(to->charge_globals, from->charge_globals, sizeof to->charge_globals);
        return;
    }
    tribo_charging_step(&m->charging, &m->scene, &to->contact.pose, to->contact.delta_y, h,
                        from->y + TRIBO_NMOTION, to->y + TRIBO_NMOTION, from->charge_globals,
                        to->charge_globals, sample);
    /* the step's contact is its end point's, and so is its episode (§8e) */
    sample->episode = to->motion.touchdowns + 1;
}

void tribo_probe_contact(const tribo_model *m, const double *y, double *s_centre,
                         double *half_width, double *centre_speed, tribo_contact_kinematics *k)
{
    const double eps = m->dyn.eps, eps2 = m->dyn.eps2;
    tribo_pose g;
    tribo_pose_at(eps2, y[TRIBO_IPHI], &g);
    const double t_c = tribo_contact_parameter(eps, &g);
    const double rho_c = tribo_contact_curvature_radius(eps2, g.h);
    /* in a contact phase the contact exists even where rounding gives delta_y <= 0 */
    const double dy = fmax(0.0, -y[TRIBO_IGAP]);
    *s_centre = tribo_arclength_at(&m->charging.arc, t_c);
    *half_width = sqrt(rho_c * dy);
    /* ds_c/dtau = |boundary speed at t_c| |dt_c/dphi| |Omega| = (eps / h)(eps / h^2) |Omega|:
       the contact runs along the boundary at the radius of curvature times the spin */
    *centre_speed = rho_c * fabs(y[TRIBO_IOMEGA]);
    k->mu = m->dyn.mu;
    k->delta_y = dy;
    k->vs = y[TRIBO_IU] + g.h * y[TRIBO_IOMEGA];
    k->rho_c = rho_c;
    k->h = g.h;
}

typedef struct sweep_target {
    tribo_model *m;
    tribo_charge_destination where;
    const tribo_contact_probe *probe;
} sweep_target;

/* The sweep's samples, each booked as work per charge model; a pending one also for the
   values it will charge when the output is read or committed (tribo_charge_sample books a
   committed one's). */
static int sink(void *ctx, const tribo_contact_sample *sample)
{
    sweep_target *s = ctx;
    tribo_model *m = s->m;
    const int models = selected_models(m);
    double work = TRIBO_WORK_SAMPLE * models +
                  (m->charging.keep_bands ? TRIBO_WORK_SAMPLE_BAND : 0.0);
    if (s->where == TRIBO_CHARGE_PENDING)
        work += values_work(m, sample->leave_by_edges, (double)models * (double)sample->count,
                            models);
    tribo_work(m, work);
    /* a sweep runs inside one contact phase, begun at or before the committed point (§8e) */
    tribo_contact_sample stamped = *sample;
    stamped.episode = m->committed.motion.touchdowns + 1;
    return tribo_charge_sample(m, &stamped, s->where) != TRIBO_OK;
}

/* The integrator's probe, each look at the contact booked as work. */
static void counted_probe(void *ctx, double t, double *s_centre, double *half_width,
                          double *centre_speed, tribo_contact_kinematics *k)
{
    sweep_target *s = ctx;
    tribo_work(s->m, TRIBO_WORK_PROBE);
    s->probe->at(s->probe->ctx, t, s_centre, half_width, centre_speed, k);
}

tribo_status tribo_charge_sweep(tribo_model *m, const tribo_contact_probe *probe, double a,
                                double b, tribo_point *p, tribo_charge_destination where,
                                double *reached)
{
    *reached = b;
    if (!m->charging.any_selected)
        return TRIBO_OK;
    sweep_target target = {m, where, probe};
    const tribo_contact_probe counted = {counted_probe, &target};
    /* a segment covered costs the sweep's budget what it costs the work limit, relative to
       one value charged per model (the budget's unit): so that the step a sweep ends books
       about the same work whatever the charging of a segment involves (1 exactly where it
       is one value per model) */
    const int models = selected_models(m);
    const double cell_cost = TRIBO_SWEEP_CELL_COST * values_work(m, 1, models, models) /
                             (models * segment_work(m));
    if (tribo_charging_sweep(&m->charging, &m->scene, &counted, a, b, m->dyn.rtol, m->dyn.atol,
                             p->y + TRIBO_NMOTION, p->charge_globals, sink, &target,
                             TRIBO_SWEEP_BUDGET, cell_cost, reached) != 0)
        return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
    return TRIBO_OK;
}

/* Apply the pending charge updates to the committed charges and make the output point the
   committed one (before a tunable or an input changes there). */
static void commit_output(tribo_model *m)
{
    for (size_t i = 0; i < m->n_pending; i++)
        tribo_charging_apply(&m->charging, &m->scene, &m->pending[i], TRIBO_CHARGE_COMMIT);
    m->committed = m->out;
    pending_clear(m);
}

/* Start the integrator afresh from the committed point, which is also the output now. */
static tribo_status restart_here(tribo_model *m)
{
    const tribo_status st = m->integrator->restart(m, m->integrator_data);
    m->out = m->committed;
    pending_clear(m);
    return st;
}

/* ---- life cycle -------------------------------------------------------------------------------- */

static void report(char *err, size_t err_size, const char *msg)
{
    if (err && err_size)
        snprintf(err, err_size, "%s", msg);
}

tribo_model *tribo_create_from_parts(const tribo_scene *scene, const tribo_parts *parts,
                                     const tribo_model *like, char *err, size_t err_size)
{
    char msg[512];
    if (!scene || !parts) {
        report(err, err_size, scene ? "parts is NULL" : "scene is NULL");
        return NULL;
    }
    const tribo_charge_model *const *models = parts->charge_models;
    const int n_models = parts->n_charge_models;
    /* the scene is validated here, once, whoever made the parts */
    if (tribo_scene_validate(scene, msg, sizeof msg) != TRIBO_OK) {
        report(err, err_size, msg);
        return NULL;
    }
    if (n_models < 32 && parts->charge_selection >> n_models) {
        snprintf(msg, sizeof msg, "charge models selected (bits 0x%x) beyond the %d of the set",
                 parts->charge_selection, n_models);
        report(err, err_size, msg);
        return NULL;
    }
    const tribo_integrator_ops *integrator = parts->integrator;
    if (!integrator) {
        snprintf(msg, sizeof msg, "%s = %d is not a known integrator", TRIBO_PARAM_NAME(integrator),
                 scene->integrator);
        report(err, err_size, msg);
        return NULL;
    }
    tribo_model *m = calloc(1, sizeof *m);
    if (!m) {
        report(err, err_size, "out of memory");
        return NULL;
    }
    m->scene = *scene;
    tribo_derive_params(m);
    const tribo_arclength *like_arc = like && like->charging.arc.s ? &like->charging.arc : NULL;
    const int st = tribo_charging_init(&m->charging, models, n_models, parts->charge_selection,
                                       scene->epsilon, scene->n_segments,
                                       scene->grain_geometry == TRIBO_GRAIN_SPHEROID, like_arc);
    if (st != 0) {
        snprintf(msg, sizeof msg,
                 st == -1 ? "out of memory (%s = %d)"
                          : "the charge models need more global states or quadratures than a "
                            "point holds (%s = %d)",
                 TRIBO_PARAM_NAME(n_segments), scene->n_segments);
        report(err, err_size, msg);
        tribo_free(m);
        return NULL;
    }
    m->n_state = TRIBO_NMOTION + m->charging.n_quadratures;
    if (tribo_vibrating(&m->dyn)) /* W_vib, last (dynamics.h; model.md §9b) */
        m->dyn.vib_slot = m->n_state++;
    m->integrator = integrator;
    if (integrator->create(m, &m->integrator_data) != TRIBO_OK || tribo_reset(m) != TRIBO_OK) {
        report(err, err_size, m->error[0] ? m->error : "out of memory");
        tribo_free(m);
        return NULL;
    }
    return m;
}

void tribo_free(tribo_model *m)
{
    if (!m)
        return;
    if (m->integrator && m->integrator_data)
        m->integrator->destroy(m->integrator_data);
    tribo_charging_free(&m->charging);
    free(m->pending);
    free(m);
}

void tribo_set_logger(tribo_model *m, tribo_log_fn fn, void *user)
{
    if (!m)
        return;
    m->log = fn;
    m->log_user = user;
}

tribo_status tribo_reset(tribo_model *m)
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    initial_point(m, &m->committed);
    m->ended = 0;
    tribo_charging_reset(&m->charging, &m->scene);
    memset(&m->stats, 0, sizeof m->stats);
    m->error[0] = '\0';
    return restart_here(m);
}

tribo_status tribo_check_outputs(tribo_model *m)
{
    if (!tribo_pending_sums(m))
        return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++) {
        const double v = tribo_get(m, (tribo_quantity)q);
        if (!isfinite(v))
            return tribo_fail(m, TRIBO_ERR_INTEGRATOR, "%s = %g at t = %.17g is not a finite number",
                              tribo_quantity_name((tribo_quantity)q), v, m->out.t);
    }
    return TRIBO_OK;
}

tribo_status tribo_advance(tribo_model *m, double t)
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (!isfinite(t) || t < m->out.t)
        return tribo_fail(m, TRIBO_ERR_TIME,
                          "cannot advance to t = %.17g: the instance is at t = %.17g", t,
                          m->out.t);
    if (t > TRIBO_TIME_MAX)
        return tribo_fail(m, TRIBO_ERR_TIME,
                          "cannot advance to t = %.17g: beyond t = %g the time is not resolved "
                          "finely enough to integrate",
                          t, TRIBO_TIME_MAX);
    if (m->ended)
        return t > m->out.t ? ended(m) : TRIBO_OK;
    m->work = 0.0;
    const tribo_status st = m->integrator->advance(m, m->integrator_data, t);
    if (st != TRIBO_OK && st != TRIBO_INCOMPLETE && st != TRIBO_ENDED)
        return st;
    const tribo_status checked = tribo_check_outputs(m);
    if (checked == TRIBO_ERR_INTEGRATOR) {
        /* one output is enough to say so; the motion or the charges overflowed */
        char what[sizeof m->error];
        memcpy(what, m->error, sizeof what);
        return tribo_fail(m, TRIBO_ERR_INTEGRATOR,
                          "the integration failed: %s (the motion or the charges overflowed); "
                          "reset the instance",
                          what);
    }
    return checked != TRIBO_OK ? checked : st;
}

tribo_status tribo_advance_fully(tribo_model *m, double t)
{
    tribo_status st;
    while ((st = tribo_advance(m, t)) == TRIBO_INCOMPLETE)
        ;
    return st;
}

tribo_status tribo_set_param(tribo_model *m, const char *name, double value)
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    const tribo_param_info *p = tribo_param_find(name);
    if (!p && tribo_param_retired_why(name))
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT, "%s", tribo_param_retired_why(name));
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
    if (m->ended)
        return ended(m);
    commit_output(m);
    tribo_param_write(&m->scene, p, value);
    tribo_derive_params(m);
    return restart_here(m);
}

tribo_status tribo_set_inputs(tribo_model *m, const double values[TRIBO_INPUT_COUNT])
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (!values)
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT, "the inputs' values are NULL");
    if (tribo_params_check(tribo_input_table(NULL), TRIBO_INPUT_COUNT, values, m->error,
                           sizeof m->error) != TRIBO_OK)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (values[TRIBO_INPUT_F_T] == m->dyn.F_T && values[TRIBO_INPUT_F_N] == m->dyn.F_N)
        return TRIBO_OK;
    if (m->ended)
        return ended(m);
    commit_output(m);
    m->dyn.F_T = values[TRIBO_INPUT_F_T];
    m->dyn.F_N = values[TRIBO_INPUT_F_N];
    return restart_here(m);
}

tribo_status tribo_set_external_force(tribo_model *m, double F_T, double F_N)
{
    const double values[TRIBO_INPUT_COUNT] = {[TRIBO_INPUT_F_T] = F_T, [TRIBO_INPUT_F_N] = F_N};
    return tribo_set_inputs(m, values);
}

const tribo_scene *tribo_get_scene(const tribo_model *m) { return m ? &m->scene : NULL; }

const char *tribo_last_error(const tribo_model *m) { return m ? m->error : "the instance is NULL"; }

void tribo_get_stats(const tribo_model *m, tribo_stats *s)
{
    if (s)
        *s = m ? m->stats : (tribo_stats){0};
}

/* ---- what can be read ------------------------------------------------------------------------ */

double tribo_get(tribo_model *m, tribo_quantity which)
{
    if (!m)
        return NAN;
    const tribo_point *p = &m->out;
    switch (which) {
#define TRIBO_TIME(id, name, vr, unit, description, value) \
    case TRIBO_QUANTITY_##id: return (value);
#define TRIBO_OUTPUT(id, name, type, vr, unit, description, value) \
    case TRIBO_QUANTITY_##id: return (value);
#include "quantities.def"
    case TRIBO_QUANTITY_COUNT: break;
    }
    return NAN;
}

const char *tribo_quantity_name(tribo_quantity q)
{
    static const char *const names[TRIBO_QUANTITY_COUNT] = {
#define TRIBO_TIME(id, name, ...) [TRIBO_QUANTITY_##id] = name,
#define TRIBO_OUTPUT(id, name, ...) [TRIBO_QUANTITY_##id] = name,
#include "quantities.def"
    };
    return (unsigned)q < TRIBO_QUANTITY_COUNT ? names[q] : NULL;
}

int tribo_includes_charge_model(const tribo_model *m, tribo_segment_charge which)
{
    return m && (unsigned)which < (unsigned)m->charging.n_models && m->charging.slot[which].selected;
}

tribo_status tribo_get_segment_charges(tribo_model *m, tribo_segment_charge which, double *out,
                                       size_t n)
{
    if (!m)
        return TRIBO_ERR_INVALID_ARGUMENT;
    if (!out)
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT, "the segment array to copy into is NULL");
    if ((unsigned)which >= (unsigned)m->charging.n_models || !m->charging.slot[which].segments)
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT,
                          "the scene does not include the %s charge model",
                          (unsigned)which < (unsigned)m->charging.n_models
                              ? m->charging.slot[which].model->name
                              : "requested");
    if (n != (size_t)m->charging.n)
        return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT,
                          "segment array of %zu values given, %s = %d", n,
                          TRIBO_PARAM_NAME(n_segments), m->charging.n);
    if (!tribo_charges_out(m))
        return tribo_fail(m, TRIBO_ERR_MEMORY, "out of memory");
    const tribo_charge_slot *slot = &m->charging.slot[which];
    const tribo_charge_view v = tribo_charge_view_of(m, which);
    slot->model->segment_values(&m->scene, v.globals,
                                m->n_pending ? slot->segments_out : slot->segments, out, v.n);
    return TRIBO_OK;
}
