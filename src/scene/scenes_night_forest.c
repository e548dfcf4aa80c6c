/* scenes_night_forest.c: the built-in scene `night-forest`: the forest's trees at night, lit only
 * by strings of small emissive lamps (fairy lights) wound around trunks, branches and crowns and
 * hung between neighbouring trees: over a hundred thousand emitters, most of them far from any
 * point they light and a few close by. Must never read files. */
#include "scene/scenes_night_forest.h"

#include <math.h>

#include "scene/builtin_shapes.h"
#include "scene/scenes_forest.h"

/* The lamps' palette: COLORS colours (the first WARM are the warm ones; the rest only appear on
 * the multicoloured strings) at LEVELS radiance levels from LAMP_RADIANCE to ten times that. */
enum { COLORS = 8, WARM = 5, LEVELS = 6, POLYLINE_MAX = 1024 };
#define LAMP_RADIANCE 12.0f
/* A lamp is a regular tetrahedron of this circumradius (an edge of 2.4 cm), its four faces
 * emitting outward, so that it shines in every direction. */
#define LAMP_RADIUS 0.015f
/* Lamps keep this far from the wood they are wound around (surface to centre). */
#define LAMP_CLEARANCE 0.035f

/* Linear RGB hues (add_materials scales each to unit luminance): amber, warm white, gold,
 * red-orange, rose, then green, blue and red for the multicoloured strings. */
static const float palette[COLORS][3] = {{1.0f, 0.45f, 0.12f}, {1.0f, 0.72f, 0.42f}, {1.0f, 0.6f, 0.2f},
                                         {1.0f, 0.3f, 0.08f},  {1.0f, 0.42f, 0.36f}, {0.3f, 1.0f, 0.35f},
                                         {0.2f, 0.35f, 1.0f},  {1.0f, 0.12f, 0.1f}};
static const int festive[4] = {7, 5, 2, 6}; /* the colour order of a multicoloured string */

struct lamps {
    struct scene_builder *b;
    pcg32 r;
    int mat[COLORS][LEVELS];
    int obj;
    vec3 pts[POLYLINE_MAX]; /* the string being laid, as a polyline */
    int num_pts;
};

/* How one string looks: its colour (or -1: cycling through `festive`), its radiance level and its
 * lamps' spacing along the wire. */
struct string_style {
    int color, level;
    float spacing;
};

static void add_materials(struct lamps *L)
{
    for (int c = 0; c < COLORS; c++) {
        const float *p = palette[c];
        const float lum = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        for (int k = 0; k < LEVELS; k++) {
            const float e = LAMP_RADIANCE * powf(10.0f, (float)k / (float)(LEVELS - 1)) / lum;
            L->mat[c][k] = scene_add_material(L->b, builtin_emitter(v3(e * p[0], e * p[1], e * p[2])));
        }
    }
}

/* One lamp at c, turned at random: the tetrahedron's faces wound counter-clockwise seen from
 * outside (emitters are one-sided). */
