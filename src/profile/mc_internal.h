/* Internal to the Monte Carlo transport (src/profile/mc*.c): the prepared plan that the photon
 * kernel reads, and the fixed-point accumulators it writes. */
#ifndef LUCENT_SRC_PROFILE_MC_INTERNAL_H
#define LUCENT_SRC_PROFILE_MC_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "base/optics.h"
#include "lucent/mc.h"

/* Per-layer constants, precomputed in float for the kernel. */
typedef struct mc_layer_k {
    float z0, z1;                     /* top and bottom, mm (z1 = +inf for a semi-infinite layer) */
    float mut, inv_mut;               /* extinction sigma_a + sigma_s and its inverse */
    float absorb;                     /* sigma_a / sigma_t: the fraction of weight dropped per interaction */
    float g;                          /* HG anisotropy */
    double g_exact;                   /* g as given (1 - g in float loses digits near 1) */
    lucent_hg_f hg;                   /* the float Henyey-Greenstein sampler's constants (base/optics.h) */
    int hg_kind;                      /* 0: isotropic, 1: float HG, 2: double HG (|g| small), 3: |g| = 1 */
    float n;                          /* index of refraction */
    float n_up, n_down;               /* the indices beyond the top and the bottom boundary */
    float cos_crit_up, cos_crit_down; /* total internal reflection when |uz| <= these */
    int clear;                        /* sigma_t == 0: photons fly to the boundary */
} mc_layer_k;

/* Offsets (in int64 counters) of the per-batch 1-D scores. Radial and depth arrays hold one
 * more bin than the grid: weight beyond the grid, unless the last bin collects it. a_zl: the SIMD
 * kernels' absorption by depth bin and layer in one array, bin iz of layer l at iz + l (unique: both
 * grow with depth), nz + layers counters; mc_fold_zl adds it into a_z and a_l. */
typedef struct mc_layout {
    size_t rd_r, tt_r, rd_a, tt_a, a_z, a_l, capped, a_zl, batch_size; /* capped: packets stopped at the step limit */
    size_t rd_ra, tt_ra, a_rz, grid_size;
} mc_layout;

typedef struct mc_plan {
    int layer_count;
    mc_layer_k layers[LUCENT_MC_MAX_LAYERS];
    int nr, nz, na;
    int r_lim, z_lim; /* clamp for bin indices: n - 1 (MCML) or n (beyond bin) */
    double dr, dz;
    float inv_dr, inv_dz;
    double inv_da;
    double scale; /* fixed-point: counters hold weight * scale */
    uint64_t photons;
    int batches;
    float w_launch; /* 1 - Rsp */
    int launch_layer;
    float launch_z;
    int score_a_rz;
    uint64_t seed;
    mc_layout lay;
} mc_plan;

/* Traces photons [begin, end) with rng, adding to batch counters `batch` (batches * batch_size)
 * and grid counters `grid` (grid_size). The scalar kernel, the reference (mc_transport.c). */
void mc_trace(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch, int64_t *grid);

/* The depth bin of z as the kernels find it: float z / dz, clamped to z_lim. */
static inline int mc_depth_bin(const mc_plan *p, float z)
{
    float zb = z * p->inv_dz;
    int iz = zb >= (float)p->z_lim ? p->z_lim : (int)zb;
    return iz < 0 ? 0 : iz;
}

/* Adds every batch's a_zl into its a_z and a_l and zeroes it (after the counters of every thread
 * and process are summed: the fold is linear, so runs of any kernel add up before it). */
void mc_fold_zl(const mc_plan *plan, int64_t *batch);

/* The kernel of one instruction set (lucent_isa): the photons, and test hooks that evaluate its
 * approximations over arrays (n a multiple of `lanes`): -ln(m 2^-24), cos and sin of the azimuth
 * from 20 bits, Henyey-Greenstein's cos theta for g from xi (mc_lanes.h). */
typedef struct mc_kernel {
    lucent_isa isa;
    int lanes;
    void (*trace)(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch, int64_t *grid,
                  int64_t *scratch);
    void (*neglog)(const uint32_t *m, float *dest, size_t n);
    void (*sincos)(const uint32_t *phi, float *c, float *s, size_t n);
    void (*hg)(double g, const float *xi, float *mu, size_t n);
} mc_kernel;

/* The most lanes of any kernel, and the counters a SIMD kernel keeps per lane while a chunk runs
 * (each lane's absorption by depth bin and layer, so that lanes scoring the same bin do not wait on
 * each other; zero between chunks): `scratch`, this many per thread. */
#define MC_LANES_MAX 16
static inline size_t mc_scratch_size(const mc_plan *p)
{
    return (size_t)MC_LANES_MAX * ((size_t)p->nz + (size_t)p->layer_count);
}

/* The kernel of `isa` (AUTO: lucent_isa_active()); NULL where this build or CPU has none. */
const mc_kernel *mc_kernel_get(lucent_isa isa);

#if defined(LUCENT_SIMD_X86)
void mc_trace_avx2(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch, int64_t *grid,
                   int64_t *scratch);
void mc_simd_neglog_avx2(const uint32_t *m, float *dest, size_t n);
void mc_simd_sincos_avx2(const uint32_t *phi, float *c, float *s, size_t n);
void mc_simd_hg_avx2(double g, const float *xi, float *mu, size_t n);
void mc_trace_avx512(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch, int64_t *grid,
                     int64_t *scratch);
void mc_simd_neglog_avx512(const uint32_t *m, float *dest, size_t n);
void mc_simd_sincos_avx512(const uint32_t *phi, float *c, float *s, size_t n);
void mc_simd_hg_avx512(double g, const float *xi, float *mu, size_t n);
#endif

#endif
