/* The Monte Carlo's SIMD paths (src/profile/mc_lanes.h, mc_avx2.c, mc_avx512.c) against independent
 * references:
 *   - their approximations against libm in double, over every input they are given: -ln(m 2^-24)
 *     for all 2^24 values of m, cos and sin of the azimuth for all 2^20 values of its bits,
 *     Henyey-Greenstein's cos theta (MCML manual eq. 3.28, in double) for 2^20 values of xi at 19
 *     values of g;
 *   - the scalar kernel (mc_transport.c, the reference, itself held to van de Hulst, Giovanelli and
 *     MCML by test_mc and test_mcml_layers): the same physics with other random numbers, so every
 *     total within 4 combined standard errors and every profile's chi^2 over its bins within
 *     n + 5 sqrt(2 n) (about 5 standard deviations of chi^2: a chance failure is below 1e-5 per
 *     check), on media that take every branch of the lanes (one layer and several, g = 0, g > 0,
 *     g < 0, mismatched indices with total internal reflection, a clear layer, more layers than
 *     lanes, A(r, z));
 *   - each path is the one asked for (its results differ from the scalar kernel's bit for bit).
 * Runs once (the plain CTest entry), whatever LUCENT_ISA says: it chooses the paths itself. A path
 * this CPU lacks is reported and left out. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mc.h"
#include "profile/mc_internal.h"
#include "test.h"

#if defined(__SANITIZE_ADDRESS__)
#define SLOW 8 /* sanitizer builds run about ten times slower: an eighth of the photons */
#else
#define SLOW 1
#endif

/* The SIMD kernels this CPU runs (NULL-terminated). */
static int simd_kernels(const mc_kernel *dest[LUCENT_ISA_COUNT])
{
    int n = 0;
    for (int i = LUCENT_ISA_AVX2; i < LUCENT_ISA_COUNT; i++) {
        const mc_kernel *k = mc_kernel_get((lucent_isa)i);
        if (k) {
            CHECK(k->isa == (lucent_isa)i && k->lanes > 1);
            dest[n++] = k;
        } else {
            printf("  %s: this CPU has no such path (left out)\n", lucent_isa_name((lucent_isa)i));
        }
    }
    dest[n] = NULL;
    return n;
}

#define BLOCK (1 << 16)

/* -ln(m 2^-24) for every m in [1, 2^24]: relative error below 3.5e-7 (the polynomial's own 3.1e-7 at
 * the ends of its interval; 0 exactly at m = 2^24). */
TEST(neglog_against_libm)
{
    const mc_kernel *ks[LUCENT_ISA_COUNT];
    simd_kernels(ks);
    uint32_t *m = malloc(BLOCK * sizeof *m);
    float *v = malloc(BLOCK * sizeof *v);
    for (int j = 0; ks[j]; j++) {
        double worst = 0;
        uint32_t at = 0;
        for (uint32_t base = 1; base <= (1u << 24); base += BLOCK) {
            for (uint32_t i = 0; i < BLOCK; i++) m[i] = base + i <= (1u << 24) ? base + i : 1u << 24;
            ks[j]->neglog(m, v, BLOCK);
            for (uint32_t i = 0; i < BLOCK; i++) {
                double ref = -log((double)m[i] * 0x1p-24);
                double e = ref > 0 ? fabs(v[i] - ref) / ref : fabs((double)v[i]);
                if (e > worst) worst = e, at = m[i];
            }
        }
        printf("  %s: -ln(m 2^-24): largest relative error %.3g (m = %u)\n", lucent_isa_name(ks[j]->isa), worst, at);
        CHECK(worst < 3.5e-7);
    }
    free(m);
    free(v);
}

/* cos and sin of phi = q pi/2 + t, t = ((b & 0x3FFFF) + 1/2) pi / 2^19 - pi/4, q = b >> 18, for every
 * 20-bit b: absolute error below 1.5e-7 (the polynomials' 3e-8 and float rounding). */
TEST(sincos_against_libm)
{
    const mc_kernel *ks[LUCENT_ISA_COUNT];
    simd_kernels(ks);
    uint32_t n = 1u << 20;
    uint32_t *b = malloc(n * sizeof *b);
    float *c = malloc(n * sizeof *c), *s = malloc(n * sizeof *s);
    for (uint32_t i = 0; i < n; i++) b[i] = i;
    for (int j = 0; ks[j]; j++) {
        ks[j]->sincos(b, c, s, n);
        double worst = 0, norm = 0;
        for (uint32_t i = 0; i < n; i++) {
            double phi = (i >> 18) * M_PI / 2 + ((i & 0x3FFFF) + 0.5) * M_PI / 524288.0 - M_PI / 4;
            worst = fmax(worst, fmax(fabs(c[i] - cos(phi)), fabs(s[i] - sin(phi))));
            norm = fmax(norm, fabs((double)c[i] * c[i] + (double)s[i] * s[i] - 1.0));
        }
        printf("  %s: cos, sin of the azimuth: largest error %.3g, largest |c^2 + s^2 - 1| %.3g\n",
               lucent_isa_name(ks[j]->isa), worst, norm);
        CHECK(worst < 1.5e-7);
    }
    free(b);
    free(c);
    free(s);
}

