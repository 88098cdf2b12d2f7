/* The pack's parts (lucent/pack.h), shared by pack.c, pack_shaders.c, pack_gltf.c and
 * pack_readme.c. Not public. */
#ifndef LUCENT_ENGINE_INTERNAL_H
#define LUCENT_ENGINE_INTERNAL_H

#include <stdio.h>

#include "lucent/bake.h"
#include "lucent/cdrf.h"
#include "lucent/kernel.h"
#include "lucent/pack.h"

/* One pack being written: the desc with its defaults resolved, the material and what was baked. */
typedef struct pack_ctx {
    lucent_pack_desc d;
    const lucent_material *m;
    lucent_material_derived derived;
    const lucent_baked *b;
    const lucent_render_settings *rs;
    lucent_pack_result r;
    const char *taps_text; /* the taps in the engine's language (lucent_taps_export) */
    double lut_png_scale;  /* cdrf-lut.png holds value / scale */
} pack_ctx;

/* True for the engines that get shaders in a GLSL dialect. */
static inline bool pack_is_glsl(lucent_pack_engine e)
{
    return e == LUCENT_PACK_GLSL || e == LUCENT_PACK_GLES || e == LUCENT_PACK_VULKAN;
}

/* The shader files of the engine (none for json): blur.frag.glsl or blur.hlsl, a complete pass;
 * cdrf.glsl|.hlsl and translucency.glsl|.hlsl, snippets without #version (the engine's shader
 * includes them). */
void pack_blur(FILE *f, const pack_ctx *p);
void pack_cdrf(FILE *f, const pack_ctx *p);
void pack_translucency(FILE *f, const pack_ctx *p);

/* material.gltf: the mesh (in mm, centred) in the material, a camera and a light (pack_gltf.c). */
lucent_status pack_gltf(const pack_ctx *p, const lucent_mesh *mesh_mm, const char *path);

/* README.md: the passes in order, their buffers, the kernel width, thickness and curvature at run time,
 * the composition with the specular, the files, the fitted engine parameters (pack_readme.c). */
void pack_readme(FILE *f, const pack_ctx *p);

#endif
