/* access.c: getting and setting variables by value reference, through the table. */
#include "instance_private.h"

#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* ---- the importer's arrays, whatever their C type ------------------------------- */

static double load(fmu_c_type t, const void *values, size_t i)
{
    switch (t) {
    case FMU_C_DOUBLE: return ((const double *)values)[i];
    case FMU_C_INT: return ((const int *)values)[i];
    case FMU_C_INT32: return ((const int32_t *)values)[i];
    case FMU_C_INT64: return (double)((const int64_t *)values)[i];
    case FMU_C_UINT64: return (double)((const uint64_t *)values)[i];
    case FMU_C_BOOL: return ((const bool *)values)[i];
    case FMU_C_NONE: break;
    }
    return NAN;
}

/* The value of v at values[i] (a Boolean as 0 or 1: check_value refuses an FMI 2.0
   Boolean other than fmi2True and fmi2False). */
static double load_value(const fmu_variable *v, fmu_c_type t, const void *values, size_t i)
{
    const double value = load(t, values, i);
    return v->type == FMU_TYPE_BOOLEAN ? (double)(value != 0.0) : value;
}

/* An FMI 2.0 Boolean is an int that must be fmi2True (1) or fmi2False (0): 2 or -1 is an
   importer's mistake (a C truth value passed as it is, or memory not written), refused
   rather than taken as true. (An FMI 3.0 Boolean is a C bool: 0 or 1 by its type.) */
static int boolean_valid(fmu_instance *inst, const char *fn, const fmu_variable *v,
                         fmu_c_type t, const void *values, size_t i)
{
    if (v->type != FMU_TYPE_BOOLEAN || t != FMU_C_INT)
        return 1;
    const double raw = load(t, values, i);
    if (raw == 0.0 || raw == 1.0)
        return 1;
    fmu_error(inst, "%s: %s = %.17g is not an fmi2Boolean: it must be fmi2True (1) or fmi2False (0)",
              fn, v->name, raw);
    return 0;
}

/* Values stored into integer arrays are integers: validated parameters, flags, classes
   and counts. A count beyond the array's type saturates (a count of 2^31 steps outside
   the model's assumptions says as much as a larger one). */
static double saturate(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

static void store(fmu_c_type t, void *values, size_t i, double v)
{
    switch (t) {
    case FMU_C_DOUBLE: ((double *)values)[i] = v; break;
    case FMU_C_INT: ((int *)values)[i] = (int)saturate(v, INT_MIN, INT_MAX); break;
    case FMU_C_INT32: ((int32_t *)values)[i] = (int32_t)saturate(v, INT32_MIN, INT32_MAX); break;
    case FMU_C_INT64: ((int64_t *)values)[i] = (int64_t)saturate(v, -0x1p63, 0x1p62); break;
    case FMU_C_UINT64: ((uint64_t *)values)[i] = (uint64_t)saturate(v, 0, 0x1p63); break;
    case FMU_C_BOOL: ((bool *)values)[i] = v != 0.0; break;
    case FMU_C_NONE: break;
    }
}

/* ---- value references -------------------------------------------------------------- */

static const fmu_variable *resolve(fmu_instance *inst, const char *fn, fmu_vr vr, unsigned types)
{
    const fmu_variable *v = fmu_variable_find(vr, inst->fmi_version);
    if (!v) {
        const fmu_retired *r = fmu_retired_find(vr);
        if (r)
            fmu_error(inst, "%s: value reference %u is retired (it was %s's): %s", fn, vr,
                      r->name, r->instead);
        else
            fmu_error(inst, "%s: unknown value reference %u", fn, vr);
        return NULL;
    }
    if (!(types & FMU_TYPE_BIT(v->type))) {
        fmu_error(inst, "%s: %s (value reference %u) is a variable of type %s", fn, v->name, vr,
                  fmu_type_name(v->type, inst->fmi_version));
        return NULL;
    }
    return v;
}

static size_t value_count(const fmu_instance *inst, const fmu_variable *v)
{
    return v->maps_to == FMU_MAPS_TO_SEGMENTS ? (size_t)fmu_scene_value(inst, "n_segments") : 1;
}

/* Resolve every value reference and check that they hold nvalues values. */
static int resolve_all(fmu_instance *inst, const char *fn, unsigned types, const fmu_vr vrs[],
                       size_t nvr, const void *values, size_t nvalues)
{
    if (nvr > 0 && (!vrs || !values)) {
        fmu_error(inst, "%s: valueReferences or values is NULL", fn);
        return 0;
    }
    size_t total = 0;
    for (size_t i = 0; i < nvr; i++) {
        const fmu_variable *v = resolve(inst, fn, vrs[i], types);
        if (!v)
            return 0;
        total += value_count(inst, v);
    }
    if (total != nvalues) {
        fmu_error(inst, "%s: nValues = %zu, but the %zu variables hold %zu values", fn, nvalues,
                  nvr, total);
        return 0;
    }
    return 1;
}

/* One variable of a call, at values[k...]; returns 0 to stop the walk. */
typedef int (*visit_fn)(fmu_instance *inst, const char *fn, const fmu_variable *v,
                        fmu_c_type c_type, void *values, size_t k);

/* Visit the variables of a call (resolved by resolve_all) in order, each with the index of
   its first value. */
static int walk(fmu_instance *inst, const char *fn, const fmu_vr vrs[], size_t nvr,
                fmu_c_type c_type, void *values, visit_fn visit)
{
    size_t k = 0;
    for (size_t i = 0; i < nvr; i++) {
        const fmu_variable *v = fmu_variable_find(vrs[i], inst->fmi_version);
        if (!visit(inst, fn, v, c_type, values, k))
            return 0;
        k += value_count(inst, v);
    }
    return 1;
}

/* ---- get ------------------------------------------------------------------------- */

static int model_readable(fmu_instance *inst, const char *fn, const fmu_variable *v)
{
    const unsigned modes = FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INITIALIZATION) | FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP) |
                           FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_TERMINATED) |
                           FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP_DISCARDED) | FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_FAILED) |
                           FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_EXITED);
    if (!(modes & FMU_LIFECYCLE_BIT(inst->lifecycle))) {
        fmu_error(inst, "%s: %s is computed from Initialization Mode on; it cannot be read in state %s",
                  fn, v->name, fmu_lifecycle_name(inst->lifecycle));
        return 0;
    }
    /* outputs in Initialization Mode reflect the parameters set so far */
    return fmu_ensure_model(inst, fn) == FMU_OK;
}

