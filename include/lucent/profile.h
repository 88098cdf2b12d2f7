/* Lucent profiles: radial diffuse reflectance profiles R_d(r) on a radial grid, the analytic
 * diffusion models (classical dipole, better dipole, multipole slabs and their layered
 * composition, Burley's normalized diffusion) and sum-of-Gaussians fits of a profile.
 *
 * Units: r in mm, coefficients in mm^-1, R_d in mm^-2 (reflected power per unit area for a
 * unit incident power), Gaussian variances in mm^2. See docs/profiles.md for the formulas. */
#ifndef LUCENT_PROFILE_H
#define LUCENT_PROFILE_H

#include <stdbool.h>

#include "lucent/base.h"
#include "lucent/material.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { LUCENT_PROFILE_MODEL_SIZE = 32, LUCENT_SOG_MAX = 16 };

/* ---- Tabulated profiles ---------------------------------------------------------------
 * Bin j covers [j dr, (j + 1) dr] (j = 0 .. count-1); r[j] = (j + 0.5) dr is its centre.
 * value[c][j] is the average of R_d over the bin's annulus,
 *   value = (2 pi integral_bin R_d(r) r dr) / (pi ((j+1)^2 - j^2) dr^2),
 * so value[c][j] times the annulus area is the power reflected into the bin.
 * error[c][j] is its standard error (0 for analytic models). */
typedef struct lucent_profile {
    int count;                             /* number of bins, > 0 */
    double dr;                             /* bin width, mm, > 0 */
    double *r;                             /* bin centres, mm */
    double *value[3];                      /* R_d per channel, mm^-2 */
    double *error[3];                      /* standard error per channel, mm^-2 */
    char model[LUCENT_PROFILE_MODEL_SIZE]; /* "dipole", "better-dipole", "mc", ... */
} lucent_profile;

/* A radial grid. A zero field means "the default for the material" (see
 * lucent_profile_grid_default). */
typedef struct lucent_profile_grid {
    double dr; /* bin width, mm */
    int count; /* number of bins */
} lucent_profile_grid;

/* Fills dest with the grid of Freude 2014, Table 6.1: dr = min(MFP_rgb) / 20 and
 * count = ceil(32 max(MFP_rgb) / dr), with MFP = 1 / sigma_t' (mm). m must be valid. */
void lucent_profile_grid_default(const lucent_material *m, lucent_profile_grid *dest);

/* Resolves grid (NULL or zero fields: the default for m; m may be NULL when grid is complete)
 * into dest. Fails with LUCENT_ERR_INVALID_ARGUMENT naming "dr" or "count". */
lucent_status lucent_profile_grid_resolve(const lucent_profile_grid *grid, const lucent_material *m,
                                          lucent_profile_grid *dest);

/* Creates a zeroed profile on grid (dr > 0, 0 < count <= 10^8), with r filled in and model
 * set to model (may be NULL). Free with lucent_profile_destroy. */
lucent_status lucent_profile_create(const lucent_profile_grid *grid, const char *model, lucent_profile **dest);

/* Creates a deep copy of src. Free with lucent_profile_destroy. */
lucent_status lucent_profile_clone(const lucent_profile *src, lucent_profile **dest);

/* Frees p (NULL is fine). */
void lucent_profile_destroy(lucent_profile *p);

/* Returns the reflectance carried by the profile's bins for channel c (0..2):
 * sum_j value[c][j] pi ((j+1)^2 - j^2) dr^2. */
double lucent_profile_total(const lucent_profile *p, int c);

/* ---- One channel of a medium, as the diffusion models see it ---- */
typedef struct lucent_medium {
    double sigma_a;       /* absorption, mm^-1, >= 0 */
    double sigma_s_prime; /* reduced scattering sigma_s (1 - g), mm^-1, >= 0; sum > 0 */
    double eta;           /* index of refraction relative to the medium outside (vacuum or air
                           for the half-space models; slabs take their neighbours from
                           lucent_slab_desc), >= 1 */
} lucent_medium;

/* Fills dest with channel c (0..2) of m: sigma_a, sigma_s (1 - g), eta. */
void lucent_medium_from_material(const lucent_material *m, int c, lucent_medium *dest);

