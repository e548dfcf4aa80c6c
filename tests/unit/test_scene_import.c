/* test_scene_import.c: mesh files through assimp (scene_import.c). Every glTF 2.0 sample of the
 * assimp-testmodels package either loads or is refused with a message naming it; the package's
 * broken files are refused without crashing; small OBJ and glTF files written here check the
 * transforms (exact scaling, mirrored winding), material mapping and overrides, NaN refusal, and
 * a glTF as a whole scene (emitters with KHR_materials_emissive_strength, its camera, a fitted
 * camera and the camera path). */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "scene/scene.h"
#include "scene/scene_import.h"
#include "test_util.h"

#define MODELS "/usr/share/assimp/models"

/* ---- file lists ---------------------------------------------------------------------------- */

struct file_list {
    int n, cap;
    char **paths;
};

static int has_ext(const char *path, const char *const *exts)
{
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/'))
        return 0;
    for (int i = 0; exts[i]; i++)
        if (strcmp(dot + 1, exts[i]) == 0)
            return 1;
    return 0;
}

/* Every regular file under dir (recursively) whose extension is in want (NULL: any) and not in
 * skip (NULL: none). */
static void collect(const char *dir, const char *const *want, const char *const *skip, struct file_list *l)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            collect(path, want, skip, l);
        } else if (S_ISREG(st.st_mode) && (!want || has_ext(path, want)) && !(skip && has_ext(path, skip))) {
            if (l->n == l->cap) {
                l->cap = l->cap ? 2 * l->cap : 64;
                l->paths = realloc(l->paths, sizeof(char *) * (size_t)l->cap);
            }
            l->paths[l->n++] = strdup(path);
        }
    }
    closedir(d);
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static void list_sort(struct file_list *l)
{
    if (l->n > 1)
        qsort(l->paths, (size_t)l->n, sizeof(char *), cmp_str);
}

static void list_free(struct file_list *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->paths[i]);
    free(l->paths);
    memset(l, 0, sizeof(*l));
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* ---- helpers ------------------------------------------------------------------------------- */

/* One import on a fresh builder (material -1, object -1). Returns the triangle count or -1; on
 * success the scene is also finished (scene_builder_end must accept what the import added) and
 * *all_finite tells whether every vertex is finite. */
static int load_one(const char *path, char *msg, int *end_ok, int *all_finite)
{
    struct scene s;
    struct scene_builder b;
    scene_builder_begin(&b, &s, "t");
    msg[0] = '\0';
    int n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    *end_ok = 0;
    *all_finite = 1;
    if (n > 0) {
        for (int i = 0; i < s.num_verts; i++)
            if (!v3_is_finite(s.verts[i]))
                *all_finite = 0;
        char emsg[RESTIR_MSG_LEN];
        *end_ok = scene_builder_end(&b, emsg) == 0;
        if (!*end_ok)
            printf("  scene_builder_end refused %s: %s\n", path, emsg);
        EXPECT(s.num_tris == n, "%s: %d triangles reported, %d in the scene", path, n, s.num_tris);
    }
    scene_destroy(&s);
    return n;
}

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    fputs(text, f);
    return fclose(f);
}

/* Writes text to path and imports it into a new scene s (the caller destroys s): the triangles
 * added, or -1 with msg. */
static int import_text(const char *path, const char *text, struct scene *s, char *msg)
{
    struct scene_builder b;
    write_file(path, text);
    scene_builder_begin(&b, s, "t");
    return scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
}

static const char *rel(const char *path)
{
    return strncmp(path, MODELS "/", strlen(MODELS) + 1) == 0 ? path + strlen(MODELS) + 1 : path;
}

/* ---- 1. the glTF 2.0 samples ---------------------------------------------------------------- */

static void test_gltf2_samples(void)
{
    static const char *const exts[] = {"gltf", "glb", NULL};
    struct file_list l = {0};
    collect(MODELS "/glTF2", exts, NULL, &l);
    list_sort(&l);
    int loaded = 0, refused = 0;
    for (int i = 0; i < l.n; i++) {
        char msg[RESTIR_MSG_LEN];
        int end_ok, finite;
        int n = load_one(l.paths[i], msg, &end_ok, &finite);
        if (n > 0) {
            loaded++;
            printf("OK %6d tris  %s\n", n, rel(l.paths[i]));
            EXPECT(end_ok, "%s: loaded but scene_builder_end refused it", l.paths[i]);
            EXPECT(finite, "%s: loaded with non-finite vertices", l.paths[i]);
        } else {
            refused++;
            printf("REFUSED       %s: %s\n", rel(l.paths[i]), msg);
            EXPECT(n == -1, "%s: returned %d", l.paths[i], n);
            EXPECT(msg[0] && strstr(msg, l.paths[i]), "%s: the message does not name the file: '%s'", l.paths[i], msg);
        }
    }
    printf("glTF2: %d files, %d loaded, %d refused\n", l.n, loaded, refused);
    /* assimp-testmodels 5.2.5~ds0-1 has 46, of which 24 load with assimp 5.2.5; the others are
     * broken on purpose or hold only points and lines (Mesh_PrimitiveMode_00-03, 07-10). */
    EXPECT(loaded >= 22, "only %d glTF 2.0 files loaded", loaded);
    list_free(&l);

    /* Specific ones: the Khronos Box (not in Debian's package, which strips it) and BoxTextured. */
    const char *box = MODELS "/glTF2/Box/glTF/Box.gltf", *textured = MODELS "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    int specific = 0;
    const char *const must[] = {box, textured};
    for (int k = 0; k < 2; k++) {
        if (!file_exists(must[k])) {
            printf("(%s is not installed)\n", rel(must[k]));
            continue;
        }
        specific++;
        char msg[RESTIR_MSG_LEN];
        int end_ok, finite;
        int n = load_one(must[k], msg, &end_ok, &finite);
        EXPECT(n == 12, "%s: %d triangles (want 12): %s", must[k], n, n < 0 ? msg : "");
    }
    EXPECT(specific > 0, "neither %s nor %s is installed", box, textured);
}

