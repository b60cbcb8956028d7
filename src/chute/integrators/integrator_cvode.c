/* integrator_cvode.c: event-driven integration with SUNDIALS CVODE.
 *
 * The force law of model.md §3 is smooth between switches, so CVODE (Adams, or BDF)
 * integrates one phase at a time and its root finding locates every switch:
 *
 *   flight                      -> contact        at delta_y = 0 (going up)
 *   contact                     -> flight         at delta_y = 0 (going down)
 *   normal sign s = -1 / +1     -> the other sign, or normal lock, at vn = 0
 *   normal lock (vn = 0,        -> s = +1 / -1    when Psi_N* leaves [dy(1-nu), dy(1+nu)],
 *     delta_y held)                               or a slipping lock's A reaches 0
 *   stick                       -> slip           at |delta_x| = mu Psi_N
 *   slip                        -> stick          when the stretch would leave the limit
 *                                                 (sigma vs falls below d(mu Psi_N)/dtau)
 *
 * (vn = V + cx Omega is the contact point's normal velocity; with damping_point = 1 the
 * centre's V takes its place and the lock holds Y, model.md §3.) At each switch the new
 * phase is set, the resets of model.md §3 applied (delta_x = 0 on a new contact, the
 * stretch held within the new limit), and CVODE restarted there.
 *
 * The phases, their switch functions and what happens at a switch are force_phases.c's;
 * this file drives CVODE through them. A switch function that dips past zero and back
 * within one step is caught on the dense output too (find_switch).
 *
 * On a vibrating plate with Adams the contact phases are taken by DOP853 instead (dop853.h,
 * docs/integrators.md): a feeder's grain has an impact a cycle, each with some four switches,
 * and each switch restarted CVODE at order 1 with a tiny first step; a one-step method
 * restarts at no cost. Its switches are all found on its dense output by find_switch, and its
 * right-hand side continues the contact's law past the lift-off (past_liftoff, dynamics.h).
 * The flights are closed-form either way; a still plate and BDF keep CVODE.
 *
 * Charging does not limit the step: both charge models are swept along each step from
 * CVODE's dense output, cut where the contact's edges cross segment boundaries, so that
 * each segment's contact time is exact to the tolerances (charging.c, model.md §5).
 *
 * Like the fixed step, the committed integration does not depend on the times asked
 * for: steps are taken in CV_ONE_STEP mode, charges are committed one whole step at a
 * time, and the state at an asked time comes from the dense output of the open step.
 * The state can be saved because CVODE is deterministic: the bytes hold the point where
 * CVODE was last restarted and the number of steps since, which a load replays.
 *
 * On a chute of finite length (model.md §9) the centre passing its end is one more root
 * (TRIBO_SWITCH_EXIT): the step that reaches it is committed, CVODE is restarted there (so
 * that the saved state is the exit point) and the run ends. With run_end = first_liftoff the
 * first switch from contact to flight ends the run the same way, at the located switch; so
 * does the event after which the grain is at rest (model.md §3c: the normal lock, the rigid
 * stick and the rolling lock at once, whose switch functions are then constant), or a
 * (re)start there.
 */
#include "integrator.h"

#include "contact.h"
#include "dop853.h"
#include "flight.h"
#include "force_phases.h"

#include <cvode/cvode.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#define N_ROOTS TRIBO_N_SWITCHES

/* A restart every so many steps bounds the replay a state load costs. */
#define STEPS_PER_RESTART 2000
/* Guards against runaway integration. */
#define MAX_EVENTS_AT_ONE_INSTANT 64
#define MAX_EVENTS_IN_A_ROW 100000
#define MAX_STEPS_PER_TIME_UNIT 1e6

typedef tribo_force_law phase; /* see force_phases.h */

typedef struct cvode_integrator {
    tribo_model *m;
    const tribo_dyn_params *dyn; /* the instance's, kept up to date by it */
    int n;                       /* components of y: the motion and the quadratures */
    SUNContext ctx;
    void *mem;
    N_Vector y, dky, abstol;
    SUNNonlinearSolver nls;
    SUNMatrix jac;
    SUNLinearSolver ls;
    phase phase;
    /* a vibrating plate's contact phases are taken by DOP853 (with Adams): each of an impact's
       switches restarts the integration, which costs a one-step method nothing and CVODE a
       climb from order 1 */
    int one_step;
    tribo_dop853 dop;
    double h_max; /* the longest step since the restart */
    int replaying; /* re-taking saved steps: no counting, no charging */
    double rhs_work; /* the work of a right-hand side (integrator.h): Adams's or BDF's */

    /* a flight is taken in closed form (flight.h), in pieces: the open piece's start, and
       how many pieces the flight has taken since its restart */
    tribo_flight flight;
    long long flight_pieces;

    /* where CVODE was last (re)started, and the steps taken since */
    double t_restart;
    double y_restart[TRIBO_NSTATE_MAX];
    long long steps_since_restart;

    /* CVODE's interpolant over its last step, as a Taylor polynomial about t_n:
       taylor[k] = y^(k)(t_n) / k!, k = 0..order (the same polynomial as CVodeGetDky's,
       evaluated without N_Vector calls, since the charging sweep probes it often) */
    double taylor_t;
    int taylor_order;
    double taylor[13][TRIBO_NSTATE_MAX];

    /* the open step: from m->committed.t to t_end, not yet committed */
    int open;
    double t_end;
    double y_end[TRIBO_NSTATE_MAX];
    int ends_at_root;
    int ends_early; /* ended where its charging sweep spent its budget: CVODE restarts there */
    int roots[N_ROOTS];
    tribo_stop_reason ending; /* why close_step ended the run (when it returns TRIBO_ENDED) */

    /* runaway guards */
    double last_event_t;
    int events_at_instant;
    long long events_in_a_row;

    char message[256]; /* CVODE's last error message */
    const char *failed_call; /* the SUNDIALS call of the set-up that failed (create) */
} cvode_integrator;

/* ---- the phase's right-hand side and root functions ---------------------------------- */

/* The dynamics at time t: the instance's, with the plate's inertial force then on a vibrating
   plate (model.md §9b). */
static const tribo_dyn_params *dyn_at(const cvode_integrator *c, double t, tribo_dyn_params *at)
{
    return tribo_dyn_at(c->dyn, t, at);
}

