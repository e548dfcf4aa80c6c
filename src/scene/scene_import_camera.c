/* scene_import_camera.c: cameras of mesh files opened as whole scenes (scene_import_camera.h).
 * Must never import geometry or materials. */
#include "scene/scene_import_camera.h"

#include <assimp/camera.h>
#include <assimp/version.h>
#include <math.h>

#include "core/check.h"
#include "scene/scene_import_ai.h"

/* World transform of the node named name (a camera's node), searched depth-first. */
static int find_node(const struct aiNode *node, const struct aiString *name, const mat4d *parent, int depth,
                     mat4d *out)
{
    if (depth > IMPORT_MAX_NODE_DEPTH)
        return 0;
    mat4d local = mat4d_from_ai(&node->mTransformation);
    mat4d t = mat4d_mul(parent, &local);
    if (ai_string_equal(&node->mName, name)) {
        *out = t;
        return 1;
    }
    for (unsigned c = 0; c < node->mNumChildren; c++)
        if (node->mChildren && node->mChildren[c] && find_node(node->mChildren[c], name, &t, depth + 1, out))
            return 1;
    return 0;
}

/* Our full vertical field of view from assimp's mHorizontalFOV, which importers fill differently:
 * documented as half the horizontal angle (what we assume for every other format), but the glTF
 * importer stores yfov * aspect before 5.3 and the full horizontal angle
 * 2 atan(tan(yfov / 2) aspect) from 5.3 on (assimp commit 39cbef1e2), both with aspect 1 when the
 * file gives none; we invert exactly what the running library did. */
static float camera_vfov_deg(const struct aiCamera *c, int gltf)
{
    double h = c->mHorizontalFOV, aspect = c->mAspect > 0.0f ? c->mAspect : 0.0, v;
    if (gltf) {
        double a = aspect > 0.0 ? aspect : 1.0;
        int new_formula = aiGetVersionMajor() > 5 || (aiGetVersionMajor() == 5 && aiGetVersionMinor() >= 3);
        v = new_formula ? 2.0 * atan(tan(0.5 * h) / a) : h / a;
    } else {
        double a = aspect > 0.0 ? aspect : 16.0 / 9.0;
        v = 2.0 * atan(tan(h) / a);
    }
    double deg = v * 180.0 / 3.14159265358979323846;
    return isfinite(deg) && deg > 1.0 && deg < 179.0 ? (float)deg : 45.0f;
}

/* An up vector not parallel to the view direction (camera_view_init needs their cross product). */
static vec3 usable_up(vec3 forward, vec3 up)
{
    if (v3_is_finite(up) && v3_length(v3_cross(forward, v3_normalize(up))) > 1e-3f)
        return v3_normalize(up);
    return fabsf(forward.y) < 0.9f ? v3(0, 1, 0) : v3(0, 0, 1);
}

/* The file's first perspective camera through its node, looking at the depth of the bounds'
 * centre. Orthographic cameras (no field of view) are passed over: we render pinhole only. */
static int file_camera(const struct aiScene *ai, const char *path, vec3 centre, float diag, struct camera *out)
{
    for (unsigned i = 0; ai->mCameras && i < ai->mNumCameras; i++) {
        const struct aiCamera *c = ai->mCameras[i];
        if (!c || !(c->mHorizontalFOV > 0.0f) || c->mOrthographicWidth > 0.0f)
            continue;
        mat4d t = mat4d_identity(), top = mat4d_identity();
        if (ai->mRootNode)
            find_node(ai->mRootNode, &c->mName, &top, 0, &t);
        /* A glTF camera sits at its node's origin looking down -z, +y up; assimp 5.2 also copies
         * the node's translation into mPosition, which would apply it twice. */
        struct aiVector3D p = c->mPosition, look = c->mLookAt, upv = c->mUp;
        if (is_gltf_path(path)) {
            p = (struct aiVector3D){0, 0, 0};
            look = (struct aiVector3D){0, 0, -1};
            upv = (struct aiVector3D){0, 1, 0};
        }
        vec3 pos = mat4d_point(&t, p.x, p.y, p.z);
        vec3 fwd = v3_normalize(mat4d_dir(&t, look.x, look.y, look.z));
        if (!v3_is_finite(pos) || !v3_is_finite(fwd) || !(v3_length(fwd) > 0.5f))
            continue;
        vec3 up = usable_up(fwd, mat4d_dir(&t, upv.x, upv.y, upv.z));
        float depth = v3_dot(v3_sub(centre, pos), fwd);
        if (!(depth > 1e-3f * diag))
            depth = diag > 0.0f ? 0.5f * diag : 1.0f;
        *out = (struct camera){pos, v3_madd(pos, fwd, depth), up, camera_vfov_deg(c, is_gltf_path(path)), 0.0f, 0.0f};
        return 1;
    }
    return 0;
}

/* Bounding box of the scene's vertices (all of them finite by now). */
static void scene_bounds(const struct scene *s, vec3 *lo, vec3 *hi)
{
    *lo = *hi = s->verts[0];
    for (int i = 1; i < s->num_verts; i++) {
        vec3 v = s->verts[i];
        *lo = v3(fminf(lo->x, v.x), fminf(lo->y, v.y), fminf(lo->z, v.z));
        *hi = v3(fmaxf(hi->x, v.x), fmaxf(hi->y, v.y), fmaxf(hi->z, v.z));
    }
}

/* Without a camera in the file: from the +z side and a little above, looking at the centre, far
 * enough that the bounding sphere fits a 45-degree vertical field of view. */
static struct camera fitted_camera(vec3 centre, float diag)
{
    float radius = diag > 0.0f ? 0.5f * diag : 1.0f;
    float dist = radius / sinf(0.5f * 45.0f * RESTIR_PI / 180.0f);
    vec3 dir = v3_normalize(v3(0.0f, 0.3f, 1.0f));
    return (struct camera){v3_madd(centre, dir, dist), centre, v3(0, 1, 0), 45.0f, 0.0f, 0.0f};
}

/* The default camera path: the camera at frame 0, moved sideways by a tenth of the bounds'
 * diagonal at frame 64, still looking at the same point (a short dolly with parallax). */
static void set_camera_path(struct scene *s, float diag)
{
    struct camera c = s->camera;
    vec3 fwd = v3_normalize(v3_sub(c.target, c.position));
    vec3 right = v3_normalize(v3_cross(fwd, c.up));
    if (!(v3_length(right) > 0.5f))
        right = v3(1, 0, 0);
    struct camera moved = c;
    moved.position = v3_madd(c.position, right, 0.1f * (diag > 0.0f ? diag : 1.0f));
    s->camera_path.num_keys = 2;
    s->camera_path.keys = xmalloc(2 * sizeof(*s->camera_path.keys));
    s->camera_path.keys[0] = (struct camera_key){0.0f, c};
    s->camera_path.keys[1] = (struct camera_key){64.0f, moved};
}

void import_cameras(const struct aiScene *ai, const char *path, struct scene *s)
{
    vec3 lo, hi;
    scene_bounds(s, &lo, &hi);
    vec3 centre = v3_scale(v3_add(lo, hi), 0.5f);
    float diag = v3_length(v3_sub(hi, lo));
    if (!file_camera(ai, path, centre, diag, &s->camera))
        s->camera = fitted_camera(centre, diag);
    set_camera_path(s, diag);
}
