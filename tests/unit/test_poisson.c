/* test_poisson.c: unit tests for the screened Poisson reconstruction (restir/poisson.h): exact data
 * reconstructs the image, residuals, the alpha -> infinity limit, DCT against CG, linearity, the
 * energy minimum, L1 robustness to outliers, L1's two preconditioners, non-finite inputs,
 * degenerate sizes and bad arguments. Must never depend on src/ headers, files or the renderer. */
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "restir/poisson.h"
#include "test_util.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static double rnd(void) /* uniform [0, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static float *falloc(size_t n)
{
    float *p = calloc(n, sizeof(float));
    if (!p) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return p;
}

/* Smooth shading + sharp edges (a vertical step and a disc) + uniform noise. */
static float *synthetic(int w, int h)
{
    float *img = falloc((size_t)w * h * 3);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                double v = 0.5 + 0.3 * sin(0.2 * x + c) * cos(0.15 * y);
                if (x > w / 3)
                    v += 0.4;
                double rx = x - 0.6 * w, ry = y - 0.5 * h;
                if (rx * rx + ry * ry < 0.06 * w * h)
                    v += 0.3 * (c + 1);
                v += 0.1 * (rnd() - 0.5);
                img[3 * ((size_t)y * w + x) + c] = (float)v;
            }
    return img;
}

/* Exact forward differences of img; the ignored last column of dx / last row of dy get junk. */
static void gradients(int w, int h, const float *img, float *dx, float *dy)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                size_t p = 3 * ((size_t)y * w + x) + c;
                dx[p] = x + 1 < w ? img[p + 3] - img[p] : 123.0f;
                dy[p] = y + 1 < h ? img[p + 3 * (size_t)w] - img[p] : -77.0f;
            }
}

static void random_image(size_t m, float lo, float hi, float *out)
{
    for (size_t i = 0; i < m; i++)
        out[i] = (float)(lo + (hi - lo) * rnd());
}

static double rel_err(const float *a, const float *b, size_t m)
{
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < m; i++) {
        num += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
        den += (double)b[i] * b[i];
    }
    return den > 0.0 ? sqrt(num / den) : sqrt(num);
}

/* The documented energy, summed over channels, straight from the rows. */
static double energy(int w, int h, const float *P, const float *dx, const float *dy, double alpha, const double *x)
{
    double e = 0.0;
    for (int y = 0; y < h; y++)
        for (int i = 0; i < w; i++)
            for (int c = 0; c < 3; c++) {
                size_t p = 3 * ((size_t)y * w + i) + c;
                double r = alpha * (x[p] - P[p]);
                e += r * r;
                if (i + 1 < w) {
                    r = x[p + 3] - x[p] - dx[p];
                    e += r * r;
                }
                if (y + 1 < h) {
                    r = x[p + 3 * (size_t)w] - x[p] - dy[p];
                    e += r * r;
                }
            }
    return e;
}

/* |b - A x| / |b| of the L2 normal equations, max over channels, evaluated here independently. */
static double normal_residual(int w, int h, const float *P, const float *dx, const float *dy, double alpha,
                              const float *x)
{
    double worst = 0.0, a2 = alpha * alpha;
    for (int c = 0; c < 3; c++) {
        double rr = 0.0, bb = 0.0;
        for (int y = 0; y < h; y++)
            for (int i = 0; i < w; i++) {
                size_t p = 3 * ((size_t)y * w + i) + c, W = 3 * (size_t)w;
                double b = a2 * P[p], ax = a2 * x[p];
                if (i + 1 < w)
                    b -= dx[p], ax += (double)x[p] - x[p + 3];
                if (i > 0)
                    b += dx[p - 3], ax += (double)x[p] - x[p - 3];
                if (y + 1 < h)
                    b -= dy[p], ax += (double)x[p] - x[p + W];
                if (y > 0)
                    b += dy[p - W], ax += (double)x[p] - x[p - W];
                rr += (b - ax) * (b - ax);
                bb += b * b;
            }
        double r = sqrt(rr / bb);
        worst = r > worst ? r : worst;
    }
    return worst;
}

