/* di_settings.c: ReSTIR DI's settings blocks (di_settings.h). */
#include "methods/restir_di/di_settings.h"

#include <stddef.h>
#include <stdio.h>

#include "core/check.h"
#include "methods/restir_di/light_cut.h"

#define D(field) offsetof(struct di_settings, field)

static const char *const visibility_mis_names[] = {"rays", "none", NULL};
static const char *const initial_names[] = {"pool", "regir", "bvh", "auto", NULL};
static const char *const regir_source_names[] = {"power", "bvh", NULL};

static const struct param_def di_rows[] = {
    {"di.light_candidates", P_INT, D(light_candidates), 0, 4096, "32", NULL, "initial RIS: light-sampled candidates",
     NULL},
    {"di.bsdf_candidates", P_INT, D(bsdf_candidates), 0, 64, "1", NULL, "initial RIS: BSDF-sampled candidates", NULL},
    {"di.visibility_reuse", P_BOOL, D(visibility_reuse), 0, 1, "on", NULL,
     "trace a shadow ray for the initial sample and drop it when occluded (Bitterli et al. "
     "2020 Alg. 5), so reuse carries visible samples (with di.visibility_mis=rays shading then needs no "
     "shadow ray)",
     NULL},
    {"di.initial", P_NAMES, D(initial), 0, 0, "auto", NULL,
     "where initial RIS draws its light candidates: auto (regir in a frame whose grid fill costs at most 0.15 "
     "of the valid pixels' own candidates, else pool; chosen by measurement, docs/BENCHMARKS.md), pool (a "
     "frame's shared draws by power), regir (a world-space grid of light reservoirs over the visible points, "
     "each cell's slots resampled toward the lights that matter there; Boksansky et al. 2021, unbiased by GRIS; "
     "needs emitters) or bvh (each pixel's own "
     "draws down the light BVH at its point, as pt chooses emitters: no grid, a tree descent per candidate)",
     initial_names},
    {"di.regir_grid", P_INT, D(regir_grid), 1, 64, "16", NULL,
     "di.initial=regir: cells along the longest side of the visible points' bounding box (cubic cells)", NULL},
    {"di.regir_slots", P_INT, D(regir_slots), 1, 1024, "128", NULL,
     "di.initial=regir: light reservoirs per occupied cell (memory: about 60 bytes each)", NULL},
    {"di.regir_candidates", P_INT, D(regir_candidates), 1, 256, "8", NULL,
     "di.initial=regir: RIS candidates per cell reservoir", NULL},
    {"di.regir_source", P_NAMES, D(regir_source), 0, 0, "power", NULL,
     "di.initial=regir: where a cell draws its candidates: power (the scene's alias table) or bvh (a cut of "
     "up to 64 nodes through the light BVH by importance at the cell's centre, each node's lights by power; "
     "a quarter of the draws by power so that every light keeps a chance)",
     regir_source_names},
};
static const struct param_def di_reuse_rows[] = {
    {"di.visibility_mis", P_NAMES, offsetof(struct di_reuse_settings, visibility_mis), 0, 0, "rays", "none",
     "with di.visibility_reuse: targets compared across domains include visibility, traced per "
     "merge (rays, unbiased), or not (none: BIASED, darkens where neighbors cannot see the light; no rays)",
     visibility_mis_names},
    {"di.boiling_filter", P_BOOL, offsetof(struct di_reuse_settings, boiling_filter), 0, 1, "off", "on",
     "BIASED: after temporal reuse, empty each reservoir whose target x W (its unshadowed estimate) exceeds its "
     "8 x 8 pixel group's mean (over the non-empty ones) 10 / di.boiling_strength - 9 times (RTXDI's boiling "
     "filter): fewer blotches, less energy",
     NULL},
    {"di.gradient_confidence", P_BOOL, offsetof(struct di_reuse_settings, gradient_confidence), 0, 1, "off", "on",
     "BIASED: in temporal reuse, the previous reservoir's confidence times (1 - lambda)^10, lambda the pixel's "
     "temporal gradient of denoise.svgf.temporal_gradient (the relative change of the lighting its samples see, "
     "di_gradient.h): after a light changes, histories stop outweighing new samples (RTXDI's confidence from "
     "gradients); the weights then depend on the samples",
     NULL},
    {"di.moved_confidence", P_FLOAT, offsetof(struct di_reuse_settings, moved_confidence), 0, 1e6, "1", NULL,
     "temporal reuse on a frame whose emitters moved (translate / rotate keys): the previous reservoir's "
     "confidence at most this (unbiased for any value: the previous frame's targets are measured in its own "
     "geometry and pose); 0 drops the history on such frames; a value above confidence_cap keeps it whole, "
     "noisier, as a sample that was good before the move may be poor after it",
     NULL},
    {"di.boiling_strength", P_FLOAT, offsetof(struct di_reuse_settings, boiling_strength), 1e-6, 1, "0.2", NULL,
     "di.boiling_filter: strength s in (0, 1]; 0.2 drops reservoirs above 41 times the group's mean", NULL},
};

_Static_assert(sizeof(enum di_visibility_mis) == sizeof(int), "enum size");
_Static_assert(sizeof(enum di_initial) == sizeof(int) && sizeof(enum regir_source) == sizeof(int), "enum size");

/* ReGIR's store at most: one block per occupied cell (no more cells than pixels), each slots +
 * window entries of 14 floats and an int (regir.h), and with di.regir_source=bvh a light cut of
 * 772 bytes (light_cut.h). */
#define REGIR_MAX_BYTES (4.0 * 1024.0 * 1024.0 * 1024.0)

static int di_validate(const struct render_params *p, const void *block, char *msg)
{
    const struct di_settings *d = block;
    if (d->light_candidates + d->bsdf_candidates < 1) {
        snprintf(msg, RESTIR_MSG_LEN, "di.light_candidates + di.bsdf_candidates must be at least 1");
        return -1;
    }
    if (d->initial == DI_INITIAL_REGIR || d->initial == DI_INITIAL_AUTO) {
        const double grid = (double)d->regir_grid * d->regir_grid * d->regir_grid;
        const double pixels = (double)p->width * p->height;
        const double cut = d->regir_source == REGIR_SOURCE_BVH ? (double)sizeof(struct light_cut) : 0.0;
        const double bytes = (grid < pixels ? grid : pixels) * ((d->regir_slots + d->light_candidates) * 60.0 + cut);
        if (bytes > REGIR_MAX_BYTES) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "di.regir_grid=%d with di.regir_slots=%d (+ di.light_candidates=%d) could need %.1f GiB of light "
                     "reservoirs (at most %.0f GiB): lower di.regir_grid or di.regir_slots",
                     d->regir_grid, d->regir_slots, d->light_candidates, bytes / (1024.0 * 1024.0 * 1024.0),
                     REGIR_MAX_BYTES / (1024.0 * 1024.0 * 1024.0));
            return -1;
        }
    }
    return 0;
}

#undef D

struct param_block di_block = PARAM_METHOD_BLOCK("di", di_rows, struct di_settings, di_validate);
struct param_block di_reuse_block = PARAM_METHOD_BLOCK("di reuse", di_reuse_rows, struct di_reuse_settings, NULL);
