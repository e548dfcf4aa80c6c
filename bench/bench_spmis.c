/* bench_spmis.c: the evaluation of 004 Sec. 6 on our scenes: standard spatial reuse (3 neighbors in
 * 30 px, defensive pairwise) against stochastic pairwise MIS (N = 3 from one cell of at most 64
 * pixels, N_c = 1, 12-step search), same code otherwise, confidence cap 20, the last frame of a
 * 50-frame camera path: MAPE over all and over disoccluded pixels, per-pass times in the layout of
 * 004 Table 2, the ablations of Fig. 2, 6 and 7, and a crop of pillars' disoccluded region.
 * Prints Markdown for docs/BENCHMARKS.md and writes images to docs/spmis/. Never run by tests. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "core/check.h"
#include "io/png.h"
#include "methods/settings.h"
#include "restir/metrics.h"

#define SPMIS_FRAMES 50
#define IMAGE_DIR "docs/spmis"

struct bench_spmis_cfg {
    int width, height, runs, ref_spp;
    char radii[96]; /* settings appended to every configuration: the pixel radii used */
    char tag[32];   /* image file suffix: resolution and radius mode */
};

struct config_result {
    double ms[PASS_COUNT], ms_total; /* mean over frames 1.. and runs */
    double mape, mape_dis;           /* last frame, mean over runs */
    double dis_fraction;             /* disoccluded share of the valid pixels */
    float *image;                    /* last frame of the first run (caller frees) */
    unsigned char *mask;             /* its disocclusion mask (caller frees) */
};

/* Applies "key=value:key=value..." to p. */
static void apply_sets(struct render_params *p, const char *sets)
{
    char msg[RESTIR_MSG_LEN];
    if (render_params_set_list(p, sets, msg) != 0) {
        fprintf(stderr, "restir_bench: %s\n", msg);
        exit(2);
    }
}

static void run_config(const struct scene *s, const struct method *m, const struct bench_spmis_cfg *c, const char *sets,
                       const float *ref, struct config_result *res)
{
    memset(res, 0, sizeof(*res));
    size_t npix = (size_t)c->width * c->height;
    res->image = xcalloc(3 * npix, sizeof(float));
    res->mask = xcalloc(npix, 1);
    unsigned char *mask = xcalloc(npix, 1);
    double timed = 0.0;
    for (int k = 0; k < c->runs; k++) {
        struct render_params p;
        render_params_defaults(&p);
        p.width = c->width;
        p.height = c->height;
        p.camera_path = 1;
        p.seed = 31 + (uint64_t)k;
        apply_sets(&p, c->radii);
        apply_sets(&p, sets);
        struct renderer r;
        renderer_init(&r, s, m, &p);
        for (int f = 0; f < SPMIS_FRAMES; f++) {
            struct frame_stats st;
            struct camera cam = scene_camera_at(s, 1, (float)f);
            renderer_render(&r, f, &cam, &st);
            if (f == 0)
                continue;
            for (int q = 0; q < PASS_COUNT; q++)
                res->ms[q] += st.ms[q];
            res->ms_total += st.ms_total;
            timed += 1.0;
        }
        long long marked = renderer_disoccluded(&r, DISOCCLUSION_FRAMES, mask);
        long long valid = renderer_valid_pixels(&r);
        struct restir_metrics_error e;
        restir_metrics_compute(r.image, ref, npix, NULL, &e);
        res->mape += e.mape / c->runs;
        if (marked > 0 && restir_metrics_compute(r.image, ref, npix, mask, &e) == 0)
            res->mape_dis += e.mape / c->runs;
        res->dis_fraction += (double)marked / (double)(valid > 0 ? valid : 1) / c->runs;
        if (k == 0) {
            memcpy(res->image, r.image, 3 * npix * sizeof(float));
            memcpy(res->mask, mask, npix);
        }
        renderer_fini(&r);
    }
    for (int q = 0; q < PASS_COUNT; q++)
        res->ms[q] /= timed;
    res->ms_total /= timed;
    free(mask);
}