static int roots(sunrealtype t, N_Vector y, sunrealtype *g, void *user)
{
    cvode_integrator *c = user;
    tribo_dyn_params at;
    tribo_switch_functions(dyn_at(c, t, &at), &c->phase, N_VGetArrayPointer(y), g);
    return 0;
}

static void evaluate(void *user, double t, const double *state, double *dydt)
{
    cvode_integrator *c = user;
    tribo_dyn_params at;
    const tribo_dyn_params *p = dyn_at(c, t, &at);
    if (c->one_step) { /* (a vibrating plate's: p is the copy `at`) */
        at.past_liftoff = 1;
        p = &at;
    }
    tribo_dynamics_rhs(p, &c->phase, state, dydt, NULL);
    /* the charge models' quadratures are integrated by the charging sweep, so that they
       do not steer the steps: here they are constant */
    for (int i = TRIBO_NMOTION; i < c->n; i++)
        dydt[i] = 0.0;
    if (p->vib_slot)
        dydt[p->vib_slot] = tribo_vibration_power(p, state);
    if (!c->replaying) {
        tribo_count(c->m, TRIBO_COUNT_RHS_EVALS, 1);
        tribo_work(c->m, c->rhs_work);
    }
}

static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
    evaluate(user, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    return 0;
}

/* ---- CVODE set-up -------------------------------------------------------------------------- */

static void error_handler(int code, const char *module, const char *function, char *msg, void *user)
{
    cvode_integrator *c = user;
    snprintf(c->message, sizeof c->message, "%s %s (%d): %s", module, function, code, msg);
    if (code == CV_WARNING)
        tribo_warn(c->m, c->message);
}

/* A contact-point normal lock holds delta_y and vn = 0 (model.md §3), the rigid stick also
   vs = 0 (§3b), a creep vn = 0 with delta_y on its band's edge. The lock's indentation does
   not move (dG/dtau = 0); the rest CVODE follows to its tolerances, and over many steps that
   error would add up, so the points the phase commits, restarts from and shows are put back
   on them: V = -cx Omega; a creep's G = -Psi_N* / (1 - nu s); Y = G + h(phi); in the rigid
   stick the contact point stopped (tribo_stop_contact_point) and the stretch at its
   quasi-static value -Psi_T*, the energy that stretch stores booked with it, so that
   E + work_dissipated does not change by it (the constraint forces do no work). Putting a
   point back twice changes nothing. The centre dashpot's lock holds Y and V exactly
   (dY/dtau = dV/dtau = 0), and G = Y - h(phi). t: the time of y (the forces of a vibrating
   plate's rigid stick are those then). */
static void hold_phase(const cvode_integrator *c, double t, double *y)
{
    if (!tribo_touching(&c->phase) || !tribo_locked(&c->phase))
        return;
    tribo_pose g;
    tribo_pose_at(c->dyn->eps2, y[TRIBO_IPHI], &g);
    if (c->dyn->damping_point == TRIBO_DAMPING_CENTRE) {
        y[TRIBO_IGAP] = y[TRIBO_IY] - g.h;
        return;
    }
    const int rigid = c->phase.tangent == TRIBO_TANGENT_RIGID;
    if (rigid)
        tribo_stop_contact_point(c->dyn, &c->phase, &g, y);
    else
        y[TRIBO_IV] = -(g.cx * y[TRIBO_IOMEGA]);
    if (!rigid && c->phase.normal == TRIBO_NORMAL_LOCK) {
        y[TRIBO_IY] = g.h + y[TRIBO_IGAP];
        return;
    }
    tribo_contact_eval ev;
    tribo_dyn_params at;
    tribo_contact_at(dyn_at(c, t, &at), &c->phase, y, &ev);
    if (c->phase.normal == TRIBO_NORMAL_CREEP)
        y[TRIBO_IGAP] = -ev.delta_y;
    y[TRIBO_IY] = g.h + y[TRIBO_IGAP];
    if (rigid) {
        const double dx = y[TRIBO_IDX];
        y[TRIBO_IWDISS] += 0.5 * (dx * dx - ev.psi_t * ev.psi_t);
        y[TRIBO_IDX] = -ev.psi_t;
    }
}

/* The longest step: the time in which the steady loads (gravity and the inputs) move a
   particle from rest by 5e-4 semi-axes, sqrt(1e-3 / load), but at least 1 (the paper's
   scenes, Gamma >= 1e-3, keep 1; the contact's own period, 2 pi, CVODE resolves itself). The
   switch functions are sampled within each step (find_switch): a step of that
   length leaves nothing between the samples. A physical particle has a tiny Gamma (1e-8 for
   a 1 mm polymer grain on steel): a step of 1 would then take ~1e6 steps to cross a chute
   the slow motion crosses in ~1e3 (model.md §8, §9). A vibrating plate's inertial force is
   one of those loads (model.md §9b). */
static double slow_step(const tribo_dyn_params *p)
{
    return fmax(1.0, sqrt(1e-3 / (p->Gamma + fabs(p->F_T) + fabs(p->F_N) + p->vib_accel)));
}

/* (Re)start at (t, y) in phase ph: a flight in closed form, a contact with CVODE. */
static tribo_status restart_at(cvode_integrator *c, double t, const double *y, const phase *ph)
{
    tribo_model *m = c->m;
    c->phase = *ph;
    c->t_restart = t;
    memcpy(c->y_restart, y, sizeof c->y_restart);
    c->steps_since_restart = 0;
    c->open = 0;
    c->ends_early = 0;
    if (!tribo_touching(ph)) {
        tribo_flight_start(&c->flight, c->dyn, t, y, c->n);
        c->flight_pieces = 0;
        if (!c->replaying)
            tribo_count(m, TRIBO_COUNT_RESTARTS, 1);
        return TRIBO_OK;
    }
    /* a rotating particle in flight must not swing its lowest point through the plate and
       back within one step unseen: 0.2 rad per step at most */
    const double spin = fabs(y[TRIBO_IOMEGA]);
    const double hmax = spin > 0.0 ? fmin(0.2 / spin, slow_step(c->dyn)) : slow_step(c->dyn);
    if (c->one_step) {
        c->h_max = hmax;
        tribo_dop853_start(&c->dop, evaluate, c, c->n, t, y, c->dyn->rtol,
                           N_VGetArrayPointer(c->abstol), hmax);
        if (!c->replaying)
            tribo_count(m, TRIBO_COUNT_RESTARTS, 1);
        return TRIBO_OK;
    }
    memcpy(N_VGetArrayPointer(c->y), y, (size_t)c->n * sizeof(double));
    int dir[N_ROOTS];
    tribo_switch_directions(c->dyn, ph, dir);
    if (CVodeReInit(c->mem, t, c->y) != CV_SUCCESS || CVodeSetRootDirection(c->mem, dir) != CV_SUCCESS ||
        CVodeSetMaxStep(c->mem, hmax) != CV_SUCCESS)
        return tribo_fail(m, TRIBO_ERR_INTEGRATOR, "CVODE restart failed at t = %.17g: %s", t,
                          c->message);
    if (!c->replaying)
        tribo_count(m, TRIBO_COUNT_RESTARTS, 1);
    return TRIBO_OK;
}

