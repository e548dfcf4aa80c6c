/* params.h: every method parameter. params.c's table is the one place a setting is spelled: key,
 * type, default, range or names, BIASED value and help; `--set`, `--help`, the defaults, validation
 * and summary.json all read it. Must never depend on the ray tracer. */
#ifndef RESTIR_RENDER_PARAMS_H
#define RESTIR_RENDER_PARAMS_H

#include <stdint.h>
#include <stdio.h>

#include "denoise/denoise.h"
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
/* Spatial reuse of paired-pixel samples (002 Sec. 4.3.2, Fig. 10): none, a random similar pair for
 * every pair, or only for edge pairs. */
enum grad_spatial_mode { GRAD_SPATIAL_OFF = 0, GRAD_SPATIAL_DENSE, GRAD_SPATIAL_ADAPTIVE };
/* Visibility in the targets that ReSTIR DI's reuse compares (Bitterli et al. 2020 Alg. 5):
 * rays traces a shadow ray for every cross-domain target (unbiased); none uses unshadowed ones
 * (BIASED: a domain that cannot see the sample still takes MIS weight). */
enum di_visibility_mis { DI_VIS_MIS_RAYS = 0, DI_VIS_MIS_NONE };
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
/* ReSTIR GI: a reused sample point's outgoing radiance toward the shading point that reuses it is
 * estimated again from the sample's own random numbers (unbiased), or the radiance the sample
 * point sent toward the pixel that first traced it (Ouyang et al. 2021; BIASED where the sample
 * point is glossy). */
enum gi_radiance_mode { GI_RADIANCE_REEVALUATE = 0, GI_RADIANCE_STORED };
/* pt's random numbers: independent PCG32 streams per pixel and vertex, or Owen-scrambled, shuffled
 * Sobol' points per pixel (core/sobol.h: a (0,m,2)-net per dimension pair over each frame's samples). */
enum pt_sampler { PT_SAMPLER_INDEPENDENT = 0, PT_SAMPLER_SOBOL };
/* Which screened Poisson reconstruction fills the image (the other one is written as a layer). */
enum recon_mode { RECON_L2 = 0, RECON_L1, RECON_BOTH };
/* Most cell-search taps spmis.search_steps takes (reuse_cells.c keeps this many uniforms). */
#define SPMIS_MAX_SEARCH_STEPS 256

struct render_params {
    int width, height;
    int spp;          /* pt: paths per pixel per frame */
    uint64_t seed;
    int threads;      /* 0: all cores */
    int camera_path;  /* 0 static camera, 1 default camera path */
    int jitter;       /* jitter primary rays over the pixel footprint */

    /* path tracer */
    int max_bounces;  /* scattering events; 1 = direct lighting only */
    int rr_bounces;   /* Russian roulette starts after this many bounces */
    enum pt_sampler sampler; /* pt's random numbers */
    enum light_sampling light_sampling;   /* NEE's points on emitting triangles in every path walk (shading/lights.h) */
    enum light_selection light_selection; /* NEE's choice of emitting triangle in every path walk (shading/lights.h) */
    enum light_env_sampling light_env;    /* NEE's directions toward the environment in every path walk */

    /* ReSTIR DI */
    int light_candidates;
    int bsdf_candidates;
    int di_visibility_reuse;             /* shadow ray for the initial sample; occluded ones dropped */
    enum di_visibility_mis di_visibility_mis;
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
    float confidence_cap;
    int history_temporal;   /* next frame's history: the temporal output (1) or the spatial output (0) */
    enum restir_mis mis;
    float temporal_normal;  /* history rejected when n . n_prev < temporal_normal */
    float temporal_plane;   /* ... or when the plane distance exceeds temporal_plane * depth */
    int temporal_ratio_guard; /* 001 Sec. 5 target-ratio guard (biased) */
    float ratio_lo, ratio_hi;
    enum temporal_reuse_mode temporal_reuse; /* path reservoirs only (restir-pt and its relatives) */
    enum temporal_subpixel_mode temporal_subpixel; /* backprojection of sub-pixel samples */
    int shading_normals;       /* scene.shading_normals: vertex normals and normal maps (1) or flat (0) */
    int alpha_masks;           /* scene.alpha: honour alpha-masked materials (1) or make every one opaque (0) */
    int ray_streams;           /* rays.streams: batched passes trace through Embree streams (1) or ray by ray */
    int simd;                  /* simd: AVX2 kernels where the CPU has them (1) or the baseline ones (0) */
    int missing_textures_warn; /* scene files: a texture that cannot be read is an error (0) or a warning (1) */
    int scene_strict;          /* mesh files that load only in part: a warning (0) or refused (1) */
    int temporal_splat_steps; /* splat with motion blur: shutter-time strata per history reservoir */

    /* camera (pt, restir-pt, area-restir: the methods whose samples carry the primary ray) */
    float camera_shutter;  /* motion blur: fraction of a frame the shutter is open (0: off) */
    float camera_aperture; /* thin-lens aperture radius (0: the scene camera's) */
    float camera_focus;    /* focus distance (0: the scene camera's) */

