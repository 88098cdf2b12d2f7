/* The accumulated estimate of a tracer (film.c: accumulation and passes; film_alloc.c: the adaptive
 * allocation of samples; film_result.c: images and figures). */
#ifndef LUCENT_TRACE_FILM_H
#define LUCENT_TRACE_FILM_H

#include "trace/internal.h"

enum { TR_FILM_ACC = 7 }; /* doubles per pixel: sum RGB, sum of squares RGB, sum of squared luminance */

/* Per pixel: the estimate's sums (acc, count samples, hits of them met an object). Adaptive films
 * also keep a pilot estimate (one sample per pixel per pass, never part of the image) whose relative
 * variance decides how many samples each pixel gets in the next pass (quota, with the fraction carried). */
typedef struct tr_film {
    int width, height;
    bool adaptive;
    uint64_t seed;
    uint64_t passes;
    double seconds;
    double *acc;
    uint32_t *count, *hits;
    double *pilot; /* TR_FILM_ACC per pixel; adaptive only */
    double *carry;
    uint32_t *quota;
    /* the light paths' estimate (light_paths.c): per pixel the sums over passes of each pass's image,
     * of its squares and of its squared luminance (TR_FILM_ACC), over light_passes passes */
    double *light;
    uint64_t light_passes;
    /* per light (light_paths.c, emitter_shares): over the passes so far, the sum of a photon's squared
     * connections scaled to a pick probability of 1, and the photons */
    double light_m2[TR_MAX_LIGHTS];
    uint64_t light_n[TR_MAX_LIGHTS];
    /* per cell of the entry grid (light_paths.c, entry_probabilities): over the passes so far, the
     * photons that went on from their first arrival there, the sum of their squared connections
     * scaled to a pick probability and an entry probability of 1, and of their scatterings */
    double entry_m2[TR_ENTRY_CELLS], entry_cost[TR_ENTRY_CELLS];
    uint32_t entry_n[TR_ENTRY_CELLS], entry_arrived[TR_ENTRY_CELLS]; /* arrived: went on or not */
    tr_stats stats;
} tr_film;

lucent_status tr_film_create(int width, int height, bool adaptive, tr_film **dest);
void tr_film_destroy(tr_film *f);
void tr_film_reset(tr_film *f);

/* One pass: every pixel's quota of samples (one each unless adaptive), plus its pilot sample. With a
 * deadline (lucent_clock_seconds(), 0: none) no tile starts after it: the pass is then cut (*cut),
 * its finished tiles keep their samples (each pixel's mean and variance use its own count, so the
 * estimate stays unbiased) and it is not counted in passes. */
lucent_status tr_film_pass(const lucent_tracer *tr, tr_film *f, lucent_pool *pool, lucent_progress *progress,
                           double deadline, bool *cut);

/* Whether this process runs the tile of pixel p (lucent/dist.h). */
bool tr_film_owns(const tr_film *f, size_t p);

/* Gives every rank the values per_pixel doubles per pixel of v of the pixels other ranks own (after
 * agreeing on status; an exact maximum against -inf). */
lucent_status tr_film_gather(const tr_film *f, double *v, int per_pixel, lucent_status status);

/* The estimate of every process together (their sums; in a merge, the parts'), a new film; first
 * agrees on status. */
lucent_status tr_film_total(const tr_film *f, lucent_status status, tr_film **dest);

/* The quota of the next pass (film_alloc.c): adaptive films give pixels samples in proportion to
 * the square root of their relative variance as the pilot estimates it. */
void tr_film_allocate(tr_film *f);

/* Samples in the next pass, all pixels together. */
uint64_t tr_film_pass_samples(const tr_film *f);

/* Adds the counts of s to into. */
void tr_film_add_stats(tr_stats *into, const tr_stats *s);

/* One pass of light paths (light_paths.c): render.photons per pixel; with a deadline no chunk starts
 * after it, and a pass cut short is dropped whole (*cut). Nothing when no light path is served. */
lucent_status tr_light_pass(const lucent_tracer *tr, tr_film *f, lucent_pool *pool, double deadline, bool *cut);

/* The RMS over object pixels of se(Y) / Y (INFINITY when there is none), over every rank's pixels. */
lucent_status tr_film_error_rms(const tr_film *f, double *dest);

/* Images and figures of the estimate. */
lucent_status tr_film_result(const tr_film *f, lucent_trace_result *dest);

#endif
