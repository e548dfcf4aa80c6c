/* camera.h: camera rays and projection for a given image size (pinhole, thin lens, a camera moving
 * during the shutter), the image-plane density of a surface point, and camera paths.
 * Must never depend on the ray tracer or render passes. */
#ifndef RESTIR_SCENE_CAMERA_H
#define RESTIR_SCENE_CAMERA_H

#include "core/rng.h"
#include "core/vec3.h"
#include "scene/scene_types.h"

/* Precomputed basis of a camera for an image of width x height pixels: the pose at the frame's
 * instant (the shutter closing), the thin lens, and the pose at the shutter opening. */
struct camera_view {
    vec3 position;
    vec3 forward, right, up; /* orthonormal */
    float tan_half_y, tan_half_x;
    int width, height;
    float lens_radius;    /* thin lens: aperture radius (0: pinhole) */
    float focus_distance; /* distance of the focal plane along forward */
    float shutter;        /* the shutter is open for this fraction of a frame before the instant (0: none) */
    vec3 open_position, open_forward, open_up; /* the pose at the shutter opening ... */
    float open_tan_half_y;                     /* ... (the previous frame's camera) */
};

/* Pinhole (or c's thin lens), no motion blur. */
void camera_view_init(struct camera_view *v, const struct camera *c, int width, int height);
/* Motion blur: the shutter opens `shutter` frames before the instant of v, when the camera was at
 * `open` (the previous frame's camera); between the two the camera moves by camera_view_pose. */
void camera_view_set_shutter(struct camera_view *v, const struct camera *open, float shutter);

/* A camera pose at one time inside the shutter (camera_view's fields of the same names). */
struct camera_pose {
    vec3 position, forward, right, up;
    float tan_half_y, tan_half_x;
};

/* The pose at shutter time `time` in [0, 1): 0 is the frame's instant, time t is t * shutter frames
 * earlier. Position and field of view move linearly, the view direction by spherical linear
 * interpolation, the up vector linearly (then orthonormalized). With no shutter, or at time 0,
 * it is v's own pose bit for bit. */
void camera_view_pose(const struct camera_view *v, float time, struct camera_pose *out);

/* The primary ray of a sample: image point (px, py) (pixel units, as camera_view_ray), lens
 * sample lens[2] in [0,1)^2 (mapped to the aperture disk by the concentric map; ignored for a
 * pinhole), at pose. A pinhole's ray is camera_view_ray's bit for bit. */
void camera_pose_ray(const struct camera_view *v, const struct camera_pose *pose, float px, float py,
                     const float lens[2], vec3 *origin, vec3 *dir);
/* The inverse: the image point whose ray from lens sample `lens` passes through world point p.
 * Writes the lens point to *origin. Returns 0 when p is not in front of the lens. */
int camera_pose_project(const struct camera_view *v, const struct camera_pose *pose, vec3 p, const float lens[2],
                        float *px, float *py, vec3 *origin);
/* The camera's dimensions of a sample: lens point and shutter time. */
struct camera_sample {
    float lens[2];
    float time;
};
/* Draws the dimensions v uses from rng (lens, then time); a pinhole without shutter draws none, so
 * its random streams are what they were before lenses and shutters. */
struct camera_sample camera_sample_draw(const struct camera_view *v, pcg32 *rng);
/* The primary ray of image point (px, py) with camera sample cs. */
void camera_sample_ray(const struct camera_view *v, const struct camera_sample *cs, float px, float py, vec3 *origin,
                       vec3 *dir);

/* Surface area per unit image area (pixels^2) at the point p with unit normal n, seen from lens
 * point `origin` at pose: |p - o|^2 cos^3(theta) / |cos_surface| * (2 tan_x / W)(2 tan_y / H)
 * with theta the angle between the ray and the optical axis. For a thin lens this holds for
 * every fixed lens point (the focal plane is where the image is measured). 0 when degenerate. */
float camera_pose_area_per_pixel(const struct camera_view *v, const struct camera_pose *pose, vec3 origin, vec3 p,
                                 vec3 n);
/* Unit direction of the ray through image point (px, py) in pixel units, (0,0) = top-left corner
 * of the image, pixel (i, j) covers [i, i+1) x [j, j+1). */
vec3 camera_view_ray(const struct camera_view *v, float px, float py);
/* Projects world point p to image coordinates; returns 0 when p is behind the camera. */
int camera_view_project(const struct camera_view *v, vec3 p, float *px, float *py);

/* Camera at a frame of the default path (or the static camera when path is 0). */
struct camera scene_camera_at(const struct scene *s, int use_path, float frame);

#endif
