/* scene_import.h: mesh files through assimp (glTF 2.0 .gltf/.glb, .obj, .ply and whatever else
 * assimp reads). Must never expose assimp types: only scene_import*.c include assimp headers. */
#ifndef RESTIR_SCENE_SCENE_IMPORT_H
#define RESTIR_SCENE_SCENE_IMPORT_H

#include "scene/scene.h"

/* A material of the file (by its name in the file) replaced by one of the builder's. */
struct scene_material_override {
    const char *file_name;
    int material;
};

/* Appends the triangles of the mesh file at path to the builder. Every vertex goes through the
 * file's node hierarchy, then through xform (4x4, row-major, p' = xform * node * p; NULL: the
 * identity; used as an affine map, its bottom row ignored). A transform that mirrors (negative
 * determinant) has its triangles' winding flipped, so fronts stay fronts. Points, lines and
 * zero-area triangles are skipped; vertex normals are not read (flat shading); the first UV
 * channel and the glTF base colour, metallic-roughness and emissive textures are (texture.h);
 * skinned or morphed meshes come in their rest pose.
 * material >= 0: every triangle gets that material; material < 0: the file's materials that
 * triangles use are added to the builder (glTF metallic-roughness factors clamped to [0, 1];
 * emissive factor times KHR_materials_emissive_strength; other formats: diffuse colour and a
 * roughness from the Phong exponent) and each triangle gets its own, except that a file material
 * named in overrides[0 .. num_overrides-1] is replaced by the given builder material (a name that
 * matches no material of the file is an error naming it). object >= 0: every triangle gets that
 * object id; object < 0: a fresh object per node of the file that holds meshes (a glTF mesh
 * instance with all its primitives, an OBJ object).
 * Returns the number of triangles added (> 0), or -1 with msg naming the file and the problem
 * (unreadable or invalid file, a header count the file cannot hold or a PLY element declared
 * twice, no triangles, a NaN or infinite vertex, an index out of range, a NaN or negative
 * emission); after -1 the builder may hold part of the file, so the scene is to be discarded.
 * Not thread-safe: assimp's C API keeps its last error in a global. */
int scene_import_mesh(struct scene_builder *b, const char *path, const float *xform, int material,
                      const struct scene_material_override *overrides, int num_overrides, int object, char *msg);

/* A mesh file as a whole scene (glTF on its own), named after the file's stem: its geometry and
 * materials, its first perspective camera (or one fitted to the bounds, from +z and a little above,
 * when it has none) as the static camera, and that camera moved sideways by a tenth of the bounds'
 * diagonal over frames 0..64, looking at the same point, as the camera path. Its emissive
 * materials are the emitters; a file without any is refused with a message that suggests a JSON
 * scene adding lights. Returns 0, or -1 with msg filled and s left empty. */
int scene_import_file(const char *path, struct scene *s, char *msg);
/* The same as d says (scene.h; NULL: the defaults, as scene_import_file). */
int scene_import_file_with(const char *path, const struct scene_load_desc *d, struct scene *s, char *msg);

#endif
