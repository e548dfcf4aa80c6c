/* scene_file.h: scenes from files and back: our JSON scene format (docs/SCENES.md; reader
 * scene_json.c, writer src/io/scene_export.c) and the one entry point every command takes a scene through. */
#ifndef RESTIR_SCENE_SCENE_FILE_H
#define RESTIR_SCENE_SCENE_FILE_H

#include <stddef.h>

#include "scene.h"

/* A built-in scene by name, or a scene file: .json (ours) or anything assimp reads (.gltf, .glb,
 * .obj, .ply, ...). Returns 0, or -1 with msg naming the scene or file and the problem. */
int scene_load(const char *name_or_path, struct scene *s, char *msg);

/* Reads a JSON scene. Paths inside it are relative to the file. Every error names the file and
 * the key (e.g. "shapes[3].radius"). Returns 0, or -1 with msg filled and s left empty. */
int scene_json_load(const char *path, struct scene *s, char *msg);
/* The same from memory: text[0 .. len-1] followed by a NUL at text[len]; file names the text in
 * messages and dir is where relative mesh paths start ("" or NULL: the current folder). */
int scene_json_parse(const char *text, size_t len, const char *file, const char *dir, struct scene *s, char *msg);

/* A camera file (`restir view` records them; `render --camera FILE` replays them): one camera per
 * frame, {"format": "restir-cameras 1", "cameras": [{position, look_at, up, vfov}, ...]} with
 * optional "scene", "method", "width", "height", "seed" describing the run that recorded it.
 * Returns 0 with *cams (malloc'ed) and *n, or -1 with msg naming the file and the key. */
int scene_cameras_load(const char *path, struct camera **cams, int *n, char *msg);

/* The file name without folders and extension ("scenes/Box.gltf" -> "Box"), cut to len. */
void scene_file_stem(const char *path, char *out, size_t len);
/* 1 when path ends with suffix (lower-case ".json"), ignoring the case of path. */
int scene_path_has_suffix(const char *path, const char *suffix);

#endif
