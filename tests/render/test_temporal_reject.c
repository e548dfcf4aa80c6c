/* test_temporal_reject.c: restir-di keeps temporal history under a static camera and rejects it after a camera cut
 * and on pixels whose material changed. Must never depend on reuse-pass internals: only frame_stats, G-buffers,
 * confidences. */
#include <string.h>

#include "core/check.h"
#include "methods/renderer.h"
#include "methods/restir_di/di_sample.h"
#include "methods/settings.h"
#include "scene/scenes_builtin.h"
#include "test_util.h"

#define W 80
#define H 60
#define NPIX (W * H)

struct two_frames {
    long long accepted, valid;   /* frame 1's frame_stats */
    unsigned char accepted_px[NPIX]; /* per pixel, from the confidence (spatial reuse off only) */
    int object[NPIX];            /* frame 1's G-buffer */
    int material[NPIX];
    unsigned char valid_px[NPIX];
};

/* Renders frame 0 from cam0 and frame 1 from cam1; between them sets the material of every
 * triangle of object `recolor_object` (-1: none) to `new_material`. With spatial reuse off, a
 * frame-1 reservoir has confidence 1 (its initial candidates) plus the history's when the
 * temporal merge accepted history (frame 0's confidence is 1), so c > 1.5 marks acceptance. */
static void render_two(struct scene *s, const struct render_params *p, const struct camera *cam0,
                       const struct camera *cam1, int recolor_object, int new_material, struct two_frames *out)
{
    int *saved = xmalloc(sizeof(int) * (size_t)s->num_tris);
    memcpy(saved, s->tri_material, sizeof(int) * (size_t)s->num_tris);
    struct renderer r;
    renderer_init(&r, s, method_named("restir-di"), p);
    struct frame_stats fs;
    renderer_render(&r, 0, cam0, &fs);
    EXPECT(fs.temporal_accepted == 0, "frame 0 has no history but accepted %lld pixels", fs.temporal_accepted);
    for (int t = 0; t < s->num_tris; t++)
        if (s->tri_object[t] == recolor_object)
            s->tri_material[t] = new_material;
    renderer_render(&r, 1, cam1, &fs);
    out->accepted = fs.temporal_accepted;
    out->valid = fs.valid_pixels;
    struct renderer_inspect in;
    renderer_inspect(&r, &in);
    const struct gbuffer *g = in.gbuffer;
    const struct di_reservoir *res = in.reservoirs;
    for (int i = 0; i < NPIX; i++) {
        out->object[i] = g->object[i];
        out->material[i] = g->material[i];
        out->valid_px[i] = g->valid[i];
        out->accepted_px[i] = g->valid[i] && res[i].c > 1.5f;
    }
    renderer_fini(&r);
    memcpy(s->tri_material, saved, sizeof(int) * (size_t)s->num_tris);
    free(saved);
}

static int count_accepted(const struct two_frames *f)
{
    int n = 0;
    for (int i = 0; i < NPIX; i++)
        n += f->accepted_px[i];
    return n;
}

/* Object whose triangles reach highest in y (cornell: the tall block, top at y = 1.2) among
 * those whose top lies below y_max; the room and the light reach y = 2. */
static int object_with_top_below(const struct scene *s, float y_max)
{
    int best = -1;
    float best_top = -1e30f;
    for (int o = 0; o < s->num_objects; o++) {
        float top = -1e30f;
        for (int t = 0; t < s->num_tris; t++)
            if (s->tri_object[t] == o)
                for (int k = 0; k < 3; k++)
                    top = fmaxf(top, s->verts[s->indices[3 * t + k]].y);
        if (top < y_max && top > best_top) {
            best_top = top;
            best = o;
        }
    }
    return best;
}

/* Material of the triangles facing -x at x = 1 (cornell: the green right wall). */
static int right_wall_material(const struct scene *s)
{
    for (int t = 0; t < s->num_tris; t++) {
        vec3 a = s->verts[s->indices[3 * t]];
        if (s->tri_normal[t].x < -0.99f && fabsf(a.x - 1.0f) < 1e-4f)
            return s->tri_material[t];
    }
    return -1;
}

