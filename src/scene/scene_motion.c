/* scene_motion.c: moving emitters (scene_motion.h): the rest pose, and each frame's pose from it. */
#include "scene/scene_motion.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_animation.h"
#include "scene/scene_light_bvh.h"
#include "scene/scene_rt.h"

struct scene_motion {
    int num_tris;
    int *tris;               /* the moving triangles, ascending */
    vec3 *verts;             /* their corners at rest, 3 per triangle (each corner its own vertex) */
    vec3 *normals;           /* their corners' shading normals at rest, or NULL (s->normals is NULL) */
    float *tangents;         /* their corners' tangents at rest (4 floats each), or NULL */
    vec3 *tri_normal;        /* their normals at rest */
    int num_quads;
    int *quads;              /* the emitter rectangles made of moving emitters */
    struct emitter_quad *quad_rest;
    int num_materials;
    struct rigid_motion *pose; /* per material: where it is now (identity for one that stays) */
    float posed_at;            /* the frame the scene holds; NAN before the first pose */
    vec3 *previous;            /* corners of the previous-frame geometry (scene_motion_pose_previous) */
    struct rigid_motion *previous_pose; /* per material: where that frame had it */
    float previous_at;         /* its frame; NAN before the first */
};

void emission_animation_motion(const struct emission_animation *a, float t, struct rigid_motion *m)
{
    const double deg = 3.14159265358979323846 / 180.0;
    const vec3 ang = a->rotate ? emission_animation_vec_at(a, a->rotate, t) : v3(0, 0, 0);
    const double cx = cos(ang.x * deg), sx = sin(ang.x * deg), cy = cos(ang.y * deg), sy = sin(ang.y * deg);
    const double cz = cos(ang.z * deg), sz = sin(ang.z * deg);
    /* R = Rz Ry Rx (x first), row-major */
    const double r[9] = {cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx,
                         sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx,
                         -sy,     cy * sx,                cy * cx};
    for (int k = 0; k < 9; k++)
        m->r[k] = (float)r[k];
    /* x' = pivot + R (x - pivot) + translate */
    const vec3 move = a->translate ? emission_animation_vec_at(a, a->translate, t) : v3(0, 0, 0);
    m->t = v3_add(v3_sub(a->pivot, rigid_dir(m, a->pivot)), move);
}

static int material_moves(const struct scene *s, int m)
{
    return s->emission_anim && emission_animation_moves(&s->emission_anim[m]);
}

