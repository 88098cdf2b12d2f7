/* compare's measures: the object mask, the reference's own noise, the error maps, and the image
 * files of a method or reference. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "eval/internal.h"

uint64_t lucent_compare_object_mask(const lucent_image *c, float *dest)
{
    uint64_t count = 0;
    for (size_t i = 0; i < (size_t)c->width * (size_t)c->height; i++) dest[i] = 0;
    for (int y = 1; y + 1 < c->height; y++)
        for (int x = 1; x + 1 < c->width; x++) {
            bool inside = true;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) inside = inside && lucent_image_get(c, x + dx, y + dy, 0) >= 0.999f;
            dest[(size_t)y * (size_t)c->width + (size_t)x] = inside;
            count += inside;
        }
    return count;
}

double lucent_compare_reference_noise(const lucent_image *m, const lucent_image *v, const float *mask)
{
    double var = 0, sq = 0;
    for (size_t i = 0; i < (size_t)m->width * (size_t)m->height; i++)
        for (int c = 0; c < 3 && (!mask || mask[i] > 0.5f); c++) {
            double r = m->data[i * (size_t)m->channels + (size_t)c];
            var += v->data[i * (size_t)v->channels + (size_t)c], sq += r * r;
        }
    return sq > 0 ? sqrt(var / sq) : 0;
}

void lucent_compare_error_colour(double e, double scale, float rgb[3])
{
    double t = fmin(fabs(e) / (scale > 0 ? scale : LUCENT_COMPARE_ERROR_MAP_SCALE), 1.0);
    if (!(t >= 0)) t = 0; /* NaN: black */
    static const float bright[3] = {1.0f, 0.32f, 0.0f}, dark[3] = {0.05f, 0.35f, 1.0f};
    const float *c = e > 0 ? bright : dark;
    for (int k = 0; k < 3; k++) rgb[k] = (float)t * c[k];
}

/* The signed relative error of pixel i: mean over R, G, B of (m - r) / (r + 0.01). */
static double signed_error(const lucent_image *img, const lucent_image *ref, size_t i)
{
    double e = 0;
    for (int c = 0; c < 3; c++) {
        double m = img->data[i * (size_t)img->channels + (size_t)c],
               r = ref->data[i * (size_t)ref->channels + (size_t)c];
        e += (m - r) / (fabs(r) + 0.01);
    }
    return e / 3;
}

static lucent_status check_pair(const lucent_image *img, const lucent_image *ref)
{
    if (img->width != ref->width || img->height != ref->height || img->channels < 3 || ref->channels < 3)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: images of %dx%dx%d and %dx%dx%d", img->width,
                            img->height, img->channels, ref->width, ref->height, ref->channels);
    return LUCENT_OK;
}

