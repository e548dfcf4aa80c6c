/* options.c: the table of command-line options (one row per option and command: kind, range,
 * default, help), and what reads it: parsing into struct cli_options with the error naming the
 * offending option, each command's --help options, and the JSON descriptions that plans store.
 * Must never run a render. */
#include "experiments/options.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/settings_file.h"
#include "methods/settings.h"

static int need_value(int i, int argc, char **argv, char *msg)
{
    if (i + 1 >= argc) {
        snprintf(msg, RESTIR_MSG_LEN, "option %s needs a value", argv[i]);
        return -1;
    }
    return 0;
}

/* summary.json's run description: the keys `restir render` takes as options of their own. */
static int apply_run_description(const char *path, const cJSON *root, struct cli_options *o, char *msg)
{
    const cJSON *v;
    char why[RESTIR_MSG_LEN];
    long long n;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "scene")) && cJSON_IsString(v)) {
        snprintf(o->params_scene, sizeof(o->params_scene), "%s", v->valuestring);
        o->scene = o->params_scene;
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "method")) && cJSON_IsString(v)) {
        snprintf(o->params_method, sizeof(o->params_method), "%s", v->valuestring);
        o->method = o->params_method;
    }
    const char *ints[] = {"width", "height", "frames", "seed"};
    const long long lo[] = {1, 1, 1, 0}, hi[] = {16384, 16384, 100000, 1ll << 62};
    for (int k = 0; k < 4; k++) {
        if (!(v = cJSON_GetObjectItemCaseSensitive(root, ints[k])))
            continue;
        char text[64] = "";
        if (cJSON_IsNumber(v))
            snprintf(text, sizeof(text), "%.17g", v->valuedouble);
        else if (cJSON_IsString(v)) /* seeds above 2^53 are written as strings */
            snprintf(text, sizeof(text), "%.60s", v->valuestring);
        if (cli_parse_int(ints[k], text, lo[k], hi[k], &n, why) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "--params %.250s: %.250s", path, why);
            return -1;
        }
        if (k == 0)
            o->params.width = (int)n;
        else if (k == 1)
            o->params.height = (int)n;
        else if (k == 2) {
            o->frames = (int)n;
            o->frames_given = 1;
        } else
            o->params.seed = (uint64_t)n;
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "env")) && cJSON_IsString(v)) {
        snprintf(o->params_env, sizeof(o->params_env), "%s", v->valuestring);
        o->env = o->params_env;
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "camera")) && cJSON_IsString(v)) {
        if (!strcmp(v->valuestring, "static") || !strcmp(v->valuestring, "path")) {
            o->params.camera_path = !strcmp(v->valuestring, "path");
            o->camera_file = NULL;
        } else {
            snprintf(o->params_camera, sizeof(o->params_camera), "%s", v->valuestring);
            o->camera_file = o->params_camera;
        }
    }
    return 0;
}

/* --params FILE: a summary.json (its run description and "settings") or a plain object of --set
 * keys. */
static int apply_params_file(const char *path, struct cli_options *o, char *msg)
{
    cJSON *root = settings_read_file(path, msg);
    if (!root)
        return -1;
    const cJSON *settings = cJSON_GetObjectItemCaseSensitive(root, "settings");
    int rc = 0;
    if (settings && !cJSON_IsObject(settings)) {
        snprintf(msg, RESTIR_MSG_LEN, "--params %.300s: \"settings\" must be an object", path);
        rc = -1;
    } else if (settings) {
        rc = apply_run_description(path, root, o, msg);
        if (rc == 0)
            rc = settings_apply_object(path, settings, &o->params, msg);
    } else {
        rc = settings_apply_object(path, root, &o->params, msg);
    }
    cJSON_Delete(root);
    return rc;
}

/* How an option's value is read. */
enum opt_kind {
    OPT_FLAG,     /* no value: the int field becomes 1 */
    OPT_TEXT,     /* a string kept as given */
    OPT_INT,      /* an int in [lo, hi] */
    OPT_LLONG,    /* a long long in [lo, hi] */
    OPT_U64,      /* a uint64_t in [lo, hi] */
    OPT_SECONDS,  /* a double in [lo, hi] */
    OPT_POSITIVE, /* a double in (0, hi] */
    OPT_RES,      /* WxH into params.width, params.height */
    OPT_CAMERA,   /* static | path, or (render) a camera file */
    OPT_NAMES,    /* one of names[]: the int field gets its index */
    OPT_SET,      /* key=value of the settings table (params.c) */
    OPT_SETTING,  /* the value of the setting named as the option (--denoise X is --set denoise=X) */
    OPT_PARAMS,   /* a summary.json or settings file */
};

