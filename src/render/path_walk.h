/* path_walk.h: one unidirectional path from a primary hit, with next-event estimation and BSDF
 * sampling at every vertex. Every complete path it forms (a prefix plus a light vertex, reached
 * by NEE or by a BSDF-sampled ray) is reported as a candidate with its contribution f, sampling
 * density and NEE/BSDF power-heuristic weight, so that `pt` can sum m f / p and ReSTIR PT can
 * resample the same candidates (the initial path sampling of Lin et al. 2022).
 *
 * Measure: the primary hit is parameterized by its image position (000 footnote 1) and every
 * later vertex by the solid angle of the direction that reaches it, so
 * f = prod_j f_s(x_j) |n_j . w_j| * Le(x_D) and densities are products of solid-angle pdfs.
 *
 * Random numbers: vertex j draws from its own stream path_rng(seed, j), first the three BSDF
 * numbers, then three NEE numbers, then one for Russian roulette (struct path_vertex_numbers). A shift mapping that replays a
 * path therefore needs only the seed (random replay, Lin et al. 2022 Sec. 7).
 * Must never depend on reservoirs. */
#ifndef RESTIR_RENDER_PATH_WALK_H
#define RESTIR_RENDER_PATH_WALK_H

#include "core/rng.h"
#include "render/params.h"
#include "scene/scene.h"

/* Vertices a walk can hold: x_1 .. x_{max_bounces}; max_bounces is capped to this. */
#define PATH_MAX_VERTICES 64

/* A scattering vertex x_j of the walk. */
struct path_vertex {
    vec3 p;
    vec3 ns, ng;   /* shading and geometric normals, on the side the path arrived from */
    vec3 wo;       /* unit direction back toward x_{j-1} (the camera for j = 1) */
    int material;
    int tri;       /* the triangle and barycentrics of p, where textures are read */
    float b1, b2;
    /* The BSDF-sampled continuation (valid for every vertex but the last one reported): */
    vec3 w_next;   /* sampled direction */
    vec3 fcos;     /* f_s(wo, w_next) |ns . w_next| */
    float pdf_dir; /* solid-angle density of w_next (BSDF lobe mixture) */
};

/* A complete path x_1 .. x_D, D >= 2, whose last vertex x_D is on an emitter or is a direction of
 * the environment light (a vertex at infinity). Vertices x_1 .. x_{D-1} are walk->v[0 .. D-2];
 * the last segment is described here because for NEE it is not the BSDF-sampled continuation of
 * x_{D-1}. */
struct path_candidate {
    int length;       /* D */
    int via_nee;      /* 1: x_D from light sampling, 0: hit by the BSDF-sampled ray */
    int at_env;       /* 1: x_D is the environment in direction w_last; light_p and light_n are unused */
    vec3 light_p;     /* x_D */
    vec3 light_n;     /* emitting normal at x_D */
    vec3 Le;          /* radiance emitted from x_D toward x_{D-1} */
    vec3 w_last;      /* unit direction x_{D-1} -> x_D */
    vec3 fcos_last;   /* f_s(x_{D-1}) |ns . w_last| */
    vec3 f;           /* path contribution */
    float pdf;        /* density of the path under this strategy, Russian roulette included */
    float mis;        /* power-heuristic weight of this strategy against the other */
};

struct path_walk {
    int nv;           /* vertices stored in v */
    struct path_vertex v[PATH_MAX_VERTICES];
};

typedef void (*path_candidate_fn)(void *ctx, const struct path_walk *w, const struct path_candidate *c);

/* Random stream of vertex j (1-based) of the path with this seed. */
static inline pcg32 path_rng(uint64_t seed, int vertex)
{
    return pcg32_make(rng_mix64(seed + 0x632be59bd9b4e019ull * (uint64_t)vertex), seed ^ 0x9e3779b97f4a7c15ull);
}

/* The random numbers vertex j of a walk consumes: bsdf[0] picks the BSDF lobe and bsdf[1..2] the
 * direction; nee[0] picks the environment or an emitter (and then the emitter) and nee[1..2] the
 * point on it; rr decides Russian roulette. */
struct path_vertex_numbers {
    float bsdf[3], nee[3], rr;
};

/* Where a walk's numbers come from: fill(ctx, j, u) writes vertex j's (1-based). path_walk_run
 * uses the replayable streams path_rng(seed, j); pt's low-discrepancy sampler its own. */
struct path_numbers {
    void (*fill)(const void *ctx, int vertex, struct path_vertex_numbers *u);
    const void *ctx;
};

/* Walks from the primary hit x1 (x1.wo toward the camera; x1's own emission is not reported:
 * paths of length 1 are the caller's) with up to max_bounces scattering events, Russian roulette
 * after rr_bounces, calling emit for every candidate. Returns the number of rays traced. */
/* NEE chooses emitters and points on them by `lights`, with the matching density in the MIS weights
 * of both strategies. Only the walk reads that density: shifts reconnect to a light vertex or
 * replay BSDF numbers, so reservoirs never need it. */
long long path_walk_run(const struct scene *s, const struct path_vertex *x1, uint64_t seed, struct light_choice lights,
                        int max_bounces, int rr_bounces, struct path_walk *w, path_candidate_fn emit, void *ctx);
/* path_walk_run with the numbers from `numbers` instead of the seed's streams. */
long long path_walk_run_numbers(const struct scene *s, const struct path_vertex *x1, const struct path_numbers *numbers,
                                struct light_choice lights, int max_bounces, int rr_bounces, struct path_walk *w,
                                path_candidate_fn emit, void *ctx);
/* The numbers path_walk_run draws: the replayable streams path_rng(*seed, j). seed must outlive the
 * walk. */
struct path_numbers path_numbers_seeded(const uint64_t *seed);

/* The primary vertex from a camera-ray hit (wo = -ray direction). */
struct path_vertex path_vertex_from_hit(const struct surface_hit *h, vec3 ray_dir);
struct bsdf;
/* The BSDF at vertex v: its material with the textures at v's point. */
void path_vertex_bsdf(const struct scene *s, const struct path_vertex *v, struct bsdf *b);

#endif
