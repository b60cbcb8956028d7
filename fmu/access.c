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
    return v->maps_to == FMU_MAPS_TO_SEGMENTS ? (size_t)inst->scene.n_segments : 1;
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

/* ---- get ------------------------------------------------------------------------- */

static int model_readable(fmu_instance *inst, const char *fn, const fmu_variable *v)
{
    const unsigned modes = FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_INITIALIZATION) | FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP) |
                           FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_TERMINATED) | FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_FAILED);
    if (!(modes & FMU_LIFECYCLE_BIT(inst->lifecycle))) {
        fmu_error(inst, "%s: %s is computed from Initialization Mode on; it cannot be read in state %s",
                  fn, v->name, fmu_lifecycle_name(inst->lifecycle));
        return 0;
    }
    /* outputs in Initialization Mode reflect the parameters set so far */
    return fmu_ensure_model(inst, fn) == FMU_OK;
}

static int has_charge_model(const fmu_instance *inst, tribo_segment_charge which)
{
    const int bit = which == TRIBO_SEGMENTS_STATIC ? TRIBO_CHARGE_STATIC : TRIBO_CHARGE_SLIDING;
    return (inst->scene.charge_model & bit) != 0;
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
    case FMU_MAPS_TO_QUANTITY:
        if (!model_readable(inst, fn, v))
            return 0;
        store(c_type, values, k, tribo_get(inst->model, (tribo_quantity)v->index));
        return 1;
    case FMU_MAPS_TO_SEGMENTS: {
        if (!model_readable(inst, fn, v))
            return 0;
        /* segment arrays are Float64 only (the type check saw to it) */
        double *out = (double *)values + k;
        const size_t n = value_count(inst, v);
        const tribo_segment_charge which = (tribo_segment_charge)v->index;
        /* a charge model the scene leaves out has no charge: zeros, as its mean */
        if (!has_charge_model(inst, which)) {
            for (size_t i = 0; i < n; i++)
                out[i] = 0.0;
            return 1;
        }
        if (tribo_get_segment_charges(inst->model, which, out, n) != TRIBO_OK) {
            fmu_error(inst, "%s: %s: %s", fn, v->name, tribo_last_error(inst->model));
            return 0;
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
    if (!resolve_all(inst, fn, types, vrs, nvr, values, nvalues))
        return FMU_ERROR;
    size_t k = 0;
    for (size_t i = 0; i < nvr; i++) {
        const fmu_variable *v = fmu_variable_find(vrs[i], inst->fmi_version);
        if (!read_variable(inst, fn, v, c_type, values, k))
            return FMU_ERROR;
        k += value_count(inst, v);
    }
    return FMU_OK;
}

/* ---- set ------------------------------------------------------------------------- */

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
    if (v->variability == FMU_VARIABILITY_TUNABLE)
        return "a tunable parameter, set before initialization ends or between steps";
    return "a fixed parameter, set in state Instantiated or in Initialization Mode";
}

static int write_parameter(fmu_instance *inst, const char *fn, const fmu_variable *v, double value)
{
    const tribo_param_info *p = fmu_variable_param(v);
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
    if (inst->lifecycle == FMU_LIFECYCLE_STEP) {
        /* the core commits the present, then runs on with the new value */
        if (tribo_set_param(inst->model, v->name, value) != TRIBO_OK) {
            fmu_error(inst, "%s: %s", fn, tribo_last_error(inst->model));
            return 0;
        }
    } else if (tribo_param_read(&inst->scene, p) != value) {
        inst->model_outdated = 1;
    }
    tribo_param_write(&inst->scene, p, value);
    fmu_note_parameter_set(inst, p);
    return 1;
}

static int write_input(fmu_instance *inst, const char *fn, const fmu_variable *v, double value)
{
    if (!(modes_settable(inst, v) & FMU_LIFECYCLE_BIT(inst->lifecycle))) {
        fmu_error(inst, "%s: %s = %.17g cannot be set in state %s", fn, v->name, value,
                  fmu_lifecycle_name(inst->lifecycle));
        return 0;
    }
    if (!isfinite(value)) {
        fmu_error(inst, "%s: %s = %.17g is invalid: the valid range is any finite number", fn,
                  v->name, value);
        return 0;
    }
    /* applied by the next step, from its communication point on */
    inst->inputs[v->index] = value;
    return 1;
}

fmu_status fmu_set(fmu_instance *inst, const char *fn, unsigned types, fmu_c_type c_type,
                   const fmu_vr vrs[], size_t nvr, const void *values, size_t nvalues)
{
    if (!inst)
        return FMU_ERROR;
    if (!resolve_all(inst, fn, types, vrs, nvr, values, nvalues))
        return FMU_ERROR;
    size_t k = 0;
    for (size_t i = 0; i < nvr; i++) {
        const fmu_variable *v = fmu_variable_find(vrs[i], inst->fmi_version);
        const double value = load(c_type, values, k);
        int ok = 0;
        switch (v->maps_to) {
        case FMU_MAPS_TO_PARAMETER: ok = write_parameter(inst, fn, v, value); break;
        case FMU_MAPS_TO_INPUT: ok = write_input(inst, fn, v, value); break;
        case FMU_MAPS_TO_TIME:
        case FMU_MAPS_TO_QUANTITY:
        case FMU_MAPS_TO_SEGMENTS:
            fmu_error(inst, "%s: %s (value reference %u) is %s, computed by the FMU: it cannot be set "
                      "(value %.17g refused)",
                      fn, v->name, v->vr,
                      v->maps_to == FMU_MAPS_TO_TIME ? "the independent variable" : "an output",
                      value);
            break;
        }
        if (!ok)
            return FMU_ERROR;
        fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s: %s = %.17g", fn, v->name, value);
        k += value_count(inst, v);
    }
    return FMU_OK;
}
