/* scene_import.c: mesh files through assimp's C API (glTF 2.0, OBJ, PLY, ...) into the scene
 * builder: node transforms, materials, the first camera. Must never print or abort on bad input. */
#include "scene/scene_import.h"

#include <assimp/GltfMaterial.h>
#include <assimp/camera.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/environment.h"
#include "scene/file_name.h"
#include "scene/import_notes.h"
#include "scene/mat4d.h"
#include "scene/scene_env.h"
#include "scene/scene_import_ai.h"
#include "scene/scene_import_camera.h"
#include "scene/scene_import_gltf.h"
#include "scene/scene_import_guard.h"
#include "scene/scene_import_precheck.h"
#include "scene/scene_import_texture.h"

/* With scene_import_texture.c the only file that includes assimp headers. Every problem goes into
 * msg, naming the file: a bad asset is user input, not a bug. */

/* ---- the import ---------------------------------------------------------------------------- */

struct importer {
    struct scene_builder *b;
    const char *path;
    const struct aiScene *ai;
    int material;             /* >= 0: every triangle's material */
    int object;               /* >= 0: every triangle's object */
    int *builder_material;    /* per file material: builder id once used, else -1 */
    int *override_material;   /* per file material: the override's builder id, else -1 */
    cJSON *gltf;              /* the glTF JSON, parsed on first need (emissive strength) */
    int gltf_tried;
    vec3 *verts;              /* one mesh's vertices after the transform (scratch) */
    vec3 *normals;            /* ... and its vertex normals, when it has them (scratch) */
    float *tangents;          /* ... and tangents (xyz, handedness), when it has them (scratch) */
    unsigned cap_verts;
    int added;                /* triangles added */
    long degenerate;          /* triangles skipped: zero area or too thin for a normal */
    long not_triangles;       /* point and line primitives skipped */
    long bad_uvs;             /* texture coordinates that were not finite (set to 0) */
    struct import_notes notes; /* assimp's warnings and errors (import_notes.h) */
    char *msg;
};

/* A float material property, or def when the file does not set it. */
static float mat_float(const struct aiMaterial *m, const char *key, unsigned type, unsigned index, float def,
                       int *present)
{
    ai_real v = 0;
    unsigned int max = 1;
    int ok = aiGetMaterialFloatArray(m, key, type, index, &v, &max) == aiReturn_SUCCESS && max == 1;
    if (present)
        *present = ok;
    return ok ? (float)v : def;
}

static int mat_color(const struct aiMaterial *m, const char *key, unsigned type, unsigned index, vec3 *out)
{
    struct aiColor4D c;
    if (aiGetMaterialColor(m, key, type, index, &c) != aiReturn_SUCCESS)
        return 0;
    *out = v3((float)c.r, (float)c.g, (float)c.b);
    return 1;
}

static void material_name(const struct aiMaterial *m, char *out, size_t cap)
{
    struct aiString s;
    if (aiGetMaterialString(m, AI_MATKEY_NAME, &s) == aiReturn_SUCCESS)
        ai_string_copy(out, cap, &s);
    else
        snprintf(out, cap, "%s", "");
}

static float clamp01(float x) { return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x; }

/* The glTF file's own JSON, parsed on first need (NULL for other formats or when unreadable). */
static const cJSON *gltf_json(struct importer *im)
{
    if (!im->gltf_tried && is_gltf_path(im->path)) {
        im->gltf_tried = 1;
        im->gltf = import_gltf_read(im->path);
    }
    return im->gltf;
}

/* Emission multiplier of file material idx: assimp's intensity (glTF emissive strength from 5.3
 * on), else the strength read from the glTF JSON (assimp 5.2), else 1. */
static float emissive_strength(struct importer *im, const struct aiMaterial *m, const char *name)
{
    int present;
    float k = mat_float(m, AI_MATKEY_EMISSIVE_INTENSITY, 1.0f, &present);
    if (present || !is_gltf_path(im->path) || !*name)
        return k;
    return mat4d_to_float(import_gltf_strength(gltf_json(im), name));
}

