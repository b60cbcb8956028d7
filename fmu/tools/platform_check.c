/*
 * platform_check: runs an FMU's binary through its FMI entry points, for checking a
 * binary built for another platform (the Windows DLL under Wine) against the native one.
 *
 *   tribo_platform_check <binary> <2|3> <token> <stop time> <step> <variable>... [-- name=value...]
 *
 * Loads the binary (LoadLibrary / dlopen), instantiates a co-simulation instance with the
 * modelDescription's token, sets the parameters and inputs given after "--" (<kind><vr>=value) before initialization,
 * steps from 0 to the stop time and prints, at every communication point, one line: the
 * time and the variables, each named by its kind and value reference (kinds: r: Real /
 * Float64, i: Integer / Int32, e: Enumeration (FMI 3.0: Int64), b: Boolean), with 17
 * significant digits. Errors go to stderr with
 * the FMU's log messages; the exit status is 1.
 */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#define LOAD(path) ((void *)LoadLibraryA(path))
#define SYMBOL(lib, name) ((void *)GetProcAddress((HMODULE)(lib), name))
#else
#include <dlfcn.h>
#define LOAD(path) dlopen(path, RTLD_NOW | RTLD_LOCAL)
#define SYMBOL(lib, name) dlsym(lib, name)
#endif

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"

enum { MAX_VARIABLES = 256 };

typedef struct variable {
    char kind; /* 'r', 'i', 'e' or 'b' */
    unsigned vr;
    double value; /* for parameters */
} variable;

static void *library;
static int failed;

static void *symbol(const char *name)
{
    void *f = SYMBOL(library, name);
    if (!f) {
        fprintf(stderr, "platform_check: %s is not exported\n", name);
        exit(1);
    }
    return f;
}

static int parse_variable(const char *text, variable *v, int with_value)
{
    char *end;
    v->kind = text[0];
    if (!v->kind || !strchr("rieb", v->kind))
        return 0;
    v->vr = (unsigned)strtoul(text + 1, &end, 10);
    if (!with_value)
        return end != text + 1 && *end == '\0';
    if (*end != '=')
        return 0;
    v->value = strtod(end + 1, &end);
    return *end == '\0';
}

/* ---- FMI 2.0 ------------------------------------------------------------------------ */

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                 fmi2String category, fmi2String message, ...)
{
    (void)env, (void)name;
    if (status >= fmi2Warning)
        fprintf(stderr, "[%s] %s\n", category, message);
}

