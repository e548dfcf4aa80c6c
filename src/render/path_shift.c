/* path_shift.c: reconnection, random replay and hybrid shift mappings between pixel domains, with
 * their Jacobian determinants (see path_shift.h; 000 Eq. 1 and 6, Lin et al. 2022 Sec. 7).
 * Every BSDF is evaluated with the vertex's shading normal for its own outgoing direction
 * (bsdf_shading_normal), x_k's too, rebuilt from its triangle and barycentrics because its
 * outgoing direction changes with the shift; geometric normals give the side tests and the
 * Jacobians' area measure. Must never depend on reservoirs. */
#include "render/path_shift.h"

#include "shading/bsdf.h"

static int material_rough_eval(const struct scene *s, const struct shift_params *sp, int material)
{
    struct bsdf b;
    bsdf_from_material(&s->materials[material], &b);
    return bsdf_roughness(&b) >= sp->min_roughness;
}

void path_shift_rough_table(const struct scene *s, const struct shift_params *sp, unsigned char *rough)
{
    for (int m = 0; m < s->num_materials; m++)
        rough[m] = (unsigned char)material_rough_eval(s, sp, m);
}

static int material_rough(const struct scene *s, const struct shift_params *sp, int material)
{
    return sp->rough ? sp->rough[material] : material_rough_eval(s, sp, material);
}

/* The shortest reconnection segment from pa the hybrid rule allows, seen from a domain whose camera
 * is at `camera`. Each domain applies its own rule: the shift into a domain checks the shifted path
 * against that domain's (shift_from_primary), which keeps the shift invertible. */
static float min_segment(const struct shift_params *sp, vec3 camera, vec3 pa)
{
    if (sp->distance_mode == SHIFT_DISTANCE_RELATIVE)
        return sp->distance_factor * v3_length(v3_sub(pa, camera));
    return sp->min_distance;
}

/* Hybrid rule: may the path reconnect at b, coming from a? light_b marks b as a light vertex,
 * which has no BSDF and always counts as rough. */
static int connectable(const struct scene *s, const struct shift_params *sp, vec3 camera, vec3 pa, int mat_a, vec3 pb,
                       int mat_b, int light_b)
{
    if (!material_rough(s, sp, mat_a) || (!light_b && !material_rough(s, sp, mat_b)))
        return 0;
    const float m = min_segment(sp, camera, pa);
    return v3_length2(v3_sub(pb, pa)) > m * m;
}

/* Reconnection vertex index k of a walked path of length D (vertices x_j = w->v[j-1]). */
static int choose_rc(const struct scene *s, const struct shift_params *sp, const struct path_walk *w, int D)
{
    if (sp->kind == SHIFT_RECONNECTION)
        return 2;
    if (sp->kind == SHIFT_HYBRID)
        for (int j = 2; j <= D - 1; j++)
            if (connectable(s, sp, sp->camera, w->v[j - 2].p, w->v[j - 2].material, w->v[j - 1].p,
                            w->v[j - 1].material, 0))
                return j;
    return D;
}

/* The factors of f from y_{k-1} = v (BSDF b) onward when it is connected to x's reconnection
 * vertex x_k: f_s(v) |n_v . w| * [f_s(x_k) |n_k . w_k|] * L, with w the unit direction v -> x_k
 * (no visibility). Writes |cos| at x_k and the squared distance; returns 0 where the connection
 * leaves either surface on the wrong side. The initial sample and every shift evaluate their
 * target through this one function, so an identity shift reproduces the cached target exactly. */
