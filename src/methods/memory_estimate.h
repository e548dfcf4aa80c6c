/* memory_estimate.h: what a renderer will allocate, known before it does (to refuse what the
 * machine cannot hold instead of being killed half way). */
#ifndef RESTIR_METHODS_MEMORY_ESTIMATE_H
#define RESTIR_METHODS_MEMORY_ESTIMATE_H

#include <stddef.h>

#include "methods/renderer.h"

/* Bytes a renderer of method with parameters p on scene s allocates, and per pixel. Measured, not
 * hand-counted: renderers are built at two small resolutions and the heap's growth (glibc's
 * mallinfo2, which sees every allocation, the reuse core's included) is fitted as fixed + per pixel
 * x pixels, which is what every buffer of the renderer is. */
size_t renderer_estimate_bytes(const struct scene *s, const struct method *method, const struct render_params *p,
                               double *bytes_per_pixel);

/* Memory the system can give now (MemAvailable of /proc/meminfo), 0 when unknown. */
size_t memory_available_bytes(void);

#endif
