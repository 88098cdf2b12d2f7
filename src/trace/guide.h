/* The direction distribution of next-event estimation through a rough boundary (guide.c). */
#ifndef LUCENT_TRACE_GUIDE_H
#define LUCENT_TRACE_GUIDE_H

#include "trace/internal.h"

/* The guide of a vertex inside a rough object's medium: a volume vertex (the direction the walk arrived
 * with) or a boundary vertex whose walk may continue inside (its outward normal and viewer direction),
 * its object, and, once prepared for a light, the direction toward it and the normal n0 of the boundary
 * point met that way. */
typedef struct tr_guide_prep {
    const tr_light *light; /* NULL: none */
    v3 from, toward, n0;   /* from: where the ray toward the light started */
} tr_guide_prep;

typedef struct tr_guide {
    v3 x, d_in;
    double depth; /* a volume vertex's: no surface nearer (its safe sphere's), once set for next-event estimation */
    bool surface;
    v3 n, o;
    int object;
    const tr_light *light;
    bool prepared, has_n0;
    v3 toward, n0, from;     /* from: where the ray that found n0 started */
    tr_guide_prep inherited; /* a nearby earlier vertex's, which preparing for its light takes instead of a ray */
} tr_guide;

/* Moves volume guide g to vertex x of object `object` (nothing selected or prepared) and hands it what
 * its last vertex prepared, or what that one inherited, while x lies within radius of that ray's start
 * in the same object. */
void tr_guide_move(tr_guide *g, v3 x, int object, double radius);

/* Makes l the light of g (forgetting what was prepared for another light); no ray. */
void tr_guide_select(tr_guide *g, const tr_light *l);

/* Readies g for light l (one ray from x toward the light, unless already done for l or inherited for l). */
void tr_guide_prepare(const lucent_tracer *tr, tr_guide *g, const tr_light *l);

/* Whether tr_guide_sample's draw for u0 is the lobe's, which needs g prepared; the walk-like share
 * (phase function or BSDF) needs only the light selected. */
bool tr_guide_draw_needs_ray(const tr_guide *g, double u0);

/* Draws an inside direction w from q (g selected, and prepared when tr_guide_draw_needs_ray); false
 * when the draw is lost (it counts as zero). */
bool tr_guide_sample(const lucent_tracer *tr, const tr_guide *g, double u0, double u1, double u2, v3 *w);

/* q(w), solid angle. */
double tr_guide_pdf(const lucent_tracer *tr, const tr_guide *g, v3 w);

/* What leaving the vertex in direction w means: *f the vertex's scattering function (phase function,
 * or BSDF times |cos|) for channel k, *pdf the walk's own density of that direction (BSDF or phase;
 * for a volume vertex per channel, with the walk's transform tf). */
void tr_guide_vertex(const lucent_tracer *tr, const tr_guide *g, const tr_transform *tf, v3 w, double f[3],
                     double pdf[3]);

#endif
