/* shift_kind.c: the names of the ReSTIR PT shift mappings (shift_kind.h).
 * Must never depend on the scene or on paths. */
#include "render/shift_kind.h"

#include <string.h>

static const char *const kind_names[] = {"reconnection", "replay", "hybrid"};

int shift_kind_parse(const char *name, enum shift_kind *out)
{
    for (int k = 0; k < 3; k++) {
        if (strcmp(name, kind_names[k]) == 0) {
            *out = (enum shift_kind)k;
            return 0;
        }
    }
    return -1;
}

const char *shift_kind_name(enum shift_kind k) { return kind_names[k]; }
