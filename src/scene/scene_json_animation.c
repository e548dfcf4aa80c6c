/* scene_json_animation.c: a material's "animation" in a scene file (scene_animation.h): its keys
 * read and checked, every error naming the file and the key, for the builder
 * (scene_animate_material). */
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_animation.h"
#include "scene/scene_json_reader.h"

/* Coordinates and angles past this are refused (as the shapes' coordinates are). */
#define ANIMATION_COORD_MAX 1e6

/* The channels a key may give besides its frame: strength (a scale of the emission), translate (an
 * offset) and rotate (degrees about x, then y, then z around the pivot). */
enum { CH_STRENGTH, CH_TRANSLATE, CH_ROTATE, CH_COUNT };
static const char *const channel_name[CH_COUNT] = {"strength", "translate", "rotate"};

/* Key i's channels into a (which has room for every key); has[c] says which channels key 0 gave,
 * and every later key must give the same ones. */
static int read_key(struct json_reader *r, const cJSON *e, const char *ek, int i, int *has,
                    struct emission_animation *a)
{
    static const char *const key_keys[] = {"frame", "strength", "translate", "rotate", NULL};
    if (!cJSON_IsObject(e))
        return json_fail(r, ek, "must be an object {\"frame\", and \"strength\", \"translate\" or \"rotate\"}");
    if (cJSON_GetObjectItemCaseSensitive(e, "scale")) {
        char sk[224];
        json_child_key(sk, sizeof sk, ek, "scale", 0);
        return json_fail(r, sk, "emitters move rigidly (\"translate\", \"rotate\"): a scale would change their "
                                "area and power");
    }
    if (json_check_keys(r, e, ek, key_keys) != 0 ||
        json_get_number(r, e, ek, "frame", 1, -1e9, 1e9, 0.0f, &a->frame[i]) != 0)
        return -1;
    for (int c = 0; c < CH_COUNT; c++) {
        const int here = cJSON_GetObjectItemCaseSensitive(e, channel_name[c]) != NULL;
        if (i == 0)
            has[c] = here;
        if (here != has[c]) {
            char ck[224];
            json_child_key(ck, sizeof ck, ek, channel_name[c], 0);
            return json_fail(r, ck, here ? "is not in the first key: a channel must be in every key or in none"
                                         : "missing: the first key has it, and a channel must be in every key or "
                                           "in none");
        }
    }
    if (!has[CH_STRENGTH] && !has[CH_TRANSLATE] && !has[CH_ROTATE])
        return json_fail(r, ek, "needs \"strength\", \"translate\" or \"rotate\" besides its frame");
    if ((has[CH_STRENGTH] && json_get_number(r, e, ek, "strength", 1, 0.0, 1e6, 0.0f, &a->strength[i]) != 0) ||
        (has[CH_TRANSLATE] && json_get_vec3(r, e, ek, "translate", 1, -ANIMATION_COORD_MAX, ANIMATION_COORD_MAX,
                                             v3(0, 0, 0), &a->translate[i]) != 0) ||
        (has[CH_ROTATE] && json_get_vec3(r, e, ek, "rotate", 1, -ANIMATION_COORD_MAX, ANIMATION_COORD_MAX,
                                          v3(0, 0, 0), &a->rotate[i]) != 0))
        return -1;
    if (!has[CH_STRENGTH])
        a->strength[i] = 1.0f;
    if (i > 0 && !(a->frame[i] > a->frame[i - 1])) {
        char fk[224];
        json_child_key(fk, sizeof fk, ek, "frame", 0);
        return json_fail(r, fk, "%g is not after the previous key's frame %g (keys must be in order)",
                         (double)a->frame[i], (double)a->frame[i - 1]);
    }
    return 0;
}

/* A material's "animation" (scene_animation.h): {"keys": [{"frame": F, "strength": S, "translate": [x, y, z],
 * "rotate": [x, y, z]}, ...], "interpolation": "linear" | "step", "pivot": [x, y, z]} into *a (a->n = 0
 * when absent). The emission the file gives must be set in a->emission by the caller. */
