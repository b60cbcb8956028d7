/* create.c: what tribo_create makes an instance of: the registered charge models
   (charge_registry.def) as the scene selects them, and the integrator of the scene's kind.
   The instance itself (model.c) is made of whatever parts it is given, so that it depends on
   no charge model and no integrator, and a test can plug in parts of its own
   (tribo_create_from_parts). */
#include "charge_registry.h"
#include "model.h"

const tribo_integrator_ops *tribo_integrator_of_kind(int kind)
{
    switch (kind) {
    case TRIBO_INTEGRATOR_FIXED_STEP: return &tribo_fixed_step_ops;
    case TRIBO_INTEGRATOR_CVODE:
    case TRIBO_INTEGRATOR_CVODE_BDF: return &tribo_cvode_ops;
    }
    return NULL;
}

tribo_parts tribo_registry_parts(const tribo_scene *scene)
{
    /* (a NULL scene gets no parts: tribo_create_from_parts refuses it) */
    return (tribo_parts){.charge_models = TRIBO_CHARGE_MODELS,
                         .n_charge_models = TRIBO_SEGMENTS_COUNT,
                         .charge_selection = scene ? tribo_charge_selection(scene) : 0u,
                         .integrator = scene ? tribo_integrator_of_kind(scene->integrator) : NULL};
}

tribo_model *tribo_create(const tribo_scene *scene, char *err, size_t err_size)
{
    return tribo_create_like(scene, NULL, err, err_size);
}

tribo_model *tribo_create_like(const tribo_scene *scene, const tribo_model *like, char *err,
                               size_t err_size)
{
    const tribo_parts registry = tribo_registry_parts(scene);
    return tribo_create_from_parts(scene, &registry, like, err, err_size);
}
