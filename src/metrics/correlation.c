/* correlation.c: correlation metrics of independent runs (000 Appendix A, Eq. 16-17) and the hard
 * pixel classification of 000 Sec. 7, as declared in restir/metrics.h. Serial code (librestir
 * does not link OpenMP). Must never depend on src/ headers, a ray tracer, files or the renderer. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "restir/metrics.h"
#include "restir/neighbors.h"

static int corr_selected(const unsigned char *mask, size_t i)
{
    return mask == NULL || mask[i] != 0;
}

/* 1 when `images` images of w x h (w, h >= 1) cannot be addressed: as floats, and as doubles with
 * one prefix sum more per row (the scratch arrays; images >= 1). */
static int corr_too_big(int width, int height, size_t images)
{
    return (size_t)width + 1 > SIZE_MAX / sizeof(double) / (size_t)height / images;
}

/* Per-pixel sample mean over the runs and 1 / (mean + eps); image n starts at base + n * stride. */
static void corr_moments(const float *base, size_t stride, int n_runs, size_t n_pixels, float eps, double *mean,
                         double *inv)
{
    for (size_t i = 0; i < n_pixels; i++)
        mean[i] = 0.0;
    for (int n = 0; n < n_runs; n++) {
        const float *img = base + (size_t)n * stride;
        for (size_t i = 0; i < n_pixels; i++)
            mean[i] += (double)img[i];
    }
    for (size_t i = 0; i < n_pixels; i++) {
        mean[i] /= (double)n_runs;
        inv[i] = 1.0 / (mean[i] + (double)eps);
    }
}

/* Half-width of each row of the integer disk dx^2 + dy^2 <= radius^2, for dy = 0 .. rows
 * (rows <= radius), capped at width (wider rows reach past the image anyway). */
static void corr_disk_rows(int radius, int rows, int width, int *half)
{
    long long r2 = (long long)radius * radius;
    for (int dy = 0; dy <= rows; dy++) {
        long long rem = r2 - (long long)dy * dy;
        long long h = (long long)sqrt((double)rem);
        while ((h + 1) * (h + 1) <= rem)
            h++;
        while (h > 0 && h * h > rem)
            h--;
        half[dy] = h > width ? width : (int)h;
    }
}

/* Columns [x0, x1] of row yy inside the disk around (x, y), clipped to the image. */
static void disk_row_span(const int *half, int x, int y, int yy, int width, int *x0, int *x1)
{
    int h = half[yy > y ? yy - y : y - yy];
    *x0 = x - h < 0 ? 0 : x - h;
    *x1 = x + h > width - 1 ? width - 1 : x + h;
}

double restir_metrics_spatial_covariance(const float *runs, int n_runs, int width, int height, int radius, float eps,
                                 const unsigned char *mask)
{
    if (runs == NULL || n_runs < 2 || width <= 0 || height <= 0 || radius < 0 ||
        corr_too_big(width, height, (size_t)n_runs))
        return NAN;
    /* Rows farther than the image is tall never hold a neighbor. */
    int r = radius < height - 1 ? radius : height - 1;
    size_t n_pixels = (size_t)width * (size_t)height;
    size_t row_len = (size_t)width + 1;

    double *mean = malloc(n_pixels * sizeof *mean);
    double *inv = malloc(n_pixels * sizeof *inv);
    double *z = malloc(n_pixels * sizeof *z);
    double *acc = calloc(n_pixels, sizeof *acc);
    double *prefix = malloc(row_len * (size_t)height * sizeof *prefix);
    int *half = malloc(((size_t)r + 1) * sizeof *half);
    double result = NAN;
    if (!mean || !inv || !z || !acc || !prefix || !half)
        goto done;

    corr_moments(runs, n_pixels, n_runs, n_pixels, eps, mean, inv);
    /* The disk of radius `radius`: rows dy with |dy| <= r, each clipped to the image. */
    corr_disk_rows(radius, r, width, half);

    /* sum_{j in disk(i), j != i} r_ij = 1/(N-1) sum_n z_ni (S_ni - z_ni), S_ni the sum of z_nj over
     * the disk including i. S_ni is read from row prefix sums: 2r + 1 segments per pixel instead
     * of one product per disk tap. |z| <= N - 1 for nonnegative data, so the prefix differences
     * lose nothing that matters in double. */
    for (int n = 0; n < n_runs; n++) {
        const float *img = runs + (size_t)n * n_pixels;
        for (size_t i = 0; i < n_pixels; i++)
            z[i] = ((double)img[i] - mean[i]) * inv[i];
        for (int y = 0; y < height; y++) {
            double *p = prefix + (size_t)y * row_len;
            const double *zr = z + (size_t)y * (size_t)width;
            p[0] = 0.0;
            for (int x = 0; x < width; x++)
                p[x + 1] = p[x] + zr[x];
        }
        for (int y = 0; y < height; y++) {
            int y0 = y - r < 0 ? 0 : y - r;
            int y1 = y + r > height - 1 ? height - 1 : y + r;
            for (int x = 0; x < width; x++) {
                size_t i = (size_t)y * (size_t)width + (size_t)x;
                if (!corr_selected(mask, i))
                    continue;
                double s = 0.0;
                for (int yy = y0; yy <= y1; yy++) {
                    int x0, x1;
                    disk_row_span(half, x, y, yy, width, &x0, &x1);
                    const double *p = prefix + (size_t)yy * row_len;
                    s += p[x1 + 1] - p[x0];
                }
                acc[i] += z[i] * (s - z[i]);
            }
        }
    }

    double total = 0.0;
    size_t counted = 0;
    for (int y = 0; y < height; y++) {
        int y0 = y - r < 0 ? 0 : y - r;
        int y1 = y + r > height - 1 ? height - 1 : y + r;
        for (int x = 0; x < width; x++) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            if (!corr_selected(mask, i))
                continue;
            long long neighbors = -1; /* the disk includes i itself */
            for (int yy = y0; yy <= y1; yy++) {
                int x0, x1;
                disk_row_span(half, x, y, yy, width, &x0, &x1);
                neighbors += x1 - x0 + 1;
            }
            if (neighbors <= 0)
                continue;
            total += acc[i] / ((double)(n_runs - 1) * (double)neighbors);
            counted++;
        }
    }
    if (counted > 0)
        result = total / (double)counted;

