/* Tests of src/cdrf: the CDRF (Kubo et al. Eq. 1-4, 6), Collomb's fit, the LUT and its files,
 * the sphere Monte Carlo and the sigma0 fit. Expected values come from analytic limits and from
 * independent computations written out here (the Fourier series of max(cos, 0), closed-form
 * transmission through an absorbing sphere, a single-scattering line integral). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/cdrf.h"
#include "test.h"

/* Independent reference: the Fourier series of the half-wave rectified cosine,
 * max(cos t, 0) = 1/pi + cos(t)/2 + (2/pi) sum_{m>=1} (-1)^(m+1) cos(2 m t) / (4 m^2 - 1);
 * convolving with a Gaussian multiplies mode k by exp(-k^2 sigma^2 / 2). Converges fast for
 * sigma >= 0.1 (terms beyond m = 60 are below exp(-72)). */
static double fourier_kubo(double theta, double sigma)
{
    double f = 1.0 / M_PI + 0.5 * exp(-0.5 * sigma * sigma) * cos(theta);
    for (int m = 1; m <= 200; m++)
        f += 2.0 / M_PI * (m % 2 ? 1.0 : -1.0) * exp(-2.0 * m * m * sigma * sigma) * cos(2.0 * m * theta) /
             (4.0 * m * m - 1.0);
    return f;
}

TEST(kubo_at_sigma_zero_is_lambert)
{
    /* Eq. 1-3 with sigma -> 0: the Gaussian becomes a delta, so f = E = max(cos, 0) (Eq. 2). */
    for (int i = 0; i <= 64; i++) {
        double t = M_PI * i / 64;
        CHECK_NEAR(lucent_cdrf_kubo(t, 0), fmax(cos(t), 0), 0);
        CHECK_NEAR(lucent_cdrf_kubo(t, 1e-6), fmax(cos(t), 0), 1e-6);
        CHECK_NEAR(lucent_cdrf_lambert(t), fmax(cos(t), 0), 0);
    }
}

TEST(kubo_matches_the_fourier_series)
{
    static const double sigmas[] = {0.1, 0.25, 0.5, 1.0, 1.7, 3.0};
    double worst = 0;
    for (int k = 0; k < 6; k++)
        for (int i = 0; i <= 40; i++) {
            double t = M_PI * i / 40;
            worst = fmax(worst, fabs(lucent_cdrf_kubo(t, sigmas[k]) - fourier_kubo(t, sigmas[k])));
        }
    CHECK_MSG(worst < 1e-11, "quadrature vs Fourier series: worst difference %.3g", worst);
}

TEST(kubo_is_periodic_and_conserves_the_mean)
{
    /* E is 2 pi-periodic and even, so f is too (symmetric about pi); the convolution keeps the
     * mean of E over the circle, 1/pi (the trapezoid rule is exact for the low modes here). */
    static const double sigmas[] = {0.05, 0.4, 1.2, 3.0};
    for (int k = 0; k < 4; k++) {
        double s = sigmas[k], mean = 0;
        for (int i = 0; i < 256; i++) mean += lucent_cdrf_kubo(2 * M_PI * i / 256, s) / 256;
        CHECK_NEAR(mean, 1.0 / M_PI, 1e-9);
        for (double t = 0.1; t < M_PI; t += 0.37) {
            CHECK_NEAR(lucent_cdrf_kubo(-t, s), lucent_cdrf_kubo(t, s), 1e-13);
            CHECK_NEAR(lucent_cdrf_kubo(2 * M_PI - t, s), lucent_cdrf_kubo(t, s), 1e-12);
            CHECK_NEAR(lucent_cdrf_kubo(M_PI + t, s), lucent_cdrf_kubo(M_PI - t, s), 1e-12);
        }
    }
    /* sigma -> infinity: everything is smeared to the mean (Fourier: 1/pi + O(exp(-sigma^2/2))). */
    CHECK_NEAR(lucent_cdrf_kubo(0.3, 10.0), 1.0 / M_PI, 1e-12);
    CHECK_NEAR(lucent_cdrf_kubo(0.3, 1e300), 1.0 / M_PI, 0);
    CHECK(isnan(lucent_cdrf_kubo(NAN, 1.0)) && isnan(lucent_cdrf_kubo(INFINITY, 1.0)));
    CHECK(isnan(lucent_cdrf_kubo(1.0, NAN)));
}

