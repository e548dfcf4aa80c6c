/* test_gbuffer_history.c: gbuffer_history_square (temporal.subpixel=search) finds the previous
 * pixels that a pixel's square, moved by its backward motion vector, overlaps: their overlap areas
 * (hand-computed here) sum to 1, each origin is the previous pixel's corner moved back by the
 * motion, and a previous pixel is left out when it is outside the image, invalid, shows another
 * surface, or overlaps with zero area (whole-pixel motion). */
#include <math.h>
#include <string.h>

#include "render/gbuffer.h"
#include "test_util.h"

enum { W = 6, H = 5 };

/* A flat, valid G-buffer: every pixel on the plane z = 0 facing +z, material 0, depth 10. */
static void flat(struct gbuffer *g)
{
    gbuffer_init(g, W, H, 0);
    for (int i = 0; i < W * H; i++) {
        g->valid[i] = 1;
        g->position[i] = v3((float)(i % W), (float)(i / W), 0.0f);
        g->normal[i] = v3(0.0f, 0.0f, 1.0f);
        g->depth[i] = 10.0f;
        g->material[i] = 0;
        g->motion[2 * i] = g->motion[2 * i + 1] = 0.0f;
    }
}

static const struct gbuffer_history_cell *find(const struct gbuffer_history_cell *c, int n, int q)
{
    for (int k = 0; k < n; k++)
        if (c[k].q == q)
            return &c[k];
    return NULL;
}

/* Checks cell q's presence, area and origin (q - motion). */
static void expect_cell(const struct gbuffer_history_cell *c, int n, int q, float area, float mx, float my)
{
    const struct gbuffer_history_cell *k = find(c, n, q);
    EXPECT(k != NULL, "previous pixel %d missing", q);
    if (!k)
        return;
    EXPECT(fabsf(k->area - area) < 1e-6f, "pixel %d: area %g, expected %g", q, (double)k->area, (double)area);
    EXPECT(k->origin[0] == (float)(q % W) - mx && k->origin[1] == (float)(q / W) - my,
           "pixel %d: origin (%g, %g)", q, (double)k->origin[0], (double)k->origin[1]);
}

int main(void)
{
    struct gbuffer g, prev;
    flat(&g);
    flat(&prev);
    struct gbuffer_history_cell c[4];
    const float p = 1e-4f; /* plane tolerance: any plane distance fails above it (depth 10) */

    /* Pixel (2, 2) moved by (0.25, -0.5): the square [2.25, 3.25) x [1.5, 2.5) overlaps pixels
     * (2,1), (3,1), (2,2), (3,2) with areas 0.75 * 0.5, 0.25 * 0.5, 0.75 * 0.5, 0.25 * 0.5. */
    const int i = 2 * W + 2;
    g.motion[2 * i] = 0.25f;
    g.motion[2 * i + 1] = -0.5f;
    for (int q = 0; q < W * H; q++)
        prev.position[q] = g.position[i]; /* same plane everywhere */
    int n = gbuffer_history_square(&g, i, &prev, 0.8f, p, c);
    EXPECT(n == 4, "interior pixel: %d cells", n);
    expect_cell(c, n, 1 * W + 2, 0.375f, 0.25f, -0.5f);
    expect_cell(c, n, 1 * W + 3, 0.125f, 0.25f, -0.5f);
    expect_cell(c, n, 2 * W + 2, 0.375f, 0.25f, -0.5f);
    expect_cell(c, n, 2 * W + 3, 0.125f, 0.25f, -0.5f);
    float sum = 0.0f;
    for (int k = 0; k < n; k++)
        sum += c[k].area;
    EXPECT(fabsf(sum - 1.0f) < 1e-6f, "areas sum to %g", (double)sum);

    /* Each test of gbuffer_history_pixel drops its pixel: another material, a turned normal,
     * another plane, an invalid pixel. */
    prev.material[1 * W + 2] = 3;
    prev.normal[1 * W + 3] = v3(1.0f, 0.0f, 0.0f);
    prev.position[2 * W + 2] = v3(0.0f, 0.0f, 1.0f);
    n = gbuffer_history_square(&g, i, &prev, 0.8f, p, c);
    EXPECT(n == 1 && c[0].q == 2 * W + 3, "three rejected cells: %d left", n);
    prev.valid[2 * W + 3] = 0;
    EXPECT(gbuffer_history_square(&g, i, &prev, 0.8f, p, c) == 0, "all four rejected");
    gbuffer_fini(&prev);
    flat(&prev);
    for (int q = 0; q < W * H; q++)
        prev.position[q] = v3(0.0f, 0.0f, 0.0f);

    /* Whole-pixel motion: one cell of area 1 (the zero-area ones are not reported). */
    g.motion[2 * i] = -1.0f;
    g.motion[2 * i + 1] = 2.0f;
    n = gbuffer_history_square(&g, i, &prev, 0.8f, p, c);
    EXPECT(n == 1 && c[0].q == 4 * W + 1 && c[0].area == 1.0f, "whole-pixel motion: %d cells", n);

    /* At the image's corner: only the cells inside it. Pixel (0, 0) moved by (-0.5, -0.5)
     * overlaps (0, 0) alone inside the image, with area 1/4. */
    const int z = 0;
    g.motion[0] = g.motion[1] = -0.5f;
    n = gbuffer_history_square(&g, z, &prev, 0.8f, p, c);
    EXPECT(n == 1 && c[0].q == 0 && fabsf(c[0].area - 0.25f) < 1e-6f, "corner: %d cells", n);

    /* No motion (the point was behind the previous camera) or an invalid pixel: nothing. */
    g.motion[0] = GBUFFER_NO_MOTION;
    EXPECT(gbuffer_history_square(&g, z, &prev, 0.8f, p, c) == 0, "no motion gave cells");
    g.valid[i] = 0;
    EXPECT(gbuffer_history_square(&g, i, &prev, 0.8f, p, c) == 0, "invalid pixel gave cells");
    gbuffer_fini(&g);
    gbuffer_fini(&prev);
    return test_finish();
}