/* Checks a medium; the message names the field ("sigma_a", "sigma_s_prime", "eta"). */
lucent_status lucent_medium_validate(const lucent_medium *md);

/* ---- Classical dipole (Jensen et al. 2001) ---- */

/* Returns R_d(r) of the classical dipole, mm^-2 (Jensen et al. 2001, eq. 4 with
 * z_r = 1/sigma_t', z_v = z_r (1 + 4A/3)). Invalid medium or r < 0: NaN. */
double lucent_dipole_eval(const lucent_medium *md, double r);

/* Fills dest with the classical-dipole profile of m (bin averages, integrated exactly);
 * grid may be NULL (the default grid). */
lucent_status lucent_profile_dipole(const lucent_material *m, const lucent_profile_grid *grid, lucent_profile **dest);

/* ---- Better dipole (d'Eon 2012, "A Better Dipole") ---- */

/* Returns R_d(r) of the better dipole, mm^-2: alpha' (C_phi phi(r) + C_E E(r)) with Grosjean's
 * D = (2 sigma_a + sigma_s') / (3 sigma_t'^2), z_v = -z_r - 4AD. Invalid input: NaN. */
double lucent_better_dipole_eval(const lucent_medium *md, double r);

/* Returns the better dipole's total diffuse reflectance 2 pi integral_0^inf R_d(r) r dr in
 * closed form. Invalid medium: NaN. */
double lucent_better_dipole_total(const lucent_medium *md);

/* Fills dest with the better-dipole profile of m; grid may be NULL. */
lucent_status lucent_profile_better_dipole(const lucent_material *m, const lucent_profile_grid *grid,
                                           lucent_profile **dest);

/* ---- Multipole slabs (Donner & Jensen 2005) ----
 * Each face of a slab has its own boundary condition, from the relative index across it
 * (Donner & Jensen 2005, Section 3): eta / eta_above on the top face and eta / eta_below on the
 * bottom face, where eta is the slab's own index (lucent_medium.eta, relative to vacuum). A
 * relative index below 1 (a denser medium outside) uses the Fdr fit for eta < 1 (Egan &
 * Hilgeman 1979); see docs/profiles.md. */
typedef struct lucent_slab_desc {
    double thickness; /* slab thickness d, mm, > 0 */
    int poles;        /* dipole pairs i = -n .. n; 0: the default (10); at most 1000 */
    double eta_above; /* index of the medium above the top face, [1, 3]; 0: 1 (vacuum / air) */
    double eta_below; /* index of the medium below the bottom face, [1, 3]; 0: 1 (vacuum / air) */
} lucent_slab_desc;

/* Fills dest[0] with the reflectance R(r) and dest[1] with the transmittance T(r) of a slab
 * (mm^-2), Donner & Jensen 2005 eqs. for the multipole with the extrapolation distances of
 * the top and bottom faces; poles 0 means 10. NaN when invalid. A slab thinner than its
 * transport mean free path 1/sigma_t' is computed as is (T can be negative; no warning here,
 * the profile builders warn). */
void lucent_multipole_eval(const lucent_medium *md, const lucent_slab_desc *slab, double r, double dest[2]);

/* Fills dest[0] and dest[1] with the totals (integrals over the plane) of R and T of the same
 * truncated multipole, in closed form per pole. Requires sigma_a > 0 (otherwise NaN). */
void lucent_multipole_totals(const lucent_medium *md, const lucent_slab_desc *slab, double dest[2]);

/* Creates dest[0] (reflectance, model "multipole-R") and dest[1] (transmittance,
 * "multipole-T") for a slab of material m; grid may be NULL. Logs a LUCENT_LOG_WARN line when
 * the thickness is below the material's transport mean free path 1/sigma_t' (any channel). */
lucent_status lucent_profile_multipole(const lucent_material *m, const lucent_slab_desc *slab,
                                       const lucent_profile_grid *grid, lucent_profile *dest[2]);

/* One layer of a layered slab: its material (eta: the layer's own index) and shape. In a
 * stack, lucent_profile_layered takes the indices of a layer's faces from its neighbours; only
 * the top layer's slab.eta_above and the bottom layer's slab.eta_below are read (the media
 * above and below the stack, 0: vacuum / air); the other eta_above / eta_below are ignored. */
