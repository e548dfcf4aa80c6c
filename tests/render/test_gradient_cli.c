/* test_gradient_cli.c: the gradient-domain methods (gpt, grad-after-restir, grestir-pt) through
 * `restir render` and `restir compare`: the EXR layers (primal, dx, dy, the other reconstruction)
 * and PNGs, the recon=l2|l1|both switch and that L1 never changes the L2 image, thread-count
 * determinism, rejected parameters, compare.csv, list and --help. Must never render in-process:
 * it runs the binary ($RESTIR_BIN) and only reads the files it writes (io/exr.h's reader). */
#include "cli_util.h"
#include "core/check.h"
#include "io/exr.h"
#include "restir/metrics.h"
#include "test_util.h"

#define W 24
#define H 16
#define NPIX (3 * W * H)
#define DIR_MAX (2 * CLI_PATH_MAX)  /* a folder under tmp */
#define FILE_MAX (3 * CLI_PATH_MAX) /* a file in such a folder */
#define ARGS_MAX (6 * CLI_PATH_MAX)

static char tmp[CLI_PATH_MAX];
static const char *grad_methods[] = {"gpt", "grad-after-restir", "grestir-pt"};
#define N_GRAD_METHODS 3

/* `restir render` of cornell at w x h, 3 frames, moving camera, into tmp/<name>; extra is pasted
 * after the common arguments. dir gets the folder. Returns the exit code. */
static int render_sized(const char *name, const char *method, int w, int h, const char *extra, char *dir)
{
    char args[ARGS_MAX], err[CLI_ERR_MAX];
    snprintf(dir, DIR_MAX, "%s/%s", tmp, name);
    snprintf(args, sizeof(args),
             "render --scene cornell --method %s --res %dx%d --frames 3 --camera path %s --out '%s'", method, w, h,
             extra, dir);
    int rc = cli_run(tmp, args, err);
    if (rc != 0)
        printf("restir %s exited %d:\n%s", args, rc, err);
    return rc;
}

static int render(const char *name, const char *method, const char *extra, char *dir)
{
    return render_sized(name, method, W, H, extra, dir);
}

/* Reads layer (NULL = default R, G, B) of dir/file; checks the size is ew x eh. Returns the buffer
 * or NULL (with a failed expectation naming the problem). */
static float *read_layer_sized(const char *dir, const char *file, const char *layer, int ew, int eh)
{
    char path[4 * CLI_PATH_MAX], msg[RESTIR_MSG_LEN];
    float *rgb = NULL;
    int w = 0, h = 0;
    snprintf(path, sizeof(path), "%s/%s", dir, file);
    int rc = exr_read_layer(path, layer, &rgb, &w, &h, msg);
    EXPECT(rc == 0, "%s: cannot read layer %s: %s", path, layer ? layer : "(default)", msg);
    if (rc != 0)
        return NULL;
    EXPECT(w == ew && h == eh, "%s layer %s is %dx%d, want %dx%d", path, layer ? layer : "(default)", w, h, ew, eh);
    if (w != ew || h != eh) {
        free(rgb);
        return NULL;
    }
    return rgb;
}

static float *read_layer(const char *dir, const char *file, const char *layer)
{
    return read_layer_sized(dir, file, layer, W, H);
}

/* Nonzero values of img (w x h RGB) in column x (x >= 0) or row y (x < 0). */
static int count_nonzero_line(const float *img, int w, int h, int x, int y)
{
    int n = 0;
    for (int k = 0; k < (x >= 0 ? h : w); k++)
        for (int c = 0; c < 3; c++)
            n += img[3 * (x >= 0 ? k * w + x : y * w + k) + c] != 0.0f;
    return n;
}

/* The forward differences have no neighbor past the right column (dx) and the bottom row (dy):
 * those must be exactly 0, while the rest of dx, dy is not. check_both_edges also needs the
 * primal to be nonzero on that column and row, so that a difference taken against a missing (black)
 * or wrapped-around neighbor would show. */
