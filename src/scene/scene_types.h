/* scene_types.h: the scene as plain data (triangles, materials, emitters, cameras), header-only.
 * Must never declare functions: every scene module includes it, so it may depend on none of them. */
#ifndef RESTIR_SCENE_SCENE_TYPES_H
#define RESTIR_SCENE_SCENE_TYPES_H

#include <stdint.h>

#include "core/sampling.h"
#include "core/vec3.h"
#include "scene/texture.h"

/* How a material reads one of its texture maps (glTF textureInfo, its sampler and
 * KHR_texture_transform): which UV set, an affine map of it (u' = m0 u + m1 v + m2, v' = m3 u +
 * m4 v + m5, in assimp's UV space where v runs up) and the wrap mode per axis. All zero is UV set
 * 0, no transform, repeat: what a map without these reads. */
enum texture_wrap { WRAP_REPEAT = 0, WRAP_CLAMP = 1, WRAP_MIRROR = 2 };
struct texture_lookup {
    int uv_set;       /* 0 or 1 */
    int has_xform;    /* 0: identity */
    float xform[6];
    int wrap_u, wrap_v; /* enum texture_wrap */
};

/* glTF-style metallic/roughness material; emission is one-sided (front = geometric normal). */
struct material {
    vec3 base_color;
    float metallic;  /* 0 dielectric (diffuse + 4% specular), 1 conductor */
    float roughness; /* perceptual roughness; GGX alpha = roughness^2 */
    vec3 emission;   /* emitted radiance, W / (m^2 sr) */
    int lambert_only; /* 1: no specular layer at all, a pure Lambertian of albedo base_color (what
                         analytic test scenes need; glTF's KHR_materials_specular factor 0) */
    /* Texture maps, glTF 2.0 style (0: none, else scene.textures[map - 1]): base_color and
     * emission are multiplied by the map's RGB; metallic and roughness by its B and G. */
    int base_color_map, metal_rough_map, emission_map;
    int normal_map;     /* glTF normalTexture (linear RGB): the shading normal in the tangent frame */
    float normal_scale; /* glTF normalTexture.scale: multiplies the map's x and y */
    /* glTF alphaMode MASK (BLEND is read as MASK at 0.5): where base_alpha times the base colour
     * map's alpha is below alpha_cutoff the surface does not exist for any ray (scene_alpha_cut) */
    int alpha_mask;
    float alpha_cutoff, base_alpha;
    /* how each map is read (the alpha channel through base_color_lookup) */
    struct texture_lookup base_color_lookup, metal_rough_lookup, emission_lookup, normal_lookup;
};

struct camera {
    vec3 position;
    vec3 target;
    vec3 up;
    float vfov_deg; /* vertical field of view */
    float aperture;       /* thin-lens aperture radius, scene units (0: pinhole) */
    float focus_distance; /* distance to the plane in focus along the view direction (0: to target) */
};

/* A camera path: keyframes at given frame numbers, interpolated by a cubic Hermite spline with
 * Catmull-Rom tangents at interior keys (continuous velocity) and zero velocity at the first and
 * last key (a two-key path is a smoothstep-eased straight line); frames outside the range clamp to
 * the ends. */
struct camera_key {
    float frame;
    struct camera cam;
};

struct camera_path {
    int num_keys;
    struct camera_key *keys;
};

struct scene_rt; /* Embree back end, opaque (scene_rt.c) */
struct environment;  /* environment.h */
struct env_sampler;  /* env_light.h */
struct scene_motion; /* scene_motion.c */

/* An emissive material's keys (scene_animation.h): strength, and a rigid motion of its triangles. */
struct emission_animation {
    int n;          /* keys; 0: the material is still */
    int step;       /* 1: each key's values hold until the next key; 0: linear between keys */
    float *frame;   /* n frames, strictly increasing */
    float *strength; /* n strengths >= 0 (1 where the keys give none) */
    vec3 *translate; /* n offsets from where the file puts the triangles, or NULL: no translation keys */
    vec3 *rotate;    /* n rotations in degrees about x, then y, then z, around pivot, or NULL: none */
    vec3 pivot;      /* the rotations' centre, in the file's coordinates */
    int pivot_given; /* 0: the file gave none, and the pivot is the centre of the material's triangles */
    vec3 emission;  /* the file's emission (times emissive_strength): what strength 1 gives */
};

/* What sampling a point on an emissive triangle needs, in one cache-friendly record. */
struct emitter {
    vec3 v0, e1, e2; /* p = v0 + b1 e1 + b2 e2 */
    vec3 n;          /* emitting (geometric) normal */
    vec3 Le;         /* emitted radiance */
    float pdf_area;  /* P(choose this emitter) / area */
    int tri;
    int textured;    /* 1: Le is modulated by an emission texture (scene_material_at) */
    int quad;        /* index into scene->emitter_quads when this triangle is half of a rectangle, else -1 */
    float radius;    /* the farthest vertex's distance from the centroid */
};

