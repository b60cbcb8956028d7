/*
 * print_variables: the FMU's variable table as JSON, with what it resolves to in the
 * core (descriptions, units, start values, ranges), the instantiation token and the log
 * categories. tests/python compares the modelDescription files against it, so that the
 * table in variables.c stays the one description of the FMU's interface.
 */
#include <math.h>
#include <stdio.h>

#include "instance.h"
#include "variables.h"

static void print_string(const char *s)
{
    if (!s) {
        fputs("null", stdout);
        return;
    }
    putchar('"');
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            putchar('\\');
        putchar(*s);
    }
    putchar('"');
}

static void print_number(double v)
{
    if (isfinite(v))
        printf("%.17g", v);
    else
        fputs("null", stdout); /* open-ended range */
}

static const char *variability_of_param(tribo_param_variability v)
{
    switch (v) {
    case TRIBO_PARAM_STRUCTURAL: return "structural";
    case TRIBO_PARAM_FIXED: return "fixed";
    case TRIBO_PARAM_TUNABLE: return "tunable";
    }
    return "?";
}

static const char *mapping_name(fmu_mapping m)
{
    switch (m) {
    case FMU_MAPS_TO_TIME: return "time";
    case FMU_MAPS_TO_PARAMETER: return "parameter";
    case FMU_MAPS_TO_INPUT: return "input";
    case FMU_MAPS_TO_QUANTITY: return "quantity";
    case FMU_MAPS_TO_SEGMENTS: return "segments";
    }
    return "?";
}

static void print_variable(const fmu_variable *v, const tribo_scene *defaults)
{
    printf("    {\"vr\": %u, \"name\": ", v->vr);
    print_string(v->name);
    for (int version = 2; version <= 3; version++) {
        const int in = fmu_variable_in_version(v, version);
        printf(", \"type_fmi%d\": ", version);
        print_string(in ? fmu_type_name(v->type, version) : NULL);
        printf(", \"causality_fmi%d\": ", version);
        print_string(in ? fmu_causality_name(v->causality, version) : NULL);
    }
    fputs(", \"variability\": ", stdout);
    print_string(fmu_variability_name(v->variability));
    fputs(", \"maps_to\": ", stdout);
    print_string(mapping_name(v->maps_to));
    fputs(", \"description\": ", stdout);
    print_string(fmu_variable_description(v));
    fputs(", \"unit\": ", stdout);
    print_string(fmu_variable_unit(v));

    const tribo_param_info *p = fmu_variable_param(v);
    fputs(", \"start\": ", stdout);
    if (p)
        print_number(tribo_param_read(defaults, p));
    else if (v->maps_to == FMU_MAPS_TO_INPUT)
        print_number(0.0);
    else
        fputs("null", stdout);
    if (p) {
        fputs(", \"min\": ", stdout);
        print_number(p->min);
        fputs(", \"max\": ", stdout);
        print_number(p->max);
        fputs(", \"core_variability\": ", stdout);
        print_string(variability_of_param(p->variability));
        printf(", \"core_is_integer\": %s", p->type != TRIBO_TYPE_REAL ? "true" : "false");
    }
    if (v->maps_to == FMU_MAPS_TO_QUANTITY) {
        fputs(", \"core_name\": ", stdout);
        print_string(tribo_quantity_name((tribo_quantity)v->index));
    }
    if (v->maps_to == FMU_MAPS_TO_SEGMENTS) {
        fputs(", \"dimension\": \"n_segments\", \"core_name\": ", stdout);
        print_string(v->index == TRIBO_SEGMENTS_STATIC ? "static" : "sliding");
    }
    fputs("}", stdout);
}

int main(void)
{
    tribo_scene defaults;
    tribo_scene_defaults(&defaults);

    fputs("{\n  \"token\": ", stdout);
    print_string(FMU_INSTANTIATION_TOKEN);

    fputs(",\n  \"log_categories\": [", stdout);
    for (int c = 0; c < FMU_LOG_CATEGORY_COUNT; c++) {
        fputs(c ? ", {\"name\": " : "{\"name\": ", stdout);
        print_string(fmu_log_category_name((fmu_log_category)c));
        fputs(", \"description\": ", stdout);
        print_string(fmu_log_category_description((fmu_log_category)c));
        putchar('}');
    }

    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    fputs("],\n  \"core_parameters\": [", stdout);
    for (size_t i = 0; i < n_params; i++) {
        fputs(i ? ", " : "", stdout);
        print_string(params[i].name);
    }
    fputs("],\n  \"core_quantities\": [", stdout);
    for (int q = 0; q < TRIBO_Q_COUNT; q++) {
        fputs(q ? ", " : "", stdout);
        print_string(tribo_quantity_name((tribo_quantity)q));
    }

    size_t n;
    const fmu_variable *vars = fmu_variables(&n);
    fputs("],\n  \"variables\": [\n", stdout);
    for (size_t i = 0; i < n; i++) {
        print_variable(&vars[i], &defaults);
        fputs(i + 1 < n ? ",\n" : "\n", stdout);
    }
    fputs("  ]\n}\n", stdout);
    return 0;
}
