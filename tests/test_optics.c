/* Tests of the library's one optics header (src/base/optics.h). Every expected value comes from a
 * formula stated beside it, written here independently of the code under test (other algebraic
 * forms, closed-form integrals, physical laws), or from a hand computation:
 *   Fresnel: normal incidence ((n1 - n2) / (n1 + n2))^2; grazing incidence -> 1 with the slope
 *     derived from the s and p amplitudes; total internal reflection beyond the critical angle;
 *     reciprocity F(eta, theta_i) = F(1 / eta, theta_t) (Stokes relations); the Cook-Torrance form
 *     (Cook & Torrance 1982; Walter et al. 2007 eq. 22); at 45 degrees into glass (eta 1.5), by
 *     hand: Rs = (137 - 36 sqrt 14) / 25, Rp = Rs^2.
 *   Refraction: Snell's law |t x m| = |d x m| / eta, coplanarity, the far side.
 *   GGX: normalisation Int D(m) (n . m) dm = 1 (quadrature); Smith G1 = 1 / (1 + Lambda) with
 *     Lambda = (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2 (Heitz 2014, section 5.3) and the projected
 *     area law Int G1(v) <v . m> D(m) dm = v . n (Heitz 2014 eq. 2); the visible-normal sampler by
 *     chi-square against D_v(m) = G1(v) <v . m> D(m) / (v . n) (Heitz 2018 eq. 2), pbrt style; the
 *     half vectors and Jacobians of Walter et al. 2007 (eqs. 13, 14, 16, 17) by the change of variables
 *     Int D_v(h(i)) |dh / di| di = 1.
 *   Henyey-Greenstein: sampling by chi-square against the closed-form cumulative distribution
 *     P(mu) = (1 - g^2) / (2 g) (1 / sqrt(1 + g^2 - 2 g mu) - 1 / (1 + g)); mean cosine g and
 *     E[mu^2] = (1 + 2 g^2) / 3 (the Legendre moments of HG are g^l); the phase function
 *     integrating to 1.
 *   The basis: orthonormal and right-handed (t x b = n) for random normals and those near +-z; the
 *     float basis within float rounding of the double one.
 *   Float Henyey-Greenstein sampling agrees with the double one within float rounding.
 * Chi-square tests follow pbrt-v3's (src/tests/bsdfs.cpp): cells with expected counts below 5
 * pooled, a p-value from the chi-square distribution, significance 1% with the Sidak correction
 * over the tests of this file. Seeds are fixed. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/optics.h"
#include "base/vec3.h"
#include "lucent/base.h"
#include "test.h"

/* ---- helpers: chi-square ---- */

/* The regularised upper incomplete gamma function Q(a, x): the series of P for x < a + 1, else
 * the continued fraction of Q evaluated by the modified Lentz method (Abramowitz & Stegun 6.5.29,
 * 6.5.31). */
static double gamma_q(double a, double x)
{
    if (x <= 0) return 1.0;
    double lg = lgamma(a);
    if (x < a + 1) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000 && fabs(term) > 1e-16 * fabs(sum); n++) term *= x / (a + n), sum += term;
        return 1.0 - sum * exp(-x + a * log(x) - lg);
    }
    double b = x + 1 - a, c = 1 / 1e-300, d = 1 / b, h = d;
    for (int i = 1; i < 10000; i++) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b, d = fabs(d) < 1e-300 ? 1e-300 : d;
        c = b + an / c, c = fabs(c) < 1e-300 ? 1e-300 : c;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1) < 1e-15) break;
    }
    return exp(-x + a * log(x) - lg) * h;
}

static int cmp_expected(const void *a, const void *b)
{
    double x = ((const double *)a)[0], y = ((const double *)b)[0];
    return x < y ? -1 : x > y;
}

/* The number of chi-square tests in this file, for the Sidak correction. */
#define CHI2_TESTS 13

/* Pearson's chi-square of observed against expected counts (n cells), cells with expected < 5
 * pooled; returns the p-value, or -1 when a cell with no expected count holds samples. */
