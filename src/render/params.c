/* params.c: the table that maps `--set` keys to fields of struct render_params, with parsing,
 * range checks and help text. Must never depend on the ray tracer or render passes. */
#include "render/params.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "restir/cells.h"
#include "restir/poisson.h"
#include "restir/spmis.h"

/* P_NAMES: an enum stored as int, spelled by the def's names; P_COUNT: an int where "M" means 0
 * (all M pixels of a reuse cell). */
enum param_type { P_INT, P_COUNT, P_FLOAT, P_BOOL, P_MIS, P_SHIFT, P_NAMES, P_PRESET };

/* One row per setting: everything about it is said here, once. */
struct param_def {
    const char *key;
    enum param_type type;
    size_t offset;
    double lo, hi;       /* accepted range for numbers */
    const char *def;     /* the default, as --set spells it (NULL: a shorthand that sets other keys) */
    const char *biased;  /* the value that makes the estimator BIASED, as --set spells it (NULL: none) */
    const char *help;
    const char *const *names; /* P_NAMES: the spellings of values 0, 1, ..., NULL-terminated */
};

static const char *const select_names[] = {"bitterli", "compat", "compat-binary", NULL};
static const char *const reuse_names[] = {"standard", "spmis", NULL};
static const char *const search_names[] = {"always", "sparse", "low-confidence", NULL};
static const char *const pick_names[] = {"uniform", "confidence", NULL};
static const char *const svgf_kernel_names[] = {"5x5", "3x3", NULL}; /* denoise_types.h */
static const char *const svgf_lum_weight_names[] = {"symmetric", "paper", NULL};
static const char *const svgf_taa_clamp_names[] = {"moving", "always", "off", NULL};
static const char *const distance_mode_names[] = {"scene", "absolute", "relative", NULL}; /* shift_kind.h */
static const char *const confidence_update_names[] = {"cell", "drawn", NULL}; /* enum spmis_confidence_update */
static const char *const search_score_names[] = {"confidence", "compat", NULL}; /* enum restir_cells_score */
static const char *const history_names[] = {"spatial", "temporal", NULL};
static const char *const grad_spatial_names[] = {"off", "dense", "adaptive", NULL};
static const char *const base_names[] = {"independent", "shared", NULL};
static const char *const recon_names[] = {"l2", "l1", "both", NULL};
static const char *const solver_names[] = {"dct", "cg", NULL};
static const char *const precond_names[] = {"multigrid", "jacobi", NULL}; /* enum restir_poisson_precond */
static const char *const visibility_mis_names[] = {"rays", "none", NULL};
static const char *const temporal_reuse_names[] = {"backproject", "splat", "both", NULL};
static const char *const temporal_subpixel_names[] = {"wrap", "search", NULL}; /* enum temporal_subpixel_mode */
static const char *const missing_texture_names[] = {"error", "warn", NULL};
static const char *const gi_radiance_names[] = {"reevaluate", "stored", NULL}; /* enum gi_radiance_mode */
static const char *const sampler_names[] = {"independent", "sobol", NULL}; /* enum pt_sampler */
static const char *const light_sampling_names[] = {"area", "solid-angle", NULL}; /* enum light_sampling */
static const char *const light_selection_names[] = {"power", "bvh", NULL};        /* enum light_selection */
static const char *const light_env_names[] = {"map", "compensated", NULL};        /* enum light_env_sampling */
/* denoise: denoise_names (denoise.h) */
static const char *const preset_names[] = {"fast", "balanced", "conservative", NULL};

/* Index of val among the NULL-terminated names, or -1. */
static int name_index(const char *const *names, const char *val)
{
    for (int k = 0; names[k]; k++)
        if (!strcmp(val, names[k]))
            return k;
    return -1;
}

/* P_NAMES fields are written through int pointers. */
_Static_assert(sizeof(enum spatial_select_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum spatial_reuse_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum spmis_search_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum spmis_confidence_update) == sizeof(int), "enum size");
_Static_assert(sizeof(enum restir_cells_score) == sizeof(int), "enum size");
_Static_assert(sizeof(enum grad_spatial_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum recon_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum di_visibility_mis) == sizeof(int), "enum size");
_Static_assert(sizeof(enum temporal_reuse_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum gi_radiance_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum light_sampling) == sizeof(int), "enum size");
_Static_assert(sizeof(enum light_selection) == sizeof(int), "enum size");
_Static_assert(sizeof(enum light_env_sampling) == sizeof(int), "enum size");

