/* integrator_fixed_step.c: the paper's fixed-step integration (model.md §7).
 *
 * Classical 4th-order Runge-Kutta on the first-order system of dynamics.h (not the
 * paper's Runge-Kutta-Nystrom: the tangential spring stretch is a first-order state
 * and the forces depend on the velocities, so the Nystrom form gains nothing). The
 * set-valued sign of the damped normal velocity (the contact point's vn = V + cx Omega, or
 * the centre's V) is regularised as tanh(vn / v_reg) (model.md §3), so is the rolling
 * torque's sign, tanh(Omega / v_reg) (§3c: a grain it holds creeps at |Omega| ~ v_reg, and
 * its run never ends at rest), and the stretch is clamped to the Coulomb limit after each
 * step.
 *
 * Steps lie on the grid t_base + k dt whatever times are asked for; the state at an
 * asked time between grid points is a partial step from the last one, not committed.
 *
 * The regularised sign is stiff within a few v_reg of vn = 0: there dvn/dtau has the rate
 * lambda = nu delta_y sech^2(vn / v_reg) / v_reg times the factor of Psi_N in dvn/dtau
 * (1 for the centre's V; for the contact point's vn at most 1 + (cx^2 + mu |cx| h) / I,
 * model.md §3), and RK4 is unstable once lambda h passes 2.79. Where a step could reach
 * that, the motion is sub-stepped (charging still once per step), and likewise where the
 * rolling torque's sign is stiff; elsewhere a step is one RK4 step.
 *
 * Charging follows the paper: a step is charged at its end point's contact. The frictional
 * work of a step that ends in flight is still booked into Sigma_s (model.md §5b).
 *
 * On a chute of finite length (model.md §9) a step that would carry the centre past its end
 * is cut where it crosses X = chute_length (end_run): the run ends there. With run_end =
 * first_liftoff a step from a point in contact to one in flight is cut the same way where the
 * lowest point's clearance G crosses 0, and the run ends there.
 */
#include "integrator.h"

#include "contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct fixed_step {
    double t_base;  /* start of the grid: 0, or where a tunable / input last changed */
    long long k;    /* steps taken on the grid */
} fixed_step;

static const tribo_force_law LAW = {.contact = TRIBO_CONTACT_BY_GEOMETRY,
                                    .normal = TRIBO_NORMAL_REGULARISED,
                                    .tangent = TRIBO_TANGENT_CLAMP,
                                    .roll = TRIBO_ROLL_REGULARISED};

/* Within this margin of RK4's real stability limit 2.79 */
#define STABLE_LAMBDA_H 2.0

/* The largest indentation a step of size h from p can reach: over the step delta_y and vn
   move by at most their rates times h (<= 0: the step cannot touch). */
static double largest_indentation(const tribo_point *p, double h)
{
    const double *y = p->y;
    return -y[TRIBO_IGAP] + h * (fabs(y[TRIBO_IV]) + fabs(p->contact.pose.cx * y[TRIBO_IOMEGA]));
}

/* The RK4 sub-steps a regularised sign needs where its rate is scale sech^2(w) / v_reg times
   gain, at w = w_min, the smallest |velocity| / v_reg the step allows. */
static int sign_substeps(const tribo_dyn_params *dp, double scale, double gain, double w_min, double h)
{
    if (w_min >= 20.0) /* sech^2 < 2e-17 */
        return 1;
    const double sech = 1.0 / cosh(w_min);
    const double n = ceil(scale * sech * sech / dp->v_reg * h / STABLE_LAMBDA_H * gain);
    return n > 1.0 ? (n < 1e6 ? (int)n : 1000000) : 1;
}

