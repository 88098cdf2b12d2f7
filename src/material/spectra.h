/* The published spectra of data/spectra.json as tables (internal to the library; lucent/spectral.h is
 * the public face). */
#ifndef LUCENT_MATERIAL_SPECTRA_H
#define LUCENT_MATERIAL_SPECTRA_H

#include "lucent/base.h"

#define SPECTRA_CIE_START 380.0
#define SPECTRA_CIE_STEP 5.0
#define SPECTRA_HB_START 380.0
#define SPECTRA_HB_STEP 2.0
enum { SPECTRA_CIE_COUNT = 81, SPECTRA_HB_COUNT = 201 };

typedef struct lucent_spectra {
    double cmf[3][SPECTRA_CIE_COUNT];    /* CIE 1931 xbar, ybar, zbar */
    double d65[SPECTRA_CIE_COUNT];       /* D65, 100 at 560 nm */
    double hb[2][SPECTRA_HB_COUNT];      /* molar extinction of HbO2, Hb, cm^-1 / (mol/L) */
    double hb_molar_mass, hb_per_liter;  /* g/mol, g/L */
    double eumelanin[2], pheomelanin[2]; /* a, b: a lambda^-b mm^-1 */
    double baseline[4];                  /* a, c, l0, w: a + c exp(-(lambda - l0) / w) mm^-1 */
    double scatter[3][3];                /* per layer kind: a' (mm^-1 at 500 nm), f_ray, b_mie */
    double xyz_to_rgb[9];                /* row-major */
} lucent_spectra;

/* The tables, read once; NULL when data/spectra.json could not be read (lucent_spectra_ready says why). */
const lucent_spectra *lucent_spectra_get(void);
lucent_status lucent_spectra_ready(void);

/* Linear interpolation of a table at x, clamped to its ends. */
double lucent_spectra_lerp(const double *table, double start, double step, int count, double x);

#endif