#define CHECK2(call)                                                                       \
    do {                                                                                   \
        if ((call) > fmi2Warning) {                                                        \
            fprintf(stderr, "platform_check: %s failed\n", #call);                         \
            return 1;                                                                      \
        }                                                                                  \
    } while (0)

static int run2(const char *token, double stop, double step, const variable *out, int n_out,
                const variable *par, int n_par)
{
    fmi2InstantiateTYPE *instantiate = symbol("fmi2Instantiate");
    fmi2SetupExperimentTYPE *setup = symbol("fmi2SetupExperiment");
    fmi2EnterInitializationModeTYPE *enter = symbol("fmi2EnterInitializationMode");
    fmi2ExitInitializationModeTYPE *exit_init = symbol("fmi2ExitInitializationMode");
    fmi2DoStepTYPE *do_step = symbol("fmi2DoStep");
    fmi2GetRealTYPE *get_real = symbol("fmi2GetReal");
    fmi2GetIntegerTYPE *get_integer = symbol("fmi2GetInteger");
    fmi2GetBooleanTYPE *get_boolean = symbol("fmi2GetBoolean");
    fmi2SetRealTYPE *set_real = symbol("fmi2SetReal");
    fmi2SetIntegerTYPE *set_integer = symbol("fmi2SetInteger");
    fmi2SetBooleanTYPE *set_boolean = symbol("fmi2SetBoolean");
    fmi2FreeInstanceTYPE *free_instance = symbol("fmi2FreeInstance");

    const fmi2CallbackFunctions callbacks = {logger2, calloc, free, NULL, NULL};
    fmi2Component c = instantiate("check", fmi2CoSimulation, token, "", &callbacks, fmi2False,
                                  fmi2False);
    if (!c) {
        fprintf(stderr, "platform_check: fmi2Instantiate failed\n");
        return 1;
    }
    for (int i = 0; i < n_par; i++) {
        if (par[i].kind == 'r')
            CHECK2(set_real(c, &par[i].vr, 1, &par[i].value));
        else if (par[i].kind == 'b') {
            const fmi2Boolean v = par[i].value != 0.0;
            CHECK2(set_boolean(c, &par[i].vr, 1, &v));
        } else {
            const fmi2Integer v = (fmi2Integer)par[i].value;
            CHECK2(set_integer(c, &par[i].vr, 1, &v));
        }
    }
    CHECK2(setup(c, fmi2False, 0.0, 0.0, fmi2True, stop));
    CHECK2(enter(c));
    CHECK2(exit_init(c));
    const long n_steps = (long)(stop / step + 0.5);
    for (long k = 0; k <= n_steps; k++) {
        const double t = k * step;
        if (k > 0)
            CHECK2(do_step(c, (k - 1) * step, t - (k - 1) * step, fmi2True));
        printf("%.17g", t);
        for (int i = 0; i < n_out; i++) {
            fmi2Real r = 0;
            fmi2Integer n = 0;
            fmi2Boolean flag = 0;
            if (out[i].kind == 'r') {
                CHECK2(get_real(c, &out[i].vr, 1, &r));
            } else if (out[i].kind == 'b') {
                CHECK2(get_boolean(c, &out[i].vr, 1, &flag));
                r = flag != 0;
            } else {
                CHECK2(get_integer(c, &out[i].vr, 1, &n));
                r = n;
            }
            printf(" %.17g", r);
        }
        putchar('\n');
    }
    free_instance(c);
    return 0;
}

/* ---- FMI 3.0 ------------------------------------------------------------------------ */

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                 fmi3String message)
{
    (void)env;
    if (status >= fmi3Warning)
        fprintf(stderr, "[%s] %s\n", category, message);
}

