/* reference_size.h: the image size a run measured against --ref FILE.exr renders at: the
 * reference's own unless --res says otherwise. Must never render. */
#ifndef RESTIR_EXPERIMENTS_REFERENCE_SIZE_H
#define RESTIR_EXPERIMENTS_REFERENCE_SIZE_H

#include "render/params.h"

/* Reads the size of the reference at path. size_given: --res (or a --params run description) set
 * p's size, which must then be the reference's: else -1 with msg naming both sizes. Otherwise p's
 * width and height become the reference's. Returns 0, or -1 with msg (also when path cannot be read). */
int reference_size_adopt(const char *path, int size_given, struct render_params *p, char *msg);

#endif
