/* compare_run.c: what `restir compare` and its planned form share (compare_run.h): specs, one method's
 * run, the reference, the table. Must never implement a method or call into cmd_compare.c or compare_plan.c. */
#include "experiments/compare_run.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_report.h"
#include "experiments/options.h"
#include "experiments/reference_checkpoint.h"
#include "gradient/grad_frame.h"
#include "io/atomic_file.h"
#include "io/report.h"
#include "scene/scene_file.h"

/* msg of render_params_set without its "--set" prefix, which
 * would name an option the user did not give. */
static const char *strip_set_prefix(const char *m)
{
    if (!strncmp(m, "--set: ", 7))
        return m + 7;
    if (!strncmp(m, "--set ", 6))
        return m + 6;
    return m;
}

/* Removes every "instances=N" from a spec's key=value list (colon separated, in place) into *n: the
 * row averages N independently seeded renderers (as --equal-time's instances; 002 Sec. 5 gives its
 * baselines fixed counts). Returns 0, or -1 with msg. */
static int take_instances(char *list, int *n, char *msg)
{
    char out[SPEC_MAX + 1] = "";
    size_t used = 0;
    for (char *tok = list, *next; tok; tok = next) {
        next = strchr(tok, ':');
        if (next)
            *next++ = '\0';
        if (!strncmp(tok, "instances=", 10)) {
            long long v = 0;
            if (cli_parse_int("instances", tok + 10, 1, MAX_INSTANCES, &v, msg) != 0)
                return -1;
            *n = (int)v;
            continue;
        }
        used += (size_t)snprintf(out + used, sizeof out - used, "%s%s", used ? ":" : "", tok);
    }
    memcpy(list, out, used + 1);
    return 0;
}

/* Parses spec "NAME[:key=value]..." onto common parameters. Returns 0, or -1 with msg naming the
 * spec and the problem (an unknown method, key or value). */
static int parse_spec(const char *spec, const struct render_params *common, struct compare_spec *c, char *msg)
{
    char sub[RESTIR_MSG_LEN];
    if (strlen(spec) > SPEC_MAX) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.40s...' is longer than %d characters", spec, SPEC_MAX);
        return -1;
    }
    snprintf(c->label, sizeof(c->label), "%s", spec);
    char buf[SPEC_MAX + 1];
    snprintf(buf, sizeof(buf), "%s", spec);
    char *rest = strchr(buf, ':');
    if (rest)
        *rest++ = '\0';
    const struct method *m = method_find(buf);
    if (!m) {
        if (rest)
            snprintf(msg, RESTIR_MSG_LEN, "unknown method '%s' in --methods spec '%s' (see restir list)", buf, spec);
        else
            snprintf(msg, RESTIR_MSG_LEN, "unknown method '%s' in --methods (see restir list)", buf);
        return -1;
    }
    c->method = m;
    c->p = *common;
    c->instances = 1;
    if (rest && take_instances(rest, &c->instances, sub) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.200s': %.280s", spec, sub);
        return -1;
    }
    if (rest && *rest && render_params_set_list(&c->p, rest, sub) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.200s': %.280s", spec, strip_set_prefix(sub));
        return -1;
    }
    /* One reference serves every row, so no row may change the integral it is measured against. */
    if (c->p.max_bounces != common->max_bounces || c->p.jitter != common->jitter ||
        c->p.camera_shutter != common->camera_shutter || c->p.camera_aperture != common->camera_aperture ||
        c->p.camera_focus != common->camera_focus) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "--methods spec '%.200s' changes the integrand (pt.max_bounces, jitter or a camera.* setting), "
                 "which every row "
                 "shares with the reference: give it to all rows with --set",
                 spec);
        return -1;
    }
    return 0;
}

/* Folder names from labels: every character outside [A-Za-z0-9._-] becomes '_', and a name an
 * earlier spec already took gets _2, _3, ... appended. */
