/* Lucent engines: each engine's subsurface model computed from its own published definition, and
 * its parameters fitted to a material's truth (Lucent's Monte Carlo profile and total diffuse
 * reflectance), with the error that remains. See docs/engines.md.
 *
 * The truth (lucent_engine_target): the radial profile R(r) of a half-space of the material lit by a
 * thin beam at normal incidence (the bake room's "mc" profile, lucent/bake.h) and its total diffuse
 * reflectance T (the bake's Monte Carlo Rd, disk-cached), or, for a layered material, one Monte Carlo
 * run of the stack (lucent/mc.h) giving both. A spectral skin (lucent/skin.h) is resolved to its
 * equivalent medium (the material the engines' models read: g, eta, the hand mapping's radius), while
 * its truth stays its own: the bands' Monte Carlo profile and the bake's T (its bands' totals, whatever
 * total_photons says); in layers it is refused (it is layered already).
 *
 * A fit matches T exactly (each engine's albedo or colour carries the total: the random walks' colour is
 * found on their own Monte Carlo) and chooses the shape parameters that minimise, summed over R, G, B, e_p^2:
 *   e_p = sqrt(sum_j (r_j R_model,j - r_j R_j)^2 / sum_j (r_j R_j)^2) over the bins with r_j <= r99,
 *         r99 the radius holding 99% of T (the whole grid when it holds less).
 * The report gives e_p per channel, the CIEDE2000 colour difference of T_model against T (the totals
 * taken as linear sRGB, white D65), and what the model cannot express.
 *
 * Units: lengths in mm inside Lucent; each engine's parameters in its own units (stated with each). */
#ifndef LUCENT_ENGINE_H
#define LUCENT_ENGINE_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/material.h"
#include "lucent/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- The engines ------------------------------------------------------------------------------ */

typedef enum lucent_engine_id {
    LUCENT_ENGINE_UNREAL_BURLEY = 0,    /* Unreal Engine 5 Subsurface Profile, Burley (mean free path) */
    LUCENT_ENGINE_UNREAL_SEPARABLE,     /* Unreal's legacy separable profile (Jimenez) */
    LUCENT_ENGINE_UNITY_HDRP,           /* Unity HDRP Diffusion Profile */
    LUCENT_ENGINE_BLENDER3_BURLEY,      /* Blender 3.x Principled BSDF, Christensen-Burley */
    LUCENT_ENGINE_BLENDER3_RANDOM_WALK, /* Blender 3.x Principled BSDF, Random Walk */
    LUCENT_ENGINE_BLENDER4_BURLEY,      /* Blender 4.x Principled BSDF, Christensen-Burley */
    LUCENT_ENGINE_OPENPBR,              /* OpenPBR Surface 1.x subsurface */
    LUCENT_ENGINE_GODOT,                /* Godot 4 StandardMaterial3D */
    LUCENT_ENGINE_GLTF,                 /* glTF 2.0 KHR_materials_transmission, _volume, _diffuse_transmission and the
                                           draft KHR_materials_volume_scatter (lucent/gltf.h's mapping, not a fit) */
    LUCENT_ENGINE_COUNT
} lucent_engine_id;

/* The engine's name on the command line ("unreal-burley", "unity-hdrp", "blender3-burley", ...). */
const char *lucent_engine_name(lucent_engine_id engine);

/* Its title ("Unreal Engine 5 Subsurface Profile (Burley)"). */
const char *lucent_engine_title(lucent_engine_id engine);

/* Reads a name of lucent_engine_name; LUCENT_ERR_INVALID_ARGUMENT listing the names otherwise. */
lucent_status lucent_engine_parse(const char *name, lucent_engine_id *dest);

/* ---- The truth -------------------------------------------------------------------------------- */

/* Limits of a target. */
enum { LUCENT_ENGINE_MAX_LAYERS = 16, LUCENT_ENGINE_SLAB_SAMPLES = 64 };

typedef struct lucent_engine_target_desc {
    const lucent_material *material; /* a homogeneous material (NULL when layers are given) */
    const lucent_layer *layers;      /* or a layered slab, top first (slab.thickness; the last may be
                                        INFINITY, a half-space), at most LUCENT_ENGINE_MAX_LAYERS */
    int layer_count;
    uint64_t photons;       /* the profile's photons per channel (0: LUCENT_BAKE_PROFILE_PHOTONS) */
    uint64_t total_photons; /* T's photons per channel: 0, the bake's (LUCENT_BAKE_RD_PHOTONS, disk-cached);
                               else a run of its own (homogeneous materials; a stack's T comes with its profile) */
    uint64_t seed;          /* 0: 1 */
    bool transmittance;     /* also the slab transmittance T(s) (homogeneous materials only; the bake
                              room's, disk-cached) */
    lucent_pool *pool;      /* NULL: serial */
    lucent_cache *cache;    /* NULL: nothing kept between runs */
} lucent_engine_target_desc;

