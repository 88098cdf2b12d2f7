/* Lucent materials: optical parameters per RGB channel, the measured presets of
 * Jensen et al. 2001, user materials from JSON, and the quantities derived from them
 * (reduced coefficients, albedos, transport coefficient, diffusion constant, mean free
 * paths, the classical-dipole total diffuse reflectance).
 *
 * Units: coefficients in mm^-1 and lengths in mm, everywhere in this API. Files may speak
 * cm^-1 or m^-1 (they must say which); they are converted when read. See docs/materials.md. */
#ifndef LUCENT_MATERIAL_H
#define LUCENT_MATERIAL_H

#include <stdbool.h>

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { LUCENT_MATERIAL_NAME_SIZE = 64 };

/* Valid ranges (checked by lucent_material_validate and by the JSON reader). */
#define LUCENT_MATERIAL_ETA_MIN 1.0
#define LUCENT_MATERIAL_ETA_MAX 3.0

/* ---- A skin described by its chromophores (docs/skin.md) ----
 * Up to three layers, top first: an epidermis, a dermis and optionally a hypodermis. Each layer's
 * absorption follows from its chromophores and the published spectra of lucent/spectral.h; its reduced
 * scattering is a power law in wavelength (Jacques 2013, eq. 2). All layers share the material's eta. */
enum { LUCENT_SKIN_MAX_LAYERS = 3 };

typedef enum lucent_skin_layer_kind {
    LUCENT_SKIN_EPIDERMIS,
    LUCENT_SKIN_DERMIS,
    LUCENT_SKIN_HYPODERMIS
} lucent_skin_layer_kind;

typedef struct lucent_skin_layer {
    int kind;           /* lucent_skin_layer_kind: names the layer and sets its default scattering */
    int reserved;       /* 0 (keeps the struct free of padding) */
    double thickness;   /* mm, > 0; INFINITY: semi-infinite (the last layer only) */
    double melanin;     /* melanosome volume fraction, [0, 1] */
    double eumelanin;   /* eumelanin share of the melanin, [0, 1] (the rest is pheomelanin) */
    double blood;       /* blood volume fraction, [0, 1]; melanin + blood <= 1 */
    double oxygenation; /* oxygen saturation of the blood, [0, 1] */
    double scatter;     /* reduced scattering mu_s' at 500 nm, mm^-1, > 0 */
    double f_rayleigh;  /* Rayleigh share of mu_s' at 500 nm, [0, 1] */
    double b_mie;       /* Mie power, mu_s' ~ lambda^-b_mie, [0, 4] */
    double g;           /* Henyey-Greenstein mean cosine, (-1, 1) */
} lucent_skin_layer;

typedef struct lucent_skin {
    int layer_count; /* 0: not a skin (an RGB material); 1..LUCENT_SKIN_MAX_LAYERS */
    int resolved;    /* 1 once the material's sigma_a, sigma_s, g hold the skin's equivalent medium
                        (lucent_skin_resolve, lucent/skin.h) */
    lucent_skin_layer layer[LUCENT_SKIN_MAX_LAYERS];
} lucent_skin;

/* A homogeneous scattering medium. Per channel (R, G, B):
 *   sigma_a >= 0, sigma_s >= 0, sigma_a + sigma_s > 0 (mm^-1), -1 < g < 1;
 * eta is the relative index of refraction (medium / outside), in [1, 3]. All finite. */
typedef struct lucent_material {
    char name[LUCENT_MATERIAL_NAME_SIZE];
    double sigma_a[3]; /* absorption coefficient, mm^-1 */
    double sigma_s[3]; /* scattering coefficient, mm^-1 */
    double g[3];       /* Henyey-Greenstein mean cosine of the phase function */
    double eta;        /* relative index of refraction */
    /* A spectral skin (skin.layer_count > 0): sigma_a, sigma_s and g then hold its equivalent
     * homogeneous medium per channel once resolved (lucent/skin.h); zero in an RGB material. */
    lucent_skin skin;
} lucent_material;

/* What follows from a material (Jensen et al. 2001). Per channel unless said. */
typedef struct lucent_material_derived {
    double sigma_s_prime[3]; /* reduced scattering sigma_s (1 - g), mm^-1 */
    double sigma_t[3];       /* extinction sigma_a + sigma_s, mm^-1 */
    double sigma_t_prime[3]; /* reduced extinction sigma_a + sigma_s', mm^-1 */
    double albedo[3];        /* single-scattering albedo sigma_s / sigma_t */
    double albedo_prime[3];  /* reduced albedo alpha' = sigma_s' / sigma_t' */
    double sigma_tr[3];      /* effective transport coefficient sqrt(3 sigma_a sigma_t'), mm^-1 */
    double diffusion[3];     /* diffusion constant D = 1 / (3 sigma_t'), mm */
    double mfp[3];           /* mean free path l = 1 / sigma_t, mm */
    double mfp_prime[3];     /* reduced (transport) mean free path l' = 1 / sigma_t', mm */
    double mfp_diffuse[3];   /* diffuse mean free path ld = 1 / sigma_tr, mm (+inf when sigma_a = 0) */
    double rd[3];            /* classical-dipole total diffuse reflectance */
    double fdr;              /* diffuse Fresnel reflectance of the boundary (one value: eta is grey) */
    double a;                /* boundary term A = (1 + Fdr) / (1 - Fdr) */
} lucent_material_derived;

