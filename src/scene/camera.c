/* camera.c: camera basis, primary rays of a pinhole or a thin lens at a time inside the shutter,
 * projection of world points (reprojection and reservoir splatting) with their image-plane
 * density, and keyframed camera paths. Must never depend on the ray tracer or render passes. */
#include "scene/camera.h"

#include <math.h>

#include "core/sampling.h"

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
    v->lens_radius = c->aperture;
    v->focus_distance = c->focus_distance > 0.0f ? c->focus_distance : v3_length(v3_sub(c->target, c->position));
    v->shutter = 0.0f;
    v->open_position = v->position;
    v->open_forward = v->forward;
    v->open_up = v->up;
    v->open_tan_half_y = v->tan_half_y;
}

void camera_view_set_shutter(struct camera_view *v, const struct camera *open, float shutter)
{
    struct camera_view o;
    camera_view_init(&o, open, v->width, v->height);
    v->shutter = shutter;
    v->open_position = o.position;
    v->open_forward = o.forward;
    v->open_up = o.up;
    v->open_tan_half_y = o.tan_half_y;
}

/* Spherical linear interpolation of unit vectors a -> b at t (nlerp where they nearly coincide). */
static vec3 slerp_unit(vec3 a, vec3 b, float t)
{
    float c = v3_dot(a, b);
    c = c > 1.0f ? 1.0f : (c < -1.0f ? -1.0f : c);
    float angle = acosf(c);
    if (angle < 1e-4f)
        return v3_normalize(v3_lerp(a, b, t));
    float sa = sinf(angle);
    return v3_normalize(v3_add(v3_scale(a, sinf((1.0f - t) * angle) / sa), v3_scale(b, sinf(t * angle) / sa)));
}

void camera_view_pose(const struct camera_view *v, float time, struct camera_pose *out)
{
    const float a = v->shutter * time;
    if (!(a > 0.0f)) {
        *out = (struct camera_pose){v->position, v->forward, v->right, v->up, v->tan_half_y, v->tan_half_x};
        return;
    }
    out->position = v3_lerp(v->position, v->open_position, a);
    out->forward = slerp_unit(v->forward, v->open_forward, a);
    vec3 up = v3_lerp(v->up, v->open_up, a);
    out->right = v3_normalize(v3_cross(out->forward, up));
    out->up = v3_cross(out->right, out->forward);
    out->tan_half_y = v->tan_half_y + (v->open_tan_half_y - v->tan_half_y) * a;
    out->tan_half_x = out->tan_half_y * (float)v->width / (float)v->height;
}

/* Image point -> tangent-plane coordinates at unit distance along the optical axis. */
static void image_to_tangent(const struct camera_view *v, const struct camera_pose *pose, float px, float py,
                             float *sx, float *sy)
{
    *sx = (2.0f * px / (float)v->width - 1.0f) * pose->tan_half_x;
    *sy = (1.0f - 2.0f * py / (float)v->height) * pose->tan_half_y;
}

static vec3 lens_point(const struct camera_view *v, const struct camera_pose *pose, const float lens[2])
{
    float lx, ly;
    warp_concentric_disk(lens[0], lens[1], &lx, &ly);
    return v3_add(pose->position,
                  v3_add(v3_scale(pose->right, lx * v->lens_radius), v3_scale(pose->up, ly * v->lens_radius)));
}

void camera_pose_ray(const struct camera_view *v, const struct camera_pose *pose, float px, float py,
                     const float lens[2], vec3 *origin, vec3 *dir)
{
    float sx, sy;
    image_to_tangent(v, pose, px, py, &sx, &sy);
    vec3 axis = v3_add(pose->forward, v3_add(v3_scale(pose->right, sx), v3_scale(pose->up, sy)));
    if (!(v->lens_radius > 0.0f)) {
        *origin = pose->position;
        *dir = v3_normalize(axis);
        return;
    }
    /* Thin lens: every ray through image point (px, py) meets the focal plane in one point. */
    vec3 focal = v3_madd(pose->position, axis, v->focus_distance);
    *origin = lens_point(v, pose, lens);
    *dir = v3_normalize(v3_sub(focal, *origin));
}

int camera_pose_project(const struct camera_view *v, const struct camera_pose *pose, vec3 p, const float lens[2],
                        float *px, float *py, vec3 *origin)
{
    const int lens_on = v->lens_radius > 0.0f;
    *origin = lens_on ? lens_point(v, pose, lens) : pose->position;
    vec3 d = v3_sub(p, *origin);
    float z = v3_dot(d, pose->forward);
    if (!(z > 1e-6f))
        return 0;
    float sx, sy;
    if (lens_on) {
        /* where the ray origin -> p meets the focal plane, relative to the lens centre */
        vec3 focal = v3_sub(v3_madd(*origin, d, v->focus_distance / z), pose->position);
        sx = v3_dot(focal, pose->right) / v->focus_distance;
        sy = v3_dot(focal, pose->up) / v->focus_distance;
    } else {
        sx = v3_dot(d, pose->right) / z;
        sy = v3_dot(d, pose->up) / z;
    }
    *px = (sx / pose->tan_half_x + 1.0f) * 0.5f * (float)v->width;
    *py = (1.0f - sy / pose->tan_half_y) * 0.5f * (float)v->height;
    return 1;
}

struct camera_sample camera_sample_draw(const struct camera_view *v, pcg32 *rng)
{
    struct camera_sample cs = {{0.0f, 0.0f}, 0.0f};
    if (v->lens_radius > 0.0f) {
        cs.lens[0] = pcg32_float(rng);
        cs.lens[1] = pcg32_float(rng);
    }
    if (v->shutter > 0.0f)
        cs.time = pcg32_float(rng);
    return cs;
}

void camera_sample_ray(const struct camera_view *v, const struct camera_sample *cs, float px, float py, vec3 *origin,
                       vec3 *dir)
{
    struct camera_pose pose;
    camera_view_pose(v, cs->time, &pose);
    camera_pose_ray(v, &pose, px, py, cs->lens, origin, dir);
}

float camera_pose_area_per_pixel(const struct camera_view *v, const struct camera_pose *pose, vec3 origin, vec3 p,
                                 vec3 n)
{
    vec3 d = v3_sub(p, origin);
    float d2 = v3_length2(d);
    if (!(d2 > 0.0f))
        return 0.0f;
    float inv = 1.0f / sqrtf(d2);
    float cos_axis = v3_dot(d, pose->forward) * inv, cos_surface = fabsf(v3_dot(d, n)) * inv;
    if (!(cos_axis > 0.0f) || !(cos_surface > 0.0f))
        return 0.0f;
    /* dA = d^2 / |cos_s| dw, dw = cos^3(theta) dsx dsy, dsx dsy = (2 tan_x / W)(2 tan_y / H) dpx dpy */
    float pixel = (2.0f * pose->tan_half_x / (float)v->width) * (2.0f * pose->tan_half_y / (float)v->height);
    return d2 * cos_axis * cos_axis * cos_axis / cos_surface * pixel;
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
            c.aperture = a->cam.aperture + (b->cam.aperture - a->cam.aperture) * t;
            c.focus_distance = a->cam.focus_distance + (b->cam.focus_distance - a->cam.focus_distance) * t;
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
        /* the lens moves linearly between keys (no overshoot below 0) */
        c.aperture = a->cam.aperture + (b->cam.aperture - a->cam.aperture) * u;
        c.focus_distance = a->cam.focus_distance + (b->cam.focus_distance - a->cam.focus_distance) * u;
        return c;
    }
    return cp->keys[n - 1].cam;
}
