// ris_pairwise.cu: librestir's per-sample functions in a CUDA kernel, the same code as on the CPU.
//
// Every "pixel" i of a 1-D image integrates f_i(x) = (x - c_i)^2 + 0.1 over [0, 1] outside a hole
// [c_i, c_i + 0.3) (modulo 1) where f_i = 0, known in closed form. The holes make the pixels'
// supports differ, which is where resampling MIS matters: 1/M weights would lose the mass of
// neighbor samples that fall in the canonical pixel's hole (set RESTIR_MIS_UNIFORM below and the
// check fails). Two kernels, as an engine would run them on the GPU:
//   1. initial RIS: M uniform candidates streamed through a restir_reservoir reservoir with target
//      p_hat_i = f_i and resampling weights (1/M) p_hat / p (restir_gris_resampling_weight);
//      the reservoir keeps its sample and contribution weight W (restir_gris_contribution_weight);
//   2. spatial reuse: pixel i merges its reservoir with those of pixels i -+ kOffset by GRIS
//      with defensive pairwise MIS (restir_gris_resample; the shift is the identity, Jacobian 1),
//      and estimates F_i = f_i(Y) W_Y.
// The host runs the same two functions on the CPU, checks that the image mean of the estimates
// matches the exact integrals within 4 standard errors, and, when a GPU is present, that the GPU
// gives the CPU's numbers. Without a GPU (or a driver) it says so and checks the CPU path only;
// --require-gpu makes that a failure.
//
// Build: nvcc -std=c++17 -fmad=false -I<prefix>/include ris_pairwise.cu -o ris_pairwise
// (header-only use of librestir: nothing to link). -fmad=false keeps the device from contracting
// a * b + c into FMAs, which the CPU build does not do either, so both round alike.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "restir/cells.h" // restir_cells_hash: the PCG hash, here our counter-based RNG
#include "restir/gris.h"

namespace {

constexpr int kPixels = 1 << 14;
constexpr int kCandidates = 8;
constexpr int kNeighbors = 2;
constexpr int kOffset = kPixels / 16; // neighbors' holes are shifted by 1/16
constexpr float kHole = 0.3f;

struct Reservoir {
    float x; // the sample, a point of [0, 1]
    float W; // its unbiased contribution weight (0: no sample)
};

RESTIR_HD float center(int pixel) { return (float)pixel / (float)kPixels; }

RESTIR_HD float integrand(int pixel, float x)
{
    float d = x - center(pixel);
    float into_hole = d >= 0.0f ? d : d + 1.0f; // distance past the hole's start, modulo 1
    return into_hole < kHole ? 0.0f : d * d + 0.1f;
}

// Integral of (x - c)^2 + 0.1 over [a, b].
double segment(double c, double a, double b)
{
    return ((b - c) * (b - c) * (b - c) - (a - c) * (a - c) * (a - c)) / 3.0 + 0.1 * (b - a);
}

// Exact integral of integrand(pixel, .) over [0, 1]: the whole interval minus the hole.
double exact(int pixel)
{
    double c = (double)center(pixel), end = c + (double)kHole;
    double hole = end <= 1.0 ? segment(c, c, end) : segment(c, c, 1.0) + segment(c, 0.0, end - 1.0);
    return segment(c, 0.0, 1.0) - hole;
}

// Uniform in [0, 1) from (seed, pixel, stream, index) by chaining the PCG hash.
RESTIR_HD float random01(unsigned seed, int pixel, int stream, int index)
{
    unsigned h = restir_cells_hash(seed);
    h = restir_cells_hash(h ^ (unsigned)pixel);
    h = restir_cells_hash(h ^ (unsigned)(stream * 1024 + index));
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

// Kernel 1's work for one pixel: RIS over kCandidates uniform candidates (source pdf 1).
RESTIR_HD Reservoir initial(unsigned seed, int pixel)
{
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    float chosen = 0.0f;
    for (int k = 0; k < kCandidates; k++) {
        float x = random01(seed, pixel, 0, k);
        float w = restir_gris_resampling_weight(1.0f / kCandidates, integrand(pixel, x), 1.0f, 1.0f);
        if (restir_reservoir_offer(&wrs, w, random01(seed, pixel, 1, k)))
            chosen = x;
    }
    Reservoir r = {chosen, restir_gris_contribution_weight(&wrs, integrand(pixel, chosen))};
    return r;
}

// Kernel 2's work for one pixel: GRIS merge of its reservoir (domain 0, canonical) with its two
// neighbors' under pairwise MIS, then the estimate f(Y) W_Y.
RESTIR_HD float spatial(unsigned seed, int pixel, const Reservoir *in)
{
    const int n = 1 + kNeighbors;
    int domain[n] = {pixel, (pixel + kPixels - kOffset) % kPixels, (pixel + kOffset) % kPixels};
    float c[n], P[n * n], W[n], J[n], u[n];
    for (int j = 0; j < n; j++) {
        const Reservoir &r = in[domain[j]];
        c[j] = 1.0f;                    // confidences: one initial reservoir each
        W[j] = r.W;
        J[j] = r.W > 0.0f ? 1.0f : 0.0f; // the identity shift; no sample, no shift
        u[j] = random01(seed, pixel, 2, j);
        // The target matrix of restir/mis.h: P[k n + j] = p_hat_k(Y_j), here without a Jacobian
        for (int k = 0; k < n; k++)
            P[k * n + j] = integrand(domain[k], r.x);
    }
    float W_out;
    int s = restir_gris_resample(RESTIR_MIS_PAIRWISE, n, c, P, W, J, u, &W_out);
    return s < 0 ? 0.0f : integrand(pixel, in[domain[s]].x) * W_out;
}

__global__ void initial_kernel(unsigned seed, Reservoir *out)
{
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < kPixels)
        out[i] = initial(seed, i);
}

__global__ void spatial_kernel(unsigned seed, const Reservoir *in, float *estimate)
{
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < kPixels)
        estimate[i] = spatial(seed, i, in);
}

