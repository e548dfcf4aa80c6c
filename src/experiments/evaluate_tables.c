/* evaluate_tables.c: the papers' tables and a verdict per claim from an
 * evaluation's merged steps (evaluate_tables.h). Must never run a command or
 * render: it reads study.csv and compare.csv. */
#include "experiments/evaluate_tables.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/csv_table.h"
#include "experiments/evaluate_change.h"
#include "experiments/evaluate_claims.h"
#include "experiments/evaluate_findings.h"
#include "experiments/evaluate_record.h"
#include "experiments/report_commit.h"
#include "experiments/stats.h"
#include "io/atomic_file.h"
#include "io/html_report.h"
#include "io/report.h"
#include "methods/method.h"

#define PATH_LEN 4400

static void fmt_pm(double v, double sem, char *out, size_t len)
{
    if (!isfinite(v))
        snprintf(out, len, "-");
    else if (isfinite(sem))
        snprintf(out, len, "%.4g +- %.2g", v, sem);
    else
        snprintf(out, len, "%.4g", v);
}

/* The scene of ours that stands in for one of the paper's, as "ours (for
 * PAPER'S)". */
static void scene_label(const struct eval_paper *paper, const char *scene, char *out, size_t len)
{
    for (const struct eval_scene_note *n = paper->scenes; n->scene; n++)
        if (!strcmp(n->scene, scene)) {
            snprintf(out, len, "%s (for %s)", scene, n->stands_for);
            return;
        }
    snprintf(out, len, "%s", scene);
}

/* What every line of a paper's claims shares: the setup's departures from the
 * paper's. */
static void differences(const struct eval_options *o, const struct eval_paper *paper, const char *scene, char *out,
                        size_t len)
{
    char res[64] = "";
    if (o->width != EVAL_PAPER_WIDTH || o->height != EVAL_PAPER_HEIGHT)
        snprintf(res, sizeof res, "%dx%d, not 1920x1080; ", o->width, o->height);
    const char *scene_note = "scene: ours";
    for (const struct eval_scene_note *n = paper->scenes; n->scene; n++)
        if (!strcmp(n->scene, scene))
            scene_note = "scene: ours, not the paper's";
    snprintf(out, len, "%s%s; %s", res, scene_note, paper->setup_note);
}

/* What a step's table and claims say about it: the heading (the scene and what
 * it stands for), the claims' "where" (the scene, and the base method where the
 * paper's recipe says so: 004)
 * and the setup's departures. */
struct step_text {
    char heading[96], where[96], diff[300];
};

static void step_text(const struct eval_options *o, const struct eval_step *s, struct step_text *x)
{
    scene_label(s->recipe, s->scene, x->heading, sizeof x->heading);
    if (s->recipe->where_names_base)
        snprintf(x->where, sizeof x->where, "%s, %s", s->scene, s->base);
    else
        snprintf(x->where, sizeof x->where, "%s", s->scene);
    differences(o, s->recipe, s->scene, x->diff, sizeof x->diff);
}

/* DIR/STEP/NAME.csv into t. */
static int read_step_csv(const char *dir, const struct eval_step *s, const char *name, struct csv_table *t)
{
    char path[PATH_LEN], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof path, "%s/%s/%s.csv", dir, s->name, name);
    if (csv_table_read(path, t, msg) != 0) {
        cli_error("evaluate: %s", msg);
        return -1;
    }
    return 0;
}

/* Row r's relMSE as the tables show it: without the reference's own share
 * (relmse_net) where the step has the reference's halves, else as measured. */
static double relmse_shown(const struct csv_table *t, int r)
{
    const double net = csv_table_num(t, r, "relmse_net");
    return isfinite(net) ? net : csv_table_num(t, r, "relmse");
}

/* The reference's own error in the metrics cols (t's columns ref_COL, the same
 * on every row, from its two independent halves) and its share of row base's
 * error, as a sentence; nothing when t has none (a reference given with --ref,
 * or a step merged before halves existed: then it says so). */
static void reference_share(struct md_text *md, const struct csv_table *t, int base, const char *const *cols,
                            const char *const *names, int n)
{
    char ref[64];
    int any = 0;
    for (int k = 0; k < n && base >= 0; k++) {
        snprintf(ref, sizeof ref, "ref_%s", cols[k]);
        const double own = csv_table_num(t, base, ref), v = csv_table_num(t, base, cols[k]);
        if (!isfinite(own))
            continue;
        md_put(md, "%s %s %.4g (%.1f%% of %s's)",
               any ? ";" : "\nThe reference's own error, from its two independent halves:", names[k], own,
               100.0 * own / v, t->cell[(size_t)(base + 1) * t->ncol]);
        any = 1;
    }
    md_put(md, any ? ". A claim whose difference is smaller than it is refused; "
                     "relMSE is shown with it subtracted.\n"
                   : "\nThe reference has no halves here: its own share of the "
                     "error is not known.\n");
}

