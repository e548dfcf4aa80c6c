/* study_denoised.c: a study's tables and plot after denoising (study_denoised.h). */
#include "experiments/study_denoised.h"

#include <math.h>
#include <stdio.h>

#include "io/atomic_file.h"
#include "io/report.h"
#include "io/svg_plot.h"

/* The mean rank (1-based) of each of v's n values into r. */
static void ranks(const double *v, int n, double *r)
{
    for (int i = 0; i < n; i++) {
        int below = 0, equal = 0;
        for (int j = 0; j < n; j++) {
            below += v[j] < v[i];
            equal += v[j] == v[i];
        }
        r[i] = below + 0.5 * (equal + 1);
    }
}

double study_rank_correlation(const double *x, const double *y, int n)
{
    if (n < 3 || n > STUDY_MAX_CONFIGS)
        return NAN;
    double rx[STUDY_MAX_CONFIGS], ry[STUDY_MAX_CONFIGS];
    ranks(x, n, rx);
    ranks(y, n, ry);
    double mx = 0.0, my = 0.0;
    for (int i = 0; i < n; i++) {
        mx += rx[i] / n;
        my += ry[i] / n;
    }
    double sxy = 0.0, sxx = 0.0, syy = 0.0;
    for (int i = 0; i < n; i++) {
        sxy += (rx[i] - mx) * (ry[i] - my);
        sxx += (rx[i] - mx) * (rx[i] - mx);
        syy += (ry[i] - my) * (ry[i] - my);
    }
    return sxx > 0.0 && syy > 0.0 ? sxy / sqrt(sxx * syy) : NAN;
}

static int write_csv(const char *dir, const struct study_config *cfg, const struct study_result *raw,
                     const struct study_result *dn, int n, char *msg)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/study_denoised.csv", dir);
    struct csv_writer csv;
    if (csv_open(&csv, path,
                 "config,radius,K,smape_all,smape_all_denoised,smape_all_denoised_sem,smape_hard,"
                 "smape_hard_denoised,temporal_cov,temporal_cov_denoised,temporal_cov_denoised_sem,spatial_cov,"
                 "spatial_cov_denoised,spatial_cov_denoised_sem,flicker16,flicker16_denoised,boiling_index,"
                 "boiling_index_denoised",
                 msg) != 0)
        return -1;
    const int s16 = FLICKER_SCALES - 1, boil = FLICKER_SCALES;
    for (int k = 0; k < n; k++)
        csv_row(&csv, "%s,%g,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g",
                cfg[k].name, cfg[k].radius, cfg[k].candidates, raw[k].smape_all, dn[k].smape_all, dn[k].smape_all_sem,
                raw[k].smape_hard, dn[k].smape_hard, raw[k].temporal_cov, dn[k].temporal_cov, dn[k].temporal_cov_sem,
                raw[k].spatial_cov, dn[k].spatial_cov, dn[k].spatial_cov_sem, raw[k].flicker[s16], dn[k].flicker[s16],
                raw[k].flicker[boil], dn[k].flicker[boil]);
    return csv_close(&csv, msg);
}