static int read_animation(struct json_reader *r, const cJSON *m, const char *mkey, int emits,
                          struct emission_animation *a)
{
    static const char *const keys[] = {"keys", "interpolation", "pivot", NULL};
    char k[128];
    json_child_key(k, sizeof k, mkey, "animation", 0);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(m, "animation");
    memset(a, 0, sizeof *a);
    if (!v)
        return 0;
    if (!cJSON_IsObject(v))
        return json_fail(r, k, "must be an object with \"keys\"");
    if (cJSON_GetObjectItemCaseSensitive(v, "transform")) {
        char t[160];
        json_child_key(t, sizeof t, k, "transform", 0);
        return json_fail(r, t, "a motion is given per key, as \"translate\" and \"rotate\" (with \"pivot\")");
    }
    if (json_check_keys(r, v, k, keys) != 0)
        return -1;
    if (!emits)
        return json_fail(r, k, "the material emits nothing: only an emitter (a material with \"emission\") can be "
                               "animated");
    const cJSON *mode = cJSON_GetObjectItemCaseSensitive(v, "interpolation");
    if (mode && (!cJSON_IsString(mode) || (strcmp(mode->valuestring, "linear") && strcmp(mode->valuestring, "step")))) {
        char t[160];
        json_child_key(t, sizeof t, k, "interpolation", 0);
        return json_fail(r, t, "must be \"linear\" or \"step\"");
    }
    a->step = mode && !strcmp(mode->valuestring, "step");
    a->pivot_given = cJSON_GetObjectItemCaseSensitive(v, "pivot") != NULL;
    if (json_get_vec3(r, v, k, "pivot", 0, -ANIMATION_COORD_MAX, ANIMATION_COORD_MAX, v3(0, 0, 0), &a->pivot) != 0)
        return -1;
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(v, "keys");
    char lk[160];
    json_child_key(lk, sizeof lk, k, "keys", 0);
    if (!cJSON_IsArray(list) || cJSON_GetArraySize(list) < 1)
        return json_fail(r, lk, list ? "must be an array of at least one {\"frame\", ...}" : "missing");
    const int n = cJSON_GetArraySize(list);
    a->frame = xmalloc(sizeof(float) * (size_t)n);
    a->strength = xmalloc(sizeof(float) * (size_t)n);
    a->translate = xmalloc(sizeof(vec3) * (size_t)n);
    a->rotate = xmalloc(sizeof(vec3) * (size_t)n);
    int has[CH_COUNT] = {0, 0, 0}, i = 0;
    for (const cJSON *e = list->child; e; e = e->next, i++) {
        char ek[192];
        json_child_key(ek, sizeof ek, lk, NULL, i);
        if (read_key(r, e, ek, i, has, a) != 0)
            return -1;
    }
    a->n = n;
    if (!has[CH_TRANSLATE]) {
        free(a->translate);
        a->translate = NULL;
    }
    if (!has[CH_ROTATE]) {
        free(a->rotate);
        a->rotate = NULL;
    }
    return 0;
}

int json_animate_material(struct json_reader *r, const cJSON *m, const char *mkey, int id)
{
    const vec3 emission = r->b->s->materials[id].emission;
    struct emission_animation a;
    if (read_animation(r, m, mkey, v3_max_component(emission) > 0.0f, &a) != 0) {
        emission_animation_free(&a);
        return -1;
    }
    if (a.n == 0)
        return 0;
    char k[80];
    json_child_key(k, sizeof k, mkey, "animation", 0);
    if (v3_max_component(emission) * emission_animation_max(&a) > 1e18f) {
        emission_animation_free(&a);
        return json_fail(r, k, "emission times its largest strength exceeds 1e18");
    }
    char why[RESTIR_MSG_LEN];
    if (scene_animate_material(r->b, id, &a, why) != 0) /* what the reader checked: not expected */
        return json_fail(r, k, "%s", why);
    return 0;
}
