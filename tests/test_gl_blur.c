/* GL tests (label gl): the screen-space separable blur on the GPU (blur.frag.glsl through
 * lucent_ssss_blur_gl) against its CPU reference (lucent_ssss_blur_cpu), and the CPU reference
 * against the kernel module's own tap convolution. Runs on llvmpipe. */
#include <math.h>

#include "lucent/convolve.h"
#include "lucent/render.h"
#include "test.h"

static lucent_gl_context *g_ctx;

static lucent_gl_context *context(void)
{
    if (!g_ctx) CHECK_OK(lucent_gl_create(NULL, &g_ctx));
    return g_ctx;
}

/* Taps of a preset material's kernel (dipole profile). */
static lucent_taps *make_taps(const char *material, lucent_kernel_model model, int rank, int count)
{
    lucent_material m;
    lucent_profile *p = NULL;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    lucent_taps *t = NULL;
    lucent_kernel_desc kd = lucent_kernel_defaults(model);
    kd.rank = rank;
    CHECK_OK(lucent_material_preset_find(material, &m));
    CHECK_OK(lucent_profile_from_source(NULL, &m, &p));
    if (p) CHECK_OK(lucent_kernel2d_from_profile(p, NULL, &gt));
    if (gt) CHECK_OK(lucent_kernel_build(gt, p, m.name, &kd, &k));
    if (k) CHECK_OK(lucent_kernel_taps(k, &(lucent_taps_desc){.count = count}, &t));
    lucent_kernel_destroy(k);
    lucent_kernel2d_destroy(gt);
    lucent_profile_destroy(p);
    return t;
}

/* A synthetic frame: the shapes signal as irradiance; depth a tilted plane (100 mm plus a slope),
 * a step of 25 mm on the right third, background (0) in the top-left corner; two materials split
 * along a diagonal. */
typedef struct frame {
    lucent_image *irr, *depth;
    uint8_t *material;
} frame;

static frame make_frame(int w, int h)
{
    frame f = {0};
    CHECK_OK(lucent_signal_shapes(w, h, &f.irr));
    CHECK_OK(lucent_image_create(w, h, 1, &f.depth));
    f.material = calloc((size_t)w * (size_t)h, 1);
    for (int y = 0; f.depth && y < h; y++)
        for (int x = 0; x < w; x++) {
            double z = 100 + 0.3 * x + 0.1 * y + (x > 2 * w / 3 ? 25 : 0);
            if (x < w / 6 && y < h / 6) z = 0;
            lucent_image_set(f.depth, x, y, 0, (float)z);
            f.material[(size_t)y * (size_t)w + (size_t)x] = x + y > w ? 1 : 0;
        }
    return f;
}

static void free_frame(frame *f)
{
    lucent_image_destroy(f->irr);
    lucent_image_destroy(f->depth);
    free(f->material);
}

static double max_difference(const lucent_image *a, const lucent_image *b)
{
    double d = 0;
    for (size_t i = 0; i < lucent_image_value_count(a); i++) d = fmax(d, fabs(a->data[i] - b->data[i]));
    return d;
}

/* Expected: lucent_ssss_blur_cpu, the double-precision reference written apart from the shader. */
static void compare_gpu_cpu(const lucent_taps *const *taps, int materials, lucent_depth_filter filter, double *worst)
{
    frame f = make_frame(96, 80);
    lucent_image *gpu = NULL, *cpu = NULL;
    lucent_ssss_blur_desc d = {.taps = taps,
                               .material_count = materials,
                               .filter = filter,
                               .pixel_scale = 80 / (2 * tan(15 * M_PI / 180)),
                               .width_scale = 1.5};
    CHECK_OK(lucent_image_create(96, 80, 3, &gpu));
    CHECK_OK(lucent_image_create(96, 80, 3, &cpu));
    if (gpu && cpu && f.irr) {
        CHECK_OK(lucent_ssss_blur_cpu(f.irr, f.depth, materials > 1 ? f.material : NULL, &d, NULL, cpu));
        CHECK_OK(lucent_ssss_blur_gl(context(), f.irr, f.depth, materials > 1 ? f.material : NULL, &d, gpu));
        double diff = max_difference(gpu, cpu);
        CHECK_MSG(diff <= 1e-3, "filter %d, %d material(s), rank %d: max |GPU - CPU| = %.3g", filter, materials,
                  taps[0]->rank, diff);
        *worst = fmax(*worst, diff);
        lucent_image_stats st;
        lucent_image_stats_compute(cpu, &st);
        CHECK(st.max[0] > 0.5 && st.nonfinite[0] == 0); /* the signal survives, no NaN */
    }
    lucent_image_destroy(gpu);
    lucent_image_destroy(cpu);
    free_frame(&f);
}

TEST(blur_gpu_equals_cpu_reference)
{
    lucent_taps *skin = make_taps("skin1", LUCENT_KERNEL_PREINT, 1, 17);
    lucent_taps *marble = make_taps("marble", LUCENT_KERNEL_PREINT, 1, 17);
    lucent_taps *svd = make_taps("skin1", LUCENT_KERNEL_SVD, 3, 25);
    double worst = 0;
    if (skin && marble && svd) {
        const lucent_taps *two[2] = {skin, marble}, *one[1] = {svd};
        for (int f = LUCENT_DEPTH_FOLLOW; f <= LUCENT_DEPTH_NONE; f++) {
            compare_gpu_cpu(two, 2, (lucent_depth_filter)f, &worst);
            compare_gpu_cpu(one, 1, (lucent_depth_filter)f, &worst);
        }
    }
    printf("     blur: max |GPU - CPU| = %.3g over 3 filters x (2 materials, rank 3)\n", worst);
    lucent_taps_destroy(skin);
    lucent_taps_destroy(marble);
    lucent_taps_destroy(svd);
}

