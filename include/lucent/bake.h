/* Lucent bake: what any renderer needs from a material, prepared on the CPU before the first frame:
 * the radial profile, the separable kernel's taps, the transmittance through a thickness, the CDRF's
 * sigma0. Each part is built from the settings it depends on and rebuilt only when one of them
 * changed; the Monte Carlo parts (slab transmittance, sigma0 fit) are kept in a disk cache.
 *
 *   part           depends on                                  built by
 *   profile        ssss.profile                                lucent_profile_from_source
 *   taps           the profile, ssss.kernel, rank, taps        lucent_kernel_build, lucent_kernel_taps
 *   transmittance  translucency.transmittance (and the         lucent_slab_transmittance_run (cached)
 *                  profile for the "profile" model)            or lucent_profile_tail
 *   sigma0         cdrf.variant                                lucent_cdrf_fit_material (cached)
 *   sog            the profile, desc.sog_count                 lucent_sog_fit, variances shared by
 *                                                              the channels (d'Eon & Luebke 2007)
 *   rd             the material only                           lucent_profile_mc_total (cached): the
 *                                                              Monte Carlo total diffuse reflectance,
 *                                                              the real-time methods' albedo (a spectral
 *                                                              skin: lucent_skin_color_of, "mc", cached) */
#ifndef LUCENT_BAKE_H
#define LUCENT_BAKE_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/kernel.h"
#include "lucent/material.h"
#include "lucent/profile.h"
#include "lucent/settings.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    LUCENT_BAKE_PROFILE = 1u << 0,
    LUCENT_BAKE_TAPS = 1u << 1,          /* bakes the profile too */
    LUCENT_BAKE_TRANSMITTANCE = 1u << 2, /* bakes the profile too for the "profile" model */
    LUCENT_BAKE_SIGMA0 = 1u << 3,
    LUCENT_BAKE_SOG = 1u << 4, /* bakes the profile too */
    LUCENT_BAKE_RD = 1u << 5
};

/* The defaults of lucent_bake_desc's photon counts, stated once. */
enum {
    LUCENT_BAKE_PROFILE_PHOTONS = 200000, /* ssss.profile "mc": per channel */
    LUCENT_BAKE_TRANSMIT_PHOTONS = 20000, /* slab transmittance: per channel and thickness */
    LUCENT_BAKE_SIGMA0_PHOTONS = 40000,   /* sigma0 fit: per channel and sphere */
    LUCENT_BAKE_SIGMA0_BINS = 18,         /* sigma0 fit: theta bins of each sphere */
    LUCENT_BAKE_RD_PHOTONS = 400000,      /* total diffuse reflectance: per channel (Skin1's blue
                                             0.113 +- 0.0005) */
    LUCENT_BAKE_SKIN_RD_PHOTONS = 10000   /* a spectral skin's: per band (lucent/skin.h) */
};

enum { LUCENT_BAKE_TRANSMIT_SIZE = 256 }; /* samples of the transmittance table */

/* What to bake and how; a zero field means the default. */
typedef struct lucent_bake_desc {
    unsigned what;                          /* LUCENT_BAKE_* */
    const lucent_render_settings *settings; /* NULL: lucent_render_settings_defaults() */
    uint64_t profile_photons;               /* 0: LUCENT_BAKE_PROFILE_PHOTONS */
    uint64_t transmit_photons;              /* 0: LUCENT_BAKE_TRANSMIT_PHOTONS */
    uint64_t sigma0_photons;                /* 0: LUCENT_BAKE_SIGMA0_PHOTONS */
    int sog_count;                          /* Gaussians of the sog part, 1..LUCENT_SOG_MAX (0: 6) */
    lucent_pool *pool;                      /* NULL: serial */
} lucent_bake_desc;

enum { LUCENT_BAKE_KEY_SIZE = 160 };

/* A material's baked parts. Zero-initialise before the first bake; free with lucent_baked_free. */
typedef struct lucent_baked {
    unsigned have; /* LUCENT_BAKE_* parts present */
    lucent_profile *profile;
    lucent_taps *taps;
    /* T(s) per channel at s = transmit_range j / (size - 1), [3 j + channel], the last entry 0: the
     * slab's own transmittance, or the profile's T(s) / T(0) (to be multiplied by the albedo). */
    float transmittance[LUCENT_BAKE_TRANSMIT_SIZE * 3];
    double transmit_range;  /* mm */
    double sigma0[3];       /* mm */
    double kd[3];           /* the fit's albedo scale k_d with sigma0 (lucent_cdrf_fit.kd) */
    double rd[3], rd_se[3]; /* the half-space's Monte Carlo total diffuse reflectance and its error */
    bool rd_cached;         /* read from the disk cache */
    bool sigma0_cached;     /* read from the disk cache */
    lucent_sog sog;         /* the profile as a sum of Gaussians with shared variances */
    /* What each part was built from ("dipole", "dipole/preint/1/17", ...): a part is rebuilt when its
     * key changes. */
    char profile_key[LUCENT_BAKE_KEY_SIZE], taps_key[LUCENT_BAKE_KEY_SIZE];
    char transmit_key[LUCENT_BAKE_KEY_SIZE], sigma0_key[LUCENT_BAKE_KEY_SIZE], sog_key[LUCENT_BAKE_KEY_SIZE];
} lucent_baked;

/* Bakes what desc asks for into baked, reusing the parts whose settings did not change. cache may
 * be NULL (nothing kept between runs). Errors name the material and the part. */
lucent_status lucent_material_bake(const lucent_material *material, const lucent_bake_desc *desc, lucent_cache *cache,
                                   lucent_baked *baked);

/* Makes dest (freed first) a deep copy of src: what a bake on another thread starts from, so that
 * it rebuilds only what changed (the viewer's background bakes). */
lucent_status lucent_baked_copy(const lucent_baked *src, lucent_baked *dest);

/* Frees the parts and zeroes baked. */
void lucent_baked_free(lucent_baked *baked);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_BAKE_H */
