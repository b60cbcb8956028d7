/* sustained_contact: grains that slide and roll down the chute, measured through the C API
 * (a command, not a test; docs/reference_case.md, "Sustained contact").
 *
 *   tribo_sustained_contact [rounds=3]
 *
 * Each case is the SI reference case (src/si/si_quantities.def's defaults, a chute of 0.3 m)
 * with some settings changed, run with CVODE to the chute's exit, `rounds` times, the
 * fastest CPU time kept; once with the SI default stick_model (rigid) and once with
 * stick_model = 0 (compliant). A library without stick_model (an older revision, built by
 * scripts/bench_sustained_contact.sh to compare) runs the one law it has, reported as
 * "compliant". Printed per case and law: CPU seconds, CVODE steps, events, impacts, the exit
 * time and q/m of both charge models at the exit.
 *
 * Only API that every revision since the SI front end has is used (quantities are looked up
 * by name), so that the same source measures the code before and after a change.
 */
#include "si.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_clock.h"

/* Quantities by their names, which every revision keeps (their enumerators were renamed). */
static tribo_quantity quantity(const char *name)
{
    for (int q = 0; tribo_quantity_name((tribo_quantity)q); q++)
        if (!strcmp(tribo_quantity_name((tribo_quantity)q), name))
            return (tribo_quantity)q;
    fprintf(stderr, "no quantity %s\n", name);
    exit(1);
}

static tribo_si_quantity si_quantity(const char *name)
{
    for (int q = 0; tribo_si_quantity_name((tribo_si_quantity)q); q++)
        if (!strcmp(tribo_si_quantity_name((tribo_si_quantity)q), name))
            return (tribo_si_quantity)q;
    fprintf(stderr, "no SI quantity %s\n", name);
    exit(1);
}

static const struct {
    const char *name, *settings;
} CASES[] = {
    {"disc placed, mu 0.5 (rolls)", "epsilon=1 mu=0.5 drop_height=0"},
    {"disc placed, mu 0 (slides)", "epsilon=1 mu=0 drop_height=0"},
    {"flat eps 0.3 placed (slides)", "epsilon=0.3 drop_height=0"},
    {"0.1 mm eps 0.3 phi0 pi/4 (settles)", "semi_major_axis=5e-5 epsilon=0.3 phi0=0.78539816339744828"},
    {"0.1 mm eps 1 (settles, rolls)", "semi_major_axis=5e-5 epsilon=1"},
    {"reference case (tumbles off)", ""},
};

typedef struct {
    int ok;
    double cpu, exit_time, qm_static, qm_sliding, impacts;
    long long steps, events;
} outcome;

static outcome run(const char *settings, const char *law, int rounds)
{
    outcome o = {0};
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    char err[1024];
    if (tribo_si_scene_apply(&si, "chute_length=0.3", err, sizeof err) != TRIBO_OK ||
        tribo_si_scene_apply(&si, settings, err, sizeof err) != TRIBO_OK) {
        fprintf(stderr, "%s\n", err);
        exit(1);
    }
    if (law && tribo_si_scene_apply(&si, law, err, sizeof err) != TRIBO_OK)
        return o; /* a library without the law */
    tribo_si_derived d;
    if (tribo_si_derive(&si, &d, err, sizeof err) != TRIBO_OK) {
        fprintf(stderr, "%s\n", err);
        exit(1);
    }
    o.cpu = 1e300;
    for (int r = 0; r < rounds; r++) {
        tribo_model *m = tribo_create(&d.scene, err, sizeof err);
        if (!m) {
            fprintf(stderr, "%s\n", err);
            exit(1);
        }
        const double t0 = cpu_seconds();
        const tribo_status st = tribo_advance_fully(m, 10.0 / d.t_star);
        const double cpu = cpu_seconds() - t0;
        if (st != TRIBO_ENDED) {
            fprintf(stderr, "%s: status %d, %s\n", settings, (int)st, tribo_last_error(m));
            exit(1);
        }
        if (cpu < o.cpu)
            o.cpu = cpu;
        tribo_stats s;
        tribo_get_stats(m, &s);
        o.steps = s.steps;
        o.events = s.events;
        o.impacts = tribo_get(m, quantity("impacts"));
        o.exit_time = tribo_si_get(&d, m, si_quantity("exit_time"));
        o.qm_static = tribo_si_get(&d, m, si_quantity("charge_to_mass_static"));
        o.qm_sliding = tribo_si_get(&d, m, si_quantity("charge_to_mass_sliding"));
        tribo_free(m);
    }
    o.ok = 1;
    return o;
}

int main(int argc, char **argv)
{
    int rounds = 3;
    for (int i = 1; i < argc; i++)
        if (sscanf(argv[i], "rounds=%d", &rounds) != 1 || rounds < 1) {
            fprintf(stderr, "usage: %s [rounds=N]\n", argv[0]);
            return 2;
        }
    printf("| case | stick | CPU [s] | steps | events | impacts | exit [s] | q/m static [uC/kg] | "
           "q/m sliding [uC/kg] |\n|---|---|---|---|---|---|---|---|---|\n");
    double total[2] = {0.0, 0.0};
    for (size_t c = 0; c < sizeof CASES / sizeof CASES[0]; c++) {
        const char *laws[2] = {"stick_model=1", "stick_model=0"};
        outcome o[2];
        o[0] = run(CASES[c].settings, laws[0], rounds);
        o[1] = o[0].ok ? run(CASES[c].settings, laws[1], rounds) : run(CASES[c].settings, NULL, rounds);
        for (int k = 0; k < 2; k++) {
            if (!o[k].ok)
                continue;
            total[k] += o[k].cpu;
            printf("| %s | %s | %.3f | %lld | %lld | %.0f | %.6f | %.4g | %.4g |\n", CASES[c].name,
                   k ? "compliant" : "rigid", o[k].cpu, o[k].steps, o[k].events, o[k].impacts,
                   o[k].exit_time, 1e6 * o[k].qm_static, 1e6 * o[k].qm_sliding);
        }
    }
    printf("\ntotal CPU: rigid %.3f s, compliant %.3f s\n", total[0], total[1]);
    return 0;
}
