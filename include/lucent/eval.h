/* Lucent eval: measuring the approximations against their references, and writing what was
 * measured. Four evaluations, each with its file writers:
 *   - compare: every real-time method of a scene against the path-traced reference (relative RMS
 *     error over the object's pixels, net of the reference's own noise, GPU frame times), as
 *     images, error maps, charts, report.html/.md/.csv and results.json (docs/compare.md);
 *   - kernel-eval: every separable kernel model against the ground-truth 2-D kernel, in kernel
 *     space and in image space on a test signal (Freude 2014, Tables 6.3-6.5; docs/kernel-eval.md);
 *   - the outputs of a diffuse reflectance profile (JSON, CSV, SVG);
 *   - the outputs of a CDRF fit to simulated spheres (JSON, CSV, SVG).
 * The library never prints: what an evaluation does as it goes (a file written, a model skipped, a
 * scene done) reaches the application through an optional event callback; long work draws through
 * the progress API (lucent_progress_set_output). Every file is written atomically.
 *
 * Usage:
 *   lucent_compare_result r;
 *   const char *scenes[] = {"data/scenes/spheres-skin.json"};
 *   lucent_compare_run(&(lucent_compare_desc){.scenes = scenes, .scene_count = 1, .spp = 256,
 *                                             .out = "out/spheres"}, &r);
 *   ... r.scenes[0].report.methods[i].rel_rms ...
 *   lucent_compare_result_free(&r); */
#ifndef LUCENT_EVAL_H
#define LUCENT_EVAL_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/cdrf.h"
#include "lucent/convolve.h"
#include "lucent/image.h"
#include "lucent/kernel.h"
#include "lucent/material.h"
#include "lucent/profile.h"
#include "lucent/render.h"
#include "lucent/report.h"
#include "lucent/scene.h"
#include "lucent/trace.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Events ------------------------------------------------------------------------------------ */

typedef enum lucent_eval_event_kind {
    LUCENT_EVAL_WROTE = 1,  /* path: a file was written (complete, renamed into place) */
    LUCENT_EVAL_SKIPPED,    /* name: a kernel model (kernel-eval) or a method (compare) was left out;
                              reason: why (compare: it names the scene) */
    LUCENT_EVAL_SCENE_DONE, /* index: compare's scene index is measured and its files written */
    LUCENT_EVAL_SLOW        /* name: a method asked for that is slow on this GL renderer; reason: an estimate
                               of its time (told before any work, so the user can stop the run) */
} lucent_eval_event_kind;

typedef struct lucent_eval_event {
    lucent_eval_event_kind kind;
    const char *path;   /* LUCENT_EVAL_WROTE */
    const char *name;   /* LUCENT_EVAL_SKIPPED: the model or method; LUCENT_EVAL_SCENE_DONE: the scene */
    const char *reason; /* LUCENT_EVAL_SKIPPED */
    int index;          /* LUCENT_EVAL_SKIPPED: the model's (compare: the scene's); LUCENT_EVAL_SCENE_DONE:
                           the scene's */
} lucent_eval_event;

/* Called on the thread that runs the evaluation; the strings live until it returns. */
typedef void (*lucent_eval_event_fn)(const lucent_eval_event *event, void *user);

/* ---- compare: real-time methods against the path-traced reference ------------------------------
 * Per scene: loads it (with the overrides), path-traces the reference, renders every method with
 * the GL renderer, measures each against the reference over the object mask, and times it. */

enum { LUCENT_COMPARE_MAX_SCENES = 16, LUCENT_COMPARE_MAX_METHODS = 32, LUCENT_COMPARE_MAX_FRAMES = 64 };

/* The methods compared when a desc names none: those that render in interactive time on a software GL
 * renderer (llvmpipe); tsd and points take tens of seconds a frame there and run only when asked for
 * (LUCENT_EVAL_SLOW tells their estimate first). */
#define LUCENT_COMPARE_DEFAULT_METHODS                                                                                 \
    "lambert,cdrf,cdrf+translucency,ssss:preint,ssss:svd1,ssss:svd3,ssss:guided,ssss:manual,ssss:jimenez,burley"
/* The report's title when a desc gives none. */
#define LUCENT_COMPARE_DEFAULT_TITLE "Lucent: real-time subsurface scattering against a path-traced reference"
/* The relative error drawn in full colour in the error maps (50%). */
#define LUCENT_COMPARE_ERROR_MAP_SCALE 0.5f

