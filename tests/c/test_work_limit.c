/* The work limit bounds an advance at every valid input, and ordinary runs stay within its
   default (docs/fmu.md, "The work limit"; docs/work_limit.md measures the CPU a unit of work
   costs, scripts/bench_work_limit.sh). What is asserted here is work, never CPU time: an
   advance books no more than its limit and one internal step past it, and every kind of
   work is booked at its weight (below). */
#include <criterion/criterion.h>
#include <string.h>

#include "integrator.h"
#include "model.h"
#include "support.h"

/* The most one internal step can book past the limit (the limit is looked at between
   steps): its charging sweep ends where it has cost TRIBO_SWEEP_BUDGET (1e5 looks at the
   contact, or 1.5e7 segments covered), and the sweep to the output point as much again,
   each look, sample and segment value of two charge models at its weight; a CVODE step
   itself is a few tens of units. */
#define ONE_STEP_WORK 3e5

/* A needle spinning on the plate: its contact runs along the boundary's 1e5 segments at
   ~1e9 segments per time unit, so that one CVODE step's charging sweep looked at the
   contact tens of millions of times. */
static const char *SPINNING_NEEDLE = "epsilon=1e-3 Gamma=10 tau0=1e9 eta=0 tau_r=1e9 "
                                     "n_segments=100000 phi0=-1e6 Omega0=-100 rtol=1e-14 "
                                     "stick_model=1";
/* A deep, wide contact on 1e5 segments: each sample charges tens of thousands of them. */
static const char *WIDE_CONTACT = "mu=100 eta=0 tau_r=1e9 n_segments=100000 v_reg=1000 "
                                  "phi0=1e6 drop_speed=10";

/* Advances of 0.1 at a work limit of 1e5 (a tenth of the default: the bound holds at any
   limit, and the sanitizer build takes seconds): each books at most its limit and one step
   past it, and makes progress. */
static void each_advance_is_bounded(const char *settings, int advances)
{
    tribo_scene s = scene_of(settings);
    s.work_limit = 100000;
    tribo_model *m = make(&s);
    double t = 0.0;
    for (int k = 0; k < advances; k++) {
        const tribo_status st = tribo_advance(m, t + 0.1);
        cr_assert(st == TRIBO_OK || st == TRIBO_INCOMPLETE, "%s", tribo_last_error(m));
        cr_expect(m->work <= s.work_limit + ONE_STEP_WORK, "%s: advance %d booked %.0f units",
                  settings, k, m->work);
        const double reached = tribo_get(m, TRIBO_QUANTITY_TIME);
        cr_expect(reached > t, "advance %d made no progress from t = %.17g", k, t);
        t = reached;
    }
    tribo_free(m);
}

Test(work_limit, an_advance_is_bounded_where_the_contact_sweeps_the_boundary_fast, .timeout = 120)
{
    each_advance_is_bounded(SPINNING_NEEDLE, 3);
}

Test(work_limit, an_advance_is_bounded_where_a_wide_contact_covers_many_segments, .timeout = 120)
{
    each_advance_is_bounded(WIDE_CONTACT, 3);
}

Test(work_limit, an_advance_is_bounded_at_the_tightest_tolerances, .timeout = 60)
{
    each_advance_is_bounded("rtol=1e-14 atol=1e-20", 3);
    each_advance_is_bounded("n_segments=64 Omega0=100 phi0=-1e6", 3);
}

/* ---- what the work counts: each kind of work at its weight (integrator.h, measured in
   docs/work_limit.md), so that a unit is about the same CPU whatever the scene ---------- */

/* The work one advance from the start books, and the counts it made. */
static double work_of_one_advance(const char *settings, double t, tribo_stats *stats)
{
    tribo_scene s = scene_of(settings);
    s.work_limit = 2000000000;
    tribo_model *m = make(&s);
    cr_assert_eq(tribo_advance(m, t), TRIBO_OK, "%s", tribo_last_error(m));
    const double work = m->work;
    tribo_get_stats(m, stats);
    tribo_free(m);
    return work;
}

/* BDF's Newton iteration costs a linear solve per right-hand side, and stiff contact takes
   several per step: each one is booked, not a flat weight per step. */
