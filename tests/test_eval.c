/* Tests of the evaluation room (lucent/eval.h) that need no GL: compare's mask, reference noise and
 * error maps, kernel-eval on a tiny case, and the profile and CDRF-fit writers. Expected values
 * come from the definitions, recomputed here independently (loops over the written files), or
 * from analytic properties (area resampling keeps a kernel's energy; the CDRF at sigma = 0 is
 * Lambert). compare's run itself needs GL: tests/test_gl_eval.c. */
#include <cjson/cJSON.h>

#include "eval/internal.h"
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

/* The worst 1% of the pixels' share of the squared error, worked by hand: 200 pixels of 1, the method off
 * by 0.5 in one pixel's three channels (0.75) and by 0.01 in every channel of the other 199 (3e-4
 * each): the worst 2 pixels (ceil(0.01 x 200)) hold (0.75 + 3e-4) / (0.75 + 199 x 3e-4) = 0.926296.
 * An even error: exactly the fraction. Equal images: 0. Pixels outside the mask do not count. */
TEST(concentration_is_the_worst_pixels_share_of_the_squared_error)
{
    lucent_image *ref, *img;
    CHECK_OK(lucent_image_create(20, 10, 3, &ref));
    CHECK_OK(lucent_image_create(20, 10, 3, &img));
    for (size_t i = 0; i < 200 * 3; i++) ref->data[i] = 1, img->data[i] = i < 3 ? 1.5f : 1.01f;
    double share = -1;
    CHECK_OK(lucent_compare_concentration(img, ref, NULL, 0.01, &share));
    CHECK_NEAR(share, (0.75 + 3e-4) / (0.75 + 199 * 3e-4), 1e-5);
    for (size_t i = 0; i < 3; i++) img->data[i] = 1.01f;
    CHECK_OK(lucent_compare_concentration(img, ref, NULL, 0.05, &share));
    CHECK_NEAR(share, 0.05, 1e-9);
    CHECK_OK(lucent_compare_concentration(ref, ref, NULL, 0.01, &share));
    CHECK(share == 0);
    float mask[200] = {0};
    mask[5] = mask[6] = 1;
    img->data[0] = 100; /* outside the mask */
    img->data[5 * 3] = 1.11f;
    CHECK_OK(lucent_compare_concentration(img, ref, mask, 0.01, &share)); /* one of two pixels */
    CHECK_NEAR(share, (0.0121 + 2e-4) / (0.0121 + 2e-4 + 3e-4), 1e-4);
    CHECK(lucent_compare_concentration(img, ref, NULL, 0, &share) == LUCENT_ERR_INVALID_ARGUMENT);
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

/* ---- compare's paired test ---- */

/* A standard normal draw (Box-Muller). */
static double normal(lucent_rng *g)
{
    double u = lucent_rng_uniform(g), v = lucent_rng_uniform(g);
    return sqrt(-2 * log(u > 0 ? u : 1e-300)) * cos(2 * M_PI * v);
}

enum { PT_W = 96, PT_H = 96 };

/* The truth of the synthetic scene: smooth, positive, different per channel. */
static double truth(int x, int y, int c) { return 1 + 0.5 * sin(0.2 * x + c) * cos(0.15 * y - c); }

/* dest = truth * (1 + scale) */
static void scaled_truth(lucent_image *dest, double scale)
{
    for (int y = 0; y < PT_H; y++)
        for (int x = 0; x < PT_W; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(dest, x, y, c, (float)(truth(x, y, c) * (1 + scale)));
}

/* A reference: the truth plus noise of relative standard deviation sd, drawn once per block x block
 * pixels (block 1: independent pixels; larger: one draw shared by a block, as light paths share a
 * photon among many pixels), and the per-pixel variance the tracer would report (sd^2 truth^2). */
static void noisy_reference(lucent_image *ref, lucent_image *var, double sd, int block, uint64_t seed)
{
    lucent_rng g;
    lucent_rng_init(seed, 0, &g);
    double draw[PT_H][PT_W][3];
    for (int by = 0; by < PT_H; by += block)
        for (int bx = 0; bx < PT_W; bx += block)
            for (int c = 0; c < 3; c++) {
                double z = normal(&g);
                for (int y = by; y < by + block && y < PT_H; y++)
                    for (int x = bx; x < bx + block && x < PT_W; x++) draw[y][x][c] = z;
            }
    for (int y = 0; y < PT_H; y++)
        for (int x = 0; x < PT_W; x++)
            for (int c = 0; c < 3; c++) {
                double t = truth(x, y, c);
                lucent_image_set(ref, x, y, c, (float)(t + sd * t * draw[y][x][c]));
                lucent_image_set(var, x, y, c, (float)(sd * t * sd * t));
            }
}

/* Acceptance (issue 31): two methods 3% apart from the truth, against a reference with 5% noise of
 * its own, are told apart by the paired test, while the older rule (net errors within the noise of
 * each other tie) cannot; two identical methods are not told apart. Expected values from the
 * definitions: d = sum (a - r)^2 - (b - r)^2 over sum r^2 and, for a = 1.03 t, b = t,
 * E[d] = 0.03^2 sum t^2 / sum r^2, se = 2 sqrt(sum (0.03 t)^2 (0.05 t)^2) / sum r^2. */
TEST(paired_test_separates_methods_a_known_amount_apart_and_not_identical_ones)
{
    lucent_image *a, *b, *ref, *var;
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &a));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &b));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &ref));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &var));
    scaled_truth(a, 0.03), scaled_truth(b, 0);
    noisy_reference(ref, var, 0.05, 1, 7);
    double t2 = 0, t4 = 0, r2 = 0;
    for (int y = 0; y < PT_H; y++)
        for (int x = 0; x < PT_W; x++)
            for (int c = 0; c < 3; c++) {
                double t = truth(x, y, c), r = lucent_image_get(ref, x, y, c);
                t2 += t * t, t4 += t * t * t * t, r2 += r * r;
            }
    lucent_compare_pair p;
    CHECK_OK(lucent_compare_paired(a, b, ref, var, NULL, 0, &p));
    double se = 2 * sqrt(0.03 * 0.03 * 0.05 * 0.05 * t4) / r2, mean = 0.03 * 0.03 * t2 / r2;
    CHECK_NEAR(p.se, se, 1e-3 * se); /* the standard error: float images */
    CHECK_MSG(fabs(p.d - mean) < 4 * se, "d %g, expected %g +- %g", p.d, mean, se); /* within its noise */
    CHECK_MSG(p.z > 20 && lucent_compare_separated(&p), "z %g", p.z); /* E[z] = 0.03 sqrt(t2^2/t4) / 0.1 ~ 34 */
    /* the same two as report rows: the paired test ranks them 1, 2; the noise rule ties them */
    lucent_image_error_stats ea, eb;
    CHECK_OK(lucent_image_compare(a, ref, NULL, &ea));
    CHECK_OK(lucent_image_compare(b, ref, NULL, &eb));
    lucent_compare_method m[2] = {{.name = "b", .rel_rms = eb.rel_rms_all}, {.name = "a", .rel_rms = ea.rel_rms_all}};
    double pair_se[4] = {0, p.se, p.se, 0};
    lucent_compare_scene sc = {.name = "synthetic",
                               .reference_spp = 64,
                               .reference_noise = lucent_compare_reference_noise(ref, var, NULL),
                               .methods = m,
                               .method_count = 2};
    int order[2], rank[2];
    CHECK(lucent_compare_rank(&sc, order, rank) && rank[0] == 1 && rank[1] == 1); /* the older rule: a tie */
    sc.pair_se = pair_se;
    CHECK(lucent_compare_rank(&sc, order, rank) && order[0] == 0 && rank[0] == 1 && rank[1] == 2);
    CHECK_NEAR(lucent_compare_pair_z(&sc, 1, 0),
               ea.rel_rms_all * ea.rel_rms_all / p.se - eb.rel_rms_all * eb.rel_rms_all / p.se, 1e-9 * fabs(p.z));
    /* identical methods: no difference, no noise in it, no separation */
    CHECK_OK(lucent_compare_paired(b, b, ref, var, NULL, 0, &p));
    CHECK(p.d == 0 && p.se == 0 && p.z == 0 && !lucent_compare_separated(&p));
    m[1].rel_rms = m[0].rel_rms, pair_se[1] = pair_se[2] = 0;
    CHECK(lucent_compare_rank(&sc, order, rank) && rank[0] == 1 && rank[1] == 1);
    lucent_image_destroy(a), lucent_image_destroy(b), lucent_image_destroy(ref), lucent_image_destroy(var);
}

