/* cmd_render.c: `restir render`: its usage, and its options into render_run's description
 * (src/experiments/render_run.h). */
#include <stdio.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/render_run.h"
#include "methods/settings.h"
#include "render/params.h"
#include "restir/metrics.h"

static void render_usage(FILE *out)
{
    char spp_readers[256], gradient_methods[256];
    settings_readers("spp", spp_readers, sizeof spp_readers);
    settings_readers("recon", gradient_methods, sizeof gradient_methods); /* the methods that reconstruct */
    fprintf(out,
            "usage: restir render --scene NAME --method NAME [--res WxH] [--frames N] [--spp N] [--seed N]\n"
            "                     [--threads N] [--camera static|path|FILE] [--ref FILE.exr] [--out DIR]\n"
            "                     [--save all|last] [--params FILE.json] [--env FILE|none] [--force]\n"
            "                     [--set key=value]...\n"
            "Writes DIR/frame_NNNN.exr and .png, DIR/metrics.csv (per frame: times per pass, rays, and\n"
            "error metrics when --ref is given; empty fields without one) and DIR/summary.json. Default DIR:\n"
            "a new folder out/SCENE-METHOD (-2, -3, ... appended when taken), said on stdout. A given --out DIR\n"
            "must be new or empty (one run per folder: exit 2 otherwise, nothing touched); --force empties it\n"
            "first, but only a folder restir wrote (summary.json, metrics.csv, frame_NNNN.*, ...), never /,\n"
            "$HOME or the current folder, and removes links inside without following them.\n"
            "--ref FILE.exr without --res renders at the reference's size; a --res that differs is an error.\n"
            "--spp applies to %s; the others render 1 sample per pixel per frame.\n"
            "--env FILE (.hdr or .exr, equirectangular) gives the scene that environment light, replacing its\n"
            "own; --env none removes it (every command that takes --scene reads --env; pt only renders it).\n"
            "--params FILE reads settings in order with the other options: a summary.json reruns that run\n"
            "(scene, method, resolution, frames, seed, camera and every setting; later options override),\n"
            "a plain JSON object of --set keys ({\"mis\": \"balance\", \"spatial.radius\": 50}) sets those.\n"
            "--camera FILE replays a camera file (one camera per frame, as restir view records them) and\n"
            "renders as many frames as it holds unless --frames says fewer.\n"
            "Gradient methods (%s) write the reconstruction as the image\n"
            "(L2; L1 with recon=l1), EXR layers primal, dx, dy (and L1 or L2 when computed), and\n"
            "frame_NNNN_{primal,dx,dy}.png (gradients in false colour: red positive, blue negative).\n\n"
            "Parameters (--set key=value, defaults shown):\n",
            spp_readers, gradient_methods);
    render_params_help(out);
    fprintf(out, "\nMetrics (against --ref):\n%s", restir_metrics_definitions());
    cli_options_help(out, "render");
}

int cmd_render(int argc, char **argv)
{
    struct cli_options o;
    char msg[RESTIR_MSG_LEN];
    if (cli_parse_options("render", argc, argv, &o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o.help) {
        render_usage(stdout);
        return 0;
    }
    return render_run(&o);
}
