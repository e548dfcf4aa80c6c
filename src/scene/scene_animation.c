/* scene_animation.c: animated emission strength (scene_animation.h). */
#include "scene/scene_animation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The keys around frame t: k, and the weight u of key k + 1 (0 before the first key, after the last
 * and for step keys). */
static void key_at(const struct emission_animation *a, float t, int *k, float *u)
{
    *k = 0;
    *u = 0.0f;
    if (t <= a->frame[0])
        return;
    if (t >= a->frame[a->n - 1]) {
        *k = a->n - 1;
        return;
    }
    while (*k + 2 < a->n && a->frame[*k + 1] <= t) /* frame[k] <= t < frame[k + 1] */
        (*k)++;
    if (!a->step)
        *u = (t - a->frame[*k]) / (a->frame[*k + 1] - a->frame[*k]);
}

float emission_animation_at(const struct emission_animation *a, float t)
{
    int k;
    float u;
    key_at(a, t, &k, &u);
    return u > 0.0f ? a->strength[k] + u * (a->strength[k + 1] - a->strength[k]) : a->strength[k];
}

vec3 emission_animation_vec_at(const struct emission_animation *a, const vec3 *keys, float t)
{
    int k;
    float u;
    key_at(a, t, &k, &u);
    return u > 0.0f ? v3_add(keys[k], v3_scale(v3_sub(keys[k + 1], keys[k]), u)) : keys[k];
}

int emission_animation_moves(const struct emission_animation *a)
{
    return a->n > 0 && (a->translate || a->rotate);
}

/* Whether a's pose at t0 and t1 differ. */
static int pose_differs(const struct emission_animation *a, float t0, float t1)
{
    const vec3 *ch[2] = {a->translate, a->rotate};
    for (int c = 0; c < 2; c++)
        if (ch[c] && !v3_equal(emission_animation_vec_at(a, ch[c], t0), emission_animation_vec_at(a, ch[c], t1)))
            return 1;
    return 0;
}

void emission_animation_free(struct emission_animation *a)
{
    free(a->frame);
    free(a->strength);
    free(a->translate);
    free(a->rotate);
    a->frame = a->strength = NULL;
    a->translate = a->rotate = NULL;
    a->n = 0;
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
        if (a->n > 0 && (emission_animation_at(a, t0) != emission_animation_at(a, t1) || pose_differs(a, t0, t1)))
            return 1;
    }
    return 0;
}

int scene_lights_moved(const struct scene *s, float t0, float t1)
{
    for (int m = 0; s->emission_anim && m < s->num_materials; m++)
        if (emission_animation_moves(&s->emission_anim[m]) && pose_differs(&s->emission_anim[m], t0, t1))
            return 1;
    return 0;
}

int scene_animation_changes(const struct scene *s, int *frames, int max)
{
    int n = 0;
    for (int m = 0; s->emission_anim && m < s->num_materials; m++) {
        const struct emission_animation *a = &s->emission_anim[m];
        for (int k = 1; k < a->n; k++) {
            const int moves = (a->translate && !v3_equal(a->translate[k], a->translate[k - 1])) ||
                              (a->rotate && !v3_equal(a->rotate[k], a->rotate[k - 1]));
            if (a->strength[k] == a->strength[k - 1] && !moves)
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