/* ---- 2. broken files ------------------------------------------------------------------------ */

/* Broken files that assimp 5.2.5 repairs rather than refuses, and how: loading them is fine as
 * long as what loads is sound. */
static const char *assimp_repairs(const char *path)
{
    static const char *const repaired[][2] = {
        {"invalid/malformed2.obj", "assimp gives the faces of the unknown material its default material"},
        {"glTF2/IndexOutOfRange/IndexOutOfRange.gltf",
         "assimp drops the faces with out-of-range indices (11 of 12 remain); the import says so"},
    };
    for (size_t i = 0; i < sizeof repaired / sizeof repaired[0]; i++)
        if (strcmp(rel(path), repaired[i][0]) == 0)
            return repaired[i][1];
    return NULL;
}

/* Loaded or refused (never a crash); where refusal is required, refused with the file named. */
static void check_broken(const char *path, int may_load, int *loaded, int *refused)
{
    const char *repair = assimp_repairs(path);
    if (repair) {
        printf("  (%s: %s)\n", rel(path), repair);
        may_load = 1;
    }
    char msg[RESTIR_MSG_LEN];
    int end_ok, finite;
    int n = load_one(path, msg, &end_ok, &finite);
    if (n > 0) {
        (*loaded)++;
        printf("OK %6d tris  %s\n", n, rel(path));
        EXPECT(may_load, "%s: loaded (%d triangles) but must be refused", path, n);
        EXPECT(finite && end_ok, "%s: loaded with non-finite vertices or refused by scene_builder_end", path);
    } else {
        (*refused)++;
        printf("REFUSED       %s: %s\n", rel(path), msg);
        EXPECT(msg[0] && strstr(msg, path), "%s: the message does not name the file: '%s'", path, msg);
    }
}

static void test_broken_files(void)
{
    static const char *const skip[] = {"bin", "png", "jpg", "jpeg", "txt", NULL};
    struct {
        const char *dir;
        int may_load;
    } groups[] = {
        {MODELS "/invalid", 0},
        {MODELS "-nonbsd/invalid", 0},
        {MODELS "/glTF2/wrongTypes", 0},
        {MODELS "/glTF2/IndexOutOfRange", 0},
        {MODELS "/glTF2/MissingBin", 0},
        {MODELS "/glTF2/SchemaFailures", 0},
        /* Only the normals are broken (NaN); the positions are fine and normals are not used. */
        {MODELS "/glTF2/BoxBadNormals-glTF-Binary", 1},
        {MODELS "/glTF2/BoxWithInfinites-glTF-Binary", 0},
    };
    for (size_t g = 0; g < sizeof groups / sizeof groups[0]; g++) {
        struct file_list l = {0};
        collect(groups[g].dir, NULL, skip, &l);
        list_sort(&l);
        int loaded = 0, refused = 0;
        for (int i = 0; i < l.n; i++)
            check_broken(l.paths[i], groups[g].may_load, &loaded, &refused);
        if (l.n > 0)
            printf("%s: %d files, %d loaded, %d refused\n", rel(groups[g].dir), l.n, loaded, refused);
        list_free(&l);
    }
    /* Named: the infinite vertices must be refused, the bad normals must not matter, and a header
     * count no file of that size can hold is refused before assimp allocates for it (16 GB). */
    char msg[RESTIR_MSG_LEN];
    int end_ok, finite;
    const char *oom = MODELS "/invalid/OutOfMemory.off";
    if (file_exists(oom)) {
        EXPECT(load_one(oom, msg, &end_ok, &finite) == -1 && strstr(msg, "header claims"),
               "%s must be refused by the header check: %s", oom, msg);
    }
    const char *inf = MODELS "/glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb";
    const char *badn = MODELS "/glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb";
    if (file_exists(inf)) {
        EXPECT(load_one(inf, msg, &end_ok, &finite) == -1, "%s must be refused", inf);
        EXPECT(strstr(msg, "not finite") != NULL, "%s: refused for another reason: %s", inf, msg);
    }
    if (file_exists(badn))
        EXPECT(load_one(badn, msg, &end_ok, &finite) == 12 && finite && end_ok, "%s must load: %s", badn, msg);
}

