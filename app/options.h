/* options.h: the options the subcommands share, parsed once into struct cli_options.
 * Must never run a render. */
#ifndef RESTIR_APP_OPTIONS_H
#define RESTIR_APP_OPTIONS_H

#include "render/params.h"

struct cli_options {
    const char *scene;
    const char *method;
    const char *methods; /* compare: comma-separated */
    const char *ref;
    const char *out;
    int frames;
    int frame;           /* reference: camera of this frame */
    int equal_time;
    int report;          /* compare, study: write DIR/index.html */
    const char *camera_file; /* render: --camera FILE, one camera per frame (restir view records them) */
    const char *env;         /* --env FILE|none: the environment light replacing the scene's own */
    const char *script;      /* view: timed input (src/view/view_script.h) */
    long long max_memory_mb; /* --max-memory: refuse renders estimated above it (0: what the system has) */
    int frames_given;
    int ref_spp;         /* compare: spp of the reference rendered when --ref is absent */
    int save_all;        /* render: write every frame (1) or only the last (0) */
    int help;
    int spp_given;
    int res_given;
    const char *configs; /* study: comma-separated configurations */
    const char *radii;   /* study: comma-separated radii */
    int runs;            /* study: independent sequences per configuration; compare: per spec */
    int ref_every;       /* compare: also measure frames K-1, 2K-1, ... against their own references */
    int warmup;          /* study: frames before measuring */
    double checkpoint_every; /* reference: seconds between checkpoints (< 0: none, 0: every chunk) */
    const char *plan;        /* study, reference, compare: write jobs into this folder instead of running */
    const char *merge;       /* study, reference, compare: merge the finished jobs of this plan folder */
    int shards;              /* reference --plan: jobs the samples are split into (0: not given) */
    struct render_params params;
    /* --params FILE: the strings it names (scene, method, camera file) live here */
    char params_scene[4096], params_method[128], params_camera[4096], params_env[4096];
};

/* Parses argv[first..argc) for `command`. Returns 0, or -1 with msg naming the bad option. */
int cli_parse_options(const char *command, int argc, char **argv, struct cli_options *o, char *msg);

#endif
