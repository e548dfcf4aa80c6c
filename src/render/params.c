/* params.c: the toolkit's settings blocks (settings_block.h): the image, the path walk's depth,
 * roulette, sampler and lights, reuse, SPMIS cells, the shift mapping, the scene, the ray tracer and
 * the camera (the denoiser's block is in params_denoise.c). Every method's own block is in its
 * folder; the registry (methods/settings.h) reads them all. Must never depend on the ray tracer or
 * render passes. */
#include "render/params.h"

#include <stddef.h>
#include <stdio.h>

#include "core/check.h"
#include "restir/cells.h"
#include "restir/spmis.h"

static const char *const select_names[] = {"bitterli", "compat", "compat-binary", NULL};
static const char *const reuse_names[] = {"standard", "spmis", NULL};
static const char *const search_names[] = {"always", "sparse", "low-confidence", NULL};
static const char *const pick_names[] = {"uniform", "confidence", NULL};
static const char *const distance_mode_names[] = {"scene", "absolute", "relative", NULL}; /* shift_kind.h */
static const char *const confidence_update_names[] = {"cell", "drawn", NULL}; /* enum spmis_confidence_update */
static const char *const search_score_names[] = {"confidence", "compat", NULL}; /* enum restir_cells_score */
static const char *const history_names[] = {"spatial", "temporal", NULL};
static const char *const temporal_reuse_names[] = {"backproject", "splat", "both", NULL};
static const char *const temporal_subpixel_names[] = {"wrap", "search", NULL}; /* enum temporal_subpixel_mode */
static const char *const missing_texture_names[] = {"error", "warn", NULL};
static const char *const sampler_names[] = {"independent", "sobol", NULL}; /* enum pt_sampler */
static const char *const light_sampling_names[] = {"area", "solid-angle", "auto", NULL}; /* enum light_sampling */
static const char *const light_selection_names[] = {"power", "bvh", NULL};        /* enum light_selection */
static const char *const light_env_names[] = {"map", "compensated", NULL};        /* enum light_env_sampling */
static const char *const preset_names[] = {"fast", "balanced", "conservative", NULL};

/* P_NAMES fields are written through int pointers. */
_Static_assert(sizeof(enum spatial_select_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum spatial_reuse_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum spmis_search_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum spmis_confidence_update) == sizeof(int), "enum size");
_Static_assert(sizeof(enum restir_cells_score) == sizeof(int), "enum size");
_Static_assert(sizeof(enum temporal_reuse_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum light_sampling) == sizeof(int), "enum size");
_Static_assert(sizeof(enum light_selection) == sizeof(int), "enum size");
_Static_assert(sizeof(enum light_env_sampling) == sizeof(int), "enum size");

#define F(field) offsetof(struct render_params, field)
#define R(field) offsetof(struct reuse_settings, field)
#define S(field) offsetof(struct spmis_settings, field)
#define H(field) offsetof(struct shift_settings, field)

/* spatial.preset, 000 Table 1: FAST (K 32, R 30), BALANCED (K 32, R 50), CONSERVATIVE (K 32, R 100). */
static void apply_preset(void *block, int k)
{
    static const float radii[] = {30.0f, 50.0f, 100.0f};
    struct reuse_settings *r = block;
    r->spatial_select = SELECT_COMPAT;
    r->spatial_candidates = 32;
    r->spatial_radius = radii[k];
}

