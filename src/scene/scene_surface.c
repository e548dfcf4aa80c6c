/* scene_surface.c: texture coordinates, textured materials and shading normals at surface points
 * (scene_surface.h). Must never trace rays or build scenes. */
#include "scene/scene_surface.h"

#include <math.h>

#include "scene/texture.h"

/* Set `set` of the UVs at the point ((0, 0) when the scene has none). */
static void uv_set_at(const struct scene *s, int set, int tri, float b1, float b2, float *u, float *v)
{
    *u = *v = 0.0f;
    const float *uv = set ? s->uv1 : s->uv;
    if (!uv)
        return;
    const uint32_t *ix = &s->indices[3 * tri];
    const float b0 = 1.0f - b1 - b2;
    *u = b0 * uv[2 * ix[0]] + b1 * uv[2 * ix[1]] + b2 * uv[2 * ix[2]];
    *v = b0 * uv[2 * ix[0] + 1] + b1 * uv[2 * ix[1] + 1] + b2 * uv[2 * ix[2] + 1];
}

/* (u, v) through the lookup's transform (glTF KHR_texture_transform), in place. */
static void transform_uv(const struct texture_lookup *l, float *u, float *v)
{
    if (l->has_xform) {
        const float *m = l->xform, x = *u, y = *v;
        *u = m[0] * x + m[1] * y + m[2];
        *v = m[3] * x + m[4] * y + m[5];
    }
}

/* The coordinates map `l` reads at the point: its UV set, through its transform. */
static void lookup_uv(const struct scene *s, const struct texture_lookup *l, int tri, float b1, float b2, float *u,
                      float *v)
{
    uv_set_at(s, l->uv_set, tri, b1, b2, u, v);
    transform_uv(l, u, v);
}

/* Texture `map` (>= 1) read through lookup l at the point. */
static vec3 map_sample(const struct scene *s, int map, const struct texture_lookup *l, int tri, float b1, float b2)
{
    float u, v;
    lookup_uv(s, l, tri, b1, b2, &u, &v);
    return texture_sample_wrap(&s->textures[map - 1], u, v, l->wrap_u, l->wrap_v);
}

/* Whether masked material m is cut out where its base colour map's UV set reads (u, v) (before
 * the lookup's transform): coverage = base_alpha times the map's bilinear alpha, below the cutoff. */
static int coverage_cut(const struct scene *s, const struct material *m, float u, float v)
{
    float a = m->base_alpha;
    if (m->base_color_map) {
        const struct texture_lookup *l = &m->base_color_lookup;
        transform_uv(l, &u, &v);
        a *= texture_sample_alpha_wrap(&s->textures[m->base_color_map - 1], u, v, l->wrap_u, l->wrap_v);
    }
    return a < m->alpha_cutoff;
}

int scene_alpha_cut(const struct scene *s, int tri, float b1, float b2)
{
    const struct material *m = &s->materials[s->tri_material[tri]];
    if (!m->alpha_mask)
        return 0;
    float u = 0.0f, v = 0.0f;
    if (m->base_color_map)
        uv_set_at(s, m->base_color_lookup.uv_set, tri, b1, b2, &u, &v);
    return coverage_cut(s, m, u, v);
}

void scene_alpha_tri(const struct scene *s, int tri, struct alpha_tri *r)
{
    const struct material *m = &s->materials[s->tri_material[tri]];
    const float *uv = m->base_color_lookup.uv_set ? s->uv1 : s->uv;
    for (int k = 0; k < 3; k++) {
        const uint32_t i = s->indices[3 * tri + k];
        r->uv[2 * k] = uv ? uv[2 * i] : 0.0f;
        r->uv[2 * k + 1] = uv ? uv[2 * i + 1] : 0.0f;
    }
    r->material = s->tri_material[tri];
    r->unused = 0;
}

int scene_alpha_cut_tri(const struct scene *s, const struct alpha_tri *r, float b1, float b2)
{
    const struct material *m = &s->materials[r->material];
    if (!m->alpha_mask)
        return 0;
    float u = 0.0f, v = 0.0f;
    if (m->base_color_map) { /* as uv_set_at */
        const float b0 = 1.0f - b1 - b2;
        u = b0 * r->uv[0] + b1 * r->uv[2] + b2 * r->uv[4];
        v = b0 * r->uv[1] + b1 * r->uv[3] + b2 * r->uv[5];
    }
    return coverage_cut(s, m, u, v);
}

const struct material *scene_material_at(const struct scene *s, int tri, float b1, float b2, struct material *tmp)
{
    const struct material *m = &s->materials[s->tri_material[tri]];
    if (!(m->base_color_map | m->metal_rough_map | m->emission_map | m->alpha_mask))
        return m;
    *tmp = *m;
    if (m->base_color_map)
        tmp->base_color = v3_mul(m->base_color, map_sample(s, m->base_color_map, &m->base_color_lookup, tri, b1, b2));
    if (m->metal_rough_map) {
        vec3 t = map_sample(s, m->metal_rough_map, &m->metal_rough_lookup, tri, b1, b2);
        tmp->roughness = m->roughness * t.y;
        tmp->metallic = m->metallic * t.z;
    }
    if (m->emission_map)
        tmp->emission = v3_mul(m->emission, map_sample(s, m->emission_map, &m->emission_lookup, tri, b1, b2));
    if (scene_alpha_cut(s, tri, b1, b2))
        tmp->emission = v3s(0.0f);
    return tmp;
}

