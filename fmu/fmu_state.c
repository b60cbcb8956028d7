/*
 * fmu_state.c: FMU states (fmi2GetFMUstate ..., fmi3GetFMUState ...).
 *
 * A state is one block of plain bytes, which is also its serialized form, so that a
 * state restores into any instance of this FMU, a fresh one included, and from bytes
 * written by another process. Layout (native byte order, 8-byte fields):
 *
 *   "TRIBOFMU", layout version, FMI version, total size,
 *   lifecycle state, start time, stop time, stop time defined, time, the inputs,
 *   number of parameters, every parameter (in the order of the front end's table: the SI
 *   FMUs save the SI scene),
 *   core instance outdated, parameters set explicitly (bit 0: rtol, bit 1: atol, bit 2:
 *   stick_model, which follows the integrator and the dashpot's point until it is set),
 *   hold_at_end (the FMU layer's parameter, in no front end's table), size of the core's
 *   state, the core's state (the front end's: tribo_state_save,
 *   tribo_separator_state_save)
 *
 * A core state size of 0 means there is no core instance to keep: none yet (before
 * initialization), or one made for parameters changed since, which would be remade.
 *
 * Restoring checks every field against what an instance can hold, derives the core's scene
 * from the parameters as the front end does (front_end.h) and loads the core's state into a
 * new core instance of that scene; the instance changes only once all of it is accepted.
 * The inputs are the front end's (fmu_front_input_count of them).
 */
#include "instance_private.h"

#include "byte_cursor.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct fmu_state {
    size_t size;
    unsigned char bytes[]; /* the serialized form */
};

static const char MAGIC[8] = {'T', 'R', 'I', 'B', 'O', 'F', 'M', 'U'};
enum { LAYOUT_VERSION = 5, HEADER_SIZE = 8 + 3 * 8 };

/* Everything but the core's state: the header, 10 fields, the inputs and the parameters. */
static size_t fixed_size(size_t n_params)
{
    return HEADER_SIZE + 10 * 8 + (size_t)fmu_front_input_count() * 8 + n_params * 8;
}

/* ---- save ---------------------------------------------------------------------- */

fmu_status fmu_state_get(fmu_instance *inst, const char *fn, fmu_state **state)
{
    if (!inst)
        return FMU_ERROR;
    if (!state)
        return fmu_error(inst, "%s: FMUState is NULL", fn);
    if (inst->lifecycle == FMU_LIFECYCLE_FAILED)
        return fmu_error(inst, "%s: the instance failed; there is no consistent state to save", fn);
    size_t n_params;
    const tribo_param_info *params = fmu_front_params(&n_params);
    /* a core instance made for parameters changed since would be remade: not worth keeping */
    const fmu_core *core = inst->core && !inst->model_outdated ? inst->core : NULL;
    const size_t core_size = core ? fmu_front_state_size(core) : 0;
    const size_t size = fixed_size(n_params) + core_size;

    fmu_state *s = *state;
    if (!s || s->size != size) {
        s = realloc(s, sizeof *s + size);
        if (!s)
            return fmu_error(inst, "%s: out of memory for a state of %zu bytes", fn, size);
        s->size = size;
        *state = s;
    }
    tribo_writer c = {s->bytes};
    tribo_write_bytes(&c, MAGIC, sizeof MAGIC);
    tribo_write_int(&c, LAYOUT_VERSION);
    tribo_write_int(&c, inst->fmi_version);
    tribo_write_int(&c, (int64_t)size);
    tribo_write_int(&c, inst->lifecycle);
    tribo_write_double(&c, inst->start_time);
    tribo_write_double(&c, inst->stop_time);
    tribo_write_int(&c, inst->stop_time_defined);
    tribo_write_double(&c, inst->time);
    for (int i = 0; i < fmu_front_input_count(); i++)
        tribo_write_double(&c, inst->inputs[i]);
    tribo_write_int(&c, (int64_t)n_params);
    for (size_t i = 0; i < n_params; i++)
        tribo_write_double(&c, tribo_param_read(&inst->scene, &params[i]));
    tribo_write_int(&c, core ? 0 : inst->model_outdated);
    /* an importer's tolerance, given later, must not override what was set explicitly */
    tribo_write_int(&c, (inst->rtol_set ? 1 : 0) | (inst->atol_set ? 2 : 0) |
                            (inst->stick_model_set ? 4 : 0));
    /* with the core's run over it says whether the instance is held there, in Step Mode at a
       time past the core's */
    tribo_write_int(&c, inst->hold_at_end);
    tribo_write_int(&c, (int64_t)core_size);
    if (core_size && fmu_front_state_save(core, c.p, core_size) != TRIBO_OK)
        return fmu_error(inst, "%s: %s", fn, fmu_front_last_error(inst->core));
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s() at time %.17g: %zu bytes", fn, inst->time, size);
    return FMU_OK;
}

