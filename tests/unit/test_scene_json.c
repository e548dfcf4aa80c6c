/* test_scene_json.c: the JSON scene reader: a scene with every shape type (a mesh file relative
 * to the JSON file, with a transform and a material override) loads with the expected triangles,
 * materials, objects and cameras (thin-lens keys included, also in camera files); every kind of
 * bad input is refused with a message that names the file and the key, and leaves nothing
 * allocated (run under ASan to see that). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "io/scene_export.h"
#include "scene/scene_file.h"
#include "scene/scene_json.h"
#include "test_util.h"

static char dir[256];

static void write_file(const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    EXPECT(f != NULL, "cannot write %s", path);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* A valid scene around the given shapes and materials text. */
static const char *const good_camera = "\"camera\": {\"position\": [0, 1, 4], \"look_at\": [0, 1, 0], \"vfov\": 40}";
static const char *const good_materials =
    "\"materials\": [{\"name\": \"white\", \"base_color\": [0.8, 0.8, 0.8]},"
    " {\"name\": \"lamp\", \"emission\": [2, 2, 2], \"emissive_strength\": 5},"
    " {\"name\": \"red\", \"base_color\": [0.8, 0.1, 0.1], \"roughness\": 0.4, \"metallic\": 0.5}]";

static void expect_loads(const char *name, const char *text, struct scene *s)
{
    char path[512], msg[RESTIR_MSG_LEN];
    write_file(name, text);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    int rc = scene_load(path, s, msg);
    EXPECT(rc == 0, "%s should load: %s", name, msg);
    if (rc != 0)
        memset(s, 0, sizeof(*s));
}

/* Loading text as d says (NULL: the defaults) must fail with a message containing the file name
 * and every part given. */
static void expect_error_with(const struct scene_load_desc *d, const char *text, const char *part1, const char *part2)
{
    static int count;
    char name[64], path[512], msg[RESTIR_MSG_LEN];
    snprintf(name, sizeof name, "bad%02d.json", count++);
    write_file(name, text);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    struct scene s;
    int rc = scene_load_with(path, d, &s, msg);
    EXPECT(rc != 0, "%s should be refused (expected '%s')", name, part1);
    if (rc == 0) {
        scene_destroy(&s);
        return;
    }
    EXPECT(strstr(msg, path) != NULL, "%s: message does not name the file: %s", name, msg);
    EXPECT(strstr(msg, part1) != NULL, "%s: message lacks '%s': %s", name, part1, msg);
    EXPECT(!part2 || strstr(msg, part2) != NULL, "%s: message lacks '%s': %s", name, part2 ? part2 : "", msg);
    printf("refused as expected: %s\n", msg);
}

static void expect_error(const char *text, const char *part1, const char *part2)
{
    expect_error_with(NULL, text, part1, part2);
}

