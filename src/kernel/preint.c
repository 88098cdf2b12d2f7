/* Pre-integration model, Freude 2014 (5.15)-(5.18): a_p(x) = integral R_d(x, y) dy and
 * a = a_p / sqrt(||R_d||_1), exact for additively separable irradiance E1(x) + E2(y). */
#include <math.h>

#include "kernel/internal.h"

lucent_status kernel_preint(const lucent_kernel2d *gt, lucent_kernel *k)
{
    int n = kernel_n(gt->half);
    lucent_status st = kernel_alloc(k, 1, gt->half, gt->h);
    if (st != LUCENT_OK) return st;
    for (int c = 0; c < 3; c++) {
        double norm = 0;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                k->a[c][j] += gt->value[c][i * n + j]; /* (5.17) */
                norm += fabs(gt->value[c][i * n + j]);
            }
        for (int j = 0; j < n; j++) k->a[c][j] /= sqrt(norm); /* (5.18) */
    }
    return LUCENT_OK;
}
