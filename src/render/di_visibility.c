/* di_visibility.c: shadow rays for ReSTIR DI's visibility reuse and its visibility-aware targets. */
#include "render/di_visibility.h"

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
