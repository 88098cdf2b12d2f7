/* Tests of the CPU convolutions (FFT 2-D, direct 2-D, separable, rank-N, taps) and the test
 * signals. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/convolve.h"
#include "test.h"

/* ---- helpers --------------------------------------------------------------------------------- */

static lucent_image *random_image(int w, int h, int ch, uint64_t seed)
{
    lucent_image *img = NULL;
    if (lucent_image_create(w, h, ch, &img) != LUCENT_OK) abort();
    lucent_rng rng;
    lucent_rng_init(seed, 0, &rng);
    for (size_t k = 0; k < lucent_image_value_count(img); k++) img->data[k] = lucent_rng_uniformf(&rng);
    return img;
}

static float *random_weights(size_t n, uint64_t seed, uint64_t stream)
{
    float *w = malloc(n * sizeof *w);
    lucent_rng rng;
    lucent_rng_init(seed, stream, &rng);
    double sum = 0.0;
    for (size_t k = 0; k < n; k++) {
        w[k] = lucent_rng_uniformf(&rng) - 0.25f;
        sum += fabs(w[k]);
    }
    for (size_t k = 0; k < n; k++) w[k] = (float)(w[k] / sum); /* sum |w| = 1: |output| <= 1 */
    return w;
}

static lucent_image *blank_like(const lucent_image *img)
{
    lucent_image *out = NULL;
    if (lucent_image_create(img->width, img->height, img->channels, &out) != LUCENT_OK) abort();
    return out;
}

static double max_abs_diff(const lucent_image *a, const lucent_image *b)
{
    double m = 0.0;
    for (size_t k = 0; k < lucent_image_value_count(a); k++) {
        double d = fabs((double)a->data[k] - (double)b->data[k]);
        if (!(d <= m)) m = d; /* NaN propagates as a failure */
    }
    return m;
}

static double channel_sum(const lucent_image *img, int c)
{
    double s = 0.0;
    for (size_t p = 0; p < (size_t)img->width * (size_t)img->height; p++)
        s += img->data[p * (size_t)img->channels + (size_t)c];
    return s;
}

/* Outer product K(i, j) = kx[i] ky[j] as a size x size array. */
static float *outer(const float *kx, const float *ky, int n)
{
    float *k = malloc((size_t)n * (size_t)n * sizeof *k);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) k[j * n + i] = kx[i] * ky[j];
    return k;
}

/* Isotropic kernel sampled at pixel centres, normalised to sum 1: Gaussian (sigma) or
 * exponential exp(-r / d) (not separable). */
static float *isotropic_kernel(int n, double width, int gaussian)
{
    float *k = malloc((size_t)n * (size_t)n * sizeof *k);
    int r = n / 2;
    double sum = 0.0;
    for (int j = -r; j <= r; j++)
        for (int i = -r; i <= r; i++) {
            double q = sqrt((double)(i * i + j * j));
            double v = gaussian ? exp(-q * q / (2.0 * width * width)) : exp(-q / width);
            k[(j + r) * n + (i + r)] = (float)v;
            sum += v;
        }
    for (int m = 0; m < n * n; m++) k[m] = (float)(k[m] / sum);
    return k;
}

/* Pre-integrated 1-D marginal a_p(i) = sum_j K(i, j) (Freude Eq. 5.15). */
static float *marginal(const float *k, int n)
{
    float *a = calloc((size_t)n, sizeof *a);
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int j = 0; j < n; j++) s += k[j * n + i];
        a[i] = (float)s;
    }
    return a;
}

static double worst_fft_diff;

/* ---- 2-D: FFT against direct ----------------------------------------------------------------- */

static void fft_vs_direct(int w, int h, int ch, int n, lucent_border border, uint64_t seed, lucent_pool *pool)
{
    lucent_image *src = random_image(w, h, ch, seed);
    lucent_image *a = blank_like(src), *b = blank_like(src);
    float *wr = random_weights((size_t)n * n, seed, 1), *wg = random_weights((size_t)n * n, seed, 2),
          *wb = random_weights((size_t)n * n, seed, 3);
    lucent_conv_kernel2d k = {n, {wr, wg, wb}};
    if (ch == 1) k.w[1] = k.w[2] = NULL;
    CHECK_OK(lucent_convolve_2d(src, &k, border, pool, a));
    CHECK_OK(lucent_convolve_2d_direct(src, &k, border, pool, b));
    double d = max_abs_diff(a, b);
    CHECK_MSG(d <= 1e-5, "%dx%dx%d kernel %d %s: FFT vs direct max diff %.3g", w, h, ch, n, lucent_border_name(border),
              d);
    if (d > worst_fft_diff) worst_fft_diff = d;
    if (ch == 4) /* alpha copied */
        for (size_t p = 0; p < (size_t)w * h; p++) CHECK(a->data[p * 4 + 3] == src->data[p * 4 + 3]);
    lucent_image_destroy(src);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
    free(wr);
    free(wg);
    free(wb);
}

