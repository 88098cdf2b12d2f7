/* Tests of MCML output files read back (src/profile/mco.c) and of a Lucent run compared with
 * one (src/profile/mco_compare.c, mco_write.c). The fixtures in tests/fixtures/mcml/mco/ are
 * real MCML 1.2.2 outputs (tests/fixtures/mcml/mco/README.md says how they were made). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "lucent/mc.h"
#include "lucent/mcml.h"
#include "test.h"

#define MCO LUCENT_SOURCE_DIR "/tests/fixtures/mcml/mco/"

static char *fixture_text(const char *name)
{
    char path[512], *text = NULL;
    size_t size;
    snprintf(path, sizeof path, MCO "%s", name);
    CHECK_OK(lucent_read_file(path, &text, &size));
    return text;
}

/* text with the first occurrence of find replaced by repl (a new string). */
/* (not inlined: gcc 12 then mistakes the pointers into text for dangling ones) */
__attribute__((noinline)) static char *edit(const char *text, const char *find, const char *repl)
{
    const char *at = strstr(text, find);
    CHECK_MSG(at != NULL, "the fixture lacks '%s'", find);
    if (!at) return strdup(text);
    size_t head = (size_t)(at - text), nf = strlen(find), nr = strlen(repl);
    size_t tail = strlen(text) - head - nf;
    char *out = malloc(head + nr + tail + 1);
    memcpy(out, text, head);
    memcpy(out + head, repl, nr);
    memcpy(out + head + nr, text + head + nf, tail + 1);
    return out;
}

/* ---- reading ---- */

/* What MCML wrote (the file's own lines) arrives in mm units. */
TEST(reads_mcml_output)
{
    lucent_mco m;
    CHECK_OK(lucent_mco_load(MCO "gcontrast_small.mco", &m));
    const lucent_mc_desc *d = &m.run.desc;
    CHECK(d->photons == 20000 && d->layer_count == 2 && strcmp(m.run.output, "gcontrast_small.mco") == 0);
    CHECK(d->grid.nz == 30 && d->grid.nr == 20 && d->grid.na == 5);
    CHECK_NEAR(d->grid.dz, 0.05, 1e-15);           /* 0.005 cm */
    CHECK_NEAR(d->grid.dr, 0.5, 1e-15);            /* 0.05 cm */
    CHECK_NEAR(d->layers[0].sigma_s, 10.0, 1e-12); /* 100 1/cm */
    CHECK_NEAR(d->layers[1].g, 0.3, 0);
    CHECK_NEAR(d->layers[1].thickness, 1.0, 1e-12); /* 0.1 cm */
    CHECK(m.rsp == 0 && m.rd == 0.566199 && m.a == 0.225668 && m.tt == 0.208134);
    CHECK(m.a_l[0] == 0.1345 && m.a_l[1] == 0.09117);
    CHECK_NEAR(m.a_z[0], 0.21882, 1e-12); /* 2.1882 1/cm */
    CHECK(m.a_rz && m.rd_ra && m.tt_ra);
    lucent_mco_free(&m);
    CHECK(m.a_z == NULL && m.run.layers == NULL);
}

/* MCML's own relations (its Sum2DRd, Sum2DA, Sum2DTt): the totals are the profiles summed over
 * their bins, which checks the reader's conversions to Lucent's units and normalisations (within
 * the 5 digits per bin): mm, and the exact solid angle of each angular band. */
