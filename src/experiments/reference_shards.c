/* reference_shards.c: a reference split into shards (reference_shards.h): the plan, one shard, the merge.
 * Must never implement a method or be called by reference_run.c: cmd_reference.c and cmd_job.c call it. */
#include "experiments/reference_shards.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/out_dir.h"
#include "experiments/plan.h"
#include "experiments/reference_run.h"
#include "io/exr.h"
#include "methods/pt/reference.h"

/* `restir reference ... --shards N --plan DIR` plans N jobs, shard s rendering the chunks
 * [s C / N, (s + 1) C / N) of the C chunks of 16 samples the unsplit reference renders, so the
 * shards hold exactly its samples; `restir job` renders one; `restir reference --merge DIR --out
 * FILE.exr` averages them weighted by their sample counts, in double, rounded once. The merged
 * image differs from the unsplit one only by the order of the floating-point sums: both are within
 * C 2^-24 (relative) of the exact mean of the same samples, so within (2 C + 1) 2^-24 of each other
 * (tests/render/test_plans.c). With --target-relmse X each shard stops early once its own estimate
 * is at most N X (restir.shard then says how many samples it holds), and the merge weights each by
 * what it holds. */

/* Chunks and samples of shard s of n over spp samples. */
static void shard_range(int spp, int n, int s, int *first_chunk, int *samples)
{
    const int chunks = (spp + REFERENCE_CHUNK_SPP - 1) / REFERENCE_CHUNK_SPP;
    const int c0 = (int)((long long)s * chunks / n), c1 = (int)((long long)(s + 1) * chunks / n);
    const int end = c1 * REFERENCE_CHUNK_SPP < spp ? c1 * REFERENCE_CHUNK_SPP : spp;
    *first_chunk = c0;
    *samples = end - c0 * REFERENCE_CHUNK_SPP;
}

static void shard_output(int s, char *out, size_t len)
{
    snprintf(out, len, "runs/shard_%04d.exr", s);
}

/* The run description every shard and the merged image carry: the unsplit reference's. */
static void run_text(const struct reference_setup *st, char *run, size_t len)
{
    struct reference_accum a;
    reference_accum_init(&a, &st->s, st->method, &st->o.params, &st->cam, &st->cam_open, st->spp);
    reference_describe(&a, run, len);
    reference_accum_fini(&a);
}

int reference_plan(const struct reference_setup *st, int argc, char **argv)
{
    const int chunks = (st->spp + REFERENCE_CHUNK_SPP - 1) / REFERENCE_CHUNK_SPP;
    if (!st->o.plan || st->o.shards < 1) {
        cli_error("reference: --shards N and --plan DIR go together");
        return EXIT_USAGE;
    }
    if (st->o.shards > chunks) {
        cli_error("reference: --shards %d is more than the %d chunks of %d samples that --spp %d makes", st->o.shards,
                  chunks, REFERENCE_CHUNK_SPP, st->spp);
        return EXIT_USAGE;
    }
    if (st->o.checkpoint_every >= 0.0) {
        cli_error("reference: --checkpoint-every does not apply to a plan (a shard that fails is run again)");
        return EXIT_USAGE;
    }
    char name[PLAN_NAME_MAX], rel[64];
    struct plan pl;
    /* a new or empty folder, or this very plan's (finished jobs kept); --force empties another */
    int rc = plan_folder_claim(st->o.plan, "reference", argc, argv, st->o.force);
    if (rc == 0)
        rc = plan_start(&pl, st->o.plan, "reference", argc, argv, scene_content_hash(&st->s));
    if (rc != 0)
        return rc;
    for (int s = 0; s < st->o.shards; s++) {
        int c0, n;
        shard_range(st->spp, st->o.shards, s, &c0, &n);
        snprintf(name, sizeof name, "shard %d: %d samples from chunk %d", s, n, c0);
        shard_output(s, rel, sizeof rel);
        plan_add_job(&pl, name, rel);
    }
    return plan_finish(&pl);
}

