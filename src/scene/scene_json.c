/* scene_json.c: the readers of our JSON scene format (docs/SCENES.md) and of camera files.
 * Must never depend on the loader entry (scene_file.c): it dispatches to us, not back. */
#include "scene/scene_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/environment.h"
#include "scene/file_name.h"
#include "scene/scene_env.h"
#include "scene/scene_import.h"
#include "scene/scene_json_reader.h"
#include "scene/texture.h"

/* Largest magnitude accepted for a coordinate or radiance: beyond it float math overflows. */
#define SCENE_COORD_MAX 1e18

/* ---- camera ---- */

static const char *const camera_keys[] = {"position", "look_at", "up", "vfov", "aperture", "focus_distance", "frame",
                                          NULL};

static int read_camera(struct json_reader *r, const cJSON *v, const char *key, int with_frame, struct camera *cam,
                       float *frame)
{
    if (json_check_keys(r, v, key, camera_keys) != 0)
        return -1;
    if (!with_frame && cJSON_GetObjectItemCaseSensitive(v, "frame")) {
        char k[256];
        json_child_key(k, sizeof k, key, "frame", 0);
        return json_fail(r, k, "only camera_path keys have a frame");
    }
    if (json_get_vec3(r, v, key, "position", 1, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(0), &cam->position) != 0 ||
        json_get_vec3(r, v, key, "look_at", 1, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(0), &cam->target) != 0 ||
        json_get_vec3(r, v, key, "up", 0, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3(0, 1, 0), &cam->up) != 0 ||
        json_get_number(r, v, key, "vfov", 0, 1e-3, 179.0, 45.0f, &cam->vfov_deg) != 0 ||
        json_get_number(r, v, key, "aperture", 0, 0.0, SCENE_COORD_MAX, 0.0f, &cam->aperture) != 0 ||
        json_get_number(r, v, key, "focus_distance", 0, 0.0, SCENE_COORD_MAX, 0.0f, &cam->focus_distance) != 0)
        return -1;
    if (with_frame && json_get_number(r, v, key, "frame", 1, -1e9, 1e9, 0.0f, frame) != 0)
        return -1;
    vec3 view = v3_sub(cam->target, cam->position);
    if (!(v3_length(view) > 0.0f))
        return json_fail(r, key, "degenerate camera: position equals look_at");
    vec3 side = v3_cross(view, cam->up);
    if (!(v3_length(side) > 1e-6f * v3_length(view) * v3_length(cam->up)))
        return json_fail(r, key, "degenerate camera: up is zero or parallel to the view direction");
    return 0;
}

static int read_camera_path(struct json_reader *r, const cJSON *path)
{
    struct scene *s = r->b->s;
    const int n = cJSON_GetArraySize(path);
    if (n < 1)
        return json_fail(r, "camera_path", "needs at least one key");
    s->camera_path.keys = xcalloc((size_t)n, sizeof(struct camera_key));
    int i = 0;
    for (const cJSON *k = path->child; k; k = k->next, i++) {
        char key[64];
        json_child_key(key, sizeof key, "camera_path", NULL, i);
        struct camera_key *ck = &s->camera_path.keys[i];
        if (read_camera(r, k, key, 1, &ck->cam, &ck->frame) != 0)
            return -1;
        s->camera_path.num_keys = i + 1;
        if (i > 0 && !(ck->frame > s->camera_path.keys[i - 1].frame))
            return json_fail(r, key, "frame must be larger than the previous key's");
    }
    return 0;
}

/* ---- materials ---- */

static const char *const material_keys[] = {"name", "base_color", "metallic", "roughness", "emission",
                                            "emissive_strength", "lambert", "base_color_texture",
                                            "metallic_roughness_texture", "emission_texture", "normal_texture",
                                            "normal_scale", "alpha", "alpha_mode", "alpha_cutoff", "animation", NULL};