/* Pixel samples of the methods' images in a compare run (lucent_compare_desc.samples). */
enum { LUCENT_COMPARE_DEFAULT_SAMPLES = 16 };

/* A compare run; a zero field means the default. */
typedef struct lucent_compare_desc {
    const char *const *scenes; /* scene files (1..LUCENT_COMPARE_MAX_SCENES, required) */
    int scene_count;
    const char *const *methods; /* method names as lucent_render_method_parse reads them
                                          (0 of them: LUCENT_COMPARE_DEFAULT_METHODS) */
    int method_count;
    const char *const *overrides; /* "key=value" for every scene (lucent_scene_load_desc) */
    int override_count;
    int spp;                       /* reference samples per pixel (0: the scene's render.spp) */
    double time_limit;             /* at most this many seconds per reference (0: the scene's
                                          render.time_limit, where 0 means none) */
    int frames;                    /* GL frames timed per method, the median kept (0: 5; more
                                          than LUCENT_COMPARE_MAX_FRAMES count as that many) */
    int samples;                   /* each method's image is the mean of this many frames jittered over the
                                      pixel (render.samples), as the reference averages each pixel's area
                                      (0: the scene's render.samples where above 1, else
                                      LUCENT_COMPARE_DEFAULT_SAMPLES); the timed frames are single */
    double scale;                  /* multiply every scene's width and height (0: keep them) */
    const char *out;               /* folder for every file (made if absent; NULL: no files, and
                                          the renderer's default cache) */
    const char *title;             /* the report's title (NULL: LUCENT_COMPARE_DEFAULT_TITLE) */
    lucent_gl_context *gl;         /* NULL: a headless context made for the run */
    lucent_pool *pool;             /* NULL: serial */
    lucent_eval_event_fn on_event; /* NULL: none */
    void *user;                    /* passed to on_event */
    int reference_runs;            /* independent runs (seeds) of the reference, sharing its budget: 0: two
                                      where light paths make one photon land in many pixels (the paired
                                      test's standard error is calibrated on them), else one; 1 or 2 */
    const char *reference;         /* NULL: trace the references; else a folder an earlier run wrote
                                      (out), whose SCENE/reference.json and EXRs are reused: its scene and
                                      settings must match, else LUCENT_ERR_INVALID_ARGUMENT naming the field */
    bool per_light;                /* also each light alone, reference and methods (a reference per light) */
    const char *revision;          /* provenance: the program's git revision (NULL: "unknown") */
    const char *command;           /* provenance: the command line (NULL: none recorded) */
    /* Real engines rendering each scene beside the methods, with the parameters `lucent fit` gives each
     * material (lucent/engine.h): "blender-cycles" (Cycles' Random Walk), "blender-cycles-burley",
     * "blender-eevee", each optionally ":hand" (the hand mapping instead of the fit). Blender 3.4 headless
     * (docs/engines.md); missing, the run fails saying so. Counted with the methods in
     * LUCENT_COMPARE_MAX_METHODS. */
    const char *const *peers;
    int peer_count;
    int peer_spp;        /* the peers' samples per pixel (0: 64) */
    uint64_t peer_seed;  /* the peers' seed (0: 1) */
    const char *blender; /* the program (NULL: $LUCENT_BLENDER, else blender on PATH) */
} lucent_compare_desc;

/* Returns what a zero lucent_compare_desc stands for (no scenes; the default methods are left to
 * method_count 0). */
lucent_compare_desc lucent_compare_defaults(void);

/* One scene's measures. Strings and arrays live in the result until lucent_compare_result_free. */
typedef struct lucent_compare_scene_result {
    lucent_compare_scene report;          /* what the report writers read: names, image paths relative
                                             to out, errors, times, the scene's JSON */
    const lucent_trace_result *reference; /* the reference: image, variance, coverage */
    const float *mask;                    /* width x height: 1 where the errors count, else 0 */
    uint64_t object_pixels;               /* pixels in the mask */
    const lucent_frame_times *times;      /* per method: the passes of the median frame */
} lucent_compare_scene_result;

typedef struct lucent_compare_store lucent_compare_store;

typedef struct lucent_compare_result {
    int scene_count; /* scenes complete */
    lucent_compare_scene_result *scenes;
    lucent_compare_store *store; /* what the pointers above point into */
} lucent_compare_result;

/* Runs the comparison; with desc->out, writes per scene SCENE/reference.png|.exr,
 * SCENE/METHOD.png|.exr, SCENE/METHOD-error.png and SCENE/errors.svg as it goes, and at the end
 * the reports of lucent_compare_write_reports. Errors name the scene and the method. On failure
 * *dest holds nothing to free. */
