/* texture.h: images that modulate material factors (glTF 2.0 base colour, metallic-roughness, emissive).
 * Must never depend on materials or render code. */
#ifndef RESTIR_SCENE_TEXTURE_H
#define RESTIR_SCENE_TEXTURE_H

#include "core/vec3.h"

/* Decoded once to linear float RGB and looked up bilinearly with repeat wrapping. UVs follow
 * assimp's convention: (0, 0) is the image's bottom-left corner. */
struct texture {
    int width, height;
    float *rgb; /* width * height * 3, linear, row 0 = the image's top row */
    float *alpha; /* width * height coverage in [0, 1] (linear), or NULL: the image has no alpha or
                     every texel is opaque */
};

/* Decodes an image file (PNG, JPEG, TGA, BMP, ... through stb_image). srgb: the file stores
 * sRGB-encoded colour (glTF base colour and emissive textures) and is converted to linear; else
 * values are linear (glTF metallic-roughness). Returns 0, or -1 with msg naming the file. */
int texture_load_file(const char *path, int srgb, struct texture *t, char *msg);
/* The same from an encoded image in memory (textures embedded in .glb files); name labels msg. */
int texture_load_memory(const unsigned char *data, int len, int srgb, const char *name, struct texture *t, char *msg);
/* An uncompressed image (assimp's embedded aiTexel array, BGRA bytes, width * height texels). */
void texture_from_bgra8(const unsigned char *bgra, int width, int height, int srgb, struct texture *t);
void texture_fini(struct texture *t);

/* Bilinear lookup at (u, v), repeat wrapping. */
vec3 texture_sample(const struct texture *t, float u, float v);
/* The alpha channel at (u, v), bilinear as texture_sample; 1 without one. */
float texture_sample_alpha(const struct texture *t, float u, float v);
/* The same with a wrap mode per axis (enum texture_wrap of scene_types.h: 0 repeat, 1 clamp to
 * the edge texels, 2 mirrored repeat), as glTF samplers define them. */
vec3 texture_sample_wrap(const struct texture *t, float u, float v, int wrap_u, int wrap_v);
float texture_sample_alpha_wrap(const struct texture *t, float u, float v, int wrap_u, int wrap_v);

#endif
