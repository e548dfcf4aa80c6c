/* di_visibility.c: shadow rays for ReSTIR DI's visibility reuse and its visibility-aware targets. */
#include "methods/restir_di/di_visibility.h"

int di_visibility_query(const struct shading_point *sp, const struct di_sample *y, struct ray_query *q)
{
    if (y->tri == DI_ENV_TRI) { /* a direction: nothing in the scene along it */
        *q = (struct ray_query){scene_offset_point(sp->p, sp->ng, y->p), y->p, 0.0f, INFINITY};
        return 1;
    }
    return scene_visibility_query(sp->p, sp->ng, y->p, y->n, q);
}

int di_sample_visible(const struct scene *s, const struct shading_point *sp, const struct di_sample *y)
{
    struct ray_query q;
    return !di_visibility_query(sp, y, &q) || !scene_occluded(s, q.o, q.d, q.tmin, q.tmax);
}

float di_domain_target(const struct scene *s, int with_visibility, const struct shading_point *sp,
                       const struct di_sample *y, long long *rays)
{
    float t = di_target(sp, y);
    if (!with_visibility || !(t > 0.0f))
        return t;
    (*rays)++;
    return di_sample_visible(s, sp, y) ? t : 0.0f;
}

/* Traces the shadow rays of the entries e with out[e] > 0 and (previous == NULL ? 1 : previous[e] == which),
 * zeroing those occluded; returns the rays counted. */
static long long trace_entries(const struct scene *s, int n, const struct shading_point *const *sp,
                               const struct di_sample *const *y, float *out, const unsigned char *previous, int which,
                               struct ray_query *q, int *ray_entry, unsigned char *occluded)
{
    long long rays = 0;
    int traced = 0;
    for (int e = 0; e < n; e++) {
        if (!(out[e] > 0.0f) || (previous ? previous[e] : 0) != which)
            continue;
        rays++; /* counted as di_domain_target counts it, also where the points coincide */
        if (di_visibility_query(sp[e], y[e], &q[traced]))
            ray_entry[traced++] = e;
    }
    if (which)
        scene_occluded_previous_batch(s, q, traced, occluded);
    else
        scene_occluded_batch(s, q, traced, occluded);
    for (int r = 0; r < traced; r++)
        if (occluded[r])
            out[ray_entry[r]] = 0.0f;
    return rays;
}

long long di_domain_target_many(const struct scene *s, int with_visibility, int n,
                                const struct shading_point *const *sp, const struct di_sample *const *y, float *out,
                                const unsigned char *previous, struct ray_query *q, int *ray_entry,
                                unsigned char *occluded)
{
    di_target_many(n, sp, y, out);
    if (!with_visibility)
        return 0;
    long long rays = trace_entries(s, n, sp, y, out, previous, 0, q, ray_entry, occluded);
    if (previous)
        rays += trace_entries(s, n, sp, y, out, previous, 1, q, ray_entry, occluded);
    return rays;
}
