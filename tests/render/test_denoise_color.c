/* test_denoise_color.c: the denoisers keep each material's colour and the image's energy. restir-di
 * renders 16 frames of a still camera at 160x90 on two small scenes, a cyan quad (base colour 0,
 * 0.6, 0.6) and a black one on a white floor under a quad lamp, and SVGF and the à-trous filter
 * denoise them; the mean of frames 8-15 against a 256-path reference of the same integrand:
 *   - over the cyan quad's pixels red / green within 25% of the reference's (with the filters
 *     averaging the floor's red illumination into the quad's undivided red channel it was 3.6x);
 *   - over the black quad's pixels the mean luminance within 25% of the reference's plus 1% of the
 *     floor's (the quad stays black);
 *   - every channel's image mean within 3% of the reference's;
 * and on many-lights (320x180, 16 frames) the denoised mean luminance of frames 8-15 within 2% of the
 * reference's (one frame's own mean varies by about 3% there; the raw frames' is printed beside it). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/exr.h"
#include "render/cli_util.h"
#include "test_util.h"

#define TEST_COST_SECONDS 40
#define DIR_MAX (4 * CLI_PATH_MAX)

/* A white floor under a quad lamp, seen from above at a slant, with a quad of base colour rgb on it. */
static int write_scene(const char *path, const char *rgb)
{
    char text[2048];
    snprintf(text, sizeof text,
             "{\"format\": \"restir-scene 1\", \"name\": \"quad-on-floor\",\n"
             " \"camera\": {\"position\": [0, 2.2, 3.0], \"look_at\": [0, 0, 0], \"vfov\": 45},\n"
             " \"materials\": [{\"name\": \"floor\", \"base_color\": [0.8, 0.8, 0.8], \"roughness\": 1},\n"
             "   {\"name\": \"quad\", \"base_color\": [%s], \"roughness\": 1},\n"
             "   {\"name\": \"lamp\", \"emission\": [1, 1, 1], \"emissive_strength\": 10}],\n"
             " \"shapes\": [\n"
             "   {\"type\": \"quads\", \"material\": \"floor\", \"quads\": [[[-4, 0, 4], [4, 0, 4], [4, 0, -4], "
             "[-4, 0, -4]]]},\n"
             "   {\"type\": \"quads\", \"material\": \"quad\", \"quads\": [[[-0.6, 0.001, 0.6], [0.6, 0.001, 0.6], "
             "[0.6, 0.001, -0.6], [-0.6, 0.001, -0.6]]]},\n"
             "   {\"type\": \"quads\", \"material\": \"lamp\", \"quads\": [[[-0.5, 2.5, -0.5], [0.5, 2.5, -0.5], "
             "[0.5, 2.5, 0.5], [-0.5, 2.5, 0.5]]]}]}\n",
             rgb);
    return cli_write_text(path, text);
}

static float *read_exr(const char *path, int *w, int *h)
{
    float *rgb = NULL;
    char msg[512];
    if (exr_read_rgb(path, &rgb, w, h, msg) != 0) {
        EXPECT(0, "%s", msg);
        return NULL;
    }
    return rgb;
}

