/* scene_light_bvh.h: building the emitter BVH a scene owns (struct light_bvh, scene_types.h), one
 * emitter per leaf, split by the surface area orientation heuristic (Conty Estevez & Kulla 2018,
 * Sec. 4.3). Selection by it is shading/light_tree.h's; this file only builds and frees. */
#ifndef RESTIR_SCENE_SCENE_LIGHT_BVH_H
#define RESTIR_SCENE_SCENE_LIGHT_BVH_H

#include "scene/scene_types.h"

/* Builds s->light_bvh over s->emitters with power[e] the selection power of emitter e (>= 0,
 * finite: scene_lights_build checks that first). Leaves an empty tree when there are no emitters.
 * Deterministic: the same emitters give the same tree. */
void scene_light_bvh_build(struct scene *s, const float *power);
/* The bounds of every node of s's tree recomputed from its emitters where they are now (moving
 * emitters, scene_motion.h); the tree, its powers and its leaves stay. */
void scene_light_bvh_refit(struct scene *s);
/* Frees the tree's arrays and empties it; an empty tree is fine. */
void scene_light_bvh_free(struct light_bvh *t);

/* The smallest cone (axis, cos of its half-angle) holding the cones (wa, cos_a) and (wb, cos_b): the
 * union of direction cones (Conty Estevez & Kulla 2018, Alg. 1). cos -1 means every direction. */
void light_cone_union(vec3 wa, float cos_a, vec3 wb, float cos_b, vec3 *w, float *cos_o);

#endif