/* ---- restore ------------------------------------------------------------------- */

/* Check the header of serialized bytes; returns a reason, or NULL if they look right. */
static const char *header_problem(const fmu_instance *inst, const unsigned char *bytes, size_t size)
{
    if (!bytes || size < HEADER_SIZE)
        return "the state is too short";
    tribo_reader c = tribo_reader_of(bytes, size);
    char magic[sizeof MAGIC];
    tribo_read_bytes(&c, magic, sizeof magic);
    const int64_t layout = tribo_read_int(&c), fmi_version = tribo_read_int(&c),
                  total = tribo_read_int(&c);
    if (memcmp(magic, MAGIC, sizeof MAGIC) != 0 || layout != LAYOUT_VERSION)
        return "the bytes are not a state of this FMU (or of another version of it)";
    if (fmi_version != inst->fmi_version)
        return "the state was saved by an instance of the other FMI version";
    if ((uint64_t)total != size)
        return "the state's size does not match its header (truncated or corrupt)";
    return NULL;
}

/* An FMU state read from bytes, not yet applied. */
typedef struct restored {
    int64_t lifecycle, stop_time_defined, model_outdated, tolerances_set, hold_at_end;
    double start_time, stop_time, time;
    double inputs[FMU_MAX_INPUTS];
    fmu_scene scene;
    fmu_derived derived; /* the front end's of scene, when there is a core state */
    const unsigned char *core;
    uint64_t core_size;
} restored;

/* Whether the lifecycle state is one an instance of this FMI version saves, and whether it
   has a core instance there. */
static int lifecycle_valid(const fmu_instance *inst, int64_t lifecycle, int has_core)
{
    switch (lifecycle) {
    case FMU_LIFECYCLE_INSTANTIATED: return !has_core;
    case FMU_LIFECYCLE_CONFIGURATION: return !has_core && inst->fmi_version == 3;
    case FMU_LIFECYCLE_INITIALIZATION: return 1;
    case FMU_LIFECYCLE_STEP:
    case FMU_LIFECYCLE_TERMINATED: return has_core;
    case FMU_LIFECYCLE_STEP_DISCARDED: return has_core && inst->fmi_version == 2;
    case FMU_LIFECYCLE_EXITED: return has_core;
    }
    return 0;
}

