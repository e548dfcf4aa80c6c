/* reference_size.c: a run's size from its --ref (reference_size.h). Must never render. */
#include "experiments/reference_size.h"

#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "io/exr.h"

int reference_size_adopt(const char *path, int size_given, struct render_params *p, char *msg)
{
    float *img = NULL;
    int w = 0, h = 0;
    if (exr_read_rgb(path, &img, &w, &h, msg) != 0)
        return -1;
    free(img);
    if (!size_given) {
        p->width = w;
        p->height = h;
        return 0;
    }
    if (w == p->width && h == p->height)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN,
             "--res %dx%d differs from the reference %.300s, which is %dx%d (without --res the run takes the "
             "reference's size)",
             p->width, p->height, path, w, h);
    return -1;
}
