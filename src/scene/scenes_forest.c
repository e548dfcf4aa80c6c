/* scenes_forest.c: the built-in scene `forest`: dense alpha-tested foliage under a sky
 * with a sun, the kind of scene 000 and 004 claim their largest gains on, made in code with its
 * textures. Must never read files. */
#include "scene/scenes_forest.h"

#include <math.h>
#include <stdlib.h>

#include "scene/builtin_shapes.h"
#include "scene/scene_env.h"

/* Sizes of the generated images and the scene's counts (the numbers docs/SCENES.md states). */
enum { LEAF_SIZE = 128, BARK_W = 64, BARK_H = 128, SKY_W = 512, SKY_H = 256 };
enum { GRID = FOREST_GRID, LEAVES_PER_TREE = 3000, BRANCHES = FOREST_BRANCHES, TRUNK_SEGMENTS = 16, TRUNK_RINGS = 8 };

/* Leaf outline in card UVs (u across, v along the leaf; the stalk at v = 0): a petiole up to
 * v = 0.12, then a blade whose half width swells and tapers to a rounded point. */
static int leaf_inside(float u, float v, float *half_width)
{
    const float x = fabsf(u - 0.5f);
    *half_width = 0.0f;
    if (v < 0.0f || v > 0.98f)
        return 0;
    if (v < 0.12f)
        return x < 0.02f;
    float t = (v - 0.1f) / 0.88f;
    *half_width = 0.46f * powf(sinf(RESTIR_PI * t), 0.75f) * (1.0f - 0.35f * t);
    return x < *half_width;
}

static unsigned char to_byte(float x) { return (unsigned char)lrintf(255.0f * fminf(fmaxf(x, 0.0f), 1.0f)); }

/* The leaf card's base colour (sRGB) with its coverage in alpha (4 x 4 samples per texel), BGRA.
 * Texels outside the leaf keep the leaf's colour so bilinear filtering never darkens the edge. */
static struct texture leaf_texture(void)
{
    unsigned char *px = xmalloc(4 * (size_t)LEAF_SIZE * LEAF_SIZE);
    for (int y = 0; y < LEAF_SIZE; y++) {
        for (int x = 0; x < LEAF_SIZE; x++) {
            int covered = 0;
            for (int sy = 0; sy < 4; sy++)
                for (int sx = 0; sx < 4; sx++) {
                    float hw, u = ((float)x + (sx + 0.5f) / 4.0f) / LEAF_SIZE;
                    float v = 1.0f - ((float)y + (sy + 0.5f) / 4.0f) / LEAF_SIZE; /* row 0 is the top */
                    covered += leaf_inside(u, v, &hw);
                }
            float hw, u = (x + 0.5f) / LEAF_SIZE, v = 1.0f - (y + 0.5f) / LEAF_SIZE, d = fabsf(u - 0.5f);
            leaf_inside(u, v, &hw);
            vec3 c = v3(0.25f, 0.45f, 0.12f);
            float vein = v - 0.7f * d; /* side veins run toward the tip */
            if (d < 0.014f)
                c = v3(0.47f, 0.6f, 0.24f); /* midrib */
            else if (vein - floorf(vein * 9.0f) / 9.0f < 0.01f)
                c = v3(0.36f, 0.54f, 0.18f);
            if (hw > 0.0f) /* darker toward the rim */
                c = v3_scale(c, 1.0f - 0.3f * fminf(d / hw, 1.0f) * fminf(d / hw, 1.0f));
            unsigned char *p = px + 4 * ((size_t)y * LEAF_SIZE + x);
            p[0] = to_byte(c.z);
            p[1] = to_byte(c.y);
            p[2] = to_byte(c.x);
            p[3] = to_byte((float)covered / 16.0f);
        }
    }
    struct texture t;
    texture_from_bgra8(px, LEAF_SIZE, LEAF_SIZE, 1, &t);
    free(px);
    return t;
}

/* Bark height: vertical ridges that wander, periodic over the unit square (integer frequencies),
 * so the map tiles without a seam. */
static float bark_height(float u, float v)
{
    float x = 8.0f * u + 0.35f * sinf(2.0f * RESTIR_PI * 2.0f * v) + 0.12f * sinf(2.0f * RESTIR_PI * (5.0f * v + 3.0f * u));
    return 1.0f - powf(fabsf(sinf(RESTIR_PI * x)), 0.6f);
}

/* The bark's tangent-space normal map (glTF convention: x along +u, y along +v, z out; linear
 * bytes n * 0.5 + 0.5), the normals of the height field by central differences. */
