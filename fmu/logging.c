/* logging.c: log categories and messages to the importer's logger. */
#include "instance_private.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Long enough for any message this FMU writes (names, values and a range); longer ones
   are cut, never overrun. */
enum { MESSAGE_SIZE = 1024 };

static const struct {
    const char *name;
    const char *description;
} CATEGORIES[FMU_LOG_CATEGORY_COUNT] = {
    [FMU_LOG_ERROR] = {"logStatusError",
                       "errors: refused calls and values (naming the variable, the value and "
                       "its valid range) and failures of the core; enabled by default"},
    [FMU_LOG_WARNING] = {"logStatusWarning", "warnings of the core"},
    [FMU_LOG_CALLS] = {"logFmiCalls", "every FMI call that changes the instance, with its arguments"},
    [FMU_LOG_CORE] = {"logCore", "informational messages of the core"},
};

const char *fmu_log_category_name(fmu_log_category c)
{
    return (unsigned)c < FMU_LOG_CATEGORY_COUNT ? CATEGORIES[c].name : NULL;
}

const char *fmu_log_category_description(fmu_log_category c)
{
    return (unsigned)c < FMU_LOG_CATEGORY_COUNT ? CATEGORIES[c].description : NULL;
}

int fmu_log_enabled(const fmu_instance *inst, fmu_log_category c)
{
    return inst && inst->logger.sink && inst->log_enabled[c];
}

static void vlog(fmu_instance *inst, fmu_status status, fmu_log_category c, const char *fmt,
                 va_list ap)
{
    if (!fmu_log_enabled(inst, c))
        return;
    char message[MESSAGE_SIZE];
    vsnprintf(message, sizeof message, fmt, ap);
    inst->logger.sink(&inst->logger, inst->name, status, CATEGORIES[c].name, message);
}

void fmu_log(fmu_instance *inst, fmu_status status, fmu_log_category c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vlog(inst, status, c, fmt, ap);
    va_end(ap);
}

fmu_status fmu_error(fmu_instance *inst, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vlog(inst, FMU_ERROR, FMU_LOG_ERROR, fmt, ap);
    va_end(ap);
    return FMU_ERROR;
}

void fmu_core_logger(void *user, int level, const char *message)
{
    fmu_instance *inst = user;
    if (level >= 1)
        fmu_log(inst, FMU_WARNING, FMU_LOG_WARNING, "core: %s", message);
    else
        fmu_log(inst, FMU_OK, FMU_LOG_CORE, "core: %s", message);
}

fmu_status fmu_set_debug_logging(fmu_instance *inst, const char *fn, int on, size_t n,
                                 const char *const categories[])
{
    if (!inst)
        return FMU_ERROR;
    int wanted[FMU_LOG_CATEGORY_COUNT] = {0};
    if (n > 0 && !categories)
        return fmu_error(inst, "%s: categories is NULL but nCategories = %zu", fn, n);
    for (size_t i = 0; i < n; i++) {
        int found = 0;
        for (int c = 0; c < FMU_LOG_CATEGORY_COUNT && categories[i]; c++)
            if (strcmp(categories[i], CATEGORIES[c].name) == 0)
                found = wanted[c] = 1;
        if (!found)
            return fmu_error(inst,
                             "%s: unknown log category '%s'; the categories are logStatusError, "
                             "logStatusWarning, logFmiCalls and logCore",
                             fn, categories[i] ? categories[i] : "(null)");
    }
    for (int c = 0; c < FMU_LOG_CATEGORY_COUNT; c++)
        if (n == 0 || wanted[c])
            inst->log_enabled[c] = on != 0;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(loggingOn = %d, nCategories = %zu)", fn, on != 0, n);
    return FMU_OK;
}