static int write_md(const char *dir, const char *denoiser, const struct study_config *cfg,
                    const struct study_result *raw, const struct study_result *dn, int n, int m, char *msg)
{
    char path[4200], tmp[4300];
    snprintf(path, sizeof path, "%s/study_denoised.md", dir);
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "w", msg);
    if (!f)
        return -1;
    fprintf(f, "Before and after denoising with %s (BIASED by nature), against the same reference; M = %d.\n\n"
               "| config | R | K | SMAPE | SMAPE %s | SMAPE hard | SMAPE hard %s | temporal cov | temporal cov %s "
               "| spatial cov | spatial cov %s |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
            denoiser, m, denoiser, denoiser, denoiser, denoiser);
    for (int k = 0; k < n; k++)
        fprintf(f, "| %s | %g | %d | %.3f | %.3f +- %.2g | %.3f | %.3f | %.4g | %.4g | %.4g | %.4g |\n", cfg[k].name,
                cfg[k].radius, cfg[k].candidates, raw[k].smape_all, dn[k].smape_all, dn[k].smape_all_sem,
                raw[k].smape_hard, dn[k].smape_hard, raw[k].temporal_cov, dn[k].temporal_cov, raw[k].spatial_cov,
                dn[k].spatial_cov);
    double pre_t[STUDY_MAX_CONFIGS], pre_s[STUDY_MAX_CONFIGS], pre_e[STUDY_MAX_CONFIGS], post[STUDY_MAX_CONFIGS];
    for (int k = 0; k < n; k++) {
        pre_t[k] = raw[k].temporal_cov;
        pre_s[k] = raw[k].spatial_cov;
        pre_e[k] = raw[k].smape_all;
        post[k] = dn[k].smape_all;
    }
    fprintf(f, "\nHow well the statistics before denoising rank the SMAPE after it, over the %d configurations "
               "(Spearman's rank correlation; 1: the same order, nan under 3 configurations):\n\n"
               "| before denoising | rank correlation with SMAPE after |\n|---|---|\n"
               "| temporal covariance | %.2f |\n| spatial covariance | %.2f |\n| SMAPE | %.2f |\n",
            n, study_rank_correlation(pre_t, post, n), study_rank_correlation(pre_s, post, n),
            study_rank_correlation(pre_e, post, n));
    return io_close_commit(f, tmp, path, msg);
}

/* 000 Sec. 1's motivation as a picture: each configuration's SMAPE after denoising against its
 * spatial covariance before; the radius curves of 000 Figure 3 as lines, the others as points. */
static int write_plot(const char *dir, const char *denoiser, const struct study_config *cfg,
                      const struct study_result *raw, const struct study_result *dn, int n, char *msg)
{
    static const char *const colors[] = {"#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"};
    double x[2][STUDY_MAX_CONFIGS], y[2][STUDY_MAX_CONFIGS], r[2][STUDY_MAX_CONFIGS];
    double px[STUDY_MAX_CONFIGS], py[STUDY_MAX_CONFIGS];
    struct plot_series series[2 + STUDY_MAX_CONFIGS];
    int cnt[2] = {0, 0}, ns = 2;
    for (int k = 0; k < n; k++) {
        const int q = study_pareto_series(&cfg[k]);
        if (q < 0) { /* a point of its own */
            px[k] = raw[k].spatial_cov;
            py[k] = dn[k].smape_all;
            series[ns] = (struct plot_series){cfg[k].name, colors[(ns - 2) % 6], 1, &px[k], &py[k], NULL};
            ns++;
            continue;
        }
        int at = cnt[q]++; /* by radius */
        for (; at > 0 && r[q][at - 1] > cfg[k].radius; at--) {
            x[q][at] = x[q][at - 1];
            y[q][at] = y[q][at - 1];
            r[q][at] = r[q][at - 1];
        }
        x[q][at] = raw[k].spatial_cov;
        y[q][at] = dn[k].smape_all;
        r[q][at] = cfg[k].radius;
    }
    series[0] = (struct plot_series){"bitterli", "#d62728", cnt[0], x[0], y[0], r[0]};
    series[1] = (struct plot_series){"compat (K 32)", "#1f77b4", cnt[1], x[1], y[1], r[1]};
    char path[4200], title[160], ylabel[80];
    snprintf(path, sizeof path, "%s/pareto_denoised.svg", dir);
    snprintf(title, sizeof title, "SMAPE after %s against spatial covariance before it (labels: R)", denoiser);
    snprintf(ylabel, sizeof ylabel, "SMAPE after %s", denoiser);
    return svg_write_xy_plot(path, title, "average relative covariance before denoising (radius 8)", ylabel, series,
                             ns, msg);
}

int study_write_denoised(const char *dir, const char *denoiser, const struct study_config *cfg,
                         const struct study_result *raw, const struct study_result *dn, int n, int m, char *msg)
{
    if (write_csv(dir, cfg, raw, dn, n, msg) != 0 || write_md(dir, denoiser, cfg, raw, dn, n, m, msg) != 0)
        return -1;
    return write_plot(dir, denoiser, cfg, raw, dn, n, msg);
}
