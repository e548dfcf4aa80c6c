/* grestir.h: Gradient with ReSTIR (002 Sec. 4.2-4.4): ReSTIR over paired-pixel samples (x, k) of
 * every horizontal and vertical pixel pair, with the outer shift T*(x, k) = (tau(x), k) (Eq. 21-22),
 * GRIS weights (Eq. 20), positivization into r+ and r- (Eq. 23-26), temporal reuse along the pair
 * motion vector with Area ReSTIR's fractional reprojection (Sec. 4.3.1) and adaptive edge-pair
 * spatial reuse (Sec. 4.3.2). The primal image comes from a separate area ReSTIR pass; the initial
 * candidates of a pair are the initial paths of its two pixels from that pass (k = 0 from a, k = 1
 * from b). Must never allocate per pixel. */
#ifndef RESTIR_METHODS_GRADIENT_GRESTIR_H
#define RESTIR_METHODS_GRADIENT_GRESTIR_H

#include "render/gbuffer.h"
#include "methods/restir_pt/restir_pt.h"
#include "restir/grad.h"

/* A paired-pixel reservoir: the base path y in pixel k of its pair (a, b) (k = 0: a, 1: b), its
 * unbiased contribution weight W, confidence c, and h(y, k) (restir/grad.h) with the target it
 * gives, both cached by the last shift into the pair. */
struct pair_reservoir {
    struct path_sample y;
    int k;
    float W, c, target;
    float h[3];
    float inner_J; /* |T'| of y's inner shift into its pair's other pixel (0: undefined there) */
};

/* Pair directions: dx pairs (a, a + x) and dy pairs (a, a + y), stored at their first pixel a. */
enum { GRAD_PAIR_X = 0, GRAD_PAIR_Y, GRAD_PAIR_DIRS };
/* r+ and r- (or one reservoir with target |h| without positivization). */
#define GRAD_SIGNS 2

struct grestir_state {
    int width, height;
    struct pair_reservoir *hist[2][GRAD_PAIR_DIRS][GRAD_SIGNS]; /* ping-pong: spatial outputs */
    struct pair_reservoir *work[GRAD_PAIR_DIRS][GRAD_SIGNS];    /* initial, then temporal outputs */
    int *neighbor[GRAD_PAIR_DIRS]; /* the spatial neighbor pair of each pair (-1: none) */
    unsigned char *edge[GRAD_PAIR_DIRS]; /* per pair: an edge pair (Sec. 4.3.2), of the last select pass */
    float *base_other;             /* per pixel and direction: f(T x) |T'| of its initial path */
    float *base_inner_J;           /* per pixel and direction: that shift's |T'| */
    long long edge_pairs, neighbors_found; /* of the last select pass */
};

void grestir_state_init(struct grestir_state *st, int width, int height);
void grestir_state_fini(struct grestir_state *st);

/* Initial candidates (Sec. 4.2.2, 4.4): each pixel's initial path (base[i], a UCW W_i for its own
 * pixel) shifted into its four neighbors; per pair the two candidates (x_a, 0) and (x_b, 1) are
 * resampled into r+ and r- (the same candidates) by GRIS with m = 1 each: the two lie in disjoint
 * parts of the paired domain, so each is the only technique that produces its part. */
long long grestir_initial_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *base,
                               struct grestir_state *st);

/* Temporal reuse (Sec. 4.3.1) from prev (the previous frame's hist[] slots). Returns rays. */
long long grestir_temporal_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                                struct grestir_state *st, int prev_slot, long long *accepted);

/* Spatial neighbor pairs by grad.spatial (reads only the G-buffer). */
void grestir_select_pass(const struct pt_frame *fr, const struct gbuffer *g, struct grestir_state *st);

/* Spatial reuse of work into hist[slot]; pairs without a neighbor keep their temporal result. */
long long grestir_spatial_pass(const struct pt_frame *fr, const struct gbuffer *g, struct grestir_state *st,
                               int slot);

/* dx, dy (RGB) += the estimates of hist[slot] (Eq. 17, 24). */
void grestir_shade_pass(const struct render_params *p, const struct grestir_state *st, int slot, float *dx,
                        float *dy);

#endif