TEST(collomb_closed_form)
{
    /* Values by hand from the blog's formula: kappa = 0, theta = 0: 1/4 * 2 + 0.075 = 0.575;
     * kappa = 1, theta = 0: 2/4 * 2 = 1. */
    CHECK_NEAR(lucent_cdrf_collomb(0, 0), 0.575, 1e-15);
    CHECK_NEAR(lucent_cdrf_collomb(0, 1), 1.0, 1e-15);
    /* kappa = 0, theta = pi: min(5 pi / 4, pi) = pi, so cos(...) + 1 = 0 and f = 0.075. */
    CHECK_NEAR(lucent_cdrf_collomb(M_PI, 0), 0.075, 1e-15);
    /* kappa = 1, theta = 1: (2/4)(cos 1.5 + 1) / (1 + (ln 2.7 / 1.45)^10). */
    double q = log(2.7) / 1.45;
    CHECK_NEAR(lucent_cdrf_collomb(1, 1), 0.5 * (cos(1.5) + 1) / (1 + pow(q, 10)), 1e-14);
    /* kappa = 3 at theta = pi: (cos(pi) + 1) = 0, 0.075 (1 - 3) < 0 -> clamped to 0. */
    CHECK_NEAR(lucent_cdrf_collomb(M_PI, 3), 0, 0);
    CHECK_NEAR(lucent_cdrf_eval(LUCENT_CDRF_COLLOMB, -1, 1), lucent_cdrf_collomb(1, 1), 0);
    lucent_cdrf_variant v;
    CHECK(lucent_cdrf_variant_parse("collomb", &v) == LUCENT_OK && v == LUCENT_CDRF_COLLOMB);
    CHECK(lucent_cdrf_variant_parse("kubo", &v) == LUCENT_OK && v == LUCENT_CDRF_KUBO);
    CHECK_ERR(lucent_cdrf_variant_parse("lambert", &v), LUCENT_ERR_INVALID_ARGUMENT, "lambert", "kubo, collomb");
    CHECK(strcmp(lucent_cdrf_variant_name(LUCENT_CDRF_COLLOMB), "collomb") == 0);
}

TEST(sigma0_from_diffuse_colour)
{
    /* Eq. 4 and Eq. 6 by hand. */
    CHECK_NEAR(lucent_cdrf_sigma(2.0, 0.25), 0.5, 0);
    CHECK_NEAR(lucent_cdrf_sigma0_from_diffuse(0.5), 0.25, 0);
    CHECK_NEAR(lucent_cdrf_sigma0_from_diffuse(-0.5), 0, 0);
    CHECK_NEAR(lucent_cdrf_sigma0_from_diffuse(NAN), 0, 0);
    lucent_image *d = NULL, *s = NULL;
    CHECK_OK(lucent_image_create(2, 1, 3, &d));
    if (!d) return;
    for (int i = 0; i < 6; i++) d->data[i] = 0.1f * (float)i;
    CHECK_OK(lucent_cdrf_sigma0_map(d, &s));
    if (s) {
        CHECK(s->channels == 3 && s->width == 2 && s->height == 1);
        for (int i = 0; i < 6; i++) CHECK_NEAR(s->data[i], (double)d->data[i] * d->data[i], 1e-7);
    }
    lucent_image_destroy(s);
    lucent_image_destroy(d);
}

