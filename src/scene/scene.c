/* scene.c: building a scene from triangles (builder), deriving normals and areas, and releasing it.
 * Must never include embree headers (scene_rt.c owns the back end) nor anything from shading up. */
#include "scene/scene.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_animation.h"
#include "scene/scene_env.h"
#include "scene/scene_light_bvh.h"
#include "scene/scene_lights.h"
#include "scene/scene_motion.h"
#include "scene/scene_rt.h"

static void *grow_to(void *p, int cap, size_t elem)
{
    void *q = realloc(p, (size_t)cap * elem);
    if (!q) {
        fprintf(stderr, "out of memory growing scene arrays\n");
        exit(1);
    }
    return q;
}

/* p (n elements of elem bytes) grown to cap elements, the new ones zeroed. */
static void *grow_to_zeroed(void *p, int n, int cap, size_t elem)
{
    char *q = grow_to(p, cap, elem);
    memset(q + (size_t)n * elem, 0, (size_t)(cap - n) * elem);
    return q;
}

/* The default triangle budget (scene_load_desc.max_triangles). */
#define DEFAULT_MAX_TRIANGLES (1 << 26)

void scene_builder_begin_with(struct scene_builder *b, struct scene *s, const char *name,
                              const struct scene_load_desc *desc)
{
    memset(s, 0, sizeof(*s));
    memset(b, 0, sizeof(*b));
    b->s = s;
    if (desc)
        b->desc = *desc;
    if (b->desc.max_triangles <= 0)
        b->desc.max_triangles = DEFAULT_MAX_TRIANGLES;
    snprintf(s->name, sizeof(s->name), "%s", name);
    s->camera = (struct camera){v3(0, 1, 3), v3(0, 1, 0), v3(0, 1, 0), 45.0f, 0.0f, 0.0f};
}

void scene_builder_begin(struct scene_builder *b, struct scene *s, const char *name)
{
    scene_builder_begin_with(b, s, name, NULL);
}

int scene_add_material(struct scene_builder *b, struct material m)
{
    struct scene *s = b->s;
    if (s->num_materials == b->cap_materials) {
        b->cap_materials = b->cap_materials ? 2 * b->cap_materials : 16;
        s->materials = grow_to(s->materials, b->cap_materials, sizeof(*s->materials));
    }
    if (s->emission_anim) /* kept as long as the materials, for scene_destroy */
        s->emission_anim = grow_to_zeroed(s->emission_anim, s->num_materials, b->cap_materials,
                                          sizeof(*s->emission_anim));
    s->materials[s->num_materials] = m;
    return s->num_materials++;
}

/* 1 when every component of v is within [-lim, lim] (0 for NaN). */
static int v3_within(vec3 v, float lim) { return fabsf(v.x) <= lim && fabsf(v.y) <= lim && fabsf(v.z) <= lim; }

int scene_animate_material(struct scene_builder *b, int m, struct emission_animation *a, char *msg)
{
    struct scene *s = b->s;
    const char *why = NULL;
    if (m < 0 || m >= s->num_materials)
        why = "no such material";
    else if (!(v3_max_component(s->materials[m].emission) > 0.0f))
        why = "the material emits nothing: only an emitter can be animated";
    else if (s->emission_anim && s->emission_anim[m].n > 0)
        why = "the material is animated already";
    else if (a->n < 1 || !a->frame || !a->strength)
        why = "an animation needs at least one key";
    for (int k = 0; !why && k < a->n; k++) {
        if (!(a->strength[k] >= 0.0f && a->strength[k] <= 1e6f))
            why = "a strength is negative, not finite or above 1e6";
        else if (k > 0 && !(a->frame[k] > a->frame[k - 1]))
            why = "the keys' frames are not increasing";
        else if ((a->translate && !v3_within(a->translate[k], 1e6f)) || (a->rotate && !v3_within(a->rotate[k], 1e6f)))
            why = "a translation or rotation is not finite or beyond 1e6";
    }
    const vec3 sampled = why ? v3s(0.0f) : v3_scale(s->materials[m].emission, emission_animation_max(a));
    if (!why && !(v3_max_component(sampled) <= 1e18f))
        why = "emission times its largest strength exceeds 1e18";
    if (why) {
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s': animation of material %d: %s", s->name, m, why);
        emission_animation_free(a);
        return -1;
    }
    if (!s->emission_anim)
        s->emission_anim = grow_to_zeroed(NULL, 0, b->cap_materials, sizeof(*s->emission_anim));
    a->emission = s->materials[m].emission;
    s->materials[m].emission = sampled; /* sampling's tables see the largest strength; scene_set_frame the frame's */
    s->emission_anim[m] = *a;
    memset(a, 0, sizeof *a);
    return 0;
}

