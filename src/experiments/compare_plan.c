/* compare_plan.c: a comparison split into jobs (compare_plan.h): the plan, one job, the merge.
 * Must never implement a method or be called by compare_run.c: compare_command.c, cmd_compare.c (--merge)
 * and cmd_job.c call it. */
#include "experiments/compare_plan.h"

#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_run.h"
#include "experiments/compare_worst.h"
#include "experiments/plan.h"
#include "experiments/reference_checkpoint.h"
#include "io/atomic_file.h"
#include "io/exr.h"

/* `restir compare ... --plan DIR` plans one job per SPEC and run (and one for the reference without
 * --ref); `restir job` runs a SPEC's frames and writes its last frame and its timing under
 * DIR/runs/FOLDER/ (run 0; a later run n writes its record, mask and last frame to run_N.bin);
 * `restir compare --merge DIR` measures every last frame against the reference and writes what the
 * unsplit compare writes into DIR (the same errors, bit for bit: they are computed from the same
 * frames; the times are the jobs' own). --equal-time is refused: its budget is one method's time on
 * the machine that runs the others; so is --ref-every. With --runs the merge has no temporal_cov
 * (000 Eq. 17 needs every run's frame sequence, which jobs do not keep). */

/* 4: denoised frames; 5: a timer per pass id up to PASS_MAX (methods name their own passes) */
static const char result_magic[8] = {'R', 'C', 'O', 'M', 'P', 'A', 'R', '5'};

/* What a SPEC's job measured: its frame time, paths per pixel and instances; has_mask: the record
 * goes on with the last frame's disocclusion mask (width x height bytes, compare_run.h); has_grad:
 * then with its forward differences (the method's signed outputs dx, dy, compare_forward_differences:
 * 2 x 3 x width x height floats; 0 in the records of versions before gradient errors, which read as
 * such methods without them); has_denoised: then with its
 * denoised last frame (denoise=svgf|atrous, 3 x width x height floats); a later run's record then
 * holds its last frame (3 x width x height floats). */
struct job_timing {
    double ms_per_frame, ms_pass[PASS_MAX];
    int32_t spp, instances, has_mask, has_grad, has_denoised, reserved;
};

/* Job k's spec (-1: the reference job) and run: the jobs are the reference, then each spec's runs. */
/* Jobs are run-major (compare_plan): after the reference, run 0 of every spec, then run 1, ... */
static int spec_of_job(const struct compare_setup *st, int k, int *run)
{
    const int j = k - (st->o.ref ? 0 : 1);
    *run = j < 0 ? 0 : j / st->n;
    return j < 0 ? -1 : j % st->n;
}

static int job_of_spec(const struct compare_setup *st, int spec, int run)
{
    return (st->o.ref ? 0 : 1) + run * st->n + spec;
}

int compare_plan(const struct compare_setup *st, int argc, char **argv)
{
    if (st->o.equal_time) {
        cli_error("compare: --equal-time cannot be planned: its budget is one method's frame time, which only "
                  "means something for methods timed on the same machine; run it unsplit");
        return EXIT_USAGE;
    }
    if (st->o.ref_every > 0) {
        cli_error("compare: --ref-every cannot be planned: a job holds one run's last frame; run it unsplit");
        return EXIT_USAGE;
    }
    char name[PLAN_NAME_MAX], rel[PLAN_PATH_MAX];
    struct plan pl;
    /* a new or empty folder, or this very plan's (finished jobs kept); --force empties another */
    int rc = plan_folder_claim(st->o.plan, "compare", argc, argv, st->o.force);
    if (rc == 0)
        rc = plan_start(&pl, st->o.plan, "compare", argc, argv, scene_content_hash(&st->s));
    if (rc != 0)
        return rc;
    if (!st->o.ref)
        plan_add_job(&pl, "the comparison's reference", "runs/reference.exr");
    /* run-major, as study_plan: one job at a time in this order times the specs interleaved */
    for (int n = 0; n < st->o.runs; n++)
        for (int k = 0; k < st->n; k++) {
            if (st->o.runs > 1)
                snprintf(name, sizeof name, "%.200s, run %d", st->specs[k].label, n);
            else
                snprintf(name, sizeof name, "%.200s", st->specs[k].label);
            if (n == 0)
                snprintf(rel, sizeof rel, "runs/%.140s/result.bin", st->specs[k].dir);
            else
                snprintf(rel, sizeof rel, "runs/%.140s/run_%d.bin", st->specs[k].dir, n);
            plan_add_job(&pl, name, rel);
        }
    return plan_finish(&pl);
}

/* Job k's result: the reference image, or a SPEC's timing, last frame, mask, gradients and denoised
 * frame (each out-pointer may be NULL; *mask, *grad and *denoised NULL when the record has none). */
