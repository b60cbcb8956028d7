/*
 * separator.h: the free-fall separator (docs/model.md §10), a second, small model for the
 * separation line: a charged grain leaves the chute and falls between two vertical plate
 * electrodes, through still air, into one of n bins at the bottom or onto a plate. SI units
 * throughout; its table is separator_quantities.def. It knows nothing of the chute's model
 * (the entry comes as inputs) nor of FMI.
 *
 * Usage:
 *   tribo_separator_scene sc;
 *   tribo_separator_scene_defaults(&sc);        // separator_quantities.def's defaults
 *   sc.voltage = 20e3;
 *   char err[512];
 *   tribo_separator *s = tribo_separator_create(&sc, err, sizeof err);
 *   double in[TRIBO_SEPARATOR_INPUT_COUNT] = {[TRIBO_SEPARATOR_INPUT_RELEASED] = 1,
 *       [TRIBO_SEPARATOR_INPUT_U_ENTRY] = 0.3, [TRIBO_SEPARATOR_INPUT_CHARGE_TO_MASS] = 1e-5};
 *   tribo_separator_set_inputs(s, in);          // released now: the flight starts
 *   while (tribo_separator_advance(s, 10.0) == TRIBO_INCOMPLETE) {}  // to the end: TRIBO_ENDED
 *   int bin = (int)tribo_separator_get(s, TRIBO_SEPARATOR_Q_BIN);
 *   tribo_separator_free(s);
 *
 * Lab frame (model.md §10): x across the gap (the plates at x = -w/2 and x = +w/2), y along
 * the plates, z up, the entry at (x_entry, 0, 0).
 */
#ifndef TRIBO_SEPARATOR_H
#define TRIBO_SEPARATOR_H

#include <stddef.h>

#include "tribo.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every parameter, one field per row of separator_quantities.def. */
typedef struct tribo_separator_scene {
#define TRIBO_PARAMETER(name, type, ...) TRIBO_CTYPE_##type name;
#include "separator_quantities.def"
} tribo_separator_scene;

/* The chute's horizontal direction (parameter chute_direction). */
typedef enum tribo_separator_direction {
    TRIBO_SEPARATOR_ALONG_PLATES = 0,
    TRIBO_SEPARATOR_ACROSS_GAP = 1
} tribo_separator_direction;

void tribo_separator_scene_defaults(tribo_separator_scene *scene);
const tribo_param_info *tribo_separator_param_table(size_t *count);
const tribo_param_info *tribo_separator_param_find(const char *name);
/* Set one, checked against its range; apply "name=value ..."; each as tribo_scene_set /
   tribo_scene_apply. */
tribo_status tribo_separator_scene_set(tribo_separator_scene *scene, const char *name, double value,
                                       char *msg, size_t msg_size);
tribo_status tribo_separator_scene_apply(tribo_separator_scene *scene, const char *settings,
                                         char *msg, size_t msg_size);

/* The inputs, in the table's order (released: 0 or 1). */
typedef enum tribo_separator_input {
#define TRIBO_BOOLEAN_INPUT(id, ...) TRIBO_SEPARATOR_INPUT_##id,
#define TRIBO_INPUT(id, ...) TRIBO_SEPARATOR_INPUT_##id,
#include "separator_quantities.def"
    TRIBO_SEPARATOR_INPUT_COUNT
} tribo_separator_input;
/* Their rows (for tribo_param_check and messages): released is an INTEGER in [0, 1]. */
const tribo_param_info *tribo_separator_input_table(size_t *count);

/* What the parameters mean for the flight (model.md §10), from the parameters alone. */
typedef struct tribo_separator_derived {
    double field;           /* E_x = -U / w, V/m                                       */
    double diameter;        /* d_e, m: the volume-equivalent sphere of the grain       */
    double area;            /* pi d_e^2 / 4, m^2                                        */
    double mass;            /* rho pi d_e^3 / 6, kg                                     */
    double half_size;       /* r = a: the grain touches a plate where |x| >= w/2 - r     */
    double x_limit;         /* w/2 - r                                                  */
    double relaxation_time; /* m / (3 pi mu d_e), s (0 without viscosity)              */
} tribo_separator_derived;

/* Every parameter in its range, and the combinations: the grain fits the gap (2 a < w) and
   the entry lies inside it (|x_entry| < w/2 - a). A failure names the parameter (or both),
   the value and the valid range. */
