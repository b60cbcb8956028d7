/* record: the outputs of the paper's study grid and of the stability matrix, bit-exactly,
   for the regression test that holds a change to "behaviour does not change".

     tribo_regression_record > tests/regression/golden.txt
     tribo_regression_record PART...      only the parts named (PARTS below): study,
                                          stability (or its runs of the fixed step and of
                                          CVODE apart: stability_fixed_step,
                                          stability_cvode), study_contact_point, physical

   At each sample time one line: run name, time (C99 hex float), "hash" and an FNV-1a hash
   of the bytes of every output (but those of a charge model the run leaves out) and of
   every per-segment charge array. At the last sample
   of a run, also every output by name with its value in %a, so that a difference can be
   read.

   The study grid and the stability matrix set damping_point = 1 (the centre dashpot, the
   law before model.md §3's revision): they are the regression of that option, which must
   keep reproducing the results it had when it was the only law. The study grid is then
   recorded again with the default, the dashpot on the contact point
   (study_contact_point/...).

   A change that moves the record on purpose re-records it and says in its commit message
   what moved, by how much and why (git log tests/regression/golden.txt), checked where it
   can be by a record whose hash leaves the change out. */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "matrix.h"
#include "physical_scale.h"

static uint64_t fnv1a(const void *data, size_t n, uint64_t h)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* The charge model whose row makes an output (charge_registry.def's block of quantities.def),
   or -1: the outputs of a model the scene leaves out read 0 and are not recorded, so that a
   model registered later, off in these runs, leaves the record as it is. */
static int model_of_output(tribo_quantity q)
{
    switch (q) {
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values)                                   \
    case TRIBO_QUANTITY_CAPPED_##id:                                                            \
    case TRIBO_QUANTITY_LOST_##id: return TRIBO_SEGMENTS_##id;
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
    default: return -1;
    }
}

static void print_outputs(const char *run, tribo_model *m, int last)
{
    const double t = tribo_get(m, TRIBO_QUANTITY_TIME);
    uint64_t h = 14695981039346656037ull;
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++) {
        const int model = model_of_output((tribo_quantity)q);
        if (model >= 0 && !tribo_includes_charge_model(m, (tribo_segment_charge)model))
            continue;
        const double v = tribo_get(m, (tribo_quantity)q);
        h = fnv1a(&v, sizeof v, h);
        if (last)
            printf("%s %a %s %a\n", run, t, tribo_quantity_name((tribo_quantity)q), v);
    }
    const size_t n = (size_t)tribo_get_scene(m)->n_segments;
    double *seg = malloc(n * sizeof *seg);
    for (int which = 0; which < TRIBO_SEGMENTS_COUNT; which++)
        if (seg && tribo_get_segment_charges(m, (tribo_segment_charge)which, seg, n) == TRIBO_OK)
            h = fnv1a(seg, n * sizeof *seg, h);
    free(seg);
    printf("%s %a hash %016" PRIx64 "\n", run, t, h);
}

/* Advance through the sample times, printing the outputs at each. */
static void run_scene(const char *run, const tribo_scene *s, const double *times, int n_times)
{
    char err[512];
    tribo_model *m = tribo_create(s, err, sizeof err);
    if (!m) {
        printf("%s create-failed %s\n", run, err);
        return;
    }
    for (int k = 0; k < n_times; k++) {
        if (tribo_advance_fully(m, times[k]) != TRIBO_OK) {
            printf("%s %a advance-failed %s\n", run, times[k], tribo_last_error(m));
            break;
        }
        print_outputs(run, m, k == n_times - 1);
    }
    tribo_free(m);
}

/* The study grid (model.md §7, the settings of the committed study: CVODE at rtol 1e-8,
   atol 1e-10), epsilon 0.1 ... 1.0, mu = nu = 0.1 and 1.0, both charge models; CVODE to
   tau = 1000, the fixed step (dt = 8e-5) to tau = 50; with the dashpot at damping_point,
   runs named <prefix>/<integrator>/eps<epsilon>/mu<mu>. */
static void record_study(const char *prefix, int damping_point)
{
    const double cvode_times[] = {1, 5, 10, 20, 50, 100, 200, 500, 1000};
    const double fixed_times[] = {1, 5, 10, 20, 50};
    for (int integrator = 0; integrator < 2; integrator++) {
        for (int e = 1; e <= 10; e++) {
            for (int f = 0; f < 2; f++) {
                tribo_scene s;
                tribo_scene_defaults(&s);
                s.epsilon = e / 10.0;
                s.mu = s.nu = f ? 1.0 : 0.1;
                s.damping_point = damping_point;
                s.charge_model_static = s.charge_model_sliding = 1;
                s.integrator = integrator ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
                s.rtol = 1e-8;
                s.atol = 1e-10;
                char run[64];
                snprintf(run, sizeof run, "%s/%s/eps%.1f/mu%.1f", prefix,
                         integrator ? "cvode" : "fixed", s.epsilon, s.mu);
                if (integrator)
                    run_scene(run, &s, cvode_times, sizeof cvode_times / sizeof *cvode_times);
                else
                    run_scene(run, &s, fixed_times, sizeof fixed_times / sizeof *fixed_times);
            }
        }
    }
}

/* Physical set-ups with the SI front end's defaults (the rigid stick, CVODE) but the fixed
   breakdown limit (§8b: the record's outputs are the cylinder's and its segments', which the
   Paschen limit of the spheroid's bands, §8e, leaves alone but for the grain's outputs): the
   reference case, the micro-scale one and the grid of Young's moduli and sizes, each sampled
   at 0.01, 0.03, 0.1 and 0.3 s and at the chute's exit, runs named physical/<n>. */
