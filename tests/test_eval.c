/* Tests of the evaluation room (lucent/eval.h) that need no GL: compare's mask, reference noise and
 * error maps, kernel-eval on a tiny case, and the profile and CDRF-fit writers. Expected values
 * come from the definitions, recomputed here independently (loops over the written files), or
 * from analytic properties (area resampling keeps a kernel's energy; the CDRF at sigma = 0 is
 * Lambert). compare's run itself needs GL: tests/test_gl_eval.c. */
#include <cjson/cJSON.h>

#include "lucent/eval.h"
#include "test.h"

/* ---- compare's measures ---- */

TEST(object_mask_keeps_pixels_whose_3x3_neighbourhood_is_covered)
{
    /* 7 x 6, covered everywhere but (5, 3) at one half and (1, 1) just below the 0.999 threshold;
     * (1, 4) exactly at it. */
    lucent_image *c;
    CHECK_OK(lucent_image_create(7, 6, 1, &c));
    for (int i = 0; i < 42; i++) c->data[i] = 1;
    c->data[3 * 7 + 5] = 0.5f;
    c->data[4 * 7 + 1] = 0.999f;
    c->data[1 * 7 + 1] = 0.998f;
    float mask[42];
    uint64_t n = lucent_compare_object_mask(c, mask);
    /* Interior pixels: x 1..5, y 1..4 (20); those with (5, 3) in their 3x3: x 4..5, y 2..4 (6);
     * those with (1, 1): x 1..2, y 1..2 (4). */
    CHECK(n == 10);
    int ones = 0;
    for (int y = 0; y < 6; y++)
        for (int x = 0; x < 7; x++) {
            bool interior = x >= 1 && x <= 5 && y >= 1 && y <= 4;
            bool near_hole = (x >= 4 && y >= 2 && y <= 4) || (x <= 2 && y <= 2);
            float want = interior && !near_hole ? 1.0f : 0.0f;
            CHECK_MSG(mask[y * 7 + x] == want, "mask(%d, %d) = %g, want %g", x, y, mask[y * 7 + x], want);
            ones += mask[y * 7 + x] == 1.0f;
        }
    CHECK(ones == 10);
    lucent_image_destroy(c);
}

TEST(reference_noise_is_sqrt_of_summed_variance_over_summed_squares)
{
    lucent_image *m, *v;
    CHECK_OK(lucent_image_create(2, 1, 3, &m));
    CHECK_OK(lucent_image_create(2, 1, 3, &v));
    const float mean[6] = {1, 2, 2, 3, 0, 4}, var[6] = {0.01f, 0.02f, 0.03f, 0.5f, 0.5f, 0.5f};
    memcpy(m->data, mean, sizeof mean), memcpy(v->data, var, sizeof var);
    const float mask[2] = {1, 0};
    /* Pixel 0 only: sum var = 0.06, sum mean^2 = 1 + 4 + 4 = 9. Both: 1.56 and 9 + 9 + 16 = 34. */
    CHECK_NEAR(lucent_compare_reference_noise(m, v, mask), sqrt((0.01 + 0.02 + 0.03) / 9.0), 1e-7);
    CHECK_NEAR(lucent_compare_reference_noise(m, v, NULL), sqrt((0.06 + 1.5) / 34.0), 1e-7);
    const float none[2] = {0, 0};
    CHECK(lucent_compare_reference_noise(m, v, none) == 0);
    lucent_image_destroy(m);
    lucent_image_destroy(v);
}

/* The signed map: (2 - 1) / (1 + 0.01) = +99% (beyond the 50% scale: full orange), (0.75 - 1) / 1.01 =
 * -24.75% (blue at 24.75 / 50 of full), black outside the mask. */