/* Two emitting triangles of one material that make a rectangle (scene_lights.c), so that
 * solid-angle sampling can draw the whole rectangle at once (Urena et al. 2013). A point is
 * corner + a lx ux + b ly uy with (a, b) in [0, 1]^2; the triangle of e[0] holds a + b <= 1, that of
 * e[1] the rest. */
struct emitter_quad {
    vec3 corner;      /* the vertex of e[0]'s triangle off the shared diagonal */
    vec3 ux, uy, uz;  /* unit edge directions, orthogonal, and ux x uy */
    vec3 centre;      /* corner + (lx ux + ly uy) / 2 */
    float lx, ly;     /* edge lengths */
    float inv_lx, inv_ly;
    float area;       /* lx ly */
    float radius;     /* half the diagonal */
    int e[2];         /* the two emitters */
    float bary[2][6]; /* per half k, its triangle's barycentrics: b1 = m0 a + m1 b + m2, b2 = m3 a + m4 b + m5 */
};

/* A node of the emitter BVH (scene_light_bvh.h): bounds of the emitters below it in position, power
 * and orientation (Conty Estevez & Kulla 2018, Sec. 4.1), in the form the importance reads. Every emitting normal below lies within
 * angle theta_o of axis (cos_o = cos theta_o; -1: any direction), and each emits into directions
 * within theta_e of its normal (cos_e = cos theta_e: 0, a hemisphere, for our one-sided emitters). */
struct light_bvh_node {
    vec3 center;    /* of the bounding box */
    float radius2;  /* squared radius of the box's bounding sphere (its half-diagonal squared) */
    float d2_min;   /* half the box's diagonal: the least squared distance the importance divides by */
    vec3 axis;      /* unit axis of the normal cone */
    float cos_o, sin_o, cos_e;
    float power;    /* sum of lights_emitter_power below */
    int second;     /* interior: index of the second child (the first is this node + 1); leaf: -1 */
    int emitter;    /* leaf: its emitter index; interior: -1 */
    int parent;     /* -1 at the root */
};

/* The emitter BVH a scene owns, one emitter per leaf, nodes in depth-first order. */
struct light_bvh {
    int num_nodes;
    struct light_bvh_node *nodes;
    int *emitter_leaf; /* per emitter: the index of its leaf */
};

/* An indexed triangle soup with per-triangle material and object ids, its materials and textures,
 * the emitter table (built by scene_lights.c), the default camera and camera path, and the opaque
 * handle of the ray-tracing back end. */
struct scene {
    char name[64];
    int num_verts;
    vec3 *verts;
    int num_tris;
    uint32_t *indices;     /* 3 per triangle */
    int *tri_material;     /* material id per triangle */
    int *tri_object;       /* object id per triangle */
    vec3 *tri_normal;      /* unit geometric normal per triangle (counter-clockwise winding) */
    float *tri_area;
    int *tri_emitter;      /* emitter index per triangle, -1 when not emissive */
    int num_materials;
    struct material *materials;
    int num_objects;
    float *uv;             /* 2 per vertex (assimp's convention, (0, 0) bottom-left), or NULL */
    float *uv1;            /* the second UV set (glTF TEXCOORD_1), 2 per vertex, or NULL */
    vec3 *normals;         /* per vertex: the file's shading normal (unit; zero where it had none
                              usable), or NULL: flat shading (scene_shading_normal) */
    float *tangents;       /* 4 per vertex: the file's tangent xyz and handedness w (glTF TANGENT),
                              or NULL: normal maps take the UV derivatives */
    int num_textures;
    struct texture *textures;
    struct scene_texture_key *texture_keys; /* where each texture came from (scene_texture_find) */
    char *load_notes; /* what the mesh imports left out or replaced, a line per file, or NULL
                         (scene_load_partial) */

    /* Emitters: emissive triangles, chosen proportionally to power (alias table). */
    int num_emitters;
    int *emitter_tri;
    struct emitter *emitters; /* compact copy of what light sampling reads, per emitter */
    struct alias_table emitter_table;
    struct light_bvh light_bvh; /* the emitters' BVH, for selection by importance at a point */
    int num_emitter_quads;
    struct emitter_quad *emitter_quads; /* rectangles made of two emitters (struct emitter's quad) */

    /* Environment light (scene_env.h): radiance from infinitely far away, or NULL; its sampler;
     * its MIS-compensated sampler for path walks (NULL where nothing is brighter than the mean);
     * the probability that a light sample picks it rather than an emitter. */
    struct environment *env;
    struct env_sampler *env_sampler;
    struct env_sampler *env_sampler_compensated;
    float env_prob;

    /* Animated emission strength (scene_animation.h): num_materials entries (n = 0: a still material),
     * or NULL when nothing is animated. */
    struct emission_animation *emission_anim;
    /* Moving emitters (scene_motion.h): where their triangles rest and what moves with them, or NULL
     * when no material has translation or rotation keys. */
    struct scene_motion *motion;

    struct camera camera;           /* default static camera */
    struct camera_path camera_path; /* default moving camera */

    struct scene_rt *rt;
    double bvh_ms; /* time scene_builder_end spent building the Embree scenes */
    float diagonal; /* of the bounding box of the vertices, set by scene_builder_end (scene_diagonal) */
};

#endif
