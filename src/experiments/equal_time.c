/* equal_time.c: the equal-time budget by paths per pixel, probed by rendering (equal_time.h). */
#include "experiments/equal_time.h"

#include "experiments/stats.h"

double equal_time_frame_ms(const struct scene *s, const struct method *m, const struct render_params *p,
                           const struct camera *cam, int frame, int spp)
{
    struct render_params q = *p;
    struct renderer r;
    struct frame_stats st;
    q.spp = spp;
    renderer_init(&r, s, m, &q);
    renderer_render(&r, frame, cam, &st); /* warm-up */
    renderer_render(&r, frame + 1, cam, &st);
    renderer_fini(&r);
    return st.ms_total;
}

int equal_time_spp_for(const struct scene *s, const struct method *m, const struct render_params *p,
                       const struct camera *cam, int frame, double budget_ms)
{
    const double ms_1spp = equal_time_frame_ms(s, m, p, cam, frame, 1);
    return equal_time_spp(budget_ms, ms_1spp, equal_time_frame_ms(s, m, p, cam, frame, 4));
}
