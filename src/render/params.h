/* params.h: a run's parameters, struct render_params, and the toolkit's settings blocks. A setting is
 * spelled once, in its block's table (settings_block.h): the toolkit's in params.c, a method's in its
 * folder; `--set`, `--help`, the defaults, validation and summary.json all read the tables through
 * the registry (methods/settings.h). Must never depend on the ray tracer. */
#ifndef RESTIR_RENDER_PARAMS_H
#define RESTIR_RENDER_PARAMS_H

#include <stdint.h>
#include <stdio.h>

#include "denoise/denoise.h"
#include "render/settings_block.h"
#include "render/shift_kind.h"
#include "shading/lights.h" /* enum light_sampling, light_selection */
#include "restir/cells.h"
#include "restir/mis.h"

/* Spatial neighbor selection (spatial_select.h). */
enum spatial_select_mode { SELECT_BITTERLI = 0, SELECT_COMPAT, SELECT_COMPAT_BINARY };
/* Spatial reuse: from the selected neighbors, or stochastic pairwise MIS over a reuse cell (004). */
enum spatial_reuse_mode { REUSE_STANDARD = 0, REUSE_SPMIS };
/* When the SPMIS cell search runs: for every pixel (004 Sec. 5.1); only where the pixel's own cell
 * has few contributing pixels (BIASED: that count depends on the samples); or only where the own
 * cell's mean confidence is low (unbiased: confidences depend on history, not on samples). */
enum spmis_search_mode { SPMIS_SEARCH_ALWAYS = 0, SPMIS_SEARCH_SPARSE, SPMIS_SEARCH_LOW_CONFIDENCE };
/* The confidence an SPMIS merge stores (004 leaves it open): c_c + min(1, N / M) c_Sigma, or c_c plus
 * the confidences of the distinct pixels drawn (reuse_cells.c). */
enum spmis_confidence_update { SPMIS_CONFIDENCE_CELL = 0, SPMIS_CONFIDENCE_DRAWN };
/* Temporal reuse of path reservoirs: the previous pixel under the backward motion vector (Area
 * ReSTIR), reservoir splatting (Liu et al. 2025: each previous reservoir forward-projected by its
 * primary hit), or both techniques combined by MIS. */
enum temporal_reuse_mode { TEMPORAL_BACKPROJECT = 0, TEMPORAL_SPLAT, TEMPORAL_BOTH };
/* Backprojection of sub-pixel samples (jitter on): the previous pixel under the motion vector,
 * whose samples are translated onto the current pixel on the unit torus (wrap: one leaving the
 * pixel re-enters at its other side), or the 2x2 previous pixels the current pixel's square
 * overlaps, each keeping only the samples that land inside it (search: Area ReSTIR, Zhang et al.
 * 2024, Sec. 4.3.1). Both are unbiased (docs/RESTIR_PT.md). */
enum temporal_subpixel_mode { TEMPORAL_SUBPIXEL_WRAP = 0, TEMPORAL_SUBPIXEL_SEARCH };
/* pt's random numbers: independent PCG32 streams per pixel and vertex, or Owen-scrambled, shuffled
 * Sobol' points per pixel (core/sobol.h: a (0,m,2)-net per dimension pair over each frame's samples). */
enum pt_sampler { PT_SAMPLER_INDEPENDENT = 0, PT_SAMPLER_SOBOL };
/* Most cell-search taps spmis.search_steps takes (reuse_cells.c keeps this many uniforms). */
#define SPMIS_MAX_SEARCH_STEPS 256

/* Reuse, shared by every ReSTIR method (restir-di, restir-pt and its relatives, restir-gi): the keys
 * temporal, spatial, spatial.*, history, confidence_cap, mis and temporal.* (params.c's reuse block). */
