/* cli.c: shared command-line helpers: parsing, folders, references, progress, frame output.
 * Must never implement a rendering method. */
#include "experiments/cli.h"

#include <errno.h>
#include <omp.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/check.h"
#include "scene/scene_animation.h"
#include "scene/scene_motion.h"
#include "io/exr.h"
#include "io/png.h"
#include "methods/memory_estimate.h"
#include "methods/pt/reference.h"
#include "scene/environment.h"
#include "scene/scene_env.h"
#include "scene/scene_file.h"

void cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("restir: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

int cli_parse_int(const char *opt, const char *s, long long lo, long long hi, long long *out, char *msg)
{
    char *end = NULL;
    errno = 0;
    long long v = s ? strtoll(s, &end, 10) : 0;
    if (!s || end == s || *end != '\0' || errno != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%s expects a whole number, got '%s'", opt, s ? s : "(nothing)");
        return -1;
    }
    if (v < lo || v > hi) {
        snprintf(msg, RESTIR_MSG_LEN, "%s %lld is out of range [%lld, %lld]", opt, v, lo, hi);
        return -1;
    }
    *out = v;
    return 0;
}

int cli_edit_distance(const char *a, const char *b)
{
    int row[65];
    const int na = (int)strnlen(a, 64), nb = (int)strnlen(b, 64);
    for (int j = 0; j <= nb; j++)
        row[j] = j;
    for (int i = 1; i <= na; i++) {
        int diag = row[0]; /* row[j - 1] of the line above */
        row[0] = i;
        for (int j = 1; j <= nb; j++) {
            const int up = row[j], sub = diag + (a[i - 1] != b[j - 1]);
            const int del = up + 1, ins = row[j - 1] + 1;
            row[j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
            diag = up;
        }
    }
    return row[nb];
}

int cli_parse_res(const char *s, int *w, int *h, char *msg)
{
    long long a, b;
    char buf[64];
    const char *x = s ? strchr(s, 'x') : NULL;
    if (!x || (size_t)(x - s) >= sizeof(buf)) {
        snprintf(msg, RESTIR_MSG_LEN, "--res expects WxH (e.g. 640x360), got '%s'", s ? s : "(nothing)");
        return -1;
    }
    memcpy(buf, s, (size_t)(x - s));
    buf[x - s] = '\0';
    if (cli_parse_int("--res width", buf, 1, 16384, &a, msg) != 0 ||
        cli_parse_int("--res height", x + 1, 1, 16384, &b, msg) != 0)
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}


int cli_load_reference(const char *path, int width, int height, float **ref, char *msg)
{
    int w, h;
    if (exr_read_rgb(path, ref, &w, &h, msg) != 0)
        return -1;
    if (w != width || h != height) {
        snprintf(msg, RESTIR_MSG_LEN, "reference '%.300s' is %dx%d but the render is %dx%d", path, w, h, width,
                 height);
        free(*ref);
        *ref = NULL;
        return -1;
    }
    for (long i = 0; i < 3l * w * h; i++) {
        if (!isfinite((*ref)[i])) {
            snprintf(msg, RESTIR_MSG_LEN, "reference '%.300s' has a NaN or infinite value at pixel %ld", path, i / 3);
            free(*ref);
            *ref = NULL;
            return -1;
        }
    }
    return 0;
}

/* RESTIR_PROGRESS_SECONDS: seconds between progress lines when stderr is no terminal; "off" or a
 * negative number: none. Default PROGRESS_LINE_SECONDS. */
static double progress_interval(void)
{
    const char *e = getenv("RESTIR_PROGRESS_SECONDS");
    if (!e || !*e)
        return PROGRESS_LINE_SECONDS;
    if (!strcmp(e, "off"))
        return -1.0;
    char *end = NULL;
    const double s = strtod(e, &end);
    return end != e && *end == '\0' && s == s ? s : PROGRESS_LINE_SECONDS;
}

/* One line of progress for a log: "restir: LABEL: DONE/TOTAL (P%), Es elapsed, ETA Ts". */
static void progress_line(struct progress *pg, int done, double elapsed)
{
    const double eta = done > 0 ? elapsed * (pg->total - done) / done : 0.0;
    fprintf(stderr, "restir: %s: %d/%d (%.0f%%), %.1fs elapsed, ETA %.1fs\n", pg->label, done, pg->total,
            pg->total > 0 ? 100.0 * done / pg->total : 100.0, elapsed, eta);
    fflush(stderr);
    pg->printed = done;
    pg->t_printed = elapsed;
}

void progress_begin(struct progress *pg, const char *label, int total)
{
    pg->tty = isatty(STDERR_FILENO);
    pg->interval = pg->tty ? 0.0 : progress_interval();
    pg->enabled = pg->tty || pg->interval >= 0.0;
    pg->total = total;
    pg->t0 = omp_get_wtime();
    pg->label = label;
    pg->done = 0;
    pg->printed = 0;
    pg->t_printed = 0.0;
    progress_update(pg, 0);
}

void progress_update(struct progress *pg, int done)
{
    if (!pg->enabled)
        return;
    pg->done = done;
    if (!pg->tty) { /* a log: a line at most every interval seconds, none before the first step */
        const double elapsed = omp_get_wtime() - pg->t0;
        if (done > pg->printed && elapsed - pg->t_printed >= pg->interval)
            progress_line(pg, done, elapsed);
        return;
    }
    const int width = 30;
    int filled = pg->total > 0 ? width * done / pg->total : width;
    double elapsed = omp_get_wtime() - pg->t0;
    double eta = done > 0 ? elapsed * (pg->total - done) / done : 0.0;
    char bar[64];
    for (int k = 0; k < width; k++)
        bar[k] = k < filled ? '#' : '.';
    bar[width] = '\0';
    fprintf(stderr, "\r%-12s [%s] %d/%d  %.1fs elapsed, ETA %.1fs ", pg->label, bar, done, pg->total, elapsed,
            eta);
    fflush(stderr);
}

void progress_end(struct progress *pg)
{
    if (pg->enabled && pg->tty)
        fputc('\n', stderr);
    else if (pg->enabled && pg->printed > 0 && pg->done > pg->printed) /* a log that has lines: the last */
        progress_line(pg, pg->done, omp_get_wtime() - pg->t0);
}

int cli_write_frame(const char *dir, int frame, const struct renderer *r, char *msg)
{
    const int w = r->p.width, h = r->p.height, outputs = method_output_count(r->method);
    char path[4200];
    /* R, G, B, then the method's outputs this frame has (method.h), each a layer named as it is */
    struct exr_layer *layers = xmalloc(sizeof(struct exr_layer) * (size_t)(1 + outputs));
    layers[0] = (struct exr_layer){NULL, r->image};
    int n = 1;
    for (int k = 0; k < outputs; k++)
        if (renderer_output(r, k))
            layers[n++] = (struct exr_layer){r->method->outputs[k].name, renderer_output(r, k)};
    snprintf(path, sizeof(path), "%s/frame_%04d.exr", dir, frame);
    int rc = exr_write_layers(path, layers, n, w, h, msg);
    free(layers);
    if (rc != 0)
        return -1;
    snprintf(path, sizeof(path), "%s/frame_%04d.png", dir, frame);
    if (png_write_srgb(path, r->image, w, h, 0.0f, msg) != 0)
        return -1;
    if (r->denoised) { /* denoise=svgf|atrous: the denoised frame as files of its own (BIASED by nature) */
        struct exr_layer denoised = {NULL, r->denoised};
        snprintf(path, sizeof(path), "%s/frame_%04d_denoised.exr", dir, frame);
        if (exr_write_layers(path, &denoised, 1, w, h, msg) != 0)
            return -1;
        snprintf(path, sizeof(path), "%s/frame_%04d_denoised.png", dir, frame);
        if (png_write_srgb(path, r->denoised, w, h, 0.0f, msg) != 0)
            return -1;
    }
    /* the estimates beside it as pictures too (debug outputs stay EXR layers) */
    for (int k = 0; k < outputs; k++) {
        const struct method_output *o = &r->method->outputs[k];
        const float *px = renderer_output(r, k);
        if (!px || o->kind == METHOD_OUTPUT_DEBUG)
            continue;
        snprintf(path, sizeof(path), "%s/frame_%04d_%s.png", dir, frame, o->name);
        if ((o->kind == METHOD_OUTPUT_SIGNED ? png_write_signed(path, px, w, h, 0.0f, msg)
                                             : png_write_srgb(path, px, w, h, 0.0f, msg)) != 0)
            return -1;
    }
    return 0;
}

void cli_frame_cameras(const struct scene *s, int use_path, int frame, struct camera *cam, struct camera *open)
{
    *cam = scene_camera_at(s, use_path, (float)frame);
    *open = scene_camera_at(s, use_path, (float)(frame > 0 ? frame - 1 : frame));
    scene_set_frame(s, (float)frame); /* animated emitters: the references render frame's lights */
}

float *cli_render_reference(const struct scene *s, const struct method *method, const struct render_params *p,
                            const struct camera *cam, const struct camera *open, int spp)
{
    struct reference_accum a;
    reference_accum_init(&a, s, method, p, cam, open, spp);
    struct progress pg;
    progress_begin(&pg, "reference", spp);
    while (a.done < spp && !cli_stop_signal) {
        reference_accum_step(&a);
        progress_update(&pg, a.done);
    }
    progress_end(&pg);
    float *img = a.done == spp ? a.mean : NULL;
    if (!img)
        free(a.mean);
    free(a.chunk);
    return img;
}

void cli_command_line(const char *command, int argc, char **argv, char *out, size_t len)
{
    snprintf(out, len, "restir %s", command);
    for (int i = 0; i < argc; i++) {
        size_t used = strlen(out);
        snprintf(out + used, len - used, strchr(argv[i], ' ') ? " '%s'" : " %s", argv[i]);
    }
}

int cli_check_memory(const struct scene *s, const struct method *m, const struct render_params *p,
                     long long max_memory_mb, char *msg)
{
    double per_pixel = 0.0;
    const double need = (double)renderer_estimate_bytes(s, m, p, &per_pixel);
    return cli_check_bytes(m->name, p->width, p->height, need, per_pixel, max_memory_mb, msg);
}

int cli_check_bytes(const char *what, int width, int height, double need_bytes, double per_pixel,
                    long long max_memory_mb, char *msg)
{
    const double need = need_bytes / (1024.0 * 1024.0);
    const double have =
        max_memory_mb > 0 ? (double)max_memory_mb : (double)memory_available_bytes() / (1024.0 * 1024.0);
    if (have <= 0.0 || need <= have)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN,
             "%s at %dx%d needs about %.0f MB (%.0f bytes per pixel), more than the %.0f MB %s; lower --res%s",
             what, width, height, need, per_pixel, have,
             max_memory_mb > 0 ? "that --max-memory allows" : "this machine has available",
             max_memory_mb > 0 ? " or raise --max-memory" : "");
    return -1;
}

volatile sig_atomic_t cli_stop_signal = 0;

/* The first signal asks for a clean stop; a second one, while that stop is under way, ends the
 * process at once (the default action), for a user who will not wait for the current frame. */
static void record_stop_signal(int sig)
{
    if (cli_stop_signal) {
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    cli_stop_signal = sig;
}

const char *cli_stop_signal_name(void)
{
    return cli_stop_signal == SIGINT ? "SIGINT" : cli_stop_signal == SIGTERM ? "SIGTERM" : "no signal";
}

void cli_catch_stop_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = record_stop_signal;
    sa.sa_flags = SA_RESTART; /* a write in progress completes */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

int cli_scene_load(const struct render_params *p, const char *env, const char *name, struct scene *s, char *msg)
{
    const struct scene_load_desc desc = {.missing_textures_warn = p->missing_textures_warn != 0,
                                         .strict = p->scene_strict != 0,
                                         .no_alpha_masks = !p->alpha_masks,
                                         .flat_shading = !p->shading_normals,
                                         .ray_streams_off = !p->ray_streams};
    if (scene_load_with(name, &desc, s, msg) != 0)
        return -1;
    if (!env)
        return 0;
    struct environment *e = NULL;
    if (strcmp(env, "none") != 0) {
        e = xcalloc(1, sizeof *e);
        if (environment_load("--env", env, 1.0f, 0.0f, e, msg) != 0) {
            free(e);
            scene_destroy(s);
            return -1;
        }
    }
    char inner[RESTIR_MSG_LEN];
    if (scene_set_environment(s, e, inner) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--env %.200s: %.250s", env, inner);
        scene_destroy(s);
        return -1;
    }
    if (!s->env && s->num_emitters == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--env none: %.300s has no emitter either, so nothing would light it", name);
        scene_destroy(s);
        return -1;
    }
    return 0;
}