static int read_job(const struct plan *pl, const struct compare_setup *st, int k, struct job_timing *timing,
                    float **image, unsigned char **mask, float **grad, float **denoised, char *why)
{
    const size_t npix = (size_t)st->p.width * (size_t)st->p.height;
    if (mask)
        *mask = NULL;
    if (grad)
        *grad = NULL;
    if (denoised)
        *denoised = NULL;
    char path[2 * PLAN_PATH_MAX];
    plan_output_path(pl, k, path, sizeof path);
    int run;
    const int spec = spec_of_job(st, k, &run);
    const size_t image_bytes = run > 0 ? sizeof(float) * 3 * npix : 0;
    float *img = NULL;
    if (spec < 0) {
        if (cli_load_reference(path, st->p.width, st->p.height, &img, why) != 0)
            return -1;
    } else {
        void *data = NULL;
        size_t size = 0;
        if (plan_blob_read(path, result_magic, pl->id, &data, &size, why) != 0)
            return -1;
        struct job_timing t = {0};
        if (size >= sizeof t)
            memcpy(&t, data, sizeof t);
        const size_t grad_bytes = t.has_grad ? sizeof(float) * 6 * npix : 0;
        const size_t dn_bytes = t.has_denoised ? sizeof(float) * 3 * npix : 0;
        if (size < sizeof t || size != sizeof t + (t.has_mask ? npix : 0) + grad_bytes + dn_bytes + image_bytes) {
            snprintf(why, RESTIR_MSG_LEN, "%.300s: not a timing record", path);
            free(data);
            return -1;
        }
        if (timing)
            *timing = t;
        if (mask && t.has_mask) {
            *mask = xmalloc(npix);
            memcpy(*mask, (const char *)data + sizeof t, npix);
        }
        if (grad && t.has_grad) {
            *grad = xmalloc(grad_bytes);
            memcpy(*grad, (const char *)data + sizeof t + (t.has_mask ? npix : 0), grad_bytes);
        }
        if (denoised && t.has_denoised) {
            *denoised = xmalloc(dn_bytes);
            memcpy(*denoised, (const char *)data + sizeof t + (t.has_mask ? npix : 0) + grad_bytes, dn_bytes);
        }
        if (run > 0) { /* a later run's last frame is in its record */
            if (image) {
                *image = xmalloc(image_bytes);
                memcpy(*image, (const char *)data + size - image_bytes, image_bytes);
            }
            free(data);
            return 0;
        }
        free(data);
        snprintf(path, sizeof path, "%s/runs/%s/frame_%04d.exr", pl->dir, st->specs[spec].dir, st->o.frames - 1);
        if (cli_load_reference(path, st->p.width, st->p.height, &img, why) != 0) {
            if (mask) {
                free(*mask);
                *mask = NULL;
            }
            if (grad) {
                free(*grad);
                *grad = NULL;
            }
            if (denoised) {
                free(*denoised);
                *denoised = NULL;
            }
            return -1;
        }
    }
    if (image)
        *image = img;
    else
        free(img);
    return 0;
}

static int job_valid(const struct plan *pl, int k, char *why, void *ctx)
{
    return read_job(pl, ctx, k, NULL, NULL, NULL, NULL, NULL, why);
}

/* compare_setup from the plan's description (its options, read back through the option table).
 * Returns 0 or an exit code having said why. */
static int compare_setup_planned(const struct plan *pl, struct compare_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    struct cli_options desc;
    if (cli_parse_options("compare", pl->argc, pl->argv, &desc, msg) != 0) {
        cli_error("%s/plan.json: %s", pl->dir, msg);
        return EXIT_USAGE;
    }
    return compare_setup(&desc, st);
}

