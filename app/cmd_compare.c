/* cmd_compare.c: `restir compare`: method specs (NAME[:key=value]...) run on the same frames against one
 * reference, optionally at equal time, into a table and compare.csv. Must never implement a method. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_plan.h"
#include "experiments/compare_run.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "experiments/stats.h"
#include "io/atomic_file.h"
#include "io/exr.h"

/* Frame time of method m at spp paths per pixel (the second of two frames, after a warm-up). */
static double frame_ms_at_spp(const struct scene *s, const struct method *m, const struct render_params *p, int spp)
{
    struct render_params q = *p;
    struct renderer r;
    struct frame_stats st;
    struct camera cam = scene_camera_at(s, p->camera_path, 0.0f);
    q.spp = spp;
    renderer_init(&r, s, m, &q);
    renderer_render(&r, 0, &cam, &st); /* warm-up */
    renderer_render(&r, 1, &cam, &st);
    renderer_fini(&r);
    return st.ms_total;
}

/* Paths per pixel of pt or gpt that fit in budget_ms (equal_time_spp: a 1-spp and a 4-spp timing,
 * the fixed per-frame cost such as gpt's reconstruction removed). */
static int spp_for_budget(const struct scene *s, const struct method *m, const struct render_params *p, double budget_ms)
{
    return equal_time_spp(budget_ms, frame_ms_at_spp(s, m, p, 1), frame_ms_at_spp(s, m, p, 4));
}

static void compare_usage(void)
{
    printf("usage: restir compare --scene NAME --methods SPEC,SPEC,... [--equal-time] [--frames N] [--res WxH]\n"
               "                      [--ref FILE.exr | --ref-spp N] [--camera static|path] [--out DIR]\n"
               "                      [--report [--self-contained]]\n"
               "                      [--seed N] [--threads N] [--runs N] [--ref-every K] [--set key=value]...\n"
               "                      [--force]\n"
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
               "our measure of 002 Fig. 7's gradient images, defined in restir render --help; whether a few\n"
               "pairs decide it: gradient_relmse_trim1 (without the worst 1%% of pairs) and gradient_mape, each with\n"
               "its _sem; ref_relmse, ref_mape, ref_smape: the reference's own error, from its two independent\n"
               "halves (empty for a --ref without them), and relmse_net: relmse without it; flip, flip_sem: the\n"
               "mean HDR-FLIP of the last frame, Andersson et al. 2021, at 67 pixels per degree, defined in\n"
               "restir render --help; ref_mape_disoccluded: the reference's own MAPE over run 0's disoccluded\n"
               "pixels)\n"
               "and each row's last frame to DIR/FOLDER/, where FOLDER is the SPEC with every character other\n"
               "than A-Z a-z 0-9 . _ - replaced by _ (and _2, _3, ... appended when two SPECs give the same\n"
               "name). Default DIR: a new folder out/compare-SCENE (-2, -3, ... appended when taken); a given\n"
               "--out DIR must be new or empty, or --force empties it first (only a folder restir wrote, never /,\n"
               "$HOME or the current folder; links inside are removed, not followed). --ref without --res: the\n"
               "reference's size. For gradient rows DIR/FOLDER_grad_worst1.png shows where\n"
               "the worst 1%% of gradient_relmse's pixel pairs are, over the dimmed reference: red the\n"
               "pair with the right neighbour, cyan with the one below, white both.\n");
    printf("DIR/frames.csv has a row per SPEC and frame: frame time, temporal pass time, the shares of\n"
               "valid pixels whose history shifted in (temporal_accept) and, for path reservoirs, that were\n"
               "offered / took a backprojected or a splatted candidate (as restir render's metrics.csv), and\n"
               "the error of the frames that have a reference: the last, and with --ref-every K also frames\n"
               "K-1, 2K-1, ..., each against its own reference (--ref-spp paths from that frame's camera;\n"
               "--ref gives the last frame's only).\n"
               "--runs N (default 1) runs every SPEC as N independently seeded sequences: errors are means\n"
               "over the runs with their standard errors (sd / sqrt N, printed after +-), and temporal_cov\n"
               "is 000's relative autocovariance (Appendix A, Eq. 17) at a lag of 3 frames over the second\n"
               "half of the frames (at least 8 frames) of the luminance clamped at 0 (the gradient methods'\n"
               "reconstructions are signed, and Eq. 17 divides by each pixel's mean, unbounded where it\n"
               "crosses 0; stderr says what share was clamped); run 0's frames are the ones written, and the times\n"
               "are the fastest run's (runs on a shared machine only ever get slower). --plan DIR makes\n"
               "each SPEC's run a job of its own; the merge then has the same errors and standard errors, but\n"
               "no temporal_cov (it needs every run's frame sequence). --ref-every and --equal-time cannot be\n"
               "planned.\n"
               "--report also writes DIR/index.html, a page that needs no network, with the command, commit\n"
               "and machine, the table and a relMSE plot (with --denoise each SPEC's denoised row after its\n"
               "own), relMSE against frame from frames.csv (with --ref-every), the time per pass from\n"
               "passes.csv as stacked bars, every image (and denoised image) beside the reference in a viewer\n"
               "(synchronized zoom and pan, A/B flip), relative-error and FLIP heat maps and the crops where\n"
               "the first two methods differ most. The page loads the PNGs beside it (reference.png, the\n"
               "FOLDERs' frames, report/): copy the whole DIR to show it elsewhere. With --self-contained\n"
               "every image is inside index.html (base64 data: URIs): the one file holds everything.\n");
    cli_options_help(stdout, "compare");
}