/* glTF alphaMode: "opaque" (default), "mask", or "blend" (read as mask, cutoff 0.5 unless given). */
static int read_alpha(struct json_reader *r, const cJSON *m, const char *key, struct material *mt)
{
    char k[96];
    json_child_key(k, sizeof k, key, "alpha_mode", 0);
    const cJSON *mode = cJSON_GetObjectItemCaseSensitive(m, "alpha_mode");
    if (mode && (!cJSON_IsString(mode) || (strcmp(mode->valuestring, "opaque") && strcmp(mode->valuestring, "mask") &&
                                           strcmp(mode->valuestring, "blend"))))
        return json_fail(r, k, "must be \"opaque\", \"mask\" or \"blend\"");
    mt->alpha_mask = mode && strcmp(mode->valuestring, "opaque") != 0;
    return json_get_number(r, m, key, "alpha", 0, 0.0, 1.0, 1.0f, &mt->base_alpha) != 0 ||
                   json_get_number(r, m, key, "alpha_cutoff", 0, 0.0, 1.0, 0.5f, &mt->alpha_cutoff) != 0
               ? -1
               : 0;
}

/* A path in the file: absolute, or relative to the file's folder. Returns -1 (msg naming key)
 * when it does not fit out. */
static int resolve_path(struct json_reader *r, const char *key, const char *name, char *out, size_t len)
{
    int n = name[0] == '/' || !*r->dir ? snprintf(out, len, "%s", name)
                                       : snprintf(out, len, "%s%s%s", r->dir, strcmp(r->dir, "/") ? "/" : "", name);
    return n >= 0 && (size_t)n < len ? 0 : json_fail(r, key, "path too long");
}

/* The texture map named by key of material object m (0 when absent), read on first use. */
static int texture_map(struct json_reader *r, const cJSON *m, const char *mkey, const char *key, int srgb, int *map)
{
    char k[128];
    json_child_key(k, sizeof k, mkey, key, 0);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(m, key);
    *map = 0;
    if (!v)
        return 0;
    if (!cJSON_IsString(v) || !*v->valuestring)
        return json_fail(r, k, "must be an image file name");
    char path[4096];
    if (resolve_path(r, k, v->valuestring, path, sizeof path) != 0)
        return -1;
    if ((*map = scene_texture_find(r->b->s, path, srgb)) > 0)
        return 0; /* read already, by this or another material */
    struct texture t;
    char tmsg[RESTIR_MSG_LEN];
    if (texture_load_file(path, srgb, &t, tmsg) != 0) {
        char why[2 * RESTIR_MSG_LEN];
        snprintf(why, sizeof why, "%s: %s: %s", r->file, k, tmsg);
        return scene_texture_unreadable(r->b, why) == 0 ? 0 : json_fail(r, k, "%s", tmsg);
    }
    *map = scene_add_texture(r->b, t, path, srgb);
    return 0;
}

static int read_materials(struct json_reader *r)
{
    int i = 0;
    for (const cJSON *m = r->materials ? r->materials->child : NULL; m; m = m->next, i++) {
        char key[64];
        json_child_key(key, sizeof key, "materials", NULL, i);
        if (json_check_keys(r, m, key, material_keys) != 0)
            return -1;
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(m, "name");
        if (!cJSON_IsString(name) || !*name->valuestring) {
            char k[80];
            json_child_key(k, sizeof k, key, "name", 0);
            return json_fail(r, k, name ? "must be a non-empty string" : "missing");
        }
        int j = 0;
        for (const cJSON *o = r->materials->child; o != m; o = o->next, j++) {
            const cJSON *on = cJSON_GetObjectItemCaseSensitive(o, "name");
            if (strcmp(on->valuestring, name->valuestring) == 0)
                return json_fail(r, key, "material name '%s' already used by materials[%d]", name->valuestring, j);
        }
        struct material mt = {0};
        float strength;
        if (json_get_vec3(r, m, key, "base_color", 0, 0.0, 1.0, v3s(0.8f), &mt.base_color) != 0 ||
            json_get_number(r, m, key, "metallic", 0, 0.0, 1.0, 0.0f, &mt.metallic) != 0 ||
            json_get_number(r, m, key, "roughness", 0, 0.0, 1.0, 1.0f, &mt.roughness) != 0 ||
            json_get_vec3(r, m, key, "emission", 0, 0.0, SCENE_COORD_MAX, v3s(0.0f), &mt.emission) != 0 ||
            json_get_number(r, m, key, "emissive_strength", 0, 0.0, SCENE_COORD_MAX, 1.0f, &strength) != 0 ||
            json_get_bool(r, m, key, "lambert", &mt.lambert_only) != 0 ||
            json_get_number(r, m, key, "normal_scale", 0, 0.0, 100.0, 1.0f, &mt.normal_scale) != 0 ||
            read_alpha(r, m, key, &mt) != 0)
            return -1;
        if (strength != 1.0f) /* KHR_materials_emissive_strength: a multiplier of the colour */
            mt.emission = v3_scale(mt.emission, strength);
        if (v3_max_component(mt.emission) > 1e18f) {
            char k[80];
            json_child_key(k, sizeof k, key, "emissive_strength", 0);
            return json_fail(r, k, "emission times strength exceeds 1e18");
        }
        if (cJSON_GetObjectItemCaseSensitive(m, "emission_texture") && !(v3_max_component(mt.emission) > 0.0f)) {
            char k[80];
            json_child_key(k, sizeof k, key, "emission_texture", 0);
            return json_fail(r, k, "has no effect without \"emission\" (the map multiplies it, as in glTF)");
        }
        /* glTF 2.0 maps: colour images are sRGB-encoded, metallic-roughness (G, B) linear */
        if (texture_map(r, m, key, "base_color_texture", 1, &mt.base_color_map) != 0 ||
            texture_map(r, m, key, "metallic_roughness_texture", 0, &mt.metal_rough_map) != 0 ||
            texture_map(r, m, key, "emission_texture", 1, &mt.emission_map) != 0 ||
            texture_map(r, m, key, "normal_texture", 0, &mt.normal_map) != 0)
            return -1;
        if (json_animate_material(r, m, key, scene_add_material(r->b, mt)) != 0)
            return -1;
    }
    return 0;
}

