/* image_io.h: every image and output-file function of src/io in one include (exr.h, png.h,
 * atomic_file.h), for code that writes frames. Must never depend on render code. */
#ifndef RESTIR_IO_IMAGE_IO_H
#define RESTIR_IO_IMAGE_IO_H

/* Writers write a temporary file and rename it, so a failure never leaves a half-written output. */
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/png.h"

#endif
