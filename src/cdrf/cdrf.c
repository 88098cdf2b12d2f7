/* The curvature-dependent reflectance function: Kubo, Dobashi & Morishima Eq. 1-4 and 6, and
 * Collomb's closed-form fit from the CDRF blog post. */
#include <math.h>
#include <string.h>

#include "lucent/cdrf.h"

#define TWO_PI (2.0 * M_PI)
#define HALF_PI (0.5 * M_PI)

/* The Gaussian is cut at this many standard deviations (its tail beyond: erfc(9/sqrt 2) ~ 2e-19). */
#define CUT_SIGMAS 9.0
/* Sub-interval length of the composite rule, in standard deviations (and at most MAX_STEP rad). */
#define STEP_SIGMAS 1.0
#define MAX_STEP 1.0

/* 12-point Gauss-Legendre nodes and weights on [-1, 1] (positive half; symmetric). */
static const double k_gl_x[6] = {0.1252334085114689154724414, 0.3678314989981801937526915, 0.5873179542866174472967024,
                                 0.7699026741943046870368938, 0.9041172563704748566784659, 0.9815606342467192506905491};
static const double k_gl_w[6] = {0.2491470458134027850005624, 0.2334925365383548087608499, 0.2031674267230659217490645,
                                 0.1600783285433462263346525, 0.1069393259953184309602547, 0.0471753363865118271946160};

lucent_status lucent_cdrf_variant_parse(const char *name, lucent_cdrf_variant *dest)
{
    if (name && strcmp(name, "kubo") == 0)
        *dest = LUCENT_CDRF_KUBO;
    else if (name && strcmp(name, "collomb") == 0)
        *dest = LUCENT_CDRF_COLLOMB;
    else
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown CDRF variant '%s' (kubo, collomb)", name ? name : "");
    return LUCENT_OK;
}

const char *lucent_cdrf_variant_name(lucent_cdrf_variant variant)
{
    return variant == LUCENT_CDRF_COLLOMB ? "collomb" : "kubo";
}

double lucent_cdrf_lambert(double theta)
{
    double c = cos(theta);
    return c > 0 ? c : 0;
}

/* Integral of g(t) cos(theta - t) over [a, b] (unnormalised Gaussian exp(-t^2 / 2 s^2)),
 * composite 12-point Gauss-Legendre. */
static double piece(double theta, double sigma, double a, double b)
{
    double step = fmin(STEP_SIGMAS * sigma, MAX_STEP);
    int n = (int)ceil((b - a) / step);
    if (n < 1) n = 1;
    double h = (b - a) / n, inv2s2 = 0.5 / (sigma * sigma), sum = 0;
    for (int k = 0; k < n; k++) {
        double mid = a + (k + 0.5) * h, half = 0.5 * h, part = 0;
        for (int i = 0; i < 6; i++) {
            double t1 = mid - half * k_gl_x[i], t2 = mid + half * k_gl_x[i];
            part += k_gl_w[i] * (exp(-t1 * t1 * inv2s2) * cos(theta - t1) + exp(-t2 * t2 * inv2s2) * cos(theta - t2));
        }
        sum += part * half;
    }
    return sum;
}

/* Kubo Eq. 1-3. E(theta - t) > 0 where theta - t lies in (-pi/2, pi/2) + 2 pi k, i.e. t in
 * (theta - pi/2 - 2 pi k, theta + pi/2 - 2 pi k); each such interval, cut to the Gaussian's
 * support, is integrated on its own, so the rule never straddles a kink of E. */
double lucent_cdrf_kubo(double theta, double sigma)
{
    if (isnan(sigma) || !isfinite(theta)) return NAN;
    if (!(sigma > 0)) return lucent_cdrf_lambert(theta);
    if (sigma > 40) return 1.0 / M_PI; /* the mean of E; the first mode is below exp(-800) */
    theta = fmod(theta, TWO_PI);
    double lo = -CUT_SIGMAS * sigma, hi = CUT_SIGMAS * sigma, sum = 0;
    int kmin = (int)floor((theta - HALF_PI - hi) / TWO_PI), kmax = (int)ceil((theta + HALF_PI - lo) / TWO_PI);
    for (int k = kmin; k <= kmax; k++) {
        double a = fmax(theta - HALF_PI - TWO_PI * k, lo), b = fmin(theta + HALF_PI - TWO_PI * k, hi);
        if (b > a) sum += piece(theta, sigma, a, b);
    }
    return sum / (sqrt(TWO_PI) * sigma);
}

double lucent_cdrf_collomb(double theta, double sigma)
{
    double t = fabs(fmod(theta, TWO_PI));
    if (t > M_PI) t = TWO_PI - t;
    double k = sigma;
    double num = cos(fmin((5.0 + k) * t / 4.0, M_PI)) + 1.0;
    double q = log(1.0 + 1.7 * k) * t / 1.45;
    double q2 = q * q, q10 = q2 * q2 * q2 * q2 * q2;
    double f = (1.0 + k) / 4.0 * num / (1.0 + q10) + 0.075 * (1.0 - k);
    return f > 0 ? f : 0;
}

double lucent_cdrf_eval(lucent_cdrf_variant variant, double theta, double sigma)
{
    return variant == LUCENT_CDRF_COLLOMB ? lucent_cdrf_collomb(theta, sigma) : lucent_cdrf_kubo(theta, sigma);
}

double lucent_cdrf_sigma(double sigma0, double kappa) { return sigma0 * kappa; /* Kubo Eq. 4 */ }

double lucent_cdrf_sigma0_from_diffuse(double diffuse) { return diffuse > 0 ? diffuse * diffuse : 0; /* Kubo Eq. 6 */ }

lucent_status lucent_cdrf_sigma0_map(const lucent_image *diffuse, lucent_image **dest)
{
    *dest = NULL;
    if (!diffuse) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sigma0 map: no diffuse colour map");
    lucent_image *out;
    lucent_status s = lucent_image_create(diffuse->width, diffuse->height, diffuse->channels, &out);
    if (s != LUCENT_OK) return s;
    size_t n = lucent_image_value_count(diffuse);
    for (size_t i = 0; i < n; i++) out->data[i] = (float)lucent_cdrf_sigma0_from_diffuse(diffuse->data[i]);
    *dest = out;
    return LUCENT_OK;
}
