/* Lucent image: linear float RGB(A) images; PNG, OpenEXR and PFM files; tonemapping;
 * difference images and error metrics (RMS, relative RMS, optionally under a mask).
 *
 * Pixels are linear light, row-major, top row first, channels interleaved.
 * sRGB encoding happens only at the border, when a PNG is written or read. */
#ifndef LUCENT_IMAGE_H
#define LUCENT_IMAGE_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest image accepted anywhere (creation and every reader): 2^28 pixels (4 GiB of RGBA
 * floats) and 2^20 pixels on a side, so a corrupt header cannot ask for terabytes. */
#define LUCENT_IMAGE_MAX_PIXELS (1ull << 28)
#define LUCENT_IMAGE_MAX_SIDE (1 << 20)

/* The most pixels an image file may declare to be read (PNG, EXR, PFM), checked against the header
 * before any pixel is decoded or allocated, so that a small file declaring a huge image (a
 * decompression bomb) is refused: "<file>: declares 30000x30000 pixels (900 Mpixels), above the read
 * limit of 64 Mpixels". Default 2^26 (64 Mpixels: 1 GiB as float RGBA), or the environment variable
 * LUCENT_IMAGE_MAX_PIXELS; at most LUCENT_IMAGE_MAX_PIXELS. */
#define LUCENT_IMAGE_DEFAULT_READ_PIXELS (1ull << 26)
void lucent_image_set_read_limit(uint64_t pixels); /* 0: back to the default */
uint64_t lucent_image_read_limit(void);

typedef struct lucent_image {
    int width;
    int height;
    int channels; /* 1 (grey), 3 (RGB) or 4 (RGBA, alpha not premultiplied) */
    float *data;  /* width * height * channels floats, row-major, top row first */
} lucent_image;

/* ---- Creation and pixel access ------------------------------------------- */

/* Creates a zero-filled image. Sizes < 1, channels other than 1, 3, 4, or a size over
 * the limits above give LUCENT_ERR_INVALID_ARGUMENT; *dest is NULL on failure. */
lucent_status lucent_image_create(int width, int height, int channels, lucent_image **dest);

/* Frees an image (NULL is allowed). */
void lucent_image_destroy(lucent_image *img);

/* Creates a deep copy of src. */
lucent_status lucent_image_clone(const lucent_image *src, lucent_image **dest);

/* Creates a copy of src with another channel count: 1 -> 3/4 replicates grey, 3 -> 4 adds
 * alpha 1, 4 -> 3 drops alpha, 3/4 -> 1 takes Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B. */
lucent_status lucent_image_convert_channels(const lucent_image *src, int channels, lucent_image **dest);

/* Returns the number of floats in the image (width * height * channels). */
size_t lucent_image_value_count(const lucent_image *img);

/* Returns the pointer to pixel (x, y) (asserts that it lies inside). */
float *lucent_image_pixel(const lucent_image *img, int x, int y);

/* Returns channel c of pixel (x, y) (asserts that all lie inside). */
float lucent_image_get(const lucent_image *img, int x, int y, int c);

/* Sets channel c of pixel (x, y) to value (asserts that all lie inside). */
void lucent_image_set(lucent_image *img, int x, int y, int c, float value);

/* Sets every value of channel c (all channels when c < 0) to value. */
void lucent_image_fill(lucent_image *img, int c, float value);

/* ---- Colour ------------------------------------------------------------------ */

/* Linear -> sRGB-encoded with the exact IEC 61966-2-1 piecewise curve:
 * 12.92 x for x <= 0.0031308, else 1.055 x^(1/2.4) - 0.055. Values <= 0 give 0 (NaN gives 0). */
float lucent_srgb_encode(float linear);

/* sRGB-encoded -> linear, the inverse: e / 12.92 for e <= 0.04045, else ((e + 0.055) / 1.055)^2.4. */
float lucent_srgb_decode(float encoded);

/* ---- Files ------------------------------------------------------------------- */

typedef enum lucent_image_format {
    LUCENT_IMAGE_FORMAT_AUTO = 0, /* from the file name's extension */
    LUCENT_IMAGE_FORMAT_PNG,
    LUCENT_IMAGE_FORMAT_EXR,
    LUCENT_IMAGE_FORMAT_PFM
} lucent_image_format;

