/* Lucent convolve: CPU convolution of images with subsurface-scattering kernels, and the
 * test signals of Freude 2014 (section 6.2). Independent of the kernel model types: kernels
 * come in as plain arrays of weights in pixel units.
 *
 *  - lucent_convolve_2d:        exact linear 2-D convolution with the full kernel (FFT);
 *  - lucent_convolve_2d_direct: the same by the O(n k^2) sum (the reference in tests);
 *  - lucent_convolve_separable: a horizontal then a vertical pass with full 1-D kernels, and
 *                               the rank-N sum of such passes (SVD models);
 *  - lucent_convolve_taps:      the same two passes with N taps at fractional pixel offsets,
 *                               sampled with linear interpolation (Jimenez's shader, Freude
 *                               Algorithm 4.1, without the depth-aware part).
 *
 * Conventions (docs/convolution.md):
 *  - Every function computes a convolution, dest(x, y) = sum_ij K(i, j) src(x - i, y - j), with
 *    pixel offsets i, j and K's centre weight at offset (0, 0); a delta image reproduces the
 *    kernel unflipped. For the symmetric kernels of every SSS model this equals the shader's
 *    gather sum_k w_k src(x + o_k).
 *  - Pixel (x, y) has its centre at (x + 0.5, y + 0.5) pixels; x grows to the right, y down
 *    (top row first, as lucent_image). Offsets are in pixels; a kernel in mm is turned into
 *    pixels by dividing by the millimetres per pixel of the image.
 *  - Colour channels 0..2 (or the only channel of a grey image) are convolved, each with its
 *    own weights; a 4th channel (alpha) is copied unchanged.
 *  - Weights for channel c: w[c]; w[1] or w[2] NULL means "use w[0]" (one grey kernel).
 *  - dest is a created image of the same width, height and channels as src; it may be src.
 *  - pool may be NULL (everything runs on the caller); results do not depend on the pool. */
#ifndef LUCENT_CONVOLVE_H
#define LUCENT_CONVOLVE_H

#include "lucent/base.h"
#include "lucent/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest kernel side / 1-D kernel length accepted (pixels). */
#define LUCENT_CONVOLVE_MAX_SIZE 8191

/* What lies outside the image. */
typedef enum lucent_border {
    LUCENT_BORDER_CLAMP = 0, /* the nearest edge pixel (GL_CLAMP_TO_EDGE) */
    LUCENT_BORDER_ZERO       /* black (GL_CLAMP_TO_BORDER with a black border) */
} lucent_border;

/* A square 2-D kernel per colour channel, in pixel units, centre in the middle. */
typedef struct lucent_conv_kernel2d {
    int size;          /* odd side length; weight (i, j) for offsets -size/2 .. size/2 */
    const float *w[3]; /* size * size weights per channel, row-major, top row (j = -size/2)
                          first: w[c][(j + size/2) * size + (i + size/2)]; w[1], w[2] may be NULL */
} lucent_conv_kernel2d;

/* N taps of a 1-D kernel, the form the GPU passes use; rank > 1 sums several two-pass
 * convolutions (rank-N models): dest = sum_p sign_p (src * taps_p horizontally * taps_p
 * vertically). */
typedef struct lucent_conv_taps {
    int count;            /* taps per pass, >= 1 */
    int rank;             /* passes summed; 0: 1 */
    const float *offsets; /* count offsets in pixels, any sign, may be fractional; every pass */
    /* rank * count weights per channel, pass-major; weights[1], weights[2] may be NULL */
    const float *weights[3];
    const float *sign[3]; /* rank factors per channel (+1 / -1 for SVD terms); NULL: all +1 */
} lucent_conv_taps;

/* Returns the name of a border mode ("clamp", "zero"); parses it back (LUCENT_ERR_INVALID_ARGUMENT
 * listing the names if unknown). */
const char *lucent_border_name(lucent_border border);
lucent_status lucent_border_parse(const char *name, lucent_border *dest);

/* Checks a 2-D kernel: size odd, 1 .. LUCENT_CONVOLVE_MAX_SIZE, w[0] set, weights finite.
 * The message names the field ("kernel size", "kernel w[1][17]"). */
lucent_status lucent_conv_kernel2d_check(const lucent_conv_kernel2d *kernel);