/* Refuse a value of v that is not a number (only a failed core holds one): what the core
   said about its failure, if anything. */
static int not_finite(fmu_instance *inst, const char *fn, const fmu_variable *v, const char *index,
                      double value)
{
    const char *why = fmu_front_last_error(inst->core);
    fmu_error(inst, "%s: %s%s = %g is not a finite number (%s%s)", fn, v->name, index, value,
              why[0] ? "the core failed: " : "the core reported no failure",
              why[0] ? why : "");
    return 0;
}

/* Write the values of v at values[k...]. */
static int read_variable(fmu_instance *inst, const char *fn, const fmu_variable *v,
                         fmu_c_type c_type, void *values, size_t k)
{
    switch (v->maps_to) {
    case FMU_MAPS_TO_TIME:
        store(c_type, values, k, inst->time);
        return 1;
    case FMU_MAPS_TO_PARAMETER:
        store(c_type, values, k, tribo_param_read(&inst->scene, fmu_variable_param(v)));
        return 1;
    case FMU_MAPS_TO_INPUT:
        store(c_type, values, k, inst->inputs[v->index]);
        return 1;
    case FMU_MAPS_TO_INSTANCE:
        store(c_type, values, k, inst->hold_at_end);
        return 1;
    case FMU_MAPS_TO_QUANTITY: {
        if (!model_readable(inst, fn, v))
            return 0;
        const double value = fmu_front_get(&inst->derived, inst->core, v->index);
        /* after a failed step the core may hold what is not a number: never with OK (a
           calculated parameter of a parameter that may be INF may be INF: the chute's
           length with no end) */
        const int no_end = value == INFINITY && v->causality == FMU_CAUSALITY_CALCULATED_PARAMETER;
        if (!isfinite(value) && !no_end)
            return not_finite(inst, fn, v, "", value);
        store(c_type, values, k, value);
        return 1;
    }
    case FMU_MAPS_TO_SEGMENTS: {
        if (!model_readable(inst, fn, v))
            return 0;
        /* segment arrays are Float64 only (the type check saw to it) */
        double *out = (double *)values + k;
        const size_t n = value_count(inst, v);
        if (fmu_front_segments(&inst->derived, inst->core, v->index, out, n) != TRIBO_OK) {
            fmu_error(inst, "%s: %s: %s", fn, v->name, fmu_front_last_error(inst->core));
            return 0;
        }
        for (size_t i = 0; i < n; i++)
            if (!isfinite(out[i])) {
                char index[32];
                snprintf(index, sizeof index, "[%zu]", i);
                return not_finite(inst, fn, v, index, out[i]);
            }
        return 1;
    }
    }
    return 0;
}