struct shard_ctx {
    const struct reference_setup *st;
    const char *run;
};

/* A shard's file: this run's, of its chunks and samples (with a relMSE target, a shard may stop
 * early: any positive count up to its range's), the right size, finite. With mean not NULL, its
 * pixels and its sample count are returned. */
static int read_shard(const struct plan *pl, int k, const struct shard_ctx *c, float **mean, int *samples, char *why)
{
    char path[PLAN_PATH_MAX + 200], text[RUN_TEXT_MAX];
    plan_output_path(pl, k, path, sizeof path);
    int c0, n;
    shard_range(c->st->spp, pl->n_jobs, k, &c0, &n);
    int rc = exr_read_attribute(path, "restir.run", text, sizeof text, why);
    if (rc < 0)
        return -1;
    if (rc > 0 || strcmp(text, c->run) != 0) {
        snprintf(why, RESTIR_MSG_LEN, "%.300s: not a shard of this plan's run (restir.run %s)", path,
                 rc > 0 ? "missing" : "differs");
        return -1;
    }
    rc = exr_read_attribute(path, "restir.shard", text, sizeof text, why);
    if (rc < 0)
        return -1;
    int their_c0 = -1, their_n = -1, used = 0;
    const int parsed = rc == 0 && sscanf(text, "%d+%d%n", &their_c0, &their_n, &used) == 2 && text[used] == '\0';
    const int early = c->st->o.target_relmse > 0.0 && their_n > 0 && their_n < n;
    if (!parsed || their_c0 != c0 || (their_n != n && !early)) {
        snprintf(why, RESTIR_MSG_LEN, "%.300s: holds chunks+samples '%.40s', not the plan's %d+%d%s", path,
                 rc > 0 ? "(none)" : text, c0, n, c->st->o.target_relmse > 0.0 ? " or fewer samples" : "");
        return -1;
    }
    float *img = NULL; /* cli_load_reference also refuses NaN and infinite values */
    if (cli_load_reference(path, c->st->o.params.width, c->st->o.params.height, &img, why) != 0)
        return -1;
    if (mean)
        *mean = img, *samples = their_n;
    else
        free(img);
    return 0;
}

static int shard_valid(const struct plan *pl, int k, char *why, void *ctx)
{
    return read_shard(pl, k, ctx, NULL, NULL, why);
}