int scene_motion_prepare(struct scene *s, char *msg)
{
    int n = 0;
    for (int t = 0; t < s->num_tris; t++)
        n += material_moves(s, s->tri_material[t]);
    if (n == 0)
        return 0;
    /* each moving corner must be its own vertex: count every vertex's triangles */
    int *uses = xcalloc((size_t)s->num_verts, sizeof(int));
    for (int k = 0; k < 3 * s->num_tris; k++)
        uses[s->indices[k]]++;
    for (int t = 0; t < s->num_tris; t++)
        for (int k = 0; k < 3 && material_moves(s, s->tri_material[t]); k++)
            if (uses[s->indices[3 * t + k]] != 1) {
                snprintf(msg, RESTIR_MSG_LEN,
                         "scene '%s': moving emitter triangle %d shares a vertex with another triangle (a moving "
                         "emitter's triangles need their own vertices)",
                         s->name, t);
                free(uses);
                return -1;
            }
    free(uses);
    for (int m = 0; m < s->num_materials; m++) /* a pivot the file left out: the triangles' centre of area */
        if (material_moves(s, m) && !s->emission_anim[m].pivot_given) {
            vec3 c = v3(0, 0, 0);
            double area = 0.0;
            for (int t = 0; t < s->num_tris; t++)
                if (s->tri_material[t] == m) {
                    const vec3 sum = v3_add(s->verts[s->indices[3 * t]],
                                            v3_add(s->verts[s->indices[3 * t + 1]], s->verts[s->indices[3 * t + 2]]));
                    c = v3_madd(c, sum, s->tri_area[t] / 3.0f);
                    area += s->tri_area[t];
                }
            s->emission_anim[m].pivot = area > 0.0 ? v3_scale(c, (float)(1.0 / area)) : c;
        }
    struct scene_motion *mo = xcalloc(1, sizeof(*mo));
    mo->num_tris = n;
    mo->tris = xmalloc(sizeof(int) * (size_t)n);
    mo->verts = xmalloc(sizeof(vec3) * 3 * (size_t)n);
    mo->normals = s->normals ? xmalloc(sizeof(vec3) * 3 * (size_t)n) : NULL;
    mo->tangents = s->tangents ? xmalloc(sizeof(float) * 12 * (size_t)n) : NULL;
    mo->tri_normal = xmalloc(sizeof(vec3) * (size_t)n);
    n = 0;
    for (int t = 0; t < s->num_tris; t++) {
        if (!material_moves(s, s->tri_material[t]))
            continue;
        mo->tris[n] = t;
        mo->tri_normal[n] = s->tri_normal[t];
        for (int k = 0; k < 3; k++) {
            const uint32_t v = s->indices[3 * t + k];
            mo->verts[3 * n + k] = s->verts[v];
            if (mo->normals)
                mo->normals[3 * n + k] = s->normals[v];
            if (mo->tangents)
                memcpy(mo->tangents + 12 * (size_t)n + 4 * k, s->tangents + 4 * (size_t)v, 4 * sizeof(float));
        }
        n++;
    }
    for (int pass = 0; pass < 2; pass++) { /* count, then keep */
        mo->num_quads = 0;
        for (int q = 0; q < s->num_emitter_quads; q++)
            if (material_moves(s, s->tri_material[s->emitter_tri[s->emitter_quads[q].e[0]]])) {
                if (pass == 1) {
                    mo->quads[mo->num_quads] = q;
                    mo->quad_rest[mo->num_quads] = s->emitter_quads[q];
                }
                mo->num_quads++;
            }
        if (pass == 0) {
            mo->quads = xmalloc(sizeof(int) * (size_t)(mo->num_quads + 1));
            mo->quad_rest = xmalloc(sizeof(*mo->quad_rest) * (size_t)(mo->num_quads + 1));
        }
    }
    mo->num_materials = s->num_materials;
    mo->pose = xmalloc(sizeof(*mo->pose) * (size_t)s->num_materials);
    mo->posed_at = NAN;
    mo->previous = xmalloc(sizeof(vec3) * 3 * (size_t)n);
    mo->previous_pose = xmalloc(sizeof(*mo->previous_pose) * (size_t)s->num_materials);
    mo->previous_at = NAN;
    s->motion = mo;
    return 0;
}

int scene_motion_tris(const struct scene *s, const int **tris)
{
    *tris = s->motion ? s->motion->tris : NULL;
    return s->motion ? s->motion->num_tris : 0;
}

void scene_motion_apply(const struct scene *s, float t)
{
    struct scene_motion *mo = s->motion;
    if (!mo || mo->posed_at == t)
        return;
    const int changed = isnan(mo->posed_at) || scene_lights_moved(s, mo->posed_at, t);
    for (int m = 0; m < mo->num_materials; m++)
        if (material_moves(s, m))
            emission_animation_motion(&s->emission_anim[m], t, &mo->pose[m]);
    mo->posed_at = t;
    if (!changed)
        return;
    /* the one place a loaded scene's geometry changes: written through the const scene (scene_set_frame) */
    struct scene *w = (struct scene *)s;
    for (int i = 0; i < mo->num_tris; i++) {
        const int tri = mo->tris[i];
        const struct rigid_motion *pose = &mo->pose[s->tri_material[tri]];
        for (int k = 0; k < 3; k++) {
            const uint32_t v = s->indices[3 * tri + k];
            w->verts[v] = rigid_point(pose, mo->verts[3 * i + k]);
            if (mo->normals)
                w->normals[v] = rigid_dir(pose, mo->normals[3 * i + k]); /* zero (none) stays zero */
            if (mo->tangents) {
                const float *r = mo->tangents + 12 * (size_t)i + 4 * k;
                const vec3 d = rigid_dir(pose, v3(r[0], r[1], r[2]));
                float *o = w->tangents + 4 * (size_t)v;
                o[0] = d.x, o[1] = d.y, o[2] = d.z, o[3] = r[3];
            }
        }
        w->tri_normal[tri] = rigid_dir(pose, mo->tri_normal[i]);
        const int e = s->tri_emitter[tri];
        if (e >= 0) {
            struct emitter *em = &w->emitters[e];
            em->v0 = s->verts[s->indices[3 * tri]];
            em->e1 = v3_sub(s->verts[s->indices[3 * tri + 1]], em->v0);
            em->e2 = v3_sub(s->verts[s->indices[3 * tri + 2]], em->v0);
            em->n = s->tri_normal[tri];
        }
    }
    for (int i = 0; i < mo->num_quads; i++) {
        const struct emitter_quad *r = &mo->quad_rest[i];
        struct emitter_quad *q = &w->emitter_quads[mo->quads[i]];
        const struct rigid_motion *pose = &mo->pose[s->tri_material[s->emitter_tri[r->e[0]]]];
        q->corner = rigid_point(pose, r->corner);
        q->centre = rigid_point(pose, r->centre);
        q->ux = rigid_dir(pose, r->ux);
        q->uy = rigid_dir(pose, r->uy);
        q->uz = rigid_dir(pose, r->uz);
    }
    scene_light_bvh_refit(w);
    scene_rt_update_moving(w);
}

