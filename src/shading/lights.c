/* lights.c: emitter selection through the scene's alias table or emitter BVH, points on emissive
 * triangles uniform in area or solid angle, one-sided emission, area-to-solid-angle conversion.
 * Must never depend on the ray tracer or render. */
#include "shading/lights.h"

#include <math.h>

#include "shading/light_tree.h"
#include "shading/spherical_rect.h"
#include "shading/spherical_triangle.h"

static vec3 tri_vertex(const struct scene *s, int tri, int k) { return s->verts[s->indices[3 * tri + k]]; }

/* Emission at a point: the material's factor, times its emission texture there; none where an
 * alpha mask cuts the point away (scene_material_at). */
static vec3 point_emission(const struct scene *s, int tri, float b1, float b2)
{
    const struct material *m = &s->materials[s->tri_material[tri]];
    if (!m->emission_map && !m->alpha_mask) /* other maps do not change emission */
        return m->emission;
    struct material tmp;
    return scene_material_at(s, tri, b1, b2, &tmp)->emission;
}

/* Area density of a point = P(choose triangle) * 1 / area (uniform on the triangle). */
float lights_pdf_area(const struct scene *s, int tri)
{
    if (tri < 0 || tri >= s->num_tris)
        return 0.0f;
    int e = s->tri_emitter[tri];
    if (e < 0 || e >= s->num_emitters)
        return 0.0f;
    float area = s->tri_area[tri];
    if (!(area > 0.0f))
        return 0.0f;
    return s->emitter_table.pmf[e] / area;
}

void lights_emitter_point(const struct scene *s, const struct emitter *em, float b1, float b2,
                          struct light_sample *ls)
{
    ls->tri = em->tri;
    ls->b1 = b1;
    ls->b2 = b2;
    ls->p = v3_add(em->v0, v3_add(v3_scale(em->e1, b1), v3_scale(em->e2, b2)));
    ls->n = em->n;
    ls->Le = em->textured ? point_emission(s, em->tri, b1, b2) : em->Le;
    ls->pdf_area = em->pdf_area;
}

void lights_point(const struct scene *s, int tri, float b1, float b2, struct light_sample *ls)
{
    int e = (tri >= 0 && tri < s->num_tris) ? s->tri_emitter[tri] : -1;
    if (e < 0) {
        /* Not an emitter: a point with zero radiance and zero density. */
        vec3 a = tri_vertex(s, tri, 0), b = tri_vertex(s, tri, 1), c = tri_vertex(s, tri, 2);
        ls->tri = tri;
        ls->b1 = b1;
        ls->b2 = b2;
        ls->p = v3_add(a, v3_add(v3_scale(v3_sub(b, a), b1), v3_scale(v3_sub(c, a), b2)));
        ls->n = s->tri_normal[tri];
        ls->Le = point_emission(s, tri, b1, b2);
        ls->pdf_area = 0.0f;
        return;
    }
    lights_emitter_point(s, &s->emitters[e], b1, b2, ls);
}

/* A point uniform on emitter em's area from u1, u2. Returns 1 when its density is positive. */
static int sample_area(const struct scene *s, const struct emitter *em, float u1, float u2, struct light_sample *ls)
{
    float b1, b2;
    warp_uniform_triangle(u1, u2, &b1, &b2);
    lights_emitter_point(s, em, b1, b2, ls);
    return ls->pdf_area > 0.0f;
}

int lights_sample(const struct scene *s, float u_select, float u1, float u2, struct light_sample *ls)
{
    if (s->num_emitters < 1)
        return 0;
    return sample_area(s, &s->emitters[alias_table_sample(&s->emitter_table, u_select)], u1, u2, ls);
}

/* lights.sample=auto's test (lights.h): whether the area density's factor cos / d^2 = h / d^3 (h the
 * distance from the emitter's plane) spreads over the emitter seen from x by at least
 * LIGHTS_AUTO_SPREAD^(3/2), i.e. d_max^2 >= LIGHTS_AUTO_SPREAD d_min^2 for its farthest and closest
 * points. First, without a square root, the bound of a sphere of radius r around the emitter's centre
 * c, d_max / d_min <= (|c - x| + r) / (|c - x| - r), below the limit beyond |c - x| = AUTO_FAR r:
 * most of a scene's emitters are that far from most points. */
#define AUTO_FAR ((sqrtf(LIGHTS_AUTO_SPREAD) + 1.0f) / (sqrtf(LIGHTS_AUTO_SPREAD) - 1.0f))