int reference_run_job(const struct plan *pl, int k)
{
    struct reference_setup st;
    int rc = reference_setup_args(pl->argc, pl->argv, &st);
    if (rc != 0)
        return rc;
    if ((rc = plan_check_scene(pl, scene_content_hash(&st.s))) != 0) {
        scene_destroy(&st.s);
        return rc;
    }
    char run[RUN_TEXT_MAX], path[PLAN_PATH_MAX + 200], msg[RESTIR_MSG_LEN] = "", shard[64];
    run_text(&st, run, sizeof run);
    plan_output_path(pl, k, path, sizeof path);
    const struct shard_ctx ctx = {&st, run};
    if (read_shard(pl, k, &ctx, NULL, NULL, msg) == 0) {
        printf("job %d of %d (%s): already done: %s\n", k + 1, pl->n_jobs, pl->jobs[k].name, path);
        scene_destroy(&st.s);
        return 0;
    }
    int c0, n;
    shard_range(st.spp, pl->n_jobs, k, &c0, &n);
    cli_catch_stop_signals();
    struct reference_accum a;
    reference_accum_init_shard(&a, &st.s, st.method, &st.o.params, &st.cam, &st.cam_open, c0, n);
    /* With a target X over N shards each stops at N X: the merged mean of N such shards has about
     * 1 / N of their error. */
    const double target = st.o.target_relmse * pl->n_jobs;
    if (target > 0.0)
        reference_accum_track_variance(&a, NULL, 0);
    while (a.done < a.spp && !cli_stop_signal) {
        reference_accum_step(&a);
        if (target > 0.0 && reference_accum_relmse_estimate(&a) <= target)
            a.spp = a.done;
    }
    snprintf(shard, sizeof shard, "%d+%d", c0, a.done);
    if (a.done < a.spp) {
        cli_error("interrupted by %s at %d of %d samples; nothing written", cli_stop_signal_name(), a.done, a.spp);
        rc = 128 + (int)cli_stop_signal;
    } else if (reference_write_image(path, a.mean, st.o.params.width, st.o.params.height, a.done, st.spp, run,
                                     st.o.method, st.o.scene, NULL, &(struct exr_attribute){"restir.shard", shard}, 1,
                                     msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    } else {
        printf("job %d of %d (%s): %s\n", k + 1, pl->n_jobs, pl->jobs[k].name, path);
    }
    reference_accum_fini(&a);
    scene_destroy(&st.s);
    return rc;
}

int reference_merge(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    int force = 0, bad = 0;
    for (int i = 0; i < argc && !bad; i++) {
        if (!strcmp(argv[i], "--force"))
            force = 1;
        else if (i + 1 < argc && !strcmp(argv[i], "--merge"))
            dir = argv[++i];
        else if (i + 1 < argc && !strcmp(argv[i], "--out"))
            out = argv[++i];
        else
            bad = 1;
    }
    if (bad || !dir || !out) {
        cli_error("usage: restir reference --merge DIR --out FILE.exr [--force] (the plan holds every other option)");
        return EXIT_USAGE;
    }
    char msg[RESTIR_MSG_LEN];
    if (out_file_check("--out", out, force, msg) != 0) { /* an earlier merge's image stays unless --force */
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    struct plan pl;
    int rc = plan_load_kind(dir, "reference", "a reference", &pl);
    if (rc != 0)
        return rc;
    struct reference_setup st;
    rc = reference_setup_args(pl.argc, pl.argv, &st);
    if (rc != 0) {
        plan_free(&pl);
        return rc;
    }
    char run[RUN_TEXT_MAX];
    run_text(&st, run, sizeof run);
    const struct shard_ctx ctx = {&st, run};
    rc = plan_check_scene(&pl, scene_content_hash(&st.s));
    if (rc == 0 && plan_check_jobs(&pl, shard_valid, (void *)&ctx, msg) != 0) {
        cli_error("cannot merge: %s", msg);
        rc = EXIT_RUNTIME;
    }
    const size_t n3 = 3 * (size_t)st.o.params.width * st.o.params.height;
    double *sum = xcalloc(n3, sizeof(double));
    long long total = 0;
    for (int k = 0; k < pl.n_jobs && rc == 0; k++) {
        float *mean = NULL;
        int n;
        if (read_shard(&pl, k, &ctx, &mean, &n, msg) != 0) {
            cli_error("cannot merge: %s", msg);
            rc = EXIT_RUNTIME;
            break;
        }
        for (size_t i = 0; i < n3; i++)
            sum[i] += (double)mean[i] * n;
        total += n;
        free(mean);
    }
    float *img = xmalloc(sizeof(float) * n3);
    for (size_t i = 0; i < n3 && total > 0; i++)
        img[i] = (float)(sum[i] / (double)total);
    char shards[32];
    snprintf(shards, sizeof shards, "%d", pl.n_jobs);
    if (rc == 0 && reference_write_image(out, img, st.o.params.width, st.o.params.height, (int)total, st.spp, run,
                                         st.o.method, st.o.scene, NULL,
                                         &(struct exr_attribute){"restir.shards", shards}, 1, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0)
        printf("reference of %s on %s (%dx%d, %lld spp) merged from %d shards into %s\n", st.o.method, st.o.scene,
               st.o.params.width, st.o.params.height, total, pl.n_jobs, out);
    free(img);
    free(sum);
    scene_destroy(&st.s);
    plan_free(&pl);
    return rc;
}
