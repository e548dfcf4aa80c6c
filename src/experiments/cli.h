/* cli.h: helpers shared by the `restir` subcommands: argument parsing, scene and reference
 * loading, output folders, progress display and frame output. Must never implement a method. */
#ifndef RESTIR_EXPERIMENTS_CLI_H
#define RESTIR_EXPERIMENTS_CLI_H

#include <signal.h>
#include <stdio.h>

#include "methods/renderer.h"
#include "render/params.h"
#include "restir/metrics.h"
#include "scene/scene.h"

/* Exit codes: 0 success, 2 bad usage, 1 runtime failure. */
#define EXIT_USAGE 2
#define EXIT_RUNTIME 1

/* Prints "restir: <message>" to stderr. */
void cli_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* The Levenshtein distance of a and b (insertions, deletions, substitutions), over at most 64
 * characters of each: how far a misspelt option is from a known one. */
int cli_edit_distance(const char *a, const char *b);
/* Parses "WxH" into width/height. Returns 0, or -1 with msg. */
int cli_parse_res(const char *s, int *w, int *h, char *msg);
/* Parses a whole number in [lo, hi] for option `opt`. Returns 0, or -1 with msg. */
int cli_parse_int(const char *opt, const char *s, long long lo, long long hi, long long *out, char *msg);

/* "restir <command> <args...>" with arguments holding spaces quoted, cut to len. */
void cli_command_line(const char *command, int argc, char **argv, char *out, size_t len);

/* SIGINT / SIGTERM: the handler only records the signal (cli_stop_signal, else 0); long commands
 * check it between frames, finish what they are writing, keep every complete output and exit with
 * 128 + the signal's number. A second signal during that stop ends the process at once. */
extern volatile sig_atomic_t cli_stop_signal;
void cli_catch_stop_signals(void);
/* "SIGINT" or "SIGTERM": the signal cli_stop_signal holds, for messages. */
const char *cli_stop_signal_name(void);

/* 0 when a renderer of method m with parameters p fits in max_memory_mb (0: the memory the system
 * has available now), else -1 with msg giving the estimate and the limit (memory_estimate.h). */
int cli_check_memory(const struct scene *s, const struct method *m, const struct render_params *p, long long max_memory_mb,
                     char *msg);
/* The same for a known need: 0 when need_bytes fits, else -1 with msg naming what (a method or
 * command), the resolution, the need (and per_pixel bytes) and the limit. */
int cli_check_bytes(const char *what, int width, int height, double need_bytes, double per_pixel,
                    long long max_memory_mb, char *msg);

/* scene_load_with the scene-loading settings of p (scene.missing_textures, scene.alpha,
 * scene.shading_normals, rays.streams: all fixed here, at load), then env (NULL: keep the
 * scene's): "none" removes its environment light, else an .hdr / .exr image replaces it. */
int cli_scene_load(const struct render_params *p, const char *env, const char *name, struct scene *s, char *msg);

/* Loads a reference EXR and checks it has the render size. Returns 0, or -1 with msg. */
int cli_load_reference(const char *path, int width, int height, float **ref, char *msg);

/* Progress on stderr: a bar with ETA, redrawn in place, when stderr is a terminal; otherwise (a log
 * file, a pipe, a cluster job's output) a line "restir: LABEL: DONE/TOTAL (P%), Es elapsed, ETA Ts"
 * at most every PROGRESS_LINE_SECONDS seconds, none before the first step is done, and one for the
 * last step at progress_end when an earlier one was printed (a short run stays silent). The
 * environment's RESTIR_PROGRESS_SECONDS sets that interval (0: a line per step; off or negative:
 * no lines). */
#define PROGRESS_LINE_SECONDS 10.0
struct progress {
    int enabled;
    int tty;          /* the bar (1) or lines (0) */
    int total, done;  /* steps in all, steps done at the last update */
    int printed;      /* lines: the steps the last line counted */
    double t0;        /* omp_get_wtime() at progress_begin */
    double interval;  /* lines: the least seconds between two */
    double t_printed; /* lines: seconds after t0 of the last line */
    const char *label;
};
void progress_begin(struct progress *pg, const char *label, int total);
void progress_update(struct progress *pg, int done);
void progress_end(struct progress *pg);

/* Writes DIR/frame_NNNN.exr and .png of r->image. The EXR also holds a layer per output the method
 * declares and this frame has (method.h; the gradient methods: the other reconstruction when computed,
 * primal, dx, dy), and each radiance or signed output gets frame_NNNN_<name>.png (signed ones in
 * false colour); with denoise=svgf|atrous also frame_NNNN_denoised.exr and .png of r->denoised.
 * Returns 0, or -1 with msg. */
int cli_write_frame(const char *dir, int frame, const struct renderer *r, char *msg);

/* Renders the converged image of what `method` estimates (pt with the method's integrand) with
 * spp samples per pixel from camera cam (shutter opening at `open`, NULL: cam) into a new
 * malloc'ed RGB buffer (methods/pt/reference.h). Returns NULL, having stopped between chunks, when a
 * stop signal arrived (cli_stop_signal). */
float *cli_render_reference(const struct scene *s, const struct method *method, const struct render_params *p,
                            const struct camera *cam, const struct camera *open, int spp);
/* The camera at frame `frame` of a sequence (the default path, or the static camera) and where
 * its shutter opens: the camera of the frame before, as renderer_render takes it. Also sets the
 * scene's animated emitters to that frame (scene_set_frame), for the reference rendered next. */
void cli_frame_cameras(const struct scene *s, int use_path, int frame, struct camera *cam, struct camera *open);

#endif