static double chi_square_p(const double *observed, const double *expected, int n)
{
    double *pair = malloc(2 * (size_t)n * sizeof *pair);
    for (int i = 0; i < n; i++) pair[2 * i] = expected[i], pair[2 * i + 1] = observed[i];
    qsort(pair, (size_t)n, 2 * sizeof *pair, cmp_expected);
    double pool_e = 0, pool_o = 0, chi2 = 0;
    int cells = 0, bad = 0;
    for (int i = 0; i < n; i++) {
        double e = pair[2 * i], o = pair[2 * i + 1];
        if (e <= 0) {
            bad |= o > 0;
        } else if (e < 5) {
            pool_e += e, pool_o += o;
        } else {
            chi2 += (o - e) * (o - e) / e, cells++;
        }
    }
    if (pool_e > 0) chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e, cells++;
    free(pair);
    if (bad) return -1;
    return gamma_q(0.5 * (cells - 1), 0.5 * chi2);
}

static void check_chi_square(const char *what, const double *observed, const double *expected, int n)
{
    double p = chi_square_p(observed, expected, n), alpha = 1 - pow(1 - 0.01, 1.0 / CHI2_TESTS);
    CHECK_MSG(p > alpha, "%s: chi-square p-value %.3g below the significance %.3g", what, p, alpha);
}

/* ---- helpers: reference formulas written independently of base/optics.h ---- */

/* Cook & Torrance 1982 (Walter et al. 2007 eq. 22): F = (g - c)^2 / (2 (g + c)^2)
 * (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2), g^2 = eta^2 - 1 + c^2; 1 when g^2 < 0. */
static double fresnel_cook_torrance(double c, double eta)
{
    double g2 = eta * eta - 1 + c * c;
    if (g2 < 0) return 1;
    double g = sqrt(g2), a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
    return 0.5 * a * a * (1 + b * b);
}

/* GGX D in its slope form: 1 / (pi alpha^2 cos^4 (1 + tan^2 / alpha^2)^2) (Walter eq. 33). */
static double ggx_d_ref(double cos_m, double alpha)
{
    if (cos_m <= 0) return 0;
    double c2 = cos_m * cos_m, tan2 = (1 - c2) / c2, k = 1 + tan2 / (alpha * alpha);
    return 1 / (M_PI * alpha * alpha * c2 * c2 * k * k);
}

/* Smith G1 = 1 / (1 + Lambda), Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2 (Heitz 2014, 5.3). */
static double ggx_g1_ref(double cos_v, double alpha)
{
    double c2 = cos_v * cos_v, tan2 = (1 - c2) / c2;
    return 1 / (1 + 0.5 * (-1 + sqrt(1 + alpha * alpha * tan2)));
}

/* D_v(m) = G1(v) <v . m> D(m) / (v . n) (Heitz 2018 eq. 2), from the reference formulas. */
static double ggx_dv_ref(v3 v, v3 n, v3 m, double alpha)
{
    double vm = v3_dot(v, m), vn = v3_dot(v, n);
    return vm > 0 ? ggx_g1_ref(vn, alpha) * vm * ggx_d_ref(v3_dot(m, n), alpha) / vn : 0;
}