TEST(fft_equals_direct)
{
    lucent_pool *pool = lucent_pool_create(2);
    /* kernels larger than the image, odd sizes, prime sizes, 1x1 kernels, both borders */
    static const int cases[][4] = {{17, 13, 3, 5}, {31, 29, 3, 21}, {8, 40, 1, 41},  {50, 37, 4, 9},
                                   {23, 23, 3, 1}, {1, 1, 3, 7},    {120, 90, 3, 45}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (int b = 0; b < 2; b++)
            fft_vs_direct(cases[i][0], cases[i][1], cases[i][2], cases[i][3], (lucent_border)b, 100 + i,
                          b ? pool : NULL);
    lucent_pool_destroy(pool);
    printf("  FFT vs direct: max |diff| %.3g over all cases\n", worst_fft_diff);
}

TEST(delta_reproduces_kernel)
{
    int n = 9, w = 31, h = 27, x0 = 12, y0 = 9;
    float *wr = random_weights((size_t)n * n, 7, 0), *wg = random_weights((size_t)n * n, 7, 1);
    lucent_conv_kernel2d k = {n, {wr, wg, NULL}}; /* blue uses w[0] */
    lucent_image *src = NULL;
    CHECK_OK(lucent_image_create(w, h, 3, &src));
    for (int c = 0; c < 3; c++) lucent_image_set(src, x0, y0, c, 1.0f);
    lucent_image *a = blank_like(src), *b = blank_like(src);
    CHECK_OK(lucent_convolve_2d(src, &k, LUCENT_BORDER_ZERO, NULL, a));
    CHECK_OK(lucent_convolve_2d_direct(src, &k, LUCENT_BORDER_ZERO, NULL, b));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int i = x - x0 + n / 2, j = y - y0 + n / 2;
            int in = i >= 0 && i < n && j >= 0 && j < n;
            for (int c = 0; c < 3; c++) {
                float want = in ? (c == 1 ? wg : wr)[j * n + i] : 0.0f;
                CHECK_NEAR(lucent_image_get(a, x, y, c), want, 1e-6);
                CHECK_NEAR(lucent_image_get(b, x, y, c), want, 1e-7);
            }
        }
    /* separable: a delta gives the outer product, unflipped */
    float kx[7] = {1, 2, 3, 4, 5, 6, 7}, ky[7] = {0.5f, 0, 0, 1, 0, 0, 2};
    const float *kxs[3] = {kx, NULL, NULL}, *kys[3] = {ky, NULL, NULL};
    CHECK_OK(lucent_convolve_separable(src, kxs, kys, 7, LUCENT_BORDER_ZERO, NULL, a));
    for (int j = 0; j < 7; j++)
        for (int i = 0; i < 7; i++) CHECK_NEAR(lucent_image_get(a, x0 - 3 + i, y0 - 3 + j, 2), kx[i] * ky[j], 1e-6);
    lucent_image_destroy(src);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
    free(wr);
    free(wg);
}

/* ---- separable ------------------------------------------------------------------------------- */

TEST(separable_equals_outer_product)
{
    lucent_pool *pool = lucent_pool_create(2);
    static const int cases[][3] = {{40, 33, 11}, {19, 25, 31}, {64, 64, 3}};
    double worst = 0.0;
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        int w = cases[t][0], h = cases[t][1], n = cases[t][2];
        lucent_image *src = random_image(w, h, 4, 300 + t);
        lucent_image *sep = blank_like(src), *full = blank_like(src);
        float *kx[3], *ky[3], *k2[3];
        for (int c = 0; c < 3; c++) {
            kx[c] = random_weights((size_t)n, 40 + t, (uint64_t)c);
            ky[c] = random_weights((size_t)n, 50 + t, (uint64_t)c);
            k2[c] = outer(kx[c], ky[c], n);
        }
        const float *kxs[3] = {kx[0], kx[1], kx[2]}, *kys[3] = {ky[0], ky[1], ky[2]};
        lucent_conv_kernel2d k = {n, {k2[0], k2[1], k2[2]}};
        for (int b = 0; b < 2; b++) {
            CHECK_OK(lucent_convolve_separable(src, kxs, kys, n, (lucent_border)b, pool, sep));
            CHECK_OK(lucent_convolve_2d(src, &k, (lucent_border)b, pool, full));
            double d = max_abs_diff(sep, full);
            CHECK_MSG(d <= 1e-5, "%dx%d length %d %s: separable vs 2-D max diff %.3g", w, h, n,
                      lucent_border_name((lucent_border)b), d);
            if (d > worst) worst = d;
        }
        lucent_image_destroy(src);
        lucent_image_destroy(sep);
        lucent_image_destroy(full);
        for (int c = 0; c < 3; c++) {
            free(kx[c]);
            free(ky[c]);
            free(k2[c]);
        }
    }
    printf("  separable vs 2-D outer product: max |diff| %.3g\n", worst);
    lucent_pool_destroy(pool);
}

