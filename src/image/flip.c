/* LDR-FLIP: the difference a person sees when flipping between a reference and a test image
 * (P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson, K. Astrom, M. D. Fairchild, "FLIP: A
 * Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2), 2020),
 * written from the paper's description:
 *   colour: both images in the linearised opponent space YyCxCz, each channel filtered by its
 *   contrast sensitivity function (a sum of Gaussians in the spatial domain, for an observer at `ppd`
 *   pixels per degree), back to linear RGB clamped to [0, 1], to CIELAB with the Hunt adjustment
 *   (a, b scaled by L / 100), and the HyAB distance |dL| + ||d(a, b)||, raised to q_c = 0.7 and
 *   compressed so that p_c = 0.4 of the largest distance (green against blue) maps to p_t = 0.95 and
 *   the largest to 1;
 *   features: edges and points of the achromatic channel found with the first and second derivatives
 *   of a Gaussian of sigma = 0.5 w ppd (w = 0.082 degrees), each kernel's positive weights summing to 1
 *   and its negative to -1; the feature difference (max of the edge and point magnitude differences
 *   over sqrt 2) raised to q_f = 0.5;
 *   FLIP = colour^(1 - feature), in [0, 1]. */
#include <math.h>
#include <stdlib.h>

#include "image/internal.h"

/* sRGB primaries, D65 (IEC 61966-2-1): linear RGB to CIE XYZ and back. */
static const double k_rgb2xyz[3][3] = {
    {0.4124564, 0.3575761, 0.1804375}, {0.2126729, 0.7151522, 0.0721750}, {0.0193339, 0.1191920, 0.9503041}};
static const double k_xyz2rgb[3][3] = {
    {3.2404542, -1.5371385, -0.4985314}, {-0.9692660, 1.8760108, 0.0415560}, {0.0556434, -0.2040259, 1.0572252}};

/* The contrast sensitivity functions of FLIP (section 4.1, after Johnson and Fairchild): per channel
 * (achromatic, red-green, blue-yellow) S(rho) = a1 exp(-b1 rho^2) + a2 exp(-b2 rho^2), rho in cycles
 * per degree. */
static const double k_csf[3][4] = {{1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};

#define FLIP_QC 0.7
#define FLIP_PC 0.4
#define FLIP_PT 0.95
#define FLIP_QF 0.5
#define FLIP_W 0.082 /* degrees */

static void mat3(const double m[3][3], const double v[3], double dest[3])
{
    for (int r = 0; r < 3; r++) dest[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
}

static void white(double w[3])
{
    const double one[3] = {1, 1, 1};
    mat3(k_rgb2xyz, one, w);
}

static void rgb_to_yycxcz(const double rgb[3], double dest[3])
{
    double xyz[3], w[3];
    mat3(k_rgb2xyz, rgb, xyz);
    white(w);
    double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
    dest[0] = 116 * y - 16, dest[1] = 500 * (x - y), dest[2] = 200 * (y - z);
}

static void yycxcz_to_rgb(const double o[3], double dest[3])
{
    double w[3], y = (o[0] + 16) / 116, xyz[3];
    white(w);
    xyz[0] = (o[1] / 500 + y) * w[0], xyz[1] = y * w[1], xyz[2] = (y - o[2] / 200) * w[2];
    mat3(k_xyz2rgb, xyz, dest);
}

/* Linear RGB to CIELAB with the Hunt adjustment (a and b times L / 100). */
static void rgb_to_hunt_lab(const double rgb[3], double dest[3])
{
    double xyz[3], w[3];
    mat3(k_rgb2xyz, rgb, xyz);
    white(w);
    lucent_xyz_to_lab(xyz, w, dest); /* CIE 15:2004 (cielab.c) */
    dest[1] *= 0.01 * dest[0], dest[2] *= 0.01 * dest[0];
}

static double hyab(const double a[3], const double b[3]) { return fabs(a[0] - b[0]) + hypot(a[1] - b[1], a[2] - b[2]); }

double lucent_flip_color_error(double hyab_distance)
{
    const double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    double g[3], b[3];
    rgb_to_hunt_lab(green, g), rgb_to_hunt_lab(blue, b);
    double cmax = pow(hyab(g, b), FLIP_QC), e = pow(fmax(hyab_distance, 0), FLIP_QC);
    if (e < FLIP_PC * cmax) return FLIP_PT / (FLIP_PC * cmax) * e;
    return fmin(FLIP_PT + (e - FLIP_PC * cmax) / (cmax - FLIP_PC * cmax) * (1 - FLIP_PT), 1.0);
}

double lucent_flip_hyab(const float rgb_a[3], const float rgb_b[3])
{
    double a[3] = {rgb_a[0], rgb_a[1], rgb_a[2]}, b[3] = {rgb_b[0], rgb_b[1], rgb_b[2]}, la[3], lb[3];
    for (int c = 0; c < 3; c++) a[c] = fmin(fmax(a[c], 0), 1), b[c] = fmin(fmax(b[c], 0), 1);
    rgb_to_hunt_lab(a, la), rgb_to_hunt_lab(b, lb);
    return hyab(la, lb);
}

/* ---- filters: every kernel is separable, w(x, y) = f(x) g(y) ---- */

/* A 1-D kernel of taps -radius .. radius. */
typedef struct taps {
    int radius;
    double w[128];
} taps;

/* Convolves plane (w x h) with f along x and g along y, edges clamped, into dest; tmp is w x h. */
static void separable(const double *plane, int w, int h, const taps *f, const taps *g, double *tmp, double *dest)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -f->radius; i <= f->radius; i++) {
                int xx = x + i < 0 ? 0 : x + i >= w ? w - 1 : x + i;
                s += f->w[i + f->radius] * plane[(size_t)y * (size_t)w + (size_t)xx];
            }
            tmp[(size_t)y * (size_t)w + (size_t)x] = s;
        }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int j = -g->radius; j <= g->radius; j++) {
                int yy = y + j < 0 ? 0 : y + j >= h ? h - 1 : y + j;
                s += g->w[j + g->radius] * tmp[(size_t)yy * (size_t)w + (size_t)x];
            }
            dest[(size_t)y * (size_t)w + (size_t)x] = s;
        }
}