static const struct param_def spp_rows[] = {
    {"spp", P_INT, F(spp), 1, 1 << 20, "1", NULL, "paths per pixel per frame", NULL},
};
static const struct param_def image_rows[] = {
    {"jitter", P_BOOL, F(jitter), 0, 1, "on", NULL, "jitter primary rays over the pixel (integrates the box filter)",
     NULL},
};
static const struct param_def depth_rows[] = {
    {"pt.max_bounces", P_INT, F(max_bounces), 1, 64, "8", NULL,
     "maximum scattering events of a path (1 = direct lighting; set for you when comparing DI methods)", NULL},
};
static const struct param_def roulette_rows[] = {
    {"pt.rr_bounces", P_INT, F(rr_bounces), 0, 1024, "3", NULL, "Russian roulette after this many bounces", NULL},
};
static const struct param_def sampler_rows[] = {
    {"sampler", P_NAMES, F(sampler), 0, 0, "sobol", NULL,
     "pt's random numbers: independent (PCG32 streams) or sobol (Owen-scrambled Sobol' points, a (0,2)-net per "
     "dimension pair over each frame's samples in a pixel; unbiased, independent across seeds and frames)",
     sampler_names},
};
static const struct param_def lights_rows[] = {
    {"lights.sample", P_NAMES, F(light_sampling), 0, 0, "area", NULL,
     "next-event estimation's point on the chosen emitting triangle in every path walk: area (uniform on it), "
     "solid-angle (uniform in the solid angle it subtends, Arvo 1995; a triangle that is half of a rectangle draws "
     "over the whole rectangle, Urena et al. 2013; area where the emitter subtends less than 0.02 sr) or auto "
     "(solid angle only where the area density would vary over the emitter by 8x or more, (d_max / d_min)^3 for "
     "its farthest and closest points, as under a large lamp close to a surface; area elsewhere, where a "
     "solid-angle point costs about 100 ns more for little less variance), with the matching density in NEE and in "
     "the MIS weight of BSDF-sampled hits; unbiased either way",
     light_sampling_names},
    {"lights.select", P_NAMES, F(light_selection), 0, 0, "bvh", NULL,
     "next-event estimation's choice of emitting triangle in every path walk: power (in proportion to its power, one "
     "alias table) or bvh (down the emitters' BVH by each node's importance at the shading point from its power, "
     "distance and orientation bounds, Conty Estevez & Kulla 2018), with the matching probability in NEE and in "
     "the MIS weight of BSDF-sampled hits; unbiased either way",
     light_selection_names},
    {"lights.env", P_NAMES, F(light_env), 0, 0, "compensated", NULL,
     "next-event estimation's directions toward an environment map in every path walk: map (in proportion to the map's "
     "luminance) or compensated (in proportion to its luminance above the map's mean, MIS compensation, Karlik et "
     "al. 2019: BSDF sampling, which every walk combines with it by MIS, covers the rest; the map's distribution "
     "where nothing is above the mean, as for a constant sky); unbiased either way",
     light_env_names},
};
static const struct param_def reuse_rows[] = {
    {"temporal", P_BOOL, R(temporal), 0, 1, "on", NULL, "temporal reuse on/off", NULL},
    {"spatial", P_BOOL, R(spatial), 0, 1, "on", NULL, "spatial reuse on/off", NULL},
    {"spatial.neighbors", P_INT, R(spatial_neighbors), 0, 5, "0", NULL,
     "spatial neighbors tried per pixel (0: the method's default, 1 for DI reservoirs, 3 for path reservoirs)", NULL},
    {"spatial.radius", P_FLOAT, R(spatial_radius), 1, 512, "30", NULL, "spatial reuse disk radius in pixels", NULL},
    {"spatial.select", P_NAMES, R(spatial_select), 0, 0, "bitterli", NULL,
     "neighbor selection: bitterli (uniform tries, 000 Eq. 7), compat (000 Algorithm 1, Eq. 14 scores), "
     "compat-binary (Algorithm 1 with Eq. 7 as score); all read only the G-buffer (unbiased)",
     select_names},
    {"spatial.preset", P_PRESET, 0, 0, 0, NULL, NULL,
     "000 presets: fast (compat, R 30, K 32), balanced (R 50), conservative (R 100)", preset_names},
    {"spatial.candidates", P_INT, R(spatial_candidates), 1, 4096, "32", NULL, "compat: candidates K per pixel", NULL},
    {"spatial.omega", P_FLOAT, R(spatial_omega), 1e-9, 12.57, "0.05", NULL,
     "compat: solid angle Omega of the position scale (Eq. 15)", NULL},
    {"spatial.beta", P_FLOAT, R(spatial_beta), 0, 1e3, "8", NULL, "compat: normal exponent beta (Eq. 15)", NULL},
    {"spatial.early_stop", P_BOOL, R(spatial_early_stop), 0, 1, "on", NULL,
     "compat: stop once more than M candidates score above 0.5 (000 Sec. 5)", NULL},
    {"spatial.normal", P_FLOAT, R(spatial_normal), -1, 1, "0.5", NULL, "Bitterli test (000 Eq. 7): minimum n . n_i",
     NULL},
    {"spatial.depth", P_FLOAT, R(spatial_depth), 0, 1e30, "0.1", NULL, "Bitterli test (000 Eq. 7): max |d_i - d| / d",
     NULL},
    {"spatial.reuse", P_NAMES, R(spatial_reuse), 0, 0, "standard", NULL,
     "spatial reuse: standard (GRIS over the selected neighbors) or spmis (004 Algorithm 2: stochastic "
     "pairwise MIS over one reuse cell; unbiased)",
     reuse_names},
    {"history", P_NAMES, R(history_temporal), 0, 0, "spatial", NULL,
     "what the next frame reuses temporally: the spatial-reuse output (spatial, as Lin et al. 2022) or the "
     "temporal output before spatial reuse (temporal: spatial reuse then cannot feed back; unbiased either way)",
     history_names},
    {"confidence_cap", P_FLOAT, R(confidence_cap), 1, 1e9, "20", NULL, "cap on confidence weights c (M cap)", NULL},
    {"mis", P_MIS, R(mis), 0, 0, "pairwise", "1/M",
     "resampling MIS: pairwise (defensive, unbiased), balance (unbiased), 1/M (BIASED: ignores that "
     "domains cannot all produce every sample)",
     NULL},
    {"temporal.normal", P_FLOAT, R(temporal_normal), -1, 1, "0.8", NULL, "history rejected when n . n_prev is below",
     NULL},
    {"temporal.plane", P_FLOAT, R(temporal_plane), 0, 1e30, "0.05", NULL,
     "history rejected when the plane distance / depth is above", NULL},
    {"temporal.ratio_guard", P_BOOL, R(temporal_ratio_guard), 0, 1, "off", "on",
     "BIASED: reject history whose target ratio leaves [ratio_lo, ratio_hi] (001 Sec. 5)", NULL},
    {"temporal.ratio_lo", P_FLOAT, R(ratio_lo), 0, 1e30, "0.1", NULL, "target-ratio guard lower bound", NULL},
    {"temporal.ratio_hi", P_FLOAT, R(ratio_hi), 0, 1e30, "10", NULL, "target-ratio guard upper bound", NULL},
    {"temporal.subpixel", P_NAMES, R(temporal_subpixel), 0, 0, "wrap", NULL,
     "backprojected sub-pixel samples of path reservoirs (needs "
     "jitter=on and temporal.reuse=backproject): wrap (the previous pixel under the motion vector; a sample "
     "leaving the current pixel re-enters at its other side) or search (the 2x2 previous pixels the current "
     "pixel overlaps, each kept where its samples land inside it, Area ReSTIR Sec. 4.3.1; mis=pairwise "
     "then weighs each path against the one previous pixel that reaches it). Both unbiased",
     temporal_subpixel_names},
};
static const struct param_def path_history_rows[] = {
    {"temporal.reuse", P_NAMES, R(temporal_reuse), 0, 0, "backproject", NULL,
     "path reservoirs (refused by methods without them): backproject (the previous "
     "pixel under the backward motion vector, Area ReSTIR), splat (Liu et al. 2025: every previous "
     "reservoir lands where its primary hit is seen now; needs jitter=on), or both, combined by balance "
     "MIS (docs/RESTIR_PT.md); all unbiased with mis=pairwise or balance",
     temporal_reuse_names},
    {"temporal.splat_steps", P_INT, R(temporal_splat_steps), 1, 16, "2", NULL,
     "splat with camera.shutter > 0: each previous reservoir is splatted into this many shutter-time strata "
     "(1: it keeps its shutter time)", NULL},
};
static const struct param_def permutation_rows[] = {
    {"temporal.permutation", P_BOOL, R(temporal_permutation), 0, 1, "off", NULL,
     "the temporal neighbour through a per-frame pixel permutation (RTXDI's permutation sampling: the "
     "reprojected pixel mirrored inside 4 x 4 tiles whose grid shifts every frame; kept only where it shows "
     "the same surface, else the reprojected pixel itself), so that a pixel's history comes from a "
     "neighbour and errors decorrelate between frames; reads only G-buffers: unbiased",
     NULL},
};
static const struct param_def spmis_rows[] = {
    {"spmis.candidates", P_COUNT, S(candidates), 1, RESTIR_SPMIS_MAX_DRAWS, "3", NULL,
     "spmis: neighbor draws N (004 Eq. 15-17); M = deterministic pairwise over the whole cell", NULL},
    {"spmis.canonical_candidates", P_COUNT, S(canonical_candidates), 1, RESTIR_SPMIS_MAX_DRAWS, "1", NULL,
     "spmis: canonical-weight draws N_c (004 Eq. 18); M = the exact Eq. 11b sum", NULL},
    {"spmis.tile", P_INT, S(tile), 1, RESTIR_CELLS_MAX_TILE, "8", NULL,
     "spmis: reuse-cell tile edge in pixels (004 Sec. 5)", NULL},
    {"spmis.normal_bins", P_INT, S(normal_bins), 1, 64, "4", NULL,
     "spmis: cell key quantizes each normal component into this many buckets", NULL},
    {"spmis.search_steps", P_INT, S(search_steps), 0, SPMIS_MAX_SEARCH_STEPS, "12", NULL,
     "spmis: cell-search taps (004 Sec. 5.1; 0 = always the pixel's own cell)", NULL},
    {"spmis.search_radius", P_FLOAT, S(search_radius), 0, 4096, "30", NULL, "spmis: initial cell-search radius, pixels",
     NULL},
    {"spmis.search_growth", P_FLOAT, S(search_growth), 1, 16, "1.25", NULL, "spmis: cell-search radius factor per tap",
     NULL},
    {"spmis.search_normal", P_FLOAT, S(search_normal), -1, 1, "0.9", NULL,
     "spmis: a search tap is rejected when n . n_tap is below this (or on another object)", NULL},
    {"spmis.search", P_NAMES, S(search), 0, 0, "always", "sparse",
     "spmis: always (search for every pixel, 004 Sec. 5.1), sparse (BIASED: search only where the own "
     "cell has at most spmis.sparse_count contributing pixels, a count that depends on the samples) or "
     "low-confidence (unbiased: search only where the own cell's mean confidence is below "
     "spmis.search_confidence, e.g. after a disocclusion)",
     search_names},
    {"spmis.search_score", P_NAMES, S(search_score), 0, 0, "confidence", NULL,
     "spmis: what an accepted search tap's cell weighs: confidence (its confidence sum, 004 Sec. 5.1) or "
     "compat (ours, in neither paper: the confidence sum times 000's compatibility score, Eq. 14-15 with "
     "spatial.omega and spatial.beta, of the tapped pixel's primary hit with the pixel's, so the cell is "
     "chosen by sample compatibility too); both read only the G-buffer and confidences (unbiased)",
     search_score_names},
    {"spmis.sparse_count", P_INT, S(sparse_count), 0, 256, "2", NULL, "spmis: threshold of the sparse search", NULL},
    {"spmis.search_confidence", P_FLOAT, S(search_confidence), 0, 1e9, "4", NULL,
     "spmis: threshold of the low-confidence search (mean c of the own cell)", NULL},
    {"spmis.confidence_adjust", P_BOOL, S(confidence_adjust), 0, 1, "on", NULL,
     "spmis: scale non-canonical confidences by N / M (004 Sec. 4.3)", NULL},
    {"spmis.canonical_pick", P_NAMES, S(canonical_pick), 0, 0, "uniform", NULL,
     "spmis: canonical draws P_c uniform (004) or proportional to confidence", pick_names},
    {"spmis.confidence_update", P_NAMES, S(confidence_update), 0, 0, "cell", NULL,
     "spmis: the confidence a merge stores (004 leaves it open), capped by confidence_cap: cell (c_c + min(1, "
     "N / M) c_Sigma, the cell's mean confidence per draw) or drawn (c_c + the confidences of the distinct pixels "
     "drawn, as one public implementation); unbiased either way (confidences only weight later merges)",
     confidence_update_names},
};
static const struct param_def shift_rows[] = {
    {"shift", P_SHIFT, H(kind), 0, 0, "hybrid", NULL,
     "shift mapping of path reuse: hybrid (replay until two rough, distant vertices, then reconnect), "
     "reconnection (at the secondary vertex), replay (whole prefix; reconnects only at the light)",
     NULL},
    {"shift.roughness", P_FLOAT, H(roughness), 0, 1, "0.2", NULL,
     "hybrid shift: GGX alpha at or above which a vertex is rough", NULL},
    {"shift.distance", P_FLOAT, H(distance), 0, 1e9, "0.01", NULL,
     "hybrid shift: minimum reconnection length, in shift.distance_mode's measure", NULL},
    {"shift.distance_mode", P_NAMES, H(distance_mode), 0, 0, "scene", NULL,
     "hybrid shift: shift.distance is a fraction of the scene diagonal (scene; 1% of a 400 m ground plane "
     "is 5.66 m on the forest), a length in scene units (absolute), or a fraction of the camera's distance to "
     "the segment's first vertex (relative: every domain judges with its own camera, so shifts stay "
     "invertible); unbiased either way",
     distance_mode_names},
};
static const struct param_def scene_rows[] = {
    {"scene.shading_normals", P_BOOL, F(shading_normals), 0, 1, "on", NULL,
     "off: every triangle shades with its geometric normal (no vertex normals, no normal maps), as before "
     "the renderer read them. This CHANGES THE SCENE: for looking at what they do, never for comparing images", NULL},
    {"scene.alpha", P_BOOL, F(alpha_masks), 0, 1, "on", NULL,
     "off: every alpha-masked material (glTF alphaMode MASK or BLEND) is opaque. This CHANGES THE SCENE "
     "(leaf cards become quads): for measuring what the masks cost, never for comparing images", NULL},
    {"scene.missing_textures", P_NAMES, F(missing_textures_warn), 0, 0, "error", NULL,
     "a texture a scene file names that cannot be read: error (refuse the scene, naming the file) or warn "
     "(say so on stderr and use the material's factor instead of the map)",
     missing_texture_names},
    {"scene.strict", P_BOOL, F(scene_strict), 0, 1, "off", NULL,
     "a mesh file that loads only in part (faces assimp dropped, a material it made up, degenerate triangles, "
     "points or lines we skipped): off says what on stderr and in scene info and renders the rest; on refuses "
     "the file with that message",
     NULL},
};
static const struct param_def trace_rows[] = {
    {"rays.streams", P_BOOL, F(ray_streams), 0, 1, "on", NULL,
     "trace the G-buffer's camera rays and restir-di's shadow rays tile by tile as Embree streams "
     "(rtcIntersect1M / rtcOccluded1M); off: one Embree call per ray. The same images either way, only the "
     "time differs (docs/BENCHMARKS.md, the section on Embree streams). Applied when the scene is loaded, so "
     "in `restir compare` the command's --set value counts, not a per-spec one", NULL},
    {"simd", P_BOOL, F(simd), 0, 1, "on", NULL,
     "vector kernels (initial RIS candidates, restir-di merge targets across pixels): on = AVX2 where the "
     "CPU has it, chosen at run time; off = the build's baseline (SSE2 on x86-64). The same images either "
     "way, only the time differs", NULL},
};
static const struct param_def camera_rows[] = {
    {"camera.shutter", P_FLOAT, F(camera_shutter), 0, 1, "0", NULL,
     "motion blur: the shutter is open for this fraction of a frame before each frame's instant, while the "
     "camera moves from the previous frame's pose (0: off; refused by methods whose samples do not carry the primary "
     "ray)",
     NULL},
    {"camera.aperture", P_FLOAT, F(camera_aperture), 0, 1e30, "0", NULL,
     "depth of field: thin-lens aperture radius in scene units (0: the scene camera's, a pinhole unless its "
     "file sets aperture; refused by methods whose samples do not carry the primary ray)",
     NULL},
    {"camera.focus_distance", P_FLOAT, F(camera_focus), 0, 1e30, "0", NULL,
     "thin lens: distance of the plane in focus along the view direction (0: the scene camera's "
     "focus_distance, else the distance to its look_at point)",
     NULL},
};

