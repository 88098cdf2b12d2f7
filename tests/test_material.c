/* Tests of src/material: the dipole against Jensen et al. 2001, derived quantities by hand,
 * units, the other parameterisations, presets, and malformed material files. */
#include <cjson/cJSON.h>
#include <pthread.h>

#include "lucent/material.h"
#include "test.h"

#define FIXTURE(name) LUCENT_SOURCE_DIR "/tests/fixtures/materials/" name

static lucent_material preset(const char *name)
{
    lucent_material m = {0};
    CHECK_OK(lucent_material_preset_find(name, &m));
    return m;
}

static void check_rd(const char *name, double r, double g, double b, double tol)
{
    lucent_material m = preset(name);
    lucent_material_derived d;
    lucent_material_derive(&m, &d);
    CHECK_NEAR(d.rd[0], r, tol);
    CHECK_NEAR(d.rd[1], g, tol);
    CHECK_NEAR(d.rd[2], b, tol);
}

/* The acceptance values of the issue: the closed form to 3 decimals. */
TEST(rd_skin1_and_marble)
{
    check_rd("Skin1", 0.436, 0.227, 0.131, 0.001);
    check_rd("Marble", 0.830, 0.791, 0.753, 0.001);
}

/* Skin1, red, by hand (sigma_a 0.032, sigma_s' 0.74 mm^-1, g 0, eta 1.3):
 *   sigma_t' = 0.772; alpha' = 0.74 / 0.772 = 0.958549
 *   sigma_tr = sqrt(3 * 0.032 * 0.772) = sqrt(0.074112) = 0.272235 mm^-1
 *   D = 1 / (3 * 0.772) = 0.431779 mm; l' = 1 / 0.772 = 1.295337 mm; ld = 1 / 0.272235 = 3.673294
 * mm Fdr(1.3) = -1.44/1.69 + 0.71/1.3 + 0.668 + 0.0636*1.3 = -0.852071 + 0.546154 + 0.668 + 0.08268
 *            = 0.444763; A = 1.444763 / 0.555237 = 2.602064
 *   s = sqrt(3 (1 - alpha')) = 0.352636; exp(-(4/3) A s) = 0.294215; exp(-s) = 0.702833
 *   Rd = 0.479275 * 1.294215 * 0.702833 = 0.435956 */
TEST(derived_by_hand)
{
    lucent_material m = preset("skin1");
    lucent_material_derived d;
    lucent_material_derive(&m, &d);
    CHECK_NEAR(d.sigma_s_prime[0], 0.74, 1e-12);
    CHECK_NEAR(d.sigma_t_prime[0], 0.772, 1e-12);
    CHECK_NEAR(d.albedo_prime[0], 0.958549, 1e-6);
    CHECK_NEAR(d.albedo[0], 0.958549, 1e-6); /* g = 0 */
    CHECK_NEAR(d.sigma_tr[0], 0.272235, 1e-6);
    CHECK_NEAR(d.diffusion[0], 0.431779, 1e-6);
    CHECK_NEAR(d.mfp_prime[0], 1.295337, 1e-6);
    CHECK_NEAR(d.mfp[0], 1.295337, 1e-6);
    CHECK_NEAR(d.mfp_diffuse[0], 3.673294, 1e-6);
    CHECK_NEAR(d.fdr, 0.444763, 1e-6);
    CHECK_NEAR(d.a, 2.602064, 1e-6);
    CHECK_NEAR(d.rd[0], 0.435956, 1e-6);
    CHECK_NEAR(lucent_fdr(1.5), 0.596733, 1e-6); /* -0.64 + 0.473333 + 0.668 + 0.0954 */
}

/* Reads rd_published from data/materials.json directly (not through the library). */
static int published(double rd[][3], char names[][64], int max)
{
    cJSON *root = NULL;
    FILE *f = fopen(LUCENT_SOURCE_DIR "/data/materials.json", "rb");
    static char text[65536];
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[n] = '\0';
    root = cJSON_Parse(text);
    int count = 0;
    const cJSON *m;
    cJSON_ArrayForEach(m, cJSON_GetObjectItem(root, "materials"))
    {
        if (count == max) break;
        const cJSON *rdj = cJSON_GetObjectItem(m, "rd_published");
        if (!rdj) continue; /* the spectral skins have none */
        for (int c = 0; c < 3; c++) rd[count][c] = cJSON_GetArrayItem(rdj, c)->valuedouble;
        snprintf(names[count], 64, "%s", cJSON_GetObjectItem(m, "name")->valuestring);
        count++;
    }
    cJSON_Delete(root);
    return count;
}

