/* passes.c: the pass timers' ids and names (passes.h), from today's ids and the names the registered
 * methods list. Must never depend on the passes or the ray tracer. */
#include "methods/passes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

#include "methods/method.h"

const char *const pass_toolkit_names[PASS_COUNT] = {
    "gbuffer",      "initial",     "temporal",     "select",       "spatial",    "cells",    "cell_search",
    "spmis_canonical", "spmis_reuse", "shade",      "pt",           "gpt",        "grad_initial",
    "grad_temporal", "grad_select", "grad_spatial", "grad_shade",   "recon_l2",   "recon_l1", "denoise",
};

static const char *names[PASS_MAX];
static int count;
static once_flag built = ONCE_FLAG_INIT;

static int find_in(const char *name)
{
    for (int k = 0; name && k < count; k++)
        if (!strcmp(names[k], name))
            return k;
    return -1;
}

/* Today's ids, then each name a method lists that is none of them, in registry order. The registry's
 * check (settings_registry_check) has refused more than PASS_MAX before any frame is timed. */
static void build(void)
{
    for (count = 0; count < PASS_COUNT; count++)
        names[count] = pass_toolkit_names[count];
    for (int m = 0; m < method_count(); m++)
        for (const char *const *p = method_at(m)->passes; p && *p; p++)
            if (find_in(*p) < 0) {
                if (count == PASS_MAX) {
                    fprintf(stderr, "restir: the methods time more than PASS_MAX (%d) passes\n", PASS_MAX);
                    abort();
                }
                names[count++] = *p;
            }
}

int pass_count(void)
{
    call_once(&built, build);
    return count;
}

const char *pass_name(int id) { return id >= 0 && id < pass_count() ? names[id] : NULL; }

int pass_find(const char *name)
{
    call_once(&built, build);
    return find_in(name);
}