/* Files that load only in part say so: the scene keeps a line naming the file and what
 * was lost, and scene.strict refuses the file with the same words; zero-area triangles are said but
 * never refused; a clean file has no note. */
static void test_partial_loads(const char *dir)
{
    struct {
        const char *path, *want[2];
    } cases[] = {
        {MODELS "/glTF2/IndexOutOfRange/IndexOutOfRange.gltf", {"1 of 12 triangles dropped", "out-of-range"}},
        {MODELS "/invalid/malformed2.obj", {"failed to locate material", "Ignoring empty face"}},
    };
    char msg[RESTIR_MSG_LEN];
    struct scene s;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        if (!file_exists(cases[k].path))
            continue;
        EXPECT(scene_import_file(cases[k].path, &s, msg) == 0, "%s loads: %s", cases[k].path, msg);
        const char *notes = s.load_notes ? s.load_notes : "";
        EXPECT(strstr(notes, cases[k].path) && strstr(notes, cases[k].want[0]) && strstr(notes, cases[k].want[1]),
               "%s: the load notes say what was lost: '%s'", rel(cases[k].path), notes);
        scene_destroy(&s);
        const struct scene_load_desc strict = {.strict = 1};
        EXPECT(scene_import_file_with(cases[k].path, &strict, &s, msg) == -1 && strstr(msg, cases[k].path) &&
                   strstr(msg, cases[k].want[0]),
               "%s: scene.strict refuses it with the same words: '%s'", rel(cases[k].path), msg);
    }
    char path[512];
    snprintf(path, sizeof path, "%s/flatpart.obj", dir); /* one triangle of zero area beside a good one */
    write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
    const struct scene_load_desc strict = {.strict = 1};
    EXPECT(scene_import_file_with(path, &strict, &s, msg) == 0, "zero-area triangles are never refused: %s", msg);
    EXPECT(s.load_notes && strstr(s.load_notes, "1 of 2 triangles skipped"), "and said: '%s'",
           s.load_notes ? s.load_notes : "");
    scene_destroy(&s);
    const char *clean = MODELS "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    if (file_exists(clean)) {
        EXPECT(scene_import_file_with(clean, &strict, &s, msg) == 0 && !s.load_notes, "%s: no notes (%s)", clean,
               s.load_notes ? s.load_notes : msg);
        scene_destroy(&s);
    }
}

/* ---- 3. small OBJ (and PLY) files written here ----------------------------------------------- */

