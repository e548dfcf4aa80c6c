/* restir_pt_settings.c: ReSTIR PT's settings block (restir_pt_settings.h). */
#include "methods/restir_pt/restir_pt_settings.h"

#include <stddef.h>

#define P(field) offsetof(struct restir_pt_settings, field)
static const struct param_def restir_pt_rows[] = {
    {"pt.candidates", P_INT, P(candidates), 1, 64, "1", NULL, "initial paths resampled per pixel", NULL},
};
#undef P

struct param_block restir_pt_block = PARAM_METHOD_BLOCK("restir-pt", restir_pt_rows, struct restir_pt_settings, NULL);