typedef struct lucent_layer {
    lucent_material material;
    lucent_slab_desc slab;
} lucent_layer;

/* Composes count (1..16) multipole layers, top first, by the Kubelka-Munk style adding rule in
 * the frequency (Hankel) domain, Donner & Jensen 2005:
 *   R12 = R1 + T1 R2 T1' / (1 - R2 R1'),  T12 = T1 T2 / (1 - R2 R1')
 * (primes: the upper stack seen from below; a layer's faces differ, so R1' != R1, T1' != T1),
 * and inverts the transform numerically into bin averages. dest[0] is the reflectance of the
 * stack seen from the top, dest[1] its transmittance. grid may be NULL (default for layer 0).
 * Logs a LUCENT_LOG_WARN line for each layer thinner than its transport mean free path
 * 1/sigma_t' (the multipole's source then lies outside it and T can be negative); the values
 * are returned as computed. */
lucent_status lucent_profile_layered(const lucent_layer *layers, int count, const lucent_profile_grid *grid,
                                     lucent_profile *dest[2]);

/* ---- Burley normalized diffusion (Christensen & Burley 2015) ---- */
typedef enum lucent_burley_fit {
    LUCENT_BURLEY_SEARCHLIGHT_MFP, /* s = 1.85 - A + 7 |A - 0.8|^3, l = mean free path */
    LUCENT_BURLEY_DIFFUSE_MFP,     /* s = 1.9 - A + 3.5 (A - 0.8)^2, l = mean free path */
    LUCENT_BURLEY_SEARCHLIGHT_DMFP /* s = 3.5 + 100 (A - 0.33)^4, l = diffuse mean free path */
} lucent_burley_fit;

/* Returns the dimensionless scaling factor s(A) of the given fit; A is clamped to [0, 1]. */
double lucent_burley_scale(lucent_burley_fit fit, double albedo);

/* Returns R(r) = A s (e^{-s r} + e^{-s r / 3}) / (8 pi r), mm^-2, for the surface albedo A and
 * the inverse length s (mm^-1, s = scale / l). Integrates to A over the plane. r = 0: +inf. */
double lucent_burley_eval(double albedo, double s, double r);

/* Per-channel parameters of Burley's profile. */
typedef struct lucent_burley_params {
    double albedo[3]; /* surface albedo A, [0, 1] */
    double length[3]; /* l: mean free path or diffuse mean free path (per fit), mm, > 0 */
    lucent_burley_fit fit;
} lucent_burley_params;

/* Fills dest from a material: A = classical-dipole total Rd, l = 1 / sigma_t' for the _MFP fits
 * and 1 / sigma_tr for the _DMFP fit (sigma_a = 0 then fails: infinite length). */
lucent_status lucent_burley_params_from_material(const lucent_material *m, lucent_burley_fit fit,
                                                 lucent_burley_params *dest);

/* Fills dest with Burley's profile (bin averages, integrated exactly); grid NULL or zero fields:
 * the Table 6.1 rule applied to the profile's lengths l / s. */
lucent_status lucent_profile_burley(const lucent_burley_params *params, const lucent_profile_grid *grid,
                                    lucent_profile **dest);

/* ---- Sum of Gaussians (d'Eon & Luebke 2007, GPU Gems 3 ch. 14) ----
 * R(r) ~ sum_i w_i G(v_i, r), G(v, r) = exp(-r^2 / (2 v)) / (2 pi v) (integrates to 1). */
typedef struct lucent_sog {
    int count;                          /* Gaussians per channel, 1..16 */
    double variance[3][LUCENT_SOG_MAX]; /* v_i per channel, mm^2, ascending */
    double weight[3][LUCENT_SOG_MAX];   /* w_i per channel, >= 0 */
    double rms[3];                      /* sqrt(sum r dr (R - fit)^2 / sum r dr R^2) per channel */
} lucent_sog;

