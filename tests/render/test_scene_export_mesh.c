/* test_scene_export_mesh.c: `restir scene export NAME|FILE --mesh --out DIR` (the triangle soup that
 * bench/cycles hands to Blender). The built-in cornell is refused by name (its materials have a
 * specular layer); its Lambertian variant (the exported JSON with every material "lambert": true,
 * as bench/cycles/lambertize.py makes it) is written with every triangle, the one emitter's two
 * triangles facing down with their radiance, and the camera; a constant environment is written,
 * shading normals are refused unless loaded with scene.shading_normals=off. */
#include <cjson/cJSON.h>
#include <string.h>

#include "cli_util.h"
#include "core/check.h"
#include "scene/scenes_builtin.h"
#include "test_util.h"

static cJSON *read_json(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    size_t got = buf ? fread(buf, 1, (size_t)n, f) : 0;
    fclose(f);
    if (!buf || got != (size_t)n) {
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    cJSON *j = cJSON_Parse(buf);
    free(buf);
    return j;
}

static double num(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static double at(const cJSON *array, int i)
{
    const cJSON *v = cJSON_GetArrayItem(array, i);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* The exported built-in cornell with every material made a pure Lambertian. */
static int write_lambert_cornell(const char *tmp, char *path)
{
    char args[2 * CLI_PATH_MAX], err[CLI_ERR_MAX], src[2 * CLI_PATH_MAX];
    snprintf(args, sizeof args, "scene export cornell --out '%s/json'", tmp);
    if (cli_run(tmp, args, err) != 0)
        return -1;
    snprintf(src, sizeof src, "%s/json/cornell.json", tmp);
    cJSON *j = read_json(src);
    if (!j)
        return -1;
    cJSON *m;
    cJSON_ArrayForEach(m, cJSON_GetObjectItemCaseSensitive(j, "materials"))
    {
        cJSON_DeleteItemFromObjectCaseSensitive(m, "metallic");
        cJSON_DeleteItemFromObjectCaseSensitive(m, "roughness");
        cJSON_DeleteItemFromObjectCaseSensitive(m, "lambert");
        cJSON_AddBoolToObject(m, "lambert", 1);
    }
    char *text = cJSON_Print(j);
    snprintf(path, 2 * CLI_PATH_MAX, "%s/json/cornell_lambert.json", tmp);
    int rc = cli_write_text(path, text);
    free(text);
    cJSON_Delete(j);
    return rc;
}

static void check_cornell(const char *file)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_create_builtin("cornell", &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    cJSON *j = read_json(file);
    EXPECT(j != NULL, "%s: missing or not JSON", file);
    if (!j) {
        scene_destroy(&s);
        return;
    }
    const cJSON *verts = cJSON_GetObjectItemCaseSensitive(j, "vertices");
    const cJSON *idx = cJSON_GetObjectItemCaseSensitive(j, "indices");
    const cJSON *tm = cJSON_GetObjectItemCaseSensitive(j, "triangle_material");
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(j, "materials");
    const int nt = (int)num(j, "triangles");
    EXPECT(nt == s.num_tris && nt == 36, "triangles %d, the built-in cornell has %d", nt, s.num_tris);
    EXPECT(cJSON_GetArraySize(idx) == 3 * s.num_tris && cJSON_GetArraySize(tm) == s.num_tris &&
               cJSON_GetArraySize(verts) == 3 * s.num_verts,
           "array sizes: %d indices, %d materials, %d coordinates", cJSON_GetArraySize(idx), cJSON_GetArraySize(tm),
           cJSON_GetArraySize(verts));
    EXPECT(num(j, "emitter_triangles") == 2, "emitter_triangles %g, 2 expected", num(j, "emitter_triangles"));
    /* Exactly one emissive material, (17, 12, 4), black, on the two triangles of the ceiling light,
     * whose front (counter-clockwise) side faces down. */
    int emissive = -1, n_emissive = 0;
    for (int m = 0; m < cJSON_GetArraySize(mats); m++) {
        const cJSON *e = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(mats, m), "emission");
        if (at(e, 0) > 0.0) {
            emissive = m;
            n_emissive++;
            EXPECT(at(e, 0) == 17.0 && at(e, 1) == 12.0 && at(e, 2) == 4.0, "emission [%g, %g, %g]", at(e, 0),
                   at(e, 1), at(e, 2));
            const cJSON *d = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(mats, m), "diffuse");
            EXPECT(at(d, 0) == 0.0 && at(d, 1) == 0.0 && at(d, 2) == 0.0, "the emitter reflects");
        }
    }
    EXPECT(n_emissive == 1, "%d emissive materials", n_emissive);
    int on_light = 0;
    for (int t = 0; t < nt && emissive >= 0; t++) {
        if ((int)at(tm, t) != emissive)
            continue;
        on_light++;
        vec3 p[3];
        for (int c = 0; c < 3; c++) {
            int v = (int)at(idx, 3 * t + c);
            p[c] = v3((float)at(verts, 3 * v), (float)at(verts, 3 * v + 1), (float)at(verts, 3 * v + 2));
            EXPECT(fabsf(p[c].y - 1.995f) < 1e-6f, "light vertex at y %g", (double)p[c].y);
        }
        vec3 n = v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0]));
        EXPECT(n.y < 0.0f && fabsf(n.x) < 1e-6f && fabsf(n.z) < 1e-6f, "light triangle %d faces [%g, %g, %g]", t,
               (double)n.x, (double)n.y, (double)n.z);
    }
    EXPECT(on_light == 2, "%d triangles carry the emitter", on_light);
    const cJSON *cam = cJSON_GetObjectItemCaseSensitive(j, "camera");
    const cJSON *pos = cJSON_GetObjectItemCaseSensitive(cam, "position");
    const cJSON *dir = cJSON_GetObjectItemCaseSensitive(cam, "direction");
    EXPECT(at(pos, 0) == 0.0 && at(pos, 1) == 1.0 && fabs(at(pos, 2) - 3.4) < 1e-6 && num(cam, "vfov_deg") == 40.0,
           "camera position [%g, %g, %g] vfov %g", at(pos, 0), at(pos, 1), at(pos, 2), num(cam, "vfov_deg"));
    EXPECT(fabs(at(dir, 0)) < 1e-6 && fabs(at(dir, 1)) < 1e-6 && fabs(at(dir, 2) + 1.0) < 1e-6,
           "camera direction [%.9g, %.9g, %.9g]",
           at(dir, 0), at(dir, 1), at(dir, 2));
    EXPECT(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(j, "environment")), "cornell has no environment");
    cJSON_Delete(j);
    scene_destroy(&s);
}