typedef struct lucent_engine_target {
    lucent_material material; /* the material, or the top layer of a stack */
    int layer_count;          /* 1: homogeneous */
    lucent_layer layers[LUCENT_ENGINE_MAX_LAYERS];
    lucent_profile *profile; /* the Monte Carlo R(r) with its standard errors */
    double rd[3], rd_se[3];  /* the total diffuse reflectance T and its standard error */
    double r99[3];           /* mm: the radius holding 99% of T (or the grid's end) */
    int bins[3];             /* the bins the profile error counts (r <= r99) */
    double coverage[3];      /* the profile's energy on its grid over T */
    double noise[3];         /* the profile's own relative noise over those bins: sqrt(sum (r se)^2 /
                                 sum (r R)^2), the floor under any e_p */
    int slab_count;          /* samples of the Monte Carlo slab transmittance T(s) (0: none) */
    double slab_thickness[LUCENT_ENGINE_SLAB_SAMPLES]; /* mm */
    double slab_value[LUCENT_ENGINE_SLAB_SAMPLES][3];  /* T per channel */
    uint64_t photons, seed;
} lucent_engine_target;

/* Builds the truth of desc's material or layers. Free with lucent_engine_target_free. */
lucent_status lucent_engine_target_build(const lucent_engine_target_desc *desc, lucent_engine_target *dest);

/* Frees what a target holds and zeroes it (a zero target is fine). */
void lucent_engine_target_free(lucent_engine_target *target);

/* ---- A fit ------------------------------------------------------------------------------------- */

enum { LUCENT_ENGINE_MAX_PARAMS = 16, LUCENT_ENGINE_TEXT_SIZE = 512 };

/* One parameter in the engine's own name and unit. */
typedef struct lucent_engine_param {
    const char *name; /* "Mean Free Path Color" */
    const char *unit; /* "cm", "mm", "" (a ratio or a colour), ... */
    int count;        /* 1: a number, 3: a colour (R, G, B), 0: a choice in text */
    double value[3];
    const char *text; /* count 0: "Christensen-Burley", "true" */
} lucent_engine_param;

/* The model's radial profile, as renderers of the Burley family evaluate it. */
typedef struct lucent_engine_burley {
    bool valid;       /* the engine's model is Burley's R(r) = A s (e^{-s r} + e^{-s r / 3}) / (8 pi r) */
    double albedo[3]; /* A */
    double d[3];      /* mm: d = 1 / s */
} lucent_engine_burley;

typedef struct lucent_engine_fit_result {
    lucent_engine_id engine;
    bool hand; /* the hand mapping (radius = 1 / sigma_tr, colour = T), not a fit */
    int param_count;
    lucent_engine_param params[LUCENT_ENGINE_MAX_PARAMS];
    double profile_error[3];              /* e_p per channel */
    double profile_error_rms;             /* sqrt(mean over channels of e_p^2) */
    double total[3];                      /* T_model */
    double delta_e;                       /* CIEDE2000(T_model, T) */
    double transmit_error;                /* relative RMS of the fitted transmittance over the slab samples
                                    (engines with one, when the target has the slab), else NaN */
    lucent_engine_burley burley;          /* the Burley form, for the renderer's burley method and peers */
    lucent_profile *profile;              /* the model's R(r) on the target's grid (owned) */
    char cannot[LUCENT_ENGINE_TEXT_SIZE]; /* what the model cannot express (g, eta, layers, ...) */
    char notes[LUCENT_ENGINE_TEXT_SIZE];  /* conventions: units, project settings, what was assumed */
} lucent_engine_fit_result;

/* How to fit; a zero field means the default. */
typedef struct lucent_engine_fit_desc {
    uint64_t model_photons; /* random-walk models: photons per channel of their Monte Carlo
                               (0: LUCENT_ENGINE_MODEL_PHOTONS) */
    lucent_pool *pool;      /* NULL: serial */
} lucent_engine_fit_desc;

enum { LUCENT_ENGINE_MODEL_PHOTONS = 50000 };

/* Fits engine's model to target. Free the result with lucent_engine_fit_result_free. gltf is not fitted:
 * its values are lucent_gltf_material_from_lucent's, its errors those of the medium a reader of the draft
 * KHR_materials_volume_scatter builds from them (lucent_gltf_material_to_lucent), traced by Lucent's
 * Monte Carlo with model_photons per channel; a material whose channel does not absorb fails (the
 * attenuation cannot carry it). */
lucent_status lucent_engine_fit(const lucent_engine_target *target, lucent_engine_id engine,
                                const lucent_engine_fit_desc *desc, lucent_engine_fit_result *dest);

/* Evaluates the hand mapping users type today, radius = 1 / sigma_tr of the (top) material and colour
 * = T, in engine's parameters. Engines without a radius (unreal-separable, godot, gltf) fail with
 * LUCENT_ERR_UNSUPPORTED. */
lucent_status lucent_engine_hand(const lucent_engine_target *target, lucent_engine_id engine,
                                 const lucent_engine_fit_desc *desc, lucent_engine_fit_result *dest);

