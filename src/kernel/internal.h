/* Shared helpers of src/kernel (not public). */
#ifndef LUCENT_KERNEL_INTERNAL_H
#define LUCENT_KERNEL_INTERNAL_H

#include "lucent/kernel.h"

/* n = 2 half + 1. */
static inline int kernel_n(int half) { return 2 * half + 1; }

/* Allocates k->a for rank passes on (half, h); zero samples, signs +1, strength 1. */
lucent_status kernel_alloc(lucent_kernel *k, int rank, int half, double h);

/* Samples the analytic Gaussians of k into k->a. */
void kernel_sample_gaussians(lucent_kernel *k);

/* Scales channel c of rank-1 kernel k so that its 2-D sum (sum a)^2 is 1. */
void kernel_unit_sum(lucent_kernel *k, int c);

/* Sets k->range to the half-width holding 99.5% of each pass's 1-D mass (max over passes and
 * channels). */
void kernel_default_range(lucent_kernel *k);

lucent_status kernel_svd(const lucent_kernel2d *gt, const lucent_kernel_desc *d, lucent_kernel *k);
lucent_status kernel_preint(const lucent_kernel2d *gt, lucent_kernel *k);
lucent_status kernel_guided(const lucent_kernel2d *gt, const lucent_kernel_desc *d, lucent_kernel *k);
lucent_status kernel_manual(const lucent_kernel2d *gt, const char *material, const lucent_kernel_desc *d,
                            lucent_kernel *k);
lucent_status kernel_sog(const lucent_kernel2d *gt, const lucent_profile *p, const lucent_kernel_desc *d,
                         lucent_kernel *k);
lucent_status kernel_jimenez(const lucent_kernel2d *gt, const lucent_kernel_desc *d, lucent_kernel *k);

#endif
