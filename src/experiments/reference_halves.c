/* reference_halves.c: a reference as two independent halves (reference_halves.h). */
#include "experiments/reference_halves.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/reference_checkpoint.h"
#include "io/exr.h"
#include "methods/pt/reference.h"

int reference_half_spp(int spp)
{
    return spp > 1 ? (spp + 1) / 2 : 1;
}

/* OUT.exr -> OUT.half_X.exr (any other name: OUT.half_X.exr appended). */
static void half_path(const char *out, char which, char *path, size_t len)
{
    const size_t n = strlen(out);
    if (n >= 4 && !strcmp(out + n - 4, ".exr"))
        snprintf(path, len, "%.*s.half_%c.exr", (int)(n - 4), out, which);
    else
        snprintf(path, len, "%s.half_%c.exr", out, which);
}

/* One half, resumable: the finished file when it holds this run, else rendered from its checkpoint
 * and written with its run description. Returns the image, or NULL with msg. */
static float *render_half(const struct scene *s, const struct method *method, const struct render_params *p,
                          const struct camera *cam, const struct camera *open, int spp, const char *path, char *msg)
{
    struct reference_accum probe;
    reference_accum_init(&probe, s, method, p, cam, open, spp);
    char run[RUN_TEXT_MAX], theirs[RUN_TEXT_MAX], why[RESTIR_MSG_LEN];
    reference_describe(&probe, run, sizeof run);
    const int w = probe.params.width, h = probe.params.height;
    reference_accum_fini(&probe);
    struct stat st;
    if (stat(path, &st) == 0 && exr_read_attribute(path, "restir.run", theirs, sizeof theirs, why) == 0 &&
        !strcmp(theirs, run)) {
        float *img = NULL;
        if (cli_load_reference(path, w, h, &img, msg) != 0)
            return NULL;
        printf("reference half %s is done\n", path);
        return img;
    }
    float *img = reference_render_resumable(s, method, p, cam, open, spp, path, msg);
    if (img && reference_write_image(path, img, w, h, spp, spp, run, method->name, s->name, NULL, NULL, 0, msg) != 0) {
        free(img);
        return NULL;
    }
    return img;
}

int reference_render_pair(const struct scene *s, const struct method *method, const struct render_params *p,
                          const struct camera *cam, const struct camera *open, int spp, const char *out,
                          struct reference_pair *r, char *msg)
{
    memset(r, 0, sizeof *r);
    r->spp_half = reference_half_spp(spp);
    struct render_params pb = *p;
    pb.seed = reference_half_b_seed(p->seed);
    if (out) {
        char pa[4200], pbp[4200];
        half_path(out, 'a', pa, sizeof pa);
        half_path(out, 'b', pbp, sizeof pbp);
        r->a = render_half(s, method, p, cam, open, r->spp_half, pa, msg);
        r->b = r->a ? render_half(s, method, &pb, cam, open, r->spp_half, pbp, msg) : NULL;
    } else {
        r->a = cli_render_reference(s, method, p, cam, open, r->spp_half);
        r->b = r->a ? cli_render_reference(s, method, &pb, cam, open, r->spp_half) : NULL;
        if (!r->b)
            snprintf(msg, RESTIR_MSG_LEN, "interrupted by %s while rendering the reference", cli_stop_signal_name());
    }
    if (!r->a || !r->b) {
        reference_pair_free(r);
        return -1;
    }
    const size_t n = 3 * (size_t)p->width * (size_t)p->height;
    r->mean = malloc(sizeof(float) * n);
    if (!r->mean) {
        snprintf(msg, RESTIR_MSG_LEN, "out of memory for the reference");
        reference_pair_free(r);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        r->mean[i] = (float)(0.5 * ((double)r->a[i] + (double)r->b[i]));
    return 0;
}

int reference_pair_finish(int rc_render, struct reference_pair *r, const char *out, int w, int h, char *msg)
{
    int rc = 0;
    if (rc_render != 0 || exr_write_rgb(out, r->mean, w, h, msg) != 0) {
        cli_error("%s", msg);
        rc = rc_render != 0 && cli_stop_signal ? 128 + (int)cli_stop_signal : EXIT_RUNTIME;
    } else {
        char path[4200];
        half_path(out, 'a', path, sizeof path);
        reference_checkpoint_discard(path);
        half_path(out, 'b', path, sizeof path);
        reference_checkpoint_discard(path);
    }
    reference_pair_free(r);
    return rc;
}

int reference_pair_write(const struct reference_pair *r, const char *out, int w, int h, char *msg)
{
    char pa[4200], pbp[4200];
    half_path(out, 'a', pa, sizeof pa);
    half_path(out, 'b', pbp, sizeof pbp);
    return exr_write_rgb(out, r->mean, w, h, msg) != 0 || exr_write_rgb(pa, r->a, w, h, msg) != 0 ||
                   exr_write_rgb(pbp, r->b, w, h, msg) != 0
               ? -1
               : 0;
}

int reference_pair_load_halves(const char *out, int w, int h, float **a, float **b, char *msg)
{
    char pa[4200], pbp[4200];
    half_path(out, 'a', pa, sizeof pa);
    half_path(out, 'b', pbp, sizeof pbp);
    *a = *b = NULL;
    struct stat st;
    const int has_a = stat(pa, &st) == 0, has_b = stat(pbp, &st) == 0;
    if (!has_a && !has_b)
        return 1;
    if (!has_a || !has_b) {
        snprintf(msg, RESTIR_MSG_LEN, "the reference %.300s has half %c but not half %c", out, has_a ? 'a' : 'b',
                 has_a ? 'b' : 'a');
        return -1;
    }
    if (cli_load_reference(pa, w, h, a, msg) != 0)
        return -1;
    if (cli_load_reference(pbp, w, h, b, msg) != 0) {
        free(*a);
        *a = NULL;
        return -1;
    }
    return 0;
}

int reference_pair_load(const char *path, int w, int h, int need_halves, struct reference_pair *r, char *msg)
{
    *r = (struct reference_pair){0};
    if (cli_load_reference(path, w, h, &r->mean, msg) != 0)
        return -1;
    const int got = reference_pair_load_halves(path, w, h, &r->a, &r->b, msg);
    if (got == 1 && need_halves) {
        char pa[4200];
        half_path(path, 'a', pa, sizeof pa);
        snprintf(msg, RESTIR_MSG_LEN,
                 "the reference has no halves (%.200s is missing): its own error cannot be subtracted; render it "
                 "again with its job (it was rendered before halves existed or copied without them)",
                 pa);
    }
    if (got < 0 || (got == 1 && need_halves)) {
        reference_pair_free(r);
        return got < 0 ? -1 : -2;
    }
    return 0;
}

void reference_pair_free(struct reference_pair *r)
{
    free(r->mean);
    free(r->a);
    free(r->b);
    r->mean = r->a = r->b = NULL;
}