static v3 spherical(double theta, double phi)
{
    return v3_make(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
}

static v3 random_unit(lucent_rng *rng)
{
    double z = 2 * lucent_rng_uniform(rng) - 1, phi = 2 * M_PI * lucent_rng_uniform(rng);
    double s = sqrt(fmax(0, 1 - z * z));
    return v3_make(s * cos(phi), s * sin(phi), z);
}

/* ---- Fresnel and refraction ---- */

TEST(fresnel_normal_incidence_is_the_square_of_the_index_contrast)
{
    const double eta[] = {1.0 / 1.5, 1.33, 1.5, 2.42};
    for (int i = 0; i < 4; i++) {
        double want = (1 - eta[i]) / (1 + eta[i]), ct;
        want *= want; /* ((n1 - n2) / (n1 + n2))^2 with eta = n2 / n1 */
        CHECK_NEAR(lucent_fresnel_dielectric(1.0, eta[i], &ct), want, 1e-15);
        CHECK_NEAR(ct, 1.0, 1e-15);
    }
    CHECK(lucent_fresnel_dielectric(0.3, 1.0, NULL) == 0.0); /* index matched: exactly 0 */
}

TEST(fresnel_tends_to_one_at_grazing_incidence)
{
    /* For c = cos_i -> 0 the amplitudes are r_s = -1 + 2c / (eta t0), r_p = 1 - 2 eta c / t0 to first
     * order, t0 = sqrt(1 - 1 / eta^2), so 1 - F = 2 c (1 / (eta t0) + eta / t0) + O(c^2). */
    const double eta[] = {1.33, 1.5, 2.42};
    for (int i = 0; i < 3; i++) {
        double e = eta[i], t0 = sqrt(1 - 1 / (e * e)), slope = 2 * (1 / (e * t0) + e / t0);
        CHECK(lucent_fresnel_dielectric(0.0, e, NULL) == 1.0);
        double c = 1e-6, F = lucent_fresnel_dielectric(c, e, NULL);
        CHECK_NEAR((1 - F) / c, slope, 1e-4 * slope);
        double prev = 0;
        for (int k = 100; k >= 0; k--) { /* F rises monotonically as the angle grows */
            double f = lucent_fresnel_dielectric(k / 100.0, e, NULL);
            CHECK(f >= prev);
            prev = f;
        }
    }
}

TEST(fresnel_total_internal_reflection_beyond_the_critical_angle)
{
    const double eta = 1 / 1.5;            /* glass to air */
    double cos_crit = sqrt(1 - eta * eta); /* sin theta_c = n_t / n_i = eta */
    for (int k = 0; k < 100; k++) {
        double c = cos_crit * k / 100.0, ct = -1;
        CHECK(lucent_fresnel_dielectric(c, eta, &ct) == 1.0);
        CHECK(ct == 0.0);
        v3 t, d = v3_make(sqrt(1 - c * c), 0, -c);
        CHECK(!lucent_refract(d, v3_make(0, 0, 1), eta, &t));
    }
    double c = cos_crit + 1e-6, ct;
    CHECK(lucent_fresnel_dielectric(c, eta, &ct) < 1.0 && ct > 0);
    v3 t;
    CHECK(lucent_refract(v3_make(sqrt(1 - c * c), 0, -c), v3_make(0, 0, 1), eta, &t));
}

TEST(fresnel_is_reciprocal)
{
    /* Stokes: the reflectance seen from the other side at the refracted angle is the same. Each
     * cosine from sqrt(1 - sin^2) carries an absolute rounding error of order eps / cos, hence the
     * tolerance 1e-14 / min(cos_i, cos_t). */
    const double eta[] = {1.33, 1.5, 2.42, 1 / 1.5};
    for (int i = 0; i < 4; i++)
        for (int k = 1; k <= 99; k++) {
            double ci = k / 100.0, ct, F = lucent_fresnel_dielectric(ci, eta[i], &ct);
            if (F >= 1.0) continue;
            double cb, tol = 1e-14 / fmin(ci, ct);
            CHECK_NEAR(lucent_fresnel_dielectric(ct, 1 / eta[i], &cb), F, tol);
            CHECK_NEAR(cb, ci, tol);
        }
}

TEST(fresnel_matches_a_hand_computation_and_the_cook_torrance_form)
{
    /* 45 degrees into glass, eta 1.5: cos_t = sqrt(7) / 3, r_s = (sqrt 2 - sqrt 7) / (sqrt 2 + sqrt 7),
     * so Rs = (9 - 2 sqrt 14) / (9 + 2 sqrt 14) = (137 - 36 sqrt 14) / 25 = 0.0920134, and
     * r_p = -(9 - 2 sqrt 14) / (9 + 2 sqrt 14), Rp = Rs^2 = 0.0084665 (at 45 degrees Rp = Rs^2). */
    double rs = (137 - 36 * sqrt(14.0)) / 25, want = 0.5 * (rs + rs * rs), ct;
    CHECK_NEAR(lucent_fresnel_dielectric(sqrt(0.5), 1.5, &ct), want, 1e-14);
    CHECK_NEAR(want, 0.0502399, 1e-7);
    CHECK_NEAR(ct, sqrt(7.0) / 3, 1e-15);
    const double eta[] = {1.33, 1.5, 2.42, 1 / 1.33, 1 / 1.5};
    for (int i = 0; i < 5; i++)
        for (int k = 0; k <= 100; k++) {
            double c = k / 100.0;
            CHECK_NEAR(lucent_fresnel_dielectric(c, eta[i], NULL), fresnel_cook_torrance(c, eta[i]), 1e-13);
        }
}

TEST(refraction_obeys_snell_and_reflection_mirrors)
{
    lucent_rng rng;
    lucent_rng_init(11, 0, &rng);
    const double eta[] = {1.5, 1 / 1.5, 1.33};
    for (int i = 0; i < 3000; i++) {
        v3 m = random_unit(&rng), d = random_unit(&rng), t;
        if (v3_dot(d, m) > 0) d = v3_neg(d);
        double e = eta[i % 3], si = v3_length(v3_cross(d, m));
        if (!lucent_refract(d, m, e, &t)) {
            CHECK(si / e >= 1 - 1e-12); /* only beyond the critical angle */
            continue;
        }
        CHECK_NEAR(v3_length(t), 1.0, 1e-14);
        CHECK_NEAR(v3_length(v3_cross(t, m)), si / e, 1e-12); /* sin_t = sin_i / eta */
        CHECK_NEAR(v3_dot(v3_cross(d, m), t), 0.0, 1e-12);    /* in the plane of incidence */
        CHECK(v3_dot(t, m) <= 0);                             /* on the far side */
        v3 r = lucent_reflect(d, m);
        CHECK_NEAR(v3_dot(r, m), -v3_dot(d, m), 1e-14);
        CHECK_NEAR(v3_length(v3_sub(v3_cross(d, m), v3_cross(r, m))), 0.0, 1e-12); /* tangent kept */
    }
}

/* ---- GGX ---- */

TEST(ggx_distribution_is_normalised)
{
    /* Int D(m) (n . m) dm = 2 pi Int_0^(pi/2) D(theta) cos sin dtheta = 1 (Walter eq. 4). */
    const double alpha[] = {0.05, 0.3, 1.0};
    for (int a = 0; a < 3; a++) {
        enum { N = 200000 };
        double h = 0.5 * M_PI / N, sum = 0;
        for (int k = 0; k < N; k++) {
            double th = (k + 0.5) * h, c = cos(th);
            double d = lucent_ggx_d(c, alpha[a]);
            CHECK_NEAR(d, ggx_d_ref(c, alpha[a]), 1e-12 * d);
            sum += d * c * sin(th);
        }
        CHECK_NEAR(2 * M_PI * sum * h, 1.0, 1e-6);
    }
}

TEST(ggx_g1_matches_the_smith_closed_form_and_the_projected_area)
{
    const double alpha[] = {0.05, 0.3, 1.0};
    for (int a = 0; a < 3; a++)
        for (int k = 1; k <= 100; k++) {
            double c = k / 100.0;
            CHECK_NEAR(lucent_ggx_g1(c, alpha[a]), ggx_g1_ref(c, alpha[a]), 1e-14);
        }
    /* Heitz 2014 eq. 2: the visible projected area of the microfacets is the macro surface's,
     * cos theta_v = G1(v) Int <v . m> D(m) dm; quadrature in (theta_m, phi_m). */
    const double cases[][2] = {{0.3, 0.4}, {0.3, 1.2}, {0.8, 1.4}};
    for (int i = 0; i < 3; i++) {
        double al = cases[i][0], tv = cases[i][1], proj = 0;
        v3 v = spherical(tv, 0);
        enum { NT = 800, NP = 400 };
        double ht = 0.5 * M_PI / NT, hp = 2 * M_PI / NP;
        for (int j = 0; j < NT; j++)
            for (int k = 0; k < NP; k++) {
                double th = (j + 0.5) * ht;
                v3 m = spherical(th, (k + 0.5) * hp);
                proj += fmax(0, v3_dot(v, m)) * ggx_d_ref(m.z, al) * sin(th);
            }
        proj *= ht * hp;
        CHECK_NEAR(lucent_ggx_g1(cos(tv), al) * proj, cos(tv), 1e-4);
    }
}

/* Samples n_samples visible normals for (alpha, v) about a tilted normal, bins them by (theta,
 * phi) in the normal's frame and compares with N Int_cell D_v sin theta (16 x 16 midpoints). */
static void check_visible_sampler(double alpha, double theta_v, uint64_t seed)
{
    enum { NT = 20, NP = 40, SUB = 16, SAMPLES = 200000 };
    v3 n = v3_normalize(v3_make(0.3, -0.2, 0.9)), t, b;
    lucent_basis(n, &t, &b);
    v3 v = lucent_from_local(spherical(theta_v, 0.7), t, b, n);
    static double obs[NT * NP], exp_[NT * NP];
    memset(obs, 0, sizeof obs);
    lucent_rng rng;
    lucent_rng_init(seed, 0, &rng);
    int below = 0;
    for (int i = 0; i < SAMPLES; i++) {
        double u1 = lucent_rng_uniform(&rng), u2 = lucent_rng_uniform(&rng);
        v3 m = lucent_to_local(lucent_ggx_sample_visible(v, n, alpha, u1, u2), t, b, n);
        double th = acos(fmax(-1, fmin(1, m.z))), ph = atan2(m.y, m.x);
        if (ph < 0) ph += 2 * M_PI;
        if (th >= 0.5 * M_PI) {
            below++;
            continue;
        }
        int it = (int)(th / (0.5 * M_PI) * NT), ip = (int)(ph / (2 * M_PI) * NP);
        obs[(it < NT ? it : NT - 1) * NP + (ip < NP ? ip : NP - 1)]++;
    }
    CHECK_MSG(below == 0, "%d visible normals below the surface", below);
    double dt = 0.5 * M_PI / NT, dp = 2 * M_PI / NP, total = 0;
    for (int it = 0; it < NT; it++)
        for (int ip = 0; ip < NP; ip++) {
            double s = 0;
            for (int a = 0; a < SUB; a++)
                for (int c = 0; c < SUB; c++) {
                    double th = (it + (a + 0.5) / SUB) * dt, ph = (ip + (c + 0.5) / SUB) * dp;
                    s += ggx_dv_ref(lucent_to_local(v, t, b, n), v3_make(0, 0, 1), spherical(th, ph), alpha) * sin(th);
                }
            exp_[it * NP + ip] = s * dt * dp / (SUB * SUB);
            total += exp_[it * NP + ip];
        }
    CHECK_NEAR(total, 1.0, 2e-3); /* D_v is a density: the quadrature itself is good */
    for (int i = 0; i < NT * NP; i++) exp_[i] *= SAMPLES;
    char what[64];
    snprintf(what, sizeof what, "visible normals, alpha %.2f, theta_v %.2f", alpha, theta_v);
    check_chi_square(what, obs, exp_, NT * NP);
}

TEST(ggx_visible_normals_follow_d_v)
{
    check_visible_sampler(0.2, 0.5, 1);
    check_visible_sampler(0.5, 1.2, 2);
    check_visible_sampler(1.0, 1.45, 3);
}

TEST(ggx_visible_pdf_is_d_v)
{
    lucent_rng rng;
    lucent_rng_init(5, 0, &rng);
    v3 n = v3_normalize(v3_make(-0.1, 0.4, 0.8));
    for (int i = 0; i < 2000; i++) {
        v3 v = random_unit(&rng), m = random_unit(&rng);
        if (v3_dot(v, n) <= 0) v = v3_neg(v);
        double want = ggx_dv_ref(v, n, m, 0.4);
        CHECK_NEAR(lucent_ggx_visible_pdf(v, n, m, 0.4), want, 1e-12 * want + 1e-300);
    }
}

/* Int over the sphere of directions i of D_v(h(o, i)) |dh / di| (midpoint quadrature in (theta,
 * phi)), counting the pairs (o, i) that a reflection (or a refraction from eta_o into eta_i) at a
 * visible normal joins: the change of variables of Walter eqs. 14 and 17. */
static double walter_integral(v3 o, double alpha, bool transmit, double eta_o, double eta_i)
{
    enum { NT = 900, NP = 900 };
    v3 n = v3_make(0, 0, 1);
    double ht = M_PI / NT, hp = 2 * M_PI / NP, sum = 0;
    for (int j = 0; j < NT; j++)
        for (int k = 0; k < NP; k++) {
            double th = (j + 0.5) * ht;
            v3 i = spherical(th, (k + 0.5) * hp);
            double f = 0;
            if (!transmit) {
                v3 m = lucent_ggx_half_reflect(o, i);
                double om = v3_dot(o, m);
                if (om > 0) f = ggx_dv_ref(o, n, m, alpha) * lucent_ggx_jacobian_reflect(om);
            } else {
                v3 m = lucent_ggx_half_transmit(o, i, eta_o, eta_i, n);
                double om = v3_dot(o, m), im = v3_dot(i, m);
                if (om > 0 && im < 0)
                    f = ggx_dv_ref(o, n, m, alpha) * lucent_ggx_jacobian_transmit(om, im, eta_o, eta_i);
            }
            sum += f * sin(th);
        }
    return sum * ht * hp;
}

TEST(ggx_half_vectors_and_jacobians_change_variables)
{
    /* Every visible normal m gives one reflected direction and, entering a denser medium (no total
     * internal reflection), one refracted direction (eta_o o + eta_i i is parallel to m), so
     * Int D_v(h(o, i)) |dh / di| di = Int D_v(m) dm = 1 in both cases. */
    v3 o = spherical(0.6, 0.3);
    CHECK_NEAR(walter_integral(o, 0.5, false, 1.0, 1.5), 1.0, 2e-3);
    CHECK_NEAR(walter_integral(o, 0.5, true, 1.0, 1.5), 1.0, 2e-3);
    /* and the half vectors invert the scattering: reflect(-o, h_r) = i, refract(-o, h_t) = i */
    lucent_rng rng;
    lucent_rng_init(9, 0, &rng);
    for (int k = 0; k < 1000; k++) {
        v3 m = lucent_ggx_sample_visible(o, v3_make(0, 0, 1), 0.5, lucent_rng_uniform(&rng), 0.25), i;
        CHECK_NEAR(v3_length(v3_sub(lucent_ggx_half_reflect(o, lucent_reflect(v3_neg(o), m)), m)), 0, 1e-12);
        if (!lucent_refract(v3_neg(o), m, 1.5, &i)) continue;
        CHECK_NEAR(v3_length(v3_sub(lucent_ggx_half_transmit(o, i, 1.0, 1.5, v3_make(0, 0, 1)), m)), 0, 1e-12);
    }
}

/* ---- Henyey-Greenstein ---- */

/* P(mu' <= mu) for HG: (1 - g^2) / (2 g) (1 / sqrt(1 + g^2 - 2 g mu) - 1 / (1 + g)); (mu + 1) / 2 at g = 0. */
static double hg_cdf(double mu, double g)
{
    if (g == 0) return 0.5 * (mu + 1);
    return (1 - g * g) / (2 * g) * (1 / sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));
}

