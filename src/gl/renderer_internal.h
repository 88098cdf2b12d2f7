/* The renderer's insides: per-object GPU meshes, per-material kernels and tables, render targets,
 * shadow maps, programs. Internal to src/gl. */
#ifndef LUCENT_SRC_GL_RENDERER_INTERNAL_H
#define LUCENT_SRC_GL_RENDERER_INTERNAL_H

#include <stdint.h>

#include "gl/gpu.h"
#include "lucent/cdrf.h"
#include "lucent/profile.h"
#include "lucent/scene.h"

enum {
    GLR_MAX_LIGHTS = 8,      /* lights other than environment lights (common.glsl MAX_LIGHTS) */
    GLR_MAX_MATERIALS = 8,   /* distinct materials in one scene (kernel rows, transmittance rows) */
    GLR_TRANSMIT_SIZE = 256, /* samples of T(s) per material */
    GLR_MAX_PROGRAMS = 24
};

/* The per-frame uniform block, laid out as std140 (common.glsl, binding 0). */
typedef struct gl_frame_block {
    float view_proj[16];
    float eye[4];
    float forward[4];
    float ambient[4];
    int32_t counts[4];
    float light_vec[GLR_MAX_LIGHTS][4];
    float light_rgb[GLR_MAX_LIGHTS][4];
    float light_shadow[GLR_MAX_LIGHTS][4];
    float light_texel[GLR_MAX_LIGHTS][4];
    float light_matrix[GLR_MAX_LIGHTS][16];
} gl_frame_block;

/* One scene object on the GPU. */
typedef struct gl_mesh {
    GLuint vao, vertices, indices, curvature, uvs, albedo_map;
    GLsizei index_count;
    int material;                /* index into the renderer's materials */
    int curvature_smooth;        /* the rings the uploaded curvature was smoothed over; -1: none */
    double curvature_range[2];   /* 5th and 95th percentiles of the mean curvature, mm^-1 */
    double sigma0[3];            /* in use for the cdrf methods */
    const char *sigma0_from;     /* "scene", "fit", "fit (cache)", "diffuse", "" */
} gl_mesh;

/* One distinct material and what the settings derive from it. */
typedef struct gl_material {
    lucent_material m;
    char profile_source[32];     /* render.profile the profile was built from ("": none yet) */
    lucent_profile *profile;
    char taps_key[96];           /* profile/model/rank/taps of `taps` */
    lucent_taps *taps;
    float transmit[GLR_TRANSMIT_SIZE * 3]; /* T(s) per channel at s = range j / (size - 1): the slab
                                              transmittance, or the profile's T(s) / T(0) */
    double transmit_range;       /* mm; 0: not built */
    int transmit_model;          /* lucent_transmittance_model of the table */
    int fit_variant;             /* variant of the sigma0 fit; -1: none */
    double fit_sigma0[3];
    bool fit_cached;
} gl_material;

/* A shadow-casting light's projection. */
typedef struct gl_light {
    int scene_index;
    int layer;                   /* shadow layer, -1: none */
    double matrix[16];           /* world -> light clip space, column-major */
    double near_plane, far_plane, texel;
    bool ortho;
} gl_light;

typedef struct gl_scene_uniforms {
    GLint albedo, sigma0, use_map, sigma0_from_map, roughness, f0, strength, material, object, translucency,
        transmit_range, transmit_v, transmit_albedo, curvature_gain, cdrf_reach, shadow_offset, lut_sigma_max;
} gl_scene_uniforms;

typedef struct gl_program_entry {
    char key[64];
    GLuint program;
    gl_scene_uniforms u;
} gl_program_entry;