tribo_status tribo_separator_derive(const tribo_separator_scene *scene, tribo_separator_derived *d,
                                    char *msg, size_t msg_size);

/* How a run ended. */
typedef enum tribo_separator_end {
    TRIBO_SEPARATOR_RUNNING = 0,
    TRIBO_SEPARATOR_LANDED = 1, /* at the bins, z = -H */
    TRIBO_SEPARATOR_CAUGHT = 2  /* on a plate, |x| = w/2 - r */
} tribo_separator_end;

typedef struct tribo_separator tribo_separator;

/* A new instance at time 0, the grain held at the entry; NULL and the reason in err on
   failure (tribo_separator_derive's, or memory). */
tribo_separator *tribo_separator_create(const tribo_separator_scene *scene, char *err,
                                        size_t err_size);
void tribo_separator_free(tribo_separator *s);
const tribo_separator_scene *tribo_separator_get_scene(const tribo_separator *s);
const char *tribo_separator_last_error(const tribo_separator *s);

/* The inputs from the current time on, each checked against its range (a refusal names it
   and changes nothing). The first time released is true the grain leaves the entry with the
   velocity and charge these inputs give; later inputs change nothing (the grain is gone). */
tribo_status tribo_separator_set_inputs(tribo_separator *s,
                                        const double values[TRIBO_SEPARATOR_INPUT_COUNT]);

/* Advance to time t (>= the current time, <= TRIBO_TIME_MAX). TRIBO_OK at t; TRIBO_ENDED
   where the run ends (at the bins or on a plate, the time stays there: every later advance
   returns TRIBO_ENDED and changes nothing); TRIBO_INCOMPLETE where the work limit stopped it
   early (it goes on from there); TRIBO_ERR_TIME for a time that goes back or is not finite;
   TRIBO_ERR_INTEGRATOR where CVODE fails (the instance must be made again or a state
   loaded). Every advance starts CVODE afresh from the state reached, so that the state of
   tribo_separator_state_save is the whole of a run: a loaded state continues bit for bit. */
tribo_status tribo_separator_advance(tribo_separator *s, double t);

/* What can be read: the time, the outputs and the calculated parameters. */
typedef enum tribo_separator_quantity {
#define TRIBO_TIME(id, ...) TRIBO_SEPARATOR_Q_##id,
#define TRIBO_OUTPUT(id, ...) TRIBO_SEPARATOR_Q_##id,
#define TRIBO_CALCULATED(id, ...) TRIBO_SEPARATOR_Q_##id,
#include "separator_quantities.def"
    TRIBO_SEPARATOR_Q_COUNT
} tribo_separator_quantity;

double tribo_separator_get(const tribo_separator *s, tribo_separator_quantity q);
/* A calculated parameter of derived numbers alone (the others read 0 here). */
double tribo_separator_calculated(const tribo_separator_derived *d, tribo_separator_quantity q);
const char *tribo_separator_quantity_name(tribo_separator_quantity q);
const tribo_separator_derived *tribo_separator_get_derived(const tribo_separator *s);
tribo_separator_end tribo_separator_end_of(const tribo_separator *s);

/* For the table's accessors: the Reynolds number now, and the bin landed in (0: none). */
double tribo_separator_reynolds(const tribo_separator *s);
int tribo_separator_bin(const tribo_separator *s);
/* The bin of a position x at the bins: 1 to n_bins from x = -w/2 (model.md §10). */
int tribo_separator_bin_of(const tribo_separator_scene *scene, double x);
/* The drag per unit mass, F_drag / m, of velocity v (model.md §10, Schiller-Naumann). */
void tribo_separator_drag(const tribo_separator_scene *scene, const tribo_separator_derived *d,
                          const double v[3], double drag_per_mass[3]);

/* The state: plain bytes, no pointers (the scene, the time, the inputs, the release, the
   motion, how it ended). A load checks everything against the instance's scene and the
   model's ranges before the instance changes. */
size_t tribo_separator_state_size(const tribo_separator *s);
tribo_status tribo_separator_state_save(const tribo_separator *s, void *buffer, size_t size);
tribo_status tribo_separator_state_load(tribo_separator *s, const void *buffer, size_t size);

#ifdef __cplusplus
}
#endif

#endif
