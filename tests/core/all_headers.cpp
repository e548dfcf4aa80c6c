// all_headers.cpp: every public header of librestir compiled as C++ (scripts/check_core.sh builds
// it with g++ -std=c++11 -Wall -Wextra -Wpedantic -Werror and runs it), and a call of each kind of
// inline per-sample function, so that the headers stay valid C++ as well as C and CUDA.
#include "restir/cells.h"
#include "restir/grad.h"
#include "restir/gris.h"
#include "restir/hd.h"
#include "restir/metrics.h"
#include "restir/mis.h"
#include "restir/neighbors.h"
#include "restir/poisson.h"
#include "restir/select.h"
#include "restir/spmis.h"
#include "restir/threads.h"
#include "restir/version.h"
#include "restir/reservoir.h"

#include <cstdio>

int main()
{
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    restir_reservoir_offer(&r, 2.0f, 0.5f);
    float c[2] = {1.0f, 1.0f}, P[4] = {1.0f, 1.0f, 1.0f, 1.0f}, W[2] = {1.0f, 1.0f}, J[2] = {1.0f, 1.0f};
    float u[2] = {0.25f, 0.75f}, W_out = 0.0f;
    int chosen = restir_gris_resample(RESTIR_MIS_PAIRWISE, 2, c, P, W, J, u, &W_out);
    const float n[3] = {0.0f, 0.0f, 1.0f}, x[3] = {0.0f, 0.0f, 0.0f};
    float h = restir_neighbors_compat(x, n, 1.0f, x, n, 0.05f, 8.0f);
    struct restir_select s;
    restir_select_init(&s, 2);
    restir_select_offer(&s, 7, 1.0f, 0.5f);
    float f[3] = {1.0f, 0.5f, 0.25f}, g[3] = {0.5f, 0.5f, 0.5f}, d[3];
    restir_grad_pair_integrand(0, f, g, d);
    struct restir_spmis_conf k;
    restir_spmis_conf_set(&k, 1.0f, 2.0f, 1.0f);
    double m = restir_spmis_pairwise(&k, 1.0f, 1.0f, 1.0f);
    uint32_t key = restir_cells_key(3u, 1, n, 4);
    std::printf("all_headers (C++, librestir %s): chosen %d W %g compat %g select %d grad %g spmis %g key %u\n",
                RESTIR_VERSION_STRING, chosen, (double)W_out, (double)h, s.count, (double)d[0], m, key);
    return chosen >= 0 && W_out > 0.0f && h > 0.99f && s.count == 1 ? 0 : 1;
}