/* The reference of method m's integrand for the last frame of the camera path. */
static float *last_frame_reference(const struct bench_spmis_cfg *c, const struct method *m, const struct scene *s)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = c->width;
    p.height = c->height;
    return bench_reference(s, m, &p, (float)(SPMIS_FRAMES - 1), 1, c->ref_spp);
}

static void free_result(struct config_result *r)
{
    free(r->image);
    free(r->mask);
}

static double spatial_ms(const struct config_result *r)
{
    return r->ms[PASS_SELECT] + r->ms[PASS_SPATIAL] + r->ms[PASS_CELLS] + r->ms[PASS_CELL_SEARCH] +
           r->ms[PASS_SPMIS_CANONICAL] + r->ms[PASS_SPMIS_REUSE];
}

/* Relative change in percent, or "-" when the base is 0 (no disoccluded pixel). */
static const char *change(double v, double base, char *buf, size_t n)
{
    if (base > 0.0)
        snprintf(buf, n, "%+.1f%%", 100.0 * (v / base - 1.0));
    else
        snprintf(buf, n, "-");
    return buf;
}

static void print_row(const char *label, const struct config_result *r, const struct config_result *base)
{
    char a[32], b[32];
    printf("| %s | %.1f | %.1f | %.4f | %.4f | %s | %s |\n", label, r->ms_total, spatial_ms(r), r->mape, r->mape_dis,
           change(r->mape, base->mape, a, sizeof(a)), change(r->mape_dis, base->mape_dis, b, sizeof(b)));
}

static void table_header(const char *title)
{
    printf("\n%s\n\n| configuration | ms/frame | ms spatial | MAPE | MAPE disoccluded | vs standard | "
           "disoccluded vs standard |\n|---|---|---|---|---|---|---|\n",
           title);
}

/* pillars: the (width / 4) x (height / 3) window holding the most disoccluded pixels, 4x enlarged:
 * standard | spmis | reference | disocclusion mask. */
static void write_crop(const struct bench_spmis_cfg *c, const float *a, const float *b, const float *ref,
                       const unsigned char *mask, const char *name)
{
    const int cw = c->width / 4, ch = c->height / 3, zoom = 4;
    int x0 = 0, y0 = 0, best = -1;
    for (int wy = 0; wy + ch <= c->height; wy += 4)
        for (int wx = 0; wx + cw <= c->width; wx += 4) {
            int n = 0;
            for (int y = wy; y < wy + ch; y++)
                for (int x = wx; x < wx + cw; x++)
                    n += mask[y * c->width + x];
            if (n > best) {
                best = n;
                x0 = wx;
                y0 = wy;
            }
        }
    const int W = 4 * cw * zoom, H = ch * zoom;
    float *out = xcalloc(3 * (size_t)W * H, sizeof(float));
    const float *src[3] = {a, b, ref};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int panel = x / (cw * zoom), sx = x0 + (x % (cw * zoom)) / zoom, sy = y0 + y / zoom;
            size_t i = (size_t)sy * c->width + sx;
            for (int k = 0; k < 3; k++)
                out[3 * ((size_t)y * W + x) + k] = panel < 3 ? src[panel][3 * i + k] : (mask[i] ? 1.0f : 0.0f);
        }
    char path[256], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof(path), "%s/%s", IMAGE_DIR, name);
    if (png_write_srgb(path, out, W, H, 1.0f, msg) != 0)
        fprintf(stderr, "restir_bench: %s\n", msg);
    else
        printf("\n%s: window (%d, %d) %dx%d, %d disoccluded pixels\n", path, x0, y0, cw, ch, best);
    free(out);
}

static void write_image(const char *name, const float *rgb, int w, int h)
{
    char path[256], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof(path), "%s/%s", IMAGE_DIR, name);
    if (png_write_srgb(path, rgb, w, h, 1.0f, msg) != 0)
        fprintf(stderr, "restir_bench: %s\n", msg);
}

