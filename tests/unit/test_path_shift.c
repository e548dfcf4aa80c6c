/* test_path_shift.c: the ReSTIR PT shift mappings (path_shift.h) are bijections with correct
 * Jacobians, checked on genuine paths of the shared path walk (every candidate of jittered walks
 * of up to 6 bounces, as pt_initial_pass would store it) in the cornell and ajar scenes, for
 * reconnection, random replay and the hybrid shift (once with thresholds that make it replay
 * through glossy metal and short segments and reconnect mid-path, once with a roughness threshold
 * nothing reaches, so that it replays up to the light):
 *  - identity: shifting a path to the pixel domain it lives in succeeds and gives the same path
 *    back (same seed and reconnection vertex, u bit-identical, same prefix density, f of
 *    the path through its vertices) with |T'| = 1; doing it twice changes nothing at all;
 *  - inverse: shifting a path to another domain and back (a spatial neighbor; a previous-frame
 *    pixel under the fractional projected camera motion, as restir_pt.c builds it; a
 *    previous-frame pixel with a fixed fractional offset, so u wraps around the pixel; a distant
 *    pixel) recovers the original path (u, reconnection vertex, prefix density, f) and the
 *    Jacobians of the two shifts multiply to 1;
 *  - forward: the shifted path's offset is u + origin_A - origin_B wrapped (clipped domains: that
 *    sum, and no shift into a pixel it falls outside of), its prefix is the
 *    one the path walk generates in the target with the same seed, |T'| equals the ratio of the
 *    two walks' prefix densities times the ratio of the solid angles of x_k seen from the two
 *    y_{k-1}, and the hybrid rule holds in the target;
 *  - the checks are not vacuous: every kind runs on thousands of paths, replay and hybrid on
 *    many with a replayed prefix (k >= 3), the hybrid shift reconnects mid-path (3 <= k < D),
 *    many forward Jacobians are far from 1 (distant reconnections nearly always), and the same
 *    round-trip checks flag a shift back into the wrong pixel. */
#include <stdlib.h>
#include <string.h>

#include "render/path_shift.h"
#include "scene/scenes_builtin.h"
#include "shading/bsdf.h"
#include "test_util.h"

#define WIDTH 64
#define HEIGHT 48
#define MAX_BOUNCES 6
#define RR_BOUNCES 64 /* no Russian roulette: long paths must occur */

/* Tolerances. path_shift adds only the fractional part of the origin difference to u, so identity
 * and whole-pixel shifts keep u bit-identical; fractional (temporal) round trips return u to
 * within an ulp (6e-8), which near-degenerate reconnections (vertices a few millimetres apart in
 * ajar's door gap) amplify to 1.3e-3 in Jf Jb. Broken Jacobians miss by far more (> 1e-2 in the
 * mutation runs). The rest is the rounding of the Jacobian and BSDF formulas. DIR_EXACT: see
 * reference_f. */
#define TOL_ID_J 1e-4
#define TOL_ID_F 1e-3
#define TOL_RT_J 3e-3
#define TOL_RT_F 1e-2
#define TOL_RT_U 1e-5
#define DIR_EXACT 1e-5
#define TOL_RT_PDF 1e-3
#define MIN_ID_RATE 0.99
#define MIN_BACK_RATE 0.97

/* ---- shift configurations ------------------------------------------------------------------ */

enum { CFG_RECONNECTION, CFG_REPLAY, CFG_HYBRID, CFG_HYBRID_NOROUGH, CFG_HYBRID_RELATIVE, NCFG };

struct config {
    const char *name;
    enum shift_kind kind;
    float min_roughness;
    float distance_frac; /* min_distance as a fraction of the scene diagonal, or (relative) of the
                            camera's distance to the segment's first vertex */
    enum shift_distance_mode distance_mode;
};

/* Metals here have GGX alpha 0.06 .. 0.16 and anything with a diffuse lobe reports roughness 1
 * (bsdf_roughness), so 0.3 makes the hybrid shift replay through every metal vertex; 2 makes
 * nothing rough, so it replays up to the light like random replay. */
static const struct config configs[NCFG] = {
    {"reconnection", SHIFT_RECONNECTION, 0.2f, 0.01f, SHIFT_DISTANCE_SCENE},
    {"replay", SHIFT_REPLAY, 0.2f, 0.01f, SHIFT_DISTANCE_SCENE},
    {"hybrid", SHIFT_HYBRID, 0.3f, 0.05f, SHIFT_DISTANCE_SCENE},
    {"hybrid-norough", SHIFT_HYBRID, 2.0f, 0.01f, SHIFT_DISTANCE_SCENE},
    /* each domain judges segments by its own camera: the motion round trips cross cameras */
    {"hybrid-relative", SHIFT_HYBRID, 0.3f, 0.1f, SHIFT_DISTANCE_RELATIVE},
};

