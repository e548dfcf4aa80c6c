/* gbuffer.h: per-pixel primary-hit data (structure of arrays) and the pass that fills it; two
 * of them ping-pong so temporal reuse can validate against the previous frame.
 * Must never depend on reservoirs or methods. */
#ifndef RESTIR_RENDER_GBUFFER_H
#define RESTIR_RENDER_GBUFFER_H

#include "scene/camera.h"
#include "scene/scene.h"
#include "shading/bsdf.h"

#define GBUFFER_NO_MOTION 1e30f
#define GBUFFER_SKY_DISTANCE 1e6f /* how far along its ray a pixel that sees nothing is reprojected from */

/* A surface point as the passes shade it: position, normals, outgoing direction and the BSDF
 * prepared for that direction (its frame and wo-dependent factors). */
struct shading_point {
    vec3 p, n, ng, wo;
    struct bsdf_frame bf;
    int valid;
};

struct gbuffer {
    int width, height;
    vec3 *position;
    vec3 *normal;         /* shading normal, facing the camera */
    vec3 *geo_normal;     /* geometric normal, facing the camera */
    float *depth;         /* distance from the camera */
    vec3 *albedo;         /* base colour */
    float *roughness;
    int *material;
    int *object;
    float *motion;        /* 2 per pixel: backward motion (previous - current image position), pixels;
                             GBUFFER_NO_MOTION when the point was behind the previous camera; for a pixel
                             that sees nothing, its direction's (from GBUFFER_SKY_DISTANCE away) */
    vec3 *emission;       /* radiance emitted toward the camera by the primary hit */
    vec3 *sub_pixel;      /* x, y: image position of the primary ray (pixel units); z unused */
    unsigned char *valid; /* 1 when the primary ray hit geometry */
    struct shading_point *shading; /* the primary hit as a shading point: every DI pass and each
                                      neighbor reads it instead of rebuilding the BSDF frame;
                                      NULL unless gbuffer_init was asked for it */
    float *select_key;    /* GBUFFER_KEY floats per pixel: position xyz, normal xyz, depth, valid;
                             what neighbor selection reads, packed so that each of its random taps
                             touches one cache line instead of four */
};

#define GBUFFER_KEY 8

/* with_shading: also keep each pixel's shading point (what the DI passes read). */
void gbuffer_init(struct gbuffer *g, int width, int height, int with_shading);
void gbuffer_fini(struct gbuffer *g);

/* Traces one (jittered when jitter != 0) primary ray per pixel from view; prev_view gives the
 * motion vectors (NULL: zero motion). Returns the number of rays traced. */
long long gbuffer_pass(struct gbuffer *g, const struct scene *s, const struct camera_view *view,
                       const struct camera_view *prev_view, int jitter, uint64_t seed, int frame);

/* The previous-frame pixel under pixel i's sub-pixel position moved by its backward motion vector,
 * when it is inside the image and valid there (no surface test); -1 otherwise. */
int gbuffer_motion_pixel(const struct gbuffer *g, int i, const struct gbuffer *prev_g);

/* Temporal reprojection with validation (001 Sec. 5): the previous-frame pixel under pixel i's
 * sub-pixel position moved by its backward motion vector, when it shows the same surface
 * (same material, n . n_prev >= normal_min, plane distance <= plane_max * depth). Reads only
 * G-buffers, so it cannot bias GRIS. Returns the pixel index, or -1. */
int gbuffer_history_pixel(const struct gbuffer *g, int i, const struct gbuffer *prev_g, float normal_min,
                          float plane_max);

/* RTXDI's permutation sampling of the temporal neighbour (temporal.permutation): frame `frame`'s tile
 * offset (ox, oy), each in 0..3, one draw of the (seed, frame) stream RNG_PASS_TEMPORAL_PERMUTATION,
 * the same for every pixel. */
void gbuffer_permutation_offset(uint64_t seed, int frame, int *ox, int *oy);
/* gbuffer_history_pixel through the permutation: the reprojected pixel (qx, qy) moved to
 * (((qx + ox) ^ 3) - ox, ((qy + oy) ^ 3) - oy), its mirror inside the 4 x 4 tiles of a grid shifted by
 * (ox, oy) (a bijection of the pixels), kept when inside the image, valid and showing pixel i's
 * surface; otherwise the reprojected pixel under gbuffer_history_pixel's test. Reads only G-buffers
 * and a per-frame offset, so it cannot bias GRIS. Returns the pixel index, or -1. */
int gbuffer_history_pixel_permuted(const struct gbuffer *g, int i, const struct gbuffer *prev_g, float normal_min,
                                   float plane_max, int ox, int oy);

/* A previous pixel that pixel i's square overlaps once moved by its backward motion vector. */
struct gbuffer_history_cell {
    int q;           /* previous pixel, row-major */
    float area;      /* the overlap's area, in pixels (the cells' areas sum to 1 when all pass) */
    float origin[2]; /* q's corner moved by -motion into the current image (a struct pt_domain origin) */
};

/* The 2x2 previous pixels that pixel i's square [x, x+1) x [y, y+1), moved by its backward motion
 * vector, overlaps (Area ReSTIR, Zhang et al. 2024, Sec. 4.3.1), each kept when it is inside the
 * image, valid, shows pixel i's surface (gbuffer_history_pixel's test) and overlaps with area > 0.
 * Writes them to cells[0 .. n) and returns n (0 to 4; 0 for an invalid pixel or one without motion).
 * Reads only G-buffers, so it cannot bias GRIS. */
int gbuffer_history_square(const struct gbuffer *g, int i, const struct gbuffer *prev_g, float normal_min,
                           float plane_max, struct gbuffer_history_cell cells[4]);

/* Pixel i's primary hit as a shading point (built once per frame by gbuffer_pass). */
static inline const struct shading_point *gbuffer_shading(const struct gbuffer *g, int i) { return &g->shading[i]; }

#endif