Test(work_limit, every_right_hand_side_cvode_evaluates_is_booked)
{
    static const char *const scenes[] = {
        "integrator=2 charge_model_static=0 charge_model_sliding=0",
        "integrator=1 charge_model_static=0 charge_model_sliding=0 epsilon=0.01 Gamma=10"};
    static const double per_rhs[] = {TRIBO_WORK_RHS_BDF, TRIBO_WORK_RHS_ADAMS};
    for (int i = 0; i < 2; i++) {
        tribo_stats st;
        const double work = work_of_one_advance(scenes[i], 200.0, &st);
        cr_assert_gt(st.rhs_evals, st.steps, "%s: %lld right-hand sides in %lld steps", scenes[i],
                     st.rhs_evals, st.steps);
        cr_expect_geq(work, per_rhs[i] * (double)st.rhs_evals +
                                TRIBO_WORK_CVODE_STEP * (double)st.steps,
                      "%s: %.0f units for %lld right-hand sides in %lld steps", scenes[i], work,
                      st.rhs_evals, st.steps);
    }
}

/* The charge of one sample over every one of 1e5 segments, committed: its work. Where
   leave_by_edges, the globals move over the sample (instantaneous transfer then takes each
   segment's saturation where it left the contact, model.md §5c). */
static double work_of_a_sample(const char *settings, int leave_by_edges)
{
    tribo_scene s = scene_of(settings);
    tribo_model *m = make(&s);
    tribo_contact_sample sample = {.duration = 1e-3, .first = 0, .count = m->charging.n,
                                   .leave_by_edges = leave_by_edges};
    if (leave_by_edges) {
        sample.n_patch = TRIBO_PATCH_POINTS;
        for (int i = 0; i < TRIBO_PATCH_POINTS; i++)
            sample.patch[i] = (tribo_patch_point){.centre = 5e4 + i, .half = 100.0, .depth = 1.0};
    }
    memcpy(sample.globals_begin, m->committed.charge_globals, sizeof sample.globals_begin);
    memcpy(sample.globals_mid, m->committed.charge_globals, sizeof sample.globals_mid);
    memcpy(sample.globals_end, m->committed.charge_globals, sizeof sample.globals_end);
    const double before = m->work;
    cr_assert_eq(tribo_charge_sample(m, &sample, TRIBO_CHARGE_COMMIT), TRIBO_OK);
    const double work = m->work - before;
    tribo_free(m);
    return work;
}

static double work_of_a_wide_sample(const char *settings)
{
    return work_of_a_sample(settings, 0);
}

/* Holding every value within the breakdown limit is a second pass over them, as costly as
   the charge itself (model.md §8b): it is booked. */
Test(work_limit, the_breakdown_limit_on_each_charged_value_is_booked)
{
    const double plain = work_of_a_wide_sample("n_segments=100000");
    const double held = work_of_a_wide_sample("n_segments=100000 Sigma_bd=1e-6");
    cr_assert_gt(plain, 0.0);
    cr_expect_gt(held, 2.0 * plain, "%.1f units with the limit, %.1f without", held, plain);
}

/* The spheroid's bands (model.md §8c) double the values a sample charges, and each band is
   widened under the patch first: both are booked. */
Test(work_limit, the_spheroids_bands_under_each_sample_are_booked)
{
    const double cylinder = work_of_a_wide_sample("n_segments=100000");
    const double spheroid = work_of_a_wide_sample("n_segments=100000 grain_geometry=1");
    cr_expect_geq(spheroid, 2.0 * cylinder + TRIBO_WORK_BAND * 1e5,
                  "%.1f units on the spheroid, %.1f on the cylinder", spheroid, cylinder);
}

/* Instantaneous transfer whose globals move over a sample gives each segment the saturation
   of the time it left the contact: a saturation per value, booked. */
Test(work_limit, each_segments_own_saturation_in_instantaneous_transfer_is_booked)
{
    const double still = work_of_a_sample("n_segments=100000 tau0=0", 0);
    const double moving = work_of_a_sample("n_segments=100000 tau0=0", 1);
    /* both charge models: two values per segment */
    cr_expect_geq(moving, still + TRIBO_WORK_LEAVE_TARGET * 2e5,
                  "%.1f units where the globals move, %.1f where they hold still", moving, still);
}

/* A contact moving steadily along the boundary at one segment per unit of time, a
   segment wide. */
static void steady_probe(void *ctx, double t, double *s_centre, double *half_width,
                         double *centre_speed, tribo_contact_kinematics *k)
{
    const double seg = *(const double *)ctx;
    *s_centre = seg * (0.37 + t);
    *half_width = 0.5 * seg;
    *centre_speed = seg;
    *k = (tribo_contact_kinematics){.mu = 0.1, .delta_y = 1e-3, .vs = 0.1, .rho_c = 1.0};
}