/* The closed form against the Rd column of Jensen et al. 2001, Figure 5. The paper prints Rd
 * to 2 decimals (+-0.005) and the coefficients to 2-3 significant digits, which moves the
 * closed form by up to about 0.003 (e.g. Skin1 green: sigma_a 0.17 +- 0.005 spans
 * Rd 0.223..0.232): all channels agree within 0.008. One entry disagrees beyond rounding:
 * Chicken1 blue, printed 0.10, while its printed coefficients (0.19, 0.38) give 0.126 (0.123 to
 * 0.130 over their rounding); we keep the paper's coefficients and record the discrepancy. */
TEST(rd_against_published_table)
{
    double rd[16][3];
    char names[16][64];
    int n = published(rd, names, 16);
    CHECK(n == 11);
    double worst = 0.0;
    for (int i = 0; i < n; i++) {
        lucent_material m = preset(names[i]);
        lucent_material_derived d;
        lucent_material_derive(&m, &d);
        for (int c = 0; c < 3; c++) {
            double diff = fabs(d.rd[c] - rd[i][c]);
            if (strcmp(names[i], "Chicken1") == 0 && c == 2) {
                CHECK_NEAR(d.rd[c], 0.126, 0.001); /* the known discrepancy */
                continue;
            }
            CHECK_MSG(diff <= 0.008, "%s[%d]: Rd %.4f vs published %.2f", names[i], c, d.rd[c], rd[i][c]);
            if (diff > worst) worst = diff;
        }
    }
    CHECK(worst > 0.005); /* the tolerance is needed: the table is rounded */
}

TEST(presets)
{
    static const char *const names[] = {"Apple",  "Chicken1", "Chicken2", "Cream", "Ketchup",  "Marble",
                                        "Potato", "Skimmilk", "Skin1",    "Skin2", "Wholemilk"};
    CHECK(lucent_material_preset_count() == 21); /* the 11 of Jensen et al. 2001, 8 spectral skins, 2 g 0.9 skins */
    for (int i = 0; i < 11; i++) {
        lucent_material m;
        CHECK_OK(lucent_material_preset(i, &m));
        CHECK(strcmp(m.name, names[i]) == 0);
        CHECK_NEAR(m.eta, strcmp(names[i], "Marble") == 0 ? 1.5 : 1.3, 0);
        CHECK_OK(lucent_material_validate(&m));
    }
    lucent_material m = preset("wHoLeMiLk");
    CHECK(strcmp(m.name, "Wholemilk") == 0);
    CHECK_NEAR(m.sigma_a[2], 0.014, 1e-15); /* mm^-1: the seed's 0.14 cm^-1 / 10 */
    CHECK_NEAR(m.sigma_s[0], 2.55, 1e-15);
    CHECK_ERR(lucent_material_preset_find("jade", &m), LUCENT_ERR_NOT_FOUND, "jade", "Skin1");
    CHECK_ERR(lucent_material_preset(21, &m), LUCENT_ERR_INVALID_ARGUMENT, "21");
}

static void *count_presets(void *arg)
{
    *(int *)arg = lucent_material_preset_count();
    return NULL;
}

TEST(presets_thread_safe)
{
    pthread_t t[4];
    int n[4] = {0};
    for (int i = 0; i < 4; i++) pthread_create(&t[i], NULL, count_presets, &n[i]);
    for (int i = 0; i < 4; i++) pthread_join(t[i], NULL);
    for (int i = 0; i < 4; i++) CHECK(n[i] == 21);
}

static lucent_material parse_one(const char *text)
{
    lucent_material *m = NULL, out = {0};
    int n = 0;
    CHECK_OK(lucent_material_parse(text, "t.json", &m, &n));
    CHECK(n == 1);
    if (m) out = m[0];
    free(m);
    return out;
}