int main(void)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_create_builtin("cornell", &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return test_finish();
    }
    struct render_params p;
    render_params_defaults(&p);
    p.width = W;
    p.height = H;
    p.seed = 77;
    const struct camera cam = scene_camera_at(&s, 0, 0.0f);
    static struct two_frames a, b, c, a_nospatial;

    /* (a) Static camera: only sub-pixel jitter differs, so nearly every pixel finds its surface. */
    render_two(&s, &p, &cam, &cam, -1, 0, &a);
    double rate_a = (double)a.accepted / (double)a.valid;
    printf("(a) static camera: %lld of %lld valid pixels accepted history (%.3f)\n", a.accepted, a.valid, rate_a);
    EXPECT(a.valid > NPIX / 2, "only %lld valid pixels", a.valid);
    EXPECT(rate_a > 0.8, "static-camera acceptance %.3f", rate_a);

    /* (b) Cut to a camera behind the back wall, looking at its back: the reprojected points lie
     * on surfaces frame 0 saw from the other side (normals opposite) or behind a block (other
     * plane), so no history may survive. A cut to a view that shares surfaces with frame 0 would
     * legitimately keep history there: reprojection finds the same surface point. */
    struct camera behind = {v3(0.2f, 1.1f, -3.0f), v3(0.0f, 1.0f, 0.0f), v3(0.0f, 1.0f, 0.0f), 40.0f, 0.0f, 0.0f};
    render_two(&s, &p, &cam, &behind, -1, 0, &b);
    double rate_b = b.valid > 0 ? (double)b.accepted / (double)b.valid : 1.0;
    printf("(b) camera cut: %lld of %lld valid pixels accepted history (%.4f)\n", b.accepted, b.valid, rate_b);
    EXPECT(b.valid > NPIX * 9 / 10, "the cut view must see geometry: %lld valid pixels", b.valid);
    EXPECT(rate_b < 0.02, "acceptance after a camera cut %.4f", rate_b);

    /* (c) Static camera, but the tall block turns green between the frames. Spatial reuse is off
     * so each pixel's acceptance is readable from its confidence; the G-buffers (and so every
     * history test but the material one) are the same as in the run without the change because
     * the seed is the same. */
    int block = object_with_top_below(&s, 1.5f);
    int green = right_wall_material(&s);
    EXPECT(block >= 0 && green >= 0, "cornell changed: block object %d, green material %d", block, green);
    if (block < 0 || green < 0) {
        scene_destroy(&s);
        return test_finish();
    }
    struct render_params q = p;
    q.reuse.spatial = 0;
    render_two(&s, &q, &cam, &cam, -1, 0, &a_nospatial);
    render_two(&s, &q, &cam, &cam, block, green, &c);
    EXPECT(count_accepted(&a_nospatial) == a_nospatial.accepted && count_accepted(&c) == c.accepted,
           "per-pixel acceptance (%d, %d) disagrees with frame_stats (%lld, %lld)", count_accepted(&a_nospatial),
           count_accepted(&c), a_nospatial.accepted, c.accepted);
    int block_px = 0, block_px_accepted_before = 0, block_px_accepted = 0, other_differ = 0, wrong_mat = 0;
    for (int i = 0; i < NPIX; i++) {
        if (c.valid_px[i] && c.object[i] == block) {
            block_px++;
            block_px_accepted_before += a_nospatial.accepted_px[i];
            block_px_accepted += c.accepted_px[i];
            wrong_mat += c.material[i] != green;
        } else {
            other_differ += c.accepted_px[i] != a_nospatial.accepted_px[i];
        }
    }
    double frac_block = (double)block_px / (double)c.valid;
    double drop = (double)(a_nospatial.accepted - c.accepted) / (double)c.valid;
    printf("(c) material change: block covers %d pixels (%.3f of valid); acceptance %.3f -> %.3f (drop %.3f); "
           "block pixels accepted before %d, after %d\n",
           block_px, frac_block, (double)a_nospatial.accepted / (double)a_nospatial.valid,
           (double)c.accepted / (double)c.valid, drop, block_px_accepted_before, block_px_accepted);
    EXPECT(wrong_mat == 0, "%d block pixels do not show the new material in frame 1's G-buffer", wrong_mat);
    EXPECT(frac_block > 0.03, "the block covers too few pixels (%d) to see a drop", block_px);
    EXPECT(block_px_accepted == 0, "%d of %d recoloured pixels kept their history", block_px_accepted, block_px);
    EXPECT(other_differ == 0, "%d pixels off the block changed their acceptance", other_differ);
    /* Without the change the block's pixels keep history, so the drop is the block's share. */
    EXPECT(block_px_accepted_before > block_px * 9 / 10, "only %d of %d block pixels accepted history unchanged",
           block_px_accepted_before, block_px);
    EXPECT(a_nospatial.accepted - c.accepted == block_px_accepted_before,
           "acceptance dropped by %lld pixels, the block had %d accepted", a_nospatial.accepted - c.accepted,
           block_px_accepted_before);
    EXPECT(drop > 0.9 * frac_block && drop <= frac_block, "drop %.4f vs block share %.4f", drop, frac_block);

    scene_destroy(&s);
    return test_finish();
}
