/* compare_schedule.c: the order and the budgets in which `restir compare` runs its specs
 * (compare_schedule in compare_run.h): the equal-time budget of 002 Sec. 5 and what a stop signal
 * leaves. Must never implement a method: what fits a budget by paths per pixel is a method's flag. */
#include <stdio.h>
#include <string.h>

#include "experiments/cli.h"
#include "experiments/compare_run.h"
#include "experiments/equal_time.h"

/* Spec k's parameters and instances within budget_ms per frame: by paths per pixel (the probe's camera
 * is the first frame's, as the sequence starts), or by as many averaged instances as fit after a short
 * run of one (at least 1, at most MAX_INSTANCES). Returns 0, or compare_run_method's code. */
static int fit_budget(const struct compare_setup *st, const struct compare_spec *c, double budget_ms, const float *ref,
                      const char *out_dir, struct render_params *q, int *instances, char *msg)
{
    if (compare_budget_by_spp(c->method)) {
        struct camera cam = scene_camera_at(&st->s, c->p.camera_path, 0.0f);
        q->spp = equal_time_spp_for(&st->s, c->method, &c->p, &cam, 0, budget_ms);
        return 0;
    }
    struct compare_result probe;
    const int frames = st->o.frames < 3 ? st->o.frames : 3;
    int rc = compare_run_method(&st->s, c, q, frames, 1, ref, out_dir, 0, NULL, 0, &probe, msg);
    if (rc != 0)
        return rc;
    int n = (int)(budget_ms / probe.ms_per_frame + 0.5);
    compare_result_free(&probe); /* the probe measures time only */
    *instances = n < 1 ? 1 : n > MAX_INSTANCES ? MAX_INSTANCES : n;
    return 0;
}

/* After a stop signal during spec `stopped`: says what stays in out_dir (the reference unless --ref
 * gave it, the folders of the finished specs) and that no table is written. */
static void say_stopped(const struct compare_setup *st, const struct compare_result *res, int stopped,
                        const char *out_dir)
{
    char kept[1024] = "";
    if (!st->o.ref)
        snprintf(kept, sizeof kept, " reference.exr");
    for (int k = 0; k < st->n; k++)
        if (res[k].instances > 0) /* finished: its last frame is written */
            snprintf(kept + strlen(kept), sizeof kept - strlen(kept), " %s/", st->specs[k].dir);
    cli_error("interrupted by %s during %s; kept in %s:%s; no compare.csv (its rows need every method)",
              cli_stop_signal_name(), st->specs[stopped].label, out_dir, kept[0] ? kept : " nothing");
}

int compare_schedule(const struct compare_setup *st, const float *ref, const char *out_dir,
                     struct compare_track *track, struct compare_result *res, char *msg)
{
    /* The first spec of a method with state between frames sets the equal-time budget (its frame
     * time, reconstruction included); the methods that fit a budget by paths per pixel (pt, gpt)
     * then do so, the others by averaging instances. */
    const struct compare_spec *specs = st->specs;
    const int n = st->n;
    double budget = -1.0;
    int first = -1, rc = 0;
    for (int k = 0; k < n && first < 0; k++)
        if (!compare_budget_by_spp(specs[k].method))
            first = k;
    int stopped_at = -1; /* the spec a stop signal interrupted */
    if (first >= 0) {
        rc = compare_run_spec(&st->s, &specs[first], &specs[first].p, st->o.frames, specs[first].instances, st->o.runs,
                              ref, out_dir, st->o.report, track, &res[first], msg);
        stopped_at = rc == RUN_STOPPED ? first : -1;
        budget = res[first].ms_per_frame;
    }
    for (int k = 0; k < n && rc == 0; k++) {
        if (k == first)
            continue;
        struct render_params q = specs[k].p;
        int instances = specs[k].instances;
        if (st->o.equal_time && budget > 0.0) {
            rc = fit_budget(st, &specs[k], budget, ref, out_dir, &q, &instances, msg);
            if (rc != 0) {
                stopped_at = rc == RUN_STOPPED ? k : -1;
                break;
            }
        }
        rc = compare_run_spec(&st->s, &specs[k], &q, st->o.frames, instances, st->o.runs, ref, out_dir, st->o.report,
                              track, &res[k], msg);
        stopped_at = rc == RUN_STOPPED ? k : -1;
    }
    if (rc == RUN_STOPPED) { /* the finished methods' frames and the reference stay; no table */
        say_stopped(st, res, stopped_at, out_dir);
        return 128 + (int)cli_stop_signal;
    }
    return rc != 0 ? EXIT_RUNTIME : 0;
}