static struct texture bark_normal_texture(void)
{
    unsigned char *px = xmalloc(4 * (size_t)BARK_W * BARK_H);
    const float k = 0.012f; /* height scale: ridges slope up to about 0.4 */
    for (int y = 0; y < BARK_H; y++) {
        for (int x = 0; x < BARK_W; x++) {
            float u = (x + 0.5f) / BARK_W, v = 1.0f - (y + 0.5f) / BARK_H;
            float du = 1.0f / BARK_W, dv = 1.0f / BARK_H;
            float hu = (bark_height(u + du, v) - bark_height(u - du, v)) / (2.0f * du);
            float hv = (bark_height(u, v + dv) - bark_height(u, v - dv)) / (2.0f * dv);
            vec3 n = v3_normalize(v3(-k * hu, -k * hv, 1.0f));
            unsigned char *p = px + 4 * ((size_t)y * BARK_W + x);
            p[0] = to_byte(0.5f * n.z + 0.5f);
            p[1] = to_byte(0.5f * n.y + 0.5f);
            p[2] = to_byte(0.5f * n.x + 0.5f);
            p[3] = 255;
        }
    }
    struct texture t;
    texture_from_bgra8(px, BARK_W, BARK_H, 0, &t);
    free(px);
    return t;
}

/* The sun: its direction, angular radius (larger than the real 0.27 degrees so that the 512 x
 * 256 map resolves it in about 20 texels) and radiance (6.4 W/m^2 on open ground against 1.85
 * from the sky: hard, dappled shadows). */
#define SUN_DIR v3(-0.8f, 0.9f, 0.5f)
#define SUN_RADIUS_DEG 1.5f
#define SUN_RADIANCE v3(5200.0f, 4700.0f, 3900.0f)

/* The equirectangular sky (environment.h's mapping, rotation 0): a blue zenith fading to a pale
 * horizon, a dim ground below it, and the sun. */
static int forest_sky(struct environment *env, char *msg)
{
    float *rgb = xmalloc(3 * sizeof(float) * (size_t)SKY_W * SKY_H);
    const vec3 sun = v3_normalize(SUN_DIR);
    const float cos_sun = cosf(SUN_RADIUS_DEG * RESTIR_PI / 180.0f);
    for (int y = 0; y < SKY_H; y++) {
        float theta = RESTIR_PI * (y + 0.5f) / SKY_H;
        for (int x = 0; x < SKY_W; x++) {
            float phi = 2.0f * RESTIR_PI * (x + 0.5f) / SKY_W;
            vec3 d = v3(sinf(theta) * cosf(phi), cosf(theta), sinf(theta) * sinf(phi));
            vec3 c;
            if (d.y < 0.0f)
                c = v3(0.12f, 0.1f, 0.08f);
            else
                c = v3_lerp(v3(1.1f, 1.12f, 1.15f), v3(0.25f, 0.45f, 0.95f), sqrtf(d.y));
            float cs = v3_dot(d, sun);
            if (cs > cos_sun)
                c = SUN_RADIANCE;
            else if (cs > 0.0f) /* a glow around the sun */
                c = v3_add(c, v3_scale(v3(1.0f, 0.85f, 0.6f), 0.6f * powf(cs, 64.0f)));
            float *p = rgb + 3 * ((size_t)y * SKY_W + x);
            p[0] = c.x;
            p[1] = c.y;
            p[2] = c.z;
        }
    }
    int rc = environment_from_rgb("forest", "the forest's sky", rgb, SKY_W, SKY_H, 1.0f, 0.0f, env, msg);
    free(rgb);
    return rc;
}

/* A tapered open cylinder from base along the unit axis, radii r0 to r1, with smooth shading
 * normals (tilted by the taper) and UVs u = u_tiles around, v = v_per_m along (the bark map's
 * tangents come from these UVs' derivatives). Faces outward. */
