/* evaluate_papers.c: each paper's evaluation as study / compare commands, planned from its recipe
 * (evaluate_papers.h; the recipes are evaluate_recipes.c). Must never run a command or read results. */
#include "experiments/evaluate_papers.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "scene/scenes_builtin.h"

#define EVAL_RUNS 4        /* an unknown paper's runs per configuration (no step is planned for one) */
#define EVAL_FRAMES 16     /* and its measured frames */
#define EVAL_REF_SPP 1024  /* paths per pixel of each comparison's reference */

const struct eval_paper *eval_paper_find(const char *id)
{
    for (int i = 0; id && eval_papers[i]; i++)
        if (!strcmp(eval_papers[i]->id, id))
            return eval_papers[i];
    return NULL;
}

int eval_runs(const struct eval_options *o, const char *paper)
{
    const struct eval_paper *p = eval_paper_find(paper);
    return o->runs > 0 ? o->runs : p ? p->runs : EVAL_RUNS;
}

int eval_ref_spp(const struct eval_options *o)
{
    return o->ref_spp > 0 ? o->ref_spp : EVAL_REF_SPP;
}

int eval_warmup(const struct eval_options *o, const char *paper)
{
    const struct eval_paper *p = eval_paper_find(paper);
    return o->warmup > 0 ? o->warmup : p ? p->warmup : 0;
}

int eval_frames(const struct eval_options *o, const char *paper)
{
    const struct eval_paper *p = eval_paper_find(paper);
    return o->frames > 0 ? o->frames : p ? p->frames : EVAL_FRAMES;
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

/* A new step of paper's recipe r on scene, with the options every step shares. */
static struct eval_step *begin(struct eval_step *steps, int *n, const struct eval_paper *paper,
                               const struct eval_step_recipe *r, const char *scene, const struct eval_options *o)
{
    RESTIR_CHECK(*n < EVAL_MAX_STEPS);
    struct eval_step *s = &steps[(*n)++];
    memset(s, 0, sizeof *s);
    s->recipe = paper;
    s->step_recipe = r;
    snprintf(s->paper, sizeof s->paper, "%s", paper->id);
    snprintf(s->kind, sizeof s->kind, "%s", r->kind);
    snprintf(s->scene, sizeof s->scene, "%s", scene);
    snprintf(s->base, sizeof s->base, "%s", r->base);
    snprintf(s->name, sizeof s->name, "%s-%s%s%s", paper->id, scene, *r->folder ? "-" : "", r->folder);
    add(s, "--scene");
    add(s, "%s", scene);
    add(s, "--res");
    add(s, "%dx%d", o->width, o->height);
    add(s, "--runs");
    add(s, "%d", eval_runs(o, paper->id));
    add(s, "--ref-spp");
    add(s, "%d", eval_ref_spp(o));
    add(s, "--frames");
    add(s, "%d", eval_frames(o, paper->id));
    if (o->threads > 0) {
        add(s, "--threads");
        add(s, "%d", o->threads);
    }
    if (o->report)
        add(s, "--report");
    return s;
}

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

/* Checks --configs: every name one of the paper's configurations, and its baseline among them. */
static int check_configs(const struct eval_options *o, const struct eval_paper *p, char *msg)
{
    if (!o->configs[0] || !p->configs)
        return 0;
    char list[sizeof o->configs];
    snprintf(list, sizeof list, "%s", o->configs);
    for (char *save = NULL, *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int known = 0;
        for (int i = 0; p->configs[i] && !known; i++)
            known = !strcmp(p->configs[i], t);
        if (!known) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "--configs: '%.40s' is not one of %s's configurations (restir evaluate --help)", t, p->id);
            return -1;
        }
    }
    if (!in_list(o->configs, p->baseline)) {
        snprintf(msg, RESTIR_MSG_LEN, "--configs: '%s' %s", p->baseline, p->baseline_why);
        return -1;
    }
    return 0;
}

/* Step r of paper p on scene (first: the first of the evaluation's scenes): the options every step
 * shares, then what r gives, in the order struct eval_step_recipe states. */