/* Exact linear (not circular) 2-D convolution through FFTW (r2c / c2r on the zero-padded,
 * border-extended channel, double precision). Agrees with lucent_convolve_2d_direct to float
 * rounding. Size errors (dest, even kernel) give LUCENT_ERR_INVALID_ARGUMENT naming the
 * parameter; FFTW memory failure gives LUCENT_ERR_OUT_OF_MEMORY. */
lucent_status lucent_convolve_2d(const lucent_image *src, const lucent_conv_kernel2d *kernel, lucent_border border,
                                 lucent_pool *pool, lucent_image *dest);

/* The same convolution by direct summation, O(width height size^2): the reference. */
lucent_status lucent_convolve_2d_direct(const lucent_image *src, const lucent_conv_kernel2d *kernel,
                                        lucent_border border, lucent_pool *pool, lucent_image *dest);

/* Separable convolution: a horizontal pass with kx[c], then a vertical pass with ky[c]
 * (length odd; entry i is the weight of offset i - length/2). Equals lucent_convolve_2d with the
 * outer product K(i, j) = kx[i] ky[j], borders included. ky may be NULL: ky = kx. */
lucent_status lucent_convolve_separable(const lucent_image *src, const float *const kx[3], const float *const ky[3],
                                        int length, lucent_border border, lucent_pool *pool, lucent_image *dest);

/* The rank-N sum: dest = sum_r (src * kx_r ky_r^T), for SVD rank-N kernel models (fold a term's
 * sign into its kx_r). kx and ky hold rank * 3 pointers, term r's channel c at [r * 3 + c]
 * (channels 1, 2 NULL: channel 0); ky may be NULL: ky = kx. */
lucent_status lucent_convolve_separable_sum(const lucent_image *src, int rank, const float *const *kx,
                                            const float *const *ky, int length, lucent_border border, lucent_pool *pool,
                                            lucent_image *dest);

/* Two passes with taps, horizontal then vertical: dest(x) = sum_k w_k src(x - o_k), where a
 * fractional position is read by linear interpolation between the two nearest pixel centres
 * (the GPU's bilinear fetch along one axis), the border applied to each of the two pixels.
 * Integer offsets give the separable convolution with the equivalent sparse kernel. With rank > 1
 * the passes of every term are summed, term p scaled by sign[c][p]. Offsets in mm become pixels
 * by dividing by the image's mm per pixel (the GPU's per-pixel kernel scale is not applied). */
lucent_status lucent_convolve_taps(const lucent_image *src, const lucent_conv_taps *taps, lucent_border border,
                                   lucent_pool *pool, lucent_image *dest);

/* ---- Test signals (Freude 2014, section 6.2) ----------------------------------------------
 * 3-channel (RGB) linear images, values in [0, 1], edges antialiased by 4 x 4 supersampling.
 * The shapes scale with the image; the suggested scale is LUCENT_SIGNAL_MM_PER_PIXEL, so a
 * 256-pixel signal covers 25.6 mm and a kernel of a few mm blurs a visible band. */
#define LUCENT_SIGNAL_MM_PER_PIXEL 0.1
#define LUCENT_SIGNAL_DEFAULT_SIZE 256

/* The vertical white-black edge: x < width / 2 is 1, the rest 0 (with an odd width the middle
 * column, cut by the edge through its centre, is 0.5). */
lucent_status lucent_signal_edge(int width, int height, lucent_image **dest);

/* A white circle and two tilted adjacent squares of different intensities on black (after the
 * figure of Freude Figures 6.6-6.10). With s = min(width, height), centred in the image:
 * circle of radius 0.2 s at (-0.25 s, 0) from the centre, value 1; two squares of side 0.22 s,
 * rotated by 30 degrees (clockwise on screen), sharing one side whose midpoint is at (0.22 s, 0),
 * values 1 (upper left) and 0.5 (lower right). At 256 pixels and 0.1 mm per pixel: a circle of
 * 10.2 mm diameter and squares of 5.6 mm side. */
lucent_status lucent_signal_shapes(int width, int height, lucent_image **dest);

/* A signal by name: "edge" or "shapes" (made at width x height; 0: LUCENT_SIGNAL_DEFAULT_SIZE),
 * else a path to a PNG, EXR or PFM file (read as it is, converted to RGB if grey). */
lucent_status lucent_signal_load(const char *spec, int width, int height, lucent_image **dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_CONVOLVE_H */
