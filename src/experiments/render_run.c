/* render_run.c: `restir render`'s run (render_run.h): frames of one method, with per-frame metrics,
 * metrics.csv and summary.json. Must never implement a method: it drives the renderer. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "experiments/render_run.h"

#include <limits.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/settings_file.h"
#include "experiments/out_dir.h"
#include "experiments/provenance.h"
#include "experiments/reference_size.h"
#include "experiments/run_prepare.h"
#include "io/atomic_file.h"
#include "io/report.h"
#include "methods/settings.h"
#include "scene/scene_file.h"
#include "scene/scenes_builtin.h"

/* What ran, so that `restir render --params summary.json` runs it again: scene, method, frames,
 * resolution, seed, camera, and every setting of the table as the renderer used it; and the build
 * that ran it. */
static cJSON *params_json(const struct cli_options *o, const struct method *method)
{
    struct render_params p = o->params;
    method_params(method, &p); /* what the renderer ran with */
    cJSON *j = cJSON_CreateObject();
    char scene[PATH_MAX], camera[PATH_MAX]; /* files by absolute path: --params may run elsewhere */
    if (scene_is_builtin(o->scene) || !realpath(o->scene, scene))
        snprintf(scene, sizeof(scene), "%s", o->scene);
    cJSON_AddStringToObject(j, "scene", scene);
    cJSON_AddStringToObject(j, "method", o->method);
    cJSON_AddNumberToObject(j, "width", p.width);
    cJSON_AddNumberToObject(j, "height", p.height);
    cJSON_AddNumberToObject(j, "frames", o->frames);
    char seed[32];
    snprintf(seed, sizeof(seed), "%llu", (unsigned long long)p.seed);
    if (p.seed <= (1ull << 53)) /* a JSON number holds it exactly */
        cJSON_AddItemToObject(j, "seed", cJSON_CreateRaw(seed));
    else
        cJSON_AddStringToObject(j, "seed", seed);
    if (o->camera_file && !realpath(o->camera_file, camera))
        snprintf(camera, sizeof(camera), "%s", o->camera_file);
    cJSON_AddStringToObject(j, "camera", o->camera_file ? camera : p.camera_path ? "path" : "static");
    if (o->env) { /* --env, by absolute path, so that --params replays the same light */
        char env[4096];
        if (strcmp(o->env, "none") == 0 || !realpath(o->env, env))
            snprintf(env, sizeof(env), "%s", o->env);
        cJSON_AddStringToObject(j, "env", env);
    }
    cJSON_AddItemToObject(j, "settings", settings_json(&p));
    char biased[RESTIR_MSG_LEN];
    render_params_biased(&p, biased, sizeof(biased));
    cJSON_AddStringToObject(j, "biased", biased); /* BIASED settings in effect; empty: none */
    if (p.denoise.method > 0) /* a layer of its own: the frame's estimator is as "biased" says */
        cJSON_AddStringToObject(j, "denoised", "frame_NNNN_denoised.*: BIASED by nature (a denoiser)");
    struct provenance build; /* which build ran it (version, commit, machine, date); --params ignores it */
    provenance_now(&build, p.threads > 0 ? p.threads : omp_get_max_threads());
    cJSON_AddItemToObject(j, "provenance", provenance_to_json(&build));
    return j;
}

/* Appends n fields ",v" of metrics.csv to out (len bytes): the values when have, else empty ones. */
static void error_fields(char *out, size_t len, const double *v, int n, int have)
{
    for (int k = 0; k < n; k++) {
        const size_t used = strlen(out);
        if (have)
            snprintf(out + used, len - used, ",%.6g", v[k]);
        else
            snprintf(out + used, len - used, ",");
    }
}

static void errors_add(struct restir_metrics_error *sum, const struct restir_metrics_error *e)
{
    sum->relmse += e->relmse;
    sum->mape += e->mape;
    sum->smape += e->smape;
    sum->luma_rmse += e->luma_rmse;
}

/* j[name] = {relmse, mape, smape[, luma_rmse]} of e divided by n (a sum over n frames). */
static void add_errors(cJSON *j, const char *name, const struct restir_metrics_error *e, double n, int luma)
{
    cJSON *o = cJSON_AddObjectToObject(j, name);
    cJSON_AddNumberToObject(o, "relmse", e->relmse / n);
    cJSON_AddNumberToObject(o, "mape", e->mape / n);
    cJSON_AddNumberToObject(o, "smape", e->smape / n);
    if (luma)
        cJSON_AddNumberToObject(o, "luma_rmse", e->luma_rmse / n);
}

