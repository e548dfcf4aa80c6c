/* scene_export.h: writing a scene as our JSON scene format (docs/SCENES.md), for
 * `restir scene export`: a user starts from a built-in scene's file and edits it. */
#ifndef RESTIR_IO_SCENE_EXPORT_H
#define RESTIR_IO_SCENE_EXPORT_H

#include "scene/scene.h"

/* Writes scene s, built by the shape calls records[0 .. n-1] (scene_create_builtin_recorded), as
 * a JSON scene at path (written to a temporary name, then renamed). Numbers are written with the
 * fewest digits that read back to the same float, and the shapes are the builder calls that made
 * the scene, so loading the file rebuilds the same triangles, materials and cameras bit for bit.
 * A scene with textures, UVs, shading normals or an environment (the forest) is refused: the
 * records do not hold them. Returns 0, or -1 with msg filled. */
int scene_export_json(const struct scene *s, const struct scene_shape_record *records, int n, const char *path,
                      char *msg);

/* Writes cams[0 .. n-1] as a camera file (scene_file.h: scene_cameras_load), numbers read back
 * bit for bit; label fields (scene, method, width, height, seed) describe the recording run.
 * Returns 0, or -1 with msg. */
int cameras_write_json(const char *path, const struct camera *cams, int n, const char *scene, const char *method,
                       int width, int height, unsigned long long seed, char *msg);

#endif