TEST(lut_rows_columns_and_monotone_widening)
{
    lucent_cdrf_lut_desc desc = {.width = 65, .height = 31};
    lucent_image *lut = NULL;
    CHECK_OK(lucent_cdrf_lut_build(&desc, &lut));
    if (!lut) return;
    CHECK(lut->width == 65 && lut->height == 31 && lut->channels == 1);
    /* Acceptance: row sigma = 0 equals max(cos theta, 0) to 1e-4. */
    for (int i = 0; i < 65; i++) CHECK_NEAR(lut->data[i], fmax(-1 + 2.0 * i / 64, 0), 1e-4);
    /* Every sample is the function at its (cos theta, sigma) (float rounding). */
    for (int j = 0; j < 31; j += 5)
        for (int i = 0; i < 65; i += 8) {
            double c = -1 + 2.0 * i / 64, s = 3.0 * j / 30;
            CHECK_NEAR(lut->data[j * 65 + i], lucent_cdrf_kubo(acos(c), s), 1e-6);
        }
    /* Widening is monotone in sigma: the peak (cos = 1) falls, every shadowed sample (cos <= 0)
     * rises, and so does the share of the row's energy in the shadow (heat equation on the circle:
     * d/dt of the mass beyond pi/2 is -f'(pi/2) > 0 while f decreases on [0, pi]). */
    double prev_share = -1;
    for (int j = 1; j < 31; j++) {
        const float *row = lut->data + j * 65, *up = row - 65;
        CHECK_MSG(row[64] < up[64], "peak does not fall at row %d", j);
        for (int i = 0; i <= 32; i++) CHECK_MSG(row[i] >= up[i], "shadow sample %d falls at row %d", i, j);
        double shadow = 0, all = 0;
        for (int i = 0; i < 65; i++) {
            double t = acos(fmin(1.0, -1 + 2.0 * i / 64));
            all += lucent_cdrf_kubo(t, 3.0 * j / 30);
            if (i <= 32) shadow += lucent_cdrf_kubo(t, 3.0 * j / 30);
        }
        CHECK(shadow / all > prev_share);
        prev_share = shadow / all;
    }
    /* The same table with two threads. */
    lucent_pool *pool = lucent_pool_create(2);
    lucent_image *lut2 = NULL;
    desc.pool = pool;
    CHECK_OK(lucent_cdrf_lut_build(&desc, &lut2));
    if (lut2) CHECK(memcmp(lut->data, lut2->data, 65 * 31 * sizeof(float)) == 0);
    lucent_image_destroy(lut2);
    lucent_pool_destroy(pool);
    lucent_image_destroy(lut);
}

TEST(lut_files)
{
    lucent_cdrf_lut_desc desc = {.variant = LUCENT_CDRF_COLLOMB, .width = 17, .height = 9, .sigma_max = 2};
    lucent_image *lut = NULL, *back = NULL;
    CHECK_OK(lucent_cdrf_lut_build(&desc, &lut));
    if (!lut) return;
    /* Collomb: row j holds kappa = 2 j / 8; column 16 is theta = 0. */
    CHECK_NEAR(lut->data[4 * 17 + 16], lucent_cdrf_collomb(0, 1.0), 1e-6);
    static const char *const names[] = {"lut.exr", "lut.pfm"};
    for (int k = 0; k < 2; k++) {
        CHECK_OK(lucent_cdrf_lut_write(test_path(names[k]), lut, 2, NULL));
        CHECK_OK(lucent_image_load(test_path(names[k]), &back));
        if (!back) continue;
        CHECK(back->width == 17 && back->height == 9);
        for (int i = 0; i < 17 * 9; i++) CHECK_NEAR(back->data[i * back->channels], lut->data[i], 0);
        lucent_image_destroy(back);
        back = NULL;
    }
    CHECK_OK(lucent_cdrf_lut_write(test_path("lut.c"), lut, 2, "my_lut"));
    char *text = NULL;
    size_t size;
    CHECK_OK(lucent_read_file(test_path("lut.c"), &text, &size));
    if (text) {
        CHECK(strstr(text, "static const float my_lut[9][17] = {") != NULL);
        CHECK(strstr(text, "#define my_lut_SIGMA_MAX 2") != NULL);
        free(text);
    }
    CHECK_ERR(lucent_cdrf_lut_write(test_path("lut.png"), lut, 2, NULL), LUCENT_ERR_UNSUPPORTED, "lut.png",
              "unknown LUT format");
    CHECK_ERR(lucent_cdrf_lut_write(test_path("missing/lut.exr"), lut, 2, NULL), LUCENT_ERR_IO, "missing/lut.exr");
    lucent_image_destroy(lut);
    lucent_image *bad = NULL;
    CHECK_ERR(lucent_cdrf_lut_build(&(lucent_cdrf_lut_desc){.width = 1}, &bad), LUCENT_ERR_INVALID_ARGUMENT,
              "width and height");
    CHECK(bad == NULL);
}