TEST(rank_n_sum_equals_2d)
{
    int w = 37, h = 30, n = 15, rank = 3;
    lucent_image *src = random_image(w, h, 3, 77);
    lucent_image *sep = blank_like(src), *full = blank_like(src);
    float *kx[9], *ky[9], *k2[3];
    for (int m = 0; m < 9; m++) {
        kx[m] = random_weights((size_t)n, 80, (uint64_t)m);
        ky[m] = random_weights((size_t)n, 81, (uint64_t)m);
    }
    for (int c = 0; c < 3; c++) {
        k2[c] = calloc((size_t)n * n, sizeof(float));
        for (int r = 0; r < rank; r++) {
            float *o = outer(kx[r * 3 + c], ky[r * 3 + c], n);
            for (int m = 0; m < n * n; m++) k2[c][m] += o[m];
            free(o);
        }
    }
    const float *kxs[9], *kys[9];
    for (int m = 0; m < 9; m++) {
        kxs[m] = kx[m];
        kys[m] = ky[m];
    }
    lucent_conv_kernel2d k = {n, {k2[0], k2[1], k2[2]}};
    for (int b = 0; b < 2; b++) {
        CHECK_OK(lucent_convolve_separable_sum(src, rank, kxs, kys, n, (lucent_border)b, NULL, sep));
        CHECK_OK(lucent_convolve_2d(src, &k, (lucent_border)b, NULL, full));
        double d = max_abs_diff(sep, full);
        CHECK_MSG(d <= 1e-5, "rank %d %s: max diff %.3g", rank, lucent_border_name((lucent_border)b), d);
    }
    lucent_image_destroy(src);
    lucent_image_destroy(sep);
    lucent_image_destroy(full);
    for (int m = 0; m < 9; m++) {
        free(kx[m]);
        free(ky[m]);
    }
    for (int c = 0; c < 3; c++) free(k2[c]);
}

/* Freude Eq. 5.15: for an additively separable signal E(x, y) = E1(x) + E2(y) and an isotropic
 * kernel K, the separable kernel a_p(x) a_p(y) / |a_p|_1 with the pre-integrated marginal
 * a_p(x) = sum_y K(x, y) gives exactly the 2-D result; for other signals it does not, unless K is
 * itself separable (a Gaussian). */
static void preintegration_case(int gaussian, double width, double *edge_diff, double *shape_diff)
{
    int n = 41, w = 96, h = 80;
    float *k = isotropic_kernel(n, width, gaussian), *a = marginal(k, n);
    lucent_conv_kernel2d k2 = {n, {k, NULL, NULL}};
    const float *ks[3] = {a, NULL, NULL};
    lucent_image *edge = NULL, *shapes = NULL;
    CHECK_OK(lucent_signal_edge(w, h, &edge));
    for (int y = 0; y < h; y++) /* + a horizontal edge: still additively separable */
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                lucent_image_set(edge, x, y, c, lucent_image_get(edge, x, y, c) + (y < h / 3 ? 0.5f : 0.0f));
    CHECK_OK(lucent_signal_shapes(w, h, &shapes));
    lucent_image *sep = blank_like(edge), *full = blank_like(edge);
    /* clamp: the border-extended signal stays additively separable */
    CHECK_OK(lucent_convolve_separable(edge, ks, NULL, n, LUCENT_BORDER_CLAMP, NULL, sep));
    CHECK_OK(lucent_convolve_2d(edge, &k2, LUCENT_BORDER_CLAMP, NULL, full));
    *edge_diff = max_abs_diff(sep, full);
    CHECK_OK(lucent_convolve_separable(shapes, ks, NULL, n, LUCENT_BORDER_CLAMP, NULL, sep));
    CHECK_OK(lucent_convolve_2d(shapes, &k2, LUCENT_BORDER_CLAMP, NULL, full));
    *shape_diff = max_abs_diff(sep, full);
    if (gaussian) { /* the marginal of the sampled Gaussian is the normalised 1-D Gaussian */
        double sum = 0.0;
        for (int i = -n / 2; i <= n / 2; i++) sum += exp(-i * i / (2.0 * width * width));
        for (int i = -n / 2; i <= n / 2; i++) CHECK_NEAR(a[i + n / 2], exp(-i * i / (2.0 * width * width)) / sum, 1e-6);
    }
    lucent_image_destroy(edge);
    lucent_image_destroy(shapes);
    lucent_image_destroy(sep);
    lucent_image_destroy(full);
    free(k);
    free(a);
}

