/* scene_import_texture.c: the textures an assimp material names, embedded (glTF buffers, data URIs,
 * raw BGRA texels) or files beside the model, resolved and decoded. Must never build geometry. */
#include "scene/scene_import_texture.h"

#include <assimp/texture.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

/* The embedded texture a reference names: "*N", or (assimp 5.1+) the file name of one. */
static const struct aiTexture *embedded(const struct aiScene *ai, const char *ref)
{
    if (!ai->mTextures || ai->mNumTextures == 0)
        return NULL;
    if (ref[0] == '*') {
        char *end = NULL;
        long i = strtol(ref + 1, &end, 10);
        return end != ref + 1 && *end == '\0' && i >= 0 && (unsigned long)i < ai->mNumTextures ? ai->mTextures[i]
                                                                                               : NULL;
    }
    const char *base = strrchr(ref, '/');
    base = base ? base + 1 : ref;
    for (unsigned i = 0; i < ai->mNumTextures; i++) {
        const struct aiTexture *t = ai->mTextures[i];
        if (t && t->mFilename.length > 0 && t->mFilename.length < MAXLEN) {
            const char *tb = strrchr(t->mFilename.data, '/');
            tb = tb ? tb + 1 : t->mFilename.data;
            if (strcmp(tb, base) == 0)
                return t;
        }
    }
    return NULL;
}

/* Decodes reference ref of the model: embedded, or the file at file_path (its resolved key). */
static int decode(const struct aiScene *ai, const char *model_path, const char *ref, const char *file_path, int srgb,
                  struct texture *t, char *msg)
{
    char label[320]; /* long names are cut: the message must fit RESTIR_MSG_LEN */
    snprintf(label, sizeof label, "%.150s (of %.150s)", ref, model_path);
    const struct aiTexture *e = embedded(ai, ref);
    if (e && e->pcData) {
        if (e->mHeight == 0) /* compressed: mWidth bytes of PNG, JPEG, ... */
            return texture_load_memory((const unsigned char *)e->pcData, (int)e->mWidth, srgb, label, t, msg);
        if (e->mWidth == 0 || e->mWidth > 32768 || e->mHeight > 32768 || (long)e->mWidth * e->mHeight > (1L << 26)) {
            snprintf(msg, RESTIR_MSG_LEN, "texture %s: %ux%u is out of range", label, e->mWidth, e->mHeight);
            return -1;
        }
        texture_from_bgra8((const unsigned char *)e->pcData, (int)e->mWidth, (int)e->mHeight, srgb, t);
        return 0;
    }
    if (ref[0] == '*') {
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: the file has no such embedded texture", label);
        return -1;
    }
    return texture_load_file(file_path, srgb, t, msg);
}

/* Where reference ref of the model at model_path lives: "model#ref" for an embedded texture, else
 * the file's path (relative to the model's folder). Returns -1 when it does not fit. */
static int texture_key(const struct aiScene *ai, const char *model_path, const char *ref, char *out, size_t len)
{
    int n;
    const char *slash = strrchr(model_path, '/');
    if (embedded(ai, ref) || ref[0] == '*')
        n = snprintf(out, len, "%s#%s", model_path, ref);
    else if (ref[0] == '/' || !slash)
        n = snprintf(out, len, "%s", ref);
    else
        n = snprintf(out, len, "%.*s/%s", (int)(slash - model_path), model_path, ref);
    return n >= 0 && (size_t)n < len ? 0 : -1;
}

int import_texture_map(struct scene_builder *b, const struct aiScene *ai, const struct aiMaterial *m,
                       const char *model_path, const enum aiTextureType *types, int ntypes, int srgb, char *msg)
{
    struct aiString ref;
    int found = 0;
    for (int k = 0; k < ntypes && !found; k++)
        found = aiGetMaterialTextureCount(m, types[k]) > 0 &&
                aiGetMaterialTexture(m, types[k], 0, &ref, NULL, NULL, NULL, NULL, NULL, NULL) == aiReturn_SUCCESS &&
                ref.length > 0 && ref.length < MAXLEN;
    if (!found)
        return 0;
    char key[4200];
    if (texture_key(ai, model_path, ref.data, key, sizeof key) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: texture path too long", model_path);
        return -1;
    }
    int map = scene_texture_find(b->s, key, srgb);
    if (map > 0)
        return map;
    struct texture t;
    if (decode(ai, model_path, ref.data, key, srgb, &t, msg) != 0)
        return scene_texture_unreadable(b, msg) == 0 ? 0 : -1;
    return scene_add_texture(b, t, key, srgb);
}