typedef struct lucent_sog_desc {
    int count;             /* N, 1..16 (required) */
    bool shared_variances; /* one set of variances for the three channels (d'Eon's skin) */
    int starts;            /* multi-start count; 0: the default (8) */
    int max_iterations;    /* Levenberg-Marquardt iterations per start; 0: the default (300) */
} lucent_sog_desc;

/* Returns G(v, r) = exp(-r^2 / (2 v)) / (2 pi v), mm^-2 (v > 0). */
double lucent_gaussian(double v, double r);

/* Returns the fitted R(r) of channel c of s. */
double lucent_sog_eval(const lucent_sog *s, int c, double r);

/* Fits p with desc->count Gaussians per channel, minimising sum_j r_j dr (R_j - fit_j)^2
 * (fit_j: the bin average of the mixture) by variable projection: non-negative least squares
 * for the weights, Levenberg-Marquardt on log variances, multi-start. Deterministic. */
lucent_status lucent_sog_fit(const lucent_profile *p, const lucent_sog_desc *desc, lucent_sog *dest);

/* d'Eon & Luebke 2007's six-Gaussian skin profile (GPU Gems 3, ch. 14, the table of Figure 14-13:
 * shared variances 0.0064 .. 7.41 mm^2 and RGB weights), as a lucent_sog (rms 0). */
void lucent_sog_deon_skin(lucent_sog *dest);

/* Creates a profile on grid holding the bin averages of the mixture s (model "sog"). */
lucent_status lucent_profile_from_sog(const lucent_sog *s, const lucent_profile_grid *grid, lucent_profile **dest);

/* ---- Profiles by name ----
 * The profile a kernel or a renderer builds from a material: "dipole" (the default),
 * "better-dipole", "burley" (searchlight fit) or "mc" (Monte Carlo of a half-space on desc's grid, by
 * default Freude Table 6.1's). */
typedef struct lucent_profile_source_desc {
    const char *source;       /* NULL: "dipole" */
    uint64_t photons;         /* mc only, per channel (0: 200000) */
    uint64_t seed;            /* mc only */
    lucent_pool *pool;        /* mc only; NULL: serial */
    lucent_profile_grid grid; /* mc only: the radial grid (zero fields: Freude Table 6.1's default) */
} lucent_profile_source_desc;

/* True when name is one of the profile names above. */
bool lucent_profile_source_known(const char *name);

/* Builds the profile of m named by desc (NULL: the dipole). Unknown names fail with
 * LUCENT_ERR_INVALID_ARGUMENT listing the known ones. Free with lucent_profile_destroy.
 * A spectral skin (m->skin.layer_count > 0, lucent/skin.h) is carried band by band in its layers:
 * "mc" by the Monte Carlo (3 photons / LUCENT_BANDS_DEFAULT per band for each photon per channel asked),
 * every other name by the layered multipole (model "skin-mc" or "skin-multipole"). */
lucent_status lucent_profile_from_source(const lucent_profile_source_desc *desc, const lucent_material *m,
                                         lucent_profile **dest);

/* The Monte Carlo total diffuse reflectance of a half-space of m per channel, lit at normal
 * incidence (the specular reflection at entry excluded), with its standard error: the same walk
 * as the "mc" profile (lucent/mc.h, Fresnel boundaries of m's eta), photons per channel (0: 200000),
 * channel c seeded 4 seed + c. The albedo the real-time methods multiply their redistribution by
 * (lucent/bake.h, LUCENT_BAKE_RD). */
lucent_status lucent_profile_mc_total(const lucent_material *m, uint64_t photons, uint64_t seed, lucent_pool *pool,
                                      double rd[3], double rd_se[3]);

/* The name of profile source i (0: "dipole"); NULL past the last. */
const char *lucent_profile_source_name(int index);

/* ---- Transmittance through a thickness (translucency) ----------------------------------
 * Light E reaching the back face of a locally flat part of thickness s leaves the front with exitance
 * E T(s) (docs/render.md, "Translucency"). Two models:
 *   slab: the total transmittance of a slab of the material lit at normal incidence on one face, from
 *     Lucent's Monte Carlo (lucent/mc.h: MCML's physics, Fresnel boundaries of the material's eta in
 *     air), sampled at LUCENT_SLAB_SAMPLES thicknesses on a quadratic grid up to s_max = 5 / sigma_tr
 *     of the slowest channel (at most 100 transport mean free paths of the sparsest), log-linear
 *     between samples and diffusion's exp(-sigma_tr s) beyond s_max;
 *   profile: Jimenez 2010, the profile's power outside radius s (lucent_profile_tail). */
