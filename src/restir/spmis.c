/* restir/spmis.c: stochastic pairwise MIS weights (004 Eq. 15-19), the confidence adjustment
 * (Sec. 4.3) and the draws of Algorithm 2 from one reuse cell.
 * Must never depend on a ray tracer, files or the renderer. */
#include "restir/spmis.h"

float restir_spmis_confidence_scale(int n_candidates, int m, int adjust)
{
    if (!adjust || m <= 0 || n_candidates <= 0 || n_candidates >= m)
        return 1.0f;
    return (float)n_candidates / (float)m;
}

void restir_spmis_conf_set(struct restir_spmis_conf *k, float c_c, float c_sigma_raw, float scale)
{
    k->c_c = c_c;
    k->scale = scale;
    k->c_sigma = scale * c_sigma_raw;
}

double restir_spmis_pairwise(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c)
{
    /* 004 Eq. 11a with c_i and c_sigma scaled alike */
    double cs = k->c_sigma, cc = k->c_c, ci = (double)k->scale * c_i;
    double ctot = cs + cc, d = cs * p_from + cc * p_c;
    if (!(ctot > 0.0) || !(d > 0.0))
        return 0.0;
    return (cs / ctot) * ci * p_from / d;
}

double restir_spmis_noncanonical(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                 double factor)
{
    /* 004 Eq. 16 = Eq. 15 applied to Eq. 11a, one draw at a time */
    return factor * restir_spmis_pairwise(k, c_i, p_from, p_c);
}

double restir_spmis_canonical_share(const struct restir_spmis_conf *k)
{
    double ctot = (double)k->c_sigma + k->c_c;
    return ctot > 0.0 ? k->c_c / ctot : 1.0;
}

double restir_spmis_canonical_term(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                   double factor)
{
    /* 004 Eq. 19, weighted by the Eq. 18 factor K(i) / (N_c P_c(i)) one draw at a time */
    double cs = k->c_sigma, cc = k->c_c, ci = (double)k->scale * c_i;
    double ctot = cs + cc, d = cs * p_from + cc * p_c;
    if (!(ctot > 0.0) || !(d > 0.0))
        return 0.0;
    return factor * (ci / ctot) * cc * p_c / d;
}

void restir_spmis_canonical_draws(const struct restir_cells *cells, int cell, int canonical, int n_c,
                                  enum restir_spmis_pick pick, const float *u, struct restir_spmis_draws *out)
{
    out->count = 0;
    int m = restir_cells_others(cells, cell, canonical);
    if (m <= 0)
        return;
    if (n_c <= 0) {
        for (int s = cell; s < cell + cells->count[cell]; s++) {
            if (cells->entry[s] == canonical)
                continue;
            out->pixel[out->count] = cells->entry[s];
            out->factor[out->count++] = 1.0;
        }
        return;
    }
    if (n_c > RESTIR_SPMIS_MAX_DRAWS)
        n_c = RESTIR_SPMIS_MAX_DRAWS;
    for (int j = 0; j < n_c; j++) {
        if (pick == RESTIR_SPMIS_PICK_CONFIDENCE) {
            double prob;
            int i = restir_cells_pick_confidence(cells, cell, canonical, u[j], &prob);
            if (i < 0)
                return; /* the others have no confidence: every beta_i is 0 (004 Eq. 19) */
            out->pixel[out->count] = i;
            out->factor[out->count++] = 1.0 / ((double)n_c * prob);
        } else {
            out->pixel[out->count] = restir_cells_pick_uniform(cells, cell, canonical, u[j]);
            out->factor[out->count++] = (double)m / (double)n_c; /* P_c = 1 / M (004 Sec. 4.2) */
        }
    }
}

void restir_spmis_neighbor_draws(const struct restir_cells *cells, int cell, int canonical, int n, const float *u,
                                 struct restir_spmis_draws *out)
{
    out->count = 0;
    if (cell < 0)
        return;
    if (n <= 0) {
        for (int s = cell; s < cell + cells->contributing[cell]; s++) {
            if (cells->entry[s] == canonical)
                continue;
            out->pixel[out->count] = cells->entry[s];
            out->factor[out->count++] = 1.0;
        }
        return;
    }
    if (n > RESTIR_SPMIS_MAX_DRAWS)
        n = RESTIR_SPMIS_MAX_DRAWS;
    for (int j = 0; j < n; j++) {
        double prob;
        int z = restir_cells_pick_weighted(cells, cell, canonical, u[j], &prob);
        if (z < 0)
            return; /* no other pixel contributes: no draw at all */
        out->pixel[out->count] = z;
        out->factor[out->count++] = 1.0 / ((double)n * prob); /* 004 Eq. 15: 1 / (N P(z)) */
    }
}
