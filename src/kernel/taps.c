/* Importance-sampled taps as in Jimenez's separable-sss (Freude 2014, 4.4: "equally spaced
 * samples ... redistributed via a quadratic mapping"): offsets clustered at the centre, each
 * weight the 1-D kernel at the tap times the tap's interval, normalised per channel, then
 * blended with the delta by the strength. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/internal.h"

/* Offsets in sampling order (ascending): o_i = range sign(s) s^2 / range^2. */
static void quadratic_offsets(int count, double range, double *dest)
{
    double step = 2 * range / (count - 1);
    for (int i = 0; i < count / 2; i++) {
        double s = -range + i * step;
        dest[i] = -range * s * s / (range * range);
        dest[count - 1 - i] = -dest[i]; /* exactly symmetric */
    }
    dest[count / 2] = 0;
}

/* The tap's interval: half the distance to each neighbour. */
static double interval(const double *o, int count, int i)
{
    double w0 = i > 0 ? fabs(o[i] - o[i - 1]) : 0, w1 = i < count - 1 ? fabs(o[i] - o[i + 1]) : 0;
    return (w0 + w1) / 2;
}

/* Listing order: centre first, then the ascending offsets without it. */
static int listed(int count, int i) { return i == count / 2 ? 0 : i < count / 2 ? i + 1 : i; }

static lucent_taps *taps_alloc(int count, int rank)
{
    lucent_taps *t = calloc(1, sizeof *t);
    if (!t) return NULL;
    t->count = count;
    t->rank = rank;
    t->offset = calloc((size_t)count, sizeof(double));
    bool ok = t->offset != NULL;
    for (int c = 0; c < 3; c++) ok &= (t->weight[c] = calloc((size_t)count * rank, sizeof(double))) != NULL;
    if (!ok) {
        lucent_taps_destroy(t);
        return NULL;
    }
    return t;
}

/* Per channel: scale so that sum_p sign_p (sum of pass p)^2 = 1 (rank 1: the sum is 1). */
static lucent_status normalise(lucent_taps *t)
{
    for (int c = 0; c < 3; c++) {
        double total = 0;
        for (int p = 0; p < t->rank; p++) {
            double s = 0;
            for (int i = 0; i < t->count; i++) s += t->weight[c][p * t->count + i];
            total += t->sign[c][p] * s * s;
        }
        double first = 0;
        for (int i = 0; i < t->count; i++) first += t->weight[c][i];
        if (!(total > 0) || (t->rank == 1 && !(first > 0)))
            return lucent_error(LUCENT_ERR_NUMERIC, "taps: channel %d has no positive weight", c);
        double f = t->rank == 1 ? 1 / first : 1 / sqrt(total);
        for (int i = 0; i < t->count * t->rank; i++) t->weight[c][i] *= f;
    }
    return LUCENT_OK;
}

/* Jimenez's strength blend (rank 1): centre lerp(1, w, t), others t w. */
static void blend(lucent_taps *t, const double strength[3])
{
    for (int c = 0; c < 3; c++) {
        t->weight[c][0] = 1 - strength[c] + strength[c] * t->weight[c][0];
        for (int i = 1; i < t->count; i++) t->weight[c][i] *= strength[c];
    }
}

static double default_range(const lucent_kernel *k, int count)
{
    if (k->model == LUCENT_KERNEL_JIMENEZ) return count > 20 ? 3 : 2;
    return k->range;
}

lucent_taps_desc lucent_taps_defaults(void) { return (lucent_taps_desc){.count = LUCENT_KERNEL_DEFAULT_TAPS}; }

double lucent_taps_radius(const lucent_taps *t)
{
    double r = 0;
    for (int k = 0; t && k < t->count; k++) r = fmax(r, fabs(t->offset[k]));
    return r;
}

/* The pinhole projection: a length l at depth z spans l / (2 z tan(fov_y / 2)) of the image height. */
double lucent_screen_pixels_per_mm(int height_px, double fov_y_deg, double depth_mm)
{
    return height_px / (2 * tan(0.5 * fov_y_deg * M_PI / 180) * depth_mm);
}

double lucent_screen_depth_mm(double object_height_mm, double fov_y_deg)
{
    return object_height_mm / (2 * tan(0.5 * fov_y_deg * M_PI / 180));
}

lucent_status lucent_kernel_taps(const lucent_kernel *k, const lucent_taps_desc *desc, lucent_taps **dest)
{
    *dest = NULL;
    int count = desc && desc->count ? desc->count : lucent_taps_defaults().count;
    double range = desc && desc->range != 0 ? desc->range : default_range(k, count);
    if (count < 3 || count > LUCENT_KERNEL_MAX_TAPS || count % 2 == 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "taps: count must be odd, 3..255 (got %d)", count);
    if (!(range > 0) || !(range <= LUCENT_TAPS_MAX_RANGE))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "taps: range must be > 0 mm and at most %g mm, got %g",
                            LUCENT_TAPS_MAX_RANGE, range);
    lucent_taps *t = taps_alloc(count, k->rank);
    double o[LUCENT_KERNEL_MAX_TAPS];
    if (!t) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "taps: out of memory");
    quadratic_offsets(count, range, o);
    for (int i = 0; i < count; i++) {
        int at = listed(count, i);
        t->offset[at] = o[i];
        for (int c = 0; c < 3; c++)
            for (int p = 0; p < k->rank; p++) {
                t->sign[c][p] = k->sign[c][p];
                t->weight[c][p * count + at] = lucent_kernel_eval(k, c, p, o[i]) * interval(o, count, i);
            }
    }
    lucent_status st = normalise(t);
    if (st == LUCENT_OK && k->rank == 1) blend(t, k->strength);
    if (st != LUCENT_OK) {
        lucent_taps_destroy(t);
        return st;
    }
    *dest = t;
    return LUCENT_OK;
}

lucent_status lucent_taps_clone(const lucent_taps *src, lucent_taps **dest)
{
    lucent_taps *t = taps_alloc(src->count, src->rank);
    if (!(*dest = t)) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "taps: out of memory");
    memcpy(t->offset, src->offset, (size_t)src->count * sizeof *t->offset);
    for (int c = 0; c < 3; c++)
        memcpy(t->weight[c], src->weight[c], (size_t)src->count * (size_t)src->rank * sizeof *t->weight[c]);
    memcpy(t->sign, src->sign, sizeof t->sign);
    return LUCENT_OK;
}

void lucent_taps_destroy(lucent_taps *t)
{
    if (!t) return;
    free(t->offset);
    for (int c = 0; c < 3; c++) free(t->weight[c]);
    free(t);
}