static int by_decreasing(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

lucent_status lucent_compare_concentration(const lucent_image *img, const lucent_image *ref, const float *mask,
                                           double fraction, double *share)
{
    *share = 0;
    lucent_status s = check_pair(img, ref);
    if (s != LUCENT_OK) return s;
    if (!(fraction > 0 && fraction <= 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: the worst pixels' fraction %g is not in (0, 1]",
                            fraction);
    size_t n = (size_t)img->width * (size_t)img->height, count = 0;
    double *e = malloc((n ? n : 1) * sizeof *e), total = 0, top = 0;
    if (!e) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "compare: %zu pixels' errors", n);
    for (size_t i = 0; i < n; i++) {
        if (mask && !(mask[i] > 0.5f)) continue;
        double d = 0;
        for (int c = 0; c < 3; c++) {
            double x =
                img->data[i * (size_t)img->channels + (size_t)c] - ref->data[i * (size_t)ref->channels + (size_t)c];
            d += x * x;
        }
        e[count++] = d, total += d;
    }
    qsort(e, count, sizeof *e, by_decreasing);
    size_t k = (size_t)ceil(fraction * (double)count);
    for (size_t i = 0; i < k && i < count; i++) top += e[i];
    free(e);
    *share = total > 0 && isfinite(total) ? top / total : 0;
    return LUCENT_OK;
}

lucent_status lucent_compare_error_map(const lucent_image *img, const lucent_image *ref, const float *mask,
                                       lucent_image **dest)
{
    *dest = NULL;
    lucent_status s = check_pair(img, ref);
    if (s == LUCENT_OK) s = lucent_image_create(img->width, img->height, 3, dest);
    for (size_t i = 0; s == LUCENT_OK && i < (size_t)img->width * (size_t)img->height; i++) {
        double e = !mask || mask[i] > 0.5f ? signed_error(img, ref, i) : 0;
        lucent_compare_error_colour(e, LUCENT_COMPARE_ERROR_MAP_SCALE, (*dest)->data + 3 * i);
    }
    return s;
}

lucent_status lucent_compare_error_scale_image(lucent_image **dest)
{
    lucent_status s = lucent_image_create(256, 14, 3, dest);
    for (int x = 0; s == LUCENT_OK && x < 256; x++) {
        float rgb[3];
        lucent_compare_error_colour(LUCENT_COMPARE_ERROR_MAP_SCALE * ((x + 0.5) / 128.0 - 1.0),
                                    LUCENT_COMPARE_ERROR_MAP_SCALE, rgb);
        for (int y = 0; y < 14; y++)
            for (int c = 0; c < 3; c++) lucent_image_set(*dest, x, y, c, rgb[c]);
    }
    return s;
}

lucent_status lucent_compare_worst_region(const lucent_image *img, const lucent_image *ref, const float *mask, int size,
                                          int *x0, int *y0)
{
    *x0 = *y0 = 0;
    lucent_status s = check_pair(img, ref);
    if (s != LUCENT_OK) return s;
    int w = img->width, h = img->height;
    if (size > w) size = w;
    if (size > h) size = h;
    /* summed-area table of the masked squared error */
    double *sat = calloc((size_t)(w + 1) * (size_t)(h + 1), sizeof *sat);
    if (!sat) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            double e2 = 0;
            for (int c = 0; c < 3 && (!mask || mask[i] > 0.5f); c++) {
                double d =
                    img->data[i * (size_t)img->channels + (size_t)c] - ref->data[i * (size_t)ref->channels + (size_t)c];
                e2 += d * d;
            }
            sat[(size_t)(y + 1) * (size_t)(w + 1) + (size_t)x + 1] =
                e2 + sat[(size_t)y * (size_t)(w + 1) + (size_t)x + 1] +
                sat[(size_t)(y + 1) * (size_t)(w + 1) + (size_t)x] - sat[(size_t)y * (size_t)(w + 1) + (size_t)x];
        }
    double best = -1;
    for (int y = 0; y + size <= h; y++)
        for (int x = 0; x + size <= w; x++) {
            size_t a = (size_t)y * (size_t)(w + 1), b = (size_t)(y + size) * (size_t)(w + 1);
            double sum =
                sat[b + (size_t)(x + size)] - sat[a + (size_t)(x + size)] - sat[b + (size_t)x] + sat[a + (size_t)x];
            if (sum > best) best = sum, *x0 = x, *y0 = y;
        }
    free(sat);
    return LUCENT_OK;
}

lucent_status lucent_compare_write_image(const char *dir, const char *stem, const lucent_image *img,
                                         const lucent_tonemap_desc *tonemap)
{
    char path[EVAL_PATH_SIZE];
    lucent_image *t;
    lucent_status s = eval_path_printf(path, sizeof path, "%s/%s.exr", dir, stem);
    if (s == LUCENT_OK) s = lucent_image_write(path, img, NULL);
    if (s == LUCENT_OK) s = lucent_image_clone(img, &t);
    if (s != LUCENT_OK) return s;
    lucent_image_tonemap(t, tonemap);
    s = eval_path_printf(path, sizeof path, "%s/%s.png", dir, stem);
    if (s == LUCENT_OK) s = lucent_image_write(path, t, NULL);
    lucent_image_destroy(t);
    return s;
}