static int l2(int w, int h, const float *P, const float *dx, const float *dy, float alpha,
              enum restir_poisson_solver s, float *out, struct restir_poisson_stats *st)
{
    return restir_poisson_l2(w, h, P, dx, dy, alpha, s, RESTIR_POISSON_TOL, 5000, out, st);
}

static int l1(int w, int h, const float *P, const float *dx, const float *dy, float alpha, float *out,
              struct restir_poisson_stats *st)
{
    return restir_poisson_l1(w, h, P, dx, dy, alpha, RESTIR_POISSON_L1_ITERATIONS, RESTIR_POISSON_PRECOND_MULTIGRID,
                             RESTIR_POISSON_L1_MG_STEPS, out, st);
}

/* (a) exact primal and gradients give back the image; (b) CG's residual; CG against DCT with
 * exact gradients and a flat primal. */
static void test_exact(int w, int h)
{
    size_t m = (size_t)w * h * 3;
    float *img = synthetic(w, h), *dx = falloc(m), *dy = falloc(m), *out = falloc(m);
    gradients(w, h, img, dx, dy);
    struct restir_poisson_stats st;
    const float alpha = RESTIR_POISSON_ALPHA;

    EXPECT(l2(w, h, img, dx, dy, alpha, RESTIR_POISSON_DCT, out, &st) == 0, "dct %dx%d", w, h);
    EXPECT(rel_err(out, img, m) < 1e-5, "%dx%d dct error %g", w, h, rel_err(out, img, m));
    EXPECT(st.iterations == 0 && st.residual < 1e-10, "%dx%d dct stats %d %g", w, h, st.iterations, st.residual);

    /* Exact data is a fixed point of CG from x0 = primal: it must see that and stop at once. */
    EXPECT(l2(w, h, img, dx, dy, alpha, RESTIR_POISSON_CG, out, &st) == 0, "cg %dx%d", w, h);
    EXPECT(rel_err(out, img, m) < 1e-5, "%dx%d cg error %g", w, h, rel_err(out, img, m));
    EXPECT(st.iterations == 0 && st.residual <= 1e-6, "%dx%d cg stats %d %g", w, h, st.iterations, st.residual);

    EXPECT(l1(w, h, img, dx, dy, alpha, out, &st) == 0, "l1 %dx%d", w, h);
    EXPECT(rel_err(out, img, m) < 1e-5, "%dx%d l1 error %g", w, h, rel_err(out, img, m));
    EXPECT(st.iterations > 0 && st.iterations <= RESTIR_POISSON_L1_ITERATIONS * RESTIR_POISSON_L1_MG_STEPS,
           "l1 iterations %d", st.iterations);

    /* Exact gradients, a flat grey primal: CG (from the grey start) has to work, and matches
     * the DCT solve of the same system. */
    float *grey = falloc(m), *ref = falloc(m);
    for (size_t i = 0; i < m; i++)
        grey[i] = 0.5f;
    EXPECT(l2(w, h, grey, dx, dy, alpha, RESTIR_POISSON_CG, out, &st) == 0, "cg grey");
    EXPECT(st.iterations > 5 && st.residual <= 1e-6, "cg stats %d %g", st.iterations, st.residual);
    EXPECT(l2(w, h, grey, dx, dy, alpha, RESTIR_POISSON_DCT, ref, NULL) == 0, "dct grey");
    EXPECT(rel_err(out, ref, m) < 1e-4, "%dx%d grey primal: cg vs dct %g", w, h, rel_err(out, ref, m));
    EXPECT(rel_err(out, img, m) > 1e-3, "%dx%d grey primal ignored", w, h);
    free(grey), free(ref);
    free(img), free(dx), free(dy), free(out);
}