/* ---- Physics (pure functions) ---- */

/* Returns the diffuse Fresnel reflectance Fdr(eta), the polynomial fit
 * Fdr = -1.440/eta^2 + 0.710/eta + 0.668 + 0.0636 eta used by Jensen et al. 2001. */
double lucent_fdr(double eta);

/* Returns the classical-dipole total diffuse reflectance Rd for reduced albedo alpha' in [0, 1]
 * (Jensen et al. 2001: the dipole profile integrated over the plane, in closed form).
 * Rd(0) = 0, Rd(1) = 1, and Rd increases with alpha'. */
double lucent_dipole_rd(double albedo_prime, double eta);

/* Returns the reduced albedo alpha' whose dipole Rd (for eta) equals rd, by bisection to 1e-12.
 * rd <= 0 gives 0; rd >= 1 gives 1. */
double lucent_dipole_albedo_from_rd(double rd, double eta);

/* Fills dest with the quantities derived from m (assumed valid; see lucent_material_validate). */
void lucent_material_derive(const lucent_material *m, lucent_material_derived *dest);

/* Checks the ranges stated at lucent_material; the message names the material and the field. */
lucent_status lucent_material_validate(const lucent_material *m);

/* ---- Other parameterisations (their inverses are in lucent_material_derived) ----
 * Each sets dest->sigma_a and dest->sigma_s from the given values and dest->g (and, for the
 * diffuse form, dest->eta), which the caller sets first. Lengths in mm. Fail with
 * LUCENT_ERR_INVALID_ARGUMENT (dest unchanged) when a value is out of range. */
typedef enum lucent_albedo_kind {
    LUCENT_ALBEDO_SINGLE, /* albedo = sigma_s / sigma_t, mfp = 1 / sigma_t (0 <= albedo <= 1) */
    LUCENT_ALBEDO_REDUCED /* albedo = sigma_s' / sigma_t', mfp = 1 / sigma_t' */
} lucent_albedo_kind;

/* From an albedo and the matching mean free path (> 0). */
lucent_status lucent_material_set_albedo(lucent_albedo_kind kind, const double albedo[3], const double mfp[3],
                                         lucent_material *dest);

/* From a diffuse colour: the dipole total diffuse reflectance rd (0 <= rd < 1) and the
 * diffuse mean free path ld = 1 / sigma_tr (> 0), inverting Rd(alpha') numerically. */
lucent_status lucent_material_set_diffuse(const double rd[3], const double mfp_diffuse[3], lucent_material *dest);

/* ---- Presets: the measured table of Jensen et al. 2001 (data/materials.json, built in) ---- */

/* Returns the number of presets (11). Thread-safe; the table is parsed once. */
int lucent_material_preset_count(void);

/* Copies preset index (0 <= index < count, in file order) into dest. */
lucent_status lucent_material_preset(int index, lucent_material *dest);

/* Copies the preset called name (case-insensitive) into dest; LUCENT_ERR_NOT_FOUND otherwise,
 * with a message listing the presets. */
lucent_status lucent_material_preset_find(const char *name, lucent_material *dest);

/* ---- Files ----
 * A material file holds one material object or {"materials": [...]}; see docs/materials.md.
 * Errors name the file and the JSON path ("my.json: materials[2].sigma_a[1]: must be >= 0").
 * All or nothing: on failure *dest is NULL and *count is 0. */

/* Reads every material of a file; free *dest with free(). */
lucent_status lucent_material_load(const char *path, lucent_material **dest, int *count);

/* Reads materials from JSON text; `name` stands for the file in messages (and names a lone
 * material that has no "name"). Free *dest with free(). */
lucent_status lucent_material_parse(const char *text, const char *name, lucent_material **dest, int *count);

/* Resolves spec into one material: a preset name (case-insensitive), a file holding exactly one
 * material, or "FILE.json#NAME" for one material of a file. */
lucent_status lucent_material_resolve(const char *spec, lucent_material *dest);

/* Writes materials as JSON text (ending in a newline) that lucent_material_parse reads back
 * ("units": "mm^-1"); with_derived adds each material's derived quantities under "derived"
 * (informational, ignored when read).
 * Free *dest with free(). */
lucent_status lucent_material_to_json(const lucent_material *materials, int count, bool with_derived, char **dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_MATERIAL_H */