TEST(units)
{
    lucent_material mm = parse_one("{\"units\":\"mm^-1\",\"sigma_a\":[0.1,0.2,0.3],\"sigma_s\":[1,2,3],\"eta\":1.3}");
    lucent_material cm = parse_one("{\"units\":\"cm^-1\",\"sigma_a\":[1,2,3],\"sigma_s\":[10,20,30],\"eta\":1.3}");
    lucent_material m1 =
        parse_one("{\"units\":\"1/m\",\"sigma_a\":[100,200,300],\"sigma_s\":[1e3,2e3,3e3],\"eta\":1.3}");
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(cm.sigma_a[c], mm.sigma_a[c], 1e-15); /* 1 cm^-1 = 0.1 mm^-1 */
        CHECK_NEAR(cm.sigma_s[c], mm.sigma_s[c], 1e-15);
        CHECK_NEAR(m1.sigma_a[c], mm.sigma_a[c], 1e-15); /* 1 m^-1 = 0.001 mm^-1 */
        CHECK_NEAR(m1.sigma_s[c], mm.sigma_s[c], 1e-15);
    }
    CHECK(strcmp(mm.name, "t") == 0); /* a lone material is named after its file */
    /* Lengths: a mean free path of 0.1 cm is 1 mm. */
    lucent_material l =
        parse_one("{\"name\":\"x\",\"units\":\"cm\",\"albedo\":0.9,\"mean_free_path\":0.1,\"eta\":1.3}");
    CHECK_NEAR(l.sigma_a[0] + l.sigma_s[0], 1.0, 1e-12);
    CHECK_NEAR(l.sigma_s[0], 0.9, 1e-12);
}

TEST(sigma_s_prime_and_g)
{
    lucent_material m = parse_one("{\"units\":\"mm^-1\",\"sigma_a\":0.01,\"sigma_s_prime\":[1,2,3],"
                                  "\"g\":[0.5,0.8,0],\"eta\":1.4}");
    CHECK_NEAR(m.sigma_s[0], 2.0, 1e-12); /* sigma_s = sigma_s' / (1 - g) */
    CHECK_NEAR(m.sigma_s[1], 10.0, 1e-12);
    CHECK_NEAR(m.sigma_s[2], 3.0, 1e-12);
    lucent_material_derived d;
    lucent_material_derive(&m, &d);
    CHECK_NEAR(d.sigma_s_prime[1], 2.0, 1e-12);
    CHECK_NEAR(d.albedo[1], 10.0 / 10.01, 1e-12);
}

TEST(albedo_round_trips)
{
    lucent_material m = preset("Skin1"), r = m;
    m.g[0] = 0.3, m.g[1] = 0.6, m.g[2] = 0.9;
    r.g[0] = 0.3, r.g[1] = 0.6, r.g[2] = 0.9;
    lucent_material_derived d, e;
    lucent_material_derive(&m, &d);
    CHECK_OK(lucent_material_set_albedo(LUCENT_ALBEDO_SINGLE, d.albedo, d.mfp, &r));
    for (int c = 0; c < 3; c++) CHECK_NEAR(r.sigma_a[c], m.sigma_a[c], 1e-12);
    for (int c = 0; c < 3; c++) CHECK_NEAR(r.sigma_s[c], m.sigma_s[c], 1e-12);
    CHECK_OK(lucent_material_set_albedo(LUCENT_ALBEDO_REDUCED, d.albedo_prime, d.mfp_prime, &r));
    for (int c = 0; c < 3; c++) CHECK_NEAR(r.sigma_s[c], m.sigma_s[c], 1e-12);
    CHECK_OK(lucent_material_set_diffuse(d.rd, d.mfp_diffuse, &r));
    lucent_material_derive(&r, &e);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(r.sigma_a[c], m.sigma_a[c], 1e-9);
        CHECK_NEAR(r.sigma_s[c], m.sigma_s[c], 1e-9);
        CHECK_NEAR(e.rd[c], d.rd[c], 1e-10);
    }
    double bad[3] = {0.5, 1.5, 0.5}, mfp[3] = {1, 1, 1};
    CHECK_ERR(lucent_material_set_albedo(LUCENT_ALBEDO_SINGLE, bad, mfp, &r), LUCENT_ERR_INVALID_ARGUMENT, "albedo[1]",
              "in [0, 1]");
}