#define F(field) offsetof(struct render_params, field)
static const struct param_def params[] = {
    {"spp", P_INT, F(spp), 1, 1 << 20, "1", NULL, "pt: paths per pixel per frame", NULL},
    {"jitter", P_BOOL, F(jitter), 0, 1, "on", NULL, "jitter primary rays over the pixel (integrates the box filter)", NULL},
    {"pt.max_bounces", P_INT, F(max_bounces), 1, 64, "8", NULL,
     "pt: maximum scattering events (1 = direct lighting; set for you when comparing DI methods)", NULL},
    {"pt.rr_bounces", P_INT, F(rr_bounces), 0, 1024, "3", NULL, "pt: Russian roulette after this many bounces", NULL},
    {"sampler", P_NAMES, F(sampler), 0, 0, "sobol", NULL,
     "pt's random numbers: independent (PCG32 streams) or sobol (Owen-scrambled Sobol' points, a (0,2)-net per "
     "dimension pair over each frame's samples in a pixel; unbiased, independent across seeds and frames)",
     sampler_names},
    {"lights.sample", P_NAMES, F(light_sampling), 0, 0, "area", NULL,
     "next-event estimation's point on the chosen emitting triangle in every path walk (pt, restir-pt and the "
     "methods on its passes, restir-gi, gpt; not restir-di's light pool): area (uniform on it) or solid-angle "
     "(uniform in the solid angle it subtends, Arvo 1995; area where it subtends less than 0.02 sr), with the "
     "matching density in NEE and in the MIS weight of BSDF-sampled hits",
     light_sampling_names},
    {"lights.select", P_NAMES, F(light_selection), 0, 0, "bvh", NULL,
     "next-event estimation's choice of emitting triangle in every path walk (pt, restir-pt and the methods on "
     "its passes, restir-gi, gpt; not restir-di's light pool): power (in proportion to its power, one alias "
     "table) or bvh (down the emitters' BVH by each node's importance at the shading point from its power, "
     "distance and orientation bounds, Conty Estevez & Kulla 2018), with the matching probability in NEE and in "
     "the MIS weight of BSDF-sampled hits; unbiased either way",
     light_selection_names},
    {"lights.env", P_NAMES, F(light_env), 0, 0, "compensated", NULL,
     "next-event estimation's directions toward an environment map in every path walk (pt, restir-pt and the "
     "methods on its passes, restir-gi, gpt; not restir-di's light pool): map (in proportion to the map's "
     "luminance) or compensated (in proportion to its luminance above the map's mean, MIS compensation, Karlik et "
     "al. 2019: BSDF sampling, which every walk combines with it by MIS, covers the rest; the map's distribution "
     "where nothing is above the mean, as for a constant sky); unbiased either way",
     light_env_names},
    {"di.light_candidates", P_INT, F(light_candidates), 0, 4096, "32", NULL, "initial RIS: light-sampled candidates", NULL},
    {"di.bsdf_candidates", P_INT, F(bsdf_candidates), 0, 64, "1", NULL, "initial RIS: BSDF-sampled candidates", NULL},
    {"di.visibility_reuse", P_BOOL, F(di_visibility_reuse), 0, 1, "on", NULL,
     "restir-di: trace a shadow ray for the initial sample and drop it when occluded (Bitterli et al. "
     "2020 Alg. 5), so reuse carries visible samples (with di.visibility_mis=rays shading then needs no "
     "shadow ray)", NULL},
    {"di.visibility_mis", P_NAMES, F(di_visibility_mis), 0, 0, "rays", "none",
     "restir-di with di.visibility_reuse: targets compared across domains include visibility, traced per "
     "merge (rays, unbiased), or not (none: BIASED, darkens where neighbors cannot see the light; no rays)",
     visibility_mis_names},
    {"temporal", P_BOOL, F(temporal), 0, 1, "on", NULL, "temporal reuse on/off", NULL},
    {"spatial", P_BOOL, F(spatial), 0, 1, "on", NULL, "spatial reuse on/off", NULL},
    {"spatial.neighbors", P_INT, F(spatial_neighbors), 0, 5, "0", NULL,
     "spatial neighbors tried per pixel (0: method default, 1 for restir-di, 3 for restir-pt)", NULL},
    {"spatial.radius", P_FLOAT, F(spatial_radius), 1, 512, "30", NULL, "spatial reuse disk radius in pixels", NULL},
    {"spatial.select", P_NAMES, F(spatial_select), 0, 0, "bitterli", NULL,
     "neighbor selection: bitterli (uniform tries, 000 Eq. 7), compat (000 Algorithm 1, Eq. 14 scores), "
     "compat-binary (Algorithm 1 with Eq. 7 as score); all read only the G-buffer (unbiased)",
     select_names},
    {"spatial.preset", P_PRESET, 0, 0, 0, NULL, NULL,
     "000 presets: fast (compat, R 30, K 32), balanced (R 50), conservative (R 100)", NULL},
    {"spatial.candidates", P_INT, F(spatial_candidates), 1, 4096, "32", NULL, "compat: candidates K per pixel", NULL},
    {"spatial.omega", P_FLOAT, F(spatial_omega), 1e-9, 12.57, "0.05", NULL, "compat: solid angle Omega of the position scale (Eq. 15)", NULL},
    {"spatial.beta", P_FLOAT, F(spatial_beta), 0, 1e3, "8", NULL, "compat: normal exponent beta (Eq. 15)", NULL},
    {"spatial.early_stop", P_BOOL, F(spatial_early_stop), 0, 1, "on", NULL,
     "compat: stop once more than M candidates score above 0.5 (000 Sec. 5)", NULL},
    {"spatial.normal", P_FLOAT, F(spatial_normal), -1, 1, "0.5", NULL, "Bitterli test (000 Eq. 7): minimum n . n_i", NULL},
    {"spatial.depth", P_FLOAT, F(spatial_depth), 0, 1e30, "0.1", NULL, "Bitterli test (000 Eq. 7): max |d_i - d| / d", NULL},
    {"history", P_NAMES, F(history_temporal), 0, 0, "spatial", NULL,
     "what the next frame reuses temporally: the spatial-reuse output (spatial, as Lin et al. 2022) or the "
     "temporal output before spatial reuse (temporal: spatial reuse then cannot feed back; unbiased either way)",
     history_names},
    {"confidence_cap", P_FLOAT, F(confidence_cap), 1, 1e9, "20", NULL, "cap on confidence weights c (M cap)", NULL},
    {"mis", P_MIS, F(mis), 0, 0, "pairwise", "1/M",
     "resampling MIS: pairwise (defensive, unbiased), balance (unbiased), 1/M (BIASED: ignores that "
     "domains cannot all produce every sample)", NULL},
    {"temporal.normal", P_FLOAT, F(temporal_normal), -1, 1, "0.8", NULL, "history rejected when n . n_prev is below", NULL},
    {"temporal.plane", P_FLOAT, F(temporal_plane), 0, 1e30, "0.05", NULL,
     "history rejected when the plane distance / depth is above", NULL},
    {"temporal.ratio_guard", P_BOOL, F(temporal_ratio_guard), 0, 1, "off", "on",
     "BIASED: reject history whose target ratio leaves [ratio_lo, ratio_hi] (001 Sec. 5)", NULL},
    {"temporal.reuse", P_NAMES, F(temporal_reuse), 0, 0, "backproject", NULL,
     "path reservoirs (restir-pt, area-restir, the gradient methods' primal): backproject (the previous "
     "pixel under the backward motion vector, Area ReSTIR), splat (Liu et al. 2025: every previous "
     "reservoir lands where its primary hit is seen now; needs jitter=on), or both, combined by balance "
     "MIS (docs/RESTIR_PT.md); all unbiased with mis=pairwise or balance",
     temporal_reuse_names},
    {"temporal.subpixel", P_NAMES, F(temporal_subpixel), 0, 0, "wrap", NULL,
     "backprojected sub-pixel samples (restir-pt, area-restir, grad-after-restir, grestir-pt's pairs; needs "
     "jitter=on and temporal.reuse=backproject): wrap (the previous pixel under the motion vector; a sample "
     "leaving the current pixel re-enters at its other side) or search (the 2x2 previous pixels the current "
     "pixel overlaps, each kept where its samples land inside it, Area ReSTIR Sec. 4.3.1; mis=pairwise "
     "then weighs each path against the one previous pixel that reaches it). Both unbiased",
     temporal_subpixel_names},
    {"scene.shading_normals", P_BOOL, F(shading_normals), 0, 1, "on", NULL,
     "off: every triangle shades with its geometric normal (no vertex normals, no normal maps), as before "
     "the renderer read them. This CHANGES THE SCENE: for looking at what they do, never for comparing images", NULL},
    {"scene.alpha", P_BOOL, F(alpha_masks), 0, 1, "on", NULL,
     "off: every alpha-masked material (glTF alphaMode MASK or BLEND) is opaque. This CHANGES THE SCENE "
     "(leaf cards become quads): for measuring what the masks cost, never for comparing images", NULL},
    {"rays.streams", P_BOOL, F(ray_streams), 0, 1, "on", NULL,
     "trace the G-buffer's camera rays and restir-di's shadow rays tile by tile as Embree streams "
     "(rtcIntersect1M / rtcOccluded1M); off: one Embree call per ray. The same images either way, only the "
     "time differs (docs/BENCHMARKS.md, the section on Embree streams). Applied when the scene is loaded, so "
     "in `restir compare` the command's --set value counts, not a per-spec one", NULL},
    {"simd", P_BOOL, F(simd), 0, 1, "on", NULL,
     "vector kernels (initial RIS candidates, restir-di merge targets across pixels): on = AVX2 where the "
     "CPU has it, chosen at run time; off = the build's baseline (SSE2 on x86-64). The same images either "
     "way, only the time differs", NULL},
    {"scene.missing_textures", P_NAMES, F(missing_textures_warn), 0, 0, "error", NULL,
     "a texture a scene file names that cannot be read: error (refuse the scene, naming the file) or warn "
     "(say so on stderr and use the material's factor instead of the map)",
     missing_texture_names},
    {"scene.strict", P_BOOL, F(scene_strict), 0, 1, "off", NULL,
     "a mesh file that loads only in part (faces assimp dropped, a material it made up, degenerate triangles, "
     "points or lines we skipped): off says what on stderr and in scene info and renders the rest; on refuses "
     "the file with that message",
     NULL},
    {"temporal.splat_steps", P_INT, F(temporal_splat_steps), 1, 16, "2", NULL,
     "splat with camera.shutter > 0: each previous reservoir is splatted into this many shutter-time strata "
     "(1: it keeps its shutter time)", NULL},
    {"camera.shutter", P_FLOAT, F(camera_shutter), 0, 1, "0", NULL,
     "motion blur: the shutter is open for this fraction of a frame before each frame's instant, while the "
     "camera moves from the previous frame's pose (0: off; pt, restir-pt, area-restir)", NULL},
    {"camera.aperture", P_FLOAT, F(camera_aperture), 0, 1e30, "0", NULL,
     "depth of field: thin-lens aperture radius in scene units (0: the scene camera's, a pinhole unless its "
     "file sets aperture; pt, restir-pt, area-restir)", NULL},
    {"camera.focus_distance", P_FLOAT, F(camera_focus), 0, 1e30, "0", NULL,
     "thin lens: distance of the plane in focus along the view direction (0: the scene camera's "
     "focus_distance, else the distance to its look_at point)", NULL},
    {"temporal.ratio_lo", P_FLOAT, F(ratio_lo), 0, 1e30, "0.1", NULL, "target-ratio guard lower bound", NULL},
    {"temporal.ratio_hi", P_FLOAT, F(ratio_hi), 0, 1e30, "10", NULL, "target-ratio guard upper bound", NULL},
    {"spatial.reuse", P_NAMES, F(spatial_reuse), 0, 0, "standard", NULL,
     "spatial reuse: standard (GRIS over the selected neighbors) or spmis (004 Algorithm 2: stochastic "
     "pairwise MIS over one reuse cell; unbiased)",
     reuse_names},
    {"spmis.candidates", P_COUNT, F(spmis_candidates), 1, RESTIR_SPMIS_MAX_DRAWS, "3", NULL,
     "spmis: neighbor draws N (004 Eq. 15-17); M = deterministic pairwise over the whole cell", NULL},
    {"spmis.canonical_candidates", P_COUNT, F(spmis_canonical_candidates), 1, RESTIR_SPMIS_MAX_DRAWS, "1", NULL,
     "spmis: canonical-weight draws N_c (004 Eq. 18); M = the exact Eq. 11b sum", NULL},
    {"spmis.tile", P_INT, F(spmis_tile), 1, RESTIR_CELLS_MAX_TILE, "8", NULL, "spmis: reuse-cell tile edge in pixels (004 Sec. 5)", NULL},
    {"spmis.normal_bins", P_INT, F(spmis_normal_bins), 1, 64, "4", NULL,
     "spmis: cell key quantizes each normal component into this many buckets", NULL},
    {"spmis.search_steps", P_INT, F(spmis_search_steps), 0, SPMIS_MAX_SEARCH_STEPS, "12", NULL,
     "spmis: cell-search taps (004 Sec. 5.1; 0 = always the pixel's own cell)", NULL},
    {"spmis.search_radius", P_FLOAT, F(spmis_search_radius), 0, 4096, "30", NULL, "spmis: initial cell-search radius, pixels", NULL},
    {"spmis.search_growth", P_FLOAT, F(spmis_search_growth), 1, 16, "1.25", NULL, "spmis: cell-search radius factor per tap", NULL},
    {"spmis.search_normal", P_FLOAT, F(spmis_search_normal), -1, 1, "0.9", NULL,
     "spmis: a search tap is rejected when n . n_tap is below this (or on another object)", NULL},
    {"spmis.search", P_NAMES, F(spmis_search), 0, 0, "always", "sparse",
     "spmis: always (search for every pixel, 004 Sec. 5.1), sparse (BIASED: search only where the own "
     "cell has at most spmis.sparse_count contributing pixels, a count that depends on the samples) or "
     "low-confidence (unbiased: search only where the own cell's mean confidence is below "
     "spmis.search_confidence, e.g. after a disocclusion)",
     search_names},
    {"spmis.search_score", P_NAMES, F(spmis_search_score), 0, 0, "confidence", NULL,
     "spmis: what an accepted search tap's cell weighs: confidence (its confidence sum, 004 Sec. 5.1) or "
     "compat (ours, in neither paper: the confidence sum times 000's compatibility score, Eq. 14-15 with "
     "spatial.omega and spatial.beta, of the tapped pixel's primary hit with the pixel's, so the cell is "
     "chosen by sample compatibility too); both read only the G-buffer and confidences (unbiased)",
     search_score_names},
    {"spmis.sparse_count", P_INT, F(spmis_sparse_count), 0, 256, "2", NULL, "spmis: threshold of the sparse search", NULL},
    {"spmis.search_confidence", P_FLOAT, F(spmis_search_confidence), 0, 1e9, "4", NULL,
     "spmis: threshold of the low-confidence search (mean c of the own cell)", NULL},
    {"spmis.confidence_adjust", P_BOOL, F(spmis_confidence_adjust), 0, 1, "on", NULL,
     "spmis: scale non-canonical confidences by N / M (004 Sec. 4.3)", NULL},
    {"spmis.canonical_pick", P_NAMES, F(spmis_canonical_pick), 0, 0, "uniform", NULL,
     "spmis: canonical draws P_c uniform (004) or proportional to confidence", pick_names},
    {"spmis.confidence_update", P_NAMES, F(spmis_confidence_update), 0, 0, "cell", NULL,
     "spmis: the confidence a merge stores (004 leaves it open), capped by confidence_cap: cell (c_c + min(1, "
     "N / M) c_Sigma, the cell's mean confidence per draw) or drawn (c_c + the confidences of the distinct pixels "
     "drawn, as one public implementation); unbiased either way (confidences only weight later merges)",
     confidence_update_names},
    {"pt.candidates", P_INT, F(pt_candidates), 1, 64, "1", NULL, "restir-pt: initial paths resampled per pixel", NULL},
    {"shift", P_SHIFT, F(shift), 0, 0, "hybrid", NULL,
     "restir-pt shift mapping: hybrid (replay until two rough, distant vertices, then reconnect), "
     "reconnection (at the secondary vertex), replay (whole prefix; reconnects only at the light)", NULL},
    {"shift.roughness", P_FLOAT, F(shift_roughness), 0, 1, "0.2", NULL, "hybrid shift: GGX alpha at or above which a vertex is rough", NULL},
    {"shift.distance", P_FLOAT, F(shift_distance), 0, 1e9, "0.01", NULL,
     "hybrid shift: minimum reconnection length, in shift.distance_mode's measure", NULL},
    {"shift.distance_mode", P_NAMES, F(shift_distance_mode), 0, 0, "scene", NULL,
     "hybrid shift: shift.distance is a fraction of the scene diagonal (scene; 1% of a 400 m ground plane "
     "is 5.66 m on the forest), a length in scene units (absolute), or a fraction of the camera's distance to "
     "the segment's first vertex (relative: every domain judges with its own camera, so shifts stay "
     "invertible); unbiased either way",
     distance_mode_names},
    {"gi.radiance", P_NAMES, F(gi_radiance), 0, 0, "reevaluate", "stored",
     "restir-gi: the outgoing radiance of a reused sample point toward the reusing shading point: reevaluate "
     "(the sample point's path estimate traced again from its own random numbers) or stored (the radiance it "
     "sent toward the pixel that traced it, as Ouyang et al. 2021; BIASED where the sample point is glossy)",
     gi_radiance_names},
    {"grad.spatial", P_NAMES, F(grad_spatial), 0, 0, "adaptive", NULL,
     "grestir-pt spatial reuse of paired-pixel samples: off, dense (a similar random pair for every pair) "
     "or adaptive (edge pairs only, 002 Sec. 4.3.2); the search reads only the G-buffer (unbiased)",
     grad_spatial_names},
    {"grad.temporal", P_BOOL, F(grad_temporal), 0, 1, "on", NULL,
     "grestir-pt: temporal reuse of paired-pixel reservoirs (needs temporal=on; off isolates the gradient "
     "pass's history from the primal's)", NULL},
    {"grad.base", P_NAMES, F(grad_base), 0, 0, "independent", NULL,
     "grestir-pt: the pairs' initial paths: independent (their own initial pass, as the public 002 code) or "
     "shared (the primal's initial paths: no extra paths, but primal and gradient errors correlate, which the "
     "solve does not smooth away); unbiased either way",
     base_names},
    {"grad.positivize", P_BOOL, F(grad_positivize), 0, 1, "on", NULL,
     "grestir-pt: separate reservoirs for the positive and negative gradient parts (002 Eq. 23-26)", NULL},
    {"grad.cross_sign", P_BOOL, F(grad_cross_sign), 0, 1, "off", NULL,
     "grestir-pt: r+ and r- also resample the neighbor's reservoir of the other sign (002 Sec. 4.4 ablation)",
     NULL},
    {"grad.search", P_INT, F(grad_search), 1, 4096, "256", NULL, "grestir-pt: random neighbor pairs tried per pair (N)", NULL},
    {"grad.radius", P_FLOAT, F(grad_radius), 1, 512, "4", NULL, "grestir-pt: pair-search radius in pixels", NULL},
    {"grad.inner_jacobian_ratio", P_FLOAT, F(grad_inner_jacobian_ratio), 0, 1e30, "0", NULL,
     "grestir-pt: reject an outer shift when the path's inner-shift Jacobians before and after it differ by more "
     "than this factor or one of them is undefined, as 002's public code does with 10 (0: off); the rule is "
     "symmetric, so the reverse shift is rejected too and reuse stays unbiased (render.gradient_unbiased)", NULL},
    {"grad.edge_albedo", P_FLOAT, F(grad_edge_albedo), 0, 1e30, "0.1", NULL, "edge pair: max albedo difference above", NULL},
    {"grad.edge_normal", P_FLOAT, F(grad_edge_normal), -1, 1, "0.9", NULL,
     "edge pair: n_a . n_b below this (the paper's text says '>', which cannot mark an edge)", NULL},
    {"grad.edge_depth", P_FLOAT, F(grad_edge_depth), 0, 1e30, "0.1", NULL, "edge pair: |d_a - d_b| / d_a above", NULL},
    {"recon", P_NAMES, F(recon), 0, 0, "l2", "l1",
     "gradient methods: which screened Poisson solve fills the image: l2 (unbiased: linear in unbiased "
     "inputs), l1 (BIASED: iteratively reweighted, robust to outliers) or both (image = L2, L1 as a layer)",
     recon_names},
    {"recon.alpha", P_FLOAT, F(recon_alpha), 1e-6, 1e6, "0.2", NULL, "screened Poisson: weight alpha of the primal term", NULL},
    {"recon.solver", P_NAMES, F(recon_solver), 0, 0, "dct", NULL,
     "L2 solver: dct (direct, exact) or cg (conjugate gradient to a relative residual of 1e-6, or recon.iterations "
     "steps)", solver_names},
    {"recon.iterations", P_INT, F(recon_iterations), 0, 100000, "0", NULL,
     "L2 with recon.solver=cg: 0 solves to a relative residual of 1e-6; N stops after exactly N CG steps from the "
     "primal, as 002's public code and Kettunen et al. do (BIASED: a truncated CG is not linear in its noisy "
     "inputs; measured in docs/BENCHMARKS.md)", NULL},
    {"recon.l1_iterations", P_INT, F(recon_l1_iterations), 1, 1000, "20", NULL, "L1: IRLS reweighting iterations", NULL},
    {"recon.l1_precond", P_NAMES, F(recon_l1_precond), 0, 0, "multigrid", NULL,
     "L1: preconditioner of the inner CG: multigrid (V-cycle) or jacobi (the public G-PT solver's kind)", precond_names},
    {"recon.l1_cg", P_INT, F(recon_l1_cg), 0, 100000, "0", NULL,
     "L1: conjugate-gradient steps per reweighting; 0: the preconditioner's default (multigrid 4, jacobi 50)", NULL},
    {"denoise", P_NAMES, F(denoise.method), 0, 0, "off", NULL,
     "denoise the finished frame into a layer of its own (frame_NNNN_denoised.exr / .png, and errors after "
     "denoising in compare and study): off, svgf (Schied et al. 2017: temporal accumulation, variance "
     "estimate, 5 edge-stopping a-trous iterations on albedo-demodulated illumination, temporal antialiasing) or "
     "atrous (Dammertz et "
     "al. 2010, spatial only); the denoised layer is BIASED by nature, the frame itself is unchanged; methods "
     "without a G-buffer (pt, gpt) trace one for it through pixel centres",
     denoise_names},
    {"denoise.svgf.alpha", P_FLOAT, F(denoise.svgf_alpha), 1e-4, 1, "0.2", NULL,
     "svgf: colour's moving-average weight (Sec. 4.1)", NULL},
    {"denoise.svgf.moments_alpha", P_FLOAT, F(denoise.svgf_moments_alpha), 1e-4, 1, "0.2", NULL,
     "svgf: luminance moments' moving-average weight", NULL},
    {"denoise.svgf.sigma_depth", P_FLOAT, F(denoise.svgf_sigma_depth), 1e-6, 1e6, "1", NULL,
     "svgf: sigma_z, the depth weight's scale on the depth gradient (Eq. 3)", NULL},
    {"denoise.svgf.sigma_normal", P_FLOAT, F(denoise.svgf_sigma_normal), 0, 4096, "128", NULL,
     "svgf: sigma_n, the power of max(0, n_p . n_q) (Eq. 4)", NULL},
    {"denoise.svgf.sigma_luminance", P_FLOAT, F(denoise.svgf_sigma_lum), 1e-6, 1e6, "4", NULL,
     "svgf: sigma_l, the luminance weight's scale on the filtered standard deviation (Eq. 5)", NULL},
    {"denoise.svgf.luminance_weight", P_NAMES, F(denoise.svgf_lum_weight), 0, 0, "symmetric", NULL,
     "svgf: whose standard deviation scales Eq. 5's luminance difference: symmetric, the mean of the centre's and "
     "the tap's, so that a bright outlier gives its energy to the neighbours that take it in; paper, the "
     "centre's alone, which drops outliers' energy (many-lights, restir-di: denoised image 2% darker; "
     "docs/DENOISE.md)",
     svgf_lum_weight_names},
    {"denoise.svgf.iterations", P_INT, F(denoise.svgf_iterations), 0, 12, "5", NULL, "svgf: a-trous iterations", NULL},
    {"denoise.svgf.kernel", P_NAMES, F(denoise.svgf_kernel), 0, 0, "5x5", NULL,
     "svgf: the a-trous kernel: 5x5, the paper's B3 spline (Sec. 4.3), or 3x3, (1 2 1) / 4 per axis, which "
     "takes 9 taps instead of 25 and reaches half as far: a deviation for speed, its error after denoising "
     "measured in docs/DENOISE.md",
     svgf_kernel_names},
    {"denoise.svgf.feedback", P_INT, F(denoise.svgf_feedback), 0, 12, "1", NULL,
     "svgf: the a-trous iteration whose output is the next frame's colour history (0: the unfiltered "
     "accumulation)", NULL},
    {"denoise.svgf.variance_frames", P_INT, F(denoise.svgf_variance_frames), 0, 255, "4", NULL,
     "svgf: histories shorter than this estimate variance spatially (7x7, Sec. 4.2)", NULL},
    {"denoise.svgf.normal", P_FLOAT, F(denoise.svgf_normal_min), -1, 1, "0.9", NULL,
     "svgf: history rejected where n . n_prev is below", NULL},
    {"denoise.svgf.plane", P_FLOAT, F(denoise.svgf_plane_max), 0, 1e30, "0.01", NULL,
     "svgf: history rejected where the plane distance exceeds this times the depth", NULL},
    {"denoise.svgf.taa", P_FLOAT, F(denoise.svgf_taa_alpha), 1e-3, 1, "0.1", NULL,
     "svgf: temporal antialiasing after remodulation (Schied et al. Sec. 4's last step; Karis 2014: the "
     "reprojected output blended with this weight of the new frame, or 1 / frames while the pixel's history "
     "is shorter; 1: off); it integrates the pixel area the jittered primary rays cover, which the "
     "feature-tested history cannot where a pixel straddles an edge",
     NULL},
    {"denoise.svgf.taa_motion", P_FLOAT, F(denoise.svgf_taa_motion), 0, 1e6, "0.5", NULL,
     "svgf: the antialiasing's history only where the pixel moved at most this many pixels since the last "
     "frame; under camera motion the history lets light bleed across silhouettes (docs/DENOISE.md); 1e6: "
     "everywhere, as Karis 2014",
     NULL},
    {"denoise.svgf.taa_clamp", P_NAMES, F(denoise.svgf_taa_clamp), 0, 0, "moving", NULL,
     "svgf: where the antialiasing's history is clamped to this frame's 3x3 neighbourhood (Karis 2014), "
     "against change: moving, on the pixels that moved since the last frame (nothing changes under a "
     "still pixel of a static scene); always, as Karis, which also drops sub-pixel emitters' energy "
     "whenever no sample of the 3x3 block hits them (many-lights: 4% darker, docs/DENOISE.md); off",
     svgf_taa_clamp_names},
    {"denoise.atrous.iterations", P_INT, F(denoise.atrous_iterations), 0, 12, "5", NULL, "atrous: iterations", NULL},
    {"denoise.atrous.sigma_color", P_FLOAT, F(denoise.atrous_sigma_color), 1e-6, 1e6, "1", NULL,
     "atrous: sigma_rt in units of the frame's mean illumination, halved per iteration", NULL},
    {"denoise.atrous.sigma_normal", P_FLOAT, F(denoise.atrous_sigma_normal), 1e-6, 1e6, "0.3", NULL,
     "atrous: sigma_n on |n_p - n_q|", NULL},
    {"denoise.atrous.sigma_position", P_FLOAT, F(denoise.atrous_sigma_position), 1e-6, 1e6, "0.05", NULL,
     "atrous: sigma_x on |x_p - x_q| as a fraction of the pixel's depth", NULL},
};
#undef F
#define NUM_PARAMS (sizeof(params) / sizeof(params[0]))

