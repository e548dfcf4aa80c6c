/* bench_gi.c: `restir_bench gi-bias [--scenes a,b] [--res WxH] [--runs N] [--frames N]`: the bias of
 * restir-gi's gi.radiance=stored (Ouyang et al. 2021's reuse of the radiance a sample point sent
 * toward the pixel that traced it), measured against gi.radiance=reevaluate (unbiased, proven by
 * render.gi_unbiased) run by run with the same seeds: the two differ only in the radiance their
 * shifts see, so the paired difference of their images has the bias as its mean and far less
 * variance than either side against a path-traced reference. Both follow the camera path. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "core/check.h"
#include "methods/settings.h"
#include "restir/metrics.h"

/* Luminance image of the last of `frames` camera-path frames of restir-gi with seed and radiance mode. */
static void render_gi(const struct scene *s, const struct render_params *base, const char *radiance, uint64_t seed,
                      int frames, double *lum)
{
    struct render_params p = *base;
    char set[64], msg[RESTIR_MSG_LEN];
    snprintf(set, sizeof set, "gi.radiance=%s", radiance);
    if (render_params_set(&p, set, msg) != 0) {
        fprintf(stderr, "bench gi-bias: %s\n", msg);
        exit(2);
    }
    p.seed = seed;
    struct renderer r;
    renderer_init(&r, s, method_named("restir-gi"), &p);
    for (int f = 0; f < frames; f++) {
        struct frame_stats st;
        struct camera cam = scene_camera_at(s, 1, (float)f);
        renderer_render(&r, f, &cam, &st);
    }
    restir_metrics_luminance(r.image, (size_t)p.width * (size_t)p.height, lum);
    renderer_fini(&r);
}

static void bias_row(const char *scene_name, int w, int h, int runs, int frames)
{
    struct scene s = bench_load_scene(scene_name);
    struct render_params p;
    render_params_defaults(&p);
    p.width = w;
    p.height = h;
    const size_t n = (size_t)w * (size_t)h;
    double *a = xmalloc(sizeof(double) * n), *b = xmalloc(sizeof(double) * n);
    double *d_sum = xcalloc(n, sizeof(double)), *d_sum2 = xcalloc(n, sizeof(double));
    double mean_re = 0.0, mean_st = 0.0, dm_sum = 0.0, dm_sum2 = 0.0;
    for (int k = 0; k < runs; k++) {
        render_gi(&s, &p, "reevaluate", 4000 + (uint64_t)k, frames, a);
        render_gi(&s, &p, "stored", 4000 + (uint64_t)k, frames, b);
        double ma = 0.0, mb = 0.0;
        for (size_t i = 0; i < n; i++) {
            const double d = b[i] - a[i];
            d_sum[i] += d;
            d_sum2[i] += d * d;
            ma += a[i];
            mb += b[i];
        }
        ma /= (double)n;
        mb /= (double)n;
        mean_re += ma / runs;
        mean_st += mb / runs;
        dm_sum += mb - ma;
        dm_sum2 += (mb - ma) * (mb - ma);
    }
    const double dm = dm_sum / runs, dm_se = sqrt((dm_sum2 / runs - dm * dm) / (runs - 1));
    /* pixels whose paired difference is significant at |z| > 4 (about 1 in 16000 by chance) */
    int significant = 0;
    double worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double m = d_sum[i] / runs, se = sqrt(fmax(d_sum2[i] / runs - m * m, 0.0) / (runs - 1));
        if (se > 0.0 && fabs(m / se) > 4.0) {
            significant++;
            const double rel = fabs(m) / fmax(mean_re, 1e-9);
            worst = rel > worst ? rel : worst;
        }
    }
    printf("| %s | %.5f | %.5f | %+.2f%% | %.1f | %d of %zu | %.1f%% |\n", scene_name, mean_re, mean_st,
           100.0 * dm / mean_re, dm_se > 0.0 ? dm / dm_se : 0.0, significant, n, 100.0 * worst);
    free(a);
    free(b);
    free(d_sum);
    free(d_sum2);
    scene_destroy(&s);
}

int bench_gi_bias(int argc, char **argv)
{
    char scenes[256] = "cornell,ajar,forest";
    int w = 64, h = 36, runs = 64, frames = 8;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--scenes") && i + 1 < argc)
            snprintf(scenes, sizeof scenes, "%s", argv[++i]);
        else if (!strcmp(argv[i], "--res") && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &w, &h) == 2)
            i++;
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: restir_bench gi-bias [--scenes a,b] [--res WxH] [--runs N] [--frames N]\n");
            return 2;
        }
    }
    if (runs < 2 || frames < 1 || w < 1 || h < 1) {
        fprintf(stderr, "restir_bench gi-bias: needs --runs >= 2, --frames >= 1 and a resolution\n");
        return 2;
    }
    printf("\n### restir-gi: gi.radiance=stored against reevaluate, %dx%d, frame %d of the camera path, %d runs paired "
           "by seed\n\n| scene | image mean, reevaluate | image mean, stored | stored - reevaluate | z | pixels "
           "|z| > 4 | largest of those, of the image mean |\n|---|---|---|---|---|---|---|\n",
           w, h, frames - 1, runs);
    for (char *tok = strtok(scenes, ","); tok; tok = strtok(NULL, ","))
        bias_row(tok, w, h, runs, frames);
    return 0;
}
