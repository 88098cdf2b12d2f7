/* Tests of the bake room (lucent/bake.h): each part equals what its module builds on its own (an
 * independent call of the same public functions), parts are rebuilt exactly when a setting they
 * depend on changes and only then, the disk cache gives back what was written bit for bit, and the
 * transmittance tables keep their physical shape (T(0) normalised to 1 for the profile model,
 * monotone in thickness). d'Eon & Luebke's skin table sums to 1 per channel (GPU Gems 3, ch. 14:
 * the profile is normalised to unit total diffuse reflectance). The rd part against Giovanelli's
 * half-space table. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/bake.h"
#include "lucent/cdrf.h"
#include "test.h"

static lucent_material skin(void)
{
    lucent_material m;
    lucent_material_preset_find("skin1", &m);
    return m;
}

TEST(parts_equal_their_modules_and_rebuild_only_when_needed)
{
    lucent_material m = skin();
    lucent_render_settings s = lucent_render_settings_defaults();
    lucent_baked b = {0};
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TAPS, .settings = &s}, NULL, &b));
    CHECK(b.have == (LUCENT_BAKE_TAPS | LUCENT_BAKE_PROFILE) && !strcmp(b.taps_key, "dipole/preint/1/17"));
    /* the same profile and taps built directly */
    lucent_profile *p = NULL;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    lucent_taps *t = NULL;
    CHECK_OK(lucent_profile_from_source(&(lucent_profile_source_desc){.source = "dipole"}, &m, &p));
    CHECK_OK(lucent_kernel2d_from_profile(p, NULL, &gt));
    lucent_kernel_desc kd = lucent_kernel_defaults(LUCENT_KERNEL_PREINT);
    CHECK_OK(lucent_kernel_build(gt, p, m.name, &kd, &k));
    CHECK_OK(lucent_kernel_taps(k, &(lucent_taps_desc){.count = 17}, &t));
    CHECK(p && b.profile && p->count == b.profile->count && !memcmp(p->value[0], b.profile->value[0], p->count * 8));
    CHECK(t && b.taps && t->count == b.taps->count && !memcmp(t->weight[1], b.taps->weight[1], 17 * 8) &&
          !memcmp(t->offset, b.taps->offset, 17 * 8));
    lucent_taps_destroy(t), lucent_kernel_destroy(k), lucent_kernel2d_destroy(gt), lucent_profile_destroy(p);
    /* the same settings: nothing rebuilt; more taps: new taps, same profile */
    const lucent_profile *prof = b.profile;
    const lucent_taps *taps = b.taps;
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TAPS, .settings = &s}, NULL, &b));
    CHECK(b.profile == prof && b.taps == taps);
    s.ssss.taps = 25;
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TAPS, .settings = &s}, NULL, &b));
    CHECK(b.profile == prof && b.taps && b.taps->count == 25);
    /* another profile: both rebuilt */
    snprintf(s.ssss.profile, sizeof s.ssss.profile, "burley");
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TAPS, .settings = &s}, NULL, &b));
    CHECK(!strcmp(b.profile_key, "burley") && !strncmp(b.taps_key, "burley/", 7));
    lucent_baked_free(&b);
    CHECK(b.have == 0 && !b.profile && !b.taps);
}

TEST(profile_transmittance_is_normalised_and_falls)
{
    lucent_material m = skin();
    lucent_render_settings s = lucent_render_settings_defaults();
    s.translucency.transmittance = LUCENT_TRANSMIT_PROFILE;
    lucent_baked b = {0};
    CHECK_OK(
        lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TRANSMITTANCE, .settings = &s}, NULL, &b));
    CHECK(b.have & LUCENT_BAKE_PROFILE); /* the profile model needs the profile */
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(b.transmittance[c], 1, 1e-6); /* T(0) / T(0) */
        CHECK(b.transmittance[3 * (LUCENT_BAKE_TRANSMIT_SIZE - 1) + c] == 0);
        for (int j = 1; j < LUCENT_BAKE_TRANSMIT_SIZE; j++)
            CHECK(b.transmittance[3 * j + c] <= b.transmittance[3 * (j - 1) + c]);
    }
    CHECK_NEAR(b.transmit_range, b.profile->count * b.profile->dr, 1e-12);
    lucent_baked_free(&b);
}

