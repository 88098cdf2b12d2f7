/* Internal interfaces of the path tracer (src/trace). Embree's types stay in embree.c.
 *
 * Files: embree.c (the ray-tracing scene), bsdf.c (dielectric boundaries), media.c (the walk's
 * transform), field.c (the fluence field the walk follows), lights.c (light sampling
 * and emission, shadow rays), guide.c (the direction distribution of next-event estimation through a
 * rough boundary), nee.c (next-event estimation and the MIS weights), integrator.c (one camera
 * path, or light path), light_paths.c (photons from the lights connected to the camera), film.c,
 * film_alloc.c, film_result.c (the accumulated estimate: passes, adaptive allocation, images and
 * statistics), tracer.c (the public API). docs/trace.md explains the estimator. */
#ifndef LUCENT_TRACE_INTERNAL_H
#define LUCENT_TRACE_INTERNAL_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "base/optics.h"
#include "base/vec3.h"
#include "lucent/scene.h"
#include "lucent/trace.h"

static inline double tr_max3(const double a[3]) { return fmax(a[0], fmax(a[1], a[2])); }
static inline double tr_mean3(const double a[3]) { return (a[0] + a[1] + a[2]) * (1.0 / 3.0); }

/* ---- dielectric boundaries (bsdf.c) ----
 * Every surface separates the outside (index 1) from an object's medium (index eta). */
typedef enum tr_boundary_kind {
    TR_BOUNDARY_MATCHED = 0, /* eta == 1: light passes straight through, whatever the roughness */
    TR_BOUNDARY_SMOOTH,      /* roughness 0: Fresnel reflection and refraction (delta) */
    TR_BOUNDARY_ROUGH        /* GGX microfacets (Walter et al. 2007) */
} tr_boundary_kind;

typedef struct tr_boundary {
    tr_boundary_kind kind;
    double eta;   /* medium / outside */
    double alpha; /* GGX alpha */
    bool cycles3; /* rough: Blender 3.x Cycles' Glass BSDF instead of Walter's (render.boundary_model) */
} tr_boundary;

/* The optics (Fresnel, refraction, GGX D and G1, visible normals, Henyey-Greenstein, the basis)
 * come from base/optics.h. */

/* The boundary's BSDF for outward normal n, toward-viewer direction o and toward-light direction i
 * (both unit, pointing away from the surface): returns f (radiance convention, with the
 * (eta_o / eta_i)^2 factor of Walter eq. 21) and sets *pdf to the density with which
 * tr_bsdf_sample picks i given o (solid angle). Rough boundaries only (delta ones give 0). */
double tr_bsdf_eval(const tr_boundary *b, v3 n, v3 o, v3 i, double *pdf);

typedef struct tr_bsdf_sample {
    v3 i;          /* the sampled direction (away from the surface) */
    double weight; /* f |cos i| / pdf */
    double pdf;    /* solid angle; 0 for delta events */
    double scale;  /* the (eta_o / eta_i)^2 in weight: radiance squeezed into the denser medium */
    bool delta;
    bool transmit;
} tr_bsdf_sample;

/* Samples i given o. Returns false when the sample is lost (a microfacet sends it below the macro
 * surface): the path ends there, which is what the single-scattering microfacet model means. */
bool tr_bsdf_sample_dir(const tr_boundary *b, v3 n, v3 o, double u0, double u1, double u2, tr_bsdf_sample *dest);

/* ---- media (media.c) ---- */

typedef struct tr_object tr_object;

/* The walk's transform at a point, per channel k: free flights with sigma*(w) = sigma_t (1 - b_k (w . u_k))
 * and directions drawn from tr_walk_pdf (b_k = 0: the analog walk). See media.c and field.c. */
#define TR_WALK_B_MAX 0.9
typedef struct tr_transform {
    v3 u[3];
    double b[3];
} tr_transform;

double tr_walk_sigma(const tr_object *ob, const tr_transform *tf, int k, v3 w);
/* The walk's exp(-sw s) for a stretch s, given e = exp(-sigma_t s): e itself where the walk is analog
 * (sw == sigma_t), so that it costs no second exp. */
static inline double tr_walk_decay(double sw, double sigma_t, double e, double s)
{
    return sw == sigma_t ? e : exp(-sw * s);
}
double tr_walk_pdf(const tr_object *ob, const tr_transform *tf, int k, v3 d_in, v3 w);
/* Per channel k, the phase function f[k] and tr_walk_pdf pdf[k] for d_in -> w (the same values, each
 * computed once). */
