/* scene_compare.h: two scenes the same, bit for bit (tests/unit/test_scenes_animated.c: a built-in scene against the
 * file it reproduces; tests/render/test_scene_export.c: an exported built-in read back): vertices, triangles, objects,
 * materials, emitters, the static camera, and animated emitters' keys and where they put every vertex and emitter
 * along the frames. The camera path is the callers' (a file may leave it out). Header-only, for tests. */
#ifndef RESTIR_TESTS_SCENE_COMPARE_H
#define RESTIR_TESTS_SCENE_COMPARE_H

#include <string.h>

#include "scene/scene.h"
#include "scene/scene_animation.h"
#include "scene/scene_motion.h"
#include "test_util.h"

#define SAME_ARRAY(a, b, n, what)                                                                  \
    EXPECT(((n) == 0) || memcmp((a), (b), sizeof(*(a)) * (size_t)(n)) == 0, "%s: %s differ", name, what)

/* The animated emitters' keys, and where every vertex and emitter is at frames 20, 28 and 0 (which
 * leaves both scenes at frame 0). */
static inline void compare_animations(const char *name, const struct scene *a, const struct scene *b)
{
    EXPECT(!a->emission_anim == !b->emission_anim, "%s: animated %d, the other's %d", name, a->emission_anim != NULL,
           b->emission_anim != NULL);
    if (!a->emission_anim || !b->emission_anim)
        return;
    for (int m = 0; m < a->num_materials; m++) {
        const struct emission_animation *p = &a->emission_anim[m], *q = &b->emission_anim[m];
        EXPECT(p->n == q->n && p->step == q->step && p->pivot_given == q->pivot_given &&
                   !memcmp(&p->pivot, &q->pivot, sizeof(vec3)) && !memcmp(&p->emission, &q->emission, sizeof(vec3)) &&
                   !p->translate == !q->translate && !p->rotate == !q->rotate,
               "%s: material %d's animation differs", name, m);
        if (p->n != q->n || !p->translate != !q->translate || !p->rotate != !q->rotate)
            continue;
        SAME_ARRAY(p->frame, q->frame, p->n, "key frames");
        SAME_ARRAY(p->strength, q->strength, p->n, "key strengths");
        if (p->translate)
            SAME_ARRAY(p->translate, q->translate, p->n, "key translations");
        if (p->rotate)
            SAME_ARRAY(p->rotate, q->rotate, p->n, "key rotations");
    }
    const float frames[] = {20.0f, 28.0f, 0.0f};
    for (int f = 0; f < 3; f++) {
        scene_set_frame(a, frames[f]);
        scene_set_frame(b, frames[f]);
        SAME_ARRAY(a->verts, b->verts, a->num_verts, "vertices along the animation");
        SAME_ARRAY(a->emitters, b->emitters, a->num_emitters, "emitters along the animation");
    }
}

/* Scene b against scene a, field by field; returns 1 when their sizes agree (the arrays were compared). */
static inline int compare_scenes(const char *name, const struct scene *a, const struct scene *b)
{
    EXPECT(a->num_verts == b->num_verts && a->num_tris == b->num_tris, "%s: %d/%d vertices, %d/%d triangles", name,
           a->num_verts, b->num_verts, a->num_tris, b->num_tris);
    EXPECT(a->num_materials == b->num_materials, "%s: %d vs %d materials", name, a->num_materials,
           b->num_materials);
    EXPECT(a->num_emitters == b->num_emitters, "%s: %d vs %d emitters", name, a->num_emitters, b->num_emitters);
    if (a->num_verts != b->num_verts || a->num_tris != b->num_tris || a->num_materials != b->num_materials ||
        a->num_emitters != b->num_emitters)
        return 0;
    SAME_ARRAY(a->verts, b->verts, a->num_verts, "vertices");
    SAME_ARRAY(a->indices, b->indices, 3 * a->num_tris, "indices");
    SAME_ARRAY(a->tri_material, b->tri_material, a->num_tris, "triangle materials");
    SAME_ARRAY(a->tri_object, b->tri_object, a->num_tris, "triangle objects");
    SAME_ARRAY(a->emitters, b->emitters, a->num_emitters, "emitters");
    for (int m = 0; m < a->num_materials; m++) {
        const struct material *x = &a->materials[m], *y = &b->materials[m];
        EXPECT(!memcmp(&x->base_color, &y->base_color, sizeof(vec3)) && x->metallic == y->metallic &&
                   x->roughness == y->roughness && !memcmp(&x->emission, &y->emission, sizeof(vec3)) &&
                   x->lambert_only == y->lambert_only,
               "%s: material %d differs", name, m);
    }
    compare_animations(name, a, b);
    EXPECT(!memcmp(&a->camera, &b->camera, sizeof(a->camera)), "%s: camera differs", name);
    return 1;
}

#endif
