/* evaluate_record.h: what an evaluation's step records when it is merged (evaluate_record.c), so its
 * table can be regenerated and checked without its jobs' outputs: STEP/provenance.json (the build
 * that planned it, the machines of its jobs and of the merge, resolution, runs, seeds, reference
 * paths, frames, scene and its content hash) and STEP/settings.json (per row of its table: the
 * method, every setting in effect and the hash of a tiny render with them). Also the provenance
 * line of a paper's section in evaluation.md. Must never measure an image or write a table. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_RECORD_H
#define RESTIR_EXPERIMENTS_EVALUATE_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "experiments/evaluate_papers.h"
#include "experiments/plan.h"
#include "methods/method.h"
#include "render/params.h"
#include "scene/scene.h"

/* The tiny render a row's hash is taken of: small enough for well under a second per row, two
 * frames so temporal reuse runs. settings.json records the values it used, and the check renders
 * with the recorded ones. */
#define EVAL_HASH_WIDTH 48
#define EVAL_HASH_HEIGHT 32
#define EVAL_HASH_FRAMES 2
#define EVAL_HASH_SEED 1

struct eval_hash_render {
    int width, height, frames;
    uint64_t seed;
};

/* FNV-1a 64 of the float pixels of every frame (and, with denoising, every denoised frame) of
 * method m rendering scene s with p at hr's size, frames and seed (p's own are replaced; threads
 * > 0: that many OpenMP threads, else p's). camera_path: the scene's camera path (frame f at path
 * time f), else its still camera. The same bits for any thread count (the renderer's promise).
 * Returns 0, or -1 with msg (RESTIR_MSG_LEN) when the settings are refused for this method or
 * scene. */
int evaluate_hash_render(const struct scene *s, const struct method *m, const struct render_params *p,
                         int camera_path, const struct eval_hash_render *hr, int threads, uint64_t *hash, char *msg);

/* At the merge of step s (merged into step_dir) of evaluation plan eval: writes step_dir/provenance.json
 * and step_dir/settings.json. Loads the step's plan and scene again. Returns 0, or an exit code
 * having said why. */
int evaluate_record_step(const struct plan *eval, const struct eval_step *s, const char *step_dir);

/* The provenance line of paper's section of evaluation.md, from the provenance.json of its merged
 * steps (steps[k] in dir/NAME, merged[k] != 0): the build, the jobs' CPUs and threads, the merge's
 * date and machine, resolution, runs, seeds, reference paths. Deterministic in those files, so the
 * merge and `restir evaluate --tables` write the same line. */
void evaluate_provenance_text(const char *dir, const struct eval_step *steps, int n, const int *merged,
                              const char *paper, char *out, size_t len);

/* The file at path read as a JSON object: new (cJSON_Delete), or NULL with msg (RESTIR_MSG_LEN)
 * naming the file (missing, unreadable, not a JSON object). */
struct cJSON *evaluate_read_json(const char *path, char *msg);

#endif