/* One row per option and command: everything about it is said here, once. commands lists the
 * subcommands that read it (" render compare "; "scene info" and "scene export" are the two forms
 * of `restir scene` that take options), ALL: every one but evaluate. Each command accepts only the
 * options it reads; rows of one option differ in range, default or help. The first row that matches
 * wins. def is the default as the option would spell it (NULL: the field's zero, or what
 * cli_parse_options sets before the table). */
struct opt_def {
    const char *name;
    const char *commands;
    enum opt_kind kind;
    size_t offset;
    long long lo, hi;
    size_t given;    /* offset of an int set to 1 when the option is given, or NO_GIVEN */
    const char *def;
    const char *arg; /* the value's placeholder in --help */
    const char *help;
    const char *const *names; /* OPT_NAMES */
};

#define O(field) offsetof(struct cli_options, field)
#define NO_GIVEN ((size_t)-1)
#define ALL NULL /* every command but evaluate: --help, -h, --env and --set only */
#define EVAL " evaluate "
#define RENDERING " render reference compare study view " /* the commands that render a scene */
#define PLANNED " reference compare study "              /* the commands that --plan splits into jobs */

/* The commands that read options through the table, in the order messages name them. */
static const char *const table_commands[] = {"render",     "reference",    "compare",  "study", "view",
                                             "scene info", "scene export", "evaluate", NULL};

static const char *const save_names[] = {"last", "all", NULL};
static const char *const hard_neighbor_names[] = {"valid", "all", NULL}; /* enum restir_hard_neighbors */