int scene_new_object(struct scene_builder *b) { return b->s->num_objects++; }

struct scene_texture_key {
    char *key;
    int srgb;
};

int scene_add_texture(struct scene_builder *b, struct texture t, const char *key, int srgb)
{
    struct scene *s = b->s;
    if (s->num_textures == b->cap_textures) {
        b->cap_textures = b->cap_textures ? 2 * b->cap_textures : 8;
        s->textures = grow_to(s->textures, b->cap_textures, sizeof(*s->textures));
        s->texture_keys = grow_to(s->texture_keys, b->cap_textures, sizeof(*s->texture_keys));
    }
    size_t len = strlen(key);
    s->texture_keys[s->num_textures].key = memcpy(xmalloc(len + 1), key, len + 1);
    s->texture_keys[s->num_textures].srgb = srgb;
    s->textures[s->num_textures++] = t;
    return s->num_textures;
}

int scene_texture_find(const struct scene *s, const char *key, int srgb)
{
    for (int t = 0; t < s->num_textures; t++)
        if (s->texture_keys[t].srgb == srgb && strcmp(s->texture_keys[t].key, key) == 0)
            return t + 1;
    return 0;
}

int scene_texture_unreadable(const struct scene_builder *b, const char *why)
{
    if (!b->desc.missing_textures_warn)
        return -1;
    fprintf(stderr, "restir: warning: %s; the material's factor is used instead of the map "
                    "(scene.missing_textures=warn)\n",
            why);
    return 0;
}

int scene_load_partial(struct scene_builder *b, const char *path, const char *notes, int lossy, char *msg)
{
    if (b->desc.strict && lossy) {
        snprintf(msg, RESTIR_MSG_LEN, "%.150s loads only in part (scene.strict=on refuses it): %.300s", path, notes);
        return -1;
    }
    fprintf(stderr, "restir: warning: %s loads only in part: %s%s\n", path, notes,
            lossy ? " (scene.strict=on refuses such a file)" : "");
    struct scene *s = b->s;
    const size_t old = s->load_notes ? strlen(s->load_notes) : 0, add = strlen(path) + strlen(notes) + 4;
    s->load_notes = grow_to(s->load_notes, (int)(old + add), 1);
    snprintf(s->load_notes + old, add, "%s: %s\n", path, notes);
    return 0;
}

void scene_set_uv_set(struct scene_builder *b, int tri, int set, const float uv[6])
{
    struct scene *s = b->s;
    if (b->over_budget) /* the triangle was refused; scene_builder_end will fail */
        return;
    RESTIR_CHECK(tri >= 0 && tri < s->num_tris && (set == 0 || set == 1));
    float **dst = set ? &s->uv1 : &s->uv;
    if (!*dst) /* first UVs: every other vertex gets (0, 0) */
        *dst = xcalloc(2 * (size_t)b->cap_verts, sizeof(float));
    for (int k = 0; k < 3; k++)
        memcpy(*dst + 2 * (size_t)s->indices[3 * tri + k], uv + 2 * k, 2 * sizeof(float));
}

void scene_set_uvs(struct scene_builder *b, int tri, const float uv[6]) { scene_set_uv_set(b, tri, 0, uv); }

void scene_set_normals(struct scene_builder *b, int tri, const vec3 n[3])
{
    struct scene *s = b->s;
    if (b->over_budget)
        return;
    RESTIR_CHECK(tri >= 0 && tri < s->num_tris);
    if (!s->normals) /* first normals: every other vertex shades flat */
        s->normals = xcalloc((size_t)b->cap_verts, sizeof(vec3));
    for (int k = 0; k < 3; k++) {
        float len = v3_length(n[k]);
        vec3 u = len > 1e-20f && isfinite(len) ? v3_scale(n[k], 1.0f / len) : v3s(0.0f);
        s->normals[s->indices[3 * tri + k]] = v3_is_finite(u) ? u : v3s(0.0f);
    }
}

void scene_set_tangents(struct scene_builder *b, int tri, const float t[12])
{
    struct scene *s = b->s;
    if (b->over_budget)
        return;
    RESTIR_CHECK(tri >= 0 && tri < s->num_tris);
    if (!s->tangents) /* first tangents: every other vertex has none (UV derivatives are used) */
        s->tangents = xcalloc(4 * (size_t)b->cap_verts, sizeof(float));
    for (int k = 0; k < 3; k++) {
        const float *c = &t[4 * k];
        const int ok = isfinite(c[0]) && isfinite(c[1]) && isfinite(c[2]);
        float *out = &s->tangents[4 * (size_t)s->indices[3 * tri + k]];
        for (int i = 0; i < 3; i++)
            out[i] = ok ? c[i] : 0.0f;
        out[3] = c[3] < 0.0f ? -1.0f : 1.0f;
    }
}