/* (b) residuals, (d) DCT vs CG, energy minimum, on random inconsistent inputs. */
static void test_inconsistent(int w, int h)
{
    size_t m = (size_t)w * h * 3;
    float *P = falloc(m), *dx = falloc(m), *dy = falloc(m), *a = falloc(m), *b = falloc(m);
    random_image(m, 0.0f, 2.0f, P);
    random_image(m, -0.5f, 0.5f, dx);
    random_image(m, -0.5f, 0.5f, dy);
    struct restir_poisson_stats sd, sc;
    const float alpha = RESTIR_POISSON_ALPHA;
    EXPECT(l2(w, h, P, dx, dy, alpha, RESTIR_POISSON_DCT, a, &sd) == 0, "dct");
    EXPECT(l2(w, h, P, dx, dy, alpha, RESTIR_POISSON_CG, b, &sc) == 0, "cg");
    /* The primal itself is far from solving the system: the residual check can fail. */
    double r_primal = normal_residual(w, h, P, dx, dy, alpha, P);
    double r_dct = normal_residual(w, h, P, dx, dy, alpha, a);
    double r_cg = normal_residual(w, h, P, dx, dy, alpha, b);
    EXPECT(r_primal > 0.1, "primal residual %g", r_primal);
    EXPECT(r_dct < 1e-5, "%dx%d dct residual (float output) %g", w, h, r_dct);
    EXPECT(sd.residual < 1e-10, "%dx%d dct residual (double) %g", w, h, sd.residual);
    EXPECT(sc.residual <= 1e-6 && sc.iterations > 1, "%dx%d cg residual %g after %d", w, h, sc.residual,
           sc.iterations);
    EXPECT(r_cg < 2e-6, "%dx%d cg residual (float output) %g", w, h, r_cg);
    EXPECT(rel_err(b, a, m) < 1e-4, "%dx%d dct vs cg %g", w, h, rel_err(b, a, m));
    EXPECT(rel_err(P, a, m) > 0.05, "solution equals the primal (%g)", rel_err(P, a, m));

    /* The DCT solution is the minimum of the documented energy: random perturbations raise it. */
    double *x = malloc(m * sizeof(double)), *y = malloc(m * sizeof(double));
    for (size_t i = 0; i < m; i++)
        x[i] = a[i];
    double e0 = energy(w, h, P, dx, dy, alpha, x);
    int lower = 0;
    for (int t = 0; t < 8; t++) {
        for (size_t i = 0; i < m; i++)
            y[i] = x[i] + 1e-3 * (rnd() - 0.5) * (t < 4 ? 1.0 : (i % 3 == 0));
        lower += energy(w, h, P, dx, dy, alpha, y) < e0;
    }
    EXPECT(lower == 0, "%d perturbations lowered the energy", lower);
    free(x), free(y);
    free(P), free(dx), free(dy), free(a), free(b);
}

/* (c) alpha -> infinity returns the primal, whatever the gradients say. */
static void test_large_alpha(void)
{
    const int w = 29, h = 17;
    size_t m = (size_t)w * h * 3;
    float *P = synthetic(w, h), *dx = falloc(m), *dy = falloc(m), *out = falloc(m);
    random_image(m, -1.0f, 1.0f, dx);
    random_image(m, -1.0f, 1.0f, dy);
    struct restir_poisson_stats st;
    EXPECT(l2(w, h, P, dx, dy, 1e4f, RESTIR_POISSON_DCT, out, &st) == 0, "dct");
    EXPECT(rel_err(out, P, m) < 1e-6, "dct alpha 1e4: %g", rel_err(out, P, m));
    EXPECT(l2(w, h, P, dx, dy, 1e4f, RESTIR_POISSON_CG, out, &st) == 0, "cg");
    EXPECT(rel_err(out, P, m) < 1e-6, "cg alpha 1e4: %g", rel_err(out, P, m));
    EXPECT(l1(w, h, P, dx, dy, 1e4f, out, &st) == 0, "l1");
    EXPECT(rel_err(out, P, m) < 1e-6, "l1 alpha 1e4: %g", rel_err(out, P, m));
    /* ... and at the default alpha the same gradients do change it. */
    EXPECT(l2(w, h, P, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_DCT, out, &st) == 0, "dct");
    EXPECT(rel_err(out, P, m) > 0.1, "alpha 0.2 ignores the gradients: %g", rel_err(out, P, m));
    free(P), free(dx), free(dy), free(out);
}