static void test_good_scene(void)
{
    char sub[300];
    snprintf(sub, sizeof sub, "%s/meshes", dir);
    EXPECT(mkdir(sub, 0777) == 0, "cannot make %s", sub);
    write_file("meshes/tri.obj", "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char text[4096];
    snprintf(
        text, sizeof text,
        "{\"format\": \"restir-scene 1\", %s, %s,\n"
        " \"camera_path\": [{\"frame\": 0, \"position\": [0, 1, 4], \"look_at\": [0, 1, 0]},"
        " {\"frame\": 10, \"position\": [1, 1, 4], \"look_at\": [0, 1, 0]}],\n"
        " \"shapes\": [\n"
        "  {\"type\": \"quads\", \"material\": \"white\", \"quads\": [[[-2, 0, 2], [2, 0, 2], [2, 0, -2], [-2, 0, "
        "-2]]]},\n"
        "  {\"type\": \"box\", \"material\": \"red\", \"min\": [-0.5, 0, -0.5], \"max\": [0.5, 1, 0.5], "
        "\"rotate_y_rad\": 0.3},\n"
        "  {\"type\": \"sphere\", \"material\": \"red\", \"center\": [1, 0.5, 0], \"radius\": 0.4, \"segments\": 8},\n"
        "  {\"type\": \"triangles\", \"material\": \"lamp\", \"object\": 7, \"vertices\": [[0, 3, 0], [0, 3, 1], [1, "
        "3, 0]]},\n"
        "  {\"type\": \"mesh\", \"file\": \"meshes/tri.obj\", \"material\": \"white\",\n"
        "   \"transform\": {\"translate\": [0, 0, -1], \"scale\": 2}}\n"
        " ]}\n",
        good_camera, good_materials);
    struct scene s;
    expect_loads("good.json", text, &s);
    if (!s.num_tris)
        return;
    /* 2 (quad) + 12 (box) + sphere 8 segments x 4 rings minus poles (2 x 8) + 1 + 1 */
    const int sphere = 8 * 4 * 2 - 2 * 8;
    EXPECT(s.num_tris == 2 + 12 + sphere + 1 + 1, "triangles %d, expected %d", s.num_tris, 2 + 12 + sphere + 2);
    EXPECT(s.num_materials == 3, "materials %d", s.num_materials);
    EXPECT(s.num_emitters == 1, "emitters %d", s.num_emitters);
    EXPECT(s.materials[1].emission.x == 10.0f, "emissive_strength multiplies: %g", s.materials[1].emission.x);
    EXPECT(s.materials[2].roughness == 0.4f && s.materials[2].metallic == 0.5f, "red material read");
    /* the lamp keeps object 7; shapes without an object get fresh ids after the largest */
    const int lamp = s.num_tris - 2;
    EXPECT(s.tri_object[lamp] == 7, "lamp object %d", s.tri_object[lamp]);
    EXPECT(s.tri_object[0] == 8 && s.tri_object[2] == 9, "fresh objects %d %d", s.tri_object[0], s.tri_object[2]);
    /* the mesh: (1, 0, 0) scaled by 2 and moved by -1 in z */
    vec3 v1 = s.verts[s.indices[3 * (s.num_tris - 1) + 1]];
    EXPECT(v1.x == 2.0f && v1.y == 0.0f && v1.z == -1.0f, "mesh vertex (%g, %g, %g), expected (2, 0, -1)", v1.x, v1.y,
           v1.z);
    EXPECT(s.camera_path.num_keys == 2 && s.camera_path.keys[1].frame == 10.0f, "camera path read");
    EXPECT(s.camera.vfov_deg == 40.0f && s.camera.up.y == 1.0f, "camera read (up defaults to +y)");
    EXPECT(s.camera.aperture == 0.0f && s.camera.focus_distance == 0.0f &&
               s.camera_path.keys[1].cam.aperture == 0.0f && s.camera_path.keys[1].cam.focus_distance == 0.0f,
           "aperture and focus_distance default to 0 (a pinhole focused at look_at)");
    EXPECT(strcmp(s.name, "good") == 0, "scene named after the file: %s", s.name);
    scene_destroy(&s);
}

static void test_errors(void)
{
    char path[512], msg[RESTIR_MSG_LEN], t[4096];
    struct scene s;
    snprintf(path, sizeof path, "%s/missing.json", dir);
    EXPECT(scene_load(path, &s, msg) != 0 && strstr(msg, path), "missing file: %s", msg);
    EXPECT(scene_load("no-such-scene", &s, msg) != 0 && strstr(msg, "no-such-scene") && strstr(msg, "cornell"),
           "unknown name lists the built-in scenes: %s", msg);

    const char *quad = "{\"type\": \"quads\", \"material\": \"lamp\", \"quads\": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}";
#define SCENE(extra, shapes)                                                                                           \
    (snprintf(t, sizeof t, "{%s, %s%s, \"shapes\": [%s]}", good_camera, good_materials, extra, shapes), t)
    expect_error("{\"camera\": ", "invalid JSON", "line 1");
    expect_error(SCENE(", \"lights\": []", quad), "lights", "unknown key");
    expect_error(
        SCENE("", "{\"type\": \"box\", \"material\": \"white\", \"min\": [0,0,0], \"max\": [1,1,1], \"radius\": 1}"),
        "shapes[0].radius", "unknown key");
    expect_error(SCENE("", "{\"type\": \"cone\", \"material\": \"white\"}"), "shapes[0].type", "cone");
    expect_error(SCENE("", "{\"type\": \"sphere\", \"material\": \"white\", \"center\": [0,0,0], \"radius\": \"big\"}"),
                 "shapes[0].radius", "number");
    expect_error(SCENE("", "{\"type\": \"sphere\", \"material\": \"white\", \"center\": [0,0,0], \"radius\": -1}"),
                 "shapes[0].radius", "range");
    expect_error(SCENE("", "{\"type\": \"sphere\", \"material\": \"white\", \"center\": [0,0], \"radius\": 1}"),
                 "shapes[0].center", "3 numbers");
    expect_error(SCENE("", "{\"type\": \"sphere\", \"material\": \"white\", \"center\": [0,1e400,0], \"radius\": 1}"),
                 "shapes[0].center", "finite");
    expect_error(SCENE("", "{\"type\": \"box\", \"material\": \"gold\", \"min\": [0,0,0], \"max\": [1,1,1]}"),
                 "shapes[0].material", "gold");
    expect_error(SCENE("", "{\"type\": \"box\", \"material\": \"white\", \"min\": [0,0,0], \"max\": [1,0,1]}"),
                 "shapes[0]", "max must exceed min");
    expect_error(SCENE("", "{\"type\": \"box\", \"material\": \"white\", \"min\": [0,0,0], \"max\": [1,1,1]}"),
                 "emissive", NULL);
    expect_error(SCENE("", "{\"type\": \"triangles\", \"material\": \"lamp\", \"vertices\": [[0,0,0],[1,0,0]]}"),
                 "shapes[0].vertices", "3 vertices");
    expect_error(SCENE("", "{\"type\": \"mesh\", \"file\": \"nowhere.obj\"}"), "shapes[0]", "nowhere.obj");
    expect_error(SCENE("", "{\"type\": \"mesh\", \"file\": \"meshes/tri.obj\", \"transform\": {\"scale\": 0}}"),
                 "shapes[0].transform.scale", "zero");
    expect_error(
        SCENE("", "{\"type\": \"mesh\", \"file\": \"meshes/tri.obj\", \"materials\": {\"tri_mat\": \"nope\"}}"),
        "shapes[0].materials.tri_mat", "nope");
    expect_error(SCENE(", \"camera_path\": [{\"frame\": 3, \"position\": [0,0,1], \"look_at\": [0,0,0]},"
                       " {\"frame\": 3, \"position\": [0,0,2], \"look_at\": [0,0,0]}]",
                       quad),
                 "camera_path[1]", "previous key");
    expect_error(SCENE(", \"camera_path\": [{\"position\": [0,0,1], \"look_at\": [0,0,0]}]", quad),
                 "camera_path[0].frame", "missing");
#undef SCENE
    /* camera and materials problems: built by hand since SCENE supplies good ones */
    snprintf(t, sizeof t, "{\"camera\": {\"position\": [1, 1, 1], \"look_at\": [1, 1, 1]}, %s, \"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera", "position equals look_at");
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"up\": [0, 0, 3]}, %s, \"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera", "parallel");
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"vfov\": 200}, %s, \"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera.vfov", "range");
    /* thin-lens keys: negative, non-number and non-finite values name the key */
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"aperture\": -1}, %s, \"shapes\": "
             "[%s]}",
             good_materials, quad);
    expect_error(t, "camera.aperture", "range");
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"focus_distance\": -0.5}, %s, "
             "\"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera.focus_distance", "range");
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"aperture\": \"wide\"}, %s, "
             "\"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera.aperture", "number");
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"focus_distance\": \"far\"}, %s, "
             "\"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera.focus_distance", "number");
    snprintf(t, sizeof t,
             "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0], \"aperture\": 1e400}, %s, "
             "\"shapes\": [%s]}",
             good_materials, quad);
    expect_error(t, "camera.aperture", "range");
    snprintf(t, sizeof t,
             "{%s, %s, \"camera_path\": [{\"frame\": 0, \"position\": [0, 0, 1], \"look_at\": [0, 0, 0], "
             "\"aperture\": -1}], \"shapes\": [%s]}",
             good_camera, good_materials, quad);
    expect_error(t, "camera_path[0].aperture", "range");
    snprintf(t, sizeof t,
             "{%s, %s, \"camera_path\": [{\"frame\": 0, \"position\": [0, 0, 1], \"look_at\": [0, 0, 0]}, "
             "{\"frame\": 1, \"position\": [0, 0, 2], \"look_at\": [0, 0, 0], \"focus_distance\": -0.5}], "
             "\"shapes\": [%s]}",
             good_camera, good_materials, quad);
    expect_error(t, "camera_path[1].focus_distance", "range");
    snprintf(t, sizeof t, "{%s, \"shapes\": [%s]}", good_materials, quad);
    expect_error(t, "camera", "missing");
    snprintf(t, sizeof t, "{%s, \"materials\": [{\"name\": \"a\", \"roughness\": 2}], \"shapes\": []}", good_camera);
    expect_error(t, "materials[0].roughness", "range");
    snprintf(t, sizeof t, "{%s, \"materials\": [{\"name\": \"a\"}, {\"name\": \"a\"}], \"shapes\": []}", good_camera);
    expect_error(t, "materials[1]", "already used");
    snprintf(t, sizeof t, "{%s, \"materials\": [{\"name\": \"a\", \"emission\": [1, -1, 0]}], \"shapes\": []}",
             good_camera);
    expect_error(t, "materials[0].emission", "range");
    snprintf(t, sizeof t, "{%s, \"materials\": [{\"base_color\": [1, 1, 1]}], \"shapes\": []}", good_camera);
    expect_error(t, "materials[0].name", "missing");
    snprintf(t, sizeof t, "{%s, %s}", good_camera, good_materials);
    expect_error(t, "shapes", "missing");
    snprintf(t, sizeof t, "{%s, %s, \"shapes\": []}", good_camera, good_materials);
    expect_error(t, "shapes", "no triangles");
    snprintf(t, sizeof t, "{\"format\": \"pbrt\", %s, %s, \"shapes\": [%s]}", good_camera, good_materials, quad);
    expect_error(t, "format", "restir-scene 1");
    expect_error("[1, 2, 3]", "must be an object", NULL);
    snprintf(t, sizeof t, "{\"name\": \"../escape\", %s, %s, \"shapes\": [%s]}", good_camera, good_materials, quad);
    expect_error(t, "name", "without");
    snprintf(t, sizeof t, "{%s, \"materials\": [{\"name\": \"a\", \"emission_texture\": \"x.png\"}], \"shapes\": []}",
             good_camera);
    expect_error(t, "materials[0].emission_texture", "without");
    snprintf(t, sizeof t, "{%s, \"materials\": [{\"name\": \"a\", \"base_color_texture\": \"nope.png\"}], \"shapes\": []}",
             good_camera);
    expect_error(t, "materials[0].base_color_texture", "nope.png");
    /* the triangle budget: refused with a message, not an exhausted machine */
    const struct scene_load_desc budget = {.max_triangles = 100};
    snprintf(t, sizeof t,
             "{%s, %s, \"shapes\": [{\"type\": \"sphere\", \"material\": \"lamp\", \"center\": [0,0,0], "
             "\"radius\": 1, \"segments\": 64}]}",
             good_camera, good_materials);
    expect_error_with(&budget, t, "more than 100 triangles", NULL);
    /* the budget is the description's, not the process's: the same file loads without it */
    write_file("budget.json", t);
    snprintf(path, sizeof path, "%s/budget.json", dir);
    const int rc = scene_load(path, &s, msg);
    EXPECT(rc == 0, "budget.json should load with the default budget: %s", msg);
    if (rc == 0)
        scene_destroy(&s);
}