fmu_status fmu_get(fmu_instance *inst, const char *fn, unsigned types, fmu_c_type c_type,
                   const fmu_vr vrs[], size_t nvr, void *values, size_t nvalues)
{
    if (!inst)
        return FMU_ERROR;
    if (!resolve_all(inst, fn, types, vrs, nvr, values, nvalues) ||
        !walk(inst, fn, vrs, nvr, c_type, values, read_variable))
        return FMU_ERROR;
    return FMU_OK;
}

/* ---- set: the whole call is checked, then applied ------------------------------------- */

static int is_structural(const fmu_instance *inst, const fmu_variable *v)
{
    return inst->fmi_version == 3 && v->causality == FMU_CAUSALITY_STRUCTURAL_PARAMETER;
}

static unsigned modes_settable(const fmu_instance *inst, const fmu_variable *v)
{
    if (is_structural(inst, v))
        return FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INSTANTIATED) | FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_CONFIGURATION);
    unsigned modes = FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INSTANTIATED) | FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INITIALIZATION);
    if (v->variability == FMU_VARIABILITY_TUNABLE || v->causality == FMU_CAUSALITY_INPUT)
        modes |= FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP);
    return modes;
}

static const char *when_settable(const fmu_instance *inst, const fmu_variable *v)
{
    if (is_structural(inst, v))
        return "a structural parameter, set in state Instantiated or in Configuration Mode";
    if (v->causality == FMU_CAUSALITY_INPUT)
        return "an input, set before initialization ends or between steps";
    if (v->variability == FMU_VARIABILITY_TUNABLE)
        return "a tunable parameter, set before initialization ends or between steps";
    return "a fixed parameter, set in state Instantiated or in Initialization Mode";
}

/* Whether the running model takes the value of a tunable parameter or an input. */
static int model_accepts(const fmu_instance *inst, const fmu_variable *v, double value, char *msg,
                         size_t msg_size)
{
    if (v->maps_to == FMU_MAPS_TO_INPUT) {
        double inputs[FMU_MAX_INPUTS], model_inputs[FMU_MAX_INPUTS];
        for (int i = 0; i < fmu_front_input_count(); i++)
            inputs[i] = i == v->index ? value : inst->inputs[i];
        return fmu_front_model_inputs(&inst->derived, inputs, model_inputs, msg, msg_size) == TRIBO_OK;
    }
    const char *name;
    double model_value;
    return fmu_front_tunable(&inst->derived, fmu_variable_param(v), value, &name, &model_value, msg,
                             msg_size) == TRIBO_OK;
}

/* Whether v may take the value now: settable in this state, and within its range. */
static int check_value(fmu_instance *inst, const char *fn, const fmu_variable *v, fmu_c_type c_type,
                       void *values, size_t k)
{
    if (!boolean_valid(inst, fn, v, c_type, values, k))
        return 0;
    const double value = load_value(v, c_type, values, k);
    const tribo_param_info *p = fmu_variable_param(v);
    if (!p) {
        fmu_error(inst, "%s: %s (value reference %u) is %s, computed by the FMU: it cannot be set "
                  "(value %.17g refused)",
                  fn, v->name, v->vr,
                  v->maps_to == FMU_MAPS_TO_TIME                     ? "the independent variable"
                  : v->causality == FMU_CAUSALITY_CALCULATED_PARAMETER ? "a calculated parameter"
                                                                       : "an output",
                  value);
        return 0;
    }
    char msg[512];
    if (tribo_param_check(p, value, msg, sizeof msg) != TRIBO_OK) {
        fmu_error(inst, "%s: %s", fn, msg);
        return 0;
    }
    if (!(modes_settable(inst, v) & FMU_LIFECYCLE_BIT(inst->lifecycle))) {
        char range[160];
        tribo_param_range_text(p, range, sizeof range);
        fmu_error(inst, "%s: %s = %.17g cannot be set in state %s: %s is %s (valid range: %s)", fn,
                  v->name, value, fmu_lifecycle_name(inst->lifecycle), v->name, when_settable(inst, v), range);
        return 0;
    }
    /* while running, the value must also be one the model takes (the front end's
       conversion: an SI value whose model value is out of the model's range is refused) */
    if (inst->lifecycle == FMU_LIFECYCLE_STEP && !model_accepts(inst, v, value, msg, sizeof msg)) {
        fmu_error(inst, "%s: %s", fn, msg);
        return 0;
    }
    return 1;
}

