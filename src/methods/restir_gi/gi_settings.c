/* gi_settings.c: ReSTIR GI's settings block (gi_settings.h). */
#include "methods/restir_gi/gi_settings.h"

#include <stddef.h>

static const char *const gi_radiance_names[] = {"reevaluate", "stored", NULL}; /* enum gi_radiance_mode */
_Static_assert(sizeof(enum gi_radiance_mode) == sizeof(int), "enum size");

#define I(field) offsetof(struct gi_settings, field)
static const struct param_def gi_rows[] = {
    {"gi.radiance", P_NAMES, I(radiance), 0, 0, "reevaluate", "stored",
     "the outgoing radiance of a reused sample point toward the reusing shading point: reevaluate "
     "(the sample point's path estimate traced again from its own random numbers) or stored (the radiance it "
     "sent toward the pixel that traced it, as Ouyang et al. 2021; BIASED where the sample point is glossy)",
     gi_radiance_names},
    {"gi.boiling_filter", P_BOOL, I(boiling_filter), 0, 1, "off", "on",
     "BIASED: after temporal reuse, empty each reservoir whose target x W (its estimate of the pixel's indirect "
     "light) exceeds its 8 x 8 pixel group's mean over the non-empty ones 10 / gi.boiling_strength - 9 times "
     "(RTXDI's boiling filter): fewer blotches, less energy",
     NULL},
    {"gi.boiling_strength", P_FLOAT, I(boiling_strength), 1e-6, 1, "0.2", NULL,
     "gi.boiling_filter: strength s in (0, 1]; 0.2 drops reservoirs above 41 times the group's mean", NULL},
};
#undef I

struct param_block gi_block = PARAM_METHOD_BLOCK("gi", gi_rows, struct gi_settings, NULL);
