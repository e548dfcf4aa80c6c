/* svgf_taps.h: the bodies of SVGF's cross-bilateral kernels (svgf_kernels.h) on DV_LANES-lane
 * vectors, for blocks of DV_LANES pixels of a row whose centre features and sums stay in registers
 * across every tap. Included once per instruction set (svgf_taps.c: 8 lanes for the SSE2 baseline
 * and AVX2; svgf_taps512.c: 16 lanes for AVX-512). Weights, with a = |z_p - z_q| / (sigma_z
 * |grad z_p . (p - q)| + eps z_p):
 *   à-trous (Sec. 4.3, Eq. 3-5): h(q) max(0, n_p . n_q)^sigma_n exp(-a - |l_p - l_q| / (sigma_l
 *   sqrt(g_3x3(Var_p)) + eps)) over the 5x5 taps at step 2^i; colour by w, variance by w^2 (Eq. 2);
 *   with denoise.svgf.luminance_weight=symmetric the luminance term's denominator is the mean of the
 *   centre's and the tap's, sigma_l (sqrt(g_3x3(Var_p)) + sqrt(g_3x3(Var_q))) / 2 + eps, so that
 *   w(p, q) = w(q, p) up to the depth term;
 *   moments (Sec. 4.2): max(0, n_p . n_q)^sigma_n exp(-a) over the 7x7 taps, for the pixels whose
 *   history is shorter than svgf_variance_frames.
 * Taps of unused pixels have depth +inf (denoise.c), hence weight 0; so does a tap of another group
 * (a pixel whose albedo leaves other channels undivided, struct denoise_frame). */
#ifndef RESTIR_DENOISE_SVGF_TAPS_H
#define RESTIR_DENOISE_SVGF_TAPS_H

#include <math.h>

#include "denoise/denoise_kernel.h"
#include "denoise/denoise_vec.h"
#include "denoise/svgf_kernels.h"

/* The kernels: the paper's 5x5 à-trous (h the B3 spline), the 3x3 one of denoise.svgf.kernel=3
 * (h = (1, 2, 1) / 4, a deviation for speed), the 7x7 moments filter. */
enum { SVGF_ATROUS, SVGF_ATROUS3, SVGF_MOMENTS };

static const float svgf_h3[3] = {0.25f, 0.5f, 0.25f};

/* The kernel's radius and its 1D tap weight at offset t (-r .. r). */
SIMD_INLINE int svgf_radius(int kind) { return kind == SVGF_ATROUS ? 2 : kind == SVGF_ATROUS3 ? 1 : 3; }
SIMD_INLINE float svgf_h(int kind, int t)
{
    return kind == SVGF_ATROUS ? denoise_b3[t + 2] : kind == SVGF_ATROUS3 ? svgf_h3[t + 1] : 1.0f;
}

/* The centre's planes and the taps' (NULL: not read by that kernel). Index 0 is depth in both; the
 * moments kernel reads the first Q_MOMENTS tap planes, the à-trous all. */
enum { C_Z, C_N0, C_N1, C_N2, C_GX, C_GY, C_GROUP, C_V0, C_V1, C_L, C_IL, C_V2, C_V3, C_LEN, C_PLANES };
enum { Q_Z, Q_N0, Q_N1, Q_N2, Q_GROUP, Q_V0, Q_V1, Q_MOMENTS, Q_L = Q_MOMENTS, Q_V2, Q_V3, Q_IL, Q_PLANES };

static inline void svgf_bases(const struct svgf_pass *p, int kind, const float *c[C_PLANES], const float *t[Q_PLANES])
{
    const struct denoise_frame *f = p->f;
    const int at = kind != SVGF_MOMENTS;
    const float *cb[C_PLANES] = {f->depth,
                                 f->normal[0],
                                 f->normal[1],
                                 f->normal[2],
                                 f->ddx,
                                 f->ddy,
                                 f->group,
                                 p->val[0],
                                 p->val[1],
                                 at ? p->lum : NULL,
                                 at ? p->invl : NULL,
                                 at ? p->val[2] : NULL,
                                 at ? p->val[3] : NULL,
                                 at ? NULL : p->len};
    const float *tb[Q_PLANES] = {f->depth,          f->normal[0],          f->normal[1],          f->normal[2],
                                 f->group,          p->val[0],             p->val[1],             at ? p->lum : NULL,
                                 at ? p->val[2] : NULL, at ? p->val[3] : NULL, at ? p->invl : NULL};
    memcpy(c, cb, sizeof(cb));
    memcpy(t, tb, sizeof(tb));
}