/* Frees the result's profile and zeroes it. */
void lucent_engine_fit_result_free(lucent_engine_fit_result *result);

/* Returns the parameter called name of a result (NULL when absent). */
const lucent_engine_param *lucent_engine_fit_param(const lucent_engine_fit_result *result, const char *name);

/* ---- The report: every engine of one material ------------------------------------------------ */

typedef struct lucent_engine_report_desc {
    lucent_engine_target_desc target;
    const lucent_engine_id *engines; /* 0 of them: every engine */
    int engine_count;
    bool hand; /* also the hand mapping of each engine that has a radius */
    lucent_engine_fit_desc fit;
} lucent_engine_report_desc;

typedef struct lucent_engine_report {
    lucent_engine_target target;
    int count;
    lucent_engine_fit_result fits[LUCENT_ENGINE_COUNT];
    lucent_engine_fit_result hand[LUCENT_ENGINE_COUNT]; /* hand[i].param_count 0: none */
} lucent_engine_report;

/* The truth and every asked engine's fit (and hand mapping). Free with lucent_engine_report_free. */
lucent_status lucent_engine_report_run(const lucent_engine_report_desc *desc, lucent_engine_report *dest);

void lucent_engine_report_free(lucent_engine_report *report);

/* The same on the heap (for bindings: Python's fit()); destroy with lucent_engine_report_destroy. */
lucent_status lucent_engine_report_create(const lucent_engine_report_desc *desc, lucent_engine_report **dest);
void lucent_engine_report_destroy(lucent_engine_report *report);

/* The report as JSON text (the truth, and per engine its parameters, errors and notes); free with free(). */
lucent_status lucent_engine_report_json(const lucent_engine_report *report, char **dest);

/* The report as Markdown text: a table of parameters per engine, then the errors; free with free(). */
lucent_status lucent_engine_report_markdown(const lucent_engine_report *report, char **dest);

/* The same, written atomically. */
lucent_status lucent_engine_report_write_json(const char *path, const lucent_engine_report *report);
lucent_status lucent_engine_report_write_markdown(const char *path, const lucent_engine_report *report);

/* ---- The models, from their definitions (tested against them in tests/test_engine.c) ------------ */

/* Christensen & Burley 2015, eq. 5 (searchlight, mean free path): s l = 1.85 - A + 7 |A - 0.8|^3; what
 * Unreal calls GetPerpendicularScalingFactor. */
double lucent_engine_unreal_scale(double albedo);

/* Unreal Engine 5 Burley: s (mm^-1) of one channel from Surface Albedo A, Mean Free Path Color m, Mean
 * Free Path Distance D and World Unit Scale W: the mean free path in mm is l = m D W 10, s = scale(A) / l. */
double lucent_engine_unreal_s(double albedo, double mfp_color, double mfp_distance, double world_unit_scale);

/* Cycles (Blender 3.4 and 4.x) Christensen-Burley: d (mm) = radius / (4 pi) (bssrdf_setup_radius). */
double lucent_engine_cycles_burley_d(double radius);

/* Cycles' Random Walk of Blender 3.x (CLOSURE_BSSRDF_RANDOM_WALK_ID): the radius scaled by
 * sqrt(3 (1 - alpha')), alpha' the classical dipole's reduced albedo for colour A with Fdr(ior), found as
 * Cycles finds it (12 bisection steps, bssrdf_dipole_compute_alpha_prime). */
double lucent_engine_cycles_rw_radius(double albedo, double radius, double ior);

/* Cycles' random walk: the single-scattering albedo for colour A and anisotropy g (Chiang, Kutz &
 * Burley 2016 with Wrenninge et al.'s anisotropic fit; subsurface_random_walk_remap), clamped as Cycles
 * does to [0, 0.999999]. */
double lucent_engine_cycles_rw_alpha(double albedo, double g);

/* OpenPBR 1.1 (Subsurface): van de Hulst's multiple-scattering albedo C of single-scattering albedo a
 * and anisotropy g, and its inversion a(C). */
double lucent_engine_openpbr_color(double alpha, double g);
double lucent_engine_openpbr_alpha(double color, double g);

/* Unity HDRP's transmittance through thickness t (mm) of a profile of scattering distance d (mm):
 * 0.25 (e^{-t/d} + 3 e^{-t/(3 d)}), to be multiplied by the Transmission Tint. */
double lucent_engine_hdrp_transmittance(double d, double t);

/* Godot 4's transmittance (non-skin): exp(-(8.25 z / depth)^2) for thickness z and Transmittance Depth
 * (same unit), to be multiplied by the Transmittance Color. */
double lucent_engine_godot_transmittance(double depth, double z);

/* Godot 4's blur: the world distance (in world units) of tap offset k (its kernel's .y) at
 * subsurf_scatter_strength, with the project's subsurface_scattering_depth_scale at 1 (the width
 * then follows the depth): k strength 2 / 3 (unit_size / depth in uv against the view's width). */
double lucent_engine_godot_tap_distance(double tap_offset, double strength);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_ENGINE_H */