/* ---- the sphere ---- */

static lucent_material make_material(double sa, double ss, double g, double eta)
{
    lucent_material m = {.name = "test", .eta = eta};
    for (int c = 0; c < 3; c++) m.sigma_a[c] = sa, m.sigma_s[c] = ss, m.g[c] = g;
    return m;
}

TEST(sphere_pure_absorber_transmission)
{
    /* eta = 1, no scattering: a ray at distance rho from the axis crosses a chord 2 sqrt(r^2 - rho^2);
     * averaged over the disk, T = 2 (1 - exp(-a r)(1 + a r)) / (a r)^2 with a = 2 sigma_a.
     * Nothing leaves toward the camera (every exit travels along -x). */
    lucent_material m = make_material(0.3, 0, 0, 1.0);
    lucent_cdrf_sphere_result res;
    CHECK_OK(lucent_cdrf_sphere_run(
        &(lucent_cdrf_sphere_desc){.material = &m, .radius = 2, .photons = 40000, .bins = 12, .seed = 3}, &res));
    double a = 0.6, r = 2, t = 2 * (1 - exp(-a * r) * (1 + a * r)) / (a * r * a * r);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(res.entered[c], 1.0, 1e-12);
        CHECK_NEAR(res.exited[c], t, 0.01);
        CHECK_NEAR(res.exited[c] + res.absorbed[c], 1.0, 1e-9);
        for (int j = 0; j < 12; j++) CHECK_NEAR(res.radiance[c][j], 0, 0);
    }
}

TEST(sphere_conserves_energy_and_fresnel_entry)
{
    /* No absorption: all that enters leaves (Russian roulette is unbiased; since the internal
     * reflection plays it too, a run's exited fraction spreads by 0.2% (sd over 12 seeds x 3 channels
     * at this photon count): bounded here by 3.5 of those, 0.7%). The entering fraction for a smooth sphere is
     * 1 - 2 Int_0^1 F(mu) mu dmu (uniform over the disk, cos i = sqrt(1 - (rho/r)^2)), integrated
     * here by the midpoint rule. */
    double eta = 1.4, refl = 0;
    enum { N = 20000 };
    for (int i = 0; i < N; i++) {
        double mu = (i + 0.5) / N, st = sqrt(1 - mu * mu) / eta, ct = sqrt(1 - st * st);
        double rs = (mu - eta * ct) / (mu + eta * ct), rp = (ct - eta * mu) / (ct + eta * mu);
        refl += 0.5 * (rs * rs + rp * rp) * 2 * mu / N;
    }
    lucent_material m = make_material(0, 2.0, 0.5, eta);
    lucent_cdrf_sphere_result res;
    CHECK_OK(lucent_cdrf_sphere_run(
        &(lucent_cdrf_sphere_desc){.material = &m, .radius = 1, .photons = 20000, .bins = 6, .seed = 5}, &res));
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(res.entered[c], 1 - refl, 0.004);
        CHECK_NEAR(res.exited[c] / res.entered[c], 1.0, 0.007);
        CHECK_NEAR(res.absorbed[c], 0, 0);
    }
    /* A rough boundary with a tiny GGX alpha behaves like the smooth one. */
    lucent_cdrf_sphere_result rough;
    CHECK_OK(lucent_cdrf_sphere_run(
        &(lucent_cdrf_sphere_desc){
            .material = &m, .radius = 1, .photons = 20000, .bins = 6, .seed = 5, .roughness = 1e-4},
        &rough));
    CHECK_NEAR(rough.entered[0], 1 - refl, 0.004);
    /* A rough boundary loses some light to masking but keeps most of it. */
    CHECK_OK(lucent_cdrf_sphere_run(
        &(lucent_cdrf_sphere_desc){
            .material = &m, .radius = 1, .photons = 20000, .bins = 6, .seed = 5, .roughness = 0.5},
        &rough));
    CHECK(rough.entered[0] > 0.7 && rough.entered[0] < 1 - refl + 0.01);
    CHECK(rough.exited[0] <= rough.entered[0] + 1e-3);
}

