/* cmd_compare.c: `restir compare`: runs several methods on the same frames against one
 * reference, optionally at equal time, and writes a table and compare.csv.
 * Must never implement a method: it drives the renderer. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "core/check.h"
#include "io/image_io.h"
#include "io/report.h"
#include "options.h"

#define MAX_METHODS 8

struct compare_result {
    enum method_id method;
    double ms_per_frame;
    int spp;
    struct restir_error err; /* of the last frame */
};

/* Runs `frames` frames of a method and measures the last frame against ref. Returns 0, or -1
 * with msg when its last frame cannot be written to out_dir/METHOD. */
static int run_method(const struct scene *s, enum method_id m, const struct render_params *p, int frames,
                      const float *ref, const char *out_dir, struct compare_result *res, char *msg)
{
    struct renderer r;
    renderer_init(&r, s, m, p);
    double ms = 0.0;
    struct progress pg;
    progress_begin(&pg, method_table[m].name, frames);
    for (int f = 0; f < frames; f++) {
        struct frame_stats st;
        struct camera cam = scene_camera_at(s, p->camera_path, (float)f);
        renderer_render(&r, f, &cam, &st);
        ms += st.ms_total;
        progress_update(&pg, f + 1);
    }
    progress_end(&pg);
    res->method = m;
    res->ms_per_frame = ms / frames;
    res->spp = m == METHOD_PT ? p->spp : 1;
    restir_error_compute(r.image, ref, (size_t)p->width * (size_t)p->height, NULL, &res->err);
    char path[4300];
    snprintf(path, sizeof(path), "%s/%s", out_dir, method_table[m].name);
    int rc = cli_make_dir(path, msg);
    if (rc == 0)
        rc = cli_write_frame(path, frames - 1, r.image, p->width, p->height, msg);
    renderer_fini(&r);
    return rc;
}

/* Paths per pixel that fit in budget_ms, from a 1-spp and a 4-spp timing (the difference
 * removes fixed per-frame cost). */
static int pt_spp_for_budget(const struct scene *s, const struct render_params *p, double budget_ms)
{
    struct render_params q = *p;
    struct renderer r;
    struct frame_stats st;
    struct camera cam = scene_camera_at(s, p->camera_path, 0.0f);
    q.spp = 1;
    renderer_init(&r, s, METHOD_PT, &q);
    renderer_render(&r, 0, &cam, &st); /* warm-up */
    renderer_render(&r, 0, &cam, &st);
    double t1 = st.ms_total;
    renderer_fini(&r);
    q.spp = 4;
    renderer_init(&r, s, METHOD_PT, &q);
    renderer_render(&r, 0, &cam, &st);
    double t4 = st.ms_total;
    renderer_fini(&r);
    double per_spp = (t4 - t1) / 3.0 > 0.25 * t1 ? (t4 - t1) / 3.0 : t1;
    double fixed = t1 - per_spp > 0.0 ? t1 - per_spp : 0.0;
    int spp = (int)((budget_ms - fixed) / per_spp);
    return spp < 1 ? 1 : spp;
}

