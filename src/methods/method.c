/* method.c: the method table and the methods' own defaults (method.h).
 * Must never depend on the passes or the ray tracer. */
#include "methods/method.h"

#include <stdio.h>
#include <string.h>

#include "core/check.h"

const struct method_info method_table[METHOD_COUNT] = {
    {"pt", "path tracing: NEE + BSDF sampling with MIS, Russian roulette (the reference method)", 0, 0},
    {"ris-di", "direct lighting by initial RIS only, no reuse (the no-reuse baseline of 001)", 1, 0},
    {"restir-di", "ReSTIR DI: initial RIS, temporal and spatial reuse by GRIS (pairwise MIS default)", 1, 0},
    {"restir-pt", "ReSTIR PT: path resampling, temporal and spatial path reuse by GRIS with shift mappings "
                  "(hybrid default) and sub-pixel reservoirs", 0, 0},
    {"area-restir", "Area ReSTIR (002 B.3): restir-pt with 1 initial candidate and 2 spatial neighbors, "
                    "sub-pixel reservoirs", 0, 0},
    {"gpt", "gradient-domain path tracing (Kettunen et al. 2015, 002 B.2): pt base paths shifted to the 4 "
            "neighbors (hybrid shift), Poisson reconstruction", 0, 1},
    {"grad-after-restir", "Gradient after ReSTIR (002 B.1): area-ReSTIR primal, gradients from shifting each "
                          "pixel's final path to its neighbors, Poisson reconstruction", 0, 1},
    {"grestir-pt", "gradient-domain ReSTIR PT (002): area-ReSTIR primal, ReSTIR over paired-pixel samples with "
                   "positivization, temporal and adaptive spatial reuse, Poisson reconstruction", 0, 1},
};

int method_find(const char *name)
{
    for (int m = 0; m < METHOD_COUNT; m++)
        if (strcmp(name, method_table[m].name) == 0)
            return m;
    return -1;
}

int method_runs_restir_pt(enum method_id m)
{
    return m == METHOD_RESTIR_PT || m == METHOD_AREA_RESTIR || m == METHOD_GRAD_AFTER_RESTIR ||
           m == METHOD_GRESTIR_PT;
}

int method_has_gbuffer(enum method_id m) { return m != METHOD_PT && m != METHOD_GPT; }

void renderer_method_params(enum method_id method, struct render_params *p)
{
    if (method == METHOD_RIS_DI) {
        p->temporal = 0;
        p->spatial = 0;
    }
    /* Area ReSTIR's primal (002 Sec. 5): 1 initial candidate (the default) and 2 spatial neighbors. */
    if ((method == METHOD_AREA_RESTIR || method == METHOD_GRAD_AFTER_RESTIR || method == METHOD_GRESTIR_PT) &&
        p->spatial_neighbors == 0)
        p->spatial_neighbors = 2;
}

void renderer_reference_params(enum method_id method, struct render_params *p)
{
    if (method_table[method].direct_only)
        p->max_bounces = 1;
}

int method_has_camera_effects(enum method_id m)
{
    return m == METHOD_PT || m == METHOD_RESTIR_PT || m == METHOD_AREA_RESTIR;
}

/* The largest aperture of the scene's static camera and camera-path keys. */
static float scene_aperture(const struct scene *s)
{
    float a = s->camera.aperture;
    for (int k = 0; k < s->camera_path.num_keys; k++)
        a = s->camera_path.keys[k].cam.aperture > a ? s->camera_path.keys[k].cam.aperture : a;
    return a;
}

int method_check_settings(enum method_id m, const struct render_params *p, const struct scene *s, char *msg)
{
    const char *name = method_table[m].name;
    if (p->temporal_reuse != TEMPORAL_BACKPROJECT && !method_runs_restir_pt(m)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.reuse=%s: %s has no path reservoirs with primary hits to splat (restir-pt, "
                 "area-restir, grad-after-restir and grestir-pt have)",
                 p->temporal_reuse == TEMPORAL_SPLAT ? "splat" : "both", name);
        return -1;
    }
    if (method_has_camera_effects(m))
        return 0;
    if (p->camera_shutter > 0.0f || p->camera_aperture > 0.0f) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "%s: %s does not render motion blur or depth of field (its samples do not carry the primary "
                 "ray's time and lens point); pt, restir-pt and area-restir do",
                 p->camera_shutter > 0.0f ? "camera.shutter" : "camera.aperture", name);
        return -1;
    }
    if (s && scene_aperture(s) > 0.0f) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "scene %s: its camera has an aperture (depth of field), which %s does not render; pt, "
                 "restir-pt and area-restir do",
                 s->name, name);
        return -1;
    }
    return 0;
}