/* The interpolated vertex normal in the file's orientation, or 0 when a corner has none. */
static vec3 vertex_normal(const struct scene *s, const uint32_t *ix, float b1, float b2)
{
    const vec3 n0 = s->normals[ix[0]], n1 = s->normals[ix[1]], n2 = s->normals[ix[2]];
    if (v3_length2(n0) == 0.0f || v3_length2(n1) == 0.0f || v3_length2(n2) == 0.0f)
        return v3s(0.0f);
    vec3 n = v3_add(v3_add(v3_scale(n0, 1.0f - b1 - b2), v3_scale(n1, b1)), v3_scale(n2, b2));
    float len2 = v3_length2(n);
    return len2 > 1e-12f ? v3_scale(n, 1.0f / sqrtf(len2)) : v3s(0.0f);
}

/* The tangent (xyz, handedness in *w) at the point: the file's, interpolated, or else the
 * triangle's dp/du from its UVs with w making (t, w n x t) follow increasing u and v. Returns 0
 * when there is none (no UVs, degenerate UVs). */
static int tangent_at(const struct scene *s, const struct texture_lookup *l, int tri, const uint32_t *ix, float b1,
                      float b2, vec3 n, vec3 *t, float *w)
{
    if (s->tangents) {
        const float *t0 = &s->tangents[4 * ix[0]], *t1 = &s->tangents[4 * ix[1]], *t2 = &s->tangents[4 * ix[2]];
        const float b0 = 1.0f - b1 - b2;
        *t = v3(b0 * t0[0] + b1 * t1[0] + b2 * t2[0], b0 * t0[1] + b1 * t1[1] + b2 * t2[1],
                b0 * t0[2] + b1 * t1[2] + b2 * t2[2]);
        *w = t0[3] < 0.0f ? -1.0f : 1.0f;
        if (v3_length2(*t) > 1e-12f)
            return 1;
    }
    if (!(l->uv_set ? s->uv1 : s->uv))
        return 0;
    const vec3 e1 = v3_sub(s->verts[ix[1]], s->verts[ix[0]]), e2 = v3_sub(s->verts[ix[2]], s->verts[ix[0]]);
    /* the map's own coordinates at the corners (its UV set through its transform) */
    float cu[3], cv[3];
    lookup_uv(s, l, tri, 0.0f, 0.0f, &cu[0], &cv[0]);
    lookup_uv(s, l, tri, 1.0f, 0.0f, &cu[1], &cv[1]);
    lookup_uv(s, l, tri, 0.0f, 1.0f, &cu[2], &cv[2]);
    const float du1 = cu[1] - cu[0], dv1 = cv[1] - cv[0], du2 = cu[2] - cu[0], dv2 = cv[2] - cv[0];
    const float det = du1 * dv2 - du2 * dv1;
    if (!(fabsf(det) > 1e-12f) || !isfinite(det))
        return 0;
    const vec3 dpdu = v3_scale(v3_sub(v3_scale(e1, dv2), v3_scale(e2, dv1)), 1.0f / det);
    const vec3 dpdv = v3_scale(v3_sub(v3_scale(e2, du1), v3_scale(e1, du2)), 1.0f / det);
    *t = dpdu;
    *w = v3_dot(v3_cross(n, dpdu), dpdv) < 0.0f ? -1.0f : 1.0f;
    return v3_length2(dpdu) > 1e-20f;
}

/* n moved by the normal map of material m at (u, v); n unchanged where the frame is degenerate. */
static vec3 apply_normal_map(const struct scene *s, const struct material *m, int tri, const uint32_t *ix, float b1,
                             float b2, vec3 n)
{
    vec3 t;
    float w;
    if (!tangent_at(s, &m->normal_lookup, tri, ix, b1, b2, n, &t, &w))
        return n;
    t = v3_sub(t, v3_scale(n, v3_dot(n, t))); /* Gram-Schmidt against the shading normal */
    float len2 = v3_length2(t);
    if (!(len2 > 1e-12f))
        return n;
    t = v3_scale(t, 1.0f / sqrtf(len2));
    const vec3 b = v3_scale(v3_cross(n, t), w);
    const vec3 c = map_sample(s, m->normal_map, &m->normal_lookup, tri, b1, b2);
    const vec3 local = v3((2.0f * c.x - 1.0f) * m->normal_scale, (2.0f * c.y - 1.0f) * m->normal_scale, 2.0f * c.z - 1.0f);
    vec3 mapped = v3_add(v3_add(v3_scale(t, local.x), v3_scale(b, local.y)), v3_scale(n, local.z));
    len2 = v3_length2(mapped);
    return len2 > 1e-12f && isfinite(len2) ? v3_scale(mapped, 1.0f / sqrtf(len2)) : n;
}

vec3 scene_shading_normal(const struct scene *s, int tri, float b1, float b2, vec3 ng)
{
    const struct material *m = &s->materials[s->tri_material[tri]];
    if (!s->normals && !m->normal_map)
        return ng;
    const uint32_t *ix = &s->indices[3 * tri];
    vec3 n = s->normals ? vertex_normal(s, ix, b1, b2) : v3s(0.0f);
    if (v3_length2(n) == 0.0f) {
        if (!m->normal_map)
            return ng;
        n = s->tri_normal[tri]; /* the file's orientation: the winding's side */
    }
    if (m->normal_map)
        n = apply_normal_map(s, m, tri, ix, b1, b2, n);
    return v3_dot(n, ng) < 0.0f ? v3_neg(n) : n;
}