static void check_hg_cos(double g, bool use_float, uint64_t seed)
{
    enum { BINS = 50, SAMPLES = 200000 };
    double obs[BINS] = {0}, exp_[BINS];
    lucent_rng rng;
    lucent_rng_init(seed, 0, &rng);
    lucent_hg_f hf = lucent_hg_prepare_f(g);
    for (int i = 0; i < SAMPLES; i++) {
        double u = lucent_rng_uniform(&rng);
        double mu = use_float ? lucent_hg_sample_cos_f(&hf, (float)u) : lucent_hg_sample_cos(g, u);
        int b = (int)((mu + 1) / 2 * BINS);
        obs[b < 0 ? 0 : b >= BINS ? BINS - 1 : b]++;
    }
    for (int b = 0; b < BINS; b++)
        exp_[b] = SAMPLES * (hg_cdf(-1 + 2.0 * (b + 1) / BINS, g) - hg_cdf(-1 + 2.0 * b / BINS, g));
    char what[64];
    snprintf(what, sizeof what, "HG cosine, g %.2f (%s)", g, use_float ? "float" : "double");
    check_chi_square(what, obs, exp_, BINS);
}

TEST(hg_cosines_follow_the_phase_function)
{
    check_hg_cos(-0.7, false, 1);
    check_hg_cos(0.0, false, 2);
    check_hg_cos(0.3, false, 3);
    check_hg_cos(0.9, false, 4);
    check_hg_cos(-0.7, true, 5);
    check_hg_cos(0.3, true, 6);
    check_hg_cos(0.9, true, 7);
}

