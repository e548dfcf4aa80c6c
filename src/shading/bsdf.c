/* bsdf.c: Lambert diffuse plus GGX specular (glTF metallic/roughness) with visible-normal
 * sampling. Must never depend on the ray tracer, lights or render passes. */
#include "shading/bsdf.h"

#include <math.h>

#include "core/sampling.h"
#include "core/simd.h"

/* max_f / min_f with the variable first return the bound for a NaN x, as fmaxf / fminf do, but
 * compile to one instruction: without -ffinite-math-only fmaxf is a libm call, and these run for
 * every BSDF built or evaluated. */
static float clampf(float x, float lo, float hi) { return min_f(max_f(x, lo), hi); }

/* Smith Lambda for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function in
 * Microfacet-Based BRDFs"), with tan^2 written as (x^2 + y^2) / z^2. */
static float ggx_lambda(vec3 w, float alpha)
{
    float z2 = w.z * w.z;
    if (z2 <= 0.0f)
        return 0.0f;
    float t2 = (w.x * w.x + w.y * w.y) / z2;
    return 0.5f * (sqrtf(1.0f + alpha * alpha * t2) - 1.0f);
}

/* Reflectance at normal incidence of glTF's dielectric (IOR 1.5). */
#define DIELECTRIC_F0 0.04f

/* Schlick 1994 weight (1 - cos)^5 of the Fresnel approximation. */
static float schlick_weight(float cos_d)
{
    float m = clampf(1.0f - cos_d, 0.0f, 1.0f);
    float m2 = m * m;
    return m2 * m2 * m;
}

static vec3 fresnel_schlick(vec3 f0, float cos_d)
{
    return v3_add(f0, v3_scale(v3_sub(v3s(1.0f), f0), schlick_weight(cos_d)));
}

static float schlick_scalar(float f0, float cos_d) { return f0 + (1.0f - f0) * schlick_weight(cos_d); }

/* The specular weight is judged by f0 because p_spec cannot depend on wo: it is fixed per
 * material so that it is the same at every vertex and in every shift. The luminance ratio of
 * the two lobes' normal-incidence albedos is a good first guess; the clamp to [0.1, 0.9]
 * keeps both lobes reachable (dielectric f0 = 0.04 would otherwise almost never sample the
 * specular lobe, whose Fresnel weight grows at grazing angles; a defensive mixture keeps
 * f cos / pdf bounded for either lobe, Hesterberg 1995, "Weighted Average Importance Sampling
 * and Defensive Mixture Distributions"). */
void bsdf_from_material(const struct material *m, struct bsdf *b)
{
    float metallic = clampf(m->metallic, 0.0f, 1.0f);
    vec3 base = v3(max_f(m->base_color.x, 0.0f), max_f(m->base_color.y, 0.0f), max_f(m->base_color.z, 0.0f));
    if (m->lambert_only) {
        b->diffuse = base;
        b->f0 = v3s(0.0f);
        b->alpha = 1.0f;
        b->p_spec = 0.0f; /* no specular lobe: eval, pdf and sample are exactly Lambert */
        return;
    }
    b->diffuse = v3_scale(base, 1.0f - metallic);
    b->f0 = v3_lerp(v3s(DIELECTRIC_F0), base, metallic);
    float r = clampf(m->roughness, 0.0f, 1.0f);
    b->alpha = max_f(r * r, BSDF_MIN_ALPHA);
    float ld = v3_luminance(b->diffuse);
    float ls = v3_luminance(b->f0);
    if (metallic >= 1.0f || ld <= 0.0f)
        b->p_spec = 1.0f;
    else
        b->p_spec = clampf(ls / (ls + ld), 0.1f, 0.9f);
}

vec3 bsdf_shading_normal(vec3 ns, vec3 ng, vec3 wo)
{
    const float c = v3_dot(ns, wo), cg = v3_dot(ng, wo);
    if (c >= BSDF_SHADING_COS_MIN || (ns.x == ng.x && ns.y == ng.y && ns.z == ng.z) || !(cg > 0.0f))
        return ns;
    vec3 n = v3_madd(ns, ng, (BSDF_SHADING_COS_MIN - c) / cg);
    float len2 = v3_length2(n);
    return len2 > 0.0f && isfinite(len2) ? v3_scale(n, 1.0f / sqrtf(len2)) : ng;
}

/* Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1: stretch wo to the
 * alpha = 1 configuration, sample the projected hemisphere (a disk whose far half is squashed
 * by the view angle), lift to the hemisphere and unstretch. Returns a unit microfacet normal
 * distributed as D_vis(h) for the given wo. */
static vec3 ggx_sample_vndf(vec3 wo, float alpha, float u1, float u2)
{
    vec3 vh = v3_normalize(v3(alpha * wo.x, alpha * wo.y, wo.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0f ? v3_scale(v3(-vh.y, vh.x, 0.0f), 1.0f / sqrtf(lensq)) : v3(1.0f, 0.0f, 0.0f);
    vec3 t2 = v3_cross(vh, t1);
    float r = sqrtf(u1);
    float phi = 2.0f * RESTIR_PI * u2;
    float p1 = r * cosf(phi);
    float p2 = r * sinf(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * sqrtf(max_f(1.0f - p1 * p1, 0.0f)) + s * p2;
    float p3 = sqrtf(max_f(1.0f - p1 * p1 - p2 * p2, 0.0f));
    vec3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(vh, p3));
    return v3_normalize(v3(alpha * nh.x, alpha * nh.y, max_f(nh.z, 0.0f)));
}

/* The lobe mixture's sample in the local frame (lo above the surface): u0 picks the lobe. */
static vec3 sample_local(const struct bsdf *b, vec3 lo, float u0, float u1, float u2)
{
    if (u0 < b->p_spec) {
        vec3 h = ggx_sample_vndf(lo, b->alpha, u1, u2);
        float d = v3_dot(lo, h);
        return v3_sub(v3_scale(h, 2.0f * d), lo); /* mirror wo about h */
    }
    return warp_cosine_hemisphere(u1, u2);
}

/* The frame's body, inlined into bsdf_eval, bsdf_pdf and bsdf_sample as well as bsdf_frame_init:
 * a one-shot evaluation then keeps the frame in registers and drops the terms it does not read
 * (the pdf's when only f is asked for), with the same operations in the same order, so the same
 * bits as through bsdf_frame_init and bsdf_frame_eval. */
SIMD_INLINE void frame_init(struct bsdf_frame *bf, const struct bsdf *b, vec3 n, vec3 wo)
{
    bf->b = *b;
    bf->fr = frame_from_normal(n);
    bf->wo_local = frame_to_local(&bf->fr, wo);
    bf->valid = bf->wo_local.z > 0.0f;
    float cos_o = max_f(bf->wo_local.z, 1e-12f);
    bf->lambda_o = b->p_spec > 0.0f ? ggx_lambda(bf->wo_local, b->alpha) : 0.0f;
    /* The factors of eval_local and pdf_local that depend on wo only. */
    float coupling = 1.0f;
    if (b->p_spec > 0.0f) {
        const float f0 = DIELECTRIC_F0;
        coupling = (1.0f - schlick_scalar(f0, cos_o)) / (1.0f - (f0 + (1.0f - f0) / 21.0f));
    }
    bf->diffuse_scale = coupling * RESTIR_INV_PI;
    bf->inv_alpha2 = 1.0f / (b->alpha * b->alpha);
    bf->spec_pdf_scale = b->p_spec / ((1.0f + bf->lambda_o) * 4.0f * cos_o);
}

/* Evaluation in the local frame (z = n), both directions already known to be above.
 * Specular: Walter et al. 2007, eq. 20, with Schlick's F at the microfacet (wi.h); Schlick is
 * linear in f0, so F with f0 = mix(0.04, base, metallic) is exactly the glTF 2.0 blend
 * (1 - metallic) * dielectric + metallic * metal of the two specular lobes.
 * Diffuse: a plain sum diffuse/pi + spec reflects more than it receives for a white dielectric
 * (albedo 1 + F), and the glTF 2.0 mix (diffuse weighted by 1 - F(wi.h), spec. Appendix B)
 * still does at grazing angles (we measured albedo 1.08 at 80 deg, roughness 0.5). We couple
 * the lobes as Kelemen & Szirmay-Kalos 2001 ("A Microfacet Based Coupled Specular-Matte BRDF
 * Model with Importance Sampling") do, with the Schlick reflectance of the dielectric
 * interface (f0 = 0.04, the one that covers the diffuse base in glTF) at the macro normal
 * standing in for their specular albedo:
 *   f_d = diffuse/pi * (1 - F(cos_o)) (1 - F(cos_i)) / (1 - F_avg),
 * F_avg = 2 int F(mu) mu dmu = f0 + (1 - f0) / 21 (the hemispherical average of Schlick).
 * It is reciprocal, and its directional albedo is exactly diffuse * (1 - F(cos_o)): the diffuse
 * lobe gets what the interface does not reflect at the viewing angle.
 * A lobe is present only when it can be sampled: the specular one only when p_spec > 0 and
 * the diffuse one only when p_spec < 1, so that the estimator f cos / pdf stays unbiased for any
 * struct bsdf (a bsdf with p_spec = 0 is pure Lambert). */
/* Mixture density: p_spec * D_vis(h) / (4 |wo.h|) + (1 - p_spec) * cos / pi, where
 * D_vis(h) = G1(wo) max(0, wo.h) D(h) / cos_o (Heitz 2018, "Sampling the GGX Distribution of
 * Visible Normals", eq. 2) and 1 / (4 wo.h) is the reflection Jacobian (Walter et al. 2007,
 * eq. 14). The wo.h factors cancel, leaving G1(wo) D(h) / (4 cos_o). */
SIMD_INLINE vec3 frame_eval(const struct bsdf_frame *bf, vec3 wi, float *pdf)
{
    const struct bsdf *b = &bf->b;
    vec3 li = frame_to_local(&bf->fr, wi);
    vec3 lo = bf->wo_local;
    if (!bf->valid || li.z <= 0.0f) {
        if (pdf)
            *pdf = 0.0f;
        return v3s(0.0f);
    }
    vec3 f = v3s(0.0f);
    float p = 0.0f;
    if (b->p_spec < 1.0f) {
        float scale = bf->diffuse_scale; /* (1 - F(cos_o)) / (1 - F_avg) / pi */
        if (b->p_spec > 0.0f)
            scale *= 1.0f - schlick_scalar(DIELECTRIC_F0, li.z);
        f = v3_scale(b->diffuse, scale);
        p = (1.0f - b->p_spec) * li.z * RESTIR_INV_PI;
    }
    if (b->p_spec > 0.0f) {
        /* GGX / Trowbridge-Reitz NDF (Walter et al. 2007, "Microfacet Models for Refraction
         * through Rough Surfaces", eq. 33) for the local half vector h, written as
         * D = 1 / (pi a^2 (h.x^2/a^2 + h.y^2/a^2 + h.z^2)^2), which avoids forming 1 - cos^2 (it
         * cancels catastrophically near the peak of the near-mirror lobes, alpha ~ 0.0025).
         * D, G2 and the 1 / (4 cos_o cos_i) of the specular term share one division: with the
         * unnormalized half vector H = wo + wi (H.z > 0: both are above), D(H / |H|) =
         * |H|^4 / (pi a^2 T^2), T = (H.x^2 + H.y^2) / a^2 + H.z^2, and
         * (1 + Lambda(wo) + Lambda(wi)) cos_i = cos_i (1/2 + Lambda(wo)) + S / 2 with
         * S = sqrt(cos_i^2 + a^2 (wi.x^2 + wi.y^2)) (ggx_lambda times cos_i). */
        vec3 H = v3_add(lo, li);
        float H2 = v3_length2(H), H4 = H2 * H2;
        float a2 = b->alpha * b->alpha;
        float T = (H.x * H.x + H.y * H.y) * bf->inv_alpha2 + H.z * H.z;
        float S = sqrtf(li.z * li.z + a2 * (li.x * li.x + li.y * li.y));
        float g2_cos_i = li.z * (0.5f + bf->lambda_o) + 0.5f * S; /* cos_i / G2 */
        float d_den = RESTIR_PI * a2 * T * T, f_den = 4.0f * lo.z * g2_cos_i;
        float r = 1.0f / (d_den * f_den);
        vec3 F = fresnel_schlick(b->f0, v3_dot(li, H) / sqrtf(H2));
        f = v3_add(f, v3_scale(F, H4 * r));
        if (v3_dot(lo, H) > 0.0f)
            p += bf->spec_pdf_scale * H4 * r * f_den; /* spec_pdf_scale * D */
    }
    if (pdf)
        *pdf = p;
    return f;
}

void bsdf_frame_init(struct bsdf_frame *bf, const struct bsdf *b, vec3 n, vec3 wo) { frame_init(bf, b, n, wo); }

vec3 bsdf_frame_eval(const struct bsdf_frame *bf, vec3 wi, float *pdf) { return frame_eval(bf, wi, pdf); }

/* bsdf_frame_sample's body (inlined into bsdf_sample too): the direction from sample_local, its
 * f and pdf from frame_eval. */
SIMD_INLINE int frame_sample(const struct bsdf_frame *bf, float u0, float u1, float u2, vec3 *wi, float *pdf, vec3 *f)
{
    if (!bf->valid)
        return 0;
    vec3 li = sample_local(&bf->b, bf->wo_local, u0, u1, u2);
    if (li.z <= 0.0f)
        return 0;
    /* pdf and f of the world-space direction returned, not of li: callers comparing them with
     * bsdf_pdf / bsdf_eval / bsdf_frame_eval of wi (the other strategy's MIS weight at the same
     * vertex) get bit-identical values, and the near-mirror lobes are steep enough that the
     * rounding of a frame round trip visibly changes the pdf. */
    vec3 w = v3_normalize(frame_to_world(&bf->fr, li));
    float p;
    vec3 fw = frame_eval(bf, w, &p);
    if (!(p > 0.0f) || !isfinite(p))
        return 0;
    *wi = w;
    *pdf = p;
    *f = fw;
    return 1;
}

int bsdf_frame_sample(const struct bsdf_frame *bf, float u0, float u1, float u2, vec3 *wi, float *pdf, vec3 *f)
{
    return frame_sample(bf, u0, u1, u2, wi, pdf, f);
}

vec3 bsdf_eval(const struct bsdf *b, vec3 n, vec3 wo, vec3 wi)
{
    struct bsdf_frame bf;
    frame_init(&bf, b, n, wo);
    return frame_eval(&bf, wi, NULL);
}

float bsdf_pdf(const struct bsdf *b, vec3 n, vec3 wo, vec3 wi)
{
    struct bsdf_frame bf;
    float p;
    frame_init(&bf, b, n, wo);
    frame_eval(&bf, wi, &p);
    return p;
}

int bsdf_sample(const struct bsdf *b, vec3 n, vec3 wo, float u0, float u1, float u2, vec3 *wi,
                float *pdf, vec3 *f)
{
    struct bsdf_frame bf;
    frame_init(&bf, b, n, wo);
    return frame_sample(&bf, u0, u1, u2, wi, pdf, f);
}

SIMD_INLINE void eval_batch_body(const struct bsdf_frame *bf, int n, const float *restrict wx,
                                 const float *restrict wy, const float *restrict wz, float *restrict fr,
                                 float *restrict fg, float *restrict fb, float *restrict pdf)
{
    const struct bsdf *b = &bf->b;
    const frame fr_ = bf->fr;
    const vec3 lo = bf->wo_local;
    const float a = b->alpha, a2 = a * a, inv_a2 = 1.0f / a2;
    const float has_diffuse = b->p_spec < 1.0f ? 1.0f : 0.0f, has_spec = b->p_spec > 0.0f ? 1.0f : 0.0f;
    /* Diffuse coupling only for mixed materials (see eval_local). */
    const float couple = b->p_spec > 0.0f ? 1.0f : 0.0f;
    const float dscale = has_diffuse * bf->diffuse_scale, dpdf = (1.0f - b->p_spec) * RESTIR_INV_PI;
    const float one_m_f0d = 1.0f - DIELECTRIC_F0;
    const float valid = bf->valid ? 1.0f : 0.0f;
    const float four_cos_o = 4.0f * max_f(lo.z, 1e-12f);
    const float lambda_o = bf->lambda_o, spec_pdf = has_spec * bf->spec_pdf_scale;
    /* Locals, not loads through b inside the loop: the stores below could alias them. */
    const float kdr = b->diffuse.x, kdg = b->diffuse.y, kdb = b->diffuse.z;
    const float f0r = b->f0.x, f0g = b->f0.y, f0b = b->f0.z;
    const float tx = fr_.t.x, ty = fr_.t.y, tz = fr_.t.z, bx = fr_.b.x, by = fr_.b.y, bz = fr_.b.z;
    const float nx = fr_.n.x, ny = fr_.n.y, nz = fr_.n.z, ox = lo.x, oy = lo.y, oz = lo.z;
    for (int k = 0; k < n; k++) {
        /* to local frame */
        float lx = wx[k] * tx + wy[k] * ty + wz[k] * tz;
        float ly = wx[k] * bx + wy[k] * by + wz[k] * bz;
        float lz = wx[k] * nx + wy[k] * ny + wz[k] * nz;
        float above = lz > 0.0f ? valid : 0.0f;
        float cz = max_f(lz, 1e-12f);
        /* diffuse with the Kelemen coupling (1 - F(cos_i)) for mixed materials */
        float m = min_f(max_f(1.0f - cz, 0.0f), 1.0f), m2 = m * m, sw = m2 * m2 * m;
        float couple_i = 1.0f - couple * (DIELECTRIC_F0 + one_m_f0d * sw);
        float fd = dscale * couple_i;
        /* specular as in bsdf_frame_eval, with the unnormalized half vector H = wo + wi: one
         * division for D, G2 and 1 / (4 cos_o cos_i) together, and wi.h = |H| / 2 (for unit wo
         * and wi, |H|^2 = 2 (1 + wo.wi) = 2 wi.H), so Schlick's F needs no normalization. */
        float hx = ox + lx, hy = oy + ly, hz = oz + lz;
        float h2 = max_f(hx * hx + hy * hy + hz * hz, 1e-30f), h4 = h2 * h2;
        float t = (hx * hx + hy * hy) * inv_a2 + hz * hz;
        float cos_d = 0.5f * sqrtf(h2);
        float mh = min_f(max_f(1.0f - cos_d, 0.0f), 1.0f), mh2 = mh * mh, swh = mh2 * mh2 * mh;
        float S = sqrtf(cz * cz + a2 * (lx * lx + ly * ly));
        float f_den = four_cos_o * (cz * (0.5f + lambda_o) + 0.5f * S); /* 4 cos_o cos_i / G2 */
        float r = (hz > 0.0f ? has_spec : 0.0f) / (RESTIR_PI * a2 * t * t * f_den);
        float s = h4 * r; /* D G2 / (4 cos_o cos_i) */
        fr[k] = above * (kdr * fd + (f0r + (1.0f - f0r) * swh) * s);
        fg[k] = above * (kdg * fd + (f0g + (1.0f - f0g) * swh) * s);
        fb[k] = above * (kdb * fd + (f0b + (1.0f - f0b) * swh) * s);
        float wo_h = ox * hx + oy * hy + oz * hz;
        pdf[k] = above * (dpdf * lz + (wo_h > 0.0f ? spec_pdf * s * f_den : 0.0f));
    }
}

static void eval_batch_baseline(const struct bsdf_frame *bf, int n, const float *wx, const float *wy,
                                const float *wz, float *fr, float *fg, float *fb, float *pdf)
{
    eval_batch_body(bf, n, wx, wy, wz, fr, fg, fb, pdf);
}

SIMD_TARGET_AVX2 static void eval_batch_avx2(const struct bsdf_frame *bf, int n, const float *wx, const float *wy,
                                             const float *wz, float *fr, float *fg, float *fb, float *pdf)
{
    eval_batch_body(bf, n, wx, wy, wz, fr, fg, fb, pdf);
}

void bsdf_frame_eval_batch(const struct bsdf_frame *bf, int n, const float *restrict wx,
                           const float *restrict wy, const float *restrict wz, float *restrict fr,
                           float *restrict fg, float *restrict fb, float *restrict pdf)
{
    if (simd_isa_active() >= SIMD_ISA_AVX2)
        eval_batch_avx2(bf, n, wx, wy, wz, fr, fg, fb, pdf);
    else
        eval_batch_baseline(bf, n, wx, wy, wz, fr, fg, fb, pdf);
}

/* bsdf_frame_eval_lanes over at most BSDF_LANES lanes: the frames' parameters gathered into
 * arrays, then one branch-free loop that mirrors bsdf_frame_eval's operations and their order
 * (selects where it branches), so every lane gets bsdf_frame_eval's bits. */
#define BSDF_LANES 64
SIMD_INLINE void eval_lanes_chunk(int n, const struct bsdf_frame *const *bf, const float *restrict wx,
                                  const float *restrict wy, const float *restrict wz, float *restrict fr,
                                  float *restrict fg, float *restrict fb)
{
    float tx[BSDF_LANES], ty[BSDF_LANES], tz[BSDF_LANES], bx[BSDF_LANES], by[BSDF_LANES], bz[BSDF_LANES];
    float nx[BSDF_LANES], ny[BSDF_LANES], nz[BSDF_LANES], ox[BSDF_LANES], oy[BSDF_LANES], oz[BSDF_LANES];
    float lambda_o[BSDF_LANES], dscale[BSDF_LANES], inv_a2[BSDF_LANES], alpha[BSDF_LANES], p_spec[BSDF_LANES];
    float kdr[BSDF_LANES], kdg[BSDF_LANES], kdb[BSDF_LANES], f0r[BSDF_LANES], f0g[BSDF_LANES], f0b[BSDF_LANES];
    int valid[BSDF_LANES];
    for (int k = 0; k < n; k++) {
        const struct bsdf_frame *f = bf[k];
        tx[k] = f->fr.t.x, ty[k] = f->fr.t.y, tz[k] = f->fr.t.z;
        bx[k] = f->fr.b.x, by[k] = f->fr.b.y, bz[k] = f->fr.b.z;
        nx[k] = f->fr.n.x, ny[k] = f->fr.n.y, nz[k] = f->fr.n.z;
        ox[k] = f->wo_local.x, oy[k] = f->wo_local.y, oz[k] = f->wo_local.z;
        lambda_o[k] = f->lambda_o, dscale[k] = f->diffuse_scale, inv_a2[k] = f->inv_alpha2;
        alpha[k] = f->b.alpha, p_spec[k] = f->b.p_spec, valid[k] = f->valid;
        kdr[k] = f->b.diffuse.x, kdg[k] = f->b.diffuse.y, kdb[k] = f->b.diffuse.z;
        f0r[k] = f->b.f0.x, f0g[k] = f->b.f0.y, f0b[k] = f->b.f0.z;
    }
    for (int k = 0; k < n; k++) {
        const float lx = wx[k] * tx[k] + wy[k] * ty[k] + wz[k] * tz[k]; /* frame_to_local */
        const float ly = wx[k] * bx[k] + wy[k] * by[k] + wz[k] * bz[k];
        const float lz = wx[k] * nx[k] + wy[k] * ny[k] + wz[k] * nz[k];
        const int has_d = p_spec[k] < 1.0f, has_s = p_spec[k] > 0.0f;
        /* diffuse: diffuse_scale, times 1 - F(cos_i) for mixed materials */
        const float m = clampf(1.0f - lz, 0.0f, 1.0f), m2 = m * m, w_i = m2 * m2 * m;
        const float scale = has_s ? dscale[k] * (1.0f - (DIELECTRIC_F0 + (1.0f - DIELECTRIC_F0) * w_i)) : dscale[k];
        const float dr = has_d ? kdr[k] * scale : 0.0f, dg = has_d ? kdg[k] * scale : 0.0f;
        const float db = has_d ? kdb[k] * scale : 0.0f;
        /* specular */
        const float hx = ox[k] + lx, hy = oy[k] + ly, hz = oz[k] + lz;
        const float h2 = hx * hx + hy * hy + hz * hz, h4 = h2 * h2;
        const float a2 = alpha[k] * alpha[k];
        const float t = (hx * hx + hy * hy) * inv_a2[k] + hz * hz;
        const float S = sqrtf(lz * lz + a2 * (lx * lx + ly * ly));
        const float g2_cos_i = lz * (0.5f + lambda_o[k]) + 0.5f * S;
        const float d_den = RESTIR_PI * a2 * t * t, f_den = 4.0f * oz[k] * g2_cos_i;
        const float r = 1.0f / (d_den * f_den);
        const float mh = clampf(1.0f - (lx * hx + ly * hy + lz * hz) / sqrtf(h2), 0.0f, 1.0f);
        const float mh2 = mh * mh, w_h = mh2 * mh2 * mh, s = h4 * r;
        const float sr = (f0r[k] + (1.0f - f0r[k]) * w_h) * s, sg = (f0g[k] + (1.0f - f0g[k]) * w_h) * s;
        const float sb = (f0b[k] + (1.0f - f0b[k]) * w_h) * s;
        const int above = valid[k] && !(lz <= 0.0f); /* as bsdf_frame_eval's test, NaN included */
        fr[k] = above ? (has_s ? dr + sr : dr) : 0.0f;
        fg[k] = above ? (has_s ? dg + sg : dg) : 0.0f;
        fb[k] = above ? (has_s ? db + sb : db) : 0.0f;
    }
}

SIMD_INLINE void eval_lanes(int n, const struct bsdf_frame *const *bf, const float *wx, const float *wy,
                            const float *wz, float *fr, float *fg, float *fb)
{
    for (int first = 0; first < n; first += BSDF_LANES)
        eval_lanes_chunk(n - first < BSDF_LANES ? n - first : BSDF_LANES, bf + first, wx + first, wy + first,
                         wz + first, fr + first, fg + first, fb + first);
}

static void eval_lanes_baseline(int n, const struct bsdf_frame *const *bf, const float *wx, const float *wy,
                                const float *wz, float *fr, float *fg, float *fb)
{
    eval_lanes(n, bf, wx, wy, wz, fr, fg, fb);
}

SIMD_TARGET_AVX2 static void eval_lanes_avx2(int n, const struct bsdf_frame *const *bf, const float *wx,
                                             const float *wy, const float *wz, float *fr, float *fg, float *fb)
{
    eval_lanes(n, bf, wx, wy, wz, fr, fg, fb);
}

void bsdf_frame_eval_lanes(int n, const struct bsdf_frame *const *bf, const float *wx, const float *wy,
                           const float *wz, float *fr, float *fg, float *fb)
{
    if (simd_isa_active() >= SIMD_ISA_AVX2)
        eval_lanes_avx2(n, bf, wx, wy, wz, fr, fg, fb);
    else
        eval_lanes_baseline(n, bf, wx, wy, wz, fr, fg, fb);
}

/* Heuristic for ReSTIR PT's hybrid shift (Lin et al. 2022, "Generalized Resampled Importance
 * Sampling": reconnect only at vertices that are rough enough). Only a purely specular-sampled
 * material (metal, or black diffuse, p_spec = 1) is judged by its GGX alpha; anything with a
 * diffuse lobe reports 1 (fully rough). That is always unbiased (the shift stays invertible),
 * but a mixed material with a sharp specular lobe (e.g. metallic 0.5, roughness 0.2) is then
 * reconnected at, which can be noisy there. */
float bsdf_roughness(const struct bsdf *b) { return b->p_spec >= 1.0f ? b->alpha : 1.0f; }
