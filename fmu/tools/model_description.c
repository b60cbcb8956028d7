/*
 * model_description: writes the modelDescription.xml of the FMI 2.0 or 3.0 FMU from the
 * FMU's variable table (variables_impl.h, made from its front end's table: src/chute/quantities.def,
 * src/si/si_quantities.def or src/separator/separator_quantities.def), at build time. Built once per
 * front end, like the FMUs.
 *
 *   tribo_model_description <2|3> <version> <source date epoch> > modelDescription.xml
 *
 * The instantiation token is written as TOKEN_PLACEHOLDER: the build replaces it with a
 * hash of the rest of the description (token.cmake), so that the token changes exactly
 * when the description does.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "front_end.h"
#include "instance.h"
#include "variables.h"

#define TOKEN_PLACEHOLDER "@INSTANTIATION_TOKEN@"

#define TRIBO_AUTHOR "the tribo contributors"
#define TRIBO_COPYRIGHT "Copyright (c) 2026 the tribo contributors"
/* the files are in each FMU's documentation/licenses/ */
#define TRIBO_LICENSE                                                                          \
    "BSD-3-Clause (documentation/licenses/license.txt); the CVODE solver linked in is SUNDIALS, " \
    "BSD-3-Clause (documentation/licenses/SUNDIALS-LICENSE)"

/* ---- text ---------------------------------------------------------------------------- */

static void put_escaped(const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", stdout); break;
        case '<': fputs("&lt;", stdout); break;
        case '>': fputs("&gt;", stdout); break;
        case '"': fputs("&quot;", stdout); break;
        default: putchar(*s);
        }
    }
}

/* An attribute name="value" (escaped), preceded by a space. */
static void attr(const char *name, const char *value)
{
    printf(" %s=\"", name);
    put_escaped(value);
    putchar('"');
}

/* The shortest decimal that reads back as v (an integer as an integer; an infinity as XML
   Schema's INF, which the importers tested read: tests/python/test_chute_fmu.py). */
