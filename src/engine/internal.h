/* What the files of the engine room share: for the fits (engine.c, burley.c, separable.c, walk.c,
 * cycles_walk.c), the error of a model against the truth, the amplitude that minimises it, a 1-D
 * minimiser and the parameter list of a result; for the pack (pack.c, pack_shaders.c, pack_gltf.c,
 * pack_readme.c), the pack being written. Not public. */
#ifndef LUCENT_SRC_ENGINE_INTERNAL_H
#define LUCENT_SRC_ENGINE_INTERNAL_H

#include <math.h>
#include <stdio.h>

#include "lucent/bake.h"
#include "lucent/cdrf.h"
#include "lucent/engine.h"
#include "lucent/kernel.h"
#include "lucent/pack.h"

/* The bins any channel's error counts: max over c of target->bins[c]. */
int eng_bins(const lucent_engine_target *t);

/* e_p of channel c of model (bin values on the target's grid, at least the counted bins). */
double eng_profile_error(const lucent_engine_target *t, int c, const double *model);

/* For a model a u(r) with total a tau (u: unit bin values on the target's grid), the a that matches the
 * truth's T (a tau = T: every engine's albedo or colour carries the total), with e_p of channel c (e_t: 0). */
double eng_amplitude(const lucent_engine_target *t, int c, const double *u, double tau, double *e_p, double *e_t);

/* Minimises f over x in [lo, hi] on a log scale: a scan of `scan` points, then golden-section search
 * about the best to a relative tolerance of 1e-4. Returns the minimiser; *fmin its value. */
typedef double (*eng_fn)(double x, void *ctx);
double eng_minimize_log(eng_fn f, void *ctx, double lo, double hi, int scan, double *fmin);

/* Appends a parameter to a result (the strings are static). */
void eng_param(lucent_engine_fit_result *r, const char *name, const char *unit, int count, const double *v);
void eng_param1(lucent_engine_fit_result *r, const char *name, const char *unit, double v);
void eng_param_text(lucent_engine_fit_result *r, const char *name, const char *text);

/* Appends to r->cannot or r->notes ("; " between items). */
void eng_cannot(lucent_engine_fit_result *r, const char *fmt, ...) LUCENT_PRINTF(2, 3);
void eng_note(lucent_engine_fit_result *r, const char *fmt, ...) LUCENT_PRINTF(2, 3);

/* Fills the errors of r (profile_error[], its RMS, total[], delta_e) from a model's bin values and totals,
 * and keeps the profile (r->profile, created on the target's grid from model[c], which hold the
 * target's bin count). */
lucent_status eng_finish(const lucent_engine_target *t, double *const model[3], const double total[3],
                         lucent_engine_fit_result *r);

/* What the material cannot be told by a homogeneous model with one g and its own boundary: per-channel
 * or layered g, layers. */
void eng_cannot_common(const lucent_engine_target *t, lucent_engine_fit_result *r, bool has_g, bool has_eta);

/* The mean g of the (top) material, and whether its channels differ. */
double eng_mean_g(const lucent_engine_target *t, bool *differs);

/* 1 / sigma_tr of each channel of the (top) material (the hand mapping's radius); false when a channel
 * does not absorb (an infinite length). */
bool eng_hand_radius(const lucent_engine_target *t, double dest[3]);

/* ---- the families (burley.c, separable.c, walk.c) ---- */

/* Unit Burley bins (A = 1, d) on the target's first n bins into dest; truncate: Cycles' cut at 16 d,
 * renormalised. */
lucent_status eng_burley_unit(const lucent_engine_target *t, int n, double d, bool truncate, double *dest);

lucent_status eng_fit_burley(const lucent_engine_target *t, lucent_engine_id e, bool hand, lucent_engine_fit_result *r);
lucent_status eng_fit_separable(const lucent_engine_target *t, lucent_engine_fit_result *r);
lucent_status eng_fit_godot(const lucent_engine_target *t, lucent_engine_fit_result *r);
lucent_status eng_fit_walk(const lucent_engine_target *t, lucent_engine_id e, bool hand,
                           const lucent_engine_fit_desc *desc, lucent_engine_fit_result *r);
/* glTF's extensions (gltf_model.c): lucent/gltf.h's values, the errors of the medium a reader builds. */
lucent_status eng_fit_gltf(const lucent_engine_target *t, const lucent_engine_fit_desc *desc,
                           lucent_engine_fit_result *r);

/* Cycles 3.4's random walk in a half-space at unit extinction (cycles_walk.c): single-scattering albedo
 * alpha, anisotropy g; rd_r (nr bins of width dr) the bin averages of the exit radius, total and its error. */
lucent_status eng_cycles_walk(double alpha, double g, uint64_t photons, uint64_t seed, double dr, int nr,
                              lucent_pool *pool, double *rd_r, double *total, double *total_se);

/* ---- the pack ---- */

/* One pack being written: the desc with its defaults resolved, the material and what was baked. */
typedef struct pack_ctx {
    lucent_pack_desc d;
    const lucent_material *m;
    lucent_material_derived derived;
    const lucent_baked *b;
    const lucent_render_settings *rs;
    lucent_pack_result r;
    const lucent_engine_report *fit; /* the engines' fitted parameters (NULL: desc.no_fit) */
    const char *taps_text;           /* the taps in the engine's language (lucent_taps_export) */
    double lut_png_scale;            /* cdrf-lut.png holds value / scale */
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