/* DIR/STEP/runs.csv (each configuration's metrics per run) into t: 1 when it is
 * there, 0 when the step was merged without it (its claims then fall back to
 * unpaired means). */
static int read_step_runs(const char *dir, const struct eval_step *s, struct csv_table *t)
{
    char path[PATH_LEN], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof path, "%s/%s/runs.csv", dir, s->name);
    return csv_table_read(path, t, msg) == 0;
}

/* 000: Table 1 (pass times), the quality metrics of Table 2's layout, the
 * claims. */
/* 000 Figure 3 on the Table 2 scene: Bitterli's selection and ours (K 32) at
 * each radius, as points of the error-covariance plane (the step's pareto.svg
 * draws them), and the claim that ours moves the frontier: lower SMAPE and
 * lower spatial covariance at the same radius (R 30 is FAST's claims'). */
static void pareto_000(struct md_text *md, struct claims *cl, const struct eval_step *s, const struct step_tables *d,
                       const char *where, const char *diff)
{
    const struct csv_table *t = d->t;
    static const double radius[4] = {10, 30, 50, 100};
    static const char *const bitterli[4] = {"bitterli-r10", "bitterli", "bitterli-r50", "bitterli-r100"};
    static const char *const ours[4] = {"compat-r10-k32", "fast", "balanced", "conservative"};
    static const char *const col[2][2] = {{"smape_all", "smape_all_sem"}, {"spatial_cov", "spatial_cov_sem"}};
    char a[4][64];
    md_put(md,
           "\nFigure 3 layout (error against spatial covariance over radii; the "
           "plot: %s/pareto.svg):\n\n"
           "| R | Bitterli SMAPE | Bitterli spatial cov | ours (K 32) SMAPE | "
           "ours spatial cov |\n|---|---|---|---|---|\n",
           s->name);
    for (int k = 0; k < 4; k++) {
        const int b = csv_table_find(t, bitterli[k]), c = csv_table_find(t, ours[k]);
        for (int m = 0; m < 2; m++) {
            fmt_pm(csv_table_num(t, b, col[m][0]), csv_table_num(t, b, col[m][1]), a[m], sizeof a[m]);
            fmt_pm(csv_table_num(t, c, col[m][0]), csv_table_num(t, c, col[m][1]), a[2 + m], sizeof a[2 + m]);
        }
        md_put(md, "| %g | %s | %s | %s | %s |\n", radius[k], a[0], a[1], a[2], a[3]);
        if (radius[k] == 30.0)
            continue;
        for (int m = 0; m < 2; m++) {
            char what[96];
            snprintf(what, sizeof what, "Fig. 3: %s, ours vs Bitterli at R %g", m ? "spatial covariance" : "SMAPE",
                     radius[k]);
            claim(cl, "000", what, where, eval_change(d, c, b, col[m][0]), "lower (a better frontier; plot only)",
                  REDUCTION(0.0), diff);
        }
    }
}

