/* scene.h: building a scene (the builder), releasing it and reading materials, plus the scene headers
 * every user needs. Must never include embree headers (only scene_rt.c does) nor shading or up. */
#ifndef RESTIR_SCENE_SCENE_H
#define RESTIR_SCENE_SCENE_H

#include "core/vec3.h"
/* Included for every user of the scene: the data, ray queries, cameras and content hash. */
#include "scene/camera.h"
#include "scene/scene_hash.h"
#include "scene/scene_rt.h"
#include "scene/scene_surface.h"
#include "scene/scene_types.h"
#include "scene/texture.h"

/* One call of the builder's shape functions, as scene export writes it back (scene_export.h):
 * replaying the records through the same functions rebuilds the same triangles bit for bit. */
enum scene_shape_kind { SHAPE_TRIANGLE, SHAPE_QUAD, SHAPE_BOX, SHAPE_SPHERE };
struct scene_shape_record {
    enum scene_shape_kind kind;
    vec3 p[4];  /* triangle: 3 corners; quad: 4 corners; box: lo, hi; sphere: center */
    float f;    /* box: rotation about y in radians; sphere: radius */
    int segments, sphere_flags; /* sphere: SPHERE_INWARD | SPHERE_SMOOTH */
    int material, object;
};

/* How a scene is to be loaded: the settings scene_load_with (scene_file.h) hands down to the
 * readers and the builder. Every field's zero is the default, so a zeroed description (or a NULL
 * pointer wherever one is taken) loads the scene as it is written. */
struct scene_load_desc {
    /* The most triangles the scene may have, counted as the builder adds them (instances and
     * imported meshes included); past it the builder stops adding and scene_builder_end refuses the
     * scene saying so. 0 (or negative): 1 << 26, about 16 GB with its BVH. Fuzzing lowers it. */
    int max_triangles;
    /* A texture that cannot be read (missing, undecodable): 0 refuses the scene with a message
     * naming the file and key; 1 says why on stderr and goes on without the map (the material's
     * factor alone; scene.missing_textures=warn). */
    int missing_textures_warn;
    /* A mesh file that loads only in part (assimp dropped faces or made up a material; we skipped
     * points, lines, zero-area triangles): 0 says what on stderr and keeps it with the scene
     * (scene.load_notes); 1 refuses the file with that message (scene.strict=on) unless all it
     * skipped was triangles of zero area. */
    int strict;
    /* 1: scene_builder_end makes every alpha-masked material opaque (scene.alpha=off: what the
     * masks cost, measured on the same geometry). 0: masks are honoured. Changes the scene. */
    int no_alpha_masks;
    /* 1: scene_builder_end drops vertex normals, tangents and normal maps, so every triangle
     * shades with its geometric normal (scene.shading_normals=off). 0: they are kept. Changes the
     * scene. */
    int flat_shading;
    /* 1: the batched ray queries (scene_intersect_batch, scene_occluded_batch) trace ray by ray
     * instead of as Embree streams (rays.streams=off). 0: streams. The same answers either way,
     * only the time differs; the owner may change it later (scene_set_ray_streams). */
    int ray_streams_off;
};

/* Builder used by the built-in scenes, scene files and tests. */
struct scene_builder {
    struct scene *s;
    struct scene_load_desc desc; /* max_triangles already resolved (> 0) */
    int cap_verts, cap_tris, cap_materials, cap_textures; /* capacities of the growing arrays */
    /* With record set, every outermost shape call is appended to records (the caller frees). */
    int record, depth;
    int over_budget; /* a triangle beyond desc.max_triangles was refused */
    int num_records, cap_records;
    struct scene_shape_record *records;
};

/* Starts building s, named name, as desc says (NULL: a zeroed description, the defaults). */
void scene_builder_begin_with(struct scene_builder *b, struct scene *s, const char *name,
                              const struct scene_load_desc *desc);