/* Material id of the value v (a material name); key names v. */
static int material_ref(struct json_reader *r, const cJSON *v, const char *key, int *id)
{
    if (!cJSON_IsString(v))
        return json_fail(r, key, "must be a material name");
    int i = 0;
    for (const cJSON *m = r->materials ? r->materials->child : NULL; m; m = m->next, i++) {
        if (strcmp(cJSON_GetObjectItemCaseSensitive(m, "name")->valuestring, v->valuestring) == 0) {
            *id = i;
            return 0;
        }
    }
    return json_fail(r, key, "no material named '%s' in \"materials\"", v->valuestring);
}

/* ---- shapes ---- */

/* Row-major 4x4 from "matrix" or from translate * rotate (z * y * x, degrees) * scale. */
static int read_transform(struct json_reader *r, const cJSON *t, const char *key, float m[16])
{
    static const char *const keys[] = {"matrix", "translate", "rotate", "scale", NULL};
    if (json_check_keys(r, t, key, keys) != 0)
        return -1;
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(t, "matrix");
    if (mat) {
        if (t->child->next)
            return json_fail(r, key, "\"matrix\" cannot be combined with translate, rotate or scale");
        if (!cJSON_IsArray(mat) || cJSON_GetArraySize(mat) != 16)
            return json_fail(r, key, "matrix must be an array of 16 numbers (row-major)");
        int i = 0;
        for (const cJSON *e = mat->child; e; e = e->next, i++) {
            if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || fabs(e->valuedouble) > SCENE_COORD_MAX)
                return json_fail(r, key, "matrix[%d] must be a finite number", i);
            m[i] = (float)e->valuedouble;
        }
        return 0;
    }
    vec3 tr, rot, sc;
    const cJSON *scale = cJSON_GetObjectItemCaseSensitive(t, "scale");
    char k[256];
    json_child_key(k, sizeof k, key, "scale", 0);
    if (scale && cJSON_IsNumber(scale)) {
        float f;
        if (json_get_number(r, t, key, "scale", 1, -SCENE_COORD_MAX, SCENE_COORD_MAX, 1.0f, &f) != 0)
            return -1;
        sc = v3s(f);
    } else if (json_get_vec3(r, t, key, "scale", 0, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(1.0f), &sc) != 0) {
        return -1;
    }
    if (sc.x == 0.0f || sc.y == 0.0f || sc.z == 0.0f)
        return json_fail(r, k, "a zero scale flattens the mesh");
    if (json_get_vec3(r, t, key, "translate", 0, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(0.0f), &tr) != 0 ||
        json_get_vec3(r, t, key, "rotate", 0, -1e6, 1e6, v3s(0.0f), &rot) != 0)
        return -1;
    const double d2r = 3.14159265358979323846 / 180.0;
    double cx = cos(rot.x * d2r), sx = sin(rot.x * d2r), cy = cos(rot.y * d2r), sy = sin(rot.y * d2r);
    double cz = cos(rot.z * d2r), sz = sin(rot.z * d2r);
    /* R = Rz Ry Rx */
    double R[3][3] = {{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
                      {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
                      {-sy, cy * sx, cy * cx}};
    const float s3[3] = {sc.x, sc.y, sc.z}, t3[3] = {tr.x, tr.y, tr.z};
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            m[4 * i + j] = (float)(R[i][j] * s3[j]);
        m[4 * i + 3] = t3[i];
    }
    m[12] = m[13] = m[14] = 0.0f;
    m[15] = 1.0f;
    return 0;
}