/* The radius of the CSF filters: 3 standard deviations of the widest Gaussian of all channels
 * (exp(-pi^2 x^2 / b) has the standard deviation sqrt(b / (2 pi^2)) degrees). */
static int csf_radius(double ppd)
{
    double bmax = 0;
    for (int c = 0; c < 3; c++)
        for (int g = 0; g < 2; g++)
            if (k_csf[c][2 * g] > 0) bmax = fmax(bmax, k_csf[c][2 * g + 1]);
    int r = (int)ceil(3 * sqrt(bmax / (2 * M_PI * M_PI)) * ppd);
    return r < 63 ? r : 63;
}

/* The CSF of channel c applied to plane: each term a exp(-b rho^2) becomes the spatial Gaussian
 * a sqrt(pi / b) exp(-pi^2 r^2 / b), r in degrees: the paper's spatial filter (the one-dimensional
 * inverse Fourier transform, used as the radial profile of the 2-D filter), as the reference
 * implementation weighs its terms (NVlabs/flip src/cpp/FLIP.h at commit 1eb247c, lines 581-595 and
 * 1741-1776, "alternative form (see FLIP paper)"), not the 2-D transform's a pi / b. Only the
 * blue-yellow channel has two terms, so only its shape depends on this weight (tested against the
 * reference's output in tests/test_image.c). Each Gaussian is separable, and the sum of the terms is
 * normalised to 1 over the kernel's square. */
static void csf_filter(int c, double ppd, const double *plane, int w, int h, double *tmp, double *acc, double *dest)
{
    int r = csf_radius(ppd);
    double total = 0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) dest[i] = 0;
    for (int g = 0; g < 2; g++) {
        double a = k_csf[c][2 * g], b = k_csf[c][2 * g + 1];
        if (!(a > 0)) continue;
        taps t = {.radius = r};
        double sum = 0;
        for (int i = -r; i <= r; i++) sum += t.w[i + r] = exp(-M_PI * M_PI * (i / ppd) * (i / ppd) / b);
        double weight = a * sqrt(M_PI / b);
        total += weight * sum * sum;
        separable(plane, w, h, &t, &t, tmp, acc);
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) dest[i] += weight * acc[i];
    }
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) dest[i] /= total;
}

/* The feature detectors of sigma pixels: the Gaussian g (sum 1), its first derivative -x g (edges)
 * and second (x^2 / sigma^2 - 1) g (points), each of the last two with its positive taps summing to 1
 * and its negative to -1; the 2-D detector along x is d(x) g(y). */
static void feature_taps(double sigma, taps *g, taps *edge, taps *point)
{
    int r = (int)ceil(3 * sigma);
    r = r < 63 ? r : 63;
    g->radius = edge->radius = point->radius = r;
    double gs = 0, ep = 0, en = 0, pp = 0, pn = 0;
    for (int i = -r; i <= r; i++) {
        double v = exp(-(double)(i * i) / (2 * sigma * sigma));
        g->w[i + r] = v, edge->w[i + r] = -i * v, point->w[i + r] = ((double)(i * i) / (sigma * sigma) - 1) * v;
        gs += v;
        if (edge->w[i + r] > 0) ep += edge->w[i + r];
        if (edge->w[i + r] < 0) en -= edge->w[i + r];
        if (point->w[i + r] > 0) pp += point->w[i + r];
        if (point->w[i + r] < 0) pn -= point->w[i + r];
    }
    for (int i = 0; i <= 2 * r; i++) {
        g->w[i] /= gs;
        edge->w[i] /= edge->w[i] > 0 ? ep : en > 0 ? en : 1;
        point->w[i] /= point->w[i] > 0 ? pp : pn > 0 ? pn : 1;
    }
}