#define CHECK3(call)                                                                       \
    do {                                                                                   \
        if ((call) > fmi3Warning) {                                                        \
            fprintf(stderr, "platform_check: %s failed\n", #call);                         \
            return 1;                                                                      \
        }                                                                                  \
    } while (0)

static int run3(const char *token, double stop, double step, const variable *out, int n_out,
                const variable *par, int n_par)
{
    fmi3InstantiateCoSimulationTYPE *instantiate = symbol("fmi3InstantiateCoSimulation");
    fmi3EnterInitializationModeTYPE *enter = symbol("fmi3EnterInitializationMode");
    fmi3ExitInitializationModeTYPE *exit_init = symbol("fmi3ExitInitializationMode");
    fmi3DoStepTYPE *do_step = symbol("fmi3DoStep");
    fmi3GetFloat64TYPE *get_float64 = symbol("fmi3GetFloat64");
    fmi3GetInt32TYPE *get_int32 = symbol("fmi3GetInt32");
    fmi3GetInt64TYPE *get_int64 = symbol("fmi3GetInt64");
    fmi3GetBooleanTYPE *get_boolean = symbol("fmi3GetBoolean");
    fmi3SetFloat64TYPE *set_float64 = symbol("fmi3SetFloat64");
    fmi3SetInt32TYPE *set_int32 = symbol("fmi3SetInt32");
    fmi3SetInt64TYPE *set_int64 = symbol("fmi3SetInt64");
    fmi3SetBooleanTYPE *set_boolean = symbol("fmi3SetBoolean");
    fmi3FreeInstanceTYPE *free_instance = symbol("fmi3FreeInstance");

    fmi3Instance c = instantiate("check", token, "", fmi3False, fmi3False, fmi3False, fmi3False,
                                 NULL, 0, NULL, logger3, NULL);
    if (!c) {
        fprintf(stderr, "platform_check: fmi3InstantiateCoSimulation failed\n");
        return 1;
    }
    for (int i = 0; i < n_par; i++) {
        if (par[i].kind == 'r')
            CHECK3(set_float64(c, &par[i].vr, 1, &par[i].value, 1));
        else if (par[i].kind == 'i') {
            const fmi3Int32 v = (fmi3Int32)par[i].value;
            CHECK3(set_int32(c, &par[i].vr, 1, &v, 1));
        } else if (par[i].kind == 'b') {
            const fmi3Boolean v = par[i].value != 0.0;
            CHECK3(set_boolean(c, &par[i].vr, 1, &v, 1));
        } else {
            const fmi3Int64 v = (fmi3Int64)par[i].value;
            CHECK3(set_int64(c, &par[i].vr, 1, &v, 1));
        }
    }
    CHECK3(enter(c, fmi3False, 0.0, 0.0, fmi3True, stop));
    CHECK3(exit_init(c));
    const long n_steps = (long)(stop / step + 0.5);
    for (long k = 0; k <= n_steps; k++) {
        const double t = k * step;
        if (k > 0) {
            fmi3Boolean event, terminate, early;
            fmi3Float64 reached;
            CHECK3(do_step(c, (k - 1) * step, t - (k - 1) * step, fmi3True, &event, &terminate,
                           &early, &reached));
        }
        printf("%.17g", t);
        for (int i = 0; i < n_out; i++) {
            fmi3Float64 r = 0;
            fmi3Int32 n = 0;
            fmi3Int64 e = 0;
            fmi3Boolean flag = false;
            if (out[i].kind == 'r') {
                CHECK3(get_float64(c, &out[i].vr, 1, &r, 1));
            } else if (out[i].kind == 'b') {
                CHECK3(get_boolean(c, &out[i].vr, 1, &flag, 1));
                r = flag;
            } else if (out[i].kind == 'i') {
                CHECK3(get_int32(c, &out[i].vr, 1, &n, 1));
                r = n;
            } else {
                CHECK3(get_int64(c, &out[i].vr, 1, &e, 1));
                r = (double)e;
            }
            printf(" %.17g", r);
        }
        putchar('\n');
    }
    free_instance(c);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 7) {
        fputs("usage: tribo_platform_check <binary> <2|3> <token> <stop time> <step> "
              "<r|i|e|b><vr>... [-- <r|i|e><vr>=<value>...]\n",
              stderr);
        return 2;
    }
    const int version = atoi(argv[2]);
    const double stop = strtod(argv[4], NULL), step = strtod(argv[5], NULL);
    variable out[MAX_VARIABLES], par[MAX_VARIABLES];
    int n_out = 0, n_par = 0, i = 6;
    for (; i < argc && strcmp(argv[i], "--") != 0 && n_out < MAX_VARIABLES; i++)
        if (!parse_variable(argv[i], &out[n_out++], 0)) {
            fprintf(stderr, "platform_check: bad variable '%s'\n", argv[i]);
            return 2;
        }
    for (i++; i < argc && n_par < MAX_VARIABLES; i++)
        if (!parse_variable(argv[i], &par[n_par++], 1)) {
            fprintf(stderr, "platform_check: bad setting '%s'\n", argv[i]);
            return 2;
        }
    if ((version != 2 && version != 3) || !(stop > 0.0) || !(step > 0.0)) {
        fputs("platform_check: bad FMI version, stop time or step\n", stderr);
        return 2;
    }
    library = LOAD(argv[1]);
    if (!library) {
        fprintf(stderr, "platform_check: cannot load %s\n", argv[1]);
        return 1;
    }
    failed = version == 2 ? run2(argv[3], stop, step, out, n_out, par, n_par)
                          : run3(argv[3], stop, step, out, n_out, par, n_par);
    return failed;
}