lucent_status lucent_compare_run(const lucent_compare_desc *desc, lucent_compare_result *dest);

/* Frees what a result holds and zeroes it (a zero result is fine). */
void lucent_compare_result_free(lucent_compare_result *result);

/* ---- compare's paired test ------------------------------------------------------------------------
 * Every method is measured against the same reference r = truth + noise n, so the difference of two
 * methods' squared errors d = (sum (a - r)^2 - sum (b - r)^2) / sum r^2 = e_a^2 - e_b^2 has the true
 * difference as its mean and -2 sum (a - b) n / sum r^2 as its noise: the noise enters once, linearly,
 * and far less than in either error alone. */

/* The block side (pixels) over which lucent_compare_noise_inflation sums. */
enum { LUCENT_COMPARE_INFLATION_BLOCK = 32 };

typedef struct lucent_compare_pair {
    double d;  /* e_a^2 - e_b^2 */
    double se; /* its standard error: 2 sqrt(inflation sum (a - b)^2 var) / sum r^2 */
    double z;  /* d / se (0 when both are 0; +-inf for a difference without noise) */
} lucent_compare_pair;

/* The paired test of images a and b against reference (variance: of its mean, per pixel and channel)
 * over R, G, B and the mask (NULL: every pixel); inflation (values below 1 count as 1) multiplies the
 * variance, which per-pixel variances understate where one path lands in many pixels. */
lucent_status lucent_compare_paired(const lucent_image *a, const lucent_image *b, const lucent_image *reference,
                                    const lucent_image *variance, const float *mask, double inflation,
                                    lucent_compare_pair *dest);

/* Whether the test separates the two (|z| >= LUCENT_COMPARE_Z). */
bool lucent_compare_separated(const lucent_compare_pair *pair);

/* How much per-pixel variances understate the variance of the paired test's sums, from two
 * independent runs r1, r2 (variances v1, v2) of the same reference, whose difference is pure noise:
 * over blocks of block x block pixels (0: LUCENT_COMPARE_INFLATION_BLOCK) and the weights w = a - b of
 * every pair of the count images, sum_blocks (sum w (r1 - r2))^2 / sum w^2 (v1 + v2) (1 when the
 * denominator is 0). Blocks must be wider than the pixels one path reaches; the value is an
 * estimate (about 2 / (blocks on the object) relative variance). */
lucent_status lucent_compare_noise_inflation(const lucent_image *const *images, int count, const lucent_image *r1,
                                             const lucent_image *v1, const lucent_image *r2, const lucent_image *v2,
                                             const float *mask, int block, double *dest);

/* The pixels the errors count: those fully covered in the reference (coverage >= 0.999) whose 8
 * neighbours are too (silhouette pixels mix object and background differently in the two
 * renderers). Fills dest (width x height floats, 1 or 0) and returns how many are 1. */
uint64_t lucent_compare_object_mask(const lucent_image *coverage, float *dest);

/* The reference's own relative standard error over the mask: sqrt(sum variance / sum mean^2) over
 * the masked pixels (mask NULL: all) and R, G, B (0 when the sum of squares is 0): the RMS distance from the truth
 * that the reference alone adds to every method's error (see lucent_compare_net_error). */
double lucent_compare_reference_noise(const lucent_image *mean, const lucent_image *variance, const float *mask);

/* The colour of a signed relative error e in the error maps: black at 0, growing linearly to full
 * at |e| = scale (and full beyond): blue (too dark, e < 0) or orange (too bright, e > 0), linear RGB. */
void lucent_compare_error_colour(double e, double scale, float rgb[3]);

/* The error map of a method: per pixel the signed relative error (image - reference) / (reference +
 * 0.01), averaged over R, G, B, zero outside the mask (NULL: everywhere counted), in the colours of
 * lucent_compare_error_colour with scale LUCENT_COMPARE_ERROR_MAP_SCALE. Free *dest with
 * lucent_image_destroy. */
lucent_status lucent_compare_error_map(const lucent_image *image, const lucent_image *reference, const float *mask,
                                       lucent_image **dest);

/* The maps' colour bar: 256 x 14 pixels, -scale at the left to +scale at the right. */
lucent_status lucent_compare_error_scale_image(lucent_image **dest);

/* The size x size square (clamped to the image) where the squared error sum over R, G, B, inside the
 * mask (NULL: everywhere), is largest: its top-left pixel in *x, *y (the first such, in row order). */