done:
    free(mean);
    free(inv);
    free(z);
    free(acc);
    free(prefix);
    free(half);
    return result;
}

double restir_metrics_temporal_autocovariance(const float *seq, int n_runs, int frames, int width, int height, int lag,
                                      float eps, const unsigned char *mask)
{
    if (seq == NULL || n_runs < 2 || frames <= 0 || width <= 0 || height <= 0 || lag < 0 || lag >= frames ||
        (size_t)n_runs > SIZE_MAX / (size_t)frames || corr_too_big(width, height, (size_t)n_runs * (size_t)frames))
        return NAN;
    size_t n_pixels = (size_t)width * (size_t)height;
    size_t selected = 0;
    for (size_t i = 0; i < n_pixels; i++)
        selected += corr_selected(mask, i) ? 1u : 0u;
    if (selected == 0)
        return NAN;

    double *mean_a = malloc(n_pixels * sizeof *mean_a);
    double *inv_a = malloc(n_pixels * sizeof *inv_a);
    double *mean_b = malloc(n_pixels * sizeof *mean_b);
    double *inv_b = malloc(n_pixels * sizeof *inv_b);
    double *acc = calloc(n_pixels, sizeof *acc);
    double result = NAN;
    if (!mean_a || !inv_a || !mean_b || !inv_b || !acc)
        goto done;

    /* Run n's frame t starts at seq + (n * frames + t) * n_pixels: runs are frames * n_pixels apart. */
    size_t run_stride = (size_t)frames * n_pixels;
    int pairs = frames - lag;
    for (int t = 0; t < pairs; t++) {
        const float *fa = seq + (size_t)t * n_pixels;
        const float *fb = seq + (size_t)(t + lag) * n_pixels;
        corr_moments(fa, run_stride, n_runs, n_pixels, eps, mean_a, inv_a);
        corr_moments(fb, run_stride, n_runs, n_pixels, eps, mean_b, inv_b);
        for (int n = 0; n < n_runs; n++) {
            const float *a = fa + (size_t)n * run_stride;
            const float *b = fb + (size_t)n * run_stride;
            for (size_t i = 0; i < n_pixels; i++)
                acc[i] += ((double)a[i] - mean_a[i]) * inv_a[i] * (((double)b[i] - mean_b[i]) * inv_b[i]);
        }
    }
    double total = 0.0;
    for (size_t i = 0; i < n_pixels; i++)
        if (corr_selected(mask, i))
            total += acc[i];
    result = total / ((double)(n_runs - 1) * (double)selected * (double)pairs);

done:
    free(mean_a);
    free(inv_a);
    free(mean_b);
    free(inv_b);
    free(acc);
    return result;
}

struct corr_rank {
    double ratio;
    size_t index;
};