static const struct opt_def option_table[] = {
    /* evaluate's own: zero means the paper's value (its recipe, evaluate_recipes.c) */
    {"--runs", EVAL, OPT_INT, O(runs), 2, 64, NO_GIVEN, NULL, "N", "independently seeded runs per configuration [4]",
     NULL},
    {"--frames", EVAL, OPT_INT, O(frames), 4, 100000, O(frames_given), NULL, "N",
     "measured frames instead of the paper's (000: 16 after the warm-up; 004: 50; 002: 16)", NULL},
    {"--warmup", EVAL, OPT_INT, O(warmup), 1, 100000, NO_GIVEN, NULL, "N", "000: warm-up frames instead of 40", NULL},
    {"--ref-spp", EVAL, OPT_INT, O(ref_spp), 1, 1 << 24, NO_GIVEN, NULL, "N",
     "reference paths per pixel instead of 1024", NULL},
    {"--threads", EVAL, OPT_INT, O(params.threads), 1, 4096, NO_GIVEN, NULL, "N", "threads per job [every core]", NULL},
    {"--scenes", EVAL, OPT_TEXT, O(scenes), 0, 0, NO_GIVEN, NULL, "LIST", "scenes instead of each paper's", NULL},
    {"--configs", EVAL, OPT_TEXT, O(configs), 0, 0, NO_GIVEN, NULL, "LIST", "000: a subset of its configurations",
     NULL},
    {"--res", EVAL, OPT_RES, 0, 0, 0, O(res_given), NULL, "WxH", "image size [1920x1080, the papers']", NULL},
    {"--out", EVAL, OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "DIR", "plan, run every job not yet done, and merge", NULL},
    {"--plan", EVAL, OPT_TEXT, O(plan), 0, 0, NO_GIVEN, NULL, "DIR", "write the plan only", NULL},
    {"--report", EVAL, OPT_FLAG, O(report), 0, 0, NO_GIVEN, NULL, "", "also write the steps' pages and index.html",
     NULL},
    {"--check", EVAL, OPT_TEXT, O(check), 0, 0, NO_GIVEN, NULL, "DIR",
     "render every row of the steps under DIR tiny with its recorded settings: exit 1 when one renders differently",
     NULL},
    {"--tables", EVAL, OPT_TEXT, O(tables), 0, 0, NO_GIVEN, NULL, "DIR",
     "write DIR/evaluation.md and claims.csv again from the steps' CSV and provenance files alone", NULL},
    {"--partial", EVAL, OPT_FLAG, O(partial), 0, 0, NO_GIVEN, NULL, "", "--tables: name the steps without tables",
     NULL},
    {"--help", EVAL, OPT_FLAG, O(help), 0, 0, NO_GIVEN, NULL, "", "print this help", NULL},
    {"-h", EVAL, OPT_FLAG, O(help), 0, 0, NO_GIVEN, NULL, "", "the same", NULL},
    /* every other command's */
    {"--help", ALL, OPT_FLAG, O(help), 0, 0, NO_GIVEN, NULL, "", "print this help", NULL},
    {"-h", ALL, OPT_FLAG, O(help), 0, 0, NO_GIVEN, NULL, "", "the same", NULL},
    {"--scene", RENDERING, OPT_TEXT, O(scene), 0, 0, NO_GIVEN, "many-lights", "NAME|FILE",
     "a built-in scene (restir list) or a scene file (JSON, glTF, OBJ, ...)", NULL},
    {"--method", " render view ", OPT_TEXT, O(method), 0, 0, NO_GIVEN, NULL, "NAME",
     "a registered method (restir list)", NULL},
    {"--method", " reference ", OPT_TEXT, O(method), 0, 0, NO_GIVEN, NULL, "NAME",
     "the method whose integrand the reference converges to (restir list)", NULL},
    {"--method", " study ", OPT_TEXT, O(method), 0, 0, NO_GIVEN, NULL, "NAME",
     "a method with spatial reuse from the selection pass (restir list)", NULL},
    {"--methods", " compare ", OPT_TEXT, O(methods), 0, 0, NO_GIVEN, NULL, "SPEC,SPEC,...",
     "methods with their settings: name[:key=value]...", NULL},
    {"--ref", " render compare study ", OPT_TEXT, O(ref), 0, 0, NO_GIVEN, NULL, "FILE.exr",
     "the reference image to measure against", NULL},
    {"--out", " render ", OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "DIR", "output folder [out/SCENE-METHOD]", NULL},
    {"--out", " reference ", OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "FILE.exr", "the reference image written", NULL},
    {"--out", " compare ", OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "DIR", "output folder [out/compare-SCENE]", NULL},
    {"--out", " study ", OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "DIR", "output folder", NULL},
    {"--out", " view ", OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "DIR", "folder of screenshots and camera.json "
     "[out/view-SCENE]", NULL},
    {"--out", " scene export ", OPT_TEXT, O(out), 0, 0, NO_GIVEN, NULL, "DIR", "folder of the exported file", NULL},
    {"--env", ALL, OPT_TEXT, O(env), 0, 0, NO_GIVEN, NULL, "FILE|none",
     "an environment light replacing the scene's own (none: remove it)", NULL},
    {"--script", " view ", OPT_TEXT, O(script), 0, 0, NO_GIVEN, NULL, "FILE", "timed input events", NULL},
    {"--res", " study ", OPT_RES, 0, 0, 0, O(res_given), "320x180", "WxH", "image size in pixels", NULL},
    {"--res", RENDERING, OPT_RES, 0, 0, 0, O(res_given), "640x360", "WxH", "image size in pixels", NULL},
    {"--frames", " study ", OPT_INT, O(frames), 1, 100000, O(frames_given), "16", "N",
     "frames per run (measured after the warm-up)", NULL},
    {"--frames", " compare ", OPT_INT, O(frames), 1, 100000, O(frames_given), "1", "N",
     "frames per run (the last is measured)", NULL},
    {"--frames", " render ", OPT_INT, O(frames), 1, 100000, O(frames_given), "1", "N", "frames to render", NULL},
    {"--frame", " reference ", OPT_INT, O(frame), 0, 100000, NO_GIVEN, NULL, "F", "the camera of frame F", NULL},
    {"--spp", " reference ", OPT_INT, O(params.spp), 1, 1 << 20, O(spp_given), NULL, "N",
     "paths per pixel (with --target-relmse: the most) [1024]", NULL},
    {"--spp", " render compare view ", OPT_INT, O(params.spp), 1, 1 << 20, O(spp_given), NULL, "N",
     "paths per pixel of the methods that read spp (restir render --help names them; the others render 1 "
     "per frame) [1]", NULL},
    {"--ref-spp", " compare study ", OPT_INT, O(ref_spp), 1, 1 << 20, NO_GIVEN, "1024", "N",
     "paths per pixel of a reference rendered when --ref is absent", NULL},
    {"--seed", RENDERING, OPT_U64, O(params.seed), 0, 1ll << 62, NO_GIVEN, NULL, "N", "the seed of every random stream",
     NULL},
    {"--max-memory", RENDERING, OPT_LLONG, O(max_memory_mb), 1, 1ll << 40, NO_GIVEN, NULL, "MB",
     "refuse a renderer estimated above this (default: the memory the system has)", NULL},
    {"--threads", RENDERING, OPT_INT, O(params.threads), 0, 1024, NO_GIVEN, "0", "N", "threads (0: every core)", NULL},
    {"--camera", " render ", OPT_CAMERA, 0, 0, 0, NO_GIVEN, "static", "static|path|FILE",
     "a still camera, the scene's camera path, or a camera file of one camera per frame (restir view records them)",
     NULL},
    {"--camera", " reference compare ", OPT_CAMERA, 0, 0, 0, NO_GIVEN, "static", "static|path",
     "a still camera or the scene's camera path", NULL},
    {"--save", " render ", OPT_NAMES, O(save_all), 0, 0, NO_GIVEN, "all", "all|last", "write every frame or the last",
     save_names},
    {"--configs", " study ", OPT_TEXT, O(configs), 0, 0, NO_GIVEN, NULL, "LIST", "configurations to run", NULL},
    {"--radii", " study ", OPT_TEXT, O(radii), 0, 0, NO_GIVEN, NULL, "LIST", "radii of the radius sweep", NULL},
    {"--runs", " compare ", OPT_INT, O(runs), 1, 100000, NO_GIVEN, "1", "N", "independently seeded runs per spec",
     NULL},
    {"--runs", " study ", OPT_INT, O(runs), 2, 100000, NO_GIVEN, "8", "N",
     "independently seeded runs per configuration", NULL},
    {"--ref-every", " compare ", OPT_INT, O(ref_every), 1, 100000, NO_GIVEN, NULL, "K",
     "also measure frames K-1, 2K-1, ... against references of their own", NULL},
    {"--warmup", " study ", OPT_INT, O(warmup), 0, 100000, NO_GIVEN, "40", "N", "frames before measuring (000 Sec. 7)",
     NULL},
    {"--hard-neighbors", " study ", OPT_NAMES, O(hard_neighbors), 0, 0, NO_GIVEN, "valid", "valid|all",
     "the neighbors 000's hard-pixel ratio counts within 30 px: valid (pixels with a surface) or all "
     "(000 Sec. 7's wording: the sky counts as failing Eq. 7, so leaves against it are hard)",
     hard_neighbor_names},
    {"--checkpoint-every", " reference ", OPT_SECONDS, O(checkpoint_every), 0, 10000000, NO_GIVEN, NULL, "SECONDS",
     "save the running mean this often (0: after every chunk; default: never)", NULL},
    {"--target-relmse", " reference ", OPT_POSITIVE, O(target_relmse), 0, 1, NO_GIVEN, NULL, "X",
     "stop once the image's estimated relMSE is at most X (--spp: the most samples; default 65536)", NULL},
    {"--plan", PLANNED, OPT_TEXT, O(plan), 0, 0, NO_GIVEN, NULL, "DIR",
     "write the work as independent jobs into DIR instead of running it", NULL},
    {"--merge", PLANNED, OPT_TEXT, O(merge), 0, 0, NO_GIVEN, NULL, "DIR", "merge the finished jobs of plan DIR", NULL},
    {"--shards", " reference ", OPT_INT, O(shards), 1, 4096, NO_GIVEN, NULL, "N",
     "with --plan: jobs the samples are split into", NULL},
    {"--params", " render ", OPT_PARAMS, 0, 0, 0, NO_GIVEN, NULL, "FILE",
     "a summary.json (runs it again) or a JSON object of --set keys", NULL},
    {"--denoise", " render compare study view ", OPT_SETTING, 0, 0, 0, NO_GIVEN, NULL, "off|svgf|atrous",
     "denoise each frame into a layer of its own, BIASED by nature (--set denoise=...; see denoise.* there)", NULL},
    {"--set", ALL, OPT_SET, 0, 0, 0, NO_GIVEN, NULL, "key=value", "one setting (restir render --help lists them)",
     NULL},
    {"--equal-time", " compare ", OPT_FLAG, O(equal_time), 0, 0, NO_GIVEN, NULL, "",
     "give every method the first stateful method's time per frame", NULL},
    {"--report", " compare study ", OPT_FLAG, O(report), 0, 0, NO_GIVEN, NULL, "",
     "also write DIR/index.html, a page that loads the PNGs beside it", NULL},
    {"--self-contained", " compare study ", OPT_FLAG, O(self_contained), 0, 0, NO_GIVEN, NULL, "",
     "with --report: every image inside index.html (base64), so the one file holds everything", NULL},
    /* one run per folder (out_dir.h): what to do when --out (--plan) already holds something */
    {"--force", " render compare study view scene export ", OPT_FLAG, O(force), 0, 0, NO_GIVEN, NULL, "",
     "empty a non-empty --out DIR first (study, compare: or --plan DIR): only a folder restir wrote, never /, "
     "$HOME or .",
     NULL},
    {"--force", " reference ", OPT_FLAG, O(force), 0, 0, NO_GIVEN, NULL, "",
     "replace an existing --out FILE.exr; start over from a checkpoint that cannot be continued", NULL},
    {"--force", EVAL, OPT_FLAG, O(force), 0, 0, NO_GIVEN, NULL, "",
     "empty a non-empty DIR first and start over (only a folder restir wrote)", NULL},
    {"--resume", " reference ", OPT_FLAG, O(resume), 0, 0, NO_GIVEN, NULL, "",
     "continue FILE.checkpoint.exr (as the same command does anyway); exit 2 when there is none", NULL},
    {"--resume", EVAL, OPT_FLAG, O(resume), 0, 0, NO_GIVEN, NULL, "",
     "continue this evaluation in DIR (as the same command does anyway); exit 2 when DIR holds none", NULL},
};

