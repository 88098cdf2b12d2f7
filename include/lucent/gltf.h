/* Lucent materials in glTF 2.0: the mapping from a Lucent material (a scattering medium behind a
 * dielectric boundary) to glTF's material extensions, and back. docs/pack.md#gltf states it in full.
 *
 *   KHR_materials_ior                 ior = eta
 *   KHR_materials_transmission        transmissionFactor 1: the boundary is a clear dielectric (the
 *                                     medium inside gives the colour), base colour white
 *   KHR_materials_volume              the ABSORPTION the ratified extension defines: light through x
 *                                     metres keeps attenuationColor^(x / attenuationDistance), so
 *                                     sigma_a,c = -ln(attenuationColor_c) / attenuationDistance
 *   KHR_materials_diffuse_transmission  diffuseTransmissionFactor 1, colour white: the cue for a dense
 *                                     medium (the extension's "Scattering & (Diffuse-)Transmission")
 *   KHR_materials_volume_scatter      DRAFT (Khronos glTF pull request 2453): multiscatterColor, the
 *                                     multiple-scattering albedo whose inversion (Kulla & Conty 2017, as
 *                                     the draft states it) gives the single-scattering albedo
 *                                     sigma_s / sigma_t; scatterAnisotropy = g
 *   extras.lucent                     Lucent's exact coefficients (sigma_a, sigma_s, g per channel in
 *                                     mm^-1, eta, the boundary's roughness), which a reader prefers
 *
 * Lengths in glTF are metres; the material's coefficients stay in mm^-1 as everywhere in Lucent. */
#ifndef LUCENT_GLTF_H
#define LUCENT_GLTF_H

#include <stdbool.h>

#include "lucent/base.h"
#include "lucent/material.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The extensions' names, as written in extensionsUsed. */
#define LUCENT_GLTF_EXT_IOR "KHR_materials_ior"
#define LUCENT_GLTF_EXT_TRANSMISSION "KHR_materials_transmission"
#define LUCENT_GLTF_EXT_VOLUME "KHR_materials_volume"
#define LUCENT_GLTF_EXT_DIFFUSE_TRANSMISSION "KHR_materials_diffuse_transmission"
#define LUCENT_GLTF_EXT_VOLUME_SCATTER "KHR_materials_volume_scatter" /* a draft */

/* A glTF material's values that matter to a scattering medium; lengths in metres. */
typedef struct lucent_gltf_material {
    char name[LUCENT_MATERIAL_NAME_SIZE];
    double base_color[3];        /* pbrMetallicRoughness.baseColorFactor (alpha is 1) */
    double metallic;             /* metallicFactor (0) */
    double roughness;            /* roughnessFactor: the square root of the microfacet alpha */
    double ior;                  /* KHR_materials_ior.ior */
    bool has_transmission;       /* KHR_materials_transmission */
    double transmission;         /* transmissionFactor */
    bool has_volume;             /* KHR_materials_volume */
    double thickness;            /* thicknessFactor, mesh units (0: thin-walled, no volume) */
    double attenuation_distance; /* metres; +INFINITY: no absorption (the extension's default) */
    double attenuation_color[3]; /* in (0, 1] */
    bool has_diffuse_transmission;
    double diffuse_transmission;          /* diffuseTransmissionFactor */
    double diffuse_transmission_color[3]; /* diffuseTransmissionColorFactor */
    bool has_scatter;                     /* KHR_materials_volume_scatter (draft) */
    double multiscatter_color[3];         /* the multiple-scattering albedo, [0, 1] */
    double scatter_anisotropy;            /* Henyey-Greenstein g, (-1, 1) */
} lucent_gltf_material;

/* The draft's single-scattering albedo from the multiple-scattering albedo m in [0, 1] (Kulla &
 * Conty 2017, "Revisiting physically based shading at Imageworks", as KHR_materials_volume_scatter
 * writes it): 1 - (4.09712 + 4.20863 m - sqrt(9.59217 + 41.6808 m + 17.7126 m^2))^2, clamped to
 * [0, 1]. */
double lucent_gltf_single_albedo(double multiscatter);

/* Its inverse: the m in [0, 1] whose lucent_gltf_single_albedo is albedo (bisection to 1e-15). */
double lucent_gltf_multiscatter_albedo(double albedo);

/* The glTF material of m (validated first): roughness_alpha is the boundary's microfacet alpha in
 * [0, 1] (the scene's "roughness"), thickness_m the volume's thicknessFactor in mesh units (> 0). The
 * attenuation distance is a tenth of the shortest absorption length, 1 / (10 max_c sigma_a,c), so that
 * every attenuationColor is at least e^-0.1: importers that read the pair linearly as an absorption
 * density (1 - colour) / distance, as Blender 3.4's does, then stay within 5% of sigma_a. */
lucent_status lucent_gltf_material_from_lucent(const lucent_material *m, double roughness_alpha, double thickness_m,
                                               lucent_gltf_material *dest);

/* The inverse: the medium a glTF material describes, and its boundary's microfacet alpha
 * (roughness^2; may be NULL).
 *   - with KHR_materials_volume (thicknessFactor > 0): sigma_a from the attenuation; with the
 *     draft KHR_materials_volume_scatter also sigma_s = sigma_a a / (1 - a), a the single-scattering
 *     albedo of multiscatterColor, and g = scatterAnisotropy; without it a clear medium (sigma_s 0);
 *   - without a volume (a surface material, thin-walled): a dense medium whose multiple-scattering
 *     albedo is the base colour (at most LUCENT_GLTF_SURFACE_MAX_ALBEDO: a medium that does not absorb
 *     gives walks without end), with a mean free path of LUCENT_GLTF_SURFACE_MFP_MM (sigma_t =
 *     1 / mfp): the draft's own reading of a colour as the look of a dense medium, at a scale glTF
 *     does not give;
 *   - eta = ior.
 * Fails (LUCENT_ERR_INVALID_ARGUMENT naming the material) when the result is not a valid medium: an
 * ior outside [1, 3], a channel with neither absorption nor scattering, a multiscatterColor of 1 in
 * a channel that absorbs (its scattering would be infinite). */
#define LUCENT_GLTF_SURFACE_MFP_MM 1.0
#define LUCENT_GLTF_SURFACE_MAX_ALBEDO 0.9
lucent_status lucent_gltf_material_to_lucent(const lucent_gltf_material *g, lucent_material *dest,
                                             double *roughness_alpha);

/* The glTF material object as JSON text (name, pbrMetallicRoughness, the extensions above and
 * extras.lucent with m's exact coefficients and roughness_alpha), as lucent pack writes it; the
 * extensions it uses are the five LUCENT_GLTF_EXT_* names. Free *dest with free(). */
lucent_status lucent_gltf_material_json(const lucent_material *m, double roughness_alpha, double thickness_m,
                                        char **dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_GLTF_H */