static int parse_value(const struct param_def *d, const char *val, struct render_params *p, char *msg)
{
    char *base = (char *)p + d->offset;
    if (d->type == P_MIS) {
        if (restir_mis_parse(val, (enum restir_mis *)(void *)base) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown MIS '%s' (pairwise, balance, 1/M)", d->key, val);
            return -1;
        }
        return 0;
    }
    if (d->type == P_SHIFT) {
        if (shift_kind_parse(val, (enum shift_kind *)(void *)base) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown shift '%s' (hybrid, reconnection, replay)", d->key, val);
            return -1;
        }
        return 0;
    }
    if (d->type == P_NAMES) {
        int k = name_index(d->names, val);
        if (k < 0) {
            char list[128] = "";
            for (int j = 0; d->names[j]; j++)
                snprintf(list + strlen(list), sizeof(list) - strlen(list), "%s%s", j ? ", " : "", d->names[j]);
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown value '%s' (%s)", d->key, val, list);
            return -1;
        }
        *(int *)(void *)base = k; /* P_NAMES fields are int-sized enums with values 0, 1, ... */
        return 0;
    }
    if (d->type == P_COUNT && (!strcmp(val, "M") || !strcmp(val, "all"))) {
        *(int *)(void *)base = 0;
        return 0;
    }
    if (d->type == P_PRESET) {
        /* 000 Table 1: FAST (K 32, R 30), BALANCED (K 32, R 50), CONSERVATIVE (K 32, R 100). */
        static const float radii[] = {30.0f, 50.0f, 100.0f};
        int k = name_index(preset_names, val);
        if (k < 0) {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: unknown preset '%s' (fast, balanced, conservative)", d->key,
                     val);
            return -1;
        }
        p->spatial_select = SELECT_COMPAT;
        p->spatial_candidates = 32;
        p->spatial_radius = radii[k];
        return 0;
    }
    if (d->type == P_BOOL) {
        int v;
        if (!strcmp(val, "on") || !strcmp(val, "1") || !strcmp(val, "true"))
            v = 1;
        else if (!strcmp(val, "off") || !strcmp(val, "0") || !strcmp(val, "false"))
            v = 0;
        else {
            snprintf(msg, RESTIR_MSG_LEN, "--set %s: expected on or off, got '%s'", d->key, val);
            return -1;
        }
        *(int *)(void *)base = v;
        return 0;
    }
    errno = 0;
    char *end = NULL;
    double v = strtod(val, &end);
    if (end == val || *end != '\0' || errno != 0 || !isfinite(v)) {
        snprintf(msg, RESTIR_MSG_LEN, "--set %s: '%s' is not a number", d->key, val);
        return -1;
    }
    if (v < d->lo || v > d->hi || (d->type != P_FLOAT && v != floor(v))) {
        snprintf(msg, RESTIR_MSG_LEN, "--set %s: %s is out of range (%s in [%g, %g]%s)", d->key, val,
                 d->type == P_FLOAT ? "number" : "integer", d->lo, d->hi, d->type == P_COUNT ? " or M" : "");
        return -1;
    }
    if (d->type == P_INT || d->type == P_COUNT)
        *(int *)(void *)base = (int)v;
    else
        *(float *)(void *)base = (float)v;
    return 0;
}

