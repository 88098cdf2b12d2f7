/* Shared by the files of src/eval: paths, folders, events, and the few functions that read
 * individual render settings (compare_settings.c). */
#ifndef LUCENT_SRC_EVAL_INTERNAL_H
#define LUCENT_SRC_EVAL_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "lucent/eval.h"

enum { EVAL_PATH_SIZE = 1200, EVAL_NAME_SIZE = 64, EVAL_SETTINGS_SIZE = 256 };

/* snprintf into a path buffer; a path that does not fit is an error, not a truncated file name. */
lucent_status eval_path_printf(char *dest, size_t size, const char *fmt, ...) LUCENT_PRINTF(3, 4);

/* mkdir -p. */
lucent_status eval_make_dirs(const char *path);

/* mkdir of one folder (its parent must exist); an existing folder is fine. */
lucent_status eval_make_dir(const char *dir);

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

/* What distinguishes a method's run, for the tables: "svd rank 3, 11 taps, ...". */
void eval_method_describe(const lucent_render_settings *settings, char *dest, size_t size);

/* The tonemapping the settings ask for PNG output. */
lucent_tonemap_desc eval_tonemap(const lucent_render_settings *settings);

/* "render.width=W" and "render.height=H" overrides that scale a scene's size by scale. */
void eval_scale_overrides(const lucent_scene *scene, double scale, char width[48], char height[48]);

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