static vec3 reconnection_eval(const struct scene *s, const struct path_vertex *v, const struct bsdf *b,
                              const struct path_sample *x, float *cos_k, float *d2)
{
    *cos_k = 0.0f;
    *d2 = 0.0f;
    vec3 wk;
    float dist2 = 1.0f, ck = 1.0f; /* a direction of the environment: no distance, no cosine */
    if (x->rc_env) {
        wk = x->rc_w;
    } else {
        vec3 to_k = v3_sub(x->rc_p, v->p);
        dist2 = v3_length2(to_k);
        if (!(dist2 > 0.0f))
            return v3s(0.0f);
        wk = v3_scale(to_k, 1.0f / sqrtf(dist2));
        ck = -v3_dot(x->rc_n, wk);
    }
    const vec3 n_v = bsdf_shading_normal(v->ns, v->ng, v->wo);
    float cos_y = v3_dot(n_v, wk);
    if (cos_y <= 0.0f || v3_dot(v->ng, wk) <= 0.0f || ck <= 0.0f)
        return v3s(0.0f);
    vec3 at_k = x->rc_L;
    if (x->rc < x->length) {
        struct bsdf bk;
        struct material tmp;
        bsdf_from_material(scene_material_at(s, x->rc_tri, x->rc_b1, x->rc_b2, &tmp), &bk);
        const vec3 wo_k = v3_neg(wk);
        const vec3 n_k = bsdf_shading_normal(scene_shading_normal(s, x->rc_tri, x->rc_b1, x->rc_b2, x->rc_n),
                                             x->rc_n, wo_k);
        vec3 fk = bsdf_eval(&bk, n_k, wo_k, x->rc_w);
        at_k = v3_mul(at_k, v3_scale(fk, fabsf(v3_dot(n_k, x->rc_w))));
    }
    *cos_k = ck;
    *d2 = dist2;
    return v3_mul(v3_scale(bsdf_eval(b, n_v, v->wo, wk), cos_y), at_k);
}

static void keep_primary(struct path_sample *y, const struct path_vertex *x1)
{
    y->x1_p = x1->p;
    y->x1_tri = x1->tri;
    y->x1_b1 = x1->b1;
    y->x1_b2 = x1->b2;
}

void path_sample_from_candidate(const struct scene *s, const struct shift_params *sp, const struct path_walk *w,
                                const struct path_candidate *c, struct path_sample *out)
{
    const int D = c->length, k = choose_rc(s, sp, w, D);
    out->length = D;
    out->rc = k;
    out->rc_env = k == D && c->at_env;
    keep_primary(out, &w->v[0]);
    if (k == D) {
        out->rc_p = c->light_p;
        out->rc_n = c->light_n;
        out->rc_L = c->Le;
        out->rc_w = out->rc_env ? c->w_last : v3s(0.0f);
        out->rc_material = -1;
        out->rc_tri = -1;
        out->rc_b1 = out->rc_b2 = 0.0f;
    } else {
        const struct path_vertex *xk = &w->v[k - 1];
        out->rc_p = xk->p;
        out->rc_n = xk->ng;
        out->rc_material = xk->material;
        out->rc_tri = xk->tri;
        out->rc_b1 = xk->b1;
        out->rc_b2 = xk->b2;
        out->rc_w = k == D - 1 ? c->w_last : xk->w_next;
        /* Radiance arriving at x_k: the suffix throughput after x_k times the emission. */
        vec3 L = c->Le;
        for (int j = D - 1; j > k; j--)
            L = v3_mul(L, j == D - 1 ? c->fcos_last : w->v[j - 1].fcos);
        out->rc_L = L;
    }
    /* The walk's f follows its rays, which leave offset origins; shifts evaluate the straight
     * segment x_{k-1} -> x_k. Cache f as the shifts define it (same prefix, reconnection_eval). */
    float pdf = 1.0f;
    vec3 F = v3s(1.0f);
    for (int j = 1; j <= k - 2; j++) {
        pdf *= w->v[j - 1].pdf_dir;
        F = v3_mul(F, w->v[j - 1].fcos);
    }
    out->prefix_pdf = pdf;
    const struct path_vertex *xk1 = &w->v[k - 2];
    struct bsdf b;
    path_vertex_bsdf(s, xk1, &b);
    out->f = v3_mul(F, reconnection_eval(s, xk1, &b, out, &out->rc_cos, &out->rc_dist2));
    if (!(out->rc_dist2 > 0.0f)) { /* the connection failed: keep finite Jacobian terms */
        out->rc_dist2 = 1.0f;
        out->rc_cos = 1.0f;
    }
}

/* u (in [0,1)) translated by delta on the unit torus. Only the fractional part of delta is added,
 * so identity and whole-pixel shifts leave u bit-identical. */
static float translate_offset(float u, float delta)
{
    float t = u + (delta - floorf(delta));
    if (t >= 1.0f)
        t -= 1.0f; /* exact: t in [1, 2) */
    return t < 1.0f ? t : 0x1.fffffep-1f;
}

static int fail(struct path_sample *y)
{
    y->length = 0;
    return 0;
}