/* Appends a record when recording and this is an outermost shape call (a box's quads and a quad's
 * triangles are not recorded again); every shape function brackets its work with depth. */
static void record_shape(struct scene_builder *b, struct scene_shape_record r)
{
    if (!b->record || b->depth > 0)
        return;
    if (b->num_records == b->cap_records) {
        b->cap_records = b->cap_records ? 2 * b->cap_records : 64;
        b->records = grow_to(b->records, b->cap_records, sizeof(*b->records));
    }
    b->records[b->num_records++] = r;
}

void scene_add_triangle(struct scene_builder *b, vec3 a, vec3 c, vec3 d, int material, int object)
{
    record_shape(b, (struct scene_shape_record){.kind = SHAPE_TRIANGLE, .p = {a, c, d}, .material = material,
                                                .object = object});
    struct scene *s = b->s;
    if (s->num_tris >= b->desc.max_triangles) {
        b->over_budget = 1;
        return;
    }
    if (s->num_tris == b->cap_tris) {
        b->cap_tris = b->cap_tris ? 2 * b->cap_tris : 256;
        s->indices = grow_to(s->indices, 3 * b->cap_tris, sizeof(*s->indices));
        s->tri_material = grow_to(s->tri_material, b->cap_tris, sizeof(int));
        s->tri_object = grow_to(s->tri_object, b->cap_tris, sizeof(int));
    }
    if (s->num_verts + 3 > b->cap_verts) {
        int old_cap = b->cap_verts;
        b->cap_verts = b->cap_verts ? 2 * b->cap_verts : 768;
        s->verts = grow_to(s->verts, b->cap_verts, sizeof(*s->verts));
        float **sets[2] = {&s->uv, &s->uv1};
        for (int k = 0; k < 2; k++)
            if (*sets[k]) {
                *sets[k] = grow_to(*sets[k], 2 * b->cap_verts, sizeof(float));
                memset(*sets[k] + 2 * (size_t)old_cap, 0, 2 * sizeof(float) * (size_t)(b->cap_verts - old_cap));
            }
        if (s->normals) {
            s->normals = grow_to(s->normals, b->cap_verts, sizeof(vec3));
            memset(s->normals + old_cap, 0, sizeof(vec3) * (size_t)(b->cap_verts - old_cap));
        }
        if (s->tangents) {
            s->tangents = grow_to(s->tangents, 4 * b->cap_verts, sizeof(float));
            memset(s->tangents + 4 * (size_t)old_cap, 0, 4 * sizeof(float) * (size_t)(b->cap_verts - old_cap));
        }
    }
    uint32_t base = (uint32_t)s->num_verts;
    s->verts[s->num_verts++] = a;
    s->verts[s->num_verts++] = c;
    s->verts[s->num_verts++] = d;
    for (int k = 0; k < 3; k++)
        s->indices[3 * s->num_tris + k] = base + (uint32_t)k;
    s->tri_material[s->num_tris] = material;
    s->tri_object[s->num_tris] = object;
    s->num_tris++;
}

void scene_add_quad(struct scene_builder *b, vec3 a, vec3 c, vec3 d, vec3 e, int material, int object)
{
    record_shape(b, (struct scene_shape_record){.kind = SHAPE_QUAD, .p = {a, c, d, e}, .material = material,
                                                .object = object});
    b->depth++;
    scene_add_triangle(b, a, c, d, material, object);
    scene_add_triangle(b, a, d, e, material, object);
    b->depth--;
}

/* Emits the six outward faces of the box spanned by the 8 corners
 * corner(i) = (i&1 ? hi.x : lo.x, i&2 ? hi.y : lo.y, i&4 ? hi.z : lo.z), transformed by rotate. */
static void add_box_corners(struct scene_builder *b, const vec3 corner[8], int material, int object)
{
    /* Each face lists its corners counter-clockwise seen from outside. */
    static const int faces[6][4] = {
        {0, 4, 6, 2}, /* -x */
        {1, 3, 7, 5}, /* +x */
        {0, 1, 5, 4}, /* -y */
        {2, 6, 7, 3}, /* +y */
        {0, 2, 3, 1}, /* -z */
        {4, 5, 7, 6}, /* +z */
    };
    for (int f = 0; f < 6; f++)
        scene_add_quad(b, corner[faces[f][0]], corner[faces[f][1]], corner[faces[f][2]], corner[faces[f][3]],
                       material, object);
}