int eval_table_000(struct md_text *md, struct claims *cl, const struct eval_options *o, const char *dir,
                   const struct eval_step *s, const struct step_tables *d)
{
    (void)dir;
    const struct csv_table *t = d->t;
    static const char *const presets[] = {"fast", "balanced", "conservative"};
    char a[64], b[64], c[64], sp[64], e[64];
    struct step_text x;
    step_text(o, s, &x);
    const char *heading = x.heading, *where = x.where, *diff = x.diff;
    md_put(md,
           "\n### %s\n\nTable 1 layout (pass times, ms, means over the measured "
           "frames and runs):\n\n"
           "| config | R | K | select | spatial | frame | frame vs Bitterli "
           "|\n|---|---|---|---|---|---|---|\n",
           heading);
    const int bit = csv_table_find(t, "bitterli");
    const double base_ms = csv_table_num(t, bit, "ms_frame");
    for (int r = 0; r < t->nrow; r++) {
        const double ms = csv_table_num(t, r, "ms_frame");
        cl->render_ms += ms * (eval_warmup(o, s->paper) + eval_frames(o, s->paper)) * eval_runs(o, s->paper);
        md_put(md, "| %s | %g | %g | %.1f | %.1f | %.1f | %+.1f%% |\n", t->cell[(size_t)(r + 1) * t->ncol],
               csv_table_num(t, r, "radius"), csv_table_num(t, r, "K"), csv_table_num(t, r, "ms_select"),
               csv_table_num(t, r, "ms_spatial"), ms, 100.0 * (ms / base_ms - 1.0));
    }
    md_put(md, "\nTable 2 layout (SMAPE in %% with standard errors over the runs; "
               "relative temporal covariance at lag "
               "3 and spatial covariance within 8 px, 000 Appendix A, with jackknife "
               "standard errors over the runs; "
               "hard pixels: 000 Sec. 7, every neighbor within 30 px counted):\n\n"
               "| config | R | K | SMAPE | hard SMAPE | temporal cov | hard temporal "
               "cov | spatial cov | frame ms |\n"
               "|---|---|---|---|---|---|---|---|---|\n");
    for (int r = 0; r < t->nrow; r++) {
        fmt_pm(csv_table_num(t, r, "smape_all"), csv_table_num(t, r, "smape_all_sem"), a, sizeof a);
        fmt_pm(csv_table_num(t, r, "smape_hard"), csv_table_num(t, r, "smape_hard_sem"), b, sizeof b);
        fmt_pm(csv_table_num(t, r, "temporal_cov"), csv_table_num(t, r, "temporal_cov_sem"), c, sizeof c);
        fmt_pm(csv_table_num(t, r, "temporal_cov_hard"), csv_table_num(t, r, "temporal_cov_hard_sem"), e, sizeof e);
        fmt_pm(csv_table_num(t, r, "spatial_cov"), csv_table_num(t, r, "spatial_cov_sem"), sp, sizeof sp);
        md_put(md, "| %s | %g | %g | %s | %s | %s | %s | %s | %.1f |\n", t->cell[(size_t)(r + 1) * t->ncol],
               csv_table_num(t, r, "radius"), csv_table_num(t, r, "K"), a, b, c, e, sp,
               csv_table_num(t, r, "ms_frame"));
    }
    static const char *const share_cols[2] = {"smape_all", "smape_hard"}, *const share_names[2] = {"SMAPE",
                                                                                                   "hard SMAPE"};
    reference_share(md, t, bit, share_cols, share_names, 2);
    /* 000 Sec. 7.1 (FAST against Bitterli R = 30): EMERALD SQUARE -29% SMAPE,
     * -49% temporal covariance; the simpler scenes (VEACH AJAR among them)
     * -5.8..-13.7% and -22..-31%; hard pixels -26..-29% SMAPE and -43..-57%
     * temporal covariance in every scene. Sec. 7.2: overheads FAST 1.3-4.4%,
     * BALANCED 2.0-6.4%, CONSERVATIVE 4.3-7.4%. */
    const int emerald = strstr(heading, "EMERALD") != NULL;
    const int fast = csv_table_find(t, "fast");
    char found[1000];
    eval_deciding_000(d, bit, fast, found, sizeof found);
    claim_found(cl, "000", "FAST: SMAPE vs Bitterli R = 30", where, eval_change(d, fast, bit, "smape_all"),
                emerald ? "-29% (EMERALD SQUARE)" : "-5.8% to -13.7% (simpler scenes)", REDUCTION(emerald ? 29.0 : 5.8),
                found, diff);
    claim_found(cl, "000", "FAST: temporal covariance vs Bitterli", where, eval_change(d, fast, bit, "temporal_cov"),
                emerald ? "-49% (EMERALD SQUARE)" : "-22% to -31% (simpler scenes)", REDUCTION(emerald ? 49.0 : 22.0),
                found, diff);
    claim_found(cl, "000", "FAST: hard-pixel SMAPE vs Bitterli", where, eval_change(d, fast, bit, "smape_hard"),
                "-26% to -29%", REDUCTION(26.0), found, diff);
    claim_found(cl, "000", "FAST: hard-pixel temporal covariance vs Bitterli", where,
                eval_change(d, fast, bit, "temporal_cov_hard"), "-43% to -57%", REDUCTION(43.0), found, diff);
    static const char *const cost_figure[] = {"+1.3% to +4.4%", "+2.0% to +6.4%", "+4.3% to +7.4%"};
    static const double cost_max[] = {4.4, 6.4, 7.4};
    for (int k = 0; k < 3; k++) {
        const int r = csv_table_find(t, presets[k]);
        char what[96], why[1000];
        snprintf(what, sizeof what, "%s: frame time vs Bitterli (cost)", presets[k]);
        /* where the extra time goes: the selection's taps, or the spatial pass
         * merging more pixels */
        snprintf(why, sizeof why, "of the %+.0f ms: select %+.0f ms, spatial reuse %+.0f ms",
                 csv_table_num(t, r, "ms_frame") - base_ms,
                 csv_table_num(t, r, "ms_select") - csv_table_num(t, bit, "ms_select"),
                 csv_table_num(t, r, "ms_spatial") - csv_table_num(t, bit, "ms_spatial"));
        claim_found(cl, "000", what, where, eval_change(d, r, bit, "ms_frame"), cost_figure[k],
                    COSTS_AT_MOST(cost_max[k]), r >= 0 ? why : "", diff);
    }
    if (!s->all_configs)
        return 0;
    /* 000 Sec. 7.3 and Table 2 (EMERALD SQUARE): a larger R lowers spatial
     * covariance (K 32: 6.0 at R 30, 1.5 at R 100, x 1e-3); a larger K raises it
     * (R 30: 4.6 at K 8, 6.6 at K 128) and lowers SMAPE (29.9 at K 8, 29.3 at K
     * 128). */
    const int r100 = csv_table_find(t, "conservative"), k8 = csv_table_find(t, "compat-r30-k8"),
              k128 = csv_table_find(t, "compat-r30-k128");
    claim(cl, "000", "Table 2: spatial covariance, R 100 vs R 30 (K 32)", where,
          eval_change(d, r100, fast, "spatial_cov"), "-75% (6.0 -> 1.5)", REDUCTION(0.0), diff);
    claim(cl, "000", "Table 2: spatial covariance, K 8 vs K 128 (R 30)", where, eval_change(d, k8, k128, "spatial_cov"),
          "-30% (6.6 -> 4.6)", REDUCTION(0.0), diff);
    claim(cl, "000", "Table 2: SMAPE, K 128 vs K 8 (R 30)", where, eval_change(d, k128, k8, "smape_all"),
          "-2% (29.9 -> 29.3)", REDUCTION(0.0), diff);
    pareto_000(md, cl, s, d, where, diff);
    return 0;
}