/* Henyey-Greenstein's cos theta against the inversion in double (MCML manual eq. 3.28), for xi at the
 * midpoints of 2^20 bins (the lanes' 20-bit xi): absolute error below 4e-7 for every g. */
TEST(hg_against_double)
{
    const mc_kernel *ks[LUCENT_ISA_COUNT];
    simd_kernels(ks);
    static const double gs[] = {0,     1e-6, -1e-4, 1e-3, -0.01, 0.05,  0.3,    -0.5, 0.7, 0.8,
                                -0.85, 0.9,  0.95,  0.99, -0.99, 0.999, 0.9999, 1.0,  -1.0};
    uint32_t n = 1u << 20;
    float *xi = malloc(n * sizeof *xi), *mu = malloc(n * sizeof *mu);
    for (uint32_t i = 0; i < n; i++) xi[i] = ((float)i + 0.5f) * 0x1p-20f;
    for (int j = 0; ks[j]; j++) {
        double worst = 0, worst_g = 0;
        for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
            double g = gs[k];
            ks[j]->hg(g, xi, mu, n);
            for (uint32_t i = 0; i < n; i++) {
                double u = xi[i], ref;
                if (g == 0)
                    ref = 2 * u - 1;
                else if (fabs(g) == 1)
                    ref = g;
                else {
                    double q = (1 - g * g) / (1 - g + 2 * g * u);
                    ref = (1 + g * g - q * q) / (2 * g);
                }
                ref = fmin(1, fmax(-1, ref));
                double e = fabs(mu[i] - ref);
                if (e > worst) worst = e, worst_g = g;
            }
        }
        printf("  %s: HG cos theta: largest error %.3g (g = %g)\n", lucent_isa_name(ks[j]->isa), worst, worst_g);
        CHECK(worst < 4e-7);
    }
    free(xi);
    free(mu);
}

/* a - b in combined standard errors. */
static double z_of(double a, double sa, double b, double sb)
{
    double c = sqrt(sa * sa + sb * sb);
    return c > 0 ? (a - b) / c : (a == b ? 0 : INFINITY);
}

static void check_total(const char *what, const char *isa, const char *name, double a, double sa, double b, double sb)
{
    double z = z_of(a, sa, b, sb);
    CHECK_MSG(fabs(z) <= 4.0, "%s, %s: %s %.6f +- %.6f, scalar %.6f +- %.6f: %.1f combined SE", what, isa, name, a, sa,
              b, sb, z);
}

/* chi^2 of a profile's bins where both sides measured something (relative errors below 0.3) */
static void check_profile(const char *what, const char *isa, const char *name, const double *a, const double *sa,
                          const double *b, const double *sb, int n)
{
    double chi2 = 0;
    int used = 0;
    for (int i = 0; i < n; i++) {
        if (!(a[i] > 0 && b[i] > 0 && sa[i] < 0.3 * a[i] && sb[i] < 0.3 * b[i])) continue;
        double z = z_of(a[i], sa[i], b[i], sb[i]);
        chi2 += z * z;
        used++;
    }
    if (!used) return;
    double limit = used + 5.0 * sqrt(2.0 * used);
    CHECK_MSG(chi2 <= limit, "%s, %s: %s: chi^2 %.1f over %d bins, above %.1f", what, isa, name, chi2, used, limit);
}

/* Runs d on the scalar kernel and on every SIMD path and compares. */
static void agree(const char *what, lucent_mc_desc d)
{
    const mc_kernel *ks[LUCENT_ISA_COUNT];
    simd_kernels(ks);
    lucent_isa was = lucent_isa_active();
    lucent_pool *pool = lucent_pool_create(2);
    d.pool = pool;
    d.photons /= SLOW;
    lucent_mc_result ref, r;
    CHECK_OK(lucent_isa_set(LUCENT_ISA_SCALAR));
    CHECK_OK(lucent_mc_run(&d, &ref));
    for (int j = 0; ks[j]; j++) {
        const char *isa = lucent_isa_name(ks[j]->isa);
        CHECK_OK(lucent_isa_set(ks[j]->isa));
        CHECK_OK(lucent_mc_run(&d, &r));
        CHECK_MSG(r.rd != ref.rd || r.a != ref.a, "%s, %s: the same numbers as the scalar kernel", what, isa);
        check_total(what, isa, "Rd", r.rd, r.rd_se, ref.rd, ref.rd_se);
        check_total(what, isa, "A", r.a, r.a_se, ref.a, ref.a_se);
        check_total(what, isa, "Tt", r.tt, r.tt_se, ref.tt, ref.tt_se);
        for (int l = 0; l < r.layer_count; l++)
            check_total(what, isa, "A in a layer", r.a_layer[l], r.a_layer_se[l], ref.a_layer[l], ref.a_layer_se[l]);
        check_profile(what, isa, "Rd(r)", r.rd_r, r.rd_r_se, ref.rd_r, ref.rd_r_se, r.grid.nr);
        check_profile(what, isa, "Tt(r)", r.tt_r, r.tt_r_se, ref.tt_r, ref.tt_r_se, r.grid.nr);
        check_profile(what, isa, "Rd(angle)", r.rd_a, r.rd_a_se, ref.rd_a, ref.rd_a_se, r.grid.na);
        check_profile(what, isa, "Tt(angle)", r.tt_a, r.tt_a_se, ref.tt_a, ref.tt_a_se, r.grid.na);
        check_profile(what, isa, "A(z)", r.a_z, r.a_z_se, ref.a_z, ref.a_z_se, r.grid.nz);
        CHECK_MSG(fabs(r.balance - 1.0) <= 3.0 * r.balance_se + 1e-6, "%s, %s: Rsp + Rd + A + Tt = %.9f +- %.9f", what,
                  isa, r.balance, r.balance_se);
        printf("  %s, %s: Rd %.5f +- %.5f (scalar %.5f +- %.5f), A %.5f, Tt %.5f\n", what, isa, r.rd, r.rd_se, ref.rd,
               ref.rd_se, r.a, r.tt);
        lucent_mc_result_free(&r);
    }
    lucent_mc_result_free(&ref);
    lucent_pool_destroy(pool);
    CHECK_OK(lucent_isa_set(was));
}

