/*
 * fmu_state.c: FMU states (fmi2GetFMUstate ..., fmi3GetFMUState ...).
 *
 * A state is one block of plain bytes, which is also its serialized form, so that a
 * state restores into any instance of this FMU, a fresh one included, and from bytes
 * written by another process. Layout (native byte order, 8-byte fields):
 *
 *   "TRIBOFMU", layout version, FMI version, total size,
 *   FMI state, start time, stop time, stop time defined, time, the inputs,
 *   number of parameters, every parameter (in the core table's order),
 *   core instance outdated, size of the core's state, the core's state (tribo_state_save)
 *
 * A core state size of 0 means there was no core instance yet (before initialization).
 */
#include "instance_private.h"

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

typedef struct cursor {
    unsigned char *p;
} cursor;

static void put(cursor *c, const void *v, size_t n) { memcpy(c->p, v, n), c->p += n; }
static void put_d(cursor *c, double v) { put(c, &v, sizeof v); }
static void put_i(cursor *c, int64_t v) { put(c, &v, sizeof v); }
static void get(cursor *c, void *v, size_t n) { memcpy(v, c->p, n), c->p += n; }
static double get_d(cursor *c) { double v; get(c, &v, sizeof v); return v; }
static int64_t get_i(cursor *c) { int64_t v; get(c, &v, sizeof v); return v; }

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
    cursor c = {s->bytes};
    put(&c, MAGIC, sizeof MAGIC);
    put_i(&c, LAYOUT_VERSION);
    put_i(&c, inst->fmi_version);
    put_i(&c, (int64_t)size);
    put_i(&c, inst->lifecycle);
    put_d(&c, inst->start_time);
    put_d(&c, inst->stop_time);
    put_i(&c, inst->stop_time_defined);
    put_d(&c, inst->time);
    for (int i = 0; i < TRIBO_INPUT_COUNT; i++)
        put_d(&c, inst->inputs[i]);
    put_i(&c, (int64_t)n_params);
    for (size_t i = 0; i < n_params; i++)
        put_d(&c, tribo_param_read(&inst->scene, &params[i]));
    put_i(&c, inst->model_outdated);
    put_i(&c, (int64_t)core_size);
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
    cursor c = {(unsigned char *)bytes};
    char magic[sizeof MAGIC];
    get(&c, magic, sizeof magic);
    const int64_t layout = get_i(&c), fmi_version = get_i(&c), total = get_i(&c);
    if (memcmp(magic, MAGIC, sizeof MAGIC) != 0 || layout != LAYOUT_VERSION)
        return "the bytes are not a state of this FMU (or of another version of it)";
    if (fmi_version != inst->fmi_version)
        return "the state was saved by an instance of the other FMI version";
    if ((uint64_t)total != size)
        return "the state's size does not match its header (truncated or corrupt)";
    return NULL;
}

static int same_structure(const tribo_scene *a, const tribo_scene *b)
{
    size_t n;
    const tribo_param_info *params = tribo_param_table(&n);
    for (size_t i = 0; i < n; i++)
        if (params[i].variability == TRIBO_PARAM_STRUCTURAL &&
            tribo_param_read(a, &params[i]) != tribo_param_read(b, &params[i]))
            return 0;
    return 1;
}

/* Load the core's bytes into the present core instance when its structure fits, else
   into a new one; *model receives the instance that holds them. */
static fmu_status load_core(fmu_instance *inst, const char *fn, const tribo_scene *scene,
                            const unsigned char *bytes, size_t size, tribo_model **model)
{
    tribo_model *m = inst->model;
    const int reuse = m && same_structure(tribo_get_scene(m), scene);
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
    cursor c = {(unsigned char *)s->bytes + HEADER_SIZE};
    const int64_t mode = get_i(&c);
    const double start_time = get_d(&c), stop_time = get_d(&c);
    const int64_t stop_time_defined = get_i(&c);
    const double time = get_d(&c);
    double inputs[TRIBO_INPUT_COUNT];
    for (int i = 0; i < TRIBO_INPUT_COUNT; i++)
        inputs[i] = get_d(&c);
    if ((size_t)get_i(&c) != n_params)
        return fmu_error(inst, "%s: the state has another set of parameters", fn);
    tribo_scene scene;
    tribo_scene_defaults(&scene);
    for (size_t i = 0; i < n_params; i++) {
        const double v = get_d(&c);
        char msg[512];
        if (tribo_param_check(&params[i], v, msg, sizeof msg) != TRIBO_OK)
            return fmu_error(inst, "%s: the state is corrupt: %s", fn, msg);
        tribo_param_write(&scene, &params[i], v);
    }
    const int64_t model_outdated = get_i(&c);
    const uint64_t core_size = (uint64_t)get_i(&c);
    if (mode < FMU_LIFECYCLE_INSTANTIATED || mode > FMU_LIFECYCLE_TERMINATED || !isfinite(start_time) ||
        !isfinite(stop_time) || !isfinite(time) || !isfinite(inputs[0]) || !isfinite(inputs[1]) ||
        core_size != s->size - fixed_size(n_params) ||
        (core_size == 0 && (mode == FMU_LIFECYCLE_STEP || mode == FMU_LIFECYCLE_TERMINATED)))
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
    inst->lifecycle = (fmu_lifecycle)mode;
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