/* Whether row d applies to `command`. */
static int opt_applies(const struct opt_def *d, const char *command)
{
    char padded[64];
    snprintf(padded, sizeof padded, " %s ", command);
    if (!d->commands)
        return strcmp(command, "evaluate") != 0;
    return strstr(d->commands, padded) != NULL;
}

/* The first row named `name` that applies to `command`, or NULL. *known says whether some row is
 * named so at all (another command's option). */
static const struct opt_def *opt_find(const char *command, const char *name, int *known)
{
    *known = 0;
    for (size_t k = 0; k < sizeof option_table / sizeof option_table[0]; k++) {
        const struct opt_def *d = &option_table[k];
        if (strcmp(d->name, name) != 0)
            continue;
        *known = 1;
        if (opt_applies(d, command))
            return d;
    }
    return NULL;
}

/* The JSON key of an option: its name without the leading dashes. */
static const char *opt_key(const char *name) { return name + (name[1] == '-' ? 2 : 1); }

/* The option of `command` nearest to `name` by edit distance when it is close (one edit, two for
 * names of 6 characters or more; a wrong name, not a short different one), else NULL. */
static const char *opt_nearest(const char *command, const char *name)
{
    const char *key = opt_key(name), *best = NULL;
    const int len = (int)strlen(key), most = len >= 6 ? 2 : 1;
    int best_d = most + 1, known;
    for (size_t k = 0; k < sizeof option_table / sizeof option_table[0]; k++) {
        const struct opt_def *d = &option_table[k];
        if (d->name[1] != '-' || opt_find(command, d->name, &known) != d)
            continue;
        const int dist = cli_edit_distance(key, opt_key(d->name));
        if (dist < best_d && dist < len) {
            best_d = dist;
            best = d->name;
        }
    }
    return best;
}

