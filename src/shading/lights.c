/* lights.c: emitter selection through the scene's alias table, uniform points on emissive triangles,
 * one-sided emission, area-to-solid-angle conversion. Must never depend on the ray tracer or render. */
#include "shading/lights.h"

#include <math.h>

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

int lights_sample(const struct scene *s, float u_select, float u1, float u2, struct light_sample *ls)
{
    if (s->num_emitters < 1)
        return 0;
    int e = alias_table_sample(&s->emitter_table, u_select);
    float b1, b2;
    warp_uniform_triangle(u1, u2, &b1, &b2);
    lights_emitter_point(s, &s->emitters[e], b1, b2, ls);
    return ls->pdf_area > 0.0f;
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
