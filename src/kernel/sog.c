/* d'Eon & Luebke's sum of Gaussians as a rank-N model: each 2-D Gaussian w G(v, r) is separable,
 * w G(v, r) = (sqrt(w) g(x; v)) (sqrt(w) g(y; v)), g the unit 1-D Gaussian: two passes per
 * Gaussian (Freude (4.4)), fitted to the material's profile by lucent_sog_fit. */
#include <math.h>

#include "kernel/internal.h"

/* Multi-starts of the fit: 2 instead of lucent_sog_fit's 8 keeps every preset under 0.5 s for
 * rank 4 (bench_kernel); the kernel-space RMS of the rank-1..4 fits did not change visibly. */
enum { SOG_STARTS = 2 };

static void take_fit(lucent_kernel *k, const lucent_sog *fit)
{
    for (int c = 0; c < 3; c++) {
        double total = 0;
        for (int i = 0; i < fit->count; i++) total += fit->weight[c][i];
        for (int i = 0; i < fit->count; i++) {
            double v = fit->variance[c][i], w = total > 0 ? fit->weight[c][i] / total : 0;
            k->gauss_variance[c][i][0] = v;
            k->gauss_weight[c][i][0] = sqrt(w) / sqrt(2 * M_PI * v);
        }
    }
}

/* Scales every pass of channel c so that the discrete 2-D sum is 1. */
static void unit_sum(lucent_kernel *k, int c)
{
    int n = kernel_n(k->half);
    double total = 0;
    for (int p = 0; p < k->rank; p++) {
        double s = 0;
        for (int j = 0; j < n; j++) s += k->a[c][p * n + j];
        total += s * s;
    }
    if (!(total > 0)) return;
    double f = 1 / sqrt(total);
    for (int j = 0; j < n * k->rank; j++) k->a[c][j] *= f;
    for (int p = 0; p < k->rank; p++) k->gauss_weight[c][p][0] *= f;
}

lucent_status kernel_sog(const lucent_kernel2d *gt, const lucent_profile *p, const lucent_kernel_desc *d,
                         lucent_kernel *k)
{
    if (!p) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel sog: needs the material's profile");
    int rank = d->rank > 0 ? d->rank : 1;
    lucent_sog fit;
    lucent_status st = lucent_sog_fit(p, &(lucent_sog_desc){.count = rank, .starts = SOG_STARTS}, &fit);
    if (st == LUCENT_OK) st = kernel_alloc(k, rank, gt->half, gt->h);
    if (st != LUCENT_OK) return st;
    k->gaussians = 1;
    take_fit(k, &fit);
    kernel_sample_gaussians(k);
    for (int c = 0; c < 3; c++) unit_sum(k, c);
    return LUCENT_OK;
}