TEST(mcml_output_is_consistent_with_itself)
{
    const char *files[] = {"gcontrast_small.mco", "nmismatch_small.mco"};
    for (int f = 0; f < 2; f++) {
        lucent_mco m;
        char path[512];
        snprintf(path, sizeof path, MCO "%s", files[f]);
        CHECK_OK(lucent_mco_load(path, &m));
        const lucent_mc_grid *g = &m.run.desc.grid;
        double rd = 0, tt = 0, a = 0, a_l = 0, rd_a = 0, rd_ra = 0;
        for (int i = 0; i < g->nr; i++) {
            double ring = 2 * M_PI * (i + 0.5) * g->dr * g->dr;
            rd += m.rd_r[i] * ring;
            tt += m.tt_r[i] * ring;
        }
        double da = M_PI / (2 * g->na);
        for (int j = 0; j < g->na; j++) {
            double omega = 4 * M_PI * sin((j + 0.5) * da) * sin(da / 2); /* Lucent's, exact */
            rd_a += m.rd_a[j] * omega;
            for (int i = 0; i < g->nr; i++)
                rd_ra += m.rd_ra[i * g->na + j] * omega * 2 * M_PI * (i + 0.5) * g->dr * g->dr;
        }
        for (int k = 0; k < g->nz; k++) a += m.a_z[k] * g->dz;
        for (int l = 0; l < m.run.desc.layer_count; l++) a_l += m.a_l[l];
        CHECK_NEAR(rd, m.rd, 1e-4 * m.rd);
        CHECK_NEAR(rd_a, m.rd, 1e-4 * m.rd); /* the file's angular units became Lucent's */
        CHECK_NEAR(rd_ra, m.rd, 1e-4 * m.rd);
        CHECK_NEAR(tt, m.tt, 1e-4 * m.tt);
        CHECK_NEAR(a, m.a, 1e-4 * m.a);
        CHECK_NEAR(a_l, m.a, 1e-3 * m.a); /* A_l has 4 digits */
        CHECK_NEAR(m.rsp + m.rd + m.a + m.tt, 1.0, 1e-5);
        lucent_mco_free(&m);
    }
}

/* Lucent's own .mco (a half-space written as 'inf') reads back as written. */
TEST(reads_lucent_output)
{
    lucent_mc_layer l = {1.4, 0.1, 10.0, 0.9, INFINITY};
    lucent_mcml_run run = {.output = "half.mco",
                           .layers = &l,
                           .desc = {.layers = &l,
                                    .layer_count = 1,
                                    .photons = 2000,
                                    .seed = 3,
                                    .grid = {.dr = 0.1, .dz = 0.1, .nr = 10, .nz = 8, .na = 4},
                                    .score_a_rz = true,
                                    .last_bin_collects = true}};
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&run.desc, &r));
    CHECK_OK(lucent_mcml_write(test_path("half.mco"), &run, &r));
    lucent_mco m;
    CHECK_OK(lucent_mco_load(test_path("half.mco"), &m));
    CHECK(isinf(m.run.desc.layers[0].thickness) && m.run.desc.photons == 2000);
    CHECK_NEAR(m.rd, r.rd, 5e-6 * r.rd);
    for (int i = 0; i < 10; i++) CHECK_NEAR(m.rd_r[i], r.rd_r[i], 5e-5 * r.rd_r[i]);
    for (int i = 0; i < 80; i++) CHECK_NEAR(m.a_rz[i], r.a_rz[i], 5e-5 * r.a_rz[i]);
    for (int j = 0; j < 4; j++) CHECK_NEAR(m.rd_a[j], r.rd_a[j], 5e-5 * r.rd_a[j]);
    for (int i = 0; i < 40; i++) CHECK_NEAR(m.rd_ra[i], r.rd_ra[i], 5e-5 * r.rd_ra[i]);
    lucent_mco_free(&m);
    lucent_mc_result_free(&r);
}