/* Over 200 references with independent pixel noise, two methods of equal true error (t (1 + 3%) and
 * t (1 - 3%)) give z of mean 0 and variance 1 (the standard error is right); with the noise shared by
 * 4 x 4 blocks of pixels (one draw, as a photon's light lands in many pixels) the per-pixel standard
 * error understates it by sqrt(16) (E[z^2] = 16 exactly for these weights: a block's 16 equal draws
 * add their weights' sum squared), and the calibration on two independent runs finds that factor,
 * after which z^2 averages 1 again. Tolerances: the mean of 200 chi-square(1) draws has a standard
 * deviation of sqrt(2 / 200) = 0.1 (3 of them: 0.3); each inflation estimate sums 144 blocks of 8 x 8
 * pixels (relative spread about sqrt(2 / 144) = 12%, so the calibrated z is a t with about 144
 * degrees of freedom, E[z^2] = 1.01). Measured: 0.89, -0.05, 15.2, 16.0, 0.92. */
TEST(paired_test_standard_error_is_calibrated_by_two_runs_where_pixels_share_noise)
{
    lucent_image *a, *b, *ref, *var, *r2, *v2;
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &a));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &b));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &ref));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &var));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &r2));
    CHECK_OK(lucent_image_create(PT_W, PT_H, 3, &v2));
    scaled_truth(a, 0.03), scaled_truth(b, -0.03);
    enum { TRIALS = 200 };
    double z2_free = 0, z_free = 0, z2_shared = 0, z2_calibrated = 0, kappa_sum = 0;
    for (int k = 0; k < TRIALS; k++) {
        lucent_compare_pair p;
        noisy_reference(ref, var, 0.05, 1, 100 + (uint64_t)k);
        CHECK_OK(lucent_compare_paired(a, b, ref, var, NULL, 0, &p));
        z2_free += p.z * p.z, z_free += p.z;
        noisy_reference(ref, var, 0.05, 4, 1000 + (uint64_t)k);
        CHECK_OK(lucent_compare_paired(a, b, ref, var, NULL, 0, &p));
        z2_shared += p.z * p.z;
        /* two independent runs of the shared-noise reference; the test uses their mean */
        noisy_reference(r2, v2, 0.05, 4, 5000 + (uint64_t)k);
        const lucent_image *images[2] = {a, b};
        double kappa;
        CHECK_OK(lucent_compare_noise_inflation(images, 2, ref, var, r2, v2, NULL, 8, &kappa));
        kappa_sum += kappa;
        lucent_image *mean, *mvar;
        CHECK_OK(lucent_image_clone(ref, &mean));
        CHECK_OK(lucent_image_clone(var, &mvar));
        for (size_t i = 0; i < (size_t)PT_W * PT_H * 3; i++)
            mean->data[i] = 0.5f * (ref->data[i] + r2->data[i]), mvar->data[i] = 0.25f * (var->data[i] + v2->data[i]);
        CHECK_OK(lucent_compare_paired(a, b, mean, mvar, NULL, kappa, &p));
        z2_calibrated += p.z * p.z;
        lucent_image_destroy(mean), lucent_image_destroy(mvar);
    }
    z2_free /= TRIALS, z_free /= TRIALS, z2_shared /= TRIALS, z2_calibrated /= TRIALS, kappa_sum /= TRIALS;
    CHECK_MSG(fabs(z2_free - 1) < 0.3 && fabs(z_free) < 0.25, "independent pixels: E[z^2] %g, E[z] %g", z2_free,
              z_free);
    CHECK_MSG(z2_shared > 10 && z2_shared < 22, "shared noise, per-pixel se: E[z^2] %g, expected 16", z2_shared);
    CHECK_MSG(fabs(kappa_sum - 16) < 2, "inflation %g, expected 16", kappa_sum);
    CHECK_MSG(fabs(z2_calibrated - 1) < 0.35, "calibrated: E[z^2] %g, expected 1", z2_calibrated);
    lucent_image_destroy(a), lucent_image_destroy(b), lucent_image_destroy(ref), lucent_image_destroy(var);
    lucent_image_destroy(r2), lucent_image_destroy(v2);
}