static void add_limb(struct scene_builder *b, vec3 base, vec3 axis, float len, float r0, float r1, int seg,
                     int rings, float u_tiles, float v_per_m, int mat, int obj)
{
    const frame f = frame_from_normal(axis);
    const float slope = (r0 - r1) / len;
    for (int j = 0; j < rings; j++) {
        for (int i = 0; i < seg; i++) {
            vec3 p[4], n[4];
            float uv[8];
            for (int k = 0; k < 4; k++) {
                const int ii = i + (k == 1 || k == 2), jj = j + (k >= 2);
                const float phi = 2.0f * RESTIR_PI * (float)ii / (float)seg, h = (float)jj / (float)rings;
                vec3 radial = v3_add(v3_scale(f.t, cosf(phi)), v3_scale(f.b, sinf(phi)));
                p[k] = v3_madd(v3_madd(base, axis, len * h), radial, r0 + (r1 - r0) * h);
                n[k] = v3_madd(radial, axis, slope);
                uv[2 * k] = u_tiles * (float)ii / (float)seg;
                uv[2 * k + 1] = v_per_m * len * h;
            }
            const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (int t = 0; t < 2; t++) {
                const int *c = tris[t];
                scene_add_triangle(b, p[c[0]], p[c[1]], p[c[2]], mat, obj);
                const int tri = b->s->num_tris - 1;
                const float tuv[6] = {uv[2 * c[0]], uv[2 * c[0] + 1], uv[2 * c[1]], uv[2 * c[1] + 1], uv[2 * c[2]],
                                      uv[2 * c[2] + 1]};
                const vec3 tn[3] = {n[c[0]], n[c[1]], n[c[2]]};
                if (!b->over_budget) {
                    scene_set_uvs(b, tri, tuv);
                    scene_set_normals(b, tri, tn);
                }
            }
        }
    }
}

/* One leaf card centred at c, facing n, its length along t (the stalk at -t): two triangles with
 * the leaf texture's UVs, flat shaded. */
static void add_leaf(struct scene_builder *b, vec3 c, vec3 n, vec3 t, float len, float wid, int mat, int obj)
{
    const vec3 s = v3_cross(t, n); /* c0 c1 c2 counter-clockwise about n */
    const vec3 p[4] = {v3_madd(v3_madd(c, t, -0.5f * len), s, -0.5f * wid), v3_madd(v3_madd(c, t, -0.5f * len), s, 0.5f * wid),
                       v3_madd(v3_madd(c, t, 0.5f * len), s, 0.5f * wid), v3_madd(v3_madd(c, t, 0.5f * len), s, -0.5f * wid)};
    const float uv[2][6] = {{0, 0, 1, 0, 1, 1}, {0, 0, 1, 1, 0, 1}};
    scene_add_triangle(b, p[0], p[1], p[2], mat, obj);
    if (!b->over_budget)
        scene_set_uvs(b, b->s->num_tris - 1, uv[0]);
    scene_add_triangle(b, p[0], p[2], p[3], mat, obj);
    if (!b->over_budget)
        scene_set_uvs(b, b->s->num_tris - 1, uv[1]);
}

/* A leaf near point c: a random spot within radius spread, facing mostly up, turned at random
 * about its normal. */
static void scatter_leaf(struct scene_builder *b, pcg32 *r, vec3 c, float spread, const int leaf[3], int obj)
{
    vec3 at = v3_madd(c, builtin_random_unit(r), spread * cbrtf(pcg32_float(r)));
    vec3 n = v3_normalize(v3_add(builtin_random_unit(r), v3(0.0f, 0.7f, 0.0f)));
    frame f = frame_from_normal(n);
    float a = builtin_rnd(r, 0.0f, 2.0f * RESTIR_PI), len = builtin_rnd(r, 0.2f, 0.32f);
    vec3 t = v3_add(v3_scale(f.t, cosf(a)), v3_scale(f.b, sinf(a)));
    add_leaf(b, at, n, t, len, 0.6f * len, leaf[pcg32_next(r) % 3], obj);
}

/* A tree at (x, z): a normal-mapped trunk, BRANCHES branches rising outward, and LEAVES_PER_TREE
 * leaf cards, half around the branches' outer parts and half through an ellipsoidal crown. Its
 * shape goes to t. */
static void add_tree(struct scene_builder *b, pcg32 *r, float x, float z, int bark, const int leaf[3],
                     struct forest_tree *t)
{
    const float h = builtin_rnd(r, 5.5f, 7.5f), r0 = builtin_rnd(r, 0.2f, 0.3f);
    const int wood = scene_new_object(b), crown = scene_new_object(b);
    add_limb(b, v3(x, 0.0f, z), v3(0, 1, 0), h, r0, 0.45f * r0, TRUNK_SEGMENTS, TRUNK_RINGS, 2.0f, 0.8f, bark, wood);
    *t = (struct forest_tree){.base = v3(x, 0.0f, z), .height = h, .r0 = r0, .r1 = 0.45f * r0};
    vec3 *tips = t->branch_root, *dirs = t->branch_dir;
    float *lens = t->branch_len;
    for (int k = 0; k < BRANCHES; k++) {
        float a = builtin_rnd(r, 0.0f, 2.0f * RESTIR_PI), y = h * builtin_rnd(r, 0.3f, 0.8f);
        dirs[k] = v3_normalize(v3(0.8f * cosf(a), builtin_rnd(r, 0.4f, 0.8f), 0.8f * sinf(a)));
        lens[k] = builtin_rnd(r, 1.5f, 2.5f);
        tips[k] = v3(x, y, z);
        add_limb(b, tips[k], dirs[k], lens[k], 0.06f, 0.025f, 6, 3, 1.0f, 2.0f, bark, wood);
    }
    for (int i = 0; i < LEAVES_PER_TREE; i++) {
        if (i % 2 == 0) {
            int k = (i / 2) % BRANCHES;
            scatter_leaf(b, r, v3_madd(tips[k], dirs[k], lens[k] * builtin_rnd(r, 0.35f, 1.0f)), 0.5f, leaf, crown);
        } else {
            vec3 d = builtin_random_unit(r);
            float s = cbrtf(pcg32_float(r));
            scatter_leaf(b, r, v3(x + 2.6f * s * d.x, 0.72f * h + 2.0f * s * d.y, z + 2.6f * s * d.z), 0.2f, leaf,
                         crown);
        }
    }
}

