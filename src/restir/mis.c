/* restir/mis.c: the names of the resampling MIS modes (restir/mis.h; the weights are inline there).
 * Must never depend on a ray tracer, files, the renderer or anything else in src/. */
#include <string.h>

#include "restir/mis.h"

int restir_mis_parse(const char *name, enum restir_mis *out)
{
    if (!name || !out)
        return -1;
    if (strcmp(name, "1/M") == 0 || strcmp(name, "uniform") == 0) {
        *out = RESTIR_MIS_UNIFORM;
        return 0;
    }
    if (strcmp(name, "balance") == 0) {
        *out = RESTIR_MIS_BALANCE;
        return 0;
    }
    if (strcmp(name, "pairwise") == 0) {
        *out = RESTIR_MIS_PAIRWISE;
        return 0;
    }
    return -1;
}

const char *restir_mis_name(enum restir_mis mode)
{
    switch (mode) {
    case RESTIR_MIS_UNIFORM:
        return "1/M";
    case RESTIR_MIS_BALANCE:
        return "balance";
    case RESTIR_MIS_PAIRWISE:
        return "pairwise";
    case RESTIR_MIS_PAIRWISE_TILED:
        return "pairwise-tiled"; /* not parsed: only callers that know their domains tile use it */
    }
    return "unknown";
}
