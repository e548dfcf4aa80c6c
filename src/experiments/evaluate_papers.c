/* evaluate_papers.c: each paper's evaluation as study / compare commands (evaluate_papers.h).
 * Must never run a command or read results. */
#include "experiments/evaluate_papers.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "scene/scenes_builtin.h"

/* The papers' settings (read from the papers; docs/EVALUATION.md lists them with their sources). */
#define EVAL_RUNS 4         /* independent runs per configuration: the minimum for a spread */
#define EVAL_002_RUNS 8     /* measured: 002's gradient errors had standard errors of 15-40% with 4 runs */
#define EVAL_REF_SPP 1024   /* paths per pixel of each comparison's reference */
#define EVAL_000_WARMUP 40  /* 000 Sec. 7: 40 frames before measuring, static camera */
#define EVAL_000_FRAMES 16  /* measured frames (000 does not say how many) */
#define EVAL_000_RADIUS 100 /* the largest radius 000 uses: CONSERVATIVE, Table 2's R = 100 */
#define EVAL_004_FRAMES 50  /* 004 Sec. 6: the last frame of a 50-frame animation */
#define EVAL_004_RADIUS 30  /* 004: standard reuse within 30 px, the cell search starting at 30 px */
#define EVAL_002_FRAMES 16  /* 002 shows single frames of camera animations; their length is not given */
#define EVAL_002_RADIUS 30  /* area ReSTIR's spatial radius, which 002's primal and baselines use */

const struct eval_scene_note eval_scene_notes[] = {
    {"000", "forest", "EMERALD SQUARE",
     "dense outdoor foliage: 25 trees with 75,000 alpha-tested leaf cards under a sun and sky, seen from the path "
     "into the crowns, static camera as in all of 000's results; the hard-pixel case 000 targets"},
    {"000", "ajar", "VEACH AJAR",
     "the same scene idea: a closed room lit through the gap of a door, mostly indirect light; static camera"},
    {"004", "pillars", "disocclusion under fast camera motion, as in 004 Figure 1",
     "the camera strafes 8 m in 64 frames (0.125 m per frame on average), 6 m from seven pillars and 8.5 m from "
     "the wall behind them: at "
     "1920x1080 the pillars move about 24 px per frame and the wall 17 px on average, so each pillar edge uncovers "
     "a band "
     "of about 7 px per frame (004 gives no speeds; this is faster than a walk at 60 Hz); frame 49 is 3/4 of "
     "the way along"},
    {"004", "forest", "dense foliage in motion",
     "the camera walks 12 m in 120 frames along the path between the trees, looking up into the crowns: every "
     "leaf edge disoccludes sky or leaves behind it"},
    {"002", "ajar", "VEACH AJAR", "the paper's own scene idea: glossy floor, light through a door gap"},
    {"002", "cornell", "an indoor scene (AACHEN TOYS, CLASSROOM, KITCHEN are not ours)",
     "closed room with a ceiling light, diffuse and glossy blocks: smooth indirect light and sharp edges"},
    {NULL, NULL, NULL, NULL}};

int eval_runs(const struct eval_options *o, const char *paper)
{
    if (o->runs > 0)
        return o->runs;
    return !strcmp(paper, "002") ? EVAL_002_RUNS : EVAL_RUNS;
}

int eval_ref_spp(const struct eval_options *o)
{
    return o->ref_spp > 0 ? o->ref_spp : EVAL_REF_SPP;
}

int eval_warmup(const struct eval_options *o)
{
    return o->warmup > 0 ? o->warmup : EVAL_000_WARMUP;
}

int eval_frames(const struct eval_options *o, const char *paper)
{
    if (o->frames > 0)
        return o->frames;
    return !strcmp(paper, "000") ? EVAL_000_FRAMES : !strcmp(paper, "004") ? EVAL_004_FRAMES : EVAL_002_FRAMES;
}

/* Appends one argument (printf-formatted) to step s. */
static void add(struct eval_step *s, const char *fmt, ...)
{
    size_t used = 0;
    for (int i = 0; i < s->argc; i++)
        used += strlen(s->argv[i]) + 1;
    va_list ap;
    va_start(ap, fmt);
    const int len = vsnprintf(s->text + used, sizeof s->text - used, fmt, ap);
    va_end(ap);
    RESTIR_CHECK(len >= 0 && (size_t)len < sizeof s->text - used && s->argc < EVAL_MAX_ARGS);
    s->argv[s->argc++] = s->text + used;
}

