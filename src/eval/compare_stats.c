/* compare's statistics: the paired test of two methods against one reference, and the calibration of
 * its standard error by two independent runs of the reference (seeds). */
#include <math.h>
#include <stdlib.h>

#include "eval/internal.h"

static lucent_status check_same(const lucent_image *a, const lucent_image *b, const char *what)
{
    if (!a || !b || a->width != b->width || a->height != b->height || a->channels < 3 || b->channels < 3)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "compare: %s: images of different sizes or fewer than 3 channels", what);
    return LUCENT_OK;
}

static inline float px(const lucent_image *im, size_t i, int c)
{
    return im->data[i * (size_t)im->channels + (size_t)c];
}

lucent_status lucent_compare_paired(const lucent_image *a, const lucent_image *b, const lucent_image *ref,
                                    const lucent_image *var, const float *mask, double inflation,
                                    lucent_compare_pair *dest)
{
    *dest = (lucent_compare_pair){0};
    lucent_status s = check_same(a, ref, "paired test");
    if (s == LUCENT_OK) s = check_same(b, ref, "paired test");
    if (s == LUCENT_OK) s = check_same(var, ref, "paired test (variance)");
    if (s != LUCENT_OK) return s;
    double d = 0, v = 0, r2 = 0;
    for (size_t i = 0; i < (size_t)ref->width * (size_t)ref->height; i++) {
        if (mask && !(mask[i] > 0.5f)) continue;
        for (int c = 0; c < 3; c++) {
            double r = px(ref, i, c), ea = px(a, i, c) - r, eb = px(b, i, c) - r, w = px(a, i, c) - px(b, i, c);
            d += ea * ea - eb * eb, v += w * w * px(var, i, c), r2 += r * r;
        }
    }
    if (!(r2 > 0)) return LUCENT_OK;
    double k = inflation > 1 ? inflation : 1;
    /* d = sum (a - t - n)^2 - (b - t - n)^2 = sum (a - t)^2 - (b - t)^2 - 2 sum (a - b) n: the reference's
     * noise n enters once, linearly, weighted by the methods' difference */
    dest->d = d / r2;
    dest->se = 2 * sqrt(k * v) / r2;
    dest->z = dest->se > 0 ? dest->d / dest->se : dest->d == 0 ? 0 : copysign(INFINITY, dest->d);
    return LUCENT_OK;
}

/* Adds over the blocks of one weight w = a - b the squared block sums of w (r1 - r2) to *num and the
 * per-pixel prediction sum w^2 (v1 + v2) to *den. */
static void inflation_terms(const lucent_image *a, const lucent_image *b, const lucent_image *const run[4],
                            const float *mask, int block, double *num, double *den)
{
    const lucent_image *r1 = run[0], *v1 = run[1], *r2 = run[2], *v2 = run[3];
    int w = r1->width, h = r1->height;
    for (int by = 0; by < h; by += block)
        for (int bx = 0; bx < w; bx += block) {
            double sum[3] = {0, 0, 0};
            for (int y = by; y < by + block && y < h; y++)
                for (int x = bx; x < bx + block && x < w; x++) {
                    size_t i = (size_t)y * (size_t)w + (size_t)x;
                    if (mask && !(mask[i] > 0.5f)) continue;
                    for (int c = 0; c < 3; c++) {
                        double wt = (double)px(a, i, c) - px(b, i, c);
                        sum[c] += wt * ((double)px(r1, i, c) - px(r2, i, c));
                        *den += wt * wt * ((double)px(v1, i, c) + px(v2, i, c));
                    }
                }
            /* the three channels of a pixel share their paths: one sum over them */
            double t = sum[0] + sum[1] + sum[2];
            *num += t * t;
        }
}

lucent_status lucent_compare_noise_inflation(const lucent_image *const *images, int count, const lucent_image *r1,
                                             const lucent_image *v1, const lucent_image *r2, const lucent_image *v2,
                                             const float *mask, int block, double *dest)
{
    *dest = 1;
    lucent_status s = check_same(r1, r2, "noise inflation");
    if (s == LUCENT_OK) s = check_same(v1, r1, "noise inflation (variance)");
    if (s == LUCENT_OK) s = check_same(v2, r1, "noise inflation (variance)");
    for (int i = 0; i < count && s == LUCENT_OK; i++) s = check_same(images[i], r1, "noise inflation (method)");
    if (s != LUCENT_OK) return s;
    if (block < 1) block = LUCENT_COMPARE_INFLATION_BLOCK;
    const lucent_image *run[4] = {r1, v1, r2, v2};
    double num = 0, den = 0;
    for (int i = 0; i < count; i++)
        for (int j = i + 1; j < count; j++) inflation_terms(images[i], images[j], run, mask, block, &num, &den);
    if (den > 0) *dest = num / den;
    return LUCENT_OK;
}

bool lucent_compare_separated(const lucent_compare_pair *p) { return fabs(p->z) >= LUCENT_COMPARE_Z; }