static int reuse_validate(const struct render_params *p, const void *block, char *msg)
{
    const struct reuse_settings *r = block;
    if (r->ratio_lo > r->ratio_hi) {
        snprintf(msg, RESTIR_MSG_LEN, "temporal.ratio_lo (%g) exceeds temporal.ratio_hi (%g)", r->ratio_lo,
                 r->ratio_hi);
        return -1;
    }
    if (r->temporal_subpixel == TEMPORAL_SUBPIXEL_SEARCH && (!p->jitter || r->temporal_reuse != TEMPORAL_BACKPROJECT)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.subpixel=search needs jitter=on and temporal.reuse=backproject: it searches the previous "
                 "pixels a pixel's area overlaps, and splatted paths are not backprojected");
        return -1;
    }
    return 0;
}

static int path_history_validate(const struct render_params *p, const void *block, char *msg)
{
    const struct reuse_settings *r = block;
    if (r->temporal_reuse != TEMPORAL_BACKPROJECT && !p->jitter) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.reuse=%s needs jitter=on: a splatted path lands anywhere inside its new pixel, which "
                 "only a pixel integrated over its area (jitter) can receive",
                 r->temporal_reuse == TEMPORAL_SPLAT ? "splat" : "both");
        return -1;
    }
    return 0;
}

