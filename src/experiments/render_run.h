/* render_run.h: `restir render` as a harness function: a description in, frames, metrics.csv and
 * summary.json out. The subcommand (app/cmd_render.c) parses the options and prints the usage.
 * Must never implement a method. */
#ifndef RESTIR_EXPERIMENTS_RENDER_RUN_H
#define RESTIR_EXPERIMENTS_RENDER_RUN_H

#include "experiments/options.h"

/* Renders desc->frames frames of desc->method on desc->scene into desc->out, which must be new or
 * empty unless desc->force empties it (default: a new folder out/SCENE-METHOD, -2, -3, ...; out_dir.h)
 * at the --ref's size when no --res is given: every frame's EXR and PNG (or the last), metrics.csv
 * with per-pass times and errors against --ref (empty fields without), summary.json that `restir
 * render --params` runs again. Returns an exit
 * code, having said what went wrong (0; 2 for bad input, nothing written; 1 for a failure while
 * rendering; 128 + the signal after SIGINT / SIGTERM, the last frame written). */
int render_run(const struct cli_options *desc);

#endif