/* ---- target domains of the round trips ------------------------------------------------------ */

enum { DOM_SPATIAL, DOM_MOTION, DOM_FRACTION, DOM_DISTANT, DOM_CLIPPED, NDOM };
static const char *const dom_names[NDOM] = {"spatial", "motion", "fraction", "distant", "clipped"};

/* ---- samples --------------------------------------------------------------------------------- */

struct sample {
    struct path_sample x;
    int px, py;    /* its pixel in the current view; origin (px, py) */
    float dir_err; /* |walk's direction x_{k-1} -> x_k - normalize(x_k - x_{k-1})| */
    vec3 f_vert;   /* f of the path through the stored vertices (reference_f) */
};

struct sample_list {
    struct sample *v;
    int n, cap;
};

static void list_push(struct sample_list *l, const struct sample *s)
{
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 4096;
        l->v = realloc(l->v, (size_t)l->cap * sizeof(*l->v));
        if (!l->v) {
            printf("out of memory\n");
            exit(2);
        }
    }
    l->v[l->n++] = *s;
}

struct collect_ctx {
    const struct scene *s;
    const struct shift_params *sp; /* NCFG */
    struct path_sample trial;      /* u and seed of the walk */
    int px, py;
    struct sample_list *lists;     /* NCFG */
};

/* The contribution of the walked path with its reconnection segment taken between the stored
 * vertices x_{k-1} and x_k rather than along the ray the walk traced: that ray leaves from a point
 * offset off the surface (scene_offset_point, ~4e-4 here), so where x_{k-1} and x_k are close
 * (corners, the door's gaps) its direction differs from the vertices' (by up to 0.17 in ajar), and
 * the walk's f with it (by up to 90%; by more than 1% for about 2% of reconnection samples). The
 * shift evaluates the path through the vertices, and so does this reference, from path_walk.h:
 * f = prod_{j<k-1} fcos_j * f_s(x_{k-1}) cos * [f_s(x_k) |n_k . w_k| if k < D] * L(x_k). */
static vec3 reference_f(const struct scene *s, const struct path_walk *w, const struct path_candidate *c,
                        const struct path_sample *x)
{
    const int k = x->rc, D = c->length;
    vec3 f = v3s(1.0f);
    for (int j = 1; j <= k - 2; j++)
        f = v3_mul(f, w->v[j - 1].fcos);
    const struct path_vertex *a = &w->v[k - 2];
    vec3 wk = v3_normalize(v3_sub(x->rc_p, a->p));
    struct bsdf b;
    bsdf_from_material(&s->materials[a->material], &b);
    f = v3_mul(f, v3_scale(bsdf_eval(&b, a->ns, a->wo, wk), v3_dot(a->ns, wk)));
    if (k < D) {
        const struct path_vertex *xk = &w->v[k - 1];
        vec3 wn = k == D - 1 ? c->w_last : xk->w_next;
        bsdf_from_material(&s->materials[xk->material], &b);
        f = v3_mul(f, v3_scale(bsdf_eval(&b, xk->ng, v3_neg(wk), wn), fabsf(v3_dot(xk->ng, wn))));
        vec3 L = c->Le; /* radiance arriving at x_k from x_{k+1} */
        for (int j = D - 1; j > k; j--)
            L = v3_mul(L, j == D - 1 ? c->fcos_last : w->v[j - 1].fcos);
        return v3_mul(f, L);
    }
    return v3_mul(f, c->Le);
}

/* Every candidate of the walk becomes a sample of every configuration (what pt_initial_pass
 * would store if it selected it). */
static void collect(void *vctx, const struct path_walk *w, const struct path_candidate *c)
{
    struct collect_ctx *ctx = vctx;
    for (int k = 0; k < NCFG; k++) {
        struct sample smp;
        smp.x = ctx->trial;
        smp.px = ctx->px;
        smp.py = ctx->py;
        path_sample_from_candidate(ctx->s, &ctx->sp[k], w, c, &smp.x);
        const struct path_vertex *prev = &w->v[smp.x.rc - 2];
        vec3 walked = smp.x.rc == c->length ? c->w_last : prev->w_next;
        smp.dir_err = v3_length(v3_sub(walked, v3_normalize(v3_sub(smp.x.rc_p, prev->p))));
        smp.f_vert = reference_f(ctx->s, w, c, &smp.x);
        if (smp.x.length >= 2 && v3_luminance(smp.x.f) > 0.0f && v3_is_finite(smp.x.f))
            list_push(&ctx->lists[k], &smp);
    }
}