TEST(error_map_is_signed_full_at_half_relative_error_and_black_outside_the_mask)
{
    lucent_image *ref, *img, *heat = NULL;
    CHECK_OK(lucent_image_create(3, 3, 3, &ref));
    CHECK_OK(lucent_image_create(3, 3, 3, &img));
    for (int i = 0; i < 27; i++) ref->data[i] = 1, img->data[i] = i / 3 == 3 ? 0.75f : 2;
    float mask[9] = {0};
    mask[4] = mask[3] = 1;
    CHECK_OK(lucent_compare_error_map(img, ref, mask, &heat));
    CHECK(heat && heat->channels == 3 && heat->width == 3 && heat->height == 3);
    float full[3], part[3];
    lucent_compare_error_colour(1.0, 0.5, full);
    lucent_compare_error_colour(-0.25 / 1.01, 0.5, part);
    CHECK(full[0] == 1.0f && full[2] == 0.0f && part[2] > part[0]); /* orange too bright, blue too dark */
    for (int p = 0; heat && p < 9; p++)
        for (int c = 0; c < 3; c++) CHECK_NEAR(heat->data[p * 3 + c], p == 4 ? full[c] : p == 3 ? part[c] : 0.0, 1e-6);
    CHECK_NEAR(part[2], 0.25 / 1.01 / 0.5, 1e-6); /* linear to full at the scale */
    lucent_image_destroy(heat);
    lucent_image_destroy(ref);
    lucent_image_destroy(img);
}

/* The worst square is where the error is: a 16 x 12 image with one wrong pixel at (11, 7) and a 4 x 4
 * window: the first window (in row order) holding it starts at (8, 4). */
TEST(worst_region_holds_the_largest_error)
{
    lucent_image *ref, *img;
    CHECK_OK(lucent_image_create(16, 12, 3, &ref));
    CHECK_OK(lucent_image_create(16, 12, 3, &img));
    for (size_t i = 0; i < 16 * 12 * 3; i++) ref->data[i] = img->data[i] = 0.5f;
    img->data[(7 * 16 + 11) * 3 + 1] = 3;
    img->data[(1 * 16 + 1) * 3 + 1] = 0.6f; /* a smaller error elsewhere */
    int x = -1, y = -1;
    CHECK_OK(lucent_compare_worst_region(img, ref, NULL, 4, &x, &y));
    CHECK(x == 8 && y == 4);
    float mask[16 * 12] = {0};
    mask[1 * 16 + 1] = 1; /* masked out, the big error does not count */
    CHECK_OK(lucent_compare_worst_region(img, ref, mask, 4, &x, &y));
    CHECK(x == 0 && y == 0);
    lucent_image_destroy(ref);
    lucent_image_destroy(img);
}

TEST(compare_refuses_a_desc_without_scenes_or_with_an_unknown_method)
{
    lucent_compare_result r;
    CHECK_ERR(lucent_compare_run(&(lucent_compare_desc){0}, &r), LUCENT_ERR_INVALID_ARGUMENT, "scene_count");
    CHECK(r.scene_count == 0 && r.scenes == NULL);
    const char *scenes[] = {"whatever.json"}, *methods[] = {"lambert", "phong"};
    CHECK_ERR(
        lucent_compare_run(
            &(lucent_compare_desc){.scenes = scenes, .scene_count = 1, .methods = methods, .method_count = 2}, &r),
        LUCENT_ERR_INVALID_ARGUMENT, "methods[1]", "phong");
    lucent_compare_desc d = lucent_compare_defaults();
    CHECK(d.frames == 5 && d.method_count == 0 && !strcmp(d.title, LUCENT_COMPARE_DEFAULT_TITLE));
    lucent_compare_result_free(&r); /* a zero result is fine */
}

/* ---- kernel-eval ---- */

TEST(kernel_eval_model_names)
{
    lucent_kernel_desc d;
    CHECK_OK(lucent_kernel_eval_model_parse("svd-norm", &d));
    CHECK(d.model == LUCENT_KERNEL_SVD && d.rank == 1 && d.normalize);
    CHECK_OK(lucent_kernel_eval_model_parse("sog-r3", &d));
    CHECK(d.model == LUCENT_KERNEL_SOG && d.rank == 3 && !d.normalize);
    CHECK_OK(lucent_kernel_eval_model_parse("guided", &d));
    CHECK(d.model == LUCENT_KERNEL_GUIDED && d.k == 1);
    CHECK_ERR(lucent_kernel_eval_model_parse("svd3", &d), LUCENT_ERR_INVALID_ARGUMENT, "unknown model 'svd3'");
    CHECK_ERR(lucent_kernel_eval_model_parse("svd-r17", &d), LUCENT_ERR_INVALID_ARGUMENT, "svd-r17");
    CHECK_ERR(lucent_kernel_eval_model_parse("sog-r", &d), LUCENT_ERR_INVALID_ARGUMENT, "sog-r");
}