static void check_edges(const char *what, const float *primal, const float *dx, const float *dy, int w, int h,
                        int check_both_edges)
{
    int dx_edge = count_nonzero_line(dx, w, h, w - 1, 0), dy_edge = count_nonzero_line(dy, w, h, -1, h - 1);
    int dx_inner = 0, dy_inner = 0;
    for (int x = 0; x < w - 1; x++)
        dx_inner += count_nonzero_line(dx, w, h, x, 0);
    for (int y = 0; y < h - 1; y++)
        dy_inner += count_nonzero_line(dy, w, h, -1, y);
    EXPECT(dx_edge == 0, "%s: dx has %d nonzero values in the last column (no right neighbor)", what, dx_edge);
    EXPECT(dy_edge == 0, "%s: dy has %d nonzero values in the last row (no lower neighbor)", what, dy_edge);
    EXPECT(dx_inner > 0, "%s: dx is zero everywhere", what);
    EXPECT(dy_inner > 0, "%s: dy is zero everywhere", what);
    if (check_both_edges) {
        EXPECT(count_nonzero_line(primal, w, h, w - 1, 0) > 0 && count_nonzero_line(primal, w, h, 0, 0) > 0,
               "%s: the primal is black on the first or last column, so the dx edge check is void", what);
        EXPECT(count_nonzero_line(primal, w, h, -1, h - 1) > 0 && count_nonzero_line(primal, w, h, -1, 0) > 0,
               "%s: the primal is black on the first or last row, so the dy edge check is void", what);
    }
}

/* Checks that layer is absent from dir/file and that the reader's message names it. */
static void expect_no_layer(const char *dir, const char *file, const char *layer)
{
    char path[4 * CLI_PATH_MAX], msg[RESTIR_MSG_LEN], want[64];
    float *rgb = NULL;
    int w = 0, h = 0;
    snprintf(path, sizeof(path), "%s/%s", dir, file);
    msg[0] = '\0';
    int rc = exr_read_layer(path, layer, &rgb, &w, &h, msg);
    EXPECT(rc != 0, "%s has a layer %s but should not", path, layer);
    snprintf(want, sizeof(want), "layer '%s'", layer);
    if (rc != 0)
        EXPECT(strstr(msg, want) != NULL, "reading the absent layer %s of %s: message does not name it: %s", layer,
               path, msg);
    free(rgb);
}