/* scene_builder_begin_with with the defaults. */
void scene_builder_begin(struct scene_builder *b, struct scene *s, const char *name);
int scene_add_material(struct scene_builder *b, struct material m);
/* Animates material m's emission along the frames (scene_animation.h): a holds n >= 1 keys with
 * increasing frames, strengths in [0, 1e6], and translate / rotate / pivot (NULL arrays: no such
 * channel); its key arrays (malloc'ed) become the scene's, and *a is left empty, whatever the
 * result. m's emission is what strength 1 gives; the material keeps it times the largest strength
 * (what sampling sees), and scene_builder_end poses frame 0. Returns 0, or -1 with msg when m is
 * not an emitting material of the scene, is animated already, or the keys are out of order or range. */
int scene_animate_material(struct scene_builder *b, int m, struct emission_animation *a, char *msg);
/* Takes ownership of t; returns its map id for struct material (>= 1). key names where it came
 * from (a resolved file path, or a model path and an embedded index) and srgb how it was decoded,
 * so that every later material naming the same image, in any file or instance, shares it. */
int scene_add_texture(struct scene_builder *b, struct texture t, const char *key, int srgb);
/* The map id of the texture added with this key and srgb, or 0. */
int scene_texture_find(const struct scene *s, const char *key, int srgb);
/* What loading does with a texture that cannot be read (missing, undecodable), as the builder's
 * desc.missing_textures_warn says: returns -1 to refuse the scene, or 0 after saying why on stderr
 * (the loader then goes on without the map). */
int scene_texture_unreadable(const struct scene_builder *b, const char *why);
/* What the import of file path left out or replaced (notes: "; "-separated items; lossy: some of
 * them lost or replaced something of the file's, not only zero-area triangles). With desc.strict
 * and lossy: returns -1 with msg naming the file and the notes; else 0 after saying them on stderr
 * and appending them to the scene's load notes. */
int scene_load_partial(struct scene_builder *b, const char *path, const char *notes, int lossy, char *msg);
/* The UVs (u0 v0 u1 v1 u2 v2) of triangle tri, already added: set 0 (scene_set_uvs) or 1. */
void scene_set_uvs(struct scene_builder *b, int tri, const float uv[6]);
void scene_set_uv_set(struct scene_builder *b, int tri, int set, const float uv[6]);
/* The shading normals of triangle tri's corners, already added (scene_shading_normal). Normalized
 * here; a zero, non-finite or NaN normal is stored as zero and shades that corner flat. */
void scene_set_normals(struct scene_builder *b, int tri, const vec3 n[3]);
/* The tangents of triangle tri's corners (x y z w each, w = handedness, glTF TANGENT), already
 * added; a non-finite tangent is stored as zero (that corner takes the UV derivatives). */
void scene_set_tangents(struct scene_builder *b, int tri, const float t[12]);
int scene_new_object(struct scene_builder *b);
void scene_add_triangle(struct scene_builder *b, vec3 a, vec3 c, vec3 d, int material, int object);
/* Quad a-b-c-d (counter-clockwise seen from the front) as two triangles. */
void scene_add_quad(struct scene_builder *b, vec3 a, vec3 c, vec3 d, vec3 e, int material, int object);
/* Axis-aligned box with outward faces. */
void scene_add_box(struct scene_builder *b, vec3 lo, vec3 hi, int material, int object);
/* Box rotated by angle_rad about the y axis through its center. */
void scene_add_box_rotated_y(struct scene_builder *b, vec3 lo, vec3 hi, float angle_rad, int material,
                             int object);
/* Closed UV sphere. Flags: SPHERE_INWARD flips the winding so the front faces the center;
 * SPHERE_SMOOTH gives every corner the sphere's exact normal as its shading normal. */
enum { SPHERE_INWARD = 1, SPHERE_SMOOTH = 2 };
void scene_add_sphere(struct scene_builder *b, vec3 center, float radius, int segments, int flags,
                      int material, int object);
/* Applies the description's scene changes (no_alpha_masks, flat_shading), finishes derived data
 * (normals, areas, emitters, alias table) and builds the Embree scene (ray_streams_off). Returns 0 on success, -1 with msg filled (e.g. no geometry, NaN vertex). */
int scene_builder_end(struct scene_builder *b, char *msg);

void scene_destroy(struct scene *s);

/* Length of the diagonal of the scene's bounding box (scale for distance thresholds). */
float scene_diagonal(const struct scene *s);

#endif