int render_run(const struct cli_options *desc)
{
    struct cli_options o = *desc;
    char msg[RESTIR_MSG_LEN];
    struct scene s;
    const struct method *method;
    int rc = o.out ? out_dir_check("--out", o.out, o.force, msg) : 0;
    /* --ref without --res (or --params): the reference's size */
    if (rc == 0 && o.ref && reference_size_adopt(o.ref, o.res_given || o.params_scene[0], &o.params, msg) != 0)
        rc = EXIT_RUNTIME;
    if (rc != 0) {
        cli_error("%s", msg);
        return rc;
    }
    if (!(method = run_find_method(o.method)))
        return EXIT_USAGE;
    rc = run_prepare(&o, method, RUN_CHECK_SETS | RUN_CHECK_MEMORY, &s);
    if (rc != 0)
        return rc;
    struct camera *cams = NULL; /* --camera FILE: one per frame */
    int ncams = 0;
    if (o.camera_file) {
        if (scene_cameras_load(o.camera_file, &cams, &ncams, msg) != 0 ||
            (o.frames_given && o.frames > ncams &&
             snprintf(msg, RESTIR_MSG_LEN, "%.300s holds %d cameras, --frames asks for %d", o.camera_file, ncams,
                      o.frames) > 0)) {
            cli_error("%s", msg);
            scene_destroy(&s);
            return EXIT_USAGE;
        }
        if (!o.frames_given)
            o.frames = ncams;
    }
    char out_dir[4096], base[4096];
    snprintf(base, sizeof(base), "out/%s-%s", s.name, o.method); /* without --out: a new folder each run */
    float *ref = NULL;
    if (o.ref && cli_load_reference(o.ref, o.params.width, o.params.height, &ref, msg) != 0) {
        cli_error("%s", msg);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    if (out_dir_open(o.out, base, o.force, out_dir, sizeof(out_dir), msg) != 0) {
        cli_error("%s", msg);
        free(cams);
        free(ref);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    char csv_path[4200], json_path[4200];
    snprintf(csv_path, sizeof(csv_path), "%s/metrics.csv", out_dir);
    snprintf(json_path, sizeof(json_path), "%s/summary.json", out_dir);
    /* One ms_<pass> column per pass id (methods/passes.h), in id order: today's, then the methods' own. */
    char header[2048] = "frame,ms_total";
    for (int q = 0; q < pass_count(); q++)
        snprintf(header + strlen(header), sizeof(header) - strlen(header), ",ms_%s", pass_name(q));
    snprintf(header + strlen(header), sizeof(header) - strlen(header), "%s",
             ",rays,mrays_per_s,temporal_accept,bp_received,bp_accepted,splat_received,splat_accepted,"
             "disoccluded,relmse,mape,smape,luma_rmse,mape_disoccluded,relmse_denoised,mape_denoised,"
             "smape_denoised,denoise_passed,denoise_reset,ms_write,nonfinite");
    struct csv_writer csv;
    if (csv_open(&csv, csv_path, header, msg) != 0) {
        cli_error("%s", msg);
        free(ref);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    struct renderer r;
    renderer_init(&r, &s, method, &o.params);
    struct progress pg;
    progress_begin(&pg, o.method, o.frames);
    double ms_sum = 0.0, rays_sum = 0.0;
    long long nonfinite_sum = 0;
    struct restir_metrics_error err = {0, 0, 0, 0}, err_sum = {0, 0, 0, 0};
    struct restir_metrics_error err_dn = {0, 0, 0, 0}, err_dn_sum = {0, 0, 0, 0}; /* of r.denoised */
    size_t npix = (size_t)o.params.width * (size_t)o.params.height;
    unsigned char *mask = xcalloc(npix, 1);
    rc = 0;
    int done = 0; /* frames rendered; fewer than o.frames after SIGINT / SIGTERM */
    cli_catch_stop_signals();
    for (int f = 0; f < o.frames && rc == 0; f++) {
        struct frame_stats st;
        struct camera cam = cams ? cams[f] : scene_camera_at(&s, o.params.camera_path, (float)f);
        renderer_render(&r, f, &cam, &st);
        ms_sum += st.ms_total;
        rays_sum += (double)st.rays;
        if (ref) {
            restir_metrics_compute(r.image, ref, npix, NULL, &err);
            errors_add(&err_sum, &err);
            if (r.denoised) {
                restir_metrics_compute(r.denoised, ref, npix, NULL, &err_dn);
                errors_add(&err_dn_sum, &err_dn);
            }
        }
        const double vp = (double)st.valid_pixels;
        double accept = st.valid_pixels > 0 ? (double)st.temporal_accepted / vp : 0.0;
        /* path reservoirs: shares of pixels offered / taking a temporal candidate per technique */
        const struct temporal_counts *tc = &st.temporal;
        double bp_rx = st.valid_pixels > 0 ? (double)tc->bp_received / vp : 0.0;
        double bp_acc = st.valid_pixels > 0 ? (double)tc->bp_accepted / vp : 0.0;
        double sp_rx = st.valid_pixels > 0 ? (double)tc->splat_received / vp : 0.0;
        double sp_acc = st.valid_pixels > 0 ? (double)tc->splat_accepted / vp : 0.0;
        /* 004 Sec. 6.2: pixels whose history was rejected in any of the last DISOCCLUSION_FRAMES frames */
        double disoccluded = 0.0, mape_disoccluded = 0.0;
        int has_disoccluded = 0; /* a MAPE over disoccluded pixels: a reference and such pixels */
        if (method_has(method, METHOD_HISTORY)) {
            long long marked = renderer_disoccluded(&r, DISOCCLUSION_FRAMES, mask);
            disoccluded = st.valid_pixels > 0 ? (double)marked / (double)st.valid_pixels : 0.0;
            struct restir_metrics_error e;
            if (ref && marked > 0 && restir_metrics_compute(r.image, ref, npix, mask, &e) == 0) {
                mape_disoccluded = e.mape;
                has_disoccluded = 1;
            }
        }
        char passes[1024] = "";
        for (int q = 0; q < pass_count(); q++)
            snprintf(passes + strlen(passes), sizeof(passes) - strlen(passes), ",%.3f", st.ms[q]);
        /* Writing is timed on its own (ms_write), outside the frame's ms_total. */
        double ms_write = 0.0;
        const int stopping = cli_stop_signal != 0; /* this frame is the last: write it as such */
        if (o.save_all || f == o.frames - 1 || stopping) {
            double t0 = omp_get_wtime();
            if (cli_write_frame(out_dir, f, &r, msg) != 0) {
                cli_error("%s", msg);
                rc = EXIT_RUNTIME;
            }
            ms_write = 1e3 * (omp_get_wtime() - t0);
        }
        /* errors only against a reference: empty fields without one, never a 0 that reads as exact */
        char errors[256] = "";
        const double e_all[] = {err.relmse, err.mape, err.smape, err.luma_rmse}, e_dis[] = {mape_disoccluded},
                     e_dn[] = {err_dn.relmse, err_dn.mape, err_dn.smape};
        error_fields(errors, sizeof errors, e_all, 4, ref != NULL);
        error_fields(errors, sizeof errors, e_dis, 1, has_disoccluded);
        error_fields(errors, sizeof errors, e_dn, 3, ref && r.denoised);
        csv_row(&csv, "%d,%.3f%s,%lld,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f%s,%lld,%lld,%.3f,%lld", f, st.ms_total,
                passes, st.rays, (double)st.rays / (st.ms_total * 1e3), accept, bp_rx, bp_acc, sp_rx, sp_acc,
                disoccluded, errors, st.denoise.passed_through, st.denoise.history_reset, ms_write, st.nonfinite);
        nonfinite_sum += st.nonfinite;
        progress_update(&pg, f + 1);
        done = f + 1;
        if (stopping)
            break;
    }
    progress_end(&pg);
    if (rc == 0 && done < o.frames) { /* interrupted: the complete frames and their metrics stay */
        if (csv_close(&csv, msg) != 0)
            cli_error("%s", msg);
        cli_error("interrupted by %s after %d of %d frames; the complete outputs are in %s",
                  cli_stop_signal_name(), done, o.frames, out_dir);
        rc = 128 + (int)cli_stop_signal;
        renderer_fini(&r);
        free(cams);
        free(mask);
        free(ref);
        scene_destroy(&s);
        return rc;
    }
    if (rc == 0 && csv_close(&csv, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    } else if (rc != 0) {
        csv_abort(&csv);
    }
    if (rc == 0) {
        cJSON *j = params_json(&o, method);
        cJSON_AddNumberToObject(j, "ms_per_frame", ms_sum / o.frames);
        cJSON_AddNumberToObject(j, "mrays_per_s", rays_sum / (ms_sum * 1e3));
        cJSON_AddNumberToObject(j, "nonfinite_discarded", (double)nonfinite_sum);
        struct rusage ru; /* the process's peak resident memory (Linux reports kilobytes) */
        if (getrusage(RUSAGE_SELF, &ru) == 0)
            cJSON_AddNumberToObject(j, "peak_memory_mb", (double)ru.ru_maxrss / 1024.0);
        if (ref) {
            add_errors(j, "last_frame", &err, 1.0, 1);
            add_errors(j, "mean_over_frames", &err_sum, o.frames, 1);
            if (r.denoised) { /* after denoising: BIASED by nature */
                add_errors(j, "last_frame_denoised", &err_dn, 1.0, 0);
                add_errors(j, "mean_over_frames_denoised", &err_dn_sum, o.frames, 0);
            }
        }
        if (json_write_file(json_path, j, msg) != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
        }
        cJSON_Delete(j);
    }
    if (rc == 0) {
        printf("%s on %s, %dx%d, %d frame(s): %.2f ms/frame, %.2f Mrays/s", o.method, o.scene, o.params.width,
               o.params.height, o.frames, ms_sum / o.frames, rays_sum / (ms_sum * 1e3));
        if (ref)
            printf(", last frame relMSE %.5g MAPE %.5g SMAPE %.4g", err.relmse, err.mape, err.smape);
        if (ref && r.denoised)
            printf("; denoised (%s, BIASED) relMSE %.5g MAPE %.5g SMAPE %.4g", denoiser_name(r.denoiser),
                   err_dn.relmse, err_dn.mape, err_dn.smape);
        printf("\noutput: %s\n", out_dir);
    }
    renderer_fini(&r);
    free(cams);
    free(ref);
    free(mask);
    scene_destroy(&s);
    return rc;
}
