/* The importance field that steers the walk (field.c). */
#ifndef LUCENT_TRACE_FIELD_H
#define LUCENT_TRACE_FIELD_H

#include "trace/internal.h"

/* Builds tr->fields from a light-tracing pre-pass (nothing when no light has a direction). */
lucent_status tr_field_build(lucent_tracer *tr, lucent_pool *pool);
void tr_field_destroy(lucent_tracer *tr);

#endif