static void destroy(void *data)
{
    cvode_integrator *c = data;
    if (!c)
        return;
    CVodeFree(&c->mem);
    if (c->nls)
        SUNNonlinSolFree(c->nls);
    if (c->ls)
        SUNLinSolFree(c->ls);
    if (c->jac)
        SUNMatDestroy(c->jac);
    if (c->y)
        N_VDestroy(c->y);
    if (c->dky)
        N_VDestroy(c->dky);
    if (c->abstol)
        N_VDestroy(c->abstol);
    if (c->ctx)
        SUNContext_Free(&c->ctx);
    free(c);
}

/* The scene's tolerances (fixed parameters: set at creation, and again when a state of a
   scene with others is loaded). The charge models' quadratures are integrated along the
   charging sweep and must not steer the step: a huge absolute tolerance takes their
   (constant) components out of the error norm. The vector keeps them whichever models are
   selected, so that the motion does not depend on the selection. The dissipated and
   external work are the mechanics' own book-keeping (smooth within a phase) and are held to
   the tolerances like the motion, so that the energy balance of model.md §6 is. */
static int set_tolerances(cvode_integrator *c)
{
    /* the dynamics' tolerances: the scene's, at most the loosest the event logic takes */
    N_VConst(c->dyn->atol, c->abstol);
    for (int i = TRIBO_NMOTION; i < c->n; i++)
        if (i != c->dyn->vib_slot) /* W_vib is the mechanics' own, like W_ext (model.md §9b) */
            N_VGetArrayPointer(c->abstol)[i] = 1e30;
    return CVodeSVtolerances(c->mem, c->dyn->rtol, c->abstol) == CV_SUCCESS;
}

/* Whether a call of the set-up failed (`ok` false); the first that did is kept for the
   message, by name, as SUNDIALS' own examples' check_retval do. */
static int failed(cvode_integrator *c, int ok, const char *call)
{
    if (!ok && !c->failed_call)
        c->failed_call = call;
    return !ok;
}

static tribo_status create(tribo_model *m, void **data)
{
    cvode_integrator *c = calloc(1, sizeof *c);
    if (!c)
        return tribo_fail(m, TRIBO_ERR_MEMORY, "cannot set up CVODE: out of memory");
    *data = c;
    c->m = m;
    c->dyn = tribo_dynamics(m);
    c->n = tribo_state_length(m);
    const tribo_scene *scene = tribo_get_scene(m);
    const int bdf = scene->integrator == TRIBO_INTEGRATOR_CVODE_BDF;
    c->rhs_work = bdf ? TRIBO_WORK_RHS_BDF : TRIBO_WORK_RHS_ADAMS;
    c->one_step = !bdf && tribo_vibrating(c->dyn);
    _Static_assert(TRIBO_NSTATE_MAX <= TRIBO_DOP853_MAX, "DOP853 holds the whole state");
    /* one SUNDIALS context per instance: nothing is shared between instances */
    if (failed(c, SUNContext_Create(NULL, &c->ctx) == 0, "SUNContext_Create") ||
        failed(c, (c->y = N_VNew_Serial(c->n, c->ctx)) != NULL, "N_VNew_Serial") ||
        failed(c, (c->dky = N_VNew_Serial(c->n, c->ctx)) != NULL, "N_VNew_Serial") ||
        failed(c, (c->abstol = N_VNew_Serial(c->n, c->ctx)) != NULL, "N_VNew_Serial") ||
        failed(c, (c->mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, c->ctx)) != NULL, "CVodeCreate"))
        goto fail;
    N_VConst(0.0, c->y);
    if (failed(c, CVodeSetErrHandlerFn(c->mem, error_handler, c) == CV_SUCCESS,
               "CVodeSetErrHandlerFn") ||
        failed(c, CVodeInit(c->mem, rhs, 0.0, c->y) == CV_SUCCESS, "CVodeInit") ||
        failed(c, set_tolerances(c), "CVodeSVtolerances") ||
        failed(c, CVodeSetUserData(c->mem, c) == CV_SUCCESS, "CVodeSetUserData") ||
        failed(c, CVodeRootInit(c->mem, N_ROOTS, roots) == CV_SUCCESS, "CVodeRootInit") ||
        failed(c, CVodeSetNoInactiveRootWarn(c->mem) == CV_SUCCESS, "CVodeSetNoInactiveRootWarn") ||
        failed(c, CVodeSetMaxHnilWarns(c->mem, -1) == CV_SUCCESS, "CVodeSetMaxHnilWarns"))
        goto fail;
    if (bdf) {
        /* Newton with a dense difference-quotient Jacobian: 10 states */
        if (failed(c, (c->jac = SUNDenseMatrix(c->n, c->n, c->ctx)) != NULL, "SUNDenseMatrix") ||
            failed(c, (c->ls = SUNLinSol_Dense(c->y, c->jac, c->ctx)) != NULL, "SUNLinSol_Dense") ||
            failed(c, CVodeSetLinearSolver(c->mem, c->ls, c->jac) == CV_SUCCESS,
                   "CVodeSetLinearSolver"))
            goto fail;
    } else {
        /* non-stiff motion: Adams with fixed-point iteration, no Jacobian */
        if (failed(c, (c->nls = SUNNonlinSol_FixedPoint(c->y, 0, c->ctx)) != NULL,
                   "SUNNonlinSol_FixedPoint") ||
            failed(c, CVodeSetNonlinearSolver(c->mem, c->nls) == CV_SUCCESS,
                   "CVodeSetNonlinearSolver"))
            goto fail;
    }
    return TRIBO_OK;
fail:
    /* with CVODE's own message where its error handler was set and said why */
    tribo_fail(m, TRIBO_ERR_MEMORY, "cannot set up CVODE: %s failed%s%s", c->failed_call,
               c->message[0] ? ": " : "", c->message);
    destroy(c);
    *data = NULL;
    return TRIBO_ERR_MEMORY;
}

