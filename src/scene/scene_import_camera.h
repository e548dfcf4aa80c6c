/* scene_import_camera.h: the camera of a mesh file opened as a whole scene: the file's first
 * perspective camera, else one fitted to the bounds, and the default camera path. Internal to
 * scene_import*.c: must never be included outside them (it exposes assimp types). */
#ifndef RESTIR_SCENE_SCENE_IMPORT_CAMERA_H
#define RESTIR_SCENE_SCENE_IMPORT_CAMERA_H

#include <assimp/scene.h>

#include "scene/scene_types.h"

/* Sets s->camera and s->camera_path for the imported file at path (s holds its triangles). */
void import_cameras(const struct aiScene *ai, const char *path, struct scene *s);

#endif
