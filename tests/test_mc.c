/* Tests of the Monte Carlo transport (src/profile/mc*.c) and MCML files (src/profile/mcml.c).
 * Statistical tests compare with published values within 3 standard errors:
 *   van de Hulst's slab (albedo 0.9, g 0.75, optical thickness 2, matched index):
 *     Rd 0.09739, Tt 0.66096 (van de Hulst 1980, as tabulated in the MCML manual, Table 4.1);
 *   Giovanelli's half-space (n 1.5, g 0, albedo 0.9): Rsp + Rd 0.2600 (Giovanelli 1955). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/material.h"
#include "lucent/mc.h"
#include "test.h"

#define FIXTURES LUCENT_SOURCE_DIR "/tests/fixtures/mcml"

/* 3 standard errors, with the statistical error of the expected value's rounding negligible. */
#define CHECK_3SE(value, se, expected)                                                                                 \
    do {                                                                                                               \
        CHECK_MSG(fabs((value) - (expected)) <= 3.0 * (se) && (se) > 0.0,                                              \
                  "%s = %.5f +- %.5f, expected %.5f (%.1f standard errors)", #value, (value), (se), (expected),        \
                  fabs((value) - (expected)) / (se));                                                                  \
    } while (0)

/* Energy balance: within 3 standard errors, plus 1e-6 for float rounding of the packet weight
 * (without roulette the balance is exact in exact arithmetic and its standard error is ~0). */
#define CHECK_BALANCE(r)                                                                                               \
    CHECK_MSG(fabs((r).balance - 1.0) <= 3.0 * (r).balance_se + 1e-6, "Rsp + Rd + A + Tt = %.9f +- %.9f, expected 1",  \
              (r).balance, (r).balance_se)

/* mm: mu_a 1, mu_s 9 mm^-1, d 0.2 mm is the same slab as 10, 90 cm^-1, 0.02 cm. */
static const lucent_mc_layer k_vanhulst = {1.0, 1.0, 9.0, 0.75, 0.2};

TEST(vanhulst_slab)
{
    lucent_pool *pool = lucent_pool_create(2);
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = &k_vanhulst,
                                             .layer_count = 1,
                                             .photons = 200000,
                                             .seed = 7,
                                             .pool = pool,
                                             .grid = {.dr = 0.01, .dz = 0.01, .nr = 50, .nz = 20}},
                           &r));
    CHECK_NEAR(r.rsp, 0.0, 0.0);
    CHECK_3SE(r.rd, r.rd_se, 0.09739);
    CHECK_3SE(r.tt, r.tt_se, 0.66096);
    CHECK_BALANCE(r);
    CHECK(r.rd_se < 0.002 && r.tt_se < 0.002); /* the test means something */
    printf("  van de Hulst: Rd %.5f +- %.5f (0.09739), Tt %.5f +- %.5f (0.66096)\n", r.rd, r.rd_se, r.tt, r.tt_se);
    lucent_mc_result_free(&r);
    lucent_pool_destroy(pool);
}

TEST(giovanelli_half_space)
{
    lucent_pool *pool = lucent_pool_create(2);
    lucent_mc_layer half = {1.5, 0.1, 0.9, 0.0, INFINITY};
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(
        &(lucent_mc_desc){.layers = &half, .layer_count = 1, .photons = 100000, .seed = 11, .pool = pool}, &r));
    CHECK_NEAR(r.rsp, 0.04, 1e-12);
    CHECK_3SE(r.rsp + r.rd, r.rd_se, 0.2600);
    CHECK_BALANCE(r);
    CHECK(r.tt == 0.0);
    CHECK(r.rd_se < 0.002);
    printf("  Giovanelli: Rsp + Rd %.5f +- %.5f (0.2600), balance %.5f +- %.5f\n", r.rsp + r.rd, r.rd_se, r.balance,
           r.balance_se);
    lucent_mc_result_free(&r);
    lucent_pool_destroy(pool);
}

static bool same_result(const lucent_mc_result *a, const lucent_mc_result *b)
{
    size_t nr = (size_t)a->grid.nr, nz = (size_t)a->grid.nz, na = (size_t)a->grid.na;
#define SAME(f, n) (memcmp(a->f, b->f, (n) * sizeof(double)) == 0)
    return a->rd == b->rd && a->rd_se == b->rd_se && a->a == b->a && a->tt == b->tt && a->balance_se == b->balance_se &&
           SAME(rd_r, nr) && SAME(rd_r_se, nr) && SAME(tt_r, nr) && SAME(rd_a, na) && SAME(a_z, nz) &&
           SAME(a_z_se, nz) && SAME(rd_ra, nr * na) && SAME(tt_ra, nr * na) && SAME(a_rz, nr * nz) &&
           SAME(a_layer, (size_t)a->layer_count);
#undef SAME
}