static void attr_number(const char *name, double v)
{
    char buf[32];
    if (isinf(v)) {
        printf(" %s=\"%sINF\"", name, v < 0 ? "-" : "");
        return;
    }
    if (v == floor(v) && fabs(v) < 1e15) {
        printf(" %s=\"%.0f\"", name, v);
        return;
    }
    for (int digits = 1; digits <= 17; digits++) {
        snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    printf(" %s=\"%s\"", name, buf);
}

/* ---- units and types ------------------------------------------------------------------ */

static int unit_used(const char *unit)
{
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    for (size_t i = 0; i < n; i++)
        if (v[i].type == FMU_TYPE_REAL && strcmp(v[i].unit, unit) == 0)
            return 1;
    return 0;
}

static int write_units(void)
{
    /* every unit the table names must be defined in it */
    size_t n, n_units;
    const fmu_variable *v = fmu_variables(&n);
    for (size_t i = 0; i < n; i++)
        if (v[i].type == FMU_TYPE_REAL && !fmu_unit_find(v[i].unit)) {
            fprintf(stderr, "model_description: %s has the unit '%s', which no TRIBO_UNIT row defines\n",
                    v[i].name, v[i].unit);
            return 0;
        }
    const fmu_unit *units = fmu_units(&n_units);
    puts("  <UnitDefinitions>");
    for (size_t u = 0; u < n_units; u++) {
        if (!unit_used(units[u].name))
            continue;
        printf("    <Unit");
        attr("name", units[u].name);
        /* an empty BaseUnit: dimensionless, which a Unit without one would not say */
        printf(">\n      <BaseUnit%s%s/>\n", *units[u].base_unit ? " " : "", units[u].base_unit);
        size_t next = 0;
        for (const fmu_display_unit *d; (d = fmu_display_units(units[u].name, &next));) {
            printf("      <DisplayUnit");
            attr("name", d->name);
            attr_number("factor", d->factor);
            puts("/>");
        }
        puts("    </Unit>");
    }
    puts("  </UnitDefinitions>");
    return 1;
}

static int enumeration_used(int enumeration)
{
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    for (size_t i = 0; i < n; i++)
        if (v[i].type == FMU_TYPE_ENUMERATION && v[i].enumeration == enumeration)
            return 1;
    return 0;
}

static void write_type_definitions(int fmi_version)
{
    size_t n;
    const fmu_enumeration *types = fmu_enumerations(&n);
    puts("  <TypeDefinitions>");
    for (size_t e = 0; e < n; e++) {
        if (!enumeration_used((int)e))
            continue;
        printf(fmi_version == 2 ? "    <SimpleType" : "    <EnumerationType");
        attr("name", types[e].type_name);
        attr("description", types[e].description);
        puts(fmi_version == 2 ? ">\n      <Enumeration>" : ">");
        size_t n_items;
        const fmu_enum_item *items = fmu_enum_items((int)e, &n_items);
        for (size_t k = 0; k < n_items; k++) {
            printf(fmi_version == 2 ? "        <Item" : "      <Item");
            attr("name", items[k].name);
            printf(" value=\"%d\"", items[k].value);
            attr("description", items[k].description);
            puts("/>");
        }
        puts(fmi_version == 2 ? "      </Enumeration>\n    </SimpleType>" : "    </EnumerationType>");
    }
    puts("  </TypeDefinitions>");
}

/* ---- variables ------------------------------------------------------------------------- */

/* min / max of a parameter, as FMI's inclusive bounds: an open end is declared as the
   nearest value inside it, so that every declared value is one the FMU accepts. */
static void attr_range(const tribo_param_info *p)
{
    if (isfinite(p->min))
        attr_number("min", p->min_inclusive ? p->min : nextafter(p->min, INFINITY));
    if (isfinite(p->max))
        attr_number("max", p->max_inclusive ? p->max : nextafter(p->max, -INFINITY));
}

/* The attributes of a variable's value: quantity and unit (reals only), range and start. */
static void attr_value(const fmu_variable *v, int fmi_version)
{
    const tribo_param_info *p = fmu_variable_param(v);
    if (v->type == FMU_TYPE_REAL) {
        const fmu_unit *unit = fmu_unit_find(v->unit);
        if (*unit->quantity)
            attr("quantity", unit->quantity);
        attr("unit", v->unit);
        if (unit->display_unit)
            attr("displayUnit", unit->display_unit);
    }
    if (v->type == FMU_TYPE_ENUMERATION)
        attr("declaredType", fmu_enumerations(NULL)[v->enumeration].type_name);
    if (p && v->type == FMU_TYPE_BOOLEAN) { /* a switch: FMI's Boolean has no range */
        attr("start", p->start != 0.0 ? "true" : "false");
    } else if (p) { /* a parameter or an input */
        attr_range(p);
        attr_number("start", p->start);
    }
    (void)fmi_version;
}

static void variable_head(const fmu_variable *v, int fmi_version)
{
    attr("name", v->name);
    printf(" valueReference=\"%u\"", v->vr);
    attr("description", v->description);
    attr("causality", fmu_causality_name(v->causality, fmi_version));
    attr("variability", fmu_variability_name(v->variability));
    /* computed from the parameters at initialization (FMI's default for a calculated
       parameter, said explicitly) */
    if (v->causality == FMU_CAUSALITY_CALCULATED_PARAMETER)
        attr("initial", "calculated");
}

/* The index (FMI 2.0: 1-based position; FMI 3.0: value reference) of a variable. */
static unsigned long reference(const fmu_variable *v, int fmi_version)
{
    if (fmi_version == 3)
        return v->vr;
    size_t n, index = 0;
    const fmu_variable *all = fmu_variables(&n);
    for (size_t i = 0; i < n && &all[i] <= v; i++)
        index += fmu_variable_in_version(&all[i], 2);
    return index;
}

static int is_parameter(const fmu_variable *v)
{
    return v->causality == FMU_CAUSALITY_PARAMETER ||
           v->causality == FMU_CAUSALITY_STRUCTURAL_PARAMETER;
}

/* The model structure. An output of a co-simulation step depends on no input directly:
   inputs act over the next step only (setting one changes no output until then), so
   every output declares an empty list, and importers see no algebraic loop through the
   FMU. At initialization an output depends on the parameters (the initial state comes
   from them, hold_at_end aside), not on the inputs; so does a calculated parameter, which FMI lists among
   the initial unknowns only. */
static void write_model_structure(int fmi_version)
{
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    const char *element[2][2] = {{"      <Unknown", "      <Unknown"}, {"    <Output", "    <InitialUnknown"}};
    puts("  <ModelStructure>");
    for (int section = 0; section < 2; section++) {
        if (fmi_version == 2)
            puts(section ? "    <InitialUnknowns>" : "    <Outputs>");
        for (size_t i = 0; i < n; i++) {
            const int initial_only = v[i].causality == FMU_CAUSALITY_CALCULATED_PARAMETER;
            if (!fmu_variable_in_version(&v[i], fmi_version) ||
                !(v[i].causality == FMU_CAUSALITY_OUTPUT || (section == 1 && initial_only)))
                continue;
            printf("%s %s=\"%lu\" dependencies=\"", element[fmi_version == 3][section],
                   fmi_version == 2 ? "index" : "valueReference", reference(&v[i], fmi_version));
            const char *separator = "";
            for (size_t j = 0; section == 1 && j < n; j++)
                /* hold_at_end acts on the steps after the run's end only */
                if (fmu_variable_in_version(&v[j], fmi_version) && is_parameter(&v[j]) &&
                    v[j].maps_to != FMU_MAPS_TO_INSTANCE) {
                    printf("%s%lu", separator, reference(&v[j], fmi_version));
                    separator = " ";
                }
            puts("\"/>");
        }
        if (fmi_version == 2)
            puts(section ? "    </InitialUnknowns>" : "    </Outputs>");
    }
    puts("  </ModelStructure>");
}

static void write_fmi2_variables(void)
{
    size_t n, index = 0;
    const fmu_variable *v = fmu_variables(&n);
    puts("  <ModelVariables>");
    for (size_t i = 0; i < n; i++) {
        if (!fmu_variable_in_version(&v[i], 2))
            continue;
        printf("    <!-- %zu -->\n    <ScalarVariable", ++index);
        variable_head(&v[i], 2);
        printf(">\n      <%s", fmu_type_name(v[i].type, 2));
        attr_value(&v[i], 2);
        puts("/>\n    </ScalarVariable>");
    }
    puts("  </ModelVariables>");
    write_model_structure(2);
}

static void write_fmi3_variables(void)
{
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    puts("  <ModelVariables>");
    for (size_t i = 0; i < n; i++) {
        if (!fmu_variable_in_version(&v[i], 3))
            continue;
        printf("    <%s", fmu_type_name(v[i].type, 3));
        variable_head(&v[i], 3);
        attr_value(&v[i], 3);
        const fmu_variable *dimension = fmu_variable_dimension(&v[i]);
        if (dimension)
            printf(">\n      <Dimension valueReference=\"%u\"/>\n    </%s>\n", dimension->vr,
                   fmu_type_name(v[i].type, 3));
        else
            puts("/>");
    }
    puts("  </ModelVariables>");
    write_model_structure(3);
}

/* ---- the description ------------------------------------------------------------------- */

/* A retired value reference stays retired, so that an importer that kept it cannot reach
   another variable through it: whether a row takes one (said on stderr). */
static int takes_a_retired_value_reference(void)
{
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    for (size_t i = 0; i < n; i++) {
        const fmu_retired *r = fmu_retired_find(v[i].vr);
        if (r) {
            fprintf(stderr, "model_description: %s takes value reference %u, retired (it was "
                    "%s's, %s): take a new one\n", v[i].name, r->vr, r->name, fmu_front_table_file);
            return 1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    const int version = argc == 4 ? atoi(argv[1]) : 0;
    char *end = NULL;
    const time_t epoch = argc == 4 ? (time_t)strtoll(argv[3], &end, 10) : 0;
    if ((version != 2 && version != 3) || !end || *end || end == argv[3]) {
        fputs("usage: tribo_model_description <2|3> <version> <source date epoch>\n", stderr);
        return 2;
    }
    const char *tool_version = argv[2];
    /* generationDateAndTime: the source date (SOURCE_DATE_EPOCH), so that the same sources
       give the same description */
    char date[32];
    const struct tm *utc = gmtime(&epoch);
    if (!utc || !strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", utc)) {
        fputs("model_description: the source date epoch is out of range\n", stderr);
        return 2;
    }
    const tribo_param_info *rtol = fmu_front_param_find("rtol");
    if (takes_a_retired_value_reference())
        return 1;

    puts("<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    /* (no double hyphen may stand in an XML comment) */
    printf("<!-- The FMI %d.0 description of %s_fmi%d.fmu, generated from %s by\n"
           "     fmu/tools/model_description.c. Do not edit: change the table, then build the\n"
           "     target update_model_descriptions and review the diff. -->\n",
           version, fmu_front_prefix, version, fmu_front_table_file);
    puts("<fmiModelDescription");
    printf("  fmiVersion=\"%d.0\"\n  modelName=\"%s\"\n", version, fmu_front_prefix);
    printf("  %s=\"" TOKEN_PLACEHOLDER "\"\n", version == 2 ? "guid" : "instantiationToken");
    printf("  description=\"");
    put_escaped(fmu_front_description);
    puts("\"");
    printf("  version=\"%s\"\n", tool_version);
    puts("  author=\"" TRIBO_AUTHOR "\"");
    puts("  copyright=\"" TRIBO_COPYRIGHT "\"");
    puts("  license=\"" TRIBO_LICENSE "\"");
    printf("  generationTool=\"tribo model_description %s\"\n", tool_version);
    printf("  generationDateAndTime=\"%s\"\n", date);
    printf("  variableNamingConvention=\"flat\"%s>\n", version == 2 ? "\n  numberOfEventIndicators=\"0\"" : "");
    printf("  <CoSimulation\n    modelIdentifier=\"%s_fmi%d\"\n"
           "    canHandleVariableCommunicationStepSize=\"true\"\n",
           fmu_front_prefix, version);
    if (version == 2)
        puts("    canNotUseMemoryManagementFunctions=\"true\"\n"
             "    canGetAndSetFMUstate=\"true\"\n    canSerializeFMUstate=\"true\"/>");
    else /* a step cut short by the work limit (work_limit) returns early where allowed */
        puts("    canGetAndSetFMUState=\"true\"\n    canSerializeFMUState=\"true\"\n"
             "    mightReturnEarlyFromDoStep=\"true\"/>");
    if (!write_units())
        return 1;
    write_type_definitions(version);
    puts("  <LogCategories>");
    for (int c = 0; c < FMU_LOG_CATEGORY_COUNT; c++) {
        printf("    <Category");
        attr("name", fmu_log_category_name((fmu_log_category)c));
        attr("description", fmu_log_category_description((fmu_log_category)c));
        puts("/>");
    }
    puts("  </LogCategories>");
    /* the default tolerance is the default of rtol, the parameter that sets it */
    printf("  <DefaultExperiment startTime=\"0\"");
    attr_number("stopTime", fmu_front_default_experiment.stop_time);
    attr_number("tolerance", rtol->start);
    attr_number("stepSize", fmu_front_default_experiment.step_size);
    puts("/>");
    if (version == 2)
        write_fmi2_variables();
    else
        write_fmi3_variables();
    puts("</fmiModelDescription>");
    return ferror(stdout) ? 1 : 0;
}