TEST(preintegration_exact_for_edges)
{
    double ge, gs, ee, es;
    preintegration_case(1, 4.0, &ge, &gs);
    preintegration_case(0, 3.0, &ee, &es);
    printf("  Gaussian: edge %.3g, shapes %.3g; exponential: edge %.3g, shapes %.3g (max |diff|)\n", ge, gs, ee, es);
    CHECK_MSG(ge <= 1e-5, "Gaussian edge: %.3g", ge);
    CHECK_MSG(gs <= 1e-5, "Gaussian shapes (Gaussian is separable): %.3g", gs);
    CHECK_MSG(ee <= 1e-5, "exponential edge: %.3g", ee);
    CHECK_MSG(es > 1e-3, "exponential shapes should differ (non-separable kernel): %.3g", es);
}

/* ---- taps ------------------------------------------------------------------------------------ */

TEST(taps_integer_equal_sparse_kernel)
{
    float off[5] = {-3, -1, 0, 2, 5};
    float wr[5] = {0.1f, 0.2f, 0.4f, 0.2f, 0.1f}, wg[5] = {0.3f, -0.1f, 0.5f, 0.2f, 0.1f};
    lucent_conv_taps taps = {.count = 5, .offsets = off, .weights = {wr, wg, NULL}};
    int n = 11; /* offsets -5 .. 5 */
    float kr[11] = {0}, kg[11] = {0};
    for (int t = 0; t < 5; t++) {
        kr[(int)off[t] + n / 2] = wr[t];
        kg[(int)off[t] + n / 2] = wg[t];
    }
    const float *ks[3] = {kr, kg, NULL};
    lucent_image *src = random_image(33, 21, 3, 5);
    lucent_image *a = blank_like(src), *b = blank_like(src);
    for (int bd = 0; bd < 2; bd++) {
        CHECK_OK(lucent_convolve_taps(src, &taps, (lucent_border)bd, NULL, a));
        CHECK_OK(lucent_convolve_separable(src, ks, NULL, n, (lucent_border)bd, NULL, b));
        double d = max_abs_diff(a, b);
        CHECK_MSG(d <= 1e-6, "%s: taps vs sparse kernel %.3g", lucent_border_name((lucent_border)bd), d);
    }
    lucent_image_destroy(src);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
}

TEST(taps_fractional_interpolate)
{
    /* a tap at offset o reads src(x - o) linearly interpolated: the same as two integer taps
     * at -d0 and -(d0 + 1) with weights (1 - f) w and f w, d0 = floor(-o), f = -o - d0 */
    float off[4] = {-2.25f, 0.0f, 0.5f, 3.75f}, wt[4] = {0.2f, 0.4f, 0.3f, 0.1f};
    lucent_conv_taps taps = {.count = 4, .offsets = off, .weights = {wt, NULL, NULL}};
    int n = 11;
    float k[11] = {0};
    for (int t = 0; t < 4; t++) {
        double d = -off[t], d0 = floor(d), f = d - d0;
        k[-(int)d0 + n / 2] += (float)((1.0 - f) * wt[t]);
        k[-(int)d0 - 1 + n / 2] += (float)(f * wt[t]);
    }
    const float *ks[3] = {k, NULL, NULL};
    lucent_image *src = random_image(29, 31, 1, 9);
    lucent_image *a = blank_like(src), *b = blank_like(src);
    for (int bd = 0; bd < 2; bd++) {
        CHECK_OK(lucent_convolve_taps(src, &taps, (lucent_border)bd, NULL, a));
        CHECK_OK(lucent_convolve_separable(src, ks, NULL, n, (lucent_border)bd, NULL, b));
        double d = max_abs_diff(a, b);
        CHECK_MSG(d <= 1e-6, "%s: fractional taps %.3g", lucent_border_name((lucent_border)bd), d);
    }
    /* a ramp read half a pixel off: one tap at +0.5 gives src(x - 0.5) = x - 0.5 inside */
    lucent_image *ramp = NULL;
    CHECK_OK(lucent_image_create(8, 2, 1, &ramp));
    for (int x = 0; x < 8; x++) lucent_image_set(ramp, x, 0, 0, (float)x), lucent_image_set(ramp, x, 1, 0, (float)x);
    lucent_image *out = blank_like(ramp);
    float o1 = 0.5f, w1 = 1.0f;
    lucent_conv_taps one = {.count = 1, .offsets = &o1, .weights = {&w1, NULL, NULL}};
    CHECK_OK(lucent_convolve_taps(ramp, &one, LUCENT_BORDER_CLAMP, NULL, out));
    CHECK_NEAR(lucent_image_get(out, 0, 0, 0), 0.0, 1e-7); /* clamped: both reads are pixel 0 */
    for (int x = 1; x < 8; x++) CHECK_NEAR(lucent_image_get(out, x, 0, 0), x - 0.5, 1e-6);
    lucent_image_destroy(ramp);
    lucent_image_destroy(out);
    lucent_image_destroy(src);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
}

