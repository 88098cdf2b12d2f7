/* What the files of the engine room share: the error of a model against the truth, the amplitude that
 * minimises it, a 1-D minimiser, and the parameter list of a result. */
#ifndef LUCENT_SRC_ENGINE_INTERNAL_H
#define LUCENT_SRC_ENGINE_INTERNAL_H

#include <math.h>

#include "lucent/engine.h"

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

/* Cycles 3.4's random walk in a half-space at unit extinction (cycles_walk.c): single-scattering albedo
 * alpha, anisotropy g; rd_r (nr bins of width dr) the bin averages of the exit radius, total and its error. */
lucent_status eng_cycles_walk(double alpha, double g, uint64_t photons, uint64_t seed, double dr, int nr,
                              lucent_pool *pool, double *rd_r, double *total, double *total_se);

#endif
