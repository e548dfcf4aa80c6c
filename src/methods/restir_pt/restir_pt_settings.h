/* restir_pt_settings.h: ReSTIR PT's own setting, the initial paths it resamples per pixel (pt.candidates),
 * read by restir-pt, area-restir and the gradient methods on their passes. The reuse, SPMIS and shift
 * settings they read are the toolkit's (render/params.h). */
#ifndef RESTIR_METHODS_RESTIR_PT_RESTIR_PT_SETTINGS_H
#define RESTIR_METHODS_RESTIR_PT_RESTIR_PT_SETTINGS_H

#include "render/params.h"

struct restir_pt_settings {
    int candidates; /* initial paths per pixel */
};

extern struct param_block restir_pt_block;
static inline const struct restir_pt_settings *restir_pt_settings_of(const struct render_params *p)
{
    return param_block_in(p, &restir_pt_block);
}
static inline struct restir_pt_settings *restir_pt_settings_mut(struct render_params *p)
{
    return param_block_in_mut(p, &restir_pt_block);
}

/* The boiling filter after the temporal pass (render/boiling_filter.h; BIASED), read by restir-pt and
 * area-restir only: pt.boiling_filter, pt.boiling_strength. */
struct restir_pt_boiling_settings {
    int filter;     /* on: empty the temporal pass's outliers by target x W */
    float strength; /* s: outliers exceed 10 / s - 9 times their group's mean */
};

extern struct param_block restir_pt_boiling_block;
static inline const struct restir_pt_boiling_settings *restir_pt_boiling_of(const struct render_params *p)
{
    return param_block_in(p, &restir_pt_boiling_block);
}

#endif
