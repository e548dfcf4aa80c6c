/* cmd_scene.c: `restir scene info NAME|FILE` (what a scene holds and what loading it costs),
 * `restir scene export NAME --out DIR` (a built-in scene as an editable JSON scene file) and
 * `restir scene export NAME|FILE --mesh --out DIR` (any scene as a triangle soup for another
 * renderer). Must never render. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "io/atomic_file.h"
#include "io/scene_export.h"
#include "io/scene_export_mesh.h"
#include "scene/scene_file.h"
#include "scene/scenes_builtin.h"

static void scene_usage(FILE *out)
{
    fprintf(out, "usage: restir scene info NAME|FILE [--set scene.missing_textures=warn] [--set scene.strict=on]\n"
                 "       restir scene export NAME --out DIR [--force]\n"
                 "       restir scene export NAME|FILE --mesh --out DIR [--force] [--set scene.shading_normals=off]\n"
                 "                           [--env FILE|none]\n"
                 "info: triangles, emitters, materials, textures, bounds, load and BVH build time of a\n"
                 "      built-in scene or a scene file (.json, .gltf, .glb, .obj, .ply; docs/SCENES.md).\n"
                 "export: writes the built-in scene NAME as DIR/NAME.json; rendering that file gives the\n"
                 "      same images as the built-in scene, bit for bit with the same seed.\n"
                 "export --mesh: writes any scene as DIR/NAME.mesh.json, a triangle soup for another renderer\n"
                 "      (bench/cycles): world-space vertices and indices, a material per triangle, the materials'\n"
                 "      diffuse albedo and front-side emission, the pinhole camera and a constant environment.\n"
                 "      Refuses (exit 2, naming the material) what a Lambert-only renderer cannot match: a used\n"
                 "      material without \"lambert\": true, a textured or alpha-masked one, shading normals, a thin\n"
                 "      lens, an environment image.\n"
                 "export writes one file, so DIR may hold other scenes; a NAME.json (NAME.mesh.json) already\n"
                 "      there is refused (exit 2, nothing written) unless --force, which replaces it.\n");
}

static int scene_info(int argc, char **argv)
{
    struct cli_options o;
    char msg[RESTIR_MSG_LEN];
    if (cli_parse_options("scene info", argc - 1, argv + 1, &o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    const char *name = argv[0];
    struct scene s;
    double t0 = omp_get_wtime();
    if (cli_scene_load(&o.params, o.env, name, &s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    double total_ms = 1e3 * (omp_get_wtime() - t0);
    vec3 lo = v3s(INFINITY), hi = v3s(-INFINITY);
    for (int i = 0; i < s.num_verts; i++) {
        vec3 v = s.verts[i];
        lo = v3(fminf(lo.x, v.x), fminf(lo.y, v.y), fminf(lo.z, v.z));
        hi = v3(fmaxf(hi.x, v.x), fmaxf(hi.y, v.y), fmaxf(hi.z, v.z));
    }
    printf("scene %s\n", s.name);
    size_t texels = 0;
    for (int t = 0; t < s.num_textures; t++)
        texels += (size_t)s.textures[t].width * (size_t)s.textures[t].height;
    printf("triangles %d\nemitters %d\nmaterials %d\ntextures %d (%.3g Mtexels)\nobjects %d\n", s.num_tris,
           s.num_emitters, s.num_materials, s.num_textures, (double)texels * 1e-6, s.num_objects);
    int smooth = 0; /* triangles with a shading normal at every corner */
    for (int t = 0; s.normals && t < s.num_tris; t++) {
        const uint32_t *ix = &s.indices[3 * t];
        smooth += v3_length2(s.normals[ix[0]]) > 0.0f && v3_length2(s.normals[ix[1]]) > 0.0f &&
                  v3_length2(s.normals[ix[2]]) > 0.0f;
    }
    printf("shading normals on %d of %d triangles (the rest flat)\n", smooth, s.num_tris);
    printf("bounds [%g, %g, %g] .. [%g, %g, %g]\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    printf("camera position [%g, %g, %g] look_at [%g, %g, %g] vfov %g\n", s.camera.position.x,
           s.camera.position.y, s.camera.position.z, s.camera.target.x, s.camera.target.y, s.camera.target.z,
           s.camera.vfov_deg);
    printf("camera_path keys %d\n", s.camera_path.num_keys);
    if (s.load_notes) /* what a mesh file's import left out (also said on stderr while loading) */
        for (const char *line = s.load_notes; *line;) {
            const size_t len = strcspn(line, "\n");
            printf("loaded in part: %.*s\n", (int)len, line);
            line += len + (line[len] == '\n');
        }
    printf("load_ms %.1f\nbvh_ms %.1f\n", total_ms - s.bvh_ms, s.bvh_ms);
    scene_destroy(&s);
    return 0;
}