TEST(kernel_eval_refuses_a_bad_desc)
{
    lucent_kernel_eval_result r;
    lucent_material m;
    CHECK_OK(lucent_material_resolve("marble", &m));
    CHECK_ERR(lucent_kernel_eval_run(&(lucent_kernel_eval_desc){0}, &r), LUCENT_ERR_INVALID_ARGUMENT, "material");
    CHECK_ERR(lucent_kernel_eval_run(&(lucent_kernel_eval_desc){.material = &m, .taps = 16}, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "taps");
    const char *bad[] = {"svd", "phong"};
    CHECK_ERR(lucent_kernel_eval_run(&(lucent_kernel_eval_desc){.material = &m, .models = bad, .model_count = 2}, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "phong");
    CHECK(r.models == NULL && r.ground_truth == NULL);
}

typedef struct events {
    int wrote, skipped;
    char skipped_name[32], reason[200];
} events;

static void count_events(const lucent_eval_event *e, void *user)
{
    events *ev = user;
    if (e->kind == LUCENT_EVAL_WROTE) ev->wrote++;
    if (e->kind == LUCENT_EVAL_SKIPPED) {
        ev->skipped++;
        snprintf(ev->skipped_name, sizeof ev->skipped_name, "%s", e->name);
        snprintf(ev->reason, sizeof ev->reason, "%s", e->reason);
    }
}

/* sqrt(mean((a - b)^2)) of channel c over every pixel, from the files. */
static double file_rms(const lucent_image *a, const lucent_image *b, int c)
{
    double sum = 0;
    size_t n = (size_t)a->width * (size_t)a->height;
    for (size_t i = 0; i < n; i++) {
        double d = (double)a->data[i * 3 + c] - b->data[i * 3 + c];
        sum += d * d;
    }
    return sqrt(sum / (double)n);
}

/* sqrt(mean((R_d - A)^2)) over the cells, A(i, j) = sum_r sign_r a_r(i) a_r(j) (cell weights). */
static double cell_rms(const lucent_kernel *k, const lucent_kernel2d *gt, int c)
{
    int n = 2 * gt->half + 1;
    double sum = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double a = 0;
            for (int r = 0; r < k->rank; r++) a += k->sign[c][r] * k->a[c][r * n + i] * k->a[c][r * n + j];
            double d = gt->value[c][(size_t)i * n + j] - a;
            sum += d * d;
        }
    return sqrt(sum / ((double)n * n));
}

/* An impulse: its exact convolution is the pixel kernel itself, whose energy is the ground
 * truth's (each channel sums to 1) because area weights of a pixel grid covering the cells sum
 * to 1 per cell. The reported RMS errors are those of the written images and of the cells. */
TEST(kernel_eval_on_an_impulse)
{
    lucent_image *imp;
    CHECK_OK(lucent_image_create(64, 64, 3, &imp));
    for (int c = 0; c < 3; c++) imp->data[(32 * 64 + 32) * 3 + c] = 1;
    char signal[600], dir[600];
    snprintf(signal, sizeof signal, "%s", test_path("impulse.exr"));
    snprintf(dir, sizeof dir, "%s", test_path("ke"));
    CHECK_OK(lucent_image_write(signal, imp, NULL));
    lucent_image_destroy(imp);
    lucent_material m;
    CHECK_OK(lucent_material_resolve("marble", &m));
    const char *models[] = {"svd-r2"};
    events ev = {0};
    lucent_kernel_eval_result r;
    CHECK_OK(lucent_kernel_eval_run(&(lucent_kernel_eval_desc){.material = &m,
                                                               .models = models,
                                                               .model_count = 1,
                                                               .signal = signal,
                                                               .mm_per_pixel = 1,
                                                               .taps = 9,
                                                               .out = dir,
                                                               .on_event = count_events,
                                                               .user = &ev},
                                    &r));
    CHECK(r.model_count == 1 && r.models[0].kernel && r.kernel_pixels < 40 && r.taps == 9 && r.table65_count == 0);
    /* signal.png, exact.png/.exr, svd-r2.png/.exr/-diff.png, the same for -taps, 4 reports: 13. */
    CHECK_MSG(ev.wrote == 13, "%d files told", ev.wrote);
    lucent_image *exact = NULL, *model = NULL;
    char path[700];
    snprintf(path, sizeof path, "%s/exact.exr", dir);
    CHECK_OK(lucent_image_load(path, &exact));
    snprintf(path, sizeof path, "%s/svd-r2.exr", dir);
    CHECK_OK(lucent_image_load(path, &model));
    for (int c = 0; exact && model && c < 3; c++) {
        double energy = 0;
        for (int i = 0; i < 64 * 64; i++) energy += exact->data[i * 3 + c];
        CHECK_NEAR(energy, 1.0, 1e-5);
        double want = file_rms(model, exact, c);
        CHECK_NEAR(r.models[0].separable.rms[c], want, 1e-9 * want + 1e-15);
        want = cell_rms(r.models[0].kernel, r.ground_truth, c);
        CHECK_NEAR(r.models[0].kernel_rms[c], want, 1e-9 * want + 1e-15);
    }
    lucent_image_destroy(exact);
    lucent_image_destroy(model);
    lucent_kernel_eval_result_free(&r);
    CHECK(r.models == NULL);
}

TEST(kernel_eval_skips_manual_without_a_preset_and_writes_nothing_without_out)
{
    lucent_material m;
    CHECK_OK(lucent_material_resolve("potato", &m));
    const char *models[] = {"manual", "preint"};
    events ev = {0};
    lucent_kernel_eval_result r;
    CHECK_OK(lucent_kernel_eval_run(&(lucent_kernel_eval_desc){.material = &m,
                                                               .models = models,
                                                               .model_count = 2,
                                                               .size = 24,
                                                               .mm_per_pixel = 1,
                                                               .no_taps = true,
                                                               .on_event = count_events,
                                                               .user = &ev},
                                    &r));
    CHECK(ev.wrote == 0 && ev.skipped == 1 && !strcmp(ev.skipped_name, "manual") && strstr(ev.reason, "Table A.1"));
    CHECK(r.model_count == 2 && !r.models[0].kernel && r.models[0].skipped[0] && r.models[1].kernel);
    CHECK(r.taps == 0 && !r.models[1].have_taps && !strcmp(r.profile, "dipole") && !strcmp(r.signal, "edge"));
    lucent_kernel_eval_result_free(&r);
}

/* ---- the profile and CDRF-fit writers ---- */

static char *read_text(const char *path)
{
    char *text = NULL;
    size_t size;
    CHECK_OK(lucent_read_file(path, &text, &size));
    return text;
}

TEST(profile_csv_and_json_hold_the_profile)
{
    lucent_material m;
    lucent_profile *p = NULL;
    CHECK_OK(lucent_material_resolve("skin1", &m));
    CHECK_OK(lucent_profile_from_source(&(lucent_profile_source_desc){.source = "dipole"}, &m, &p));
    if (!p) return;
    const char *csv = test_path("p.csv");
    CHECK_OK(lucent_profile_write_csv(csv, &m, p));
    char *text = read_text(csv), *line = text ? strchr(text, '\n') : NULL;
    CHECK(line && !strncmp(line + 1, "r_mm,R,R_se,G,G_se,B,B_se\n", 26));
    int rows = 0;
    for (line = line ? strchr(line + 1, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n'), rows++) {
        double v[7];
        CHECK(sscanf(line + 1, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6]) == 7);
        if (rows >= p->count) break;
        CHECK_NEAR(v[0], p->r[rows], 1e-8 * p->r[rows]);
        for (int c = 0; c < 3; c++) CHECK_NEAR(v[1 + 2 * c], p->value[c][rows], 1e-8 * fabs(p->value[c][rows]));
    }
    CHECK(rows == p->count);
    free(text);
    const char *json = test_path("p.json");
    lucent_sog sog;
    CHECK_OK(lucent_sog_fit(p, &(lucent_sog_desc){.count = 2}, &sog));
    CHECK_OK(lucent_profile_write_json(json, &(lucent_profile_report){.material = &m, .profile = p, .sog = &sog}));
    text = read_text(json);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    CHECK(root && cJSON_GetObjectItem(root, "bins")->valueint == p->count);
    CHECK(root &&
          cJSON_GetArraySize(cJSON_GetObjectItem(cJSON_GetObjectItemCaseSensitive(root, "R"), "value")) == p->count);
    CHECK(root && cJSON_GetObjectItem(cJSON_GetObjectItem(root, "sum_of_gaussians"), "count")->valueint == 2);
    CHECK(root && !cJSON_GetObjectItem(root, "photons_per_channel")); /* recorded for "mc" only */
    cJSON_Delete(root);
    free(text);
    CHECK_OK(lucent_profile_write_svg(test_path("p.svg"), &m, p, &sog));
    const lucent_profile *both[] = {p, p};
    CHECK_OK(lucent_profile_write_compare_svg(test_path("pc.svg"), &m, both, 2));
    lucent_profile_destroy(p);
}

/* Kubo Eq. 1-3 at sigma = 0 is Lambert: a fit with sigma0 = 0 tabulates k_d max(cos theta, 0). */
TEST(cdrf_fit_csv_tabulates_the_fitted_function)
{
    lucent_material m;
    CHECK_OK(lucent_material_resolve("marble", &m));
    lucent_cdrf_sphere_result sp[2] = {{.bins = 4, .radius = 2, .photons = 100},
                                       {.bins = 4, .radius = 5, .photons = 100}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 4; j++) {
            sp[i].theta[j] = (j + 0.5) * M_PI / 4;
            for (int c = 0; c < 3; c++) sp[i].radiance[c][j] = 0.1 * (j + 1), sp[i].radiance_se[c][j] = 0.01;
        }
    lucent_cdrf_fit fit = {.variant = LUCENT_CDRF_KUBO, .kd = {0.5, 1, 2}};
    lucent_cdrf_fit_report rep = {
        .material = &m, .spheres = sp, .sphere_count = 2, .fit = &fit, .seed = 7, .cone = 0.2, .roughness = 0.1};
    const char *csv = test_path("fit.csv");
    CHECK_OK(lucent_cdrf_fit_write_csv(csv, &rep));
    char *text = read_text(csv), *line = text ? strchr(text, '\n') : NULL; /* past the comment */
    CHECK(line && !strncmp(line + 1, "radius_mm,theta_deg,R,R_se,R_fit,G,G_se,G_fit,B,B_se,B_fit\n", 59));
    int rows = 0;
    for (line = line ? strchr(line + 1, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n'), rows++) {
        double v[11];
        int got = sscanf(line + 1, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4],
                         &v[5], &v[6], &v[7], &v[8], &v[9], &v[10]);
        CHECK(got == 11);
        if (got != 11 || rows >= 8) break;
        CHECK_NEAR(v[0], rows < 4 ? 2 : 5, 0);
        double theta = (rows % 4 + 0.5) * M_PI / 4;
        CHECK_NEAR(v[1], theta * 180 / M_PI, 1e-6);
        for (int c = 0; c < 3; c++) CHECK_NEAR(v[4 + 3 * c], fit.kd[c] * fmax(cos(theta), 0), 1e-8);
    }
    CHECK(rows == 8);
    free(text);
    CHECK_OK(lucent_cdrf_fit_write_json(test_path("fit.json"), &rep));
    text = read_text(test_path("fit.json"));
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    CHECK(root && cJSON_GetArraySize(cJSON_GetObjectItem(root, "spheres")) == 2);
    CHECK(root && cJSON_GetObjectItem(root, "seed")->valuedouble == 7);
    cJSON_Delete(root);
    free(text);
    CHECK_OK(lucent_cdrf_fit_write_svg(test_path("fit.svg"), &rep));
}

TEST_MAIN(TEST_ENTRY(object_mask_keeps_pixels_whose_3x3_neighbourhood_is_covered),
          TEST_ENTRY(reference_noise_is_sqrt_of_summed_variance_over_summed_squares),
          TEST_ENTRY(error_map_is_signed_full_at_half_relative_error_and_black_outside_the_mask),
          TEST_ENTRY(worst_region_holds_the_largest_error),
          TEST_ENTRY(compare_refuses_a_desc_without_scenes_or_with_an_unknown_method),
          TEST_ENTRY(kernel_eval_model_names), TEST_ENTRY(kernel_eval_refuses_a_bad_desc),
          TEST_ENTRY(kernel_eval_on_an_impulse),
          TEST_ENTRY(kernel_eval_skips_manual_without_a_preset_and_writes_nothing_without_out),
          TEST_ENTRY(profile_csv_and_json_hold_the_profile), TEST_ENTRY(cdrf_fit_csv_tabulates_the_fitted_function))
