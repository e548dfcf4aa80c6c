/* gbuffer.c: allocation of the G-buffer and the primary-visibility pass that fills it, with
 * sub-pixel jitter and backward motion vectors. Must never depend on reservoirs or methods. */
#include "render/gbuffer.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "render/tiles.h"
#include "scene/scene_env.h"
#include "shading/lights.h"

void gbuffer_init(struct gbuffer *g, int width, int height, int with_shading)
{
    size_t n = (size_t)width * (size_t)height;
    memset(g, 0, sizeof(*g));
    g->width = width;
    g->height = height;
    g->position = xcalloc(n, sizeof(vec3));
    g->normal = xcalloc(n, sizeof(vec3));
    g->geo_normal = xcalloc(n, sizeof(vec3));
    g->depth = xcalloc(n, sizeof(float));
    g->albedo = xcalloc(n, sizeof(vec3));
    g->roughness = xcalloc(n, sizeof(float));
    g->material = xcalloc(n, sizeof(int));
    g->object = xcalloc(n, sizeof(int));
    g->motion = xcalloc(2 * n, sizeof(float));
    g->emission = xcalloc(n, sizeof(vec3));
    g->sub_pixel = xcalloc(n, sizeof(vec3));
    g->valid = xcalloc(n, 1);
    g->select_key = xcalloc(n * GBUFFER_KEY, sizeof(float));
    g->shading = with_shading ? xcalloc(n, sizeof(struct shading_point)) : NULL;
}

void gbuffer_fini(struct gbuffer *g)
{
    free(g->position);
    free(g->normal);
    free(g->geo_normal);
    free(g->depth);
    free(g->albedo);
    free(g->roughness);
    free(g->material);
    free(g->object);
    free(g->motion);
    free(g->emission);
    free(g->sub_pixel);
    free(g->valid);
    free(g->select_key);
    free(g->shading);
    memset(g, 0, sizeof(*g));
}

static void shading_point_init(struct shading_point *sp, const struct material *m, vec3 p, vec3 n, vec3 ng,
                               vec3 camera)
{
    sp->valid = 1;
    sp->p = p;
    sp->ng = ng;
    sp->wo = v3_normalize(v3_sub(camera, p));
    sp->n = n = bsdf_shading_normal(n, ng, sp->wo);
    struct bsdf b;
    bsdf_from_material(m, &b);
    bsdf_frame_init(&sp->bf, &b, n, sp->wo);
}

long long gbuffer_pass(struct gbuffer *g, const struct scene *s, const struct camera_view *view,
                       const struct camera_view *prev_view, int jitter, uint64_t seed, int frame)
{
    long long rays = 0;
    const int ntiles = tile_count(g->width, g->height);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        /* The tile's camera rays first, traced together as one coherent stream (they share the
         * camera's origin), then each pixel's G-buffer entry from its hit. */
        int pixel[RESTIR_TILE_W * RESTIR_TILE_H], n = 0;
        struct ray_query q[RESTIR_TILE_W * RESTIR_TILE_H];
        struct surface_hit hits[RESTIR_TILE_W * RESTIR_TILE_H];
        unsigned char hit[RESTIR_TILE_W * RESTIR_TILE_H];
        for (struct tile_pixel px = tile_first_pixel(g->width, g->height, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            pcg32 rng = rng_for(seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_GBUFFER);
            float jx = jitter ? pcg32_float(&rng) : 0.5f, jy = jitter ? pcg32_float(&rng) : 0.5f;
            g->sub_pixel[i] = v3((float)px.x + jx, (float)px.y + jy, 0.0f);
            q[n] = (struct ray_query){view->position, camera_view_ray(view, g->sub_pixel[i].x, g->sub_pixel[i].y),
                                      0.0f, INFINITY};
            pixel[n++] = i;
        }
        scene_intersect_batch(s, q, n, 1, hits, hit);
        rays += n;
        for (int k = 0; k < n; k++) {
            const int i = pixel[k];
            const float px = g->sub_pixel[i].x, py = g->sub_pixel[i].y;
            const vec3 dir = q[k].d;
            const struct surface_hit h = hits[k];
            g->motion[2 * i] = g->motion[2 * i + 1] = prev_view ? GBUFFER_NO_MOTION : 0.0f;
            float *key = &g->select_key[(size_t)i * GBUFFER_KEY];
            if (!hit[k]) {
                /* the sky's motion: where its direction (a point at infinity) was in the previous view,
                 * for the denoisers' antialiasing of the silhouettes against it */
                float qx, qy;
                if (prev_view && camera_view_project(prev_view, v3_madd(view->position, dir, GBUFFER_SKY_DISTANCE),
                                                     &qx, &qy)) {
                    g->motion[2 * i] = qx - px;
                    g->motion[2 * i + 1] = qy - py;
                }
                memset(key, 0, sizeof(float) * GBUFFER_KEY);
                g->valid[i] = 0;
                g->emission[i] = scene_env_radiance(s, dir); /* the sky seen */
                g->material[i] = g->object[i] = -1;
                g->depth[i] = INFINITY;
                if (g->shading)
                    g->shading[i].valid = 0;
                continue;
            }
            struct material textured;
            const struct material *m = scene_material_at(s, h.tri, h.b1, h.b2, &textured);
            g->valid[i] = 1;
            g->position[i] = h.p;
            g->normal[i] = h.ns;
            g->geo_normal[i] = h.ng;
            g->depth[i] = h.t;
            const float packed[GBUFFER_KEY] = {h.p.x, h.p.y, h.p.z, h.ns.x, h.ns.y, h.ns.z, h.t, 1.0f};
            memcpy(key, packed, sizeof(packed));
            g->albedo[i] = m->base_color;
            g->roughness[i] = m->roughness;
            g->material[i] = h.material;
            g->object[i] = h.object;
            g->emission[i] = s->tri_emitter[h.tri] >= 0 ? lights_radiance(s, h.tri, h.b1, h.b2, v3_neg(dir)) : v3s(0.0f);
            if (g->shading)
                shading_point_init(&g->shading[i], m, h.p, h.ns, h.ng, view->position);
            float qx, qy;
            if (prev_view && camera_view_project(prev_view, h.p, &qx, &qy)) {
                g->motion[2 * i] = qx - px;
                g->motion[2 * i + 1] = qy - py;
            }
        }
    }
    return rays;
}

