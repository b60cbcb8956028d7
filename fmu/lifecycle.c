/* lifecycle.c: creating and freeing instances and moving them between FMI states. */
#include "instance_private.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const LIFECYCLE_NAMES[] = {
    [FMU_LIFECYCLE_INSTANTIATED] = "Instantiated",
    [FMU_LIFECYCLE_CONFIGURATION] = "Configuration Mode",
    [FMU_LIFECYCLE_INITIALIZATION] = "Initialization Mode",
    [FMU_LIFECYCLE_STEP] = "Step Mode",
    [FMU_LIFECYCLE_TERMINATED] = "Terminated",
    [FMU_LIFECYCLE_STEP_DISCARDED] =
        "Step Discarded (stepFailed: the last step ended early; terminate, reset or restore a state)",
    [FMU_LIFECYCLE_FAILED] = "Error (after a failure of the core: reset the instance or restore a state)",
    /* the front end's: what ends its core's run */
    [FMU_LIFECYCLE_EXITED] = fmu_front_exited_state_name,
};

const char *fmu_lifecycle_name(fmu_lifecycle state) { return LIFECYCLE_NAMES[state]; }

int fmu_lifecycle_allows(fmu_instance *inst, const char *fn, unsigned states)
{
    if (states & FMU_LIFECYCLE_BIT(inst->lifecycle))
        return 1;
    fmu_error(inst, "%s is not allowed in state %s", fn, fmu_lifecycle_name(inst->lifecycle));
    return 0;
}

void fmu_restore_start_values(fmu_instance *inst)
{
    fmu_front_free(inst->core);
    inst->core = NULL;
    inst->model_outdated = 0;
    fmu_front_defaults(&inst->scene);
    inst->rtol_set = inst->atol_set = 0;
    inst->stick_model_set = 0;
    fmu_follow_defaults(&inst->scene, 0);
    inst->hold_at_end = 0;
    const tribo_param_info *inputs = fmu_front_inputs();
    for (int i = 0; i < FMU_MAX_INPUTS; i++)
        inst->inputs[i] = i < fmu_front_input_count() ? inputs[i].start : 0.0;
    inst->start_time = 0.0;
    inst->stop_time = 0.0;
    inst->stop_time_defined = 0;
    inst->time = 0.0;
    inst->lifecycle = FMU_LIFECYCLE_INSTANTIATED;
}

void fmu_refuse_instantiation(const fmu_logger *logger, const char *fn, const char *name,
                              const char *reason)
{
    if (!logger || !logger->sink)
        return;
    char message[512];
    snprintf(message, sizeof message, "%s: %s", fn, reason);
    logger->sink(logger, name ? name : "", FMU_ERROR, fmu_log_category_name(FMU_LOG_ERROR), message);
}

fmu_instance *fmu_instantiate(int fmi_version, const char *fn, const char *name,
                              const char *token, const char *expected_token,
                              const fmu_logger *logger, int logging_on)
{
    if (!name || !*name) {
        fmu_refuse_instantiation(logger, fn, name, "the instance name is empty");
        return NULL;
    }
    if (!token || strcmp(token, expected_token) != 0) {
        fmu_refuse_instantiation(logger, fn, name,
                                 "the instantiation token (GUID) is not this FMU's: the "
                                 "modelDescription.xml does not belong to this binary");
        return NULL;
    }
    fmu_instance *inst = calloc(1, sizeof *inst);
    /* a copy: the importer may free its string once we return */
    char *name_copy = malloc(strlen(name) + 1);
    if (!inst || !name_copy) {
        free(inst);
        free(name_copy);
        fmu_refuse_instantiation(logger, fn, name, "out of memory");
        return NULL;
    }
    inst->name = strcpy(name_copy, name);
    inst->fmi_version = fmi_version;
    if (logger)
        inst->logger = *logger;
    /* errors and warnings (e.g. a contact outside the model's assumptions) reach the
       importer without debug logging; loggingOn adds the core's notes. The trace of every
       call (logFmiCalls, a line per call and per value set) only where the importer asks for
       it by name, or for every category, with SetDebugLogging: an importer that turns
       loggingOn on for its own log level (libcosim through the FMI Library) would otherwise
       print thousands of lines of a run */
    for (int c = 0; c < FMU_LOG_CATEGORY_COUNT; c++)
        inst->log_enabled[c] = c == FMU_LOG_ERROR || c == FMU_LOG_WARNING ||
                               (logging_on && c != FMU_LOG_CALLS);
    fmu_restore_start_values(inst);
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(instanceName = \"%s\", loggingOn = %d)", fn, name,
            logging_on != 0);
    return inst;
}