/* `scene export NAME|FILE --mesh --out DIR [--set ...] [--env ...]`: the scene loaded as the
 * renderer loads it (scene settings and --env apply), written as DIR/NAME.mesh.json. */
static int scene_export_mesh(int argc, char **argv)
{
    const char *name = NULL;
    char **rest = xmalloc(sizeof(char *) * (size_t)(argc + 1));
    int n = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--mesh"))
            continue;
        if (argv[i][0] == '-') {
            rest[n++] = argv[i];
            if (cli_option_takes_value("scene export", argv[i]) && i + 1 < argc)
                rest[n++] = argv[++i];
        } else if (!name) {
            name = argv[i];
        } else {
            rest[n++] = argv[i];
        }
    }
    struct cli_options o;
    char msg[RESTIR_MSG_LEN];
    int parsed = cli_parse_options("scene export", n, rest, &o, msg);
    free(rest);
    if (parsed != 0) {
        cli_error("%s%s", strncmp(msg, "scene export: ", 14) ? "scene export --mesh: " : "", msg);
        return EXIT_USAGE;
    }
    if (!name || !o.out) {
        cli_error("scene export --mesh needs a scene (a built-in name or a file) and --out DIR");
        return EXIT_USAGE;
    }
    struct scene s;
    if (cli_scene_load(&o.params, o.env, name, &s, msg) != 0) {
        cli_error("scene export --mesh: %s", msg);
        return EXIT_USAGE;
    }
    int rc = 0;
    char path[4200];
    if (scene_export_mesh_check(&s, msg) != 0) {
        cli_error("scene export --mesh: %s", msg);
        rc = EXIT_USAGE;
    } else if (snprintf(path, sizeof path, "%s/%s.mesh.json", o.out, s.name) >= (int)sizeof path) {
        cli_error("scene export --mesh: the output path is too long");
        rc = EXIT_USAGE;
    } else if (out_file_check("scene export --mesh:", path, o.force, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_USAGE;
    } else if (io_make_dirs(o.out, msg) != 0 || scene_export_mesh_json(&s, name, path, msg) != 0) {
        cli_error("scene export --mesh: %s", msg);
        rc = EXIT_RUNTIME;
    } else {
        printf("%s\n", path);
    }
    scene_destroy(&s);
    return rc;
}

static int scene_export(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (!strcmp(argv[i], "--mesh"))
            return scene_export_mesh(argc, argv);
    const char *name = NULL, *out = NULL;
    int force = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--force"))
            force = 1;
        else if (argv[i][0] != '-' && !name)
            name = argv[i];
        else {
            cli_error("scene export: unexpected argument '%s'", argv[i]);
            return EXIT_USAGE;
        }
    }
    if (!name || !out) {
        cli_error("scene export needs a built-in scene name and --out DIR");
        return EXIT_USAGE;
    }
    struct scene s;
    struct scene_shape_record *records = NULL;
    int n = 0;
    char msg[RESTIR_MSG_LEN];
    if (!scene_is_builtin(name)) {
        cli_error("scene export: '%s' is not a built-in scene (restir list); export writes built-in scenes as files",
                  name);
        return EXIT_USAGE;
    }
    if (scene_create_builtin_recorded(name, &s, &records, &n, msg) != 0) {
        cli_error("scene export: %s", msg);
        return EXIT_USAGE;
    }
    char path[4200];
    snprintf(path, sizeof path, "%s/%s.json", out, name);
    int rc = 0;
    if (out_file_check("scene export:", path, force, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_USAGE;
    } else if (io_make_dirs(out, msg) != 0 || scene_export_json(&s, records, n, path, msg) != 0) {
        cli_error("scene export: %s", msg);
        rc = EXIT_RUNTIME;
    } else {
        printf("%s\n", path);
    }
    free(records);
    scene_destroy(&s);
    return rc;
}

int cmd_scene(int argc, char **argv)
{
    if (argc < 1) {
        scene_usage(stderr);
        return EXIT_USAGE;
    }
    for (int i = 0; i < argc; i++) /* scene --help, scene info --help, scene export NAME --mesh -h, ... */
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            scene_usage(stdout);
            return 0;
        }
    if (!strcmp(argv[0], "info") && argc >= 2 && argv[1][0] != '-')
        return scene_info(argc - 1, argv + 1);
    if (!strcmp(argv[0], "export"))
        return scene_export(argc - 1, argv + 1);
    cli_error("scene: expected 'info NAME|FILE', 'export NAME --out DIR' or 'export NAME|FILE --mesh --out DIR'");
    scene_usage(stderr);
    return EXIT_USAGE;
}
