/* restir/spmis.c: stochastic pairwise MIS weights (004 Eq. 15-19), the confidence adjustment
 * (Sec. 4.3) and the draws of Algorithm 2 from one reuse cell.
 * Must never depend on a ray tracer, files or the renderer. */
#include "restir/spmis.h"

int restir_spmis_canonical_draws(const struct restir_cells *cells, int cell, int canonical, int n_c,
                                 enum restir_spmis_pick pick, const float *u, struct restir_spmis_draws *out)
{
    if (!cells || !out || (n_c > 0 && !u) ||
        (pick != RESTIR_SPMIS_PICK_UNIFORM && pick != RESTIR_SPMIS_PICK_CONFIDENCE))
        return -1;
    out->count = 0;
    int m = restir_cells_others(cells, cell, canonical); /* 0 also for a cell not of the last build */
    if (m <= 0)
        return 0;
    if (n_c <= 0) {
        for (int s = cell; s < cell + cells->count[cell]; s++) {
            if (cells->entry[s] == canonical)
                continue;
            out->pixel[out->count] = cells->entry[s];
            out->factor[out->count++] = 1.0;
        }
        return 0;
    }
    if (n_c > RESTIR_SPMIS_MAX_DRAWS)
        n_c = RESTIR_SPMIS_MAX_DRAWS;
    for (int j = 0; j < n_c; j++) {
        if (pick == RESTIR_SPMIS_PICK_CONFIDENCE) {
            double prob;
            int i = restir_cells_pick_confidence(cells, cell, canonical, u[j], &prob);
            if (i < 0)
                return 0; /* the others have no confidence: every beta_i is 0 (004 Eq. 19) */
            out->pixel[out->count] = i;
            out->factor[out->count++] = 1.0 / ((double)n_c * prob);
        } else {
            out->pixel[out->count] = restir_cells_pick_uniform(cells, cell, canonical, u[j]);
            out->factor[out->count++] = (double)m / (double)n_c; /* P_c = 1 / M (004 Sec. 4.2) */
        }
    }
    return 0;
}

int restir_spmis_neighbor_draws(const struct restir_cells *cells, int cell, int canonical, int n, const float *u,
                                struct restir_spmis_draws *out)
{
    if (!cells || !out || (n > 0 && !u))
        return -1;
    out->count = 0;
    if (n <= 0) {
        /* no other pixel, or not a cell of the last build: nothing to enumerate (the picks below
         * return -1 there by themselves) */
        if (restir_cells_others(cells, cell, canonical) <= 0)
            return 0;
        for (int s = cell; s < cell + cells->contributing[cell]; s++) {
            if (cells->entry[s] == canonical)
                continue;
            out->pixel[out->count] = cells->entry[s];
            out->factor[out->count++] = 1.0;
        }
        return 0;
    }
    if (n > RESTIR_SPMIS_MAX_DRAWS)
        n = RESTIR_SPMIS_MAX_DRAWS;
    for (int j = 0; j < n; j++) {
        double prob;
        int z = restir_cells_pick_weighted(cells, cell, canonical, u[j], &prob);
        if (z < 0)
            return 0; /* no other pixel contributes: no draw at all */
        out->pixel[out->count] = z;
        out->factor[out->count++] = 1.0 / ((double)n * prob); /* 004 Eq. 15: 1 / (N P(z)) */
    }
    return 0;
}
