/* camera.c: pinhole camera basis, primary rays, projection of world points (for reprojection),
 * and keyframed camera paths. Must never depend on the ray tracer or render passes. */
#include "scene/camera.h"

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

/* The camera path's curve: a cubic Hermite spline through the keys, with Catmull-Rom tangents at
 * interior keys (for uneven key spacing: (P_{k+1} - P_{k-1}) / (t_{k+1} - t_{k-1}), so the velocity
 * is continuous across keys) and zero velocity at the first and last key (the camera eases in and
 * out). A two-key path is then the smoothstep-eased straight line, and is computed as such (bit
 * for bit the easing the built-in scenes' paths always had). */
struct hermite {
    float h00, h10, h01, h11; /* basis at s; tangents are per unit s of the segment */
    float in_scale, out_scale; /* segment length over the spans of the tangents, 0 at the ends */
};

static vec3 hermite_v3(const struct hermite *h, vec3 prev, vec3 a, vec3 b, vec3 next)
{
    vec3 ma = v3_scale(v3_sub(b, prev), h->in_scale), mb = v3_scale(v3_sub(next, a), h->out_scale);
    return v3_add(v3_add(v3_scale(a, h->h00), v3_scale(ma, h->h10)), v3_add(v3_scale(b, h->h01), v3_scale(mb, h->h11)));
}

static float hermite_f(const struct hermite *h, float prev, float a, float b, float next)
{
    return h->h00 * a + h->h10 * (b - prev) * h->in_scale + h->h01 * b + h->h11 * (next - a) * h->out_scale;
}

struct camera scene_camera_at(const struct scene *s, int use_path, float frame)
{
    const struct camera_path *cp = &s->camera_path;
    if (!use_path || cp->num_keys == 0)
        return s->camera;
    if (frame <= cp->keys[0].frame)
        return cp->keys[0].cam;
    const int n = cp->num_keys;
    for (int k = 0; k + 1 < n; k++) {
        const struct camera_key *a = &cp->keys[k], *b = &cp->keys[k + 1];
        if (frame > b->frame)
            continue;
        const float u = (frame - a->frame) / (b->frame - a->frame);
        struct camera c;
        if (k == 0 && k + 2 >= n) {
            float t = smoothstep01(u);
            c.position = v3_lerp(a->cam.position, b->cam.position, t);
            c.target = v3_lerp(a->cam.target, b->cam.target, t);
            c.up = v3_normalize(v3_lerp(a->cam.up, b->cam.up, t));
            c.vfov_deg = a->cam.vfov_deg + (b->cam.vfov_deg - a->cam.vfov_deg) * t;
            return c;
        }
        const struct camera_key *pk = k > 0 ? &cp->keys[k - 1] : a, *nk = k + 2 < n ? &cp->keys[k + 2] : b;
        const float seg = b->frame - a->frame, u2 = u * u, u3 = u2 * u;
        struct hermite h = {2 * u3 - 3 * u2 + 1, u3 - 2 * u2 + u, -2 * u3 + 3 * u2, u3 - u2,
                            k > 0 ? seg / (b->frame - pk->frame) : 0.0f, k + 2 < n ? seg / (nk->frame - a->frame) : 0.0f};
        c.position = hermite_v3(&h, pk->cam.position, a->cam.position, b->cam.position, nk->cam.position);
        c.target = hermite_v3(&h, pk->cam.target, a->cam.target, b->cam.target, nk->cam.target);
        vec3 up = hermite_v3(&h, pk->cam.up, a->cam.up, b->cam.up, nk->cam.up);
        c.up = v3_length(up) > 1e-6f ? v3_normalize(up) : a->cam.up; /* keys' ups may nearly cancel */
        /* the spline may overshoot between keys: keep the field of view a field of view */
        c.vfov_deg = fminf(fmaxf(hermite_f(&h, pk->cam.vfov_deg, a->cam.vfov_deg, b->cam.vfov_deg, nk->cam.vfov_deg),
                                 1e-3f),
                           179.0f);
        return c;
    }
    return cp->keys[n - 1].cam;
}