TEST(dipole_inverse)
{
    for (double eta = 1.0; eta <= 2.0; eta += 0.25)
        for (double a = 0.0; a < 1.0; a += 0.0625)
            CHECK_NEAR(lucent_dipole_albedo_from_rd(lucent_dipole_rd(a, eta), eta), a, 1e-9);
    CHECK(lucent_dipole_rd(0.0, 1.3) == 0.0);
    CHECK(lucent_dipole_rd(1.0, 1.3) == 1.0);
    CHECK(lucent_dipole_albedo_from_rd(-1.0, 1.3) == 0.0);
    CHECK(lucent_dipole_albedo_from_rd(1.0, 1.3) == 1.0);
    CHECK(lucent_dipole_rd(0.5, 1.3) < lucent_dipole_rd(0.6, 1.3));
}

TEST(fixtures_that_load)
{
    lucent_material *m;
    int n;
    CHECK_OK(lucent_material_load(FIXTURE("jade.json"), &m, &n));
    CHECK(n == 1 && strcmp(m[0].name, "jade") == 0);
    CHECK_NEAR(m[0].sigma_a[0], 0.05, 1e-15);
    CHECK_NEAR(m[0].sigma_s[2], 8.0, 1e-12);
    CHECK_NEAR(m[0].g[1], 0.5, 0);
    free(m);
    CHECK_OK(lucent_material_load(FIXTURE("two.json"), &m, &n));
    CHECK(n == 2 && strcmp(m[1].name, "soap") == 0);
    lucent_material_derived d;
    lucent_material_derive(&m[1], &d);
    CHECK_NEAR(d.rd[0], 0.8, 1e-9);
    CHECK_NEAR(d.mfp_diffuse[2], 2.0, 1e-9);
    lucent_material_derive(&m[0], &d);
    CHECK_NEAR(d.albedo_prime[1], 0.98, 1e-12);
    CHECK_NEAR(d.mfp_prime[1], 0.8, 1e-12);
    free(m);
    lucent_material one;
    CHECK_OK(lucent_material_resolve(FIXTURE("two.json") "#SOAP", &one));
    CHECK(strcmp(one.name, "soap") == 0);
    CHECK_ERR(lucent_material_resolve(FIXTURE("two.json"), &one), LUCENT_ERR_INVALID_ARGUMENT, "two.json",
              "holds 2 materials");
}

/* Each malformed file: status, and a message naming the file and the field. */
TEST(malformed_fixtures)
{
    lucent_material *m = (lucent_material *)&m;
    int n = -1;
#define BAD(file, ...)                                                                                                 \
    CHECK_ERR(lucent_material_load(FIXTURE(file), &m, &n), LUCENT_ERR_PARSE, file, __VA_ARGS__);                       \
    CHECK(m == NULL && n == 0)
    BAD("missing_field.json", "eta: missing field");
    BAD("negative.json", "sigma_a[1]: must be >= 0", "-0.02");
    BAD("nan.json", "line 4, column 21", "(in field \"sigma_a\")",
        "not a number JSON allows"); /* NaN is not JSON: named by line, column and field */
    BAD("huge.json", "sigma_s_prime[1]: expected a finite number"); /* 1e999 reads as inf */
    BAD("wrong_type.json", "eta: expected a number, got a string");
    BAD("broken.json", "invalid JSON");
    BAD("unknown_key.json", "anisotropy: unknown field");
    BAD("no_units.json", "units: missing field");
    BAD("list_bad.json", "materials[1].sigma_s_prime[2]: must be >= 0");
#undef BAD
    CHECK_ERR(lucent_material_load(FIXTURE("absent.json"), &m, &n), LUCENT_ERR_IO, "absent.json");
}

static void bad_text(const char *text, const char *what)
{
    lucent_material *m;
    int n;
    CHECK_ERR(lucent_material_parse(text, "in.json", &m, &n), LUCENT_ERR_PARSE, "in.json: ", what);
}

