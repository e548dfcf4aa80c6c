/* scene.h: the scene as plain data: an indexed triangle soup with per-triangle material and
 * object ids, materials, the emitter list, the camera and camera path, and the opaque handle of
 * the ray-tracing back end. Must never include embree headers (only scene_rt.c does). */
#ifndef RESTIR_SCENE_SCENE_H
#define RESTIR_SCENE_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include "../core/sampling.h"
#include "../core/vec3.h"
#include "texture.h"

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
};

struct camera {
    vec3 position;
    vec3 target;
    vec3 up;
    float vfov_deg; /* vertical field of view */
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

/* What sampling a point on an emissive triangle needs, in one cache-friendly record. */
struct emitter {
    vec3 v0, e1, e2; /* p = v0 + b1 e1 + b2 e2 */
    vec3 n;          /* emitting (geometric) normal */
    vec3 Le;         /* emitted radiance */
    float pdf_area;  /* P(choose this emitter) / area */
    int tri;
    int textured;    /* 1: Le is modulated by an emission texture (scene_material_at) */
};

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
    int num_textures;
    struct texture *textures;
    struct scene_texture_key *texture_keys; /* where each texture came from (scene_texture_find) */

    /* Emitters: emissive triangles, chosen proportionally to power (alias table). */
    int num_emitters;
    int *emitter_tri;
    struct emitter *emitters; /* compact copy of what light sampling reads, per emitter */
    struct alias_table emitter_table;

    struct camera camera;           /* default static camera */
    struct camera_path camera_path; /* default moving camera */

    struct scene_rt *rt;
    double bvh_ms; /* time scene_builder_end spent building the Embree scenes */
};

/* Surface point reconstructed from a triangle hit. */
struct surface_hit {
    vec3 p;
    vec3 ng;   /* geometric normal, unit, facing the incoming ray */
    vec3 ns;   /* shading normal (equal to ng: flat shading) */
    float t;
    int tri;
    float b1, b2; /* barycentrics of p: p = (1-b1-b2) v0 + b1 v1 + b2 v2 */
    int material;
    int object;
    int front; /* 1 when the ray hit the front (emitting) side */
};

/* One call of the builder's shape functions, as scene export writes it back (scene_export.h):
 * replaying the records through the same functions rebuilds the same triangles bit for bit. */
enum scene_shape_kind { SHAPE_TRIANGLE, SHAPE_QUAD, SHAPE_BOX, SHAPE_SPHERE };
struct scene_shape_record {
    enum scene_shape_kind kind;
    vec3 p[4];  /* triangle: 3 corners; quad: 4 corners; box: lo, hi; sphere: center */
    float f;    /* box: rotation about y in radians; sphere: radius */
    int segments, inward_facing; /* sphere */
    int material, object;
};

/* Builder used by the built-in scenes, scene files and tests. */
struct scene_builder {
    struct scene *s;
    int cap_verts, cap_tris, cap_materials, cap_textures; /* capacities of the growing arrays */
    /* With record set, every outermost shape call is appended to records (the caller frees). */
    int record, depth;
    int over_budget; /* a triangle beyond scene_set_max_triangles was refused */
    int num_records, cap_records;
    struct scene_shape_record *records;
};

void scene_builder_begin(struct scene_builder *b, struct scene *s, const char *name);
int scene_add_material(struct scene_builder *b, struct material m);
/* Takes ownership of t; returns its map id for struct material (>= 1). key names where it came
 * from (a resolved file path, or a model path and an embedded index) and srgb how it was decoded,
 * so that every later material naming the same image, in any file or instance, shares it. */
int scene_add_texture(struct scene_builder *b, struct texture t, const char *key, int srgb);
/* The map id of the texture added with this key and srgb, or 0. */
int scene_texture_find(const struct scene *s, const char *key, int srgb);
/* The most triangles a scene may have (default 1 << 26, about 16 GB with its BVH): a builder past
 * it stops adding and scene_builder_end fails saying so. Fuzzing lowers it. */
