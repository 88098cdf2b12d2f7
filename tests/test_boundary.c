/* Tests of the path tracer's boundary on flat parts (lucent_boundary_run, src/profile/boundary_mc.c)
 * and of the bake part made from it (LUCENT_BAKE_BOUNDARY). Expected values: Giovanelli 1955's
 * half-space (published), energy conservation, Beer-Lambert through a matched slab (closed form),
 * Helmholtz reciprocity (a physical law), and the factors' definitions. The tables against the path
 * tracer itself: test_gl_boundary. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/bake.h"
#include "lucent/profile.h"
#include "test.h"

enum { N = LUCENT_BOUNDARY_BINS };

static lucent_material grey(double sigma_a, double sigma_s, double eta)
{
    lucent_material m;
    memset(&m, 0, sizeof m);
    snprintf(m.name, sizeof m.name, "grey");
    for (int c = 0; c < 3; c++) m.sigma_a[c] = sigma_a, m.sigma_s[c] = sigma_s;
    m.eta = eta;
    return m;
}

/* The cosine-weighted solid angle of bin b over pi: hi^2 - lo^2. */
static double bin_weight(int b) { return (2.0 * b + 1.0) / (N * N); }

static lucent_boundary_result *run(const lucent_material *m, double roughness, double thickness, uint64_t photons,
                                   lucent_pool *pool)
{
    lucent_boundary_result *r = malloc(sizeof *r);
    CHECK(r != NULL);
    if (!r) return NULL;
    lucent_boundary_desc d = {
        .material = m, .roughness = roughness, .thickness = thickness, .photons = photons, .pool = pool};
    CHECK_OK(lucent_boundary_run(&d, r));
    return r;
}

/* Giovanelli 1955 (n 1.5, g 0, albedo 0.9, normal incidence): Rsp + Rd = 0.2600, Rsp 0.04, so
 * Rd = 0.2200 (4 digits), the value test_bake holds the MCML walk to. The smooth face's row of the
 * normal incidence bin (0 to 14.4 degrees) integrated over exit, within 3 standard errors plus 0.001
 * for the bin's width (Rd changes by less over 14 degrees; Fresnel's reflectance by 0.0003). */
TEST(smooth_half_space_matches_giovanelli)
{
    lucent_material m = grey(0.1, 0.9, 1.5);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_boundary_result *r = run(&m, 0, 0, 6000, pool);
    for (int c = 0; r && c < 3; c++) {
        double err = r->reflect_total_se[c][N - 1], rd = r->reflect_total[c][N - 1];
        printf("     channel %d: Rd %.4f +- %.4f (Giovanelli 0.2200), specular %.4f (Fresnel 0.0400)\n", c, rd, err,
               r->specular[c][N - 1]);
        CHECK_MSG(fabs(rd - 0.2200) <= 3 * err + 0.001, "Rd %.4f +- %.4f", rd, err);
        CHECK_NEAR(r->specular[c][N - 1], 0.0401, 0.0003);
    }
    free(r);
    lucent_pool_destroy(pool);
}

/* Energy: light that enters a half-space comes back or is absorbed, so with a smooth face the
 * reflectance of each incidence bin plus its specular albedo plus the absorbed fraction is 1. A rough
 * face's single-scattering microfacets lose what their masking stops (as the path tracer's do): less
 * than 1. (A little absorption keeps the walks short.) */
