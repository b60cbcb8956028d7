/* instance_private.h: what the files of the instance layer share (not the wrappers). */
#ifndef TRIBO_FMU_INSTANCE_PRIVATE_H
#define TRIBO_FMU_INSTANCE_PRIVATE_H

#include "front_end.h"
#include "instance.h"

/* The states of FMI 2.0 / 3.0 co-simulation that this FMU has. FMI 2.0 has no
   Configuration Mode; Step Mode is FMI 2.0's slaveInitialized (stepComplete). */
typedef enum fmu_lifecycle {
    FMU_LIFECYCLE_INSTANTIATED,
    FMU_LIFECYCLE_CONFIGURATION,
    FMU_LIFECYCLE_INITIALIZATION,
    FMU_LIFECYCLE_STEP,
    FMU_LIFECYCLE_TERMINATED,
    /* FMI 2.0's stepFailed: a step was discarded (it ended early); outputs and FMU states
       can be read, and terminate, reset or a saved FMU state lead on */
    FMU_LIFECYCLE_STEP_DISCARDED,
    FMU_LIFECYCLE_FAILED, /* the core failed: only reset, a saved FMU state or free help */
    /* the core's run is over (the chute's: the particle left it, model.md §9; the
       separator's: the grain reached the bins or a plate, §10); outputs and FMU states can
       be read, and terminate, reset or a saved FMU state lead on (FMI 2.0: fmi2Terminated;
       FMI 3.0: terminateSimulation) */
    FMU_LIFECYCLE_EXITED
} fmu_lifecycle;

#define FMU_LIFECYCLE_BIT(m) (1u << (m))

struct fmu_instance {
    int fmi_version;
    char *name;
    fmu_logger logger;
    int log_enabled[FMU_LOG_CATEGORY_COUNT];

    fmu_lifecycle lifecycle;
    /* The parameters as the importer sees them (the front end's table); tunable changes
       while running go to the model too. */
    fmu_scene scene;
    double inputs[FMU_MAX_INPUTS]; /* the importer's, in the front end's units */
    /* The core instance: made when first needed after initialization starts, remade
       when a parameter changed since (model_outdated), from `derived`: what the front end
       made of `scene` then (the core's scene and the units of the outputs). */
    fmu_core *core;
    int model_outdated;
    fmu_derived derived;

    /* rtol, atol set by the importer (they win over the experiment's tolerance) */
    int rtol_set, atol_set;
    /* stick_model set by the importer; until then it follows the integrator and the
       dashpot's point (fmu_follow_defaults) */
    int stick_model_set;

    double start_time;
    double stop_time;
    int stop_time_defined;
    double time; /* the FMU's time: start_time + the core's time */

    /* FMI 3.0: the importer allows a step to end early (earlyReturnAllowed) */
    int early_return_allowed;

    /* the parameter hold_at_end: at the core's run's end the instance stays in Step Mode,
       its time following the steps, the core left where its run ended (step.c); "held" is
       then hold_at_end and the core's run over, so it needs no flag of its own */
    int hold_at_end;
};

/* Communication points that differ by less than this around `time` are the same point
   computed another way (t + h + h ... against t + n h). */
double fmu_rounding_tolerance(double time);

/* Log through the importer's logger if the category is enabled. */
void fmu_log(fmu_instance *inst, fmu_status status, fmu_log_category category, const char *fmt,
             ...) __attribute__((format(printf, 4, 5)));
/* Log an error (category logStatusError) and return FMU_ERROR. */
fmu_status fmu_error(fmu_instance *inst, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int fmu_log_enabled(const fmu_instance *inst, fmu_log_category category);
/* Route the core's own messages to the importer. */
void fmu_core_logger(void *inst, int level, const char *message);

const char *fmu_lifecycle_name(fmu_lifecycle state);
/* 1 if inst is in one of the lifecycle states (FMU_LIFECYCLE_BIT mask); else logs why fn is refused. */
int fmu_lifecycle_allows(fmu_instance *inst, const char *fn, unsigned states);

/* Make the core instance from the current parameters if there is none or it is
   outdated: the front end derives the model's scene (its refusal is logged as the
   dimensionless scene's is). */
fmu_status fmu_ensure_model(fmu_instance *inst, const char *fn);
/* Pass the importer's inputs, converted by the front end, to the core instance. */
fmu_status fmu_pass_inputs(fmu_instance *inst, const char *fn);
/* A parameter of the front end's scene. */
double fmu_scene_value(const fmu_instance *inst, const char *name);
/* Drop the core instance and put every variable back to its start value. */
void fmu_restore_start_values(fmu_instance *inst);
/* Note that the importer set parameter p (the tolerance does not override it; a default
   that follows others no longer does). */
void fmu_note_parameter_set(fmu_instance *inst, const tribo_param_info *p);
/* The value of stick_model in `scene` that follows the integrator and the dashpot's point
   where the importer has not set it (stick_model_set 0): its start value, the rigid stick
   only where they allow it (tribo_rigid_stick_allowed), else the compliant one. A front end
   without a stick_model is left as it is. */
void fmu_follow_defaults(fmu_scene *scene, int stick_model_set);
/* Whether stick_model, integrator and damping_point in `scene` go together; if not, a
   sentence that says why in msg. */
int fmu_stick_model_fits(const fmu_scene *scene, char *msg, size_t msg_size);

#endif
