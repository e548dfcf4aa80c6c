/* scene_export.c: a scene as our JSON format (docs/SCENES.md). The shapes are the builder calls
 * that made the scene (consecutive triangles or quads of one material and object grouped into one
 * shape), and every float is written with the fewest digits that read back to the same float, so
 * scene_json_load rebuilds the scene bit for bit. Must never read scene files. */
#include "io/scene_export.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "io/atomic_file.h"
#include "io/report.h"

/* Shortest %g form of f that the reader (strtod, then a float conversion) turns back into f. */
static void format_float(float f, char *out, size_t len)
{
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(out, len, "%.*g", digits, (double)f);
        if ((float)strtod(out, NULL) == f)
            return;
    }
}

static cJSON *number(float f)
{
    char buf[32];
    format_float(f, buf, sizeof buf);
    return cJSON_CreateRaw(buf);
}

static cJSON *vec(vec3 v)
{
    char x[32], y[32], z[32], buf[112];
    format_float(v.x, x, sizeof x);
    format_float(v.y, y, sizeof y);
    format_float(v.z, z, sizeof z);
    snprintf(buf, sizeof buf, "[%s, %s, %s]", x, y, z);
    return cJSON_CreateRaw(buf);
}

static void material_name(int id, char *out, size_t len) { snprintf(out, len, "material_%d", id); }

static cJSON *camera_json(const struct camera *c, const float *frame)
{
    cJSON *j = cJSON_CreateObject();
    if (frame)
        cJSON_AddItemToObject(j, "frame", number(*frame));
    cJSON_AddItemToObject(j, "position", vec(c->position));
    cJSON_AddItemToObject(j, "look_at", vec(c->target));
    cJSON_AddItemToObject(j, "up", vec(c->up));
    cJSON_AddItemToObject(j, "vfov", number(c->vfov_deg));
    /* only when set, so that pinhole cameras export as before */
    if (c->aperture != 0.0f)
        cJSON_AddItemToObject(j, "aperture", number(c->aperture));
    if (c->focus_distance != 0.0f)
        cJSON_AddItemToObject(j, "focus_distance", number(c->focus_distance));
    return j;
}

/* A material's "animation" (docs/SCENES.md): its keys with every channel it has, the pivot only
 * where the scene gave one (the default, the triangles' centre, is computed again on reading). */
static cJSON *animation_json(const struct emission_animation *a)
{
    cJSON *j = cJSON_CreateObject();
    if (a->step)
        cJSON_AddStringToObject(j, "interpolation", "step");
    if (a->pivot_given)
        cJSON_AddItemToObject(j, "pivot", vec(a->pivot));
    cJSON *keys = cJSON_AddArrayToObject(j, "keys");
    for (int k = 0; k < a->n; k++) {
        cJSON *key = cJSON_CreateObject();
        cJSON_AddItemToObject(key, "frame", number(a->frame[k]));
        cJSON_AddItemToObject(key, "strength", number(a->strength[k]));
        if (a->translate)
            cJSON_AddItemToObject(key, "translate", vec(a->translate[k]));
        if (a->rotate)
            cJSON_AddItemToObject(key, "rotate", vec(a->rotate[k]));
        cJSON_AddItemToArray(keys, key);
    }
    return j;
}

static cJSON *materials_json(const struct scene *s)
{
    cJSON *list = cJSON_CreateArray();
    for (int m = 0; m < s->num_materials; m++) {
        const struct material *mt = &s->materials[m];
        cJSON *j = cJSON_CreateObject();
        char name[32];
        material_name(m, name, sizeof name);
        cJSON_AddStringToObject(j, "name", name);
        cJSON_AddItemToObject(j, "base_color", vec(mt->base_color));
        cJSON_AddItemToObject(j, "metallic", number(mt->metallic));
        cJSON_AddItemToObject(j, "roughness", number(mt->roughness));
        const struct emission_animation *a = s->emission_anim ? &s->emission_anim[m] : NULL;
        if (a && a->n > 0) { /* what strength 1 gives, and the keys */
            cJSON_AddItemToObject(j, "emission", vec(a->emission));
            cJSON_AddItemToObject(j, "animation", animation_json(a));
        } else if (v3_max_component(mt->emission) > 0.0f) {
            cJSON_AddItemToObject(j, "emission", vec(mt->emission));
        }
        if (mt->lambert_only)
            cJSON_AddBoolToObject(j, "lambert", 1);
        cJSON_AddItemToArray(list, j);
    }
    return list;
}

static cJSON *shape_head(const char *type, int material, int object)
{
    cJSON *j = cJSON_CreateObject();
    char name[32];
    material_name(material, name, sizeof name);
    cJSON_AddStringToObject(j, "type", type);
    cJSON_AddStringToObject(j, "material", name);
    cJSON_AddNumberToObject(j, "object", object);
    return j;
}

