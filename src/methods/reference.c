/* reference.c: the running-mean reference (reference.h). */
#include "methods/reference.h"

#include <stdio.h>
#include <string.h>

#include "core/check.h"
#include "methods/renderer.h"
#include "render/pt.h"

void reference_accum_init(struct reference_accum *a, const struct scene *s, const struct method *method,
                          const struct render_params *p, const struct camera *cam, const struct camera *open, int spp)
{
    memset(a, 0, sizeof *a);
    a->scene = s;
    a->params = *p;
    method_reference_params(method, &a->params);
    renderer_camera_view(&a->params, cam, open, &a->view);
    a->spp = spp;
    const size_t n = 3 * (size_t)a->params.width * (size_t)a->params.height;
    a->mean = xcalloc(n, sizeof(float));
    a->chunk = xcalloc(n, sizeof(float));
}

void reference_accum_init_shard(struct reference_accum *a, const struct scene *s, const struct method *method,
                                const struct render_params *p, const struct camera *cam, const struct camera *open,
                                int first_chunk, int spp)
{
    reference_accum_init(a, s, method, p, cam, open, spp);
    a->first_chunk = first_chunk;
}

int reference_accum_can_resume(int done, int spp)
{
    return done >= 0 && done <= spp && (done % REFERENCE_CHUNK_SPP == 0 || done == spp);
}

void reference_accum_resume(struct reference_accum *a, const float *mean, int done)
{
    RESTIR_CHECK(reference_accum_can_resume(done, a->spp));
    memcpy(a->mean, mean, 3 * sizeof(float) * (size_t)a->params.width * (size_t)a->params.height);
    a->done = done;
}

long long reference_accum_step(struct reference_accum *a)
{
    RESTIR_CHECK(a->done < a->spp);
    const int c = a->first_chunk + a->done / REFERENCE_CHUNK_SPP;
    const int k = a->spp - a->done < REFERENCE_CHUNK_SPP ? a->spp - a->done : REFERENCE_CHUNK_SPP;
    /* sampler=sobol: chunk c continues one sequence at point c REFERENCE_CHUNK_SPP */
    long long rays = pt_pass_chunk(a->scene, &a->view, &a->params, REFERENCE_FRAME_BASE + c, REFERENCE_FRAME_BASE,
                                   (uint32_t)c * REFERENCE_CHUNK_SPP, k, a->chunk);
    const double done = a->done, total = a->done + k;
    const ptrdiff_t n = 3 * (ptrdiff_t)a->params.width * a->params.height;
#pragma omp parallel for schedule(static)
    for (ptrdiff_t i = 0; i < n; i++)
        a->mean[i] = (float)(((double)a->mean[i] * done + (double)a->chunk[i] * k) / total);
    a->done += k;
    return rays;
}

void reference_accum_fini(struct reference_accum *a)
{
    free(a->mean);
    free(a->chunk);
    memset(a, 0, sizeof *a);
}

void reference_describe(const struct reference_accum *a, char *out, size_t len)
{
    const struct render_params *p = &a->params;
    const struct camera_view *v = &a->view; /* what the primary rays are made of, exactly (%a) */
    snprintf(out, len,
             "scene=%016llx; res=%dx%d; seed=%llu; camera=%a,%a,%a/%a,%a,%a/%a,%a,%a/%a,%a,%a/%a,%a; "
             "pt.max_bounces=%d; pt.rr_bounces=%d; jitter=%d; chunk=%d",
             (unsigned long long)scene_content_hash(a->scene), p->width, p->height, (unsigned long long)p->seed,
             v->position.x, v->position.y, v->position.z, v->forward.x, v->forward.y, v->forward.z, v->right.x,
             v->right.y, v->right.z, v->up.x, v->up.y, v->up.z, v->tan_half_x, v->tan_half_y, p->max_bounces,
             p->rr_bounces, p->jitter, REFERENCE_CHUNK_SPP);
    /* the lens and the shutter only where they are on, so earlier references keep their id */
    size_t used = strlen(out);
    if (v->lens_radius > 0.0f && used < len)
        used += (size_t)snprintf(out + used, len - used, "; lens=%a,%a", v->lens_radius, v->focus_distance);
    if (p->sampler == PT_SAMPLER_SOBOL && used < len) /* as the lens: earlier references keep their id */
        used += (size_t)snprintf(out + used, len - used, "; sampler=sobol");
    if (p->light_sampling == LIGHT_SAMPLING_SOLID_ANGLE && used < len)
        used += (size_t)snprintf(out + used, len - used, "; lights=solid-angle");
    if (p->light_selection == LIGHT_SELECT_BVH && used < len)
        used += (size_t)snprintf(out + used, len - used, "; lights.select=bvh");
    if (v->shutter > 0.0f && used < len)
        snprintf(out + used, len - used, "; shutter=%a; open=%a,%a,%a/%a,%a,%a/%a,%a,%a/%a", v->shutter,
                 v->open_position.x, v->open_position.y, v->open_position.z, v->open_forward.x, v->open_forward.y,
                 v->open_forward.z, v->open_up.x, v->open_up.y, v->open_up.z, v->open_tan_half_y);
}
