/* scenes_night_forest.h: the built-in scene `night-forest` (scenes_night_forest.c), for
 * scenes_builtin.c. Must never read files. */
#ifndef RESTIR_SCENE_SCENES_NIGHT_FOREST_H
#define RESTIR_SCENE_SCENES_NIGHT_FOREST_H

#include "scene/scene.h"

/* The forest's ground and 25 trees (scenes_forest.h) with no sky, lit only by strings of small
 * tetrahedral lamps (four emissive triangles each, warm colours, radiance over a decade) wound
 * around trunks, branches and crowns and hung between neighbouring trees; the forest's camera
 * path along the path beneath the garlands. */
void scene_build_night_forest(struct scene_builder *b);

#endif