static void plan_step(const struct eval_options *o, const struct eval_paper *p, const struct eval_step_recipe *r,
                      const char *scene, int first, struct eval_step *steps, int *n)
{
    struct eval_step *s = begin(steps, n, p, r, scene, o);
    if (!p->warmup) {
        add(s, "--camera");
        add(s, "path");
    }
    if (r->method) {
        add(s, "--method");
        add(s, "%s", r->method);
    }
    if (r->configs) {
        s->all_configs = first;
        add(s, "--warmup");
        add(s, "%d", eval_warmup(o, p->id));
        char list[512] = "";
        size_t used = 0;
        for (int i = 0; p->configs[i] && (first || i < p->configs_every_scene); i++)
            if (!o->configs[0] || in_list(o->configs, p->configs[i]))
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", used ? "," : "", p->configs[i]);
        add(s, "--configs");
        add(s, "%s", list);
    }
    if (r->nvariants > 0) {
        char list[1024] = "";
        size_t used = 0;
        for (int k = 0; k < r->nvariants; k++) {
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s%s", k ? "," : "", r->base,
                                     r->variants[k].spec);
            RESTIR_CHECK(used < sizeof list);
        }
        add(s, "--methods");
        add(s, "%s", list);
    }
    for (int i = 0; r->extra && r->extra[i]; i++)
        add(s, "%s", r->extra[i]);
    for (int i = 0; r->settings && r->settings[i]; i++) {
        add(s, "--set");
        add(s, "%s", r->settings[i]);
    }
}

/* Checks that the image holds the disk of the paper's largest pixel radius. */
static int check_res(const struct eval_options *o, const struct eval_paper *p, char *msg)
{
    const int need = 2 * p->radius + 1;
    if (o->width >= need && o->height >= need)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN,
             "--res %dx%d is below what %s's radii allow: %s reaches %d pixels, which needs at least %dx%d "
             "(the paper evaluates at %dx%d)",
             o->width, o->height, p->id, p->radius_what, p->radius, need, need, EVAL_PAPER_WIDTH, EVAL_PAPER_HEIGHT);
    return -1;
}

/* The most steps any paper plans per scene: the room --scenes must leave for each scene. */
static int most_steps_per_scene(void)
{
    int most = 0;
    for (int i = 0; eval_papers[i]; i++)
        most = eval_papers[i]->nsteps > most ? eval_papers[i]->nsteps : most;
    return most;
}

static int paper_steps(const struct eval_options *o, const struct eval_paper *p, struct eval_step *steps, int *n,
                       char *msg)
{
    if (check_res(o, p, msg) != 0 || check_configs(o, p, msg) != 0)
        return -1;
    char list[256], first_scene[32] = "";
    snprintf(list, sizeof list, "%s", o->scenes[0] ? o->scenes : p->default_scenes);
    int first = 1;
    for (char *save = NULL, *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save), first = 0) {
        if (*n + most_steps_per_scene() > EVAL_MAX_STEPS) {
            snprintf(msg, RESTIR_MSG_LEN, "--scenes: more than %d steps in all", EVAL_MAX_STEPS);
            return -1;
        }
        int known = 0;
        for (int i = 0; scene_builtins[i].name && !known; i++)
            known = !strcmp(scene_builtins[i].name, t);
        if (!known) {
            snprintf(msg, RESTIR_MSG_LEN, "--scenes: '%.40s' is not a built-in scene name (see restir list)", t);
            return -1;
        }
        if (first)
            snprintf(first_scene, sizeof first_scene, "%s", t);
        for (int k = 0; k < p->nsteps; k++)
            if (!p->steps[k].first_scene_only)
                plan_step(o, p, &p->steps[k], t, first, steps, n);
    }
    for (int k = 0; k < p->nsteps; k++) /* e.g. 004's ablations, after the main table's steps */
        if (p->steps[k].first_scene_only)
            plan_step(o, p, &p->steps[k], first_scene, 1, steps, n);
    return 0;
}

int eval_steps(const struct eval_options *o, struct eval_step *steps, int *n, char *msg)
{
    *n = 0;
    const int all = !strcmp(o->paper, "all");
    int any = 0;
    for (int i = 0; eval_papers[i]; i++)
        if (all || !strcmp(o->paper, eval_papers[i]->id)) {
            any = 1;
            if (paper_steps(o, eval_papers[i], steps, n, msg) != 0)
                return -1;
        }
    if (!any) {
        snprintf(msg, RESTIR_MSG_LEN, "unknown paper '%.40s' (000, 004, 002 or all)", o->paper);
        return -1;
    }
    return 0;
}