/* A new step of paper on scene, with the options every step shares. */
static struct eval_step *begin(struct eval_step *steps, int *n, const char *paper, const char *kind,
                               const char *scene, const char *base, const struct eval_options *o)
{
    RESTIR_CHECK(*n < EVAL_MAX_STEPS);
    struct eval_step *s = &steps[(*n)++];
    memset(s, 0, sizeof *s);
    snprintf(s->paper, sizeof s->paper, "%s", paper);
    snprintf(s->kind, sizeof s->kind, "%s", kind);
    snprintf(s->scene, sizeof s->scene, "%s", scene);
    snprintf(s->base, sizeof s->base, "%s", strcmp(base, "ablation") ? base : "restir-pt");
    snprintf(s->name, sizeof s->name, "%s-%s%s%s", paper, scene, *base ? "-" : "", base);
    add(s, "--scene");
    add(s, "%s", scene);
    add(s, "--res");
    add(s, "%dx%d", o->width, o->height);
    add(s, "--runs");
    add(s, "%d", eval_runs(o, paper));
    add(s, "--ref-spp");
    add(s, "%d", eval_ref_spp(o));
    add(s, "--frames");
    add(s, "%d", eval_frames(o, paper));
    if (o->threads > 0) {
        add(s, "--threads");
        add(s, "%d", o->threads);
    }
    if (o->report)
        add(s, "--report");
    return s;
}

static void set(struct eval_step *s, const char *kv)
{
    add(s, "--set");
    add(s, "%s", kv);
}

const char *const eval_000_configs[] = {"bitterli",
                                        "fast",
                                        "balanced",
                                        "conservative", /* Table 1 */
                                        "compat-r30-k8",
                                        "compat-r30-k128",
                                        "compat-r50-k8",
                                        "compat-r50-k128", /* Table 2's R x K */
                                        "compat-r100-k8",
                                        "compat-r100-k128",
                                        "bitterli-r10",
                                        "bitterli-r50",
                                        "bitterli-r100",
                                        "compat-r10-k32", /* Figure 3's radii */
                                        "spatial-off",
                                        "bitterli-history-temporal",
                                        "fast-history-temporal", /* does spatial reuse itself help? */
                                        NULL};

const char *const eval_004_suffixes[EVAL_004_ROWS] = {
    "", ":spatial.reuse=spmis", ":spatial.reuse=spmis:spmis.search_score=compat",
    /* the rows that decide 004's claims here: the own cell only (does the search cost SPMIS its overall loss?),
     * and the search only where the own cell's confidence is low */
    ":spatial.reuse=spmis:spmis.search_steps=0", ":spatial.reuse=spmis:spmis.search=low-confidence"};

/* Whether name is an item of the comma-separated list. */
static int in_list(const char *list, const char *name)
{
    const size_t n = strlen(name);
    for (const char *p = list; *p;) {
        const char *end = strchr(p, ',');
        const size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == n && !strncmp(p, name, n))
            return 1;
        p += len + (end != NULL);
    }
    return 0;
}

/* Checks --configs: every name one of 000's, and Bitterli's R = 30 (every claim's baseline) among them. */
static int check_configs_000(const struct eval_options *o, char *msg)
{
    if (!o->configs[0])
        return 0;
    char list[sizeof o->configs];
    snprintf(list, sizeof list, "%s", o->configs);
    for (char *save = NULL, *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int known = 0;
        for (int i = 0; eval_000_configs[i] && !known; i++)
            known = !strcmp(eval_000_configs[i], t);
        if (!known) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "--configs: '%.40s' is not one of 000's configurations (restir evaluate --help)", t);
            return -1;
        }
    }
    if (!in_list(o->configs, "bitterli")) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "--configs: 'bitterli' (Bitterli's R = 30) is missing: every 000 claim is "
                 "measured against it");
        return -1;
    }
    return 0;
}