/* Read and check everything but the core's state; returns a reason, or NULL. */
static const char *read_restored(const fmu_instance *inst, const fmu_state *s, restored *r,
                                 char *msg, size_t msg_size)
{
    size_t n_params;
    const tribo_param_info *params = fmu_front_params(&n_params);
    if (s->size < fixed_size(n_params))
        return "the state is too short";
    tribo_reader c = tribo_reader_of(s->bytes + HEADER_SIZE, s->size - HEADER_SIZE);
    r->lifecycle = tribo_read_int(&c);
    r->start_time = tribo_read_double(&c);
    r->stop_time = tribo_read_double(&c);
    r->stop_time_defined = tribo_read_int(&c);
    r->time = tribo_read_double(&c);
    const tribo_param_info *inputs = fmu_front_inputs();
    for (int i = 0; i < FMU_MAX_INPUTS; i++)
        r->inputs[i] = 0.0;
    for (int i = 0; i < fmu_front_input_count(); i++) {
        r->inputs[i] = tribo_read_double(&c);
        if (tribo_param_check(&inputs[i], r->inputs[i], msg, msg_size) != TRIBO_OK)
            return msg;
    }
    if ((size_t)tribo_read_int(&c) != n_params)
        return "the state has another set of parameters";
    fmu_front_defaults(&r->scene);
    for (size_t i = 0; i < n_params; i++) {
        const double v = tribo_read_double(&c);
        if (tribo_param_check(&params[i], v, msg, msg_size) != TRIBO_OK)
            return msg;
        tribo_param_write(&r->scene, &params[i], v);
    }
    r->model_outdated = tribo_read_int(&c);
    r->tolerances_set = tribo_read_int(&c);
    r->hold_at_end = tribo_read_int(&c);
    r->core_size = (uint64_t)tribo_read_int(&c);
    r->core = c.p;
    const int has_core = r->core_size > 0;
    if (r->core_size != s->size - fixed_size(n_params))
        return "the size of the core's state does not match the state's";
    if (!lifecycle_valid(inst, r->lifecycle, has_core) ||
        (r->model_outdated != 0 && r->model_outdated != 1) || (has_core && r->model_outdated) ||
        r->tolerances_set < 0 || r->tolerances_set > 7 ||
        (r->hold_at_end != 0 && r->hold_at_end != 1))
        return "the FMI state is not one this FMU saves";
    fmu_scene followed = r->scene;
    fmu_follow_defaults(&followed, (r->tolerances_set & 4) != 0);
    if (memcmp(&followed, &r->scene, sizeof followed) != 0)
        return "its stick_model, not set explicitly, does not follow its integrator and "
               "damping_point";
    if (!isfinite(r->start_time) || !isfinite(r->time) || !isfinite(r->stop_time) ||
        (r->stop_time_defined != 0 && r->stop_time_defined != 1) ||
        (r->stop_time_defined ? !(r->stop_time >= r->start_time) : r->stop_time != 0.0))
        return "the start, stop or current time is invalid";
    /* without a core instance the run has not started */
    if (!has_core && r->time != r->start_time)
        return "the time is not the start time, but there is no run";
    return NULL;
}

/* A core instance in the saved core state, for the restored parameters (r->derived is made
   of them); NULL after logging why not. */
static fmu_core *load_core(fmu_instance *inst, const char *fn, restored *r)
{
    char why[512];
    if (fmu_front_derive(&r->scene, &r->derived, why, sizeof why) != TRIBO_OK) {
        fmu_error(inst, "%s: the state is corrupt: its parameters make no model: %s", fn, why);
        return NULL;
    }
    fmu_core *m = fmu_front_create(&r->derived, inst->core, fmu_core_logger, inst, why, sizeof why);
    if (!m) {
        fmu_error(inst, "%s: the model cannot be created: %s", fn, why);
        return NULL;
    }
    if (fmu_front_state_load(m, &r->derived, r->core, (size_t)r->core_size, why, sizeof why) !=
        TRIBO_OK) {
        fmu_error(inst, "%s: %s", fn, why);
        fmu_front_free(m);
        return NULL;
    }
    /* the FMU's time is the start time plus the core's, in the front end's unit; held at the
       run's end (hold_at_end), that or later */
    const double unit = fmu_front_time_unit(&r->derived), t = fmu_front_core_time(m);
    const double offset = r->time - (r->start_time + unit * t);
    const int held = r->hold_at_end && fmu_front_run_over(m);
    if (!isfinite(t) ||
        !(held ? offset >= -fmu_rounding_tolerance(r->time)
               : fabs(offset) <= fmu_rounding_tolerance(r->time))) {
        fmu_error(inst, "%s: the state is corrupt: its time %.17g is not its start time %.17g "
                  "plus the core's time %.17g (times %.17g)", fn, r->time, r->start_time, t, unit);
        fmu_front_free(m);
        return NULL;
    }
    return m;
}