lucent_status lucent_compare_worst_region(const lucent_image *image, const lucent_image *reference, const float *mask,
                                          int size, int *x, int *y);

/* How concentrated a method's error is: the share of its squared error (summed over R, G, B, inside
 * the mask, NULL: everywhere) that the worst `fraction` of those pixels hold (at least one pixel): the
 * fraction itself where the error is spread evenly, near 1 where a few pixels hold it all (a bright
 * rim, a seam), 0 where the images agree. The error without those pixels is rel_rms sqrt(1 - share). */
#define LUCENT_COMPARE_WORST_FRACTION 0.01
lucent_status lucent_compare_concentration(const lucent_image *image, const lucent_image *reference, const float *mask,
                                           double fraction, double *share);

/* Writes DIR/STEM.exr (linear) and DIR/STEM.png (tonemapped by tonemap; NULL: the defaults). */
lucent_status lucent_compare_write_image(const char *dir, const char *stem, const lucent_image *image,
                                         const lucent_tonemap_desc *tonemap);

/* Writes results.json: per scene its size, reference (spp, seconds, noise), object pixels, GL
 * device and scene JSON, and per method the errors (rel_rms, rel_rms_net, rel_rms_rgb), frame and
 * setup times, settings and per-pass GPU times. */
lucent_status lucent_compare_write_results_json(const char *path, const lucent_compare_result *result);

/* Writes DIR/report.html (titled title; NULL: LUCENT_COMPARE_DEFAULT_TITLE), report.md, report.csv
 * and results.json, telling each file to on_event (may be NULL). */
lucent_status lucent_compare_write_reports(const char *dir, const char *title, const lucent_compare_result *result,
                                           lucent_eval_event_fn on_event, void *user);

/* ---- compare's regions ---------------------------------------------------------------------------
 * Each object pixel classed by the surface seen through its centre (lucent_tracer_probe): by the
 * lights (lit: some light within 75 degrees of the normal and unoccluded; else terminator: some light
 * 75 to 105 degrees from it; else cast shadow: some light within 75 degrees but occluded; else
 * attached shadow: every light beyond 105 degrees; environment lights do not count), by the view
 * (grazing: the normal beyond 75 degrees from the camera), by the mesh's mean curvature (convex:
 * radius LUCENT_COMPARE_CONVEX_RADIUS_MM or less) and by the outline (silhouette band: within 3
 * pixels of a pixel the object covers less than half). The last three overlap the first four. */

enum {
    LUCENT_COMPARE_REGION_LIT = 0,
    LUCENT_COMPARE_REGION_TERMINATOR,
    LUCENT_COMPARE_REGION_ATTACHED_SHADOW,
    LUCENT_COMPARE_REGION_CAST_SHADOW,
    LUCENT_COMPARE_REGION_GRAZING,
    LUCENT_COMPARE_REGION_CONVEX,
    LUCENT_COMPARE_REGION_SILHOUETTE,
    LUCENT_COMPARE_REGION_COUNT
};

/* Curvature radius (mm) up to which a surface counts as convex. */
#define LUCENT_COMPARE_CONVEX_RADIUS_MM 20.0

/* "lit", "terminator", "attached shadow", "cast shadow", "grazing view", "convex", "silhouette band"
 * (NULL out of range). */
const char *lucent_compare_region_name(int region);

/* Per pixel (width x height of the probe) a bit per region (bit k: region k), 0 outside the mask
 * (NULL: every pixel) and where no object is seen; lights_on (NULL: all) picks the scene's lights
 * that count; coverage: the reference's. */
lucent_status lucent_compare_regions(const lucent_scene *scene, const lucent_trace_probe *probe,
                                     const lucent_image *coverage, const float *mask, const bool *lights_on,
                                     lucent_pool *pool, uint8_t *dest);

/* One image's measures over one region (NaN where the region is empty or the reference dark). */
typedef struct lucent_compare_region_values {
    uint64_t pixels;        /* masked pixels in the region */
    double rel_rms;         /* sqrt(sum (m - r)^2 / sum r^2) over the region, R, G and B */
    double ratio;           /* sum m / sum r */
    double error_share;     /* the region's sum (m - r)^2 over the mask's */
    double energy;          /* the region's sum r^2 over the mask's */
    double reference_noise; /* sqrt(sum var / sum r^2) over the region (NaN without variance) */
} lucent_compare_region_values;

