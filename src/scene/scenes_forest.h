/* scenes_forest.h: the built-in scene `forest` (scenes_forest.c), for scenes_builtin.c: its
 * geometry, materials and generated textures through the builder, then its sky once the scene
 * is built. Must never read files. */
#ifndef RESTIR_SCENE_SCENES_FOREST_H
#define RESTIR_SCENE_SCENES_FOREST_H

#include "scene/scene.h"

/* 25 trees with normal-mapped trunks and 3000 alpha-masked leaf cards each on a 400 m ground,
 * its camera and a 120-frame walk along a path between them. */
void scene_build_forest(struct scene_builder *b);
/* Gives the finished scene its generated sky with a sun (its only light). Returns 0, or -1 with
 * msg. */
int scene_light_forest(struct scene *s, char *msg);

#endif
