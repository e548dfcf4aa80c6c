/* test_bsdf_frame.c: the fused per-shading-point evaluations (bsdf_frame_eval and the batch
 * form) return the same f_r and pdf as bsdf_eval and bsdf_pdf for random materials and directions. */
#include "core/rng.h"
#include "core/sampling.h"
#include "shading/bsdf.h"
#include "test_util.h"

static float rel_diff(float a, float b) { return fabsf(a - b) / fmaxf(fmaxf(fabsf(a), fabsf(b)), 1e-6f); }

int main(void)
{
    pcg32 rng = pcg32_make(42, 7);
    float worst_f = 0.0f, worst_p = 0.0f;
    int zero_mismatch = 0, nonzero = 0;
    for (int k = 0; k < 200000; k++) {
        struct material m = {.base_color = v3(pcg32_float(&rng), pcg32_float(&rng), pcg32_float(&rng)),
                             .metallic = k % 3 == 0 ? 1.0f : pcg32_float(&rng),
                             .roughness = pcg32_float(&rng),
                             .emission = v3s(0.0f),
                             .lambert_only = k % 7 == 0};
        struct bsdf b;
        bsdf_from_material(&m, &b);
        vec3 n = warp_uniform_sphere(pcg32_float(&rng), pcg32_float(&rng));
        vec3 wo = warp_uniform_sphere(pcg32_float(&rng), pcg32_float(&rng));
        vec3 wi = warp_uniform_sphere(pcg32_float(&rng), pcg32_float(&rng));
        struct bsdf_frame bf;
        bsdf_frame_init(&bf, &b, n, wo);
        float pdf_fused;
        vec3 f_fused = bsdf_frame_eval(&bf, wi, &pdf_fused);
        vec3 f = bsdf_eval(&b, n, wo, wi);
        float pdf = bsdf_pdf(&b, n, wo, wi);
        float wx = wi.x, wy = wi.y, wz = wi.z, br, bg, bb, bpdf;
        bsdf_frame_eval_batch(&bf, 1, &wx, &wy, &wz, &br, &bg, &bb, &bpdf);
        vec3 f_batch = v3(br, bg, bb);
        if ((v3_max_component(f) > 0.0f) != (v3_max_component(f_fused) > 0.0f) || (pdf > 0.0f) != (pdf_fused > 0.0f) ||
            (v3_max_component(f) > 0.0f) != (v3_max_component(f_batch) > 0.0f) || (pdf > 0.0f) != (bpdf > 0.0f))
            zero_mismatch++;
        if (pdf > 0.0f) {
            nonzero++;
            worst_f = fmaxf(worst_f, rel_diff(v3_luminance(f), v3_luminance(f_fused)));
            worst_p = fmaxf(worst_p, rel_diff(pdf, pdf_fused));
            worst_f = fmaxf(worst_f, rel_diff(v3_luminance(f), v3_luminance(f_batch)));
            worst_p = fmaxf(worst_p, rel_diff(pdf, bpdf));
        }
    }
    printf("%d nonzero cases: worst relative difference f %.3g, pdf %.3g\n", nonzero, worst_f, worst_p);
    EXPECT(nonzero > 40000, "too few directions above the surface (%d)", nonzero);
    EXPECT(zero_mismatch == 0, "%d cases disagree on whether f or pdf is zero", zero_mismatch);
    EXPECT(worst_f < 1e-3f, "f differs by %g", worst_f);
    EXPECT(worst_p < 1e-3f, "pdf differs by %g", worst_p);
    return test_finish();
}