/* The test for triangle em: d_max from the vertices, d_min bounded below by
 * max(h, |centroid - x| - em->radius), so that it errs toward solid angle. */
static int triangle_spread(const struct emitter *em, vec3 x)
{
    const vec3 a = v3_sub(em->v0, x), to_c = v3_add(a, v3_scale(v3_add(em->e1, em->e2), 1.0f / 3.0f));
    const float dc2 = v3_length2(to_c), far = AUTO_FAR * em->radius;
    if (dc2 > far * far)
        return 0;
    const vec3 b = v3_add(a, em->e1), c = v3_add(a, em->e2);
    const float d_max2 = fmaxf(v3_length2(a), fmaxf(v3_length2(b), v3_length2(c)));
    const float d_min = fmaxf(fabsf(v3_dot(a, em->n)), sqrtf(dc2) - em->radius);
    return d_max2 >= LIGHTS_AUTO_SPREAD * d_min * d_min;
}

/* The test for rectangle q, exactly: its closest and farthest points in its own frame. */
static int quad_spread(const struct emitter_quad *q, vec3 x)
{
    const float far = AUTO_FAR * q->radius;
    if (v3_length2(v3_sub(q->centre, x)) > far * far)
        return 0;
    const vec3 d = v3_sub(q->corner, x);
    const float x0 = v3_dot(d, q->ux), y0 = v3_dot(d, q->uy), h = v3_dot(d, q->uz);
    const float x1 = x0 + q->lx, y1 = y0 + q->ly;
    const float cx = x0 > 0.0f ? x0 : (x1 < 0.0f ? x1 : 0.0f), cy = y0 > 0.0f ? y0 : (y1 < 0.0f ? y1 : 0.0f);
    const float d_max2 = fmaxf(x0 * x0, x1 * x1) + fmaxf(y0 * y0, y1 * y1) + h * h;
    return d_max2 >= LIGHTS_AUTO_SPREAD * (cx * cx + cy * cy + h * h);
}

/* The solid angle emitter em subtends from x when solid-angle sampling applies there (t set up for
 * the sampler), else 0. solid-angle: a triangle whose area over the squared distance of its
 * centroid is below LIGHTS_SOLID_ANGLE_MIN is not even measured: that test costs a few multiplies
 * (squared, without a square root) where the solid angle costs an atan2 and three square roots, and
 * in tessellated scenes most chosen triangles fail it. auto: the spread test instead. Either way the
 * solid angle must then be at least LIGHTS_SOLID_ANGLE_MIN. */
static float emitter_solid_angle(const struct emitter *em, vec3 x, enum light_sampling mode,
                                 struct spherical_triangle *t)
{
    if (mode == LIGHT_SAMPLING_AUTO) {
        if (!triangle_spread(em, x))
            return 0.0f;
    } else {
        const vec3 centroid = v3_add(em->v0, v3_scale(v3_add(em->e1, em->e2), 1.0f / 3.0f));
        const float twice_area2 = v3_length2(v3_cross(em->e1, em->e2)), d2 = v3_length2(v3_sub(centroid, x));
        const float limit = 2.0f * (float)LIGHTS_SOLID_ANGLE_MIN * d2;
        if (twice_area2 < limit * limit)
            return 0.0f;
    }
    const float omega = spherical_triangle_init(t, x, em->v0, em->e1, em->e2);
    return omega >= (float)LIGHTS_SOLID_ANGLE_MIN ? omega : 0.0f;
}

/* The rectangle q as seen from x in *r when it is sampled as a whole there, by the same rules as a
 * triangle's (emitter_solid_angle; auto reads the rectangle's exact closest and farthest points).
 * Returns 0 (area sampling of each half) otherwise; the same rule for both halves, so that a point
 * of either has one density whichever half was chosen. */
static int quad_applies(const struct emitter_quad *q, vec3 x, enum light_sampling mode, struct spherical_rect *r)
{
    if (mode == LIGHT_SAMPLING_AUTO ? !quad_spread(q, x)
                                    : q->area < (float)LIGHTS_SOLID_ANGLE_MIN * v3_length2(v3_sub(q->centre, x)))
        return 0;
    return spherical_rect_init(r, x, q->corner, q->ux, q->uy, q->lx, q->ly) >= (float)LIGHTS_SOLID_ANGLE_MIN;
}

/* The emitter for shading point x, normal n, by `select`, with its probability, and by the BVH also
 * light_tree_sample_pair's pmf_pair (quad_pmf). -1 when none. */