static int read_mesh(struct json_reader *r, const cJSON *sh, const char *key, int material, int object)
{
    static const char *const keys[] = {"type", "file", "transform", "material", "materials", "object", NULL};
    if (json_check_keys(r, sh, key, keys) != 0)
        return -1;
    char k[256];
    json_child_key(k, sizeof k, key, "file", 0);
    const cJSON *file = cJSON_GetObjectItemCaseSensitive(sh, "file");
    if (!cJSON_IsString(file) || !*file->valuestring)
        return json_fail(r, k, file ? "must be a file name" : "missing");
    char path[4096];
    if (resolve_path(r, k, file->valuestring, path, sizeof path) != 0)
        return -1;
    float m[16];
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(sh, "transform");
    json_child_key(k, sizeof k, key, "transform", 0);
    if (t && read_transform(r, t, k, m) != 0)
        return -1;
    /* "materials": {"name in the file": "our material"} */
    const cJSON *map = cJSON_GetObjectItemCaseSensitive(sh, "materials");
    struct scene_material_override ov[64];
    int nov = 0;
    if (map) {
        json_child_key(k, sizeof k, key, "materials", 0);
        if (!cJSON_IsObject(map))
            return json_fail(r, k, "must be an object mapping the file's material names to ours");
        for (const cJSON *e = map->child; e; e = e->next) {
            char ek[320];
            json_child_key(ek, sizeof ek, k, e->string, 0);
            if (nov == 64)
                return json_fail(r, k, "at most 64 material overrides per mesh");
            ov[nov].file_name = e->string;
            if (material_ref(r, e, ek, &ov[nov].material) != 0)
                return -1;
            nov++;
        }
    }
    char imsg[RESTIR_MSG_LEN];
    if (scene_import_mesh(r->b, path, t ? m : NULL, material, ov, nov, object, imsg) < 0)
        return json_fail(r, key, "%s", imsg);
    return 0;
}

