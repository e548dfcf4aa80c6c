/* camera.c: pinhole camera basis, primary rays, projection of world points (for reprojection),
 * and keyframed camera paths. Must never depend on the ray tracer or render passes. */
#include "camera.h"

#include <math.h>

void camera_view_init(struct camera_view *v, const struct camera *c, int width, int height)
{
    v->position = c->position;
    v->forward = v3_normalize(v3_sub(c->target, c->position));
    v->right = v3_normalize(v3_cross(v->forward, c->up));
    v->up = v3_cross(v->right, v->forward);
    v->tan_half_y = tanf(0.5f * c->vfov_deg * RESTIR_PI / 180.0f);
    v->tan_half_x = v->tan_half_y * (float)width / (float)height;
    v->width = width;
    v->height = height;
}

vec3 camera_view_ray(const struct camera_view *v, float px, float py)
{
    float sx = (2.0f * px / (float)v->width - 1.0f) * v->tan_half_x;
    float sy = (1.0f - 2.0f * py / (float)v->height) * v->tan_half_y;
    return v3_normalize(v3_add(v->forward, v3_add(v3_scale(v->right, sx), v3_scale(v->up, sy))));
}

int camera_view_project(const struct camera_view *v, vec3 p, float *px, float *py)
{
    vec3 d = v3_sub(p, v->position);
    float z = v3_dot(d, v->forward);
    if (!(z > 1e-6f))
        return 0;
    float sx = v3_dot(d, v->right) / z, sy = v3_dot(d, v->up) / z;
    *px = (sx / v->tan_half_x + 1.0f) * 0.5f * (float)v->width;
    *py = (1.0f - sy / v->tan_half_y) * 0.5f * (float)v->height;
    return 1;
}

static float smoothstep01(float t) { return t * t * (3.0f - 2.0f * t); }

struct camera scene_camera_at(const struct scene *s, int use_path, float frame)
{
    const struct camera_path *cp = &s->camera_path;
    if (!use_path || cp->num_keys == 0)
        return s->camera;
    if (frame <= cp->keys[0].frame)
        return cp->keys[0].cam;
    for (int k = 0; k + 1 < cp->num_keys; k++) {
        const struct camera_key *a = &cp->keys[k], *b = &cp->keys[k + 1];
        if (frame <= b->frame) {
            float t = smoothstep01((frame - a->frame) / (b->frame - a->frame));
            struct camera c;
            c.position = v3_lerp(a->cam.position, b->cam.position, t);
            c.target = v3_lerp(a->cam.target, b->cam.target, t);
            c.up = v3_normalize(v3_lerp(a->cam.up, b->cam.up, t));
            c.vfov_deg = a->cam.vfov_deg + (b->cam.vfov_deg - a->cam.vfov_deg) * t;
            return c;
        }
    }
    return cp->keys[cp->num_keys - 1].cam;
}
