/* scene_hash.c: scene_content_hash, which tells a resumed reference whether its scene is the one
 * its checkpoint was rendered from. Must never hash what rendering does not read. */
#include "scene/scene_hash.h"

#include <assert.h>

#include "core/hash.h"
#include "scene/environment.h"
#include "scene/texture.h"

/* Hashing the structs' bytes is only stable when they hold no padding: all 4-byte fields. */
static_assert(sizeof(vec3) == 3 * sizeof(float), "vec3 must be three packed floats");
static_assert(sizeof(struct material) == 57 * 4, "struct material must be 4-byte fields without padding");


uint64_t scene_content_hash(const struct scene *s)
{
    uint64_t h = FNV1A64_BASIS;
    const int counts[4] = {s->num_verts, s->num_tris, s->num_materials, s->num_textures};
    h = fnv1a64(h, counts, sizeof counts);
    h = fnv1a64(h, s->verts, sizeof(vec3) * (size_t)s->num_verts);
    h = fnv1a64(h, s->indices, 3 * sizeof(uint32_t) * (size_t)s->num_tris);
    h = fnv1a64(h, s->tri_material, sizeof(int) * (size_t)s->num_tris);
    h = fnv1a64(h, s->tri_object, sizeof(int) * (size_t)s->num_tris);
    if (s->uv)
        h = fnv1a64(h, s->uv, 2 * sizeof(float) * (size_t)s->num_verts);
    if (s->uv1)
        h = fnv1a64(h, s->uv1, 2 * sizeof(float) * (size_t)s->num_verts);
    if (s->normals)
        h = fnv1a64(h, s->normals, sizeof(vec3) * (size_t)s->num_verts);
    if (s->tangents)
        h = fnv1a64(h, s->tangents, 4 * sizeof(float) * (size_t)s->num_verts);
    h = fnv1a64(h, s->materials, sizeof(struct material) * (size_t)s->num_materials);
    if (s->env) { /* the environment light: its image, or colour, and how it is scaled and turned */
        const struct environment *e = s->env;
        const int size[2] = {e->width, e->height};
        const float k[5] = {e->constant.x, e->constant.y, e->constant.z, e->intensity, e->rotation};
        h = fnv1a64(h, size, sizeof size);
        h = fnv1a64(h, k, sizeof k);
        if (e->rgb)
            h = fnv1a64(h, e->rgb, 3 * sizeof(float) * (size_t)e->width * (size_t)e->height);
    }
    for (int m = 0; s->emission_anim && m < s->num_materials; m++) { /* animated emitters: their keys */
        const struct emission_animation *a = &s->emission_anim[m];
        const int head[3] = {a->n, a->step, (a->translate != NULL) + 2 * (a->rotate != NULL)};
        h = fnv1a64(h, head, sizeof head);
        if (a->n < 1)
            continue;
        h = fnv1a64(h, a->frame, sizeof(float) * (size_t)a->n);
        h = fnv1a64(h, a->strength, sizeof(float) * (size_t)a->n);
        if (a->translate)
            h = fnv1a64(h, a->translate, sizeof(vec3) * (size_t)a->n);
        if (a->rotate)
            h = fnv1a64(h, a->rotate, sizeof(vec3) * (size_t)a->n);
        h = fnv1a64(h, &a->pivot, sizeof(vec3));
        h = fnv1a64(h, &a->emission, sizeof(vec3));
    }
    for (int t = 0; t < s->num_textures; t++) {
        const struct texture *x = &s->textures[t];
        const int size[2] = {x->width, x->height};
        h = fnv1a64(h, size, sizeof size);
        h = fnv1a64(h, x->rgb, 3 * sizeof(float) * (size_t)x->width * (size_t)x->height);
    }
    return h;
}