/* Two layers of different index over a third: refraction, TIR, every score, A(r,z). */
static const lucent_mc_layer k_three[] = {
    {1.37, 0.1, 10.0, 0.9, 0.1}, {1.45, 0.05, 5.0, 0.5, 0.2}, {1.4, 0.02, 2.0, 0.0, 0.5}};

TEST(same_seed_same_result_for_any_thread_count)
{
    lucent_mc_result r[3];
    int threads[3] = {1, 2, 3};
    for (int i = 0; i < 3; i++) {
        lucent_pool *pool = lucent_pool_create(threads[i]);
        CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = k_three,
                                                 .layer_count = 3,
                                                 .photons = 20000,
                                                 .seed = 3,
                                                 .pool = pool,
                                                 .score_a_rz = true,
                                                 .grid = {.dr = 0.02, .nr = 40, .nz = 40}},
                               &r[i]));
        lucent_pool_destroy(pool);
    }
    CHECK(same_result(&r[0], &r[1]));
    CHECK(same_result(&r[0], &r[2]));
    CHECK_BALANCE(r[0]);
    lucent_mc_result other;
    CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = k_three,
                                             .layer_count = 3,
                                             .photons = 20000,
                                             .seed = 4,
                                             .score_a_rz = true,
                                             .grid = {.dr = 0.02, .nr = 40, .nz = 40}},
                           &other));
    CHECK(other.rd != r[0].rd); /* the seed matters */
    lucent_mc_result_free(&other);
    for (int i = 0; i < 3; i++) lucent_mc_result_free(&r[i]);
}

/* The profiles integrate to the totals: sum rd_r[i] * ring area = Rd (all on the grid). */
TEST(profiles_integrate_to_totals)
{
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = k_three,
                                             .layer_count = 3,
                                             .photons = 20000,
                                             .seed = 5,
                                             .score_a_rz = true,
                                             .last_bin_collects = true,
                                             .grid = {.dr = 0.05, .dz = 0.01, .nr = 50, .nz = 80}},
                           &r));
    double dr = 0.05, dz = 0.01, rd = 0, tt = 0, az = 0, arz = 0, ra = 0, a_l = 0;
    for (int i = 0; i < 50; i++) {
        double ring = 2 * M_PI * (i + 0.5) * dr * dr;
        rd += r.rd_r[i] * ring;
        tt += r.tt_r[i] * ring;
        for (int k = 0; k < 80; k++) arz += r.a_rz[i * 80 + k] * ring * dz;
        for (int j = 0; j < r.grid.na; j++) {
            double da = M_PI / (2 * r.grid.na);
            ra += r.rd_ra[i * r.grid.na + j] * ring * 4 * M_PI * sin((j + 0.5) * da) * sin(da / 2);
        }
    }
    for (int k = 0; k < 80; k++) az += r.a_z[k] * dz;
    for (int l = 0; l < 3; l++) a_l += r.a_layer[l];
    CHECK_NEAR(rd, r.rd, 1e-9);
    CHECK_NEAR(tt, r.tt, 1e-9);
    CHECK_NEAR(ra, r.rd, 1e-9);
    CHECK_NEAR(az, r.a, 1e-9);
    CHECK_NEAR(arz, r.a, 1e-9);
    CHECK_NEAR(a_l, r.a, 1e-12);
    CHECK(r.rd_beyond == 0.0 && r.a_z_beyond == 0.0);
    CHECK(r.a_layer[0] > 0 && r.a_layer[1] > 0 && r.a_layer[2] > 0);
    lucent_mc_result_free(&r);
}

/* Without MCML's convention the weight beyond the grid is kept apart. */
TEST(beyond_the_grid)
{
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = &k_vanhulst,
                                             .layer_count = 1,
                                             .photons = 20000,
                                             .seed = 1,
                                             .grid = {.dr = 0.001, .dz = 0.001, .nr = 10, .nz = 10}},
                           &r));
    double rd = 0;
    for (int i = 0; i < 10; i++) rd += r.rd_r[i] * 2 * M_PI * (i + 0.5) * 1e-6;
    CHECK(r.rd_beyond > 0.5 * r.rd);
    CHECK_NEAR(rd + r.rd_beyond, r.rd, 1e-9);
    CHECK(r.a_z_beyond > 0.0);
    lucent_mc_result_free(&r);
}

