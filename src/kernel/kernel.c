/* Separable kernel models: the common object, dispatch, evaluation and kernel-space errors. */
#include <math.h>
#include <stdlib.h>
#include <strings.h>

#include "kernel/internal.h"

static const char *const k_model_names[LUCENT_KERNEL_MODEL_COUNT] = {"svd",    "preint", "guided",
                                                                     "manual", "sog",    "jimenez"};

const char *lucent_kernel_model_name(lucent_kernel_model model)
{
    return model >= 0 && model < LUCENT_KERNEL_MODEL_COUNT ? k_model_names[model] : "unknown";
}

lucent_status lucent_kernel_model_parse(const char *name, lucent_kernel_model *dest)
{
    for (int m = 0; name && m < LUCENT_KERNEL_MODEL_COUNT; m++)
        if (strcasecmp(name, k_model_names[m]) == 0) {
            *dest = (lucent_kernel_model)m;
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "unknown kernel model '%s' (svd, preint, guided, manual, sog, jimenez)", name ? name : "");
}

lucent_kernel_desc lucent_kernel_defaults(lucent_kernel_model model)
{
    lucent_kernel_desc d = {.model = model, .rank = 1, .max_evaluations = 400};
    if (model == LUCENT_KERNEL_JIMENEZ) {
        static const double t[3] = {0.48, 0.41, 0.28}, f[3] = {1.0, 0.37, 0.3};
        for (int c = 0; c < 3; c++) d.strength[c] = t[c], d.falloff[c] = f[c];
    }
    return d;
}

lucent_status kernel_alloc(lucent_kernel *k, int rank, int half, double h)
{
    k->rank = rank;
    k->half = half;
    k->h = h;
    size_t n = (size_t)kernel_n(half) * (size_t)rank;
    for (int c = 0; c < 3; c++) {
        k->strength[c] = 1;
        for (int p = 0; p < LUCENT_KERNEL_MAX_RANK; p++) k->sign[c][p] = 1;
        if (!(k->a[c] = calloc(n, sizeof(double))))
            return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel: out of memory");
    }
    return LUCENT_OK;
}

/* Integral of w exp(-x^2 / (2 v)) over [x0, x1]. */
static double gauss_mass(double w, double v, double x0, double x1)
{
    double s = sqrt(2 * v);
    return w * sqrt(M_PI * v / 2) * (erf(x1 / s) - erf(x0 / s));
}

void kernel_sample_gaussians(lucent_kernel *k)
{
    int n = kernel_n(k->half);
    for (int c = 0; c < 3; c++)
        for (int p = 0; p < k->rank; p++)
            for (int j = 0; j < n; j++) {
                double x0 = (j - k->half - 0.5) * k->h, sum = 0;
                for (int g = 0; g < k->gaussians; g++)
                    sum += gauss_mass(k->gauss_weight[c][p][g], k->gauss_variance[c][p][g], x0, x0 + k->h);
                k->a[c][p * n + j] = sum;
            }
}

void kernel_unit_sum(lucent_kernel *k, int c)
{
    int n = kernel_n(k->half);
    double sum = 0;
    for (int j = 0; j < n; j++) sum += k->a[c][j];
    if (!(sum > 0)) return;
    for (int j = 0; j < n; j++) k->a[c][j] /= sum;
    for (int g = 0; g < k->gaussians; g++) k->gauss_weight[c][0][g] /= sum;
}

/* The half-width holding 99.5% of pass p's 1-D mass |a| in channel c. */
static double mass_radius(const lucent_kernel *k, int c, int p)
{
    int n = kernel_n(k->half);
    const double *a = k->a[c] + p * n;
    double total = 0, sum = fabs(a[k->half]);
    for (int j = 0; j < n; j++) total += fabs(a[j]);
    int r = 0;
    while (r < k->half && sum < 0.995 * total) {
        r++;
        sum += fabs(a[k->half - r]) + fabs(a[k->half + r]);
    }
    return (r + 0.5) * k->h;
}

void kernel_default_range(lucent_kernel *k)
{
    double range = k->h;
    for (int c = 0; c < 3; c++)
        for (int p = 0; p < k->rank; p++) range = fmax(range, mass_radius(k, c, p));
    k->range = range;
}

