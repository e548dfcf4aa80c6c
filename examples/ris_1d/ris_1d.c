/* ris_1d.c: librestir from an application that owns its samples. Estimates the integral of
 * f(x) = x^2 over [0, 1] (exactly 1/3) by RIS: per estimate, M uniform candidates resampled by
 * streaming WRS with weights p_hat(x) / p(x), p_hat(x) = x, then f(Y) W_Y with W_Y the GRIS
 * contribution weight (restir_gris_contribution_weight). Prints the mean over many independent
 * estimates with its standard error and exits 1 when it is more than 4 standard errors from 1/3.
 * Built against the installed package by scripts/check_core.sh, through pkg-config and CMake. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "restir/gris.h"
#include "restir/version.h"

/* A small generator of the application's own (xorshift64*): librestir leaves random numbers to it. */
static double uniform(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1.0p-53;
}

int main(void)
{
    enum { M = 8, RUNS = 200000 };
    uint64_t s = 0x9e3779b97f4a7c15ull;
    double sum = 0.0, sum2 = 0.0;
    for (int r = 0; r < RUNS; r++) {
        struct restir_reservoir wrs;
        restir_reservoir_init(&wrs);
        float y = 0.0f;
        for (int k = 0; k < M; k++) {
            const float x = (float)uniform(&s);
            const float w = x / (float)M; /* m_i p_hat(x) / p(x), m_i = 1/M, p = 1 */
            if (restir_reservoir_offer(&wrs, w, (float)uniform(&s)))
                y = x;
        }
        const float W = restir_gris_contribution_weight(&wrs, y); /* p_hat(Y) = Y */
        const double est = (double)y * y * W;                        /* f(Y) W_Y */
        sum += est;
        sum2 += est * est;
    }
    const double mean = sum / RUNS, se = sqrt((sum2 / RUNS - mean * mean) / (RUNS - 1));
    printf("librestir %s: RIS estimate of the integral of x^2 on [0,1]: %.5f +- %.5f (exact 0.33333)\n",
           RESTIR_VERSION_STRING, mean, se);
    return fabs(mean - 1.0 / 3.0) <= 4.0 * se ? 0 : 1;
}