/* msg for `name`, which `command` does not read: the commands that do (an option of another
 * command is refused, not ignored), and the nearest option of this one. */
static void opt_refusal(const char *command, const char *name, char *msg)
{
    char owners[256] = "", hint[96] = "";
    size_t used = 0;
    int known;
    for (int c = 0; table_commands[c]; c++)
        if (opt_find(table_commands[c], name, &known) && used < sizeof owners)
            used += (size_t)snprintf(owners + used, sizeof owners - used, "%s%s", used ? ", " : "",
                                     table_commands[c]);
    const char *near = opt_nearest(command, name);
    if (near)
        snprintf(hint, sizeof hint, "; did you mean %s?", near);
    if (owners[0])
        snprintf(msg, RESTIR_MSG_LEN, "%s: option '%.60s' is not read by %s (it is an option of: %s)%s", command,
                 name, command, owners, hint);
    else
        snprintf(msg, RESTIR_MSG_LEN, "%s: unknown option '%.100s'%s", command, name, hint);
}

/* Applies value val of row d to o. Returns 0, or -1 with msg. */
static int opt_apply(const struct opt_def *d, const char *command, const char *val, struct cli_options *o, char *msg)
{
    char *base = (char *)o;
    long long v;
    switch (d->kind) {
    case OPT_FLAG:
        *(int *)(base + d->offset) = 1;
        break;
    case OPT_TEXT:
        *(const char **)(base + d->offset) = val;
        break;
    case OPT_INT:
    case OPT_LLONG:
    case OPT_U64:
        if (cli_parse_int(d->name, val, d->lo, d->hi, &v, msg) != 0)
            return -1;
        if (d->kind == OPT_INT)
            *(int *)(base + d->offset) = (int)v;
        else if (d->kind == OPT_LLONG)
            *(long long *)(base + d->offset) = v;
        else
            *(uint64_t *)(base + d->offset) = (uint64_t)v;
        break;
    case OPT_SECONDS: {
        char *end = NULL;
        errno = 0;
        double s = strtod(val, &end);
        if (end == val || *end != '\0' || errno != 0 || !(s >= (double)d->lo && s <= (double)d->hi)) {
            snprintf(msg, RESTIR_MSG_LEN, "%s expects seconds in [%lld, %g], got '%s'", d->name, d->lo, (double)d->hi,
                     val);
            return -1;
        }
        *(double *)(base + d->offset) = s;
        break;
    }
    case OPT_POSITIVE: {
        char *end = NULL;
        errno = 0;
        double x = strtod(val, &end);
        if (end == val || *end != '\0' || errno != 0 || !(x > 0.0 && x <= (double)d->hi)) {
            snprintf(msg, RESTIR_MSG_LEN, "%s expects a number in (0, %g], got '%s'", d->name, (double)d->hi, val);
            return -1;
        }
        *(double *)(base + d->offset) = x;
        break;
    }
    case OPT_RES:
        if (cli_parse_res(val, &o->params.width, &o->params.height, msg) != 0)
            return -1;
        break;
    case OPT_CAMERA:
        if (!strcmp(val, "static"))
            o->params.camera_path = 0;
        else if (!strcmp(val, "path"))
            o->params.camera_path = 1;
        else if (!strcmp(command, "render"))
            o->camera_file = val; /* a camera file: one camera per frame */
        else {
            snprintf(msg, RESTIR_MSG_LEN, "--camera expects static or path, got '%s'", val);
            return -1;
        }
        break;
    case OPT_NAMES: {
        int k = 0;
        while (d->names[k] && strcmp(d->names[k], val) != 0)
            k++;
        if (!d->names[k]) {
            snprintf(msg, RESTIR_MSG_LEN, "%s expects %s, got '%s'", d->name, d->arg, val);
            return -1;
        }
        *(int *)(base + d->offset) = k;
        break;
    }
    case OPT_SETTING: {
        if (o->n_setting_texts == CLI_MAX_SETTING_TEXTS) {
            snprintf(msg, RESTIR_MSG_LEN, "%s given more than %d times", d->name, CLI_MAX_SETTING_TEXTS);
            return -1;
        }
        char *text = o->setting_texts[o->n_setting_texts++];
        snprintf(text, sizeof o->setting_texts[0], "%s=%s", opt_key(d->name), val);
        return opt_apply(&(struct opt_def){"--set", NULL, OPT_SET, 0, 0, 0, NO_GIVEN, NULL, "", "", NULL}, command,
                         text, o, msg);
    }
    case OPT_SET:
        if (o->n_sets == CLI_MAX_SETS) {
            snprintf(msg, RESTIR_MSG_LEN, "more than %d --set options", CLI_MAX_SETS);
            return -1;
        }
        o->sets[o->n_sets++] = val;
        return render_params_set(&o->params, val, msg);
    case OPT_PARAMS:
        return apply_params_file(val, o, msg);
    }
    if (d->given != NO_GIVEN)
        *(int *)(base + d->given) = 1;
    return 0;
}

