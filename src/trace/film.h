/* The accumulated estimate of a tracer (film.c). */
#ifndef LUCENT_TRACE_FILM_H
#define LUCENT_TRACE_FILM_H

#include "trace/internal.h"

typedef struct tr_film {
    int width, height;
    uint64_t seed;
    uint64_t spp;
    double seconds;
    double *acc;
    uint32_t *hits;
    tr_stats stats;
} tr_film;

lucent_status tr_film_create(int width, int height, tr_film **dest);
void tr_film_destroy(tr_film *f);
void tr_film_reset(tr_film *f);

/* Adds one sample to every pixel (sample index f->spp). */
lucent_status tr_film_pass(const lucent_tracer *tr, tr_film *f, lucent_pool *pool, lucent_progress *progress);

/* The RMS over object pixels of se(Y) / Y (INFINITY when there is none). */
double tr_film_error_rms(const tr_film *f);

/* Images and figures of the estimate. */
lucent_status tr_film_result(const tr_film *f, lucent_trace_result *dest);

#endif
