/* The ground-truth 2-D kernel: the radial profile rotated onto a square grid, normalised per
 * channel (Freude 2014, 6.1-6.2: "simple rotation" of R_d(r); "all ground-truth kernels were
 * normalized prior to approximation ... the discrete values of each kernel sum up to 1"). */
#include <math.h>
#include <stdlib.h>

#include "kernel/internal.h"

/* R_d(r) of channel c: linear between bin centres, the first bin's value inside r[0], 0 past
 * the last centre. */
static double profile_at(const lucent_profile *p, int c, double r)
{
    double u = r / p->dr - 0.5;
    if (u <= 0) return p->value[c][0];
    int j = (int)u;
    if (j >= p->count - 1) return 0;
    double f = u - j;
    return (1 - f) * p->value[c][j] + f * p->value[c][j + 1];
}

/* The radius holding `energy` of channel c's reflectance on the grid. */
static double energy_radius(const lucent_profile *p, int c, double energy)
{
    double total = lucent_profile_total(p, c), sum = 0;
    for (int j = 0; j < p->count; j++) {
        sum += p->value[c][j] * M_PI * (2.0 * j + 1) * p->dr * p->dr;
        if (sum >= energy * total) return (j + 1) * p->dr;
    }
    return p->count * p->dr;
}

static lucent_status check_profile(const lucent_profile *p)
{
    if (!p || p->count < 2 || !(p->dr > 0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel: profile needs at least 2 bins");
    for (int c = 0; c < 3; c++)
        if (!(lucent_profile_total(p, c) > 0))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel: profile channel %d has no positive reflectance",
                                c);
    return LUCENT_OK;
}

/* Average of R_d over cell (i, j), by s x s midpoint subsamples, times the cell area. */
static double cell_value(const lucent_profile *p, int c, double x0, double y0, double h, int s)
{
    double sum = 0, hs = h / s;
    for (int a = 0; a < s; a++)
        for (int b = 0; b < s; b++) {
            double x = x0 + (b + 0.5) * hs, y = y0 + (a + 0.5) * hs;
            sum += profile_at(p, c, sqrt(x * x + y * y));
        }
    return sum * hs * hs;
}

static void fill_channel(const lucent_profile *p, int c, lucent_kernel2d *k, int s)
{
    int n = kernel_n(k->half);
    double total = 0, *v = k->value[c];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double y0 = (i - k->half - 0.5) * k->h, x0 = (j - k->half - 0.5) * k->h;
            v[i * n + j] = i <= k->half && j <= k->half
                               ? cell_value(p, c, x0, y0, k->h, s)
                               : v[(i <= k->half ? i : n - 1 - i) * n + (j <= k->half ? j : n - 1 - j)];
            total += v[i * n + j];
        }
    for (int i = 0; i < n * n; i++) v[i] /= total;
}

lucent_kernel2d_desc lucent_kernel2d_defaults(void) { return (lucent_kernel2d_desc){.energy = 0.999, .max_half = 100}; }

lucent_status lucent_kernel2d_from_profile(const lucent_profile *p, const lucent_kernel2d_desc *desc,
                                           lucent_kernel2d **dest)
{
    *dest = NULL;
    lucent_kernel2d_desc d = desc ? *desc : (lucent_kernel2d_desc){0};
    lucent_status s = check_profile(p);
    if (s != LUCENT_OK) return s;
    lucent_kernel2d_desc def = lucent_kernel2d_defaults();
    if (d.energy == 0) d.energy = def.energy;
    if (d.max_half == 0) d.max_half = def.max_half;
    if (!(d.energy > 0 && d.energy <= 1) || d.max_half < 1 || d.max_half > 2000 || d.cell < 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "kernel grid: energy must be in (0, 1], max_half in 1..2000, cell >= 0");
    double extent = 0;
    for (int c = 0; c < 3; c++) extent = fmax(extent, energy_radius(p, c, d.energy));
    double h = d.cell > 0 ? d.cell : fmax(p->dr, extent / d.max_half);
    int half = (int)ceil(extent / h - 1e-9);
    if (half < 1) half = 1;
    if (half > d.max_half) half = d.max_half;
    lucent_kernel2d *k = calloc(1, sizeof *k);
    if (!k) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel: out of memory");
    k->half = half;
    k->h = h;
    size_t n = (size_t)kernel_n(half);
    for (int c = 0; c < 3; c++)
        if (!(k->value[c] = malloc(n * n * sizeof(double)))) {
            lucent_kernel2d_destroy(k);
            return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel: out of memory");
        }
    int sub = (int)ceil(2 * h / p->dr);
    sub = sub < 2 ? 2 : sub > 8 ? 8 : sub;
    for (int c = 0; c < 3; c++) fill_channel(p, c, k, sub);
    *dest = k;
    return LUCENT_OK;
}

void lucent_kernel2d_destroy(lucent_kernel2d *k)
{
    if (!k) return;
    for (int c = 0; c < 3; c++) free(k->value[c]);
    free(k);
}