static void write_mask(const char *name, const unsigned char *mask, int w, int h)
{
    float *rgb = xcalloc(3 * (size_t)w * h, sizeof(float));
    for (size_t i = 0; i < (size_t)w * h; i++)
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = mask[i] ? 1.0f : 0.0f;
    write_image(name, rgb, w, h);
    free(rgb);
}

/* Standard reuse with 3 neighbors for both methods (004 Sec. 6: M = 3 in a 30 px radius). */
#define STANDARD "spatial.reuse=standard:spatial.neighbors=3"
#define SPMIS "spatial.reuse=spmis"

/* The main comparison of one method on the given scenes, with the per-pass table. */
static void compare_scenes(const struct bench_spmis_cfg *c, const struct method *m, const char *const *scenes, int n)
{
    const char *name = m->name;
    double table[8][PASS_COUNT + 2];
    const char *pass_scene[8];
    for (int sc = 0; sc < n; sc++) {
        struct scene s = bench_load_scene(scenes[sc]);
        float *ref = last_frame_reference(c, m, &s);
        struct config_result std_r, sp_r, eq_r;
        run_config(&s, m, c, STANDARD, ref, &std_r);
        run_config(&s, m, c, SPMIS, ref, &sp_r);
        /* Equal time: the faster of the two gets more reuse, in proportion to its spatial cost. */
        char eq[128];
        const char *eq_label;
        double ratio = spatial_ms(&sp_r) / spatial_ms(&std_r);
        if (ratio > 1.0) {
            int k = (int)lrint(3.0 * ratio);
            snprintf(eq, sizeof(eq), STANDARD ":spatial.neighbors=%d", k < 5 ? (k > 3 ? k : 4) : 5);
            eq_label = "standard, equal time";
        } else {
            int k = (int)lrint(3.0 / ratio);
            snprintf(eq, sizeof(eq), SPMIS ":spmis.candidates=%d", k > 3 ? (k < 64 ? k : 64) : 4);
            eq_label = "spmis, equal time";
        }
        run_config(&s, m, c, eq, ref, &eq_r);
        char title[256];
        snprintf(title, sizeof(title),
                 "### %s on %s, %dx%d, camera path frame %d (%.1f%% of pixels disoccluded), %d runs, %d-spp "
                 "reference",
                 name, scenes[sc], c->width, c->height, SPMIS_FRAMES - 1, 100.0 * sp_r.dis_fraction, c->runs,
                 c->ref_spp);
        table_header(title);
        print_row("standard (3 neighbors, 30 px)", &std_r, &std_r);
        print_row("spmis (N 3, N_c 1, 12-step search)", &sp_r, &std_r);
        char label[192];
        snprintf(label, sizeof(label), "%s (`%s`)", eq_label, strrchr(eq, ':') + 1);
        print_row(label, &eq_r, &std_r);
        char file[128];
        snprintf(file, sizeof(file), "%s_%s_mask_%s.png", name, scenes[sc], c->tag);
        write_mask(file, sp_r.mask, c->width, c->height);
        if (!strcmp(scenes[sc], "pillars")) {
            snprintf(file, sizeof(file), "%s_pillars_crop_%s.png", name, c->tag);
            write_crop(c, std_r.image, sp_r.image, ref, sp_r.mask, file);
        }
        pass_scene[sc] = scenes[sc];
        for (int q = 0; q < PASS_COUNT; q++)
            table[sc][q] = sp_r.ms[q];
        table[sc][PASS_COUNT] = sp_r.ms_total;
        table[sc][PASS_COUNT + 1] = std_r.ms[PASS_SELECT] + std_r.ms[PASS_SPATIAL];
        free_result(&std_r);
        free_result(&sp_r);
        free_result(&eq_r);
        free(ref);
        scene_destroy(&s);
    }
    /* 004 Table 2 layout: rows are passes, then the mean and spread over the scenes. */
    static const struct {
        const char *label;
        int pass;
    } rows[] = {{"Initial Sampling", PASS_INITIAL},
                {"Temporal Reuse", PASS_TEMPORAL},
                {"Ours: Create Reuse Cells (Alg. 1)", PASS_CELLS},
                {"Ours: Cell Search (Alg. 2 line 2)", PASS_CELL_SEARCH},
                {"Ours: Compute m~_c (Alg. 2 lines 6-12)", PASS_SPMIS_CANONICAL},
                {"Ours: Stochastic Neighbor Reuse (lines 13-20)", PASS_SPMIS_REUSE},
                {"Full frame (spmis)", PASS_COUNT},
                {"Standard: selection + spatial reuse", PASS_COUNT + 1}};
    printf("\n### %s per-pass CPU time (ms), layout of 004 Table 2, %dx%d, %d threads, mean of frames 1-%d\n\n|"
           " pass",
           name, c->width, c->height, omp_get_max_threads(), SPMIS_FRAMES - 1);
    for (int sc = 0; sc < n; sc++)
        printf(" | %s", pass_scene[sc]);
    printf(" | mean +- sd |\n|---");
    for (int sc = 0; sc <= n; sc++)
        printf("|---");
    printf("|\n");
    for (size_t q = 0; q < sizeof(rows) / sizeof(rows[0]); q++) {
        double sum = 0.0, sum2 = 0.0;
        printf("| %s", rows[q].label);
        for (int sc = 0; sc < n; sc++) {
            double v = table[sc][rows[q].pass];
            printf(" | %.2f", v);
            sum += v;
            sum2 += v * v;
        }
        double mu = sum / n, sd = n > 1 ? sqrt(fmax(0.0, (sum2 - n * mu * mu) / (n - 1))) : 0.0;
        printf(" | %.2f +- %.2f |\n", mu, sd);
    }
}

