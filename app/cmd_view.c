/* cmd_view.c: `restir view`: options and scene for the interactive viewer (src/view/viewer.h).
 * Must never render itself. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "experiments/run_prepare.h"
#include "scene/scene_file.h"
#include "view/viewer.h"

static void view_usage(FILE *out)
{
    char cycle[256];
    view_method_cycle_names(cycle, sizeof cycle);
    fprintf(out,
            "usage: restir view --scene NAME|FILE [--method NAME] [--res WxH] [--seed N] [--threads N]\n"
            "                   [--script FILE] [--out DIR [--force]] [--set key=value]...\n"
            "A window that renders frame after frame (default method: the first of the M cycle, 640x360).\n"
            "Mouse drag turns the camera, W A S D move, Q E down and up; M next method (%s),\n"
            "T temporal reuse, Y spatial reuse, N neighbor selection, P spmis; V debug views (confidence,\n"
            "temporal acceptance, selected-neighbor count, reuse cells, temporal candidates per technique:\n"
            "black none, dark red received but none accepted, green backprojection accepted, blue splat\n"
            "accepted, cyan both; then the method's own outputs, e.g. primal, dx, dy); O denoised / raw\n"
            "frame (SVGF the first time; --denoise svgf|atrous starts with one), I the other denoiser;\n"
            "K screenshot (EXR and PNG, the denoised frame too,\n"
            "and DIR/screenshot_NNNN_view.png of a\n"
            "debug view on screen), C camera.json: the cameras since the last change of method or\n"
            "settings, which `restir render --camera DIR/camera.json --method M --res WxH --seed N`\n"
            "replays exactly; escape quits and writes DIR/last_frame.exr and .png. The title shows the\n"
            "per-pass times.\n"
            "--script FILE: timed input, one event per line ('F press KEY', 'F hold KEY N', 'F drag DX DY',\n"
            "'F quit', 'F screenshot FILE': the window as it shows then, as a PNG under DIR unless FILE is\n"
            "absolute, F >= 1; F counts frames from the start). Default DIR: a new folder out/view-SCENE\n"
            "(-2, -3, ... appended when taken), made at the first save; a given --out DIR must be new or\n"
            "empty, or --force empties it first. Without a display it says so and exits 1.\n",
            cycle);
    cli_options_help(out, "view");
}

/* What the viewer checks before it restarts with another method or setting: what run_prepare checked
 * before the first frame (the settings against the method and the scene, and memory). */
struct view_check {
    const struct scene *scene;
    long long max_memory_mb;
};

static int view_check_method(void *ctx, const struct method *m, const struct render_params *p, char *msg)
{
    const struct view_check *c = ctx;
    return run_check_method(c->scene, m, p, NULL, 0, c->max_memory_mb, RUN_CHECK_MEMORY, msg);
}

int cmd_view(int argc, char **argv)
{
    struct cli_options o;
    char msg[RESTIR_MSG_LEN];
    if (cli_parse_options("view", argc, argv, &o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o.help) {
        view_usage(stdout);
        return 0;
    }
    if (o.out && out_dir_check("--out", o.out, o.force, msg) != 0) {
        cli_error("%s", msg); /* a folder of its own: nothing is touched */
        return EXIT_USAGE;
    }
    const struct method *m = o.method ? run_find_method(o.method) : view_method_after(NULL);
    if (!m)
        return EXIT_USAGE;
    struct scene s;
    int rc = run_prepare(&o, m, RUN_CHECK_MEMORY, &s);
    if (rc != 0)
        return rc;
    if (o.params.threads > 0)
        omp_set_num_threads(o.params.threads);
    char out_dir[4096], base[4096];
    snprintf(base, sizeof base, "out/view-%s", s.name); /* without --out: a new folder each session */
    if (o.out)
        snprintf(out_dir, sizeof out_dir, "%s", o.out);
    struct stat st; /* the viewer makes its folder once a window is open; --force empties it now */
    if (o.out ? o.force && stat(o.out, &st) == 0 && out_dir_prepare(o.out, 1, msg) != 0
              : out_dir_fresh_name(base, out_dir, sizeof out_dir, msg) != 0) {
        cli_error("%s", msg);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    struct view_check check = {&s, o.max_memory_mb};
    const struct view_options vo = {&s, m, o.params, o.script, out_dir, view_check_method, &check};
    rc = view_run(&vo, msg);
    if (rc != 0)
        cli_error("view: %s", msg);
    scene_destroy(&s);
    return rc == 0 ? 0 : rc == 2 ? EXIT_USAGE : EXIT_RUNTIME;
}