TEST(hg_phase_function_is_normalised_and_matches_its_cdf)
{
    const double g[] = {-0.7, 0.0, 0.3, 0.9};
    for (int i = 0; i < 4; i++) {
        enum { N = 100000 };
        double sum = 0, h = 2.0 / N;
        for (int k = 0; k < N; k++) sum += lucent_hg_phase(-1 + (k + 0.5) * h, g[i]);
        CHECK_NEAR(2 * M_PI * sum * h, 1.0, 1e-6); /* Int p dw = 2 pi Int p dmu = 1 */
        /* dP / dmu = 2 pi p(mu) (central difference of the closed-form distribution) */
        for (int k = 1; k < 20; k++) {
            double mu = -1 + k / 10.0, e = 1e-5;
            double dp = (hg_cdf(mu + e, g[i]) - hg_cdf(mu - e, g[i])) / (2 * e);
            CHECK_NEAR(2 * M_PI * lucent_hg_phase(mu, g[i]), dp, 1e-6 * (1 + dp));
        }
    }
}

TEST(hg_directions_have_mean_cosine_g_and_uniform_azimuth)
{
    enum { SAMPLES = 100000, BINS = 36 };
    const double g[] = {-0.5, 0.2, 0.85};
    lucent_rng rng;
    lucent_rng_init(21, 0, &rng);
    for (int i = 0; i < 3; i++) {
        v3 d = v3_normalize(v3_make(0.2, 0.9, -0.4));
        /* an azimuth frame built independently of lucent_basis (Gram-Schmidt from x) */
        v3 e1 = v3_normalize(v3_madd(v3_make(1, 0, 0), d, -d.x)), e2 = v3_cross(d, e1);
        double sum = 0, sum_perp1 = 0, sum_perp2 = 0, obs[BINS] = {0}, exp_[BINS];
        for (int k = 0; k < SAMPLES; k++) {
            double u1 = lucent_rng_uniform(&rng), u2 = lucent_rng_uniform(&rng);
            v3 w = lucent_hg_sample(d, g[i], u1, u2);
            CHECK_NEAR(v3_length(w), 1.0, 1e-12);
            double x = v3_dot(w, e1), y = v3_dot(w, e2), ph = atan2(y, x);
            sum += v3_dot(w, d), sum_perp1 += x, sum_perp2 += y;
            int b = (int)((ph + M_PI) / (2 * M_PI) * BINS);
            obs[b < BINS ? b : BINS - 1]++;
        }
        /* Var mu = E[mu^2] - g^2 = (1 + 2 g^2) / 3 - g^2; each perpendicular component has variance
         * (1 - E[mu^2]) / 2 and mean 0 */
        double e2m = (1 + 2 * g[i] * g[i]) / 3, se = sqrt((e2m - g[i] * g[i]) / SAMPLES);
        double se_perp = sqrt(0.5 * (1 - e2m) / SAMPLES);
        CHECK_MSG(fabs(sum / SAMPLES - g[i]) <= 3 * se, "g %.2f: mean cosine %.5f +- %.5f", g[i], sum / SAMPLES, se);
        CHECK(fabs(sum_perp1 / SAMPLES) <= 3 * se_perp && fabs(sum_perp2 / SAMPLES) <= 3 * se_perp);
        for (int b = 0; b < BINS; b++) exp_[b] = (double)SAMPLES / BINS;
        char what[64];
        snprintf(what, sizeof what, "HG azimuth, g %.2f", g[i]);
        check_chi_square(what, obs, exp_, BINS);
    }
}

