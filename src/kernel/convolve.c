/* Exact 2-D convolution of an image with a full kernel: through FFTW (r2c / c2r on the
 * zero-padded, border-extended channel) and by direct summation (the reference).
 *
 * Linear convolution by FFT. With r = size / 2, the channel is extended by r pixels on every
 * side (clamp or zero), P(u) = src(u - r) for u in [0, W + 2r), and the kernel is stored with
 * its offset -r at index 0, Kp(k) = K(k - r). Their linear convolution is
 * C(v) = sum_k Kp(k) P(v - k) = sum_i K(i) src(v - 2r - i), so dest(x) = C(x + 2r). For
 * x in [0, W) and k in [0, 2r], v - k = x + 2r - k lies in [0, W + 2r): a cyclic convolution of
 * any length N >= W + 2r never wraps for the outputs read, so N is the smallest 2-3-5-7-smooth
 * length >= W + 2r (per axis). */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include <fftw3.h>

#include "kernel/convolve_internal.h"
#include "lucent/convolve.h"

/* FFTW's planner is not thread-safe; executing a plan is. */
static pthread_mutex_t fftw_planner_lock = PTHREAD_MUTEX_INITIALIZER;

const char *lucent_border_name(lucent_border border) { return border == LUCENT_BORDER_ZERO ? "zero" : "clamp"; }

lucent_status lucent_border_parse(const char *name, lucent_border *dest)
{
    if (name && strcmp(name, "clamp") == 0)
        *dest = LUCENT_BORDER_CLAMP;
    else if (name && strcmp(name, "zero") == 0)
        *dest = LUCENT_BORDER_ZERO;
    else
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown border '%s' (clamp, zero)", name ? name : "");
    return LUCENT_OK;
}

/* Checks src and dest: present, 1, 3 or 4 channels, the same size. */
lucent_status conv_check_images(const char *fn, const lucent_image *src, const lucent_image *dest)
{
    if (!src || !src->data) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: src is NULL", fn);
    if (!dest || !dest->data) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: dest is NULL", fn);
    if (src->channels != 1 && src->channels != 3 && src->channels != 4)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: src has %d channels (1, 3 or 4)", fn, src->channels);
    if (dest->width != src->width || dest->height != src->height || dest->channels != src->channels)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: dest is %dx%dx%d but src is %dx%dx%d (sizes must match)",
                            fn, dest->width, dest->height, dest->channels, src->width, src->height, src->channels);
    return LUCENT_OK;
}

lucent_status lucent_conv_kernel2d_check(const lucent_conv_kernel2d *kernel)
{
    if (!kernel) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel is NULL");
    int n = kernel->size;
    if (n < 1 || n > LUCENT_CONVOLVE_MAX_SIZE || n % 2 == 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "kernel size is %d: it must be odd, 1 to %d, so the centre is a pixel", n,
                            LUCENT_CONVOLVE_MAX_SIZE);
    if (!kernel->w[0]) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel w[0] is NULL");
    for (int c = 0; c < 3; c++) {
        if (!kernel->w[c]) continue;
        for (size_t k = 0; k < (size_t)n * (size_t)n; k++)
            if (!isfinite(kernel->w[c][k]))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel w[%d][%zu] is not a finite number", c, k);
    }
    return LUCENT_OK;
}

/* Number of convolved channels (alpha excluded). */
static int colour_channels(const lucent_image *img) { return img->channels == 4 ? 3 : img->channels; }

static const float *kernel_weights(const lucent_conv_kernel2d *k, int c) { return k->w[c] ? k->w[c] : k->w[0]; }

/* Copies alpha from src to dest (no-op for images without alpha or when they alias). */
static void copy_alpha(const lucent_image *src, lucent_image *dest)
{
    if (src->channels != 4 || src->data == dest->data) return;
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t p = 0; p < n; p++) dest->data[p * 4 + 3] = src->data[p * 4 + 3];
}

/* Index along an axis of length n for border mode b: clamped, or -1 (zero) outside. */
static inline int border_index(int i, int n, lucent_border b)
{
    if (i >= 0 && i < n) return i;
    if (b == LUCENT_BORDER_ZERO) return -1;
    return i < 0 ? 0 : n - 1;
}

/* ---- Direct summation ------------------------------------------------------------------------ */

typedef struct direct_ctx {
    const lucent_image *src;
    const lucent_conv_kernel2d *kernel;
    lucent_border border;
    lucent_image *dest;
} direct_ctx;

