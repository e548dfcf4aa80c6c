/* test_splat_shift.c: the camera pieces of reservoir splatting and its shift (camera.h,
 * path_shift_splat in path_shift.h), on genuine paths of the shared path walk along the camera
 * paths of pillars, foliage and cornell, with a pinhole, a thin lens and a moving shutter:
 *  - rays and projection: camera_pose_project inverts camera_pose_ray (image point back within
 *    1e-3 px, the same lens point), for pinhole and thin lens, at the instant and inside the
 *    shutter; camera_view_pose is the view's own pose bit for bit at time 0 and the previous
 *    camera's at time 1 with a full shutter; a pinhole's ray is camera_view_ray's bit for bit;
 *  - the image-plane density: the ratio of camera_pose_area_per_pixel seen from two poses equals
 *    a finite-difference determinant of the map image_prev -> x_1 -> image_cur (relative 1e-3,
 *    measured 1.2e-4); a density with cos^3 on the wrong side (an early bug, which the render
 *    unbiasedness test found) misses by 5-10%;
 *  - the shift: a previous-frame path splatted into the current frame keeps x_1, the lens sample
 *    and (time_scale 1) its time, lands in the pixel its primary hit projects to, and splatting it
 *    back at the same time returns it to its pixel and sub-pixel offset (1e-3 px) with Jacobians
 *    multiplying to 1 (2e-3), the time scale entering J once; occluded or off-screen landings are
 *    refused; the checks are not vacuous (thousands of paths, Jacobians far from 1, refusals seen). */
#include <stdlib.h>
#include <string.h>

#include "render/path_shift.h"
#include "scene/scene_file.h"
#include "scene/scene_rt.h"
#include "test_util.h"

#define WIDTH 40
#define HEIGHT 24

static float frand(pcg32 *r) { return pcg32_float(r); }

static void test_pose_and_rays(const struct scene *s, const struct camera *c0, const struct camera *c1)
{
    struct camera_view v;
    camera_view_init(&v, c1, WIDTH, HEIGHT);
    struct camera_pose p;
    camera_view_pose(&v, 0.0f, &p);
    EXPECT(!memcmp(&p.position, &v.position, sizeof(vec3)) && !memcmp(&p.forward, &v.forward, sizeof(vec3)) &&
               p.tan_half_y == v.tan_half_y,
           "%s: pose at time 0 is the view's own", s->name);
    vec3 o, d;
    const float lens0[2] = {0.3f, 0.7f};
    camera_pose_ray(&v, &p, 12.25f, 7.5f, lens0, &o, &d);
    vec3 dv = camera_view_ray(&v, 12.25f, 7.5f);
    EXPECT(!memcmp(&d, &dv, sizeof(vec3)) && !memcmp(&o, &v.position, sizeof(vec3)),
           "%s: a pinhole ray is camera_view_ray's bit for bit", s->name);
    camera_view_set_shutter(&v, c0, 1.0f);
    struct camera_view v0;
    camera_view_init(&v0, c0, WIDTH, HEIGHT);
    camera_view_pose(&v, 1.0f, &p);
    EXPECT(v3_length(v3_sub(p.position, v0.position)) < 1e-5f && v3_length(v3_sub(p.forward, v0.forward)) < 1e-5f &&
               v3_length(v3_sub(p.up, v0.up)) < 1e-5f && fabsf(p.tan_half_y - v0.tan_half_y) < 1e-6f,
           "%s: a full shutter opens at the previous camera", s->name);
    /* projection inverts the ray: pinhole and lens, several times */
    pcg32 rng = pcg32_make(7, 1);
    double worst = 0.0;
    int tried = 0;
    for (int lens_on = 0; lens_on < 2; lens_on++) {
        v.lens_radius = lens_on ? 0.05f : 0.0f;
        for (int k = 0; k < 400; k++) {
            float px = frand(&rng) * WIDTH, py = frand(&rng) * HEIGHT, lens[2] = {frand(&rng), frand(&rng)};
            camera_view_pose(&v, frand(&rng), &p);
            camera_pose_ray(&v, &p, px, py, lens, &o, &d);
            struct surface_hit h;
            if (!scene_intersect(s, o, d, 0.0f, INFINITY, &h))
                continue;
            float qx, qy;
            vec3 oq;
            EXPECT(camera_pose_project(&v, &p, h.p, lens, &qx, &qy, &oq), "%s: a hit point projects", s->name);
            EXPECT(v3_length(v3_sub(oq, o)) < 1e-5f, "%s: the same lens point", s->name);
            double e = fmax(fabs(qx - px), fabs(qy - py));
            worst = e > worst ? e : worst;
            tried++;
        }
    }
    EXPECT(tried > 200 && worst < 1e-3, "%s: projection inverts rays (%d tried, worst %.2g px)", s->name, tried, worst);
}