/* The thin-lens keys: read for the static camera, every camera_path key and camera files, and
 * written back by the camera writer only when non-zero (so pinhole cameras write as before). */
static void test_lens(void)
{
    const char *quad = "{\"type\": \"quads\", \"material\": \"lamp\", \"quads\": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}";
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"position\": [0, 1, 4], \"look_at\": [0, 1, 0], \"aperture\": 0.05, "
             "\"focus_distance\": 3.5}, %s,\n"
             " \"camera_path\": [{\"frame\": 0, \"position\": [0, 1, 4], \"look_at\": [0, 1, 0], \"aperture\": 0},"
             " {\"frame\": 10, \"position\": [1, 1, 4], \"look_at\": [0, 1, 0], \"aperture\": 0.125,"
             " \"focus_distance\": 2}],\n"
             " \"shapes\": [%s]}\n",
             good_materials, quad);
    struct scene s;
    expect_loads("lens.json", text, &s);
    if (!s.num_tris)
        return;
    EXPECT(s.camera.aperture == 0.05f && s.camera.focus_distance == 3.5f, "static camera lens: aperture %g, focus %g",
           s.camera.aperture, s.camera.focus_distance);
    EXPECT(s.camera_path.num_keys == 2, "lens path keys %d", s.camera_path.num_keys);
    if (s.camera_path.num_keys == 2) {
        const struct camera *k0 = &s.camera_path.keys[0].cam, *k1 = &s.camera_path.keys[1].cam;
        EXPECT(k0->aperture == 0.0f && k0->focus_distance == 0.0f, "path key 0 lens: aperture %g, focus %g",
               k0->aperture, k0->focus_distance);
        EXPECT(k1->aperture == 0.125f && k1->focus_distance == 2.0f, "path key 1 lens: aperture %g, focus %g",
               k1->aperture, k1->focus_distance);
    }

    /* camera files: the same reader, and the writer's output reads back bit for bit */
    struct camera cams[2] = {s.camera, s.camera};
    cams[1].aperture = 0.0f;
    cams[1].focus_distance = 0.0f;
    cams[1].vfov_deg = 30.0f;
    scene_destroy(&s);
    char path[512], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof path, "%s/lens-cameras.json", dir);
    EXPECT(cameras_write_json(path, cams, 2, "lens", "pt", 64, 32, 1, msg) == 0, "cameras_write_json: %s", msg);
    struct camera *back = NULL;
    int n = 0;
    int rc = scene_cameras_load(path, &back, &n, msg);
    EXPECT(rc == 0 && n == 2, "camera file with lens keys should load (%d cameras): %s", n, rc == 0 ? "" : msg);
    if (rc == 0 && n == 2) {
        EXPECT(back[0].aperture == cams[0].aperture && back[0].focus_distance == cams[0].focus_distance,
               "camera file lens round trip: aperture %g, focus %g", back[0].aperture, back[0].focus_distance);
        EXPECT(back[1].aperture == 0.0f && back[1].focus_distance == 0.0f && back[1].vfov_deg == 30.0f,
               "camera file pinhole round trip");
    }
    free(back);
    /* a pinhole camera writes no lens keys; the lens camera writes both */
    FILE *f = fopen(path, "rb");
    EXPECT(f != NULL, "cannot read %s", path);
    if (f) {
        static char written[1 << 14];
        size_t len = fread(written, 1, sizeof written - 1, f);
        fclose(f);
        written[len] = '\0';
        int apertures = 0, focuses = 0;
        for (const char *p = written; (p = strstr(p, "\"aperture\"")); p++)
            apertures++;
        for (const char *p = written; (p = strstr(p, "\"focus_distance\"")); p++)
            focuses++;
        EXPECT(apertures == 1 && focuses == 1,
               "camera file has %d aperture and %d focus_distance keys, expected 1 and 1", apertures, focuses);
    }
    /* a bad lens key in a camera file names the file and the key */
    snprintf(path, sizeof path, "%s/bad-lens-cameras.json", dir);
    write_file("bad-lens-cameras.json", "{\"format\": \"restir-cameras 1\", \"cameras\": [{\"position\": [0, 0, 1], "
                                        "\"look_at\": [0, 0, 0], \"focus_distance\": -0.5}]}");
    back = NULL;
    rc = scene_cameras_load(path, &back, &n, msg);
    EXPECT(rc != 0 && strstr(msg, path) && strstr(msg, "cameras[0].focus_distance"),
           "camera file with focus_distance -0.5 should be refused naming the file and key: %s", rc ? msg : "loaded");
    if (rc == 0)
        free(back);
    else
        printf("refused as expected: %s\n", msg);
}