/* Is x's reconnection vertex seen from v? A direction of the environment is when the ray along it
 * escapes the scene. */
static int reconnection_visible(const struct scene *s, const struct path_vertex *v, const struct path_sample *x)
{
    if (x->rc_env)
        return !scene_occluded(s, scene_offset_point(v->p, v->ng, x->rc_w), x->rc_w, 0.0f, INFINITY);
    return scene_visible(s, v->p, v->ng, x->rc_p, x->rc_n);
}

/* The shift of x from its shifted primary vertex v = y_1 on: random replay of the directions
 * sampled at y_1 .. y_{k-2}, through the same sampling routine as the walk (bsdf_frame_sample),
 * so that an identity shift reproduces its densities bit for bit, then the reconnection of
 * y_{k-1} to x_k. Writes the Jacobian of everything after the primary vertex to *jacobian. */
static int shift_from_primary(const struct scene *s, const struct shift_params *sp, vec3 camera,
                              const struct path_sample *x, struct path_vertex v, struct path_sample *y, float *jacobian,
                              long long *rays)
{
    const int D = x->length, k = x->rc;
    const int hybrid = sp->kind == SHIFT_HYBRID;
    struct surface_hit h;
    struct bsdf b;
    path_vertex_bsdf(s, &v, &b);
    vec3 F = v3s(1.0f);
    float prefix_pdf = 1.0f;
    for (int j = 1; j <= k - 2; j++) {
        pcg32 rng = path_rng(x->seed, j);
        float u0 = pcg32_float(&rng), u1 = pcg32_float(&rng), u2 = pcg32_float(&rng);
        vec3 wi, f;
        float pdf;
        struct bsdf_frame bf;
        const vec3 n = bsdf_shading_normal(v.ns, v.ng, v.wo);
        bsdf_frame_init(&bf, &b, n, v.wo);
        if (!bsdf_frame_sample(&bf, u0, u1, u2, &wi, &pdf, &f) || v3_dot(wi, v.ng) <= 0.0f)
            return fail(y);
        F = v3_mul(F, v3_scale(f, v3_dot(n, wi)));
        prefix_pdf *= pdf;
        (*rays)++;
        if (!scene_intersect(s, scene_offset_point(v.p, v.ng, wi), wi, 0.0f, INFINITY, &h))
            return fail(y);
        struct path_vertex next = path_vertex_from_hit(&h, wi);
        /* The shifted path must pick the same reconnection vertex, or T would not be invertible. */
        if (hybrid && connectable(s, sp, camera, v.p, v.material, next.p, next.material, 0))
            return fail(y);
        v = next;
        path_vertex_bsdf(s, &v, &b);
    }
    /* Reconnect y_{k-1} = v to x_k. */
    if (hybrid && k < D && !connectable(s, sp, camera, v.p, v.material, x->rc_p, x->rc_material, 0))
        return fail(y);
    float cos_k, d2;
    vec3 f = v3_mul(F, reconnection_eval(s, &v, &b, x, &cos_k, &d2));
    if (!(v3_max_component(f) > 0.0f) || !v3_is_finite(f))
        return fail(y);
    (*rays)++;
    if (!reconnection_visible(s, &v, x))
        return fail(y);
    y->rc_cos = cos_k;
    y->rc_dist2 = d2;
    y->prefix_pdf = prefix_pdf;
    y->f = f;
    /* |T'| = replayed density ratio * solid-angle change of the reconnection (path_shift.h). */
    float J = (x->prefix_pdf / prefix_pdf) * (cos_k / d2) * (x->rc_dist2 / x->rc_cos);
    if (!(J > 0.0f) || !isfinite(J))
        return fail(y);
    *jacobian = J;
    return 1;
}