void scene_forest_grow(struct scene_builder *b, struct forest_tree trees[FOREST_TREES])
{
    pcg32 r = pcg32_make(23, 29);
    struct texture leaf_tex = leaf_texture(), bark_tex = bark_normal_texture();
    const int leaf_map = scene_add_texture(b, leaf_tex, "builtin:forest/leaf", 1);
    const int bark_map = scene_add_texture(b, bark_tex, "builtin:forest/bark-normal", 0);
    int ground = scene_add_material(b, builtin_diffuse(0.26f, 0.22f, 0.15f));
    struct material bark = builtin_diffuse(0.32f, 0.24f, 0.17f);
    bark.normal_map = bark_map;
    bark.normal_scale = 1.0f;
    bark.base_alpha = 1.0f;
    int bark_mat = scene_add_material(b, bark);
    /* Three tints of one leaf texture; MASK at 0.5 (glTF's default cutoff). */
    const vec3 tint[3] = {v3(1.0f, 1.0f, 1.0f), v3(0.8f, 0.95f, 0.6f), v3(1.0f, 0.9f, 0.55f)};
    int leaf[3];
    for (int k = 0; k < 3; k++) {
        struct material m = builtin_surface(tint[k], 0.0f, 0.55f);
        m.base_color_map = leaf_map;
        m.alpha_mask = 1;
        m.alpha_cutoff = 0.5f;
        m.base_alpha = 1.0f;
        leaf[k] = scene_add_material(b, m);
    }
    builtin_rect(b, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0), 200.0f, 200.0f, ground, scene_new_object(b));
    /* Trees on a jittered 5 x 5 grid 5 m apart, leaving a path along x = 0 for the camera. */
    for (int gz = 0; gz < GRID; gz++) {
        for (int gx = 0; gx < GRID; gx++) {
            float x = -10.0f + 5.0f * (float)gx + builtin_rnd(&r, -1.2f, 1.2f);
            float z = -12.0f + 5.0f * (float)gz + builtin_rnd(&r, -1.2f, 1.2f);
            if (fabsf(x) < 2.2f) /* keep the middle column off the path */
                x = copysignf(2.2f + fabsf(x), x == 0.0f ? 1.0f : x);
            add_tree(b, &r, x, z, bark_mat, leaf, &trees[gz * GRID + gx]);
        }
    }
}

void scene_build_forest(struct scene_builder *b)
{
    struct forest_tree trees[FOREST_TREES];
    scene_forest_grow(b, trees);
    b->s->camera = (struct camera){v3(0.2f, 1.6f, 9.0f), v3(0.6f, 3.2f, -2.0f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f};
    scene_forest_walk(b->s);
}

void scene_forest_walk(struct scene *s)
{
    /* A walk along the path, looking ahead and up into the crowns: 12 m over 120 frames. */
    struct camera_key keys[3] = {{0, {v3(0.2f, 1.6f, 11.0f), v3(0.0f, 2.6f, 0.0f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f}},
                                 {60, {v3(-0.3f, 1.65f, 5.0f), v3(0.6f, 3.0f, -6.0f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f}},
                                 {120, {v3(0.4f, 1.7f, -1.0f), v3(1.5f, 3.2f, -12.0f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f}}};
    builtin_set_path(s, 3, keys);
}

int scene_light_forest(struct scene *s, char *msg)
{
    struct environment *env = xcalloc(1, sizeof *env);
    if (forest_sky(env, msg) != 0) {
        free(env);
        return -1;
    }
    return scene_set_environment(s, env, msg);
}
