/* restir/mis.h: resampling MIS weights for GRIS (004 Sec. 2.4-2.7): 1/M, generalized balance and
 * defensive generalized pairwise. Pure functions of confidences and target values.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_MIS_H
#define RESTIR_MIS_H

#ifdef __cplusplus
extern "C" {
#endif

enum restir_mis {
    RESTIR_MIS_UNIFORM = 0, /* m_i = c_i / sum c: the "1/M" weights; BIASED when domains differ */
    RESTIR_MIS_BALANCE,     /* generalized balance heuristic, 004 Eq. 9 */
    RESTIR_MIS_PAIRWISE     /* defensive generalized pairwise MIS, 004 Eq. 11-12 */
};

/* Parses "1/M" (or "uniform"), "balance", "pairwise". Returns 0, or -1 for an unknown name. */
int restir_mis_parse(const char *name, enum restir_mis *out);
const char *restir_mis_name(enum restir_mis mode);

/* Which entries of the target matrix a mode reads: 1 when p_hat_{<-k}(Y_j) is needed. */
int restir_mis_needs(enum restir_mis mode, int k, int j);

/* Resampling MIS weights m_j(Y_j), j = 0..n-1, for one GRIS merge whose domain 0 is canonical.
 * c[k] are confidence weights; p[k * n + j] = p_hat_{<-k}(Y_j), the Jacobian-corrected target of
 * domain k at sample j shifted into the target domain (004 Eq. 10; 0 where Y_j is outside the
 * image of T_k). Only entries with restir_mis_needs(mode, k, j) are read. */
void restir_mis_weights(enum restir_mis mode, int n, const float *c, const float *p, float *m);

#ifdef __cplusplus
}
#endif

#endif
