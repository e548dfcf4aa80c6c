/* camera.h: pinhole camera rays and projection for a given image size, and camera paths.
 * Must never depend on the ray tracer or render passes. */
#ifndef RESTIR_SCENE_CAMERA_H
#define RESTIR_SCENE_CAMERA_H

#include "core/vec3.h"
#include "scene/scene_types.h"

/* Precomputed basis of a camera for an image of width x height pixels. */
struct camera_view {
    vec3 position;
    vec3 forward, right, up; /* orthonormal */
    float tan_half_y, tan_half_x;
    int width, height;
};

void camera_view_init(struct camera_view *v, const struct camera *c, int width, int height);
/* Unit direction of the ray through image point (px, py) in pixel units, (0,0) = top-left corner
 * of the image, pixel (i, j) covers [i, i+1) x [j, j+1). */
vec3 camera_view_ray(const struct camera_view *v, float px, float py);
/* Projects world point p to image coordinates; returns 0 when p is behind the camera. */
int camera_view_project(const struct camera_view *v, vec3 p, float *px, float *py);

/* Camera at a frame of the default path (or the static camera when path is 0). */
struct camera scene_camera_at(const struct scene *s, int use_path, float frame);

#endif
