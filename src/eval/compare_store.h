/* What lucent_compare_run keeps per run and per scene, shared by compare.c and compare_scenes.c. */
#ifndef LUCENT_SRC_EVAL_COMPARE_STORE_H
#define LUCENT_SRC_EVAL_COMPARE_STORE_H

#include "eval/internal.h"

/* The lights that get a table of their own (each light alone). */
enum { EVAL_MAX_LIGHTS = 8 };

typedef struct method_store {
    char name[EVAL_NAME_SIZE], image[EVAL_PATH_SIZE], error_image[EVAL_PATH_SIZE], settings[EVAL_SETTINGS_SIZE];
    char crop_image[EVAL_PATH_SIZE];
} method_store;

/* One table of regions: per region and method the values, and the report's view of them. */
typedef struct region_table {
    double rel_rms[LUCENT_COMPARE_REGION_COUNT][LUCENT_COMPARE_MAX_METHODS];
    double ratio[LUCENT_COMPARE_REGION_COUNT][LUCENT_COMPARE_MAX_METHODS];
    double share[LUCENT_COMPARE_REGION_COUNT][LUCENT_COMPARE_MAX_METHODS];
    lucent_compare_region regions[LUCENT_COMPARE_REGION_COUNT];
} region_table;

typedef struct scene_store {
    lucent_scene *scene;
    char stem[EVAL_NAME_SIZE]; /* the scene's folder under out */
    char dir[EVAL_PATH_SIZE];  /* out/stem ("" without out) */
    char reference[EVAL_PATH_SIZE], chart[EVAL_PATH_SIZE], device[300], reference_from[EVAL_PATH_SIZE];
    eval_reference ref;
    float *mask; /* object pixels counted in the errors */
    uint64_t mask_pixels;
    int method_count;
    int renderer_count; /* methods[0 .. renderer_count) are the renderer's; the peers (real engines) follow */
    method_store methods[LUCENT_COMPARE_MAX_METHODS];
    lucent_compare_method rows[LUCENT_COMPARE_MAX_METHODS]; /* the report's view of methods[] */
    lucent_frame_times times[LUCENT_COMPARE_MAX_METHODS];
    lucent_image *images[LUCENT_COMPARE_MAX_METHODS]; /* each method's image until the scene is measured */
    double pair_se[LUCENT_COMPARE_MAX_METHODS * LUCENT_COMPARE_MAX_METHODS];
    double inflation;
    int skipped_count;
    char skipped_name[LUCENT_COMPARE_MAX_METHODS][EVAL_NAME_SIZE], skipped_why[LUCENT_COMPARE_MAX_METHODS][512];
    lucent_compare_skipped skipped[LUCENT_COMPARE_MAX_METHODS]; /* the report's view of the two above */
    lucent_trace_probe probe;                                   /* what each pixel sees (regions) */
    uint8_t *region_bits;
    region_table region; /* the scene's regions */
    lucent_compare_region *regions;
    int region_count;
    int light_count; /* lights measured alone */
    char light_name[EVAL_MAX_LIGHTS][48];
    double light_rms[EVAL_MAX_LIGHTS][LUCENT_COMPARE_MAX_METHODS],
        light_ratio[EVAL_MAX_LIGHTS][LUCENT_COMPARE_MAX_METHODS];
    region_table light_region[EVAL_MAX_LIGHTS];
    lucent_compare_light lights[EVAL_MAX_LIGHTS];
} scene_store;

/* The desc with its defaults resolved, and what the run records. */
typedef struct run {
    lucent_compare_desc d;
    char method_text[1024]; /* the default list, split in place */
    const char *methods[LUCENT_COMPARE_MAX_METHODS];
    lucent_gl_context *gl;
    int scene_index; /* the scene being measured */
    char device[300], machine[400], date[40];
    lucent_compare_provenance provenance;
} run;

struct lucent_compare_store {
    scene_store *scenes;
    int count; /* scenes begun (each to be freed) */
    run *run;  /* the run's desc and provenance, which the results point into */
};

/* Writes DIR/STEM.exr and .png (tonemapped as rs says) of the scene's folder, telling each file. */
lucent_status eval_write_image(const run *r, const scene_store *ss, const char *stem, const lucent_image *img,
                               const lucent_render_settings *rs);

/* Loads a scene with the run's overrides, then extra ones, and for a scale two more that resize it
 * (read from a first, mesh-less load), so that the scene's JSON records the size the images have. */
lucent_status eval_load_scene(const run *r, const char *path, const char *const *extra, int extra_count,
                              lucent_scene **dest);

/* compare_scenes.c: the regions of the scene's pixels and every method's error in them. */
lucent_status eval_scene_regions(const run *r, scene_store *ss);

/* compare_scenes.c: each light alone, reference and methods (desc.per_light). */
lucent_status eval_scene_lights(const run *r, const char *cache_dir, scene_store *ss);

/* compare_scenes.c: tells (LUCENT_EVAL_SLOW) of each method asked for that is slow on the run's GL
 * renderer, with an estimate, before any work. */
void eval_warn_slow(const run *r);

#endif