typedef enum lucent_exr_pixel {
    LUCENT_EXR_PIXEL_DEFAULT = 0, /* float */
    LUCENT_EXR_PIXEL_FLOAT,
    LUCENT_EXR_PIXEL_HALF
} lucent_exr_pixel;

typedef enum lucent_exr_compression {
    LUCENT_EXR_COMPRESSION_DEFAULT = 0, /* zip */
    LUCENT_EXR_COMPRESSION_NONE,
    LUCENT_EXR_COMPRESSION_RLE,
    LUCENT_EXR_COMPRESSION_ZIPS,
    LUCENT_EXR_COMPRESSION_ZIP,
    LUCENT_EXR_COMPRESSION_PIZ
} lucent_exr_compression;

/* How to write an image; a zero field means the default (lucent_image_write_defaults). */
typedef struct lucent_image_write_desc {
    lucent_image_format format; /* default: from the extension (.png, .exr, .pfm) */
    /* PNG: 8 (default) or 16 bits per sample. Colour samples are sRGB-encoded at both depths
     * (and marked with sRGB, gAMA and cHRM chunks), unless png_linear, which stores them
     * linearly and marks the file with gAMA 1.0. Alpha is always linear. Values are clamped
     * to [0, 1] and rounded to the nearest code; NaN is written as 0. */
    int png_bits;
    bool png_linear;
    lucent_exr_pixel exr_pixel;             /* default float */
    lucent_exr_compression exr_compression; /* default zip */
} lucent_image_write_desc;

/* Returns the write defaults with every field resolved. */
lucent_image_write_desc lucent_image_write_defaults(void);

/* ---- Labels ---------------------------------------------------------------
 * A 5 x 7 pixel font (src/image/text.c): upper-case letters, the lower-case letters of Lucent's
 * labels (others are drawn upper case), digits and . , - + / ^ ( ) : = %. Each glyph is 6 x 8
 * pixels with its spacing, times scale. */

/* Draws text with its top-left corner at (x, y), scale pixels per font pixel (>= 1), in linear RGB
 * (images of 3 or 4 channels; others are left alone); what falls outside the image is clipped. */
void lucent_image_draw_text(lucent_image *img, int x, int y, int scale, const float rgb[3], const char *text);

/* The width in pixels that text takes at scale (no spacing after the last glyph). */
int lucent_image_text_width(const char *text, int scale);

/* The version of the OpenEXR core library linked, e.g. "3.1.5" (its exr_get_library_version). */
const char *lucent_image_openexr_version(void);

/* Tells the format from a path's extension (case-insensitive .png, .exr, .pfm);
 * LUCENT_ERR_UNSUPPORTED with a message naming the path otherwise. */
lucent_status lucent_image_format_from_path(const char *path, lucent_image_format *dest);

/* Reads a PNG, EXR or PFM file, chosen by extension, into a new linear float image.
 * Every failure names the file in the message. */
lucent_status lucent_image_load(const char *path, lucent_image **dest);

/* Reads a PNG: grey gives 1 channel; grey+alpha, RGB, palette and tRNS give 3 or 4 channels.
 * 1, 2, 4, 8 and 16-bit samples are scaled to [0, 1]; colour is decoded with the sRGB curve,
 * or with 1/gamma when the file has a gAMA chunk and no sRGB chunk (gAMA 1.0: linear). */
lucent_status lucent_image_load_png(const char *path, lucent_image **dest);

/* Reads part 0 of an OpenEXR file (scanline or tiled, level 0; half, float or uint samples):
 * channels R, G, B [, A] give 3 or 4 channels; Y [, A] gives 1 or 4; a lone channel gives 1. */
lucent_status lucent_image_load_exr(const char *path, lucent_image **dest);

/* Reads a PFM file ("PF": RGB, "Pf": grey; negative scale: little endian; rows bottom-to-top). */
lucent_status lucent_image_load_pfm(const char *path, lucent_image **dest);

/* Writes img atomically (complete file or none) in the format of desc (NULL: defaults). */
lucent_status lucent_image_write(const char *path, const lucent_image *img, const lucent_image_write_desc *desc);

/* Writes a PNG (grey, RGB or RGBA by channel count) as desc says. */
lucent_status lucent_image_write_png(const char *path, const lucent_image *img, const lucent_image_write_desc *desc);

