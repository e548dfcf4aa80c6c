/* reference_pt.h: the pt the unbiasedness tests compare other methods with. They pin its random
 * numbers to independent PCG32 streams and its emitter choice to power, not pt's defaults
 * (sampler=sobol, lights.select=bvh): each run is then an i.i.d. draw whose variance the Welch
 * test models exactly, and a change of pt's defaults leaves these tests' realizations alone. pt's
 * defaults are proved against this pinned pt in render.pt_sampling_unbiased. With sobol as the
 * reference (half its variance), three cases failed one pixel each at |t| 4.2-4.9, and the same
 * cases with 3-4x more runs passed those pixels (docs/BENCHMARKS.md): the methods' heavy-tailed
 * run means then dominate the test's denominator. */
#ifndef RESTIR_TEST_REFERENCE_PT_H
#define RESTIR_TEST_REFERENCE_PT_H

#include "render/params.h"

static inline void reference_pt_pin(struct render_params *p)
{
    p->sampler = PT_SAMPLER_INDEPENDENT;
    p->light_selection = LIGHT_SELECT_POWER;
    p->light_env = LIGHT_ENV_MAP;
}

#endif
