/* scene_env.c: attaching an environment light to a scene (scene_env.h).
 * Must never trace rays or depend on shading. */
#include "scene/scene_env.h"

#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "scene/env_light.h"

void scene_env_free(struct scene *s)
{
    if (s->env_sampler)
        env_sampler_fini(s->env_sampler);
    free(s->env_sampler);
    if (s->env_sampler_compensated)
        env_sampler_fini(s->env_sampler_compensated);
    free(s->env_sampler_compensated);
    s->env_sampler_compensated = NULL;
    if (s->env)
        environment_fini(s->env);
    free(s->env);
    s->env = NULL;
    s->env_sampler = NULL;
    s->env_prob = 0.0f;
}

int scene_set_environment(struct scene *s, struct environment *env, char *msg)
{
    scene_env_free(s);
    if (!env)
        return 0;
    struct env_sampler *sampler = xmalloc(sizeof *sampler);
    if (env_sampler_init(sampler, env) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "the environment has no direction of positive radiance");
        env_sampler_fini(sampler);
        free(sampler);
        environment_fini(env);
        free(env);
        return -1;
    }
    s->env = env;
    s->env_sampler = sampler;
    s->env_prob = s->num_emitters > 0 ? 0.5f : 1.0f;
    struct env_sampler *compensated = xmalloc(sizeof *compensated);
    if (env_sampler_init_compensated(compensated, env) == 0) {
        s->env_sampler_compensated = compensated;
    } else {
        env_sampler_fini(compensated);
        free(compensated);
    }
    return 0;
}