/* "vertices": [[x,y,z], ...] (triangles) or "quads": [[c0,c1,c2,c3], ...] */
static int read_polygons(struct json_reader *r, const cJSON *sh, const char *key, int corners, int material, int object)
{
    static const char *const tri_keys[] = {"type", "vertices", "uvs", "normals", "material", "object", NULL};
    static const char *const quad_keys[] = {"type", "quads", "material", "object", NULL};
    if (json_check_keys(r, sh, key, corners == 3 ? tri_keys : quad_keys) != 0)
        return -1;
    int ok;
    const char *name = corners == 3 ? "vertices" : "quads";
    const cJSON *list = json_get_array(r, sh, key, name, 1, &ok);
    if (!ok)
        return -1;
    char k[256];
    json_child_key(k, sizeof k, key, name, 0);
    const int n = cJSON_GetArraySize(list);
    if (n == 0 || (corners == 3 && n % 3 != 0))
        return json_fail(r, k, corners == 3 ? "needs 3 vertices per triangle" : "is empty");
    /* triangles: optional "uvs" [[u, v], ...], one per vertex; quads: the unit square, c0 at (0, 0) */
    const cJSON *uvs = corners == 3 ? json_get_array(r, sh, key, "uvs", 0, &ok) : NULL;
    if (!ok)
        return -1;
    if (uvs && cJSON_GetArraySize(uvs) != n) {
        char uk[256];
        json_child_key(uk, sizeof uk, key, "uvs", 0);
        return json_fail(r, uk, "needs one [u, v] per vertex (%d)", n);
    }
    /* triangles: optional "normals" [[x, y, z], ...], one shading normal per vertex */
    const cJSON *normals = corners == 3 ? json_get_array(r, sh, key, "normals", 0, &ok) : NULL;
    if (!ok)
        return -1;
    char nk[256];
    json_child_key(nk, sizeof nk, key, "normals", 0);
    if (normals && cJSON_GetArraySize(normals) != n)
        return json_fail(r, nk, "needs one [x, y, z] per vertex (%d)", n);
    const cJSON *uv_item = uvs ? uvs->child : NULL, *n_item = normals ? normals->child : NULL;
    float uv[8];
    vec3 nrm[3];
    vec3 p[4];
    int i = 0, c = 0;
    for (const cJSON *e = list->child; e; e = e->next, i++) {
        char ek[300];
        json_child_key(ek, sizeof ek, k, NULL, i);
        if (corners == 3) {
            if (json_vec3_value(r, e, ek, -SCENE_COORD_MAX, SCENE_COORD_MAX, &p[c]) != 0)
                return -1;
            if (uv_item) {
                char uk[300];
                json_child_key(uk, sizeof uk, key, "uvs", 0);
                json_child_key(ek, sizeof ek, uk, NULL, i);
                if (!cJSON_IsArray(uv_item) || cJSON_GetArraySize(uv_item) != 2 ||
                    !cJSON_IsNumber(uv_item->child) || !cJSON_IsNumber(uv_item->child->next) ||
                    !isfinite(uv_item->child->valuedouble) || !isfinite(uv_item->child->next->valuedouble) ||
                    fabs(uv_item->child->valuedouble) > 1e6 || fabs(uv_item->child->next->valuedouble) > 1e6)
                    return json_fail(r, ek, "must be [u, v] (finite, at most 1e6)");
                uv[2 * c] = (float)uv_item->child->valuedouble;
                uv[2 * c + 1] = (float)uv_item->child->next->valuedouble;
                uv_item = uv_item->next;
            }
            if (n_item) {
                json_child_key(ek, sizeof ek, nk, NULL, i);
                if (json_vec3_value(r, n_item, ek, -1e6f, 1e6f, &nrm[c]) != 0)
                    return -1;
                if (!(v3_length(nrm[c]) > 1e-6f))
                    return json_fail(r, ek, "must be a non-zero direction");
                n_item = n_item->next;
            }
            if (++c == 3) {
                scene_add_triangle(r->b, p[0], p[1], p[2], material, object);
                if (uvs)
                    scene_set_uvs(r->b, r->b->s->num_tris - 1, uv);
                if (normals)
                    scene_set_normals(r->b, r->b->s->num_tris - 1, nrm);
                c = 0;
            }
            continue;
        }
        if (!cJSON_IsArray(e) || cJSON_GetArraySize(e) != 4)
            return json_fail(r, ek, "a quad is an array of 4 corners");
        int j = 0;
        for (const cJSON *q = e->child; q; q = q->next, j++) {
            char qk[320];
            json_child_key(qk, sizeof qk, ek, NULL, j);
            if (json_vec3_value(r, q, qk, -SCENE_COORD_MAX, SCENE_COORD_MAX, &p[j]) != 0)
                return -1;
        }
        scene_add_quad(r->b, p[0], p[1], p[2], p[3], material, object);
        const struct material *qm = &r->b->s->materials[material];
        if (qm->base_color_map | qm->metal_rough_map | qm->emission_map | qm->normal_map) {
            /* a textured quad gets the unit square: triangles c0 c1 c2 and c0 c2 c3 */
            const float first[6] = {0, 0, 1, 0, 1, 1}, second[6] = {0, 0, 1, 1, 0, 1};
            scene_set_uvs(r->b, r->b->s->num_tris - 2, first);
            scene_set_uvs(r->b, r->b->s->num_tris - 1, second);
        }
    }
    return 0;
}

static int read_box(struct json_reader *r, const cJSON *sh, const char *key, int material, int object)
{
    static const char *const keys[] = {"type", "min", "max", "rotate_y_rad", "material", "object", NULL};
    vec3 lo, hi;
    float angle;
    if (json_check_keys(r, sh, key, keys) != 0 ||
        json_get_vec3(r, sh, key, "min", 1, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(0), &lo) != 0 ||
        json_get_vec3(r, sh, key, "max", 1, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(0), &hi) != 0 ||
        json_get_number(r, sh, key, "rotate_y_rad", 0, -1e6, 1e6, 0.0f, &angle) != 0)
        return -1;
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
        return json_fail(r, key, "max must exceed min in x, y and z");
    scene_add_box_rotated_y(r->b, lo, hi, angle, material, object);
    return 0;
}