/* glTF alphaMode, alphaCutoff and baseColorFactor's alpha (BLEND is read as MASK at the cutoff,
 * 0.5 by default: a path tracer has no blending order). */
static int import_alpha(struct importer *im, const struct aiMaterial *m, const char *name, struct material *out)
{
    struct aiString mode;
    out->base_alpha = 1.0f;
    out->alpha_cutoff = 0.5f;
    if (aiGetMaterialString(m, AI_MATKEY_GLTF_ALPHAMODE, &mode) != aiReturn_SUCCESS)
        return 0;
    out->alpha_mask = !strcmp(mode.data, "MASK") || !strcmp(mode.data, "BLEND");
    if (!out->alpha_mask)
        return 0;
    int present;
    float cutoff = mat_float(m, AI_MATKEY_GLTF_ALPHACUTOFF, 0.5f, &present);
    if (!(cutoff >= 0.0f && cutoff <= 1.0f)) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%s: material '%s': alphaCutoff %g is outside [0, 1]", im->path, name,
                 (double)cutoff);
        return -1;
    }
    out->alpha_cutoff = cutoff;
    struct aiColor4D c;
    if (aiGetMaterialColor(m, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS && isfinite(c.a))
        out->base_alpha = clamp01((float)c.a);
    return 0;
}

/* Our material for file material idx. glTF metallic-roughness factors map one to one, and its
 * three texture maps multiply them (scene_import_texture.c). For other formats: the diffuse colour, and a
 * roughness from the Phong exponent Ns when there is no roughness: Beckmann alpha =
 * sqrt(2 / (Ns + 2)) (Walter et al. 2007), used as GGX alpha, roughness = sqrt(alpha), so Ns 0 is
 * fully rough and Ns 1000 gives 0.21. glTF's KHR_materials_pbrSpecularGlossiness (assimp reports
 * its glossiness) becomes a dielectric with the diffuse colour and roughness 1 - glossiness: the
 * metallic-roughness defaults that assimp also fills in (white metal) would be wrong. */