struct reuse_settings {
    int temporal;
    int spatial;
    int spatial_neighbors;  /* 0: the method's default (render_params_spatial_neighbors) */
    enum spatial_select_mode spatial_select;
    int spatial_candidates; /* compat: K candidates tried (000 Algorithm 1) */
    float spatial_omega;    /* compat: solid angle of the position scale s (000 Eq. 15) */
    float spatial_beta;     /* compat: normal exponent (000 Eq. 15) */
    int spatial_early_stop; /* compat: stop once more than M candidates score above 0.5 */
    float spatial_radius;
    float spatial_normal;   /* Bitterli test, 000 Eq. 7: n . n_i >= spatial_normal */
    float spatial_depth;    /* Bitterli test, 000 Eq. 7: |d_i - d| / d < spatial_depth */
    enum spatial_reuse_mode spatial_reuse;
    float confidence_cap;
    int history_temporal;   /* next frame's history: the temporal output (1) or the spatial output (0) */
    enum restir_mis mis;
    float temporal_normal;  /* history rejected when n . n_prev < temporal_normal */
    float temporal_plane;   /* ... or when the plane distance exceeds temporal_plane * depth */
    int temporal_ratio_guard; /* 001 Sec. 5 target-ratio guard (biased) */
    float ratio_lo, ratio_hi;
    enum temporal_reuse_mode temporal_reuse; /* path reservoirs only (restir-pt and its relatives) */
    enum temporal_subpixel_mode temporal_subpixel; /* backprojection of sub-pixel samples */
    int temporal_splat_steps; /* splat with motion blur: shutter-time strata per history reservoir */
    int temporal_permutation; /* RTXDI's permutation sampling of the temporal neighbour (params_block_permutation) */
};

/* Stochastic pairwise MIS with reuse cells (004): the keys spmis.* (reuse_cells.h). */
struct spmis_settings {
    int candidates;           /* N: neighbor draws (Eq. 15-17); 0 = M, deterministic pairwise over the cell */
    int canonical_candidates; /* N_c: canonical-weight draws (Eq. 18); 0 = M, the exact Eq. 11b */
    int tile;                 /* cell tiles are tile x tile pixels */
    int normal_bins;          /* cell key: buckets per normal component */
    int search_steps;         /* cell search (Sec. 5.1): taps */
    float search_radius;      /* ... initial radius in pixels */
    float search_growth;      /* ... radius factor per tap */
    float search_normal;      /* ... a tap is rejected when n . n_tap is below */
    enum spmis_search_mode search;
    enum restir_cells_score search_score; /* confidence (004) or compat (ours) */
    int sparse_count;         /* sparse search: own cell used when it has more contributing pixels */
    float search_confidence;  /* low-confidence search: own cell used when its mean c reaches this */
    int confidence_adjust;    /* scale non-canonical confidences by N / M (Sec. 4.3) */
    int canonical_pick;       /* enum restir_spmis_pick: P_c uniform or proportional to c */
    enum spmis_confidence_update confidence_update; /* the confidence a merge stores */
};

/* The shift mapping of path reuse (path_shift.h): the keys shift and shift.*. */
struct shift_settings {
    enum shift_kind kind;
    float roughness;   /* hybrid: GGX alpha at or above which a vertex is rough */
    float distance;    /* hybrid: minimum reconnection length, in distance_mode's measure */
    int distance_mode; /* enum shift_distance_mode (shift_kind.h) */
};

/* Bytes of struct render_params that hold the methods' own settings blocks (settings_block.h); the
 * registry refuses to start when the registered blocks need more. */
#define RENDER_PARAMS_METHOD_BYTES 256

/* A run's parameters: the toolkit's settings, each in its block's place, and the methods' own
 * blocks in method_settings. A plain value: copy it to change a setting for one run. */
struct render_params {
    int width, height;
    int spp;          /* pt, gpt: paths per pixel per frame */
    uint64_t seed;
    int threads;      /* 0: all cores */
    int camera_path;  /* 0 static camera, 1 default camera path */
    int jitter;       /* jitter primary rays over the pixel footprint */