void cli_options_defaults(const char *command, struct cli_options *o)
{
    memset(o, 0, sizeof(*o));
    render_params_defaults(&o->params);
    o->checkpoint_every = -1.0;
    char msg[RESTIR_MSG_LEN];
    for (size_t k = 0; k < sizeof option_table / sizeof option_table[0]; k++) {
        const struct opt_def *d = &option_table[k];
        int known;
        if (!d->def || opt_find(command, d->name, &known) != d || d->kind == OPT_RES || d->kind == OPT_CAMERA)
            continue; /* the settings table's own defaults hold for --res and --camera */
        const size_t given = d->given;
        RESTIR_CHECK(opt_apply(d, command, d->def, o, msg) == 0);
        if (given != NO_GIVEN)
            *(int *)((char *)o + given) = 0; /* a default is not given */
    }
}

int cli_parse_options(const char *command, int argc, char **argv, struct cli_options *o, char *msg)
{
    cli_options_defaults(command, o);
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strncmp(a, "--", 2) != 0 && strcmp(a, "-h") != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "%s: unexpected argument '%s'", command, a);
            return -1;
        }
        int known;
        const struct opt_def *d = opt_find(command, a, &known);
        if (!d) {
            opt_refusal(command, a, msg);
            return -1;
        }
        if (d->kind != OPT_FLAG && need_value(i, argc, argv, msg) != 0)
            return -1;
        const char *val = d->kind == OPT_FLAG ? NULL : argv[++i];
        if (opt_apply(d, command, val, o, msg) != 0)
            return -1;
    }
    if (o->self_contained && !o->report) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: --self-contained is an option of --report (add --report)", command);
        return -1;
    }
    return render_params_validate(&o->params, msg);
}

