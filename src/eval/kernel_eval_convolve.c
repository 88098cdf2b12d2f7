/* kernel-eval in image space: the kernels, per-cell weights on cells of side h, become pixel
 * kernels by exact area resampling (a pixel of side p takes the part of each cell it covers;
 * separable: the pixel kernel of a product a(x) a(y) is the product of the pixel kernels of a),
 * then convolve the signal: the ground truth in 2-D (FFT), each model as its rank-N separable sum
 * and as its taps. */
#include <math.h>
#include <stdlib.h>

#include "eval/kernel_eval.h"

lucent_status ke_make_resampler(ke_run *ev)
{
    const lucent_kernel2d *gt = ev->res->ground_truth;
    double h = gt->h, p = ev->d.mm_per_pixel;
    int hp = (int)ceil((gt->half + 0.5) * h / p - 0.5);
    if (hp < 0) hp = 0;
    if (hp > LUCENT_CONVOLVE_MAX_SIZE / 2)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "kernel of %.4g mm needs %d pixels at %.4g mm per pixel (at most %d): raise --mm-per-pixel",
                            (gt->half + 0.5) * h, 2 * hp + 1, p, LUCENT_CONVOLVE_MAX_SIZE);
    int np = 2 * hp + 1, nc = 2 * gt->half + 1;
    ev->hp = hp;
    ev->res->kernel_pixels = np;
    ev->w = calloc((size_t)np * (size_t)nc, sizeof *ev->w);
    ev->wlo = malloc((size_t)np * sizeof *ev->wlo);
    ev->whi = malloc((size_t)np * sizeof *ev->whi);
    if (!ev->w || !ev->wlo || !ev->whi) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: resampler");
    for (int i = 0; i < np; i++) {
        double lo = (i - hp - 0.5) * p, hi = (i - hp + 0.5) * p;
        ev->wlo[i] = nc, ev->whi[i] = -1;
        for (int j = 0; j < nc; j++) {
            double clo = (j - gt->half - 0.5) * h, chi = (j - gt->half + 0.5) * h;
            double ov = fmin(hi, chi) - fmax(lo, clo);
            if (ov <= 0) continue;
            ev->w[(size_t)i * nc + j] = ov / h;
            if (j < ev->wlo[i]) ev->wlo[i] = j;
            ev->whi[i] = j;
        }
    }
    return LUCENT_OK;
}

static void resample_1d(const ke_run *ev, const double *a, float *dest)
{
    int np = 2 * ev->hp + 1, nc = 2 * ev->res->ground_truth->half + 1;
    for (int i = 0; i < np; i++) {
        double sum = 0;
        for (int j = ev->wlo[i]; j <= ev->whi[i]; j++) sum += ev->w[(size_t)i * nc + j] * a[j];
        dest[i] = (float)sum;
    }
}

/* The ground truth's channel c on the pixel grid, np * np floats. */
static lucent_status resample_2d(const ke_run *ev, int c, float *dest)
{
    int np = 2 * ev->hp + 1, nc = 2 * ev->res->ground_truth->half + 1;
    double *tmp = malloc((size_t)nc * (size_t)np * sizeof *tmp); /* tmp[yj][xi] */
    if (!tmp) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: resampling");
    const double *g = ev->res->ground_truth->value[c];
    for (int yj = 0; yj < nc; yj++)
        for (int xi = 0; xi < np; xi++) {
            double sum = 0;
            for (int xj = ev->wlo[xi]; xj <= ev->whi[xi]; xj++)
                sum += g[(size_t)yj * nc + xj] * ev->w[(size_t)xi * nc + xj];
            tmp[(size_t)yj * np + xi] = sum;
        }
    for (int yi = 0; yi < np; yi++)
        for (int xi = 0; xi < np; xi++) {
            double sum = 0;
            for (int yj = ev->wlo[yi]; yj <= ev->whi[yi]; yj++)
                sum += ev->w[(size_t)yi * nc + yj] * tmp[(size_t)yj * np + xi];
            dest[(size_t)yi * np + xi] = (float)sum;
        }
    free(tmp);
    return LUCENT_OK;
}

lucent_status ke_convolve_exact(ke_run *ev)
{
    int np = 2 * ev->hp + 1;
    float *w[3] = {NULL, NULL, NULL};
    lucent_status s = LUCENT_OK;
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        w[c] = malloc((size_t)np * (size_t)np * sizeof *w[c]);
        s = w[c] ? resample_2d(ev, c, w[c]) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: kernel");
    }
    lucent_conv_kernel2d k = {np, {w[0], w[1], w[2]}};
    if (s == LUCENT_OK)
        s = lucent_image_create(ev->signal->width, ev->signal->height, ev->signal->channels, &ev->exact);
    if (s == LUCENT_OK) s = lucent_convolve_2d(ev->signal, &k, LUCENT_BORDER_CLAMP, ev->d.pool, ev->exact);
    for (int c = 0; c < 3; c++) free(w[c]);
    return s;
}

lucent_status ke_convolve_separable(const ke_run *ev, const lucent_kernel *k, lucent_image *dest)
{
    int np = 2 * ev->hp + 1, nc = 2 * ev->res->ground_truth->half + 1, rank = k->rank;
    float *buf = malloc((size_t)2 * rank * 3 * np * sizeof *buf);
    const float **kx = malloc((size_t)2 * rank * 3 * sizeof *kx);
    if (!buf || !kx) {
        free(buf), free(kx);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: separable kernel");
    }
    const float **ky = kx + rank * 3;
    for (int r = 0; r < rank; r++)
        for (int c = 0; c < 3; c++) {
            float *x = buf + ((size_t)r * 3 + c) * np, *y = buf + ((size_t)(rank + r) * 3 + c) * np;
            resample_1d(ev, k->a[c] + (size_t)r * nc, y);
            for (int i = 0; i < np; i++) x[i] = (float)k->sign[c][r] * y[i];
            kx[r * 3 + c] = x, ky[r * 3 + c] = y;
        }
    lucent_status s =
        lucent_convolve_separable_sum(ev->signal, rank, kx, ky, np, LUCENT_BORDER_CLAMP, ev->d.pool, dest);
    free(buf);
    free(kx);
    return s;
}

lucent_status ke_convolve_taps(const ke_run *ev, const lucent_kernel *k, lucent_image *dest)
{
    lucent_taps_desc td = lucent_taps_defaults();
    td.count = ev->res->taps;
    lucent_taps *t = NULL;
    lucent_status s = lucent_kernel_taps(k, &td, &t);
    if (s != LUCENT_OK) return s;
    size_t n = (size_t)t->count, per = n * (size_t)t->rank;
    float *buf = malloc((n + 3 * per + 3 * (size_t)t->rank) * sizeof *buf);
    if (!buf) {
        lucent_taps_destroy(t);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: taps");
    }
    for (size_t i = 0; i < n; i++) buf[i] = (float)(t->offset[i] / ev->d.mm_per_pixel);
    lucent_conv_taps ct = {.count = t->count, .rank = t->rank, .offsets = buf};
    for (int c = 0; c < 3; c++) {
        float *w = buf + n + c * per, *sg = buf + n + 3 * per + (size_t)c * t->rank;
        for (size_t i = 0; i < per; i++) w[i] = (float)t->weight[c][i];
        for (int r = 0; r < t->rank; r++) sg[r] = (float)t->sign[c][r];
        ct.weights[c] = w, ct.sign[c] = sg;
    }
    s = lucent_convolve_taps(ev->signal, &ct, LUCENT_BORDER_CLAMP, ev->d.pool, dest);
    free(buf);
    lucent_taps_destroy(t);
    return s;
}
