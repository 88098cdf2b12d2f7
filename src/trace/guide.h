/* The direction distribution of next-event estimation through a rough boundary (guide.c). */
#ifndef LUCENT_TRACE_GUIDE_H
#define LUCENT_TRACE_GUIDE_H

#include "trace/internal.h"

/* A volume vertex's guide: the vertex, the direction the walk arrived with, its object, and, once
 * prepared for a light, the direction toward it and the boundary normal n0 met that way. */
typedef struct tr_guide {
    v3 x, d_in;
    int object;
    const tr_light *light;
    bool prepared, has_n0;
    v3 toward, n0;
} tr_guide;

/* Readies g for light l (one ray from x toward the light, unless already done for l). */
void tr_guide_prepare(const lucent_tracer *tr, tr_guide *g, const tr_light *l);

/* Draws an inside direction w from q; false when the draw is lost (it counts as zero). */
bool tr_guide_sample(const lucent_tracer *tr, const tr_guide *g, double u0, double u1, double u2, v3 *w);

/* q(w), solid angle. */
double tr_guide_pdf(const lucent_tracer *tr, const tr_guide *g, v3 w);

#endif