/* 000 Sec. 7: the error-correlation study of ReSTIR PT with M = 1 neighbor, Bitterli's R = 30
 * against FAST / BALANCED / CONSERVATIVE (Table 1); on the first scene also the R x K grid of
 * Table 2 (K = 32 is the presets' row), Figure 3's Pareto curves (Bitterli at R 10, 30, 50,
 * 100; ours at K 32 and R 10 and the presets' 30, 50, 100) and the rows that decide whether
 * spatial reuse itself helps there (no spatial reuse; Bitterli and FAST with the temporal output
 * as history). --configs keeps a subset. */
static void steps_000(const struct eval_options *o, const char *scene, int first, struct eval_step *steps, int *n)
{
    struct eval_step *s = begin(steps, n, "000", "study", scene, "", o);
    s->table2 = first;
    add(s, "--method");
    add(s, "restir-pt");
    add(s, "--warmup");
    add(s, "%d", eval_warmup(o));
    char list[512] = "";
    size_t used = 0;
    for (int i = 0; eval_000_configs[i] && (first || i < EVAL_000_TABLE1_CONFIGS); i++)
        if (!o->configs[0] || in_list(o->configs, eval_000_configs[i]))
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", used ? "," : "", eval_000_configs[i]);
    add(s, "--configs");
    add(s, "%s", list);
    /* 000 Sec. 7's hard pixels: every neighbor within 30 px counts, the sky's included (study's
     * default leaves sky neighbors out) */
    add(s, "--hard-neighbors");
    add(s, "all");
    set(s, "spatial.neighbors=1");
    set(s, "temporal.reuse=splat"); /* 000 Sec. 7: Area ReSTIR's reservoirs with splatting */
}

/* 004 Sec. 6: the last frame of a camera animation; standard reuse (3 neighbors in 30 px, pairwise
 * MIS) against SPMIS (8x8 cells, N = 3, N_c = 1, the 12-tap search from 30 px), SPMIS with our
 * compatibility-scored cell search, with the own cell only, and with the low-confidence search
 * (eval_004_suffixes). ReSTIR PT: 1 initial candidate, 8 bounces, cap 20. The
 * ablation step varies SPMIS alone as Figures 2, 6 and 7 do. */
static void steps_004(const struct eval_options *o, const char *scene, const char *base, int ablation,
                      struct eval_step *steps, int *n)
{
    struct eval_step *s = begin(steps, n, "004", "compare", scene, ablation ? "ablation" : base, o);
    s->ablation = ablation;
    add(s, "--camera");
    add(s, "path");
    add(s, "--methods");
    /* Figure 2 (N / M confidence scaling), Figure 7 (N of M; its N = M, "standard deterministic reuse
     * over the whole tile", needs N_c = M too, or the canonical weight stays stochastic), Figure 6 (N_c) */
    if (ablation)
        add(s,
            "%s:spatial.reuse=spmis,%s:spatial.reuse=spmis:spmis.confidence_adjust=off,"
            "%s:spatial.reuse=spmis:spmis.candidates=1,"
            "%s:spatial.reuse=spmis:spmis.candidates=M:spmis.canonical_candidates=M,"
            "%s:spatial.reuse=spmis:spmis.canonical_candidates=4,%s:spatial.reuse=spmis:spmis.canonical_candidates="
            "M",
            base, base, base, base, base, base);
    else {
        char list[512] = "";
        size_t used = 0;
        for (int k = 0; k < EVAL_004_ROWS; k++)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s%s", k ? "," : "", base,
                                     eval_004_suffixes[k]);
        add(s, "%s", list);
    }
    set(s, "spatial.neighbors=3");
    set(s, "spatial.radius=30");
    set(s, "mis=pairwise");
    set(s, "confidence_cap=20");
    if (!strcmp(base, "restir-pt")) {
        set(s, "pt.candidates=1");
        set(s, "pt.max_bounces=8");
    }
}

/* 002 Sec. 5: equal time at the paper's own cost ratios (30 ms: ours x 1, Gradient after ReSTIR x 2,
 * Area ReSTIR x 4, G-PT at 3 spp), L2 and L1 reconstructions, a moving camera. */
