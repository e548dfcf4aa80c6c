/* settings_block.c: parsing, spelling and range checks of one setting row, and where a block's values
 * live in struct render_params (settings_block.h). */
#include "render/settings_block.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "render/shift_kind.h"
#include "restir/mis.h"

_Noreturn void param_block_unplaced(const struct param_block *b)
{
    fprintf(stderr, "restir: settings block '%s' was never placed in the parameters (not registered)\n", b->name);
    abort();
}

/* Index of val among the NULL-terminated names, or -1. */
static int name_index(const char *const *names, const char *val)
{
    for (int k = 0; names[k]; k++)
        if (!strcmp(val, names[k]))
            return k;
    return -1;
}

/* "a, b, c" of the NULL-terminated names into list (n bytes). */
static void names_list(const char *const *names, char *list, size_t n)
{
    list[0] = '\0';
    for (int j = 0; names[j]; j++)
        snprintf(list + strlen(list), n - strlen(list), "%s%s", j ? ", " : "", names[j]);
}

int param_parse(const struct param_block *b, const struct param_def *d, const char *val, void *block, char *msg)
{
    char *base = (char *)block + d->offset;
    if (d->type == P_MIS) {
        if (restir_mis_parse(val, (enum restir_mis *)(void *)base) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown MIS '%s' (pairwise, balance, 1/M)", d->key, val);
            return -1;
        }
        return 0;
    }
    if (d->type == P_SHIFT) {
        if (shift_kind_parse(val, (enum shift_kind *)(void *)base) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown shift '%s' (hybrid, reconnection, replay)", d->key, val);
            return -1;
        }
        return 0;
    }
    if (d->type == P_NAMES || d->type == P_PRESET) {
        int k = name_index(d->names, val);
        if (k < 0) {
            char list[128];
            names_list(d->names, list, sizeof list);
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown %s '%s' (%s)", d->key,
                     d->type == P_PRESET ? "preset" : "value", val, list);
            return -1;
        }
        if (d->type == P_PRESET)
            b->preset(block, k);
        else
            *(int *)(void *)base = k; /* P_NAMES fields are int-sized enums with values 0, 1, ... */
        return 0;
    }
    if (d->type == P_COUNT && (!strcmp(val, "M") || !strcmp(val, "all"))) {
        *(int *)(void *)base = 0;
        return 0;
    }
    if (d->type == P_BOOL) {
        int v;
        if (!strcmp(val, "on") || !strcmp(val, "1") || !strcmp(val, "true"))
            v = 1;
        else if (!strcmp(val, "off") || !strcmp(val, "0") || !strcmp(val, "false"))
            v = 0;
        else {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: expected on or off, got '%s'", d->key, val);
            return -1;
        }
        *(int *)(void *)base = v;
        return 0;
    }
    errno = 0;
    char *end = NULL;
    double v = strtod(val, &end);
    if (end == val || *end != '\0' || errno != 0 || !isfinite(v)) {
        snprintf(msg, RESTIR_MSG_LEN, "--set %s: '%s' is not a number", d->key, val);
        return -1;
    }
    if (v < d->lo || v > d->hi || (d->type != P_FLOAT && v != floor(v))) {
        snprintf(msg, RESTIR_MSG_LEN, "--set %s: %s is out of range (%s in [%g, %g]%s)", d->key, val,
                 d->type == P_FLOAT ? "number" : "integer", d->lo, d->hi, d->type == P_COUNT ? " or M" : "");
        return -1;
    }
    if (d->type == P_INT || d->type == P_COUNT)
        *(int *)(void *)base = (int)v;
    else
        *(float *)(void *)base = (float)v;
    return 0;
}

/* The shortest %g spelling of v (at least 6 digits) that --set parses back to v exactly, so that
 * settings written to summary.json reproduce the run bit for bit. */
static void format_float(float v, char *val, size_t n)
{
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(val, n, "%.*g", digits, v);
        if ((float)strtod(val, NULL) == v)
            return;
    }
}

void param_format(const struct param_def *d, const void *block, char *val, size_t n)
{
    const char *base = (const char *)block + d->offset;
    switch (d->type) {
    case P_INT: snprintf(val, n, "%d", *(const int *)(const void *)base); break;
    case P_FLOAT: format_float(*(const float *)(const void *)base, val, n); break;
    case P_BOOL: snprintf(val, n, "%s", *(const int *)(const void *)base ? "on" : "off"); break;
    case P_MIS: snprintf(val, n, "%s", restir_mis_name(*(const enum restir_mis *)(const void *)base)); break;
    case P_SHIFT: snprintf(val, n, "%s", shift_kind_name(*(const enum shift_kind *)(const void *)base)); break;
    case P_COUNT: {
        int v = *(const int *)(const void *)base;
        snprintf(val, n, v ? "%d" : "M", v);
        break;
    }
    case P_NAMES: snprintf(val, n, "%s", d->names[*(const int *)(const void *)base]); break;
    case P_PRESET: snprintf(val, n, "-"); break;
    }
}

int param_check(const struct param_def *d, const void *block, char *msg)
{
    const char *base = (const char *)block + d->offset;
    if (d->type == P_INT || d->type == P_COUNT || d->type == P_BOOL || d->type == P_FLOAT) {
        double v = d->type == P_FLOAT ? (double)*(const float *)(const void *)base : *(const int *)(const void *)base;
        if (!(v >= d->lo && v <= d->hi) && !(d->type == P_COUNT && v == 0.0)) {
            snprintf(msg, RESTIR_MSG_LEN, "%s = %g is out of range [%g, %g]", d->key, v, d->lo, d->hi);
            return -1;
        }
    } else if (d->type == P_NAMES) {
        int k = *(const int *)(const void *)base, count = 0;
        while (d->names[count])
            count++;
        if (k < 0 || k >= count) {
            snprintf(msg, RESTIR_MSG_LEN, "%s = %d is not one of its %d values", d->key, k, count);
            return -1;
        }
    }
    return 0;
}