/* Apply a value check_value accepted. */
static int apply_value(fmu_instance *inst, const char *fn, const fmu_variable *v, fmu_c_type c_type,
                       void *values, size_t k)
{
    const double value = load_value(v, c_type, values, k);
    if (v->maps_to == FMU_MAPS_TO_INPUT) {
        /* applied by the next step, from its communication point on */
        inst->inputs[v->index] = value;
    } else if (v->maps_to == FMU_MAPS_TO_INSTANCE) {
        /* fixed: the core does not know it, and none is made of it */
        inst->hold_at_end = value != 0.0;
    } else {
        const tribo_param_info *p = fmu_variable_param(v);
        if (inst->lifecycle == FMU_LIFECYCLE_STEP) {
            /* the core commits the present, then runs on with the new value; it has checked
               nothing the FMU did not, so a failure here is the integrator's restart */
            const char *model_name;
            double model_value;
            char msg[512];
            if (fmu_front_tunable(&inst->derived, p, value, &model_name, &model_value, msg,
                                  sizeof msg) != TRIBO_OK ||
                fmu_front_set_param(inst->core, &inst->derived, model_name, model_value) !=
                    TRIBO_OK) {
                inst->lifecycle = FMU_LIFECYCLE_FAILED;
                fmu_error(inst, "%s: %s", fn, fmu_front_last_error(inst->core));
                return 0;
            }
        } else {
            /* by their bits: -0.0 == +0.0, and a core made with the one holds it where the
               scene, and so the state, hold the other */
            const double held = tribo_param_read(&inst->scene, p);
            if (memcmp(&held, &value, sizeof value) != 0)
                inst->model_outdated = 1;
        }
        tribo_param_write(&inst->scene, p, value);
        fmu_note_parameter_set(inst, p);
    }
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s: %s = %.17g", fn, v->name, value);
    return 1;
}

/* Whether the parameters after the call (each value checked alone already) go together
   where the FMU can tell: the rigid stick chosen explicitly with the fixed step or the
   centre's dashpot is refused here, at the set call that makes the conflict, whichever of
   them comes last; a stick_model left unset follows them (fmu_follow_defaults). */
static int call_fits(fmu_instance *inst, const char *fn, const fmu_vr vrs[], size_t nvr,
                     fmu_c_type c_type, const void *values)
{
    fmu_scene trial = inst->scene;
    int stick_model_set = inst->stick_model_set;
    size_t k = 0;
    for (size_t i = 0; i < nvr; i++) {
        const fmu_variable *v = fmu_variable_find(vrs[i], inst->fmi_version);
        if (v->maps_to == FMU_MAPS_TO_PARAMETER) {
            const tribo_param_info *p = fmu_variable_param(v);
            tribo_param_write(&trial, p, load_value(v, c_type, values, k));
            stick_model_set |= strcmp(p->name, "stick_model") == 0;
        }
        k += value_count(inst, v);
    }
    fmu_follow_defaults(&trial, stick_model_set);
    char msg[400];
    if (fmu_stick_model_fits(&trial, msg, sizeof msg))
        return 1;
    fmu_error(inst, "%s: %s", fn, msg);
    return 0;
}

/* After the call: a default that follows the parameters set follows them. */
static void follow_defaults(fmu_instance *inst)
{
    const fmu_scene before = inst->scene;
    fmu_follow_defaults(&inst->scene, inst->stick_model_set);
    if (memcmp(&before, &inst->scene, sizeof before) != 0)
        inst->model_outdated = 1;
}

fmu_status fmu_set(fmu_instance *inst, const char *fn, unsigned types, fmu_c_type c_type,
                   const fmu_vr vrs[], size_t nvr, const void *values, size_t nvalues)
{
    if (!inst)
        return FMU_ERROR;
    /* the walk's signature serves get and set alike; set only reads the values */
    void *in = (void *)values;
    if (!resolve_all(inst, fn, types, vrs, nvr, values, nvalues) ||
        !walk(inst, fn, vrs, nvr, c_type, in, check_value) ||
        !call_fits(inst, fn, vrs, nvr, c_type, values) ||
        !walk(inst, fn, vrs, nvr, c_type, in, apply_value))
        return FMU_ERROR;
    follow_defaults(inst);
    return FMU_OK;
}
