/*
 * model_description: writes the modelDescription.xml of the FMI 2.0 or 3.0 FMU from the
 * FMU's variable table (variables.c, made from src/quantities.def), at build time.
 *
 *   tribo_model_description <2|3> <tool version> > modelDescription.xml
 *
 * The instantiation token is written as TOKEN_PLACEHOLDER: the build replaces it with a
 * hash of the rest of the description (token.cmake), so that the token changes exactly
 * when the description does.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "instance.h"
#include "variables.h"

#define TOKEN_PLACEHOLDER "@INSTANTIATION_TOKEN@"

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

/* The shortest decimal that reads back as v (an integer as an integer). */
static void attr_number(const char *name, double v)
{
    char buf[32];
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

/* ---- units ---------------------------------------------------------------------------- */

/* Every unit a variable may name, with its BaseUnit attributes (NULL: none). */
static const struct {
    const char *name, *base;
} UNITS[] = {
    {"1", NULL},
    {"deg", "rad=\"1\" factor=\"0.017453292519943295\""},
    {"rad", "rad=\"1\""},
};

static int unit_used(const char *unit)
{
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(v[i].unit, unit) == 0)
            return 1;
    return 0;
}

static int write_units(void)
{
    /* every unit the table names must be defined here */
    size_t n;
    const fmu_variable *v = fmu_variables(&n);
    for (size_t i = 0; i < n; i++) {
        int known = 0;
        for (size_t u = 0; u < sizeof UNITS / sizeof UNITS[0]; u++)
            known |= strcmp(UNITS[u].name, v[i].unit) == 0;
        if (!known) {
            fprintf(stderr, "model_description: %s has the unit '%s', which UNITS does not define\n",
                    v[i].name, v[i].unit);
            return 0;
        }
    }
    puts("  <UnitDefinitions>");
    for (size_t u = 0; u < sizeof UNITS / sizeof UNITS[0]; u++) {
        if (!unit_used(UNITS[u].name))
            continue;
        printf("    <Unit");
        attr("name", UNITS[u].name);
        if (UNITS[u].base)
            printf(">\n      <BaseUnit %s/>\n    </Unit>\n", UNITS[u].base);
        else
            puts("/>");
    }
    puts("  </UnitDefinitions>");
    return 1;
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

/* The attributes of a variable's value: unit (reals only), range and start. */
static void attr_value(const fmu_variable *v, int fmi_version)
{
    const tribo_param_info *p = fmu_variable_param(v);
    if (v->type == FMU_TYPE_REAL)
        attr("unit", v->unit);
    if (p) { /* a parameter or an input */
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
    puts("  <ModelStructure>");
    for (int section = 0; section < 2; section++) {
        puts(section ? "    <InitialUnknowns>" : "    <Outputs>");
        index = 0;
        for (size_t i = 0; i < n; i++) {
            if (!fmu_variable_in_version(&v[i], 2))
                continue;
            index++;
            if (v[i].causality == FMU_CAUSALITY_OUTPUT)
                printf("      <Unknown index=\"%zu\"/>\n", index);
        }
        puts(section ? "    </InitialUnknowns>" : "    </Outputs>");
    }
    puts("  </ModelStructure>");
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
    puts("  <ModelStructure>");
    for (int section = 0; section < 2; section++)
        for (size_t i = 0; i < n; i++)
            if (fmu_variable_in_version(&v[i], 3) && v[i].causality == FMU_CAUSALITY_OUTPUT)
                printf("    <%s valueReference=\"%u\"/>\n", section ? "InitialUnknown" : "Output",
                       v[i].vr);
    puts("  </ModelStructure>");
}

/* ---- the description ------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    const int version = argc == 3 ? atoi(argv[1]) : 0;
    if (version != 2 && version != 3) {
        fputs("usage: tribo_model_description <2|3> <tool version>\n", stderr);
        return 2;
    }
    const char *tool_version = argv[2];
    const tribo_param_info *rtol = tribo_param_find("rtol");

    puts("<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    /* (no double hyphen may stand in an XML comment) */
    printf("<!-- The FMI %d.0 description of tribo_fmi%d.fmu, generated from src/quantities.def by\n"
           "     fmu/tools/model_description.c. Do not edit: change the table, then build the\n"
           "     target update_model_descriptions and review the diff. -->\n",
           version, version);
    puts("<fmiModelDescription");
    printf("  fmiVersion=\"%d.0\"\n  modelName=\"tribo\"\n", version);
    printf("  %s=\"" TOKEN_PLACEHOLDER "\"\n", version == 2 ? "guid" : "instantiationToken");
    puts("  description=\"A 2D elliptical particle tribocharging on a tilted plate (after Ireland 2012)\"");
    printf("  generationTool=\"tribo %s\"\n", tool_version);
    printf("  variableNamingConvention=\"flat\"%s>\n", version == 2 ? "\n  numberOfEventIndicators=\"0\"" : "");
    printf("  <CoSimulation\n    modelIdentifier=\"tribo_fmi%d\"\n"
           "    canHandleVariableCommunicationStepSize=\"true\"\n",
           version);
    if (version == 2)
        puts("    canNotUseMemoryManagementFunctions=\"true\"\n"
             "    canGetAndSetFMUstate=\"true\"\n    canSerializeFMUstate=\"true\"/>");
    else /* a step cut short by the work limit (work_limit) returns early where allowed */
        puts("    canGetAndSetFMUState=\"true\"\n    canSerializeFMUState=\"true\"\n"
             "    mightReturnEarlyFromDoStep=\"true\"/>");
    if (!write_units())
        return 1;
    puts("  <LogCategories>");
    for (int c = 0; c < FMU_LOG_CATEGORY_COUNT; c++) {
        printf("    <Category");
        attr("name", fmu_log_category_name((fmu_log_category)c));
        attr("description", fmu_log_category_description((fmu_log_category)c));
        puts("/>");
    }
    puts("  </LogCategories>");
    /* the default tolerance is the default of rtol, the parameter that sets it */
    printf("  <DefaultExperiment startTime=\"0\" stopTime=\"1000\"");
    attr_number("tolerance", rtol->start);
    puts(" stepSize=\"0.1\"/>");
    if (version == 2)
        write_fmi2_variables();
    else
        write_fmi3_variables();
    puts("</fmiModelDescription>");
    return ferror(stdout) ? 1 : 0;
}
