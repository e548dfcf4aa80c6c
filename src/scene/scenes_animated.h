/* scenes_animated.h: the built-in scenes whose emitters change along the frames (scene_animation.h):
 * switch-room, a lamp switched off and on, and moving-lamp, a lamp that moves and comes back. For
 * measuring lag and ghosting after a light changes (compare's lag_frames and ghost_frames). Must
 * never read files. */
#ifndef RESTIR_SCENE_SCENES_ANIMATED_H
#define RESTIR_SCENE_SCENES_ANIMATED_H

#include "scene/scene.h"

/* A room lit by a steady ceiling lamp, a small red triangle and a blue lamp switched off at frame 16
 * and on again at 32 (step keys): the scene of tests/data/scenes/switch_room.json, triangle for
 * triangle. */
void scene_build_switch_room(struct scene_builder *b);
/* The same room with the blue lamp moving: still until frame 16, carried across the room and tilted
 * by frame 24, held until 32, back where it started by frame 40 (linear keys of translation and
 * rotation, so both its light and its shadow move). */
void scene_build_moving_lamp(struct scene_builder *b);

#endif