/* (e) L2 is linear in (primal, dx, dy). */
static void test_linear(void)
{
    const int w = 31, h = 20;
    const size_t m = (size_t)w * h * 3;
    const float s = -1.75f;
    float *in[2][3], *mix[3], *r1 = falloc(m), *r2 = falloc(m), *rm = falloc(m), *comb = falloc(m);
    for (int k = 0; k < 3; k++) {
        mix[k] = falloc(m);
        for (int t = 0; t < 2; t++) {
            in[t][k] = falloc(m);
            random_image(m, -1.0f, 1.0f, in[t][k]);
        }
        for (size_t i = 0; i < m; i++)
            mix[k][i] = s * in[0][k][i] + in[1][k][i];
    }
    for (int solver = 0; solver < 2; solver++) {
        enum restir_poisson_solver sv = solver ? RESTIR_POISSON_CG : RESTIR_POISSON_DCT;
        double tol = 1e-10;
        EXPECT(restir_poisson_l2(w, h, in[0][0], in[0][1], in[0][2], 0.3f, sv, tol, 5000, r1, NULL) == 0, "in1");
        EXPECT(restir_poisson_l2(w, h, in[1][0], in[1][1], in[1][2], 0.3f, sv, tol, 5000, r2, NULL) == 0, "in2");
        EXPECT(restir_poisson_l2(w, h, mix[0], mix[1], mix[2], 0.3f, sv, tol, 5000, rm, NULL) == 0, "mix");
        for (size_t i = 0; i < m; i++)
            comb[i] = s * r1[i] + r2[i];
        EXPECT(rel_err(rm, comb, m) < 1e-5, "solver %d: linearity error %g", solver, rel_err(rm, comb, m));
    }
    for (int k = 0; k < 3; k++) {
        free(mix[k]);
        free(in[0][k]), free(in[1][k]);
    }
    free(r1), free(r2), free(rm), free(comb);
}

/* (f) outlier gradients: L1 stays closer to the true image than L2. */
static void test_l1_outliers(void)
{
    const int w = 48, h = 32;
    size_t m = (size_t)w * h * 3;
    float *img = synthetic(w, h), *P = falloc(m), *dx = falloc(m), *dy = falloc(m);
    float *o2 = falloc(m), *o1 = falloc(m);
    gradients(w, h, img, dx, dy);
    for (size_t i = 0; i < m; i++)
        P[i] = img[i] + (float)(0.1 * (rnd() - 0.5)); /* noisy primal */
    /* One row of dx with large wrong values (a failed shift), and a few fireflies in dy. */
    const int y0 = h / 2;
    for (int x = 5; x < w - 5; x++)
        for (int c = 0; c < 3; c++)
            dx[3 * ((size_t)y0 * w + x) + c] += 4.0f;
    for (int k = 0; k < 10; k++) {
        size_t p = (size_t)(rnd() * (w * (h - 1)));
        dy[3 * p + (size_t)(rnd() * 3)] -= 20.0f;
    }
    struct restir_poisson_stats st;
    EXPECT(l2(w, h, P, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_DCT, o2, &st) == 0, "l2");
    EXPECT(l1(w, h, P, dx, dy, RESTIR_POISSON_ALPHA, o1, &st) == 0, "l1");
    double e2 = rel_err(o2, img, m), e1 = rel_err(o1, img, m), ep = rel_err(P, img, m);
    printf("outliers: primal error %.4g, L2 %.4g, L1 %.4g\n", ep, e2, e1);
    EXPECT(e1 < 0.3 * e2, "L1 error %g vs L2 %g", e1, e2);
    EXPECT(e1 < ep, "L1 error %g vs primal %g", e1, ep);
    free(img), free(P), free(dx), free(dy), free(o2), free(o1);
}