/* |det d(image_cur)/d(image_prev)| at image point (px, py) of the previous view by central
 * differences, following x_1 over its triangle; 0 when a tap leaves the triangle. */
static double fd_determinant(const struct scene *s, const struct camera_view *vp, const struct camera_pose *pp,
                             const struct camera_view *vc, const struct camera_pose *pc, float px, float py,
                             const float lens[2], int tri)
{
    const float e = 0.05f; /* central differences: O(e^2) truncation, far less float round-off */
    float img[4][2];
    const float taps[4][2] = {{e, 0}, {-e, 0}, {0, e}, {0, -e}};
    for (int t = 0; t < 4; t++) {
        vec3 o, d, oc;
        struct surface_hit h;
        camera_pose_ray(vp, pp, px + taps[t][0], py + taps[t][1], lens, &o, &d);
        if (!scene_intersect(s, o, d, 0.0f, INFINITY, &h) || h.tri != tri ||
            !camera_pose_project(vc, pc, h.p, lens, &img[t][0], &img[t][1], &oc))
            return 0.0;
    }
    double a = (img[0][0] - img[1][0]) / (2 * e), b = (img[2][0] - img[3][0]) / (2 * e);
    double c = (img[0][1] - img[1][1]) / (2 * e), d = (img[2][1] - img[3][1]) / (2 * e);
    return fabs(a * d - b * c);
}

static void test_area_ratio(const struct scene *s, const struct camera *c0, const struct camera *c1, float lens_radius,
                            float shutter)
{
    struct camera_view vp, vc;
    camera_view_init(&vp, c0, WIDTH, HEIGHT);
    camera_view_init(&vc, c1, WIDTH, HEIGHT);
    vp.lens_radius = vc.lens_radius = lens_radius;
    if (shutter > 0.0f)
        camera_view_set_shutter(&vc, c0, shutter);
    pcg32 rng = pcg32_make(11, 3);
    int checked = 0, far_from_one = 0;
    double worst = 0.0;
    for (int k = 0; k < 3000 && checked < 300; k++) {
        float px = frand(&rng) * WIDTH, py = frand(&rng) * HEIGHT, lens[2] = {frand(&rng), frand(&rng)};
        struct camera_pose pp, pc;
        camera_view_pose(&vp, 0.0f, &pp);
        camera_view_pose(&vc, frand(&rng), &pc);
        vec3 o, d, oc;
        struct surface_hit h;
        float qx, qy;
        camera_pose_ray(&vp, &pp, px, py, lens, &o, &d);
        if (!scene_intersect(s, o, d, 0.0f, INFINITY, &h) || !camera_pose_project(&vc, &pc, h.p, lens, &qx, &qy, &oc))
            continue;
        double fd = fd_determinant(s, &vp, &pp, &vc, &pc, px, py, lens, h.tri);
        float ap = camera_pose_area_per_pixel(&vp, &pp, o, h.p, h.ng);
        float ac = camera_pose_area_per_pixel(&vc, &pc, oc, h.p, h.ng);
        /* grazing surfaces make the differences unreliable */
        if (!(fd > 0.0) || !(ap > 0.0f && ac > 0.0f) || fabsf(v3_dot(h.ng, d)) < 0.2f ||
            fabsf(v3_dot(h.ng, v3_normalize(v3_sub(h.p, oc)))) < 0.2f)
            continue;
        double rel = fabs(ap / ac / fd - 1.0);
        if (rel > 1e-3)
            printf("  at (%.3f, %.3f) -> (%.3f, %.3f): formula %.5f, differences %.5f\n", (double)px, (double)py,
                   (double)qx, (double)qy, (double)(ap / ac), fd);
        worst = rel > worst ? rel : worst;
        far_from_one += fabs(fd - 1.0) > 0.02;
        checked++;
    }
    printf("%s lens %.2f shutter %.1f: %d points, worst relative error %.2g, %d with |J - 1| > 0.02\n", s->name,
           (double)lens_radius, (double)shutter, checked, worst, far_from_one);
    EXPECT(checked >= 100 && worst < 1e-3, "%s: area ratio = finite-difference Jacobian (%d points, worst %.2g)",
           s->name, checked, worst);
}