static int make_material(struct importer *im, unsigned idx, struct material *out)
{
    const struct aiMaterial *m = im->ai->mMaterials[idx];
    char name[256];
    material_name(m, name, sizeof name);
    vec3 base = v3s(0.8f);
    float metallic, roughness;
    int spec_gloss, has_rough, has_shin;
    float gloss = mat_float(m, AI_MATKEY_GLOSSINESS_FACTOR, 0.0f, &spec_gloss);
    if (spec_gloss) {
        mat_color(m, AI_MATKEY_COLOR_DIFFUSE, &base);
        metallic = 0.0f;
        roughness = 1.0f - gloss;
    } else {
        if (!mat_color(m, AI_MATKEY_BASE_COLOR, &base))
            mat_color(m, AI_MATKEY_COLOR_DIFFUSE, &base);
        metallic = mat_float(m, AI_MATKEY_METALLIC_FACTOR, 0.0f, NULL);
        roughness = mat_float(m, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f, &has_rough);
        float ns = mat_float(m, AI_MATKEY_SHININESS, 0.0f, &has_shin);
        if (!has_rough && has_shin && ns >= 0.0f)
            roughness = sqrtf(sqrtf(2.0f / (ns + 2.0f)));
    }
    if (isnan(base.x) || isnan(base.y) || isnan(base.z) || isnan(metallic) || isnan(roughness)) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%s: material '%s': base colour, metallic or roughness is NaN", im->path,
                 name);
        return -1;
    }
    vec3 emission = v3s(0.0f);
    mat_color(m, AI_MATKEY_COLOR_EMISSIVE, &emission);
    if (v3_max_component(emission) > 0.0f)
        emission = v3_scale(emission, emissive_strength(im, m, name));
    if (!v3_is_finite(emission) || emission.x < 0.0f || emission.y < 0.0f || emission.z < 0.0f) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%s: material '%s': emission (%g %g %g) is NaN, infinite or negative",
                 im->path, name, (double)emission.x, (double)emission.y, (double)emission.z);
        return -1;
    }
    *out = (struct material){.base_color = v3(clamp01(base.x), clamp01(base.y), clamp01(base.z)),
                             .metallic = clamp01(metallic),
                             .roughness = clamp01(roughness),
                             .emission = emission};
    /* glTF 2.0 texture maps: base colour and emissive are sRGB-encoded, metallic-roughness linear
     * (G roughness, B metallic; assimp 5.2 files it as UNKNOWN, later versions as METALNESS) */
    static const enum aiTextureType base_types[] = {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE};
    static const enum aiTextureType mr_types[] = {aiTextureType_UNKNOWN, aiTextureType_METALNESS};
    static const enum aiTextureType emissive_types[] = {aiTextureType_EMISSIVE};
    static const enum aiTextureType normal_types[] = {aiTextureType_NORMALS};
    out->base_color_map = import_texture_map(im->b, im->ai, m, im->path, base_types, 2, 1, im->msg);
    if (out->base_color_map < 0)
        return -1;
    if (!spec_gloss && is_gltf_path(im->path)) { /* elsewhere UNKNOWN is a catch-all and METALNESS one channel */
        out->metal_rough_map = import_texture_map(im->b, im->ai, m, im->path, mr_types, 2, 0, im->msg);
        if (out->metal_rough_map < 0)
            return -1;
    }
    if (v3_max_component(emission) > 0.0f) {
        out->emission_map =
            import_texture_map(im->b, im->ai, m, im->path, emissive_types, 1, 1, im->msg);
        if (out->emission_map < 0)
            return -1;
    }
    if (import_alpha(im, m, name, out) != 0)
        return -1;
    /* texCoord, sampler wrap modes and KHR_texture_transform, by material name from the JSON */
    char inner[RESTIR_MSG_LEN];
    if (*name && gltf_json(im) && import_gltf_lookups(im->gltf, name, out, inner) != 0) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%.200s: %.300s", im->path, inner);
        return -1;
    }
    /* glTF normalTexture (linear) and its scale (assimp files it as the texture's scale key) */
    out->normal_map = import_texture_map(im->b, im->ai, m, im->path, normal_types, 1, 0, im->msg);
    if (out->normal_map < 0)
        return -1;
    ai_real scale = 1;
    unsigned max = 1;
    out->normal_scale = 1.0f;
    if (aiGetMaterialFloatArray(m, AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), &scale, &max) ==
            aiReturn_SUCCESS &&
        max == 1) {
        if (!isfinite(scale) || fabs(scale) > 100.0) {
            snprintf(im->msg, RESTIR_MSG_LEN, "%s: material '%s': normalTexture.scale %g is not in [-100, 100]",
                     im->path, name, (double)scale);
            return -1;
        }
        out->normal_scale = (float)scale;
    }
    return 0;
}

/* Builder material for a triangle of a mesh using file material idx (added on first use, so
 * materials no triangle uses never reach the scene). */
static int triangle_material(struct importer *im, const struct aiMesh *mesh, unsigned mesh_index, int *id)
{
    if (im->material >= 0) {
        *id = im->material;
        return 0;
    }
    unsigned idx = mesh->mMaterialIndex;
    if (idx >= im->ai->mNumMaterials || !im->ai->mMaterials[idx]) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%s: mesh %u uses material %u, the file has %u", im->path, mesh_index,
                 idx, im->ai->mNumMaterials);
        return -1;
    }
    if (im->override_material[idx] >= 0) {
        *id = im->override_material[idx];
        return 0;
    }
    if (im->builder_material[idx] < 0) {
        struct material mt;
        if (make_material(im, idx, &mt) != 0)
            return -1;
        im->builder_material[idx] = scene_add_material(im->b, mt);
    }
    *id = im->builder_material[idx];
    return 0;
}

/* Zero-area triangles (real assets have a few) are skipped: scene_builder_end would accept them
 * (derive_triangle_data gives them area 0 and a made-up normal, they never emit, Embree ignores
 * them) but they add nothing. Also skipped: triangles so thin that the normal computed the way
 * scene.c computes it is not of unit length (underflow). Returns 1 to skip, 0 to keep, -1 when
 * the area overflows float (coordinates near FLT_MAX), which no normal survives. */
