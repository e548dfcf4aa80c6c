/* scene_animation.h: emitters whose strength changes along the frames: a material's
 * "animation" in a scene file, keys of (frame, strength) that scale the emission the file gives,
 * linear between keys or held until the next ("step"), the first and last values held before and
 * after them. Sampling never sees the change: the emitters' power tables and light BVH are built
 * with each material's largest strength, so every emitter that can shine keeps a positive density,
 * and scene_set_frame then writes the frame's emission into the materials and emitters that
 * shading and sampling read. Moving emitters (keys of a transform) are not supported yet. */
#ifndef RESTIR_SCENE_SCENE_ANIMATION_H
#define RESTIR_SCENE_SCENE_ANIMATION_H

#include "scene/scene.h"

/* The strength of animation a at frame t (a->n >= 1). */
float emission_animation_at(const struct emission_animation *a, float t);
/* Its largest strength. */
float emission_animation_max(const struct emission_animation *a);

/* 1 when some material of s is animated (s->emission_anim != NULL). */
static inline int scene_is_animated(const struct scene *s)
{
    return s->emission_anim != NULL;
}

/* The strength at frame t of the emitter triangle tri's material: 1 for a still one (or a
 * non-emitter), its keys' value for an animated one. */
float scene_emission_strength(const struct scene *s, int tri, float t);

/* The frames at which some emitter stops changing: every key after a first whose strength differs
 * from the key before it (a step's switch, a ramp's end), rounded up to a whole frame, ascending and
 * without repeats, at most max of them into frames. Returns how many (0 for a still scene). */
int scene_animation_changes(const struct scene *s, int *frames, int max);

/* 1 when some animated emitter's strength at frame t1 differs from its strength at t0. */
int scene_lights_differ(const struct scene *s, float t0, float t1);

/* Sets every animated material's emission, and the Le of its emitters, to frame t's (the loaded
 * scene's frame 0 otherwise). The one change a loaded scene takes: its materials' and emitters'
 * arrays are written through the const scene. Not thread-safe with anything that reads the scene;
 * renderer_render calls it before a frame's passes, the references before their first path. Does
 * nothing for a still scene. */
void scene_set_frame(const struct scene *s, float t);

#endif