/* A matched, non-scattering absorber: T = exp(-mu_a d) exactly in expectation (Beer-Lambert),
 * and every photon leaves unscattered at 0 degrees. */
TEST(beer_lambert)
{
    lucent_mc_layer l = {1.0, 2.0, 0.0, 0.0, 0.5};
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = &l, .layer_count = 1, .photons = 2000, .seed = 1}, &r));
    /* Albedo 0: the first interaction absorbs the whole packet, so T is the probability
     * that the first step crosses the slab, exp(-sigma_t d). */
    CHECK_3SE(r.tt, r.tt_se, exp(-1.0));
    CHECK(r.rd == 0.0);
    CHECK(r.tt_a[0] > 0.0 && r.tt_a[1] == 0.0);
    lucent_mc_result_free(&r);
}

/* A clear slab of glass over a turbid one: Rsp counts the multiple reflections inside the
 * glass (MCML manual eq. 3.2), and the run conserves energy. */
TEST(glass_layer)
{
    lucent_mc_layer l[2] = {{1.5, 0, 0, 0, 0.1}, {1.33, 0.1, 10.0, 0.8, 1.0}};
    lucent_mc_desc d = {.layers = l, .layer_count = 2, .photons = 20000, .seed = 2};
    double r1 = 0.04, r2 = pow(0.17 / 2.83, 2);
    CHECK_NEAR(lucent_mc_specular(&d), r1 + (1 - r1) * (1 - r1) * r2 / (1 - r1 * r2), 1e-12);
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&d, &r));
    CHECK_BALANCE(r);
    CHECK(r.a_layer[0] == 0.0 && r.a_layer[1] > 0.0);
    lucent_mc_result_free(&r);
}

TEST(validation)
{
    lucent_mc_layer l[2] = {{1.4, 0.1, 1.0, 0.0, INFINITY}, {1.4, 0.1, 1.0, 0.0, 1.0}};
    lucent_mc_result r;
    CHECK_ERR(lucent_mc_run(&(lucent_mc_desc){.layers = l, .layer_count = 2}, &r), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[0].thickness", "semi-infinite");
    l[0].thickness = 1.0;
    l[1].g = 1.5;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = l, .layer_count = 2}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[1].g: must be in [-1, 1], got 1.5");
    l[1].g = 0.0;
    l[1].n = 0.5;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = l, .layer_count = 2}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[1].n");
    l[1].n = 1.4;
    l[1].sigma_a = -1;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = l, .layer_count = 2}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[1].sigma_a");
    l[1].sigma_a = 0.1;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = l, .layer_count = 0}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers");
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = l, .layer_count = 2, .grid = {.nr = 200000}}),
              LUCENT_ERR_INVALID_ARGUMENT, "too many bins");
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){
                  .layers = l, .layer_count = 2, .score_a_rz = 1, .grid = {.nr = 100000, .nz = 100000}}),
              LUCENT_ERR_INVALID_ARGUMENT, "too many bins");
    CHECK_OK(lucent_mc_validate(&(lucent_mc_desc){.layers = l, .layer_count = 2}));
    lucent_mc_desc d;
    lucent_mc_defaults(&(lucent_mc_desc){.layers = l, .layer_count = 2}, &d);
    CHECK(d.photons == 100000 && d.batches == 32 && d.grid.nr == 640 && d.n_above == 1.0);
    CHECK_NEAR(d.grid.dr, 1.0 / 1.1 / 20, 1e-15);
}

/* ---- MCML files ---- */

TEST(mcml_read_converts_cm_to_mm)
{
    lucent_mcml_file f;
    CHECK_OK(lucent_mcml_load(FIXTURES "/two_runs.mci", &f));
    CHECK(f.run_count == 2);
    if (f.run_count != 2) return;
    const lucent_mcml_run *r = &f.runs[0];
    CHECK(strcmp(r->output, "glass.mco") == 0 && r->line == 5);
    CHECK(r->desc.photons == 3000 && r->desc.layer_count == 3);
    CHECK(r->desc.grid.nz == 30 && r->desc.grid.nr == 40 && r->desc.grid.na == 5);
    CHECK_NEAR(r->desc.grid.dr, 0.02, 1e-15);       /* 20E-4 cm */
    CHECK_NEAR(r->layers[1].sigma_s, 10.0, 1e-12);  /* 100 cm^-1 */
    CHECK_NEAR(r->layers[1].thickness, 0.1, 1e-15); /* 0.01 cm */
    CHECK(r->desc.score_a_rz && r->desc.last_bin_collects);
    CHECK(isinf(f.runs[1].layers[0].thickness));
    lucent_mcml_file_free(&f);
}