/* ---- stepping -------------------------------------------------------------------------------- */

/* The bytes of the charge models' quadratures in a state (the sweep's, which CVODE holds
   constant), after the motion; W_vib, last on a vibrating plate, is CVODE's. */
static size_t charge_quadratures(const cvode_integrator *c)
{
    return (size_t)(c->n - TRIBO_NMOTION - (c->dyn->vib_slot ? 1 : 0)) * sizeof(double);
}

static void describe_state(const cvode_integrator *c, const double *y, char *buf, size_t n)
{
    const phase *ph = &c->phase;
    snprintf(buf, n,
             "X = %.9g, Y = %.9g, clearance of the lowest point G = %.9g, phi = %.9g, U = %.9g, "
             "V = %.9g, Omega = %.9g, delta_x = %.9g; "
             "phase: %s%s%s%s",
             y[TRIBO_IX], y[TRIBO_IY], y[TRIBO_IGAP], y[TRIBO_IPHI], y[TRIBO_IU], y[TRIBO_IV],
             y[TRIBO_IOMEGA],
             y[TRIBO_IDX], tribo_touching(ph) ? "contact, " : "flight",
             !tribo_touching(ph) ? ""
             : ph->normal == TRIBO_NORMAL_LOCK ? "normal lock, "
             : ph->normal == TRIBO_NORMAL_CREEP ? (ph->normal_sign > 0 ? "creeping out, " : "creeping in, ")
             : ph->normal_sign > 0 ? "moving out, "
                                       : "moving in, ",
             !tribo_touching(ph)                    ? ""
             : ph->tangent == TRIBO_TANGENT_STICK ? "stick"
             : ph->tangent == TRIBO_TANGENT_RIGID ? "rigid stick"
                                                  : "slip",
             !tribo_touching(ph) || ph->roll == TRIBO_ROLL_FREE ? ""
             : ph->roll == TRIBO_ROLL_LOCK                      ? ", rolling lock"
             : ph->roll_sign > 0                                ? ", turning anticlockwise"
                                                                : ", turning clockwise");
}

static tribo_status fail_at(cvode_integrator *c, double t, const double *y, const char *why)
{
    char state[400];
    describe_state(c, y, state, sizeof state);
    return tribo_fail(c->m, TRIBO_ERR_INTEGRATOR, "CVODE integration stopped at t = %.17g: %s; state: %s",
                      t, why, state);
}

static void capture_interpolant(cvode_integrator *c);
#define GRAZING_SAMPLES 8
static int find_switch(cvode_integrator *c, double t_start, int last);

/* The longest piece of a flight, in units of slow_step, and the most evaluations of the
   clearance a piece spends looking for the flight's end before it ends where it got to (so
   that a flight that never comes down, or spins fast, is taken in bounded pieces). */
#define FLIGHT_PIECE_STEPS 1000.0
#define FLIGHT_PIECE_EVALUATIONS 64

/* The next piece of a flight: from the end of the last one (or the restart), to the flight's
   end (flight.h) or as far as the piece may go; it becomes the open step. */
static tribo_status take_flight_piece(cvode_integrator *c)
{
    if (c->flight_pieces++ > 0)
        tribo_flight_start(&c->flight, c->dyn, c->t_end, c->y_end, c->n);
    const double t0 = c->flight.t0;
    tribo_flight_end why;
    long used;
    const double t_end = tribo_flight_end_of(&c->flight, c->dyn, t0,
                                             t0 + FLIGHT_PIECE_STEPS * slow_step(c->dyn),
                                             FLIGHT_PIECE_EVALUATIONS, &why, &used);
    c->steps_since_restart++;
    c->open = 1;
    c->t_end = t_end;
    tribo_flight_state(&c->flight, c->dyn, t_end, c->y_end);
    for (int i = 0; i < N_ROOTS; i++)
        c->roots[i] = 0;
    c->ends_at_root = why != TRIBO_FLIGHT_GOES_ON;
    if (why == TRIBO_FLIGHT_CONTACT)
        c->roots[TRIBO_SWITCH_CONTACT] = +1;
    else if (why == TRIBO_FLIGHT_EXIT)
        c->roots[TRIBO_SWITCH_EXIT] = -1;
    if (!c->replaying) {
        tribo_count(c->m, TRIBO_COUNT_STEPS, 1);
        tribo_work(c->m, TRIBO_WORK_FLIGHT_PIECE + TRIBO_WORK_FLIGHT_EVALUATION * (double)used);
    }
    return TRIBO_OK;
}

/* A contact's step by DOP853: its switches are located on its dense output (find_switch),
   like the grazing ones of a CVODE step. */
static tribo_status take_one_step(cvode_integrator *c)
{
    if (tribo_dop853_step(&c->dop, c->h_max) != 0)
        return fail_at(c, c->dop.t, c->dop.y, "DOP853's step fell below the rounding of t");
    c->steps_since_restart++;
    c->open = 1;
    c->t_end = c->dop.t;
    memcpy(c->y_end, c->dop.y, (size_t)c->n * sizeof(double));
    hold_phase(c, c->t_end, c->y_end);
    c->ends_at_root = 0;
    for (int i = 0; i < N_ROOTS; i++)
        c->roots[i] = 0;
    const int looks = find_switch(c, tribo_committed(c->m)->t, GRAZING_SAMPLES);
    if (!c->replaying) {
        tribo_count(c->m, TRIBO_COUNT_STEPS, 1);
        tribo_work(c->m, TRIBO_WORK_CVODE_STEP + TRIBO_WORK_GRAZING_LOOK * (double)looks);
    }
    return TRIBO_OK;
}

/* Take one step from the end of the last one (a CVODE step in contact, a piece of the flight
   in flight); it becomes the open step. */
