/* The importance field that steers the walk (field.c). */
#ifndef LUCENT_TRACE_FIELD_H
#define LUCENT_TRACE_FIELD_H

#include "trace/internal.h"

/* Builds tr->fields from a light-tracing pre-pass (nothing when no light has a direction). With a deadline (lucent_clock_seconds(), 0: none) photon chunks not begun by then are left out:
 * a field of fewer photons (the gradient of ln phi needs no normalisation), still only a density. */
lucent_status tr_field_build(lucent_tracer *tr, lucent_pool *pool, double deadline);
void tr_field_destroy(lucent_tracer *tr);

/* The share of each cell of f (object's grid) inside the object, from 2 x 2 x 2 points per cell (for tests). */
void tr_field_inside_share(const lucent_tracer *tr, int object, const tr_field *f, float *dest);

#endif
