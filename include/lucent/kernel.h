/* Lucent kernels: the ground-truth 2-D kernel of a radial profile, separable models of it
 * (Freude 2014, chapters 4-5: SVD rank-N, pre-integration, guided optimisation, manual
 * two-Gaussian; d'Eon's sum of Gaussians; Jimenez's skin kernel), importance-sampled taps and
 * their export as GLSL, HLSL, C and JSON.
 *
 * Units: lengths in mm. A kernel's values are per grid cell and sum to 1 per channel.
 * See docs/kernels.md. */
#ifndef LUCENT_KERNEL_H
#define LUCENT_KERNEL_H

#include <stdbool.h>

#include "lucent/base.h"
#include "lucent/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { LUCENT_KERNEL_MAX_RANK = 16, LUCENT_KERNEL_MAX_GAUSSIANS = 6, LUCENT_KERNEL_MAX_TAPS = 255 };

/* ---- Ground truth (Freude 2014, 6.1-6.2) ------------------------------------------------
 * A (2 half + 1)^2 grid of square cells of side h centred on the origin; cell (i, j) (row i:
 * y = (i - half) h, column j: x = (j - half) h) holds the average of R_d over the cell times
 * its area, normalised so that every channel sums to 1. */
typedef struct lucent_kernel2d {
    int half;         /* cells on each side of the centre; the grid has n = 2 half + 1 */
    double h;         /* cell size, mm */
    double *value[3]; /* n * n values per channel, row-major */
} lucent_kernel2d;

typedef struct lucent_kernel2d_desc {
    double energy; /* the grid reaches the radius holding this fraction of the profile's
                      reflectance (max over channels); 0: the default (0.999) */
    int max_half;  /* most cells on each side; 0: the default (100) */
    double cell;   /* cell size, mm; 0: the larger of the profile's dr and extent / max_half */
} lucent_kernel2d_desc;

/* Returns the defaults a zero lucent_kernel2d_desc stands for (energy 0.999, max_half 100,
 * cell 0: derived from the profile). */
lucent_kernel2d_desc lucent_kernel2d_defaults(void);

/* Rotates the radial profile p onto a grid (supersampled cell averages of the bin values,
 * linear in r between bin centres), normalised per channel. Fails on a profile whose
 * channel has no positive reflectance. Free with lucent_kernel2d_destroy. */
lucent_status lucent_kernel2d_from_profile(const lucent_profile *p, const lucent_kernel2d_desc *desc,
                                           lucent_kernel2d **dest);

/* Frees k (NULL is fine). */
void lucent_kernel2d_destroy(lucent_kernel2d *k);

/* ---- Separable models ----
 * A model is A = sum_i sign_i a_i(x) a_i(y) per channel (rank passes, two 1-D convolutions
 * each), sampled on the ground truth's 1-D grid x_j = (j - half) h. Analytic models (manual,
 * sog, jimenez) also keep their Gaussians, a_i(x) = sum_k w_k exp(-x^2 / (2 v_k)), so that taps
 * evaluate them exactly. The Jimenez model adds a centre delta: (1 - t) delta + t A. */
typedef enum lucent_kernel_model {
    LUCENT_KERNEL_SVD,     /* Freude (5.5)-(5.10); optionally normalised, (5.12) */
    LUCENT_KERNEL_PREINT,  /* pre-integration, Freude (5.15)-(5.18) */
    LUCENT_KERNEL_GUIDED,  /* guided optimisation, Freude (5.19)-(5.20) */
    LUCENT_KERNEL_MANUAL,  /* two Gaussians, Freude (5.21) */
    LUCENT_KERNEL_SOG,     /* d'Eon & Luebke 2007: one 2-D Gaussian per rank */
    LUCENT_KERNEL_JIMENEZ, /* Jimenez's skin kernel, Freude (4.8) */
    LUCENT_KERNEL_MODEL_COUNT
} lucent_kernel_model;