/* Non-finite inputs read as 0: same result as with zeros there, and finite. */
static void test_nonfinite(void)
{
    const int w = 19, h = 13;
    size_t m = (size_t)w * h * 3;
    float *P = synthetic(w, h), *dx = falloc(m), *dy = falloc(m), *a = falloc(m), *b = falloc(m);
    gradients(w, h, P, dx, dy);
    P[3 * 40 + 1] = NAN;
    dx[3 * 77] = INFINITY;
    dy[3 * 100 + 2] = -INFINITY;
    dx[3 * 150 + 1] = NAN;
    float *Pz = falloc(m), *dxz = falloc(m), *dyz = falloc(m);
    memcpy(Pz, P, m * sizeof(float));
    memcpy(dxz, dx, m * sizeof(float));
    memcpy(dyz, dy, m * sizeof(float));
    Pz[3 * 40 + 1] = dxz[3 * 77] = dyz[3 * 100 + 2] = dxz[3 * 150 + 1] = 0.0f;
    for (int k = 0; k < 3; k++) {
        int rc1, rc2;
        if (k < 2) {
            enum restir_poisson_solver sv = k ? RESTIR_POISSON_CG : RESTIR_POISSON_DCT;
            rc1 = l2(w, h, P, dx, dy, RESTIR_POISSON_ALPHA, sv, a, NULL);
            rc2 = l2(w, h, Pz, dxz, dyz, RESTIR_POISSON_ALPHA, sv, b, NULL);
        } else {
            rc1 = l1(w, h, P, dx, dy, RESTIR_POISSON_ALPHA, a, NULL);
            rc2 = l1(w, h, Pz, dxz, dyz, RESTIR_POISSON_ALPHA, b, NULL);
        }
        EXPECT(rc1 == 0 && rc2 == 0, "solver %d", k);
        int finite = 1;
        for (size_t i = 0; i < m; i++)
            finite &= isfinite(a[i]) != 0;
        EXPECT(finite, "solver %d: non-finite output", k);
        EXPECT(memcmp(a, b, m * sizeof(float)) == 0, "solver %d: NaN/inf not read as 0 (%g)", k, rel_err(a, b, m));
    }
    free(P), free(dx), free(dy), free(a), free(b), free(Pz), free(dxz), free(dyz);
}

/* (g) w = 1 or h = 1 (and 1x1) reconstruct exact data. */
static void test_thin(void)
{
    const int sizes[4][2] = {{1, 1}, {1, 17}, {23, 1}, {2, 9}};
    for (int k = 0; k < 4; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        size_t m = (size_t)w * h * 3;
        float *img = synthetic(w, h), *dx = falloc(m), *dy = falloc(m), *out = falloc(m);
        gradients(w, h, img, dx, dy);
        struct restir_poisson_stats st;
        EXPECT(l2(w, h, img, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_DCT, out, &st) == 0, "dct %dx%d", w, h);
        EXPECT(rel_err(out, img, m) < 1e-5, "dct %dx%d error %g", w, h, rel_err(out, img, m));
        EXPECT(l2(w, h, img, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_CG, out, &st) == 0, "cg %dx%d", w, h);
        EXPECT(rel_err(out, img, m) < 1e-5, "cg %dx%d error %g", w, h, rel_err(out, img, m));
        EXPECT(l1(w, h, img, dx, dy, RESTIR_POISSON_ALPHA, out, &st) == 0, "l1 %dx%d", w, h);
        EXPECT(rel_err(out, img, m) < 1e-5, "l1 %dx%d error %g", w, h, rel_err(out, img, m));
        /* Inconsistent gradients on a line: DCT and CG still agree. */
        random_image(m, -0.3f, 0.3f, dx);
        random_image(m, -0.3f, 0.3f, dy);
        float *o2 = falloc(m);
        EXPECT(l2(w, h, img, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_DCT, out, NULL) == 0, "dct");
        EXPECT(l2(w, h, img, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_CG, o2, NULL) == 0, "cg");
        EXPECT(rel_err(o2, out, m) < 1e-4, "%dx%d dct vs cg %g", w, h, rel_err(o2, out, m));
        EXPECT(normal_residual(w, h, img, dx, dy, RESTIR_POISSON_ALPHA, out) < 1e-5, "%dx%d residual", w, h);
        free(o2);
        free(img), free(dx), free(dy), free(out);
    }
}

