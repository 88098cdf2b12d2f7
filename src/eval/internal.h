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

#endif