static int select_emitter(const struct scene *s, enum light_selection select, vec3 x, vec3 n, float u, float *pmf,
                          float *pmf_pair)
{
    if (select == LIGHT_SELECT_BVH)
        return light_tree_sample_pair(&s->light_bvh, x, n, u, pmf, pmf_pair);
    const int e = alias_table_sample(&s->emitter_table, u);
    *pmf = s->emitter_table.pmf[e];
    return e;
}

static float emitter_pmf(const struct scene *s, enum light_selection select, vec3 x, vec3 n, int e)
{
    return select == LIGHT_SELECT_BVH ? light_tree_pmf(&s->light_bvh, x, n, e) : s->emitter_table.pmf[e];
}

/* The probability of choosing either half of q, given the one chosen (e) with its pmf and, when e
 * was just drawn down the BVH, its pmf_pair (either negative: not known yet): by power the sum of both
 * table entries; down the BVH, when the halves are sibling leaves (as the builder pairs them), the
 * probability of their parent times its children's probabilities' sum in one product
 * (light_tree_pmf_pair), else pmf(e[0]) + pmf(e[1]) in that order whichever was chosen. Either way
 * sampler and density agree bit for bit (light_tree.h repeats the sampler's arithmetic). */
static float quad_pmf(const struct scene *s, enum light_selection select, vec3 x, vec3 n, const struct emitter_quad *q,
                      int e, float pmf, float pmf_pair)
{
    if (select != LIGHT_SELECT_BVH)
        return s->emitter_table.pmf[q->e[0]] + s->emitter_table.pmf[q->e[1]];
    const struct light_bvh *t = &s->light_bvh;
    if (t->nodes[t->emitter_leaf[q->e[0]]].parent == t->nodes[t->emitter_leaf[q->e[1]]].parent)
        return pmf_pair >= 0.0f ? pmf_pair : light_tree_pmf_pair(t, x, n, e);
    const float p0 = q->e[0] == e && pmf >= 0.0f ? pmf : light_tree_pmf(t, x, n, q->e[0]);
    const float p1 = q->e[1] == e && pmf >= 0.0f ? pmf : light_tree_pmf(t, x, n, q->e[1]);
    return p0 + p1;
}

/* ls->pdf_area for a point drawn uniformly in a solid angle omega with probability pmf:
 * pdf_area d^2 / cos_l = pmf / omega, the density the direction was drawn with. */
static int solid_angle_density(vec3 x, float pmf, float omega, struct light_sample *ls)
{
    const vec3 d = v3_sub(ls->p, x);
    const float dist2 = v3_length2(d); /* cos_l / dist^2 = |n . d| / dist^3 */
    ls->pdf_area = dist2 > 0.0f ? pmf * fabsf(v3_dot(ls->n, d)) / (omega * dist2 * sqrtf(dist2)) : 0.0f;
    return ls->pdf_area > 0.0f;
}

/* A point of rectangle q uniform in its solid angle from x (r, spherical_rect.h): the half it falls
 * in, its barycentrics there (clamped into the triangle against rounding), density (pmf(e[0]) +
 * pmf(e[1])) / omega: both halves' choices lead to this one map. */
static int sample_quad(const struct scene *s, const struct emitter_quad *q, const struct spherical_rect *r, vec3 x,
                       float pmf_quad, float u1, float u2, struct light_sample *ls)
{
    float sx, ty;
    spherical_rect_sample(r, u1, u2, &sx, &ty);
    const float a = sx * q->inv_lx, b = ty * q->inv_ly;
    const int k = a + b <= 1.0f ? 0 : 1;
    const float *m = q->bary[k];
    float b1 = m[0] * a + m[1] * b + m[2], b2 = m[3] * a + m[4] * b + m[5];
    b1 = b1 < 0.0f ? 0.0f : b1;
    b2 = b2 < 0.0f ? 0.0f : b2;
    if (b1 + b2 > 1.0f) {
        const float sum = b1 + b2;
        b1 /= sum, b2 /= sum;
    }
    lights_emitter_point(s, &s->emitters[q->e[k]], b1, b2, ls);
    return solid_angle_density(x, pmf_quad, r->omega, ls);
}

