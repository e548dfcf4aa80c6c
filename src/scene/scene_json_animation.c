/* scene_json_animation.c: a material's "animation" in a scene file (scene_animation.h): its
 * strength keys read and checked, kept per material while the file is read, and attached to the
 * scene once it is built. */
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_animation.h"
#include "scene/scene_json_reader.h"

/* A material's "animation" (scene_animation.h): {"keys": [{"frame": F, "strength": S}, ...],
 * "interpolation": "linear" | "step"} scaling its emission; into *a (a->n = 0 when absent). The
 * emission the file gives must be set in a->emission by the caller. */
static int read_animation(struct json_reader *r, const cJSON *m, const char *mkey, int emits,
                          struct emission_animation *a)
{
    static const char *const keys[] = {"keys", "interpolation", "transform", NULL};
    static const char *const key_keys[] = {"frame", "strength", NULL};
    char k[128];
    json_child_key(k, sizeof k, mkey, "animation", 0);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(m, "animation");
    memset(a, 0, sizeof *a);
    if (!v)
        return 0;
    if (!cJSON_IsObject(v))
        return json_fail(r, k, "must be an object with \"keys\"");
    if (json_check_keys(r, v, k, keys) != 0)
        return -1;
    if (!emits)
        return json_fail(r, k, "the material emits nothing: only an emitter (a material with \"emission\") can be "
                               "animated");
    if (cJSON_GetObjectItemCaseSensitive(v, "transform")) {
        char t[160];
        json_child_key(t, sizeof t, k, "transform", 0);
        return json_fail(r, t, "moving emitters are not supported yet (only \"keys\" of strength)");
    }
    const cJSON *mode = cJSON_GetObjectItemCaseSensitive(v, "interpolation");
    if (mode && (!cJSON_IsString(mode) || (strcmp(mode->valuestring, "linear") && strcmp(mode->valuestring, "step")))) {
        char t[160];
        json_child_key(t, sizeof t, k, "interpolation", 0);
        return json_fail(r, t, "must be \"linear\" or \"step\"");
    }
    a->step = mode && !strcmp(mode->valuestring, "step");
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(v, "keys");
    char lk[160];
    json_child_key(lk, sizeof lk, k, "keys", 0);
    if (!cJSON_IsArray(list) || cJSON_GetArraySize(list) < 1)
        return json_fail(r, lk, list ? "must be an array of at least one {\"frame\", \"strength\"}" : "missing");
    const int n = cJSON_GetArraySize(list);
    a->frame = xmalloc(sizeof(float) * (size_t)n);
    a->strength = xmalloc(sizeof(float) * (size_t)n);
    int i = 0;
    for (const cJSON *e = list->child; e; e = e->next, i++) {
        char ek[192];
        json_child_key(ek, sizeof ek, lk, NULL, i);
        a->n = i; /* what is filled so far, for the caller's free */
        if (!cJSON_IsObject(e))
            return json_fail(r, ek, "must be an object {\"frame\", \"strength\"}");
        if (json_check_keys(r, e, ek, key_keys) != 0 ||
            json_get_number(r, e, ek, "frame", 1, -1e9, 1e9, 0.0f, &a->frame[i]) != 0 ||
            json_get_number(r, e, ek, "strength", 1, 0.0, 1e6, 0.0f, &a->strength[i]) != 0)
            return -1;
        if (i > 0 && !(a->frame[i] > a->frame[i - 1])) {
            char fk[224];
            json_child_key(fk, sizeof fk, ek, "frame", 0);
            return json_fail(r, fk, "%g is not after the previous key's frame %g (keys must be in order)",
                             (double)a->frame[i], (double)a->frame[i - 1]);
        }
    }
    a->n = n;
    return 0;
}

/* Keeps material id's animation for the scene (r->anim grows with the materials). */
void json_keep_animation(struct json_reader *r, int id, const struct emission_animation *a)
{
    if (id >= r->anim_cap) {
        const int cap = id + 16;
        r->anim = xrealloc(r->anim, sizeof(*r->anim) * (size_t)cap);
        memset(r->anim + r->anim_cap, 0, sizeof(*r->anim) * (size_t)(cap - r->anim_cap));
        r->anim_cap = cap;
    }
    r->anim[id] = *a;
    r->animated |= a->n > 0;
}

int json_read_animation(struct json_reader *r, const cJSON *m, const char *mkey, vec3 *emission,
                        struct emission_animation *a)
{
    if (read_animation(r, m, mkey, v3_max_component(*emission) > 0.0f, a) != 0) {
        free(a->frame);
        free(a->strength);
        return -1;
    }
    if (a->n == 0)
        return 0;
    /* sampling's tables see the largest strength; scene_set_frame the frame's */
    a->emission = *emission;
    *emission = v3_scale(*emission, emission_animation_max(a));
    if (v3_max_component(*emission) > 1e18f) {
        free(a->frame);
        free(a->strength);
        char k[80];
        json_child_key(k, sizeof k, mkey, "animation", 0);
        return json_fail(r, k, "emission times its largest strength exceeds 1e18");
    }
    return 0;
}

void json_animation_attach(struct json_reader *r, struct scene *s)
{
    if (s && r->animated) { /* the animation keys move into the scene, frame 0 set */
        s->emission_anim = xcalloc((size_t)s->num_materials, sizeof(*s->emission_anim));
        for (int m = 0; m < s->num_materials && m < r->anim_cap; m++) {
            s->emission_anim[m] = r->anim[m];
            r->anim[m].frame = r->anim[m].strength = NULL;
        }
        scene_set_frame(s, 0.0f);
    }
    for (int m = 0; m < r->anim_cap; m++) {
        free(r->anim[m].frame);
        free(r->anim[m].strength);
    }
    free(r->anim);
}
