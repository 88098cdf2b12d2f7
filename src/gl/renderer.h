/* The renderer core: a scene on a GL context, made of parts each owned by one file (targets.c,
 * shadows.c, bounce.c, meshes.c, tables.c, programs.c, blur.c) and drawn by one method of methods/ per frame.
 * Only the core (renderer.c, frame.c, output.c) and the method files see every part.
 * Internal to src/gl. */
#ifndef LUCENT_SRC_GL_RENDERER_H
#define LUCENT_SRC_GL_RENDERER_H

#include <stdint.h>

#include "gl/bounce.h"
#include "gl/core/gpu.h"
#include "gl/meshes.h"
#include "gl/programs.h"
#include "gl/shadows.h"
#include "gl/tables.h"
#include "gl/targets.h"
#include "lucent/render.h"

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

struct lucent_renderer {
    lucent_gl_context *ctx;
    const lucent_scene *scene;
    lucent_renderer_desc desc;
    lucent_cache *cache; /* NULL without desc.cache_dir */
    gl_targets targets;
    gl_shadows shadows;
    gl_bounce bounce; /* light between surfaces (render.bounce) */
    gl_meshes meshes;
    gl_tables tables;
    gl_programs programs;
    gl_timer timer;
    GLuint frame_ubo, empty_vao, dummy_tex, compose_program, present_program;
    bool aov;                         /* tests: the scene pass's auxiliary outputs */
    void *state[LUCENT_METHOD_COUNT]; /* each method's own, created by its first frame */
    lucent_render_settings last;      /* the settings of the last frame */
    bool have_frame;
    lucent_frame_times last_times;
    double jitter[2]; /* the camera's offset in pixels, within [-1/2, 1/2) (render.samples) */
};

/* The bake desc of the renderer for settings s and parts `what` (lucent/bake.h). */
lucent_bake_desc gl_renderer_bake_desc(const lucent_renderer *r, const lucent_render_settings *s, unsigned what);

/* The albedo object i is shaded with: the scene's colour when it gives one, else the hemispherical
 * albedo of a half-space of its material behind the path tracer's boundary at the object's
 * roughness (the boundary bake, made by every frame: the diffuse light the reference reflects under
 * uniform light; docs/render.md, "One boundary"); an albedo map is applied in the shader. */
void gl_renderer_object_albedo(const lucent_renderer *r, int object, double dest[3]);

/* The camera's view-projection for the targets' size, offset by r->jitter pixels (every pass that
 * projects the scene: the frame block, points). */
void gl_renderer_view_proj(const lucent_renderer *r, double dest[16]);

/* Draws every visible object's triangles with the bound program (shadow casters, scene passes). */
void gl_renderer_draw_objects(const lucent_renderer *r);

/* ---- output.c ---- */

/* Reads the final target back, sample k of n of the pixel (render.samples): rgb / n added to the image,
 * alpha (coverage) / n to the mask, which the last sample makes 1 where at least half the samples were
 * covered (k 0 creates both). */
lucent_status gl_renderer_read_back(lucent_renderer *r, lucent_render_result *res, int k, int n);

/* ---- frame.c ---- */

/* Runs one frame of method s->view.method (prepare, then its passes between timestamps). */
lucent_status gl_frame(lucent_renderer *r, const lucent_render_settings *s, lucent_frame_times *times);

/* ---- tests: auxiliary outputs (normal + curvature, position + object, light 0 terms) ---- */
void gl_renderer_set_aov(lucent_renderer *r, bool on);
lucent_status gl_renderer_read_aov(lucent_renderer *r, int which, lucent_image **dest);

#endif