/* The sub-steps the normal dashpot's regularised sign needs (substeps_needed). */
static int normal_substeps(const tribo_dyn_params *dp, const tribo_point *p, double h)
{
    if (dp->nu == 0.0)
        return 1;
    const double *y = p->y;
    const tribo_contact_eval *c = &p->contact;
    const double dy_max = largest_indentation(p, h);
    if (dy_max <= 0.0)
        return 1;
    const double force_max = dy_max * (1.0 + dp->nu);
    double gain = 1.0, accel, vn;
    /* the loads: gravity, the input and a vibrating plate's inertial force (model.md §9b) */
    if (dp->damping_point == TRIBO_DAMPING_CENTRE) {
        accel = dp->Gamma + fabs(dp->F_N) + dp->vib_accel + force_max;
        vn = y[TRIBO_IV];
    } else {
        /* over every orientation |cx| <= 1 - eps, h <= 1 and |kappa| <= 2 (1 - eps) / eps, so
           over the step |cx| grows by at most h |kappa| |Omega| */
        const double spin = fabs(y[TRIBO_IOMEGA]) + h * dp->inv_inertia * force_max * (1.0 + dp->mu);
        const double kappa_max = 2.0 * (1.0 - dp->eps) / dp->eps;
        const double arm = fmin(1.0 - dp->eps, fabs(c->pose.cx) + h * kappa_max * spin);
        gain = 1.0 + dp->inv_inertia * arm * (arm + dp->mu);
        accel = dp->Gamma + fabs(dp->F_N) + dp->vib_accel + force_max * gain +
                kappa_max * spin * spin;
        vn = tribo_damped_velocity(dp, &c->pose, y);
    }
    const double v_min = fmax(0.0, fabs(vn) - accel * h) / dp->v_reg;
    return sign_substeps(dp, dp->nu * dy_max, gain, v_min, h);
}

/* How many RK4 sub-steps a step of size h from p needs for the rolling torque's regularised
   sign (model.md §3c): dOmega/dtau has the rate mu_r Psi_N sech^2(Omega / v_reg) / (I v_reg)
   there, for |Omega| as small as the step allows (the torques' arms are at most 1, the
   rolling torque's mu_r <= 1). */
static int roll_substeps(const tribo_dyn_params *dp, const tribo_point *p, double h)
{
    const double dy_max = largest_indentation(p, h);
    if (dy_max <= 0.0)
        return 1;
    const double force_max = dy_max * (1.0 + dp->nu);
    const double spin_rate_max = dp->inv_inertia * force_max * (1.0 + dp->mu + dp->mu_roll);
    const double w_min = fmax(0.0, fabs(p->y[TRIBO_IOMEGA]) - spin_rate_max * h) / dp->v_reg;
    return sign_substeps(dp, dp->inv_inertia * dp->mu_roll * force_max, 1.0, w_min, h);
}

/* How many RK4 sub-steps a step of size h from p needs to stay stable: the largest rate
   the regularised sign can have during the step, for |vn| as small as the step allows
   (and the rolling torque's, roll_substeps). Uses the contact already evaluated at p (the
   end of the last step). */
static int substeps_needed(const tribo_dyn_params *dp, const tribo_point *p, double h)
{
    const int roll = dp->mu_roll > 0.0 ? roll_substeps(dp, p, h) : 1;
    const int normal = normal_substeps(dp, p, h);
    return roll > normal ? roll : normal;
}
/* dy/dtau at time t: the motion, the charge models' quadratures integrated with it and, on a
   vibrating plate, the work of its inertial force (model.md §9b). */
static void rhs(const tribo_model *m, double t, const double *y, double *dydt)
{
    tribo_contact_eval ev;
    tribo_dyn_params at;
    const tribo_dyn_params *p = tribo_dyn_at(tribo_dynamics(m), t, &at);
    tribo_dynamics_rhs(p, &LAW, y, dydt, &ev);
    tribo_quadrature_rates(m, &ev, dydt + TRIBO_NMOTION);
    if (p->vib_slot)
        dydt[p->vib_slot] = tribo_vibration_power(p, y);
}