/* Equivalent 1-D kernel (length n) of taps at fractional offsets with weights w. */
static void taps_kernel(const float *off, const float *w, int count, int n, float *dest)
{
    memset(dest, 0, (size_t)n * sizeof *dest);
    for (int t = 0; t < count; t++) {
        double d = -off[t], d0 = floor(d), f = d - d0;
        dest[-(int)d0 + n / 2] += (float)((1.0 - f) * w[t]);
        if (f > 0.0) dest[-(int)d0 - 1 + n / 2] += (float)(f * w[t]);
    }
}

TEST(taps_rank_n_with_signs)
{
    enum { RANK = 2, COUNT = 3, N = 7 };
    float off[COUNT] = {-1.5f, 0.0f, 2.0f};
    float w[3][RANK * COUNT] = {{0.2f, 0.5f, 0.3f, 0.1f, 0.3f, 0.05f},
                                {0.3f, 0.4f, 0.2f, 0.2f, 0.1f, 0.1f},
                                {0.1f, 0.8f, 0.1f, 0.3f, 0.2f, 0.2f}};
    float sign0[RANK] = {1.0f, -1.0f}, sign1[RANK] = {1.0f, 1.0f};
    lucent_conv_taps taps = {.count = COUNT,
                             .rank = RANK,
                             .offsets = off,
                             .weights = {w[0], w[1], w[2]},
                             .sign = {sign0, sign1, NULL}}; /* channel 2 takes sign0 */
    float kx[RANK * 3][N], ky[RANK * 3][N];
    const float *kxs[RANK * 3], *kys[RANK * 3];
    for (int p = 0; p < RANK; p++)
        for (int c = 0; c < 3; c++) {
            float sg = (c == 1 ? sign1 : sign0)[p];
            taps_kernel(off, w[c] + p * COUNT, COUNT, N, ky[p * 3 + c]);
            for (int i = 0; i < N; i++) kx[p * 3 + c][i] = sg * ky[p * 3 + c][i];
            kxs[p * 3 + c] = kx[p * 3 + c];
            kys[p * 3 + c] = ky[p * 3 + c];
        }
    lucent_image *src = random_image(26, 19, 3, 31);
    lucent_image *a = blank_like(src), *b = blank_like(src);
    for (int bd = 0; bd < 2; bd++) {
        CHECK_OK(lucent_convolve_taps(src, &taps, (lucent_border)bd, NULL, a));
        CHECK_OK(lucent_convolve_separable_sum(src, RANK, kxs, kys, N, (lucent_border)bd, NULL, b));
        double d = max_abs_diff(a, b);
        CHECK_MSG(d <= 1e-6, "%s: rank-2 taps %.3g", lucent_border_name((lucent_border)bd), d);
    }
    lucent_image_destroy(src);
    lucent_image_destroy(a);
    lucent_image_destroy(b);
}

/* ---- energy, aliasing, threads --------------------------------------------------------------- */