static lucent_status direct_rows(void *vctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk;
    (void)thread;
    const direct_ctx *ctx = vctx;
    const lucent_image *s = ctx->src;
    int n = ctx->kernel->size, r = n / 2, ch = s->channels, nc = colour_channels(s);
    for (int y = (int)begin; y < (int)end; y++) {
        for (int x = 0; x < s->width; x++) {
            for (int c = 0; c < nc; c++) {
                const float *w = kernel_weights(ctx->kernel, c);
                double acc = 0.0;
                for (int j = -r; j <= r; j++) {
                    int sy = border_index(y - j, s->height, ctx->border);
                    if (sy < 0) continue;
                    const float *row = s->data + (size_t)sy * (size_t)s->width * (size_t)ch;
                    const float *wr = w + (size_t)(j + r) * (size_t)n + (size_t)r;
                    for (int i = -r; i <= r; i++) {
                        int sx = border_index(x - i, s->width, ctx->border);
                        if (sx >= 0) acc += (double)wr[i] * (double)row[(size_t)sx * (size_t)ch + (size_t)c];
                    }
                }
                ctx->dest->data[((size_t)y * (size_t)s->width + (size_t)x) * (size_t)ch + (size_t)c] = (float)acc;
            }
        }
    }
    return LUCENT_OK;
}

lucent_status lucent_convolve_2d_direct(const lucent_image *src, const lucent_conv_kernel2d *kernel,
                                        lucent_border border, lucent_pool *pool, lucent_image *dest)
{
    lucent_status s = conv_check_images("lucent_convolve_2d_direct", src, dest);
    if (s == LUCENT_OK) s = lucent_conv_kernel2d_check(kernel);
    if (s != LUCENT_OK) return s;
    lucent_image *copy = NULL;
    if (src->data == dest->data) { /* the sum reads neighbours: work from a copy */
        s = lucent_image_clone(src, &copy);
        if (s != LUCENT_OK) return s;
        src = copy;
    }
    direct_ctx ctx = {src, kernel, border, dest};
    s = lucent_parallel_for(pool, (uint64_t)src->height, 4, direct_rows, &ctx);
    if (s == LUCENT_OK) copy_alpha(src, dest);
    lucent_image_destroy(copy);
    return s;
}

/* ---- FFT ------------------------------------------------------------------------------------- */

/* Smallest n >= m whose only prime factors are 2, 3, 5 and 7 (FFTW's fast sizes). */
static int fft_size(int m)
{
    for (int n = m > 1 ? m : 1;; n++) {
        int k = n;
        static const int primes[4] = {2, 3, 5, 7};
        for (int p = 0; p < 4; p++)
            while (k % primes[p] == 0) k /= primes[p];
        if (k == 1) return n;
    }
}

typedef struct fft_ctx {
    const lucent_image *src;
    const lucent_conv_kernel2d *kernel;
    lucent_border border;
    lucent_image *dest;
    int nx, ny; /* FFT lengths */
    fftw_plan forward, inverse;
} fft_ctx;

/* Fills the real buffer with the border-extended channel c of src, padded with zeros. */
static void fft_load_image(const fft_ctx *ctx, int c, double *buf)
{
    const lucent_image *s = ctx->src;
    int r = ctx->kernel->size / 2, ch = s->channels;
    memset(buf, 0, (size_t)ctx->nx * (size_t)ctx->ny * sizeof *buf);
    for (int v = 0; v < s->height + 2 * r; v++) {
        int sy = border_index(v - r, s->height, ctx->border);
        if (sy < 0) continue;
        double *row = buf + (size_t)v * (size_t)ctx->nx;
        const float *srow = s->data + (size_t)sy * (size_t)s->width * (size_t)ch;
        for (int u = 0; u < s->width + 2 * r; u++) {
            int sx = border_index(u - r, s->width, ctx->border);
            if (sx >= 0) row[u] = srow[(size_t)sx * (size_t)ch + (size_t)c];
        }
    }
}

static void fft_load_kernel(const fft_ctx *ctx, int c, double *buf)
{
    int n = ctx->kernel->size;
    const float *w = kernel_weights(ctx->kernel, c);
    memset(buf, 0, (size_t)ctx->nx * (size_t)ctx->ny * sizeof *buf);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) buf[(size_t)j * (size_t)ctx->nx + (size_t)i] = w[(size_t)j * (size_t)n + (size_t)i];
}

