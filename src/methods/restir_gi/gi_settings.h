/* gi_settings.h: ReSTIR GI's own settings: what a reused sample point's outgoing radiance is (gi.radiance), and
 * the boiling filter after its temporal reuse (gi.boiling_filter, gi.boiling_strength). */
#ifndef RESTIR_METHODS_RESTIR_GI_GI_SETTINGS_H
#define RESTIR_METHODS_RESTIR_GI_GI_SETTINGS_H

#include "render/params.h"

/* ReSTIR GI: a reused sample point's outgoing radiance toward the shading point that reuses it is
 * estimated again from the sample's own random numbers (unbiased), or the radiance the sample
 * point sent toward the pixel that first traced it (Ouyang et al. 2021; BIASED where the sample
 * point is glossy). */
enum gi_radiance_mode { GI_RADIANCE_REEVALUATE = 0, GI_RADIANCE_STORED };

struct gi_settings {
    enum gi_radiance_mode radiance;
    int boiling_filter;     /* BIASED: drop the temporal pass's outliers (render/boiling_filter.h) */
    float boiling_strength; /* its s: outliers exceed 10 / s - 9 times their group's mean target x W */
};

extern struct param_block gi_block;
static inline const struct gi_settings *gi_settings_of(const struct render_params *p)
{
    return param_block_in(p, &gi_block);
}
static inline struct gi_settings *gi_settings_mut(struct render_params *p) { return param_block_in_mut(p, &gi_block); }

#endif