/* The complete example of docs/SCENES.md (its first json block) loads and renders what it says. */
static void test_docs_example(void)
{
    const char *data = getenv("RESTIR_TEST_DATA");
    EXPECT(data != NULL, "RESTIR_TEST_DATA is not set (run through ctest)");
    if (!data)
        return;
    char path[1024], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof path, "%s/../../docs/SCENES.md", data);
    FILE *f = fopen(path, "rb");
    EXPECT(f != NULL, "cannot read %s", path);
    if (!f)
        return;
    static char doc[1 << 16];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = '\0';
    char *begin = strstr(doc, "```json\n"), *end = begin ? strstr(begin + 8, "```") : NULL;
    EXPECT(begin && end, "docs/SCENES.md has no json block");
    if (!begin || !end)
        return;
    begin += 8;
    *end = '\0';
    struct scene s;
    int rc = scene_json_parse(begin, (size_t)(end - begin), "docs/SCENES.md example", NULL, &s, msg);
    EXPECT(rc == 0, "the example of docs/SCENES.md does not load: %s", msg);
    if (rc != 0)
        return;
    EXPECT(strcmp(s.name, "lamp-and-box") == 0 && s.num_textures == 1 && s.num_emitters == 2 &&
               s.camera_path.num_keys == 3,
           "example: name %s, %d textures, %d emitters, %d path keys", s.name, s.num_textures, s.num_emitters,
           s.camera_path.num_keys);
    scene_destroy(&s);
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/restir-scene-json-XXXXXX");
    if (!mkdtemp(dir)) {
        EXPECT(0, "cannot make a temporary folder");
        return test_finish();
    }
    test_good_scene();
    test_errors();
    test_lens();
    test_docs_example();
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    EXPECT(system(cmd) == 0, "cannot remove %s", dir);
    return test_finish();
}