/* One colour channel per chunk: K^ = FFT(kernel), I^ = FFT(image), dest = IFFT(K^ I^) / N. */
static lucent_status fft_channel(void *vctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk;
    (void)end;
    (void)thread;
    const fft_ctx *ctx = vctx;
    int c = (int)begin;
    size_t nreal = (size_t)ctx->nx * (size_t)ctx->ny;
    size_t ncplx = (size_t)ctx->ny * (size_t)(ctx->nx / 2 + 1);
    double *buf = fftw_malloc(nreal * sizeof *buf);
    fftw_complex *kspec = fftw_malloc(ncplx * sizeof *kspec);
    fftw_complex *ispec = fftw_malloc(ncplx * sizeof *ispec);
    lucent_status s = LUCENT_OK;
    if (!buf || !kspec || !ispec) {
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "lucent_convolve_2d: out of memory for %dx%d FFTs", ctx->nx,
                         ctx->ny);
        goto done;
    }
    fft_load_kernel(ctx, c, buf);
    fftw_execute_dft_r2c(ctx->forward, buf, kspec);
    fft_load_image(ctx, c, buf);
    fftw_execute_dft_r2c(ctx->forward, buf, ispec);
    double scale = 1.0 / (double)nreal;
    for (size_t k = 0; k < ncplx; k++) {
        double re = kspec[k][0] * ispec[k][0] - kspec[k][1] * ispec[k][1];
        double im = kspec[k][0] * ispec[k][1] + kspec[k][1] * ispec[k][0];
        ispec[k][0] = re * scale;
        ispec[k][1] = im * scale;
    }
    fftw_execute_dft_c2r(ctx->inverse, ispec, buf);
    const lucent_image *src = ctx->src;
    int r2 = 2 * (ctx->kernel->size / 2), ch = src->channels;
    for (int y = 0; y < src->height; y++) {
        const double *row = buf + (size_t)(y + r2) * (size_t)ctx->nx + (size_t)r2;
        float *drow = ctx->dest->data + (size_t)y * (size_t)src->width * (size_t)ch + (size_t)c;
        for (int x = 0; x < src->width; x++) drow[(size_t)x * (size_t)ch] = (float)row[x];
    }
done:
    fftw_free(buf);
    fftw_free(kspec);
    fftw_free(ispec);
    return s;
}

/* Makes the forward and inverse plans (out of place, FFTW_ESTIMATE) under the planner lock.
 * The plans are executed later on other arrays from fftw_malloc (same alignment). */
static lucent_status fft_plan(fft_ctx *ctx)
{
    size_t nreal = (size_t)ctx->nx * (size_t)ctx->ny;
    size_t ncplx = (size_t)ctx->ny * (size_t)(ctx->nx / 2 + 1);
    pthread_mutex_lock(&fftw_planner_lock);
    double *buf = fftw_malloc(nreal * sizeof *buf);
    fftw_complex *spec = fftw_malloc(ncplx * sizeof *spec);
    if (buf && spec) {
        ctx->forward = fftw_plan_dft_r2c_2d(ctx->ny, ctx->nx, buf, spec, FFTW_ESTIMATE);
        ctx->inverse = fftw_plan_dft_c2r_2d(ctx->ny, ctx->nx, spec, buf, FFTW_ESTIMATE);
    }
    fftw_free(buf);
    fftw_free(spec);
    pthread_mutex_unlock(&fftw_planner_lock);
    if (!buf || !spec)
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "lucent_convolve_2d: out of memory for %dx%d FFTs", ctx->nx,
                            ctx->ny);
    if (!ctx->forward || !ctx->inverse)
        return lucent_error(LUCENT_ERR_INTERNAL, "lucent_convolve_2d: FFTW could not plan %dx%d FFTs", ctx->nx,
                            ctx->ny);
    return LUCENT_OK;
}

static void fft_unplan(fft_ctx *ctx)
{
    pthread_mutex_lock(&fftw_planner_lock);
    if (ctx->forward) fftw_destroy_plan(ctx->forward);
    if (ctx->inverse) fftw_destroy_plan(ctx->inverse);
    pthread_mutex_unlock(&fftw_planner_lock);
}

lucent_status lucent_convolve_2d(const lucent_image *src, const lucent_conv_kernel2d *kernel, lucent_border border,
                                 lucent_pool *pool, lucent_image *dest)
{
    lucent_status s = conv_check_images("lucent_convolve_2d", src, dest);
    if (s == LUCENT_OK) s = lucent_conv_kernel2d_check(kernel);
    if (s != LUCENT_OK) return s;
    int r = kernel->size / 2;
    fft_ctx ctx = {.src = src,
                   .kernel = kernel,
                   .border = border,
                   .dest = dest,
                   .nx = fft_size(src->width + 2 * r),
                   .ny = fft_size(src->height + 2 * r)};
    s = fft_plan(&ctx);
    /* Each chunk reads channel c of src before writing channel c of dest, so dest may be src. */
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, (uint64_t)colour_channels(src), 1, fft_channel, &ctx);
    fft_unplan(&ctx);
    if (s == LUCENT_OK) copy_alpha(src, dest);
    return s;
}
