/*
 * instance.h: the FMU instance, independent of the FMI version.
 *
 * fmi2.c and fmi3.c are thin: they translate their version's entry points into these
 * calls. Everything an FMU does besides that lives here: the state machine, the
 * dispatch of value references through the variable table, the validation of values
 * (against the core's parameter table), the logging, the co-simulation step and the
 * FMU state blobs. The physics stays in the core.
 *
 * `fn` arguments are the FMI function's name, for the log messages.
 */
#ifndef TRIBO_FMU_INSTANCE_H
#define TRIBO_FMU_INSTANCE_H

#include <stddef.h>

#include "variables.h"

/* Same order and meaning as fmi2Status / fmi3Status. */
typedef enum fmu_status { FMU_OK, FMU_WARNING, FMU_DISCARD, FMU_ERROR, FMU_FATAL } fmu_status;

/* ---- logging: the importer's callback behind a version-neutral signature --------- */

typedef void (*fmu_any_function)(void);
typedef struct fmu_logger fmu_logger;
typedef void (*fmu_log_sink)(const fmu_logger *logger, const char *instance_name,
                             fmu_status status, const char *category, const char *message);
struct fmu_logger {
    fmu_log_sink sink;                /* the wrapper's adapter; NULL: nobody listens  */
    fmu_any_function importer_logger; /* the importer's callback, cast back by sink */
    void *environment;                /* the importer's instance environment         */
};

typedef enum fmu_log_category {
    FMU_LOG_ERROR,    /* "logStatusError": refused calls and values, core failures */
    FMU_LOG_WARNING,  /* "logStatusWarning": warnings of the core                   */
    FMU_LOG_CALLS,    /* "logFmiCalls": every FMI call that changes the instance    */
    FMU_LOG_CORE,     /* "logCore": informational messages of the core              */
    FMU_LOG_CATEGORY_COUNT
} fmu_log_category;

const char *fmu_log_category_name(fmu_log_category category);
const char *fmu_log_category_description(fmu_log_category category);

/* ---- life cycle ------------------------------------------------------------------ */

typedef struct fmu_instance fmu_instance;

/* A new instance in the Instantiated state, every parameter at its start value. The
   name is copied. Returns NULL (after logging why, if it can) when the name is empty,
   the token is not expected_token (the binary's, generated with its modelDescription)
   or memory runs out. With logging_on every category is enabled, else logStatusError and
   logStatusWarning. */
fmu_instance *fmu_instantiate(int fmi_version, const char *fn, const char *name,
                              const char *token, const char *expected_token,
                              const fmu_logger *logger, int logging_on);
void fmu_free(fmu_instance *inst);
/* Log why fn creates no instance (e.g. an interface type this FMU does not have). */
void fmu_refuse_instantiation(const fmu_logger *logger, const char *fn, const char *name,
                              const char *reason);

/* Enable (on) or disable the categories named (all of them when n is 0); an unknown
   name is refused and nothing changes. */
fmu_status fmu_set_debug_logging(fmu_instance *inst, const char *fn, int on, size_t n,
                                 const char *const categories[]);

fmu_status fmu_setup_experiment(fmu_instance *inst, const char *fn, int tolerance_defined,
                                double tolerance, double start_time, int stop_time_defined,
                                double stop_time);
fmu_status fmu_enter_configuration(fmu_instance *inst, const char *fn);
fmu_status fmu_exit_configuration(fmu_instance *inst, const char *fn);
fmu_status fmu_enter_initialization(fmu_instance *inst, const char *fn);
fmu_status fmu_exit_initialization(fmu_instance *inst, const char *fn);

/* FMI 3.0: the importer allows early returns (earlyReturnAllowed at instantiation). */
void fmu_allow_early_return(fmu_instance *inst, int allowed);

/* Advance from current_time (which must be the instance's time up to rounding) by
   step > 0; *reached receives the time reached (the instance's time on failure).
   When the work limit of the core (parameter work_limit) ends the step early, the
   instance stays at the time reached: with an early return allowed (FMI 3.0) the status
   is FMU_OK and *early_return 1; otherwise FMU_DISCARD (FMI 2.0: the instance enters
   stepFailed, FMI 3.0 stays in Step Mode). When the particle leaves the chute during the
   step (model.md §9), the run is over at the exit time, *reached: *terminate is 1; FMI 2.0
   gets FMU_DISCARD (with fmi2Terminated), FMI 3.0 FMU_OK (with terminateSimulation, and an
   early return where allowed). Either way the instance ends in its exited state, where a
   further step is refused with the reason. */
fmu_status fmu_do_step(fmu_instance *inst, const char *fn, double current_time, double step,
                       double *reached, int *early_return, int *terminate);
/* Whether the run is over: the particle left the chute (fmi2Terminated). */
int fmu_exited(const fmu_instance *inst);
fmu_status fmu_terminate(fmu_instance *inst, const char *fn);
/* Back to the Instantiated state with every variable at its start value. */
fmu_status fmu_reset(fmu_instance *inst, const char *fn);

double fmu_time(const fmu_instance *inst);

/* Log `reason` as an error of `fn` and return FMU_ERROR: for the functions behind a
   capability this FMU does not have. inst may be NULL. */
fmu_status fmu_refuse(fmu_instance *inst, const char *fn, const char *reason);

/* ---- values ---------------------------------------------------------------------- */

/* The C type of the importer's value array. */
typedef enum fmu_c_type {
    FMU_C_NONE,
    FMU_C_DOUBLE,
    FMU_C_INT,   /* also fmi2Boolean */
    FMU_C_INT32,
    FMU_C_INT64, /* FMI 3.0 enumerations */
    FMU_C_UINT64,
    FMU_C_BOOL   /* fmi3Boolean */
} fmu_c_type;

#define FMU_TYPE_BIT(t) (1u << (t))

/* Get / set the variables vrs[0..nvr) whose types are among the `types` bits
   (FMU_TYPE_BIT), stored as c_type. nvalues is the total number of values (arrays
   count their elements). A set stops at the first value refused. */
fmu_status fmu_get(fmu_instance *inst, const char *fn, unsigned types, fmu_c_type c_type,
                   const fmu_vr vrs[], size_t nvr, void *values, size_t nvalues);
fmu_status fmu_set(fmu_instance *inst, const char *fn, unsigned types, fmu_c_type c_type,
                   const fmu_vr vrs[], size_t nvr, const void *values, size_t nvalues);

/* ---- FMU states: plain bytes, no pointers; the blob is its own serialization ----- */

typedef struct fmu_state fmu_state;

/* Save the instance into *state (a new state if *state is NULL, else overwritten). */
fmu_status fmu_state_get(fmu_instance *inst, const char *fn, fmu_state **state);
fmu_status fmu_state_set(fmu_instance *inst, const char *fn, const fmu_state *state);
fmu_status fmu_state_free(fmu_instance *inst, const char *fn, fmu_state **state);
fmu_status fmu_state_size(fmu_instance *inst, const char *fn, const fmu_state *state,
                          size_t *size);
fmu_status fmu_state_serialize(fmu_instance *inst, const char *fn, const fmu_state *state,
                               void *bytes, size_t size);
fmu_status fmu_state_deserialize(fmu_instance *inst, const char *fn, const void *bytes,
                                 size_t size, fmu_state **state);

#endif
