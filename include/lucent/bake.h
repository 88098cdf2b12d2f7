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
 *                                                              Monte Carlo total diffuse reflectance
 *                                                              under a smooth boundary (MCML's; a
 *                                                              spectral skin: lucent_skin_color_of,
 *                                                              "mc", cached)
 *   boundary       the material, desc.roughness                lucent_boundary_run (cached): the path
 *                                                              tracer's rough boundary on a half-space,
 *                                                              the real-time methods' albedo and their
 *                                                              entry and exit factors (docs/render.md,
 *                                                              "One boundary")
 *   spheres        the boundary (its roughness),               lucent_cdrf_sphere_run (cached): the
 *                  desc.sphere_photons                         exitance of Monte Carlo spheres of the
 *                                                              material behind the same boundary over
 *                                                              theta and radius (docs/render.md,
 *                                                              "Curved parts")
 *   sheet          the boundary's roughness,                   lucent_sheet_run (cached): sheets of the
 *                  desc.sheet_photons                          material behind the same boundary lit
 *                                                              from behind, per thickness: the thin
 *                                                              parts' lobe and diffuse light
 *                                                              (docs/render.md, "Thin parts") */
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
    LUCENT_BAKE_RD = 1u << 5,
    LUCENT_BAKE_BOUNDARY = 1u << 6,
    LUCENT_BAKE_SPHERES = 1u << 7, /* bakes the boundary too */
    LUCENT_BAKE_SHEET = 1u << 8
};

/* The defaults of lucent_bake_desc's photon counts, stated once. */
enum {
    LUCENT_BAKE_PROFILE_PHOTONS = 200000, /* ssss.profile "mc": per channel */
    LUCENT_BAKE_TRANSMIT_PHOTONS = 20000, /* slab transmittance: per channel and thickness */
    LUCENT_BAKE_SIGMA0_PHOTONS = 40000,   /* sigma0 fit: per channel and sphere */
    LUCENT_BAKE_SIGMA0_BINS = 18,         /* sigma0 fit: theta bins of each sphere */
    LUCENT_BAKE_RD_PHOTONS = 400000,      /* total diffuse reflectance: per channel (Skin1's blue
                                             0.113 +- 0.0005) */
    LUCENT_BAKE_SKIN_RD_PHOTONS = 10000,  /* a spectral skin's: per band (lucent/skin.h) */
    LUCENT_BAKE_BOUNDARY_PHOTONS = 2000,  /* boundary: per channel and incidence bin (about 1% per table
                                             entry for Skin1, 2% for marble; 0.8 s and 6 s of CPU) */
    LUCENT_BAKE_SPHERE_PHOTONS = 20000,   /* spheres: per channel and radius */
    LUCENT_BAKE_SHEET_PHOTONS = 4000      /* sheet: per channel and thickness */
};

/* The spheres part's table: radii r0 2^(k/2), k < LUCENT_BAKE_SPHERE_RADII, and theta bins of pi / BINS. */
enum { LUCENT_BAKE_SPHERE_RADII = 16, LUCENT_BAKE_SPHERE_BINS = 36 };

enum { LUCENT_BAKE_TRANSMIT_SIZE = 256 }; /* samples of the transmittance table */

/* The sheet part's thicknesses: sheet_range ((j + 1) / ROWS)^2, j < ROWS. */
enum { LUCENT_BAKE_SHEET_ROWS = 24 };