int compare_run_job(const struct plan *pl, int k)
{
    static struct compare_setup st;
    int rc = compare_setup_planned(pl, &st);
    if (rc != 0)
        return rc;
    if ((rc = plan_check_scene(pl, scene_content_hash(&st.s))) != 0) {
        scene_destroy(&st.s);
        return rc;
    }
    char path[PLAN_PATH_MAX + 200], runs[PLAN_PATH_MAX + 16], msg[RESTIR_MSG_LEN];
    plan_output_path(pl, k, path, sizeof path);
    snprintf(runs, sizeof runs, "%s/runs", pl->dir);
    if (read_job(pl, &st, k, NULL, NULL, NULL, NULL, NULL, msg) == 0) {
        printf("job %d of %d (%s): already done: %s\n", k + 1, pl->n_jobs, pl->jobs[k].name, path);
        scene_destroy(&st.s);
        return 0;
    }
    cli_catch_stop_signals();
    int run;
    const int spec = spec_of_job(&st, k, &run);
    if (spec < 0) {
        struct reference_pair pair;
        rc = reference_pair_finish(compare_render_reference_pair(&st, path, &pair, msg), &pair, path, st.p.width,
                                   st.p.height, msg);
    } else {
        struct compare_result res;
        memset(&res, 0, sizeof res);
        struct render_params q = st.specs[spec].p;
        q.seed = compare_run_seed(q.seed, run);
        char folder[PLAN_PATH_MAX + 240];
        snprintf(folder, sizeof folder, "%s/%s", runs, st.specs[spec].dir); /* run 0 writes its frame there */
        if (io_make_dirs(folder, msg) != 0) {
            cli_error("%s", msg);
            scene_destroy(&st.s);
            return EXIT_RUNTIME;
        }
        rc = compare_run_method(&st.s, &st.specs[spec], &q, st.o.frames, st.specs[spec].instances, NULL, runs, run > 0,
                                NULL, run, &res, msg);
        if (rc == RUN_STOPPED) {
            cli_error("interrupted by %s; no result written", cli_stop_signal_name());
            rc = 128 + (int)cli_stop_signal;
        } else if (rc != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
        } else {
            /* written after the frame: a result file means the frame is there */
            struct job_timing t = {.ms_per_frame = res.ms_per_frame,
                                   .spp = res.spp,
                                   .instances = res.instances,
                                   .has_mask = res.mask != NULL,
                                   .has_grad = res.grad != NULL,
                                   .has_denoised = res.denoised != NULL};
            memcpy(t.ms_pass, res.ms_pass, sizeof t.ms_pass);
            const size_t npix = (size_t)st.p.width * (size_t)st.p.height;
            const void *parts[5] = {&t, NULL, NULL, NULL, NULL};
            size_t sizes[5] = {sizeof t, 0, 0, 0, 0};
            int n_parts = 1;
            if (res.mask) {
                parts[n_parts] = res.mask;
                sizes[n_parts++] = npix;
            }
            if (res.grad) {
                parts[n_parts] = res.grad;
                sizes[n_parts++] = sizeof(float) * 6 * npix;
            }
            if (res.denoised) {
                parts[n_parts] = res.denoised;
                sizes[n_parts++] = sizeof(float) * 3 * npix;
            }
            if (res.image) {
                parts[n_parts] = res.image;
                sizes[n_parts++] = sizeof(float) * 3 * npix;
            }
            if (plan_blob_write(path, result_magic, pl->id, parts, sizes, n_parts, msg) != 0) {
                cli_error("%s", msg);
                rc = EXIT_RUNTIME;
            }
        }
        free(res.mask);
        free(res.grad);
        free(res.denoised);
        free(res.image);
    }
    if (rc == 0)
        printf("job %d of %d (%s): %s\n", k + 1, pl->n_jobs, pl->jobs[k].name, path);
    scene_destroy(&st.s);
    return rc;
}

/* Copies every file of from/ but the results (result.bin, run_N.bin) into to/ (made), each through a temporary name. */
static int copy_folder(const char *from, const char *to, char *msg)
{
    if (io_make_dirs(to, msg) != 0)
        return -1;
    DIR *d = opendir(from);
    if (!d) {
        snprintf(msg, RESTIR_MSG_LEN, "cannot read %.300s", from);
        return -1;
    }
    int rc = 0;
    for (struct dirent *e = readdir(d); e && rc == 0; e = readdir(d)) {
        if (e->d_name[0] == '.' || !strcmp(e->d_name, "result.bin") || !strncmp(e->d_name, "run_", 4) ||
            strstr(e->d_name, ".tmp-"))
            continue;
        char src[2 * PLAN_PATH_MAX + 300], dst[2 * PLAN_PATH_MAX + 300];
        snprintf(src, sizeof src, "%s/%s", from, e->d_name);
        snprintf(dst, sizeof dst, "%s/%s", to, e->d_name);
        rc = plan_copy_file(src, dst, msg);
    }
    closedir(d);
    return rc;
}

