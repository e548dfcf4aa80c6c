/* test_compare_track_cov.c: compare's temporal covariance (compare_track.c, 000 Eq. 17) on synthetic frames.
 *  - Radiance-like (non-negative) frames: compare_track_end is restir_metrics_temporal_autocovariance of their
 *    luminance, bit for bit.
 *  - Signed frames, as the gradient methods' L2 / L1 reconstructions (002 Sec. 5) are: a pixel whose mean over
 *    the runs is +-1e-3 with values of +-1 makes Eq. 17's ratio unbounded (|a_i| in the 10^5 here), the bug
 *    an evaluation found (tcov -61.5 against 2.0 for near-identical images). The track measures the luminance
 *    clamped at 0, so its tcov stays within the non-negative bound N - 1 and equals the metric of the clamped
 *    frames. */
#include <math.h>
#include <string.h>

#include "experiments/compare_track.h"
#include "restir/metrics.h"
#include "test_util.h"

enum { RUNS = 4, FRAMES = 8, W = 2, H = 1, NPIX = W * H, FIRST = FRAMES / 2, WINDOW = FRAMES - FIRST };

/* Pixel i of run n at frame f (f in the window): pixel 0 positive, pixel 1 signed with a mean of ~0 when
 * `signed_` (else its absolute value). */
static float value(int n, int f, int i, int signed_)
{
    static const float base[RUNS] = {1.0f, -1.0f, 0.999f, -1.0f};
    if (i == 0)
        return 0.5f + 0.1f * (float)n + 0.01f * (float)f * (float)(n % 2);
    const float v = base[n] * (1.0f + 0.05f * (float)((n + f) % 3));
    return signed_ ? v : fabsf(v);
}

/* Runs the track over the window's frames and returns its tcov; lum gets the luminance it was given (grey
 * pixels, so the Rec. 709 weights sum to 1 up to float rounding) in the metric's layout, clamped if clamp. */
static double track_tcov(int signed_, int clamp, float *lum)
{
    struct compare_track t;
    compare_track_init(&t, FRAMES, RUNS, 0, W, H, NULL);
    compare_track_begin(&t);
    for (int n = 0; n < RUNS; n++)
        for (int f = FIRST; f < FRAMES; f++) {
            float img[3 * NPIX];
            for (int i = 0; i < NPIX; i++) {
                const float v = value(n, f, i, signed_);
                img[3 * i] = img[3 * i + 1] = img[3 * i + 2] = v;
                const float l = 0.2126f * v + 0.7152f * v + 0.0722f * v;
                lum[((size_t)n * WINDOW + (size_t)(f - FIRST)) * NPIX + (size_t)i] = clamp && l < 0.0f ? 0.0f : l;
            }
            EXPECT(compare_track_wants_image(&t, f), "frame %d is in the covariance window", f);
            compare_track_image(&t, n, f, img);
        }
    const double tcov = compare_track_end(&t, "synthetic");
    compare_track_fini(&t);
    return tcov;
}

int main(void)
{
    static float lum[RUNS * WINDOW * NPIX];
    const double eps = 1e-4; /* 000 Appendix A, as compare_track.c */

    /* non-negative frames: the clamp changes nothing */
    double tcov = track_tcov(0, 0, lum);
    double want = restir_metrics_temporal_autocovariance(lum, RUNS, WINDOW, W, H, COMPARE_COV_LAG, (float)eps, NULL);
    EXPECT(isfinite(want) && memcmp(&tcov, &want, sizeof tcov) == 0, "non-negative: tcov %.17g, metric %.17g", tcov,
           want);

    /* signed frames: unclamped, the metric is garbage; the track's number is the clamped frames' and bounded */
    track_tcov(1, 0, lum);
    const double raw = restir_metrics_temporal_autocovariance(lum, RUNS, WINDOW, W, H, COMPARE_COV_LAG, (float)eps,
                                                              NULL);
    EXPECT(fabs(raw) > 100.0 * (RUNS - 1), "the signed frames should break the unclamped metric: %g", raw);
    tcov = track_tcov(1, 1, lum);
    want = restir_metrics_temporal_autocovariance(lum, RUNS, WINDOW, W, H, COMPARE_COV_LAG, (float)eps, NULL);
    EXPECT(memcmp(&tcov, &want, sizeof tcov) == 0, "signed: tcov %.17g, clamped metric %.17g", tcov, want);
    EXPECT(isfinite(tcov) && fabs(tcov) <= RUNS - 1, "signed: tcov %g outside the bound %d", tcov, RUNS - 1);
    return test_finish();
}