/* Malformed files: a parse error naming the file, the line and the section; nothing leaks. */
TEST(malformed_files_name_the_line)
{
    char *good = fixture_text("gcontrast_small.mco");
    if (!good) return;
    struct {
        const char *find, *repl, *msg;
    } bad[] = {
        {"A1 \t#", "A2 \t#", "t.mco: line 1: expected the format version A1"},
        {"A1 \t#", "B1 \t#", "line 1: binary .mco files (B1) are not supported"},
        {"InParm \t", "InParms \t", "line 12: expected the section InParm, got 'InParms'"},
        {"1\t0.5\t60\t0.3\t0.1", "1\t0.5\t60\t1.3\t0.1", "line 22: layer 2: g must be in [-1, 1], got 1.3"},
        {"0.566199 ", "0.56x199 ", "line 27: RAT: value 2: expected a number, got '0.56x199'"},
        {"0.566199 ", "nan ", "line 27: RAT: value 2: not a usable number"},
        {"0.566199 ", "-0.5 ", "line 27: RAT: value 2: must be >= 0, got -0.5"},
        {"      0.1345\n", "      0.1345 0.5\n", "line 33: A_l: more than 2 values (layers)"},
        {"  2.1882E+00\n", "", "line 66: A_z: expected 30 values (nz), got 29 before section Rd_r"},
        {"  2.1882E+00\n", "  2.1882E+00 1e999\n", "line 36: A_z: value 2: not a usable number"},
        {"Rd_a #", "Rd_x #", "line 89: expected a section name (RAT, A_l, A_z, ...), got 'Rd_x'"},
        {"Rd_a #", "Rd_a 5 #", "line 89: unexpected data after the section name Rd_a"},
        {"Tt_a #", "Rd_a #", "line 118: section Rd_a appears twice (first at line 89)"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char *text = edit(good, bad[i].find, bad[i].repl);
        lucent_mco m;
        CHECK_ERR(lucent_mco_parse(text, "t.mco", &m), LUCENT_ERR_PARSE, bad[i].msg);
        CHECK(m.a_z == NULL && m.run.layers == NULL);
        free(text);
    }
    /* cut inside A_rz (line 130 on: 600 values, 13 characters each), and with the 1-D section
     * Tt_a gone */
    char *cut = strdup(good);
    cut[strstr(cut, "\nA_rz\n") - cut + 400] = '\0';
    lucent_mco m;
    CHECK_ERR(lucent_mco_parse(cut, "t.mco", &m), LUCENT_ERR_PARSE,
              "line 130: A_rz: the rest of the file is too short for 600 values (nr x nz)");
    strcpy(cut, good);
    cut[strstr(cut, "\nA_rz\n") - cut + 1300] = '\0';
    CHECK_ERR(lucent_mco_parse(cut, "t.mco", &m), LUCENT_ERR_PARSE,
              "unexpected end of file, expected A_rz: 600 values (nr x nz)");
    cut[strstr(cut, "\nTt_a #") - cut + 1] = '\0';
    CHECK_ERR(lucent_mco_parse(cut, "t.mco", &m), LUCENT_ERR_PARSE,
              "line 118: unexpected end of file: missing the section Tt_a");
    /* a short file naming a huge grid is refused before anything large is allocated */
    CHECK_ERR(lucent_mco_parse("A1\nInParm\nx.mco A\n10\n0.01 0.01\n200 100000 1\n1\n1\n"
                               "1 1 1 0 1\n1\nRAT\n0\n0\n0\n1\nA_rz\n1\n",
                               "t.mco", &m),
              LUCENT_ERR_PARSE, "line 16: A_rz: the rest of the file is too short for 20000000 values (nr x nz)");
    CHECK_ERR(lucent_mco_parse("", "t.mco", &m), LUCENT_ERR_PARSE,
              "t.mco: line 1: unexpected end of file, expected the format version (A1)");
    CHECK_ERR(lucent_mco_load(MCO "absent.mco", &m), LUCENT_ERR_IO, "absent.mco");
    /* without the 2-D sections the file still reads (they are not compared) */
    cut = strcpy(cut, good);
    cut[strstr(cut, "\nA_rz\n") - cut + 1] = '\0';
    CHECK_OK(lucent_mco_parse(cut, "t.mco", &m));
    CHECK(m.a_rz == NULL && m.tt_a != NULL);
    lucent_mco_free(&m);
    free(cut);
    free(good);
}

/* ---- comparing ---- */

/* A Lucent run of the fixture's simulation, with n photons. */
static void run_of(const lucent_mco *m, uint64_t photons, lucent_mc_result *r)
{
    lucent_mc_desc d = m->run.desc;
    d.photons = photons;
    d.seed = 5;
    d.score_a_rz = false;
    CHECK_OK(lucent_mc_run(&d, r));
}

/* A run compared with the .mco written from it: every difference is the file's rounding. */
TEST(compare_with_itself)
{
    lucent_mco m;
    CHECK_OK(lucent_mco_load(MCO "nmismatch_small.mco", &m));
    lucent_mc_result r;
    run_of(&m, 20000, &r);
    lucent_mcml_run run = m.run;
    run.output = "self.mco";
    CHECK_OK(lucent_mcml_write(test_path("self.mco"), &run, &r));
    lucent_mco self;
    CHECK_OK(lucent_mco_load(test_path("self.mco"), &self));
    lucent_mco_comparison c;
    CHECK_OK(lucent_mco_compare(&self, &r, &c));
    CHECK(c.rsp_equal && c.a_l_on_grid && c.se_scale == 1.0);
    CHECK_NEAR(c.rsp_lucent, 0.04, 1e-15); /* ((1.5 - 1) / (1.5 + 1))^2 */
    CHECK(c.beyond3 == 0 && c.compared > 50);
    CHECK_MSG(c.chi2 / c.compared < 1e-4, "chi2/bin %g: more than rounding", c.chi2 / c.compared);
    for (int k = 0; k < LUCENT_MCO_SECTION_COUNT; k++) {
        const lucent_mco_section *s = &c.sections[k];
        CHECK(s->unresolved == 0);
        for (int i = 0; i < s->count; i++)
            if (s->bins[i].lucent == 0) CHECK(s->bins[i].state == LUCENT_MCO_EMPTY);
    }
    lucent_mco_comparison_free(&c);
    lucent_mco_free(&self);
    lucent_mc_result_free(&r);
    lucent_mco_free(&m);
}

/* A wrong total stands out; MCML's standard error scales with its photons; weight on MCML's
 * side only is "unresolved", not counted; A_l is not compared when a boundary is off the grid. */
TEST(compare_finds_differences)
{
    lucent_mco m;
    CHECK_OK(lucent_mco_load(MCO "gcontrast_small.mco", &m));
    lucent_mc_result r;
    run_of(&m, 80000, &r);
    m.rd *= 1.05;
    m.rd_r[19] = 1.0; /* beyond Lucent's reach: Lucent's bin is empty */
    r.rd_r[19] = r.rd_r_se[19] = 0;
    lucent_mco_comparison c;
    CHECK_OK(lucent_mco_compare(&m, &r, &c));
    const lucent_mco_bin *rd = &c.sections[LUCENT_MCO_RAT].bins[0];
    CHECK_NEAR(c.se_scale, 2.0, 1e-15); /* sqrt(80000 / 20000) */
    CHECK_NEAR(rd->mcml_se, 2.0 * rd->lucent_se, 1e-15);
    CHECK(rd->state == LUCENT_MCO_COMPARED && rd->z < -3.0);
    CHECK(c.sections[LUCENT_MCO_RAT].beyond3 >= 1 && c.beyond3 >= 1);
    CHECK(c.sections[LUCENT_MCO_RD_R].bins[19].state == LUCENT_MCO_UNRESOLVED);
    CHECK(c.sections[LUCENT_MCO_RD_R].unresolved == 1);
    lucent_mco_comparison_free(&c);
    m.run.layers[0].thickness = 0.52; /* 0.052 cm: off the 0.005 cm grid */
    CHECK_OK(lucent_mco_compare(&m, &r, &c));
    CHECK(!c.a_l_on_grid && c.sections[LUCENT_MCO_A_L].incomparable == 2 && c.sections[LUCENT_MCO_A_L].compared == 0);
    lucent_mco_comparison_free(&c);
    lucent_mc_result_free(&r);
    lucent_mco_free(&m);
}

TEST(check_run_names_the_difference)
{
    lucent_mco m;
    CHECK_OK(lucent_mco_load(MCO "gcontrast_small.mco", &m));
    lucent_mcml_file f;
    CHECK_OK(lucent_mcml_load(MCO "gcontrast_small.mci", &f));
    CHECK_OK(lucent_mco_check_run(&m, &f.runs[0].desc));
    f.runs[0].layers[1].sigma_s = 15.0;
    CHECK_ERR(lucent_mco_check_run(&m, &f.runs[0].desc), LUCENT_ERR_INVALID_ARGUMENT,
              "layer 2: mus [1/cm] is 150, the .mco's is 60");
    f.runs[0].layers[1].sigma_s = 6.0;
    f.runs[0].desc.grid.nr = 21;
    CHECK_ERR(lucent_mco_check_run(&m, &f.runs[0].desc), LUCENT_ERR_INVALID_ARGUMENT, "nr is 21, the .mco's is 20");
    lucent_mc_result r;
    CHECK_OK(lucent_mc_run(&f.runs[0].desc, &r));
    lucent_mco_comparison c;
    CHECK_ERR(lucent_mco_compare(&m, &r, &c), LUCENT_ERR_INVALID_ARGUMENT, "nr 21");
    lucent_mc_result_free(&r);
    lucent_mcml_file_free(&f);
    lucent_mco_free(&m);
}

/* CSV: a row per bin (and Rsp) in cm units; JSON: the same counts as the comparison. */
TEST(comparison_files)
{
    lucent_mco m;
    CHECK_OK(lucent_mco_load(MCO "gcontrast_small.mco", &m));
    lucent_mc_result r;
    run_of(&m, 20000, &r);
    lucent_mco_comparison c;
    CHECK_OK(lucent_mco_compare(&m, &r, &c));
    CHECK_OK(lucent_mco_comparison_write_csv(test_path("c.csv"), &c));
    CHECK_OK(lucent_mco_comparison_write_json(test_path("c.json"), &c));
    char *text;
    size_t size;
    CHECK_OK(lucent_read_file(test_path("c.csv"), &text, &size));
    int lines = 0;
    for (const char *p = text; *p; p++) lines += *p == '\n';
    CHECK(lines == 1 + 1 + 3 + 2 + 30 + 20 + 5 + 20 + 5);
    CHECK(strstr(text, "\nA_z,0,0.0025,z [cm],1/cm,") != NULL);
    char row[64];
    snprintf(row, sizeof row, "\nRd_r,0,0.025,r [cm],1/cm2,%.9g,", r.rd_r[0] * 100.0);
    CHECK_MSG(strstr(text, row) != NULL, "no row '%s'", row + 1);
    free(text);
    cJSON *json;
    CHECK_OK(lucent_json_parse_file(test_path("c.json"), &json));
    const cJSON *summary = cJSON_GetObjectItem(json, "summary");
    CHECK(cJSON_GetObjectItem(summary, "compared")->valueint == c.compared);
    CHECK(cJSON_GetObjectItem(summary, "beyond_3se")->valueint == c.beyond3);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(json, "sections")) == LUCENT_MCO_SECTION_COUNT);
    cJSON_Delete(json);
    CHECK_ERR(lucent_mco_comparison_write_csv(test_path("no/such/dir/c.csv"), &c), LUCENT_ERR_IO, "no/such/dir");
    lucent_mco_comparison_free(&c);
    lucent_mc_result_free(&r);
    lucent_mco_free(&m);
}

TEST_MAIN(TEST_ENTRY(reads_mcml_output), TEST_ENTRY(mcml_output_is_consistent_with_itself),
          TEST_ENTRY(reads_lucent_output), TEST_ENTRY(malformed_files_name_the_line), TEST_ENTRY(compare_with_itself),
          TEST_ENTRY(compare_finds_differences), TEST_ENTRY(check_run_names_the_difference),
          TEST_ENTRY(comparison_files))
