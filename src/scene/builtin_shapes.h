/* builtin_shapes.h: what the scenes made in code share: material shorthands, rectangles, camera
 * paths and seeded random placement. Header-only (static inline), for scenes_builtin.c and the
 * scenes in their own files. Must never read files. */
#ifndef RESTIR_SCENE_BUILTIN_SHAPES_H
#define RESTIR_SCENE_BUILTIN_SHAPES_H

#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "scene/scene.h"

static inline struct material builtin_surface(vec3 base, float metallic, float roughness)
{
    return (struct material){.base_color = base, .metallic = metallic, .roughness = roughness};
}

static inline struct material builtin_diffuse(float r, float g, float b)
{
    return builtin_surface(v3(r, g, b), 0.0f, 1.0f);
}

static inline struct material builtin_emitter(vec3 e) { return (struct material){.roughness = 1.0f, .emission = e}; }

/* Rectangle centred at c with unit normal n, unit tangent t, half extents hu (along t) and hv. */
static inline void builtin_rect(struct scene_builder *b, vec3 c, vec3 n, vec3 t, float hu, float hv, int mat, int obj)
{
    vec3 u = v3_scale(t, hu), v = v3_scale(v3_cross(n, t), hv);
    vec3 p0 = v3_sub(v3_sub(c, u), v), p1 = v3_sub(v3_add(c, u), v);
    vec3 p2 = v3_add(v3_add(c, u), v), p3 = v3_add(v3_sub(c, u), v);
    scene_add_quad(b, p0, p1, p2, p3, mat, obj);
}

static inline void builtin_set_path(struct scene *s, int n, const struct camera_key *keys)
{
    s->camera_path.num_keys = n;
    s->camera_path.keys = xmalloc(sizeof(*keys) * (size_t)n);
    memcpy(s->camera_path.keys, keys, sizeof(*keys) * (size_t)n);
}

static inline float builtin_rnd(pcg32 *r, float lo, float hi) { return lo + (hi - lo) * pcg32_float(r); }

/* A uniformly distributed unit vector. */
static inline vec3 builtin_random_unit(pcg32 *r)
{
    float z = builtin_rnd(r, -1.0f, 1.0f), phi = builtin_rnd(r, 0.0f, 2.0f * RESTIR_PI);
    float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return v3(s * cosf(phi), s * sinf(phi), z);
}

#endif