/* ---- comparisons ----------------------------------------------------------------------------- */

static double rel_diff(double a, double b)
{
    double m = fmax(fabs(a), fabs(b));
    return m > 0.0 ? fabs(a - b) / m : 0.0;
}

static double f_diff(vec3 a, vec3 b)
{
    double m = fmax(fmax(fabs(a.x), fabs(a.y)), fabs(a.z));
    m = fmax(m, fmax(fmax(fabs(b.x), fabs(b.y)), fabs(b.z)));
    if (!(m > 0.0))
        return 0.0;
    double d = fmax(fmax(fabs(a.x - b.x), fabs(a.y - b.y)), fabs(a.z - b.z));
    return d / m;
}

/* Distance of two sub-pixel offsets (not wrapped: u = 0 and u = 1 - eps are a pixel apart). */
static double u_diff(const float a[2], const float b[2])
{
    return fmax(fabs((double)a[0] - (double)b[0]), fabs((double)a[1] - (double)b[1]));
}

static int v3_same(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

static struct pt_domain make_domain(const struct camera_view *v, int x, int y, float ox, float oy)
{
    struct pt_domain d = {v, x, y, {ox, oy}, 0};
    return d;
}

/* Deviations of a round trip's result z (|J| of the two shifts Jf, Jb) from the path x it
 * started from, xid being x as the shift evaluates it in its own domain. Returns 1 when z is not
 * x back. */
struct rt_dev {
    double j, f, u, pdf;
};

static int roundtrip_wrong(const struct path_sample *x, const struct path_sample *xid, const struct path_sample *z,
                           float Jf, float Jb, struct rt_dev *d)
{
    d->j = fabs((double)Jf * (double)Jb - 1.0);
    d->f = f_diff(z->f, xid->f);
    d->u = u_diff(z->u, x->u);
    d->pdf = rel_diff(z->prefix_pdf, xid->prefix_pdf);
    int same = z->seed == x->seed && z->length == x->length && z->rc == x->rc && v3_same(z->rc_p, x->rc_p) &&
               v3_same(z->rc_n, x->rc_n) && v3_same(z->rc_w, x->rc_w) && v3_same(z->rc_L, x->rc_L) &&
               z->rc_material == x->rc_material;
    return !same || d->j > TOL_RT_J || d->f > TOL_RT_F || d->u > TOL_RT_U || d->pdf > TOL_RT_PDF;
}

static void ignore_candidate(void *ctx, const struct path_walk *w, const struct path_candidate *c)
{
    (void)ctx;
    (void)w;
    (void)c;
}

/* The prefix y_1 .. y_{k-1} that the path walk generates with this seed from offset u in a domain:
 * what the shift must replay (path_walk.h: vertex j draws from its own stream). Returns 0 when the
 * walk ends before y_{k-1}. */
static int walk_prefix(const struct scene *s, const struct pt_domain *d, const float u[2], uint64_t seed, int k,
                       struct path_walk *w)
{
    float px, py;
    path_image_position(d->x, d->y, u, &px, &py);
    vec3 dir = camera_view_ray(d->view, px, py);
    struct surface_hit h;
    if (!scene_intersect(s, d->view->position, dir, 0.0f, INFINITY, &h))
        return 0;
    struct path_vertex x1 = path_vertex_from_hit(&h, dir);
    path_walk_run(s, &x1, seed, LIGHT_CHOICE_POWER_AREA, k - 2, 1 << 20, w, ignore_candidate, NULL);
    return w->nv == k - 1;
}

static double prefix_density(const struct path_walk *w, int k)
{
    double p = 1.0;
    for (int j = 1; j <= k - 2; j++)
        p *= (double)w->v[j - 1].pdf_dir;
    return p;
}

/* The hybrid rule (path_shift.h): may a path reconnect at b coming from a? */
static int rough(const struct scene *s, const struct shift_params *sp, int material)
{
    struct bsdf b;
    bsdf_from_material(&s->materials[material], &b);
    return bsdf_roughness(&b) >= sp->min_roughness;
}

/* The hybrid rule as the domain whose camera is at `camera` applies it (path_shift.h). */
static int connectable(const struct scene *s, const struct shift_params *sp, vec3 camera, vec3 pa, int ma, vec3 pb,
                       int mb)
{
    const float m = sp->distance_mode == SHIFT_DISTANCE_RELATIVE ? sp->distance_factor * v3_length(v3_sub(pa, camera))
                                                                  : sp->min_distance;
    return rough(s, sp, ma) && (mb < 0 || rough(s, sp, mb)) && v3_length(v3_sub(pb, pa)) > m;
}

/* Solid angle per unit area of x_k seen from p: |n_k . (p - x_k)| / |p - x_k|^3. */
static double solid_angle_factor(vec3 p, const struct path_sample *x)
{
    vec3 d = v3_sub(p, x->rc_p);
    double d2 = (double)v3_length2(d);
    return fabs((double)v3_dot(x->rc_n, d)) / (d2 * sqrt(d2));
}

/* ---- statistics ------------------------------------------------------------------------------ */

struct id_stats {
    long tried, ok, bad;
    long exact; /* paths whose walked direction x_{k-1} -> x_k is the vertices' (dir_err) */
    double worst_j, worst_u, worst_pdf, worst_f, worst_f_walk, worst_f_offset, worst_idem;
};

struct rt_stats {
    long tried, fwd_ok, back_ok, bad;
    long deep;       /* round trips with k >= 3 */
    long nontrivial; /* round trips with |J_forward - 1| > 1e-2 */
    double worst_j, worst_f, worst_u, worst_pdf;
    long geo;        /* forward shifts whose Jacobian was recomputed from walked prefixes */
    double worst_geo;
    double worst_uf; /* forward: |y.u - wrap(x.u + origin_A - origin_B)| */
    long wrong, wrong_caught; /* control: inverse shifts into the wrong pixel, and how many are flagged */
    long outside;             /* clipped: shifts into the next previous pixel tried (each must fail) */
};

static int bad_printed;

static void report_bad(const char *what, const char *scene, const struct config *cfg, const struct sample *s,
                       double dj, double df, double du)
{
    if (bad_printed++ >= 12)
        return;
    printf("  BAD %s %s %s: pixel (%d,%d) D=%d k=%d u=(%.7f,%.7f) seed=%llu |J-1|=%.3g f=%.3g u=%.3g\n", what,
           scene, cfg->name, s->px, s->py, s->x.length, s->x.rc, (double)s->x.u[0], (double)s->x.u[1],
           (unsigned long long)s->x.seed, dj, df, du);
}

/* ---- one scene ------------------------------------------------------------------------------- */

/* paths: jittered paths walked per pixel (ajar is mostly dark: few paths reach its light). */
static void test_scene(const char *name, int paths)
{
    struct scene s;
    char msg[512];
    if (scene_create_builtin(name, &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    /* The current frame 6 and the previous frame 0 of the scene's camera path. */
    struct camera_view cur, prev;
    struct camera ccur = scene_camera_at(&s, 1, 6.0f), cprev = scene_camera_at(&s, 1, 0.0f);
    camera_view_init(&cur, &ccur, WIDTH, HEIGHT);
    camera_view_init(&prev, &cprev, WIDTH, HEIGHT);

    struct shift_params sp[NCFG];
    for (int k = 0; k < NCFG; k++) {
        sp[k].kind = configs[k].kind;
        sp[k].min_roughness = configs[k].min_roughness;
        sp[k].min_distance = configs[k].distance_frac * scene_diagonal(&s);
        sp[k].distance_mode = configs[k].distance_mode;
        sp[k].distance_factor = configs[k].distance_frac;
        sp[k].camera = cur.position; /* the samples are made in the current view */
        sp[k].rough = NULL; /* roughness computed per query */
    }

    /* Genuine samples: jittered primary rays and path walks as pt_initial_pass makes them. */
    struct sample_list lists[NCFG];
    memset(lists, 0, sizeof(lists));
    struct collect_ctx ctx = {&s, sp, {0}, 0, 0, lists};
    struct path_walk walk;
    pcg32 rng = pcg32_make(0x5eed0001u + (uint64_t)strlen(name), 17);
    for (int y = 0; y < HEIGHT; y++) {
        for (int x = 0; x < WIDTH; x++) {
            for (int n = 0; n < paths; n++) {
                ctx.trial.u[0] = pcg32_float(&rng);
                ctx.trial.u[1] = pcg32_float(&rng);
                ctx.trial.seed = ((uint64_t)pcg32_next(&rng) << 32) | pcg32_next(&rng);
                ctx.px = x;
                ctx.py = y;
                float px, py;
                path_image_position(x, y, ctx.trial.u, &px, &py);
                vec3 d = camera_view_ray(&cur, px, py);
                struct surface_hit hit;
                if (!scene_intersect(&s, cur.position, d, 0.0f, INFINITY, &hit))
                    continue;
                struct path_vertex x1 = path_vertex_from_hit(&hit, d);
                path_walk_run(&s, &x1, ctx.trial.seed, LIGHT_CHOICE_POWER_AREA, MAX_BOUNCES, RR_BOUNCES, &walk, collect,
                              &ctx);
            }
        }
    }

    /* Backward motion of every pixel centre from the current to the previous view (as the
     * G-buffer's motion vectors give it); motion_ok = 0 where the centre ray misses or the point
     * leaves the previous image. */
    static float motion[WIDTH * HEIGHT][2];
    static int motion_ok[WIDTH * HEIGHT];
    for (int y = 0; y < HEIGHT; y++) {
        for (int x = 0; x < WIDTH; x++) {
            int i = y * WIDTH + x;
            motion_ok[i] = 0;
            vec3 d = camera_view_ray(&cur, (float)x + 0.5f, (float)y + 0.5f);
            struct surface_hit hit;
            float qx, qy;
            if (!scene_intersect(&s, cur.position, d, 0.0f, INFINITY, &hit) ||
                !camera_view_project(&prev, hit.p, &qx, &qy))
                continue;
            if (qx < 0.0f || qy < 0.0f || qx >= (float)WIDTH || qy >= (float)HEIGHT)
                continue;
            motion[i][0] = qx - ((float)x + 0.5f);
            motion[i][1] = qy - ((float)y + 0.5f);
            motion_ok[i] = 1;
        }
    }

    long long rays = 0;
    struct path_walk walk_a, walk_b;
    for (int k = 0; k < NCFG; k++) {
        const struct config *cfg = &configs[k];
        const struct sample_list *L = &lists[k];
        struct id_stats id = {0};
        struct rt_stats rt[NDOM];
        memset(rt, 0, sizeof(rt));
        long deep = 0, mid = 0, distant_ok = 0, distant_far = 0;
        pcg32 nrng = pcg32_make(0xd0d0u + (uint64_t)k, 3);
        for (int i = 0; i < L->n; i++) {
            const struct sample *smp = &L->v[i];
            const struct path_sample *x = &smp->x;
            deep += x->rc >= 3;
            mid += x->rc >= 3 && x->rc < x->length;
            struct pt_domain A = make_domain(&cur, smp->px, smp->py, (float)smp->px, (float)smp->py);

            /* (1) identity: f against the path through the stored vertices (reference_f) for
             * every path, and against the walk's own f where the walk's ray direction and the
             * vertices' agree (dir_err). */
            struct path_sample xid;
            float J;
            id.tried++;
            if (!path_shift(&s, &sp[k], x, &A, &A, &xid, &J, &rays))
                continue;
            id.ok++;
            {
                double dj = fabs((double)J - 1.0), du = u_diff(xid.u, x->u);
                double df = f_diff(xid.f, smp->f_vert), dw = f_diff(xid.f, x->f);
                double dp = rel_diff(xid.prefix_pdf, x->prefix_pdf);
                int exact_dir = smp->dir_err <= DIR_EXACT;
                id.worst_j = fmax(id.worst_j, dj);
                id.worst_u = fmax(id.worst_u, du);
                id.worst_pdf = fmax(id.worst_pdf, dp);
                id.worst_f = fmax(id.worst_f, df);
                if (exact_dir) {
                    id.exact++;
                    id.worst_f_walk = fmax(id.worst_f_walk, dw);
                } else {
                    id.worst_f_offset = fmax(id.worst_f_offset, dw);
                }
                int same = xid.seed == x->seed && xid.length == x->length && xid.rc == x->rc &&
                           v3_same(xid.rc_p, x->rc_p) && v3_same(xid.rc_n, x->rc_n) && v3_same(xid.rc_w, x->rc_w) &&
                           v3_same(xid.rc_L, x->rc_L) && xid.rc_material == x->rc_material;
                if (!same || dj > TOL_ID_J || du > 0.0 || dp > TOL_ID_J || df > TOL_ID_F ||
                    (exact_dir && dw > TOL_ID_F)) {
                    id.bad++;
                    report_bad("identity", name, cfg, smp, dj, df, du);
                }
                /* Shifting the shifted path to its own pixel again changes nothing at all (its u
                 * already lies on the float grid of u + origin). */
                struct path_sample y2;
                float J2;
                int ok2 = path_shift(&s, &sp[k], &xid, &A, &A, &y2, &J2, &rays);
                double dj2 = ok2 ? fabs((double)J2 - 1.0) : 1.0, df2 = ok2 ? f_diff(y2.f, xid.f) : 1.0;
                double du2 = ok2 ? u_diff(y2.u, xid.u) : 1.0;
                id.worst_idem = fmax(id.worst_idem, fmax(dj2, fmax(df2, du2)));
                if (!ok2 || dj2 > TOL_ID_J || df2 > 1e-5 || du2 > 0.0) {
                    id.bad++;
                    report_bad("identity twice", name, cfg, smp, dj2, df2, du2);
                }
            }

            /* (2) round trips A -> B -> A */
            for (int dk = 0; dk < NDOM; dk++) {
                struct pt_domain B;
                int bx, by;
                if (dk == DOM_SPATIAL) {
                    int dx, dy;
                    do {
                        dx = (int)(pcg32_next(&nrng) % 11u) - 5;
                        dy = (int)(pcg32_next(&nrng) % 11u) - 5;
                    } while (dx == 0 && dy == 0);
                    bx = smp->px + dx;
                    by = smp->py + dy;
                    if (bx < 0 || bx >= WIDTH)
                        bx = smp->px - dx;
                    if (by < 0 || by >= HEIGHT)
                        by = smp->py - dy;
                    B = make_domain(&cur, bx, by, (float)bx, (float)by);
                } else if (dk == DOM_MOTION) {
                    /* restir_pt.c: previous pixel q under the backward motion, origin q - motion. */
                    int pi = smp->py * WIDTH + smp->px;
                    if (!motion_ok[pi])
                        continue;
                    float mx = motion[pi][0], my = motion[pi][1];
                    bx = (int)floorf((float)smp->px + 0.5f + mx);
                    by = (int)floorf((float)smp->py + 0.5f + my);
                    B = make_domain(&prev, bx, by, (float)bx - mx, (float)by - my);
                } else if (dk == DOM_FRACTION) {
                    bx = smp->px;
                    by = smp->py;
                    B = make_domain(&prev, bx, by, (float)bx - 0.37f, (float)by + 0.61f);
                } else if (dk == DOM_CLIPPED) {
                    /* temporal.subpixel=search (restir_pt.c): the previous pixel of the 2x2 under the
                     * motion that x's image position falls in, origin q - motion, shifts clipped to
                     * [0,1)^2; the previous pixel beside it must refuse x. */
                    int pi = smp->py * WIDTH + smp->px;
                    if (!motion_ok[pi])
                        continue;
                    float mx = motion[pi][0], my = motion[pi][1];
                    bx = (int)floorf((float)smp->px + x->u[0] + mx);
                    by = (int)floorf((float)smp->py + x->u[1] + my);
                    B = make_domain(&prev, bx, by, (float)bx - mx, (float)by - my);
                    B.clip = 1;
                    struct pt_domain side = make_domain(&prev, bx + 1, by, (float)(bx + 1) - mx, (float)by - my);
                    side.clip = 1;
                    struct path_sample ys;
                    float Js;
                    rt[dk].outside++;
                    if (path_shift(&s, &sp[k], x, &A, &side, &ys, &Js, &rays)) {
                        rt[dk].bad++;
                        report_bad("clipped shift outside its pixel", name, cfg, smp, 0.0, 0.0, 0.0);
                    }
                } else {
                    bx = (smp->px + WIDTH / 2) % WIDTH;
                    by = (smp->py + HEIGHT / 3) % HEIGHT;
                    B = make_domain(&cur, bx, by, (float)bx, (float)by);
                }
                struct rt_stats *r = &rt[dk];
                r->tried++;
                struct path_sample y, z;
                float Jf, Jb;
                if (!path_shift(&s, &sp[k], x, &A, &B, &y, &Jf, &rays))
                    continue;
                r->fwd_ok++;
                if (dk == DOM_DISTANT && k == CFG_RECONNECTION) {
                    distant_ok++;
                    distant_far += fabs((double)Jf - 1.0) > 1e-2;
                }
                /* y's offset is x's translated by the domains' origins (path_shift.h), compared on
                 * the torus since the wrap may round either way at the pixel's edge. */
                for (int c = 0; c < 2; c++) {
                    double e = (double)x->u[c] + (double)A.origin[c] - (double)B.origin[c];
                    double d = fabs((double)y.u[c] - (e - floor(e)));
                    d = fmin(d, 1.0 - d);
                    r->worst_uf = fmax(r->worst_uf, d);
                    if (d > TOL_RT_U) {
                        r->bad++;
                        report_bad("translation of u", name, cfg, smp, 0.0, 0.0, d);
                    }
                }
                /* The shifted path is the walk's prefix from y's offset in B with x's seed,
                 * reconnected to x_k, and |T'| is the ratio of the walks' prefix densities times
                 * the ratio of the solid angles of x_k seen from the two y_{k-1} (path_shift.h);
                 * the hybrid shift must keep its rule in B (no earlier reconnectable segment). */
                if (walk_prefix(&s, &A, x->u, x->seed, x->rc, &walk_a) &&
                    walk_prefix(&s, &B, y.u, x->seed, x->rc, &walk_b)) {
                    const int kk = x->rc;
                    double jg = prefix_density(&walk_a, kk) / prefix_density(&walk_b, kk) *
                                solid_angle_factor(walk_b.v[kk - 2].p, x) / solid_angle_factor(walk_a.v[kk - 2].p, x);
                    double dg = rel_diff(Jf, jg);
                    int rule = 1;
                    if (cfg->kind == SHIFT_HYBRID) {
                        for (int j = 2; j <= kk - 1; j++)
                            rule &= !connectable(&s, &sp[k], B.view->position, walk_b.v[j - 2].p,
                                                 walk_b.v[j - 2].material, walk_b.v[j - 1].p, walk_b.v[j - 1].material);
                        if (kk < x->length)
                            rule &= connectable(&s, &sp[k], B.view->position, walk_b.v[kk - 2].p,
                                                walk_b.v[kk - 2].material, x->rc_p,
                                                x->rc_material);
                    }
                    r->geo++;
                    r->worst_geo = fmax(r->worst_geo, dg);
                    if (dg > TOL_RT_J || !rule) {
                        r->bad++;
                        report_bad(rule ? "Jacobian vs walk" : "hybrid rule in target", name, cfg, smp, dg, 0.0,
                                   0.0);
                    }
                } else {
                    r->bad++;
                    report_bad("no walked prefix", name, cfg, smp, 0.0, 0.0, 0.0);
                }
                if (!path_shift(&s, &sp[k], &y, &B, &A, &z, &Jb, &rays))
                    continue;
                r->back_ok++;
                r->deep += x->rc >= 3;
                r->nontrivial += fabs((double)Jf - 1.0) > 1e-2;
                struct rt_dev dev;
                if (roundtrip_wrong(x, &xid, &z, Jf, Jb, &dev)) {
                    r->bad++;
                    report_bad(dom_names[dk], name, cfg, smp, dev.j, dev.f, dev.u);
                }
                r->worst_j = fmax(r->worst_j, dev.j);
                r->worst_f = fmax(r->worst_f, dev.f);
                r->worst_u = fmax(r->worst_u, dev.u);
                r->worst_pdf = fmax(r->worst_pdf, dev.pdf);
                /* Control: the same checks flag a shift back into the horizontally adjacent pixel
                 * (same sub-pixel offset u, so only f, the densities and |T'| can tell). */
                if (dk == DOM_SPATIAL) {
                    int wx = smp->px + (smp->px + 1 < WIDTH ? 1 : -1);
                    struct pt_domain W = make_domain(&cur, wx, smp->py, (float)wx, (float)smp->py);
                    if (wx != bx || smp->py != by) {
                        struct path_sample zw;
                        float Jw;
                        if (path_shift(&s, &sp[k], &y, &B, &W, &zw, &Jw, &rays)) {
                            r->wrong++;
                            r->wrong_caught += roundtrip_wrong(x, &xid, &zw, Jf, Jw, &dev);
                        }
                    }
                }
            }
        }

        printf("%s %-15s %6d samples, %6ld with k >= 3, %5ld with 3 <= k < D\n", name, cfg->name, L->n, deep, mid);
        printf("  identity   %6ld/%6ld ok (%.4f), %ld bad; worst |J-1| %.2g, u %.2g, prefix pdf %.2g, f %.2g; "
               "f vs walk %.2g on %ld paths with dir_err <= %.0e (%.2g on the others); shifted twice %.2g\n",
               id.ok, id.tried, id.tried ? (double)id.ok / (double)id.tried : 0.0, id.bad, id.worst_j, id.worst_u,
               id.worst_pdf, id.worst_f, id.worst_f_walk, id.exact, DIR_EXACT, id.worst_f_offset, id.worst_idem);
        EXPECT(L->n >= 2000, "%s %s: only %d samples", name, cfg->name, L->n);
        EXPECT(id.tried > 0 && (double)id.ok >= MIN_ID_RATE * (double)id.tried, "%s %s: identity succeeded %ld/%ld",
               name, cfg->name, id.ok, id.tried);
        EXPECT(id.bad == 0, "%s %s: %ld identity shifts changed the path (worst |J-1| %.3g, f %.3g)", name,
               cfg->name, id.bad, id.worst_j, id.worst_f);
        for (int dk = 0; dk < NDOM; dk++) {
            const struct rt_stats *r = &rt[dk];
            double back_rate = r->fwd_ok ? (double)r->back_ok / (double)r->fwd_ok : 1.0;
            printf("  %-9s  %5ld tried, %5ld forward, %5ld back (%.4f), %5ld with k >= 3, %5ld |Jf-1| > 1e-2, "
                   "%ld bad; worst |JfJb-1| %.2g, f %.2g, u %.2g, prefix pdf %.2g; forward u %.2g, "
                   "|Jf| vs walks %.2g (%ld)\n",
                   dom_names[dk], r->tried, r->fwd_ok, r->back_ok, back_rate, r->deep, r->nontrivial, r->bad,
                   r->worst_j, r->worst_f, r->worst_u, r->worst_pdf, r->worst_uf, r->worst_geo, r->geo);
            EXPECT(back_rate >= MIN_BACK_RATE, "%s %s %s: the inverse shift succeeded for %ld of %ld", name,
                   cfg->name, dom_names[dk], r->back_ok, r->fwd_ok);
            EXPECT(r->bad == 0,
                   "%s %s %s: %ld round trips did not recover the path (worst |JfJb-1| %.3g, f %.3g, u %.3g, "
                   "|Jf| vs walks %.3g)",
                   name, cfg->name, dom_names[dk], r->bad, r->worst_j, r->worst_f, r->worst_u, r->worst_geo);
        }
        /* Clipped shifts happen, and none reached the previous pixel beside the right one. */
        EXPECT(rt[DOM_CLIPPED].fwd_ok >= 200 && rt[DOM_CLIPPED].outside >= rt[DOM_CLIPPED].fwd_ok,
               "%s %s: only %ld clipped shifts (%ld beside)", name, cfg->name, rt[DOM_CLIPPED].fwd_ok,
               rt[DOM_CLIPPED].outside);
        /* Control: the round-trip checks flag inverse shifts into the wrong pixel. */
        const struct rt_stats *sr = &rt[DOM_SPATIAL];
        printf("  control: %ld of %ld shifts back into the wrong pixel flagged\n", sr->wrong_caught, sr->wrong);
        EXPECT(sr->wrong >= 200 && (double)sr->wrong_caught >= 0.9 * (double)sr->wrong,
               "%s %s: only %ld of %ld shifts back into the wrong pixel flagged", name, cfg->name, sr->wrong_caught,
               sr->wrong);
        /* Not vacuous: round trips happen, with Jacobians far from 1 and, for replay and hybrid,
         * through replayed prefixes. */
        long back_all = 0, nontrivial_all = 0, deep_all = 0;
        for (int dk = 0; dk < NDOM; dk++) {
            back_all += rt[dk].back_ok;
            nontrivial_all += rt[dk].nontrivial;
            deep_all += rt[dk].deep;
        }
        EXPECT(back_all >= 1000, "%s %s: only %ld round trips", name, cfg->name, back_all);
        EXPECT(nontrivial_all >= 200, "%s %s: only %ld round trips with |J_forward - 1| > 1e-2", name, cfg->name,
               nontrivial_all);
        if (k != CFG_RECONNECTION) {
            EXPECT(deep >= 500, "%s %s: only %ld samples with k >= 3", name, cfg->name, deep);
            EXPECT(deep_all >= 300, "%s %s: only %ld round trips with k >= 3", name, cfg->name, deep_all);
        } else {
            EXPECT(deep == 0, "%s reconnection: %ld samples with k != 2", name, deep);
            /* Negative control: reconnecting from a distant pixel changes the solid angle of x_2. */
            printf("  negative control: %ld of %ld distant reconnections have |J-1| > 1e-2\n", distant_far,
                   distant_ok);
            EXPECT(distant_ok >= 200 && (double)distant_far >= 0.5 * (double)distant_ok,
                   "%s: distant reconnection Jacobians far from 1: %ld of %ld", name, distant_far, distant_ok);
        }
        if (k == CFG_REPLAY || k == CFG_HYBRID_NOROUGH)
            EXPECT(mid == 0, "%s %s: %ld samples reconnect before the light", name, cfg->name, mid);
        /* The hybrid shift replays through smooth or short segments and then reconnects. */
        if (k == CFG_HYBRID || k == CFG_HYBRID_RELATIVE)
            EXPECT(mid >= 200, "%s %s: only %ld samples with 3 <= k < D", name, cfg->name, mid);
    }
    printf("%s: %lld rays traced by shifts\n", name, rays);
    for (int k = 0; k < NCFG; k++)
        free(lists[k].v);
    scene_destroy(&s);
}

int main(void)
{
    test_scene("cornell", 2);
    test_scene("ajar", 12);
    return test_finish();
}