/* 004: the main table (MAPE overall and over disoccluded pixels) and its
 * claims. */
/* 004 Table 2's layout: each reuse's pass times per frame (run 0's means over
 * the frames). */
static int table2_004(struct md_text *md, const char *dir, const struct eval_step *s, char (*label)[160],
                      const char *const *names, int rows)
{
    struct csv_table p;
    if (read_step_csv(dir, s, "passes", &p) != 0)
        return -1;
    static const char *const pass[] = {"initial",     "temporal",        "select",      "spatial", "cells",
                                       "cell_search", "spmis_canonical", "spmis_reuse", "shade"};
    md_put(md, "\nTable 2 layout (ms per frame of each pass, the fastest run, "
               "mean over its frames; spmis: create cells, cell "
               "search, canonical weight m_c, stochastic neighbor reuse):\n\n| "
               "reuse | initial | temporal | select | "
               "spatial | cells | cell search | m_c | neighbor reuse | shade "
               "|\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < rows; k++) {
        const int r = csv_table_find(&p, label[k]);
        md_put(md, "| %s |", names[k]);
        for (size_t q = 0; q < sizeof pass / sizeof pass[0]; q++)
            md_put(md, " %.1f |", csv_table_num(&p, r, pass[q]));
        md_put(md, "\n");
    }
    /* 004 Table 2 (GPU, 1080p, four scenes): create cells 1.57, m_c 4.40, neighbor reuse 9.19 ms against
     * initial sampling's 8.68 ms. Their ratio is the one cost figure both tables have. */
    const double paper_spmis = 1.57 + 4.40 + 9.19, paper_initial = 8.68;
    md_put(md,
           "\nSPMIS's own passes (cells, cell search, m_c, neighbor reuse) against initial sampling: the paper's "
           "GPU %.2f / %.2f ms = %.2fx; here",
           paper_spmis, paper_initial, paper_spmis / paper_initial);
    for (int k = 1; k < rows; k++) {
        const int r = csv_table_find(&p, label[k]);
        double own = 0.0;
        for (size_t q = 4; q < 8; q++)
            own += csv_table_num(&p, r, pass[q]);
        md_put(md, "%s %s %.2fx", k > 1 ? ";" : ":", names[k], own / csv_table_num(&p, r, "initial"));
    }
    md_put(md, " (standard reuse's spatial pass: %.2fx).\n",
           csv_table_num(&p, csv_table_find(&p, label[0]), "spatial") /
               csv_table_num(&p, csv_table_find(&p, label[0]), "initial"));
    csv_table_free(&p);
    return 0;
}

