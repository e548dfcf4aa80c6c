/* test_camera_path.c: the camera path's spline passes through every key, holds still outside the
 * keys, starts and ends at rest, has continuous velocity across interior keys (unevenly spaced),
 * and a two-key path is exactly the smoothstep-eased straight line. */
#include <math.h>
#include <string.h>

#include "scene/scene.h"
#include "test_util.h"

static struct camera cam(float x, float y, float z, float fov)
{
    return (struct camera){v3(x, y, z), v3(0, 0, -5), v3(0, 1, 0), fov, 0.0f, 0.0f};
}

static float dist(vec3 a, vec3 b) { return v3_length(v3_sub(a, b)); }

int main(void)
{
    struct camera_key keys[4] = {
        {0, cam(0, 1, 5, 40)}, {10, cam(2, 1.5f, 4, 45)}, {14, cam(3, 1, 2, 50)}, {30, cam(0, 2, 1, 40)}};
    struct scene s;
    memset(&s, 0, sizeof s);
    s.camera = cam(9, 9, 9, 30);
    s.camera_path = (struct camera_path){4, keys};

    EXPECT(scene_camera_at(&s, 0, 5.0f).position.x == 9.0f, "use_path 0 gives the static camera");
    for (int k = 0; k < 4; k++) {
        struct camera c = scene_camera_at(&s, 1, keys[k].frame);
        EXPECT(dist(c.position, keys[k].cam.position) < 1e-5f && fabsf(c.vfov_deg - keys[k].cam.vfov_deg) < 1e-4f,
               "key %d is on the path (off by %g)", k, dist(c.position, keys[k].cam.position));
    }
    EXPECT(dist(scene_camera_at(&s, 1, -3.0f).position, keys[0].cam.position) == 0.0f, "holds before the first key");
    EXPECT(dist(scene_camera_at(&s, 1, 99.0f).position, keys[3].cam.position) == 0.0f, "holds after the last key");

    /* velocity by central differences on either side of each interior key, and at the ends */
    const float h = 2e-3f; /* one-sided estimates differ by O(h) times the jump in acceleration (C1, not C2) */
    for (int k = 1; k < 3; k++) {
        float t = keys[k].frame;
        vec3 before = v3_scale(v3_sub(scene_camera_at(&s, 1, t - h).position, scene_camera_at(&s, 1, t - 2 * h).position), 1.0f / h);
        vec3 after = v3_scale(v3_sub(scene_camera_at(&s, 1, t + 2 * h).position, scene_camera_at(&s, 1, t + h).position), 1.0f / h);
        /* both one-sided estimates sit 1.5 h from the key: they agree to O(h) when velocity is continuous */
        float jump = dist(before, after), speed = v3_length(before);
        EXPECT(speed > 0.05f && jump < 0.05f * speed + 1e-3f, "velocity continuous at key %d: %g vs speed %g", k, jump,
               speed);
        /* Catmull-Rom: the velocity at key k is (P_{k+1} - P_{k-1}) / (t_{k+1} - t_{k-1}) */
        vec3 want = v3_scale(v3_sub(keys[k + 1].cam.position, keys[k - 1].cam.position),
                             1.0f / (keys[k + 1].frame - keys[k - 1].frame));
        vec3 mid = v3_scale(v3_sub(scene_camera_at(&s, 1, t + h).position, scene_camera_at(&s, 1, t - h).position),
                            0.5f / h);
        EXPECT(dist(mid, want) < 0.02f * v3_length(want), "key %d velocity %g %g %g, want %g %g %g", k, mid.x, mid.y,
               mid.z, want.x, want.y, want.z);
    }
    vec3 start = v3_scale(v3_sub(scene_camera_at(&s, 1, h).position, keys[0].cam.position), 1.0f / h);
    vec3 end = v3_scale(v3_sub(keys[3].cam.position, scene_camera_at(&s, 1, 30.0f - h).position), 1.0f / h);
    EXPECT(v3_length(start) < 0.01f && v3_length(end) < 0.01f, "starts and ends at rest (%g, %g)", v3_length(start),
           v3_length(end));

    /* two keys: the smoothstep-eased line, bit for bit */
    s.camera_path.num_keys = 2;
    for (int i = 0; i <= 10; i++) {
        float f = (float)i;
        float u = f / 10.0f, t = u * u * (3.0f - 2.0f * u);
        vec3 want = v3_lerp(keys[0].cam.position, keys[1].cam.position, t);
        vec3 got = scene_camera_at(&s, 1, f).position;
        EXPECT(!memcmp(&want, &got, sizeof want), "two-key path at frame %g", f);
    }
    return test_finish();
}
