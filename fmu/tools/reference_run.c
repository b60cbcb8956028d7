/*
 * reference_run: the core driven directly through its C API, for the tests to compare
 * the FMUs against. It reads commands from stdin, one per line:
 *
 *   set NAME VALUE     a scene parameter, before `create`
 *   create             the instance, from the scene so far (defaults otherwise)
 *   advance T          tribo_advance to core time T (on a chute it may end before)
 *   param NAME VALUE   tribo_set_param (a tunable, mid-run)
 *   force F_T F_N      tribo_set_external_force
 *   print              one JSON line: every quantity by its tribo_quantity_name
 *   segments           one JSON line: every registered charge model's segment array, by its
 *                      name (null without the model)
 *
 * Numbers are printed with 17 significant digits, so they read back bit-identically.
 * A failure prints {"error": "..."} and exits with status 1.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "charge_registry.h"

#include "tribo.h"

static void print_number(double v)
{
    if (isnan(v))
        fputs("NaN", stdout);
    else if (isinf(v))
        fputs(v > 0 ? "Infinity" : "-Infinity", stdout);
    else
        printf("%.17g", v);
}

static void print_text(const char *s)
{
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            putchar('\\');
        putchar(*s);
    }
}

static int fail(const char *what, const char *why)
{
    fputs("{\"error\": \"", stdout);
    print_text(what);
    fputs(": ", stdout);
    print_text(why);
    puts("\"}");
    return 1;
}

static void print_segments(tribo_model *m, const char *key, tribo_segment_charge which, size_t n)
{
    double *q = malloc(n * sizeof *q);
    printf("\"%s\": ", key);
    if (q && tribo_get_segment_charges(m, which, q, n) == TRIBO_OK) {
        putchar('[');
        for (size_t i = 0; i < n; i++) {
            fputs(i ? ", " : "", stdout);
            print_number(q[i]);
        }
        putchar(']');
    } else {
        fputs("null", stdout);
    }
    free(q);
}

int main(void)
{
    tribo_scene scene;
    tribo_scene_defaults(&scene);
    tribo_model *m = NULL;
    char line[256], err[512];

    while (fgets(line, sizeof line, stdin)) {
        char cmd[32], name[64];
        double a = 0.0, b = 0.0;
        const int n = sscanf(line, "%31s", cmd);
        if (n != 1)
            continue;
        if (strcmp(cmd, "create") == 0) {
            if (!(m = tribo_create(&scene, err, sizeof err)))
                return fail("create", err);
            continue;
        }
        if (strcmp(cmd, "set") == 0 && sscanf(line, "%*s %63s %lf", name, &a) == 2) {
            if (tribo_scene_set(&scene, name, a, err, sizeof err) != TRIBO_OK)
                return fail("set", err);
            continue;
        }
        if (!m)
            return fail(cmd, "no instance: `create` first");
        tribo_status st = TRIBO_OK;
        if (strcmp(cmd, "advance") == 0 && sscanf(line, "%*s %lf", &a) == 1) {
            st = tribo_advance(m, a);
        } else if (strcmp(cmd, "param") == 0 && sscanf(line, "%*s %63s %lf", name, &a) == 2) {
            st = tribo_set_param(m, name, a);
        } else if (strcmp(cmd, "force") == 0 && sscanf(line, "%*s %lf %lf", &a, &b) == 2) {
            st = tribo_set_external_force(m, a, b);
        } else if (strcmp(cmd, "print") == 0) {
            putchar('{');
            for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++) {
                printf("%s\"%s\": ", q ? ", " : "", tribo_quantity_name((tribo_quantity)q));
                print_number(tribo_get(m, (tribo_quantity)q));
            }
            puts("}");
        } else if (strcmp(cmd, "segments") == 0) {
            const size_t n_seg = (size_t)tribo_get_scene(m)->n_segments;
            putchar('{');
            for (int k = 0; k < TRIBO_SEGMENTS_COUNT; k++) {
                fputs(k ? ", " : "", stdout);
                print_segments(m, TRIBO_CHARGE_MODELS[k]->name, (tribo_segment_charge)k, n_seg);
            }
            puts("}");
        } else {
            return fail("unknown command", cmd);
        }
        if (st != TRIBO_OK && st != TRIBO_ENDED) /* (the run may end on a chute) */
            return fail(cmd, tribo_last_error(m));
    }
    tribo_free(m);
    return 0;
}