static void add_lamp(struct lamps *L, vec3 c, int mat)
{
    const frame f = frame_from_normal(builtin_random_unit(&L->r));
    const float s = LAMP_RADIUS / sqrtf(3.0f);
    const float corner[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    vec3 p[4];
    for (int i = 0; i < 4; i++)
        p[i] = v3_add(c, v3_add(v3_add(v3_scale(f.t, s * corner[i][0]), v3_scale(f.b, s * corner[i][1])),
                                v3_scale(f.n, s * corner[i][2])));
    for (int i = 0; i < 4; i++) {
        vec3 q[3];
        for (int j = 0, n = 0; j < 4; j++)
            if (j != i)
                q[n++] = p[j];
        /* The face opposite corner i points away from it. */
        if (v3_dot(v3_cross(v3_sub(q[1], q[0]), v3_sub(q[2], q[0])), v3_sub(q[0], p[i])) < 0.0f) {
            vec3 t = q[1];
            q[1] = q[2];
            q[2] = t;
        }
        scene_add_triangle(L->b, q[0], q[1], q[2], mat, L->obj);
    }
}

/* Lays lamps along the polyline in L->pts, st.spacing apart from a random start, each at the
 * string's level or (one in four) a level brighter or dimmer. */
static void lay_string(struct lamps *L, struct string_style st)
{
    float at = st.spacing * pcg32_float(&L->r); /* the next lamp's distance along the current segment */
    int lamp = 0;
    for (int i = 0; i + 1 < L->num_pts; i++) {
        const vec3 a = L->pts[i], d = v3_sub(L->pts[i + 1], a);
        const float len = v3_length(d);
        for (; at < len; at += st.spacing, lamp++) {
            int level = st.level;
            if (pcg32_float(&L->r) < 0.25f)
                level += pcg32_float(&L->r) < 0.5f ? -1 : 1;
            level = level < 0 ? 0 : level >= LEVELS ? LEVELS - 1 : level;
            const int color = st.color >= 0 ? st.color : festive[lamp % 4];
            add_lamp(L, v3_madd(a, d, at / len), L->mat[color][level]);
        }
        at -= len;
    }
}

static struct string_style warm_style(struct lamps *L)
{
    return (struct string_style){.color = (int)(pcg32_next(&L->r) % WARM),
                                 .level = (int)(pcg32_next(&L->r) % LEVELS),
                                 .spacing = builtin_rnd(&L->r, 0.08f, 0.12f)};
}

/* The trunk's radius at height y. */
static float trunk_radius(const struct forest_tree *t, float y) { return t->r0 + (t->r1 - t->r0) * y / t->height; }

/* A helix up the trunk from knee height to about 4 m, 0.15 to 0.3 m a turn. */
static void wind_trunk(struct lamps *L, const struct forest_tree *t)
{
    const float y0 = builtin_rnd(&L->r, 0.3f, 0.8f), y1 = fminf(0.62f * t->height, builtin_rnd(&L->r, 3.4f, 4.6f));
    const float pitch = builtin_rnd(&L->r, 0.15f, 0.3f), a0 = builtin_rnd(&L->r, 0.0f, 2.0f * RESTIR_PI);
    const int n = (int)fminf((float)(POLYLINE_MAX - 1), 24.0f * (y1 - y0) / pitch);
    for (int i = 0; i <= n; i++) {
        const float y = y0 + (y1 - y0) * (float)i / (float)n, a = a0 + 2.0f * RESTIR_PI * (y - y0) / pitch;
        const float rad = trunk_radius(t, y) + LAMP_CLEARANCE;
        L->pts[i] = v3(t->base.x + rad * cosf(a), y, t->base.z + rad * sinf(a));
    }
    L->num_pts = n + 1;
    lay_string(L, warm_style(L));
}

/* A loose helix around branch k from the trunk's surface to near its tip. */
static void wind_branch(struct lamps *L, const struct forest_tree *t, int k)
{
    const vec3 dir = t->branch_dir[k], root = t->branch_root[k];
    const frame f = frame_from_normal(dir);
    const float len = t->branch_len[k], s0 = trunk_radius(t, root.y) + 0.1f, s1 = 0.92f * len;
    const float pitch = builtin_rnd(&L->r, 0.3f, 0.5f), rad = 0.06f + LAMP_CLEARANCE;
    const int n = 64;
    for (int i = 0; i <= n; i++) {
        const float s = s0 + (s1 - s0) * (float)i / (float)n, a = 2.0f * RESTIR_PI * s / pitch;
        const vec3 around = v3_add(v3_scale(f.t, rad * cosf(a)), v3_scale(f.b, rad * sinf(a)));
        L->pts[i] = v3_add(v3_madd(root, dir, s), around);
    }
    L->num_pts = n + 1;
    lay_string(L, warm_style(L));
}

/* A helix wound over the crown, at 0.7 to 0.95 of its semi-axes, from below its equator to near
 * its top: inside the outer leaves, so the crown glows. */
static void wind_crown(struct lamps *L, const struct forest_tree *t)
{
    const float k = builtin_rnd(&L->r, 0.7f, 0.95f), ax = 2.6f * k, ay = 2.0f * k, cy = 0.72f * t->height;
    const float e0 = builtin_rnd(&L->r, -0.9f, -0.6f), e1 = builtin_rnd(&L->r, 0.9f, 1.2f);
    const float turns = builtin_rnd(&L->r, 4.0f, 6.5f), a0 = builtin_rnd(&L->r, 0.0f, 2.0f * RESTIR_PI);
    const int n = (int)(48.0f * turns);
    for (int i = 0; i <= n; i++) {
        const float u = (float)i / (float)n, e = e0 + (e1 - e0) * u, a = a0 + 2.0f * RESTIR_PI * turns * u;
        L->pts[i] = v3(t->base.x + ax * cosf(e) * cosf(a), cy + ay * sinf(e), t->base.z + ax * cosf(e) * sinf(a));
    }
    L->num_pts = n + 1;
    lay_string(L, warm_style(L));
}

/* A garland hung from trunk a to trunk b: fixed at 2.6 to 4.4 m on the trunks' facing sides and
 * sagging as a parabola, never below 2.3 m (the camera walks beneath). One in four is
 * multicoloured. */
static void hang_garland(struct lamps *L, const struct forest_tree *a, const struct forest_tree *b)
{
    vec3 d = v3_sub(b->base, a->base);
    d.y = 0.0f;
    d = v3_normalize(d);
    const float ya = builtin_rnd(&L->r, 2.6f, 4.4f), yb = builtin_rnd(&L->r, 2.6f, 4.4f);
    const vec3 pa = v3_madd(v3(a->base.x, ya, a->base.z), d, trunk_radius(a, ya) + LAMP_CLEARANCE);
    const vec3 pb = v3_madd(v3(b->base.x, yb, b->base.z), d, -(trunk_radius(b, yb) + LAMP_CLEARANCE));
    const float sag = fminf(builtin_rnd(&L->r, 0.3f, 1.2f), fminf(ya, yb) - 2.3f);
    const int n = 64;
    for (int i = 0; i <= n; i++) {
        const float u = (float)i / (float)n;
        L->pts[i] = v3_madd(v3_lerp(pa, pb, u), v3(0, 1, 0), -4.0f * sag * u * (1.0f - u));
    }
    L->num_pts = n + 1;
    struct string_style st = warm_style(L);
    if (pcg32_float(&L->r) < 0.25f)
        st.color = -1;
    lay_string(L, st);
}

void scene_build_night_forest(struct scene_builder *b)
{
    struct forest_tree trees[FOREST_TREES];
    scene_forest_grow(b, trees);
    struct lamps L = {.b = b, .r = pcg32_make(41, 43)};
    add_materials(&L);
    for (int i = 0; i < FOREST_TREES; i++) {
        L.obj = scene_new_object(b);
        wind_trunk(&L, &trees[i]);
        for (int k = 0; k < FOREST_BRANCHES; k++)
            if (pcg32_float(&L.r) < 0.7f)
                wind_branch(&L, &trees[i], k);
        wind_crown(&L, &trees[i]);
    }
    /* Garlands between grid neighbours: across and along the path, and along one diagonal. */
    L.obj = scene_new_object(b);
    const int g = FOREST_GRID;
    for (int z = 0; z < g; z++) {
        for (int x = 0; x < g; x++) {
            const struct forest_tree *t = &trees[z * g + x];
            if (x + 1 < g)
                hang_garland(&L, t, &trees[z * g + x + 1]);
            if (z + 1 < g)
                hang_garland(&L, t, &trees[(z + 1) * g + x]);
            if (x + 1 < g && z + 1 < g)
                hang_garland(&L, t, &trees[(z + 1) * g + x + 1]);
        }
    }
    /* On the path at the forest's edge, looking down it under the garlands; the forest's walk. */
    b->s->camera = (struct camera){v3(0.3f, 1.7f, 10.5f), v3(0.0f, 2.8f, -2.0f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f};
    scene_forest_walk(b->s);
}