static int all_finite(const float *a, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

/* Number of floats whose bits differ (memcmp per value: -0 and 0 differ, NaN equals itself). */
static int count_bit_diffs(const float *a, const float *b, int n)
{
    int d = 0;
    for (int i = 0; i < n; i++)
        if (memcmp(&a[i], &b[i], sizeof(float)) != 0)
            d++;
    return d;
}

/* 1 when path exists and starts with the PNG signature. */
static int is_png(const char *dir, const char *file)
{
    char path[4 * CLI_PATH_MAX];
    unsigned char sig[8] = {0};
    static const unsigned char want[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    snprintf(path, sizeof(path), "%s/%s", dir, file);
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    size_t n = fread(sig, 1, 8, f);
    fclose(f);
    return n == 8 && memcmp(sig, want, 8) == 0;
}

/* metrics.csv of dir: columns ms_recon_l2 and ms_recon_l1 exist and are positive in each of the
 * 3 data rows (both solves ran every frame). */
static void check_metrics(const char *dir, const char *method)
{
    static char csv[CLI_ERR_MAX];
    char path[FILE_MAX];
    snprintf(path, sizeof(path), "%s/metrics.csv", dir);
    cli_read_text(path, csv, sizeof(csv));
    EXPECT(csv[0] != '\0', "%s: %s is missing or empty", method, path);
    int c2 = cli_csv_column(csv, "ms_recon_l2"), c1 = cli_csv_column(csv, "ms_recon_l1");
    EXPECT(c2 >= 0, "%s: %s has no column ms_recon_l2", method, path);
    EXPECT(c1 >= 0, "%s: %s has no column ms_recon_l1", method, path);
    int rows = 0;
    for (const char *line = cli_next_line(csv); line; line = cli_next_line(line)) {
        rows++;
        if (c2 >= 0) {
            double v = cli_csv_number(line, c2);
            EXPECT(v > 0.0, "%s: ms_recon_l2 of data row %d is %g", method, rows, v);
        }
        if (c1 >= 0) {
            double v = cli_csv_number(line, c1);
            EXPECT(v > 0.0, "%s: ms_recon_l1 of data row %d is %g", method, rows, v);
        }
    }
    EXPECT(rows == 3, "%s: %s has %d data rows, want 3 (one per frame)", method, path, rows);
}

/* Cases 1-3 for one method: recon=both, recon=l1 and recon=l2 of the same seed. */
static void check_method(const char *method)
{
    char both[DIR_MAX], l1[DIR_MAX], l2[DIR_MAX], name[128];
    const char *f = "frame_0002.exr";
    snprintf(name, sizeof(name), "%s-both", method);
    int rc_both = render(name, method, "--set recon=both", both);
    EXPECT(rc_both == 0, "%s: render with recon=both exited %d", method, rc_both);
    snprintf(name, sizeof(name), "%s-l1", method);
    int rc_l1 = render(name, method, "--set recon=l1", l1);
    EXPECT(rc_l1 == 0, "%s: render with recon=l1 exited %d", method, rc_l1);
    snprintf(name, sizeof(name), "%s-l2", method);
    int rc_l2 = render(name, method, "--set recon=l2", l2);
    EXPECT(rc_l2 == 0, "%s: render with recon=l2 exited %d", method, rc_l2);

    /* 1. recon=both: the default image (L2) and the layers primal, dx, dy, L1. */
    float *img = read_layer(both, f, NULL), *primal = read_layer(both, f, "primal"),
          *dx = read_layer(both, f, "dx"), *dy = read_layer(both, f, "dy"), *lone = read_layer(both, f, "L1");
    if (img && primal && dx && dy && lone) {
        EXPECT(all_finite(img, NPIX), "%s recon=both: default image not finite", method);
        EXPECT(all_finite(primal, NPIX), "%s recon=both: primal not finite", method);
        EXPECT(all_finite(dx, NPIX), "%s recon=both: dx not finite", method);
        EXPECT(all_finite(dy, NPIX), "%s recon=both: dy not finite", method);
        EXPECT(all_finite(lone, NPIX), "%s recon=both: L1 not finite", method);
        EXPECT(count_bit_diffs(img, lone, NPIX) > 0, "%s recon=both: the default image equals the L1 layer",
               method);
        EXPECT(count_bit_diffs(img, primal, NPIX) > 0, "%s recon=both: the default image equals the primal", method);
        check_edges(method, primal, dx, dy, W, H, 0);
    }
    expect_no_layer(both, f, "L2"); /* L2 is the default image itself */
    const char *pngs[] = {"frame_0002.png", "frame_0002_dx.png", "frame_0002_dy.png", "frame_0002_primal.png"};
    for (int k = 0; k < 4; k++)
        EXPECT(is_png(both, pngs[k]), "%s recon=both: %s/%s is missing or not a PNG", method, both, pngs[k]);
    check_metrics(both, method);

    /* 2. recon=l1: the default image is the L1 solve (the L1 layer of recon=both), L2 is a layer (the
     * default image of recon=both); recon=l2: no second reconstruction. */
    float *l1_img = read_layer(l1, f, NULL), *l1_l2 = read_layer(l1, f, "L2"), *l1_primal = read_layer(l1, f, "primal");
    if (l1_img && l1_l2) {
        EXPECT(all_finite(l1_img, NPIX) && all_finite(l1_l2, NPIX), "%s recon=l1: image or L2 not finite", method);
        EXPECT(count_bit_diffs(l1_img, l1_l2, NPIX) > 0, "%s recon=l1: the default image equals the L2 layer",
               method);
    }
    if (l1_img && lone) {
        int d = count_bit_diffs(l1_img, lone, NPIX);
        EXPECT(d == 0, "%s: recon=l1 image differs from the L1 layer of recon=both in %d values", method, d);
    }
    if (l1_l2 && img) {
        int d = count_bit_diffs(l1_l2, img, NPIX);
        EXPECT(d == 0, "%s: L2 layer of recon=l1 differs from the image of recon=both in %d values", method, d);
    }
    if (l1_primal && primal) {
        int d = count_bit_diffs(l1_primal, primal, NPIX);
        EXPECT(d == 0, "%s: primal of recon=l1 differs from that of recon=both in %d values", method, d);
    }
    expect_no_layer(l1, f, "L1"); /* L1 is the default image itself */
    expect_no_layer(l2, f, "L1");
    expect_no_layer(l2, f, "L2");

    /* 3. Computing L1 as well must not change the L2 image, nor what it was solved from. */
    float *l2_img = read_layer(l2, f, NULL), *l2_dx = read_layer(l2, f, "dx"), *l2_dy = read_layer(l2, f, "dy");
    if (l2_img && img) {
        int d = count_bit_diffs(l2_img, img, NPIX);
        EXPECT(d == 0, "%s: the L2 image of recon=l2 and recon=both differs in %d values", method, d);
    }
    if (l2_dx && dx && l2_dy && dy) {
        int d = count_bit_diffs(l2_dx, dx, NPIX) + count_bit_diffs(l2_dy, dy, NPIX);
        EXPECT(d == 0, "%s: dx/dy of recon=l2 and recon=both differ in %d values", method, d);
    }
    free(img), free(primal), free(dx), free(dy), free(lone);
    free(l1_img), free(l1_l2), free(l1_primal), free(l2_img), free(l2_dx), free(l2_dy);
}

/* The edges of dx and dy where the image is lit there: at 24x16 the box leaves the outer columns
 * black, at 16x24 (portrait) it fills every edge. */
static void check_edges_portrait(const char *method)
{
    char dir[DIR_MAX], name[128];
    const char *f = "frame_0002.exr";
    snprintf(name, sizeof(name), "%s-portrait", method);
    int rc = render_sized(name, method, H, W, "--set recon=l2", dir);
    EXPECT(rc == 0, "%s: render at %dx%d exited %d", method, H, W, rc);
    float *primal = read_layer_sized(dir, f, "primal", H, W), *dx = read_layer_sized(dir, f, "dx", H, W),
          *dy = read_layer_sized(dir, f, "dy", H, W);
    if (primal && dx && dy) {
        snprintf(name, sizeof(name), "%s at %dx%d", method, H, W);
        check_edges(name, primal, dx, dy, H, W, 1);
    }
    free(primal), free(dx), free(dy);
}

/* recon=l2 is the default: a render without --set recon writes the same bytes as recon=l2. */
static void check_default_recon(void)
{
    char d0[DIR_MAX], d2[DIR_MAX], a[FILE_MAX], b[FILE_MAX];
    EXPECT(render("gpt-default", "gpt", "", d0) == 0, "gpt: render without --set recon failed");
    snprintf(d2, sizeof(d2), "%s/gpt-l2", tmp);
    snprintf(a, sizeof(a), "%s/frame_0002.exr", d0);
    snprintf(b, sizeof(b), "%s/frame_0002.exr", d2);
    long size = 0;
    int same = cli_files_equal(a, b, &size);
    EXPECT(same == 1, "gpt: the default recon and recon=l2 give different frames (%s)",
           same < 0 ? "missing" : "bytes differ");
}

/* 3. grestir-pt writes the same bytes with 1 and 2 threads; another seed changes them. */
static void check_threads(void)
{
    char t1[DIR_MAX], t2[DIR_MAX], s2[DIR_MAX];
    EXPECT(render("grestir-t1", "grestir-pt", "--set recon=both --threads 1", t1) == 0,
           "grestir-pt: render with 1 thread failed");
    EXPECT(render("grestir-t2", "grestir-pt", "--set recon=both --threads 2", t2) == 0,
           "grestir-pt: render with 2 threads failed");
    EXPECT(render("grestir-seed2", "grestir-pt", "--set recon=both --threads 2 --seed 2", s2) == 0,
           "grestir-pt: render with seed 2 failed");
    const char *files[] = {"frame_0000.exr", "frame_0002.exr", "frame_0002.png", "frame_0002_dx.png"};
    for (int k = 0; k < 4; k++) {
        char a[FILE_MAX], b[FILE_MAX], c[FILE_MAX];
        snprintf(a, sizeof(a), "%s/%s", t1, files[k]);
        snprintf(b, sizeof(b), "%s/%s", t2, files[k]);
        snprintf(c, sizeof(c), "%s/%s", s2, files[k]);
        long size = 0, size_c = 0;
        int same = cli_files_equal(a, b, &size);
        EXPECT(same == 1, "grestir-pt: %s differs between 1 and 2 threads (%s)", files[k],
               same < 0 ? "missing" : "bytes differ");
        EXPECT(size > 0, "grestir-pt: %s is empty", files[k]);
        if (strstr(files[k], ".exr")) {
            int same_c = cli_files_equal(a, c, &size_c);
            EXPECT(same_c == 0, "grestir-pt: %s does not change with the seed (%d)", files[k], same_c);
        }
    }
    /* Which images differ, so a byte difference above can be traced to a pass. */
    const char *layers[] = {NULL, "L1", "primal", "dx", "dy"};
    for (int f = 0; f < 3; f++) {
        char file[32];
        snprintf(file, sizeof(file), "frame_%04d.exr", f);
        for (int k = 0; k < 5; k++) {
            float *a = read_layer(t1, file, layers[k]), *b = read_layer(t2, file, layers[k]);
            if (a && b) {
                int d = count_bit_diffs(a, b, NPIX);
                EXPECT(d == 0, "grestir-pt: %s layer %s differs in %d values between 1 and 2 threads", file,
                       layers[k] ? layers[k] : "(default)", d);
            }
            free(a), free(b);
        }
    }
}

/* 4. Bad gradient parameters: exit 2, "restir: " naming the key and the choices, no output. */
static void expect_rejected(const char *method, const char *set, const char *const *need, int n_need)
{
    char out[DIR_MAX], args[ARGS_MAX], err[CLI_ERR_MAX];
    snprintf(out, sizeof(out), "%s/rejected-%s", tmp, method);
    snprintf(args, sizeof(args), "render --scene cornell --method %s --res %dx%d --frames 3 --camera path --set %s "
             "--out '%s'", method, W, H, set, out);
    int rc = cli_run(tmp, args, err);
    printf("[--set %s] exit %d: %s", set, rc, err[0] ? err : "(no message)\n");
    EXPECT(rc == 2, "--set %s: exit %d, want 2", set, rc);
    EXPECT(strncmp(err, "restir: ", 8) == 0, "--set %s: stderr does not start with 'restir: ': %s", set, err);
    for (int k = 0; k < n_need; k++)
        EXPECT(strstr(err, need[k]) != NULL, "--set %s: message does not mention '%s': %s", set, need[k], err);
    EXPECT(strstr(err, "internal error") == NULL, "--set %s: hit an internal check: %s", set, err);
    int left = cli_count_entries(out, "");
    EXPECT(left <= 0, "--set %s: %d files left in %s", set, left, out);
    cli_remove_tree(out);
}

static void check_rejected(void)
{
    const char *recon[] = {"recon", "l3", "l2", "l1", "both"};
    const char *spatial[] = {"grad.spatial", "sparse", "off", "dense", "adaptive"};
    const char *alpha[] = {"recon.alpha", "0"};
    expect_rejected("gpt", "recon=l3", recon, 5);
    expect_rejected("grestir-pt", "grad.spatial=sparse", spatial, 5);
    expect_rejected("grad-after-restir", "recon.alpha=0", alpha, 2);
    const char *iterations[] = {"recon.iterations", "recon.solver=cg"};
    expect_rejected("gpt", "recon.iterations=50", iterations, 2);
}

/* 4b. recon.iterations=N: N CG steps of L2 from the primal. One step leaves the solve visibly short
 * of DCT's exact one; 400 steps reach it (to 1e-4 relative), on the same inputs (the paths do not
 * depend on the solver). */
static void check_fixed_iterations(void)
{
    char exact[DIR_MAX], one[DIR_MAX], many[DIR_MAX];
    EXPECT(render("gpt-dct", "gpt", "--set recon=l2", exact) == 0, "gpt: DCT render failed");
    EXPECT(render("gpt-cg1", "gpt", "--set recon=l2 --set recon.solver=cg --set recon.iterations=1", one) == 0,
           "gpt: 1-step CG render failed");
    EXPECT(render("gpt-cg400", "gpt", "--set recon=l2 --set recon.solver=cg --set recon.iterations=400", many) == 0,
           "gpt: 400-step CG render failed");
    float *a = read_layer(exact, "frame_0002.exr", NULL), *b = read_layer(one, "frame_0002.exr", NULL),
          *c = read_layer(many, "frame_0002.exr", NULL), *pa = read_layer(exact, "frame_0002.exr", "primal"),
          *pb = read_layer(one, "frame_0002.exr", "primal");
    if (a && b && c && pa && pb) {
        EXPECT(count_bit_diffs(pa, pb, NPIX) == 0, "the solver changed the primal");
        double d1 = 0.0, d400 = 0.0, norm = 0.0;
        for (int k = 0; k < NPIX; k++) {
            d1 += ((double)b[k] - a[k]) * ((double)b[k] - a[k]);
            d400 += ((double)c[k] - a[k]) * ((double)c[k] - a[k]);
            norm += (double)a[k] * a[k];
        }
        printf("recon.iterations: |cg1 - dct|^2 / |dct|^2 = %.3g, |cg400 - dct|^2 / |dct|^2 = %.3g\n", d1 / norm,
               d400 / norm);
        EXPECT(d1 / norm > 1e-6, "one CG step reproduced the exact solve (%g)", d1 / norm);
        EXPECT(d400 / norm < 1e-8, "400 CG steps did not reach the exact solve (%g)", d400 / norm);
    } else {
        EXPECT(0, "missing layers of the recon.iterations renders");
    }
    free(a), free(b), free(c), free(pa), free(pb);
}

/* 5. compare at equal time with gradient and non-gradient methods. */
static void check_compare(void)
{
    static char csv[CLI_ERR_MAX];
    char dir[DIR_MAX], args[ARGS_MAX], err[CLI_ERR_MAX], path[FILE_MAX], sub[FILE_MAX];
    const char *methods[] = {"grestir-pt", "gpt", "area-restir", "pt"};
    snprintf(dir, sizeof(dir), "%s/compare", tmp);
    snprintf(args, sizeof(args),
             "compare --scene cornell --res %dx%d --frames 3 --camera path --equal-time --ref-spp 16 "
             "--methods grestir-pt,gpt,area-restir,pt --out '%s'",
             W, H, dir);
    int rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "compare exited %d: %s", rc, err);
    snprintf(path, sizeof(path), "%s/compare.csv", dir);
    cli_read_text(path, csv, sizeof(csv));
    const char *header = "method,ms_per_frame,spp,instances,relmse,mape,smape,luma_rmse,runs,temporal_cov,relmse_sem,"
                         "mape_sem,smape_sem,mape_disoccluded,mape_disoccluded_sem,disoccluded_share,gradient_relmse,"
                         "gradient_relmse_sem,gradient_relmse_trim1,gradient_relmse_trim1_sem,gradient_mape,"
                         "gradient_mape_sem,relmse_denoised,relmse_denoised_sem,mape_denoised,mape_denoised_sem,"
                         "smape_denoised,smape_denoised_sem,mape_disoccluded_denoised,mape_disoccluded_denoised_sem,"
                         "temporal_cov_denoised,ref_relmse,ref_mape,ref_smape,relmse_net,flip,flip_sem,"
                         "ref_mape_disoccluded,flicker1,flicker4,flicker16,boiling_index,"
                         "flicker1_denoised,flicker4_denoised,flicker16_denoised,boiling_index_denoised,lag_frames,"
                         "lag_frames_denoised,lag_frames_blocks,lag_frames_blocks_denoised,ghost_frames,"
                         "ghost_frames_denoised\n";
    double grad_relmse[4], grad_trim[4], grad_mape[4], flip[4];
    EXPECT(strncmp(csv, header, strlen(header)) == 0, "%s: wrong header:\n%s", path, csv);
    int rows = 0;
    for (const char *line = cli_next_line(csv); line; line = cli_next_line(line)) {
        if (rows < 4) {
            size_t len = strlen(methods[rows]);
            EXPECT(strncmp(line, methods[rows], len) == 0 && line[len] == ',', "%s: row %d is not %s: %.80s", path,
                   rows + 1, methods[rows], line);
        }
        double ms = cli_csv_number(line, 1), spp = cli_csv_number(line, 2), inst = cli_csv_number(line, 3);
        EXPECT(ms > 0.0 && isfinite(ms), "%s row %d: ms_per_frame %g", path, rows + 1, ms);
        EXPECT(spp >= 1.0, "%s row %d: spp %g", path, rows + 1, spp);
        EXPECT(inst >= 1.0, "%s row %d: instances %g", path, rows + 1, inst);
        for (int c = 4; c < 8; c++) {
            double e = cli_csv_number(line, c);
            EXPECT(isfinite(e) && e >= 0.0, "%s row %d: error column %d is %g", path, rows + 1, c, e);
        }
        if (rows < 4) {
            grad_relmse[rows] = cli_csv_number(line, 16);
            grad_trim[rows] = cli_csv_number(line, 18);
            grad_mape[rows] = cli_csv_number(line, 20);
            flip[rows] = cli_csv_number(line, cli_csv_column(csv, "flip"));
            /* relmse_net is relmse less the reference's own relMSE (its two halves' relMSE / 2) */
            const double rel = cli_csv_number(line, 4), own = cli_csv_number(line, cli_csv_column(csv, "ref_relmse")),
                         net = cli_csv_number(line, cli_csv_column(csv, "relmse_net"));
            EXPECT(own > 0.0 && fabs(net - (rel - own)) <= 1e-4 * rel, "%s row %d: relmse_net %g, relmse %g, ref %g",
                   path, rows + 1, net, rel, own);
            EXPECT(flip[rows] > 0.0 && flip[rows] < 1.0, "%s row %d: flip %g", path, rows + 1, flip[rows]);
        }
        rows++;
    }
    EXPECT(rows == 4, "%s has %d rows, want 4", path, rows);
    /* the gradient rows' gradient_relmse is restir_metrics_gradient_relmse of the frame's dx, dy layers
     * against the reference (the written frame is the measured one: instances = 1); the others have none */
    float *ref = read_layer(dir, "reference.exr", NULL);
    for (int k = 0; k < 2; k++) {
        snprintf(sub, sizeof(sub), "%s/%s", dir, methods[k]);
        float *dx = read_layer(sub, "frame_0002.exr", "dx"), *dy = read_layer(sub, "frame_0002.exr", "dy");
        if (dx)
            EXPECT(all_finite(dx, NPIX), "compare: %s/frame_0002.exr has a non-finite dx", sub);
        const double want = dx && dy && ref ? restir_metrics_gradient_relmse(dx, dy, ref, W, H) : NAN;
        EXPECT(rows == 4 && isfinite(want) && fabs(grad_relmse[k] - want) <= 1e-5 * want,
               "compare: %s gradient_relmse %.9g, its frame's %.9g", methods[k], rows == 4 ? grad_relmse[k] : NAN,
               want);
        /* the trimmed relMSE and gradient MAPE of the same frame */
        const double trim = dx && dy && ref ? restir_metrics_gradient_relmse_trimmed(dx, dy, ref, W, H, 0.01) : NAN;
        const double mape = dx && dy && ref ? restir_metrics_gradient_mape(dx, dy, ref, W, H) : NAN;
        EXPECT(rows == 4 && isfinite(trim) && fabs(grad_trim[k] - trim) <= 1e-5 * trim && trim <= want,
               "compare: %s gradient_relmse_trim1 %.9g, its frame's %.9g", methods[k], rows == 4 ? grad_trim[k] : NAN,
               trim);
        EXPECT(rows == 4 && isfinite(mape) && fabs(grad_mape[k] - mape) <= 1e-5 * mape,
               "compare: %s gradient_mape %.9g, its frame's %.9g", methods[k], rows == 4 ? grad_mape[k] : NAN, mape);
        /* the flip column is restir_metrics_flip of the same frame at FLIP's default viewing condition */
        float *img = read_layer(sub, "frame_0002.exr", NULL);
        double fl = NAN;
        if (!img || !ref || restir_metrics_flip(img, ref, W, H, RESTIR_METRICS_FLIP_PPD, NULL, &fl) != 0)
            fl = NAN;
        EXPECT(rows == 4 && isfinite(fl) && fabs(flip[k] - fl) <= 1e-5 * fl, "compare: %s flip %.9g, its frame's %.9g",
               methods[k], rows == 4 ? flip[k] : NAN, fl);
        free(img);
        free(dx);
        free(dy);
    }
    free(ref);
    for (int k = 2; k < rows && k < 4; k++)
        EXPECT(isnan(grad_relmse[k]) && isnan(grad_trim[k]) && isnan(grad_mape[k]),
               "compare: %s has gradient errors (%g, %g, %g) but no gradients", methods[k], grad_relmse[k],
               grad_trim[k], grad_mape[k]);
    snprintf(sub, sizeof(sub), "%s/pt", dir);
    expect_no_layer(sub, "frame_0002.exr", "dx");
    /* the image of the worst 1% of the gradient pairs, for the gradient rows only */
    EXPECT(cli_count_entries(dir, "grestir-pt_grad_worst1.png") == 1 &&
               cli_count_entries(dir, "gpt_grad_worst1.png") == 1,
           "compare: no worst-pairs image for a gradient row in %s", dir);
    EXPECT(cli_count_entries(dir, "_grad_worst1.png") == 2, "compare: a worst-pairs image for a row without "
           "gradients in %s", dir);
}

/* 6. list names the gradient methods; render --help calls L1 BIASED on the recon line. */
static void check_list_and_help(void)
{
    static char out[CLI_ERR_MAX];
    char err[CLI_ERR_MAX], want[128];
    const char *listed[] = {"area-restir", "gpt", "grad-after-restir", "grestir-pt"};
    int rc = cli_run_capture(tmp, "list", out, err);
    EXPECT(rc == 0, "restir list exited %d: %s", rc, err);
    for (int k = 0; k < 4; k++) {
        snprintf(want, sizeof(want), "method %s\t", listed[k]);
        EXPECT(strstr(out, want) != NULL, "restir list does not list method %s", listed[k]);
    }
    rc = cli_run_capture(tmp, "render --help", out, err);
    EXPECT(rc == 0, "restir render --help exited %d", rc);
    const char *p = strstr(out, "\n  recon ");
    char line[1024] = "";
    if (p) {
        p++;
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len >= sizeof(line))
            len = sizeof(line) - 1;
        memcpy(line, p, len);
        line[len] = '\0';
    }
    EXPECT(line[0] != '\0', "render --help has no line for the parameter recon");
    const char *l1 = strstr(line, "l1");
    EXPECT(l1 && strstr(l1, "BIASED"), "render --help does not call l1 BIASED on the recon line: '%s'", line);
}

int main(void)
{
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    for (int m = 0; m < N_GRAD_METHODS; m++) {
        check_method(grad_methods[m]);
        check_edges_portrait(grad_methods[m]);
    }
    check_default_recon();
    check_threads();
    check_rejected();
    check_fixed_iterations();
    check_compare();
    check_list_and_help();
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