TEST(monte_carlo_parts_come_back_from_the_cache_bit_for_bit)
{
    lucent_material m = skin();
    lucent_render_settings s = lucent_render_settings_defaults();
    lucent_cache *cache = NULL;
    CHECK_OK(lucent_cache_create(test_path("cache/deeper"), &cache));
    lucent_bake_desc d = {.what = LUCENT_BAKE_TRANSMITTANCE | LUCENT_BAKE_SIGMA0,
                          .settings = &s,
                          .transmit_photons = 2000,
                          .sigma0_photons = 2000};
    lucent_baked first = {0}, second = {0};
    CHECK_OK(lucent_material_bake(&m, &d, cache, &first));
    CHECK(!first.sigma0_cached && !(first.have & LUCENT_BAKE_PROFILE)); /* the slab needs no profile */
    CHECK_OK(lucent_material_bake(&m, &d, cache, &second));
    CHECK(second.sigma0_cached);
    CHECK(!memcmp(first.sigma0, second.sigma0, sizeof first.sigma0));
    CHECK(!memcmp(first.transmittance, second.transmittance, sizeof first.transmittance));
    CHECK(first.transmit_range == second.transmit_range);
    /* the sigma0 part is the material's fit with the stated radii, bins and photons */
    lucent_cdrf_fit fit;
    CHECK_OK(lucent_cdrf_fit_material(
        &(lucent_cdrf_material_fit_desc){.material = &m, .photons = 2000, .bins = LUCENT_BAKE_SIGMA0_BINS, .seed = 1},
        &fit, NULL));
    CHECK(!memcmp(fit.sigma0, first.sigma0, sizeof fit.sigma0));
    /* another photon count misses the cache */
    lucent_baked third = {0};
    d.sigma0_photons = 2001;
    CHECK_OK(lucent_material_bake(&m, &d, cache, &third));
    CHECK(!third.sigma0_cached);
    lucent_baked_free(&first), lucent_baked_free(&second), lucent_baked_free(&third);
    lucent_cache_destroy(cache);
}

/* The rd part (the real-time methods' albedo) is the total diffuse reflectance of the half-space:
 * Giovanelli 1955's n 1.5, g 0, albedo 0.9 gives Rsp + Rd 0.2600 (4 digits: +- 0.00005) with
 * Rsp = ((1.5 - 1) / (1.5 + 1))^2 = 0.04, so Rd = 0.2200. The three channels, here one medium, are
 * three independent runs (seeds 4, 5, 6); their mean is within 3 of its standard errors. A second bake
 * reads it back from the cache bit for bit. */
TEST(rd_is_the_half_space_total_diffuse_reflectance)
{
    lucent_material m = skin();
    snprintf(m.name, sizeof m.name, "giovanelli");
    m.eta = 1.5;
    for (int c = 0; c < 3; c++) m.sigma_a[c] = 0.1, m.sigma_s[c] = 0.9, m.g[c] = 0.0;
    lucent_pool *pool = lucent_pool_create(2);
    lucent_cache *cache = NULL;
    CHECK_OK(lucent_cache_create(test_path("cache/rd"), &cache));
    lucent_bake_desc d = {.what = LUCENT_BAKE_RD, .pool = pool};
    lucent_baked first = {0}, second = {0};
    CHECK_OK(lucent_material_bake(&m, &d, cache, &first));
    CHECK(first.have == LUCENT_BAKE_RD && !first.rd_cached);
    double mean = 0, var = 0;
    for (int c = 0; c < 3; c++) {
        CHECK(first.rd_se[c] > 0 && first.rd_se[c] < 0.001); /* the test means something */
        mean += first.rd[c] / 3, var += first.rd_se[c] * first.rd_se[c] / 9;
        printf("  Giovanelli half-space, channel %d: Rd %.5f +- %.5f (0.2200)\n", c, first.rd[c], first.rd_se[c]);
    }
    CHECK(fabs(mean - 0.2200) <= 3 * sqrt(var) + 0.00005);
    printf("  the three channels pooled: Rd %.5f +- %.5f (0.2200)\n", mean, sqrt(var));
    CHECK_OK(lucent_material_bake(&m, &d, cache, &second));
    CHECK(second.rd_cached && !memcmp(first.rd, second.rd, sizeof first.rd) &&
          !memcmp(first.rd_se, second.rd_se, sizeof first.rd_se));
    /* another SIMD path has numbers of its own: it does not read this path's entry (docs/mcml.md) */
    lucent_isa was = lucent_isa_active(), other = was == LUCENT_ISA_SCALAR ? LUCENT_ISA_AVX2 : LUCENT_ISA_SCALAR;
    if (lucent_isa_supported(other)) {
        lucent_baked third = {0};
        CHECK_OK(lucent_isa_set(other));
        CHECK_OK(lucent_material_bake(&m, &d, cache, &third));
        CHECK(!third.rd_cached && memcmp(first.rd, third.rd, sizeof first.rd));
        lucent_baked_free(&third);
        CHECK_OK(lucent_isa_set(was));
    }
    lucent_baked_free(&first), lucent_baked_free(&second);
    lucent_cache_destroy(cache);
    lucent_pool_destroy(pool);
}