int gbuffer_motion_pixel(const struct gbuffer *g, int i, const struct gbuffer *prev_g)
{
    if (!g->valid[i] || g->motion[2 * i] == GBUFFER_NO_MOTION)
        return -1;
    float qx = g->sub_pixel[i].x + g->motion[2 * i], qy = g->sub_pixel[i].y + g->motion[2 * i + 1];
    if (!(qx >= 0.0f && qy >= 0.0f && qx < (float)prev_g->width && qy < (float)prev_g->height))
        return -1;
    int q = (int)qy * prev_g->width + (int)qx;
    return prev_g->valid[q] ? q : -1;
}

/* Does valid previous pixel q show pixel i's surface (gbuffer_history_pixel's test)? */
static int same_surface(const struct gbuffer *g, int i, const struct gbuffer *prev_g, int q, float normal_min,
                        float plane_max)
{
    if (prev_g->material[q] != g->material[i] || v3_dot(g->normal[i], prev_g->normal[q]) < normal_min)
        return 0;
    float plane = fabsf(v3_dot(prev_g->normal[q], v3_sub(g->position[i], prev_g->position[q])));
    return plane <= plane_max * g->depth[i];
}

int gbuffer_history_pixel(const struct gbuffer *g, int i, const struct gbuffer *prev_g, float normal_min,
                          float plane_max)
{
    int q = gbuffer_motion_pixel(g, i, prev_g);
    return q >= 0 && same_surface(g, i, prev_g, q, normal_min, plane_max) ? q : -1;
}

void gbuffer_permutation_offset(uint64_t seed, int frame, int *ox, int *oy)
{
    pcg32 rng = rng_for(seed, (uint64_t)frame, 0, RNG_PASS_TEMPORAL_PERMUTATION);
    const uint32_t u = pcg32_next(&rng);
    *ox = (int)(u & 3u);
    *oy = (int)((u >> 2) & 3u);
}

int gbuffer_history_pixel_permuted(const struct gbuffer *g, int i, const struct gbuffer *prev_g, float normal_min,
                                   float plane_max, int ox, int oy)
{
    const int q = gbuffer_motion_pixel(g, i, prev_g);
    if (q < 0)
        return -1;
    const int x = (((q % prev_g->width) + ox) ^ 3) - ox, y = (((q / prev_g->width) + oy) ^ 3) - oy;
    if (x >= 0 && y >= 0 && x < prev_g->width && y < prev_g->height) {
        const int r = y * prev_g->width + x;
        if (prev_g->valid[r] && same_surface(g, i, prev_g, r, normal_min, plane_max))
            return r;
    }
    return same_surface(g, i, prev_g, q, normal_min, plane_max) ? q : -1;
}

int gbuffer_history_square(const struct gbuffer *g, int i, const struct gbuffer *prev_g, float normal_min,
                           float plane_max, struct gbuffer_history_cell cells[4])
{
    if (!g->valid[i] || g->motion[2 * i] == GBUFFER_NO_MOTION)
        return 0;
    /* pixel i's square [x, x+1) x [y, y+1) moved by the motion vector */
    const float sx = (float)(i % g->width) + g->motion[2 * i], sy = (float)(i / g->width) + g->motion[2 * i + 1];
    const float fx = floorf(sx), fy = floorf(sy);
    const float wx[2] = {fx + 1.0f - sx, sx - fx}, wy[2] = {fy + 1.0f - sy, sy - fy};
    int n = 0;
    for (int dy = 0; dy < 2; dy++) {
        for (int dx = 0; dx < 2; dx++) {
            const float qx = fx + (float)dx, qy = fy + (float)dy, area = wx[dx] * wy[dy];
            if (!(area > 0.0f && qx >= 0.0f && qy >= 0.0f && qx < (float)prev_g->width && qy < (float)prev_g->height))
                continue;
            const int q = (int)qy * prev_g->width + (int)qx;
            if (!prev_g->valid[q] || !same_surface(g, i, prev_g, q, normal_min, plane_max))
                continue;
            cells[n].q = q;
            cells[n].area = area;
            cells[n].origin[0] = qx - g->motion[2 * i];
            cells[n].origin[1] = qy - g->motion[2 * i + 1];
            n++;
        }
    }
    return n;
}