void tr_walk_phase_pdf(const tr_object *ob, const tr_transform *tf, v3 d_in, v3 w, double f[3], double pdf[3]);
v3 tr_walk_sample(const tr_object *ob, const tr_transform *tf, int k, v3 d_in, double u0, double u1, double u2);

/* Safe spheres and the deep next-event roulette (integrator.c) pay for their distance queries only
 * where walks are long: media whose albedo is at least this in every channel (marble 0.998, the
 * jade bunny 0.990; Skin1's blue 0.68, where they cost 1.8x per sample and save nothing). */
#define TR_DENSE_ALBEDO 0.98

#define TR_MAX_LIGHTS 64 /* the lights a tracer takes (lights.c) */

/* ---- the ray-tracing scene (embree.c) ---- */
typedef struct tr_geometry tr_geometry;

typedef struct tr_hit {
    double t;
    int object; /* index into the tracer's objects */
    v3 n;       /* outward unit geometric normal of the triangle hit */
    int prim;   /* the triangle's index in its mesh */
    float u, v; /* its barycentrics: the point is (1 - u - v) v0 + u v1 + v v2 */
} tr_hit;

lucent_status tr_geometry_create(const lucent_scene *scene, const int *object_of, int count, tr_geometry **dest);
void tr_geometry_destroy(tr_geometry *g);

/* The first surface along o + t d with tnear < t < tfar (tfar may be INFINITY). */
bool tr_intersect(const tr_geometry *g, v3 o, v3 d, double tnear, double tfar, tr_hit *hit);

/* Whether any surface lies along o + t d for 0 < t < tfar. */
bool tr_occluded(const tr_geometry *g, v3 o, v3 d, double tfar);

/* The distance from p to the nearest surface of any object, or rmax when none is nearer (Embree's
 * point query with an exact point-triangle distance on the meshes' double positions); *closest (may
 * be NULL) receives the nearest surface point found (p itself when none is nearer than rmax). The
 * search costs less the smaller rmax is: a caller that knows a surface point s may pass |p - s|. */
double tr_distance_bound(const tr_geometry *g, v3 p, double rmax, v3 *closest);

/* A lattice of distances to the nearest surface over [lo, hi], spacing about h, each distance capped
 * at cap and filled on first use (depth.c); NULL when out of memory or the bounds are not finite. */
typedef struct tr_depth tr_depth;
tr_depth *tr_depth_create(const double lo[3], const double hi[3], double h, double cap);
void tr_depth_destroy(tr_depth *z);

/* A lower bound on the distance from x to any surface (0 outside the lattice). */
double tr_depth_bound(const tr_depth *z, const tr_geometry *g, v3 x);
/* The same bound from the vertices already known, without filling any (0 where none is). */
double tr_depth_known_bound(const tr_depth *z, v3 x);
/* Sphere tracing from x + t w along unit w (no surface before t) through the known vertices, each
 * step less margin, until past t_stop (or until the steps get small): the ray from x meets no surface
 * before the t returned. */
double tr_depth_free_run(const tr_depth *z, v3 x, v3 w, double t, double t_stop, double margin);

/* Ray queries (tr_intersect, tr_occluded) and distance queries this thread has made so far. */
void tr_geometry_queries(uint64_t *rays, uint64_t *points);

/* ---- the tracer ---- */
struct tr_object {
    int scene_index; /* objects[i] in the scene file */
    tr_boundary boundary;
    double sigma_t[3], sigma_s[3], g[3];
    double g_mean;      /* the guide's phase component (channel-independent) */
    double sigma_t_min; /* of the three channels: sets the walk's distance scales (integrator.c) */
    bool dense;         /* every channel's albedo >= TR_DENSE_ALBEDO: walks long enough for safe spheres */
    bool light_paths;   /* its subsurface light comes from light paths (light_paths.c) */
    tr_depth *depth;    /* dense objects: distances to the surface for the safe spheres (integrator.c) */
};

/* An object's importance field (field.c): a grid of grad ln(fluence) per channel. */
typedef struct tr_field {
    double lo[3], cell;
    int n[3];
    size_t offset; /* of its cells among all objects' during the build */
    float *grad;   /* per cell, per channel, 3 components */
} tr_field;