// One frame on the CPU.
void frame_cpu(unsigned seed, std::vector<Reservoir> &res, std::vector<float> &estimate)
{
    for (int i = 0; i < kPixels; i++)
        res[i] = initial(seed, i);
    for (int i = 0; i < kPixels; i++)
        estimate[i] = spatial(seed, i, res.data());
}

// One frame on the GPU; false when a CUDA call failed (its message printed).
bool frame_gpu(unsigned seed, std::vector<float> &estimate)
{
    Reservoir *d_res = nullptr;
    float *d_est = nullptr;
    bool ok = cudaMalloc(&d_res, sizeof(Reservoir) * kPixels) == cudaSuccess &&
              cudaMalloc(&d_est, sizeof(float) * kPixels) == cudaSuccess;
    if (ok) {
        const int block = 256, grid = (kPixels + block - 1) / block;
        initial_kernel<<<grid, block>>>(seed, d_res);
        spatial_kernel<<<grid, block>>>(seed, d_res, d_est);
        ok = cudaGetLastError() == cudaSuccess &&
             cudaMemcpy(estimate.data(), d_est, sizeof(float) * kPixels, cudaMemcpyDeviceToHost) == cudaSuccess;
    }
    if (!ok)
        std::printf("ris_pairwise: CUDA: %s\n", cudaGetErrorString(cudaGetLastError()));
    cudaFree(d_res);
    cudaFree(d_est);
    return ok;
}

} // namespace

int main(int argc, char **argv)
{
    const bool require_gpu = argc > 1 && std::strcmp(argv[1], "--require-gpu") == 0;
    const int frames = 16;
    std::vector<Reservoir> res(kPixels);
    std::vector<float> cpu(kPixels), gpu(kPixels);

    // The image mean of the error over all frames and pixels, with its standard error.
    double sum = 0.0, sum2 = 0.0;
    for (int f = 0; f < frames; f++) {
        frame_cpu(1000u + (unsigned)f, res, cpu);
        for (int i = 0; i < kPixels; i++) {
            double e = (double)cpu[i] - exact(i);
            sum += e;
            sum2 += e * e;
        }
    }
    const double count = (double)frames * kPixels;
    const double bias = sum / count;
    const double se = std::sqrt((sum2 / count - bias * bias) / (count - 1.0));
    const bool unbiased = std::fabs(bias) <= 4.0 * se;
    std::printf("ris_pairwise: CPU, %d frames x %d pixels: mean error %.3e +- %.3e (%s)\n", frames, kPixels, bias,
                se, unbiased ? "consistent with 0" : "BIASED");

    int devices = 0;
    cudaError_t e = cudaGetDeviceCount(&devices);
    if (e != cudaSuccess || devices == 0) {
        std::printf("ris_pairwise: no CUDA device (%s): the GPU part did not run\n",
                    e != cudaSuccess ? cudaGetErrorString(e) : "none found");
        return unbiased && !require_gpu ? 0 : 1;
    }
    // The same frame on both: the same functions, rounded alike, must give the same numbers.
    frame_cpu(7u, res, cpu);
    if (!frame_gpu(7u, gpu))
        return 1;
    int differ = 0;
    double worst = 0.0;
    for (int i = 0; i < kPixels; i++) {
        if (cpu[i] != gpu[i])
            differ++;
        double rel = std::fabs((double)gpu[i] - cpu[i]) / (std::fabs((double)cpu[i]) + 1e-6);
        worst = rel > worst ? rel : worst;
    }
    std::printf("ris_pairwise: GPU vs CPU, %d pixels: %d differ, largest relative difference %.3e\n", kPixels, differ,
                worst);
    return unbiased && worst < 1e-5 ? 0 : 1;
}