int path_shift(const struct scene *s, const struct shift_params *sp, const struct path_sample *x,
               const struct pt_domain *from, const struct pt_domain *to, struct path_sample *y, float *jacobian,
               long long *rays)
{
    *y = *x;
    *jacobian = 0.0f;
    if (x->length < 2)
        return fail(y);
    if (from->clip || to->clip) {
        for (int a = 0; a < 2; a++) {
            y->u[a] = x->u[a] + (from->origin[a] - to->origin[a]);
            if (!(y->u[a] >= 0.0f && y->u[a] < 1.0f))
                return fail(y); /* the path lands outside pixel `to` */
        }
    } else {
        y->u[0] = translate_offset(x->u[0], from->origin[0] - to->origin[0]);
        y->u[1] = translate_offset(x->u[1], from->origin[1] - to->origin[1]);
    }
    float px, py;
    path_image_position(to->x, to->y, y->u, &px, &py);
    struct camera_pose pose;
    camera_view_pose(to->view, y->time, &pose);
    vec3 o, dir;
    camera_pose_ray(to->view, &pose, px, py, y->lens, &o, &dir);
    struct surface_hit h;
    (*rays)++;
    if (!scene_intersect(s, o, dir, 0.0f, INFINITY, &h))
        return fail(y);
    struct path_vertex v = path_vertex_from_hit(&h, dir);
    keep_primary(y, &v);
    return shift_from_primary(s, sp, to->view->position, x, v, y, jacobian, rays);
}

/* x's primary hit projected from its lens point through view at `time`: the pose, the image
 * position and the lens point; 0 when behind the lens or outside the image. */
static int splat_project(const struct path_sample *x, const struct camera_view *view, float time,
                         struct camera_pose *pose, float *px, float *py, vec3 *origin)
{
    camera_view_pose(view, time, pose);
    if (!camera_pose_project(view, pose, x->x1_p, x->lens, px, py, origin))
        return 0;
    return *px >= 0.0f && *py >= 0.0f && *px < (float)view->width && *py < (float)view->height;
}

int path_splat_position(const struct path_sample *x, const struct camera_view *view, float time, float *px,
                        float *py)
{
    struct camera_pose pose;
    vec3 o;
    return splat_project(x, view, time, &pose, px, py, &o);
}

/* The fractional part of an image coordinate known to lie in [0, size): the sub-pixel offset. */
static float sub_pixel(float p, int *cell)
{
    *cell = (int)p;
    float u = p - (float)*cell;
    return u < 1.0f ? u : 0x1.fffffep-1f;
}

int path_shift_splat(const struct scene *s, const struct shift_params *sp, const struct path_sample *x,
                     const struct camera_view *from_view, const struct camera_view *to_view, float time,
                     float time_scale, int *pixel, struct path_sample *y, float *jacobian, long long *rays)
{
    *y = *x;
    *jacobian = 0.0f;
    *pixel = -1;
    if (x->length < 2)
        return fail(y);
    struct camera_pose to_pose, from_pose;
    camera_view_pose(from_view, x->time, &from_pose);
    vec3 o, o_from;
    float px, py, qx, qy;
    if (!splat_project(x, to_view, time, &to_pose, &px, &py, &o) ||
        !camera_pose_project(from_view, &from_pose, x->x1_p, x->lens, &qx, &qy, &o_from))
        return fail(y);
    int ix, iy;
    y->u[0] = sub_pixel(px, &ix);
    y->u[1] = sub_pixel(py, &iy);
    y->time = time;
    vec3 dir = v3_normalize(v3_sub(x->x1_p, o));
    struct surface_hit h;
    scene_surface_at(s, x->x1_tri, x->x1_b1, x->x1_b2, x->x1_p, dir, &h);
    /* x_1 is kept: the shifted primary ray is o -> x_1, and it must reach x_1 unoccluded. */
    (*rays)++;
    if (!scene_visible(s, o, dir, x->x1_p, h.ng))
        return fail(y);
    /* The image-position part of |T'|: x_1 fixed, so d(image_to)/d(image_from) is the ratio of
     * surface area per pixel seen from the old and the new lens point (camera.h). */
    float a_from = camera_pose_area_per_pixel(from_view, &from_pose, o_from, x->x1_p, h.ng);
    float a_to = camera_pose_area_per_pixel(to_view, &to_pose, o, x->x1_p, h.ng);
    float J_rest;
    if (!(a_from > 0.0f && a_to > 0.0f) ||
        !shift_from_primary(s, sp, to_view->position, x, path_vertex_from_hit(&h, dir), y, &J_rest, rays))
        return fail(y);
    float J = a_from / a_to * J_rest * time_scale;
    if (!(J > 0.0f) || !isfinite(J))
        return fail(y);
    *jacobian = J;
    *pixel = iy * to_view->width + ix;
    return 1;
}