void scene_add_box_rotated_y(struct scene_builder *b, vec3 lo, vec3 hi, float angle_rad, int material,
                             int object)
{
    record_shape(b, (struct scene_shape_record){.kind = SHAPE_BOX, .p = {lo, hi}, .f = angle_rad,
                                                .material = material, .object = object});
    vec3 center = v3_scale(v3_add(lo, hi), 0.5f);
    float cs = cosf(angle_rad), sn = sinf(angle_rad);
    vec3 corner[8];
    for (int i = 0; i < 8; i++) {
        vec3 p = v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        vec3 d = v3_sub(p, center);
        corner[i] = v3_add(center, v3(cs * d.x + sn * d.z, d.y, -sn * d.x + cs * d.z));
    }
    b->depth++;
    add_box_corners(b, corner, material, object);
    b->depth--;
}

void scene_add_box(struct scene_builder *b, vec3 lo, vec3 hi, int material, int object)
{
    scene_add_box_rotated_y(b, lo, hi, 0.0f, material, object);
}

void scene_add_sphere(struct scene_builder *b, vec3 center, float radius, int segments, int flags,
                      int material, int object)
{
    record_shape(b, (struct scene_shape_record){.kind = SHAPE_SPHERE, .p = {center}, .f = radius,
                                                .segments = segments, .sphere_flags = flags,
                                                .material = material, .object = object});
    b->depth++;
    const int inward = flags & SPHERE_INWARD, smooth = flags & SPHERE_SMOOTH;
    int rings = segments / 2 > 2 ? segments / 2 : 2;
    for (int i = 0; i < rings; i++) {
        float t0 = RESTIR_PI * (float)i / (float)rings, t1 = RESTIR_PI * (float)(i + 1) / (float)rings;
        for (int j = 0; j < segments; j++) {
            float p0 = 2.0f * RESTIR_PI * (float)j / (float)segments;
            float p1 = 2.0f * RESTIR_PI * (float)(j + 1) / (float)segments;
#define SPHERE_DIR(t, p) v3(sinf(t) * cosf(p), cosf(t), sinf(t) * sinf(p))
            vec3 na = SPHERE_DIR(t0, p0), nc = SPHERE_DIR(t0, p1), nd = SPHERE_DIR(t1, p1), ne = SPHERE_DIR(t1, p0);
#undef SPHERE_DIR
            vec3 a = v3_madd(center, na, radius), c = v3_madd(center, nc, radius);
            vec3 d = v3_madd(center, nd, radius), e = v3_madd(center, ne, radius);
            /* The tangent along theta crossed with the one along phi points inward, so a, c, d, e
             * winds outward and a, e, d, c inward. Poles degenerate to triangles. */
            const float sign = inward ? -1.0f : 1.0f;
            vec3 n1[3] = {v3_scale(na, sign), v3_scale(inward ? nd : nc, sign), v3_scale(inward ? nc : nd, sign)};
            vec3 n2[3] = {v3_scale(na, sign), v3_scale(inward ? ne : nd, sign), v3_scale(inward ? nd : ne, sign)};
            if (i != 0) {
                scene_add_triangle(b, a, inward ? d : c, inward ? c : d, material, object);
                if (smooth)
                    scene_set_normals(b, b->s->num_tris - 1, n1);
            }
            if (i != rings - 1) {
                scene_add_triangle(b, a, inward ? e : d, inward ? d : e, material, object);
                if (smooth)
                    scene_set_normals(b, b->s->num_tris - 1, n2);
            }
        }
    }
    b->depth--;
}

static int derive_triangle_data(struct scene *s, char *msg)
{
    s->tri_normal = xmalloc(sizeof(vec3) * (size_t)s->num_tris);
    s->tri_area = xmalloc(sizeof(float) * (size_t)s->num_tris);
    for (int i = 0; i < s->num_verts; i++) {
        if (!v3_is_finite(s->verts[i])) {
            snprintf(msg, RESTIR_MSG_LEN, "scene '%s': vertex %d is not finite", s->name, i);
            return -1;
        }
    }
    for (int t = 0; t < s->num_tris; t++) {
        if (s->tri_material[t] < 0 || s->tri_material[t] >= s->num_materials) {
            snprintf(msg, RESTIR_MSG_LEN, "scene '%s': triangle %d has unknown material %d", s->name, t,
                     s->tri_material[t]);
            return -1;
        }
        vec3 a = s->verts[s->indices[3 * t]], c = s->verts[s->indices[3 * t + 1]];
        vec3 d = s->verts[s->indices[3 * t + 2]];
        vec3 n = v3_cross(v3_sub(c, a), v3_sub(d, a));
        float len = v3_length(n);
        s->tri_area[t] = 0.5f * len;
        s->tri_normal[t] = len > 0.0f ? v3_scale(n, 1.0f / len) : v3(0, 1, 0);
    }
    return 0;
}