void render_params_defaults(struct render_params *p)
{
    memset(p, 0, sizeof(*p));
    /* What the command line sets by options of its own (--res, --seed, --threads, --camera). */
    p->width = 640;
    p->height = 360;
    p->seed = 1;
    p->threads = 0;
    p->camera_path = 0;
    char msg[RESTIR_MSG_LEN];
    for (size_t i = 0; i < NUM_PARAMS; i++)
        if (params[i].def)
            RESTIR_CHECK(parse_value(&params[i], params[i].def, p, msg) == 0);
}

int render_params_set(struct render_params *p, const char *assignment, char *msg)
{
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment) {
        snprintf(msg, RESTIR_MSG_LEN, "--set expects key=value, got '%s'", assignment);
        return -1;
    }
    size_t klen = (size_t)(eq - assignment);
    for (size_t i = 0; i < NUM_PARAMS; i++) {
        if (strlen(params[i].key) == klen && strncmp(params[i].key, assignment, klen) == 0)
            return parse_value(&params[i], eq + 1, p, msg);
    }
    snprintf(msg, RESTIR_MSG_LEN, "--set: unknown key '%.*s' (see restir render --help)", (int)klen, assignment);
    return -1;
}

int render_params_set_list(struct render_params *p, const char *list, char *msg)
{
    char buf[1024];
    if (strlen(list) >= sizeof(buf)) {
        snprintf(msg, RESTIR_MSG_LEN, "settings '%.40s...' are longer than %zu characters", list, sizeof(buf) - 1);
        return -1;
    }
    snprintf(buf, sizeof(buf), "%s", list);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ":", &save); tok; tok = strtok_r(NULL, ":", &save))
        if (render_params_set(p, tok, msg) != 0)
            return -1;
    return 0;
}