/* The permutation moves the backprojected pixel; splatted history and the 2x2 search have none. */
static int permutation_validate(const struct render_params *p, const void *block, char *msg)
{
    const struct reuse_settings *r = block;
    (void)p;
    if (r->temporal_permutation && (r->temporal_reuse != TEMPORAL_BACKPROJECT || r->temporal_subpixel != TEMPORAL_SUBPIXEL_WRAP)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.permutation=on permutes the backprojected pixel: it needs temporal.reuse=backproject "
                 "and temporal.subpixel=wrap");
        return -1;
    }
    return 0;
}

#define TOOLKIT_BLOCK(var, name, common, base, validate)                                                            \
    const struct param_block params_block_##var = {name, var##_rows, sizeof(var##_rows) / sizeof(var##_rows[0]),   \
                                                   base, 0, 0, common, validate, NULL}
TOOLKIT_BLOCK(spp, "spp", 0, 0, NULL);
TOOLKIT_BLOCK(image, "image", 1, 0, NULL);
TOOLKIT_BLOCK(depth, "depth", 0, 0, NULL);
TOOLKIT_BLOCK(roulette, "roulette", 0, 0, NULL);
TOOLKIT_BLOCK(sampler, "sampler", 0, 0, NULL);
TOOLKIT_BLOCK(lights, "lights", 0, 0, NULL);
const struct param_block params_block_reuse = {
    "reuse", reuse_rows, sizeof(reuse_rows) / sizeof(reuse_rows[0]), F(reuse), 0, 0, 0, reuse_validate, apply_preset};
