/* Lucent skin: the spectral transport of a skin described by its chromophores (lucent_skin in
 * lucent/material.h, the spectra of lucent/spectral.h). Each wavelength band is its own layered medium;
 * the layered multipole (Donner & Jensen 2005) or the Monte Carlo (lucent/mc.h) carries each band, and
 * the bands become linear sRGB through the CIE 1931 observer under D65, per radius (docs/skin.md).
 *
 * A skin material also has an equivalent homogeneous medium per channel (sigma_a, sigma_s, g of the
 * material), for what reads coefficients (the path tracer, the CDRF's spheres, the slab transmittance):
 * the medium whose half-space has, under the same diffusion model, the skin's RGB total diffuse
 * reflectance and the second moment of its RGB profile. lucent_skin_resolve fills it. */
#ifndef LUCENT_SKIN_H
#define LUCENT_SKIN_H

#include <stdint.h>

#include "lucent/base.h"
#include "lucent/material.h"
#include "lucent/mc.h"
#include "lucent/profile.h"
#include "lucent/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    LUCENT_SKIN_MC_PHOTONS = 20000,  /* per band: the "mc" profile's default */
    LUCENT_SKIN_COLOR_PHOTONS = 5000 /* per band: the "mc" colour's default (about 1% per band) */
};

/* How to carry a skin through its bands; zero fields mean the default. */
typedef struct lucent_skin_desc {
    int bands;                /* 1..LUCENT_BANDS_MAX (0: LUCENT_BANDS_DEFAULT) */
    const char *transport;    /* "multipole" (NULL), "mc", or "shortcut": the three-coefficient shortcut
                              (lucent_skin_shortcut_layers), for comparison */
    uint64_t photons;         /* mc: per band (0: LUCENT_SKIN_MC_PHOTONS, colour: LUCENT_SKIN_COLOR_PHOTONS) */
    uint64_t seed;            /* mc: band b is seeded seed * LUCENT_BANDS_MAX + b */
    lucent_pool *pool;        /* mc only; NULL: serial */
    lucent_profile_grid grid; /* zero fields: the Freude Table 6.1 grid of the equivalent medium */
    lucent_cache *cache;      /* mc colour: kept between runs (NULL: none) */
} lucent_skin_desc;

/* What a skin looks like: its total diffuse reflectance per band (specular reflection excluded, normal
 * incidence) and the colour of that spectrum. */
typedef struct lucent_skin_color {
    int bands;
    double center[LUCENT_BANDS_MAX];         /* nm */
    double reflectance[LUCENT_BANDS_MAX];    /* per band */
    double reflectance_se[LUCENT_BANDS_MAX]; /* its standard error (0 for the multipole) */
    double xyz[3];                           /* CIE XYZ under D65, Y of a perfect white = 1 */
    double lab[3];                           /* CIELAB, D65 white */
    double rgb[3];                           /* linear sRGB, white balanced (flat R -> (R, R, R)) */
    double ita;                              /* degrees */
    const char *category;                    /* lucent_ita_category(ita) */
} lucent_skin_color;

/* The multipole layers of m at three wavelengths, one per channel (nm[c]); a semi-infinite last
 * layer becomes a slab of max(10 mm, 30 / sigma_tr) with 2 poles. dest has room for
 * LUCENT_SKIN_MAX_LAYERS; *count receives m's layer count. */
lucent_status lucent_skin_layers(const lucent_material *m, const double nm[3], lucent_layer *dest, int *count);

/* The Monte Carlo layers of m at wavelength nm (lucent/mc.h: sigma_s = sigma_s' / (1 - g), the last
 * layer semi-infinite when it is); dest has room for LUCENT_SKIN_MAX_LAYERS. */
lucent_status lucent_skin_mc_layers(const lucent_material *m, double nm, lucent_mc_layer *dest, int *count);

/* The total diffuse reflectance per band and its colour: by the layered multipole (the transforms at
 * k = 0; fast, the diffusion approximation's error) or by the Monte Carlo ("mc": transport theory, the
 * standard errors in reflectance_se; what the bake's albedo uses). desc NULL: multipole, default bands.
 * "shortcut": the colour of the three-coefficient shortcut's totals (rgb, and xyz, lab, ita from it;
 * no spectrum: reflectance is 0). */
lucent_status lucent_skin_color_of(const lucent_material *m, const lucent_skin_desc *desc, lucent_skin_color *dest);

/* Fills m's sigma_a, sigma_s and g with the equivalent homogeneous medium (see above) and sets
 * m->skin.resolved. A material that is not a skin is left as it is (LUCENT_OK). */
lucent_status lucent_skin_resolve(lucent_material *m);

/* The linear sRGB radial profile of a skin: every band carried by desc->transport on one grid, the
 * bands weighted per radius (multipole: the weighted transforms inverted once; mc: the bands' histograms
 * weighted, standard errors combined). Model "skin-multipole" or "skin-mc"; "shortcut": the layered
 * multipole of the shortcut's three channels ("skin-shortcut"). */
lucent_status lucent_profile_skin(const lucent_material *m, const lucent_skin_desc *desc, lucent_profile **dest);

/* The three-coefficient shortcut: each layer's coefficients averaged per channel first (weights the
 * positive part of lucent_bands' W_cb), then one layered multipole per channel. dest has room for LUCENT_SKIN_MAX_LAYERS. */
lucent_status lucent_skin_shortcut_layers(const lucent_material *m, int bands, lucent_layer *dest, int *count);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_SKIN_H */
