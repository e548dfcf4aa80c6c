/* options.c: parsing of the shared subcommand options into struct cli_options, with the error
 * message naming the offending option. Must never run a render. */
#include "options.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "core/check.h"
#include "settings_file.h"

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

int cli_parse_options(const char *command, int argc, char **argv, struct cli_options *o, char *msg)
{
    memset(o, 0, sizeof(*o));
    render_params_defaults(&o->params);
    o->scene = "many-lights";
    o->frames = 1;
    o->ref_spp = 1024;
    o->save_all = 1;
    o->runs = strcmp(command, "compare") ? 8 : 1;
    o->warmup = 40; /* 000 Sec. 7 */
    o->checkpoint_every = -1.0;
    int frames_given = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        long long v;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            o->help = 1;
            continue;
        }
        if (!strcmp(a, "--equal-time")) {
            o->equal_time = 1;
            continue;
        }
        if (!strcmp(a, "--report")) {
            o->report = 1;
            continue;
        }
        if (strncmp(a, "--", 2) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "%s: unexpected argument '%s'", command, a);
            return -1;
        }
        if (need_value(i, argc, argv, msg) != 0)
            return -1;
        const char *val = argv[++i];
        if (!strcmp(a, "--scene"))
            o->scene = val;
        else if (!strcmp(a, "--method"))
            o->method = val;
        else if (!strcmp(a, "--methods"))
            o->methods = val;
        else if (!strcmp(a, "--ref"))
            o->ref = val;
        else if (!strcmp(a, "--out"))
            o->out = val;
        else if (!strcmp(a, "--env"))
            o->env = val;
        else if (!strcmp(a, "--script") && !strcmp(command, "view"))
            o->script = val;
        else if (!strcmp(a, "--res")) {
            if (cli_parse_res(val, &o->params.width, &o->params.height, msg) != 0)
                return -1;
            o->res_given = 1;
        } else if (!strcmp(a, "--frames")) {
            if (cli_parse_int(a, val, 1, 100000, &v, msg) != 0)
                return -1;
            o->frames = (int)v;
            frames_given = 1;
        } else if (!strcmp(a, "--frame")) {
            if (cli_parse_int(a, val, 0, 100000, &v, msg) != 0)
                return -1;
            o->frame = (int)v;
        } else if (!strcmp(a, "--spp")) {
            if (cli_parse_int(a, val, 1, 1 << 20, &v, msg) != 0)
                return -1;
            o->params.spp = (int)v;
            o->spp_given = 1;
        } else if (!strcmp(a, "--ref-spp")) {
            if (cli_parse_int(a, val, 1, 1 << 20, &v, msg) != 0)
                return -1;
            o->ref_spp = (int)v;
        } else if (!strcmp(a, "--seed")) {
            if (cli_parse_int(a, val, 0, (1ll << 62), &v, msg) != 0)
                return -1;
            o->params.seed = (uint64_t)v;
        } else if (!strcmp(a, "--max-memory")) {
            if (cli_parse_int(a, val, 1, 1LL << 40, &v, msg) != 0)
                return -1;
            o->max_memory_mb = v;
        } else if (!strcmp(a, "--threads")) {
            if (cli_parse_int(a, val, 0, 1024, &v, msg) != 0)
                return -1;
            o->params.threads = (int)v;
        } else if (!strcmp(a, "--camera")) {
            if (!strcmp(val, "static"))
                o->params.camera_path = 0;
            else if (!strcmp(val, "path"))
                o->params.camera_path = 1;
            else if (!strcmp(command, "render") || !strcmp(command, "view"))
                o->camera_file = val; /* a camera file: one camera per frame */
            else {
                snprintf(msg, RESTIR_MSG_LEN, "--camera expects static or path, got '%s'", val);
                return -1;
            }
        } else if (!strcmp(a, "--save")) {
            if (!strcmp(val, "all"))
                o->save_all = 1;
            else if (!strcmp(val, "last"))
                o->save_all = 0;
            else {
                snprintf(msg, RESTIR_MSG_LEN, "--save expects all or last, got '%s'", val);
                return -1;
            }
        } else if (!strcmp(a, "--configs")) {
            o->configs = val;
        } else if (!strcmp(a, "--radii")) {
            o->radii = val;
        } else if (!strcmp(a, "--runs")) {
            if (cli_parse_int(a, val, strcmp(command, "compare") ? 2 : 1, 100000, &v, msg) != 0)
                return -1;
            o->runs = (int)v;
        } else if (!strcmp(a, "--ref-every") && !strcmp(command, "compare")) {
            if (cli_parse_int(a, val, 1, 100000, &v, msg) != 0)
                return -1;
            o->ref_every = (int)v;
        } else if (!strcmp(a, "--warmup")) {
            if (cli_parse_int(a, val, 0, 100000, &v, msg) != 0)
                return -1;
            o->warmup = (int)v;
        } else if (!strcmp(a, "--checkpoint-every") && !strcmp(command, "reference")) {
            char *end = NULL;
            errno = 0;
            double s = strtod(val, &end);
            if (end == val || *end != '\0' || errno != 0 || !(s >= 0.0 && s <= 1e7)) {
                snprintf(msg, RESTIR_MSG_LEN, "--checkpoint-every expects seconds in [0, 1e7], got '%s'", val);
                return -1;
            }
            o->checkpoint_every = s;
        } else if (!strcmp(a, "--plan") && strcmp(command, "render") && strcmp(command, "view")) {
            o->plan = val;
        } else if (!strcmp(a, "--merge") && strcmp(command, "render") && strcmp(command, "view")) {
            o->merge = val;
        } else if (!strcmp(a, "--shards") && !strcmp(command, "reference")) {
            if (cli_parse_int(a, val, 1, 4096, &v, msg) != 0)
                return -1;
            o->shards = (int)v;
        } else if (!strcmp(a, "--params") && !strcmp(command, "render")) {
            if (apply_params_file(val, o, msg) != 0)
                return -1;
            frames_given |= o->frames_given;
        } else if (!strcmp(a, "--set")) {
            if (render_params_set(&o->params, val, msg) != 0)
                return -1;
        } else {
            snprintf(msg, RESTIR_MSG_LEN, "%s: unknown option '%s'", command, a);
            return -1;
        }
    }
    o->frames_given = frames_given;
    if (!frames_given && !strcmp(command, "study"))
        o->frames = 16;
    return render_params_validate(&o->params, msg);
}
