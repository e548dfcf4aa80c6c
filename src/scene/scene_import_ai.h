/* scene_import_ai.h: small helpers on assimp's types that the importer's files share (limits,
 * transforms, strings, the glTF test). Header-only; internal to scene_import*.c: must never be
 * included outside them (it exposes assimp types). */
#ifndef RESTIR_SCENE_SCENE_IMPORT_AI_H
#define RESTIR_SCENE_SCENE_IMPORT_AI_H

#include <assimp/scene.h>
#include <string.h>

#include "scene/file_name.h"
#include "scene/mat4d.h"

/* Deeper node hierarchies are refused rather than risking the stack (real assets have tens). */
#define IMPORT_MAX_NODE_DEPTH 1024
/* The builder's arrays grow by doubling int capacities (3 indices per triangle); this keeps every
 * capacity far from INT_MAX. */
#define IMPORT_MAX_TRIS 100000000

/* ---- 4x4 transforms: assimp's as mat4d (mat4d.h) ------------------------------------------- */

static inline mat4d mat4d_from_ai(const struct aiMatrix4x4 *a)
{
    const double v[16] = {a->a1, a->a2, a->a3, a->a4, a->b1, a->b2, a->b3, a->b4,
                          a->c1, a->c2, a->c3, a->c4, a->d1, a->d2, a->d3, a->d4};
    mat4d r;
    memcpy(r.m, v, sizeof(v));
    return r;
}

/* ---- small helpers ------------------------------------------------------------------------- */

/* aiString as a C string; its length field is trusted only up to the buffer. */
static inline void ai_string_copy(char *dst, size_t cap, const struct aiString *s)
{
    size_t n = s->length < MAXLEN ? s->length : MAXLEN - 1;
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, s->data, n);
    dst[n] = '\0';
}

static inline int ai_string_equal(const struct aiString *a, const struct aiString *b)
{
    return a->length == b->length && a->length < MAXLEN && memcmp(a->data, b->data, a->length) == 0;
}

static inline int is_gltf_path(const char *path)
{
    return scene_path_has_suffix(path, ".gltf") || scene_path_has_suffix(path, ".glb");
}

#endif
