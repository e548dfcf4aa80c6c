/* scene_surface.h: what a point of a triangle looks like to shading: its texture coordinates, its
 * material with the texture maps applied, and its shading normal (vertex normals, normal map).
 * Must never trace rays or include the builder (scene_surface.c reads finished scenes only). */
#ifndef RESTIR_SCENE_SCENE_SURFACE_H
#define RESTIR_SCENE_SCENE_SURFACE_H

#include "scene/scene_types.h"

/* The material at a point of triangle tri (barycentrics b1, b2): its factors times its textures
 * there. Returns the scene's own material when it has no textures, else fills and returns tmp. */
const struct material *scene_material_at(const struct scene *s, int tri, float b1, float b2, struct material *tmp);

/* 1 where the point is cut out of an alpha-masked material (glTF alphaMode MASK: coverage =
 * base_alpha times the base colour map's alpha, bilinear, below alpha_cutoff): every ray passes
 * through it (scene_rt.c's Embree filter) and it emits nothing (scene_material_at). */
int scene_alpha_cut(const struct scene *s, int tri, float b1, float b2);

/* What scene_alpha_cut reads of one triangle, in one record of 32 bytes: the ray tracer keeps one
 * per alpha-masked primitive, so a candidate hit's test touches one cache line instead of the
 * triangle's material index, its vertex indices and three vertices' UVs (scene_rt.c). */
struct alpha_tri {
    float uv[6];  /* the corners' coordinates in the set the base colour map reads (0 without UVs) */
    int material; /* s->tri_material[tri] */
    int unused;
};
void scene_alpha_tri(const struct scene *s, int tri, struct alpha_tri *r);
/* scene_alpha_cut of the record's triangle: the same arithmetic, so the same answer bit for bit. */
int scene_alpha_cut_tri(const struct scene *s, const struct alpha_tri *r, float b1, float b2);

/* The shading normal at barycentrics (b1, b2) of triangle tri, turned to the side of ng (the
 * geometric normal as the caller faces it): the corners' normals interpolated and normalized
 * (the triangle's own normal where the scene or a corner has none), then the material's normal
 * map applied in the tangent frame there (glTF 2.0 normalTexture: n_t = 2 texel - 1 with x, y
 * times normal_scale; tangent from the file's TANGENT, else from the triangle's UV derivatives,
 * made orthogonal to the normal; bitangent = w cross(n, t)). Exactly ng for flat shading without a
 * normal map. */
vec3 scene_shading_normal(const struct scene *s, int tri, float b1, float b2, vec3 ng);

#endif