int eval_table_004(struct md_text *md, struct claims *cl, const struct eval_options *o, const char *dir,
                   const struct eval_step *s, const struct step_tables *d)
{
    const struct csv_table *t = d->t;
    const struct eval_step_recipe *rc = s->step_recipe;
    const int rows = rc->nvariants;
    RESTIR_CHECK(rows >= 4 && rows <= EVAL_MAX_VARIANTS); /* the claims read rows 0 (standard), 1 and 3 */
    char a[64], b[64], c[64], fl[64], label[EVAL_MAX_VARIANTS][160];
    const char *names[EVAL_MAX_VARIANTS];
    struct step_text x;
    step_text(o, s, &x);
    const char *scene = x.heading, *where = x.where, *diff = x.diff;
    for (int k = 0; k < rows; k++) {
        snprintf(label[k], sizeof label[k], "%s%s", s->base, rc->variants[k].spec);
        names[k] = rc->variants[k].name;
    }
    md_put(md,
           "\n### %s, %s\n\nLast frame (%d) of the camera path, means over %d "
           "runs +- standard errors:\n\n"
           "| reuse | ms/frame | MAPE | MAPE disoccluded | disoccluded share | "
           "relMSE | FLIP |\n|---|---|---|---|---|---|---|\n",
           scene, s->base, eval_frames(o, s->paper) - 1, eval_runs(o, s->paper));
    int row[EVAL_MAX_VARIANTS];
    for (int k = 0; k < rows; k++) {
        const int r = row[k] = csv_table_find(t, label[k]);
        fmt_pm(csv_table_num(t, r, "mape"), csv_table_num(t, r, "mape_sem"), a, sizeof a);
        fmt_pm(csv_table_num(t, r, "mape_disoccluded"), csv_table_num(t, r, "mape_disoccluded_sem"), b, sizeof b);
        fmt_pm(relmse_shown(t, r), csv_table_num(t, r, "relmse_sem"), c, sizeof c);
        cl->render_ms += csv_table_num(t, r, "ms_per_frame") * eval_frames(o, s->paper) * eval_runs(o, s->paper);
        fmt_pm(csv_table_num(t, r, "flip"), csv_table_num(t, r, "flip_sem"), fl, sizeof fl);
        md_put(md, "| %s | %.1f | %s | %s | %.3f | %s | %s |\n", names[k], csv_table_num(t, r, "ms_per_frame"), a, b,
               csv_table_num(t, r, "disoccluded_share"), c, fl);
    }
    static const char *const share_cols[2] = {"mape", "relmse"}, *const share_names[2] = {"MAPE", "relMSE"};
    reference_share(md, t, row[0], share_cols, share_names, 2);
    const int own = rc->paper_ran_base; /* the paper's claims as it states them, or carried over to our base */
    static const char *const col[2][2] = {{"mape", "mape_sem"}, {"mape_disoccluded", "mape_disoccluded_sem"}};
    char found[2][1000];
    for (int m = 0; m < 2; m++)
        eval_deciding_004(d, row[0], row[1], row[3], col[m][0], found[m], sizeof found[m]);
    /* each variant against standard reuse; the paper claims SPMIS's (the first), the others are ours */
    for (int v = 0; v < rows - 1; v++)
        for (int m = 0; m < 2; m++) {
            char what[160];
            snprintf(what, sizeof what, "%s: MAPE %s vs standard", rc->variants[v + 1].claim,
                     m ? "disoccluded" : "overall");
            const char *figure = v     ? "none (not in the paper)"
                                 : own ? (m ? "lower, \"especially in disocclusions\"" : "lower overall")
                                 : m   ? "lower in disocclusions (the paper: ReSTIR PT only)"
                                       : "lower (the paper: ReSTIR PT only)";
            claim_found(cl, s->paper, what, where, eval_change(d, row[v + 1], row[0], col[m][0]), figure,
                        v ? NO_CLAIM : REDUCTION(0.0), v ? "" : found[m], diff);
        }
    return table2_004(md, dir, s, label, names, rows) == 0 ? 0 : EXIT_RUNTIME;
}

/* 004 Figures 2, 6 and 7: SPMIS's own variants on one scene, and the claims the
 * figures make. */
int eval_table_004_ablation(struct md_text *md, struct claims *cl, const struct eval_options *o, const char *dir,
                            const struct eval_step *s, const struct step_tables *d)
{
    (void)dir;
    const struct csv_table *t = d->t;
    const struct eval_step_recipe *rc = s->step_recipe;
    RESTIR_CHECK(rc->nvariants == 6); /* the claims read the rows by their place in the recipe */
    char a[64], b[64], label[6][200];
    struct step_text x;
    step_text(o, s, &x);
    const char *scene = x.heading, *where = x.where, *diff = x.diff;
    int row[6];
    md_put(md,
           "\n### %s, SPMIS variants (004 Figures 2, 6, 7), %s\n\nLast frame "
           "(%d) of the camera path, means over %d "
           "runs +- standard errors:\n\n| variant | ms/frame | MAPE | MAPE "
           "disoccluded |\n|---|---|---|---|\n",
           scene, s->base, eval_frames(o, s->paper) - 1, eval_runs(o, s->paper));
    for (int k = 0; k < 6; k++) {
        snprintf(label[k], sizeof label[k], "%s%s", s->base, rc->variants[k].spec);
        const int r = row[k] = csv_table_find(t, label[k]);
        fmt_pm(csv_table_num(t, r, "mape"), csv_table_num(t, r, "mape_sem"), a, sizeof a);
        fmt_pm(csv_table_num(t, r, "mape_disoccluded"), csv_table_num(t, r, "mape_disoccluded_sem"), b, sizeof b);
        cl->render_ms += csv_table_num(t, r, "ms_per_frame") * eval_frames(o, s->paper) * eval_runs(o, s->paper);
        md_put(md, "| %s | %.1f | %s | %s |\n", rc->variants[k].name, csv_table_num(t, r, "ms_per_frame"), a, b);
    }
#define MAPE_CHANGE(x, y) eval_change(d, row[x], row[y], "mape")
    claim(cl, "004", "Fig. 2: the N / M scaling vs none: MAPE", where, MAPE_CHANGE(0, 1), "lower (images only)",
          REDUCTION(0.0), diff);
    claim(cl, "004", "Fig. 7: N = N_c = M vs N = 3: MAPE", where, MAPE_CHANGE(3, 0), "lower (\"some loss of quality\")",
          REDUCTION(0.0), diff);
    claim(cl, "004", "Fig. 7: N = 3 vs N = N_c = M: frame time", where, eval_change(d, row[0], row[3], "ms_per_frame"),
          "lower (\"significant cost reduction\")", REDUCTION(0.0), diff);
    claim(cl, "004", "Fig. 6: N_c = M vs N_c = 1: MAPE", where, MAPE_CHANGE(5, 0), "\"only slightly\" different",
          SMALL_CHANGE(5.0), diff);
#undef MAPE_CHANGE
    return 0;
}

