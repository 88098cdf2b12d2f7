/* Shared by the files of src/eval: paths, folders, events, and the few functions that read
 * individual render settings (compare_settings.c). */
#ifndef LUCENT_SRC_EVAL_INTERNAL_H
#define LUCENT_SRC_EVAL_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "lucent/eval.h"
#include "lucent/scene.h"

enum { EVAL_PATH_SIZE = 1200, EVAL_NAME_SIZE = 64, EVAL_SETTINGS_SIZE = 256 };

/* snprintf into a path buffer; a path that does not fit is an error, not a truncated file name. */
lucent_status eval_path_printf(char *dest, size_t size, const char *fmt, ...) LUCENT_PRINTF(3, 4);

/* mkdir -p. */
lucent_status eval_make_dirs(const char *path);

/* "ssss:svd3" -> "ssss-svd3", "cdrf+translucency" -> "cdrf-translucency": a file stem. */
void eval_file_stem(const char *name, char *dest, size_t size);

/* Tells on_event that path was written when s is LUCENT_OK; returns s. */
lucent_status eval_wrote(lucent_eval_event_fn on_event, void *user, lucent_status s, const char *path);

/* ---- compare_settings.c: every use of an individual render setting in src/eval ---- */

/* Applies method (a name lucent_render_method_parse reads) to settings. */
lucent_status eval_method_settings(const char *method, lucent_render_settings *settings);

/* True when the method of settings cannot render scene's materials (the manual kernel has Table A.1
 * parameters for five materials only), with why in reason; a compare run skips it there. */
bool eval_method_unavailable(const lucent_render_settings *settings, const lucent_scene *scene, char *reason,
                             size_t size);

/* The pixel samples of a method's image: `samples` (a compare run's; 0: the settings' own where above 1,
 * else LUCENT_COMPARE_DEFAULT_SAMPLES). */
void eval_image_samples(int samples, lucent_render_settings *settings);

/* What distinguishes a method's run, for the tables: "svd rank 3, 11 taps, ...". */
void eval_method_describe(const lucent_render_settings *settings, char *dest, size_t size);

/* The tonemapping the settings ask for PNG output. */
lucent_tonemap_desc eval_tonemap(const lucent_render_settings *settings);

/* "render.width=W" and "render.height=H" overrides that scale a scene's size by scale. */
void eval_scale_overrides(const lucent_scene *scene, double scale, char width[48], char height[48]);

/* ---- compare_reference.c: the reference, traced or reused ---- */

typedef struct eval_reference_desc {
    int spp;           /* 0: the scene's */
    double time_limit; /* 0: the scene's */
    int runs;          /* 0: two runs where light paths are used, else one; 1; 2 */
    lucent_pool *pool;
    const char *label; /* progress */
} eval_reference_desc;

typedef struct eval_reference {
    lucent_trace_result result; /* the reference: one run, or the two combined */
    lucent_trace_result run[2]; /* the two independent runs (runs == 2) */
    int runs;
} eval_reference;

/* Traces the reference of scene as d says (two runs share the budget, half each). */
lucent_status eval_reference_trace(const lucent_scene *scene, const eval_reference_desc *d, eval_reference *dest);

/* The estimate of two independent runs: their passes' mean (weighted by spp) and its variance. */
lucent_status eval_reference_combine(const lucent_trace_result *a, const lucent_trace_result *b,
                                     lucent_trace_result *dest);

void eval_reference_free(eval_reference *r);

/* What a reference depends on: the scene after overrides without its name, description and render
 * settings, plus the render settings the tracer reads (size, background, the trace group but its
 * budget and seed). */
struct cJSON;
lucent_status eval_reference_identity(const lucent_scene *scene, struct cJSON **dest);

/* Writes dir/reference-variance.exr, -coverage.exr, the runs' images and reference.json (what made
 * it); reference.exr is the reference's image, written with its PNG. */
lucent_status eval_reference_write(const char *dir, const lucent_scene *scene, const eval_reference *ref,
                                   lucent_eval_event_fn on_event, void *user);

/* Reads the numbers of a reference.json's text (file names it in errors) into dest (no images), after
 * checking that it was made of the same scene and settings (else an error naming the file and the
 * first field that differs). */
lucent_status eval_reference_parse(const char *text, const char *file, const lucent_scene *scene, eval_reference *dest);

/* Reads what eval_reference_write wrote into dir, after checking that it was made of the same scene
 * and settings (else an error naming reference.json and the first field that differs). */
lucent_status eval_reference_read(const char *dir, const lucent_scene *scene, eval_reference *dest);

/* ---- compare_provenance.c ---- */

/* "Linux 6.1.0 x86_64, <the processor's model name>" and the online processors. */
void eval_machine(char *dest, size_t size, int *cores);

/* The current time as ISO 8601 UTC. */
void eval_date(char *dest, size_t size);

/* ---- compare_peers.c: a real engine (Blender) rendering the scene with the fitted parameters ---- */

typedef struct eval_peer_desc {
    const char *spec;          /* "blender-cycles", "blender-cycles-burley", "blender-eevee", ":hand" after one */
    const lucent_scene *scene; /* loaded, meshes in world mm */
    int spp;                   /* samples per pixel (0: 64) */
    uint64_t seed;
    const char *blender;   /* the program (NULL: $LUCENT_BLENDER, else blender on PATH) */
    const char *cache_dir; /* the disk cache of the fits' truths (NULL: none) */
    lucent_pool *pool;     /* NULL: serial (Blender then runs 1 thread) */
} eval_peer_desc;

typedef struct eval_peer_result {
    lucent_image *image; /* RGB, the scene's size, linear */
    char settings[EVAL_SETTINGS_SIZE];
    double seconds; /* Blender's wall time */
} eval_peer_result;

/* Whether spec names a peer (an error naming the known ones otherwise). */
lucent_status eval_peer_check(const char *spec);

/* Fits each material, writes the scene for Blender, runs it, reads its image. Blender missing: a clear
 * LUCENT_ERR_UNSUPPORTED saying how to get it. */
lucent_status eval_peer_render(const eval_peer_desc *desc, eval_peer_result *dest);

#endif
