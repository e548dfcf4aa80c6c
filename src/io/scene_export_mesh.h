/* scene_export_mesh.h: a loaded scene as a triangle soup in JSON (`restir scene export NAME|FILE
 * --mesh --out DIR`), for handing the same geometry, Lambert materials, camera and constant
 * environment to another renderer (bench/cycles/build_scene.py builds it in Blender). Must never
 * render or read scene files. */
#ifndef RESTIR_IO_SCENE_EXPORT_MESH_H
#define RESTIR_IO_SCENE_EXPORT_MESH_H

#include "scene/scene.h"

/* Whether s can be written as a triangle soup that another renderer's Lambert-only materials
 * reproduce: every material some triangle uses is `lambert` (no specular layer), untextured and not
 * alpha-masked; no triangle has shading normals (they are interpolated and bent in ways another
 * renderer does not copy: load with scene.shading_normals=off); the camera is a pinhole; the
 * environment, if any, is one constant colour. Returns 0, or -1 with msg (RESTIR_MSG_LEN) naming
 * the first material (index, colour, how many triangles use it) or feature that cannot match. */
int scene_export_mesh_check(const struct scene *s, char *msg);

/* Writes s (after scene_export_mesh_check) to path through a temporary sibling renamed into place:
 * a JSON object with
 *   "format": "restir-mesh 1", "scene": s->name, "source": source (what was loaded),
 *   "up": "+y" (Blender is z-up: (x, y, z) here is (x, -z, y) there),
 *   "vertices": [x0, y0, z0, x1, ...] world space, "indices": [a0, b0, c0, a1, ...] (counter-clockwise
 *   seen from the front), "triangle_material": [m0, m1, ...],
 *   "materials": [{"used", "diffuse": albedo, "emission": radiance}] (emission from the front only),
 *   "camera": {"position", "look_at", "direction", "up", "right" (the orthonormal basis our camera
 *   builds), "vfov_deg", "model"}, "environment": null or {"color": radiance},
 *   "triangles", "emitter_triangles".
 * Floats are written with 9 significant digits (they read back to the same float). Returns 0, or
 * -1 with msg. */
int scene_export_mesh_json(const struct scene *s, const char *source, const char *path, char *msg);

#endif
