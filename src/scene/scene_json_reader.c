/* scene_json_reader.c: typed getters for our JSON files (scenes, camera files) whose every error
 * names the file and the key. Must never depend on what the values mean (the builder, formats). */
#include "scene/scene_json_reader.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/check.h"

void json_msgf(char *out, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out, len, fmt, ap);
    va_end(ap);
}

int json_fail(struct json_reader *r, const char *key, const char *fmt, ...)
{
    char what[RESTIR_MSG_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (key && *key)
        json_msgf(r->msg, RESTIR_MSG_LEN, "%s: %s: %s", r->file, key, what);
    else
        json_msgf(r->msg, RESTIR_MSG_LEN, "%s: %s", r->file, what);
    return -1;
}

void json_child_key(char *out, size_t len, const char *parent, const char *name, int index)
{
    int n = name ? snprintf(out, len, "%s%s%s", parent, *parent ? "." : "", name)
                 : snprintf(out, len, "%s[%d]", parent, index);
    if (n >= (int)len && len > 4)
        memcpy(out + len - 4, "...", 4); /* a cut key says so */
}

int json_check_keys(struct json_reader *r, const cJSON *obj, const char *key, const char *const *allowed)
{
    if (!cJSON_IsObject(obj))
        return json_fail(r, key, "must be an object");
    for (const cJSON *c = obj->child; c; c = c->next) {
        int known = 0;
        for (int i = 0; allowed[i] && !known; i++)
            known = strcmp(c->string, allowed[i]) == 0;
        if (!known) {
            char k[256];
            json_child_key(k, sizeof k, key, c->string, 0);
            return json_fail(r, k, "unknown key");
        }
    }
    return 0;
}

/* The member name of obj (its key, for messages, into k): 1 with *v when present, 0 when absent
 * and optional, -1 (with the message) when absent and required. */
static int member(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int required, char *k,
                  size_t klen, const cJSON **v)
{
    json_child_key(k, klen, key, name, 0);
    *v = cJSON_GetObjectItemCaseSensitive(obj, name);
    if (*v)
        return 1;
    return required ? json_fail(r, k, "missing") : 0;
}

int json_get_number(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int required,
                    double lo, double hi, float fallback, float *out)
{
    char k[256];
    const cJSON *v;
    int has = member(r, obj, key, name, required, k, sizeof k, &v);
    if (has <= 0) {
        *out = fallback;
        return has;
    }
    if (!cJSON_IsNumber(v))
        return json_fail(r, k, "must be a number");
    double d = v->valuedouble;
    if (!isfinite(d) || d < lo || d > hi)
        return json_fail(r, k, "%g is out of range [%g, %g]", d, lo, hi);
    *out = (float)d;
    return 0;
}

int json_get_int(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int lo, int hi,
                 int fallback, int *out)
{
    float f = 0.0f; /* set whenever json_get_number returns 0; GCC cannot see it across the call */
    if (json_get_number(r, obj, key, name, 0, lo, hi, (float)fallback, &f) != 0)
        return -1;
    if (f != floorf(f)) {
        char k[256];
        json_child_key(k, sizeof k, key, name, 0);
        return json_fail(r, k, "must be an integer");
    }
    *out = (int)f;
    return 0;
}

int json_get_bool(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, name);
    if (!v) {
        *out = 0;
        return 0;
    }
    if (!cJSON_IsBool(v)) {
        char k[256];
        json_child_key(k, sizeof k, key, name, 0);
        return json_fail(r, k, "must be true or false");
    }
    *out = cJSON_IsTrue(v);
    return 0;
}

int json_vec3_value(struct json_reader *r, const cJSON *v, const char *key, double lo, double hi, vec3 *out)
{
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3)
        return json_fail(r, key, "must be an array of 3 numbers");
    float c[3];
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return json_fail(r, key, "must be an array of 3 finite numbers");
        if (e->valuedouble < lo || e->valuedouble > hi)
            return json_fail(r, key, "component %g is out of range [%g, %g]", e->valuedouble, lo, hi);
        c[i] = (float)e->valuedouble;
    }
    *out = v3(c[0], c[1], c[2]);
    return 0;
}

int json_get_vec3(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int required,
                  double lo, double hi, vec3 fallback, vec3 *out)
{
    char k[256];
    const cJSON *v;
    int has = member(r, obj, key, name, required, k, sizeof k, &v);
    if (has <= 0) {
        *out = fallback;
        return has;
    }
    return json_vec3_value(r, v, k, lo, hi, out);
}

const cJSON *json_get_array(struct json_reader *r, const cJSON *obj, const char *key, const char *name,
                            int required, int *ok)
{
    char k[256];
    json_child_key(k, sizeof k, key, name, 0);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, name);
    *ok = 1;
    if (!v) {
        if (required)
            *ok = json_fail(r, k, "missing") == 0;
        return NULL;
    }
    if (!cJSON_IsArray(v)) {
        *ok = json_fail(r, k, "must be an array") == 0;
        return NULL;
    }
    return v;
}

int json_line_of(const char *text, const char *at)
{
    int line = 1;
    for (const char *c = text; at && c < at && *c; c++)
        line += *c == '\n';
    return line;
}