/* Pointers to DV_LANES pixels from q on in the first count planes: into the planes where inside,
 * else into copies in pad holding lanes [lo, hi) and an unused pixel (depth +inf, else 0) in the
 * others. */
SIMD_INLINE void svgf_point(const float *const base[], int count, int q, int inside, int lo, int hi,
                            float pad[][DV_LANES], const float *ptr[])
{
    for (int k = 0; k < count; k++) {
        if (inside) {
            ptr[k] = base[k] + q;
            continue;
        }
        for (int l = 0; l < DV_LANES; l++)
            pad[k][l] = l >= lo && l < hi ? base[k][q + l] : (k == 0 ? INFINITY : 0.0f);
        ptr[k] = pad[k];
    }
}

/* One tap's weight wt into the sums: sum[0] the weights, sum[1..2] the weighted values v[0..1], and
 * for the à-trous (at) sum[3] the weighted v2 and sum[4] the variance v3 weighted by wt^2 (Eq. 2). */
SIMD_INLINE void svgf_add(dv_f sum[5], dv_f wt, const float *const v[2], const float *v2, const float *v3, int at)
{
    sum[0] += wt;
    sum[1] += wt * dv_load(v[0]);
    sum[2] += wt * dv_load(v[1]);
    if (at) {
        sum[3] += wt * dv_load(v2);
        sum[4] += wt * wt * dv_load(v3);
    }
}

/* The pixels x .. x + DV_LANES - 1 of row y (those inside the image). inside: every tap of every
 * lane lies in the row. squarings >= 0: sigma_n = 2^squarings, the power taken by squaring (the
 * default 128 = 2^7), 0 where n . n' < nd_min (below 2^DENOISE_EXP2_CUT, never a denormal); -1:
 * any sigma_n, by exp2(sigma_n log2(n . n')). sym: the symmetric luminance term. Called with
 * constants: each case compiles apart. */
SIMD_INLINE void svgf_block(const struct svgf_pass *p, const float *const cb[C_PLANES],
                            const float *const tb[Q_PLANES], int y, int x, int inside, int squarings, int sym,
                            int kind)
{
    const int w = p->f->width, h = p->f->height, i = y * w + x;
    const int at = kind != SVGF_MOMENTS, r = svgf_radius(kind), step = at ? p->step : 1;
    const int lanes = w - x < DV_LANES ? w - x : DV_LANES;
    float cpad[C_PLANES][DV_LANES], tpad[Q_PLANES][DV_LANES];
    const float *c[C_PLANES], *t[Q_PLANES];
    svgf_point(cb, at ? C_LEN : C_L, i, inside, 0, lanes, cpad, c);
    if (!at)
        svgf_point(cb + C_LEN, 1, i, inside, 0, lanes, cpad + C_LEN, c + C_LEN);
    const dv_f zp = dv_load(c[C_Z]), gx = dv_load(c[C_GX]), gy = dv_load(c[C_GY]), ez = p->eps_ln2 * zp;
    const dv_f n0 = dv_load(c[C_N0]), n1 = dv_load(c[C_N1]), n2 = dv_load(c[C_N2]);
    const dv_f lp = at ? dv_load(c[C_L]) : zp, ip = at ? dv_load(c[C_IL]) : zp, gp = dv_load(c[C_GROUP]);
    dv_f sum[5] = {dv_splat(0.0f), dv_splat(0.0f), dv_splat(0.0f), dv_splat(0.0f), dv_splat(0.0f)};
    for (int ty = -r; ty <= r; ty++) {
        const int oy = ty * step, yq = y + oy;
        if (yq < 0 || yq >= h)
            continue;
        const dv_f goy = gy * (float)oy;
#pragma GCC unroll 7
        for (int tx = -r; tx <= r; tx++) {
            const int ox = tx * step, q = yq * w + x + ox;
            if (tx == 0 && ty == 0) { /* the centre: every edge-stopping factor is exactly 1 */
                svgf_add(sum, dv_splat(svgf_h(kind, 0) * svgf_h(kind, 0)), c + C_V0, c[C_V2], c[C_V3], at);
                continue;
            }
            const int lo = x + ox < 0 ? -(x + ox) : 0, hi = w - (x + ox) < lanes ? w - (x + ox) : lanes;
            svgf_point(tb, at ? Q_PLANES : Q_MOMENTS, q, inside, lo, hi, tpad, t);
            /* 1 / Eq. 3's denominator depends on the centre alone: off the taps' dependency chain */
            const dv_f rden = 1.0f / (p->sz_ln2 * dv_abs(gx * (float)ox + goy) + ez);
            dv_f a = dv_abs(zp - dv_load(t[Q_Z])) * rden;
            if (at && sym) { /* log2(e) / (sigma_l (sd_p + sd_q) / 2 + eps): the harmonic mean of ip and iq */
                const dv_f iq = dv_load(t[Q_IL]);
                a += dv_abs(lp - dv_load(t[Q_L])) * (2.0f * ip * iq / (ip + iq));
            } else if (at) {
                a += dv_abs(lp - dv_load(t[Q_L])) * ip;
            }
            dv_f nd = n0 * dv_load(t[Q_N0]) + n1 * dv_load(t[Q_N1]) + n2 * dv_load(t[Q_N2]);
            dv_f wt;
            if (squarings >= 0) {
                nd = (dv_f)((dv_i)nd & (nd >= p->nd_min));
                for (int k = 0; k < squarings; k++)
                    nd *= nd;
                wt = nd * dv_exp2_neg(a);
            } else {
                dv_f l2;
                for (int l = 0; l < DV_LANES; l++) /* rare (sigma_n not a power of 2): scalar log2 */
                    l2[l] = denoise_log2(nd[l] > 1e-20f ? nd[l] : 1e-20f);
                wt = dv_exp2_neg(a - p->sn * l2);
            }
            if (at)
                wt *= svgf_h(kind, ty) * svgf_h(kind, tx);
            wt = (dv_f)((dv_i)wt & (dv_load(t[Q_GROUP]) == gp));
            svgf_add(sum, wt, t + Q_V0, t[Q_V2], t[Q_V3], at);
        }
    }
    const dv_i used = gp != 0.0f;
    const dv_f zero = dv_splat(0.0f);
    dv_f out[4];
    int outs = 4;
    const dv_f sw = sum[0];
    if (at) {
        out[0] = dv_select(used, sum[1] / sw, zero);
        out[1] = dv_select(used, sum[2] / sw, zero);
        out[2] = dv_select(used, sum[3] / sw, zero);
        out[3] = dv_select(used, sum[4] / (sw * sw), zero);
    } else { /* the filtered moments' variance where the history is short; the row holds the others' */
        const dv_f m1 = sum[1] / sw, var = sum[2] / sw - m1 * m1;
        const dv_i filtered = used & (dv_load(c[C_LEN]) < p->short_history);
        out[0] = dv_select(filtered, dv_select(var > 0.0f, var, zero), dv_load(p->out[0] + i));
        outs = 1;
    }
    for (int k = 0; k < outs; k++)
        if (lanes == DV_LANES)
            dv_store(p->out[k] + i, out[k]);
        else
            for (int l = 0; l < lanes; l++)
                p->out[k][i + l] = out[k][l];
}