static void test_obj(const char *dir)
{
    char path[512], msg[RESTIR_MSG_LEN];
    struct scene s;
    struct scene_builder b;

    /* A NaN vertex is refused, naming the file (and the vertex). */
    snprintf(path, sizeof path, "%s/nan.obj", dir);
    write_file(path, "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    scene_builder_begin(&b, &s, "t");
    int n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n == -1 && strstr(msg, path) && strstr(msg, "vertex 0"), "NaN vertex: %d, '%s'", n, msg);
    scene_destroy(&s);

    /* One triangle scaled by 2: exactly doubled, in the file's order; front normal +z. */
    snprintf(path, sizeof path, "%s/tri.obj", dir);
    write_file(path, "v 0.1 0.2 0.3\nv 1.1 0.2 0.3\nv 0.1 1.7 0.3\nf 1 2 3\n");
    const float scale2[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
    scene_builder_begin(&b, &s, "t");
    int mat = scene_add_material(
        &b, (struct material){
                .base_color = v3s(0.5f), .metallic = 0, .roughness = 1, .emission = v3s(0), .lambert_only = 0});
    n = scene_import_mesh(&b, path, scale2, mat, NULL, 0, 7, msg);
    EXPECT(n == 1, "tri.obj: %d (%s)", n, msg);
    if (n == 1) {
        const float want[3][3] = {{0.1f, 0.2f, 0.3f}, {1.1f, 0.2f, 0.3f}, {0.1f, 1.7f, 0.3f}};
        for (int v = 0; v < 3; v++) {
            vec3 p = s.verts[s.indices[v]];
            EXPECT(p.x == 2 * want[v][0] && p.y == 2 * want[v][1] && p.z == 2 * want[v][2],
                   "vertex %d: (%.9g %.9g %.9g)", v, (double)p.x, (double)p.y, (double)p.z);
        }
        EXPECT(s.tri_material[0] == mat && s.tri_object[0] == 7, "material %d object %d", s.tri_material[0],
               s.tri_object[0]);
        EXPECT(scene_builder_end(&b, msg) == 0, "%s", msg);
        EXPECT(s.tri_normal[0].z > 0.999f, "unmirrored normal (%g %g %g)", (double)s.tri_normal[0].x,
               (double)s.tri_normal[0].y, (double)s.tri_normal[0].z);
    }
    scene_destroy(&s);

    /* Mirrored in x (determinant -1): the mirror image of a +z-facing triangle still faces +z, which
     * needs the winding flipped. */
    const float mirror[16] = {-1, 0, 0, 3, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    scene_builder_begin(&b, &s, "t");
    mat = scene_add_material(
        &b, (struct material){
                .base_color = v3s(0.5f), .metallic = 0, .roughness = 1, .emission = v3s(0), .lambert_only = 0});
    n = scene_import_mesh(&b, path, mirror, mat, NULL, 0, -1, msg);
    EXPECT(n == 1, "tri.obj mirrored: %d (%s)", n, msg);
    if (n == 1) {
        EXPECT(s.verts[0].x == 3.0f - 0.1f && s.verts[1].x == 3.0f - 0.1f && s.verts[2].x == 3.0f - 1.1f,
               "mirrored vertices not in flipped order: x %g %g %g", (double)s.verts[0].x, (double)s.verts[1].x,
               (double)s.verts[2].x);
        EXPECT(scene_builder_end(&b, msg) == 0, "%s", msg);
        EXPECT(s.tri_normal[0].z > 0.999f, "mirrored normal (%g %g %g)", (double)s.tri_normal[0].x,
               (double)s.tri_normal[0].y, (double)s.tri_normal[0].z);
    }
    scene_destroy(&s);

    /* Materials, overrides, objects, degenerate triangles and lines. */
    char mtl[512];
    snprintf(mtl, sizeof mtl, "%s/two.mtl", dir);
    write_file(mtl, "newmtl red\nKd 2 0.1 0\nNs 1000\n\nnewmtl blue\nKd 0 0 0.9\nPm 0.5\nPr 0.25\n\n"
                    "newmtl lamp\nKd 0 0 0\nKe 3 2 1\n\nnewmtl bad\nKd 1 1 1\nKe -1 0 0\n");
    snprintf(path, sizeof path, "%s/two.obj", dir);
    write_file(path, "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                     "o first\nusemtl red\nf 1 2 3\nf 1 2 4\nl 1 3\n"
                     "o second\nusemtl blue\nf 2 4 5\nusemtl lamp\nf 1 2 3\n");
    scene_builder_begin(&b, &s, "t");
    n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n == 3, "two.obj: %d triangles (want 3: one degenerate skipped, the line ignored): %s", n, msg);
    if (n == 3) {
        EXPECT(s.num_objects == 2, "two.obj: %d objects", s.num_objects);
        EXPECT(s.num_materials == 3, "two.obj: %d materials (the unused 'bad' must not be added)", s.num_materials);
        const struct material *red = &s.materials[s.tri_material[0]];
        const struct material *blue = &s.materials[s.tri_material[1]];
        const struct material *lamp = &s.materials[s.tri_material[2]];
        EXPECT(red->base_color.x == 1.0f && fabsf(red->base_color.y - 0.1f) < 1e-6f && red->metallic == 0.0f,
               "red: (%g %g %g) metallic %g", (double)red->base_color.x, (double)red->base_color.y,
               (double)red->base_color.z, (double)red->metallic);
        EXPECT_NEAR(red->roughness, sqrt(sqrt(2.0 / 1002.0)), 1e-6, "roughness from Ns 1000");
        EXPECT(fabsf(blue->base_color.z - 0.9f) < 1e-6f && blue->metallic == 0.5f && blue->roughness == 0.25f,
               "blue: b %g metallic %g roughness %g", (double)blue->base_color.z, (double)blue->metallic,
               (double)blue->roughness);
        EXPECT(lamp->emission.x == 3.0f && lamp->emission.y == 2.0f && lamp->emission.z == 1.0f,
               "lamp emission (%g %g %g)", (double)lamp->emission.x, (double)lamp->emission.y,
               (double)lamp->emission.z);
        EXPECT(s.tri_object[0] != s.tri_object[1] && s.tri_object[1] == s.tri_object[2],
               "objects %d %d %d: one per OBJ object", s.tri_object[0], s.tri_object[1], s.tri_object[2]);
        EXPECT(scene_builder_end(&b, msg) == 0, "%s", msg);
        EXPECT(s.num_emitters == 1, "two.obj: %d emitters", s.num_emitters);
    }
    scene_destroy(&s);

    /* Overrides by name; an unknown name fails naming it (and nothing else). */
    scene_builder_begin(&b, &s, "t");
    int green = scene_add_material(
        &b, (struct material){
                .base_color = v3(0, 1, 0), .metallic = 0, .roughness = 1, .emission = v3s(0), .lambert_only = 0});
    struct scene_material_override ov[2] = {{"red", green}, {"lamp", green}};
    n = scene_import_mesh(&b, path, NULL, -1, ov, 2, -1, msg);
    EXPECT(n == 3, "two.obj with overrides: %d (%s)", n, msg);
    if (n == 3) {
        EXPECT(s.tri_material[0] == green && s.tri_material[2] == green && s.tri_material[1] != green,
               "overridden materials %d %d %d (green %d)", s.tri_material[0], s.tri_material[1], s.tri_material[2],
               green);
        EXPECT(s.num_materials == 2, "%d materials: only blue is added besides ours", s.num_materials);
    }
    scene_destroy(&s);
    scene_builder_begin(&b, &s, "t");
    green = scene_add_material(
        &b, (struct material){
                .base_color = v3(0, 1, 0), .metallic = 0, .roughness = 1, .emission = v3s(0), .lambert_only = 0});
    struct scene_material_override unknown[2] = {{"red", green}, {"no-such-material", green}};
    n = scene_import_mesh(&b, path, NULL, -1, unknown, 2, -1, msg);
    EXPECT(n == -1 && strstr(msg, "'no-such-material'") && strstr(msg, path) && !strstr(msg, "blue"),
           "unknown override: %d '%s'", n, msg);
    scene_destroy(&s);

    /* A negative emission is refused, naming the file and the material. */
    snprintf(path, sizeof path, "%s/bad.obj", dir);
    write_file(path, "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl bad\nf 1 2 3\n");
    scene_builder_begin(&b, &s, "t");
    n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n == -1 && strstr(msg, path) && strstr(msg, "'bad'"), "negative emission: %d '%s'", n, msg);
    scene_destroy(&s);

    /* Only lines or degenerate triangles: "no triangles". */
    snprintf(path, sizeof path, "%s/flat.obj", dir);
    write_file(path, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nl 1 2\n");
    scene_builder_begin(&b, &s, "t");
    n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n == -1 && strstr(msg, path) && strstr(msg, "no triangles"), "degenerate only: %d '%s'", n, msg);
    scene_destroy(&s);

    /* A header count the file cannot hold is refused before assimp allocates for it (it would
     * zero-fill 12 GB for this one). */
    snprintf(path, sizeof path, "%s/huge.ply", dir);
    write_file(path, "ply\nformat binary_little_endian 1.0\ncomment element vertex 1\nelement vertex 1000000000\n"
                     "property float x\nproperty float y\nproperty float z\nend_header\n");
    scene_builder_begin(&b, &s, "t");
    n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n == -1 && strstr(msg, path) && strstr(msg, "header claims 1000000000"), "huge PLY header: %d '%s'", n, msg);
    scene_destroy(&s);

    /* A header that declares the vertices twice (a misspelled end_header lets the next copy of
     * the header in): assimp 5.2 sizes the mesh by the first count and writes the second past
     * its end, a heap overflow that need not crash (found by fuzzing), so it is refused first.
     * A comment naming an element twice is no declaration. */
    snprintf(path, sizeof path, "%s/twice.ply", dir);
    n = import_text(path,
                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nenl_header\n0 0 0\nply\nelement vertex 8\nproperty float x\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n",
                    &s, msg);
    EXPECT(n == -1 && strstr(msg, path) && strstr(msg, "declares element 'vertex' twice"), "PLY vertex twice: %d '%s'",
           n, msg);
    scene_destroy(&s);
    snprintf(path, sizeof path, "%s/comment.ply", dir);
    n = import_text(path,
                    "ply\nformat ascii 1.0\ncomment element vertex 3\nelement vertex 3\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                    &s, msg);
    EXPECT(n == 1, "a PLY whose comment names an element: %d '%s'", n, msg);
    scene_destroy(&s);

    /* A file that does not exist. */
    snprintf(path, sizeof path, "%s/missing.obj", dir);
    scene_builder_begin(&b, &s, "t");
    n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n == -1 && strstr(msg, path), "missing file: %d '%s'", n, msg);
    scene_destroy(&s);
}

