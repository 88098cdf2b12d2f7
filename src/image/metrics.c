/* Statistics of one image, and errors of an image against a reference: RMS and relative RMS per
 * channel, optionally under a mask. Sums are kept in double. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/internal.h"

void lucent_image_stats_compute(const lucent_image *img, lucent_image_stats *dest)
{
    lucent_image_stats st = {.channels = img->channels};
    uint64_t finite[4] = {0};
    double sum[4] = {0};
    for (int c = 0; c < 4; c++) st.min[c] = INFINITY, st.max[c] = -INFINITY;
    size_t n = lucent_image_value_count(img);
    for (size_t i = 0; i < n; i++) {
        int c = (int)(i % (size_t)img->channels);
        double v = img->data[i];
        if (!isfinite(v)) {
            st.nonfinite[c]++;
            continue;
        }
        finite[c]++, sum[c] += v;
        if (v < st.min[c]) st.min[c] = v;
        if (v > st.max[c]) st.max[c] = v;
    }
    for (int c = 0; c < 4; c++) {
        st.mean[c] = finite[c] ? sum[c] / (double)finite[c] : 0.0;
        if (!finite[c]) st.min[c] = st.max[c] = 0.0;
    }
    *dest = st;
}

/* rms / reference rms, defined as 0 when both are 0 and +inf when only the reference's is. */
static double relative(double sq_err, double sq_ref)
{
    if (sq_ref > 0.0) return sqrt(sq_err / sq_ref);
    return sq_err > 0.0 ? INFINITY : 0.0;
}

lucent_status lucent_image_compare(const lucent_image *a, const lucent_image *b, const float *mask,
                                   lucent_image_error_stats *dest)
{
    lucent_status s = image_check_same(a, b);
    if (s != LUCENT_OK) return s;
    lucent_image_error_stats r = {.channels = a->channels};
    double err[4] = {0}, ref[4] = {0}, err_all = 0, ref_all = 0;
    size_t n = (size_t)a->width * (size_t)a->height, ch = (size_t)a->channels;
    for (size_t i = 0; i < n; i++) {
        if (mask && !(mask[i] > 0.5f)) continue;
        r.pixel_count++;
        for (size_t c = 0; c < ch; c++) {
            double d = (double)a->data[i * ch + c] - b->data[i * ch + c], v = b->data[i * ch + c];
            err[c] += d * d, ref[c] += v * v;
            if (fabs(d) > r.max_abs[c] || isnan(d)) r.max_abs[c] = fabs(d);
        }
    }
    if (r.pixel_count == 0) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mask selects no pixel (none > 0.5)");
    for (size_t c = 0; c < ch; c++) {
        r.rms[c] = sqrt(err[c] / (double)r.pixel_count);
        r.rel_rms[c] = relative(err[c], ref[c]);
        err_all += err[c], ref_all += ref[c];
    }
    r.rms_all = sqrt(err_all / ((double)r.pixel_count * (double)ch));
    r.rel_rms_all = relative(err_all, ref_all);
    *dest = r;
    return LUCENT_OK;
}

lucent_status lucent_image_compare_masked(const lucent_image *a, const lucent_image *b, const lucent_image *mask,
                                          lucent_image_error_stats *dest)
{
    if (mask && (mask->channels != 1 || mask->width != a->width || mask->height != a->height))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "mask is %dx%d with %d channels; expected %dx%d with 1 channel", mask->width, mask->height,
                            mask->channels, a->width, a->height);
    return lucent_image_compare(a, b, mask ? mask->data : NULL, dest);
}

lucent_status lucent_image_difference(const lucent_image *a, const lucent_image *b, lucent_diff_mode mode,
                                      lucent_image **dest)
{
    *dest = NULL;
    lucent_status s = image_check_same(a, b);
    if (s == LUCENT_OK) s = lucent_image_create(a->width, a->height, a->channels, dest);
    if (s != LUCENT_OK) return s;
    size_t n = lucent_image_value_count(a);
    for (size_t i = 0; i < n; i++) {
        float d = a->data[i] - b->data[i];
        (*dest)->data[i] = mode == LUCENT_DIFF_ABSOLUTE ? fabsf(d) : d;
    }
    return LUCENT_OK;
}

lucent_status lucent_image_error_map(const lucent_image *a, const lucent_image *b, bool relative, float epsilon,
                                     lucent_image **dest)
{
    *dest = NULL;
    lucent_status s = image_check_same(a, b);
    if (s == LUCENT_OK) s = lucent_image_create(a->width, a->height, 1, dest);
    if (s != LUCENT_OK) return s;
    float eps = epsilon > 0.0f ? epsilon : 0.01f;
    size_t n = (size_t)a->width * (size_t)a->height, ch = (size_t)a->channels;
    size_t colour = ch == 4 ? 3 : ch;
    for (size_t i = 0; i < n; i++) {
        float sum = 0.0f;
        for (size_t c = 0; c < colour; c++) {
            float d = fabsf(a->data[i * ch + c] - b->data[i * ch + c]);
            sum += relative ? d / (fabsf(b->data[i * ch + c]) + eps) : d;
        }
        (*dest)->data[i] = sum / (float)colour;
    }
    return LUCENT_OK;
}

static int compare_floats(const void *x, const void *y)
{
    float a = *(const float *)x, b = *(const float *)y;
    return (a > b) - (a < b);
}

lucent_status lucent_image_percentile(const lucent_image *img, int c, double p, float *dest)
{
    *dest = 0.0f;
    size_t n = (size_t)img->width * (size_t)img->height, k = 0;
    float *v = malloc(n * sizeof *v);
    if (!v) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for a percentile");
    for (size_t i = 0; i < n; i++) {
        float x = img->data[i * (size_t)img->channels + (size_t)c];
        if (isfinite(x)) v[k++] = x;
    }
    if (k) {
        qsort(v, k, sizeof *v, compare_floats);
        double pc = p < 0 ? 0 : p > 100 ? 100 : p;
        size_t rank = (size_t)ceil(pc / 100.0 * (double)k); /* nearest rank: ceil(p/100 N) */
        *dest = v[rank ? rank - 1 : 0];
    }
    free(v);
    return LUCENT_OK;
}