static tribo_status take_step(cvode_integrator *c)
{
    if (!tribo_touching(&c->phase))
        return take_flight_piece(c);
    if (c->one_step)
        return take_one_step(c);
    double t_ret;
    /* in one-step mode the target only sets the direction and the first step's scale */
    const int flag = CVode(c->mem, c->t_restart + 1.0, c->y, &t_ret, CV_ONE_STEP);
    if (flag < 0) {
        char why[400];
        char *name = CVodeGetReturnFlagName(flag);
        snprintf(why, sizeof why, "%s (%s)", name ? name : "CVODE error", c->message);
        free(name);
        return fail_at(c, t_ret, N_VGetArrayPointer(c->y), why);
    }
    c->steps_since_restart++;
    c->open = 1;
    c->t_end = t_ret;
    memcpy(c->y_end, N_VGetArrayPointer(c->y), (size_t)c->n * sizeof(double));
    hold_phase(c, t_ret, c->y_end);
    c->ends_at_root = flag == CV_ROOT_RETURN;
    if (c->ends_at_root)
        CVodeGetRootInfo(c->mem, c->roots);
    capture_interpolant(c);
    const int looks = c->ends_at_root ? 0 : find_switch(c, tribo_committed(c->m)->t, GRAZING_SAMPLES - 1);
    if (!c->replaying) {
        /* (its right-hand sides are booked as CVODE evaluates them) */
        tribo_count(c->m, TRIBO_COUNT_STEPS, 1);
        tribo_work(c->m, TRIBO_WORK_CVODE_STEP +
                             TRIBO_WORK_INTERPOLANT * (double)(c->taylor_order + 1) +
                             TRIBO_WORK_GRAZING_LOOK * (double)looks);
    }
    return TRIBO_OK;
}

static double dense_component(const cvode_integrator *c, double t, int i)
{
    if (c->one_step)
        return tribo_dop853_dense(&c->dop, t, i);
    const double u = t - c->taylor_t;
    double v = c->taylor[c->taylor_order][i];
    for (int k = c->taylor_order - 1; k >= 0; k--)
        v = v * u + c->taylor[k][i];
    return v;
}

static void dense(cvode_integrator *c, double t, double *y)
{
    if (!tribo_touching(&c->phase)) {
        tribo_flight_state(&c->flight, c->dyn, t, y);
        return;
    }
    for (int i = 0; i < c->n; i++)
        y[i] = dense_component(c, t, i);
}

/* CVODE sees a switch only where a root function has changed sign between the ends of a
   step. A switch function can dip past zero and back within one step: in stick under
   normal lock the undamped tangential oscillation brings the stretch to the (constant)
   Coulomb limit almost tangentially, and a dip of 1e-6 past it lies within one step, unseen
   at its ends. So each step is also sampled inside on the dense output; the first sample
   past a switch (beyond the rounding of that function's values in the step) is bisected to
   the crossing, and the step ends there as if CVODE had found it. A DOP853 step's switches are
   all found so, its end's sample among them (last = GRAZING_SAMPLES; CVODE's own root finding
   looks at a CVODE step's ends: last = GRAZING_SAMPLES - 1). */

static void switch_functions(cvode_integrator *c, double t, double *g)
{
    double y[TRIBO_NSTATE_MAX];
    dense(c, t, y);
    tribo_dyn_params at;
    tribo_switch_functions(dyn_at(c, t, &at), &c->phase, y, g);
}

/* The first time in [a, b] where switch function i is past its switch (direction dir), a
   before it and b past it; counts the looks. */
static double bisect(cvode_integrator *c, int dir, int i, double a, double b, int *looks)
{
    for (int it = 0; it < 60 && b - a > 1e-15 * (1.0 + fabs(b)); it++, (*looks)++) {
        const double mid = 0.5 * (a + b);
        double gm[N_ROOTS];
        switch_functions(c, mid, gm);
        if (dir * gm[i] > 0.0)
            b = mid;
        else
            a = mid;
    }
    return b;
}

/* Returns how many times it looked at the switch functions. */
static int find_switch(cvode_integrator *c, double t_start, int last)
{
    int dir[N_ROOTS];
    tribo_switch_directions(c->dyn, &c->phase, dir);
    double g[GRAZING_SAMPLES + 1][N_ROOTS], scale[N_ROOTS] = {0};
    const double h = c->t_end - t_start;
    if (!(h > 0.0))
        return 0;
    int looks = GRAZING_SAMPLES + 1;
    for (int j = 0; j <= GRAZING_SAMPLES; j++) {
        switch_functions(c, t_start + h * j / GRAZING_SAMPLES, g[j]);
        for (int i = 0; i < N_ROOTS; i++)
            scale[i] = fmax(scale[i], fabs(g[j][i]));
    }
    for (int j = 1; j <= last; j++) {
        /* every function past its switch at this sample is bisected, between the last sample
           before it and this one, to its crossing: the earliest is the switch (two can cross
           between two samples, a slip starting just before the lift-off, say) */
        int found = -1;
        double at = INFINITY;
        for (int i = 0; i < N_ROOTS; i++) {
            const double noise = 1e-12 + 1e-9 * scale[i];
            if (dir[i] == 0 || !(dir[i] * g[0][i] <= noise && dir[i] * g[j][i] > noise))
                continue;
            const double crossing = bisect(c, dir[i], i, t_start + h * (j - 1) / GRAZING_SAMPLES,
                                           t_start + h * j / GRAZING_SAMPLES, &looks);
            if (crossing < at) {
                at = crossing;
                found = i;
            }
        }
        if (found < 0)
            continue;
        c->t_end = at;
        dense(c, at, c->y_end);
        hold_phase(c, at, c->y_end);
        c->ends_at_root = 1;
        for (int i = 0; i < N_ROOTS; i++)
            c->roots[i] = i == found ? dir[i] : 0;
        return looks;
    }
    return looks;
}

/* Take CVODE's interpolant over the step just taken (see taylor). */
static void capture_interpolant(cvode_integrator *c)
{
    CVodeGetCurrentTime(c->mem, &c->taylor_t);
    /* the interpolant's degree is the last step's order: asking CVodeGetDky beyond it is an
       error CVODE formats into a message, once per step */
    int order = 0;
    CVodeGetLastOrder(c->mem, &order);
    double factorial = 1.0;
    int k = 0;
    for (; k <= order && k < 13 && CVodeGetDky(c->mem, c->taylor_t, k, c->dky) == CV_SUCCESS; k++) {
        if (k > 0)
            factorial *= k;
        const double *d = N_VGetArrayPointer(c->dky);
        for (int i = 0; i < c->n; i++)
            c->taylor[k][i] = d[i] / factorial;
    }
    c->taylor_order = k - 1;
}