int cmd_compare(int argc, char **argv)
{
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--merge")) {
            if (argc != 2) {
                cli_error("compare --merge DIR takes no other option (the plan holds them)");
                return EXIT_USAGE;
            }
            return compare_merge(argv[i + 1]);
        }
    char parse_msg[RESTIR_MSG_LEN];
    struct cli_options desc;
    if (cli_parse_options("compare", argc, argv, &desc, parse_msg) != 0) {
        cli_error("%s", parse_msg);
        return EXIT_USAGE;
    }
    if (desc.help) {
        compare_usage();
        return 0;
    }
    if (!desc.plan && desc.out && out_dir_check("--out", desc.out, desc.force, parse_msg) != 0) {
        cli_error("%s", parse_msg); /* a folder of its own: nothing is touched */
        return EXIT_USAGE;
    }
    static struct compare_setup st;
    int rc = compare_setup(&desc, &st);
    if (rc != 0)
        return rc;
    if (st.o.plan) {
        rc = compare_plan(&st, argc, argv);
        scene_destroy(&st.s);
        return rc;
    }
    char msg[RESTIR_MSG_LEN];
    const struct cli_options o = st.o;
    const struct render_params p = st.p;
    struct compare_spec *specs = st.specs;
    const int n = st.n;
    cli_catch_stop_signals();
    char out_dir[4096], base[4096];
    snprintf(base, sizeof(base), "out/compare-%s", st.s.name); /* without --out: a new folder each run */
    struct reference_pair pair = {0};
    if (o.ref) {
        if (cli_load_reference(o.ref, p.width, p.height, &pair.mean, msg) != 0 ||
            reference_pair_load_halves(o.ref, p.width, p.height, &pair.a, &pair.b, msg) < 0)
            rc = EXIT_RUNTIME;
    } else if (compare_render_reference_pair(&st, NULL, &pair, msg) != 0) {
        cli_error("interrupted by %s while rendering the reference; nothing written", cli_stop_signal_name());
        scene_destroy(&st.s);
        return 128 + (int)cli_stop_signal;
    }
    if (rc == 0 && out_dir_open(o.out, base, o.force, out_dir, sizeof(out_dir), msg) != 0)
        rc = EXIT_RUNTIME;
    if (rc != 0) {
        cli_error("%s", msg);
        reference_pair_free(&pair);
        scene_destroy(&st.s);
        return rc;
    }
    float *ref = pair.mean;
    char ref_path[4200];
    snprintf(ref_path, sizeof(ref_path), "%s/reference.exr", out_dir);
    if (!o.ref && reference_pair_write(&pair, ref_path, p.width, p.height, msg) != 0)
        cli_error("warning: %s", msg);
    /* --ref-every: the earlier frames' references, written as reference_NNNN.exr */
    struct compare_track track;
    compare_track_init(&track, o.frames, o.runs, o.ref_every, p.width, p.height, ref);
    for (int k = 0; k + 1 < track.nref; k++) {
        if (!(track.ref[k] = compare_render_reference_at(&st, track.ref_frame[k]))) {
            cli_error("interrupted by %s while rendering the reference of frame %d; kept in %s: the references "
                      "finished before it",
                      cli_stop_signal_name(), track.ref_frame[k], out_dir);
            compare_track_fini(&track);
            reference_pair_free(&pair);
            scene_destroy(&st.s);
            return 128 + (int)cli_stop_signal;
        }
        snprintf(ref_path, sizeof(ref_path), "%s/reference_%04d.exr", out_dir, track.ref_frame[k]);
        if (exr_write_rgb(ref_path, track.ref[k], p.width, p.height, msg) != 0)
            cli_error("warning: %s", msg);
    }
    if (compare_track_open(&track, out_dir, msg) != 0) {
        cli_error("%s", msg);
        compare_track_fini(&track);
        reference_pair_free(&pair);
        scene_destroy(&st.s);
        return EXIT_RUNTIME;
    }
    /* The first spec of a method with state between frames sets the equal-time budget (its frame
     * time, reconstruction included); the METHOD_BUDGET_BY_SPP ones (pt, gpt) then fit it by paths
     * per pixel, the others by averaging instances. */
    struct compare_result res[MAX_METHODS] = {0};
    double budget = -1.0;
    int first = -1;
    for (int k = 0; k < n && first < 0; k++)
        if (!compare_budget_by_spp(specs[k].method))
            first = k;
    int stopped_at = -1; /* the spec a stop signal interrupted */
    if (first >= 0) {
        rc = compare_run_spec(&st.s, &specs[first], &specs[first].p, o.frames, specs[first].instances, o.runs, ref,
                              out_dir, o.report, &track, &res[first], msg);
        stopped_at = rc == RUN_STOPPED ? first : -1;
        budget = res[first].ms_per_frame;
    }
    for (int k = 0; k < n && rc == 0; k++) {
        if (k == first)
            continue;
        struct render_params q = specs[k].p;
        int instances = specs[k].instances;
        if (o.equal_time && budget > 0.0) {
            if (compare_budget_by_spp(specs[k].method)) {
                q.spp = spp_for_budget(&st.s, specs[k].method, &specs[k].p, budget);
            } else {
                /* one instance's time from a short run, then as many as fit (at least 1) */
                struct compare_result probe;
                rc = compare_run_method(&st.s, &specs[k], &q, o.frames < 3 ? o.frames : 3, 1, ref, out_dir, 0, NULL, 0,
                                        &probe, msg);
                if (rc != 0) {
                    stopped_at = rc == RUN_STOPPED ? k : -1;
                    break;
                }
                instances = (int)(budget / probe.ms_per_frame + 0.5);
                compare_result_free(&probe); /* the probe measures time only */
                instances = instances < 1 ? 1 : instances > MAX_INSTANCES ? MAX_INSTANCES : instances;
            }
        }
        rc = compare_run_spec(&st.s, &specs[k], &q, o.frames, instances, o.runs, ref, out_dir, o.report, &track, &res[k],
                              msg);
        stopped_at = rc == RUN_STOPPED ? k : -1;
    }
    if (rc == RUN_STOPPED) { /* the finished methods' frames and the reference stay; no table */
        char kept[1024] = "";
        if (!o.ref)
            snprintf(kept, sizeof kept, " reference.exr");
        for (int k = 0; k < n; k++)
            if (res[k].instances > 0) /* finished: its last frame is written */
                snprintf(kept + strlen(kept), sizeof kept - strlen(kept), " %s/", specs[k].dir);
        cli_error("interrupted by %s during %s; kept in %s:%s; no compare.csv (its rows need every method)",
                  cli_stop_signal_name(), specs[stopped_at].label, out_dir, kept[0] ? kept : " nothing");
        rc = 128 + (int)cli_stop_signal;
    } else if (rc != 0) {
        rc = EXIT_RUNTIME;
    }
    if (rc == 0 && compare_track_close(&track, msg) != 0)
        rc = EXIT_RUNTIME;
    compare_track_fini(&track);
    if (rc != 0) {
        if (rc == EXIT_RUNTIME)
            cli_error("%s", msg);
        for (int k = 0; k < n; k++)
            compare_result_free(&res[k]);
        reference_pair_free(&pair);
        scene_destroy(&st.s);
        return rc;
    }

    char command[8192];
    cli_command_line("compare", argc, argv, command, sizeof command);
    compare_reference_noise(res, n, pair.a, pair.b, ref, (size_t)p.width * p.height);
    rc = compare_write_table(&st, out_dir, command, res, ref);
    for (int k = 0; k < n; k++)
        compare_result_free(&res[k]);
    reference_pair_free(&pair);
    scene_destroy(&st.s);
    return rc;
}