TEST(energy_conserved_away_from_edges)
{
    int w = 72, h = 64, n = 31, margin = 22;
    lucent_image *src = NULL;
    CHECK_OK(lucent_image_create(w, h, 3, &src));
    lucent_rng rng;
    lucent_rng_init(11, 0, &rng);
    for (int y = margin; y < h - margin; y++)
        for (int x = margin; x < w - margin; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(src, x, y, c, lucent_rng_uniformf(&rng));
    float *k = isotropic_kernel(n, 3.0, 0), *a = marginal(k, n);
    lucent_conv_kernel2d k2 = {n, {k, NULL, NULL}};
    const float *ks[3] = {a, NULL, NULL};
    /* normalised taps at fractional offsets reaching 10.5 pixels (< margin - 1) */
    float off[7] = {-10.5f, -4.25f, -1.0f, 0.0f, 1.0f, 4.25f, 10.5f};
    float wt[7] = {0.05f, 0.1f, 0.2f, 0.3f, 0.2f, 0.1f, 0.05f};
    lucent_conv_taps taps = {.count = 7, .offsets = off, .weights = {wt, NULL, NULL}};
    lucent_image *out = blank_like(src);
    for (int m = 0; m < 3; m++) {
        if (m == 0) CHECK_OK(lucent_convolve_2d(src, &k2, LUCENT_BORDER_CLAMP, NULL, out));
        if (m == 1) CHECK_OK(lucent_convolve_separable(src, ks, NULL, n, LUCENT_BORDER_CLAMP, NULL, out));
        if (m == 2) CHECK_OK(lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, out));
        for (int c = 0; c < 3; c++) {
            double s0 = channel_sum(src, c), s1 = channel_sum(out, c);
            CHECK_MSG(fabs(s1 - s0) <= 1e-5 * s0, "method %d channel %d: sum %.9g -> %.9g", m, c, s0, s1);
        }
    }
    lucent_image_destroy(src);
    lucent_image_destroy(out);
    free(k);
    free(a);
}

TEST(dest_may_be_src_and_threads_do_not_matter)
{
    int n = 9;
    float *k = isotropic_kernel(n, 2.0, 0), *a = marginal(k, n);
    lucent_conv_kernel2d k2 = {n, {k, NULL, NULL}};
    const float *ks[3] = {a, NULL, NULL};
    float off[3] = {-1.5f, 0.0f, 1.5f}, wt[3] = {0.25f, 0.5f, 0.25f};
    lucent_conv_taps taps = {.count = 3, .offsets = off, .weights = {wt, NULL, NULL}};
    lucent_pool *pool = lucent_pool_create(2);
    for (int m = 0; m < 4; m++) {
        lucent_image *src = random_image(45, 38, 4, 21);
        lucent_image *ref = blank_like(src), *par = blank_like(src);
        lucent_status s1 = LUCENT_OK, s2 = LUCENT_OK, s3 = LUCENT_OK;
        if (m == 0) {
            s1 = lucent_convolve_2d(src, &k2, LUCENT_BORDER_ZERO, NULL, ref);
            s2 = lucent_convolve_2d(src, &k2, LUCENT_BORDER_ZERO, pool, par);
            s3 = lucent_convolve_2d(src, &k2, LUCENT_BORDER_ZERO, pool, src);
        } else if (m == 1) {
            s1 = lucent_convolve_2d_direct(src, &k2, LUCENT_BORDER_ZERO, NULL, ref);
            s2 = lucent_convolve_2d_direct(src, &k2, LUCENT_BORDER_ZERO, pool, par);
            s3 = lucent_convolve_2d_direct(src, &k2, LUCENT_BORDER_ZERO, pool, src);
        } else if (m == 2) {
            s1 = lucent_convolve_separable(src, ks, NULL, n, LUCENT_BORDER_CLAMP, NULL, ref);
            s2 = lucent_convolve_separable(src, ks, NULL, n, LUCENT_BORDER_CLAMP, pool, par);
            s3 = lucent_convolve_separable(src, ks, NULL, n, LUCENT_BORDER_CLAMP, pool, src);
        } else {
            s1 = lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, ref);
            s2 = lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, pool, par);
            s3 = lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, pool, src);
        }
        CHECK_OK(s1);
        CHECK_OK(s2);
        CHECK_OK(s3);
        CHECK_MSG(memcmp(ref->data, par->data, lucent_image_value_count(ref) * sizeof(float)) == 0,
                  "method %d: result depends on the pool", m);
        CHECK_MSG(memcmp(ref->data, src->data, lucent_image_value_count(ref) * sizeof(float)) == 0,
                  "method %d: dest == src differs", m);
        lucent_image_destroy(src);
        lucent_image_destroy(ref);
        lucent_image_destroy(par);
    }
    lucent_pool_destroy(pool);
    free(k);
    free(a);
}

/* ---- errors ---------------------------------------------------------------------------------- */