TEST(half_space_keeps_energy)
{
    lucent_material m = grey(0.01, 1, 1.4);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_boundary_result *smooth = run(&m, 0, 0, 300, pool), *rough = run(&m, 0.5, 0, 300, pool);
    for (int i = 2; smooth && rough && i < N; i += 7) {
        /* the sum's standard error is at most the sum of its terms' (they correlate) */
        double es = smooth->reflect_total_se[0][i] + smooth->specular_se[0][i] + smooth->absorbed_se[0][i];
        double er = rough->reflect_total_se[0][i] + rough->specular_se[0][i] + rough->absorbed_se[0][i];
        double s = smooth->reflect_total[0][i] + smooth->specular[0][i] + smooth->absorbed[0][i];
        double r = rough->reflect_total[0][i] + rough->specular[0][i] + rough->absorbed[0][i];
        printf("     incidence cosine %.2f: smooth %.4f +- %.4f, rough (0.5) %.4f +- %.4f\n",
               lucent_boundary_bin_cosine(i), s, es, r, er);
        CHECK_MSG(fabs(s - 1) <= 3 * es, "smooth: %.4f", s);
        CHECK_MSG(r < 1 - 3 * er, "rough: %.4f", r);
    }
    free(smooth), free(rough);
    lucent_pool_destroy(pool);
}

/* A matched (eta 1), non-scattering slab: light at cosine mu leaves the far face unscattered, in its
 * own direction, with probability exp(-sigma_a s / mu) (Beer-Lambert), nothing reflected. Per
 * incidence bin the cosine-weighted mean of that over the bin (the light is drawn so within it), by
 * quadrature, within 3 binomial standard errors of the photon count; all of it within the incidence
 * bin and its neighbours (the exit kernel resolves an angle to 0.35 degrees inside) and of order 0. */
TEST(matched_slab_follows_beer_lambert)
{
    enum { PHOTONS = 2000 };
    lucent_material m = grey(0.5, 0, 1.0);
    lucent_boundary_result *r = run(&m, 0, 1.0, PHOTONS, NULL);
    for (int i = 0; r && i < N; i++) {
        double lo = (double)i / N, hi = (i + 1.0) / N, expect = 0;
        enum { Q = 200 };
        for (int k = 0; k < Q; k++) { /* uniform in mu^2 */
            double mu = sqrt(lo * lo + (k + 0.5) / Q * (hi * hi - lo * lo));
            expect += exp(-0.5 / mu) / Q;
        }
        double t = r->transmit_total[0][i], near = 0, order0 = 0, tol = 3 * sqrt(expect * (1 - expect) / PHOTONS);
        for (int o = i - 1; o <= i + 1; o++)
            if (o >= 0 && o < N) near += r->transmit[0][i][o] * bin_weight(o);
        for (int o = 0; o < N; o++) order0 += r->transmit_order[0][0][i][o] * bin_weight(o);
        CHECK_MSG(fabs(t - expect) <= tol + 1e-12, "bin %d: %g vs %g (tolerance %g)", i, t, expect, tol);
        CHECK_MSG(fabs(near - t) <= 1e-9 * (1 + t) && fabs(order0 - t) <= 1e-9 * (1 + t), "bin %d: %g, %g of %g", i,
                  near, order0, t);
        CHECK(r->reflect_total[0][i] == 0 && r->specular[0][i] == 0);
    }
    free(r);
}

/* Helmholtz reciprocity: light and viewer both outside, f(mu_i, mu_o) = f(mu_o, mu_i) (the boundary's
 * BSDF keeps the generalised reciprocity of Walter et al. 2007). The table and its transpose are
 * independent estimates; their differences over the combined standard error have mean square about
 * 1 (with 8 batches the error estimates spread, so the bound is 2). */
TEST(rough_half_space_is_reciprocal)
{
    lucent_material m;
    CHECK_OK(lucent_material_preset_find("skin1", &m));
    lucent_pool *pool = lucent_pool_create(2);
    lucent_boundary_result *r = run(&m, 0.3, 0, 1500, pool);
    for (int c = 0; r && c < 3; c++) {
        double chi2 = 0, worst = 0;
        int n = 0;
        for (int i = 0; i < N; i++)
            for (int o = i + 1; o < N; o++) {
                double z = (r->reflect[c][i][o] - r->reflect[c][o][i]) /
                           sqrt(pow(r->reflect_se[c][i][o], 2) + pow(r->reflect_se[c][o][i], 2));
                chi2 += z * z, n++, worst = fmax(worst, fabs(z));
            }
        printf("     channel %d: mean square of (f - f^T) / se %.2f over %d pairs, largest |z| %.1f\n", c, chi2 / n, n,
               worst);
        CHECK_MSG(chi2 / n < 2, "channel %d: %.2f", c, chi2 / n);
    }
    free(r);
    lucent_pool_destroy(pool);
}

