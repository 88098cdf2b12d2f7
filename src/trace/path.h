/* The state of one camera path and the bookkeeping of multiple importance sampling (integrator.c,
 * nee.c). See docs/trace.md for the estimator.
 *
 * Hero channel (spectral MIS, Wilkie et al. 2014, "Hero wavelength spectral sampling", EGSR): every
 * distance and phase-function direction of a path is sampled for one channel h drawn uniformly; beta
 * holds f_c / p_h (the path throughput of channel c over the hero's density) and r holds p_k / p_h
 * (the density with which channel k's own sampling would have made the same path). The balance
 * heuristic over the three channels gives the estimate beta_c L / mean_k(r_k), which is unbiased for
 * every channel whatever the hero. beta and r may be rescaled together (the estimate is unchanged). */
#ifndef LUCENT_TRACE_PATH_H
#define LUCENT_TRACE_PATH_H

#include "lucent/base.h"
#include "trace/guide.h"
#include "trace/internal.h"

/* What could also have found a light that the walk reaches next (Veach 1997, ch. 9):
 *   MIS_NONE: nothing (the camera, a delta boundary): the walk's own find counts fully;
 *   MIS_SURFACE: light sampling at rough boundary vertex p (outward normal n), and, when has_guide,
 *       next-event estimation through the boundary from the volume vertex before it;
 *   MIS_VOLUME: light sampling at vertex p inside an index-matched medium (n zero). */
typedef enum tr_mis_kind { MIS_NONE = 0, MIS_SURFACE, MIS_VOLUME } tr_mis_kind;

typedef struct tr_mis {
    tr_mis_kind kind;
    v3 p, n;
    double a[3];  /* r at the vertex */
    double pb[3]; /* density of the walk's direction there, per channel (BSDF or phase) */
    double tc[3]; /* transmittance along the walk since the vertex, per channel */
    bool has_guide;
    tr_guide guide; /* the volume vertex before p and ... */
    double rx[3];   /* ... r there, */
    v3 w;           /* the direction the walk took from it, */
    double walk_h;  /* and the hero's density of that step: p_HG(w) T_h(segment) */
} tr_mis;

typedef struct tr_path {
    const lucent_tracer *tr;
    lucent_rng *rng;
    tr_stats *stats;
    int hero;
    double beta[3], r[3];
    double eta_scale; /* undoes the radiance scaling of the boundaries crossed, for Russian roulette */
    double tw;        /* the hero's weight from the walk's transform so far (analog / transformed density) */
    bool analog;      /* the transform is off for the rest of the path (tw passed TR_TW_MAX at a vertex) */
    double L[3];
    v3 o, d;
    int medium; /* the object whose medium the ray travels in, -1 outside */
    int bounces, scatters;
    bool camera_ray; /* no surface met yet */
    bool done;
    tr_mis mis;
    /* the last vertex (volume, or boundary continuing inside), while the walk travels from it in a
     * rough object's medium */
    bool from_volume;
    tr_guide guide;
    double rx[3];
    double walk_h;
    /* a sphere inside the current medium that holds no surface (integrator.c) */
    v3 safe_c;
    double safe_r;     /* 0: none */
    double nee_weight; /* 1 / the probability with which this vertex's next-event estimate was made */
    /* A light path (light_paths.c): a photon whose next-event estimates connect to the camera
     * (tr->camera_light) and land in splats, scaled by splat_scale; beta is power, not radiance. */
    bool to_camera;
    struct tr_splats *splats;
    double splat_scale;
    tr_photon_entry *entry; /* a light path's entry roulette (NULL: a camera path) */
    /* A camera path before its first refracting surface (primary), and once it entered a light-path
     * object there (camera_side): the light-path lights' share of its light is the light paths' */
    bool primary, camera_side;
} tr_path;

static inline double tr_u(tr_path *p) { return lucent_rng_uniform(p->rng); }

/* How far the ray from x along unit w stays inside the path's safe sphere, where no surface is (0 when
 * x is not inside one). */
static inline double tr_path_safe_run(const tr_path *p, v3 x, v3 w)
{
    if (!(p->safe_r > 0)) return 0;
    v3 e = v3_sub(x, p->safe_c);
    double b = v3_dot(e, w), c = v3_dot(e, e) - p->safe_r * p->safe_r;
    return c < 0 ? -b + sqrt(b * b - c) : 0.0;
}

/* Where the transform's weights have grown past this, the walk goes on analog: in dense media, many
 * short steps under a coarse field multiply small mismatches into fireflies. Decided at scattering
 * vertices only, so that everything sampled from a vertex (and its MIS weights) uses one mode. */
#define TR_TW_MAX 4.0

/* The walk's transform at x in object `object` for this path (zero once it is analog). */
static inline void tr_path_transform(const tr_path *p, int object, v3 x, tr_transform *dest)
{
    if (p->analog)
        *dest = (tr_transform){{{0, 0, 0}}, {0, 0, 0}};
    else
        tr_field_lookup(p->tr, object, x, dest);
}

/* Adds value_c to the estimate when finite; tr_path_add_at: for a light path, to pixel `pixel` of its splats. */
void tr_path_add(tr_path *p, const double value[3]);
void tr_path_add_at(tr_path *p, long pixel, const double value[3]);

/* The light a next-event estimate out of object `object` targets: the camera for a light path (NULL
 * unless the object is one the light paths serve), else a light picked (the camera side's lights once
 * it left the others to the light paths); *ratio is the pick probability over the one lights.c's
 * densities carry. NULL when there is none. */
const tr_light *tr_path_pick(tr_path *p, int object, double *ratio);

/* Next-event estimation (nee.c): through a rough boundary from the vertex g describes (it is prepared
 * for the light picked, and keeps that for the walk's weights), from a volume vertex in an
 * index-matched medium, and at a boundary vertex. */
void tr_nee_through(tr_path *p, tr_guide *g);
void tr_nee_volume_matched(tr_path *p, v3 x);
void tr_nee_surface(tr_path *p, v3 y, v3 n, int object, bool inside);

/* The balance-heuristic weight of a light the walk found (in direction w) against the strategies
 * recorded in p->mis. */
double tr_mis_hit_weight(tr_path *p, const tr_light *l, v3 w);

#endif
