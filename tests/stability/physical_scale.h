/* physical_scale.h: the stability checks of matrix.h on physical set-ups (the SI front end,
   docs/model.md §8): the SI reference case, a micro-scale one, and a grid of Young's
   moduli and sizes, each run with CVODE from the drop to the chute's exit. */
#ifndef TRIBO_STABILITY_PHYSICAL_SCALE_H
#define TRIBO_STABILITY_PHYSICAL_SCALE_H

#include "matrix.h"
#include "si.h"

/* The reference case (si_quantities.def's defaults, a chute of 0.3 m), then settings. */
#define PHYSICAL_REFERENCE "chute_length=0.3"
/* The micro-scale case: the same grain with a = 50 um. */
#define PHYSICAL_MICRO "chute_length=0.3 semi_major_axis=5e-5"

/* The grid: the particle's Young's modulus (Pa) and its size 2a (m). */
extern const double PHYSICAL_MODULI[];
extern const int N_PHYSICAL_MODULI;
extern const double PHYSICAL_SIZES[];
extern const int N_PHYSICAL_SIZES;

/* The SI set-up of settings (applied to the reference case's), derived: TRIBO_OK, or the
   refusal's message in msg. */
tribo_status physical_derive(const char *settings, tribo_si_derived *d, char *msg, size_t msg_size);

/* Run a derived set-up with the integrator to the exit (at most t_end_s seconds), sampled
   every every_s seconds, with matrix.h's checks and every SI output finite. */
void physical_run(const tribo_si_derived *d, int integrator, double t_end_s, double every_s,
                  stability_result *r);

#endif