TEST(hg_float_sampling_agrees_with_double)
{
    /* mu = (a - t^2) e with t = b / (c + d u), a = 1 + g^2, b = 1 - g^2, c = 1 - g, d = 2 g,
     * e = 1 / (2 g), for the |g| >= 0.01 the Monte Carlo runs in float. Each float rounding is at most
     * eps = FLT_EPSILON relative; to first order t carries the relative error
     * dt = eps (2 + (|c| + |d u|) / |c + d u|) (b, the sum with its cancellation, the quotient), so
     * |mu_f - mu| <= eps (|e| (2 a + t^2 (2 + 2 dt / eps)) + 2) (a, t^2 and their difference, then e). */
    const double g[] = {-0.99, -0.5, -0.05, 0.01, 0.3, 0.9, 0.99};
    for (int i = 0; i < 7; i++) {
        lucent_hg_f hf = lucent_hg_prepare_f(g[i]);
        for (int k = 0; k <= 1000; k++) {
            float u = (float)(k / 1000.0);
            double a = 1 + g[i] * g[i], c = 1 - g[i], d = 2 * g[i], den = c + d * u, t = (1 - g[i] * g[i]) / den;
            double dt = FLT_EPSILON * (2 + (fabs(c) + fabs(d * u)) / fabs(den));
            double tol = FLT_EPSILON * (fabs(1 / (2 * g[i])) * (2 * a + t * t * (2 + 2 * dt / FLT_EPSILON)) + 2);
            CHECK_NEAR(lucent_hg_sample_cos_f(&hf, u), lucent_hg_sample_cos(g[i], u), tol);
        }
    }
}