static int triangle_degenerate(vec3 a, vec3 c, vec3 d)
{
    vec3 n = v3_cross(v3_sub(c, a), v3_sub(d, a));
    float len = v3_length(n);
    if (isnan(len) || isinf(len))
        return -1;
    if (!(len > 0.0f))
        return 1;
    return fabsf(v3_length(v3_scale(n, 1.0f / len)) - 1.0f) > 1e-3f;
}

/* Appends the triangles of mesh mesh_index placed by transform t. *object is the node's object
 * id, made on its first triangle. */
static int add_mesh(struct importer *im, unsigned mesh_index, const mat4d *t, int *object)
{
    const struct aiMesh *mesh = im->ai->mMeshes[mesh_index];
    if (!mesh)
        return 0;
    char mname[256];
    ai_string_copy(mname, sizeof mname, &mesh->mName);
    if (mesh->mNumFaces > 0 && (!mesh->mFaces || !mesh->mVertices)) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%s: mesh %u ('%s') has faces but no vertex or face data", im->path,
                 mesh_index, mname);
        return -1;
    }
    if (mesh->mNumVertices > im->cap_verts) {
        free(im->verts);
        free(im->normals);
        free(im->tangents);
        im->cap_verts = mesh->mNumVertices;
        im->verts = xmalloc(sizeof(vec3) * im->cap_verts);
        im->normals = xmalloc(sizeof(vec3) * im->cap_verts);
        im->tangents = xmalloc(4 * sizeof(float) * im->cap_verts);
    }
    for (unsigned v = 0; v < mesh->mNumVertices; v++) {
        const struct aiVector3D *p = &mesh->mVertices[v];
        im->verts[v] = mat4d_point(t, p->x, p->y, p->z);
        if (mesh->mNormals) /* glTF NORMAL, OBJ vn, PLY nx ny nz; non-finite ones shade flat */
            im->normals[v] = mat4d_normal(t, mesh->mNormals[v].x, mesh->mNormals[v].y, mesh->mNormals[v].z);
        if (mesh->mNormals && mesh->mTangents && mesh->mBitangents) { /* glTF TANGENT: xyz, w handedness */
            const struct aiVector3D *tv = &mesh->mTangents[v], *bv = &mesh->mBitangents[v], *nv = &mesh->mNormals[v];
            vec3 tn = v3(tv->x, tv->y, tv->z), bn = v3(bv->x, bv->y, bv->z), nn = v3(nv->x, nv->y, nv->z);
            vec3 tw = mat4d_dir(t, tn.x, tn.y, tn.z); /* a tangent moves with the surface */
            float w = v3_dot(v3_cross(nn, tn), bn) < 0.0f ? -1.0f : 1.0f;
            im->tangents[4 * v] = tw.x;
            im->tangents[4 * v + 1] = tw.y;
            im->tangents[4 * v + 2] = tw.z;
            im->tangents[4 * v + 3] = w * (mat4d_det3(t) < 0.0 ? -1.0f : 1.0f); /* a mirror flips the frame */
        }
    }
    const int flip = mat4d_det3(t) < 0.0; /* a mirror: swap two corners so fronts stay fronts */
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        const struct aiFace *face = &mesh->mFaces[f];
        if (face->mNumIndices != 3 || !face->mIndices) {
            im->not_triangles++; /* points and lines (SortByPType keeps them apart; Triangulate left no polygons) */
            continue;
        }
        vec3 p[3];
        for (int k = 0; k < 3; k++) {
            unsigned i = face->mIndices[k];
            if (i >= mesh->mNumVertices) {
                snprintf(im->msg, RESTIR_MSG_LEN, "%s: mesh %u ('%s'): face %u uses vertex %u of %u", im->path,
                         mesh_index, mname, f, i, mesh->mNumVertices);
                return -1;
            }
            p[k] = im->verts[i];
            if (!v3_is_finite(p[k])) {
                snprintf(im->msg, RESTIR_MSG_LEN,
                         "%s: mesh %u ('%s'): vertex %u is not finite after the transform (%g %g %g)", im->path,
                         mesh_index, mname, i, (double)p[k].x, (double)p[k].y, (double)p[k].z);
                return -1;
            }
        }
        if (flip) {
            vec3 tmp = p[1];
            p[1] = p[2];
            p[2] = tmp;
        }
        int dg = triangle_degenerate(p[0], p[1], p[2]);
        if (dg < 0) {
            snprintf(im->msg, RESTIR_MSG_LEN, "%s: mesh %u ('%s'): face %u is too large (its area overflows float)",
                     im->path, mesh_index, mname, f);
            return -1;
        }
        if (dg > 0) {
            im->degenerate++;
            continue;
        }
        if (im->b->s->num_tris >= IMPORT_MAX_TRIS) {
            snprintf(im->msg, RESTIR_MSG_LEN, "%s: more than %d triangles in the scene", im->path, IMPORT_MAX_TRIS);
            return -1;
        }
        int mat;
        if (triangle_material(im, mesh, mesh_index, &mat) != 0)
            return -1;
        if (*object < 0)
            *object = im->object >= 0 ? im->object : scene_new_object(im->b);
        scene_add_triangle(im->b, p[0], p[1], p[2], mat, *object);
        if (mesh->mTextureCoords[0]) {
            float uv[6];
            for (int k = 0; k < 3; k++) {
                /* the corner that went to slot k (slots 1 and 2 swap under a mirror) */
                unsigned i = face->mIndices[flip && k ? 3 - k : k];
                const struct aiVector3D *c = &mesh->mTextureCoords[0][i];
                im->bad_uvs += !isfinite(c->x) || !isfinite(c->y);
                uv[2 * k] = isfinite(c->x) ? (float)c->x : 0.0f;
                uv[2 * k + 1] = isfinite(c->y) ? (float)c->y : 0.0f;
            }
            scene_set_uvs(im->b, im->b->s->num_tris - 1, uv);
        }
        if (mesh->mTextureCoords[1]) { /* glTF TEXCOORD_1, for maps whose texCoord is 1 */
            float uv[6];
            for (int k = 0; k < 3; k++) {
                const struct aiVector3D *c = &mesh->mTextureCoords[1][face->mIndices[flip && k ? 3 - k : k]];
                im->bad_uvs += !isfinite(c->x) || !isfinite(c->y);
                uv[2 * k] = isfinite(c->x) ? (float)c->x : 0.0f;
                uv[2 * k + 1] = isfinite(c->y) ? (float)c->y : 0.0f;
            }
            scene_set_uv_set(im->b, im->b->s->num_tris - 1, 1, uv);
        }
        if (mesh->mNormals) {
            vec3 n[3];
            for (int k = 0; k < 3; k++)
                n[k] = im->normals[face->mIndices[flip && k ? 3 - k : k]];
            scene_set_normals(im->b, im->b->s->num_tris - 1, n);
        }
        if (mesh->mNormals && mesh->mTangents && mesh->mBitangents) {
            float tg[12];
            for (int k = 0; k < 3; k++)
                memcpy(&tg[4 * k], &im->tangents[4 * face->mIndices[flip && k ? 3 - k : k]], 4 * sizeof(float));
            scene_set_tangents(im->b, im->b->s->num_tris - 1, tg);
        }
        im->added++;
    }
    return 0;
}