static void rk4(tribo_model *m, double t, double *y, double h)
{
    const int n = tribo_state_length(m);
    double k1[TRIBO_NSTATE_MAX], k2[TRIBO_NSTATE_MAX], k3[TRIBO_NSTATE_MAX], k4[TRIBO_NSTATE_MAX];
    double tmp[TRIBO_NSTATE_MAX];

    rhs(m, t, y, k1);
    for (int i = 0; i < n; i++)
        tmp[i] = y[i] + 0.5 * h * k1[i];
    rhs(m, t + 0.5 * h, tmp, k2);
    for (int i = 0; i < n; i++)
        tmp[i] = y[i] + 0.5 * h * k2[i];
    rhs(m, t + 0.5 * h, tmp, k3);
    for (int i = 0; i < n; i++)
        tmp[i] = y[i] + h * k3[i];
    rhs(m, t + h, tmp, k4);
    for (int i = 0; i < n; i++)
        y[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
    tribo_count(m, TRIBO_COUNT_RHS_EVALS, 4);
}

/* Hold the stretch within the Coulomb limit (model.md §3); in flight the limit is 0, so the
   stretch is 0 when contact is regained. The spring energy the clamp removes is
   dissipated by friction. Fills ev (with the forces at time t); returns the stretch before the
   clamp. */
static double clamp_stretch(const tribo_dyn_params *dp, double t, double *y, tribo_contact_eval *ev)
{
    tribo_dyn_params at;
    tribo_contact_at(tribo_dyn_at(dp, t, &at), &LAW, y, ev);
    const double dx = y[TRIBO_IDX];
    const double dx_held = tribo_clamp(dx, ev->limit);
    y[TRIBO_IDX] = dx_held;
    y[TRIBO_IWDISS] += 0.5 * (dx * dx - dx_held * dx_held);
    ev->psi_t = -dx_held;
    return dx;
}

/* One step of size h from p to next; the contact over the step is returned in sample
   (charged at the end point's contact for the whole step, as the paper does). */
static void step(tribo_model *m, const tribo_point *p, double h, tribo_point *next,
                 tribo_contact_sample *sample, int commit)
{
    const tribo_dyn_params *dp = tribo_dynamics(m);
    memcpy(next->y, p->y, sizeof next->y);
    next->t = p->t + h;
    const int n = substeps_needed(dp, p, h);
    tribo_contact_eval *ev = &next->contact;
    for (int k = 1; k < n; k++) {
        rk4(m, p->t + (k - 1) * (h / n), next->y, h / n);
        clamp_stretch(dp, p->t + k * (h / n), next->y, ev);
    }
    rk4(m, p->t + (n - 1) * (h / n), next->y, h / n);
    if (n > 1)
        tribo_count(m, TRIBO_COUNT_SUBSTEPS, n - 1);
    tribo_work(m, TRIBO_WORK_FIXED_STEP * n);

    const double dx = clamp_stretch(dp, next->t, next->y, ev);
    next->slipping = ev->in_contact && fabs(dx) >= ev->limit && (ev->limit > 0.0 || ev->vs != 0.0);

    tribo_book_interval(m, p, next, commit);
    tribo_charge_step(m, p, next, h, sample);
}

/* The ends of a run within a step (model.md §9), each a function of the point that crosses
   from below 0 to 0 or above there: the centre passing the end of the chute, X - L; the
   contact lost, the lowest point's clearance G (the contact is geometric: delta_y > 0). */
typedef double (*end_function)(const tribo_model *m, const tribo_point *p);

static double past_the_end(const tribo_model *m, const tribo_point *p)
{
    return p->y[TRIBO_IX] - tribo_dynamics(m)->chute_length;
}

static double clearance(const tribo_model *m, const tribo_point *p)
{
    (void)m;
    return p->y[TRIBO_IGAP];
}

/* Whether the run may end within any step: a step is then booked only once it is known not to. */
static int run_can_end(const tribo_model *m)
{
    return isfinite(tribo_dynamics(m)->chute_length) || tribo_dynamics(m)->end_at_liftoff;
}

/* The step from p that ends where f crosses 0, given that one of length h_past ends at or
   past it: its length is bracketed, by false position with the Illinois rule, to the
   rounding of the time, between a step that ends before the crossing and one that ends at
   or past it; the latter is the step taken. Deterministic: the same for every advance that
   meets it. Each length tried is the one an advance to its end time would take, t - p->t,
   so that advancing to the end found is this step bit for bit. */
static double crossing_step(tribo_model *m, const tribo_point *p, double h_past, end_function fn)
{
    tribo_point probe;
    tribo_contact_sample sample;
    double lo = 0.0, hi = h_past, f_lo = fn(m, p);
    step(m, p, h_past, &probe, &sample, 0);
    double f_hi = fn(m, &probe);
    int side = 0; /* which end the last two updates kept */
    for (int it = 0; it < 200 && f_hi > 0.0 && hi - lo > 2e-16 * (p->t + hi); it++) {
        double h = hi - f_hi * (hi - lo) / (f_hi - f_lo);
        if (!(h > lo && h < hi))
            h = 0.5 * (lo + hi);
        h = (p->t + h) - p->t;
        if (!(h > lo && h < hi))
            break; /* the bracket is one rounding of the time wide */
        step(m, p, h, &probe, &sample, 0);
        const double f = fn(m, &probe);
        if (f >= 0.0) {
            hi = h, f_hi = f;
            if (side == +1)
                f_lo *= 0.5;
            side = +1;
        } else {
            lo = h, f_lo = f;
            if (side == -1)
                f_hi *= 0.5;
            side = -1;
        }
    }
    return hi;
}

/* Where a step of length h_past from p to next ends the run, if it does: the length of the
   step to the first end it crosses (*why says which), or 0 if it crosses none. */
static double end_within(tribo_model *m, const tribo_point *p, const tribo_point *next,
                         double h_past, tribo_stop_reason *why)
{
    double h = 0.0;
    if (past_the_end(m, next) >= 0.0) {
        h = crossing_step(m, p, h_past, past_the_end);
        *why = TRIBO_STOP_EXIT;
    }
    if (tribo_dynamics(m)->end_at_liftoff && p->contact.in_contact && !next->contact.in_contact) {
        const double h_lift = crossing_step(m, p, h_past, clearance);
        if (h == 0.0 || h_lift < h) {
            h = h_lift;
            *why = TRIBO_STOP_LIFTOFF;
        }
    }
    return h;
}

/* Cut the step from the committed point at the end of the run found by end_within (length
   h, why), commit it and end the run. */
static tribo_status end_run(tribo_model *m, fixed_step *f, double h, tribo_stop_reason why)
{
    const tribo_point *p = tribo_committed(m);
    tribo_point end;
    tribo_contact_sample sample;
    step(m, p, h, &end, &sample, 1);
    tribo_commit(m, &end);
    tribo_charge_sample(m, &sample, TRIBO_CHARGE_COMMIT);
    tribo_count(m, TRIBO_COUNT_STEPS, 1);
    /* the grid starts at the end, so that a saved state's committed point is on it */
    f->t_base = end.t;
    f->k = 0;
    return tribo_stop_early(m, why);
}

static tribo_status create(tribo_model *m, void **data)
{
    (void)m;
    return (*data = calloc(1, sizeof(fixed_step))) ? TRIBO_OK : TRIBO_ERR_MEMORY;
}

static void destroy(void *data) { free(data); }

static tribo_status restart(tribo_model *m, void *data)
{
    fixed_step *f = data;
    tribo_point p = *tribo_committed(m);
    f->t_base = p.t;
    f->k = 0;
    /* the contact under this integrator's law (substeps_needed reads it) */
    tribo_dyn_params at;
    tribo_contact_at(tribo_dyn_at(tribo_dynamics(m), p.t, &at), &LAW, p.y, &p.contact);
    tribo_commit(m, &p);
    return TRIBO_OK;
}

/* Grid point k: computed one way everywhere, so that a time is on the grid or not alike
   for the advance and for a loaded state. */
static double grid(const fixed_step *f, long long k, double dt) { return f->t_base + (double)k * dt; }

/* A time that is a grid point up to this fraction of dt counts as that grid point: it is
   the same point computed another way (t + h + h ... against t + n h). */
#define GRID_SLACK 1e-9
/* The grid must stay resolved: t / dt below 2^45 leaves each step 2^7 roundings of t wide. */
#define GRID_MAX_STEPS 0x1p45

static tribo_status advance(tribo_model *m, void *data, double t)
{
    fixed_step *f = data;
    const double dt = tribo_get_scene(m)->dt;
    if (!(t / dt < GRID_MAX_STEPS))
        return tribo_fail(m, TRIBO_ERR_TIME,
                          "cannot advance the fixed step to t = %.17g: steps of dt = %g are not "
                          "resolved there (t / dt must stay below 2^45)",
                          t, dt);
    tribo_contact_sample sample;
    tribo_point next;
    tribo_stop_reason why;
    const int can_end = run_can_end(m);

    /* commit every grid point up to t, none after it; where the run can end, a step is
       booked (its assumption check counted) only once it is known not to end it */
    while (grid(f, f->k + 1, dt) <= t) {
        if (tribo_work_spent(m))
            return tribo_stop_early(m, TRIBO_STOP_WORK_LIMIT);
        step(m, tribo_committed(m), dt, &next, &sample, !can_end);
        if (can_end) {
            const double h = end_within(m, tribo_committed(m), &next, dt, &why);
            if (h > 0.0)
                return end_run(m, f, h, why);
            tribo_book_interval(m, tribo_committed(m), &next, 1);
        }
        f->k++;
        next.t = grid(f, f->k, dt); /* no drift over millions of steps */
        tribo_commit(m, &next);
        tribo_charge_sample(m, &sample, TRIBO_CHARGE_COMMIT);
        tribo_count(m, TRIBO_COUNT_STEPS, 1);
    }

    /* the end may lie within the next grid step, before t: the grid step tells */
    if (can_end && t > tribo_committed(m)->t) {
        const tribo_point *p = tribo_committed(m);
        step(m, p, dt, &next, &sample, 0);
        const double h = end_within(m, p, &next, dt, &why);
        if (h > 0.0 && p->t + h <= t)
            return end_run(m, f, h, why);
    }

    tribo_output_begin(m);
    const tribo_point *committed = tribo_committed(m);
    tribo_point out;
    if (t - committed->t <= GRID_SLACK * dt) {
        out = *committed;
        out.t = t;
        tribo_output_set(m, &out);
        return TRIBO_OK;
    }
    /* a time just before the next grid point is that grid point: its whole step, not
       committed (the next advance commits it, the same) */
    const double h = grid(f, f->k + 1, dt) - t <= GRID_SLACK * dt ? dt : t - committed->t;
    step(m, committed, h, &out, &sample, 0);
    out.t = t;
    tribo_output_set(m, &out);
    return tribo_charge_sample(m, &sample, TRIBO_CHARGE_PENDING);
}

static size_t state_size(const void *data)
{
    (void)data;
    return sizeof(double) + sizeof(long long);
}

static void state_save(const void *data, unsigned char *b)
{
    const fixed_step *f = data;
    memcpy(b, &f->t_base, sizeof f->t_base);
    memcpy(b + sizeof f->t_base, &f->k, sizeof f->k);
}

static tribo_status state_load(tribo_model *m, void *data, const unsigned char *b, double t_out)
{
    fixed_step *f = data;
    fixed_step saved;
    memcpy(&saved.t_base, b, sizeof saved.t_base);
    memcpy(&saved.k, b + sizeof saved.t_base, sizeof saved.k);
    const double dt = tribo_get_scene(m)->dt, t = tribo_committed(m)->t;
    /* the committed point is grid point k, and the output lies before grid point k + 1 */
    if (!(saved.t_base >= 0.0 && saved.t_base <= t) || saved.k < 0 ||
        !((double)saved.k < GRID_MAX_STEPS) || grid(&saved, saved.k, dt) != t ||
        !(t_out < grid(&saved, saved.k + 1, dt)))
        return tribo_fail(m, TRIBO_ERR_STATE,
                          "the fixed step's state is corrupt: its grid (from t = %.17g, step "
                          "%lld of dt = %g) does not hold the committed time %.17g and the "
                          "output time %.17g",
                          saved.t_base, saved.k, dt, t, t_out);
    *f = saved;
    return TRIBO_OK;
}

const tribo_integrator_ops tribo_fixed_step_ops = {
    create, destroy, restart, advance, state_size, state_save, state_load,
};