/* The L1 energy on a 2x1 image by hand: alpha (|x0 - P0| + |x1 - P1|) + |x1 - x0 - G|, lengths over
 * RGB; a NaN input reads as 0; bad arguments give NaN. */
static void test_l1_energy(void)
{
    const float P[6] = {1, 1, 1, 0, 0, 0}, x[6] = {1, 1, 2, 3, 0, 4}, dy[6] = {0};
    const float dx[6] = {1, NAN, 0, 9, 9, 9}; /* dx of the last column is ignored */
    /* |x0 - P0| = 1, |x1 - P1| = 5, |x1 - x0 - G| = |(1, -1, 2)| = sqrt 6 */
    const double want = 0.5 * 6.0 + sqrt(6.0);
    const double got = restir_poisson_l1_energy(2, 1, P, dx, dy, 0.5f, x);
    EXPECT(fabs(got - want) < 1e-12, "l1 energy %.17g, want %.17g", got, want);
    EXPECT(isnan(restir_poisson_l1_energy(2, 1, P, dx, dy, 0.0f, x)), "alpha 0");
    EXPECT(isnan(restir_poisson_l1_energy(2, 1, P, dx, dy, 0.5f, NULL)), "NULL image");
}

/* (h) the two preconditioners of L1's CG: solved far enough, they give the same IRLS iterates (the
 * preconditioner changes how CG gets there, not where); at their defaults the L1 energy is the same
 * to a fraction of a percent; multigrid is bit-identical on 1 and 2 threads; odd, thin and tiny
 * sizes (levels of 1-wide blocks) work. Inputs: a noisy image with outlier gradients, as in (f). */
