/* di_settings.c: ReSTIR DI's settings blocks (di_settings.h). */
#include "methods/restir_di/di_settings.h"

#include <stddef.h>
#include <stdio.h>

#include "core/check.h"

#define D(field) offsetof(struct di_settings, field)

static const char *const visibility_mis_names[] = {"rays", "none", NULL};

static const struct param_def di_rows[] = {
    {"di.light_candidates", P_INT, D(light_candidates), 0, 4096, "32", NULL, "initial RIS: light-sampled candidates",
     NULL},
    {"di.bsdf_candidates", P_INT, D(bsdf_candidates), 0, 64, "1", NULL, "initial RIS: BSDF-sampled candidates", NULL},
    {"di.visibility_reuse", P_BOOL, D(visibility_reuse), 0, 1, "on", NULL,
     "trace a shadow ray for the initial sample and drop it when occluded (Bitterli et al. "
     "2020 Alg. 5), so reuse carries visible samples (with di.visibility_mis=rays shading then needs no "
     "shadow ray)",
     NULL},
};
static const struct param_def di_reuse_rows[] = {
    {"di.visibility_mis", P_NAMES, offsetof(struct di_reuse_settings, visibility_mis), 0, 0, "rays", "none",
     "with di.visibility_reuse: targets compared across domains include visibility, traced per "
     "merge (rays, unbiased), or not (none: BIASED, darkens where neighbors cannot see the light; no rays)",
     visibility_mis_names},
};

_Static_assert(sizeof(enum di_visibility_mis) == sizeof(int), "enum size");

static int di_validate(const struct render_params *p, const void *block, char *msg)
{
    (void)p;
    const struct di_settings *d = block;
    if (d->light_candidates + d->bsdf_candidates < 1) {
        snprintf(msg, RESTIR_MSG_LEN, "di.light_candidates + di.bsdf_candidates must be at least 1");
        return -1;
    }
    return 0;
}

#undef D

struct param_block di_block = PARAM_METHOD_BLOCK("di", di_rows, struct di_settings, di_validate);
struct param_block di_reuse_block = PARAM_METHOD_BLOCK("di reuse", di_reuse_rows, struct di_reuse_settings, NULL);