/* A Lambertian quad under a constant sky, with shading normals on a second triangle. */
static const char *const sky_scene =
    "{\"name\": \"sky-quad\", \"camera\": {\"position\": [0, 1, 3], \"look_at\": [0, 0, 0]},\n"
    " \"environment\": {\"color\": [0.5, 0.25, 1], \"intensity\": 2},\n"
    " \"materials\": [{\"name\": \"grey\", \"base_color\": [0.5, 0.5, 0.5], \"lambert\": true}],\n"
    " \"shapes\": [{\"type\": \"quads\", \"material\": \"grey\", \"quads\": [[[-1, 0, 1], [1, 0, 1], [1, 0, -1], "
    "[-1, 0, -1]]]},\n"
    "  {\"type\": \"triangles\", \"material\": \"grey\", \"vertices\": [[0, 0.5, 0], [1, 0.5, 0], [0, 1, 0]],\n"
    "   \"normals\": [[0, 0, 1], [0.2, 0, 1], [0, 0.2, 1]]}]}\n";

int main(void)
{
    char tmp[CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    char args[6 * CLI_PATH_MAX], err[CLI_ERR_MAX], out[CLI_ERR_MAX], file[2 * CLI_PATH_MAX],
        lambert[2 * CLI_PATH_MAX];

    /* The built-in cornell: diffuse plus specular materials, refused naming the first one. */
    snprintf(args, sizeof args, "scene export cornell --mesh --out '%s/mesh'", tmp);
    int rc = cli_run(tmp, args, err);
    snprintf(file, sizeof file, "%s/mesh/cornell.mesh.json", tmp);
    EXPECT(rc == 2 && strstr(err, "material 0 ") && strstr(err, "specular layer"),
           "built-in cornell: exit %d, not refused naming material 0:\n%s", rc, err);
    EXPECT(access(file, F_OK) != 0, "a refused export wrote %s", file);

    /* Its Lambertian variant. */
    EXPECT(write_lambert_cornell(tmp, lambert) == 0, "cannot write the Lambertian cornell");
    snprintf(args, sizeof args, "scene export '%s' --mesh --out '%s/mesh'", lambert, tmp);
    rc = cli_run_capture(tmp, args, out, err);
    EXPECT(rc == 0 && strstr(out, "cornell.mesh.json"), "restir %s exited %d:\n%s", args, rc, err);
    check_cornell(file);

    /* A constant environment is written (colour times intensity); shading normals are refused
     * unless the scene is loaded without them. */
    char sky[2 * CLI_PATH_MAX];
    snprintf(sky, sizeof sky, "%s/sky_quad.json", tmp);
    EXPECT(cli_write_text(sky, sky_scene) == 0, "cannot write %s", sky);
    snprintf(args, sizeof args, "scene export '%s' --mesh --out '%s/mesh'", sky, tmp);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 2 && strstr(err, "shading normals"), "shading normals: exit %d, not refused:\n%s", rc, err);
    snprintf(args, sizeof args, "scene export '%s' --mesh --set scene.shading_normals=off --out '%s/mesh'", sky, tmp);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    snprintf(file, sizeof file, "%s/mesh/sky-quad.mesh.json", tmp);
    cJSON *j = read_json(file);
    const cJSON *env = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(j, "environment"), "color");
    EXPECT(at(env, 0) == 1.0 && at(env, 1) == 0.5 && at(env, 2) == 2.0, "environment [%g, %g, %g], [1, 0.5, 2] expected",
           at(env, 0), at(env, 1), at(env, 2));
    EXPECT(num(j, "triangles") == 3 && num(j, "emitter_triangles") == 0, "sky-quad: %g triangles, %g emitting",
           num(j, "triangles"), num(j, "emitter_triangles"));
    cJSON_Delete(j);

    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