/* Writes a single-part scanline OpenEXR file with channels Y, or R, G, B [, A]. */
lucent_status lucent_image_write_exr(const char *path, const lucent_image *img, const lucent_image_write_desc *desc);

/* Writes a little-endian PFM ("Pf" for 1 channel, "PF" for 3; 4 channels are refused). */
lucent_status lucent_image_write_pfm(const char *path, const lucent_image *img);

/* ---- Tonemapping -------------------------------------------------------------- */

typedef enum lucent_tonemap_op {
    LUCENT_TONEMAP_NONE = 0, /* identity (a PNG writer still clamps to [0, 1]) */
    LUCENT_TONEMAP_CLAMP,    /* clamp to [0, 1] */
    LUCENT_TONEMAP_REINHARD, /* x / (1 + x), per channel (Reinhard et al. 2002, eq. 3) */
    LUCENT_TONEMAP_FILMIC    /* Narkowicz 2015 ACES fit: x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14) */
} lucent_tonemap_op;

typedef struct lucent_tonemap_desc {
    lucent_tonemap_op op; /* default none */
    float exposure;       /* stops: values are multiplied by 2^exposure first; default 0 */
} lucent_tonemap_desc;

/* Parses "none", "clamp", "reinhard" or "filmic"; LUCENT_ERR_INVALID_ARGUMENT listing them otherwise. */
lucent_status lucent_tonemap_op_parse(const char *name, lucent_tonemap_op *dest);

/* Returns the operator's name ("none", "clamp", "reinhard", "filmic"; "unknown" out of range). */
const char *lucent_tonemap_op_name(lucent_tonemap_op op);

/* Returns the operator applied to one linear value (already exposed); NaN gives 0 except for none. */
float lucent_tonemap_value(lucent_tonemap_op op, float x);

/* Applies exposure, then the operator, to every colour channel of img in place (alpha untouched).
 * The result is still linear; sRGB encoding happens when writing a PNG. */
void lucent_image_tonemap(lucent_image *img, const lucent_tonemap_desc *desc);

/* ---- Statistics, differences and error metrics -------------------------------- */

/* Per-channel summary of one image. Non-finite values are counted, not summed. */
typedef struct lucent_image_stats {
    int channels;
    double min[4], max[4], mean[4];
    uint64_t nonfinite[4];
} lucent_image_stats;

/* Computes per-channel min, max and mean of the finite values (0 when there are none). */
void lucent_image_stats_compute(const lucent_image *img, lucent_image_stats *dest);

/* Errors of an image a against a reference b over the counted pixels (all, or mask > 0.5):
 *   rms[c]     = sqrt(mean((a - b)^2))
 *   rel_rms[c] = rms[c] / sqrt(mean(b^2))   (0 when both are 0; +inf when only b's is 0)
 *   max_abs[c] = max |a - b|
 * and the same pooled over all channels in rms_all / rel_rms_all. */
typedef struct lucent_image_error_stats {
    int channels;
    uint64_t pixel_count; /* pixels counted (those under the mask) */
    double rms[4], rel_rms[4], max_abs[4];
    double rms_all, rel_rms_all;
} lucent_image_error_stats;

/* Compares a with the reference b. mask: NULL (every pixel) or width * height floats, where
 * pixels with mask > 0.5 count. Sizes or channel counts that differ give
 * LUCENT_ERR_INVALID_ARGUMENT naming both; a mask selecting no pixel too. */
lucent_status lucent_image_compare(const lucent_image *a, const lucent_image *b, const float *mask,
                                   lucent_image_error_stats *dest);

/* As lucent_image_compare, with the mask given as a 1-channel image of the same size (or NULL). */
lucent_status lucent_image_compare_masked(const lucent_image *a, const lucent_image *b, const lucent_image *mask,
                                          lucent_image_error_stats *dest);

/* ---- FLIP: the difference seen when flipping between two images --------------------------------
 * LDR-FLIP (Andersson et al. 2020, written from the paper): reference and test are displayed images,
 * linear RGB in [0, 1] (tonemapped; values outside are clamped), seen from ppd pixels per degree (the
 * paper's observer: 67, at 0.7 m from a 0.7 m wide 3840-pixel screen). */

/* The observer the paper assumes: 0.7 m from a 0.7 m wide screen of 3840 pixels. */
#define LUCENT_FLIP_PPD 67.0