/* Per pixel of image im: the filtered, Hunt-adjusted Lab (3 per pixel) and the edge and point
 * magnitudes of its luminance. */
static lucent_status flip_planes(const lucent_image *im, double ppd, double *lab, double *edge, double *point)
{
    int w = im->width, h = im->height;
    size_t n = (size_t)w * (size_t)h;
    double *buf = malloc(8 * n * sizeof *buf);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "flip: out of memory");
    double *opp[3] = {buf, buf + n, buf + 2 * n}, *tmp = buf + 3 * n, *acc = buf + 4 * n,
           *out[3] = {buf + 5 * n, buf + 6 * n, buf + 7 * n};
    for (size_t i = 0; i < n; i++) {
        double rgb[3], o[3];
        for (int c = 0; c < 3; c++) rgb[c] = fmin(fmax(im->data[i * (size_t)im->channels + (size_t)c], 0), 1);
        rgb_to_yycxcz(rgb, o);
        for (int c = 0; c < 3; c++) opp[c][i] = o[c];
    }
    for (int c = 0; c < 3; c++) csf_filter(c, ppd, opp[c], w, h, tmp, acc, out[c]);
    for (size_t i = 0; i < n; i++) {
        double o[3] = {out[0][i], out[1][i], out[2][i]}, rgb[3];
        yycxcz_to_rgb(o, rgb);
        for (int c = 0; c < 3; c++) rgb[c] = fmin(fmax(rgb[c], 0), 1);
        rgb_to_hunt_lab(rgb, lab + 3 * i);
        opp[0][i] = (opp[0][i] + 16) / 116; /* the achromatic channel, normalised to [0, 1] */
    }
    taps g, e, p;
    feature_taps(0.5 * FLIP_W * ppd, &g, &e, &p);
    separable(opp[0], w, h, &e, &g, tmp, out[1]), separable(opp[0], w, h, &g, &e, tmp, out[2]);
    for (size_t i = 0; i < n; i++) edge[i] = hypot(out[1][i], out[2][i]);
    separable(opp[0], w, h, &p, &g, tmp, out[1]), separable(opp[0], w, h, &g, &p, tmp, out[2]);
    for (size_t i = 0; i < n; i++) point[i] = hypot(out[1][i], out[2][i]);
    free(buf);
    return LUCENT_OK;
}

lucent_status lucent_image_flip(const lucent_image *reference, const lucent_image *test, double ppd, const float *mask,
                                lucent_image **map, double *mean)
{
    if (map) *map = NULL;
    *mean = NAN;
    if (reference->width != test->width || reference->height != test->height || reference->channels < 3 ||
        test->channels < 3)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "flip: images of %dx%dx%d and %dx%dx%d (RGB of one size)",
                            reference->width, reference->height, reference->channels, test->width, test->height,
                            test->channels);
    if (!(ppd > 0) || !isfinite(ppd) || ppd > 400)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "flip: pixels per degree: expected (0, 400], got %g", ppd);
    int w = reference->width, h = reference->height;
    size_t n = (size_t)w * (size_t)h;
    double *buf = malloc(10 * n * sizeof *buf);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "flip: out of memory");
    double *lab[2] = {buf, buf + 3 * n}, *edge[2] = {buf + 6 * n, buf + 7 * n}, *point[2] = {buf + 8 * n, buf + 9 * n};
    lucent_status s = flip_planes(reference, ppd, lab[0], edge[0], point[0]);
    if (s == LUCENT_OK) s = flip_planes(test, ppd, lab[1], edge[1], point[1]);
    if (s == LUCENT_OK && map) s = lucent_image_create(w, h, 1, map);
    double sum = 0;
    uint64_t count = 0;
    for (size_t i = 0; s == LUCENT_OK && i < n; i++) {
        if (mask && !(mask[i] > 0.5f)) {
            if (map) (*map)->data[i] = 0;
            continue;
        }
        double c = lucent_flip_color_error(hyab(lab[0] + 3 * i, lab[1] + 3 * i));
        double f = fmax(fabs(edge[0][i] - edge[1][i]), fabs(point[0][i] - point[1][i])) / sqrt(2.0);
        double v = pow(c, 1 - pow(fmin(f, 1.0), FLIP_QF));
        if (map) (*map)->data[i] = (float)v;
        sum += v, count++;
    }
    free(buf);
    if (s != LUCENT_OK) {
        if (map) lucent_image_destroy(*map), *map = NULL;
        return s;
    }
    *mean = count ? sum / (double)count : NAN;
    return LUCENT_OK;
}
