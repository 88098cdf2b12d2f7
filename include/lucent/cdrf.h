/* Lucent CDRF: the curvature-dependent reflectance function of Kubo, Dobashi & Morishima
 * (Eq. 1-4, 6), Collomb's closed-form fit (as published on the CDRF blog post), its 2-D
 * look-up table, a Monte Carlo simulation of translucent spheres (the paper's Figure 6
 * experiment) and the least-squares fit of sigma0 to it. See docs/cdrf.md.
 *
 * Angles in radians, lengths in mm, curvature in 1/mm, so sigma = sigma0 * kappa is an angle. */
#ifndef LUCENT_CDRF_H
#define LUCENT_CDRF_H

#include <stdint.h>

#include "lucent/base.h"
#include "lucent/image.h"
#include "lucent/material.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lucent_cdrf_variant {
    LUCENT_CDRF_KUBO = 0,   /* Eq. 1-3: max(cos, 0) convolved with a Gaussian of width sigma */
    LUCENT_CDRF_COLLOMB = 1 /* the blog's closed-form fit, its kappa read as sigma */
} lucent_cdrf_variant;

/* Parses "kubo" or "collomb" (case-sensitive); LUCENT_ERR_INVALID_ARGUMENT listing them otherwise. */
lucent_status lucent_cdrf_variant_parse(const char *name, lucent_cdrf_variant *dest);

/* Returns "kubo" or "collomb". */
const char *lucent_cdrf_variant_name(lucent_cdrf_variant variant);

/* Kubo Eq. 2: E(theta) = max(cos theta, 0), the Lambert term. */
double lucent_cdrf_lambert(double theta);

/* Kubo Eq. 1-3: (E * g)(theta) for a Gaussian of standard deviation sigma (radians, >= 0).
 * E is Eq. 2 on the whole real line, i.e. 2 pi-periodic: light that spreads past theta = pi
 * along the sphere's great circle comes round from the other side (equivalently, E is extended
 * symmetrically about pi). Computed by composite Gauss-Legendre quadrature split at the kinks
 * of E, to about 1e-12. sigma = 0 gives E exactly (Lambert is the sigma -> 0 limit); sigma > 40
 * gives the mean 1/pi; a NaN or infinite argument gives NaN. */
double lucent_cdrf_kubo(double theta, double sigma);

/* Collomb's fit, with kappa = sigma:
 * f = (1 + k)/4 (cos(min((5 + k) theta / 4, pi)) + 1) / (1 + (ln(1 + 1.7 k) theta / 1.45)^10)
 *     + 0.075 (1 - k), clamped to >= 0 (for k > 1 the formula goes negative near theta = pi).
 * theta is folded into [0, pi]. It does not reduce to Lambert at sigma = 0. */
double lucent_cdrf_collomb(double theta, double sigma);

/* The chosen variant at theta (radians) and sigma. */
double lucent_cdrf_eval(lucent_cdrf_variant variant, double theta, double sigma);

/* Kubo Eq. 4: sigma = sigma0 * kappa (sigma0 in mm, kappa in 1/mm). */
double lucent_cdrf_sigma(double sigma0, double kappa);

/* Kubo Eq. 6: sigma0 = d_c^2 from a diffuse colour value d_c (negative or NaN gives 0). */
double lucent_cdrf_sigma0_from_diffuse(double diffuse);

/* Eq. 6 on every sample of a diffuse colour map (any channel count); dest has the same shape. */
lucent_status lucent_cdrf_sigma0_map(const lucent_image *diffuse, lucent_image **dest);

/* ---- The look-up table (Kubo section V) ----
 * A single-channel float image: column i holds cos theta = -1 + 2 i / (width - 1), row j (from
 * the top) holds sigma = sigma_max j / (height - 1). Samples sit on the end points, so a shader
 * reads it at u = (0.5 + (cos + 1) / 2 (width - 1)) / width, v likewise. */
typedef struct lucent_cdrf_lut_desc {
    lucent_cdrf_variant variant;
    int width;         /* cos theta samples (0: 256), >= 2 */
    int height;        /* sigma samples (0: 256), >= 2 */
    double sigma_max;  /* 0: 3 (radians) */
    lucent_pool *pool; /* NULL: serial */
} lucent_cdrf_lut_desc;

/* Returns the defaults with every field resolved. */
lucent_cdrf_lut_desc lucent_cdrf_lut_defaults(void);

/* Builds the table; *dest is a 1-channel image (NULL on failure). */
lucent_status lucent_cdrf_lut_build(const lucent_cdrf_lut_desc *desc, lucent_image **dest);

/* Writes the table by the path's extension: .exr, .pfm, or .c / .h (a C array
 * `static const float NAME[height][width]` with the axes in a comment; name NULL: lucent_cdrf_lut). */
lucent_status lucent_cdrf_lut_write(const char *path, const lucent_image *lut, double sigma_max, const char *name);

/* ---- The sphere simulation (Kubo Figure 6) ----
 * A sphere of radius r of the material, lit by a directional light from +x (irradiance 1 on a
 * plane facing the light), seen by a camera along +z. Light is traced from the light; radiance
 * that leaves the sphere toward the camera is scored against the angle theta between the exit
 * point's normal and the light. The scene is symmetric about the x axis, so every exit is rotated
 * about x onto the visible equator (y = 0, z > 0) and accepted when its direction lies within a
 * cone of half-angle `cone` around +z; the tally is divided by the band's area times the
 * cone's projected solid angle. Light reflected at first entry (the specular highlight) is not
 * scored: the result is the subsurface radiance only. */
enum { LUCENT_CDRF_MAX_BINS = 720 };

/* The sphere radii the Monte Carlo simulates, mm: below 1 nm no photon of double precision enters (a radius
 * of 1e-300 gave an empty tally, fitted as sigma0 = k_d = 0), above 1 km the steps lose the sphere. */
