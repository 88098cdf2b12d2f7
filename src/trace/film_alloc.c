/* Adaptive sampling without bias: a pilot estimate (one sample per pixel per pass, its own RNG
 * streams, never added to the image) measures each pixel's relative variance per sample v_p of the
 * luminance; the next pass gives pixel p one sample plus a share of BUDGET - 1 samples per pixel in
 * proportion to sqrt(v_p) (smoothed over 3 x 3 pixels, capped at CAP times the mean). That share
 * minimises sum_p v_p / n_p, the mean squared relative error, for a given number of samples. The
 * samples of the image depend on the pilot only, never on themselves, so each pixel's mean stays an
 * unbiased estimate (a count chosen from the same samples' spread would bias it). Fractions are
 * carried to the next pass, so the allocation is deterministic. */
#include <math.h>
#include <stdlib.h>

#include "trace/film.h"

#define BUDGET 4.0 /* image samples per pixel per pass, on average (the pilot adds one); 8 measured no better */
#define CAP 16.0
enum { PILOT_MIN = 4 }; /* pilot samples before the allocation leaves uniform */

/* v_p of the pilot at pixel p (0 where the pilot's luminance is 0). */
static double pilot_relvar(const tr_film *f, size_t p)
{
    const double *a = f->pilot + p * TR_FILM_ACC, *w = tr_film_luminance;
    double n = (double)f->passes, s = w[0] * a[0] + w[1] * a[1] + w[2] * a[2], mean = s / n;
    double var = (a[6] - s * s / n) / (n - 1.0);
    return mean > 0 ? fmax(0.0, var) / (mean * mean) : 0.0;
}

static double smoothed_weight(const tr_film *f, const double *v, int x, int y)
{
    double sum = 0;
    int count = 0;
    for (int dy = -1; dy <= 1; dy++) /* 5 x 5 measured no better */
        for (int dx = -1; dx <= 1; dx++) {
            int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= f->width || yy >= f->height) continue;
            sum += v[(size_t)yy * (size_t)f->width + (size_t)xx], count++;
        }
    return sqrt(sum / count);
}

static void uniform(tr_film *f, uint32_t q)
{
    for (size_t p = 0; p < (size_t)f->width * (size_t)f->height; p++) f->quota[p] = q;
}

void tr_film_allocate(tr_film *f)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    if (!f->adaptive) {
        uniform(f, 1);
        return;
    }
    double *v = malloc(n * sizeof *v), *w = malloc(n * sizeof *w), total = 0, mean = 0;
    if (!v || !w || f->passes < PILOT_MIN) {
        free(v), free(w);
        uniform(f, (uint32_t)BUDGET);
        return;
    }
    for (size_t p = 0; p < n; p++) v[p] = pilot_relvar(f, p);
    for (int y = 0; y < f->height; y++)
        for (int x = 0; x < f->width; x++) mean += w[(size_t)y * f->width + x] = smoothed_weight(f, v, x, y);
    mean /= (double)n;
    for (size_t p = 0; p < n; p++) total += w[p] = fmin(w[p], CAP * mean);
    for (size_t p = 0; p < n; p++) {
        f->carry[p] += total > 0 ? (BUDGET - 1.0) * (double)n * w[p] / total : BUDGET - 1.0;
        double extra = floor(f->carry[p]);
        f->carry[p] -= extra;
        f->quota[p] = 1 + (uint32_t)extra;
    }
    free(v), free(w);
}
