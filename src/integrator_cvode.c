/* integrator_cvode.c: placeholder until the CVODE integrator lands (issue 4). */
#include "model.h"

static tribo_status create(tribo_model *m)
{
    return tribo_fail(m, TRIBO_ERR_INVALID_ARGUMENT,
                      "integrator = 1 (CVODE) is not available in this build");
}
static void destroy(tribo_model *m) { (void)m; }
static void restart(tribo_model *m) { (void)m; }
static tribo_status advance(tribo_model *m, double t) { (void)m; (void)t; return TRIBO_ERR_INTEGRATOR; }
static size_t state_size(const tribo_model *m) { (void)m; return 0; }
static void state_save(const tribo_model *m, unsigned char *b) { (void)m; (void)b; }
static tribo_status state_load(tribo_model *m, const unsigned char *b) { (void)m; (void)b; return TRIBO_OK; }

const tribo_integrator_ops tribo_cvode_ops = {
    "CVODE", create, destroy, restart, advance, state_size, state_save, state_load,
};
