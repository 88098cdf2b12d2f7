/* Lucent trace: the physically based reference. A volumetric path tracer (Embree 3) for the scenes of
 * lucent/scene.h: homogeneous media inside closed meshes (sigma_a, sigma_s, g per channel, eta),
 * a dielectric boundary that is rough (GGX, the object's roughness) or smooth (Fresnel) or index
 * matched (eta 1), Henyey-Greenstein random walks, next-event estimation from every vertex with
 * multiple importance sampling, the camera of lucent_camera_ray. See docs/trace.md.
 *
 * Usage:
 *   lucent_tracer *tr;
 *   lucent_tracer_create(scene, NULL, &tr);            (refuses scenes it cannot converge on)
 *   lucent_trace_result r;
 *   lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 64, .pool = pool}, &r);
 *   ... r.image (mean radiance), r.variance (of that mean), r.coverage ...
 *   lucent_trace_result_free(&r);
 *   lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 64, .pool = pool}, &r); (adds 64 more)
 *   lucent_tracer_destroy(tr);
 *
 * Determinism: sample s of pixel (x, y) draws from RNG stream (s << 32 | y * width + x) of the seed,
 * and every pixel adds its samples in order, so an estimate depends only on the seed and the
 * number of samples: not on the thread count, nor on how the samples were split between calls. */
#ifndef LUCENT_TRACE_H
#define LUCENT_TRACE_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/image.h"
#include "lucent/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lucent_tracer lucent_tracer;

/* The rough boundary's BSDF (render.boundary_model). WALTER: Walter et al. 2007, the physics
 * Lucent follows. CYCLES3: a peer's convention, for side-by-side validation, not physics: Blender
 * 3.x Cycles' Glass BSDF, reflection weighted by the Fresnel term of the macro normal and the view
 * direction, refraction by max(1e-4, 1 - that), no check that a transmitted pair's implied microfacet
 * is valid (docs/trace.md). */
typedef enum lucent_boundary_model { LUCENT_BOUNDARY_WALTER = 0, LUCENT_BOUNDARY_CYCLES3 } lucent_boundary_model;

/* Which objects' subsurface light is traced from the lights (render.light_paths, docs/trace.md "Light
 * paths"): none, the dense ones (every channel's albedo >= 0.98) with a rough boundary, or every
 * object with a rough boundary. */
typedef enum lucent_light_paths {
    LUCENT_LIGHT_PATHS_OFF = 0,
    LUCENT_LIGHT_PATHS_AUTO,
    LUCENT_LIGHT_PATHS_ALL
} lucent_light_paths;

/* How a tracer is made; a zero field means the default. */
typedef struct lucent_tracer_desc {
    /* Drop the light reflected where a camera ray first meets a refracting surface (the specular
     * highlight), keeping the light that went through the medium: what the CDRF sphere simulation
     * (lucent_cdrf_sphere_run) and diffuse-only approximations produce. Default false. */
    bool subsurface_only;
    /* For comparison only: next-event estimation only at the boundary vertices the walk meets (what
     * Blender's Cycles does), not through the boundary from every scattering vertex. Unbiased, but
     * under a delta light with a rough boundary it converges one to two orders of magnitude slower.
     * Default false. */
    bool boundary_nee_only;
    /* Adaptive sampling: each pass gives every pixel one sample plus a share of three more per pixel
     * in proportion to the square root of its relative variance, measured by a separate pilot
     * estimate (one more sample per pixel and pass, not part of the image), so the image stays
     * unbiased. For the per-pixel relative error (dark regions of translucent objects). Default false:
     * one sample per pixel and pass. */
    bool adaptive;
    /* For comparison only (both unbiased, the defaults are faster in dense media; docs/trace.md):
     * plain_flights: every free flight inside a medium asks Embree for the boundary ahead, instead of
     * skipping the query when the flight ends inside a sphere known to hold no surface;
     * nee_every_vertex: next-event estimation from every volume vertex, instead of playing Russian
     * roulette with it at vertices deeper than a few mean free paths (weighted by 1 / probability) and
     * on its exit, each with its own ray toward the light for its guide (not one a vertex within a mean
     * free path traced). */
    bool plain_flights;
    bool nee_every_vertex;
} lucent_tracer_desc;

/* Creates a tracer for a loaded scene (which must outlive it): builds the ray-tracing scene from the
 * visible objects (render settings, camera and lights from the scene). Refuses, with
 * LUCENT_ERR_UNSUPPORTED and a message naming the light and the object, a scene where a delta light
 * (directional with angular_radius 0, or point) could reach an object's medium only through a smooth
 * boundary (roughness 0, eta != 1): a path tracer cannot converge on that light's share. desc may be
 * NULL. On failure *dest is NULL. */
lucent_status lucent_tracer_create(const lucent_scene *scene, const lucent_tracer_desc *desc, lucent_tracer **dest);

/* Destroys a tracer (NULL is accepted). */
void lucent_tracer_destroy(lucent_tracer *tracer);

/* Forgets the samples taken, so that the next render starts a new estimate (any seed). */
void lucent_tracer_reset(lucent_tracer *tracer);