/* The per-pixel FLIP map (1 channel, 0 where the two look the same, 1 for the largest difference;
 * NULL map: none) and its mean over the mask (NULL: every pixel; NaN when the mask is empty). */
lucent_status lucent_image_flip(const lucent_image *reference, const lucent_image *test, double ppd, const float *mask,
                                lucent_image **map, double *mean);

/* FLIP's colour error of a HyAB distance: d^0.7 compressed so that 0.4 of the largest distance's
 * (green against blue, Hunt-adjusted) maps to 0.95 and the largest to 1 (Andersson et al. 2020,
 * section 4.1). */
double lucent_flip_color_error(double hyab_distance);

/* The HyAB distance |dL| + ||d(a, b)|| between two linear RGB colours (clamped to [0, 1]) in CIELAB with
 * the Hunt adjustment (a, b times L / 100), white D65. */
double lucent_flip_hyab(const float rgb_a[3], const float rgb_b[3]);

typedef enum lucent_diff_mode {
    LUCENT_DIFF_SIGNED = 0, /* a - b per channel */
    LUCENT_DIFF_ABSOLUTE    /* |a - b| per channel */
} lucent_diff_mode;

/* Creates the per-channel difference image of a and b (same size and channels). */
lucent_status lucent_image_difference(const lucent_image *a, const lucent_image *b, lucent_diff_mode mode,
                                      lucent_image **dest);

/* Creates a 1-channel map of the per-pixel error of a against the reference b, averaged over the
 * colour channels (alpha ignored): |a - b| when !relative, |a - b| / (|b| + epsilon) when relative
 * (epsilon <= 0: 0.01). Same size and channels required. */
lucent_status lucent_image_error_map(const lucent_image *a, const lucent_image *b, bool relative, float epsilon,
                                     lucent_image **dest);

/* Returns the p-th percentile (0 <= p <= 100, nearest rank) of channel c's finite values in *dest
 * (0 when none). Allocates a scratch copy of the channel. */
lucent_status lucent_image_percentile(const lucent_image *img, int c, double p, float *dest);

/* Creates an RGB false-colour heat map of a 1-channel image: value / scale, clamped to [0, 1],
 * through a black - purple - red - orange - yellow - white ramp (linear RGB, so the PNG shows
 * the ramp's sRGB colours). scale <= 0: the 99th percentile of the values (1 when that is 0). */
lucent_status lucent_image_heatmap(const lucent_image *values, float scale, lucent_image **dest);

/* The scale lucent_image_heatmap uses: scale when > 0, else the 99th percentile of the values (1 when
 * that is 0). */
lucent_status lucent_image_heatmap_scale(const lucent_image *values, float scale, float *dest);

/* The heat map of values (as lucent_image_heatmap) with its colour bar below: the ramp from 0 to the
 * scale, labelled with 0, the middle and the scale, and `label` (what the values are, e.g. "A-B";
 * NULL: none). The image is at least 200 pixels wide (the map at the top left, on black). *used (may
 * be NULL) receives the scale. */
lucent_status lucent_image_heatmap_with_bar(const lucent_image *values, float scale, const char *label,
                                            lucent_image **dest, float *used);
/* ---- Colour differences -----------------------------------------------------------------------
 * Linear sRGB (IEC 61966-2-1 primaries, white D65) to CIE XYZ and CIELAB (reference white D65:
 * Xn = 0.95047, Yn = 1, Zn = 1.08883), and the CIEDE2000 colour difference (Sharma, Wu & Dalal 2005). */

/* XYZ of linear sRGB rgb (Y = 1 for white). */
void lucent_linear_srgb_to_xyz(const double rgb[3], double dest[3]);

/* CIELAB (CIE 15:2004) of XYZ relative to the white white_xyz (for a spectral reflectance, the bands' white:
 * D65 through the same tables, so that a flat reflector has a* = b* = 0). */
void lucent_xyz_to_lab(const double xyz[3], const double white_xyz[3], double lab[3]);

/* CIELAB (L*, a*, b*) of linear sRGB rgb against the D65 white. */
void lucent_linear_srgb_to_lab(const double rgb[3], double dest[3]);

/* The CIEDE2000 difference of two CIELAB colours (k_L = k_C = k_H = 1). */
double lucent_ciede2000(const double lab1[3], const double lab2[3]);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_IMAGE_H */
