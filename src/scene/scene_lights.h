/* scene_lights.h: the emitter table a scene owns (which triangles emit, their power alias table).
 * Must never depend on shading: light sampling (src/shading/lights.h) reads this table, not back. */
#ifndef RESTIR_SCENE_SCENE_LIGHTS_H
#define RESTIR_SCENE_SCENE_LIGHTS_H

#include "scene/scene_types.h"

/* Emitter power used for selection: luminance(Le) * area * pi. */
float lights_emitter_power(const struct scene *s, int tri);
/* Fills s->tri_emitter, emitter_tri, num_emitters, emitter_table and emitters from the triangles'
 * materials and areas (scene_builder_end, after normals and areas). Returns 0, or -1 with msg when
 * the emitter powers are invalid (negative or NaN emission). */
int scene_lights_build(struct scene *s, char *msg);

#endif
