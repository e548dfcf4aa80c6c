/* method.c: looking methods up in the registry, and the checks and defaults every method shares
 * (method.h). Must never depend on the passes or the ray tracer. */
#include "methods/method.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

const struct method *method_find(const char *name)
{
    for (int k = 0; name && k < method_count(); k++)
        if (strcmp(name, method_at(k)->name) == 0)
            return method_at(k);
    return NULL;
}

const struct method *method_named(const char *name)
{
    const struct method *m = method_find(name);
    if (!m) {
        fprintf(stderr, "restir: no registered method is called '%s'\n", name ? name : "(null)");
        abort();
    }
    return m;
}

void method_names_with(unsigned caps, char *out, size_t n)
{
    size_t len = 0;
    out[0] = '\0';
    for (int k = 0; k < method_count(); k++) {
        const struct method *m = method_at(k);
        if (!method_has(m, caps))
            continue;
        int w = snprintf(out + len, n - len, "%s%s", len ? ", " : "", m->name);
        if (w < 0 || (size_t)w >= n - len)
            return;
        len += (size_t)w;
    }
}

/* What every method reads: the scene and ray-tracing settings, the pixel jitter, the camera's lens
 * and shutter (refused by capability where a method does not render them), and temporal.reuse (by
 * capability too). */
#define METHOD_COMMON_SETTINGS "jitter scene. rays. simd camera. temporal.reuse temporal.splat_steps denoise denoise."

/* 1 when key matches one pattern of the space-separated list. */
static int setting_in(const char *list, const char *key)
{
    const size_t klen = strlen(key);
    for (const char *s = list; s && *s;) {
        while (*s == ' ')
            s++;
        size_t n = strcspn(s, " ");
        if (n > 0 && ((s[n - 1] == '.' && klen > n && !strncmp(key, s, n)) || (n == klen && !strncmp(key, s, n))))
            return 1;
        s += n;
    }
    return 0;
}

int method_uses_setting(const struct method *m, const char *key)
{
    return setting_in(METHOD_COMMON_SETTINGS, key) || setting_in(m->settings, key);
}

int method_check_assignments(const struct method *m, const char *const *assignments, int n, char *msg)
{
    for (int i = 0; i < n; i++) {
        for (const char *a = assignments[i]; a && *a;) {
            char key[96];
            size_t len = strcspn(a, "=:");
            snprintf(key, sizeof key, "%.*s", (int)(len < sizeof key - 1 ? len : sizeof key - 1), a);
            if (key[0] && !method_uses_setting(m, key)) {
                snprintf(msg, RESTIR_MSG_LEN, "--set %s: %s does not read this setting (restir render --help lists "
                         "what each setting is for)", key, m->name);
                return -1;
            }
            a = strchr(a, ':');
            a = a ? a + 1 : NULL;
        }
    }
    return 0;
}

void method_params(const struct method *m, struct render_params *p)
{
    if (m->defaults)
        m->defaults(p);
}

void method_reference_params(const struct method *m, struct render_params *p)
{
    if (method_has(m, METHOD_DIRECT_ONLY))
        p->max_bounces = 1;
}

/* The largest aperture of the scene's static camera and camera-path keys. */
static float scene_aperture(const struct scene *s)
{
    float a = s->camera.aperture;
    for (int k = 0; k < s->camera_path.num_keys; k++)
        a = s->camera_path.keys[k].cam.aperture > a ? s->camera_path.keys[k].cam.aperture : a;
    return a;
}

int method_check_settings(const struct method *m, const struct render_params *p, const struct scene *s, char *msg)
{
    char names[256];
    if (p->temporal_reuse != TEMPORAL_BACKPROJECT && !method_has(m, METHOD_PATH_RESERVOIRS)) {
        method_names_with(METHOD_PATH_RESERVOIRS, names, sizeof names);
        snprintf(msg, RESTIR_MSG_LEN, "temporal.reuse=%s: %s has no path reservoirs with primary hits to splat (%s have)",
                 p->temporal_reuse == TEMPORAL_SPLAT ? "splat" : "both", m->name, names);
        return -1;
    }
    if (!method_has(m, METHOD_CAMERA_EFFECTS)) {
        method_names_with(METHOD_CAMERA_EFFECTS, names, sizeof names);
        if (p->camera_shutter > 0.0f || p->camera_aperture > 0.0f) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "%s: %s does not render motion blur or depth of field (its samples do not carry the primary "
                     "ray's time and lens point); %s do",
                     p->camera_shutter > 0.0f ? "camera.shutter" : "camera.aperture", m->name, names);
            return -1;
        }
        if (s && scene_aperture(s) > 0.0f) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "scene %s: its camera has an aperture (depth of field), which %s does not render; %s do",
                     s->name, m->name, names);
            return -1;
        }
    }
    return m->check ? m->check(p, s, msg) : 0;
}