TEST(errors_name_the_parameter)
{
    lucent_image *src = random_image(12, 10, 3, 1), *small = NULL, *grey = NULL;
    CHECK_OK(lucent_image_create(10, 10, 3, &small));
    CHECK_OK(lucent_image_create(12, 10, 1, &grey));
    float w[25] = {0}, nanw[9] = {0};
    w[12] = 1.0f;
    nanw[4] = NAN;
    lucent_conv_kernel2d k = {5, {w, NULL, NULL}};
    const float *ks[3] = {w, NULL, NULL};
    CHECK_ERR(lucent_convolve_2d(src, &k, LUCENT_BORDER_CLAMP, NULL, small), LUCENT_ERR_INVALID_ARGUMENT, "dest",
              "10x10x3", "12x10x3");
    CHECK_ERR(lucent_convolve_2d_direct(src, &k, LUCENT_BORDER_CLAMP, NULL, grey), LUCENT_ERR_INVALID_ARGUMENT, "dest",
              "12x10x1");
    CHECK_ERR(lucent_convolve_separable(src, ks, NULL, 5, LUCENT_BORDER_CLAMP, NULL, small),
              LUCENT_ERR_INVALID_ARGUMENT, "dest");
    k.size = 4;
    CHECK_ERR(lucent_convolve_2d(src, &k, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT, "kernel size",
              "4", "odd");
    CHECK_ERR(lucent_convolve_2d_direct(src, &k, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "kernel size");
    k.size = 0;
    CHECK_ERR(lucent_conv_kernel2d_check(&k), LUCENT_ERR_INVALID_ARGUMENT, "kernel size");
    lucent_conv_kernel2d kn = {3, {w, nanw, NULL}};
    CHECK_ERR(lucent_convolve_2d(src, &kn, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "kernel w[1][4]");
    lucent_conv_kernel2d k0 = {3, {NULL, w, NULL}};
    CHECK_ERR(lucent_conv_kernel2d_check(&k0), LUCENT_ERR_INVALID_ARGUMENT, "w[0]");
    CHECK_ERR(lucent_convolve_separable(src, ks, NULL, 4, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "length is 4", "odd");
    const float *nulls[3] = {NULL, NULL, NULL};
    CHECK_ERR(lucent_convolve_separable(src, ks, nulls, 5, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "ky[0]");
    CHECK_ERR(lucent_convolve_separable_sum(src, 0, ks, NULL, 5, LUCENT_BORDER_CLAMP, NULL, src),
              LUCENT_ERR_INVALID_ARGUMENT, "rank");
    float off[2] = {0.0f, NAN}, wt[2] = {1.0f, 1.0f};
    lucent_conv_taps taps = {.count = 2, .offsets = off, .weights = {wt, NULL, NULL}};
    CHECK_ERR(lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "offsets[1]");
    float sg[1] = {NAN};
    off[1] = 1.0f;
    taps.sign[0] = sg;
    CHECK_ERR(lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "sign[0][0]");
    taps.rank = -1;
    CHECK_ERR(lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "taps rank");
    taps.count = 0;
    CHECK_ERR(lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, src), LUCENT_ERR_INVALID_ARGUMENT,
              "taps count");
    CHECK_ERR(lucent_convolve_taps(src, &taps, LUCENT_BORDER_CLAMP, NULL, small), LUCENT_ERR_INVALID_ARGUMENT, "dest");
    lucent_border b = LUCENT_BORDER_CLAMP;
    CHECK(lucent_border_parse("zero", &b) == LUCENT_OK && b == LUCENT_BORDER_ZERO);
    CHECK_ERR(lucent_border_parse("wrap", &b), LUCENT_ERR_INVALID_ARGUMENT, "wrap", "clamp, zero");
    CHECK(strcmp(lucent_border_name(LUCENT_BORDER_CLAMP), "clamp") == 0);
    lucent_image_destroy(src);
    lucent_image_destroy(small);
    lucent_image_destroy(grey);
}

/* ---- signals --------------------------------------------------------------------------------- */

TEST(signal_edge)
{
    lucent_image *e = NULL;
    CHECK_OK(lucent_signal_edge(8, 4, &e));
    CHECK(e && e->channels == 3);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 8; x++)
            for (int c = 0; c < 3; c++) CHECK(lucent_image_get(e, x, y, c) == (x < 4 ? 1.0f : 0.0f));
    lucent_image_destroy(e);
    CHECK_OK(lucent_signal_edge(9, 3, &e));
    CHECK(lucent_image_get(e, 3, 1, 0) == 1.0f);
    CHECK(lucent_image_get(e, 4, 1, 0) == 0.5f); /* the middle column is cut by the edge */
    CHECK(lucent_image_get(e, 5, 1, 0) == 0.0f);
    lucent_image_destroy(e);
    CHECK_ERR(lucent_signal_edge(0, 4, &e), LUCENT_ERR_INVALID_ARGUMENT, "0");
}

TEST(signal_shapes)
{
    int s = 256;
    lucent_image *img = NULL;
    CHECK_OK(lucent_signal_shapes(s, s, &img));
    lucent_image_stats st;
    lucent_image_stats_compute(img, &st);
    CHECK(st.min[0] == 0.0 && st.max[0] == 1.0);
    /* area: circle pi 0.2^2 at 1, squares 0.22^2 at 1 and 0.5 */
    double want = M_PI * 0.04 + 0.0484 * 1.5;
    CHECK_NEAR(st.mean[0], want, 2e-3);
    CHECK(lucent_image_get(img, s / 2 - (int)(0.25 * s), s / 2, 1) == 1.0f); /* circle centre */
    double t = 30.0 * M_PI / 180.0, a = 0.22;
    int ax = (int)(s / 2 + (0.22 - 0.5 * a * cos(t)) * s), ay = (int)(s / 2 - 0.5 * a * sin(t) * s);
    int bx = (int)(s / 2 + (0.22 + 0.5 * a * cos(t)) * s), by = (int)(s / 2 + 0.5 * a * sin(t) * s);
    CHECK(lucent_image_get(img, ax, ay, 0) == 1.0f);
    CHECK(lucent_image_get(img, bx, by, 2) == 0.5f);
    CHECK(lucent_image_get(img, 0, 0, 0) == 0.0f && lucent_image_get(img, s - 1, s - 1, 0) == 0.0f);
    CHECK(lucent_image_get(img, s / 2, s / 2 + (int)(0.35 * s), 0) == 0.0f);
    /* nothing touches the border: room for a kernel at 0.1 mm / pixel */
    for (int x = 0; x < s; x++) CHECK(lucent_image_get(img, x, 2, 0) == 0.0f);
    if (getenv("LUCENT_TEST_KEEP")) lucent_image_write(test_path("shapes.png"), img, NULL);
    lucent_image_destroy(img);
}

TEST(signal_load)
{
    lucent_image *img = NULL, *grey = NULL;
    CHECK_OK(lucent_signal_load("edge", 0, 0, &img));
    CHECK(img && img->width == LUCENT_SIGNAL_DEFAULT_SIZE && img->height == LUCENT_SIGNAL_DEFAULT_SIZE);
    lucent_image_destroy(img);
    CHECK_OK(lucent_signal_load("shapes", 64, 32, &img));
    CHECK(img && img->width == 64 && img->height == 32);
    lucent_image_destroy(img);
    CHECK_OK(lucent_image_create(5, 4, 1, &grey));
    lucent_image_set(grey, 2, 1, 0, 0.25f);
    CHECK_OK(lucent_image_write(test_path("grey.exr"), grey, NULL));
    CHECK_OK(lucent_signal_load(test_path("grey.exr"), 0, 0, &img));
    CHECK(img && img->channels == 3 && img->width == 5 && img->height == 4);
    if (img) CHECK_NEAR(lucent_image_get(img, 2, 1, 1), 0.25, 1e-6);
    lucent_image_destroy(img);
    lucent_image_destroy(grey);
    CHECK(lucent_signal_load(test_path("missing.png"), 0, 0, &img) != LUCENT_OK);
    CHECK(strstr(lucent_last_error(), "missing.png") != NULL);
    CHECK(img == NULL);
    CHECK_ERR(lucent_signal_load("", 0, 0, &img), LUCENT_ERR_INVALID_ARGUMENT, "edge");
}

TEST_MAIN(TEST_ENTRY(fft_equals_direct), TEST_ENTRY(delta_reproduces_kernel),
          TEST_ENTRY(separable_equals_outer_product), TEST_ENTRY(rank_n_sum_equals_2d),
          TEST_ENTRY(preintegration_exact_for_edges), TEST_ENTRY(taps_integer_equal_sparse_kernel),
          TEST_ENTRY(taps_fractional_interpolate), TEST_ENTRY(taps_rank_n_with_signs),
          TEST_ENTRY(energy_conserved_away_from_edges), TEST_ENTRY(dest_may_be_src_and_threads_do_not_matter),
          TEST_ENTRY(errors_name_the_parameter), TEST_ENTRY(signal_edge), TEST_ENTRY(signal_shapes),
          TEST_ENTRY(signal_load))