int cli_option_takes_value(const char *command, const char *name)
{
    int known;
    const struct opt_def *d = opt_find(command, name, &known);
    for (size_t k = 0; !d && known && k < sizeof option_table / sizeof option_table[0]; k++)
        if (!strcmp(option_table[k].name, name)) /* another command's: its value goes with it to the refusal */
            d = &option_table[k];
    return d && d->kind != OPT_FLAG;
}

void cli_options_help(FILE *out, const char *command)
{
    fprintf(out, "\nOptions of restir %s (defaults in brackets):\n", command);
    for (size_t k = 0; k < sizeof option_table / sizeof option_table[0]; k++) {
        const struct opt_def *d = &option_table[k];
        int known;
        if (opt_find(command, d->name, &known) != d || !strcmp(d->name, "-h"))
            continue;
        char lhs[64];
        snprintf(lhs, sizeof lhs, "%s%s%s", d->name, d->arg[0] ? " " : "", d->arg);
        fprintf(out, "  %-28s %s", lhs, d->help);
        if (d->def)
            fprintf(out, " [%s]", d->def);
        fputc('\n', out);
    }
}


static int opt_is_number(const struct opt_def *d)
{
    return d->kind == OPT_INT || d->kind == OPT_LLONG || d->kind == OPT_SECONDS || d->kind == OPT_POSITIVE;
}

cJSON *cli_options_describe(const char *command, int argc, char **argv, char *msg)
{
    cJSON *j = cJSON_CreateObject(), *set = cJSON_CreateArray(), *pos = cJSON_CreateArray();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        int known;
        const struct opt_def *d = a[0] == '-' ? opt_find(command, a, &known) : NULL;
        if (a[0] != '-') {
            cJSON_AddItemToArray(pos, cJSON_CreateString(a));
            continue;
        }
        if (!d || (d->kind != OPT_FLAG && i + 1 >= argc)) {
            if (d)
                snprintf(msg, RESTIR_MSG_LEN, "%s: no value for '%s'", command, a);
            else
                opt_refusal(command, a, msg);
            cJSON_Delete(j);
            cJSON_Delete(set);
            cJSON_Delete(pos);
            return NULL;
        }
        const char *val = d->kind == OPT_FLAG ? NULL : argv[++i];
        cJSON *item;
        if (d->kind == OPT_SET) {
            cJSON_AddItemToArray(set, cJSON_CreateString(val));
            continue;
        }
        if (d->kind == OPT_FLAG)
            item = cJSON_CreateTrue();
        else if (opt_is_number(d))
            item = cJSON_CreateNumber(strtod(val, NULL));
        else
            item = cJSON_CreateString(val);
        if (cJSON_GetObjectItemCaseSensitive(j, opt_key(d->name)))
            cJSON_ReplaceItemInObjectCaseSensitive(j, opt_key(d->name), item);
        else
            cJSON_AddItemToObject(j, opt_key(d->name), item);
    }
    cJSON_AddItemToObject(j, "set", set);
    cJSON_AddItemToObject(j, "positional", pos);
    return j;
}