/* The probe of the charging sweep: the contact at time t of the open step (model.md §5). */
static void probe(void *ctx, double t, double *s_centre, double *half_width, double *centre_speed,
                  tribo_contact_kinematics *k)
{
    cvode_integrator *c = ctx;
    /* the components tribo_probe_contact reads: the sweep probes often */
    static const int read[] = {TRIBO_IGAP, TRIBO_IPHI, TRIBO_IU, TRIBO_IOMEGA};
    double y[TRIBO_NSTATE_MAX];
    for (size_t i = 0; i < sizeof read / sizeof read[0]; i++)
        y[read[i]] = dense_component(c, t, read[i]);
    tribo_probe_contact(c->m, y, s_centre, half_width, centre_speed, k);
    /* the rigid stick does not slip: no frictional work (model.md §3b) */
    if (c->phase.tangent == TRIBO_TANGENT_RIGID && tribo_touching(&c->phase))
        k->vs = 0.0;
}

/* Charge over [a, b] inside the open step, advancing p's quadratures and charge globals:
   committed, or queued for the output point. */
static tribo_status sweep_charges(cvode_integrator *c, double a, double b, tribo_point *p,
                                  tribo_charge_destination where, double *reached)
{
    *reached = b;
    if (!tribo_touching(&c->phase) || !(b > a))
        return TRIBO_OK;
    const tribo_contact_probe pr = {probe, c};
    return tribo_charge_sweep(c->m, &pr, a, b, p, where, reached);
}

/* End the open step at t, inside it, where its charging sweep spent its budget (a contact
   that sweeps the boundary very fast, e.g. a spinning needle, or a wide contact on many
   segments): the step's work stays bounded, and CVODE restarts there once it is closed. */
static void end_step_early(cvode_integrator *c, double t)
{
    c->t_end = t;
    dense(c, t, c->y_end);
    hold_phase(c, t, c->y_end);
    c->ends_at_root = 0;
    for (int i = 0; i < N_ROOTS; i++)
        c->roots[i] = 0;
    c->ends_early = 1;
}

/* The point at time t (with y there) in the current phase. */
static void fill_point(cvode_integrator *c, tribo_point *p, double t, const double *y,
                       const tribo_point *from, int commit)
{
    p->t = t;
    memcpy(p->y, y, sizeof p->y);
    hold_phase(c, t, p->y);
    tribo_dyn_params at;
    tribo_contact_at(dyn_at(c, t, &at), &c->phase, p->y, &p->contact);
    if (tribo_touching(&c->phase)) {
        /* the phase decides contact, also where rounding makes delta_y = -1e-17 */
        p->contact.in_contact = 1;
        /* in slip the stretch is held at the limit (model.md §3); CVODE's integrated stretch
           follows it only to the tolerances */
        if (c->phase.tangent == TRIBO_TANGENT_SLIP)
            p->y[TRIBO_IDX] = c->phase.slip_sign * p->contact.limit;
    } else {
        p->contact.in_contact = 0;
    }
    p->slipping = tribo_touching(&c->phase) && c->phase.tangent == TRIBO_TANGENT_SLIP;
    tribo_book_interval(c->m, from, p, commit);
}

/* The committed point again, at y after an event or a restart (no time passes). */
static void commit_again(cvode_integrator *c, double t, const double *y)
{
    const tribo_point *committed = tribo_committed(c->m);
    tribo_point p = *committed;
    fill_point(c, &p, t, y, committed, 1);
    tribo_commit(c->m, &p);
}

/* Commit the open step: its charges, its end point, and the event that ends it. */
static tribo_status close_step(cvode_integrator *c)
{
    tribo_model *m = c->m;
    const tribo_point *committed = tribo_committed(m);
    const size_t quadratures = charge_quadratures(c);
    tribo_point next;
    memcpy(next.charge_globals, committed->charge_globals, sizeof next.charge_globals);
    /* the quadratures are the sweep's, not CVODE's (it holds them constant) */
    memcpy(next.y + TRIBO_NMOTION, committed->y + TRIBO_NMOTION, quadratures);
    /* the exit is where the centre reaches L: CVODE locates the root in time to its own
       tolerance, which can leave X a rounding short of L (model.md §9) */
    if (c->ends_at_root && c->roots[TRIBO_SWITCH_EXIT] && c->y_end[TRIBO_IX] < c->dyn->chute_length)
        c->y_end[TRIBO_IX] = c->dyn->chute_length;
    double reached;
    tribo_status st = sweep_charges(c, committed->t, c->t_end, &next, TRIBO_CHARGE_COMMIT, &reached);
    if (st != TRIBO_OK)
        return st;
    if (reached < c->t_end)
        end_step_early(c, reached);
    memcpy(c->y_end + TRIBO_NMOTION, next.y + TRIBO_NMOTION, quadratures);
    fill_point(c, &next, c->t_end, c->y_end, committed, 1);
    tribo_commit(m, &next);
    c->open = 0;

    if (!c->roots[TRIBO_SWITCH_EXIT] && !(c->y_end[TRIBO_IX] < c->dyn->chute_length)) {
        /* past the end without the exit root: the root finding cannot resolve L - X where
           it is below its resolution (a chute of 5e-324), also where the step ends at
           another switch's root: the run ends at the step's end */
        c->ending = TRIBO_STOP_EXIT;
        st = restart_at(c, c->t_end, tribo_committed(m)->y, &c->phase);
        return st == TRIBO_OK ? TRIBO_ENDED : st;
    }
    if (!c->ends_at_root) {
        c->events_in_a_row = 0;
        if (c->ends_early || c->steps_since_restart >= STEPS_PER_RESTART) {
            c->ends_early = 0;
            return restart_at(c, c->t_end, c->y_end, &c->phase);
        }
        return TRIBO_OK;
    }

    /* the end of the run: no phase follows (model.md §9) */
    if (c->roots[TRIBO_SWITCH_EXIT]) {
        c->ending = TRIBO_STOP_EXIT;
        st = restart_at(c, c->t_end, tribo_committed(m)->y, &c->phase);
        return st == TRIBO_OK ? TRIBO_ENDED : st;
    }

    /* an event: new phase, resets, restart */
    const double t = c->t_end;
    if (fabs(t - c->last_event_t) <= 1e-12 * fmax(1.0, fabs(t)))
        c->events_at_instant++;
    else
        c->events_at_instant = 1;
    c->last_event_t = t;
    if (c->events_at_instant > MAX_EVENTS_AT_ONE_INSTANT)
        return fail_at(c, t, c->y_end, "event cascade: the force law keeps switching at one instant");
    if (++c->events_in_a_row > MAX_EVENTS_IN_A_ROW)
        return fail_at(c, t, c->y_end, "too many events in a row without a regular step");
    double y[TRIBO_NSTATE_MAX];
    memcpy(y, c->y_end, sizeof y);
    tribo_dyn_params at;
    const phase ph = tribo_phase_after(dyn_at(c, t, &at), &c->phase, y, c->roots);
    const int lift_off = tribo_touching(&c->phase) && !tribo_touching(&ph);
    tribo_count(m, TRIBO_COUNT_EVENTS, 1);
    st = restart_at(c, t, y, &ph);
    if (st != TRIBO_OK)
        return st;
    commit_again(c, t, y);
    if (lift_off && c->dyn->end_at_liftoff) { /* the run's end, like the chute's exit */
        c->ending = TRIBO_STOP_LIFTOFF;
        return TRIBO_ENDED;
    }
    if (tribo_at_rest(&ph) && !tribo_vibrating(c->dyn)) {
        /* for ever, under constant inputs (model.md §3c); never on a vibrating plate, whose
           load is not constant (§9b) */
        c->ending = TRIBO_STOP_REST;
        return TRIBO_ENDED;
    }
    return TRIBO_OK;
}