TOOLKIT_BLOCK(path_history, "path history", 1, F(reuse), path_history_validate);
TOOLKIT_BLOCK(permutation, "temporal permutation", 0, F(reuse), permutation_validate);
TOOLKIT_BLOCK(spmis, "spmis", 0, F(spmis), NULL);
TOOLKIT_BLOCK(shift, "shift", 0, F(shift), NULL);
TOOLKIT_BLOCK(scene, "scene", 1, 0, NULL);
TOOLKIT_BLOCK(trace, "ray tracing", 1, 0, NULL);
TOOLKIT_BLOCK(camera, "camera", 1, 0, NULL);
#undef TOOLKIT_BLOCK
#undef F
#undef R
#undef S
#undef H

const struct param_block *const render_params_toolkit_blocks[] = {
    &params_block_spp,
    &params_block_image,
    &params_block_depth,
    &params_block_roulette,
    &params_block_sampler,
    &params_block_lights,
    &params_block_reuse,
    &params_block_denoise,
    &params_block_path_history,
    &params_block_permutation,
    &params_block_spmis,
    &params_block_shift,
    &params_block_scene,
    &params_block_trace,
    &params_block_camera,
};
const size_t render_params_toolkit_block_count =
    sizeof(render_params_toolkit_blocks) / sizeof(render_params_toolkit_blocks[0]);