void fmu_free(fmu_instance *inst)
{
    if (!inst)
        return;
    fmu_front_free(inst->core);
    free(inst->name);
    free(inst);
}

double fmu_time(const fmu_instance *inst) { return inst->time; }

int fmu_exited(const fmu_instance *inst) { return inst && inst->lifecycle == FMU_LIFECYCLE_EXITED; }

void fmu_allow_early_return(fmu_instance *inst, int allowed)
{
    if (inst)
        inst->early_return_allowed = allowed != 0;
}

fmu_status fmu_refuse(fmu_instance *inst, const char *fn, const char *reason)
{
    if (!inst)
        return FMU_ERROR;
    return fmu_error(inst, "%s: %s", fn, reason);
}

void fmu_note_parameter_set(fmu_instance *inst, const tribo_param_info *p)
{
    if (strcmp(p->name, "rtol") == 0)
        inst->rtol_set = 1;
    else if (strcmp(p->name, "atol") == 0)
        inst->atol_set = 1;
    else if (strcmp(p->name, "stick_model") == 0)
        inst->stick_model_set = 1;
}

/* The rigid stick needs CVODE and the contact point's dashpot (model.md §3b): the SI FMUs'
   default, rigid, gives way to the compliant stick where the importer chose the fixed step
   or the centre's dashpot and left stick_model alone, so that each of those alone is a
   valid set-up; chosen explicitly, the rigid stick with either is refused at the set call
   (access.c). */
void fmu_follow_defaults(fmu_scene *scene, int stick_model_set)
{
    const tribo_param_info *stick = fmu_front_param_find("stick_model");
    if (!stick || stick_model_set)
        return;
    const int rigid_fits = tribo_rigid_stick_allowed(
        (int)tribo_param_read(scene, fmu_front_param_find("integrator")),
        (int)tribo_param_read(scene, fmu_front_param_find("damping_point")));
    tribo_param_write(scene, stick,
                      stick->start == TRIBO_STICK_RIGID && !rigid_fits ? TRIBO_STICK_COMPLIANT
                                                                       : stick->start);
}

int fmu_stick_model_fits(const fmu_scene *scene, char *msg, size_t msg_size)
{
    const tribo_param_info *stick = fmu_front_param_find("stick_model");
    if (!stick || tribo_param_read(scene, stick) != TRIBO_STICK_RIGID)
        return 1;
    const double integrator = tribo_param_read(scene, fmu_front_param_find("integrator"));
    const double damping = tribo_param_read(scene, fmu_front_param_find("damping_point"));
    if (tribo_rigid_stick_allowed((int)integrator, (int)damping))
        return 1;
    snprintf(msg, msg_size,
             "stick_model = 1 (rigid), set explicitly, does not go with integrator = %g and "
             "damping_point = %g: the rigid stick needs CVODE (integrator = 1 or 2) and the "
             "contact point's dashpot (damping_point = 0); set stick_model = 0 (compliant), or "
             "leave it unset to follow them",
             integrator, damping);
    return 0;
}

double fmu_scene_value(const fmu_instance *inst, const char *name)
{
    return tribo_param_read(&inst->scene, fmu_front_param_find(name));
}

static void set_parameter(fmu_instance *inst, const tribo_param_info *p, double value)
{
    if (tribo_param_read(&inst->scene, p) != value)
        inst->model_outdated = 1;
    tribo_param_write(&inst->scene, p, value);
}

/* The importer's tolerance is CVODE's relative tolerance, and the absolute one keeps its
   ratio to it: atol = atol's default * tolerance / rtol's default (= tolerance / 100), so
   that the default experiment's tolerance, rtol's default, gives the defaults bit for bit.
   rtol or atol set by the importer wins, whenever it was set. The fixed step ignores both
   (dt sets its accuracy). A tolerance that would give either out of its range is refused
   even where both were set (it is the importer's mistake all the same); checked before the
   experiment changes anything, applied after (use_tolerance). */