static int read_sphere(struct json_reader *r, const cJSON *sh, const char *key, int material, int object)
{
    static const char *const keys[] = {"type",   "center",   "radius", "segments", "inward",
                                       "smooth", "material", "object", NULL};
    vec3 c;
    float radius;
    int segments = 0, inward = 0, smooth = 0;
    if (json_check_keys(r, sh, key, keys) != 0 ||
        json_get_vec3(r, sh, key, "center", 1, -SCENE_COORD_MAX, SCENE_COORD_MAX, v3s(0), &c) != 0 ||
        json_get_number(r, sh, key, "radius", 1, 0.0, SCENE_COORD_MAX, 1.0f, &radius) != 0 ||
        json_get_int(r, sh, key, "segments", 3, 4096, 32, &segments) != 0 ||
        json_get_bool(r, sh, key, "inward", &inward) != 0 || json_get_bool(r, sh, key, "smooth", &smooth) != 0)
        return -1;
    if (!(radius > 0.0f)) {
        char k[256];
        json_child_key(k, sizeof k, key, "radius", 0);
        return json_fail(r, k, "must be positive");
    }
    scene_add_sphere(r->b, c, radius, segments, (inward ? SPHERE_INWARD : 0) | (smooth ? SPHERE_SMOOTH : 0), material,
                     object);
    return 0;
}

/* Largest explicit "object" id, so that shapes without one get fresh ids after it. */
static int max_object_id(const cJSON *shapes)
{
    int max_id = -1;
    for (const cJSON *sh = shapes->child; sh; sh = sh->next) {
        const cJSON *o = cJSON_GetObjectItemCaseSensitive(sh, "object");
        if (cJSON_IsNumber(o) && o->valuedouble >= 0 && o->valuedouble <= 1e6 && o->valuedouble > max_id)
            max_id = (int)o->valuedouble;
    }
    return max_id;
}

static int read_shapes(struct json_reader *r, const cJSON *shapes)
{
    r->b->s->num_objects = max_object_id(shapes) + 1;
    int i = 0;
    for (const cJSON *sh = shapes->child; sh; sh = sh->next, i++) {
        char key[64], k[96];
        json_child_key(key, sizeof key, "shapes", NULL, i);
        if (!cJSON_IsObject(sh))
            return json_fail(r, key, "must be an object");
        const cJSON *type = cJSON_GetObjectItemCaseSensitive(sh, "type");
        json_child_key(k, sizeof k, key, "type", 0);
        if (!cJSON_IsString(type))
            return json_fail(r, k, type ? "must be a string" : "missing (mesh, triangles, quads, box or sphere)");
        const int is_mesh = strcmp(type->valuestring, "mesh") == 0;
        int object = -1, material = -1;
        if (json_get_int(r, sh, key, "object", 0, 1000000, -1, &object) != 0)
            return -1;
        const cJSON *mv = cJSON_GetObjectItemCaseSensitive(sh, "material");
        json_child_key(k, sizeof k, key, "material", 0);
        if (mv && material_ref(r, mv, k, &material) != 0)
            return -1;
        if (!mv && !is_mesh)
            return json_fail(r, k, "missing");
        if (object < 0 && !is_mesh)
            object = scene_new_object(r->b);
        int rc;
        if (is_mesh)
            rc = read_mesh(r, sh, key, material, object);
        else if (strcmp(type->valuestring, "triangles") == 0)
            rc = read_polygons(r, sh, key, 3, material, object);
        else if (strcmp(type->valuestring, "quads") == 0)
            rc = read_polygons(r, sh, key, 4, material, object);
        else if (strcmp(type->valuestring, "box") == 0)
            rc = read_box(r, sh, key, material, object);
        else if (strcmp(type->valuestring, "sphere") == 0)
            rc = read_sphere(r, sh, key, material, object);
        else {
            json_child_key(k, sizeof k, key, "type", 0);
            rc = json_fail(r, k, "unknown shape type '%s' (mesh, triangles, quads, box or sphere)", type->valuestring);
        }
        if (rc != 0)
            return -1;
        if (object >= r->b->s->num_objects)
            r->b->s->num_objects = object + 1;
    }
    return 0;
}

static const char *const top_keys[] = {"format",    "name",   "camera",      "camera_path",
                                       "materials", "shapes", "environment", NULL};

/* "environment": {"image": FILE, "intensity": k, "rotation": degrees} or {"color": [r, g, b],
 * "intensity": k}. */