int render_params_validate(const struct render_params *p, char *msg)
{
    if (p->width < 1 || p->height < 1 || p->width > 16384 || p->height > 16384 ||
        (long long)p->width * p->height > 64ll * 1024 * 1024) {
        snprintf(msg, RESTIR_MSG_LEN, "resolution %dx%d is out of range (1..16384 per side, 64 Mpixel total)",
                 p->width, p->height);
        return -1;
    }
    if (p->light_candidates + p->bsdf_candidates < 1) {
        snprintf(msg, RESTIR_MSG_LEN, "di.light_candidates + di.bsdf_candidates must be at least 1");
        return -1;
    }
    if (p->grad_inner_jacobian_ratio > 0.0f && p->grad_inner_jacobian_ratio < 1.0f) {
        snprintf(msg, RESTIR_MSG_LEN, "grad.inner_jacobian_ratio = %g: 0 (off) or a factor of at least 1",
                 (double)p->grad_inner_jacobian_ratio);
        return -1;
    }
    if (p->recon_iterations > 0 && p->recon_solver != RESTIR_POISSON_CG) {
        snprintf(msg, RESTIR_MSG_LEN, "recon.iterations = %d needs recon.solver=cg (dct solves exactly)",
                 p->recon_iterations);
        return -1;
    }
    if (p->denoise.svgf_feedback > p->denoise.svgf_iterations) {
        snprintf(msg, RESTIR_MSG_LEN, "denoise.svgf.feedback = %d exceeds denoise.svgf.iterations = %d",
                 p->denoise.svgf_feedback, p->denoise.svgf_iterations);
        return -1;
    }
    if (p->ratio_lo > p->ratio_hi) {
        snprintf(msg, RESTIR_MSG_LEN, "temporal.ratio_lo (%g) exceeds temporal.ratio_hi (%g)", p->ratio_lo,
                 p->ratio_hi);
        return -1;
    }
    if (p->temporal_reuse != TEMPORAL_BACKPROJECT && !p->jitter) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.reuse=%s needs jitter=on: a splatted path lands anywhere inside its new pixel, which "
                 "only a pixel integrated over its area (jitter) can receive",
                 p->temporal_reuse == TEMPORAL_SPLAT ? "splat" : "both");
        return -1;
    }
    if (p->temporal_subpixel == TEMPORAL_SUBPIXEL_SEARCH && (!p->jitter || p->temporal_reuse != TEMPORAL_BACKPROJECT)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.subpixel=search needs jitter=on and temporal.reuse=backproject: it searches the previous "
                 "pixels a pixel's area overlaps, and splatted paths are not backprojected");
        return -1;
    }
    /* Every key's range or names, also for values set other than through --set (options of their
     * own such as --spp, a study's radii, a method's defaults). */
    for (size_t i = 0; i < NUM_PARAMS; i++) {
        const struct param_def *d = &params[i];
        const char *base = (const char *)p + d->offset;
        if (d->type == P_INT || d->type == P_COUNT || d->type == P_BOOL || d->type == P_FLOAT) {
            double v = d->type == P_FLOAT ? (double)*(const float *)(const void *)base : *(const int *)(const void *)base;
            if (!(v >= d->lo && v <= d->hi) && !(d->type == P_COUNT && v == 0.0)) {
                snprintf(msg, RESTIR_MSG_LEN, "%s = %g is out of range [%g, %g]", d->key, v, d->lo, d->hi);
                return -1;
            }
        } else if (d->type == P_NAMES) {
            int k = *(const int *)(const void *)base, count = 0;
            while (d->names[count])
                count++;
            if (k < 0 || k >= count) {
                snprintf(msg, RESTIR_MSG_LEN, "%s = %d is not one of its %d values", d->key, k, count);
                return -1;
            }
        }
    }
    return 0;
}