/* Depth-first over the node tree, parent transform first (p' = xform * root * ... * node * p).
 * One object per node that holds meshes: assimp splits a glTF mesh into one aiMesh per primitive
 * (per material), and an OBJ group likewise, and those are parts of one object; a mesh placed by
 * two nodes is two objects. */
static int walk_nodes(struct importer *im, const struct aiNode *node, const mat4d *parent, int depth)
{
    if (depth > IMPORT_MAX_NODE_DEPTH) {
        snprintf(im->msg, RESTIR_MSG_LEN, "%s: node hierarchy deeper than %d levels", im->path,
                 IMPORT_MAX_NODE_DEPTH);
        return -1;
    }
    mat4d local = mat4d_from_ai(&node->mTransformation);
    mat4d t = mat4d_mul(parent, &local);
    int object = -1;
    for (unsigned k = 0; k < node->mNumMeshes; k++) {
        unsigned mi = node->mMeshes ? node->mMeshes[k] : im->ai->mNumMeshes;
        if (mi >= im->ai->mNumMeshes) {
            snprintf(im->msg, RESTIR_MSG_LEN, "%s: a node uses mesh %u, the file has %u", im->path, mi,
                     im->ai->mNumMeshes);
            return -1;
        }
        if (add_mesh(im, mi, &t, &object) != 0)
            return -1;
    }
    for (unsigned c = 0; c < node->mNumChildren; c++)
        if (node->mChildren && node->mChildren[c] && walk_nodes(im, node->mChildren[c], &t, depth + 1) != 0)
            return -1;
    return 0;
}