TEST(mcml_errors_name_the_line)
{
    lucent_mcml_file f;
    struct {
        const char *file, *msg;
    } bad[] = {
        {"missing_line.mci", "missing_line.mci: line 13: unexpected end of file"},
        {"negative_thickness.mci", "line 15: layer 1: thickness d must be > 0"},
        {"bad_g.mci", "line 15: layer 1: g must be in [-1, 1], got 1.5"},
        {"low_n.mci", "line 14: n for the medium above must be in [1, 10], got 0.9"},
        {"too_many_bins.mci", "line 10: too many radial bins"},
        {"bad_number.mci", "line 8: expected the number of photons, got '2e5x'"},
        {"extra_data.mci", "line 17: unexpected data after the last of 1 run"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", FIXTURES, bad[i].file);
        CHECK_ERR(lucent_mcml_load(path, &f), LUCENT_ERR_PARSE, bad[i].msg);
        CHECK(f.runs == NULL);
    }
    CHECK_ERR(lucent_mcml_parse("1.0\n1\nx.mco B\n", "t.mci", &f), LUCENT_ERR_PARSE,
              "t.mci: line 3: output format 'B' is not supported");
    CHECK_ERR(lucent_mcml_parse("2.0\n", "t.mci", &f), LUCENT_ERR_PARSE, "line 1: file version 2");
    CHECK_ERR(lucent_mcml_parse("", "t.mci", &f), LUCENT_ERR_PARSE, "line 1: unexpected end");
    CHECK_ERR(lucent_mcml_parse("1\n1\na A\n10\n.1 .1\n1 1 1\n2\n1\n1 1 1 0 inf\n1 1 1 0 1\n1\n", "t.mci", &f),
              LUCENT_ERR_PARSE, "line 9: layer 1: only the last layer may be semi-infinite");
}

/* Reads the numbers following a section header line of an .mco (up to a blank line). */
static int mco_section(const char *text, const char *head, double *dest, int max)
{
    const char *p = strstr(text, head);
    if (!p) return -1;
    p = strchr(p + 1, '\n'); /* the end of the header line */
    int n = 0;
    while (p && p[1] && p[1] != '\n' && n < max) {
        char *end;
        dest[n++] = strtod(p + 1, &end);
        p = strchr(end, '\n');
    }
    return n;
}

/* The .mco: MCML's normalisations in cm, the last radial bin collecting what lies beyond. */
TEST(mcml_write_units_and_last_bin)
{
    lucent_mcml_file f;
    CHECK_OK(lucent_mcml_load(FIXTURES "/vanhulst.mci", &f));
    if (f.run_count != 1) return;
    lucent_mcml_run *run = &f.runs[0];
    run->desc.photons = 20000;
    run->desc.grid.nr = 5; /* 0.005 cm: most of Rd lies beyond and lands in the last bin */
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&run->desc, &r));
    CHECK_OK(lucent_mcml_write(test_path("v.mco"), run, &r));
    char *text;
    size_t size;
    CHECK_OK(lucent_read_file(test_path("v.mco"), &text, &size));
    double v[64];
    CHECK(mco_section(text, "\nRAT ", v, 4) == 4);
    CHECK_NEAR(v[1], r.rd, 1e-6);
    CHECK_NEAR(v[3], r.tt, 1e-6);
    CHECK(mco_section(text, "\nRd_r ", v, 64) == 5);
    double rd = 0, dr = 0.001; /* cm */
    for (int i = 0; i < 5; i++) rd += v[i] * 2 * M_PI * (i + 0.5) * dr * dr;
    CHECK_NEAR(rd, r.rd, 1e-3 * r.rd); /* 4 significant digits in the file */
    CHECK(v[4] > v[3]);                /* the last bin collected everything beyond */
    CHECK(mco_section(text, "\nA_z ", v, 64) == 20);
    double a = 0;
    for (int i = 0; i < 20; i++) a += v[i] * 0.001;
    CHECK_NEAR(a, r.a, 1e-3 * r.a);
    CHECK(strstr(text, "\nA_rz\n") && strstr(text, "\nRd_ra\n") && strstr(text, "\nTt_ra\n"));
    CHECK(strstr(text, "\n1\t10\t90\t0.75\t0.02\t# layer 1\n") != NULL);
    free(text);
    lucent_mc_result_free(&r);
    lucent_mcml_file_free(&f);
}

