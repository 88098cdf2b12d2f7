/* Separable convolution: a horizontal then a vertical 1-D pass (Jimenez's two passes, Freude
 * section 4.4, Algorithm 4.1, without the depth-aware part), with full 1-D kernels, their rank-N
 * sums, or N taps at fractional offsets read by linear interpolation.
 *
 * Everything is one pass over taps: a full kernel of length L is the taps with offsets
 * -L/2 .. L/2 (integer offsets read one pixel, no interpolation). Clamping a row or a column is
 * the same before or after filtering along the other axis, so the two passes equal the 2-D
 * convolution with the outer product, borders included. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/convolve_internal.h"
#include "lucent/convolve.h"

static int colour_channels(const lucent_image *img) { return img->channels == 4 ? 3 : img->channels; }

/* One tap, ready for a pass: read at x + d0 and x + d0 + 1 with weights (1 - f) and f. */
typedef struct pass_tap {
    int d0;
    float f;
    float w[3];
} pass_tap;

typedef struct pass_ctx {
    const float *in;
    float *out;
    int width, height, channels, nc;
    int vertical;   /* 0: along x, 1: along y */
    int accumulate; /* out += result instead of out = result */
    lucent_border border;
    const pass_tap *taps;
    int count;
} pass_ctx;

/* Value of channel c at integer position i along the pass axis, the other coordinate fixed. */
static inline double fetch(const pass_ctx *p, const float *line, size_t stride, int n, int i, int c)
{
    if (i < 0 || i >= n) {
        if (p->border == LUCENT_BORDER_ZERO) return 0.0;
        i = i < 0 ? 0 : n - 1;
    }
    return (double)line[(size_t)i * stride + (size_t)c];
}

static lucent_status pass_rows(void *vctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk;
    (void)thread;
    const pass_ctx *p = vctx;
    size_t ch = (size_t)p->channels, rowlen = (size_t)p->width * ch;
    for (int y = (int)begin; y < (int)end; y++) {
        for (int x = 0; x < p->width; x++) {
            /* the line through (x, y) along the pass axis, and the position on it */
            const float *line = p->vertical ? p->in + (size_t)x * ch : p->in + (size_t)y * rowlen;
            size_t stride = p->vertical ? rowlen : ch;
            int n = p->vertical ? p->height : p->width, pos = p->vertical ? y : x;
            float *o = p->out + (size_t)y * rowlen + (size_t)x * ch;
            for (int c = 0; c < p->nc; c++) {
                double acc = 0.0;
                for (int k = 0; k < p->count; k++) {
                    const pass_tap *t = &p->taps[k];
                    double v = fetch(p, line, stride, n, pos + t->d0, c);
                    if (t->f != 0.0f) v += (double)t->f * (fetch(p, line, stride, n, pos + t->d0 + 1, c) - v);
                    acc += (double)t->w[c] * v;
                }
                o[c] = p->accumulate ? o[c] + (float)acc : (float)acc;
            }
        }
    }
    return LUCENT_OK;
}

static lucent_status run_pass(pass_ctx *p, lucent_pool *pool)
{
    return lucent_parallel_for(pool, (uint64_t)p->height, 8, pass_rows, p);
}

/* Taps for a full 1-D kernel (per channel, NULL: channel 0): offsets -length/2 .. length/2. */
static void taps_from_kernel(const float *const k[3], int length, pass_tap *dest)
{
    int r = length / 2;
    for (int i = 0; i < length; i++) {
        /* convolution: dest(x) = sum_o w(o) src(x - o), so the read is at x + d0 with d0 = -o */
        dest[i].d0 = r - i;
        dest[i].f = 0.0f;
        for (int c = 0; c < 3; c++) dest[i].w[c] = (k[c] ? k[c] : k[0])[i];
    }
}

static lucent_status check_kernel1d(const char *name, int term, const float *const k[3], int length)
{
    if (!k[0])
        return term < 0 ? lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s[0] is NULL", name)
                        : lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s[%d] (term %d, channel 0) is NULL", name,
                                       term * 3, term);
    for (int c = 0; c < 3; c++) {
        if (!k[c]) continue;
        for (int i = 0; i < length; i++)
            if (!isfinite(k[c][i]))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                    "%s: term %d, channel %d, weight %d is not a finite number", name,
                                    term < 0 ? 0 : term, c, i);
    }
    return LUCENT_OK;
}