static void test_l1_preconditioners(void)
{
    const int sizes[7][2] = {{1, 1}, {1, 17}, {23, 1}, {5, 3}, {37, 23}, {64, 48}, {97, 61}};
    const enum restir_poisson_precond J = RESTIR_POISSON_PRECOND_JACOBI, M = RESTIR_POISSON_PRECOND_MULTIGRID;
    for (int k = 0; k < 7; k++) {
        const int w = sizes[k][0], h = sizes[k][1];
        const size_t m = (size_t)w * h * 3;
        float *img = synthetic(w, h), *P = falloc(m), *dx = falloc(m), *dy = falloc(m);
        float *oj = falloc(m), *om = falloc(m), *o1 = falloc(m);
        gradients(w, h, img, dx, dy);
        for (size_t i = 0; i < m; i++) {
            P[i] = img[i] + (float)(0.2 * (rnd() - 0.5));
            if (rnd() < 0.03)
                dx[i] += (float)(8.0 * (rnd() - 0.5));
        }
        const float a = RESTIR_POISSON_ALPHA;
        struct restir_poisson_stats sj, sm;
        /* Converged: 12 reweightings (reg down to 2.4e-5, weights spanning 1e4), each solved to a
         * residual far below the defaults'. */
        EXPECT(restir_poisson_l1(w, h, P, dx, dy, a, 12, J, 4000, oj, &sj) == 0, "jacobi %dx%d", w, h);
        EXPECT(restir_poisson_l1(w, h, P, dx, dy, a, 12, M, 200, om, &sm) == 0, "multigrid %dx%d", w, h);
        const double converged = rel_err(om, oj, m);
        EXPECT(converged < 1e-5, "%dx%d converged multigrid vs jacobi: %g (residuals %g, %g)", w, h, converged,
               sm.residual, sj.residual);
        EXPECT(sm.residual < 1e-8, "%dx%d multigrid residual %g", w, h, sm.residual);
        /* Defaults. */
        EXPECT(restir_poisson_l1(w, h, P, dx, dy, a, RESTIR_POISSON_L1_ITERATIONS, J, RESTIR_POISSON_L1_CG_STEPS,
                                 oj, &sj) == 0,
               "jacobi default");
        EXPECT(restir_poisson_l1(w, h, P, dx, dy, a, RESTIR_POISSON_L1_ITERATIONS, M, RESTIR_POISSON_L1_MG_STEPS,
                                 om, &sm) == 0,
               "multigrid default");
        const double ej = restir_poisson_l1_energy(w, h, P, dx, dy, a, oj);
        const double em = restir_poisson_l1_energy(w, h, P, dx, dy, a, om);
        printf("l1 preconditioners %dx%d: converged |mg - jacobi| %.2g, default L1 energy mg %.8g, jacobi %.8g\n",
               w, h, converged, em, ej);
        EXPECT(em <= ej * 1.005, "%dx%d default L1 energy: multigrid %.8g, jacobi %.8g", w, h, em, ej);
        EXPECT(sm.iterations <= RESTIR_POISSON_L1_ITERATIONS * RESTIR_POISSON_L1_MG_STEPS, "multigrid steps %d",
               sm.iterations);
        /* Thread count. */
        omp_set_num_threads(1);
        EXPECT(restir_poisson_l1(w, h, P, dx, dy, a, RESTIR_POISSON_L1_ITERATIONS, M, RESTIR_POISSON_L1_MG_STEPS,
                                 o1, NULL) == 0,
               "1 thread");
        omp_set_num_threads(2);
        EXPECT(restir_poisson_l1(w, h, P, dx, dy, a, RESTIR_POISSON_L1_ITERATIONS, M, RESTIR_POISSON_L1_MG_STEPS,
                                 om, NULL) == 0,
               "2 threads");
        EXPECT(memcmp(o1, om, m * sizeof(float)) == 0, "%dx%d multigrid differs between 1 and 2 threads", w, h);
        free(img), free(P), free(dx), free(dy), free(oj), free(om), free(o1);
    }
}

