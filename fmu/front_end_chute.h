/* front_end_chute.h: what the chute's two front ends (front_end_model.c, front_end_si.c)
   give the core functions they share (front_end_chute.c). */
#ifndef TRIBO_FMU_FRONT_END_CHUTE_H
#define TRIBO_FMU_FRONT_END_CHUTE_H

#include "front_end.h"

/* The chute model's scene the front end derived. */
tribo_scene *fmu_front_model_scene(fmu_derived *d);
/* The factor from the model's per-segment values to the importer's. */
double fmu_front_segment_factor(const fmu_derived *d, tribo_segment_charge which);

#endif
