/* Lucent spectral: wavelength bands over the visible range, colour through the CIE 1931 2-degree
 * observer under D65, CIELAB, the individual typology angle (ITA) and CIEDE2000, and the chromophores
 * of skin (melanin, haemoglobin, the baseline) from the published spectra of data/spectra.json.
 *
 * The colour convention (docs/skin.md): a reflectance spectrum R(lambda) becomes linear sRGB as
 * rgb_c = sum_b W[c][b] R_b, with W[c][b] = integral over band b of (M xbar, ybar, zbar)_c D65 dlambda
 * (M: the sRGB matrix of IEC 61966-2-1), each channel's weights divided by their sum (the white
 * balance), so a flat reflector R gives (R, R, R). Wavelengths in nm. */
#ifndef LUCENT_SPECTRAL_H
#define LUCENT_SPECTRAL_H

#include "lucent/base.h"
#include "lucent/image.h" /* lucent_xyz_to_lab, lucent_ciede2000 */
#include "lucent/material.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LUCENT_SPECTRAL_MIN_NM 380.0
#define LUCENT_SPECTRAL_MAX_NM 780.0
enum {
    LUCENT_BANDS_MAX = 80, /* 5 nm bands */
    LUCENT_BANDS_DEFAULT = 20
};

/* count equal bands over [380, 780] nm; band b covers [380 + b w, 380 + (b + 1) w], w = 400 / count,
 * and is sampled at its centre. */
typedef struct lucent_bands {
    int count;
    double width;                    /* nm */
    double center[LUCENT_BANDS_MAX]; /* nm */
    double rgb[3][LUCENT_BANDS_MAX]; /* linear sRGB weights, white balanced: each row sums to 1 */
    double xyz[3][LUCENT_BANDS_MAX]; /* CIE XYZ weights under D65, Y of a flat reflector of 1 = 1 */
    double white_xyz[3];             /* XYZ of a flat reflector of 1 (Y = 1) */
    double rgb_unbalanced[3];        /* sRGB of that white before the white balance (~1) */
} lucent_bands;

/* Fills dest with count bands (1..LUCENT_BANDS_MAX; 0: LUCENT_BANDS_DEFAULT). The weights integrate
 * the linear interpolants of the 5 nm CIE tables exactly over each band. */
lucent_status lucent_bands_make(int count, lucent_bands *dest);

/* CIE XYZ (Y of a perfect white = 1) and linear sRGB of a reflectance spectrum sampled per band. */
void lucent_bands_xyz(const lucent_bands *b, const double *reflectance, double xyz[3]);
void lucent_bands_rgb(const lucent_bands *b, const double *reflectance, double rgb[3]);

/* The XYZ of a white-balanced linear sRGB colour under these bands (the inverse of lucent_bands_rgb's
 * mapping for a spectrum: the white balance undone, the sRGB matrix inverted). */
void lucent_bands_rgb_to_xyz(const lucent_bands *b, const double rgb[3], double xyz[3]);

/* CIELAB of XYZ against a white (lucent_xyz_to_lab) and the CIEDE2000 difference (lucent_ciede2000): in
 * lucent/image.h, the image room's colour differences, which the skin's colours use. */

/* The individual typology angle ITA = atan((L* - 50) / b*) in degrees (Chardon et al. 1991), and its
 * category (Del Bino et al. 2006): "very light" (> 55), "light" (41..55], "intermediate" (28..41],
 * "tan" (10..28], "brown" (-30..10], "dark" (<= -30). */
double lucent_ita(const double lab[3]);
const char *lucent_ita_category(double ita);

/* ---- Chromophores (mm^-1 at wavelength nm in [380, 780]; data/spectra.json) ---- */

/* Whole blood (150 g Hb per litre) of oxygen saturation s: s mu_a(HbO2) + (1 - s) mu_a(Hb) (Prahl). */
double lucent_blood_absorption(double nm, double saturation);
/* Melanin of eumelanin share e: e sigma_a(eumelanin) + (1 - e) sigma_a(pheomelanin) (Donner & Jensen 2006). */
double lucent_melanin_absorption(double nm, double eumelanin);
/* The skin's baseline absorption (Donner & Jensen 2006 after Jacques / Saidi). */
double lucent_baseline_absorption(double nm);

/* ---- Skin layers (lucent_skin in lucent/material.h) ---- */

/* The default layer of a kind: thickness (epidermis 0.1 mm, dermis semi-infinite, hypodermis
 * semi-infinite), no chromophores, oxygenation 0.75, eumelanin 0.7, g 0.8 and the layer's published
 * scattering (data/spectra.json: Jacques 2013 for epidermis and dermis, Bashkatov 2005 for fat). */
void lucent_skin_layer_defaults(lucent_skin_layer_kind kind, lucent_skin_layer *dest);

/* The name of a layer kind ("epidermis", "dermis", "hypodermis"); NULL for others. */
const char *lucent_skin_layer_name(int kind);

/* Checks a skin's layers; the message names the material (name) and the field
 * ("skin.epidermis.melanin: must be in [0, 1], got 1.5"). */
lucent_status lucent_skin_validate(const lucent_skin *skin, const char *name);

/* Layer `layer`'s absorption and reduced scattering at wavelength nm, mm^-1:
 *   sigma_a = M sigma_a,mel + B sigma_a,blood + (1 - M - B) sigma_a,baseline   (Jacques 1998, D&J 2006)
 *   sigma_s' = scatter (f_ray (nm/500)^-4 + (1 - f_ray) (nm/500)^-b_mie)         (Jacques 2013, eq. 2) */
void lucent_skin_coefficients(const lucent_skin *skin, int layer, double nm, double *sigma_a, double *sigma_s_prime);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_SPECTRAL_H */