static lucent_status check_length(int length)
{
    if (length < 1 || length > LUCENT_CONVOLVE_MAX_SIZE || length % 2 == 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "length is %d: a 1-D kernel length must be odd, 1 to %d, so the centre "
                            "is a pixel",
                            length, LUCENT_CONVOLVE_MAX_SIZE);
    return LUCENT_OK;
}

/* Copies the colour channels of a float buffer laid out like img into img (alpha kept). */
static void store_colour(const float *buf, lucent_image *img)
{
    size_t n = (size_t)img->width * (size_t)img->height, ch = (size_t)img->channels;
    int nc = colour_channels(img);
    for (size_t p = 0; p < n; p++)
        for (int c = 0; c < nc; c++) img->data[p * ch + (size_t)c] = buf[p * ch + (size_t)c];
}

static void copy_alpha(const lucent_image *src, lucent_image *dest)
{
    if (src->channels != 4 || src->data == dest->data) return;
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t p = 0; p < n; p++) dest->data[p * 4 + 3] = src->data[p * 4 + 3];
}

/* Runs sum over terms of (horizontal taps hx[t], then vertical taps vy[t]) from src into dest.
 * tmp holds the horizontal result; with several terms, acc collects the sum. */
static lucent_status two_passes(const lucent_image *src, int terms, const pass_tap *hx, int hcount, const pass_tap *vy,
                                int vcount, lucent_border border, lucent_pool *pool, lucent_image *dest, const char *fn)
{
    size_t nvalues = lucent_image_value_count(src);
    float *tmp = malloc(nvalues * sizeof *tmp);
    float *acc = terms > 1 ? calloc(nvalues, sizeof *acc) : NULL;
    if (!tmp || (terms > 1 && !acc)) {
        free(tmp);
        free(acc);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory for a %dx%d image", fn, src->width,
                            src->height);
    }
    lucent_status s = LUCENT_OK;
    pass_ctx p = {.width = src->width,
                  .height = src->height,
                  .channels = src->channels,
                  .nc = colour_channels(src),
                  .border = border};
    for (int t = 0; t < terms && s == LUCENT_OK; t++) {
        p.in = src->data;
        p.out = tmp;
        p.vertical = 0;
        p.accumulate = 0;
        p.taps = hx + (size_t)t * (size_t)hcount;
        p.count = hcount;
        s = run_pass(&p, pool);
        if (s != LUCENT_OK) break;
        /* one term: straight into dest (src was read completely by the first pass) */
        p.in = tmp;
        p.out = terms > 1 ? acc : dest->data;
        p.vertical = 1;
        p.accumulate = terms > 1;
        p.taps = vy + (size_t)t * (size_t)vcount;
        p.count = vcount;
        s = run_pass(&p, pool);
    }
    if (s == LUCENT_OK && terms > 1) store_colour(acc, dest);
    if (s == LUCENT_OK) copy_alpha(src, dest);
    free(tmp);
    free(acc);
    return s;
}

