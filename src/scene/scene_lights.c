/* scene_lights.c: the emitter table a scene owns (which triangles emit, their power alias table and
 * BVH, and which pairs of them make rectangles).
 * Must never depend on shading: light sampling (src/shading/lights.c) reads this table, not back. */
#include "scene/scene_lights.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "scene/scene_light_bvh.h"

static vec3 tri_emission(const struct scene *s, int tri) { return s->materials[s->tri_material[tri]].emission; }

/* Power of a Lambertian emitter of radiance L over area A: integral of L cos over the
 * hemisphere times A = pi L A (one-sided). Luminance collapses the colour for selection. */
float lights_emitter_power(const struct scene *s, int tri)
{
    return v3_luminance(tri_emission(s, tri)) * s->tri_area[tri] * RESTIR_PI;
}

static vec3 corner_of(const struct scene *s, int tri, int k) { return s->verts[s->indices[3 * tri + k]]; }
static int same_point(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* Relative tolerance of the rectangle test: the closing corner and the right angle within this
 * fraction of the edges (float rounding of rotated corners is ~1e-7 of their coordinates). */
#define QUAD_TOLERANCE 1e-5f

/* Whether emitters ea and eb are the two halves of a rectangle: one material, the same side, two
 * corners in common (the diagonal), the fourth corner closing a parallelogram with right angles.
 * Fills q with the rectangle and each half's map from rectangle coordinates to its barycentrics. */
static int pair_quad(const struct scene *s, int ea, int eb, struct emitter_quad *q)
{
    const int ta = s->emitter_tri[ea], tb = s->emitter_tri[eb];
    if (s->tri_material[ta] != s->tri_material[tb] || v3_dot(s->tri_normal[ta], s->tri_normal[tb]) < 0.9999f)
        return 0;
    int shared_a[3] = {0, 0, 0}, shared_b[3] = {0, 0, 0}, n_shared = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (same_point(corner_of(s, ta, i), corner_of(s, tb, j)) && !shared_a[i] && !shared_b[j]) {
                shared_a[i] = shared_b[j] = 1;
                n_shared++;
            }
    if (n_shared != 2)
        return 0;
    int ia = 0, ib = 0, id[2], nd = 0;
    for (int i = 0; i < 3; i++) {
        if (!shared_a[i])
            ia = i;
        else
            id[nd++] = i;
        if (!shared_b[i])
            ib = i;
    }
    /* rectangle coordinates (a, b) of the four corners: the lone corner of A (0, 0), the diagonal
     * (1, 0) and (0, 1), the lone corner of B (1, 1) */
    const vec3 o = corner_of(s, ta, ia), d0 = corner_of(s, ta, id[0]), d1 = corner_of(s, ta, id[1]);
    const vec3 ob = corner_of(s, tb, ib), ex = v3_sub(d0, o), ey = v3_sub(d1, o);
    const float lx = v3_length(ex), ly = v3_length(ey);
    if (!(lx > 0.0f && ly > 0.0f) || !isfinite(lx * ly))
        return 0;
    if (v3_length(v3_sub(v3_add(o, v3_add(ex, ey)), ob)) > QUAD_TOLERANCE * (lx + ly) ||
        fabsf(v3_dot(ex, ey)) > QUAD_TOLERANCE * lx * ly)
        return 0;
    q->corner = o;
    q->ux = v3_scale(ex, 1.0f / lx);
    q->uy = v3_normalize(v3_sub(ey, v3_scale(q->ux, v3_dot(ey, q->ux)))); /* exactly orthogonal */
    q->uz = v3_cross(q->ux, q->uy);
    q->lx = lx;
    q->ly = ly;
    q->inv_lx = 1.0f / lx;
    q->inv_ly = 1.0f / ly;
    q->area = lx * ly;
    q->radius = 0.5f * sqrtf(lx * lx + ly * ly);
    q->centre = v3_add(o, v3_scale(v3_add(ex, ey), 0.5f));
    q->e[0] = ea;
    q->e[1] = eb;
    for (int k = 0; k < 2; k++) {
        const int t = k == 0 ? ta : tb;
        float c[3][2];
        for (int v = 0; v < 3; v++) {
            const vec3 p = corner_of(s, t, v);
            c[v][0] = same_point(p, d0) || (k == 1 && !same_point(p, d1)) ? 1.0f : 0.0f;
            c[v][1] = same_point(p, d1) || (k == 1 && !same_point(p, d0)) ? 1.0f : 0.0f;
        }
        /* (a, b) = c0 + b1 (c1 - c0) + b2 (c2 - c0), inverted; the determinant is +-1 */
        const float m00 = c[1][0] - c[0][0], m01 = c[2][0] - c[0][0], m10 = c[1][1] - c[0][1], m11 = c[2][1] - c[0][1];
        const float det = m00 * m11 - m01 * m10;
        if (det != 1.0f && det != -1.0f)
            return 0;
        const float i00 = m11 / det, i01 = -m01 / det, i10 = -m10 / det, i11 = m00 / det;
        float *m = q->bary[k];
        m[0] = i00, m[1] = i01, m[2] = -(i00 * c[0][0] + i01 * c[0][1]);
        m[3] = i10, m[4] = i11, m[5] = -(i10 * c[0][0] + i11 * c[0][1]);
    }
    return 1;
}

/* Pairs consecutive emitters into rectangles where they make one (scene_add_quad and mesh files
 * list a quad's two triangles one after the other); sets every emitter's quad. Two passes of the
 * same greedy pairing: count, then fill. */
static void find_quads(struct scene *s)
{
    struct emitter_quad q;
    int n = 0;
    for (int e = 0; e + 1 < s->num_emitters; e++)
        if (pair_quad(s, e, e + 1, &q))
            n++, e++;
    s->num_emitter_quads = n;
    s->emitter_quads = n > 0 ? xmalloc(sizeof(q) * (size_t)n) : NULL;
    for (int e = 0; e < s->num_emitters; e++)
        s->emitters[e].quad = -1;
    n = 0;
    for (int e = 0; e + 1 < s->num_emitters; e++)
        if (pair_quad(s, e, e + 1, &q)) {
            s->emitter_quads[n] = q;
            s->emitters[e].quad = s->emitters[e + 1].quad = n++;
            e++;
        }
}

int scene_lights_build(struct scene *s, char *msg)
{
    s->tri_emitter = xmalloc(sizeof(int) * (size_t)s->num_tris);
    s->emitter_tri = xmalloc(sizeof(int) * (size_t)s->num_tris);
    s->num_emitters = 0;
    for (int t = 0; t < s->num_tris; t++) {
        vec3 e = s->materials[s->tri_material[t]].emission;
        int emits = v3_max_component(e) > 0.0f && s->tri_area[t] > 0.0f;
        s->tri_emitter[t] = emits ? s->num_emitters : -1;
        if (emits)
            s->emitter_tri[s->num_emitters++] = t;
    }
    if (s->num_emitters == 0)
        return 0; /* a scene without lights renders black; light sampling reports no sample */
    float *power = xmalloc(sizeof(float) * (size_t)s->num_emitters);
    for (int i = 0; i < s->num_emitters; i++)
        power[i] = lights_emitter_power(s, s->emitter_tri[i]);
    int rc = alias_table_init(&s->emitter_table, power, s->num_emitters);
    if (rc != 0) {
        free(power);
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s': emitter powers are invalid (negative or NaN emission)",
                 s->name);
        return -1;
    }
    s->emitters = xmalloc(sizeof(*s->emitters) * (size_t)s->num_emitters);
    for (int e = 0; e < s->num_emitters; e++) {
        int t = s->emitter_tri[e];
        struct emitter *em = &s->emitters[e];
        em->v0 = s->verts[s->indices[3 * t]];
        em->e1 = v3_sub(s->verts[s->indices[3 * t + 1]], em->v0);
        em->e2 = v3_sub(s->verts[s->indices[3 * t + 2]], em->v0);
        em->n = s->tri_normal[t];
        em->Le = s->materials[s->tri_material[t]].emission;
        /* per-point radiance: an emission map, or an alpha mask that cuts parts of it away */
        em->textured = s->materials[s->tri_material[t]].emission_map != 0 || s->materials[s->tri_material[t]].alpha_mask;
        em->pdf_area = s->emitter_table.pmf[e] / s->tri_area[t];
        em->tri = t;
        const vec3 centroid = v3_scale(v3_add(em->e1, em->e2), 1.0f / 3.0f); /* from v0 */
        em->radius = sqrtf(fmaxf(v3_length2(centroid), fmaxf(v3_length2(v3_sub(em->e1, centroid)),
                                                             v3_length2(v3_sub(em->e2, centroid)))));
    }
    find_quads(s);
    scene_light_bvh_build(s, power);
    free(power);
    return 0;
}