/* ---- 4. a glTF as a whole scene ------------------------------------------------------------- */

static void base64(const unsigned char *in, size_t n, char *out)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)in[i] << 16 | (i + 1 < n ? (unsigned)in[i + 1] << 8 : 0u) | (i + 2 < n ? in[i + 2] : 0u);
        out[o++] = tab[v >> 18 & 63];
        out[o++] = tab[v >> 12 & 63];
        out[o++] = i + 1 < n ? tab[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? tab[v & 63] : '=';
    }
    out[o] = '\0';
}

/* A floor quad (two triangles, material "Floor") and a downward-facing lamp triangle (material
 * "Lamp": emissive factor (1, 0.5, 0.25) times KHR_materials_emissive_strength 4), optionally with
 * a perspective camera at (0, 1, 5) looking down -z (yfov 0.7, aspect 1.5). */
static void write_lamp_gltf_floor(const char *path, int with_camera, const char *floor_alpha);

static void write_lamp_gltf(const char *path, int with_camera) { write_lamp_gltf_floor(path, with_camera, ""); }

/* floor_alpha: "" or glTF keys added to the Floor material, e.g. "\"alphaMode\":\"MASK\"," */
static void write_lamp_gltf_floor(const char *path, int with_camera, const char *floor_alpha)
{
    static const float pos[9][3] = {
        {-1, 0, -1},       {-1, 0, 1},       {1, 0, 1},    {-1, 0, -1}, {1, 0, 1}, {1, 0, -1}, /* floor, facing +y */
        {-0.5f, 2, -0.5f}, {0.5f, 2, -0.5f}, {0, 2, 0.5f},                                     /* lamp, facing -y */
    };
    unsigned char bytes[sizeof pos];
    memcpy(bytes, pos, sizeof pos); /* glTF buffers are little-endian, as is every machine we run on */
    char b64[2 * sizeof pos];
    base64(bytes, sizeof bytes, b64);
    char json[8192];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_materials_emissive_strength\"],"
             "\"scene\":0,\"scenes\":[{\"nodes\":[0%s]}],"
             "\"nodes\":[{\"mesh\":0}%s],"
             "%s"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0},"
             "{\"attributes\":{\"POSITION\":1},\"material\":1}]}],"
             "\"materials\":[{\"name\":\"Floor\",%s\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.4,0.6,0.75],"
             "\"metallicFactor\":0.25,\"roughnessFactor\":0.5}},"
             "{\"name\":\"Lamp\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
             "\"emissiveFactor\":[1,0.5,0.25],"
             "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}}],"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":72},"
             "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":36}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\","
             "\"min\":[-1,0,-1],\"max\":[1,0,1]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
             "\"min\":[-0.5,2,-0.5],\"max\":[0.5,2,0.5]}]}\n",
             with_camera ? ",1" : "", with_camera ? ",{\"camera\":0,\"translation\":[0,1,5]}" : "",
             with_camera ? "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7,"
                           "\"aspectRatio\":1.5,\"znear\":0.01,\"zfar\":100}}],"
                         : "",
             floor_alpha, sizeof pos, b64);
    write_file(path, json);
}

