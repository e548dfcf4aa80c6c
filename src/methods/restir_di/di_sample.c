/* di_sample.c: evaluation of the ReSTIR DI integrand without visibility, shared by initial
 * sampling, temporal and spatial reuse and shading. Must never trace rays. */
#include "methods/restir_di/di_sample.h"

#include <math.h>
#include <stddef.h>

#include "core/simd.h"
#include "render/nonfinite.h"

vec3 di_unshadowed_pdf(const struct shading_point *sp, const struct di_sample *y, float *bsdf_pdf_area)
{
    if (bsdf_pdf_area)
        *bsdf_pdf_area = 0.0f;
    if (!sp->valid || y->tri < 0)
        return v3s(0.0f);
    const int env = y->tri == DI_ENV_TRI;
    vec3 to = env ? y->p : v3_sub(y->p, sp->p);
    float d2 = env ? 1.0f : v3_length2(to);
    if (!(d2 > 0.0f))
        return v3s(0.0f);
    vec3 wi = env ? to : v3_scale(to, 1.0f / sqrtf(d2));
    float cos_x = v3_dot(sp->n, wi), cos_y = -v3_dot(y->n, wi);
    if (cos_x <= 0.0f || cos_y <= 0.0f || v3_dot(sp->ng, wi) <= 0.0f)
        return v3s(0.0f);
    float pdf_sa;
    vec3 f = bsdf_frame_eval(&sp->bf, wi, bsdf_pdf_area ? &pdf_sa : NULL);
    float g = cos_y / d2; /* solid angle to area at y */
    if (bsdf_pdf_area)
        *bsdf_pdf_area = pdf_sa * g;
    return v3_scale(v3_mul(y->Le, f), cos_x * g);
}

vec3 di_unshadowed(const struct shading_point *sp, const struct di_sample *y)
{
    return di_unshadowed_pdf(sp, y, NULL);
}

float di_target(const struct shading_point *sp, const struct di_sample *y)
{
    return v3_luminance(di_unshadowed(sp, y));
}

/* di_target_many over at most DI_LANES pairs: the geometry of di_unshadowed_pdf in one
 * branch-free loop over gathered arrays (selects where it returns early), the BSDF through
 * bsdf_frame_eval_lanes, then the product and luminance in di_target's order. */
#define DI_LANES 64
SIMD_INLINE void geometry_chunk(int n, const struct shading_point *const *sp, const struct di_sample *const *y,
                                float *restrict wx, float *restrict wy, float *restrict wz, float *restrict cg,
                                int *restrict ok)
{
    float px[DI_LANES], py[DI_LANES], pz[DI_LANES], nx[DI_LANES], ny[DI_LANES], nz[DI_LANES];
    float gx[DI_LANES], gy[DI_LANES], gz[DI_LANES], yx[DI_LANES], yy[DI_LANES], yz[DI_LANES];
    float mx[DI_LANES], my[DI_LANES], mz[DI_LANES];
    int live[DI_LANES], env[DI_LANES];
    for (int k = 0; k < n; k++) {
        const struct shading_point *s = sp[k];
        const struct di_sample *q = y[k];
        px[k] = s->p.x, py[k] = s->p.y, pz[k] = s->p.z;
        nx[k] = s->n.x, ny[k] = s->n.y, nz[k] = s->n.z;
        gx[k] = s->ng.x, gy[k] = s->ng.y, gz[k] = s->ng.z;
        yx[k] = q->p.x, yy[k] = q->p.y, yz[k] = q->p.z;
        mx[k] = q->n.x, my[k] = q->n.y, mz[k] = q->n.z;
        live[k] = s->valid && q->tri >= 0;
        env[k] = q->tri == DI_ENV_TRI;
    }
    for (int k = 0; k < n; k++) {
        /* an environment sample holds its direction: d2 = 1 and wi = to exactly */
        const float tx = env[k] ? yx[k] : yx[k] - px[k], ty = env[k] ? yy[k] : yy[k] - py[k];
        const float tz = env[k] ? yz[k] : yz[k] - pz[k];
        const float d2 = env[k] ? 1.0f : tx * tx + ty * ty + tz * tz;
        const float inv = 1.0f / sqrtf(d2);
        const float dx = tx * inv, dy = ty * inv, dz = tz * inv;
        const float cos_x = nx[k] * dx + ny[k] * dy + nz[k] * dz;
        const float cos_y = -(mx[k] * dx + my[k] * dy + mz[k] * dz);
        const float cos_g = gx[k] * dx + gy[k] * dy + gz[k] * dz;
        wx[k] = dx, wy[k] = dy, wz[k] = dz;
        cg[k] = cos_x * (cos_y / d2);
        /* as di_unshadowed_pdf's tests, NaN included */
        ok[k] = live[k] && d2 > 0.0f && !(cos_x <= 0.0f) && !(cos_y <= 0.0f) && !(cos_g <= 0.0f);
    }
}