static int read_environment(struct json_reader *r, const cJSON *v)
{
    static const char *const keys[] = {"image", "color", "intensity", "rotation", NULL};
    if (!cJSON_IsObject(v))
        return json_fail(r, "environment", "must be an object with \"image\" or \"color\"");
    if (json_check_keys(r, v, "environment", keys) != 0)
        return -1;
    float k, deg;
    vec3 color;
    const cJSON *image = cJSON_GetObjectItemCaseSensitive(v, "image");
    const int has_color = cJSON_GetObjectItemCaseSensitive(v, "color") != NULL;
    if (json_get_number(r, v, "environment", "intensity", 0, 0.0, SCENE_COORD_MAX, 1.0f, &k) != 0 ||
        json_get_number(r, v, "environment", "rotation", 0, -360.0, 360.0, 0.0f, &deg) != 0 ||
        json_get_vec3(r, v, "environment", "color", 0, 0.0, SCENE_COORD_MAX, v3s(1.0f), &color) != 0)
        return -1;
    if (!image == !has_color)
        return json_fail(r, "environment", "needs exactly one of \"image\" and \"color\"");
    char inner[RESTIR_MSG_LEN], path[4096];
    r->env = xcalloc(1, sizeof *r->env);
    int rc;
    if (image) {
        if (!cJSON_IsString(image) || !*image->valuestring)
            return json_fail(r, "environment.image", "must be an image file name (.hdr or .exr)");
        if (resolve_path(r, "environment.image", image->valuestring, path, sizeof path) != 0)
            return -1;
        rc = environment_load("environment.image", path, k, deg * (float)(RESTIR_PI / 180.0), r->env, inner);
    } else {
        rc = environment_constant("environment.color", color, k, r->env, inner);
    }
    return rc == 0 ? 0 : json_fail(r, "environment", "%s", inner);
}

static int read_scene(struct json_reader *r, const cJSON *root)
{
    if (json_check_keys(r, root, "", top_keys) != 0)
        return -1;
    const cJSON *format = cJSON_GetObjectItemCaseSensitive(root, "format");
    if (format && !(cJSON_IsString(format) && strcmp(format->valuestring, "restir-scene 1") == 0))
        return json_fail(r, "format", "must be \"restir-scene 1\"");
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(root, "name");
    if (name && !cJSON_IsString(name))
        return json_fail(r, "name", "must be a string");
    if (name) { /* it names output folders: one plain path component */
        const char *v = name->valuestring;
        int bad = !*v || strlen(v) >= sizeof r->b->s->name || strstr(v, "..") != NULL;
        for (const char *c = v; *c && !bad; c++)
            bad = *c == '/' || *c == '\\' || (unsigned char)*c < 32;
        if (bad)
            return json_fail(r, "name", "must be 1 to 63 characters without '/', '\\', '..' or control characters");
    }
    if (name)
        snprintf(r->b->s->name, sizeof r->b->s->name, "%s", name->valuestring);
    int ok;
    r->materials = (cJSON *)json_get_array(r, root, "", "materials", 0, &ok);
    if (!ok || read_materials(r) != 0)
        return -1;
    const cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
    if (!cam)
        return json_fail(r, "camera", "missing");
    float unused;
    if (read_camera(r, cam, "camera", 0, &r->b->s->camera, &unused) != 0)
        return -1;
    const cJSON *path = json_get_array(r, root, "", "camera_path", 0, &ok);
    if (!ok || (path && read_camera_path(r, path) != 0))
        return -1;
    if (!path) { /* the path of a scene without one stands still */
        r->b->s->camera_path.num_keys = 1;
        r->b->s->camera_path.keys = xcalloc(1, sizeof(struct camera_key));
        r->b->s->camera_path.keys[0].cam = r->b->s->camera;
    }
    const cJSON *shapes = json_get_array(r, root, "", "shapes", 1, &ok);
    if (!ok || read_shapes(r, shapes) != 0)
        return -1;
    if (r->b->s->num_tris == 0)
        return json_fail(r, "shapes", "no triangles");
    const cJSON *env = cJSON_GetObjectItemCaseSensitive(root, "environment");
    if (env)
        return read_environment(r, env);
    int emissive = 0;
    for (int t = 0; t < r->b->s->num_tris && !emissive; t++)
        emissive = v3_max_component(r->b->s->materials[r->b->s->tri_material[t]].emission) > 0.0f;
    if (!emissive)
        return json_fail(r, "shapes",
                         "no shape has an emissive material: add an emitter (a material with \"emission\") "
                         "or an \"environment\"");
    return 0;
}