static fmu_status check_tolerance(fmu_instance *inst, const char *fn, double tolerance)
{
    const tribo_param_info *rtol = fmu_front_param_find("rtol"), *atol = fmu_front_param_find("atol");
    char msg[512];
    if (tribo_param_check(rtol, tolerance, msg, sizeof msg) == TRIBO_OK &&
        tribo_param_check(atol, atol->start * (tolerance / rtol->start), msg, sizeof msg) == TRIBO_OK)
        return FMU_OK;
    /* what the tolerance would have set, so that the reason reads true */
    const double ratio = rtol->start / atol->start;
    const char *sets = inst->rtol_set && inst->atol_set
                           ? "neither of CVODE's rtol and atol (both were set explicitly)"
                       : inst->rtol_set ? "CVODE's atol (rtol was set explicitly)"
                       : inst->atol_set ? "CVODE's rtol (atol was set explicitly)"
                                        : "CVODE's rtol, and atol";
    return fmu_error(inst,
                     "%s: tolerance = %.17g is invalid: it would set %s; an importer's tolerance "
                     "must be one rtol can take, and tolerance / %g one atol can: %s",
                     fn, tolerance, sets, ratio, msg);
}

static void use_tolerance(fmu_instance *inst, const char *fn, double tolerance)
{
    const tribo_param_info *rtol = fmu_front_param_find("rtol"), *atol = fmu_front_param_find("atol");
    if (inst->rtol_set && inst->atol_set) {
        fmu_log(inst, FMU_OK, FMU_LOG_CALLS,
                "%s: tolerance = %g not used: rtol = %g and atol = %g were set explicitly", fn,
                tolerance, fmu_scene_value(inst, "rtol"), fmu_scene_value(inst, "atol"));
        return;
    }
    if (!inst->rtol_set)
        set_parameter(inst, rtol, tolerance);
    if (!inst->atol_set)
        set_parameter(inst, atol, atol->start * (tolerance / rtol->start));
    /* (the separator has no other integrator than CVODE) */
    const int fixed_step = fmu_front_param_find("integrator") &&
                           fmu_scene_value(inst, "integrator") == TRIBO_INTEGRATOR_FIXED_STEP;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s: tolerance = %g: rtol = %g (%s), atol = %g (%s)%s",
            fn, tolerance, fmu_scene_value(inst, "rtol"),
            inst->rtol_set ? "set explicitly" : "the tolerance", fmu_scene_value(inst, "atol"),
            inst->atol_set ? "set explicitly" : "from the tolerance",
            fixed_step ? "; the fixed-step integrator uses neither: dt sets its accuracy" : "");
}

/* Every argument is checked before any applies: a refused experiment changes nothing. */
fmu_status fmu_setup_experiment(fmu_instance *inst, const char *fn, int tolerance_defined,
                                double tolerance, double start_time, int stop_time_defined,
                                double stop_time)
{
    if (!inst || !fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INSTANTIATED)))
        return FMU_ERROR;
    if (!isfinite(start_time))
        return fmu_error(inst, "%s: startTime = %g is invalid: it must be finite", fn, start_time);
    if (stop_time_defined && !(isfinite(stop_time) && stop_time >= start_time))
        return fmu_error(inst,
                         "%s: stopTime = %.17g is invalid: it must be finite and >= startTime = "
                         "%.17g",
                         fn, stop_time, start_time);
    if (tolerance_defined && check_tolerance(inst, fn, tolerance) != FMU_OK)
        return FMU_ERROR;
    inst->start_time = start_time;
    inst->time = start_time;
    inst->stop_time_defined = stop_time_defined != 0;
    inst->stop_time = stop_time_defined ? stop_time : 0.0;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(startTime = %.17g, stopTime = %s%.17g)", fn,
            start_time, stop_time_defined ? "" : "(undefined) ", stop_time);
    if (tolerance_defined)
        use_tolerance(inst, fn, tolerance);
    return FMU_OK;
}

fmu_status fmu_enter_configuration(fmu_instance *inst, const char *fn)
{
    if (!inst || !fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INSTANTIATED)))
        return FMU_ERROR;
    inst->lifecycle = FMU_LIFECYCLE_CONFIGURATION;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s()", fn);
    return FMU_OK;
}

fmu_status fmu_exit_configuration(fmu_instance *inst, const char *fn)
{
    if (!inst || !fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_CONFIGURATION)))
        return FMU_ERROR;
    inst->lifecycle = FMU_LIFECYCLE_INSTANTIATED;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s()", fn);
    return FMU_OK;
}