/* One row: blocks of DV_LANES pixels; those with taps outside the image through copies. */
SIMD_INLINE void svgf_row(const struct svgf_pass *p, int y, int kind)
{
    const int w = p->f->width, at = kind != SVGF_MOMENTS, reach = svgf_radius(kind) * (at ? p->step : 1);
    const float *cb[C_PLANES], *tb[Q_PLANES];
    svgf_bases(p, kind, cb, tb);
    const size_t row = (size_t)y * w;
    if (!at) /* every used pixel's variance from its own moments; svgf_block replaces the short histories' */
        for (int x = 0; x < w; x++) {
            const float m1 = p->val[0][row + x], var = p->val[1][row + x] - m1 * m1;
            p->out[0][row + x] = p->f->use[row + x] != 0.0f && var > 0.0f ? var : 0.0f;
        }
    for (int x = 0; x < w; x += DV_LANES) {
        if (!at) { /* skip blocks without a short history */
            int any = 0;
            for (int l = 0; l < DV_LANES && x + l < w; l++)
                any |= p->f->use[row + x + l] != 0.0f && p->len[row + x + l] < p->short_history;
            if (!any)
                continue;
        }
        const int inside = x >= reach && x + DV_LANES + reach <= w, sym = at && p->lum_symmetric;
        if (p->sn == 128.0f && sym)
            inside ? svgf_block(p, cb, tb, y, x, 1, 7, 1, kind) : svgf_block(p, cb, tb, y, x, 0, 7, 1, kind);
        else if (p->sn == 128.0f)
            inside ? svgf_block(p, cb, tb, y, x, 1, 7, 0, kind) : svgf_block(p, cb, tb, y, x, 0, 7, 0, kind);
        else
            inside ? svgf_block(p, cb, tb, y, x, 1, -1, sym, kind) : svgf_block(p, cb, tb, y, x, 0, -1, sym, kind);
    }
}

#endif