/* A region's measures from their definitions: two regions (left and right halves), a method 10% too
 * bright on the left and exact on the right. */
TEST(region_measures_follow_their_definitions)
{
    lucent_image *ref, *img, *var;
    CHECK_OK(lucent_image_create(4, 2, 3, &ref));
    CHECK_OK(lucent_image_create(4, 2, 3, &img));
    CHECK_OK(lucent_image_create(4, 2, 3, &var));
    uint8_t bits[8];
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 4; x++) {
            bits[y * 4 + x] = x < 2 ? 1u << LUCENT_COMPARE_REGION_LIT : 1u << LUCENT_COMPARE_REGION_TERMINATOR;
            for (int c = 0; c < 3; c++) {
                float r = x < 2 ? 2.0f : 1.0f;
                lucent_image_set(ref, x, y, c, r);
                lucent_image_set(img, x, y, c, x < 2 ? 1.1f * r : r);
                lucent_image_set(var, x, y, c, 0.04f);
            }
        }
    lucent_compare_region_values v;
    CHECK_OK(lucent_compare_region_measure(bits, LUCENT_COMPARE_REGION_LIT, NULL, ref, var, img, &v));
    CHECK(v.pixels == 4);
    CHECK_NEAR(v.rel_rms, 0.1, 1e-6);
    CHECK_NEAR(v.ratio, 1.1, 1e-6);
    CHECK_NEAR(v.error_share, 1.0, 1e-12);   /* all of the error is on the left */
    CHECK_NEAR(v.energy, 16.0 / 20.0, 1e-6); /* 12 values of 4 against 12 of 1 */
    CHECK_NEAR(v.reference_noise, sqrt(0.04 / 4.0), 1e-6);
    CHECK_OK(lucent_compare_region_measure(bits, LUCENT_COMPARE_REGION_TERMINATOR, NULL, ref, var, img, &v));
    CHECK(v.pixels == 4 && v.rel_rms == 0 && v.error_share == 0);
    CHECK_OK(lucent_compare_region_measure(bits, LUCENT_COMPARE_REGION_CONVEX, NULL, ref, var, img, &v));
    CHECK(v.pixels == 0 && isnan(v.rel_rms));
    CHECK(!strcmp(lucent_compare_region_name(LUCENT_COMPARE_REGION_SILHOUETTE), "silhouette band"));
    CHECK(lucent_compare_region_name(LUCENT_COMPARE_REGION_COUNT) == NULL);
    lucent_image_destroy(ref), lucent_image_destroy(img), lucent_image_destroy(var);
}

