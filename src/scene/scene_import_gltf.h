/* scene_import_gltf.h: what assimp does not tell about a glTF material, read from the file's own
 * JSON: KHR_materials_emissive_strength (assimp 5.2 drops it) and how each texture map is read
 * (texCoord, the sampler's wrap modes, KHR_texture_transform). Must never depend on assimp: it
 * reads the file beside it. */
#ifndef RESTIR_SCENE_SCENE_IMPORT_GLTF_H
#define RESTIR_SCENE_SCENE_IMPORT_GLTF_H

#include <cjson/cJSON.h>

#include "scene/scene_types.h"

/* The JSON of the .gltf (the whole file) or .glb (its first chunk) at path, parsed (the caller
 * frees it with cJSON_Delete), or NULL when it cannot be read or parsed. */
cJSON *import_gltf_read(const char *path);
/* KHR_materials_emissive_strength of the material named name in gltf (NULL: no file), or 1 when
 * the file has no uniquely named material of that name or that material has no strength. In
 * double: the caller converts it to float the way it converts every other double of the file. */
double import_gltf_strength(const cJSON *gltf, const char *name);
/* The four maps' lookups (texture_lookup in scene_types.h) of the uniquely named material name:
 * texCoord (0 or 1; KHR_texture_transform's own texCoord wins), the sampler's wrapS / wrapT, and
 * the transform T(offset) R(rotation) S(scale) of glTF's UV space (v down) rewritten for assimp's
 * (v up). Leaves m's lookups zero (set 0, identity, repeat) where the file says nothing. Returns
 * 0, or -1 with msg naming the material and key for a non-finite or out-of-range value. */
int import_gltf_lookups(const cJSON *gltf, const char *name, struct material *m, char *msg);
/* The triangles the file's default scene declares (TRIANGLES: count / 3 of the indices, else of
 * POSITION; strips and fans: count - 2), each mesh counted once per node that places it, so that
 * the import can say how many assimp dropped; -1 when the JSON does not say (gltf NULL, a missing
 * or malformed accessor, a node tree deeper than 64). */
long import_gltf_declared_triangles(const cJSON *gltf);

#endif
