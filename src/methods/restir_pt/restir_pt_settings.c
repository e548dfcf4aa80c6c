/* restir_pt_settings.c: ReSTIR PT's settings block (restir_pt_settings.h). */
#include "methods/restir_pt/restir_pt_settings.h"

#include <stddef.h>

#define P(field) offsetof(struct restir_pt_settings, field)
static const struct param_def restir_pt_rows[] = {
    {"pt.candidates", P_INT, P(candidates), 1, 64, "1", NULL, "initial paths resampled per pixel", NULL},
};
#undef P

struct param_block restir_pt_block = PARAM_METHOD_BLOCK("restir-pt", restir_pt_rows, struct restir_pt_settings, NULL);

#define B(field) offsetof(struct restir_pt_boiling_settings, field)
static const struct param_def restir_pt_boiling_rows[] = {
    {"pt.boiling_filter", P_BOOL, B(filter), 0, 1, "off", "on",
     "BIASED: after temporal reuse, empty each path reservoir whose target x W (RTXDI's weight for paths) exceeds "
     "its 8 x 8 pixel group's mean over the non-empty ones 10 / pt.boiling_strength - 9 times (RTXDI's boiling "
     "filter): fewer blotches, less energy",
     NULL},
    {"pt.boiling_strength", P_FLOAT, B(strength), 1e-6, 1, "0.2", NULL,
     "pt.boiling_filter: strength s in (0, 1]; 0.2 drops reservoirs above 41 times the group's mean", NULL},
};
#undef B

struct param_block restir_pt_boiling_block =
    PARAM_METHOD_BLOCK("restir-pt boiling", restir_pt_boiling_rows, struct restir_pt_boiling_settings, NULL);
