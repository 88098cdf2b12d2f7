/* What the estimate says: the mean radiance, the variance of that mean and the coverage per pixel, and
 * the summary of the per-pixel relative standard error of the luminance over the object. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/dist.h"
#include "trace/film.h"

/* Mean and variance of the mean of sum s, sum of squares s2 over n samples. */
static void mean_var(double s, double s2, double n, double *mean, double *var)
{
    *mean = n > 0 ? s / n : 0.0;
    *var = n > 1 ? fmax(0.0, (s2 - s * s / n) / (n * (n - 1.0))) : 0.0;
}

/* Mean and variance of the mean of component k (0..2 RGB, 3 the luminance) of pixel p: the camera
 * paths' samples plus the light paths' passes (independent estimates of the two shares). */
static void pixel_mean_var(const tr_film *f, size_t p, int k, double *mean, double *var)
{
    const double *w = tr_film_luminance;
    double m[2], v[2];
    for (int part = 0; part < 2; part++) {
        const double *a = (part ? f->light : f->acc) + p * TR_FILM_ACC;
        double n = part ? (double)f->light_passes : (double)f->count[p];
        double s = k < 3 ? a[k] : w[0] * a[0] + w[1] * a[1] + w[2] * a[2], s2 = k < 3 ? a[3 + k] : a[6];
        mean_var(s, s2, n, &m[part], &v[part]);
    }
    *mean = m[0] + m[1], *var = v[0] + v[1];
}

/* se(Y) / Y of a pixel, or -1 when Y is 0. */
static double pixel_rel_error(const tr_film *f, size_t p)
{
    double mean, var;
    pixel_mean_var(f, p, 3, &mean, &var);
    return mean > 0 ? sqrt(var) / mean : -1.0;
}

static bool object_pixel(const tr_film *f, size_t p) { return f->count[p] && 2 * (uint64_t)f->hits[p] >= f->count[p]; }

lucent_status tr_film_error_rms(const tr_film *f, double *dest)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    double *e = malloc((n ? n : 1) * sizeof *e), sum = 0;
    lucent_status s = e ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    for (size_t p = 0; s == LUCENT_OK && p < n; p++) e[p] = object_pixel(f, p) ? pixel_rel_error(f, p) : -1.0;
    if (lucent_dist_size() > 1) s = tr_film_gather(f, e, 1, s); /* the pixels other ranks own */
    if (s != LUCENT_OK) {
        free(e);
        return s;
    }
    uint64_t count = 0;
    for (size_t p = 0; p < n; p++)
        if (e[p] >= 0) sum += e[p] * e[p], count++;
    free(e);
    *dest = count ? sqrt(sum / (double)count) : INFINITY;
    return LUCENT_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static lucent_status error_summary(const tr_film *f, lucent_trace_error *e)
{
    size_t n = (size_t)f->width * (size_t)f->height, count = 0;
    double *v = malloc((n ? n : 1) * sizeof *v), sum = 0;
    if (!v) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    memset(e, 0, sizeof *e);
    for (size_t p = 0; p < n; p++) {
        if (!object_pixel(f, p)) continue;
        double r = pixel_rel_error(f, p);
        if (r < 0)
            e->dark_pixels++;
        else
            v[count++] = r, sum += r * r;
    }
    qsort(v, count, sizeof *v, cmp_double);
    e->pixels = count;
    if (count) {
        e->median = v[count / 2];
        e->p90 = v[(size_t)(0.9 * (double)(count - 1))];
        e->rms = sqrt(sum / (double)count);
    }
    free(v);
    return LUCENT_OK;
}

static lucent_status make_images(const tr_film *f, lucent_trace_result *r)
{
    lucent_status s = lucent_image_create(f->width, f->height, 3, &r->image);
    if (s == LUCENT_OK) s = lucent_image_create(f->width, f->height, 3, &r->variance);
    if (s == LUCENT_OK) s = lucent_image_create(f->width, f->height, 1, &r->coverage);
    if (s != LUCENT_OK) return s;
    for (size_t p = 0; p < (size_t)f->width * (size_t)f->height; p++) {
        double n = (double)f->count[p];
        for (int c = 0; c < 3; c++) {
            double mean, var;
            pixel_mean_var(f, p, c, &mean, &var);
            r->image->data[3 * p + c] = (float)mean;
            r->variance->data[3 * p + c] = (float)var;
        }
        r->coverage->data[p] = n > 0 ? (float)(f->hits[p] / n) : 0.0f;
        r->samples += f->count[p];
    }
    return LUCENT_OK;
}

lucent_status tr_film_result(const tr_film *f, lucent_trace_result *r)
{
    memset(r, 0, sizeof *r);
    lucent_status s = make_images(f, r);
    if (s == LUCENT_OK) s = error_summary(f, &r->error);
    if (s != LUCENT_OK) {
        lucent_trace_result_free(r);
        return s;
    }
    r->spp = f->passes, r->seed = f->seed, r->seconds = f->seconds;
    r->samples_per_second = f->seconds > 0 ? (double)f->stats.paths / f->seconds : 0;
    r->truncated = f->stats.truncated, r->escaped = f->stats.escaped, r->nonfinite = f->stats.nonfinite;
    const tr_stats *st = &f->stats;
    r->cost = (lucent_trace_cost){.paths = st->paths,
                                  .scatters = st->scatters,
                                  .bounces = st->bounces,
                                  .rays = st->rays,
                                  .points = st->points,
                                  .free_flights = st->free_flights,
                                  .nee = st->nee,
                                  .photons = st->photons,
                                  .entry_ended = st->entry_ended};
    return LUCENT_OK;
}

void lucent_trace_result_free(lucent_trace_result *r)
{
    if (!r) return;
    lucent_image_destroy(r->image);
    lucent_image_destroy(r->variance);
    lucent_image_destroy(r->coverage);
    memset(r, 0, sizeof *r);
}