/* ---- the basis ---- */

static void check_basis(v3 n)
{
    v3 t, b;
    lucent_basis(n, &t, &b);
    double e = fmax(fabs(v3_dot(t, t) - 1), fabs(v3_dot(b, b) - 1));
    e = fmax(e, fmax(fabs(v3_dot(t, b)), fmax(fabs(v3_dot(t, n)), fabs(v3_dot(b, n)))));
    e = fmax(e, v3_length(v3_sub(v3_cross(t, b), n))); /* right-handed: t x b = n */
    CHECK_MSG(e <= 1e-14, "n = (%.17g, %.17g, %.17g): error %.3g", n.x, n.y, n.z, e);
    v3 w = v3_normalize(v3_make(0.3, -0.5, 0.8));
    CHECK(v3_length(v3_sub(lucent_from_local(lucent_to_local(w, t, b, n), t, b, n), w)) <= 1e-14);
}

TEST(basis_is_orthonormal_and_right_handed)
{
    lucent_rng rng;
    lucent_rng_init(3, 0, &rng);
    for (int i = 0; i < 100000; i++) check_basis(random_unit(&rng));
    const double z[] = {1.0, -1.0, 1 - 1e-12, -1 + 1e-12, 1 - 1e-6, -1 + 1e-6, 1e-9, -1e-9, 0.0, -0.0};
    for (int i = 0; i < 10; i++)
        for (int k = 0; k < 8; k++) {
            double s = sqrt(fmax(0, 1 - z[i] * z[i])), phi = k * M_PI / 4 + 0.1;
            check_basis(v3_make(s * cos(phi), s * sin(phi), z[i]));
        }
    check_basis(v3_make(1, 0, -0.0));
    /* the float basis: the same formula, so within float rounding of the double one */
    for (int i = 0; i < 10000; i++) {
        v3 n = random_unit(&rng), t, b;
        if (i < 80) { /* near +-z too */
            double zz = z[i % 10], s = sqrt(fmax(0, 1 - zz * zz));
            n = v3_make(s * cos(i * 0.1), s * sin(i * 0.1), zz);
        }
        lucent_basis(n, &t, &b);
        float nf[3] = {(float)n.x, (float)n.y, (float)n.z}, tf[3], bf[3];
        lucent_basis_f(nf, tf, bf);
        double e = fmax(v3_length(v3_sub(v3_make(tf[0], tf[1], tf[2]), t)),
                        v3_length(v3_sub(v3_make(bf[0], bf[1], bf[2]), b)));
        CHECK_MSG(e <= 1e-6, "n = (%.9g, %.9g, %.9g): float basis off by %.3g", n.x, n.y, n.z, e);
    }
    /* lucent_around: the cosine to the axis is the one asked for */
    for (int i = 0; i < 1000; i++) {
        v3 n = random_unit(&rng);
        double mu = 2 * lucent_rng_uniform(&rng) - 1;
        v3 w = lucent_around(n, mu, 2 * M_PI * lucent_rng_uniform(&rng));
        CHECK_NEAR(v3_dot(w, n), mu, 1e-14);
    }
}