/* Maps every override to the file materials of its name; a name no file material has is an
 * error (a typo would otherwise silently keep the file's material). */
static int resolve_overrides(struct importer *im, const struct scene_material_override *ov, int n)
{
    const int nm = (int)im->ai->mNumMaterials;
    for (int i = 0; i < n; i++) {
        const char *want = ov[i].file_name ? ov[i].file_name : "";
        if (ov[i].material < 0 || ov[i].material >= im->b->s->num_materials) {
            snprintf(im->msg, RESTIR_MSG_LEN, "%s: material override '%s': material %d does not exist", im->path,
                     want, ov[i].material);
            return -1;
        }
        int found = 0;
        for (int j = 0; j < nm; j++) {
            char name[MAXLEN];
            if (!im->ai->mMaterials[j])
                continue;
            material_name(im->ai->mMaterials[j], name, sizeof name);
            if (strcmp(name, want) == 0) {
                if (im->override_material[j] < 0)
                    im->override_material[j] = ov[i].material;
                found = 1;
            }
        }
        if (!found) {
            snprintf(im->msg, RESTIR_MSG_LEN, "%s: material override '%s' matches no material of the file",
                     im->path, want);
            return -1;
        }
    }
    return 0;
}

/* What the import left out or replaced, in one line: assimp's warnings and our own counts, handed
 * to scene_load_partial (said on stderr and kept with the scene, or the file refused). */
static int report_partial(struct importer *im)
{
    struct import_notes *n = &im->notes;
    const long declared = is_gltf_path(im->path) && gltf_json(im) ? import_gltf_declared_triangles(im->gltf) : -1;
    const long reached = im->added + im->degenerate; /* the triangles assimp handed over */
    if (declared > reached)
        import_notes_add(n, 1, "%ld of %ld triangles dropped by assimp", declared - reached, declared);
    if (im->degenerate)
        import_notes_add(n, 0, "%ld of %ld triangles skipped (zero area or too thin for a normal)", im->degenerate,
                         im->degenerate + im->added);
    if (im->not_triangles)
        import_notes_add(n, 1, "%ld point and line primitives skipped", im->not_triangles);
    if (im->bad_uvs)
        import_notes_add(n, 1, "%ld texture coordinates not finite, set to 0", im->bad_uvs);
    return n->count ? scene_load_partial(im->b, im->path, n->text, n->lossy > 0, im->msg) : 0;
}

/* scene_import_mesh, and for scene_import_file also the aiScene itself (*keep, on success only;
 * the caller releases it) for its camera. */