typedef struct tr_light {
    lucent_light_type type;
    int scene_index;
    double radiance[3]; /* directional: irradiance (delta) or disc radiance; point/sphere: intensity
                           (point) or surface radiance (sphere); environment: radiance */
    v3 toward;          /* directional: unit direction toward the light */
    v3 position;
    double radius;      /* sphere */
    double cos_cone;    /* directional disc: cos of the angular radius */
    double solid_angle; /* directional disc */
    bool delta;
    double select;     /* probability that next-event estimation picks it */
    bool light_paths;  /* the light paths (light_paths.c) carry its light into the objects they serve */
    double select_cam; /* the pick probability for camera paths that leave it to them (0 when it is theirs) */
    double power;      /* light paths: its luminous power through the emission disc (emit_area times) */
} tr_light;

/* The depth lattices of the dense objects (none with plain_flights), each over its mesh's bounds. */
lucent_status tr_depth_setup(lucent_tracer *tr);

struct lucent_tracer {
    const lucent_scene *scene;
    lucent_render_settings render;
    lucent_tracer_desc desc;
    tr_geometry *geometry;
    tr_object *objects;
    int object_count;
    tr_light *lights;
    int light_count;
    double select_cdf[TR_MAX_LIGHTS], select_cdf_cam[TR_MAX_LIGHTS];
    /* light paths (light_paths.c): photons from the lights marked light_paths, whose connections to
     * the camera (camera_light, a point "light" at the eye) carry the subsurface light of the objects
     * marked light_paths; camera paths that enter such an object first leave those lights to them */
    bool light_paths;
    int camera_side_lights; /* lights left to camera paths that enter a light-path object */
    tr_light camera_light;
    double emit_centre[3], emit_radius; /* photons start on a disc of this radius about the centre */
    double entry_lo[3], entry_h;        /* the entry grid over the scene's bounds: cubes of side entry_h */
    int entry_n[3];                     /* cells per axis, TR_ENTRY_RES at most */
    double eps;                         /* ray offset from surfaces, mm */
    bool has_matched;                   /* some object is index matched (shadow rays must pass through it) */
    const tr_light *walk_target;        /* the strongest light with a direction (NULL: none) */
    tr_field *fields;                   /* one per object once built (NULL: the analog walk) */
    double walk_strength;               /* the share of the fluence gradient the walk follows */
    struct tr_film *film;
};

/* A photon's start: uniform (u1, u2) on the disc of radius r about c + 2 r a, perpendicular to a. A
 * photon leaving it along -a meets all of a scene in the sphere (c, r) (field.c, light_paths.c). */
static inline v3 tr_disc_start(v3 c, double r, v3 a, double u1, double u2)
{
    v3 t, b;
    lucent_basis(a, &t, &b);
    double rho = r * sqrt(u1), phi = 2.0 * M_PI * u2;
    return v3_add(v3_madd(c, a, 2.0 * r), v3_add(v3_scale(t, rho * cos(phi)), v3_scale(b, rho * sin(phi))));
}

/* ---- lights (lights.c) ---- */
lucent_status tr_lights_build(lucent_tracer *tr);

/* Picks a light for next-event estimation; NULL when there is none. camera_side: a camera path that
 * leaves the light-path lights to the light paths picks among the others (select_cam). */
const tr_light *tr_light_pick(const lucent_tracer *tr, double u, bool camera_side);

/* The factor by which a camera-side path's pick probability of l differs from l->select, the
 * probability folded into tr_light_sample_from's and tr_light_pdf's densities (1 off the camera side). */
static inline double tr_light_pick_ratio(const tr_light *l, bool camera_side)
{
    return camera_side ? l->select_cam / l->select : 1.0;
}

/* Rec. 709 luminance weights (film.c), and the luminance of an RGB triple. */
extern const double tr_film_luminance[3];
static inline double tr_luminance(const double c[3])
{
    return tr_film_luminance[0] * c[0] + tr_film_luminance[1] * c[1] + tr_film_luminance[2] * c[2];
}

typedef struct tr_light_sample {
    v3 w;         /* unit direction toward the light */
    double dist;  /* distance to the emitter along w (INFINITY for distant lights) */
    double le[3]; /* radiance, or for delta lights the irradiance at the point */
    double pdf;   /* solid angle density (times the pick probability); for delta lights the pick probability */
    bool delta;
} tr_light_sample;

/* Samples light l from point p; n is the outward normal of a surface point (directions on its outer
 * side are sampled) or zero for a point in a medium. False when the light gives nothing there. */
bool tr_light_sample_from(const tr_light *l, v3 p, v3 n, double u1, double u2, tr_light_sample *dest);

/* Density (times the pick probability) with which tr_light_sample_from picks w from p (n as above);
 * 0 for delta lights. */
double tr_light_pdf(const tr_light *l, v3 p, v3 n, v3 w);

/* Radiance seen along a ray that escapes to infinity in direction w: the environment and sun discs.
 * Calls fn for each light that contributes, so the caller can weight them. */
