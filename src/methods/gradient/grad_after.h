/* grad_after.h: Gradient after ReSTIR (002 Sec. 4.1, baseline B.1): each pixel's final ReSTIR path
 * Y_a with its unbiased contribution weight W_a, shifted into the four neighbors: one-sided
 * differences omega_an(Y_a) (f_a(Y_a) - f_n(T Y_a) |T'|) W_a (Eq. 11, omega by Eq. 13), combined
 * by Eq. 12 (grad_combine). Unbiased because omega_an vanishes wherever p_hat_a does, so the
 * integrand lies in the support W_a is a contribution weight for. Must never allocate. */
#ifndef RESTIR_METHODS_GRADIENT_GRAD_AFTER_H
#define RESTIR_METHODS_GRADIENT_GRAD_AFTER_H

#include "methods/restir_pt/restir_pt.h"

/* os (grad_common.h) += the one-sided differences of the final reservoirs res. Returns rays. */
long long grad_after_pass(const struct pt_frame *fr, const struct pt_reservoir *res, float *os);

#endif