/* The shortest %g spelling of v (at least 6 digits) that --set parses back to v exactly, so that
 * settings written to summary.json reproduce the run bit for bit. */
static void format_float(float v, char *val, size_t n)
{
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(val, n, "%.*g", digits, v);
        if ((float)strtod(val, NULL) == v)
            return;
    }
}

/* The value of d's field in p as --set spells it. */
static void format_value(const struct param_def *pd, const struct render_params *p, char *val, size_t n)
{
    const char *base = (const char *)p + pd->offset;
    switch (pd->type) {
    case P_INT: snprintf(val, n, "%d", *(const int *)(const void *)base); break;
    case P_FLOAT: format_float(*(const float *)(const void *)base, val, n); break;
    case P_BOOL: snprintf(val, n, "%s", *(const int *)(const void *)base ? "on" : "off"); break;
    case P_MIS: snprintf(val, n, "%s", restir_mis_name(*(const enum restir_mis *)(const void *)base)); break;
    case P_SHIFT: snprintf(val, n, "%s", shift_kind_name(*(const enum shift_kind *)(const void *)base)); break;
    case P_COUNT: {
        int v = *(const int *)(const void *)base;
        snprintf(val, n, v ? "%d" : "M", v);
        break;
    }
    case P_NAMES: snprintf(val, n, "%s", pd->names[*(const int *)(const void *)base]); break;
    case P_PRESET: snprintf(val, n, "-"); break;
    }
}