/* A sweep cuts a contact that runs along the boundary into samples, several per look at
   the contact, each charged by every model: each is booked, queued for the output point as
   well as committed (tribo_charge_sweep books per model; one model here). */
Test(work_limit, every_sample_of_a_sweep_is_booked_per_charge_model)
{
    /* the static model alone: no states along the contact, so that the pieces are as long
       as a contact may move in one (eight segments) and its samples outnumber the looks */
    tribo_scene s = scene_of("n_segments=2000 charge_model_sliding=0");
    tribo_model *m = make(&s);
    double seg = m->charging.arc.perimeter / m->charging.n;
    const tribo_contact_probe probe = {steady_probe, &seg};
    tribo_point p = m->committed;
    double reached;
    const double before = m->work;
    cr_assert_eq(tribo_charge_sweep(m, &probe, 0.0, 200.0, &p, TRIBO_CHARGE_PENDING, &reached),
                 TRIBO_OK);
    cr_assert_eq(reached, 200.0);
    const double samples = (double)m->n_pending;
    cr_assert_geq(samples, 200.0, "%.0f samples", samples);
    cr_expect_geq(m->work - before, TRIBO_WORK_SAMPLE * samples, "%.1f units for %.0f samples",
                  m->work - before, samples);
    tribo_free(m);
}

/* Where a step's sweep spends its budget the step ends there, whatever the work limit and
   whichever times the output is asked at: the same run. */
Test(work_limit, a_step_ended_by_its_sweep_is_the_same_at_any_limit_and_output_times,
     .timeout = 240)
{
    /* the needle's first contact, t = 0.0071479, and a little of its sweep */
    const double T = 0.0071489;
    tribo_scene s = scene_of(SPINNING_NEEDLE);
    tribo_model *whole = make(&s);
    cr_assert_eq(tribo_advance_fully(whole, T), TRIBO_OK, "%s", tribo_last_error(whole));
    tribo_stats stats;
    tribo_get_stats(whole, &stats);
    /* steps ended by their sweeps: restarts beyond the start's, the events' and the
       periodic ones */
    cr_assert(stats.restarts > 1 + stats.events + stats.steps / 2000 + 10,
              "%lld restarts, %lld events, %lld steps: no step ended by its sweep",
              stats.restarts, stats.events, stats.steps);
    s.work_limit = 997;
    tribo_model *parts = make(&s);
    int stops = 0;
    for (int k = 1; k <= 7; k++) {
        tribo_status st;
        while ((st = tribo_advance(parts, T * k / 7.0)) == TRIBO_INCOMPLETE)
            stops++;
        cr_assert_eq(st, TRIBO_OK, "%s", tribo_last_error(parts));
    }
    cr_expect(stops > 10, "%d stops", stops);
    cr_expect(same_outputs(whole, parts));
    tribo_free(whole);
    tribo_free(parts);
}

/* The paper's fixed step at its dt in a communication step of 100 (1.25e6 RK4 steps: the
   drop and its contact, each step at its weight, 855,000 units), and CVODE in the same steps
   over the paper's runs (model.md §7, to 5000) at the ends and the middle of epsilon's
   range: no advance stops early. */
Test(work_limit, ordinary_runs_stay_within_the_default, .timeout = 900)
{
    tribo_scene s = scene_of("integrator=0");
    tribo_model *m = make(&s);
    cr_expect_eq(tribo_advance(m, 100.0), TRIBO_OK, "fixed step to 100: %s", tribo_last_error(m));
    cr_expect_lt(m->work, 0.9 * s.work_limit, "%.0f units", m->work);
    tribo_free(m);
    const char *paper[] = {"mu=0.1 nu=0.1", "mu=1 nu=1"};
    const double epsilons[] = {0.1, 0.5, 1.0};
    for (size_t i = 0; i < 2; i++)
        for (size_t j = 0; j < 3; j++) {
            tribo_scene c = scene_of(paper[i]);
            c.epsilon = epsilons[j];
            tribo_model *r = make(&c);
            for (int k = 1; k <= 50; k++)
                cr_expect_eq(tribo_advance(r, 100.0 * k), TRIBO_OK, "%s epsilon %g to %d: %s",
                             paper[i], c.epsilon, 100 * k, tribo_last_error(r));
            tribo_free(r);
        }
}