/* The ablations of 004 Fig. 2 (confidence adjustment), Fig. 6 (N_c), Fig. 7 (N, N = M), and the
 * search modes, on one scene. */
static void ablations(const struct bench_spmis_cfg *c, const struct method *m, const char *scene)
{
    struct scene s = bench_load_scene(scene);
    float *ref = last_frame_reference(c, m, &s);
    struct config_result base;
    run_config(&s, m, c, STANDARD, ref, &base);
    static const char *const groups[][6] = {
        {"Confidence adjustment N / M (004 Fig. 2)", SPMIS ":spmis.candidates=1",
         SPMIS ":spmis.candidates=1:spmis.confidence_adjust=off", SPMIS ":spmis.candidates=3",
         SPMIS ":spmis.candidates=3:spmis.confidence_adjust=off", SPMIS ":spmis.candidates=8"},
        {"", SPMIS ":spmis.candidates=8:spmis.confidence_adjust=off", NULL, NULL, NULL, NULL},
        {"Canonical draws N_c (004 Fig. 6)", SPMIS ":spmis.canonical_candidates=1",
         SPMIS ":spmis.canonical_candidates=4", SPMIS ":spmis.canonical_candidates=M",
         SPMIS ":spmis.canonical_pick=confidence", NULL},
        {"Neighbor draws N, N = M deterministic over the cell (004 Fig. 7)", SPMIS ":spmis.candidates=1",
         SPMIS ":spmis.candidates=3", SPMIS ":spmis.candidates=8",
         SPMIS ":spmis.candidates=M:spmis.canonical_candidates=M", NULL},
        {"Cell search (004 Sec. 5.1; sparse is BIASED)", SPMIS ":spmis.search=always", SPMIS ":spmis.search=sparse",
         SPMIS ":spmis.search=low-confidence", SPMIS ":spmis.search_steps=0", NULL},
    };
    for (size_t g = 0; g < sizeof(groups) / sizeof(groups[0]); g++) {
        if (groups[g][0][0]) {
            char title[256];
            snprintf(title, sizeof(title), "### Ablation, %s on %s: %s", m->name, scene, groups[g][0]);
            table_header(title);
            print_row("standard", &base, &base);
        }
        for (int k = 1; k < 6 && groups[g][k]; k++) {
            struct config_result r;
            run_config(&s, m, c, groups[g][k], ref, &r);
            print_row(groups[g][k] + strlen(SPMIS) + 1, &r, &base);
            free_result(&r);
        }
    }
    free_result(&base);
    free(ref);
    scene_destroy(&s);
}