int render_params_get(const struct render_params *p, const char *key, char *val, size_t n)
{
    for (size_t i = 0; i < NUM_PARAMS; i++) {
        if (!strcmp(params[i].key, key)) {
            format_value(&params[i], p, val, n);
            return 0;
        }
    }
    val[0] = '\0';
    return -1;
}

void render_params_help(FILE *out)
{
    struct render_params d;
    render_params_defaults(&d);
    for (size_t i = 0; i < NUM_PARAMS; i++) {
        char val[32];
        format_value(&params[i], &d, val, sizeof(val));
        fprintf(out, "  %-26s %-11s %s", params[i].key, val, params[i].help);
        if (params[i].biased)
            fprintf(out, " [%s=%s is BIASED]", params[i].key, params[i].biased);
        fputc('\n', out);
    }
}

const char *render_params_key(size_t i)
{
    /* shorthands (spatial.preset) set other keys and have no value of their own */
    for (size_t k = 0; k < NUM_PARAMS; k++)
        if (params[k].def && i-- == 0)
            return params[k].key;
    return NULL;
}

int render_params_biased(const struct render_params *p, char *out, size_t n)
{
    int count = 0;
    if (n > 0)
        out[0] = '\0';
    for (size_t i = 0; i < NUM_PARAMS; i++) {
        if (!params[i].biased)
            continue;
        char val[32];
        format_value(&params[i], p, val, sizeof(val));
        if (strcmp(val, params[i].biased) != 0)
            continue;
        size_t used = strlen(out);
        snprintf(out + used, n - used, "%s%s=%s", count ? ", " : "", params[i].key, val);
        count++;
    }
    return count;
}
