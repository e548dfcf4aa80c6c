/* scene_rt.h: the private seam between the scene data and its Embree back end.
 * Must never expose embree types (only scene_rt.c includes embree3/rtcore.h). */
#ifndef RESTIR_SCENE_SCENE_RT_H
#define RESTIR_SCENE_SCENE_RT_H

#include "scene.h"

/* Builds the acceleration structure over s's triangles. Returns 0, or -1 with msg. */
int scene_rt_build(struct scene *s, char *msg);
void scene_rt_destroy(struct scene *s);

#endif