typedef void (*tr_light_fn)(void *ctx, const tr_light *l, const double le[3]);
void tr_lights_escaped(const lucent_tracer *tr, v3 w, tr_light_fn fn, void *ctx);

/* How far a shadow ray from o along w (a direction sampled toward light l from a point near o, at
 * distance dist from there) may go before it reaches the light itself: for a sphere light, where the
 * ray from o meets it (dist when it passes by); for the others, dist. A shadow ray offset from the
 * sampled point meets a sphere light at another depth, and cut at dist it was blocked by the light
 * it was aimed at (by how much the offset moves the entry point across the sphere). */
double tr_light_distance(const tr_light *l, v3 o, v3 w, double dist);

/* The nearest sphere light hit by o + t d for t < tfar: its index, or -1. */
int tr_sphere_light_hit(const lucent_tracer *tr, v3 o, v3 d, double tfar, double *t);

/* Transmittance from o along d over (0, tmax) starting in medium `medium` (-1: outside): passes
 * through index-matched surfaces, multiplying exp(-sigma_t s) per channel for the stretches inside
 * media; false when a refracting surface or a sphere light blocks the way. Tw (may be NULL) receives
 * the probability that the walk's free flights pass the same stretches (exp(-sigma* s)). */
bool tr_transmittance(const lucent_tracer *tr, v3 o, v3 d, double tmax, int medium, double T[3], double Tw[3]);

/* The walk's transform at x in object `object` (zero without a field). */
void tr_field_lookup(const lucent_tracer *tr, int object, v3 x, tr_transform *dest);

/* ---- one camera path (integrator.c) ---- */
typedef struct tr_stats {
    uint64_t paths, scatters, bounces, escaped, truncated, nonfinite;
    uint64_t rays, points; /* ray queries (intersections, shadow rays) and distance queries */
    uint64_t free_flights; /* free flights inside a medium that needed no ray query (within a safe sphere) */
    uint64_t nee;          /* next-event estimates made from volume vertices */
    uint64_t photons;      /* light paths (light_paths.c); their queries count in rays and points */
    uint64_t entry_ended;  /* photons the entry roulette ended (integrator.c) */
} tr_stats;

/* Estimates the radiance through image point (px, py); dest receives RGB. Returns whether the camera
 * ray hit a visible object. */
bool tr_trace_path(const lucent_tracer *tr, double px, double py, struct lucent_rng *rng, double dest[3],
                   tr_stats *stats);

/* ---- light paths (light_paths.c) ---- */
struct tr_splats;

/* Decides which lights and objects the light paths serve (tracer.c calls it once the lights and the
 * objects are built). */
void tr_light_paths_setup(lucent_tracer *tr);

/* The light paths' entry roulette (light_paths.c): where a photon first arrives at an object the
 * light paths serve, it goes on with the probability q of that point's cell of the entry grid, and
 * is weighted by 1 / q. In: q per cell (NULL: 1 everywhere). Out: whether it arrived, the cell, and
 * the probability it was given there. */
enum { TR_ENTRY_RES = 24, TR_ENTRY_CELLS = TR_ENTRY_RES * TR_ENTRY_RES * TR_ENTRY_RES };
typedef struct tr_photon_entry {
    const float *q;
    bool arrived, went_on;
    int cell;
    double q_cell;
} tr_photon_entry;

/* The cell of the entry grid that holds y (-1: none). */
int tr_entry_cell(const lucent_tracer *tr, v3 y);

/* One light path from a photon leaving o along d with power per channel beta (relative) whose connections to
 * the camera land in splats, scaled by scale, through the entry roulette of entry (integrator.c). */
void tr_trace_light_path(const lucent_tracer *tr, v3 o, v3 d, const double beta[3], double scale,
                         struct lucent_rng *rng, struct tr_splats *splats, tr_photon_entry *entry, tr_stats *stats);

/* Multiplies le (a camera-light sample's 1 / d^2 at boundary point y) by the camera's importance
 * there: a pixel is the mean radiance over its area A of the image plane at unit distance, so a
 * direction at angle theta off the axis weighs 1 / (A cos^3 theta) (light_paths.c). Returns the
 * pixel (row-major index) where y appears, or -1 when it is outside the view (le untouched). */
long tr_light_paths_importance(const lucent_tracer *tr, v3 y, double le[3]);

/* Adds value (RGB) to pixel `pixel` of a pass's splats (light_paths.c). */
void tr_splat(struct tr_splats *s, long pixel, const double value[3]);

#endif