/* KHR_texture_transform, texCoord and sampler wraps on the glTF sample that tests them:
 * the lookups of "Offset U" and "Rotation" against glTF's formula by hand, CLAMP_TO_EDGE read. */
static void test_texture_transform(void)
{
    const char *path = MODELS "/glTF2/textureTransform/TextureTransformTest.gltf";
    if (!file_exists(path)) {
        EXPECT(0, "%s is missing (make test installs assimp-testmodels)", path);
        return;
    }
    struct scene s;
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, &s, "tt");
    int n = scene_import_mesh(&b, path, NULL, -1, NULL, 0, -1, msg);
    EXPECT(n > 0, "%s: %s", path, msg);
    int offset_u = -1, rotation = -1;
    for (int t = 0; t < s.num_tris; t++) {
        const struct material *m = &s.materials[s.tri_material[t]];
        const float *x = m->base_color_lookup.xform;
        if (!m->base_color_lookup.has_xform)
            continue;
        if (x[0] == 1.0f && x[2] == 0.5f && x[5] == 0.0f) /* offset [0.5, 0] and nothing else */
            offset_u = s.tri_material[t];
        if (fabsf(x[0] - 0.92387953f) < 1e-6f && fabsf(x[2] - 0.38268343f) < 1e-6f) /* rotation pi/8 alone */
            rotation = s.tri_material[t];
    }
    EXPECT(offset_u >= 0 && rotation >= 0, "materials with offset %d / rotation %d", offset_u, rotation);
    if (offset_u >= 0) { /* offset [0.5, 0]: u + 0.5, v unchanged (both UV spaces) */
        const struct texture_lookup *l = &s.materials[offset_u].base_color_lookup;
        const float want[6] = {1, 0, 0.5f, 0, 1, 0};
        for (int i = 0; i < 6; i++)
            EXPECT(fabsf(l->xform[i] - want[i]) < 1e-6f, "Offset U xform[%d] = %g, want %g", i, l->xform[i], want[i]);
        EXPECT(l->wrap_u == WRAP_CLAMP && l->wrap_v == WRAP_CLAMP && l->uv_set == 0, "sampler 0 clamps (33071)");
    }
    if (rotation >= 0) { /* glTF: u' = cos r u + sin r v, v' = -sin r u + cos r v with v down, r = 0.39 */
        const struct texture_lookup *l = &s.materials[rotation].base_color_lookup;
        const double r = 0.39269908169872414, u = 0.3, vg = 0.2; /* vg: glTF's v; assimp's is 1 - vg */
        const double ug2 = cos(r) * u + sin(r) * vg, vg2 = -sin(r) * u + cos(r) * vg;
        const float ua = l->xform[0] * 0.3f + l->xform[1] * 0.8f + l->xform[2];
        const float va = l->xform[3] * 0.3f + l->xform[4] * 0.8f + l->xform[5];
        EXPECT(fabs(ua - ug2) < 1e-5 && fabs(va - (1.0 - vg2)) < 1e-5, "Rotation maps (0.3, 0.8) to (%g, %g), want (%g, %g)",
               ua, va, ug2, 1.0 - vg2);
    }
    scene_builder_end(&b, msg);
    scene_destroy(&s);
}

