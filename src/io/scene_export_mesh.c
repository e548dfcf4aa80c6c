/* scene_export_mesh.c: a loaded scene as a JSON triangle soup with Lambert materials, its pinhole
 * camera and a constant environment (scene_export_mesh.h), refusing what a Lambert-only renderer
 * cannot reproduce. Must never render or read scene files. */
#include "io/scene_export_mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "io/atomic_file.h"
#include "scene/camera.h"
#include "scene/environment.h"

static int material_textured(const struct material *m)
{
    return m->base_color_map || m->metal_rough_map || m->emission_map || m->normal_map;
}

/* Why material m cannot be matched by a Lambert diffuse plus a one-sided emitter, or NULL. */
static const char *material_problem(const struct material *m)
{
    if (material_textured(m))
        return "is textured (a base colour, metallic-roughness, emission or normal map); the export writes "
               "constant colours only";
    if (m->alpha_mask)
        return "is alpha-masked (glTF alphaMode MASK or BLEND)";
    if (!m->lambert_only)
        return "has a specular layer (every material without \"lambert\": true is diffuse plus GGX specular, "
               "metallic or not), which a Lambert-only comparison cannot match; give it \"lambert\": true to "
               "compare a diffuse variant";
    return NULL;
}

static int has_shading_normals(const struct scene *s)
{
    if (!s->normals)
        return 0;
    for (int i = 0; i < s->num_verts; i++)
        if (v3_length2(s->normals[i]) > 0.0f)
            return 1;
    return 0;
}

int scene_export_mesh_check(const struct scene *s, char *msg)
{
    int *uses = xcalloc((size_t)(s->num_materials > 0 ? s->num_materials : 1), sizeof(int));
    int *first = xcalloc((size_t)(s->num_materials > 0 ? s->num_materials : 1), sizeof(int));
    for (int t = s->num_tris - 1; t >= 0; t--) {
        int m = s->tri_material[t];
        if (m >= 0 && m < s->num_materials) {
            uses[m]++;
            first[m] = t;
        }
    }
    int rc = 0;
    for (int m = 0; m < s->num_materials && rc == 0; m++) {
        const char *why = uses[m] ? material_problem(&s->materials[m]) : NULL;
        if (why) {
            const struct material *mt = &s->materials[m];
            snprintf(msg, RESTIR_MSG_LEN,
                     "scene %s: material %d (base_color [%g, %g, %g], metallic %g, roughness %g; %d triangles, "
                     "the first %d) %s",
                     s->name, m, (double)mt->base_color.x, (double)mt->base_color.y, (double)mt->base_color.z,
                     (double)mt->metallic, (double)mt->roughness, uses[m], first[m], why);
            rc = -1;
        }
    }
    free(uses);
    free(first);
    if (rc != 0)
        return rc;
    if (has_shading_normals(s)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "scene %s has shading normals, which are interpolated and bent (docs/SCENES.md) in ways another "
                 "renderer does not copy; export and render it with --set scene.shading_normals=off",
                 s->name);
        return -1;
    }
    if (s->camera.aperture > 0.0f) {
        snprintf(msg, RESTIR_MSG_LEN, "scene %s: the camera has a thin lens (aperture %g); the export writes pinholes",
                 s->name, (double)s->camera.aperture);
        return -1;
    }
    if (s->env && s->env->rgb) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "scene %s: its environment is an image (%d x %d); the export writes constant environments only",
                 s->name, s->env->width, s->env->height);
        return -1;
    }
    return 0;
}

static void put_vec(FILE *f, vec3 v) { fprintf(f, "[%.9g, %.9g, %.9g]", (double)v.x, (double)v.y, (double)v.z); }

