/* Grains (settings lines of the SI front end) each run through its first contact by several
   integrators: the first contact's time tau_c is found with CVODE (to 0.01), then each
   integrator's motion at tau_c + 0.5, 1 and 3 is printed in full precision, a line each: grain,
   integrator (its index among the arguments), tau - tau_c, the run's status, X, Y, phi, U, V,
   Omega, in_contact, impacts (scripts/bench_first_contacts.sh, docs/integrators.md).
   Usage: tribo_first_contacts SETUPS EXTRA_SETTINGS INTEGRATOR_SETTINGS... */
#include "si.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The grain of the settings `parts` (applied in turn to the SI defaults), or NULL (said why). */
static tribo_model *create(const char *line, const char *extra, const char *integrator)
{
    const char *parts[] = {line, extra, integrator};
    char err[1024];
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    tribo_status st = TRIBO_OK;
    for (size_t i = 0; st == TRIBO_OK && i < sizeof parts / sizeof parts[0]; i++)
        st = tribo_si_scene_apply(&si, parts[i], err, sizeof err);
    tribo_si_derived d;
    tribo_model *m = st == TRIBO_OK && tribo_si_derive(&si, &d, err, sizeof err) == TRIBO_OK
                         ? tribo_create(&d.scene, err, sizeof err)
                         : NULL;
    if (!m)
        fprintf(stderr, "refused: %s\n", err);
    return m;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s SETUPS EXTRA_SETTINGS INTEGRATOR_SETTINGS...\n", argv[0]);
        return 2;
    }
    FILE *f = fopen(argv[1], "r");
    if (!f) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    static const double after[] = {0.5, 1.0, 3.0};
    static const tribo_quantity shown[] = {TRIBO_QUANTITY_X, TRIBO_QUANTITY_Y, TRIBO_QUANTITY_PHI,
                                           TRIBO_QUANTITY_U, TRIBO_QUANTITY_V, TRIBO_QUANTITY_OMEGA,
                                           TRIBO_QUANTITY_IN_CONTACT, TRIBO_QUANTITY_IMPACTS};
    static char line[1 << 14];
    for (int grain = 0; fgets(line, sizeof line, f); grain++) {
        line[strcspn(line, "\n")] = 0;
        tribo_model *m = create(line, argv[2], "integrator=1");
        if (!m)
            return 1;
        double tau_c = 0.0;
        while (tribo_get(m, TRIBO_QUANTITY_IMPACTS) < 1.0 && tribo_advance_fully(m, tau_c + 0.01) == TRIBO_OK)
            tau_c += 0.01;
        tribo_free(m);
        for (int k = 3; k < argc; k++) {
            if (!(m = create(line, argv[2], argv[k])))
                return 1;
            for (size_t j = 0; j < sizeof after / sizeof after[0]; j++) {
                const int st = (int)tribo_advance_fully(m, tau_c + after[j]);
                printf("%d %d %g %d", grain, k - 3, after[j], st);
                for (size_t i = 0; i < sizeof shown / sizeof shown[0]; i++)
                    printf(" %.17g", tribo_get(m, shown[i]));
                printf("\n");
                if (st != TRIBO_OK)
                    break;
            }
            tribo_free(m);
        }
    }
    fclose(f);
    return 0;
}