/* Appends s to the growing argv. */
static void push_arg(int *argc, char ***argv, int *cap, const char *s)
{
    if (*argc + 1 >= *cap) {
        *cap = *cap ? 2 * *cap : 32;
        *argv = realloc(*argv, sizeof(char *) * (size_t)*cap);
        RESTIR_CHECK(*argv != NULL);
    }
    const size_t n = strlen(s) + 1;
    (*argv)[*argc] = xmalloc(n);
    memcpy((*argv)[*argc], s, n);
    (*argc)++;
    (*argv)[*argc] = NULL;
}

void cli_options_free_argv(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        free(argv[i]);
    free(argv);
}

/* The strings of array `key` of desc, pushed each after `option` (NULL: alone). Returns 0, or -1. */
static int push_strings(const char *command, const cJSON *desc, const char *key, const char *option, int *argc,
                        char ***argv, int *cap, char *msg)
{
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(desc, key);
    if (!a)
        return 0;
    if (!cJSON_IsArray(a)) {
        snprintf(msg, RESTIR_MSG_LEN, "%s description: \"%s\" must be an array of strings", command, key);
        return -1;
    }
    const cJSON *e;
    cJSON_ArrayForEach(e, a)
    {
        if (!cJSON_IsString(e)) {
            snprintf(msg, RESTIR_MSG_LEN, "%s description: \"%s\" must be an array of strings", command, key);
            return -1;
        }
        if (option)
            push_arg(argc, argv, cap, option);
        push_arg(argc, argv, cap, e->valuestring);
    }
    return 0;
}

int cli_options_argv(const char *command, const cJSON *desc, int *argc_out, char ***argv_out, char *msg)
{
    int argc = 0, cap = 0;
    char **argv = NULL;
    *argc_out = 0;
    *argv_out = NULL;
    if (!cJSON_IsObject(desc)) {
        snprintf(msg, RESTIR_MSG_LEN, "%s description: not a JSON object", command);
        return -1;
    }
    push_arg(&argc, &argv, &cap, "--help"); /* a placeholder, removed below, so argv is never NULL */
    const cJSON *item;
    cJSON_ArrayForEach(item, desc)
    {
        if (!strcmp(item->string, "set") || !strcmp(item->string, "positional"))
            continue;
        char name[64];
        snprintf(name, sizeof name, "--%.60s", item->string);
        int known;
        const struct opt_def *d = opt_find(command, name, &known);
        if (!d || d->kind == OPT_SET) {
            snprintf(msg, RESTIR_MSG_LEN, "%s description: unknown key \"%.100s\"", command, item->string);
            cli_options_free_argv(argc, argv);
            return -1;
        }
        char text[64];
        const char *val = NULL;
        if (d->kind == OPT_FLAG) {
            if (!cJSON_IsTrue(item) && !cJSON_IsFalse(item)) {
                snprintf(msg, RESTIR_MSG_LEN, "%s description: \"%s\" must be true or false", command, item->string);
                cli_options_free_argv(argc, argv);
                return -1;
            }
            if (cJSON_IsFalse(item))
                continue;
        } else if (opt_is_number(d)) {
            if (!cJSON_IsNumber(item)) {
                snprintf(msg, RESTIR_MSG_LEN, "%s description: \"%s\" must be a number", command, item->string);
                cli_options_free_argv(argc, argv);
                return -1;
            }
            snprintf(text, sizeof text, "%.17g", item->valuedouble);
            val = text;
        } else {
            if (!cJSON_IsString(item)) {
                snprintf(msg, RESTIR_MSG_LEN, "%s description: \"%s\" must be a string", command, item->string);
                cli_options_free_argv(argc, argv);
                return -1;
            }
            val = item->valuestring;
        }
        push_arg(&argc, &argv, &cap, name);
        if (val)
            push_arg(&argc, &argv, &cap, val);
    }
    if (push_strings(command, desc, "set", "--set", &argc, &argv, &cap, msg) != 0 ||
        push_strings(command, desc, "positional", NULL, &argc, &argv, &cap, msg) != 0) {
        cli_options_free_argv(argc, argv);
        return -1;
    }
    free(argv[0]);
    memmove(argv, argv + 1, sizeof(char *) * (size_t)argc); /* the placeholder out, NULL kept last */
    *argc_out = argc - 1;
    *argv_out = argv;
    return 0;
}