static void steps_002(const struct eval_options *o, const char *scene, struct eval_step *steps, int *n)
{
    struct eval_step *s = begin(steps, n, "002", "compare", scene, "", o);
    add(s, "--camera");
    add(s, "path");
    add(s, "--methods");
    /* the L2 rows first: the report's crops are where the first two (ours and B.1) differ most; B.1
     * once (equal samples, not the paper's equal time) last, so that the paper's rows stay in place
     * (measured: per sample ours is 1.1-2x better, at equal time against two averaged B.1 instances) */
    add(s, "grestir-pt,grad-after-restir:instances=2,area-restir:instances=4,gpt:spp=3,grestir-pt:recon=l1,"
           "grad-after-restir:instances=2:recon=l1,gpt:spp=3:recon=l1,grad-after-restir");
}

static const char *default_scenes(const char *paper)
{
    return !strcmp(paper, "000") ? "forest,ajar" : !strcmp(paper, "004") ? "pillars,forest" : "ajar,cornell";
}

/* Checks that the image holds the disk of the paper's largest pixel radius. */
static int check_res(const struct eval_options *o, const char *paper, int radius, const char *what, char *msg)
{
    const int need = 2 * radius + 1;
    if (o->width >= need && o->height >= need)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN,
             "--res %dx%d is below what %s's radii allow: %s reaches %d pixels, which needs at least %dx%d "
             "(the paper evaluates at %dx%d)",
             o->width, o->height, paper, what, radius, need, need, EVAL_PAPER_WIDTH, EVAL_PAPER_HEIGHT);
    return -1;
}

static int paper_steps(const struct eval_options *o, const char *paper, struct eval_step *steps, int *n, char *msg)
{
    int rc = !strcmp(paper, "000") ? check_res(o, paper, EVAL_000_RADIUS, "CONSERVATIVE (R = 100)", msg)
             : !strcmp(paper, "004")
                 ? check_res(o, paper, EVAL_004_RADIUS, "the 30-pixel reuse and cell search", msg)
                 : check_res(o, paper, EVAL_002_RADIUS, "area ReSTIR's 30-pixel reuse", msg);
    if (rc != 0 || (!strcmp(paper, "000") && check_configs_000(o, msg) != 0))
        return -1;
    char list[256], first_scene[32] = "";
    snprintf(list, sizeof list, "%s", o->scenes[0] ? o->scenes : default_scenes(paper));
    int first = 1;
    for (char *save = NULL, *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save), first = 0) {
        if (*n + 3 > EVAL_MAX_STEPS) {
            snprintf(msg, RESTIR_MSG_LEN, "--scenes: more than %d steps in all", EVAL_MAX_STEPS);
            return -1;
        }
        int known = 0;
        for (int i = 0; scene_builtin_names[i] && !known; i++)
            known = !strcmp(scene_builtin_names[i], t);
        if (!known) {
            snprintf(msg, RESTIR_MSG_LEN, "--scenes: '%.40s' is not a built-in scene name (see restir list)", t);
            return -1;
        }
        if (first)
            snprintf(first_scene, sizeof first_scene, "%s", t);
        if (!strcmp(paper, "000"))
            steps_000(o, t, first, steps, n);
        else if (!strcmp(paper, "004")) {
            steps_004(o, t, "restir-pt", 0, steps, n);
            steps_004(o, t, "restir-di", 0, steps, n);
        } else
            steps_002(o, t, steps, n);
    }
    if (!strcmp(paper, "004")) /* the ablations on the first scene, after the main table's steps */
        steps_004(o, first_scene, "restir-pt", 1, steps, n);
    return 0;
}

int eval_steps(const struct eval_options *o, struct eval_step *steps, int *n, char *msg)
{
    *n = 0;
    static const char *const papers[] = {"000", "004", "002"};
    int any = 0;
    for (int i = 0; i < 3; i++)
        if (!strcmp(o->paper, papers[i]) || !strcmp(o->paper, "all")) {
            any = 1;
            if (paper_steps(o, papers[i], steps, n, msg) != 0)
                return -1;
        }
    if (!any) {
        snprintf(msg, RESTIR_MSG_LEN, "unknown paper '%.40s' (000, 004, 002 or all)", o->paper);
        return -1;
    }
    return 0;
}