static lucent_status check_desc(const lucent_kernel2d *gt, const lucent_kernel_desc *d)
{
    if (d->model < 0 || d->model >= LUCENT_KERNEL_MODEL_COUNT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel: unknown model %d", (int)d->model);
    if (!gt && d->model != LUCENT_KERNEL_JIMENEZ && d->model != LUCENT_KERNEL_MANUAL)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel %s: needs the ground truth",
                            lucent_kernel_model_name(d->model));
    bool ranked = d->model == LUCENT_KERNEL_SVD || d->model == LUCENT_KERNEL_SOG;
    if (d->rank < 0 || d->rank > LUCENT_KERNEL_MAX_RANK || (!ranked && d->rank > 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel %s: rank must be %s",
                            lucent_kernel_model_name(d->model), ranked ? "1..16" : "1 (a separable model)");
    if (gt && d->rank > kernel_n(gt->half))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel: rank %d exceeds the grid size %d", d->rank,
                            kernel_n(gt->half));
    return LUCENT_OK;
}

static lucent_status dispatch(const lucent_kernel2d *gt, const lucent_profile *p, const char *name,
                              const lucent_kernel_desc *d, lucent_kernel *k)
{
    switch (d->model) {
    case LUCENT_KERNEL_SVD: return kernel_svd(gt, d, k);
    case LUCENT_KERNEL_PREINT: return kernel_preint(gt, k);
    case LUCENT_KERNEL_GUIDED: return kernel_guided(gt, d, k);
    case LUCENT_KERNEL_MANUAL: return kernel_manual(gt, name, d, k);
    case LUCENT_KERNEL_SOG: return kernel_sog(gt, p, d, k);
    default: return kernel_jimenez(gt, d, k);
    }
}

lucent_status lucent_kernel_build(const lucent_kernel2d *gt, const lucent_profile *p, const char *material_name,
                                  const lucent_kernel_desc *desc, lucent_kernel **dest)
{
    *dest = NULL;
    lucent_kernel_desc d = desc ? *desc : (lucent_kernel_desc){0};
    lucent_status s = check_desc(gt, &d);
    if (s != LUCENT_OK) return s;
    lucent_kernel *k = calloc(1, sizeof *k);
    if (!k) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel: out of memory");
    k->model = d.model;
    s = dispatch(gt, p, material_name, &d, k);
    if (s != LUCENT_OK) {
        lucent_kernel_destroy(k);
        return s;
    }
    if (k->range == 0) kernel_default_range(k);
    *dest = k;
    return LUCENT_OK;
}

void lucent_kernel_destroy(lucent_kernel *k)
{
    if (!k) return;
    for (int c = 0; c < 3; c++) free(k->a[c]);
    free(k);
}

double lucent_kernel_eval(const lucent_kernel *k, int c, int pass, double x)
{
    if (k->gaussians > 0) {
        double sum = 0;
        for (int g = 0; g < k->gaussians; g++)
            sum += k->gauss_weight[c][pass][g] * exp(-x * x / (2 * k->gauss_variance[c][pass][g]));
        return sum;
    }
    double u = x / k->h + k->half;
    int n = kernel_n(k->half);
    if (!(u >= 0) || u >= n - 1) return u == n - 1 ? k->a[c][pass * n + n - 1] : 0; /* before the cast to int */
    int j = (int)floor(u);
    double f = u - j;
    return (1 - f) * k->a[c][pass * n + j] + f * k->a[c][pass * n + j + 1];
}

/* A_ij of channel c, Freude (5.10): sum over passes of sign a(x_i) a(x_j). */
static double reconstructed(const lucent_kernel *k, int c, int i, int j)
{
    int n = kernel_n(k->half);
    double sum = 0;
    for (int p = 0; p < k->rank; p++) sum += k->sign[c][p] * k->a[c][p * n + i] * k->a[c][p * n + j];
    return sum;
}

void lucent_kernel_rms(const lucent_kernel *k, const lucent_kernel2d *gt, double dest[3])
{
    int n = kernel_n(gt->half);
    for (int c = 0; c < 3; c++) {
        if (k->half != gt->half || k->h != gt->h) {
            dest[c] = NAN;
            continue;
        }
        double sum = 0;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double e = gt->value[c][i * n + j] - reconstructed(k, c, i, j);
                sum += e * e;
            }
        dest[c] = sqrt(sum / ((double)n * n));
    }
}

void lucent_kernel_norm1(const lucent_kernel *k, double dest[3])
{
    int n = kernel_n(k->half);
    for (int c = 0; c < 3; c++) {
        double sum = 0;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) sum += fabs(reconstructed(k, c, i, j));
        dest[c] = sum;
    }
}