/* A JSON string of s (names are checked to be printable; quotes and backslashes escaped). */
static void put_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static void put_camera(FILE *f, const struct camera *c)
{
    struct camera_view v;
    camera_view_init(&v, c, 2, 1); /* the basis does not depend on the image size */
    fputs("  \"camera\": {\"position\": ", f);
    put_vec(f, c->position);
    fputs(", \"look_at\": ", f);
    put_vec(f, c->target);
    fputs(",\n    \"direction\": ", f);
    put_vec(f, v.forward);
    fputs(", \"up\": ", f);
    put_vec(f, v.up);
    fputs(", \"right\": ", f);
    put_vec(f, v.right);
    fprintf(f, ", \"vfov_deg\": %.9g,\n", (double)c->vfov_deg);
    fputs("    \"model\": \"pinhole (camera_sample_ray): pixel (i, j) of a W x H image, (0, 0) top-left, is "
          "sampled at (px, py) = (i + u, j + v) with u, v uniform in [0, 1) (a 1-pixel box filter); the ray "
          "leaves position along normalize(direction + right * (2 px / W - 1) * t * W / H + up * (1 - 2 py / "
          "H) * t), t = tan(vfov_deg / 2); no clipping planes\"},\n",
          f);
}

static void put_materials(FILE *f, const struct scene *s, const int *uses)
{
    fputs("  \"materials\": [\n", f);
    for (int m = 0; m < s->num_materials; m++) {
        const struct material *mt = &s->materials[m];
        fprintf(f, "    {\"index\": %d, \"used\": %s, \"diffuse\": ", m, uses[m] ? "true" : "false");
        put_vec(f, uses[m] ? mt->base_color : v3s(0.0f));
        fputs(", \"emission\": ", f);
        put_vec(f, uses[m] ? mt->emission : v3s(0.0f));
        fprintf(f, "}%s\n", m + 1 < s->num_materials ? "," : "");
    }
    fputs("  ],\n", f);
}

int scene_export_mesh_json(const struct scene *s, const char *source, const char *path, char *msg)
{
    if (scene_export_mesh_check(s, msg) != 0)
        return -1;
    char tmp[4200];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "wb", msg);
    if (!f)
        return -1;
    int *uses = xcalloc((size_t)(s->num_materials > 0 ? s->num_materials : 1), sizeof(int));
    int emitting = 0;
    for (int t = 0; t < s->num_tris; t++) {
        int m = s->tri_material[t];
        uses[m]++;
        emitting += v3_max_component(s->materials[m].emission) > 0.0f;
    }
    fputs("{\n  \"format\": \"restir-mesh 1\",\n  \"scene\": ", f);
    put_string(f, s->name);
    fputs(",\n  \"source\": ", f);
    put_string(f, source);
    fprintf(f, ",\n  \"up\": \"+y\",\n  \"triangles\": %d,\n  \"emitter_triangles\": %d,\n", s->num_tris, emitting);
    fputs("  \"emission_sides\": \"front: the side from which a triangle's indices run counter-clockwise\",\n", f);
    put_camera(f, &s->camera);
    if (s->env) {
        fputs("  \"environment\": {\"color\": ", f);
        put_vec(f, v3_scale(s->env->constant, s->env->intensity));
        fputs("},\n", f);
    } else {
        fputs("  \"environment\": null,\n", f);
    }
    put_materials(f, s, uses);
    fputs("  \"vertices\": [", f);
    for (int i = 0; i < s->num_verts; i++)
        fprintf(f, "%s%.9g, %.9g, %.9g", i ? (i % 4 ? ", " : ",\n    ") : "\n    ", (double)s->verts[i].x,
                (double)s->verts[i].y, (double)s->verts[i].z);
    fputs("\n  ],\n  \"indices\": [", f);
    for (int t = 0; t < s->num_tris; t++)
        fprintf(f, "%s%u, %u, %u", t ? (t % 8 ? ", " : ",\n    ") : "\n    ", s->indices[3 * t],
                s->indices[3 * t + 1], s->indices[3 * t + 2]);
    fputs("\n  ],\n  \"triangle_material\": [", f);
    for (int t = 0; t < s->num_tris; t++)
        fprintf(f, "%s%d", t ? (t % 24 ? ", " : ",\n    ") : "\n    ", s->tri_material[t]);
    fputs("\n  ]\n}\n", f);
    free(uses);
    return io_close_commit(f, tmp, path, msg);
}
