/* reference_halves.h: a comparison's reference as two independent halves (reference_halves.c), so
 * that error metrics can remove the reference's own noise: half a renders spp / 2 samples with the
 * reference's seed, half b the other spp / 2 with an independent seed, and the reference is their
 * mean r = (a + b) / 2. (a - b)^2 / 4 then estimates Var(r) per pixel without bias, and |a - b| / 2
 * is distributed as |r - R| for Gaussian noise (stats.h: reference_halves_relmse). With
 * sampler=sobol each half is one scrambled sequence of its own seed. Must never implement a method. */
#ifndef RESTIR_EXPERIMENTS_REFERENCE_HALVES_H
#define RESTIR_EXPERIMENTS_REFERENCE_HALVES_H

#include "methods/method.h"
#include "render/params.h"
#include "scene/camera.h"
#include "scene/scene.h"

/* The seed of half b of a reference of seed `seed`: independent of half a's and of every run's. */
static inline uint64_t reference_half_b_seed(uint64_t seed)
{
    return seed ^ 0x68616c662d622121ull;
}

/* A reference and its halves, each w * h * 3 floats (to free with reference_pair_free). */
struct reference_pair {
    float *mean, *a, *b;
    int spp_half; /* samples in each half */
};

/* Each half's samples for a reference of spp: spp / 2 rounded up, at least 1 (an odd spp renders one
 * sample more in all). */
int reference_half_spp(int spp);

/* Renders the pair: in memory when out is NULL (returns -1 after a stop signal), else resumably as a
 * plan's job: each half keeps a checkpoint beside OUT (OUT.half_a.exr's, OUT.half_b.exr's) and, once
 * done, is written as OUT.half_a.exr / OUT.half_b.exr with its run description, so a job killed in
 * half b continues there. Returns 0, or -1 with msg (a stop, a failed save, an unusable file). */
int reference_render_pair(const struct scene *s, const struct method *method, const struct render_params *p,
                          const struct camera *cam, const struct camera *open, int spp, const char *out,
                          struct reference_pair *r, char *msg);

/* A plan's reference job's end: writes r->mean to out as a plain RGB EXR (the halves are already
 * beside it), removes the halves' checkpoints and frees r. With rc_render != 0 (the render failed:
 * msg says why) writes nothing. Returns 0, 128 + the signal after a stop, or EXIT_RUNTIME, having said
 * what failed. */
int reference_pair_finish(int rc_render, struct reference_pair *r, const char *out, int w, int h, char *msg);

/* Writes r->mean to out and the halves beside it (OUT.half_a.exr, OUT.half_b.exr) as plain RGB EXRs,
 * for a reference rendered in memory. Returns 0, or -1 with msg. */
int reference_pair_write(const struct reference_pair *r, const char *out, int w, int h, char *msg);

/* The halves beside the reference out (OUT.half_a.exr, OUT.half_b.exr) of size w x h into *a and *b.
 * Returns 0; 1 when there are none (a reference given with --ref, or written before halves existed:
 * *a and *b NULL); -1 with msg when one is missing, of another size or holds a non-finite value. */
int reference_pair_load_halves(const char *out, int w, int h, float **a, float **b, char *msg);

/* The reference at path (r->mean) and its halves (r->a, r->b; NULL when it has none) of size w x h,
 * for a merge. need_halves: the reference is the plan's own, whose job renders halves, so the
 * subtraction of its own error is asked for and a reference without them (one rendered before halves
 * existed, or copied without them) is refused. Returns 0; -1 with msg for a missing or bad file; -2
 * with msg, naming the file, when halves are needed and absent. r is left empty on failure. */
int reference_pair_load(const char *path, int w, int h, int need_halves, struct reference_pair *r, char *msg);

void reference_pair_free(struct reference_pair *r);

#endif