/* Records i .. returned index - 1: the run of triangles or quads sharing material and object. */
static int polygon_run(const struct scene_shape_record *r, int n, int i, cJSON *shapes)
{
    const int quads = r[i].kind == SHAPE_QUAD, corners = quads ? 4 : 3;
    cJSON *j = shape_head(quads ? "quads" : "triangles", r[i].material, r[i].object);
    cJSON *list = cJSON_AddArrayToObject(j, quads ? "quads" : "vertices");
    int k = i;
    for (; k < n && r[k].kind == r[i].kind && r[k].material == r[i].material && r[k].object == r[i].object; k++) {
        cJSON *target = list;
        if (quads) {
            target = cJSON_CreateArray();
            cJSON_AddItemToArray(list, target);
        }
        for (int c = 0; c < corners; c++)
            cJSON_AddItemToArray(target, vec(r[k].p[c]));
    }
    cJSON_AddItemToArray(shapes, j);
    return k;
}

static cJSON *shapes_json(const struct scene_shape_record *r, int n)
{
    cJSON *shapes = cJSON_CreateArray();
    for (int i = 0; i < n;) {
        if (r[i].kind == SHAPE_TRIANGLE || r[i].kind == SHAPE_QUAD) {
            i = polygon_run(r, n, i, shapes);
            continue;
        }
        cJSON *j = shape_head(r[i].kind == SHAPE_BOX ? "box" : "sphere", r[i].material, r[i].object);
        if (r[i].kind == SHAPE_BOX) {
            cJSON_AddItemToObject(j, "min", vec(r[i].p[0]));
            cJSON_AddItemToObject(j, "max", vec(r[i].p[1]));
            if (r[i].f != 0.0f)
                cJSON_AddItemToObject(j, "rotate_y_rad", number(r[i].f));
        } else {
            cJSON_AddItemToObject(j, "center", vec(r[i].p[0]));
            cJSON_AddItemToObject(j, "radius", number(r[i].f));
            cJSON_AddNumberToObject(j, "segments", r[i].segments);
            if (r[i].sphere_flags & SPHERE_INWARD)
                cJSON_AddBoolToObject(j, "inward", 1);
            if (r[i].sphere_flags & SPHERE_SMOOTH)
                cJSON_AddBoolToObject(j, "smooth", 1);
        }
        cJSON_AddItemToArray(shapes, j);
        i++;
    }
    return shapes;
}

/* Prints root (and deletes it) to path through a temporary file and a rename. */
static int write_json(cJSON *root, const char *path, char *msg)
{
    int rc = json_write_file(path, root, msg);
    cJSON_Delete(root);
    return rc;
}

int cameras_write_json(const char *path, const struct camera *cams, int n, const char *scene, const char *method,
                       int width, int height, unsigned long long seed, char *msg)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "format", "restir-cameras 1");
    cJSON_AddStringToObject(root, "scene", scene);
    cJSON_AddStringToObject(root, "method", method);
    cJSON_AddNumberToObject(root, "width", width);
    cJSON_AddNumberToObject(root, "height", height);
    cJSON_AddNumberToObject(root, "seed", (double)seed);
    cJSON *list = cJSON_AddArrayToObject(root, "cameras");
    for (int k = 0; k < n; k++)
        cJSON_AddItemToArray(list, camera_json(&cams[k], NULL));
    return write_json(root, path, msg);
}

int scene_export_json(const struct scene *s, const struct scene_shape_record *records, int n, const char *path,
                      char *msg)
{
    /* The records hold shapes and materials; what the builder adds beside them is not written
     * yet, and a file without it would render another scene. */
    if (s->num_textures > 0 || s->env || s->uv || s->normals || s->tangents) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "scene %s has generated textures, UVs, shading normals or an environment, which export does not "
                 "write yet (it would write a different scene); render it by name",
                 s->name);
        return -1;
    }
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "format", "restir-scene 1");
    cJSON_AddStringToObject(root, "name", s->name);
    cJSON_AddItemToObject(root, "camera", camera_json(&s->camera, NULL));
    cJSON *path_keys = cJSON_AddArrayToObject(root, "camera_path");
    for (int k = 0; k < s->camera_path.num_keys; k++)
        cJSON_AddItemToArray(path_keys, camera_json(&s->camera_path.keys[k].cam, &s->camera_path.keys[k].frame));
    cJSON_AddItemToObject(root, "materials", materials_json(s));
    cJSON_AddItemToObject(root, "shapes", shapes_json(records, n));
    return write_json(root, path, msg);
}
