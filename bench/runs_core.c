/* The core's cost of a package command's runs: the runs `tribo impact-map`, `tribo calibrate`
   and `tribo line` make, written by bench/runs_feed.py one a line, run through the C API
   alone (the SI front end, and the separator's core for the line), in this process, one
   after another (scripts/bench_runs_package.sh sets the package's whole command beside it).
   A line of the feed:

       HORIZON UNIT SI_SETTINGS [| SEPARATOR_SETTINGS]

   UNIT `s` (the horizon in seconds: a chute's grain) or `tstar` (in units of the run's t*:
   an impact's time limit); SI_SETTINGS the SI front end's "name=value ..." (the FMU's names
   and units); after `|`, the separator's settings of a line's grain (its size, shape, tilt,
   x_entry, the line's separator settings; the voltage apart): the grain leaves the chute
   where its run ends and is flown at every voltage of VOLTAGES, as the package does
   (python/tribo/line/grain.py: held to the chute's end, released with the chute's u, v and
   q/m where it left, to the horizon after that). Prints the runs, the CPU of each part and
   the failures; exits 3 where a run failed.
   Usage: tribo_runs_core FEED [VOLTAGES=v1,v2,...] [SEPARATOR_HORIZON_S=10] */
#include "separator.h"
#include "si.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_clock.h"

enum { MAX_VOLTAGES = 256 };

/* What a chute's run hands the separator. */
typedef struct chute_end {
    int exited;
    double time_end, u, v, charge_to_mass;
} chute_end;

/* One run of the SI front end to `horizon` (s, or in t* with in_t_star); 0, or 1 where it
   failed, -1 where its set-up is refused. */
static int run_chute(const char *settings, double horizon, int in_t_star, chute_end *end)
{
    char err[1024];
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    tribo_si_derived d;
    if (tribo_si_scene_apply(&si, settings, err, sizeof err) != TRIBO_OK ||
        tribo_si_derive(&si, &d, err, sizeof err) != TRIBO_OK) {
        fprintf(stderr, "refused: %s\n", err);
        return -1;
    }
    tribo_model *m = tribo_create(&d.scene, err, sizeof err);
    if (!m) {
        fprintf(stderr, "refused: %s\n", err);
        return -1;
    }
    const tribo_status st = tribo_advance_fully(m, in_t_star ? horizon : horizon / d.t_star);
    end->exited = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_EXITED) != 0.0;
    end->time_end = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_TIME);
    end->u = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_U);
    end->v = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_V);
    end->charge_to_mass = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_Q_PER_M);
    tribo_free(m);
    return st != TRIBO_OK && st != TRIBO_ENDED;
}

/* One separator run of a grain that left the chute as `end` says (or never did); as
   run_chute's result. */
static int fly(const char *settings, double voltage, const chute_end *end, double horizon)
{
    char err[1024];
    tribo_separator_scene sc;
    tribo_separator_scene_defaults(&sc);
    if (tribo_separator_scene_apply(&sc, settings, err, sizeof err) != TRIBO_OK ||
        tribo_separator_scene_set(&sc, "voltage", voltage, err, sizeof err) != TRIBO_OK) {
        fprintf(stderr, "refused: %s\n", err);
        return -1;
    }
    tribo_separator *s = tribo_separator_create(&sc, err, sizeof err);
    if (!s) {
        fprintf(stderr, "refused: %s\n", err);
        return -1;
    }
    tribo_status st = TRIBO_OK;
    if (end->time_end > 0.0)
        st = tribo_separator_advance(s, end->time_end);
    if (end->exited && st == TRIBO_OK) {
        const double in[TRIBO_SEPARATOR_INPUT_COUNT] = {
            [TRIBO_SEPARATOR_INPUT_RELEASED] = 1.0, [TRIBO_SEPARATOR_INPUT_U_ENTRY] = end->u,
            [TRIBO_SEPARATOR_INPUT_V_ENTRY] = end->v,
            [TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS] = end->charge_to_mass};
        st = tribo_separator_set_inputs(s, in);
        while (st == TRIBO_OK && (st = tribo_separator_advance(s, end->time_end + horizon)) ==
                                     TRIBO_INCOMPLETE)
            st = TRIBO_OK; /* the work limit: go on from there, as the FMU's step does */
    }
    tribo_separator_free(s);
    return st != TRIBO_OK && st != TRIBO_ENDED;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s FEED [VOLTAGES] [SEPARATOR_HORIZON_S]\n", argv[0]);
        return 2;
    }
    double voltages[MAX_VOLTAGES];
    int n_voltages = 0;
    if (argc > 2) {
        for (char *p = argv[2]; *p && n_voltages < MAX_VOLTAGES;) {
            char *next;
            voltages[n_voltages++] = strtod(p, &next);
            p = *next == ',' ? next + 1 : next;
            if (next == p && *p) {
                fprintf(stderr, "voltages %s: numbers separated by commas\n", argv[2]);
                return 2;
            }
        }
    }
    const double horizon = argc > 3 ? atof(argv[3]) : 10.0;
    FILE *f = fopen(argv[1], "r");
    if (!f) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    static char line[1 << 15];
    int runs = 0, flights = 0, failed = 0;
    double chute_cpu = 0.0, separator_cpu = 0.0;
    while (fgets(line, sizeof line, f)) {
        char unit[16];
        double t_end;
        int used = 0;
        if (sscanf(line, "%lf %15s %n", &t_end, unit, &used) != 2) {
            fprintf(stderr, "not a run: %s", line);
            fclose(f);
            return 2;
        }
        char *separator = strchr(line, '|');
        if (separator)
            *separator++ = '\0';
        chute_end end;
        double start = cpu_seconds();
        int st = run_chute(line + used, t_end, strcmp(unit, "tstar") == 0, &end);
        chute_cpu += cpu_seconds() - start;
        runs++;
        for (int i = 0; separator && st >= 0 && i < n_voltages; i++) {
            start = cpu_seconds();
            const int flown = fly(separator, voltages[i], &end, horizon);
            separator_cpu += cpu_seconds() - start;
            flights++;
            st = flown < 0 ? flown : st + flown;
        }
        if (st < 0) {
            fclose(f);
            return 1;
        }
        failed += st;
    }
    fclose(f);
    printf("runs %d  separator runs %d  CPU %.3f s  chute %.3f s  separator %.3f s  failed %d\n",
           runs, flights, chute_cpu + separator_cpu, chute_cpu, separator_cpu, failed);
    return failed ? 3 : 0;
}