TEST(malformed_text)
{
    const char *base = "\"units\":\"mm^-1\",\"eta\":1.3";
    char t[512];
#define T(fmt, what) (snprintf(t, sizeof t, fmt, base), bad_text(t, what))
    T("{%s,\"sigma_a\":[1,2,3]}", "sigma_s: missing field");
    T("{%s,\"sigma_a\":[1,2],\"sigma_s\":1}", "sigma_a: expected 3 numbers");
    T("{%s,\"sigma_a\":1,\"sigma_s\":1,\"sigma_s_prime\":1}", "not both");
    T("{%s,\"sigma_a\":1,\"sigma_s\":1,\"albedo\":0.5}", "albedo: cannot be combined with \"sigma_a\"");
    T("{%s,\"sigma_a\":0,\"sigma_s\":0}", "sigma_a + sigma_s[0]: must be > 0");
    T("{%s,\"sigma_a\":1,\"sigma_s\":1,\"g\":1}", "g: must be in (-1, 1)");
    T("{%s,\"sigma_a\":1,\"sigma_s\":null}", "sigma_s: expected 3 numbers or one number, got null");
    T("{%s}", "sigma_a: missing field");
    T("{%s,\"sigma_a\":1,\"sigma_s\":1,\"name\":\"\"}", "name: must have 1 to 63 characters");
    T("{%s,\"albedo\":0.5,\"mean_free_path\":1}", "units: expected \"mm\", \"cm\" or \"m\" with mean_free_path");
#undef T
    bad_text("{\"units\":\"mm\",\"eta\":1.3,\"diffuse_reflectance\":1,\"diffuse_mean_free_path\":1}",
             "diffuse_reflectance: must be in [0, 1), got 1");
    bad_text("{\"units\":\"mm^-1\",\"eta\":0.9,\"sigma_a\":1,\"sigma_s\":1}", "eta: must be in [1, 3], got 0.9");
    bad_text("[1, 2]", "expected an object");
    bad_text("{\"materials\": []}", "materials: expected at least one material");
    bad_text("{\"materials\": [{\"units\":\"mm^-1\",\"eta\":1.3,\"sigma_a\":1,\"sigma_s\":1}]}",
             "materials[0].name: missing field");
    bad_text("{\"materials\": "
             "[{\"name\":\"a\",\"units\":\"mm^-1\",\"eta\":1.3,\"sigma_a\":1,\"sigma_s\":1},"
             "{\"name\":\"A\",\"units\":\"mm^-1\",\"eta\":1.3,\"sigma_a\":1,\"sigma_s\":1}]}",
             "materials[1].name: \"A\" is also the name of materials[0]");
    bad_text("{\"materials\": [], \"comment\": 1}", "comment: unknown field");
}

TEST(validate)
{
    lucent_material m = preset("Apple");
    CHECK_OK(lucent_material_validate(&m));
    m.sigma_s[2] = NAN;
    CHECK_ERR(lucent_material_validate(&m), LUCENT_ERR_INVALID_ARGUMENT, "Apple: sigma_s[2]");
    m = preset("Apple");
    m.eta = 3.5;
    CHECK_ERR(lucent_material_validate(&m), LUCENT_ERR_INVALID_ARGUMENT, "Apple: eta");
}

TEST(json_round_trip)
{
    lucent_material in[2] = {preset("Marble"), preset("Ketchup")};
    in[1].g[1] = 0.7;
    char *text;
    CHECK_OK(lucent_material_to_json(in, 2, true, &text));
    lucent_material *out = NULL;
    int n = 0;
    CHECK_OK(lucent_material_parse(text, "round.json", &out, &n));
    CHECK(n == 2);
    for (int i = 0; i < n && out; i++) {
        CHECK(strcmp(out[i].name, in[i].name) == 0);
        for (int c = 0; c < 3; c++) {
            CHECK(out[i].sigma_a[c] == in[i].sigma_a[c]);
            CHECK(out[i].sigma_s[c] == in[i].sigma_s[c]);
            CHECK(out[i].g[c] == in[i].g[c]);
        }
        CHECK(out[i].eta == in[i].eta);
    }
    CHECK(strstr(text, "\"rd_dipole\""));
    free(out);
    free(text);
}

TEST_MAIN(TEST_ENTRY(rd_skin1_and_marble), TEST_ENTRY(derived_by_hand), TEST_ENTRY(rd_against_published_table),
          TEST_ENTRY(presets), TEST_ENTRY(presets_thread_safe), TEST_ENTRY(units), TEST_ENTRY(sigma_s_prime_and_g),
          TEST_ENTRY(albedo_round_trips), TEST_ENTRY(dipole_inverse), TEST_ENTRY(fixtures_that_load),
          TEST_ENTRY(malformed_fixtures), TEST_ENTRY(malformed_text), TEST_ENTRY(validate), TEST_ENTRY(json_round_trip))