/* The bake part: the albedo is the hemispherical albedo of the table, the exit curve integrates to 1,
 * every column of the entry factor too, and albedo x A x E gives the table back (its symmetric
 * estimate); baked again from the cache bit for bit; another roughness is another bake. */
TEST(bake_part_factors_the_table)
{
    lucent_material m;
    CHECK_OK(lucent_material_preset_find("skin1", &m));
    lucent_pool *pool = lucent_pool_create(2);
    lucent_cache *cache = NULL;
    CHECK_OK(lucent_cache_create(test_path("cache/boundary"), &cache));
    lucent_bake_desc d = {.what = LUCENT_BAKE_BOUNDARY, .roughness = 0.3, .boundary_photons = 300, .pool = pool};
    lucent_baked a = {0}, b = {0};
    CHECK_OK(lucent_material_bake(&m, &d, cache, &a));
    CHECK(a.have == LUCENT_BAKE_BOUNDARY && !a.boundary_cached && a.boundary_roughness == 0.3);
    for (int c = 0; c < 3; c++) {
        double e = 0;
        for (int o = 0; o < N; o++) e += a.boundary[(N * N + o) * 3 + c] * bin_weight(o);
        CHECK_NEAR(e, 1, 1e-5);
        for (int o = 0; o < N; o += 5) {
            double s = 0;
            for (int i = 0; i < N; i++) s += a.boundary[(i * N + o) * 3 + c] * bin_weight(i);
            CHECK_NEAR(s, 1, 1e-5);
        }
        CHECK(a.boundary_albedo[c] > 0.05 && a.boundary_albedo[c] < 0.5);
    }
    CHECK(a.boundary_albedo[0] > a.boundary_albedo[1] && a.boundary_albedo[1] > a.boundary_albedo[2]); /* skin */
    CHECK_OK(lucent_material_bake(&m, &d, cache, &b));
    CHECK(b.boundary_cached && !memcmp(a.boundary, b.boundary, sizeof a.boundary));
    d.roughness = 0.1;
    CHECK_OK(lucent_material_bake(&m, &d, cache, &b));
    CHECK(!b.boundary_cached && b.boundary_roughness == 0.1 && memcmp(a.boundary, b.boundary, sizeof a.boundary));
    d.roughness = 2;
    CHECK_ERR(lucent_material_bake(&m, &d, cache, &b), LUCENT_ERR_INVALID_ARGUMENT, "Skin1", "roughness");
    lucent_baked_free(&a), lucent_baked_free(&b);
    lucent_cache_destroy(cache);
    lucent_pool_destroy(pool);
}

TEST(bad_input_is_named)
{
    lucent_material m = grey(0.1, 1, 1.4);
    lucent_boundary_result *r = malloc(sizeof *r);
    CHECK_ERR(lucent_boundary_run(&(lucent_boundary_desc){.material = &m, .roughness = 1.5}, r),
              LUCENT_ERR_INVALID_ARGUMENT, "grey", "roughness");
    CHECK_ERR(lucent_boundary_run(&(lucent_boundary_desc){.material = &m, .thickness = -1}, r),
              LUCENT_ERR_INVALID_ARGUMENT, "grey", "thickness");
    CHECK_ERR(lucent_boundary_run(&(lucent_boundary_desc){.material = NULL}, r), LUCENT_ERR_INVALID_ARGUMENT,
              "no material");
    free(r);
}

TEST_MAIN(TEST_ENTRY(smooth_half_space_matches_giovanelli), TEST_ENTRY(half_space_keeps_energy),
          TEST_ENTRY(matched_slab_follows_beer_lambert), TEST_ENTRY(rough_half_space_is_reciprocal),
          TEST_ENTRY(bake_part_factors_the_table), TEST_ENTRY(bad_input_is_named))
