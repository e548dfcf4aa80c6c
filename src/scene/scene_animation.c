/* scene_animation.c: animated emission strength (scene_animation.h). */
#include "scene/scene_animation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

float emission_animation_at(const struct emission_animation *a, float t)
{
    if (t <= a->frame[0])
        return a->strength[0];
    if (t >= a->frame[a->n - 1])
        return a->strength[a->n - 1];
    int k = 0; /* frame[k] <= t < frame[k + 1] */
    while (k + 2 < a->n && a->frame[k + 1] <= t)
        k++;
    if (a->step)
        return a->strength[k];
    const float u = (t - a->frame[k]) / (a->frame[k + 1] - a->frame[k]);
    return a->strength[k] + u * (a->strength[k + 1] - a->strength[k]);
}

float emission_animation_max(const struct emission_animation *a)
{
    float m = 0.0f;
    for (int k = 0; k < a->n; k++)
        m = a->strength[k] > m ? a->strength[k] : m;
    return m;
}

float scene_emission_strength(const struct scene *s, int tri, float t)
{
    if (!s->emission_anim || tri < 0 || tri >= s->num_tris)
        return 1.0f;
    const struct emission_animation *a = &s->emission_anim[s->tri_material[tri]];
    return a->n > 0 ? emission_animation_at(a, t) : 1.0f;
}

int scene_lights_differ(const struct scene *s, float t0, float t1)
{
    for (int m = 0; s->emission_anim && m < s->num_materials; m++) {
        const struct emission_animation *a = &s->emission_anim[m];
        if (a->n > 0 && emission_animation_at(a, t0) != emission_animation_at(a, t1))
            return 1;
    }
    return 0;
}

void scene_set_frame(const struct scene *s, float t)
{
    if (!s->emission_anim)
        return;
    for (int m = 0; m < s->num_materials; m++) {
        const struct emission_animation *a = &s->emission_anim[m];
        if (a->n > 0)
            s->materials[m].emission = v3_scale(a->emission, emission_animation_at(a, t));
    }
    for (int e = 0; e < s->num_emitters; e++) {
        const int m = s->tri_material[s->emitters[e].tri];
        if (s->emission_anim[m].n > 0)
            s->emitters[e].Le = s->materials[m].emission;
    }
}

int scene_animation_changes(const struct scene *s, int *frames, int max)
{
    int n = 0;
    for (int m = 0; s->emission_anim && m < s->num_materials; m++) {
        const struct emission_animation *a = &s->emission_anim[m];
        for (int k = 1; k < a->n; k++) {
            if (a->strength[k] == a->strength[k - 1])
                continue;
            const int f = (int)ceilf(a->frame[k]);
            int at = 0; /* insertion point in the sorted list */
            while (at < n && frames[at] < f)
                at++;
            if ((at < n && frames[at] == f) || n == max)
                continue;
            memmove(frames + at + 1, frames + at, sizeof(int) * (size_t)(n - at));
            frames[at] = f;
            n++;
        }
    }
    return n;
}