static double luminance(const float *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

/* Renders 16 frames of scene with restir-di and denoiser into dir. Returns 0, or -1. */
static int render(const char *tmp, const char *dir, const char *scene, const char *res, const char *denoiser)
{
    char args[12 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(args, sizeof args,
             "render --scene '%s' --method restir-di --res %s --frames 16 --seed 3 --denoise %s --out '%s'", scene,
             res, denoiser, dir);
    const int rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    return rc == 0 ? 0 : -1;
}

/* Frame f of a render into dir (layer "_denoised" or ""), malloc'ed, or NULL. */
static float *frame(const char *dir, int f, const char *layer)
{
    char path[DIR_MAX + 40];
    snprintf(path, sizeof path, "%s/frame_%04d%s.exr", dir, f, layer);
    int w, h;
    return read_exr(path, &w, &h);
}

static double mean_luminance(const float *img, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += luminance(&img[3 * i]);
    return s / n;
}

/* The reference of restir-di's integrand at res, 256 paths, into path. */
static float *reference(const char *tmp, const char *path, const char *scene, const char *res, int *w, int *h)
{
    char args[8 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(args, sizeof args, "reference --scene '%s' --method restir-di --res %s --spp 256 --out '%s'", scene, res,
             path);
    const int rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    return rc == 0 ? read_exr(path, w, h) : NULL;
}

static void check_channel_means(const char *what, const float *ref, const float *img, int n, double tolerance)
{
    for (int c = 0; c < 3; c++) {
        double sr = 0.0, si = 0.0;
        for (int i = 0; i < n; i++)
            sr += ref[3 * i + c], si += img[3 * i + c];
        printf("%s: channel %d mean %.5f, reference %.5f (%+.2f%%)\n", what, c, si / n, sr / n, 100.0 * (si / sr - 1));
        EXPECT(fabs(si / sr - 1.0) <= tolerance, "%s: channel %d's mean is %.4f of the reference's", what, c, si / sr);
    }
}

/* The quad's pixels: in the reference, red below half of green (cyan) or luminance below a tenth of
 * the floor's median-ish level, the image mean (black). */
static void check_quad(const char *tmp, const char *scene, const char *name, int cyan, const float *ref, int n)
{
    double mean = 0.0;
    for (int i = 0; i < n; i++)
        mean += luminance(&ref[3 * i]) / n;
    for (int m = 0; m < 2; m++) {
        const char *denoiser = m ? "atrous" : "svgf";
        char dir[DIR_MAX], what[64];
        snprintf(dir, sizeof dir, "%s/%s_%s", tmp, name, denoiser);
        snprintf(what, sizeof what, "%s quad, %s", name, denoiser);
        if (render(tmp, dir, scene, "160x90", denoiser) != 0)
            continue;
        float *img = calloc(3 * (size_t)n, sizeof(float)); /* the mean of frames 8-15: edges' jitter averaged */
        for (int f = 8; f < 16; f++) {
            float *one = frame(dir, f, "_denoised");
            for (int i = 0; one && i < 3 * n; i++)
                img[i] += one[i] / 8.0f;
            free(one);
        }
        double rr = 0.0, rg = 0.0, ir = 0.0, ig = 0.0, rl = 0.0, il = 0.0;
        int count = 0;
        for (int i = 0; i < n; i++) {
            const float *r = &ref[3 * i], *p = &img[3 * i];
            const int in = cyan ? r[1] > 0.05f * (float)mean && r[0] < 0.5f * r[1] : luminance(r) < 0.1 * mean;
            if (!in)
                continue;
            count++;
            rr += r[0], rg += r[1], ir += p[0], ig += p[1];
            rl += luminance(r), il += luminance(p);
        }
        EXPECT(count > 200, "%s: only %d pixels of the quad", what, count);
        if (cyan) {
            printf("%s: red / green over %d pixels %.4f, reference %.4f\n", what, count, ir / ig, rr / rg);
            EXPECT(fabs(ir / ig - rr / rg) <= 0.25 * rr / rg, "%s: red / green %.4f, the reference's %.4f", what,
                   ir / ig, rr / rg);
        } else {
            printf("%s: mean luminance over %d pixels %.5f, reference %.5f (image mean %.4f)\n", what, count,
                   il / count, rl / count, mean);
            EXPECT(fabs(il - rl) / count <= 0.25 * rl / count + 0.01 * mean,
                   "%s: mean luminance %.5f, the reference's %.5f", what, il / count, rl / count);
        }
        check_channel_means(what, ref, img, n, 0.03);
        free(img);
    }
}

int main(void)
{
    char tmp[CLI_PATH_MAX], scene[DIR_MAX], path[DIR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    const char *names[2] = {"cyan", "black"}, *colours[2] = {"0, 0.6, 0.6", "0, 0, 0"};
    for (int k = 0; k < 2; k++) {
        snprintf(scene, sizeof scene, "%s/%s.json", tmp, names[k]);
        snprintf(path, sizeof path, "%s/%s_ref.exr", tmp, names[k]);
        EXPECT(write_scene(scene, colours[k]) == 0, "cannot write %s", scene);
        int w = 0, h = 0;
        float *ref = reference(tmp, path, scene, "160x90", &w, &h);
        if (ref)
            check_quad(tmp, scene, names[k], k == 0, ref, w * h);
        free(ref);
    }
    /* the image's energy on many-lights, whose emitters (albedo 0) sit beside lit walls */
    int w = 0, h = 0;
    snprintf(path, sizeof path, "%s/many_ref.exr", tmp);
    float *ref = reference(tmp, path, "many-lights", "320x180", &w, &h);
    for (int m = 0; ref && m < 2; m++) {
        const char *denoiser = m ? "atrous" : "svgf";
        char dir[DIR_MAX];
        snprintf(dir, sizeof dir, "%s/many_%s", tmp, denoiser);
        if (render(tmp, dir, "many-lights", "320x180", denoiser) != 0)
            continue;
        double raw = 0.0, dn = 0.0;
        for (int f = 8; f < 16; f++) {
            float *a = frame(dir, f, ""), *b = frame(dir, f, "_denoised");
            raw += a ? mean_luminance(a, w * h) / 8 : NAN;
            dn += b ? mean_luminance(b, w * h) / 8 : NAN;
            free(a);
            free(b);
        }
        const double lr = mean_luminance(ref, w * h);
        printf("many-lights, %s: mean luminance of frames 8-15 %.5f of the reference's (raw %.5f)\n", denoiser,
               dn / lr, raw / lr);
        EXPECT(fabs(dn / lr - 1.0) <= 0.02, "many-lights, %s: mean luminance %.4f of the reference's", denoiser,
               dn / lr);
    }
    free(ref);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