fmu_status fmu_enter_initialization(fmu_instance *inst, const char *fn)
{
    if (!inst || !fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INSTANTIATED)))
        return FMU_ERROR;
    inst->lifecycle = FMU_LIFECYCLE_INITIALIZATION;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s()", fn);
    return FMU_OK;
}

/* A core instance of the current parameters, made aside (the instance does not change):
   NULL after logging why not. */
static fmu_core *make_model(fmu_instance *inst, const char *fn, fmu_derived *derived)
{
    char why[512];
    fmu_core *core = NULL;
    if (fmu_front_derive(&inst->scene, derived, why, sizeof why) != TRIBO_OK ||
        !(core = fmu_front_create(derived, inst->core, fmu_core_logger, inst, why, sizeof why))) {
        fmu_error(inst, "%s: the model cannot be created: %s", fn, why);
        return NULL;
    }
    const char *notice = fmu_front_notice(derived);
    if (notice)
        fmu_log(inst, FMU_WARNING, FMU_LOG_WARNING, "%s: %s", fn, notice);
    return core;
}

static void install_model(fmu_instance *inst, fmu_core *core, const fmu_derived *derived)
{
    fmu_front_free(inst->core);
    inst->core = core;
    inst->derived = *derived;
    inst->model_outdated = 0;
}

fmu_status fmu_ensure_model(fmu_instance *inst, const char *fn)
{
    if (inst->core && !inst->model_outdated)
        return FMU_OK;
    fmu_derived derived;
    fmu_core *model = make_model(inst, fn, &derived);
    if (!model)
        return FMU_ERROR;
    install_model(inst, model, &derived);
    return FMU_OK;
}

/* The importer's inputs, converted by the front end (what it derived for `model`), to the
   core instance `model`. */
static fmu_status pass_inputs_to(fmu_instance *inst, const char *fn, fmu_core *model,
                                 const fmu_derived *derived)
{
    double model_inputs[FMU_MAX_INPUTS];
    char why[512];
    if (fmu_front_model_inputs(derived, inst->inputs, model_inputs, why, sizeof why) != TRIBO_OK)
        return fmu_error(inst, "%s: %s", fn, why);
    if (fmu_front_set_inputs(model, model_inputs) != TRIBO_OK)
        return fmu_error(inst, "%s: %s", fn, fmu_front_last_error(model));
    return FMU_OK;
}

fmu_status fmu_pass_inputs(fmu_instance *inst, const char *fn)
{
    return pass_inputs_to(inst, fn, inst->core, &inst->derived);
}

fmu_status fmu_exit_initialization(fmu_instance *inst, const char *fn)
{
    if (!inst || !fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INITIALIZATION)))
        return FMU_ERROR;
    /* a refusal leaves the instance as it was, in Initialization Mode (where parameters can
       still be changed): a core instance it needs is made aside, and kept only once it has
       taken the inputs (the SI front end refuses inputs whose model values are out of range) */
    if (inst->core && !inst->model_outdated) {
        if (fmu_pass_inputs(inst, fn) != FMU_OK)
            return FMU_ERROR;
    } else {
        fmu_derived derived;
        fmu_core *model = make_model(inst, fn, &derived);
        if (!model)
            return FMU_ERROR;
        if (pass_inputs_to(inst, fn, model, &derived) != FMU_OK) {
            fmu_front_free(model);
            return FMU_ERROR;
        }
        install_model(inst, model, &derived);
    }
    inst->lifecycle = FMU_LIFECYCLE_STEP;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s() at time %.17g", fn, inst->time);
    return FMU_OK;
}

fmu_status fmu_terminate(fmu_instance *inst, const char *fn)
{
    if (!inst || !fmu_lifecycle_allows(inst, fn,
                                       FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP) |
                                           FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP_DISCARDED) |
                                           FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_EXITED)))
        return FMU_ERROR;
    inst->lifecycle = FMU_LIFECYCLE_TERMINATED;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s() at time %.17g", fn, inst->time);
    return FMU_OK;
}

fmu_status fmu_reset(fmu_instance *inst, const char *fn)
{
    if (!inst)
        return FMU_ERROR;
    fmu_restore_start_values(inst);
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s()", fn);
    return FMU_OK;
}
