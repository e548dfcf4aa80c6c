/* bsdf.h: the material model: Lambert diffuse plus GGX microfacet specular (glTF
 * metallic/roughness), with eval / sample / pdf. All directions are unit vectors pointing away
 * from the surface; pdfs are in solid angle; eval returns f_r without the cosine.
 * Must never depend on the ray tracer or on render passes. */
#ifndef RESTIR_SHADING_BSDF_H
#define RESTIR_SHADING_BSDF_H

#include "core/vec3.h"
#include "scene/scene.h"

/* Minimum GGX alpha: keeps near-mirror lobes finite so eval/pdf stay well defined. */
#define BSDF_MIN_ALPHA 0.0025f

struct bsdf {
    vec3 diffuse;   /* Lambert albedo: base_color * (1 - metallic) */
    vec3 f0;        /* Schlick reflectance at normal incidence: mix(0.04, base_color, metallic) */
    float alpha;    /* GGX alpha = max(roughness^2, BSDF_MIN_ALPHA) */
    float p_spec;   /* probability of sampling the specular lobe */
};

void bsdf_from_material(const struct material *m, struct bsdf *b);

/* Shading normals. The BSDF's normal at a point is the interpolated shading normal ns
 * (scene_shading_normal, on the side of the geometric normal ng facing wo), bent toward ng where wo
 * would be below or grazing it: ns' = normalize(ns + t ng) with t = (c_min - ns.wo) / (ng.wo),
 * so ns'.wo > 0 (the "black facet" a view below the interpolated hemisphere would see; the bend
 * of Keller et al. 2017, "The Iray light transport simulation and rendering system", Sec. A.3,
 * in its simplest form). A function of (ns, ng, wo) only: every estimator and shift evaluates f at
 * a vertex through it with that vertex's own wo, so they integrate the same f. Light leaks are the
 * callers' geometric test: directions must leave on ng's side (wi.ng > 0) as well as on ns''s.
 * Returns ns unchanged where ns == ng (flat shading) or ns.wo >= c_min. */
#define BSDF_SHADING_COS_MIN 0.01f
vec3 bsdf_shading_normal(vec3 ns, vec3 ng, vec3 wo);

/* f_r(wo, wi) for normal n (n on the side of wo; zero when either direction is below). */
vec3 bsdf_eval(const struct bsdf *b, vec3 n, vec3 wo, vec3 wi);
/* Solid-angle density with which bsdf_sample produces wi. */
float bsdf_pdf(const struct bsdf *b, vec3 n, vec3 wo, vec3 wi);
/* Samples wi from three uniforms. Returns 0 when no direction is produced (e.g. below the
 * surface); otherwise 1 with *wi, *pdf (solid angle, equal to bsdf_pdf) and *f = bsdf_eval. */
int bsdf_sample(const struct bsdf *b, vec3 n, vec3 wo, float u0, float u1, float u2, vec3 *wi,
                float *pdf, vec3 *f);
/* A BSDF prepared for one shading point and outgoing direction: the local frame and every term
 * that depends on wo only, so that evaluating many wi (RIS candidates, reuse) is cheap. */
struct bsdf_frame {
    struct bsdf b;
    frame fr;
    vec3 wo_local;
    float lambda_o;      /* Smith Lambda(wo) */
    float diffuse_scale; /* Kelemen coupling factor (1 - F(cos_o)) / (1 - F_avg) times 1/pi */
    float spec_pdf_scale;/* p_spec G1(wo) / (4 cos_o) */
    float inv_alpha2;    /* 1 / alpha^2 */
    int valid;           /* wo above the surface */
};

void bsdf_frame_init(struct bsdf_frame *bf, const struct bsdf *b, vec3 n, vec3 wo);
/* f_r(wo, wi) as bsdf_eval, and when pdf != NULL the solid-angle density of wi as bsdf_pdf. */
vec3 bsdf_frame_eval(const struct bsdf_frame *bf, vec3 wi, float *pdf);

/* bsdf_sample with the prepared frame: the same directions for the same uniforms (up to the
 * rounding of the frame), with *pdf and *f = bsdf_frame_eval of the returned wi. Where one shading
 * point both samples and evaluates (a path vertex: NEE and the continuation) this builds the frame
 * and the wo terms once instead of per call. */
int bsdf_frame_sample(const struct bsdf_frame *bf, float u0, float u1, float u2, vec3 *wi, float *pdf, vec3 *f);

/* bsdf_frame_eval over n directions in structure-of-arrays form (world space, unit), written
 * branch-free so the compiler vectorizes it: f_r into fr/fg/fb and the solid-angle pdf into pdf.
 * Directions below the surface get 0. Agrees with bsdf_frame_eval to rounding. */
void bsdf_frame_eval_batch(const struct bsdf_frame *bf, int n, const float *restrict wx,
                           const float *restrict wy, const float *restrict wz, float *restrict fr,
                           float *restrict fg, float *restrict fb, float *restrict pdf);

/* f_r of n (frame, direction) pairs, one frame per lane (SIMD across shading points: each lane a
 * different pixel's frame): fr/fg/fb[k] = bsdf_frame_eval(bf[k], (wx, wy, wz)[k], NULL), bit for
 * bit, on the baseline and the AVX2 path alike (core/simd.h). */
void bsdf_frame_eval_lanes(int n, const struct bsdf_frame *const *bf, const float *wx, const float *wy,
                           const float *wz, float *fr, float *fg, float *fb);

/* Roughness measure used by path-space heuristics (GGX alpha; 1 for pure diffuse). */
float bsdf_roughness(const struct bsdf *b);

#endif
