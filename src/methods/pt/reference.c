/* reference.c: the running-mean reference (reference.h). */
#include "methods/pt/reference.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/check.h"
#include "methods/renderer.h"
#include "methods/pt/pt.h"

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
    float *m2 = a->m2;
#pragma omp parallel for schedule(static)
    for (ptrdiff_t i = 0; i < n; i++) {
        const float old = a->mean[i];
        a->mean[i] = (float)(((double)old * done + (double)a->chunk[i] * k) / total);
        if (m2) /* West 1979: M2 += w (x - mean_old)(x - mean_new) */
            m2[i] = (float)((double)m2[i] + k * ((double)a->chunk[i] - old) * ((double)a->chunk[i] - a->mean[i]));
    }
    a->done += k;
    a->var_obs += m2 != NULL;
    return rays;
}

void reference_accum_track_variance(struct reference_accum *a, const float *m2, int var_obs)
{
    const size_t n = 3 * (size_t)a->params.width * (size_t)a->params.height;
    free(a->m2);
    a->m2 = xcalloc(n, sizeof(float));
    if (m2) {
        memcpy(a->m2, m2, n * sizeof(float));
        a->var_obs = var_obs;
    } else {
        a->var_obs = a->done > 0;
    }
}

double reference_accum_relmse_estimate(const struct reference_accum *a)
{
    if (!a->m2 || a->var_obs < REFERENCE_VARIANCE_MIN_OBS || a->done < 1)
        return INFINITY;
    const int w = a->params.width, h = a->params.height;
    const double scale = 1.0 / ((double)(a->var_obs - 1) * a->done);
    /* per-row sums, added in row order: the same number whatever the thread count, so the stop
     * rule that reads it stops every run at the same chunk */
    double *row = xmalloc(sizeof(double) * (size_t)h);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        double sum = 0.0;
        for (ptrdiff_t i = 3 * (ptrdiff_t)y * w; i < 3 * (ptrdiff_t)(y + 1) * w; i++)
            sum += (double)a->m2[i] * scale / ((double)a->mean[i] * a->mean[i] + 1e-3);
        row[y] = sum;
    }
    double sum = 0.0;
    for (int y = 0; y < h; y++)
        sum += row[y];
    free(row);
    return sum / (3.0 * w * (double)h);
}

void reference_accum_fini(struct reference_accum *a)
{
    free(a->mean);
    free(a->chunk);
    free(a->m2);
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
    if (p->light_sampling == LIGHT_SAMPLING_AUTO && used < len)
        used += (size_t)snprintf(out + used, len - used, "; lights=auto");
    if (p->light_selection == LIGHT_SELECT_BVH && used < len)
        used += (size_t)snprintf(out + used, len - used, "; lights.select=bvh");
    if (p->light_env == LIGHT_ENV_COMPENSATED && used < len)
        used += (size_t)snprintf(out + used, len - used, "; lights.env=compensated");
    if (v->shutter > 0.0f && used < len)
        snprintf(out + used, len - used, "; shutter=%a; open=%a,%a,%a/%a,%a,%a/%a,%a,%a/%a", v->shutter,
                 v->open_position.x, v->open_position.y, v->open_position.z, v->open_forward.x, v->open_forward.y,
                 v->open_forward.z, v->open_up.x, v->open_up.y, v->open_up.z, v->open_tan_half_y);
}
