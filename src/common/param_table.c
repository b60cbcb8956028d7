/* param_table.c: what is done with a table of parameters (param_table.h), whichever table
   it is: the chute's scene (quantities.def, scene.c), the SI front end's (si_quantities.def,
   si.c) or the separator's (separator_quantities.def, separator.c). */
#include "param_table.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void tribo_table_defaults(tribo_param_table_of t, void *scene, size_t scene_size)
{
    if (!scene)
        return;
    memset(scene, 0, scene_size);
    for (size_t i = 0; i < t.n; i++)
        tribo_param_write(scene, &t.rows[i], t.rows[i].start);
}

const tribo_param_info *tribo_table_find(tribo_param_table_of t, const char *name)
{
    for (size_t i = 0; name && i < t.n; i++)
        if (strcmp(t.rows[i].name, name) == 0)
            return &t.rows[i];
    return NULL;
}

double tribo_param_read(const void *scene, const tribo_param_info *p)
{
    if (!scene || !p)
        return NAN;
    const char *base = (const char *)scene + p->offset;
    if (p->type != TRIBO_TYPE_REAL) {
        int v;
        memcpy(&v, base, sizeof v);
        return (double)v;
    }
    double v;
    memcpy(&v, base, sizeof v);
    return v;
}

void tribo_param_write(void *scene, const tribo_param_info *p, double value)
{
    if (!scene || !p)
        return;
    char *base = (char *)scene + p->offset;
    if (p->type != TRIBO_TYPE_REAL) {
        /* saturated: a value an int cannot hold is invalid anyway, and reads back otherwise */
        const int v = value >= (double)INT_MAX ? INT_MAX : value > (double)INT_MIN ? (int)value : INT_MIN;
        memcpy(base, &v, sizeof v);
    } else {
        memcpy(base, &value, sizeof value);
    }
}

void tribo_param_range_text(const tribo_param_info *p, char *buf, size_t n)
{
    if (p->type != TRIBO_TYPE_REAL) {
        snprintf(buf, n, "an integer with %.0f <= %s <= %.0f", p->min, p->name, p->max);
        return;
    }
    const int has_lo = isfinite(p->min), has_hi = isfinite(p->max);
    if (has_lo && p->max == INFINITY && p->max_inclusive)
        snprintf(buf, n, "%g %s %s <= INF (INF: none)", p->min, p->min_inclusive ? "<=" : "<",
                 p->name);
    else if (has_lo && has_hi)
        snprintf(buf, n, "%g %s %s %s %g", p->min, p->min_inclusive ? "<=" : "<", p->name,
                 p->max_inclusive ? "<=" : "<", p->max);
    else if (has_lo)
        snprintf(buf, n, "%s %s %g (finite)", p->name, p->min_inclusive ? ">=" : ">", p->min);
    else if (has_hi)
        snprintf(buf, n, "%s %s %g (finite)", p->name, p->max_inclusive ? "<=" : "<", p->max);
    else
        snprintf(buf, n, "any finite number");
}

tribo_status tribo_param_check(const tribo_param_info *p, double v, char *msg, size_t msg_size)
{
    /* a closed infinite bound admits the infinity itself (quantities.def) */
    int ok = isfinite(v) || (v == INFINITY && p->max == INFINITY && p->max_inclusive);
    if (ok && p->type != TRIBO_TYPE_REAL)
        ok = v == floor(v);
    if (ok)
        ok = p->min_inclusive ? v >= p->min : v > p->min;
    if (ok)
        ok = p->max_inclusive ? v <= p->max : v < p->max;
    if (ok)
        return TRIBO_OK;
    if (msg && msg_size) {
        char range[128];
        tribo_param_range_text(p, range, sizeof range);
        snprintf(msg, msg_size, "%s = %.17g is invalid: the valid range is %s", p->name, v,
                 range);
    }
    return TRIBO_ERR_INVALID_ARGUMENT;
}

tribo_status tribo_params_check(const tribo_param_info *rows, int n, const double *values, char *msg,
                                size_t msg_size)
{
    for (int i = 0; i < n; i++)
        if (tribo_param_check(&rows[i], values[i], msg, msg_size) != TRIBO_OK)
            return TRIBO_ERR_INVALID_ARGUMENT;
    return TRIBO_OK;
}

const char *tribo_table_retired(tribo_param_table_of t, const char *name)
{
    for (const tribo_param_retired *r = t.retired; r && r->name && name; r++)
        if (strcmp(r->name, name) == 0)
            return r->instead;
    return NULL;
}

tribo_status tribo_table_set(tribo_param_table_of t, void *scene, const char *name, double value,
                             char *msg, size_t msg_size)
{
    if (!scene) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "scene is NULL");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    const tribo_param_info *p = tribo_table_find(t, name);
    if (!p) {
        const char *instead = tribo_table_retired(t, name);
        if (msg && msg_size && instead)
            snprintf(msg, msg_size, "%s", instead);
        else if (msg && msg_size)
            snprintf(msg, msg_size, "unknown parameter '%s'", name ? name : "(null)");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    const tribo_status st = tribo_param_check(p, value, msg, msg_size);
    if (st == TRIBO_OK)
        tribo_param_write(scene, p, value);
    return st;
}

tribo_status tribo_table_apply(tribo_param_table_of t, void *scene, const char *settings, char *msg,
                               size_t msg_size)
{
    const char *p = settings ? settings : "";
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            return TRIBO_OK;
        const char *end = p;
        while (*end && !isspace((unsigned char)*end))
            end++;
        char item[128], *value_end;
        const char *eq = memchr(p, '=', (size_t)(end - p));
        const size_t len = (size_t)(end - p);
        if (!eq || len >= sizeof item) {
            if (msg && msg_size)
                snprintf(msg, msg_size, "expected name=value, got '%.*s'", (int)len, p);
            return TRIBO_ERR_INVALID_ARGUMENT;
        }
        memcpy(item, p, len);
        item[len] = '\0';
        item[eq - p] = '\0';
        const char *text = item + (eq - p) + 1;
        const double value = strtod(text, &value_end);
        if (value_end == text || *value_end) {
            if (msg && msg_size)
                snprintf(msg, msg_size, "%s: '%s' is not a number", item, text);
            return TRIBO_ERR_INVALID_ARGUMENT;
        }
        const tribo_status st = tribo_table_set(t, scene, item, value, msg, msg_size);
        if (st != TRIBO_OK)
            return st;
        p = end;
    }
}

tribo_status tribo_table_validate(tribo_param_table_of t, const void *scene, char *msg, size_t msg_size)
{
    if (!scene) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "scene is NULL");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    for (size_t i = 0; i < t.n; i++) {
        tribo_status st = tribo_param_check(&t.rows[i], tribo_param_read(scene, &t.rows[i]), msg,
                                            msg_size);
        if (st != TRIBO_OK)
            return st;
    }
    return TRIBO_OK;
}