/* Single scattering toward +z from the equator point at theta, eta = 1, isotropic: the line integral
 * L = Int_0^{2 r sin theta} sigma_s / (4 pi) exp(-sigma_t d_L(q)) exp(-sigma_t s) ds, q = p - s z,
 * d_L(q) the distance from q to the sphere toward the light (+x). */
static double single_scatter(double theta, double r, double sa, double ss)
{
    double st = sa + ss, px = r * cos(theta), pz = r * sin(theta), len = 2 * pz, sum = 0;
    enum { N = 400 };
    for (int i = 0; i < N; i++) {
        double s = (i + 0.5) * len / N, qz = pz - s;
        double dl = -px + sqrt(fmax(0.0, r * r - qz * qz));
        sum += ss / (4 * M_PI) * exp(-st * dl) * exp(-st * s) * len / N;
    }
    return sum;
}

TEST(sphere_single_scattering_radiance)
{
    /* Checks the estimator's normalisation (photon power, band area, cone solid angle, the rotation
     * about the light axis) against an independent line integral. Only exits after exactly one
     * scattering are scored (max_order = 1). Bins away from grazing view; 3 se plus 3% for the
     * cone's angular averaging. */
    double r = 1, sa = 0.6, ss = 0.6;
    lucent_material m = make_material(sa, ss, 0, 1.0);
    lucent_cdrf_sphere_result res;
    lucent_pool *pool = lucent_pool_create(2);
    CHECK_OK(lucent_cdrf_sphere_run(&(lucent_cdrf_sphere_desc){.material = &m,
                                                               .radius = r,
                                                               .photons = 600000,
                                                               .bins = 6,
                                                               .seed = 11,
                                                               .max_order = 1,
                                                               .cone = 0.25,
                                                               .pool = pool},
                                    &res));
    for (int j = 1; j < 5; j++) {
        double ta = M_PI * j / 6, tb = M_PI * (j + 1) / 6, num = 0, den = 0;
        for (int k = 0; k < 20; k++) { /* bin average weighted like the estimator: sin theta * cos view */
            double t = ta + (k + 0.5) * (tb - ta) / 20, w = sin(t) * sin(t);
            num += w * single_scatter(t, r, sa, ss), den += w;
        }
        double expect = num / den, got = res.radiance[0][j], se = res.radiance_se[0][j];
        CHECK_MSG(fabs(got - expect) <= 3 * se + 0.03 * expect, "bin %d: MC %.5g +- %.2g, single scattering %.5g", j,
                  got, se, expect);
    }
    /* The same seed gives the same numbers on one thread and on two. */
    lucent_cdrf_sphere_result one, two;
    lucent_material skin = make_material(0.1, 1.0, 0.3, 1.3);
    lucent_cdrf_sphere_desc d = {
        .material = &skin, .radius = 2, .photons = 20000, .bins = 9, .seed = 2, .roughness = 0.3};
    CHECK_OK(lucent_cdrf_sphere_run(&d, &one));
    d.pool = pool;
    CHECK_OK(lucent_cdrf_sphere_run(&d, &two));
    CHECK(memcmp(&one, &two, sizeof one) == 0);
    lucent_pool_destroy(pool);
}

