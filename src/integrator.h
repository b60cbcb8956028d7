/* integrator.h: what an integrator provides to the instance (internal to the core). */
#ifndef TRIBO_INTEGRATOR_H
#define TRIBO_INTEGRATOR_H

#include <stddef.h>

#include "tribo.h"

typedef struct tribo_integrator_ops {
    const char *name;
    /* Allocate the integrator's data for the instance (m->integrator_data). */
    tribo_status (*create)(tribo_model *m);
    void (*destroy)(tribo_model *m);
    /* The committed point was set from outside (reset, state load, a tunable or an
       input changed): start afresh from it. */
    void (*restart)(tribo_model *m);
    /* Commit the motion up to t, then set m->out (and m->pending) to the state at t. */
    tribo_status (*advance)(tribo_model *m, double t);
    /* The integrator's own state, as plain bytes. */
    size_t (*state_size)(const tribo_model *m);
    void (*state_save)(const tribo_model *m, unsigned char *buffer);
    tribo_status (*state_load)(tribo_model *m, const unsigned char *buffer);
} tribo_integrator_ops;

extern const tribo_integrator_ops tribo_fixed_step_ops;
extern const tribo_integrator_ops tribo_cvode_ops;

#endif