/* Media outside what float steps can take, and grids that cannot be represented (issue 17): refused,
 * with the field named; the per-thread scores are capped. */
TEST(degenerate_media_refused)
{
    lucent_mc_layer l = {1.3, 0.01, 1e300, 0.0, INFINITY};
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &l, .layer_count = 1}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[0].sigma_s", "outside what the Monte Carlo can step");
    l.sigma_s = 1e-300, l.sigma_a = 0;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &l, .layer_count = 1}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[0].sigma_s");
    l.sigma_s = 1, l.sigma_a = 1e300;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &l, .layer_count = 1}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[0].sigma_a");
    l.sigma_a = 0.1;
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &l, .layer_count = 1, .grid = {.dr = 1e-300}}),
              LUCENT_ERR_INVALID_ARGUMENT, "grid.dr", "cannot be represented");
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &l, .layer_count = 1, .grid = {.dr = 1, .dz = 1e-300}}),
              LUCENT_ERR_INVALID_ARGUMENT, "grid.dz");
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &l, .layer_count = 1, .grid = {.dr = 1e300, .nr = 10}}),
              LUCENT_ERR_INVALID_ARGUMENT, "grid.dr", "spans more than");
    lucent_mc_layer slab = {1.3, 0.1, 1, 0, 1e300};
    CHECK_ERR(lucent_mc_validate(&(lucent_mc_desc){.layers = &slab, .layer_count = 1}), LUCENT_ERR_INVALID_ARGUMENT,
              "layers[0].thickness");
    /* The largest grid with A(r, z): (2 x 100001 x 200 + 100001 x 201) counters of 8 bytes, 0.48 GB a thread:
     * 8 threads would take 3.9 GB, above the 2 GiB cap; refused before anything is allocated. */
    lucent_pool *pool = lucent_pool_create(8);
    lucent_mc_result r;
    CHECK_ERR(lucent_mc_run(&(lucent_mc_desc){.layers = &l,
                                              .layer_count = 1,
                                              .photons = 10,
                                              .pool = pool,
                                              .score_a_rz = 1,
                                              .grid = {.nr = 100000, .nz = 200, .na = 200}},
                            &r),
              LUCENT_ERR_INVALID_ARGUMENT, "per thread", "8 threads", "fewer threads");
    lucent_pool_destroy(pool);
}

/* A medium that does not absorb: every packet keeps its weight 1 - Rsp until it leaves or reaches the step
 * limit, so energy conservation reads Rsp + Rd + capped (1 - Rsp) / N = 1 exactly (up to the fixed-point
 * rounding), and the capped packets are counted. */
TEST(non_absorbing_medium_is_bounded)
{
    lucent_mc_layer l = {1.0, 0.0, 1.0, 0.9, INFINITY};
    lucent_mc_result r;
    uint64_t n = 3000;
    CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = &l, .layer_count = 1, .photons = n, .seed = 3}, &r));
    printf("  %llu of %llu packets reached the step limit; Rd %.5f\n", (unsigned long long)r.capped,
           (unsigned long long)n, r.rd);
    CHECK(r.capped > 0 && r.capped < n / 10);
    CHECK_NEAR(r.rsp + r.rd + (double)r.capped * (1 - r.rsp) / (double)n, 1.0, 1e-6);
    CHECK(r.a == 0 && r.tt == 0);
    lucent_mc_result_free(&r);
}

/* The g 0.9 skin presets (data/materials.json): the table's sigma_a and sigma_s' (Jensen et al. 2001,
 * Figure 5) with g 0.9, sigma_s = sigma_s' / (1 - g). By the similarity relation (a medium of sigma_a,
 * sigma_s, g transports light as one of sigma_a, sigma_s (1 - g), g = 0 once the light is about one
 * transport mean free path l' deep: Wang & Jacques 1993, "Analysis of diffusion theory and similarity
 * relations for light reflectance by turbid media", Proc. SPIE 1888) their total diffuse reflectance
 * under normal light is close to the g = 0 preset's. Above that depth the two differ: the forward-
 * scattering medium carries the light about l' deeper before turning it, and so absorbs up to a
 * further fraction sigma_a l' = 1 - a' of it (a' = sigma_s' / sigma_t', the reduced albedo). Bound:
 * Rd(g 0.9) no higher than Rd(g 0) and no lower than (1 - (1 - a')) Rd(g 0) = a' Rd(g 0), each within 3
 * standard errors of the difference (Monte Carlo, 50000 photons each). Measured ratios
 * Rd(0.9) / Rd(0): 0.77 at a' 0.68, 0.89 at 0.84, 0.96-1.00 at 0.93-0.99, so the bound's lower side is
 * 0.7 (1 - a') from the data; an MC that ignored g (sigma_s = 10 sigma_s' isotropic: Rd ~0.8) or a
 * preset with sigma_s = sigma_s' at g 0.9 (Rd a few %) falls far outside. */