static void test_whole_scene(const char *dir)
{
    char msg[RESTIR_MSG_LEN], path[512];
    struct scene s;

    /* The Box has no emitters: it loads under the default sky, as glTF viewers show it. */
    const char *box = MODELS "/glTF2/Box/glTF/Box.gltf";
    if (!file_exists(box))
        box = MODELS "/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    int rc = scene_import_file(box, &s, msg);
    EXPECT(rc == 0 && s.num_emitters == 0 && s.env != NULL && s.env_prob == 1.0f, "%s as a scene: %d '%s'", box, rc,
           rc ? msg : "");
    if (rc == 0)
        scene_destroy(&s);

    /* The package's one glTF with an emissive material (grep emissiveFactor): ClearCoatTest's
     * "LabelMaterial", emissive factor 1. It has no camera: a fitted one. */
    const char *cc = MODELS "/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
    if (file_exists(cc)) {
        rc = scene_import_file(cc, &s, msg);
        EXPECT(rc == 0 && s.num_emitters > 0, "%s as a scene: %d, %d emitters: %s", cc, rc, s.num_emitters,
               rc ? msg : "");
        printf("%s as a scene: %d triangles, %d emitters, %d materials, %d objects\n", rel(cc), s.num_tris,
               s.num_emitters, s.num_materials, s.num_objects);
        scene_destroy(&s);
    }

    /* Ours: strength, camera and winding known exactly. */
    snprintf(path, sizeof path, "%s/lamp.gltf", dir);
    write_lamp_gltf(path, 1);
    rc = scene_import_file(path, &s, msg);
    EXPECT(rc == 0, "%s: %s", path, msg);
    if (rc == 0) {
        EXPECT(strcmp(s.name, "lamp") == 0, "scene name '%s'", s.name);
        EXPECT(s.num_tris == 3 && s.num_emitters == 1, "%d triangles, %d emitters", s.num_tris, s.num_emitters);
        const struct material *floor = &s.materials[s.tri_material[0]];
        EXPECT(fabsf(floor->base_color.x - 0.2f) < 1e-6f && fabsf(floor->base_color.z - 0.6f) < 1e-6f &&
                   floor->metallic == 0.25f && floor->roughness == 0.5f && v3_max_component(floor->emission) == 0.0f,
               "floor material (%g %g %g) m %g r %g", (double)floor->base_color.x, (double)floor->base_color.y,
               (double)floor->base_color.z, (double)floor->metallic, (double)floor->roughness);
        if (s.num_emitters == 1) {
            vec3 le = s.emitters[0].Le;
            EXPECT(le.x == 4.0f && le.y == 2.0f && le.z == 1.0f, "lamp radiance (%g %g %g), want (4 2 1)", (double)le.x,
                   (double)le.y, (double)le.z);
            EXPECT(s.emitters[0].n.y < -0.999f, "lamp faces (%g %g %g), want down", (double)s.emitters[0].n.x,
                   (double)s.emitters[0].n.y, (double)s.emitters[0].n.z);
        }
        EXPECT(s.tri_normal[0].y > 0.999f && s.tri_normal[1].y > 0.999f, "floor faces up");
        struct camera c = s.camera;
        EXPECT(c.position.x == 0.0f && c.position.y == 1.0f && c.position.z == 5.0f, "camera at (%g %g %g)",
               (double)c.position.x, (double)c.position.y, (double)c.position.z);
        vec3 fwd = v3_normalize(v3_sub(c.target, c.position));
        EXPECT(fwd.z < -0.999f, "camera looks along (%g %g %g), want -z", (double)fwd.x, (double)fwd.y, (double)fwd.z);
        EXPECT(c.up.y > 0.999f, "camera up (%g %g %g)", (double)c.up.x, (double)c.up.y, (double)c.up.z);
        EXPECT_NEAR(c.vfov_deg, 0.7 * 180.0 / 3.14159265358979, 1e-3, "vertical fov from yfov 0.7");
        EXPECT(s.camera_path.num_keys == 2, "%d path keys", s.camera_path.num_keys);
        if (s.camera_path.num_keys == 2) {
            struct camera_key k0 = s.camera_path.keys[0], k1 = s.camera_path.keys[1];
            float moved = v3_length(v3_sub(k1.cam.position, k0.cam.position));
            EXPECT(k0.frame == 0.0f && k1.frame == 64.0f, "key frames %g %g", (double)k0.frame, (double)k1.frame);
            EXPECT_NEAR(moved, 0.1 * scene_diagonal(&s), 1e-4, "path moves a tenth of the diagonal");
            EXPECT(v3_length(v3_sub(k1.cam.target, k0.cam.target)) == 0.0f, "path keeps the target");
        }
    }
    scene_destroy(&s);

    /* glTF alpha: OPAQUE ignores baseColorFactor's alpha; MASK keeps its cutoff and that
     * alpha; BLEND is read as MASK at 0.5; a cutoff outside [0, 1] is refused by name. */
    const struct {
        const char *keys;
        int mask;
        float cutoff, alpha;
    } alpha_cases[] = {{"", 0, 0.5f, 1.0f},
                       {"\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3,", 1, 0.3f, 0.75f},
                       {"\"alphaMode\":\"BLEND\",", 1, 0.5f, 0.75f}};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/alpha%d.gltf", dir, k);
        write_lamp_gltf_floor(path, 0, alpha_cases[k].keys);
        rc = scene_import_file(path, &s, msg);
        EXPECT(rc == 0, "%s: %s", path, msg);
        if (rc != 0)
            continue;
        const struct material *floor = &s.materials[s.tri_material[0]];
        EXPECT(floor->alpha_mask == alpha_cases[k].mask &&
                   (!floor->alpha_mask ||
                    (floor->alpha_cutoff == alpha_cases[k].cutoff && floor->base_alpha == alpha_cases[k].alpha)),
               "alpha case %d: mask %d cutoff %g alpha %g", k, floor->alpha_mask, (double)floor->alpha_cutoff,
               (double)floor->base_alpha);
        scene_destroy(&s);
    }
    snprintf(path, sizeof path, "%s/alpha-bad.gltf", dir);
    write_lamp_gltf_floor(path, 0, "\"alphaMode\":\"MASK\",\"alphaCutoff\":2,");
    rc = scene_import_file(path, &s, msg);
    EXPECT(rc != 0 && strstr(msg, path) && strstr(msg, "alphaCutoff") && strstr(msg, "Floor"),
           "alphaCutoff 2 must be refused naming the file, material and key: %s", msg);

    /* Without a camera: one fitted to the bounds, looking at the centre from +z, above. */
    snprintf(path, sizeof path, "%s/lamp-nocam.gltf", dir);
    write_lamp_gltf(path, 0);
    rc = scene_import_file(path, &s, msg);
    EXPECT(rc == 0, "%s: %s", path, msg);
    if (rc == 0) {
        struct camera c = s.camera;
        vec3 centre = v3(0, 1, 0);
        float radius = 0.5f * scene_diagonal(&s);
        vec3 d = v3_sub(c.position, centre);
        EXPECT(v3_length(v3_sub(c.target, centre)) < 1e-5f, "fitted camera looks at (%g %g %g)", (double)c.target.x,
               (double)c.target.y, (double)c.target.z);
        EXPECT(d.z > 0.0f && d.y > 0.0f, "fitted camera at (%g %g %g): want +z and above", (double)c.position.x,
               (double)c.position.y, (double)c.position.z);
        EXPECT(radius / v3_length(d) <= sinf(0.5f * c.vfov_deg * RESTIR_PI / 180.0f) * 1.0001f,
               "bounding sphere (r %g at %g) does not fit vfov %g", (double)radius, (double)v3_length(d),
               (double)c.vfov_deg);
    }
    scene_destroy(&s);

    /* A file that does not exist: refused, naming it, scene left empty. */
    snprintf(path, sizeof path, "%s/none.glb", dir);
    rc = scene_import_file(path, &s, msg);
    EXPECT(rc == -1 && strstr(msg, path) && s.num_tris == 0, "missing file: %d '%s'", rc, msg);
}

int main(void)
{
    if (!file_exists(MODELS)) {
        EXPECT(0,
               "%s does not exist: the assimp test models are missing; `make test` installs the "
               "assimp-testmodels package",
               MODELS);
        return test_finish();
    }
    char dir[] = "/tmp/restir-import-XXXXXX";
    if (!mkdtemp(dir)) {
        EXPECT(0, "mkdtemp failed");
        return test_finish();
    }
    test_gltf2_samples();
    test_broken_files();
    test_obj(dir);
    test_partial_loads(dir);
    test_texture_transform();
    test_whole_scene(dir);

    /* Remove what we wrote (the folder holds only our files). */
    static const char *const ours[] = {"nan.obj",  "tri.obj",  "two.obj",   "two.mtl",         "bad.obj",
                                       "flat.obj", "huge.ply", "lamp.gltf", "lamp-nocam.gltf", "flatpart.obj", NULL};
    for (int i = 0; ours[i]; i++) {
        char p[512];
        snprintf(p, sizeof p, "%s/%s", dir, ours[i]);
        remove(p);
    }
    rmdir(dir);
    return test_finish();
}
