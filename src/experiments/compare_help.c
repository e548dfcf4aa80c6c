/* compare_help.c: the text of `restir compare --help` (compare_usage in compare_command.h): what a
 * SPEC is, how equal time is reached, every file the command writes and its columns. */
#include "experiments/compare_command.h"

#include "experiments/cli.h"
#include "methods/method.h"

void compare_usage(FILE *out)
{
    char by_spp[256];
    method_names_with(METHOD_BUDGET_BY_SPP, by_spp, sizeof by_spp);
    fprintf(out,
            "usage: restir compare --scene NAME --methods SPEC,SPEC,... [--equal-time] [--frames N] [--res WxH]\n"
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
            "first SPEC of a method with state between frames (gradient methods: L2 reconstruction\n"
            "included, 002 Sec. 5): the stateless methods (%s)\n"
            "get as many paths per pixel as fit, the other methods average as many independently seeded\n"
            "instances as fit (gradient methods average primal and gradients, then reconstruct\n"
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
            "pair with the right neighbour, cyan with the one below, white both.\n",
            by_spp);
    fprintf(out,
            "DIR/frames.csv has a row per SPEC and frame: frame time, temporal pass time, the shares of\n"
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
    cli_options_help(out, "compare");
}
