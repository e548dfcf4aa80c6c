/* scene_import_gltf.h: KHR_materials_emissive_strength read from a glTF file's own JSON, for
 * assimp versions that drop it. Must never depend on assimp: it reads the file beside it. */
#ifndef RESTIR_SCENE_SCENE_IMPORT_GLTF_H
#define RESTIR_SCENE_SCENE_IMPORT_GLTF_H

#include <cjson/cJSON.h>

/* The JSON of the .gltf (the whole file) or .glb (its first chunk) at path, parsed (the caller
 * frees it with cJSON_Delete), or NULL when it cannot be read or parsed. */
cJSON *import_gltf_read(const char *path);
/* KHR_materials_emissive_strength of the material named name in gltf (NULL: no file), or 1 when
 * the file has no uniquely named material of that name or that material has no strength. In
 * double: the caller converts it to float the way it converts every other double of the file. */
double import_gltf_strength(const cJSON *gltf, const char *name);

#endif
