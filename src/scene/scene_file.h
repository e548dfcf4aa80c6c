/* scene_file.h: the one entry point every command takes a scene (or a camera file) through.
 * Must never be included by the format readers it dispatches to (scene_json, scene_import). */
#ifndef RESTIR_SCENE_SCENE_FILE_H
#define RESTIR_SCENE_SCENE_FILE_H

#include "scene/scene.h"

/* A built-in scene by name, or a scene file: .json (ours, scene_json.h) or anything assimp reads
 * (.gltf, .glb, .obj, .ply, ...; scene_import.h), loaded as d says (struct scene_load_desc in
 * scene.h: triangle budget, unreadable textures, alpha masks, shading normals, Embree streams;
 * NULL or zeroed: the defaults); the settings live in d and the scene, none process-wide.
 * Returns 0, or -1 with msg naming the scene or file and the problem. */
int scene_load_with(const char *name_or_path, const struct scene_load_desc *d, struct scene *s, char *msg);
/* scene_load_with with the defaults. */
int scene_load(const char *name_or_path, struct scene *s, char *msg);

/* A camera file (`restir view` records them; `render --camera FILE` replays them): one camera per
 * frame, {"format": "restir-cameras 1", "cameras": [{position, look_at, up, vfov, aperture,
 * focus_distance}, ...]} with optional "scene", "method", "width", "height", "seed" describing the run that recorded it.
 * Returns 0 with *cams (malloc'ed) and *n, or -1 with msg naming the file and the key. */
int scene_cameras_load(const char *path, struct camera **cams, int *n, char *msg);

#endif