int lights_sample_at(const struct scene *s, struct light_choice choice, vec3 x, vec3 n, float u_select, float u1,
                     float u2, struct light_sample *ls)
{
    if (s->num_emitters < 1)
        return 0;
    float pmf, pmf_pair = -1.0f;
    const int e = select_emitter(s, choice.select, x, n, u_select, &pmf, &pmf_pair);
    if (e < 0)
        return 0;
    const struct emitter *em = &s->emitters[e];
    float omega = 0.0f;
    struct spherical_triangle t;
    if (choice.point != LIGHT_SAMPLING_AREA) {
        if (em->quad >= 0) {
            const struct emitter_quad *q = &s->emitter_quads[em->quad];
            struct spherical_rect r;
            if (quad_applies(q, x, choice.point, &r))
                return sample_quad(s, q, &r, x, quad_pmf(s, choice.select, x, n, q, e, pmf, pmf_pair), u1, u2, ls);
        } else {
            omega = emitter_solid_angle(em, x, choice.point, &t);
        }
    }
    vec3 dir;
    if (!(omega > 0.0f) || !spherical_triangle_sample(&t, u1, u2, &dir)) {
        if (!sample_area(s, em, u1, u2, ls))
            return 0;
        ls->pdf_area = pmf / s->tri_area[em->tri]; /* em->pdf_area's formula with this selection's pmf */
        return ls->pdf_area > 0.0f;
    }
    /* The point where dir meets the triangle's plane, as barycentrics (clamped into the triangle
     * against rounding). */
    const vec3 nt = v3_cross(em->e1, em->e2), to = v3_sub(em->v0, x);
    const float denom = v3_dot(dir, nt);
    if (denom == 0.0f)
        return 0;
    const vec3 q = v3_sub(v3_add(x, v3_scale(dir, v3_dot(to, nt) / denom)), em->v0);
    const float d00 = v3_dot(em->e1, em->e1), d01 = v3_dot(em->e1, em->e2), d11 = v3_dot(em->e2, em->e2);
    const float d20 = v3_dot(q, em->e1), d21 = v3_dot(q, em->e2), det = d00 * d11 - d01 * d01;
    float b1 = (d11 * d20 - d01 * d21) / det, b2 = (d00 * d21 - d01 * d20) / det;
    b1 = b1 < 0.0f ? 0.0f : b1;
    b2 = b2 < 0.0f ? 0.0f : b2;
    if (b1 + b2 > 1.0f) {
        const float sum = b1 + b2;
        b1 /= sum, b2 /= sum;
    }
    lights_emitter_point(s, em, b1, b2, ls);
    return solid_angle_density(x, pmf, omega, ls);
}

float lights_pdf_at(const struct scene *s, struct light_choice choice, vec3 x, vec3 n, int tri, float dist,
                    float cos_l)
{
    const int e = tri >= 0 && tri < s->num_tris ? s->tri_emitter[tri] : -1;
    if (e < 0)
        return 0.0f; /* not an emitter (tri_emitter holds only triangles of positive area) */
    const struct emitter *em = &s->emitters[e];
    if (choice.point != LIGHT_SAMPLING_AREA && em->quad >= 0) {
        const struct emitter_quad *q = &s->emitter_quads[em->quad];
        struct spherical_rect r;
        if (quad_applies(q, x, choice.point, &r))
            return quad_pmf(s, choice.select, x, n, q, e, -1.0f, -1.0f) / r.omega;
    }
    const float pmf = emitter_pmf(s, choice.select, x, n, e);
    if (choice.point != LIGHT_SAMPLING_AREA && em->quad < 0) {
        struct spherical_triangle t;
        const float omega = emitter_solid_angle(em, x, choice.point, &t);
        if (omega > 0.0f)
            return pmf / omega;
    }
    const float pdf_area = pmf / s->tri_area[tri];
    return pdf_area * dist * dist / (cos_l > 1e-12f ? cos_l : 1e-12f);
}

/* Emission is one-sided: only the front (counter-clockwise, geometric normal) side emits. */
vec3 lights_radiance(const struct scene *s, int tri, float b1, float b2, vec3 w_out)
{
    if (tri < 0 || tri >= s->num_tris || v3_dot(s->tri_normal[tri], w_out) <= 0.0f)
        return v3s(0.0f);
    return point_emission(s, tri, b1, b2);
}

/* dA = dist^2 / |cos_l| dw (PBRT 3rd ed., eq. 5.6), so p_w = p_A dist^2 / cos_l. A light that
 * shows x its back (cos_l <= 0) cannot deliver light there, so its density is 0. */
float lights_pdf_solid_angle(float pdf_area, vec3 x, vec3 light_p, vec3 light_n)
{
    vec3 d = v3_sub(x, light_p);
    float dist2 = v3_length2(d);
    if (!(dist2 > 0.0f))
        return 0.0f;
    float cos_l = v3_dot(light_n, d) / sqrtf(dist2);
    if (cos_l <= 0.0f)
        return 0.0f;
    return pdf_area * dist2 / cos_l;
}