int compare_merge(const char *dir)
{
    char msg[RESTIR_MSG_LEN];
    struct plan pl;
    int rc = plan_load_kind(dir, "compare", "a comparison", &pl);
    if (rc != 0)
        return rc;
    static struct compare_setup st;
    rc = compare_setup_planned(&pl, &st);
    if (rc != 0) {
        plan_free(&pl);
        return rc;
    }
    rc = plan_check_scene(&pl, scene_content_hash(&st.s));
    if (rc == 0 && plan_check_jobs(&pl, job_valid, &st, msg) != 0) {
        cli_error("cannot merge: %s", msg);
        rc = EXIT_RUNTIME;
    }
    struct reference_pair pair = {0};
    char path[PLAN_PATH_MAX + 300], to[PLAN_PATH_MAX + 300];
    snprintf(path, sizeof path, "%s/runs/reference.exr", pl.dir);
    const char *ref_path = st.o.ref ? st.o.ref : path;
    if (rc == 0) {
        const int got = reference_pair_load(ref_path, st.p.width, st.p.height, !st.o.ref, &pair, msg);
        if (got != 0) {
            cli_error("cannot merge %s: %s", pl.dir, msg);
            rc = got == -2 ? EXIT_USAGE : EXIT_RUNTIME;
        }
    }
    const float *ref = pair.mean;
    snprintf(to, sizeof to, "%s/reference.exr", pl.dir);
    if (rc == 0 && !st.o.ref && plan_copy_file(path, to, msg) != 0) { /* where the unsplit compare puts it */
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    struct compare_result res[MAX_METHODS];
    memset(res, 0, sizeof res);
    const size_t npix = (size_t)st.p.width * st.p.height;
    for (int k = 0; k < st.n && rc == 0; k++) {
        struct compare_runs acc = {0};
        for (int n = 0; n < st.o.runs && rc == 0; n++) { /* in run order, as compare_run_spec */
            struct job_timing t;
            float *image = NULL, *grad = NULL, *denoised = NULL;
            unsigned char *mask = NULL;
            if (read_job(&pl, &st, job_of_spec(&st, k, n), &t, &image, &mask, &grad, &denoised, msg) != 0) {
                cli_error("cannot merge: %s", msg);
                rc = EXIT_RUNTIME;
                break;
            }
            struct compare_result one = {.method = st.specs[k].method};
            restir_metrics_compute(image, ref, npix, NULL, &one.err);
            one.flip = compare_flip(image, ref, st.p.width, st.p.height);
            compare_disoccluded_error(image, ref, mask, npix, &one.mape_dis, &one.dis_share);
            compare_gradient_errors(grad, grad ? grad + 3 * npix : NULL, ref, st.p.width, st.p.height, &one);
            compare_denoised_errors(denoised, ref, mask, npix, &one);
            if (!grad && method_output_find(st.specs[k].method, "dx", METHOD_OUTPUT_SIGNED) >= 0)
                fprintf(stderr,
                        "restir: compare --merge: %s, run %d: its job was written without gradients (by a restir "
                        "before gradient errors): no gradient_relmse for the row\n",
                        st.specs[k].label, n);
            one.ms_per_frame = t.ms_per_frame;
            compare_runs_add(&acc, &one);
            if (n == 0 && grad &&
                compare_write_worst_pairs(pl.dir, st.specs[k].dir, grad, grad + 3 * npix, ref, st.p.width, st.p.height,
                                          COMPARE_GRAD_TRIM, msg) != 0) {
                cli_error("%s", msg);
                rc = EXIT_RUNTIME;
            }
            one.dis_mask = n == 0 ? mask : NULL; /* run 0's: the reference's own error there */
            if (n > 0)
                free(mask);
            free(grad);
            if (n > 0 || !st.o.report)
                free(denoised);
            if (n > 0) {
                one.ms_per_frame = t.ms_per_frame;
                memcpy(one.ms_pass, t.ms_pass, sizeof one.ms_pass);
                compare_keep_fastest(&res[k], &one);
                free(image);
                continue;
            }
            res[k] = one;
            res[k].ms_per_frame = t.ms_per_frame;
            memcpy(res[k].ms_pass, t.ms_pass, sizeof t.ms_pass);
            res[k].spp = t.spp;
            res[k].instances = t.instances;
            compare_result_clear_sequence(&res[k]); /* not planned: they need every run's frames */
            if (st.o.report) {
                res[k].image = image;
                res[k].image_dn = denoised;
            } else {
                free(image);
            }
        }
        if (rc != 0)
            break;
        compare_runs_finish(&acc, &res[k]);
        snprintf(path, sizeof path, "%s/runs/%s", pl.dir, st.specs[k].dir);
        snprintf(to, sizeof to, "%s/%s", pl.dir, st.specs[k].dir);
        if (copy_folder(path, to, msg) != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
        }
    }
    if (rc == 0) {
        compare_reference_noise(res, st.n, pair.a, pair.b, ref, npix);
        rc = compare_write_table(&st, pl.dir, pl.command, res, ref);
    }
    for (int k = 0; k < st.n; k++)
        compare_result_free(&res[k]);
    reference_pair_free(&pair);
    scene_destroy(&st.s);
    plan_free(&pl);
    return rc;
}
