/* scene_lights.c: the emitter table a scene owns (which triangles emit, their power alias table and
 * BVH).
 * Must never depend on shading: light sampling (src/shading/lights.c) reads this table, not back. */
#include "scene/scene_lights.h"

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
    }
    scene_light_bvh_build(s, power);
    free(power);
    return 0;
}