/* (g) bad input returns -1 and leaves out alone. */
static void test_bad_input(void)
{
    const int w = 8, h = 5;
    size_t m = (size_t)w * h * 3;
    float *P = synthetic(w, h), *dx = falloc(m), *dy = falloc(m), *out = falloc(m);
    gradients(w, h, P, dx, dy);
    for (size_t i = 0; i < m; i++)
        out[i] = 42.0f;
    const enum restir_poisson_solver D = RESTIR_POISSON_DCT, C = RESTIR_POISSON_CG;
    const double tol = RESTIR_POISSON_TOL;
    struct restir_poisson_stats st = {-5, -5.0, -5.0};
    EXPECT(restir_poisson_l2(0, h, P, dx, dy, 0.2f, D, tol, 100, out, &st) == -1, "w = 0");
    EXPECT(restir_poisson_l2(w, -3, P, dx, dy, 0.2f, D, tol, 100, out, &st) == -1, "h < 0");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.0f, D, tol, 100, out, &st) == -1, "alpha 0");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, -0.2f, C, tol, 100, out, &st) == -1, "alpha < 0");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, NAN, D, tol, 100, out, &st) == -1, "alpha NaN");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, INFINITY, D, tol, 100, out, &st) == -1, "alpha inf");
    EXPECT(restir_poisson_l2(w, h, NULL, dx, dy, 0.2f, D, tol, 100, out, &st) == -1, "NULL primal");
    EXPECT(restir_poisson_l2(w, h, P, NULL, dy, 0.2f, C, tol, 100, out, &st) == -1, "NULL dx");
    EXPECT(restir_poisson_l2(w, h, P, dx, NULL, 0.2f, D, tol, 100, out, &st) == -1, "NULL dy");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.2f, D, tol, 100, NULL, &st) == -1, "NULL out");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.2f, (enum restir_poisson_solver)7, tol, 100, out, &st) == -1,
           "bad solver");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.2f, C, 0.0, 100, out, &st) == -1, "tol 0");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.2f, C, NAN, 100, out, &st) == -1, "tol NaN");
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.2f, C, tol, 0, out, &st) == -1, "max_iters 0");
    EXPECT(restir_poisson_l2(1 << 30, 1 << 30, P, dx, dy, 0.2f, C, tol, 10, out, &st) == -1, "huge");
    EXPECT(restir_poisson_l1(w, 0, P, dx, dy, 0.2f, 20, RESTIR_POISSON_PRECOND_JACOBI, 50, out, &st) == -1,
           "l1 h = 0");
    EXPECT(restir_poisson_l1(w, h, P, dx, dy, 0.0f, 20, RESTIR_POISSON_PRECOND_JACOBI, 50, out, &st) == -1,
           "l1 alpha 0");
    EXPECT(restir_poisson_l1(w, h, P, NULL, dy, 0.2f, 20, RESTIR_POISSON_PRECOND_JACOBI, 50, out, &st) == -1,
           "l1 NULL dx");
    EXPECT(restir_poisson_l1(w, h, P, dx, dy, 0.2f, -1, RESTIR_POISSON_PRECOND_JACOBI, 50, out, &st) == -1,
           "l1 iterations < 0");
    EXPECT(restir_poisson_l1(w, h, P, dx, dy, 0.2f, 20, RESTIR_POISSON_PRECOND_JACOBI, 0, out, &st) == -1,
           "l1 cg_steps 0");
    EXPECT(restir_poisson_l1(w, h, P, dx, dy, 0.2f, 20, (enum restir_poisson_precond)9, 4, out, &st) == -1,
           "l1 bad preconditioner");
    int untouched = 1;
    for (size_t i = 0; i < m; i++)
        untouched &= out[i] == 42.0f;
    EXPECT(untouched, "out written on error");
    EXPECT(st.iterations == -5 && st.residual == -5.0, "stats written on error");
    /* The valid neighbours of those calls work; L1 with 0 reweightings is the L2 solution. */
    float *o2 = falloc(m);
    EXPECT(restir_poisson_l2(w, h, P, dx, dy, 0.2f, D, tol, 100, o2, NULL) == 0, "valid l2");
    EXPECT(restir_poisson_l1(w, h, P, dx, dy, 0.2f, 0, RESTIR_POISSON_PRECOND_JACOBI, 50, out, &st) == 0 &&
               st.iterations == 0,
           "l1 0 iters");
    EXPECT(rel_err(out, o2, m) == 0.0, "l1 with 0 iterations: %g", rel_err(out, o2, m));
    free(o2);
    free(P), free(dx), free(dy), free(out);
}

int main(void)
{
    test_exact(37, 23);
    test_exact(64, 48);
    test_inconsistent(37, 23);
    test_inconsistent(64, 48);
    test_large_alpha();
    test_linear();
    test_l1_outliers();
    test_nonfinite();
    test_thin();
    test_l1_energy();
    test_l1_preconditioners();
    test_bad_input();
    return test_finish();
}