TEST(sums_of_gaussians)
{
    lucent_sog skin_table;
    lucent_sog_deon_skin(&skin_table);
    for (int c = 0; c < 3; c++) {
        double w = 0;
        for (int i = 0; i < skin_table.count; i++) w += skin_table.weight[c][i];
        CHECK_NEAR(w, 1, 1e-9);
        CHECK(skin_table.variance[c][0] == 0.0064 && skin_table.variance[c][5] == 7.41);
    }
    lucent_material m = skin();
    lucent_baked b = {0};
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_SOG, .sog_count = 4}, NULL, &b));
    CHECK(b.sog.count == 4);
    for (int i = 0; i < 4; i++) CHECK(b.sog.variance[0][i] == b.sog.variance[2][i]); /* shared variances */
    for (int c = 0; c < 3; c++) {
        double w = 0; /* each Gaussian integrates to 1: the weights sum to the fit's total */
        for (int i = 0; i < 4; i++) w += b.sog.weight[c][i];
        CHECK_NEAR(w / lucent_profile_total(b.profile, c), 1, 0.05);
    }
    CHECK_ERR(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_SOG, .sog_count = 17}, NULL, &b),
              LUCENT_ERR_INVALID_ARGUMENT, "Skin1", "1 to 16");
    lucent_baked_free(&b);
}

/* A copy holds the same parts bit for bit, stands alone (the original freed), and a bake started from
 * it rebuilds only what changed. */
TEST(copies_stand_alone)
{
    lucent_material m = skin();
    lucent_render_settings s = lucent_render_settings_defaults();
    lucent_baked b = {0}, c = {0};
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TAPS, .settings = &s}, NULL, &b));
    lucent_baked keep = b; /* the original's scalars and keys (its pointers are not read after the free) */
    size_t bins = (size_t)b.profile->count, taps = (size_t)b.taps->count * (size_t)b.taps->rank;
    double *value = malloc(bins * sizeof *value), *weight = malloc(taps * sizeof *weight);
    memcpy(value, b.profile->value[2], bins * sizeof *value);
    memcpy(weight, b.taps->weight[0], taps * sizeof *weight);
    double sign = b.taps->sign[0][0];
    CHECK_OK(lucent_baked_copy(&b, &c));
    CHECK(c.profile != b.profile && c.taps != b.taps);
    lucent_baked_free(&b);
    CHECK(c.have == keep.have && !strcmp(c.taps_key, keep.taps_key) && !strcmp(c.profile_key, keep.profile_key));
    CHECK(c.profile->count == (int)bins && !memcmp(c.profile->value[2], value, bins * sizeof *value));
    CHECK(!memcmp(c.taps->weight[0], weight, taps * sizeof *weight) && c.taps->sign[0][0] == sign);
    const lucent_profile *p = c.profile;
    s.ssss.taps = 9;
    CHECK_OK(lucent_material_bake(&m, &(lucent_bake_desc){.what = LUCENT_BAKE_TAPS, .settings = &s}, NULL, &c));
    CHECK(c.profile == p && c.taps->count == 9); /* the profile kept, the taps rebuilt */
    lucent_baked_free(&c);
    free(value), free(weight);
}

TEST_MAIN(TEST_ENTRY(parts_equal_their_modules_and_rebuild_only_when_needed), TEST_ENTRY(copies_stand_alone),
          TEST_ENTRY(profile_transmittance_is_normalised_and_falls),
          TEST_ENTRY(monte_carlo_parts_come_back_from_the_cache_bit_for_bit), TEST_ENTRY(sums_of_gaussians),
          TEST_ENTRY(rd_is_the_half_space_total_diffuse_reflectance))
