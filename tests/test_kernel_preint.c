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

/* The dipole ground truth of a preset and its pre-integrated model, with their kernels as
 * float arrays for the convolution (k2: n x n, k1: n per channel). Returns n, 0 on failure. */
typedef struct preint_case {
    lucent_profile *p;
    lucent_kernel2d *gt;
    lucent_kernel *k;
    float *k2[3], *k1[3];
} preint_case;

static int preint_setup(const char *name, preint_case *pc)
{
    lucent_material m;
    memset(pc, 0, sizeof *pc);
    CHECK_OK(lucent_material_preset_find(name, &m));
    CHECK_OK(lucent_profile_dipole(&m, NULL, &pc->p));
    if (pc->p) CHECK_OK(lucent_kernel2d_from_profile(pc->p, NULL, &pc->gt));
    lucent_kernel_desc desc = lucent_kernel_defaults(LUCENT_KERNEL_PREINT);
    if (pc->gt) CHECK_OK(lucent_kernel_build(pc->gt, pc->p, name, &desc, &pc->k));
    if (!pc->k) return 0;
    int n = 2 * pc->gt->half + 1;
    for (int c = 0; c < 3; c++) {
        pc->k2[c] = malloc((size_t)n * (size_t)n * sizeof(float));
        pc->k1[c] = malloc((size_t)n * sizeof(float));
        for (int i = 0; i < n * n; i++) pc->k2[c][i] = (float)pc->gt->value[c][i];
        for (int i = 0; i < n; i++) pc->k1[c][i] = (float)pc->k->a[c][i];
    }
    return n;
}

static void preint_teardown(preint_case *pc)
{
    for (int c = 0; c < 3; c++) free(pc->k2[c]), free(pc->k1[c]);
    lucent_kernel_destroy(pc->k);
    lucent_kernel2d_destroy(pc->gt);
    lucent_profile_destroy(pc->p);
}

/* Convolves src both ways; returns the largest difference. */
static double exact_minus_separable(const lucent_image *src, const preint_case *pc, int n)
{
    lucent_image *exact = NULL, *separable = NULL;
    CHECK_OK(lucent_image_create(src->width, src->height, src->channels, &exact));
    CHECK_OK(lucent_image_create(src->width, src->height, src->channels, &separable));
    lucent_conv_kernel2d kernel = {.size = n, .w = {pc->k2[0], pc->k2[1], pc->k2[2]}};
    CHECK_OK(lucent_convolve_2d(src, &kernel, LUCENT_BORDER_CLAMP, NULL, exact));
    CHECK_OK(
        lucent_convolve_separable(src, (const float *const *)pc->k1, NULL, n, LUCENT_BORDER_CLAMP, NULL, separable));
    double d = max_difference(exact, separable);
    lucent_image_destroy(exact);
    lucent_image_destroy(separable);
    return d;
}

/* Convolves each signal both ways on the kernel's own cell grid (one cell = one pixel). */
static void check_material(const char *name)
{
    preint_case pc;
    int n = preint_setup(name, &pc);
    for (int kind = SIGNAL_VERTICAL; n && kind <= SIGNAL_SUM; kind++) {
        lucent_image *src = edge_signal(n + 40, kind);
        double d = exact_minus_separable(src, &pc, n);
        CHECK_MSG(d <= 1e-5, "%s, signal %d: max |separable - exact| = %.3g", name, kind, d);
        printf("  %s signal %d (%dx%d kernel): max difference %.2g\n", name, kind, n, n, d);
        lucent_image_destroy(src);
    }
    preint_teardown(&pc);
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
    preint_case pc;
    int n = preint_setup("Skin1", &pc), size = n + 40;
    lucent_image *src = NULL;
    CHECK_OK(lucent_image_create(size, size, 3, &src));
    for (int y = size / 3; n && y < 2 * size / 3; y++)
        for (int x = size / 3; x < 2 * size / 3; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(src, x, y, c, 1.0f);
    if (n) CHECK(exact_minus_separable(src, &pc, n) > 1e-3);
    lucent_image_destroy(src);
    preint_teardown(&pc);
}

TEST_MAIN(TEST_ENTRY(preint_exact_for_additively_separable_signals), TEST_ENTRY(preint_not_exact_for_a_square))
