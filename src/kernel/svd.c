/* SVD rank-N model, Freude 2014 (5.5)-(5.10), with the optional 1-norm scaling (5.12). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/internal.h"

/* Decomposes one channel (n x n, row-major): s (n), u and vt (n x n). */
static lucent_status decompose(const double *m, int n, double *s, double *u, double *vt)
{
    double *copy = malloc((size_t)n * n * sizeof *copy);
    if (!copy) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel svd: out of memory");
    memcpy(copy, m, (size_t)n * n * sizeof *copy);
    lapack_int info = LAPACKE_dgesdd(LAPACK_ROW_MAJOR, 'A', n, n, copy, n, s, u, n, vt, n);
    free(copy);
    if (info != 0) return lucent_error(LUCENT_ERR_NUMERIC, "kernel svd: LAPACKE_dgesdd failed (info %d)", (int)info);
    return LUCENT_OK;
}

/* a_i = u^(i) sqrt(sigma_i) (5.10); sign_i = sign(u^(i) . v^(i)) (-1 where the symmetric kernel
 * has a negative eigenvalue); each pass oriented to a non-negative sum. */
static void take_passes(lucent_kernel *k, int c, int n, const double *s, const double *u, const double *vt)
{
    for (int p = 0; p < k->rank; p++) {
        double dot = 0, sum = 0;
        for (int j = 0; j < n; j++) {
            dot += u[j * n + p] * vt[p * n + j];
            sum += u[j * n + p];
        }
        double f = sqrt(s[p]) * (sum < 0 ? -1 : 1);
        k->sign[c][p] = dot < 0 ? -1 : 1;
        for (int j = 0; j < n; j++) k->a[c][p * n + j] = f * u[j * n + p];
    }
}

lucent_status kernel_svd(const lucent_kernel2d *gt, const lucent_kernel_desc *d, lucent_kernel *k)
{
    int n = kernel_n(gt->half);
    lucent_status st = kernel_alloc(k, d->rank > 0 ? d->rank : 1, gt->half, gt->h);
    double *s = malloc((size_t)n * sizeof *s), *u = malloc((size_t)n * n * sizeof *u),
           *vt = malloc((size_t)n * n * sizeof *vt);
    if (st == LUCENT_OK && (!s || !u || !vt)) st = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel svd: out of memory");
    for (int c = 0; c < 3 && st == LUCENT_OK; c++) {
        st = decompose(gt->value[c], n, s, u, vt);
        if (st == LUCENT_OK) take_passes(k, c, n, s, u, vt);
    }
    free(s);
    free(u);
    free(vt);
    if (st != LUCENT_OK || !d->normalize) return st;
    double norm[3];
    lucent_kernel_norm1(k, norm); /* (5.11); the ground truth's 1-norm is 1 */
    for (int c = 0; c < 3; c++)
        for (int j = 0; j < n * k->rank; j++) k->a[c][j] /= sqrt(norm[c]); /* (5.12) */
    return LUCENT_OK;
}