    /* every path walk (path_walk.h) */
    int max_bounces;  /* scattering events; 1 = direct lighting only */
    int rr_bounces;   /* Russian roulette starts after this many bounces */
    enum pt_sampler sampler; /* pt's random numbers */
    enum light_sampling light_sampling;   /* NEE's points on emitting triangles (shading/lights.h) */
    enum light_selection light_selection; /* NEE's choice of emitting triangle (shading/lights.h) */
    enum light_env_sampling light_env;    /* NEE's directions toward the environment */

    /* the scene and the ray tracer */
    int shading_normals;       /* scene.shading_normals: vertex normals and normal maps (1) or flat (0) */
    int alpha_masks;           /* scene.alpha: honour alpha-masked materials (1) or make every one opaque (0) */
    int ray_streams;           /* rays.streams: batched passes trace through Embree streams (1) or ray by ray */
    int simd;                  /* simd: AVX2 kernels where the CPU has them (1) or the baseline ones (0) */
    int missing_textures_warn; /* scene files: a texture that cannot be read is an error (0) or a warning (1) */
    int scene_strict;          /* mesh files that load only in part: a warning (0) or refused (1) */

    /* camera (the methods whose samples carry the primary ray: METHOD_CAMERA_EFFECTS) */
    float camera_shutter;  /* motion blur: fraction of a frame the shutter is open (0: off) */
    float camera_aperture; /* thin-lens aperture radius (0: the scene camera's) */
    float camera_focus;    /* focus distance (0: the scene camera's) */

    struct reuse_settings reuse;
    struct spmis_settings spmis;
    struct shift_settings shift;

    /* denoising of the finished frame (SVGF or a-trous, DENOISE.md): a layer of its own, never read by an estimator */
    struct denoise_settings denoise;

    /* the registered methods' own settings blocks, where the registry placed them (settings_block.h) */
    _Alignas(16) unsigned char method_settings[RENDER_PARAMS_METHOD_BYTES];
};

/* The light strategy of next-event estimation in every path walk (path_walk.h). */
static inline struct light_choice render_params_light_choice(const struct render_params *p)
{
    const struct light_choice c = {p->light_selection, p->light_sampling, p->light_env};
    return c;
}

/* Spatial neighbors a method tries: spatial.neighbors, or when 0 the default of 001 for ReSTIR DI
 * (1) and of Lin et al. 2022 for ReSTIR PT (3). */
static inline int render_params_spatial_neighbors(const struct render_params *p, int path_reuse)
{
    return p->reuse.spatial_neighbors > 0 ? p->reuse.spatial_neighbors : (path_reuse ? 3 : 1);
}

/* The MIS of a merge whose non-canonical domains tile the canonical one (temporal.subpixel=search):
 * mis=pairwise as restir_mis_weights_pairwise_tiled, balance and 1/M as they are. */
static inline enum restir_mis render_params_tiled_mis(const struct render_params *p)
{
    return p->reuse.mis == RESTIR_MIS_PAIRWISE ? RESTIR_MIS_PAIRWISE_TILED : p->reuse.mis;
}

/* The toolkit's blocks, for the method rows that list the ones they read. */
extern const struct param_block params_block_spp;
extern const struct param_block params_block_image;
extern const struct param_block params_block_depth;
extern const struct param_block params_block_roulette;
extern const struct param_block params_block_sampler;
extern const struct param_block params_block_lights;
extern const struct param_block params_block_reuse;
extern const struct param_block params_block_path_history;
extern const struct param_block params_block_permutation; /* temporal.permutation: the methods that implement it */
extern const struct param_block params_block_spmis;
extern const struct param_block params_block_shift;
extern const struct param_block params_block_scene;
extern const struct param_block params_block_trace;
extern const struct param_block params_block_camera;
extern const struct param_block params_block_denoise;

/* The toolkit's settings blocks (params.c, params_denoise.c), in the order `restir render --help`
 * lists them. The registry (methods/settings.h) adds the methods' blocks and implements --set, the
 * defaults, validation and help over all of them. */
extern const struct param_block *const render_params_toolkit_blocks[];
extern const size_t render_params_toolkit_block_count;

#endif
