/* A feed's grains (settings lines of the SI front end, as bench/population_feed.py writes
   them) run through the C API one by one to their end or the horizon, each grain's end
   printed on a line in full precision: the run's status, then time, X, Y, phi, U, V, Omega,
   Q_static, Q_sliding, impacts, work_dissipated. It uses only the SI front end's settings
   text and the model's advance, so that it compiles against earlier cores too
   (scripts/bench_feeder_precision.sh --before REV sets two cores' ends side by side).
   Usage: tribo_feeder_state FEED [EXTRA_SETTINGS] [HORIZON_S=5] */
#include "feed_args.h"
#include "si.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    feed_args args;
    if (!open_feed(argc, argv, &args))
        return 2;
    static const tribo_quantity shown[] = {
        TRIBO_QUANTITY_TIME,   TRIBO_QUANTITY_X,       TRIBO_QUANTITY_Y,
        TRIBO_QUANTITY_PHI,    TRIBO_QUANTITY_U,       TRIBO_QUANTITY_V,
        TRIBO_QUANTITY_OMEGA,  TRIBO_QUANTITY_STATIC,  TRIBO_QUANTITY_SLIDING,
        TRIBO_QUANTITY_IMPACTS, TRIBO_QUANTITY_WORK_DISSIPATED};
    static char line[1 << 14];
    while (fgets(line, sizeof line, args.feed)) {
        char err[1024];
        tribo_si_scene si;
        tribo_si_scene_defaults(&si);
        tribo_si_derived d;
        tribo_model *m = NULL;
        if (tribo_si_scene_apply(&si, line, err, sizeof err) != TRIBO_OK ||
            tribo_si_scene_apply(&si, args.extra, err, sizeof err) != TRIBO_OK ||
            tribo_si_derive(&si, &d, err, sizeof err) != TRIBO_OK ||
            !(m = tribo_create(&d.scene, err, sizeof err))) {
            fprintf(stderr, "refused: %s\n", err);
            fclose(args.feed);
            return 1;
        }
        printf("%d", (int)tribo_advance_fully(m, args.horizon / d.t_star));
        for (size_t i = 0; i < sizeof shown / sizeof shown[0]; i++)
            printf(" %.17g", tribo_get(m, shown[i]));
        printf("\n");
        tribo_free(m);
    }
    fclose(args.feed);
    return 0;
}