static tribo_status restart(tribo_model *m, void *data)
{
    cvode_integrator *c = data;
    const tribo_point *committed = tribo_committed(m);
    double y[TRIBO_NSTATE_MAX];
    memcpy(y, committed->y, sizeof y);
    /* the phase follows from the state alone */
    tribo_dyn_params at;
    const phase ph = tribo_phase_after(dyn_at(c, committed->t, &at), &TRIBO_PHASE_FLIGHT, y, NULL);
    c->events_at_instant = 0;
    c->events_in_a_row = 0;
    c->last_event_t = -INFINITY;
    const tribo_status st = restart_at(c, committed->t, y, &ph);
    if (st == TRIBO_OK)
        commit_again(c, committed->t, y);
    return st;
}

static tribo_status advance(tribo_model *m, void *data, double t)
{
    cvode_integrator *c = data;
    const double t_start = tribo_committed(m)->t;
    const double max_steps = 1e5 + MAX_STEPS_PER_TIME_UNIT * fmax(0.0, t - t_start);
    long long steps = 0;
    tribo_status st;
next_step:
    for (;;) {
        if (c->open && t <= c->t_end)
            break;
        if (c->open && (st = close_step(c)) != TRIBO_OK)
            return st == TRIBO_ENDED ? tribo_stop_early(m, c->ending) : st;
        if (t <= tribo_committed(m)->t)
            break;
        /* (re)started at rest: the run ends there (model.md §3c) */
        if (!c->open && tribo_at_rest(&c->phase) && !tribo_vibrating(c->dyn))
            return tribo_stop_early(m, TRIBO_STOP_REST);
        if (tribo_work_spent(m))
            return tribo_stop_early(m, TRIBO_STOP_WORK_LIMIT);
        if (++steps > max_steps)
            return fail_at(c, tribo_committed(m)->t, tribo_committed(m)->y,
                           "too much work: more than 1e6 steps per time unit");
        if ((st = take_step(c)) != TRIBO_OK)
            return st;
    }

    /* the state at t, from the open step's dense output */
    tribo_output_begin(m);
    const tribo_point *committed = tribo_committed(m);
    tribo_point out;
    if (!c->open || t <= committed->t) {
        out = *committed;
        out.t = t;
        tribo_output_set(m, &out);
        return TRIBO_OK;
    }
    double y[TRIBO_NSTATE_MAX];
    dense(c, t, y);
    memcpy(y + TRIBO_NMOTION, committed->y + TRIBO_NMOTION, charge_quadratures(c));
    memcpy(out.charge_globals, committed->charge_globals, sizeof out.charge_globals);
    fill_point(c, &out, t, y, committed, 0);
    double reached;
    st = sweep_charges(c, committed->t, t, &out, TRIBO_CHARGE_PENDING, &reached);
    if (st == TRIBO_OK && reached < t) {
        /* the step's sweep ends before t: the step ends there, as it would without the
           output (tribo_charging_sweep), and the advance goes on from it */
        tribo_output_begin(m);
        end_step_early(c, reached);
        goto next_step;
    }
    tribo_output_set(m, &out);
    return st;
}

/* ---- state ------------------------------------------------------------------------------------ */

typedef struct saved {
    double t_restart;
    double y_restart[TRIBO_NSTATE_MAX];
    long long steps_since_restart;
    long long open;
    long long contact, normal, tangent, started_at_rest, compliant_slip, roll, roll_from_rest;
    double normal_sign, slip_sign, roll_sign;
    double last_event_t;
    long long events_at_instant, events_in_a_row;
} saved;

static size_t state_size(const void *data)
{
    (void)data;
    return sizeof(saved);
}

static void state_save(const void *data, unsigned char *b)
{
    const cvode_integrator *c = data;
    saved s;
    memset(&s, 0, sizeof s);
    s.t_restart = c->t_restart;
    memcpy(s.y_restart, c->y_restart, sizeof s.y_restart);
    s.steps_since_restart = c->steps_since_restart;
    s.open = c->open;
    s.contact = tribo_touching(&c->phase);
    s.normal = c->phase.normal;
    s.tangent = c->phase.tangent;
    s.normal_sign = c->phase.normal_sign;
    s.slip_sign = c->phase.slip_sign;
    s.started_at_rest = c->phase.started_at_rest;
    s.compliant_slip = c->phase.compliant_slip;
    s.roll = c->phase.roll;
    s.roll_sign = c->phase.roll_sign;
    s.roll_from_rest = c->phase.roll_from_rest;
    s.last_event_t = c->last_event_t;
    s.events_at_instant = c->events_at_instant;
    s.events_in_a_row = c->events_in_a_row;
    memcpy(b, &s, sizeof s);
}

/* Whether a saved rolling rule is one this integrator can produce (model.md §3c): none in flight
   or without rolling resistance; else turning one way (from rest or not) or the rolling lock. */
static int saved_roll_valid(const cvode_integrator *c, const saved *s)
{
    if (s->contact == 0 || c->dyn->mu_roll == 0.0)
        return s->roll == TRIBO_ROLL_FREE && s->roll_sign == 0.0 && s->roll_from_rest == 0;
    if (s->roll == TRIBO_ROLL_TURNING)
        return (s->roll_sign == 1.0 || s->roll_sign == -1.0) &&
               (s->roll_from_rest == 0 || s->roll_from_rest == 1);
    return s->roll == TRIBO_ROLL_LOCK && s->roll_sign == 0.0 && s->roll_from_rest == 0;
}