#define LUCENT_CDRF_SPHERE_MIN_RADIUS 1e-6
#define LUCENT_CDRF_SPHERE_MAX_RADIUS 1e6

typedef struct lucent_cdrf_sphere_desc {
    const lucent_material *material;
    double radius;    /* mm, in [LUCENT_CDRF_SPHERE_MIN_RADIUS, LUCENT_CDRF_SPHERE_MAX_RADIUS] */
    double roughness; /* GGX alpha of the boundary; 0: smooth (Fresnel) */
    uint64_t photons; /* per channel (0: 200000); rounded up to a multiple of the batch count */
    int bins;         /* theta bins over [0, pi] (0: 36) */
    double cone;      /* acceptance half-angle, radians (0: 0.2) */
    int batches;      /* fixed chunks, one RNG stream each (0: 32), >= 2, for standard errors */
    uint64_t seed;
    int max_order;     /* score only exits after at most this many scatterings (0: all) */
    lucent_pool *pool; /* NULL: serial */
    const char *label; /* progress label (NULL: "CDRF sphere") */
} lucent_cdrf_sphere_desc;

typedef struct lucent_cdrf_sphere_result {
    int bins;
    double radius;
    double theta[LUCENT_CDRF_MAX_BINS];          /* bin centres, radians */
    double radiance[3][LUCENT_CDRF_MAX_BINS];    /* per channel, per unit irradiance */
    double radiance_se[3][LUCENT_CDRF_MAX_BINS]; /* standard errors from the batches */
    double exitance[3][LUCENT_CDRF_MAX_BINS];    /* the light leaving each theta band, every direction, per
                                                    unit area and unit irradiance */
    double flow[3][LUCENT_CDRF_MAX_BINS];        /* the mean over that light of t . f, t its direction, f the
                                                    unit tangent away from the light: how far the exit leans
                                                    down the surface (0: as on a half-space) */
    double entered[3];                           /* fraction of the light's power that entered the sphere */
    double exited[3];                            /* fraction that left it again (every direction) */
    double absorbed[3];                          /* fraction absorbed inside */
    uint64_t photons;                            /* per channel, after rounding */
} lucent_cdrf_sphere_result;

/* Runs the simulation for the three channels. Identical for any thread count. */
lucent_status lucent_cdrf_sphere_run(const lucent_cdrf_sphere_desc *desc, lucent_cdrf_sphere_result *dest);

/* ---- The fit of sigma0 (and the albedo scale k_d) ----
 * Per channel, minimises sum over spheres and bins of w (k_d f(theta; sigma0 / r) - L)^2 with
 * w = sin(theta) / se^2: sin theta is the bin's share of the pixels on the equator line (Kubo's
 * Figure 6 fits the pixels of that line), se is floored at 2% of the channel's largest radiance so
 * that bins where the batches saw one photon or none do not dominate. k_d has a closed form;
 * sigma0 is searched on a grid over [0, sigma0_max], then by golden section. Lambert (sigma0 = 0,
 * k_d fitted) is evaluated alike. The RMS errors are over the equator's pixels (weight sin theta). */
typedef struct lucent_cdrf_fit {
    lucent_cdrf_variant variant;
    double sigma0[3]; /* mm */
    double kd[3];
    double rms[3];  /* RMS of (model - L) over the equator pixels of all spheres */
    double chi2[3]; /* weighted sum of squares at the optimum */
    double lambert_kd[3];
    double lambert_rms[3];
    double lambert_chi2[3];
} lucent_cdrf_fit;

/* Fits count sphere results (count >= 1); sigma0_max 0 means 20 mm. */
lucent_status lucent_cdrf_fit_spheres(const lucent_cdrf_sphere_result *spheres, int count, lucent_cdrf_variant variant,
                                      double sigma0_max, lucent_cdrf_fit *dest);

/* ---- sigma0 of a material: Monte Carlo spheres and the fit together ----
 * Simulates spheres of the material of the given radii and fits them (lucent_cdrf_sphere_run, then
 * lucent_cdrf_fit_spheres): what `lucent cdrf-fit` and the renderer's sigma0 do. */
#define LUCENT_CDRF_FIT_RADII                                                                                          \
    {                                                                                                                  \
        2.0, 5.0, 10.0, 20.0                                                                                           \
    } /* mm: the default radii, Kubo Fig. 6 style */
enum { LUCENT_CDRF_FIT_RADIUS_COUNT = 4, LUCENT_CDRF_FIT_MAX_RADII = 16 };

typedef struct lucent_cdrf_material_fit_desc {
    const lucent_material *material;
    lucent_cdrf_variant variant;
    const double *radii;    /* mm (NULL: LUCENT_CDRF_FIT_RADII) */
    int radius_count;       /* with radii: 1..LUCENT_CDRF_FIT_MAX_RADII */
    uint64_t photons;       /* per channel and sphere (0: the sphere's default) */
    int bins;               /* theta bins (0: the sphere's default) */
    double roughness, cone; /* as lucent_cdrf_sphere_desc */
    uint64_t seed;          /* sphere i runs with seed 64 seed + i */
    double sigma0_max;      /* mm (0: 20) */
    lucent_pool *pool;
    const char *label; /* progress label before "sphere r = R mm" (may be NULL) */
} lucent_cdrf_material_fit_desc;

/* Runs the spheres and the fit. spheres (may be NULL) receives the sphere results, radius_count of
 * them (free with free()). */
lucent_status lucent_cdrf_fit_material(const lucent_cdrf_material_fit_desc *desc, lucent_cdrf_fit *dest,
                                       lucent_cdrf_sphere_result **spheres);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_CDRF_H */
