/* compare_command.c: `restir compare` from its parsed description to the table (compare_command.h):
 * the reference, the output folder, the per-frame track, the specs run by compare_schedule, and
 * compare.csv. Must never implement a method. */
#include "experiments/compare_command.h"
#include "scene/scene_animation.h"

#include <stdio.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_plan.h"
#include "experiments/compare_run.h"
#include "experiments/out_dir.h"
#include "io/exr.h"

/* The references of the frames before the last that --ref-every asks for, into track and written as
 * out_dir/reference_NNNN.exr (a failed write is a warning). Returns 0, or 128 + the signal having said
 * what is kept. */
static int render_earlier_references(const struct compare_setup *st, struct compare_track *track,
                                     const char *out_dir)
{
    char msg[RESTIR_MSG_LEN], path[4200];
    for (int k = 0; k + 1 < track->nref; k++) {
        if (!(track->ref[k] = compare_render_reference_at(st, track->ref_frame[k]))) {
            cli_error("interrupted by %s while rendering the reference of frame %d; kept in %s: the references "
                      "finished before it",
                      cli_stop_signal_name(), track->ref_frame[k], out_dir);
            return 128 + (int)cli_stop_signal;
        }
        snprintf(path, sizeof(path), "%s/reference_%04d.exr", out_dir, track->ref_frame[k]);
        if (exr_write_rgb(path, track->ref[k], st->p.width, st->p.height, msg) != 0)
            cli_error("warning: %s", msg);
    }
    return 0;
}

/* With the reference pair and out_dir in place: the track, every spec, the table. Returns an exit code,
 * having said what went wrong. */
static int run_specs(const struct compare_setup *st, const struct reference_pair *pair, const char *out_dir,
                     int argc, char **argv)
{
    char msg[RESTIR_MSG_LEN];
    const int n = st->n;
    struct compare_track track;
    compare_track_init(&track, st->o.frames, st->o.runs, st->o.ref_every, st->p.width, st->p.height, pair->mean);
    track.nchanges = scene_animation_changes(&st->s, track.change, COMPARE_MAX_CHANGES);
    for (int f = track.cov_first + 1; f < st->o.frames; f++) /* flicker would measure the lights' own change */
        track.lights_change_in_window |= scene_lights_differ(&st->s, (float)(f - 1), (float)f);
    int rc = render_earlier_references(st, &track, out_dir);
    if (rc != 0) {
        compare_track_fini(&track);
        return rc;
    }
    if (compare_track_open(&track, out_dir, msg) != 0) {
        cli_error("%s", msg);
        compare_track_fini(&track);
        return EXIT_RUNTIME;
    }
    struct compare_result res[MAX_METHODS] = {0};
    rc = compare_schedule(st, pair->mean, out_dir, &track, res, msg);
    if (rc == 0 && compare_track_close(&track, msg) != 0)
        rc = EXIT_RUNTIME;
    compare_track_fini(&track);
    if (rc == EXIT_RUNTIME)
        cli_error("%s", msg);
    if (rc == 0) {
        char command[8192];
        cli_command_line("compare", argc, argv, command, sizeof command);
        compare_reference_noise(res, n, pair->a, pair->b, pair->mean, (size_t)st->p.width * st->p.height);
        rc = compare_write_table(st, out_dir, command, res, pair->mean);
    }
    for (int k = 0; k < n; k++)
        compare_result_free(&res[k]);
    return rc;
}

/* After setup: the reference (read from --ref, else rendered as two halves), the output folder, then
 * run_specs. Returns an exit code, having said what went wrong. */
static int run_comparison(const struct compare_setup *st, int argc, char **argv)
{
    char msg[RESTIR_MSG_LEN], out_dir[4096], base[4096];
    const struct render_params *p = &st->p;
    int rc = 0;
    cli_catch_stop_signals();
    snprintf(base, sizeof(base), "out/compare-%s", st->s.name); /* without --out: a new folder each run */
    struct reference_pair pair = {0};
    if (st->o.ref) {
        if (cli_load_reference(st->o.ref, p->width, p->height, &pair.mean, msg) != 0 ||
            reference_pair_load_halves(st->o.ref, p->width, p->height, &pair.a, &pair.b, msg) < 0)
            rc = EXIT_RUNTIME;
    } else if (compare_render_reference_pair(st, NULL, &pair, msg) != 0) {
        cli_error("interrupted by %s while rendering the reference; nothing written", cli_stop_signal_name());
        return 128 + (int)cli_stop_signal;
    }
    if (rc == 0 && out_dir_open(st->o.out, base, st->o.force, out_dir, sizeof(out_dir), msg) != 0)
        rc = EXIT_RUNTIME;
    if (rc != 0) {
        cli_error("%s", msg);
        reference_pair_free(&pair);
        return rc;
    }
    char ref_path[4200];
    snprintf(ref_path, sizeof(ref_path), "%s/reference.exr", out_dir);
    if (!st->o.ref && reference_pair_write(&pair, ref_path, p->width, p->height, msg) != 0)
        cli_error("warning: %s", msg);
    rc = run_specs(st, &pair, out_dir, argc, argv);
    reference_pair_free(&pair);
    return rc;
}

int compare_command(const struct cli_options *desc, int argc, char **argv)
{
    char msg[RESTIR_MSG_LEN];
    if (!desc->plan && desc->out && out_dir_check("--out", desc->out, desc->force, msg) != 0) {
        cli_error("%s", msg); /* a folder of its own: nothing is touched */
        return EXIT_USAGE;
    }
    static struct compare_setup st; /* MAX_METHODS specs with their parameters: kept off the stack */
    int rc = compare_setup(desc, &st);
    if (rc != 0)
        return rc;
    rc = st.o.plan ? compare_plan(&st, argc, argv) : run_comparison(&st, argc, argv);
    scene_destroy(&st.s);
    return rc;
}