static int corr_rank_cmp(const void *pa, const void *pb)
{
    const struct corr_rank *a = pa, *b = pb;
    if (a->ratio != b->ratio)
        return a->ratio < b->ratio ? -1 : 1;
    return (a->index > b->index) - (a->index < b->index);
}

int restir_metrics_hard_pixels(const float *normals, const float *depth, const unsigned char *valid, int width, int height,
                       float radius, float normal_min, float depth_max, float fraction, unsigned char *mask_out,
                       float *ratio_out)
{
    return restir_metrics_hard_pixels_counting(normals, depth, valid, width, height, radius, normal_min, depth_max,
                                               fraction, RESTIR_HARD_NEIGHBORS_VALID, mask_out, ratio_out);
}

int restir_metrics_hard_pixels_counting(const float *normals, const float *depth, const unsigned char *valid, int width,
                                        int height, float radius, float normal_min, float depth_max, float fraction,
                                        enum restir_hard_neighbors counting, unsigned char *mask_out, float *ratio_out)
{
    if (normals == NULL || depth == NULL || mask_out == NULL || width <= 0 || height <= 0 || !(radius >= 0.0f) ||
        (counting != RESTIR_HARD_NEIGHBORS_VALID && counting != RESTIR_HARD_NEIGHBORS_ALL))
        return -1;
    const int count_invalid = counting == RESTIR_HARD_NEIGHBORS_ALL;
    /* The count returned is an int; rank holds 16 bytes per pixel (more than the 3 normal floats). */
    if ((size_t)width > (size_t)INT_MAX / (size_t)height ||
        (size_t)width * (size_t)height > SIZE_MAX / sizeof(struct corr_rank))
        return -1;
    size_t n_pixels = (size_t)width * (size_t)height;
    /* Disk rows: |dy| <= floor(radius), clipped to the image height; half-widths clipped to its width. */
    int extent = width > height ? width : height;
    int r = radius >= (float)extent ? extent : (int)floorf(radius);
    double r2 = (double)radius * (double)radius;
    int *half = malloc(((size_t)r + 1) * sizeof *half);
    struct corr_rank *rank = malloc(n_pixels * sizeof *rank);
    if (!half || !rank) {
        free(half);
        free(rank);
        return -1;
    }
    for (int dy = 0; dy <= r; dy++) {
        int h = 0;
        while (h < width && (double)(h + 1) * (h + 1) + (double)dy * dy <= r2)
            h++;
        half[dy] = h;
    }

    memset(mask_out, 0, n_pixels);
    size_t n_valid = 0;
    for (int y = 0; y < height; y++) {
        int y0 = y - r < 0 ? 0 : y - r;
        int y1 = y + r > height - 1 ? height - 1 : y + r;
        for (int x = 0; x < width; x++) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            if (valid != NULL && !valid[i]) {
                if (ratio_out)
                    ratio_out[i] = -1.0f;
                continue;
            }
            const float *n_i = normals + 3 * i;
            float d_i = depth[i];
            long long total = 0, compatible = 0;
            for (int yy = y0; yy <= y1; yy++) {
                int h = half[yy > y ? yy - y : y - yy];
                int x0 = x - h < 0 ? 0 : x - h;
                int x1 = x + h > width - 1 ? width - 1 : x + h;
                size_t row = (size_t)yy * (size_t)width;
                for (int xx = x0; xx <= x1; xx++) {
                    size_t j = row + (size_t)xx;
                    if (j == i)
                        continue;
                    if (valid != NULL && !valid[j]) {
                        total += count_invalid; /* counted as failing Eq. 7, or not at all */
                        continue;
                    }
                    total++;
                    compatible += restir_neighbors_bitterli(n_i, normals + 3 * j, d_i, depth[j], normal_min,
                                                             depth_max) != 0;
                }
            }
            /* No valid neighbor at all: no reuse candidate, the hardest case. */
            double ratio = total > 0 ? (double)compatible / (double)total : 0.0;
            if (ratio_out)
                ratio_out[i] = (float)ratio;
            rank[n_valid].ratio = ratio;
            rank[n_valid].index = i;
            n_valid++;
        }
    }

    /* round(fraction * valid), halves up; NaN or negative fractions select nothing. */
    size_t hard = 0;
    if (fraction >= 1.0f)
        hard = n_valid;
    else if (fraction > 0.0f)
        hard = (size_t)floor((double)fraction * (double)n_valid + 0.5);
    if (hard > n_valid)
        hard = n_valid;
    qsort(rank, n_valid, sizeof *rank, corr_rank_cmp);
    for (size_t k = 0; k < hard; k++)
        mask_out[rank[k].index] = 1;

    free(half);
    free(rank);
    return (int)hard;
}
