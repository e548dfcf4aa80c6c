/* scene_animation.h: emitters that change along the frames: a material's "animation" in a scene
 * file, keys of (frame, strength) that scale the emission the file gives and of (frame, translate,
 * rotate) that move its triangles rigidly (scene_motion.h), linear between keys or held until the
 * next ("step"), the first and last values held before and after them. Sampling never sees a
 * strength change: the emitters' power tables and light BVH are built with each material's largest
 * strength, so every emitter that can shine keeps a positive density, and scene_set_frame
 * (scene_motion.h) then
 * writes the frame's emission into the materials and emitters that shading and sampling read, and
 * moves the moving ones. */
#ifndef RESTIR_SCENE_SCENE_ANIMATION_H
#define RESTIR_SCENE_SCENE_ANIMATION_H

#include <stddef.h>

#include "scene/scene_types.h"

/* The strength of animation a at frame t (a->n >= 1). */
float emission_animation_at(const struct emission_animation *a, float t);
/* The value at frame t of a vector channel of a (keys: a->translate or a->rotate, n values). */
vec3 emission_animation_vec_at(const struct emission_animation *a, const vec3 *keys, float t);
/* 1 when a has translation or rotation keys. */
int emission_animation_moves(const struct emission_animation *a);
/* Frees a's keys (a itself is the caller's) and leaves it still. */
void emission_animation_free(struct emission_animation *a);
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

/* The frames at which some emitter stops changing: every key after a first whose strength or pose
 * differs from the key before it (a step's switch, a ramp's end), rounded up to a whole frame, ascending and
 * without repeats, at most max of them into frames. Returns how many (0 for a still scene). */
int scene_animation_changes(const struct scene *s, int *frames, int max);

/* 1 when some animated emitter's strength or pose at frame t1 differs from that at t0. */
int scene_lights_differ(const struct scene *s, float t0, float t1);
/* 1 when some moving emitter's pose at frame t1 differs from that at t0. */
int scene_lights_moved(const struct scene *s, float t0, float t1);


#endif
