/* Jimenez's separable skin kernel, Freude 2014 (4.8), as his separable-sss code builds it:
 * p(r) is the red channel of d'Eon & Luebke's six-Gaussian skin profile without its narrowest
 * Gaussian (that light is the delta term, weighted by 1 - strength), each Gaussian evaluated
 * at r / (0.001 + falloff) per channel. */
#include <math.h>

#include "kernel/internal.h"

static void defaults(const lucent_kernel_desc *d, double t[3], double f[3])
{
    lucent_kernel_desc def = lucent_kernel_defaults(LUCENT_KERNEL_JIMENEZ);
    bool st = d->strength[0] != 0 || d->strength[1] != 0 || d->strength[2] != 0;
    bool fa = d->falloff[0] != 0 || d->falloff[1] != 0 || d->falloff[2] != 0;
    for (int c = 0; c < 3; c++) {
        t[c] = st ? d->strength[c] : def.strength[c];
        f[c] = fa ? d->falloff[c] : def.falloff[c];
    }
}

lucent_status kernel_jimenez(const lucent_kernel2d *gt, const lucent_kernel_desc *d, lucent_kernel *k)
{
    double t[3], f[3];
    defaults(d, t, f);
    for (int c = 0; c < 3; c++)
        if (!(t[c] >= 0 && t[c] <= 1) || !(f[c] >= 0) || !isfinite(f[c]))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "jimenez kernel: strength must be in [0, 1] and falloff >= 0 "
                                "(channel %d)",
                                c);
    lucent_status st = kernel_alloc(k, 1, gt ? gt->half : 200, gt ? gt->h : 0.025);
    if (st != LUCENT_OK) return st;
    /* d'Eon & Luebke's skin, red channel, without its narrowest Gaussian (Jimenez's implementation). */
    lucent_sog skin;
    lucent_sog_deon_skin(&skin);
    const double *k_variance = skin.variance[0] + 1, *k_weight = skin.weight[0] + 1;
    k->gaussians = 5;
    for (int c = 0; c < 3; c++) {
        double s = 0.001 + f[c]; /* G(r / s; v) = exp(-r^2 / (2 v s^2)) / (2 pi v) */
        for (int g = 0; g < 5; g++) {
            k->gauss_variance[c][0][g] = k_variance[g] * s * s;
            k->gauss_weight[c][0][g] = k_weight[g] / (2 * M_PI * k_variance[g]);
        }
        k->strength[c] = t[c];
    }
    kernel_sample_gaussians(k);
    int n = kernel_n(k->half);
    for (int c = 0; c < 3; c++) { /* the sampled pass carries the delta: t p + (1 - t) delta */
        kernel_unit_sum(k, c);
        for (int j = 0; j < n; j++) k->a[c][j] *= t[c];
        k->a[c][k->half] += 1 - t[c];
    }
    k->range = 2;
    return LUCENT_OK;
}
