/* method.h: the table of methods (name, what it estimates, which passes it runs) and each method's
 * own defaults on top of the settings. Must never depend on the passes or the ray tracer. */
#ifndef RESTIR_METHODS_METHOD_H
#define RESTIR_METHODS_METHOD_H

#include "render/params.h"
#include "scene/scene_types.h"

enum method_id {
    METHOD_PT = 0,
    METHOD_RIS_DI,
    METHOD_RESTIR_DI,
    METHOD_RESTIR_PT,
    METHOD_AREA_RESTIR,       /* 002 B.3: restir-pt with 1 initial candidate and 2 spatial neighbors */
    METHOD_GPT,               /* 002 B.2: gradient-domain path tracing */
    METHOD_GRAD_AFTER_RESTIR, /* 002 B.1: gradients from shifting the final area-ReSTIR paths */
    METHOD_GRESTIR_PT,        /* 002: Gradient with ReSTIR over paired-pixel samples */
    METHOD_COUNT
};

struct method_info {
    const char *name;
    const char *description;
    int direct_only; /* estimates direct lighting only: its reference is pt with 1 bounce */
    int gradient;    /* renders primal + gradients and reconstructs (002) */
};

extern const struct method_info method_table[METHOD_COUNT];

/* Returns the method id, or -1 for an unknown name. */
int method_find(const char *name);
/* Methods that run the ReSTIR PT passes (restir-pt, area-restir, and the primal of grad-after-restir
 * and grestir-pt). */
int method_runs_restir_pt(enum method_id m);
/* Methods that trace their own primary rays instead of reading a G-buffer (pt, gpt). */
int method_has_gbuffer(enum method_id m);

/* Methods whose samples carry the primary ray's shutter time and lens point (pt, restir-pt,
 * area-restir): the ones that render camera.shutter and camera.aperture. */
int method_has_camera_effects(enum method_id m);
/* Checks what depends on the method (and the scene, when s is not NULL): temporal.reuse=splat|both
 * needs path reservoirs; motion blur and depth of field need method_has_camera_effects. Returns 0,
 * or -1 with msg naming the key. */
int method_check_settings(enum method_id m, const struct render_params *p, const struct scene *s, char *msg);

/* The method's own defaults on top of p (ris-di: no reuse; area-restir and the primal of
 * grad-after-restir and grestir-pt: 2 spatial neighbors unless spatial.neighbors is set).
 * renderer_init applies them; reports call it to say what ran. */
void renderer_method_params(enum method_id method, struct render_params *p);
/* The parameters a method's reference integrates with: pt with max_bounces = 1 for DI methods. */
void renderer_reference_params(enum method_id method, struct render_params *p);

#endif