/* How spatial reuse meets temporal reuse: standard and spmis with temporal reuse on (history = the
 * spatial output), with the history taken before spatial reuse (no feedback of spatial reuse into
 * the next frame), and with temporal reuse off (every pixel as right after a disocclusion). Each
 * spmis row is measured against the standard row of the same regime. */
static void temporal_interplay(const struct bench_spmis_cfg *c, const struct method *m, const char *scene)
{
    struct scene s = bench_load_scene(scene);
    float *ref = last_frame_reference(c, m, &s);
    static const char *const regimes[3][2] = {{"temporal on", ""},
                                              {"history before spatial reuse", ":history=temporal"},
                                              {"temporal off", ":temporal=off"}};
    char title[256];
    snprintf(title, sizeof(title), "### %s on %s: spatial reuse against temporal reuse (each spmis row vs the "
             "standard row above it)", m->name, scene);
    table_header(title);
    for (int k = 0; k < 3; k++) {
        char a[192], b[192], la[96], lb[96];
        snprintf(a, sizeof(a), "%s%s", STANDARD, regimes[k][1]);
        snprintf(b, sizeof(b), "%s%s", SPMIS, regimes[k][1]);
        snprintf(la, sizeof(la), "standard, %s", regimes[k][0]);
        snprintf(lb, sizeof(lb), "spmis, %s", regimes[k][0]);
        struct config_result ra, rb;
        run_config(&s, m, c, a, ref, &ra);
        run_config(&s, m, c, b, ref, &rb);
        print_row(la, &ra, &ra);
        print_row(lb, &rb, &ra);
        free_result(&ra);
        free_result(&rb);
    }
    free(ref);
    scene_destroy(&s);
}

void bench_spmis(const struct bench_spmis_options *o)
{
    struct bench_spmis_cfg c = {o->width, o->height, o->runs, o->ref_spp, "", ""};
    snprintf(c.tag, sizeof(c.tag), "%dx%d%s", o->width, o->height, o->scale_radii ? "_scaled" : "");
    /* Pixel radii are tuned in 004 for 1080p: keep them, or scale them by height / 1080. Tiles stay
     * 8x8 either way (a cell needs pixels to reuse from). */
    float radius = o->scale_radii ? 30.0f * (float)o->height / 1080.0f : 30.0f;
    snprintf(c.radii, sizeof(c.radii), "spatial.radius=%g:spmis.search_radius=%g", radius, radius);
    printf("\n## Stochastic pairwise MIS (004), %dx%d, %s (8x8 tiles, %g px radii), confidence cap 20\n", c.width,
           c.height, o->scale_radii ? "pixel radii scaled by height / 1080" : "paper pixel parameters kept", radius);
    if (o->main) {
        const char *const pt_scenes[] = {"pillars", "ajar", "foliage", "cornell", "forest"};
        compare_scenes(&c, method_named("restir-pt"), pt_scenes, 5);
        const char *const di_scenes[] = {"pillars", "many-lights", "forest"};
        compare_scenes(&c, method_named("restir-di"), di_scenes, 3);
    }
    if (o->ablations) {
        struct bench_spmis_cfg a = c;
        a.runs = 1;
        ablations(&a, method_named("restir-pt"), "pillars");
        ablations(&a, method_named("restir-di"), "pillars");
    }
    if (o->interplay) {
        struct bench_spmis_cfg a = c;
        a.runs = 1;
        temporal_interplay(&a, method_named("restir-pt"), "pillars");
        temporal_interplay(&a, method_named("restir-pt"), "cornell");
    }
}