TEST(agree_van_de_hulst_slab) /* one layer, g > 0, matched */
{
    lucent_mc_layer l = {1.0, 1.0, 9.0, 0.75, 0.2};
    agree("van de Hulst's slab", (lucent_mc_desc){.layers = &l,
                                                  .layer_count = 1,
                                                  .photons = 400000,
                                                  .seed = 21,
                                                  .grid = {.dr = 0.01, .dz = 0.01, .nr = 50, .nz = 20, .na = 10}});
}

TEST(agree_isotropic_half_space) /* g = 0: the lanes' direct isotropic direction; n 1.5: TIR */
{
    lucent_mc_layer l = {1.5, 0.1, 0.9, 0.0, INFINITY};
    agree("Giovanelli's half-space",
          (lucent_mc_desc){.layers = &l, .layer_count = 1, .photons = 200000, .seed = 22, .score_a_rz = true});
}

TEST(agree_backward_scattering_slab) /* g < 0, a slab with a mismatched index below */
{
    lucent_mc_layer l = {1.3, 0.2, 5.0, -0.7, 0.6};
    agree("a backward-scattering slab", (lucent_mc_desc){.layers = &l,
                                                         .layer_count = 1,
                                                         .n_below = 1.5,
                                                         .photons = 200000,
                                                         .seed = 23,
                                                         .grid = {.dr = 0.02, .dz = 0.02, .nr = 60, .nz = 30}});
}

TEST(agree_three_layers) /* refraction between layers, TIR, A(r, z), the last bin collecting */
{
    static const lucent_mc_layer l[] = {
        {1.37, 0.1, 10.0, 0.9, 0.1}, {1.45, 0.05, 5.0, 0.5, 0.2}, {1.4, 0.02, 2.0, 0.0, 0.5}};
    agree("three layers", (lucent_mc_desc){.layers = l,
                                           .layer_count = 3,
                                           .photons = 200000,
                                           .seed = 24,
                                           .score_a_rz = true,
                                           .last_bin_collects = true,
                                           .grid = {.dr = 0.02, .dz = 0.01, .nr = 50, .nz = 80}});
}

TEST(agree_glass_over_tissue) /* a clear layer (per lane, in scalar code) over a turbid one */
{
    static const lucent_mc_layer l[] = {{1.5, 0, 0, 0, 0.1}, {1.33, 0.1, 10.0, 0.8, 1.0}};
    agree("glass over tissue", (lucent_mc_desc){.layers = l, .layer_count = 2, .photons = 100000, .seed = 25});
}

TEST(agree_more_layers_than_lanes) /* 20 layers: the lanes gather their layers' constants */
{
    lucent_mc_layer l[20];
    for (int i = 0; i < 20; i++)
        l[i] = (lucent_mc_layer){1.3 + 0.01 * (i % 4), 0.05 + 0.01 * (i % 3), 8.0 - 0.2 * i, 0.9 - 0.04 * i,
                                 i == 19 ? INFINITY : 0.05};
    agree("20 layers", (lucent_mc_desc){.layers = l,
                                        .layer_count = 20,
                                        .photons = 100000,
                                        .seed = 26,
                                        .grid = {.dr = 0.05, .dz = 0.05, .nr = 40, .nz = 40}});
}

TEST_MAIN(TEST_ENTRY(neglog_against_libm), TEST_ENTRY(sincos_against_libm), TEST_ENTRY(hg_against_double),
          TEST_ENTRY(agree_van_de_hulst_slab), TEST_ENTRY(agree_isotropic_half_space),
          TEST_ENTRY(agree_backward_scattering_slab), TEST_ENTRY(agree_three_layers),
          TEST_ENTRY(agree_glass_over_tissue), TEST_ENTRY(agree_more_layers_than_lanes))