static int import_mesh(struct scene_builder *b, const char *path, const float *xform, int material,
                       const struct scene_material_override *overrides, int num_overrides, int object, char *msg,
                       const struct aiScene **keep)
{
    if (material >= b->s->num_materials) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: material %d does not exist", path, material);
        return -1;
    }
    if (import_precheck_counts(path, msg) != 0)
        return -1;
    /* Triangulate: polygons to triangles in their own winding. SortByPType: points and lines in
     * meshes of their own. ValidateDataStructure: assimp's own consistency checks (indices in
     * range, node tree well formed) before we read anything. Nothing that merges or reorders
     * vertices (JoinIdenticalVertices, the optimizers): we keep the file's order. */
    const unsigned flags = aiProcess_Triangulate | aiProcess_ValidateDataStructure | aiProcess_SortByPType;
    if (import_guard_probe(path, flags, msg) != 0)
        return -1;
    struct importer im = {.b = b, .path = path, .material = material, .object = object, .msg = msg};
    import_notes_listen(&im.notes);
    const struct aiScene *ai = aiImportFile(path, flags);
    import_notes_stop();
    im.ai = ai;
    if (!ai) {
        const char *e = aiGetErrorString();
        snprintf(msg, RESTIR_MSG_LEN, "%s: %s", path, e && *e ? e : "assimp could not read the file");
        return -1;
    }
    unsigned nm = ai->mNumMaterials;
    im.builder_material = xmalloc(sizeof(int) * (nm ? nm : 1));
    im.override_material = xmalloc(sizeof(int) * (nm ? nm : 1));
    for (unsigned i = 0; i < nm; i++)
        im.builder_material[i] = im.override_material[i] = -1;
    int rc = 0;
    if (nm > 0 && !ai->mMaterials) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: the material table is missing", path);
        rc = -1;
    }
    if (rc == 0)
        rc = resolve_overrides(&im, overrides, num_overrides);
    if (rc == 0 && ai->mRootNode && ai->mMeshes) {
        mat4d top = xform ? mat4d_from_floats(xform) : mat4d_identity();
        rc = walk_nodes(&im, ai->mRootNode, &top, 0);
    }
    if (rc == 0 && im.added == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: no triangles", path);
        rc = -1;
    }
    if (rc == 0)
        rc = report_partial(&im);
    free(im.builder_material);
    free(im.override_material);
    free(im.verts);
    free(im.normals);
    free(im.tangents);
    cJSON_Delete(im.gltf);
    if (rc == 0 && keep)
        *keep = ai;
    else
        aiReleaseImport(ai);
    return rc == 0 ? im.added : -1;
}

int scene_import_mesh(struct scene_builder *b, const char *path, const float *xform, int material,
                      const struct scene_material_override *overrides, int num_overrides, int object, char *msg)
{
    return import_mesh(b, path, xform, material, overrides, num_overrides, object, msg, NULL);
}

/* ---- a file as a whole scene --------------------------------------------------------------- */

static int has_emissive_triangle(const struct scene *s)
{
    for (int t = 0; t < s->num_tris; t++)
        if (v3_max_component(s->materials[s->tri_material[t]].emission) > 0.0f)
            return 1;
    return 0;
}

int scene_import_file(const char *path, struct scene *s, char *msg)
{
    return scene_import_file_with(path, NULL, s, msg);
}

int scene_import_file_with(const char *path, const struct scene_load_desc *d, struct scene *s, char *msg)
{
    char name[sizeof(s->name)];
    scene_file_stem(path, name, sizeof name);
    struct scene_builder b;
    scene_builder_begin_with(&b, s, name, d);
    const struct aiScene *ai = NULL;
    if (import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg, &ai) < 0) {
        scene_destroy(s);
        return -1;
    }
    int rc = 0;
    const int unlit = !has_emissive_triangle(s);
    import_cameras(ai, path, s);
    aiReleaseImport(ai);
    if (rc == 0) {
        char inner[RESTIR_MSG_LEN];
        if (scene_builder_end(&b, inner) != 0) {
            /* in two steps: the path first, then as much of the builder's message as fits */
            snprintf(msg, RESTIR_MSG_LEN, "%s: ", path);
            size_t used = strlen(msg);
            snprintf(msg + used, RESTIR_MSG_LEN - used, "%s", inner);
            rc = -1;
        }
    }
    if (rc == 0 && unlit) { /* as glTF viewers do: a sky, said on stderr (--env replaces or removes it) */
        struct environment *sky = xcalloc(1, sizeof *sky);
        environment_default_sky(sky);
        rc = scene_set_environment(s, sky, msg);
        if (rc == 0)
            fprintf(stderr, "restir: %s has no emissive material: lit by the default sky (--env FILE to choose "
                            "another, --env none to refuse the file)\n",
                    path);
    }
    if (rc != 0)
        scene_destroy(s);
    return rc;
}