enum { LUCENT_SLAB_SAMPLES = 20 };

typedef struct lucent_slab_transmittance {
    double s_max;                          /* mm: the thickest sample */
    double thickness[LUCENT_SLAB_SAMPLES]; /* mm */
    double value[LUCENT_SLAB_SAMPLES][3];  /* T per sample and channel */
    double sigma_tr[3];                    /* mm^-1: the tail's decay */
} lucent_slab_transmittance;

/* The thicknesses of m's slab samples (dest->s_max, thickness, sigma_tr; values untouched). */
void lucent_slab_transmittance_grid(const lucent_material *m, lucent_slab_transmittance *dest);

/* Runs the Monte Carlo of every sample (photons per channel and thickness; seed 1 + sample). */
lucent_status lucent_slab_transmittance_run(const lucent_material *m, uint64_t photons, lucent_pool *pool,
                                            lucent_slab_transmittance *dest);

/* T of channel c at thickness s (mm). */
double lucent_slab_transmittance_eval(const lucent_slab_transmittance *t, int c, double s);

/* The profile's power outside radius s, integral_s^inf 2 pi rho R(rho) drho, exact for the
 * piecewise-constant bins of p (lucent_profile_tail(p, c, 0) is lucent_profile_total). */
double lucent_profile_tail(const lucent_profile *p, int c, double s);

/* ---- The path tracer's boundary on a flat part (docs/render.md, "One boundary") ----------
 * A half-space (thickness 0) or a slab of the material whose faces are the path tracer's rough
 * dielectric boundary (GGX alpha = roughness, Walter et al. 2007 with single-scattering microfacets,
 * from base/optics.h; roughness 0: a smooth Fresnel face), lit by collimated light at incidence
 * cosine mu_i. Tables over incidence and exit cosine bins (uniform in cosine, LUCENT_BOUNDARY_BINS of
 * them, light drawn cosine-weighted within its incidence bin), averaged over azimuth: the bin average
 * of pi f(mu_i, mu_o), f the BRDF (reflect) or BTDF (transmit) of the light that entered the medium,
 * so that a face lit by irradiance E at mu_i shows radiance E table / pi at mu_o. The light reflected
 * where it arrives (the specular lobe) is not in the tables; its albedo is. Photons per channel and
 * incidence bin; chunks (channel, incidence bin, batch) seeded (seed, chunk). */
enum { LUCENT_BOUNDARY_BINS = 32, LUCENT_BOUNDARY_PHOTONS = 20000 };

typedef struct lucent_boundary_desc {
    const lucent_material *material;
    double roughness; /* GGX alpha of both faces, [0, 1]; 0: smooth */
    double thickness; /* mm; 0: a half-space */
    uint64_t photons; /* per channel and incidence bin (0: LUCENT_BOUNDARY_PHOTONS) */
    int batches;      /* for the standard errors, 2..4096 (0: 8) */
    uint64_t seed;    /* 0: 1 */
    lucent_pool *pool;
    const char *label; /* the progress bar's (NULL: "boundary tables") */
} lucent_boundary_desc;