/* ---- compare's reused reference: reference.json ---- */

/* Replaces the first `from` in text by `to` (into a static buffer). */
static const char *edited(const char *text, const char *from, const char *to)
{
    static char buf[8192];
    const char *at = strstr(text, from);
    if (!at) return text;
    snprintf(buf, sizeof buf, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    return buf;
}

/* The reference.json a run wrote (tests/fixtures/compare: the test sphere, 16 spp) reads back; a
 * malformed one, or one made of another scene, is refused with the file and the field named. */
TEST(reference_json_reads_back_and_refuses_what_does_not_match)
{
    char scene_path[600], ref_path[600];
    snprintf(scene_path, sizeof scene_path, "%s/tests/fixtures/scenes/sphere.json", LUCENT_SOURCE_DIR);
    snprintf(ref_path, sizeof ref_path, "%s/tests/fixtures/compare/reference.json", LUCENT_SOURCE_DIR);
    lucent_scene *scene = NULL;
    CHECK_OK(lucent_scene_load(scene_path, &(lucent_scene_load_desc){.skip_meshes = true}, &scene));
    char *text = NULL;
    size_t size;
    CHECK_OK(lucent_read_file(ref_path, &text, &size));
    if (!scene || !text) return;
    eval_reference r;
    CHECK_OK(eval_reference_parse(text, "r.json", scene, &r));
    CHECK(r.runs == 1 && r.result.spp == 16 && r.result.samples == 30720 && r.result.seed == 1);
    CHECK_ERR(eval_reference_parse(edited(text, "\"runs\":\t1", "\"runs\":\t3"), "r.json", scene, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "r.json", "runs", "must be 1 or 2, got 3");
    CHECK_ERR(eval_reference_parse(edited(text, "\"runs\":\t1", "\"runs\":\t2"), "r.json", scene, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "run_results", "expected 2 runs, got 0");
    CHECK_ERR(eval_reference_parse(edited(text, "\"spp\":\t16", "\"spp\":\t-1"), "r.json", scene, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "result.spp", "got -1");
    CHECK_ERR(eval_reference_parse(edited(text, "\"spp\":\t16", "\"spp\":\t\"x\""), "r.json", scene, &r),
              LUCENT_ERR_PARSE, "result.spp");
    CHECK_ERR(eval_reference_parse(edited(text, "\"skin1\"", "\"skin2\""), "r.json", scene, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "r.json: objects[0].material: the reference was made with \"skin2\"",
              "has \"skin1\"");
    CHECK_ERR(eval_reference_parse(edited(text, "\"48\"", "\"96\""), "r.json", scene, &r), LUCENT_ERR_INVALID_ARGUMENT,
              "render.width", "\"96\"", "\"48\"");
    CHECK_ERR(eval_reference_parse(edited(text, "\"intensity\":\t3", "\"power\":\t3"), "r.json", scene, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "lights[0].power");
    /* the fixture predates render.interreflection: it was traced with its default (on), which the scene
     * holds (the parse above), and not with it off */
    CHECK(!strstr(text, "interreflection"));
    scene->render.trace.interreflection = false;
    CHECK_ERR(eval_reference_parse(text, "r.json", scene, &r), LUCENT_ERR_INVALID_ARGUMENT, "render.interreflection",
              "the reference was made with nothing", "\"false\"");
    scene->render.trace.interreflection = true;
    char truncated[64];
    snprintf(truncated, sizeof truncated, "%.40s", text);
    CHECK(eval_reference_parse(truncated, "r.json", scene, &r) != LUCENT_OK && strstr(lucent_last_error(), "r.json"));
    CHECK_ERR(eval_reference_parse("[]", "r.json", scene, &r), LUCENT_ERR_PARSE, "r.json");
    /* the images beside it are read too: a folder without them names the first missing */
    char dir[600];
    snprintf(dir, sizeof dir, "%s/tests/fixtures/compare", LUCENT_SOURCE_DIR);
    CHECK_ERR(eval_reference_read(dir, scene, &r), LUCENT_ERR_IO, "compare/reference.exr");
    free(text);
    lucent_scene_destroy(scene);
}

TEST_MAIN(TEST_ENTRY(object_mask_keeps_pixels_whose_3x3_neighbourhood_is_covered),
          TEST_ENTRY(paired_test_separates_methods_a_known_amount_apart_and_not_identical_ones),
          TEST_ENTRY(paired_test_standard_error_is_calibrated_by_two_runs_where_pixels_share_noise),
          TEST_ENTRY(region_measures_follow_their_definitions),
          TEST_ENTRY(reference_json_reads_back_and_refuses_what_does_not_match),
          TEST_ENTRY(reference_noise_is_sqrt_of_summed_variance_over_summed_squares),
          TEST_ENTRY(error_map_is_signed_full_at_half_relative_error_and_black_outside_the_mask),
          TEST_ENTRY(worst_region_holds_the_largest_error),
          TEST_ENTRY(concentration_is_the_worst_pixels_share_of_the_squared_error),
          TEST_ENTRY(compare_refuses_a_desc_without_scenes_or_with_an_unknown_method),
          TEST_ENTRY(kernel_eval_model_names), TEST_ENTRY(kernel_eval_refuses_a_bad_desc),
          TEST_ENTRY(kernel_eval_on_an_impulse),
          TEST_ENTRY(kernel_eval_skips_manual_without_a_preset_and_writes_nothing_without_out),
          TEST_ENTRY(profile_csv_and_json_hold_the_profile), TEST_ENTRY(cdrf_fit_csv_tabulates_the_fitted_function))