/* The method of a method spec ("gpt:spp=3": gpt), or NULL when it names none registered. */
static const struct method *spec_method(const char *spec)
{
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)strcspn(spec, ":"), spec);
    return method_find(name);
}

/* The rows of 002's recipe (evaluate_recipes.c) by their place: ours and its three rivals with the L2
 * and the L1 reconstruction, and Gradient after ReSTIR once. */
static const int ours_at[2] = {0, 4}, rivals_at[2][3] = {{1, 2, 3}, {5, 2, 6}}, once_at = 7;

/* 002: the equal-time table (L2 and L1) and its claims. */
int eval_table_002(struct md_text *md, struct claims *cl, const struct eval_options *o, const char *dir,
                   const struct eval_step *s, const struct step_tables *d)
{
    (void)dir;
    const struct csv_table *t = d->t;
    const struct eval_variant *v = s->step_recipe->variants;
    RESTIR_CHECK(s->step_recipe->nvariants == 8);
    char a[64], b[64], fl[64], g[3][64];
    struct step_text x;
    step_text(o, s, &x);
    const char *heading = x.heading, *where = x.where, *diff = x.diff;
    md_put(md,
           "\n### %s\n\nLast frame (%d) of the camera path, the paper's "
           "equal-time ratios (on its GPU every row "
           "takes ours' time; time / ours' is the ratio measured on this "
           "machine, and the next column the instances, "
           "or G-PT's paths, that fit ours' time here); means over %d runs +- "
           "standard errors (FLIP: mean HDR-FLIP, Andersson et al. 2021, at 67 "
           "pixels per degree; gradient relMSE: of the estimated forward "
           "differences against the reference's, "
           "our measure of Fig. 7's gradient images; trim 1%%: the same without "
           "the worst 1%% of pixel pairs, "
           "which carry most of it; gradient MAPE: robust to them, both issue "
           "42's):\n\n| method | instances | spp | "
           "ms/frame | time / ours' | instances or spp at ours' time here | "
           "relMSE | MAPE | FLIP | gradient relMSE | "
           "gradient relMSE trim 1%% | gradient MAPE |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
           heading, eval_frames(o, s->paper) - 1, eval_runs(o, s->paper));
    static const char *const grad_col[3][2] = {{"gradient_relmse", "gradient_relmse_sem"},
                                               {"gradient_relmse_trim1", "gradient_relmse_trim1_sem"},
                                               {"gradient_mape", "gradient_mape_sem"}};
    const int ours_row = csv_table_find(t, v[ours_at[0]].spec);
    for (int r = 0; r < t->nrow; r++) {
        fmt_pm(relmse_shown(t, r), csv_table_num(t, r, "relmse_sem"), a, sizeof a);
        fmt_pm(csv_table_num(t, r, "mape"), csv_table_num(t, r, "mape_sem"), b, sizeof b);
        for (int k = 0; k < 3; k++)
            fmt_pm(csv_table_num(t, r, grad_col[k][0]), csv_table_num(t, r, grad_col[k][1]), g[k], sizeof g[k]);
        cl->render_ms += csv_table_num(t, r, "ms_per_frame") * eval_frames(o, s->paper) * eval_runs(o, s->paper);
        fmt_pm(csv_table_num(t, r, "flip"), csv_table_num(t, r, "flip_sem"), fl, sizeof fl);
        /* the paper's ratios give every row ours' time on its GPU (time / ours' = 1
         * there); here the ratio is measured, and the instances (or, for a method
         * budgeted by paths per pixel such as G-PT, the paths) that would fit ours'
         * time follow */
        const double ms = csv_table_num(t, r, "ms_per_frame"), ours_ms = csv_table_num(t, ours_row, "ms_per_frame"),
                     inst = csv_table_num(t, r, "instances"), spp = csv_table_num(t, r, "spp");
        const struct method *m = spec_method(t->cell[(size_t)(r + 1) * t->ncol]);
        const double per = m && method_has(m, METHOD_BUDGET_BY_SPP) ? ms / spp : ms / inst;
        md_put(md, "| %s | %g | %g | %.1f | %.2f | %.2f | %s | %s | %s | %s | %s | %s |\n",
               t->cell[(size_t)(r + 1) * t->ncol], inst, spp, ms, ms / ours_ms, ours_ms / per, a, b, fl, g[0], g[1],
               g[2]);
    }
    static const char *const share_cols[2] = {"mape", "relmse"}, *const share_names[2] = {"MAPE", "relMSE"};
    reference_share(md, t, ours_row, share_cols, share_names, 2);
    for (int l = 0; l < 2; l++) {
        const int me = csv_table_find(t, v[ours_at[l]].spec);
        for (int k = 0; k < 3; k++) {
            const char *rival = v[rivals_at[l][k]].spec, *name = v[rivals_at[0][k]].claim;
            const struct method *rm = spec_method(rival);
            if (l == 1 && !(rm && method_has(rm, METHOD_GRADIENT))) /* no gradients, no L1 reconstruction
                                                                       (Area ReSTIR): Figure 8 shows it in the
                                                                       L2 row only */
                continue;
            const int r = csv_table_find(t, rival);
            /* relMSE as the paper; MAPE too: relMSE's few outlier pixels can hide a
             * difference (their spread over runs is of the order of the mean) that
             * MAPE, robust to them, shows */
            static const char *const metric[2][3] = {{"relMSE", "relmse", "relmse_sem"}, {"MAPE", "mape", "mape_sem"}};
            char found[1000];
            eval_gradient_findings(d, me, r, found, sizeof found);
            for (int m = 0; m < 2; m++) {
                char what[128];
                snprintf(what, sizeof what, "%s: %s vs %s", l ? "L1" : "L2", metric[m][0], name);
                claim_found(cl, "002", what, where, eval_change(d, me, r, metric[m][1]),
                            m ? "lower at equal time (Fig. 7, 8 show images; the paper "
                                "names no metric)"
                              : "lower at equal time (Fig. 7, 8; no numbers)",
                            REDUCTION(0.0), found, diff);
            }
        }
    }
    /* Fig. 7 and Sec. 6: "our method tends to produce highest-quality gradients"
     * at equal time. The gradients do not depend on the reconstruction: the L2
     * rows judge it. */
    const int me = ours_row;
    for (int k = 0; k < 3; k += 2) {
        const int r = csv_table_find(t, v[rivals_at[0][k]].spec);
        char what[128], found[1000];
        snprintf(what, sizeof what, "Fig. 7: gradient relMSE vs %s", v[rivals_at[0][k]].claim);
        eval_gradient_findings(d, me, r, found, sizeof found);
        claim_found(cl, "002", what, where, eval_change(d, me, r, "gradient_relmse"),
                    "lower at equal time (images only)", REDUCTION(0.0), found, diff);
    }
    /* Gradient after ReSTIR once: the same samples per frame as ours, not the
     * paper's equal time */
    const int once = csv_table_find(t, v[once_at].spec);
    char once_what[128];
    snprintf(once_what, sizeof once_what, "gradient relMSE vs %s (equal samples)", v[once_at].claim);
    claim(cl, "002", once_what, where, eval_change(d, me, once, "gradient_relmse"), "none (not in the paper)", NO_CLAIM,
          diff);
    /* the gradient claim again without the worst 1% of pairs and as
     * MAPE, informational: the paper shows images only, and these say whether a
     * few pairs decide the relMSE verdict */
    static const char *const robust[2] = {"gradient relMSE trim 1%", "gradient MAPE"};
    const int vs[2] = {csv_table_find(t, v[rivals_at[0][0]].spec), once};
    const char *const vs_name[2] = {v[rivals_at[0][0]].claim, v[once_at].claim};
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 2; k++) {
            char what[128];
            snprintf(what, sizeof what, "%s vs %s", robust[m], vs_name[k]);
            claim(cl, "002", what, where, eval_change(d, me, vs[k], grad_col[m + 1][0]),
                  "none (the relMSE claim without its worst pairs)", NO_CLAIM, diff);
        }
    return 0;
}

