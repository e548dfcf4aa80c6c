/* scene_import_texture.h: the textures of an assimp material as texture maps of the builder
 * (internal to scene_import*.c, the only files that include assimp headers). */
#ifndef RESTIR_SCENE_SCENE_IMPORT_TEXTURE_H
#define RESTIR_SCENE_SCENE_IMPORT_TEXTURE_H

#include <assimp/material.h>
#include <assimp/scene.h>

#include "scene.h"

/* Textures of one file already added to the builder, so materials sharing one load it once. */
struct import_texture_cache {
    int count, cap;
    struct import_texture_entry {
        char key[1024]; /* the file's texture reference ("*0" for an embedded one) */
        int srgb, map;
    } *entries;
};

void import_texture_cache_fini(struct import_texture_cache *c);

/* The map id (>= 1) of the first texture of m among types[0 .. ntypes-1], decoded as sRGB or
 * linear and added to the builder on first use; 0 when m has none. Embedded textures ("*N", or a
 * name matching an embedded texture's) come from ai->mTextures; others are files relative to the
 * model file's folder. Returns -1 with msg naming the model and the texture when it cannot be
 * read. */
int import_texture_map(struct scene_builder *b, const struct aiScene *ai, const struct aiMaterial *m,
                       const char *model_path, const enum aiTextureType *types, int ntypes, int srgb,
                       struct import_texture_cache *cache, char *msg);

#endif
