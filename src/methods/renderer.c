/* renderer.c: runs one frame of a registered method: the camera view, the method's own passes
 * (struct method.render_frame), the non-finite guard on the image, and the timing. Must never read
 * or write files or name a method. */
#include "methods/renderer.h"
#include "scene/scene_animation.h"
#include "scene/scene_motion.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/simd.h"
#include "render/nonfinite.h"

_Static_assert(PASS_MAX <= 64, "struct frame_stats.reconstructed has a bit per pass id");

void renderer_init(struct renderer *r, const struct scene *s, const struct method *method, const struct render_params *p)
{
    memset(r, 0, sizeof(*r));
    r->scene = s;
    r->p = *p;
    r->method = method;
    method_params(method, &r->p);
    r->image = xcalloc(3 * (size_t)r->p.width * (size_t)r->p.height, sizeof(float));
    r->state = method->create(r);
    if (r->p.threads > 0)
        omp_set_num_threads(r->p.threads);
    if (r->p.denoise.method > 0) {
        r->denoiser = denoiser_create(&r->p.denoise, r->p.width, r->p.height);
        RESTIR_CHECK(r->denoiser != NULL);
        r->denoised = xcalloc(3 * (size_t)r->p.width * (size_t)r->p.height, sizeof(float));
    }
}

void renderer_fini(struct renderer *r)
{
    if (r->method && r->state)
        r->method->destroy(r->state);
    free(r->image);
    denoiser_destroy(r->denoiser);
    free(r->denoised);
    if (r->denoise_gbuffer) {
        gbuffer_fini(r->denoise_gbuffer);
        free(r->denoise_gbuffer);
    }
    memset(r, 0, sizeof(*r));
}

void renderer_reconstruct(struct renderer *r, struct frame_stats *st)
{
    if (!r->method->reconstruct)
        return;
    double before[PASS_MAX];
    memcpy(before, st->ms, sizeof before);
    r->method->reconstruct(r, r->state, st);
    for (int q = 0; q < PASS_MAX; q++)
        if (st->ms[q] != before[q])
            st->reconstructed |= 1ull << q;
}

void renderer_inspect(const struct renderer *r, struct renderer_inspect *out)
{
    memset(out, 0, sizeof(*out));
    if (r->method->inspect)
        r->method->inspect(r->state, out);
}

float *renderer_output(const struct renderer *r, int k)
{
    if (k < 0 || k >= method_output_count(r->method) || !r->method->output)
        return NULL;
    return r->method->output(r, r->state, k);
}

long long renderer_disoccluded(const struct renderer *r, int frames, unsigned char *mask)
{
    struct renderer_inspect in;
    renderer_inspect(r, &in);
    const int n = r->p.width * r->p.height;
    long long marked = 0;
    for (int i = 0; i < n; i++) {
        mask[i] = in.gbuffer && in.age && in.gbuffer->valid[i] && in.age[i] < frames;
        marked += mask[i];
    }
    return marked;
}

long long renderer_valid_pixels(const struct renderer *r)
{
    struct renderer_inspect in;
    renderer_inspect(r, &in);
    if (!in.gbuffer)
        return -1;
    long long valid = 0;
    for (int i = 0; i < in.gbuffer->width * in.gbuffer->height; i++)
        valid += in.gbuffer->valid[i];
    return valid;
}

void renderer_camera_view(const struct render_params *p, const struct camera *cam, const struct camera *open,
                          struct camera_view *v)
{
    struct camera c = *cam, o = open ? *open : *cam;
    if (p->camera_aperture > 0.0f)
        c.aperture = o.aperture = p->camera_aperture;
    if (p->camera_focus > 0.0f)
        c.focus_distance = o.focus_distance = p->camera_focus;
    camera_view_init(v, &c, p->width, p->height);
    if (p->camera_shutter > 0.0f)
        camera_view_set_shutter(v, &o, p->camera_shutter);
}

void renderer_set_shutter_open(struct renderer *r, const struct camera *open)
{
    r->prev_cam = *open;
    r->has_prev_cam = 1;
}

void renderer_denoise_guide(const struct gbuffer *g, struct denoise_guide *out)
{
    *out = (struct denoise_guide){g->width, g->height, g->position, g->normal,  g->depth,
                                  g->object, g->albedo, g->emission, g->motion, g->valid, NULL};
}

/* The frame in r->image denoised into r->denoised, guided by the method's G-buffer, or by one
 * traced through the pixel centres (its rays counted) where the method keeps none. */
static void renderer_denoise(struct renderer *r, const struct camera_view *view, struct frame_stats *st)
{
    struct renderer_inspect in;
    renderer_inspect(r, &in);
    const struct gbuffer *g = in.gbuffer;
    if (!g) {
        if (!r->denoise_gbuffer) {
            r->denoise_gbuffer = xmalloc(sizeof(struct gbuffer));
            gbuffer_init(r->denoise_gbuffer, r->p.width, r->p.height, 0);
        }
        st->rays += gbuffer_pass(r->denoise_gbuffer, r->scene, view, r->denoise_frames > 0 ? &r->prev_view : NULL, 0,
                                 r->p.seed, r->frame);
        g = r->denoise_gbuffer;
    }
    struct denoise_guide guide;
    renderer_denoise_guide(g, &guide);
    guide.temporal_gradient = in.gbuffer ? in.temporal_gradient : NULL;
    RESTIR_CHECK(denoiser_run(r->denoiser, r->image, &guide, r->denoised, &st->denoise) == 0);
    r->denoise_frames++;
}

void renderer_render(struct renderer *r, int frame, const struct camera *cam, struct frame_stats *st)
{
    memset(st, 0, sizeof(*st));
    struct camera_view view;
    renderer_camera_view(&r->p, cam, r->has_prev_cam ? &r->prev_cam : NULL, &view);
    r->lights_changed = r->rendered > 0 && scene_lights_differ(r->scene, (float)r->frame, (float)frame);
    r->lights_moved = r->rendered > 0 && scene_lights_moved(r->scene, (float)r->frame, (float)frame);
    r->rendered++;
    r->prev_cam = *cam;
    r->has_prev_cam = 1;
    simd_allow(r->p.simd); /* process-wide */
    double t0 = omp_get_wtime();
    r->prev_frame = r->frame;
    r->frame = frame;
    scene_set_frame(r->scene, (float)frame); /* animated emitters: this frame's lights */
    r->method->render_frame(r, r->state, &view, st);
    renderer_reconstruct(r, st);
    /* the frame's radiance (every method, reconstructions included) */
    st->nonfinite += nonfinite_discard_rgb(r->image, (size_t)r->p.width * (size_t)r->p.height);
    if (r->denoiser)
        RENDERER_TIMED(st, PASS_DENOISE, renderer_denoise(r, &view, st));
    r->prev_view = view;
    st->ms_total = 1e3 * (omp_get_wtime() - t0);
}