TEST(g09_skin_presets_keep_the_tables_reduced_coefficients)
{
    static const char *const pairs[2][2] = {{"Skin1", "Skin1-g0.9"}, {"Skin2", "Skin2-g0.9"}};
    static const double table[2][2][3] = {{{0.032, 0.17, 0.48}, {0.74, 0.88, 1.01}},
                                          {{0.013, 0.070, 0.145}, {1.09, 1.59, 1.79}}}; /* sigma_a, sigma_s' */
    lucent_pool *pool = lucent_pool_create(2);
    for (int k = 0; k < 2; k++) {
        lucent_material m0, m9;
        lucent_material_derived d0, d9;
        CHECK_OK(lucent_material_preset_find(pairs[k][0], &m0));
        CHECK_OK(lucent_material_preset_find(pairs[k][1], &m9));
        lucent_material_derive(&m0, &d0), lucent_material_derive(&m9, &d9);
        for (int c = 0; c < 3; c++) {
            CHECK(m0.g[c] == 0 && m9.g[c] == 0.9);
            CHECK_NEAR(m9.sigma_a[c], table[k][0][c], 1e-15);
            CHECK_NEAR(d9.sigma_s_prime[c], table[k][1][c], 1e-12);
            CHECK_NEAR(d0.sigma_s_prime[c], table[k][1][c], 1e-12);
            CHECK_NEAR(m9.sigma_s[c], 10 * table[k][1][c], 1e-12);
            CHECK_NEAR(d9.rd[c], d0.rd[c], 1e-12); /* the dipole sees only the reduced coefficients */
            double rd[2], se[2];
            for (int v = 0; v < 2; v++) {
                const lucent_material *m = v ? &m9 : &m0;
                lucent_mc_layer half = {m->eta, m->sigma_a[c], m->sigma_s[c], m->g[c], INFINITY};
                lucent_mc_result r;
                CHECK_OK(lucent_mc_run(&(lucent_mc_desc){.layers = &half,
                                                         .layer_count = 1,
                                                         .photons = 50000,
                                                         .seed = (uint64_t)(100 + 10 * k + 2 * c + v),
                                                         .pool = pool},
                                       &r));
                rd[v] = r.rd, se[v] = r.rd_se;
                lucent_mc_result_free(&r);
            }
            double diff = rd[1] - rd[0], sd = sqrt(se[0] * se[0] + se[1] * se[1]), ap = d0.albedo_prime[c];
            CHECK(sd > 0 && sd < 0.005);
            CHECK_MSG(diff <= 3 * sd && diff >= -(1 - ap) * rd[0] - 3 * sd,
                      "%s[%d] (a' %.3f): Rd %.4f with g 0.9, %.4f with g 0 (+- %.4f)", pairs[k][1], c, ap, rd[1], rd[0],
                      sd);
            printf("  %s[%d]: a' %.3f, Rd g 0 %.4f, g 0.9 %.4f +- %.4f, ratio %.3f\n", pairs[k][0], c, ap, rd[0], rd[1],
                   sd, rd[1] / rd[0]);
        }
    }
    lucent_pool_destroy(pool);
}

TEST_MAIN(TEST_ENTRY(vanhulst_slab), TEST_ENTRY(giovanelli_half_space),
          TEST_ENTRY(same_seed_same_result_for_any_thread_count), TEST_ENTRY(profiles_integrate_to_totals),
          TEST_ENTRY(beyond_the_grid), TEST_ENTRY(beer_lambert), TEST_ENTRY(glass_layer), TEST_ENTRY(validation),
          TEST_ENTRY(mcml_read_converts_cm_to_mm), TEST_ENTRY(mcml_errors_name_the_line),
          TEST_ENTRY(mcml_write_units_and_last_bin), TEST_ENTRY(degenerate_media_refused),
          TEST_ENTRY(non_absorbing_medium_is_bounded),
          TEST_ENTRY(g09_skin_presets_keep_the_tables_reduced_coefficients))