void scene_motion_pose_previous(const struct scene *s, float t)
{
    struct scene_motion *mo = s->motion;
    if (!mo || mo->previous_at == t || !scene_can_trace_previous(s))
        return;
    for (int m = 0; m < mo->num_materials; m++)
        if (material_moves(s, m))
            emission_animation_motion(&s->emission_anim[m], t, &mo->previous_pose[m]);
    for (int i = 0; i < mo->num_tris; i++) {
        const struct rigid_motion *pose = &mo->previous_pose[s->tri_material[mo->tris[i]]];
        for (int k = 0; k < 3; k++)
            mo->previous[3 * i + k] = rigid_point(pose, mo->verts[3 * i + k]);
    }
    scene_rt_update_previous(s, mo->previous);
    mo->previous_at = t;
}

/* The point at (b1, b2) of triangle tri and its normal, where pose (NULL: frame t's, computed) puts
 * a moving one; where the scene holds it now for one that stays. */
static void point_posed(const struct scene *s, int tri, float b1, float b2, float t,
                        const struct rigid_motion *pose, vec3 *p, vec3 *n)
{
    const struct scene_motion *mo = s->motion;
    vec3 v[3];
    *n = s->tri_normal[tri];
    for (int k = 0; k < 3; k++)
        v[k] = s->verts[s->indices[3 * tri + k]];
    if (mo && material_moves(s, s->tri_material[tri])) {
        int lo = 0, hi = mo->num_tris - 1; /* tris is ascending */
        while (lo < hi) {
            const int mid = (lo + hi) / 2;
            if (mo->tris[mid] < tri)
                lo = mid + 1;
            else
                hi = mid;
        }
        struct rigid_motion at;
        if (!pose) {
            emission_animation_motion(&s->emission_anim[s->tri_material[tri]], t, &at);
            pose = &at;
        }
        for (int k = 0; k < 3; k++)
            v[k] = rigid_point(pose, mo->verts[3 * lo + k]);
        *n = rigid_dir(pose, mo->tri_normal[lo]);
    }
    *p = v3_add(v[0], v3_add(v3_scale(v3_sub(v[1], v[0]), b1), v3_scale(v3_sub(v[2], v[0]), b2)));
}

void scene_motion_point_previous(const struct scene *s, int tri, float b1, float b2, vec3 *p, vec3 *n)
{
    const struct scene_motion *mo = s->motion;
    const int posed = mo && !isnan(mo->previous_at);
    point_posed(s, tri, b1, b2, posed ? mo->previous_at : 0.0f,
                posed ? &mo->previous_pose[s->tri_material[tri]] : NULL, p, n);
}

void scene_motion_point_at(const struct scene *s, int tri, float b1, float b2, float t, vec3 *p, vec3 *n)
{
    point_posed(s, tri, b1, b2, t, NULL, p, n);
}

void scene_set_frame(const struct scene *s, float t)
{
    if (!s->emission_anim)
        return;
    for (int m = 0; m < s->num_materials; m++) {
        const struct emission_animation *a = &s->emission_anim[m];
        if (a->n > 0)
            s->materials[m].emission = v3_scale(a->emission, emission_animation_at(a, t));
    }
    for (int e = 0; e < s->num_emitters; e++) {
        const int m = s->tri_material[s->emitters[e].tri];
        if (s->emission_anim[m].n > 0)
            s->emitters[e].Le = s->materials[m].emission;
    }
    scene_motion_apply(s, t);
}

void scene_motion_free(struct scene *s)
{
    struct scene_motion *mo = s->motion;
    if (!mo)
        return;
    free(mo->tris);
    free(mo->previous);
    free(mo->previous_pose);
    free(mo->verts);
    free(mo->normals);
    free(mo->tangents);
    free(mo->tri_normal);
    free(mo->quads);
    free(mo->quad_rest);
    free(mo->pose);
    free(mo);
    s->motion = NULL;
}