int cmd_compare(int argc, char **argv)
{
    struct cli_options o;
    char msg[RESTIR_MSG_LEN];
    if (cli_parse_options("compare", argc, argv, &o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o.help) {
        printf("usage: restir compare --scene NAME --methods a,b,... [--equal-time] [--frames N] [--res WxH]\n"
               "                      [--ref FILE.exr | --ref-spp N] [--camera static|path] [--out DIR]\n"
               "                      [--seed N] [--threads N] [--set key=value]...\n"
               "Runs each method for N frames (default 1) and measures the last frame against the reference\n"
               "(rendered with --ref-spp paths, default 1024, when --ref is absent). With --equal-time every\n"
               "method gets the frame time of the first ReSTIR method: pt gets as many paths per pixel as fit.\n"
               "When DI methods are compared, pt estimates direct lighting only (1 bounce), like them.\n"
               "Writes DIR/compare.csv (method, ms per frame, spp, relmse, mape, smape, luma_rmse) and each\n"
               "method's last frame to DIR/METHOD/. Default DIR: out/compare-SCENE.\n");
        return 0;
    }
    if (!o.methods) {
        cli_error("--methods a,b,... is required (see restir list)");
        return EXIT_USAGE;
    }
    enum method_id methods[MAX_METHODS];
    int n = 0, any_direct = 0;
    char list[1024];
    snprintf(list, sizeof(list), "%s", o.methods);
    for (char *tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        int m = method_find(tok);
        if (m < 0) {
            cli_error("unknown method '%s' in --methods (see restir list)", tok);
            return EXIT_USAGE;
        }
        if (n == MAX_METHODS) {
            cli_error("--methods lists more than %d methods", MAX_METHODS);
            return EXIT_USAGE;
        }
        methods[n++] = (enum method_id)m;
        any_direct |= method_table[m].direct_only;
    }
    if (n == 0) {
        cli_error("--methods lists no method (see restir list)");
        return EXIT_USAGE;
    }
    struct scene s;
    if (scene_create_builtin(o.scene, &s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o.params.threads > 0)
        omp_set_num_threads(o.params.threads);
    struct render_params p = o.params;
    if (any_direct)
        renderer_reference_params(METHOD_RESTIR_DI, &p); /* pt estimates the same integral */
    char out_dir[4096];
    snprintf(out_dir, sizeof(out_dir), "%s", o.out ? o.out : "");
    if (!o.out)
        snprintf(out_dir, sizeof(out_dir), "out/compare-%s", o.scene);
    float *ref = NULL;
    int rc = 0;
    if (o.ref) {
        if (cli_load_reference(o.ref, p.width, p.height, &ref, msg) != 0)
            rc = EXIT_RUNTIME;
    } else {
        struct render_params rp = p;
        rp.seed = p.seed ^ 0x7265666572656e63ull; /* independent of the compared runs */
        struct camera cam = scene_camera_at(&s, p.camera_path, (float)(o.frames - 1));
        ref = cli_render_reference(&s, any_direct ? METHOD_RESTIR_DI : METHOD_PT, &rp, &cam, o.ref_spp);
    }
    if (rc == 0 && cli_make_dir(out_dir, msg) != 0)
        rc = EXIT_RUNTIME;
    if (rc != 0) {
        cli_error("%s", msg);
        free(ref);
        scene_destroy(&s);
        return rc;
    }
    char ref_path[4200];
    snprintf(ref_path, sizeof(ref_path), "%s/reference.exr", out_dir);
    if (!o.ref && exr_write_rgb(ref_path, ref, p.width, p.height, msg) != 0)
        cli_error("warning: %s", msg);

    /* ReSTIR methods first: the first of them sets the equal-time budget. */
    struct compare_result res[MAX_METHODS];
    double budget = -1.0;
    for (int k = 0; k < n; k++) {
        if (methods[k] == METHOD_PT)
            continue;
        if (run_method(&s, methods[k], &p, o.frames, ref, out_dir, &res[k], msg) != 0) {
            rc = EXIT_RUNTIME;
            break;
        }
        if (budget < 0.0)
            budget = res[k].ms_per_frame;
    }
    for (int k = 0; k < n && rc == 0; k++) {
        if (methods[k] != METHOD_PT)
            continue;
        struct render_params q = p;
        if (o.equal_time && budget > 0.0)
            q.spp = pt_spp_for_budget(&s, &p, budget);
        if (run_method(&s, methods[k], &q, o.frames, ref, out_dir, &res[k], msg) != 0)
            rc = EXIT_RUNTIME;
    }
    if (rc != 0) {
        cli_error("%s", msg);
        free(ref);
        scene_destroy(&s);
        return rc;
    }

    char csv_path[4200];
    snprintf(csv_path, sizeof(csv_path), "%s/compare.csv", out_dir);
    struct csv_writer csv;
    if (csv_open(&csv, csv_path, "method,ms_per_frame,spp,relmse,mape,smape,luma_rmse", msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    printf("%s, %dx%d, %s camera, error at frame %d%s:\n", o.scene, p.width, p.height,
           p.camera_path ? "moving" : "static", o.frames - 1, o.equal_time ? ", equal time" : "");
    printf("%-12s %10s %6s %12s %10s %8s %12s\n", "method", "ms/frame", "spp", "relMSE", "MAPE", "SMAPE",
           "relMSE/first");
    for (int k = 0; k < n; k++) {
        const struct compare_result *c = &res[k];
        printf("%-12s %10.2f %6d %12.5g %10.5g %8.3f %12.3f\n", method_table[c->method].name, c->ms_per_frame,
               c->spp, c->err.relmse, c->err.mape, c->err.smape,
               res[0].err.relmse > 0 ? c->err.relmse / res[0].err.relmse : 0.0);
        if (rc == 0)
            csv_row(&csv, "%s,%.3f,%d,%.6g,%.6g,%.6g,%.6g", method_table[c->method].name, c->ms_per_frame, c->spp,
                    c->err.relmse, c->err.mape, c->err.smape, c->err.luma_rmse);
    }
    if (rc == 0 && csv_close(&csv, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0)
        printf("output: %s\n", out_dir);
    free(ref);
    scene_destroy(&s);
    return rc;
}