lucent_status lucent_compare_region_measure(const uint8_t *bits, int region, const float *mask,
                                            const lucent_image *reference, const lucent_image *variance,
                                            const lucent_image *image, lucent_compare_region_values *dest);

/* ---- kernel-eval: separable kernel models against the ground truth ------------------------------
 * Builds the ground-truth 2-D kernel of a material's profile and each model of it, then compares
 * them in kernel space (RMS over the grid, Freude Table 6.3) and in image space: the signal
 * convolved exactly with the ground truth (2-D FFT) against each model's separable rank-N
 * convolution and its taps (Tables 6.4-6.5). Kernels in mm become pixel kernels by exact area
 * resampling. */

enum { LUCENT_KERNEL_EVAL_MAX_MODELS = 40, LUCENT_KERNEL_EVAL_TABLE65 = 6, LUCENT_KERNEL_EVAL_NAME_SIZE = 32 };

/* The models evaluated when a desc names none. */
#define LUCENT_KERNEL_EVAL_DEFAULT_MODELS "svd,svd-norm,preint,guided,manual,sog,jimenez"

/* A kernel-eval run; a zero field means the default. */
typedef struct lucent_kernel_eval_desc {
    const lucent_material *material; /* required */
    const char *const *models;       /* names of lucent_kernel_eval_model_parse (0 of them:
                                          LUCENT_KERNEL_EVAL_DEFAULT_MODELS) */
    int model_count;
    bool table65;                       /* also SVD rank N against N Gaussians, N = 1..6 (Freude
                                          Table 6.5; always for Skin1) */
    lucent_profile_source_desc profile; /* the profile (zero: the dipole; pool NULL: desc's pool) */
    const char *signal;                 /* "edge" (NULL), "shapes", or a PNG/EXR/PFM file */
    int size;                           /* edge and shapes: side in pixels (0: LUCENT_SIGNAL_DEFAULT_SIZE) */
    double mm_per_pixel;                /* the signal's scale (0: LUCENT_SIGNAL_MM_PER_PIXEL) */
    int taps;                           /* taps per pass, odd, 3..255 (0: 17) */
    bool no_taps;                       /* no tap convolutions */
    double heat_scale;                  /* the error drawn white in the heat maps (0: 0.1) */
    const char *out;                    /* folder for the files (made if absent; its parent must exist;
                                          NULL: no files) */
    lucent_pool *pool;                  /* NULL: serial */
    lucent_eval_event_fn on_event;      /* NULL: none */
    void *user;
} lucent_kernel_eval_desc;

/* Returns the defaults a zero lucent_kernel_eval_desc stands for (no material). */
lucent_kernel_eval_desc lucent_kernel_eval_defaults(void);

/* Reads a model name: svd (rank 1), svd-norm (normalised, Freude (5.12)), preint, guided (k = 1),
 * manual, sog (1 Gaussian), jimenez, svd-rN or sog-rN (N = 1..16). LUCENT_ERR_INVALID_ARGUMENT
 * naming the model and the known ones otherwise. */
lucent_status lucent_kernel_eval_model_parse(const char *name, lucent_kernel_desc *dest);

typedef struct lucent_kernel_eval_model {
    char name[LUCENT_KERNEL_EVAL_NAME_SIZE]; /* as asked: "svd-norm", "sog-r3" */
    lucent_kernel_desc desc;
    bool plotted;                       /* asked for (in the slices, images and tables), not only Table 6.5 */
    lucent_kernel *kernel;              /* NULL when skipped */
    char skipped[200];                  /* why it was left out ("" when built): manual without a preset */
    double kernel_rms[3];               /* lucent_kernel_rms against the ground truth */
    lucent_image_error_stats separable; /* the rank-N convolution against the exact one */
    lucent_image_error_stats taps;      /* the taps' convolution (when have_taps) */
    bool have_taps;
} lucent_kernel_eval_model;

typedef struct lucent_kernel_eval_result {
    lucent_material material;
    char profile[32]; /* the profile's source name */
    char signal[512]; /* the signal's name */
    int signal_width, signal_height;
    double mm_per_pixel;
    int kernel_pixels; /* side of the pixel kernel, 2 h + 1 */
    int taps;          /* taps per pass (0: none) */
    lucent_kernel2d *ground_truth;
    lucent_kernel_eval_model *models;
    int model_count;
    int table65[LUCENT_KERNEL_EVAL_TABLE65][2]; /* indices into models: svd-rN, sog-rN */
    int table65_count;
} lucent_kernel_eval_result;

