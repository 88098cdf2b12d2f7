/* Pre-integration is exact for additively separable signals (Freude 2014, Eq. 5.15): for a
 * vertical edge, a horizontal edge and their sum, the separable convolution with the
 * pre-integrated model equals the exact 2-D convolution with the ground-truth kernel.
 * Why: a vertical edge's image depends only on the kernel's marginal along x, and the model's
 * 1-D kernel is that marginal (with the other factor summing to 1); by linearity the same
 * holds for sums of vertical and horizontal edges. Expected: equality up to float rounding
 * (the issue asks for 1e-5). */
#include "lucent/convolve.h"
#include "lucent/kernel.h"
#include "lucent/profile.h"
#include "test.h"

enum { SIGNAL_VERTICAL, SIGNAL_HORIZONTAL, SIGNAL_SUM };

/* A size x size RGB image: 1 left of the middle column (vertical edge), above the middle row
 * (horizontal edge), or both added. */
static lucent_image *edge_signal(int size, int kind)
{
    lucent_image *img = NULL;
    if (lucent_image_create(size, size, 3, &img) != LUCENT_OK) return NULL;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            float v = (kind != SIGNAL_HORIZONTAL && x < size / 2 ? 1.0f : 0.0f) +
                      (kind != SIGNAL_VERTICAL && y < size / 2 ? 1.0f : 0.0f);
            for (int c = 0; c < 3; c++) lucent_image_set(img, x, y, c, v);
        }
    return img;
}

static double max_difference(const lucent_image *a, const lucent_image *b)
{
    double m = 0;
    size_t n = (size_t)a->width * (size_t)a->height * (size_t)a->channels;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs((double)a->data[i] - (double)b->data[i]));
    return m;
}

/* Convolves each signal both ways on the kernel's own cell grid (one cell = one pixel). */
static void check_material(const char *name)
{
    lucent_material m;
    lucent_profile *p = NULL;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    CHECK_OK(lucent_material_preset_find(name, &m));
    CHECK_OK(lucent_profile_dipole(&m, NULL, &p));
    CHECK_OK(lucent_kernel2d_from_profile(p, NULL, &gt));
    lucent_kernel_desc desc = lucent_kernel_defaults(LUCENT_KERNEL_PREINT);
    CHECK_OK(lucent_kernel_build(gt, p, name, &desc, &k));
    if (!gt || !k) return;
    int n = 2 * gt->half + 1;
    float *k2[3], *k1[3];
    for (int c = 0; c < 3; c++) {
        k2[c] = malloc((size_t)n * (size_t)n * sizeof(float));
        k1[c] = malloc((size_t)n * sizeof(float));
        for (int i = 0; i < n * n; i++) k2[c][i] = (float)gt->value[c][i];
        for (int i = 0; i < n; i++) k1[c][i] = (float)k->a[c][i];
    }
    lucent_conv_kernel2d kernel = {.size = n, .w = {k2[0], k2[1], k2[2]}};
    for (int kind = SIGNAL_VERTICAL; kind <= SIGNAL_SUM; kind++) {
        lucent_image *src = edge_signal(n + 40, kind), *exact = NULL, *separable = NULL;
        CHECK_OK(lucent_image_create(src->width, src->height, 3, &exact));
        CHECK_OK(lucent_image_create(src->width, src->height, 3, &separable));
        CHECK_OK(lucent_convolve_2d(src, &kernel, LUCENT_BORDER_CLAMP, NULL, exact));
        CHECK_OK(lucent_convolve_separable(src, (const float *const *)k1, NULL, n,
                                           LUCENT_BORDER_CLAMP, NULL, separable));
        double d = max_difference(exact, separable);
        CHECK_MSG(d <= 1e-5, "%s, signal %d: max |separable - exact| = %.3g", name, kind, d);
        printf("  %s signal %d (%dx%d kernel): max difference %.2g\n", name, kind, n, n, d);
        lucent_image_destroy(src);
        lucent_image_destroy(exact);
        lucent_image_destroy(separable);
    }
    for (int c = 0; c < 3; c++) free(k2[c]), free(k1[c]);
    lucent_kernel_destroy(k);
    lucent_kernel2d_destroy(gt);
    lucent_profile_destroy(p);
}

TEST(preint_exact_for_additively_separable_signals)
{
    check_material("Skin1");
    check_material("Marble");
}

/* A control: on a signal that is not additively separable (a bright square), the
 * pre-integrated kernel is not exact, so the test above could fail. */
TEST(preint_not_exact_for_a_square)
{
    lucent_material m;
    lucent_profile *p = NULL;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    CHECK_OK(lucent_material_preset_find("Skin1", &m));
    CHECK_OK(lucent_profile_dipole(&m, NULL, &p));
    CHECK_OK(lucent_kernel2d_from_profile(p, NULL, &gt));
    lucent_kernel_desc desc = lucent_kernel_defaults(LUCENT_KERNEL_PREINT);
    CHECK_OK(lucent_kernel_build(gt, p, "Skin1", &desc, &k));
    int n = 2 * gt->half + 1, size = n + 40;
    float *k2 = malloc((size_t)n * (size_t)n * sizeof(float)), *k1 = malloc((size_t)n * sizeof(float));
    for (int i = 0; i < n * n; i++) k2[i] = (float)gt->value[0][i];
    for (int i = 0; i < n; i++) k1[i] = (float)k->a[0][i];
    lucent_image *src = NULL, *exact = NULL, *separable = NULL;
    CHECK_OK(lucent_image_create(size, size, 1, &src));
    for (int y = size / 3; y < 2 * size / 3; y++)
        for (int x = size / 3; x < 2 * size / 3; x++) lucent_image_set(src, x, y, 0, 1.0f);
    CHECK_OK(lucent_image_create(size, size, 1, &exact));
    CHECK_OK(lucent_image_create(size, size, 1, &separable));
    lucent_conv_kernel2d kernel = {.size = n, .w = {k2, NULL, NULL}};
    const float *kx[3] = {k1, k1, k1};
    CHECK_OK(lucent_convolve_2d(src, &kernel, LUCENT_BORDER_CLAMP, NULL, exact));
    CHECK_OK(lucent_convolve_separable(src, kx, NULL, n, LUCENT_BORDER_CLAMP, NULL, separable));
    CHECK(max_difference(exact, separable) > 1e-3);
    lucent_image_destroy(src);
    lucent_image_destroy(exact);
    lucent_image_destroy(separable);
    free(k2);
    free(k1);
    lucent_kernel_destroy(k);
    lucent_kernel2d_destroy(gt);
    lucent_profile_destroy(p);
}

TEST_MAIN(TEST_ENTRY(preint_exact_for_additively_separable_signals),
          TEST_ENTRY(preint_not_exact_for_a_square))
