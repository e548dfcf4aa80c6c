/* scenes_builtin.h: the scenes made in code, by name (the table scene_builtins). Must never read
 * files. */
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
/* One built-in scene: a row of scene_builtins. */
struct scene_builtin {
    const char *name;        /* what --scene takes */
    const char *description; /* one line, for `restir list` */
    void (*build)(struct scene_builder *b);
    /* Lights that need the finished scene (an environment's share depends on the emitters), or NULL.
     * Returns 0, or -1 with msg. */
    int (*light)(struct scene *s, char *msg);
};
/* Every built-in scene, the default (many-lights) first; a row whose name is NULL ends it. */
extern const struct scene_builtin scene_builtins[];

#endif
