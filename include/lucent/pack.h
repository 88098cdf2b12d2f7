/* Lucent engine packs: everything an engine needs to draw one material as `lucent render` does, in
 * one folder (docs/pack.md): the separable kernel's taps and a complete blur pass, the CDRF's
 * shading snippet and look-up table, the translucency table T(s), in the engine's shading language
 * (GLSL 4.50, GLSL ES 3.00 for WebGL2, Vulkan GLSL, HLSL) or as data only; the tables as float EXR,
 * 16-bit PNG and CSV; the constants as JSON; a glTF 2.0 scene of a small mesh in the material
 * (lucent/gltf.h's mapping); and a README that says how to wire it, with each engine's parameters
 * fitted to the material (lucent/engine.h). The parts come from the bake room (lucent/bake.h) with
 * the renderer's settings. */
#ifndef LUCENT_PACK_H
#define LUCENT_PACK_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/material.h"
#include "lucent/mesh.h"
#include "lucent/settings.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lucent_pack_engine {
    LUCENT_PACK_GLSL = 0, /* OpenGL 4.5, GLSL 4.50 */
    LUCENT_PACK_GLES,     /* OpenGL ES 3.0 / WebGL2 (three.js, Babylon.js), GLSL ES 3.00 */
    LUCENT_PACK_VULKAN,   /* Vulkan GLSL 4.50 for SPIR-V (descriptor sets, push constants) */
    LUCENT_PACK_HLSL,     /* Direct3D 11/12, HLSL shader model 5 */
    LUCENT_PACK_JSON,     /* the data only: no shaders */
    LUCENT_PACK_ENGINE_COUNT
} lucent_pack_engine;

/* "glsl", "gles", "vulkan", "hlsl", "json" */
const char *lucent_pack_engine_name(lucent_pack_engine engine);

/* The engine called name (one of the above); LUCENT_ERR_INVALID_ARGUMENT listing them otherwise. */
lucent_status lucent_pack_engine_find(const char *name, lucent_pack_engine *dest);

/* How to pack; a zero field means the default (lucent_pack_defaults). */
typedef struct lucent_pack_desc {
    lucent_pack_engine engine;
    const char *out;                        /* the folder (created); required */
    int screen_width;                       /* pixels; 1920 */
    int screen_height;                      /* pixels; 1080 */
    double fov_y;                           /* vertical field of view, degrees; 45 */
    double object_height_mm;                /* the object's height: the glTF mesh's, and the depth of the printed width
                                where it fills the screen's height; 1800 */
    double distance_mm;                     /* instead: the depth of the printed width; 0: from object_height_mm */
    const lucent_render_settings *settings; /* the renderer's settings the parts are baked with; NULL:
                                               lucent_render_settings_defaults() */
    int lut_width, lut_height;              /* the CDRF look-up table; 64 x 64 */
    double kappa_max;                       /* its largest curvature, 1/mm; 1 */
    uint64_t sigma0_photons;                /* per channel and sphere of the sigma0 fit; the bake's */
    uint64_t transmit_photons;              /* per channel and thickness of T(s); the bake's */
    const lucent_mesh *mesh;                /* the glTF's mesh (any units: centred and scaled to object_height_mm);
                                NULL: an icosphere of that diameter */
    double roughness;    /* the boundary's microfacet alpha in the glTF; 0: 0.3, the scenes' default */
    lucent_cache *cache; /* sigma0 fits and slab tables kept between runs; NULL: none */
    lucent_pool *pool;   /* NULL: serial */
    /* The README's engine parameters, fitted to the material by lucent/engine.h (every engine, no hand
     * mapping), as `lucent fit` fits them: */
    uint64_t fit_photons;       /* the truth's profile photons per channel; 0: the fit's default
                                   (LUCENT_BAKE_PROFILE_PHOTONS, and the bake's Rd for T, kept in cache);
                                   N: N, and 2 N for T (as `lucent fit --photons N`) */
    uint64_t fit_model_photons; /* the random-walk and glTF models' photons per channel; 0:
                                   LUCENT_ENGINE_MODEL_PHOTONS */
    bool no_fit;                /* true: no fit (the README says how to get one) */
} lucent_pack_desc;

/* The defaults a zero desc stands for (out NULL). */
lucent_pack_desc lucent_pack_defaults(void);

/* What a pack holds about the screen: the kernel's width where desc says. */
typedef struct lucent_pack_result {
    double radius_mm;            /* the kernel's half-width (lucent_taps_radius) */
    double depth_mm;             /* where the width is measured */
    double pixels_per_mm;        /* at that depth (lucent_screen_pixels_per_mm) */
    double width_px;             /* 2 radius_mm pixels_per_mm */
    double pixels_per_mm_at_1mm; /* what the blur pass divides by the depth */
    double thickness_m;          /* the glTF's thicknessFactor: the mesh's mean chord 4 V / A */
    int file_count;              /* files written */
} lucent_pack_result;

/* Writes the pack of m into desc->out (see docs/pack.md for the files). The outputs go through the
 * library's atomic writer (lucent/output.h). result may be NULL. Errors name the material, the
 * part or the file. */
lucent_status lucent_pack(const lucent_material *m, const lucent_pack_desc *desc, lucent_pack_result *result);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_PACK_H */