void scene_set_max_triangles(int n);
/* The UVs (u0 v0 u1 v1 u2 v2) of triangle tri, already added. */
void scene_set_uvs(struct scene_builder *b, int tri, const float uv[6]);
int scene_new_object(struct scene_builder *b);
void scene_add_triangle(struct scene_builder *b, vec3 a, vec3 c, vec3 d, int material, int object);
/* Quad a-b-c-d (counter-clockwise seen from the front) as two triangles. */
void scene_add_quad(struct scene_builder *b, vec3 a, vec3 c, vec3 d, vec3 e, int material, int object);
/* Axis-aligned box with outward faces. */
void scene_add_box(struct scene_builder *b, vec3 lo, vec3 hi, int material, int object);
/* Box rotated by angle_rad about the y axis through its center. */
void scene_add_box_rotated_y(struct scene_builder *b, vec3 lo, vec3 hi, float angle_rad, int material,
                             int object);
/* Closed UV sphere; inward_facing flips the winding so the front faces the center. */
void scene_add_sphere(struct scene_builder *b, vec3 center, float radius, int segments, int inward_facing,
                      int material, int object);
/* Finishes derived data (normals, areas, emitters, alias table) and builds the Embree scene.
 * Returns 0 on success, -1 with msg filled (e.g. no geometry, NaN vertex). */
int scene_builder_end(struct scene_builder *b, char *msg);

void scene_destroy(struct scene *s);
/* A 64-bit FNV-1a hash of everything rendering reads: vertices, triangles, their materials,
 * objects and uvs, the materials and the textures' texels. Equal scenes hash equally on every
 * machine and run; a changed vertex, material or texel changes it (up to hash collisions). */
uint64_t scene_content_hash(const struct scene *s);

/* The material at a point of triangle tri (barycentrics b1, b2): its factors times its textures
 * there. Returns the scene's own material when it has no textures, else fills and returns tmp. */
const struct material *scene_material_at(const struct scene *s, int tri, float b1, float b2, struct material *tmp);

/* Length of the diagonal of the scene's bounding box (scale for distance thresholds). */
float scene_diagonal(const struct scene *s);

/* Camera at a frame of the default path (or the static camera when path is 0). */
struct camera scene_camera_at(const struct scene *s, int use_path, float frame);

/* Ray queries (scene_rt.c). tmax may be INFINITY. */
int scene_intersect(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax, struct surface_hit *hit);
/* Closest hit among the emissive triangles only, ignoring every other surface. */
int scene_intersect_emitters(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax,
                             struct surface_hit *hit);
int scene_occluded(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax);
/* p moved off its surface (normal n) to the side that direction `toward` leaves from. */
vec3 scene_offset_point(vec3 p, vec3 n, vec3 toward);
/* Visibility between two surface points with normals, offsetting both ends. */
int scene_visible(const struct scene *s, vec3 p0, vec3 n0, vec3 p1, vec3 n1);

/* Ray logging for benchmarks: while a log is active every query is recorded (per thread, no
 * locks), so a frame's rays can be replayed through Embree alone to separate ray-tracing time
 * from shading time. */
enum ray_kind { RAY_CLOSEST = 0, RAY_OCCLUDED, RAY_EMITTERS };
struct ray_record {
    vec3 o, d;
    float tmin, tmax;
    int kind;
};
void scene_ray_log_begin(const struct scene *s);
/* Stops logging and returns all recorded rays (malloc'ed, caller frees) and their count. */
struct ray_record *scene_ray_log_end(const struct scene *s, size_t *count);
/* Traces the recorded rays again in parallel; returns the elapsed milliseconds. */
double scene_ray_replay(const struct scene *s, const struct ray_record *rays, size_t count);

/* Built-in scenes (scenes_builtin.c). Returns 0, or -1 with msg naming the unknown scene. */
int scene_create_builtin(const char *name, struct scene *s, char *msg);
/* The same, also returning the builder's shape calls (malloc'ed, caller frees) for export. */
int scene_create_builtin_recorded(const char *name, struct scene *s, struct scene_shape_record **records,
                                  int *num_records, char *msg);
int scene_is_builtin(const char *name);
/* Names of built-in scenes, NULL terminated. */
extern const char *const scene_builtin_names[];
extern const char *const scene_builtin_descriptions[];

#endif
