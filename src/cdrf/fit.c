/* The least-squares fit of sigma0 and the albedo scale k_d to simulated spheres (Kubo section 4.2,
 * Figure 6): per channel, minimise sum sin(theta) (k_d f(theta; sigma0 / r) - L)^2 / se^2 over every
 * sphere and bin (sin theta: the bin's share of the equator line's pixels). k_d is linear, so for a given sigma0 it has the closed form
 * k_d = sum f L / se^2 / sum f^2 / se^2; sigma0 is found by a grid scan and a golden-section
 * refinement around the best grid point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/cdrf.h"

enum { GRID = 120, GOLDEN_STEPS = 60 };
#define SE_FLOOR 0.02

typedef struct fit_data {
    const lucent_cdrf_sphere_result *spheres;
    int count, channel;
    lucent_cdrf_variant variant;
    double se_floor;
} fit_data;

typedef struct fit_eval {
    double kd, chi2, rms;
} fit_eval;

/* The weight of a bin: its pixel share on the equator line (sin theta: pixels are uniform in
 * x = r cos theta, as in Kubo's Figure 6) over its variance. */
static double weight(const fit_data *fd, double theta, double se)
{
    double e = fmax(se, fd->se_floor);
    return sin(theta) / (e * e);
}

static fit_eval evaluate(const fit_data *fd, double sigma0)
{
    double sfl = 0, sff = 0, n = 0;
    int c = fd->channel;
    for (int i = 0; i < fd->count; i++) {
        const lucent_cdrf_sphere_result *s = &fd->spheres[i];
        for (int j = 0; j < s->bins; j++) {
            double f = lucent_cdrf_eval(fd->variant, s->theta[j], sigma0 / s->radius);
            double w = weight(fd, s->theta[j], s->radiance_se[c][j]);
            sfl += w * f * s->radiance[c][j], sff += w * f * f;
        }
    }
    fit_eval e = {.kd = sff > 0 ? sfl / sff : 0};
    double sq = 0;
    for (int i = 0; i < fd->count; i++) {
        const lucent_cdrf_sphere_result *s = &fd->spheres[i];
        for (int j = 0; j < s->bins; j++) {
            double res = e.kd * lucent_cdrf_eval(fd->variant, s->theta[j], sigma0 / s->radius) - s->radiance[c][j];
            e.chi2 += res * res * weight(fd, s->theta[j], s->radiance_se[c][j]);
            sq += sin(s->theta[j]) * res * res, n += sin(s->theta[j]);
        }
    }
    e.rms = n > 0 ? sqrt(sq / n) : 0;
    return e;
}

/* Minimises chi2 over sigma0 in [0, hi]. */
static double search(const fit_data *fd, double hi)
{
    double best = 0, best_chi2 = evaluate(fd, 0).chi2;
    for (int k = 1; k <= GRID; k++) {
        double s0 = hi * k / GRID, chi2 = evaluate(fd, s0).chi2;
        if (chi2 < best_chi2) best = s0, best_chi2 = chi2;
    }
    double a = fmax(0.0, best - hi / GRID), b = fmin(hi, best + hi / GRID);
    const double phi = 0.6180339887498949;
    double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
    double f1 = evaluate(fd, x1).chi2, f2 = evaluate(fd, x2).chi2;
    for (int k = 0; k < GOLDEN_STEPS; k++) {
        if (f1 < f2)
            b = x2, x2 = x1, f2 = f1, x1 = b - phi * (b - a), f1 = evaluate(fd, x1).chi2;
        else
            a = x1, x1 = x2, f1 = f2, x2 = a + phi * (b - a), f2 = evaluate(fd, x2).chi2;
    }
    double x = 0.5 * (a + b);
    return evaluate(fd, x).chi2 < best_chi2 ? x : best;
}

lucent_status lucent_cdrf_fit_spheres(const lucent_cdrf_sphere_result *spheres, int count, lucent_cdrf_variant variant,
                                      double sigma0_max, lucent_cdrf_fit *dest)
{
    if (!spheres || count < 1) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF fit: no spheres");
    if (sigma0_max == 0) sigma0_max = 20.0;
    if (!(sigma0_max > 0) || !isfinite(sigma0_max))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF fit: sigma0_max must be > 0 mm");
    for (int i = 0; i < count; i++)
        if (!(spheres[i].radius > 0) || spheres[i].bins < 1 || spheres[i].bins > LUCENT_CDRF_MAX_BINS)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF fit: sphere %d has no data", i);
    memset(dest, 0, sizeof *dest);
    dest->variant = variant;
    for (int c = 0; c < 3; c++) {
        double peak = 0;
        for (int i = 0; i < count; i++)
            for (int j = 0; j < spheres[i].bins; j++) peak = fmax(peak, fabs(spheres[i].radiance[c][j]));
        fit_data fd = {.spheres = spheres,
                       .count = count,
                       .channel = c,
                       .variant = variant,
                       .se_floor = peak > 0 ? SE_FLOOR * peak : 1e-30};
        double s0 = search(&fd, sigma0_max);
        fit_eval e = evaluate(&fd, s0);
        dest->sigma0[c] = s0, dest->kd[c] = e.kd, dest->rms[c] = e.rms, dest->chi2[c] = e.chi2;
        fd.variant = LUCENT_CDRF_KUBO; /* Lambert: Kubo at sigma = 0 */
        fit_eval l = evaluate(&fd, 0);
        dest->lambert_kd[c] = l.kd, dest->lambert_rms[c] = l.rms, dest->lambert_chi2[c] = l.chi2;
    }
    return LUCENT_OK;
}
