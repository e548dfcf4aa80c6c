/* emitter_material.h: the material the emitter-sampling tests build their scenes from: grey
 * Lambert with emission e (zero: not an emitter). Must never depend on render passes. */
#ifndef RESTIR_TEST_EMITTER_MATERIAL_H
#define RESTIR_TEST_EMITTER_MATERIAL_H

#include <string.h>

#include "scene/scene.h"

static inline struct material emitter_material(vec3 e)
{
    struct material m;
    memset(&m, 0, sizeof m);
    m.base_color = v3s(0.5f);
    m.roughness = 1.0f;
    m.emission = e;
    return m;
}

#endif