/* Whether saved bytes hold values this integrator can produce. */
static int saved_valid(const cvode_integrator *c, const saved *s)
{
    int ok = isfinite(s->t_restart) && s->steps_since_restart >= 0 &&
             s->steps_since_restart <= STEPS_PER_RESTART && (s->open == 0 || s->open == 1) &&
             (s->contact == 0 || s->contact == 1) &&
             (s->normal == TRIBO_NORMAL_SIGN || s->normal == TRIBO_NORMAL_LOCK ||
              (s->normal == TRIBO_NORMAL_CREEP && c->dyn->rigid_stick && s->contact == 1 &&
               c->dyn->damping_point == TRIBO_DAMPING_CONTACT_POINT &&
               (s->normal_sign == 1.0 || s->normal_sign == -1.0))) &&
             (s->tangent == TRIBO_TANGENT_STICK || s->tangent == TRIBO_TANGENT_SLIP ||
              (s->tangent == TRIBO_TANGENT_RIGID && c->dyn->rigid_stick && s->contact == 1 &&
               (s->normal == TRIBO_NORMAL_LOCK || s->normal == TRIBO_NORMAL_CREEP) &&
               c->dyn->damping_point == TRIBO_DAMPING_CONTACT_POINT)) &&
             (s->normal_sign == 1.0 || s->normal_sign == -1.0 || s->normal_sign == 0.0) &&
             (s->started_at_rest == 0 ||
              (s->started_at_rest == 1 && s->contact == 1 && s->normal == TRIBO_NORMAL_SIGN)) &&
             (s->compliant_slip == 0 ||
              (s->compliant_slip == 1 && c->dyn->rigid_stick && s->contact == 1 &&
               s->tangent == TRIBO_TANGENT_SLIP &&
               (s->normal == TRIBO_NORMAL_LOCK || s->normal == TRIBO_NORMAL_CREEP) &&
               c->dyn->damping_point == TRIBO_DAMPING_CONTACT_POINT)) &&
             (s->slip_sign == 1.0 || s->slip_sign == -1.0 || s->slip_sign == 0.0) &&
             saved_roll_valid(c, s) && (isfinite(s->last_event_t) || s->last_event_t == -INFINITY) &&
             s->events_at_instant >= 0 && s->events_at_instant <= MAX_EVENTS_AT_ONE_INSTANT &&
             s->events_in_a_row >= 0 && s->events_in_a_row <= MAX_EVENTS_IN_A_ROW;
    for (int i = 0; ok && i < c->n; i++)
        ok = isfinite(s->y_restart[i]);
    return ok;
}

static tribo_status state_load(tribo_model *m, void *data, const unsigned char *b, double t_out)
{
    cvode_integrator *c = data;
    saved s;
    memcpy(&s, b, sizeof s);
    const double t = tribo_committed(m)->t;
    if (!saved_valid(c, &s) || !(s.t_restart <= t) || !(s.last_event_t <= t) ||
        (!s.open && t_out != t))
        return tribo_fail(m, TRIBO_ERR_STATE, "the CVODE state is corrupt");
    if (!set_tolerances(c))
        return tribo_fail(m, TRIBO_ERR_STATE, "CVODE refused the tolerances rtol = %g, atol = %g: %s",
                          c->dyn->rtol, c->dyn->atol, c->message);
    phase ph;
    ph.contact = s.contact ? TRIBO_CONTACT_ON : TRIBO_CONTACT_OFF;
    ph.normal = (tribo_normal_rule)s.normal;
    ph.tangent = (tribo_tangent_rule)s.tangent;
    ph.normal_sign = s.normal_sign;
    ph.slip_sign = s.slip_sign;
    ph.started_at_rest = (int)s.started_at_rest;
    ph.compliant_slip = (int)s.compliant_slip;
    ph.roll = (tribo_roll_rule)s.roll;
    ph.roll_sign = s.roll_sign;
    ph.roll_from_rest = (int)s.roll_from_rest;
    /* CVODE is deterministic: the same restart and steps give the same open step. They must
       reach the committed point, time and motion (but for the stretch, which a slip holds at
       its limit there): the steps before the open one end there, and the open one holds the
       output time. */
    c->replaying = 1;
    double reached = s.t_restart, before = s.t_restart;
    double y_reached[TRIBO_NSTATE_MAX], y_before[TRIBO_NSTATE_MAX];
    memcpy(y_reached, s.y_restart, sizeof y_reached);
    memcpy(y_before, s.y_restart, sizeof y_before);
    tribo_status st = restart_at(c, s.t_restart, s.y_restart, &ph);
    for (long long k = 0; st == TRIBO_OK && k < s.steps_since_restart; k++) {
        before = reached;
        memcpy(y_before, y_reached, sizeof y_before);
        if ((st = take_step(c)) == TRIBO_OK) {
            reached = c->t_end;
            memcpy(y_reached, c->y_end, sizeof y_reached);
        }
    }
    c->replaying = 0;
    if (st != TRIBO_OK)
        return tribo_fail(m, TRIBO_ERR_STATE, "the CVODE state does not replay: %s",
                          tribo_last_error(m));
    const double at = s.open ? before : reached;
    /* the committed point is the step's end put back on the phase's constraints once more
       (fill_point), which in the rigid stick can move the last bit */
    double y_at[TRIBO_NSTATE_MAX];
    memcpy(y_at, s.open ? y_before : y_reached, sizeof y_at);
    hold_phase(c, at, y_at);
    int same = at == t && (!s.open || (s.steps_since_restart > 0 && t_out <= reached));
    for (int i = 0; same && i < TRIBO_NMOTION; i++)
        same = i == TRIBO_IDX || y_at[i] == tribo_committed(m)->y[i];
    if (!same)
        return tribo_fail(m, TRIBO_ERR_STATE,
                          "the CVODE state is corrupt: its steps from t = %.17g do not reach the "
                          "committed point at t = %.17g",
                          s.t_restart, t);
    c->open = (int)s.open;
    c->last_event_t = s.last_event_t;
    c->events_at_instant = (int)s.events_at_instant;
    c->events_in_a_row = s.events_in_a_row;
    return TRIBO_OK;
}

const tribo_integrator_ops tribo_cvode_ops = {
    create, destroy, restart, advance, state_size, state_save, state_load,
};