typedef struct lucent_kernel {
    lucent_kernel_model model;
    int rank;                               /* passes, 1..LUCENT_KERNEL_MAX_RANK */
    int half;                               /* 1-D grid: n = 2 half + 1 samples */
    double h;                               /* sample spacing, mm */
    double *a[3];                           /* rank * n samples per channel, pass-major */
    double sign[3][LUCENT_KERNEL_MAX_RANK]; /* +1 or -1 per pass */
    int gaussians;                          /* analytic Gaussians per pass; 0: sampled only */
    double gauss_weight[3][LUCENT_KERNEL_MAX_RANK][LUCENT_KERNEL_MAX_GAUSSIANS];
    double gauss_variance[3][LUCENT_KERNEL_MAX_RANK][LUCENT_KERNEL_MAX_GAUSSIANS]; /* mm^2 */
    double strength[3];                                                            /* Jimenez's t (1: no delta) */
    double range;            /* the taps' default half-width, mm */
    double constraint_error; /* guided: max_c | ||a||_1^2 - ||R_d||_1 | */
} lucent_kernel;

/* The two-Gaussian parameters of Freude (5.21): a(x) = w G(x, tau_n) + (1 - w) G(x, tau_f),
 * G a unit-integral 1-D Gaussian. Standard deviations in mm (Table A.1 gives no unit; Lucent
 * reads them as mm). */
typedef struct lucent_manual_params {
    double sd_near[3]; /* sqrt(tau_n), mm */
    double sd_far[3];  /* sqrt(tau_f), mm */
    double w;          /* near weight, [0, 1] */
} lucent_manual_params;

typedef struct lucent_kernel_desc {
    lucent_kernel_model model;
    int rank;            /* svd and sog: passes (0: 1); the others are rank 1 */
    bool normalize;      /* svd: scale to the ground truth's 1-norm, Freude (5.12) */
    double k;            /* guided: exponent of Gamma (5.20); 0 is a valid value */
    double b;            /* guided: axis damping of Gamma on x, y in [-1, 1]; 0: none */
    int max_evaluations; /* guided: per level; 0: the default (400) */
    bool use_manual;     /* manual: take `manual` instead of the material's preset */
    lucent_manual_params manual;
    double strength[3]; /* jimenez: t per channel; all 0: (0.48, 0.41, 0.28) */
    double falloff[3];  /* jimenez: f per channel; all 0: (1.0, 0.37, 0.3) */
} lucent_kernel_desc;

/* Returns the defaults a zero lucent_kernel_desc stands for with the given model: rank 1,
 * max_evaluations 400, and for jimenez strength (0.48, 0.41, 0.28), falloff (1.0, 0.37, 0.3). */
lucent_kernel_desc lucent_kernel_defaults(lucent_kernel_model model);

/* Returns the model's name ("svd", "preint", "guided", "manual", "sog", "jimenez"). */
const char *lucent_kernel_model_name(lucent_kernel_model model);

/* Parses a model name; LUCENT_ERR_INVALID_ARGUMENT listing the models otherwise. */
lucent_status lucent_kernel_model_parse(const char *name, lucent_kernel_model *dest);

/* Fills dest with the Table A.1 parameters of Freude 2014 for Apple, Ketchup, Marble, Skin1 or
 * Wholemilk (case-insensitive); LUCENT_ERR_NOT_FOUND otherwise. */
lucent_status lucent_manual_preset(const char *material, lucent_manual_params *dest);

/* Builds a model of ground truth gt (profile p: needed by sog, may be NULL otherwise;
 * material_name: manual's preset unless desc->use_manual). The Jimenez model ignores gt's
 * values and samples on its grid. Free with lucent_kernel_destroy. */
lucent_status lucent_kernel_build(const lucent_kernel2d *gt, const lucent_profile *p, const char *material_name,
                                  const lucent_kernel_desc *desc, lucent_kernel **dest);

/* Frees k (NULL is fine). */
void lucent_kernel_destroy(lucent_kernel *k);

/* Returns a_pass(x) of channel c: exact for analytic models, else linear between samples
 * (0 outside the grid). */
double lucent_kernel_eval(const lucent_kernel *k, int c, int pass, double x);

/* Fills dest[c] with the kernel-space RMS of channel c, sqrt(mean((R_d - A)^2)) over gt's cells
 * (Freude Table 6.3); NaN when k was not built on gt's grid. */
void lucent_kernel_rms(const lucent_kernel *k, const lucent_kernel2d *gt, double dest[3]);