static void assign_dirs(struct compare_spec *c, int n)
{
    for (int k = 0; k < n; k++) {
        char base[SPEC_MAX + 1];
        size_t len = strlen(c[k].label);
        for (size_t i = 0; i <= len; i++) {
            char ch = c[k].label[i];
            int ok = ch == '\0' || (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
                     ch == '.' || ch == '_' || ch == '-';
            base[i] = ok ? ch : '_';
        }
        snprintf(c[k].dir, sizeof(c[k].dir), "%s", base);
        for (int suffix = 2;; suffix++) {
            int taken = 0;
            for (int j = 0; j < k && !taken; j++)
                taken = !strcmp(c[j].dir, c[k].dir);
            if (!taken)
                break;
            snprintf(c[k].dir, sizeof(c[k].dir), "%s_%d", base, suffix);
        }
    }
}

int compare_budget_by_spp(const struct method *m) { return method_has(m, METHOD_BUDGET_BY_SPP); }

/* The instances average their last frames. For gradient methods the primal and gradient images
 * are averaged and then reconstructed once (002 Sec. 5, Figure 8), and the frame time counts the
 * instances' passes and one reconstruction. */
/* The instances' average image of a frame before the last (the last frame averages in place). */
static const float *instances_mean(const struct renderer *r, int instances, size_t n3, float *scratch)
{
    if (instances == 1)
        return r[0].image;
    const float inv = 1.0f / (float)instances;
    for (size_t i = 0; i < n3; i++) {
        float sum = 0.0f;
        for (int k = 0; k < instances; k++)
            sum += r[k].image[i];
        scratch[i] = sum * inv;
    }
    return scratch;
}

/* One cell of a printed table: v by fmt, or '-' right-aligned in width characters when v is NaN or
 * infinite (a metric that does not apply to the row). */
static void table_cell(char *out, size_t n, const char *fmt, int width, double v)
{
    if (isfinite(v))
        snprintf(out, n, fmt, v);
    else
        snprintf(out, n, "%*s", width, "-");
}

void compare_disoccluded_error(const float *image, const float *ref, const unsigned char *mask, size_t npix,
                               double *mape, double *share)
{
    *mape = *share = NAN;
    if (!mask)
        return;
    size_t marked = 0;
    for (size_t i = 0; i < npix; i++)
        marked += mask[i] != 0;
    *share = npix ? (double)marked / (double)npix : NAN;
    struct restir_error e;
    if (marked > 0 && restir_error_compute(image, ref, npix, mask, &e) == 0)
        *mape = e.mape;
}

int compare_run_method(const struct scene *s, const struct compare_spec *c, const struct render_params *p, int frames,
                       int instances, const float *ref, const char *out_dir, int keep_image, struct compare_track *track,
                       int run, struct compare_result *res, char *msg)
{
    const struct method *m = c->method;
    struct renderer r[MAX_INSTANCES];
    for (int k = 0; k < instances; k++) {
        struct render_params q = *p;
        q.seed = p->seed + COMPARE_INSTANCE_SEED_STRIDE * (uint64_t)k;
        renderer_init(&r[k], s, m, &q);
    }
    const size_t n3 = 3 * (size_t)p->width * (size_t)p->height;
    float *scratch = track && instances > 1 ? xmalloc(sizeof(float) * n3) : NULL;
    double ms = 0.0, ms_pass[PASS_COUNT] = {0};
    struct progress pg;
    progress_begin(&pg, c->label, frames);
    for (int f = 0; f < frames; f++) {
        if (cli_stop_signal) { /* stopped: this method's result would be incomplete, so none */
            progress_end(&pg);
            for (int k = 0; k < instances; k++)
                renderer_fini(&r[k]);
            free(scratch);
            return RUN_STOPPED;
        }
        struct camera cam = scene_camera_at(s, p->camera_path, (float)f);
        struct frame_stats st0;
        double ms_frame = 0.0;
        for (int k = 0; k < instances; k++) {
            struct frame_stats st;
            renderer_render(&r[k], f, &cam, &st);
            ms_frame += st.ms_total - (k > 0 ? st.ms[PASS_RECON_L2] + st.ms[PASS_RECON_L1] : 0.0);
            for (int q = 0; q < PASS_COUNT; q++) /* as the frame time: one reconstruction */
                ms_pass[q] += k > 0 && (q == PASS_RECON_L2 || q == PASS_RECON_L1) ? 0.0 : st.ms[q];
            if (k == 0)
                st0 = st;
        }
        ms += ms_frame;
        if (track) {
            compare_track_stats(track, f, ms_frame, &st0);
            if (f < frames - 1 && compare_track_wants_image(track, f))
                compare_track_image(track, run, f, instances_mean(r, instances, n3, scratch));
        }
        progress_update(&pg, f + 1);
    }
    progress_end(&pg);
    free(scratch);
    struct grad_frame *grad[MAX_INSTANCES] = {0};
    for (int k = 0; k < instances; k++)
        grad[k] = renderer_gradients(&r[k]);
    if (instances > 1) {
        const float inv = 1.0f / (float)instances;
        for (size_t i = 0; i < n3; i++) {
            float sum[4] = {0, 0, 0, 0};
            for (int k = 0; k < instances; k++) {
                sum[0] += r[k].image[i];
                if (grad[k]) {
                    sum[1] += grad[k]->primal[i];
                    sum[2] += grad[k]->dx[i];
                    sum[3] += grad[k]->dy[i];
                }
            }
            r[0].image[i] = sum[0] * inv;
            if (grad[0]) {
                grad[0]->primal[i] = sum[1] * inv;
                grad[0]->dx[i] = sum[2] * inv;
                grad[0]->dy[i] = sum[3] * inv;
            }
        }
        if (grad[0]) {
            struct frame_stats st;
            memset(&st, 0, sizeof(st));
            renderer_reconstruct(&r[0], &st);
        }
    }
    if (track && compare_track_wants_image(track, frames - 1))
        compare_track_image(track, run, frames - 1, r[0].image);
    res->method = m;
    res->ms_per_frame = ms / frames;
    for (int q = 0; q < PASS_COUNT; q++)
        res->ms_pass[q] = ms_pass[q] / frames;
    res->spp = compare_budget_by_spp(m) ? p->spp : 1;
    res->instances = instances;
    const size_t npix = (size_t)p->width * (size_t)p->height;
    unsigned char *mask = NULL;
    if (method_has(m, METHOD_HISTORY)) { /* the first instance's history decides (004 Sec. 6.2) */
        mask = xmalloc(npix);
        renderer_disoccluded(&r[0], DISOCCLUSION_FRAMES, mask);
    }
    res->mask = NULL;
    res->grad = NULL;
    res->grad_relmse = NAN;
    const struct grad_frame *g = grad[0];
    if (ref) { /* a planned job measures nothing: the merge does, from the frame, mask and gradients it writes */
        restir_error_compute(r[0].image, ref, npix, NULL, &res->err);
        compare_disoccluded_error(r[0].image, ref, mask, npix, &res->mape_dis, &res->dis_share);
        if (g)
            res->grad_relmse = restir_gradient_relmse(g->dx, g->dy, ref, p->width, p->height);
        free(mask);
    } else {
        res->mask = mask;
        if (g) {
            res->grad = xmalloc(2 * sizeof(float) * n3);
            memcpy(res->grad, g->dx, sizeof(float) * n3);
            memcpy(res->grad + n3, g->dy, sizeof(float) * n3);
        }
    }
    res->image = NULL;
    if (keep_image) {
        res->image = xmalloc(sizeof(float) * n3);
        memcpy(res->image, r[0].image, sizeof(float) * n3);
    }
    if (run > 0) { /* a later run is measured only: run 0's frame is the one written */
        for (int k = 0; k < instances; k++)
            renderer_fini(&r[k]);
        return 0;
    }
    char path[4400];
    snprintf(path, sizeof(path), "%s/%s", out_dir, c->dir);
    int rc = io_make_dirs(path, msg);
    if (rc == 0)
        rc = cli_write_frame(path, frames - 1, &r[0], msg);
    for (int k = 0; k < instances; k++)
        renderer_fini(&r[k]);
    return rc;
}

static void compare_usage(void)
{
    printf("usage: restir compare --scene NAME --methods SPEC,SPEC,... [--equal-time] [--frames N] [--res WxH]\n"
               "                      [--ref FILE.exr | --ref-spp N] [--camera static|path] [--out DIR] [--report]\n"
               "                      [--seed N] [--threads N] [--runs N] [--ref-every K] [--set key=value]...\n"
               "Each SPEC is NAME[:key=value]...: method NAME (see restir list) with the command's parameters,\n"
               "then each key=value applied as by --set (see restir render --help) for that row only, e.g.\n"
               "  --methods 'restir-pt,restir-pt:mis=balance:spatial.neighbors=5,pt'\n"
               "The key instances=N (1-16) makes the row average N independently seeded renderers (as\n"
               "--equal-time does; 002 Sec. 5 gives its baselines such fixed counts).\n"
               "The whole SPEC labels its row. Runs each SPEC for N frames (default 1) and measures the last\n"
               "frame against the reference, rendered from the common parameters with --ref-spp paths\n"
               "(default 1024) when --ref is absent. With --equal-time every row gets the frame time of the\n"
               "first SPEC other than pt (gradient methods: L2 reconstruction included, 002 Sec. 5): pt and\n"
               "gpt get as many paths per pixel as fit, the other methods average as many independently\n"
               "seeded instances as fit (gradient methods average primal and gradients, then reconstruct\n"
               "once). When DI methods are compared, pt estimates direct lighting only (1 bounce), like them.\n"
               "Writes DIR/compare.csv (method = the SPEC, ms per frame, spp, instances, relmse, mape, smape,\n"
               "luma_rmse, runs, temporal_cov, and with --runs the standard errors relmse_sem, mape_sem,\n"
               "smape_sem; then mape_disoccluded, its mape_disoccluded_sem and disoccluded_share: 004 Sec.\n"
               "6.2's MAPE over the pixels whose history was rejected in any of the last 4 frames, for the\n"
               "methods with a G-buffer history; then gradient_relmse and gradient_relmse_sem for the gradient\n"
               "methods: the relMSE of the last frame's estimated forward differences against the reference's,\n"
               "our measure of 002 Fig. 7's gradient images, defined in restir render --help)\n"
               "and each row's last frame to DIR/FOLDER/, where FOLDER is the SPEC with every character other\n"
               "than A-Z a-z 0-9 . _ - replaced by _ (and _2, _3, ... appended when two SPECs give the same\n"
               "name). Default DIR: out/compare-SCENE.\n"
               "DIR/frames.csv has a row per SPEC and frame: frame time, temporal pass time, the shares of\n"
               "valid pixels whose history shifted in (temporal_accept) and, for path reservoirs, that were\n"
               "offered / took a backprojected or a splatted candidate (as restir render's metrics.csv), and\n"
               "the error of the frames that have a reference: the last, and with --ref-every K also frames\n"
               "K-1, 2K-1, ..., each against its own reference (--ref-spp paths from that frame's camera;\n"
               "--ref gives the last frame's only).\n"
               "--runs N (default 1) runs every SPEC as N independently seeded sequences: errors are means\n"
               "over the runs with their standard errors (sd / sqrt N, printed after +-), and temporal_cov\n"
               "is 000's relative autocovariance (Appendix A, Eq. 17) at a lag of 3 frames over the second\n"
               "half of the frames (at least 8 frames); run 0's frames are the ones written, and the times\n"
               "are the fastest run's (runs on a shared machine only ever get slower). --plan DIR makes\n"
               "each SPEC's run a job of its own; the merge then has the same errors and standard errors, but\n"
               "no temporal_cov (it needs every run's frame sequence). --ref-every and --equal-time cannot be\n"
               "planned.\n"
               "--report also writes DIR/index.html: one self-contained page (no network) with the command,\n"
               "commit and machine, the table, a relMSE plot, every image beside the reference in a viewer\n"
               "(synchronized zoom and pan, A/B flip), relative-error heat maps and the crops where the first\n"
               "two methods differ most.\n");
    cli_options_help(stdout, "compare");
}

int compare_setup(int argc, char **argv, struct compare_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    struct cli_options *o = &st->o;
    if (cli_parse_options("compare", argc, argv, o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o->help) {
        compare_usage();
        return -1;
    }
    if (!o->methods) {
        cli_error("--methods SPEC,SPEC,... is required (see restir list)");
        return EXIT_USAGE;
    }
    char list[MAX_METHODS * (SPEC_MAX + 1) + 64];
    if (strlen(o->methods) >= sizeof(list)) {
        cli_error("--methods is longer than %zu characters", sizeof(list) - 1);
        return EXIT_USAGE;
    }
    snprintf(list, sizeof(list), "%s", o->methods);
    st->n = 0;
    for (char *tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        if (st->n == MAX_METHODS) {
            cli_error("--methods lists more than %d methods", MAX_METHODS);
            return EXIT_USAGE;
        }
        if (parse_spec(tok, &o->params, &st->specs[st->n], msg) != 0) {
            cli_error("%s", msg);
            return EXIT_USAGE;
        }
        st->n++;
    }
    if (st->n == 0) {
        cli_error("--methods lists no method (see restir list)");
        return EXIT_USAGE;
    }
    for (int k = 0; k < st->n && o->equal_time; k++)
        if (st->specs[k].instances != 1) {
            cli_error("--methods spec '%s': instances= and --equal-time both set a row's instances; give one",
                      st->specs[k].label);
            return EXIT_USAGE;
        }
    st->p = o->params;
    st->integrand = st->specs[0].method;
    for (int k = st->n - 1; k >= 0; k--)
        if (method_has(st->specs[k].method, METHOD_DIRECT_ONLY))
            st->integrand = st->specs[k].method;
    method_reference_params(st->integrand, &st->p); /* pt estimates the same integral */
    for (int k = 0; k < st->n; k++) {
        method_reference_params(st->integrand, &st->specs[k].p); /* as for --set */
        if (render_params_validate(&st->specs[k].p, msg) != 0) {
            cli_error("--methods spec '%s': %s", st->specs[k].label, msg);
            return EXIT_USAGE;
        }
    }
    assign_dirs(st->specs, st->n);
    if (cli_scene_load(&o->params, o->env, o->scene, &st->s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    for (int k = 0; k < st->n; k++) { /* each method's renderers exist one at a time */
        if (method_check_settings(st->specs[k].method, &st->specs[k].p, &st->s, msg) != 0) {
            cli_error("--methods spec '%s': %s", st->specs[k].label, msg);
            scene_destroy(&st->s);
            return EXIT_USAGE;
        }
        if (cli_check_memory(&st->s, st->specs[k].method, &st->specs[k].p, o->max_memory_mb, msg) != 0) {
            cli_error("--methods spec '%s': %s", st->specs[k].label, msg);
            scene_destroy(&st->s);
            return EXIT_RUNTIME;
        }
    }
    if (o->params.threads > 0)
        omp_set_num_threads(o->params.threads);
    return 0;
}

void compare_runs_add(struct compare_runs *a, const struct compare_result *r)
{
    const struct restir_error *e = &r->err;
    const double x[7] = {e->relmse, e->mape, e->smape, e->luma_rmse, r->mape_dis, r->dis_share, r->grad_relmse};
    a->n++;
    for (int k = 0; k < 7; k++)
        running_mean_add(&a->m[k], x[k]);
}

void compare_runs_finish(const struct compare_runs *a, struct compare_result *res)
{
    const int runs = a->n;
    double sem[7];
    for (int k = 0; k < 7; k++)
        sem[k] = running_mean_sem(&a->m[k]);
    if (runs > 1) { /* one run keeps its error bit for bit */
        res->err = (struct restir_error){a->m[0].mean, a->m[1].mean, a->m[2].mean, a->m[3].mean};
        res->mape_dis = a->m[4].mean;
        res->dis_share = a->m[5].mean;
        res->grad_relmse = a->m[6].mean;
    }
    res->sem = (struct restir_error){sem[0], sem[1], sem[2], sem[3]};
    res->mape_dis_sem = sem[4];
    res->grad_relmse_sem = sem[6];
    res->runs = runs;
}

void compare_keep_fastest(struct compare_result *res, const struct compare_result *run)
{
    if (run->ms_per_frame < res->ms_per_frame) {
        res->ms_per_frame = run->ms_per_frame;
        memcpy(res->ms_pass, run->ms_pass, sizeof res->ms_pass);
    }
}

int compare_run_spec(const struct scene *s, const struct compare_spec *c, const struct render_params *p, int frames,
                     int instances, int runs, const float *ref, const char *out_dir, int keep_image,
                     struct compare_track *track, struct compare_result *res, char *msg)
{
    struct compare_runs acc = {0};
    if (track)
        compare_track_begin(track);
    for (int n = 0; n < runs; n++) {
        struct render_params q = *p;
        q.seed = compare_run_seed(p->seed, n);
        struct compare_result one;
        int rc = compare_run_method(s, c, &q, frames, instances, ref, out_dir, n == 0 && keep_image, track, n,
                                    n == 0 ? res : &one, msg);
        if (rc != 0) {
            if (n > 0) {
                free(res->image);
                res->image = NULL;
            }
            return rc;
        }
        compare_runs_add(&acc, n == 0 ? res : &one);
        if (n > 0)
            compare_keep_fastest(res, &one);
    }
    compare_runs_finish(&acc, res);
    res->temporal_cov = track ? compare_track_end(track, c->label) : NAN;
    return 0;
}

float *compare_render_reference(const struct compare_setup *st)
{
    return compare_render_reference_at(st, st->o.frames - 1);
}

/* What the reference at frame `frame` renders: its params and cameras. */
static const struct method *reference_inputs(const struct compare_setup *st, int frame, struct render_params *rp,
                                       struct camera *cam, struct camera *open)
{
    *rp = st->p;
    /* independent of the compared runs and of the other frames' references */
    rp->seed = reference_seed(st->p.seed);
    if (frame != st->o.frames - 1)
        rp->seed += 0x2545F4914F6CDD1Dull * (uint64_t)(frame + 1);
    cli_frame_cameras(&st->s, st->p.camera_path, frame, cam, open);
    return st->integrand;
}

float *compare_render_reference_at(const struct compare_setup *st, int frame)
{
    struct render_params rp;
    struct camera cam, open;
    const struct method *m = reference_inputs(st, frame, &rp, &cam, &open);
    return cli_render_reference(&st->s, m, &rp, &cam, &open, st->o.ref_spp);
}

float *compare_render_reference_resumable(const struct compare_setup *st, const char *out, char *msg)
{
    struct render_params rp;
    struct camera cam, open;
    const struct method *m = reference_inputs(st, st->o.frames - 1, &rp, &cam, &open);
    return reference_render_resumable(&st->s, m, &rp, &cam, &open, st->o.ref_spp, out, msg);
}

/* DIR/passes.csv: each row's mean time per frame of every pass (the fastest run; its instances summed, one
 * reconstruction), the breakdown of 004 Table 2 and 000 Table 1. Returns 0, or -1 with msg. */
static int write_passes(const char *out_dir, const struct compare_spec *specs, const struct compare_result *res, int n,
                        char *msg)
{
    char path[4200], header[1024] = "method";
    size_t used = strlen(header);
    for (int q = 0; q < PASS_COUNT; q++)
        used += (size_t)snprintf(header + used, sizeof header - used, ",%s", pass_names[q]);
    snprintf(path, sizeof path, "%s/passes.csv", out_dir);
    struct csv_writer csv;
    if (csv_open(&csv, path, header, msg) != 0)
        return -1;
    for (int k = 0; k < n; k++) {
        char row[2048];
        csv_field(row, sizeof row, specs[k].label);
        used = strlen(row);
        for (int q = 0; q < PASS_COUNT; q++)
            used += (size_t)snprintf(row + used, sizeof row - used, ",%.4f", res[k].ms_pass[q]);
        csv_row(&csv, "%s", row);
    }
    return csv_close(&csv, msg);
}

int compare_write_table(const struct compare_setup *st, const char *out_dir, const char *command,
                        const struct compare_result *res, const float *ref)
{
    char msg[RESTIR_MSG_LEN];
    const struct cli_options *o = &st->o;
    const struct render_params *p = &st->p;
    const struct compare_spec *specs = st->specs;
    const int n = st->n;
    int rc = 0;
    char csv_path[4200];
    snprintf(csv_path, sizeof(csv_path), "%s/compare.csv", out_dir);
    struct csv_writer csv;
    if (csv_open(&csv, csv_path,
                 "method,ms_per_frame,spp,instances,relmse,mape,smape,luma_rmse,runs,temporal_cov,relmse_sem,mape_sem,"
                 "smape_sem,mape_disoccluded,mape_disoccluded_sem,disoccluded_share,gradient_relmse,gradient_relmse_sem",
                 msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    int w = 12;
    for (int k = 0; k < n; k++)
        if ((int)strlen(specs[k].label) > w)
            w = (int)strlen(specs[k].label);
    printf("%s, %dx%d, %s camera, error at frame %d%s:\n", o->scene, p->width, p->height,
           p->camera_path ? "moving" : "static", o->frames - 1, o->equal_time ? ", equal time" : "");
    const int runs = o->runs > 1;
    int any_grad = 0; /* a gradient method's row: the table gets 002 Fig. 7's gradient relMSE */
    for (int k = 0; k < n; k++)
        any_grad |= isfinite(res[k].grad_relmse);
    if (runs)
        printf("(errors: means of %d independently seeded runs, +- their standard error; tcov: 000 Eq. 17 at lag %d "
               "over frames %d-%d)\n",
               o->runs, COMPARE_COV_LAG, o->frames / 2, o->frames - 1);
    printf("%-*s %10s %6s %5s %12s%s %10s%s %8s%s %12s %10s%s %6s%s%s%s\n", w, "method", "ms/frame", "spp", "inst",
           "relMSE", runs ? "       +-" : "", "MAPE", runs ? "       +-" : "", "SMAPE", runs ? "     +-" : "",
           "relMSE/first", "MAPE dis", runs ? "       +-" : "", "dis", runs ? "         tcov" : "",
           any_grad ? "  grad relMSE" : "", any_grad && runs ? "       +-" : "");
    for (int k = 0; k < n; k++) {
        const struct compare_result *c = &res[k];
        /* a metric that does not apply to the row (no history, no gradients, one run) prints '-' */
        char tcov[32] = "", se[4][32] = {"", "", "", ""}, grad[2][32] = {"", ""}, dis[2][32];
        if (any_grad)
            table_cell(grad[0], sizeof grad[0], " %12.5g", 13, c->grad_relmse);
        if (any_grad && runs)
            table_cell(grad[1], sizeof grad[1], " %8.2g", 9, c->grad_relmse_sem);
        if (runs) {
            table_cell(tcov, sizeof tcov, " %12.5g", 13, c->temporal_cov);
            table_cell(se[0], sizeof se[0], " %8.2g", 9, c->sem.relmse);
            table_cell(se[1], sizeof se[1], " %8.2g", 9, c->sem.mape);
            table_cell(se[2], sizeof se[2], " %6.2g", 7, c->sem.smape);
            table_cell(se[3], sizeof se[3], " %8.2g", 9, c->mape_dis_sem);
        }
        table_cell(dis[0], sizeof dis[0], " %10.5g", 11, c->mape_dis);
        table_cell(dis[1], sizeof dis[1], " %6.3f", 7, c->dis_share);
        printf("%-*s %10.2f %6d %5d %12.5g%s %10.5g%s %8.3f%s %12.3f%s%s%s%s%s%s\n", w, specs[k].label,
               c->ms_per_frame, c->spp, c->instances, c->err.relmse, se[0], c->err.mape, se[1], c->err.smape, se[2],
               res[0].err.relmse > 0 ? c->err.relmse / res[0].err.relmse : 0.0, dis[0], se[3], dis[1], tcov, grad[0],
               grad[1]);
        if (rc == 0) {
            char field[2 * SPEC_MAX + 4], cov[32] = "", sem[4][32] = {"", "", "", ""}, dis[2][32] = {"", ""},
                                          gr[2][32] = {"", ""};
            csv_field(field, sizeof(field), specs[k].label);
            if (isfinite(c->temporal_cov))
                snprintf(cov, sizeof cov, "%.6g", c->temporal_cov);
            if (c->runs > 1) {
                snprintf(sem[0], sizeof sem[0], "%.6g", c->sem.relmse);
                snprintf(sem[1], sizeof sem[1], "%.6g", c->sem.mape);
                snprintf(sem[2], sizeof sem[2], "%.6g", c->sem.smape);
                if (isfinite(c->mape_dis_sem))
                    snprintf(sem[3], sizeof sem[3], "%.6g", c->mape_dis_sem);
            }
            if (isfinite(c->mape_dis))
                snprintf(dis[0], sizeof dis[0], "%.6g", c->mape_dis);
            if (isfinite(c->dis_share))
                snprintf(dis[1], sizeof dis[1], "%.6g", c->dis_share);
            if (isfinite(c->grad_relmse))
                snprintf(gr[0], sizeof gr[0], "%.6g", c->grad_relmse);
            if (c->runs > 1 && isfinite(c->grad_relmse_sem))
                snprintf(gr[1], sizeof gr[1], "%.6g", c->grad_relmse_sem);
            csv_row(&csv, "%s,%.3f,%d,%d,%.6g,%.6g,%.6g,%.6g,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s", field, c->ms_per_frame,
                    c->spp, c->instances, c->err.relmse, c->err.mape, c->err.smape, c->err.luma_rmse,
                    c->runs > 0 ? c->runs : 1, cov, sem[0], sem[1], sem[2], dis[0], sem[3], dis[1], gr[0], gr[1]);
        }
    }
    if (rc == 0 && csv_close(&csv, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0 && write_passes(out_dir, specs, res, n, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0 && o->report) {
        char pngs[MAX_METHODS][SPEC_MAX + 40];
        struct compare_report_method rm[MAX_METHODS];
        for (int k = 0; k < n; k++) {
            snprintf(pngs[k], sizeof pngs[k], "%s/frame_%04d.png", specs[k].dir, o->frames - 1);
            rm[k] = (struct compare_report_method){specs[k].label, pngs[k], specs[k].dir, res[k].image,
                                                   res[k].ms_per_frame, res[k].spp, res[k].instances, res[k].err};
        }
        const struct compare_report_run run = {out_dir, command, st->s.name, p->width, p->height, o->frames - 1,
                                               p->camera_path, o->equal_time, ref};
        if (compare_write_report(&run, n, rm, msg) != 0) {
            cli_error("--report: %s", msg);
            rc = EXIT_RUNTIME;
        }
    }
    if (rc == 0)
        printf("output: %s%s\n", out_dir, o->report ? " (report: index.html)" : "");
    return rc;
}