/* Shapes go through the same builder calls the built-in scenes make, so an exported built-in scene
 * reads back bit for bit. Nothing is half-built on failure. */
int scene_json_parse(const char *text, size_t len, const char *file, const char *dir, struct scene *s, char *msg)
{
    return scene_json_parse_with(text, len, file, dir, NULL, s, msg);
}

int scene_json_parse_with(const char *text, size_t len, const char *file, const char *dir,
                          const struct scene_load_desc *d, struct scene *s, char *msg)
{
    memset(s, 0, sizeof(*s)); /* empty on every failure, so scene_destroy is always safe */
    struct json_reader r = {.file = file, .msg = msg};
    snprintf(r.dir, sizeof r.dir, "%s", dir ? dir : "");
    const char *end = NULL;
    /* text[len] must be the NUL that require_null_terminated looks for, hence len + 1 */
    cJSON *root = cJSON_ParseWithLengthOpts(text, len + 1, &end, 1);
    if (!root)
        return json_fail(&r, NULL, "invalid JSON at line %d", json_line_of(text, end ? end : cJSON_GetErrorPtr()));
    char stem[64];
    scene_file_stem(file, stem, sizeof stem);
    struct scene_builder b;
    scene_builder_begin_with(&b, s, stem, d);
    r.b = &b;
    int rc = read_scene(&r, root);
    cJSON_Delete(root);
    if (rc == 0 && scene_builder_end(&b, msg) != 0) {
        char inner[RESTIR_MSG_LEN];
        memcpy(inner, msg, sizeof inner);
        json_msgf(msg, RESTIR_MSG_LEN, "%s: %s", file, inner);
        rc = -1;
    }
    if (r.env && rc == 0) {
        char inner[RESTIR_MSG_LEN];
        if (scene_set_environment(s, r.env, inner) != 0) {
            json_msgf(msg, RESTIR_MSG_LEN, "%s: environment: %s", file, inner);
            rc = -1;
        }
    } else if (r.env) {
        environment_fini(r.env);
        free(r.env);
    }
    if (rc != 0)
        scene_destroy(s);
    return rc;
}

int scene_json_load(const char *path, const struct scene_load_desc *d, struct scene *s, char *msg)
{
    memset(s, 0, sizeof(*s));
    long len = 0;
    char *text = scene_read_whole_file(path, &len, msg);
    if (!text)
        return -1;
    char dir[4096] = "";
    const char *slash = strrchr(path, '/');
    if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else if (slash && slash - path < (long)sizeof dir)
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    else if (slash) {
        free(text);
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: path too long", path);
        return -1;
    }
    int rc = scene_json_parse_with(text, (size_t)len, path, dir, d, s, msg);
    free(text);
    return rc;
}

int scene_json_cameras_parse(const char *text, size_t len, const char *file, struct camera **cams, int *n,
                             char *msg)
{
    *cams = NULL;
    *n = 0;
    struct json_reader r = {.file = file, .msg = msg};
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, len + 1, &end, 1);
    int rc = 0;
    static const char *const keys[] = {"format", "scene", "method", "width", "height", "seed", "cameras", NULL};
    if (!root)
        rc = json_fail(&r, NULL, "invalid JSON at line %d", json_line_of(text, end ? end : cJSON_GetErrorPtr()));
    else if (json_check_keys(&r, root, "", keys) != 0)
        rc = -1;
    const cJSON *list = rc == 0 ? cJSON_GetObjectItemCaseSensitive(root, "cameras") : NULL;
    if (rc == 0 && (!cJSON_IsArray(list) || cJSON_GetArraySize(list) < 1))
        rc = json_fail(&r, "cameras", "must be an array of at least one camera, one per frame");
    if (rc == 0) {
        *cams = xcalloc((size_t)cJSON_GetArraySize(list), sizeof(struct camera));
        int i = 0;
        for (const cJSON *c = list->child; c && rc == 0; c = c->next, i++) {
            char key[64];
            float unused;
            json_child_key(key, sizeof key, "cameras", NULL, i);
            rc = read_camera(&r, c, key, 0, &(*cams)[i], &unused);
        }
        *n = i;
        if (rc != 0) {
            free(*cams);
            *cams = NULL;
            *n = 0;
        }
    }
    cJSON_Delete(root);
    return rc;
}
