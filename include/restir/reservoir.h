/* restir/reservoir.h: weighted reservoir sampling and GRIS bookkeeping, independent of what a
 * sample is: the caller keeps the sample, the library decides which candidate wins and what
 * contribution weight it gets. Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_RESERVOIR_H
#define RESTIR_RESERVOIR_H

#ifdef __cplusplus
extern "C" {
#endif

/* Streaming weighted reservoir sampling (Chao 1982): after offering candidates with weights w_i,
 * candidate i is selected with probability w_i / sum_j w_j. */
struct restir_wrs {
    float w_sum;
    int selected;  /* index of the selected candidate among those offered, -1 if none */
    int offered;   /* number of candidates offered */
};

void restir_wrs_init(struct restir_wrs *r);
/* Offers a candidate with resampling weight w >= 0 using uniform u in [0,1). Returns 1 when the
 * candidate becomes the selection (the caller then stores its sample), 0 otherwise. Weights that
 * are not finite or not positive are counted as offered and never selected. */
int restir_wrs_offer(struct restir_wrs *r, float w, float u);
/* Merges reservoir b (which summarizes its own stream) into a: b's selection wins with
 * probability b.w_sum / (a.w_sum + b.w_sum). Returns 1 when b's selection is taken. */
int restir_wrs_merge(struct restir_wrs *a, const struct restir_wrs *b, float u);

/* Unbiased contribution weight of the GRIS output Y (004 Eq. 7): W_Y = sum_j w_j / p_hat(Y).
 * Returns 0 when nothing was selected or p_hat(Y) <= 0. With resampling MIS weights that sum to
 * one (004 Eq. 8), classic RIS is the special case m_i = 1/M. */
float restir_gris_contribution_weight(const struct restir_wrs *r, float target_of_selected);

/* Confidence of a GRIS output: the sum of input confidences, capped (004 Sec. 2.5). */
float restir_confidence_merge(float c_sum, float cap);

#ifdef __cplusplus
}
#endif

#endif
