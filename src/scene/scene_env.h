/* scene_env.h: a scene's environment light: attaching one (from a scene file's "environment" or
 * the command line's --env) with its importance sampler and its share of light samples.
 * Must never trace rays or depend on shading. */
#ifndef RESTIR_SCENE_SCENE_ENV_H
#define RESTIR_SCENE_SCENE_ENV_H

#include "scene/environment.h"
#include "scene/scene_types.h"

/* Gives s the environment env (taken over; NULL removes the scene's own), builds its sampler and
 * sets env_prob: 1 without emitters, else 1/2 (a light sample picks the environment or an emitter
 * with equal odds: both strategies stay unbiased whatever the split, and a power-based split would
 * need a scene scale the two do not share). Returns 0, or -1 with msg when the environment has no
 * direction of positive radiance. Also builds the MIS-compensated sampler path walks may use
 * (env_light.h), left NULL where no direction is brighter than the mean. */
int scene_set_environment(struct scene *s, struct environment *env, char *msg);
/* Radiance arriving from direction d at infinity (a ray that escapes): the environment's, or black
 * without one. */
static inline vec3 scene_env_radiance(const struct scene *s, vec3 d)
{
    return s->env ? environment_radiance(s->env, d) : v3s(0.0f);
}
/* Frees the environment and its sampler (scene_destroy calls it). */
void scene_env_free(struct scene *s);

#endif