static void record_physical(void)
{
    const double times_s[] = {0.01, 0.03, 0.1, 0.3, 10.0};
    const int n_times = sizeof times_s / sizeof *times_s;
    char settings[64][160];
    int n = 0;
    snprintf(settings[n++], sizeof settings[0], "breakdown_model=0 %s", PHYSICAL_REFERENCE);
    snprintf(settings[n++], sizeof settings[0], "breakdown_model=0 %s", PHYSICAL_MICRO);
    for (int e = 0; e < N_PHYSICAL_MODULI; e++)
        for (int z = 0; z < N_PHYSICAL_SIZES; z++)
            snprintf(settings[n++], sizeof settings[0],
                     "breakdown_model=0 youngs_modulus_particle=%.17g semi_major_axis=%.17g",
                     PHYSICAL_MODULI[e],
                     0.5 * PHYSICAL_SIZES[z]);
    for (int c = 0; c < n; c++) {
        char run[32], err[512];
        snprintf(run, sizeof run, "physical/%d", c);
        tribo_si_derived d;
        if (physical_derive(settings[c], &d, err, sizeof err) != TRIBO_OK) {
            printf("%s derive-failed %s\n", run, err);
            continue;
        }
        tribo_model *m = tribo_create(&d.scene, err, sizeof err);
        if (!m) {
            printf("%s create-failed %s\n", run, err);
            continue;
        }
        for (int k = 0; k < n_times; k++) {
            const tribo_status status = tribo_advance_fully(m, times_s[k] / d.t_star);
            if (status != TRIBO_OK && status != TRIBO_ENDED) {
                printf("%s %a advance-failed %s\n", run, times_s[k], tribo_last_error(m));
                break;
            }
            print_outputs(run, m, status == TRIBO_ENDED || k == n_times - 1);
            if (status == TRIBO_ENDED)
                break;
        }
        tribo_free(m);
    }
}

enum stability_runs { FIXED_STEP_RUNS = 1, CVODE_RUNS = 2, EVERY_RUN = 3 };

/* The stability matrix, every case with every integrator (`runs`: those of the fixed step,
   of CVODE or both), sampled as its test does (every 0.5 to tau = 50); every 10th sample
   is printed. */
static void record_stability(enum stability_runs runs)
{
    double times[100];
    for (int k = 0; k < 100; k++)
        times[k] = 0.5 * (k + 1);
    for (int c = 0; c < N_STABILITY_CASES; c++) {
        for (int i = 0; i < N_STABILITY_INTEGRATORS; i++) {
            const int fixed = STABILITY_INTEGRATORS[i] == TRIBO_INTEGRATOR_FIXED_STEP;
            if (!(runs & (fixed ? FIXED_STEP_RUNS : CVODE_RUNS)))
                continue;
            tribo_scene s;
            tribo_scene_defaults(&s);
            tribo_scene_apply(&s, STABILITY_CASES[c].settings, NULL, 0);
            s.damping_point = TRIBO_DAMPING_CENTRE;
            s.integrator = STABILITY_INTEGRATORS[i];
            char run[128];
            snprintf(run, sizeof run, "stability/%d/%s", c,
                     stability_integrator_name(STABILITY_INTEGRATORS[i]));
            for (char *p = run; *p; p++)
                if (*p == ' ')
                    *p = '_';
            char err[512];
            tribo_model *m = tribo_create(&s, err, sizeof err);
            if (!m) {
                printf("%s create-failed %s\n", run, err);
                continue;
            }
            for (int k = 0; k < 100; k++) {
                if (tribo_advance_fully(m, times[k]) != TRIBO_OK) {
                    printf("%s %a advance-failed %s\n", run, times[k], tribo_last_error(m));
                    break;
                }
                if ((k + 1) % 10 == 0)
                    print_outputs(run, m, k == 99);
            }
            tribo_free(m);
        }
    }
}

static void record_study_centre(void) { record_study("study", TRIBO_DAMPING_CENTRE); }
static void record_stability_every_run(void) { record_stability(EVERY_RUN); }
static void record_stability_fixed_step(void) { record_stability(FIXED_STEP_RUNS); }
static void record_stability_cvode(void) { record_stability(CVODE_RUNS); }

/* The default: the study grid with the dashpot on the contact point. */
static void record_study_contact_point(void)
{
    record_study("study_contact_point", TRIBO_DAMPING_CONTACT_POINT);
}

/* The parts of the record that the regression tests run each on its own
   (tests/regression/CMakeLists.txt), so that ctest shares them out over the cores: golden.txt
   is study, stability (each case's runs of both integrators in turn), study_contact_point
   and physical. */
static const struct {
    const char *name;
    void (*record)(void);
} PARTS[] = {{"study", record_study_centre},
             {"stability", record_stability_every_run},
             {"stability_fixed_step", record_stability_fixed_step},
             {"stability_cvode", record_stability_cvode},
             {"study_contact_point", record_study_contact_point},
             {"physical", record_physical}};
enum { N_PARTS = sizeof PARTS / sizeof *PARTS };

/* The index of the part named `name` in PARTS, or -1. */
static int part_named(const char *name)
{
    for (int p = 0; p < N_PARTS; p++)
        if (strcmp(name, PARTS[p].name) == 0)
            return p;
    return -1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        record_study_centre();
        record_stability_every_run();
        record_study_contact_point();
        record_physical();
        return 0;
    }
    for (int a = 1; a < argc; a++) {
        if (part_named(argv[a]) < 0) {
            fprintf(stderr, "tribo_regression_record: no part %s (the parts:", argv[a]);
            for (int p = 0; p < N_PARTS; p++)
                fprintf(stderr, " %s", PARTS[p].name);
            fprintf(stderr, ")\n");
            return 2;
        }
    }
    for (int a = 1; a < argc; a++)
        PARTS[part_named(argv[a])].record();
    return 0;
}
