/* The estimate: per pixel the sums of the samples, of their squares and of the squared luminance,
 * and how many camera rays met an object. Work is cut into passes (one sample per pixel) and tiles
 * of TILE x TILE pixels; a pass runs its tiles in parallel and each pixel adds its own sample, so the
 * sums are added in sample order whatever the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "trace/film.h"

enum { TILE = 16, ACC = 7 }; /* ACC doubles per pixel: sum RGB, sum of squares RGB, sum of Y^2 */

static const double k_lum[3] = {0.2126, 0.7152, 0.0722}; /* Rec. 709 */

lucent_status tr_film_create(int width, int height, tr_film **dest)
{
    size_t n = (size_t)width * (size_t)height;
    tr_film *f = calloc(1, sizeof *f);
    if (f) f->acc = calloc(n * ACC, sizeof *f->acc);
    if (f && f->acc) f->hits = calloc(n, sizeof *f->hits);
    if (!f || !f->hits) {
        tr_film_destroy(f);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory for a %d x %d image", width, height);
    }
    f->width = width, f->height = height;
    *dest = f;
    return LUCENT_OK;
}

void tr_film_destroy(tr_film *f)
{
    if (!f) return;
    free(f->acc);
    free(f->hits);
    free(f);
}

void tr_film_reset(tr_film *f)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    memset(f->acc, 0, n * ACC * sizeof *f->acc);
    memset(f->hits, 0, n * sizeof *f->hits);
    f->spp = 0, f->seed = 0, f->seconds = 0;
    memset(&f->stats, 0, sizeof f->stats);
}

typedef struct pass_job {
    const lucent_tracer *tr;
    tr_film *film;
    uint64_t sample;
    int tiles_x;
    tr_stats *stats; /* one per thread */
    lucent_progress *progress;
} pass_job;

static void add_sample(tr_film *f, size_t pixel, const double v[3], bool covered)
{
    double *a = f->acc + pixel * ACC, y = 0;
    for (int c = 0; c < 3; c++) a[c] += v[c], a[3 + c] += v[c] * v[c], y += k_lum[c] * v[c];
    a[6] += y * y;
    f->hits[pixel] += covered;
}

static lucent_status pass_tile(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end;
    pass_job *job = ctx;
    tr_film *f = job->film;
    int x0 = (int)(chunk % (uint64_t)job->tiles_x) * TILE, y0 = (int)(chunk / (uint64_t)job->tiles_x) * TILE;
    int x1 = x0 + TILE < f->width ? x0 + TILE : f->width, y1 = y0 + TILE < f->height ? y0 + TILE : f->height;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            size_t pixel = (size_t)y * (size_t)f->width + (size_t)x;
            lucent_rng rng;
            lucent_rng_init(f->seed, job->sample << 32 | pixel, &rng);
            double px = x + lucent_rng_uniform(&rng), py = y + lucent_rng_uniform(&rng), v[3];
            bool covered = tr_trace_path(job->tr, px, py, &rng, v, &job->stats[thread]);
            add_sample(f, pixel, v, covered);
        }
    lucent_progress_add(job->progress, (uint64_t)(x1 - x0) * (uint64_t)(y1 - y0));
    return LUCENT_OK;
}

static void merge_stats(tr_stats *into, const tr_stats *s)
{
    into->paths += s->paths, into->scatters += s->scatters, into->bounces += s->bounces;
    into->escaped += s->escaped, into->truncated += s->truncated, into->nonfinite += s->nonfinite;
}

lucent_status tr_film_pass(const lucent_tracer *tr, tr_film *f, lucent_pool *pool, lucent_progress *progress)
{
    int threads = pool ? lucent_pool_threads(pool) : 1;
    tr_stats *stats = calloc((size_t)threads, sizeof *stats);
    if (!stats) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    pass_job job = {.tr = tr, .film = f, .sample = f->spp, .tiles_x = (f->width + TILE - 1) / TILE,
                    .stats = stats, .progress = progress};
    uint64_t tiles = (uint64_t)job.tiles_x * (uint64_t)((f->height + TILE - 1) / TILE);
    lucent_status s = lucent_parallel_for(pool, tiles, 1, pass_tile, &job);
    for (int t = 0; t < threads; t++) merge_stats(&f->stats, &stats[t]);
    free(stats);
    if (s == LUCENT_OK) f->spp++;
    return s;
}

/* Mean and variance of the mean of sum s, sum of squares s2 over n samples. */
static void mean_var(double s, double s2, double n, double *mean, double *var)
{
    *mean = s / n;
    *var = n > 1 ? fmax(0.0, (s2 - s * s / n) / (n * (n - 1.0))) : 0.0;
}

/* se(Y) / Y of a pixel, or -1 when Y is 0. */
static double pixel_rel_error(const tr_film *f, size_t pixel)
{
    const double *a = f->acc + pixel * ACC;
    double n = (double)f->spp, sy = k_lum[0] * a[0] + k_lum[1] * a[1] + k_lum[2] * a[2], mean, var;
    mean_var(sy, a[6], n, &mean, &var);
    return mean > 0 ? sqrt(var) / mean : -1.0;
}

static bool object_pixel(const tr_film *f, size_t pixel) { return 2 * (uint64_t)f->hits[pixel] >= f->spp; }

double tr_film_error_rms(const tr_film *f)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    double sum = 0;
    uint64_t count = 0;
    for (size_t p = 0; p < n; p++) {
        double e = object_pixel(f, p) ? pixel_rel_error(f, p) : -1.0;
        if (e >= 0) sum += e * e, count++;
    }
    return count ? sqrt(sum / (double)count) : INFINITY;
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
        if (!object_pixel(f, p) || f->spp == 0) continue;
        double r = pixel_rel_error(f, p);
        if (r < 0) e->dark_pixels++;
        else v[count++] = r, sum += r * r;
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
    if (s != LUCENT_OK || f->spp == 0) return s;
    size_t n = (size_t)f->width * (size_t)f->height;
    double spp = (double)f->spp;
    for (size_t p = 0; p < n; p++) {
        const double *a = f->acc + p * ACC;
        for (int c = 0; c < 3; c++) {
            double mean, var;
            mean_var(a[c], a[3 + c], spp, &mean, &var);
            r->image->data[3 * p + c] = (float)mean;
            r->variance->data[3 * p + c] = (float)var;
        }
        r->coverage->data[p] = (float)(f->hits[p] / spp);
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
    r->spp = f->spp, r->seed = f->seed, r->seconds = f->seconds;
    r->samples_per_second = f->seconds > 0 ? (double)f->stats.paths / f->seconds : 0;
    r->truncated = f->stats.truncated, r->escaped = f->stats.escaped, r->nonfinite = f->stats.nonfinite;
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