    /* stochastic pairwise MIS with reuse cells (004) */
    enum spatial_reuse_mode spatial_reuse;
    int spmis_candidates;           /* N: neighbor draws (Eq. 15-17); 0 = M, deterministic pairwise over the cell */
    int spmis_canonical_candidates; /* N_c: canonical-weight draws (Eq. 18); 0 = M, the exact Eq. 11b */
    int spmis_tile;                 /* cell tiles are spmis_tile x spmis_tile pixels */
    int spmis_normal_bins;          /* cell key: buckets per normal component */
    int spmis_search_steps;         /* cell search (Sec. 5.1): taps */
    float spmis_search_radius;      /* ... initial radius in pixels */
    float spmis_search_growth;      /* ... radius factor per tap */
    float spmis_search_normal;      /* ... a tap is rejected when n . n_tap is below */
    enum spmis_search_mode spmis_search;
    enum restir_cells_score spmis_search_score; /* spmis.search_score: confidence (004) or compat (ours) */
    int spmis_sparse_count;         /* sparse search: own cell used when it has more contributing pixels */
    float spmis_search_confidence;  /* low-confidence search: own cell used when its mean c reaches this */
    int spmis_confidence_adjust;    /* scale non-canonical confidences by N / M (Sec. 4.3) */
    int spmis_canonical_pick;       /* enum restir_spmis_pick: P_c uniform or proportional to c */
    enum spmis_confidence_update spmis_confidence_update; /* the confidence a merge stores */

    /* ReSTIR PT */
    int pt_candidates;      /* initial paths per pixel */
    enum shift_kind shift;
    float shift_roughness;  /* hybrid: GGX alpha at or above which a vertex is rough */
    float shift_distance;   /* hybrid: minimum reconnection length, in shift.distance_mode's measure */
    int shift_distance_mode; /* enum shift_distance_mode (shift_kind.h) */

    /* ReSTIR GI */
    enum gi_radiance_mode gi_radiance; /* what a reused sample point's outgoing radiance is */

    /* gradient-domain ReSTIR PT (002) */
    enum grad_spatial_mode grad_spatial;
    int grad_temporal;      /* temporal reuse of paired-pixel reservoirs (with temporal on) */
    int grad_base;          /* pairs' initial paths: 0 independent of the primal's, 1 the primal's own */
    int grad_positivize;    /* two reservoirs r+, r- per pair (Eq. 23-26) */
    int grad_cross_sign;    /* r+ and r- also reuse the other sign's neighbor reservoir */
    int grad_search;        /* N: random neighbor pairs tried by the pair search (256) */
    float grad_radius;      /* pair-search neighborhood radius, pixels */
    float grad_inner_jacobian_ratio; /* reject outer shifts whose inner Jacobians differ more (0: off) */
    float grad_edge_albedo, grad_edge_normal, grad_edge_depth; /* edge-pair thresholds (Sec. 4.3.2) */
    enum recon_mode recon;
    float recon_alpha;      /* screened Poisson weight alpha of the primal (0.2) */
    int recon_solver;       /* enum restir_poisson_solver: dct or cg for L2 */
    int recon_iterations;   /* CG steps of L2 from the primal; 0: to the tolerance */
    int recon_l1_iterations, recon_l1_cg; /* IRLS reweightings and CG steps per reweighting (0: default) */
    int recon_l1_precond;   /* enum restir_poisson_precond of the L1 solve's CG */

    /* denoising of the finished frame (SVGF or a-trous, DENOISE.md): a layer of its own, never read by an estimator */
    struct denoise_settings denoise;
};

/* Spatial neighbors a method tries: spatial.neighbors, or when 0 the default of 001 for ReSTIR DI
 * (1) and of Lin et al. 2022 for ReSTIR PT (3). */
/* The light strategy of next-event estimation in every path walk (path_walk.h): pt, references,
 * restir-pt and the methods built on its passes, restir-gi and gpt. */
static inline struct light_choice render_params_light_choice(const struct render_params *p)
{
    const struct light_choice c = {p->light_selection, p->light_sampling, p->light_env};
    return c;
}

static inline int render_params_spatial_neighbors(const struct render_params *p, int path_reuse)
{
    return p->spatial_neighbors > 0 ? p->spatial_neighbors : (path_reuse ? 3 : 1);
}

void render_params_defaults(struct render_params *p);
/* Applies one "key=value". Returns 0, or -1 with msg naming the key or the bad value. */
int render_params_set(struct render_params *p, const char *assignment, char *msg);
/* Applies "key=value:key=value..." in order (the settings part of a method spec such as
 * `restir-pt:spatial.reuse=spmis:spmis.candidates=8`). Returns 0, or -1 with msg. */
int render_params_set_list(struct render_params *p, const char *list, char *msg);
/* Checks ranges (resolution, counts, ...). Returns 0, or -1 with msg naming the problem. */
int render_params_validate(const struct render_params *p, char *msg);
/* The value of key in p as --set spells it ("l2", "on", "0.2", ...) into val (n bytes). Returns 0,
 * or -1 (val empty) for an unknown key. */
int render_params_get(const struct render_params *p, const char *key, char *val, size_t n);
/* Prints every key with its default, meaning, and the value that makes it BIASED. */
void render_params_help(FILE *out);
/* The i-th key that has a value of its own (every key --set takes but shorthands such as
 * spatial.preset), in table order; NULL past the last. With render_params_get this lists every
 * setting of a run, as summary.json records it. */
const char *render_params_key(size_t i);
/* Writes "key=value, ..." of the settings in p whose value makes the estimator BIASED into out
 * (n bytes) and returns how many there are (0: every setting in p is unbiased). */
int render_params_biased(const struct render_params *p, char *out, size_t n);

/* The MIS of a merge whose non-canonical domains tile the canonical one (temporal.subpixel=search):
 * mis=pairwise as restir_mis_weights_pairwise_tiled, balance and 1/M as they are. */
static inline enum restir_mis render_params_tiled_mis(const struct render_params *p)
{
    return p->mis == RESTIR_MIS_PAIRWISE ? RESTIR_MIS_PAIRWISE_TILED : p->mis;
}

#endif
