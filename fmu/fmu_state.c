/*
 * fmu_state.c: FMU states (fmi2GetFMUstate ..., fmi3GetFMUState ...).
 *
 * A state is one block of plain bytes, which is also its serialized form, so that a
 * state restores into any instance of this FMU, a fresh one included, and from bytes
 * written by another process. Layout (native byte order, 8-byte fields):
 *
 *   "TRIBOFMU", layout version, FMI version, total size,
 *   lifecycle state, start time, stop time, stop time defined, time, the inputs,
 *   number of parameters, every parameter (in the core table's order),
 *   core instance outdated, size of the core's state, the core's state (tribo_state_save)
 *
 * A core state size of 0 means there was no core instance yet (before initialization).
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
enum { LAYOUT_VERSION = 1, HEADER_SIZE = 8 + 3 * 8 };

/* Everything but the core's state: the header, 8 fields, the inputs and the parameters. */
static size_t fixed_size(size_t n_params)
{
    return HEADER_SIZE + 8 * 8 + TRIBO_INPUT_COUNT * 8 + n_params * 8;
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
    const tribo_param_info *params = tribo_param_table(&n_params);
    const size_t core_size = inst->model ? tribo_state_size(inst->model) : 0;
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
    for (int i = 0; i < TRIBO_INPUT_COUNT; i++)
        tribo_write_double(&c, inst->inputs[i]);
    tribo_write_int(&c, (int64_t)n_params);
    for (size_t i = 0; i < n_params; i++)
        tribo_write_double(&c, tribo_param_read(&inst->scene, &params[i]));
    tribo_write_int(&c, inst->model_outdated);
    tribo_write_int(&c, (int64_t)core_size);
    if (core_size && tribo_state_save(inst->model, c.p, core_size) != TRIBO_OK)
        return fmu_error(inst, "%s: %s", fn, tribo_last_error(inst->model));
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

/* Load the core's bytes into the present core instance when its structure fits, else
   into a new one; *model receives the instance that holds them. */
static fmu_status load_core(fmu_instance *inst, const char *fn, const tribo_scene *scene,
                            const unsigned char *bytes, size_t size, tribo_model **model)
{
    tribo_model *m = inst->model;
    const int reuse = m && !tribo_scene_structure_differs(tribo_get_scene(m), scene);
    if (!reuse) {
        char why[512];
        if (!(m = tribo_create(scene, why, sizeof why)))
            return fmu_error(inst, "%s: the model cannot be created: %s", fn, why);
        tribo_set_logger(m, fmu_core_logger, inst);
    }
    if (tribo_state_load(m, bytes, size) != TRIBO_OK) {
        fmu_error(inst, "%s: the core refused the state: %s", fn, tribo_last_error(m));
        if (reuse)
            inst->lifecycle = FMU_LIFECYCLE_FAILED; /* the core instance may be half loaded */
        else
            tribo_free(m);
        return FMU_ERROR;
    }
    *model = m;
    return FMU_OK;
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

    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    if (s->size < fixed_size(n_params))
        return fmu_error(inst, "%s: the state is too short", fn);
    tribo_reader c = tribo_reader_of(s->bytes + HEADER_SIZE, s->size - HEADER_SIZE);
    const int64_t lifecycle = tribo_read_int(&c);
    const double start_time = tribo_read_double(&c), stop_time = tribo_read_double(&c);
    const int64_t stop_time_defined = tribo_read_int(&c);
    const double time = tribo_read_double(&c);
    double inputs[TRIBO_INPUT_COUNT];
    for (int i = 0; i < TRIBO_INPUT_COUNT; i++)
        inputs[i] = tribo_read_double(&c);
    if ((size_t)tribo_read_int(&c) != n_params)
        return fmu_error(inst, "%s: the state has another set of parameters", fn);
    tribo_scene scene;
    tribo_scene_defaults(&scene);
    for (size_t i = 0; i < n_params; i++) {
        const double v = tribo_read_double(&c);
        char msg[512];
        if (tribo_param_check(&params[i], v, msg, sizeof msg) != TRIBO_OK)
            return fmu_error(inst, "%s: the state is corrupt: %s", fn, msg);
        tribo_param_write(&scene, &params[i], v);
    }
    const int64_t model_outdated = tribo_read_int(&c);
    const uint64_t core_size = (uint64_t)tribo_read_int(&c);
    if (lifecycle < FMU_LIFECYCLE_INSTANTIATED || lifecycle > FMU_LIFECYCLE_TERMINATED || !isfinite(start_time) ||
        !isfinite(stop_time) || !isfinite(time) || !isfinite(inputs[0]) || !isfinite(inputs[1]) ||
        core_size != s->size - fixed_size(n_params) ||
        (core_size == 0 && (lifecycle == FMU_LIFECYCLE_STEP || lifecycle == FMU_LIFECYCLE_TERMINATED)))
        return fmu_error(inst, "%s: the state is corrupt", fn);

    tribo_model *model = NULL;
    if (core_size && load_core(inst, fn, &scene, c.p, core_size, &model) != FMU_OK)
        return FMU_ERROR;
    if (inst->model != model)
        tribo_free(inst->model);
    inst->model = model;
    inst->model_outdated = model_outdated != 0;
    inst->scene = scene;
    for (int i = 0; i < TRIBO_INPUT_COUNT; i++)
        inst->inputs[i] = inputs[i];
    inst->lifecycle = (fmu_lifecycle)lifecycle;
    inst->start_time = start_time;
    inst->stop_time = stop_time;
    inst->stop_time_defined = stop_time_defined != 0;
    inst->time = time;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(): back at time %.17g in state %s", fn, time,
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