TEST_MAIN(TEST_ENTRY(fresnel_normal_incidence_is_the_square_of_the_index_contrast),
          TEST_ENTRY(fresnel_tends_to_one_at_grazing_incidence),
          TEST_ENTRY(fresnel_total_internal_reflection_beyond_the_critical_angle), TEST_ENTRY(fresnel_is_reciprocal),
          TEST_ENTRY(fresnel_matches_a_hand_computation_and_the_cook_torrance_form),
          TEST_ENTRY(refraction_obeys_snell_and_reflection_mirrors), TEST_ENTRY(ggx_distribution_is_normalised),
          TEST_ENTRY(ggx_g1_matches_the_smith_closed_form_and_the_projected_area),
          TEST_ENTRY(ggx_visible_normals_follow_d_v), TEST_ENTRY(ggx_visible_pdf_is_d_v),
          TEST_ENTRY(ggx_half_vectors_and_jacobians_change_variables), TEST_ENTRY(hg_cosines_follow_the_phase_function),
          TEST_ENTRY(hg_phase_function_is_normalised_and_matches_its_cdf),
          TEST_ENTRY(hg_directions_have_mean_cosine_g_and_uniform_azimuth),
          TEST_ENTRY(hg_float_sampling_agrees_with_double), TEST_ENTRY(basis_is_orthonormal_and_right_handed))