/* What to bake and how; a zero field means the default. */
typedef struct lucent_bake_desc {
    unsigned what;                          /* LUCENT_BAKE_* */
    const lucent_render_settings *settings; /* NULL: lucent_render_settings_defaults() */
    uint64_t profile_photons;               /* 0: LUCENT_BAKE_PROFILE_PHOTONS */
    uint64_t transmit_photons;              /* 0: LUCENT_BAKE_TRANSMIT_PHOTONS */
    uint64_t sigma0_photons;                /* 0: LUCENT_BAKE_SIGMA0_PHOTONS */
    int sog_count;                          /* Gaussians of the sog part, 1..LUCENT_SOG_MAX (0: 6) */
    double roughness;                       /* boundary: the GGX alpha of the object's boundary, [0, 1]
                                               (0: smooth, Fresnel's) */
    uint64_t boundary_photons;              /* 0: LUCENT_BAKE_BOUNDARY_PHOTONS */
    uint64_t sphere_photons;                /* 0: LUCENT_BAKE_SPHERE_PHOTONS */
    uint64_t sheet_photons;                 /* 0: LUCENT_BAKE_SHEET_PHOTONS */
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
    /* The path tracer's boundary on a half-space of the material at boundary_roughness
     * (lucent_boundary_run; docs/render.md, "One boundary"), as the real-time methods use it: the
     * albedo of uniform light (the hemispherical albedo, boundary_albedo), the exit curve E(mu_o)
     * (the exit under uniform light over the albedo, 2 int E mu dmu = 1) and the entry factor
     * A(mu_i, mu_o) = pi f(mu_i, mu_o) / (albedo E(mu_o)) (2 int A mu_i dmu_i = 1), so that a surface lit
     * at mu_i shows albedo A(mu_i, mu_o) E(mu_o) E_light mu_i / pi. boundary[((row x BINS) + o) x 3 + c]:
     * rows 0..BINS-1 A at the incidence bins' centres, row BINS E, exit bins o (lucent/profile.h). */
    double boundary_albedo[3];
    double boundary_roughness;
    float boundary[(LUCENT_BOUNDARY_BINS + 1) * LUCENT_BOUNDARY_BINS * 3];
    bool boundary_cached; /* read from the disk cache */
    /* Curved parts (LUCENT_BAKE_SPHERES): Monte Carlo spheres of the material behind the boundary,
     * radius sphere_r0 2^(k/2) mm (sphere_r0 a quarter of the material's shortest diffusion length
     * 1 / sigma_tr), lit from one side; the exitance of each band of theta (the angle from the light)
     * over the half-space's exitance at the band's incidence, a(max(cos theta, 0)) (the boundary's table):
     * the factor that replaces max(cos theta, 0) for a point of curvature 1 / r. spheres[((k x BINS) + j)
     * x 3 + c]; row k = RADII is the flat limit, the bin's mean of max(cos theta, 0). Then as many rows
     * (k + RADII + 1) of beta, how the exit leans down the surface away from the light on a sphere:
     * the radiance toward v is the exitance's times (1 + beta v . f), f the unit tangent away from the
     * light (beta = 4 <t . f> over the exits, for an exit lobe 1 + beta t . f over a cosine one; the
     * flat row 0). */
    double sphere_r0;
    float spheres[2 * (LUCENT_BAKE_SPHERE_RADII + 1) * LUCENT_BAKE_SPHERE_BINS * 3];
    bool spheres_cached;
    /* Thin parts (LUCENT_BAKE_SHEET; docs/render.md, "Thin parts"): sheets of the material behind the
     * boundary at `roughness`, thickness sheet_range ((j + 1) / ROWS)^2 (sheet_range five of the longest
     * diffusion lengths 1 / sigma_tr), lit from behind along the normal (lucent_sheet_run): pi f of the
     * light through them per exit angle bin (LUCENT_SHEET_BINS uniform in [0, 90] degrees), rows j < ROWS
     * the lobe (scattering orders 0 and 1, read at the angle from the light's direction of travel), rows
     * ROWS + j the rest (read at the angle from the normal). sheet[((row x BINS) + b) x 3 + c]. */
    double sheet_range;
    float sheet[2 * LUCENT_BAKE_SHEET_ROWS * LUCENT_SHEET_BINS * 3];
    bool sheet_cached;
    /* What each part was built from ("dipole", "dipole/preint/1/17", ...): a part is rebuilt when its
     * key changes. */
    char profile_key[LUCENT_BAKE_KEY_SIZE], taps_key[LUCENT_BAKE_KEY_SIZE];
    char transmit_key[LUCENT_BAKE_KEY_SIZE], sigma0_key[LUCENT_BAKE_KEY_SIZE], sog_key[LUCENT_BAKE_KEY_SIZE];
    char boundary_key[LUCENT_BAKE_KEY_SIZE], spheres_key[LUCENT_BAKE_KEY_SIZE], sheet_key[LUCENT_BAKE_KEY_SIZE];
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