lucent_status lucent_convolve_separable_sum(const lucent_image *src, int rank, const float *const *kx,
                                            const float *const *ky, int length, lucent_border border, lucent_pool *pool,
                                            lucent_image *dest)
{
    static const char fn[] = "lucent_convolve_separable";
    lucent_status s = conv_check_images(fn, src, dest);
    if (s == LUCENT_OK) s = check_length(length);
    if (s != LUCENT_OK) return s;
    if (rank < 1 || rank > 1024)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: rank is %d (1 to 1024)", fn, rank);
    if (!kx) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: kx is NULL", fn);
    if (!ky) ky = kx;
    for (int t = 0; t < rank && s == LUCENT_OK; t++) {
        s = check_kernel1d("kx", rank > 1 ? t : -1, kx + 3 * t, length);
        if (s == LUCENT_OK) s = check_kernel1d("ky", rank > 1 ? t : -1, ky + 3 * t, length);
    }
    if (s != LUCENT_OK) return s;
    size_t n = (size_t)rank * (size_t)length;
    pass_tap *hx = malloc(n * sizeof *hx), *vy = malloc(n * sizeof *vy);
    if (!hx || !vy) {
        free(hx);
        free(vy);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    for (int t = 0; t < rank; t++) {
        taps_from_kernel(kx + 3 * t, length, hx + (size_t)t * (size_t)length);
        taps_from_kernel(ky + 3 * t, length, vy + (size_t)t * (size_t)length);
    }
    s = two_passes(src, rank, hx, length, vy, length, border, pool, dest, fn);
    free(hx);
    free(vy);
    return s;
}

lucent_status lucent_convolve_separable(const lucent_image *src, const float *const kx[3], const float *const ky[3],
                                        int length, lucent_border border, lucent_pool *pool, lucent_image *dest)
{
    return lucent_convolve_separable_sum(src, 1, kx, ky, length, border, pool, dest);
}

/* Checks the taps and turns pass p of them into hx (weights times the sign, horizontal) and
 * vy (vertical). */
static lucent_status prepare_taps(const char *fn, const lucent_conv_taps *taps, int rank, pass_tap *hx, pass_tap *vy)
{
    int n = taps->count;
    for (int k = 0; k < n; k++) {
        float o = taps->offsets[k];
        if (!isfinite(o) || fabsf(o) > (float)LUCENT_CONVOLVE_MAX_SIZE)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps offsets[%d] is %g (finite, at most %d pixels)",
                                fn, k, (double)o, LUCENT_CONVOLVE_MAX_SIZE);
        double d = -(double)o, d0 = floor(d); /* read at x - o */
        for (int p = 0; p < rank; p++) {
            pass_tap *h = &hx[p * n + k], *v = &vy[p * n + k];
            h->d0 = v->d0 = (int)d0;
            h->f = v->f = (float)(d - d0);
            for (int c = 0; c < 3; c++) {
                const float *w = taps->weights[c] ? taps->weights[c] : taps->weights[0];
                const float *sg = taps->sign[c] ? taps->sign[c] : taps->sign[0];
                float wk = w[p * n + k], sk = sg ? sg[p] : 1.0f;
                if (!isfinite(wk))
                    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps weights[%d][%d] is not a finite number",
                                        fn, c, p * n + k);
                if (!isfinite(sk))
                    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps sign[%d][%d] is not a finite number", fn,
                                        c, p);
                h->w[c] = wk * sk;
                v->w[c] = wk;
            }
        }
    }
    return LUCENT_OK;
}

lucent_status lucent_convolve_taps(const lucent_image *src, const lucent_conv_taps *taps, lucent_border border,
                                   lucent_pool *pool, lucent_image *dest)
{
    static const char fn[] = "lucent_convolve_taps";
    lucent_status s = conv_check_images(fn, src, dest);
    if (s != LUCENT_OK) return s;
    if (!taps) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps is NULL", fn);
    if (taps->count < 1 || taps->count > LUCENT_CONVOLVE_MAX_SIZE)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps count is %d (1 to %d)", fn, taps->count,
                            LUCENT_CONVOLVE_MAX_SIZE);
    int rank = taps->rank == 0 ? 1 : taps->rank;
    if (rank < 1 || rank > 1024)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps rank is %d (0 to 1024)", fn, taps->rank);
    if (!taps->offsets) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps offsets is NULL", fn);
    if (!taps->weights[0]) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps weights[0] is NULL", fn);
    if (!taps->sign[0] && (taps->sign[1] || taps->sign[2]))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: taps sign[0] is NULL", fn);
    size_t n = (size_t)rank * (size_t)taps->count;
    pass_tap *hx = malloc(n * sizeof *hx), *vy = malloc(n * sizeof *vy);
    if (!hx || !vy) {
        free(hx);
        free(vy);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    s = prepare_taps(fn, taps, rank, hx, vy);
    if (s == LUCENT_OK) s = two_passes(src, rank, hx, taps->count, vy, taps->count, border, pool, dest, fn);
    free(hx);
    free(vy);
    return s;
}