fmu_status fmu_state_set(fmu_instance *inst, const char *fn, const fmu_state *s)
{
    if (!inst)
        return FMU_ERROR;
    if (!s)
        return fmu_error(inst, "%s: FMUState is NULL", fn);
    const char *problem = header_problem(inst, s->bytes, s->size);
    if (problem)
        return fmu_error(inst, "%s: %s", fn, problem);
    restored r;
    char msg[512];
    if ((problem = read_restored(inst, s, &r, msg, sizeof msg)))
        return fmu_error(inst, "%s: the state is corrupt: %s", fn, problem);
    fmu_core *model = NULL;
    if (r.core_size && !(model = load_core(inst, fn, &r)))
        return FMU_ERROR;
    /* the FMU is in its exited state exactly when the core's run is over (the chute's: the
       particle left it, or lifted off with run_end = first_liftoff, model.md §9; the
       separator's: the grain reached the bins or a plate, §10), or has been terminated */
    const int over = model && fmu_front_run_over(model);
    /* held at the run's end (hold_at_end), the instance stays in Step Mode there */
    const int exited = over && !r.hold_at_end;
    if (model && r.lifecycle != FMU_LIFECYCLE_TERMINATED && exited != (r.lifecycle == FMU_LIFECYCLE_EXITED)) {
        fmu_front_free(model);
        return fmu_error(inst, "%s: the state is corrupt: its run %s over (hold_at_end = %d), "
                         "but its FMI state is %s", fn, over ? "is" : "is not",
                         (int)r.hold_at_end, fmu_lifecycle_name((fmu_lifecycle)r.lifecycle));
    }

    /* all accepted: the instance becomes the state */
    fmu_front_free(inst->core);
    inst->core = model;
    if (model)
        inst->derived = r.derived;
    inst->model_outdated = r.model_outdated != 0;
    inst->rtol_set = (r.tolerances_set & 1) != 0;
    inst->atol_set = (r.tolerances_set & 2) != 0;
    inst->stick_model_set = (r.tolerances_set & 4) != 0;
    inst->hold_at_end = r.hold_at_end != 0;
    inst->scene = r.scene;
    for (int i = 0; i < FMU_MAX_INPUTS; i++)
        inst->inputs[i] = r.inputs[i];
    inst->lifecycle = (fmu_lifecycle)r.lifecycle;
    inst->start_time = r.start_time;
    inst->stop_time = r.stop_time;
    inst->stop_time_defined = r.stop_time_defined != 0;
    inst->time = r.time;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(): back at time %.17g in state %s", fn, r.time,
            fmu_lifecycle_name(inst->lifecycle));
    return FMU_OK;
}
/* ---- free, serialize, deserialize ------------------------------------------------ */

fmu_status fmu_state_free(fmu_instance *inst, const char *fn, fmu_state **state)
{
    (void)fn;
    if (!inst)
        return FMU_ERROR;
    if (state) {
        free(*state);
        *state = NULL;
    }
    return FMU_OK;
}

fmu_status fmu_state_size(fmu_instance *inst, const char *fn, const fmu_state *state, size_t *size)
{
    if (!inst)
        return FMU_ERROR;
    if (!state || !size)
        return fmu_error(inst, "%s: FMUState or size is NULL", fn);
    *size = state->size;
    return FMU_OK;
}

fmu_status fmu_state_serialize(fmu_instance *inst, const char *fn, const fmu_state *state,
                               void *bytes, size_t size)
{
    if (!inst)
        return FMU_ERROR;
    if (!state || !bytes)
        return fmu_error(inst, "%s: FMUState or serializedState is NULL", fn);
    if (size < state->size)
        return fmu_error(inst, "%s: size = %zu is too small for the state's %zu bytes", fn, size,
                         state->size);
    memcpy(bytes, state->bytes, state->size);
    return FMU_OK;
}

fmu_status fmu_state_deserialize(fmu_instance *inst, const char *fn, const void *bytes,
                                 size_t size, fmu_state **state)
{
    if (!inst)
        return FMU_ERROR;
    if (!state)
        return fmu_error(inst, "%s: FMUState is NULL", fn);
    const char *problem = header_problem(inst, bytes, size);
    if (problem)
        return fmu_error(inst, "%s: %s", fn, problem);
    fmu_state *s = malloc(sizeof *s + size);
    if (!s)
        return fmu_error(inst, "%s: out of memory for a state of %zu bytes", fn, size);
    s->size = size;
    memcpy(s->bytes, bytes, size);
    *state = s;
    return FMU_OK;
}