/* The reference itself, checked against the kernel module's lucent_convolve_taps (written for the
 * kernel issue): at constant depth with no depth filter the two are the same two-pass tap sum. */
TEST(blur_reference_equals_convolve_taps)
{
    lucent_taps *t = make_taps("skin1", LUCENT_KERNEL_SVD, 2, 17);
    frame f = make_frame(64, 48);
    lucent_image *ref = NULL, *conv = NULL;
    CHECK_OK(lucent_image_create(64, 48, 3, &ref));
    CHECK_OK(lucent_image_create(64, 48, 3, &conv));
    if (t && ref && conv && f.irr) {
        lucent_image_fill(f.depth, 0, 120);
        double scale = 48 / (2 * tan(10 * M_PI / 180)), step = scale / 120;
        float off[LUCENT_KERNEL_MAX_TAPS], *w[3], sign[3][LUCENT_KERNEL_MAX_RANK];
        for (int k = 0; k < t->count; k++) off[k] = (float)(t->offset[k] * step);
        for (int c = 0; c < 3; c++) {
            w[c] = malloc((size_t)(t->rank * t->count) * sizeof *w[c]);
            for (int i = 0; i < t->rank * t->count; i++) w[c][i] = (float)t->weight[c][i];
            for (int p = 0; p < t->rank; p++) sign[c][p] = (float)t->sign[c][p];
        }
        lucent_conv_taps ct = {.count = t->count,
                               .rank = t->rank,
                               .offsets = off,
                               .weights = {w[0], w[1], w[2]},
                               .sign = {sign[0], sign[1], sign[2]}};
        lucent_image *rgb = NULL;
        CHECK_OK(lucent_image_convert_channels(f.irr, 3, &rgb));
        CHECK_OK(lucent_convolve_taps(rgb, &ct, LUCENT_BORDER_CLAMP, NULL, conv));
        const lucent_taps *one[1] = {t};
        lucent_ssss_blur_desc d = {.taps = one, .material_count = 1, .pixel_scale = scale, .filter = LUCENT_DEPTH_NONE};
        CHECK_OK(lucent_ssss_blur_cpu(f.irr, f.depth, NULL, &d, NULL, ref));
        double diff = max_difference(ref, conv);
        CHECK_MSG(diff <= 1e-5, "reference vs lucent_convolve_taps: %.3g", diff);
        for (int c = 0; c < 3; c++) free(w[c]);
        lucent_image_destroy(rgb);
    }
    lucent_image_destroy(ref);
    lucent_image_destroy(conv);
    free_frame(&f);
    lucent_taps_destroy(t);
}

/* Depth awareness: at a 25 mm step the follow-surface and Gaussian filters keep the far side's
 * light out (the expected values are the unblurred input on a flat region and, across the step,
 * less leakage than without a filter). */
TEST(blur_depth_filters_stop_leaks)
{
    lucent_taps *t = make_taps("marble", LUCENT_KERNEL_PREINT, 1, 25);
    lucent_image *irr = NULL, *depth = NULL, *out = NULL;
    CHECK_OK(lucent_image_create(64, 8, 3, &irr));
    CHECK_OK(lucent_image_create(64, 8, 1, &depth));
    CHECK_OK(lucent_image_create(64, 8, 3, &out));
    if (t && irr && depth && out) {
        for (int y = 0; y < 8; y++)
            for (int x = 0; x < 64; x++) {
                lucent_image_set(depth, x, y, 0, x < 32 ? 100.0f : 60.0f); /* near bright right half */
                for (int c = 0; c < 3; c++) lucent_image_set(irr, x, y, c, x < 32 ? 0.0f : 1.0f);
            }
        const lucent_taps *one[1] = {t};
        double leak[3];
        for (int f = 0; f < 3; f++) {
            lucent_ssss_blur_desc d = {
                .taps = one, .material_count = 1, .pixel_scale = 200, .filter = (lucent_depth_filter)f};
            CHECK_OK(lucent_ssss_blur_cpu(irr, depth, NULL, &d, NULL, out));
            leak[f] = lucent_image_get(out, 30, 4, 0);
        }
        CHECK_MSG(leak[LUCENT_DEPTH_NONE] > 0.01, "no filter: light crosses the step (%.3g)", leak[LUCENT_DEPTH_NONE]);
        CHECK_MSG(leak[LUCENT_DEPTH_FOLLOW] < 1e-6, "follow: no light across a step wider than R (%.3g)",
                  leak[LUCENT_DEPTH_FOLLOW]);
        CHECK_MSG(leak[LUCENT_DEPTH_GAUSSIAN] < 0.01 * leak[LUCENT_DEPTH_NONE], "gaussian: leak %.3g vs %.3g",
                  leak[LUCENT_DEPTH_GAUSSIAN], leak[LUCENT_DEPTH_NONE]);
    }
    lucent_image_destroy(irr);
    lucent_image_destroy(depth);
    lucent_image_destroy(out);
    lucent_taps_destroy(t);
}

static void cleanup(void) { lucent_gl_destroy(g_ctx); }

int main(int argc, char **argv)
{
    static const test_case cases[] = {TEST_ENTRY(blur_gpu_equals_cpu_reference),
                                      TEST_ENTRY(blur_reference_equals_convolve_taps),
                                      TEST_ENTRY(blur_depth_filters_stop_leaks)};
    int rc = test_run(cases, (int)(sizeof cases / sizeof cases[0]), argc, argv);
    cleanup();
    return rc;
}