SIMD_INLINE void combine_chunk(int n, const struct di_sample *const *y, const float *restrict fr,
                               const float *restrict fg, const float *restrict fb, const float *restrict cg,
                               const int *restrict ok, float *restrict out)
{
    float lr[DI_LANES], lg[DI_LANES], lb[DI_LANES];
    for (int k = 0; k < n; k++)
        lr[k] = y[k]->Le.x, lg[k] = y[k]->Le.y, lb[k] = y[k]->Le.z;
    for (int k = 0; k < n; k++) {
        const float t = 0.2126f * (lr[k] * fr[k] * cg[k]) + 0.7152f * (lg[k] * fg[k] * cg[k]) +
                        0.0722f * (lb[k] * fb[k] * cg[k]);
        out[k] = ok[k] ? t : 0.0f;
    }
}

static void geometry_baseline(int n, const struct shading_point *const *sp, const struct di_sample *const *y,
                              float *wx, float *wy, float *wz, float *cg, int *ok)
{
    geometry_chunk(n, sp, y, wx, wy, wz, cg, ok);
}

SIMD_TARGET_AVX2 static void geometry_avx2(int n, const struct shading_point *const *sp,
                                           const struct di_sample *const *y, float *wx, float *wy, float *wz,
                                           float *cg, int *ok)
{
    geometry_chunk(n, sp, y, wx, wy, wz, cg, ok);
}

static void combine_baseline(int n, const struct di_sample *const *y, const float *fr, const float *fg,
                             const float *fb, const float *cg, const int *ok, float *out)
{
    combine_chunk(n, y, fr, fg, fb, cg, ok, out);
}

SIMD_TARGET_AVX2 static void combine_avx2(int n, const struct di_sample *const *y, const float *fr,
                                          const float *fg, const float *fb, const float *cg, const int *ok,
                                          float *out)
{
    combine_chunk(n, y, fr, fg, fb, cg, ok, out);
}

void di_target_many(int n, const struct shading_point *const *sp, const struct di_sample *const *y, float *out)
{
    const int avx2 = simd_isa_active() >= SIMD_ISA_AVX2;
    for (int first = 0; first < n; first += DI_LANES) {
        const int m = n - first < DI_LANES ? n - first : DI_LANES;
        float wx[DI_LANES], wy[DI_LANES], wz[DI_LANES], cg[DI_LANES], fr[DI_LANES], fg[DI_LANES], fb[DI_LANES];
        int ok[DI_LANES];
        const struct bsdf_frame *bf[DI_LANES];
        for (int k = 0; k < m; k++)
            bf[k] = &sp[first + k]->bf;
        if (avx2)
            geometry_avx2(m, sp + first, y + first, wx, wy, wz, cg, ok);
        else
            geometry_baseline(m, sp + first, y + first, wx, wy, wz, cg, ok);
        bsdf_frame_eval_lanes(m, bf, wx, wy, wz, fr, fg, fb);
        if (avx2)
            combine_avx2(m, y + first, fr, fg, fb, cg, ok, out + first);
        else
            combine_baseline(m, y + first, fr, fg, fb, cg, ok, out + first);
    }
}

NONFINITE_DEFINE_DISCARD(nonfinite_discard_di, struct di_reservoir, di_reservoir_clear)