struct lucent_renderer {
    lucent_gl_context *ctx;
    const lucent_scene *scene;
    lucent_renderer_desc desc;
    gl_mesh *meshes;
    gl_material materials[GLR_MAX_MATERIALS];
    int material_count;
    gl_light lights[GLR_MAX_LIGHTS];
    int light_count;
    double ambient[3];           /* environment lights' radiance, summed */
    double bound_centre[3], bound_radius;
    /* render targets */
    int width, height;
    bool aov;                    /* tests: extra targets with normal, position, light-0 terms */
    GLuint tex_diffuse, tex_specular, tex_depth, tex_zbuffer, tex_final, tex_aov[3];
    GLuint fbo_scene, fbo_final;
    /* shadows */
    int shadow_size, shadow_layers;
    GLuint shadow_tex, shadow_fbo, sampler_compare, sampler_raw;
    /* tables */
    GLuint lut_tex, transmit_tex, dummy_tex;
    int lut_variant;             /* -1: none */
    double lut_sigma_max;
    char transmit_key[48];
    /* programs and passes */
    gl_program_entry programs[GLR_MAX_PROGRAMS];
    int program_count;
    GLuint compose_program, present_program, shadow_program, empty_vao, frame_ubo;
    gl_blur blur;
    char blur_key[160];
    gl_timer timer;
    lucent_render_settings last;  /* the settings of the last frame */
    bool have_frame;
    lucent_frame_times last_times;
};

/* ---- scene_gpu.c: meshes, curvature, albedo maps ---- */
lucent_status gl_meshes_upload(lucent_renderer *r);
lucent_status gl_meshes_curvature(lucent_renderer *r, int smooth_rings);
void gl_meshes_free(lucent_renderer *r);

/* ---- materials.c: profiles, taps, transmittance; sigma0 ---- */
lucent_status gl_materials_collect(lucent_renderer *r);
lucent_status gl_materials_prepare(lucent_renderer *r, const lucent_render_settings *s, bool taps, bool transmit);
lucent_status gl_objects_sigma0(lucent_renderer *r, const lucent_render_settings *s);
void gl_materials_free(lucent_renderer *r);

/* ---- sigma0.c: the Monte Carlo fit of sigma0 and its cache ---- */
lucent_status gl_sigma0_fit(const lucent_material *m, lucent_cdrf_variant variant, const lucent_renderer_desc *desc,
                            double dest[3], bool *cached);

/* ---- cache.c: the disk cache of Monte Carlo results ---- */
struct cJSON;
/* The cache file of key: DIR/PREFIX-<FNV-1a of key>.json (the key is stored inside and compared). */
void gl_cache_path(const char *dir, const char *prefix, const char *key, char *dest, size_t size);
/* Reads count numbers of field from path if it holds key; false (a miss) otherwise. */
bool gl_cache_read(const char *path, const char *key, const char *field, int count, double *dest);
/* Adds key to json, writes it to path atomically (creating dir), frees json; warns on failure. */
void gl_cache_write(const char *dir, const char *path, const char *key, struct cJSON *json);

/* ---- transmit.c: the Monte Carlo slab transmittance for translucency ---- */
/* Fills table[size * 3] with T(s) per channel at s = *range j / (size - 1), the last entry 0. */
lucent_status gl_transmit_slab(const lucent_material *m, const lucent_renderer_desc *desc, int size, float *table,
                               double *range);

/* ---- shadow.c: light projections and the shadow pass ---- */
lucent_status gl_lights_setup(lucent_renderer *r);
lucent_status gl_shadows_resize(lucent_renderer *r, int size);
void gl_shadows_draw(lucent_renderer *r);
void gl_shadows_free(lucent_renderer *r);

/* ---- frame.c: targets, programs, the passes of one frame ---- */
lucent_status gl_targets_resize(lucent_renderer *r, int width, int height);
lucent_status gl_frame_draw(lucent_renderer *r, const lucent_render_settings *s, lucent_frame_times *times);
void gl_frame_free(lucent_renderer *r);

/* ---- prepare.c: everything a frame needs, rebuilt only when its settings changed ---- */
lucent_status gl_prepare(lucent_renderer *r, const lucent_render_settings *s);
lucent_status gl_settings_check(const lucent_render_settings *s);

/* ---- tests: auxiliary outputs (normal + curvature, position + object, light 0 terms) ---- */
void gl_renderer_set_aov(lucent_renderer *r, bool on);
lucent_status gl_renderer_read_aov(lucent_renderer *r, int which, lucent_image **dest);

#endif
