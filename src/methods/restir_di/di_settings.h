/* di_settings.h: ReSTIR DI's own settings: its initial candidates (di.light_candidates, di.bsdf_candidates,
 * di.visibility_reuse, di.initial and ReGIR's di.regir_*; ris-di reads them too) and the visibility in its reuse's targets (di.visibility_mis) */
#ifndef RESTIR_METHODS_RESTIR_DI_DI_SETTINGS_H
#define RESTIR_METHODS_RESTIR_DI_DI_SETTINGS_H

#include "render/params.h"

/* Visibility in the targets that ReSTIR DI's reuse compares (Bitterli et al. 2020 Alg. 5):
 * rays traces a shadow ray for every cross-domain target (unbiased); none uses unshadowed ones
 * (BIASED: a domain that cannot see the sample still takes MIS weight). */
enum di_visibility_mis { DI_VIS_MIS_RAYS = 0, DI_VIS_MIS_NONE };

/* Where initial RIS takes its light candidates: the frame's power-sampled pool (light_pool.h), the
 * slots of ReGIR's grid cell that holds the pixel's point (regir.h), or the pixel's own draws down
 * the light BVH at its point (pt's emitter choice; no sharing, no grid). */
enum di_initial { DI_INITIAL_POOL = 0, DI_INITIAL_REGIR, DI_INITIAL_BVH, DI_INITIAL_AUTO };
/* di.initial=auto fills the grid in a frame only when its slots' candidates are at most this share of
 * the valid pixels' own (regir_fill_share), else takes the pool. Measured on many-lights
 * (docs/BENCHMARKS.md): share 0.12 at 640x360, the grid's frame +10% for 14% lower relMSE per frame;
 * share 0.41 at 320x180, +29..69% for 7% lower; cornell's one lamp at 320x180, share 0.93, +80%. Tiny
 * images, whose cells hold few pixels each, get the pool. */
#define DI_AUTO_REGIR_MAX_FILL_SHARE 0.15
/* Whether a renderer builds ReGIR's grid: for regir and auto where the scene has emitters (the cells
 * hold emitter samples); auto uses the pool elsewhere, and an explicit regir without emitters is
 * refused by the method's check (a renderer made without it falls back to the pool too). */
static inline int di_initial_uses_regir(enum di_initial initial, int num_emitters)
{
    return num_emitters > 0 && (initial == DI_INITIAL_REGIR || initial == DI_INITIAL_AUTO);
}
/* Where ReGIR's cells draw the candidates of their slots: by power from the scene's alias table, or
 * from a cut through the light BVH at the cell's centre (light_cut.h) mixed with power
 * (REGIR_POWER_SHARE, regir.c). */
enum regir_source { REGIR_SOURCE_POWER = 0, REGIR_SOURCE_BVH };

struct di_settings {
    int light_candidates;
    int bsdf_candidates;
    int visibility_reuse; /* shadow ray for the initial sample; occluded ones dropped */
    enum di_initial initial;
    int regir_grid;       /* cells along the longest axis of the shading points' bounding box */
    int regir_slots;      /* reservoirs per cell */
    int regir_candidates; /* RIS candidates per reservoir */
    enum regir_source regir_source;
};

struct di_reuse_settings {
    enum di_visibility_mis visibility_mis;
    int boiling_filter;     /* BIASED: drop the temporal pass's outliers (render/boiling_filter.h) */
    float boiling_strength; /* its s: outliers exceed 10 / s - 9 times their group's mean target x W */
    int gradient_confidence; /* BIASED: history confidence scaled down where the temporal gradient is high */
    float moved_confidence;  /* the history's confidence at most, on a frame whose emitters moved (0: dropped) */
};

extern struct param_block di_block; /* di: the initial candidates */
static inline const struct di_settings *di_settings_of(const struct render_params *p)
{
    return param_block_in(p, &di_block);
}
static inline struct di_settings *di_settings_of_mut(struct render_params *p)
{
    return param_block_in_mut(p, &di_block);
}
extern struct param_block di_reuse_block; /* di reuse: visibility in reuse, the boiling filter */
static inline const struct di_reuse_settings *di_reuse_settings_of(const struct render_params *p)
{
    return param_block_in(p, &di_reuse_block);
}
static inline struct di_reuse_settings *di_reuse_settings_of_mut(struct render_params *p)
{
    return param_block_in_mut(p, &di_reuse_block);
}

#endif