/* The diagonal of the vertices' bounding box, once per scene: a renderer asks at every start, and
 * a walk over a large mesh's vertices cost 26% of a test starting thousands of small renders. */
static float vertex_bounds_diagonal(const struct scene *s)
{
    if (s->num_verts == 0)
        return 0.0f;
    vec3 lo = s->verts[0], hi = s->verts[0];
    for (int i = 1; i < s->num_verts; i++) {
        vec3 v = s->verts[i];
        lo = v3(fminf(lo.x, v.x), fminf(lo.y, v.y), fminf(lo.z, v.z));
        hi = v3(fmaxf(hi.x, v.x), fmaxf(hi.y, v.y), fmaxf(hi.z, v.z));
    }
    return v3_length(v3_sub(hi, lo));
}

int scene_builder_end(struct scene_builder *b, char *msg)
{
    struct scene *s = b->s;
    if (b->over_budget) {
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s' has more than %d triangles (the limit)", s->name,
                 b->desc.max_triangles);
        return -1;
    }
    if (s->num_tris == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s' has no triangles", s->name);
        return -1;
    }
    for (int m = 0; m < s->num_materials; m++) {
        if (b->desc.no_alpha_masks)
            s->materials[m].alpha_mask = 0;
        if (b->desc.flat_shading)
            s->materials[m].normal_map = 0;
        const struct material *mt = &s->materials[m];
        if (!v3_is_finite(mt->base_color) || !v3_is_finite(mt->emission) || !isfinite(mt->metallic) ||
            !isfinite(mt->roughness) || v3_max_component(v3_neg(mt->emission)) > 0.0f) {
            snprintf(msg, RESTIR_MSG_LEN, "scene '%s': material %d has NaN, infinite or negative values",
                     s->name, m);
            return -1;
        }
        const int maps[4] = {mt->base_color_map, mt->metal_rough_map, mt->emission_map, mt->normal_map};
        for (int k = 0; k < 4; k++) {
            if (maps[k] < 0 || maps[k] > s->num_textures) {
                snprintf(msg, RESTIR_MSG_LEN, "scene '%s': material %d names texture %d of %d", s->name, m, maps[k],
                         s->num_textures);
                return -1;
            }
        }
    }
    if (b->desc.flat_shading) {
        free(s->normals);
        free(s->tangents);
        s->normals = NULL;
        s->tangents = NULL;
    }
    if (derive_triangle_data(s, msg) != 0 || scene_lights_build(s, msg) != 0 || scene_motion_prepare(s, msg) != 0)
        return -1;
    s->diagonal = vertex_bounds_diagonal(s);
    double t0 = omp_get_wtime();
    const int *moving_tris;
    const int moving = scene_motion_tris(s, &moving_tris);
    int rc = scene_rt_build(s, moving_tris, moving, msg);
    s->bvh_ms = 1e3 * (omp_get_wtime() - t0);
    if (rc == 0) {
        scene_set_ray_streams(s, !b->desc.ray_streams_off);
        scene_set_frame(s, 0.0f); /* animated emitters (s->emission_anim, set by the reader): frame 0 */
    }
    return rc;
}

void scene_destroy(struct scene *s)
{
    scene_rt_destroy(s);
    scene_env_free(s);
    free(s->verts);
    free(s->indices);
    free(s->tri_material);
    free(s->tri_object);
    free(s->tri_normal);
    free(s->tri_area);
    free(s->tri_emitter);
    free(s->emitter_tri);
    free(s->emitters);
    free(s->emitter_quads);
    free(s->materials);
    free(s->camera_path.keys);
    free(s->uv);
    free(s->uv1);
    free(s->normals);
    free(s->tangents);
    for (int t = 0; t < s->num_textures; t++) {
        texture_fini(&s->textures[t]);
        free(s->texture_keys[t].key);
    }
    free(s->textures);
    free(s->texture_keys);
    free(s->load_notes);
    for (int m = 0; s->emission_anim && m < s->num_materials; m++)
        emission_animation_free(&s->emission_anim[m]);
    free(s->emission_anim);
    scene_motion_free(s);
    if (s->num_emitters > 0)
        alias_table_fini(&s->emitter_table);
    scene_light_bvh_free(&s->light_bvh);
    memset(s, 0, sizeof(*s));
}

float scene_diagonal(const struct scene *s) { return s->diagonal; }