/* How much to add to the estimate; a zero field means the default. */
typedef struct lucent_trace_desc {
    int spp;             /* passes to add, one sample per pixel each unless adaptive (0: the scene's
                            render.spp); the call may stop earlier at time_limit or target_error */
    uint64_t seed;       /* 0: the estimate's seed, or the scene's render.seed for a new estimate.
                            An estimate keeps the seed it started with: another seed for an estimate
                            that has samples is refused */
    lucent_pool *pool;   /* NULL: the calling thread only */
    double time_limit;   /* seconds for this call (0: the scene's render.time_limit, where 0 means
                            none; < 0: none); checked before every tile of 16 x 16 pixels, so
                            the call ends within a tile's time of it; a pass cut short keeps its
                            finished tiles' samples (each pixel's mean uses its own count) without
                            counting in spp, so a limit shorter than one pass leaves pixels empty */
    double target_error; /* stop once the estimate's error_rms (lucent_trace_result) is at most this,
                            after at least 16 samples per pixel (0: no target) */
    const char *label;   /* progress label (NULL: "trace") */
} lucent_trace_desc;

/* Summary of the per-pixel relative standard error of the luminance, se(Y) / Y, over the object
 * pixels (coverage >= 0.5 and Y > 0). */
typedef struct lucent_trace_error {
    double median, p90, rms; /* rms: sqrt of the mean of (se / Y)^2 */
    uint64_t pixels;         /* object pixels with Y > 0 */
    uint64_t dark_pixels;    /* object pixels with Y == 0 (no relative error) */
} lucent_trace_error;

/* Where the time goes: totals over the estimate's camera paths (the pilot's included) and light paths
 * (photons, docs/trace.md "Light paths"; their queries, scatterings and estimates count here too). */
typedef struct lucent_trace_cost {
    uint64_t paths;
    uint64_t scatters;     /* volume scattering vertices */
    uint64_t bounces;      /* surface events */
    uint64_t rays;         /* Embree ray queries: intersections and shadow rays */
    uint64_t points;       /* Embree distance (point) queries */
    uint64_t free_flights; /* free flights inside a medium that needed no ray query */
    uint64_t nee;          /* next-event estimates made from volume vertices */
    uint64_t photons;      /* light paths (docs/trace.md); their queries count in rays and points */
    uint64_t entry_ended;  /* photons the entry roulette ended where they first arrived at an object */
} lucent_trace_cost;

typedef struct lucent_trace_result {
    lucent_image *image;    /* mean linear HDR RGB radiance, top row first */
    lucent_image *variance; /* RGB variance of that mean (the standard error squared), from the samples */
    lucent_image *coverage; /* 1 channel: the fraction of camera rays that met a visible object */
    uint64_t spp;           /* passes in the estimate (all calls): samples per pixel, unless adaptive */
    uint64_t samples;       /* camera samples in the image (all pixels; adaptive: the pilot's not counted) */
    uint64_t seed;
    double seconds;            /* rendering time of the estimate (all calls), wall clock */
    double samples_per_second; /* camera paths per second over the estimate */
    lucent_trace_error error;
    uint64_t truncated; /* paths ended by max_bounces / max_scatter */
    uint64_t escaped;   /* paths that left a medium through a hole in its mesh */
    uint64_t nonfinite; /* contributions dropped because they were not finite (expect 0) */
    lucent_trace_cost cost;
} lucent_trace_result;

/* Adds samples to the tracer's estimate and returns the whole estimate so far (new images, freed
 * with lucent_trace_result_free). Progress goes to lucent_progress. */
lucent_status lucent_tracer_render(lucent_tracer *tracer, const lucent_trace_desc *desc, lucent_trace_result *dest);

/* Frees the images of a result (and zeroes it). */
void lucent_trace_result_free(lucent_trace_result *result);

/* What the camera sees through each pixel's centre (the GL renderer's sample), for measuring an image
 * by region (lucent compare). Arrays are width x height, top row first. */
typedef struct lucent_trace_probe {
    int width, height;
    int light_count;           /* the scene's lights */
    int *object;               /* per pixel: the scene object seen (objects[i]), -1 none */
    int *triangle;             /* its triangle in the object's mesh, -1 none */
    float *bary;               /* 2 per pixel: (u, v), the point is (1 - u - v) v0 + u v1 + v v2 */
    float *position;           /* 3 per pixel: the point seen, world mm */
    float *normal;             /* 3 per pixel: the triangle's outward unit normal */
    unsigned char *unoccluded; /* light_count per pixel: 1 when no surface lies between the point and the
                                  light (directional: along its direction; point and sphere: up to the
                                  centre; environment: always 1), 0 else or where no object is seen */
} lucent_trace_probe;

/* Casts one ray through each pixel's centre and one shadow ray per light from what it meets. Free
 * with lucent_trace_probe_free. */
lucent_status lucent_tracer_probe(const lucent_tracer *tracer, lucent_trace_probe *dest);

/* Frees the arrays of a probe (and zeroes it). */
void lucent_trace_probe_free(lucent_trace_probe *probe);

/* The version of the Embree library linked, e.g. "3.13.5" (asked of a new Embree device: RTC_DEVICE_PROPERTY_VERSION);
 * "unknown" when no device can be made. */
const char *lucent_trace_embree_version(void);

/* What a trace's JSON sidecar records (docs/trace.md); a zero field means the default. */
typedef struct lucent_trace_sidecar_desc {
    const lucent_scene *scene;         /* required: its JSON after overrides is recorded */
    const char *scene_file;            /* as given (NULL: scene->path) */
    const lucent_tracer_desc *tracer;  /* the tracer's options (NULL: the defaults) */
    const lucent_trace_result *result; /* required */
    int threads;                       /* the threads that rendered */
} lucent_trace_sidecar_desc;

/* Writes the sidecar to path (atomically): renderer and version, scene file, size, samples, seed,
 * time and rate, threads, the tracer's options, the relative standard error over the object, the
 * paths truncated, escaped or dropped, and the scene after overrides. */
lucent_status lucent_trace_write_sidecar(const char *path, const lucent_trace_sidecar_desc *desc);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_TRACE_H */
