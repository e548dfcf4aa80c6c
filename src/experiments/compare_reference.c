/* compare_reference.c: a comparison's references: what they integrate (the integrand's pt), their seeds
 * (independent of the runs and of each other) and cameras, rendered at once or resumably for a
 * plan's job (compare_run.h). */
#include "experiments/compare_run.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "experiments/cli.h"
#include "experiments/reference_checkpoint.h"

/* What the reference at frame `frame` renders: its params and cameras. */
static const struct method *reference_inputs(const struct compare_setup *st, int frame, struct render_params *rp,
                                       struct camera *cam, struct camera *open)
{
    *rp = st->p;
    /* independent of the compared runs and of the other frames' references */
    rp->seed = reference_seed(st->p.seed);
    if (frame != st->o.frames - 1)
        rp->seed += 0x2545F4914F6CDD1Dull * (uint64_t)(frame + 1);
    cli_frame_cameras(&st->s, st->p.camera_path, frame, cam, open);
    return st->integrand;
}

float *compare_render_reference_at(const struct compare_setup *st, int frame)
{
    struct render_params rp;
    struct camera cam, open;
    const struct method *m = reference_inputs(st, frame, &rp, &cam, &open);
    return cli_render_reference(&st->s, m, &rp, &cam, &open, st->o.ref_spp);
}

int compare_render_reference_pair(const struct compare_setup *st, const char *out, struct reference_pair *r,
                                  char *msg)
{
    struct render_params rp;
    struct camera cam, open;
    const struct method *m = reference_inputs(st, st->o.frames - 1, &rp, &cam, &open);
    return reference_render_pair(&st->s, m, &rp, &cam, &open, st->o.ref_spp, out, r, msg);
}

void compare_reference_noise(struct compare_result *res, int n, const float *a, const float *b, const float *ref,
                             size_t npix)
{
    struct restir_metrics_error own = {NAN, NAN, NAN, NAN};
    if (a && b)
        restir_metrics_compute(a, ref, npix, NULL, &own); /* |a - r| = |a - b| / 2 */
    for (int k = 0; k < n; k++) {
        double share = NAN;
        res[k].ref_own_dis = NAN;
        if (a && b) /* half a over run 0's disoccluded pixels: MAPE there, as ref_own[1] overall */
            compare_disoccluded_error(a, ref, res[k].dis_mask, npix, &res[k].ref_own_dis, &share);
        free(res[k].dis_mask);
        res[k].dis_mask = NULL;
        res[k].ref_own[0] = own.relmse;
        res[k].ref_own[1] = own.mape;
        res[k].ref_own[2] = own.smape;
        res[k].relmse_net = res[k].err.relmse - own.relmse; /* NaN without halves */
        for (int r = 0; res[k].per_run && r < res[k].runs; r++) {
            double *v = &res[k].per_run[(size_t)r * COMPARE_RUN_COLS];
            v[COMPARE_RUN_COLS - 1] = v[0] - own.relmse;
        }
    }
}
