/* scenes_builtin.h: the scenes made in code (cornell, ajar, many-lights, foliage, pillars, furnace, forest,
 * night-forest), by name. Must never read files. */
#ifndef RESTIR_SCENE_SCENES_BUILTIN_H
#define RESTIR_SCENE_SCENES_BUILTIN_H

#include "scene/scene.h"

/* Builds the built-in scene name. Returns 0, or -1 with msg naming the unknown scene. */
int scene_create_builtin(const char *name, struct scene *s, char *msg);
/* The same as d says (scene.h; NULL: the defaults, as scene_create_builtin). */
int scene_create_builtin_with(const char *name, const struct scene_load_desc *d, struct scene *s, char *msg);
/* scene_create_builtin, also returning the builder's shape calls (malloc'ed, caller frees) for export. */
int scene_create_builtin_recorded(const char *name, struct scene *s, struct scene_shape_record **records,
                                  int *num_records, char *msg);
int scene_is_builtin(const char *name);
/* Names of built-in scenes, NULL terminated. */
extern const char *const scene_builtin_names[];
extern const char *const scene_builtin_descriptions[];

#endif