/* ---- the shift on walked paths ----------------------------------------------------------------- */

struct collect_ctx {
    const struct scene *s;
    const struct shift_params *sp;
    struct path_sample trial;
    struct path_sample *out;
    int n, cap;
    int pixel;
    int *pixels;
};

static void collect(void *vctx, const struct path_walk *w, const struct path_candidate *c)
{
    struct collect_ctx *ctx = vctx;
    if (ctx->n == ctx->cap)
        return;
    struct path_sample x = ctx->trial;
    path_sample_from_candidate(ctx->s, ctx->sp, w, c, &x);
    if (x.length >= 2 && v3_luminance(x.f) > 0.0f && v3_is_finite(x.f)) {
        ctx->pixels[ctx->n] = ctx->pixel;
        ctx->out[ctx->n++] = x;
    }
}

static void test_splat(const struct scene *s, const struct camera *c0, const struct camera *c1, float lens_radius,
                       float shutter, enum shift_kind kind)
{
    struct camera_view vp, vc;
    camera_view_init(&vp, c0, WIDTH, HEIGHT);
    camera_view_init(&vc, c1, WIDTH, HEIGHT);
    vp.lens_radius = vc.lens_radius = lens_radius;
    if (shutter > 0.0f) {
        camera_view_set_shutter(&vp, c0, shutter); /* a still previous frame: its shutter sees c0 only */
        camera_view_set_shutter(&vc, c0, shutter);
    }
    struct shift_params sp = {.kind = kind,
                              .min_roughness = 0.25f,
                              .min_distance = 0.01f * scene_diagonal(s),
                              .distance_mode = SHIFT_DISTANCE_SCENE,
                              .rough = NULL};
    struct collect_ctx ctx = {s, &sp, {0}, NULL, 0, 4000, 0, NULL};
    ctx.out = calloc((size_t)ctx.cap, sizeof(*ctx.out));
    ctx.pixels = calloc((size_t)ctx.cap, sizeof(int));
    pcg32 rng = pcg32_make(5, 9);
    struct path_walk walk;
    for (int y = 0; y < HEIGHT; y++) {
        for (int x = 0; x < WIDTH; x++) {
            ctx.trial.u[0] = frand(&rng);
            ctx.trial.u[1] = frand(&rng);
            ctx.trial.lens[0] = lens_radius > 0.0f ? frand(&rng) : 0.0f;
            ctx.trial.lens[1] = lens_radius > 0.0f ? frand(&rng) : 0.0f;
            ctx.trial.time = shutter > 0.0f ? frand(&rng) : 0.0f;
            ctx.trial.seed = ((uint64_t)pcg32_next(&rng) << 32) | pcg32_next(&rng);
            struct camera_sample cs = {{ctx.trial.lens[0], ctx.trial.lens[1]}, ctx.trial.time};
            vec3 o, d;
            camera_sample_ray(&vp, &cs, (float)x + ctx.trial.u[0], (float)y + ctx.trial.u[1], &o, &d);
            struct surface_hit h;
            if (!scene_intersect(s, o, d, 0.0f, INFINITY, &h))
                continue;
            struct path_vertex x1 = path_vertex_from_hit(&h, d);
            ctx.pixel = y * WIDTH + x;
            path_walk_run(s, &x1, ctx.trial.seed, LIGHT_CHOICE_POWER_AREA, 5, 64, &walk, collect, &ctx);
        }
    }
    int landed = 0, refused = 0, far = 0, bad_pixel = 0, bad_round = 0;
    double worst_u = 0.0, worst_j = 0.0;
    for (int k = 0; k < ctx.n; k++) {
        const struct path_sample *x = &ctx.out[k];
        struct path_sample y, z;
        float Jf, Jb, px, py;
        int p, q;
        const float time_scale = shutter > 0.0f ? 0.5f : 1.0f; /* as a 2-stratum splat's */
        if (!path_shift_splat(s, &sp, x, &vp, &vc, x->time, time_scale, &p, &y, &Jf, &(long long){0})) {
            refused++;
            continue;
        }
        landed++;
        EXPECT(path_splat_position(x, &vc, x->time, &px, &py) && (int)py * WIDTH + (int)px == p,
               "%s: lands where its primary hit projects", s->name);
        bad_pixel += y.x1_tri != x->x1_tri || v3_length2(v3_sub(y.x1_p, x->x1_p)) != 0.0f ||
                     y.lens[0] != x->lens[0] || y.time != x->time;
        if (!path_shift_splat(s, &sp, &y, &vc, &vp, y.time, 1.0f / time_scale, &q, &z, &Jb, &(long long){0})) {
            bad_round++;
            continue;
        }
        double du = fmax(fabs(z.u[0] - x->u[0]), fabs(z.u[1] - x->u[1]));
        double dj = fabs((double)Jf * Jb - 1.0);
        if (q != ctx.pixels[k] && du < 0.5)
            bad_round++; /* same offset in another pixel */
        else if (q == ctx.pixels[k]) {
            worst_u = du > worst_u ? du : worst_u;
            worst_j = dj > worst_j ? dj : worst_j;
        }
        far += fabs(Jf / time_scale - 1.0) > 0.05;
    }
    printf("%s lens %.2f shutter %.1f shift %d: %d paths, %d landed, %d refused, %d with |J - 1| > 0.05, "
           "round trip worst du %.2g, |Jf Jb - 1| %.2g\n",
           s->name, (double)lens_radius, (double)shutter, (int)kind, ctx.n, landed, refused, far, worst_u, worst_j);
    EXPECT(ctx.n >= 400 && landed >= ctx.n / 4 && refused > 0, "%s: enough paths land and some are refused", s->name);
    EXPECT(bad_pixel == 0, "%s: the splat keeps x_1, the lens sample and the time (%d differ)", s->name, bad_pixel);
    EXPECT(bad_round <= landed / 100, "%s: splatting back returns the path (%d of %d do not)", s->name, bad_round,
           landed);
    EXPECT(worst_u < 1e-3 && worst_j < 2e-3, "%s: round trip du %.2g, |Jf Jb - 1| %.2g", s->name, worst_u, worst_j);
    free(ctx.out);
    free(ctx.pixels);
}

int main(void)
{
    const char *scenes[] = {"pillars", "foliage", "cornell"};
    for (int k = 0; k < 3; k++) {
        struct scene s;
        char msg[512];
        EXPECT(scene_load(scenes[k], &s, msg) == 0, "%s", msg);
        /* frames 12 apart: a larger step than a frame, so Jacobians differ visibly from 1 */
        struct camera c0 = scene_camera_at(&s, 1, 20.0f), c1 = scene_camera_at(&s, 1, 32.0f);
        test_pose_and_rays(&s, &c0, &c1);
        test_area_ratio(&s, &c0, &c1, 0.0f, 0.0f);
        test_area_ratio(&s, &c0, &c1, 0.05f, 0.0f);
        test_area_ratio(&s, &c0, &c1, 0.0f, 1.0f);
        test_splat(&s, &c0, &c1, 0.0f, 0.0f, SHIFT_HYBRID);
        test_splat(&s, &c0, &c1, 0.0f, 0.0f, SHIFT_REPLAY);
        test_splat(&s, &c0, &c1, 0.05f, 1.0f, SHIFT_HYBRID);
        scene_destroy(&s);
    }
    return test_finish();
}