/* Fills dest[c] with the 1-norm of the reconstructed kernel, sum |A| (Freude (5.11)). */
void lucent_kernel_norm1(const lucent_kernel *k, double dest[3]);

/* ---- Taps (Jimenez's separable-sss sampling) ----
 * Offsets o_i = range * sign(s) s^2 / range^2, s = -range + i 2 range / (N - 1), listed centre
 * first, then negative ascending, then positive; weight_i = a(o_i) times the tap's interval
 * (half the distance to each neighbour); per-channel normalisation; then the strength blend
 * (centre: 1 - t + t w, others: t w). Rank N: one tap set per pass, scaled per channel so that
 * sum_i sign_i (sum of pass i)^2 = 1. */
typedef struct lucent_taps {
    int count;                              /* taps per pass (odd) */
    int rank;                               /* passes */
    double *offset;                         /* count offsets, mm */
    double *weight[3];                      /* rank * count weights per channel, pass-major */
    double sign[3][LUCENT_KERNEL_MAX_RANK]; /* per pass */
} lucent_taps;

/* The default taps per pass, shared by `lucent kernel`, `lucent pack` and the renderer's ssss.taps. */
enum { LUCENT_KERNEL_DEFAULT_TAPS = 17 };

typedef struct lucent_taps_desc {
    int count;    /* taps; 0: LUCENT_KERNEL_DEFAULT_TAPS; odd, 3..255 */
    double range; /* half-width, mm; 0: the model's (Jimenez: 2, or 3 above 20 taps); at most
                     LUCENT_TAPS_MAX_RANGE */
} lucent_taps_desc;

/* The largest taps' half-width, mm (1 km: beyond it the offsets' squares leave double's range). */
#define LUCENT_TAPS_MAX_RANGE 1e6

/* Returns the defaults a zero lucent_taps_desc stands for (17 taps; range 0: the model's). */
lucent_taps_desc lucent_taps_defaults(void);

/* The largest |offset| of a tap set (mm): the kernel's half-width, and the depth range of the
 * renderer's follow-surface test (times ssss.width_scale). */
double lucent_taps_radius(const lucent_taps *t);

/* Pixels per mm on screen of a surface at linear depth depth_mm (mm) seen by a perspective camera
 * with vertical field of view fov_y_deg (degrees) that renders height_px rows (square pixels):
 *   height / (2 tan(fov_y / 2) depth).
 * A tap at offset o (mm) lands o times this many pixels from the centre; depth 1 gives the scale
 * the renderer's blur divides by the depth (src/gl/shaders/blur.frag.glsl). */
double lucent_screen_pixels_per_mm(int height_px, double fov_y_deg, double depth_mm);

/* The depth (mm) at which an object object_height_mm tall fills the screen's height under that
 * camera: object_height / (2 tan(fov_y / 2)) (lucent pack's and lucent kernel's --object-height). */
double lucent_screen_depth_mm(double object_height_mm, double fov_y_deg);

/* Samples k into taps. Free with lucent_taps_destroy. */
lucent_status lucent_kernel_taps(const lucent_kernel *k, const lucent_taps_desc *desc, lucent_taps **dest);

/* Creates a deep copy of src. Free with lucent_taps_destroy. */
lucent_status lucent_taps_clone(const lucent_taps *src, lucent_taps **dest);

/* Frees t (NULL is fine). */
void lucent_taps_destroy(lucent_taps *t);

/* ---- Export ---- */
typedef enum lucent_kernel_format {
    LUCENT_KERNEL_GLSL,
    LUCENT_KERNEL_HLSL,
    LUCENT_KERNEL_C,
    LUCENT_KERNEL_JSON,
    LUCENT_KERNEL_FORMAT_COUNT
} lucent_kernel_format;

/* Parses a format name ("glsl", "hlsl", "c", "json"); LUCENT_ERR_INVALID_ARGUMENT otherwise. */
lucent_status lucent_kernel_format_parse(const char *name, lucent_kernel_format *dest);

/* Writes taps as text (ending in a newline): GLSL and HLSL declarations plus a one-pass blur
 * function (no #version, no entry point), a C header, or JSON. label names the kernel in
 * comments (may be NULL). Free *dest with free(). */
lucent_status lucent_taps_export(const lucent_taps *t, lucent_kernel_format format, const char *label, char **dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_KERNEL_H */