typedef struct lucent_boundary_result {
    uint64_t photons; /* per channel and incidence bin */
    /* [channel][incidence bin][exit bin]: pi f, and its standard error */
    double reflect[3][LUCENT_BOUNDARY_BINS][LUCENT_BOUNDARY_BINS];
    double reflect_se[3][LUCENT_BOUNDARY_BINS][LUCENT_BOUNDARY_BINS];
    double transmit[3][LUCENT_BOUNDARY_BINS][LUCENT_BOUNDARY_BINS]; /* slabs only */
    double transmit_se[3][LUCENT_BOUNDARY_BINS][LUCENT_BOUNDARY_BINS];
    /* transmit split by scattering order: [0] unscattered, [1] scattered once, [2] more */
    double transmit_order[3][3][LUCENT_BOUNDARY_BINS][LUCENT_BOUNDARY_BINS];
    /* the rows integrated over exit, 2 int table mu_o dmu_o (the reflectance and transmittance of
     * light arriving in each incidence bin), and their standard errors */
    double reflect_total[3][LUCENT_BOUNDARY_BINS], reflect_total_se[3][LUCENT_BOUNDARY_BINS];
    double transmit_total[3][LUCENT_BOUNDARY_BINS], transmit_total_se[3][LUCENT_BOUNDARY_BINS];
    double specular[3][LUCENT_BOUNDARY_BINS]; /* the albedo of the reflection where the light arrives */
    double absorbed[3][LUCENT_BOUNDARY_BINS]; /* the fraction absorbed in the medium */
    double specular_se[3][LUCENT_BOUNDARY_BINS], absorbed_se[3][LUCENT_BOUNDARY_BINS];
} lucent_boundary_result;

/* Runs the Monte Carlo of desc into dest (about 400 kB: allocate it). Deterministic for a seed. */
lucent_status lucent_boundary_run(const lucent_boundary_desc *desc, lucent_boundary_result *dest);

/* The centre of bin b of the tables' cosines, (b + 1/2) / LUCENT_BOUNDARY_BINS. */
double lucent_boundary_bin_cosine(int bin);

/* ---- A sheet lit from behind (docs/render.md, "Thin parts") -------------------------------------
 * A slab of the material `thickness` mm thick behind the same rough faces as lucent_boundary_run (the
 * same walk), lit by collimated light exactly along its normal: the light leaving the far face, the bin
 * average of pi f(theta_o) (f the BTDF of the sheet, so that a back face lit by irradiance E shows
 * radiance E table / pi on the front at theta_o from the normal), exit bins uniform in theta_o
 * (LUCENT_SHEET_BINS over [0, 90] degrees: fine enough for the forward lobe of two rough faces), split by
 * scattering order into the lobe (unscattered and once scattered: the light that keeps the direction of
 * the light) and the diffuse rest (scattered twice or more). Chunks (channel, batch) seeded (seed, chunk). */
enum { LUCENT_SHEET_BINS = 45, LUCENT_SHEET_PHOTONS = 20000 };

typedef struct lucent_sheet_desc {
    const lucent_material *material;
    double roughness; /* GGX alpha of both faces, [0, 1]; 0: smooth */
    double thickness; /* mm, > 0 */
    uint64_t photons; /* per channel (0: LUCENT_SHEET_PHOTONS) */
    int batches;      /* for the standard errors, 2..4096 (0: 8) */
    uint64_t seed;    /* 0: 1 */
    lucent_pool *pool;
    const char *label; /* the progress bar's (NULL: "sheet tables") */
} lucent_sheet_desc;

typedef struct lucent_sheet_result {
    uint64_t photons; /* per channel */
    /* [channel][exit bin]: pi f of orders 0 and 1, of orders >= 2, and their standard errors */
    double lobe[3][LUCENT_SHEET_BINS], lobe_se[3][LUCENT_SHEET_BINS];
    double diffuse[3][LUCENT_SHEET_BINS], diffuse_se[3][LUCENT_SHEET_BINS];
    double unscattered[3][LUCENT_SHEET_BINS]; /* order 0 alone (a part of lobe) */
    double total[3], total_se[3];             /* the transmittance, 2 int (lobe + diffuse) mu dmu */
} lucent_sheet_result;

/* Runs the sheet's Monte Carlo into dest. Deterministic for a seed. */
lucent_status lucent_sheet_run(const lucent_sheet_desc *desc, lucent_sheet_result *dest);

/* The same for count thicknesses (desc->thickness unread) into dest[0..count-1], thickness k seeded
 * seed + k; the faces' exit kernels, which most of a single run's time builds, are built once. */
lucent_status lucent_sheet_run_many(const lucent_sheet_desc *desc, const double *thickness, int count,
                                    lucent_sheet_result *dest);

/* The centre of exit bin b of the sheet's tables, in radians from the normal. */
double lucent_sheet_bin_angle(int bin);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_PROFILE_H */