/* Runs the evaluation. With desc->out, writes into it signal.png, exact.png/.exr, per asked model
 * MODEL.png/.exr, MODEL-diff.png (and -taps), then kernel-axis.svg, kernel-diagonal.svg, tables.md
 * and results.json. A manual model without a Table A.1 preset is skipped (told as
 * LUCENT_EVAL_SKIPPED), not an error. On failure *dest holds nothing to free. */
lucent_status lucent_kernel_eval_run(const lucent_kernel_eval_desc *desc, lucent_kernel_eval_result *dest);

/* Frees what a result holds and zeroes it (a zero result is fine). */
void lucent_kernel_eval_result_free(lucent_kernel_eval_result *result);

/* The slices y = 0 (diagonal false) or x = y of the ground truth and the asked models, one panel
 * per channel (Freude Figure 6.2), as SVG. */
lucent_status lucent_kernel_eval_write_slices(const char *path, const lucent_kernel_eval_result *result, bool diagonal);

/* The tables (Freude 6.3, 6.4 and, when computed, 6.5) as Markdown. */
lucent_status lucent_kernel_eval_write_tables(const char *path, const lucent_kernel_eval_result *result);

/* Every measure as JSON. */
lucent_status lucent_kernel_eval_write_json(const char *path, const lucent_kernel_eval_result *result);

/* ---- The outputs of a profile (lucent profile) -------------------------------------------------- */

/* What a profile's JSON records beside the profile. */
typedef struct lucent_profile_report {
    const lucent_material *material;
    const lucent_profile *profile;
    uint64_t photons, seed;     /* recorded when the profile's model is "mc" */
    const lucent_sog *sog;      /* a sum-of-Gaussians fit to record (NULL: none) */
    const lucent_layer *layers; /* the layered slab the profile is of, top first, recorded as "layers"
                                   (each material and thickness_mm; NULL: none) */
    int layer_count;
} lucent_profile_report;

/* The profile as JSON: model, material, units, grid, totals, radii, values and errors per channel. */
lucent_status lucent_profile_write_json(const char *path, const lucent_profile_report *report);

/* The profile as CSV: r_mm,R,R_se,G,G_se,B,B_se under a comment line naming material and model. */
lucent_status lucent_profile_write_csv(const char *path, const lucent_material *material,
                                       const lucent_profile *profile);

/* One profile as SVG: RGB curves, linear near zero and logarithmic over the range, with the
 * sum-of-Gaussians fit dashed when sog is not NULL. */
lucent_status lucent_profile_write_svg(const char *path, const lucent_material *material, const lucent_profile *profile,
                                       const lucent_sog *sog);

/* Several models of one material as SVG: one logarithmic panel per channel, a curve per model (at
 * most 8). */
lucent_status lucent_profile_write_compare_svg(const char *path, const lucent_material *material,
                                               const lucent_profile *const *profiles, int count);

/* ---- The outputs of a CDRF fit (lucent cdrf-fit) ------------------------------------------------- */

/* A fit with the simulations it was fitted to. */
typedef struct lucent_cdrf_fit_report {
    const lucent_material *material;
    const lucent_cdrf_sphere_result *spheres;
    int sphere_count;
    const lucent_cdrf_fit *fit;
    uint64_t seed;    /* the simulations' seed */
    double cone;      /* the camera's acceptance half-angle, radians */
    double roughness; /* the boundary's GGX alpha */
} lucent_cdrf_fit_report;

/* The fit and every sphere's data (radiance and standard errors per bin and channel) as JSON. */
lucent_status lucent_cdrf_fit_write_json(const char *path, const lucent_cdrf_fit_report *report);

/* One row per sphere and bin: radius_mm,theta_deg, then per channel the radiance, its standard
 * error and the fitted k_d f(theta; sigma0 / r). */
lucent_status lucent_cdrf_fit_write_csv(const char *path, const lucent_cdrf_fit_report *report);

/* The data and the fitted curves, one panel per channel, as SVG. */
lucent_status lucent_cdrf_fit_write_svg(const char *path, const lucent_cdrf_fit_report *report);

/* ---- The chart of engine fits (lucent fit; lucent/engine.h) ------------------------------------ */

typedef struct lucent_engine_report lucent_engine_report;

/* r R(r) of the truth and of each engine's fit and hand mapping (dashed), one panel per channel up to
 * r99, as SVG. */
lucent_status lucent_engine_report_write_svg(const char *path, const lucent_engine_report *report);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_EVAL_H */
