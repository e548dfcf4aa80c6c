/* method.c: looking methods up in the registry, and the checks and defaults every method shares
 * (method.h). Must never depend on the passes or the ray tracer. */
#include "methods/method.h"
#include "scene/scene_animation.h"
#include "scene/scene_motion.h"

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

int method_output_count(const struct method *m)
{
    int n = 0;
    while (m->outputs && m->outputs[n].name)
        n++;
    return n;
}

int method_output_find(const struct method *m, const char *name, enum method_output_kind kind)
{
    for (int k = 0; k < method_output_count(m); k++)
        if (m->outputs[k].kind == kind && !strcmp(m->outputs[k].name, name))
            return k;
    return -1;
}

void method_names_where(int (*keep)(const struct method *m, const void *ctx), const void *ctx, char *out, size_t n)
{
    size_t len = 0;
    if (n > 0)
        out[0] = '\0';
    for (int k = 0; k < method_count(); k++) {
        const struct method *m = method_at(k);
        if (!keep(m, ctx))
            continue;
        int w = snprintf(out + len, n - len, "%s%s", len ? ", " : "", m->name);
        if (w < 0 || (size_t)w >= n - len)
            return;
        len += (size_t)w;
    }
}

static int has_caps(const struct method *m, const void *caps) { return method_has(m, *(const unsigned *)caps); }

void method_names_with(unsigned caps, char *out, size_t n) { method_names_where(has_caps, &caps, out, n); }

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
    if (p->reuse.temporal_reuse != TEMPORAL_BACKPROJECT && !method_has(m, METHOD_PATH_RESERVOIRS)) {
        method_names_with(METHOD_PATH_RESERVOIRS, names, sizeof names);
        snprintf(msg, RESTIR_MSG_LEN,
                 "temporal.reuse=%s: %s has no path reservoirs with primary hits to splat (%s have)",
                 p->reuse.temporal_reuse == TEMPORAL_SPLAT ? "splat" : "both", m->name, names);
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
    if (p->denoise.svgf_temporal_gradient && !method_has(m, METHOD_TEMPORAL_GRADIENT)) {
        method_names_with(METHOD_TEMPORAL_GRADIENT, names, sizeof names);
        snprintf(msg, RESTIR_MSG_LEN,
                 "denoise.svgf.temporal_gradient=on: %s hands the denoiser no temporal gradient (methods that do: %s)",
                 m->name, names);
        return -1;
    }
    if (s && scene_has_moving_emitters(s) && p->camera_shutter > 0.0f) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "camera.shutter: scene %s has moving emitters, and motion blur sees the scene at one instant "
                 "(the ray-tracing BVH holds one pose): render it with camera.shutter=0",
                 s->name);
        return -1;
    }
    if (s && scene_is_animated(s) && !method_has(m, METHOD_ANIMATED_EMITTERS)) {
        method_names_with(METHOD_ANIMATED_EMITTERS, names, sizeof names);
        snprintf(msg, RESTIR_MSG_LEN,
                 "scene %s has animated emitters, which %s does not render yet (samples it reuses would keep "
                 "an earlier frame's lights); %s do",
                 s->name, m->name, names);
        return -1;
    }
    return m->check ? m->check(p, s, msg) : 0;
}