/* index.html: the evaluation's text and a link to each step's own page. */
static int write_index(const char *dir, const char *command, const struct eval_step *steps, int n, const char *md,
                       char *msg)
{
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s/index.html", dir);
    struct html_page pg;
    if (html_begin(&pg, path, "restir evaluate", msg) != 0)
        return -1;
    html_run_info(&pg, command, RESTIR_GIT_COMMIT);
    html_raw(&pg, "<h2>Steps</h2><ul>");
    for (int k = 0; k < n; k++)
        html_raw(&pg, "<li><a href=\"%s/index.html\">%s</a> (restir %s)</li>", steps[k].name, steps[k].name,
                 steps[k].kind);
    html_raw(&pg, "</ul><h2>Tables and claims</h2><pre>");
    html_text(&pg, md);
    html_raw(&pg, "</pre>");
    return html_end(&pg, msg);
}

int evaluate_write_tables(const char *dir, const char *command, const struct eval_options *o,
                          const struct eval_step *steps, int n, const int *merged)
{
    char msg[RESTIR_MSG_LEN], path[PATH_LEN];
    struct md_text md = {0};
    struct claims cl;
    memset(&cl, 0, sizeof cl);
    snprintf(path, sizeof path, "%s/claims.csv", dir);
    if (csv_open(&cl.csv, path,
                 "paper,claim,where,ours_change_pct,ours_lo_pct,ours_hi_pct,"
                 "interval,seeds,paper_figure,verdict,why",
                 msg) != 0) {
        cli_error("%s", msg);
        return EXIT_RUNTIME;
    }
    cl.csv_ok = 1;
    int rc = 0;
    const struct eval_paper *paper = NULL;
    for (int k = 0; k < n && rc == 0; k++) {
        const struct eval_step *s = &steps[k];
        if (s->recipe != paper) { /* a paper's section: its setup, then its steps, then its claims */
            if (paper)
                flush_claims(&md, &cl, paper->id);
            paper = s->recipe;
            const char *current = paper->id;
            md_put(&md,
                   "\n## %s\n\n`%s`\n\n%dx%d (the paper: %dx%d), %d independently "
                   "seeded runs per configuration, "
                   "references of %d paths per pixel, ",
                   paper->title, command, o->width, o->height, EVAL_PAPER_WIDTH, EVAL_PAPER_HEIGHT,
                   eval_runs(o, current), eval_ref_spp(o));
            if (paper->warmup > 0)
                md_put(&md, "static camera, %d warm-up frames, %d measured frames.\n", eval_warmup(o, current),
                       eval_frames(o, current));
            else
                md_put(&md, "camera path, error of frame %d.\n", eval_frames(o, current) - 1);
            md_put(&md, "Pixel radii as in the paper (not scaled with the resolution).\n");
            char provenance[2048]; /* the steps' provenance.json, so --tables writes
                                      the merge's very line */
            evaluate_provenance_text(dir, steps, n, merged, current, provenance, sizeof provenance);
            md_put(&md, "%s\n", provenance);
            if (paper->configs && o->configs[0])
                md_put(&md,
                       "Configurations: only %s (--configs; the whole evaluation runs %s): claims on the others read "
                       "\"not measured\".\n",
                       o->configs, paper->configs_whole);
            for (int j = k; j < n && steps[j].recipe == paper; j++)
                for (const struct eval_scene_note *sn = paper->scenes; sn->scene; sn++)
                    if (!strcmp(sn->scene, steps[j].scene) && (j == k || strcmp(steps[j - 1].scene, steps[j].scene)))
                        md_put(&md, "- scene `%s` for %s: %s.\n", sn->scene, sn->stands_for, sn->why);
        }
        if (!merged[k]) {
            md_put(&md,
                   "\n### %s: not finished\n\nIts jobs are not all done yet: this "
                   "evaluation was merged with "
                   "`--partial`; run the remaining jobs and merge again.\n",
                   s->name);
            continue;
        }
        struct csv_table t, runs;
        if (read_step_csv(dir, s, s->kind, &t) != 0) {
            rc = EXIT_RUNTIME;
            break;
        }
        const int has_runs = read_step_runs(dir, s, &runs);
        const struct step_tables d = {&t, has_runs ? &runs : NULL, eval_runs(o, s->paper)};
        rc = s->step_recipe->table(&md, &cl, o, dir, s, &d);
        csv_table_free(&t);
        if (has_runs)
            csv_table_free(&runs);
    }
    if (rc == 0 && paper)
        flush_claims(&md, &cl, paper->id);
    free(cl.md.s);
    if (rc == 0 && csv_close(&cl.csv, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    } else if (rc != 0)
        csv_abort(&cl.csv);
    snprintf(path, sizeof path, "%s/evaluation.md", dir);
    if (rc == 0 && io_write_file(path, md.s, md.len, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0 && o->report && write_index(dir, command, steps, n, md.s, msg) != 0) {
        cli_error("--report: %s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0)
        printf("%s\nevaluation: %s/evaluation.md, %s/claims.csv%s\n", md.s, dir, dir, o->report ? ", index.html" : "");
    free(md.s);
    return rc;
}