TEST(sphere_rejects_bad_input)
{
    lucent_material m = make_material(0.1, 1, 0, 1.3);
    lucent_cdrf_sphere_result res;
    CHECK_ERR(lucent_cdrf_sphere_run(&(lucent_cdrf_sphere_desc){.material = &m, .radius = -1}, &res),
              LUCENT_ERR_INVALID_ARGUMENT, "radius");
    CHECK_ERR(lucent_cdrf_sphere_run(&(lucent_cdrf_sphere_desc){.material = &m, .radius = 1, .roughness = 2}, &res),
              LUCENT_ERR_INVALID_ARGUMENT, "roughness");
    m.g[1] = 1.5;
    CHECK_ERR(lucent_cdrf_sphere_run(&(lucent_cdrf_sphere_desc){.material = &m, .radius = 1}, &res),
              LUCENT_ERR_INVALID_ARGUMENT, "g[1]");
}

/* ---- the fit ---- */

TEST(fit_recovers_synthetic_sigma0)
{
    /* Data made from the model itself, k_d f(theta; sigma0 / r), sigma0 = (1.5, 0.8, 0.3) mm and
     * k_d = (0.2, 0.15, 0.1): the fit must find them; Lambert's residual must be larger. */
    static const double radii[3] = {1, 2, 5}, s0[3] = {1.5, 0.8, 0.3}, kd[3] = {0.2, 0.15, 0.1};
    lucent_cdrf_sphere_result *sp = calloc(3, sizeof *sp);
    if (!sp) return;
    for (int i = 0; i < 3; i++) {
        sp[i].bins = 18, sp[i].radius = radii[i];
        for (int j = 0; j < 18; j++) {
            sp[i].theta[j] = M_PI * (j + 0.5) / 18;
            for (int c = 0; c < 3; c++) {
                sp[i].radiance[c][j] = kd[c] * lucent_cdrf_kubo(sp[i].theta[j], s0[c] / radii[i]);
                sp[i].radiance_se[c][j] = 0.001;
            }
        }
    }
    lucent_cdrf_fit fit;
    CHECK_OK(lucent_cdrf_fit_spheres(sp, 3, LUCENT_CDRF_KUBO, 10, &fit));
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(fit.sigma0[c], s0[c], 1e-4);
        CHECK_NEAR(fit.kd[c], kd[c], 1e-5);
        CHECK(fit.rms[c] < 1e-6);
        CHECK(fit.lambert_rms[c] > 10 * fit.rms[c]);
    }
    CHECK_ERR(lucent_cdrf_fit_spheres(sp, 0, LUCENT_CDRF_KUBO, 0, &fit), LUCENT_ERR_INVALID_ARGUMENT, "no spheres");
    free(sp);
}

TEST_MAIN(TEST_ENTRY(kubo_at_sigma_zero_is_lambert), TEST_ENTRY(kubo_matches_the_fourier_series),
          TEST_ENTRY(kubo_is_periodic_and_conserves_the_mean), TEST_ENTRY(collomb_closed_form),
          TEST_ENTRY(sigma0_from_diffuse_colour), TEST_ENTRY(lut_rows_columns_and_monotone_widening),
          TEST_ENTRY(lut_files), TEST_ENTRY(sphere_pure_absorber_transmission),
          TEST_ENTRY(sphere_conserves_energy_and_fresnel_entry), TEST_ENTRY(sphere_single_scattering_radiance),
          TEST_ENTRY(sphere_rejects_bad_input), TEST_ENTRY(fit_recovers_synthetic_sigma0))
